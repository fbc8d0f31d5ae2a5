"""V's polar coefficient gamma near the gimbal lock (issue 40, part 1 leftover): squares from the balls' ends.

Over wide x2 boxes near pi/2 Arb's square of a ball (cos^2 x2, (h cos t + mu sin t)^2) reaches below 0, so gamma
was not certainly positive and the bound of largest_sublevel was [-inf, +inf]; v_polar now squares from the ends
there (cos x2 <= 1/8 on the box). Every certified range is checked against mpmath samples.
"""
import mpmath
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, MpGimbal
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.core.balls import certainly_positive
from rigor_gyro.kinds.lyapunov.polar_forms import square_from_ends, v_polar

NEAR = dict(AGAFONOV2013, x2_star="1.56979632679489661923132169163975144")


def test_square_from_ends_contains_every_square_and_stays_nonnegative():
    with working_precision(64):
        for mid, rad in (("0.3", "0.2"), ("-1", "0.5"), ("0", "2"), ("3.15", "1.35")):
            x = arb(mid) + arb(0, rad)
            sq = square_from_ends(x)
            # >= 0 up to the union's outward rounding; > 0 where the ball excludes 0
            assert sq.lower() >= -sq.upper() * arb(2) ** -20
            assert x.contains(0) or sq.lower() > 0
            for k in range(11):
                y = arb(mid) - arb(rad) + 2 * arb(rad) * k / 10
                assert sq.contains(y * y)
        x = arb("3.15") + arb(0, "1.35")
        assert not (x * x).lower() >= 0 and square_from_ends(x).lower() >= arb("3.2")


def test_gamma_is_positive_near_the_gimbal_lock_and_contains_sampled_values():
    g = gimbal_from_parameters(NEAR)[0]
    mg = MpGimbal(NEAR)
    mpmath.mp.dps = 30
    with working_precision(128):
        xs = g.c.x2_star
        X = xs * arb("0.998047").union(arb(1))
        T = arb.pi() * arb("0.742188").union(arb("0.744141"))
        gamma = v_polar(g, X, T)[2]
        assert certainly_positive(gamma.lower())
        lo, hi = float(gamma.lower()), float(gamma.upper())
    x2lo, x2hi = float(xs.mid()) * 0.998047, float(xs.mid())
    for i in range(6):
        for j in range(6):
            x2 = mpmath.mpf(x2lo) + (x2hi - x2lo) * i / 5
            t = mpmath.pi * (mpmath.mpf("0.742188") + (mpmath.mpf("0.744141") - mpmath.mpf("0.742188")) * j / 5)
            # gamma = V(cos t, x2, sin t) - alpha - beta (V is alpha + beta r + gamma r^2 at r = 1) ... via r = +-1
            vp = mg.V(mpmath.cos(t), x2, mpmath.sin(t))
            vm = mg.V(-mpmath.cos(t), x2, -mpmath.sin(t))
            al = mg.V(0, x2, 0)
            gam = (vp + vm) / 2 - al
            assert lo * (1 - 1e-12) <= gam <= hi * (1 + 1e-12)
