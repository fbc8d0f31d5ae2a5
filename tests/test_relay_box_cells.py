"""Relay boxes of +-1 % in one parameter (issue 37 part 1): theta*(P) by the band Newton step with sub-box
unions (kinds/periodic_orbit/subbox_union.py), the sign condition and multipliers cell by cell (cellwise.py).
Every certified range holds mpmath samples of the box."""
from __future__ import annotations

from fractions import Fraction

import pytest
from flint import acb, arb

from rigor_gyro.core.balls import ball, working_precision
from rigor_gyro.core.jets import Jet
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.periodic_orbit.continuation import _Models
from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, nutation_cubic
from rigor_gyro.kinds.periodic_orbit.subbox_union import cells, gradient_union, split_counts
from tests.test_relay_box_continuation import _continued, _model, _params, _q, _theta_mp

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")


def test_cells_cover_the_ball_with_exact_ends():
    X = arb(1, 0.25)
    for n in (1, 2, 3, 8):
        cs = cells(X, n)
        assert len(cs) == n
        assert cs[0][0].lower() <= X.lower() and cs[-1][0].upper() >= X.upper()
        for (a, ma), (b, mb) in zip(cs, cs[1:]):
            assert a.upper() >= b.lower()             # consecutive cells touch
        for c, mid in cs:
            assert mid.rad() == 0 and c.contains(mid)


def test_split_counts_halves_the_heaviest_direction():
    assert split_counts([1.0, 0.0], 8) == [8, 1]
    assert split_counts([1.0, 1.0], 16) == [4, 4]
    assert split_counts([0.0], 8) == [1]


def test_gradient_union_holds_point_gradients():
    """The union of G's gradient over Theta x (B +-1 %) contains the gradient at sampled points, each
    evaluated as a point jet (its own ball, independent of the cells)."""
    m = _model()
    P = m.params
    B = Fraction(int(P.B.p), int(P.B.q))
    with working_precision(128):
        iso = isolate_polynomial(nutation_cubic(P))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        cvals = {k: ball(getattr(P, k)) for k in PARAMETER_NAMES}
        box = dict(cvals, B=ball(_q(B * Fraction(99, 100))).union(ball(_q(B * Fraction(101, 100)))))
        Theta = arb("0.1383", "0.0015")
        u = gradient_union(lambda c, b: _Models(c, b, ["B"], guesses), cvals, box, ["B"], Theta, [4, 2])
        assert u is not None and not u[1].contains(0)
        for i in range(5):
            for j in range(3):
                Bx = B * (Fraction(99, 100) + Fraction(2, 100) * Fraction(i, 4))
                th = Theta.lower() + (Theta.upper() - Theta.lower()) * j / 2
                pv = dict(cvals, B=ball(_q(Bx)))
                from types import SimpleNamespace
                mod = _Models(SimpleNamespace(**pv), {"B": pv["B"]}, ["B"], guesses)
                g = mod.centre.G(Jet.variable(acb(th), 1, 2))
                assert u[0].overlaps(g.d[0].real) and u[1].overlaps(g.d[1].real)
                assert u[0].contains(arb(g.d[0].real.mid())) and u[1].contains(arb(g.d[1].real.mid()))


@pytest.mark.parametrize("name", ["B", pytest.param("H", marks=pytest.mark.slow), pytest.param("A", marks=pytest.mark.slow)])
def test_one_percent_box_genuine_and_stable_holds_mpmath_samples(name):
    m, o, lo, hi = _continued(name, Fraction(1, 100))
    assert o.genuine and o.stable is True, o.problem
    assert o.max_modulus.upper() < 1
    # the max modulus ranges over the whole box like the largest modulus does (every cell's, not one's)
    assert o.max_modulus.lower() <= o.moduli[0].lower() + 1e-9 and o.max_modulus.upper() >= o.moduli[0].upper() - 1e-9
    for k in range(9):
        x = lo + (hi - lo) * Fraction(k, 8)
        th = _theta_mp(_params(m, **{name: x}), float(o.theta.lower()) - 1e-6, float(o.theta.upper()) + 1e-6)
        assert o.theta.contains(arb(mp.nstr(th, 30))), (x, th, o.theta)
        mods = sorted((abs(z) for z in approx.approx_multipliers(_params(m, **{name: x}), float(th))), reverse=True)
        assert o.max_modulus.lower() < mods[0] < o.max_modulus.upper(), (x, mods[0], o.max_modulus)
        for ball_, v in zip(o.moduli, mods):
            assert ball_.lower() - 1e-12 < v < ball_.upper() + 1e-12


