"""Work-precision of one scene: for each precision of a schedule, pinned (one attempt, no escalation),
the relative enclosure width of every certified quantity, the bits lost, and the wall time; beside it
the float and mpmath (30 digits) paths with their actual errors against the certified values.

Definitions (all reported, none decides anything):

* relative width w = 2 rad / |mid| of a quantity's ball, kept as log2(w) (a float: w itself underflows
  a double below 2^-1074, and 2048-bit enclosures are narrower than that); "exact" for a zero radius;
* bits lost = log2(w / 2^-p) = log2(w) + p at precision p: how far the enclosure is from the precision's resolution;
* a quantity *follows the precision* at p when it lost at most ``MAX_BITS_LOST`` bits, and *meets the
  requested width* when w is at most the width the scene requests (options ``rel_width``, or
  ``theta_width`` for theta*); otherwise it is *stuck* (a constant somewhere caps it);
* a method's actual error = |value - mid| / |mid| against the certified ball at the highest precision
  (its radius is negligible beside any error shown).

Times are the median, min and max of ``repeat`` runs in this process (warm: the import is excluded).
"""
from __future__ import annotations

import importlib
import math
import statistics
import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from flint import arb

from ..core.balls import working_precision
from ..kinds import KINDS, kind_module
from ..prover import prove_scene
from ..scene import Scene

__all__ = ["SCHEDULE", "MAX_BITS_LOST", "MP_DPS", "SceneBench", "bench_scene", "relative_width", "log2_width",
           "bits_lost",
           "relative_error", "float_hint", "requested_widths"]

#: the precision schedule (bits)
SCHEDULE = (53, 64, 128, 256, 512, 1024, 2048)
#: the goal: at most this many bits lost, or the requested width met
MAX_BITS_LOST = 10
#: digits of the mpmath path
MP_DPS = 30


def relative_width(x: arb) -> float | None:
    """2 rad / |mid| as a float (0.0 for an exact ball; None for a non-finite ball or one containing 0)."""
    if not x.is_finite() or x.contains(0):
        return None
    if x.rad() == 0:
        return 0.0
    return float(2 * x.rad() / abs(x.mid()))


def log2_width(x: arb) -> float | str | None:
    """log2 of the relative width 2 rad / |mid|, computed in balls (no underflow at any precision);
    "exact" for a zero radius; None for a non-finite ball or one containing 0."""
    if not x.is_finite() or x.contains(0):
        return None
    if x.rad() == 0:
        return "exact"
    with working_precision(64):
        return float((2 * x.rad() / abs(x.mid())).log() / arb(2).log())


def bits_lost(log2w, prec: int) -> float | None:
    """log2(w / 2^-prec) = log2(w) + prec; None for an exact or unknown width."""
    if not isinstance(log2w, float):
        return None
    return log2w + prec


def relative_error(value, ball: arb) -> float | None:
    """|value - mid| / |mid| for a float or an mpmath number, computed in balls from its decimal text."""
    with working_precision(512):     # arb(text) rounds to the working precision: never at 53 bits here
        try:
            v = arb(value if isinstance(value, str) else _text(value))
        except Exception:
            return None
        if not (v.is_finite() and ball.is_finite()) or ball.mid() == 0:
            return None
        return float(abs(v - ball.mid()) / abs(ball.mid()))


def _text(value) -> str:
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else "nan"
    import mpmath
    return mpmath.nstr(value, 60, strip_zeros=False)


@dataclass
class SceneBench:
    """The measurements of one scene (JSON-able through :meth:`as_json`)."""

    scene: str
    kind: str
    requested: dict[str, float]
    rows: list[dict[str, Any]] = field(default_factory=list)          # one per precision
    methods: dict[str, dict[str, Any]] = field(default_factory=dict)  # float, mpmath30
    quantities: list[str] = field(default_factory=list)

    def as_json(self) -> dict[str, Any]:
        return {"scene": self.scene, "kind": self.kind, "requested_widths": self.requested,
                "max_bits_lost": MAX_BITS_LOST, "quantities": self.quantities, "precisions": self.rows,
                "methods": self.methods}

    def status(self, name: str) -> str:
        """At the highest precision that gave a width: 'follows 2^-p' (at most MAX_BITS_LOST bits lost),
        'requested width met', 'exact', 'contains 0' (no relative width), 'loses N bits' (the width
        shrinks like 2^-p, more than MAX_BITS_LOST bits lost) or 'stuck' (it did not shrink from the
        precision before by at least half the precision gained: a constant caps it)."""
        have = [r for r in self.rows if name in r["log2_widths"]]
        if not have:
            return "absent"
        last = have[-1]
        w = last["log2_widths"][name]
        if w == "exact":
            return "exact"
        if w is None:
            return "contains 0"
        lost = bits_lost(w, last["prec"])
        if lost <= MAX_BITS_LOST:
            return "follows 2^-p"
        req = self.requested.get(name)
        if req is not None and w <= req:
            return "requested width met"
        prev = have[-2]["log2_widths"][name] if len(have) > 1 else None
        if isinstance(prev, float) and w > prev - (last["prec"] - have[-2]["prec"]) / 2:
            return "stuck"
        return f"loses {lost:.0f} bits"


