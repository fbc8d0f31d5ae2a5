"""The exact flow of the relay stabiliser (Roitenberg 1947) between switchings, in Arb balls.

Model. State x = (beta, beta', Omega, i, I); between switchings x' = M x + e u with u = +-S and

    M = [[0, 1, 0, 0, 0], [0, 0, -H/B, 0, 0], [0, H/A, 0, K/A, 0],
         [0, 0, -n/(K tau), -1/tau, p/tau], [0, 0, 0, 0, -1/sigma]],   e = (0, 0, 0, 0, 1/sigma),

i.e. the paper's system (2) with n = K n1. Its characteristic polynomial is z (z + 1/sigma) C(z) with
the paper's cubic (4) C(z) = z^3 + z^2/tau + (q^2 + n/(tau A)) z + q^2/tau, q^2 = H^2/(A B).

Spectral form. When the five eigenvalues are simple (checked exactly: C squarefree, C(0) != 0,
C(-1/sigma) != 0), exp(M t) = sum_k e^{lambda_k t} P_k with rank-one projectors P_k = r_k l_k^T /
(l_k^T r_k) written from explicit right/left eigenvectors. Everything below is a finite sum of
exponentials in t with ball coefficients, so it can be evaluated on a *time interval* (a ball t) and
expanded in Taylor series (``acb_series``), which is what interval Newton and the sign condition need.
The symmetric orbit: with u = +S on (0, theta) and x(theta) = -x(0),
(I + exp(M theta)) x0 = -w(theta), i.e. x0(theta) = -tanh(M theta / 2) M^{-1} e S, a matrix function
that is analytic at z = 0 (value theta/2). Its beta component is the half-period function

    g(theta) = beta0(theta) = -S sum_k rho_k tanh(lambda_k theta / 2) / lambda_k   (theta/2 for lambda = 0),

rho_k = e1^T P_k e (residues of beta(z)/u(z) = -kappa / (z C(z) (sigma z + 1)), kappa = H K p/(A B tau)).
The paper's determinant g(x) of (12) equals beta0(x) times a factor that does not vanish near its root
(see :mod:`rigor_gyro.kinds.periodic_orbit.paper`), so both have the same roots there.

Guarantee: every function returns balls (or ball vectors/matrices) containing the exact value for
every point of the input balls, at the current working precision; the eigenvalue balls come from
:func:`rigor_gyro.core.polyroots.isolate_polynomial` (exact squarefreeness, certified isolation).

Precision: the caller's (set with :func:`rigor_gyro.core.balls.working_precision` / the prover).
Stiff cases (tau -> 0: an eigenvalue near -1/tau) lose about log2(1/tau^3) bits in the projectors;
escalation recovers them.

Fails when: an eigenvalue is repeated (measure-zero parameter sets) or the cubic's roots cannot be
isolated at this precision: :class:`DegenerateSpectrum` with the reason (the kind reports the claims
inconclusive).

Example:
    >>> from rigor_gyro.core.balls import working_precision
    >>> from flint import fmpq
    >>> P = RelayParams.from_strings(A="125", B="2/15", H="100", tau="0.01", sigma="0.13125", n="50",
    ...                              K="7.5", p="40", S="0.15")
    >>> with working_precision(128):
    ...     sp = Spectrum(P)
    ...     c = g_coeffs(sp, arb("0.1382674296573154568759301070"), 2)
    >>> abs(c[0]) < arb("1e-20"), c[1] > 0      # g vanishes at theta*, increasing
    (True, True)

Reference: Roitenberg Ya. N. (1947), Avtokolebaniya giroskopicheskikh stabilizatorov, PMM 11 (seed 001).
"""
from __future__ import annotations

from dataclasses import dataclass
from math import comb, factorial
from typing import Callable, Sequence

from flint import acb, acb_mat, acb_series, arb, arb_mat, arb_poly, fmpq, fmpq_mat, fmpq_poly

from ...core.balls import ball, certainly_positive, series_coefficients, series_length
from ...core.exact import parse_exact
from ...core.polyroots import isolate_polynomial
from .nutation_form import fast_form

__all__ = ["PARAMETER_NAMES", "RelayParams", "DegenerateSpectrum", "Mode", "Spectrum", "envelope_margin", "system_matrix",
           "forcing", "nutation_cubic", "g_coeffs", "pole_free_coeffs", "x0_at", "ExpSum", "orbit_expsums", "state_at",
           "phi_at", "vector_field", "half_period_jacobian", "taylor_enclosure", "tail_bound",
           "taylor5_leading_coefficient", "moment_zero_orders", "AMPLITUDE_PARAMETERS", "amplitude_similarity"]

