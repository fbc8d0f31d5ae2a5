"""Rudenko (1976) as printed: the formula table (printed OCR text against the reading used), formula
(14) in dimensional form, and the audit of every number the example prints.

The formulas themselves, in both readings, are in :mod:`.model` (the claims use them too).

Guarantee: every audit row is decided in ball arithmetic or exact rational arithmetic; a printed
decimal is compared with :func:`rigor_gyro.core.audit.audit_printed` (correct rounding at the printed
digits). Audit rows never change a claim.
"""
from __future__ import annotations

import functools
from typing import Callable

from flint import arb, fmpq

from ...core.audit import NUMBER, audit_printed, half_unit, numbers
from ...core.chain_classify import classify_against_chain
from ...core.formula_edits import search_single_edits
from ...core.paper_chain import Chain
from ...core.balls import (ball, certainly_gt, certainly_le, certainly_lt, certainly_positive, current_precision,
                           decimal_bounds)
from ...core.outcome import AuditRow, AuditStatus
from ...core.polyroots import isolate_polynomial
from .paper_hz import TRIED, WINDOW_READINGS, READ_FORMULAS, derived_row, exact_chain, hz_chain, input_box, shared_scale_note
from .paper_scale import consistent_eps, consistent_eps_row
from .paper_text import text_rows
from .paper_steps import step_rows
from .model import (APPROX_TEXT, BRACKETS, EDIT_FORMULAS, NotReal, Params, approximation, bracket,
                    characteristic_quartic)

__all__ = ["PAPER_SCHEMA", "formula_table", "audit", "dimensional_14"]

#: what a scene's [paper] table may hold (checked at load: core.audit.check_printed)
PAPER_SCHEMA = {"hz_lower": numbers(4), "hz_approx": numbers(4), "hz_upper": numbers(4), "hz_exact": numbers(4),
                "error_bound": NUMBER}


def dimensional_14(j: int, A1: fmpq, A2: fmpq, A3: fmpq, K2: fmpq, K3: fmpq, H2: fmpq,
                   corrected: bool) -> tuple[fmpq, fmpq, fmpq]:
    """Formula (14) for (lambda_j^0)^2 as exact rationals (q0, q1, q2) with value q0 + s*sqrt(q2)
    ... returned as (rational part, sign, radicand): (lambda^0)^2 = q0 + sign*sqrt(q2) (q2 = 0 for j = 1, 2).

    ``corrected`` uses A2 H^2/A3^3 in R4 where the paper prints A2 H^2/A3 (dimensionally wrong)."""
    if j == 1:
        return H2 / (A1 * H2 / K2 + (A1 + A2 + A3) * (A2 + A3)), fmpq(0), fmpq(0)
    if j == 2:
        return (K2 * A2 * (A1 + A2 + A3) + H2 * A1) / (A1 * A2 * (A2 + A3 + H2 / K3)), fmpq(0), fmpq(0)
    r4 = A3 / (2 * (A2 + A3)) * (K2 / A2 + A2 * H2 / (A3 ** 3 if corrected else A3))
    rad = r4 * r4 + A2 * H2 / ((A2 + A3) * A3 * A3) * (K3 / A3 - K2 / (A2 + A3))
    return K3 * (A2 + A3) / (A2 * A3) + r4, fmpq(-1 if j == 3 else 1), rad


# ----------------------------------------------------------------------------- formulas for the report

