"""Audit of printed numbers: is the paper's number a correct rounding of the certified value?

Guarantee: :func:`audit_printed` says ``agrees`` only when every point of the certified ball rounds
to the printed number at the printed number of decimals (|v - printed| <= half a unit in its last
place), ``disagrees`` only when no point does, ``undecided`` otherwise (raise the precision).
:func:`agreeing_digits` is the largest number of significant digits d (up to the printed ones) at
which the printed number, rounded to d digits, is certainly a correct rounding of the value.

Example:
    >>> from flint import arb, fmpq
    >>> audit_printed("41.4", arb(fmpq(41412, 1000)))[0].value
    'agrees'
    >>> audit_printed("41.4", arb(fmpq(41460, 1000)))[0].value
    'disagrees'
    >>> agreeing_digits("0.589168", arb(fmpq(589210, 1000000)))
    4
"""
from __future__ import annotations

import difflib
import functools
import re
from decimal import Decimal
from fractions import Fraction

from flint import arb, ctx, fmpq

from .balls import ball_key, certainly_gt, certainly_le, exact_endpoint_integers
from .errors import SceneError
from .outcome import AuditStatus

__all__ = ["audit_printed", "printed_status", "agreeing_digits", "half_unit", "check_printed", "NUMBER", "TEXT", "numbers", "keys",
           "PRINTED_NUMBER"]

#: a number as a paper prints it: optional sign, ASCII digits, a point, an exponent; at most 60 characters
_PRINTED = re.compile(r"^[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]{1,3})?$", re.ASCII)
PRINTED_NUMBER = _PRINTED
NUMBER = "number"
TEXT = "text"


def numbers(n: int, blank_ok: bool = False) -> tuple:
    """Schema: a list of at most n printed numbers ("" allowed where the paper prints none, if blank_ok)."""
    return ("list", n, blank_ok)


def keys(allowed, spec) -> tuple:
    """Schema: a table whose keys come from ``allowed`` (a set, or a regex string), each value of ``spec``."""
    return ("keys", allowed, spec)


def check_printed(table: object, schema: dict, where: str = "[paper]") -> None:
    """Check the scene's ``[paper]`` table against a kind's schema before anything is computed.

    Fails when: a key is unknown (with a did-you-mean), a printed number is not a decimal string
    (TOML floats included), a list is too long or a table has the wrong shape: :class:`SceneError`
    naming the key and what is allowed (CLI exit 2)."""
    _check(table, schema, where)


def _check(value: object, spec, where: str) -> None:
    if isinstance(spec, dict):
        if not isinstance(value, dict):
            raise SceneError(f"{where} must be a table with keys from {sorted(spec)}, got {type(value).__name__}")
        for k, v in value.items():
            if k not in spec:
                close = difflib.get_close_matches(k, list(spec), n=1, cutoff=0.6)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise SceneError(f"{where}: unknown key {k!r}{hint}; allowed: {', '.join(sorted(spec))}")
            _check(v, spec[k], f"{where} {k}")
        return
    if spec == NUMBER:
        if not (isinstance(value, str) and len(value) <= 60 and _PRINTED.match(value.strip())):
            raise SceneError(f"{where} = {value!r}: a printed number is a quoted decimal such as \"0.0124\" "
                             "(at most 60 characters)")
        return
    if spec == TEXT:
        if not (isinstance(value, str) and len(value) <= 1000):
            raise SceneError(f"{where} = {value!r}: expected a quoted text of at most 1000 characters")
        return
    tag = spec[0]
    if tag == "list":
        _, n, blank_ok = spec
        if not isinstance(value, list) or len(value) > n:
            raise SceneError(f"{where}: expected a list of at most {n} quoted printed numbers, got {value!r}"[:300])
        for i, x in enumerate(value):
            if not (blank_ok and x == ""):
                _check(x, NUMBER, f"{where}[{i}]")
        return
    if tag == "keys":
        _, allowed, sub = spec
        if not isinstance(value, dict):
            raise SceneError(f"{where} must be a table, got {type(value).__name__}")
        for k, v in value.items():
            ok = re.fullmatch(allowed, k) if isinstance(allowed, str) else k in allowed
            if not ok:
                shown = allowed if isinstance(allowed, str) else ", ".join(sorted(allowed))
                raise SceneError(f"{where}: key {k!r} is not one the paper has; allowed: {shown}"[:400])
            _check(v, sub, f"{where} {k}")
        return
    raise AssertionError(f"bad schema {spec!r}")


