"""Vdot and V in polar form over the (x2, t) rectangle of region (17): Vdot(r cos t, x2, r sin t) = -r^2 (A + r B)
(:func:`vdot_polar`), the direct test's box function A - R |B| (:func:`direct_margin`) and its bound of the supremum
radius at a point (:func:`direct_radius_upper`), V = alpha + beta r + gamma r^2 (:func:`v_polar`) and the largest
sublevel set's lower bound over boxes (:func:`sublevel_lower_bound`), and the extents of {V < c} from its x2
slices (:func:`slice_extent`).

Guarantee: each form encloses its quantity for every point of its ball or box arguments, at the working
precision (centred forms intersected with the direct ones). Fails when: never raises on finite balls; a box
where a form cannot decide gives a wide ball (the caller subdivides)."""

from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import (certainly_gt, certainly_le, certainly_lt, certainly_negative, certainly_positive,
                           sqrt_of_nonnegative)
from ...core.boxes import even_in
from .moments import MomentLaw
from .model import Dual, Gimbal, mean_value_enclosure

__all__ = ["DIRECT_DOMAIN", "GIMBAL_LOCK_COS", "direct_margin", "direct_radius_upper", "law_is_odd", "slice_extent",
           "slice_in_region", "square_from_ends", "sublevel_lower_bound", "symmetric_in_x2", "v_polar", "vdot_polar"]

# --------------------------------------------------------------------------- Vdot <= 0 directly

#: the (x2, t) domain of the direct test, in exact coordinates: x2 = u x2*, t = pi s
DIRECT_DOMAIN = {"u": (Fraction(-1), Fraction(1)), "s": (Fraction(0), Fraction(1))}


