"""Roitenberg (1947)'s own forms: the a_ij of (7), determinant (12), D1..D5 of (9), the closed-form
orbit, alpha by (14)-(15), Table 2, the b_ij of (16) (Table 3), h, c, k of Table 4, the quartic (25);
and the audit of every number the example prints.

The rigorous orbit is computed in :mod:`rigor_gyro.kinds.periodic_orbit.claims` from the spectral flow; this module
re-expresses it in the paper's variables, so that each printed number can be compared with a ball.

Correspondence with the paper (the report shows it):
* (7): each component of x(t) on 0 < t < theta* is sum_k w_k Re(alpha_k e^{lambda_k t}) + c0 + c1 t
  (:class:`rigor_gyro.kinds.periodic_orbit.flow.ExpSum`); for beta, D1 = -2 Im alpha_pair, D2 = 2 Re alpha_pair,
  D3 = alpha_{-mu2}, a16 D5 = alpha_{-1/sigma}, D4 = c0, a17 S = c1 = -K p S/H.
* (12): g_paper(x) = det of the 6x6 matrix of (9) with S as the sixth unknown. It vanishes exactly
  where beta0(x) does (both say: the symmetric solution of half-period x starts on beta = 0), up to
  a factor that does not vanish near theta*; its printed values have another scale and the opposite
  sign (the audit shows the sign pattern).
* (23)-(25): T x = -K x, so the multipliers are the eigenvalues of -K: the rigorous Jacobian
  :func:`rigor_gyro.kinds.periodic_orbit.flow.half_period_jacobian` is -K with K = k_ij of Table 4.

Guarantee: every value is a ball containing the exact value for the exact parameters and the exact
theta* (its ball). The audit uses :func:`rigor_gyro.core.audit.audit_printed`: ``agrees`` only if every point
of the ball rounds to the printed number; the note always says how many significant digits agree.
"""
from __future__ import annotations

from typing import Any

from flint import acb, arb, arb_mat, fmpq

from ...core.audit import NUMBER, TEXT, agreeing_digits, audit_printed, half_unit, keys, numbers
from ...core.balls import ball, certainly_negative, certainly_positive, decimal_bounds
from ...core.outcome import AuditRow, AuditStatus
from .flow import (ExpSum, amplitude_similarity, Spectrum, half_period_jacobian, nutation_cubic, orbit_expsums, phi_at,
                   vector_field)

__all__ = ["PAPER_SCHEMA", "formula_table", "paper_coefficients", "orbit_quantities", "determinant_12", "audit"]

_A_KEYS = {f"a{G}{j}" for G in (2, 3, 4) for j in range(1, 7)} | {f"a{G}6" for G in (1, 2, 3, 4)} | {"a17", "a47"}
_B_KEYS = {f"b{G}_{j}" for G, n in ((1, 23), (2, 18), (3, 17), (4, 18)) for j in range(1, n + 1)} | {"b5_1", "b5_2"}
_H_KEYS = {f"h{r}{c}" for r in range(1, 5) for c in range(1, 5)} | {"h54"}
_C_KEYS = {f"c{r}{c}" for r in range(1, 6) for c in range(1, 6)}
_K_KEYS = {f"k{r}{c}" for r in range(1, 5) for c in range(1, 5)}
#: what a scene's [paper] table may hold (checked at load: core.audit.check_printed); the coefficient
#: names are those of the paper's forms (7), (16) and Tables 1-4 (tests check them against the code)
PAPER_SCHEMA = {
    "cubic": numbers(3), "inv_sigma": NUMBER, "mu1": NUMBER, "omega": NUMBER, "mu2": NUMBER, "theta_star": NUMBER,
    "g_table_x": numbers(100), "g_table_g": numbers(100), "D": numbers(5), "stable": TEXT, "quartic": numbers(4),
    "a": keys(_A_KEYS, NUMBER),
    "orbit": {c: numbers(6, blank_ok=True) for c in ("beta", "beta_dot", "Omega", "i", "I", "alpha")},
    "table2": keys(r"theta|[0-9]{1,3}(\.[0-9]{1,6})?", numbers(6, blank_ok=True)),
    "table3": keys(_B_KEYS, NUMBER),
    "table4": {"x_star": numbers(4), "z": numbers(4), "h": keys(_H_KEYS, NUMBER), "c": keys(_C_KEYS, NUMBER),
               "k": keys(_K_KEYS, NUMBER)},
    "lambda": {k: NUMBER for k in ("lambda1", "lambda3", "re_complex", "im_complex", "modulus")},
    # where the transcription garbles a symbol, the text as transcribed (the number used above is the reading)
    "as_transcribed": keys(r"[A-Za-z0-9 =.,'*_()-]{1,60}", TEXT),
}


