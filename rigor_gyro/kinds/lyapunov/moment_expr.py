"""A moment law written as an expression in the scene's ``[moment]`` table (issue 42, part 2).

A scene of kind ``lyapunov`` with ``moment = "expression"`` gives its law as

    [moment]
    f = "a*sin(x2) + b*x2^3"      # over + - * / ^ (integer exponents), sin cos tan exp log sqrt tanh atan abs
    b = "0.05"                    # its own named parameters: exact decimals (or constant expressions)

The names f may use are ``x2``, the scene's parameter ``a`` (so a tolerance box over ``a`` varies the law) and
the table's own parameters. The text is parsed by :mod:`rigor_gyro.core.expressions` (a grammar of its own, never
``eval``); f' is its exact symbolic derivative (:func:`rigor_gyro.core.expressions.derivative`). Both are
evaluated on ``arb`` balls, :class:`.model.Dual` numbers (forward mode: f on a Dual gives f', f' on a Dual gives
f''), ``arb_series`` (the equilibria's interval Newton) and, inside the quadrature of G, ``acb`` balls with
Arb's analyticity flag (log, sqrt, atan and abs refuse a ball touching their branch cut or kink, so the
integration's error bound stays rigorous).

What the law certifies before it is used (:func:`expression_law`, bad input otherwise, naming the entry):

* f has a value on |x2| <= x2* as far as cheap certain tests see (:mod:`rigor_gyro.core.expression_domain`):
  a denominator that is the zero polynomial in x2 or has an exact rational root in [-x2*, x2*], or, at the exact
  points x2 = 0 and a dyadic x2 in (0, x2*], a denominator that is an exactly-zero ball or sqrt/log of an
  argument certainly outside its domain, is refused naming the sub-expression and the point (a ball merely
  containing 0 is never a reason);
* f is not a constant: exact evaluation with x2 a real of unknown value (``0*x2``) giving one rational for
  every x2 is refused (the method needs x2 f(x2) > 0 for 0 < |x2| <= x2*);
* f(0) = 0 exactly, by exact evaluation at x2 = 0 (rationals, and sin 0 = 0, cos 0 = 1, exp 0 = 1, log 1 = 0,
  ...; the scene's ``a`` a real of unknown value): a value certainly nonzero, or one the exact evaluation
  cannot show to be 0, is refused;
* f is odd, read off the formula (:func:`rigor_gyro.core.expressions.parity`). The kind's claims use the
  symmetry x2 -> -x2 that an odd law gives (V(-x) = V(x): v_positive and the cylinder bounds run over
  [0, x2*]), so a law not certified odd is refused (a bad-input message naming f), never assumed odd;
* x2 f(x2) > 0 is not assumed either: the claim v_positive certifies f(x2)/x2 > 0 on [0, x2*] (undecided if
  it fails there).

The exact zeros of f at x2 in {-pi, -pi/2, 0, pi/2, pi} (:meth:`ExpressionMoment.zeros_over_pi`) come from the
same exact evaluation (sin(k pi) = 0, cos(pi/2) = 0, ...), so the equilibria of ``a*sin(x2)`` at +-pi are named.

f(x)/x through 0: the Taylor form c1 + x (c2 + x (c3 + x c4(hull(0, x)))), c_k = f^(k)(0)/k! from an
``arb_series`` at 0 and c4 over the hull (Lagrange remainder; the series cap is set for the length read), and
for x away from 0 intersected with f(x)/x directly. G(x) = int_0^x cos(s) f(s) / (A0 - C0 sin^2 s) ds by
``acb.integral`` at a point (or thin ball) x.

Guarantee: every method returns a ball containing the exact value for every argument in its balls, at the
current precision (set by the caller). Fails when: an argument leaves f's domain (log of a ball reaching 0,
a pole of tan): the result is a non-finite ball (undecided upstream), never a wrong enclosure. Budget: one
acb.integral call stops after EVAL_LIMIT + EVAL_LIMIT_PER_BIT prec integrand evaluations (a wider ball), and
inside the kind's attempt all of G's quadratures share QUADRATURE_BUDGET (:func:`quadrature_budget`): once it is
spent G raises :class:`QuadratureBudgetSpent` and the attempt's undecided claims are inconclusive, naming it.
"""
from __future__ import annotations

from fractions import Fraction
from typing import Mapping

from flint import acb, arb, arb_series, fmpq

