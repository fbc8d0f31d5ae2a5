"""Width of the validated flow's enclosures against step count and Taylor order. Prints tables; asserts nothing.

    python benchmarks/flow_width.py [--orders 8,12,16,20,24] [--prec 64] [--gimbal-time 0.02]

1. The pendulum x'' = -sin x from a point (1, 0) and from a box of radius 1e-6, to t = 6, at each order: steps,
   the end width, the width growth per step ((w_end / w_0)^(1/steps)) and the wall time.
2. The gimbal gyroscope, system (2) of Agafonov et al. 2013 (the paper's example: nutation at 1369 rad/s), from a
   point and from a box of radius 1e-6 in each coordinate near x = (0.005, 0.3, 0), over --gimbal-time seconds:
   the same columns, and the width every 20 steps (how the wrapping grows).
Timing lives here, never in the tests (rigor_gyro.core.validated_flow; floats only print).
"""
from __future__ import annotations

import argparse
import time
from fractions import Fraction

from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.validated_flow import validated_flow
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters

PAPER = dict(A="2", C="3.3", A1="2.2", B1="2.2", C1="2.8", A2="8.5", H="1e4", k="0.4", a="100", x2_star="pi/6",
             mu="0.02", moment="sine")


def _box(mids, rad):
    return [arb(m) + arb(0, rad) if rad else arb(m) for m in mids]


def _row(name, field, mids, rad, t_end, order, prec, every=0):
    with working_precision(prec):
        t0 = time.perf_counter()
        fl = validated_flow(field, _box(mids, rad), t_end, order=order)
        wall = time.perf_counter() - t0
        w0 = max(float(b.rad()) for b in _box(mids, rad))
        w = [max(float(b.rad()) for b in s.end) for s in fl.steps]
    n = len(fl.steps)
    growth = (w[-1] / w0) ** (1 / n) if n and w0 > 0 else float("nan")
    print(f"| {name} | {order} | {'box' if rad else 'point'} | {n} | {float(fl.t):.4g} | {w[-1] if w else 0:.3e} | "
          f"{growth:.5f} | {wall:.2f} | {wall / max(n, 1) * 1e3:.1f} |" + ("" if fl.complete else f" stopped: {fl.reason}"))
    if every and w:
        print("    width every %d steps: " % every + ", ".join(f"{w[k]:.2e}" for k in range(0, n, every)))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--orders", default="8,12,16,20,24")
    ap.add_argument("--prec", type=int, default=64)
    ap.add_argument("--gimbal-time", default="0.02")
    args = ap.parse_args()
    orders = [int(x) for x in args.orders.split(",")]
    print("| system | order | start | steps | t | end width | growth / step | wall s | ms / step |")
    print("|---|---|---|---|---|---|---|---|---|")
    pend = lambda x: [x[1], -x[0].sin()]  # noqa: E731
    for order in orders:
        _row("pendulum", pend, ["1", "0"], 0, Fraction(6), order, args.prec)
        _row("pendulum", pend, ["1", "0"], "1e-6", Fraction(6), order, args.prec)
    g, _ = gimbal_from_parameters(PAPER)
    field = lambda x: g.rhs(*x)  # noqa: E731
    T = Fraction(args.gimbal_time)
    for order in orders:
        _row("gimbal (2)", field, ["0.005", "0.3", "0"], 0, T, order, args.prec)
        _row("gimbal (2)", field, ["0.005", "0.3", "0"], "1e-6", T, order, args.prec, every=20 if order == 20 else 0)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
