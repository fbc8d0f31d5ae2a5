"""Figures of a proved Lyapunov scene (``rigor-gyro prove ... --plots``): drawings, never verdicts.

* ``<name>_slices.png``: the region (17) (disc of radius R) and the certified invariant set
  {V < c_set} in the (x1, x3) plane at x2 = 0, x2*/2, x2* (V evaluated in floats for drawing);
* ``<name>_psi.png``: certified lower bounds of min over the disc of Psi1 and Psi2 over x2 pieces
  (the enclosures the claim rests on, drawn as steps);
* ``<name>_trajectories.png``: float trajectories (scipy) from the edge of the set: x1^2 + x3^2 and V
  against time.

:func:`build_figures` returns the Figures (name -> Figure), :func:`plots` saves them. Each is a float
drawing of certified data (Okabe-Ito colours, with a legend) and never decides anything.
matplotlib is imported here only (optional extra ``plots``).
"""
from __future__ import annotations

from pathlib import Path

from flint import arb

from ...core.balls import interval, working_precision
from ...core.figure_style import OKABE_ITO, SERIES, declutter_ticks

__all__ = ["plots", "build_figures", "paving_figure", "PAVING_COLOURS"]

#: status of a paved box -> (face colour, legend text)
PAVING_COLOURS = {"enters": (OKABE_ITO["blue"], "box whose validated flow enters {V < c} (certified)"),
                  "inside": (OKABE_ITO["bluish green"], "box inside {V < c} (certified)"),
                  "undecided": ("0.75", "undecided within the time budget"),
                  "skipped": ("0.92", "not tried")}

SET_COLOUR = OKABE_ITO["bluish green"]


