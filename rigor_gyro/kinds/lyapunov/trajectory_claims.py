"""The opt-in trajectory claims of the lyapunov kind (issue 40, part 2): statements, proofs and their re-checks.

* ``region_not_invariant``: region (17) is not positively invariant (a certified trajectory from a rational point of
  the region leaves it), while the sublevel estimates stay positively invariant by the Lyapunov argument;
* ``initial_point``: the trajectory from the scene option ``initial_point`` converges to 0 (its enclosure enters the
  component of {V < natural_c_max_lower} around 0, inside the domain of attraction by natural_sublevel); refuted
  only when the point is exactly an equilibrium other than 0; otherwise, if the budget ends first, inconclusive.

The integrations are those of :mod:`rigor_gyro.kinds.lyapunov.trajectories` (validated Taylor flow, Lohner form);
the witness stores the start (exact rationals), the order and every step (exact dyadic rationals), and
:func:`check_region_exit` / :func:`check_initial_point` re-run exactly those steps and re-decide the end.

Precision: the attempt's (prover) or the certificate's (checker). Fails when: see the trajectories module; a claim
whose integration stops is inconclusive with the integrator's reason (never refuted by a budget).
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb

from ...core.balls import certainly_gt, certainly_le, decimal_bounds
from ...core.exact import Exact, parse_exact
from ...core.errors import ParameterError
from ...core.outcome import Claim, Status
from .model import Gimbal
from .polar_forms import law_is_odd
from .trajectories import (FLOW_ORDER, enters_estimate, equilibrium_other_than_origin, exact_ball, exact_box,
                           fraction_text, parse_fraction, region_exit)

__all__ = ["paving_claim", "check_paving", "PAVING_TEXT", "TRAJECTORY_CLAIMS", "TRAJECTORY_OPTIONS", "parse_initial_point", "region_not_invariant_claim",
           "initial_point_claim", "check_region_exit", "check_initial_point", "INITIAL_POINT_STEPS"]

TRAJECTORY_CLAIMS = {
    "region_not_invariant": "Region (17) (|x2| <= x2*, x1^2 + x3^2 <= R^2, R = R_used) is not positively invariant: the "
                            "solution of system (2) from the stored rational point of the region (x1 just below R, "
                            "x2 = x3 = 0) leaves it; its validated enclosure (Taylor method of the stored order, a-priori "
                            "enclosure by the high-order Picard test, Lohner form) at the end of the stored steps lies "
                            "certainly outside the region. V at the point exceeds c* of invariant_estimate, so this does "
                            "not contradict the positive invariance of the sublevel estimates, which rests on Vdot <= 0 on "
                            "them (invariant_estimate, largest_sublevel, natural_sublevel).",
    "initial_point": "The solution of system (2) from the point of the scene option initial_point converges to the origin: "
                     "its validated enclosure at the end of the stored steps lies in the component of "
                     "{V < natural_c_max_lower} around 0 (V < natural_c_max_lower and |x2| <= the certified reach of "
                     "natural_sublevel, on the enclosure), which lies in the domain of attraction (natural_sublevel). "
                     "Refuted only when the point is exactly an equilibrium other than 0; when the enclosure has not "
                     "entered within initial_point_time, inconclusive.",
}
#: option -> default (merged into the kind's OPTIONS)
TRAJECTORY_OPTIONS = {"initial_point": "", "initial_point_time": "1"}
#: step budget of one initial_point integration (about 40 ms a step on the paper's example at order 20)
INITIAL_POINT_STEPS = 3000


def parse_initial_point(text: str) -> tuple[Exact, Exact, Exact]:
    """"x1, x2, x3" as exact numbers (x2 may be a rational multiple of pi; x1, x3 rational)."""
    parts = [p.strip() for p in str(text).split(",")]
    if len(parts) != 3 or not all(parts):
        raise ParameterError(f"option 'initial_point' = {text!r}: need three numbers \"x1, x2, x3\"")
    xs = [parse_exact(p, f"initial_point[{i}]") for i, p in enumerate(parts)]
    if xs[0].pi_power or xs[2].pi_power or xs[1].pi_power not in (0, 1):
        raise ParameterError(f"option 'initial_point' = {text!r}: x1 and x3 must be rational, x2 rational or "
                             "a rational multiple of pi")
    return xs[0], xs[1], xs[2]


def _fmt(x: arb, digits: int = 8) -> str:
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def region_not_invariant_claim(g: Gimbal, R: arb, xs: arb, c_star: arb | None, witnesses: dict) -> Claim:
    text = TRAJECTORY_CLAIMS["region_not_invariant"]
    tr = region_exit(g, R, xs)
    if not tr.reached:
        return Claim("region_not_invariant", text, Status.INCONCLUSIVE,
                     f"no certified exit of region (17) from the point x1 = {fraction_text(tr.point[0])}: {tr.reason}",
                     details={}, counterexample=None, decides=None)
    box = exact_box(tr.point)
    v0 = g.V(*box)
    end = tr.flow.steps[-1].end
    witnesses["region_not_invariant"] = tr.witness()
    vs = ""
    if c_star is not None and c_star.is_finite():
        vs = (f"; V at the point = {_fmt(v0)} > c* = {_fmt(c_star)}" if certainly_gt(v0, c_star)
              else f"; V at the point = {_fmt(v0)}")
    r2 = end[0] * end[0] + end[2] * end[2]
    return Claim(
        "region_not_invariant", text, Status.PROVED,
        f"from (x1, x2, x3) = ({fraction_text(tr.point[0])}, 0, 0) (in region (17), R = {_fmt(R, 10)}) the enclosure at "
        f"t = {fraction_text(tr.time)} = {float(tr.time):.6g} ({len(tr.steps)} steps, order {tr.order}) has "
        f"x1^2 + x3^2 in {_fmt(r2, 8)} > R^2 = {_fmt(R * R, 8)}: the solution has left the region (nutation turns x1 "
        f"into x3 with amplitude ratio about sqrt(A0/B0)){vs}",
        details={"point": [fraction_text(x) for x in tr.point], "exit_time": fraction_text(tr.time),
                 "steps": len(tr.steps), "order": tr.order},
        counterexample=None, decides=None)


def initial_point_claim(g: Gimbal, point: tuple[Exact, Exact, Exact] | None, t_max: Fraction,
                        level: arb | None, reach: arb | None, witnesses: dict) -> Claim:
    text = TRAJECTORY_CLAIMS["initial_point"]

    def inconclusive(why: str, decides=None) -> Claim:
        c = Claim("initial_point", text, Status.INCONCLUSIVE, why, details={}, counterexample=None, decides=decides)
        c.precision_cannot_help = why
        return c
    if point is None:
        return inconclusive("no option initial_point = \"x1, x2, x3\" in the scene")
    x1, x2, x3 = point
    desc = f"({x1.text}, {x2.text}, {x3.text})"
    r = x2.rational if x2.pi_power == 1 else (Fraction(0) if x2.rational == 0 else None)
    if equilibrium_other_than_origin(g, x1.rational, r, x3.rational):
        return Claim("initial_point", text, Status.REFUTED,
                     f"{desc} is an equilibrium of (2) other than 0 (x1 = x3 = 0, f(x2) = 0 exactly): the solution "
                     "stays there and does not converge to 0",
                     details={"point": [x1.text, x2.text, x3.text]},
                     counterexample={"equilibrium": [x1.text, x2.text, x3.text]}, decides=None)
    if level is None or reach is None:
        return inconclusive("needs a proved natural_sublevel (its level and certified reach) in the same scene: add "
                            "it to [claims] only")
    if not law_is_odd(g.law):
        return inconclusive("the component test needs an odd moment law")
    if x2.pi_power:
        return inconclusive("x2 must be rational to be integrated from an exact point")
    box = [x1.ball(), x2.ball(), x3.ball()]
    tr = enters_estimate(g, box, level, reach, t_max, max_steps=INITIAL_POINT_STEPS,
                         point=(x1.rational, x2.rational, x3.rational))
    if not tr.reached:
        return inconclusive(f"the enclosure from {desc} did not enter {{V < natural_c_max_lower}} within "
                            f"t = {float(t_max):.6g} ({tr.reason}): neither convergence nor divergence is certified; "
                            "try a larger initial_point_time")
    witnesses["initial_point"] = tr.witness()
    end = tr.flow.steps[-1].end if tr.flow.steps else box
    v_end = g.V(*end)
    return Claim("initial_point", text, Status.PROVED,
                 f"from {desc} (V = {_fmt(g.V(*box))}) the enclosure at t = {fraction_text(tr.time)} = "
                 f"{float(tr.time):.6g} ({len(tr.steps)} steps, order {tr.order}) has V in {_fmt(v_end)} < "
                 f"natural_c_max_lower = {_fmt(level, 10)} and |x2| <= {_fmt(abs(end[1]).upper(), 6)} <= reach "
                 f"{_fmt(reach, 8)}: in the certified estimate, so the solution converges to 0",
                 details={"point": [x1.text, x2.text, x3.text], "entry_time": fraction_text(tr.time),
                          "steps": len(tr.steps), "order": tr.order},
                 counterexample=None, decides=None)


def _stored(w: dict):
    point = tuple(parse_fraction(x) for x in w["point"])
    steps = [parse_fraction(h) for h in w["steps"]]
    order = int(w["order"])
    if len(point) != 3 or order < 1 or order > 64 or any(h <= 0 for h in steps):
        raise ValueError("bad stored integration")
    return point, steps, order


def check_region_exit(g: Gimbal, R: arb | None, xs: arb, w: dict | None) -> tuple[bool, str]:
    """Re-run the stored integration from the stored point at the stored steps and order: the point certainly in
    region (17), the last step end certainly outside."""
    if not w or R is None:
        return False, "no stored integration, or no re-derived R"
    try:
        point, steps, order = _stored(w)
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "the stored point, steps or order are not readable"
    if not steps:
        return False, "no stored steps"
    tr = region_exit(g, R, xs, point=point, steps=steps, order=order, t_max=sum(steps, Fraction(0)))
    return tr.reached, ("the stored integration re-run: the start is in region (17) and the enclosure at the last "
                        f"step end ({len(steps)} steps, order {order}) is outside" if tr.reached else
                        f"the re-run does not leave the region certainly: {tr.reason}")


def check_initial_point(g: Gimbal, point: tuple[Exact, Exact, Exact] | None, level: arb | None, reach: arb | None,
                        w: dict | None) -> tuple[bool, str]:
    """Re-run the stored integration from the scene's initial_point at the stored steps and order; its last step end
    must lie in the component of {V < level} around 0 (level, reach: re-verified by the natural_sublevel check)."""
    if not w or point is None or level is None or reach is None:
        return False, "no stored integration, no initial_point option, or no re-verified natural_sublevel"
    try:
        stored, steps, order = _stored(w)
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "the stored point, steps or order are not readable"
    if point[1].pi_power or tuple(p.rational for p in point) != stored:
        return False, "the stored point is not the scene's initial_point"
    box = [exact_ball(q) for q in stored]
    t_end = sum(steps, Fraction(0))
    tr = enters_estimate(g, box, level, reach, t_end if steps else Fraction(0), steps=steps or None, order=order)
    return tr.reached, (f"the stored integration re-run ({len(steps)} steps, order {order}): the enclosure lies in "
                        "{V < natural_c_max_lower}, |x2| <= reach" if tr.reached else
                        f"the re-run does not enter the estimate: {tr.reason}")


# ------------------------------------------------------------------------------------ the slice paving (part 2b)

PAVING_TEXT = ("On the slice x2 = 0 (the (x1, x3) plane), every box listed as 'enters' lies in the domain of attraction of "
               "0: the validated flow of the whole box (stored steps and order) reaches the component of "
               "{V < natural_c_max_lower} around 0 (natural_sublevel) within the model time paving_time; every box "
               "listed 'inside' lies in that component already. The entering boxes on which V > natural_c_max_lower "
               "(certainly, at t = 0) are disjoint from the sublevel set's slice, so the slice of the certified inner "
               "estimate (the set's slice and those boxes) has area at least area_ratio_lower times the area of "
               "{V(x1, 0, x3) < natural_c_max_lower} (an ellipse, its area enclosed in closed form).")
TRAJECTORY_CLAIMS["attraction_paving"] = PAVING_TEXT
TRAJECTORY_OPTIONS.update({"paving_grid": "8", "paving_scale": "3", "paving_time": "3"})


def paving_claim(g: Gimbal, level: arb | None, reach: arb | None, grid: int, scale: Fraction, t_max: Fraction,
                 witnesses: dict) -> Claim:
    from .attraction_paving import ellipse_area, gained_area, pave_slice
    if level is None or reach is None:
        c = Claim("attraction_paving", PAVING_TEXT, Status.INCONCLUSIVE,
                  "needs a proved natural_sublevel (its level and certified reach) in the same scene",
                  details={}, counterexample=None, decides=None)
        c.precision_cannot_help = c.reason
        return c
    pv = pave_slice(g, level, reach, grid, scale, t_max, FLOW_ORDER)
    area = ellipse_area(g, level)
    gain = gained_area(pv.boxes)
    ratio = 1 + exact_ball(gain) / area
    lo, _ = decimal_bounds(ratio, 8)
    witnesses["attraction_paving"] = {"grid": grid, "half_width": [fraction_text(x) for x in pv.half_width],
                                      "t_max": fraction_text(t_max), "boxes": [b.to_json() for b in pv.boxes]}
    counts = {s: pv.count(s) for s in ("inside", "enters", "skipped", "undecided")}
    steps = [len(b.steps) for b in pv.boxes if b.status == "enters"]
    return Claim("attraction_paving", PAVING_TEXT, Status.PROVED,
                 f"{grid} x {grid} boxes over |x1| <= {float(pv.half_width[0]):.6g}, |x3| <= {float(pv.half_width[1]):.6g} "
                 f"({scale} times the slice's half-extents): {counts['inside']} inside, {counts['enters']} enter within "
                 f"t = {float(t_max):.6g} ({min(steps) if steps else 0} to {max(steps) if steps else 0} steps of order "
                 f"{FLOW_ORDER}), {counts['skipped']} not tried (V > {40} c at the centre), {counts['undecided']} undecided; "
                 f"the entering boxes outside the sublevel slice add area {float(gain):.6g} to its {_fmt(area, 6)}: "
                 f"the certified inner estimate's slice is at least {lo} times the sublevel set's",
                 details={"area_ratio_lower": lo, "gained_area": fraction_text(gain), **counts},
                 counterexample=None, decides=None)


def check_paving(g: Gimbal, level: arb | None, reach: arb | None, w: dict | None, details: dict) -> tuple[bool, str]:
    """Re-run every stored box (entering ones at their stored steps and order), re-derive the gained area exactly
    and the stated lower bound of the area ratio."""
    from .attraction_paving import PavedBox, ellipse_area, gained_area, recheck_box
    if not w or level is None or reach is None:
        return False, "no stored paving, or no re-verified natural_sublevel"
    try:
        boxes = [PavedBox.from_json(b) for b in w["boxes"]]
        stated = parse_fraction(details["area_ratio_lower"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "the stored boxes or the stated ratio are not readable"
    for b in boxes:
        if not recheck_box(g, b, level, reach):
            return False, f"the box x1 in {b.x1}, x3 in {b.x3} ({b.status}) is not re-derived"
    ratio = 1 + exact_ball(gained_area(boxes)) / ellipse_area(g, level)
    if not (ratio.is_finite() and certainly_le(exact_ball(stated), ratio)):
        return False, "the stated area_ratio_lower is above the re-derived ratio"
    return True, f"{len(boxes)} stored boxes re-derived (the entering ones re-integrated); the area ratio re-derived"
