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
from fractions import Fraction

from ..core.boxes import Box
from .safe_set import common_refinement, conjunction

__all__ = ["exact_decimal", "leaves_csv"]


def exact_decimal(q: Fraction) -> str:
    """``q`` as a terminating decimal when it has one (the exact value, every digit), else ``p/q``."""
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d, twos = d // 2, twos + 1
    while d % 5 == 0:
        d, fives = d // 5, fives + 1
    if d != 1:
        return f"{q.numerator}/{q.denominator}"
    n = max(twos, fives)
    scaled = q * 10 ** n                     # an integer
    sign = "-" if scaled < 0 else ""
    digits = str(abs(scaled.numerator)).rjust(n + 1, "0")
    whole, frac = digits[:len(digits) - n], digits[len(digits) - n:]
    return sign + whole + ("." + frac if n else "")


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
