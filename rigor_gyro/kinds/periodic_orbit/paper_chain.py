"""Roitenberg (1947)'s own chain (issue 39): every printed number of Section 3 recomputed the way the
author did, from the paper's own printed inputs, as an Arb enclosure.

Order of the author's computation (each stage reads only prints of earlier stages):
cubic (4) -> mu1, omega, mu2 (its roots) -> a_ij (from the printed exponents) -> [theta*: no chain, see
below] -> D1..D5 ((9) at the printed theta*, the beta'(theta*) = -beta'(0) row dropped) ->
the closed form (7) (printed a_ij times printed D; alpha by the quadrature (14)-(15) of the printed
Omega row) -> Table 2 (the printed closed form at t) -> x* (its t = 0 row) -> z = eps (10) -> Table 3
(b of (16) from the printed a_ij) -> h, c of Table 1 (printed b, x*, z, exponents) -> k (24) -> the
quartic (25) -> its roots.

Each printed input is the interval of its rounding, an exact constant (S, a17 S, a47 S) is exact, and
an upstream print that the stage's own classification finds to be a misprint (one edit lands it in its
chain window, :mod:`rigor_gyro.core.digit_edits`) is replaced downstream by its intended value. The
chain is built once with every correction, then once per correction with that one print left as
printed (the alternates that name a ``propagated-misprint``). The computation runs as stages
(:func:`_stages`); each build after the first starts from an earlier build's state after the last stage
before its first row whose inputs differ (:mod:`rigor_gyro.core.staged_build`: the same balls and decisions
as a build from the start, only without repeating them).

The consistency identities of :mod:`.paper_identities` narrow a stage's chain where they agree with it
(the same number printed elsewhere, a row sum, the orbit's symmetry), and name themselves in the row.
theta* has no chain: (12) with the printed a_ij read within their rounding is some 4e4 wide near its
root (a45 = 23299.0 enters with cancellation), so it bounds no root.

Guarantee: each chain value is an enclosure over the input intervals (interval arithmetic; the quartic's roots by a Rouche bound over the coefficient intervals). Failure mode: a stage
whose enclosure is not finite gives no chain for its rows (they keep the exact reference only).
"""
from __future__ import annotations

from dataclasses import replace
from fractions import Fraction
from functools import partial
from typing import Any

from flint import acb, arb, arb_mat, ctx, fmpq, fmpq_poly

from ...core.balls import ball, ball_key, certainly_negative, certainly_positive, exact_endpoints_fmpq
from ...core.digit_edits import edits_into
from ...core.chain_classify import chain_window, decide, print_value
from ...core.paper_chain import DEFAULT_SLACK, Chain, exact_value, relation_refs, rounding_interval
from ...core.staged_build import StagedBuilds
from .paper_identities import printed_rows, relations
from .paper_forms import a_from_exponents, alpha_of_omega, b_coefficients, k_of_c, quartic_of_k, table1

__all__ = ["relay_chains", "ORBIT_LABELS"]

ORBIT_LABELS = ["sin", "cos", "e^-mu2t", "e^-t/sigma", "t", "const"]
#: rows no later stage reads (besides Table 2's)
_LEAVES = {"lambda1", "lambda3", "Re lambda2,4", "|Im lambda2,4|", "|lambda2| = |lambda4|", "theta*"}


