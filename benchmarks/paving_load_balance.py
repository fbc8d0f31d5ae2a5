"""Simulated load balance of the built-in pavings on N workers. Prints a table.

    python benchmarks/paving_load_balance.py [--scenes NAME ...|--all] [--workers 1,2,4,8,16] [--overhead-ms 0.3]

Each paving runs once in this process with every box evaluation timed (one `Executor.map` call is one
level of the paving). The recorded costs are then scheduled as the process pool would run them: per
level, the tasks cut into `workers * BATCHES_PER_WORKER["pool"]` batches of consecutive tasks, each batch
taken by the first free worker, plus a fixed cost per batch (`--overhead-ms`: pickling and the round
trip), and a barrier at the end of each level (the next level's boxes are the children of this one's).
Columns: the serial time (the sum of the costs), and per N the simulated speed-up serial / makespan, and
the same without the barriers (every level's batches in one queue: what a best-first engine without
levels could reach), and the streaming frontier that a pool or Dask runs (rigor_gyro/margins/stream.py):
a box's halves are ready as soon as its result is in (speculation), a free worker takes the next ready
boxes in the queue's order, as many as make ~50 ms at the mean cost measured so far (at most 256, at
most an even share of the ready boxes), plus the fixed cost per batch; the maps after the paving (point
proofs, searches, ranges) keep their barriers. Speculative work that ``max_boxes`` throws away is not
modelled (it only occurs where the cap is reached); nor are the halves of boxes in flight that the engine
starts when a worker would idle (the replay has them, at the mean box cost where they were never needed). With ``--replay``, a last column per N replays the
paving through the real engine (rigor_gyro/margins/stream.py, unchanged) on a virtual-time executor: each
box's outcome and cost are the recorded ones, a batch runs on the worker free first, plus the fixed cost
per batch; it checks that the replayed paving is the recorded one and gives serial / virtual makespan.
Box costs are CPU seconds of this process (``time.process_time``: little moved by other processes on a
shared machine; ``--wall`` for wall seconds). The simulation decides nothing about a paving; it says
where parallelism is lost.
"""
from __future__ import annotations

import argparse
import heapq
import sys
import time
from pathlib import Path

import json
import math

from rigor_gyro.core.boxes import Box
from rigor_gyro.margins import paving
from rigor_gyro.margins.executors import BATCHES_PER_WORKER, Executor
from rigor_gyro.margins.paving import box_scene, has_tolerances, pave
from rigor_gyro.margins.stream import MAX_BATCH, TARGET_SECONDS
from rigor_gyro.scene import builtin_scenes, load_scene

DEFAULT_SCENES = ["margin_rudenko_brackets_tolerance", "margin_agafonov_k_tolerance", "margin_agafonov_k_mu",
                  "margin_roitenberg_n_tolerance"]


class TimingExecutor(Executor):
    """In process; records the wall time of every task, per map call (a level)."""

    def __init__(self):
        super().__init__(1)
        self.levels: list[list[float]] = []
        self.boxes: list[tuple] = []        # every box evaluation: (box JSON, claims, outcome, seconds)
        self.after: list[list[float]] = []  # the maps after the paving (not box evaluations)

    clock = staticmethod(time.process_time)

    def map(self, fn, tasks):
        costs, out = [], []
        for t in tasks:
            t0 = self.clock()
            out.append(fn(*t))
            costs.append(self.clock() - t0)
        self.levels.append(costs)
        if fn is paving.evaluate_task:
            self.boxes += [(t[4], tuple(t[5]), o, c) for t, o, c in zip(tasks, out, costs)]
        else:
            self.after.append(costs)
        return out


