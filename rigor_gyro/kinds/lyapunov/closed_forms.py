"""Closed forms shared by the claims and the checker (rigor-gyro check recomputes them from its own m, M): the
constants of (13)-(18) from m and M, the damping margin, points of the cylinder x1^2 + x3^2 = R^2, and the ends of
c* (the minimum of V on the boundary of region (17): the faces |x2| = x2* in closed form, the cylinder by a lower
bound over x2 pieces).

Guarantee: enclosures at the working precision for every m, M in their balls. Fails when: never raises; a
quantity not certainly defined (a square root of a ball reaching below 0) comes out infinite or NaN, and the
claims reading it stay inconclusive."""

from __future__ import annotations

import math
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_lt, square, sqrt_of_nonnegative
from .model import Gimbal, hypot_ball

__all__ = ["CIRCLE_DIRECTIONS", "DAMPING_THRESHOLDS", "c_star_lower", "c_star_upper", "closed_form_constants",
           "cylinder_lower_bound", "cylinder_points", "damping_margin", "faces_minimiser_inside"]

# ------------------------------------------------------------------------------------ constants, c*
# Closed forms shared by the claims and the checker (rigor-gyro check recomputes them from its own m, M).

def closed_form_constants(g: Gimbal, m: arb, M: arb) -> dict[str, arb]:
    """A0, B0, C0, p = max(M, A0 m / cos^2 x2*), k_min, the mu interval (16), R1 (13), R2 (14), R, for
    enclosures m, M of the maxima (every returned ball contains the value for every m, M in them)."""
    c = g.c
    A0, B0, C0, H, k, mu = c.A0, c.B0, c.C0, c.H, c.k, c.mu
    xs = c.x2_star
    s, cs = xs.sin(), xs.cos()
    pA = A0 * m / cs ** 2
    p = M.max(pA)
    out = {"A0": A0, "B0": B0, "C0": C0, "m": m, "M": M, "A0_m_over_cos2": pA, "p": p,
           "k_min": p * A0 / H, "mu_min": p / H, "mu_max": k / A0}
    Ds = A0 - C0 * s ** 2
    D1 = 108 * A0 * (A0 - C0) * H ** 4 * cs ** 4 * square(k / A0 - mu)
    D2 = 16 * mu ** 2 * A0 * (A0 - C0) * H ** 2 * C0 ** 2 + 27 * square(mu * k * B0 * C0 + (A0 - C0) * H ** 2)
    P = A0 - C0 - C0 * cs ** 2
    E1 = 4 * H ** 2 * square(mu * H * cs ** 2 - m * A0) * Ds ** 4
    E2 = A0 ** 2 * (4 * mu ** 2 * H ** 2 * square(P) * Ds ** 2 * s ** 2 + square(mu * k * B0 * C0 - (A0 - C0) * H ** 2))
    # D1, E1 are squares times positive factors and D2, E2 sums of squares: >= 0 exactly
    R1, R2 = sqrt_of_nonnegative(D1 / D2), sqrt_of_nonnegative(E1 / E2)
    out.update({"R1": R1, "R2": R2, "R": R1.min(R2), "R2_base": mu * H * cs ** 2 - m * A0})
    return out


#: the thresholds in k of the conditions damping_condition needs (mu > p/H of (16) is no threshold in k)
DAMPING_THRESHOLDS = ("k > k_min = p A0/H (18)", "k > mu A0 (mu < k/A0 of (16))")


def damping_margin(g: Gimbal, k_min: arb) -> tuple[arb, str, dict[str, arb]]:
    """The design margin in k of damping_condition: min over its thresholds t in k (k_min of (18) and mu A0,
    from mu < k/A0 of (16)) of k/t - 1, the name of the binding threshold (both names when the two are not
    separated at this precision) and every threshold's k/t - 1. Valid for every k_min in its ball."""
    c = g.c
    each = {name: c.k / t - 1 for name, t in zip(DAMPING_THRESHOLDS, (k_min, c.mu * c.A0))}
    (n1, a), (n2, b) = each.items()
    binding = n1 if certainly_lt(a, b) else n2 if certainly_lt(b, a) else f"{n1} and {n2} (not separated)"
    return a.min(b), binding, each


