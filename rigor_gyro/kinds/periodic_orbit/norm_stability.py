"""``stable`` over a parameter box without isolating the multipliers: a Gershgorin bound on the spectral
radius of the half-period Jacobian in the centre's eigenvector coordinates (issue 37 part 1).

Why: :mod:`.continuation` step 3 encloses the four multipliers by Rump's method, which must isolate each
eigenvalue of a ball matrix. Over a box of several parameters the centred form of J in eigenvector
coordinates is wide enough that the complex pair (moduli ~0.6 at the printed Roitenberg parameters) is not
isolated, although the largest modulus (0.957) moves by about 0.002 over a +-0.5 % box of all six parameters
and its margin to 1 is 0.043. ``stable`` needs only every modulus < 1, and Gershgorin's theorem gives that
without isolation: every eigenvalue of a matrix K lies in some disc |z - K_ii| <= R_i (R_i = sum_{j != i}
|K_ij|, rows; or the same with columns), so rho(K) <= max_i (|K_ii| + R_i). With K = V^{-1} J V (V an exact
complex point matrix: the midpoints of the centre's eigenvector enclosures, so K(centre) is nearly diagonal)
and K's entries enclosed over the box by the centred form K(c) + sum_k (V^{-1} dJ_k V) dev_k, the bound
holds for every member of the box at once. A positive diagonal rescaling D (K -> D^{-1} K D, the same
eigenvalues) moves off-diagonal mass from the row with the largest modulus to rows with slack; a few
choices of D are tried and the smallest bound kept (each one is a valid bound).

Guarantee: :func:`spectral_radius_bound` returns an arb upper bound U with rho(J) <= U for every matrix J
in the ball family given (every parameter of the box). Where a Gershgorin disc is disjoint from the union of
the others, it holds exactly one eigenvalue, which gives the lower end of the largest modulus (else 0).
Precision: the current working precision. Fails when: V is singular or an entry is not finite: None.
"""
from __future__ import annotations

from flint import acb, acb_mat, arb, arb_mat

from ...core.balls import certainly_lt, certainly_positive

__all__ = ["eigen_coordinate_family", "spectral_radius_bound", "largest_modulus_range"]


def eigen_coordinate_family(Jc: arb_mat, terms) -> acb_mat | None:
    """K_box = V^{-1} J(c) V + sum_k (V^{-1} dJ_k V) dev_k, containing V^{-1} J V for every member (``terms``:
    [(dJ_k over the box, deviation ball)], the centred form of J); V the midpoints of the centre's right
    eigenvectors (an exact matrix). None if the centre's eigenvectors or V^{-1} cannot be enclosed."""
    n = Jc.nrows()
    try:
        _, R = acb_mat(Jc).eig(right=True, algorithm="rump")
        V = acb_mat([[acb(R[i, j].real.mid(), R[i, j].imag.mid()) for j in range(n)] for i in range(n)])
        Vi = V.inv()
    except (ValueError, ZeroDivisionError):
        return None
    K = Vi * acb_mat(Jc) * V
    for dJ, dev in terms:
        K = K + (Vi * acb_mat(dJ) * V) * acb(dev)
    if not all(K[i, j].is_finite() for i in range(n) for j in range(n)):
        return None
    return K


def _discs(K: acb_mat, d: list[float], rows: bool) -> list[tuple[arb, arb]]:
    """(|K_ii| (a ball), R_i upper bound) of D^{-1} K D (rows) or of its transpose's (columns)."""
    n = K.nrows()
    out = []
    for i in range(n):
        R = arb(0)
        for j in range(n):
            if j != i:
                e = K[i, j] if rows else K[j, i]
                s = arb(d[j]) / arb(d[i]) if rows else arb(d[i]) / arb(d[j])
                R = R + abs(e) * s
        out.append((abs(K[i, i]), R))
    return out


def _scalings(K: acb_mat) -> list[list[float]]:
    """Diagonal scalings to try: none, and ones that shrink the off-diagonal sums of the rows with the
    least slack (1 - |K_ii|), by weights growing with each row's slack (floats: any positive D is valid)."""
    n = K.nrows()
    slack = [max(1e-6, 1 - float(abs(K[i, i]).mid())) for i in range(n)]
    out = [[1.0] * n]
    for p in (0.5, 1.0, 2.0):
        out.append([s ** p for s in slack])
        out.append([s ** -p for s in slack])
    return out


def spectral_radius_bound(K: acb_mat) -> arb | None:
    """An upper bound (an exact arb point) of rho(M) for every matrix M in the ball matrix K (module
    docstring): the least over the tried scalings, rows and columns, of max_i (|K_ii| + R_i); None if not finite."""
    best = None
    for d in _scalings(K):
        for rows in (True, False):
            b = arb(0)
            for a, R in _discs(K, d, rows):
                b = b.max(a + R)
            if not b.is_finite():
                continue
            u = arb(b.upper())
            if best is None or certainly_lt(u, best):
                best = u
    return best


def largest_modulus_range(K: acb_mat) -> arb | None:
    """A ball [lo, hi] containing max_i |lambda_i(M)| for every M in K: hi from :func:`spectral_radius_bound`;
    lo from Gershgorin's second theorem (a row disc disjoint from the union of the others holds exactly one
    eigenvalue, whose modulus is then >= |K_ii| - R_i), the largest such lower bound, else 0."""
    hi = spectral_radius_bound(K)
    if hi is None:
        return None
    discs = _discs(K, [1.0] * K.nrows(), True)
    lo = arb(0)
    for i, (a, R) in enumerate(discs):
        ci, ri = K[i, i], R
        isolated = True
        for j, (_, Rj) in enumerate(discs):
            if j != i and not certainly_positive(abs(ci - K[j, j]) - ri - Rj):
                isolated = False
                break
        if isolated:
            low = a - ri
            if certainly_positive(low):
                lo = lo.max(arb(low.lower()))
    return lo.union(hi) if certainly_lt(lo, hi) else arb(hi)
