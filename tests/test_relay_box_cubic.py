"""The nutation cubic's roots over a wide parameter box by parametric Newton around a linear predictor
(core/implicit_roots.polynomial_root_over_box, kinds/periodic_orbit/parametric.py): every certified root ball
holds the mpmath roots of sampled members; a wrong start or a box too wide is undecided, never a false ball."""
from __future__ import annotations

from fractions import Fraction

import pytest
from flint import acb, arb, fmpq

from rigor_gyro.core.balls import ball, interval, working_precision
from rigor_gyro.core.implicit_roots import polynomial_root_over_box
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, nutation_cubic
from rigor_gyro.kinds.periodic_orbit.parametric import RelayJets, _root_over_box, parameter_jets
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")


def _q(x: Fraction) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _setup(spec: dict[str, Fraction]):
    """(params, centre jets, box coefficient jets, centre coefficients, deviations, guesses, exact ends)."""
    m = validate(load_scene("roitenberg1947"))
    P = m.params
    names = list(spec)
    cv = {k: ball(getattr(P, k)) for k in PARAMETER_NAMES}
    bv = dict(cv)
    ends = {}
    for k, rel in spec.items():
        v = Fraction(int(getattr(P, k).p), int(getattr(P, k).q))
        ends[k] = (v * (1 - rel), v * (1 + rel))
        bv[k] = interval(ball(_q(ends[k][0])), ball(_q(ends[k][1])))
    iso = isolate_polynomial(nutation_cubic(P))
    guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
    cen = RelayJets(parameter_jets(cv, names, 1), len(names) + 1, guesses)
    bj = parameter_jets(bv, names, 1)
    A, B, H, tau, n = (bj[k] for k in ("A", "B", "H", "tau", "n"))
    q2 = H * H / (A * B)
    c = [q2 / tau, q2 + n / (tau * A), 1 / tau, q2 * 0 + 1]
    devs = [bv[k] - cv[k] for k in names] + [arb(0)]
    return P, cen, c, devs, guesses, ends


def _mp_roots(P, **kw):
    v = {k: mp.mpf(int(getattr(P, k).p)) / int(getattr(P, k).q) for k in ("A", "B", "H", "tau", "n")}
    v.update({k: mp.mpf(x.numerator) / x.denominator for k, x in kw.items()})
    q2 = v["H"] ** 2 / (v["A"] * v["B"])
    return mp.polyroots([1, 1 / v["tau"], q2 + v["n"] / (v["tau"] * v["A"]), q2 / v["tau"]], maxsteps=200, extraprec=60)


def _inside(z: acb, r) -> bool:
    return z.real.contains(arb(mp.nstr(mp.re(r), 25))) and z.imag.contains(arb(mp.nstr(mp.im(r), 25)))


@pytest.mark.parametrize("spec", [{"tau": Fraction(1, 10)}, {"tau": Fraction(1, 20), "n": Fraction(1, 10)}])
def test_root_over_box_holds_mpmath_roots(spec):
    with mp.workdps(30), working_precision(128):
        P, cen, c, devs, guesses, ends = _setup(spec)
        for k, g in enumerate(guesses):
            real = g.imag.is_zero()
            z = _root_over_box(c, cen.coeffs, cen.lams[k], devs, real)
            assert z is not None, (spec, g)
            if real:
                assert z.imag.is_zero()
            for i in range(5):
                pt = {name: lo + (hi - lo) * Fraction(i, 4) for name, (lo, hi) in ends.items()}
                roots = _mp_roots(P, **pt)
                near = min(roots, key=lambda r: abs(r - complex(float(g.real.mid()), float(g.imag.mid()))))
                assert _inside(acb(z), near), (spec, pt, z, near)
                # exactly one of the member's roots in a real root's ball (its other roots are far off)
                if real:
                    assert sum(_inside(acb(z), r) for r in roots) == 1


