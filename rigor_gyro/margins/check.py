"""Re-verify a paving certificate (schema ``rigor-gyro/paving/1``) from its own data.

Checked: the digest; the scene re-validated as a box scene (domain on the whole box, the claims, the
settings); per claim, that the stored sub-boxes are exactly the leaves of a bisection tree of the
whole box under the paving's split rule (so they tile it: no gap, no overlap), the volume fractions
recomputed exactly (with the decimals and sub-box counts the report prints), every proved and refuted
sub-box re-evaluated on its own balls with the kind's box rigour at the stored precision, every stored
point proof re-run by the point prover, the claims not decided over boxes re-derived, and the claim's
status and the verdict re-derived by the rules of :mod:`.paving`. An undecided sub-box claims nothing.
The texts the report prints are re-derived too: the point parameters (the scene's values of the
parameters without tolerances), each claim's reasons (the first sub-box of each status in the order
pave evaluates: the whole box, then the stored leaves; or the time limit that stopped it), and each
point proof's whole record (status, reason, precision).
A paving that stopped early (a budget, Ctrl-C: ``stopped``) lists its ``pending`` boxes: each group is
the whole box or the two halves of a split, and each of its boxes is an undecided sub-box of every claim
it lists (a pending box claims nothing); a claim with pending boxes gives the stop as its undecided
reason. ``prove --resume`` runs these checks before it continues a paving (:mod:`.resume`).
A second path beside the box rigour: decided sub-boxes are cross-checked by the point prover at their
midpoints and extreme corners (:mod:`.sampled`: a spread of ``samples`` of them per claim); a point
verdict that contradicts its sub-box fails the check.
The run's counters of a paving that ran its course (boxes evaluated, levels, the budget flag) are
re-derived from its sub-boxes (:func:`_check_counters`); a paving that stopped early must say so in a
text pave writes, with nothing pave runs after the last box (:func:`_check_stopped`). A counterexample
search's settings, undecided-leaf count and probes, and a Monte Carlo estimate's settings, are the scene's.
Not checked: the settings chosen on the command line (``point_prec``, ``point_maxprec``, ``priority``:
range-checked only; the point proofs are re-run at the stored precisions).

Cost: one box evaluation per decided sub-box and one of the whole box (no search, no splitting), one
point proof per stored point, and up to 3 ``samples`` point proofs per claim.
"""
from __future__ import annotations

import json
import re
from fractions import Fraction
from typing import Any

from ..certificate import digest
from ..core.balls import MAX_PREC, MIN_PREC
from ..core.boxes import Box, fraction_text, tiles_by_bisection
from ..core.errors import RigorGyroError
from ..scene import Scene
from .models import settings_json
from .sampled import SAMPLED_BOXES, cross_check

__all__ = ["check_paving"]


def _tiles(whole: Box, boxes: list[Box], frozen: tuple[str, ...] = ()) -> bool:
    """Whether ``boxes`` are exactly the leaves of a bisection tree of ``whole`` (Box.split's rule)."""
    return tiles_by_bisection(whole, boxes, frozen)


def CheckResult(item: str, ok: bool, message: str) -> tuple[str, bool, str]:
    """A check as a plain triple (rigor_gyro.check turns it into its CheckResult; no import cycle)."""
    return item, bool(ok), message


