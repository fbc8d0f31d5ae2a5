"""Which single edits of a printed decimal land it in a target interval (integer arithmetic only).

:func:`edits_into` undoes each edit a typesetter or a copyist makes (a wrong sign, a shifted decimal
point, two adjacent digits transposed, a digit dropped, a digit written twice, one digit replaced, two
digits replaced) and keeps the results that lie in the closed rational interval [lo, hi] (the paper
chain's window, :mod:`rigor_gyro.core.chain_classify`).

An edit counts as *evidence* only when it is not a chance fit:
* the print lies at least ``10 W`` (``factor`` W) from the intended number, W = hi - lo the window's width (an edit in
  the last digits, inside the noise of the computation, says nothing);
* the print keeps at least ``k + 1`` *constrained* significant digits, those whose place is at least W
  (k = the digits the edit changes: 1, or 2 for a transposition or a two-digit substitution, which
  needs 4): the digits left untouched must agree with the window, and enough of them do.

Guarantee: exact (rational and integer comparisons, no float); every Edit returned has its intended value in
[lo, hi] and passes both tests. Failure mode: none (an empty list when nothing fits); cost O(n^2 100) for
n printed digits (the two-digit substitutions), each candidate one integer comparison.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

from flint import fmpq

__all__ = ["Edit", "EDIT_CLASSES", "edits_into", "decimal_text"]

#: the edit classes, in the order a reading prefers them (simplest first)
EDIT_CLASSES = ("sign", "decimal-shift", "digit-substituted", "digits-transposed", "digit-doubled", "digit-dropped",
                "multi-digit-substituted")
_SHIFTS = (1, -1, 2, -2, 3, -3)


@dataclass(frozen=True)
class Edit:
    cls: str
    #: the print with the edit undone (a decimal text)
    intended: str
    #: what was edited, e.g. "4 for 1 at significant position 1"
    what: str


def decimal_text(negative: bool, digits: str, exponent: int) -> str:
    """The decimal -digits * 10^exponent (plain notation, trailing zeros kept)."""
    d = Decimal((1 if negative else 0, tuple(int(c) for c in digits), exponent))
    return format(d, "f")


def _constrained(n: int, exponent: int, wn: int, wd: int) -> int:
    """How many of the n significant digits (the last at place 10^exponent) have a place >= the width
    wn / wd (wd > 0), in integers."""
    if wn <= 0:
        return n
    for i in range(n):                              # the places decrease with i: the first one below ends it
        p = exponent + n - 1 - i
        if not (wd * 10 ** p >= wn if p >= 0 else wd >= wn * 10 ** -p):
            return i
    return n



def _q(x) -> fmpq:
    """An exact rational (int, Fraction or fmpq) as an fmpq: flint's C rationals are 4-5x faster than
    Fraction for the window arithmetic below."""
    return x if isinstance(x, fmpq) else fmpq(x.numerator, x.denominator)


def edits_into(printed: str, lo: Fraction | fmpq, hi: Fraction | fmpq, evidential: bool = True,
               factor: int = 10) -> list[Edit]:
    """Every evidential single edit of ``printed`` whose result lies in [lo, hi] (module docstring),
    in the order of :data:`EDIT_CLASSES`; with ``evidential=False`` every edit that lands there (candidates
    that need other evidence, such as a downstream row reproduced only with them). ``factor``: the distance
    test's multiple of W (10; 5 for a window of the print's rounding alone, slack 0, where a chance fit is
    rarer). Memoised (the chain builder asks the same question in each of its passes), keyed by the window's
    ends as integer numerators and denominators (an fmpq's hash costs about 3 us): do not mutate the list
    returned."""
    lo, hi = _q(lo), _q(hi)                       # exact rationals of either kind, compared as fmpq
    return _edits_into(printed, int(lo.p), int(lo.q), int(hi.p), int(hi.q), evidential, factor)


@functools.lru_cache(maxsize=4096)
def _parsed(printed: str) -> tuple:
    """The print's sign, significant digits (leading zeros dropped) and exponent, with what the loops read
    from them (memoised: the chain builder asks about one print against many windows)."""
    sign, tup, exp = Decimal(printed.strip()).as_tuple()
    digits = "".join(map(str, tup)).lstrip("0")
    n = len(digits)
    swapped = [(i, int(digits[:i] + digits[i + 1] + digits[i] + digits[i + 2:])) for i in range(n - 1)
               if digits[i] != digits[i + 1]]
    return (bool(sign), digits, exp, n, int(digits) if digits else 0, [10 ** (n - 1 - i) for i in range(n)],
            [int(ch) for ch in digits], swapped)


def _scaled(num: int, den: int, s: int) -> tuple[int, int]:
    """num / den * 10^s as (numerator, positive denominator), not reduced."""
    return (num * 10 ** s, den) if s >= 0 else (num, den * 10 ** -s)


def _ceil(num: int, den: int) -> int:
    return -(-num // den)


@functools.lru_cache(maxsize=16384)
def _edits_into(printed: str, lp: int, lq: int, hp: int, hq: int, evidential: bool, factor: int) -> list[Edit]:
    """:func:`edits_into` of the window [lp/lq, hp/hq] (lowest terms, lq, hq > 0). The window arithmetic is
    in Python integers (each rational test cross-multiplied by the positive denominators: the same exact
    comparisons as in rationals, several times cheaper)."""
    neg, digits, exp, n, M, place, dig, swapped = _parsed(printed)
    if not digits or lp * hq > hp * lq:
        return []
    sg = -1 if neg else 1
    v = sg * M                                     # the print in units of its last place, signed
    an, ad = _scaled(lp, lq, -exp)                 # the window [a, b] in those units
    bn, bd = _scaled(hp, hq, -exp)
    wn, wd = _scaled(hp * lq - lp * hq, lq * hq, -exp)     # its width Wu = b - a = wn / wd
    c = _constrained(n, exp, hp * lq - lp * hq, lq * hq)
    out: list[Edit] = []
    # the distance test |print - intended| >= factor W, in units of 10^(exp + e): an integer threshold
    thr = {-1: _ceil(factor * wn * 10, wd), 0: _ceil(factor * wn, wd)}
    win = {-1: (_ceil(an * 10, ad), (bn * 10) // bd), 0: (_ceil(an, ad), bn // bd),
           1: (_ceil(an, ad * 10), bn // (bd * 10))}

    def fits(V: int, k: int, e: int = 0) -> bool:
        """the signed count V of units 10^(exp + e) is in the window (and, when evidential, far enough);
        integers only"""
        A, B = win[e]
        if not A <= V <= B:
            return False
        dist, t = (abs(10 * v - V), thr[-1]) if e < 0 else (abs(v - V), thr[0]) if e == 0 else (abs(v - 10 * V), thr[0])
        if not evidential:
            return dist != 0
        return dist >= t and c >= k + 1

    def text(m: int, e: int = exp) -> str:
        return decimal_text(neg, str(m), e)
    if fits(-v, 1):
        out.append(Edit("sign", decimal_text(not neg, digits, exp), "the sign"))
    for k in _SHIFTS:
        q = v * 10 ** (k + 3)                       # 1000 v 10^k: a <= v 10^k <= b etc. times 1000 ad, bd, wd
        if 1000 * an <= q * ad and q * bd <= 1000 * bn and (not evidential or (
                abs(q - 1000 * v) * wd >= 1000 * factor * wn and c >= 2)) and q != 1000 * v:
            out.append(Edit("decimal-shift", decimal_text(neg, digits, exp + k),
                            f"the decimal point {abs(k)} place(s) {'right' if k > 0 else 'left'}"))
            break
    A, B = win[0]
    if neg:
        A, B = -B, -A                               # the window for the unsigned count M'
    for i in range(n):
        rest = M - place[i] * dig[i]
        lo_d, hi_d = -((rest - A) // place[i]), (B - rest) // place[i]
        for d in range(max(lo_d, 1 if i == 0 else 0), min(hi_d, 9) + 1):
            if d != dig[i] and fits(sg * (rest + d * place[i]), 1):
                out.append(Edit("digit-substituted", text(rest + d * place[i]),
                                f"{dig[i]} for {d} at significant position {i + 1}"))
    for i, m in swapped:                            # two adjacent (different) digits transposed
        if fits(sg * m, 2):
            out.append(Edit("digits-transposed", text(m), f"{digits[i]}{digits[i + 1]} for "
                            f"{digits[i + 1]}{digits[i]} at significant positions {i + 1}, {i + 2}"))
    # a dropped digit: the intended number has one more digit, inserted after position i (same decade)
    A1, B1 = win[-1]
    if neg:
        A1, B1 = -B1, -A1                           # the window for the unsigned count, one place finer
    for i in range(1, n - 1):                      # at least two digits shifted after the gap
        k = n - i                                  # the digits after the gap
        base = (M // 10 ** k) * 10 ** (k + 1) + M % 10 ** k
        for d in range(max(0, -((base - A1) // 10 ** k)), min(9, (B1 - base) // 10 ** k) + 1):
            m = base + d * 10 ** k
            if fits(sg * m, 1, -1):
                out.append(Edit("digit-dropped", text(m, exp - 1), f"the digit {d} left out after significant "
                                                                    f"position {i}"))
    # a doubled digit: the print writes one digit twice (the intended has one digit fewer)
    for i in range(1, n - 2):                      # at least two digits after the doubled one
        if digits[i] == digits[i - 1]:
            m = int(digits[:i] + digits[i + 1:])
            if fits(sg * m, 1, 1):
                out.append(Edit("digit-doubled", text(m, exp + 1), f"the digit {digits[i]} written twice"))
                break
    if (c >= 4 or not evidential) and not out:     # two digits only where no single edit fits
        for i in range(n):
            for j in range(i + 1, n):
                if evidential and place[j] * wd < factor * wn:   # each edited place above the noise (W)
                    continue
                rest = M - place[i] * dig[i] - place[j] * dig[j]
                # d1 with some d2 in 0..9 landing in [A, B]: A - 9 place[j] <= rest + d1 place[i] <= B
                d1_lo = max(1 if i == 0 else 0, -((rest + 9 * place[j] - A) // place[i]))
                for d1 in range(d1_lo, min(9, (B - rest) // place[i]) + 1):
                    if d1 == dig[i]:
                        continue
                    r1 = rest + d1 * place[i]
                    lo_d, hi_d = -((r1 - A) // place[j]), (B - r1) // place[j]
                    for d2 in range(max(lo_d, 0), min(hi_d, 9) + 1):
                        m = r1 + d2 * place[j]
                        if d2 != dig[j] and fits(sg * m, 2):
                            out.append(Edit("multi-digit-substituted", text(m),
                                            f"{dig[i]}, {dig[j]} for {d1}, {d2} at significant positions "
                                            f"{i + 1}, {j + 1}"))
    out.sort(key=lambda e: _ORDER[e.cls])
    return out


_ORDER = {c_: k for k, c_ in enumerate(EDIT_CLASSES)}
