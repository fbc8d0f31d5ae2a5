"""The paving checker's second path: decided sub-boxes cross-checked by the point prover at points.

The checker re-evaluates every decided sub-box with the kind's box rigour (``kinds/<kind>/boxes.py`` and
the parametric forms it calls): a bug in that code would be re-evaluated, and confirmed, by the same
code. This module asks code that shares none of it, the kind's point prover (``kinds/<kind>/claims.py``
on exact rational parameters, the path ``rigor-gyro prove`` takes), at points of the decided sub-boxes:

* every sub-box when a claim has at most ``count`` decided ones, otherwise ``count`` of them spread
  evenly over the stored order (the first and the last always among them);
* in each, its midpoint and its two extreme corners (every edge at its lower end; every edge at its
  upper end), where a box rigour that dropped part of its box would fail first.

A point proof *contradicts* its sub-box when it refutes the claim inside a sub-box stored as proved,
or proves it inside one stored as refuted (a claim refuted over a box fails at every point of it).
An inconclusive point proof (a precision cap, a budget) is no evidence either way and is counted as
such; a point the point prover refuses as bad input is counted with it, named in the message.

Guarantee: a contradiction is certain (both verdicts come from Arb enclosures), so the check fails.
No contradiction is evidence, not proof, that the box rigour is right away from the sampled points: the
message says how many points of how many sub-boxes were asked.

Cost: up to 3 ``count`` point proofs of one claim per claim (``count`` = :data:`SAMPLED_BOXES` by default,
``rigor-gyro check --samples N``; 0 turns this check off).
"""
from __future__ import annotations

import json
from fractions import Fraction
from typing import Any, Callable

from ..core.boxes import Box
from ..core.errors import RigorGyroError

__all__ = ["SAMPLED_BOXES", "chosen", "sample_points", "cross_check"]

#: decided sub-boxes per claim that the point prover is asked at, by default
SAMPLED_BOXES = 8


def chosen(boxes: list[Any], count: int) -> list[Any]:
    """``count`` of ``boxes`` spread evenly over their order (all of them when there are at most ``count``)."""
    n = len(boxes)
    if count <= 0 or n == 0:
        return []
    if n <= count:
        return list(boxes)
    if count == 1:
        return [boxes[0]]
    return [boxes[(i * (n - 1)) // (count - 1)] for i in range(count)]


def sample_points(box: Box) -> list[tuple[str, dict[str, Fraction]]]:
    """The midpoint and the two extreme corners of ``box``, named; a degenerate box (no width) gives one."""
    lower = {n: box.interval(n)[0] for n in box.names}
    upper = {n: box.interval(n)[1] for n in box.names}
    out = [("midpoint", box.midpoint()), ("lower corner", lower), ("upper corner", upper)]
    seen, unique = set(), []
    for name, p in out:
        key = tuple(sorted(p.items()))
        if key not in seen:
            seen.add(key)
            unique.append((name, p))
    return unique


#: the point status that contradicts a sub-box status
_CONTRADICTS = {"proved": "refuted", "refuted": "proved"}


def cross_check(claim: str, decided: list[tuple[Box, str]], count: int,
                prove_at: Callable[[dict[str, Fraction]], str]) -> tuple[bool, str]:
    """(ok, message): the point prover, ``prove_at(point) -> status``, asked at :func:`sample_points` of
    :func:`chosen` decided sub-boxes of ``claim`` (see the module docstring)."""
    if count <= 0:
        return True, "not cross-checked by the point prover (check --samples 0)"
    picked = chosen([x for x in decided if x[1] in _CONTRADICTS], count)
    if not picked:
        return True, "no decided sub-box to cross-check by the point prover"
    asked, agree, open_, refused = 0, 0, 0, []
    for box, status in picked:
        for where, point in sample_points(box):
            asked += 1
            try:
                got = prove_at(point)
            except RigorGyroError as e:
                refused.append(f"{where} of {json.dumps(box.to_json())}: {e}")
                continue
            if got == _CONTRADICTS[status]:
                return False, (f"the point prover {got} the claim at the {where} "
                               f"{ {k: str(v) for k, v in point.items()} } of a sub-box stored {status} "
                               f"({json.dumps(box.to_json())}): the box rigour and the point rigour disagree")
            if got == status:
                agree += 1
            else:
                open_ += 1
    total = sum(1 for x in decided if x[1] in _CONTRADICTS)
    msg = (f"the point prover (code apart from the box rigour) agrees at {agree} of {asked} points of {len(picked)} "
           f"of the {total} decided sub-boxes (midpoints and extreme corners); {open_} inconclusive there")
    if refused:
        msg += f"; {len(refused)} refused as bad input (first: {refused[0]})"
    return True, msg
