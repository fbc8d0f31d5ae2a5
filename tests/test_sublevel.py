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

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.certificate import Status, digest
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box, tiles_by_bisection
from rigor_gyro.core.subdivision import lower_bound_on_box
from rigor_gyro.kinds.lyapunov.approx import MpGimbal


def _cert(**params):
    scene = load_scene("agafonov2013")
    scene = dataclasses.replace(scene, name="variant", parameters=dict(scene.parameters, **params))
    return json.loads(json.dumps(prove_scene(scene).to_json()))


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
    assert 10 * hi < n_lo <= n_up and (n_up - n_lo) / n_up < Fraction(2, 1000)


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
