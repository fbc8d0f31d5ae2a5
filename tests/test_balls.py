"""Certified predicates, precision handling and outward-rounded decimals."""
from fractions import Fraction

import pytest
from flint import arb, ctx, fmpq
from hypothesis import given
from hypothesis import strategies as st

from rigor_gyro.core.balls import (certainly_ge, certainly_gt, certainly_le, certainly_lt, compare,
                              decimal_bounds, escalate, possibly_zero, quantity, working_precision)


def test_touching_balls_are_undecided():
    a, b = arb(1, 1), arb(2, 1)            # [0, 2] and [1, 3]
    assert compare(a, b) is None
    assert not certainly_lt(a, b) and not certainly_ge(a, b)
    assert not certainly_lt(arb(1), arb(1)) and not certainly_gt(arb(1), arb(1))


def test_nan_and_infinity_never_decide():
    nan, inf = arb("nan"), arb("inf")
    for x in (nan, inf, -inf):
        assert compare(x, 0) is None
        assert not certainly_lt(x, 1) and not certainly_gt(x, 1) and not certainly_le(x, 1)
        assert possibly_zero(x)


def test_separated_balls_decide():
    assert compare(arb(1), arb(2)) == -1 and compare(arb(3, "0.5"), arb(1)) == 1
    assert certainly_le(arb(1), arb(1))    # exact equal points: <= holds everywhere


def test_precision_restored_after_exception():
    before = ctx.prec
    with pytest.raises(RuntimeError):
        with working_precision(300):
            assert ctx.prec == 300
            raise RuntimeError("boom")
    assert ctx.prec == before


def test_escalate_records_needed_precision_and_restores():
    before = ctx.prec
    target = arb(2) ** -150

    def attempt(p):
        return arb(fmpq(1, 3)).rad()

    out = escalate(attempt, lambda r: r < target, prec=64, maxprec=1024)
    assert out.done and out.prec == 256 and out.tried == [64, 128, 256]
    out = escalate(attempt, lambda r: False, prec=64, maxprec=200)
    assert not out.done and out.tried == [64, 128]
    assert ctx.prec == before


def test_escalate_restores_precision_when_attempt_raises():
    before = ctx.prec
    with pytest.raises(ZeroDivisionError):
        escalate(lambda p: 1 / 0, lambda r: True)
    assert ctx.prec == before


def test_default_str_collapses_but_bounds_do_not():
    x = arb(1).union(arb(2))
    lo, hi = decimal_bounds(x)
    assert Fraction(lo) <= 1 and Fraction(hi) >= 2 and Fraction(hi) - Fraction(lo) < 2


@given(st.integers(-10**30, 10**30), st.integers(1, 10**20), st.integers(0, 120), st.integers(64, 400))
def test_decimal_bounds_contain_the_ball(num, den, radexp, prec):
    with working_precision(prec):
        x = arb(fmpq(num, den)) + arb(0, arb(2) ** -radexp)
    lo, hi = decimal_bounds(x)
    q = quantity(x)
    assert Fraction(lo) <= Fraction(q["mid"]) <= Fraction(hi)
    # exact comparison with the ball's endpoints (an arb of a long decimal would itself be rounded)
    man, exp = x.mid().man_exp()
    mid = Fraction(int(man)) * Fraction(2) ** int(exp)
    rman, rexp = arb(x.rad()).man_exp()
    rad = Fraction(int(rman)) * Fraction(2) ** int(rexp)
    assert Fraction(lo) <= mid - rad and mid + rad <= Fraction(hi)
    assert Fraction(q["rad"]) >= 0


def test_quantity_keeps_its_keys_and_digits_for_every_ball():
    from rigor_gyro.core.balls import quantity
    for x in (arb("nan"), arb("inf"), arb(1) / 3):
        assert set(quantity(x)) == {"lo", "hi", "mid", "rad"}
    assert len(quantity(arb(1) / 3, 5)["lo"]) < len(quantity(arb(1) / 3)["lo"])


def test_an_audit_row_with_a_value_prints_its_enclosure():
    from rigor_gyro.core.outcome import AuditRow, AuditStatus
    row = AuditRow("x", "1", "r", arb(1) / 3, AuditStatus.AGREES).to_json()
    assert Fraction(row["lo"]) <= Fraction(1, 3) <= Fraction(row["hi"])
    empty = AuditRow("x", "1", "r", None, AuditStatus.AGREES).to_json()
    assert empty["lo"] == "" and empty["hi"] == ""


def test_the_small_predicates_decide_only_on_certainty():
    from rigor_gyro.core.balls import certainly_within, contains, is_finite, overlaps
    from rigor_gyro.core.outcome import Status
    assert certainly_within(arb(1), 0, 2) and not certainly_within(arb(0), 0, 2)
    assert not certainly_within(arb(1, 1), 0, 2) and not certainly_within(arb("nan"), 0, 2)
    assert contains(arb(1, 1), arb(1)) and not contains(arb(1, 1), arb(3))
    assert not contains(arb("nan"), arb(1)) and not contains(arb(1, 1), arb("inf"))
    assert overlaps(arb(1, 1), arb(2, 1)) and not overlaps(arb(0), arb(1))
    assert is_finite(arb(1)) and not is_finite(arb("inf")) and not is_finite(arb("nan"))
    assert Status.of(True, False) is Status.PROVED and Status.of(False, True) is Status.REFUTED
    assert Status.of(False, False) is Status.INCONCLUSIVE
    with pytest.raises(AssertionError):
        Status.of(True, True)
