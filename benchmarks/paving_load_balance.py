"""Simulated load balance of the built-in pavings on N workers. Prints a table.

    python benchmarks/paving_load_balance.py [--scenes NAME ...] [--workers 1,2,4,8,16] [--overhead-ms 0.3]

Each paving runs once in this process with every box evaluation timed (one `Executor.map` call is one
level of the paving). The recorded costs are then scheduled as the process pool would run them: per
level, the tasks cut into `workers * BATCHES_PER_WORKER["pool"]` batches of consecutive tasks, each batch
taken by the first free worker, plus a fixed cost per batch (`--overhead-ms`: pickling and the round
trip), and a barrier at the end of each level (the next level's boxes are the children of this one's).
Columns: the serial time (the sum of the costs), and per N the simulated speed-up serial / makespan, and
the same without the barriers (every level's batches in one queue: what a best-first engine without
levels could reach). The simulation decides nothing about a paving; it says where parallelism is lost.
"""
from __future__ import annotations

import argparse
import heapq
import sys
import time
from pathlib import Path

from rigor_gyro.margins.executors import BATCHES_PER_WORKER, Executor
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.scene import load_scene

DEFAULT_SCENES = ["margin_rudenko_brackets_tolerance", "margin_agafonov_k_tolerance", "margin_agafonov_k_mu",
                  "margin_roitenberg_n_tolerance"]


class TimingExecutor(Executor):
    """In process; records the wall time of every task, per map call (a level)."""

    def __init__(self):
        super().__init__(1)
        self.levels: list[list[float]] = []

    def map(self, fn, tasks):
        costs, out = [], []
        for t in tasks:
            t0 = time.perf_counter()
            out.append(fn(*t))
            costs.append(time.perf_counter() - t0)
        self.levels.append(costs)
        return out


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


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=DEFAULT_SCENES)
    ap.add_argument("--workers", default="1,2,4,8,16")
    ap.add_argument("--overhead-ms", type=float, default=0.3, help="fixed cost per batch (default 0.3 ms)")
    args = ap.parse_args(argv)
    ns = [int(n) for n in args.workers.split(",")]
    print("| paving | boxes | levels | serial s | " + " | ".join(f"N={n} (no barrier)" for n in ns) + " |")
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
            cells.append(f"{serial / with_b:.2f} ({serial / without:.2f})")
        boxes = sum(len(lv) for lv in ex.levels)
        print(f"| {name} | {boxes} | {len(ex.levels)} | {serial:.2f} | " + " | ".join(cells) + " |")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    raise SystemExit(main())
