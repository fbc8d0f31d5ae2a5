"""The characteristic polynomial of a ``[system]`` model as exact polynomials in chosen parameters (those a box
tolerates), for the box rigour (:mod:`.system_boxes`).

Every entry is a rational function of the parameters (+ - * / and integer powers of exact rationals), read
exactly as numerator / denominator over ``fmpq_mpoly`` (python-flint's multivariate polynomials). Row i of
lambda^2 M + lambda (G + D) + K is multiplied by L_i, the product of its entries' distinct denominators, so that
every entry is a polynomial, and the determinant is expanded along rows (Laplace, memoised):

    det(scaled) = (prod_i L_i) det(lambda^2 M + lambda (G + D) + K) = sum_k c_k(p) lambda^k,

each c_k an exact polynomial in the parameters. The roots in lambda are those of P wherever every L_i is nonzero
(the caller checks that on its box); identically vanishing coefficients are decided exactly (a polynomial that
is 0), never from balls.

Guarantee: exact (no rounding). :func:`mpoly_ball` returns a ball containing the polynomial's value for every
point of the parameter balls (term by term). Fails when: an entry divides by an identically zero polynomial
(ZeroDivisionError; the point validation has refused a division by zero at the midpoint already).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, fmpq, fmpq_mpoly_ctx

from .system_model import SystemModel

__all__ = ["RationalFunction", "characteristic_mpolys", "mpoly_ball", "entry_functions", "same_function"]


@dataclass(frozen=True)
class RationalFunction:
    """num / den, both ``fmpq_mpoly`` of one context (den never the zero polynomial); ``guards``: every divisor
    met on the way (non-constant), which must be nonzero for the expression written to have a value, even where
    the function simplifies it away ((1/a)^0 - 1 is the function 0, with no value at a = 0: review)."""

    num: object
    den: object
    guards: tuple = field(default=(), compare=False)

    def __add__(self, o):
        o = _lift(o, self)
        g = self.guards + o.guards
        if self.den == o.den:
            return RationalFunction(self.num + o.num, self.den, g)
        return RationalFunction(self.num * o.den + o.num * self.den, self.den * o.den, g)

    __radd__ = __add__

    def __neg__(self):
        return RationalFunction(-self.num, self.den, self.guards)

    def __sub__(self, o):
        return self + (-_lift(o, self))

    def __rsub__(self, o):
        return _lift(o, self) + (-self)

    def __mul__(self, o):
        o = _lift(o, self)
        return RationalFunction(self.num * o.num, self.den * o.den, self.guards + o.guards)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = _lift(o, self)
        if o.num.is_zero():
            raise ZeroDivisionError("division by an identically zero rational function")
        extra = () if o.num.is_constant() else (o.num,)
        return RationalFunction(self.num * o.den, self.den * o.num, self.guards + o.guards + extra)

    def __rtruediv__(self, o):
        return _lift(o, self) / self

    def __pow__(self, n: int):
        out = RationalFunction(self.num.context().constant(1), self.num.context().constant(1), self.guards)
        for _ in range(n):
            out = out * self
        return out


def _lift(x, like: RationalFunction) -> RationalFunction:
    if isinstance(x, RationalFunction):
        return x
    ctx = like.num.context()
    q = x if isinstance(x, fmpq) else fmpq(Fraction(x).numerator, Fraction(x).denominator)
    return RationalFunction(ctx.constant(q), ctx.constant(1))


def _environment(model: SystemModel, names: tuple[str, ...], fixed: dict[str, Fraction]):
    """(context, env, number): the parameters in ``names`` as the variables of an ``fmpq_mpoly`` context, the
    others at their exact values in ``fixed``, and the rational defs (the only ones matrix entries may use), as
    RationalFunctions; ``number`` lifts an exact constant. ZeroDivisionError when a def divides by an identically
    zero expression."""
    ctx = fmpq_mpoly_ctx.get(tuple(names), "lex")
    one = ctx.constant(1)
    env: dict = {}
    for k, g in zip(names, ctx.gens()):
        env[k] = RationalFunction(g, one)
    for k, v in fixed.items():
        if k not in env:
            env[k] = RationalFunction(ctx.constant(fmpq(v.numerator, v.denominator)), one)
    number = lambda q: RationalFunction(ctx.constant(fmpq(q.numerator, q.denominator)), one)
    for name, e in model.defs:
        if name in model.values:          # the rational defs (the matrices use no other)
            env[name] = e.evaluate(env, number=number)
    return ctx, env, number


def entry_functions(model: SystemModel, names: tuple[str, ...], fixed: dict[str, Fraction], exprs) -> list:
    """The entries ``exprs`` (parsed matrix entries) as exact RationalFunctions of the parameters ``names`` (the
    others at their values in ``fixed``): two spellings of one function give equal functions
    (:func:`same_function`). ZeroDivisionError when an entry divides by an identically zero expression."""
    ctx, env, number = _environment(model, names, fixed)
    return [e.evaluate(env, number=number) for e in exprs]


def same_function(a: RationalFunction, b: RationalFunction, sign: int = 1) -> bool:
    """Whether a = sign * b identically (exactly: a.num b.den - sign b.num a.den is the zero polynomial). On a box
    with interior this is the same as a = sign * b at every point of it where both are defined."""
    return (a.num * b.den - b.num * a.den * sign).is_zero()


def characteristic_mpolys(model: SystemModel, names: tuple[str, ...], fixed: dict[str, Fraction]):
    """(context, [c_0, ..., c_2n], [L_1, ..., L_n]): the coefficients of det of the row-scaled matrix polynomial
    as exact polynomials in ``names`` (the other parameters at their exact values in ``fixed``), and the row
    factors L_i (see the module docstring) followed by every other divisor an entry met (its ``guards``): the
    caller needs all of them nonzero on its box."""
    ctx, env, number = _environment(model, names, fixed)
    one = ctx.constant(1)
    zero = RationalFunction(ctx.constant(0), one)

    def entry(key: str, i: int, j: int) -> RationalFunction:
        rows = getattr(model, key)
        return zero if rows is None else rows[i][j].evaluate(env, number=number)
    n = model.n
    matrix, factors = [], []
    for i in range(n):
        row = [(entry("K", i, j), entry("G", i, j) + entry("D", i, j), entry("M", i, j)) for j in range(n)]
        dens = []
        for cell in row:
            for rf in cell:
                if not rf.num.is_zero() and not rf.den.is_constant() and rf.den not in dens:
                    dens.append(rf.den)
        L = one
        for d in dens:
            L = L * d
        scaled = []
        for cell in row:
            coeffs = []
            for rf in cell:
                if rf.num.is_zero():
                    coeffs.append(ctx.constant(0))
                    continue
                other = one
                skipped = False
                for d in dens:
                    if d == rf.den and not skipped:
                        skipped = True
                        continue
                    other = other * d
                # rf.den is one of dens (then L / den = other) or a constant (then L / den = L / c)
                coeffs.append(rf.num * other if skipped else rf.num * L * (1 / rf.den.leading_coefficient()))
            scaled.append(coeffs)
        matrix.append(scaled)
        factors.append(L)
    memo: dict[int, list] = {}

    def minor(row: int, used: int) -> list:
        if row == n:
            return [one]
        if used in memo:
            return memo[used]
        total: list = []
        sign = 1
        for col in range(n):
            if used >> col & 1:
                continue
            e = matrix[row][col]
            if any(not c.is_zero() for c in e):
                sub = minor(row + 1, used | (1 << col))
                prod = [ctx.constant(0)] * (len(e) + len(sub) - 1)
                for a, x in enumerate(e):
                    if x.is_zero():
                        continue
                    for b, y in enumerate(sub):
                        prod[a + b] = prod[a + b] + x * y
                total = total + [ctx.constant(0)] * (len(prod) - len(total))
                for k, c in enumerate(prod):
                    total[k] = total[k] + c if sign > 0 else total[k] - c
            sign = -sign
        memo[used] = total
        return total
    c = minor(0, 0)
    c = c + [ctx.constant(0)] * (2 * n + 1 - len(c))
    # every divisor an entry met must be nonzero too (not only the denominators left after simplifying): checked
    # by the caller with the row factors, never used in the scaling
    for key in ("M", "G", "D", "K"):
        rows = getattr(model, key)
        for i in range(n if rows is not None else 0):
            for j in range(n):
                for g in rows[i][j].evaluate(env, number=number).guards:
                    if not g.is_constant() and g not in factors:
                        factors.append(g)
    return ctx, c, factors


def mpoly_ball(p, balls: list[arb]) -> arb:
    """A ball containing p(x) for every x in the balls (one per variable of p's context), term by term."""
    out = arb(0)
    for exps, c in p.to_dict().items():
        t = arb(c)
        for x, e in zip(balls, exps):
            if e:
                t *= x ** e
        out += t
    return out
