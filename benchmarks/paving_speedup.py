"""Speed-up of a paving with the worker count, for the process pool and for Dask. Prints a table.

    python benchmarks/paving_speedup.py [--repeat 2] [--scene eigen|lyap] [--executor pool|dask]

Paves two scenes (the eigenfrequency example over eps x Omega2 and a Lyapunov box in k x mu) in process,
on a pool of 1 and 2 workers and on a Dask LocalCluster of 1 and 2 workers, checks that every paving
is identical to the in-process one, and reports the wall time (best of --repeat) and the speed-up
against one worker of the same executor. Start-up of the pool / cluster is excluded (created once).
"""
from __future__ import annotations

import argparse
import time

from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.margins.report import paving_json
from rigor_gyro.scene import parse_scene

SCENES = {
    "eigenfrequencies eps x Omega2 (7167 boxes)": """
name = "bench_eig"
kind = "eigenfrequencies"
source = "benchmark"
[parameters]
a = "15.08"
b = "6.154"
eps = "[0.1, 0.12]"
Omega2 = "[0.6, 0.65]"
[options]
box_resolution = "1/64"
""",
    "lyapunov k x mu (resolution 1/8)": """
name = "bench_lyap"
kind = "lyapunov"
source = "benchmark"
[parameters]
A = "2"
C = "3.3"
A1 = "2.2"
B1 = "2.2"
C1 = "2.8"
A2 = "8.5"
H = "1e4"
k = "[0.05, 1]"
a = "100"
x2_star = "pi/6"
mu = "[0.005, 0.05]"
moment = "sine"
[options]
box_resolution = "1/8"
""",
}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--scene", choices=("eigen", "lyap"), help="only the scene whose label starts so")
    ap.add_argument("--executor", choices=("pool", "dask"), help="only this executor")
    args = ap.parse_args()
    print("| scene | executor | workers | wall s (best) | speed-up vs 1 worker | identical |")
    print("|---|---|---|---|---|---|")
    for label, text in SCENES.items():
        if args.scene and not label.startswith(args.scene):
            continue
        bs = box_scene(parse_scene(text))
        reference = paving_json(pave(bs, Executor(1)))
        for kind, scheduler in (("pool", None), ("dask", "local")):
            if args.executor and kind != args.executor:
                continue
            base = None
            for workers in (1, 2):
                ex = Executor(workers, scheduler) if (workers > 1 or scheduler) else Executor(1)
                if kind == "pool" and workers == 1:
                    ex = Executor(1)
                best, same = float("inf"), True
                for _ in range(args.repeat):
                    t0 = time.perf_counter()
                    data = paving_json(pave(bs, ex))
                    best = min(best, time.perf_counter() - t0)
                    same = same and data == reference
                ex.close()
                base = base or best
                name = "in process" if kind == "pool" and workers == 1 else kind
                print(f"| {label} | {name} | {workers} | {best:.2f} | {base / best:.2f}x | {same} |", flush=True)


if __name__ == "__main__":
    main()
