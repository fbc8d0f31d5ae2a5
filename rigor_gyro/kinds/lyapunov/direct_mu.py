"""The direct test over the mu interval (16): which mu gives the largest radius with Vdot <= 0 on the
whole disc cylinder, and a certified bound that no admissible mu does better.

R_dsup(mu) is the supremum of the radii R with Vdot <= 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2 (Vdot of
system (2) and V (7) at that mu). :func:`direct_sup_upper_bound` bounds sup over a mu interval of
R_dsup by branch and bound over mu: on a piece Mu, any point (x2, t) of the (x2, t) rectangle gives
R_dsup(mu) <= :func:`~rigor_gyro.kinds.lyapunov.model.direct_radius_upper` for every mu in Mu, so the
smallest of these over a point set bounds the piece. The piece with the largest bound first gets its own
point (a float search for the minimiser of A/|B| at its midpoint, warm-started from the best point
known), then is bisected, until the largest bound is within the target.

The float searches only choose points and the best mu (a search result, named as such by the claim);
the bound holds whatever they return (any point gives a valid bound). Precision: the working one.

Fails when: never raises on a finite model; a piece without a finite bound keeps the whole bound at
+inf (then the claim is inconclusive).
"""
from __future__ import annotations

import math
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import ball_key, certainly_gt, certainly_le, certainly_lt, exact_fraction
from ...core.subdivision import best_first_bisection
from .direct_face import face_polish
from .float_twin import float_twin, in_safe_range
from .model import Gimbal
from .polar_forms import direct_radius_upper, vdot_polar
from .search import compass, grid_then_compass, scaled_ratio

__all__ = ["direct_sup_upper_bound", "direct_point_search", "piece_upper"]


def _fq(x: float) -> fmpq:
    f = Fraction(x)
    return fmpq(f.numerator, f.denominator)


def direct_point_search(g: Gimbal, start: tuple[float, float] | None = None) -> tuple[float, float, float, float]:
    """A float search for inf over (x2, t) of A/|B| at g's mu (the supremum radius of the direct test):
    the smallest value on a 17 x 33 grid of (u, s) (x2 = u x2*, t = pi s; scanned by the float twin when the law
    has one, :func:`_float_proposal`: the same grid point, fewer ball evaluations), refined by a compass search; from
    ``start``, the compass search only (a warm start). Returns (estimate, u, s, the smallest A seen). A
    heuristic: it only chooses a radius to certify, a direction for a point above it, a bounding point;
    everything is certified afterwards."""
    xs, pi = g.c.x2_star, arb.pi()
    amin = math.inf

    def value(u: float, s: float):
        nonlocal amin
        A, B = vdot_polar(g, xs * arb(u), pi * arb(s))
        a, b = float(A.mid()), float(B.mid())
        amin = min(amin, a)
        return scaled_ratio(A, B, a, b), None

    def amin_seen(a: float) -> None:
        nonlocal amin
        amin = min(amin, a)
    if start is None:
        v, u, s, _ = grid_then_compass(value, (17, 33), 90, propose=_float_proposal(g, amin_seen, value))
    else:
        v0, _ = value(*start)
        v, u, s, _ = compass(value, (v0, start[0], start[1], None), (1 / 64, 1 / 128), 40)
    return v, u, s, amin


#: a float A at most this fraction of its terms' size (|c10| + |c20|) may owe its sign to rounding: the ball
#: decides what the search sees there (a hostile review's scene: mu just below k/A0, A(0, 0) = 1e-12 certified > 0
#: and 0.0 in floats, which made vdot_direct give up "at any precision")
TWIN_A_RELATIVE = 1e-9


def _float_proposal(g: Gimbal, seen, ball_value):
    """The grid scan of :func:`direct_point_search` in floats (:mod:`.float_twin`), each A passed to ``seen``
    (the smallest A seen is part of the search's answer, and its sign stops the search: only a ball's midpoint
    may say A <= 0, so a float A within :data:`TWIN_A_RELATIVE` of 0 goes to ``ball_value(u, s)``, the search's
    own ball evaluation, which records its midpoint); None without a twin."""
    fg = float_twin(g)
    if fg is None:
        return None
    xs, pi = fg.xs, math.pi

    def propose(u: float, s: float) -> float:
        try:
            A, B = fg.vdot_polar(xs * u, pi * s)
            (c10, _, _), (c20, _, _) = fg.psi_coefficients(xs * u)
        except (OverflowError, ZeroDivisionError, ValueError):
            return math.nan
        if not in_safe_range(A, B):
            return math.nan
        if not A > TWIN_A_RELATIVE * (abs(c10) + abs(c20)):
            return ball_value(u, s)[0]
        seen(A)
        return A / abs(B) if B != 0 else math.inf
    return propose


