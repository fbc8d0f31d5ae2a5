"""The speed ratios of issues 12 and 41, measured in one run on this machine. Prints tables; asserts nothing.

    python benchmarks/speed_ratios.py [--repeat 3]            everything below
    python benchmarks/speed_ratios.py --goals [--repeat 7]    only issue 41's goals (0. below), a minute or two
    python benchmarks/speed_ratios.py --goals --extremes      only the gimbal extremes (0. (b))
    python benchmarks/speed_ratios.py --goals --before DIR [--after DIR2]
        the same, each run paired with a run of the source tree DIR (``git archive <commit>`` unpacked
        there), interleaved: before/after (after: the installed tree, or DIR2)

0. Issue 41's goals. (a) Cold ``rigor-gyro prove rudenko1976 roitenberg1947 agafonov2013 --workers 1`` (every
   claim they prove, certificates and reports written) against the float script of the same three scenes
   (``--float-script --scenes ...``, and with ``--full``: also the Lyapunov polar-form quantities), median
   wall time and median user CPU of ``--repeat`` paired runs, interleaved. Goal: <= 0.6x the float script's
   wall, <= 0.35 s user CPU. (b) The gimbal extremes: agafonov2013 with H = 1e300 and with a = 1e-300
   (temporary scenes, its [paper] table left out): wall, user CPU and each claim's status. Goal: decided
   or honestly inconclusive in under 10 s.
   Every subprocess runs with bytecode caches (PYTHONPYCACHEPREFIX in a temporary folder, warmed by one
   run that is not counted; PYTHONDONTWRITEBYTECODE removed): an installed package has its ``.pyc``
   files, and numpy/scipy's are in site-packages already. OPENBLAS_NUM_THREADS=1 for every run: on a
   shared 2-core machine OpenBLAS's threads made scipy's 5x5 ``expm`` 30-100x slower (the float script's
   relay part took 10-25 s instead of 0.4 s), which would flatter the certified path.

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
import json
import os
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile
import time

PAPER = ("agafonov2013", "roitenberg1947", "roitenberg1947_b2over15", "rudenko1976")
#: the range the relay certificates search, (0, T]: the float script is given the same range
RELAY_T = {"roitenberg1947": 0.7283, "roitenberg1947_b2over15": 0.7283}
#: the three papers' scenes of issue 41's cold-prove goal
THREE = ("rudenko1976", "roitenberg1947", "agafonov2013")
#: issue 41's gimbal extremes: agafonov2013 with one parameter replaced
EXTREMES = (("H", "1e300"), ("a", "1e-300"))
HERE = pathlib.Path(__file__).resolve()
#: the subprocesses' working folder: not the repository (``python -m`` puts the working folder first on the path,
#: so run from a checkout every "tree" would import the checkout's rigor_gyro)
NEUTRAL = tempfile.gettempdir()


def float_script(full: bool = False, scenes=PAPER) -> None:
    """The uncertified equivalent of ``prove --all``: every quantity in floats, nothing certified. ``full``:
    also the quantities of the Lyapunov kind's polar-form claims (R_direct at the scene's mu, c_max, and
    the direct test's search over mu: mu_direct, R_direct_max), which ``prove --all`` certifies too."""
    from rigor_gyro import load_scene
    from rigor_gyro.kinds.eigenfrequencies.approx import bench_float as eig
    from rigor_gyro.kinds.lyapunov.approx import float_constants, float_polar_estimates
    from rigor_gyro.kinds.periodic_orbit.approx import bench_float as relay
    for name in scenes:
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


