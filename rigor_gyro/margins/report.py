"""The paving certificate (JSON, schema ``rigor-gyro/paving/1``) and its Markdown report.

The JSON holds the scene exactly as written, the whole box, the settings, and per claim: the status
over the whole box, the volume fractions (exact rationals, and decimals for reading), every final
sub-box with its outcome (exact endpoints), and the point proofs at sub-box midpoints; a paving that
stopped early (``stopped``) also lists its ``pending`` boxes (queued, not yet evaluated: undecided
leaves of their open claims, which :mod:`.resume` continues). It is
byte-identical for every executor and worker count (wall times go to ``timings/<name>.json``).
``rigor-gyro check`` re-evaluates it (:func:`check_paving`).
"""
from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

from ..certificate import digest
from ..core.boxes import fraction_text
from ..report import write_pair
from ..version import __version__
from .paving import SCHEMA, Paving
from .ranges import summarise

__all__ = ["claim_numbers", "decimal_text", "paving_json", "render_paving", "write_paving"]


def decimal_text(q: Fraction, digits: int = 6) -> str:
    """A volume fraction or an end for reading (``digits`` significant digits; the exact value is stored
    beside it). The paving checker re-derives it."""
    return f"{float(q):.{digits}g}"


def claim_numbers(vol: dict[str, Fraction], statuses: list[str]) -> dict[str, dict]:
    """The numbers a paving states for a claim: its volume fractions (exact, and for reading) and its
    sub-box counts, from the fractions ``vol`` and each sub-box's status. The paving checker re-derives
    them with this function from its own volumes."""
    return {"volume_fraction": {k: fraction_text(v) for k, v in vol.items()},
            "volume_fraction_decimal": {k: decimal_text(v) for k, v in vol.items()},
            "sub_boxes": {k: sum(1 for s in statuses if s == k) for k in ("proved", "refuted", "undecided")}}


def ranges_json(bs, search) -> dict[str, Any]:
    """The quantities' ranges (:func:`.ranges.summarise`), the tiles they were enclosed on and the points
    they cite (only those: the checker re-evaluates each, and the summary of the cited points is the
    summary of all the points evaluated, whose minima and maxima they are)."""
    items = summarise(bs.box, search.specs, search.tiles, search.points)
    cited = []
    for it in items:
        for end in ("low", "high"):
            pt = it.get("points", {}).get(end, {}).get("point")
            if pt is not None and pt not in cited:
                cited.append(pt)
    return {"quantities": items, "range_tiles": [b.to_json() for b, _ in search.tiles],
            "range_points": cited}


def paving_json(p: Paving) -> dict[str, Any]:
    bs = p.bs
    claims = []
    for c in p.claims:
        claims.append({
            "id": c.id, "statement": c.statement, "status": c.status,
            **claim_numbers(c.volume(bs.box), [s for _, s in c.boxes]),
            "reasons": dict(sorted(c.reasons.items())),
            "points": c.points,
            "boxes": [{"box": b.to_json(), "status": s} for b, s in c.boxes],
            **{k: c.search[k] for k in ("counterexample_search", "monte_carlo") if k in c.search},
        })
    data = {
        "schema": SCHEMA,
        "scene": bs.scene.header(),
        "software": {"rigor_gyro": __version__},
        "box": bs.box.to_json(),
        "point_parameters": dict(bs.points),
        "settings": bs.settings(),
        "verdict": p.verdict,
        "boxes_evaluated": p.evaluated, "levels": p.levels, "budget_exhausted": p.budget_hit,
        "claims": claims,
        "not_box_claims": bs.skipped,
    }
    if p.stopped:       # only then, so that a paving that ran its course is byte-identical to before
        data["stopped"] = p.stopped
        data["pending"] = [g.to_json() for g in p.pending]
    if p.ranges is not None:
        data.update(ranges_json(bs, p.ranges))
    data["integrity"] = {"sha256": digest(data)}
    return data


