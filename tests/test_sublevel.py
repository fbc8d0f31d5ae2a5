"""The largest sublevel set c_max (claim ``largest_sublevel``): the core lower-bound branch and bound,
the claim's bounds against an independent mpmath sampling of {Vdot >= 0}, its refutations, and the
checker's re-derivation (with tampered certificates rejected)."""
import copy
import dataclasses
import json
import random
from fractions import Fraction

import mpmath
import pytest
from flint import arb

from rigor_gyro import load_scene, prove_scene, reproduce
from rigor_gyro.certificate import digest
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import exact_endpoints, exact_fraction, working_precision
from rigor_gyro.core.boxes import Box, tiles_by_bisection
from rigor_gyro.core.subdivision import lower_bound_on_box
from rigor_gyro.kinds.lyapunov.approx import MpGimbal


def _cert(**params):
    scene = load_scene("agafonov2013")
    scene = dataclasses.replace(scene, name="variant", parameters=dict(scene.parameters, **params))
    raw = prove_scene(scene).to_json()
    reproduce.keep(raw)         # the texts check's re-proof of this scene at these settings is this very proof
    return json.loads(json.dumps(raw))


def _claim(data):
    return next(c for c in data["claims"] if c["id"] == "largest_sublevel")


def _refix(data):
    data["integrity"] = {"sha256": digest(data)}
    return data


@pytest.fixture(scope="module")
def example():
    return _cert()


# ------------------------------------------------------------------ core

def test_lower_bound_on_box_is_below_the_minimum_and_tiles():
    whole = Box.of({"x": (Fraction(-1), Fraction(1)), "y": (Fraction(0), Fraction(2))})

    def f(b):
        return (b["x"] - arb("0.3")) ** 2 + (b["y"] - 1) ** 2 + arb("0.5")
    with working_precision(64):
        r = lower_bound_on_box(f, whole, "0.499", max_pieces=5000)
        assert r.reached and r.bound <= arb("0.5") and r.bound >= arb("0.499")
        assert tiles_by_bisection(whole, r.leaves)
        # every leaf's lower end is >= the bound (the bound is their minimum)
        assert all(f({k: b.ball(k) for k in b.names}).lower() >= r.bound for b in r.leaves)
        # a budget leaves the bound valid, only lower, and says it was not reached
        small = lower_bound_on_box(f, whole, "0.499", max_pieces=5)
        assert not small.reached and small.bound <= arb("0.5") and small.bound < r.bound
        assert tiles_by_bisection(whole, small.leaves)


def test_lower_bound_on_box_never_bounds_from_a_nan():
    whole = Box.of({"x": (Fraction(0), Fraction(1))})

    def f(b):
        return arb("nan") if b["x"].contains(arb(3) / 4) else arb(1)
    with working_precision(64):
        r = lower_bound_on_box(f, whole, "0.5", max_pieces=50)
        assert not r.reached and not r.bound.is_finite() and r.bound < 0


# ------------------------------------------------------------------ the claim

def test_the_example_c_max_is_proved_and_the_faces_bind(example):
    c = _claim(example)
    assert c["status"] == "proved", c["reason"]
    d = c["details"]
    lo, hi = Fraction(d["c_max_lower"]), Fraction(d["c_max_upper"])
    assert 0 < lo <= hi and (hi - lo) / lo < Fraction(1, 10 ** 9)
    assert d["binds"] == "faces"
    # the faces' level is c* (both are min phi(+-x2*)); the Vdot part lies far above it
    cstar = example["quantities"]["c_star"]
    assert Fraction(cstar["lo"]) <= hi and lo <= Fraction(cstar["hi"])
    n_lo, n_up = Fraction(d["vdot_level_lower"]), Fraction(d["vdot_level_upper"])
    # the faces bind by a factor > 2: the level of {Vdot >= 0} is bracketed to GAP_FACES_BIND (10 %) only
    assert 10 * hi < n_lo <= n_up and (n_up - n_lo) / n_up < Fraction(11, 100)
    assert (n_up - n_lo) / n_up > Fraction(2, 1000)             # not the 1e-3 bracket: that work is skipped


