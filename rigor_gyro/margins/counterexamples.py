"""Counterexamples searched over the whole box, and a Monte Carlo estimate of each claim's failing fraction.

A paving leaves a claim ``undecided`` on leaves where its box rigour could not decide at the resolution. A
claim that fails on part of such leaves is refuted by one certified counterexample, wherever it lies. This
module looks for one over *all* the undecided leaves of a claim, not only the first few:

1. :func:`candidate_points` proposes points: the Halton sequence in exact rationals
   (:mod:`rigor_gyro.core.halton`: no random state) mapped onto the union of the claim's undecided leaves in
   proportion to volume; at each point the kind's box rigour on the degenerate box {point} at low precision
   (:data:`PROBE_PREC` bits; a *probe*) says refuted / undecided / proved, and where the kind has a margin
   provider (:data:`MARGIN_PROVIDERS`) the claim's smallest gap at the point, as a float. Points are ranked
   (probe refuted first, then the smallest margin), at most one per leaf while other leaves have candidates,
   and the best non-refuted ones take a few steps inside their leaf toward a smaller margin.
2. :func:`prove_candidates` runs the point prover (:func:`rigor_gyro.margins.paving.point_task`, the path of
   ``rigor-gyro prove``, from ``point_prec`` to ``point_maxprec`` bits) at each candidate. Only a point proof
   whose status is ``refuted`` makes a certified counterexample (:func:`certified_counterexamples`); it is
   reported with the leaf that contains it (checked exactly).
3. :func:`failing_fraction_estimate` estimates, by plain Monte Carlo with a fixed seed, the fraction of the
   box's volume where each claim fails, with a Wilson interval; :func:`agrees_with_paving` compares it with
   the certified fractions of a paving.

Guarantee: the proposal (probes, margins, floats, ranking) never decides anything: a candidate is only a
point to ask the point prover. A counterexample returned by :func:`certified_counterexamples` is a point of
the box at which the point prover refuted the claim on Arb balls, so the claim over the box is refuted.
A point prover that refutes inside a leaf stored ``proved`` (or proves inside one stored ``refuted``) is a
contradiction between two rigorous paths: AssertionError. The Monte Carlo estimate is statistical
(evidence, not proof): its interval holds the true fraction with the stated confidence only.

Precision: probes at ``prec`` bits (default :data:`PROBE_PREC`); point proofs at the scene's point
precisions; the estimate classifies each sample with the point prover (``classifier="point"``, code apart
from the box rigour) or with a probe (``"box"``, faster).

Failure modes: no undecided leaf, or no candidate failing anywhere, gives no counterexample (never a
refutation); a candidate the point prover leaves inconclusive is reported as such. Determinism: every
point is an exact rational fixed by the leaves and the parameters; executors return results in order.
"""
from __future__ import annotations

import json
import math
import random
from dataclasses import dataclass
from fractions import Fraction
from statistics import NormalDist
from typing import Any, Callable

from ..core.balls import working_precision
from ..core.boxes import Box, fraction_text
from ..core.halton import points_in_boxes
from ..kinds import optional_module
from .executors import Executor
from .models import scene_model, settings_json, task_scene
from .point_proofs import point_task

__all__ = ["PROBE_PREC", "MARGIN_PROVIDERS", "Candidate", "probe_task", "candidate_points", "shortest_decimal",
           "prove_candidates", "search_claim",
           "certified_counterexamples", "contains", "wilson_interval", "failing_fraction_estimate",
           "agrees_with_paving", "paving_searches"]

#: bits of the probes (the box rigour on a point box): a proposal only, so low
PROBE_PREC = 64
#: probes per executor task (each ~2 ms for the eigenfrequency kind: batches of ~50 ms)
BATCH = 24
_RANK = {"refuted": 0, "undecided": 1, "proved": 2}


# --------------------------------------------------------------------------- margins (floats, ranking only)

