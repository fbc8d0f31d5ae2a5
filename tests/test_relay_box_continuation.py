"""The relay orbit continued over a parameter box (kinds/periodic_orbit/continuation.py, box_orbit.py) and the
jets behind it (core/jets.py): every certified range holds mpmath / float samples of the box."""
from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest
from flint import acb, arb, fmpq

from rigor_gyro.core.balls import ball, interval, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.jets import Jet, second_order_gradient, second_order_value
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box
from rigor_gyro.kinds.periodic_orbit.continuation import continue_orbit
from rigor_gyro.kinds.periodic_orbit.flow import nutation_cubic
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")

THETA0 = arb("0.138133574136")


def _model():
    return validate(load_scene("roitenberg1947"))


def _q(x: Fraction) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _continued(name: str, rel: Fraction, prec: int = 128):
    m = _model()
    P = m.params
    v = Fraction(int(getattr(P, name).p), int(getattr(P, name).q))
    lo, hi = v * (1 - rel), v * (1 + rel)
    with working_precision(prec):
        box = {name: interval(ball(_q(lo)), ball(_q(hi)))}
        iso = isolate_polynomial(nutation_cubic(P))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        o = continue_orbit(P, box, [name], guesses, THETA0)
    return m, o, lo, hi


def _theta_mp(params, lo: float, hi: float):
    """theta* by mpmath (expm of the augmented matrix, 30 digits) bracketed in [lo, hi] (a sign change of g)."""
    with mp.workdps(20):
        v = {k: mp.mpf(x.numerator) / x.denominator for k, x in params.items()}
        M = mp.matrix([[0, 1, 0, 0, 0], [0, 0, -v["H"] / v["B"], 0, 0], [0, v["H"] / v["A"], 0, v["K"] / v["A"], 0],
                       [0, 0, -v["n"] / (v["K"] * v["tau"]), -1 / v["tau"], v["p"] / v["tau"]],
                       [0, 0, 0, 0, -1 / v["sigma"]]])
        aug = mp.zeros(6, 6)
        for i in range(5):
            for j in range(5):
                aug[i, j] = M[i, j]
        aug[4, 5] = v["S"] / v["sigma"]

        def g(t):
            E = mp.expm(aug * t)
            Phi = mp.matrix([[E[i, j] for j in range(5)] for i in range(5)])
            return mp.lu_solve(mp.eye(5) + Phi, -mp.matrix([E[i, 5] for i in range(5)]))[0]
        a, b = mp.mpf(lo), mp.mpf(hi)
        ga, gb = g(a), g(b)
        assert ga * gb < 0, "no sign change of g across the certified ball (widened by 1e-6)"
        # the bracket shrunk to (hi - lo) / 2^45, as 45 bisections would: Illinois steps (regula falsi, the end
        # kept twice running has its value halved), a bisection whenever a step did not halve the bracket
        width, kept, fa, fb = (b - a) / 2 ** 45, 0, ga, gb
        while b - a > width:
            before = b - a
            c = (a * fb - b * fa) / (fb - fa)
            if not a < c < b:
                c = (a + b) / 2
            gc = g(c)
            if gc * ga > 0:
                a, fa = c, gc
                fb, kept = (fb / 2, kept) if kept > 0 else (fb, 1)
            else:
                b, fb = c, gc
                fa, kept = (fa / 2, kept) if kept < 0 else (fa, -1)
            if b - a > before / 2:
                c = (a + b) / 2
                gc = g(c)
                if gc * ga > 0:
                    a, fa = c, gc
                else:
                    b, fb = c, gc
                kept = 0
        return (a + b) / 2


def _params(m, **kw):
    d = {k: Fraction(int(getattr(m.params, k).p), int(getattr(m.params, k).q)) for k in
         ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")}
    d.update(kw)
    return d


@pytest.mark.parametrize("name, rel", [("n", Fraction(1, 100)),
                                       pytest.param("tau", Fraction(3, 1000), marks=pytest.mark.slow),
                                       pytest.param("B", Fraction(3, 1000), marks=pytest.mark.slow)])
def test_continued_orbit_holds_mpmath_samples(name, rel):
    m, o, lo, hi = _continued(name, rel)
    assert o.theta is not None and o.genuine, o.problem
    for k in range(5):
        x = lo + (hi - lo) * Fraction(k, 4)
        th = _theta_mp(_params(m, **{name: x}), float(o.theta.lower()) - 1e-6, float(o.theta.upper()) + 1e-6)
        assert o.theta.contains(arb(mp.nstr(th, 30))), (x, th, o.theta)
        if o.max_modulus is not None:
            mods = [abs(z) for z in approx.approx_multipliers(_params(m, **{name: x}), float(th))]
            assert o.max_modulus.lower() < max(mods) < o.max_modulus.upper()
        # the certified gradient of theta* against a difference quotient inside the box
        if k == 2:
            h = (hi - lo) / 1000
            t1 = _theta_mp(_params(m, **{name: x + h}), float(th) - 1e-4, float(th) + 1e-4)
            t0 = _theta_mp(_params(m, **{name: x - h}), float(th) - 1e-4, float(th) + 1e-4)
            dq = (t1 - t0) / (2 * mp.mpf(h.numerator) / h.denominator)
            assert o.theta_gradient[0].contains(arb(mp.nstr(dq, 12))) or \
                abs(float(o.theta_gradient[0].mid()) - float(dq)) < float(o.theta_gradient[0].rad()) * 1.01


def test_continued_orbit_stable_over_n_box():
    _, o, _, _ = _continued("n", Fraction(1, 100))
    assert o.stable is True and o.max_modulus.upper() < 1


def test_box_claims_decided_by_continuation():
    m = _model()
    box = Box.of({"n": (Fraction(495, 10), Fraction(505, 10))})
    with working_precision(128):
        out = evaluate_box(m, box, ["orbit_genuine", "stable"])
    assert out["orbit_genuine"][0] == "proved" and out["stable"][0] == "proved"
    assert "continued" in out["stable"][1]


def test_box_stable_not_proved_where_it_fails():
    # n far from the printed point with a wide box: the continuation must not claim more than it shows
    m = _model()
    box = Box.of({"n": (Fraction(5), Fraction(200))})
    with working_precision(128):
        out = evaluate_box(m, box, ["stable"])
    assert out["stable"][0] != "proved"


def test_jets_second_order_forms_hold_samples():
    # f(x, y) = exp(x y) / (1 + x^2) over [0.9, 1.1] x [1.9, 2.1]
    def f(x, y):
        return (x * y).exp() / (1 + x * x)
    c = (arb(1), arb(2))
    X = (arb(1, 0.1), arb(2, 0.1))
    devs = [X[0] - c[0], X[1] - c[1]]
    cen = f(Jet.variable(acb(c[0]), 0, 2), Jet.variable(acb(c[1]), 1, 2))
    nx = Jet(Jet.variable(acb(X[0]), 0, 2), [acb(1), acb(0)])
    ny = Jet(Jet.variable(acb(X[1]), 1, 2), [acb(0), acb(1)])
    box = f(nx, ny)
    val = second_order_value(cen.real, box.real, devs)
    grad = second_order_gradient(cen.real, box.real, devs)
    import math
    for i in range(11):
        for j in range(11):
            x, y = 0.9 + 0.02 * i, 1.9 + 0.02 * j
            fx = math.exp(x * y) / (1 + x * x)
            assert val.contains(arb(fx))
            fy_x = y * fx - 2 * x * fx / (1 + x * x)
            assert grad[0].contains(arb(fy_x)) and grad[1].contains(arb(x * fx))
    assert val.rad() < box.v.v.real.rad()