def check_paving(data: dict[str, Any], samples: int = SAMPLED_BOXES, executor=None) -> list[tuple[str, bool, str]]:
    """The checks of a paving certificate, as (item, ok, message) triples (see the module docstring);
    ``samples``: decided sub-boxes per claim cross-checked by the point prover (0: none); ``executor``
    (:class:`.executors.Executor`): where the decided sub-boxes are re-evaluated (default: here)."""
    from .order import check_priority
    from .paving import box_scene, evaluate_task, point_task
    from .point_proofs import spread
    from .report import claim_numbers
    out: list = []
    add = out.append
    ok = isinstance(data.get("integrity"), dict) and data["integrity"].get("sha256") == digest(data)
    add(CheckResult("integrity", ok, "digest matches" if ok else "the digest does not match the content"))
    from .. import __version__
    wrote = (data.get("software") or {}).get("rigor_gyro") if isinstance(data.get("software"), dict) else None
    add(CheckResult("software", wrote == __version__, f"written by rigor_gyro {wrote}" if wrote == __version__ else
                    f"written by rigor_gyro {wrote!r}: this checker re-derives the reasons and records of pavings of "
                    f"its own version ({__version__}) only; check it with the version that wrote it"))
    sc = data["scene"]
    try:
        scene = Scene.from_header(sc)
        bs = box_scene(scene)
    except (RigorGyroError, TypeError, ValueError, KeyError) as e:
        add(CheckResult("scene", False, f"the paving's scene is not a valid box scene: {e}"))
        return out
    from .identity import builtin_differs
    if (differs := builtin_differs(sc)) is not None:
        add(CheckResult("scene", False, differs))
    add(CheckResult("box", data["box"] == bs.box.to_json(), "the box re-derived from the scene"))
    st = data.get("settings") if isinstance(data.get("settings"), dict) else {}
    if "point_prec" in st or "point_maxprec" in st:     # chosen on the command line, not by the scene
        pp, pm = st.get("point_prec"), st.get("point_maxprec")
        if not (isinstance(pp, int) and isinstance(pm, int) and MIN_PREC <= pp <= pm <= MAX_PREC):
            add(CheckResult("settings", False, f"the point proofs' precisions {pp}, {pm} are out of range"))
            return out
        bs.point_prec, bs.point_maxprec = pp, pm
    if "priority" in st:        # chosen on the command line: the order, never what a box's evaluation says
        try:
            bs.priority = check_priority(st["priority"])
        except RigorGyroError as e:
            add(CheckResult("settings", False, str(e)))
            return out
    settings = bs.settings()
    add(CheckResult("settings", data["settings"] == settings, "the settings re-derived from the scene"))
    ok = data.get("point_parameters") == dict(bs.points)
    add(CheckResult("point_parameters", ok, "the point parameters re-derived from the scene" if ok else
                    "the stored point parameters are not the scene's values of the parameters without tolerances"))
    ids = [c["id"] for c in data["claims"]]
    skipped = data.get("not_box_claims")
    add(CheckResult("claims", ids == bs.claims and skipped == bs.skipped,
                    f"claims {ids}" + ("" if skipped == bs.skipped else
                                       f"; the claims not decided over boxes are {bs.skipped}, not {skipped}")))
    statements = bs.box_statements
    pj = json.dumps(bs.points, sort_keys=True)
    oj = settings_json(bs.options, bs.scene.model)
    mj = json.dumps({k: fraction_text(q) for k, q in bs.box.midpoint().items()}, sort_keys=True)
    statuses = []
    memo: dict = {}         # the Monte Carlo re-run, once for every claim
    stopped = data["stopped"] if isinstance(data.get("stopped"), str) else ""
    pending = data.get("pending")
    open_claims, whole_pending = _pending_claims(pending, bs.box)
    # the whole box is what pave evaluates first, for every claim: its reason opens each claim's reasons
    # (unless it is still pending: stopped before its first evaluation)
    first = {} if whole_pending else evaluate_task(bs.scene.kind, pj, oj, mj, json.dumps(bs.box.to_json()),
                                                   tuple(bs.claims), bs.prec)
    evaluations = _evaluate_decided(data["claims"], bs, pj, oj, mj, executor)
    leaves: dict[str, dict] = {}
    for c in data["claims"]:
        cid = c["id"]
        if c.get("statement") != "For every parameter value in the box: " + statements.get(cid, ""):
            add(CheckResult(cid, False, "the statement is not the kind's box statement"))
        boxes = [(Box.from_json(b["box"]), b["status"]) for b in c["boxes"]]
        if any(s not in ("proved", "refuted", "undecided") for _, s in boxes):
            add(CheckResult(cid, False, "unknown sub-box status"))
            continue
        leaves[cid] = {b.edges: s for b, s in boxes}
        tiles = _tiles(bs.box, [b for b, _ in boxes], bs.frozen)
        add(CheckResult(cid, tiles, "the sub-boxes tile the box (leaves of its bisection tree)" if tiles else
                        "the sub-boxes do not tile the box"))
        total = bs.box.volume()
        vol = {k: sum((b.volume() for b, s in boxes if s == k), Fraction(0)) / total
               for k in ("proved", "refuted", "undecided")}
        # the exact fractions, the decimals the report prints and the sub-box counts, from the volumes above
        want = claim_numbers(vol, [s for _, s in boxes])
        numbers = {k: c.get(k) for k in want} == want
        add(CheckResult(cid, numbers, "volume fractions (exact and decimal) and sub-box counts recomputed" if numbers
                        else "the stored volume fractions or sub-box counts are not the sub-boxes' own"))
        bad = []
        reasons = {}
        if cid in first:
            reasons[first[cid][0]] = first[cid][1]
        for b, s in boxes:
            if s == "undecided":
                continue
            got, why = evaluations[(cid, b.edges)]
            reasons.setdefault(got, why)
            if got != s:
                bad.append(f"{b.to_json()}: stored {s}, re-evaluated {got}")
        add(CheckResult(cid, not bad, "every decided sub-box re-evaluated" if not bad else bad[0]))

        def prove_at(point, cid=cid):
            return point_task(bs.scene.kind, json.dumps(bs.point_parameters(point), sort_keys=True), oj, cid,
                              bs.point_prec, bs.point_maxprec)["status"]
        add(CheckResult(cid, *cross_check(cid, boxes, samples, prove_at)))
        if stopped and pending is None and "undecided" in c.get("reasons", {}) \
                and any(s == "undecided" for _, s in boxes):      # written before pavings listed pending boxes
            reasons["undecided"] = stopped
        elif stopped and cid in open_claims:      # a claim with pending boxes: the stop is why they are undecided
            reasons["undecided"] = stopped
        ok = c.get("reasons") == dict(sorted(reasons.items()))
        add(CheckResult(cid, ok, "the reasons re-derived (the first sub-box of each status)" if ok else
                        "the stored reasons are not the sub-boxes' own (re-evaluated in pave's order)"))
        # the point proofs are exactly pave's: the midpoints of max_points refuted and max_points undecided
        # sub-boxes spread evenly over each list in order, every parameter as the scene has it
        expected = []
        for outcome in ("refuted", "undecided"):
            for b, _ in spread([x for x in boxes if x[1] == outcome], bs.max_points):
                expected.append((outcome, bs.point_parameters(b.midpoint())))
        stored = [(p.get("box_outcome"), p.get("point")) for p in c["points"]]
        if isinstance(data.get("stopped"), str) and data["stopped"] and not stored:
            expected = []       # stopped by the time limit before the point proofs: it claims none
        add(CheckResult(cid, stored == expected, "the point proofs are at the midpoints pave chooses" if stored == expected
                        else "the stored point proofs are not the midpoints of the paving's refuted and undecided sub-boxes"))
        wrong = []
        for p in c["points"] if stored == expected else []:
            redo = point_task(bs.scene.kind, json.dumps(p["point"], sort_keys=True), oj, cid, bs.point_prec,
                              bs.point_maxprec)
            got = redo["status"]
            if got != p["status"]:
                wrong.append(f"point {p['point']}: stored {p['status']}, re-proved {got}")
            elif {k: v for k, v in p.items() if k not in ("box_outcome", "point")} != redo:
                wrong.append(f"point {p['point']}: the stored reason or precision is not the point proof's own")
            if p["box_outcome"] == "refuted" and got == "proved":
                wrong.append(f"point {p['point']}: proved at the midpoint of a sub-box refuted everywhere")
        add(CheckResult(cid, not wrong, f"{len(c['points'])} point proofs re-run" if not wrong else wrong[0]))
        found = _check_searches(bs, data, c, boxes, oj, add, memo)
        status = ("refuted" if any(s == "refuted" for _, s in boxes) or any(p["status"] == "refuted" for p in c["points"])
                  or found
                  else "proved" if boxes and all(s == "proved" for _, s in boxes) else "inconclusive")
        statuses.append(status)
        add(CheckResult(cid, c["status"] == status, f"status {c['status']!r}" + ("" if c["status"] == status else
                                                                                f", but the sub-boxes give {status!r}")))
    verdict = "refuted" if "refuted" in statuses else "proved" if statuses and all(s == "proved" for s in statuses) \
        else "inconclusive"
    add(CheckResult("verdict", data.get("verdict") == verdict, f"verdict {data.get('verdict')!r}"))
    if pending is not None or stopped or "stopped" in data:
        add(_check_stopped(data, stopped, pending, leaves))
        add(_check_pending(bs, pending, stopped, leaves))
    elif leaves and all(_tiles(bs.box, [Box(e) for e in ls], bs.frozen) for ls in leaves.values()):
        add(_check_counters(bs, data, leaves))
    if any(k in data for k in ("quantities", "range_tiles", "range_points")):
        add(_check_ranges(bs, data, pj, oj, mj, executor))
    return out


