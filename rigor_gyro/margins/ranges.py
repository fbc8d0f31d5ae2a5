"""Certified ranges of a kind's quantities over a tolerance box, worst-case margins and sensitivities.

The numbers an engineer designs with over a box (ibexopt style): for each quantity q of the kind's
``box_quantities`` module (:mod:`rigor_gyro.core.box_values`),

* the **outer range** [L, U]: L <= q(P) <= U for every parameter value P in the box. It is the hull of
  the kind's enclosures of q over sub-boxes (*tiles*) that are the leaves of a bisection tree of the box
  (so they cover it), each tile's ball containing q over the whole tile;
* the **inner range** [a, b]: every value in [a, b] is taken by q somewhere in the box. a is an upper
  bound of q at a certified point P_low and b a lower bound at P_high; q is continuous on the box, so q
  takes every value between q(P_low) and q(P_high). Given only when q was enclosed on every tile and the
  tiles measure one object (:func:`one_branch`: a function of the parameters, or for an object each tile
  chooses, such as the relay's orbit continued from the tile's centre, touching tiles shown to choose the
  same one); otherwise the item says so under ``branches``;
* for a **margin** (a quantity whose sign decides a claim) the **worst case**: min q >= L over the box,
  and q(P_low) <= a, so the minimum is known to within a - L (the gap, also relative to |a|);
* **sensitivities**: for each box parameter k, a ball containing dq/dP_k over the box (the hull of the
  tiles' gradient balls, when the kind gives them), and the effect of k's tolerance, at most
  max |dq/dP_k| times k's half-width; a derivative of certain sign says q is monotone in k on the box.

The search (which tiles to split, which points to evaluate) is a heuristic that spends at most
``range_boxes`` tile evaluations: it splits the tile holding the lowest lower end (and the highest upper
end) of each quantity whose relative gap still exceeds ``range_gap``, and any tile where a quantity was
not enclosed. What it ends with is certified however it chose: :func:`summarise` derives every stated
number from the tiles' and points' enclosures alone, and ``rigor-gyro check`` re-evaluates every stored
tile and point and derives them again.

Exactness: the kind's balls are turned into their exact rational endpoints in the worker
(:func:`~rigor_gyro.core.balls.exact_endpoints`), so hulls and minima are exact rational arithmetic; the
stated decimals round outward (outer range, lower bounds) or inward (inner range) to ``DIGITS``.

Fails when: never for a quantity the kind cannot enclose (it is reported as not enclosed on that part of
the box); the kind's ParameterError propagates.
"""
from __future__ import annotations

import contextlib
import json
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from ..core.balls import exact_endpoints, inward_interval_text, interval_text, working_precision
from ..core.boxes import Box, fraction_text
from ..core.deadline import TimeLimitReached, until
from ..kinds import optional_module
from .models import scene_model

__all__ = ["RANGE_OPTIONS", "quantities_module", "quantity_specs", "range_task", "RangeSearch", "search_ranges", "summarise"]

#: the ranges' options in a scene's [options]: the tile evaluations spent, the relative gap aimed at
RANGE_OPTIONS = {"range_boxes": "64", "range_gap": "1/100"}
#: significant digits of the stated decimals
DIGITS = 10

Interval = tuple[Fraction, Fraction]


def quantities_module(kind: str):
    """The kind's ``box_quantities`` module, or None when it certifies no quantity over a box."""
    return optional_module(kind, "box_quantities")


def quantity_specs(kind: str, points_json: str, options_json: str, mid_json: str) -> dict:
    """The scene's quantities: ``{id: QuantitySpec}`` of the kind's ``BOX_QUANTITIES``, restricted by its
    optional ``quantity_names(model)`` (a quantity the scene does not define, such as a frequency in Hz
    without a scale, is not listed)."""
    mod = quantities_module(kind)
    pick = getattr(mod, "quantity_names", None)
    if pick is None:
        return dict(mod.BOX_QUANTITIES)
    names = set(pick(scene_model(kind, points_json, options_json, mid_json)))
    return {k: v for k, v in mod.BOX_QUANTITIES.items() if k in names}


def point_box(point: dict[str, Fraction]) -> Box:
    return Box(tuple((k, q, q) for k, q in point.items()))


def _interval(x) -> list[str] | None:
    if not x.is_finite():
        return None
    lo, hi = exact_endpoints(x)
    return [fraction_text(lo), fraction_text(hi)]


