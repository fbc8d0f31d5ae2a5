"""Markdown and JSON of the benchmarks (work-precision per scene, the stress catalog). Answer first."""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from .workprecision import MAX_BITS_LOST, SceneBench

__all__ = ["scene_markdown", "summary_markdown", "write_scene"]


def _g(x: float | None, digits: int = 2) -> str:
    return "-" if x is None else ("0" if x == 0 else f"{x:.{digits}g}")


def _w(log2w) -> str:
    """A relative width from its log2, as 3.1e-153 (no float underflow)."""
    if log2w == "exact":
        return "0"
    if not isinstance(log2w, float):
        return "-"
    e10 = log2w * 0.30102999566398120
    k = math.floor(e10)
    return f"{10 ** (e10 - k):.2g}e{k}"


def _ms(t: dict[str, float]) -> str:
    return f"{1000 * t['median_s']:.1f} [{1000 * t['min_s']:.1f}, {1000 * t['max_s']:.1f}]"


def _worst(sb: SceneBench, row: dict[str, Any]) -> tuple[str, float | None]:
    best = ("-", None)
    for k, lost in row["bits_lost"].items():
        if lost is not None and (best[1] is None or lost > best[1]) and sb.status(k) != "requested width met":
            best = (k, lost)
    return best


def headline(sb: SceneBench) -> str:
    """One sentence: does every quantity follow 2^-p or meet its requested width, and which do not."""
    bad = {q: sb.status(q) for q in sb.quantities if sb.status(q).startswith(("loses", "stuck"))}
    if not bad:
        return (f"every quantity's width follows 2^-p with at most {MAX_BITS_LOST} bits lost, or meets the width "
                "the scene requests")
    return (f"{len(bad)} of {len(sb.quantities)} quantities neither follow 2^-p within {MAX_BITS_LOST} bits nor meet "
            "a requested width: " + ", ".join(f"`{q}` ({s})" for q, s in bad.items()))


def scene_markdown(sb: SceneBench) -> str:
    top = sb.rows[-1]["prec"] if sb.rows else 0
    out = [f"# Work-precision: `{sb.scene}` (kind `{sb.kind}`)", "",
           f"**Answer:** {headline(sb)}.", "",
           "Each proof is pinned at one precision (one attempt, no escalation). Relative width w = 2 rad/|mid|; "
           f"bits lost = log2(w / 2^-p). Times: median [min, max] in ms over repeated runs, warm (imports "
           "excluded). The float and mpmath paths are uncertified scripts (the kind's `approx` module); their "
           f"error is measured against the certified ball at {top} bits. Regenerate: `rigor-gyro bench {sb.scene}`.",
           "", "## Time and verdict per precision", "",
           "| bits | verdict | time ms | worst bits lost (quantity) | slowest phase | pieces |", "|---|---|---|---|---|---|"]
    for r in sb.rows:
        q, lost = _worst(sb, r)
        ph = max(r["phases_s"].items(), key=lambda kv: kv[1], default=None)
        pieces = sum(r["pieces"].values()) if r["pieces"] else 0
        out.append(f"| {r['prec']} | {r['verdict']} | {_ms(r['times'])} | {_g(lost, 3)} (`{q}`) | "
                   + (f"{ph[0]} {1000 * ph[1]:.1f} ms" if ph else "-") + f" | {pieces or '-'} |")
    if sb.methods:
        out += ["", "## Against the uncertified paths", "", "| method | time ms | worst relative error (quantity) | "
                "roots found |", "|---|---|---|---|"]
        arb_row = next((r for r in sb.rows if r["verdict"] == "proved"), sb.rows[-1]) if sb.rows else None
        if arb_row is not None:
            q, _ = max(((k, w) for k, w in arb_row["log2_widths"].items() if isinstance(w, float)),
                       key=lambda kv: kv[1], default=("-", None))
            out.append(f"| Arb, certified, {arb_row['prec']} bits (first precision that proves) | "
                       f"{_ms(arb_row['times'])} | width {_w(arb_row['log2_widths'].get(q))} (`{q}`) | - |")
        for name, m in sb.methods.items():
            if "failed" in m:
                out.append(f"| {name} | - | failed: {m['failed']} | - |")
                continue
            errs = [(k, e) for k, e in m["errors"].items() if e is not None]
            k, e = max(errs, key=lambda kv: kv[1], default=("-", None))
            out.append(f"| {name} | {_ms(m['times'])} | {_g(e)} (`{k}`) | {m.get('found') if m.get('found') is not None else '-'} |")
    out += ["", "## Bits lost per quantity", "",
            "| quantity | " + " | ".join(str(r["prec"]) for r in sb.rows) + f" | w at {top} | status | float error | "
            f"mpmath error |", "|---|" + "---|" * (len(sb.rows) + 4)]
    fl = sb.methods.get("float", {}).get("errors", {})
    mp = next((m.get("errors", {}) for n, m in sb.methods.items() if n.startswith("mpmath")), {})
    for q in sb.quantities:
        cells = [_g(r["bits_lost"].get(q), 3) if q in r["bits_lost"] else "" for r in sb.rows]
        w = sb.rows[-1]["log2_widths"].get(q) if sb.rows else None
        out.append(f"| `{q}` | " + " | ".join(cells) + f" | {_w(w)} | {sb.status(q)} | {_g(fl.get(q))} | {_g(mp.get(q))} |")
    req = sorted({v for v in sb.requested.values()})
    if req:
        out += ["", "Requested widths (4 x the scene's option, relative): " + ", ".join(_w(v) for v in req) + "."]
    return "\n".join(out) + "\n"


