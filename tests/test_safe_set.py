"""The safe set of a paving and its certified yield (rigor_gyro.margins.safe_set)."""
from fractions import Fraction

import mpmath
import pytest

from rigor_gyro.core.balls import decimal_bounds, working_precision
from rigor_gyro.core.boxes import Box, tiles_by_bisection
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins.safe_set import (Law, common_refinement, conjunction, parse_laws, piece_probability,
                                         safe_set, yield_bounds)

WHOLE = Box.of({"a": (Fraction(0), Fraction(1)), "b": (Fraction(0), Fraction(2))})


def _tree(depth_of, box=WHOLE, status_of=None):
    """Leaves of a bisection tree: split while depth_of(box) says so; statuses from status_of(box)."""
    out, stack = [], [(box, 0)]
    while stack:
        b, d = stack.pop()
        if d < depth_of(b):
            l, r = b.split(WHOLE)
            stack.extend([(r, d + 1), (l, d + 1)])
        else:
            out.append((b, status_of(b)))
    return out


def _lo(b, k):
    return b.interval(k)[0]


def test_the_refinement_tiles_the_box_and_keeps_each_claims_status():
    # claim B: 2 leaves (the whole box is split along a: both edges are whole, a comes first), refuted
    # where a >= 1/2; claim A: 4 leaves (then along b), proved where a < 1/2 and b < 1, else undecided
    A = _tree(lambda b: 2, status_of=lambda b: "proved" if _lo(b, "a") < Fraction(1, 2) and _lo(b, "b") < 1
              else "undecided")
    B = _tree(lambda b: 1, status_of=lambda b: "refuted" if _lo(b, "a") >= Fraction(1, 2) else "proved")
    pieces = common_refinement(WHOLE, (), {"A": A, "B": B})
    assert tiles_by_bisection(WHOLE, [p for p, _ in pieces])
    for p, st in pieces:
        mid = p.midpoint()
        assert st["A"] == ("proved" if mid["a"] < Fraction(1, 2) and mid["b"] < 1 else "undecided")
        assert st["B"] == ("refuted" if mid["a"] > Fraction(1, 2) else "proved")
    out = safe_set(WHOLE, (), {"A": A, "B": B}, {"a": Law(), "b": Law()})
    assert out["volume"]["lower_exact"] == "1/4" and out["volume"]["upper_exact"] == "1/2"
    assert out["counts"] == {"proved": 1, "refuted": 2, "undecided": 1} and len(pieces) == 4


def test_the_conjunction_is_refuted_by_any_proved_by_all():
    assert conjunction({"A": "proved", "B": "refuted"}) == "refuted"
    assert conjunction({"A": "proved", "B": "undecided"}) == "undecided"
    assert conjunction({"A": "proved", "B": "proved"}) == "proved"
    assert conjunction({"A": "undecided", "B": "refuted"}) == "refuted"


def test_leaves_that_are_not_one_bisection_tree_are_refused():
    A = _tree(lambda b: 1, status_of=lambda b: "proved")
    with pytest.raises(ValueError):
        common_refinement(WHOLE, (), {"A": A[:1]})                  # a gap
    off = Box.of({"a": (Fraction(0), Fraction(1, 3)), "b": (Fraction(0), Fraction(2))})
    with pytest.raises(ValueError):
        common_refinement(WHOLE, (), {"A": [(off, "proved")] + A})   # not a node of the tree


def test_a_truncated_normal_piece_contains_mpmaths_probability():
    laws = {"a": Law(Fraction(3)), "b": Law()}
    piece = Box.of({"a": (Fraction(1, 4), Fraction(3, 8)), "b": (Fraction(0), Fraction(1, 2))})
    with working_precision(128):
        p = piece_probability(piece, WHOLE, laws)
    mpmath.mp.dps = 40
    mu, s = mpmath.mpf(1) / 2, mpmath.mpf(1) / 6
    cdf = lambda x: mpmath.ncdf(x, mu, s)
    want = (cdf(mpmath.mpf(3) / 8) - cdf(mpmath.mpf(1) / 4)) / (cdf(1) - cdf(0)) * mpmath.mpf(1) / 4
    lo, hi = (Fraction(x) for x in decimal_bounds(p, 30))
    w = Fraction(mpmath.nstr(want, 38))
    assert lo - Fraction(1, 10 ** 36) <= w <= hi + Fraction(1, 10 ** 36) and hi - lo < Fraction(1, 10 ** 25)


def test_the_normal_yield_brackets_an_mpmath_sample_of_the_truncated_law():
    A = _tree(lambda b: 3, status_of=lambda b: "proved" if _lo(b, "a") >= Fraction(1, 4) else "refuted")
    laws = {"a": Law(Fraction(2)), "b": Law(Fraction(2))}
    with working_precision(128):
        y = yield_bounds([(b, s) for b, s in A], WHOLE, laws)
    assert not y["exact"] and Fraction(y["lower"]) <= Fraction(y["upper"])
    mpmath.mp.dps = 30
    # the exact yield: P(a >= 1/4) under N(1/2, 1/4) truncated to [0, 1]
    cdf = lambda x: mpmath.ncdf(x, mpmath.mpf(1) / 2, mpmath.mpf(1) / 4)
    exact = (cdf(1) - cdf(mpmath.mpf(1) / 4)) / (cdf(1) - cdf(0))
    assert Fraction(y["lower"]) <= Fraction(mpmath.nstr(exact, 25)) <= Fraction(y["upper"])
    assert Fraction(y["upper"]) - Fraction(y["lower"]) < Fraction(1, 10 ** 5)      # nothing undecided here


def test_laws_parse_per_parameter_and_refuse_what_they_cannot_read():
    assert parse_laws("normal 3", ("a", "b")) == {"a": Law(Fraction(3)), "b": Law(Fraction(3))}
    assert parse_laws("b: normal 2", ("a", "b")) == {"a": Law(), "b": Law(Fraction(2))}
    for bad in ("gauss", "normal -1", "normal x", "c: uniform"):
        with pytest.raises(ParameterError):
            parse_laws(bad, ("a", "b"))


def test_a_normal_yield_with_undecided_pieces_is_not_rounded_up_to_one():
    """Safe where a >= 1/2, undecided elsewhere, both laws normal: the yield is [P(a >= 1/2), 1] = [1/2, 1]
    (the law is symmetric about the midpoint), never [1, 1]; with every piece safe it is [1, 1] exactly."""
    A = _tree(lambda b: 3, status_of=lambda b: "proved" if _lo(b, "a") >= Fraction(1, 2) else "undecided")
    laws = {"a": Law(Fraction(3)), "b": Law(Fraction(3))}
    with working_precision(128):
        y = yield_bounds(A, WHOLE, laws)
        assert Fraction(1, 2) - Fraction(1, 10 ** 5) <= Fraction(y["lower"]) <= Fraction(1, 2) and y["upper"] == "1"
        y = yield_bounds([(b, "proved") for b, _ in A], WHOLE, laws)
        assert (y["lower"], y["upper"]) == ("1", "1")
        y = yield_bounds([(b, "refuted") for b, _ in A], WHOLE, laws)
        assert (y["lower"], y["upper"]) == ("0", "0")