def _mp_sample_min_over_n(params: dict, n: int, seed: int, around=None) -> float:
    """min of V over sampled points where Vdot >= 0 (mpmath, 30 digits; no guarantee: a reference)."""
    mpmath.mp.dps = 30
    g = MpGimbal(params)
    rng = random.Random(seed)
    best = mpmath.inf
    for _ in range(n):
        if around is None:
            x2 = (2 * rng.random() - 1) * g.xs
            t = rng.random() * mpmath.pi
            r = (2 * rng.random() - 1) * 10 ** rng.uniform(-4, 0)
        else:
            u0, s0, r0 = around
            x2 = max(-g.xs, min(g.xs, (u0 + rng.gauss(0, 1e-3)) * g.xs))
            t = (s0 + rng.gauss(0, 1e-3)) * mpmath.pi
            r = r0 * (1 + rng.gauss(0, 1e-2))
        x1, x3 = r * mpmath.cos(t), r * mpmath.sin(t)
        v1, v2, v3 = g.grad_V(x1, x2, x3)
        d1, d2, d3 = g.rhs3(x1, x2, x3)
        if v1 * d1 + v2 * d2 + v3 * d3 >= 0:
            best = min(best, g.V(x1, x2, x3))
    return float(best)


def test_sampled_points_of_vdot_nonnegative_lie_above_the_certified_level(example):
    d = _claim(example)["details"]
    pt = example["witnesses"]["largest_sublevel"]["point"]
    params = load_scene("agafonov2013").parameters
    xs = float(mpmath.pi / 6)
    x1, x2, x3 = (float(Fraction(pt[k][0])) for k in ("x1", "x2", "x3"))
    r = (x1 * x1 + x3 * x3) ** 0.5 * (1 if x1 >= 0 else -1)
    t = float(mpmath.atan2(x3 * (1 if r > 0 else -1), x1 * (1 if r > 0 else -1)))
    sampled = min(_mp_sample_min_over_n(params, 400, 1),
                  _mp_sample_min_over_n(params, 400, 2, around=(x2 / xs, t / float(mpmath.pi), r)))
    assert sampled >= float(Fraction(d["vdot_level_lower"]))
    # the sampling gets within the certified gap of the upper bound near the point
    assert sampled <= float(Fraction(d["vdot_level_upper"])) * 1.01


def test_a_wide_x2_range_makes_vdot_bind_and_the_checker_confirms():
    data = _cert(x2_star="1.3")
    c = _claim(data)
    assert c["status"] == "proved" and c["details"]["binds"] == "vdot", c["reason"]
    assert Fraction(c["details"]["c_max_lower"]) == Fraction(c["details"]["vdot_level_lower"])
    assert check_certificate(data).ok


@pytest.mark.parametrize("params, where", [({"k": "0.2"}, "origin"), ({"H": "3000"}, "faces")])
def test_no_positive_level_is_refuted_with_a_certified_reason(params, where):
    data = _cert(**params)
    c = _claim(data)
    assert c["status"] == "refuted" and c["counterexample"]["where"] == where, c["reason"]
    assert check_certificate(data).ok
    bad = copy.deepcopy(data)
    if where == "origin":
        _claim(bad)["counterexample"]["t_over_pi"] = "1/2"      # A(0, pi/2) = c20(0) > 0 here
    else:       # at H = 3000, A(0, pi/2) = H (mu H - a) / (B0 A0) < 0 too (a genuine reason); A(0, 0) > 0
        _claim(bad)["counterexample"]["where"] = "origin"
        _claim(bad)["counterexample"]["t_over_pi"] = "0"
    assert not check_certificate(_refix(bad)).ok


