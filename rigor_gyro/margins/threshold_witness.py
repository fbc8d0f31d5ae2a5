"""Witnesses of a robust threshold: points of the other parameters' box where the claim fails.

A threshold search whose scene has other parameters as tolerances decides each step over their box: proved
means for every point of it (a paving), refuted means at some point of it. Near the robust threshold the set
of failing points shrinks to a sliver at a face or corner of the box, far below the paving's resolution: the
paving leaves it undecided and the search used to stop there (a bracket of 1e-4 where 1e-6 was asked). This
module keeps the points that refuted the claim and proposes new ones, so a refuted step costs one point proof:

* :meth:`Witnesses.refute` tries the kept witnesses at the new value of the searched parameter (point proofs,
  the path of ``rigor-gyro prove``), then, after an inconclusive paving, the corners of its undecided leaves
  (the failing sliver of a claim monotone in a box parameter lies at a face, so at a corner of some leaf), at
  most :data:`MAX_CORNER_PROOFS` point proofs;
* the point that refutes is kept, most recent first, at most :data:`KEEP`.

Guarantee: a step is refuted only by a point proof that refutes the claim at the exact point
{searched parameter = value, box parameters = the witness}, and the witness lies in the box (checked exactly):
a certified counterexample to "the claim holds for every point of the box". Nothing here proves a step.
Failure mode: no witness refutes: the step stays what the paving said (inconclusive), never refuted.
Precision: the point prover's default ladder.
"""
from __future__ import annotations

import itertools
from fractions import Fraction
from typing import Any

from ..core.boxes import Box, fraction_text

__all__ = ["Witnesses", "KEEP", "MAX_CORNER_PROOFS", "in_box", "point_status"]

#: witnesses kept (most recent first)
KEEP = 4
#: point proofs at corners of undecided leaves after one inconclusive paving
MAX_CORNER_PROOFS = 16
#: a leaf with more varying edges than this offers its two extreme corners and its midpoint, not all 2^d corners
CORNER_DIMS = 3


def in_box(box: Box, point: dict[str, Fraction]) -> bool:
    """Whether ``point`` names exactly the box's parameters and lies in it (exact comparisons)."""
    return set(point) == set(box.names) and all(lo <= point[k] <= hi for k, lo, hi in box.edges)


def point_status(scene, param: str, value: Fraction, claim: str, point: dict[str, Fraction],
                 seconds: float | None = None) -> tuple[str, str]:
    """The point prover on ``claim`` at {param: value, box parameters: point, the scene's other numbers}."""
    from ..prover import prove_scene
    from ..scene import Scene
    from .paving import box_scene
    bs = box_scene(scene)
    params = {**bs.point_parameters(point), param: fraction_text(value)}
    s = Scene(name=scene.name, kind=scene.kind, source=scene.source, parameters=params, claims_only=[claim],
              options=dict(bs.options), model=dict(scene.model))
    c = prove_scene(s, time_limit=seconds).claim(claim)
    return c.status.value, c.reason


def _corners(leaf: Box) -> list[dict[str, Fraction]]:
    varying = [(k, lo, hi) for k, lo, hi in leaf.edges if lo != hi]
    fixed = {k: lo for k, lo, hi in leaf.edges if lo == hi}
    if len(varying) <= CORNER_DIMS:
        return [{**fixed, **{k: c for (k, _, _), c in zip(varying, ends)}}
                for ends in itertools.product(*((lo, hi) for _, lo, hi in varying))]
    return [{**fixed, **{k: lo for k, lo, _ in varying}}, {**fixed, **{k: hi for k, _, hi in varying}},
            leaf.midpoint()]


class Witnesses:
    """The failing points of one robust threshold search (module docstring)."""

    def __init__(self) -> None:
        self.points: list[dict[str, Fraction]] = []

    def keep(self, point: dict[str, Fraction]) -> None:
        self.points = [point] + [p for p in self.points if p != point][:KEEP - 1]

    def refute(self, scene, param: str, value: Fraction, claim: str, leaves: list[Box] | None, budget) \
            -> tuple[dict[str, Fraction], str] | None:
        """(witness, reason) where a point proof refutes the claim at ``value``: the kept witnesses first, then
        (``leaves``: the undecided leaves of an inconclusive paving) their corners; None when none does."""
        from .paving import box_scene
        box = box_scene(scene).box
        tried: list[dict[str, Fraction]] = []
        queue = list(self.points)
        for leaf in leaves or []:
            queue += _corners(leaf)
        corner_budget = MAX_CORNER_PROOFS
        for point in queue:
            if point in tried or not in_box(box, point):
                continue
            if point not in self.points:
                if corner_budget == 0:
                    break
                corner_budget -= 1
            if budget is not None and budget.expired():
                return None
            tried.append(point)
            st, why = point_status(scene, param, value, claim, point,
                                   budget.remaining() if budget is not None else None)
            if st == "refuted":
                self.keep(point)
                return point, why
        return None


def witness_json(point: dict[str, Fraction]) -> dict[str, Any]:
    return {k: fraction_text(v) for k, v in sorted(point.items())}
