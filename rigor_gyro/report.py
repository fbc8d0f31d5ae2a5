"""Certificate -> Markdown report, and writing both files into the output folder.

The report is rendered from the certificate's JSON form only, so a report can be re-made from a
stored certificate (``render_markdown(json.load(f))``) and says nothing the certificate does not.
"""
from __future__ import annotations

import json
import os
import tempfile
from fractions import Fraction
from pathlib import Path
from typing import Any

from .certificate import Certificate, dumps_indented
from .core.errors import SceneError
from .scene import check_name

__all__ = ["render_markdown", "write_outputs", "write_pair", "output_paths"]

_MARK = {"proved": "PROVED", "refuted": "REFUTED", "inconclusive": "INCONCLUSIVE"}


def _esc(text: Any) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _short(q: dict[str, str], digits: int = 10) -> str:
    """A stored quantity as its midpoint to ``digits`` significant digits and its certified half-width; an
    exact number (a searched decimal, radius 0, lo = hi) as itself, without a half-width."""
    from decimal import Decimal, InvalidOperation, localcontext
    if q.get("rad") == "0" and q.get("lo") is not None and q.get("lo") == q.get("hi"):
        return f"{q['lo']} (exact)"
    try:
        mid = Decimal(q["mid"])
    except (InvalidOperation, KeyError, ValueError):
        return f"[{q.get('lo')}, {q.get('hi')}]"
    with localcontext() as c:
        c.prec = digits
        m = +mid
    return f"{m} (+- {q['rad']})"


def _summary(cert: dict[str, Any]) -> list[str]:
    """The answer first: the verdict, the kind's headline in a line or two (the relay's period and
    frequency, the estimate's extents and radii beside the paper's R, the audit's counts and refuted
    assertions), the claims not proved in one line each, the kind's HEADLINE quantities (midpoint and
    certified half-width), and how to read the rest. Everything from the certificate's stored bounds."""
    from .kinds import kind_module
    claims = cert["claims"]
    by: dict[str, list[str]] = {}
    for c in claims:
        by.setdefault(c["status"], []).append(c["id"])
    out = ["## Summary", "",
           f"**Verdict: {cert['verdict']}** ({len(claims)} claims: "
           + ", ".join(f"{len(by[s])} {s}" for s in ("proved", "refuted", "inconclusive") if s in by) + ")."]
    heads = _HEADLINES.get(cert["scene"]["kind"], lambda _: [])(cert) + audit_headlines(cert)
    if heads:
        out += [""] + heads
    bad = [c for c in claims if c["status"] != "proved"]
    if bad:
        out.append("")
    for c in bad:
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


#: the audit's table names by row id (the relay paper's tables; other papers' rows fall to "other rows")
AUDIT_TABLES = ((r"^b\d,\d+$", "Table 3 (b of (16))"),
                (r"^(h\d\d|c\d\d|k\d\d|z\d \(eps\d\)|beta'\*|Omega\*|i\*|I\*)$", "Table 4 (x*, z, h, c, k)"),
                (r"^(quartic|lambda|Re lambda|\|Im lambda|\|lambda)", "the quartic (25) and its roots"),
                (r"^(D\d|beta |beta_dot |Omega |i |I |alpha )", "D and the closed form (7)"),
                (r"^(a\d\d|mu\d|omega|1/sigma|theta\*|cubic)", "the exponents, a_ij and theta*"),
                (r"^g\(", "the g(x) table"))


def _audit_section(rows: list[dict]) -> list[str]:
    """The audit (:func:`rigor_gyro.core.audit_report.audit_section`: counts by class, the misprints
    found, the paper's arithmetic by table, the unexplained with their nearest chain value)."""
    from .core.audit_report import audit_section
    return audit_section(rows, _edits_brief, AUDIT_TABLES)


# ---------------------------------------------------------------- the summary's headline lines
# (issue 35: an engineer reads the answer in a minute). Every number from the certificate's stored
# decimal bounds, as exact rationals, rounded outward; nothing is recomputed in floats.

