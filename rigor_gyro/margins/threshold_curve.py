"""Threshold curves: a certified band in the plane of two parameters (``rigor-gyro margin --along``).

Where a claim's threshold in one parameter (``param``, say eps) moves with another (``along``, say Omega2), the
curve eps_c(Omega2) is bracketed cell by cell. The range of ``along`` is cut into cells [w, w']; in each cell
the claim is decided over the cell by a paving (:func:`rigor_gyro.margins.paving.pave`, ``along`` a tolerance,
the scene's other tolerances too) at exact values of ``param``:

* **proved at a** on a cell: the claim holds at param = a for every ``along`` in the cell (every leaf proved);
* **refuted at b** on a cell: it fails at param = b for every ``along`` in the cell (every leaf refuted: the box
  rigour's certified inequality over the leaf, never a search result).

Between a proved value and a refuted one the cell's search bisects at exact rational midpoints. A midpoint
where the claim is neither (it holds for some ``along`` of the cell and fails for others, or the paving cannot
tell) cannot narrow the band at this cell width: the cell is split in two (continuation along the boundary),
each half starting from its parent's two values (a value proved, or refuted, over the parent holds over each
half, so no proof is repeated), down to ``max_depth`` halvings, breadth first (so a search out of time still
covers the whole range). A cell's band [min(a, b), max(a, b)] then says:
for every ``along`` in the cell the claim is proved at a and refuted at b, so its outcome changes between them
(not necessarily once). The first cell's ends come from ``--lo``/``--hi``; each next cell starts from the band
of the cell before it, widened until its ends decide (falling back to ``--lo``/``--hi``).

Exit status: 0 every cell bracketed to the requested relative width; 3 some cell stopped wider (mixed at the
finest cell, inconclusive, or out of time) or without a bracket: never 1 (a search is not a refutation); 2 bad
input. The checker (:func:`check_curve`) re-paves every cell at its two stored values and checks that the
cells tile the ``along`` range.
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from ..core.balls import interval_text, rational_text
from ..core.boxes import fraction_text, is_tolerance
from ..core.deadline import Budget, check_time_limit
from ..core.errors import ParameterError, RigorGyroError
from ..core.exact import option_count, option_number
from ..scene import Scene
from .threshold import search_range

__all__ = ["Cell", "Curve", "find_curve", "write_curve", "check_curve", "cell_status", "SCHEMA"]

SCHEMA = "rigor-gyro/threshold-curve/1"
#: bisection steps per cell at most
CELL_STEPS = 60
#: the paving options of a cell's decision (over the scene's own)
CELL_OPTIONS = {"range_boxes": "0", "max_points": "0", "search_points": "0", "monte_carlo": "0"}
#: where a cell's search tries after a mixed midpoint, before splitting the cell (fractions of the way from
#: the proved value to the refuted one)
AROUND = (Fraction(1, 4), Fraction(3, 4))


@dataclass
class Cell:
    along: tuple[Fraction, Fraction]
    depth: int
    proved_at: Fraction | None = None
    refuted_at: Fraction | None = None
    proofs: int = 0
    stopped: str = ""

    def band(self) -> tuple[Fraction, Fraction] | None:
        if self.proved_at is None or self.refuted_at is None:
            return None
        return min(self.proved_at, self.refuted_at), max(self.proved_at, self.refuted_at)

    def to_json(self) -> dict[str, Any]:
        b = self.band()
        return {"along": [fraction_text(x) for x in self.along], "proved_at": _ft(self.proved_at),
                "refuted_at": _ft(self.refuted_at), "band": [fraction_text(x) for x in b] if b else None,
                "band_decimal": list(interval_text(*b)[:2]) if b else None, "proofs": self.proofs,
                "stopped": self.stopped}


def _ft(x: Fraction | None) -> str | None:
    return None if x is None else fraction_text(x)


@dataclass
class Curve:
    scene: Scene
    param: str
    along: str
    claim: str
    lo: Fraction
    hi: Fraction
    along_lo: Fraction
    along_hi: Fraction
    width: Fraction
    cells: list[Cell] = field(default_factory=list)
    stopped: str = ""

    def _narrow(self, c: Cell) -> bool:
        b = c.band()
        return b is not None and b[1] - b[0] <= self.width * max(abs(b[0]), abs(b[1]))

    @property
    def certified(self) -> bool:
        return bool(self.cells) and not self.stopped and all(self._narrow(c) for c in self.cells)

    @property
    def exit_code(self) -> int:
        return 0 if self.certified else 3

    def lines(self) -> list[str]:
        head = (f"{self.scene.name}: threshold of {self.claim!r} in {self.param} along {self.along} in "
                f"[{rational_text(self.along_lo)}, {rational_text(self.along_hi)}]")
        out = [f"{head}: {sum(c.band() is not None for c in self.cells)} of {len(self.cells)} cells bracketed, "
               f"{sum(self._narrow(c) for c in self.cells)} to the relative width {rational_text(self.width)}"]
        for c in self.cells:
            b = c.band()
            where = f"{self.along} in [{rational_text(c.along[0])}, {rational_text(c.along[1])}]"
            if b is None:
                out.append(f"  {where}: no band ({c.stopped})")
            else:
                lo, hi, rounded = interval_text(*b)
                out.append(f"  {where}: the outcome changes in {self.param} in [{lo}, {hi}]"
                           f"{' (rounded outward)' if rounded else ''}" + (f" ({c.stopped})" if c.stopped else ""))
        return out + ([f"{head}: stopped: {self.stopped}"] if self.stopped else [])

    def to_json(self) -> dict[str, Any]:
        return {"schema": SCHEMA, "scene": self.scene.header(), "param": self.param, "along": self.along,
                "claim": self.claim, "search": [fraction_text(self.lo), fraction_text(self.hi)],
                "along_range": [fraction_text(self.along_lo), fraction_text(self.along_hi)],
                "requested_relative_width": fraction_text(self.width), "certified": self.certified,
                "statement": statement(self.claim, self.param, self.along),
                "cells": [c.to_json() for c in self.cells], "stopped": self.stopped}


def statement(claim: str, param: str, along: str) -> str:
    return (f"for each cell and every {along} in it (and every point of the scene's other tolerances), claim "
            f"{claim!r} holds at {param} = proved_at and fails at {param} = refuted_at (pavings of the cell), so "
            f"its outcome changes in {param} within the cell's band")


def cell_status(scene: Scene, param: str, value: Fraction, along: str, cell: tuple[Fraction, Fraction],
                claim: str, seconds: float | None = None) -> tuple[str, str]:
    """("proved" | "refuted" | "mixed" | "inconclusive", reason) of ``claim`` at ``param = value`` over the cell
    (``along`` in it): proved and refuted mean at every point of the cell (module docstring)."""
    from .paving import box_scene, pave
    params = {**scene.parameters, param: fraction_text(value),
              along: f"[{fraction_text(cell[0])}, {fraction_text(cell[1])}]"}
    # the leaves' statuses are all a cell needs: no quantity ranges, no point proofs, no search
    opts = {**scene.options, **CELL_OPTIONS}
    s = Scene(name=scene.name, kind=scene.kind, source=scene.source, parameters=params, claims_only=[claim],
              options=opts, model=dict(scene.model))
    p = pave(box_scene(s), time_limit=seconds)
    c = p.claims[0]
    kinds = {st for _, st in c.boxes}
    if p.stopped or not c.boxes:
        return "inconclusive", p.stopped or "no leaf"
    if kinds == {"proved"}:
        return "proved", f"proved on all {len(c.boxes)} leaves"
    if kinds == {"refuted"}:
        return "refuted", f"refuted on all {len(c.boxes)} leaves"
    if "proved" in kinds and "refuted" in kinds:
        return "mixed", "proved on part of the cell, refuted on another"
    return "inconclusive", f"leaves {sorted(kinds)}"


def _search_cell(curve: Curve, cell: Cell, budget: Budget) -> bool:
    """Bisect the cell's band; True when it ended on a mixed (or undecided) value wider than the width (the
    caller may split the cell)."""
    p, r = cell.proved_at, cell.refuted_at
    for _ in range(CELL_STEPS):
        if curve._narrow(cell):
            return False
        if budget.expired():
            cell.stopped = budget.reason()
            return False
        moved = False
        for t in (Fraction(1, 2),) + AROUND:
            x = p + (r - p) * t
            if budget.expired():
                break
            st, why = cell_status(curve.scene, curve.param, x, curve.along, cell.along, curve.claim, budget.remaining())
            cell.proofs += 1
            if st == "proved":
                p, moved = x, True
            elif st == "refuted":
                r, moved = x, True
            if moved:
                break
        cell.proved_at, cell.refuted_at = p, r
        if not moved:
            cell.stopped = f"neither proved nor refuted over the whole cell at {curve.param} = {rational_text(p + (r - p) / 2)}"
            return True
    cell.stopped = f"{CELL_STEPS} bisection steps"
    return False


def _ends(curve: Curve, cell: Cell, guess: tuple[Fraction, Fraction] | None, budget: Budget) -> None:
    """The cell's first proved and refuted values: from the previous band widened (continuation), else the
    search range's ends."""
    tries = []
    if guess is not None:
        lo, hi = guess
        gap = max(hi - lo, (curve.hi - curve.lo) / 2 ** 20)
        for k in (1, 4, 16):
            tries.append((max(curve.lo, lo - k * gap), min(curve.hi, hi + k * gap)))
    tries.append((curve.lo, curve.hi))
    for lo, hi in tries:
        got = {}
        for x in (lo, hi):
            if budget.expired():
                cell.stopped = budget.reason()
                return
            got[x], _ = cell_status(curve.scene, curve.param, x, curve.along, cell.along, curve.claim,
                                    budget.remaining())
            cell.proofs += 1
        if {got[lo], got[hi]} == {"proved", "refuted"}:
            cell.proved_at, cell.refuted_at = (lo, hi) if got[lo] == "proved" else (hi, lo)
            return
    cell.stopped = ("the claim is not proved over the cell at one end of the search and refuted over it at the "
                    "other: widen --lo/--hi, or use more --cells")


