"""Arb balls: working precision, certified predicates, escalation, outward-rounded decimals.

This is the only module that sets ``flint.ctx.prec`` and ``flint.ctx.cap`` and the only one that
compares balls with bare operators (a test greps for it). Everything else asks through the named
predicates below, and builds Taylor series through :func:`series_length` / :func:`series_coefficients`.

Guarantee: a predicate ``certainly_P(...)`` returns True only when P holds for every point of the
balls involved; False means "not proved" (P may still hold). Balls that are NaN or infinite never
decide anything. :func:`decimal_bounds` returns decimal strings ``lo <= x <= hi`` for every point x of
the ball (outward rounding, exact rational arithmetic; python-flint's ``str()`` is not used).

Precision: :func:`working_precision` and :func:`escalate` restore ``ctx.prec`` on every exit,
exceptions included; :func:`series_length` likewise restores ``ctx.cap``.

Series trap: python-flint silently cuts every ``arb_series`` / ``acb_series`` result to ``ctx.cap``
terms (default 10) whatever ``prec=`` the input had; a Taylor coefficient read past the cap is then
missing, and filling it with 0 makes an enclosure that is not rigorous. :func:`series_length` raises
the cap for the block, and :func:`series_coefficients` returns exactly n coefficients only when the
series' own ``prec`` covers them (trailing coefficients within ``prec`` that python-flint strips are
exact zeros); otherwise it raises :class:`SeriesTruncated`.

Fails when: never raises on wide balls; it reports "undecided" (None / False) instead.

Example:
    >>> from flint import arb
    >>> certainly_lt(arb(1), arb(2)), certainly_lt(arb(1, 2), arb(2)), certainly_ge(arb(1, 2), arb(2))
    (True, False, False)
    >>> compare(arb("nan"), arb(0)) is None
    True
    >>> lo, hi = decimal_bounds(arb(1).union(arb(2)))   # str() would print [+/- 2.01]
    >>> Fraction(lo) <= 1 and Fraction(hi) >= 2
    True
"""
from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable, Generic, Iterator, TypeVar

from flint import acb, acb_series, arb, arb_series, ctx, fmpq

from .errors import ParameterError
from .exact import parse_exact

__all__ = [
    "DEFAULT_PREC", "square", "DEFAULT_MAXPREC", "working_precision", "current_precision", "ball", "is_finite",
    "certainly_lt", "certainly_le", "certainly_gt", "certainly_ge", "certainly_positive",
    "certainly_negative", "certainly_nonzero", "possibly_zero", "compare", "contains",
    "overlaps", "certainly_within", "interval", "exact_fraction", "exponent10", "decimal_bounds", "is_far", "enclosure_text", "rational_text", "interval_text", "inward_interval_text",
    "width_text", "about_text", "Quantity", "as_quantity", "quantity", "stored_hull",
    "rel_width_at_most", "sqrt_of_nonnegative", "ball_key", "exact_endpoints", "exact_endpoints_fmpq", "Escalation", "escalate", "check_precision", "MIN_PREC", "MAX_PREC", "series_length", "series_coefficients", "SeriesTruncated",
]

DEFAULT_PREC = 64
DEFAULT_MAXPREC = 4096
#: the working precision is an integer number of bits in [MIN_PREC, MAX_PREC] (checked before any work)
MIN_PREC = 16
MAX_PREC = 32768
#: bits a computation may add to the working precision as guard digits (a claim's final quantities at
#: prec + 64, a checker's recomputation): :func:`working_precision` accepts up to MAX_PREC + this, so that
#: --maxprec 32768 itself stays usable (it stopped with exit 2 at 32768 + 64)
GUARD_ROOM = 1024

T = TypeVar("T")


@contextlib.contextmanager
def working_precision(prec: int) -> Iterator[int]:
    """Set the working precision to ``prec`` bits inside the block (MIN_PREC to MAX_PREC + GUARD_ROOM: a
    requested precision is checked against MAX_PREC by :func:`check_precision`, its guard bits may exceed it);
    always restored afterwards."""
    if isinstance(prec, bool) or not isinstance(prec, int) or not MIN_PREC <= prec <= MAX_PREC + GUARD_ROOM:
        raise ParameterError(f"precision must be an integer number of bits from {MIN_PREC} to {MAX_PREC} (plus at "
                             f"most {GUARD_ROOM} guard bits), got {prec!r}")
    saved = ctx.prec
    try:
        ctx.prec = prec
        yield prec
    finally:
        ctx.prec = saved


