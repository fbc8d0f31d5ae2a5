"""What a lyapunov verdict or margin states must be what was shown (issue 36 parts 2-4): the direct test's
box function against an independent evaluation, vdot_nonpositive refuted only by a point where Vdot > 0,
the damping margin to the binding threshold, bad boxes named by their bad end, futile escalations cut."""
from __future__ import annotations

import dataclasses
from fractions import Fraction

import mpmath
import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.lyapunov.approx import MpGimbal
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.kinds.lyapunov.model import direct_margin
from rigor_gyro.scene import load_scene


def _g_and_mp(params: dict):
    scene = load_scene("agafonov2013")
    full = dict(scene.parameters, **params)
    with mpmath.workdps(50):
        mg = MpGimbal(full)
    return validate(dataclasses.replace(scene, parameters=full)).gimbal, mg


# ------------------------------------------------------------------------------ part 3: A - R |B| on wide boxes

def _mp_margin(mg, u, s, R):
    """A - R |B| at x2 = u pi/6, t = pi s from mpmath's grad V . f (automatic differentiation of (7) along (2),
    not the Psi coefficients): Vdot(r cos t, x2, r sin t) = -r^2 (A + r B) exactly, so r = +-1 give
    A = -(Vdot(1) + Vdot(-1)) / 2 and B = (Vdot(-1) - Vdot(1)) / 2."""
    x2, t = mpmath.pi / 6 * u, mpmath.pi * s
    c, sn = mpmath.cos(t), mpmath.sin(t)
    vp, vm = mg.grad_V_dot_f(c, x2, sn), mg.grad_V_dot_f(-c, x2, -sn)
    A, B = -(vp + vm) / 2, (vm - vp) / 2
    return A - R * abs(B)


@pytest.mark.parametrize("u, s, R", [(("-1/4", "1/4"), ("2/5", "1/2"), "1"),
                                     (("9/10", "1"), ("1/5", "3/10"), "1"),
                                     (("-1/10", "1/10"), ("9/20", "11/20"), "1"),
                                     (("-1/4", "1/4"), ("2/5", "1/2"), "1/10")],
                         ids=["B changes sign, R = 1", "near the face, R = 1", "around t = pi/2, R = 1",
                              "B changes sign, R = 0.1"])
def test_the_direct_margin_encloses_a_minus_r_abs_b_sampled_independently_over_a_wide_box(u, s, R):
    """direct_margin's ball on a wide box (|B| of large radius: the term R |B| spans ~1e5 there) contains
    A - R |B| at every point of a 21 x 21 grid of the box, each evaluated in mpmath at 40 digits from
    grad V . f (an independent path). Dropping the radius of |B| in the direct form gives a lower end above
    the sampled minimum (the named mutant `direct_margin_abs_b_radius_dropped`)."""
    g, mg = _g_and_mp({})
    box = Box.of({"u": tuple(Fraction(x) for x in u), "s": tuple(Fraction(x) for x in s)})
    with working_precision(64):
        F = direct_margin(g, arb(Fraction(R).numerator) / Fraction(R).denominator)(
            {"u": box.ball("u"), "s": box.ball("s")})
    assert F.is_finite()
    lo, hi = float(F.lower()), float(F.upper())
    n = 20
    with mpmath.workdps(40):
        Rm = mpmath.mpf(Fraction(R).numerator) / Fraction(R).denominator
        (u0, u1), (s0, s1) = ([mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in p] for p in (u, s))
        vals = [_mp_margin(mg, u0 + (u1 - u0) * i / n, s0 + (s1 - s0) * j / n, Rm)
                for i in range(n + 1) for j in range(n + 1)]
    low, high = min(vals), max(vals)
    assert lo <= low * (1 + mpmath.sign(low) * mpmath.mpf("1e-12")), (F, low)
    assert high * (1 - mpmath.sign(high) * mpmath.mpf("1e-12")) <= hi, (F, high)
    # the radius matters here: the spread of the samples is a good part of the enclosure's width
    assert high - low > (hi - lo) / 50
