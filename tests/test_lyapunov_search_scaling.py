"""The direct test's float search compares A/|B| even where A and B leave the double range (issue 41: at
H = 1e300 both are about H^2 = 1e600, their floats were inf and the search reported "inf A/|B| ~ inf")."""
import math

from flint import arb

from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.direct_mu import direct_point_search
from rigor_gyro.kinds.lyapunov.search import scaled_ratio


def _ratio(A, B):
    return scaled_ratio(A, B, float(A.mid()), float(B.mid()))


def test_scaled_ratio_in_and_beyond_the_double_range():
    assert _ratio(arb(3), arb(-2)) == 1.5                       # the common case: a / |b|, unchanged
    assert _ratio(arb(3), arb(0)) == math.inf
    big = arb(10) ** 600
    assert math.isclose(_ratio(3 * big, -2 * big), 1.5, rel_tol=1e-15)
    assert math.isclose(_ratio(-3 * big, 2 * big), -1.5, rel_tol=1e-15)
    tiny = arb(10) ** -600                                       # floats underflow to 0
    assert math.isclose(_ratio(3 * tiny, 2 * tiny), 1.5, rel_tol=1e-15)
    assert math.isclose(_ratio(arb(3) * tiny, arb(1)), 0.0, abs_tol=1e-300)
    assert math.isclose(_ratio(arb(1), 2 * tiny), math.inf) or _ratio(arb(1), 2 * tiny) > 1e300
    assert math.isclose(_ratio(3 * big, arb(2) * 10 ** 300 * big), 1.5e-300, rel_tol=1e-12)


def _gimbal(H):
    return gimbal_from_parameters(dict(AGAFONOV2013, H=H))[0]


def test_the_search_at_H_1e300_finds_the_radius_it_finds_at_H_1e30():
    # A/|B| depends on H only through terms of relative size 1/H^2: the same minimiser and value
    v30, u30, s30, a30 = direct_point_search(_gimbal("1e30"))
    v300, u300, s300, a300 = direct_point_search(_gimbal("1e300"))
    assert math.isfinite(v300) and v300 > 0 and a300 > 0
    assert math.isclose(v300, v30, rel_tol=1e-9)
    assert abs(u300 - u30) < 1e-6 and abs(s300 - s30) < 1e-6