def _render_search(data: dict[str, Any], c: dict[str, Any]) -> list[str]:
    """The counterexample search over the undecided leaves and the Monte Carlo cross-check, when stored."""
    out = []
    cs = c.get("counterexample_search")
    if cs and "skipped" in cs:
        out.append(f"- counterexample search skipped: {cs['skipped']}")
    elif cs:
        found = [p for p in cs["proofs"] if p["status"] == "refuted"]
        line = (f"- counterexample search over all {cs['undecided_leaves']} undecided sub-box(es) "
                f"({cs['settings']['samples']} Halton samples, {len(cs['proofs'])} candidate(s) proved point by "
                f"point): {len(found)} certified counterexample(s) in {len(cs['leaves'])} sub-box(es)")
        if found:
            line += "; the first: " + ", ".join(f"{k} = {v}" for k, v in found[0]["point"].items() if k in data["box"])
        out.append(line)
    mc = c.get("monte_carlo")
    if mc and "skipped" in mc:
        out.append(f"- Monte Carlo cross-check skipped: {mc['skipped']}")
    elif mc:
        lo, hi = mc["interval"]
        out.append(f"- Monte Carlo cross-check (evidence, not proof): {mc['failing']} of {mc['samples']} uniform "
                   f"samples fail ({mc['unknown']} undecided), failing fraction in [{lo:.4f}, {hi:.4f}] at "
                   f"{mc['confidence']:.3g} confidence; the certified refuted fraction is "
                   f"{c['volume_fraction_decimal']['refuted']} and the undecided {c['volume_fraction_decimal']['undecided']}: "
                   + ("consistent" if mc.get("consistent") else "NOT consistent (a bug in the paving or the sampling)"))
    return out


def render_paving(data: dict[str, Any]) -> str:
    """The report: the answer first (verdict per claim with its volume fractions), then the settings."""
    box = ", ".join(f"{k} in [{decimal_text(Fraction(v[0]), 10)}, {decimal_text(Fraction(v[1]), 10)}]"
                    for k, v in data["box"].items())
    out = [f"# {data['scene']['name']}: {data['verdict'].upper()} over the box {box}", ""]
    out.append("| claim | over the whole box | proved volume | refuted volume | undecided volume | sub-boxes (p/r/u) |")
    out.append("|---|---|---|---|---|---|")
    for c in data["claims"]:
        v, n = c["volume_fraction_decimal"], c["sub_boxes"]
        out.append(f"| {c['id']} | **{c['status']}** | {v['proved']} | {v['refuted']} | {v['undecided']} | "
                   f"{n['proved']}/{n['refuted']}/{n['undecided']} |")
    out.append("")
    out.extend(_render_ranges(data))
    for c in data["claims"]:
        out.append(f"## {c['id']}: {c['status']}")
        out.append("")
        out.append(c["statement"])
        out.append("")
        for k, why in c["reasons"].items():
            out.append(f"- a sub-box {k}: {why}")
        ce = [p for p in c["points"] if p["status"] == "refuted"]
        if ce:
            pt = ce[0]["point"]
            out.append(f"- certified counterexample ({len(ce)} point(s) re-proved refuted; the first): "
                       + ", ".join(f"{k} = {v}" for k, v in pt.items() if k in data["box"])
                       + f": {ce[0]['reason']}")
        out.extend(_render_search(data, c))
        und = [p for p in c["points"] if p["box_outcome"] == "undecided"]
        if und:
            out.append(f"- the midpoints of {len(und)} undecided sub-box(es), proved point by point: "
                       + ", ".join(f"{s}: {sum(1 for p in und if p['status'] == s)}"
                                   for s in ("proved", "refuted", "inconclusive")))
        out.append("")
    s = data["settings"]
    if s.get("unsplit"):
        out.append(f"Not split: {', '.join(s['unsplit'])} (the box claims do not depend on it; the kind's boxes "
                   "module says why, and decides each sub-box at its lower end there).")
        out.append("")
    out.append(f"Settings: box_resolution {s['box_resolution']} of each edge, max_boxes {s['max_boxes']}, box "
               f"evaluations at {s['box_prec']} bits; {_count(data['boxes_evaluated'], 'box', 'boxes')} evaluated in "
               f"{_count(data['levels'], 'level', 'levels')}" + (f"; stopped: {data['stopped']}, {_pending_text(data)} and no point "
                                      "proof run" if data.get("stopped") else "; the box budget was exhausted"
                                      if data["budget_exhausted"] else "") + "."
               + (f" Boxes evaluated {s['priority']} first." if s.get("priority") else ""))
    if data["not_box_claims"]:
        out.append("")
        out.append(f"Not decided over boxes (point claims only): {', '.join(data['not_box_claims'])}.")
    out.append("")
    out.append("A sub-box is *proved* when the claim holds for every parameter value in it, *refuted* when it fails "
               "for every value in it (certified on balls containing the sub-box, or at one value of a parameter the "
               "claims do not depend on), *undecided* otherwise; a "
               "resolution or budget never refutes. The JSON beside this file lists every sub-box exactly "
               f"(schema `{data['schema']}`).")
    out.append("")
    return "\n".join(out)