PARAMETER_NAMES = ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")


class DegenerateSpectrum(ArithmeticError):
    """The closed form needs five simple eigenvalues; this says which condition failed. ``exact``: the
    condition was decided in exact rational arithmetic (a repeated eigenvalue of the exact parameters), so no
    precision can lift it; otherwise it may be a ball too wide at this precision."""

    def __init__(self, message: str, exact: bool = False):
        super().__init__(message)
        self.exact = exact


@dataclass(frozen=True)
class RelayParams:
    """The nine exact rational parameters of system (2)."""

    A: fmpq
    B: fmpq
    H: fmpq
    tau: fmpq
    sigma: fmpq
    n: fmpq
    K: fmpq
    p: fmpq
    S: fmpq

    @classmethod
    def from_strings(cls, **kw: str) -> "RelayParams":
        return cls(**{k: parse_exact(kw[k], k).fmpq() for k in PARAMETER_NAMES})

    def replace(self, **kw: str) -> "RelayParams":
        d = {k: getattr(self, k) for k in PARAMETER_NAMES}
        d.update({k: parse_exact(v, k).fmpq() for k, v in kw.items()})
        return RelayParams(**d)

    @property
    def q2(self) -> fmpq:
        return self.H * self.H / (self.A * self.B)

    @property
    def kappa(self) -> fmpq:
        return self.H * self.K * self.p / (self.A * self.B * self.tau)


def system_matrix(P: RelayParams) -> fmpq_mat:
    """M of x' = M x + e u, exactly."""
    z = fmpq(0)
    return fmpq_mat([[z, 1, z, z, z],
                     [z, z, -P.H / P.B, z, z],
                     [z, P.H / P.A, z, P.K / P.A, z],
                     [z, z, -P.n / (P.K * P.tau), -1 / P.tau, P.p / P.tau],
                     [z, z, z, z, -1 / P.sigma]])


def forcing(P: RelayParams) -> list[fmpq]:
    """e of x' = M x + e u (u = S sign beta), exactly."""
    return [fmpq(0), fmpq(0), fmpq(0), fmpq(0), 1 / P.sigma]


#: the parameters that enter the orbit only through its amplitude K p S (see :func:`amplitude_similarity`)
AMPLITUDE_PARAMETERS = ("S", "p", "K")


def amplitude_similarity(P: RelayParams) -> bool:
    """Exactly (rationals): the gains p and K enter only the amplitude of the orbit.

    With D = diag(1, 1, 1, 1/K, 1/(p K)) and y = D^-1 x, the system x' = M x + e S sign(beta) becomes
    y' = M_1 y + e (K p S) sign(beta), where M_1 is M at p = K = 1: checked here as
    D^-1 M(P) D = M(P at p = K = 1) and D^-1 e = K p e. The first three components (beta, beta', Omega,
    which carry g, the switching and the sign condition) are the same in x and y, so
    x(t; p, K, S) has the half-period roots, the sign condition and (the Jacobians being similar) the
    multipliers of the orbit with p = K = 1 and amplitude K p S, and those do not depend on the
    amplitude (homogeneity in S). True for every valid P; a False would mean the model changed."""
    D = fmpq_mat(5, 5, [fmpq(1) if i == j and i < 3 else fmpq(0) for i in range(5) for j in range(5)])
    D[3, 3], D[4, 4] = 1 / P.K, 1 / (P.p * P.K)
    Dinv = fmpq_mat(5, 5, [fmpq(1) if i == j and i < 3 else fmpq(0) for i in range(5) for j in range(5)])
    Dinv[3, 3], Dinv[4, 4] = P.K, P.p * P.K
    one = RelayParams(**{k: (fmpq(1) if k in ("p", "K") else getattr(P, k)) for k in PARAMETER_NAMES})
    e, e1 = forcing(P), forcing(one)
    De = [sum((Dinv[i, j] * e[j] for j in range(5)), fmpq(0)) for i in range(5)]
    return Dinv * system_matrix(P) * D == system_matrix(one) and De == [P.K * P.p * x for x in e1]


def nutation_cubic(P: RelayParams) -> fmpq_poly:
    """The paper's cubic (4): z^3 + z^2/tau + (q^2 + n/(tau A)) z + q^2/tau (ascending coefficients)."""
    return fmpq_poly([P.q2 / P.tau, P.q2 + P.n / (P.tau * P.A), 1 / P.tau, 1])


