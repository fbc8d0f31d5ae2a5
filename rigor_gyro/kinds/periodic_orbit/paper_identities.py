"""Roitenberg (1947)'s printed numbers by audit row id, and the consistency identities they must obey
(issue 39): the same number printed in several places (D_j, the closed form (7), Table 4's h), the
symmetry of the orbit (Table 2's theta* row is minus its t = 0 row, which is x* of Table 4; c15 =
beta'(theta*) = -beta'*), the row sums of (16) at t = 0 (x(0) = x0), the structure of the a_ij (a_G4 =
a_G1, a_G2 = -a_G3), b_G16 = a_G6, and alpha = -(B/H) beta' (from B beta'' + H Omega = 0 and (15)).

Every identity is exact (rational coefficients from the stated parameters); each is a statement about
the exact values, so the author's numbers obey it up to his rounding. Guarantee: the identities are
proved in the tests on the certified values (each holds within the certified balls).
"""
from __future__ import annotations

from fractions import Fraction
from typing import Any

from ...core.paper_chain import Relation

__all__ = ["printed_rows", "relations"]

_LABELS = ["sin", "cos", "e^-mu2t", "e^-t/sigma", "t", "const"]


def printed_rows(paper: dict[str, Any]) -> dict[str, str]:
    """Row id -> printed text, for every printed number of the example (the ids of :func:`.paper.audit`)."""
    out: dict[str, str] = {}
    for k in ("mu1", "omega", "mu2", "theta_star"):
        if k in paper:
            out["theta*" if k == "theta_star" else k] = paper[k]
    if "inv_sigma" in paper:
        out["1/sigma"] = paper["inv_sigma"]
    for k, v in paper.get("a", {}).items():
        out[k] = v
    for j, v in enumerate(paper.get("D", []), start=1):
        out[f"D{j}"] = v
    for comp, vals in paper.get("orbit", {}).items():
        for lab, v in zip(_LABELS, vals):
            if v:
                out["i sin" if (comp, lab) == ("i", "sin") else f"{comp} {lab}"] = v
    names = ["alpha", "beta", "Omega", "beta'", "i", "I"]
    for t, vals in paper.get("table2", {}).items():
        for nm, v in zip(names, vals):
            if v:
                out[f"Table 2 t={t} {nm}"] = v
    for k, v in paper.get("table3", {}).items():
        G, j = k[1:].split("_")
        out[f"b{G},{j}"] = v
    t4 = paper.get("table4", {})
    for nm, v in zip(["beta'*", "Omega*", "i*", "I*"], t4.get("x_star", [])):
        out[nm] = v
    for j, v in enumerate(t4.get("z", []), start=1):
        out[f"z{j} (eps{j})"] = v
    for grp in ("h", "c", "k"):
        out.update(t4.get(grp, {}))
    for j, v in enumerate(paper.get("quartic", []), start=1):
        out[f"quartic (25): coefficient of lambda^{4 - j}"] = v
    lam = paper.get("lambda", {})
    for key, rid in (("lambda1", "lambda1"), ("lambda3", "lambda3"), ("re_complex", "Re lambda2,4"),
                     ("im_complex", "|Im lambda2,4|"), ("modulus", "|lambda2| = |lambda4|")):
        if key in lam:
            out[rid] = lam[key]
    return out


def _eq(a: str, b: str, name: str, f: Fraction = Fraction(1)) -> Relation:
    """x_a = f x_b."""
    return Relation(((a, Fraction(1)), (b, -Fraction(f))), Fraction(0), name)


def _equal_group(ids: list[str], name: str) -> list[Relation]:
    return [_eq(ids[i], ids[j], name) for i in range(len(ids)) for j in range(i + 1, len(ids))]


