"""An inner estimate of the domain of attraction beyond {V < c}: a paving of the slice x2 = 0 by certified trajectories.

The slice x2 = 0, the (x1, x3) plane, is cut into an N x N grid of boxes (exact rational ends) over the square
|x1| <= L e1, |x3| <= L e3, where e1, e3 are the half-extents of the ellipse {V(x1, 0, x3) < c} (V is a quadratic
form on this slice: F(0) = f3(0) = 0) and L the option ``paving_scale``. Each box is

* ``inside``: already in the component of {V < c} around 0 (:func:`rigor_gyro.kinds.lyapunov.trajectories.in_estimate`);
* ``enters``: the validated flow of the whole box (Lohner form, stored steps and order) reaches, within the model time
  T, a step end whose enclosure lies in that component: every point of the box is in the domain of attraction;
* ``skipped``: V at the box's centre exceeds ``SKIP_FACTOR`` c (not tried: the integration budget is kept for boxes
  near the set);
* ``undecided``: the flow did not enter within T or its step budget (a budget never refutes anything).

The area gained: the boxes that enter and lie certainly outside {V < c} on the slice (V > c on the whole box at
t = 0) are disjoint from the ellipse, so the slice of the certified inner estimate (ellipse union entering boxes)
has area at least A_ellipse + sum of their areas; ``area_ratio_lower`` = 1 + that sum / A_ellipse, with A_ellipse
= 2 pi c / sqrt(4 a11 a33 - a13^2) for V = a11 x1^2 + a13 x1 x3 + a33 x3^2, enclosed in balls.

Precision: the current working precision. Fails when: see the trajectories module (undecided boxes stay undecided).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb

import math

from ...core.balls import certainly_gt, exact_endpoints
from .model import Gimbal
from .trajectories import enters_estimate, exact_ball, fraction_text, in_estimate, parse_fraction

__all__ = ["above_level", "PavedBox", "SlicePaving", "slice_form", "ellipse_area", "ellipse_extents", "pave_slice", "box_balls",
           "SKIP_FACTOR", "gained_area", "recheck_box"]

#: boxes whose centre has V above this multiple of c are not integrated
SKIP_FACTOR = 40
#: the step budget of one box's integration
BOX_STEPS = 400


def slice_form(g: Gimbal) -> tuple[arb, arb, arb]:
    """(a11, a13, a33) with V(x1, 0, x3) = a11 x1^2 + a13 x1 x3 + a33 x3^2 exactly (V (7) at x2 = 0)."""
    c = g.c
    z = arb(0)
    return c.H ** 2 / (2 * c.B0 ** 2), c.mu * c.H / c.B0, (g.f2(z) + c.mu * g.f1(z)) / 2


def ellipse_area(g: Gimbal, level: arb) -> arb:
    a11, a13, a33 = slice_form(g)
    return 2 * arb.pi() * level / (4 * a11 * a33 - a13 * a13).sqrt()


def ellipse_extents(g: Gimbal, level: arb) -> tuple[arb, arb]:
    """Half-extents in x1 and x3 of {a11 x1^2 + a13 x1 x3 + a33 x3^2 < level}: sqrt(4 c a33 / D), sqrt(4 c a11 / D),
    D = 4 a11 a33 - a13^2."""
    a11, a13, a33 = slice_form(g)
    d = 4 * a11 * a33 - a13 * a13
    return (4 * level * a33 / d).sqrt(), (4 * level * a11 / d).sqrt()


@dataclass
class PavedBox:
    x1: tuple[Fraction, Fraction]
    x3: tuple[Fraction, Fraction]
    status: str
    steps: list[Fraction] = field(default_factory=list)
    order: int = 0
    outside: bool = False          # V > level certainly on the whole box at t = 0

    def area(self) -> Fraction:
        return (self.x1[1] - self.x1[0]) * (self.x3[1] - self.x3[0])

    def to_json(self) -> dict:
        return {"x1": [fraction_text(x) for x in self.x1], "x3": [fraction_text(x) for x in self.x3],
                "status": self.status, "steps": [fraction_text(h) for h in self.steps], "order": self.order,
                "outside": self.outside}

    @classmethod
    def from_json(cls, d: dict) -> "PavedBox":
        return cls(tuple(parse_fraction(x) for x in d["x1"]), tuple(parse_fraction(x) for x in d["x3"]),
                   str(d["status"]), [parse_fraction(h) for h in d["steps"]], int(d["order"]), bool(d["outside"]))


@dataclass
class SlicePaving:
    boxes: list[PavedBox]
    half_width: tuple[Fraction, Fraction]
    grid: int
    t_max: Fraction

    def count(self, status: str) -> int:
        return sum(1 for b in self.boxes if b.status == status)


#: bisection depth of the test V > c over a box of the slice (a ball product x1 * x1 over a wide ball reaches
#: below 0: the direct evaluation alone rarely decides)
ABOVE_DEPTH = 5


def above_level(g: Gimbal, x1: tuple[Fraction, Fraction], x3: tuple[Fraction, Fraction], level: arb,
                depth: int = ABOVE_DEPTH) -> bool:
    """V(x1, 0, x3) > level for every point of the rectangle, certainly: the direct enclosure on the rectangle, else
    on its four quarters, recursively to ``depth``."""
    balls = [exact_ball(x1[0]).union(exact_ball(x1[1])), arb(0), exact_ball(x3[0]).union(exact_ball(x3[1]))]
    if certainly_gt(g.V(*balls), level):
        return True
    if depth <= 0:
        return False
    m1, m3 = (x1[0] + x1[1]) / 2, (x3[0] + x3[1]) / 2
    return all(above_level(g, a, b, level, depth - 1) for a in ((x1[0], m1), (m1, x1[1]))
               for b in ((x3[0], m3), (m3, x3[1])))


def box_balls(b: PavedBox) -> list[arb]:
    lo1, hi1 = (exact_ball(x) for x in b.x1)
    lo3, hi3 = (exact_ball(x) for x in b.x3)
    return [lo1.union(hi1), arb(0), lo3.union(hi3)]


def _rational_above(x: arb, digits: int = 6) -> Fraction:
    """A rational of about ``digits`` significant digits, at or above x's upper end (floats only choose it)."""
    _, hi = exact_endpoints(x.upper())
    k = digits - 1 - math.floor(math.log10(float(hi)))
    scale = Fraction(10) ** k
    q = Fraction(math.ceil(hi * scale)) / scale
    return q if q >= hi else q + 1 / scale