def formula_table() -> list[dict[str, str]]:
    """Every formula of the scene: as printed and as read, with the evidence for the reading."""
    rows = [
        {"id": "(1)", "printed": "lambda^2 [l(b-1)+b][l^2(a-b)(b-1) + l(eps(a-1)+b(a-b)) + eps a] + "
                                 "lambda^2 [l(b-1)+1][l^2(a-b)(b-1) + l(eps(a-1)+a-b) + eps] = 0",
         "reading": "lambda^2 P1(lambda^2) + Omega^2 P2(lambda^2) = 0",
         "note": "The factor of the second product was lost in transcription. Omega^2 reproduces (2) "
                 "coefficient by coefficient and the ratios of the paper's 'exact' frequencies; the printed "
                 "lambda^2 makes Omega^2 drop out (see the audit)."},
        {"id": "(2)", "printed": "Omega^2 = omega (omega-nu2)(omega-nu5)(omega-nu6) / ((omega-nu1)(omega-nu3)(omega-nu4))",
         "reading": "as printed", "note": "lambda = i sqrt(omega); nu3 = 1/(b-1), nu5 = b/(b-1)."},
        {"id": "branches", "printed": "branch 3: poles nu5, nu6 and zeros nu5, nu6",
         "reading": "branch 1 (0, nu1); branch 2 (nu2, nu3); branch 3 (nu4, nu5); branch 4 (nu6, oo)",
         "note": "Branch 3 is garbled in the text; F > 0 exactly on these four intervals when the nus are ordered."},
        {"id": "(4)", "printed": "v2^- v1^- = [...] + ... = 0 (garbled)",
         "reading": "(a-b)(b-1) w^2 - (eps(a-1) + a-b) w + eps = 0 -> nu1 < nu4; "
                    "(a-b)(b-1) w^2 - (eps(a-1) + b(a-b)) w + eps a = 0 -> nu2 < nu6",
         "note": "Read off the two quartic factors of (1)."},
        {"id": "(5)", "printed": "nu1^- = eps/(a-b+eps(a-1)), nu1^+ = eps/(a-b), nu2^- = eps a/(b(a-b)+eps(a-1)), "
                                 "nu2^+ = eps a/(b(a-b)), nu4^- = (1+eps)/(b-1), nu4^+ = nu4^- + eps^2(a-1)/((a-b)(a-b+eps(a-1))), "
                                 "nu6^- = (b^2+eps)/(b(b-1)), nu6^+ = nu6^- + eps^2 a(a-1)/(b(a-b)((a-b)b+eps(a-1)))",
         "reading": "as printed", "note": ""},
        {"id": "(6)", "printed": "... >= F >= omega(omega-nu2^-)/(omega-nu1^+) [1 + eps/(b(b-1))]",
         "reading": "factor Lambda b^2 with Lambda = 1 + eps/(b(b-1))",
         "note": "(7) uses Lambda b^2; with Lambda alone the upper bound of (7) would be far from the printed 43.4 Hz."},
    ]
    for j, br in BRACKETS.items():
        rows.append({"id": f"{br.eq} lower", "printed": br.lo_printed,
                     "reading": br.lo_reading or "as printed", "note": br.reading_note if br.lo_read else ""})
        rows.append({"id": f"{br.eq} upper", "printed": br.hi_printed,
                     "reading": br.hi_reading or "as printed", "note": br.reading_note if br.hi_read else ""})
    for j, text in APPROX_TEXT.items():
        rows.append({"id": f"approx omega_{j}", "printed": text, "reading": "as printed", "note": ""})
    rows.append({"id": "(14) R4", "printed": "R4 = A3/(2(A2+A3)) (K2/A2 + A2 H^2/A3)",
                 "reading": "R4 = A3/(2(A2+A3)) (K2/A2 + A2 H^2/A3^3)",
                 "note": "The printed term is not a squared frequency (dimension check); the reading makes (14) "
                         "equal (13) for every A3, K3 (checked exactly in the audit)."})
    return rows


# ----------------------------------------------------------------------------- the audit

def _fmt(x: arb) -> str:
    lo, hi = decimal_bounds(x, 8)
    return f"[{lo}, {hi}]"


def _q(x) -> arb:
    return ball(x)


def _hz(s: arb, w: arb | None) -> arb | None:
    return s * w.sqrt() if w is not None and certainly_positive(w) else None


def _value(f: Callable[[Params], arb] | None, p: Params) -> arb | None:
    """The formula's ball, or None when it has no real value (NotReal)."""
    if f is None:
        return None
    try:
        return f(p)
    except NotReal:
        return None


@functools.lru_cache(maxsize=512)
def _print_balls(printed: str, prec: int) -> tuple[arb, arb]:
    """The printed decimal and half a unit in its last place, as balls at ``prec`` bits (the edit search
    asks for the same print's scales hundreds of times; parsing it is most of the cost)."""
    h = half_unit(printed)
    return _q(printed), arb(fmpq(h.numerator, h.denominator))


def _scale_range(printed: str, w: arb) -> arb:
    """The set of scales s for which s*sqrt(w) rounds to ``printed``, as a ball (hull)."""
    x, hq = _print_balls(printed, current_precision())
    return ((x - hq) / w.sqrt()).union((x + hq) / w.sqrt())


