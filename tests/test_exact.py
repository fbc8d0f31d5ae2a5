"""Exact parameter parsing: strings become rationals (times pi) with no binary rounding."""
from fractions import Fraction

import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.exact import parse_exact


@pytest.mark.parametrize("text, rational, pi", [
    ("15.08", Fraction(1508, 100), 0),
    ("1e4", Fraction(10000), 0),
    ("2/15", Fraction(2, 15), 0),
    ("-3", Fraction(-3), 0),
    ("pi/6", Fraction(1, 6), 1),
    ("0.5*pi", Fraction(1, 2), 1),
    ("2*pi/3", Fraction(2, 3), 1),
    ("1.5e-3", Fraction(3, 2000), 0),
    (" 0.1076 ", Fraction(1076, 10000), 0),
    (7, Fraction(7), 0),
    (Fraction(1, 3), Fraction(1, 3), 0),
    (fmpq(2, 7), Fraction(2, 7), 0),
])
def test_parses_exactly(text, rational, pi):
    x = parse_exact(text)
    assert x.rational == rational and x.pi_power == pi


@pytest.mark.parametrize("text", ["15.08", "0.1", "1e-30", "123456789.987654321", "2/15"])
def test_round_trip_through_fraction(text):
    """The exact value equals Python's exact reading of the same decimal."""
    assert parse_exact(text).rational == Fraction(text)


def test_ball_contains_exact_value_at_working_precision():
    with working_precision(200):
        b = parse_exact("0.1").ball()
        assert b.is_finite() and b.contains(arb(fmpq(1, 10)))
        assert b.rad() < arb(2) ** -190
        p6 = parse_exact("pi/6").ball()
        assert p6.is_finite() and (p6 * 6 - arb.pi()).contains(0)


@pytest.mark.parametrize("bad", [0.1, "abc", "1..2", "", "pi*pi", "1/0", "0x10", True, None, [1]])
def test_bad_input_raises_parameter_error(bad):
    with pytest.raises(ParameterError):
        parse_exact(bad, name="x")


def test_float_error_names_parameter_and_fix():
    with pytest.raises(ParameterError, match=r"parameter 'eps'.*\"0.1\""):
        parse_exact(0.1, name="eps")


def test_messages_name_the_parameter_and_suggest_the_near_key():
    """A parse error names the parameter it is about (and only then says 'parameter'); an unknown key
    close to a known one gets a did-you-mean, a key close to none gets none; to_fmpq is parse_exact's
    rational as an fmpq, with the same errors."""
    from flint import fmpq
    from rigor_gyro.core.exact import parse_parameters, to_fmpq
    with pytest.raises(ParameterError) as named:
        parse_exact("1/x", "eps")
    assert str(named.value).startswith("parameter 'eps': ")
    with pytest.raises(ParameterError) as anonymous:
        parse_exact("1/x")
    assert str(anonymous.value).startswith("cannot read '1/x'")
    with pytest.raises(ParameterError, match=r"did you mean 'Omega2'\?"):
        parse_parameters({"Omega22": "1"}, "eigenfrequencies", ["eps", "Omega2"], [])
    with pytest.raises(ParameterError) as far:
        parse_parameters({"zzzz": "1"}, "eigenfrequencies", ["eps", "Omega2"], [])
    assert "unknown parameter(s) ['zzzz'] for kind 'eigenfrequencies'; expected" in str(far.value)
    assert "did you mean" not in str(far.value)
    assert to_fmpq("-7/3e2") == fmpq(-7, 300) and to_fmpq("0.25", "k") == fmpq(1, 4)
    with pytest.raises(ParameterError, match="parameter 'k': "):
        to_fmpq("pi", "k")          # a multiple of pi is not rational


def test_the_parsers_limits_are_exactly_where_documented():
    """1000 digits, exponent 400 and magnitudes 1e-300..1e300 are accepted; one more is refused, with a
    message naming the parameter."""
    from rigor_gyro.core.exact import MAX_DIGITS, MAX_MAGNITUDE
    ok = ["1." + "0" * (MAX_DIGITS - 1), "0." + "0" * 299 + "1", "1e300", "-1e300", "1e-300", "1" + "0" * 300,
          "1/1" + "0" * 300, "1e+300", "0.1e-299"]
    for text in ok:
        assert parse_exact(text, "x").rational is not None, text
    assert parse_exact("0e400", "x").rational == 0 and parse_exact("0e-400", "x").rational == 0
    bad = [("1" * (MAX_DIGITS + 1), "at most 1000 digits"), ("0e401", "exponent must lie in [-400, 400]"),
           ("0e-401", "exponent must lie in [-400, 400]"), ("0e0401", "exponent must lie in [-400, 400]"),
           ("1e301", "magnitude between 1e-300 and 1e300"), ("1.1e300", "magnitude between"),
           ("1e-301", "magnitude between"), ("0.9e-300", "magnitude between"), ("-1e301", "magnitude between"),
           (10 ** 301, "magnitude between"), (2 ** (4 * MAX_DIGITS + 1), "more than 1000 digits")]
    for value, words in bad:
        with pytest.raises(ParameterError) as e:
            parse_exact(value, "x")
        assert "parameter 'x'" in str(e.value) and words in str(e.value), (value, str(e.value))
    assert parse_exact(10 ** MAX_MAGNITUDE, "x").rational == 10 ** MAX_MAGNITUDE
    assert parse_exact(2 ** 996, "x").rational == 2 ** 996
    assert parse_exact("0e" + "0" * 5 + "400", "x").rational == 0          # leading zeros of the exponent


@pytest.mark.parametrize("text, value, pi_power", [
    ("+5", Fraction(5), 0), ("- 5", Fraction(-5), 0), ("+ 2/3", Fraction(2, 3), 0), ("1E5", Fraction(10**5), 0),
    ("2*3*4", Fraction(24), 0), ("-pi/6", Fraction(-1, 6), 1), ("0.5*pi", Fraction(1, 2), 1),
    ("2*2*2*2*2*2*2*2", Fraction(256), 0)])              # MAX_FACTORS = 8 factors
def test_signs_exponents_and_factors_are_read_exactly(text, value, pi_power):
    e = parse_exact(text, "x")
    assert (e.rational, e.pi_power) == (value, pi_power)


@pytest.mark.parametrize("text, words", [("2/pi", "rational multiples of pi"), ("pi*pi", "rational multiples of pi"),
                                         ("2*2*2*2*2*2*2*2*2", "at most 8 factors")])
def test_pi_in_a_denominator_or_squared_and_a_ninth_factor_are_refused(text, words):
    with pytest.raises(ParameterError) as e:
        parse_exact(text, "x")
    assert words in str(e.value) and "parameter 'x'" in str(e.value)