class _Reader:
    """Records each row's chain and decides the value downstream stages read for it.

    The decision chain of a row is its computed chain narrowed by the consistency identities that agree
    with it (each identity solved for the row from the other rows' prints, kept only where it meets the
    computed chain's window: an identity that contradicts the computation is not evidence). A print
    outside that window with an evidential edit into it is read downstream as the edit's result; with a
    non-evidential edit only, the edit is a candidate (``candidates``), tried by :func:`relay_chains`."""

    def __init__(self, prints: dict[str, str], rels, keep=(), forced: dict | None = None, memo: dict | None = None):
        self.prints, self.rels, self.keep = prints, rels, set(keep)
        #: :meth:`_narrow`'s results, shared by the passes of one :func:`relay_chains` call (its relations)
        self.memo = {} if memo is None else memo
        self.order: list[str] = []
        self.forced = forced or {}
        self.chains: dict[str, Chain] = {}
        self.fixes: dict[str, str] = {}
        self.candidates: dict[str, str] = {}
        #: the fixes decided on the computed chain alone by a one-digit edit (the identities of the next pass
        #: may read them; a fix found through an identity or by two substituted digits is not read again)
        self.strong: dict[str, str] = {}

    def take(self, rid: str, txt: str | None, value: arb | None, source: str, slack: int = DEFAULT_SLACK,
             exact: bool = False) -> arb | None:
        read = exact_value if exact else rounding_interval
        if not txt:
            return value
        if value is None or not value.is_finite():
            return read(txt)
        narrowed, names = self._narrow(rid, txt, value, slack)
        ch = Chain(narrowed, source, slack, identity="; ".join(names), computed=value if names else None)
        self.chains[rid] = ch
        self.order.append(rid)
        if rid in self.keep:
            return read(txt)
        if rid in self.forced:
            self.fixes[rid] = ch.accepted = self.forced[rid]
            return read(self.forced[rid])
        kind, ed, by_identity = decide(txt, ch)
        if kind == "edit":
            self.fixes[rid] = ed.intended
            if not by_identity and ed.cls != "multi-digit-substituted":
                self.strong[rid] = ed.intended
            return read(ed.intended)
        if kind == "none":
            w = chain_window(txt, ch.computed if ch.computed is not None else narrowed, slack)
            cand = edits_into(txt, *w, evidential=False)
            if cand:
                self.candidates[rid] = cand[0].intended
        return read(txt)


    def snapshot(self) -> tuple:
        """Copies of what the reader has accumulated (its Chain objects are shared: no one mutates a Chain
        after its take; :func:`relay_chains` replaces the ones it annotates)."""
        return tuple(self.order), dict(self.chains), dict(self.fixes), dict(self.candidates), dict(self.strong)

    def restore(self, snap: tuple) -> None:
        """Continue from a :meth:`snapshot` (copied again: this reader appends to its own)."""
        order, chains, fixes, candidates, strong = snap
        self.order, self.chains, self.fixes = list(order), dict(chains), dict(fixes)
        self.candidates, self.strong = dict(candidates), dict(strong)

    def _narrow(self, rid: str, txt: str, value: arb, slack: int) -> tuple[arb, list[str]]:
        """``value`` narrowed by the identities of ``rid`` that meet its window, and their names; memoised
        by everything the result depends on (the builder's passes ask the same row again with the same
        ball and the same prints of the identities' other rows)."""
        rels = self.rels.get(rid, ()) if isinstance(self.rels, dict) else self.rels
        key = (rid, txt, *ball_key(value), slack, ctx.prec,
               tuple(tuple(self.prints.get(o) for o, _ in rel.terms) for rel in rels))
        hit = self.memo.get(key)
        if hit is not None:
            return hit
        narrowed, names = value, []
        for ref, name in relation_refs(rid, self.prints, self.rels):
            win = chain_window(txt, narrowed, slack)
            if ref.is_finite() and win is not None and name not in names:
                lo, hi = exact_endpoints_fmpq(ref)
                a, b = max(lo, win[0]), min(hi, win[1])
                if a <= b and (b - a) < (win[1] - win[0]):
                    narrowed = _interval(a, b)
                    names.append(name)
        self.memo[key] = (narrowed, names)        # arb balls are immutable; the name lists are never mutated
        return narrowed, names


def _in(txt: str, ch: Chain) -> bool:
    w = chain_window(txt, ch.value, ch.slack)
    return w is not None and w[0] <= print_value(txt.strip()) <= w[1]


def _interval(a: fmpq, b: fmpq) -> arb:
    return arb(a).union(arb(b))


def _roots_of_printed_cubic(coefs: list[str]):
    """(mu1, omega, mu2) of lambda^3 + c2 lambda^2 + c1 lambda + c0 with the printed (exact) coefficients."""
    from fractions import Fraction
    c = [Fraction(x) for x in coefs]
    poly = fmpq_poly([fmpq(x.numerator, x.denominator) for x in (c[2], c[1], c[0], Fraction(1))])
    roots = [z for z, _ in poly.complex_roots()]
    real = [z for z in roots if z.imag.is_zero()]
    cplx = [z for z in roots if certainly_positive(z.imag)]
    if len(real) != 1 or len(cplx) != 1:
        return None
    return -cplx[0].real, cplx[0].imag, -real[0].real


#: the last theta* chain, by its printed inputs and the precision (each of the builder's passes asks it)
_THETA: dict = {}