class SeriesTruncated(ArithmeticError):
    """A series came back shorter than the coefficients asked of it (``ctx.cap`` too small): a bug in
    the caller, never a result (see the series trap in the module docstring)."""


@contextlib.contextmanager
def series_length(n: int) -> Iterator[int]:
    """Inside the block, series operations keep at least ``n`` terms (``ctx.cap >= n``); restored
    afterwards, exceptions included."""
    if not isinstance(n, int) or n < 1:
        raise ParameterError(f"series length must be a positive integer, got {n!r}")
    saved = ctx.cap
    try:
        ctx.cap = max(saved, n)
        yield n
    finally:
        ctx.cap = saved


def series_coefficients(s, n: int) -> list:
    """Exactly the first ``n`` Taylor coefficients of the series ``s`` (an ``arb_series`` or
    ``acb_series``), or of a constant (ball) ``s`` (then the others are exactly 0).

    Guarantee: every returned coefficient is the series' coefficient; coefficients python-flint left
    out below ``s.prec`` are exact zeros. Fails when: ``s.prec < n`` (the series was cut short, e.g.
    by ``ctx.cap``): :class:`SeriesTruncated`."""
    if not isinstance(s, (arb_series, acb_series)):
        return [s] + [type(s)(0)] * (n - 1)
    if s.prec < n:
        raise SeriesTruncated(f"series of precision {s.prec} asked for {n} coefficients "
                              f"(ctx.cap = {ctx.cap}): wrap the computation in series_length({n})")
    c = list(s.coeffs())[:n]
    zero = arb(0) if isinstance(s, arb_series) else acb(0)
    return c + [zero] * (n - len(c))


def check_precision(prec: object, name: str = "prec") -> int:
    """``prec`` if it is an integer number of bits in [MIN_PREC, MAX_PREC]; ParameterError otherwise."""
    if isinstance(prec, bool) or not isinstance(prec, int) or not MIN_PREC <= prec <= MAX_PREC:
        raise ParameterError(f"{name} must be an integer number of bits from {MIN_PREC} to {MAX_PREC}, got {prec!r}")
    return prec


def current_precision() -> int:
    """The working precision in bits (read-only view of ``flint.ctx.prec``)."""
    return ctx.prec


def ball(x: object) -> arb:
    """The ball of an exact number at the current precision.

    Accepts ``arb`` (returned as is), ``Exact``, ``fmpq``, ``int``, ``Fraction`` or a decimal string;
    a Python ``float`` raises ParameterError (it is already rounded).
    """
    if type(x) is arb or isinstance(x, arb):
        return x
    if isinstance(x, fmpq):
        return arb(x)
    if isinstance(x, int) and not isinstance(x, bool):
        return arb(x)
    return parse_exact(x).ball()


def is_finite(x: arb) -> bool:
    """True when the ball is finite (not NaN, no infinite endpoint)."""
    return bool(x.is_finite())


def compare(a: object, b: object) -> int | None:
    """-1 if a < b certainly, 1 if a > b certainly, None if undecided (overlap, NaN or infinity).

    Equality of balls is never decided (two exact equal balls are reported as undecided too: a
    verdict must not rest on touching balls).
    """
    x = a if type(a) is arb else ball(a)
    y = b if type(b) is arb else ball(b)
    if not (x.is_finite() and y.is_finite()):
        return None
    if x < y:
        return -1
    if x > y:
        return 1
    return None


#: the exact 0 the sign predicates compare with (exact at every precision)
_ZERO = arb(0)

# The predicates below take a fast path for two plain ``arb`` (not a subclass, which may define its own
# comparisons): the same finiteness tests and the same comparison as :func:`compare`, without its
# conversions (they are a measurable part of a proof's time: issue 41).


def certainly_lt(a: object, b: object) -> bool:
    if type(a) is arb and type(b) is arb:
        return bool(a.is_finite() and b.is_finite() and a < b)
    return compare(a, b) == -1