def _hull(balls: list) -> arb | None:
    """The union of the balls (None for none)."""
    out = None
    for b in balls:
        out = b if out is None else out.union(b)
    return out


def _meets(x: arb, y: arb) -> bool:
    """Certainly a common point: the exact hulls intersect."""
    return certainly_le(x.lower(), y.upper()) and certainly_le(y.lower(), x.upper())


def _scale_reproduces(printed: str, w: arb, inner: tuple[arb, arb]) -> tuple[arb, arb, arb] | None:
    """An exact scale m certainly inside ``inner`` (exact ends of an interval inside the scales the
    paper's own 'exact' values imply) at which ``printed`` is certainly a correct rounding of
    m * sqrt(w), with the ends (lo, hi) of the scales near it that it was chosen from; None when no
    such scale is certain (undecided: the outer range of ``w`` only proposes m, the two final tests
    decide)."""
    if not certainly_positive(w):
        return None
    own = _scale_range(printed, w)
    lo = own.lower() if certainly_le(inner[0], own.lower()) else inner[0]
    hi = own.upper() if certainly_le(own.upper(), inner[1]) else inner[1]
    if not certainly_lt(lo, hi):
        return None
    m = ((lo + hi) / 2).mid()
    if not (certainly_le(inner[0], m) and certainly_le(m, inner[1])):
        return None
    if audit_printed(printed, m * w.sqrt())[0] is not AuditStatus.AGREES:
        return None
    return m, lo, hi


def _inner_of(ends: list[tuple[arb, arb]]) -> tuple[arb, arb] | None:
    """Exact ends of an interval certainly inside the hull of the scale ranges whose inner ends are
    ``ends`` (None when there are none or the order of the ends is not certain)."""
    if not ends:
        return None
    lo_in = min((lo for lo, _ in ends), key=lambda v: float(v.mid()))   # float picks; exact below
    hi_in = max((hi for _, hi in ends), key=lambda v: float(v.mid()))
    if all(certainly_le(lo_in, lo) for lo, _ in ends) and all(certainly_le(hi, hi_in) for _, hi in ends):
        return lo_in, hi_in
    return None


def _at_paper_scale(row: AuditRow, printed: str, w: arb | None, inner: tuple[arb, arb] | None,
                    hull: arb | None) -> AuditRow:
    """Mark ``row`` ``propagated`` when the print is certainly a correct rounding of hz_scale * sqrt(w)
    at an exact scale certainly inside ``inner``, an interval inside the scales the paper's own 'exact'
    values imply (the paper never prints its scale sqrt(K3/A3)/(2 pi), and its four 'exact' values need
    different ones; ``hull``, that interval's outer ball, is only printed). The value at that scale is
    the row's ``propagated`` ball; the note gives the scale."""
    if inner is None or w is None:
        return row
    found = _scale_reproduces(printed, w, inner)
    if found is None:
        return row
    m, lo, hi = found
    val = m * w.sqrt()
    row.propagated = val
    row.propagated_from = (f"hz_scale = {m.str(7, radius=False)}, inside the interval {_fmt(hull)} of scales the "
                           "paper's own 'exact' values imply")
    row.note += f"; at the paper's scales: a correct rounding for hz_scale in [{lo.str(7, radius=False)}, {hi.str(7, radius=False)}]"
    return row


