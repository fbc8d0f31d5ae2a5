"""kinds/periodic_orbit/box_quantities.py: every certified range holds mpmath / float samples of the box, and a
point box gives a tight ball."""
from __future__ import annotations

from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.box_quantities import BOX_QUANTITIES, quantities_box
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
from tests.test_relay_box_continuation import _theta_mp  # noqa: E402


def _params(m, **kw):
    d = {k: Fraction(int(getattr(m.params, k).p), int(getattr(m.params, k).q)) for k in
         ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")}
    d.update(kw)
    return d


def test_box_quantities_hold_samples_of_a_half_percent_box():
    m = validate(load_scene("roitenberg1947"))
    lo, hi = Fraction(4975, 100), Fraction(5025, 100)
    with working_precision(128):
        q = quantities_box(m, Box.of({"n": (lo, hi)}), list(BOX_QUANTITIES))
    assert set(q) == set(BOX_QUANTITIES)
    th, per, mx, margin = (q[k].value for k in ("theta_star", "period", "max_modulus", "stability_margin"))
    assert BOX_QUANTITIES["stability_margin"].claim == "stable" and margin.lower() > 0
    # mpmath's theta* at 10 points of the box (2 s each), for the enclosures and for the branch below
    samples = [(n, _theta_mp(_params(m, n=n), float(th.lower()) - 1e-6, float(th.upper()) + 1e-6))
               for n in (lo + (hi - lo) * Fraction(k, 9) for k in range(10))]
    for n, t in samples:
        assert th.contains(arb(mp.nstr(t, 18))) and per.contains(arb(mp.nstr(2 * t, 18)))
        mods = [abs(z) for z in approx.approx_multipliers(_params(m, n=n), float(t))]
        assert mx.lower() < max(mods) < mx.upper() and margin.lower() < 1 - max(mods) < margin.upper()
    # the branch: theta* about the centre by the mean value theorem, and theta* g's only root in unique_in
    br = q["theta_star"].branch
    assert all(q[k].branch is br for k in BOX_QUANTITIES) and list(br.centre) == ["n"] and br.centre["n"] == 50
    assert br.unique_in.contains(br.key) and br.key.contains(br.at_centre)
    for n, t in samples:
        assert (br.at_centre + br.gradient["n"] * (arb(n.numerator) / n.denominator - 50)).contains(arb(mp.nstr(t, 18)))


def test_box_quantities_tight_on_a_point_box():
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        q = quantities_box(m, Box.of({"n": (Fraction(50), Fraction(50))}), ["theta_star", "stability_margin"])
    assert q["theta_star"].value.rad() < 1e-14
    assert q["theta_star"].value.overlaps(arb("0.138133574136193", 1e-15))
    assert q["stability_margin"].value.rad() < 1e-10


def test_the_stability_margins_lower_bound_is_below_a_float_optimisers_minimum():
    """Worst case against a float optimiser (issue 37): over a +-0.25 % box of B and sigma, the certified lower
    end of the stability margin is <= the smallest margin L-BFGS-B finds (float theta* by brentq inside the
    certified theta* range, float multipliers), and not far below it (the enclosure's width)."""
    from scipy.optimize import brentq, minimize
    m = validate(load_scene("roitenberg1947"))
    r = Fraction(1, 400)
    box = Box.of({"B": (Fraction("0.133") * (1 - r), Fraction("0.133") * (1 + r)),
                  "sigma": (Fraction("0.13125") * (1 - r), Fraction("0.13125") * (1 + r))})
    with working_precision(128):
        q = quantities_box(m, box, ["stability_margin", "theta_star"])
    lower = float(q["stability_margin"].value.lower())
    t_lo, t_hi = float(q["theta_star"].value.lower()) - 1e-9, float(q["theta_star"].value.upper()) + 1e-9
    bounds = [tuple(float(x) for x in box.interval(k)) for k in ("B", "sigma")]

    def margin(x):
        p = _params(m, B=Fraction(float(x[0])), sigma=Fraction(float(x[1])))
        t = brentq(lambda s: approx.approx_g(p, s), t_lo, t_hi, xtol=1e-14)
        return 1 - max(abs(z) for z in approx.approx_multipliers(p, t))
    best = min(minimize(margin, x0, bounds=bounds, method="L-BFGS-B", options={"maxiter": 30}).fun
               for x0 in ([(a + b) / 2 for a, b in bounds], [a for a, _ in bounds], [b for _, b in bounds]))
    assert lower <= best
    assert best - lower <= 0.002, (lower, best)       # measured: 0.04289 against 0.04315


def test_touching_sub_boxes_of_a_two_parameter_box_are_shown_to_follow_one_orbit():
    """H and n at +-1 %, cut in two along H: each half's theta* enclosure sits at an end of its range where they
    meet, so its branch needs a uniqueness ball wider than the enclosure (the band step leaves them equal);
    with it the ranges layer joins the halves (an inner range is stated)."""
    from rigor_gyro.margins.ranges import one_branch
    m = validate(load_scene("roitenberg1947"))
    whole = Box.of({"H": (Fraction(99), Fraction(101)), "n": (Fraction(495, 10), Fraction(505, 10))})
    tiles = []
    with working_precision(128):
        for half in whole.split(whole):
            br = quantities_box(m, half, ["theta_star"])["theta_star"].branch
            assert br.unique_in.contains(br.key) and br.unique_in.rad() > br.key.rad()
            tiles.append((half, {"branch": _branch_text(br)}))
    assert one_branch(tiles)


def _branch_text(br):
    from rigor_gyro.margins.ranges import _branch_json
    return _branch_json(br)


def test_the_uniqueness_ball_is_widened_only_where_dg_dtheta_is_shown_nonzero(monkeypatch):
    """Where at_most_one_root does not show dG/dtheta != 0 on the wider ball, U stays the continuation's own."""
    from rigor_gyro.kinds.periodic_orbit import box_quantities as bq
    m = validate(load_scene("roitenberg1947"))
    box = Box.of({"H": (Fraction(995, 10), Fraction(1005, 10))})
    tried = []

    def never(Pc, balls, dirs, guesses, W):
        tried.append(W)
        return False
    monkeypatch.setattr(bq, "at_most_one_root", never)
    with working_precision(128):
        br = bq.quantities_box(m, box, ["theta_star"])["theta_star"].branch
    assert len(tried) == len(bq.UNIQUE_WIDENING) and all(W.rad() > br.unique_in.rad() for W in tried)
    assert br.unique_in.rad() <= 2 * br.key.rad()       # not widened: the continuation's U (about the enclosure)


def test_a_point_whose_root_search_stops_at_t_max_measures_nothing():
    """With T_max = 0.3 s (below the tail bound 0.73 s) the equation is searched on (0, 0.3] only: an orbit beyond it
    is not excluded, so the one genuine orbit found need not be the one the sub-boxes around the point follow."""
    import dataclasses
    scene = load_scene("roitenberg1947")
    full = validate(scene)
    cut = validate(dataclasses.replace(scene, options={**scene.options, "T_max": "0.3"}))
    point = Box.of({"n": (Fraction(50), Fraction(50))})
    with working_precision(128):
        assert "theta_star" in quantities_box(full, point, ["theta_star"])
        assert quantities_box(cut, point, ["theta_star"]) == {}
