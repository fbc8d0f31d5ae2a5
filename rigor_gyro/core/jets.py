"""First-order forward-mode automatic differentiation in complex balls (jets), for centred forms over a box.

A :class:`Jet` is a value v and a tuple of gradient balls d = (d_1 .. d_m), one per direction. Feed a
function jets whose values are balls containing the inputs' ranges over a box X and whose gradients are the
partial derivatives of the inputs (unit vectors for free variables, or enclosures of dy/dx over X for an
input y(x) defined implicitly); every operation applies the chain rule in ball arithmetic. Then the output's
value contains f(x) and its gradient d_k contains df/dx_k, for every x in X: each ball operation is an
enclosure of the exact operation for every point of its operand balls, and the chain rule holds pointwise.

The mean value theorem then gives the centred form (:func:`centred`):

    f(x) in f(c) + sum_k D_k (x_k - c_k)   for every x in X   (D_k the gradient enclosures over X),

for real-valued f (apply it to the real and imaginary parts separately for a complex one: each part is
real-valued, and the gradient of Re f is Re of the gradient). Its width is first order in X's width times
|f'|, against the naive evaluation's, which also carries every dependency's overestimate.

Jets nest: a jet whose value and gradient entries are themselves jets (over the same directions) carries
second derivatives: for f evaluated on nested inputs (outer and inner gradients both unit vectors, inner
values the box), ``f.d[k].d[j]`` contains d2f/dx_k dx_j on the box. With the centre's first-order jet that
gives the second-order forms :func:`second_order_value` (f(c) + grad f(c) . (x - c) + (x - c)^T H (x - c) / 2,
Taylor with the Lagrange remainder) and :func:`second_order_gradient` (grad f(c) + H (x - c), the mean value
theorem for each partial derivative), whose excess is of third / second order in the box's width.

Guarantee: enclosures as stated, at the current working precision (python-flint's ``ctx.prec``).
Fails when: a division by a ball containing 0 gives non-finite balls (the caller checks ``is_finite``).

Example:
    >>> from flint import acb, arb
    >>> x = Jet.variable(acb(arb(1, 0.01)), 0, 1)          # x in [0.99, 1.01], dx/dx = 1
    >>> y = (x * x).exp()                                   # y = exp(x^2)
    >>> c = Jet.constant(acb(1)).__mul__(Jet.constant(acb(1))).exp()
    >>> f = centred(c.v.real, [y.d[0].real], [arb(0, 0.01)])
    >>> f.contains(arb("1.0201").exp()) and f.contains(arb("0.9801").exp())
    True
"""
from __future__ import annotations

from typing import Sequence

from flint import acb, arb

__all__ = ["Jet", "base", "centred", "jet_sum", "second_order_value", "second_order_gradient"]


def _c(x):
    return x if isinstance(x, (acb, Jet)) else acb(x)


def _re(x):
    return x.real if isinstance(x, Jet) else acb(x.real)


def base(x) -> acb:
    """The innermost value ball of a (possibly nested) jet, or the ball itself."""
    while isinstance(x, Jet):
        x = x.v
    return x


def _finite(x) -> bool:
    return x.is_finite()