from ...core.balls import current_precision, series_coefficients, series_length, working_precision
from ...core import quadrature
from ...core.errors import ParameterError
from ...core.exact import Exact
from ...core.expression_domain import first_undefined, polynomial_poles, unparse
from ...core.expressions import UNARY_FUNCTIONS, Expr, compile_expr, derivative, evaluate_exact, parse, parity
from .model import Dual
from .moments import MomentLaw

__all__ = ["ExpressionMoment", "QuadratureBudgetSpent", "quadrature_budget", "EVAL_LIMIT", "QUADRATURE_BUDGET", "OddExpressionMoment", "expression_law", "exact_value", "arb_power", "taylor_q", "f_over_x_form", "Q_ORDER",
           "Q_NEAR", "FINITE", "RESERVED",
           "TAYLOR_ORDER", "MAX_PARAMETERS"]

#: names a [moment] table may not give its own parameters
RESERVED = frozenset({"x2", "a", "f", "pi", "e", "x2_points", "interpolant"}) | UNARY_FUNCTIONS | {"sign"}
#: per acb.integral call: at most EVAL_LIMIT + EVAL_LIMIT_PER_BIT * prec integrand evaluations (Arb's own
#: default, 1000 prec + prec^2, let one call near a branch point run for seconds at 64 bits)
EVAL_LIMIT = 10_000
EVAL_LIMIT_PER_BIT = 100
#: per attempt of the lyapunov kind (one precision): the integrand evaluations of all G quadratures, each
#: weighted by max(1, prec // 64)
QUADRATURE_BUDGET = 5_000_000
#: the order n of f(x)/x's Taylor form (the remainder coefficient c_n over hull(0, x))
TAYLOR_ORDER = 4
MAX_PARAMETERS = 32


def _q(q: Fraction) -> fmpq:
    return fmpq(q.numerator, q.denominator)


def _nan():
    return arb("nan")


# ------------------------------------------------------------------------------------ functions per value type

def _sign(v: arb) -> arb:
    if v > 0:
        return arb(1)
    if v < 0:
        return arb(-1)
    return _nan()


def _monotone(fn):
    """An increasing function of a ball from its exact ends (Arb's tanh of a wide ball is far wider than
    [-1, 1]: tanh([-5.3, 5.3]) came back as +-3.8e4)."""
    def g(v: arb) -> arb:
        if not v.is_finite():
            return _nan()
        if v.rad().is_zero():
            return fn(v)
        return fn(arb(v.lower())).union(fn(arb(v.upper())))
    return g


_tanh, _atan = _monotone(arb.tanh), _monotone(arb.atan)
_ARB = {"sin": arb.sin, "cos": arb.cos, "tan": arb.tan, "exp": arb.exp, "log": arb.log, "sqrt": arb.sqrt,
        "tanh": _tanh, "atan": _atan, "abs": abs, "sign": _sign}

#: f'(v) of each function, for Dual numbers (v a ball)
_DERIV = {"sin": arb.cos, "cos": lambda v: -v.sin(), "tan": lambda v: 1 + arb_power(v.tan(), 2), "exp": arb.exp,
          "log": lambda v: 1 / v if v > 0 else _nan(), "sqrt": lambda v: 1 / (2 * v.sqrt()) if v > 0 else _nan(),
          "tanh": lambda v: 1 - arb_power(_tanh(v), 2), "atan": lambda v: 1 / (1 + arb_power(v, 2)), "abs": _sign,
          "sign": lambda v: arb(0) if (v > 0 or v < 0) else _nan()}


def _series_tanh(s):
    """tanh of a series by the recurrence of T' = (1 - T^2) S' from T_0 = tanh(S_0) (Arb's tanh of the ball):
    k T_k = sum_{j=1..k} j S_j ([k = j] - (T^2)_{k-j}); tight on wide balls, where 1 - 2/(exp(2S) + 1) is not."""
    n = s.prec
    S = series_coefficients(s, n)
    T = [_tanh(S[0])]
    T2 = [arb_power(T[0], 2)]
    for k in range(1, n):
        acc = arb(0)
        for j in range(1, k + 1):
            acc += j * S[j] * ((1 if k == j else 0) - T2[k - j])
        T.append(acc / k)
        T2.append(sum((T[i] * T[k - i] for i in range(k + 1)), arb(0)))
    return arb_series(T, prec=n)


def _series_abs(s):
    c0 = series_coefficients(s, 1)[0]
    if c0 > 0:
        return s
    if c0 < 0:
        return -s
    return s * _nan()


def _series_sign(s):
    c0 = series_coefficients(s, 1)[0]
    return 0 * s + _sign(c0)


