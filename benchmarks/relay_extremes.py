"""The relay stabiliser at large H: time, roots, pieces and precision of a cold proof, H = 1e3 .. 1e7, for
both readings of B (the printed B = 0.133 and B = 2/15). Prints a Markdown table; asserts nothing.

    python benchmarks/relay_extremes.py [--H 1e3,1e4,1e5,1e6,1e7] [--time-limit 120] [--repeat 1]

Each row is one `rigor-gyro prove SCENE -o TMP -q` in a child process (a cold start, imports included) on a
scene written to a temporary folder: roitenberg1947 (or roitenberg1947_b2over15) with only H changed. The
columns: user CPU of the child (s, median of --repeat runs), its wall time, the verdict, the half_period claim's
status, roots, pieces, pieces per root, and the precisions tried (the last one is where it was decided). Below
the table: the growth exponent of the user time in H (least-squares slope of log time against log H, per B
reading, over the rows whose half_period claim was decided). Timing lives here, never in the tests.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENE = '''name = "{name}"
kind = "periodic_orbit"
source = """benchmarks/relay_extremes.py: roitenberg1947 with B = {B} and H = {H}"""

[parameters]
A = "125"
B = "{B}"
H = "{H}"
tau = "0.01"
sigma = "0.13125"
n = "50"
K = "7.5"
p = "40"
S = "0.15"
'''

READINGS = (("printed B = 0.133", "0.133"), ("B = 2/15", "2/15"))


def run(path: Path, out: Path, time_limit: float) -> dict:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "rigor_gyro", "prove", str(path), "-o", str(out), "-q", "-j", "1",
           "--time-limit", str(time_limit)]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    user = after.ru_utime - before.ru_utime
    cert = json.loads((out / (path.stem + ".json")).read_text())
    hp = next(c for c in cert["claims"] if c["id"] == "half_period")
    det = hp.get("details", {})
    return {"user": user, "wall": wall, "verdict": cert["verdict"], "half_period": hp["status"],
            "roots": det.get("roots"), "pieces": det.get("pieces"), "precs": cert.get("precisions_tried")}


def slope(xs: list[float], ys: list[float]) -> float:
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--H", default="1e3,1e4,1e5,1e6,1e7")
    ap.add_argument("--time-limit", type=float, default=120.0, help="per scene (rigor-gyro prove --time-limit)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--readings", default="both", choices=("both", "printed", "2/15"))
    a = ap.parse_args()
    Hs = [h.strip() for h in a.H.split(",") if h.strip()]
    readings = [r for r in READINGS if a.readings == "both" or (a.readings == "printed") == (r[1] == "0.133")]
    print(f"python {' '.join(sys.argv)}  (cpus: {os.cpu_count()}, load {os.getloadavg()[0]:.2f})\n")
    print("| B | H | user s | wall s | verdict | half_period | roots | pieces | pieces/root | precisions |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    growth = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for label, B in readings:
            pts = []
            for H in Hs:
                name = f"relay_B{B.replace('/', 'o').replace('.', 'p')}_H_{H}"
                path = tmp / f"{name}.toml"
                path.write_text(SCENE.format(name=name, B=B, H=H))
                rows = [run(path, tmp, a.time_limit) for _ in range(a.repeat)]
                rows.sort(key=lambda r: r["user"])
                r = rows[len(rows) // 2]
                ppr = f"{r['pieces'] / r['roots']:.2f}" if r["roots"] and r["pieces"] else "-"
                print(f"| {label} | {H} | {r['user']:.2f} | {r['wall']:.2f} | {r['verdict']} | {r['half_period']} | "
                      f"{r['roots']} | {r['pieces']} | {ppr} | {r['precs']} |", flush=True)
                if r["half_period"] in ("proved", "refuted"):
                    pts.append((math.log(float(H)), math.log(r["user"])))
            if len(pts) >= 2:
                growth[label] = (slope([p[0] for p in pts], [p[1] for p in pts]), len(pts))
    print()
    for label, (k, n) in growth.items():
        print(f"growth exponent of user time in H, {label}: {k:.2f} (least squares over {n} decided rows)")


if __name__ == "__main__":
    main()
