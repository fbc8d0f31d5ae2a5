"""The Halton low-discrepancy sequence in exact rationals, and volume-weighted points in a union of boxes.

:func:`halton` gives the i-th point of the d-dimensional Halton sequence (radical inverses of i in the
first d primes) as exact :class:`~fractions.Fraction` coordinates in [0, 1): no random state, no floats, so
the same index gives the same point on every machine. :func:`points_in_boxes` maps the sequence onto a
union of boxes (disjoint up to faces, e.g. the leaves of a paving) with one more dimension than the
boxes have edges: the first coordinate (base 2) picks a box by its share of the total volume (exact
cumulative volumes), the others (bases 3, 5, ...) place the point in that box. The points are therefore
spread over the union in proportion to volume: box k receives about N vol_k / vol points of the first N,
and the positions inside the boxes are themselves low-discrepancy. (Reusing the first coordinate inside
the chosen box would be degenerate: with 2^m equal boxes it takes only a few values there.)

Guarantee: every point returned lies in the closed box it is reported with (exact arithmetic), and the
report is the first box (in the given order) whose volume share contains the point's first coordinate.
Precision: exact. Fails when: more than ``MAX_DIMENSION - 1`` parameters, or every box of zero volume (an
empty union): ValueError. A box of zero volume among others is never chosen.
"""
from __future__ import annotations

from bisect import bisect_right
from fractions import Fraction
from typing import Iterator

from .boxes import Box

__all__ = ["PRIMES", "MAX_DIMENSION", "radical_inverse", "halton", "points_in_boxes"]

PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53, 59, 61, 67, 71)
MAX_DIMENSION = len(PRIMES)


def radical_inverse(i: int, base: int) -> Fraction:
    """The base-``base`` digits of ``i >= 0`` mirrored about the radix point: exact, in [0, 1)."""
    if i < 0 or base < 2:
        raise ValueError("radical_inverse needs i >= 0 and base >= 2")
    num, den = 0, 1
    while i:
        i, digit = divmod(i, base)
        num, den = num * base + digit, den * base
    return Fraction(num, den)


def halton(i: int, dimension: int) -> tuple[Fraction, ...]:
    """The i-th point (i >= 0; 0 is the origin) of the Halton sequence in [0, 1)^dimension, exactly."""
    if not 1 <= dimension <= MAX_DIMENSION:
        raise ValueError(f"halton: dimension must be in 1..{MAX_DIMENSION} (got {dimension})")
    return tuple(radical_inverse(i, PRIMES[k]) for k in range(dimension))


def points_in_boxes(boxes: list[Box], count: int, start: int = 1) -> Iterator[tuple[int, dict[str, Fraction]]]:
    """(index of the box, exact point in it) for Halton indices ``start`` .. ``start + count - 1`` mapped
    onto the union of ``boxes`` (all over the same parameters, in the same order) in proportion to volume
    (see the module docstring). Zero-width edges stay at their value."""
    if not boxes:
        return
    vols = [b.volume() if any(hi > lo for _, lo, hi in b.edges) else Fraction(0) for b in boxes]
    cum, total = [], Fraction(0)
    for v in vols:
        total += v
        cum.append(total)
    if total <= 0:
        raise ValueError("points_in_boxes: the boxes have no volume")
    names = boxes[0].names
    for i in range(start, start + count):
        u = halton(i, len(names) + 1)
        k = bisect_right(cum, u[0] * total)   # cum[k-1] <= u0 total < cum[k], so vols[k] > 0
        box = boxes[k]
        point = {}
        for n, t in zip(names, u[1:]):
            lo, hi = box.interval(n)
            point[n] = lo + t * (hi - lo)
        yield k, point
