"""Prove a scene: validate it, run its kind at escalating precision, assemble the certificate.

Every kind provides the interface of :mod:`rigor_gyro.kinds` (``CLAIMS``, ``validate``, ``attempt``
returning a :class:`rigor_gyro.kinds.Attempt`).

Guarantee: :func:`prove_scene` returns the first attempt in which every requested claim is decided
(proved or refuted), every requested width is met and every audit row is decided, trying
p0, 2 p0, ... <= maxprec, where p0 is prec doubled while it is below what the scene's ``rel_width``
needs (log2(1 / rel_width) + 8 bits: an attempt that cannot meet the width is not run); otherwise
the attempt at the highest precision, whose undecided claims say ``inconclusive`` with the hint to
raise ``--maxprec``. Each claim records the lowest precision, among those tried, at which it already
had its final status.

Time limit: with ``time_limit`` (seconds of wall clock), escalation stops when it runs out; an attempt
still running then is interrupted (Unix main thread; elsewhere the limit is checked between attempts),
and the certificate is the last attempt that finished, its undecided claims inconclusive with the reason
"time limit". When no attempt finished, every requested claim is inconclusive for that reason (nothing
is decided, so nothing is lost: a budget never refutes).
"""
from __future__ import annotations

import math
import time
from fractions import Fraction
from typing import Callable

from flint import arb

from .certificate import Certificate
from .core.balls import DEFAULT_MAXPREC, DEFAULT_PREC, Escalation, check_precision, escalate
from .core.deadline import TimeLimitReached, check_time_limit, time_limit as _time_limit
from .core.errors import ParameterError, SceneError
from .core.outcome import AuditStatus, Claim, Status
from .kinds import Attempt, Phases, claim_statements, kind_module, scene_claims
from .scene import Scene

__all__ = ["prove_scene", "requested_claims"]


def requested_claims(scene: Scene, available: dict[str, str], every: dict[str, str] | None = None) -> list[str]:
    """The claim ids the scene asks for, in the kind's order: by default ``available`` (the kind's
    ``CLAIMS``); with ``claims_only``, those of ``every`` (the kind's ``ALL_CLAIMS``, which adds the opt-in
    claims a scene must name; default ``available``) that it names."""
    every = every or available
    if scene.claims_only is None:
        return list(available)
    unknown = [c for c in scene.claims_only if c not in every]
    if unknown:
        raise SceneError(f"scene {scene.name!r}: unknown claim(s) {unknown}; this kind has {list(every)}")
    return [c for c in every if c in scene.claims_only]


def _stuck(before: arb | None, after: arb | None, prec: int) -> str | None:
    """Why doubling the precision did not help the undecided ball (``before`` at prec/2, ``after`` at
    prec), or None when it still may: the ball did not shrink by at least half, or it stayed unbounded
    (infinite radius at both; NaN, no information, may still progress). (A ball that shrinks around 0
    is not taken as "exactly 0": a tiny nonzero margin is decided by more precision; exact equalities
    are decided exactly by the kinds.)"""
    if before is None or after is None:
        return None
    if not (before.is_finite() or after.is_finite() or before.is_nan() or after.is_nan()):
        return ("doubling the precision left the deciding enclosure unbounded (most likely a subdivision budget "
                "or a search limits it, not the precision: raise the scene's max_pieces; the escalation stops "
                "here whatever --maxprec is)")
    if not (before.is_finite() and after.is_finite()):
        return None
    r0, r1 = before.rad(), after.rad()
    if not (2 * r1 < r0) and not (r0.is_zero() and not r1.is_zero()):
        return ("doubling the precision did not shrink the deciding enclosure (its width is set by a "
                "subdivision tolerance or budget, or by an exact degeneracy, not by the precision)")
    return None


def _final(a: Attempt, item: str) -> bool:
    c = next((c for c in a.claims if c.id == item), None)
    return c is not None and bool(c.precision_cannot_help)


def no_progress(prev: tuple[int, Attempt], now: tuple[int, Attempt]) -> dict[str, str] | None:
    """If nothing undecided at ``now`` can be helped by more precision, {item: why} (items: claim ids,
    ``widths``, ``row:<id>``); None as soon as one undecided item may still progress.

    The kinds say what decides an inconclusive claim (``Claim.decides``); a claim without it, a
    width requirement without ``width_quantities`` or an audit row without a value may always progress."""
    (p0, a0), (p1, a1) = prev, now
    why: dict[str, str] = {}
    before = {c.id: c for c in a0.claims}
    for c in a1.claims:
        if c.status is not Status.INCONCLUSIVE:
            continue
        if c.precision_cannot_help:
            why[c.id] = c.precision_cannot_help
            continue
        b = before.get(c.id)
        reason = _stuck(b.decides if b is not None and b.status is Status.INCONCLUSIVE else None, c.decides, p1)
        if reason is None:
            return None
        why[c.id] = reason
    if not a1.widths_met:
        if not a1.width_quantities:
            return None
        shrinking = [n for n in a1.width_quantities
                     if n in a0.quantities and n in a1.quantities
                     and _stuck(a0.quantities[n], a1.quantities[n], p1) is None]
        if shrinking:
            return None
        why["widths"] = (f"the widths of {', '.join(a1.width_quantities)} did not shrink from {p0} to {p1} bits "
                         "(set by a subdivision tolerance: relax option rel_width)")
    rows0 = {r.id: r for r in a0.paper}
    for r in a1.paper:
        if r.status is AuditStatus.UNDECIDED:
            r0 = rows0.get(r.id)
            reason = _stuck(r0.value if r0 is not None else None, r.value, p1)
            if reason is None:
                return None
            why[f"row:{r.id}"] = reason
    return why if why else None


