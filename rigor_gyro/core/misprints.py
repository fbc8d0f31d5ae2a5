"""Why a printed number differs from its certified value: a discrepancy classifier for paper audits.

:func:`classify_printed` takes a number as a paper prints it and a ball that certainly contains the
true value, and names the single, simplest reading that reproduces the print, in this order:

``agrees``            the print is a correct rounding of the value (every point of the ball);
``propagated``        the print is a correct rounding of some value the recomputation from the paper's own
                      printed inputs allows (the kind gives a ball holding every value those inputs give,
                      each read within its printed rounding): the paper's computation, not a misprint;
``last-digit``        the correct rounding at the printed place is one unit away in the last place;
``sign``              the negated print agrees;
``decimal-shift``     the print agrees with the value times 10^k, k in +-1..+-6;
``digits-transposed`` the correct rounding with two adjacent digits swapped;
``digit-dropped``     the value rounded to one more significant digit, with one digit left out;
``digit-doubled``     the value rounded to one fewer significant digit, with one digit written twice;
``digit-substituted`` the correct rounding with one digit replaced (not the last: a last digit off by a
                      few units is a numerical difference, left ``unexplained``);

(the four digit edits only for prints of at least ``MIN_DIGITS_FOR_EDITS`` significant digits). For a
print of at least ``MIN_DIGITS_FOR_COMPOUND`` significant digits, an edit also explains a print it
reproduces to within one unit in the last place, and, failing that, a print whose digits after the
edit agree with the value to at least ``MIN_DIGITS_FOR_EDITS`` significant digits, the edited one among
them and two agreeing digits after it (a misprint on top of the paper's own rounding); with the one-unit
relaxation the edit must leave three digits after it (two exact, the last one unit off); the reading
says which;
``unexplained``       none of these;
``undecided``         the ball is too wide to tell (it straddles a rounding boundary of the printed place
                      in a way that matters): raise the precision.

Guarantee: each class except ``unexplained`` and ``undecided`` is decided in ball arithmetic: the
correct roundings of the value at the needed places are computed from the ball's certain bounds and
used only when both ends of the ball round alike, and ``agrees`` (for the value, the recomputed value,
the negation, a shift) is :func:`rigor_gyro.core.audit.audit_printed`'s certain agreement. The reading
returned says which digits the value has and how the print was obtained from them. A classification is
an explanation, not a proof of what the author meant: several readings may fit, and the first in the
order above is reported (``readings`` lists every one that fits).
"""
from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

from flint import arb, fmpq

from .audit import PRINTED_NUMBER, agreeing_digits, audit_printed
from .balls import exact_fraction, exponent10
from .chain_classify import classify_against_chain
from .classification import Classification
from .outcome import AuditRow, AuditStatus
from .paper_chain import Chain

__all__ = ["CLASSES", "ROW_CLASSES", "MIN_DIGITS_FOR_EDITS", "MIN_DIGITS_FOR_COMPOUND", "Classification", "classify_printed", "classify_row",
           "rounded_at"]

CLASSES = ("agrees", "propagated", "last-digit", "propagated-misprint", "sign", "decimal-shift", "digits-transposed",
           "digit-dropped", "digit-doubled", "digit-substituted", "multi-digit-substituted", "unexplained", "undecided")
#: digit edits are readings only for prints of at least this many significant digits (with fewer, some
#: single-digit edit fits almost any pair of numbers, and says nothing)
MIN_DIGITS_FOR_EDITS = 3
#: an edit combined with the paper's own rounding (one unit off in the last place, or agreement on a
#: prefix only) is a reading only for prints of at least this many significant digits
MIN_DIGITS_FOR_COMPOUND = 5
_SHIFTS = (1, -1, 2, -2, 3, -3, 4, -4, 5, -5, 6, -6)