def moment_zero_orders(P: RelayParams) -> list[fmpq]:
    """e1^T M^j e for j = 0..4, exactly. j = 0..3 vanish: g is odd with g = O(theta^5) at 0."""
    M = system_matrix(P)
    v = fmpq_mat([[x] for x in forcing(P)])
    out = []
    for _ in range(5):
        out.append(v[0, 0])
        v = M * v
    return out


@dataclass
class Mode:
    """One nonzero eigenvalue (a representative of a conjugate pair has weight 2: take 2 Re)."""

    lam: acb
    weight: int
    proj: acb_mat          # P_k (5x5)
    pe: list[acb]          # P_k e S
    label: str


class Spectrum:
    """Eigenvalues and spectral projectors of M at the current precision (see module docstring)."""

    def __init__(self, P: RelayParams):
        self.P = P
        C = nutation_cubic(P)
        nu = -1 / P.sigma
        if C(nu) == 0:
            raise DegenerateSpectrum("-1/sigma is also a root of the cubic (4): a repeated eigenvalue", exact=True)
        roots = isolate_polynomial(C)
        if not roots.squarefree:
            raise DegenerateSpectrum(f"the cubic (4) has a repeated root ({roots.reason})", exact=True)
        if not roots.verified:
            raise DegenerateSpectrum(f"roots of the cubic (4) not isolated at this precision: {roots.reason}")
        S = ball(P.S)
        modes: list[Mode] = []
        for lam in roots.real:
            modes.append(self._cubic_mode(acb(lam), 1, "real root of (4)"))
        upper = [z for z in roots.nonreal if certainly_positive(z.imag)]
        if len(upper) * 2 != len(roots.nonreal):
            raise DegenerateSpectrum("non-real roots of (4) not paired at this precision")
        for lam in upper:
            modes.append(self._cubic_mode(lam, 2, "complex pair of (4)"))
        modes.append(self._sigma_mode(nu))
        self.modes = modes
        # lambda = 0: P0 = e1 l0^T, exact
        l0 = [fmpq(1), P.B * P.n / (P.H * P.H), -P.A / P.H, -P.tau * P.K / P.H, -P.sigma * P.p * P.K / P.H]
        self.P0 = arb_mat([[ball(x) for x in l0]] + [[arb(0)] * 5 for _ in range(4)])
        self.p0e = [ball(l0[4] / P.sigma) * S if r == 0 else arb(0) for r in range(5)]
        self.e = [ball(x) for x in forcing(P)]
        self.M = arb_mat([[ball(system_matrix(P)[i, j]) for j in range(5)] for i in range(5)])

    def _cubic_mode(self, lam: acb, weight: int, label: str) -> Mode:
        P = self.P
        A, B, H, K, p, tau, sigma = (ball(x) for x in (P.A, P.B, P.H, P.K, P.p, P.tau, P.sigma))
        r = [acb(1), lam, -(B / H) * lam ** 2, (-(A * B / H) * lam ** 3 - H * lam) / K, acb(0)]
        a = lam + 1 / tau
        l = [acb(0), (H / A) / lam, acb(1), (K / A) / a, (p / tau) * (K / A) / (a * (lam + 1 / sigma))]
        return self._mode(lam, weight, r, l, label)

    def _sigma_mode(self, nu: fmpq) -> Mode:
        P = self.P
        rho2 = -(P.B / P.H) * nu * nu
        rho3 = (-(P.A * P.B / P.H) * nu ** 3 - P.H * nu) / P.K
        den = (P.n / (P.K * P.tau)) * rho2 + (nu + 1 / P.tau) * rho3
        if den == 0:
            raise DegenerateSpectrum("the -1/sigma eigenvector is degenerate")
        r0 = (P.p / P.tau) / den
        r = [acb(ball(x)) for x in (r0, r0 * nu, r0 * rho2, r0 * rho3, fmpq(1))]
        l = [acb(0)] * 4 + [acb(1)]
        return self._mode(acb(ball(nu)), 1, r, l, "-1/sigma (current I)")

    def _mode(self, lam: acb, weight: int, r: list[acb], l: list[acb], label: str) -> Mode:
        d = sum((l[i] * r[i] for i in range(5)), acb(0))
        proj = acb_mat([[r[i] * l[j] / d for j in range(5)] for i in range(5)])
        S = ball(self.P.S)
        pe = [proj[i, 4] * ball(1 / self.P.sigma) * S for i in range(5)]
        return Mode(lam, weight, proj, pe, label)

    def jacobian(self, theta: arb, x0: Sequence[arb]) -> arb_mat:
        """The half-period Jacobian at the switching time ``theta`` from ``x0``
        (:func:`half_period_jacobian`; a box spectrum overrides this with a tighter enclosure)."""
        return half_period_jacobian(self, theta, x0)

    def multipliers(self, J: arb_mat, theta: arb) -> list[acb]:
        """Enclosures of the eigenvalues of the ball matrix J, the Jacobian at ``theta`` (Rump's method,
        valid for every matrix in the ball; ValueError if they are not isolated). A box spectrum
        overrides this with a tighter enclosure."""
        return list(acb_mat(J).eig(algorithm="rump"))

    # ----------------------------------------------------------------- convenient scalars
    @property
    def a(self) -> arb:
        """Slope of the tail g ~ a theta + b: a = K p S / (2 H) > 0."""
        return -self.p0e[0] / 2

    @property
    def b(self) -> arb:
        return sum((m.weight * (m.pe[0] / m.lam).real for m in self.modes), arb(0))

    def eigenvalues(self) -> list[acb]:
        out = [acb(0)]
        for m in self.modes:
            out.append(m.lam)
            if m.weight == 2:
                out.append(m.lam.conjugate())
        return out


