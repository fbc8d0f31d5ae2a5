"""Stored enclosures read back exactly (``core/stored.py``): what a checker believes of a certificate's
decimals. Every answer is compared with exact rationals."""
from fractions import Fraction

import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import exact_endpoints, working_precision
from rigor_gyro.core.stored import as_ball, ball_text, encloses, exact_text, fmpq_of, interval, meets, number, pieces_text


@pytest.mark.parametrize("text, value", [
    ("1.5", Fraction(3, 2)), (" 2/3 ", Fraction(2, 3)), ("1e-3", Fraction(1, 1000)), ("-0.25e+2", Fraction(-25)),
    ("7", Fraction(7)), ("-12/8", Fraction(-3, 2)), ("1e-999999", Fraction(1, 10**999999)), ("0", Fraction(0))])
def test_a_stored_number_is_its_exact_rational(text, value):
    assert number(text) == value


@pytest.mark.parametrize("text", [
    "nan", "inf", "-inf", "1.", ".5", "1/0", "0/0", "1e1234567", "0x10", "1_000", "\u0661", "1/-2", "1.5/2", "", " ",
    "1e", "+1", "1 2", 1.5, 2, None, ["1"], "9" * 20001])
def test_anything_else_is_a_value_error(text):
    with pytest.raises(ValueError):
        number(text)


def test_a_stored_interval_is_read_from_a_dict_or_a_pair_and_never_inverted():
    assert interval({"lo": "0.1", "hi": "0.2", "mid": "9", "rad": "9"}) == (Fraction(1, 10), Fraction(1, 5))
    assert interval(["1/3", "1/3"]) == (Fraction(1, 3), Fraction(1, 3))
    assert interval(("-1", "2")) == (Fraction(-1), Fraction(2))
    with pytest.raises(ValueError, match="lo > hi"):
        interval(["0.2", "0.1"])
    with pytest.raises(ValueError):
        interval({"lo": "0.1", "hi": "x"})


def test_fmpq_of_is_exact():
    assert fmpq_of(Fraction(-7, 3)) == fmpq(-7, 3)
    assert fmpq_of(Fraction(10**40 + 1, 3 * 10**39)) == fmpq(10**40 + 1, 3 * 10**39)


def test_encloses_needs_every_point_of_the_ball_inside():
    with working_precision(64):
        third = arb(fmpq(1, 3))                                  # not exact: a ball around 1/3
        lo, hi = exact_endpoints(third)
        assert lo < Fraction(1, 3) < hi
        assert encloses((lo, hi), third)                         # its own ends: touching counts
        assert encloses((lo - 1, hi + 1), third)
        assert not encloses((lo + Fraction(1, 10**40), hi), third)   # a hair short below
        assert not encloses((lo, hi - Fraction(1, 10**40)), third)   # a hair short above
        assert not encloses((Fraction(1, 3), Fraction(1, 3)), third)  # the number alone: the ball is wider
        assert encloses((Fraction(1, 2), Fraction(1, 2)), arb(0.5))  # an exact ball at its point
        assert not encloses((Fraction(-10**9), Fraction(10**9)), arb("nan"))
        assert not encloses((Fraction(-10**9), Fraction(10**9)), arb("inf"))
        assert not encloses((Fraction(-10**9), Fraction(10**9)), arb(0, "inf"))


def test_meets_needs_one_common_point():
    with working_precision(64):
        x = arb(1, 0.5)                                          # about [0.5, 1.5]
        lo, hi = exact_endpoints(x)
        assert meets((lo - 1, lo), x)                            # touching at the lower end
        assert meets((hi, hi + 1), x)                            # touching at the upper end
        assert meets((lo - 1, hi + 1), x) and meets((Fraction(1), Fraction(1)), x)
        assert not meets((lo - 1, lo - Fraction(1, 10**30)), x)
        assert not meets((hi + Fraction(1, 10**30), hi + 1), x)
        assert not meets((Fraction(-10**9), Fraction(10**9)), arb("nan"))
        assert not meets((Fraction(-10**9), Fraction(10**9)), arb(0, "inf"))


def test_as_ball_contains_the_whole_stored_interval():
    with working_precision(53):
        b = as_ball((Fraction(1, 3), Fraction(2, 3)))
        lo, hi = exact_endpoints(b)
        assert lo <= Fraction(1, 3) and Fraction(2, 3) <= hi
        assert hi - lo < Fraction(1, 3) * (1 + Fraction(1, 2**28))   # a radius has 30 bits
        b = as_ball((Fraction(-1, 7), Fraction(-1, 7)))
        lo, hi = exact_endpoints(b)
        assert lo <= Fraction(-1, 7) <= hi and hi - lo < Fraction(1, 2**45)


def test_the_texts_are_exact_and_read_back():
    assert exact_text(Fraction(1, 3)) == "1/3" and exact_text(Fraction(4, 2)) == "2" and exact_text(Fraction(-5, 7)) == "-5/7"
    with working_precision(64):
        a, b = arb(fmpq(1, 3)), arb(fmpq(2, 3))
        lo_a, hi_a = exact_endpoints(a)
        lo_b, hi_b = exact_endpoints(b)
        assert ball_text(a) == [str(lo_a), str(hi_a)]
        assert pieces_text([(a, b), (b, a)]) == [[str(lo_a), str(hi_b)], [str(lo_b), str(hi_a)]]
        assert [number(t) for t in ball_text(a)] == [lo_a, hi_a]
        inf_lo, inf_hi = pieces_text([(arb("-inf"), arb("inf"))])[0]
        assert (inf_lo, inf_hi) == ("-inf", "inf")
        with pytest.raises(ValueError):                          # an infinite end is no stored number
            number(inf_lo)
        with pytest.raises(ValueError):
            number(inf_hi)


def test_the_length_limit_is_20000_characters_and_the_message_quotes_the_text():
    assert number("1" * 20000) == (10 ** 20000 - 1) // 9       # past Python's 4300-digit int() limit
    with pytest.raises(ValueError, match=r"not a finite stored number: '1111"):
        number("1" * 20001)
    with pytest.raises(ValueError, match=r"not a finite stored number: 'nan'"):
        number("nan")
    with pytest.raises(ValueError, match=r"zero denominator: '3/0'"):
        number("3/0")


def test_numbers_past_pythons_4300_digit_limit_are_written_and_read_exactly():
    """A certificate at 16384 bits stores dyadic pieces p/2^16384 (about 4900 digits each)."""
    x = Fraction(3 ** 20001, 2 ** 16384)
    assert number(exact_text(x)) == x
    assert number(exact_text(-x)) == -x
    assert number(exact_text(Fraction(7 ** 6000))) == 7 ** 6000
    with working_precision(16384):
        b = arb(fmpq(1, 3))
        lo, hi = exact_endpoints(b)
        assert [number(t) for t in ball_text(b)] == [lo, hi]
    assert number("1" * 5000 + "." + "2" * 5000 + "e-3") == Fraction(int("1" * 3000) * 10**2000 + int("1" * 2000), 1) \
        / 10**3 + Fraction(int("2" * 3000) * 10**2000 + int("2" * 2000), 10**5000) / 10**3


@pytest.mark.parametrize("text, value", [("-0.5", Fraction(-1, 2)), ("-0", Fraction(0)), ("0.000", Fraction(0)),
                                         ("12.5e3", Fraction(12500)), ("12.5e-3", Fraction(1, 80)),
                                         ("-3/6", Fraction(-1, 2)), ("007", Fraction(7)), ("5e0", Fraction(5))])
def test_the_decimal_reader_agrees_with_fraction(text, value):
    assert number(text) == value == Fraction(text)