def _with_edits(row: AuditRow, key: tuple[str, int], eq: str, printed: str, p: Params, s: arb,
                hull: arb | None, inner: tuple[arb, arb] | None) -> AuditRow:
    """For a print that neither the formula as printed, nor its reading, nor the paper's own scales
    explain: which single edits of the printed formula (``EDIT_FORMULAS``) reproduce it, in Hz at a
    scale the paper's 'exact' values allow (at the scene's hz_scale when there is no such interval).
    ``hull``: that interval as an outer ball; ``inner``: exact ends of an interval inside it (an edit
    reproduces only at an exact scale certainly inside; where that is not certain it is undecided)."""
    if row.status in (AuditStatus.AGREES, AuditStatus.MISPRINT):
        return row
    if isinstance(row.propagated, Chain):
        if row.value is None or not row.value.is_finite() or \
                classify_against_chain(printed, row.value, row.propagated).cls != "unexplained":
            return row
    elif row.propagated is not None:
        return row
    text, defs = EDIT_FORMULAS[key]
    a, b, e, W = (ball(x) for x in p)

    def reproduces(w: arb) -> bool | None:
        if not certainly_positive(w):
            return False
        if inner is None:
            st = audit_printed(printed, s * w.sqrt())[0]
            return True if st is AuditStatus.AGREES else None if st is AuditStatus.UNDECIDED else False
        if not _meets(_scale_range(printed, w), hull):
            return False                # no scale of the (outer) interval gives the print: certainly not
        return True if _scale_reproduces(printed, w, inner) is not None else None
    env = {"a": a, "b": b, "eps": e, "W": W}
    res = search_single_edits(text, env, printed, defs, reproduces)
    how = ("in Hz at an exact scale inside the interval the paper's own 'exact' values imply" if inner is not None
           else "in Hz at the scene's hz_scale")
    row.formula_edits = res.to_json(f"{eq} as printed", how)
    row.note += "; " + res.summary(f"{eq} as printed", how)
    if not res.reproducing and key in READ_FORMULAS:
        # widened to two edits of the print: one edit of the reading (itself one edit of the print)
        rtext, rdefs = READ_FORMULAS[key]
        res2 = search_single_edits(rtext, env, printed, rdefs, reproduces)
        two = res2.to_json(f"{eq} as read", how)
        fe = row.formula_edits
        fe["formula"] = f"{eq} as printed, then {eq} as read (one edit of the reading: two of the print)"
        fe["tried"] += two["tried"]
        fe["reproducing"] = fe["reproducing"] + [f"of the reading: {h}" for h in two["reproducing"]]
        fe["reproducing_formulas"] = fe["reproducing_formulas"] + two["reproducing_formulas"]
        fe["summary"] += "; " + res2.summary(f"{eq} as read (two edits of the print)", how)
        row.note += "; " + res2.summary(f"{eq} as read (two edits of the print)", how)
    return row


def _scale_inner(printed: str, w: arb) -> tuple[arb, arb]:
    """Exact ends (lo, hi) of an interval of scales s for which s*sqrt(w) certainly rounds to
    ``printed`` for every value in the ball w: inside the true range (the inner ends of its bounds)."""
    h = half_unit(printed)
    x = _q(printed)
    hq = arb(fmpq(h.numerator, h.denominator))
    return ((x - hq) / w.sqrt()).upper(), ((x + hq) / w.sqrt()).lower()


def _number_row(rid: str, printed: str, s: arb, w_printed: arb, w_read: arb | None,
                printed_text: str, read_text: str, hull: arb | None = None,
                inner: tuple[arb, arb] | None = None) -> AuditRow:
    """Audit a printed Hz number against the printed formula and (if different) the reading."""
    hz_p = _hz(s, w_printed)
    st_p, note_p = (audit_printed(printed, hz_p) if hz_p is not None
                    else (AuditStatus.DISAGREES, "formula value not real or not > 0: no frequency"))
    note = f"printed formula: {(_fmt(hz_p) + ' Hz, ' + note_p) if hz_p is not None else note_p}"
    if hz_p is not None:
        note += f"; reproduced for scales in {_fmt(_scale_range(printed, w_printed))}"
    if w_read is None:
        return _at_paper_scale(AuditRow(rid, printed, printed_text, hz_p, st_p, note), printed, w_printed, inner, hull)
    hz_r = _hz(s, w_read)
    st_r, note_r = (audit_printed(printed, hz_r) if hz_r is not None else (AuditStatus.DISAGREES, "<= 0"))
    note += f"; reading: {_fmt(hz_r)} Hz, {note_r}, reproduced for scales in {_fmt(_scale_range(printed, w_read))}" if hz_r is not None else "; reading <= 0"
    if st_p is AuditStatus.AGREES:
        status = AuditStatus.AGREES
    elif st_r is AuditStatus.AGREES:
        status = AuditStatus.MISPRINT
    elif AuditStatus.UNDECIDED in (st_p, st_r):
        status = AuditStatus.UNDECIDED
    else:
        status = AuditStatus.DISAGREES
    row = AuditRow(rid, printed, read_text, hz_r, status, note)
    return _at_paper_scale(row, printed, w_read, inner, hull)