def certainly_gt(a: object, b: object) -> bool:
    if type(a) is arb and type(b) is arb:
        return bool(a.is_finite() and b.is_finite() and a > b)
    return compare(a, b) == 1


def certainly_le(a: object, b: object) -> bool:
    """a <= b for every point; touching exact balls count (e.g. exact 1 <= exact 1)."""
    x = a if type(a) is arb else ball(a)
    y = b if type(b) is arb else ball(b)
    return bool(x.is_finite() and y.is_finite() and x <= y)


def certainly_ge(a: object, b: object) -> bool:
    return certainly_le(b, a)


def certainly_positive(x: object) -> bool:
    if type(x) is arb:
        return bool(x.is_finite() and x > _ZERO)
    return certainly_gt(x, 0)


def certainly_negative(x: object) -> bool:
    if type(x) is arb:
        return bool(x.is_finite() and x < _ZERO)
    return certainly_lt(x, 0)


def certainly_nonzero(x: object) -> bool:
    return compare(x, 0) is not None


def possibly_zero(x: object) -> bool:
    """True unless the ball certainly excludes zero (NaN and infinite balls possibly contain it)."""
    return not certainly_nonzero(x)


def contains(outer: arb, inner: object) -> bool:
    """True when every point of ``inner`` lies in ``outer`` (both finite)."""
    y = ball(inner)
    return bool(outer.is_finite() and y.is_finite() and outer.contains(y))


def overlaps(a: arb, b: arb) -> bool:
    return bool(a.overlaps(b))


def certainly_within(x: object, lo: object, hi: object) -> bool:
    """lo < x < hi for every point of x (strict)."""
    return certainly_lt(lo, x) and certainly_lt(x, hi)


def interval(lo: object, hi: object) -> arb:
    """A ball containing [lo, hi] (Arb's union at the current precision). Its radius is rounded up, so
    its lower end may sit a little below ``lo`` (a few units in the radius's last place); and printed
    with few digits it may look far wider than it is (``[+/- 1.01]`` for [1/3, 1] at 53 bits)."""
    return ball(lo).union(ball(hi))


def sqrt_of_nonnegative(x: arb) -> arb:
    """sqrt of a quantity the caller knows to be >= 0 (a square, a sum of squares) whose ball may
    reach below 0: the ball [0, sqrt(upper)] then, instead of Arb's NaN. Requires: the exact value
    is >= 0 for every point the ball stands for (otherwise the result is not an enclosure)."""
    if not x.is_finite():
        return arb("nan")
    if x >= 0:
        return x.sqrt()
    up = x.upper()
    return arb(0).union(up.sqrt()) if up >= 0 else arb("nan")


def rel_width_at_most(x: arb, tol: object) -> bool:
    """True when the ball's width 2*rad is certainly <= tol * |x| (relative width), x nonzero, with a
    margin of 1/100 of tol for the outward rounding of its printed decimals (so the decimal interval a
    certificate stores also has relative width <= tol)."""
    if not x.is_finite() or possibly_zero(x):
        return False
    return certainly_le(2 * x.rad(), ball(tol) * x.abs_lower() * arb("0.99"))


# ---------------------------------------------------------------- decimal output, rounded outward

def exact_fraction(x: arb) -> Fraction:
    """The exact rational value of an exact (radius 0) finite ball such as ``x.lower()``."""
    man, exp = x.man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def exponent10(q: Fraction) -> int:
    """floor(log10(|q|)) for a rational q != 0, in exact (integer) arithmetic (no float or Decimal
    rounding: a value within 10^-200 of a power of ten still gets its own decade)."""
    return _exponent10_int(abs(q.numerator), q.denominator)


_exponent10 = exponent10


def _exponent10_int(n: int, d: int) -> int:
    """floor(log10(n / d)) for integers n, d > 0, exactly."""
    e = int((n.bit_length() - d.bit_length()) * 0.30102999566398120)
    # 10^e <= n/d < 10^(e+1), compared as integers
    while (d * 10 ** e > n) if e >= 0 else (d > n * 10 ** -e):
        e -= 1
    while (d * 10 ** (e + 1) <= n) if e + 1 >= 0 else (d <= n * 10 ** -(e + 1)):
        e += 1
    return e


