"""Figures of pavings, thresholds and scans: float drawings of certified data, never a verdict.

A figure decides nothing: every colour and position is read from the certified JSON (exact rationals
drawn as floats), and the JSON and its report are the result.

:func:`build_paving_figure` (one figure per claim, saved by :func:`paving_plots` as
``<out>/<name>_<claim>.png``), the SIVIA picture of a paving: with one box parameter a 1-D strip (the
sub-intervals along the parameter's axis); with two, the plane of both; with more, the projection onto
the first two (each box is drawn over its projection, so a colour says that some box projecting there
has that outcome). Colours (Okabe-Ito, colour-blind safe): bluish green proved for every parameter in
the sub-box, vermillion refuted for every parameter, orange undecided; black crosses: point
counterexamples re-proved refuted by the point prover; hollow markers: the other point proofs (midpoints
of undecided sub-boxes). Every sub-box is drawn (a sliver narrower than a pixel has no edge, so its
colour is not hidden by one); the legend gives the counts and volume fractions.

:func:`build_margin_figure` (saved by :func:`margin_plot` as ``<out>/<stem>.png``) draws a threshold
(``rigor-gyro margin``: each point proof of the bisection at its value, the certified bracket shaded,
with a zoom on the bracket) or a scan (``--scan``: one row of point proofs per claim, coloured by
status; below, each quantity asked for against the parameter, its certified enclosure as an error bar;
a point with no finite enclosure is marked at the bottom of the panel, not dropped).

Needs the ``plots`` extra (matplotlib, imported inside the functions only).
"""
from __future__ import annotations

from fractions import Fraction
from pathlib import Path
from typing import Any

from ..core.figure_style import COUNTEREXAMPLE_COLOUR, OKABE_ITO, STATUS_COLOURS, declutter_ticks

__all__ = ["paving_plots", "margin_plot", "build_paving_figure", "build_margin_figure", "build_safe_set_figure",
           "safe_set_plot", "COLOURS"]

COLOURS = {k: STATUS_COLOURS[k] for k in ("proved", "refuted", "undecided")}
BOX_GID = "paving-boxes"
BRACKET_COLOUR = OKABE_ITO["sky blue"]


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _f(v) -> float:
    return float(Fraction(v))


def _slim_ticks(ax, axes: str = "both") -> None:
    """Few ticks, and an offset/scientific notation on a narrow range (labels stay short)."""
    from matplotlib.ticker import MaxNLocator, ScalarFormatter
    for name in ("x", "y"):
        if axes not in ("both", name):
            continue
        axis = ax.xaxis if name == "x" else ax.yaxis
        if axis.get_scale() != "linear":
            continue
        axis.set_major_locator(MaxNLocator(nbins=5))
        fmt = ScalarFormatter(useOffset=True)
        fmt.set_powerlimits((-3, 4))
        axis.set_major_formatter(fmt)


def _axes(data: dict[str, Any], axes: tuple[str, ...] | None) -> tuple[str, str | None]:
    """The parameters drawn along x and y: ``axes`` (one or two box parameters) or the box's first two."""
    names = list(data["box"])
    if axes:
        unknown = [a for a in axes if a not in names]
        if unknown or not 1 <= len(axes) <= 2 or len(set(axes)) != len(axes):
            from ..core.errors import ParameterError
            raise ParameterError(f"--axes {','.join(axes)}: name one or two distinct box parameters "
                                 f"({', '.join(names)})")
        return axes[0], (axes[1] if len(axes) > 1 else None)
    return names[0], (names[1] if len(names) > 1 else None)


