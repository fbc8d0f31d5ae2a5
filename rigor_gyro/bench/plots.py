"""Work-precision figure per scene: error (log) against wall time (log), one curve per method.

Arb: the worst relative enclosure width over the scene's quantities at each precision of the schedule
(a certified error bound); float and mpmath: the worst actual error against the certified values (one
point each: they have no precision knob here). Needs matplotlib (the ``plots`` extra)."""
from __future__ import annotations

from pathlib import Path

from .workprecision import SceneBench

__all__ = ["work_precision_figure"]


def work_precision_figure(sb: SceneBench, out: Path) -> Path:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    xs, ys, labels = [], [], []
    for r in sb.rows:
        ws = [w for w in r["log2_widths"].values() if isinstance(w, float)]
        if ws and max(ws) > -1070:          # below a double's range the point cannot be drawn
            xs.append(r["times"]["median_s"])
            ys.append(2.0 ** max(ws))
            labels.append(str(r["prec"]))
    ax.loglog(xs, ys, "o-", label="Arb (certified width)")
    for x, y, t in zip(xs, ys, labels):
        ax.annotate(t, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    for name, m in sb.methods.items():
        if "failed" in m:
            continue
        errs = [e for e in m["errors"].values() if e]
        if errs:
            ax.loglog([m["times"]["median_s"]], [max(errs)], "s" if name == "float" else "^", ms=8,
                      label=f"{name} (actual error)")
    ax.set_xlabel("wall time per proof / solve (s)")
    ax.set_ylabel("worst relative error or width")
    ax.set_title(f"{sb.scene}: error against run time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{sb.scene}.png"
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
