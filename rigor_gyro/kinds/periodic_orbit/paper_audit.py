"""The audit of Roitenberg (1947)'s Section 3: every printed number against two references, the exact
value for the stated parameters (certified, from the orbit of :mod:`.claims`) and the paper's own chain
(:mod:`.paper_chain`: the number recomputed from the paper's printed inputs), classified by
:func:`rigor_gyro.core.chain_classify.classify_against_chain`; the silent corrections the model makes
when it reads the paper (:mod:`.paper_silent`); the verbal conclusions.

Guarantee: each row's value is a ball containing the exact value; its chain an enclosure of the values
the paper's printed inputs allow; a row's status ``misprint`` is the classifier's decision on those balls
(exact rational comparisons), never a hand list. Failure mode: a stage of the chain that is not
computable leaves its rows with the exact reference only (classified as before).
"""
from __future__ import annotations

from flint import arb, fmpq

from ...core.audit import audit_printed, half_unit
from ...core.balls import ball, certainly_negative, certainly_positive
from ...core.chain_classify import MISPRINT_CLASSES, classify_against_chain
from ...core.outcome import AuditRow, AuditStatus
from ...core.paper_chain import Chain
from .flow import Spectrum, amplitude_similarity, nutation_cubic, orbit_expsums
from .paper_model import alpha_form, determinant_12, fmt_ball, form7, paper_coefficients, paper_tables
from .paper_chain import relay_chains
from .paper_silent import silent_corrections

__all__ = ["audit", "g_from_printed_row"]


def _row(rid: str, printed: str, value: arb | None, reading: str = "certified value") -> AuditRow:
    if value is None:
        return AuditRow(rid, printed, reading, None, AuditStatus.UNDECIDED, "not computable for these parameters")
    st, note = audit_printed(printed, value)
    return AuditRow(rid, printed, reading, value, st, note)


def _printed_inputs_of_12(paper: dict):
    """(coefficients, sigma) of determinant (12) exactly as the paper prints them (its a_ij, mu1, omega, mu2
    and 1/sigma), or None when the scene does not print them all."""
    a = paper.get("a", {})
    need = [(1, 6), (1, 7), (4, 7)] + [(G, j) for G in (2, 3, 4) for j in range(1, 7)]
    if not all(f"a{G}{j}" in a for G, j in need) or not all(k in paper for k in ("mu1", "omega", "mu2", "inv_sigma")):
        return None
    pc = {"a": {(G, j): ball(a[f"a{G}{j}"]) for G, j in need},
          "mu1": ball(paper["mu1"]), "omega": ball(paper["omega"]), "mu2": ball(paper["mu2"])}
    return pc, 1 / ball(paper["inv_sigma"])


def g_from_printed_row(gx, gv, from_printed) -> AuditRow:
    """Does the printed g(x) table come from (12) with the paper's own printed inputs? Where that
    determinant changes sign between two printed x, and the ratios print / recomputed (one scale would
    make them equal)."""
    signs = ["+" if certainly_positive(d) else "-" if certainly_negative(d) else "?" for _, d in from_printed]
    change = next(((from_printed[i][0], from_printed[i + 1][0]) for i in range(len(signs) - 1)
                   if {signs[i], signs[i + 1]} == {"+", "-"}), None)
    # each print read within its rounding: a common scale exists iff the ratio balls share a point
    ratios = [_within_rounding(v) / d for (x, d), v in zip(from_printed, gv) if v.strip() not in ("0", "-0") and
              (certainly_positive(d) or certainly_negative(d))]
    lo = min(float(r.mid()) for r in ratios) if ratios else float("nan")
    hi = max(float(r.mid()) for r in ratios) if ratios else float("nan")
    apart = any(not r.overlaps(q) for r in ratios for q in ratios)
    common = None
    for r in ratios:
        common = r if common is None else (common.intersection(r) if common.overlaps(r) else None)
        if common is None:
            break
    one_scale = bool(ratios) and not apart and common is not None and all(r.overlaps(common) for r in ratios)
    status = AuditStatus.DISAGREES if apart else AuditStatus.AGREES if one_scale else AuditStatus.UNDECIDED
    return AuditRow("g(x) table from (12) with the printed a_ij", " ".join(gv),
                    " ".join(signs), None, status,
                    "determinant (12) evaluated (certified) with the paper's printed a_ij, mu1, omega, mu2, 1/sigma: "
                    + (f"its sign changes between x = {change[0]} and {change[1]}" if change else "no sign change")
                    + f"; the printed values divided by it range over [{lo:.4g}, {hi:.4g}]"
                    + (" (one scale fits every print within its rounding)" if one_scale else
                       ": no common scale (certified, each print within its rounding), so the printed table does not "
                       "come from (12) as written with the printed coefficients" if apart else
                       ": a common scale is not excluded at this precision"))