def _theta_exact_inputs(paper: dict[str, Any], guess: arb) -> arb | None:
    """An enclosure of a root of (12) near ``guess`` with the printed a_ij and exponents read exactly:
    bisection of a certified sign change of the determinant (IVT) to width 1e-12; None without one
    within +-1e-4 of the guess."""
    from .paper_model import determinant_12
    a = {(int(k[1]), int(k[2])): ball(v) for k, v in paper.get("a", {}).items()}
    need = [(1, 6), (1, 7), (4, 7)] + [(G, j) for G in (2, 3, 4) for j in range(1, 7)]
    if not all(k in a for k in need) or not all(k in paper for k in ("mu1", "omega", "mu2", "inv_sigma")):
        return None
    pc = {"a": a, "mu1": ball(paper["mu1"]), "omega": ball(paper["omega"]), "mu2": ball(paper["mu2"])}
    sig = 1 / ball(paper["inv_sigma"])

    def sgn(x: arb) -> int:
        d = determinant_12(pc, sig, x)
        return 1 if certainly_positive(d) else -1 if certainly_negative(d) else 0
    lo, hi = arb((guess - arb("1e-4")).mid()), arb((guess + arb("1e-4")).mid())
    sl, sh = sgn(lo), sgn(hi)
    if sl == 0 or sh == 0 or sl == sh:
        return None
    while certainly_positive(hi - lo - arb("1e-12")):
        m = arb(((lo + hi) / 2).mid())
        sm = sgn(m)
        if sm == 0:
            break
        lo, hi = (m, hi) if sm == sl else (lo, m)
    return lo.union(hi)


def _quartic_roots(q: list[arb]) -> dict[str, arb] | None:
    """Roots of lambda^4 + q3 lambda^3 + ... + q0 over the coefficient balls: the roots of the midpoint
    polynomial (exact rationals), each inflated by a Rouche radius r with |p_mid| > sum |dq_j| |z|^j on
    the circle |z - z0| = r (so each polynomial of the family has exactly one root in that disc; a disc
    symmetric about the real axis holds a real root)."""
    from ...core.balls import exact_fraction
    mids = [exact_fraction(arb(x.mid())) for x in q]
    rads = [arb(x.rad()) for x in q]
    poly = fmpq_poly([fmpq(m.numerator, m.denominator) for m in reversed(mids)] + [1])
    roots = [z for z, _ in poly.complex_roots()]
    if len(roots) != 4:
        return None
    co = [acb(c) for c in [arb(fmpq(m.numerator, m.denominator)) for m in reversed(mids)] + [arb(1)]]
    out = []
    for z0 in roots:
        d1 = sum((j * co[j] * z0 ** (j - 1) for j in range(1, 5)), acb(0))
        r = arb(0)
        ok = False
        for _ in range(6):
            R = abs(z0) + r
            E = sum((rads[3 - j] * R ** j for j in range(4)), arb(0))
            if r.is_zero():
                r = 4 * E / abs(d1)
                continue
            # |p(z0 + u)| >= |p'(z0)| r - sum_{k>=2} |p^(k)(z0)/k!| r^k on |u| = r
            rest = arb(0)
            for k in range(2, 5):
                ck = sum((_binom(j, k) * co[j] * z0 ** (j - k) for j in range(k, 5)), acb(0))
                rest += abs(ck) * r ** k
            if certainly_positive(abs(d1) * r - rest - E):
                ok = True
                break
            r = 2 * r
        if not ok:
            return None
        out.append((z0, r))
    real = sorted([(z, r) for z, r in out if z.imag.is_zero()], key=lambda zr: -abs(zr[0].real.mid()))
    cplx = [(z, r) for z, r in out if certainly_positive(z.imag)]
    if len(real) != 2 or len(cplx) != 1:
        return None

    def pm(x: arb, r: arb) -> arb:
        return x + arb(0, r.upper())
    z, r = cplx[0]
    return {"lambda1": pm(real[0][0].real, real[0][1]), "lambda3": pm(real[1][0].real, real[1][1]),
            "re_complex": pm(z.real, r), "im_complex": pm(z.imag, r), "modulus": pm(abs(z), r)}


def _binom(n: int, k: int) -> int:
    from math import comb
    return comb(n, k)


def _stages(paper: dict[str, Any], P) -> list:
    """The author's computation (module docstring) as stages ``(reader, state) -> state | None`` (None: the
    chain stops there), one per step and one per Table 2 time, so that a build that differs from an earlier
    one from some row on restarts at that row's stage (:class:`rigor_gyro.core.staged_build.StagedBuilds`).
    No stage mutates a container of the state it reads (each returns a new dict)."""
    fixed = [_s_exponents, _s_a, _s_theta, _s_z, _s_D, _s_form, _s_alpha]
    t2 = [partial(_s_table2, t, vals) for t, vals in paper.get("table2", {}).items()]
    tail = [_s_xstar, _s_b, _s_h, _s_c, _s_k, _s_quartic, _s_lambda]
    return [partial(s, paper, P) for s in fixed] + [partial(s, paper, P) for s in t2] + \
        [partial(s, paper, P) for s in tail]