# --------------------------------------------------------------------------- the half-period function

def _series(center: arb | acb, n: int) -> acb_series:
    """The identity series t = center + (t - center), of precision n; build it, and everything
    computed from it, inside ``series_length(n)`` (python-flint caps series at ``ctx.cap`` terms)."""
    return acb_series([acb(center), 1], prec=n)


def _half_tanh_over_lam(lam: acb, s: acb_series) -> acb_series:
    """tanh(lam s / 2) / lam = (E - 1) / ((E + 1) lam), E = exp(lam s), |E| <= 1 for Re lam < 0."""
    E = (lam * s).exp()
    return (E - 1) / ((E + 1) * lam)


def g_coeffs(sp: Spectrum, center: arb, n: int) -> list[arb]:
    """Taylor coefficients g_j(c) = g^{(j)}(c)/j!, j < n, of g at every point c of the ball ``center``.

    A spectrum may carry ``near_zero`` (a :class:`NearZeroSeries`): where it applies (|c| small), its
    power series gives the coefficients instead of the spectral sum (the box spectrum does this: its
    spectral terms cancel near 0).

    Series trap: python-flint cuts series to ``ctx.cap`` terms without warning; the series is built
    inside :func:`~rigor_gyro.core.balls.series_length` (n) and read with ``series_coefficients``,
    which raises rather than pad a cut series with zeros."""
    near = getattr(sp, "near_zero", None)
    if near is not None:
        out = near.coeffs(center, n)
        if out is not None:
            return out
    tot = [arb(0)] * n
    with series_length(n):
        s = _series(center, n)
        for m in sp.modes:
            try:
                c = series_coefficients(_half_tanh_over_lam(m.lam, s) * m.pe[0], n)
            except ValueError:  # E + 1 not separated from 0 on a wide ball: no information
                return [arb("nan")] * n
            for j in range(n):
                tot[j] -= m.weight * c[j].real
    # lambda = 0: -p0e[0] * theta / 2
    tot[0] -= sp.p0e[0] * center / 2
    if n > 1:
        tot[1] -= sp.p0e[0] / 2
    return tot


