"""Rudenko (1976): audit rows for the derivation's steps and the verbal claims around (14) (issue 39):
(5) for every parameter (exact identities), the step of (6) (its two sides against F on [0, nu1], and
the factor the right side needs from (3) and (5)), and the statements in words after (14).

Guarantee:
- (5): polynomial identities in (a, b, eps) checked exactly over ``fmpq_mpoly``; with them (5) holds for
  every a > b > 1, eps > 0 (the argument is in the row; every step is one of the identities or a sign of a
  product of positive factors).
- (6): each side's inequality against F on [0, nu1] is reduced, by multiplying with factors that are
  positive there, to a polynomial with exact rational coefficients being positive on [0, nu1]; decided by
  bisection in balls (each piece certainly positive), refuted only at a certified point where it is
  negative. The factor row compares two exact rationals' balls.
- (14): the limits are exact algebra in (14) (checked in exact rationals at the example's dimensional
  parameters with A3 = K3 = 1); the sensitivities of the exact frequencies are certified by the implicit
  function theorem in balls at the certified roots.
Failure mode: a bisection that does not decide within its budget gives no row (an undecided row would only
make the prover raise the precision, which a budget does not change). Precision: the working precision.
"""
from __future__ import annotations

from flint import arb, fmpq, fmpq_mpoly_ctx, fmpq_poly

from ...core.balls import certainly_gt, certainly_lt, certainly_negative, certainly_positive, decimal_bounds
from ...core.dual_balls import Dual, variable
from ...core.outcome import AuditRow, AuditStatus
from .model import Params, quartic_value

__all__ = ["step_rows", "five_identities", "positive_on"]

ROOT = "__w__"


def _fmt(x: arb, n: int = 8) -> str:
    lo, hi = decimal_bounds(x, n)
    return f"[{lo}, {hi}]"


# ----------------------------------------------------------------------------- (5) for every parameter

def five_identities() -> dict[str, bool]:
    """The identities (5) rests on, each checked exactly as a polynomial identity in (a, b, eps) (denominators
    cleared; c2 = (a-b)(b-1), B1 = eps(a-1) + a - b, B2 = eps(a-1) + b(a-b)):
    q14(nu1+) (a-b)^2 = -eps^2 (a-b)^2 / ... i.e. q14(eps/(a-b)) = -eps^2; q26(eps a/(b(a-b))) = -eps^2 a/b^2;
    B1/c2 - nu1- - nu4- = nu4+ - nu4-; B1/c2 - nu1+ = nu4-; the same two for nu2, nu6."""
    ctx = fmpq_mpoly_ctx.get(("a", "b", "e"), "lex")
    a, b, e = ctx.gens()
    c2 = (a - b) * (b - 1)
    B1, B2 = e * (a - 1) + a - b, e * (a - 1) + b * (a - b)
    out = {}
    # q14(eps/(a-b)) (a-b)^2 = c2 eps^2 - B1 eps (a-b) + eps (a-b)^2 and -eps^2 (a-b)^2
    out["q14(nu1+) = -eps^2"] = c2 * e * e - B1 * e * (a - b) + e * (a - b) ** 2 == -e * e * (a - b) ** 2
    # q26(eps a/(b(a-b))) (b(a-b))^2 = c2 eps^2 a^2 - B2 eps a b (a-b) + eps a b^2 (a-b)^2 and -eps^2 a/b^2 (b(a-b))^2
    out["q26(nu2+) = -eps^2 a/b^2"] = (c2 * e * e * a * a - B2 * e * a * b * (a - b) + e * a * b * b * (a - b) ** 2
                                       == -e * e * a * (a - b) ** 2)
    # B1/c2 - eps/(a-b) = (1+eps)/(b-1): times c2: B1 - eps (b-1) = (1+eps)(a-b)
    out["B1/c2 - nu1+ = nu4-"] = B1 - e * (b - 1) == (1 + e) * (a - b)
    # B2/c2 - eps a/(b(a-b)) = (b^2+eps)/(b(b-1)): times b c2: b B2 - eps a (b-1) = (b^2+eps)(a-b)
    out["B2/c2 - nu2+ = nu6-"] = b * B2 - e * a * (b - 1) == (b * b + e) * (a - b)
    # nu4+ - nu4- = eps/(a-b) - eps/B1 (= nu1+ - nu1-): eps^2 (a-1)/((a-b) B1), times (a-b) B1
    out["nu4+ - nu4- = nu1+ - nu1-"] = e * B1 - e * (a - b) == e * e * (a - 1)
    # nu6+ - nu6- = nu2+ - nu2-: eps a/(b(a-b)) - eps a/(b(a-b) + eps(a-1)) = eps^2 a (a-1)/(b(a-b)(b(a-b)+eps(a-1)))
    bb = b * (a - b) + e * (a - 1)
    out["nu6+ - nu6- = nu2+ - nu2-"] = e * a * bb - e * a * b * (a - b) == e * e * a * (a - 1)
    out["B2 = b(a-b) + eps(a-1) (nu2- denominator)"] = B2 == bb
    return out