def _round_q_at(q: Fraction, exponent: int) -> Decimal:
    """q rounded half-even at the place 10^exponent, exactly (integer arithmetic; the Decimal is built
    from its digit string, so no context precision rounds it)."""
    num, den = q.numerator, q.denominator
    if exponent >= 0:
        den *= 10 ** exponent
    else:
        num *= 10 ** -exponent
    n, r = divmod(num, den)                 # floor; 0 <= r < den
    twice = 2 * r
    if twice > den or (twice == den and n % 2):
        n += 1
    return Decimal(f"{n}E{exponent}")


def rounded_at(value: arb, exponent: int) -> Decimal | None:
    """The correct rounding (half-even) of every point of ``value`` at the place 10^exponent, or None
    when the ball's two ends round differently (or it is not finite). Exact: the ends are dyadic
    rationals, rounded in integer arithmetic (a conversion to a 200-digit Decimal first would round a
    value within 10^-200 of a tie onto the tie)."""
    if not value.is_finite():
        return None
    lo, hi = exact_fraction(value.lower()), exact_fraction(value.upper())
    a = _round_q_at(lo, exponent)
    return a if a == _round_q_at(hi, exponent) else None


def _sig_rounded(value: arb, nsig: int) -> Decimal | None:
    """``value`` rounded to ``nsig`` significant digits (None if its ends round differently or lie in
    different decades)."""
    if nsig < 1 or not value.is_finite():
        return None
    lo, hi = exact_fraction(value.lower()), exact_fraction(value.upper())
    if lo == 0 or hi == 0 or (lo < 0) != (hi < 0):
        return None
    mag = exponent10(lo)
    if exponent10(hi) != mag:
        return None
    return rounded_at(value, mag - nsig + 1)


def _digits(d: Decimal) -> str:
    """The significant digits of |d| (no leading zeros), e.g. 0.013827 -> '13827'."""
    return "".join(map(str, d.copy_abs().as_tuple().digits)).lstrip("0") or "0"


def _place_digits(d: Decimal, exponent: int) -> str:
    """|d| written as an integer count of units of 10^exponent (the digits down to that place)."""
    n = int(d.copy_abs().scaleb(-exponent).to_integral_value())
    return str(n)


def _transposed(a: str, b: str) -> int | None:
    if len(a) != len(b):
        return None
    diff = [i for i in range(len(a)) if a[i] != b[i]]
    if len(diff) == 2 and diff[1] == diff[0] + 1 and a[diff[0]] == b[diff[1]] and a[diff[1]] == b[diff[0]]:
        return diff[0]
    return None


def _substituted(a: str, b: str) -> int | None:
    if len(a) != len(b):
        return None
    diff = [i for i in range(len(a)) if a[i] != b[i]]
    return diff[0] if len(diff) == 1 else None


def _one_removed(longer: str, shorter: str) -> int | None:
    if len(longer) != len(shorter) + 1:
        return None
    for i in range(len(longer)):
        if longer[:i] + longer[i + 1:] == shorter:
            return i
    return None


def _q(x: Fraction) -> arb:
    return arb(fmpq(x.numerator, x.denominator))


