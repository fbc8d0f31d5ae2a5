"""Classify a printed number against two references: the exact value for the stated parameters and
the paper's own chain (:class:`rigor_gyro.core.paper_chain.Chain`), issue 39.

In order, the first that holds:

``agrees``                  the print is a correct rounding of the exact value (every point of its ball);
``propagated``              the print is a correct rounding of some point of the chain: the paper's own
                            arithmetic from its own printed inputs, however far from the exact value;
``last-digit``              the same within the chain's ``slack`` units of the print's last digit (the
                            author's intermediate rounding): still the paper's arithmetic;
``propagated-misprint``     only the chain with an upstream misprint left as printed reproduces the print
                            (the author computed with the wrong upstream number; the row names it);
an edit class               one edit of the print (:mod:`rigor_gyro.core.digit_edits`: sign, decimal-shift,
                            digits-transposed, digit-dropped, digit-doubled, digit-substituted,
                            multi-digit-substituted) lands it in the chain's window: a misprint, whatever the
                            exact value says (an edit that reproduces only the exact value is no evidence);
``unexplained``             none of these; the reading gives the nearest chain value.

The window of a chain for a print is its hull widened by half a unit of the print's last digit plus
``slack`` units. Guarantee: every decision is an exact rational comparison of the chain's (or the exact
value's) certain bounds; ``propagated`` means the print is not excluded by the chain's enclosure (an
enclosure over-approximates the values the printed inputs allow, so a wide chain accepts more: its width
is in the reading). Failure mode: a non-finite chain gives ``unexplained`` with that said.
"""
from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

from flint import arb, fmpq

from .audit import audit_printed, half_unit
from .balls import ball_key, exact_endpoint_integers, exact_endpoints_fmpq
from .classification import Classification
from .digit_edits import edits_into
from .paper_chain import Chain

__all__ = ["classify_against_chain", "decide", "chain_window", "chain_text", "print_value", "MISPRINT_CLASSES"]

#: classes that say "a misprint" (the print is not what the author computed)
MISPRINT_CLASSES = ("sign", "decimal-shift", "digits-transposed", "digit-dropped", "digit-doubled",
                    "digit-substituted", "multi-digit-substituted")


def chain_window(printed: str, value: arb, slack: int) -> tuple[fmpq, fmpq] | None:
    """[lo - h - slack u, hi + h + slack u] for the ball ``value`` and the print's half unit h and unit u
    (None when the ball is not finite), as exact flint rationals (compare them with :func:`print_value`)."""
    if not value.is_finite():
        return None
    key = (printed, *ball_key(value), slack)
    hit = _WINDOWS.get(key)
    if hit is None:
        if len(_WINDOWS) > 16384:
            _WINDOWS.clear()
        lo, hi = _ends(value)
        h = half_unit(printed)
        pad = fmpq(h.numerator, h.denominator) * (1 + 2 * slack)
        hit = _WINDOWS[key] = (lo - pad, hi + pad)
    return hit


_ENDS: dict = {}
#: chain windows memoised by (print, the ball's exact midpoint and radius, slack): the builder's passes ask
#: the same windows again
_WINDOWS: dict = {}


def _ends(value: arb) -> tuple[fmpq, fmpq]:
    """The exact ends of a finite ball, memoised by its exact midpoint and radius."""
    key = ball_key(value)
    hit = _ENDS.get(key)
    if hit is None:
        if len(_ENDS) > 8192:
            _ENDS.clear()
        hit = _ENDS[key] = exact_endpoints_fmpq(value)
    return hit


def _inside(printed: str, window: tuple[fmpq, fmpq] | None) -> bool:
    return window is not None and window[0] <= print_value(printed.strip()) <= window[1]


