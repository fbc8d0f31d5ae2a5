"""The three speed ratios of issue 12, measured in one run on this machine. Prints a table; asserts nothing.

    python benchmarks/speed_ratios.py [--repeat 3]

1. Cold processes: ``rigor-gyro prove --all`` (certified, writes the certificates and reports; one scene per core, and
   with ``--workers 1``) against
   the equivalent uncertified float script (``--float-script`` below: numpy/scipy compute the same
   quantities for the same scenes: the quartic's roots; m, M, the constants, c* and the mu search;
   g's roots on the certificate's search range, x(0) and the multipliers), and against the same script
   with ``--full``, which also computes the Lyapunov kind's polar-form quantities that ``prove --all``
   certifies since issue 13 (R_direct, c_max, mu_direct and R_direct_max, by the same searches in
   floats). Median wall time of ``--repeat`` runs each, interleaved, imports included.
2. Computation only (in one process, imports excluded): ``prove_scene`` against the mpmath path at 30
   digits (non-rigorous; the kind's ``approx.bench_mpmath``, with the mu search for the Lyapunov kind).
   Each scene also without its paper audit (the mpmath path audits nothing). For the Lyapunov kind
   two rows: against the constants and the mu search only (the row the issue first measured), and
   against every quantity the claims certify (also R_direct, c_max and the direct test's search over
   mu, by ``approx.mp_polar_estimates``, the same grid-then-compass searches in mpmath).
3. Relay fast nutation: H = 1e4 and 1e5 (the stress scenes), time, pieces and roots.
"""
from __future__ import annotations

import argparse
import dataclasses
import statistics
import subprocess
import sys
import tempfile
import time

PAPER = ("agafonov2013", "roitenberg1947", "roitenberg1947_b2over15", "rudenko1976")
#: the range the relay certificates search, (0, T]: the float script is given the same range
RELAY_T = {"roitenberg1947": 0.7283, "roitenberg1947_b2over15": 0.7283}


def float_script(full: bool = False) -> None:
    """The uncertified equivalent of ``prove --all``: every quantity in floats, nothing certified. ``full``:
    also the quantities of the Lyapunov kind's polar-form claims (R_direct at the scene's mu, c_max, and
    the direct test's search over mu: mu_direct, R_direct_max), which ``prove --all`` certifies too."""
    from rigor_gyro import load_scene
    from rigor_gyro.kinds.eigenfrequencies.approx import bench_float as eig
    from rigor_gyro.kinds.lyapunov.approx import float_constants, float_polar_estimates
    from rigor_gyro.kinds.periodic_orbit.approx import bench_float as relay
    for name in PAPER:
        sc = load_scene(name)
        p = dict(sc.parameters)
        if sc.kind == "eigenfrequencies":
            eig(p)
        elif sc.kind == "lyapunov":
            k = float_constants(p, with_best_mu=True)
            if full:
                float_polar_estimates(p, (k["mu_min"], k["mu_max"]))
        else:
            relay(p, hint={"theta_star": 0.13827, "T": RELAY_T[name], "t0": 1e-3})


def _medians_cold(cmds, repeat):
    """Median wall time of each command, the commands interleaved run by run (this machine's speed drifts
    by up to 50 % within an hour: blocks of runs of one command would compare different machines)."""
    ts = [[] for _ in cmds]
    for _ in range(repeat):
        for cmd, t_list in zip(cmds, ts):
            t = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            t_list.append(time.perf_counter() - t)
    return [statistics.median(t_list) for t_list in ts]


def _median(fn, repeat):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--float-script", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--full", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.float_script:
        float_script(args.full)
        return
    out = tempfile.mkdtemp()
    prove = [sys.executable, "-m", "rigor_gyro", "prove", "--all", "--quiet", "--out", out]
    fl = [sys.executable, __file__, "--float-script"]
    t_prove, t_one, t_float, t_full = _medians_cold([prove, prove + ["--workers", "1"], fl, fl + ["--full"]],
                                                    args.repeat)
    print("| measure | certified s | uncertified s | ratio |")
    print("|---|---|---|---|")
    for what, t_f in (("the float script", t_float),
                      ("the float script computing every certified quantity (+ R_direct, c_max, mu_direct)", t_full)):
        print(f"| `rigor-gyro prove --all` (one scene per core) vs {what}, cold processes | {t_prove:.2f} | "
              f"{t_f:.2f} | {t_prove / t_f:.2f}x |")
        print(f"| `rigor-gyro prove --all --workers 1` vs {what}, cold processes | {t_one:.2f} | "
              f"{t_f:.2f} | {t_one / t_f:.2f}x |")
    from rigor_gyro import load_scene, prove_scene
    import importlib
    from rigor_gyro.kinds import KINDS
    for name in PAPER:
        sc = load_scene(name)
        prove_scene(sc)        # warm
        tp = _median(lambda: prove_scene(sc), args.repeat)
        approx = importlib.import_module(KINDS[sc.kind] + ".approx")
        p = dict(sc.parameters)
        if sc.kind == "lyapunov":
            fn = lambda: approx.mp_constants(p, dps=30, with_best_mu=True)  # noqa: E731
            # the same quantity set as the claims: also R_direct, c_max and the direct test's search over mu
            # (vdot_direct, largest_sublevel, best_mu_direct)
            def full():
                k = approx.mp_constants(p, dps=30, with_best_mu=True)
                return approx.mp_polar_estimates(p, dps=30, mu_interval=(k["mu_min"], k["mu_max"]))
            full()
            tf = _median(full, args.repeat)
            print(f"| `{name}`: computation, prove_scene vs mpmath 30 digits computing every certified quantity "
                  f"(+ R_direct, c_max, mu_direct) | {tp:.3f} | {tf:.3f} | {tp / tf:.2f}x |")
        elif sc.kind == "periodic_orbit":
            fn = lambda: approx.bench_mpmath(p, dps=30, hint={"theta_star": 0.13827})  # noqa: E731
        else:
            fn = lambda: approx.bench_mpmath(p, dps=30)  # noqa: E731
        fn()
        tm = _median(fn, args.repeat)
        print(f"| `{name}`: computation, prove_scene vs mpmath 30 digits | {tp:.3f} | {tm:.3f} | {tp / tm:.2f}x |")
        # the mpmath path audits no paper: the same proof without the scene's [paper] table (what a
        # paving's sub-box or a user's own scene runs)
        bare = dataclasses.replace(sc, paper={})
        prove_scene(bare)
        tb = _median(lambda: prove_scene(bare), args.repeat)
        print(f"| `{name}`: computation without the paper audit, prove_scene vs mpmath 30 digits | {tb:.3f} | "
              f"{tm:.3f} | {tb / tm:.2f}x |")
    for name in ("stress_relay_H_1e4", "stress_relay_H_1e5"):
        sc = load_scene(name)
        t = time.perf_counter()
        c = prove_scene(sc)
        dt = time.perf_counter() - t
        hp = c.claim("half_period")
        print(f"| `{name}`: {hp.details.get('roots')} roots, {hp.details.get('pieces')} pieces, "
              f"bits {c.precisions_tried} | {dt:.2f} | - | - |")


if __name__ == "__main__":
    main()
