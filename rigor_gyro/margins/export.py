"""A paving's leaves as a table for a design review: CSV, one row per piece, every claim's status.

The rows are the pieces of the claims' common refinement (:func:`.safe_set.common_refinement`): on each
piece every claim has one status, so a row gives the piece's edges, each claim's status and ``all``, the
status of "every claim holds" there. Edges are exact: a terminating decimal where the end has one (the
bisection of a decimal box always does), else the fraction ``p/q``; each reads back to the same
rational. Read the file with any spreadsheet or ``csv``/pandas; the certificate stays the result (check
it with ``rigor-gyro check`` first: this reads its leaves as they are).
"""
from __future__ import annotations

import csv
import io

from ..core.boxes import Box, exact_decimal
from .safe_set import common_refinement, conjunction

__all__ = ["leaves_csv"]


def leaves_csv(data: dict) -> str:
    """The CSV text of a paving certificate (schema ``rigor-gyro/paving/1``): header
    ``<p>_lo,<p>_hi,...,<claim>...,all``, one row per piece of the claims' common refinement, in tree order."""
    whole = Box.from_json(data["box"])
    frozen = tuple(data.get("settings", {}).get("unsplit", ()))
    claims = [c["id"] for c in data["claims"]]
    leaves = {c["id"]: [(Box.from_json(b["box"]), b["status"]) for b in c["boxes"]] for c in data["claims"]}
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow([f"{n}_{end}" for n in whole.names for end in ("lo", "hi")] + claims + ["all"])
    for piece, statuses in common_refinement(whole, frozen, leaves):
        edges = [exact_decimal(v) for n in whole.names for v in piece.interval(n)]
        w.writerow(edges + [statuses[c] for c in claims] + [conjunction(statuses)])
    return out.getvalue()