class Jet:
    """A complex ball value with a tuple of complex ball gradients (see the module docstring)."""

    __slots__ = ("v", "d")

    def __init__(self, v, d: Sequence = ()):
        self.v = _c(v)
        self.d = tuple(_c(x) for x in d)

    @classmethod
    def constant(cls, v, m: int = 0) -> "Jet":
        return cls(v, (acb(0),) * m)

    @classmethod
    def variable(cls, v, k: int, m: int) -> "Jet":
        """The free variable number k of m (gradient the unit vector e_k)."""
        return cls(v, tuple(acb(1) if j == k else acb(0) for j in range(m)))

    @staticmethod
    def _lift(x, m: int) -> "Jet":
        return x if isinstance(x, Jet) else Jet(x, (acb(0),) * m)

    def _pair(self, other):
        o = Jet._lift(other, len(self.d))
        if len(o.d) != len(self.d):
            raise ValueError(f"jets of {len(self.d)} and {len(o.d)} directions")
        return o

    def __add__(self, other):
        o = self._pair(other)
        return Jet(self.v + o.v, [a + b for a, b in zip(self.d, o.d)])

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, [-a for a in self.d])

    def __sub__(self, other):
        return self + (-self._pair(other))

    def __rsub__(self, other):
        return self._pair(other) - self

    def __mul__(self, other):
        o = self._pair(other)
        return Jet(self.v * o.v, [a * o.v + self.v * b for a, b in zip(self.d, o.d)])

    __rmul__ = __mul__

    def __truediv__(self, other):
        o = self._pair(other)
        q = self.v / o.v
        return Jet(q, [(a - q * b) / o.v for a, b in zip(self.d, o.d)])

    def __rtruediv__(self, other):
        return self._pair(other) / self

    def __pow__(self, k: int):
        if not isinstance(k, int) or k < 0:
            raise ValueError("only non-negative integer powers")
        out = Jet.constant(acb(1), len(self.d))
        for _ in range(k):
            out = out * self
        return out

    def exp(self) -> "Jet":
        e = self.v.exp()
        return Jet(e, [e * a for a in self.d])

    @property
    def real(self) -> "Jet":
        """Re of the jet (value and gradients: the directions are real variables)."""
        return Jet(_re(self.v), [_re(a) for a in self.d])

    def conjugate(self) -> "Jet":
        return Jet(self.v.conjugate(), [a.conjugate() for a in self.d])

    def is_finite(self) -> bool:
        return _finite(self.v) and all(_finite(a) for a in self.d)


def jet_sum(xs, m: int) -> Jet:
    out = Jet.constant(acb(0), m)
    for x in xs:
        out = out + x
    return out


def centred(value_at_centre: arb, gradient: Sequence[arb], deviations: Sequence[arb]) -> arb:
    """f(c) + sum_k D_k (x_k - c_k): a ball containing f(x) for every x in the box, given f(c)'s ball, the
    gradient enclosures D_k over the box and the deviation balls x_k - c_k (module docstring)."""
    out = value_at_centre
    for g, dev in zip(gradient, deviations):
        out = out + g * dev
    return out


def _square(x: arb) -> arb:
    """x^2 for every point of the ball x, from its ends (>= 0; tighter than x * x, which reaches below 0)."""
    lo, hi = x.lower(), x.upper()
    out = (lo * lo).union(hi * hi)
    return out.union(arb(0)) if x.contains(0) else out


def _hessian(box: Jet, k: int, j: int) -> arb:
    return box.d[k].d[j].real if isinstance(box.d[k], Jet) else arb(0)


def second_order_value(centre: Jet, box: Jet, deviations: Sequence[arb]) -> arb:
    """f(x) for every x in the box, f real: f(c) + sum_k f_k(c) dev_k + sum_kj H_kj(box) dev_k dev_j / 2
    (``centre``: f's first-order jet at the centre point; ``box``: its nested jet over the box)."""
    out = centre.v.real
    m = len(deviations)
    for k in range(m):
        out = out + centre.d[k].real * deviations[k]
    for k in range(m):
        for j in range(m):
            dd = _square(deviations[k]) if k == j else deviations[k] * deviations[j]
            out = out + _hessian(box, k, j) * dd / 2
    return out


def second_order_gradient(centre: Jet, box: Jet, deviations: Sequence[arb]) -> list[arb]:
    """[df/dx_k for every x in the box] for f real: f_k(c) + sum_j H_kj(box) dev_j."""
    m = len(deviations)
    out = []
    for k in range(m):
        g = centre.d[k].real
        for j in range(m):
            g = g + _hessian(box, k, j) * deviations[j]
        out.append(g)
    return out