def _count(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _pending_text(data: dict[str, Any]) -> str:
    """What a stopped paving left open, and how to continue it."""
    pending = data.get("pending")
    if pending is None:             # written before pavings listed their pending boxes
        return "the open sub-boxes left undecided"
    n = sum(len(g["boxes"]) for g in pending)
    if not n:
        return "no box left pending"
    return (f"{n} pending sub-box(es) left undecided (`rigor-gyro prove --resume {data['scene']['name']}.json` "
            "continues the paving)")


def _point_text(point: dict[str, str]) -> str:
    return ", ".join(f"{k} = {decimal_text(Fraction(v), 8)}" for k, v in point.items())


def _render_ranges(data: dict[str, Any]) -> list[str]:
    """The numbers over the box: worst-case margins first, then every quantity's ranges and sensitivities."""
    items = data.get("quantities")
    if not items:
        return []
    out = []
    for it in items:
        w = it.get("worst_case")
        if w is None:
            continue
        where = "" if it["enclosed_fraction"] == "1" else f" (on the {decimal_text(Fraction(it['enclosed_fraction']), 4)} of the box's volume where it was enclosed)"
        at = _point_text(it['points']['low']['point'])
        if Fraction(w["gap"]) < 0:      # a point outside the enclosed part goes below its bound: say so first
            out.append(f"- **{it['description']}: a value <= {w['attained_at_most']} is attained at {at}** (certified), "
                       f"below {w['lower_bound']}, the certified lower bound{where}: the point lies outside that part, "
                       "and no lower bound over the whole box is certified.")
            continue
        rel = f", relative gap {w['relative_gap']}" if w["relative_gap"] is not None else ""
        out.append(f"- **{it['description']} >= {w['lower_bound']}** for every parameter value in the box{where} "
                   f"(certified); a value <= {w['attained_at_most']} is attained at {at} (gap {w['gap']}{rel}).")
    if out:
        out = ["Worst cases over the box (claim margins: the claim holds where the margin is > 0):", ""] + out + [""]
    out.append("| quantity | unit | every value in the box lies in (certified) | every value here is taken (certified) | "
               "largest effect of a tolerance |")
    out.append("|---|---|---|---|---|")
    for it in items:
        o = it["outer"]
        outer = "not enclosed" if o is None else f"[{o['lo']}, {o['hi']}]"
        if o is not None and it["enclosed_fraction"] != "1":
            outer += f" on {decimal_text(Fraction(it['enclosed_fraction']), 4)} of the volume"
        inner = it.get("inner")
        inner = "-" if not inner else f"[{inner['lo']}, {inner['hi']}]"
        sens = it.get("sensitivities") or []
        top = "-" if not sens else "; ".join(
            f"{s['parameter']}: <= {s['effect_at_most']}" + (f" ({s['monotone']})" if s["monotone"] else "")
            for s in sens[:3])
        out.append(f"| {it['id']}: {it['description']} | {it['unit'] or '-'} | {outer} | {inner} | {top} |")
    out.append("")
    for it in items:
        if it.get("branches"):
            out.append(f"- {it['id']}: {it['branches']}.")
            out.append("")
    out.append(f"Ranges from {len(data['range_tiles'])} sub-boxes tiling the box (each enclosure contains the quantity over "
               "its whole sub-box) and certified values at sub-box midpoints and corners; a tolerance's effect is at most the largest "
               "|dq/dk| over the box times k's half-width (monotone: the derivative's sign is certain on the whole box).")
    out.append("")
    return out


def write_paving(p: Paving, out_dir: str | Path) -> tuple[Path, Path]:
    data = paving_json(p)
    return write_pair(out_dir, data["scene"]["name"], json.dumps(data, indent=1, ensure_ascii=False) + "\n",
                      render_paving(data), {"total_s": round(p.seconds, 3), "executor": p.executor})