def plots(scene, cert, out_dir) -> list[str]:
    """Save :func:`build_figures` as ``<out>/<file name>``; the paths (strings)."""
    import matplotlib.pyplot as plt
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, fig in build_figures(scene, cert).items():
        p = out / name
        fig.savefig(p, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(str(p))
    return paths


def build_figures(scene, cert) -> dict:
    """The scene's Figures by file name: the slices, the Psi bounds and (with c_set) the trajectories."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from .approx import FloatGimbal
    from .claims import validate
    from .vdot_tests import psi_min_functions

    model = validate(scene)
    g = model.gimbal
    fg = FloatGimbal(dict(scene.parameters), scene.model or None)
    q = cert.quantities
    figs = {}
    paving = (getattr(cert, "witnesses", None) or {}).get("attraction_paving")
    if paving:
        figs[f"{scene.name}_attraction_paving.png"] = paving_figure(scene, cert, paving)
    if not (q.get("R_used") or q.get("R")):
        return figs
    R = float((q.get("R_used") or q["R"]).mid())
    c_set = float(q["c_set"].mid()) if "c_set" in q else None
    with working_precision(64):
        xs = float(g.x2_star.ball().mid())

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    t = np.linspace(-1.05 * R, 1.05 * R, 241)
    X1, X3 = np.meshgrid(t, t)
    for ax, x2 in zip(axes, (0.0, xs / 2, xs)):
        ax.add_patch(plt.Circle((0, 0), R, fill=False, color="k", lw=1.2, label="region (17)"))
        if c_set is not None:
            Vv = fg.V(X1, np.full_like(X1, x2), X3)
            inside = X1 ** 2 + X3 ** 2 < R ** 2
            ax.contourf(X1, X3, np.where(inside, Vv, np.nan), levels=[-np.inf, c_set], colors=[SET_COLOUR], alpha=0.35)
            ax.contour(X1, X3, np.where(inside, Vv, np.nan), levels=[c_set], colors=[SET_COLOUR])
        ax.set_title(f"x2 = {x2:.4g}")
        ax.set_xlabel("x1 = alpha-dot")
        ax.set_ylabel("x3 = beta-dot")
        ax.set_aspect("equal")
    handles = [Line2D([], [], color="k", lw=1.2, label=f"region (17): disc of radius R = {R:.6g}")]
    if c_set is not None:
        handles.append(Patch(facecolor=SET_COLOUR, alpha=0.35, edgecolor=SET_COLOUR,
                             label=f"certified invariant set V < c_set = {c_set:.6g} (drawn in floats)"))
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8)
    fig.suptitle(f"{scene.name}: region (17) and the invariant set V < c_set (a drawing, never a verdict)")
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    declutter_ticks(fig)
    figs[f"{scene.name}_slices.png"] = fig

    with working_precision(64):
        psi1, psi2 = psi_min_functions(g, arb(str(R)))
        n = 64
        edges = [arb(str(xs * i / n)) for i in range(n + 1)]
        lows = [[float(fn(interval(a, b)).lower().mid()) for a, b in zip(edges, edges[1:])] for fn in (psi1, psi2)]
    fig, ax = plt.subplots(figsize=(7, 4))
    xe = np.linspace(0, xs, n + 1)
    for lo, name, colour in zip(lows, ("Psi1", "Psi2"), SERIES):
        ax.stairs(lo, xe, color=colour, label=f"certified lower bound of min {name} over the disc")
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("x2")
    ax.set_yscale("symlog")
    ax.legend()
    ax.set_title(f"{scene.name}: Psi lower bounds on x2 pieces (R = {R:.6g})")
    fig.tight_layout()
    declutter_ticks(fig)
    figs[f"{scene.name}_psi.png"] = fig

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
            for i, run in enumerate(runs):
                y = run.y
                colour = SERIES[i % len(SERIES)]
                a1.plot(run.t, y[0] ** 2 + y[2] ** 2, lw=0.6, color=colour, gid="trajectory")
                a2.plot(run.t, fg.V(y[0], y[1], y[2]), lw=0.8, color=colour, gid="trajectory",
                        label=f"start {i + 1} (float solve)")
            a1.axhline(R ** 2, color="k", lw=0.8, ls="--", label="R^2: edge of region (17)")
            a1.set_ylabel("x1^2 + x3^2")
            a2.axhline(c_set, color="k", lw=0.8, ls="--", label="c_set: level of the certified set")
            a2.set_ylabel("V")
            for a in (a1, a2):
                a.set_xlabel("t [s]")
                a.legend(fontsize=7, loc="best")
            fig.suptitle(f"{scene.name}: float trajectories from the edge of the certified set (never a verdict)")
            fig.tight_layout()
            declutter_ticks(fig)
            figs[f"{scene.name}_trajectories.png"] = fig
    return figs


def paving_figure(scene, cert, paving: dict):
    """The slice x2 = 0: the sublevel set {V(x1, 0, x3) < c} (float contour of the certified level), the paved boxes
    by status (the certified data, exact ends), and float trajectories (scipy solve_ivp, vermillion) from the
    corners of the outermost entering boxes, projected on (x1, x3): a cross-check drawing, never a verdict."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from fractions import Fraction
    from matplotlib.patches import Patch, Rectangle
    from scipy.integrate import solve_ivp

    from .approx import FloatGimbal

    fg = FloatGimbal(dict(scene.parameters), scene.model or None)
    q = cert.quantities
    c = float(q["natural_c_max_lower"].mid())
    w1, w3 = (float(Fraction(x)) for x in paving["half_width"])
    fig, ax = plt.subplots(figsize=(7.5, 6.5))
    boxes = paving["boxes"]
    for b in boxes:
        x1 = [float(Fraction(x)) for x in b["x1"]]
        x3 = [float(Fraction(x)) for x in b["x3"]]
        colour, _ = PAVING_COLOURS.get(b["status"], ("white", ""))
        ax.add_patch(Rectangle((x1[0], x3[0]), x1[1] - x1[0], x3[1] - x3[0], facecolor=colour, alpha=0.45,
                               edgecolor="k", lw=0.4))
    t1, t3 = np.linspace(-w1, w1, 301), np.linspace(-w3, w3, 301)
    X1, X3 = np.meshgrid(t1, t3)
    ax.contour(X1, X3, fg.V(X1, np.zeros_like(X1), X3), levels=[c], colors=[OKABE_ITO["reddish purple"]], linewidths=2)
    T = float(Fraction(paving["t_max"]))
    outer = sorted((b for b in boxes if b["status"] == "enters"),
                   key=lambda b: -max(abs(float(Fraction(x))) for x in b["x1"] + b["x3"]))[:6]
    for b in outer:
        x1, x3 = float(Fraction(b["x1"][1])), float(Fraction(b["x3"][1]))
        run = solve_ivp(fg.rhs_scalar, (0.0, T), [x1, 0.0, x3], rtol=1e-10, atol=1e-14, max_step=T / 400)
        ax.plot(run.y[0], run.y[2], lw=0.7, color=OKABE_ITO["vermillion"])
    handles = [Patch(facecolor=col, alpha=0.45, edgecolor="k", label=txt) for st, (col, txt) in PAVING_COLOURS.items()
               if any(b["status"] == st for b in boxes)]
    handles.append(plt.Line2D([], [], color=OKABE_ITO["reddish purple"], lw=2,
                              label=f"V(x1, 0, x3) = natural_c_max_lower = {c:.6g} (contour drawn in floats)"))
    handles.append(plt.Line2D([], [], color=OKABE_ITO["vermillion"], lw=0.7,
                              label="float trajectories (solve_ivp) from box corners, projected"))
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1), fontsize=7, ncol=1)
    ax.set_xlim(-w1, w1)
    ax.set_ylim(-w3, w3)
    ax.set_xlabel("x1 = alpha-dot")
    ax.set_ylabel("x3 = beta-dot")
    ax.set_title(f"{scene.name}: slice x2 = 0, boxes entering the certified set within t = {T:g} s")
    fig.tight_layout()
    declutter_ticks(fig)
    return fig
