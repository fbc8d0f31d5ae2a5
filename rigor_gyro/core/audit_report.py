"""The audit section of a report (issue 39; rendered by rigor_gyro.report, kept here as text-only code
on the stored rows): counts by class, then the misprints found (printed ->
intended, the evidence in one line), then the paper's arithmetic by table (prints that its own inputs
reproduce though the exact value differs), then the unexplained rows with their nearest chain value,
then the verbal assertions and the rows that agree.

Guarantee: text only, from the certificate's stored rows (no number is recomputed here). Failure mode:
none (a row without a class is listed under its status).
"""
from __future__ import annotations

import re
from decimal import Decimal, InvalidOperation, ROUND_HALF_EVEN, localcontext
from typing import Any

__all__ = ["audit_section", "MISPRINT_CLASSES", "ARITHMETIC_CLASSES", "table_of"]

#: classes that say "the print is not what the author computed"
MISPRINT_CLASSES = ("sign", "decimal-shift", "digits-transposed", "digit-dropped", "digit-doubled", "digit-substituted",
                    "multi-digit-substituted", "propagated-misprint", "misprint-reading")
#: classes that say "the author's own arithmetic" (the print reproduces from the paper's own inputs)
ARITHMETIC_CLASSES = ("propagated", "last-digit")
_PLAIN = ("agrees", "assertion-confirmed")
#: a misprint's evidence is cut to this many characters in the report (the JSON has it whole)
_LINE = 260


def _esc(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def table_of(rid: str, rules=()) -> str:
    """The part of the paper a row belongs to, for grouping the arithmetic: the first of ``rules``
    ((regex, name), ...: the report's per-paper table names) that matches the row id, else "Table N" when
    the id starts so, else "other rows"."""
    for pat, name in rules:
        if re.search(pat, rid):
            return name
    m = re.match(r"^(Table \d+)", rid)
    return m.group(1) if m else "other rows"


def _certified_digits(lo: str, hi: str, printed: str, extra: int = 3) -> str:
    try:
        a, b, p = Decimal(lo), Decimal(hi), Decimal(printed.strip())
    except (InvalidOperation, ValueError):
        return f"[{lo}, {hi}]" if lo else ""
    with localcontext() as c:
        c.prec = max(len(p.as_tuple().digits), 1) + extra
        c.rounding = ROUND_HALF_EVEN
        ra, rb = +a, +b
    return str(ra) if ra == rb else f"[{lo}, {hi}]"


def _counts(rows: list[dict]) -> list[tuple[str, int]]:
    counts: dict[str, int] = {}
    for r in rows:
        k = r.get("class", r["status"])
        counts[k] = counts.get(k, 0) + 1
    return sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))


def _one_line(r: dict) -> str:
    """printed -> intended and the evidence (the class reading), or for a formula reading, the reading."""
    cls = r.get("class", r["status"])
    if cls == "misprint-reading" or not r.get("class_reading"):
        return f"{_esc(r['printed'])} -> {_esc(r['reading'])} ({_esc(r['note'])})"
    text = _esc(r["class_reading"])
    return f"**{cls}**: " + (text if len(text) <= _LINE else text[:_LINE - 3] + "...")


def audit_section(rows: list[dict], edits_brief=lambda r: "", tables=()) -> list[str]:
    """The report's audit (module docstring); ``edits_brief(row)`` adds the formula-edit search of a row
    (core.formula_edits) where the kind ran one; ``tables``: :func:`table_of`'s rules."""
    out = ["## Audit of the paper", "",
           "The audit never changes the verdict. Each printed number has two references: its exact value for the "
           "stated parameters (certified) and, where the kind has one, the paper's own chain (the number "
           "recomputed from the paper's printed inputs, each the interval of its rounding, exact constants exact, "
           "upstream misprints corrected: an Arb enclosure). A print that rounds the chain is the paper's "
           "arithmetic (`propagated`, `last-digit`), however far from the exact value; a print that one edit "
           "(sign, decimal point, one or two digits) brings into the chain is a misprint of that class; "
           "`unexplained` is left for prints no chain reproduces. A class is a reading of the print, not a proof "
           "of what the author meant.", ""]
    out.append(f"**{len(rows)} rows:** " + ", ".join(f"{n} {c}" for c, n in _counts(rows)) + ".")
    out.append("")
    mis = [r for r in rows if r.get("class") in MISPRINT_CLASSES
           or (r.get("class") is None and r["status"] == "misprint")]
    if mis:
        out += [f"### Misprints found: {len(mis)} (printed -> intended, the evidence)", ""]
        out += [f"- `{_esc(r['id'])}`: {_one_line(r)}" for r in mis]
        out.append("")
    refuted = [r for r in rows if r.get("class", r["status"]) in ("assertion-refuted", "refuted")]
    if refuted:
        out += [f"### {len(refuted)} assertions of the paper certified false", ""]
        out += [f"- `{_esc(r['id'])}`: {_esc(r['printed'])} ({_esc(r['note'])})" for r in refuted]
        out.append("")
    arith = [r for r in rows if r.get("class") in ARITHMETIC_CLASSES]
    if arith:
        out += [f"### {len(arith)} prints that are the paper's arithmetic, by table", "",
                "Each rounds the paper's own chain (within its `last-digit` slack) but not the exact value: the "
                "paper's inputs, not its typesetting, carry the difference. printed -> exact value (to the printed "
                "digits plus three).", ""]
        groups: dict[str, list[dict]] = {}
        for r in arith:
            groups.setdefault(table_of(r["id"], tables), []).append(r)
        for name, rs in groups.items():
            out += [f"- **{name}** ({len(rs)}): " + "; ".join(
                f"{_esc(r['id'])} {_esc(r['printed'])} -> {_certified_digits(r['lo'], r['hi'], r['printed'])}"
                for r in rs) + "."]
        out.append("")
    unex = [r for r in rows if r.get("class") in ("unexplained", "undecided")]
    if unex:
        out += [f"### {len(unex)} unexplained: no chain from the paper's own inputs reproduces the print", ""]
        out += [f"- `{_esc(r['id'])}` {_esc(r['printed'])} (exact {_certified_digits(r['lo'], r['hi'], r['printed'])}): "
                f"{_esc(r.get('class_reading', ''))}{edits_brief(r)}" for r in unex]
        out.append("")
    other = [r for r in rows if r not in mis and r not in refuted and r not in arith and r not in unex
             and r.get("class", r["status"]) not in _PLAIN]
    if other:
        out += ["### Other rows", "", "; ".join(f"{_esc(r['id'])} ({_esc(r.get('class', r['status']))})" for r in other)
                + ".", ""]
    plain = [r for r in rows if r.get("class", r["status"]) in _PLAIN]
    if plain:
        out += ["### Rows that agree", "",
                "; ".join(f"{_esc(r['id'])} ({_esc(r['printed'])})" for r in plain) + ".", "",
                "Every row, with its certified bounds, its paper-chain reading and notes, is in the JSON certificate "
                "(`paper`).", ""]
    return out