def piece_upper(g: Gimbal, Mu: arb, points: list[tuple[fmpq, fmpq]], memo: dict | None = None) -> arb:
    """The smallest of the points' bounds of R_dsup over the mu ball ``Mu`` (exact comparisons: arb's min of
    two balls widens), +inf if none is finite. ``memo``: a dict kept by the caller (one precision) with one
    list ``points`` that only grows at its end, where each point's bound over each ball is computed once (a
    piece re-bounded after a new point keeps the old ones); keyed by the point's index in that list (an fmpq's
    hash costs about 3 us) and the ball."""
    best = arb("inf")
    mkey = ball_key(Mu) if memo is not None else None
    for i, (u, s) in enumerate(points):
        if memo is None:
            b = direct_radius_upper(g, u, s, Mu)
        else:
            key = (i, mkey)
            b = memo.get(key)
            if b is None:
                b = memo[key] = direct_radius_upper(g, u, s, Mu)
        if b.is_finite() and (not best.is_finite() or certainly_lt(b, best)):
            best = b
    return best


def direct_sup_upper_bound(g: Gimbal, mu_lo: arb, mu_hi: arb, gap: arb, max_pieces: int = 400, cold_every: int = 8):
    """A certified upper bound U of sup over mu in [mu_lo, mu_hi] of R_dsup(mu) (exact ends), and the best
    mu the searches saw.

    Stops when the largest piece bound is <= (1 + gap) times the best estimate seen, or at ``max_pieces``.
    Each piece's point comes from a compass search warm-started at the last point found; every
    ``cold_every``-th one also from a whole grid search (the better of the two is kept). A warm search stuck
    in a local minimum overestimates the radius at that mu: the caller compares the best estimate with a
    cold search at its mu and retries with ``cold_every = 1`` when they disagree.
    Returns (U, pieces evaluated, the cover [(lo, hi), ...] of [mu_lo, mu_hi], the points [(u, s), ...]
    as exact rationals, (estimate, mu as a Fraction) of the best estimate seen). Guarantee: U (an exact
    ball) is >= R_dsup(mu) for every mu in the interval, whatever the stopping reason; the estimate is a
    float search result, not certified."""
    points: list[tuple[fmpq, fmpq]] = []
    seen: set = set()
    bounds: dict = {}           # piece_upper's memo: (u, s, mu ball) -> bound
    best = (-math.inf, None)
    last = None

    def own_point(mu: Fraction) -> None:
        nonlocal best, last
        gm = g.with_mu(fmpq(mu.numerator, mu.denominator))
        v, u, s, _ = direct_point_search(gm, last)
        if last is not None:            # a warm start may sit in a local minimum: compare with a cold one
            v2, u2, s2, _ = direct_point_search(gm) if len(points) % cold_every == 0 else (math.inf, u, s, 0)
            if v2 < v:
                v, u, s = v2, u2, s2
        if abs(u) == 1 and math.isfinite(v):
            # on a face: Newton steps put the point on the minimiser (its bound is then tangent to R_dsup at mu)
            vp, sp = face_polish(gm, int(u), s)
            if vp <= v:
                v, s = vp, float(sp)
        last = (u, s)
        if (u, s) not in seen:
            seen.add((u, s))
            points.append((_fq(u), _fq(s)))
        # the search's value overestimates R_dsup(mu) when it misses the global minimiser: every known
        # point bounds it too, so keep the smallest
        at = piece_upper(g, arb(fmpq(mu.numerator, mu.denominator)), points, bounds)
        if at.is_finite():
            v = min(v, float(at))
        if math.isfinite(v) and v > best[0]:
            best = (v, mu)

    own_point(exact_fraction(((mu_lo + mu_hi) / 2).mid()))
    pieces, count = best_first_bisection(
        mu_lo, mu_hi, lambda a, b: piece_upper(g, a.union(b), points, bounds), lambda mid: own_point(exact_fraction(mid)),
        lambda up: up.is_finite() and best[1] is not None and certainly_le(up, arb(best[0]) * (1 + gap)),
        max_pieces, refined=True)
    U = pieces[0][2]
    for _, _, u in pieces:
        if not u.is_finite() or (U.is_finite() and certainly_gt(u, U)):
            U = u
    return U, count, sorted(((a, b) for a, b, _ in pieces), key=lambda p: exact_fraction(p[0])), points, best
