"""Exact parameter boxes: tolerances written ``"[lo, hi]"`` or ``"mid +- rad"``, split and measured exactly.

A box assigns each of some parameters a closed interval [lo, hi] with exact rational endpoints (the
other parameters stay points). A claim about a box is a statement for every parameter value in it;
a kind decides such a statement on balls that contain the whole box (:meth:`Box.ball`).

Guarantee: endpoints are exact rationals parsed by :func:`~rigor_gyro.core.exact.parse_exact` (never
floats); :meth:`Box.ball` returns, at the current precision, a ball containing every point of the
interval; :meth:`Box.split` halves an edge at its exact midpoint, so the two halves cover the box
and their volumes add up exactly; :meth:`Box.midpoint` is an exact point of the box.

Fails when: the text is neither a number, ``[lo, hi]`` nor ``mid +- rad``; lo > hi; rad < 0; an
endpoint involves pi (a tolerance must be rational): :class:`ParameterError` naming the parameter.
An interval with lo == hi is a point (allowed).

Example:
    >>> parse_tolerance("[0.132, 0.134]", "B")
    (Fraction(33, 250), Fraction(67, 500))
    >>> parse_tolerance("0.15 +- 0.01", "S")
    (Fraction(7, 50), Fraction(4, 25))
    >>> parse_tolerance("0.15", "S") is None
    True
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from .balls import ball_key
from .errors import ParameterError
from .exact import parse_exact

__all__ = ["Box", "parse_tolerance", "is_tolerance", "split_parameters", "fraction_text", "exact_decimal", "tiles_by_bisection",
           "even_in"]

_BRACKET = re.compile(r"^\[\s*([^,\[\]]+?)\s*,\s*([^,\[\]]+?)\s*\]$")
_PLUS_MINUS = re.compile(r"^(.+?)\s*(?:\+-|\+/-|±)\s*(.+)$")


def is_tolerance(value: object) -> bool:
    """Whether a parameter value is written as an interval (``[lo, hi]`` or ``mid +- rad``)."""
    return isinstance(value, str) and (value.strip().startswith("[") or any(t in value for t in ("+-", "+/-", "±")))


def _rational(text: str, name: str, what: str) -> Fraction:
    x = parse_exact(text, name)
    if not x.is_rational:
        raise ParameterError(f"parameter {name!r}: the {what} {text!r} of a tolerance must be rational (no pi)")
    return x.rational


def parse_tolerance(value: object, name: str) -> tuple[Fraction, Fraction] | None:
    """(lo, hi) of a parameter written as an interval, exactly; None when it is a plain number."""
    if not is_tolerance(value):
        return None
    text = value.strip()
    m = _BRACKET.match(text)
    if m:
        lo, hi = _rational(m.group(1), name, "lower end"), _rational(m.group(2), name, "upper end")
        if lo > hi:
            raise ParameterError(f"parameter {name!r} = {value!r}: the lower end exceeds the upper end (need lo <= hi)")
        return lo, hi
    if text.startswith("["):
        raise ParameterError(f"parameter {name!r} = {value!r}: write an interval as \"[lo, hi]\" with two exact "
                             "numbers, e.g. \"[0.132, 0.134]\"")
    m = _PLUS_MINUS.match(text)
    if not m:
        raise ParameterError(f"parameter {name!r} = {value!r}: write a tolerance as \"mid +- rad\", e.g. \"0.15 +- 0.01\"")
    mid, rad = _rational(m.group(1), name, "midpoint"), _rational(m.group(2), name, "radius")
    if rad < 0:
        raise ParameterError(f"parameter {name!r} = {value!r}: the radius must be >= 0")
    return mid - rad, mid + rad


def fraction_text(q: Fraction) -> str:
    """An exact rational as text that :func:`parse_exact` reads back to the same value."""
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def exact_decimal(q: Fraction) -> str:
    """``q`` as a terminating decimal when it has one (the exact value, every digit), else ``p/q``."""
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d, twos = d // 2, twos + 1
    while d % 5 == 0:
        d, fives = d // 5, fives + 1
    if d != 1:
        return f"{q.numerator}/{q.denominator}"
    n = max(twos, fives)
    scaled = q * 10 ** n                     # an integer
    sign = "-" if scaled < 0 else ""
    digits = str(abs(scaled.numerator)).rjust(n + 1, "0")
    whole, frac = digits[:len(digits) - n], digits[len(digits) - n:]
    return sign + whole + ("." + frac if n else "")


def _ball(lo: Fraction, hi: Fraction) -> arb:
    a = arb(fmpq(lo.numerator, lo.denominator))
    return a if lo == hi else a.union(arb(fmpq(hi.numerator, hi.denominator)))


@dataclass(frozen=True)
class Box:
    """Closed intervals with exact rational endpoints, in a fixed parameter order."""

    edges: tuple[tuple[str, Fraction, Fraction], ...]

    @classmethod
    def of(cls, intervals: dict[str, tuple[Fraction, Fraction]]) -> "Box":
        return cls(tuple((k, Fraction(lo), Fraction(hi)) for k, (lo, hi) in intervals.items()))

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(k for k, _, _ in self.edges)

    def interval(self, name: str) -> tuple[Fraction, Fraction]:
        for k, lo, hi in self.edges:
            if k == name:
                return lo, hi
        raise KeyError(name)

    def ball(self, name: str) -> arb:
        """A ball containing the whole interval of ``name`` (at the current precision)."""
        return _ball(*self.interval(name))

    def balls(self) -> dict[str, arb]:
        """{name: :meth:`ball`} for every edge, in the box's order (one pass over the edges)."""
        return {k: _ball(lo, hi) for k, lo, hi in self.edges}

    def midpoint(self) -> dict[str, Fraction]:
        return {k: (lo + hi) / 2 for k, lo, hi in self.edges}

    def intersection(self, other: "Box") -> "Box | None":
        """The common part of two closed boxes over the same parameters (exact), or None when they share no
        point (touching boxes share a face, an edge or a corner)."""
        edges = tuple((n, max(alo, blo), min(ahi, bhi))
                      for (n, alo, ahi), (_, blo, bhi) in zip(self.edges, other.edges))
        return Box(edges) if all(lo <= hi for _, lo, hi in edges) else None

    def volume(self) -> Fraction:
        """The product of the nonzero edge widths (degenerate edges do not count)."""
        v = Fraction(1)
        for _, lo, hi in self.edges:
            if hi > lo:
                v *= hi - lo
        return v

    def relative_widths(self, whole: "Box") -> dict[str, Fraction]:
        """Each edge's width as a fraction of the same edge in ``whole`` (0 for a point edge)."""
        out = {}
        for k, lo, hi in self.edges:
            wlo, whi = whole.interval(k)
            out[k] = (hi - lo) / (whi - wlo) if whi > wlo else Fraction(0)
        return out

    def split(self, whole: "Box", frozen: tuple[str, ...] = ()) -> tuple["Box", "Box"]:
        """The two halves along the edge that is widest relative to ``whole`` (first such edge on ties),
        never along a ``frozen`` edge (a parameter the claims do not depend on). Exact: the relative widths
        are compared as integer cross products and the midpoint is one Fraction of integers (the same
        choice and midpoint as Fraction arithmetic, at a fraction of its cost: issue 41)."""
        wide = {k: (lo, hi) for k, lo, hi in whole.edges}
        best_k, bn, bd = None, 0, 1
        for k, lo, hi in self.edges:
            if k in frozen:
                continue
            wlo, whi = wide[k]
            if whi > wlo:
                ln, ld, hn, hd = lo.numerator, lo.denominator, hi.numerator, hi.denominator
                Ln, Ld, Hn, Hd = wlo.numerator, wlo.denominator, whi.numerator, whi.denominator
                # (hi - lo) / (whi - wlo) = ((hn ld - ln hd) Ld Hd) / (hd ld (Hn Ld - Ln Hd)), denominators > 0
                rn, rd = (hn * ld - ln * hd) * Ld * Hd, hd * ld * (Hn * Ld - Ln * Hd)
            else:
                rn, rd = 0, 1
            if best_k is None or rn * bd > bn * rd:
                best_k, bn, bd = k, rn, rd
        if best_k is None:
            raise ValueError("every edge of the box is frozen")
        if bn == 0:
            raise ValueError("a box of points cannot be split")
        lo, hi = self.interval(best_k)
        mid = Fraction(lo.numerator * hi.denominator + hi.numerator * lo.denominator, 2 * lo.denominator * hi.denominator)
        left = tuple((n, a, mid) if n == best_k else (n, a, b) for n, a, b in self.edges)
        right = tuple((n, mid, b) if n == best_k else (n, a, b) for n, a, b in self.edges)
        return Box(left), Box(right)

    def to_json(self) -> dict[str, list[str]]:
        return {k: [fraction_text(lo), fraction_text(hi)] for k, lo, hi in self.edges}

    @classmethod
    def from_json(cls, data: dict[str, list[str]]) -> "Box":
        return cls(tuple((k, Fraction(v[0]), Fraction(v[1])) for k, v in data.items()))