def _fmt(x: arb, d: int = 10) -> str:
    lo, hi = decimal_bounds(x, d)
    return f"[{lo}, {hi}]"


# ----------------------------------------------------------------------------- the paper's variables

def _modes(sp: Spectrum):
    """(pair mode, real cubic mode, sigma mode); needs one complex pair (the paper's case)."""
    pair = [m for m in sp.modes if m.weight == 2]
    real = [m for m in sp.modes if m.weight == 1 and m.label.startswith("real")]
    sig = [m for m in sp.modes if m.label.startswith("-1/sigma")]
    if len(pair) != 1 or len(real) != 1:
        return None
    return pair[0], real[0], sig[0]


def paper_coefficients(sp: Spectrum) -> dict[str, Any] | None:
    """mu1, omega, mu2 and a_ij of (7) (None when the cubic has three real roots: the paper's form
    (6) assumes a complex pair)."""
    md = _modes(sp)
    if md is None:
        return None
    pair, real, sig = md
    P = sp.P
    A, B, H, K, p = (ball(x) for x in (P.A, P.B, P.H, P.K, P.p))

    def comp(lam):
        return [acb(1), lam, -(B / H) * lam ** 2, (-(A * B / H) * lam ** 3 - H * lam) / K]

    c1, c3 = comp(pair.lam), comp(real.lam)
    a: dict[tuple[int, int], arb] = {}
    for g in range(1, 4):
        G = g + 1
        a[(G, 1)] = c1[g].real
        a[(G, 3)] = c1[g].imag
        a[(G, 2)] = -c1[g].imag
        a[(G, 4)] = c1[g].real
        a[(G, 5)] = c3[g].real
    r = [sig.proj[i, 4] for i in range(5)]   # the -1/sigma eigenvector with I-component 1 (proj = r e5^T)
    for g in range(4):
        a[(g + 1, 6)] = r[g].real
    a[(1, 7)] = -ball(P.K * P.p / P.H)
    a[(4, 7)] = p
    return {"mu1": -pair.lam.real, "omega": pair.lam.imag, "mu2": -real.lam.real, "a": a,
            "modes": md}


def _form7(f: ExpSum, md) -> list[arb]:
    """[sin, cos, e^{-mu2 t}, e^{-t/sigma}, t, const] coefficients of an ExpSum in the paper's form."""
    pair, real, sig = md
    out = {"sin": arb(0), "cos": arb(0), "mu2": arb(0), "sig": arb(0)}
    for alpha, lam, w in f.terms:
        if lam is pair.lam:
            out["sin"] = -2 * alpha.imag
            out["cos"] = 2 * alpha.real
        elif lam is real.lam:
            out["mu2"] = alpha.real
        else:
            out["sig"] = alpha.real
    return [out["sin"], out["cos"], out["mu2"], out["sig"], f.c1, f.c0]


def _alpha(f_Omega: ExpSum, md, theta: arb) -> tuple[list[arb], ExpSum]:
    """alpha = int Omega dt + C with alpha(0) = -alpha(theta*) ((14)-(15)); Omega has no t-term."""
    terms = [(a / l, l, w) for a, l, w in f_Omega.terms]
    F = ExpSum(terms, arb(0), f_Omega.c0)
    C = -(F(arb(0)) + F(theta)) / 2
    F = ExpSum(terms, C, f_Omega.c0)
    return _form7(F, md), F


