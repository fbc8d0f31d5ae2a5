"""The paper's numbers and formulas (Agafonov et al. 2013) against the certified values.

Every row is decided in ball arithmetic: a printed number ``agrees`` when it is a correct rounding of
the certified enclosure at its printed digits; a printed formula is compared with what system (2) and
V (7) actually give (formula (8) against automatic differentiation, term by term); a verbal
statement ("R = R1", the final region) is ``confirmed`` or ``refuted`` by a certified computation
(a refutation carries its witness). Audit rows never change a claim.

Which printed numbers exist is data: the scene's ``[paper]`` table (keys below); rows about the
printed formulas (8) and the definition of m, and section 2's first-approximation statements ((4), (5),
its derivative, and the linear-setting sentence about p and M), are always produced.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.audit import NUMBER, TEXT, audit_printed
from ...core.balls import certainly_gt, certainly_lt, certainly_nonzero, certainly_positive, decimal_bounds
from ...core.formula_edits import search_single_edits
from ...core.outcome import AuditRow, AuditStatus, Status
from ...core.subdivision import enclose_max
from .model import Dual, Gimbal
from .vdot_tests import certify_vdot_nonpositive
from .moments import MOMENTS
from .paper_open import best_formula_mu_row, invariance_row, label_rows, rho1_row

__all__ = ["audit", "formula_table", "PAPER_KEYS", "PAPER_SCHEMA", "vdot_formula_audit"]

#: [paper] key -> (quantity name, what the paper calls it)
PAPER_KEYS = {"A0": ("A0", "A0 = A + A1 + A2"), "B0": ("B0", "B0 = A + B1"), "C0": ("C0", "C0 = A + A1 - C1"),
              "m": ("m", "m (section 3)"), "M": ("M", "M (section 3)"), "p": ("p", "p = max(M, A0 m / cos^2 x2*)"),
              "k_min": ("k_min", "(18): k > p A0 / H"), "mu_min": ("mu_min", "lower end of the mu range"),
              "mu_max": ("mu_max", "upper end of the mu range"), "R1": ("R1", "R1 from (13)"),
              "R2": ("R2", "R2 from (14)")}

#: what a scene's [paper] table may hold (checked at load: core.audit.check_printed)
PAPER_SCHEMA = {**{k: NUMBER for k in PAPER_KEYS}, "limit": TEXT, "R": NUMBER}

MONOMIALS = [("x1^2", 0, 0), ("x1^3", 0, 1), ("x1^2x3", 0, 2), ("x3^2", 1, 0), ("x1x3^2", 1, 1), ("x3^3", 1, 2)]
TERM_NAMES = {("x1^2", 0): "Psi1 constant term (x1^2)", ("x1^3", 0): "Psi1 x1-term", ("x1^2x3", 0): "Psi1 x3-term",
              ("x3^2", 1): "Psi2 constant terms (x3^2)", ("x1x3^2", 1): "Psi2 x1-term", ("x3^3", 1): "Psi2 x3-term"}


def _fmt(x: arb, d: int = 10) -> str:
    lo, hi = decimal_bounds(x, d)
    return lo if lo == hi else f"[{lo}, {hi}]"


#: R1 (13) and R2 (14) as printed (section 2), for the single-edit search when a printed value disagrees
EDIT_FORMULAS = {
    "R1": ("(13)", "sqrt(D1/D2)",
           {"D1": "108*A0*(A0 - C0)*H**4*cos(x)**4*(k/A0 - mu)**2",
            "D2": "16*mu**2*A0*(A0 - C0)*H**2*C0**2 + 27*(mu*k*B0*C0 + (A0 - C0)*H**2)**2"}),
    "R2": ("(14)", "sqrt(E1/E2)",
           {"E1": "4*H**2*(mu*H*cos(x)**2 - m*A0)**2*(A0 - C0*sin(x)**2)**4",
            "E2": "A0**2*(4*mu**2*H**2*(A0 - C0 - C0*cos(x)**2)**2*(A0 - C0*sin(x)**2)**2*sin(x)**2"
                  " + (mu*k*B0*C0 - (A0 - C0)*H**2)**2)"}),
}


def _edit_inputs(g: Gimbal, m: arb) -> dict[str, arb]:
    c = g.c
    return {"A0": c.A0, "B0": c.B0, "C0": c.C0, "H": c.H, "k": c.k, "mu": c.mu, "m": m, "x": c.x2_star}


def vdot_formula_audit(g, xs: arb) -> tuple[list[str], list[str], list[str]]:
    """Compare the coefficients of grad V . f (automatic differentiation, extracted exactly as a cubic
    in x1, x3) with (8) as printed and as derived, at x2 = j x2*/4, j = 1..4 (exact-ish balls).
    Returns (printed terms certified wrong, derived terms certified wrong, notes)."""
    wrong_printed, wrong_derived, notes = set(), set(), []
    zero_terms = ("1", "x1", "x3", "x1x3")
    for j in (1, 2, 3, 4):
        x2 = xs * j / 4
        mono = g.vdot_monomials(x2)
        for key in zero_terms:
            if certainly_nonzero(mono[key]):
                wrong_derived.add(f"{key} (nonzero in grad V . f)")
        derived = g.psi_coefficients(x2)
        printed = g.psi_printed_coefficients(x2)
        for key, i, t in MONOMIALS:
            if certainly_nonzero(mono[key] + printed[i][t]):
                wrong_printed.add(TERM_NAMES[(key, i)])
                if j == 4:
                    notes.append(f"at x2 = x2*: {TERM_NAMES[(key, i)]} printed {_fmt(printed[i][t])}, "
                                 f"grad V . f gives {_fmt(-mono[key])}")
            if certainly_nonzero(mono[key] + derived[i][t]):
                wrong_derived.add(TERM_NAMES[(key, i)])
    return sorted(wrong_printed), sorted(wrong_derived), notes


def formula_table() -> list[dict[str, str]]:
    """Formulas as printed and as read."""
    return [
        {"id": "(8) Psi2 x3-term", "printed": "((A0-C0) H^2 - mu k B0 C0) sin 2x2 / (B0 (A0 - C0 sin^2 x2)^2) x3",
         "reading": "((A0-C0) H^2 - mu k B0 C0) sin x2 cos x2 / (B0 (A0 - C0 sin^2 x2)^2) x3",
         "note": "grad V . f from (7) and (2) (automatic differentiation in balls) has half the printed term; the "
                 "paper's own bound (13) uses the halved coefficient (the 1/2 in front of |x3|)."},
        {"id": "m", "printed": "m = max_{|x2|<=x2*} |cos x2 f'(x2)| / (A0 C0 sin^2 x2)",
         "reading": "m = max_{|x2|<=x2*} |cos x2 f'(x2)| / (A0 - C0 sin^2 x2)",
         "note": "As printed the quotient is unbounded at x2 = 0; the derivation of (13) bounds "
                 "H cos x2 f'/(B0 D) by H m / B0, which needs the reading, and the example's m = a/A0 = 7.874 is it."},
        {"id": "(17)", "printed": "|x2| <= x2*, x1^2 + x3^2 < R", "reading": "|x2| <= x2*, x1^2 + x3^2 < R^2",
         "note": "(17) itself writes R^2 = min(R1^2, R2^2); the example's final statement drops the square."},
        {"id": "M (sine)", "printed": "M = a C0 sin^2 x2* / ((A0 - C0 sin^2 x2*) ln(A0/(A0 - C0 sin^2 x2*)))",
         "reading": "as printed (q is increasing on [0, x2*]: the maximum is at x2*)",
         "note": "Enclosed here by certified branch and bound, not by the monotonicity claim; q -> a at x2 = 0."},
    ]


def _row(id_, printed, reading, value, status, note=""):
    return AuditRow(id_, printed, reading, value, status, note)


def audit(ctx, quantities: dict[str, arb]) -> tuple[list[AuditRow], list[dict[str, str]], list[str]]:
    """All audit rows of the scene; see the module docstring."""
    g, paper = ctx.g, ctx.m.paper
    rows: list[AuditRow] = []
    notes: list[str] = []
    wrong_p, wrong_d, vnotes = vdot_formula_audit(g, ctx.xs)
    if wrong_d:
        notes.append("internal check FAILED: the derived Psi form differs from grad V . f in " + ", ".join(wrong_d))
    if wrong_p:
        rows.append(_row("(8)", "Psi1, Psi2 of (8)", "x3-term of Psi2 with sin x2 cos x2 instead of sin 2x2", None,
                         AuditStatus.MISPRINT if wrong_p == ["Psi2 x3-term"] and not wrong_d else AuditStatus.DISAGREES,
                         "terms that disagree with grad V . f (certified, automatic differentiation of (7) along (2) "
                         "at x2 = x2*/4 .. x2*): " + ", ".join(wrong_p) + "; all other terms agree within the "
                         "enclosures. " + "; ".join(vnotes)))
    else:
        rows.append(_row("(8)", "Psi1, Psi2 of (8)", "as printed", None, AuditStatus.AGREES,
                         "every term agrees with grad V . f within the enclosures at x2 = x2*/4 .. x2*"))
    # the printed definition of m is unbounded at x2 = 0
    c = g.c
    t = arb(fmpq(1, 1000))
    printed_m = abs(t.cos() * g.df(t)) / (c.A0 * c.C0 * t.sin() ** 2)
    if "m" in quantities and certainly_gt(printed_m, quantities["m"] * 1000):
        rows.append(_row("m definition", "|cos x2 f'| / (A0 C0 sin^2 x2)", "|cos x2 f'| / (A0 - C0 sin^2 x2)",
                         quantities["m"], AuditStatus.MISPRINT,
                         f"as printed the quotient is {_fmt(printed_m, 6)} at x2 = 0.001 (unbounded as x2 -> 0); "
                         "the reading gives the value enclosed here"))
    for key, (qname, what) in PAPER_KEYS.items():
        if key in paper and qname in quantities:
            status, note = audit_printed(str(paper[key]), quantities[qname])
            row = _row(key, str(paper[key]), what, quantities[qname], status, note)
            if key in EDIT_FORMULAS and status is not AuditStatus.AGREES and "m" in quantities:
                eq, text, defs = EDIT_FORMULAS[key]
                res = search_single_edits(text, _edit_inputs(g, quantities["m"]), str(paper[key]), defs)
                row.formula_edits = res.to_json(f"{eq} as printed")
                row.note += "; " + res.summary(f"{eq} as printed")
            rows.append(row)
    if "limit" in paper:
        # lim f / sqrt(int_0^x f) = sqrt(2 f'(0)) for an odd law; the paper prints (2a)^(1/2)
        d0 = g.df(arb(0))
        val = (2 * d0).sqrt()
        same = d0.rad().is_zero() and (d0 - c.a).is_zero()
        rows.append(_row("limit", str(paper["limit"]), "lim_{x2->0} f (int_0^x2 f)^(-1/2) = (2 f'(0))^(1/2)", val,
                         AuditStatus.CONFIRMED if same else AuditStatus.REFUTED if certainly_nonzero(d0 - c.a)
                         else AuditStatus.UNDECIDED,
                         f"f'(0) = {_fmt(d0, 8)} for the law {g.law.formula!r}: the limit is (2 f'(0))^(1/2)"))
    if "R" in paper and "R" in quantities:
        R1, R2 = quantities["R1"], quantities["R2"]
        printed = str(paper["R"])
        if certainly_gt(R1, R2):
            rows.append(_row("R = R1", f"R = R1 = {printed}", "R = min(R1, R2) (17)", quantities["R"],
                             AuditStatus.REFUTED, f"R2 = {_fmt(R2, 6)} < R1 = {_fmt(R1, 6)}: R = R2, not R1"))
        else:
            st, note = audit_printed(printed, quantities["R"])
            rows.append(_row("R = R1", f"R = R1 = {printed}", "R = min(R1, R2) (17)", quantities["R"], st, note))
    if "R" in paper:
        Rq = Fraction(str(paper["R"]))
        leaves = invariance_row(g, arb(fmpq(Rq.numerator, Rq.denominator)), ctx.xs, str(paper["R"]))
        rows += _region_rows(ctx, str(paper["R"]), leaves is not None)
        if leaves is not None:
            rows.append(leaves)
    # the paper's own statements (rows only for a scene that transcribes the paper: its [paper] table; a box of
    # a tolerance scene has no single mu to vary)
    if "R1" in paper and "R1" in quantities:
        row = rho1_row(g, ctx.xs, quantities["R1"], str(paper["R1"]), ctx.m.max_pieces)
        if row is not None:
            rows.append(row)
    if "mu_min" in paper and all(k in quantities for k in ("m", "M", "mu_min", "mu_max")):
        try:
            row = best_formula_mu_row(g, quantities["m"], quantities["M"], quantities["mu_min"], quantities["mu_max"])
            if row is not None:
                rows.append(row)
        except NotImplementedError:     # a box's gimbal (a [paper] table on a tolerance scene): no mu to vary
            pass
    if paper:
        rows += label_rows()
    if g.law.name in MOMENTS:
        # section 2's first-approximation statements are about the paper's laws (a sin x2 and its linearisation
        # a x2); a scene's own [moment] law is not the paper's model, and its report does not audit them
        rows += linear_section_rows(g, ctx.xs, ctx.m.max_pieces)
    if "A0" in paper:
        # a silent correction (issue 39): the unit the example prints for A0
        rows.append(_row("unit of A0", f"A0 = {paper['A0']} g cm s", f"A0 = {paper['A0']} g cm s^2", None,
                         AuditStatus.MISPRINT, "A0 = A + A1 + A2 is a sum of moments of inertia, like B0 and C0, which "
                         "the example prints in g cm s^2; its m = a/A0 in s^-2 (a in g cm) needs A0 in g cm s^2"))
    return rows, formula_table(), notes


def linear_section_rows(g: Gimbal, xs: arb, max_pieces: int) -> list[AuditRow]:
    """Section 2's first-approximation statements, each checked at the scene's parameters (f'(0) plays
    the paper's a): the linearised system (4) against the Jacobian of (2) at the origin (automatic
    differentiation); the quadratic form (5) against the second-order part of V (7); the derivative of
    (5) along (4) (the matrix J' Q + Q J, in balls) against the printed Vdot; and the sentence 'in the
    linear setting (18) coincides with (6), since p = M = A0 m = a' against M certified for f = a x2 in
    system (2). A printed entry is wrong only when its ball certainly differs from the certified one;
    "agrees" means within the enclosures at these parameters (the identities themselves are checked
    symbolically in tests/test_lyapunov_identity.py)."""
    c = g.c
    H, A0, B0, k, mu = c.H, c.A0, c.B0, c.k, c.mu
    a = g.df(arb(0))
    rows: list[AuditRow] = []
    # (4): the Jacobian of (2) at the origin, column by column
    zero = arb(0)
    J = [[None] * 3 for _ in range(3)]
    for j in range(3):
        args = [Dual(zero, arb(1) if i == j else arb(0)) for i in range(3)]
        for i, comp in enumerate(g.rhs(*args)):
            J[i][j] = comp.d if isinstance(comp, Dual) else arb(0)
    printed4 = [[-k / A0, -a / A0, -H / A0], [zero, zero, arb(1)], [H / B0, zero, zero]]
    names = [f"d x{i + 1}'/d x{j + 1}" for i in range(3) for j in range(3)]
    wrong = [n for n, x, y in zip(names, (x for r in J for x in r), (y for r in printed4 for y in r))
             if certainly_nonzero(x - y)]
    rows.append(_row("(4) linearised system", "x1' = -H/A0 x3 - k/A0 x1 - a/A0 x2, x2' = x3, x3' = H/B0 x1",
                     "the Jacobian of (2) at 0 (automatic differentiation; a = f'(0))", None,
                     AuditStatus.DISAGREES if wrong else AuditStatus.CONFIRMED,
                     ("entries that certainly differ: " + ", ".join(wrong)) if wrong else
                     "every entry agrees with the Jacobian of (2) at the origin within the enclosures (the identity "
                     "is proved symbolically in tests/test_lyapunov_identity.py)"))
    # (5): the second-order part of V (7) at 0, Q (symmetric, V = x' Q x)
    q22_7 = mu * a * H / (2 * A0 * B0)
    q23_7 = a * H / (A0 * B0)                   # the coefficient of x2 x3 (f3'(0) = H f'(0)/(A0 B0))
    q33 = (H * H / (A0 * B0) + mu * k / A0) / 2
    q13, q11 = mu * H / B0, H * H / (2 * B0 * B0)
    q23_5 = a * H / (2 * A0 * B0)
    if certainly_nonzero(q23_5 - q23_7):
        rows.append(_row("(5) coefficient of x2 x3", "a H / (2 A0 B0)", "a H / (A0 B0)", q23_7, AuditStatus.MISPRINT,
                         f"the x2 x3 term of (7) at second order is x3 f3(x2) ~ (a H/(A0 B0)) x2 x3 = {_fmt(q23_7, 8)}, "
                         f"not {_fmt(q23_5, 8)}; with the printed coefficient the derivative along (4) has a cross "
                         f"term {_fmt(-H * H * a / (2 * A0 * B0 * B0), 6)} x1 x2 and is not the printed Vdot, with "
                         "the reading it is (see the next row)"))

    def vdot_matrix(q23):
        Q = [[q11, zero, q13 / 2], [zero, q22_7, q23 / 2], [q13 / 2, q23 / 2, q33]]
        return [[sum((J[r][i] * Q[r][j] + Q[i][r] * J[r][j] for r in range(3)), arb(0)) for j in range(3)]
                for i in range(3)]
    Mv = vdot_matrix(q23_7)
    v11_printed = -(H * H / A0) * (k - A0 * mu)
    v11_read = -(H * H / (A0 * B0 * B0)) * (k - A0 * mu)
    v33_printed = -(H / (A0 * B0)) * (mu * H - a)
    cross = [n for n, x in (("x1 x2", Mv[0][1]), ("x1 x3", Mv[0][2]), ("x2 x3", Mv[1][2]), ("x2^2", Mv[1][1]))
             if certainly_nonzero(x)]
    x33_ok = not certainly_nonzero(Mv[2][2] - v33_printed)
    x11_printed_wrong = certainly_nonzero(Mv[0][0] - v11_printed)
    x11_read_ok = not certainly_nonzero(Mv[0][0] - v11_read)
    status = (AuditStatus.MISPRINT if x11_printed_wrong and x11_read_ok and x33_ok and not cross else
              AuditStatus.AGREES if not x11_printed_wrong and x33_ok and not cross else AuditStatus.DISAGREES)
    rows.append(_row("Vdot of (5) along (4)", "-(H^2/A0)(k - A0 mu) x1^2 - (H/(A0 B0))(mu H - a) x3^2",
                     "-(H^2/(A0 B0^2))(k - A0 mu) x1^2 - (H/(A0 B0))(mu H - a) x3^2", Mv[0][0], status,
                     f"J' Q + Q J from (4) and (5) (with the x2 x3 coefficient of (7)), in balls: x1^2 coefficient "
                     f"{_fmt(Mv[0][0], 8)} (printed formula {_fmt(v11_printed, 8)}, reading {_fmt(v11_read, 8)}), x3^2 "
                     f"coefficient {_fmt(Mv[2][2], 8)} (printed {_fmt(v33_printed, 8)}); "
                     + ("the other entries vanish within the enclosures" if not cross else
                        "nonzero entries: " + ", ".join(cross))))
    # 'in the linear setting (18) coincides with (6), since p = M = A0 m = a': M for f = a x2 in (2)
    lin = Gimbal(g.A0, g.B0, g.C0, g.H, g.k, g.a, g.mu, g.x2_star, MOMENTS["linear"])
    lin_a = lin.c.a
    # to 2^-40, relative to a where 0 < |a| < 1 (an absolute 2^-40 could not tell M from a = 1e-300 at all)
    tol = arb(2) ** -40
    if certainly_lt(abs(lin_a), 1) and certainly_positive(abs(lin_a)):
        tol = tol * abs(lin_a).lower()
    M_lin = enclose_max(lin.q, 0, xs, abs_tol=tol, max_pieces=max_pieces).ball
    st = (AuditStatus.REFUTED if certainly_gt(M_lin, lin_a) or certainly_gt(lin_a, M_lin) else AuditStatus.UNDECIDED)
    rows.append(_row("linear setting: p = M = A0 m = a", "(18) coincides with (6), since p = M = A0 m = a",
                     "M = max q over |x2| <= x2* for f = a x2 in system (2)", M_lin, st,
                     f"for f = a x2 in (2), M = {_fmt(M_lin, 10)} (certified maximum) against a = {_fmt(lin_a, 10)}: "
                     "q = f^2/(2 D G) is not a when D = A0 - C0 sin^2 x2 and cos x2 are kept, so p > a and (18) is "
                     "stricter than (6); the sentence holds for the linearised system (4) only (D = A0, cos x2 = 1)"
                     if st is AuditStatus.REFUTED else "not decided at this precision"))
    return rows


def _region_rows(ctx, printed_R: str, leaves: bool) -> list[AuditRow]:
    """The final statement 'region |x2| <= x2*, x1^2 + x3^2 < R' with R as printed: as printed (radius
    sqrt(R)) and as read (radius R): does Vdot <= 0 hold there?"""
    rows = []
    Rq = Fraction(printed_R)
    R_read = arb(fmpq(Rq.numerator, Rq.denominator))
    for label, radius, reading in (("region as printed", R_read.sqrt(), f"x1^2 + x3^2 < {printed_R} (radius sqrt(R))"),
                                   ("region read with R^2", R_read, f"x1^2 + x3^2 < {printed_R}^2")):
        verdict = certify_vdot_nonpositive(ctx.g, ctx.xs, radius, "radius", ctx.m.max_pieces)
        status = {Status.PROVED: AuditStatus.CONFIRMED, Status.REFUTED: AuditStatus.REFUTED}.get(
            verdict.status, AuditStatus.UNDECIDED)
        note = ("confirmed only as 'Vdot <= 0 there': Vdot <= 0 on it certified (" + verdict.reason.split(": ", 1)[-1][:160]
                + "); the paper's claim is an attraction region, which needs the region positively invariant as well: "
                + ("the paper does not show it, and it fails: a certified trajectory leaves the region (row '(17) "
                   "positively invariant'; see invariant_estimate for the sets that are)" if leaves else
                   "the paper does not show it (see invariant_estimate for the sets that are)")) \
            if status is AuditStatus.CONFIRMED else verdict.reason
        rows.append(_row(label, f"|x2| <= x2*, x1^2 + x3^2 < R, R = {printed_R}",
                         reading + (": Vdot <= 0 there" if status is AuditStatus.CONFIRMED else ""), radius, status, note))
    return rows