def chain_text(value: arb, printed: str) -> str:
    """The chain's ball at the print's place plus two digits, [lo, hi] rounded outward (or one number)."""
    if not value.is_finite():
        return "(not finite)"
    ln, ld, hn, hd = exact_endpoint_integers(value)
    e = Decimal(printed.strip()).as_tuple().exponent - 2

    def fmt(num: int, den: int, up: bool) -> str:
        # num / den in units of 10^e, rounded down or up (integers: den > 0)
        num, den = (num, den * 10 ** e) if e >= 0 else (num * 10 ** -e, den)
        m = -((-num) // den) if up else num // den
        return format(Decimal(m).scaleb(e), "f")
    a, b = fmt(ln, ld, False), fmt(hn, hd, True)
    return a if a == b else f"[{a}, {b}]"


def classify_against_chain(printed: str, value: arb, chain: Chain):
    """The class of ``printed`` against the exact ball ``value`` and the paper chain ``chain`` (module
    docstring). Returns a :class:`rigor_gyro.core.classification.Classification` with ``intended`` set for a
    misprint class."""
    text = printed.strip()
    key = (text, *ball_key(value))
    hit = chain.cache.get(key)
    if hit is None:
        hit = chain.cache[key] = _classify(text, value, chain)
    return hit


def decide(text: str, chain: Chain):
    """The chain's verdict on a print, shared by the kind's chain builder (which value downstream stages
    read) and the classifier (the row's class), so the two never disagree. Returns (kind, edit, narrowed):
    kind ``propagated`` (inside the window at slack 0), ``last-digit`` (inside at the chain's slack),
    ``edit`` (an evidential edit lands inside: first at slack 0 with distance factor 5, then at the slack
    with factor 10), ``candidate`` (only the accepted non-evidential edit of ``chain.accepted`` lands) or
    ``none``; ``narrowed`` says whether the identity-narrowed chain decided (else the computed one).
    The narrowed chain is tried first; where it only rejects the print (no edit lands in it), the computed
    chain decides (the prints break the identity by a few units: the paper's arithmetic, not evidence)."""
    key = (text, _ball_key(chain.value), _NO_BALL if chain.computed is None else _ball_key(chain.computed),
           chain.slack, chain.accepted)
    hit = _DECIDED.get(key)
    if hit is None:
        if len(_DECIDED) > 16384:
            _DECIDED.clear()
        hit = _DECIDED[key] = _decide(text, chain)
    return hit


#: decide's verdicts memoised by (print, the exact midpoints and radii of the chain's balls, slack, accepted):
#: its result is a function of these alone, and the chain builder's passes ask the same question again
_DECIDED: dict = {}
_NO_BALL = ("no ball",)


def _ball_key(value: arb):
    """A finite ball's exact midpoint and radius (None for any non-finite ball: every window is None)."""
    return ball_key(value) if value.is_finite() else None


def print_value(text: str) -> fmpq:
    """The printed decimal ``text`` (stripped) as an exact flint rational, memoised."""
    hit = _PRINTS.get(text)
    if hit is None:
        if len(_PRINTS) > 16384:
            _PRINTS.clear()
        x = Fraction(text)
        hit = _PRINTS[text] = fmpq(x.numerator, x.denominator)
    return hit


_PRINTS: dict = {}


def _decide(text: str, chain: Chain):
    """:func:`decide` without its memo."""
    x = print_value(text)
    refs = [(chain.value, True)] + ([(chain.computed, False)] if chain.computed is not None else [])
    for val, narrowed in refs:
        w0, ws = chain_window(text, val, 0), chain_window(text, val, chain.slack)
        if w0 is None:
            continue
        if w0[0] <= x <= w0[1]:
            return "propagated", None, narrowed and chain.computed is not None
        if ws[0] <= x <= ws[1]:
            return "last-digit", None, narrowed and chain.computed is not None
        ed = edits_into(text, *w0, factor=5) or edits_into(text, *ws)
        if ed:
            return "edit", ed[0], narrowed and chain.computed is not None
    if chain.accepted:
        for val, narrowed in refs:
            ws = chain_window(text, val, chain.slack)
            if ws is not None:
                ed = [e for e in edits_into(text, *ws, evidential=False) if e.intended == chain.accepted]
                if ed:
                    return "candidate", ed[0], narrowed and chain.computed is not None
    return "none", None, False


def _classify(text: str, value: arb, chain: Chain):
    status, _ = audit_printed(text, value)
    if status.value == "agrees":
        return Classification("agrees", f"{text} is a correct rounding of the exact value", ["agrees"])
    kind, e, narrowed = decide(text, chain)
    shown = chain.value if (narrowed or chain.computed is None) else chain.computed
    src = chain.source + (f"; narrowed by the identity {chain.identity}" if narrowed else "")
    ref = f"paper chain ({src}) {chain_text(shown, text)}"
    if kind == "propagated":
        return Classification("propagated", f"{text} rounds the {ref}: the paper's arithmetic from its own "
                                            "printed inputs, not a misprint", ["propagated"])
    if kind == "last-digit":
        return Classification("last-digit", f"{text} is within {chain.slack} units of its last digit of the {ref}: "
                                            "the paper's own rounding", ["last-digit"])
    for alt, upstream in chain.alternates:
        w = chain_window(text, alt, chain.slack)
        if w is not None and w[0] <= print_value(text) <= w[1]:
            return Classification("propagated-misprint",
                                  f"{text} follows from the misprint in {upstream} as printed (the chain with "
                                  f"{upstream} as printed gives {chain_text(alt, text)}; corrected, the {ref})",
                                  ["propagated-misprint"], upstream=upstream)
    if kind in ("edit", "candidate"):
        why = f"; {chain.evidence}" if kind == "candidate" else ""
        return Classification(e.cls, f"{text} -> {e.intended} (printed {e.what}): the intended number is in the "
                                     f"{ref}{why}", [e.cls], intended=e.intended)
    return Classification("unexplained", f"no edit of {text} reaches the {ref} (nearest chain value); "
                                         f"{chain.evidence or 'the paper computed another number at this step'}",
                          ["unexplained"])
