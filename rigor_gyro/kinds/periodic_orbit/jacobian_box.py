"""The half-period Jacobian over a box of parameters, in centred (mean-value) form.

Why: over a box, :func:`.flow.half_period_jacobian` on a :class:`.boxes.BoxSpectrum` (theta* an
interval, the parameters balls) takes each spectral term's dependence on theta and on the
parameters independently. Measured at 128 bits on the printed Roitenberg parameters with n in
50 +- 0.01: its entries have radius 0.108 where J varies by 0.009 over the box (theta* alone: 0.051
against 0.0077; the parameter balls alone: 0.057 against 0.0011), so ``stable`` (margin 0.043) was
decided only on sub-boxes about 1e-3 wide in n.

What: for every (theta, P) in Theta x box, by the mean value theorem,

    J(theta, P) in J(theta_c, P_c) + dJ/dtheta (Theta x box) (Theta - theta_c)
                                   + sum_k dJ/dP_k (Theta x box) (P_k - P_c,k),

(theta_c, P_c) the balls' centres (exact points of them), the derivatives enclosed over the whole of
Theta x box. Everything comes from matrix exponentials, not from the spectral decomposition: with
N = [[M, e S], [0, 0]] (6 x 6), exp(N theta) = [[Phi, w], [0, 1]] (Phi = exp(M theta), w the
response to the relay's +S over [0, theta]); the symmetric orbit starts at x0 = -(I + Phi)^{-1} w
(x(theta) = -x0), the field before the switching is f = -M x0 + e S, and
J = -[(I - f e1^T / f_0) Phi] on rows and columns 1..4, as in :func:`.flow.half_period_jacobian`.
The derivatives: d/dtheta exp(N theta) = N exp(N theta); d/dP_k exp(N theta) = L(N theta,
theta dN/dP_k), the Frechet derivative of exp, which is the upper right block of
exp([[N theta, E], [0, N theta]]) (Higham, *Functions of Matrices*, 2008, Theorem 3.6 and (3.16));
dN/dP_k from a two-term arb series in P_k, the other parameters balls; then the chain rule through
the solve for x0 and the quotient by f_0.

Guarantee: every entry of :func:`centred_jacobian`'s matrix contains that entry of J(theta, P) for every
theta in the ball ``theta`` and every P in the parameter balls. It rests on Arb's ``arb_mat.exp``
and ``solve`` enclosing the exact result for every member of a ball matrix (the 12 x 12 block matrix's
two diagonal blocks are then independent members of N theta: a superset, still an enclosure).

Precision: the caller's. Fails when: I + Phi may be singular, f_0 may vanish, or an enclosure is not
finite over the box (a parameter ball reaching 0, an overflow): returns None and the caller keeps the
direct enclosure.
"""
from __future__ import annotations

from flint import acb, acb_mat, arb, arb_mat, arb_series

from ...core.balls import series_coefficients, series_length
from .flow import PARAMETER_NAMES, RelayParams

__all__ = ["augmented_matrix", "centred_jacobian", "centred_terms", "eigen_coordinate_multipliers", "jacobian_by_exponential"]


def _entries(P) -> list[list]:
    """N = [[M, e S], [0, 0]] as nested lists of the parameters' own type (balls or series)."""
    z = 0 * P.H
    return [[z, z + 1, z, z, z, z],
            [z, z, -P.H / P.B, z, z, z],
            [z, P.H / P.A, z, P.K / P.A, z, z],
            [z, z, -P.n / (P.K * P.tau), -1 / P.tau, P.p / P.tau, z],
            [z, z, z, z, -1 / P.sigma, P.S / P.sigma],
            [z, z, z, z, z, z]]


def augmented_matrix(P: RelayParams) -> arb_mat:
    """N(P) (6 x 6) for parameter balls P: every entry contains its value for every member."""
    return arb_mat(_entries(P))


def _parameter_derivative(P: RelayParams, name: str) -> arb_mat:
    """dN/dP_name enclosed over the parameter balls (a length-2 series in P_name)."""
    with series_length(2):
        Ps = RelayParams(**{k: arb_series([getattr(P, k), 1], prec=2) if k == name else getattr(P, k)
                            for k in PARAMETER_NAMES})
        rows = _entries(Ps)
        return arb_mat([[series_coefficients(x, 2)[1] if isinstance(x, arb_series) else arb(0) for x in r]
                        for r in rows])


def _block(A: arb_mat, i0: int, i1: int, j0: int, j1: int) -> arb_mat:
    return arb_mat([[A[i, j] for j in range(j0, j1)] for i in range(i0, i1)])


def _parts(E: arb_mat):
    """(Phi, w) of a 6 x 6 matrix [[Phi, w], [., .]]."""
    return _block(E, 0, 5, 0, 5), _block(E, 0, 5, 5, 6)


def _identity(n: int) -> arb_mat:
    return arb_mat(n, n, [1 if i == j else 0 for i in range(n) for j in range(n)])


def _frechet_exp(X: arb_mat, D: arb_mat) -> arb_mat:
    """The Frechet derivative L(X, D) of exp: the upper right block of exp([[X, D], [0, X]])."""
    n = X.nrows()
    big = arb_mat(2 * n, 2 * n)
    for i in range(n):
        for j in range(n):
            big[i, j] = big[n + i, n + j] = X[i, j]
            big[i, n + j] = D[i, j]
    return _block(big.exp(), 0, n, n, 2 * n)


def _orbit(N: arb_mat, E: arb_mat):
    """(Phi, x0, f) from N and E = exp(N theta), or None if I + Phi may be singular."""
    Phi, w = _parts(E)
    try:
        x0 = -(_identity(5) + Phi).solve(w, algorithm="precond")
    except ZeroDivisionError:
        return None
    M, eS = _parts(N)
    f = -(M * x0) + eS
    return Phi, x0, f