_SERIES = {"sin": arb_series.sin, "cos": arb_series.cos, "tan": arb_series.tan, "exp": arb_series.exp,
           "log": arb_series.log, "sqrt": arb_series.sqrt, "tanh": _series_tanh, "atan": arb_series.atan,
           "abs": _series_abs, "sign": _series_sign}


def _apply(name: str, v):
    t = type(v)
    if t is arb:
        return _ARB[name](v)
    if t is Dual:
        return Dual(_ARB[name](v.v), _DERIV[name](v.v) * v.d)
    if t is arb_series:
        return _SERIES[name](v)
    raise TypeError(f"cannot apply {name} to {t.__name__}")


_FUNCTIONS = {name: (lambda v, _n=name: _apply(_n, v)) for name in _ARB}


def _mul_power(x, n: int):
    """x^n (n >= 1) by repeated squaring with ``*`` (any ring: arb points, series, acb)."""
    out = None
    while n:
        if n & 1:
            out = x if out is None else out * x
        n >>= 1
        if n:
            x = x * x
    return out


def arb_power(x: arb, n: int) -> arb:
    """x^n (n >= 0) for every x in the ball, from its exact ends by monotonicity (odd n: increasing; even n:
    |x|^n, 0 included where the ball contains 0). Not Arb's ``**``, which returns nan on some balls about 0."""
    if n == 0:
        return arb(1)
    if n == 1:
        return x
    if not x.is_finite():
        return _nan()
    lo, hi = _mul_power(arb(x.lower()), n), _mul_power(arb(x.upper()), n)
    r = lo.union(hi)
    if n % 2 == 0 and x.contains(0):
        r = r.union(arb(0))
    return r


def _power(base, n: int):
    """base^n for an integer n of either sign, on every value type the law meets."""
    if n < 0:
        return 1 / _power(base, -n)
    t = type(base)
    if t is arb:
        return arb_power(base, n)
    if t is Dual:
        if n == 0:
            return Dual(arb(1), 0 * base.d)
        return Dual(arb_power(base.v, n), n * arb_power(base.v, n - 1) * base.d)
    if n == 0:
        return 1 + 0 * base
    return _mul_power(base, n)


def _acb_functions_of(analytic: bool) -> dict:
    """The functions on complex balls for acb.integral: log, sqrt, atan (through logs) and abs (real_abs)
    with Arb's analyticity flag, so a ball meeting a branch cut or the kink of abs gives a non-finite value."""
    def atan(z):
        iz = acb(0, 1) * z
        return acb(0, 1) / 2 * ((1 - iz).log(analytic=analytic) - (1 + iz).log(analytic=analytic))
    return {"sin": acb.sin, "cos": acb.cos, "tan": acb.tan, "exp": acb.exp, "tanh": acb.tanh,
            "log": lambda z: z.log(analytic=analytic), "sqrt": lambda z: z.sqrt(analytic=analytic), "atan": atan,
            "abs": lambda z: z.real_abs(analytic=analytic), "sign": lambda z: z.real_sgn(analytic=analytic)}


_ACB_FUNCTIONS = {flag: _acb_functions_of(flag) for flag in (False, True)}


def _acb_functions(analytic: bool) -> dict:
    return _ACB_FUNCTIONS[analytic]


# ------------------------------------------------------------------------------------ exact evaluation

class _Finite:
    """A real number of unknown value (the scene's ``a``, sin of an irrational point, ...)."""

    def __repr__(self):
        return "FINITE"


FINITE = _Finite()


def _pi(r: Fraction):
    return Fraction(0) if r == 0 else ("pi", r)