def _eigenfrequency_margins(model, box: Box, claims: list[str]) -> dict[str, float | None]:
    """The smallest of each claim's gaps (:class:`rigor_gyro.kinds.eigenfrequencies.slack_forms.GapSet`: a
    bracket's omega_j - lower and upper - omega_j, the ordering, branch and bound gaps) at the point ``box``,
    as the float midpoint of its ball; None where a gap is not enclosed (or for ``roots``, which has none), and
    for every claim of a ``[system]`` model (no gaps: the probes' statuses alone rank its candidates)."""
    from ..core.centred_forms import exact_ball
    from ..core.dual_balls import constant
    from ..kinds.eigenfrequencies.boxes import box_roots
    from ..kinds.eigenfrequencies.slack_forms import GapSet
    from ..kinds.eigenfrequencies.system_model import SystemModel
    if isinstance(model, SystemModel):
        return {c: None for c in claims}
    roots, _ = box_roots(model, box)
    gaps = GapSet(model, box, roots)
    duals = {k: constant(exact_ball(lo)) for k, lo, _ in box.edges}
    lists: dict[str, Callable[[], list]] = {"nu_ordering": gaps.ordering_gaps, "branches": gaps.branch_gaps,
                                           "nu_bounds": gaps.bound_gaps}
    out: dict[str, float | None] = {}
    for c in claims:
        make = (lambda j=int(c[-1]): gaps.bracket_gaps(j)) if c.startswith("bracket_") else lists.get(c)
        if make is None:
            out[c] = None
            continue
        values = []
        for _, f, _ in make():
            try:
                d = f(duals)
            except ArithmeticError:
                d = None
            if d is None or not d.value.is_finite():
                values = None
                break
            values.append(float(d.value.mid()))
        out[c] = min(values) if values else None
    return out


#: kind -> margins(model, point_box, claims) -> {claim: float or None}: the claim's smallest gap at the point
#: (negative where it fails), used only to rank and to step toward failure
MARGIN_PROVIDERS: dict[str, Callable[..., dict[str, float | None]]] = {"eigenfrequencies": _eigenfrequency_margins}


def _point_box(whole: Box, point: dict[str, Fraction]) -> Box:
    return Box(tuple((k, point[k], point[k]) for k in whole.names))


def probe_task(kind: str, points_json: str, options_json: str, mid_json: str, whole_json: str, batch_json: str,
               claims: tuple[str, ...], prec: int, margins: bool) -> list[dict[str, list]]:
    """Probes of a batch of points (strings in, strings out): per point {claim: [status, margin or None]},
    the status of the kind's box rigour on the point box at ``prec`` bits (an ArithmeticError: undecided)."""
    model = scene_model(kind, points_json, options_json, mid_json)
    whole = Box.from_json(json.loads(whole_json))
    boxes = optional_module(kind, "boxes")
    provider = MARGIN_PROVIDERS.get(kind) if margins else None
    out = []
    for p in json.loads(batch_json):
        box = _point_box(whole, {k: Fraction(v) for k, v in p.items()})
        with working_precision(prec):
            try:
                st = boxes.evaluate_box(model, box, list(claims))
            except ArithmeticError as e:
                st = {c: ("undecided", str(e)) for c in claims}
            try:
                m = provider(model, box, list(claims)) if provider else {}
            except ArithmeticError:
                m = {}
        out.append({c: [st[c][0], m.get(c)] for c in claims})
    return out


def _probe(bs, points: list[dict[str, Fraction]], claims: tuple[str, ...], prec: int, ex: Executor,
           margins: bool = True) -> list[dict[str, list]]:
    pj = json.dumps(bs.points, sort_keys=True)
    oj = settings_json(bs.options, bs.scene.model)
    mj = json.dumps({k: fraction_text(q) for k, q in bs.box.midpoint().items()}, sort_keys=True)
    wj = json.dumps(bs.box.to_json())
    texts = [{k: fraction_text(q) for k, q in p.items()} for p in points]
    tasks = [(bs.scene.kind, pj, oj, mj, wj, json.dumps(texts[i:i + BATCH]), claims, prec, margins)
             for i in range(0, len(texts), BATCH)]
    return [r for batch in ex.map(probe_task, tasks) for r in batch]


