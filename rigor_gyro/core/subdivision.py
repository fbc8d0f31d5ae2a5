"""Certified statements over an interval by subdivision: positivity, and enclosures of extrema.

``f`` maps an ``arb`` (an interval X) to an ``arb`` that contains f(t) for every t in X; written
with ball operations only, it gives that guarantee automatically.

Guarantee:
* :func:`certify_positive` returns PROVED only when f(X) > 0 certainly on pieces covering [lo, hi];
  REFUTED only with a witness point t (an exact ball) where f(t) <= 0 certainly (for strict
  positivity) ; otherwise INCONCLUSIVE with the piece where it got stuck.
* :func:`enclose_max` / :func:`enclose_min` return a ball containing max (min) of f over [lo, hi]:
  its lower end is a certified value of f at a point (so max >= it), its upper end the largest upper
  bound of f over pieces covering the interval (so max <= it).

Precision: the current working precision. Pieces are bisected at exact midpoints.

Fails when: ``max_pieces`` is exhausted: positivity is INCONCLUSIVE; an extremum is returned with
``converged = False`` (the ball is still valid, only wider than ``abs_tol``).

Example:
    >>> from flint import arb
    >>> from rigor_gyro.core.balls import working_precision
    >>> with working_precision(64):
    ...     r = certify_positive(lambda x: x * x - x + 1, "-2", "2")
    ...     m = enclose_max(lambda x: x.sin(), "0", "3", abs_tol="1e-8")
    >>> r.status.value, m.ball.contains(1), m.converged
    ('proved', True, True)
"""
from __future__ import annotations

import heapq
from dataclasses import dataclass, field
from typing import Callable

from flint import arb, fmpq

from .balls import (ball, certainly_le, certainly_lt, certainly_positive, decimal_bounds, enclosure_text,
                    exact_fraction, interval)
from .outcome import Status
from .roots import enclose_f_df

__all__ = ["best_first_bisection", "Positivity", "Extremum", "BoxPositivity", "BoxLowerBound", "mean_value_form", "certify_positive",
           "certify_positive_on_box", "lower_bound_on_box", "enclose_max", "enclose_min"]

IntervalFunction = Callable[[arb], arb]


def mean_value_form(f) -> IntervalFunction:
    """Wrap f (which must accept ``arb_series``) into the mean-value enclosure
    f(X) in f(m) + f'(X) (X - m), intersected with the direct enclosure: much tighter on small
    pieces, so positivity with a thin margin needs far fewer pieces."""
    def g(x: arb) -> arb:
        fx, dfx = enclose_f_df(f, x)
        if x.rad().is_zero():
            return fx
        m = x.mid()
        fm, _ = enclose_f_df(f, m)
        mv = fm + dfx * (x - m)
        return fx.intersection(mv) if fx.overlaps(mv) else mv
    return g


@dataclass
class Positivity:
    """Outcome of :func:`certify_positive`."""

    status: Status
    pieces: int
    witness: arb | None = None          # a point where f <= 0 certainly (REFUTED)
    witness_value: arb | None = None
    stuck: tuple[arb, arb] | None = None  # an undecided piece (INCONCLUSIVE)
    reason: str = ""
    stuck_value: arb | None = None        # f over the undecided piece: what would decide it


