"""Long campaigns against independent references: ``rigor-gyro campaign --kind KIND --cases N``.

For each of N random valid scenes of a kind (wide ranges, extremes included; drawn from ``--seed``),
prove it and compare

* every certified quantity the kind's reference covers with an independent mpmath evaluation at 50
  digits or more: the ball must contain it (a *containment failure* is a soundness bug: the run fails
  and prints the scene);
* the float (numpy/scipy) result: a float outside its tolerance is a *float miss*, counted and listed
  with its relative error (floats are not references);
* every verdict with an independent decision where one exists (mpmath brackets and orderings, sampled
  Vdot and V, a dense scan of g): a *verdict disagreement* fails the run;
* the certificate itself with the independent checker (``rigor-gyro check``, after a JSON round trip):
  a certificate it does not confirm is a *check failure* and fails the run.

Cases run on a process pool (``--workers``); tasks and results are plain strings and JSON-able data.
A case that runs longer than ``--case-timeout`` seconds is stopped and counted *timed out*: an
inconclusive case, never an agreement (the limit is a budget, not evidence).
The kind's sampler and references are its ``campaign`` module (float side: never imported by a proof).

Exit status: 0 no containment failure and no verdict disagreement, 1 otherwise, 2 bad usage.
"""
from __future__ import annotations

import importlib
import json
import random
import signal
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from typing import Any

from .kinds import KINDS

__all__ = ["CaseResult", "run_case", "run_campaign", "summary_table"]


@dataclass
class CaseResult:
    params: dict[str, str]
    verdict: str = ""
    seconds: float = 0.0
    containment_failures: list[str] = field(default_factory=list)
    verdict_disagreements: list[str] = field(default_factory=list)
    float_misses: list[tuple[str, float]] = field(default_factory=list)
    compared: int = 0
    error: str = ""
    timed_out: bool = False
    check_failures: list[str] = field(default_factory=list)


class CaseTimeout(Exception):
    """Raised inside a case by the alarm of ``--case-timeout``."""


_FIRED = [False]


def _alarm(signum, frame):
    _FIRED[0] = True
    raise CaseTimeout


def _module(kind: str):
    return importlib.import_module(KINDS[kind] + ".campaign")


def run_case(kind: str, params: dict[str, str], options: dict | None = None,
             timeout: float | None = None) -> dict[str, Any]:
    """Prove one scene and compare it (runs in a worker: strings in, JSON-able dict out).

    ``timeout`` (seconds, Unix main thread only) stops the case: verdict ``inconclusive``, ``timed_out``.
    """
    from .check import check_certificate
    from .prover import prove_scene
    from .scene import Scene
    mod = _module(kind)
    res = CaseResult(dict(params))
    t0 = time.perf_counter()
    armed = bool(timeout) and hasattr(signal, "setitimer")
    _FIRED[0] = False
    if armed:
        old = signal.signal(signal.SIGALRM, _alarm)
        signal.setitimer(signal.ITIMER_REAL, float(timeout))
    try:
        scene = Scene(name="campaign", kind=kind, source="campaign", parameters=dict(params),
                      options=dict(options or mod.OPTIONS))
        cert = prove_scene(scene, maxprec=mod.MAXPREC)
        res.seconds = time.perf_counter() - t0
        res.verdict = cert.verdict.value
        mod.compare(params, cert, res)
        report = check_certificate(json.loads(json.dumps(cert.to_json())))
        if not report.ok:
            f = report.first_failure
            res.check_failures.append(f"{f.item}: {f.message}"[:300] if f else "no check ran")
    except CaseTimeout:
        res.verdict, res.timed_out = "inconclusive", True
        res.containment_failures, res.verdict_disagreements, res.float_misses, res.compared = [], [], [], 0
        res.check_failures = []
        res.seconds = time.perf_counter() - t0
    except Exception as e:  # a crash in a valid case is a finding, reported as such
        if _FIRED[0]:       # the alarm's exception surfaced through a C callback (acb.integral: SystemError)
            res.verdict, res.timed_out = "inconclusive", True
            res.containment_failures, res.verdict_disagreements, res.float_misses, res.compared = [], [], [], 0
            res.check_failures = []
        else:
            res.error = f"{type(e).__name__}: {e}"[:300]
        res.seconds = time.perf_counter() - t0
    finally:
        if armed:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, old)
    return res.__dict__


def run_campaign(kind: str, cases: int, seed: int, workers: int = 1, progress=None,
                 timeout: float | None = None) -> list[dict[str, Any]]:
    """Draw ``cases`` scenes from ``seed`` and run them on ``workers`` processes (1: in this process),
    each stopped after ``timeout`` seconds (None: no limit)."""
    mod = _module(kind)
    rng = random.Random(seed)
    drawn = [mod.draw(rng) for _ in range(cases)]
    out: list[dict[str, Any]] = []
    if workers <= 1:
        for p in drawn:
            out.append(run_case(kind, p, None, timeout))
            if progress:
                progress(len(out), cases)
        return out
    with ProcessPoolExecutor(max_workers=workers) as pool:
        for r in pool.map(run_case, [kind] * len(drawn), drawn, [None] * len(drawn),
                              [timeout] * len(drawn), chunksize=4):
            out.append(r)
            if progress:
                progress(len(out), cases)
    return out


def _inconclusive(results: list[dict[str, Any]]) -> str:
    """The inconclusive count, with how many of them hit the time limit."""
    n = sum(1 for r in results if r["verdict"] == "inconclusive")
    t = sum(1 for r in results if r.get("timed_out"))
    return f"{n} ({t} timed out)" if t else str(n)


def summary_table(kind: str, seed: int, results: list[dict[str, Any]]) -> str:
    """The Markdown summary: cases, verdicts, failures (must be 0), float misses, time per case."""
    n = len(results)
    by = {v: sum(1 for r in results if r["verdict"] == v) for v in ("proved", "refuted", "inconclusive")}
    cf = [r for r in results if r["containment_failures"]]
    vd = [r for r in results if r["verdict_disagreements"]]
    ck = [r for r in results if r.get("check_failures")]
    errs = [r for r in results if r["error"]]
    fm = [(name, err) for r in results for name, err in r["float_misses"]]
    worst = max((e for _, e in fm), default=0.0)
    times = sorted(r["seconds"] for r in results) or [0.0]
    compared = sum(r["compared"] for r in results)
    lines = ["| kind | seed | cases | proved | refuted | inconclusive | crashes | containment failures | "
             "verdict disagreements | check failures | values compared | float misses (worst rel. error) | "
             "s/case median (max) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
             f"| {kind} | {seed} | {n} | {by['proved']} | {by['refuted']} | {_inconclusive(results)} | {len(errs)} | "
             f"{len(cf)} | {len(vd)} | {len(ck)} | {compared} | {len(fm)} ({worst:.2g}) | "
             f"{times[len(times) // 2]:.2f} ({times[-1]:.2f}) |"]
    for r in (cf + vd + ck + errs)[:10]:
        lines.append("")
        lines.append(f"- FAILED scene {json.dumps(r['params'])}: " + "; ".join(
            r["containment_failures"] + r["verdict_disagreements"] + r.get("check_failures", [])
            + ([r["error"]] if r["error"] else []))[:600])
    return "\n".join(lines)
