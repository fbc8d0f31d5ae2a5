"""Roitenberg (1947)'s algebraic forms, on any inputs (balls): the a_ij of (7) from the exponents, the
b_ij of (16) from the a_ij, the h, c, k of Table 1 and (24), the quartic (25) from k, and the alpha
coefficients by the quadrature (14)-(15).

Used twice: with the certified exponents (the exact value of a row, :mod:`.paper`) and with the paper's
own printed numbers, each an interval of its rounding (the paper's chain, :mod:`.paper_chain`).
Guarantee: interval arithmetic throughout (each output is an enclosure of the form's value over the
input balls, at the working precision). Failure mode: a singular matrix in (16) (the inverse then
raises ZeroDivisionError / ValueError: the caller treats it as "no chain").
"""
from __future__ import annotations

from flint import acb, arb, arb_mat

__all__ = ["a_from_exponents", "b_coefficients", "table1", "k_of_c", "quartic_of_k", "alpha_of_omega"]


def a_from_exponents(mu1: arb, omega: arb, mu2: arb, inv_sigma: arb, P) -> dict[tuple[int, int], arb]:
    """a_ij of (7) from the exponents: the eigenvector of (2) with beta-component 1 for the complex pair
    and -mu2 ([1, lam, -(B/H) lam^2, (-(AB/H) lam^3 - H lam)/K]), and the -1/sigma eigenvector with
    I-component 1 (Omega = Kp / ((A lam + H^2/(B lam))(1 + tau lam) + n), i = (p - n1 Omega)/(1 + tau lam),
    beta' = -H Omega/(B lam), beta = beta'/lam); a17 = -Kp/H, a47 = p. P: exact parameters (A, B, H, K,
    p, tau, n) as anything ``arb`` accepts through ``ball``."""
    from ...core.balls import ball
    A, B, H, K, p, tau, n = (ball(x) for x in (P.A, P.B, P.H, P.K, P.p, P.tau, P.n))

    def comp(lam):
        return [acb(1), lam, -(B / H) * lam ** 2, (-(A * B / H) * lam ** 3 - H * lam) / K]
    c1, c3 = comp(acb(-mu1, omega)), comp(acb(-mu2))
    a: dict[tuple[int, int], arb] = {}
    for g in range(1, 4):
        G = g + 1
        a[(G, 1)] = c1[g].real
        a[(G, 3)] = c1[g].imag
        a[(G, 2)] = -c1[g].imag
        a[(G, 4)] = c1[g].real
        a[(G, 5)] = c3[g].real
    lam = -inv_sigma
    Om = K * p / ((A * lam + H ** 2 / (B * lam)) * (1 + tau * lam) + n)
    i_ = (p - (n / K) * Om) / (1 + tau * lam)
    bd = -H * Om / (B * lam)
    a[(1, 6)], a[(2, 6)], a[(3, 6)], a[(4, 6)] = bd / lam, bd, Om, i_
    a[(1, 7)] = -K * p / H
    a[(4, 7)] = p
    return a


def b_coefficients(a: dict[tuple[int, int], arb], S: arb) -> dict[tuple[int, int], arb]:
    """b_ij of (16) (Table 3) from the a_ij of (7) and S: the general solution (7) with D1..D5 solved from
    the initial values (beta0 = 0, beta'0, Omega0, i0, I0)."""
    z = arb(0)
    N = arb_mat([[z, 1, 1, 1, a[(1, 6)]],
                 [a[(2, 3)], a[(2, 4)], a[(2, 5)], z, a[(2, 6)]],
                 [a[(3, 3)], a[(3, 4)], a[(3, 5)], z, a[(3, 6)]],
                 [a[(4, 3)], a[(4, 4)], a[(4, 5)], z, a[(4, 6)]],
                 [z, z, z, z, 1]])
    Ni = N.inv()
    part0 = [z, a[(1, 7)] * S, z, a[(4, 7)] * S, S]
    cst = [-sum((Ni[r, j] * part0[j] for j in range(5)), arb(0)) for r in range(5)]
    rowsD = [[Ni[r, j] for j in range(1, 5)] + [cst[r]] for r in range(5)]

    def comb(coefs):
        return [sum((cf * rowsD[r][j] for r, cf in coefs), arb(0)) for j in range(5)]
    b: dict[tuple[int, int], arb] = {}

    def put(G, blocks):
        k = 1
        for blk in blocks:
            for v in blk:
                b[(G, k)] = v
                k += 1
    for G in (1, 2, 3, 4):
        sinb = comb([(0, a[(G, 1)] if G > 1 else arb(1)), (1, a[(G, 2)] if G > 1 else arb(0))])
        cosb = comb([(0, a[(G, 3)] if G > 1 else arb(0)), (1, a[(G, 4)] if G > 1 else arb(1))])
        e3b = comb([(2, a[(G, 5)] if G > 1 else arb(1))])
        a6 = a[(G, 6)]
        sgb = [a6, -a6 * S]
        if G == 1:
            d4 = comb([(1, arb(-1)), (2, arb(-1)), (4, -a[(1, 6)])])
            put(1, [sinb, cosb, e3b, sgb, [d4[4], a[(1, 7)] * S], d4[:4]])
        elif G == 2:
            put(2, [sinb, cosb, e3b, sgb, [a[(1, 7)] * S]])
        elif G == 3:
            put(3, [sinb, cosb, e3b, sgb])
        else:
            put(4, [sinb, cosb, e3b, sgb, [a[(4, 7)] * S]])
    b[(5, 1)] = -S
    b[(5, 2)] = S
    return b


