"""The validated Taylor integrator (rigor_gyro.core.validated_flow, core.taylor_jets) against mpmath's odefun.

Every enclosure (at each step end, and over each step at sampled times) must contain the high-precision solution
from every sampled start of the initial box: exact comparison of the ball's ends (as rationals) with mpmath's
value at 30 digits. The width growth per step is measured on a box and bounded. mpmath only checks.
"""
from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import exact_endpoints, working_precision
from rigor_gyro.core.taylor_jets import Grad, taylor_coefficients
from rigor_gyro.core.validated_flow import (Flow, LohnerSet, apriori_enclosure, dyadic_below, lohner_step,
                                            validated_flow, verified)


def _frac(x) -> Fraction:
    x = mpmath.mpf(x)
    man, exp = x.man_exp                     # the mantissa comes unsigned
    q = Fraction(int(man)) * Fraction(2) ** int(exp) if exp >= 0 else Fraction(int(man), 2 ** int(-exp))
    return -q if x < 0 else q


def _inside(ball: arb, value) -> bool:
    with working_precision(4096):   # python-flint's mid() rounds to the working precision: read the ends exactly
        lo, hi = exact_endpoints(ball)
    v = _frac(value)
    # mpmath's own error at 30 digits is far below every radius here; allow it explicitly
    slack = abs(v) * Fraction(1, 10 ** 27) + Fraction(1, 10 ** 50)
    return lo - slack <= v <= hi + slack


# (name, field on balls/series/Grad, field for mpmath, start box as (mid, rad) strings, t_end)
CASES = [
    ("pendulum", lambda x: [x[1], -x[0].sin()], lambda t, y: [y[1], -mpmath.sin(y[0])],
     [("1", "0"), ("0", "0")], Fraction(2)),
    ("van_der_pol", lambda x: [x[1], (1 - x[0] * x[0]) * x[1] - x[0]],
     lambda t, y: [y[1], (1 - y[0] ** 2) * y[1] - y[0]], [("2", "0"), ("0", "0")], Fraction(2)),
    ("quotient_exp", lambda x: [x[1] / (1 + x[0] * x[0]), -x[0] + (-x[1]).exp() / 4],
     lambda t, y: [y[1] / (1 + y[0] ** 2), -y[0] + mpmath.exp(-y[1]) / 4], [("0.5", "0"), ("0.25", "0")],
     Fraction(2)),
    ("pendulum_box", lambda x: [x[1], -x[0].sin()], lambda t, y: [y[1], -mpmath.sin(y[0])],
     [("1", "1/1000"), ("0", "1/1000")], Fraction(1)),
]


def _box(spec):
    out = []
    for m, r in spec:
        mq, rq = Fraction(m), Fraction(r)
        out.append(arb(mq.numerator) / mq.denominator + arb(0, arb(rq.numerator) / rq.denominator))
    return out


def _starts(spec):
    """The centre and the corners of the start box (exact rationals)."""
    mids = [Fraction(m) for m, _ in spec]
    rads = [Fraction(r) for _, r in spec]
    out = [mids]
    if any(rads):
        for s0, s1 in ((-1, -1), (1, -1), (1, 1)):
            out.append([mids[0] + s0 * rads[0], mids[1] + s1 * rads[1]])
    return out


@pytest.mark.parametrize("name,field,mp_field,spec,t_end", CASES, ids=[c[0] for c in CASES])
def test_enclosures_contain_the_high_precision_solution(name, field, mp_field, spec, t_end):
    with working_precision(64):
        fl = validated_flow(field, _box(spec), t_end, order=16)
    assert fl.complete and not fl.reason, fl.reason
    assert fl.t == t_end and sum(fl.step_sizes) == t_end
    mpmath.mp.dps = 30
    for start in _starts(spec):
        sol = mpmath.odefun(mp_field, 0, [mpmath.mpf(start[0].numerator) / start[0].denominator,
                                          mpmath.mpf(start[1].numerator) / start[1].denominator])
        for st in fl.steps:
            t1 = st.t0 + st.h
            y = sol(mpmath.mpf(t1.numerator) / t1.denominator)
            assert all(_inside(b, v) for b, v in zip(st.end, y)), (name, float(t1), st.end, y)
            tm = st.t0 + st.h / 3
            ym = sol(mpmath.mpf(tm.numerator) / tm.denominator)
            assert all(_inside(b, v) for b, v in zip(st.over, ym)), (name, float(tm))


def test_width_growth_per_step_is_measured_and_bounded():
    """A box of radius 1e-6 around the pendulum's start: the end widths grow by a bounded factor per step
    (the doubleton form; a plain box would wrap under the rotation)."""
    spec = [("1", "1/1000000"), ("0", "1/1000000")]
    with working_precision(64):
        fl = validated_flow(CASES[0][1], _box(spec), Fraction(6), order=16)
    assert fl.complete
    w0 = max(float(b.rad()) for b in _box(spec))
    w = [max(float(b.rad()) for b in st.end) for st in fl.steps]
    growth = (w[-1] / w0) ** (1 / len(w))
    # the flow's own Jacobian stretches the box by at most about 2 over t = 6 here; allow 1.05 per step
    assert growth < 1.05, (growth, w[:5], w[-5:])