def certify_positive(f: IntervalFunction, lo: object, hi: object, *, max_pieces: int = 20000,
                     min_width: object = None, record: list | None = None) -> Positivity:
    """Decide f > 0 on [lo, hi] by bisection; see the module docstring. With ``record`` (a list), each
    piece (a, b) on which f > 0 was certified is appended to it: the witness a checker re-evaluates."""
    stack = [(ball(lo), ball(hi))]
    done = 0
    while stack:
        a, b = stack.pop()
        x = interval(a, b)
        fx = f(x)
        done += 1
        if certainly_positive(fx):
            if record is not None:
                record.append((a, b))
            continue
        mid = ((a + b) / 2).mid()
        fm = f(mid)
        if certainly_le(fm, 0):
            return Positivity(Status.REFUTED, done, mid, fm, reason=f"f(t) <= 0 at the point t = {enclosure_text(mid, 20)}")
        for end in (a, b):
            fe = f(end)
            if certainly_le(fe, 0):
                return Positivity(Status.REFUTED, done, end, fe, reason=f"f(t) <= 0 at the point t = {enclosure_text(end, 20)}")
        too_small = min_width is not None and certainly_lt(b - a, ball(min_width))
        if done + len(stack) >= max_pieces or too_small or not certainly_lt(a, mid) or not certainly_lt(mid, b):
            return Positivity(Status.INCONCLUSIVE, done, stuck=(a, b), stuck_value=fx,
                              reason=f"f not separated from 0 on [{decimal_bounds(a, 12)[0]}, {decimal_bounds(b, 12)[1]}] after {done} "
                                     "pieces (raise precision or max_pieces; f may touch 0 there)")
        stack.append((mid, b))
        stack.append((a, mid))
    return Positivity(Status.PROVED, done, reason=f"f > 0 certified on {done} pieces")


class _LargestFirst:
    """Heap key putting the largest upper bound first: compared as floats (fast), and exactly only when
    the floats tie (the balls are exact points, so the comparison is decided). The order only chooses
    which piece to refine next; the enclosure is the max over every piece, whatever the order."""

    __slots__ = ("key", "up")

    def __init__(self, up: arb) -> None:
        self.up = up
        self.key = -float(up) if up.is_finite() else float("-inf")

    def __lt__(self, other: "_LargestFirst") -> bool:
        if self.key != other.key:
            return self.key < other.key
        return bool(self.up > other.up)


@dataclass
class Extremum:
    """A certified enclosure ``ball`` of an extremum, with the point that attains the certified
    bound and the number of pieces used."""

    ball: arb
    argpoint: arb
    pieces: int
    converged: bool
    #: the final pieces (a, b), covering [lo, hi]: the upper end of the ball is the largest upper
    #: bound of f over them, and the lower end f at ``argpoint``; the witness a checker re-evaluates
    cover: list = field(default_factory=list)


def enclose_max(f: IntervalFunction, lo: object, hi: object, *, abs_tol: object = "1e-12",
                rel_tol: object = 0, max_pieces: int = 20000) -> Extremum:
    """Enclose max of f over [lo, hi] to width about ``abs_tol + rel_tol * |max|`` (branch and bound).
    A relative tolerance is what certifies the sign of a small extremum: with only an absolute one
    fixed from the size of f elsewhere, a maximum of 1e-9 would be "converged" at width 1e-6."""
    a0, b0 = ball(lo), ball(hi)
    atol, rtol = ball(abs_tol), ball(rel_tol)
    best_pt = ((a0 + b0) / 2).mid()
    best = f(best_pt).lower()          # max >= best (f at a point, its lower bound)
    for p in (a0, b0):
        v = f(p).lower()
        if certainly_lt(best, v):
            best, best_pt = v, p
    heap: list[tuple[_LargestFirst, int, arb, arb, arb]] = []
    count = 0

    def push(a: arb, b: arb) -> None:
        nonlocal count
        up = f(interval(a, b)).upper()
        count += 1
        # the heap top is the piece with the largest upper bound
        heapq.heappush(heap, (_LargestFirst(up), count, a, b, up))

    push(a0, b0)
    converged = False
    while heap:
        _, _, a, b, up = heap[0]
        if certainly_le(up - best, atol + rtol * abs(best)):
            converged = True
            break
        if count >= max_pieces:
            break
        heapq.heappop(heap)
        mid = ((a + b) / 2).mid()
        v = f(mid).lower()
        if certainly_lt(best, v):
            best, best_pt = v, mid
        if not (certainly_lt(a, mid) and certainly_lt(mid, b)):
            heapq.heappush(heap, (_LargestFirst(up), count, a, b, up))
            break
        push(a, mid)
        push(mid, b)
    upper = best
    for item in heap:                       # the heap's pieces cover [lo, hi]
        upper = upper.max(item[4])          # certified max of upper bounds
    return Extremum(best.union(upper), best_pt, count, converged, [(item[2], item[3]) for item in heap])


