"""Campaign sampler and references for ``lyapunov`` (float side: mpmath and numpy; no verdicts).

References: :func:`.approx.mp_constants` at 50 digits (closed forms, quadrature, grid-refined maxima)
for A0 .. R; the damping condition decided in mpmath with a margin; Vdot and V sampled in floats on
the region where the certificate says Vdot <= 0 or V > 0 (a sample clearly of the wrong sign is a
verdict disagreement, checked again in mpmath before it is reported).
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
    if samples:       # a float sample of the wrong sign: decided again in mpmath before it counts
        mg = MpGimbal(params)
        with mpmath.workdps(40):
            for claim, fn, x1, x2, x3 in samples:
                val = getattr(mg, fn)(mpmath.mpf(float(x1)), mpmath.mpf(float(x2)), mpmath.mpf(float(x3)))
                wrong = val > 0 if claim == "vdot_nonpositive" else val <= 0
                if wrong:
                    res.verdict_disagreements.append(f"{claim} proved but mpmath {fn} = {mpmath.nstr(val, 8)} at "
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