def orbit_quantities(model, sp: Spectrum, orbit) -> tuple[dict[str, arb], list[str]]:
    """D1..D5 and the certified closed form (7) of the scene's orbit (quantities and a note)."""
    md = _modes(sp)
    if md is None:
        return {}, ["the cubic (4) has three real roots: the paper's form (6)-(7) (one complex pair) does not apply"]
    comps = orbit_expsums(sp, orbit.x0)
    beta = _form7(comps[0], md)
    I = _form7(comps[4], md)
    pc = paper_coefficients(sp)
    q = {"D1": beta[0], "D2": beta[1], "D3": beta[2], "D4": beta[5], "D5": I[3]}
    names = ["beta", "beta'", "Omega", "i", "I"]
    lines = []
    for nm, f in zip(names, comps):
        c = _form7(f, md)
        lines.append(f"{nm} = {_fmt(c[0], 9)} e^(-mu1 t) sin(omega t) + {_fmt(c[1], 9)} e^(-mu1 t) cos(omega t) + "
                     f"{_fmt(c[2], 9)} e^(-mu2 t) + {_fmt(c[3], 9)} e^(-t/sigma) + {_fmt(c[4], 9)} t + {_fmt(c[5], 9)}")
    al, _ = _alpha(comps[2], md, orbit.theta)
    lines.append(f"alpha = {_fmt(al[0], 9)} e^(-mu1 t) sin(omega t) + {_fmt(al[1], 9)} e^(-mu1 t) cos(omega t) + "
                 f"{_fmt(al[2], 9)} e^(-mu2 t) + {_fmt(al[3], 9)} e^(-t/sigma) + {_fmt(al[5], 9)}")
    note = (f"Orbit in the paper's closed form (7) on 0 < t < theta* (certified coefficients; mu1 = {_fmt(pc['mu1'], 12)}, "
            f"omega = {_fmt(pc['omega'], 12)}, mu2 = {_fmt(pc['mu2'], 12)}, 1/sigma exact; on the second half-period "
            "multiply by -1 and restart t at 0): " + "; ".join(lines))
    return q, [note]


# ----------------------------------------------------------------------------- determinant (12)

def determinant_12(pc: dict[str, Any], sigma: arb, x: arb) -> arb:
    """The paper's g(x): the 6x6 determinant (12) with the exact a_ij (in balls)."""
    a, mu1, om, mu2 = pc["a"], pc["mu1"], pc["omega"], pc["mu2"]
    e1 = (-mu1 * x).exp() * (om * x).sin()
    e2 = (-mu1 * x).exp() * (om * x).cos()
    e3 = (-mu2 * x).exp()
    e4 = (-x / sigma).exp()

    def r(G):
        return [a[(G, 1)] * e1 + a[(G, 3)] * (e2 + 1), a[(G, 2)] * e1 + a[(G, 4)] * (e2 + 1),
                a[(G, 5)] * (e3 + 1), a[(G, 6)] * (e4 + 1)]

    R2, R3, R4 = r(2), r(3), r(4)
    z = arb(0)
    Mx = arb_mat([[z, 1, 1, 1, a[(1, 6)], z],
                  [e1, e2, e3, 1, a[(1, 6)] * e4, a[(1, 7)] * x],
                  [R2[0], R2[1], R2[2], z, R2[3], 2 * a[(1, 7)]],
                  [R3[0], R3[1], R3[2], z, R3[3], z],
                  [R4[0], R4[1], R4[2], z, R4[3], 2 * a[(4, 7)]],
                  [z, z, z, z, e4 + 1, 2]])
    return Mx.det()


# ----------------------------------------------------------------------------- Tables 3 and 4

