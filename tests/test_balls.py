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


def test_escalate_tries_every_doubling_up_to_maxprec_inclusive_and_passes_each_precision():
    """Each attempt gets its precision as argument and as ctx.prec; maxprec itself is tried when it is a
    doubling (64 -> 128 with maxprec 128), and maxprec = prec (a documented setting: --prec 16384 --maxprec
    16384) runs once; ``done`` is False, not merely falsy, when nothing was accepted."""
    seen = []

    def attempt(p):
        seen.append((p, ctx.prec))
        return p

    out = escalate(attempt, lambda r: False, prec=64, maxprec=128)
    assert out.tried == [64, 128] and out.prec == 128 and out.result == 128 and out.done is False
    assert seen == [(64, 64), (128, 128)]
    out = escalate(attempt, lambda r: r == 256, prec=256, maxprec=256)
    assert out.tried == [256] and out.done is True
    from rigor_gyro.core.errors import ParameterError
    with pytest.raises(ParameterError, match="maxprec"):
        escalate(attempt, lambda r: True, prec=256, maxprec=128)


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
    # the stated half-width: the exact one rounded up to 3 significant digits
    r = Fraction(q["rad"])
    assert rad <= r <= rad * Fraction(101, 100)
    digits = q["rad"].lower().split("e")[0].replace(".", "").replace("-", "").strip("0")
    assert len(digits) <= 3, q["rad"]


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


# ---------------------------------------------------------------- decimals in integer arithmetic

def _round_decimal_reference(q: Fraction, digits: int, mode: str) -> str:
    """The Fraction formulation the integer code replaced (kept here as the oracle)."""
    import math

    from rigor_gyro.core.balls import _format_scaled
    if q == 0:
        return "0"
    a = abs(q)
    e = int((a.numerator.bit_length() - a.denominator.bit_length()) * 0.30102999566398120)
    while Fraction(10) ** e > a:
        e -= 1
    while Fraction(10) ** (e + 1) <= a:
        e += 1
    scale = digits - 1 - e
    scaled = q * Fraction(10) ** scale
    n = math.floor(scaled) if mode == "down" else math.ceil(scaled) if mode == "up" else round(scaled)
    return _format_scaled(n, scale)


@given(st.integers(-10**40, 10**40), st.one_of(st.integers(1, 10**30), st.integers(0, 300).map(lambda k: 2**k),
                                              st.integers(0, 40).map(lambda k: 10**k)),
       st.integers(1, 40), st.sampled_from(["down", "up", "nearest"]))
def test_round_decimal_matches_the_fraction_formulation(num, den, digits, mode):
    from rigor_gyro.core.balls import _round_decimal
    q = Fraction(num, den)
    assert _round_decimal(q, digits, mode) == _round_decimal_reference(q, digits, mode)


@given(st.integers(-10**6, 10**6), st.integers(0, 8), st.integers(1, 12), st.sampled_from(["down", "up", "nearest"]))
def test_round_decimal_ties_and_exact_values(m, k, digits, mode):
    from rigor_gyro.core.balls import _round_decimal
    q = Fraction(2 * m + 1, 2 * 10**k)       # a tie at some digit count: ties go to even for 'nearest'
    assert _round_decimal(q, digits, mode) == _round_decimal_reference(q, digits, mode)


def _agreeing_digits_reference(printed: str, value: arb) -> int:
    from decimal import ROUND_HALF_EVEN, Decimal

    from rigor_gyro.core.balls import exact_endpoints
    dec = Decimal(printed.strip())
    total, best = len(dec.as_tuple().digits), 0
    if dec == 0 or not value.is_finite():
        return 0
    lo, hi = exact_endpoints(value)
    for d in range(1, total + 1):
        r = dec.quantize(Decimal(1).scaleb(dec.adjusted() - d + 1), rounding=ROUND_HALF_EVEN)
        half = Decimal(5).scaleb(r.as_tuple().exponent - 1)
        if Fraction(r - half) <= lo and hi <= Fraction(r + half):
            best = d
    return best