def _check_counters(bs, data: dict[str, Any], leaves: dict[str, dict]) -> tuple[str, bool, str]:
    """The counters of a paving that ran its course, from its leaves: every box of the union of the claims'
    bisection trees (each leaf and each box split on the way to one) was evaluated exactly once, so
    ``boxes_evaluated`` is their count and ``levels`` the depth of the deepest plus one; ``budget_exhausted``
    says whether some undecided sub-box is coarser than the resolution (split no further for ``max_boxes``).
    The same for a paving resumed or refined (:mod:`.resume` keeps the counts) or streamed (:mod:`.stream`)."""
    boxes = {e for ls in leaves.values() for e in ls}
    count, deepest = 0, 0
    todo = [(bs.box, [Box(e) for e in boxes], 0)]
    while todo:
        node, inside, depth = todo.pop()
        count, deepest = count + 1, max(deepest, depth)
        if all(b == node for b in inside):
            continue
        for child in node.split(bs.box, bs.frozen):
            todo.append((child, [b for b in inside if all(lo >= clo and hi <= chi for (_, lo, hi), (_, clo, chi)
                                                              in zip(b.edges, child.edges))], depth + 1))
    coarse = any(s == "undecided" and any(w > bs.resolution for n, w in Box(e).relative_widths(bs.box).items()
                                          if n not in bs.frozen)
                 for ls in leaves.values() for e, s in ls.items())
    want = {"boxes_evaluated": count, "levels": deepest + 1, "budget_exhausted": coarse}
    got = {k: data.get(k) for k in want}
    return CheckResult("counters", got == want, f"the run's counters {want} re-derived from the sub-boxes" if got == want
                       else f"the run's counters {got} are not the sub-boxes' {want}")


