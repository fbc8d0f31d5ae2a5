"""Float (numpy/scipy) and mpmath cross-checks for the periodic-orbit scene. No guarantees.

Independent of the rigorous code path: the flow here is ``scipy.linalg.expm`` (or ``mpmath.expm``) of the
augmented 6x6 matrix [[M, e S], [0, 0]] (giving exp(M t) and the forced response w(t) together), the
half-period function is the beta component of the solution of (I + exp(M theta)) x0 = -w(theta), and
the relay system itself is integrated by ``solve_ivp`` with an event on beta = 0.

* :func:`approx_roots_expm_brentq`: grid + brentq on g (a grid can miss close pairs of roots: that is
  the point of the rigorous isolation);
* :func:`approx_multipliers`: numpy eigvals of the half-period Jacobian with the switching-time correction;
* :func:`approx_relay_simulation`: the relay system integrated through many switchings; observed
  half-periods and the per-half-cycle contraction of a perturbation;
* :func:`approx_orbit_mpmath`: theta* and x0 by mpmath.findroot at ``dps`` digits.
"""
from __future__ import annotations

from fractions import Fraction

__all__ = ["matrices", "approx_g", "approx_roots_expm_brentq", "approx_x0", "approx_multipliers",
           "approx_relay_simulation", "approx_orbit_mpmath", "bench_float", "bench_mpmath"]

NAMES = ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")


def _vals(params: dict, conv=float):
    return [conv(Fraction(params[k])) for k in NAMES]


def matrices(params: dict):
    """M (5x5), e (5), S and the augmented 6x6 matrix, as numpy float arrays."""
    import numpy as np
    A, B, H, tau, sig, n, K, p, S = _vals(params)
    M = np.array([[0, 1, 0, 0, 0], [0, 0, -H / B, 0, 0], [0, H / A, 0, K / A, 0],
                  [0, 0, -n / (K * tau), -1 / tau, p / tau], [0, 0, 0, 0, -1 / sig]], dtype=float)
    e = np.array([0, 0, 0, 0, 1 / sig])
    aug = np.zeros((6, 6))
    aug[:5, :5] = M
    aug[:5, 5] = e * S
    return M, e, S, aug


def approx_x0(params: dict, theta: float):
    import numpy as np
    from scipy.linalg import expm
    M, e, S, aug = matrices(params)
    E = expm(aug * theta)
    return np.linalg.solve(np.eye(5) + E[:5, :5], -E[:5, 5])


def approx_g(params: dict, theta: float) -> float:
    return float(approx_x0(params, theta)[0])


def approx_roots_expm_brentq(params: dict, T: float, grid: int = 4000, t0: float = 1e-3) -> list[float]:
    """Sign changes of g on a uniform grid of (t0, T], each refined by brentq."""
    import numpy as np
    from scipy.optimize import brentq
    ts = np.linspace(t0, T, grid)
    gs = [approx_g(params, t) for t in ts]
    out = []
    for a, b, ga, gb in zip(ts, ts[1:], gs, gs[1:]):
        if ga == 0:
            out.append(float(a))
        elif ga * gb < 0:
            out.append(brentq(lambda t: approx_g(params, t), a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps))
    return out


def approx_multipliers(params: dict, theta: float):
    """Eigenvalues of -[(I - f e1^T/f_1) exp(M theta)]_{1..4,1..4}, f = M x(theta) + e S, x(theta) = -x0."""
    import numpy as np
    from scipy.linalg import expm
    M, e, S, aug = matrices(params)
    x0 = approx_x0(params, theta)
    Phi = expm(M * theta)
    f = M @ (-x0) + e * S
    Q = (np.eye(5) - np.outer(f, np.eye(5)[0]) / f[0]) @ Phi
    ev = np.linalg.eigvals(-Q[1:, 1:])
    return sorted(ev, key=lambda z: -abs(z))