def _attach_chain(row: AuditRow, scale, f, box, what: str, eps_text: str) -> None:
    """Give a Hz row its paper chain (:func:`.paper_hz.hz_chain`) when the paper's scale is known."""
    if scale is None:
        return
    ch = hz_chain(f, box, scale, what, eps_text)
    if ch is not None:
        row.propagated = ch
        row.note += f"; paper chain ({ch.source}): {_fmt(ch.value)} Hz"


def audit(model, p: Params, omegas: list[arb]) -> list[AuditRow]:
    """Audit rows for every number the paper prints in its example (needs ``hz_scale``)."""
    rows: list[AuditRow] = []
    paper = model.paper
    a, b, e, W = (model.q(k) for k in ("a", "b", "eps", "Omega2"))
    # (1): the printed factor lambda^2 against the reading Omega^2
    printed_q = characteristic_quartic(a, b, e, W, factor="lambda2")
    pr = isolate_polynomial(printed_q)
    pos = [x for x in pr.real if certainly_positive(x)] if pr.squarefree else []
    general = _general_claim_row(a, b, e)
    if general is not None:
        rows.append(general)
    rows.append(AuditRow("(1) factor of the second product", "lambda^2", "Omega^2", None, AuditStatus.MISPRINT,
                         f"as printed the equation does not depend on Omega^2 and has {len(pos)} positive root(s) "
                         f"{[_fmt(x) for x in pos]} and {len(pr.nonreal)} non-real: not four frequencies; the reading "
                         "gives (2) and four positive roots"))
    if len(omegas) != 4:
        return rows
    s = ball(model.hz_scale.fmpq()) if model.hz_scale is not None else None
    exact = paper.get("hz_exact")
    if s is None:
        # no Hz row: without hz_scale nothing decides them (an undecided row without a value would make the
        # prover raise the precision to its limit, which cannot help)
        return rows
    hull, inner, scale = None, None, None
    from decimal import Decimal
    eps_text = format(Decimal(int(e.p)) / Decimal(int(e.q)), "f")
    if exact:
        ranges = [_scale_range(x, omegas[j - 1]) for j, x in enumerate(exact, start=1)]
        # the scales the paper's 'exact' values imply: each value's range, kept when it meets the hull of
        # the others' (a misprinted value, say 100 times off, would otherwise stretch the interval for all)
        others = [_hull([r for i, r in enumerate(ranges) if i != j]) for j in range(len(ranges))]
        consistent = [r for r, o in zip(ranges, others) if o is not None and _meets(r, o)]
        hull = _hull(consistent)
        inner_ends = [_scale_inner(x, omegas[j - 1]) for j, x in enumerate(exact, start=1)]
        inner = _inner_of([e for e, r in zip(inner_ends, ranges) if r in consistent])
        lo_max = max(ranges, key=lambda r: float(r.lower().mid()))  # float picks; balls decide below
        hi_min = min(ranges, key=lambda r: float(r.upper().mid()))
        disjoint = certainly_gt(lo_max.lower(), hi_min.upper())
        overlap = certainly_le(lo_max.upper(), hi_min.lower())
        # the paper's Hz scale: the scales its four 'exact' values share at the eps that makes them consistent
        scale = consistent_eps(a, b, W, eps_text, list(exact)) if len(exact) == 4 and (disjoint or overlap) else None
        if scale is not None:
            hull, inner = scale.outer(), (scale.lo.upper(), scale.hi.lower())
        for j, x in enumerate(exact, start=1):
            st, note = audit_printed(x, s * omegas[j - 1].sqrt())
            rng = ranges[j - 1]
            row = AuditRow(f"'exact' lambda_{j} (Hz)", x, f"hz_scale * sqrt(omega_{j})", s * omegas[j - 1].sqrt(), st,
                           f"{note}; correct rounding for scales in {_fmt(rng)}")
            if scale is not None:
                got = exact_chain(j, list(exact), scale)
                if got is not None:
                    row.propagated = got[0]
                    row.note += (f"; at eps = {scale.text} the other three 'exact' values share the scales {got[1]}, "
                                 f"and omega_{j} there times them gives {_fmt(got[0].value)} Hz")
                rows.append(row)
                continue
            # an 'exact' value is judged against the scales the *other* consistent values imply
            own_hull = _hull([r for i, r in enumerate(ranges) if i != j - 1 and r in consistent])
            own_inner = _inner_of([e for i, (e, r) in enumerate(zip(inner_ends, ranges))
                                   if i != j - 1 and r in consistent])
            rows.append(_at_paper_scale(row, x, omegas[j - 1], own_inner, own_hull))
        rows.append(AuditRow("'exact' values share one Hz scale", ", ".join(exact),
                             "intersection of the scale ranges above", None,
                             AuditStatus.REFUTED if disjoint else AuditStatus.CONFIRMED if overlap else AuditStatus.UNDECIDED,
                             f"ranges {[_fmt(r) for r in ranges]}; " + (
                                 "their intersection is certainly empty: no single sqrt(K3/A3)/(2 pi) reproduces all four"
                                 if disjoint else "a common scale exists")))
        if disjoint and scale is not None:
            row = consistent_eps_row(a, b, e, W, eps_text, list(exact), found=scale)
            if row is not None:
                rows.append(row)
    box = input_box(model)
    for key, kind in (("hz_lower", "lower"), ("hz_upper", "upper")):
        for j, x in enumerate(paper.get(key, []), start=1):
            br = BRACKETS[j]
            pf = br.lo if kind == "lower" else br.hi
            rf = br.lo_read if kind == "lower" else br.hi_read
            row = _number_row(f"{br.eq} lambda_{j}{'-' if kind == 'lower' else '+'} (Hz)", x, s,
                              _value(pf, p), _value(rf, p), br.lo_printed if kind == "lower" else br.hi_printed,
                              (br.lo_reading if kind == "lower" else br.hi_reading) or "as printed",
                              *((None, None) if scale is not None else (hull, inner)))
            _attach_chain(row, scale, rf or pf, box, f"{br.eq} {kind} bound{' as read' if rf else ''}", eps_text)
            if (kind, j) in WINDOW_READINGS:      # the edit search first: its edits are the reading's evidence
                row = _with_edits(row, (kind, j), br.eq, x, p, s, hull, inner)
            if scale is not None and row.status is not AuditStatus.AGREES:
                derived_row(row, (kind, j), x, box, scale, eps_text, p, Params(p.a, p.b, arb(scale.eps), p.W))
            rows.append(row if (kind, j) in WINDOW_READINGS else _with_edits(row, (kind, j), br.eq, x, p, s, hull, inner))
    for j, x in enumerate(paper.get("hz_approx", []), start=1):
        eq = "(12)" if j == 1 else "(13)"
        row = _number_row(f"{eq} lambda_{j}~ (Hz)", x, s, _value(lambda q, j=j: approximation(j, q), p), None,
                          APPROX_TEXT[j], "as printed", *((None, None) if scale is not None else (hull, inner)))
        _attach_chain(row, scale, lambda q, j=j: approximation(j, q), box, f"{eq} approximation of omega_{j}", eps_text)
        rows.append(_with_edits(row, ("approx", j), eq, x, p, s, hull, inner))
    if scale is not None:
        _unexplained_notes(rows, p, scale)
    bound = paper.get("error_bound")
    if bound is not None:
        rows.extend(_five_percent_rows(bound, p, omegas, paper))
    rows.append(_label_12_row())
    rows.extend(_fourteen_rows(model))
    rows.extend(text_rows(a, b, e, W, general))
    rows.extend(step_rows(a, b, e, W, omegas))
    return rows