# --------------------------------------------------------------------------- 1. candidates

@dataclass(frozen=True)
class Candidate:
    """A point to ask the point prover: exact coordinates of the box's parameters, the index of the leaf it
    lies in (in the leaves given), the probe's status there and the margin (float or None): a proposal."""

    point: dict[str, Fraction]
    leaf: int
    probe: str
    margin: float | None

    def key(self) -> tuple:
        m = self.margin if self.margin is not None and math.isfinite(self.margin) else math.inf
        return (_RANK[self.probe], m)


def _better(a: Candidate, b: Candidate) -> bool:
    return a.key() < b.key()


def _improve(bs, cand: Candidate, leaf: Box, claim: str, steps: int, prec: int, ex: Executor) -> Candidate:
    """Up to ``steps`` rounds of a compass search inside ``leaf``: the 2 d points one step away along each
    edge (a quarter of the leaf's edge, halved each round, clamped to the leaf), moving to the best of them
    when it ranks better."""
    for s in range(steps):
        nbrs = []
        for k, lo, hi in leaf.edges:
            h = (hi - lo) / 2 ** (s + 2)
            for sign in (-1, 1):
                x = min(max(cand.point[k] + sign * h, lo), hi)
                if x != cand.point[k]:
                    nbrs.append({**cand.point, k: x})
        if not nbrs:
            break
        probes = _probe(bs, nbrs, (claim,), prec, ex)
        best = min((Candidate(p, cand.leaf, r[claim][0], r[claim][1]) for p, r in zip(nbrs, probes)),
                   key=Candidate.key)
        if _better(best, cand):
            cand = best
    return cand


def candidate_points(bs, leaves: list[tuple[Box, str]], claim: str, n: int, samples: int | None = None,
                     prec: int = PROBE_PREC, improve_steps: int = 2, executor: Executor | None = None,
                     outcomes: tuple[str, ...] = ("undecided",), tidy: bool = True) -> list[Candidate]:
    """Up to ``n`` candidate counterexamples to ``claim`` over the leaves whose status is in ``outcomes``
    (``leaves``: the claim's leaves as the paving stores them, ``(box, status)``; :attr:`Candidate.leaf`
    indexes this list). ``samples`` Halton points (default ``32 n``) spread over those leaves by volume are
    probed; candidates are the points whose probe is not ``proved``, best first (probe refuted, then the
    smallest margin), one per leaf before any second one in a leaf; the best ``n`` that are not refuted by
    their probe take ``improve_steps`` rounds of local search; with ``tidy``, each is then moved to short
    decimals nearby where its probe ranks no worse (:func:`shortest_decimal`). Deterministic; never decides."""
    ex = executor or Executor(1)
    idx = [i for i, (_, s) in enumerate(leaves) if s in outcomes]
    if n <= 0 or not idx:
        return []
    count = samples if samples is not None else 32 * n
    drawn = list(points_in_boxes([leaves[i][0] for i in idx], count))
    probes = _probe(bs, [p for _, p in drawn], (claim,), prec, ex)
    cands = [Candidate(p, idx[k], r[claim][0], r[claim][1]) for (k, p), r in zip(drawn, probes)]
    order = sorted(range(len(cands)), key=lambda i: (cands[i].key(), i))
    first, rest, seen = [], [], set()
    for i in order:
        (rest if cands[i].leaf in seen else first).append(cands[i])
        seen.add(cands[i].leaf)
    ranked = first + rest
    chosen = ranked[:n]
    chosen = [c if c.probe == "refuted" or c.margin is None
              else _improve(bs, c, leaves[c.leaf][0], claim, improve_steps, prec, ex) for c in chosen]
    if tidy:
        chosen = _tidied(bs, chosen, leaves, claim, prec, ex)
    return [c for c in sorted(chosen, key=Candidate.key) if c.probe != "proved"]


