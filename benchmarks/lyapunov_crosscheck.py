"""Float / mpmath cross-check of the Lyapunov scene (Agafonov et al. 2013). Prints tables; asserts nothing.

    python benchmarks/lyapunov_crosscheck.py [--long-horizon 100] [--no-long] [--no-certified] [--dps 50]

1. Constants: mpmath (50 digits) against float64 and, unless --no-certified, the certified balls of
   ``prove_scene`` (does the ball contain the mpmath value?), for the paper's example.
2. Time scales of the linearisation at 0 (nutation frequency, decay rates, periods per time constant).
3. Integrator choice: one start from the edge of {V < c*} over a short horizon with LSODA, DOP853, RK45
   and Radau (run time, rhs calls, steps per nutation period, monotonicity of V).
4. Trajectories from the edge of {V < c*} and from outside the box, over a short horizon (LSODA, one
   run per start) and a long one (DOP853, all starts integrated as one stacked system).
5. Extreme cases of the issue: mpmath constants, and (unless --no-certified) whether the certificate's
   balls contain them.
Timing lives here, never in the tests.
"""
from __future__ import annotations

import argparse
import time

import mpmath
import numpy as np

from rigor_gyro.kinds.lyapunov.approx import (AGAFONOV2013, FloatGimbal, edge_points, float_constants, mp_constants,
                                        time_scales, trajectories)

KEYS = ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R", "R_sup", "c_star",
        "mu_best", "R_max")
ENCLOSED = ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R", "c_star")

EXTREME = {
    "paper (sine)": {},
    "linear moment": {"moment": "linear"},
    "x2* = 0.49 pi": {"x2_star": "0.49*pi"},
    "k just above k_min": {"k": "0.1694", "mu": "0.0133339"},
    "H = 1e6": {"H": "1e6"},
    "H = 10": {"H": "10"},
    "a = 1e-6": {"a": "0.000001"},
    "a = 1e6": {"a": "1e6"},
    "C0 < 0": {"C1": "10"},
    "R far too large (option R=0.5)": {"__R": "0.5"},
}


def table(rows, header):
    widths = [max(len(str(r[i])) for r in rows + [header]) for i in range(len(header))]
    print("  ".join(str(h).ljust(w) for h, w in zip(header, widths)))
    for r in rows:
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)))
    print()


def certify(params: dict, R: str | None = None):
    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import parse_scene
    body = "".join(f'{k} = "{v}"\n' for k, v in params.items())
    opts = f'[options]\nR = "{R}"\n' if R else ""
    t = time.perf_counter()
    cert = prove_scene(parse_scene(f'name = "x"\nkind = "lyapunov"\n[parameters]\n{body}{opts}'))
    return cert, time.perf_counter() - t


def contains(ball, value) -> str:
    if ball is None or value is None:
        return "-"
    from flint import arb
    from rigor_gyro.core.balls import working_precision
    with working_precision(256), mpmath.workdps(70):
        x = arb(mpmath.nstr(value, 60))
        return "yes" if (ball + arb(0, arb("1e-40") * abs(x))).contains(x) else "NO"


def below(ball, value) -> str:
    """For a certified lower bound (R_max): is it certainly <= the mpmath supremum (+1e-40 relative)?"""
    if ball is None or value is None:
        return "-"
    from flint import arb
    from rigor_gyro.core.balls import certainly_le, working_precision
    with working_precision(256), mpmath.workdps(70):
        x = arb(mpmath.nstr(value, 60))
        return "lower bound ok" if certainly_le(ball, x + arb(0, arb("1e-40") * abs(x))) else "NO"


