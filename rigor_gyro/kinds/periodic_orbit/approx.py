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
* :func:`approx_orbit_mpmath`: theta* and x0 by mpmath.findroot at ``dps`` digits;
* ``plant_*``: the same cross-checks for a user's relay plant ([plant] scenes): an event-driven simulation,
  g in mpmath, the Jacobian by central differences, the describing-function crossing on a frequency grid.
"""
from __future__ import annotations

from fractions import Fraction

__all__ = ["matrices", "approx_g", "approx_roots_expm_brentq", "approx_x0", "approx_multipliers",
           "approx_relay_simulation", "approx_orbit_mpmath", "bench_float", "bench_mpmath", "plant_as_float",
           "plant_simulate_half", "plant_g_mp", "plant_x0_mp", "plant_jacobian_fd", "plant_describing_function",
           "plant_long_run"]

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

# ------------------------------------------------------------------ the [plant] path (plant_* modules)
# Cross-checks of a user's relay plant (scene [plant]; never a verdict): an event-driven simulation with
# scipy's expm of the augmented matrix, g in mpmath, the half-period map's Jacobian by central differences,
# the describing-function crossing on a dense frequency grid.

def _plant_libs():
    """numpy, mpmath, scipy's expm and brentq, imported when a cross-check runs (as above: lazily)."""
    import mpmath
    import numpy as np
    from scipy.linalg import expm
    from scipy.optimize import brentq
    return np, mpmath, expm, brentq

def plant_as_float(model):
    """(M, e, c, S, h) as numpy float arrays/floats."""
    np, mpmath, expm, brentq = _plant_libs()
    n = model.n
    M = np.array([[float(model.M[i, j]) for j in range(n)] for i in range(n)])
    return M, np.array([float(x) for x in model.e]), np.array([float(x) for x in model.c]), float(model.S), float(model.h)


def _plant_flow(M, e, S, x, t):
    np, mpmath, expm, brentq = _plant_libs()
    n = len(e)
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = M
    A[:n, n] = e * S
    z = expm(A * t) @ np.append(x, 1.0)
    return z[:n]


def plant_simulate_half(model, x0, t_max: float, steps: int = 4000):
    """(t_switch, x(t_switch)): the first time c . x(t) = -h from x0 with u = +S, or (None, None); the
    state stepped by the exact propagator expm(A dt) of the augmented matrix, the crossing by brentq."""
    np, mpmath, expm, brentq = _plant_libs()
    M, e, c, S, h = plant_as_float(model)
    n = len(e)
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = M
    A[:n, n] = e * S
    dt = t_max / steps
    step = expm(A * dt)
    z = np.append(np.asarray(x0, float), 1.0)
    prev_v = c @ z[:n] + h
    for k in range(1, steps + 1):
        z_next = step @ z
        v = c @ z_next[:n] + h
        if v < 0 <= prev_v:
            base = z.copy()
            t0 = (k - 1) * dt
            f = lambda s: c @ (expm(A * s) @ base)[:n] + h      # noqa: E731
            s = brentq(f, 0.0, dt, xtol=1e-15)
            return t0 + s, (expm(A * s) @ base)[:n]
        z, prev_v = z_next, v
    return None, None


def plant_x0_mp(model, theta, dps: int = 40):
    """x0(theta) in mpmath."""
    np, mpmath, expm, brentq = _plant_libs()
    with mpmath.workdps(dps):
        n = model.n
        A = mpmath.zeros(n + 1, n + 1)
        for i in range(n):
            for j in range(n):
                A[i, j] = mpmath.mpf(int(model.M[i, j].p)) / int(model.M[i, j].q)
            A[i, n] = mpmath.mpf(int(model.e[i].p)) / int(model.e[i].q) * mpmath.mpf(int(model.S.p)) / int(model.S.q)
        E = mpmath.expm(A * mpmath.mpf(theta))
        I = mpmath.eye(n)
        Em = mpmath.matrix([[E[i, j] for j in range(n)] for i in range(n)])
        w = mpmath.matrix([E[i, n] for i in range(n)])
        return mpmath.lu_solve(I + Em, -w)


def plant_g_mp(model, theta, dps: int = 40):
    np, mpmath, expm, brentq = _plant_libs()
    x0 = plant_x0_mp(model, theta, dps)
    with mpmath.workdps(dps):
        return sum(mpmath.mpf(int(model.c[i].p)) / int(model.c[i].q) * x0[i] for i in range(model.n)) \
            - mpmath.mpf(int(model.h.p)) / int(model.h.q)


def _plant_section(model):
    np, mpmath, expm, brentq = _plant_libs()
    c = [float(x) for x in model.c]
    j = int(np.argmax(np.abs(c)))
    return j, np.array(c)


def plant_jacobian_fd(model, x0, theta: float, eps: float = 1e-7):
    """The Jacobian of P(x) = -x(tau(x)) on the section c . x = h, in the coordinates x_i, i != j, by
    central differences of :func:`plant_simulate_half`."""
    np, mpmath, expm, brentq = _plant_libs()
    n = model.n
    j, c = _plant_section(model)
    h = float(model.h)
    idx = [i for i in range(n) if i != j]

    def lift(z):
        x = np.zeros(n)
        x[idx] = z
        x[j] = (h - c[idx] @ z) / c[j]
        return x

    def P(z):
        t, x = plant_simulate_half(model, lift(z), theta * 1.5, steps=3000)
        return -x[idx]
    z0 = np.asarray(x0)[idx]
    J = np.zeros((n - 1, n - 1))
    for k in range(n - 1):
        dz = np.zeros(n - 1)
        dz[k] = eps
        J[:, k] = (P(z0 + dz) - P(z0 - dz)) / (2 * eps)
    return J


def plant_long_run(model, x0, half_periods: int, t_max: float, steps: int = 4000):
    """Switch times over many half-periods from x0 (the relay loop simulated; the sign flips each half)."""
    np, mpmath, expm, brentq = _plant_libs()
    x = np.asarray(x0, float)
    times = []
    for _ in range(half_periods):
        t, xe = plant_simulate_half(model, x, t_max, steps)
        if t is None:
            break
        times.append(t)
        x = -xe
    return times


def plant_describing_function(model, w_lo=1e-3, w_hi=1e3, points: int = 20001):
    """Frequencies w > 0 where Im G(i w) changes sign with S Re G(i w) > 0, and the amplitudes."""
    np, mpmath, expm, brentq = _plant_libs()
    M, e, c, S, h = plant_as_float(model)
    n = len(e)
    ws = np.geomspace(w_lo, w_hi, points)
    G = np.array([c @ np.linalg.solve(1j * w * np.eye(n) - M, e) for w in ws])
    out = []
    for k in range(points - 1):
        if np.sign(G[k].imag) != np.sign(G[k + 1].imag) and S * G[k].real > 0:
            w = brentq(lambda v: (c @ np.linalg.solve(1j * v * np.eye(n) - M, e)).imag, ws[k], ws[k + 1])
            g = c @ np.linalg.solve(1j * w * np.eye(n) - M, e)
            out.append((w, 4 * S * g.real / np.pi, 2 * np.pi / w))
    return out