def _unexplained_notes(rows: list[AuditRow], p: Params, scale) -> None:
    """Every Hz row that no chain explains says what was tried (:data:`.paper_hz.TRIED`); where both omega_2
    prints are unexplained, whether one Hz scale reproduces both (:func:`.paper_hz.shared_scale_note`)."""
    def unexplained(r: AuditRow) -> bool:
        return (isinstance(r.propagated, Chain) and r.value is not None and r.value.is_finite()
                and classify_against_chain(r.printed, r.value, r.propagated).cls == "unexplained")
    hz = [r for r in rows if r.id.endswith("(Hz)") and unexplained(r)]
    for r in hz:
        r.note += "; " + TRIED
    by_id = {r.id: r for r in hz}
    pair = [("(8) lambda_2+ (Hz)", _value(BRACKETS[2].hi_read or BRACKETS[2].hi, p)),
            ("(13) lambda_2~ (Hz)", _value(lambda q: approximation(2, q), p))]
    if all(rid in by_id and w is not None for rid, w in pair):
        note = shared_scale_note([(by_id[rid].printed, w) for rid, w in pair], scale)
        if note is not None:
            for rid, _ in pair:
                by_id[rid].note += "; " + note


#: where the audit of the general claim looks for a counterexample: Omega2 = 10^-k with the scene's a, b, eps
GENERAL_CLAIM_OMEGA2 = ("1/10", "1/100", "1/1000", "1/10000", "1/100000", "1/1000000")