def _s_exponents(paper, P, R: _Reader, st: dict) -> dict | None:
    S = ball(P.S)
    a17S, a47S = -ball(P.K * P.p / P.H) * S, ball(P.p) * S
    # the cubic (4) has no chain: it is where the reading of B is decided (its row keeps the exact value)
    inv_sig = R.take("1/sigma", paper.get("inv_sigma"), 1 / ball(P.sigma), "1/sigma from the stated sigma")
    ex = {}
    roots = _roots_of_printed_cubic(paper["cubic"]) if len(paper.get("cubic", [])) == 3 else None
    for k, j in (("mu1", 0), ("omega", 1), ("mu2", 2)):
        ex[k] = R.take(k, paper.get(k), roots[j] if roots else None, "root of the printed cubic")
    if any(ex[k] is None for k in ex) or inv_sig is None:
        return None
    return {"S": S, "a17S": a17S, "a47S": a47S, "inv_sig": inv_sig, "mu1": ex["mu1"], "om": ex["omega"],
            "mu2": ex["mu2"]}


def _s_a(paper, P, R: _Reader, st: dict) -> dict | None:
    a_chain = a_from_exponents(st["mu1"], st["om"], st["mu2"], st["inv_sig"], P)
    a: dict[tuple[int, int], arb] = {}
    for (G, j), v in a_chain.items():
        txt = paper.get("a", {}).get(f"a{G}{j}")
        exact = (G, j) in ((1, 7), (4, 7))
        a[(G, j)] = R.take(f"a{G}{j}", txt, v, "the printed mu1, omega, mu2, 1/sigma in (7)'s eigenvectors",
                           0 if exact else DEFAULT_SLACK, exact=exact) if txt else v
    if not paper.get("theta_star"):
        return None
    return {**st, "a": a}


def _s_theta(paper, P, R: _Reader, st: dict) -> dict:
    # theta*: (12) with the printed a_ij read within their rounding does not bound a root (its enclosure
    # is some 4e4 wide near theta*: a45 = 23299.0 enters with cancellation); with the printed numbers read
    # exactly it brackets one (a sign change, certified): that is theta*'s chain (a narrower definition,
    # said in its source); the later stages read the printed theta*
    key = (tuple(sorted(paper.get("a", {}).items())), tuple(paper.get(k) for k in ("mu1", "omega", "mu2", "inv_sigma",
                                                                               "theta_star")), ctx.prec)
    if key not in _THETA:
        _THETA.clear()
        _THETA[key] = _theta_exact_inputs(paper, ball(paper["theta_star"]))
    th = _THETA[key]
    R.take("theta*", paper["theta_star"], th, "a root of (12) with the printed a_ij, mu1, omega, mu2, 1/sigma read "
           "exactly (certified sign change; read within their rounding, (12) bounds no root)")
    theta = rounding_interval(paper["theta_star"])
    mu1, om, mu2, inv_sig = st["mu1"], st["om"], st["mu2"], st["inv_sig"]
    e1 = (-mu1 * theta).exp() * (om * theta).sin()
    e2 = (-mu1 * theta).exp() * (om * theta).cos()
    e3, e4 = (-mu2 * theta).exp(), (-inv_sig * theta).exp()
    return {**st, "theta": theta, "e": (e1, e2, e3, e4)}


def _s_z(paper, P, R: _Reader, st: dict) -> dict:
    for j, v in enumerate(st["e"], start=1):
        txt = (paper.get("table4", {}).get("z") or [None] * 4)[j - 1] if len(paper.get("table4", {}).get("z", [])) >= j else None
        R.take(f"z{j} (eps{j})", txt, v, "(10) at the printed theta* with the printed exponents")
    return st


