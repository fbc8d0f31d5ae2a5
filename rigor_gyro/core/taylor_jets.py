"""Taylor coefficients of the solutions of x' = f(x) in Arb balls, with first derivatives in the initial values.

A :class:`Grad` is a value and a tuple of partial derivatives (one per direction); its entries may be ``arb``
balls or ``arb_series`` (truncated Taylor series in t). Every operation applies the exact rule of calculus in
ball arithmetic (sum, product, quotient, integer power, sin, cos, exp, sqrt), so a vector field written with
+, -, *, /, ** and the methods ``sin``, ``cos``, ``sin_cos``, ``exp``, ``sqrt`` runs unchanged on balls, on
series and on :class:`Grad` of either.

:func:`taylor_coefficients` computes the Taylor coefficients in t of the solution x(t; x0) of x' = f(x) with
x(0) = x0 by Picard iteration on truncated series (x^(j+1) = x0 + int_0^t f(x^(j)): iteration j makes the
coefficient of t^j correct, and the series is kept j + 1 terms long), for every x0 in the ball vector ``x0``.
With ``gradients=True`` it also computes the coefficients of the Jacobian dx(t)/dx0 (the variational equation
V' = Df(x) V, V(0) = I, carried as the partials of a :class:`Grad` seeded with the unit vectors).

Guarantee: the k-th returned coefficient contains x^(k)(0)/k! (resp. d/dx0 of it) for every x0 in the balls,
at the current working precision. The series length is set with
:func:`rigor_gyro.core.balls.series_length` and every coefficient read through
:func:`rigor_gyro.core.balls.series_coefficients`, so python-flint's silent ``ctx.cap`` truncation raises
:class:`~rigor_gyro.core.balls.SeriesTruncated` instead of dropping a coefficient (FLINT-NOTES, the cap trap).

Fails when: f divides by a ball containing 0 or takes sqrt of one reaching below 0: the coefficients come back
non-finite (the caller checks ``is_finite`` and shrinks its step or its box).

Example:
    >>> from flint import arb, fmpq
    >>> from rigor_gyro.core.balls import working_precision
    >>> with working_precision(64):
    ...     c = taylor_coefficients(lambda x: [x[1], -x[0]], [arb(0), arb(1)], 5)   # x = sin t
    ...     [(c.values[0][k] - v).contains(0) for k, v in enumerate((0, 1, 0, fmpq(-1, 6), 0, fmpq(1, 120)))]
    [True, True, True, True, True, True]
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Sequence

from flint import arb, arb_series

from .balls import series_coefficients, series_length

__all__ = ["Grad", "TaylorCoefficients", "taylor_coefficients", "Field"]

#: a vector field: a list of n state entries (arb, arb_series or Grad) -> a list of n entries of the same kinds
Field = Callable[[list], Sequence]


def _const(x):
    return x if isinstance(x, (arb, arb_series)) else arb(x)


class Grad:
    """A value with its partial derivatives in ``len(d)`` directions (entries arb or arb_series)."""

    __slots__ = ("v", "d")

    def __init__(self, v, d: Sequence = ()):
        self.v = _const(v)
        self.d = tuple(d)

    def __add__(self, o):
        if isinstance(o, Grad):
            return Grad(self.v + o.v, [a + b for a, b in zip(self.d, o.d)])
        return Grad(self.v + o, self.d)

    __radd__ = __add__

    def __neg__(self):
        return Grad(-self.v, [-a for a in self.d])

    def __sub__(self, o):
        if isinstance(o, Grad):
            return Grad(self.v - o.v, [a - b for a, b in zip(self.d, o.d)])
        return Grad(self.v - o, self.d)

    def __rsub__(self, o):
        return Grad(o - self.v, [-a for a in self.d])

    def __mul__(self, o):
        if isinstance(o, Grad):
            return Grad(self.v * o.v, [a * o.v + self.v * b for a, b in zip(self.d, o.d)])
        return Grad(self.v * o, [a * o for a in self.d])

    __rmul__ = __mul__

    def __truediv__(self, o):
        if isinstance(o, Grad):
            inv = 1 / o.v
            q = self.v * inv
            return Grad(q, [(a - q * b) * inv for a, b in zip(self.d, o.d)])
        inv = 1 / _const(o)
        return Grad(self.v * inv, [a * inv for a in self.d])

    def __rtruediv__(self, o):
        inv = 1 / self.v
        q = o * inv
        return Grad(q, [-(q * inv) * a for a in self.d])

    def __pow__(self, n: int):
        if not isinstance(n, int) or n < 0:
            raise ValueError("Grad supports only non-negative integer powers")
        if n == 0:
            return Grad(arb(1), [0 * a for a in self.d])
        if n == 1:
            return self
        p = self.v ** (n - 1)
        return Grad(p * self.v, [(n * p) * a for a in self.d])

    def sin_cos(self):
        s, c = self.v.sin_cos()
        return Grad(s, [c * a for a in self.d]), Grad(c, [-(s * a) for a in self.d])

    def sin(self):
        return self.sin_cos()[0]

    def cos(self):
        return self.sin_cos()[1]

    def exp(self):
        e = self.v.exp()
        return Grad(e, [e * a for a in self.d])

    def sqrt(self):
        r = self.v.sqrt()
        h = 1 / (2 * r)
        return Grad(r, [h * a for a in self.d])


@dataclass
class TaylorCoefficients:
    """values[i][k] contains the coefficient of t^k of x_i(t); jacobian[i][j][k] that of dx_i/dx0_j (empty
    when not asked)."""

    order: int
    values: list[list[arb]]
    jacobian: list[list[list[arb]]]

    def is_finite(self) -> bool:
        return all(c.is_finite() for row in self.values for c in row) and \
            all(c.is_finite() for row in self.jacobian for col in row for c in col)


def _series(coeffs: list[arb]) -> arb_series:
    return arb_series(coeffs, prec=len(coeffs))


def _coeffs(x, n: int) -> list[arb]:
    """The first n coefficients of a series, ball or integer entry (a constant: zeros after the first)."""
    if isinstance(x, arb_series):
        return series_coefficients(x, n)
    return [_const(x)] + [arb(0)] * (n - 1)


def taylor_coefficients(field: Field, x0: Sequence[arb], order: int, gradients: bool = False,
                        seed: Sequence[Sequence[arb]] | None = None) -> TaylorCoefficients:
    """Taylor coefficients of order 0..``order`` of x(t) with x' = field(x), x(0) in the balls ``x0`` (module
    docstring). ``gradients``: also those of dx(t)/dx0 (V(0) = I), or of V(t) with V(0) = ``seed`` (a matrix
    of balls, rows the state components) when given."""
    n = len(x0)
    if order < 0:
        raise ValueError("order must be >= 0")
    m = n if gradients else 0
    if gradients and seed is None:
        seed = [[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)]
    vals = [[_const(x)] for x in x0]
    jac = [[[seed[i][j]] for j in range(m)] for i in range(n)]
    with series_length(order + 2):
        for j in range(1, order + 1):
            # the state as series of length j (coefficients 0 .. j-1 already correct)
            xs = [Grad(_series(vals[i]), [_series(jac[i][q]) for q in range(m)]) if m else _series(vals[i])
                  for i in range(n)]
            fx = list(field(xs))
            if len(fx) != n:
                raise ValueError(f"the field returned {len(fx)} components for a state of {n}")
            for i in range(n):
                fi = fx[i]
                fv = fi.v if isinstance(fi, Grad) else fi
                c = _coeffs(fv, j)
                vals[i].append(c[j - 1] / j)
                for q in range(m):
                    dq = fi.d[q] if isinstance(fi, Grad) and fi.d else arb(0)
                    jac[i][q].append(_coeffs(dq, j)[j - 1] / j)
    return TaylorCoefficients(order, vals, jac)