def _round_decimal(q: Fraction | tuple[int, int], digits: int, mode: str) -> str:
    """q rounded to ``digits`` significant decimal digits: mode 'down', 'up' or 'nearest' (ties to
    even). ``q``: a Fraction, or (numerator, positive denominator) in any terms (the result depends on the
    value only: the decade, the floor and the remainder's ratio to the denominator). Exact integer
    arithmetic (no Fraction products: the certificate writes thousands)."""
    num, den = q if isinstance(q, tuple) else (q.numerator, q.denominator)
    if num == 0:
        return "0"
    e = _exponent10_int(abs(num), den)
    scale = digits - 1 - e
    # n = round(num * 10^scale / den) in the mode asked, by one integer division
    if scale >= 0:
        top, bottom = num * 10 ** scale, den
    else:
        top, bottom = num, den * 10 ** -scale
    n, r = divmod(top, bottom)              # floor; 0 <= r < bottom
    if r:
        if mode == "up":
            n += 1
        elif mode == "nearest":
            twice = 2 * r
            if twice > bottom or (twice == bottom and n % 2):
                n += 1
        elif mode != "down":
            raise ValueError(f"unknown rounding mode {mode!r}")
    return _format_scaled(n, scale)


def _format_scaled(n: int, scale: int) -> str:
    """The decimal string of n * 10**(-scale), plain when short, otherwise in e-notation."""
    if n == 0:
        return "0"
    sign = "-" if n < 0 else ""
    digits = str(abs(n)).rstrip("0")  # n has at most ~60 digits
    scale -= len(str(abs(n))) - len(digits)
    exponent = len(digits) - 1 - scale  # value = d.ddd * 10**exponent
    if -6 <= exponent <= 20:
        if scale <= 0:
            return sign + digits + "0" * (-scale)
        if scale >= len(digits):
            return sign + "0." + "0" * (scale - len(digits)) + digits
        return sign + digits[:-scale] + "." + digits[-scale:]
    mant = digits[0] + ("." + digits[1:] if len(digits) > 1 else "")
    return f"{sign}{mant}e{exponent:+d}"


def rational_text(q: Fraction, max_digits: int = 100) -> str:
    """An exact rational shown as what it is: its exact decimal when it terminates within ``max_digits``
    significant digits (1/5 -> "0.2", 3/40 -> "0.075", 1200 -> "1200"), otherwise the fraction "n/d"
    (1/3 -> "1/3"). Never through a float; :func:`~fractions.Fraction` reads either form back exactly."""
    q = Fraction(q)
    d, a, b = q.denominator, 0, 0
    while d % 2 == 0:
        d, a = d // 2, a + 1
    while d % 5 == 0:
        d, b = d // 5, b + 1
    if d == 1:
        scale = max(a, b)
        n = q.numerator * 10 ** scale // q.denominator          # exact: the denominator divides 10^scale
        if len(str(abs(n)).rstrip("0")) <= max_digits:
            return _format_scaled(n, scale)
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def interval_text(lo: Fraction, hi: Fraction, digits: int | None = None) -> tuple[str, str, bool]:
    """Decimals (l, h, rounded) with l <= lo <= hi <= h: each end exact when it has at most ``digits``
    significant digits, otherwise rounded outward to them (``rounded`` says whether any end was). The
    default ``digits`` resolves the width hi - lo to about 1/100 (at least 6 digits)."""
    lo, hi = Fraction(lo), Fraction(hi)
    if digits is None:
        top = max(abs(lo), abs(hi))
        digits = 6 if top == 0 or hi == lo else max(6, exponent10(top) - exponent10(hi - lo) + 3)
    l, h = _round_decimal(lo, digits, "down"), _round_decimal(hi, digits, "up")
    return l, h, Fraction(l) != lo or Fraction(h) != hi


def inward_interval_text(lo: Fraction, hi: Fraction, digits: int) -> tuple[str, str]:
    """Decimals (l, h) with lo <= l and h <= hi: each end rounded inward to ``digits`` significant digits
    (for an interval certified to lie inside a set). When [lo, hi] is narrower than the rounding, l > h:
    the caller checks before stating [l, h]."""
    return _round_decimal(Fraction(lo), digits, "up"), _round_decimal(Fraction(hi), digits, "down")


