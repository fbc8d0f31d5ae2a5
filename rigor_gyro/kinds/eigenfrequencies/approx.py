"""Float (numpy/scipy) and mpmath cross-checks for the eigenfrequency scene. No guarantees.

``approx_roots_numpy`` uses numpy's companion-matrix eigenvalues on float coefficients;
``approx_roots_brentq`` brackets each branch of F with scipy's brentq; ``approx_roots_mpmath``
uses mpmath.polyroots at ``dps`` digits. All take exact strings and build their own coefficients,
independently of the rigorous code (the coefficients are expanded here by hand from (1)).
"""
from __future__ import annotations

from fractions import Fraction

__all__ = ["quartic_coefficients", "approx_roots_numpy", "approx_roots_brentq", "approx_roots_mpmath",
           "bench_float", "bench_mpmath"]


def quartic_coefficients(a, b, eps, W) -> list:
    """Coefficients (highest first) of Q(w) = -w P1(-w) + W P2(-w), expanded by hand.

    Works for any number type supporting + - * (Fraction, float, mpf)."""
    c2 = (a - b) * (b - 1)
    s1 = eps * (a - 1) + b * (a - b)
    s2 = eps * (a - 1) + (a - b)
    # -w P1(-w) = -w (b - (b-1) w)(c2 w^2 - s1 w + eps a)
    # W P2(-w)  =  W (1 - (b-1) w)(c2 w^2 - s2 w + eps)
    # (b - (b-1) w)(c2 w^2 - s1 w + eps a) = -(b-1)c2 w^3 + (b c2 + (b-1) s1) w^2 - (b s1 + (b-1) eps a) w + b eps a
    t3, t2, t1, t0 = -(b - 1) * c2, b * c2 + (b - 1) * s1, -(b * s1 + (b - 1) * eps * a), b * eps * a
    u3, u2, u1, u0 = -(b - 1) * c2, c2 + (b - 1) * s2, -(s2 + (b - 1) * eps), eps
    return [-t3, -t2 + W * u3, -t1 + W * u2, -t0 + W * u1, W * u0]


def _floats(a, b, eps, W):
    return [float(Fraction(x)) for x in (a, b, eps, W)]


def approx_roots_numpy(a: str, b: str, eps: str, W: str) -> list[float]:
    """The real parts of numpy.roots, sorted (float; may be inaccurate for stiff parameters)."""
    import numpy as np
    r = np.roots(quartic_coefficients(*_floats(a, b, eps, W)))
    return sorted(float(x.real) for x in r)


def approx_roots_brentq(a: str, b: str, eps: str, W: str) -> list[float] | None:
    """Each root by scipy.optimize.brentq on its branch of F - W (assumes the paper's nu order);
    None when a branch has no sign change in floats."""
    import numpy as np
    from scipy.optimize import brentq
    af, bf, ef, Wf = _floats(a, b, eps, W)
    c2 = (af - bf) * (bf - 1)
    n1, n4 = sorted(np.roots([c2, -(ef * (af - 1) + af - bf), ef]).real)
    n2, n6 = sorted(np.roots([c2, -(ef * (af - 1) + bf * (af - bf)), ef * af]).real)
    n3, n5 = 1 / (bf - 1), bf / (bf - 1)
    coeffs = quartic_coefficients(af, bf, ef, Wf)
    q = np.poly1d(coeffs)
    out = []
    big = max(4 * n6, n6 + 4 * Wf + 10)
    for lo, hi in ((0.0, n1), (n2, n3), (n4, n5), (n6, big)):
        xa, xb = lo + 1e-300, hi
        fa, fb = q(xa), q(xb)
        if not (np.isfinite(fa) and np.isfinite(fb)) or fa * fb > 0:
            return None
        out.append(brentq(q, xa, xb, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500))
    return out


def approx_roots_mpmath(a: str, b: str, eps: str, W: str, dps: int = 50) -> list:
    """mpmath.polyroots at ``dps`` digits on the exact rational coefficients (no guarantee)."""
    import mpmath
    with mpmath.workdps(dps + 20):
        fr = [mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in (a, b, eps, W)]
        coeffs = quartic_coefficients(*fr)
        r = mpmath.polyroots(coeffs, maxsteps=400, extraprec=4 * dps)
        return sorted((mpmath.re(x) for x in r), key=float)


def _named(roots, params: dict) -> dict:
    out = {f"omega_{j}": r for j, r in enumerate(roots, start=1)}
    if params.get("hz_scale"):
        h = Fraction(params["hz_scale"])
        for j, r in enumerate(roots, start=1):
            out[f"freq_hz_{j}"] = (r ** 0.5 if isinstance(r, float) else _mp_sqrt(r)) * (
                float(h) if isinstance(r, float) else _mp_fraction(h))
    return out


def _mp_sqrt(x):
    import mpmath
    return mpmath.sqrt(x)


def _mp_fraction(f: Fraction):
    import mpmath
    return mpmath.mpf(f.numerator) / f.denominator


def bench_float(params: dict, hint=None) -> dict:
    """What an uncertified float script computes: numpy.roots of the quartic, by certificate name
    (omega_j, freq_hz_j), plus ``found`` (how many real positive roots floats report). No guarantee."""
    a, b, eps, W = (params[k] for k in ("a", "b", "eps", "Omega2"))
    import numpy as np
    r = np.roots(quartic_coefficients(*_floats(a, b, eps, W)))
    real = sorted(float(x.real) for x in r if abs(x.imag) <= 1e-12 * max(abs(x), 1e-300))
    out = _named(sorted(float(x.real) for x in r), params)
    out["found"] = sum(1 for x in real if x > 0)
    return out


def bench_mpmath(params: dict, dps: int = 30, hint=None) -> dict:
    """The same at ``dps`` digits with mpmath.polyroots (non-rigorous). No guarantee."""
    import mpmath
    a, b, eps, W = (params[k] for k in ("a", "b", "eps", "Omega2"))
    with mpmath.workdps(dps):
        return _named(approx_roots_mpmath(a, b, eps, W, dps=dps), params)
