"""Certificate -> Markdown report, and writing both files into the output folder.

The report is rendered from the certificate's JSON form only, so a report can be re-made from a
stored certificate (``render_markdown(json.load(f))``) and says nothing the certificate does not.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any

from .certificate import Certificate
from .core.errors import SceneError
from .scene import check_name

__all__ = ["render_markdown", "write_outputs", "write_pair", "output_paths"]

_MARK = {"proved": "PROVED", "refuted": "REFUTED", "inconclusive": "INCONCLUSIVE"}


def _esc(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _short(q: dict[str, str], digits: int = 10) -> str:
    """A stored quantity as its midpoint to ``digits`` significant digits and its certified half-width."""
    from decimal import Decimal, InvalidOperation, localcontext
    try:
        mid = Decimal(q["mid"])
    except (InvalidOperation, KeyError, ValueError):
        return f"[{q.get('lo')}, {q.get('hi')}]"
    with localcontext() as c:
        c.prec = digits
        m = +mid
    return f"{m} (+- {q['rad']})"


def _summary(cert: dict[str, Any]) -> list[str]:
    """The answer first: the verdict and its claims in one line each, the numbers an engineer wants
    (the kind's HEADLINE quantities, midpoint and certified half-width), and how to read the rest."""
    from .kinds import kind_module
    claims = cert["claims"]
    by: dict[str, list[str]] = {}
    for c in claims:
        by.setdefault(c["status"], []).append(c["id"])
    out = ["## Summary", "",
           f"**Verdict: {cert['verdict']}** ({len(claims)} claims: "
           + ", ".join(f"{len(by[s])} {s}" for s in ("proved", "refuted", "inconclusive") if s in by) + ")."]
    for c in claims:
        if c["status"] != "proved":
            out.append(f"- `{c['id']}` **{c['status']}**: {_esc(c['reason'])[:300]}"
                       + ("..." if len(c["reason"]) > 300 else ""))
    try:
        headline = getattr(kind_module(cert["scene"]["kind"]), "HEADLINE", {})
    except Exception:
        headline = {}
    q = cert["quantities"]
    rows = [(name, what) for name, what in headline.items() if name in q]
    if any(n.startswith("freq_hz_") for n, _ in rows):         # Hz given: the omegas are in the details
        rows = [(n, w) for n, w in rows if not n.startswith("omega_")]
    if rows:
        out += ["", "| quantity | certified value (midpoint, +- half-width) |", "|---|---|"]
        for name, what in rows:
            out.append(f"| {what} (`{name}`) | {_short(q[name])} |")
    out += ["", "*How to read this report:* the verdict is *proved* only if every claim is; a *refuted* claim "
            "carries a certified counterexample in its reason; an *inconclusive* one says what to try. Every number "
            "is a ball that certainly contains the exact value for the exact parameters below (full bounds under "
            "*Certified enclosures*, all data in the JSON certificate); the audit of the paper comes last and never "
            "changes the verdict.", ""]
    return out


def render_markdown(cert: dict[str, Any]) -> str:
    """The Markdown report of a certificate given in its JSON form."""
    scene = cert["scene"]
    out: list[str] = []
    out.append(f"# {scene['name']}: {_MARK[cert['verdict']]}")
    out.append("")
    out.append(f"*Kind* `{scene['kind']}`. *Source*: {_esc(scene.get('source', ''))}")
    out.append("")
    out.append("Every statement below is a theorem about the exact parameters listed (decimal strings "
               "read as exact rationals), decided by Arb ball arithmetic (python-flint "
               f"{cert['software']['python_flint']}, rigor_gyro {cert['software']['rigor_gyro']}). "
               f"Working precision: {cert['precision_bits']} bits (tried {cert.get('precisions_tried', [])}).")
    out.append("")
    out += _summary(cert)
    out.append("## Parameters (exact)")
    out.append("")
    out.append("| name | value |")
    out.append("|---|---|")
    for k, v in scene["parameters"].items():
        out.append(f"| `{_esc(k)}` | `{_esc(v)}` |")
    out.append("")
    if scene.get("options"):
        out.append("Options: " + ", ".join(f"`{_esc(k)} = {_esc(v)}`" for k, v in scene["options"].items()) + ".")
        out.append("")
    if scene.get("claims_only"):
        out.append("Claims asked for: " + ", ".join(f"`{_esc(c)}`" for c in scene["claims_only"]) + " (not all of the kind's).")
        out.append("")
    out.append("## Claims")
    out.append("")
    out.append("| claim | status | statement | reason | bits |")
    out.append("|---|---|---|---|---|")
    for c in cert["claims"]:
        out.append(f"| `{c['id']}` | **{c['status']}** | {_esc(c['statement'])} | {_esc(c['reason'])} | "
                   f"{c['precision_bits']} |")
    out.append("")
    if cert["quantities"]:
        out.append("## Certified enclosures")
        out.append("")
        out.append("Each value certainly lies in [lo, hi] (decimal bounds rounded outward).")
        out.append("")
        out.append("| quantity | lo | hi | radius |")
        out.append("|---|---|---|---|")
        for k, q in cert["quantities"].items():
            out.append(f"| `{k}` | {q['lo']} | {q['hi']} | {q['rad']} |")
        out.append("")
    if cert.get("formulas"):
        out.append("## Formulas: as printed and as read")
        out.append("")
        for f in cert["formulas"]:
            out.append(f"- **{f['id']}**. Printed: `{f['printed']}`")
            if f.get("reading") and f["reading"] != f["printed"]:
                out.append(f"  Read as: `{f['reading']}`")
            if f.get("note"):
                out.append(f"  {f['note']}")
        out.append("")
    if cert.get("paper"):
        out += _audit_section(cert["paper"])
    if cert.get("notes"):
        out.append("## Notes")
        out.append("")
        for n in cert["notes"]:
            out.append(f"- {n}")
        out.append("")
    out.append("## How to read this report")
    out.append("")
    out.append("*proved*: the ball computation decided the claim for the exact parameters. *refuted*: a "
               "certified counterexample exists (given in the reason). *inconclusive*: not decided at "
               "the precisions tried; the reason says what to try. The JSON certificate next to this "
               "file holds the same data (schema `" + cert["schema"] + "`).")
    out.append("")
    return "\n".join(out)


def _certified_digits(lo: str, hi: str, printed: str, extra: int = 3) -> str:
    """The certified value to the printed number's significant digits plus ``extra`` (both ends of the
    ball round alike there; otherwise the ball's [lo, hi])."""
    from decimal import Decimal, InvalidOperation, ROUND_HALF_EVEN, localcontext
    try:
        a, b, p = Decimal(lo), Decimal(hi), Decimal(printed.strip())
    except (InvalidOperation, ValueError):
        return f"[{lo}, {hi}]" if lo else ""
    n = max(len(p.as_tuple().digits), 1) + extra
    with localcontext() as c:
        c.prec = n
        c.rounding = ROUND_HALF_EVEN
        ra, rb = +a, +b
    return str(ra) if ra == rb else f"[{lo}, {hi}]"


#: audit classes that are plain agreement (not listed among the discrepancies)
_PLAIN = ("agrees", "assertion-confirmed")
#: classes that are numerical differences, not misprints: listed compactly
_NUMERICAL = ("propagated", "last-digit", "unexplained")


def _edits_brief(r: dict) -> str:
    """" (single edits of the printed formula: ...)" for a row that has the search (core.formula_edits)."""
    fe = r.get("formula_edits")
    if not fe:
        return ""
    hits = fe["reproducing"]
    if not hits:
        return f" (none of {fe['tried']} single edits of {_esc(fe['formula'])} reproduces it)"
    shown = "; ".join(_esc(h) for h in hits[:3]) + ("; ..." if len(hits) > 3 else "")
    return (f" ({'one' if len(hits) == 1 else len(hits)} of {fe['tried']} single edits of {_esc(fe['formula'])} "
            f"reproduce{'s' if len(hits) == 1 else ''} it: {shown})")


def _audit_section(rows: list[dict]) -> list[str]:
    """The audit: counts by discrepancy class first, the rows that are not plain agreement next (with
    the reading that reproduces each print), the full table last."""
    out = ["## Audit of the paper", "",
           "The audit never changes the verdict. Each printed number is compared with its certified value at "
           "its printed digits (status *agrees*: a correct rounding; *misprint*: a printed formula that the "
           "stated reading reproduces; *confirmed* / *refuted* for verbal assertions), and each row gets the "
           "discrepancy class that explains it (core.misprints: `last-digit`, `sign`, `decimal-shift`, "
           "`digits-transposed`, `digit-dropped`, `digit-doubled`, `digit-substituted`, `propagated`, or "
           "`unexplained`: no single edit of the digits, sign or decimal point gives the print). A class is a reading "
           "of the print, not a proof of what the author meant.", ""]
    counts: dict[str, int] = {}
    for r in rows:
        counts[r.get("class", r["status"])] = counts.get(r.get("class", r["status"]), 0) + 1
    out.append(f"**{len(rows)} rows:** " + ", ".join(f"{n} {c}" for c, n in
                                                     sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))) + ".")
    out.append("")
    odd = [r for r in rows if r.get("class", r["status"]) not in _PLAIN]
    numerical = [r for r in odd if r.get("class") in _NUMERICAL]
    explained = [r for r in odd if r.get("class") not in _NUMERICAL]
    if explained:
        out += ["### Misprints, refuted assertions and corrected formulas", "",
                "| item | printed | reading | certified (3 digits more than printed) | class | why (the reading that "
                "reproduces the print) | note |", "|---|---|---|---|---|---|---|"]
        for r in explained:
            out.append(f"| {_esc(r['id'])} | {_esc(r['printed'])} | {_esc(r['reading'])} | "
                       f"{_certified_digits(r['lo'], r['hi'], r['printed'])} | "
                       f"**{r.get('class', r['status'])}** | {_esc(r.get('class_reading', ''))} | {_esc(r['note'])} |")
        out.append("")
    for cls, text in (("propagated", "the paper's own computation, not a misprint: a correct rounding of the value "
                                     "recomputed from the paper's printed inputs (each within its printed rounding; "
                                     "the inputs each row needs are in the JSON's class_reading); printed -> certified"),
                      ("last-digit", "one unit off in the last printed digit (rounding)"),
                      ("unexplained", "no edit of the digits, sign or decimal point explains the print (the paper's "
                                      "own computation differs; printed -> certified to the printed digits plus three; "
                                      "in parentheses, where searched, the single edits of the printed formula that "
                                      "reproduce the print)")):
        rs = [r for r in numerical if r.get("class") == cls]
        if rs:
            out += [f"### {len(rs)} {cls}: {text}", "",
                    "; ".join(f"{_esc(r['id'])} {_esc(r['printed'])} -> {_certified_digits(r['lo'], r['hi'], r['printed'])}"
                              f"{_edits_brief(r)}" for r in rs) + ".", ""]
    plain = [r for r in rows if r.get("class", r["status"]) in _PLAIN]
    if plain:
        out += ["### Rows that agree", "",
                "; ".join(f"{_esc(r['id'])} ({_esc(r['printed'])})" for r in plain) + ".", "",
                "Every row, with its certified bounds and notes, is in the JSON certificate (`paper`).", ""]
    return out