def _s_D(paper, P, R: _Reader, st: dict) -> dict | None:
    # D1..D5 from (9) at the printed theta*, without its third row (beta'(theta*) = -beta'(0)): the five
    # rows the printed D satisfy (with the third dropped they agree to 6-7 digits; each other choice to 3-5)
    a, (e1, e2, e3, e4), theta, S = st["a"], st["e"], st["theta"], st["S"]
    r = {}
    for G in (3, 4):
        r[(G, 1)] = a[(G, 1)] * e1 + a[(G, 3)] * (e2 + 1)
        r[(G, 2)] = a[(G, 2)] * e1 + a[(G, 4)] * (e2 + 1)
        r[(G, 5)] = a[(G, 5)] * (e3 + 1)
        r[(G, 6)] = a[(G, 6)] * (e4 + 1)
    z = arb(0)
    Mx = arb_mat([[z, 1, 1, 1, a[(1, 6)]],
                  [e1, e2, e3, 1, a[(1, 6)] * e4],
                  [r[(3, 1)], r[(3, 2)], r[(3, 5)], z, r[(3, 6)]],
                  [r[(4, 1)], r[(4, 2)], r[(4, 5)], z, r[(4, 6)]],
                  [z, z, z, z, e4 + 1]])
    rhs = arb_mat([[z], [-a[(1, 7)] * theta * S], [z], [-2 * a[(4, 7)] * S], [-2 * S]])
    try:
        Dm = Mx.solve(rhs)
    except (ZeroDivisionError, ValueError):
        return None
    Dp = paper.get("D", [])
    D = [R.take(f"D{j}", Dp[j - 1] if len(Dp) >= j else None, Dm[j - 1, 0], "(9) at the printed theta* with the "
                "printed a_ij") for j in range(1, 6)]
    return {**st, "D": D}


def _s_form(paper, P, R: _Reader, st: dict) -> dict:
    # the closed form (7)
    a, D, a17S, a47S, S = st["a"], st["D"], st["a17S"], st["a47S"], st["S"]
    orbit = paper.get("orbit", {})
    src = "the printed a_ij times the printed D"
    form = {
        "beta": [D[0], D[1], D[2], a[(1, 6)] * D[4], a17S, D[3]],
        "I": [None, None, None, D[4], None, S],
    }
    for comp, G, const in (("beta_dot", 2, a17S), ("Omega", 3, None), ("i", 4, a47S)):
        form[comp] = [a[(G, 1)] * D[0] + a[(G, 2)] * D[1], a[(G, 3)] * D[0] + a[(G, 4)] * D[1], a[(G, 5)] * D[2],
                      a[(G, 6)] * D[4], None, const]
    used: dict[str, list] = {}
    for comp in ("beta", "beta_dot", "Omega", "i", "I"):
        vals = orbit.get(comp, [""] * 6)
        used[comp] = []
        for k, lab in enumerate(ORBIT_LABELS):
            v = form[comp][k]
            txt = vals[k] if k < len(vals) else ""
            rid = "i sin" if (comp, lab) == ("i", "sin") else f"{comp} {lab}"
            exact = v is not None and (lab == "t" or (lab == "const" and comp != "beta"))
            used[comp].append(R.take(rid, txt, v, src if not exact else "an exact constant (a17 S, a47 S or S)",
                                     0 if exact else DEFAULT_SLACK, exact=exact) if v is not None else
                              (rounding_interval(txt) if txt else None))
    return {**st, "used": used}


def _s_alpha(paper, P, R: _Reader, st: dict) -> dict:
    used = st["used"]
    om_c = used["Omega"][:4]
    al = alpha_of_omega(om_c, st["mu1"], st["om"], st["mu2"], st["inv_sig"], st["theta"]) \
        if all(x is not None for x in om_c) else None
    if al is None:
        return st
    vals = paper.get("orbit", {}).get("alpha", [""] * 6)
    alpha: list = []
    for k, lab in enumerate(ORBIT_LABELS):
        kk = {"sin": 0, "cos": 1, "e^-mu2t": 2, "e^-t/sigma": 3, "const": 4}.get(lab)
        txt = vals[k] if k < len(vals) else ""
        if lab == "const":      # alpha = -(B/H) beta': the constant is -(B/H) a17 S exactly (0.0006)
            alpha.append(R.take("alpha const", txt, -ball(P.B / P.H) * st["a17S"],
                                "-(B/H) a17 S (alpha = -(B/H) beta', exact)", 0, exact=True))
            continue
        alpha.append(R.take(f"alpha {lab}", txt, al[kk], "the quadrature (14)-(15) of the printed Omega "
                            "row") if kk is not None else None)
    return {**st, "used": {**used, "alpha": alpha}}


#: Table 2's columns: (name in the row id, component of the closed form)
_T2_ORDER = [("alpha", "alpha"), ("beta", "beta"), ("Omega", "Omega"), ("beta'", "beta_dot"), ("i", "i"), ("I", "I")]