def width_text(w: Fraction) -> str:
    """A nonnegative exact width, rounded up to 3 significant digits (exact when it has at most 3)."""
    return _round_decimal(Fraction(w), 3, "up")


def about_text(q: Fraction, digits: int = 4) -> str:
    """An exact rational to ``digits`` significant digits, rounded to nearest (for fractions of a volume
    shown beside their exact value), exact when it has at most that many digits."""
    return _round_decimal(Fraction(q), digits, "nearest")


#: decimals are printed to the digits the ball supports (its accuracy + 3), up to this many
MAX_DIGITS_OUT = 4000


def _digits_for(x: arb) -> int:
    """The significant digits a ball supports, plus three: its relative accuracy, or for an exact ball
    the bits of its midpoint (an exact ball prints to its precision, not forever)."""
    bits = x.rel_accuracy_bits() if not x.rad().is_zero() else max(int(x.bits()), 1)
    return max(6, min(MAX_DIGITS_OUT, int(bits * 0.30103) + 3))


def ball_key(x: arb) -> tuple[int, int, int, int]:
    """An exact key of a finite ball for a memo: its midpoint's and its radius's (mantissa, exponent), as Python
    ints. Two balls get the same key exactly when they are the same ball (Arb's (mantissa, exponent) pairs are
    canonical). Python ints rather than the fmpz that ``man_exp`` returns: a dict hashes its key at every
    lookup, and python-flint hashes an fmpz by converting it to an int each time (those hashes were about 3% of
    the instructions of a cold proof of the three papers: issue 41). The keys of the last few ball objects are
    remembered by identity (an arb is immutable, and the entry holds the object, so its id is not reused while
    remembered): a chain row asks the key of one ball several times."""
    hit = _KEYS.get(id(x))
    if hit is not None and hit[0] is x:
        return hit[1]
    m, e = x.mid().man_exp()
    rm, re = x.rad().man_exp()
    key = (int(m), int(e), int(rm), int(re))
    if len(_KEYS) >= 64:
        _KEYS.clear()
    _KEYS[id(x)] = (x, key)
    return key


#: ball_key's last keys: id -> (the ball object, its key)
_KEYS: dict[int, tuple] = {}


def exact_endpoints(x: arb) -> tuple[Fraction, Fraction]:
    """The exact rational endpoints mid - rad and mid + rad of a finite ball (no rounding at all,
    whatever the bits of the midpoint and the exponent of the radius)."""
    mid, rad = exact_fraction(x.mid()), exact_fraction(arb(x.rad()))
    return mid - rad, mid + rad


def exact_endpoint_integers(x: arb) -> tuple[int, int, int, int]:
    """(ln, ld, hn, hd): the exact ends of a finite ball, mid - rad = ln / ld and mid + rad = hn / hd, with
    ld = hd a power of two (not reduced to lowest terms: compare them by cross-multiplication), from the
    ball's exact midpoint and radius (:func:`ball_key`) in Python integers (no Fraction, no gcd)."""
    m, e, rm, re = ball_key(x)
    if not rm:
        re = e
    elif not m:
        e = re
    E = min(e, re)
    mid, rad = m << (e - E), rm << (re - E)
    if E >= 0:
        return (mid - rad) << E, 1, (mid + rad) << E, 1
    return mid - rad, 1 << -E, mid + rad, 1 << -E


def exact_endpoints_fmpq(x: arb) -> tuple[fmpq, fmpq]:
    """:func:`exact_endpoints` as flint rationals (the same exact numbers; C arithmetic, several times faster
    than Fraction where a loop compares many of them)."""
    mid, rad = _fmpq_exact(x.mid()), _fmpq_exact(arb(x.rad()))
    return mid - rad, mid + rad


def _fmpq_exact(x: arb) -> fmpq:
    man, exp = x.man_exp()
    man, exp = int(man), int(exp)
    return fmpq(man * 2**exp) if exp >= 0 else fmpq(man, 2**-exp)


