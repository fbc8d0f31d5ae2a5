"""Pave a scene's tolerance box, claim by claim (SIVIA: Jaulin, Kieffer, Didrit, Walter 2001).

A scene whose parameters include tolerances (``"[lo, hi]"``, ``"mid +- rad"``; :mod:`rigor_gyro.core.boxes`)
states each claim for every parameter value in the box. The box is evaluated by the kind's ``boxes``
module on balls containing it; where a claim is undecided the box is halved along its relatively
widest edge, down to ``box_resolution`` (each edge at most that fraction of the whole box's edge) or
until ``max_boxes`` evaluations were spent. Every sub-box ends, per claim, as

* ``proved``: the claim holds for every parameter value in the sub-box (certified on balls);
* ``refuted``: the claim fails for every parameter value in it (certified on balls); its midpoint is
  re-proved refuted by the point prover (up to ``max_points`` points per claim, spread evenly over the refuted
  sub-boxes in order, as are those of the undecided ones), a counterexample anyone can re-check with
  ``rigor-gyro prove``;
* ``undecided``: neither, at the resolution and budget; its midpoint is proved by the point prover,
  and a refutation there is a certified counterexample inside the box.

The claim over the whole box is ``proved`` only when every sub-box is proved, ``refuted`` when some
point is certainly a counterexample, otherwise ``inconclusive`` with the undecided volume fraction. A
resolution or a budget never refutes.

Options (the scene's ``[options]``, beside the kind's): ``box_resolution`` (relative, default 1/64),
``max_boxes`` (default 20000), ``box_prec`` (bits for the box evaluations, default 128), ``max_points``
(point proofs per claim and outcome, default 16); ``search_points`` (default 0: off) and ``search_samples``
(default 32 per point): a counterexample search over *every* undecided leaf of a claim (Halton points
probed by the box rigour, the best candidates proved by the point prover: a refuted one refutes the claim,
:mod:`.counterexamples`); ``monte_carlo`` (samples, default 0: off) and ``monte_carlo_seed``: each claim's
failing fraction estimated by the point prover at uniform samples, beside the certified fractions
(evidence, never a verdict). With either on, the settings state all four.

Anytime: boxes are evaluated best first (:mod:`.order`: the largest first by default, which is
breadth-first; or those next to a decided region first) in batches. A time limit, a box budget for the
run, Ctrl-C or a broken executor stop it between batches; the boxes still queued are then *pending*
(undecided leaves, listed apart), and the paving written is a valid partial certificate that ``check``
verifies and :mod:`.resume` continues (``prove --resume``) to exactly the paving an uninterrupted run
gives; with a checkpoint callback it is also written every so often while the run goes on.

Determinism: the batches and what each evaluation says depend only on the boxes, not on the executor or
the worker count; the paving is identical for every executor and worker count. On a pool or a Dask
cluster the ``volume`` order runs as a streaming frontier (:mod:`.stream`: no barrier between batches,
results committed in the same order, the same certificate).
"""
from __future__ import annotations

import contextlib
import json
import signal
import threading
import time
from concurrent.futures import BrokenExecutor
from dataclasses import dataclass, field
from fractions import Fraction
from types import SimpleNamespace
from typing import Any

from ..core.balls import DEFAULT_MAXPREC, DEFAULT_PREC, working_precision
from ..core.boxes import Box, exact_decimal, fraction_text, split_parameters
from ..core.deadline import Budget, TimeLimitReached, check_time_limit, until
from ..core.errors import ParameterError, SceneError
from ..core.exact import option_count, option_number
from ..kinds import KINDS, box_claims, kind_module, optional_module, scene_claims
from ..scene import Scene
from .executors import Executor
from .models import scene_model as _model, settings_json
from .point_proofs import point_task, spread
from .order import DEFAULT_PRIORITY, Frontier, Group, check_priority, volume_depth
from .ranges import quantities_module, quantity_specs, search_ranges