def exact_value(expr: Expr, x2, params: Mapping[str, Fraction]):
    """The exact value of ``expr`` at x2 = ``x2`` (a Fraction, ("pi", r) for r pi, or :data:`FINITE`: every real
    x2 at once), the scene's ``a`` a real of unknown value: a Fraction, ("pi", r), :data:`FINITE` (a real, value
    unknown) or None (unknown, possibly undefined: a division by something that may be 0, log of something that
    may be <= 0, tan at a pole).

    Guarantee: a Fraction returned is the exact value for every real a (and every real x2 when ``x2`` is
    FINITE); FINITE means defined and real."""
    def ev(t):
        op = t[0]
        if op == "num":
            return t[1]
        if op == "name":
            n = t[1]
            return x2 if n == "x2" else FINITE if n == "a" else params[n]
        if op == "neg":
            v = ev(t[1])
            return -v if isinstance(v, Fraction) else _pi(-v[1]) if isinstance(v, tuple) else v
        if op == "call":
            return _exact_call(t[1], ev(t[2][0]))
        if op == "^":
            v, n = ev(t[1]), t[2]
            if v is None:
                return None
            if n == 0:
                return Fraction(1)
            if isinstance(v, Fraction):
                return None if (v == 0 and n < 0) else v ** n
            if isinstance(v, tuple):
                return v if n == 1 else FINITE
            return FINITE if n > 0 else None
        x, y = ev(t[1]), ev(t[2])
        if op in "+-":
            if x is None or y is None:
                return None
            if isinstance(y, tuple) and op == "-":
                y = _pi(-y[1])
            elif isinstance(y, Fraction) and op == "-":
                y = -y
            if isinstance(x, Fraction) and isinstance(y, Fraction):
                return x + y
            if isinstance(x, tuple) and isinstance(y, tuple):
                return _pi(x[1] + y[1])
            if isinstance(x, Fraction) and x == 0:
                return y
            if isinstance(y, Fraction) and y == 0:
                return x
            return FINITE
        if op == "*":
            if x is None or y is None:
                return None
            if (isinstance(x, Fraction) and x == 0) or (isinstance(y, Fraction) and y == 0):
                return Fraction(0)
            if isinstance(x, Fraction) and isinstance(y, Fraction):
                return x * y
            if isinstance(x, Fraction) and isinstance(y, tuple):
                return _pi(x * y[1])
            if isinstance(y, Fraction) and isinstance(x, tuple):
                return _pi(y * x[1])
            return FINITE
        # division
        if x is None or y is None or y is FINITE or (isinstance(y, Fraction) and y == 0):
            return None
        if isinstance(y, Fraction):
            return x / y if isinstance(x, Fraction) else _pi(x[1] / y) if isinstance(x, tuple) else FINITE
        # y = r pi, r != 0
        if isinstance(x, Fraction) and x == 0:
            return Fraction(0)
        return x[1] / y[1] if isinstance(x, tuple) else FINITE
    return ev(expr.tree)


def _exact_call(name: str, v):
    if v is None:
        return None
    zero = isinstance(v, Fraction) and v == 0
    half_pi = isinstance(v, tuple) and (2 * v[1]).denominator == 1      # v = k pi / 2
    if name == "sin":
        if zero:
            return Fraction(0)
        if half_pi:
            k = int(2 * v[1])
            return Fraction(0) if k % 2 == 0 else Fraction(1 if k % 4 == 1 else -1)
        return FINITE
    if name == "cos":
        if zero:
            return Fraction(1)
        if half_pi:
            k = int(2 * v[1])
            return Fraction(0) if k % 2 else Fraction(1 if k % 4 == 0 else -1)
        return FINITE
    if name == "tan":
        if zero or (half_pi and v[1].denominator == 1):
            return Fraction(0)
        return None                                        # possibly a pole
    if name in ("tanh", "atan"):
        return Fraction(0) if zero else FINITE
    if name == "exp":
        return Fraction(1) if zero else FINITE
    if name == "abs":
        return abs(v) if isinstance(v, Fraction) else _pi(abs(v[1])) if isinstance(v, tuple) else FINITE
    if name == "log":
        if isinstance(v, Fraction):
            return Fraction(0) if v == 1 else FINITE if v > 0 else None
        return FINITE if isinstance(v, tuple) and v[1] > 0 else None
    if name == "sqrt":
        if isinstance(v, Fraction):
            if v < 0:
                return None
            p, q = _isqrt(v.numerator), _isqrt(v.denominator)
            return Fraction(p, q) if p is not None and q is not None else FINITE
        return FINITE if isinstance(v, tuple) and v[1] > 0 else None
    return None


def _isqrt(n: int) -> int | None:
    import math
    r = math.isqrt(n)
    return r if r * r == n else None


# ------------------------------------------------------------------------------------ q through 0

def f_over_x_form(c: list, rem: arb, x: arb) -> arb:
    """f(x)/x = c_1 + c_2 x + ... + c_{n-1} x^(n-2) + rem x^(n-1) by Horner's scheme in the ball x, where
    c = [c_1, ..., c_{n-1}] are f's Taylor coefficients at 0 (f(0) = 0) and rem encloses f's n-th coefficient
    over hull(0, x) (the Lagrange remainder)."""
    t = rem
    for ck in reversed(c):
        t = ck + x * t
    return t


