"""core.digit_edits in integers (issue 41) decides exactly as its earlier fmpq implementation, kept here
verbatim as the reference: the same edits, in the same order, with the same texts, for random prints
against windows around them and around their edits (every class, both modes, both distance factors)."""
from __future__ import annotations

import random
from decimal import Decimal
from fractions import Fraction as F

from flint import fmpq

from rigor_gyro.core.digit_edits import EDIT_CLASSES, _SHIFTS, Edit, _edits_into, decimal_text

def _constrained(n: int, exponent: int, width: fmpq) -> int:
    """How many of the n significant digits (the last at place 10^exponent) have a place >= width."""
    if width <= 0:
        return n
    return sum(1 for i in range(n) if _TEN ** (exponent + n - 1 - i) >= width)


_TEN = fmpq(10)


_TEN = fmpq(10)


def _reference(printed: str, lp: int, lq: int, hp: int, hq: int, evidential: bool, factor: int) -> list[Edit]:
    """The fmpq implementation of core.digit_edits before issue 41 (verbatim)."""
    sign, tup, exp = Decimal(printed.strip()).as_tuple()
    digits = "".join(map(str, tup)).lstrip("0")
    lo, hi = fmpq(lp, lq), fmpq(hp, hq)
    if not digits or lo > hi:
        return []
    n, neg = len(digits), bool(sign)
    M = int(digits)
    sg = -1 if neg else 1
    v = sg * M                                     # the print in units of its last place, signed
    scale = _TEN ** -exp
    a, b = lo * scale, hi * scale                  # the window in those units
    Wu = b - a
    c = _constrained(n, exp, hi - lo)
    out: list[Edit] = []
    # the distance test |print - intended| >= factor W, in units of 10^(exp + e): an integer threshold
    thr = {e: int((factor * Wu * _TEN ** -e).ceil()) for e in (-1, 0, 1)}
    win = {e: (int((a * _TEN ** -e).ceil()), int((b * _TEN ** -e).floor())) for e in (-1, 0, 1)}

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
        q = v * _TEN ** k
        if a <= q <= b and (not evidential or (abs(q - v) >= factor * Wu and c >= 2)) and q != v:
            out.append(Edit("decimal-shift", decimal_text(neg, digits, exp + k),
                            f"the decimal point {abs(k)} place(s) {'right' if k > 0 else 'left'}"))
            break
    place = [10 ** (n - 1 - i) for i in range(n)]
    dig = [int(ch) for ch in digits]
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
    for i in range(n - 1):
        if digits[i] != digits[i + 1]:
            m = int(digits[:i] + digits[i + 1] + digits[i] + digits[i + 2:])
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
                if evidential and place[j] < factor * Wu:   # each edited place above the noise
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
    order = {c_: k for k, c_ in enumerate(EDIT_CLASSES)}
    out.sort(key=lambda e: order[e.cls])
    return out


def _cases(n: int, seed: int):
    rnd = random.Random(seed)
    for _ in range(n):
        nd, e = rnd.randint(1, 9), rnd.randint(-9, 4)
        m = rnd.randint(10 ** (nd - 1), 10 ** nd - 1)
        neg = rnd.random() < 0.4
        printed = decimal_text(neg, str(m), e)
        x = F(printed)
        if rnd.random() < 0.5:              # a window around an edit of the print: the edits land
            ds = list(str(m))
            ds[rnd.randrange(len(ds))] = str(rnd.randint(0, 9))
            if rnd.random() < 0.3 and len(ds) > 2:
                i = rnd.randrange(len(ds) - 1)
                ds[i], ds[i + 1] = ds[i + 1], ds[i]
            x = F(decimal_text(neg if rnd.random() < 0.8 else not neg, "".join(ds), e + rnd.choice([0, 0, 0, 1, -1])))
        if rnd.random() < 0.3:              # a decimal shift of the print
            x = F(printed) * F(10) ** rnd.choice(_SHIFTS)
        w = F(rnd.randint(0, 50), 10 ** rnd.randint(0, 12)) * F(10) ** e * rnd.choice([1, 1, 1000])
        r = rnd.random()
        if r < 0.25 and x != F(printed):    # the width at the distance test's threshold (factor 5 or 10)
            w = abs(x - F(printed)) / rnd.choice([5, 10]) * rnd.choice([F(99, 100), 1, F(101, 100)])
        elif r < 0.4:                       # the width at a digit's place (the constrained-digits test)
            w = F(10) ** (e + rnd.randint(0, nd)) * rnd.choice([F(99, 100), 1, F(101, 100)])
        lo, hi = x - w * F(rnd.randint(0, 100), 100), x + w * F(rnd.randint(0, 100), 100)
        if r < 0.4 and rnd.random() < 0.5:
            lo = hi - w                     # exactly that width
        if rnd.random() < 0.03:
            lo, hi = hi, lo                 # an empty window
        yield printed, lo, hi


def _shown(edits) -> list[tuple[str, str, str]]:
    return [(e.cls, e.intended, e.what) for e in edits]


def test_the_integer_edits_are_the_rational_ones():
    found = set()
    for printed, lo, hi in _cases(1500, 41):
        for evidential in (True, False):
            for factor in (5, 10):
                args = (printed, lo.numerator, lo.denominator, hi.numerator, hi.denominator, evidential, factor)
                got = _edits_into.__wrapped__(*args)
                assert _shown(got) == _shown(_reference(*args)), args
                found.update(e.cls for e in got)
    assert found == set(EDIT_CLASSES)       # every class met, so every branch was compared


def _both(printed: str, lo: F, hi: F, evidential: bool = True, factor: int = 10) -> list[tuple[str, str, str]]:
    args = (printed, lo.numerator, lo.denominator, hi.numerator, hi.denominator, evidential, factor)
    got = _shown(_edits_into.__wrapped__(*args))
    assert got == _shown(_reference(*args))
    return got


def test_the_boundaries_of_the_integer_tests():
    """The cases where a rational test is at its boundary: a decimal shift at the distance threshold (1.05
    for 0.105: 0.945 from it, the threshold 10 W with W just above and below 0.0945, two constrained
    digits), and a two-digit substitution whose lower place equals 10 W (12345 for 19845, W = 10)."""
    x, below, above = F("0.105"), F("0.0936"), F("0.0954")
    assert [e[0] for e in _both("1.05", x - below / 2, x + below / 2)] == ["decimal-shift"]
    assert _both("1.05", x - above / 2, x + above / 2) == []
    assert [e[:2] for e in _both("12345", F(19840), F(19850))] == [("multi-digit-substituted", "19845")]
    assert _both("12345", F(19840), F(19851)) == []      # W = 11: the place 100 is below 10 W
