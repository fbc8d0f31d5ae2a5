"""Checker time against proving time, per built-in scene. Prints a table; asserts nothing.

    python benchmarks/check_vs_prove.py [--repeat 3]

Each time is the best of ``--repeat`` runs in one process (imports excluded): proving the scene, then
re-verifying its certificate with ``rigor-gyro check``'s :func:`rigor_gyro.check.check_certificate`.
"""
from __future__ import annotations

import argparse
import json
import time

from rigor_gyro import builtin_scenes, load_scene, prove_scene
from rigor_gyro.check import check_certificate


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    print(f"| scene | prove (s) | check (s) | check / prove | confirmed |")
    print("|---|---|---|---|---|")
    for name in builtin_scenes():
        scene = load_scene(name)
        tp, tc, data, ok = float("inf"), float("inf"), None, None
        for _ in range(args.repeat):
            t = time.perf_counter()
            data = json.loads(json.dumps(prove_scene(scene).to_json()))
            tp = min(tp, time.perf_counter() - t)
        for _ in range(args.repeat):
            t = time.perf_counter()
            ok = check_certificate(data).ok
            tc = min(tc, time.perf_counter() - t)
        print(f"| {name} | {tp:.3f} | {tc:.3f} | {tc / tp:.2f} | {ok} |")


if __name__ == "__main__":
    main()