def approx_relay_simulation(params: dict, x_start, half_cycles: int = 60, rtol: float = 1e-12, atol: float = 1e-15):
    """Integrate x' = M x + e S sign(beta) from x_start (beta = 0, beta' > 0) with an event on beta = 0.

    Uses the symmetry: each half-cycle is integrated with u = +S from the mirrored state. Returns
    (half_periods, section_points), each section point (beta', Omega, i, I) after mirroring."""
    import numpy as np
    from scipy.integrate import solve_ivp
    M, e, S, aug = matrices(params)

    def rhs(t, x):
        return M @ x + e * S

    def ev(t, x):
        return x[0]
    ev.terminal, ev.direction = True, -1
    x = np.array(x_start, dtype=float)
    x[0] = 0.0
    halves, points = [], [x[1:].copy()]
    for _ in range(half_cycles):
        sol = solve_ivp(rhs, (0, 100.0), x, events=ev, rtol=rtol, atol=atol, method="DOP853", first_step=1e-9)
        if not sol.t_events[0].size:
            break
        te, xe = sol.t_events[0][0], sol.y_events[0][0]
        halves.append(float(te))
        x = -xe
        x[0] = 0.0
        points.append(x[1:].copy())
    return halves, points


def approx_orbit_mpmath(params: dict, theta_guess: float, dps: int = 40):
    """(theta*, x0) by mpmath.findroot on g at ``dps`` digits (mpmath.expm of the augmented matrix)."""
    import mpmath as mp
    with mp.workdps(dps + 10):
        A, B, H, tau, sig, n, K, p, S = [mp.mpf(v.numerator) / v.denominator for v in _vals(params, lambda x: x)]
        M = mp.matrix([[0, 1, 0, 0, 0], [0, 0, -H / B, 0, 0], [0, H / A, 0, K / A, 0],
                       [0, 0, -n / (K * tau), -1 / tau, p / tau], [0, 0, 0, 0, -1 / sig]])
        aug = mp.zeros(6, 6)
        for i in range(5):
            for j in range(5):
                aug[i, j] = M[i, j]
        aug[4, 5] = S / sig

        def x0(t):
            E = mp.expm(aug * t)
            Phi = mp.matrix([[E[i, j] for j in range(5)] for i in range(5)])
            w = mp.matrix([E[i, 5] for i in range(5)])
            return mp.lu_solve(mp.eye(5) + Phi, -w)

        th = mp.findroot(lambda t: x0(t)[0], mp.mpf(theta_guess))
        return th, [x0(th)[i] for i in range(5)]


def bench_float(params: dict, hint=None) -> dict:
    """What an uncertified float script computes: the sign changes of g on a 2000-point grid of
    (t0, T] (``hint["t0"]``, ``hint["T"]``: the range the certificate searched; default (1e-3 T, 2 theta]),
    refined by brentq; the root nearest ``hint["theta_star"]`` as theta_star, its x(0) and multiplier
    moduli (numpy eigvals), by certificate name; ``found`` is the number of roots the grid sees.
    No guarantee."""
    hint = hint or {}
    th = hint.get("theta_star", 0.5)
    T = hint.get("T", 2 * th)
    roots = approx_roots_expm_brentq(params, T, grid=2000, t0=hint.get("t0", 1e-3 * T))
    out: dict = {"found": len(roots)}
    if not roots:
        return out
    t = min(roots, key=lambda r: abs(r - th))
    out["theta_star"] = t
    out["period"] = 2 * t
    x0 = approx_x0(params, t)
    for name, k in (("beta_dot_0", 1), ("Omega_0", 2), ("i_0", 3), ("I_0", 4)):
        out[name] = float(x0[k])
    for j, z in enumerate(approx_multipliers(params, t), start=1):
        out[f"multiplier_modulus_{j}"] = float(abs(z))
    return out


def bench_mpmath(params: dict, dps: int = 30, hint=None) -> dict:
    """theta_star and x(0) by mpmath.findroot at ``dps`` digits from ``hint["theta_star"]`` (non-rigorous)."""
    import mpmath as mp
    hint = hint or {}
    th, x0 = approx_orbit_mpmath(params, hint.get("theta_star", 0.5), dps=dps)
    with mp.workdps(dps + 10):
        out = {"theta_star": th, "period": 2 * th}
    for name, k in (("beta_dot_0", 1), ("Omega_0", 2), ("i_0", 3), ("I_0", 4)):
        out[name] = x0[k]
    return out