def shortest_decimal(lo: Fraction, hi: Fraction) -> Fraction:
    """The decimal with the fewest digits after the point in [lo, hi] (the smallest such; exact); lo when
    there is none with up to 40 digits (lo == hi, or a very narrow interval)."""
    for digits in range(41):
        step = Fraction(1, 10 ** digits)
        c = math.ceil(lo / step) * step
        if c <= hi:
            return c
    return lo


def _tidied(bs, cands: list[Candidate], leaves: list[tuple[Box, str]], claim: str, prec: int,
            ex: Executor) -> list[Candidate]:
    """Each candidate moved to the shortest decimals within 1/32 of its leaf's edge (inside the leaf), so
    that a counterexample reads like one a person would write; kept there only when the probe ranks it no
    worse (status first), else left where it was."""
    tidy = []
    for c in cands:
        box = leaves[c.leaf][0]
        tidy.append({k: shortest_decimal(max(lo, c.point[k] - (hi - lo) / 32), min(hi, c.point[k] + (hi - lo) / 32))
                     for k, lo, hi in box.edges})
    probes = _probe(bs, tidy, (claim,), prec, ex)
    out = []
    for c, p, r in zip(cands, tidy, probes):
        t = Candidate(p, c.leaf, r[claim][0], r[claim][1])
        out.append(t if _RANK[t.probe] <= _RANK[c.probe] else c)
    return out


# --------------------------------------------------------------------------- 2. point proofs

def contains(box: Box, point: dict[str, Fraction]) -> bool:
    """Whether the exact ``point`` lies in the closed ``box`` (every edge of the box)."""
    return all(lo <= point[k] <= hi for k, lo, hi in box.edges)


def prove_candidates(bs, leaves: list[tuple[Box, str]], claim: str, candidates: list[Candidate],
                     executor: Executor | None = None) -> list[dict[str, Any]]:
    """The point prover at each candidate: ``[{point, leaf, leaf_status, probe, status, reason,
    precision_bits}]`` in the candidates' order (``point``: the box's parameters as exact text; ``leaf``: the
    index in ``leaves`` of the leaf containing it, checked exactly). AssertionError when a candidate is not
    in its leaf, or when the point prover contradicts its leaf (refuted in a ``proved`` leaf, proved in a
    ``refuted`` one: one of two rigorous paths is wrong)."""
    ex = executor or Executor(1)
    oj = settings_json(bs.options, bs.scene.model)
    for c in candidates:
        if not contains(leaves[c.leaf][0], c.point):
            raise AssertionError(f"claim {claim}: candidate {c.point} is not in leaf {c.leaf}")
    tasks = [(bs.scene.kind, json.dumps(bs.point_parameters(c.point), sort_keys=True), oj, claim, bs.point_prec,
              bs.point_maxprec) for c in candidates]
    out = []
    for c, res in zip(candidates, ex.map(point_task, tasks)):
        leaf_status = leaves[c.leaf][1]
        if {leaf_status, res["status"]} == {"proved", "refuted"}:
            raise AssertionError(f"claim {claim}: leaf {c.leaf} ({json.dumps(leaves[c.leaf][0].to_json())}) is "
                                 f"{leaf_status} for every parameter, but the point prover {res['status']} the "
                                 f"claim at {c.point}: an unsound box or point evaluation")
        out.append({"point": {k: fraction_text(q) for k, q in c.point.items()}, "leaf": c.leaf,
                    "leaf_status": leaf_status, "probe": c.probe, **res})
    return out


