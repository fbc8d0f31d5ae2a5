"""Float and mpmath twins of the moment laws written in the scene (issue 42 part 2), for cross-checks only.

:class:`FloatExpressionLaw` evaluates the same parsed expression (and its exact symbolic derivative) as
:mod:`.moment_expr` with numpy, mpmath or math functions; :class:`FloatSplineLaw` evaluates the exact piece
coefficients of :mod:`.moment_table` in floats. They plug into :mod:`.approx` (``FloatGimbal(params, moment=...)``)
in place of the built-in float laws. Guarantee: none (floats never decide). Fails when: as the law's own
functions (a float nan or an exception where the expression is undefined).
"""
from __future__ import annotations

import bisect
import math

import mpmath
import numpy as np

from ...core.exact import parse_exact
from .moment_scene import scene_moment_law

__all__ = ["FloatExpressionLaw", "FloatSplineLaw", "float_scene_law"]

_NP = {"sin": np.sin, "cos": np.cos, "tan": np.tan, "exp": np.exp, "log": np.log, "sqrt": np.sqrt, "tanh": np.tanh,
       "atan": np.arctan, "abs": np.abs, "sign": np.sign}
_MP = {"sin": mpmath.sin, "cos": mpmath.cos, "tan": mpmath.tan, "exp": mpmath.exp, "log": mpmath.log,
       "sqrt": mpmath.sqrt, "tanh": mpmath.tanh, "atan": mpmath.atan, "abs": mpmath.fabs, "sign": mpmath.sign}
_MATH = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "exp": math.exp, "log": math.log, "sqrt": math.sqrt,
         "tanh": math.tanh, "atan": math.atan, "abs": abs, "sign": lambda v: math.copysign(1.0, v) if v else 0.0}


def _kit(lib):
    if lib.name == "mpmath":
        return _MP, (lambda q: mpmath.mpf(q.numerator) / q.denominator)
    if lib.name == "float":
        return _NP, (lambda q: q.numerator / q.denominator)
    return _MATH, (lambda q: q.numerator / q.denominator)


class FloatExpressionLaw:
    """The expression law of a scene in floats / mpmath (the interface of approx's ``_Law``)."""

    odd = True          # the ball law exists only when the formula is certified odd

    def __init__(self, law):
        self.law = law
        self.name = law.name

    def _ev(self, e, a, x, lib):
        fns, num = _kit(lib)
        env = {k: num(v) for k, v in self.law.params.items()}
        r = e.evaluate({**env, "a": a, "x2": x}, number=num, functions=fns)
        return r * lib.one_like(x) if lib.name == "float" else r

    def f(self, a, x, lib):
        return self._ev(self.law.expr, a, x, lib)

    def df(self, a, x, lib):
        return self._ev(self.law.dexpr, a, x, lib)

    def f_over_x(self, a, x, lib):
        if lib.name == "float":
            x = np.asarray(x, dtype=float)
            safe = np.where(x == 0, 1.0, x)
            return np.where(x == 0, self.df(a, 0.0 * x, lib), self.f(a, safe, lib) / safe)
        return self.df(a, x, lib) if x == 0 else self.f(a, x, lib) / x

    def G(self, a, A0, C0, x, lib):
        return None

    def q(self, a, A0, C0, x, lib):
        return None


class FloatSplineLaw(FloatExpressionLaw):
    """The spline law of a measured table in floats / mpmath, from its exact piece coefficients."""

    def __init__(self, law):
        self.law = law
        self.name = law.name
        self.starts = [float(s) for s in law.starts]
        self.pieces = law.pieces

    def _piece(self, x: float):
        return self.pieces[bisect.bisect_right(self.starts, x)]

    def _poly(self, x, lib, order: int):
        def one(v):
            _, _, b, co = self._piece(float(v))
            c = [mpmath.mpf(q.numerator) / q.denominator if lib.name == "mpmath" else float(q) for q in co]
            u = v - (mpmath.mpf(b.numerator) / b.denominator if lib.name == "mpmath" else float(b))
            if order == 0:
                return c[0] + u * (c[1] + u * (c[2] + u * c[3]))
            if order == 1:
                return c[1] + u * (2 * c[2] + 3 * c[3] * u)
            return 2 * c[2] + 6 * c[3] * u
        if lib.name == "float":
            arr = np.asarray(x, dtype=float)
            return np.vectorize(one, otypes=[float])(arr) if arr.ndim else one(float(arr))
        return one(x)

    def f(self, a, x, lib):
        return self._poly(x, lib, 0)

    def df(self, a, x, lib):
        return self._poly(x, lib, 1)


def float_scene_law(params: dict, moment: dict):
    """The float twin of the law a scene writes in its [moment] table (``params['moment']`` is "expression" or
    "table")."""
    law = scene_moment_law(params["moment"], moment, parse_exact(params["x2_star"], "x2_star"))
    return FloatSplineLaw(law) if hasattr(law, "pieces") else FloatExpressionLaw(law)