def _basis(st: dict, t: arb) -> list[arb]:
    """The functions of the closed form (7) at t (the order of :data:`ORBIT_LABELS`)."""
    mu1, om, mu2, inv_sig = st["mu1"], st["om"], st["mu2"], st["inv_sig"]
    return [(-mu1 * t).exp() * (om * t).sin(), (-mu1 * t).exp() * (om * t).cos(), (-mu2 * t).exp(),
            (-inv_sig * t).exp(), t, arb(1)]


def _at(st: dict, comp: str, basis: list[arb]) -> arb | None:
    """The printed closed form of ``comp`` at the t of ``basis`` (None without its coefficients)."""
    cf = st["used"].get(comp)
    if not cf:
        return None
    tot = arb(0)
    for c_, b_ in zip(cf, basis):
        if c_ is not None:
            tot += c_ * b_
    return tot


def _s_table2(t: str, vals: list, paper, P, R: _Reader, st: dict) -> dict:
    # Table 2: the printed closed form at t (alpha, beta, Omega, beta', i, I); the basis at t is computed
    # once per row (the same operations on the same balls: the same ball as once per column)
    basis = _basis(st, st["theta"] if t == "theta" else exact_value(t))
    for (nm, comp), txt in zip(_T2_ORDER, vals):
        v = _at(st, comp, basis)
        if v is not None:
            R.take(f"Table 2 t={t} {nm}", txt, v, "the printed closed form (7) at t")
    return st


def _s_xstar(paper, P, R: _Reader, st: dict) -> dict:
    # Table 4: x* (the t = 0 point), then Table 3, h, c, k, the quartic and its roots
    t4 = paper.get("table4", {})
    basis = _basis(st, arb(0))
    xs = []
    for j, (nm, comp) in enumerate((("beta'*", "beta_dot"), ("Omega*", "Omega"), ("i*", "i"), ("I*", "I"))):
        txt = t4.get("x_star", [None] * 4)[j] if len(t4.get("x_star", [])) > j else None
        xs.append(R.take(nm, txt, _at(st, comp, basis), "the printed closed form (7) at t = 0"))
    zp = t4.get("z", [])
    eps = [rounding_interval(zp[j]) if len(zp) > j and f"z{j + 1} (eps{j + 1})" not in R.fixes else
           (rounding_interval(R.fixes[f"z{j + 1} (eps{j + 1})"]) if len(zp) > j else st["e"][j])
           for j in range(4)]
    return {**st, "xs": xs, "eps": eps}


def _s_b(paper, P, R: _Reader, st: dict) -> dict | None:
    try:
        bch = b_coefficients(st["a"], st["S"])
    except (ZeroDivisionError, ValueError):
        return None
    b = {}
    for (G, j), v in bch.items():
        txt = paper.get("table3", {}).get(f"b{G}_{j}")
        exact = (G, j) in ((1, 19), (2, 18), (4, 18), (5, 1), (5, 2))
        b[(G, j)] = R.take(f"b{G},{j}", txt, v, "(16) from the printed a_ij", 0 if exact else DEFAULT_SLACK,
                           exact=exact) if txt else v
    if any(x is None for x in st["xs"]):
        return None
    return {**st, "b": b}


def _s_h(paper, P, R: _Reader, st: dict) -> dict:
    h, c = table1(st["b"], st["xs"], st["eps"], st["mu1"], st["om"], st["mu2"], st["inv_sig"])
    t4 = paper.get("table4", {})
    hv = {}
    for (G, j), v in h.items():
        hv[(G, j)] = R.take(f"h{G}{j}", t4.get("h", {}).get(f"h{G}{j}"), v, "Table 1 with the printed b, x*")
    return {**st, "c_table1": c, "hv": hv}


def _s_c(paper, P, R: _Reader, st: dict) -> dict:
    # c_G5 from the printed h (the author's order: h first, then c); a copy of Table 1's c (the state's is
    # never mutated)
    c, hv, b = dict(st["c_table1"]), st["hv"], st["b"]
    mu1, om, mu2, inv_sig = st["mu1"], st["om"], st["mu2"], st["inv_sig"]
    e1p, e2p, e3p, e4p = st["eps"]
    for G in (1, 2, 3, 4):
        c[(G, 5)] = ((-mu1 * e1p + om * e2p) * hv[(G, 1)] - (mu1 * e2p + om * e1p) * hv[(G, 2)]
                     - mu2 * e3p * hv[(G, 3)] - e4p * hv[(G, 4)] * inv_sig) + (b[(1, 19)] if G == 1 else 0)
    c[(5, 5)] = -e4p * hv[(5, 4)] * inv_sig
    t4 = paper.get("table4", {})
    cv = {}
    for (G, j), v in c.items():
        exact = G == 5 and j < 4
        cv[(G, j)] = R.take(f"c{G}{j}", t4.get("c", {}).get(f"c{G}{j}"), v, "Table 1 with the printed b, h, z",
                            0 if exact else DEFAULT_SLACK, exact=exact)
    return {**st, "cv": cv}