def _draw_boxes(ax, data: dict[str, Any], boxes: list[tuple[dict, str]], x: str, y: str | None) -> None:
    """One patch per box ({name: [lo, hi]}, status) projected onto (x, y), in the status colours; an
    edge only where the box is wide enough to show its colour (1/40 of the range)."""
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle
    xlo, xhi = (_f(v) for v in data["box"][x])
    ylo, yhi = (_f(v) for v in data["box"][y]) if y else (0.0, 1.0)
    rects, colours, widths = [], [], []
    for box, status in boxes:
        x0, x1 = (_f(v) for v in box[x])
        y0, y1 = (_f(v) for v in box[y]) if y else (0.0, 1.0)
        rects.append(Rectangle((x0, y0), x1 - x0, y1 - y0))
        colours.append(COLOURS[status])
        thick = (x1 - x0) >= (xhi - xlo) / 40 and (not y or (y1 - y0) >= (yhi - ylo) / 40)
        widths.append(0.3 if thick else 0.0)
    coll = PatchCollection(rects, facecolors=colours, edgecolors="#333333", linewidths=widths)
    coll.set_gid(BOX_GID)
    ax.add_collection(coll)
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(ylo, yhi)
    ax.set_xlabel(x)
    if y:
        ax.set_ylabel(y)
        _slim_ticks(ax)
    else:
        ax.set_yticks([])
        _slim_ticks(ax, "x")


def build_paving_figure(data: dict[str, Any], claim: dict[str, Any], axes: tuple[str, ...] | None = None):
    """The Figure of one claim of a paving (``paving_json``): one patch per sub-box (the PatchCollection
    with gid ``paving-boxes``), the point proofs as markers, a legend of the outcomes; ``axes``: the one
    or two box parameters to draw (default: the first two; more parameters are projected)."""
    plt = _pyplot()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    x, y = _axes(data, axes)
    fig, ax = plt.subplots(figsize=(9.0, 5.0) if y else (9.5, 2.4))
    _draw_boxes(ax, data, [(b["box"], b["status"]) for b in claim["boxes"]], x, y)

    handles = []
    n, v = claim["sub_boxes"], claim["volume_fraction_decimal"]
    for st in ("proved", "refuted", "undecided"):
        handles.append(Patch(facecolor=COLOURS[st], edgecolor="#333333", linewidth=0.3,
                             label=f"{st}: {n[st]} sub-box(es), {_short(v[st])} of the volume"))
    groups = {"refuted": ("X", COUNTEREXAMPLE_COLOUR, COUNTEREXAMPLE_COLOUR,
                          "counterexample (point proof: refuted)"),
              "proved": ("o", "none", COUNTEREXAMPLE_COLOUR, "point proof: proved (undecided box's midpoint)"),
              "inconclusive": ("s", "none", OKABE_ITO["grey"], "point proof: inconclusive")}
    for st, (marker, face, edge, label) in groups.items():
        pts = [p for p in claim["points"] if p["status"] == st]
        if not pts:
            continue
        px = [_f(p["point"][x]) for p in pts]
        py = [_f(p["point"][y]) if y else 0.5 for p in pts]
        ax.plot(px, py, linestyle="none", marker=marker, markersize=6 if st == "refuted" else 5,
                markerfacecolor=face, markeredgecolor=edge, gid=f"points-{st}")
        handles.append(Line2D([], [], linestyle="none", marker=marker, markerfacecolor=face, markeredgecolor=edge,
                              label=f"{label}: {len(pts)}"))
    return _finish(fig, ax, data, f"{claim['id']}: {claim['status']} over the box", (x, y), handles)


def _finish(fig, ax, data: dict[str, Any], what: str, axes: tuple, handles: list):
    """The title (naming a projection when the box has more parameters than the axes drawn), the legend
    beside the axes, the layout."""
    names = list(data["box"])
    drawn = [n for n in axes if n]
    extra = f" (projection onto {', '.join(drawn)} of {len(names)} parameters)" if len(names) > len(drawn) else ""
    ax.set_title(f"{data['scene']['name']}: {what}{extra}\n(a float drawing of the certified paving)", fontsize=9)
    ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.tight_layout()
    declutter_ticks(fig)
    return fig


def _short(dec: str) -> str:
    """A volume fraction's decimal text, at most 6 significant digits (the report has them all)."""
    try:
        return f"{float(dec):.6g}"
    except ValueError:
        return dec


def paving_plots(data: dict[str, Any], out_dir: str | Path, axes: tuple[str, ...] | None = None,
                 formats: tuple[str, ...] = ("png",)) -> list[Path]:
    """Save :func:`build_paving_figure` of every claim as ``<out>/<name>_<claim>.<format>`` for each of
    ``formats`` (png, svg, pdf); the paths."""
    plt = _pyplot()
    paths = []
    for c in data["claims"]:
        fig = build_paving_figure(data, c, axes)
        paths.extend(_save(fig, Path(out_dir) / f"{data['scene']['name']}_{c['id']}", formats))
        plt.close(fig)
    return paths