def constants_table(dps: int, certified: bool):
    print(f"== 1. constants at the paper's example: mpmath ({dps} digits) vs float64 vs certified balls")
    t = time.perf_counter()
    mp = mp_constants(AGAFONOV2013, dps=dps)
    t_mp = time.perf_counter() - t
    t = time.perf_counter()
    fl = float_constants(AGAFONOV2013)
    t_fl = time.perf_counter() - t
    cert, t_c = certify(AGAFONOV2013) if certified else (None, 0.0)
    rows = []
    for k in KEYS:
        m, f = mp.get(k), fl.get(k)
        with mpmath.workdps(dps + 10):
            rel = "-" if m is None or f is None or m == 0 else mpmath.nstr(abs(mpmath.mpf(f) - m) / abs(m), 2)
        ball = cert.quantities.get(k) if cert else None
        rows.append((k, mpmath.nstr(m, 25) if m is not None else "-", repr(f), rel,
                     ball.str(18, radius=True) if ball is not None else "-",
                     contains(ball, m) if k in ENCLOSED else below(ball, m) if k == "R_max" else "-"))
    table(rows, ("quantity", "mpmath", "float64", "rel diff", "certified ball", "contains mpmath"))
    print(f"run times: mp_constants {t_mp:.2f} s, float_constants {t_fl:.2f} s, prove_scene {t_c:.2f} s; "
          f"c* attained on: {mp['c_star_where']} (cylinder minimum {mpmath.nstr(mp['c_star_cylinder'], 12)}); "
          f"mu_best: {mp['mu_best_kind']}\n")
    return mp


def time_scale_table():
    print("== 2. time scales of the linearisation at 0")
    ts = time_scales(AGAFONOV2013)
    rows = [("eigenvalues", ", ".join(mpmath.nstr(e, 12) for e in ts["eigenvalues"])),
            ("nutation (rad/s)", mpmath.nstr(ts["nutation_rad_s"], 12)),
            ("nutation (Hz)", mpmath.nstr(ts["nutation_hz"], 12)),
            ("nutation period (s)", mpmath.nstr(ts["nutation_period"], 8)),
            ("H / sqrt(A0 B0)", mpmath.nstr(ts["gyro_frequency_estimate"], 12)),
            ("decay rates (1/s)", ", ".join(mpmath.nstr(r, 12) for r in ts["decay_rates"])),
            ("slowest rate (a/H = 0.01)", mpmath.nstr(ts["slowest_rate"], 12)),
            ("time constant (s)", mpmath.nstr(ts["time_constant"], 10)),
            ("nutation periods per time constant", mpmath.nstr(ts["periods_per_time_constant"], 8))]
    table(rows, ("time scale", "value"))
    return ts


def method_table(start, cstar: float, horizon: float, ts):
    print(f"== 3. integrator choice: one start from the edge of {{V < c*}}, horizon {horizon} s "
          f"({horizon * float(ts['nutation_hz']):.0f} nutation periods)")
    rows = []
    for method, rtol in (("LSODA", 1e-9), ("LSODA", 1e-10), ("DOP853", 1e-8), ("DOP853", 1e-10), ("RK45", 1e-8),
                         ("Radau", 1e-8)):
        h = horizon if method != "Radau" else horizon / 10
        o = trajectories(AGAFONOV2013, [start], h, rtol=rtol, method=method, c_star=cstar)[0]
        per = o.n_steps / (h * float(ts["nutation_hz"]))
        rows.append((method, f"{rtol:g}", f"{h:g}", f"{o.seconds:.2f}", f"{o.seconds / h:.2f}", o.nfev,
                     f"{per:.1f}", o.V_nonincreasing, f"{o.max_V_increase / o.V0:.2e}", f"{o.V_final:.10g}"))
    table(rows, ("method", "rtol", "horizon s", "run s", "run s per sim s", "rhs calls", "steps/period",
                 "V non-incr.", "max dV/V0", "V(end)"))


def trajectory_table(label, runs, cstar):
    print(label)
    rows = []
    for o in runs:
        rows.append((", ".join(f"{v:.4g}" for v in o.start), f"{o.V0 / cstar:.6f}", o.in_box_at_start,
                     o.in_set_at_start, f"{np.sqrt(o.max_r2):.5g}", f"{o.max_abs_x2:.4g}", o.left_box,
                     o.stayed_in_set, o.V_nonincreasing, f"{o.max_V_increase / max(abs(o.V0), 1e-300):.1e}",
                     f"{o.V_final / cstar:.4g}", f"{o.final_norm:.3g}", f"{o.seconds:.1f}", o.success))
    table(rows, ("start (x1, x2, x3)", "V0/c*", "in box", "in set", "max r", "max|x2|", "left box",
                 "stayed in set", "V non-incr.", "max dV/V0", "V(T)/c*", "|x(T)|", "s", "ok"))