def _general_claim_row(a: fmpq, b: fmpq, e: fmpq) -> AuditRow | None:
    """The paper's claim that the brackets (7)-(10) hold without any smallness assumption: refuted by a
    certified counterexample point (the scene's a, b, eps with a small Omega2: exact quartic roots and
    the bracket in balls), or None when none of the points tried is one (a paving over a wide domain,
    ``rigor-gyro prove --group margin``, says more)."""
    claim = "the brackets (7)-(10) hold without any smallness assumption (for all a > b > 1, eps, Omega2 > 0)"
    for text in GENERAL_CLAIM_OMEGA2:
        W = fmpq(*map(int, text.split("/")))
        pr = isolate_polynomial(characteristic_quartic(a, b, e, W))
        if not pr.verified or pr.nonreal or len(pr.real) != 4:
            continue
        p = Params(ball(a), ball(b), ball(e), ball(W))
        for j in range(1, 5):
            try:
                lo, hi = bracket(j, p, reading="intended")
            except NotReal:
                continue
            w = pr.real[j - 1]
            side = "lower" if certainly_gt(lo, w) else "upper" if certainly_gt(w, hi) else None
            if side:
                bound = lo if side == "lower" else hi
                return AuditRow("general claim: no smallness assumption", claim,
                                f"counterexample: Omega2 = {text}, a, b, eps of the scene", w, AuditStatus.REFUTED,
                                f"bracket {BRACKETS[j].eq} (reading used by the claims): omega_{j} = {_fmt(w)} is "
                                f"{'below its lower' if side == 'lower' else 'above its upper'} bound {_fmt(bound)} "
                                "(certified); the brackets need Omega2 not too small")
    return None        # no counterexample among the points tried: no row (an undecided row would only
    #                    make the prover escalate; a search that finds nothing proves nothing)


def _printed_errors(paper: dict, j: int, bound: str) -> str:
    """The paper's own printed numbers against its printed 'exact' value of root j, at face value (exact
    rationals): which of them already break the bound."""
    from fractions import Fraction
    ex = paper.get("hz_exact", [])
    if len(ex) < j:
        return ""
    e, lim = Fraction(ex[j - 1]), Fraction(bound)
    parts, bad = [], []
    for key, name in (("hz_lower", "lower"), ("hz_approx", "approx"), ("hz_upper", "upper")):
        vals = paper.get(key, [])
        if len(vals) >= j:
            r = Fraction(vals[j - 1]) / e - 1
            parts.append(f"{name} {vals[j - 1]}: {float(100 * r):+.2f} %")
            if abs(r) > lim:
                bad.append(name)
    return (f"; the paper's own printed numbers against its 'exact' {ex[j - 1]} Hz (face value): " + ", ".join(parts)
            + (f": {', '.join(bad)} already exceed {float(100 * lim):g} %" if bad else ": all within"))