__all__ = ["MARGIN_OPTIONS", "BoxScene", "Paving", "PaveState", "box_scene", "pave", "has_tolerances",
           "boxes_module", "evaluate_task", "point_task", "start_state", "INTERRUPTED", "CHECKPOINT"]

MARGIN_OPTIONS = {"box_resolution": "1/64", "max_boxes": "20000", "box_prec": "128", "max_points": "16",
                  "range_boxes": "64", "range_gap": "1/100", "search_points": "0", "search_samples": "0",
                  "monte_carlo": "0", "monte_carlo_seed": "0"}
SCHEMA = "rigor-gyro/paving/1"


def has_tolerances(scene: Scene) -> bool:
    from ..core.boxes import is_tolerance
    return any(is_tolerance(v) for v in scene.parameters.values())


def boxes_module(kind: str):
    """The kind's ``boxes`` module (its rigour over parameter boxes), or None when it has none."""
    return optional_module(kind, "boxes")


@dataclass
class BoxScene:
    """A validated scene with tolerances: the point parameters, the box, the claims and settings."""

    scene: Scene
    points: dict[str, Any]
    box: Box
    options: dict[str, Any]          # the kind's options (margin options removed)
    claims: list[str]
    resolution: Fraction
    max_boxes: int
    prec: int
    max_points: int
    skipped: list[str] = field(default_factory=list)   # requested by default, not decidable over a box
    frozen: tuple[str, ...] = ()     # box parameters the kind's box claims do not depend on (never split)
    range_boxes: int = 64            # tile evaluations for the quantities' ranges (:mod:`.ranges`); 0: none
    range_gap: Fraction = Fraction(1, 100)
    #: the point proofs' starting and largest precision (``prove --prec/--maxprec``; the box evaluations use
    #: ``prec``, the scene's ``box_prec``)
    point_prec: int = DEFAULT_PREC
    point_maxprec: int = DEFAULT_MAXPREC
    #: the order boxes are evaluated in (:mod:`.order`; ``prove --priority``)
    priority: str = DEFAULT_PRIORITY
    #: the counterexample search over every undecided leaf (:mod:`.counterexamples`): candidates per claim
    #: (0: none), Halton samples (0: 32 per candidate); the Monte Carlo cross-check's samples (0: none), seed
    search_points: int = 0
    search_samples: int = 0
    monte_carlo: int = 0
    monte_carlo_seed: int = 0
    #: {claim: statement} of the claims the kind decides over a box for this scene's model
    box_statements: dict[str, str] = field(default_factory=dict)

    def searches(self) -> bool:
        return bool(self.search_points or self.monte_carlo)

    def settings(self) -> dict[str, Any]:
        """The settings a paving certificate states (the checker re-derives them from the scene)."""
        return {"box_resolution": fraction_text(self.resolution), "max_boxes": self.max_boxes, "box_prec": self.prec,
                "max_points": self.max_points, "unsplit": list(self.frozen), "range_boxes": self.range_boxes,
                "range_gap": fraction_text(self.range_gap), "point_prec": self.point_prec,
                "point_maxprec": self.point_maxprec,
                **({} if self.priority == DEFAULT_PRIORITY else {"priority": check_priority(self.priority)}),
                **({"search_points": self.search_points, "search_samples": self.search_samples,
                    "monte_carlo": self.monte_carlo, "monte_carlo_seed": self.monte_carlo_seed}
                   if self.searches() else {})}

    def point_parameters(self, point: dict[str, Fraction]) -> dict[str, str]:
        return {**{k: v for k, v in self.points.items()}, **{k: fraction_text(q) for k, q in point.items()}}


def _end_text(q: Fraction) -> str:
    """An end of a tolerance as an exact decimal where it has one (-0.02, not -1/50), else as a fraction."""
    return exact_decimal(q)


