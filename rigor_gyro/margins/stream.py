"""The streaming frontier: a paving's boxes evaluated on a pool or a Dask cluster with no barrier between
levels, the results committed in the canonical order, so that the paving is byte-identical whatever the
executor, the worker count and the timing.

:func:`.paving.pave` evaluates the queue (:mod:`.order`) batch by batch: each batch is the best groups up
to :data:`.order.BATCH` boxes, evaluated, then committed (leaves recorded, undecided boxes split and their
halves queued). On N workers that is a barrier per batch: the last, slowest boxes of a level leave the
other workers idle. Here, instead:

* **Dispatch.** Workers are kept busy with small batches of boxes (sized from the measured cost of a box
  to about :data:`TARGET_SECONDS` of work on a pool, :data:`DASK_TARGET_SECONDS` on Dask, never more than an even share of what is available): first
  the queued groups in the queue's order (taken from :class:`~.order.Frontier` ahead of their commit),
  then *speculative* boxes: the halves of a box whose result arrived but is not yet committed (it is
  undecided and coarser than the resolution, so it will be split unless ``max_boxes`` forbids it); and
  when a worker would idle, the halves of a box still in flight, as if it stays undecided (the first
  levels of a paving have fewer boxes than workers).
  The scene travels to each Dask worker once (``Executor.share``); a task carries only box edges.
* **Commit.** Results are kept by (box, claims) and committed group by group strictly in the queue's
  order, each commit exactly :func:`.paving._commit` of that group, as the batched loop does. For the
  ``volume`` priority every group queued by a commit comes after every group already queued (its boxes
  are smaller, or as large and later), so the groups taken ahead are in the final order, and the commits
  are those of the batched loop in the same order: the same leaves, order, reasons, splits (``max_boxes``
  counts in commit order) and pending list. A speculative result is used only when the commit queues
  that box with those claims; otherwise it is dropped (work lost, never a verdict).
* **Stops.** The batched loop's batches are tracked as *virtual batches* (the groups it would have popped
  at once; computed at each boundary from the queue); a box budget (``--box-budget``) and the progress
  report act at their boundaries, so a budgeted partial paving is byte-identical to the batched loop's.
  A time limit, a checkpoint, Ctrl-C or a broken executor act after the current commit: the groups not
  committed (in flight, done out of order, or queued) are put back in the queue with their places, as
  pending, and the partial paving resumes to the uninterrupted one (:mod:`.resume`).

Used for the ``volume`` priority on a parallel executor; the ``boundary`` priority scores a group by its
sibling's result and may queue a group ahead of those taken, so it keeps the batched loop (its barrier).

Guarantee: the same certificate as the batched loop (tests/test_paving_stream.py, pool and in process);
timing decides only how fast. Fails when: a task raises (the exception propagates, as from ``map``).
"""
from __future__ import annotations

import json
import time
from collections import deque
from itertools import islice
from concurrent.futures import BrokenExecutor

from ..core.deadline import TimeLimitReached, until
from .order import BATCH

__all__ = ["stream_pave", "evaluate_batch", "TARGET_SECONDS", "DASK_TARGET_SECONDS", "MAX_BATCH"]

#: the work a dispatched batch aims at on a process pool (its per-task cost is 0.1-2 ms)
TARGET_SECONDS = 0.05
#: on Dask: a task's round trip through the scheduler costs more, and on a machine with as many cores as
#: workers the scheduler competes with them (measured idle on 2 cores, margin_rudenko_all_tolerance, 2047
#: boxes of ~9 ms: 0.05 s batches 13.1 s, 0.2 s 11.0 s, 0.5 s 10.7 s, one process 18.5 s; the pool 10.0 s
#: at 0.05 and 9.8 s at 0.2)
DASK_TARGET_SECONDS = 0.25
#: boxes in one dispatched batch at most
MAX_BATCH = 256


def evaluate_batch(scene: tuple, items: list) -> list:
    """In a worker: each (box JSON, claims) of ``items`` evaluated on the scene ``(evaluate, kind, points
    JSON, settings JSON, midpoint JSON, prec)`` by ``evaluate`` (:func:`.paving.evaluate_task`, a
    module-level function: it travels by name); [(outcome, seconds)] in order."""
    evaluate, kind, pj, oj, mj, prec = scene
    out = []
    for box_json, claims in items:
        t0 = time.perf_counter()
        res = evaluate(kind, pj, oj, mj, box_json, tuple(claims), prec)
        out.append((res, time.perf_counter() - t0))
    return out