def _five_percent_rows(bound: str, p: Params, omegas: list[arb], paper: dict | None = None) -> list[AuditRow]:
    """'The error of the estimates and approximate formulas does not exceed 5%' per root, in Hz
    (relative error sqrt(value/omega_j) - 1, independent of the scale), on the readings used; the note
    says which reading each verdict uses and what the paper's own printed numbers give."""
    rows = []
    lim = ball(bound)
    for j in range(1, 5):
        br = BRACKETS[j]
        vals = {"lower": _value(br.lo_read or br.lo, p), "approx": _value(lambda q: approximation(j, q), p),
                "upper": _value(br.hi_read or br.hi, p)}
        errs, fails, und = {}, [], []
        for k, v in vals.items():
            if v is None or not certainly_positive(v):
                fails.append(f"{k} <= 0")
                continue
            err = (v / omegas[j - 1]).sqrt() - 1
            errs[k] = err
            if certainly_gt(abs(err), lim):
                fails.append(f"{k} {_fmt(100 * err)} %")
            elif not certainly_le(abs(err), lim):
                und.append(k)
        status = AuditStatus.REFUTED if fails else AuditStatus.UNDECIDED if und else AuditStatus.CONFIRMED
        note = "; ".join(f"{k}: {_fmt(100 * v)} %" for k, v in errs.items())
        if fails:
            note = "exceeds: " + ", ".join(fails) + "; all: " + note
        used = [f"lower by {br.eq} {'as read (' + br.lo_reading + ')' if br.lo_read else 'as printed'}",
                f"approx by {'(12)' if j == 1 else '(13)'}",
                f"upper by {br.eq} {'as read (' + br.hi_reading + ')' if br.hi_read else 'as printed'}"]
        note += "; verdict on: " + ", ".join(used) + (_printed_errors(paper, j, bound) if paper else "")
        rows.append(AuditRow(f"error <= {bound} for root {j} (Hz)", f"error does not exceed 5% (root {j})",
                             "relative error in Hz of the bracket (as read) and the approximation", None, status, note))
    return rows


def _label_12_row() -> AuditRow:
    return AuditRow("(12) label", "omega_4 ~ eps W [W (a-b) + eps a b]^-1", "omega_1 ~ ...", None,
                    AuditStatus.MISPRINT, "(11)-(12) derive from the branch of omega_1 (its bound (6)); the formula "
                    "approximates omega_1 (see approx_rel_error_1), the text says omega_2, omega_3, omega_4 follow")


def _fourteen_rows(model) -> list[AuditRow]:
    """(14) with A3 = K3 = 1 equals (12)/(13) exactly; with other A3, K3 the printed R4 does not, the
    corrected R4 (A3^3) does. Checked in exact rational arithmetic."""
    a, b, e, W = (model.q(k) for k in ("a", "b", "eps", "Omega2"))
    out = []
    results = {}
    for A3, K3 in ((fmpq(1), fmpq(1)), (fmpq(2), fmpq(3))):
        A1, A2, K2, H2 = (a - b) * A3, (b - 1) * A3, e * K3, W * K3 * A3
        for corrected in (False, True):
            ok = True
            for j in range(1, 5):
                q0, sg, rad = dimensional_14(j, A1, A2, A3, K2, K3, H2, corrected)
                # dimensionless (12)/(13) in exact form: compare rational part and radicand after / (K3/A3)
                t = K3 / A3
                d0, dsg, drad = _approx_exact(j, a, b, e, W)
                ok = ok and (q0 / t == d0) and (sg == dsg) and (rad / (t * t) == drad)
            results[(int(A3.p), corrected)] = ok
    st = AuditStatus.MISPRINT if (results[(1, False)] and not results[(2, False)] and results[(2, True)]) else (
        AuditStatus.AGREES if results[(2, False)] else AuditStatus.DISAGREES)
    out.append(AuditRow("(14) R4 term A2 H^2/A3", "A2 H^2/A3", "A2 H^2/A3^3", None, st,
                        f"exact check: printed (14) = (12)/(13) for A3=K3=1: {results[(1, False)]}; for A3=2, K3=3: "
                        f"{results[(2, False)]}; corrected R4 for A3=2, K3=3: {results[(2, True)]}"))
    return out


def _approx_exact(j: int, a: fmpq, b: fmpq, e: fmpq, W: fmpq) -> tuple[fmpq, fmpq, fmpq]:
    """(12)/(13) as rational part, sign, radicand (exact)."""
    if j == 1:
        return e * W / (W * (a - b) + e * a * b), fmpq(0), fmpq(0)
    if j == 2:
        return (e * (b - 1) * a + W * (a - b)) / ((a - b) * (b - 1) * (b + W)), fmpq(0), fmpq(0)
    r3 = (e / (b * (b - 1)) + (b - 1) * W / b) / 2
    return b / (b - 1) + r3, fmpq(-1 if j == 3 else 1), r3 * r3 + (b - 1) * W * (b - e) / (b * b)