def _b_box(rel=Fraction(1, 100)):
    m = _model()
    P = m.params
    B = Fraction(int(P.B.p), int(P.B.q))
    iso = isolate_polynomial(nutation_cubic(P))
    guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
    cvals = {k: ball(getattr(P, k)) for k in PARAMETER_NAMES}
    box = dict(cvals, B=ball(_q(B * (1 - rel))).union(ball(_q(B * (1 + rel)))))
    return m, B, guesses, cvals, box


def test_band_residual_holds_point_residuals():
    """band_root's F0 contains F(0, P) = G(tc + slope (P - c), P) at sampled P (point evaluations), and its
    image, when inside the band, holds the offset of theta*(P) from the tangent (mpmath theta*)."""
    from types import SimpleNamespace
    from rigor_gyro.kinds.periodic_orbit.subbox_union import band_root
    m, B, guesses, cvals, box = _b_box()
    with working_precision(128):
        from rigor_gyro.kinds.periodic_orbit.continuation import _centre_root
        models = _Models(m.params, {"B": box["B"]}, ["B"], guesses)
        tc = arb(_centre_root(models, arb("0.138133574136")).mid())
        Gc = models.centre.G(Jet.variable(acb(tc), 1, 2))
        slope = [arb((-(Gc.d[0].real) / Gc.d[1].real).mid())]        # the centre's tangent
        res = band_root(lambda c, b: _Models(c, b, ["B"], guesses), cvals, box, ["B"], tc, slope, arb("1e-4"), [8])
        assert res is not None
        image, F0, gu = res
        assert not gu.contains(0) and arb(-1e-4) < image < arb(1e-4)     # inside the band: theta*(P) is there
        for i in range(9):
            Bx = B * (Fraction(99, 100) + Fraction(2, 100) * Fraction(i, 8))
            pv = dict(cvals, B=ball(_q(Bx)))
            mod = _Models(SimpleNamespace(**pv), {"B": pv["B"]}, ["B"], guesses)
            th = tc + slope[0] * (pv["B"] - cvals["B"])
            val = mod.centre.G(Jet.variable(acb(th), 1, 2)).v.real
            assert F0.contains(arb(val.mid())), (Bx, val, F0)
            t = _theta_mp(_params(m, B=Bx), float(th.mid()) - 2e-3, float(th.mid()) + 2e-3)
            off = arb(mp.nstr(t, 30)) - th
            assert image.contains(arb(off.mid())), (Bx, off, image)


def test_accepted_band_image_lies_inside_its_band(monkeypatch):
    """The band Newton step over B +-1 % is accepted only when its image lies inside the band it assumed."""
    import rigor_gyro.kinds.periodic_orbit.continuation as cont
    calls = []
    real = cont.band_root

    def recording(*a):
        out = real(*a)
        calls.append((a[6], out))
        return out
    monkeypatch.setattr(cont, "band_root", recording)
    _, o, _, _ = _continued("B", Fraction(1, 100))
    assert o.genuine and "offset from the centre's tangent" in o.theta_method
    accepted = [(rho, res) for rho, res in calls if res is not None and -rho < res[0] < rho]
    assert accepted, "no band image inside its band"
    # the run stopped at the first image inside its band: every earlier call's image was outside
    first_inside = next(i for i, (rho, res) in enumerate(calls) if res is not None and -rho < res[0] < rho)
    assert len(calls) == first_inside + 1


def test_claims_over_a_one_percent_box_in_A():
    """evaluate_box decides orbit_genuine and stable over A +-1 % in one box (no paving split)."""
    from rigor_gyro.core.boxes import Box
    from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box
    m = _model()
    A = Fraction(int(m.params.A.p), int(m.params.A.q))
    with working_precision(128):
        out = evaluate_box(m, Box.of({"A": (A * Fraction(99, 100), A * Fraction(101, 100))}), ["orbit_genuine", "stable"])
    assert out["orbit_genuine"][0] == "proved" and out["stable"][0] == "proved", out
    assert "cells" in out["stable"][1]


def test_cells_left_undecided_keep_orbit_genuine_unproved(monkeypatch):
    """Over H +-1 % the whole-box sign condition does not decide; with a budget of 2 cells for a first grid
    of 4, two parts of the box have no cell proved genuine: orbit_genuine must stay unproved."""
    import rigor_gyro.kinds.periodic_orbit.cellwise as cw
    monkeypatch.setattr(cw, "MAX_CELLS", 2)
    _, o, _, _ = _continued("H", Fraction(1, 100))
    assert o.theta is not None and not o.genuine and o.stable is not True
    monkeypatch.setattr(cw, "MAX_CELLS", 64)
    _, o, _, _ = _continued("H", Fraction(1, 100))
    assert o.genuine and o.stable is True