def _stop_texts() -> dict[str, str]:
    """The texts pave writes in ``stopped`` (regular expressions, matched whole), by what stopped it."""
    from ..core.deadline import Budget
    from .paving import CHECKPOINT, INTERRUPTED, box_budget_reason
    limit = re.escape(Budget(1.0).reason()).replace(re.escape("1"), r"\S+", 1)
    return {"time limit": limit, "Ctrl-C": re.escape(INTERRUPTED),
            "broken executor": r"the executor broke \(.*\); the (batch in flight was|batches in flight were) left pending",
            "box budget": re.escape(box_budget_reason(7)).replace("7", r"[0-9]+", 1),
            "checkpoint": re.escape(CHECKPOINT).replace(re.escape("{n}"), r"[0-9]+")}


def _check_stopped(data: dict[str, Any], stopped: str, pending, leaves: dict[str, dict]) -> tuple[str, bool, str]:
    """A paving that says it stopped early: ``stopped`` is a text pave writes (a time limit, Ctrl-C, a broken
    executor, a box budget, a checkpoint: :func:`_stop_texts`); the stop came before the point proofs, the
    searches and the quantities' ranges (pave runs them only after the last box), so none is stored and
    ``budget_exhausted`` is set. Without pending boxes the only stop pave writes is Ctrl-C (during the point
    proofs, the searches or the ranges: the leaves complete); a paving written before pavings listed their
    pending boxes (no ``pending``) could stop only at its time limit, leaving undecided sub-boxes."""
    texts = _stop_texts()
    if not isinstance(data.get("stopped"), str) or not stopped:
        return CheckResult("stopped", False, f"'stopped' {data.get('stopped')!r} in a paving: a stop is a non-empty "
                           "text, written only when pave stopped early")
    allowed = ("Ctrl-C",) if pending == [] else ("time limit",) if pending is None else tuple(texts)
    if not any(re.fullmatch(texts[k], stopped, flags=re.S) for k in allowed):
        return CheckResult("stopped", False, f"'stopped' {stopped[:120]!r} is not a text pave writes "
                           + ("when it stops with no pending box (only Ctrl-C during the point proofs, searches or "
                              "ranges)" if pending == [] else "without listing pending boxes (only its time limit: "
                              "'time limit of S s reached (--time-limit)')" if pending is None else
                              f"(a stop by: {', '.join(allowed)})"))
    if m := re.fullmatch(texts["checkpoint"], stopped):
        if f"after {data.get('boxes_evaluated')} box evaluations" not in m.group(0):
            return CheckResult("stopped", False, "a checkpoint's count of box evaluations is not the paving's")
    if any(c.get("points") for c in data["claims"]) or any(k in data for k in ("quantities", "range_tiles")):
        return CheckResult("stopped", False, "point proofs or quantity ranges in a paving that stopped before them")
    if data.get("budget_exhausted") is not True:
        return CheckResult("stopped", False, "a paving that stopped early with budget_exhausted not true")
    if pending is None and not any(s == "undecided" for ls in leaves.values() for s in ls.values()):
        return CheckResult("stopped", False, "stopped at the time limit, yet no sub-box is undecided")
    return CheckResult("stopped", True, f"stopped: {stopped[:80]} (a stop pave writes; no point proof, search or range "
                       "after it)")