def _endpoints(x: arb) -> tuple[Fraction | None, Fraction | None]:
    """Exact endpoints of x, None for an infinite end."""
    if x.is_finite():
        return exact_endpoints(x)
    lo, hi = x.lower(), x.upper()
    return (exact_fraction(lo) if lo.is_finite() else None), (exact_fraction(hi) if hi.is_finite() else None)


#: the largest decimal exponent a certificate stores (core.stored reads exponents of up to 6 digits): a far
#: value beyond it is printed as the bound 1e-999999 or 1e+999999 (or 0, or infinity) on its side
STORED_EXPONENT = 999999
#: binary exponents beyond +-2^20 (about 10^+-315653) are printed from the ball's own exponent
#: (:func:`_far_round`): the exact rational path would need 10^e with e in the millions (minutes of work)
FAR_EXPONENT = 2 ** 20
#: bits per decimal digit (log2 10 = 3.32, rounded up) of the precision a far ball's ends are taken at
FAR_END_BITS_PER_DIGIT = 4


def is_far(x: arb) -> bool:
    """Whether a finite ball is printed from its own exponent (:data:`FAR_EXPONENT`): its exact endpoints
    would have more than a million bits."""
    return x.is_finite() and _far(x)


def _far(x: arb) -> bool:
    """Whether a finite ball's midpoint or radius has a binary exponent beyond +-FAR_EXPONENT (cheap: the
    exponents only; exact zero is never far)."""
    for v in (x.mid(), arb(x.rad())):
        if not v.is_zero():
            man, exp = v.man_exp()
            e = int(exp) + int(man).bit_length()
            if abs(e) > FAR_EXPONENT:
                return True
    return False


def _far_round(v: arb, digits: int, mode: str) -> str:
    """An exact nonzero ball value v (an endpoint, radius 0) far from 1 (:data:`FAR_EXPONENT`) to
    ``digits`` significant digits, rounded 'down' or 'up' (rigorously: the digits of |v| / 10^e, e an
    integer near log10 |v|, enclosed by Arb and rounded outward) or to 'nearest' (the enclosure's midpoint:
    for a midpoint or a description, not a bound). Beyond 10^+-999999 (:data:`STORED_EXPONENT`) the bound on
    the value's side: 0 or +-1e-999999 below, +-1e+999999 or infinity above. Work bounded by the digits and the
    exponent's length."""
    if v.is_zero():
        return "0"
    neg = certainly_negative(v)
    bits = 64 + 4 * digits + 2 * abs(int(v.mid().man_exp()[1])).bit_length()
    with working_precision(bits):
        mag = abs(v)
        e = math.floor(float((mag.log() / arb(10).log()).mid()))
        y = mag * arb(10) ** (digits - 1 - e)           # |v| 10^(digits-1-e), about 10^(digits-1)
        shrink = mode == "nearest" or (mode == "down") != neg      # the magnitude rounded to nearest or down
        if mode == "nearest":
            n = round(exact_fraction(y.mid()))
        elif shrink:
            n = math.floor(exact_fraction(y.lower()))
        else:
            n = math.ceil(exact_fraction(y.upper()))
    exponent = len(str(n)) - 1 - (digits - 1 - e) if n else -STORED_EXPONENT - 1      # of n 10^(e + 1 - digits)
    sign = "-" if neg else ""
    if exponent < -STORED_EXPONENT:     # |v| < 10^-999999: 0 or 10^-999999 (a bound the stored format reads)
        return "0" if shrink else f"{sign}1e-{STORED_EXPONENT}"
    if exponent > STORED_EXPONENT:      # |v| > 10^999999: 10^999999 or infinity
        return f"{sign}1e+{STORED_EXPONENT}" if shrink and mode != "nearest" else ("-inf" if neg else "+inf")
    return _format_scaled(-n if neg else n, digits - 1 - e)