def stream_makespan(bs, boxes: list[tuple], after: list[list[float]], workers: int, overhead: float) -> float:
    """The streaming frontier's simulated makespan (see the module docstring)."""
    index = {(bj, cl): i for i, (bj, cl, _, _) in enumerate(boxes)}
    children: list[list[int]] = [[] for _ in boxes]
    for i, (bj, cl, out, _) in enumerate(boxes):
        und = tuple(c for c in cl if out[c][0] == "undecided")
        if und:
            b = Box.from_json(json.loads(bj))
            for h in b.split(bs.box, bs.frozen):
                j = index.get((json.dumps(h.to_json()), und))
                if j is not None:
                    children[i].append(j)
    ready = [0] if boxes else []        # heap of canonical indices
    events: list = []                   # (finish time, worker, [indices])
    free, t, spent, done = list(range(workers)), 0.0, 0.0, 0
    while ready or events:
        while free and ready:
            mean = spent / done if done else None
            per = TARGET_SECONDS / mean if mean else 1
            size = int(max(1, min(per, MAX_BATCH, math.ceil(len(ready) / workers))))
            take = [heapq.heappop(ready) for _ in range(min(size, len(ready)))]
            alone = not events and len(take) == 1 and not ready      # run in the parent (stream.py)
            heapq.heappush(events, (t + (0 if alone else overhead) + sum(boxes[i][3] for i in take), free.pop(), take))
        t, w, take = heapq.heappop(events)
        free.append(w)
        for i in take:
            spent, done = spent + boxes[i][3], done + 1
            for j in children[i]:
                heapq.heappush(ready, j)
    for lv in after:                    # point proofs, searches, ranges: barriers as before
        t += sum(lv) if len(lv) < workers else _makespan([b + overhead for b in _batches(lv, workers)], workers)
    return t


