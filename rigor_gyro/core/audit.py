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

from decimal import ROUND_HALF_EVEN, Decimal
from fractions import Fraction

from flint import arb, fmpq

from .balls import certainly_gt, certainly_le
from .outcome import AuditStatus

__all__ = ["audit_printed", "agreeing_digits", "half_unit"]


def half_unit(printed: str) -> Fraction:
    """Half a unit in the last printed place of a decimal string ("41.4" -> 1/20)."""
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
    """(status, note) for a printed decimal against a certified ball; the note gives the digits."""
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
    certainly a correct rounding of ``value`` at that many digits (0 if none)."""
    dec = Decimal(printed.strip())
    total = _sig_digits(printed)
    best = 0
    for d in range(1, total + 1):
        if dec == 0:
            break
        shift = dec.adjusted() - d + 1          # exponent of the last kept digit
        rounded = dec.quantize(Decimal(1).scaleb(shift), rounding=ROUND_HALF_EVEN)
        half = Fraction(1, 2) * Fraction(10) ** shift
        if _correct_rounding(Fraction(rounded), half, value) is AuditStatus.AGREES:
            best = d
    return best
