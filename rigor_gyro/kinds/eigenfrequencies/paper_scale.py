"""Rudenko (1976)'s 'exact' frequencies and the Hz scale (issue 39): the four printed 'exact' values
(41.4, 121.5, 521.5, 935.7 Hz) admit no common scale sqrt(K3/A3)/(2 pi) at the printed parameters;
this module finds the parameter reading that makes them consistent: the nearest four-digit eps (all
else as printed) at which one scale reproduces all four, with a certified witness scale.

Guarantee: a candidate eps is accepted only when, in ball arithmetic at that exact rational eps, the
quartic (2) has four positive roots (isolated, :func:`rigor_gyro.core.polyroots.isolate_polynomial`), the
intersection of the four scale ranges is certainly nonempty, and a decimal witness scale inside it makes
each 'exact' value a correct rounding (:func:`rigor_gyro.core.audit.audit_printed` agrees). Failure mode:
no candidate in the scanned range fits (the row then says so: no eps within the scan explains them);
the scan is over four-digit decimals within 0.0010 of the printed eps (21 candidates, nearest first).
"""
from __future__ import annotations

from decimal import Decimal
from fractions import Fraction
from typing import NamedTuple

from flint import arb, fmpq

from ...core.audit import audit_printed, half_unit
from ...core.balls import ball, certainly_lt, certainly_positive, decimal_bounds
from ...core.outcome import AuditRow, AuditStatus
from ...core.polyroots import isolate_polynomial
from .model import characteristic_quartic

__all__ = ["consistent_eps_row", "consistent_eps", "fit_scales", "ScaleReading", "EPS_SCAN"]

#: candidates: eps_printed + k * 10^-4, |k| <= EPS_SCAN, nearest first
EPS_SCAN = 10


def _omegas(a: fmpq, b: fmpq, e: fmpq, W: fmpq) -> list[arb] | None:
    iso = isolate_polynomial(characteristic_quartic(a, b, e, W))
    pos = sorted([x for x in iso.real if certainly_positive(x)], key=lambda x: float(x.mid())) \
        if iso.squarefree else []
    return pos if len(pos) == 4 else None


def fit_scales(exact: list[str], om: list[arb]) -> tuple[arb, arb] | None:
    """(lo, hi): the common scales of the prints ``exact`` of sqrt(om), when their ranges certainly
    intersect (lo a ball around the largest lower end, hi around the smallest upper end)."""
    los, his = [], []
    for x, w in zip(exact, om):
        h = half_unit(x)
        hq = arb(fmpq(h.numerator, h.denominator))
        los.append((ball(x) - hq) / w.sqrt())
        his.append((ball(x) + hq) / w.sqrt())
    lo = max(los, key=lambda r: float(r.mid()))     # a float picks; the balls decide below
    hi = min(his, key=lambda r: float(r.mid()))
    if all(certainly_lt(l_, hi) for l_ in los) and all(certainly_lt(lo, h_) for h_ in his):
        return lo, hi
    return None


def _witness(lo: arb, hi: arb) -> fmpq | None:
    """A decimal with few digits certainly inside (lo, hi)."""
    a, b = decimal_bounds(lo, 12)[1], decimal_bounds(hi, 12)[0]
    for digits in range(1, 10):
        q = Decimal(1).scaleb(-digits)
        m = ((Decimal(a) + Decimal(b)) / 2).quantize(q)
        f = Fraction(m)
        s = fmpq(f.numerator, f.denominator)
        if certainly_lt(lo, arb(s)) and certainly_lt(arb(s), hi):
            return s
    return None


class ScaleReading(NamedTuple):
    """The eps reading that gives the 'exact' values one Hz scale: ``eps`` (exact) and its text, ``k`` its
    distance from the printed eps in units of 10^-4, ``lo``/``hi`` balls whose exact hull [lo.lower(),
    hi.upper()] contains every common scale and [lo.upper(), hi.lower()] is inside them, ``witness`` a
    decimal scale that reproduces all four, ``omegas`` the four roots at that eps."""

    eps: fmpq
    text: str
    k: int
    lo: arb
    hi: arb
    witness: fmpq
    omegas: list

    def outer(self) -> arb:
        """A ball containing every common scale (the hull)."""
        return self.lo.union(self.hi)


def consistent_eps(a: fmpq, b: fmpq, W: fmpq, eps_text: str, exact: list[str]) -> ScaleReading | None:
    """The nearest four-digit eps (a, b, Omega^2 as printed) at which one Hz scale reproduces the four
    'exact' values, certified (module docstring); None when no candidate of the scan fits."""
    base = Fraction(eps_text)
    step = Fraction(1, 10000)
    for k in sorted(range(-EPS_SCAN, EPS_SCAN + 1), key=lambda k: (abs(k), k)):
        cand = base + k * step
        ce = fmpq(cand.numerator, cand.denominator)
        om = _omegas(a, b, ce, W)
        if om is None:
            continue
        got = fit_scales(exact, om)
        if got is None:
            continue
        s = _witness(*got)
        if s is None or not all(audit_printed(x, arb(s) * w.sqrt())[0] is AuditStatus.AGREES
                                for x, w in zip(exact, om)):
            continue
        et = format(Decimal(cand.numerator) / Decimal(cand.denominator), "f")
        return ScaleReading(ce, et, k, got[0], got[1], s, om)
    return None


def consistent_eps_row(a: fmpq, b: fmpq, e: fmpq, W: fmpq, eps_text: str, exact: list[str],
                       found: ScaleReading | None = None) -> AuditRow | None:
    """The row: the nearest four-digit eps at which one Hz scale reproduces the four 'exact' values
    (``found``: :func:`consistent_eps` if already computed)."""
    r = found if found is not None else consistent_eps(a, b, W, eps_text, exact)
    if r is None:
        # an exact scan that found nothing: no row (an undecided row would make the prover raise the
        # precision, which cannot change a scan of exact decimals; at other parameters this is the rule)
        return None
    lo, hi = decimal_bounds(r.lo, 7)[0], decimal_bounds(r.hi, 7)[1]
    s, et = r.witness, r.text
    return AuditRow("'exact' values: the eps that gives them one Hz scale", f"eps = {eps_text}",
                    f"eps = {et} (a, b, Omega^2 as printed)", None,
                    AuditStatus.CONFIRMED if r.k == 0 else AuditStatus.MISPRINT,
                    f"at eps = {et} the four 'exact' values {', '.join(exact)} share the Hz scales [{lo}, {hi}] "
                    f"(certified); hz_scale = {s.p}/{s.q} = {float(s.p) / float(s.q):.6g} reproduces each as a "
                    f"correct rounding (witness); the printed eps = {eps_text} admits none (row 'exact' values "
                    "share one Hz scale): the machine computation of the 'exact' values used this eps, or the "
                    "printed eps has its last digit wrong; the nearest such four-digit eps, "
                    f"scanned within {EPS_SCAN} units of the printed one; this scale is the paper's Hz scale in "
                    "every Hz row's paper chain")


_fit = fit_scales        # the earlier name (tests use it)