def decimal_bounds(x: arb, digits: int | None = None) -> tuple[str, str]:
    """Decimal strings (lo, hi) with lo <= every point of x <= hi, rounded outward.

    ``digits`` significant digits (default: the ball's accuracy plus three). Infinite or NaN balls
    give ("-inf", "+inf") / ("nan", "nan"). A ball beyond 10^+-315653 (:data:`FAR_EXPONENT`) is rounded from
    its endpoints rounded outward at the working precision (:func:`_far_round`), not from its exact ones.
    """
    if x.is_nan():
        return "nan", "nan"
    exact = getattr(x, "exact", None)
    if exact is None and x.is_finite() and _far(x):
        d = digits or _digits_for(x)
        # the ends at a precision the digits need (Arb rounds lower() and upper() outward at the working
        # precision: at 53 bits a ball 1 +- 2^-2^21 printed as [1 - 2^-53, 1 + 2^-52], 10^380 times wider than its
        # accuracy, which no longer told two roots 1e-400 apart (fuzz report 12))
        with working_precision(max(current_precision(), FAR_END_BITS_PER_DIGIT * d + 64)):
            ends = x.lower(), x.upper()
        return tuple(_far_end(w, d, mode) for w, mode in zip(ends, ("down", "up")))
    if exact is not None:
        a = b = exact
    elif x.is_finite():             # the exact ends as integer ratios (no Fraction: rows and quantities by the hundred)
        ln, ld, hn, hd = exact_endpoint_integers(x)
        a, b = (ln, ld), (hn, hd)
    else:
        a, b = _endpoints(x)
    d = digits or (max(6, len(rational_text(exact))) if exact is not None else _digits_for(x))
    lo = _round_decimal(a, d, "down") if a is not None else "-inf"
    hi = _round_decimal(b, d, "up") if b is not None else "+inf"
    return lo, hi


def _far_end(w: arb, digits: int, mode: str) -> str:
    """An exact endpoint rounded to ``digits`` in ``mode``: exactly when its exponent is moderate, else
    :func:`_far_round`."""
    return _far_round(w, digits, mode) if _far(w) else _round_decimal(exact_fraction(w), digits, mode)


def enclosure_text(x: arb, digits: int = 12) -> str:
    """A ball as text for a reason or a report: ``[lo, hi]`` rounded outward to ``digits`` significant
    digits (one decimal when both ends print alike), ``[-inf, +inf]`` for an unbounded ball, ``nan``;
    never python-flint's ``[mid +/- rad]``, whose printing can collapse the ball."""
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def decimal_bounds_apart(x: arb, value: object, digits: int) -> tuple[str, str]:
    """:func:`decimal_bounds` with at least ``digits`` significant digits, and more when needed so that
    the printed interval excludes ``value`` whenever the ball certainly does (a modulus certainly > 1
    never prints as [1, 1.0001]). Up to the ball's own accuracy plus three digits."""
    v = ball(value)
    apart = certainly_lt(x, v) or certainly_gt(x, v)
    d, top = digits, max(digits, _digits_for(x))
    while True:
        lo, hi = decimal_bounds(x, d)
        if not apart or d >= top or _far(x) and not _far(v):     # far from a modest value: the digits show it
            return lo, hi
        if certainly_gt(x, v) and Fraction(lo) > exact_fraction(v) or certainly_lt(x, v) and Fraction(hi) < exact_fraction(v):
            return lo, hi
        d = min(top, 2 * d)


def square(x):
    """x * x. Trap: python-flint's ``x ** 2`` (any integer power) of a ball centred exactly at 0 with a positive
    radius is nan (``arb(0, 1e-10) ** 2``), where ``x * x`` is [+/- 1e-20]; elsewhere the two are the same ball,
    bit for bit (20,000 random balls at 53-256 bits). A nan decides nothing, so the power is sound but can leave
    a claim undecided, or make a checker's recomputation miss a stored enclosure (k = mu A0 exactly)."""
    return x * x


def quantity(x: arb, digits: int | None = None) -> dict[str, str]:
    """The certificate form of a ball: outward-rounded ``lo``/``hi``, and the midpoint (nearest) and
    half-width (rounded up, 3 digits) of the exact interval [x.lower(), x.upper()]."""
    lo, hi = decimal_bounds(x, digits)
    exact = getattr(x, "exact", None)
    if exact is not None and lo == hi:          # a searched decimal: the number itself, radius 0
        return {"lo": lo, "hi": hi, "mid": lo, "rad": "0"}
    if not x.is_finite():
        return {"lo": lo, "hi": hi, "mid": "nan" if x.is_nan() else "inf", "rad": "inf"}
    d = digits or _digits_for(x)
    if _far(x):
        return {"lo": lo, "hi": hi, "mid": _far_end(x.mid(), d, "nearest"), "rad": _far_end(arb(x.rad()), 3, "up")}
    ln, ld, hn, hd = exact_endpoint_integers(x)
    mid = _round_decimal((ln * hd + hn * ld, 2 * ld * hd), d, "nearest")
    rad = _round_decimal((hn * ld - ln * hd, 2 * ld * hd), 3, "up")
    return {"lo": lo, "hi": hi, "mid": mid, "rad": rad}