def _pending_claims(pending, whole: Box) -> tuple[set, bool]:
    """The claims some pending group lists, and whether the whole box itself is pending (nothing evaluated);
    an empty answer for a malformed list (:func:`_check_pending` reports it)."""
    try:
        claims = {c for g in pending or [] for c in g["claims"]}
        whole_pending = any([Box.from_json(b) for b in g["boxes"]] == [whole] for g in pending or [])
        return claims, whole_pending
    except (TypeError, ValueError, KeyError, AttributeError, ZeroDivisionError):
        return set(), False


def _evaluate_decided(claims: list, bs, pj: str, oj: str, mj: str, executor) -> dict:
    """{(claim, box edges): [status, reason]}: every decided sub-box of every claim re-evaluated with the
    kind's box rigour, on ``executor`` when given (the results do not depend on where they run). A sub-box
    decided for several claims is evaluated once for all of them (in the paving's claim order), as the
    paving evaluates a box for all its open claims at once."""
    from .paving import evaluate_task
    order = [c["id"] for c in claims]
    wanted: dict[tuple, tuple[Box, set]] = {}
    for c in claims:
        for b in c["boxes"]:
            if b["status"] in ("proved", "refuted"):
                box = Box.from_json(b["box"])
                wanted.setdefault(box.edges, (box, set()))[1].add(c["id"])
    keys = list(wanted)
    tasks = [(bs.scene.kind, pj, oj, mj, json.dumps(wanted[e][0].to_json()),
              tuple(c for c in order if c in wanted[e][1]), bs.prec) for e in keys]
    outs = executor.map(evaluate_task, tasks) if executor is not None else [evaluate_task(*t) for t in tasks]
    return {(cid, e): out[cid] for e, out in zip(keys, outs) for cid in wanted[e][1]}


