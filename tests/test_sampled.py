"""The paving checker's point-prover cross-check (rigor_gyro.margins.sampled), with a stand-in prover."""
from fractions import Fraction

from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins.sampled import chosen, cross_check, sample_points


def _box(lo, hi):
    return Box.of({"a": (Fraction(lo), Fraction(hi)), "b": (Fraction(0), Fraction(1))})


def test_the_spread_keeps_the_first_and_the_last_and_every_box_when_few():
    boxes = list(range(100))
    assert chosen(boxes, 8)[0] == 0 and chosen(boxes, 8)[-1] == 99 and len(set(chosen(boxes, 8))) == 8
    assert chosen(boxes[:5], 8) == boxes[:5] and chosen(boxes, 0) == [] and chosen([], 3) == []


def test_midpoint_and_both_extreme_corners_each_once():
    pts = dict(sample_points(_box(0, 2)))
    assert pts == {"midpoint": {"a": 1, "b": Fraction(1, 2)}, "lower corner": {"a": 0, "b": 0},
                   "upper corner": {"a": 2, "b": 1}}
    flat = Box.of({"a": (Fraction(1), Fraction(1))})
    assert [w for w, _ in sample_points(flat)] == ["midpoint"]


def test_a_contradiction_at_the_upper_corner_of_the_last_box_fails():
    boxes = [(_box(i, i + 1), "proved") for i in range(20)]
    bad = lambda p: "refuted" if p == {"a": 20, "b": 1} else "proved"
    ok, msg = cross_check("c", boxes, 8, bad)
    assert not ok and "upper corner" in msg and "stored proved" in msg
    ok, msg = cross_check("c", boxes, 8, lambda p: "proved")
    assert ok and "agrees at 24 of 24 points of 8 of the 20 decided sub-boxes" in msg


def test_a_refuted_box_proved_at_a_point_fails_and_inconclusive_points_are_no_evidence():
    boxes = [(_box(0, 1), "refuted"), (_box(1, 2), "undecided")]
    assert not cross_check("c", boxes, 8, lambda p: "proved")[0]
    ok, msg = cross_check("c", boxes, 8, lambda p: "inconclusive")
    assert ok and "agrees at 0 of 3 points of 1 of the 1 decided" in msg and "3 inconclusive" in msg


def test_a_point_refused_as_bad_input_is_counted_not_a_verdict():
    def refuse(p):
        raise ParameterError("b must be positive")
    ok, msg = cross_check("c", [(_box(0, 1), "proved")], 8, refuse)
    assert ok and "3 refused as bad input" in msg and "b must be positive" in msg