def split_parameters(parameters: dict[str, object]) -> tuple[dict[str, object], Box]:
    """Separate a scene's parameters into the points (as written) and the box of the tolerances."""
    points, edges = {}, {}
    for k, v in parameters.items():
        t = parse_tolerance(v, k)
        if t is None:
            points[k] = v
        else:
            edges[k] = t
    return points, Box.of(edges)


def tiles_by_bisection(whole: Box, boxes: list[Box], frozen: tuple[str, ...] = ()) -> bool:
    """Whether ``boxes`` are exactly the leaves of a bisection tree of ``whole`` (:meth:`Box.split`'s
    rule): then they cover ``whole`` and meet only on faces. Exact; linear in the number of boxes."""
    want = {b.edges for b in boxes}
    if len(want) != len(boxes):
        return False
    seen, budget = 0, 2 * len(boxes) + 1       # a valid tree has len(boxes) - 1 inner nodes
    stack = [whole]
    while stack:
        node = stack.pop()
        budget -= 1
        if budget < 0:
            return False
        if node.edges in want:
            seen += 1
            continue
        if all(hi == lo for n, lo, hi in node.edges if n not in frozen):
            return False
        stack.extend(node.split(whole, frozen))
    return seen == len(boxes)


def even_in(f, name: str):
    """Wrap a box function ``f`` ({coordinate: ball} -> ball) that is even in the coordinate ``name``
    (its value at x and at x with ``name`` negated are the same for every x): a box whose ``name`` ball
    has a negative midpoint is evaluated as its mirror image (that ball negated, exactly: the other
    balls the same), and each box's ball is kept, so a box and its mirror image cost one evaluation.

    Guarantee: the set of values of f over a box and over its mirror image are the same set, so the
    ball ``f`` gives on one encloses f over the other. Every caller that wraps the same ``f`` (a prover
    and a checker) gets the very same ball for a box and its mirror image: the canonical image is
    evaluated either way. The evenness is the caller's theorem about ``f``; it is not checked here (a
    caller that cannot prove it must not wrap).

    Fails when: never; non-finite balls are passed to ``f`` as they are and not kept."""
    cache: dict = {}

    def g(balls: dict):
        if not all(b.is_finite() for b in balls.values()):
            return f(balls)
        b = balls[name]
        if b.mid() < 0:
            balls = {**balls, name: -b}
        key = tuple((k, *ball_key(balls[k])) for k in sorted(balls))
        hit = cache.get(key)
        if hit is None:
            hit = cache[key] = f(balls)
        return hit
    return g