def _batches(costs: list[float], workers: int) -> list[float]:
    parts = workers * BATCHES_PER_WORKER["pool"]
    size = max(1, len(costs) // parts)
    return [sum(costs[i:i + size]) for i in range(0, len(costs), size)]


def _makespan(jobs: list[float], workers: int) -> float:
    """Jobs in order, each to the first free worker (a shared queue)."""
    free = [0.0] * workers
    for j in jobs:
        heapq.heapreplace(free, free[0] + j)
    return max(free)


def simulate(levels: list[list[float]], workers: int, overhead: float) -> tuple[float, float]:
    """(makespan with a barrier per level, makespan of one queue of every level's batches)."""
    if workers == 1:
        total = sum(sum(lv) for lv in levels)
        return total, total
    barrier, queue = 0.0, []
    for lv in levels:
        if len(lv) < workers:                 # the executor runs these in process (executors.py)
            barrier += sum(lv)
            queue.append(sum(lv))
            continue
        jobs = [b + overhead for b in _batches(lv, workers)]
        barrier += _makespan(jobs, workers)
        queue.extend(jobs)
    return barrier, _makespan(queue, workers)


class VirtualPool(Executor):
    """A parallel executor in virtual time for :func:`replay`: a submitted batch runs at once (recorded
    outcomes), on the worker free first, for its recorded cost plus ``overhead``; ``wait_any`` advances
    the clock to the first finish. Work the caller does between calls (a box run in the parent) advances
    the clock too."""

    def __init__(self, workers: int, overhead: float, counter: list):
        super().__init__(1)
        self.workers, self.overhead, self.counter = workers, overhead, counter
        self.now, self.free, self.finish, self.seen = 0.0, [0.0] * workers, {}, 0.0

    @property
    def parallel(self):
        return True

    def _parent(self):
        self.now += self.counter[0] - self.seen
        self.seen = self.counter[0]

    def submit(self, fn, *args):
        from concurrent.futures import Future
        self._parent()
        f = Future()
        f.set_result(fn(*args))
        cost = self.counter[0] - self.seen
        self.seen = self.counter[0]
        w = min(range(self.workers), key=lambda i: self.free[i])
        self.free[w] = max(self.now, self.free[w]) + cost + self.overhead
        self.finish[f] = self.free[w]
        return f

    def wait_any(self, futures, timeout=None):
        self._parent()
        first = min(self.finish[f] for f in futures)
        self.now = max(self.now, first)
        return [f for f in futures if self.finish[f] <= self.now]


def replay(bs, boxes: list[tuple], after: list[list[float]], workers: int, overhead: float) -> tuple[float, bool]:
    """(virtual makespan of the real streaming engine on ``workers``, whether its leaves are the recorded
    ones); the maps after the paving as in :func:`simulate` (barriers)."""
    import copy
    from rigor_gyro.margins import stream
    from rigor_gyro.margins.report import paving_json
    table = {(bj, tuple(cl)): (out, c) for bj, cl, out, c in boxes}
    counter = [0.0]

    mean = sum(c for *_, c in boxes) / max(1, len(boxes))

    def recorded(kind, pj, oj, mj, box_json, claims, prec):
        # a speculative box the recorded paving never evaluated (its parent was decided): wasted work,
        # costed at the mean box; its outcome is never committed
        out, c = table.get((box_json, tuple(claims)), ({k: ["proved", "not recorded"] for k in claims}, mean))
        counter[0] += c
        return out

    class Clock:                           # the engine's clock for the box costs it measures
        perf_counter = staticmethod(lambda: counter[0])
        monotonic = staticmethod(time.monotonic)

    real_eval, real_time = paving.evaluate_task, stream.time
    paving.evaluate_task, stream.time = recorded, Clock
    try:
        b2 = copy.copy(bs)
        b2.max_points, b2.search_points, b2.monte_carlo = 0, 0, 0
        ex = VirtualPool(workers, overhead, counter)
        got = paving_json(pave(b2, ex))
        ex._parent()
        span = ex.now
        paving.evaluate_task = recorded
        want = paving_json(pave(b2))
    finally:
        paving.evaluate_task, stream.time = real_eval, real_time
    for lv in after:
        span += sum(lv) if len(lv) < workers else _makespan([b + overhead for b in _batches(lv, workers)], workers)
    return span, got["claims"] == want["claims"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=DEFAULT_SCENES)
    ap.add_argument("--all", action="store_true", help="every built-in scene with tolerances")
    ap.add_argument("--workers", default="1,2,4,8,16")
    ap.add_argument("--overhead-ms", type=float, default=0.3, help="fixed cost per batch (default 0.3 ms)")
    ap.add_argument("--replay", action="store_true", help="replay through the real engine in virtual time")
    ap.add_argument("--wall", action="store_true", help="box costs in wall seconds (default: CPU seconds)")
    args = ap.parse_args(argv)
    if args.wall:
        TimingExecutor.clock = staticmethod(time.perf_counter)
    ns = [int(n) for n in args.workers.split(",")]
    if args.all:
        args.scenes = [n for n in builtin_scenes("all") if has_tolerances(load_scene(n))]
    what = "barrier / none / stream" + (" / replay" if args.replay else "")
    print("| paving | boxes | levels | serial s | " + " | ".join(f"N={n} {what}" for n in ns) + " |")
    print("|---|---|---|---|" + "---|" * len(ns))
    for name in args.scenes:
        ex = TimingExecutor()
        bs = box_scene(load_scene(name))
        bs.range_boxes = 0                      # the claims' paving only
        pave(bs, ex)
        serial = sum(sum(lv) for lv in ex.levels)
        cells = []
        for n in ns:
            with_b, without = simulate(ex.levels, n, args.overhead_ms / 1000)
            streamed = stream_makespan(bs, ex.boxes, ex.after, n, args.overhead_ms / 1000) if n > 1 else serial
            cell = f"{serial / with_b:.2f} / {serial / without:.2f} / **{serial / streamed:.2f}**"
            if args.replay:
                span, same = replay(bs, ex.boxes, ex.after, n, args.overhead_ms / 1000) if n > 1 else (serial, True)
                cell += f" / **{serial / span:.2f}**" + ("" if same else " (leaves differ!)")
            cells.append(cell)
        boxes = sum(len(lv) for lv in ex.levels)
        print(f"| {name} | {boxes} | {len(ex.levels)} | {serial:.2f} | " + " | ".join(cells) + " |")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    raise SystemExit(main())