def _bad_end(module, mid: Scene, box: Box, error: ParameterError, given: dict) -> ParameterError:
    """The error for a box whose midpoint is bad input, naming the end of a tolerance that is (the midpoint
    is only where it was first seen): each end of each tolerance, the rest at their midpoints, is validated
    on its own; the first that fails gives the message ("parameter 'k' = '[-1, 1]': k's lower end -1: need
    > 0"). The midpoint's own error when no single end fails."""
    for name in box.names:
        lo, hi = box.interval(name)
        for end, value in (("lower", lo), ("upper", hi)):
            text = _end_text(value)
            probe = Scene(name=mid.name, kind=mid.kind, source=mid.source,
                          parameters={**mid.parameters, name: text}, claims_only=mid.claims_only,
                          options=mid.options, paper={}, path=mid.path, model=mid.model)
            try:
                module.validate(probe)
            except ParameterError as e:
                msg = str(e)
                if repr(name) not in msg:
                    continue
                head = f"parameter {name!r} = {text!r}: "
                tail = msg[len(head):] if msg.startswith(head) else msg
                return ParameterError(f"parameter {name!r} = {str(given.get(name, '')).strip()!r}: "
                                      f"{name}'s {end} end {text}: {tail}")
    return ParameterError(f"{error} (at the box's midpoint)")


def box_scene(scene: Scene) -> BoxScene:
    """Validate a scene with tolerances: the box, the margin options, the domain on the whole box
    (the kind's ``validate_box``), the claims. ParameterError/SceneError naming what to change."""
    from ..prover import requested_claims
    points, box = split_parameters(scene.parameters)
    point_edges = {k: lo for k, lo, hi in box.edges if lo == hi}
    box = Box(tuple(e for e in box.edges if e[1] != e[2]))
    points.update({k: fraction_text(q) for k, q in point_edges.items()})
    if not box.edges:
        raise ParameterError("every tolerance has zero width: write the parameters as numbers")
    module = kind_module(scene.kind)
    boxes = boxes_module(scene.kind)
    if boxes is None:
        raise ParameterError(f"parameter {box.names[0]!r}: kind {scene.kind!r} cannot take a tolerance yet (only a "
                             f"point value); kinds that can: {', '.join(k for k in KINDS if boxes_module(k))}")
    margin = {k: str(scene.options[k]) for k in MARGIN_OPTIONS if k in scene.options}
    kind_opts = {k: v for k, v in scene.options.items() if k not in MARGIN_OPTIONS}
    m = {**MARGIN_OPTIONS, **margin}
    resolution = option_number(m["box_resolution"], "box_resolution", above="0", at_most="1").rational
    if resolution < Fraction(1, 2 ** 40):
        raise ParameterError(f"option 'box_resolution' = {m['box_resolution']!r}: need at least 2^-40")
    max_boxes = option_count(m["max_boxes"], "max_boxes", 1, 10 ** 7)
    prec = option_count(m["box_prec"], "box_prec", 32, 4096)
    max_points = option_count(m["max_points"], "max_points", 0, 10 ** 4)
    range_boxes = option_count(m["range_boxes"], "range_boxes", 0, 10 ** 6)
    range_gap = option_number(m["range_gap"], "range_gap", above="0", at_most="1").rational
    search = (option_count(m["search_points"], "search_points", 0, 10 ** 4),
              option_count(m["search_samples"], "search_samples", 0, 10 ** 7),
              option_count(m["monte_carlo"], "monte_carlo", 0, 10 ** 7),
              option_count(m["monte_carlo_seed"], "monte_carlo_seed", 0, 2 ** 31))
    mid = Scene(name=scene.name, kind=scene.kind, source=scene.source,
                parameters={**points, **{k: fraction_text(q) for k, q in box.midpoint().items()}},
                claims_only=scene.claims_only, options=kind_opts, paper={}, path=scene.path, model=dict(scene.model))
    try:
        model = module.validate(mid)
    except ParameterError as e:
        raise _bad_end(module, mid, box, e, scene.parameters) from None
    with working_precision(prec):
        boxes.validate_box(model, box)
    wanted = requested_claims(scene, *scene_claims(module, scene))
    decidable = box_claims(boxes, model)
    if scene.claims_only is not None:
        bad = [c for c in wanted if c not in decidable]
        if bad:
            raise SceneError(f"claim {bad[0]!r} cannot be decided over a box; kind {scene.kind!r} decides "
                             f"{list(decidable)} over boxes")
        claims, skipped = wanted, []
    else:
        claims = [c for c in wanted if c in decidable]
        skipped = [c for c in wanted if c not in decidable]
    frozen = tuple(n for n in box.names if n in getattr(boxes, "UNSPLIT_PARAMETERS", ()))
    if len(frozen) == len(box.names):
        frozen = frozen[1:]           # something must be splittable; the first frozen edge is
    bs = BoxScene(scene, points, box, kind_opts, claims, resolution, max_boxes, prec, max_points, skipped,
                  frozen, range_boxes, range_gap, box_statements=decidable)
    bs.search_points, bs.search_samples, bs.monte_carlo, bs.monte_carlo_seed = search
    return bs


