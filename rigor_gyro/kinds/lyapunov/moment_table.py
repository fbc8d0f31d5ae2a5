"""A moment law given as a table of measured points (issue 42, part 2): a certified cubic-spline interpolant.

A scene of kind ``lyapunov`` with ``moment = "table"`` writes

    [moment]
    x2 = ["0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6"]     # exact decimals, from 0, strictly increasing
    f  = ["0", "9.98", "19.9", "29.6", "38.9", "47.9", "56.5"]

and the law is, by definition, the natural cubic spline S through the points and their odd reflections
(-x_i, -f_i) (so f is odd and f(0) = 0 by construction, not by assumption), continued beyond +-x_n along its end
tangent (natural: S'' = 0 there, so S stays C^2 on the whole line). The spline's second derivatives are solved
exactly in rationals (a tridiagonal system, Thomas' algorithm in ``Fraction``), so every piece is an exact cubic
p0 + p1 u + p2 u^2 + p3 u^3 in u = x2 - x_i.

Enclosures (the interpolant's own bounds, at the current precision): S, S', S'' over a ball are the union, over
the pieces the ball meets, of the piece's polynomial on the ball's part in that piece (Horner in balls); a Dual
gives (S, S' d) and (S', S'' d) (forward mode); an ``arb_series`` gets its value and first derivative (what the
equilibria's interval Newton reads; S is C^2, so the mean-value theorem it rests on holds), its higher
coefficients non-finite. f(x)/x through 0 is S'(0) + S''(hull(0, x)) x / 2 (Taylor, S(0) = 0, S C^2),
intersected with S'(hull(0, x)) (mean value). G(x) = int_0^x cos(s) S(s) / D(s) ds is even (S odd) and is
summed piece by piece, each by ``acb.integral`` of the piece's own polynomial (entire in s, so the quadrature's
bound is rigorous) between exact knots; where the ball x meets a knot x_k, G(x_k) + (x - x_k) g(hull(x_k, x))
(mean value of the continuous integrand g).

Bad input (ParameterError naming the entry, numbered from 1 as ``[plant]``'s ``M[1][1]``: ``x2[1]`` is the first
point; exit 2): an entry that is not an exact rational number (``pi/12``, a parameter's name: the spline is solved
exactly in rationals), lists of different lengths or fewer than 3 points (or more
than :data:`MAX_POINTS`), a first point other than (0, 0), x2 not strictly increasing, a last x2 below the scene's
x2* (the law would be extrapolated over the range the claims use), an f_i <= 0 for x_i > 0 (the data violate
x2 f(x2) > 0, which the method needs; between the points the claim v_positive certifies f/x > 0).

Guarantee: every method returns a ball containing the exact value of the spline law for every argument in its
balls. Fails when: an argument is non-finite (the result is non-finite).
"""
from __future__ import annotations

import bisect
import hashlib
import re
from fractions import Fraction
from typing import Mapping

from flint import acb, arb, arb_series, fmpq

from ...core.balls import certainly_le, current_precision, exact_endpoints, series_coefficients, working_precision
from ...core import quadrature
from ...core.errors import ParameterError
from ...core.exact import Exact
from ...core.expressions import UNARY_FUNCTIONS, Expr, evaluate_exact, parse
from .model import Dual
from .moment_expr import taylor_q
from .moments import MomentLaw

__all__ = ["SplineMoment", "table_law", "natural_spline", "MAX_POINTS"]

MAX_POINTS = 101


def _q(q: Fraction) -> fmpq:
    return fmpq(q.numerator, q.denominator)