def enclose_min(f: IntervalFunction, lo: object, hi: object, *, abs_tol: object = "1e-12",
                rel_tol: object = 0, max_pieces: int = 20000) -> Extremum:
    """Enclose min of f over [lo, hi] (as -max(-f))."""
    m = enclose_max(lambda x: -f(x), lo, hi, abs_tol=abs_tol, rel_tol=rel_tol, max_pieces=max_pieces)
    return Extremum(-m.ball, m.argpoint, m.pieces, m.converged, m.cover)


BoxFunction = Callable[[dict], arb]


@dataclass
class BoxPositivity:
    """Outcome of :func:`certify_positive_on_box`: the status, the leaves on which f > 0 was certified
    (PROVED: they tile the box, the witness a checker re-evaluates), a point (exact rationals, by
    name) where f <= 0 certainly (REFUTED), or the undecided box (INCONCLUSIVE)."""

    status: Status
    leaves: list = field(default_factory=list)
    witness: dict | None = None
    witness_value: arb | None = None
    stuck: object = None
    reason: str = ""


#: boxes of certify_positive_on_box whose midpoint is always tried as a counterexample (a coarse
#: refutation stays as early as it was, whatever the box's enclosure is centred at)
EARLY_MIDPOINTS = 64


def certify_positive_on_box(f: BoxFunction, whole, *, max_pieces: int = 20000) -> BoxPositivity:
    """Decide f > 0 on a box (a :class:`rigor_gyro.core.boxes.Box`) by bisection along its relatively
    widest edge (:meth:`Box.split`). ``f`` maps {name: ball} (each ball containing the box's edge) to a
    ball containing f over the box.

    Guarantee: PROVED only when f > 0 certainly on every leaf, and the leaves are the leaves of a
    bisection tree of ``whole`` (so they cover it); REFUTED only with a witness point (the box's exact
    midpoint) where f <= 0 certainly; INCONCLUSIVE when ``max_pieces`` is exhausted (never a refutation).
    Precision: the current working precision."""
    leaves: list = []
    stack = [whole]
    count = 0
    while stack:
        box = stack.pop()
        count += 1
        v = f(box.balls())
        if certainly_positive(v):
            leaves.append(box)
            continue
        last = count + len(stack) >= max_pieces
        # the midpoint is tried as a counterexample on the first boxes, where the box's enclosure is
        # centred at <= 0, and when the search is about to stop (deeper, a box centred above 0 is most
        # often positive: its point evaluation would be wasted; its children are tried in turn)
        if last or count <= EARLY_MIDPOINTS or not v.mid() > 0:
            mid = box.midpoint()
            vm = f({k: arb(fmpq(q.numerator, q.denominator)) for k, q in mid.items()})
            if certainly_le(vm, 0):
                return BoxPositivity(Status.REFUTED, leaves, witness=mid, witness_value=vm,
                                     reason="f <= 0 at a point (certified)")
        if last:
            return BoxPositivity(Status.INCONCLUSIVE, leaves, stuck=box,
                                 reason=f"undecided after {count} boxes (raise max_pieces or the precision)")
        stack.extend(reversed(box.split(whole)))
    return BoxPositivity(Status.PROVED, leaves, reason=f"f > 0 certified on {len(leaves)} boxes")


@dataclass
class BoxLowerBound:
    """Outcome of :func:`lower_bound_on_box`: ``bound`` (an exact ball) is <= f on every leaf, and the
    leaves tile the box (the leaves of a bisection tree), so inf f over the box >= ``bound``; ``reached``
    says whether it reached the target."""

    bound: arb
    leaves: list
    reached: bool
    boxes: int


class _SmallestFirst:
    """Heap key putting the smallest lower end first (floats, exact comparison on ties; the order only
    chooses which box to refine next: the bound is the minimum over every leaf, whatever the order).
    ``lo`` is the exact lower end, or None for -inf (nothing known: NaN or unbounded below) and +inf
    (nothing asked there); ``key`` is its float."""

    __slots__ = ("key", "lo")

    def __init__(self, v: arb) -> None:
        low = v.lower()
        key = float(low)            # arb prints every infinite ball as [+/- inf]: the float tells the sign
        if key != key or key == float("-inf"):
            self.key, self.lo = float("-inf"), None
        elif key == float("inf"):
            self.key, self.lo = float("inf"), None
        else:
            self.key, self.lo = key, low

    def __lt__(self, other: "_SmallestFirst") -> bool:
        if self.key != other.key or self.lo is None or other.lo is None:
            return self.key < other.key
        return bool(self.lo < other.lo)