def _piece_counts(claims) -> dict[str, int]:
    """Per claim, the subdivision piece counts its details record (keys ending in ``pieces``)."""
    out = {}
    for c in claims:
        for k, v in c.details.items():
            if k.endswith("pieces") and isinstance(v, int) and not isinstance(v, bool):
                out[f"{c.id}.{k}"] = v
    return out


#: bits beyond log2(1 / rel_width) that an attempt needs before it can meet the width (the roundings of
#: a few dozen operations); below that an attempt is certain to be thrown away
WIDTH_GUARD_BITS = 8


def starting_precision(model, prec: int, maxprec: int) -> int:
    """``prec`` doubled (up to ``maxprec``) while it is below log2(1 / rel_width) + WIDTH_GUARD_BITS, for a
    model with a ``rel_width`` option; ``prec`` otherwise. The schedule stays prec * 2^j."""
    rel = getattr(model, "rel_width", None)
    if rel is None:
        return prec
    q = rel.rational if hasattr(rel, "rational") else Fraction(int(rel.p), int(rel.q))
    if q <= 0:
        return prec
    need = math.ceil(math.log2(q.denominator) - math.log2(q.numerator)) + WIDTH_GUARD_BITS
    p = prec
    while p < need and 2 * p <= maxprec:
        p *= 2
    return p


def prove_scene(scene: Scene, *, prec: int = DEFAULT_PREC, maxprec: int = DEFAULT_MAXPREC,
                time_limit: float | None = None, progress: Callable[[str, int], None] | None = None) -> Certificate:
    """Prove ``scene``; see the module docstring. ``progress(phase, bits)``, if given, is told each phase
    (a claim or a stage) of each attempt as it starts (display only). Bad input raises before any computation:
    :class:`SceneError` (not a Scene, unknown kind or claim) or :class:`ParameterError` (parameters,
    options, precisions, time limit out of range)."""
    if not isinstance(scene, Scene):
        raise SceneError(f"prove_scene needs a Scene (from load_scene or parse_scene), got {type(scene).__name__}")
    from .core.boxes import is_tolerance
    boxed = [(k, v) for k, v in scene.parameters.items() if is_tolerance(v)]
    if boxed:
        k, v = boxed[0]
        raise ParameterError(f"scene {scene.name!r} has tolerances (parameter {k} = {v!r}): prove_scene proves one "
                             "point; pave the box with rigor_gyro.pave(rigor_gyro.box_scene(scene)) (and "
                             f"rigor_gyro.write_paving), or run `rigor-gyro prove` on the scene file")
    check_precision(prec, "prec")
    check_precision(maxprec, "maxprec")
    if maxprec < prec:
        raise ParameterError(f"maxprec ({maxprec}) must be >= prec ({prec})")
    try:
        time_limit = check_time_limit(time_limit, "time_limit")
    except ValueError as e:
        raise ParameterError(str(e)) from None
    module = kind_module(scene.kind)
    model = module.validate(scene)
    wanted = requested_claims(scene, *scene_claims(module, scene))
    history: list[tuple[int, Attempt]] = []
    t0 = time.perf_counter()

    attempt_seconds: list[list] = []

    def run(p: int) -> Attempt:
        t = time.perf_counter()
        if progress is not None:
            progress("", p)
            Phases.listener = lambda phase: progress(phase, p)
        try:
            a = module.attempt(model, wanted, p)
        finally:
            Phases.listener = None
        attempt_seconds.append([p, round(time.perf_counter() - t, 4)])
        history.append((p, a))
        return a

    hopeless: dict[str, str] = {}

    def done(a: Attempt) -> bool:
        if a.settled or a.stalled or budget.expired():
            return True
        if len(history) < 2:
            return False
        why = no_progress(history[-2], history[-1])
        # a claim that rests on a refuted one, or on a restricted search, is final at once; a deciding
        # ball must stop shrinking over two doublings running before escalation stops for it
        if why is not None and (all(_final(history[-1][1], k) for k in why)
                                or len(history) >= 3 and no_progress(history[-3], history[-2]) is not None):
            hopeless.update(why)
            return True
        return False

    p0 = starting_precision(model, prec, maxprec)
    with _time_limit(time_limit) as budget:
        try:
            esc = escalate(run, done, prec=p0, maxprec=maxprec)
        except TimeLimitReached:
            if not budget.fired:        # an outer alarm (a checker's --time-limit), not this proof's limit
                raise
            esc = None
        except Exception:
            if not budget.fired:        # a bug, not the alarm surfacing through a C callback
                raise
            esc = None
    elapsed = time.perf_counter() - t0
    timed_out = esc is None or (budget.expired() and not esc.result.settled)
    if esc is None:
        esc = _interrupted(history, claim_statements(module, model), wanted, p0, budget.reason())
    if history and not esc.result.settled:
        esc = _best_attempt(esc, history)
    final = esc.result
    for claim in final.claims:
        claim.precision_bits = esc.prec
        for p, a in history:
            same = [c for c in a.claims if c.id == claim.id and c.status is claim.status]
            if same and claim.status is not Status.INCONCLUSIVE:
                claim.precision_bits = p
                break
        if claim.status is Status.INCONCLUSIVE and not (timed_out and not history):
            if timed_out:
                hint = budget.reason()
            elif claim.id in hopeless:
                hint = f"escalation stopped: {hopeless[claim.id]}"
            elif (final.stalled or history[-1][1].stalled) and not final.settled:
                # (the last attempt's stall stopped the escalation when an earlier attempt was kept)
                hint = "more precision does not help here (see the reason)"
            else:
                hint = f"try --maxprec {2 * maxprec}"
            claim.reason += f" [undecided at every precision tried: {esc.tried} bits; {hint}]"
    notes = list(final.notes)
    if timed_out:
        notes.append(time_limit_note(budget.reason(), esc.prec if history else None, esc.tried[-1]))
    if not final.widths_met and not timed_out:
        if "widths" in hopeless:
            notes.append(f"requested enclosure widths not met: {hopeless['widths']}")
        elif not esc.done:
            notes.append(f"requested enclosure widths not met by {esc.tried[-1]} bits: try --maxprec {2 * maxprec}")
    for row in final.paper:
        if row.status is AuditStatus.UNDECIDED and f"row:{row.id}" in hopeless:
            row.note += f" [undecided: {hopeless[f'row:{row.id}']}]"
    return Certificate(scene=scene.header(paper=True), precision_bits=esc.prec, claims=final.claims,
                       quantities=final.quantities, paper=final.paper,
                       timings={"total_s": round(elapsed, 4), "attempts_s": attempt_seconds,
                                "final_attempt_phases_s": {k: round(v, 4) for k, v in final.phase_seconds.items()},
                                "pieces": _piece_counts(final.claims)},
                       precisions_tried=esc.tried,
                       formulas=final.formulas, notes=notes, extra=final.extra, witnesses=final.witnesses,
                       settings={"prec": prec, "maxprec": maxprec,
                                 **({"time_limit": time_limit} if time_limit is not None else {})})