# --------------------------------------------------------------------------- tasks (run in workers)

def evaluate_task(kind: str, points_json: str, options_json: str, mid_json: str, box_json: str,
                  claims: tuple[str, ...], prec: int) -> dict[str, list[str]]:
    """One box: {claim: [status, reason]} (strings in, strings out)."""
    model = _model(kind, points_json, options_json, mid_json)
    box = Box.from_json(json.loads(box_json))
    with working_precision(prec):
        out = boxes_module(kind).evaluate_box(model, box, list(claims))
    return {k: [v[0], v[1]] for k, v in out.items()}


# --------------------------------------------------------------------------- the paving

@dataclass
class ClaimPaving:
    id: str
    statement: str
    boxes: list[tuple[Box, str]] = field(default_factory=list)
    reasons: dict[str, str] = field(default_factory=dict)      # the first reason seen per outcome
    points: list[dict[str, Any]] = field(default_factory=list)  # point proofs at sub-box midpoints
    #: {"counterexample_search": ..., "monte_carlo": ...} when the scene asks (:mod:`.counterexamples`)
    search: dict[str, Any] = field(default_factory=dict)

    def volume(self, whole: Box) -> dict[str, Fraction]:
        total = whole.volume()
        v = {"proved": Fraction(0), "refuted": Fraction(0), "undecided": Fraction(0)}
        for b, s in self.boxes:
            v[s] += b.volume() / total
        return v

    @property
    def status(self) -> str:
        if any(p["status"] == "refuted" for p in self.points) or any(s == "refuted" for _, s in self.boxes) \
                or searched_refutation(self.search):
            return "refuted"
        if self.boxes and all(s == "proved" for _, s in self.boxes):
            return "proved"
        return "inconclusive"


@dataclass
class Paving:
    bs: BoxScene
    claims: list[ClaimPaving]
    evaluated: int
    levels: int
    budget_hit: bool
    seconds: float = 0.0
    executor: str = ""
    #: why the paving stopped before its resolution (the time limit), or "" when it ran its course
    stopped: str = ""
    #: the tiles and points of the quantities' ranges (:mod:`.ranges`), None when the kind has none
    ranges: Any = None
    #: the groups still queued when it stopped (:mod:`.order`), best first: undecided leaves of their claims
    pending: list = field(default_factory=list)

    @property
    def verdict(self) -> str:
        st = [c.status for c in self.claims]
        return "refuted" if "refuted" in st else "proved" if all(s == "proved" for s in st) else "inconclusive"

    @property
    def exit_code(self) -> int:
        return {"proved": 0, "refuted": 1, "inconclusive": 3}[self.verdict]


@dataclass
class PaveState:
    """Where a paving stands between two batches (:mod:`.resume` rebuilds it from a partial paving): per
    claim the leaves so far (decided, or undecided at the resolution or the ``max_boxes`` cap) in the order
    they were evaluated and the first reason per outcome; the queued groups (:mod:`.order`); the boxes
    created toward ``max_boxes`` (evaluated and queued), the boxes evaluated, the levels (the deepest box
    evaluated, plus one) and whether ``max_boxes`` left a box unsplit."""

    result: dict[str, ClaimPaving]
    frontier: Frontier
    created: int = 1
    evaluated: int = 0
    levels: int = 0
    budget_hit: bool = False


