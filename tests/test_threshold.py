"""A threshold search's statement (rigor_gyro.margins.threshold): what it writes is what its point proofs
certify, in either orientation, in its lines, its JSON and its files; its search range and claim.

tests/test_margins.py has only searches refuted at the lower end; a search that took its proved end for
its refuted one, a bracket written with one end twice, a default range off by a factor went unnoticed
(proofs/mutation.md section 13).
"""
import dataclasses
import json
from fractions import Fraction

import pytest
from flint import arb, fmpq

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import interval_text, rational_text, working_precision
from rigor_gyro.core.boxes import fraction_text
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins.threshold import find_threshold, search_range, write_threshold


def _agafonov(**params):
    s = load_scene("agafonov2013")
    return dataclasses.replace(s, parameters=dict(s.parameters, **params), claims_only=["damping_condition"])


def _status_at(scene, param, value, claim):
    s = dataclasses.replace(scene, parameters=dict(scene.parameters, **{param: fraction_text(value)}),
                            claims_only=[claim])
    return prove_scene(s).claim(claim).status.value


def _assert_stated_truly(res, scene):
    """Everything the result states, against the point proofs redone and the steps it lists."""
    assert res.certified and res.exit_code == 0 and not res.stopped
    p, r = res.proved_at, res.refuted_at
    assert _status_at(scene, res.param, p, res.claim) == "proved"
    assert _status_at(scene, res.param, r, res.claim) == "refuted"
    steps = {Fraction(s["value"]): s["status"] for s in res.steps}
    assert steps[p] == "proved" and steps[r] == "refuted"
    assert len(steps) == len(res.steps) and steps[res.lo] and steps[res.hi]       # the two ends, then the bisection
    lo, hi = min(p, r), max(p, r)
    assert res.bracket() == (lo, hi) and hi - lo <= res.width * max(abs(lo), abs(hi))
    data = res.to_json()
    assert data["bracket"] == [fraction_text(lo), fraction_text(hi)]
    bl, bh, rounded = interval_text(lo, hi)
    assert data["bracket_decimal"] == [bl, bh] and Fraction(bl) <= lo < hi <= Fraction(bh)   # outward
    assert rounded == (Fraction(bl) != lo or Fraction(bh) != hi)
    assert data["search"] == [fraction_text(res.lo), fraction_text(res.hi)]
    assert data["requested_relative_width"] == fraction_text(res.width) and data["certified"] is True
    assert data["statement"] == (f"claim {res.claim!r} is proved at {res.param} = {fraction_text(p)} and refuted at "
                                 f"{res.param} = {fraction_text(r)} (point proofs), so its outcome changes in "
                                 f"[{fraction_text(lo)}, {fraction_text(hi)}]")
    assert data["steps"] == res.steps and data["param"] == res.param and data["claim"] == res.claim
    lines = res.lines()
    assert len(lines) == 1
    assert f"proved at {res.param} = {rational_text(p)}, refuted at {res.param} = {rational_text(r)}:" in lines[0]
    assert Fraction(rational_text(p)) == p and Fraction(rational_text(r)) == r          # exact points, exactly
    assert (f"changes in [{bl}, {bh}]{' (rounded outward)' if rounded else ''} (width " in lines[0]
            and f"{len(res.steps)} proofs" in lines[0])


def test_a_threshold_proved_below_and_refuted_above_holds_what_it_states():
    """Damping (16) needs mu < k/A0: proved at the lower end of the search, refuted at the upper end."""
    scene = _agafonov()
    res = find_threshold(scene, "mu", lo="0.02", hi="0.5", width="1e-3")
    assert res.claim == "damping_condition"          # the scene's only claim, chosen without --claim
    assert res.proved_at < res.refuted_at
    _assert_stated_truly(res, scene)
    A0 = prove_scene(_agafonov()).quantities["A0"]
    with working_precision(128):
        edge = arb(fmpq(2, 5)) / A0                  # k / A0, k = 0.4
        lo, hi = res.bracket()
        assert arb(fmpq(lo.numerator, lo.denominator)) < edge < arb(fmpq(hi.numerator, hi.denominator))


def test_a_threshold_refuted_below_and_proved_above_holds_what_it_states():
    scene = dataclasses.replace(load_scene("rudenko1976"), claims_only=["bracket_2"])
    res = find_threshold(scene, "Omega2", lo="1e-6", hi="1", claim="bracket_2", width="1e-3")
    assert res.refuted_at < res.proved_at
    _assert_stated_truly(res, scene)


def test_a_threshold_is_written_as_its_json_and_a_table_of_its_steps(tmp_path):
    scene = _agafonov()
    res = find_threshold(scene, "mu", lo="0.02", hi="0.5", width="1e-2")
    json_path, md_path = sorted(write_threshold(res, str(tmp_path)), key=lambda p: p.suffix)
    assert json_path.name == "margin_agafonov2013_mu.json"
    assert json.loads(json_path.read_text()) == json.loads(json.dumps(res.to_json()))
    md = md_path.read_text().splitlines()
    assert md[0] == "# " + res.lines()[0]
    rows = [line for line in md if line.startswith("| ") and line[2].isdigit()]
    assert rows == [f"| {i} | {rational_text(Fraction(s['value']))} | {s['status']} |" for i, s in enumerate(res.steps, 1)]


