"""Parametric enclosures of a function over a box of exact parameters: the centred (mean-value) form with
derivatives by forward-mode AD in balls (:mod:`.dual_balls`), and the exact extremes of a function that is
monotone in some parameters (decided on the relevant face).

For f of parameters P in a box B (exact rational edges), :func:`enclose` evaluates f on Duals over B (value
and gradient balls G_k over all of B) and at the box's exact midpoint P0, and returns

    f(B) contained in  f_naive(B)  intersected with  f(P0) + sum_k G_k (B_k - P0_k),

the mean-value theorem along the segment from P0 to P (B is convex; f is C^1 on B where every G_k is
finite, see :mod:`.dual_balls`). The centred part is second order in the box width where the naive part
is first order.

:func:`extreme` encloses min f (or max f) over B: where G_k certainly has one sign on B, f is monotone in
p_k on B, so the minimum lies on the face p_k = lo_k (increasing) or hi_k (decreasing), exactly; the face
is a smaller box on which the gradients are enclosed again, and so on. When every parameter is fixed the
face is an exact point and the extreme is f at that point (a ball as narrow as the precision). The result
is a ball containing the extreme itself (its lower end bounds min f from below, its upper end is at least
min f, which f attains on the face), with the faces chosen.

:func:`sign_over_box` decides a sign condition f > 0 (or f >= 0) on a box with these: ``positive`` when
the enclosed minimum is certainly > 0 (>= 0), ``negative`` when the enclosed maximum is certainly < 0, and
says how in its text.

Guarantee: as above, for a caller's ``f`` that is an enclosure on Duals in the sense of
:mod:`.dual_balls` (it returns None where it cannot enclose; an exception from an enclosure that is not
differentiable on the box (:class:`~.dual_balls.NotDifferentiable`), or any other ArithmeticError, is taken
as None). Precision: the
current working precision. Fails when: f returns None or a non-finite value on the box: :func:`enclose`
returns None and :func:`extreme` / :func:`sign_over_box` say undecided (never a wrong sign).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable

from flint import arb, fmpq

from .balls import certainly_gt, certainly_le, certainly_lt
from .boxes import Box
from .dual_balls import Dual, constant, gradient_finite, variable

__all__ = ["Enclosure", "Extreme", "enclose", "extreme", "refined_extreme", "sign_over_box", "point_box", "exact_ball"]

#: f(params) -> Dual or None: params maps each parameter name to a Dual over its edge (constants on
#: degenerate edges)
BoxFunction = Callable[[dict], "Dual | None"]


def exact_ball(q: Fraction) -> arb:
    return arb(fmpq(q.numerator, q.denominator))


def point_box(point: dict[str, Fraction]) -> Box:
    return Box(tuple((k, Fraction(v), Fraction(v)) for k, v in point.items()))


def _duals(box: Box) -> dict[str, Dual]:
    return {k: (variable(k, box.ball(k)) if hi > lo else constant(exact_ball(lo))) for k, lo, hi in box.edges}


def _call(f: BoxFunction, params: dict) -> Dual | None:
    try:
        out = f(params)
    except ArithmeticError:      # NotDifferentiable, a formula's own "no real value", division by zero
        return None
    if out is None or not isinstance(out, Dual) or not out.value.is_finite():
        return None
    return out


@dataclass(frozen=True)
class Enclosure:
    """``value`` contains f(P) for every P in the box; ``gradient`` maps each non-degenerate edge to a ball
    containing df/dp over the box (empty when the gradient was not finite)."""

    value: arb
    gradient: dict[str, arb] = field(default_factory=dict)


def enclose(f: BoxFunction, box: Box) -> Enclosure | None:
    """f over the box: naive Dual value intersected with the centred form (see the module docstring)."""
    D = _call(f, _duals(box))
    if D is None:
        return None
    wide = [k for k, lo, hi in box.edges if hi > lo]
    if not wide:
        return Enclosure(D.value, {})
    if not gradient_finite(D):
        return Enclosure(D.value, {})
    mid = box.midpoint()
    D0 = _call(f, {k: constant(exact_ball(v)) for k, v in mid.items()})
    value = D.value
    if D0 is not None:
        centred = D0.value
        for k in wide:
            g = D.grad.get(k)
            if g is not None:
                centred = centred + g * (box.ball(k) - exact_ball(mid[k]))
        if centred.is_finite():
            value = value.intersection(centred) if value.overlaps(centred) else centred
    return Enclosure(value, {k: D.grad.get(k, arb(0)) for k in wide})


@dataclass(frozen=True)
class Extreme:
    """``value`` contains min f (or max f) over the box; ``faces`` the parameters fixed by monotonicity
    (name -> ("lo" or "hi", the exact end)), ``signs`` the certified sign of df/dp for each of them."""

    value: arb
    faces: dict[str, tuple[str, Fraction]]
    signs: dict[str, int]
    free: tuple[str, ...] = ()

    def text(self, side: int) -> str:
        what = "min" if side < 0 else "max"
        if not self.faces:
            return f"{what} by the centred form"
        fixed = ", ".join(f"{k} = {end}" for k, (end, _) in self.faces.items())
        signs = ", ".join(f"d/d{k} {'>' if self.signs[k] > 0 else '<'} 0" for k in self.faces)
        if self.free:
            return f"{what} on the face {fixed} (monotone: {signs}), over {', '.join(self.free)} by the centred form"
        return f"{what} at the corner {fixed} (monotone: {signs}), exactly"


def extreme(f: BoxFunction, box: Box, side: int, first: Enclosure | None = None,
            enough: Callable[[arb], bool] | None = None) -> Extreme | None:
    """A ball containing min_B f (side -1) or max_B f (side +1), deciding the monotone parameters at faces.
    ``first``: f's enclosure on the whole box if already computed. ``enough``: stop fixing faces once the
    current face's enclosure satisfies it (that enclosure still contains the extreme: the extreme over the
    box is attained on the face)."""
    faces: dict[str, tuple[str, Fraction]] = {}
    signs: dict[str, int] = {}
    cur = box
    enc = first
    for _ in range(len(box.edges) + 1):
        if enc is None:
            enc = enclose(f, cur)
        if enc is None:
            return None
        signed = {}
        for k, g in enc.gradient.items():
            if certainly_gt(g, 0):
                signed[k] = 1
            elif certainly_lt(g, 0):
                signed[k] = -1
        if not signed or (enough is not None and enough(enc.value)):
            break
        edges = []
        for k, lo, hi in cur.edges:
            if k in signed:
                at_lo = signed[k] * side < 0
                end = lo if at_lo else hi
                faces[k], signs[k] = ("lo" if at_lo else "hi", end), signed[k]
                edges.append((k, end, end))
            else:
                edges.append((k, lo, hi))
        cur = Box(tuple(edges))
        enc = None
    return Extreme(enc.value, faces, signs, tuple(k for k, lo, hi in cur.edges if hi > lo))


def refined_extreme(f: BoxFunction, box: Box, side: int, budget: int = 8) -> arb | None:
    """A ball containing min_B f (side -1) or max_B f (+1), narrowed by bisection: the leaf whose extreme is
    the worst (lowest lower end for a minimum) and still has edges not fixed by monotonicity is halved along
    its relatively widest such edge, ``budget`` times at most. The extreme over the box is the extreme over
    the leaves (they tile it), so it lies between the best and the worst of the leaves' balls' ends:
    [min of lower ends, min of upper ends] for a minimum. None when some leaf is not enclosed."""
    first = extreme(f, box, side)
    if first is None:
        return None
    leaves = [(first, box)]

    def worse(u: arb, v: arb) -> bool:      # u's end is further out than v's (exact ends compared exactly)
        return bool(u.lower() < v.lower()) if side < 0 else bool(u.upper() > v.upper())
    for _ in range(budget):
        pick = None
        for i, (ex, b) in enumerate(leaves):
            if ex.free and (pick is None or worse(ex.value, leaves[pick][0].value)):
                pick = i
        if pick is None:
            break
        ex, b = leaves[pick]
        widths = {k: (hi - lo) / (box.interval(k)[1] - box.interval(k)[0]) for k, lo, hi in b.edges if k in ex.free}
        cut = max(widths, key=lambda k: widths[k])
        halves = []
        for part in (0, 1):
            edges = []
            for k, lo, hi in b.edges:
                if k == cut:
                    m = (lo + hi) / 2
                    lo, hi = (lo, m) if part == 0 else (m, hi)
                edges.append((k, lo, hi))
            child = Box(tuple(edges))
            cx = extreme(f, child, side)
            if cx is None:
                return None
            halves.append((cx, child))
        leaves[pick:pick + 1] = halves
    lows = [ex.value.lower() for ex, _ in leaves]
    highs = [ex.value.upper() for ex, _ in leaves]
    if side < 0:
        lo, hi = lows[0], highs[0]
        for a, b in zip(lows[1:], highs[1:]):
            lo, hi = lo.min(a), hi.min(b)
    else:
        lo, hi = lows[0], highs[0]
        for a, b in zip(lows[1:], highs[1:]):
            lo, hi = lo.max(a), hi.max(b)
    return lo.union(hi)


def sign_over_box(f: BoxFunction, box: Box, strict: bool = True) -> tuple[str, str, Extreme | None, Extreme | None]:
    """('positive' | 'negative' | 'undecided', how, min extreme, max extreme) for the condition f > 0
    (``strict``) or f >= 0 on every point of the box: positive when min f is certainly > 0 (>= 0),
    negative when max f is certainly < 0 (then the condition fails at every point of the box). The side
    the whole box's enclosure leans to is tried first; an extreme not computed is None."""
    def pos(v: arb) -> bool:
        return certainly_gt(v, 0) if strict else certainly_le(0, v)

    def neg(v: arb) -> bool:
        return certainly_lt(v, 0)

    enc = enclose(f, box)
    if enc is None:
        return "undecided", "not enclosed on this box", None, None
    lo = hi = None
    sides = (-1, 1) if enc.value.mid() >= 0 else (1, -1)
    for side in sides:
        ex = extreme(f, box, side, enc, pos if side < 0 else neg)
        if ex is None:
            continue
        if side < 0:
            lo = ex
            if pos(ex.value):
                return "positive", f"{ex.text(-1)} > 0", lo, hi
        else:
            hi = ex
            if neg(ex.value):
                return "negative", f"{ex.text(+1)} < 0", lo, hi
    return "undecided", "the enclosure of its range contains 0", lo, hi