def _edit_then_agreeing_prefix(text: str, P: Decimal, value: arb) -> list[tuple[str, str]]:
    """Compound readings: one edit (sign, a substituted digit, two transposed digits) undone, after which
    the print agrees with the value to d >= MIN_DIGITS_FOR_EDITS significant digits, the edited digit
    among them and at least one agreeing digit after it (the rest is the paper's own rounding or
    computation). The best d wins; the reading gives it. At least two agreeing digits must follow the
    edited ones: with one, some edit fits a random print too often (about n/10 for n digits)."""
    n = len(_digits(P))
    sig = P.as_tuple()
    digits = list(sig.digits)
    lead = next((k for k, d in enumerate(digits) if d != 0), 0)
    out: list[tuple[str, str, int]] = []

    def build(ds, negative) -> str:
        return str(Decimal((1 if negative else 0, tuple(ds), sig.exponent)))

    neg = -P
    if P != 0:
        d = agreeing_digits(str(neg), value)
        if d >= MIN_DIGITS_FOR_EDITS:
            out.append(("sign", f"with its sign changed the print, {neg}, agrees with the value to {d} of {n} "
                                "significant digits (the rest is the paper's own rounding or computation)", d))
    # the value's own digits at the printed place propose the replacement digit (one candidate per position)
    T = rounded_at(value, sig.exponent)
    tdig = list(Decimal(abs(T)).quantize(Decimal(1).scaleb(sig.exponent)).as_tuple().digits) if T is not None else []
    tdig = [0] * (len(digits) - len(tdig)) + tdig if len(tdig) <= len(digits) else []
    for i in range(lead, len(digits)):
        pos = i - lead                               # 0-based significant position
        for r in ([tdig[i]] if tdig else range(10)):
            if r == digits[i] or (r == 0 and i == lead):
                continue
            ds = digits[:i] + [r] + digits[i + 1:]
            d = agreeing_digits(build(ds, sig.sign), value)
            if d >= max(MIN_DIGITS_FOR_EDITS, pos + 3):
                out.append(("digit-substituted", f"with its digit {digits[i]} (position {pos + 1}) read as {r}, the "
                                                 f"print agrees with the value to {d} of {n} significant digits (the "
                                                 "rest is the paper's own rounding or computation)", d))
        if i + 1 < len(digits) and digits[i] != digits[i + 1]:
            ds = digits[:i] + [digits[i + 1], digits[i]] + digits[i + 2:]
            d = agreeing_digits(build(ds, sig.sign), value)
            if d >= max(MIN_DIGITS_FOR_EDITS, pos + 4):
                out.append(("digits-transposed", f"with its digits {digits[i]}{digits[i + 1]} (positions {pos + 1}, "
                                                 f"{pos + 2}) swapped back, the print agrees with the value to {d} of "
                                                 f"{n} significant digits (the rest is the paper's own rounding or "
                                                 "computation)", d))
    if not out:
        return []
    best = max(d for _, _, d in out)
    return [next((c, r) for c, r, d in out if d == best)]


def _near(rounded: Decimal, exponent: int, compound: bool = True) -> list[tuple[Decimal, str]]:
    """The readings of a correct rounding that a hand-computed table may print: itself, and (when
    ``compound``) one unit up or down in its last place (the ubiquitous last-digit difference)."""
    u = Decimal(1).scaleb(exponent)
    if not compound:
        return [(rounded, "")]
    return [(rounded, ""), (rounded + u, " (and one unit off in the last place)"),
            (rounded - u, " (and one unit off in the last place)")]


def _rounds_to_print_somewhere(P: Decimal, x: arb) -> bool:
    """Certainly some point of the ball x rounds to the print P at its printed place: the ball's exact
    hull meets [P - h, P + h], h half a unit in P's last place (exact rational comparisons)."""
    if not x.is_finite():
        return False
    h = Fraction(1, 2) * Fraction(10) ** P.as_tuple().exponent
    p = Fraction(P)
    return exact_fraction(x.lower()) <= p + h and exact_fraction(x.upper()) >= p - h