def _s_k(paper, P, R: _Reader, st: dict) -> dict:
    t4 = paper.get("table4", {})
    kv = {}
    for (g, j), v in k_of_c(st["cv"]).items():
        kv[(g, j)] = R.take(f"k{g}{j}", t4.get("k", {}).get(f"k{g}{j}"), v, "(24) with the printed c")
    return {**st, "kv": kv}


def _s_quartic(paper, P, R: _Reader, st: dict) -> dict:
    q = quartic_of_k(st["kv"])
    qp = paper.get("quartic", [])
    qu = [R.take(f"quartic (25): coefficient of lambda^{3 - j}", qp[j] if len(qp) > j else None, q[j],
                 "det(lambda I + K) with the printed k") for j in range(4)]
    return {**st, "qu": qu}


def _s_lambda(paper, P, R: _Reader, st: dict) -> dict:
    rts = _quartic_roots(st["qu"])
    lam = paper.get("lambda", {})
    if rts:
        for key, rid in (("lambda1", "lambda1"), ("lambda3", "lambda3"), ("re_complex", "Re lambda2,4"),
                         ("im_complex", "|Im lambda2,4|"), ("modulus", "|lambda2| = |lambda4|")):
            R.take(rid, lam.get(key), rts[key], "roots of the printed quartic (25)")
    return st


def _changed(rels, a: tuple, b: tuple) -> set[str]:
    """The rows whose takes may differ between two build configurations ``(prints, keep, forced)``: kept as
    printed in one only, forced to another text, or narrowed by an identity that reads a print that differs
    (:meth:`_Reader._narrow` reads the prints of every row of the row's identities; nothing else of the
    configuration reaches a take)."""
    (pa, ka, fa), (pb, kb, fb) = a, b
    out = set(ka ^ kb)
    out.update(r for r in fa.keys() | fb.keys() if fa.get(r) != fb.get(r))
    if pa is not pb and pa != pb:           # (the passes build equal prints as new dicts)
        for o in pa.keys() | pb.keys():
            if pa.get(o) != pb.get(o):
                for rel in (rels.get(o, ()) if isinstance(rels, dict) else rels):
                    out.update(r for r, _ in rel.terms)
    return out


def _build(paper: dict[str, Any], P, prints, rels, keep=(), forced: dict | None = None, memo: dict | None = None,
           builds: StagedBuilds | None = None, need: set | None = None) -> _Reader:
    """The chain built with ``prints`` for the identities, the rows ``keep`` read as printed and the rows
    ``forced`` read as the given text. ``builds``: the earlier builds of the same :func:`relay_chains` call
    (same paper, parameters, identities and precision): the build starts from the state of one of them after
    the last stage before its first row whose take differs (:func:`_changed`), exactly what it would compute
    (:mod:`rigor_gyro.core.staged_build`). ``need``: the rows the caller reads; the build may stop once it
    has taken them all."""
    R = _Reader(prints, rels, keep, forced, memo)
    if builds is None:
        builds = StagedBuilds(_stages(paper, P), partial(_changed, rels))
    return builds.run(R, (prints, R.keep, R.forced), need)


def _paper_parameters(paper: dict[str, Any], P):
    """The parameters the author computed with: the stated ones, except B, which the printed cubic fixes
    (its constant term is c0 = q^2/tau, q^2 = H^2/(A B), so B = H^2 / (A tau c0)): the chain is the paper's
    own whatever B the scene reads (the printed 0.133 gives another cubic)."""
    from types import SimpleNamespace
    from .flow import PARAMETER_NAMES
    vals = {k: getattr(P, k) for k in PARAMETER_NAMES}
    cubic = paper.get("cubic", [])
    if len(cubic) == 3:
        c0 = Fraction(cubic[2])
        if c0 > 0:
            vals["B"] = P.H * P.H / (P.A * P.tau * fmpq(c0.numerator, c0.denominator))
    return SimpleNamespace(**vals)


