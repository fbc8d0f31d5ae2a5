"""Certified trajectories of system (2): the validated flow of :mod:`rigor_gyro.core.validated_flow` on the gimbal.

Three uses, each an opt-in claim of :mod:`rigor_gyro.kinds.lyapunov.claims` (re-run by the checker at the stored
step sequence and order):

* :func:`region_exit`: region (17) (|x2| <= x2*, x1^2 + x3^2 <= R^2) is not positively invariant: the trajectory
  from a rational point of the region (x1 = R_q <= R, x2 = x3 = 0, R_q the largest multiple of 10^-12 certainly
  <= R) is enclosed until an enclosure at a step end lies certainly outside the region
  (:func:`certainly_outside_region`). Nutation turns x1 into x3 with amplitude ratio about sqrt(A0/B0) > 1, so it
  leaves within a quarter of a nutation period.
* :func:`enters_estimate`: a box of initial values converges to 0 when the enclosure of its trajectories at some
  step end lies in the component of {V < c} around 0 for a certified level c (:func:`in_estimate`).
* :func:`equilibrium_other_than_origin`: a start that is exactly an equilibrium other than 0 (x1 = x3 = 0,
  x2 = r pi with f(r pi) = 0 exactly, r != 0) certainly does not converge to 0 (uniqueness of solutions).

:func:`in_estimate` (the component test): for c <= natural_c_max_lower and E the certified reach of the natural
sublevel set (phi < c_lower on [0, E], phi even for an odd law), a box with V < c and |x2| <= E certainly lies in
the component of {V < c} that contains 0: at each fixed x2 with |x2| <= E, {V < c} is the inside of an ellipse in
(x1, x3) (V is a positive definite quadratic in (x1, x3) plus phi(x2) < c) containing the minimiser of V on that
slice, which moves continuously with x2 and is 0 at x2 = 0; so every such point is joined to 0 inside {V < c}.

Precision: the current working precision (the prover's; the checker re-runs at the certificate's).
Fails when: the flow cannot be verified (a step below h_min) or the budget of steps or model time runs out before
the enclosure decides: the result says so (never a verdict from a budget).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_gt, certainly_le, certainly_lt, exact_endpoints
from ...core.validated_flow import Flow, validated_flow
from .model import Gimbal
from .polar_forms import law_is_odd

__all__ = ["FLOW_ORDER", "EXIT_TIME", "gimbal_field", "exact_ball", "exact_box", "certainly_outside_region",
           "certainly_inside_region", "region_exit_point", "region_exit", "in_estimate", "enters_estimate",
           "equilibrium_other_than_origin", "Trajectory", "fraction_text", "parse_fraction"]

#: Taylor order of every stored integration (stored with the steps: the checker uses the stored one)
FLOW_ORDER = 20
#: model time allowed for the trajectory from region (17) to leave it (a quarter nutation period is 1.1 ms)
EXIT_TIME = Fraction(1, 10)
#: the exit point's x1 is a multiple of this just below R
EXIT_GRID = Fraction(1, 10 ** 12)


def gimbal_field(g: Gimbal):
    """System (2) as a vector field on balls, series and Grads (Gimbal.rhs works on all three)."""
    return lambda x: g.rhs(x[0], x[1], x[2])


def exact_ball(q: Fraction) -> arb:
    return arb(fmpq(q.numerator, q.denominator))


def exact_box(point) -> list[arb]:
    return [exact_ball(Fraction(x)) for x in point]


def fraction_text(q: Fraction) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def parse_fraction(text: str) -> Fraction:
    return Fraction(str(text))


def certainly_outside_region(box, R: arb, xs: arb) -> bool:
    """Every point of the box lies outside region (17): x1^2 + x3^2 > R^2 or |x2| > x2*, certainly."""
    x1, x2, x3 = box
    return certainly_gt(x1 * x1 + x3 * x3, R * R) or certainly_gt(abs(x2), xs)


def certainly_inside_region(box, R: arb, xs: arb) -> bool:
    x1, x2, x3 = box
    return certainly_le(x1 * x1 + x3 * x3, R * R) and certainly_le(abs(x2), xs)


def region_exit_point(R: arb) -> tuple[Fraction, Fraction, Fraction]:
    """(R_q, 0, 0): R_q the largest multiple of ``EXIT_GRID`` at or below R's lower end."""
    lo, _ = exact_endpoints(R.lower())
    q = Fraction(int(lo / EXIT_GRID)) * EXIT_GRID
    return q, Fraction(0), Fraction(0)