def test_root_over_box_as_written_needs_the_scaling_over_tau_ten_percent():
    # the cubic as written does not verify the stiff real root over tau +-10 %: the scaled variable does
    with working_precision(128):
        _, cen, c, devs, guesses, _ = _setup({"tau": Fraction(1, 10)})
        assert polynomial_root_over_box(c, cen.coeffs, cen.lams[0], devs, True) is None
        assert _root_over_box(c, cen.coeffs, cen.lams[0], devs, True) is not None


def test_root_over_box_wrong_start_is_undecided_or_holds_a_root():
    # a start far from any root of the centre (not a root enclosure) must not produce a ball without a root
    with mp.workdps(30), working_precision(128):
        P, cen, c, devs, _, ends = _setup({"tau": Fraction(1, 20)})
        for start in (acb(-50), acb(-99), acb(0, 20)):
            z = polynomial_root_over_box(c, cen.coeffs, start, devs, start.imag.is_zero())
            for i in range(5):
                pt = {name: lo + (hi - lo) * Fraction(i, 4) for name, (lo, hi) in ends.items()}
                assert z is None or any(_inside(acb(z), r) for r in _mp_roots(P, **pt)), (start, z)


def test_relay_jets_roots_over_tau_eight_percent():
    # RelayJets over tau +-8 % (the one-step family Newton fails there): the eigenvalue balls hold mpmath's roots
    from rigor_gyro.kinds.periodic_orbit.parametric import parameter_jets as pj
    with mp.workdps(30), working_precision(128):
        P, cen, c, devs, guesses, ends = _setup({"tau": Fraction(2, 25)})
        bv = {k: ball(getattr(P, k)) for k in PARAMETER_NAMES}
        lo, hi = ends["tau"]
        bv["tau"] = interval(ball(_q(lo)), ball(_q(hi)))
        box = RelayJets(pj(bv, ["tau"], 1), 2, guesses, centre=cen.lams, devs=devs, centre_coeffs=cen.coeffs)
        for i in range(5):
            x = lo + (hi - lo) * Fraction(i, 4)
            roots = _mp_roots(P, tau=x)
            for lam in box.lams:
                assert any(_inside(lam, r) for r in roots), (x, lam)


def test_orbit_continued_over_tau_five_percent_holds_samples():
    # one box of tau +-5 % (the cubic's roots by the predictor): theta*(P) and the largest modulus hold samples
    from rigor_gyro.kinds.periodic_orbit.continuation import continue_orbit
    approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
    m = validate(load_scene("roitenberg1947"))
    P = m.params
    v = Fraction(int(P.tau.p), int(P.tau.q))
    lo, hi = v * Fraction(19, 20), v * Fraction(21, 20)
    with working_precision(128):
        iso = isolate_polynomial(nutation_cubic(P))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        o = continue_orbit(P, {"tau": interval(ball(_q(lo)), ball(_q(hi)))}, ["tau"], guesses,
                           arb("0.138133574136"))
    assert o.genuine and o.stable is True, o.problem
    base = {k: Fraction(int(getattr(P, k).p), int(getattr(P, k).q)) for k in PARAMETER_NAMES}
    for i in range(3):
        pt = dict(base, tau=lo + (hi - lo) * Fraction(i, 2))
        th = _theta_mp(pt, float(o.theta.lower()) - 1e-6, float(o.theta.upper()) + 1e-6)
        assert o.theta.contains(arb(mp.nstr(th, 25))), (pt["tau"], th, o.theta)
        mods = [abs(z) for z in approx.approx_multipliers(pt, float(th))]
        assert o.max_modulus.lower() < max(mods) < o.max_modulus.upper() < 1


