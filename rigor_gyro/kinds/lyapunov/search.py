"""Searches on point values over the (x2, t) rectangle of the polar form: they only *choose* (a radius to
certify, a direction for a counterexample, a target for a lower bound); nothing they return is trusted.

Coordinates: x2 = u x2*, t = pi s, (u, s) in [-1, 1] x [0, 1], as in
:data:`rigor_gyro.kinds.lyapunov.model.DIRECT_DOMAIN`.
"""
from __future__ import annotations

import math
from typing import Any, Callable

__all__ = ["grid_then_compass", "compass", "scaled_ratio"]

#: the smallest positive normal double: below it a float has lost relative precision (or is 0)
_TINY = 2.2250738585072014e-308


def scaled_ratio(A, B, a: float, b: float) -> float:
    """A/|B| as a float for a search to compare, from the balls A, B and their midpoints a, b as floats: a/|b|
    where both floats kept their magnitude (normal doubles, or an exact 0 for a: the common case,
    unchanged), +inf where B's midpoint is exactly 0, else the quotient of the balls' exact midpoints taken
    in arb (its exponent range is unbounded) and only then made a float, so terms beyond the double range
    (H = 1e300 makes A and B about H^2; a = 1e-300 makes terms about a) give their ratio instead of
    inf/inf = nan or x/0. A heuristic value: it only chooses where to search; nothing decides on it."""
    if _TINY <= abs(b) < math.inf and (_TINY <= abs(a) < math.inf or (a == 0 and A.mid().is_zero())):
        return a / abs(b)
    mb = B.mid()
    if mb.is_zero():
        return math.inf
    return float((A.mid() / abs(mb)).mid())


#: the grid points whose float-twin value is within this relative distance of the twin's minimum are
#: evaluated in balls (the twin agrees with the balls' midpoints to about 1e-13; a margin far above it)
PROPOSAL_WINDOW = 1e-6


def grid_then_compass(value: Callable[[float, float], tuple[float, Any]], grid: tuple[int, int], steps: int,
                      extra: Any = None, propose: Callable[[float, float], float] | None = None
                      ) -> tuple[float, float, float, Any]:
    """The smallest ``value(u, s)[0]`` on an nu x ns grid of the rectangle (ends included), then refined by a
    compass search (the four axis moves; the step halves when none improves) for ``steps`` rounds. Returns
    (value, u, s, the second item ``value`` returned there; ``extra`` if no finite value was seen). A
    heuristic: no guarantee of a global minimum.

    ``propose``: a cheap twin of ``value(u, s)[0]`` (floats, :mod:`.float_twin`) that scans the grid instead;
    only the grid points within PROPOSAL_WINDOW (relative) of its minimum are evaluated by ``value``, the best
    of them (the first in grid order on ties) starts the compass search. Where the twin agrees with ``value``
    to better than that window (its purpose) the result is the very one the ball grid gives; where it
    returns NaN anywhere or no finite value, the grid is scanned by ``value`` as without it."""
    nu, ns = grid
    pts = [(-1 + 2 * i / (nu - 1), j / (ns - 1)) for i in range(nu) for j in range(ns)]
    best = None
    if propose is not None:
        twin = []
        for u, s in pts:
            v = propose(u, s)
            if v != v:                  # NaN: the twin is out of its range here; scan in balls
                twin = None
                break
            twin.append(v)
        bv = min(twin) if twin else math.inf
        if math.isfinite(bv):
            # every grid point within the twin's noise of its minimum (ties, e.g. by a symmetry, are broken
            # by the ball values in grid order, exactly as the ball grid breaks them)
            near = bv + PROPOSAL_WINDOW * abs(bv)
            best = (math.inf, 0.0, 0.5, extra)
            for (u, s), tv in zip(pts, twin):
                if tv <= near:
                    v, x = value(u, s)
                    if v < best[0]:
                        best = (v, u, s, x)
            if not best[0] < math.inf:
                best = None
    if best is None:
        best = (math.inf, 0.0, 0.5, extra)
        for u, s in pts:
            v, x = value(u, s)
            if v < best[0]:
                best = (v, u, s, x)
    v0, u, s, x0 = best
    return compass(value, (v0, u, s, x0), (2 / (nu - 1), 1 / (ns - 1)), steps)


def compass(value: Callable[[float, float], tuple[float, Any]], start: tuple[float, float, float, Any],
            step: tuple[float, float], steps: int) -> tuple[float, float, float, Any]:
    """A compass search for the smallest ``value(u, s)[0]`` from ``start`` = (value, u, s, extra) there: the
    four axis moves of ``step``, halved when none improves, for ``steps`` rounds. Returns (value, u, s,
    extra) at the best point seen. A heuristic: a local minimum at best. ``value`` must be a function of the
    point (each point is evaluated once; ``start``'s value is taken as given)."""
    v0, u, s, x0 = start
    hu, hs = step
    # each point's value once: a move makes the point left behind a neighbour again, and steps below a
    # double's resolution give the same points over and over (``value`` is a function of the point: the
    # same comparisons, the same answer, about half the evaluations)
    seen: dict = {(u, s): (v0, x0)}
    for _ in range(steps):
        moved = False
        for du, ds in ((hu, 0), (-hu, 0), (0, hs), (0, -hs)):
            a, b = u + du, s + ds
            if -1 <= a <= 1 and 0 <= b <= 1:
                hit = seen.get((a, b))
                if hit is None:
                    hit = seen[(a, b)] = value(a, b)
                v, x = hit
                if v < v0:
                    v0, u, s, x0, moved = v, a, b, x, True
        if not moved:
            hu, hs = hu / 2, hs / 2
    return v0, u, s, x0