def _check_pending(bs, pending, stopped: str, leaves: dict[str, dict]) -> tuple[str, bool, str]:
    """The pending boxes of a paving that stopped early: only then; each group is the whole box (all claims
    open) or the two halves of one split; its claims are the paving's, in its order; each of its boxes is
    an undecided sub-box of each claim it lists, and no box is pending twice. A pending box claims nothing
    (it is an undecided sub-box); these checks keep ``--resume`` from continuing a queue that is not the
    paving's own."""
    if not stopped:
        return CheckResult("pending", False, "pending boxes in a paving that ran its course (no 'stopped')")
    if pending is None:
        return CheckResult("pending", True, "stopped; written before pavings listed their pending boxes")
    seen: set = set()
    try:
        for g in pending:
            boxes = [Box.from_json(b) for b in g["boxes"]]
            claims = list(g["claims"])
            if not isinstance(g["score"], int) or isinstance(g["score"], bool) or g["score"] < 0:
                return CheckResult("pending", False, f"a pending group's score {g['score']!r} is not a count")
            if not claims or claims != [c for c in bs.claims if c in claims]:
                return CheckResult("pending", False, f"the pending claims {claims} are not some of {bs.claims} in order")
            if len(boxes) == 1:
                if boxes[0] != bs.box or claims != list(bs.claims):
                    return CheckResult("pending", False, "a pending box alone that is not the whole box for every claim")
            elif len(boxes) == 2:
                hull = Box(tuple((n, min(a1, a2), max(b1, b2)) for (n, a1, b1), (_, a2, b2)
                                 in zip(boxes[0].edges, boxes[1].edges)))
                if [e[0] for e in boxes[0].edges] != [e[0] for e in boxes[1].edges] \
                        or hull.split(bs.box, bs.frozen) != tuple(boxes):
                    return CheckResult("pending", False, f"a pending pair is not the two halves of a split: "
                                       f"{[b.to_json() for b in boxes]}")
            else:
                return CheckResult("pending", False, "a pending group of neither one nor two boxes")
            for b in boxes:
                if b.edges in seen:
                    return CheckResult("pending", False, f"the box {b.to_json()} is pending twice")
                seen.add(b.edges)
                for c in claims:
                    if leaves.get(c, {}).get(b.edges) != "undecided":
                        return CheckResult("pending", False, f"the pending box {b.to_json()} is not an undecided "
                                           f"sub-box of {c}")
    except (TypeError, ValueError, KeyError, AttributeError, ZeroDivisionError) as e:
        return CheckResult("pending", False, f"a pending group is malformed: {type(e).__name__}: {e}")
    return CheckResult("pending", True, f"{len(seen)} pending sub-box(es), each undecided for the claims it lists")


def _check_searches(bs, data: dict[str, Any], c: dict[str, Any], boxes: list, oj: str, add, memo: dict) -> bool:
    """The claim's stored counterexample search and Monte Carlo estimate (:mod:`.counterexample_check`):
    present exactly when the settings ask for them (a paving stopped early, or a search the time limit
    skipped, holds none), every stored point proof re-proved, the estimate re-run with its seed. Returns
    whether the search holds a certified counterexample (verified here)."""
    from .counterexample_check import check_counterexamples, check_monte_carlo
    from .counterexamples import (MC_CLASSIFIER, MC_CONFIDENCE, PROBE_PREC, failing_fraction_estimate, probe_task,
                                  search_settings)
    from .paving import point_task, searched_refutation
    cid = c["id"]
    stopped = isinstance(data.get("stopped"), str) and bool(data["stopped"])
    cs, mc = c.get("counterexample_search"), c.get("monte_carlo")
    want_cs = bool(bs.search_points) and not stopped and any(s == "undecided" for _, s in boxes)
    want_mc = bool(bs.monte_carlo) and not stopped
    if (cs is not None) != want_cs or (mc is not None) != want_mc:
        add(CheckResult(cid, False, "a counterexample search or Monte Carlo estimate where the settings ask for none, "
                                    "or none where they ask for one"))
        return False
    found = False
    limit = _stop_texts()["time limit"]
    for name, part in (("counterexample search", cs), ("Monte Carlo estimate", mc)):
        if part is not None and "skipped" in part and not re.fullmatch(limit, str(part["skipped"])):
            add(CheckResult(cid, False, f"the {name} says it was skipped for {str(part['skipped'])[:80]!r}: pave skips "
                            "one only when its time limit ran out"))
    if cs is not None and "skipped" not in cs:
        want = search_settings(bs.search_points, bs.search_samples or None)
        undecided = sum(1 for _, s in boxes if s == "undecided")
        if cs.get("settings") != want or cs.get("undecided_leaves") != undecided:
            add(CheckResult(cid, False, f"the counterexample search's settings {cs.get('settings')} and undecided leaves "
                            f"{cs.get('undecided_leaves')!r} are not the scene's {want} and the claim's {undecided}"))

        def prove_at(point, cid=cid):
            return point_task(bs.scene.kind, json.dumps(bs.point_parameters(point), sort_keys=True), oj, cid,
                              bs.point_prec, bs.point_maxprec)

        def probe_at(point, cid=cid):
            batch = json.dumps([{k: fraction_text(q) for k, q in point.items()}])
            return probe_task(bs.scene.kind, json.dumps(bs.points, sort_keys=True), oj,
                              json.dumps({k: fraction_text(q) for k, q in bs.box.midpoint().items()}, sort_keys=True),
                              json.dumps(bs.box.to_json()), batch, (cid,), PROBE_PREC, False)[0][cid][0]
        ok, msg = check_counterexamples(bs.box, boxes, cid, cs, prove_at, probe_at)
        add(CheckResult(cid, ok, msg))
        found = ok and searched_refutation({"counterexample_search": cs})
    if mc is not None and "skipped" not in mc:
        want = {"samples": bs.monte_carlo, "seed": bs.monte_carlo_seed, "classifier": MC_CLASSIFIER,
                "confidence": MC_CONFIDENCE}
        got = {k: mc.get(k) for k in want}
        if got != want:
            add(CheckResult(cid, False, f"the Monte Carlo estimate's {got} are not the scene's {want}"))
            return found
        total = bs.box.volume()
        volume = {k: sum((b.volume() for b, s in boxes if s == k), Fraction(0)) / total
                  for k in ("proved", "refuted", "undecided")}

        def rerun(cid=cid, mc=mc):      # one run for every claim, as pave ran it (the claims proved together)
            key = (mc["samples"], mc["seed"], mc["classifier"])
            if key not in memo:
                memo[key] = failing_fraction_estimate(bs, list(bs.claims), mc["samples"], mc["seed"],
                                                      classifier=mc["classifier"])
            return memo[key][cid]
        add(CheckResult(cid, *check_monte_carlo(cid, mc, volume, rerun)))
    return found