def taylor_q(f_series, A0: arb, C0: arb, x: arb, n: int = None, cache: dict | None = None) -> arb | None:
    """q = f^2 / (2 D G) on the ball x, with the 0/0 at x = 0 removed by Taylor forms in x (f(0) = 0):
    f(x)/x = sum_{k<n} f_k x^(k-1) + f_n(H) x^(n-1) and 2 G(x)/x^2 = sum_{1<=j<=n-2} 2 g_j x^(j-1)/(j+1) +
    2 g_{n-1}(H) x^(n-2)/n, where f_k, g_j are the Taylor coefficients at 0 of f and of g = cos f / D
    (G' = g, G(0) = 0, g(0) = 0), and f_n(H), g_{n-1}(H) their coefficients over H = hull(0, x) (Lagrange
    remainders; the remainder of G integrates r(s) s^(n-1) whose second factor keeps its sign on [0, x]).
    ``f_series`` maps an arb_series to f's series and must be valid (f analytic) on H. Each polynomial is
    Horner's in the ball x, so the enclosure shrinks with x's width (a branch and bound converges at a
    maximum at 0, where the mean-value form of f^2/(2 D G) does not). None when not finite. ``cache``: a dict
    for the coefficients at 0 (keyed by the precision and the balls A0, C0)."""
    n = n or Q_ORDER
    H = arb(0).union(x)

    def g(s):
        sn = s.sin()
        return s.cos() * f_series(s) / (A0 - C0 * sn * sn)
    key = (current_precision(), n, A0.mid().man_exp(), A0.rad().man_exp(), C0.mid().man_exp(), C0.rad().man_exp())
    with series_length(n + 1):
        try:
            return _taylor_q(f_series, g, A0, C0, x, n, H, key, cache)
        except ValueError:          # a series division with a leading term that may be 0: no enclosure here
            return None


def _taylor_q(f_series, g, A0, C0, x, n, H, key, cache):
    """:func:`taylor_q`'s body (inside its series length)."""
    at0 = cache.get(key) if cache is not None else None
    if at0 is None:
        s0 = arb_series([arb(0), 1], prec=n + 1)
        at0 = (series_coefficients(f_series(s0), n + 1), series_coefficients(g(s0), n))
        if cache is not None:
            if len(cache) > 64:
                cache.clear()
            cache[key] = at0
    sH = arb_series([H, 1], prec=n + 1)
    fH, gH = series_coefficients(f_series(sH), n + 1), series_coefficients(g(sH), n)
    f0, g0 = at0
    t = f_over_x_form(f0[1:n], fH[n], x)
    u = 2 * gH[n - 1] / n
    for j in range(n - 2, 0, -1):
        u = 2 * g0[j] / (j + 1) + x * u
    sn = x.sin()
    q = t * t / ((A0 - C0 * sn * sn) * u)
    return q if q.is_finite() else None


#: the order of :func:`taylor_q`, and the |x2| up to which the laws use it (beyond, the mean-value form of
#: f^2 / (2 D G) converges without it)
Q_ORDER = 8
Q_NEAR = Fraction(1, 4)


# ------------------------------------------------------------------------------------ the law

class QuadratureBudgetSpent(Exception):
    """Raised by :meth:`ExpressionMoment.G` when the open quadrature budget is spent (never a verdict: the
    lyapunov kind's attempt leaves the claims it was deciding undecided, naming the budget)."""


