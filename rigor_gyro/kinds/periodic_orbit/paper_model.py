"""The model's side of Roitenberg (1947)'s forms (the audit is :mod:`.paper_audit`, the paper's own
chain :mod:`.paper_chain`): the a_ij of (7), determinant (12), D1..D5 of (9), the closed-form
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

from flint import acb, arb, arb_mat

from ...core.audit import NUMBER, TEXT, keys, numbers
from ...core.balls import ball, decimal_bounds
from .paper_forms import b_coefficients
from .flow import ExpSum, Spectrum, half_period_jacobian, orbit_expsums, phi_at, vector_field

__all__ = ["PAPER_SCHEMA", "formula_table", "paper_coefficients", "orbit_quantities", "determinant_12", "fmt_ball", "form7",
           "alpha_form", "paper_tables", "modes_of"]

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


def fmt_ball(x: arb, d: int = 10) -> str:
    lo, hi = decimal_bounds(x, d)
    return f"[{lo}, {hi}]"


# ----------------------------------------------------------------------------- the paper's variables

def modes_of(sp: Spectrum):
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
    md = modes_of(sp)
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


def form7(f: ExpSum, md) -> list[arb]:
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


def alpha_form(f_Omega: ExpSum, md, theta: arb) -> tuple[list[arb], ExpSum]:
    """alpha = int Omega dt + C with alpha(0) = -alpha(theta*) ((14)-(15)); Omega has no t-term."""
    terms = [(a / l, l, w) for a, l, w in f_Omega.terms]
    F = ExpSum(terms, arb(0), f_Omega.c0)
    C = -(F(arb(0)) + F(theta)) / 2
    F = ExpSum(terms, C, f_Omega.c0)
    return form7(F, md), F


def orbit_quantities(model, sp: Spectrum, orbit) -> tuple[dict[str, arb], list[str]]:
    """D1..D5 and the certified closed form (7) of the scene's orbit (quantities and a note)."""
    md = modes_of(sp)
    if md is None:
        return {}, ["the cubic (4) has three real roots: the paper's form (6)-(7) (one complex pair) does not apply"]
    comps = orbit_expsums(sp, orbit.x0)
    beta = form7(comps[0], md)
    I = form7(comps[4], md)
    pc = paper_coefficients(sp)
    q = {"D1": beta[0], "D2": beta[1], "D3": beta[2], "D4": beta[5], "D5": I[3]}
    names = ["beta", "beta'", "Omega", "i", "I"]
    lines = []
    for nm, f in zip(names, comps):
        c = form7(f, md)
        lines.append(f"{nm} = {fmt_ball(c[0], 9)} e^(-mu1 t) sin(omega t) + {fmt_ball(c[1], 9)} e^(-mu1 t) cos(omega t) + "
                     f"{fmt_ball(c[2], 9)} e^(-mu2 t) + {fmt_ball(c[3], 9)} e^(-t/sigma) + {fmt_ball(c[4], 9)} t + {fmt_ball(c[5], 9)}")
    al, _ = alpha_form(comps[2], md, orbit.theta)
    lines.append(f"alpha = {fmt_ball(al[0], 9)} e^(-mu1 t) sin(omega t) + {fmt_ball(al[1], 9)} e^(-mu1 t) cos(omega t) + "
                 f"{fmt_ball(al[2], 9)} e^(-mu2 t) + {fmt_ball(al[3], 9)} e^(-t/sigma) + {fmt_ball(al[5], 9)}")
    note = (f"Orbit in the paper's closed form (7) on 0 < t < theta* (certified coefficients; mu1 = {fmt_ball(pc['mu1'], 12)}, "
            f"omega = {fmt_ball(pc['omega'], 12)}, mu2 = {fmt_ball(pc['mu2'], 12)}, 1/sigma exact; on the second half-period "
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

def paper_tables(sp: Spectrum, pc: dict[str, Any], orbit) -> dict[str, Any]:
    """b_ij of (16), h, c, k of Table 4, eps_j (z_j), and the quartic (25), for the orbit."""
    a = pc["a"]
    P = sp.P
    b = b_coefficients(a, ball(P.S))
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

