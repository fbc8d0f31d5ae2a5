"""Where a ``[system]`` bracket bound certainly has no value at the scene's parameters (bad input, exit 2):
``1/sqrt(a - 1)`` at a = 1, ``1/(sqrt(2)^2 - 2)``. A ball that is not finite at every precision tried is no
proof of that (``1/(sqrt(2) - 1.41421356...)`` needs more bits); this module looks for a certain reason with
:func:`rigor_gyro.core.expression_domain.first_undefined` (the expression code's own evaluator, guarded), on
values that stay exact wherever they can:

* the parameters and the rational defs are exact rationals (``fmpq``), and so is every + - * / ^ of them;
* sqrt of an exact rational square is that exact rational (sqrt(0) = 0, sqrt(9/4) = 3/2); sqrt of another
  exact rational r >= 0 is a ball that remembers r, so that an even power of it is the exact r^k
  (sqrt(2)^2 - 2 is exactly 0); anything else is an Arb ball at the working precision.

A finding is then certain (first_undefined's rule): a divisor or a negative power's base that is an exact 0.
A sqrt of a certainly negative number is not looked for here: the claim refutes it (no real value,
:class:`.system_model.NotRealBound`), as before. The defs a bound uses are evaluated first, in order (a def
that only another bracket uses never decides this one).

Guarantee: a ParameterError is raised only with such a proof. Nothing found means "no certain reason", never
"finite": the claim then stays as the balls decide it.
"""
from __future__ import annotations

from math import isqrt

from flint import arb, fmpq

from ...core.errors import ParameterError
from ...core.expression_domain import first_undefined

__all__ = ["check_bracket_values", "bracket_without_value"]


class _Surd(arb):
    """sqrt(r) for an exact rational r > 0 that is not a square: a ball, with r kept (``square``)."""

    square: fmpq


def _number(q) -> fmpq:
    return fmpq(q.numerator, q.denominator)


def _sqrt(x):
    if isinstance(x, fmpq):
        if x >= 0:
            p, q = int(x.p), int(x.q)
            rp, rq = isqrt(p), isqrt(q)
            if rp * rp == p and rq * rq == q:
                return fmpq(rp, rq)
            s = _Surd(arb(x).sqrt())
            s.square = x
            return s
        return arb(x).sqrt()            # nan (no real value): never an exact 0, so never a finding
    return x.sqrt()


def _power(x, n: int):
    if isinstance(x, _Surd) and n % 2 == 0:
        return x.square ** (n // 2)     # exact: r > 0, any sign of n
    if n < 0:
        return 1 / (x ** -n)           # a base exactly 0 was named by the guard before this
    return x ** n


def bracket_without_value(model, j: int) -> str | None:
    """Why a bound of bracket j (1-based) of a validated :class:`.system_model.SystemModel` certainly has no
    value at the scene's parameters, naming the bound (or the def it uses), or None (module docstring)."""
    bounds = model.brackets[j - 1]
    env: dict = {k: _number(x.rational) for k, x in model.params.items()}
    for name, e in model.defs_needed(bounds):
        found = first_undefined(e.tree, env, _number, {"sqrt": _sqrt}, _power, domains={})
        if found is not None:
            return f"the def {name} = {e.text.strip()!r} that it uses has no value at the scene's parameters: {found[1]}"
        env[name] = e.evaluate(env, _number, {"sqrt": _sqrt}, _power)
    for side, e in zip(("lower", "upper"), bounds):
        found = first_undefined(e.tree, env, _number, {"sqrt": _sqrt}, _power, domains={})
        if found is not None:
            return f"its {side} bound {e.text!r} has no finite value at the scene's parameters: {found[1]}"
    return None


def check_bracket_values(model) -> None:
    """ParameterError (exit 2) naming the first bracket with a bound that certainly has no value (a division by
    an exact 0: ``1/sqrt(a - 1)`` at a = 1)."""
    for j in range(1, len(model.brackets) + 1):
        why = bracket_without_value(model, j)
        if why is not None:
            raise ParameterError(f"[system] brackets[{j}]: {why}; write a bound with a finite value at these "
                                 "parameters")
