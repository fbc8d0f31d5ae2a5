"""Where a parsed expression (:mod:`rigor_gyro.core.expressions`) certainly has no value: a division by a
denominator that is exactly 0, a negative power of an exact 0, or a function of an argument certainly outside
its real domain (sqrt of a negative number, log of a number <= 0). Callers refuse such input (bad input,
naming the sub-expression) instead of carrying a non-finite ball to a later, misleading message.

Two tests, both certain and cheap:

* :func:`first_undefined`: the expression evaluated once on the caller's values (exact rationals or Arb
  balls), each division, negative power and domain-restricted call checked on its operand's value. A ball says
  "no value" only when it is EXACTLY 0 (radius 0, midpoint 0: the true value is certainly 0) or lies entirely
  outside the function's domain; a ball that merely contains 0 or overlaps the domain's boundary is no evidence
  and is passed over.
* :func:`polynomial_poles`: each denominator (and base of a negative power) that is a polynomial in one name
  with exact rational coefficients is expanded exactly; the zero polynomial, or its exact rational roots (FLINT's
  factorisation over Q, degree at most :data:`MAX_POLE_DEGREE`, coefficients of at most
  :data:`MAX_POLE_HEIGHT_BITS` bits), are points where the expression has no value.

Guarantee: every finding is a proof that the expression has no (real) value at the point named, for every
value of the names the caller left unknown (balls of infinite radius, or names outside the polynomial). None
means "nothing found", never "defined everywhere".
"""
from __future__ import annotations

from fractions import Fraction
from typing import Any, Callable, Mapping

from flint import arb, fmpq, fmpq_poly

from .expressions import Expr

__all__ = ["first_undefined", "polynomial_poles", "unparse", "ARB_DOMAINS", "MAX_POLE_DEGREE", "MAX_POLE_HEIGHT_BITS"]

#: a denominator polynomial of higher degree is not factored (the test stays cheap; nothing is claimed)
MAX_POLE_DEGREE = 64
#: nor one whose integer numerator has coefficients of more bits: FLINT's factorisation of a structured
#: polynomial with huge coefficients (1e400 (x2 + 1e-400)^64 + 1: 85000 bits) takes seconds, and it runs before
#: any time limit applies; below this cap it takes milliseconds
MAX_POLE_HEIGHT_BITS = 4096


def _certainly_negative(v) -> bool:
    return bool(v < 0) if isinstance(v, (arb, Fraction, int, fmpq)) else False


def _certainly_nonpositive(v) -> bool:
    return bool(v <= 0) if isinstance(v, (arb, Fraction, int, fmpq)) else False


#: function -> (test "the argument is certainly outside the real domain", the domain in words)
ARB_DOMAINS: dict[str, tuple[Callable[[Any], bool], str]] = {
    "sqrt": (_certainly_negative, "x >= 0"),
    "log": (_certainly_nonpositive, "x > 0"),
}


def exactly_zero(v) -> bool:
    """True only when ``v`` is certainly 0: an exact rational 0 or an Arb ball of radius 0 centred at 0."""
    if isinstance(v, arb):
        return v.is_zero()
    if isinstance(v, (Fraction, int, fmpq)) and not isinstance(v, bool):
        return v == 0
    return False


def _show(v) -> str:
    if isinstance(v, arb):
        if v.rad().is_zero() and v.mid().is_finite():
            m, e = v.mid().man_exp()
            return str(int(m) * Fraction(2) ** int(e))
        return v.str(6, radius=True)
    return str(v)


_PRECEDENCE = {"+": 1, "-": 1, "*": 2, "/": 2, "neg": 3, "^": 4}


def unparse(t: tuple, outer: int = 0) -> str:
    """A tree as text in the grammar (parentheses only where precedence needs them)."""
    op = t[0]
    if op == "num":                      # a non-integer reads as a quotient: parenthesised where "/" would be
        q = t[1]
        if q < 0 or (q.denominator != 1 and _PRECEDENCE["/"] < outer):
            return f"({q})"
        return str(q)
    if op == "name":
        return t[1]
    if op == "call":
        return f"{t[1]}({', '.join(unparse(a) for a in t[2])})"
    if op == "neg":
        s = "-" + unparse(t[1], _PRECEDENCE["neg"])
        p = _PRECEDENCE["neg"]
    elif op == "^":
        s = f"{unparse(t[1], 5)}^{t[2] if t[2] >= 0 else f'({t[2]})'}"
        p = _PRECEDENCE["^"]
    else:
        p = _PRECEDENCE[op]
        right = unparse(t[2], p + 1 if op in "-/" else p)
        s = f"{unparse(t[1], p)} {op} {right}" if op in "+-" else f"{unparse(t[1], p)}{op}{right}"
    return f"({s})" if p < outer else s