def test_stored_steps_rerun_identically_and_a_refused_step_is_reported():
    f = CASES[0][1]
    with working_precision(64):
        fl = validated_flow(f, _box(CASES[0][3]), Fraction(1), order=12)
        again = validated_flow(f, _box(CASES[0][3]), Fraction(1), order=12, steps=fl.step_sizes)
        assert again.complete and [s.end for s in again.steps] == [s.end for s in fl.steps] or \
            all(a.overlaps(b) for s, t in zip(again.steps, fl.steps) for a, b in zip(s.end, t.end))
        # a step far too long for the order: the a-priori test fails, the flow stops and says so (no enclosure)
        bad = validated_flow(f, _box(CASES[0][3]), Fraction(64), order=4, steps=[Fraction(64)])
    assert not bad.complete and not bad.steps and "could not be verified" in bad.reason


def test_minimum_step_stops_the_integration():
    """A field with a pole at t = 1 (x' = x^2, x(0) = 1: x = 1/(1 - t)): the integration cannot pass it; it
    stops below h_min with its reason, every enclosure before it correct."""
    with working_precision(64):
        fl = validated_flow(lambda x: [x[0] * x[0]], [arb(1)], Fraction(2), order=10, h_min=Fraction(1, 2 ** 20))
    assert not fl.complete and "could not be verified" in fl.reason
    assert fl.t < 1
    mpmath.mp.dps = 40
    for st in fl.steps:
        t1 = st.t0 + st.h
        assert _inside(st.end[0], 1 / (1 - mpmath.mpf(t1.numerator) / t1.denominator))


def test_the_picard_test_decides_by_containment():
    """verified() accepts only a new enclosure inside the guess; a guess that is too small fails (a mutant that
    accepted it would give the step 'enclosures' not containing the solution: the tests above catch that)."""
    Y = [arb(0, 1)]
    W = [[arb(1, 1)]]
    assert verified(Y, W, [arb(0, "0.5")], [[arb(1, "0.5")]])
    assert not verified(Y, W, [arb(0, 2)], [[arb(1, "0.5")]])
    assert not verified(Y, W, [arb(0, "0.5")], [[arb(1, 2)]])
    assert not verified(Y, W, [arb("nan")], [[arb(1, "0.5")]])
    with working_precision(64):
        # x' = x on [0, 2] from [1, 1]: the first-order guess cannot hold at order 1 with h = 2
        assert apriori_enclosure(lambda x: [x[0]], [arb(1)], Fraction(2), 1) is None
        enc = apriori_enclosure(lambda x: [x[0]], [arb(1)], Fraction(1, 8), 10)
        assert enc is not None and enc[0][0].contains(arb(Fraction(1, 8).numerator / 8).exp())


def test_taylor_coefficients_and_gradients_of_a_rotation():
    with working_precision(64):
        c = taylor_coefficients(lambda x: [x[1], -x[0]], [arb(0), arb(1)], 8, gradients=True)
        fact = 1
        for k in range(9):
            if k:
                fact *= k
            sin_k = [0, 1, 0, -1][k % 4]
            cos_k = [1, 0, -1, 0][k % 4]
            assert (c.values[0][k] - arb(sin_k) / fact).contains(0)
            # d x0(t) / d x0(0) = cos t, d x0(t) / d x1(0) = sin t
            assert (c.jacobian[0][0][k] - arb(cos_k) / fact).contains(0)
            assert (c.jacobian[0][1][k] - arb(sin_k) / fact).contains(0)
        g = Grad(arb(2), [arb(1)])
        h = (g * g + 1 / g - g ** 3).sin()
        # d/dx sin(x^2 + 1/x - x^3) at 2 = cos(4 + 1/2 - 8) (2x - 1/x^2 - 3x^2)
        assert (h.d[0] - arb(-3.5).cos() * (4 - arb(1) / 4 - 12)).contains(0)


def test_dyadic_steps_are_exact_and_below_the_proposal():
    for x in (1e-3, 0.7, 3.0, 123.456):
        q = dyadic_below(x)
        assert 0 < q <= Fraction(x) and q.denominator & (q.denominator - 1) == 0
        assert q > Fraction(x) * Fraction(62, 64)


def test_the_remainder_term_is_in_every_step_end():
    """x' = x from 1 at order 2 over one step of 1/8: the Taylor polynomial 1 + h + h^2/2 misses e^h by 3e-4; only
    the Lagrange remainder (coefficient 3 over the a-priori enclosure) brings e^(1/8) into the enclosure."""
    with working_precision(64):
        fl = validated_flow(lambda x: [x[0]], [arb(1)], Fraction(1, 8), order=2, steps=[Fraction(1, 8)])
        assert fl.complete
        e = fl.steps[0].end[0]
        assert e.contains(arb(fmpq(1, 8)).exp())
        assert not e.contains(1 + arb(fmpq(1, 8)) + arb(fmpq(1, 128)))   # the polynomial alone is not the value


def test_a_box_image_contains_its_corners_under_a_nonlinear_flow():
    """x' = x^2 from [0.4, 0.6] over t in [0, 1/2] (x(t) = x0 / (1 - x0 t)): the Jacobian varies by 30 % over the
    box, so the mean-value form needs its correction term (J B - mid(J B)) r0; the image of every corner and of
    the centre is enclosed at every step end."""
    box = [arb(fmpq(1, 2)) + arb(0, fmpq(1, 10))]
    with working_precision(64):
        fl = validated_flow(lambda x: [x[0] * x[0]], box, Fraction(1, 2), order=8, steps=[Fraction(1, 2)])
        assert fl.complete
        for x0 in (Fraction(2, 5), Fraction(1, 2), Fraction(3, 5)):
            for st in fl.steps:
                t = st.t0 + st.h
                exact = x0 / (1 - x0 * t)
                assert st.end[0].contains(arb(fmpq(exact.numerator, exact.denominator))), (x0, st.end)
