"""Three similarity invariants of the relay: a box of the six physical parameters replaced by a box of three
(issue 37 part 1: all six at once).

Why: over a box, every direction the centred forms of :mod:`.continuation` follow adds its own enclosure
excess. The orbit's existence, its genuineness and its multipliers depend on (A, B, H, tau, sigma, n) only
through

    a = H^2 tau^2 / (A B),    b = n tau / A,    s = sigma / tau.

Proof (exact, checked in rationals by :func:`conjugacy_holds`): for P and P' with the same (a, b, s), let
alpha = tau / tau' and t = alpha t', y(t') = D^{-1} x(alpha t') with the positive diagonal
D = diag(d0..d4), d0 = 1, d1 = 1/alpha, d2 = alpha d1 (H/A)(A'/H'), d3 = d2 A/(alpha A'), d4 = d3. Then
alpha D^{-1} M(P) D = M(P') (each entry: (3,3), (4,4) by alpha = tau/tau' and s; the two 2-cycles by a and b;
the others by the choice of D, with K' = K and p' = p) and alpha D^{-1} e(P) S = e(P') S' with S' = S / d4 > 0.
So y solves the relay system at P' (the relay's sign is that of beta = d0 y0), every half-period theta of P
is alpha theta' of P', beta > 0 on (0, theta) exactly when y0 > 0 on (0, theta'), and the half-period maps are
conjugate by D (restricted to beta', Omega, i, I), so the multipliers are equal. S' differs from S, which the
claims do not depend on (homogeneity, see :mod:`.boxes`).

What: :func:`similar_box` maps a box to the box of (B', sigma', n') at A' = A_c, H' = H_c, tau' = tau_c (the
box's midpoints) whose members realise every (a, b, s) of the box: a is increasing in H and tau and decreasing
in A and B, so its range is exact from the corners (and so are b's and s's), and B' = H_c^2 tau_c^2 / (A_c a),
n' = b A_c / tau_c, sigma' = s tau_c are monotone in a, b, s. The new box contains the image of the old (the
image of a box under the monomial map is not a box: the new box is a superset, which only costs width).

Guarantee: ``orbit_genuine`` and ``stable`` (and any claim about the existence, genuineness or multipliers of
a symmetric orbit) proved on the similar box hold on the original box. Not for claims that quote theta* or
depend on a tracked orbit's nearness to a given theta (theta scales by tau / tau_c).
Precision: exact rationals. Fails when: a parameter of the box is not positive: ValueError (validated before).
"""
from __future__ import annotations

from fractions import Fraction

from flint import fmpq, fmpq_mat

from ...core.boxes import Box
from .flow import PARAMETER_NAMES, RelayParams, forcing, system_matrix

__all__ = ["INVARIANT_NAMES", "REDUCED", "similar_box", "similar_point", "conjugacy_holds"]

#: the parameters a similar box keeps at the box's midpoint (the others carry the three invariants)
FIXED = ("A", "H", "tau")
#: the parameters of the similar box
REDUCED = ("B", "sigma", "n")
INVARIANT_NAMES = ("a = H^2 tau^2/(A B)", "b = n tau/A", "s = sigma/tau")


def _iv(box: Box, params, k: str) -> tuple[Fraction, Fraction]:
    if k in box.names:
        return box.interval(k)
    v = getattr(params, k)
    v = Fraction(int(v.p), int(v.q))
    return v, v


def similar_box(params, box: Box) -> tuple[Box, dict[str, Fraction]] | None:
    """(the box of (B, sigma, n), the fixed {A, H, tau} midpoints) as in the module docstring, or None when the
    box varies none of A, H, tau (nothing to reduce). ``params``: the model's exact parameters (fmpq), for
    those the box does not vary."""
    if not any(k in box.names and box.interval(k)[0] != box.interval(k)[1] for k in FIXED):
        return None
    A, B, H, tau, sigma, n = (_iv(box, params, k) for k in ("A", "B", "H", "tau", "sigma", "n"))
    for lo, _ in (A, B, H, tau, sigma, n):
        if lo <= 0:
            raise ValueError("a relay parameter of the box is not positive")
    Ac, Hc, tc = (sum(x) / 2 for x in (A, H, tau))
    a = (H[0] ** 2 * tau[0] ** 2 / (A[1] * B[1]), H[1] ** 2 * tau[1] ** 2 / (A[0] * B[0]))
    b = (n[0] * tau[0] / A[1], n[1] * tau[1] / A[0])
    s = (sigma[0] / tau[1], sigma[1] / tau[0])
    k = Hc * Hc * tc * tc / Ac
    out = Box.of({"B": (k / a[1], k / a[0]), "sigma": (s[0] * tc, s[1] * tc), "n": (b[0] * Ac / tc, b[1] * Ac / tc)})
    return out, {"A": Ac, "H": Hc, "tau": tc}


def similar_point(P: RelayParams, fixed: dict[str, Fraction]) -> RelayParams:
    """The member P' of a similar box with A, H, tau = ``fixed`` and the same (a, b, s) as P (exactly)."""
    q = lambda x: fmpq(x.numerator, x.denominator)
    Ac, Hc, tc = q(fixed["A"]), q(fixed["H"]), q(fixed["tau"])
    a = P.H * P.H * P.tau * P.tau / (P.A * P.B)
    vals = {k: getattr(P, k) for k in PARAMETER_NAMES}
    vals.update(A=Ac, H=Hc, tau=tc, B=Hc * Hc * tc * tc / (Ac * a), n=P.n * P.tau * Ac / (P.A * tc),
                sigma=P.sigma * tc / P.tau)
    return RelayParams(**vals)


def conjugacy_holds(P: RelayParams, Q: RelayParams) -> bool:
    """Exactly: alpha D^{-1} M(P) D = M(Q) and alpha D^{-1} e(P) = c e(Q) with c > 0 (module docstring's D,
    alpha = tau_P / tau_Q), K and p equal. True whenever P and Q have the same (a, b, s); a False for such a
    pair would mean the model changed."""
    if P.K != Q.K or P.p != Q.p:
        return False
    alpha = P.tau / Q.tau
    d = [fmpq(1), 1 / alpha]
    d.append(alpha * d[1] * (P.H / P.A) * (Q.A / Q.H))
    d.append(d[2] * P.A / (alpha * Q.A))
    d.append(d[3])
    M, N = system_matrix(P), system_matrix(Q)
    lhs = fmpq_mat(5, 5, [alpha * M[i, j] * d[j] / d[i] for i in range(5) for j in range(5)])
    e, f = forcing(P), forcing(Q)
    c = alpha * e[4] / d[4] / f[4]
    return lhs == N and c > 0 and all(alpha * e[i] / d[i] == c * f[i] for i in range(5))