def vdot_polar(g: Gimbal, x2, t, mu: arb | None = None):
    """(A, B) with Vdot(r cos t, x2, r sin t) = -r^2 (A + r B) for every r, exactly (Vdot's Psi form:
    A = c10 cos^2 t + c20 sin^2 t, B = c11 cos^3 t + c13 sin t cos^2 t + c21 cos t sin^2 t + c23 sin^3 t).
    Accepts balls or :class:`Dual` numbers in x2 and t; ``mu``: a ball, for every mu in it (default the
    scene's mu)."""
    (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(x2) if mu is None else g.psi_coefficients(x2, mu)
    c, s = t.cos(), t.sin()
    A = c10 * c * c + c20 * s * s
    B = c11 * c * c * c + c13 * s * c * c + c21 * c * s * s + c23 * s * s * s
    return A, B


def symmetric_in_x2(g: Gimbal, f):
    """The (u, s) box function ``f`` of :func:`direct_margin` or :func:`sublevel_lower_bound`, evaluating
    a box with u < 0 as its mirror image u -> -u and each box once (:func:`rigor_gyro.core.boxes.even_in`)
    when g's law is odd; ``f`` itself otherwise. The prover and the checker both wrap, so they get the
    same ball on every box.

    Why it is valid: with f odd (so f' even) and D, cos even in x2, the coefficients c10, c20 of
    :meth:`Gimbal.psi_coefficients` are even in x2 and c11, c13, c21, c23 odd, so in the polar form
    (:func:`vdot_polar`) A(-x2, t) = A(x2, t) and B(-x2, t) = -B(x2, t): A - R |B| is even in u. For V,
    F and the S term are even and f3 odd, so the part of {Vdot >= 0} above the box -U x S is the
    point reflection p -> -p of the part above U x S, where V takes the same values."""
    return even_in(f, "u") if law_is_odd(g.law) else f


def law_is_odd(law: MomentLaw) -> bool:
    """Whether the law declares itself odd in its own class (a subclass that changes f does not inherit
    the declaration) and f(-x) = -f(x) is not contradicted at three points (a check that can only
    refuse: the declaration is the law's theorem, read off its formula)."""
    if not type(law).__dict__.get("odd", False):
        return False
    a = arb(1)
    return all((law.f(a, -x) + law.f(a, x)).contains(0) for x in (arb("0.3"), arb("0.7"), arb("1.3")))


def direct_radius_upper(g: Gimbal, u: fmpq, s: fmpq, mu: arb) -> arb:
    """An upper bound, valid for every mu in the ball ``mu``, of the supremum radius of the direct test: the
    largest R with Vdot <= 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2 (R_dsup(mu)). +inf when nothing is known.

    Why: at the point x2 = u x2* (|u| <= 1 exact, inside the range), t = pi s, Vdot(r cos t, x2, r sin t)
    = -r^2 (A + r B) (:func:`vdot_polar`). Where B != 0, r = -sign(B) rho (1 + delta) with rho = A / |B|
    gives Vdot > 0 for every delta > 0 when A > 0, and any small r of that sign does when A <= 0: so
    R_dsup(mu) <= max(rho(mu), 0).

    How: where d rho / d mu (forward-mode over the ball) has one sign, max(rho, 0) is monotone on the
    ball and its maximum is taken at the exact end it points to (no dependency overestimation: mu enters
    A and B through terms of size H^2 that cancel); otherwise the ball evaluation over the whole ball.
    Either way the upper end of max(A, 0).upper / |B|.lower."""
    if not certainly_le(abs(arb(u)), 1):
        return arb("inf")
    X, T = g.c.x2_star * arb(u), arb.pi() * arb(s)
    A, B = vdot_polar(g, X, T, mu)
    if not (A.is_finite() and B.is_finite()) or not (certainly_positive(B) or certainly_negative(B)):
        return arb("inf")
    if not mu.rad().is_zero():
        Ad, Bd = vdot_polar(g, X, T, Dual(mu, arb(1)))
        slope = (Ad / Bd).d if certainly_positive(B) else -(Ad / Bd).d
        end = mu.upper() if certainly_le(arb(0), slope) else mu.lower() if certainly_le(slope, 0) else None
        if end is not None:
            A, B = vdot_polar(g, X, T, end)
            if not (A.is_finite() and (certainly_positive(B) or certainly_negative(B))):
                return arb("inf")
    num = A.upper() if certainly_positive(A.upper()) else arb(0)
    return (num / abs(B).lower()).upper()


def direct_margin(g: Gimbal, R: arb):
    """The box function {u, s} -> A - R |B| at x2 = u x2*, t = pi s (see :func:`vdot_polar`), enclosed
    in a centered (mean-value) form where B has one sign on the box, intersected with the direct one.

    Guarantee: if it is > 0 on boxes covering DIRECT_DOMAIN, then for every (x2, t) with |x2| <= x2*,
    A > R |B| >= 0, so A + r B > 0 for all 0 <= r <= R (affine in r): Vdot < 0 on the whole region
    |x2| <= x2*, 0 < x1^2 + x3^2 <= R^2 (B(t + pi) = -B(t), A(t + pi) = A(t): t in [0, pi] suffices)."""
    xs, pi = g.c.x2_star, arb.pi()

    def at(U, S):
        return vdot_polar(g, xs * U, pi * S)

    def f(box: dict) -> arb:
        U, S = box["u"], box["s"]
        A, B = at(U, S)
        direct = A - R * abs(B)
        if U.rad().is_zero() and S.rad().is_zero() or certainly_positive(direct):
            # a point, or already positive: the centered form (a subset of a positive ball) decides nothing
            # more (only the sign is used: leaves and refutations are the same with or without it)
            return direct
        if certainly_positive(B):
            sgn = 1
        elif certainly_negative(B):
            sgn = -1
        else:
            return direct
        # one direction at a time, the other argument a plain ball (no zero-derivative dual arithmetic:
        # the t-derivative needs psi_coefficients only as balls)
        Au, Bu = at(Dual(U, arb(1)), S)
        As, Bs = at(U, Dual(S, arb(1)))
        um, sm = arb(U.mid()), arb(S.mid())
        Am, Bm = at(um, sm)
        mv = (Am - R * abs(Bm) + (Au.d - R * sgn * Bu.d) * (U - um) + (As.d - R * sgn * Bs.d) * (S - sm))
        if not mv.is_finite():
            return direct
        return direct.intersection(mv) if direct.overlaps(mv) else mv
    return f


# --------------------------------------------------------------------------- the largest sublevel set

def v_polar(g: Gimbal, x2, t):
    """(alpha, beta, gamma) with V(r cos t, x2, r sin t) = alpha + beta r + gamma r^2 for every real r,
    exactly: alpha = mu F, beta = f3 sin t, gamma = ((h cos t + mu sin t)^2 + S sin^2 t) / 2 with
    h = H cos x2 / B0 (a sum of squares where S > 0: V is a convex quadratic in r)."""
    c = g.c
    ct, st = t.cos(), t.sin()
    h = c.H * x2.cos() / c.B0
    gamma = ((h * ct + c.mu * st) ** 2 + g.S(x2) * st * st) / 2
    if type(x2) is arb and type(t) is arb and not certainly_positive(gamma.lower()) and \
            not certainly_gt(x2.cos().lower(), GIMBAL_LOCK_COS):
        # near the gimbal lock h cos t and cos^2 x2 span wide balls and Arb's square, mid^2 - 2 |mid| rad - rad^2 at
        # its lower end, reaches below 0 ([-0.36, 13.3] for x2 within 1e-3 of pi/2): squares from the balls' ends
        # instead (>= 0, and > 0 where the ball excludes 0). Only near the lock (cos x2 <= GIMBAL_LOCK_COS on the
        # box) and only where the direct form does not decide: every certificate away from the lock is unchanged.
        # S = f2 + mu (f1 - mu) with f2 = H^2 cos^2 x2 / (D B0): its cos^2 from the ends too
        S = c.H ** 2 * square_from_ends(x2.cos()) / (g.D(x2) * c.B0) + c.mu * (g.f1(x2) - c.mu)
        tight = (square_from_ends(h * ct + c.mu * st) + S * square_from_ends(st)) / 2
        if tight.is_finite():
            gamma = tight
    return (c.mu * g.F(x2), g.f3(x2) * st, gamma)


#: v_polar squares from the balls' ends where cos x2 may be below this (the gimbal lock; see v_polar)
GIMBAL_LOCK_COS = arb(1) / 8


def square_from_ends(x: arb) -> arb:
    """A ball containing y^2 for every y in the ball x, from the ends of |x| (never below 0)."""
    a = abs(x)
    lo = arb(0) if x.contains(0) else a.lower()
    hi = a.upper()
    return (lo * lo).union(hi * hi)


def sublevel_lower_bound(g: Gimbal):
    """The box function {u, s} -> a ball whose lower end is <= V(r cos t, x2, r sin t) for every x2 = u x2*,
    t = pi s in the box and every real r != 0 with Vdot >= 0 there (Vdot = -r^2 (A + r B), see
    :func:`vdot_polar`, so those r are the half-line r B <= -A), i.e. a lower bound of V over the part of
    {Vdot >= 0, (x1, x3) != 0} above the box (+inf where that part is empty).

    How: where A > 0 certainly, |r| >= A/|B| (its lower end over the box) and, when B has one sign, the
    sign of r is known; V = alpha + beta r + gamma r^2 is then bounded below over that half-line by its
    lower-end quadratic (gamma's lower end must be > 0: S > 0 and cos x2 > 0). Where A may be <= 0 the
    whole line r != 0 is admitted (the global minimum of the quadratic). Valid for t in [0, pi] with r of
    either sign, which covers every direction of (x1, x3).

    Guarantee: a lower bound over the box, never an enclosure (a point's value is not V's minimum)."""
    xs, pi = g.c.x2_star, arb.pi()

    def f(box: dict) -> arb:
        X, T = xs * box["u"], pi * box["s"]
        A, B = vdot_polar(g, X, T)
        alpha, beta, gamma = v_polar(g, X, T)
        glo = gamma.lower()
        if not (glo.is_finite() and certainly_positive(glo) and alpha.is_finite() and beta.is_finite()):
            return arb("-inf")
        if certainly_positive(A):
            bhi = abs(B).upper()
            if not bhi.is_finite():
                return arb("-inf")
            if certainly_le(bhi, 0):
                return arb("inf")           # A + r B = A > 0 for every r: Vdot < 0 off r = 0
            rho = (A.lower() / bhi).lower()
            if certainly_positive(B):
                b = (-beta).lower()         # r = -s, s >= rho
            elif certainly_negative(B):
                b = beta.lower()            # r = s, s >= rho
            else:
                b = -(abs(beta).upper())
        else:
            rho, b = arb(0), -(abs(beta).upper())
        a = alpha.lower()
        # the minimum over s >= rho of a + b s + glo s^2 (valid below alpha + beta' s + gamma s^2 for s >= 0)
        if certainly_le(-b / (2 * glo), rho):
            return a + b * rho + glo * rho * rho
        return a - b * b / (4 * glo)
    return f


# --------------------------------------------------------------------------- extents of {V < c}

def slice_extent(g: Gimbal, c: arb, axis: str):
    """x2 (a ball) -> an upper bound of max |x_axis| over the slice {(x1, x3): V(x1, x2, x3) < c} (axis
    "x1" or "x3"), exact where the slice is certainly non-empty. At fixed x2, V is a convex quadratic in
    (x1, x3) with minimum phi(x2) at z0 = (mu f3/(h S), -f3/S) (h = H cos x2 / B0), so the slice is the
    ellipse 1/2 (z - z0)' P (z - z0) < c - phi, P^-1 = [[S + mu^2, -mu h], [-mu h, h^2]] / (h^2 S):

        max |x1| = (mu |f3| / S + sqrt(2 (c - phi) (S + mu^2) / S)) / h,  max |x3| = |f3| / S + sqrt(2 (c - phi) / S).

    Where c - phi < 0 certainly the slice is empty and 0 is returned (the set's maximum is >= 0: it
    contains the origin); where c - phi may be either sign, [0, its upper end] replaces it (an upper bound).
    Guarantee: an upper bound everywhere; the exact maximum (a ball containing it) where c > phi certainly."""
    mu = g.c.mu

    def smooth(x2):             # where c > phi and f3 > 0: no case split, so it takes Dual numbers
        S = g.S(x2)
        d, f3 = c - g.phi(x2), g.f3(x2)
        if axis == "x1":
            return (mu * f3 / S + (2 * d * (S + mu * mu) / S).sqrt()) / (g.c.H * x2.cos() / g.c.B0)
        return f3 / S + (2 * d / S).sqrt()
    centred = mean_value_enclosure(smooth)

    def e(x2):
        if not x2.rad().is_zero() and certainly_positive(c - g.phi(x2)) and certainly_positive(g.f3(x2)):
            # the mean-value form: at a flat maximum its overestimation is quadratic in the piece width
            v = centred(x2)
            if v.is_finite():
                return v
        S = g.S(x2)
        d = c - g.phi(x2)
        if certainly_lt(d, 0):
            return arb(0)
        if not certainly_positive(d):
            d = arb(0).union(d.upper())
        f3 = abs(g.f3(x2))
        # d is >= 0 here (d itself, or the hull of 0 and its upper end): its ball may reach below 0
        if axis == "x1":
            return (mu * f3 / S + sqrt_of_nonnegative(2 * d * (S + mu * mu) / S)) / (g.c.H * x2.cos() / g.c.B0)
        return f3 / S + sqrt_of_nonnegative(2 * d / S)
    return e


def slice_in_region(g: Gimbal, c: arb, R: arb, x2) -> bool:
    """Certainly: the slice {V(., x2, .) < c} is non-empty (c > phi(x2)) and its centre z0 lies inside
    the disc x1^2 + x3^2 < R^2. With V >= c on the cylinder of radius R (c <= c*), the whole slice then
    lies in the disc (it is convex and cannot cross the circle), so it is a slice of {x in (17): V < c}."""
    S = g.S(x2)
    f3 = g.f3(x2)
    h = g.c.H * x2.cos() / g.c.B0
    z1, z3 = g.c.mu * f3 / (h * S), -f3 / S
    return certainly_positive(c - g.phi(x2)) and certainly_lt(z1 * z1 + z3 * z3, R * R)