def _save(fig, stem: Path, formats: tuple[str, ...]) -> list[Path]:
    out = []
    for fmt in formats:
        if fmt not in ("png", "svg", "pdf"):
            from ..core.errors import ParameterError
            raise ParameterError(f"figure format {fmt!r}: choose png, svg or pdf")
        path = stem.with_name(f"{stem.name}.{fmt}")
        fig.savefig(path, dpi=120, bbox_inches="tight", metadata={"Date": None} if fmt == "svg" else None)
        out.append(path)
    return out


def build_safe_set_figure(data: dict[str, Any], safe: dict[str, Any], axes: tuple[str, ...] | None = None):
    """The Figure of a paving's safe set (:func:`rigor_gyro.margins.safe_set.safe_set`): each piece of the
    claims' common refinement coloured by the status of "every selected claim holds", the certified
    yield in the legend."""
    plt = _pyplot()
    from matplotlib.patches import Patch
    x, y = _axes(data, axes)
    fig, ax = plt.subplots(figsize=(9.0, 5.0) if y else (9.5, 2.4))
    _draw_boxes(ax, data, [(b.to_json(), st) for b, st in safe["pieces"]], x, y)
    labels = {"proved": "safe: every claim proved", "refuted": "some claim refuted",
              "undecided": "undecided"}
    handles = [Patch(facecolor=COLOURS[st], edgecolor="#333333", linewidth=0.3,
                     label=f"{labels[st]}: {safe['counts'][st]} piece(s)") for st in ("proved", "refuted", "undecided")]
    vol, yl = safe["volume"], safe["yield"]
    handles.append(Patch(facecolor="none", edgecolor="none",
                         label=f"volume fraction safe: [{vol['lower']}, {vol['upper']}]"))
    laws = sorted(set(safe["laws"].values()))
    if laws != ["uniform"]:
        said = (f"every parameter {laws[0]}" if len(laws) == 1 else
                "; ".join(f"{k}: {v}" for k, v in safe["laws"].items()))
        handles.append(Patch(facecolor="none", edgecolor="none",
                             label=f"yield ({said}): [{yl['lower']}, {yl['upper']}]"))
    return _finish(fig, ax, data, f"where {', '.join(safe['claims'])} all hold", (x, y), handles)


def safe_set_plot(data: dict[str, Any], safe: dict[str, Any], out_dir: str | Path,
                  axes: tuple[str, ...] | None = None, formats: tuple[str, ...] = ("png",)) -> list[Path]:
    """Save :func:`build_safe_set_figure` as ``<out>/<name>_safe_set.<format>``; the paths."""
    plt = _pyplot()
    fig = build_safe_set_figure(data, safe, axes)
    paths = _save(fig, Path(out_dir) / f"{data['scene']['name']}_safe_set", formats)
    plt.close(fig)
    return paths


def build_margin_figure(data: dict[str, Any]):
    """The Figure of a threshold or scan result (``to_json()`` of either) and its file stem."""
    if data["schema"].startswith("rigor-gyro/scan/"):
        return _scan_figure(data), f"scan_{data['scene']['name']}_{data['param']}"
    if data["schema"].startswith("rigor-gyro/threshold-curve/"):
        return _curve_figure(data), f"curve_{data['scene']['name']}_{data['param']}_{data['along']}"
    return _threshold_figure(data), f"margin_{data['scene']['name']}_{data['param']}"


def margin_plot(data: dict[str, Any], out_dir: str | Path) -> Path:
    """One figure for a threshold or scan result (``to_json()`` of either), ``<out>/<stem>.png``."""
    plt = _pyplot()
    fig, stem = build_margin_figure(data)
    path = Path(out_dir) / f"{stem}.png"
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return path


def _status_handles(statuses):
    from matplotlib.lines import Line2D
    return [Line2D([], [], linestyle="none", marker="o", markerfacecolor=STATUS_COLOURS[s],
                   markeredgecolor="#333333", label=s) for s in statuses]