def _outward(q: Fraction, digits: int, up: bool) -> str:
    """The rational ``q`` rounded to ``digits`` significant digits, up (toward +oo) or down: exact
    decimal arithmetic (Decimal division of two exact integers is correctly rounded), no float."""
    from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal, localcontext
    with localcontext() as c:
        c.prec = digits
        c.rounding = ROUND_CEILING if up else ROUND_FLOOR
        d = Decimal(q.numerator) / Decimal(q.denominator)
    text = format(d, "f") if -7 < d.adjusted() < 21 else str(d)
    return "0" if d == 0 else text


def _bounds_text(lo: Fraction, hi: Fraction, digits: int = 10) -> str:
    """[lo, hi] rounded outward to ``digits`` significant digits (one number when both ends round alike,
    as for an exact value)."""
    a, b = _outward(lo, digits, up=False), _outward(hi, digits, up=True)
    return a if a == b else f"[{a}, {b}]"


def _fractions(q: dict[str, str]) -> tuple[Fraction, Fraction] | None:
    """The stored decimal bounds of a quantity as exact rationals (None if an end is not finite)."""
    try:
        return Fraction(q["lo"]), Fraction(q["hi"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return None


def _q_text(q: dict[str, str], digits: int = 10) -> str:
    """A stored quantity as its certified interval, rounded outward to ``digits`` significant digits."""
    f = _fractions(q)
    return _bounds_text(*f, digits) if f else f"[{q.get('lo')}, {q.get('hi')}]"


def _reciprocal(lo: Fraction, hi: Fraction) -> tuple[Fraction, Fraction] | None:
    """[1/hi, 1/lo]: the exact image of [lo, hi] under 1/x when 0 < lo (None otherwise)."""
    return (1 / hi, 1 / lo) if lo > 0 else None


def orbit_headlines(cert: dict[str, Any]) -> list[str]:
    """Kind periodic_orbit: each genuine orbit's period 2 theta* and frequency 1/period (in Hz: the
    scenes' time unit is the second), from the root's stored enclosure of theta* (exact rationals,
    rounded outward); the stable ones first."""
    roots = (cert.get("extra") or {}).get("roots") or []
    genuine = [r for r in roots if r.get("kind") == "genuine"]
    out = []
    for stable in (True, False, None):
        for r in (r for r in genuine if r.get("stable") is stable):
            try:
                lo, hi = (Fraction(x) for x in r["theta"])
            except (KeyError, TypeError, ValueError, ZeroDivisionError):
                continue
            what = {True: "stable", False: "unstable", None: "stability undecided"}[stable]
            freq = _reciprocal(2 * lo, 2 * hi)
            label = "Self-oscillation" + (f" {len(out) + 1} of {len(genuine)}" if len(genuine) > 1 else "")
            out.append(f"- **{label}** (genuine, {what}): period 2 theta* = {_bounds_text(2 * lo, 2 * hi)} s, "
                       "frequency 1/period = " + (f"{_bounds_text(*freq)} Hz" if freq else
                                                  "not enclosed (theta* not certainly > 0)") + ".")
    if not out and roots:
        out.append(f"- **No genuine orbit certified** among the {len(roots)} root{'s' if len(roots) > 1 else ''} of the "
                   "half-period equation.")
    return out


def eigenfrequency_headlines(cert: dict[str, Any]) -> list[str]:
    """Kind eigenfrequencies: the four eigenfrequencies in Hz (given hz_scale), else the omegas."""
    q = cert["quantities"]
    for key, unit in (("freq_hz", " (Hz)"), ("omega", " (omega_j)")):
        got = [q[f"{key}_{j}"] for j in range(1, 5) if f"{key}_{j}" in q]
        if got:
            return [f"- **Eigenfrequencies**{unit}: " + ", ".join(_q_text(v, 8) for v in got) + "."]
    return []


#: kind lyapunov: the certified radii beside the paper's R, in this order (quantity, what)
_RADII = (("R", "R = min(R1, R2)"), ("R_used", "R used"), ("R_direct", "R_direct (direct test, scene's mu)"),
          ("R_max", "R_max (Psi test, mu_best)"), ("R_direct_max", "R_direct_max (direct test, mu_direct)"))


def lyapunov_headlines(cert: dict[str, Any]) -> list[str]:
    """Kind lyapunov: the extents of the invariant estimate, and the paper's printed R (its audit rows)
    beside the certified radii."""
    q = cert["quantities"]
    out = []
    ext = [(a, q[f"extent_{a}"]) for a in ("x1", "x2", "x3") if f"extent_{a}" in q]
    if ext:
        level = f" with c* = {_q_text(q['c_star'], 10)}" if "c_star" in q else ""
        out.append(f"- **Estimate of the domain of attraction** {{V < c*}} in region (17){level}: extents "
                   + ", ".join(f"max |{a}| = {_q_text(v, 6)}" for a, v in ext) + ".")
    rows = {r["id"]: r for r in cert.get("paper") or []}
    printed = [f"{k} = {rows[k]['printed']}" for k in ("R1", "R2") if k in rows]
    said = next((rows[k] for k in ("R = R1", "R") if k in rows), None)
    if said is not None:
        printed.append(f"\"{said['printed'] if '=' in said['printed'] else 'R = ' + said['printed']}\""
                       + (f" ({said['status']}: {said['note']})" if said.get("status") in ("refuted", "confirmed")
                          and said.get("note") else ""))
    certified = [f"{what} = {_q_text(q[k], 10)}" for k, what in _RADII
                 if k in q and not (k == "R_used" and "R" in q and q["R"] == q["R_used"])]
    if printed or certified:
        out.append("- **Radius R of region (17)** (x1^2 + x3^2 <= R^2): "
                   + (f"the paper prints {', '.join(printed)}" if printed else "")
                   + ("; " if printed and certified else "") + (f"certified: {'; '.join(certified)}" if certified else "")
                   + ".")
    return out


_HEADLINES = {"periodic_orbit": orbit_headlines, "lyapunov": lyapunov_headlines,
              "eigenfrequencies": eigenfrequency_headlines}


def _class_counts(rows: list[dict]) -> list[tuple[str, int]]:
    """Audit rows per discrepancy class, the most frequent first."""
    counts: dict[str, int] = {}
    for r in rows:
        counts[r.get("class", r["status"])] = counts.get(r.get("class", r["status"]), 0) + 1
    return sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))


