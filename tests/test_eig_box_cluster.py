"""Eigenfrequency roots over boxes at small Omega2 (issue 37: the general paving left the roots not enclosed
at Omega2 < 0.1): omega_3, omega_4 go like the zeros' midpoint -+ sqrt(Omega2 / C) and omega_1 like
Omega2 / (a b), so the family Newton test fails; the sign-change test with the quartic affine in (a, eps,
Omega2) and F = Omega2 monotone encloses them. Every certified ball is sampled in mpmath."""
import random
import sys
from fractions import Fraction as Fr
from pathlib import Path

import mpmath
import pytest
import sympy
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.eigenfrequencies import boxes as B

sys.path.insert(0, str(Path(__file__).parent))
from test_eig_box_forms import _model, _mp_roots  # noqa: E402

A, BB = Fr("15.08"), Fr("6.154")
DE, DW = Fr(1999, 1000 * 256), Fr(9999, 1000 * 256)       # the general paving's finest boxes


def _gbox(e0, W0, de=DE, dW=DW):
    return Box((("a", A, A), ("b", BB, BB), ("eps", e0, e0 + de), ("Omega2", W0, W0 + dW)))


def test_quartic_is_affine_in_a_eps_omega2():
    """The corners of (a, eps, Omega2) bound the quartic at fixed omega and b (AFFINE_IN)."""
    a, b, e, W, x = sympy.symbols("a b e W x")
    l = -x
    p1 = (l * (b - 1) + b) * (l ** 2 * (a - b) * (b - 1) + l * (e * (a - 1) + b * (a - b)) + e * a)
    p2 = (l * (b - 1) + 1) * (l ** 2 * (a - b) * (b - 1) + l * (e * (a - 1) + a - b) + e)
    Q = sympy.expand(l * p1 + W * p2)
    for v in (a, e, W):
        assert sympy.degree(Q, v) == 1
    assert set(B.AFFINE_IN) == {"a", "eps", "Omega2"}


@pytest.mark.parametrize("e0,W0", [(Fr(1, 1000) + 40 * DE, Fr(1, 1000)), (Fr(1, 1000), Fr(1, 1000) + DW)])
def test_small_omega2_roots_enclosed_and_sampled(e0, W0):
    box = _gbox(e0, W0)
    with working_precision(128):
        roots, _ = B.box_roots(_model(box), box, nus=False)
    assert roots.omegas is not None and all(w > 0 for w in roots.omegas)
    rnd = random.Random(7)
    pts = [{"a": A, "b": BB, "eps": e0 + DE * Fr(i, 1), "Omega2": W0 + DW * Fr(j, 1)} for i in (0, 1) for j in (0, 1)]
    pts += [{"a": A, "b": BB, "eps": e0 + DE * Fr(rnd.randint(0, 1000), 1000),
             "Omega2": W0 + DW * Fr(rnd.randint(0, 1000), 1000)} for _ in range(12)]
    for P in pts:
        mp = _mp_roots(P)
        for w, r in zip(roots.omegas, mp):
            lo, hi = float(w.lower()), float(w.upper())
            assert lo <= float(r) <= hi, (P, lo, float(r), hi)


def test_sign_change_refuses_a_hull_that_misses_a_root():
    """A proposal hull shifted off the roots fails the end-sign test (None, never a wrong ball)."""
    box = _gbox(Fr("0.5"), Fr(1, 1000))
    m = _model(box)
    with working_precision(128):
        p = B._balls(m, box)
        fams = [B._quartic_family(c)[0] for c in B._affine_corners(m, box)]
        props = B._proposals(m, box, B.characteristic_quartic)
        assert B._sign_change_roots(fams, B._quartic_family(p)[1], props, ratio=B._quartic_ratio(p)) is not None
        shifted = [[r * arb(Fr(11, 10).numerator) / 10 for r in rs] for rs in props]
        assert B._sign_change_roots(fams, B._quartic_family(p)[1], shifted, ratio=B._quartic_ratio(p)) is None