def _tables(sp: Spectrum, pc: dict[str, Any], orbit) -> dict[str, Any]:
    """b_ij of (16), h, c, k of Table 4, eps_j (z_j), and the quartic (25), for the orbit."""
    a = pc["a"]
    P = sp.P
    S = ball(P.S)
    z = arb(0)
    N = arb_mat([[z, 1, 1, 1, a[(1, 6)]],
                 [a[(2, 3)], a[(2, 4)], a[(2, 5)], z, a[(2, 6)]],
                 [a[(3, 3)], a[(3, 4)], a[(3, 5)], z, a[(3, 6)]],
                 [a[(4, 3)], a[(4, 4)], a[(4, 5)], z, a[(4, 6)]],
                 [z, z, z, z, 1]])
    Ni = N.inv()
    part0 = [z, a[(1, 7)] * S, z, a[(4, 7)] * S, S]
    cst = [-sum((Ni[r, j] * part0[j] for j in range(5)), arb(0)) for r in range(5)]
    rowsD = [[Ni[r, j] for j in range(1, 5)] + [cst[r]] for r in range(5)]

    def comb(coefs):
        return [sum((cf * rowsD[r][j] for r, cf in coefs), arb(0)) for j in range(5)]

    b: dict[tuple[int, int], arb] = {}

    def put(G, blocks):
        k = 1
        for blk in blocks:
            for v in blk:
                b[(G, k)] = v
                k += 1

    for G in (1, 2, 3, 4):
        sinb = comb([(0, a[(G, 1)] if G > 1 else arb(1)), (1, a[(G, 2)] if G > 1 else arb(0))])
        cosb = comb([(0, a[(G, 3)] if G > 1 else arb(0)), (1, a[(G, 4)] if G > 1 else arb(1))])
        e3b = comb([(2, a[(G, 5)] if G > 1 else arb(1))])
        a6 = a[(G, 6)]
        sgb = [a6, -a6 * S]
        if G == 1:
            d4 = comb([(1, arb(-1)), (2, arb(-1)), (4, -a[(1, 6)])])
            put(1, [sinb, cosb, e3b, sgb, [d4[4], a[(1, 7)] * S], d4[:4]])
        elif G == 2:
            put(2, [sinb, cosb, e3b, sgb, [a[(1, 7)] * S]])
        elif G == 3:
            put(3, [sinb, cosb, e3b, sgb])
        else:
            put(4, [sinb, cosb, e3b, sgb, [a[(4, 7)] * S]])
    b[(5, 1)] = -S
    b[(5, 2)] = S
    xs = orbit.x0[1:]
    h: dict[tuple[int, int], arb] = {}
    for G in (1, 2, 3, 4):
        for m in range(3):
            h[(G, m + 1)] = sum((b[(G, 5 * m + j + 1)] * xs[j] for j in range(4)), arb(0)) + b[(G, 5 * m + 5)]
        h[(G, 4)] = b[(G, 16)] * xs[3] + b[(G, 17)]
    h[(5, 4)] = xs[3] + b[(5, 1)]
    th = orbit.theta
    mu1, om, mu2 = pc["mu1"], pc["omega"], pc["mu2"]
    eps = [(-mu1 * th).exp() * (om * th).sin(), (-mu1 * th).exp() * (om * th).cos(), (-mu2 * th).exp(),
           (-th / ball(P.sigma)).exp()]
    Phi = phi_at(sp, th)
    f = vector_field(sp, [-v for v in orbit.x0])
    c: dict[tuple[int, int], arb] = {}
    for r in range(5):
        for j in range(4):
            c[(r + 1, j + 1)] = Phi[r, j + 1]
        c[(r + 1, 5)] = f[r]
    J = half_period_jacobian(sp, th, orbit.x0)
    k = -J
    cp = J.charpoly()             # det(lambda I - J) = lambda^4 + q1 lambda^3 + ...
    return {"b": b, "h": h, "c": c, "k": k, "eps": eps, "charpoly": cp}


# ----------------------------------------------------------------------------- formulas for the report