def natural_spline(xs: list[Fraction], ys: list[Fraction]) -> list[tuple[Fraction, Fraction, Fraction, Fraction]]:
    """The exact coefficients (p0, p1, p2, p3) of each piece [x_i, x_{i+1}] of the natural cubic spline through
    the points, in u = x - x_i (Thomas' algorithm in exact rationals)."""
    n = len(xs)
    h = [xs[i + 1] - xs[i] for i in range(n - 1)]
    # unknowns M_1 .. M_{n-2}; M_0 = M_{n-1} = 0
    m = n - 2
    a = [h[i] for i in range(m)]                 # sub-diagonal (coefficient of M_i in row i+1)
    b = [2 * (h[i] + h[i + 1]) for i in range(m)]
    c = [h[i + 1] for i in range(m)]
    d = [6 * ((ys[i + 2] - ys[i + 1]) / h[i + 1] - (ys[i + 1] - ys[i]) / h[i]) for i in range(m)]
    for i in range(1, m):
        w = a[i] / b[i - 1]
        b[i] -= w * c[i - 1]
        d[i] -= w * d[i - 1]
    M = [Fraction(0)] * n
    for i in range(m - 1, -1, -1):
        M[i + 1] = (d[i] - (c[i] * M[i + 2] if i + 1 < m else 0)) / b[i]
    out = []
    for i in range(n - 1):
        hi = h[i]
        p1 = (ys[i + 1] - ys[i]) / hi - hi * (2 * M[i] + M[i + 1]) / 6
        out.append((ys[i], p1, M[i] / 2, (M[i + 1] - M[i]) / (6 * hi)))
    return out