def start_state(bs: BoxScene) -> PaveState:
    """A paving about to start: the whole box queued for every claim."""
    statements = bs.box_statements
    result = {c: ClaimPaving(c, "For every parameter value in the box: " + statements[c]) for c in bs.claims}
    return PaveState(result, Frontier(bs.priority, [Group((bs.box,), tuple(bs.claims))]), created=1)


#: the reasons a run stops before its course, beside the time limit's (:class:`~rigor_gyro.core.deadline.Budget`)
INTERRUPTED = "interrupted (Ctrl-C)"
CHECKPOINT = ("checkpoint after {n} box evaluations, the run still going (if it was killed, "
              "`rigor-gyro prove --resume` continues from here)")


def box_budget_reason(n: int) -> str:
    return f"box budget of {n} evaluations reached (--box-budget)"


@contextlib.contextmanager
def _deferred_interrupt():
    """Hold Ctrl-C (SIGINT) while the state is updated: yields a list that is non-empty if one arrived."""
    got: list = []
    if threading.current_thread() is not threading.main_thread():
        yield got
        return
    old = signal.signal(signal.SIGINT, lambda signum, frame: got.append(signum))
    try:
        yield got
    finally:
        signal.signal(signal.SIGINT, old)


def _commit(bs: BoxScene, st: PaveState, batch: list[Group], outs: list[dict]) -> None:
    """Record a batch's evaluations: decided claims become leaves; an undecided box is split (its halves
    queued with the claims still open) unless it is fine at the resolution or ``max_boxes`` would be
    exceeded, then it is an undecided leaf (a budget never refutes)."""
    whole, i = bs.box, 0
    for g in batch:
        gouts = outs[i:i + len(g.boxes)]
        i += len(g.boxes)
        for j, b in enumerate(g.boxes):
            out = gouts[j]
            sibling = gouts[1 - j] if len(g.boxes) == 2 else None
            st.levels = max(st.levels, volume_depth(whole, b) + 1)
            undecided = []
            for c in g.claims:
                status, reason = out[c]
                st.result[c].reasons.setdefault(status, reason)
                if status == "undecided":
                    undecided.append(c)
                else:
                    st.result[c].boxes.append((b, status))
            if not undecided:
                continue
            fine = all(w <= bs.resolution for n, w in b.relative_widths(whole).items() if n not in bs.frozen)
            if fine or st.created + 2 > bs.max_boxes:
                st.budget_hit = st.budget_hit or not fine
                for c in undecided:
                    st.result[c].boxes.append((b, "undecided"))
            else:
                near = 0 if sibling is None else sum(1 for c in undecided if sibling[c][0] != "undecided")
                score = max(near, g.score - 1)          # the boundary priority's (:mod:`.order`)
                st.frontier.push(Group(b.split(whole, bs.frozen), tuple(undecided), score))
                st.created += 2
        st.evaluated += len(g.boxes)


def searched_refutation(search: dict[str, Any]) -> bool:
    """Whether a claim's counterexample search holds a certified counterexample (a point proof refuted)."""
    found = search.get("counterexample_search") or {}
    return any(p.get("status") == "refuted" for p in found.get("proofs", []) if isinstance(p, dict))


def _snapshot(bs: BoxScene, st: PaveState, stopped: str, seconds: float, label: str, ranges=None,
              searches: dict[str, dict[str, Any]] | None = None) -> Paving:
    """The paving as it stands: the leaves, and when ``stopped``, the queued boxes as undecided leaves of
    their open claims (pending; the claim's undecided reason is then ``stopped``)."""
    pending = st.frontier.groups() if stopped else []
    claims = []
    for c, cp in st.result.items():
        boxes = list(cp.boxes) + [(b, "undecided") for g in pending if c in g.claims for b in g.boxes]
        reasons = dict(cp.reasons)
        if any(c in g.claims for g in pending):
            reasons["undecided"] = stopped
        claims.append(ClaimPaving(cp.id, cp.statement, boxes, reasons, list(cp.points),
                                  dict((searches or {}).get(cp.id, {}))))
    return Paving(bs, claims, st.evaluated, st.levels, st.budget_hit or bool(stopped), seconds, label, stopped,
                  ranges, pending)