def formula_table() -> list[dict[str, str]]:
    return [
        {"id": "(2)", "printed": "A Omega' - H beta' - K i = 0; tau i' + i + n1 Omega - p I = 0; B beta'' + H Omega = 0; "
                                 "sigma I' + I = S sign beta",
         "reading": "x' = M x + e S sign(beta), x = (beta, beta', Omega, i, I), n = K n1",
         "note": "linear between switchings; the flow is exp(M t) = sum_k e^{lambda_k t} P_k (simple eigenvalues, "
                 "checked exactly)"},
        {"id": "(4)", "printed": "[lambda^3 + lambda^2/tau + (q^2 + n/(tau A)) lambda + q^2/tau](lambda + 1/sigma) lambda = 0",
         "reading": "as printed", "note": "the paper's example prints lambda^3 + 100 lambda^2 + 640 lambda + 60000: "
                                          "q^2 = 600, i.e. B = 2/15 (or H = 5 sqrt 399), not the printed B = 0.133 "
                                          "(q^2 = 601.50...); see the audit"},
        {"id": "(8)-(13)", "printed": "periodicity conditions (8) -> linear system (9) in D1..D5, S; g(x) = det (12) = 0",
         "reading": "g(theta) = beta0(theta) = e1^T x0(theta), x0 = -tanh(M theta/2) M^{-1} e S",
         "note": "same roots near theta* (both say the symmetric solution closes on beta = 0); rigor_gyro isolates "
                 "the roots of beta0, and audits the determinant (12) separately"},
        {"id": "(7), (14)-(15)", "printed": "beta = D1 e^{-mu1 t} sin wt + D2 e^{-mu1 t} cos wt + D3 e^{-mu2 t} + D4 + "
                                            "a16 D5 e^{-t/sigma} + a17 S t, ...; alpha = int Omega dt + C, alpha(0) = -alpha(theta*)",
         "reading": "as printed", "note": "certified coefficients in the notes; the printed i-row has the sign of its "
                                          "sin coefficient wrong (audit)"},
        {"id": "(16)", "printed": "... + (b116 I0 + b117) e^{-t/tau} + ...",
         "reading": "(b116 I0 + b117) e^{-t/sigma}", "note": "OCR/print: the I-mode decays with sigma (b116 = a16)"},
        {"id": "(21)-(25)", "printed": "T x_i + sum c_ij x_j + c_i5 x5 = 0; k from (24); det(lambda I + K) = 0",
         "reading": "multipliers = eigenvalues of -K = -[(I - f e1^T/f1) exp(M theta*)]_{1..4,1..4}",
         "note": "f = vector field just before the switching (saltation: first-order correction of the switching "
                 "time); product of the multipliers = -exp(-(1/tau + 1/sigma) theta*) (Liouville), checked"},
        {"id": "(24) indices", "printed": "k_g2 = (c_{g+1,2} c15 - c_{g+1,6} c12)/c15, ... c_{g+1,7}, c_{g+1,8}",
         "reading": "k_gj = (c_{g+1,j} c15 - c_{g+1,5} c1j)/c15", "note": "the printed second index runs on; every k_gj "
                                                                          "uses c_{g+1,5}"},
    ]


# ----------------------------------------------------------------------------- the audit

#: printed numbers that disagree with the certified value but agree with an evident correction
#: (key -> (corrected text, why))
READINGS = {
    "D1": ("0.0417756", "the orbit formula below it prints 0.0417756"),
    "b5,1": ("-0.15", "b51 = -S (I = (I0 - S) e^{-t/sigma} + S)"),
    "h21": ("0.191795", "h21 is the beta' sin coefficient of the orbit, printed there as 0.191795"),
    "i sin": ("-0.202595", "sign: the i-row of the closed form has the opposite sign of h41 = -0.202593"),
    "c15": ("-1.234394", "c15 = f_1(theta*-) = beta'(theta*) = -beta'(0)"),
    "z4 (eps4)": ("0.348720", "z4 = eps4 = exp(-theta*/sigma), printed as c54 = 0.348720"),
    "b1,13": ("0.0000430652", "single-digit misprint (2 for 3)"),
    "b1,18": ("0.0638624", "single-digit misprint (8 for 3)"),
    "b1,23": ("-0.393749", "single-digit misprint (5 for 3)"),
    "b3,3": ("0.000135992", "single-digit misprint (2 for 3)"),
    "b3,7": ("1.003596", "single-digit misprint (5 for 3)"),
    "b3,12": ("-0.00359612", "single-digit misprint (5 for 3)"),
    "b4,4": ("-0.583083", "sign"),
    "b4,7": ("-6.33182", "sign"),
    "c23": ("0.00016867", "decimal point shifted"),
}


def _row(rid: str, printed: str, value: arb | None, reading: str = "certified value") -> AuditRow:
    if value is None:
        return AuditRow(rid, printed, reading, None, AuditStatus.UNDECIDED, "not computable for these parameters")
    st, note = audit_printed(printed, value)
    if st is AuditStatus.DISAGREES and rid in READINGS:
        corr, why = READINGS[rid]
        st2, note2 = audit_printed(corr, value)
        d = agreeing_digits(corr, value)
        if d >= min(3, len(corr.lstrip("-0.").replace(".", ""))):
            return AuditRow(rid, printed, f"{corr} ({why})", value, AuditStatus.MISPRINT,
                            f"printed: {note}; reading {corr}: {note2}")
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