def _jacobian(Phi: arb_mat, f: arb_mat) -> arb_mat:
    J = arb_mat(4, 4)
    for i in range(1, 5):
        for j in range(1, 5):
            J[i - 1, j - 1] = -(Phi[i, j] - f[i, 0] * Phi[0, j] / f[0, 0])
    return J


def jacobian_by_exponential(P: RelayParams, theta: arb) -> arb_mat | None:
    """J(theta, P) enclosed for every theta in the ball and every P in the balls, through exp(N theta)
    (no mean-value form: used at the centre, where the balls are points). None as in the module docstring."""
    N = augmented_matrix(P)
    orbit = _orbit(N, (N * theta).exp())
    if orbit is None or not _finite(orbit[2]) or orbit[2][0, 0].contains(0):
        return None
    return _jacobian(orbit[0], orbit[2])


def _derivative(N, E, dN, dE, Phi, x0, f) -> arb_mat:
    """dJ for the direction in which N moves by dN and exp(N theta) by dE (the chain rule of the module
    docstring)."""
    dPhi, dw = _parts(dE)
    dx0 = -(_identity(5) + Phi).solve(dPhi * x0 + dw, algorithm="precond")
    M, _ = _parts(N)
    dM, deS = _parts(dN)
    df = -(dM * x0) - M * dx0 + deS
    f0, df0 = f[0, 0], df[0, 0]
    dJ = arb_mat(4, 4)
    for i in range(1, 5):
        for j in range(1, 5):
            dJ[i - 1, j - 1] = -(dPhi[i, j] - (df[i, 0] * Phi[0, j] + f[i, 0] * dPhi[0, j]) / f0
                                 + f[i, 0] * Phi[0, j] * df0 / (f0 * f0))
    return dJ


def _finite(A: arb_mat) -> bool:
    return all(A[i, j].is_finite() for i in range(A.nrows()) for j in range(A.ncols()))


def centred_terms(P: RelayParams, theta: arb):
    """(J at the centre, [(dJ over the box, deviation ball) per direction]) or None (module docstring):
    what :func:`centred_jacobian` and :func:`eigen_coordinate_multipliers` are built from."""
    centre = RelayParams(**{k: arb(getattr(P, k).mid()) for k in PARAMETER_NAMES})
    theta_c = arb(theta.mid())
    J = jacobian_by_exponential(centre, theta_c)
    if J is None:
        return None
    N = augmented_matrix(P)
    E = (N * theta).exp()
    orbit = _orbit(N, E)
    if orbit is None:
        return None
    Phi, x0, f = orbit
    if not (_finite(E) and _finite(x0) and _finite(f)) or f[0, 0].contains(0):
        return None
    terms = []
    try:
        directions = [(theta - theta_c, arb_mat(6, 6), N * E)]
        for k in PARAMETER_NAMES:
            dev = getattr(P, k) - getattr(centre, k)
            if dev.is_zero():
                continue
            dN = _parameter_derivative(P, k)
            directions.append((dev, dN, _frechet_exp(N * theta, dN * theta)))
        for dev, dN, dE in directions:
            terms.append((_derivative(N, E, dN, dE, Phi, x0, f), dev))
    except ZeroDivisionError:
        return None
    return J, terms


def centred_jacobian(P: RelayParams, theta: arb, parts=None) -> arb_mat | None:
    """J(theta, P) for every theta in the ball ``theta`` and every P in the parameter balls, in the
    centred form of the module docstring; None when it cannot be formed (see there). ``parts``: the
    :func:`centred_terms` of (P, theta) if already computed."""
    parts = centred_terms(P, theta) if parts is None else parts
    if parts is None:
        return None
    J, terms = parts
    for dJ, dev in terms:
        J = J + dJ * dev
    return J if _finite(J) else None


def eigen_coordinate_multipliers(P: RelayParams, theta: arb, parts=None) -> list[acb] | None:
    """The eigenvalues of J(theta, P) for every theta in the ball and every P in the balls, from the
    centred form taken in the centre's eigenvector coordinates: K = V^{-1} J V with V an exact point
    matrix (the midpoints of the centre's eigenvector enclosures) and V^{-1} enclosed, so
    K_box = V^{-1} J(centre) V + sum_k (V^{-1} dJ_k V) dev_k contains V^{-1} J V for every member, whose
    eigenvalues are J's; Rump's method on K_box then encloses the eigenvalues of every matrix in it.

    Why: J's entries move with n far more than its eigenvalues (measured on n in 50 +- 0.2: J's
    radius 0.26, the moduli move by 1e-5); in eigenvector coordinates that motion is mostly off the
    diagonal, which moves the eigenvalues only to second order, and the ball K_box is 65 times narrower.
    None if an eigen-decomposition or the inverse fails (the caller keeps Rump's method on J).
    ``parts`` as in :func:`centred_jacobian`."""
    parts = centred_terms(P, theta) if parts is None else parts
    if parts is None:
        return None
    Jc, terms = parts
    try:
        _, R = acb_mat(Jc).eig(right=True, algorithm="rump")
        V = acb_mat([[acb(R[i, j].real.mid(), R[i, j].imag.mid()) for j in range(4)] for i in range(4)])
        Vi = V.inv()
        K = Vi * acb_mat(Jc) * V
        for dJ, dev in terms:
            K = K + (Vi * acb_mat(dJ) * V) * acb(dev)
        eig = list(K.eig(algorithm="rump"))
    except (ValueError, ZeroDivisionError):
        return None
    return eig if len(eig) == 4 and all(z.is_finite() for z in eig) else None