def _env(tree: str | None, cache: str) -> dict:
    """The subprocesses' environment: bytecode caches under ``cache``, one BLAS thread, and the source tree
    ``tree`` first on the path (None: the installed one)."""
    env = dict(os.environ, PYTHONPYCACHEPREFIX=cache, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    if tree is not None:
        env["PYTHONPATH"] = os.pathsep.join([tree] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    return env


def _run(cmd, env, timeout=None):
    """(wall s, user CPU s, completed process) of one run of ``cmd``."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    t = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout, cwd=NEUTRAL)
    wall = time.perf_counter() - t
    return wall, resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - r0, p


def _paired(cmds, repeat):
    """Median (wall, user CPU) of each (cmd, env), the commands interleaved run by run, after one warm-up
    run each (it fills the bytecode cache; not counted). A failing run raises."""
    for cmd, env in cmds:
        subprocess.run(cmd, check=True, capture_output=True, env=env, cwd=NEUTRAL)
    ts = [([], []) for _ in cmds]
    for _ in range(repeat):
        for (cmd, env), (w, u) in zip(cmds, ts):
            wall, user, p = _run(cmd, env)
            if p.returncode not in (0, 3):
                raise RuntimeError(f"{cmd} exited {p.returncode}: {p.stderr[-2000:]}")
            w.append(wall)
            u.append(user)
    return [(statistics.median(w), statistics.median(u)) for w, u in ts]


def extreme_scene(folder: str, param: str, value: str) -> str:
    """A temporary copy of agafonov2013 with ``param`` = ``value`` (its [paper] table left out: the printed
    numbers are the paper's scene's). Returns the TOML path."""
    from rigor_gyro.scene import builtin_scenes
    lines, out = builtin_scenes()["agafonov2013"].read_text().splitlines(), []
    for line in lines:
        if line.strip() == "[paper]":
            break
        if line.startswith("name = "):
            line = f'name = "agafonov2013_{param}_{value}"'
        elif line.startswith(f"{param} = "):
            line = f'{param} = "{value}"'
        out.append(line)
    path = os.path.join(folder, f"agafonov2013_{param}_{value}.toml")
    pathlib.Path(path).write_text("\n".join(out) + "\n")
    return path


def goals(repeat: int, before: str | None, after: str | None = None, extremes_only: bool = False) -> None:
    """Issue 41's goal rows (0. in the module's docstring)."""
    cache, out = tempfile.mkdtemp(), tempfile.mkdtemp()
    trees = [("after", after)] + ([("before", before)] if before else [])
    if not extremes_only:
        _cold_goal(trees, cache, out, repeat)
    _extremes(trees, cache, out)


def _cold_goal(trees, cache, out, repeat) -> None:
    """Goal (a): the cold three-paper prove against the float script, paired and interleaved."""
    cmds, names = [], []
    for label, tree in trees:
        env = _env(tree, os.path.join(cache, label))
        cmds.append(([sys.executable, "-m", "rigor_gyro", "prove", *THREE, "-q", "--workers", "1", "--out",
                      os.path.join(out, label)], env))
        names.append(f"`rigor-gyro prove {' '.join(THREE)} --workers 1` ({label})")
    env = _env(None, os.path.join(cache, "float"))
    fl = [sys.executable, str(HERE), "--float-script", "--scenes", ",".join(THREE)]
    cmds += [(fl, env), (fl + ["--full"], env)]
    names += ["float script, the same three scenes", "float script --full (+ R_direct, c_max, mu_direct)"]
    res = _paired(cmds, repeat)
    load = os.getloadavg()
    print(f"Cold processes, median of {repeat} paired interleaved runs (load average {load[0]:.2f} {load[1]:.2f} "
          f"{load[2]:.2f}; {os.cpu_count()} cores):\n")
    print("| run | wall s | user CPU s | wall / float script | wall / float script --full |")
    print("|---|---|---|---|---|")
    t_fl, t_full = res[-2][0], res[-1][0]
    for name, (w, u) in zip(names, res):
        print(f"| {name} | {w:.2f} | {u:.2f} | {w / t_fl:.2f}x | {w / t_full:.2f}x |")
    print("\nGoal: the certified run <= 0.6x the float script's wall and <= 0.35 s user CPU.\n")


def _extremes(trees, cache, out) -> None:
    """Goal (b): the gimbal extremes, one run each per tree (wall and user CPU of the process)."""
    print("| extreme scene | tree | wall s | user CPU s | verdict | bits tried | claims (status) |")
    print("|---|---|---|---|---|---|---|")
    for param, value in EXTREMES:
        path = extreme_scene(out, param, value)
        for label, tree in trees:
            env = _env(tree, os.path.join(cache, label))
            o = os.path.join(out, f"x_{label}")
            try:
                wall, user, p = _run([sys.executable, "-m", "rigor_gyro", "prove", path, "-q", "--workers", "1",
                                      "--out", o], env, timeout=600)
            except subprocess.TimeoutExpired:
                print(f"| agafonov2013, {param} = {value} | {label} | > 600 | - | timed out | - | - |")
                continue
            cert = json.loads(pathlib.Path(o, f"agafonov2013_{param}_{value}.json").read_text())
            st: dict[str, list[str]] = {}
            for c in cert["claims"]:
                st.setdefault(c["status"], []).append(c["id"])
            text = "; ".join(f"{k}: {', '.join(v)}" if k != "proved" else f"proved: {len(v)}" for k, v in st.items())
            print(f"| agafonov2013, {param} = {value} | {label} | {wall:.2f} | {user:.2f} | {cert['verdict']} | "
                  f"{cert['precisions_tried']} | {text} |")
    print("\nGoal: decided or honestly inconclusive in under 10 s.")


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
    ap.add_argument("--goals", action="store_true", help="only issue 41's goal rows (0. above)")
    ap.add_argument("--before", metavar="DIR", help="with --goals: also run the source tree DIR (a `git archive` "
                    "of an older commit unpacked there), paired and interleaved with the current one")
    ap.add_argument("--after", metavar="DIR", help="with --goals: run the source tree DIR as 'after' instead of the "
                    "installed one (two `git archive`s compared, whatever the work tree holds)")
    ap.add_argument("--extremes", action="store_true", help="with --goals: only the gimbal extremes (goal (b))")
    ap.add_argument("--float-script", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--full", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--scenes", default=",".join(PAPER), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.float_script:
        float_script(args.full, args.scenes.split(","))
        return
    goals(args.repeat, args.before, args.after, args.extremes)
    if args.goals:
        return
    print()
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
