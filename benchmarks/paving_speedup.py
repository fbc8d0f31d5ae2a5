"""Real speed-up of the built-in pavings on 2 workers (process pool, Dask), paired with one process. Prints a
Markdown table.

    python benchmarks/paving_speedup.py [--all | --scenes NAME ...] [--executors pool,dask] [--repeat 1]
                                        [--workers 2] [--skip NAME ...] [--simulate 2,4,8]

Per scene: the paving in this process (one worker: the batched loop), then on a pool of ``--workers``
processes (the streaming frontier, rigor_gyro/margins/stream.py) and on a Dask LocalCluster of as many
worker processes, interleaved (1, N, N, 1, ... for ``--repeat`` pairs), each paving compared byte for byte
with the in-process one (`identical`). Columns: wall seconds (median) per executor; the speed-up, the
median of the paired ratios wall(1) / wall(N) (pairs run back to back, so load from other processes
mostly cancels); the CPU ratio, user+system CPU of the parent and the pool's workers over the in-process
run's (the work the pool adds: pickling, model builds per worker, speculative boxes); the load average
over the run. The pool and the cluster are started outside the timing (a pool forks its workers lazily:
that is inside). A paving is the ``pave`` call: box evaluations, point proofs, the scene's searches; the
quantities' ranges only with ``--ranges`` (as in paving_load_balance.py: they are a separate search, and
take a minute on some one-box scenes). With ``--simulate 2,4,8`` the same scenes' load balance follows, simulated
up to those worker counts with the real engine replayed in virtual time (benchmarks/paving_load_balance.py).
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import sys
import time
from pathlib import Path

from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.paving import box_scene, has_tolerances, pave
from rigor_gyro.margins.report import paving_json
from rigor_gyro.scene import builtin_scenes, load_scene, parse_scene

#: beside the built-in scenes: the eigenfrequency example over eps x Omega2 at 1/64 (about 7000 boxes of
#: about 1 ms: the grain where the per-task cost of a pool or a scheduler shows)
EXTRA = {"bench_eig_1ms": """
name = "bench_eig_1ms"
kind = "eigenfrequencies"
source = "benchmark"
[parameters]
a = "15.08"
b = "6.154"
eps = "[0.1, 0.12]"
Omega2 = "[0.6, 0.65]"
[options]
box_resolution = "1/64"
"""}


def _cpu() -> float:
    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def _run(bs, make) -> tuple[float, float, str]:
    """(wall, CPU of this process and its finished children, paving JSON) of one paving on a fresh executor."""
    ex = make()
    if ex._client is not None:             # the cluster's workers up before the clock starts
        ex._client.wait_for_workers(ex.workers)
    c0, t0 = _cpu(), time.perf_counter()
    data = json.dumps(paving_json(pave(bs, ex)), sort_keys=True)
    wall = time.perf_counter() - t0
    ex.close()                             # the pool's workers finish: their CPU is counted
    return wall, _cpu() - c0, data


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", nargs="+", default=["margin_rudenko_brackets_tolerance"])
    ap.add_argument("--all", action="store_true", help="every built-in scene with tolerances")
    ap.add_argument("--skip", nargs="*", default=[])
    ap.add_argument("--executors", default="pool,dask")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--ranges", action="store_true", help="the quantities' ranges too")
    ap.add_argument("--repeat", type=int, default=1, help="pairs per executor (default 1)")
    ap.add_argument("--simulate", default=None, metavar="N,N,...",
                    help="then the simulated load balance of the same scenes up to these worker counts, with the "
                         "real engine replayed in virtual time (benchmarks/paving_load_balance.py --replay)")
    args = ap.parse_args(argv)
    names = [n for n in builtin_scenes("all") if has_tolerances(load_scene(n))] if args.all else args.scenes
    names = [n for n in names if n not in args.skip]
    kinds = args.executors.split(",")
    n = args.workers
    print("| paving | boxes | 1 process s | " + " | ".join(f"{k} N={n} s | speed-up | CPU ratio | identical"
                                                            for k in kinds) + " | load |")
    print("|---|---|---|" + "---|---|---|---|" * len(kinds) + "---|")
    for name in names:
        bs = box_scene(parse_scene(EXTRA[name]) if name in EXTRA else load_scene(name))
        if not args.ranges:
            bs.range_boxes = 0
        load0 = os.getloadavg()[0]
        ones, cells, boxes = [], [], None
        for k in kinds:
            scheduler = "local" if k == "dask" else None
            walls, ratios, cpus, same = [], [], [], True
            for i in range(args.repeat):
                order = (False, True) if i % 2 == 0 else (True, False)
                got = {}
                for parallel in order:
                    got[parallel] = _run(bs, (lambda: Executor(n, scheduler)) if parallel else (lambda: Executor(1)))
                (w1, c1, d1), (wn, cn, dn) = got[False], got[True]
                ones.append(w1)
                walls.append(wn)
                ratios.append(w1 / wn)
                cpus.append(cn / c1 if k == "pool" else float("nan"))
                same = same and d1 == dn
                boxes = json.loads(d1)["boxes_evaluated"]
            cpu = statistics.median(cpus)
            cells.append(f"{statistics.median(walls):.2f} | **{statistics.median(ratios):.2f}x** | "
                         f"{'-' if cpu != cpu else f'{cpu:.2f}'} | {same}")
        load = (load0 + os.getloadavg()[0]) / 2
        print(f"| {name} | {boxes} | {statistics.median(ones):.2f} | " + " | ".join(cells) + f" | {load:.1f} |",
              flush=True)
    if args.simulate:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        import paving_load_balance
        print()
        return paving_load_balance.main(["--replay", "--workers", args.simulate, "--scenes", *names])
    return 0


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    raise SystemExit(main())
