"""Campaign sampler and references for ``eigenfrequencies`` (float side: mpmath and numpy; no verdicts).

References: the four roots by mpmath.polyroots at 60 digits (:func:`.approx.approx_roots_mpmath`), the
nus by the quadratic formula in mpmath, the paper's orderings decided in mpmath with a margin; the
float path is numpy.roots (:func:`.approx.approx_roots_numpy`).
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath
from flint import arb

from .approx import approx_roots_mpmath, approx_roots_numpy

OPTIONS: dict = {}
MAXPREC = 2048
MP_DPS = 60
#: mpmath's own error (polyroots at 60 + 20 digits): a certified ball separated from the reference by
#: more than this is a containment failure
MP_REL_TOL = 1e-45
#: numpy.roots forward error ~ condition * 1e-16: a float root farther off is a float miss
FLOAT_REL_TOL = 1e-8
#: an mpmath ordering is an independent decision only when its margin exceeds this (relative)
DECISION_MARGIN = 1e-30


def _dec(x: float) -> str:
    return f"{x:.6g}"


def _log_uniform(rng, lo: float, hi: float) -> float:
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def draw(rng) -> dict[str, str]:
    """b in (1, 20], a - b in (0, 50], eps in (0, 2], Omega2 in (0, 10], log-uniform, 10% extremes."""
    if rng.random() < 0.1:
        b = 1 + _log_uniform(rng, 1e-8, 20)
        a = b + _log_uniform(rng, 1e-6, 1e3)
        eps = _log_uniform(rng, 1e-12, 10)
        W = _log_uniform(rng, 1e-6, 1e12)
    else:
        b = 1 + _log_uniform(rng, 1e-2, 19)
        a = b + _log_uniform(rng, 1e-2, 50)
        eps = _log_uniform(rng, 1e-3, 2)
        W = _log_uniform(rng, 1e-3, 10)
    bs = _dec(b)
    if Fraction(bs) <= 1:
        bs = "1.00000001"
    as_ = _dec(a)
    if Fraction(as_) <= Fraction(bs):
        as_ = str(Fraction(bs) + Fraction(1, 10 ** 6))
    return {"a": as_, "b": bs, "eps": _dec(eps), "Omega2": _dec(W)}


def _ball_misses(ball: arb, ref) -> bool:
    """True when the certified ball is certainly separated from the reference +- its own error."""
    tol = abs(ref) * MP_REL_TOL + mpmath.mpf(10) ** (-MP_DPS)
    lo, hi = ball.lower(), ball.upper()
    return bool(arb(mpmath.nstr(ref + tol, MP_DPS)) < lo or arb(mpmath.nstr(ref - tol, MP_DPS)) > hi)


def compare(params: dict[str, str], cert, res) -> None:
    a, b, eps, W = (params[k] for k in ("a", "b", "eps", "Omega2"))
    q = cert.quantities
    st = {c.id: c.status.value for c in cert.claims}
    with mpmath.workdps(MP_DPS + 20):
        roots = approx_roots_mpmath(a, b, eps, W, dps=MP_DPS)
        A, B, E = (mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in (a, b, eps))
        c2 = (A - B) * (B - 1)
        def quad(s1, s0):
            d = mpmath.sqrt(s1 * s1 - 4 * c2 * s0)
            return (s1 - d) / (2 * c2), (s1 + d) / (2 * c2)
        n1, n4 = quad(E * (A - 1) + A - B, E)
        n2, n6 = quad(E * (A - 1) + B * (A - B), E * A)
        nus = {1: n1, 2: n2, 3: 1 / (B - 1), 4: n4, 5: B / (B - 1), 6: n6}
        for j, r in enumerate(roots, start=1):
            name = f"omega_{j}"
            if name in q:
                res.compared += 1
                if _ball_misses(q[name], r):
                    res.containment_failures.append(f"{name}: ball {q[name].str(20)} misses mpmath {mpmath.nstr(r, 30)}")
        for k, v in nus.items():
            name = f"nu_{k}"
            if name in q:
                res.compared += 1
                if _ball_misses(q[name], v):
                    res.containment_failures.append(f"{name}: ball misses mpmath {mpmath.nstr(v, 30)}")
        chain = [mpmath.mpf(0)] + [nus[k] for k in range(1, 7)]
        gaps = [(chain[i + 1] - chain[i]) / max(abs(chain[i + 1]), mpmath.mpf(1)) for i in range(6)]
        if all(g > DECISION_MARGIN for g in gaps) and st.get("nu_ordering") == "refuted":
            res.verdict_disagreements.append("nu_ordering refuted, mpmath finds the order")
        if any(g < -DECISION_MARGIN for g in gaps) and st.get("nu_ordering") == "proved":
            res.verdict_disagreements.append("nu_ordering proved, mpmath finds a violation")
        if len(roots) == 4 and all(r > 0 for r in roots):
            iv = [(0, nus[1]), (nus[2], nus[3]), (nus[4], nus[5]), (nus[6], None)]
            inside = all(r - lo > DECISION_MARGIN * r and (hi is None or hi - r > DECISION_MARGIN * r)
                         for r, (lo, hi) in zip(roots, iv))
            outside = any(lo - r > DECISION_MARGIN * r or (hi is not None and r - hi > DECISION_MARGIN * r)
                          for r, (lo, hi) in zip(roots, iv))
            if inside and st.get("branches") == "refuted" or outside and st.get("branches") == "proved":
                res.verdict_disagreements.append(f"branches {st.get('branches')} against mpmath")
    try:
        fl = approx_roots_numpy(a, b, eps, W)
    except Exception:
        fl = []
    for j, f in enumerate(fl, start=1):
        name = f"omega_{j}"
        if name in q and q[name].is_finite():
            m = float(q[name].mid())
            err = abs(f - m) / abs(m) if m else abs(f)
            if not err <= FLOAT_REL_TOL:
                res.float_misses.append((name, err))