def _percent_rows(rows: list[dict]) -> list[str]:
    """Kind eigenfrequencies: the paper's "error does not exceed 5 %" (audit rows ``error <= x for root
    j``) in one line: where it is refuted, with the certified errors that exceed it."""
    import re
    found = [(m, r) for r in rows for m in [re.match(r"error <= (\S+) for root (\d+)", r["id"])] if m]
    if not found:
        return []
    claim = re.sub(r"\s*\(root \d+\)\s*$", "", found[0][1]["printed"])
    bad = [(m.group(2), r) for m, r in found if r["status"] == "refuted"]
    good = [m.group(2) for m, r in found if r["status"] == "confirmed"]
    rest = [m.group(2) for m, r in found if r["status"] not in ("refuted", "confirmed")]

    def roots(js: list[str]) -> str:
        return ("root " if len(js) == 1 else "roots ") + (", ".join(js[:-1]) + " and " + js[-1] if len(js) > 1 else js[0])

    if not bad:
        line = f"- **Confirmed: \"{claim}\"** for {roots(good)}" if good else f"- \"{claim}\": not decided"
    else:
        parts = []
        for j, r in bad:
            note = r.get("note", "")
            shown = note.split(";", 1)[0].removeprefix("exceeds: ") if note.startswith("exceeds: ") else note
            parts.append(f"root {j}: {shown}")
        line = (f"- **Refuted: \"{claim}\"** (relative errors in Hz of the brackets and approximations, "
                f"certified): exceeded for {roots([j for j, _ in bad])} ({'; '.join(parts)})")
        if good:
            line += f"; holds for {roots(good)}"
    if rest and (bad or good):
        line += f"; undecided for {roots(rest)}"
    return [line + "."]


