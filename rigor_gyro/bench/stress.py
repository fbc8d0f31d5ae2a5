"""The stiff and extreme catalog: every built-in scene of the ``stress`` group, proved once as the
prover would (escalating from 64 bits), with what the float (numpy/scipy) path makes of it.

For each scene: the verdict and each claim's status with the precision that decided it (or, for an
undecided claim, why); the wall time; the number of precisions tried; subdivision pieces; and the
float path's worst relative error against the certified values, the number of roots it finds against
the certified count, or its failure. Measurements only: the verdicts are the prover's.
"""
from __future__ import annotations

import importlib
import time
from typing import Any

from ..kinds import KINDS
from ..prover import prove_scene
from ..scene import builtin_scenes, load_scene
from .workprecision import float_hint, relative_error

__all__ = ["run_stress", "stress_markdown"]


def _certified_roots(cert) -> int | None:
    """How many roots the certificate isolates (relay: roots of g; eigenfrequencies: omega_j)."""
    for c in cert.claims:
        if c.id == "half_period" and isinstance(c.details.get("roots"), int):
            return c.details["roots"]
    n = sum(1 for k in cert.quantities if k.startswith("omega_"))
    return n or None


def _float_path(scene, cert) -> dict[str, Any]:
    approx = importlib.import_module(KINDS[scene.kind] + ".approx")
    t = time.perf_counter()
    try:
        values = approx.bench_float(dict(scene.parameters), hint=float_hint(cert))
    except Exception as e:
        return {"failed": f"{type(e).__name__}: {e}"[:160], "seconds": time.perf_counter() - t}
    out: dict[str, Any] = {"seconds": time.perf_counter() - t, "found": values.get("found")}
    errs = {k: relative_error(v, cert.quantities[k]) for k, v in values.items() if k in cert.quantities}
    bad = {k: e for k, e in errs.items() if e is None}
    errs = {k: e for k, e in errs.items() if e is not None}
    if errs:
        k = max(errs, key=errs.get)
        out["worst"] = (k, errs[k])
    out["unusable"] = sorted(bad)       # NaN, inf or not a number
    return out


def run_stress(names=None, progress=None) -> list[dict[str, Any]]:
    """Prove each stress scene (default: the whole group) and run its float path; JSON-able rows."""
    rows = []
    for name in names or list(builtin_scenes("stress")):
        scene = load_scene(name)
        if progress:
            progress(name)
        t = time.perf_counter()
        cert = prove_scene(scene)
        seconds = time.perf_counter() - t
        claims = []
        for c in cert.claims:
            claims.append({"id": c.id, "status": c.status.value, "bits": c.precision_bits,
                           "reason": c.reason if c.status.value == "inconclusive" else ""})
        rows.append({"scene": name, "kind": scene.kind, "source": scene.source, "verdict": cert.verdict.value,
                     "seconds": seconds, "precisions_tried": cert.precisions_tried, "claims": claims,
                     "pieces": cert.timings.get("pieces", {}), "certified_roots": _certified_roots(cert),
                     "float": _float_path(scene, cert)})
    return rows


def _float_cell(r: dict[str, Any]) -> str:
    f = r["float"]
    if "failed" in f:
        return f"fails: {f['failed']}"
    parts = []
    if "worst" in f:
        k, e = f["worst"]
        parts.append(f"worst rel. error {e:.2g} (`{k}`)" if e < 1e300 else
                     f"worst rel. error > 1e300 (`{k}`: the value is below a double's range)")
    if f.get("unusable"):
        parts.append("no usable value for " + ", ".join(f"`{k}`" for k in f["unusable"][:4]))
    if f.get("found") is not None and r["certified_roots"] is not None and f["found"] != r["certified_roots"]:
        parts.append(f"finds {f['found']} roots of the {r['certified_roots']} certified")
    elif f.get("found") is not None and r["certified_roots"] is not None:
        parts.append(f"finds the {f['found']} roots")
    return "; ".join(parts) or "nothing to compare"


def _outcome(r: dict[str, Any]) -> str:
    by: dict[str, list[str]] = {}
    for c in r["claims"]:
        by.setdefault(c["status"], []).append(c)
    out = []
    for st in ("proved", "refuted", "inconclusive"):
        cs = by.get(st, [])
        if cs:
            bits = sorted({c["bits"] for c in cs})
            out.append(f"{len(cs)} {st} (at {'/'.join(map(str, bits))} bits)")
    und = [c for c in r["claims"] if c["status"] == "inconclusive"]
    if und:
        out.append(f"`{und[0]['id']}`: {und[0]['reason'][:220]}")
    return "; ".join(out)


def stress_markdown(rows: list[dict[str, Any]]) -> str:
    n_incl = sum(1 for r in rows if r["verdict"] == "inconclusive")
    out = ["# Stress catalog: stiff and extreme scenes", "",
           f"**Answer:** {len(rows)} scenes; " + ", ".join(
               f"{sum(1 for r in rows if r['verdict'] == v)} {v}" for v in ("proved", "refuted", "inconclusive"))
           + (". An inconclusive scene says why (a budget or a precision cap, never a refutation)." if n_incl else "."),
           "", "Each scene is a built-in scene of the `stress` group (`rigor-gyro list`), proved as `rigor-gyro "
           "prove` does (64 bits, doubling as needed). The float column is the kind's uncertified numpy/scipy "
           "script, judged against the certified values. Regenerate: `rigor-gyro bench --stress --out proofs`.", "",
           "| scene | what is extreme | verdict | claims (precision that decided them) | time s | precisions tried | "
           "pieces | float path |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        what = r["source"].split(" with ", 1)[-1].rstrip(".") if " with " in r["source"] else r["source"]
        pieces = sum(r["pieces"].values()) if r["pieces"] else "-"
        out.append(f"| `{r['scene']}` | {what} | **{r['verdict']}** | {_outcome(r)} | {r['seconds']:.2f} | "
                   f"{', '.join(map(str, r['precisions_tried']))} | {pieces} | {_float_cell(r)} |")
    return "\n".join(out) + "\n"