def pave_slice(g: Gimbal, level: arb, reach: arb, grid: int, scale: Fraction, t_max: Fraction,
               order: int, box_steps: int = BOX_STEPS) -> SlicePaving:
    """The grid paving of the module docstring (every box decided by balls alone)."""
    e1, e3 = ellipse_extents(g, level)
    w1, w3 = _rational_above(e1 * arb(scale.numerator) / scale.denominator), \
        _rational_above(e3 * arb(scale.numerator) / scale.denominator)
    boxes = []
    for i in range(grid):
        for j in range(grid):
            x1 = (-w1 + 2 * w1 * i / grid, -w1 + 2 * w1 * (i + 1) / grid)
            x3 = (-w3 + 2 * w3 * j / grid, -w3 + 2 * w3 * (j + 1) / grid)
            pb = PavedBox(x1, x3, "undecided")
            balls = box_balls(pb)
            pb.outside = above_level(g, x1, x3, level)
            centre = [exact_ball((x1[0] + x1[1]) / 2), arb(0), exact_ball((x3[0] + x3[1]) / 2)]
            if in_estimate(g, balls, level, reach):
                pb.status = "inside"
            elif certainly_gt(g.V(*centre), SKIP_FACTOR * level):
                pb.status = "skipped"
            else:
                tr = enters_estimate(g, balls, level, reach, t_max, order=order, max_steps=box_steps)
                if tr.reached:
                    pb.status, pb.steps, pb.order = "enters", tr.steps, order
            boxes.append(pb)
    return SlicePaving(boxes, (w1, w3), grid, t_max)


def recheck_box(g: Gimbal, b: PavedBox, level: arb, reach: arb) -> bool:
    """Re-run a stored box: 'inside' re-decided at t = 0; 'enters' re-integrated at its stored steps and order, the
    last step end in the estimate; 'outside' (when stated) re-decided. Other statuses claim nothing."""
    balls = box_balls(b)
    if b.outside and not above_level(g, b.x1, b.x3, level):
        return False
    if b.status == "inside":
        return in_estimate(g, balls, level, reach)
    if b.status == "enters":
        if not b.steps or b.order < 1:
            return False
        tr = enters_estimate(g, balls, level, reach, sum(b.steps, Fraction(0)), steps=b.steps, order=b.order)
        return tr.reached
    return b.status in ("skipped", "undecided")


def gained_area(boxes: list[PavedBox]) -> Fraction:
    """The area of the entering boxes certainly outside the ellipse (exact)."""
    return sum((b.area() for b in boxes if b.status == "enters" and b.outside), Fraction(0))