def pave(bs: BoxScene, executor: Executor | None = None, progress=None, time_limit: float | None = None, *,
         box_budget: int | None = None, state: PaveState | None = None, checkpoint=None,
         checkpoint_every: float | None = None, keep_on_interrupt: bool = False) -> Paving:
    """The paving of ``bs.box`` for each of ``bs.claims`` (see the module docstring), best first in
    ``bs.priority`` (:mod:`.order`), in batches. It stops when ``time_limit`` (seconds) has run out (a batch
    evaluated in process is interrupted by the alarm and left pending; a pool's batches in flight finish), and
    between batches when this run has evaluated ``box_budget`` boxes or more, or on Ctrl-C (or a broken executor,
    whose batch in flight is left unevaluated): the queued boxes are then *pending* (undecided leaves of
    their open claims, listed in ``pending``), no point proof is run and the paving is a valid partial
    certificate (its decided leaves stand; a budget never refutes) that :mod:`.resume` continues exactly.
    ``state`` (from :mod:`.resume`) continues a partial paving instead of starting at the whole box.
    ``checkpoint(paving)`` is called with such a partial paving (reason: :data:`CHECKPOINT`) every
    ``checkpoint_every`` seconds while work remains (a run killed then resumes from the last one).
    Ctrl-C: with ``keep_on_interrupt`` (the command line) the paving so far is returned (stopped:
    :data:`INTERRUPTED`); otherwise KeyboardInterrupt propagates, as from any library call."""
    p = _pave(bs, executor, progress, time_limit, box_budget, state, checkpoint, checkpoint_every)
    if p.stopped == INTERRUPTED and not keep_on_interrupt:
        raise KeyboardInterrupt
    return p