def pole_free_coeffs(sp: Spectrum, center: arb, n: int) -> list[arb]:
    """Taylor coefficients at every point of ``center`` of G(theta) = g(theta) K(theta), where
    K = prod over the complex pairs lambda, conj(lambda) of (1 + E)(1 + conj E), E = exp(lambda theta).

    Why: g's spectral terms tanh(lambda theta / 2) / lambda have poles where E = -1, at complex theta
    within (2k + 1) pi |Re lambda| / |lambda|^2 of the real axis: for a lightly damped fast nutation they
    sit next to theta = (2k + 1) pi / omega, and no Taylor model of g is accurate on a piece wider than
    that distance, so the root search bisects towards every one of them. K > 0 for real theta > 0
    (|E| < 1 when Re lambda < 0), so G and g have the same roots, with the same multiplicities; and
    in G each pair's own term is (E - 1)(1 + conj E) / lambda, pole-free. Same series trap as g_coeffs.
    A fast, lightly damped nutation (:func:`.nutation_form.fast_form`: one complex pair, omega >= 1000
    times the slowest real rate) takes G's nutation form instead (the same function, other and tighter
    balls, a fraction of the cost); the prover and rigor-gyro check both come here, so they agree.

    Requires: a spectrum whose complex modes have Re lambda < 0 (a stable nutation cubic). Where a box
    spectrum's ``near_zero`` series applies, g comes from it (its spectral terms cancel there) and G's
    coefficients are the Cauchy product with K's."""
    form = fast_form(sp)
    if form is not None:
        return form.coeffs(center, n)
    pairs = [m for m in sp.modes if m.weight == 2]
    tot = [arb(0)] * n
    with series_length(n):
        s = _series(center, n)
        E = {id(m): (m.lam * s).exp() for m in pairs}
        Ec = {id(m): (m.lam.conjugate() * s).exp() for m in pairs}
        one = acb_series([1], prec=n)
        K = one
        for m in pairs:
            K = K * (1 + E[id(m)]) * (1 + Ec[id(m)])
        near = getattr(sp, "near_zero", None)
        g_near = near.coeffs(center, n) if near is not None else None
        if g_near is not None:      # near 0 (a box spectrum): g from its power series, times K's series
            k = [x.real for x in series_coefficients(K, n)]
            return [sum((g_near[i] * k[j - i] for i in range(j + 1)), arb(0)) for j in range(n)]
        for m in sp.modes:
            try:
                if m.weight == 2:
                    others = one
                    for o in pairs:
                        if o is not m:
                            others = others * (1 + E[id(o)]) * (1 + Ec[id(o)])
                    term = (E[id(m)] - 1) * (1 + Ec[id(m)]) / m.lam * others
                else:
                    term = _half_tanh_over_lam(m.lam, s) * K
                c = series_coefficients(term * m.pe[0], n)
            except ValueError:
                return [arb("nan")] * n
            for j in range(n):
                tot[j] -= m.weight * c[j].real
        # lambda = 0: -p0e[0] theta / 2, times K
        lin = series_coefficients(acb_series([acb(center), 1], prec=n) * K, n)
        for j in range(n):
            tot[j] -= sp.p0e[0] * lin[j].real / 2
    return tot


def envelope_margin(sp: Spectrum, X: arb) -> tuple[int, arb] | None:
    """(sigma, M) with sigma G(theta) >= M for every theta in the ball X (X > 0), or None when the
    bound does not apply (a spectrum without exactly one complex pair, a ``near_zero`` box spectrum, or
    s of no certain sign on X). No root of g on X when M > 0 certainly.

    Why: with one complex pair lambda = d + i omega (d < 0), E = exp(lambda theta) = rho e^(i phi), the
    pole-free G of :func:`pole_free_coeffs` is exactly

        G = a + b cos phi + c sin phi,  a = s (1 + rho^2) + 2 q_r (1 - rho^2),  b = 2 s rho,  c = 4 q_i rho,

    where q = pe_0 / lambda and s(theta) = g's slow part (the real modes and the linear term). a, b, c
    vary slowly (no omega in them), so over a piece spanning many nutation periods sigma G >=
    sigma a - sqrt(b^2 + c^2), sigma = sign s, which is

        M = |s| (1 - rho)^2 + 2 sigma q_r (1 - rho^2) - 16 rho q_i^2 / (sqrt(4 s^2 + 16 q_i^2) + 2 |s|),

    written so that no term cancels (1 - rho and 1 - rho^2 by expm1): for a lightly damped fast nutation
    a and sqrt(b^2 + c^2) agree to ~(d theta)^2 and their difference would be lost. Each ball below
    contains its quantity at every theta in X, so M's ball contains M(theta). Precision: the current
    one; M is a lower bound, not an enclosure of G's minimum."""
    if getattr(sp, "near_zero", None) is not None:
        return None
    pairs = [m for m in sp.modes if m.weight == 2]
    if len(pairs) != 1 or any(m.weight != 1 for m in sp.modes if m is not pairs[0]):
        return None
    pair = pairs[0]
    d = pair.lam.real
    if not (certainly_positive(-d) and certainly_positive(X.lower())):
        return None
    q = pair.pe[0] / pair.lam
    qr, qi = q.real, q.imag
    Xc = acb(X)
    slow = -sp.p0e[0] * X / 2
    for m in sp.modes:
        if m is not pair:
            slow -= (m.pe[0] * (m.lam * Xc / 2).tanh() / m.lam).real
    if certainly_positive(slow):
        sigma = 1
    elif certainly_positive(-slow):
        sigma = -1
    else:
        return None
    a_s = sigma * slow                  # |s| > 0 on X
    rho = (d * X).exp()
    one_m_rho = -(d * X).expm1()
    one_m_rho2 = -(2 * d * X).expm1()
    if not (certainly_positive(one_m_rho) and certainly_positive(one_m_rho2)):
        return None                     # expm1 on a wide piece near 0 may reach below 0: no bound here
    # products of positive balls by their ends: a wide ball times itself in midpoint-radius arithmetic
    # reaches below 0 (and the square root of 4 s^2 + 16 q_i^2 would be NaN)
    qi2 = _positive_product(abs(qi), abs(qi)) if certainly_positive(abs(qi).lower()) else qi * qi
    M = (_positive_product(a_s, one_m_rho, one_m_rho) + 2 * sigma * qr * one_m_rho2
         - 16 * rho * qi2 / ((4 * _positive_product(a_s, a_s) + 16 * qi2).sqrt() + 2 * a_s))
    return sigma, M


