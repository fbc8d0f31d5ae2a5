"""Merge campaign results (``rigor-gyro campaign --out DIR`` writes campaign_<kind>_<seed>.json) into
one table: a row per file and a total per kind. Prints Markdown.

    python tools/campaign_summary.py DIR_OR_FILE...
"""
from __future__ import annotations

import json
import sys
from pathlib import Path


def _checked(results):
    """Check failures; '-' for result files written before the campaign ran the checker."""
    if not any("check_failures" in r for r in results):
        return "-"
    return str(sum(1 for r in results if r.get("check_failures")))


def _timed_out(results):
    t = sum(1 for r in results if r.get("timed_out"))
    return f" ({t} timed out)" if t else ""


def rows(paths):
    files = []
    for p in map(Path, paths):
        if not p.exists():
            raise SystemExit(f"campaign_summary: {p} does not exist (give result folders or campaign_KIND_SEED.json files)")
        files += sorted(p.glob("campaign_*.json")) if p.is_dir() else [p]
    per_kind: dict[str, list] = {}
    out = ["| kind | seed(s) | cases | proved | refuted | inconclusive | crashes | containment failures | "
           "verdict disagreements | check failures | values compared | float misses (worst rel. error) | "
           "s/case median (max) | s/case mean |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def line(kind, seeds, results):
        by = {v: sum(1 for r in results if r["verdict"] == v) for v in ("proved", "refuted", "inconclusive")}
        fm = [e for r in results for _, e in r["float_misses"]]
        times = sorted(r["seconds"] for r in results)
        return (f"| {kind} | {seeds} | {len(results)} | {by['proved']} | {by['refuted']} | {by['inconclusive']}"
                f"{_timed_out(results)} | "
                f"{sum(1 for r in results if r['error'])} | {sum(1 for r in results if r['containment_failures'])} | "
                f"{sum(1 for r in results if r['verdict_disagreements'])} | {_checked(results)} | "
                f"{sum(r['compared'] for r in results)} | "
                f"{len(fm)} ({max(fm, default=0.0):.2g}) | {times[len(times) // 2]:.2f} ({times[-1]:.2f}) | "
                f"{sum(times) / len(times):.2f} |")
    for f in files:
        kind, seed = f.stem.split("_", 1)[1].rsplit("_", 1)
        results = json.loads(f.read_text())
        per_kind.setdefault(kind, []).append((seed, results))
        out.append(line(kind, seed, results))
    for kind, items in per_kind.items():
        if len(items) > 1:
            out.append(line(f"**{kind} total**", ", ".join(s for s, _ in items), [r for _, rs in items for r in rs]))
    return out


if __name__ == "__main__":
    print("\n".join(rows(sys.argv[1:] or ["."])))