def test_a_search_without_a_change_states_no_bracket():
    res = find_threshold(_agafonov(), "mu", lo="0.001", hi="0.5")
    assert not res.certified and res.exit_code == 3 and res.bracket() is None
    data = res.to_json()
    assert data["bracket"] is None and data["statement"] is None and data["bracket_decimal"] is None
    assert res.lines() == [f"agafonov2013: margin of 'damping_condition' in mu: no change of outcome certified in "
                           f"[0.001, 0.5]: {res.stopped}"]
    assert "refuted at mu = 0.001 and refuted at mu = 0.5" in res.stopped


@pytest.mark.parametrize("value, lo, hi, want", [
    ("3", None, None, (Fraction(3, 2), Fraction(6))),
    ("-3", None, None, (Fraction(-6), Fraction(-3, 2))),
    ("3", "1/7", None, (Fraction(1, 7), Fraction(6))),
    ("3", None, "10", (Fraction(3, 2), Fraction(10))),
    ("pi/6", "0.1", "0.2", (Fraction(1, 10), Fraction(1, 5))),
])
def test_the_search_range_is_half_and_twice_the_value_unless_given(value, lo, hi, want):
    scene = _agafonov(x2_star=value)
    assert search_range(scene, "x2_star", lo, hi) == want


@pytest.mark.parametrize("value, lo, hi, match", [
    ("pi/6", "0.1", None, "involves pi"), ("pi/6", None, "0.2", "involves pi"), ("pi/6", None, None, "involves pi"),
    ("3", "2", "2", "--lo < --hi"), ("3", "pi/8", "1", "--lo"),
])
def test_a_search_range_that_is_not_two_rationals_in_order_is_refused(value, lo, hi, match):
    with pytest.raises(ParameterError, match=match):
        search_range(_agafonov(x2_star=value), "x2_star", lo, hi)


@pytest.mark.parametrize("width", ["2", "0", "-1e-3"])
def test_a_relative_width_outside_0_1_is_refused(width):
    with pytest.raises(ParameterError, match="--width"):
        find_threshold(_agafonov(), "mu", lo="0.02", hi="0.5", width=width)


def test_an_inconclusive_midpoint_is_stepped_around_and_the_bracket_still_reaches_its_width(monkeypatch):
    """A stand-in claim that holds below 7/5 and is inconclusive within 1/100 of 3/2 (the first midpoint
    of [1, 2]): the search steps around 3/2 and certifies [p, r] around 7/5 to the requested width; where
    every point tried around a midpoint is inconclusive it stops there (never a refutation)."""
    from rigor_gyro.margins import threshold as th
    window = Fraction(1, 100)

    def fake(scene, param, value, claim, seconds=None, leaves=None):
        if abs(value - Fraction(3, 2)) < window:
            return "inconclusive", "stand-in: undecided near 3/2"
        return ("proved", "below") if value < Fraction(7, 5) else ("refuted", "above")
    monkeypatch.setattr(th, "_status", fake)
    scene = _agafonov(k="3")
    res = find_threshold(scene, "k", lo="1", hi="2", claim="damping_condition", width="1e-6")
    assert res.certified and res.proved_at < Fraction(7, 5) <= res.refuted_at
    assert (res.refuted_at - res.proved_at) <= Fraction(1, 10 ** 6) * res.refuted_at
    values = [Fraction(s["value"]) for s in res.steps]
    assert values[2] == Fraction(3, 2) and values[3] == 1 + Fraction(3, 8)     # 3/8 of the way from 1 to 2
    window = Fraction(1, 2)              # now every point tried around 3/2 is inconclusive
    res = find_threshold(scene, "k", lo="1", hi="2", claim="damping_condition", width="1e-6")
    assert not res.certified and res.exit_code == 3
    assert "inconclusive at k = 1.5 and at the 6 points around it tried" in res.stopped
    assert len(res.steps) == 2 + 1 + 6


def test_time_out_among_the_points_around_says_how_many_were_tried(monkeypatch):
    """When the time limit comes after 2 of the 6 points around an inconclusive midpoint, ``stopped`` says
    so (not "at the 6 points around it tried"), and the log's replay accepts that text and only it."""
    from rigor_gyro.core.deadline import Budget
    from rigor_gyro.margins import threshold as th
    from rigor_gyro.margins.threshold_log import replay
    calls, out_of_time = [], [False]

    def fake(scene, param, value, claim, seconds=None, leaves=None):
        calls.append(value)
        if len(calls) == 5:              # the ends, the midpoint 3/2, then the second point around it
            out_of_time[0] = True
        if abs(value - Fraction(3, 2)) < Fraction(1, 2):
            return "inconclusive", "stand-in: undecided near 3/2"
        return ("proved", "below") if value < Fraction(7, 5) else ("refuted", "above")
    monkeypatch.setattr(th, "_status", fake)
    monkeypatch.setattr(Budget, "expired", lambda self: out_of_time[0])
    res = find_threshold(_agafonov(k="3"), "k", lo="1", hi="2", claim="damping_condition", width="1e-6",
                         time_limit=1000)
    assert not res.certified and res.exit_code == 3
    assert len(res.steps) == 2 + 1 + 2
    assert res.stopped == ("time limit of 1000 s reached (--time-limit) after 2 of the 6 points around k = 1.5: "
                           "the bracket certified so far is kept")
    log = replay(res.steps, Fraction(1), Fraction(2), Fraction(1, 10 ** 6), "k")
    assert not log.error and log.stopped_ok(res.stopped) and log.budget_only
    assert not log.stopped_ok(res.stopped.replace("after 2 of", "after 3 of"))
    assert not log.stopped_ok("the claim is inconclusive at k = 1.5 and at the 6 points around it tried: "
                              "stand-in: undecided near 3/2")