def certified_counterexamples(proofs: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The point proofs that certify a counterexample: those the point prover refuted (never a probe)."""
    return [p for p in proofs if p["status"] == "refuted"]


#: a Monte Carlo estimate's default confidence and classifier (a paving's estimate uses them; its checker asks them)
MC_CONFIDENCE = 0.999
MC_CLASSIFIER = "point"


def search_settings(n: int, samples: int | None = None, prec: int = PROBE_PREC, improve_steps: int = 2) -> dict:
    """The ``settings`` a search of ``n`` points stores (``samples`` None: 32 n drawn samples); its checker
    derives them from the scene's options the same way."""
    return {"points": n, "samples": samples if samples is not None else 32 * n, "probe_prec": prec,
            "improve_steps": improve_steps, "sequence": "halton"}


def search_claim(bs, leaves: list[tuple[Box, str]], claim: str, n: int, samples: int | None = None,
                 prec: int = PROBE_PREC, improve_steps: int = 2, executor: Executor | None = None) -> dict[str, Any]:
    """Steps 1 and 2 for one claim, as a paving certificate would store them: ``{"settings": {points, samples,
    probe_prec, improve_steps, sequence}, "undecided_leaves", "proofs": prove_candidates(...), "refuted",
    "leaves": the distinct leaves holding a certified counterexample}``."""
    settings = search_settings(n, samples, prec, improve_steps)
    cands = candidate_points(bs, leaves, claim, n, settings["samples"], prec, improve_steps, executor)
    proofs = prove_candidates(bs, leaves, claim, cands, executor)
    found = certified_counterexamples(proofs)
    return {"settings": settings,
            "undecided_leaves": sum(1 for _, s in leaves if s == "undecided"), "proofs": proofs,
            "refuted": len(found), "leaves": sorted({p["leaf"] for p in found})}


# --------------------------------------------------------------------------- 3. Monte Carlo

def wilson_interval(k: int, n: int, confidence: float) -> tuple[float, float]:
    """Wilson's score interval for a binomial proportion (k successes of n) at ``confidence`` (floats)."""
    if n <= 0:
        return 0.0, 1.0
    z = NormalDist().inv_cdf(0.5 + confidence / 2)
    p = k / n
    den = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / den
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / den
    return max(0.0, centre - half), min(1.0, centre + half)


def uniform_points(whole: Box, count: int, seed: int) -> list[dict[str, Fraction]]:
    """``count`` points uniform in ``whole`` (pseudo-random with ``seed``, exact: each coordinate at the centre
    of one of 2^32 equal cells of its edge)."""
    rng = random.Random(seed)
    return [{k: lo + Fraction(2 * rng.getrandbits(32) + 1, 2 ** 33) * (hi - lo) for k, lo, hi in whole.edges}
            for _ in range(count)]


def _point_statuses(kind: str, params_json: str, options_json: str, claims: tuple[str, ...], prec: int,
                    maxprec: int) -> dict[str, str]:
    from ..prover import prove_scene
    scene = task_scene("sample", kind, "monte carlo sample", json.loads(params_json), options_json, list(claims))
    cert = prove_scene(scene, prec=prec, maxprec=maxprec)
    return {c: cert.claim(c).status.value for c in claims}


def failing_fraction_estimate(bs, claims: list[str] | None = None, samples: int = 1000, seed: int = 0,
                              confidence: float = MC_CONFIDENCE, classifier: str = MC_CLASSIFIER, prec: int = PROBE_PREC,
                              executor: Executor | None = None) -> dict[str, dict[str, Any]]:
    """Per claim, {samples, failing, unknown, fraction, interval, confidence, seed, classifier}: ``samples``
    uniform points of the box (:func:`uniform_points`), each classified by the point prover at ``prec`` ..
    ``bs.point_maxprec`` bits (``classifier="point"``) or by a probe (``"box"``); ``failing`` counts refuted
    samples, ``unknown`` the rest that are not proved. ``interval`` = [Wilson lower end of failing / samples,
    Wilson upper end of (failing + unknown) / samples] at ``confidence``: statistical, never a verdict."""
    ex = executor or Executor(1)
    claims = tuple(claims if claims is not None else bs.claims)
    pts = uniform_points(bs.box, samples, seed)
    if classifier == "point":
        oj = settings_json(bs.options, bs.scene.model)
        tasks = [(bs.scene.kind, json.dumps(bs.point_parameters(p), sort_keys=True), oj, claims, prec,
                  bs.point_maxprec) for p in pts]
        statuses = ex.map(_point_statuses, tasks)
    elif classifier == "box":
        statuses = [{c: r[c][0] for c in claims} for r in _probe(bs, pts, claims, prec, ex, margins=False)]
    else:
        raise ValueError(f"classifier must be 'point' or 'box' (got {classifier!r})")
    out = {}
    for c in claims:
        k = sum(1 for s in statuses if s[c] == "refuted")
        u = sum(1 for s in statuses if s[c] not in ("refuted", "proved"))
        lo, _ = wilson_interval(k, samples, confidence)
        _, hi = wilson_interval(k + u, samples, confidence)
        out[c] = {"samples": samples, "failing": k, "unknown": u, "fraction": k / samples if samples else 0.0,
                  "interval": [lo, hi], "confidence": confidence, "seed": seed, "classifier": classifier}
    return out


def agrees_with_paving(volume: dict[str, Fraction], estimate: dict[str, Any]) -> tuple[bool, str]:
    """Whether a claim's Monte Carlo interval meets what the paving certifies about its failing fraction:
    at least the refuted volume fraction, at most the refuted plus the undecided one (``volume``:
    :meth:`rigor_gyro.margins.paving.ClaimPaving.volume`). A disagreement means a wrong paving, a wrong
    classifier, or (with probability at most 1 - confidence) an unlucky sample: evidence, never a verdict."""
    lo_c = volume["refuted"]
    hi_c = volume["refuted"] + volume["undecided"]
    lo, hi = estimate["interval"]
    ok = float(lo_c) <= hi and lo <= float(hi_c)
    text = (f"Monte Carlo: {estimate['failing']} of {estimate['samples']} samples fail "
            f"({estimate['fraction']:.4f}; {estimate['confidence']:.1%} interval [{lo:.4f}, {hi:.4f}]); the paving "
            f"certifies a failing fraction in [{float(lo_c):.4f}, {float(hi_c):.4f}]: "
            + ("consistent" if ok else "INCONSISTENT"))
    return ok, text


# --------------------------------------------------------------------------- 4. for the paving

def paving_searches(bs, claims: list, n: int, samples: int | None = None, mc_samples: int = 0, seed: int = 0,
                    prec: int = PROBE_PREC, executor: Executor | None = None, budget=None) -> dict[str, dict[str, Any]]:
    """What a paving adds per claim (``claims``: the paving's claim results, each with ``id``, ``boxes`` (the
    leaves) and ``volume(whole)``): ``{"counterexample_search": search_claim(...)}`` for a claim with undecided
    leaves, and with ``mc_samples`` > 0 ``{"monte_carlo": failing_fraction_estimate(...) plus "consistent":
    agrees_with_paving(...)}``. With a ``budget`` (:class:`rigor_gyro.core.deadline.Budget`) that has run
    out, what is left is skipped (``{"skipped": reason}``): a search never decides, so skipping one loses
    nothing certified."""
    ex = executor or Executor(1)
    out: dict[str, dict[str, Any]] = {c.id: {} for c in claims}
    for c in claims:
        if any(s == "undecided" for _, s in c.boxes) and n > 0:
            if budget is not None and budget.expired():
                out[c.id]["counterexample_search"] = {"skipped": budget.reason()}
            else:
                out[c.id]["counterexample_search"] = search_claim(bs, c.boxes, c.id, n, samples, prec, executor=ex)
    if mc_samples > 0:
        if budget is not None and budget.expired():
            for c in claims:
                out[c.id]["monte_carlo"] = {"skipped": budget.reason()}
        else:
            est = failing_fraction_estimate(bs, [c.id for c in claims], mc_samples, seed, executor=ex)
            for c in claims:
                out[c.id]["monte_carlo"] = {**est[c.id],
                                            "consistent": agrees_with_paving(c.volume(bs.box), est[c.id])[0]}
    return out
