"""Prove a scene: validate it, run its kind at escalating precision, assemble the certificate.

Every kind provides the interface of :mod:`rigor_gyro.kinds` (``CLAIMS``, ``validate``, ``attempt``
returning a :class:`rigor_gyro.kinds.Attempt`).

Guarantee: :func:`prove_scene` returns the first attempt in which every requested claim is decided
(proved or refuted), every requested width is met and every audit row is decided, trying
prec, 2 prec, ... <= maxprec; otherwise the attempt at the highest precision, whose undecided claims
say ``inconclusive`` with the hint to raise ``--maxprec``. Each claim records the lowest precision at
which it already had its final status.
"""
from __future__ import annotations

import time

from .certificate import Certificate
from .core.balls import DEFAULT_MAXPREC, DEFAULT_PREC, check_precision, escalate
from .core.errors import ParameterError, SceneError
from .core.outcome import Status
from .kinds import Attempt, kind_module
from .scene import Scene

__all__ = ["prove_scene", "requested_claims"]


def requested_claims(scene: Scene, available: dict[str, str]) -> list[str]:
    """The claim ids the scene asks for (default: all of its kind), in the kind's order."""
    if scene.claims_only is None:
        return list(available)
    unknown = [c for c in scene.claims_only if c not in available]
    if unknown:
        raise SceneError(f"scene {scene.name!r}: unknown claim(s) {unknown}; this kind has {list(available)}")
    return [c for c in available if c in scene.claims_only]


def prove_scene(scene: Scene, *, prec: int = DEFAULT_PREC, maxprec: int = DEFAULT_MAXPREC) -> Certificate:
    """Prove ``scene``; see the module docstring. Bad input raises before any computation:
    :class:`SceneError` (not a Scene, unknown kind or claim) or :class:`ParameterError` (parameters,
    options, precisions out of range)."""
    if not isinstance(scene, Scene):
        raise SceneError(f"prove_scene needs a Scene (from load_scene or parse_scene), got {type(scene).__name__}")
    check_precision(prec, "prec")
    check_precision(maxprec, "maxprec")
    if maxprec < prec:
        raise ParameterError(f"maxprec ({maxprec}) must be >= prec ({prec})")
    module = kind_module(scene.kind)
    model = module.validate(scene)
    wanted = requested_claims(scene, module.CLAIMS)
    history: list[tuple[int, Attempt]] = []
    t0 = time.perf_counter()

    def run(p: int) -> Attempt:
        a = module.attempt(model, wanted, p)
        history.append((p, a))
        return a

    esc = escalate(run, lambda a: a.settled or a.stalled, prec=prec, maxprec=maxprec)
    elapsed = time.perf_counter() - t0
    final = esc.result
    for claim in final.claims:
        claim.precision_bits = esc.prec
        for p, a in history:
            same = [c for c in a.claims if c.id == claim.id and c.status is claim.status]
            if same and claim.status is not Status.INCONCLUSIVE:
                claim.precision_bits = p
                break
        if claim.status is Status.INCONCLUSIVE:
            hint = ("more precision does not help here (see the reason)" if final.stalled and not final.settled
                    else f"try --maxprec {2 * maxprec}")
            claim.reason += f" [undecided at every precision tried: {esc.tried} bits; {hint}]"
    notes = list(final.notes)
    if not esc.done and final.widths_met is False:
        notes.append(f"requested enclosure widths not met by {esc.prec} bits: try --maxprec {2 * maxprec}")
    return Certificate(scene=scene.header(), precision_bits=esc.prec, claims=final.claims,
                       quantities=final.quantities, paper=final.paper,
                       timings={"total_s": round(elapsed, 4)}, precisions_tried=esc.tried,
                       formulas=final.formulas, notes=notes, extra=final.extra)
