"""Forward-mode automatic differentiation in Arb balls: a :class:`Dual` is an ``arb`` (its value) that also
carries a gradient, so that a formula written for balls (``a / (b - 1) + x.sqrt()``) encloses, evaluated
on Duals over a parameter box, both the formula's values and its partial derivatives over the whole box.

A Dual *is* an ``arb`` (a subclass): comparisons, ``certainly_*`` predicates and printing see its value, so
the same code that decides at a point runs unchanged on Duals. Arithmetic (+, -, *, /, integer powers,
``sqrt``) is overridden and propagates the gradient by the chain rule, each partial derivative a ball.

Guarantee: if every input Dual's value contains x_k and its gradient contains dx_k/dp_i for every
parameter value p in a set S (a constant's gradient is exactly 0), then the output's value contains f(p)
and its gradient entry i contains df/dp_i for every p in S, provided every gradient entry of the output is
finite. Finiteness certifies differentiability on S: a division's denominator ball excludes 0 (Arb returns
a non-finite ball otherwise), ``sqrt`` is differentiated only where its argument is certainly positive
(:class:`NotDifferentiable` otherwise).

Failure modes, loud by design: an operand that is a plain ``arb`` (not a Dual, not an exact int / fmpq /
Fraction) raises TypeError, because its gradient is unknown: any arb method not overridden here (``min``,
``union``, ``abs``, ...) returns a plain arb, and using that result again in Dual arithmetic raises rather
than treating it as a constant. Precision: the current working precision (``ctx.prec``).

Example:
    >>> from flint import arb
    >>> x = Dual(arb(2), {"x": arb(1)})
    >>> y = x * x + 3 / x
    >>> (y.grad["x"] - arb("3.25")).contains(0)      # 2x - 3/x^2 at x = 2
    True
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

__all__ = ["Dual", "NotDifferentiable", "constant", "variable", "gradient_finite"]


class NotDifferentiable(ArithmeticError):
    """A Dual operation whose derivative is not enclosed on the whole set (sqrt of a ball not certainly > 0)."""


def _exact(x) -> arb:
    if isinstance(x, bool):
        raise TypeError("a bool is not a number")
    if isinstance(x, int):
        return arb(x)
    if isinstance(x, fmpq):
        return arb(x)
    if isinstance(x, Fraction):
        return arb(fmpq(x.numerator, x.denominator))
    raise TypeError(f"operand {x!r} ({type(x).__name__}) in Dual arithmetic: only Duals and exact numbers (int, "
                    "fmpq, Fraction) are allowed; a plain arb's gradient is unknown")


def _lift(x) -> "Dual":
    return x if isinstance(x, Dual) else Dual(_exact(x), {})


def _add(g: dict, h: dict, sign: int = 1) -> dict:
    out = dict(g)
    for k, v in h.items():
        w = v if sign > 0 else -v
        out[k] = out[k] + w if k in out else w
    return out


def _scale(g: dict, c: arb) -> dict:
    return {k: v * c for k, v in g.items()}


class Dual(arb):
    """An arb value with ``grad``: {parameter name: ball of the partial derivative}; a missing name is an
    exactly zero partial derivative."""

    def __init__(self, value, grad: dict | None = None):
        arb.__init__(self, value)
        self.grad = dict(grad or {})

    @property
    def value(self) -> arb:
        """The value as a plain arb."""
        return arb(self)

    def __add__(self, other):
        o = _lift(other)
        return Dual(arb.__add__(self.value, o.value), _add(self.grad, o.grad))

    __radd__ = __add__

    def __sub__(self, other):
        o = _lift(other)
        return Dual(arb.__sub__(self.value, o.value), _add(self.grad, o.grad, -1))

    def __rsub__(self, other):
        return _lift(other).__sub__(self)

    def __neg__(self):
        return Dual(-self.value, {k: -v for k, v in self.grad.items()})

    def __pos__(self):
        return self

    def __mul__(self, other):
        o = _lift(other)
        u, v = self.value, o.value
        return Dual(u * v, _add(_scale(self.grad, v), _scale(o.grad, u)))

    __rmul__ = __mul__

    def __truediv__(self, other):
        o = _lift(other)
        u, v = self.value, o.value
        q = u / v
        # d(u/v) = (du - q dv) / v
        return Dual(q, _scale(_add(self.grad, _scale(o.grad, q), -1), 1 / v))

    def __rtruediv__(self, other):
        return _lift(other).__truediv__(self)

    def __pow__(self, n, modulo=None):
        if modulo is not None or isinstance(n, bool) or not isinstance(n, int) or n < 0:
            raise TypeError("Dual ** n: only a non-negative int exponent")
        if n == 0:
            return Dual(arb(1), {})
        out = self
        for _ in range(n - 1):
            out = out * self
        return out

    def sqrt(self):
        v = self.value
        if not self.grad:
            return Dual(v.sqrt(), {})
        if not (v > 0):
            raise NotDifferentiable("sqrt of a ball not certainly positive")
        s = v.sqrt()
        return Dual(s, _scale(self.grad, 1 / (2 * s)))


def constant(x) -> Dual:
    """A Dual with zero gradient: an exact number, or a ball that contains the value for every parameter in
    the set considered (then its derivative must truly be 0, i.e. it must not depend on the parameters)."""
    return Dual(x if isinstance(x, arb) else _exact(x), {})


def variable(name: str, value: arb) -> Dual:
    """The parameter ``name`` ranging over the ball ``value``: gradient {name: 1}."""
    return Dual(value, {name: arb(1)})


def gradient_finite(x) -> bool:
    """Whether a Dual's value and every gradient entry are finite (the Guarantee's condition)."""
    return isinstance(x, Dual) and x.value.is_finite() and all(v.is_finite() for v in x.grad.values())