def requested_widths(scene: Scene, cert) -> dict[str, float]:
    """Per quantity, log2 of the relative width the scene requests (its options or the kind's defaults;
    times 4: derived quantities combine a few requested ones)."""
    claims = importlib.import_module(KINDS[scene.kind] + ".claims")
    opts = {**getattr(claims, "OPTIONS", {}), **scene.options}
    out: dict[str, float] = {}
    if "rel_width" in opts and opts["rel_width"]:
        rw = math.log2(4 * float(Fraction(str(opts["rel_width"]))))
        for name in cert.quantities:
            out[name] = rw
    if "theta_width" in opts and "theta_star" in cert.quantities:
        th = float(cert.quantities["theta_star"].mid())
        for name in ("theta_star", "period"):
            out[name] = math.log2(4 * float(Fraction(str(opts["theta_width"]))) / th)
    return out


def _timed(fn, repeat: int):
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, {"median_s": statistics.median(times), "min_s": min(times), "max_s": max(times)}


def float_hint(cert) -> dict[str, float]:
    """Where the float paths should look (a root finder needs a start or a range; a user would have a
    plot): the certified theta* (float), and the range the certificate searched, (theta_min, T], so a
    float root count is comparable with the certified one."""
    q = cert.quantities
    if "theta_star" not in q:
        return {}
    th = float(q["theta_star"].mid())
    hint = {"theta_star": th, "T": 2.2 * th}
    w = (cert.witnesses or {}).get("half_period") or {}
    try:
        hint["T"] = float(Fraction(w["T"]))
        hint["t0"] = float(Fraction(w["theta_min"]))
    except (KeyError, ValueError, ZeroDivisionError):
        pass
    return hint


def _method(scene: Scene, cert, name: str, repeat: int) -> dict[str, Any]:
    approx = importlib.import_module(KINDS[scene.kind] + ".approx")
    params = dict(scene.parameters)
    hint = float_hint(cert)
    fn = (lambda: approx.bench_float(params, hint=hint)) if name == "float" else \
        (lambda: approx.bench_mpmath(params, dps=MP_DPS, hint=hint))
    try:
        values, t = _timed(fn, repeat)
    except Exception as e:    # a float path that fails is a finding about the float path
        return {"failed": f"{type(e).__name__}: {e}"[:200]}
    errors = {}
    for k, v in values.items():
        if k in cert.quantities:
            errors[k] = relative_error(v, cert.quantities[k])
    return {"times": t, "errors": errors, "found": values.get("found")}


def bench_scene(scene: Scene, schedule=SCHEDULE, repeat: int = 3, methods: bool = True,
                progress=None) -> SceneBench:
    """Prove ``scene`` pinned at each precision of ``schedule`` (``repeat`` times each), then run the
    float and mpmath paths ``repeat`` times; see the module docstring."""
    kind_module(scene.kind)
    best = None
    sb = SceneBench(scene.name, scene.kind, {})
    for p in schedule:
        if progress:
            progress(f"{scene.name}: {p} bits")
        cert, t = _timed(lambda: prove_scene(scene, prec=p, maxprec=p), repeat)
        widths = {k: log2_width(x) for k, x in cert.quantities.items()}
        sb.rows.append({"prec": p, "verdict": cert.verdict.value, "times": t, "log2_widths": widths,
                        "bits_lost": {k: bits_lost(w, p) for k, w in widths.items()},
                        "phases_s": cert.timings.get("final_attempt_phases_s", {}),
                        "pieces": cert.timings.get("pieces", {}),
                        "claims": {c.id: c.status.value for c in cert.claims}})
        for k in cert.quantities:
            if k not in sb.quantities:
                sb.quantities.append(k)
        best = cert
    sb.requested = requested_widths(scene, best)
    if methods:
        for name in ("float", f"mpmath{MP_DPS}"):
            if progress:
                progress(f"{scene.name}: {name}")
            sb.methods[name] = _method(scene, best, "float" if name == "float" else "mpmath", repeat)
    return sb