def lower_bound_on_box(f: BoxFunction, whole, target: object, *, max_pieces: int = 20000) -> BoxLowerBound:
    """A certified lower bound of inf f over a box (a :class:`rigor_gyro.core.boxes.Box`), raised by
    best-first bisection (the box with the smallest lower end is split along its relatively widest edge)
    until every leaf's lower end is >= ``target`` or ``max_pieces`` boxes were evaluated. ``f`` maps
    {name: ball} (each ball containing the box's edge) to a ball whose lower end is <= f on the box (it
    need only be a lower bound; f may be +inf where nothing is asked).

    Guarantee: ``bound`` = the smallest lower end over the returned leaves, which tile ``whole``; so
    f >= ``bound`` on the whole box, whatever the stopping reason (a budget only leaves the bound lower).
    It never claims an upper bound of inf f. Precision: the current working precision. A NaN lower end
    counts as -inf (``bound`` is then -inf: nothing is certified)."""
    t = ball(target)
    heap: list = []
    count = 0

    def push(box) -> None:
        nonlocal count
        count += 1
        heapq.heappush(heap, (_SmallestFirst(f(box.balls())), count, box))

    push(whole)
    reached = False
    while heap:
        top = heap[0][0]
        if top.key == float("inf") or (top.lo is not None and certainly_le(t, top.lo)):
            reached = True
            break
        if count + 2 > max_pieces:
            break
        key, n, box = heapq.heappop(heap)
        try:
            halves = box.split(whole)
        except ValueError:              # a box of points: nothing left to split
            heapq.heappush(heap, (key, n, box))     # its own tie-breaker back (Boxes do not compare)
            break
        for half in halves:
            push(half)
    bound = arb("inf")
    for key, _, _ in heap:              # the smallest lower end over the leaves, by exact comparison
        if key.key == float("-inf"):
            bound = arb("-inf")
            break
        if key.lo is not None and (not bound.is_finite() or certainly_lt(key.lo, bound)):
            bound = key.lo
    return BoxLowerBound(bound, [item[2] for item in heap], reached, count)


def best_first_bisection(lo: arb, hi: arb, bound: Callable[[arb, arb], arb], refine: Callable[[arb], None],
                         done: Callable[[arb], bool], max_pieces: int, refined: bool = False):
    """Best-first bisection of [lo, hi] (exact ends) for an upper bound of a function's maximum.

    ``bound(a, b)`` is an upper bound (an exact ball, or +inf) over [a, b]; ``refine(mid)`` may add what
    makes the bounds better (a search point at the piece's midpoint): the piece with the largest bound
    is first refined once (unless ``refined``: the whole interval already was), then bisected, until
    ``done(bound)`` holds for the largest bound or ``max_pieces`` bounds were taken.

    Returns ([(a, b, bound), ...], bounds taken): the pieces cover [lo, hi], each with its bound, in heap
    order (the largest first). Guarantee: whatever the stopping reason, the largest of the bounds is an
    upper bound over [lo, hi] (as much as each ``bound`` is one over its piece)."""
    heap: list = []
    count = 0

    def push(a: arb, b: arb, own: bool) -> None:
        nonlocal count
        up = bound(a, b)
        count += 1
        key = -exact_fraction(up) if up.is_finite() else float("-inf")
        heapq.heappush(heap, (key, count, a, b, up, own))

    push(lo, hi, refined)
    while count < max_pieces:
        _, _, a, b, up, own = heap[0]
        if done(up):
            break
        heapq.heappop(heap)
        mid = ((a + b) / 2).mid()
        if not own:
            refine(mid)
            push(a, b, True)
            continue
        if not (certainly_lt(a, mid) and certainly_lt(mid, b)):
            push(a, b, True)
            break
        push(a, mid, False)
        push(mid, b, False)
    return [(item[2], item[3], item[4]) for item in heap], count
