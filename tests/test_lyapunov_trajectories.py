"""Trajectory claims of the lyapunov kind (issue 40, part 2): region (17) not invariant, convergence from a point.

The levels used here are the certified ones of natural_sublevel on the paper's example (c_lower = 77.2245103353671,
reach 583/512); mpmath and scipy only cross-check (V sampled on a certified box; the float trajectory crosses the
same boundary).
"""
from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.exact import parse_exact
from rigor_gyro.core.outcome import Status
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, FloatGimbal, MpGimbal
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.trajectories import (certainly_inside_region, certainly_outside_region,
                                                    enters_estimate, equilibrium_other_than_origin, exact_box,
                                                    in_estimate, region_exit, region_exit_point)
from rigor_gyro.kinds.lyapunov.trajectory_claims import (check_initial_point, check_region_exit, initial_point_claim,
                                                         parse_initial_point, region_not_invariant_claim)

PREC = 64
R = "0.0106"                        # the paper's printed R
LEVEL = Fraction("77.2245103353671")   # natural_c_max_lower of agafonov2013_natural (certified)
REACH = Fraction(583, 512)


def _g():
    return gimbal_from_parameters(dict(AGAFONOV2013))[0]


def _level():
    return arb(fmpq(LEVEL.numerator, LEVEL.denominator)), arb(fmpq(583, 512))


def test_region_17_is_left_by_a_certified_trajectory_and_the_checker_reruns_it():
    g = _g()
    with working_precision(PREC):
        Rb = arb(fmpq(106, 10000))
        w: dict = {}
        c = region_not_invariant_claim(g, Rb, g.c.x2_star, None, w)
        assert c.status is Status.PROVED, c.reason
        wit = w["region_not_invariant"]
        x1 = Fraction(wit["point"][0])
        assert Fraction(106, 10000) - Fraction(2, 10 ** 12) < x1 <= Fraction(106, 10000)
        assert wit["order"] == 20 and wit["steps"]
        ok, msg = check_region_exit(g, Rb, g.c.x2_star, wit)
        assert ok, msg
        # the stored steps cut: at t = 0 nothing has left
        bad = dict(wit, steps=[])
        assert not check_region_exit(g, Rb, g.c.x2_star, bad)[0]
        # a stored point outside the region is no witness
        assert not check_region_exit(g, Rb, g.c.x2_star, dict(wit, point=["1/50", "0", "0"]))[0]
        # a step far too long for the order: the re-run cannot verify it, so nothing is re-derived
        assert not check_region_exit(g, Rb, g.c.x2_star, dict(wit, steps=["1/2"]))[0]
        # a start well inside: after the stored step it is still inside
        inside = dict(wit, point=["1/1000", "0", "0"])
        assert not check_region_exit(g, Rb, g.c.x2_star, inside)[0]
    # scipy cross-check: the float trajectory from the same point leaves the disc too
    from scipy.integrate import solve_ivp
    fg = FloatGimbal(dict(AGAFONOV2013))
    t_exit = float(Fraction(wit["steps"][0]))
    sol = solve_ivp(fg.rhs_scalar, (0, t_exit), [0.0106, 0, 0], rtol=1e-11, atol=1e-14)
    assert sol.y[0, -1] ** 2 + sol.y[2, -1] ** 2 > 0.0106 ** 2


def test_region_predicates_decide_only_when_certain():
    with working_precision(PREC):
        Rb, xs = arb(1), arb(1)
        assert certainly_outside_region([arb(1), arb(0), arb("0.5")], Rb, xs)
        assert not certainly_outside_region([arb(1), arb(0), arb(0)], Rb, xs)       # on the boundary
        assert not certainly_outside_region([arb("0.9", "0.2"), arb(0), arb(0)], Rb, xs)
        assert certainly_outside_region([arb(0), arb("1.1"), arb(0)], Rb, xs)
        assert certainly_inside_region([arb(1), arb(0), arb(0)], Rb, xs)
        assert not certainly_inside_region([arb(1, "0.01"), arb(0), arb(0)], Rb, xs)
        assert not certainly_inside_region([arb(0), arb("1.01"), arb(0)], Rb, xs)
        q = region_exit_point(arb(fmpq(106, 10000)) + arb(0, "1e-20"))
        assert q[0] <= Fraction(106, 10000) and Fraction(106, 10000) - q[0] < Fraction(2, 10 ** 12)