class Quantity(arb):
    """A certified quantity: the arb ball itself (every arithmetic and predicate works on it; the results
    are plain arbs) that shows its certified digits, not python-flint's default 53 bits.

    ``str``/``repr`` print the ball to the digits its own accuracy supports, as ``[mid +/- rad]`` from
    Arb's ``arb_get_str``, whose printed ball contains the ball (a radius of 8e-79 prints as such, where
    ``str(arb)`` at the default precision prints 17 digits and a radius of 8e-19). A decimal chosen by a
    search (``exact``, an exact rational: the ball then encloses it at the precision it was made at) is
    that number exactly: printed as its exact decimal, without a radius, and stored so in certificates
    (:func:`quantity`)."""

    def __init__(self, x: object, exact: Fraction | None = None):
        super().__init__(x)
        self.exact = None if exact is None else Fraction(exact)

    @classmethod
    def of_exact(cls, q: Fraction) -> "Quantity":
        """The exact rational q (a searched decimal) as a quantity: a ball containing q at the current
        precision, that shows and stores q exactly."""
        q = Fraction(q)
        return cls(arb(fmpq(q.numerator, q.denominator)), exact=q)

    def text(self) -> str:
        if self.exact is not None:
            return rational_text(self.exact)
        if not self.is_finite():
            return arb.str(self)
        return arb.str(self, _digits_for(self) - 1, radius=True)

    __str__ = text

    def __repr__(self) -> str:
        return self.text()


def as_quantity(x: object) -> object:
    """``x`` as a :class:`Quantity` when it is an arb (anything else unchanged)."""
    return x if isinstance(x, Quantity) or not isinstance(x, arb) else Quantity(x)


def stored_hull(x: arb) -> arb:
    """A ball containing the certificate's decimal interval [lo, hi] of ``x`` (:func:`quantity`).

    Use: a quantity derived from ``stored_hull(x)`` contains whatever a checker derives from any value
    in the stored interval of x, not only from values in the ball x (the decimals are rounded outward,
    so a checker's own enclosure of x may lie in that slack and still be confirmed). Non-finite balls
    are returned unchanged."""
    if not x.is_finite():
        return x
    lo, hi = decimal_bounds(x)
    a, b = Fraction(lo), Fraction(hi)
    return interval(arb(fmpq(a.numerator, a.denominator)), arb(fmpq(b.numerator, b.denominator)))


# ---------------------------------------------------------------- precision escalation

@dataclass
class Escalation(Generic[T]):
    """The outcome of :func:`escalate`: the last result, the precision it was computed at, whether
    ``done`` accepted it, and every precision tried."""

    result: T
    prec: int
    done: bool
    tried: list[int] = field(default_factory=list)


def escalate(attempt: Callable[[int], T], done: Callable[[T], bool], *, prec: int = DEFAULT_PREC,
             maxprec: int = DEFAULT_MAXPREC) -> Escalation[T]:
    """Run ``attempt(p)`` at p = prec, 2 prec, 4 prec, ... <= maxprec until ``done(result)``.

    Guarantee: returns the first accepted result with the precision it needed, or the result at the
    highest precision tried with ``done=False`` (the caller reports inconclusive and suggests a
    higher ``maxprec``). ``ctx.prec`` is restored on every exit.
    """
    check_precision(prec, "prec")
    check_precision(maxprec, "maxprec")
    if maxprec < prec:
        raise ParameterError(f"maxprec ({maxprec}) must be >= prec ({prec})")
    p, tried = prec, []
    while True:
        with working_precision(p):
            result = attempt(p)
        tried.append(p)
        if done(result):
            return Escalation(result, p, True, tried)
        if 2 * p > maxprec:
            return Escalation(result, p, False, tried)
        p *= 2