def test_ratio_encloses_F_numerator():
    """_quartic_ratio's N contains g'h - gh' at sampled points of the eps interval (exact rationals)."""
    box = _gbox(Fr("0.3"), Fr(1, 1000))
    m = _model(box)
    a, b, e, x = sympy.symbols("a b e x")
    l = -x
    p1 = (l * (b - 1) + b) * (l ** 2 * (a - b) * (b - 1) + l * (e * (a - 1) + b * (a - b)) + e * a)
    h = (l * (b - 1) + 1) * (l ** 2 * (a - b) * (b - 1) + l * (e * (a - 1) + a - b) + e)
    g = x * p1
    N = sympy.diff(g, x) * h - g * sympy.diff(h, x)
    with working_precision(128):
        ratio = B._quartic_ratio(B._balls(m, box))
        for xv in (Fr("1.2"), Fr("1.31"), Fr("0.002")):
            hb, nb = ratio(arb(xv.numerator) / xv.denominator)
            for ev in (Fr("0.3"), Fr("0.3") + DE / 3, Fr("0.3") + DE):
                sub = {a: sympy.Rational(A), b: sympy.Rational(BB), e: sympy.Rational(ev), x: sympy.Rational(xv)}
                nv, hv = sympy.Rational(N.subs(sub)), sympy.Rational(h.subs(sub))
                assert float(nb.lower()) <= float(nv) <= float(nb.upper())


def _setup(e0=Fr("0.5"), W0=Fr(1, 1000)):
    box = _gbox(e0, W0)
    m = _model(box)
    p = B._balls(m, box)
    fams = [B._quartic_family(c)[0] for c in B._affine_corners(m, box)]
    return p, fams, B._proposals(m, box, B.characteristic_quartic)


def test_sign_change_refuses_a_hull_beside_the_roots():
    """Root 1's proposals moved above its true range (still monotone there): both ends have one sign, None."""
    with working_precision(128):
        p, fams, props = _setup()
        moved = [[r[0] + arb("0.001")] + list(r[1:]) for r in props]
        assert B._sign_change_roots(fams, B._quartic_family(p)[1], moved, ratio=B._quartic_ratio(p)) is None


def test_sign_change_refuses_the_midpoint_alone():
    """Proposals from the midpoint only: a hull far narrower than the roots' range; the corners disagree in
    sign at its ends, so no ball (an uncertain sign never counts)."""
    with working_precision(128):
        p, fams, props = _setup()
        mid_only = [props[-1]]
        assert B._sign_change_roots(fams, B._quartic_family(p)[1], mid_only, ratio=B._quartic_ratio(p)) is None


def test_sign_change_needs_every_corner():
    """Proposals from one corner and the midpoint: a hull that misses the other corners' roots; the sign test
    at every corner refuses it (a test at one corner would accept it)."""
    with working_precision(128):
        p, fams, props = _setup()
        part = [props[0], props[-1]]
        assert B._sign_change_roots(fams, B._quartic_family(p)[1], part, ratio=B._quartic_ratio(p)) is None


def test_one_sign_only_when_certain_everywhere():
    assert B._one_sign([arb(1), arb(2)]) == 1 and B._one_sign([arb(-1), arb(-2)]) == -1
    assert B._one_sign([arb(1), arb(0, 1)]) == 0 and B._one_sign([arb(-1), arb(0, 1)]) == 0
    assert B._one_sign([arb(1), arb(-1)]) == 0


def test_taylor_at_contains_the_polynomial_on_the_ball():
    """_taylor_at(poly, x) contains poly(t) at sampled exact points t of x (mpmath at 40 digits)."""
    from flint import arb_poly
    poly = arb_poly([arb(3), arb(-7), arb(2), arb(5), arb(-1)])
    x = arb("1.2", "0.3")
    with working_precision(128):
        enc = B._taylor_at(poly, x)
    mpmath.mp.dps = 40
    for i in range(21):
        t = mpmath.mpf("0.9") + mpmath.mpf("0.6") * i / 20
        v = 3 - 7 * t + 2 * t ** 2 + 5 * t ** 3 - t ** 4
        assert mpmath.mpf(enc.lower().str(40, radius=False)) <= v <= mpmath.mpf(enc.upper().str(40, radius=False))
