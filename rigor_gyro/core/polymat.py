"""Determinants of matrix polynomials with exact rational coefficients, two ways.

A matrix polynomial is given by its coefficient matrices ``[A0, A1, ..., Ad]`` (square ``fmpq_mat`` of one
size n): A(x) = A0 + A1 x + ... + Ad x^d, and det A(x) is a polynomial of degree <= n d.

* :func:`det_by_interpolation` evaluates det A(x) exactly (``fmpq_mat.det``) at the n d + 1 points
  x = 0, 1, ..., n d and interpolates (Newton's divided differences in exact rationals): fast.
* :func:`det_by_expansion` expands det A(x) along rows over ``fmpq_poly`` entries (Laplace, memoised on the
  set of columns used): a different computation of the same polynomial, for an independent re-check.

Guarantee: both return the exact ``fmpq_poly`` det A(x) (no rounding anywhere).

Fails when: the matrices are not square of one size (ValueError); n above :data:`MAX_SIZE` (ValueError: the
expansion is exponential in n).
"""
from __future__ import annotations

from flint import fmpq, fmpq_mat, fmpq_poly

__all__ = ["det_by_interpolation", "det_by_expansion", "MAX_SIZE"]

MAX_SIZE = 14


def _shape(coeffs: list[fmpq_mat]) -> int:
    if not coeffs:
        raise ValueError("a matrix polynomial needs at least one coefficient matrix")
    n = coeffs[0].nrows()
    if any(c.nrows() != n or c.ncols() != n for c in coeffs):
        raise ValueError("the coefficient matrices must be square and of one size")
    if n > MAX_SIZE:
        raise ValueError(f"matrices of size {n} exceed {MAX_SIZE}")
    return n


def det_by_interpolation(coeffs: list[fmpq_mat]) -> fmpq_poly:
    """det(sum_k coeffs[k] x^k) exactly, from its values at x = 0 .. n d (see the module docstring)."""
    n = _shape(coeffs)
    deg = n * (len(coeffs) - 1)
    xs = [fmpq(j) for j in range(deg + 1)]
    ys = []
    for x in xs:
        m = coeffs[-1]
        for c in reversed(coeffs[:-1]):
            m = m * x + c
        ys.append(m.det() if n else fmpq(1))
    # Newton's divided differences, then the Newton form expanded
    dd = list(ys)
    for level in range(1, len(xs)):
        for i in range(len(xs) - 1, level - 1, -1):
            dd[i] = (dd[i] - dd[i - 1]) / (xs[i] - xs[i - level])
    p = fmpq_poly([dd[-1]])
    for i in range(len(xs) - 2, -1, -1):
        p = p * fmpq_poly([-xs[i], 1]) + dd[i]
    return p


def det_by_expansion(coeffs: list[fmpq_mat]) -> fmpq_poly:
    """det(sum_k coeffs[k] x^k) exactly, by Laplace expansion along rows over polynomial entries."""
    n = _shape(coeffs)
    entries = [[fmpq_poly([c[i, j] for c in coeffs]) for j in range(n)] for i in range(n)]
    memo: dict[int, fmpq_poly] = {}

    def minor(row: int, used: int) -> fmpq_poly:
        if row == n:
            return fmpq_poly([1])
        if used in memo:
            return memo[used]
        total, sign = fmpq_poly([]), 1
        for col in range(n):
            if used >> col & 1:
                continue
            e = entries[row][col]
            if not e.is_zero():
                total += sign * e * minor(row + 1, used | (1 << col))
            sign = -sign
        memo[used] = total
        return total
    return minor(0, 0)
