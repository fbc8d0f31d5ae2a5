"""The largest sublevel set near the gimbal lock (kinds/lyapunov/sublevel.py: phi_lower and box_lower_bound, issue
40): every certified lower bound below mpmath's V and phi sampled over its box; the stress scene x2* within 1e-3
of pi/2 decided (it was inconclusive: the polar bound reached [-5187, ...] on 2999 boxes)."""
from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, MpGimbal
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.sublevel import box_lower_bound, largest_sublevel, phi_lower

LOCK = dict(AGAFONOV2013, x2_star="1.56979632679489661923132169163975144")
DPS = 30


def _mq(q: Fraction):
    return mpmath.mpf(q.numerator) / q.denominator


def _mpf(x: arb):
    return mpmath.mpf(x.mid().str(40, radius=False))


def _ball(lo: Fraction, hi: Fraction) -> arb:
    return arb(fmpq(lo.numerator, lo.denominator)).union(arb(fmpq(hi.numerator, hi.denominator)))


@pytest.mark.parametrize("params, lo, hi", [
    (LOCK, Fraction(1563, 1000), Fraction(15697, 10000)),       # at the lock: cos x2 in [0.001, 0.008]
    (LOCK, Fraction(3, 2), Fraction(1563, 1000)),
    (LOCK, Fraction(1, 10), Fraction(1, 5)),
    (dict(AGAFONOV2013, mu="0.035"), Fraction(1, 4), Fraction(1, 2)),   # mu > f1 somewhere: the plain form
])
def test_phi_lower_is_below_mpmath_phi_and_v_sampled_over_the_x2_interval(params, lo, hi):
    g, mg = gimbal_from_parameters(params)[0], MpGimbal(params)
    with working_precision(64):
        p = phi_lower(g, _ball(lo, hi))
    if p is None:
        assert params.get("mu") == "0.035"        # S > 0 not certain there: no bound, never a wrong one
        return
    with mpmath.workdps(DPS):
        bound = _mpf(p)
        for i in range(9):
            x2 = _mq(lo) + (_mq(hi) - _mq(lo)) * i / 8
            S = mg.f2(x2) + mg.mu * (mg.f1(x2) - mg.mu)
            assert S > 0
            phi = mg.mu * mg.F(x2) - mg.f3(x2) ** 2 / (2 * S)
            assert phi >= bound, (i, phi, bound)
            for x1 in (-0.3, 0, 0.2):
                for x3 in (-0.1, 0, 0.05):
                    assert mg.V(mpmath.mpf(x1), x2, mpmath.mpf(x3)) >= bound


def test_phi_lower_at_the_lock_is_close_to_mpmath_minimum():
    """Not only below: within 30 % of phi's minimum over the interval at the lock (the cancellation-free form;
    evaluated as it stands, f3^2 / (2 S) made the bound about -5000)."""
    g, mg = gimbal_from_parameters(LOCK)[0], MpGimbal(LOCK)
    lo, hi = Fraction(1563, 1000), Fraction(15697, 10000)
    with working_precision(64):
        p = phi_lower(g, _ball(lo, hi))
    with mpmath.workdps(DPS):
        low = min(mg.mu * mg.F(x) - mg.f3(x) ** 2 / (2 * (mg.f2(x) + mg.mu * (mg.f1(x) - mg.mu)))
                  for x in (_mq(lo) + (_mq(hi) - _mq(lo)) * i / 16 for i in range(17)))
        assert 0.7 * low <= _mpf(p) <= low


def test_box_lower_bound_near_the_lock_is_below_v_at_points_where_vdot_is_nonnegative():
    g, mg = gimbal_from_parameters(LOCK)[0], MpGimbal(LOCK)
    xs = mpmath.mpf("1.56979632679489661923132169163975144")
    for u, s in (((Fraction(255, 256), Fraction(1)), (Fraction(101, 256), Fraction(51, 128))),
                 ((Fraction(-1), Fraction(-127, 128)), (Fraction(1, 2), Fraction(33, 64)))):
        b = Box.of({"u": u, "s": s})
        with working_precision(64):
            v = box_lower_bound(g)({k: b.ball(k) for k in b.names})
        with mpmath.workdps(DPS):
            bound, seen = _mpf(v.lower()), 0
            for i in range(5):
                for j in range(5):
                    x2 = xs * (_mq(u[0]) + (_mq(u[1]) - _mq(u[0])) * i / 4)
                    t = mpmath.pi * (_mq(s[0]) + (_mq(s[1]) - _mq(s[0])) * j / 4)
                    for r in (-1000, -100, -10, -3, -1, -0.1, 0.1, 1, 3, 10, 100, 1000):
                        x1, x3 = r * mpmath.cos(t), r * mpmath.sin(t)
                        if mg.grad_V_dot_f(x1, x2, x3) >= 0:
                            seen += 1
                            assert mg.V(x1, x2, x3) >= bound
            assert seen > 0


def test_the_lock_stress_scene_largest_sublevel_is_decided_and_brackets_the_natural_c_max():
    """x2* within 1e-3 of pi/2: c_max > 0 certified (V > 0 on the range, the faces at 93.3 above the point of
    N at 77.22: N binds), the upper end the same point as the natural sublevel set's (77.2245866...)."""
    g = gimbal_from_parameters(LOCK)[0]
    with working_precision(64):
        r = largest_sublevel(g, 20000)
    assert r.c_lower is not None and Fraction(r.c_lower) > 40, r.reason
    assert Fraction(r.c_upper) < Fraction("77.22459") and r.binding == "vdot"