def test_in_estimate_is_sound_on_sampled_points():
    """A certified box in the estimate: V sampled in mpmath stays below the level everywhere in it; a box reaching
    past the reach or above the level is refused."""
    g = _g()
    mg = MpGimbal(dict(AGAFONOV2013))
    with working_precision(PREC):
        level, reach = _level()
        box = [arb("0.001", "1e-4"), arb("0.5", "1e-3"), arb("0.001", "1e-4")]
        assert in_estimate(g, box, level, reach)
        assert not in_estimate(g, [box[0], arb("1.14", "1e-3"), box[2]], level, reach)   # |x2| > reach possible
        assert not in_estimate(g, [arb("0.0053"), arb(0), arb(0)], level, reach)            # V > level there
        # V < level certainly, but |x2| = 1.14 beyond the certified reach: refused (the reach decides)
        beyond = [arb("4.3768179e-7", "1e-12"), arb("1.14", "1e-9"), arb("-0.0217587513", "1e-12")]
        assert g.V(*beyond) < level and not in_estimate(g, beyond, level, reach)
        # a box straddling the level (V from below to above it): refused
        straddle = [arb("0.005218", "2e-6"), arb(0), arb(0)]
        assert g.V(*straddle).contains(level) and not in_estimate(g, straddle, level, reach)
    mpmath.mp.dps = 30
    for i in range(-2, 3):
        for j in range(-2, 3):
            for k in range(-2, 3):
                x1 = mpmath.mpf("0.001") + i * mpmath.mpf("1e-4") / 2
                x2 = mpmath.mpf("0.5") + j * mpmath.mpf("1e-3") / 2
                x3 = mpmath.mpf("0.001") + k * mpmath.mpf("1e-4") / 2
                assert mg.V(x1, x2, x3) < mpmath.mpf(LEVEL.numerator) / LEVEL.denominator


