"""The SIVIA picture of a paving: sub-boxes coloured by outcome (float drawing of certified boxes).

One figure per claim, ``<out>/<name>_<claim>.png``: with two box parameters, the plane of both; with
one, the interval against a unit height; with more, the projection onto the first two (each box is
drawn over its projection, so a colour says that some box projecting there has that outcome). Green:
proved for every parameter in the sub-box; red: refuted for every parameter; yellow: undecided;
black dots: point counterexamples re-proved by the point prover. Needs the ``plots`` extra.
"""
from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import Any

__all__ = ["paving_plots"]

COLOURS = {"proved": "#4caf50", "refuted": "#e53935", "undecided": "#fdd835"}


def paving_plots(data: dict[str, Any], out_dir: str | Path) -> list[Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    names = list(data["box"])
    x, y = names[0], (names[1] if len(names) > 1 else None)
    paths = []
    for c in data["claims"]:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        rects, colours = [], []
        for b in c["boxes"]:
            x0, x1 = (float(Fraction(v)) for v in b["box"][x])
            y0, y1 = (float(Fraction(v)) for v in b["box"][y]) if y else (0.0, 1.0)
            rects.append(Rectangle((x0, y0), x1 - x0, y1 - y0))
            colours.append(COLOURS[b["status"]])
        ax.add_collection(PatchCollection(rects, facecolors=colours, edgecolors="black",
                                          linewidths=0.2 if len(rects) < 2000 else 0.0))
        for p in c["points"]:
            if p["status"] == "refuted":
                px = float(Fraction(p["point"][x]))
                py = float(Fraction(p["point"][y])) if y else 0.5
                ax.plot(px, py, "k.", markersize=3)
        lo, hi = (float(Fraction(v)) for v in data["box"][x])
        ax.set_xlim(lo, hi)
        if y:
            lo, hi = (float(Fraction(v)) for v in data["box"][y])
            ax.set_ylim(lo, hi)
            ax.set_ylabel(y)
        else:
            ax.set_ylim(0, 1)
            ax.set_yticks([])
        ax.set_xlabel(x)
        v = c["volume_fraction_decimal"]
        ax.set_title(f"{data['scene']['name']}: {c['id']}: {c['status']}\n"
                     f"proved {v['proved']}, refuted {v['refuted']}, undecided {v['undecided']}", fontsize=9)
        path = Path(out_dir) / f"{data['scene']['name']}_{c['id']}.png"
        fig.tight_layout()
        fig.savefig(path, dpi=120)
        plt.close(fig)
        paths.append(path)
    return paths