def relay_chains(paper: dict[str, Any], P) -> tuple[dict[str, Chain], dict[str, str]]:
    """(row id -> Chain, row id -> intended text of each upstream correction). The chain is built with
    every evidential correction; a candidate correction (an edit that lands in a window too wide to be
    evidence by itself) is accepted when the build with it reproduces more downstream prints and loses
    none (the author computed with the intended number); then, for each correction, the chain with that
    one print left as printed gives the ``alternates``."""
    _w = chain_window
    P = _paper_parameters(paper, P)
    prints = orig = printed_rows(paper)
    rels: dict[str, list] = {}
    for rel in relations(Fraction(int(P.B.p), int(P.B.q)) / Fraction(int(P.H.p), int(P.H.q)),
                         list(paper.get("table2", {}))):
        for r_, _ in rel.terms:
            rels.setdefault(r_, []).append(rel)

    seen: dict[int, tuple[Chain, bool]] = {}

    def inside(ch: dict[str, Chain]) -> set[str]:
        # whether a row's print is in its chain's window, memoised by the Chain object (the builds share the
        # objects of the rows before their first difference; a Chain's value and slack are never reassigned,
        # and the entry holds the object, so its id is not reused)
        out = set()
        for k, c in ch.items():
            hit = seen.get(id(c))
            if hit is None or hit[0] is not c:
                txt = orig.get(k)
                w = _w(txt, c.value, c.slack) if txt else None
                hit = seen[id(c)] = (c, w is not None and w[0] <= print_value(txt.strip()) <= w[1])
            if hit[1]:
                out.add(k)
        return out
    forced: dict[str, str] = {}
    memo: dict = {}
    # every build below starts from the state of an earlier one where their inputs agree (staged_build)
    builds = StagedBuilds(_stages(paper, P), partial(_changed, rels))
    full = _build(paper, P, prints, rels, memo=memo, builds=builds)
    for _ in range(2):          # the identities read the other rows as corrected by the previous pass
        again = _build(paper, P, {**prints, **full.strong}, rels, memo=memo, builds=builds)
        if again.fixes == full.fixes:
            break
        full = again
    prints = {**prints, **full.strong}
    base = inside(full.chains)
    why: dict[str, str] = {}
    for rid, intended in list(full.candidates.items()):
        if rid.startswith("Table 2 ") or rid in _LEAVES:
            continue                # no later stage reads it: no downstream evidence to find
        trial = _build(paper, P, prints, rels, forced={**forced, rid: intended}, memo=memo, builds=builds)
        got = inside(trial.chains)
        gained = sorted(got - base - {rid})
        if gained and not (base - got - {rid}):
            forced[rid] = intended
            why[rid] = ", ".join(gained[:4]) + (" ..." if len(gained) > 4 else "")
            base = got
    if forced:
        full = _build(paper, P, prints, rels, forced=forced, memo=memo, builds=builds)
    chains = full.chains            # the reader's own dict; its Chain objects may be shared with other
    for rid in forced:              # builds' snapshots: the annotated ones are replaced, not mutated
        if rid in chains:
            chains[rid] = replace(chains[rid], accepted=forced[rid], cache={},
                                  evidence=f"downstream rows reproduce only with {forced[rid]}: {why[rid]}")
    # alternates: only for rows no chain explains, and only where the build with every correction left as
    # printed reproduces them (then one build per earlier correction names the one that does)
    lost = [k for k in full.order if k in orig and k not in full.fixes and decide(orig[k], chains[k])[0] == "none"]
    if lost and full.fixes:
        raw = _build(paper, P, prints, rels, keep=set(full.fixes), forced=forced, memo=memo, builds=builds,
                     need=set(lost))
        lost = [k for k in lost if k in raw.chains and _in(orig[k], raw.chains[k])]
        pos = {k: i for i, k in enumerate(full.order)}
        for rid in sorted(full.fixes, key=lambda r: pos.get(r, 0)):
            todo = [k for k in lost if pos[k] > pos.get(rid, 0)]
            if not todo:
                continue
            alt = _build(paper, P, prints, rels, keep={rid}, forced=forced, memo=memo, builds=builds, need=set(todo))
            for k in todo:
                if k in alt.chains and _in(orig[k], alt.chains[k]):
                    chains[k] = replace(chains[k], cache={},
                                        alternates=chains[k].alternates + ((alt.chains[k].value, rid),))
                    lost.remove(k)
    return chains, dict(full.fixes)