def _pave(bs: BoxScene, executor, progress, time_limit, box_budget, state, checkpoint, checkpoint_every) -> Paving:
    """:func:`pave`, returning the paving so far on Ctrl-C."""
    budget = Budget(check_time_limit(time_limit))
    t0 = time.perf_counter()
    ex = executor or Executor(1)
    whole = bs.box
    pj = json.dumps(bs.points, sort_keys=True)
    oj = settings_json(bs.options, bs.scene.model)
    mj = json.dumps({k: fraction_text(q) for k, q in whole.midpoint().items()}, sort_keys=True)
    st = state if state is not None else start_state(bs)
    stopped, run, last = "", 0, time.monotonic()
    if getattr(ex, "parallel", False) and st.frontier.priority == "volume" and len(st.frontier):
        from .stream import stream_pave     # no barrier between levels; the same certificate (:mod:`.stream`)
        hooks = SimpleNamespace(_commit=_commit, _deferred_interrupt=_deferred_interrupt, INTERRUPTED=INTERRUPTED,
                                CHECKPOINT=CHECKPOINT, box_budget_reason=box_budget_reason)
        stopped = stream_pave(bs, st, ex, (evaluate_task, bs.scene.kind, pj, oj, mj, bs.prec), hooks,
                              budget=budget, box_budget=box_budget,
                              progress=progress, checkpoint=checkpoint, checkpoint_every=checkpoint_every,
                              snapshot=lambda why: _snapshot(bs, st, why, time.perf_counter() - t0, ex.label))
    while len(st.frontier) and not stopped:
        batch = st.frontier.pop_batch()
        items = [(g, b) for g in batch for b in g.boxes]
        tasks = [(bs.scene.kind, pj, oj, mj, json.dumps(b.to_json()), g.claims, bs.prec) for g, b in items]
        try:
            # in process (one worker, or fewer boxes than workers: the whole box) a batch can take minutes:
            # the alarm interrupts it at the time limit and the batch is left pending
            with until(budget) if ex.runs_here(len(tasks)) else contextlib.nullcontext():
                outs = ex.map(evaluate_task, tasks)
        except TimeLimitReached:
            if not budget.fired:        # an outer alarm (a checker's --time-limit), not this paving's limit
                raise
            st.frontier.restore_batch()
            stopped = budget.reason()
            break
        except KeyboardInterrupt:
            st.frontier.restore_batch()
            stopped = INTERRUPTED
            break
        except BrokenExecutor as e:
            st.frontier.restore_batch()
            stopped = f"the executor broke ({type(e).__name__}: {e}); the batch in flight was left pending"
            break
        with _deferred_interrupt() as interrupted:
            _commit(bs, st, batch, outs)
            run += len(items)
            if progress:
                progress(st.evaluated, len(st.frontier), st.result)
        if interrupted:
            stopped = INTERRUPTED
        elif len(st.frontier) and budget.expired():
            stopped = budget.reason()
        elif len(st.frontier) and box_budget is not None and run >= box_budget:
            stopped = box_budget_reason(box_budget)
        elif len(st.frontier) and checkpoint is not None and checkpoint_every is not None \
                and time.monotonic() - last >= checkpoint_every:
            with _deferred_interrupt() as interrupted:
                checkpoint(_snapshot(bs, st, CHECKPOINT.format(n=st.evaluated), time.perf_counter() - t0, ex.label))
            last = time.monotonic()
            stopped = INTERRUPTED if interrupted else ""
    if stopped:
        return _snapshot(bs, st, stopped, time.perf_counter() - t0, ex.label)
    result = st.result
    try:
        # point proofs at midpoints: refuted boxes (re-checkable counterexamples) and undecided boxes
        ptasks, owners = [], []
        for c, cp in result.items():
            for outcome in ("refuted", "undecided"):
                for b, s in spread([x for x in cp.boxes if x[1] == outcome], bs.max_points):
                    params = bs.point_parameters(b.midpoint())
                    ptasks.append((bs.scene.kind, json.dumps(params, sort_keys=True), oj, c, bs.point_prec,
                                   bs.point_maxprec))
                    owners.append((c, b, outcome, params))
        points = ex.map(point_task, ptasks)
    except KeyboardInterrupt:       # the leaves are complete; the point proofs are not run
        return _snapshot(bs, st, INTERRUPTED, time.perf_counter() - t0, ex.label)
    for (c, b, outcome, params), res in zip(owners, points):
        if outcome == "refuted" and res["status"] == "proved":   # a box refuted everywhere, proved at a point
            raise AssertionError(f"claim {c}: box {b.to_json()} refuted for every parameter, but its midpoint "
                                 f"is proved: an unsound box or point evaluation")
        result[c].points.append({"box_outcome": outcome, "point": params, **res})
    searches = None
    if bs.searches():
        from .counterexamples import paving_searches
        try:
            searches = paving_searches(bs, [st.result[c] for c in bs.claims], bs.search_points,
                                       bs.search_samples or None, bs.monte_carlo, bs.monte_carlo_seed,
                                       executor=ex, budget=budget)
        except KeyboardInterrupt:
            for cp in result.values():
                cp.points = []
            return _snapshot(bs, st, INTERRUPTED, time.perf_counter() - t0, ex.label)
    ranges = None
    qmod = quantities_module(bs.scene.kind)
    if qmod is not None and bs.range_boxes:
        try:
            ranges = search_ranges(bs.scene.kind, whole, bs.frozen, pj, oj, mj, bs.prec,
                                   list(quantity_specs(bs.scene.kind, pj, oj, mj)),
                                   bs.range_boxes, bs.range_gap, ex, budget)
        except TimeLimitReached:        # the whole box's evaluation outlasted the limit: the claims stand, no ranges
            if not budget.fired:
                raise
            ranges = None
        except KeyboardInterrupt:
            for cp in result.values():
                cp.points = []
            return _snapshot(bs, st, INTERRUPTED, time.perf_counter() - t0, ex.label)
    return _snapshot(bs, st, "", time.perf_counter() - t0, ex.label, ranges, searches)