def find_curve(scene: Scene, param: str, along: str, *, lo: str | None, hi: str | None, along_lo: str,
               along_hi: str, claim: str, cells: int = 8, width: str = "1e-3", max_depth: int = 4,
               time_limit: float | None = None) -> Curve:
    """The threshold curve of ``claim`` in ``param`` along ``along`` (module docstring)."""
    try:
        budget = Budget(check_time_limit(time_limit, "time_limit"))
    except ValueError as e:
        raise ParameterError(str(e)) from None
    for name, flag in ((param, "--param"), (along, "--along")):
        if name not in scene.parameters:
            raise ParameterError(f"{flag} {name!r} is not a parameter of scene {scene.name!r}; it has {sorted(scene.parameters)}")
        if is_tolerance(scene.parameters[name]):
            raise ParameterError(f"{flag} {name!r} is written as a tolerance: write it as a number")
    if param == along:
        raise ParameterError("--along must name another parameter than --param")
    from ..kinds import kind_module, scene_claims
    module = kind_module(scene.kind)
    every = scene_claims(module, scene)[1]              # a [system] scene's own claims, not the paper kind's
    if claim not in every:
        raise ParameterError(f"--claim {claim!r}: scene {scene.name!r} has {list(every)}")
    lo_q, hi_q = search_range(scene, param, lo, hi)
    a_lo, a_hi = search_range(scene, along, along_lo, along_hi)
    n = option_count(str(cells), "--cells", 1, 256)
    depth = option_count(str(max_depth), "--max-depth", 0, 12)
    w = option_number(width, "--width", above="0", at_most="1").rational
    curve = Curve(scene, param, along, claim, lo_q, hi_q, a_lo, a_hi, w)
    queue = [Cell((a_lo + (a_hi - a_lo) * i / n, a_lo + (a_hi - a_lo) * (i + 1) / n), 0) for i in range(n)]
    guess = None
    while queue:
        cell = queue.pop(0)
        if cell.proved_at is None:
            _ends(curve, cell, guess, budget)
            if cell.band() is None:
                curve.cells.append(cell)
                continue
        mixed = _search_cell(curve, cell, budget)
        if mixed and cell.depth < depth and not budget.expired():
            mid = (cell.along[0] + cell.along[1]) / 2
            kids = [Cell((cell.along[0], mid), cell.depth + 1, cell.proved_at, cell.refuted_at, 0),
                    Cell((mid, cell.along[1]), cell.depth + 1, cell.proved_at, cell.refuted_at, 0)]
            queue.extend(kids)          # breadth first: the whole range narrows level by level (anytime)
            continue
        curve.cells.append(cell)
        if cell.depth == 0:
            guess = cell.band() or guess
        if budget.expired():
            curve.stopped = f"{budget.reason()}: the cells bracketed so far are kept"
            for c in queue:
                c.stopped = c.stopped or "not searched: out of time (the band is its parent cell's)"
            curve.cells.extend(queue)
            break
    curve.cells.sort(key=lambda c: c.along)
    return curve