def _circle_directions(n: int = 32) -> list[tuple[Fraction, Fraction]]:
    """n exact rational points (c, s) of the unit circle, c^2 + s^2 = 1 exactly, near the angles 2 pi j / n:
    c = (1 - t^2) / (1 + t^2), s = 2 t / (1 + t^2) with t = tan(pi j / n) rounded to a float (any rational t
    gives a point of the circle; the float only places it)."""
    out = []
    for j in range(n):
        t = Fraction(math.tan(math.pi * j / n)) if 2 * j != n else None
        out.append((Fraction(-1), Fraction(0)) if t is None else ((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)))
    return out


#: the directions V is sampled in on the cylinder (an upper bound of c*: V at points of the cylinder)
CIRCLE_DIRECTIONS = _circle_directions()


def cylinder_points(R: arb, xs: arb) -> list[tuple[arb, arb, arb]]:
    """96 balls (x1, x2, x3), each containing a point of the cylinder x1^2 + x3^2 = R^2 with |x2| <= x2*
    (for every radius R's ball holds): the 32 CIRCLE_DIRECTIONS, exact rationals of the unit circle, times
    R, at x2 = 0, x2*/2, x2*. V's smallest upper end over them is >= V at a point of the cylinder, so it
    bounds c* (V's minimum over that cylinder piece) from above."""
    return [(R * arb(fmpq(c.numerator, c.denominator)), x2, R * arb(fmpq(s_.numerator, s_.denominator)))
            for x2 in (arb(0), xs / 2, xs) for c, s_ in CIRCLE_DIRECTIONS]


def faces_minimiser_inside(g: Gimbal, xs: arb, R: arb) -> bool:
    """The point (m1, m3) where V is smallest on the face x2 = x2* lies certainly inside the disc
    x1^2 + x3^2 < R^2 (then the faces' closed form phi(x2*) is V's minimum over the face piece of the
    region, and it bounds c* from above as well as below)."""
    m1, m3 = g.phi_minimiser(xs)
    return certainly_lt(m1 ** 2 + m3 ** 2, R ** 2)


def c_star_lower(face: arb, cyl: arb, inside: bool) -> arb:
    """A lower bound of c* = min(V on the faces |x2| = x2* inside the disc, V on the cylinder): ``cyl`` (a
    lower bound of V's minimum on the cylinder), and with the faces' minimiser inside the disc also the
    faces' value phi(x2*)'s lower end (``face`` encloses it). Without the minimiser inside, the faces' minimum
    over the disc lies on its rim, on the cylinder: cyl bounds it."""
    return face.lower().min(cyl) if inside else cyl


def c_star_upper(g: Gimbal, R: arb, xs: arb, face: arb, inside: bool) -> arb:
    """An upper bound of c* (an exact point): the smallest upper end of V over the cylinder points (each
    ball holds V at a point of the cylinder), and with the faces' minimiser inside the disc also the faces'
    value phi(x2*)'s upper end."""
    samples = [g.V(*p) for p in cylinder_points(R, xs)]
    upper = samples[0]
    for s in samples[1:]:
        upper = upper.min(s)
    return upper.upper().min(face.upper()) if inside else upper.upper()


def cylinder_lower_bound(g: Gimbal, R: arb):
    """x2 piece -> a lower bound of min over theta of V(R cos theta, x2, R sin theta).

    On the circle V = alpha + beta sin(th) + gamma cos(2 th) + delta sin(2 th) with
    alpha = mu F + (f2 + mu f1 + h^2) R^2/4, beta = f3 R, gamma = (h^2 - f2 - mu f1) R^2/4,
    delta = mu h R^2/2 (h = H cos x2 / B0), so V >= alpha - |beta| - sqrt(gamma^2 + delta^2)."""
    c = g.c

    def lb(x2):
        h = c.H * x2.cos() / c.B0
        e = g.f2(x2) + c.mu * g.f1(x2)
        alpha = c.mu * g.F(x2) + (e + h * h) * R * R / 4
        gamma = (h * h - e) * R * R / 4
        delta = c.mu * h * R * R / 2
        return alpha - abs(g.f3(x2)) * R - hypot_ball(gamma, delta)
    return lb
