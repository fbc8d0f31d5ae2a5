"""The symmetric periodic orbit of a relay plant x' = M x + e u, u = S sign(c . x) (hysteresis h), in Arb.

The symmetric orbit. With u = +S on (0, theta) and x(theta) = -x(0) (the second half mirrors the first),
(I + exp(M theta)) x0 = -int_0^theta exp(M s) ds e S, i.e. x0(theta) = -S phi_theta(M) e with
phi_theta(z) = tanh(z theta / 2) / z (theta/2 at z = 0): a matrix function defined for every M whose
eigenvalues lambda have no lambda theta in i pi (2Z + 1), in particular for real theta > 0 when no
eigenvalue is on the imaginary axis (the model checks this exactly). The orbit closes when the relay
switches at theta: the half-period condition

    g(theta) = c . x0(theta) - h = 0.

Spectral form (simple eigenvalues, checked exactly by the model): f(M) e = sum_k f(lambda_k) R_k e with
R_k e = N(lambda_k) / p'(lambda_k) (residues of (z I - M)^-1 e; N the exact numerator polynomials), so

    g(theta) = -S sum_k r_k tanh(lambda_k theta / 2) / lambda_k - S r_0 theta / 2 - h,    r_k = N_c(lambda_k) / p'(lambda_k),

r_0 the residue at a simple zero eigenvalue (exact rational; absent without an integrator). A conjugate pair
is one term with weight 2 (2 Re). Each term is written with E = exp(lambda theta) (Re lambda < 0) or
E = exp(-lambda theta) (Re lambda > 0), |E| < 1, tanh = sigma (1 - E)/(1 + E), sigma = sign Re lambda:
no overflow for unstable modes. The root search isolates the pole-free G = g K, K = prod over the pairs
|1 + E|^2 > 0 on real theta > 0 (the same roots; tanh's complex poles near the real axis of a lightly
damped mode removed), as the Roitenberg path does.

On the orbit, y(t) = c . x(t) = S sum_k r_k (2 e^(lambda t) / (1 + e^(lambda theta)) - 1) / lambda_k
+ S r_0 (t - theta / 2), a sum of exponentials (:class:`~.flow.ExpSum`).

Near 0 (:func:`near_zero_bound`): g(theta) = -S sum_j c_j m_(2j) theta^(2j+1) - h with the exact Markov
parameters m_k = c M^k e and tanh(z/2)/z = sum_j c_j z^(2j), |c_j| <= (2 pi^2/3) / pi^(2j+2); with
L = |M|_inf (exact), |m_k| <= |c|_1 |e|_inf L^k. So the sign of g on (0, rho] is certified from exact
numbers and a geometric tail. Tail (:func:`tail_bound`): g(theta) = a theta + b + R(theta) with
a = -S r_0 / 2, b = -S sum_k w_k Re(sigma_k r_k / lambda_k) - h and |R| <= sum_k 2 w_k |S r_k / lambda_k|
q_k / (1 - q_k), q_k = exp(-|Re lambda_k| T), for every theta >= T.

Guarantee: every function returns balls containing the exact value at every point of the input balls, at
the current working precision. Fails when: the roots of p are not isolated, or a real part not separated
from 0, at this precision: :class:`~.flow.DegenerateSpectrum` (the claims are then inconclusive).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from flint import acb, acb_poly, acb_series, arb, arb_mat, fmpq, fmpq_poly

from ...core.balls import (ball, certainly_lt, certainly_negative, certainly_positive, interval, series_coefficients,
                           series_length)
from ...core.subdivision import enclose_max
from ...core.polyroots import isolate_polynomial
from .flow import DegenerateSpectrum, ExpSum, taylor_enclosure
from .plant_model import PlantModel, markov
from .plant_statements import AMPLITUDE_REL, TAYLOR_ORDER

__all__ = ["PlantMode", "PlantSpectrum", "g_coeffs", "x0_at", "orbit_output", "tail_bound", "near_zero_bound",
           "near_zero_order", "jacobian", "liouville_product", "matrix_ball", "amplitude", "section_index",
           "neutral_multiplier",
           "leading_coefficient"]


@dataclass
class PlantMode:
    """One nonzero eigenvalue (a pair's representative has weight 2: take 2 Re)."""

    lam: acb
    weight: int
    sigma: int            # sign of Re lambda
    rc: acb               # N_c(lambda) / p'(lambda)
    rx: list              # N_i(lambda) / p'(lambda), i < n


def matrix_ball(Q) -> arb_mat:
    """An exact rational matrix (fmpq_mat) as a ball matrix."""
    return arb_mat([[ball(Q[i, j]) for j in range(Q.ncols())] for i in range(Q.nrows())])


class PlantSpectrum:
    """Eigenvalues (roots of the exact characteristic polynomial) and residues at the current precision."""

    def __init__(self, model: PlantModel):
        self.model = model
        p = model.charpoly
        n = model.n
        dp = p.derivative()
        q = fmpq_poly([p[k] for k in range(1, n + 1)]) if model.zero_eigenvalue else p
        roots = isolate_polynomial(q)
        if not roots.squarefree:
            raise DegenerateSpectrum("a repeated eigenvalue")
        if not roots.verified:
            raise DegenerateSpectrum(f"eigenvalues not isolated at this precision: {roots.reason}")
        upper = [z for z in roots.nonreal if certainly_positive(z.imag)]
        if 2 * len(upper) != len(roots.nonreal):
            raise DegenerateSpectrum("non-real eigenvalues not paired at this precision")
        Ns = [acb_poly([acb(ball(N[k])) for k in range(N.degree() + 1)]) if N.degree() >= 0 else acb_poly([])
              for N in model.numerators]
        Nc = model.numerator_c
        Ncb = acb_poly([acb(ball(Nc[k])) for k in range(Nc.degree() + 1)]) if Nc.degree() >= 0 else acb_poly([])
        dpb = acb_poly([acb(ball(dp[k])) for k in range(dp.degree() + 1)])
        self.modes: list[PlantMode] = []
        for lam, w in [(acb(x), 1) for x in roots.real] + [(z, 2) for z in upper]:
            re = lam.real
            if certainly_negative(re):
                sg = -1
            elif certainly_positive(re):
                sg = 1
            else:
                raise DegenerateSpectrum("the real part of an eigenvalue is not separated from 0 at this precision")
            d = dpb(lam)
            self.modes.append(PlantMode(lam, w, sg, Ncb(lam) / d, [N(lam) / d for N in Ns]))
        S = ball(model.S)
        self.S = S
        self.h = ball(model.h)
        if model.zero_eigenvalue:
            d0 = dp[0]
            self.r0c = ball(Nc[0] / d0) if Nc.degree() >= 0 else arb(0)
            self.r0x = [ball(N[0] / d0) if N.degree() >= 0 else arb(0) for N in model.numerators]
        else:
            self.r0c = arb(0)
            self.r0x = [arb(0)] * n
        self.M = matrix_ball(model.M)
        self.e = [ball(x) for x in model.e]
        self.c = [ball(x) for x in model.c]

    @property
    def a(self) -> arb:
        """Slope of g at infinity."""
        return -self.S * self.r0c / 2

    @property
    def b(self) -> arb:
        """Offset of g at infinity."""
        out = -self.h
        for m in self.modes:
            out -= self.S * m.weight * (m.sigma * m.rc / m.lam).real
        return out

    def eigenvalues(self) -> list[acb]:
        out = [acb(0)] if self.model.zero_eigenvalue else []
        for m in self.modes:
            out.append(m.lam)
            if m.weight == 2:
                out.append(m.lam.conjugate())
        return out


def _E(m: PlantMode, s):
    """exp(lambda s) for Re lambda < 0, exp(-lambda s) for Re lambda > 0 (|E| < 1 on real s > 0)."""
    return (m.lam * s).exp() if m.sigma < 0 else (-m.lam * s).exp()


def _Ec(m: PlantMode, s):
    return (m.lam.conjugate() * s).exp() if m.sigma < 0 else (-m.lam.conjugate() * s).exp()


def g_coeffs(sp: PlantSpectrum, center: arb, n: int, pole_free: bool = True) -> list[arb]:
    """Taylor coefficients (j < n) at every point of the ball ``center`` of g, or (``pole_free``) of
    G = g K, K = prod over the conjugate pairs |1 + E|^2 (module docstring). Series kept to n terms
    (``series_length``); a non-finite enclosure (1 + E not separated from 0 on a wide complex ball) is
    returned as NaN balls (no information, never a verdict)."""
    pairs = [m for m in sp.modes if m.weight == 2] if pole_free else []
    with series_length(n):
        s = acb_series([acb(center), 1], prec=n)
        one = acb_series([1], prec=n)
        E = {id(m): _E(m, s) for m in sp.modes}
        Ec = {id(m): _Ec(m, s) for m in pairs}
        K = one
        for m in pairs:
            K = K * (1 + E[id(m)]) * (1 + Ec[id(m)])
        try:
            total = (s * (sp.r0c * sp.S / 2) + sp.h) * K
            for m in sp.modes:
                Ek = E[id(m)]
                if m.weight == 2 and pole_free:
                    term = (1 - Ek) * (1 + Ec[id(m)])
                    for o in pairs:
                        if o is not m:
                            term = term * (1 + E[id(o)]) * (1 + Ec[id(o)])
                else:
                    term = (1 - Ek) / (1 + Ek) * K
                total += term * (m.weight * m.sigma * sp.S * m.rc / m.lam)
            c = series_coefficients(total, n)
        except ValueError:
            return [arb("nan")] * n
    return [-x.real for x in c]


def x0_at(sp: PlantSpectrum, theta: arb) -> list[arb]:
    """x0(theta) = -S phi_theta(M) e, every component, at every point of the ball theta."""
    t = acb(theta)
    out = [-sp.S * r * theta / 2 for r in sp.r0x]
    for m in sp.modes:
        Ek = _E(m, t)
        th = m.sigma * (1 - Ek) / ((1 + Ek) * m.lam)
        for i, r in enumerate(m.rx):
            out[i] -= m.weight * sp.S * (th * r).real
    return out


def orbit_output(sp: PlantSpectrum, theta: arb) -> ExpSum:
    """y(t) = c . x(t) on the half-period (0, theta) of the symmetric orbit of half-period theta (module
    docstring) as a sum of exponentials, for every theta in the ball."""
    terms = []
    c0 = -sp.S * sp.r0c * theta / 2
    t = acb(theta)
    for m in sp.modes:
        if m.sigma < 0:
            alpha = 2 * sp.S * m.rc / ((1 + (m.lam * t).exp()) * m.lam)
        else:                                  # 2 / (1 + e^(lam theta)) = 2 F / (1 + F), F = e^(-lam theta)
            F = (-m.lam * t).exp()
            alpha = 2 * sp.S * m.rc * F / ((1 + F) * m.lam)
        terms.append((alpha, m.lam, m.weight))
        c0 -= m.weight * sp.S * (m.rc / m.lam).real
    return ExpSum(terms, c0, sp.S * sp.r0c)


def tail_bound(sp: PlantSpectrum, T: arb) -> tuple[arb, arb]:
    """(lower, upper): balls whose lower end / upper end bound g(theta) from below / above for every
    theta >= T > 0: a theta + b -+ B(T) at theta = T, a valid bound beyond T when a >= 0 (lower) or
    a <= 0 (upper), since a theta + b is monotone (see the module docstring)."""
    B = arb(0)
    for m in sp.modes:
        q = (-abs(m.lam.real) * T).exp()
        B += 2 * m.weight * abs(sp.S * m.rc / m.lam) * q / (1 - q)
    base = sp.a * T + sp.b
    return base - B, base + B


def near_zero_order(model: PlantModel) -> tuple[int, fmpq]:
    """(j0, lead): the first j with m_(2j) = c M^(2j) e != 0, and the exact leading coefficient
    lead = -S c_j0 m_(2j0) of g + h = lead theta^(2 j0 + 1) + ... (c_j of tanh(z/2)/z)."""
    m = markov(model.M, model.e, model.c, 2 * model.n)
    j0 = next(j for j in range(model.n) if m[2 * j] != 0)
    n2 = 2 * j0 + 2
    cj = 2 * (fmpq(4) ** (j0 + 1) - 1) * fmpq.bernoulli(n2) / fmpq(_factorial(n2))
    return j0, -model.S * cj * m[2 * j0]


def _factorial(k: int) -> int:
    out = 1
    for i in range(2, k + 1):
        out *= i
    return out


def balancing(model: PlantModel, sweeps: int = 20) -> list[int]:
    """Exponents k_i of a diagonal similarity D = diag(2^k_i) that reduces |D^-1 M D|_inf (Osborne's
    balancing, powers of two; floats choose, nothing is assumed of the choice: any D gives a valid bound).
    Entries or scalings beyond the double range (an overflow, a NaN): no balancing (D = I, also valid)."""
    try:
        return _balancing(model, sweeps)
    except (OverflowError, ValueError, ZeroDivisionError):
        return [0] * model.n


def _balancing(model: PlantModel, sweeps: int) -> list[int]:
    n = model.n
    A = [[abs(float(model.M[i, j])) for j in range(n)] for i in range(n)]
    k = [0] * n
    for _ in range(sweeps):
        changed = False
        for i in range(n):
            r = sum(A[i][j] * 2.0 ** (k[j] - k[i]) for j in range(n) if j != i)
            c = sum(A[j][i] * 2.0 ** (k[i] - k[j]) for j in range(n) if j != i)
            if r == 0 or c == 0:
                continue
            step = int(round(0.5 * math.log2(r / c)))
            if step:
                k[i] += step
                changed = True
        if not changed:
            break
    return k


def _norms(model: PlantModel) -> tuple[fmpq, fmpq]:
    """(L, C) with |c M^k e| <= C L^k for every k, exactly: L = |D^-1 M D|_inf (max row sum) and
    C = |c D|_1 |D^-1 e|_inf for the balancing D of :func:`balancing` (c M^k e = (c D)(D^-1 M D)^k (D^-1 e))."""
    n = model.n
    d = [fmpq(2) ** x if x >= 0 else 1 / fmpq(2) ** (-x) for x in balancing(model)]
    L = max(sum((abs(model.M[i, j]) * d[j] / d[i] for j in range(n)), fmpq(0)) for i in range(n))
    C = sum((abs(model.c[i]) * d[i] for i in range(n)), fmpq(0)) * max(abs(model.e[i]) / d[i] for i in range(n))
    return L, C


def near_zero_bound(model: PlantModel, rho: arb) -> bool:
    """Certainly no root of g on (0, rho] (rho > 0 exact): with h > 0, |c . x0(theta)| <= |S| C theta
    (1/2 + (2/3) q / (1 - q)) < h; with h = 0, |lead| > |S| C (2/3) (L/pi)^(2 j0) q / (1 - q), so
    g = theta^(2 j0 + 1) (lead + tail) keeps lead's sign. q = (L rho / pi)^2 < 1 (module docstring)."""
    L, C = _norms(model)
    pi = arb.pi()
    q = (ball(L) * rho / pi) ** 2
    if not certainly_positive(1 - q):
        return False
    geo = q / (1 - q)
    S = abs(ball(model.S))
    if model.h > 0:
        return certainly_positive(ball(model.h) - S * ball(C) * rho * (arb(1) / 2 + arb(2) / 3 * geo))
    j0, lead = near_zero_order(model)
    return certainly_positive(abs(ball(lead)) - S * ball(C) * arb(2) / 3 * (ball(L) / pi) ** (2 * j0) * geo)


def leading_coefficient(coeffs, k: int, t: arb, extra: int = 6) -> arb:
    """A ball containing f^(k)(xi)/k! for every xi in [0, t] (a Taylor model about the midpoint: point
    coefficients of orders k .. k+extra-1 and the next one enclosed over [0, t], intersected with the
    direct enclosure), for ``coeffs(center, n)`` -> Taylor coefficients of f at every point of a ball.
    When f^(j)(0) = 0 exactly for j < k (g + h's odd series below its first nonzero term, h = 0),
    f(theta) = theta^k f^(k)(xi)/k! for some xi in (0, theta): a ball of one strict sign means no root of f
    on (0, t]."""
    X = interval(arb(0), t)
    m = arb(X.mid())
    w = X - m
    order = k + extra
    c = coeffs(m, order)
    cN = coeffs(X, order + 1)[order]
    tot = arb(0)
    for j in range(k, order):
        tot += math.comb(j, k) * c[j] * _ipow(w, j - k)
    tot += math.comb(order, k) * cN * _ipow(w, order - k)
    direct = coeffs(X, k + 1)[k]
    if not (direct.is_finite() and tot.is_finite()):
        return tot if tot.is_finite() else direct
    return tot.intersection(direct) if tot.overlaps(direct) else tot


def _ipow(x: arb, k: int) -> arb:
    out = arb(1)
    for _ in range(k):
        out *= x
    return out


def liouville_product(sp: PlantSpectrum, theta: arb, x0: list[arb]) -> arb:
    """The product of the n - 1 multipliers: (-1)^(n-1) exp(tr M theta) (c . f0) / (c . f1), with
    f0 = M x0 + e S, f1 = -M x0 + e S the vector field at the start and at the end of the half-period
    (the Poincare map's Jacobian determinant between sections; the symmetry contributes (-1)^(n-1))."""
    n = sp.model.n
    tr = sum((sp.M[i, i] for i in range(n)), arb(0))
    Mx = [sum((sp.M[i, j] * x0[j] for j in range(n)), arb(0)) for i in range(n)]
    cf0 = sum((sp.c[i] * (Mx[i] + sp.e[i] * sp.S) for i in range(n)), arb(0))
    cf1 = sum((sp.c[i] * (-Mx[i] + sp.e[i] * sp.S) for i in range(n)), arb(0))
    return (-1) ** (n - 1) * (tr * theta).exp() * cf0 / cf1


def neutral_multiplier(model: PlantModel) -> bool:
    """True when every symmetric orbit has the multiplier -1 exactly (decided in exact rationals): M has the
    zero eigenvalue and N_c(0) = 0, i.e. the zero mode is uncontrollable (w M = 0, w e = 0) or unobservable
    (M v = 0, c v = 0), since r_0 = N_c(0)/p'(0) = (c v)(w e)/(w v). Then w . x is conserved by the flow and
    w f1 = 0 (w x0 = -S phi(0) w e = 0), so w P = -w for the half-period map P of :func:`jacobian` (the
    symmetry flips the sign): -1 is an eigenvalue of P, whose image lies in the section (c P = 0), hence
    a multiplier; likewise P v = -v in the unobservable case. A modulus exactly 1: no precision decides
    "every modulus < 1" (nor > 1 from it)."""
    Nc = model.numerator_c
    return model.zero_eigenvalue and (Nc.degree() < 0 or Nc[0] == 0)


def section_index(model: PlantModel) -> int:
    """The coordinate eliminated on the section c . x = h: the largest |c_j| (the first such)."""
    best = max(abs(x) for x in model.c)
    return next(j for j, x in enumerate(model.c) if abs(x) == best)


def jacobian(M: arb_mat, e: list[arb], c: list[arb], S: arb, theta: arb, x0: list[arb], j: int) -> arb_mat:
    """The (n-1)x(n-1) Jacobian of the half-period map on the section c . x = const, composed with the
    symmetry x -> -x, in the coordinates x_i, i != j: -(I - f1 c^T / (c . f1)) exp(M theta) (switching-time
    correction, f1 = -M x0 + e S the field at the switching), with x_j eliminated through c. Its eigenvalues
    are the orbit's multipliers. ``exp`` is Arb's matrix exponential of the ball matrix M theta."""
    n = len(e)
    E = (M * theta).exp()
    f1 = [-sum((M[i, k] * x0[k] for k in range(n)), arb(0)) + e[i] * S for i in range(n)]
    cf1 = sum((c[i] * f1[i] for i in range(n)), arb(0))
    cE = [sum((c[i] * E[i, k] for i in range(n)), arb(0)) for k in range(n)]
    P = arb_mat(n, n)
    for i in range(n):
        for k in range(n):
            P[i, k] = -(E[i, k] - f1[i] * cE[k] / cf1)
    idx = [i for i in range(n) if i != j]
    K = arb_mat(n - 1, n - 1)
    for a, i in enumerate(idx):
        for b, k in enumerate(idx):
            K[a, b] = P[i, k] - P[i, j] * c[k] / c[j]
    return K


def amplitude(sp: PlantSpectrum, theta: arb, rel=AMPLITUDE_REL, pad: bool = True) -> tuple[arb, arb]:
    """(A, t*): a ball containing the amplitude max over the period of |c . x(t)| of the orbit of half-period
    theta (= max of y on [0, theta*]: y >= -h there and y(0) = h, and the other half is -y), by branch and
    bound (:func:`~rigor_gyro.core.subdivision.enclose_max`) to relative width about ``rel``, widened by
    ``rel`` |A| on each side when ``pad`` (so that a checker's tighter enclosure lies inside it); t* is a point
    of (0, theta*) where y was evaluated for the lower end."""
    y = orbit_output(sp, theta)
    f = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (0,))[0]     # noqa: E731
    tol = ball(fmpq(rel.numerator, rel.denominator))
    ext = enclose_max(f, arb(0), theta.upper(), abs_tol=0, rel_tol=tol, max_pieces=20000)
    up = ext.ball.upper()
    t = ext.argpoint
    low = f(t).lower() if certainly_lt(t, theta.lower()) else sp.h
    if pad:
        w = (tol * abs(up)).upper()
        low, up = (low - w).lower(), (up + w).upper()
    return interval(low, up), t