def _check_ranges(bs, data: dict[str, Any], pj: str, oj: str, mj: str, executor=None) -> tuple[str, bool, str]:
    """The quantities' ranges: the stored tiles tile the box, every tile and cited point is re-evaluated
    with the kind's box rigour at the stored precision (on ``executor`` when given: the evaluations do not
    depend on where they run), and every stated number (outer and inner ranges, worst cases,
    sensitivities) is derived again from those evaluations alone (:func:`.ranges.summarise`)."""
    from .ranges import quantities_module, quantity_specs, range_task, summarise
    mod = quantities_module(bs.scene.kind)
    if mod is None:
        return CheckResult("quantities", False, f"kind {bs.scene.kind!r} certifies no quantity over a box")
    if not all(k in data for k in ("quantities", "range_tiles", "range_points")):
        return CheckResult("quantities", False, "quantities, range_tiles and range_points go together")
    try:
        tiles = [Box.from_json(t) for t in data["range_tiles"]]
        points = [{k: Fraction(v) for k, v in p.items()} for p in data["range_points"]]
    except (TypeError, ValueError, ZeroDivisionError, AttributeError) as e:
        return CheckResult("quantities", False, f"a stored tile or point is not exact: {e}")
    if not tiles_by_bisection(bs.box, tiles, bs.frozen):
        return CheckResult("quantities", False, "the range tiles do not tile the box")
    for p in points:
        if set(p) != set(bs.box.names) or any(not lo <= p[k] <= hi for k, lo, hi in bs.box.edges):
            return CheckResult("quantities", False, f"the point {p} is not a point of the box")
    from .ranges import point_box
    tasks = [(bs.scene.kind, pj, oj, mj, json.dumps(b.to_json()), bs.prec) for b in tiles]
    tasks += [(bs.scene.kind, pj, oj, mj, json.dumps(point_box(p).to_json()), bs.prec) for p in points]
    outs = executor.map(range_task, tasks) if executor is not None else [range_task(*t) for t in tasks]
    tv, pv = list(zip(tiles, outs[:len(tiles)])), list(zip(points, outs[len(tiles):]))
    want = summarise(bs.box, quantity_specs(bs.scene.kind, pj, oj, mj), tv, pv)
    ok = data["quantities"] == want
    return CheckResult("quantities", ok, f"{len(want)} quantity ranges re-derived from {len(tiles)} tiles and "
                       f"{len(points)} points" if ok else "the stated ranges are not the re-evaluated tiles' and points' own")