def audit_headlines(cert: dict[str, Any]) -> list[str]:
    """The audit in two or three lines: rows by class, the "error < 5 %" claim (Rudenko), the other
    assertions of the paper certified false."""
    rows = cert.get("paper") or []
    if not rows:
        return []
    out = [f"- **Audit of the paper** (never changes the verdict): {len(rows)} rows: "
           + ", ".join(f"{n} {c}" for c, n in _class_counts(rows)) + "."]
    pct = _percent_rows(rows)
    out += pct
    refuted = [r["id"] for r in rows if r.get("class", r["status"]) == "assertion-refuted"
               and not (pct and r["id"].startswith("error <= "))]
    if refuted:
        out.append(f"- **{'Other assertions' if pct else 'Assertions'} of the paper certified false**: "
                   + "; ".join(f"`{i}`" for i in refuted) + " (each with its counterexample under *Audit*).")
    return out


#: the environment variable that asks for durable outputs (see :func:`write_outputs`)
DURABLE_ENV = "RIGOR_GYRO_DURABLE"


def _durable() -> bool:
    return os.environ.get(DURABLE_ENV, "") not in ("", "0")


def _write_temp(folder: Path, final: str, text: str, sync: bool = False) -> Path:
    """Write ``text`` to a hidden temporary file next to ``final`` (same folder, so a rename is atomic);
    flushed to the disk before returning when ``sync``."""
    fd, tmp = tempfile.mkstemp(prefix=f".{final}.", suffix=".tmp", dir=folder)
    try:
        os.chmod(tmp, 0o666 & ~_umask())        # mkstemp makes 0600; an output file is an ordinary file
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
            if sync:
                f.flush()
                os.fsync(f.fileno())
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return Path(tmp)


def _sync_folder(folder: Path) -> None:
    """Flush a folder's entries (the renames) to the disk, where the platform allows it."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


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
    Durability: by default nothing is forced to the disk (an fsync per file cost 65-80 ms of wall time per
    run of the three papers): a crash of the process never leaves a partial file, but after a power loss
    or an OS crash a file may be old or empty. ``rigor-gyro check`` rejects such a file (digest, schema),
    and a proof is re-run in seconds. With the environment variable ``RIGOR_GYRO_DURABLE=1`` the
    certificate and the report are flushed to the disk before they are renamed, and the folder after (the
    timings file never is: it is run-dependent and git-ignored).
    Fails when: the folder cannot be created or written (OSError), the name is unsafe (SceneError)."""
    data = cert.to_json()
    return write_pair(out_dir, data["scene"]["name"], dumps_indented(data) + "\n",
                      render_markdown(data), cert.timings_json())


def write_pair(out_dir: str | Path, name: str, jtext: str, mtext: str, timings: dict | None) -> tuple[Path, Path]:
    """Write ``<name>.json`` (``jtext``) and ``<name>.md`` (``mtext``), and ``timings/<name>.json``, with
    the guarantees of :func:`write_outputs` (which uses it; so do margin reports)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    jpath, mpath = output_paths(name, out)
    temps: list[Path] = []
    try:
        sync = _durable()
        temps.append(_write_temp(out, jpath.name, jtext, sync))
        temps.append(_write_temp(out, mpath.name, mtext, sync))
        mpath.unlink(missing_ok=True)
        os.replace(temps[0], jpath)
        os.replace(temps[1], mpath)
        if sync:
            _sync_folder(out)
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