@given(st.floats(-1e6, 1e6, allow_nan=False), st.integers(1, 15), st.integers(1, 17), st.integers(-3, 3))
def test_agreeing_digits_matches_the_decimal_formulation(x, radexp, digits, nudge):
    from rigor_gyro.core.audit import agreeing_digits
    v = arb(repr(x), repr(abs(x) * 10.0 ** -radexp + 1e-300))
    printed = f"{x:.{digits}g}"
    if "e" in printed or "inf" in printed:
        return
    if nudge and printed[-1].isdigit():      # a last digit off by a few units: fewer digits agree
        printed = printed[:-1] + str((int(printed[-1]) + nudge) % 10)
    assert agreeing_digits(printed, v) == _agreeing_digits_reference(printed, v)


@given(st.integers(-10**6, 10**6), st.integers(2, 40), st.integers(0, 60), st.integers(3, 8), st.booleans())
def test_decimal_bounds_apart_excludes_the_value_exactly_when_the_ball_does(num, k, radexp, digits, near):
    """decimal_bounds_apart (how a multiplier modulus is printed against 1): the printed interval
    contains the ball; it excludes the value whenever the ball certainly does (a modulus certainly > 1
    never prints as [1, 1.0001]), with the digits asked when those already exclude it, and it is the
    plain decimal_bounds when the ball does not exclude the value."""
    from rigor_gyro.core.balls import decimal_bounds, decimal_bounds_apart, exact_fraction
    x = arb(1) + arb(fmpq(num, 10 ** k)) * (arb(fmpq(1, 10 ** 6)) if near else 1) + arb(0, fmpq(1, 2 ** radexp))
    lo, hi = decimal_bounds_apart(x, 1, digits)
    assert Fraction(lo) <= exact_fraction(x.lower()) and Fraction(hi) >= exact_fraction(x.upper())
    plain = decimal_bounds(x, digits)
    if certainly_gt(x, 1):
        assert Fraction(lo) > 1
    elif certainly_lt(x, 1):
        assert Fraction(hi) < 1
    else:
        assert (lo, hi) == plain
    if Fraction(plain[0]) > 1 or Fraction(plain[1]) < 1:
        assert (lo, hi) == plain


def test_the_certificate_form_of_a_non_finite_ball_says_which_it_is():
    """quantity() of a NaN ball and of an unbounded one: outward ends that say nothing is known, and a
    midpoint that tells them apart (a reader of the certificate sees why no decimal is given)."""
    from rigor_gyro.core.balls import quantity
    nan, unbounded = quantity(arb("nan")), quantity(arb(0, "inf"))
    assert nan["mid"] == "nan" and unbounded["mid"] == "inf"
    assert nan["rad"] == unbounded["rad"] == "inf"
    assert set(nan) == set(unbounded) == {"lo", "hi", "mid", "rad"}


def test_the_stored_hull_is_the_decimal_interval_for_any_sign():
    """stored_hull(x) is exactly [lo, hi] of the certificate's decimals of x (rounded outward, so it
    holds x), for x negative, positive and through 0; a non-finite ball is returned as it is."""
    from fractions import Fraction
    from flint import fmpq
    from rigor_gyro.core.balls import decimal_bounds, exact_fraction, stored_hull
    with working_precision(128):
        for x in (arb(fmpq(-508, 3), fmpq(1, 10 ** 14)), arb(fmpq(508, 3), fmpq(1, 10 ** 14)), arb(0, fmpq(1, 7)),
                  arb(fmpq(-1, 3), fmpq(1, 10 ** 30))):
            lo, hi = decimal_bounds(x)
            h = stored_hull(x)
            assert h.is_finite() and h.contains(x)
            a, b = (arb(fmpq(*Fraction(t).as_integer_ratio())) for t in (lo, hi))
            assert h.contains(a) and h.contains(b)                        # the whole stored interval
            width = exact_fraction(h.upper()) - exact_fraction(h.lower())
            assert width <= (Fraction(hi) - Fraction(lo)) * (1 + Fraction(1, 2 ** 20))   # and hardly more
        nan = arb("nan")
        assert stored_hull(nan) is nan


