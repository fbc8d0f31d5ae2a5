"""Continue a paving from its certificate: resume a partial one (``prove --resume PAVING.json``) and
refine the undecided sub-boxes of any one (``--refine RESOLUTION``).

A paving that stopped early (a time limit, a box budget, Ctrl-C, a checkpoint of a run that was then
killed) lists its *pending* boxes: queued and not yet evaluated, stored as undecided sub-boxes of their
open claims (:mod:`.paving`). :func:`resume_state` rebuilds the paving's state from the certificate:

* the certificate is verified first by the checker's rules (:func:`.check.check_paving`, every decided
  sub-box re-evaluated on the executor, the tiling, the pending list; the point-prover cross-check is
  left to ``rigor-gyro check``), and by its schema; a paving that fails any check is refused
  (ParameterError), so nothing stored is trusted beyond what the checker re-derives;
* the decided sub-boxes and the undecided ones that are not pending are the leaves so far, in their
  stored order; the pending groups are queued again in their stored order (best first), so the run goes
  on exactly as the interrupted one would have: the same leaves, statuses, reasons, point proofs and
  verdict as an uninterrupted run (tests/test_paving_anytime.py);
* each claim's reasons are the stored ones, except the undecided reason of a claim with pending boxes
  (the stop), which is the whole box's own again (re-evaluated, as the checker does).

``--refine`` gives a new ``box_resolution`` (at most the paving's; it replaces the option in the scene the
new paving states): each undecided sub-box that is not pending and is coarser than it is split again, its
halves queued with the claims it was undecided for; decided sub-boxes are kept as they are. The refined
paving's leaves are those a fresh paving at the new resolution has (in another order), unless
``max_boxes``, which counts the paving's evaluations in all its runs, runs out first.

Fails when: the data is not a paving, fails its check, a paving that ran its course is resumed without
``--refine``, or the new resolution is not finer: ParameterError (exit 2) saying which.
"""
from __future__ import annotations

import json
from typing import Any

from ..core.boxes import Box, fraction_text
from ..core.errors import ParameterError, RigorGyroError
from ..scene import Scene
from .order import Frontier, Group, check_priority
from .models import settings_json
from .paving import SCHEMA, BoxScene, ClaimPaving, PaveState, box_scene, evaluate_task

__all__ = ["verify_paving", "resume_state"]


def verify_paving(data: Any, executor=None, what: str = "the paving") -> None:
    """ParameterError unless ``data`` is a paving that passes its schema and the checker's rules (without
    the point-prover cross-check); the decided sub-boxes are re-evaluated on ``executor``."""
    from ..check import load_schema, schema_errors
    from .check import check_paving
    if not isinstance(data, dict) or data.get("schema") != SCHEMA:
        raise ParameterError(f"{what} is not a paving (schema {SCHEMA!r})")
    try:
        errors = schema_errors(data, load_schema("paving-1"))
    except RecursionError:
        errors = ["$: nested too deeply to validate"]
    if errors:
        raise ParameterError(f"{what} does not conform to paving-1.schema.json: {errors[0]}")
    try:
        results = check_paving(data, samples=0, executor=executor)
    except (RigorGyroError, KeyError, TypeError, ValueError, ArithmeticError, AttributeError, IndexError) as e:
        raise ParameterError(f"{what} cannot be checked: {type(e).__name__}: {e}") from None
    bad = [r for r in results if not r[1]]
    if bad:
        raise ParameterError(f"{what} fails its check, so it is not continued: {bad[0][0]}: {bad[0][2]}")


def _unfinished(bs: BoxScene, box: Box) -> bool:
    """Whether ``box`` is coarser than the resolution along an edge that is split."""
    return any(w > bs.resolution for n, w in box.relative_widths(bs.box).items() if n not in bs.frozen)


def resume_state(data: Any, executor=None, refine: str | None = None, priority: str | None = None
                 ) -> tuple[BoxScene, PaveState]:
    """The box scene and the state that :func:`.paving.pave` continues (see the module docstring): the
    certificate ``data`` verified first (:func:`verify_paving`); ``refine``: the new box_resolution;
    ``priority``: the order from here on (default: the paving's)."""
    verify_paving(data, executor)
    if not data.get("stopped") and refine is None:
        raise ParameterError("the paving ran its course: nothing to resume (give --refine RESOLUTION to split its "
                             "undecided sub-boxes finer)")
    scene = Scene.from_header(data["scene"])
    settings = data["settings"]
    old = box_scene(scene).resolution
    if refine is not None:
        scene.options["box_resolution"] = str(refine).strip()
    bs = box_scene(scene)
    if bs.resolution > old:
        raise ParameterError(f"--refine {refine}: the paving's box_resolution is {settings['box_resolution']}; "
                             "a refinement must be at most that (finer)")
    bs.point_prec, bs.point_maxprec = settings["point_prec"], settings["point_maxprec"]
    bs.priority = check_priority(priority if priority is not None else settings.get("priority", bs.priority))
    whole = bs.box
    pending = [Group.from_json(g) for g in data.get("pending", [])]
    pend = {c: {b.edges for g in pending if c in g.claims for b in g.boxes} for c in bs.claims}
    evaluated_whole = not any(g.boxes == (whole,) for g in pending)
    first = {}
    if evaluated_whole and any(pend.values()):
        first = evaluate_task(bs.scene.kind, json.dumps(bs.points, sort_keys=True),
                              settings_json(bs.options, bs.scene.model),
                              json.dumps({k: fraction_text(q) for k, q in whole.midpoint().items()}, sort_keys=True),
                              json.dumps(whole.to_json()), tuple(bs.claims), bs.prec)
    statements = bs.box_statements
    result: dict[str, ClaimPaving] = {}
    reopen: dict[tuple, list[str]] = {}         # undecided leaves split again by --refine: their claims
    boxes_of: dict[tuple, Box] = {}
    for c in data["claims"]:
        cid, leaves = c["id"], []
        for item in c["boxes"]:
            b, s = Box.from_json(item["box"]), item["status"]
            if s == "undecided" and b.edges in pend[cid]:
                continue                                    # pending: queued again below
            if s == "undecided" and refine is not None and _unfinished(bs, b):
                reopen.setdefault(b.edges, []).append(cid)
                boxes_of[b.edges] = b
                continue
            leaves.append((b, s))
        reasons = dict(c["reasons"])
        if pend[cid]:
            reasons.pop("undecided", None)
            if cid in first and first[cid][0] == "undecided":
                reasons["undecided"] = first[cid][1]
        result[cid] = ClaimPaving(cid, "For every parameter value in the box: " + statements[cid], leaves, reasons)
    groups = pending + [Group(boxes_of[e].split(whole, bs.frozen), tuple(x for x in bs.claims if x in cs))
                        for e, cs in reopen.items()]
    frontier = Frontier(bs.priority, groups)
    evaluated = data["boxes_evaluated"]
    budget_hit = any(s == "undecided" and _unfinished(bs, b) for cp in result.values() for b, s in cp.boxes)
    return bs, PaveState(result, frontier, created=evaluated + len(frontier), evaluated=evaluated,
                         levels=data["levels"], budget_hit=budget_hit)

