"""The paper's own chain: a printed number recomputed the way its author did, from the paper's own
printed inputs (issue 39).

A :class:`Chain` is the second reference of an audit row, beside the exact value for the stated
parameters: a ball holding every value the author's computation could give from the paper's printed
inputs, each printed input read as the interval of its rounding (:func:`rounding_interval`), exact
constants kept exact (:func:`exact_value`), and an upstream print that is itself a misprint replaced
by its intended value. ``alternates`` are the same computation with one such upstream misprint left
as printed (the classifier names that upstream row when only an alternate reproduces the print:
class ``propagated-misprint``). ``slack`` is the number of units of the print's last digit the
author's own intermediate rounding may add beyond the chain (0 for an exact chain).

Guarantee: ``value`` (and each alternate) is an Arb enclosure of that set of values (interval
arithmetic over the input intervals; an over-approximation, never a sample), computed at the working
precision. The classifier's decisions on it (:mod:`rigor_gyro.core.chain_classify`) are exact
rational comparisons of its hull. Failure mode: a wide input interval (a print with few digits in a
sensitive place) gives a wide chain, which reproduces more prints; the width is reported.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, ctx, fmpq

from .audit import half_unit
from .balls import ball

__all__ = ["Chain", "Relation", "relation_refs", "rounding_interval", "exact_value", "DEFAULT_SLACK"]

#: the author's own rounding beyond the chain, in units of the print's last digit: in the 1947 example the
#: prints that round a chain value sit at most 2.7 units outside its ball (the hand computation carried
#: a digit or two more than it printed and rounded at each step); measured in tests/test_paper_chain.py
DEFAULT_SLACK = 3


@dataclass
class Chain:
    """The paper-chain reference of one printed number (see the module docstring)."""

    value: arb
    source: str
    slack: int = DEFAULT_SLACK
    #: ((ball, upstream row id), ...): the chain with that upstream misprint left as printed
    alternates: tuple = ()
    #: the consistency identities that narrowed ``value``, named in the row's reading
    identity: str = ""
    #: the chain before that narrowing (None when no identity narrowed it)
    computed: arb | None = None
    #: extra evidence text for the reading (e.g. which identity decided)
    evidence: str = field(default="")
    #: an edit accepted on other evidence (``evidence``: downstream rows reproduced only with it), whose
    #: window alone is too wide to make it evidential: the intended text
    accepted: str | None = None
    #: the classification of a print against this chain, memoised by (print, exact ball): the kind decides
    #: a row's status with it, the certificate writes its class (the same decision, computed once)
    cache: dict = field(default_factory=dict, repr=False, compare=False)

    def is_finite(self) -> bool:
        return self.value.is_finite()


def rounding_interval(txt: str) -> arb:
    """Every number the printed decimal ``txt`` may stand for: [x - h, x + h], h half a unit in its
    last printed place (exact ends, the ball built from exact rationals, rounded outward at the working
    precision; memoised per precision)."""
    return _rounding_interval(txt, ctx.prec)


@functools.lru_cache(maxsize=8192)
def _rounding_interval(txt: str, prec: int) -> arb:
    h = half_unit(txt)
    x = Fraction(txt.strip())
    lo, hi = x - h, x + h
    return arb(fmpq(lo.numerator, lo.denominator)).union(arb(fmpq(hi.numerator, hi.denominator)))


def exact_value(txt: str) -> arb:
    """The printed decimal as an exact number (for a constant the paper states exactly: S = 0.15), as a
    ball at the working precision (memoised per precision)."""
    return _exact_value(txt.strip(), ctx.prec)


@functools.lru_cache(maxsize=4096)
def _exact_value(txt: str, prec: int) -> arb:
    return ball(txt)


@dataclass(frozen=True)
class Relation:
    """A consistency identity the paper's numbers obey: sum coef_r x_r = const over printed rows
    (exact rational coefficients), named for the reading (e.g. "D1 = beta sin = h11")."""

    terms: tuple            # ((row id, Fraction coef), ...)
    const: Fraction
    name: str


def relation_refs(rid: str, prints: dict[str, str], relations, slack: int = DEFAULT_SLACK) -> list[tuple[arb, str]]:
    """For row ``rid``: each relation containing it (``relations``: a list, or a dict row id -> its relations), solved for it from the other rows' prints (each the
    interval of its rounding widened by ``slack`` units of its last digit): [(ball, relation name)].
    A relation with a missing print gives nothing. Guarantee: each ball holds every value of x_rid the
    relation allows with the other prints read within rounding plus slack (interval arithmetic)."""
    out = []
    for rel in (relations.get(rid, ()) if isinstance(relations, dict) else relations):
        coefs = dict(rel.terms)
        if rid not in coefs:
            continue
        acc = _q(rel.const)
        ok = True
        for o, cf in rel.terms:
            if o == rid:
                continue
            txt = prints.get(o)
            if not txt:
                ok = False
                break
            u = 2 * half_unit(txt) * slack
            x = rounding_interval(txt) + _q(u) * arb(0, 1)
            acc -= _q(cf) * x
        if ok:
            out.append((acc / _q(coefs[rid]), rel.name))
    return out


def _q(x: Fraction) -> arb:
    x = Fraction(x)
    return arb(fmpq(x.numerator, x.denominator))