def classify_printed(printed: str, value: arb, propagated: arb | None = None,
                     propagated_from: str | None = None) -> Classification:
    """Classify the printed decimal ``printed`` against the certified ball ``value`` (and, when the kind
    has one, ``propagated``: a ball containing the value recomputed from the paper's own printed inputs).
    See the module docstring for the classes, their order and the guarantee. An edit (sign, shift,
    transposition, dropped, doubled or substituted digit) also explains a print that it reproduces to
    within one unit in the last place; the reading says so."""
    text = printed.strip()
    P = Decimal(text)
    exp = P.as_tuple().exponent
    fits: list[tuple[str, str]] = []

    status, _ = audit_printed(text, value)
    if status is AuditStatus.AGREES:
        return Classification("agrees", f"{text} is a correct rounding of the certified value", ["agrees"])
    T = rounded_at(value, exp)
    compound = len(_digits(P)) >= MIN_DIGITS_FOR_COMPOUND
    if propagated is not None and _rounds_to_print_somewhere(P, propagated):
        source = propagated_from or "the paper's own printed inputs"
        fits.append(("propagated", f"{text} is a correct rounding of the value recomputed from {source} (the "
                                   f"computation, not the print, is off; the certified value "
                                   f"rounds to {T if T is not None else 'an undecided rounding'})"))
    if T is not None and T != P and P != 0 and abs(T - P) == Decimal(1).scaleb(exp):   # a printed 0 is exact
        fits.append(("last-digit", f"the value rounds to {T} at the printed place: the print is one unit off "
                                   "in its last digit"))
    if T is not None and P != 0:
        for cand, extra in _near(T, exp, compound):
            if cand == -P and cand != 0:
                fits.append(("sign", f"the value reads {T}: the print has the wrong sign{extra}"))
                break
    # a decimal shift keeps the significant digits: the value to the print's significant digits, moved
    vs = _sig_rounded(value, len(_digits(P))) if P != 0 else None
    k = (P.adjusted() - vs.adjusted()) if vs is not None and vs != 0 else 0
    if k and abs(k) <= max(map(abs, _SHIFTS)):
        shifted = rounded_at(value * _q(Fraction(10) ** k), exp)
        if shifted is not None and any(c == P for c, _ in _near(shifted, exp, compound)):
            extra = "" if shifted == P else " (and one unit off in the last place)"
            fits.append(("decimal-shift", f"{text} is the value times 10^{k}: the decimal point is {abs(k)} "
                                          f"place(s) {'right' if k > 0 else 'left'} of where it belongs{extra}"))
    nsig = len(_digits(P))
    edits = nsig >= MIN_DIGITS_FOR_EDITS
    if edits and T is not None:
        b = _place_digits(P, exp)
        for cand, extra in _near(T, exp, compound):
            if cand == P or (cand.is_signed() != P.is_signed() and cand != 0):
                continue
            a = _place_digits(cand, exp)
            i = _transposed(a, b)
            if i is not None and (not extra or i + 1 <= len(a) - 4):
                fits.append(("digits-transposed", f"the value reads {T} at the printed place; the print swaps "
                                                  f"the digits {a[i]}{a[i + 1]} of {cand} to {b[i]}{b[i + 1]}{extra}"))
                break
        for cand, extra in _near(T, exp, compound):
            if cand == P or (cand.is_signed() != P.is_signed() and cand != 0):
                continue
            a = _place_digits(cand, exp)
            i = _substituted(a, b)
            # not in the last place: a last digit off by a few units is a numerical difference, not a misprint
            if i is not None and i < len(a) - 1 and (not extra or i <= len(a) - 4):
                fits.append(("digit-substituted", f"the value reads {T} at the printed place; the print has {b[i]} "
                                                  f"for the digit {a[i]} of {cand}{extra}"))
                break
    up = _sig_rounded(value, nsig + 1) if edits else None
    if up is not None and up.is_signed() == P.is_signed():
        for cand, extra in _near(up, up.as_tuple().exponent, compound):
            if cand.adjusted() != P.adjusted():
                continue
            i = _one_removed(_digits(cand), _digits(P))
            if i is not None and (not extra or i <= len(_digits(cand)) - 4):
                fits.append(("digit-dropped", f"the value reads {up} to {nsig + 1} significant digits; the print "
                                              f"leaves out the digit {_digits(cand)[i]} (position {i + 1}) of "
                                              f"{cand}{extra}"))
                break
    down = _sig_rounded(value, nsig - 1) if edits else None
    if down is not None and down.is_signed() == P.is_signed():
        dp = _digits(P)
        for cand, extra in _near(down, down.as_tuple().exponent, compound):
            if cand.adjusted() != P.adjusted():
                continue
            dd = _digits(cand)
            twice = [i for i in range(1, len(dp)) if dp[i] == dp[i - 1] and dp[:i] + dp[i + 1:] == dd
                     and (not extra or i <= len(dp) - 4)]
            if twice:
                fits.append(("digit-doubled", f"the value reads {down} to {nsig - 1} significant digits; the print "
                                              f"writes the digit {dp[twice[0]]} of {cand} twice{extra}"))
                break
    if not fits and compound:
        fits += _edit_then_agreeing_prefix(text, P, value)
    if fits:
        order = {c: n for n, c in enumerate(CLASSES)}
        fits.sort(key=lambda cr: order[cr[0]])
        return Classification(fits[0][0], fits[0][1], [c for c, _ in fits])
    if T is None and status is AuditStatus.UNDECIDED:
        return Classification("undecided", "the certified ball straddles a rounding boundary of the printed place "
                                           "(raise the precision)", ["undecided"])
    shown = T if T is not None else "(a rounding the ball does not decide)"
    return Classification("unexplained", f"the value reads {shown}; no single edit gives the print",
                          ["unexplained"])


