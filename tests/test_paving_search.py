"""The counterexample search and the Monte Carlo cross-check inside a paving (scene options search_points,
monte_carlo): stored per claim, deciding `refuted` only through a refuted point proof, re-derived by the
checker, absent (and the certificate unchanged) when not asked for."""
import copy

import pytest

from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.margins.report import paving_json, render_paving
from rigor_gyro.scene import parse_scene
from tests.forgery import failures, reseal

SCENE = """
name = "cx_test"
kind = "eigenfrequencies"
source = "test: bracket (7) fails on part of this box (eps > 1), no sub-box is refuted whole and the 16 midpoints hold"
[parameters]
a = "15.08"
b = "6.154"
eps = "[0.1, 1.3]"
Omega2 = "[0.5, 2.2]"
[claims]
only = ["bracket_1"]
[options]
box_resolution = "1/4"
range_boxes = "0"
"""


@pytest.fixture(scope="module")
def searched():
    text = SCENE + 'search_points = "8"\nmonte_carlo = "200"\n'
    return paving_json(pave(box_scene(parse_scene(text))))


def test_the_search_refutes_where_the_midpoints_did_not_and_the_checker_confirms(searched):
    c = searched["claims"][0]
    assert not any(b["status"] == "refuted" for b in c["boxes"])           # no sub-box refuted whole
    assert not any(p["status"] == "refuted" for p in c["points"])          # the 16 midpoints all hold
    cs = c["counterexample_search"]
    assert cs["refuted"] >= 1 and c["status"] == "refuted" and searched["verdict"] == "refuted"
    assert all(p["leaf_status"] == "undecided" for p in cs["proofs"])
    assert c["monte_carlo"]["samples"] == 200 and c["monte_carlo"]["consistent"] is True
    assert failures(searched) == []
    md = render_paving(searched)
    assert "certified counterexample(s)" in md and "Monte Carlo cross-check (evidence, not proof)" in md


def test_without_the_options_nothing_is_searched_and_the_settings_are_as_before():
    data = paving_json(pave(box_scene(parse_scene(SCENE))))
    c = data["claims"][0]
    assert "counterexample_search" not in c and "monte_carlo" not in c and c["status"] == "inconclusive"
    assert not any(k.startswith(("search", "monte")) for k in data["settings"])


def _edit(data, change):
    bad = copy.deepcopy(data)
    change(bad["claims"][0])
    return reseal(bad)


def test_forged_searches_and_estimates_are_rejected(searched):
    refuted = next(i for i, p in enumerate(searched["claims"][0]["counterexample_search"]["proofs"])
                   if p["status"] == "refuted")

    def flip_to_proved(c):
        c["counterexample_search"]["proofs"][refuted]["status"] = "proved"

    def drop_search(c):
        del c["counterexample_search"]

    def more_failing(c):
        c["monte_carlo"]["failing"] += 1

    for change in (flip_to_proved, drop_search, more_failing):
        got = failures(_edit(searched, change))
        assert got and any(item == "bracket_1" for item, _ in got), change.__name__
