"""The checker's side of the counterexample search and the Monte Carlo cross-check
(:mod:`rigor_gyro.margins.counterexamples`): what a paving certificate stores about them, re-derived.

* :func:`check_counterexamples`: every stored point proof of a claim's search (``search_claim(...)["proofs"]``)
  names a point of the box (the box's parameters, exact text), a leaf of the claim that contains it (exact),
  that leaf's stored status, the probe's status (``probe``: re-probed, never ``proved``), and the point
  prover's status, reason and precision, which ``prove_at`` re-proves and must give again exactly; a point refuted inside a leaf stored ``proved`` (or proved inside one stored
  ``refuted``) is a contradiction. The counts (``refuted``, ``leaves``) must follow from the proofs.
* :func:`check_monte_carlo`: a stored estimate's fraction and interval must follow from its counts (the
  Wilson interval recomputed), and its ``consistent`` flag from the paving's certified volume fractions;
  with ``rerun``, the counts must be those of a fresh run with the stored seed (the estimate is deterministic).

Guarantee: a failure names the first stored item that does not re-derive. The search itself (which points
were proposed) is not re-run: a point proof stands on its own, wherever its point came from. Precision: the
point proofs' (``prove_at``'s); the Wilson interval in floats, compared to 1e-12 relative.
Fails when: never raises on a malformed entry; it reports it.
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Callable

from ..core.boxes import Box
from .counterexamples import agrees_with_paving, contains, wilson_interval

__all__ = ["check_counterexamples", "check_monte_carlo"]

_CONTRADICTORY = {"proved", "refuted"}


def _point(whole: Box, text: Any) -> dict[str, Fraction] | None:
    if not isinstance(text, dict) or sorted(text) != sorted(whole.names):
        return None
    try:
        return {k: Fraction(str(text[k])) for k in whole.names}
    except (ValueError, ZeroDivisionError):
        return None


def check_counterexamples(whole: Box, leaves: list[tuple[Box, str]], claim: str, search: dict[str, Any],
                          prove_at: Callable[[dict[str, Fraction]], dict[str, Any]],
                          probe_at: Callable[[dict[str, Fraction]], str] | None = None) -> tuple[bool, str]:
    """(ok, message) for one claim's stored search (see the module docstring); ``prove_at(point)`` returns
    the point prover's ``{status, reason, precision_bits}`` at the exact point (e.g. through
    :func:`rigor_gyro.margins.paving.point_task`); ``probe_at(point)``, when given, the probe's status there
    (:func:`.counterexamples.probe_task`), which each stored ``probe`` must be (never ``proved``: the search
    proves only the points its probe did not prove)."""
    proofs = search.get("proofs")
    if not isinstance(proofs, list):
        return False, f"claim {claim}: the counterexample search stores no list of point proofs"
    refuted_leaves = set()
    for i, p in enumerate(proofs):
        where = f"claim {claim}, search point {i}"
        point = _point(whole, p.get("point") if isinstance(p, dict) else None)
        if point is None or not contains(whole, point):
            return False, f"{where}: not a point of the box ({p.get('point') if isinstance(p, dict) else p!r})"
        leaf = p.get("leaf")
        if not isinstance(leaf, int) or isinstance(leaf, bool) or not 0 <= leaf < len(leaves):
            return False, f"{where}: leaf {leaf!r} is not an index of the claim's {len(leaves)} leaves"
        box, status = leaves[leaf]
        if p.get("leaf_status") != status:
            return False, f"{where}: leaf {leaf} is stored {status}, the search says {p.get('leaf_status')!r}"
        if not contains(box, point):
            return False, f"{where}: the point {p['point']} is not in leaf {leaf} ({box.to_json()})"
        if probe_at is not None:
            probe = probe_at(point)
            if p.get("probe") != probe or probe == "proved":
                return False, (f"{where}: the probe gives {probe!r} at {p['point']}, the certificate "
                               f"{p.get('probe')!r}" + (" (a point its probe proved is never a candidate)"
                                                        if probe == "proved" else ""))
        got = prove_at(point)
        for key in ("status", "reason", "precision_bits"):
            if got.get(key) != p.get(key):
                return False, (f"{where}: the point prover gives {key} {got.get(key)!r} at {p['point']}, the "
                               f"certificate {p.get(key)!r}")
        if {status, got["status"]} == _CONTRADICTORY:
            return False, (f"{where}: the point prover {got['status']} the claim at {p['point']}, inside leaf {leaf} "
                           f"stored {status} for every parameter: the box and point rigour disagree")
        if got["status"] == "refuted":
            refuted_leaves.add(leaf)
    refuted = sum(1 for p in proofs if p.get("status") == "refuted")
    if search.get("refuted") != refuted or search.get("leaves") != sorted(refuted_leaves):
        return False, (f"claim {claim}: the search states {search.get('refuted')!r} counterexamples in leaves "
                       f"{search.get('leaves')!r}; its proofs give {refuted} in {sorted(refuted_leaves)}")
    return True, (f"claim {claim}: {len(proofs)} searched point(s) re-proved by the point prover, {refuted} "
                  f"certified counterexample(s) in {len(refuted_leaves)} leaf(s)")


def _close(x: Any, y: float) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isclose(x, y, rel_tol=1e-12, abs_tol=1e-15)


def check_monte_carlo(claim: str, stored: dict[str, Any], volume: dict[str, Fraction] | None = None,
                      rerun: Callable[[], dict[str, Any]] | None = None) -> tuple[bool, str]:
    """(ok, message) for one claim's stored estimate (see the module docstring); ``volume``: the claim's
    certified volume fractions (for the ``consistent`` flag), ``rerun()``: a fresh estimate of this claim."""
    try:
        n, k, u, conf = stored["samples"], stored["failing"], stored["unknown"], stored["confidence"]
        ints = all(isinstance(x, int) and not isinstance(x, bool) for x in (n, k, u))
        if not (ints and 0 <= k and 0 <= u and k + u <= n and 0 < conf < 1):
            return False, f"claim {claim}: Monte Carlo counts {n}, {k}, {u} or confidence {conf} impossible"
        lo, _ = wilson_interval(k, n, conf)
        _, hi = wilson_interval(k + u, n, conf)
        lo_s, hi_s = stored["interval"]
        if not (_close(stored["fraction"], k / n if n else 0.0) and _close(lo_s, lo) and _close(hi_s, hi)):
            return False, (f"claim {claim}: Monte Carlo fraction {stored['fraction']} and interval {stored['interval']} "
                           f"do not follow from {k} failing and {u} unknown of {n} (interval [{lo}, {hi}])")
        if volume is not None and "consistent" in stored:
            ok, _ = agrees_with_paving(volume, stored)
            if stored["consistent"] is not ok:
                return False, f"claim {claim}: Monte Carlo stored consistent = {stored['consistent']}, re-derived {ok}"
    except (KeyError, TypeError, ValueError) as e:
        return False, f"claim {claim}: Monte Carlo estimate malformed ({type(e).__name__}: {e})"
    if rerun is not None:
        fresh = rerun()
        if (fresh["samples"], fresh["failing"], fresh["unknown"]) != (n, k, u):
            return False, (f"claim {claim}: Monte Carlo re-run with seed {stored.get('seed')} gives {fresh['failing']} "
                           f"failing and {fresh['unknown']} unknown of {fresh['samples']}, stored {k} and {u} of {n}")
    return True, f"claim {claim}: Monte Carlo counts and interval re-derived ({k} failing of {n})"
