"""The figures' shared style: a colour-blind-safe palette (Okabe-Ito) and tick/label de-cluttering.

Plain data and duck-typed helpers: this module imports nothing (no matplotlib, no numpy), so the
rigorous side may import it without pulling in a float library (tests/test_rules.py). The helpers take
matplotlib Figure/Axes objects built by the figure modules (the kinds' and margins' ``plots``,
``bench.plots``), which import matplotlib themselves. A figure is a float drawing of certified data; it
never decides anything.
"""
from __future__ import annotations

__all__ = ["OKABE_ITO", "STATUS_COLOURS", "STATUS_LABELS", "COUNTEREXAMPLE_COLOUR", "SERIES",
           "tick_label_overlaps", "text_overlaps", "declutter_ticks", "place_point_labels"]

#: Okabe & Ito (2008), "Color universal design": distinguishable with every common colour-vision deficiency
OKABE_ITO = {"black": "#000000", "orange": "#E69F00", "sky blue": "#56B4E9", "bluish green": "#009E73",
             "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00", "reddish purple": "#CC79A7",
             "grey": "#999999"}

#: an outcome's colour: proved bluish green, refuted vermillion, undecided / inconclusive orange
STATUS_COLOURS = {"proved": OKABE_ITO["bluish green"], "refuted": OKABE_ITO["vermillion"],
                  "undecided": OKABE_ITO["orange"], "inconclusive": OKABE_ITO["orange"]}
STATUS_LABELS = {"proved": "proved", "refuted": "refuted", "undecided": "undecided",
                 "inconclusive": "inconclusive"}
COUNTEREXAMPLE_COLOUR = OKABE_ITO["black"]
#: colours for curves that are not outcomes (methods, quantities, trajectories), in order
SERIES = [OKABE_ITO[k] for k in ("blue", "vermillion", "bluish green", "reddish purple", "orange", "sky blue",
                                 "black", "yellow")]


def _drawn(fig) -> None:
    fig.canvas.draw()


def _visible_tick_labels(axis, minor: bool | None = None) -> list:
    """The tick labels the axis actually draws (inside the view, visible, with text), by position; only the
    minor (``minor=True``) or major (False) ones when asked."""
    lo, hi = sorted(axis.get_view_interval())
    ticks = [] if minor is True else [(t, False) for t in axis.get_major_ticks()]
    ticks += [] if minor is False else [(t, True) for t in axis.get_minor_ticks()]
    out = []
    for tick, _ in ticks:
        loc = tick.get_loc()
        if loc is None or not (lo - 1e-12 * abs(hi - lo) <= loc <= hi + 1e-12 * abs(hi - lo)):
            continue
        for lab in (tick.label1, tick.label2):
            if lab.get_visible() and lab.get_text() and tick.get_visible():
                out.append((loc, lab))
    return [lab for _, lab in sorted(out, key=lambda p: p[0])]


def text_overlaps(texts, renderer=None) -> list[tuple[str, str]]:
    """Pairs of the given (drawn, visible) Text artists whose window extents overlap."""
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in texts if t.get_visible() and t.get_text()]
    bad = []
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            if boxes[i][1].overlaps(boxes[j][1]):
                bad.append((boxes[i][0], boxes[j][0]))
    return bad


def tick_label_overlaps(fig) -> list[tuple[str, str]]:
    """Pairs of tick labels of one axis of ``fig`` that overlap once drawn (empty: none collide)."""
    _drawn(fig)
    bad = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            bad += text_overlaps(_visible_tick_labels(axis))
    return bad


def _thin(fig, axis, minor: bool | None) -> None:
    """Hide every other label (then three of four, ...) of the given kind until the axis has no collision."""
    step = 2
    while text_overlaps(_visible_tick_labels(axis)) and step <= 64:
        for i, lab in enumerate(_visible_tick_labels(axis, minor)):
            if i % 2:
                lab.set_visible(False)
        _drawn(fig)
        step *= 2


def declutter_ticks(fig) -> None:
    """Make every axis's tick labels non-overlapping: thin the minor labels of a colliding axis (a log
    axis's), then rotate colliding x labels, then thin the major labels (every other one) until none
    collide."""
    _drawn(fig)
    for ax in fig.axes:
        for which, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            if not text_overlaps(_visible_tick_labels(axis)):
                continue
            _thin(fig, axis, True)
            if which == "x" and text_overlaps(_visible_tick_labels(axis)):
                for lab in ax.get_xticklabels(which="both"):
                    lab.set_rotation(30)
                    lab.set_horizontalalignment("right")
                _drawn(fig)
            _thin(fig, axis, None)


#: offsets (points) tried in order for a point label
_OFFSETS = [(5, 5), (5, -12), (-8, 6), (-8, -12), (5, 16), (-8, 16), (5, -22), (-8, -22), (14, 0), (-18, 0),
            (5, 28), (5, -34)]


def place_point_labels(ax, xs, ys, texts, fontsize: float = 7) -> list[str]:
    """Label the points (x, y) with ``texts`` so that no two labels overlap: each label takes the first
    offset of a fixed list that collides with no label placed before and covers no point; a label with no free offset is
    not drawn and returned (the caller lists it elsewhere, e.g. in the legend), so nothing is dropped
    silently. Returns the texts that could not be placed."""
    fig = ax.figure
    _drawn(fig)
    placed, left_out = [], []
    r = 5.0         # half the size of a marker (pixels): a label keeps clear of every point
    dots = [tuple(ax.transData.transform((x, y))) for x, y in zip(xs, ys)]

    def hits_a_point(ext) -> bool:
        return any(ext.x0 - r <= px <= ext.x1 + r and ext.y0 - r <= py <= ext.y1 + r for px, py in dots)

    for x, y, t in zip(xs, ys, texts):
        for dx, dy in _OFFSETS:
            a = ax.annotate(t, (x, y), textcoords="offset points", xytext=(dx, dy), fontsize=fontsize,
                            ha="left" if dx >= 0 else "right", va="bottom" if dy >= 0 else "top")
            ext = a.get_window_extent(fig.canvas.get_renderer())
            axbox = ax.get_window_extent()
            inside = axbox.x0 <= ext.x0 and ext.x1 <= axbox.x1 and axbox.y0 <= ext.y0 and ext.y1 <= axbox.y1
            if inside and not any(ext.overlaps(o) for o in placed) and not hits_a_point(ext):
                placed.append(ext)
                break
            a.remove()
        else:
            left_out.append(t)
    return left_out
