"""The README section "What the papers got wrong", generated from the committed certificates.

    python tools/papers_wrong.py            # print the section
    python tools/papers_wrong.py --write    # replace it in README.md (between the markers)

Per paper (one certificate per source; for Roitenberg the reading B = 2/15 that reproduces the paper's
own cubic), from the audit rows and their discrepancy classes (rigor_gyro.core.misprints): the
counts by class, every refuted assertion and every printed formula that a stated reading corrects,
and every printed number the classifier explains by a single edit. Nothing here is typed by hand:
tests/test_readme.py fails when the section is out of date.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "<!-- papers-wrong:begin -->", "<!-- papers-wrong:end -->"
#: the certificate that audits each paper
PAPERS = {"Rudenko (1976), eigenfrequency brackets": "rudenko1976",
          "Agafonov et al. (2013), attraction estimate": "agafonov2013",
          "Roitenberg (1947), relay self-oscillation (read with B = 2/15)": "roitenberg1947_b2over15"}
EDITS = ("sign", "decimal-shift", "digits-transposed", "digit-dropped", "digit-doubled", "digit-substituted",
         "multi-digit-substituted", "propagated-misprint")


def _cell(text: str, n: int = 160) -> str:
    text = str(text).replace("|", "\\|").replace("\n", " ")
    return text if len(text) <= n else text[:n - 3] + "..."


def _edited(row: dict) -> str:
    """' (with FORMULA edited: EDIT)' for a row an edit of its printed formula reproduces, else ''."""
    hits = (row.get("formula_edits") or {}).get("reproducing") or []
    return f" (with {row['formula_edits']['formula']} edited: {_cell(hits[0], 50)})" if hits else ""


def section(proofs: Path = ROOT / "proofs") -> str:
    out = [BEGIN, "", "## What the papers got wrong", "",
           "Generated from the audit rows of the committed certificates by `python tools/papers_wrong.py --write` "
           "(each row's class comes from `rigor_gyro.core.misprints`; a class is a reading of a print, not a "
           "proof of what the author meant). The full audit, with every row, is in each report.", ""]
    for title, name in PAPERS.items():
        data = json.loads((proofs / f"{name}.json").read_text(encoding="utf-8"))
        rows = data.get("paper", [])
        counts: dict[str, int] = {}
        for r in rows:
            counts[r["class"]] = counts.get(r["class"], 0) + 1
        out += [f"### {title}", "", f"{len(rows)} audited items (`proofs/{name}.md`): " + ", ".join(
            f"{n} {c}" for c, n in sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))) + ".", ""]
        wrong = [r for r in rows if r["class"] == "assertion-refuted"]
        if wrong:
            out += ["Assertions certified false:", ""]
            out += [f"- **{_cell(r['id'], 80)}**: printed \"{_cell(r['printed'], 100)}\"; {_cell(r['note'], 220)}"
                    for r in wrong]
            out.append("")
        garbled = [r for r in rows if r["id"].startswith("transcription: ")]
        if garbled:
            out += ["Symbols the transcription garbled, as read:", ""]
            out += [f"- **{_cell(r['id'][len('transcription: '):], 80)}**: transcribed `{_cell(r['printed'], 40)}`, "
                    f"read as `{_cell(r['reading'], 40)}`" for r in garbled]
            out.append("")
        formulas = [r for r in rows if r["class"] == "misprint-reading" and r not in garbled]
        if formulas:
            out += ["Printed formulas that do not give the paper's own numbers, and the reading that does:", ""]
            out += [f"- **{_cell(r['id'], 80)}**: printed `{_cell(r['printed'], 90)}`, read as `{_cell(r['reading'], 90)}`"
                    for r in formulas]
            out.append("")
        edits = [r for r in rows if r["class"] in EDITS]
        if edits:
            out += ["Printed numbers explained by one edit (misprints found by the classifier):", "",
                    "| item | printed | class | reading |", "|---|---|---|---|"]
            out += [f"| {_cell(r['id'], 50)} | {_cell(r['printed'], 30)} | {r['class']} | {_cell(r['class_reading'])} |"
                    for r in edits]
            out.append("")
        # a print that an edit of its formula reproduces and that rounds that chain is the paper's own
        # computation: listed once, with the propagated rows below (the edit named there)
        fe = [r for r in rows if r.get("formula_edits") and r["class"] not in ("propagated", "last-digit")]
        if fe:
            out += ["Printed numbers that neither the formula nor its reading gives, against the single edits of "
                    "the printed formula (core.formula_edits, each evaluated in balls):", ""]
            for r in fe:
                f = r["formula_edits"]
                hits = f["reproducing"]
                what = (f"none of {f['tried']} reproduces it" if not hits else
                        f"{'one' if len(hits) == 1 else len(hits)} of {f['tried']} reproduce{'s' if len(hits) == 1 else ''} "
                        f"it: " + "; ".join(_cell(h, 70) for h in hits[:4]) + ("; ..." if len(hits) > 4 else ""))
                out.append(f"- **{_cell(r['id'], 50)}** printed `{_cell(r['printed'], 20)}`, {f['formula']}: {what}")
            out.append("")
        prop = [r for r in rows if r["class"] == "propagated"]
        if prop:
            out += [f"{len(prop)} printed numbers are the paper's own computation, not misprints: each is a correct "
                    "rounding of the value recomputed from the paper's inputs (" + "; ".join(
                        f"{_cell(r['id'], 40)} {_cell(r['printed'], 20)}" + _edited(r) for r in prop[:8])
                    + (", ..." if len(prop) > 8 else "") + "); the report gives the inputs each needs.", ""]
        parts = [f"{counts[k]} {what}" for k, what in (("last-digit", "numbers one unit off in the last digit (rounding)"),
                                                       ("unexplained", "numbers that no edit of their digits explains (listed in the report)"))
                 if counts.get(k)]
        if parts:
            out += ["Besides: " + " and ".join(parts) + ".", ""]
    out.append(END)
    return "\n".join(out)


def write(readme: Path = ROOT / "README.md") -> bool:
    """Replace the section in the README; True if the file changed."""
    text = readme.read_text(encoding="utf-8")
    new = section()
    if BEGIN in text and END in text:
        head, rest = text.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        updated = head + new + tail
    else:
        updated = text.rstrip("\n") + "\n\n" + new + "\n"
    if updated != text:
        readme.write_text(updated, encoding="utf-8")
    return updated != text


if __name__ == "__main__":
    if "--write" in sys.argv[1:]:
        print("README.md updated" if write() else "README.md already up to date")
    else:
        print(section())