@functools.lru_cache(maxsize=4096)
def half_unit(printed: str) -> Fraction:
    """Half a unit in the last printed place of a decimal string ("41.4" -> 1/20); memoised (exact)."""
    exp = Decimal(printed.strip()).as_tuple().exponent
    return Fraction(1, 2) * Fraction(10) ** exp


def _q(x: Fraction) -> arb:
    return arb(fmpq(x.numerator, x.denominator))


def _correct_rounding(printed: Fraction, half: Fraction, value: arb) -> AuditStatus:
    dev = abs(value - _q(printed))
    if certainly_le(dev, _q(half)):
        return AuditStatus.AGREES
    if certainly_gt(dev, _q(half)):
        return AuditStatus.DISAGREES
    return AuditStatus.UNDECIDED


def audit_printed(printed: str, value: arb) -> tuple[AuditStatus, str]:
    """(status, note) for a printed decimal against a certified ball; the note gives the digits. Memoised
    for a finite ball by (print, the ball's exact midpoint and radius, the working precision): the result is
    a function of these (the audit of a row and its classification ask the same question)."""
    if not value.is_finite():
        return _audit_printed(printed, value)
    key = (printed, ball_key(value), ctx.prec)
    hit = _AUDITED.get(key)
    if hit is None:
        if len(_AUDITED) > 4096:
            _AUDITED.clear()
        hit = _AUDITED[key] = _audit_printed(printed, value)
    return hit


_AUDITED: dict = {}


def printed_status(printed: str, value: arb) -> AuditStatus:
    """The status :func:`audit_printed` gives, without its note (no digit count): for a search that only
    asks whether a value gives the print (the same exact comparison)."""
    return _correct_rounding(Fraction(printed.strip()), half_unit(printed), value)


def _audit_printed(printed: str, value: arb) -> tuple[AuditStatus, str]:
    """:func:`audit_printed` without its memo."""
    p = Fraction(printed.strip())
    status = _correct_rounding(p, half_unit(printed), value)
    d = agreeing_digits(printed, value)
    total = _sig_digits(printed)
    note = f"agrees to {d} of {total} significant digits" if d < total else f"all {total} printed digits correct"
    return status, note


def _sig_digits(printed: str) -> int:
    return len(Decimal(printed.strip()).as_tuple().digits)


def agreeing_digits(printed: str, value: arb) -> int:
    """Largest d <= printed significant digits such that printed, rounded to d significant digits, is
    certainly a correct rounding of ``value`` at that many digits (0 if none). Exact integer arithmetic."""
    sign, digs, exp = Decimal(printed.strip()).as_tuple()
    total = len(digs)
    M = int("".join(map(str, digs)) or "0")
    if M == 0 or not value.is_finite():
        return 0
    ln, ld, hn, hd = _endpoint_integers(value)   # the ball's exact ends: each test is integer comparisons
    adjusted = exp + total - 1
    best = 0
    for d in range(1, total + 1):
        k = total - d                               # digits dropped: the last kept digit is at 10^(exp + k)
        if k:
            p10 = 10 ** k
            r, rem = divmod(M, p10)
            twice = 2 * rem
            if twice > p10 or (twice == p10 and r % 2):
                r += 1                              # ROUND_HALF_EVEN, as Decimal.quantize
        else:
            r = M
        r = -r if sign else r
        # rounded = r 10^shift, half = 5 10^(shift-1): within half a unit <=> 10 r - 5 <= 10 x / 10^shift <= 10 r + 5
        e = adjusted - d                            # shift - 1
        if e >= 0:
            scale = 10 ** e
            ok = (10 * r - 5) * scale * ld <= ln and hn <= (10 * r + 5) * scale * hd
        else:
            scale = 10 ** (-e)
            ok = (10 * r - 5) * ld <= ln * scale and hn * scale <= (10 * r + 5) * hd
        if ok:
            best = d
    return best


_ENDS: dict = {}


def _endpoint_integers(value: arb) -> tuple[int, int, int, int]:
    """(ln, ld, hn, hd) with the exact ends of a finite ball lo = ln/ld, hi = hn/hd, memoised by the
    ball's exact midpoint and radius (the classifier asks the same value about many readings)."""
    key = ball_key(value)
    hit = _ENDS.get(key)
    if hit is None:
        if len(_ENDS) > 4096:
            _ENDS.clear()
        hit = _ENDS[key] = exact_endpoint_integers(value)
    return hit
