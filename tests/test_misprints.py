"""The discrepancy classifier (core.misprints): each class on planted prints, the order of readings,
the digit thresholds, and a property: a single planted edit of a correct rounding is read as that edit
(or as a simpler reading that also fits), never as agreement."""
from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import pytest
from flint import arb, fmpq
from hypothesis import given, strategies as st

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.misprints import CLASSES, classify_printed, classify_row, rounded_at
from rigor_gyro.core.outcome import AuditRow, AuditStatus

V = arb(fmpq(1382699412, 10 ** 10))      # 0.1382699412 exactly


@pytest.mark.parametrize("printed, cls", [
    ("0.13827", "agrees"),
    ("0.13828", "last-digit"),
    ("0.13826", "last-digit"),
    ("-0.13827", "sign"),
    ("1.3827", "decimal-shift"),
    ("0.013827", "decimal-shift"),
    ("0.13872", "digits-transposed"),
    ("0.1387", "digit-dropped"),
    ("0.138827", "digit-doubled"),
    ("0.13927", "digit-substituted"),
    ("0.13829", "unexplained"),          # the last digit two units off: a numerical difference
    ("0.5", "unexplained"),              # one significant digit: no digit edit is a reading
    ("0.24", "unexplained"),
])
def test_each_class_on_a_planted_print(printed, cls):
    c = classify_printed(printed, V)
    assert c.cls == cls, (printed, c)
    assert c.readings[0] == cls and c.cls in CLASSES


def test_propagated_comes_before_a_digit_reading():
    c = classify_printed("0.13828", V, propagated=arb(fmpq(138281, 10 ** 6)))
    assert c.cls == "propagated" and "last-digit" in c.readings


def test_compound_readings_need_enough_digits_and_two_agreeing_digits_after_the_edit():
    # a misprinted leading digit on top of the paper's own rounding (a hand-computed table)
    c = classify_printed("0.248720", arb(fmpq(348727, 10 ** 6)))
    assert c.cls == "digit-substituted" and "agrees with the value to 4 of 6" in c.reading
    # the edit in the 4th of 6 digits with one agreeing digit after it: chance, not a reading
    assert classify_printed("24.5407", arb(fmpq(245714, 10 ** 4))).cls == "unexplained"


def test_a_wide_ball_is_undecided_not_explained():
    wide = arb(fmpq(13827, 10 ** 5), fmpq(1, 10 ** 4))
    assert rounded_at(wide, -5) is None
    assert classify_printed("0.13820", wide).cls == "undecided"


def test_row_classes_for_assertions_formulas_and_non_numbers():
    assert classify_row(AuditRow("a", "V > 0", "", None, AuditStatus.CONFIRMED)).cls == "assertion-confirmed"
    assert classify_row(AuditRow("a", "R = R1", "", None, AuditStatus.REFUTED)).cls == "assertion-refuted"
    assert classify_row(AuditRow("f", "lambda^2", "Omega^2", None, AuditStatus.MISPRINT)).cls == "misprint-reading"
    assert classify_row(AuditRow("n", "41.4, 121.5", "", V, AuditStatus.DISAGREES)).cls == "not-a-number"
    assert classify_row(AuditRow("x", "0.13872", "", V, AuditStatus.DISAGREES)).cls == "digits-transposed"


@given(st.integers(10 ** 5, 10 ** 6 - 1), st.integers(0, 4), st.sampled_from(["transpose", "sign", "shift"]))
def test_a_planted_edit_is_never_read_as_agreement(n, i, edit):
    value = arb(fmpq(n * 1000 + 123, 10 ** 9))            # 0.nnnnnn123: rounds to 0.nnnnnn
    true = rounded_at(value, -6)
    digits = list(str(true)[2:])
    if edit == "transpose":
        if digits[i] == digits[i + 1]:
            return
        digits[i], digits[i + 1] = digits[i + 1], digits[i]
        # (a transposition that moves a leading digit past a zero is also a decimal shift)
        printed, expect = "0." + "".join(digits), {"digits-transposed", "last-digit", "decimal-shift"}
    elif edit == "sign":
        printed, expect = str(-true), {"sign"}
    else:
        printed, expect = str(true * 10), {"decimal-shift"}
    c = classify_printed(printed, value)
    assert c.cls != "agrees"
    assert c.cls in expect or set(c.readings) & expect, (printed, c)
    assert Decimal(printed) != true