def _five_row() -> AuditRow:
    ok = five_identities()
    good = all(ok.values())
    note = ("exact polynomial identities in (a, b, eps) (fmpq_mpoly): " + "; ".join(f"{k}: {v}" for k, v in ok.items())
            + ". Hence for every a > b > 1, eps > 0: q14 and q26 have positive leading coefficient c2 = (a-b)(b-1) and "
            "are negative at nu1+ and nu2+, so each has two real roots with nu1 < nu1+ < nu4, nu2 < nu2+ < nu6; the "
            "smaller root 2C/(B + sqrt(B^2 - 4 c2 C)) > C/B (C, B > 0) gives nu1 > nu1-, nu2 > nu2-; by Vieta nu4 = "
            "B1/c2 - nu1 and nu6 = B2/c2 - nu2, so nu4- < nu4 < nu4+ and nu6- < nu6 < nu6+ follow from the bounds on "
            "nu1, nu2 with the identities above. Every inequality of (5) is strict")
    if not good:
        return None             # an identity failing would be a bug here, not a fact about the paper: no row
    return AuditRow("(5) for every parameter", "the bounds (5) (stated for the system's parameters in general)",
                    "nu_k^- < nu_k < nu_k^+ (k = 1, 2, 4, 6) for all a > b > 1, eps > 0", None,
                    AuditStatus.CONFIRMED, note)


# ----------------------------------------------------------------------------- (6)

def positive_on(P: fmpq_poly, lo: arb, hi: arb, max_pieces: int = 4096) -> tuple[str, arb | None, int]:
    """P > 0 on [lo, hi]: ("positive", None, pieces) when every piece of a bisection is certainly positive,
    ("negative", x, pieces) with an exact point x where P(x) < 0 is certified, else ("undecided", None, pieces)."""
    Pa = P.to_arb_poly() if hasattr(P, "to_arb_poly") else None
    ev = (lambda x: Pa(x)) if Pa is not None else (lambda x: _horner(P, x))
    todo, pieces = [(lo, hi)], 0
    while todo and pieces < max_pieces:
        l, h = todo.pop()
        pieces += 1
        if certainly_positive(ev(l.union(h))):
            continue
        m = arb(((l + h) / 2).mid())
        if certainly_negative(ev(m)):
            return "negative", m, pieces
        todo += [(l, m), (m, h)]
    return ("positive" if not todo else "undecided"), None, pieces


def _horner(P: fmpq_poly, x: arb) -> arb:
    out = arb(0)
    for c in reversed(P.coeffs()):
        out = out * x + arb(c)
    return out


def _six_polys(a: fmpq, b: fmpq, e: fmpq) -> dict:
    """The exact polynomials of the (6) rows (module docstring), with c = b - 1:
    left:  LHS - F = omega / (q14 (1 - c w)) * H, H = eps a b (1 - c w) - q26 (b - c w), H(0) = 0: H / w;
    right: (F - RHS) q14 (1 - c w)(nu1+ - w) / w = q26 (b - c w)(nu1+ - w) - k (nu2- - w) q14 (1 - c w), with
    k the factor of the right side (printed Lambda, read Lambda b^2)."""
    w = fmpq_poly([0, 1])
    c, c2 = b - 1, (a - b) * (b - 1)
    q14 = c2 * w * w - (e * (a - 1) + a - b) * w + e
    q26 = c2 * w * w - (e * (a - 1) + b * (a - b)) * w + e * a
    H = e * a * b * (1 - c * w) - q26 * (b - c * w)
    Hw, rem = divmod(H, w)
    n1p, n2m = e / (a - b), e * a / (b * (a - b) + e * (a - 1))
    lam = (b * (b - 1) + e) / (b * (b - 1))

    def right(k):
        return q26 * (b - c * w) * (n1p - w) - k * (n2m - w) * q14 * (1 - c * w)
    return {"H/w": Hw, "H rem": rem, "right printed": right(lam), "right read": right(lam * b * b), "lam": lam,
            "n1p": n1p, "n2m": n2m, "q14": q14}