def test_initial_point_converges_and_the_checker_reruns_the_steps():
    g = _g()
    pt = parse_initial_point("0.005221, 0, 0")
    with working_precision(PREC):
        level, reach = _level()
        w: dict = {}
        c = initial_point_claim(g, pt, Fraction(1, 10), level, reach, w)
        assert c.status is Status.PROVED, c.reason
        wit = w["initial_point"]
        assert len(wit["steps"]) > 5
        ok, msg = check_initial_point(g, pt, level, reach, wit)
        assert ok, msg
        # half the steps: the enclosure has not entered yet
        assert not check_initial_point(g, pt, level, reach, dict(wit, steps=wit["steps"][:len(wit["steps"]) // 2]))[0]
        # another point than the scene's
        assert not check_initial_point(g, parse_initial_point("0.00522, 0, 0"), level, reach, wit)[0]
        # a level just below V at the stored end: the same steps do not prove it
        assert not check_initial_point(g, pt, level - 1, reach, wit)[0]
    # the float trajectory agrees: V falls below the level by the certified entry time
    from scipy.integrate import solve_ivp
    fg = FloatGimbal(dict(AGAFONOV2013))
    t_in = float(sum(Fraction(h) for h in wit["steps"]))
    sol = solve_ivp(fg.rhs_scalar, (0, t_in), [0.005221, 0, 0], rtol=1e-11, atol=1e-14)
    assert fg.V(*sol.y[:, -1]) < float(LEVEL)


def test_initial_point_refuted_only_at_an_exact_other_equilibrium_else_inconclusive():
    g = _g()
    with working_precision(PREC):
        level, reach = _level()
        c = initial_point_claim(g, parse_initial_point("0, pi, 0"), Fraction(1), level, reach, {})
        assert c.status is Status.REFUTED and c.counterexample == {"equilibrium": ["0", "pi", "0"]}
        # far outside the estimate: no verdict within a short time (never refuted by a budget)
        c = initial_point_claim(g, parse_initial_point("0, 1.3, 0"), Fraction(1, 1000), level, reach, {})
        assert c.status is Status.INCONCLUSIVE
        c = initial_point_claim(g, parse_initial_point("0.005221, 0, 0"), Fraction(1), None, None, {})
        assert c.status is Status.INCONCLUSIVE and "natural_sublevel" in c.reason
    assert equilibrium_other_than_origin(g, 0, Fraction(-1), 0)
    assert not equilibrium_other_than_origin(g, 0, Fraction(0), 0)
    assert not equilibrium_other_than_origin(g, Fraction(1, 10), Fraction(1), 0)
    assert not equilibrium_other_than_origin(g, 0, Fraction(1, 2), 0)      # f(pi/2) != 0 for the sine law
    assert not equilibrium_other_than_origin(g, 0, None, 0)


def test_initial_point_option_is_parsed_exactly():
    x1, x2, x3 = parse_initial_point("0.005221, pi, -1/3")
    assert x1.rational == Fraction(5221, 10 ** 6) and x2.pi_power == 1 and x3.rational == Fraction(-1, 3)
    from rigor_gyro.core.errors import ParameterError
    for bad in ("1, 2", "pi, 0, 0", "a, b, c", "1,,2"):
        with pytest.raises(ParameterError):
            parse_initial_point(bad)


# ------------------------------------------------------------------------------------ the slice paving (part 2b)

DEMO = dict(AGAFONOV2013, H="100", a="1", k="20")
DEMO_LEVEL = Fraction("0.00773069206889387")       # natural_c_max_lower of the demo parameters (certified)


def test_a_small_slice_paving_is_certified_and_rechecked():
    from rigor_gyro.kinds.lyapunov.attraction_paving import (PavedBox, above_level, ellipse_area, gained_area,
                                                             recheck_box)
    from rigor_gyro.kinds.lyapunov.trajectory_claims import check_paving, paving_claim
    g = gimbal_from_parameters(DEMO)[0]
    with working_precision(PREC):
        level = arb(fmpq(DEMO_LEVEL.numerator, DEMO_LEVEL.denominator))
        reach = arb(fmpq(583, 512))
        w: dict = {}
        c = paving_claim(g, level, reach, 2, Fraction(3, 2), Fraction(3), w)
        assert c.status is Status.PROVED and c.details["area_ratio_lower"] in ("1", "1.0000000")
        boxes = [PavedBox.from_json(b) for b in w["attraction_paving"]["boxes"]]
        assert [b.status for b in boxes] == ["enters"] * 4
        # all four boxes touch the origin's neighbourhood: none is disjoint from the ellipse, nothing is gained
        assert not any(b.outside for b in boxes) and gained_area(boxes) == 0
        ok, msg = check_paving(g, level, reach, w["attraction_paving"], c.details)    # re-runs every box
        assert ok, msg
        b = boxes[0]
        # a box's steps cut short, or a false 'outside', or 'inside' at t = 0: not re-derived
        assert not recheck_box(g, PavedBox(b.x1, b.x3, "enters", b.steps[:2], b.order), level, reach)
        assert not recheck_box(g, PavedBox(b.x1, b.x3, "enters", b.steps, b.order, outside=True), level, reach)
        assert not recheck_box(g, PavedBox(b.x1, b.x3, "inside"), level, reach)
        # above_level: a rectangle far out is above c, one containing the origin is not
        far = (Fraction(1, 50), Fraction(1, 40))
        assert above_level(g, far, far, level) and not above_level(g, b.x1, b.x3, level)
        # an entering box far out counts in the gain: its area, exactly
        out = PavedBox(far, far, "enters", [Fraction(1)], 20, outside=True)
        assert gained_area(boxes + [out]) == out.area() and gained_area([PavedBox(far, far, "undecided")]) == 0
        area = ellipse_area(g, level)
        # the stated ratio is re-derived from the boxes: above it, rejected (no boxes: the ratio is exactly 1)
        empty = dict(w["attraction_paving"], boxes=[])
        assert check_paving(g, level, reach, empty, {"area_ratio_lower": "1"})[0]
        assert not check_paving(g, level, reach, empty, {"area_ratio_lower": "1.5"})[0]
    # the ellipse's area in closed form against a float count of grid points (a cross-check only)
    import numpy as np
    fg = FloatGimbal(DEMO)
    e1, e3 = 0.006, 0.0095
    X1, X3 = np.meshgrid(np.linspace(-e1, e1, 1201), np.linspace(-e3, e3, 1201))
    frac = float(np.mean(fg.V(X1, np.zeros_like(X1), X3) < float(DEMO_LEVEL)))
    assert abs(frac * 4 * e1 * e3 / float(area.mid()) - 1) < 0.01