def _within_rounding(txt: str) -> arb:
    """Every number a printed decimal may stand for: [x - h, x + h], h half a unit in its last place."""
    h = half_unit(txt)
    return ball(txt) + arb(fmpq(-h.numerator, h.denominator)).union(arb(fmpq(h.numerator, h.denominator)))


def audit(model, sp: Spectrum, orbit) -> list[AuditRow]:
    """Every printed number of the example (from the scene's [paper] table) against the certified orbit."""
    paper = model.paper
    rows: list[AuditRow] = []
    P = sp.P
    C = nutation_cubic(P)
    if "cubic" in paper:
        for txt, coef, nm in zip(paper["cubic"], (C[2], C[1], C[0]), ("lambda^2", "lambda", "1")):
            rows.append(_row(f"cubic (4): coefficient of {nm}", txt, arb(coef),
                             "exact: 1/tau, q^2 + n/(tau A), q^2/tau"))
    if "inv_sigma" in paper:
        rows.append(_row("1/sigma", paper["inv_sigma"], 1 / ball(P.sigma)))
    pc = paper_coefficients(sp)
    if pc is None:
        rows.append(AuditRow("form (6)", "one real root and a complex pair", "", None, AuditStatus.REFUTED,
                             "the cubic has three real roots for these parameters"))
        return rows
    for key in ("mu1", "omega", "mu2"):
        if key in paper:
            rows.append(_row(key, paper[key], pc[key]))
    for key, txt in paper.get("a", {}).items():
        G, j = int(key[1]), int(key[2])
        rows.append(_row(f"a{G}{j}", txt, pc["a"][(G, j)], "exact eigenvectors of (4) in the form (7)"))
    if "theta_star" in paper:
        rows.append(_row("theta*", paper["theta_star"], orbit.theta, "certified root of g"))
    # g(x) table: values and sign pattern of the determinant (12)
    gx, gv = paper.get("g_table_x", []), paper.get("g_table_g", [])
    if gx:
        sig = ball(P.sigma)
        signs_p, signs_o = [], []
        printed_pc = _printed_inputs_of_12(paper)
        from_printed = []
        for x, v in zip(gx, gv):
            d = determinant_12(pc, sig, ball(x))
            st, note = audit_printed(v, d)
            so = "+" if certainly_positive(d) else "-" if certainly_negative(d) else "?"
            sp_ = "+" if certainly_positive(ball(v)) else "-" if certainly_negative(ball(v)) else "0"
            signs_p.append(sp_)
            signs_o.append(so)
            row = AuditRow(f"g({x}) of (12)", v, "determinant (12), exact a_ij", d, st,
                           f"{note}; sign: printed {sp_}, certified {so}")
            if printed_pc is not None:
                # the paper's own computation: (12) with its printed a_ij and exponents, each exactly as printed
                d_pr = determinant_12(printed_pc[0], printed_pc[1], ball(x))
                row.propagated = Chain(d_pr, "determinant (12) with the paper's printed a_ij, mu1, omega, mu2 and "
                                       "1/sigma, each exactly as printed; the printed table has another scale: see "
                                       "the row 'g(x) table from (12) with the printed a_ij'", slack=0)
                from_printed.append((x, d_pr))
            rows.append(row)
        if from_printed:
            rows.append(g_from_printed_row(gx, gv, from_printed))
        rows.append(AuditRow("g(x) table: sign pattern", " ".join(signs_p), " ".join(signs_o), None,
                             AuditStatus.DISAGREES if signs_p != signs_o else AuditStatus.AGREES,
                             f"certified root theta* = {fmt_ball(orbit.theta, 12)}: (12) changes sign between the "
                             "printed x values bracketing it; the printed table is monotonically decreasing with its "
                             "zero at 0.13826994, the determinant as written increases through theta* (opposite sign, "
                             "other scale)"))
    comps = orbit_expsums(sp, orbit.x0)
    md = pc["modes"]
    beta7 = form7(comps[0], md)
    D = [beta7[0], beta7[1], beta7[2], beta7[5], form7(comps[4], md)[3]]
    for j, txt in enumerate(paper.get("D", []), start=1):
        rows.append(_row(f"D{j}", txt, D[j - 1], "(9) at theta*"))
    names = {"beta": 0, "beta_dot": 1, "Omega": 2, "i": 3, "I": 4}
    labels = ["sin", "cos", "e^-mu2t", "e^-t/sigma", "t", "const"]
    for comp, vals in paper.get("orbit", {}).items():
        if comp == "alpha":
            cf, _ = alpha_form(comps[2], md, orbit.theta)
        else:
            cf = form7(comps[names[comp]], md)
        for lab, v, txt in zip(labels, cf, vals):
            if txt:
                rows.append(_row(f"{comp} {lab}" if not (comp == "i" and lab == "sin") else "i sin", txt, v,
                                 "closed form (7), certified"))
    # Table 2
    t2 = paper.get("table2", {})
    if t2:
        _, alpha_f = alpha_form(comps[2], md, orbit.theta)
        order = [("alpha", alpha_f), ("beta", comps[0]), ("Omega", comps[2]), ("beta'", comps[1]),
                 ("i", comps[3]), ("I", comps[4])]
        for t, vals in t2.items():
            tt = orbit.theta if t == "theta" else ball(t)
            for (nm, f), txt in zip(order, vals):
                if txt is None or txt == "":
                    continue
                rows.append(_row(f"Table 2 t={t} {nm}", txt, f(tt), "x(t) on the certified orbit"))
    tabs = paper_tables(sp, pc, orbit)
    for key, txt in paper.get("table3", {}).items():
        G, j = key[1:].split("_")
        rows.append(_row(f"b{G},{j}", txt, tabs["b"][(int(G), int(j))], "(16) from the certified x0"))
    t4 = paper.get("table4", {})
    for j, txt in enumerate(t4.get("x_star", []), start=1):
        rows.append(_row(["beta'*", "Omega*", "i*", "I*"][j - 1], txt, orbit.x0[j], "certified x0"))
    for j, txt in enumerate(t4.get("z", []), start=1):
        rows.append(_row(f"z{j} (eps{j})", txt, tabs["eps"][j - 1], "(10) at theta*"))
    for key, txt in t4.get("h", {}).items():
        rows.append(_row(key, txt, tabs["h"][(int(key[1]), int(key[2]))], "Table 1 with certified b, x*"))
    for key, txt in t4.get("c", {}).items():
        rows.append(_row(key, txt, tabs["c"][(int(key[1]), int(key[2]))],
                         "c_rj = d x_r(theta*)/d x_j(0), c_r5 = f_r(theta*-)"))
    for key, txt in t4.get("k", {}).items():
        rows.append(_row(key, txt, tabs["k"][int(key[1]) - 1, int(key[2]) - 1], "k = -Jacobian"))
    cp = tabs["charpoly"]
    for j, txt in enumerate(paper.get("quartic", []), start=1):
        rows.append(_row(f"quartic (25): coefficient of lambda^{4 - j}", txt, cp[4 - j], "det(lambda I + K)"))
    if orbit.multipliers:
        mult = orbit.multipliers
        real = [z for z in mult if z.imag.contains(0)]
        cplx = [z for z in mult if not z.imag.contains(0)]
        real.sort(key=lambda z: -float(abs(z).mid()))
        lam = paper.get("lambda", {})
        if "lambda1" in lam and real:
            rows.append(_row("lambda1", lam["lambda1"], real[0].real, "largest real multiplier"))
        if "lambda3" in lam and len(real) > 1:
            rows.append(_row("lambda3", lam["lambda3"], real[1].real, "smallest real multiplier"))
        if cplx:
            zc = cplx[0]
            if "re_complex" in lam:
                rows.append(_row("Re lambda2,4", lam["re_complex"], zc.real, "complex pair"))
            if "im_complex" in lam:
                rows.append(_row("|Im lambda2,4|", lam["im_complex"], abs(zc.imag), "complex pair"))
            if "modulus" in lam:
                rows.append(_row("|lambda2| = |lambda4|", lam["modulus"], abs(zc), "modulus of the complex pair"))
        if "stable" in paper:
            rows.append(AuditRow("'all roots of (25) have modulus < 1: the motion is stable'", paper["stable"],
                                 "max modulus < 1", orbit.moduli[0],
                                 AuditStatus.CONFIRMED if orbit.stable else
                                 AuditStatus.REFUTED if orbit.stable is False else AuditStatus.UNDECIDED,
                                 f"max modulus {fmt_ball(orbit.moduli[0], 10)}"))
            rows.append(_gains_row(P, orbit.stable))
    _attach_chains(rows, paper, P)
    rows += silent_corrections(paper, P)
    by_id = {r.id: r for r in rows}
    for rid, txt in paper.get("as_transcribed", {}).items():
        used = by_id[rid].printed if rid in by_id else "(no such row)"
        rows.append(AuditRow(f"transcription: {rid}", str(txt), used, None, AuditStatus.MISPRINT,
                             "a symbol garbled by the transcription, read as the digit its neighbours and the certified "
                             f"value imply (a reading of the print, not a result); the row {rid!r} judges the reading"))
    return rows