def _positive_product(*xs: arb) -> arb:
    """A ball containing the product of balls that are all certainly > 0, from their ends (tight for
    wide balls, unlike midpoint-radius multiplication)."""
    lo, hi = arb(1), arb(1)
    for x in xs:
        lo = (lo * x.lower()).lower()
        hi = (hi * x.upper()).upper()
    return lo.union(hi)


class NearZeroSeries:
    """g near theta = 0 as its power series, from matrix powers (no spectral decomposition):

        g(theta) = -S e1^T tanh(M theta / 2) M^{-1} e = sum_j a_j theta^(2j+1),
        a_j = -S c_j e1^T M^(2j) e,   tanh(z/2)/z = sum_j c_j z^(2j),  c_j = 2 (4^(j+1) - 1) B_(2j+2) / (2j+2)!.

    Guarantee: for |theta| <= rho (complex), the tail beyond j = J is at most
    T = (2 pi^2/3) S |e|_inf Cmax rho/pi^2 q^(J+1)/(1-q), q = (rho nu/pi)^2 < 1, using |c_j| <= (2 pi^2/3)/pi^(2j+2)
    (c_j = 2 (4^n - 1) 2 zeta(2n)/(2 pi)^(2n), n = j+1) and |e1^T M^k e| <= |M^k|_inf |e|_inf <= Cmax nu^k
    (nu = |M^N|_inf^(1/N) >= 1, Cmax = max over r < N of |M^r|_inf nu^-r); by Cauchy's estimate the tail's Taylor
    coefficient k at c is at most T / (rho - |c|)^k. Coefficients are returned only for |c| <= ``reach`` rho.
    Every enclosure holds for every matrix in the ball matrix M (a box spectrum's), so the moments,
    computed by matrix-vector products, keep the exact zeros e1^T M^j e = 0 (j <= 3) and do not cancel."""

    def __init__(self, M: arb_mat, e: Sequence[arb], S: arb, terms: int = 800, N: int = 64, reach: float = 0.85):
        v = arb_mat([[x] for x in e])
        self.a: list[arb] = []
        for j in range(terms + 1):
            if j:
                v = M * (M * v)
            n2 = 2 * j + 2
            c = 2 * (arb(4) ** (j + 1) - 1) * arb(fmpq.bernoulli(n2)) / arb(factorial(n2))
            self.a.append(-S * c * v[0, 0])
        norms, W = [], arb_mat(5, 5)
        for i in range(5):
            W[i, i] = 1
        for r in range(N):
            norms.append(_inf_norm(W))
            W = W * M
        nuN = _inf_norm(W)
        self.nu = nuN.max(arb(1)) ** (arb(1) / N)
        # |M^k| <= |M^N|^floor(k/N) |M^r| <= nu^k max_r |M^r| nu^-r  (k = N floor(k/N) + r)
        self.cmax = arb(0)
        for r in range(N):
            self.cmax = self.cmax.max((norms[r] / self.nu ** r).upper())
        self.rho = (arb.pi() / self.nu * arb("0.95")).lower()
        q = (self.rho * self.nu / arb.pi()) ** 2
        enorm = arb(0)
        for x in e:
            enorm = enorm.max(abs(x).upper())
        self.tail = (2 * arb.pi() ** 2 / 3) * abs(S) * enorm * self.cmax * self.rho / arb.pi() ** 2 * \
            q ** (terms + 1) / (1 - q)
        self.reach = arb(reach) * self.rho
        self.J = terms
        coeffs = [arb(0)] * (2 * terms + 2)
        for j, a in enumerate(self.a):
            coeffs[2 * j + 1] = a
        self._derivs = [arb_poly(coeffs)]

    def coeffs(self, center: arb, n: int) -> list[arb] | None:
        c = abs(center).upper()
        if not (c <= self.reach):
            return None
        s = self.rho - c
        while len(self._derivs) < n:             # P^(k)/k!, built once, evaluated in C (Horner)
            k = len(self._derivs)
            self._derivs.append(self._derivs[-1].derivative() * (arb(1) / k))
        return [self._derivs[k](center) + arb(0, (self.tail / s ** k).upper()) for k in range(n)]


