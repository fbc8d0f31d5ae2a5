"""Campaign sampler and references for ``periodic_orbit`` (float side: mpmath and scipy; no verdicts).

References: theta* and x(0) by mpmath.findroot on g at 50 digits with mpmath.expm
(:func:`.approx.approx_orbit_mpmath`); "genuine" decided independently by sampling beta on (0, theta*)
in floats (a sample <= 0 is re-evaluated in mpmath before it counts); the float path is scipy expm +
brentq for theta* and numpy eigenvalues for the multipliers.
"""
from __future__ import annotations

from fractions import Fraction

import mpmath
from flint import arb

from .approx import approx_g, approx_multipliers, approx_orbit_mpmath

OPTIONS: dict = {}
MAXPREC = 1024
MP_DPS = 50
MP_ABS_TOL = 1e-40
FLOAT_THETA_TOL = 1e-9
FLOAT_MULT_TOL = 1e-7
BETA_SAMPLES = 400
BASE = dict(A="125", B="2/15", H="100", tau="0.01", sigma="0.13125", n="50", K="7.5", p="40", S="0.15")


def draw(rng) -> dict[str, str]:
    p = dict(BASE)
    for k in ("A", "B", "H", "sigma", "n", "K", "p", "S"):
        q = Fraction(p[k]) * Fraction(rng.randint(25, 400), 100)
        p[k] = f"{q.numerator}/{q.denominator}"
    p["tau"] = rng.choice(["0.01", "0.005", "0.02", "0.001", "0.0001", "0.00001"])
    if rng.random() < 0.3:
        p["H"] = rng.choice(["300", "1000", "2000"])
    return p


def _misses(ball: arb, ref) -> bool:
    return bool(arb(mpmath.nstr(ref + MP_ABS_TOL, MP_DPS)) < ball.lower()
                or arb(mpmath.nstr(ref - MP_ABS_TOL, MP_DPS)) > ball.upper())


def compare(params: dict[str, str], cert, res) -> None:
    q = cert.quantities
    if "theta_star" not in q:
        return
    th = q["theta_star"]
    try:
        thm, x0 = approx_orbit_mpmath(params, float(th.mid()), dps=MP_DPS)
    except Exception as e:      # mpmath.findroot failing is about mpmath, not the ball
        res.float_misses.append((f"mpmath findroot failed ({type(e).__name__})", 0.0))
        return
    res.compared += 1
    if _misses(th, thm):
        res.containment_failures.append(f"theta_star: ball {th.str(25)} misses mpmath {mpmath.nstr(thm, 30)}")
    for name, k in (("beta_dot_0", 1), ("Omega_0", 2), ("i_0", 3), ("I_0", 4)):
        if name in q:
            res.compared += 1
            if _misses(q[name], x0[k]):
                res.containment_failures.append(f"{name}: ball misses mpmath {mpmath.nstr(x0[k], 25)}")
    # genuine: beta(t) > 0 on (0, theta*), sampled on the float flow from the mpmath start
    import numpy as np
    from scipy.linalg import expm
    from .approx import matrices
    _, _, _, aug = matrices(params)
    x = np.array([float(v) for v in x0])
    T = float(thm)
    bad = []
    for j in range(1, BETA_SAMPLES):
        t = T * j / BETA_SAMPLES
        y = expm(aug * t) @ np.append(x, 1.0)
        if y[0] <= 0:
            bad.append(t)
    if bad:
        res.verdict_disagreements.append(f"orbit_genuine {cert.claim('orbit_genuine').status.value} but float "
                                         f"beta(t) <= 0 at t = {bad[0]:.6g} (of {len(bad)} samples)")
    # floats: theta by brentq, the multipliers by numpy
    try:
        from scipy.optimize import brentq
        t0, h = float(th.mid()), 1e-6 * float(th.mid())
        if approx_g(params, t0 - h) * approx_g(params, t0 + h) < 0:
            tf = brentq(lambda s: approx_g(params, s), t0 - h, t0 + h, xtol=1e-16)
            err = abs(tf - t0) / t0
            if err > FLOAT_THETA_TOL:
                res.float_misses.append(("theta_star", err))
            for j, z in enumerate(approx_multipliers(params, tf), start=1):
                m = q.get(f"multiplier_modulus_{j}")
                if m is not None and m.is_finite():
                    mm = float(m.mid())
                    err = abs(abs(z) - mm) / max(mm, 1e-300)
                    if err > FLOAT_MULT_TOL and abs(abs(z) - mm) > 1e-15:
                        res.float_misses.append((f"multiplier_modulus_{j}", err))
        else:
            res.float_misses.append(("theta_star (float g has no sign change)", 1.0))
    except Exception as e:
        res.float_misses.append((f"float path failed ({type(e).__name__})", 1.0))