def range_task(kind: str, points_json: str, options_json: str, mid_json: str, box_json: str, prec: int
               ) -> dict[str, Any]:
    """One tile (or point, a box of zero width): {quantity: {"value": [lo, hi], "gradient": {k: [lo, hi]}}}
    with exact rational ends as text; a quantity missing or unbounded on the tile is left out."""
    model = scene_model(kind, points_json, options_json, mid_json)
    mod = quantities_module(kind)
    box = Box.from_json(json.loads(box_json))
    out: dict[str, Any] = {}
    with working_precision(prec):
        values = mod.quantities_box(model, box, list(quantity_specs(kind, points_json, options_json, mid_json)))
        for q, bv in values.items():
            v = _interval(bv.value)
            if v is None:
                continue
            grad = {k: g for k, g in ((k, _interval(b)) for k, b in sorted(bv.gradient.items())) if g is not None}
            out[q] = {"value": v, "gradient": grad}
            if bv.branch is not None:
                out[q]["branch"] = _branch_json(bv.branch)
    return out


def _branch_json(b) -> dict[str, Any] | None:
    """A :class:`~rigor_gyro.core.box_values.Branch` with exact rational ends as text; None (kept, so that the
    tile is known to measure an object it chose) when a ball of it is not finite: such a tile joins no other."""
    balls = [b.key, b.at_centre, b.unique_in, *b.gradient.values()]
    if not all(x.is_finite() for x in balls):
        return None
    return {"key": _interval(b.key), "unique_in": _interval(b.unique_in), "at_centre": _interval(b.at_centre),
            "centre": {k: fraction_text(v) for k, v in sorted(b.centre.items())},
            "gradient": {k: _interval(g) for k, g in sorted(b.gradient.items())}}


def _pair(v: list[str]) -> Interval:
    return Fraction(v[0]), Fraction(v[1])


@dataclass
class RangeSearch:
    """What :func:`search_ranges` ends with: the tiles with their evaluations, and the points evaluated
    (each a tile's midpoint) with theirs. Everything stated is derived from these by :func:`summarise`."""

    tiles: list[tuple[Box, dict[str, Any]]]
    points: list[tuple[dict[str, Fraction], dict[str, Any]]]
    evaluated: int
    specs: dict = None          # the scene's quantities (:func:`quantity_specs`)


def _gap_open(q: str, tiles, points, gap: Fraction) -> tuple[bool, bool]:
    """Whether the low and the high end of q still need work: not enclosed everywhere, or the distance
    between the certified bound and the best point value above ``gap`` relative to that value."""
    if any(q not in v for _, v in tiles):
        return True, True
    lo = min(_pair(v[q]["value"])[0] for _, v in tiles)
    hi = max(_pair(v[q]["value"])[1] for _, v in tiles)
    pv = [_pair(v[q]["value"]) for _, v in points if q in v]
    if not pv:
        return True, True
    best_lo = min(p[1] for p in pv)
    best_hi = max(p[0] for p in pv)
    scale = max(abs(best_lo), abs(best_hi), Fraction(1, 10 ** 30))
    return best_lo - lo > gap * scale, hi - best_hi > gap * scale


def _corner(box: Box, grad: dict[str, list[str]], end: str, frozen: tuple[str, ...]) -> dict[str, Fraction]:
    """The point of ``box`` where a quantity with these gradient balls is lowest (``end`` "low") or highest:
    the face an edge's certain derivative sign points to, the edge's midpoint where the sign is unknown."""
    out = {}
    for k, lo, hi in box.edges:
        g = grad.get(k)
        sign = 0 if g is None or k in frozen else (1 if Fraction(g[0]) > 0 else -1 if Fraction(g[1]) < 0 else 0)
        if end == "high":
            sign = -sign
        out[k] = lo if sign > 0 else hi if sign < 0 else (lo + hi) / 2
    return out