def time_limit_note(why: str, prec: int | None, last: int) -> str:
    """The note of a run stopped by its time limit: the certificate is the attempt at ``prec`` bits (None: no
    attempt finished), ``last`` being the last attempt that finished (:func:`_best_attempt` may take an earlier
    one). The checker writes the same note for its re-proof (:mod:`.reproduce`)."""
    if prec is None:
        return f"{why}: the certificate is the last attempt that finished (none did: nothing was decided)"
    if prec == last:
        return f"{why}: the certificate is the last attempt that finished ({prec} bits)"
    return (f"{why}: the certificate is the attempt at {prec} bits, which decided every claim any attempt that "
            f"finished decided (the last one, at {last} bits, decided fewer)")


def _decided(a: Attempt) -> set[tuple[str, Status]]:
    return {(c.id, c.status) for c in a.claims if c.status is not Status.INCONCLUSIVE}


def _best_attempt(esc: Escalation, history: list[tuple[int, Attempt]]) -> Escalation:
    """The escalation's result, or an earlier attempt that decided every claim any attempt decided (the same
    statuses) where the last one decided fewer: a higher precision can spend a budget sooner (a quadrature's
    subdivisions) and lose claims decided below it, and more time must not give a weaker certificate. The last
    such attempt is taken (the narrowest enclosures); a claim it leaves undecided is undecided at every precision
    tried. Without one attempt deciding all the others' claims, the last attempt stands, as before."""
    every = set().union(*(_decided(a) for _, a in history))
    if _decided(esc.result) == every:
        return esc
    for p, a in reversed(history):
        if _decided(a) == every:
            return Escalation(a, p, esc.done, esc.tried)     # done: why the escalation stopped, kept
    return esc


def _interrupted(history: list[tuple[int, Attempt]], statements: dict[str, str], wanted: list[str], p0: int,
                 why: str) -> Escalation:
    """The escalation as it stood when the time limit interrupted an attempt: the last attempt that
    finished, or (none did) every requested claim inconclusive for the time limit."""
    if history:
        p, a = history[-1]
        return Escalation(a, p, False, [q for q, _ in history])
    claims = [Claim(c, statements[c], Status.INCONCLUSIVE, f"not decided: {why} before the first attempt "
                    f"({p0} bits) finished") for c in wanted]
    return Escalation(Attempt(claims=claims, quantities={}, widths_met=False), p0, False, [p0])
