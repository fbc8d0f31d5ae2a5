"""Campaign sampler and references for ``lyapunov`` (float side: mpmath and numpy; no verdicts).

References: :func:`.approx.mp_constants` at 50 digits (closed forms, quadrature, grid-refined maxima)
for A0 .. R; the damping condition decided in mpmath with a margin; Vdot and V sampled in floats on
the region where the certificate says Vdot <= 0 or V > 0 (a sample clearly of the wrong sign is a
verdict disagreement, checked again in mpmath before it is reported). ``vdot_direct``: grad V . f (the
analytic gradient, not the Psi form) sampled on the disc of radius R_direct, half the samples on its
rim (Vdot is -r^2 (A + r B) along a ray: the rim is the worst case); ``best_mu_direct``: the same at
mu_direct on the disc of radius R_direct_max. ``largest_sublevel``: along random
rays (x2, t), where grad V . f first turns >= 0 and at V's minimum beyond it, V must be >= c_max_lower.
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
from flint import arb

from .approx import AGAFONOV2013, FloatGimbal, MpGimbal, float_constants, mp_constants

OPTIONS: dict = {}
MAXPREC = 512
MP_DPS = 50
MP_REL_TOL = 1e-40
FLOAT_REL_TOL = 1e-6
DECISION_MARGIN = 1e-20
CONSTANTS = ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R")
SAMPLES = 200
#: a sampled V below c_max_lower by more than this (relative) where Vdot >= 0 counts against the claim
SUBLEVEL_SLACK = 1e-9


def _dec(x: float) -> str:
    return f"{x:.6g}"


def _log_uniform(rng, lo: float, hi: float) -> float:
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def draw(rng) -> dict[str, str]:
    p = dict(AGAFONOV2013)
    for k in ("A", "A1", "B1", "C1", "A2"):
        p[k] = _dec(float(Fraction(p[k])) * _log_uniform(rng, 0.25, 4))
    p["C"] = _dec(_log_uniform(rng, 0.5, 10))
    p["H"] = _dec(_log_uniform(rng, 10, 1e6))
    p["k"] = _dec(_log_uniform(rng, 0.02, 5))
    p["a"] = _dec(_log_uniform(rng, 1, 1e4))
    A0 = sum(float(Fraction(p[k])) for k in ("A", "A1", "A2"))
    # mostly inside mu < k/A0 (the upper end of (16)); the rest anywhere (damping refuted there)
    p["mu"] = _dec(float(Fraction(p["k"])) / A0 * rng.uniform(0.05, 0.95) if rng.random() < 0.7
                   else _log_uniform(rng, 1e-4, 0.5))
    p["x2_star"] = rng.choice(["pi/6", "pi/4", "pi/12", _dec(rng.uniform(0.05, 1.5))])
    p["moment"] = rng.choice(["sine", "linear"])
    return p


def _misses(ball: arb, ref) -> bool:
    tol = abs(ref) * MP_REL_TOL + mpmath.mpf(10) ** (-MP_DPS)
    return bool(arb(mpmath.nstr(ref + tol, MP_DPS)) < ball.lower() or arb(mpmath.nstr(ref - tol, MP_DPS)) > ball.upper())


def compare(params: dict[str, str], cert, res) -> None:
    q = cert.quantities
    st = {c.id: c.status.value for c in cert.claims}
    mp = mp_constants(params, dps=MP_DPS, with_best_mu=False)
    for name in CONSTANTS:
        if name in q and mp.get(name) is not None and q[name].is_finite():
            res.compared += 1
            if _misses(q[name], mp[name]):
                res.containment_failures.append(f"{name}: ball {q[name].str(20)} misses mpmath {mpmath.nstr(mp[name], 25)}")
    k, mu = (mpmath.mpf(Fraction(params[x]).numerator) / Fraction(params[x]).denominator for x in ("k", "mu"))
    margins = [k - mp["k_min"], mu - mp["mu_min"], mp["mu_max"] - mu]
    scale = [abs(mp["k_min"]), abs(mp["mu_min"]), abs(mp["mu_max"])]
    holds = all(m > DECISION_MARGIN * s for m, s in zip(margins, scale))
    fails = any(m < -DECISION_MARGIN * s for m, s in zip(margins, scale))
    if holds and st.get("damping_condition") == "refuted" or fails and st.get("damping_condition") == "proved":
        res.verdict_disagreements.append(f"damping_condition {st.get('damping_condition')} against mpmath")
    fg = FloatGimbal(params)
    rng = np.random.default_rng(0)
    xs = float(fg.xs)
    samples = []
    if st.get("vdot_nonpositive") == "proved" and "R_used" in q:
        R = float(q["R_used"].lower().mid())
        r = R * np.sqrt(rng.uniform(0, 1, SAMPLES))
        t = rng.uniform(0, 2 * np.pi, SAMPLES)
        x1, x3, x2 = r * np.cos(t), r * np.sin(t), rng.uniform(-xs, xs, SAMPLES)
        vd = fg.vdot_psi(x1, x2, x3)
        samples += [("vdot_nonpositive", "vdot_psi", x1[i], x2[i], x3[i]) for i in np.nonzero(vd > 0)[0][:3]]
    if st.get("v_positive") == "proved":
        x1, x3 = rng.normal(0, 1, SAMPLES), rng.normal(0, 1, SAMPLES)
        x2 = rng.uniform(-xs, xs, SAMPLES)
        v = fg.V(x1, x2, x3)
        samples += [("v_positive", "V", x1[i], x2[i], x3[i]) for i in np.nonzero(v <= 0)[0][:3]]
    samples += _direct_samples(fg, q, st, rng, xs) + _sublevel_samples(fg, q, st, rng, xs)
    if samples:       # a float sample of the wrong sign: decided again in mpmath before it counts
        mg = MpGimbal(params)
        with mpmath.workdps(40):
            for claim, fn, x1, x2, x3 in samples:
                val = getattr(mg, fn)(mpmath.mpf(float(x1)), mpmath.mpf(float(x2)), mpmath.mpf(float(x3)))
                if claim == "largest_sublevel_face":
                    wrong = val < mpmath.mpf(float(q["c_max_lower"].mid())) * (1 - SUBLEVEL_SLACK)
                elif claim == "largest_sublevel":
                    vdot = mg.grad_V_dot_f(mpmath.mpf(float(x1)), mpmath.mpf(float(x2)), mpmath.mpf(float(x3)))
                    level = mpmath.mpf(float(q["c_max_lower"].mid()))
                    wrong = vdot >= 0 and val < level * (1 - SUBLEVEL_SLACK)
                else:
                    wrong = val > 0 if claim in ("vdot_nonpositive", "vdot_direct") else val <= 0
                if wrong:
                    res.verdict_disagreements.append(f"{claim} proved but mpmath {fn} = {mpmath.nstr(val, 8)} at "
                                                     f"({float(x1):.6g}, {float(x2):.6g}, {float(x3):.6g})")
    # best_mu_direct: the same samples at mu_direct on the disc of radius R_direct_max
    bd = next((c for c in cert.claims if c.id == "best_mu_direct"), None)
    if bd is not None and st.get("best_mu_direct") == "proved":
        at_mu = dict(params, mu=bd.details["mu_direct"])
        for claim, fn, x1, x2, x3 in _direct_samples(FloatGimbal(at_mu), q, st, rng, xs, "best_mu_direct",
                                                     "R_direct_max"):
            with mpmath.workdps(40):
                val = MpGimbal(at_mu).grad_V_dot_f(mpmath.mpf(float(x1)), mpmath.mpf(float(x2)), mpmath.mpf(float(x3)))
            if val > 0:
                res.verdict_disagreements.append(f"{claim} proved but mpmath {fn} = {mpmath.nstr(val, 8)} at mu_direct, "
                                                 f"({float(x1):.6g}, {float(x2):.6g}, {float(x3):.6g})")
    try:
        fl = float_constants(params, with_best_mu=False)
    except Exception:
        return
    for name in CONSTANTS:
        if name in q and fl.get(name) is not None and q[name].is_finite():
            m = float(q[name].mid())
            err = abs(fl[name] - m) / abs(m) if m else abs(fl[name])
            if not err <= FLOAT_REL_TOL:
                res.float_misses.append((name, float(err)))


def _ray_coefficients(fg, x2, t):
    """(A, B) with grad V . f (r cos t, x2, r sin t) = -r^2 (A + r B), from two evaluations of the
    analytic grad V . f (r = 1, 2): Vdot is a cubic form in (x1, x3) with no terms below degree 2."""
    v1 = fg.grad_V_dot_f(np.cos(t), x2, np.sin(t))
    v2 = fg.grad_V_dot_f(2 * np.cos(t), x2, 2 * np.sin(t))
    # -v1 = A + B, -v2 / 4 = A + 2 B
    B = -v2 / 4 + v1
    return -v1 - B, B


def _direct_samples(fg, q, st, rng, xs, claim: str = "vdot_direct", radius: str = "R_direct") -> list:
    if st.get(claim) != "proved" or radius not in q:
        return []
    R = float(q[radius].mid())
    n = SAMPLES
    r = np.where(np.arange(n) % 2 == 0, R, R * np.sqrt(rng.uniform(0, 1, n)))
    t = rng.uniform(0, 2 * np.pi, n)
    x1, x3, x2 = r * np.cos(t), r * np.sin(t), rng.uniform(-xs, xs, n)
    vd = fg.grad_V_dot_f(x1, x2, x3)
    scale = np.abs(fg.grad_V_dot_f(x1, x2 * 0, x3)) + 1e-300
    bad = np.nonzero(vd > 1e-9 * scale)[0][:3]
    return [(claim, "grad_V_dot_f", x1[i], x2[i], x3[i]) for i in bad]


def _sublevel_samples(fg, q, st, rng, xs) -> list:
    if st.get("largest_sublevel") != "proved" or "c_max_lower" not in q:
        return []
    level = float(q["c_max_lower"].mid())
    n = SAMPLES
    x2 = rng.uniform(-xs, xs, n)
    t = rng.uniform(0, np.pi, n)
    A, B = _ray_coefficients(fg, x2, t)
    out = []
    for face in (xs, -xs):                  # the faces |x2| = x2* bound the set too: V >= the level there
        x3m = -float(fg.f3(face)) / float(fg.S(face))
        x1m = -float(fg.mu) * x3m * float(fg.B0) / (float(fg.H) * math.cos(face))
        for j in range(8):
            d1, d3 = (0.0, 0.0) if j == 0 else rng.normal(0, 1e-3, 2) * (abs(x1m) + abs(x3m) + 1e-12)
            v = float(fg.V(x1m + d1, face, x3m + d3))
            if math.isfinite(v) and v < level * (1 - 10 * SUBLEVEL_SLACK):
                out.append(("largest_sublevel_face", "V", x1m + d1, face, x3m + d3))
                break
    for i in range(n):
        a, b = float(A[i]), float(B[i])
        if not (math.isfinite(a) and math.isfinite(b)) or b == 0:
            continue
        r0 = -a / b                         # Vdot >= 0 on r >= r0 (b < 0) or r <= r0 (b > 0), r of either sign
        rs = [r0 * (1 + 1e-9)] if abs(r0) > 0 else []
        c, sn = math.cos(t[i]), math.sin(t[i])
        v0, vp, vm = (float(fg.V(r * c, x2[i], r * sn)) for r in (0.0, 1.0, -1.0))
        beta, gamma = (vp - vm) / 2, (vp + vm) / 2 - v0
        if gamma > 0:                       # V's minimum on the line, if it lies where Vdot >= 0
            rv = -beta / (2 * gamma)
            if a + rv * b <= 0 and rv != 0:
                rs.append(rv)
        for r in rs:
            x1, x3 = r * math.cos(t[i]), r * math.sin(t[i])
            v = float(fg.V(x1, x2[i], x3))
            if math.isfinite(v) and v < level * (1 - 10 * SUBLEVEL_SLACK):
                out.append(("largest_sublevel", "V", x1, float(x2[i]), x3))
        if len(out) >= 3:
            break
    return out