class SplineMoment(MomentLaw):
    """The natural cubic spline of measured points, odd by construction (module docstring)."""

    odd = True
    G_on_balls = False

    def __init__(self, xs: list[Fraction], fs: list[Fraction], digest: str):
        self.points = list(zip(xs, fs))
        knots = [-x for x in reversed(xs[1:])] + list(xs)
        vals = [-y for y in reversed(fs[1:])] + list(fs)
        polys = natural_spline(knots, vals)
        (x0, _), (xn, yn) = (knots[0], vals[0]), (knots[-1], vals[-1])
        hl = knots[-1] - knots[-2]
        p0, p1, p2, p3 = polys[-1]
        slope = p1 + 2 * p2 * hl + 3 * p3 * hl * hl            # S'(x_n) = S'(-x_n) (S' even)
        # pieces: (start, end, base, coefficients); the ends are None for the tangent continuations
        self.pieces = ([(None, x0, x0, (-yn, slope, Fraction(0), Fraction(0)))]
                       + [(knots[i], knots[i + 1], knots[i], polys[i]) for i in range(len(polys))]
                       + [(xn, None, xn, (yn, slope, Fraction(0), Fraction(0)))])
        self.starts = [p[0] for p in self.pieces[1:]]         # knots[0 .. -2], then x_n
        self.knots = knots
        self.name = f"table: {len(xs)} points, natural cubic spline [{digest}]"
        pts = ", ".join(f"({x}, {y})" for x, y in self.points[:4]) + (", ..." if len(xs) > 4 else "")
        self.formula = (f"f(x2) = natural cubic spline through the {len(xs)} measured points {pts} and their odd "
                        f"reflections, continued along its end tangent beyond |x2| = {xs[-1]}")
        self._coef: dict[int, list] = {}
        self._G: dict = {}
        self._qcache: dict = {}

    # ------------------------------------------------------------------ piecewise enclosures
    def _balls(self):
        p = current_precision()
        c = self._coef.get(p)
        if c is None:
            c = self._coef[p] = [(None if s is None else arb(_q(s)), None if e is None else arb(_q(e)), arb(_q(b)),
                                  tuple(arb(_q(v)) for v in co)) for s, e, b, co in self.pieces]
        return c

    def _meets(self, x: arb) -> range:
        lo, hi = exact_endpoints(x)
        i = bisect.bisect_right(self.starts, lo)              # piece index of lo (0: the left continuation)
        j = bisect.bisect_right(self.starts, hi)
        return range(i, j + 1)

    def _enclose(self, x: arb, order: int) -> arb:
        """S (order 0), S' (1) or S'' (2) over the ball x."""
        if not x.is_finite():
            return arb("nan")
        out = None
        balls = self._balls()
        for k in self._meets(x):
            s, e, b, (p0, p1, p2, p3) = balls[k]
            if s is None:
                part = x.intersection(arb(x.lower()).union(e))
            elif e is None:
                part = x.intersection(s.union(arb(x.upper())))
            else:
                part = x.intersection(s.union(e))
            u = part - b
            if order == 0:
                v = p0 + u * (p1 + u * (p2 + u * p3))
            elif order == 1:
                v = p1 + u * (2 * p2 + u * 3 * p3)
            else:
                v = 2 * p2 + 6 * p3 * u
            out = v if out is None else out.union(v)
        return out

    def f(self, a, x):
        t = type(x)
        if t is Dual:
            return Dual(self._enclose(x.v, 0), self._enclose(x.v, 1) * x.d)
        if t is arb_series:
            n = x.prec
            c = series_coefficients(x, min(n, 2))
            v = [self._enclose(c[0], 0)]
            if n >= 2:
                v.append(self._enclose(c[0], 1) * c[1])
            v += [arb("nan")] * (n - len(v))
            return arb_series(v, prec=n)
        return self._enclose(x, 0)

    def df(self, a, x):
        if type(x) is Dual:
            return Dual(self._enclose(x.v, 1), self._enclose(x.v, 2) * x.d)
        if type(x) is arb_series:
            return arb_series([self._enclose(series_coefficients(x, 1)[0], 1)] + [arb("nan")] * (x.prec - 1),
                              prec=x.prec)
        return self._enclose(x, 1)

    def zeros_over_pi(self):
        return (Fraction(0),)

    def f_over_x(self, a, x):
        """S(x)/x: S'(0) + S''(H) x/2 and S'(H) over H = hull(0, x) (S(0) = 0, S C^2), and S(x)/x off 0."""
        H = arb(0).union(x)
        taylor = self._enclose(arb(0), 1) + self._enclose(H, 2) * x / 2
        mv = self._enclose(H, 1)
        t = taylor.intersection(mv) if taylor.overlaps(mv) else mv
        if x.contains(0):
            return t
        direct = self._enclose(x, 0) / x
        return direct.intersection(t) if direct.overlaps(t) else direct

    def q_closed(self, a, A0, C0, x):
        """f^2 / (2 D G) for |x| <= x_1 (the first knot) by :func:`.moment_expr.taylor_q`: there S is the odd
        cubic p1 s + p3 s^3 of the piece at 0 (its p0 and p2 are exactly 0), analytic; None elsewhere."""
        x1 = self.points[1][0]
        p0, p1, p2, p3 = self.pieces[len(self.knots) // 2 + 1][3]
        if p0 != 0 or p2 != 0 or type(x) is not arb or type(A0) is not arb or not abs(x).upper() <= arb(_q(x1)):
            return None
        c1, c3 = arb(_q(p1)), arb(_q(p3))
        return taylor_q(lambda t: c1 * t + c3 * t * t * t, A0, C0, x, cache=self._qcache)

    # ------------------------------------------------------------------ G
    def _integrand_ball(self, A0, C0, s: arb) -> arb:
        sn = s.sin()
        return s.cos() * self._enclose(s, 0) / (A0 - C0 * sn * sn)

    def _piece_integral(self, k: int, A0, C0, lo, hi) -> arb:
        _, _, b, co = self._balls()[k]
        A0c, C0c, bc = acb(A0), acb(C0), acb(b)
        cc = [acb(v) for v in co]

        def integrand(t, analytic):
            u = t - bc
            sn = t.sin()
            return t.cos() * (cc[0] + u * (cc[1] + u * (cc[2] + u * cc[3]))) / (A0c - C0c * sn * sn)
        return quadrature.integral(integrand, acb(lo), acb(hi)).real

    def _G_at_knots(self, A0, C0) -> list[arb]:
        """G at the knots 0 = x_0 < x_1 < ... < x_n (exact points), per precision and (A0, C0) balls."""
        key = (current_precision(), A0.mid().man_exp(), A0.rad().man_exp(), C0.mid().man_exp(), C0.rad().man_exp())
        g = self._G.get(key)
        if g is None:
            n0 = len(self.knots) // 2                         # index of the knot 0
            g = [arb(0)]
            for i in range(n0, len(self.knots) - 1):
                k = i + 1                                     # piece index (0 is the left continuation)
                g.append(g[-1] + self._piece_integral(k, A0, C0, arb(_q(self.knots[i])), arb(_q(self.knots[i + 1]))))
            if len(self._G) > 64:
                self._G.clear()
            self._G[key] = g
        return g

    def G(self, a, A0, C0, x):
        """int_0^x cos(s) S(s) / (A0 - C0 sin^2 s) ds for a point or thin ball x (even in x)."""
        if x.is_zero():
            return arb(0)
        if not (x.is_finite() and type(A0) is arb and type(C0) is arb):
            return arb("nan")
        y = abs(x)
        gk = self._G_at_knots(A0, C0)
        pos = self.knots[len(self.knots) // 2:]               # 0, x_1, ..., x_n
        lo, hi = exact_endpoints(y)
        i = bisect.bisect_right(pos, lo) - 1                  # pos[i] <= lo
        j = bisect.bisect_right(pos, hi) - 1
        base = arb(_q(pos[i]))
        if i != j or pos[i] == lo:
            # the ball meets a knot pos[j]: mean value of the continuous integrand between it and y
            kn = arb(_q(pos[j]))
            return gk[j] + (y - kn) * self._integrand_ball(A0, C0, kn.union(y))
        k = len(self.knots) // 2 + i + 1                      # the piece starting at pos[i]
        return gk[i] + self._piece_integral(k, A0, C0, base, y)


def _list(table: Mapping[str, object], key: str) -> list[Fraction]:
    v = table.get(key)
    if not isinstance(v, list):
        raise ParameterError(f"[moment] {key}: need a list of exact numbers (strings), e.g. {key} = [\"0\", \"0.1\"]")
    out = []
    for i, t in enumerate(v):
        if isinstance(t, list):
            raise ParameterError(f"[moment] {key}[{i + 1}]: need an exact number, got a list")
        out.append(evaluate_exact(_entry(t, f"[moment] {key}[{i + 1}]"), {}))
    return out


def _entry(t: object, where: str) -> Expr:
    """One table entry parsed as an exact rational (no names, no functions); ParameterError naming ``where``.
    A formula in names (``pi/12``, a parameter) gets a message saying why: the spline is solved exactly in
    rationals, so its points must be rational."""
    try:
        return parse(t, where)
    except ParameterError:
        words = set(re.findall(r"(?<![0-9.])[A-Za-z_][A-Za-z0-9_]*", t)) if isinstance(t, str) else set()
        if not words:
            raise
        named = parse(t, where, names=words, functions=UNARY_FUNCTIONS)     # a grammar error is raised as such
        used = sorted(named.names() | ({"pi"} & words))
        why = (f"; {t} uses pi, which is not rational" if "pi" in used else "") + \
            (f"; {', '.join(repr(u) for u in used if u != 'pi')}: write the value, not the name"
             if set(used) - {"pi"} else "")
        raise ParameterError(f"{where} = {t!r}: table points are exact rational numbers such as 1/12 or 0.2618, "
                             f"not formulas (the spline is solved exactly in rationals){why}") from None


def table_law(table: Mapping[str, object], x2_star: Exact) -> SplineMoment:
    """The spline law of a ``[moment]`` table (module docstring); ParameterError naming the entry when unusable."""
    extra = sorted(set(table) - {"x2", "f", "interpolant"})
    if extra:
        raise ParameterError(f"[moment] {extra[0]}: unknown entry of a table law (it has x2, f and interpolant)")
    interp = table.get("interpolant", "cubic")
    if interp != "cubic":
        raise ParameterError(f"[moment] interpolant = {interp!r}: only \"cubic\" (the natural cubic spline, C^2: "
                             "the Lyapunov function needs f'), not piecewise linear")
    xs, fs = _list(table, "x2"), _list(table, "f")
    if len(xs) != len(fs):
        raise ParameterError(f"[moment] f: {len(fs)} values for {len(xs)} points x2")
    if not 3 <= len(xs) <= MAX_POINTS:
        raise ParameterError(f"[moment] x2: need 3 to {MAX_POINTS} points (from 0), given {len(xs)}")
    if xs[0] != 0 or fs[0] != 0:
        raise ParameterError("[moment] x2[1], f[1]: the first point must be (0, 0) (the equilibrium; the law is "
                             "the odd extension of the points)")
    for i in range(1, len(xs)):
        if not xs[i] > xs[i - 1]:
            raise ParameterError(f"[moment] x2[{i + 1}] = {xs[i]}: the points must be strictly increasing")
        if not fs[i] > 0:
            raise ParameterError(f"[moment] f[{i + 1}] = {fs[i]}: need f > 0 at x2 > 0 (x2 f(x2) > 0 is the method's "
                                 "condition)")
    with working_precision(256):
        covers = certainly_le(x2_star.ball(), arb(_q(xs[-1])))
    if not covers:
        raise ParameterError(f"[moment] x2[{len(xs)}] = {xs[-1]}: the table must reach x2* (the range the claims "
                             "use), not be extrapolated over it")
    digest = hashlib.sha256(repr((xs, fs)).encode()).hexdigest()[:12]
    return SplineMoment(xs, fs, digest)