def test_sqrt_of_a_nonnegative_quantity_whose_ball_reaches_below_zero():
    """sqrt_of_nonnegative: Arb's sqrt where the ball is certainly >= 0; [0, sqrt(upper)] where it
    reaches below 0 with its upper end >= 0 (the caller knows the value is >= 0); NaN (deciding
    nothing) for a certainly negative or non-finite ball."""
    from rigor_gyro.core.balls import sqrt_of_nonnegative
    with working_precision(64):
        assert sqrt_of_nonnegative(arb(4)) == 2
        s = sqrt_of_nonnegative(arb("0.25", "0.25"))                   # [0, 0.5]: certainly >= 0
        assert s.is_finite() and s.contains(0) and s.contains(arb("0.5").sqrt()) and s.upper() < arb("0.7072")
        t = sqrt_of_nonnegative(arb(0, arb("1e-10")))                  # [-1e-10, 1e-10]
        assert t.is_finite() and t.contains(0) and t.contains(arb("1e-5")) and t.lower() > -arb("1e-13")   # union rounding
        assert t.upper() < arb("1.0001e-5")
        u = sqrt_of_nonnegative(arb("0.25").union(arb("0.36")))         # certainly >= 0: Arb's sqrt, not [0, ..]
        assert u.is_finite() and u.contains(arb("0.5")) and u.contains(arb("0.6")) and u.lower() > arb("0.4999")
        for bad in (arb(-1, arb("0.5")), arb("nan"), arb("inf"), arb(0, arb("inf"))):
            assert sqrt_of_nonnegative(bad).is_nan()


def test_relative_width_is_decided_with_a_one_percent_margin():
    """rel_width_at_most(x, tol): 2 rad(x) <= 0.99 tol |x| certainly (the 1 % leaves room for the
    decimals' outward rounding); False for a ball through 0 or a non-finite one."""
    from rigor_gyro.core.balls import rel_width_at_most
    with working_precision(64):
        for sign in (1, -1):
            x = arb(sign, arb("1e-6"))                                  # width 2e-6 (radius rounded up)
            assert rel_width_at_most(x, "3e-6") and rel_width_at_most(x, "2.03e-6")
            assert not rel_width_at_most(x, "2e-6") and not rel_width_at_most(x, "2.01e-6")
        assert not rel_width_at_most(arb(0, arb("1e-6")), "1e6") and not rel_width_at_most(arb(0), "1")
        big = arb(100, arb("1e-4"))                                     # relative width 2e-6 at |x| = 100
        assert rel_width_at_most(big, "3e-6") and not rel_width_at_most(big, "1.9e-6")
        assert not rel_width_at_most(arb("nan"), "1") and not rel_width_at_most(arb("inf"), "1")
        assert rel_width_at_most(arb(5), "1e-30")                       # an exact ball has width 0


def test_precision_and_series_length_are_checked_and_restored():
    from flint import ctx
    from rigor_gyro.core.balls import MAX_PREC, MIN_PREC, check_precision, series_length
    from rigor_gyro.core.exact import ParameterError
    assert check_precision(MIN_PREC) == MIN_PREC and check_precision(MAX_PREC) == MAX_PREC
    for bad in (MIN_PREC - 1, MAX_PREC + 1, True, 64.0, "64"):
        with pytest.raises(ParameterError, match=f"prec must be an integer number of bits from {MIN_PREC} to {MAX_PREC}"):
            check_precision(bad)
    with pytest.raises(ParameterError, match="maxprec must be"):
        check_precision(8, "maxprec")
    saved = ctx.cap
    with series_length(saved + 5) as n:
        assert n == saved + 5 and ctx.cap == saved + 5
    with series_length(1):
        assert ctx.cap == saved                                          # never lowered
    with pytest.raises(RuntimeError), series_length(saved + 7):
        raise RuntimeError
    assert ctx.cap == saved
    for bad in (0, -3, 2.5):
        with pytest.raises(ParameterError, match="series length must be a positive integer"):
            with series_length(bad):
                pass


def _floor_log10(q: Fraction) -> int:
    """floor(log10 |q|) by exact comparisons with powers of ten (the reference)."""
    q, e = abs(q), 0
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


@pytest.mark.parametrize("q", [Fraction(1), Fraction(10), Fraction(21, 2), Fraction(99, 10), Fraction(1, 10),
                               Fraction(105, 10), Fraction(11, 1), Fraction(10**20 - 1), Fraction(10**20),
                               Fraction(1, 10**30), Fraction(1, 10**30 - 1), Fraction(1, 10**30 + 1),
                               Fraction(3, 7), Fraction(-7, 3), Fraction(10**300 + 1, 3), Fraction(2, 10**300 + 7),
                               Fraction(2**1000, 3**600), Fraction(3**600, 2**1000), Fraction(123456789, 10**5),
                               Fraction(999999, 10**6), Fraction(10**6, 999999)])