def _six_rows(a: fmpq, b: fmpq, e: fmpq, nu: dict) -> list[AuditRow]:
    """(6) on [0, nu1]: left side >= F, F >= right side (factor printed Lambda, and read Lambda b^2), and the
    factor (3) with (5) gives: K(0) = nu5 nu6/(nu3 nu4) = b nu6/nu4 >= b nu6-/nu4+, against Lambda b^2."""
    if nu is None:
        return []
    P = _six_polys(a, b, e)
    top = nu[1].upper()           # [0, nu1] inside [0, top]; the reductions hold on [0, nu1) (factors > 0)
    rows = []
    if P["H rem"] == 0:
        st, x, n = positive_on(P["H/w"], arb(0), arb(top))
        if st != "undecided":
            rows.append(AuditRow(
                "(6) left side >= F on [0, nu1]", "omega eps a b / ((b-1)(a-b) omega^2 - (eps(a-1)+a-b) omega + eps) >= F",
                "as printed (the left side is F with (omega-nu2)(omega-nu6) replaced by its value eps a/((a-b)(b-1)) at 0 "
                "and (omega-nu5)/(omega-nu3) by its value b at 0)", None,
                AuditStatus.CONFIRMED if st == "positive" else AuditStatus.REFUTED,
                (f"LHS - F = omega H(omega)/(q14 (1 - (b-1) omega)) with q14 > 0 and 1 - (b-1) omega > 0 on [0, nu1); H/omega "
                 f"(exact rational cubic) > 0 on [0, {_fmt(nu[1])}] certified on {n} pieces: the left side bounds F from "
                 "above on the branch, equal at omega = 0; (7)'s lower bound drops the omega^2 term of the denominator, "
                 "which only raises the left side" if st == "positive" else
                 f"H/omega < 0 at omega = {_fmt(x)} (certified): the left side is below F there")))
    results = {}
    for key in ("right printed", "right read"):
        st, x, n = positive_on(P[key], arb(0), arb(top))
        results[key] = (st, x, n)
    text = {"right printed": "factor [1 + eps/(b(b-1))] = Lambda as printed",
            "right read": "factor Lambda b^2 (the reading (7) uses)"}
    for key, (st, x, n) in results.items():
        if st == "undecided":
            continue
        rows.append(AuditRow(
            f"(6) F >= right side on [0, nu1] ({'printed' if key == 'right printed' else 'as read'})",
            "F >= omega (omega - nu2^-)/(omega - nu1^+) [1 + eps/(b(b-1))]", text[key], None,
            AuditStatus.CONFIRMED if st == "positive" else AuditStatus.REFUTED,
            (f"(F - RHS) q14 (1 - (b-1) omega)(nu1+ - omega)/omega (exact rational polynomial; the factors are > 0 on "
             f"[0, nu1) since nu1 < nu1+ < nu3) is > 0 on [0, {_fmt(nu[1])}], certified on {n} pieces" if st == "positive"
             else f"the reduced polynomial is < 0 at omega = {_fmt(x)} (certified): the right side exceeds F there")))
    # the factor: what (3) and (5) give for K(0), against Lambda b^2
    k0 = b * nu[6] / nu[4]
    n4p = (1 + e) / (b - 1) + e * e * (a - 1) / ((a - b) * (a - b + e * (a - 1)))
    k0_low = b * ((b * b + e) / (b * (b - 1))) / n4p
    lb2 = arb(P["lam"] * b * b)
    if certainly_lt(k0, lb2):
        ok_read = results["right read"][0] == "positive"
        rows.append(AuditRow(
            "(6) step: the right side's factor from (3) and (5)", "[1 + eps/(b(b-1))] (read Lambda b^2)",
            "K(0) = nu5 nu6/(nu3 nu4) = b nu6/nu4 >= b nu6^-/nu4^+ (what (3) with (5) gives)", k0,
            AuditStatus.REFUTED,
            f"K(0) = {_fmt(k0)} (its bound from (5): b nu6-/nu4+ = {_fmt(arb(k0_low))}) < Lambda b^2 = {_fmt(lb2)} "
            f"(certified): the read factor Lambda b^2 = b (b + eps/(b-1)) is not a lower bound of K on [0, nu1] "
            "(K increases from K(0), row '(3) K monotone'), so (6) as read does not follow from (3) and (5) (it is "
            "K(0) at eps = 0, b^2, raised by Lambda); the printed Lambda alone is far below K(0) and gives an upper "
            "bound of omega_1 far from 43.4 Hz. " + (
                "Yet F >= the right side as read holds on [0, nu1] at the example (row above): the slack of nu2^- and "
                "nu1^+ in (omega - nu2^-)/(omega - nu1^+) covers the excess, so (7)'s upper bound is a valid bound here "
                "by another argument than the paper's" if ok_read else
                "and F >= the right side as read is not certified on [0, nu1] (row above)")))
    return rows