def _theta_mp(params: dict, lo: float, hi: float):
    """theta* by mpmath (expm of the augmented matrix, 20 digits), bisected on a sign change of g in [lo, hi]."""
    with mp.workdps(20):
        v = {k: mp.mpf(x.numerator) / x.denominator for k, x in params.items()}
        aug = mp.zeros(6, 6)
        rows = [[0, 1, 0, 0, 0], [0, 0, -v["H"] / v["B"], 0, 0], [0, v["H"] / v["A"], 0, v["K"] / v["A"], 0],
                [0, 0, -v["n"] / (v["K"] * v["tau"]), -1 / v["tau"], v["p"] / v["tau"]], [0, 0, 0, 0, -1 / v["sigma"]]]
        for i in range(5):
            for j in range(5):
                aug[i, j] = rows[i][j]
        aug[4, 5] = v["S"] / v["sigma"]

        def g(t):
            E = mp.expm(aug * t)
            Phi = mp.matrix([[E[i, j] for j in range(5)] for i in range(5)])
            return mp.lu_solve(mp.eye(5) + Phi, -mp.matrix([E[i, 5] for i in range(5)]))[0]
        a, b = mp.mpf(lo), mp.mpf(hi)
        ga = g(a)
        assert ga * g(b) < 0, "no sign change of g across the certified ball"
        for _ in range(30):
            c = (a + b) / 2
            if g(c) * ga > 0:
                a = c
            else:
                b = c
        return (a + b) / 2


def test_extend_covers_only_certified_pieces():
    # continuation._extend: the stretch returned is covered by contiguous pieces on which the test held
    from rigor_gyro.kinds.periodic_orbit.continuation import _extend
    for direction, start, limit in ((+1, arb("0.01"), arb(1)), (-1, arb("0.9"), arb(0))):
        calls = []

        def holds(a, b):
            ok = bool(b < arb("0.3")) if direction > 0 else bool(a > arb("0.6"))
            calls.append((a, b, ok))
            return ok
        x = _extend(holds, arb(start.mid()), limit, direction)
        good = [(a, b) for a, b, ok in calls if ok]
        if direction > 0:
            assert arb("0.15") < x <= arb("0.3")
            ends = [arb(start.mid())] + [b for _, b in good]
            assert all(good[i][0] == ends[i] for i in range(len(good))), "pieces not contiguous"
        else:
            assert arb("0.6") <= x < arb("0.75")
            ends = [arb(start.mid())] + [a for a, _ in good]
            assert all(good[i][1] == ends[i] for i in range(len(good))), "pieces not contiguous"
        assert ends[-1] == x


@pytest.mark.slow
def test_h_box_genuine_by_extended_monotone_stretches_holds_samples():
    # H +-2.75 % in one box: orbit_genuine and stable proved (the monotone stretches of beta extended piece by
    # piece); beta > 0 on (0, theta*) and the largest modulus < 1 at sampled members (floats)
    import numpy as np
    from rigor_gyro.core.boxes import Box
    from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box
    approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
    m = validate(load_scene("roitenberg1947"))
    box = Box.of({"H": (Fraction(100) * Fraction(3890, 4000), Fraction(100) * Fraction(4110, 4000))})
    with working_precision(128):
        out = evaluate_box(m, box, ["orbit_genuine", "stable"])
    assert out["orbit_genuine"][0] == "proved" and out["stable"][0] == "proved", out
    base = {k: Fraction(int(getattr(m.params, k).p), int(getattr(m.params, k).q)) for k in PARAMETER_NAMES}
    for i in range(3):
        pt = dict(base, H=box.interval("H")[0] + (box.interval("H")[1] - box.interval("H")[0]) * Fraction(i, 2))
        th = approx.approx_roots_expm_brentq(pt, 0.2, grid=400)
        th = min(th, key=lambda t: abs(t - 0.138))
        from scipy.linalg import expm
        _, _, _, aug = approx.matrices(pt)
        x0 = approx.approx_x0(pt, th)
        beta = [(expm(aug * t)[:5, :5] @ x0 + expm(aug * t)[:5, 5])[0] for t in np.linspace(0, th, 60)[1:-1]]
        assert min(beta) > 0, min(beta)
        assert max(abs(z) for z in approx.approx_multipliers(pt, th)) < 1