def _attach_chains(rows: list[AuditRow], paper: dict, P) -> None:
    """Give each printed-number row its paper-chain reference (:mod:`.paper_chain`) and, where the
    two-reference classifier finds a misprint, the status ``misprint`` and the intended number as its
    reading (the program's own reasoning: no hand list). No chain (a stage not computable) leaves the row
    with the exact reference only."""
    try:
        chains, _ = relay_chains(paper, P)
    except (ZeroDivisionError, ValueError, KeyError, IndexError):
        return
    for row in rows:
        ch = chains.get(row.id)
        if ch is None or row.value is None or not row.value.is_finite():
            continue
        row.propagated = ch
        c = classify_against_chain(row.printed, row.value, ch)
        if c.cls in MISPRINT_CLASSES and c.intended is not None:
            row.status = AuditStatus.MISPRINT
            row.reading = f"{c.intended} ({c.cls})"
            row.note = f"{row.note}; reading {c.intended}: {audit_printed(c.intended, row.value)[1]}"


def _gains_row(P, stable: bool | None) -> AuditRow:
    """The paper's conclusion (the stabiliser performs a stable self-oscillation), which it shows for its
    example only, across the gains p and K: certified for every p, K, S > 0 at the scene's other
    parameters (n = K n1 held fixed) when the example's orbit is certified stable and the exact
    similarity of :func:`~.flow.amplitude_similarity` holds."""
    ok = amplitude_similarity(P)
    amp = ball(P.K * P.p * P.S)
    status = (AuditStatus.CONFIRMED if ok and stable is True else
              AuditStatus.REFUTED if ok and stable is False else AuditStatus.UNDECIDED)
    if not ok:
        note = "the exact similarity did not hold: the model is not the paper's system (2)"
    else:
        note = ("the amplifier gain p and the torque constant K enter the orbit only through its amplitude K p S = "
                f"{fmt_ball(amp)} (exact similarity), so theta*, the sign condition and the multipliers are those of "
                "the example for every p, K, S > 0 with A, B, H, tau, sigma and n = K n1 as in the scene; the "
                "example's stability is " + ("certified, so the conclusion holds for every such gain" if stable is True
                                             else "refuted, so it fails for every such gain" if stable is False
                                             else "undecided") +
                " (the paper shows it at p = 40, K = 7.5 only; changing K at a fixed n1 changes n, which does "
                "matter: scans in n in proofs/margins/README.md)")
    return AuditRow("conclusion across the gains p and K (at fixed n = K n1)",
                    "the periodic motion is stable: the stabiliser performs auto-oscillations (shown for the example)",
                    "for every p, K, S > 0: D^-1 M D = M(p = K = 1), D^-1 e = K p e, D = diag(1, 1, 1, 1/K, 1/(p K)) "
                    "(exact rationals), and the example's orbit stable", None, status, note)
