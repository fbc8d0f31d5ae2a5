"""The checker's side of the counterexample search and the Monte Carlo cross-check
(margins/counterexample_check.py): a stored search and estimate re-derive; each tamper is caught."""
from __future__ import annotations

import copy
import json
from fractions import Fraction

import pytest

from rigor_gyro.margins import counterexamples as cx
from rigor_gyro.margins.counterexample_check import check_counterexamples, check_monte_carlo
from rigor_gyro.margins.paving import box_scene, pave, point_task
from rigor_gyro.scene import Scene


@pytest.fixture(scope="module")
def searched():
    bs = box_scene(Scene(name="cx", kind="eigenfrequencies", source="test", claims_only=["bracket_1"],
                         parameters={"a": "15.08", "b": "6.154", "eps": "[0.001, 2]", "Omega2": "[0.001, 10]"},
                         options={"box_resolution": "1/8", "range_boxes": "0"}))
    claim = pave(bs).claims[0]
    search = cx.search_claim(bs, claim.boxes, "bracket_1", 3, samples=32)
    oj = json.dumps(bs.options, sort_keys=True)

    def prove_at(point):
        return point_task(bs.scene.kind, json.dumps(bs.point_parameters(point), sort_keys=True), oj, "bracket_1",
                          bs.point_prec, bs.point_maxprec)
    est = cx.failing_fraction_estimate(bs, samples=40, seed=2)["bracket_1"]
    est["consistent"] = cx.agrees_with_paving(claim.volume(bs.box), est)[0]
    return bs, claim, search, prove_at, est


def test_a_stored_search_re_derives(searched):
    bs, claim, search, prove_at, _ = searched
    assert search["refuted"] >= 1 and len(search["leaves"]) == search["refuted"]
    assert all(p["point"]["eps"].count("/") <= 1 for p in search["proofs"])
    ok, msg = check_counterexamples(bs.box, claim.boxes, "bracket_1", search, prove_at)
    assert ok, msg


def _tampered(search, **edits):
    s = copy.deepcopy(search)
    s["proofs"][0].update(edits)
    return s


@pytest.mark.parametrize("edit, needle", [
    ({"status": "proved"}, "point prover gives status"),
    ({"reason": "made up"}, "point prover gives reason"),
    ({"leaf_status": "proved"}, "is stored undecided"),
    ({"point": {"eps": "3", "Omega2": "1"}}, "not a point of the box"),
    ({"point": {"eps": "1"}}, "not a point of the box"),
    ({"leaf": 10 ** 6}, "not an index"),
    ({"leaf": True}, "not an index"),
])
def test_each_tamper_of_a_search_point_is_caught(searched, edit, needle):
    bs, claim, search, prove_at, _ = searched
    ok, msg = check_counterexamples(bs.box, claim.boxes, "bracket_1", _tampered(search, **edit), prove_at)
    assert not ok and needle in msg, msg


def test_a_search_point_in_another_leaf_is_caught(searched):
    bs, claim, search, prove_at, _ = searched
    leaf = search["proofs"][0]["leaf"]
    other = next(i for i, (b, s) in enumerate(claim.boxes)
                 if s == claim.boxes[leaf][1] and not cx.contains(b, {k: Fraction(v) for k, v in
                                                                      search["proofs"][0]["point"].items()}))
    ok, msg = check_counterexamples(bs.box, claim.boxes, "bracket_1", _tampered(search, leaf=other), prove_at)
    assert not ok and "is not in leaf" in msg, msg


def test_a_counterexample_in_a_leaf_stored_proved_is_a_contradiction(searched):
    bs, claim, search, prove_at, _ = searched
    first = next(p for p in search["proofs"] if p["status"] == "refuted")
    forged = list(claim.boxes)
    forged[first["leaf"]] = (forged[first["leaf"]][0], "proved")
    s = copy.deepcopy(search)
    s["proofs"] = [dict(first, leaf_status="proved")]
    s["refuted"], s["leaves"] = 1, [first["leaf"]]
    ok, msg = check_counterexamples(bs.box, forged, "bracket_1", s, prove_at)
    assert not ok and "disagree" in msg, msg


def test_the_search_counts_must_follow_from_its_proofs(searched):
    bs, claim, search, prove_at, _ = searched
    for key, value in (("refuted", search["refuted"] + 1), ("leaves", search["leaves"][1:] + [10 ** 6])):
        s = dict(search, **{key: value})
        ok, msg = check_counterexamples(bs.box, claim.boxes, "bracket_1", s, prove_at)
        assert not ok and "its proofs give" in msg, msg
    ok, msg = check_counterexamples(bs.box, claim.boxes, "bracket_1", dict(search, proofs=None), prove_at)
    assert not ok


def test_a_stored_estimate_re_derives_and_each_tamper_is_caught(searched):
    bs, claim, _, _, est = searched
    vol = claim.volume(bs.box)
    rerun = lambda: cx.failing_fraction_estimate(bs, samples=40, seed=2)["bracket_1"]
    ok, msg = check_monte_carlo("bracket_1", est, vol, rerun)
    assert ok, msg
    for edit in ({"failing": est["failing"] + 1}, {"interval": [0.0, 1.0]}, {"fraction": 0.5},
                 {"consistent": not est["consistent"]}, {"unknown": -1}, {"samples": "40"}):
        ok, msg = check_monte_carlo("bracket_1", {**est, **edit}, vol)
        assert not ok, edit
    other = cx.failing_fraction_estimate(bs, samples=40, seed=5)["bracket_1"]
    assert other["failing"] != est["failing"]
    ok, msg = check_monte_carlo("bracket_1", {**other, "seed": 2}, None, rerun)
    assert not ok and "re-run" in msg, msg
    assert not check_monte_carlo("bracket_1", {"samples": 3}, vol)[0]


def test_shortest_decimal():
    assert cx.shortest_decimal(Fraction(1234, 1000), Fraction(1301, 1000)) == Fraction(13, 10)
    assert cx.shortest_decimal(Fraction(-7, 3), Fraction(-2)) == -2
    assert cx.shortest_decimal(Fraction(1, 3), Fraction(1, 3)) == Fraction(1, 3)
    lo, hi = Fraction(123451, 100000), Fraction(123469, 100000)
    assert lo <= cx.shortest_decimal(lo, hi) <= hi and cx.shortest_decimal(lo, hi) == Fraction(12346, 10000)
