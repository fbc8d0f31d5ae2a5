"""Work-precision figure per scene: log2 of the error or width against wall time (log), one curve per method.

A float drawing of measured and certified data; it decides nothing. Arb: the worst relative enclosure
width over the scene's quantities at each precision of the schedule (a certified error bound), one
point per precision, labelled with its bits; float and mpmath: the worst actual error against the
certified values (one point each: they have no precision knob here).

The vertical axis is log2 of the relative width or error, not the width itself: a 2048-bit enclosure is
narrower than 2^-1074, the least double, so as a float it would be 0 and a log axis would drop it. The
log2 widths are computed in balls (``workprecision.log2_width``), so every precision is drawn. A
precision with no finite width (every quantity exact or containing 0) or a method with error 0 has no
log2; it is named in the legend, not dropped silently. Needs matplotlib (the ``plots`` extra).
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from ..core.figure_style import OKABE_ITO, SERIES, declutter_ticks, place_point_labels
from .workprecision import SceneBench

__all__ = ["work_precision_figure", "build_work_precision_figure", "work_precision_points"]


def work_precision_points(sb: SceneBench | dict[str, Any]) -> dict[str, Any]:
    """What the figure draws: Arb (time, log2 width, bits) per precision with a finite width, the precisions
    without one, and per method (time, log2 error) or the reason it has none."""
    data = sb.as_json() if isinstance(sb, SceneBench) else sb
    arb_pts, undrawn = [], []
    for r in data["precisions"]:
        ws = [w for w in r["log2_widths"].values() if isinstance(w, float) and math.isfinite(w)]
        if ws:
            arb_pts.append((r["times"]["median_s"], max(ws), r["prec"]))
        else:
            undrawn.append(r["prec"])
    methods = {}
    for name, m in data["methods"].items():
        if "failed" in m:
            methods[name] = "failed"
            continue
        errs = [e for e in m["errors"].values() if e is not None]
        if not errs:
            methods[name] = "no error measured"
        elif max(errs) == 0:
            methods[name] = "error 0 (no log2)"
        else:
            methods[name] = (m["times"]["median_s"], math.log2(max(errs)))
    return {"scene": data["scene"], "arb": arb_pts, "arb_undrawn": undrawn, "methods": methods}


def build_work_precision_figure(sb: SceneBench | dict[str, Any]):
    """The Figure of one scene's work-precision (a :class:`SceneBench` or its ``as_json()``): the Arb
    curve (gid ``arb``, one point per precision), one marker per method (gid ``method-<name>``), the
    precisions as point labels that do not collide (those with no room are named in the legend)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    pts = work_precision_points(sb)
    fig, ax = plt.subplots(figsize=(7.6, 4.6))
    xs = [p[0] for p in pts["arb"]]
    ys = [p[1] for p in pts["arb"]]
    ax.plot(xs, ys, "o-", color=SERIES[0], gid="arb",
            label="Arb: log2 certified relative width (worst quantity)")
    markers = {"float": "s"}
    extra = []
    for i, (name, m) in enumerate(pts["methods"].items(), start=1):
        if isinstance(m, str):
            extra.append(Line2D([], [], linestyle="none", marker="", label=f"{name}: {m}, not drawn"))
            continue
        ax.plot([m[0]], [m[1]], linestyle="none", marker=markers.get(name, "^"), ms=8, color=SERIES[i % len(SERIES)],
                markeredgecolor="black", gid=f"method-{name}", label=f"{name}: log2 actual relative error (worst)")
    if pts["arb_undrawn"]:
        extra.append(Line2D([], [], linestyle="none", marker="",
                            label=f"Arb at {', '.join(map(str, pts['arb_undrawn']))} bits: no finite width "
                                  "(exact or contains 0), not drawn"))
    ax.set_xscale("log")
    ax.set_xlabel("wall time per proof / solve (s, median)")
    ax.set_ylabel("log2 relative width or error")
    ax.set_title(f"{pts['scene']}: error against run time (labels: Arb precision in bits)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3, color=OKABE_ITO["grey"])
    if xs:
        lo, hi = min(xs + [m[0] for m in pts["methods"].values() if not isinstance(m, str)]), \
            max(xs + [m[0] for m in pts["methods"].values() if not isinstance(m, str)])
        ax.set_xlim(lo / 1.6, hi * 1.6)
        ylo = min(ys + [m[1] for m in pts["methods"].values() if not isinstance(m, str)])
        yhi = max(ys + [m[1] for m in pts["methods"].values() if not isinstance(m, str)])
        pad = max(20.0, 0.08 * (yhi - ylo))
        ax.set_ylim(ylo - pad, yhi + pad)
    handles = ax.get_legend_handles_labels()[0] + extra
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    left = place_point_labels(ax, xs, ys, [str(p[2]) for p in pts["arb"]])
    if left:
        handles.append(Line2D([], [], linestyle="none", marker="",
                              label=f"Arb points also at {', '.join(left)} bits (labels with no room)"))
        ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    declutter_ticks(fig)
    return fig


def work_precision_figure(sb: SceneBench, out: Path) -> Path:
    """Save :func:`build_work_precision_figure` as ``<out>/<scene>.png``; the path."""
    import matplotlib.pyplot as plt
    fig = build_work_precision_figure(sb)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{sb.scene}.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path
