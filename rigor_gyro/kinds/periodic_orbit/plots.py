"""Figures of a proved periodic-orbit scene (``rigor-gyro prove ... --plots``): drawings, never verdicts.

* ``<name>_orbit.png``: beta, Omega, i, I over one period 2 theta* of the scene's orbit, evaluated in
  balls from the certified initial point and drawn at their midpoints (floats for drawing only).

matplotlib is imported inside :func:`plots` only (optional extra ``plots``).
"""
from __future__ import annotations

from pathlib import Path

from ...core.balls import working_precision
from .claims import validate
from .flow import Spectrum, orbit_expsums, x0_at

__all__ = ["plots"]


def plots(scene, cert, out_dir) -> list:
    """Draw beta, Omega, i, I over one period of the scene's orbit (floats for drawing only; the curve is
    evaluated from the certified initial point). Imports matplotlib here only."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if "theta_star" not in cert.quantities:
        return []
    model = validate(scene)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
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
    for ax, i in zip(axes, (0, 2, 3, 4)):
        ax.plot(ts, ys[i], lw=1.2)
        ax.axvline(thf, color="grey", lw=0.6, ls="--")
        ax.axhline(0, color="grey", lw=0.4)
        ax.set_ylabel(names[i])
    axes[-1].set_xlabel("t (s)")
    axes[0].set_title(f"{scene.name}: one period 2 theta*, theta* = {thf:.12g} s")
    fig.tight_layout()
    path = out / f"{scene.name}_orbit.png"
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return [path]