def test_exponent10_is_floor_log10_exactly(q):
    from rigor_gyro.core.balls import exponent10
    assert exponent10(q) == _floor_log10(q)


def test_exponent10_just_around_every_power_of_ten():
    from rigor_gyro.core.balls import exponent10
    for e in range(-40, 41):
        p = Fraction(10) ** e
        for q in (p, p * (1 - Fraction(1, 10**25)), p * (1 + Fraction(1, 10**25)), p * Fraction(11, 10), p * Fraction(21, 2)):
            assert exponent10(q) == _floor_log10(q), q


def test_digits_follow_the_balls_accuracy_and_an_exact_balls_bits():
    from rigor_gyro.core.balls import MAX_DIGITS_OUT, _digits_for
    with working_precision(200):
        x = arb(fmpq(1, 3)) + arb(0, arb(2) ** -100)                 # about 98 bits of accuracy
        assert _digits_for(x) == int(x.rel_accuracy_bits() * 0.30103) + 3
        assert _digits_for(arb(fmpq(1, 3))) == int(arb(fmpq(1, 3)).rel_accuracy_bits() * 0.30103) + 3
        assert _digits_for(arb(0.5)) == 6                              # 1 bit: at least 6 digits
        assert _digits_for(arb(2) ** 100 + 1) == int(101 * 0.30103) + 3    # exact, 101 bits of mantissa
        assert _digits_for(arb(1, 0.1)) == 6                           # a wide ball: still 6
    with working_precision(20000):
        assert _digits_for(arb(fmpq(1, 3))) == MAX_DIGITS_OUT


def test_decimal_bounds_of_infinite_and_nan_balls():
    """Arb's infinite balls are [+-inf] and the points +-inf (a union with inf is [+-inf]): their
    bounds are the texts "-inf" and "+inf"; a NaN ball's are "nan"."""
    with working_precision(64):
        assert decimal_bounds(arb("nan")) == ("nan", "nan")
        for x in (arb(0, "inf"), arb("inf"), arb("-inf"), arb(1).union(arb("inf"))):
            assert decimal_bounds(x) == ("-inf", "+inf"), x


def test_exponent10_of_huge_numerators_and_denominators_is_exact_integer_arithmetic():
    """n and d of 400+ digits (a float of either overflows): every comparison stays in integers."""
    from rigor_gyro.core.balls import exponent10
    big = 10 ** 400
    for e in range(-12, 13):
        p = Fraction(10) ** e
        for q in (Fraction(big * p.numerator + 1, big * p.denominator), Fraction(big * p.numerator - 1, big * p.denominator),
                  Fraction(big * p.numerator * 3 + 7, big * p.denominator)):
            assert exponent10(q) == _floor_log10(q), (e, float(q))


def test_series_coefficients_pad_with_exact_zeros_of_the_series_type():
    """A constant gives itself and n - 1 exact zeros; a series whose last coefficients python-flint left out
    (zeros below its precision) is padded with exact zeros of its own type (arb or acb), to exactly n."""
    from flint import acb, acb_series, arb_series

    from rigor_gyro.core.balls import series_coefficients, series_length
    assert series_coefficients(arb(3), 4) == [3, 0, 0, 0] and len(series_coefficients(arb(3), 1)) == 1
    c = series_coefficients(acb(2, 1), 3)
    assert c[0] == acb(2, 1) and c[1:] == [0, 0] and all(isinstance(x, acb) for x in c)
    with series_length(6):
        for s, kind in ((arb_series([1, 2], prec=6), arb), (acb_series([acb(1, 1), 2], prec=6), acb)):
            got = series_coefficients(s, 5)
            assert len(got) == 5 and all(isinstance(x, kind) for x in got), kind
            assert got[1] == 2 and all(x == 0 and x.rad() == 0 for x in got[2:]), kind


def _slow(name, a, b=None):
    """The predicates' definitions through compare (the forms before their fast paths for plain arbs)."""
    from rigor_gyro.core.balls import ball
    if name == "le":
        x, y = ball(a), ball(b)
        return bool(x.is_finite() and y.is_finite() and x <= y)
    c = compare(a, 0 if b is None else b)
    return c == {"lt": -1, "gt": 1, "pos": 1, "neg": -1}[name]