def _scan_figure(data: dict[str, Any]):
    plt = _pyplot()
    name, param, claims, quantities = data["scene"]["name"], data["param"], data["claims"], data["quantities"]
    xs = [_f(p["value"]) for p in data["points"]]
    nq = len(quantities)
    fig, axes = plt.subplots(1 + nq, 1, figsize=(8.5, 1.2 + 0.45 * len(claims) + 2.6 * nq), sharex=True,
                             gridspec_kw={"height_ratios": [0.6 + 0.35 * len(claims)] + [2.6] * nq}, squeeze=False)
    axes = axes[:, 0]
    top = axes[0]
    for i, c in enumerate(claims):
        for st in ("proved", "refuted", "inconclusive"):
            px = [x for x, p in zip(xs, data["points"]) if p["claims"][c]["status"] == st]
            if px:
                top.plot(px, [i] * len(px), "o", linestyle="none", color=STATUS_COLOURS[st], markeredgecolor="#333333",
                         markersize=6, gid=f"status-{c}-{st}")
    top.set_yticks(range(len(claims)), claims)
    top.set_ylim(-0.6, len(claims) - 0.4)
    k = "; ".join(f"{c}: proved at {data['counts'][c]['proved']}, refuted at {data['counts'][c]['refuted']}, "
                  f"inconclusive at {data['counts'][c]['inconclusive']}" for c in claims)
    top.set_title(f"{name}: scan of {param}, {len(xs)} exact points (point proofs; nothing is claimed between "
                  f"them)\n{k}", fontsize=8)
    top.legend(handles=_status_handles(("proved", "refuted", "inconclusive")), fontsize=7, loc="upper left",
               bbox_to_anchor=(1.01, 1.0), borderaxespad=0, title="claim status", title_fontsize=7)
    from matplotlib.lines import Line2D
    for ax, q in zip(axes[1:], quantities):
        have = [(x, p["quantities"].get(q)) for x, p in zip(xs, data["points"])]
        good = [(x, float(b[0]), float(b[1])) for x, b in have if b]
        missing = [x for x, b in have if not b]
        if good:
            mids = [(lo + hi) / 2 for _, lo, hi in good]
            err = [(hi - lo) / 2 for _, lo, hi in good]
            ax.errorbar([g[0] for g in good], mids, yerr=err, fmt="o", color=OKABE_ITO["blue"], ecolor="black",
                        capsize=3, markersize=4, gid=f"quantity-{q}")
        handles = [Line2D([], [], marker="o", color=OKABE_ITO["blue"], linestyle="none",
                          label=f"{q} ({len(good)} points)")]
        if missing:
            ax.plot(missing, [0.02] * len(missing), "v", linestyle="none", color=OKABE_ITO["grey"],
                    transform=ax.get_xaxis_transform(), gid=f"quantity-{q}-missing")
            handles.append(Line2D([], [], marker="v", color=OKABE_ITO["grey"], linestyle="none",
                                  label=f"no finite enclosure: {len(missing)} points"))
        ax.set_ylabel(q)
        ax.set_title(f"{q} against {param}: its certified enclosure at each scan point (error bar, often below a "
                     "pixel)", fontsize=8)
        ax.legend(handles=handles, fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        _slim_ticks(ax, "y")
    if data.get("log"):
        axes[-1].set_xscale("log")
    else:
        _slim_ticks(axes[-1], "x")
    axes[-1].set_xlabel(param)
    fig.tight_layout()
    declutter_ticks(fig)
    return fig


def _threshold_figure(data: dict[str, Any]):
    plt = _pyplot()
    name, param = data["scene"]["name"], data["param"]
    steps = data["steps"]
    bracket = [_f(v) for v in data["bracket"]] if data.get("bracket") else None
    fig, axes = plt.subplots(1, 2 if bracket else 1, figsize=(10.5 if bracket else 6.5, 4.2), squeeze=False)
    axes = axes[0]
    lo, hi = (_f(v) for v in data["search"])
    from matplotlib.ticker import MaxNLocator
    for ax in axes:
        for st in ("proved", "refuted", "inconclusive"):
            pts = [(i, _f(s["value"])) for i, s in enumerate(steps, start=1) if s["status"] == st]
            if pts:
                ax.plot([p[1] for p in pts], [p[0] for p in pts], "o", linestyle="none", color=STATUS_COLOURS[st],
                        markeredgecolor="#333333", markersize=5, gid=f"steps-{st}")
        other = [(i, _f(s["value"])) for i, s in enumerate(steps, start=1)
                 if s["status"] not in ("proved", "refuted", "inconclusive")]
        if other:
            ax.plot([p[1] for p in other], [p[0] for p in other], "s", linestyle="none", color="black", markersize=5)
        if bracket:
            ax.axvspan(bracket[0], bracket[1], color=BRACKET_COLOUR, alpha=0.5, gid="bracket")
        ax.set_ylabel("point proof (step)")
        ax.yaxis.set_major_locator(MaxNLocator(nbins=6, integer=True))
        ax.set_xlabel(param)
    ax0 = axes[0]
    if lo > 0 and hi / lo > 100:
        ax0.set_xscale("log")
    else:
        _slim_ticks(ax0, "x")
    ax0.set_xlim(lo - (hi - lo) * 0.02 if ax0.get_xscale() == "linear" else lo / 1.5,
                 hi + (hi - lo) * 0.02 if ax0.get_xscale() == "linear" else hi * 1.5)
    from matplotlib.patches import Patch
    handles = _status_handles(("proved", "refuted", "inconclusive"))
    if bracket:
        handles.append(Patch(color=BRACKET_COLOUR, alpha=0.5, label=f"certified bracket [{data['bracket_decimal'][0]}, "
                                                                     f"{data['bracket_decimal'][1]}]"))
        zoom = axes[1]
        w = bracket[1] - bracket[0]
        zoom.set_xlim(bracket[0] - 1.5 * w, bracket[1] + 1.5 * w)
        _slim_ticks(zoom, "x")
        zoom.set_title("zoom on the bracket", fontsize=8)
    ax0.set_title(f"{name}: threshold of {data['claim']!r} in {param}: "
                  + ("certified" if data["certified"] else f"stopped: {data['stopped'][:80]}"), fontsize=9)
    fig.legend(handles=handles, fontsize=7, loc="lower center", ncol=len(handles), bbox_to_anchor=(0.5, 0.0))
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    declutter_ticks(fig)
    return fig


def _curve_figure(data: dict[str, Any]):
    """A threshold curve: each cell's certified band as a rectangle (the claim's outcome changes inside it for
    every value of the cell), the proved side and the refuted side marked."""
    from matplotlib.patches import Rectangle
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(8.5, 4.8))
    for c in data["cells"]:
        a0, a1 = (_f(x) for x in c["along"])
        if c["band"] is None:
            ax.axvspan(a0, a1, color=STATUS_COLOURS["undecided"], alpha=0.25, lw=0)
            continue
        lo, hi = (_f(x) for x in c["band"])
        ax.add_patch(Rectangle((a0, lo), a1 - a0, hi - lo, facecolor="#444444", edgecolor="none", gid="band"))
        p, r = _f(c["proved_at"]), _f(c["refuted_at"])
        ax.plot([a0, a1], [p, p], color=STATUS_COLOURS["proved"], lw=1.5)
        ax.plot([a0, a1], [r, r], color=STATUS_COLOURS["refuted"], lw=1.5)
    ax.autoscale_view()
    ax.set_xlabel(data["along"])
    ax.set_ylabel(data["param"])
    from matplotlib.lines import Line2D
    handles = [Rectangle((0, 0), 1, 1, facecolor="#444444", label="certified band: the outcome changes inside"),
               Line2D([], [], color=STATUS_COLOURS["proved"], label=f"{data['claim']} proved on the whole cell"),
               Line2D([], [], color=STATUS_COLOURS["refuted"], label=f"{data['claim']} refuted on the whole cell")]
    ax.legend(handles=handles, loc="best", fontsize=8)
    ax.set_title(f"{data['scene']['name']}: threshold of {data['claim']} in {data['param']} along {data['along']}",
                 fontsize=10)
    fig.tight_layout()
    return fig
