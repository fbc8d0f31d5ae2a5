"""The SIVIA picture of a paving: sub-boxes coloured by outcome (float drawing of certified boxes).

One figure per claim, ``<out>/<name>_<claim>.png``: with two box parameters, the plane of both; with
one, the interval against a unit height; with more, the projection onto the first two (each box is
drawn over its projection, so a colour says that some box projecting there has that outcome). Green:
proved for every parameter in the sub-box; red: refuted for every parameter; yellow: undecided;
black dots: point counterexamples re-proved by the point prover. Needs the ``plots`` extra.

:func:`margin_plot` draws a threshold (``rigor-gyro margin``: each point proof of the bisection at its
value, the certified bracket shaded) or a scan (``--scan``: each point proof at its value, coloured by
the claim's status, against the first quantity asked for, its certified enclosure as an error bar).
"""
from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import Any

__all__ = ["paving_plots", "margin_plot"]

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


def margin_plot(data: dict[str, Any], out_dir: str | Path) -> Path:
    """One figure for a threshold or scan result (``to_json()`` of either), ``<out>/<stem>.png``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colour = {"proved": COLOURS["proved"], "refuted": COLOURS["refuted"], "inconclusive": COLOURS["undecided"]}
    name, param = data["scene"]["name"], data["param"]
    fig, ax = plt.subplots(figsize=(6.5, 4))
    if data["schema"].startswith("rigor-gyro/scan/"):
        claim = data["claims"][-1]
        q = data["quantities"][0] if data["quantities"] else None
        for p in data["points"]:
            x = float(Fraction(p["value"]))
            st = p["claims"][claim]["status"]
            b = p["quantities"].get(q) if q else None
            if b:
                lo, hi = float(b[0]), float(b[1])
                ax.errorbar([x], [(lo + hi) / 2], yerr=[[(hi - lo) / 2], [(hi - lo) / 2]], fmt="o",
                            color=colour[st], markersize=5)
            else:
                ax.plot([x], [0.5], "o", color=colour[st], markersize=6)
        if data.get("log"):
            ax.set_xscale("log")
        ax.set_ylabel(q or "")
        if not q:
            ax.set_yticks([])
        k = data["counts"][claim]
        ax.set_title(f"{name}: scan of {param}, claim {claim!r} (point proofs)\nproved at {k['proved']}, refuted at "
                     f"{k['refuted']}, inconclusive at {k['inconclusive']} points", fontsize=9)
        stem = f"scan_{name}_{param}"
    else:
        for i, st in enumerate(data["steps"], start=1):
            ax.plot([float(Fraction(st["value"]))], [i], "o", color=colour.get(st["status"], "black"), markersize=5)
        if data.get("bracket"):
            l, r = (float(Fraction(v)) for v in data["bracket"])
            ax.axvspan(l, r, color="#90caf9", alpha=0.6, label=f"certified bracket [{data['bracket_decimal'][0]}, "
                                                               f"{data['bracket_decimal'][1]}]")
            ax.legend(fontsize=7, loc="upper right")
        ax.set_ylabel("point proof (step)")
        ax.set_title(f"{name}: threshold of {data['claim']!r} in {param}\n"
                     + ("certified" if data["certified"] else f"stopped: {data['stopped'][:80]}"), fontsize=9)
        stem = f"margin_{name}_{param}"
    ax.set_xlabel(param)
    path = Path(out_dir) / f"{stem}.png"
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path

