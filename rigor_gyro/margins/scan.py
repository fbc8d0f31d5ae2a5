"""Scans: a scene's claims proved point by point along one parameter (``rigor-gyro margin --scan N``).

The N points are exact decimals from ``lo`` to ``hi`` (both included), evenly spaced, or evenly spaced
in log scale with ``--log`` (each point rounded to 12 significant digits, then taken exactly). Each is
proved by the point prover, on the executor of the pavings (a process pool or Dask; the results come
back in the order of the points, so the map is the same whatever the executor). The result is a map of
point proofs: at each of the N exact points, each claim's status is a theorem (and the quantities asked
for are certified enclosures there); nothing is said between the points (a threshold bisection or a
paving of a tolerance box does that).

Exit status: 0 every point decided every claim (proved or refuted), 3 some point left a claim
inconclusive; never 1 (a scan is a map, not a claim over the range); 2 bad input (the parameter is
absent, a tolerance or not rational; lo >= hi; --log with lo <= 0; N outside [2, 10000]; a point
outside the kind's domain; a quantity the kind does not report).
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from ..core.balls import rational_text
from ..core.boxes import fraction_text, is_tolerance
from ..core.errors import ParameterError, RigorGyroError
from ..kinds import kind_module, scene_claims
from ..scene import Scene
from .models import settings_json, task_scene
from .threshold import search_range

__all__ = ["Scan", "scan_points", "run_scan", "write_scan", "check_scan", "statement", "SCHEMA"]

SCHEMA = "rigor-gyro/scan/1"
MAX_POINTS = 10000


def scan_points(lo: Fraction, hi: Fraction, n: int, log: bool) -> list[Fraction]:
    """N exact points from lo to hi (ends exact; interior points rounded to 12 significant digits)."""
    if log:
        import math
        a, b = math.log10(lo), math.log10(hi)
        inner = [Fraction(f"{10 ** (a + (b - a) * i / (n - 1)):.11e}") for i in range(1, n - 1)]
    else:
        inner = [Fraction(f"{float(lo + (hi - lo) * Fraction(i, n - 1)):.11e}") for i in range(1, n - 1)]
    out = [lo]
    for x in inner:             # strictly increasing and strictly inside (lo, hi), whatever the rounding did
        if out[-1] < x < hi:
            out.append(x)
    return out + [hi]


def scan_task(kind: str, params_json: str, options_json: str, claims: tuple[str, ...],
              quantities: tuple[str, ...]) -> dict[str, Any]:
    """The point prover at one exact parameter point (strings in, JSON-able data out)."""
    from ..core.balls import decimal_bounds
    from ..prover import prove_scene
    scene = task_scene("scan_point", kind, "margin scan point", json.loads(params_json), options_json, list(claims))
    cert = prove_scene(scene)
    out: dict[str, Any] = {"claims": {}, "quantities": {}, "precision_bits": cert.precision_bits}
    for c in claims:
        cl = cert.claim(c)
        out["claims"][c] = {"status": cl.status.value, "reason": cl.reason[:300]}
    for q in quantities:
        v = cert.quantities.get(q)
        out["quantities"][q] = list(decimal_bounds(v, 12)) if v is not None and v.is_finite() else None
    return out


@dataclass
class Scan:
    scene: Scene
    param: str
    claims: list[str]
    quantities: list[str]
    values: list[Fraction]
    log: bool
    results: list[dict[str, Any]] = field(default_factory=list)

    @property
    def exit_code(self) -> int:
        decided = all(r["claims"][c]["status"] in ("proved", "refuted") for r in self.results for c in self.claims)
        return 0 if decided else 3

    def counts(self) -> dict[str, dict[str, int]]:
        out = {c: {"proved": 0, "refuted": 0, "inconclusive": 0} for c in self.claims}
        for r in self.results:
            for c in self.claims:
                out[c][r["claims"][c]["status"]] = out[c].get(r["claims"][c]["status"], 0) + 1
        return out

    def lines(self) -> list[str]:
        head = (f"{self.scene.name}: scan of {self.param} over [{_d(self.values[0])}, {_d(self.values[-1])}] "
                f"({len(self.values)} exact points{', log-spaced' if self.log else ''}; point proofs, nothing "
                "is claimed between the points)")
        out = [head]
        for c, k in self.counts().items():
            out.append(f"  {c}: proved at {k['proved']}, refuted at {k['refuted']}, inconclusive at "
                       f"{k['inconclusive']} of {len(self.values)} points")
        return out

    def to_json(self) -> dict[str, Any]:
        return {"schema": SCHEMA, "scene": self.scene.header(), "param": self.param,
                "claims": self.claims, "quantities": self.quantities, "log": self.log,
                "statement": statement(self.param),
                "counts": self.counts(),
                "points": [{"value": fraction_text(v), **r} for v, r in zip(self.values, self.results)]}

    def markdown(self) -> str:
        cols = self.claims + self.quantities
        rows = [f"# {self.lines()[0]}", ""] + [f"- {x.strip()}" for x in self.lines()[1:]] + [
            "", "Each cell is a point proof at that exact value (the other parameters as in the scene); the "
            "quantities are certified enclosures of what the scene reports there (for the relay kind: of the orbit "
            "theta_star, the shortest stable genuine orbit when one is stable, else the shortest genuine orbit; the "
            "`stable` claim holds when some genuine orbit is stable; with the scene's option `orbit` every claim "
            "and quantity is about the one root of g nearest that half-period, so that a scan follows one orbit "
            "instead of whichever is stable at each point).",
            "", f"| {self.param} | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
        for v, r in zip(self.values, self.results):
            cells = [r["claims"][c]["status"] for c in self.claims]
            for q in self.quantities:
                b = r["quantities"].get(q)
                cells.append(f"[{b[0]}, {b[1]}]" if b else "-")
            rows.append(f"| {_d(v)} | " + " | ".join(cells) + " |")
        return "\n".join(rows) + "\n"


def statement(param: str) -> str:
    """What a scan output states, as its checker re-derives it."""
    return (f"at each exact value of {param} listed, each claim has the status given (a point proof at that value, "
            "the other parameters as in the scene); nothing is claimed between the values")


def _d(q: Fraction) -> str:
    """The exact decimal of q (every scan point has one; 1/5 -> "0.2"), or "n/d" for an end that does not
    terminate (1/3 -> "1/3"); never through a float."""
    return rational_text(q)


def run_scan(scene: Scene, param: str, n: int, *, lo: str | None = None, hi: str | None = None,
             claim: str | None = None, quantities: list[str] | None = None, log: bool = False,
             workers: int | None = 1, scheduler: str | None = None) -> Scan:
    """Prove ``scene``'s claims (or ``claim``) at ``n`` exact values of ``param`` between lo and hi."""
    module = kind_module(scene.kind)
    if param not in scene.parameters:
        raise ParameterError(f"--param {param!r} is not a parameter of scene {scene.name!r}; it has "
                             f"{sorted(scene.parameters)}")
    if any(is_tolerance(v) for v in scene.parameters.values()):
        raise ParameterError("--scan needs a scene of points (write every parameter as a number; a tolerance "
                             "box is paved by `rigor-gyro prove`)")
    module.validate(scene)
    if not 2 <= n <= MAX_POINTS:
        raise ParameterError(f"--scan {n}: need 2 <= N <= {MAX_POINTS}")
    default, every = scene_claims(module, scene)        # a [system] scene's own claims, not the paper kind's
    claims = list(default) if scene.claims_only is None else [c for c in every if c in scene.claims_only]
    if claim is not None:
        if claim not in every:
            raise ParameterError(f"--claim {claim!r}: scene {scene.name!r} has {list(every)}")
        claims = [claim]
    quantities = list(quantities or [])
    bad = [q for q in quantities if q not in getattr(module, "HEADLINE", {})]
    if bad:
        raise ParameterError(f"--quantity {bad[0]!r}: kind {scene.kind!r} reports {sorted(module.HEADLINE)}")

    lo_q, hi_q = search_range(scene, param, lo, hi)
    if log and not lo_q > 0:
        raise ParameterError(f"--log needs --lo > 0 (got {lo_q})")
    values = scan_points(lo_q, hi_q, n, log)
    for x in (values[0], values[-1]):               # the domain, checked before any work
        try:
            module.validate(Scene(name=scene.name, kind=scene.kind, source=scene.source,
                                  parameters={**scene.parameters, param: fraction_text(x)}, options=dict(scene.options),
                                  model=dict(scene.model)))
        except ParameterError as e:
            raise ParameterError(f"{param} = {_d(x)} is outside the kind's domain: {e}") from None
    options_json = settings_json(scene.options, scene.model)
    tasks = [(scene.kind, json.dumps({**scene.parameters, param: fraction_text(x)}, sort_keys=True), options_json,
              tuple(claims), tuple(quantities)) for x in values]
    from .executors import make_executor
    ex = make_executor(workers, scheduler)
    try:
        results = ex.map(scan_task, tasks)
    finally:
        ex.close()
    return Scan(scene, param, claims, quantities, values, log, results)