# ----------------------------------------------------------------------------- the statements in words after (14)

def _elasticities(a: fmpq, b: fmpq, e: fmpq, W: fmpq, w: arb) -> dict:
    """d ln omega / d p at the certified root w (implicit function theorem in balls: -Q_p / (Q_w w))."""
    ps = Params(variable("a", arb(a)), variable("b", arb(b)), variable("eps", arb(e)), variable("W", arb(W)))
    D = quartic_value(Dual(w, {ROOT: arb(1)}), ps)
    gw = D.grad.get(ROOT)
    return {k: -D.grad.get(k, arb(0)) / (gw * w) for k in ("a", "b", "eps", "W")}


def _fourteen_claim_rows(a: fmpq, b: fmpq, e: fmpq, W: fmpq, omegas: list[arb], nu2: arb | None) -> list[AuditRow]:
    rows = []
    if len(omegas) != 4:
        return rows
    # (i) infinitely stiff gimbal (K2, K3 -> oo at fixed eps = K2/K3): lambda_1^0 -> H / sqrt((A1+A2+A3)(A2+A3)),
    #     the others -> oo
    A3 = K3 = fmpq(1)
    A1, A2, H2 = (a - b) * A3, (b - 1) * A3, W * K3 * A3
    S1, S2 = A1 + A2 + A3, A2 + A3
    lim = H2 / (S1 * S2)
    l1 = H2 / (A1 * H2 / (e * K3) + S1 * S2)            # (14) lambda_1^0 squared
    gap_identity = lim - l1 == A1 * H2 * H2 / ((e * K3) * S1 * S2 * (A1 * H2 / (e * K3) + S1 * S2))
    text = ("when the stiffness of the gimbal's mountings is infinitely large, the expression for omega_1 gives the "
            "known first nutation frequency, and the other frequencies become infinitely large")
    if gap_identity and nu2 is not None and certainly_positive(nu2):
        rows.append(AuditRow(
            "(14) infinitely stiff gimbal", text,
            "K2, K3 -> oo at fixed eps = K2/K3 (H, A1, A2, A3 fixed)", None, AuditStatus.CONFIRMED,
            "lambda_1^0^2 = H^2/(A1 H^2/K2 + S1 S2) (S1 = A1+A2+A3, S2 = A2+A3) differs from H^2/(S1 S2) by exactly "
            "A1 H^4/(K2 S1 S2 (A1 H^2/K2 + S1 S2)) <= A1 H^4/(K2 S1^2 S2^2) -> 0 (identity checked in exact rationals at "
            "the example with A3 = K3 = 1): the rigid gimbal's nutation frequency H/sqrt(S1 S2) (in (12): omega_1 -> "
            "Omega^2/(a b) as Omega^2 -> 0). The others, for the exact roots and not only (14): for every Omega^2 > 0 "
            "the quartic's roots 2, 3, 4 lie on the branches (nu2, nu3), (nu4, nu5), (nu6, oo) (F > 0 only on the four "
            "branches, from 0 or oo to oo or 0 on each, and four roots in all), so lambda_j^2 = omega_j K3/A3 > nu2 K3/A3 "
            f"with nu2 = {_fmt(nu2)} > 0 depending on a, b, eps only: -> oo as K3 -> oo (the nu order holds at this eps: "
            "claim nu_ordering)"))
    # (ii) lambda_1, lambda_2 practically independent of K3 when x = H^2/(K3 (A2+A3)) = Omega^2/b is small
    x = W / b
    el = [_elasticities(a, b, e, W, w) for w in omegas]
    # d ln lambda_j / d ln K3 at fixed H, A, K2: lambda_j^2 = omega_j K3/A3, Omega^2 ~ 1/K3, eps ~ 1/K3
    k3 = [(1 - e_["W"] * arb(W) - e_["eps"] * arb(e)) / 2 for e_ in el]
    xa = arb(x)
    small = [certainly_lt(abs(k3[j]), xa) for j in (0, 1)]
    large = [certainly_gt(abs(k3[j]), xa) for j in (0, 1)]
    if all(small) or any(large):
        rows.append(AuditRow(
            "(14) lambda_1, lambda_2 nearly independent of K3",
            "if H^2 [K3 (A2+A3)]^-1 is small against 1, the first and second frequencies practically do not depend on "
            "the stiffness K3",
            f"|d ln lambda_j / d ln K3| <= x = H^2/(K3 (A2+A3)) = Omega^2/b = {float(x):.4g} for j = 1, 2 (exact "
            "frequencies, at the example)", None,
            AuditStatus.CONFIRMED if all(small) else AuditStatus.REFUTED,
            f"in (14) lambda_1^0 has no K3 and lambda_2^0^2 depends on K3 only through H^2/K3 beside A2+A3 (elasticity "
            f"x/(2(1+x)) = {float(x / (2 * (1 + x))):.4g}); for the exact roots (implicit function theorem in balls, K3 "
            f"acting through Omega^2 and eps): d ln lambda_1/d ln K3 = {_fmt(k3[0], 6)}, d ln lambda_2/d ln K3 = "
            f"{_fmt(k3[1], 6)}, against lambda_3, lambda_4: {_fmt(k3[2], 6)}, {_fmt(k3[3], 6)} (about 1/2: they scale "
            "like sqrt(K3))"))
    # (iii) small eps: lambda_3, lambda_4 do not depend on A1 and K2
    # d ln lambda_j / d ln A1 = (a - b)/2 d ln omega/da (a = (A1+A2+A3)/A3); d ln lambda_j / d ln K2 = eps/2 d ln omega/deps
    sa = [(a - b) * e_["a"] / 2 for e_ in el]
    sk = [arb(e) * e_["eps"] / 2 for e_ in el]
    lim3 = arb(fmpq(1, 100))
    four = sa[2:] + sk[2:]
    if all(certainly_lt(abs(s), lim3) for s in four) or any(certainly_gt(abs(s), lim3) for s in four):
        ok = all(certainly_lt(abs(s), lim3) for s in four)
        rows.append(AuditRow(
            "(14) lambda_3, lambda_4 independent of A1 and K2 at small eps",
            "at sufficiently small eps (~0.2) lambda_3^0 and lambda_4^0 do not depend on A1 nor on K2",
            "(14) for lambda_3,4 has no A1 (exact); for the exact lambda_3, lambda_4 at the example: |d ln lambda / "
            "d ln A1| < 0.01 and |d ln lambda / d ln K2| < 0.01 (a 1 % change moves them by less than 0.01 %)", None,
            AuditStatus.CONFIRMED if ok else AuditStatus.REFUTED,
            "(14)'s lambda_3,4^0 contain K2 (in R4 and under the root) but not A1, so in (14) the claim holds for A1 "
            "exactly and for K2 only approximately; for the exact frequencies (implicit function theorem in balls, "
            "A1 acting through a, K2 through eps): d ln lambda_j / d ln A1 = " + ", ".join(_fmt(s, 4) for s in sa) +
            " and d ln lambda_j / d ln K2 = " + ", ".join(_fmt(s, 4) for s in sk) + " for j = 1..4 (certified); "
            + ("lambda_3, lambda_4 are below 0.01 in both, lambda_1, lambda_2 carry the dependence: 'do not depend' "
               "holds in this approximate sense, not exactly" if ok else "not below 0.01 for lambda_3 or lambda_4")))
    return rows


def _nus(a: fmpq, b: fmpq, e: fmpq) -> dict | None:
    from ...core.polyroots import isolate_polynomial
    from .model import nu_quadratics
    q14, q26 = nu_quadratics(a, b, e)
    r14, r26 = isolate_polynomial(q14), isolate_polynomial(q26)
    if len(r14.real) != 2 or len(r26.real) != 2 or r14.nonreal or r26.nonreal:
        return None
    nu1, nu4 = sorted(r14.real, key=lambda x: float(x.mid()))
    nu2, nu6 = sorted(r26.real, key=lambda x: float(x.mid()))
    return {1: nu1, 2: nu2, 4: nu4, 6: nu6}


def step_rows(a: fmpq, b: fmpq, e: fmpq, W: fmpq, omegas: list[arb], nu: dict | None = None) -> list[AuditRow]:
    """The rows of this module (those it decided)."""
    nu = nu if nu is not None else _nus(a, b, e)
    rows = [r for r in (_five_row(),) if r is not None]
    rows += _six_rows(a, b, e, nu)
    rows += _fourteen_claim_rows(a, b, e, W, omegas, nu.get(2) if nu else None)
    return rows