#: classes of rows that are not one printed number against one value
ROW_CLASSES = ("misprint-reading", "assertion-confirmed", "assertion-refuted", "not-a-number")


def _schema_knows(cls: str) -> bool:
    """Whether the certificate schema's class enum lists ``cls`` (the classes of issue 39 appear in the
    certificates once the schema admits them; until then each is written as its nearest older class, the
    reading naming it)."""
    global _SCHEMA_TEXT
    if _SCHEMA_TEXT is None:
        from pathlib import Path
        try:
            _SCHEMA_TEXT = (Path(__file__).resolve().parent.parent / "schemas" / "certificate-2.schema.json").read_text()
        except OSError:
            _SCHEMA_TEXT = ""
    return f'"{cls}"' in _SCHEMA_TEXT


_SCHEMA_TEXT: str | None = None
#: a class of issue 39 -> the older class written while the schema does not list it
_OLDER = {"multi-digit-substituted": "digit-substituted", "propagated-misprint": "propagated"}


def _as_schema(c: Classification) -> Classification:
    if c.cls in _OLDER and not _schema_knows(c.cls):
        return Classification(_OLDER[c.cls], f"[{c.cls}] {c.reading}", [_OLDER[c.cls]] + c.readings[1:],
                              c.intended, c.upstream)
    return c


def classify_row(row: AuditRow) -> Classification:
    """The class of one audit row: :func:`classify_printed` when the row is one printed decimal against
    a certified ball (``row.propagated``, when the kind set it, is the value recomputed from the paper's
    printed inputs; a :class:`~rigor_gyro.core.paper_chain.Chain` there sends the row to
    :func:`~rigor_gyro.core.chain_classify.classify_against_chain`, the two-reference classifier); for other rows, from the row's status: a verbal assertion is
    ``assertion-confirmed`` or ``assertion-refuted``, a printed formula the model reads otherwise is
    ``misprint-reading`` (its reading is the row's ``reading``), anything else ``not-a-number``."""
    if row.status is AuditStatus.CONFIRMED:
        return Classification("assertion-confirmed", "the assertion is certified true", ["assertion-confirmed"])
    if row.status is AuditStatus.REFUTED:
        return Classification("assertion-refuted", "the assertion is certified false", ["assertion-refuted"])
    printed = row.printed.strip()
    if row.value is not None and PRINTED_NUMBER.match(printed) and row.value.is_finite():
        prop = getattr(row, "propagated", None)
        if isinstance(prop, Chain):
            return _as_schema(classify_against_chain(printed, row.value, prop))
        return classify_printed(printed, row.value, getattr(row, "propagated", None),
                                getattr(row, "propagated_from", None))
    if row.status is AuditStatus.MISPRINT:
        return Classification("misprint-reading", f"reproduced by the reading {row.reading!r}", ["misprint-reading"])
    return Classification("not-a-number", "not one printed number against one value", ["not-a-number"])
