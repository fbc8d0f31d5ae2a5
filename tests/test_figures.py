"""Every figure is opened and checked for content: the legend names the outcomes, the palette is
Okabe-Ito, every sub-box / point / precision is drawn (none dropped silently), a 1-D paving is a strip,
and no two tick labels or point labels overlap. The figures are float drawings of certified data; these
tests check the drawing, never a verdict."""
from __future__ import annotations

from fractions import Fraction

import pytest

pytest.importorskip("matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402

from rigor_gyro import load_scene, prove_scene  # noqa: E402
from rigor_gyro.core.figure_style import (OKABE_ITO, STATUS_COLOURS, declutter_ticks, text_overlaps,  # noqa: E402
                                          tick_label_overlaps)
from rigor_gyro.margins.paving import box_scene, pave  # noqa: E402
from rigor_gyro.margins.plots import (BOX_GID, build_margin_figure, build_paving_figure, margin_plot,  # noqa: E402
                                      paving_plots)
from rigor_gyro.margins.report import paving_json  # noqa: E402
from rigor_gyro.scene import parse_scene  # noqa: E402

PALETTE = {v.lower() for v in OKABE_ITO.values()}
BOX_TEXT = """
name = "figure_box"
kind = "eigenfrequencies"
source = "a small paving for the figure tests"
[parameters]
a = "15.08"
b = "6.154"
eps = "{eps}"
Omega2 = "{omega2}"
[claims]
only = ["bracket_1", "bracket_2"]
[options]
box_resolution = "1/16"
range_boxes = "0"
"""


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _legend_texts(fig_or_ax) -> list[str]:
    legends = list(getattr(fig_or_ax, "legends", []))
    axes = fig_or_ax.axes if hasattr(fig_or_ax, "legends") and hasattr(fig_or_ax, "get_axes") else [fig_or_ax]
    for ax in axes:
        if ax.get_legend() is not None:
            legends.append(ax.get_legend())
    return [t.get_text() for lg in legends for t in lg.get_texts()]


def _boxes(fig):
    [coll] = [c for ax in fig.axes for c in ax.collections if c.get_gid() == BOX_GID]
    return coll


def _paving(eps: str, omega2: str) -> dict:
    return paving_json(pave(box_scene(parse_scene(BOX_TEXT.format(eps=eps, omega2=omega2)))))


def _synthetic_paving(names: list[str]) -> dict:
    """A paving JSON by hand: a proved box, a refuted box, an undecided box and a sliver 1e-9 wide."""
    edges = {n: ["0", "1"] for n in names}

    def box(x0, x1):
        return {n: ([str(x0), str(x1)] if i == 0 else ["0", "1"]) for i, n in enumerate(names)}
    boxes = [{"box": box(0, Fraction(1, 2)), "status": "proved"},
             {"box": box(Fraction(1, 2), Fraction(3, 4)), "status": "refuted"},
             {"box": box(Fraction(3, 4), Fraction(3, 4) + Fraction(1, 10 ** 9)), "status": "refuted"},
             {"box": box(Fraction(3, 4) + Fraction(1, 10 ** 9), 1), "status": "undecided"}]
    point = {n: "0.9" for n in names}
    claim = {"id": "c", "status": "refuted", "boxes": boxes,
             "sub_boxes": {"proved": 1, "refuted": 2, "undecided": 1},
             "volume_fraction_decimal": {"proved": "0.5", "refuted": "0.25", "undecided": "0.25"},
             "points": [{"box_outcome": "undecided", "point": point, "status": "refuted", "reason": ""},
                        {"box_outcome": "undecided", "point": {n: "0.8" for n in names}, "status": "proved",
                         "reason": ""}]}
    return {"scene": {"name": "synthetic"}, "box": edges, "claims": [claim]}


def _assert_outcome_legend(texts):
    for st in ("proved", "refuted", "undecided"):
        assert any(t.startswith(st) for t in texts), (st, texts)


# ----------------------------------------------------------------------------- pavings

def test_a_1d_paving_is_a_strip_with_every_sub_box_and_counterexample(tmp_path):
    data = _paving("[0.1, 0.9]", "0.625")
    claim = next(c for c in data["claims"] if c["id"] == "bracket_2")
    fig = build_paving_figure(data, claim)
    ax = fig.axes[0]
    coll = _boxes(fig)
    assert len(coll.get_paths()) == len(claim["boxes"]) == sum(claim["sub_boxes"].values())
    for path, b in zip(coll.get_paths(), claim["boxes"]):     # each box along the parameter, full strip height
        (x0, y0), (x1, y1) = path.get_extents().get_points()
        assert (x0, x1) == pytest.approx([float(Fraction(v)) for v in b["box"]["eps"]])
        assert (y0, y1) == (0.0, 1.0)
    assert ax.get_yticks().size == 0 and ax.get_ylim() == (0.0, 1.0)
    bb = ax.get_window_extent()
    assert bb.width > 3 * bb.height                          # a strip, not a square plane
    texts = _legend_texts(ax)
    _assert_outcome_legend(texts)
    n_ce = sum(p["status"] == "refuted" for p in claim["points"])
    assert n_ce > 0 and any(t.startswith("counterexample") and t.endswith(f": {n_ce}") for t in texts)
    [ce] = [ln for ln in ax.lines if ln.get_gid() == "points-refuted"]
    assert len(ce.get_xdata()) == n_ce
    n_pr = sum(p["status"] == "proved" for p in claim["points"])   # 0 since the small-Omega2 roots are enclosed
    pr = [ln for ln in ax.lines if ln.get_gid() == "points-proved"]
    assert [len(ln.get_xdata()) for ln in pr] == ([n_pr] if n_pr else [])
    assert tick_label_overlaps(fig) == []
    assert [p.name for p in paving_plots(data, tmp_path)] == ["figure_box_bracket_1.png", "figure_box_bracket_2.png"]


def test_a_2d_paving_draws_every_leaf_in_the_palette():
    data = _paving("[0.1, 0.2]", "0.625 +- 0.025")       # split: the parametric forms decide [0.1, 0.12] whole
    for claim in data["claims"]:
        fig = build_paving_figure(data, claim)
        coll = _boxes(fig)
        assert len(coll.get_paths()) == len(claim["boxes"]) > 1
        faces = [to_hex(c) for c in coll.get_facecolors()]
        assert faces == [STATUS_COLOURS[b["status"]].lower() for b in claim["boxes"]]
        assert set(faces) <= PALETTE
        ax = fig.axes[0]
        assert ax.get_xlabel() == "eps" and ax.get_ylabel() == "Omega2"
        _assert_outcome_legend(_legend_texts(ax))
        assert tick_label_overlaps(fig) == []


@pytest.mark.parametrize("names", [["x"], ["x", "y"], ["x", "y", "z"]])
def test_slivers_have_no_edge_and_points_are_all_drawn(names):
    data = _synthetic_paving(names)
    fig = build_paving_figure(data, data["claims"][0])
    coll = _boxes(fig)
    assert len(coll.get_paths()) == 4
    widths = list(coll.get_linewidths())
    assert widths[2] == 0 and widths[0] > 0                   # the 1e-9 sliver has no edge to hide its colour
    ax = fig.axes[0]
    assert {ln.get_gid() for ln in ax.lines} == {"points-refuted", "points-proved"}
    assert ("projection" in ax.get_title()) == (len(names) > 2)
    texts = _legend_texts(ax)
    _assert_outcome_legend(texts)
    assert any(t.startswith("counterexample") for t in texts)
    assert tick_label_overlaps(fig) == []


# ----------------------------------------------------------------------------- scans and thresholds

def test_a_scan_figure_draws_the_quantity_it_names(tmp_path):
    from rigor_gyro.margins.scan import run_scan
    scan = run_scan(load_scene("roitenberg1947"), "n", 3, lo="1", hi="100", claim="stable",
                    quantities=["stability_margin"])
    data = scan.to_json()
    data["points"][1]["quantities"]["stability_margin"] = None      # a point with no finite enclosure
    fig, stem = build_margin_figure(data)
    assert stem == "scan_roitenberg1947_n"
    top, qax = fig.axes[:2]
    assert len(fig.axes) == 2
    drawn = sum(len(ln.get_xdata()) for ln in top.lines if (ln.get_gid() or "").startswith("status-stable-"))
    assert drawn == 3                                          # every point's status
    assert {"proved", "refuted", "inconclusive"} <= set(_legend_texts(top))
    assert qax.get_ylabel() == "stability_margin" and "stability_margin" in qax.get_title()
    [bars] = qax.containers
    assert len(bars.lines[0].get_xdata()) == 2                  # the two enclosures, as error bars
    assert [ln for ln in qax.lines if ln.get_gid() == "quantity-stability_margin-missing"][0].get_xdata() == [50.5]
    assert any("no finite enclosure: 1" in t for t in _legend_texts(qax))
    mids = sorted(bars.lines[0].get_ydata())
    encl = sorted((float(p["quantities"]["stability_margin"][0]) + float(p["quantities"]["stability_margin"][1])) / 2
                  for p in data["points"] if p["quantities"]["stability_margin"])
    assert mids == pytest.approx(encl)
    colours = {to_hex(ln.get_color()) for ln in top.lines}
    assert colours <= PALETTE
    assert tick_label_overlaps(fig) == []
    assert margin_plot(scan.to_json(), tmp_path).name == "scan_roitenberg1947_n.png"


def test_a_threshold_figure_shows_every_proof_and_the_bracket():
    from rigor_gyro.margins.threshold import find_threshold
    th = find_threshold(load_scene("rudenko1976"), "Omega2", lo="1e-6", hi="1", claim="bracket_2", width="1e-3")
    data = th.to_json()
    assert data["certified"]
    fig, stem = build_margin_figure(data)
    assert stem == "margin_rudenko1976_Omega2"
    full, zoom = fig.axes
    n = sum(len(ln.get_xdata()) for ln in full.lines if (ln.get_gid() or "").startswith("steps-"))
    assert n == len(data["steps"])
    l, r = (float(Fraction(v)) for v in data["bracket"])
    for ax in (full, zoom):
        [span] = [p for p in ax.patches if p.get_gid() == "bracket"]
        assert span.get_x() == pytest.approx(l) and span.get_x() + span.get_width() == pytest.approx(r)
    lo, hi = zoom.get_xlim()
    assert lo < l < r < hi and hi - lo < 10 * (r - l)
    texts = _legend_texts(fig)
    assert any(t.startswith("certified bracket") for t in texts)
    assert {"proved", "refuted", "inconclusive"} <= set(texts)
    assert tick_label_overlaps(fig) == []


# ----------------------------------------------------------------------------- work-precision

def test_the_work_precision_figure_draws_every_precision_including_2048_bits():
    from rigor_gyro.bench.plots import build_work_precision_figure
    from rigor_gyro.bench.workprecision import SCHEDULE, bench_scene
    sb = bench_scene(load_scene("rudenko1976"), repeat=1)
    fig = build_work_precision_figure(sb)
    ax = fig.axes[0]
    [arb] = [ln for ln in ax.lines if ln.get_gid() == "arb"]
    ys = list(arb.get_ydata())
    assert len(ys) == len(SCHEDULE) == 7 and 2048 in SCHEDULE
    assert min(ys) < -2000                                     # the 2048-bit width: far below 2^-1074
    assert ys == [max(w for w in r["log2_widths"].values() if isinstance(w, float)) for r in sb.rows]
    lo, hi = ax.get_ylim()
    assert lo < min(ys) and max(ys) < hi
    assert "log2" in ax.get_ylabel()
    assert {ln.get_gid() for ln in ax.lines} >= {"method-float", "method-mpmath30"}
    labels = [t for t in ax.texts if t.get_text().isdigit()]
    no_room = [t for t in _legend_texts(ax) if t.startswith("Arb points also at")]
    named = no_room[0].split("also at ")[1].split(" bits")[0].split(", ") if no_room else []
    for p in SCHEDULE:                                         # every precision labelled, or named in the legend
        assert any(t.get_text() == str(p) for t in labels) or str(p) in named
    assert text_overlaps(labels) == []
    assert tick_label_overlaps(fig) == []


# ----------------------------------------------------------------------------- the kinds' figures

def test_the_lyapunov_figures_have_legends_and_every_curve():
    from rigor_gyro.kinds.lyapunov.plots import build_figures
    scene = load_scene("agafonov2013")
    figs = build_figures(scene, prove_scene(scene))
    assert sorted(figs) == ["agafonov2013_psi.png", "agafonov2013_slices.png", "agafonov2013_trajectories.png"]
    slices = figs["agafonov2013_slices.png"]
    assert len(slices.axes) == 3
    texts = _legend_texts(slices)
    assert any(t.startswith("region (17)") for t in texts) and any("invariant set" in t for t in texts)
    psi = figs["agafonov2013_psi.png"].axes[0]
    assert len(psi.patches) == 2 and len(_legend_texts(psi)) == 2
    a1, a2 = figs["agafonov2013_trajectories.png"].axes
    assert sum(ln.get_gid() == "trajectory" for ln in a1.lines) == 6
    assert sum(ln.get_gid() == "trajectory" for ln in a2.lines) == 6
    assert any(t.startswith("c_set") for t in _legend_texts(a2))
    for fig in figs.values():
        assert tick_label_overlaps(fig) == []


def test_the_relay_orbit_figure_has_four_curves_and_legends():
    from rigor_gyro.kinds.periodic_orbit.plots import build_figures
    scene = load_scene("roitenberg1947")
    figs = build_figures(scene, prove_scene(scene))
    [fig] = figs.values()
    assert len(fig.axes) == 4
    for ax in fig.axes:
        [curve] = [ln for ln in ax.lines if ln.get_gid() == "orbit"]
        assert len(curve.get_xdata()) == 402 and to_hex(curve.get_color()) in PALETTE
        assert any("theta*" in t for t in _legend_texts(ax))
    assert tick_label_overlaps(fig) == []


# ----------------------------------------------------------------------------- the style helpers

def test_declutter_removes_overlapping_tick_labels():
    """The overlap check can fail: 80 crowded tick labels overlap, and declutter_ticks clears them."""
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.set_xticks(range(80), [f"label{i}" for i in range(80)])
    ax.set_xlim(0, 79)
    assert tick_label_overlaps(fig) != []
    declutter_ticks(fig)
    assert tick_label_overlaps(fig) == []
    assert any(t.get_visible() for t in ax.get_xticklabels())


def test_a_stopped_threshold_and_a_bare_log_scan_are_still_drawn_in_full():
    """No bracket: one panel with every step and the outcome legend; a log scan with no quantity: only the
    status rows, one per claim, every point drawn."""
    steps = [{"value": "1/1000", "status": "proved", "reason": ""}, {"value": "1", "status": "proved", "reason": ""}]
    data = {"schema": "rigor-gyro/threshold/1", "scene": {"name": "s"}, "param": "p", "claim": "c",
            "search": ["1/1000", "1"], "certified": False, "bracket": None, "bracket_decimal": None,
            "stopped": "the claim is proved at both ends", "steps": steps}
    fig, _ = build_margin_figure(data)
    [ax] = fig.axes
    assert sum(len(ln.get_xdata()) for ln in ax.lines) == 2 and ax.get_xscale() == "log"
    assert not [p for p in ax.patches if p.get_gid() == "bracket"]
    assert {"proved", "refuted", "inconclusive"} <= set(_legend_texts(fig))
    assert tick_label_overlaps(fig) == []
    pts = [{"value": v, "claims": {"a": {"status": sa}, "b": {"status": sb}}, "quantities": {}}
           for v, sa, sb in (("1/10", "proved", "refuted"), ("1", "inconclusive", "refuted"),
                             ("10", "refuted", "proved"))]
    scan = {"schema": "rigor-gyro/scan/1", "scene": {"name": "s"}, "param": "p", "claims": ["a", "b"],
            "quantities": [], "log": True, "points": pts,
            "counts": {"a": {"proved": 1, "refuted": 1, "inconclusive": 1},
                       "b": {"proved": 1, "refuted": 2, "inconclusive": 0}}}
    fig, _ = build_margin_figure(scan)
    [top] = fig.axes
    assert top.get_xscale() == "log"
    for c in ("a", "b"):
        assert sum(len(ln.get_xdata()) for ln in top.lines if ln.get_gid().startswith(f"status-{c}-")) == 3
    colours = {ln.get_gid(): to_hex(ln.get_color()) for ln in top.lines}
    assert colours["status-a-inconclusive"] == STATUS_COLOURS["inconclusive"].lower()
    assert colours["status-b-refuted"] == STATUS_COLOURS["refuted"].lower()
    assert tick_label_overlaps(fig) == []


def test_the_lyapunov_figures_draw_a_scene_s_own_moment_law():
    # the float drawing model is built with the scene's [moment] table (without it: ParameterError)
    from rigor_gyro.kinds.lyapunov.plots import build_figures
    from rigor_gyro.scene import builtin_scenes
    assert "agafonov2013_sine_cubic" in builtin_scenes("moment")
    scene = load_scene("agafonov2013_sine_cubic")
    figs = build_figures(scene, prove_scene(scene))
    assert sorted(figs) == [f"agafonov2013_sine_cubic_{n}.png" for n in ("psi", "slices", "trajectories")]