def table1(b, xs, eps, mu1, omega, mu2, inv_sigma) -> tuple[dict, dict]:
    """(h, c) of Table 1 from b_ij, x* = (beta'*, Omega*, i*, I*), eps_1..4 and the exponents, as read:
    h_g1..h_g3 with b_g3 i* (the table prints "b13 I*"), and the second column's c31..c35 as c51..c55."""
    e1, e2, e3, e4 = eps
    h: dict[tuple[int, int], arb] = {}
    for G in (1, 2, 3, 4):
        for m in range(3):
            h[(G, m + 1)] = sum((b[(G, 5 * m + j + 1)] * xs[j] for j in range(4)), arb(0)) + b[(G, 5 * m + 5)]
        h[(G, 4)] = b[(G, 16)] * xs[3] + b[(G, 17)]
    h[(5, 4)] = xs[3] + b[(5, 1)]
    c: dict[tuple[int, int], arb] = {}
    for G in (1, 2, 3, 4):
        for j in range(1, 4):
            c[(G, j)] = e1 * b[(G, j)] + e2 * b[(G, j + 5)] + e3 * b[(G, j + 10)]
        c[(G, 4)] = e1 * b[(G, 4)] + e2 * b[(G, 9)] + e3 * b[(G, 14)] + e4 * b[(G, 16)]
        c[(G, 5)] = ((-mu1 * e1 + omega * e2) * h[(G, 1)] - (mu1 * e2 + omega * e1) * h[(G, 2)]
                     - mu2 * e3 * h[(G, 3)] - e4 * h[(G, 4)] * inv_sigma)
    for j in range(1, 4):
        c[(1, j)] += b[(1, j + 19)]
    c[(1, 4)] += b[(1, 23)]
    c[(1, 5)] += b[(1, 19)]
    for j in range(1, 4):
        c[(5, j)] = arb(0)
    c[(5, 4)] = e4
    c[(5, 5)] = -e4 * h[(5, 4)] * inv_sigma
    return h, c


def k_of_c(c) -> dict[tuple[int, int], arb]:
    """k_gj = (c_{g+1,j} c15 - c_{g+1,5} c1j) / c15 ((24), the second index read as 5 throughout)."""
    return {(g, j): (c[(g + 1, j)] * c[(1, 5)] - c[(g + 1, 5)] * c[(1, j)]) / c[(1, 5)]
            for g in range(1, 5) for j in range(1, 5)}


def quartic_of_k(k) -> list[arb]:
    """[q3, q2, q1, q0] of det(lambda I + K) = lambda^4 + q3 lambda^3 + q2 lambda^2 + q1 lambda + q0."""
    K = arb_mat([[k[(r, j)] for j in range(1, 5)] for r in range(1, 5)])
    cp = (-K).charpoly()
    return [cp[3], cp[2], cp[1], cp[0]]


def alpha_of_omega(om: list[arb], mu1: arb, omega: arb, mu2: arb, inv_sigma: arb, theta: arb) -> list[arb]:
    """alpha's [sin, cos, e^-mu2t, e^-t/sigma, const] by the quadrature (14) of Omega's [sin, cos, e^-mu2t,
    e^-t/sigma] coefficients, with C from (15) alpha(0) = -alpha(theta)."""
    s, c, m2, sg = om
    d = mu1 * mu1 + omega * omega
    A = (-mu1 * s + omega * c) / d
    B = (-omega * s - mu1 * c) / d
    a3, a4 = -m2 / mu2, -sg / inv_sigma
    F0 = B + a3 + a4
    Ft = (-mu1 * theta).exp() * (A * (omega * theta).sin() + B * (omega * theta).cos()) + a3 * (-mu2 * theta).exp() \
        + a4 * (-inv_sigma * theta).exp()
    return [A, B, a3, a4, -(F0 + Ft) / 2]