def _inf_norm(W: arb_mat) -> arb:
    """An upper bound of the infinity norm (max row sum of |entries|) of every matrix in the ball W."""
    best = arb(0)
    for i in range(W.nrows()):
        row = arb(0)
        for j in range(W.ncols()):
            row += abs(W[i, j]).upper()
        best = best.max(row.upper())
    return best


def x0_at(sp: Spectrum, theta: arb) -> list[arb]:
    """x0(theta) = -tanh(M theta/2) M^{-1} e S: the start of the symmetric solution of half-period theta
    (beta0 = g(theta)); every point of the ball theta."""
    s = acb(theta)
    out = [-sp.p0e[i] * theta / 2 for i in range(5)]
    for m in sp.modes:
        E = (m.lam * s).exp()
        h = (E - 1) / ((E + 1) * m.lam)
        for i in range(5):
            out[i] -= m.weight * (h * m.pe[i]).real
    return out


# --------------------------------------------------------------------------- sums of exponentials

@dataclass
class ExpSum:
    """f(t) = sum_k w_k Re(alpha_k e^{lambda_k t}) + c0 + c1 t (a component of x(t) on one half-period)."""

    terms: list[tuple[acb, acb, int]]   # (alpha, lambda, weight)
    c0: arb
    c1: arb

    def coeffs(self, center: arb, n: int) -> list[arb]:
        """Taylor coefficients at every point of the ball ``center`` (j < n); the series is kept to n
        terms (``series_length``: python-flint would cut it to ``ctx.cap`` silently)."""
        tot = [arb(0)] * n
        with series_length(n):
            s = _series(center, n)
            for alpha, lam, w in self.terms:
                c = series_coefficients((lam * s).exp() * alpha, n)
                for j in range(n):
                    tot[j] += w * c[j].real
        tot[0] += self.c0 + self.c1 * center
        if n > 1:
            tot[1] += self.c1
        return tot

    def __call__(self, t: arb) -> arb:
        return self.coeffs(t, 1)[0]

    def derivative(self) -> "ExpSum":
        return ExpSum([(a * l, l, w) for a, l, w in self.terms], self.c1, arb(0))


def orbit_expsums(sp: Spectrum, x0: Sequence[arb]) -> list[ExpSum]:
    """The five components of x(t) = exp(M t) x0 + w(t) with u = +S, as :class:`ExpSum` (the paper's
    form (7): per component, coefficients of e^{lambda_k t}, a constant and a multiple of t)."""
    out = []
    for i in range(5):
        terms = []
        c0 = sum((sp.P0[i, j] * x0[j] for j in range(5)), arb(0))
        for m in sp.modes:
            px = sum((m.proj[i, j] * x0[j] for j in range(5)), acb(0))
            alpha = px + m.pe[i] / m.lam
            terms.append((alpha, m.lam, m.weight))
            c0 -= m.weight * (m.pe[i] / m.lam).real
        out.append(ExpSum(terms, c0, sp.p0e[i]))
    return out


def state_at(sp: Spectrum, x0: Sequence[arb], t: arb) -> list[arb]:
    return [f(t) for f in orbit_expsums(sp, x0)]


def phi_at(sp: Spectrum, t: arb) -> arb_mat:
    """exp(M t) = P0 + sum_k e^{lambda_k t} P_k (real 5x5 ball matrix)."""
    out = arb_mat(sp.P0)
    for m in sp.modes:
        E = (m.lam * acb(t)).exp()
        for i in range(5):
            for j in range(5):
                out[i, j] += m.weight * (E * m.proj[i, j]).real
    return out


def vector_field(sp: Spectrum, x: Sequence[arb], u_sign: int = 1) -> list[arb]:
    """M x + e u with u = u_sign * S."""
    S = ball(sp.P.S)
    return [sum((sp.M[i, j] * x[j] for j in range(5)), arb(0)) + sp.e[i] * S * u_sign for i in range(5)]