def write_curve(res: Curve, out_dir: str) -> list[Path]:
    from ..report import write_pair
    md = "\n".join([f"# {res.lines()[0]}", "", f"| {res.along} from | to | {res.param} band | proofs | note |",
                    "|---|---|---|---|---|"]
                   + [f"| {rational_text(c.along[0])} | {rational_text(c.along[1])} | "
                      f"{'[' + ', '.join(interval_text(*c.band())[:2]) + ']' if c.band() else '-'} | {c.proofs} | "
                      f"{c.stopped or ''} |" for c in res.cells] + [""])
    return list(write_pair(out_dir, f"curve_{res.scene.name}_{res.param}_{res.along}",
                           json.dumps(res.to_json(), indent=1) + "\n", md, None))


def _dyadic_between(x: Fraction, lo: Fraction, hi: Fraction) -> bool:
    """Whether x = lo + (hi - lo) t with t in [0, 1] a dyadic rational (what bisections from lo and hi reach)."""
    t = (x - lo) / (hi - lo)
    return 0 <= t <= 1 and t.denominator & (t.denominator - 1) == 0


def check_curve(data: dict[str, Any]) -> list[tuple[str, bool, str]]:
    """Re-verify a threshold curve (schema ``rigor-gyro/threshold-curve/1``, already validated) as (item, ok,
    message) triples: the scene, parameters and claim valid; the statement re-derived; the cells tile the
    ``along`` range in order; each cell's band, decimals re-derived from its stored values; each stored value
    re-paved over its cell (proved at proved_at, refuted at refuted_at, every leaf); ``certified`` re-derived.
    The search range: every stored value inside it, and the first cell's (searched from the range's two ends,
    no earlier band to start from) reached from them by bisection (lo + (hi - lo) t, t dyadic). Each ``stopped``
    is a text the search writes there: none on a cell bracketed to the width; a cell left mixed names its
    band's midpoint, where it and the points around it are re-paved neither proved nor refuted over the cell;
    a cell with no band says the search ends do not decide it, re-paved so (these two re-pavings are skipped
    when the time limit stopped the run: a paving cut short is inconclusive). Not re-run: the bisections, so
    ``proofs`` (how many pavings the search ran) is not checked (the file does not record ``--cells`` and
    ``--max-depth``, which the search needs)."""
    out: list[tuple[str, bool, str]] = []

    def add(item: str, ok: bool, message: str) -> None:
        out.append((item, bool(ok), message))

    try:
        scene = Scene.from_header(data["scene"])
        param, along, claim = data["param"], data["along"], data["claim"]
        from ..kinds import kind_module
        if claim not in kind_module(scene.kind).CLAIMS or param == along:
            raise ParameterError("claim or parameters not valid")
        for name in (param, along):
            if name not in scene.parameters or is_tolerance(scene.parameters[name]):
                raise ParameterError(f"{name!r} is not a number parameter of the scene")
    except (RigorGyroError, TypeError, ValueError, KeyError) as e:
        add("scene", False, f"the curve's scene, parameters or claim are not valid: {e}")
        return out
    from .identity import builtin_differs
    differs = builtin_differs(data["scene"])
    add("scene", differs is None, differs or f"scene {scene.name!r}, {param!r} along {along!r}, claim {claim!r}")
    add("statement", data["statement"] == statement(claim, param, along), "the curve's statement re-derived")
    a_lo, a_hi = (Fraction(t) for t in data["along_range"])
    lo_s, hi_s = (Fraction(t) for t in data["search"])
    w = Fraction(data["requested_relative_width"])
    cells = data["cells"]
    ends = [(Fraction(c["along"][0]), Fraction(c["along"][1])) for c in cells]
    tiled = (bool(ends) and ends[0][0] == a_lo and ends[-1][1] == a_hi and all(x < y for x, y in ends)
             and all(ends[i][1] == ends[i + 1][0] for i in range(len(ends) - 1)))
    add("cells", tiled, f"{len(cells)} cells tile [{rational_text(a_lo)}, {rational_text(a_hi)}] in order")
    values = [Fraction(c[k]) for c in cells for k in ("proved_at", "refuted_at") if c[k] is not None]
    first = [Fraction(cells[0][k]) for k in ("proved_at", "refuted_at") if cells and cells[0][k] is not None]
    ok = (lo_s < hi_s and 0 < w <= 1 and all(lo_s <= x <= hi_s for x in values)
          and all(_dyadic_between(x, lo_s, hi_s) for x in first))
    add("search", ok, f"search [{rational_text(lo_s)}, {rational_text(hi_s)}]: every value inside it, the first "
        "cell's reached from its ends by bisection" if ok else f"the search range [{rational_text(lo_s)}, "
        f"{rational_text(hi_s)}] is not the one the cells' values were searched in")
    limit = r"time limit of \S+ s reached \(--time-limit\)"
    timed = bool(data["stopped"]) or any(re.fullmatch(limit, str(c["stopped"])) for c in cells)
    stop_ok = data["stopped"] == "" or bool(re.fullmatch(limit + re.escape(": the cells bracketed so far are kept"),
                                                         str(data["stopped"])))
    add("stopped", stop_ok, "the curve's 'stopped' a text the search writes" if stop_ok else
        f"'stopped' {str(data['stopped'])[:120]!r} is not a text the search writes")
    narrow_all = bool(cells)
    for c, cell in zip(cells, ends):
        where = f"{along} in [{rational_text(cell[0])}, {rational_text(cell[1])}]"
        p, r = c["proved_at"], c["refuted_at"]
        if p is None or r is None:
            narrow_all = False
            add(where, c["band"] is None and c["band_decimal"] is None, "no band stated")
            _check_cell_stop(add, scene, param, along, claim, c, cell, None, w, timed, data["stopped"], lo_s, hi_s)
            continue
        p, r = Fraction(p), Fraction(r)
        lo, hi = min(p, r), max(p, r)
        add(f"{where} band", p != r and c["band"] == [fraction_text(lo), fraction_text(hi)]
            and c["band_decimal"] == list(interval_text(lo, hi)[:2]), "the band re-derived from its two values")
        narrow_all = narrow_all and hi - lo <= w * max(abs(lo), abs(hi))
        for x, want in ((p, "proved"), (r, "refuted")):
            st, why = cell_status(scene, param, x, along, cell, claim)
            add(f"{where} {want}_at", st == want, f"{param} = {rational_text(x)}: re-paved {st} over the cell"
                + ("" if st == want else f" ({why[:160]})"))
        _check_cell_stop(add, scene, param, along, claim, c, cell, (p, r), w, timed, data["stopped"], lo_s, hi_s)
    add("certified", data["certified"] == (narrow_all and tiled and not data["stopped"]),
        f"certified {data['certified']}")
    return out


