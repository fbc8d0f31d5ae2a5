"""Figures of a proved periodic-orbit scene (``rigor-gyro prove ... --plots``): drawings, never verdicts.

* ``<name>_orbit.png``: beta, Omega, i, I over one period 2 theta* of the scene's orbit, evaluated in
  balls from the certified initial point and drawn at their midpoints (floats for drawing only); for a
  [plant] scene, the relay input c . x and output u over one period, with the switching levels +-h.

:func:`build_figures` returns the Figures (file name -> Figure), :func:`plots` saves them; a figure
is a float drawing of certified data and never decides anything. matplotlib is imported inside the
functions only (optional extra ``plots``).
"""
from __future__ import annotations

from pathlib import Path

from ...core.balls import working_precision
from ...core.figure_style import OKABE_ITO, SERIES, declutter_ticks
from .dispatch import validate
from .flow import Spectrum, orbit_expsums, x0_at
from .plant_model import PlantModel
from .plant_orbit import PlantSpectrum, orbit_output

__all__ = ["plots", "build_figures"]


def plots(scene, cert, out_dir) -> list:
    """Save :func:`build_figures` as ``<out>/<file name>``; the paths."""
    import matplotlib.pyplot as plt
    figs = build_figures(scene, cert)
    if not figs:
        return []
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, fig in figs.items():
        path = out / name
        fig.savefig(path, dpi=120)
        plt.close(fig)
        paths.append(path)
    return paths


def build_figures(scene, cert) -> dict:
    """Draw beta, Omega, i, I over one period of the scene's orbit (floats for drawing only; the curve is
    evaluated from the certified initial point): ``{"<name>_orbit.png": Figure}``, or {} without theta*."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if "theta_star" not in cert.quantities:
        return {}
    model = validate(scene)
    if isinstance(model, PlantModel):
        return _plant_figure(scene, cert, model)
    with working_precision(max(cert.precision_bits, 64)):
        sp = Spectrum(model.params)
        th = cert.quantities["theta_star"]
        x0 = x0_at(sp, th)
        comps = orbit_expsums(sp, x0)
        N = 200
        ts, ys = [], [[] for _ in range(5)]
        thf = float(th.mid())
        for half in (0, 1):
            for k in range(N + 1):
                t = th * k / N
                vals = [c(t) for c in comps]
                ts.append(half * thf + thf * k / N)
                for i in range(5):
                    ys[i].append((-1) ** half * float(vals[i].mid()))
    names = ["beta (rad)", "beta' (rad/s)", "Omega (rad/s)", "i (A)", "I (A)"]
    fig, axes = plt.subplots(4, 1, figsize=(7, 9), sharex=True)
    for ax, i, colour in zip(axes, (0, 2, 3, 4), SERIES):
        ax.plot(ts, ys[i], lw=1.2, color=colour, gid="orbit", label=names[i].split(" ")[0] + " (ball midpoints)")
        ax.axvline(thf, color=OKABE_ITO["grey"], lw=0.8, ls="--", label="theta* (half period)")
        ax.axhline(0, color=OKABE_ITO["grey"], lw=0.4)
        ax.set_ylabel(names[i])
        ax.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("t (s)")
    axes[0].set_title(f"{scene.name}: one period 2 theta*, theta* = {thf:.12g} s\n"
                      "(drawn from the certified initial point; a drawing, never a verdict)", fontsize=10)
    fig.tight_layout()
    declutter_ticks(fig)
    return {f"{scene.name}_orbit.png": fig}


def _plant_figure(scene, cert, model) -> dict:
    """A [plant] scene: y = c . x and the relay output u over one period of the scene's orbit (y evaluated
    in balls on the certified theta*, drawn at the midpoints)."""
    import matplotlib.pyplot as plt
    with working_precision(max(cert.precision_bits, 64)):
        sp = PlantSpectrum(model)
        th = cert.quantities["theta_star"]
        y = orbit_output(sp, th)
        N = 400
        thf = float(th.mid())
        ts, ys, us = [], [], []
        for half in (0, 1):
            for k in range(N + 1):
                ts.append(half * thf + thf * k / N)
                ys.append((-1) ** half * float(y(th * k / N).mid()))
                us.append((-1) ** half * float(model.S))
    h = float(model.h)
    fig, axes = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    axes[0].plot(ts, ys, lw=1.2, color=SERIES[0], gid="orbit", label="c . x (ball midpoints)")
    for level in ((h, -h) if h else (0.0,)):
        axes[0].axhline(level, color=OKABE_ITO["grey"], lw=0.6, ls=":", label="switching level" if level >= 0 else None)
    axes[1].step(ts, us, where="post", lw=1.2, color=SERIES[1], label="u (relay output)")
    for ax in axes:
        ax.axvline(thf, color=OKABE_ITO["grey"], lw=0.8, ls="--", label="theta* (half period)")
        ax.legend(fontsize=7, loc="upper right")
    axes[0].set_ylabel("c . x")
    axes[1].set_ylabel("u")
    axes[1].set_xlabel("t")
    axes[0].set_title(f"{scene.name}: one period 2 theta*, theta* = {thf:.12g}\n"
                      "(drawn from the certified orbit; a drawing, never a verdict)", fontsize=10)
    fig.tight_layout()
    declutter_ticks(fig)
    return {f"{scene.name}_orbit.png": fig}