def search_ranges(kind: str, whole: Box, frozen: tuple[str, ...], pj: str, oj: str, mj: str, prec: int,
                  names: list[str], budget: int, gap: Fraction, executor, clock=None) -> RangeSearch:
    """Tiles and points for the ranges of ``names`` (see the module docstring), at most ``budget`` tile
    evaluations, fewer when ``clock`` (a :class:`~rigor_gyro.core.deadline.Budget`) expires: in process its alarm
    ends a round (dropped: the tiles before it stand) or the first evaluation (TimeLimitReached: no ranges).
    Points: each tile's midpoint, and for the tiles that hold a quantity's extreme end, the corner its
    gradient's signs point to. Deterministic without a clock: the same tiles for every executor."""
    seen: set = set()

    def evaluate(boxes: list[Box], extra: list[dict[str, Fraction]]):
        cand = [b.midpoint() for b in boxes] + extra
        mids = []
        for m in cand:
            key = tuple(sorted(m.items()))
            if key not in seen:
                seen.add(key)
                mids.append(m)
        tasks = [(kind, pj, oj, mj, json.dumps(b.to_json()), prec) for b in boxes]
        tasks += [(kind, pj, oj, mj, json.dumps(point_box(m).to_json()), prec) for m in mids]
        with until(clock) if clock is not None and executor.runs_here(len(tasks)) else contextlib.nullcontext():
            outs = executor.map(range_task, tasks)
        return list(zip(boxes, outs[:len(boxes)])), list(zip(mids, outs[len(boxes):]))

    def corners(items: list[tuple[Box, dict[str, Any]]]) -> list[dict[str, Fraction]]:
        out = []
        for b, v in items:
            for q in names:
                if q in v and v[q]["gradient"]:
                    out += [_corner(b, v[q]["gradient"], end, frozen) for end in ("low", "high")]
        return out

    tiles, points = evaluate([whole], [])
    _, more = evaluate([], corners(tiles))
    points += more
    evaluated = 1
    while evaluated < budget and not (clock is not None and clock.expired()):
        chosen: list[int] = []
        spare: list[int] = []
        for q in names:
            low, high = _gap_open(q, tiles, points, gap)
            enclosed = [i for i, (_, v) in enumerate(tiles) if q in v]
            spare.extend(i for i, (_, v) in enumerate(tiles) if q not in v)
            if not enclosed:
                continue
            if low:
                chosen.append(min(enclosed, key=lambda i: (_pair(tiles[i][1][q]["value"])[0], i)))
            if high:
                chosen.append(max(enclosed, key=lambda i: (_pair(tiles[i][1][q]["value"])[1], -i)))
        chosen = sorted(set(i for i in chosen if not _is_point(tiles[i][0], frozen)))
        room = max(0, (budget - evaluated) // 2)
        if len(chosen) < room:      # then the tiles where a quantity was not enclosed, in order
            chosen += sorted(set(i for i in spare if i not in chosen and not _is_point(tiles[i][0], frozen)))
        chosen = chosen[:room]
        if not chosen:
            break
        children = [c for i in chosen for c in tiles[i][0].split(whole, frozen)]
        try:
            new_tiles, new_points = evaluate(children, [])
            _, more = evaluate([], corners(new_tiles))
        except TimeLimitReached:        # the round is dropped: the tiles so far still tile the box
            if clock is None or not clock.fired:
                raise
            break
        evaluated += len(children)
        gone = set(chosen)
        tiles = [t for i, t in enumerate(tiles) if i not in gone] + new_tiles
        points = points + new_points + more
    return RangeSearch(tiles, points, evaluated, quantity_specs(kind, pj, oj, mj))


def _key_over(branch: dict[str, Any], part: Box) -> Interval:
    """The branch's key over ``part`` (a part of its tile), exactly: at_centre + sum_k gradient_k (P_k - c_k)
    in rational interval arithmetic (mean value theorem on the convex tile), intersected with the key's
    enclosure over the whole tile."""
    lo, hi = _pair(branch["at_centre"])
    for k, g in branch["gradient"].items():
        glo, ghi = _pair(g)
        c = Fraction(branch["centre"][k])
        plo, phi = part.interval(k)
        ends = [x * (p - c) for x in (glo, ghi) for p in (plo, phi)]
        lo, hi = lo + min(ends), hi + max(ends)
    klo, khi = _pair(branch["key"])
    return max(lo, klo), min(hi, khi)


def one_branch(enclosed: list[tuple[Box, dict[str, Any]]]) -> bool:
    """Whether the tiles' values of a quantity measure one object, so that the quantity is one function,
    continuous on the box: true for a function of the parameters (no tile gives a ``branch``); for objects chosen
    per tile, when every two touching tiles are shown to agree on their common part F: one's key over F
    (:func:`_key_over`) lies inside the other's ``unique_in`` (exact rational comparisons). Why: for P in F the
    first tile's key(P) is then a candidate in the second's unique_in, where the second tile's object is the only
    one, so both measure the same object at P. The quantity, continuous on each closed tile and agreeing on every
    overlap, is one continuous function on the union (pasting lemma). A tile without a branch (not located)
    beside tiles with one: false."""
    if not any("branch" in v for _, v in enclosed):
        return True
    branches = [v.get("branch") for _, v in enclosed]
    if not all(branches):
        return False
    boxes = [b for b, _ in enclosed]

    def inside(k: Interval, u: list[str]) -> bool:
        ulo, uhi = _pair(u)
        return ulo <= k[0] and k[1] <= uhi

    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            common = boxes[i].intersection(boxes[j])
            if common is None:
                continue
            if not (inside(_key_over(branches[i], common), branches[j]["unique_in"])
                    or inside(_key_over(branches[j], common), branches[i]["unique_in"])):
                return False
    return True


def _is_point(b: Box, frozen: tuple[str, ...]) -> bool:
    return all(lo == hi for n, lo, hi in b.edges if n not in frozen)


def _text(point: dict[str, Fraction]) -> dict[str, str]:
    return {k: fraction_text(q) for k, q in point.items()}


def summarise(whole: Box, specs: dict, tiles: list[tuple[Box, dict[str, Any]]],
              points: list[tuple[dict[str, Fraction], dict[str, Any]]]) -> list[dict[str, Any]]:
    """The stated ranges, worst cases and sensitivities, derived from the tiles' and points' enclosures
    only (the checker calls this on its own re-evaluations). ``specs``: the kind's BOX_QUANTITIES."""
    total = whole.volume()
    out = []
    for q, spec in specs.items():
        enclosed = [(b, v[q]) for b, v in tiles if q in v]
        covered = sum((b.volume() for b, _ in enclosed), Fraction(0)) / total if total else Fraction(int(bool(enclosed)))
        item: dict[str, Any] = {"id": q, "description": spec.description, "unit": spec.unit}
        if spec.claim is not None:
            item["margin_of"] = spec.claim
        item["enclosed_fraction"] = fraction_text(covered)
        if not enclosed:
            item["outer"] = None
            out.append(item)
            continue
        lo = min(_pair(v["value"])[0] for _, v in enclosed)
        hi = max(_pair(v["value"])[1] for _, v in enclosed)
        l, h, _ = interval_text(lo, hi, DIGITS)
        item["outer"] = {"lo": l, "hi": h}
        joined = one_branch(enclosed)
        if not joined:
            item["branches"] = ("the sub-boxes' objects are not shown to be one (some touching sub-boxes' branches "
                                "not shown to agree): no inner range, no tolerance effects")
        pv = [(p, _pair(v[q]["value"])) for p, v in points if q in v]
        if pv:
            p_low, v_low = min(pv, key=lambda t: (t[1][1], sorted(t[0].items())))
            p_high, v_high = max(pv, key=lambda t: (t[1][0], [(-x) for _, x in sorted(t[0].items())]))
            item["points"] = {"low": {"point": _text(p_low), "value_at_most": interval_text(v_low[1], v_low[1], DIGITS)[1]},
                              "high": {"point": _text(p_high), "value_at_least": interval_text(v_high[0], v_high[0], DIGITS)[0]}}
            if covered == 1 and v_low[1] <= v_high[0] and joined:
                a, b = inward_interval_text(v_low[1], v_high[0], DIGITS)
                item["inner"] = {"lo": a, "hi": b} if Fraction(a) <= Fraction(b) else None
            else:
                item["inner"] = None
            if spec.claim is not None:
                gap = v_low[1] - lo
                rel = gap / abs(v_low[1]) if v_low[1] != 0 else None
                item["worst_case"] = {"lower_bound": l, "attained_at_most": item["points"]["low"]["value_at_most"],
                                      "gap": interval_text(gap, gap, 3)[1],
                                      "relative_gap": None if rel is None else interval_text(rel, rel, 3)[1]}
        grads = {}
        for k in whole.names:
            gs = [_pair(v["gradient"][k]) for _, v in enclosed if k in v.get("gradient", {})]
            if len(gs) == len(enclosed):
                grads[k] = (min(g[0] for g in gs), max(g[1] for g in gs))
        if grads and covered == 1 and joined:
            sens = []
            for k, (glo, ghi) in grads.items():
                klo, khi = whole.interval(k)
                effect = max(abs(glo), abs(ghi)) * (khi - klo) / 2
                gl, gh, _ = interval_text(glo, ghi, 6)
                sens.append((effect, k, {"parameter": k, "derivative": {"lo": gl, "hi": gh},
                                         "monotone": "increasing" if glo > 0 else "decreasing" if ghi < 0 else None,
                                         "effect_at_most": interval_text(effect, effect, 3)[1]}))
            item["sensitivities"] = [s for _, _, s in sorted(sens, key=lambda t: (-t[0], t[1]))]
        out.append(item)
    return out


def tiles_json(tiles: list[tuple[Box, dict[str, Any]]]) -> list[dict[str, Any]]:
    return [b.to_json() for b, _ in tiles]