@dataclass
class Trajectory:
    """A stored integration: start, order, steps, whether its goal was reached, and why not."""

    point: tuple[Fraction, ...]
    order: int
    flow: Flow
    reached: bool
    reason: str = ""

    @property
    def steps(self) -> list[Fraction]:
        return self.flow.step_sizes

    @property
    def time(self) -> Fraction:
        return self.flow.t

    def witness(self) -> dict:
        return {"point": [fraction_text(Fraction(x)) for x in self.point], "order": self.order,
                "steps": [fraction_text(h) for h in self.steps]}


def region_exit(g: Gimbal, R: arb, xs: arb, point=None, steps=None, order: int = FLOW_ORDER,
                t_max: Fraction = EXIT_TIME, max_steps: int = 100000) -> Trajectory:
    """Integrate from ``point`` (default :func:`region_exit_point`) until a step end lies certainly outside
    region (17) (or re-run ``steps``); ``reached`` only when the start is certainly inside the region and the last
    step end certainly outside. At most ``max_steps`` steps (then not ``reached``, the reason says so)."""
    point = tuple(point) if point is not None else region_exit_point(R)
    box = exact_box(point)
    if not certainly_inside_region(box, R, xs):
        return Trajectory(point, order, Flow(order), False, "the start is not certainly inside region (17)")
    fl = validated_flow(gimbal_field(g), box, t_max, order, steps=steps, max_steps=max_steps,
                        stop=None if steps is not None else (lambda st: certainly_outside_region(st.end, R, xs)))
    ok = bool(fl.steps) and certainly_outside_region(fl.steps[-1].end, R, xs)
    why = "" if ok else (fl.reason or f"the enclosure stayed inside or on the boundary up to t = {float(fl.t):.6g}")
    return Trajectory(point, order, fl, ok, why)


def in_estimate(g: Gimbal, box, level: arb, reach: arb) -> bool:
    """The box lies in the component of {V < level} around 0 (module docstring): V < level on the box and
    |x2| <= reach, certainly (the caller guarantees level <= the certified c_lower whose reach this is and an odd
    law)."""
    x1, x2, x3 = box
    if not law_is_odd(g.law):
        return False
    return certainly_le(abs(x2), reach) and certainly_lt(g.V(x1, x2, x3), level)


def enters_estimate(g: Gimbal, box, level: arb, reach: arb, t_max: Fraction, steps=None, order: int = FLOW_ORDER,
                    max_steps: int = 4000, point=None) -> Trajectory:
    """Integrate the box until a step end lies in the component of {V < level} around 0 (or re-run ``steps``)."""
    box = list(box)
    if in_estimate(g, box, level, reach):
        return Trajectory(tuple(point or ()), order, Flow(order, complete=True), True, "")
    fl = validated_flow(gimbal_field(g), box, t_max, order, steps=steps, max_steps=max_steps,
                        stop=None if steps is not None else (lambda st: in_estimate(g, st.end, level, reach)))
    ok = bool(fl.steps) and in_estimate(g, fl.steps[-1].end, level, reach)
    why = "" if ok else (fl.reason or f"the enclosure had not entered the estimate by t = {float(fl.t):.6g}")
    return Trajectory(tuple(point or ()), order, fl, ok, why)


def equilibrium_other_than_origin(g: Gimbal, x1, x2_over_pi: Fraction | None, x3) -> bool:
    """True when (x1, r pi, x3) with x1 = x3 = 0 exactly and r != 0 a stored exact zero of the law (f(r pi) = 0):
    an equilibrium of (2) other than 0, from which the solution stays put (x2' = x3 = 0, x3' = 0 at x1 = 0,
    x1' = -f(x2)/D = 0)."""
    if x2_over_pi is None or Fraction(x1) != 0 or Fraction(x3) != 0 or x2_over_pi == 0:
        return False
    return any(Fraction(r) == x2_over_pi for r in g.law.zeros_over_pi())