class ExpressionMoment(MomentLaw):
    """f(x2) given as an expression (module docstring). Not odd by declaration: only
    :class:`OddExpressionMoment` (built when the formula is certified odd) declares ``odd``.

    ``budget``: None (no budget: the paving's boxes, direct use) or a one-element list [remaining weighted
    integrand evaluations], opened by the kind's attempt (:func:`quadrature_budget`); G raises
    :class:`QuadratureBudgetSpent` once it is spent. Each acb.integral call is capped at EVAL_LIMIT +
    EVAL_LIMIT_PER_BIT prec integrand evaluations (Arb's eval_limit; a capped call returns a wider, possibly
    non-finite, ball: undecided upstream, never a wrong enclosure)."""

    G_on_balls = False
    budget: list | None = None

    def __init__(self, f: Expr, params: dict[str, Fraction]):
        self.expr = f
        self.dexpr = derivative(f, "x2")
        self.params = dict(params)
        shown = ", ".join(f"{k} = {v}" for k, v in self.params.items())
        self.formula = f"f(x2) = {f.text}" + (f" with {shown}" if shown else "")
        #: unique per law (the boxes' shared extrema cache is keyed by it)
        self.name = "expression: " + f.text + (f" ({shown})" if shown else "")
        self._balls: dict[int, dict[str, arb]] = {}
        self._zeros = tuple(r for r in (Fraction(-1), Fraction(-1, 2), Fraction(0), Fraction(1, 2), Fraction(1))
                            if exact_value(f, _pi(r), self.params) == 0)
        self._c0: dict = {}
        self._compiled: dict = {}
        self._qcache: dict = {}
        self._gmemo: dict = {}

    def _code(self, which: str, kind: object):
        """The compiled expression (``which``: "f" or "df") for real values (kind None) or complex balls in
        the quadrature (kind: the analyticity flag), per precision (its numbers are balls of that precision)."""
        key = (which, kind, current_precision())
        fn = self._compiled.get(key)
        if fn is None:
            e = self.expr if which == "f" else self.dexpr
            if kind is None:
                fn = compile_expr(e, lambda q: arb(_q(q)), _FUNCTIONS, _power)
            else:
                fn = compile_expr(e, lambda q: acb(arb(_q(q))), _acb_functions(kind), _power)
            if len(self._compiled) > 64:
                self._compiled.clear()
            self._compiled[key] = fn
        return fn

    def _env(self, a, x) -> dict:
        p = current_precision()
        b = self._balls.get(p)
        if b is None:
            b = self._balls[p] = {k: arb(_q(v)) for k, v in self.params.items()}
        return {**b, "a": a, "x2": x}

    def _eval(self, which: str, a, x):
        try:
            r = self._code(which, None)(self._env(a, x))
        except ValueError:
            # python-flint refuses a series division whose leading term may be 0 (a wide ball): not finite
            if type(x) is not arb_series:
                raise
            return arb_series([_nan()] * x.prec, prec=x.prec)
        if type(r) is not type(x) and type(r) is arb:
            r = r + 0 * x                                 # a constant: the argument's type (Dual, series)
        return r

    def f(self, a, x):
        return self._eval("f", a, x)

    def df(self, a, x):
        return self._eval("df", a, x)

    def zeros_over_pi(self):
        return self._zeros

    def _taylor_at_zero(self, a: arb) -> list:
        """c_1 .. c_{n-1} of f at 0 (c_k = f^(k)(0)/k!), cached per precision and ball a."""
        key = (current_precision(), a.mid().man_exp(), a.rad().man_exp())
        c = self._c0.get(key)
        if c is None:
            n = TAYLOR_ORDER
            with series_length(n):
                s = self.f(a, arb_series([arb(0), 1], prec=n))
                c = series_coefficients(s if isinstance(s, arb_series) else s, n)[1:]
            if len(self._c0) > 64:
                self._c0.clear()
            self._c0[key] = c
        return c

    def f_over_x(self, a, x):
        """f(x)/x for every x in the ball (f(0) = 0 certified when the law was built): the Taylor form of the
        module docstring, intersected with f(x)/x where x excludes 0."""
        if type(a) is not arb or type(x) is not arb:
            return _nan()
        n = TAYLOR_ORDER
        c = self._taylor_at_zero(a)
        hull = arb(0).union(x)
        with series_length(n + 1):
            s = self.f(a, arb_series([hull, 1], prec=n + 1))
            rem = series_coefficients(s, n + 1)[n]
        t = f_over_x_form(c, rem, x)
        if x.contains(0):
            return t
        direct = self.f(a, x) / x
        if not t.is_finite():
            return direct
        if not direct.is_finite():
            return t
        return direct.intersection(t) if direct.overlaps(t) else t

    def q_closed(self, a, A0, C0, x):
        """f^2 / (2 D G) by :func:`taylor_q` for |x| <= Q_NEAR (None beyond, or for a non-ball a)."""
        if type(a) is not arb or type(x) is not arb or not abs(x).upper() <= arb(_q(Q_NEAR)):
            return None
        return taylor_q(lambda s: self.f(a, s), A0, C0, x, cache=self._qcache.setdefault(
            (a.mid().man_exp(), a.rad().man_exp()), {}) if len(self._qcache) < 64 else None)

    def G(self, a, A0, C0, x):
        """int_0^x cos(s) f(s) / (A0 - C0 sin^2 s) ds by acb.integral (x a point or thin ball)."""
        if x.is_zero():
            return arb(0)
        if type(a) is not arb or not (x.is_finite() and type(A0) is arb and type(C0) is arb):
            return _nan()
        # memoised: Arb's quadrature is deterministic given the precision and the exact balls, and adjacent
        # pieces ask for G at their shared ends
        key = tuple(v.man_exp() for b in (x, a, A0, C0) for v in (b.mid(), b.rad())) + (current_precision(),)
        hit = self._gmemo.get(key)
        if hit is None:
            if len(self._gmemo) > 100_000:
                self._gmemo.clear()
            hit = self._gmemo[key] = self._G(a, A0, C0, x)
        return hit

    def _G(self, a, A0, C0, x):
        budget = self.budget
        if budget is not None and budget[0] <= 0:
            raise QuadratureBudgetSpent(
                f"the quadrature budget of the [moment] law {self.expr.text!r} was spent (G = int_0^x2 cos f / D by "
                f"acb.integral: {QUADRATURE_BUDGET} integrand evaluations per attempt, weighted by precision/64, "
                f"at most {EVAL_LIMIT} + {EVAL_LIMIT_PER_BIT} prec a call); f may be slow to integrate or leave its "
                "domain on [0, x2*] (a pole, a branch point)")
        A0c, C0c, ac = acb(A0), acb(C0), acb(a)
        p = current_precision()
        count = [0]
        b = self._balls.get(p) or {k: arb(_q(v)) for k, v in self.params.items()}
        consts = {k: acb(v) for k, v in b.items()}
        codes = {flag: self._code("f", flag) for flag in (False, True)}
        env = {**consts, "a": ac}

        def integrand(t, analytic):
            count[0] += 1
            env["x2"] = t
            fv = codes[bool(analytic)](env)
            s = t.sin()
            return t.cos() * fv / (A0c - C0c * s * s)
        try:
            return quadrature.integral(integrand, 0, acb(x), eval_limit=EVAL_LIMIT + EVAL_LIMIT_PER_BIT * p).real
        finally:
            if budget is not None:
                budget[0] -= count[0] * max(1, p // 64)


class OddExpressionMoment(ExpressionMoment):
    """An expression law whose formula is certified odd (:func:`rigor_gyro.core.expressions.parity`)."""

    odd = True


class quadrature_budget:
    """Context manager: opens a budget of ``QUADRATURE_BUDGET`` weighted integrand evaluations on ``law`` (an
    :class:`ExpressionMoment`; other laws are left alone) and closes it on exit (budget None again)."""

    def __init__(self, law, amount: int | None = None):
        self.law = law if isinstance(law, ExpressionMoment) else None
        self.amount = QUADRATURE_BUDGET if amount is None else amount

    def __enter__(self):
        if self.law is not None:
            self.law.budget = [self.amount]
        return self

    def spent(self) -> int:
        """Weighted evaluations used so far (0 without an expression law)."""
        return 0 if self.law is None or self.law.budget is None else self.amount - self.law.budget[0]

    def __exit__(self, *exc):
        if self.law is not None:
            self.used = self.spent()
            self.law.budget = None
        return False


def _refuse_undefined(f: Expr, params: Mapping[str, Fraction], x2_star: Exact | None) -> None:
    """ParameterError when f certainly has no value at some x2 with |x2| <= x2* (x2 = 0 when ``x2_star`` is
    None), for every a: a denominator (or base of a negative power) that is a polynomial in x2 and is the zero
    polynomial or has an exact rational root in [-x2*, x2*]; or, evaluated with balls at the exact points x2 = 0
    and a dyadic x2 in (0, x2*] (a a ball of infinite radius: every real), a division by an exactly-zero ball or
    sqrt/log of an argument certainly outside its domain (:mod:`rigor_gyro.core.expression_domain`)."""
    where = f"[moment] f = {f.text!r}"
    for d, r in polynomial_poles(f.tree, "x2", params):
        if r is None:
            raise ParameterError(f"{where}: f has no value for any x2: it divides by {unparse(d)}, which is exactly 0 "
                                 "for every x2; remove or rewrite the division")
        if r == 0 or (x2_star is not None and _within_x2_star(r, x2_star)):
            shown = x2_star.text or x2_star.rational if x2_star is not None else ""
            region = "" if r == 0 else f", inside |x2| <= x2* = {shown} (the range the claims use)"
            raise ParameterError(f"{where}: f({r}) has no value: it divides by {unparse(d)}, which is "
                                 f"exactly 0 at x2 = {r}{region}; change f"
                                 + ("" if r == 0 else " or choose x2* below the pole"))
    points = [Fraction(0)]
    if x2_star is not None and (p := _dyadic_below(x2_star)) is not None:
        points.append(p)
    with working_precision(64):
        env0 = {k: arb(_q(v)) for k, v in params.items()}
        env0["a"] = arb(0, "inf")
        for x in points:
            inside = " (inside |x2| <= x2*, the range the claims use)" if x else ""
            found = first_undefined(f.tree, {**env0, "x2": arb(_q(x))}, lambda q: arb(_q(q)), _FUNCTIONS, _power,
                                    at=f" at x2 = {x}{inside}")
            if found is None:
                continue
            sub, why = found
            if _depends_on(sub, "x2"):
                raise ParameterError(f"{where}: f({x}) has no value: {why}; change f")
            raise ParameterError(f"{where}: {why} (a constant), so f has no real value for any x2; change f")


def _refuse_constant(f: Expr, params: Mapping[str, Fraction]) -> None:
    """ParameterError when the exact evaluation with x2 a real of unknown value (:func:`exact_value`) shows f
    to be the same rational c for every x2 and every a (``0*x2``): x2 f(x2) > 0 then fails for some x2 != 0."""
    c = exact_value(f, FINITE, params)
    if isinstance(c, Fraction):
        raise ParameterError(f"[moment] f = {f.text!r}: f(x2) = {c} exactly for every x2 (it does not depend on x2): "
                             "the method needs a restoring moment, x2 f(x2) > 0 for 0 < |x2| <= x2*")


def _depends_on(t: tuple, name: str) -> bool:
    return name in Expr(t, "", "").names()


def _within_x2_star(r: Fraction, x2_star: Exact) -> bool:
    """|r| <= x2* certainly (x2* rational: exactly; r pi: by balls at rising precision, never equal)."""
    if x2_star.pi_power == 0:
        return abs(r) <= x2_star.rational
    for prec in (64, 256, 1024):
        with working_precision(prec):
            b = x2_star.ball()
            if arb(_q(abs(r))) < b:
                return True
            if arb(_q(abs(r))) > b:
                return False
    return False


def _dyadic_below(x2_star: Exact) -> Fraction | None:
    """The largest 2^-k (0 <= k <= 60) certainly <= x2* (0 < x2* < pi/2), or None when there is none (x2* below
    2^-60: no second point is tried, since a point beyond x2* would name a pole outside the claims' range)."""
    with working_precision(64):
        lo = x2_star.ball().lower()
    p = Fraction(1)
    while not arb(_q(p)) <= lo:
        if p <= Fraction(1, 2 ** 60):
            return None
        p /= 2
    return p


def expression_law(table: Mapping[str, object], x2_star: Exact | None = None) -> ExpressionMoment:
    """The law of a ``[moment]`` table with ``f = "..."`` and named parameters; ParameterError naming the entry
    when the table or the expression is unusable, f certainly has no value at some |x2| <= x2* (x2 = 0 without
    ``x2_star``), f is constant in x2, or f(0) = 0 / oddness cannot be certified."""
    where = "[moment] f"
    params: dict[str, Fraction] = {}
    names = [k for k in table if k != "f"]
    if len(names) > MAX_PARAMETERS:
        raise ParameterError(f"[moment]: at most {MAX_PARAMETERS} parameters, given {len(names)}")
    for k in names:
        if k in RESERVED or not k.isidentifier() or not k.isascii():
            raise ParameterError(f"[moment] {k}: a parameter may not be called {k!r} (reserved: x2, a, f, the "
                                 f"function names); name it otherwise")
        v = table[k]
        if isinstance(v, list):
            raise ParameterError(f"[moment] {k}: a parameter is one exact number (a list is a table law's x2_points / f)")
        e = parse(v, f"[moment] {k}")
        params[k] = evaluate_exact(e, {})
    text = table.get("f")
    if text is None:
        raise ParameterError("[moment]: missing f (the law, e.g. f = \"a*sin(x2) + b*x2^3\")")
    if isinstance(text, list):
        raise ParameterError("[moment] f: a list of values needs moment = \"table\" and x2_points")
    f = parse(text, where, names={"x2", "a", *params}, functions=UNARY_FUNCTIONS)
    if "x2" not in f.names():
        raise ParameterError(f"{where} = {f.text!r}: does not depend on x2")
    _refuse_undefined(f, params, x2_star)
    _refuse_constant(f, params)
    if parity(f, "x2") != "odd":
        raise ParameterError(f"{where} = {f.text!r}: not certified odd in x2 from its formula; the lyapunov kind's "
                             "claims use the symmetry x2 -> -x2 of an odd law (V(-x) = V(x)), so f must be odd: "
                             "sums of odd terms, odd powers of x2, sin/tan/tanh/atan of odd arguments, products "
                             "by the sign rule")
    f0 = exact_value(f, Fraction(0), params)
    if f0 != 0:
        what = f"f(0) = {f0}" if isinstance(f0, Fraction) else "f(0) could not be shown to be exactly 0"
        raise ParameterError(f"{where} = {f.text!r}: {what}; the origin must be an equilibrium (f(0) = 0)")
    law = OddExpressionMoment(f, params)
    return law