def half_period_jacobian(sp: Spectrum, theta: arb, x0: Sequence[arb]) -> arb_mat:
    """Jacobian of the half-period point map on the section beta = 0 in (beta', Omega, i, I), composed
    with the symmetry x -> -x: -[(I - f e1^T / f_1) exp(M theta)] restricted to rows/columns 1..4, with
    f = M x(theta) + e S the vector field just before the switching (x(theta) = -x0): the first-order
    correction for the perturbed switching time (saltation). Its eigenvalues are the roots of (25)."""
    Phi = phi_at(sp, theta)
    f = vector_field(sp, [-v for v in x0])
    out = arb_mat(4, 4)
    for i in range(1, 5):
        for j in range(1, 5):
            out[i - 1, j - 1] = -(Phi[i, j] - f[i] * Phi[0, j] / f[0])
    return out


# --------------------------------------------------------------------------- Taylor-model enclosures

CoeffFn = Callable[[arb, int], list[arb]]


def _ipow(x: arb, k: int) -> arb:
    """x**k by multiplication (arb's ** gives NaN for balls containing 0)."""
    out = arb(1)
    for _ in range(k):
        out *= x
    return out


def taylor_enclosure(coeff_fn: CoeffFn, X: arb, order: int = 8, derivs: Sequence[int] = (0,)) -> list[arb]:
    """Balls containing f^{(k)}(t) for every t in X, for each k in ``derivs``: the Taylor polynomial of
    f at mid(X) (point coefficients) plus the Lagrange remainder with the order-th coefficient enclosed
    over X, intersected with the direct enclosure over X. ``coeff_fn(center, n)`` must return balls
    containing f^{(j)}(c)/j! (j < n) for every point c of the ball ``center``."""
    kmax = max(derivs)
    if X.rad().is_zero():
        direct = coeff_fn(X, kmax + 1)
        return [direct[k] * factorial(k) for k in derivs]
    m = arb(X.mid())
    w = X - m
    c = coeff_fn(m, order)
    over = coeff_fn(X, order + 1)       # one evaluation over X: the direct enclosures and the remainder's
    direct, cN = over[:kmax + 1], over[order]
    out = []
    pw = [arb(1)]                       # w^i by the products _ipow makes (the same balls), made once
    for _ in range(order - min(derivs)):
        pw.append(pw[-1] * w)
    for k in derivs:
        tot = arb(0)
        for j in range(k, order):
            tot += comb(j, k) * c[j] * pw[j - k]
        tot += comb(order, k) * cN * pw[order - k]
        tot *= factorial(k)
        d = direct[k] * factorial(k)
        if not d.is_finite():
            out.append(tot)
        elif not tot.is_finite():
            out.append(d)
        else:
            out.append(tot.intersection(d) if tot.overlaps(d) else tot)
    return out


def taylor5_leading_coefficient(sp: Spectrum, X: arb, order: int = 12) -> arb:
    """A ball containing g^{(5)}(xi)/5! for every xi in X (Taylor model about mid X): with
    g(0) = ... = g^{(4)}(0) = 0 exactly, g(theta) = theta^5 g^{(5)}(xi)/5! for some xi in (0, theta)."""
    if X.rad().is_zero():
        return g_coeffs(sp, X, 6)[5]
    m = arb(X.mid())
    w = X - m
    c = g_coeffs(sp, m, order)
    cN = g_coeffs(sp, X, order + 1)[order]
    tot = arb(0)
    for j in range(5, order):
        tot += comb(j, 5) * c[j] * _ipow(w, j - 5)
    tot += comb(order, 5) * cN * _ipow(w, order - 5)
    direct = g_coeffs(sp, X, 6)[5]
    if not (direct.is_finite() and tot.is_finite()):
        return tot if tot.is_finite() else direct
    return tot.intersection(direct) if tot.overlaps(direct) else tot


def tail_bound(sp: Spectrum, T: arb) -> arb:
    """A ball whose lower end is <= g(theta) for every theta >= T (T > 0):
    g(theta) = a theta + b - 2 S-weighted sum (rho_k/lambda_k) E_k/(1+E_k), |E_k/(1+E_k)| <=
    e^{Re lambda_k T}/(1 - e^{Re lambda_k T}), and a > 0, so a T + b - B(T) is a lower bound."""
    B = arb(0)
    for m in sp.modes:
        q = (m.lam.real * T).exp()
        amp = 2 * m.weight * abs(m.pe[0] / m.lam)
        B += amp * q / (1 - q)
    return sp.a * T + sp.b - B