def first_undefined(tree: tuple, env: Mapping[str, Any], number: Callable[[Fraction], Any],
                    functions: Mapping[str, Callable], power: Callable[[Any, int], Any],
                    domains: Mapping[str, tuple[Callable[[Any], bool], str]] = ARB_DOMAINS,
                    at: str = "") -> tuple[tuple, str] | None:
    """The first operation (in evaluation order) of ``tree`` with certainly no value at ``env``: (the
    sub-tree, the reason in words: "divides by D, which is exactly 0", "sqrt(u): its argument is -1, certainly
    outside sqrt's domain x >= 0"; ``at``, e.g. " at x2 = 0", follows the value), or None. The values are
    computed with ``number``, ``functions`` and ``power`` as :meth:`Expr.evaluate` does; see the module
    docstring for what counts as certain."""
    class _Found(Exception):
        pass

    def guard(t, values):
        if t[0] == "call":
            test = domains.get(t[1])
            if test is not None and test[0](values[0]):
                arg, val = unparse(t[2][0]), _show(values[0])
                value = f"is {val}" if arg == val else f"{arg} is {val}{at}"
                raise _Found(t, f"{unparse(t)} has no real value: its argument {value}, certainly outside "
                                f"{t[1]}'s domain {test[1]}")
        elif t[0] == "^":
            if t[2] < 0 and exactly_zero(values[0]):
                raise _Found(t, f"{unparse(t)} divides by {unparse(t[1])}, which is exactly 0{at}")
        elif exactly_zero(values[1]):
            raise _Found(t, f"it divides by {unparse(t[2])}, which is exactly 0{at}")
    try:
        Expr(tree, "", "").evaluate(env, number, functions, power, guard=guard)
    except _Found as found:
        return found.args[0], found.args[1]
    return None


def _polynomial(t: tuple, name: str, consts: Mapping[str, Fraction]) -> fmpq_poly | None:
    """``t`` as an exact polynomial in ``name`` (the names in ``consts`` exact rationals), or None when it is
    not one (another name, a function, a division by a non-constant, a negative power)."""
    op = t[0]
    if op == "num":
        return fmpq_poly([fmpq(t[1].numerator, t[1].denominator)])
    if op == "name":
        if t[1] == name:
            return fmpq_poly([0, 1])
        q = consts.get(t[1])
        return None if q is None else fmpq_poly([fmpq(q.numerator, q.denominator)])
    if op == "neg":
        p = _polynomial(t[1], name, consts)
        return None if p is None else -p
    if op == "^":
        p = _polynomial(t[1], name, consts)
        return None if p is None or t[2] < 0 else p ** t[2]
    if op in "+-*/":
        a, b = _polynomial(t[1], name, consts), _polynomial(t[2], name, consts)
        if a is None or b is None:
            return None
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if b.degree() != 0:                                # only a division by a nonzero constant
            return None
        return a / b[0]
    return None


def polynomial_poles(tree: tuple, name: str, consts: Mapping[str, Fraction]) -> list[tuple[tuple, Fraction | None]]:
    """For each denominator (or base of a negative power) of ``tree`` that is a polynomial D in ``name`` with
    exact rational coefficients (module docstring): (D's sub-tree, None) when D is the zero polynomial (no
    value for any ``name``), and (D's sub-tree, r) for each exact rational root r of D (no value at
    ``name`` = r). Degrees above :data:`MAX_POLE_DEGREE` are skipped."""
    out: list[tuple[tuple, Fraction | None]] = []

    def visit(t):
        op = t[0]
        if op in ("num", "name"):
            return
        if op == "call":
            for a in t[2]:
                visit(a)
            return
        if op in ("neg", "^"):
            visit(t[1])
            if op == "^" and t[2] < 0:
                check(t[1])
            return
        visit(t[1])
        visit(t[2])
        if op == "/":
            check(t[2])

    def check(d):
        p = _polynomial(d, name, consts)
        if p is None:
            return
        if p.is_zero():
            out.append((d, None))
            return
        if not 1 <= p.degree() <= MAX_POLE_DEGREE or p.numer().height_bits() > MAX_POLE_HEIGHT_BITS:
            return
        for factor, _ in p.factor()[1]:
            if factor.degree() == 1:
                r = -factor[0] / factor[1]
                out.append((d, Fraction(int(r.p), int(r.q))))
    visit(tree)
    return out