def _check_cell_stop(add, scene: Scene, param: str, along: str, claim: str, c: dict[str, Any],
                     cell: tuple[Fraction, Fraction], pr: tuple[Fraction, Fraction] | None, w: Fraction, timed: bool,
                     curve_stopped: str, lo: Fraction, hi: Fraction) -> None:
    """A cell's ``stopped``: a text the search writes for a cell in this state (see :func:`check_curve`)."""
    where = f"{along} in [{rational_text(cell[0])}, {rational_text(cell[1])}] stopped"
    text = c["stopped"]
    limit = r"time limit of \S+ s reached \(--time-limit\)"
    unsearched = "not searched: out of time (the band is its parent cell's)"
    if isinstance(text, str) and (re.fullmatch(limit, text) or text == unsearched and curve_stopped):
        add(where, True, "stopped by the time limit")
        return
    if pr is None:
        ok = text == ("the claim is not proved over the cell at one end of the search and refuted over it at the "
                      "other: widen --lo/--hi, or use more --cells")
        if ok and not timed:
            got = {cell_status(scene, param, x, along, cell, claim)[0] for x in (lo, hi)}
            ok = got != {"proved", "refuted"}
        add(where, ok, "no band: the search's ends re-paved, not one proved and one refuted over the cell" if ok else
            f"no band, and 'stopped' {str(text)[:120]!r} is not what the search finds at its ends over the cell")
        return
    p, r = pr
    narrow = abs(r - p) <= w * max(abs(p), abs(r))
    if narrow:
        add(where, text == "", "bracketed to the width: nothing stopped it" if text == "" else
            f"a cell bracketed to the requested width with 'stopped' {str(text)[:120]!r}: the search writes none")
        return
    if text == f"{CELL_STEPS} bisection steps":
        add(where, True, text)
        return
    ok = text == f"neither proved nor refuted over the whole cell at {param} = {rational_text(p + (r - p) / 2)}"
    if ok and not timed:
        for t in (Fraction(1, 2),) + AROUND:
            st, _ = cell_status(scene, param, p + (r - p) * t, along, cell, claim)
            if st in ("proved", "refuted"):
                ok = False
                break
    add(where, ok, "left mixed: the band's midpoint and the points around it re-paved, none proved or refuted over "
        "the cell" if ok else f"a band wider than the width with 'stopped' {str(text)[:120]!r}, not what the search "
        "finds there")