def _g_from_printed_row(gx, gv, from_printed) -> AuditRow:
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


def _printed_form7(paper: dict) -> dict[tuple[str, str], tuple[arb, str]]:
    """(component, basis label) -> (ball, text): the coefficient of form (7) as the paper builds it from its
    own printed a_ij and D1..D5 (D1..D3 as beta's row prints them; each read within its printed rounding): sin = a_G1 D1 + a_G2 D2,
    cos = a_G3 D1 + a_G4 D2, e^-mu2t = a_G5 D3, e^-t/sigma = a_G6 D5 for beta_dot, Omega, i (G = 2, 3, 4),
    and e^-t/sigma = a16 D5 for beta. Empty when the scene does not print them."""
    a, D = paper.get("a", {}), list(paper.get("D", []))
    if len(D) != 5:
        return {}
    # beta's own row prints D1, D2, D3 (its sin, cos, e^-mu2t coefficients) again: where the two prints
    # differ (D1 0.0447756 against 0.0417756 in the 1947 example), the beta row is what the later numbers use
    beta = paper.get("orbit", {}).get("beta", [])
    for k, idx in ((0, 0), (1, 1), (2, 2)):
        if len(beta) > idx and beta[idx]:
            D[k] = beta[idx]
    d = [_within_rounding(x) for x in D]
    out: dict[tuple[str, str], tuple[arb, str]] = {}

    def coef(G: int, j: int) -> arb | None:
        txt = a.get(f"a{G}{j}")
        return _within_rounding(txt) if txt else None
    for comp, G in (("beta_dot", 2), ("Omega", 3), ("i", 4)):
        parts = {"sin": ((1, 0), (2, 1)), "cos": ((3, 0), (4, 1)), "e^-mu2t": ((5, 2),), "e^-t/sigma": ((6, 4),)}
        for lab, terms in parts.items():
            cs = [coef(G, j) for j, _ in terms]
            if all(c is not None for c in cs):
                val = sum((c * d[k] for c, (_, k) in zip(cs, terms)), arb(0))
                text = " + ".join(f"a{G}{j} D{k + 1}" for j, k in terms)
                out[(comp, lab)] = (val, f"the paper's own printed a_ij and D ({text}, each within its printed rounding)")
    if coef(1, 6) is not None:
        out[("beta", "e^-t/sigma")] = (coef(1, 6) * d[4], "the paper's own printed a16 D5 (each within its printed rounding)")
    return out