def summary_markdown(benches: list[SceneBench]) -> str:
    out = ["# Benchmarks: error against run time", "",
           "Regenerate with `rigor-gyro bench --out proofs/bench --plots` (the built-in scenes) and "
           "`rigor-gyro bench --stress --out proofs` (the stress catalog, `proofs/stress.md`). Times are "
           "machine-dependent; widths and bits lost are not.", "",
           "| scene | answer | most bits lost at the top precision (quantity: bits; quantities at their requested width "
           "left out) | Arb time at 64 / top bits ms | "
           "float ms (worst error) | mpmath30 ms (worst error) |", "|---|---|---|---|---|---|"]
    for sb in benches:
        top = sb.rows[-1]
        lost = sorted(((q, v) for q, v in top["bits_lost"].items()
                       if v is not None and sb.status(q) not in ("requested width met", "exact")),
                      key=lambda kv: -kv[1])[:6]
        bad = sum(1 for q in sb.quantities if sb.status(q).startswith(("loses", "stuck")))
        r64 = next((r for r in sb.rows if r["prec"] == 64), sb.rows[0])

        def meth(name):
            m = sb.methods.get(name)
            if not m or "failed" in m:
                return "-"
            e = max((v for v in m["errors"].values() if v is not None), default=None)
            return f"{1000 * m['times']['median_s']:.1f} ({_g(e)})"
        mp = next((n for n in sb.methods if n.startswith("mpmath")), "")
        out.append(f"| `{sb.scene}` | {'all follow 2^-p or meet the requested width' if not bad else f'{bad} do not'} | "
                   + ", ".join(f"{q}: {v:.0f}" for q, v in lost) +
                   f" | {1000 * r64['times']['median_s']:.1f} / {1000 * top['times']['median_s']:.1f} | "
                   f"{meth('float')} | {meth(mp)} |")
    return "\n".join(out) + "\n"


def write_scene(sb: SceneBench, out: Path) -> list[Path]:
    out.mkdir(parents=True, exist_ok=True)
    md, js = out / f"{sb.scene}.md", out / f"{sb.scene}.json"
    md.write_text(scene_markdown(sb), encoding="utf-8")
    js.write_text(json.dumps(sb.as_json(), indent=1, default=str) + "\n", encoding="utf-8")
    return [md, js]