def test_propagated_needs_some_value_of_the_recomputation_to_round_to_the_print():
    """`propagated` means: some value the paper's own inputs allow (a ball) rounds to the print. A ball
    meeting the print's rounding interval [P - h, P + h] qualifies even when it is wider than it; a ball
    beside the interval does not."""
    from rigor_gyro.core.misprints import classify_printed
    value = arb("1.23464")                        # the certified value: 1.234394 is not a rounding of it
    wide = arb("1.2343").union(arb("1.2345"))     # holds 1.234394 +- 5e-7
    beside = arb("1.2340").union(arb("1.2343"))   # ends below 1.2343935
    assert classify_printed("1.234394", value, wide).cls == "propagated"
    assert classify_printed("1.234394", value, beside).cls != "propagated"
    assert classify_printed("1.234394", value, None).cls != "propagated"


def test_the_relay_tables_are_judged_against_the_paper_s_own_closed_form():
    """Table 2 and the coefficients of form (7) are recomputed from the paper's own printed coefficients,
    exponents, a_ij and D (each within its printed rounding): at t = 0, alpha = -0.00164586 is the sum of its
    printed coefficients (the paper's arithmetic), while i sin = 0.202595 is still a sign misprint (the
    paper's own a41 D1 + a42 D2 is negative); beta sin = 0.0417756 is the paper's own D1 (printed 0.0447756
    above it: the misprint is D1's, decided by the identity D1 = beta sin = h11)."""
    from rigor_gyro import load_scene, prove_scene
    rows = {r["id"]: r for r in prove_scene(load_scene("roitenberg1947_b2over15")).to_json()["paper"]}
    assert rows["Table 2 t=0 alpha"]["class"] == "propagated"
    assert rows["beta_dot sin"]["class"] == "propagated"
    assert rows["i sin"]["class"] == "sign"
    assert rows["beta sin"]["class"] == "propagated"
    assert rows["D1"]["class"] == "digit-substituted" and "D1 = beta sin = h11" in rows["D1"]["class_reading"]
    # a symbol the transcription garbled is a row, never only a silent correction in the scene's data
    tr = rows["transcription: Table 2 t=0.10 Omega"]
    assert tr["printed"] == "0.028f524" and tr["reading"] == rows["Table 2 t=0.10 Omega"]["printed"] == "0.0286524"


@given(st.integers(min_value=-10 ** 30, max_value=10 ** 30), st.integers(min_value=0, max_value=700),
       st.integers(min_value=-40, max_value=5))
def test_rounded_at_is_the_exact_half_even_rounding(man, shift, exponent):
    """An exact ball m 2^-shift against the half-even rounding done in Fractions: rounded_at is exact,
    whatever the number of decimal digits of the dyadic (a 200-digit conversion was not)."""
    with working_precision(4096):
        x = arb(fmpq(man, 2 ** shift))
        assert x.rad() == 0
    q = Fraction(man, 2 ** shift) / Fraction(10) ** exponent
    n = q.numerator // q.denominator
    r = q - n
    if r > Fraction(1, 2) or (r == Fraction(1, 2) and n % 2):
        n += 1
    assert rounded_at(x, exponent) == Decimal(f"{n}E{exponent}")


def test_a_dyadic_within_1e_200_of_a_tie_rounds_away_from_the_tie():
    with working_precision(2400):
        above = arb(fmpq(1, 8)) + arb(fmpq(1, 2 ** 700))      # 0.125 + 2^-700: rounds up at 2 places
        below = arb(fmpq(1, 8)) - arb(fmpq(1, 2 ** 700))
        assert above.rad() == 0 and below.rad() == 0
        assert rounded_at(above, -2) == Decimal("0.13")
        assert rounded_at(below, -2) == Decimal("0.12")
        assert rounded_at(arb(fmpq(1, 8)), -2) == Decimal("0.12")            # the tie: half-even