def _printed_closed_form(paper: dict):
    """(component, t) -> the paper's closed form (7) evaluated from its own printed numbers (coefficients
    of [e^-mu1t sin wt, e^-mu1t cos wt, e^-mu2t, e^-t/sigma, t, const], each read as every number it may
    round from, and mu1, omega, mu2, 1/sigma as printed): a ball holding the values the paper's Table 2
    could show if its arithmetic were exact (each coefficient enters once, so the ball is that set, up to
    the basis values' rounding). None when the scene does not print them all. Table 2's beta'
    is the printed beta_dot."""
    orbit = paper.get("orbit", {})
    if not orbit or not all(k in paper for k in ("mu1", "omega", "mu2", "inv_sigma")):
        return None
    # the exponents as printed (each appears in several terms: read within its rounding, a ball would
    # overestimate the set of values the inputs allow); the coefficients, each in one term, within theirs
    mu1, w, mu2, isg = (ball(paper[k]) for k in ("mu1", "omega", "mu2", "inv_sigma"))

    def at(comp: str, t: arb) -> arb | None:
        cf = orbit.get("beta_dot" if comp == "beta'" else comp)
        if cf is None:
            return None
        basis = [(-mu1 * t).exp() * (w * t).sin(), (-mu1 * t).exp() * (w * t).cos(), (-mu2 * t).exp(),
                 (-isg * t).exp(), t, arb(1)]
        total = arb(0)
        for c, b in zip(cf, basis):
            if c:
                total += _within_rounding(c) * b
        return total
    return at


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
                row.propagated = determinant_12(printed_pc[0], printed_pc[1], ball(x))
                row.propagated_from = ("determinant (12) with the paper's printed a_ij, mu1, omega, mu2 and 1/sigma, "
                                       "each exactly as printed")
                from_printed.append((x, row.propagated))
            rows.append(row)
        if from_printed:
            rows.append(_g_from_printed_row(gx, gv, from_printed))
        rows.append(AuditRow("g(x) table: sign pattern", " ".join(signs_p), " ".join(signs_o), None,
                             AuditStatus.DISAGREES if signs_p != signs_o else AuditStatus.AGREES,
                             f"certified root theta* = {_fmt(orbit.theta, 12)}: (12) changes sign between the "
                             "printed x values bracketing it; the printed table is monotonically decreasing with its "
                             "zero at 0.13826994, the determinant as written increases through theta* (opposite sign, "
                             "other scale)"))
    comps = orbit_expsums(sp, orbit.x0)
    md = pc["modes"]
    beta7 = _form7(comps[0], md)
    D = [beta7[0], beta7[1], beta7[2], beta7[5], _form7(comps[4], md)[3]]
    for j, txt in enumerate(paper.get("D", []), start=1):
        rows.append(_row(f"D{j}", txt, D[j - 1], "(9) at theta*"))
    names = {"beta": 0, "beta_dot": 1, "Omega": 2, "i": 3, "I": 4}
    labels = ["sin", "cos", "e^-mu2t", "e^-t/sigma", "t", "const"]
    from_printed = _printed_form7(paper)
    for comp, vals in paper.get("orbit", {}).items():
        if comp == "alpha":
            cf, _ = _alpha(comps[2], md, orbit.theta)
        else:
            cf = _form7(comps[names[comp]], md)
        for lab, v, txt in zip(labels, cf, vals):
            if txt:
                row = _row(f"{comp} {lab}" if not (comp == "i" and lab == "sin") else "i sin", txt, v,
                           "closed form (7), certified")
                prop = from_printed.get((comp, lab))
                if prop is not None:
                    row.propagated, row.propagated_from = prop
                rows.append(row)
    # Table 2
    t2 = paper.get("table2", {})
    printed_at = _printed_closed_form(paper)
    if t2:
        _, alpha_f = _alpha(comps[2], md, orbit.theta)
        order = [("alpha", alpha_f), ("beta", comps[0]), ("Omega", comps[2]), ("beta'", comps[1]),
                 ("i", comps[3]), ("I", comps[4])]
        for t, vals in t2.items():
            tt = orbit.theta if t == "theta" else ball(t)
            for (nm, f), txt in zip(order, vals):
                if txt is None or txt == "":
                    continue
                row = _row(f"Table 2 t={t} {nm}", txt, f(tt), "x(t) on the certified orbit")
                if printed_at is not None and t != "theta":
                    # the paper's own computation: its printed closed form (7) at t, from its printed
                    # coefficients and exponents (the classifier then tells its arithmetic from a misprint)
                    row.propagated = printed_at(nm, ball(t))
                    row.propagated_from = ("the paper's printed closed form (7) at this t (its printed coefficients, "
                                           "mu1, omega, mu2, 1/sigma)")
                rows.append(row)
    tabs = _tables(sp, pc, orbit)
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
                                 f"max modulus {_fmt(orbit.moduli[0], 10)}"))
            rows.append(_gains_row(P, orbit.stable))
    by_id = {r.id: r for r in rows}
    for rid, txt in paper.get("as_transcribed", {}).items():
        used = by_id[rid].printed if rid in by_id else "(no such row)"
        rows.append(AuditRow(f"transcription: {rid}", str(txt), used, None, AuditStatus.MISPRINT,
                             "a symbol garbled by the transcription, read as the digit its neighbours and the certified "
                             f"value imply (a reading of the print, not a result); the row {rid!r} judges the reading"))
    return rows


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
                f"{_fmt(amp)} (exact similarity), so theta*, the sign condition and the multipliers are those of "
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
