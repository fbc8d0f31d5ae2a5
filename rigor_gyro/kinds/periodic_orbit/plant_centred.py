"""Centred (mean-value) enclosures over a parameter box of a ``[plant]`` model's polynomial data: the
characteristic polynomial's coefficients p_k and the Krylov numerators' coefficients N_i,k of
:func:`.plant_model.numerators` (and c . N), for :class:`.plant_box.PlantBoxSpectrum` (issue 37, centred forms).

Why: ``arb_mat.charpoly`` of the ball matrix M(box) evaluates each p_k with every entry a ball of its own, and
the example's coefficients are sums of products of entries of size 100 and 600 that nearly cancel; a box of
relative width 1e-4 in H then leaves a coefficient whose family of roots has a real part not separated from 0.
Here every p_k, N_i,k is a polynomial in the entries, the entries the scene's expressions in its parameters, so

    p_k(P) in p_k(P0) + sum_j dp_k/dP_j(box) (P_j - P0_j)       (the mean value theorem, P0 the box's exact midpoint)

with the gradient balls by forward-mode differentiation in balls (:mod:`rigor_gyro.core.dual_balls`) through
the entries' expressions and the Faddeev-LeVerrier recurrence (integer divisions only), intersected with the
naive value (the same Dual evaluation's value part). Second order in the box's width where the naive form is
first order.

Guarantee: each returned ball contains the coefficient's value for every parameter value in the box, at the
current precision. Fails when: an entry's expression uses an operation the Dual numbers do not have, or a value
or gradient is not finite on the box (a division by an interval containing 0): None (the caller keeps the
naive balls).
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.boxes import Box
from ...core.dual_balls import Dual, constant, gradient_finite, variable

__all__ = ["centred_polynomial_data", "centred_scalar", "faddeev_leverrier"]


def _exact(q: Fraction) -> arb:
    return arb(fmpq(q.numerator, q.denominator))


def faddeev_leverrier(M: list[list], n: int) -> list:
    """[p_0, ..., p_n] of det(z I - M) = sum p_k z^k (p_n = 1) for a matrix of Duals (or any ring with exact
    integer division by k): B_1 = I, p_{n-1} = -tr M; B_k = M B_{k-1} + p_{n-k+1} I, p_{n-k} = -tr(M B_k)/k."""
    one, zero = constant(1), constant(0)
    p = [zero] * (n + 1)
    p[n] = one
    B = [[one if i == j else zero for j in range(n)] for i in range(n)]
    for k in range(1, n + 1):
        MB = [[sum((M[i][r] * B[r][j] for r in range(n)), zero) for j in range(n)] for i in range(n)]
        p[n - k] = -sum((MB[i][i] for i in range(n)), zero) / k
        if k < n:
            B = [[MB[i][j] + (p[n - k] if i == j else zero) for j in range(n)] for i in range(n)]
    return p


def _data(exprs, env: dict, number) -> tuple[list, list[list], list]:
    """(p, Ns, Nc) from the entries' expressions evaluated at ``env`` (Duals)."""
    Mx, ex, cx = exprs
    M = [[x.evaluate(env, number=number) for x in r] for r in Mx]
    e = [x.evaluate(env, number=number) for x in ex]
    c = [x.evaluate(env, number=number) for x in cx]
    n = len(e)
    p = faddeev_leverrier(M, n)
    zero = constant(0)
    krylov = [e]
    for _ in range(n - 1):
        v = krylov[-1]
        krylov.append([sum((M[i][r] * v[r] for r in range(n)), zero) for i in range(n)])
    Ns = [[zero] * n for _ in range(n)]
    for k in range(n):
        for i in range(k + 1, n + 1):
            v = krylov[i - k - 1]
            for r in range(n):
                Ns[r][k] = Ns[r][k] + p[i] * v[r]
    Nc = [sum((c[i] * Ns[i][k] for i in range(n)), zero) for k in range(n)]
    return p, Ns, Nc


def centred_polynomial_data(exprs, exact: dict[str, Fraction], box: Box, grads: dict | None = None):
    """(p, Ns, Nc) as balls: p[k] the coefficients of det(z I - M), Ns[i][k] those of N_i(z) = (adj(z I - M) e)_i,
    Nc[k] those of c . N(z), each containing its value for every member of the box (module docstring); ``exprs``
    = (M, e, c) parsed expressions, ``exact`` every parameter's exact value (the box's edges override). None
    when not enclosed. ``grads`` (a dict): filled with P_j -> (the p_k's, the Nc_k's partial derivatives in
    P_j over the box), for the parametric form of g in :mod:`.plant_box`."""
    wide = [k for k, lo, hi in box.edges if hi > lo]
    number = lambda q: constant(_exact(q))                   # noqa: E731
    env_box = {k: constant(_exact(v)) for k, v in exact.items()}
    env_mid = dict(env_box)
    mid = box.midpoint()
    for k, lo, hi in box.edges:
        env_box[k] = variable(k, box.ball(k)) if hi > lo else constant(_exact(lo))
        env_mid[k] = constant(_exact(mid[k]))
    try:
        over = _data(exprs, env_box, number)
        at_mid = _data(exprs, env_mid, number)
    except (ArithmeticError, TypeError, AttributeError, KeyError, ValueError):
        return None
    dev = {k: box.ball(k) - _exact(mid[k]) for k in wide}

    def centred(D: Dual, D0: Dual) -> arb | None:
        if not gradient_finite(D) or not D0.value.is_finite():
            return None
        v = D0.value
        for k, g in D.grad.items():
            if k in dev:
                v = v + g * dev[k]
        naive = D.value
        return naive.intersection(v) if naive.overlaps(v) else v

    p = [centred(a, b) for a, b in zip(over[0], at_mid[0])]
    Ns = [[centred(a, b) for a, b in zip(r, s)] for r, s in zip(over[1], at_mid[1])]
    Nc = [centred(a, b) for a, b in zip(over[2], at_mid[2])]
    flat = p + [x for r in Ns for x in r] + Nc
    if any(x is None or not x.is_finite() for x in flat):
        return None
    if grads is not None:         # dp_k/dP_j and d(c . N)_k/dP_j over the box, for each varying P_j
        for j in wide:
            grads[j] = ([D.grad.get(j, arb(0)) for D in over[0]], [D.grad.get(j, arb(0)) for D in over[2]])
    return p, Ns, Nc


def centred_scalar(expr, exact: dict[str, Fraction], box: Box) -> tuple[arb, dict[str, arb]] | None:
    """(value over the box, {P_j: d/dP_j over the box}) of one entry's expression (S or h), by the same Dual
    evaluation; None when not enclosed."""
    number = lambda q: constant(_exact(q))                   # noqa: E731
    env = {k: constant(_exact(v)) for k, v in exact.items()}
    for k, lo, hi in box.edges:
        env[k] = variable(k, box.ball(k)) if hi > lo else constant(_exact(lo))
    try:
        D = expr.evaluate(env, number=number)
    except (ArithmeticError, TypeError, AttributeError, KeyError, ValueError):
        return None
    if not gradient_finite(D):
        return None
    return D.value, {k: D.grad.get(k, arb(0)) for k, lo, hi in box.edges if hi > lo}