def relations(B_over_H: Fraction, table2_times: list[str]) -> list[Relation]:
    """The identities of the relay example (module docstring). ``B_over_H`` exact; ``table2_times``:
    the t keys of Table 2 (for alpha = -(B/H) beta' in each row)."""
    R: list[Relation] = []
    R += _equal_group(["D1", "beta sin", "h11"], "D1 = beta sin = h11 (one number printed three times)")
    R += _equal_group(["D2", "beta cos", "h12"], "D2 = beta cos = h12")
    R += _equal_group(["D3", "beta e^-mu2t", "h13"], "D3 = beta e^-mu2t = h13")
    R += _equal_group(["D4", "beta const"], "D4 = beta const")
    R += _equal_group(["D5", "I e^-t/sigma", "h54"], "D5 = I e^-t/sigma = h54 = I* + b51")
    R += _equal_group(["beta e^-t/sigma", "h14"], "beta e^-t/sigma = h14 (= a16 D5)")
    for G, comp in ((2, "beta_dot"), (3, "Omega"), (4, "i")):
        for m, lab in enumerate(_LABELS[:4], start=1):
            rid = "i sin" if (comp, lab) == ("i", "sin") else f"{comp} {lab}"
            R.append(_eq(rid, f"h{G}{m}", f"{rid} = h{G}{m} (Table 1: h_G1..h_G4 are the coefficients of (7))"))
    for G in (1, 2, 3, 4):
        R.append(_eq(f"a{G}6", f"b{G},16", f"a{G}6 = b{G},16 (the I0 term of (16))"))
    for G in (2, 3, 4):
        R.append(_eq(f"a{G}1", f"a{G}4", f"a{G}1 = a{G}4 (real part of the pair's eigenvector)"))
        R.append(_eq(f"a{G}2", f"a{G}3", f"a{G}2 = -a{G}3 (imaginary part)", Fraction(-1)))
    R.append(_eq("a21", "mu1", "a21 = -mu1", Fraction(-1)))
    R.append(_eq("a23", "omega", "a23 = omega"))
    R.append(_eq("a25", "mu2", "a25 = -mu2", Fraction(-1)))
    for x, comp in (("beta'*", "beta'"), ("Omega*", "Omega"), ("i*", "i"), ("I*", "I")):
        R.append(_eq(x, f"Table 2 t=0 {comp}", f"{x} = Table 2 t=0 {comp} (x* is the orbit at t = 0)"))
        R.append(_eq(f"Table 2 t=theta {comp}", x, f"Table 2 t=theta* {comp} = -{x} (symmetry of the orbit)",
                     Fraction(-1)))
    R.append(_eq("Table 2 t=theta alpha", "Table 2 t=0 alpha", "alpha(theta*) = -alpha(0) ((15))", Fraction(-1)))
    R.append(_eq("c15", "beta'*", "c15 = beta'(theta*) = -beta'* (symmetry)", Fraction(-1)))
    R.append(_eq("z4 (eps4)", "c54", "z4 = eps4 = c54 (Table 1)"))
    # row sums of (16) at t = 0: x(0) = x0
    one = {2: 6, 3: 7, 4: 8}
    for G in (1, 2, 3, 4):
        base = [(6, 11), (7, 12), (8, 13)]
        for k, (p, q) in enumerate(base):
            terms = [(f"b{G},{p}", 1), (f"b{G},{q}", 1)] + ([(f"b1,{20 + k}", 1)] if G == 1 else [])
            const = 1 if G > 1 and one[G] == p else 0
            R.append(Relation(tuple((r, Fraction(c)) for r, c in terms), Fraction(const),
                              f"row sum of (16) at t = 0: {' + '.join(r for r, _ in terms)} = {const}"))
        terms = [(f"b{G},9", 1), (f"b{G},14", 1), (f"b{G},16", 1)] + ([("b1,23", 1)] if G == 1 else [])
        R.append(Relation(tuple((r, Fraction(c)) for r, c in terms), Fraction(0),
                          f"row sum of (16) at t = 0: {' + '.join(r for r, _ in terms)} = 0"))
        tail = {1: ["b1,10", "b1,15", "b1,17", "b1,18"], 2: ["b2,10", "b2,15", "b2,17", "b2,18"],
                3: ["b3,10", "b3,15", "b3,17"], 4: ["b4,10", "b4,15", "b4,17", "b4,18"]}[G]
        R.append(Relation(tuple((r, Fraction(1)) for r in tail), Fraction(0),
                          f"row sum of (16) at t = 0: {' + '.join(tail)} = 0"))
    # alpha = -(B/H) beta' (exact): the closed form's coefficients and each Table 2 row
    for lab in ("sin", "cos", "e^-mu2t", "e^-t/sigma", "const"):
        R.append(_eq(f"alpha {lab}", f"beta_dot {lab}", f"alpha = -(B/H) beta' ({lab} coefficient)", -B_over_H))
    for t in table2_times:
        R.append(_eq(f"Table 2 t={t} alpha", f"Table 2 t={t} beta'", f"alpha = -(B/H) beta' at t = {t}", -B_over_H))
    return R