_EDGE = [arb(0), arb(0, 1), arb(1), arb(-1), arb(1, 1), arb(-1, 1), arb(2, "0.5"), arb("nan"), arb("inf"),
         -arb("inf"), arb(0, "inf"), arb("1e-300", "1e-310"), arb("-1e-300", "2e-300")]


@given(st.integers(-50, 50), st.integers(0, 40), st.integers(-50, 50), st.integers(0, 40))
def test_the_fast_paths_of_the_predicates_agree_with_compare(n1, r1, n2, r2):
    # plain arbs take a fast path in certainly_lt/gt/le/positive/negative: the same verdict as compare's
    from rigor_gyro.core.balls import certainly_negative, certainly_positive
    pts = [arb(n1, r1 / 8), arb(n2, r2 / 8)] + _EDGE
    for a in pts:
        assert certainly_positive(a) == _slow("pos", a) and certainly_negative(a) == _slow("neg", a)
        for b in pts[:2] + [_EDGE[0], _EDGE[7]]:
            assert certainly_lt(a, b) == _slow("lt", a, b) and certainly_gt(a, b) == _slow("gt", a, b)
            assert certainly_le(a, b) == _slow("le", a, b) and certainly_le(b, a) == _slow("le", b, a)


def test_a_subclass_of_arb_takes_the_general_path():
    # a subclass may compare in its own way: the predicates go through compare, which converts it with ball()
    from rigor_gyro.core.balls import Quantity, certainly_positive
    q = Quantity(arb(1), exact=Fraction(1))
    assert certainly_positive(q) and certainly_lt(q, arb(2)) and not certainly_gt(q, 2)
    assert not certainly_positive(Quantity(arb(0, 1)))


def test_ball_key_is_the_exact_ball():
    # the memos' key: equal exactly for the same midpoint and radius, different for any other ball
    from rigor_gyro.core.balls import ball_key
    a = arb(1) / 3
    assert ball_key(a) == ball_key(arb(1) / 3) and all(type(v) is int for v in ball_key(a))
    for other in (a + arb(0, 2.0 ** -80), arb(1) / 3 * (1 + arb(2) ** -60), -a, arb(0), arb(0, 1)):
        assert ball_key(other) != ball_key(a)
    with working_precision(128):
        assert ball_key(arb(1) / 3) != ball_key(a)


def test_ball_key_remembers_a_ball_by_identity_only():
    # the remembered keys hold their balls: an equal ball that is another object gets the same key, and a new
    # ball (even at an address a freed one had) its own
    from rigor_gyro.core.balls import ball_key
    a = arb(2) / 7
    k = ball_key(a)
    assert ball_key(a) is k and ball_key(arb(2) / 7) == k
    keys = {ball_key(arb(j) / 7) for j in range(200)}          # 200 short-lived balls: 200 different keys
    assert len(keys) == 200


def test_a_ball_with_a_far_tiny_radius_keeps_its_accuracy_in_print():
    """A normal midpoint with a radius below 2^-2^20 (the far path): the printed ends were those of Arb's
    lower()/upper() at the working precision, [1 - 2^-53, 1 + 2^-52] for 1 +- 2^-2^21 (fuzz report 12: two roots
    1e-400 apart were stored as the same interval, and the checker rejected the honest certificate). The ends
    must contain the ball and be as tight as the digits asked for."""
    from fractions import Fraction
    from rigor_gyro.core.balls import decimal_bounds, quantity, working_precision
    with working_precision(53):
        x = arb(1) + arb(0, arb(2) ** -(2 ** 21))
        for digits in (5, 30, 400):
            lo, hi = decimal_bounds(x, digits)
            assert Fraction(lo) < 1 < Fraction(hi)
            assert Fraction(hi) - Fraction(lo) <= Fraction(3, 10 ** (digits - 1)), (digits, lo, hi)
        q = quantity(x)
        assert Fraction(q["hi"]) - Fraction(q["lo"]) < Fraction(1, 10 ** 3000)
    with working_precision(4096):
        y = arb(1) + arb(2) ** -1300 + arb(0, arb(2) ** -(2 ** 21))      # a midpoint off every short decimal
    with working_precision(53):
        lo, hi = decimal_bounds(y, 500)
        exact = 1 + Fraction(1, 2 ** 1300)
        assert Fraction(lo) < exact < Fraction(hi) and Fraction(hi) - Fraction(lo) < Fraction(1, 10 ** 498)
