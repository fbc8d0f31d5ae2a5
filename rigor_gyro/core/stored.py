"""Stored enclosures read back exactly: the decimal ``[lo, hi]`` of a certificate as rationals.

A certificate stores every enclosure as outward-rounded decimal strings. A checker reads them back
as exact rationals (never floats) and compares them with balls it computes itself.

Guarantee: :func:`interval` returns the exact rationals written; :func:`encloses` is True only when
every point of the ball lies in the stored interval (exact comparison of the ball's endpoints);
:func:`as_ball` is a ball containing the whole stored interval at the current precision.
Fails when: a string is not a finite decimal or fraction: ValueError (the checker reports the
certificate's data as uncheckable).
"""
from __future__ import annotations

import re
from fractions import Fraction

from flint import arb, fmpq, fmpz

from .balls import exact_endpoints

__all__ = ["number", "interval", "encloses", "as_ball", "fmpq_of", "exact_text", "pieces_text", "ball_text"]


#: a stored number: a decimal (exponent within +-999999: a stiff multiplier is 1e-55701) or an exact p/q (dyadics at high precision have
#: many digits), at most 20000 characters; anything else is rejected before any arithmetic
_STORED = re.compile(r"^-?[0-9]+(?:\.[0-9]+)?(?:e[+-]?[0-9]{1,6})?$|^-?[0-9]+/[0-9]+$", re.ASCII)


def number(text: str) -> Fraction:
    """A stored decimal (or ``p/q``) as an exact rational; ValueError for anything else.

    Digits are read by FLINT, not by ``int``: Python refuses to convert more than 4300 digits
    (``sys.set_int_max_str_digits``), and the dyadic pieces of a certificate at 16384 bits have more."""
    if not isinstance(text, str) or len(text) > 20000 or not _STORED.match(text.strip()):
        raise ValueError(f"not a finite stored number: {str(text)[:40]!r}")
    s = text.strip()
    if "/" in s:
        p, q = s.split("/")
        den = int(fmpz(q))
        if den == 0:
            raise ValueError(f"a stored fraction with a zero denominator: {text[:40]!r}")
        return Fraction(int(fmpz(p)), den)
    mant, _, exp = s.partition("e")
    whole, _, frac = mant.partition(".")
    n, e = int(fmpz(whole + frac)), int(exp or 0) - len(frac)
    return Fraction(n * 10 ** e) if e >= 0 else Fraction(n, 10 ** -e)


def interval(q) -> tuple[Fraction, Fraction]:
    """(lo, hi) of a stored quantity (a dict with lo/hi, or a [lo, hi] pair); ValueError if lo > hi."""
    lo, hi = (q["lo"], q["hi"]) if isinstance(q, dict) else q
    a, b = number(lo), number(hi)
    if a > b:
        raise ValueError(f"stored interval [{lo}, {hi}] has lo > hi")
    return a, b


def fmpq_of(x: Fraction) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def encloses(stored: tuple[Fraction, Fraction], x: arb) -> bool:
    """True when every point of the finite ball x lies in the stored [lo, hi] (exact)."""
    if not x.is_finite():
        return False
    lo, hi = exact_endpoints(x)
    return stored[0] <= lo and hi <= stored[1]


def meets(stored: tuple[Fraction, Fraction], x: arb) -> bool:
    """True when the finite ball x and the stored [lo, hi] share a point (exact). Two enclosures of
    the same number always meet, whatever their precisions; a stored value that misses the
    checker's own enclosure cannot contain the number."""
    if not x.is_finite():
        return False
    lo, hi = exact_endpoints(x)
    return stored[0] <= hi and lo <= stored[1]


def as_ball(stored: tuple[Fraction, Fraction]) -> arb:
    """A ball containing the whole stored interval, at the current precision."""
    return arb(fmpq_of(stored[0])).union(arb(fmpq_of(stored[1])))


def exact_text(x: Fraction) -> str:
    """An exact rational as text the checker reads back (``p/q`` or an integer); any number of digits
    (written by FLINT: Python's ``str`` of an int stops at 4300 digits)."""
    num = str(fmpz(x.numerator))
    return num if x.denominator == 1 else f"{num}/{fmpz(x.denominator)}"


def pieces_text(pairs) -> list[list[str]]:
    """Pieces (a, b) of balls as exact [lo, hi] texts covering them: [a.lower, b.upper]."""
    out = []
    for a, b in pairs:
        lo = exact_text(exact_endpoints(a)[0]) if a.is_finite() else "-inf"   # no stored number: rejected
        hi = exact_text(exact_endpoints(b)[1]) if b.is_finite() else "inf"
        out.append([lo, hi])
    return out


def ball_text(x) -> list[str]:
    """A finite ball as its exact [lo, hi] texts."""
    lo, hi = exact_endpoints(x)
    return [exact_text(lo), exact_text(hi)]
