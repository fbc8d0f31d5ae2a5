"""Figures of a proved Lyapunov scene (``rigor-gyro prove ... --plots``): drawings, never verdicts.

* ``<name>_slices.png``: the region (17) (disc of radius R) and the certified invariant set
  {V < c_set} in the (x1, x3) plane at x2 = 0, x2*/2, x2* (V evaluated in floats for drawing);
* ``<name>_psi.png``: certified lower bounds of min over the disc of Psi1 and Psi2 over x2 pieces
  (the enclosures the claim rests on, drawn as steps);
* ``<name>_trajectories.png``: float trajectories (scipy) from the edge of the set: x1^2 + x3^2 and V
  against time.

matplotlib is imported here only (optional extra ``plots``).
"""
from __future__ import annotations

from pathlib import Path

from flint import arb

from ...core.balls import interval, working_precision

__all__ = ["plots"]


def _save(fig, out: Path, name: str, paths: list[str]) -> None:
    import matplotlib.pyplot as plt
    p = out / name
    fig.savefig(p, dpi=110, bbox_inches="tight")
    plt.close(fig)
    paths.append(str(p))


def plots(scene, cert, out_dir) -> list[str]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from .approx import FloatGimbal
    from .claims import validate
    from .model import psi_min_functions

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    model = validate(scene)
    g = model.gimbal
    fg = FloatGimbal(dict(scene.parameters))
    q = cert.quantities
    R = float((q.get("R_used") or q["R"]).mid())
    c_set = float(q["c_set"].mid()) if "c_set" in q else None
    with working_precision(64):
        xs = float(g.x2_star.ball().mid())
    paths = []

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    t = np.linspace(-1.05 * R, 1.05 * R, 241)
    X1, X3 = np.meshgrid(t, t)
    for ax, x2 in zip(axes, (0.0, xs / 2, xs)):
        ax.add_patch(plt.Circle((0, 0), R, fill=False, color="k", lw=1.2, label="region (17)"))
        if c_set is not None:
            Vv = fg.V(X1, np.full_like(X1, x2), X3)
            inside = X1 ** 2 + X3 ** 2 < R ** 2
            ax.contourf(X1, X3, np.where(inside, Vv, np.nan), levels=[-np.inf, c_set], colors=["tab:green"], alpha=0.35)
            ax.contour(X1, X3, np.where(inside, Vv, np.nan), levels=[c_set], colors=["tab:green"])
        ax.set_title(f"x2 = {x2:.4g}")
        ax.set_xlabel("x1 = alpha-dot")
        ax.set_ylabel("x3 = beta-dot")
        ax.set_aspect("equal")
    fig.suptitle(f"{scene.name}: region (17) and the invariant set V < c_set (green)")
    _save(fig, out, f"{scene.name}_slices.png", paths)

    with working_precision(64):
        psi1, psi2 = psi_min_functions(g, arb(str(R)))
        n = 64
        edges = [arb(str(xs * i / n)) for i in range(n + 1)]
        lows = [[float(fn(interval(a, b)).lower().mid()) for a, b in zip(edges, edges[1:])] for fn in (psi1, psi2)]
    fig, ax = plt.subplots(figsize=(7, 4))
    xe = np.linspace(0, xs, n + 1)
    for lo, name in zip(lows, ("Psi1", "Psi2")):
        ax.stairs(lo, xe, label=f"certified lower bound of min {name} over the disc")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("x2")
    ax.set_yscale("symlog")
    ax.legend()
    ax.set_title(f"{scene.name}: Psi lower bounds on x2 pieces (R = {R:.6g})")
    _save(fig, out, f"{scene.name}_psi.png", paths)

    if c_set is not None:
        starts = []
        for ang in np.linspace(0, 2 * np.pi, 6, endpoint=False):
            lo, hi = 0.0, R
            for _ in range(50):       # float bisection to the edge of {V < c_set} along a ray
                mid = (lo + hi) / 2
                pt = (mid * np.cos(ang), 0.5 * xs * np.sin(ang) * mid / R, mid * np.sin(ang))
                (lo, hi) = (mid, hi) if fg.V(*pt) < c_set else (lo, mid)
            r = 0.98 * lo
            starts.append((r * np.cos(ang), 0.5 * xs * np.sin(ang) * r / R, r * np.sin(ang)))
        from scipy.integrate import solve_ivp
        runs = [solve_ivp(fg.rhs_scalar, (0.0, 2.0), s0, method="LSODA", rtol=1e-10, atol=1e-14) for s0 in starts]
        if runs:
            fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4))
            for run in runs:
                y = run.y
                a1.plot(run.t, y[0] ** 2 + y[2] ** 2, lw=0.6)
                a2.plot(run.t, fg.V(y[0], y[1], y[2]), lw=0.8)
            a1.axhline(R ** 2, color="k", lw=0.8)
            a1.set_ylabel("x1^2 + x3^2")
            a2.axhline(c_set, color="tab:green", lw=0.8)
            a2.set_ylabel("V")
            for a in (a1, a2):
                a.set_xlabel("t [s]")
            fig.suptitle(f"{scene.name}: float trajectories from the edge of the certified set (never a verdict)")
            _save(fig, out, f"{scene.name}_trajectories.png", paths)
    return paths