def test_a_tampered_c_max_witness_is_rejected(example):
    assert check_certificate(example).ok

    def rejected(mutate):
        d = copy.deepcopy(example)
        mutate(d)
        return not check_certificate(_refix(d)).ok

    w = lambda d: d["witnesses"]["largest_sublevel"]                         # noqa: E731
    det = lambda d: _claim(d)["details"]                                     # noqa: E731

    def raise_lower(d):
        det(d)["vdot_level_lower"] = str(Fraction(det(d)["vdot_level_upper"]) * Fraction(999, 1000) + 1)
        d["quantities"]["vdot_level_lower"] = {"lo": det(d)["vdot_level_lower"], "hi": det(d)["vdot_level_lower"],
                                               "mid": det(d)["vdot_level_lower"], "rad": "0"}

    def raise_c(d):
        v = str(Fraction(det(d)["c_max_upper"]) + 1)
        det(d)["c_max_lower"] = v
        d["quantities"]["c_max_lower"] = {"lo": v, "hi": v, "mid": v, "rad": "0"}

    def move_point(d):
        w(d)["point"]["x3"] = ["0", "0"]
        w(d)["point"]["x1"] = ["1/1000", "1/1000"]
    assert rejected(lambda d: w(d)["boxes"].pop(len(w(d)["boxes"]) // 2))
    assert rejected(raise_lower)
    assert rejected(raise_c)
    assert rejected(move_point)
    assert rejected(lambda d: det(d).__setitem__("binds", "vdot"))
    assert rejected(lambda d: w(d).pop("point"))

    # a hostile review: a non-positive c_max_lower, a stored bound wider than its decimal
    def nonpositive(d):
        for k in ("c_max_lower", "vdot_level_lower"):
            det(d)[k] = "-1"
            d["quantities"][k] = {"lo": "-1", "hi": "-1", "mid": "-1", "rad": "0"}
        det(d)["binds"] = "undecided"

    def wide(d):
        d["quantities"]["c_max_lower"]["hi"] = "234"
    assert rejected(nonpositive)
    assert rejected(wide)


def test_an_axis_segment_outside_the_range_is_rejected(example):
    """extent_x2_axis is the root of mu F(x2) = c_set in [0, x2*]; a stored segment beyond x2* (where the sine
    law's F decreases again) must not be confirmed."""
    d = copy.deepcopy(example)
    d["quantities"]["extent_x2_axis"] = {"lo": "3", "hi": "3.1", "mid": "3.05", "rad": "0.05"}
    assert not check_certificate(_refix(d)).ok


# ------------------------------------------------------------------ the extents of {V < c_set}

def test_the_extents_enclose_the_sampled_maxima_of_the_set(example):
    """extent_x1, extent_x2, extent_x3 enclose max |x_i| over {x in (17): V < c_set}: mpmath samples of the
    set never exceed the upper ends, and sampled points come within 1% of the
    lower ends within 1% (the set's sup is approached); both lie beyond the axis segments."""
    q = example["quantities"]
    inv = next(c for c in example["claims"] if c["id"] == "invariant_estimate")
    c = float(Fraction(inv["details"]["c_set"]))
    R = float(Fraction(q["R_used"]["hi"]))
    mpmath.mp.dps = 30
    g = MpGimbal(load_scene("agafonov2013").parameters)
    xs = float(g.xs)
    hi = {k: float(Fraction(q[f"extent_{k}"]["hi"])) for k in ("x1", "x2", "x3")}
    lo = {k: float(Fraction(q[f"extent_{k}"]["lo"])) for k in ("x1", "x2", "x3")}
    assert lo["x3"] > float(Fraction(q["extent_x3_axis"]["hi"])) * 1.4      # the old box capped x3 at R
    assert lo["x2"] > float(Fraction(q["extent_x2_axis"]["hi"]))
    rng = random.Random(5)
    best = {"x1": 0.0, "x2": 0.0, "x3": 0.0}
    for _ in range(3000):
        x2 = (2 * rng.random() - 1) * xs
        S = g.f2(x2) + g.mu * (g.f1(x2) - g.mu)
        h = g.H * mpmath.cos(x2) / g.B0
        f3 = g.f3(x2)
        # a point of the slice's ellipse (centre z0, P^-1 as in model.slice_extent), scaled inside
        z1, z3 = g.mu * f3 / (h * S), -f3 / S
        d = c - (g.mu * g.F(x2) - f3 ** 2 / (2 * S))
        if d <= 0:
            continue
        t, s = rng.random() * 2 * mpmath.pi, rng.random() ** 0.1
        # the ellipse 1/2 (z - z0)' P (z - z0) = d: z - z0 = sqrt(2 d) L u with L L' = P^-1, |u| = s
        p11, p13, p33 = (S + g.mu ** 2) / (h * h * S), -g.mu / (h * S), 1 / S
        l11 = mpmath.sqrt(p11)
        l31 = p13 / l11
        l33 = mpmath.sqrt(p33 - l31 ** 2)
        u1, u3 = s * mpmath.cos(t), s * mpmath.sin(t)
        x1 = z1 + mpmath.sqrt(2 * d) * l11 * u1
        x3 = z3 + mpmath.sqrt(2 * d) * (l31 * u1 + l33 * u3)
        if g.V(x1, x2, x3) < c and x1 ** 2 + x3 ** 2 < R ** 2:
            for k, v in (("x1", x1), ("x2", x2), ("x3", x3)):
                best[k] = max(best[k], abs(float(v)))
    for k in best:
        assert best[k] <= hi[k], k
    assert best["x3"] >= lo["x3"] * (1 - 1e-2) and best["x1"] >= lo["x1"] * (1 - 1e-2)


def test_a_tampered_extent_witness_is_rejected(example):
    def rejected(mutate):
        d = copy.deepcopy(example)
        mutate(d)
        return not check_certificate(_refix(d)).ok
    w = lambda d: d["witnesses"]["invariant_estimate"]                       # noqa: E731

    def shrink(d, k):
        v = d["quantities"][k]
        v["hi"] = v["lo"]
    assert rejected(lambda d: w(d)["extent_x3"]["cover"].pop(0))
    assert rejected(lambda d: w(d)["extent_x2"]["beyond"].pop(-1))
    assert rejected(lambda d: shrink(d, "extent_x3"))
    assert rejected(lambda d: shrink(d, "extent_x2"))
    # a point below the stored lower end: the stored enclosure then claims more than the witness shows
    assert rejected(lambda d: w(d)["extent_x2"].__setitem__("point", ["1/2", "1/2"]))


def test_slice_in_region_needs_a_non_empty_slice_inside_the_disc(example):
    """slice_in_region: the slice {V(., x2, .) < c} certainly non-empty with its centre inside the disc
    (true at x2 = 0 for c = c_set; false at x2 = x2*, where phi = c* > c_set, and for a tiny disc)."""
    from rigor_gyro.kinds.lyapunov.claims import validate
    from rigor_gyro.kinds.lyapunov.polar_forms import slice_in_region
    inv = next(c for c in example["claims"] if c["id"] == "invariant_estimate")
    c = Fraction(inv["details"]["c_set"])
    R = Fraction(example["quantities"]["R_used"]["lo"])
    g = validate(load_scene("agafonov2013")).gimbal
    with working_precision(64):
        cb, Rb = arb(c.numerator) / c.denominator, arb(R.numerator) / R.denominator
        assert slice_in_region(g, cb, Rb, arb(0))
        assert slice_in_region(g, cb, Rb, g.c.x2_star * arb("0.9"))
        assert not slice_in_region(g, cb, Rb, g.c.x2_star)
        assert not slice_in_region(g, cb, Rb * arb("1e-9"), g.c.x2_star * arb("0.9"))   # centre outside


def _exact_min_on_half_line(g, x2, t):
    """min of V(r cos t, x2, r sin t) over r != 0 with A + r B <= 0 at an exact point, in closed form (the
    vertex of the quadratic clamped into the half-line r B <= -A), as a ball; None where undecided."""
    from rigor_gyro.kinds.lyapunov.polar_forms import v_polar, vdot_polar
    A, B = vdot_polar(g, x2, t)
    al, be, ga = v_polar(g, x2, t)
    if not (A > 0) or B.contains(0):
        return None
    r0, rv = -A / B, -be / (2 * ga)
    if B < 0:                   # r >= r0 > 0
        r = rv if rv > r0 else r0 if rv < r0 else None
    else:                       # r <= r0 < 0
        r = rv if rv < r0 else r0 if rv > r0 else None
    return None if r is None else al + be * r + ga * r * r


def test_the_sublevel_bound_is_below_the_exact_minimum_at_points_of_each_box():
    """On random boxes of (x2, t), the lower bound of V over {Vdot >= 0} is below the exact minimum over the
    half-line at points of the box (computed in closed form, not through the bound's code): a bound taken
    on the wrong side of r = 0 or from the wrong vertex would exceed it somewhere."""
    from rigor_gyro.kinds.lyapunov.claims import validate
    from rigor_gyro.kinds.lyapunov.polar_forms import sublevel_lower_bound
    g = validate(load_scene("agafonov2013")).gimbal
    rng = random.Random(11)
    checked = 0
    with working_precision(64):
        lb = sublevel_lower_bound(g)
        xs, pi = g.c.x2_star, arb.pi()
        for _ in range(300):
            w = Fraction(1, 2 ** rng.randint(3, 9))
            u0 = Fraction(rng.randint(-2 ** 9, 2 ** 9), 2 ** 9) * (1 - w)
            s0 = Fraction(rng.randint(0, 2 ** 9), 2 ** 9) * (1 - w)
            box = Box.of({"u": (u0, u0 + w), "s": (s0, s0 + w)})
            bound = lb({k: box.ball(k) for k in box.names}).lower()
            if not bound.is_finite():
                continue
            for _ in range(3):
                u = u0 + w * Fraction(rng.randint(0, 64), 64)
                s = s0 + w * Fraction(rng.randint(0, 64), 64)
                v = _exact_min_on_half_line(g, xs * (arb(u.numerator) / u.denominator),
                                            pi * (arb(s.numerator) / s.denominator))
                if v is not None:
                    checked += 1
                    assert not (bound > v), (u, s, bound, v)
    assert checked > 100


def test_lower_bound_on_box_stops_on_a_box_of_points():
    """A degenerate box cannot be split: the search stops there with the bound so far (no crash)."""
    whole = Box.of({"x": (Fraction(1, 3), Fraction(1, 3)), "y": (Fraction(0), Fraction(0))})
    with working_precision(64):
        r = lower_bound_on_box(lambda b: b["x"] - 1, whole, "0", max_pieces=50)
    assert not r.reached and r.bound < 0 and len(r.leaves) == 1


def test_the_cylinder_margin_is_a_lower_bound_that_samples_of_the_side_respect(example):
    """cylinder_margin_lower: V >= (1 + margin) c* on the side x1^2 + x3^2 = R^2 of region (17). mpmath
    samples of the side never fall below that level, and come within 1 % of it (the faces bind in this
    scene, so the side has slack: margin ~ 0.73; a margin of c* against itself would be 0)."""
    q = example["quantities"]
    m = float(Fraction(q["cylinder_margin_lower"]["hi"]))
    c_hi = float(Fraction(q["c_star"]["hi"]))
    R = float(Fraction(q["R_used"]["lo"]))
    assert 0.5 < m < 1
    mpmath.mp.dps = 30
    g = MpGimbal(load_scene("agafonov2013").parameters)
    rng = random.Random(11)
    low = min(g.V(R * mpmath.cos(t), x2, R * mpmath.sin(t)) for t, x2 in
              ((rng.random() * 2 * mpmath.pi, (2 * rng.random() - 1) * g.xs) for _ in range(4000)))
    assert float(low) >= (1 + m) * c_hi
    assert float(low) <= (1 + m) * c_hi * 1.01


# ------------------------------------------------------------------ the claim's helpers (mutation testing)

def _gimbal(**params):
    from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
    return gimbal_from_parameters(dict(load_scene("agafonov2013").parameters, **params))[0]


def test_the_half_line_value_is_the_minimum_of_the_quadratic_over_the_half_line():
    """_value_on_half_line (a search helper): the minimum of al + be r + ga r^2 over {A + r B <= 0} and the r
    attaining it, against a dense scan of that half-line (and the whole line when B = 0)."""
    from rigor_gyro.kinds.lyapunov.sublevel import _value_on_half_line
    rng = random.Random(3)
    for _ in range(200):
        A, B = rng.uniform(-3, 3), rng.choice([0.0, rng.uniform(-3, 3)])
        al, be, ga = rng.uniform(-2, 2), rng.uniform(-4, 4), rng.uniform(0.1, 3)
        value, r = _value_on_half_line(A, B, al, be, ga)
        # a scan of [-12, 12], the half-line's end and the parabola's vertex
        grid = [k / 2000 for k in range(-24000, 24001)] + ([-A / B] if B else []) + [-be / (2 * ga)]
        allowed = [x for x in grid if A + x * B <= 1e-12]
        if not allowed:
            assert value == float("inf")
            continue
        scan = min(al + be * x + ga * x * x for x in allowed)
        assert value <= scan + 1e-12 and value >= scan - 1e-5, (A, B, al, be, ga, value, scan)
        assert A + r * B <= 1e-9 and abs(al + be * r + ga * r * r - value) <= 1e-9


def test_the_origin_counterexample_is_the_first_grid_point_where_A_at_x2_0_is_certainly_negative(monkeypatch):
    """_origin_counterexample returns the first s = j/64, j = 0..64, where A(0, pi s) < 0 certainly (A not
    containing 0), and None when there is none: on made-up A(x2, t) (the real A is never negative on the
    paper's scenes). A depends on x2, so evaluating it anywhere but x2 = 0 is seen."""
    from rigor_gyro.kinds.lyapunov import sublevel

    def fake(law):
        return lambda g, X, T, mu=None: (law(T) + 100 * X, arb(1))
    cases = [(lambda T: T.cos() + arb(1) / 2, Fraction(43, 64)),         # cos t < -1/2 first at j = 43
             (lambda T: T.cos() + arb("0.9995"), Fraction(1)),           # only at t = pi (j = n)
             (lambda T: T.sin() + arb("0.01"), None),                   # only beyond pi: not on the grid
             (lambda T: arb("0.5"), None),                              # positive below 1
             (lambda T: arb(0), None),                                  # certainly <= 0, but it is 0
             (lambda T: arb(0) * T, None)]                              # contains 0 (a ball around 0)
    with working_precision(64):
        for law, want in cases:
            monkeypatch.setattr(sublevel, "vdot_polar", fake(law))
            got = sublevel._origin_counterexample(None)
            assert (got and got[0]) == want, (want, got)
            if want is not None:
                assert got[1] < 0 and got[1].is_finite() and got[1].overlaps(law(arb.pi() * arb(want.numerator) / want.denominator))


def test_a_point_of_n_is_returned_only_where_vdot_is_certainly_positive():
    """_point_of_n: asked for a radius well inside {Vdot < 0} (0.3 of the boundary along the search's ray) it
    finds nothing; asked just beyond the boundary it returns exact rationals with |x2| <= x2* where Vdot > 0
    (an mpmath evaluation at 40 digits, not the code's), and V's enclosure there."""
    from rigor_gyro.kinds.lyapunov.polar_forms import vdot_polar
    from rigor_gyro.kinds.lyapunov.sublevel import _point_of_n, _search
    mpmath.mp.dps = 40
    for xs in ("1/10", "pi/6"):
        g = _gimbal(x2_star=xs)
        mg = MpGimbal(dict(load_scene("agafonov2013").parameters, x2_star=xs))
        with working_precision(64):
            _, u, s, _ = _search(g)
            A, B = vdot_polar(g, g.c.x2_star * arb(u), arb.pi() * arb(s))
            r0 = float((-A / B).mid())
            assert _point_of_n(g, u, s, 0.3 * r0) is None
            (x1, x2, x3), v = _point_of_n(g, u, s, r0)
            assert abs(x2) <= g.c.x2_star and (x1 != 0 or x3 != 0)
            assert all(y.rad() == 0 for y in (x1, x2, x3))
            q = [mpmath.mpf(exact_fraction(y).numerator) / exact_fraction(y).denominator for y in (x1, x2, x3)]
            assert mg.grad_V_dot_f(*q) > 0
            lo, hi = exact_endpoints(v)
            assert lo <= Fraction(mpmath.nstr(mg.V(*q), 35)) * (1 + Fraction(1, 10 ** 15)) and \
                Fraction(mpmath.nstr(mg.V(*q), 35)) * (1 - Fraction(1, 10 ** 15)) <= hi


def test_a_face_level_below_1_is_a_level_not_a_refutation():
    """At x2* = 1/10 the faces' level min phi(+-x2*) is 0.934: in (0, 1]. It binds, c_max is that level,
    nothing is refuted (a refutation on 'phi <= 1' instead of 'phi <= 0' would be false here)."""
    from rigor_gyro.kinds.lyapunov.sublevel import largest_sublevel
    g = _gimbal(x2_star="1/10")
    with working_precision(64):
        r = largest_sublevel(g, 4000)
        face = g.phi(g.c.x2_star)
    assert 0 < face < 1
    assert r.refutation is None and r.binding == "faces"
    lo, hi = Fraction(r.c_lower), Fraction(r.c_upper)
    f_lo, f_hi = exact_endpoints(face)
    assert 0 < lo <= f_lo and f_hi <= hi and hi - lo < Fraction(1, 10 ** 9)
