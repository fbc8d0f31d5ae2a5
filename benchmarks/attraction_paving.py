"""Prove, check and draw the slice paving of the domain of attraction (issue 40, part 2b). Prints a summary.

    python benchmarks/attraction_paving.py [--scene benchmarks/scenes/gimbal_attraction_paving.toml] [--out DIR]
                                           [--no-check]

Proves the scene (natural_sublevel, then attraction_paving: every box of the slice x2 = 0 integrated by the
validated flow), re-verifies the certificate with the checker (which re-integrates every entering box at its stored
steps), and writes the figure <out>/<name>_attraction_paving.png (sublevel set, certified boxes, solve_ivp
trajectories as a cross-check). Wall times are printed (integration cost per box). Floats only draw.
"""
from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from rigor_gyro.check import check_certificate
from rigor_gyro.kinds.lyapunov.plots import paving_figure
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene

HERE = Path(__file__).resolve().parent


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default=str(HERE / "scenes" / "gimbal_attraction_paving.toml"))
    ap.add_argument("--out", default="proofs/attraction_paving")
    ap.add_argument("--no-check", action="store_true")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scene = load_scene(args.scene)
    t0 = time.perf_counter()
    cert = prove_scene(scene)
    t_prove = time.perf_counter() - t0
    data = json.loads(json.dumps(cert.to_json()))
    (out / f"{scene.name}.json").write_text(json.dumps(data, indent=1))
    claims = {c["id"]: c for c in data["claims"]}
    for cid in ("natural_sublevel", "attraction_paving"):
        print(f"{cid}: {claims[cid]['status']} - {claims[cid]['reason'][:600]}")
    pv = data["witnesses"].get("attraction_paving", {})
    boxes = pv.get("boxes", [])
    tried = [b for b in boxes if b["status"] in ("enters", "undecided")]
    steps = [len(b["steps"]) for b in boxes if b["status"] == "enters"]
    print(f"prove: {t_prove:.1f} s wall; {len(tried)} boxes integrated, {sum(steps)} steps in all "
          f"({t_prove / max(len(tried), 1):.2f} s a box including the natural level; "
          f"{sum(steps) / max(len(steps), 1):.1f} steps a box)")
    if not args.no_check:
        t0 = time.perf_counter()
        res = check_certificate(data)
        print(f"check: {'confirmed' if res.ok else 'REJECTED'} in {time.perf_counter() - t0:.1f} s")
    import matplotlib.pyplot as plt
    fig = paving_figure(scene, cert, pv)
    path = out / f"{scene.name}_attraction_paving.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(f"figure: {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