def _wanted(bs, box, claims, out) -> tuple | None:
    """The claims a box's halves would be queued with (undecided, box coarser than the resolution)."""
    undecided = tuple(c for c in claims if out[c][0] == "undecided")
    if not undecided:
        return None
    fine = all(w <= bs.resolution for n, w in box.relative_widths(bs.box).items() if n not in bs.frozen)
    return None if fine else undecided


def stream_pave(bs, st, ex, scene: tuple, paving, *, budget, box_budget, progress, checkpoint, checkpoint_every,
                snapshot) -> str:
    """Run the paving state ``st`` to its end or a stop on the parallel executor ``ex`` (see the module
    docstring); returns why it stopped ("" when it ran its course). ``scene`` as :func:`evaluate_batch`
    takes it; ``paving``: the paving's own pieces (``_commit``, ``_deferred_interrupt``, ``INTERRUPTED``,
    ``CHECKPOINT``, ``box_budget_reason``; passed in, not imported: :mod:`.paving` imports this module);
    ``snapshot(stopped)`` is the paving for a checkpoint."""
    frontier = st.frontier
    shared: list = []               # the scene as sent to the workers (once, at the first submit)
    queue: deque = deque()          # (key, group) taken from the frontier, not committed, in the queue's order
    taken = 0                       # queue[:taken] have every box dispatched or known
    results: dict = {}              # (edges, claims) -> outcome
    running: set = set()            # (edges, claims) in flight
    inflight: dict = {}             # future -> [(box, claims)]
    spec: deque = deque()           # speculative (box, claims)
    committed: set = set()          # (edges, claims) committed (a stale speculative entry is skipped)
    presplit: set = set()           # (edges, claims) in flight whose halves were queued before the result
    cost, ncost = 0.0, 0
    target = DASK_TARGET_SECONDS if getattr(ex, "scheduler", None) is not None else TARGET_SECONDS
    run, vb_left, last = 0, 0, time.monotonic()
    stopped = ""

    def key_of(b, claims):
        return (b.edges, claims)

    def extend() -> bool:
        item = frontier.pop_item()
        if item is None:
            return False
        queue.append(item)
        return True

    def start_virtual_batch() -> int:
        """Groups in the batched loop's next batch (at least one), from the queue's order."""
        n, k = 0, 0
        while True:
            if k == len(queue) and not extend():
                return k
            size = len(queue[k][1].boxes)
            if k and n + size > BATCH[frontier.priority]:
                return k
            n, k = n + size, k + 1

    def canonical_items(limit: int) -> list:
        nonlocal taken
        items = []
        while len(items) < limit:
            if taken == len(queue):
                if box_budget is not None and vb_left <= taken and \
                        run + sum(len(g.boxes) for _, g in islice(queue, vb_left)) >= box_budget:
                    break                       # the budget stops the paving at this batch's end
                if not extend():
                    break
            g = queue[taken][1]
            for b in g.boxes:
                k = key_of(b, g.claims)
                if k not in results and k not in running:
                    if len(items) == limit:
                        return items            # a group's boxes may go to two workers
                    items.append((b, g.claims))
                    running.add(k)
            taken += 1
        return items

    def dispatch() -> None:
        while len(inflight) < 2 * ex.workers:
            avail = len(frontier) + sum(len(g.boxes) for _, g in islice(queue, taken, None)) + len(spec)
            per = target / (cost / ncost) if ncost and cost > 0 else 1
            size = int(max(1, min(per, MAX_BATCH, -(-avail // ex.workers))))
            items = canonical_items(size)
            while len(items) < size and spec and box_budget is None:
                b, claims = spec.popleft()
                k = key_of(b, claims)
                if k not in results and k not in running and k not in committed:
                    items.append((b, claims))
                    running.add(k)
            if not items and box_budget is None and len(inflight) < ex.workers and presplit_one():
                continue                        # an idle worker: a box in flight's halves, before its result
            if not items:
                return
            payload = [(json.dumps(b.to_json()), list(c)) for b, c in items]
            if not inflight and len(items) == 1 and avail <= 1:
                # one box and nothing else to do (the whole box, a paving of one box): here, as ``map``
                # does with fewer tasks than workers, not a round trip to a worker
                with until(budget):             # minutes for a hard whole box: the alarm ends it at the limit
                    outs = evaluate_batch(scene, payload)
                record(items, outs)
                return
            if not shared:
                shared.append(ex.share(scene))
            inflight[ex.submit(evaluate_batch, shared[0], payload)] = items

    def presplit_one() -> bool:
        """Queue as speculative the halves of the oldest box in flight not yet so split (with its claims,
        as if it stays undecided on all): work for a worker that would idle; used only if it comes true."""
        for items in inflight.values():
            for b, claims in items:
                k = key_of(b, claims)
                if k in presplit or _wanted(bs, b, claims, {c: ("undecided",) for c in claims}) is None:
                    continue
                presplit.add(k)
                if st.created + 2 <= bs.max_boxes:
                    spec.extend((h, claims) for h in b.split(bs.box, bs.frozen))
                    return True
        return False

    def record(items, outs) -> None:
        nonlocal cost, ncost
        for (b, claims), (out, seconds) in zip(items, outs):
            k = key_of(b, claims)
            running.discard(k)
            results[k] = out
            cost, ncost = cost + seconds, ncost + 1
            undecided = _wanted(bs, b, claims, out)
            if undecided is not None and st.created + 2 <= bs.max_boxes:
                spec.extend((h, undecided) for h in b.split(bs.box, bs.frozen))

    def receive(timeout) -> None:
        for f in ex.wait_any(list(inflight), timeout):
            items = inflight.pop(f)
            record(items, ex.result(f))

    def ready(g) -> bool:
        return all(key_of(b, g.claims) in results for b in g.boxes)

    vb_left = start_virtual_batch()
    try:
        while queue or len(frontier):
            dispatch()
            if not (queue and ready(queue[0][1])):
                if not inflight and not (queue and ready(queue[0][1])):
                    raise RuntimeError("streaming paving: the next group to commit was never dispatched")
                left = budget.remaining()
                receive(None if left is None else max(0.01, min(1.0, left)))
            while queue and ready(queue[0][1]) and not stopped:
                _, g = queue.popleft()
                taken = max(0, taken - 1)        # the head may be ready unseen (speculative results)
                outs = [results.pop(key_of(b, g.claims)) for b in g.boxes]
                committed.update(key_of(b, g.claims) for b in g.boxes)
                with paving._deferred_interrupt() as interrupted:
                    paving._commit(bs, st, [g], outs)
                run += len(g.boxes)
                vb_left -= 1
                if vb_left == 0:
                    if progress:
                        progress(st.evaluated, len(frontier) + sum(len(x.boxes) for _, x in queue), st.result)
                    more = bool(queue) or bool(len(frontier))
                    if more and box_budget is not None and run >= box_budget:
                        stopped = paving.box_budget_reason(box_budget)
                    vb_left = start_virtual_batch()
                more = bool(queue) or bool(len(frontier))
                if interrupted:
                    stopped = paving.INTERRUPTED
                elif more and not stopped and budget.expired():
                    stopped = budget.reason()
                elif more and not stopped and checkpoint is not None and checkpoint_every is not None \
                        and time.monotonic() - last >= checkpoint_every:
                    frontier.put_back(queue)
                    try:
                        with paving._deferred_interrupt() as interrupted:
                            checkpoint(snapshot(paving.CHECKPOINT.format(n=st.evaluated)))
                    finally:
                        for _ in range(len(queue)):
                            frontier.pop_item()     # the same items, best first: the queue again
                    last = time.monotonic()
                    stopped = paving.INTERRUPTED if interrupted else ""
            if stopped:
                break
            if not budget.expired() or not (queue or len(frontier)):
                continue
            stopped = budget.reason()
            break
    except TimeLimitReached:
        if not budget.fired:            # an outer alarm (a checker's --time-limit), not this paving's limit
            raise
        stopped = budget.reason()
    except KeyboardInterrupt:
        stopped = paving.INTERRUPTED
    except BrokenExecutor as e:
        stopped = f"the executor broke ({type(e).__name__}: {e}); the batches in flight were left pending"
    for f in inflight:
        f.cancel()
    frontier.put_back(queue)
    return stopped