def extreme_table(dps: int, certified: bool):
    print("== 5. extreme cases: mpmath constants (and whether the certificate's balls contain them)")
    rows = []
    for label, change in EXTREME.items():
        change = dict(change)
        R = change.pop("__R", None)
        params = dict(AGAFONOV2013, **change)
        t = time.perf_counter()
        mp = mp_constants(params, dps=dps, R=R)
        t_mp = time.perf_counter() - t
        cert, t_c = certify(params, R) if certified else (None, 0.0)
        misses = []
        if cert:
            for k in ENCLOSED:
                b = cert.quantities.get(k)
                if b is not None and b.is_finite() and mp.get(k) is not None and contains(b, mp[k]) == "NO":
                    misses.append(k)
        status = " ".join(f"{c.id[:8]}:{c.status.value[:4]}" for c in cert.claims) if cert else "-"
        rows.append((label, mpmath.nstr(mp["M"], 10), mpmath.nstr(mp["p"], 8), mpmath.nstr(mp["k_min"], 6),
                     mpmath.nstr(mp["R"], 6), mpmath.nstr(mp["R_sup"], 6),
                     mpmath.nstr(mp["c_star"], 8) if mp["c_star"] is not None else "-",
                     mpmath.nstr(mp["mu_best"], 8) if mp["mu_best"] is not None else "-",
                     f"{t_mp:.2f}", f"{t_c:.2f}", status, ",".join(misses) or ("none" if cert else "-")))
    table(rows, ("case", "M", "p", "k_min", "R", "R_sup(mu)", "c*", "mu_best", "mp s", "cert s", "claims",
                 "balls missing mpmath"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--long-horizon", type=float, default=100.0, help="seconds of simulated time (default 100)")
    ap.add_argument("--short-horizon", type=float, default=2.0)
    ap.add_argument("--no-long", action="store_true")
    ap.add_argument("--no-certified", action="store_true")
    ap.add_argument("--dps", type=int, default=50)
    args = ap.parse_args()
    certified = not args.no_certified
    mp = constants_table(args.dps, certified)
    ts = time_scale_table()
    cstar = float(mp["c_star"])
    pts = edge_points(AGAFONOV2013, cstar, n=6)
    method_table(pts.edge[0], cstar, 0.5, ts)
    runs = trajectories(AGAFONOV2013, np.vstack([pts.edge, pts.outside]), args.short_horizon, c_star=cstar)
    trajectory_table(f"== 4a. short horizon {args.short_horizon} s, LSODA rtol 1e-9, one run per start "
                     f"(outside: {', '.join(pts.outside_labels)})", runs, cstar)
    if not args.no_long:
        starts = np.vstack([pts.edge, pts.outside])
        runs = trajectories(AGAFONOV2013, starts, args.long_horizon, c_star=cstar, method="DOP853", rtol=1e-8,
                            joint=True)
        trajectory_table(f"== 4b. long horizon {args.long_horizon} s "
                         f"({args.long_horizon * float(ts['nutation_hz']):.0f} nutation periods, "
                         f"{args.long_horizon / float(ts['time_constant']):.2f} slowest time constants), DOP853 rtol "
                         f"1e-8, all {len(starts)} starts as one stacked system (s = shared total)", runs, cstar)
    extreme_table(args.dps, certified)
    g = FloatGimbal(AGAFONOV2013)
    x = np.random.default_rng(0)
    x2 = x.uniform(-g.xs, g.xs, 100000)
    r = 0.0106 * np.sqrt(x.uniform(0, 1, 100000))
    th = x.uniform(0, 2 * np.pi, 100000)
    x1, x3 = r * np.cos(th), r * np.sin(th)
    vd, vp = g.grad_V_dot_f(x1, x2, x3), g.vdot_psi(x1, x2, x3)
    print(f"float grad V . f vs audited Psi form at 1e5 random points of (17): max rel diff "
          f"{np.max(np.abs(vd - vp) / np.abs(vp)):.2e}; max Vdot {np.max(vd):.3e} (<= 0 expected)")


if __name__ == "__main__":
    main()