def write_scan(res: Scan, out_dir: str) -> list[Path]:
    from ..report import write_pair
    return list(write_pair(out_dir, f"scan_{res.scene.name}_{res.param}", json.dumps(res.to_json(), indent=1) + "\n",
                           res.markdown(), None))


def check_scan(data: dict[str, Any], max_points: int | None = None) -> list[tuple[str, bool, str]]:
    """Re-verify a scan output (schema ``rigor-gyro/scan/1``, already validated against its JSON Schema) as
    (item, ok, message) triples.

    Checked: the scene, parameter, claims and quantities valid for the kind (as :func:`run_scan` requires);
    the points exact, strictly increasing, each with exactly the claims and quantities listed; the counts
    and the statement re-derived; then every point re-proved by the point prover, which is deterministic:
    each stored status (proved, refuted or inconclusive), reason and ``precision_bits`` must be the
    re-proof's own, and each stored quantity interval (or null) the re-computed one, digit for digit.
    ``max_points``: re-prove only that many points, evenly spread with both ends (a quick look); the points
    not re-proved are then unverified, so the ``re-proved`` item FAILS, saying only a sample was re-proved
    (a sample never confirms a scan)."""
    out: list[tuple[str, bool, str]] = []

    def add(item: str, ok: bool, message: str) -> None:
        out.append((item, bool(ok), message))

    sc = data["scene"]
    try:
        scene = Scene.from_header(sc)
        module = kind_module(scene.kind)
        param, claims, quantities = data["param"], list(data["claims"]), list(data["quantities"])
        if param not in scene.parameters or any(is_tolerance(v) for v in scene.parameters.values()):
            raise ParameterError(f"{param!r} is not a parameter of a scene of points")
        if not claims or any(c not in scene_claims(module, scene)[1] for c in claims) or len(set(claims)) != len(claims):
            raise ParameterError(f"claims {claims} are not distinct claims of scene {scene.name!r}")
        if any(q not in getattr(module, "HEADLINE", {}) for q in quantities):
            raise ParameterError(f"quantities {quantities}: kind {scene.kind!r} reports {sorted(module.HEADLINE)}")
        module.validate(scene)
    except (RigorGyroError, TypeError, ValueError, KeyError) as e:
        add("scene", False, f"the scan's scene, parameter, claims or quantities are not valid: {e}")
        return out
    from .identity import builtin_differs
    differs = builtin_differs(sc)
    add("scene", differs is None, differs or f"scene {scene.name!r}, parameter {param!r}, claims {claims} valid for "
        "the kind")
    points = data["points"]
    values = [Fraction(p["value"]) for p in points]
    add("points", len(values) >= 2 and all(a < b for a, b in zip(values, values[1:]))
        and all(list(p["claims"]) == claims and list(p["quantities"]) == quantities for p in points),
        f"{len(values)} exact points, strictly increasing, each with the claims and quantities listed")
    counts = {c: {k: sum(1 for p in points if p["claims"][c]["status"] == k)
                  for k in ("proved", "refuted", "inconclusive")} for c in claims}
    add("counts", data["counts"] == counts, "the counts re-derived from the points")
    add("statement", data["statement"] == statement(param), "the scan's statement")
    n = len(points)
    k = n if max_points is None else max(2, max_points)
    sampled = n > k
    picked = sorted({round(i * (n - 1) / (k - 1)) for i in range(k)}) if sampled else list(range(n))
    options_json = settings_json(scene.options, scene.model)
    bad: list[str] = []
    for i in picked:
        x, stored = values[i], points[i]
        res = scan_task(scene.kind, json.dumps({**scene.parameters, param: fraction_text(x)}, sort_keys=True),
                        options_json, tuple(claims), tuple(quantities))
        at = f"{param} = {_d(x)}"
        for c in claims:
            st, got = stored["claims"][c], res["claims"][c]
            if st["status"] != got["status"]:
                bad.append(f"{c} at {at}: stored {st['status']}, re-decided {got['status']}")
            elif st.get("reason") != got["reason"]:
                bad.append(f"{c} at {at}: the stored reason is not the re-proof's own ({got['reason'][:120]!r})")
        if stored.get("precision_bits") != res["precision_bits"]:
            bad.append(f"{at}: precision_bits {stored.get('precision_bits')!r}, the re-proof's {res['precision_bits']}")
        for q in quantities:
            s_b, r_b = stored["quantities"][q], res["quantities"][q]
            if s_b != r_b:      # the same decimals (12 digits, outward), or null where the re-proof has none
                bad.append(f"{q} at {at}: stored {s_b}, not the re-computed {r_b}" + (
                    " (it does not contain it)" if s_b is not None and r_b is not None and not
                    Fraction(s_b[0]) <= Fraction(r_b[0]) <= Fraction(r_b[1]) <= Fraction(s_b[1]) else ""))
    mismatch = "" if not bad else f": {len(bad)} mismatch(es), first: {bad[0]}"
    if sampled:
        add("re-proved", False, f"only a sample was re-proved ({len(picked)} of {n} points, evenly spread, both "
            f"ends){mismatch}: the other points are not verified (re-prove every point: the default)")
    else:
        add("re-proved", not bad, f"all {n} points re-proved (status, reason, precision, quantities)" + mismatch)
    return out