def _write_temp(folder: Path, final: str, text: str) -> Path:
    """Write ``text`` to a hidden temporary file next to ``final`` (same folder, so a rename is atomic)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{final}.", suffix=".tmp", dir=folder)
    try:
        os.chmod(tmp, 0o666 & ~_umask())        # mkstemp makes 0600; an output file is an ordinary file
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return Path(tmp)


def _timings_path(jpath: Path) -> Path:
    """``<out>/timings/<name>.json``: beside the outputs, never among them (a glob of <out>/*.json
    sees certificates only)."""
    return jpath.parent / "timings" / jpath.name


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def output_paths(name: str, out_dir: str | Path) -> tuple[Path, Path]:
    """``<out>/<name>.json`` and ``<out>/<name>.md``; SceneError if the name would leave the folder."""
    out = Path(out_dir)
    check_name(name)
    jpath, mpath = out / f"{name}.json", out / f"{name}.md"
    if jpath.resolve().parent != out.resolve():
        raise SceneError(f"scene name {name!r} would write outside the output folder {str(out)!r}")
    for path in (jpath, mpath, _timings_path(jpath)):
        if path.exists() and not path.is_file():
            raise SceneError(f"{str(path)!r} exists and is not a file: move it, or choose another --out")
    return jpath, mpath


def write_outputs(cert: Certificate, out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``<name>.json`` and ``<name>.md`` into ``out_dir`` (created if needed), and the run's wall
    times to ``timings/<name>.json`` (git-ignored: the pair itself is byte-identical across runs).

    Guarantee: each file is written whole to a temporary name in the same folder and renamed into
    place; both are complete before either is replaced, and the old report is removed before the new
    certificate appears, so a reader never sees a truncated file nor a certificate beside the report
    of another run (an interruption between the renames leaves the new certificate without a report).
    Fails when: the folder cannot be created or written (OSError), the name is unsafe (SceneError)."""
    data = cert.to_json()
    return write_pair(out_dir, data["scene"]["name"], json.dumps(data, indent=2, ensure_ascii=False) + "\n",
                      render_markdown(data), cert.timings_json())


def write_pair(out_dir: str | Path, name: str, jtext: str, mtext: str, timings: dict | None) -> tuple[Path, Path]:
    """Write ``<name>.json`` (``jtext``) and ``<name>.md`` (``mtext``), and ``timings/<name>.json``, with
    the guarantees of :func:`write_outputs` (which uses it; so do margin reports)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    jpath, mpath = output_paths(name, out)
    temps: list[Path] = []
    try:
        temps.append(_write_temp(out, jpath.name, jtext))
        temps.append(_write_temp(out, mpath.name, mtext))
        mpath.unlink(missing_ok=True)
        os.replace(temps[0], jpath)
        os.replace(temps[1], mpath)
        if timings is not None:
            # run-dependent data (wall time) beside the pair, never inside it: the pair is reproducible
            tpath = _timings_path(jpath)
            tpath.parent.mkdir(exist_ok=True)
            temps.append(_write_temp(tpath.parent, tpath.name, json.dumps(timings, indent=2) + "\n"))
            os.replace(temps[2], tpath)
    finally:
        for tmp in temps:
            tmp.unlink(missing_ok=True)
    return jpath, mpath
