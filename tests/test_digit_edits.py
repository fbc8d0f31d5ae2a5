"""core.digit_edits: which single edits of a print land it in a window, and when that is evidence."""
from __future__ import annotations

from fractions import Fraction as F

from hypothesis import given, strategies as st

from rigor_gyro.core.digit_edits import EDIT_CLASSES, edits_into


def _around(x: str, pad: str) -> tuple[F, F]:
    return F(x) - F(pad), F(x) + F(pad)


def test_each_edit_class_is_found():
    cases = [("0.0447756", "0.0417756", "digit-substituted", "0.0417756"),
             ("6.33182", "-6.33182", "sign", "-6.33182"),
             ("0.0016867", "0.00016867", "decimal-shift", "0.00016867"),
             ("0.012253", "0.012235", "digits-transposed", "0.012235"),
             ("0.015105", "0.0195105", "digit-dropped", "0.0195105"),
             ("-1.224194", "-1.234394", "multi-digit-substituted", "-1.234394")]
    for printed, target, cls, intended in cases:
        got = edits_into(printed, *_around(target, "0.0000001"))
        assert got and got[0].cls == cls and got[0].intended == intended, (printed, got)


def test_a_doubled_digit():
    got = edits_into("0.3908883", *_around("0.390883", "0.0000002"))
    assert got and got[0].cls == "digit-doubled" and got[0].intended == "0.390883"


def test_a_two_digit_print_against_an_exact_value():
    """-0.45 for S = 0.15 exactly: the window is the print's rounding alone; one substitution fits."""
    got = edits_into("-0.45", F(-155, 1000), F(-145, 1000))
    assert [(e.cls, e.intended) for e in got] == [("digit-substituted", "-0.15")]


def test_an_edit_inside_the_noise_is_no_evidence():
    """A print 6 units off in its last digit: substituting that digit lands, but the distance is not 10 W."""
    lo, hi = _around("0.00503942", "0.000000035")          # W = 7e-8: the print is 6e-8 away
    assert edits_into("0.00503948", lo, hi) == []
    assert "0.00503942" in [e.intended for e in edits_into("0.00503948", lo, hi, evidential=False)]


def test_a_wide_window_leaves_few_constrained_digits():
    """95.46 against [14, 17]: the substitution 9 -> 1 lands 80 away (far beyond 10 W = 30), but only the
    tens digit is above the window's width: one constrained digit is no evidence; against [15.2, 15.7]
    two are."""
    assert edits_into("95.46", F(14), F(17)) == []
    assert edits_into("95.46", F(14), F(17), evidential=False)
    assert [e.intended for e in edits_into("95.46", F("15.2"), F("15.7"))] == ["15.46"]


def test_the_dropped_and_doubled_edits_need_two_digits_after_them():
    """0.00503948 against 0.005039418: the dropped digit would sit before the last one: not evidence."""
    assert edits_into("0.00503948", *_around("0.005039418", "0.000000001")) == []


def test_the_distance_factor():
    """factor 5 (a window of the print's rounding alone) admits an edit at the second-to-last digit that
    factor 10 does not: 1.00328 for 1.00338 (b4,13) against a window 1.1e-5 wide."""
    lo, hi = _around("1.0033787", "0.0000055")
    assert edits_into("1.00328", lo, hi) == []
    assert [e.intended for e in edits_into("1.00328", lo, hi, factor=5)] == ["1.00338"]


@given(st.integers(min_value=10 ** 4, max_value=10 ** 7 - 1), st.integers(min_value=-9, max_value=-1),
       st.booleans(), st.integers(min_value=0, max_value=6), st.integers(min_value=0, max_value=9))
def test_every_edit_found_lands_in_the_window_and_a_planted_substitution_is_found(m, e, neg, pos, d):
    """Every Edit returned lies in [lo, hi] (exactly); a substitution planted away from the last two digits
    of a narrow window is found."""
    digits = str(m)
    if pos >= len(digits) - 2 or digits[pos] == str(d) or (pos == 0 and d == 0):
        return
    target = F(int(digits) * (-1 if neg else 1)) * F(10) ** e
    printed_digits = digits[:pos] + str(d) + digits[pos + 1:]
    printed = str(F(int(printed_digits) * (-1 if neg else 1)) * F(10) ** e)
    from decimal import Decimal
    printed = format(Decimal(("-" if neg else "") + printed_digits).scaleb(e), "f")
    h = F(1, 2) * F(10) ** e
    lo, hi = target - h, target + h
    got = edits_into(printed, lo, hi)
    for ed in got:
        assert lo <= F(ed.intended) <= hi and ed.cls in EDIT_CLASSES
    assert any(ed.cls == "digit-substituted" and F(ed.intended) == target for ed in got)


def test_the_memo_of_edits_into_keys_the_window_exactly():
    # the memo is keyed by the window's integer numerators and denominators: a Fraction and an fmpq window give
    # the same edits, and a window one unit narrower (which excludes the intended value) gives none of them
    from fractions import Fraction as F
    from flint import fmpq
    from rigor_gyro.core.digit_edits import edits_into
    got = edits_into("0.1432", F(1341, 10000), F(1343, 10000))
    assert [e.intended for e in got] == [e.intended for e in edits_into("0.1432", fmpq(1341, 10000), fmpq(1343, 10000))]
    assert "0.1342" in [e.intended for e in got]
    assert "0.1342" not in [e.intended for e in edits_into("0.1432", F(13421, 100000), F(1343, 10000))]
