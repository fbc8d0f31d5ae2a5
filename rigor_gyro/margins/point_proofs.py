"""The point prover on one claim at one exact parameter point, as a task for an executor (strings in,
plain data out): what pavings, their checker and the counterexample search ask at single points.

Guarantee: the status, reason and precision are the point prover's own (``rigor-gyro prove`` on a scene
of that point with that one claim), from ``prec`` up to ``maxprec`` bits; except at a point where the scene is
bad input (the model has no value there: a division by zero, a singular M): that point is ``inconclusive``
with the refusal as its reason (never refuted, never proved), not bad input for the whole box.
"""
from __future__ import annotations

import json
from typing import Any

from ..core.balls import DEFAULT_MAXPREC, DEFAULT_PREC
from ..core.errors import ParameterError
from .models import task_scene

__all__ = ["point_task", "spread"]


def point_task(kind: str, params_json: str, options_json: str, claim: str, prec: int = DEFAULT_PREC,
               maxprec: int = DEFAULT_MAXPREC) -> dict[str, Any]:
    """The point prover on one claim at one exact parameter point, from ``prec`` up to ``maxprec`` bits; a
    point where the scene is bad input is ``inconclusive`` with the refusal as its reason (see the module
    docstring), its precision ``prec``."""
    from ..prover import prove_scene
    scene = task_scene("point", kind, "margin point", json.loads(params_json), options_json, [claim])
    try:
        c = prove_scene(scene, prec=prec, maxprec=maxprec).claim(claim)
    except ParameterError as e:
        return {"status": "inconclusive", "precision_bits": prec,
                "reason": f"no value at this point, so neither a counterexample nor a proof (the scene is bad input "
                          f"here: {e})"}
    return {"status": c.status.value, "reason": c.reason, "precision_bits": c.precision_bits}


def spread(items: list, k: int) -> list:
    """``k`` of ``items`` evenly spread over the list, its first and last included (all of them when ``k`` >= their
    number; the middle one when ``k`` = 1): where a paving proves its sub-boxes' midpoints point by point, so that
    the points sample the whole box and not only its first sub-boxes in order."""
    n = len(items)
    if k >= n:
        return list(items)
    if k <= 0:
        return []
    if k == 1:
        return [items[n // 2]]
    return [items[(i * (n - 1) + (k - 1) // 2) // (k - 1)] for i in range(k)]
