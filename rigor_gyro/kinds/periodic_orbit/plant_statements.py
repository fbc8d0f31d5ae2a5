"""The claim statements of a [plant] scene of kind ``periodic_orbit`` (:mod:`.plant_claims`), and the
settings the plant path shares (Taylor order, guard bits, the amplitude's tolerance). Holds no mathematics."""
from __future__ import annotations

from fractions import Fraction

__all__ = ["PLANT_CLAIMS", "TAYLOR_ORDER", "GUARD_BITS", "AMPLITUDE_REL"]

PLANT_CLAIMS = {
    "half_period": "Every root of the half-period equation g(theta) = c . x0(theta) - h = 0 (x0(theta) the start of "
                   "the symmetric solution of half-period theta) on the searched range is isolated: each piece of "
                   "the range is certified root-free or to hold exactly one root; each root is classified as a "
                   "genuine symmetric orbit or as spurious with a certified witness.",
    "orbit_genuine": "For the orbit of the scene (and every root reported genuine), c . x(t) > -h on the whole open "
                     "interval (0, theta*): the relay does not switch early; proved for all t, not sampled.",
    "initial_point": "The point x(0) where the orbit switches to u = +S (c . x(0) = h) is enclosed "
                     "(quantities x0_1 .. x0_n).",
    "multipliers": "The Jacobian of the half-period point map on the section c . x = h (switching-time "
                   "correction and symmetry x -> -x included) has the enclosed eigenvalues and moduli, for every "
                   "genuine orbit.",
    "stable": "A genuine orbit is stable: every multiplier modulus is certainly < 1 (stability_margin = "
              "1 - max modulus, enclosed).",
}

#: Taylor order of the enclosures over pieces (point coefficients + Lagrange remainder)
TAYLOR_ORDER = 8
#: bits above the working precision at which a genuine orbit's quantities are recomputed
GUARD_BITS = 32
#: relative tolerance of the amplitude's branch and bound (the stored enclosure is padded by it)
AMPLITUDE_REL = Fraction(1, 10 ** 7)
