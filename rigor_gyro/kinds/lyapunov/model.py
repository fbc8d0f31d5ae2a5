"""The gimbal gyroscope with viscous friction (Agafonov et al. 2013) in ball arithmetic.

System (2), x1 = alpha-dot, x2 = beta, x3 = beta-dot, D = A0 - C0 sin^2 x2:

    x1' = [C0 sin 2x2 x1 x3 - H cos x2 x3 - k x1 - f(x2)] / D,  x2' = x3,
    x3' = [-1/2 C0 sin 2x2 x1^2 + H cos x2 x1] / B0;

Lyapunov function (7): V = mu F + x3 f3 + 1/2 f2 x3^2 + mu/2 f1 x3^2 + mu (H/B0) cos x2 x1 x3
+ H^2/(2 B0^2) cos^2 x2 x1^2, f1 = k/D, f2 = H^2 cos^2 x2/(D B0), f3 = H cos x2 f/(D B0),
F = int_0^x2 f3 = (H/B0) G.

Two independent routes to Vdot = grad V . f:

* :meth:`Gimbal.vdot`: forward-mode automatic differentiation of V (7) along the vector field (2) in
  ball arithmetic (dual numbers over ``arb``; dF/dx2 = f3 by definition of F): no hand algebra;
* :meth:`Gimbal.psi_coefficients`: the form Vdot = -Psi1 x1^2 - Psi2 x3^2, Psi_i = ci0 + ci1 x1 + ci3 x3,
  derived from (7) and (2) by hand and verified as an exact identity symbolically
  (tests/test_lyapunov_identity.py) and in balls at run time against the first route.
  The paper's printed (8) is :meth:`Gimbal.psi_printed_coefficients` (audited, never used by a claim).

The decomposition used for positivity: with h = H cos x2 / B0 and S = f2 + mu (f1 - mu),

    V = phi(x2) + 1/2 S (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2,   phi = mu F - f3^2/(2 S),
    phi = (F/S) psi(x2),  psi = (H cos^2 x2/(D B0)) (mu H - q(x2)) + mu^2 (f1 - mu),

with q = f^2/(2 D G), the quotient whose maximum is the paper's M (0/0 at x2 = 0: enclosed through
the moment law's f(x)/x, see :meth:`Gimbal.q`).

The certified statement shared by the claim ``vdot_nonpositive`` and the audit of the paper's final
region is here too: :func:`certify_vdot_nonpositive` (Vdot <= 0 on region (17) of a given radius).

Guarantee: every method returns a ball containing the exact value for every argument in the ball
arguments, at the current working precision; parameters are exact rationals (x2* may be a rational
multiple of pi).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, ctx as _ctx, fmpq

from ...core.balls import (ball_key, certainly_gt, certainly_le, certainly_lt, certainly_negative, certainly_positive, current_precision, decimal_bounds, square,
                           exact_fraction, sqrt_of_nonnegative)
from ...core.boxes import even_in
from ...core.exact import Exact
from ...core.outcome import Status
from ...core.stored import ball_text, pieces_text
from ...core.subdivision import certify_positive
from .moments import MomentLaw

__all__ = ["Dual", "Gimbal", "ParameterBalls", "mean_value_enclosure", "hypot_ball", "psi_min_functions", "vdot_witness",
           "VdotVerdict", "certify_vdot_nonpositive", "certify_psi_test", "psi_counterexample", "closed_form_constants", "cylinder_lower_bound",
           "DAMPING_THRESHOLDS", "damping_margin", "rational_points_inside",
           "CIRCLE_DIRECTIONS", "cylinder_points", "faces_minimiser_inside", "c_star_lower", "c_star_upper",
           "DIRECT_DOMAIN", "vdot_polar", "direct_margin", "symmetric_in_x2",
           "law_is_odd", "v_polar", "square_from_ends", "sublevel_lower_bound", "slice_extent", "slice_in_region"]


class Dual:
    """A first-order dual number v + d eps over ``arb``: forward-mode differentiation in balls.

    An operand that is not a Dual is a constant (derivative 0) and is used as it is: no zero
    derivative is carried through the arithmetic (each rule is the exact derivative rule, evaluated in
    ball arithmetic, so v and d enclose the value and the derivative)."""

    __slots__ = ("v", "d")

    def __init__(self, v, d=0):
        self.v, self.d = (v if type(v) is arb else arb(v)), d

    def __add__(self, o):
        if type(o) is Dual:
            return Dual(self.v + o.v, self.d + o.d)
        return Dual(self.v + o, self.d)

    __radd__ = __add__

    def __neg__(self):
        return Dual(-self.v, -self.d)

    def __sub__(self, o):
        if type(o) is Dual:
            return Dual(self.v - o.v, self.d - o.d)
        return Dual(self.v - o, self.d)

    def __rsub__(self, o):
        return Dual(o - self.v, -self.d)

    def __mul__(self, o):
        if type(o) is Dual:
            return Dual(self.v * o.v, self.d * o.v + self.v * o.d)
        return Dual(self.v * o, self.d * o)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if type(o) is Dual:
            return Dual(self.v / o.v, (self.d * o.v - self.v * o.d) / (o.v * o.v))
        return Dual(self.v / o, self.d / o)

    def __rtruediv__(self, o):
        v = self.v
        return Dual(o / v, -(o * self.d) / (v * v))

    def __pow__(self, n: int):
        if n != 2:
            raise ValueError("Dual supports only squares")
        v = self.v
        return Dual(v * v, 2 * v * self.d)

    def sin(self):
        s, c = self.v.sin_cos()
        return Dual(s, c * self.d)

    def cos(self):
        s, c = self.v.sin_cos()
        return Dual(c, -s * self.d)

    def sqrt(self):
        r = self.v.sqrt()
        return Dual(r, self.d / (2 * r))


def sin_cos(x):
    """(sin x, cos x) of a ball or a :class:`Dual` from one sin_cos evaluation."""
    if type(x) is Dual:
        sv, cv = x.v.sin_cos()
        return Dual(sv, cv * x.d), Dual(cv, -sv * x.d)
    return x.sin_cos()


def mean_value_enclosure(fn):
    """Wrap ``fn`` (written with +, -, *, /, sin, cos, so it accepts both ``arb`` and :class:`Dual`)
    into the mean-value enclosure fn(m) + fn'(X) (X - m), fn' enclosed over X by forward-mode
    differentiation, intersected with the direct enclosure. Near an interior or end-point maximum the
    overestimation is quadratic in the piece width instead of linear, so branch and bound converges.
    (Not :func:`rigor_gyro.core.subdivision.mean_value_form`, which needs arb_series: q contains G, whose
    derivative is known only through its definition dG/dx2 = cos f / D, which a Dual carries.)"""
    def g(X: arb) -> arb:
        direct = fn(X)
        if X.rad().is_zero():
            return direct
        d = fn(Dual(X, arb(1))).d
        m = X.mid()
        mv = fn(m) + d * (X - m)
        if not mv.is_finite():
            return direct
        return direct.intersection(mv) if direct.overlaps(mv) else mv
    return g


def hypot_ball(a: arb, b: arb) -> arb:
    """A ball containing sqrt(a^2 + b^2) for all values of a and b in their balls, built from the
    endpoints of |a| and |b| (so it never takes the square root of a ball reaching below 0)."""
    def ends(x):
        ax = abs(x)
        lo = ax.lower()
        return (lo if lo > 0 else arb(0)), ax.upper()
    (al, au), (bl, bu) = ends(a), ends(b)
    lo = (al * al + bl * bl).sqrt().lower()
    hi = (au * au + bu * bu).sqrt().upper()
    return lo.union(hi)


#: entries of one Gimbal's per-ball memo before it is cleared (bounds its memory)
MEMO_LIMIT = 200_000


def _mu_free(method):
    """:func:`_per_ball` for a method that does not depend on mu: its memo (``_shared``) is shared by the
    gimbals :meth:`Gimbal.with_mu` makes from one plain Gimbal (the same parameters but mu), so the searches
    and branch and bounds over mu meet each x2 ball once."""
    wrapper = _per_ball(method)
    wrapper.mu_free = True
    return wrapper


def _per_ball(method):
    """Memoise a Gimbal method of one ball ``x2`` (at the scene's mu), keyed by the precision and the
    ball's exact midpoint and radius. Arb arithmetic is deterministic given those, so a memoised
    value is the very ball the method would return: certificates are unchanged, only repeated work
    goes (a 2-D branch and bound in (x2, t) meets each x2 piece many times). A Dual number with an exact
    seed d (the mean-value forms' X + 1 eps) is keyed by its ball and seed the same way (its value is a
    tuple of Duals, never changed in place: Dual arithmetic makes new numbers). Extra arguments (a mu
    ball) and non-finite balls are computed, never memoised."""
    name = method.__name__

    def wrapper(self, x2, *args, **kwargs):
        if args or kwargs:
            return method(self, x2, *args, **kwargs)
        # the key's ball part is remembered for the last argument object (arb and Dual objects are never
        # changed in place, and the gimbal keeps a reference, so ``is`` means the same ball): the methods of
        # one evaluation pass the same object to one another, and its exact midpoint and radius are read once
        prec = _ctx.prec
        last = self._last_key
        if last[0] is x2 and last[1] == prec:
            base = last[2]
        elif type(x2) is arb and x2.is_finite():
            base = (prec, *ball_key(x2))
            self._last_key = (x2, prec, base)
        elif type(x2) is Dual and type(x2.d) is arb and x2.v.is_finite() and x2.d.is_exact() and x2.d.is_finite():
            base = (prec, *ball_key(x2.v), *ball_key(x2.d))
            self._last_key = (x2, prec, base)
        else:
            return method(self, x2)
        key = (name, base)
        memo = self._shared if wrapper.mu_free else self._memo
        hit = memo.get(key)
        if hit is None:
            if len(memo) >= MEMO_LIMIT:
                memo.clear()
            hit = memo[key] = method(self, x2)
        return hit
    wrapper.__name__, wrapper.__doc__, wrapper.__wrapped__ = name, method.__doc__, method
    wrapper.mu_free = False
    return wrapper


@dataclass
class ParameterBalls:
    A0: arb
    B0: arb
    C0: arb
    H: arb
    k: arb
    a: arb
    mu: arb
    x2_star: arb


def psi_from_parts(parts: tuple, H, B0, k, mu, mkBC) -> tuple[tuple, tuple]:
    """((c10, c11, c13), (c20, c21, c23)) of the Psi form from the mu-free factors of
    :meth:`Gimbal._psi_parts` (s, cos, 1/D, f', cos^2, s f, s cos / D, H/B0, C0 H/B0^2, (A0 - C0) H^2, P) and
    H, B0, k, mu, mu k B0 C0: plain arithmetic, the same for balls (the proofs) and floats (the float twin's
    proposals, :mod:`.float_twin`), so the two cannot drift apart."""
    s, cs, iD, fp, cs2, sf, scs_iD, HB, C0HB2, AH2, P = parts
    c10 = cs2 * (HB * HB * (k * iD - mu) + C0HB2 * sf * iD)
    c11 = mu * C0HB2 * s * cs2
    c13 = (mkBC + AH2) / (B0 * B0) * scs_iD
    c20 = HB * iD * (mu * H * cs2 - cs * fp + P * sf * iD)
    c21 = mu * HB * P * s * iD
    c23 = (AH2 - mkBC) / B0 * scs_iD * iD
    return (c10, c11, c13), (c20, c21, c23)


@dataclass
class Gimbal:
    """Exact parameters of system (2) and Lyapunov function (7), with ball-valued functions."""

    A0: fmpq
    B0: fmpq
    C0: fmpq
    H: fmpq
    k: fmpq
    a: fmpq
    mu: fmpq
    x2_star: Exact
    law: MomentLaw

    def __post_init__(self):
        self._cache: dict[int, ParameterBalls] = {}
        self._memo: dict = {}
        #: the memo of the methods that do not depend on mu (_mu_free), shared by with_mu's gimbals
        self._shared: dict = {}
        #: (argument object, precision, the ball part of its memo key) of the last memoised call (_per_ball)
        self._last_key: tuple = (None, None, None)
        #: (precision, parameter balls) of the last read of ``c``
        self._last_c: tuple = (None, None)

    def with_mu(self, mu: fmpq) -> "Gimbal":
        g = Gimbal(self.A0, self.B0, self.C0, self.H, self.k, self.a, mu, self.x2_star, self.law)
        if type(self) is Gimbal:        # the same parameters but mu: the mu-free memo is shared (a subclass's
            g._shared = self._shared    # parameters are balls of its own: never shared with a plain Gimbal)
        return g

    @property
    def c(self) -> ParameterBalls:
        """The parameters as balls at the current precision (cached per precision)."""
        p = _ctx.prec
        last = self._last_c
        if last[0] == p:
            return last[1]
        if p not in self._cache:
            self._cache[p] = ParameterBalls(*(arb(v) for v in (self.A0, self.B0, self.C0, self.H, self.k, self.a,
                                                        self.mu)), self.x2_star.ball())
        self._last_c = (p, self._cache[p])
        return self._cache[p]

    # --------------------------------------------------------------------- the model's functions
    def D(self, x2):
        c = self.c
        return c.A0 - c.C0 * x2.sin() ** 2

    def f(self, x2):
        return self.law.f(self.c.a, x2)

    def df(self, x2):
        return self.law.df(self.c.a, x2)

    def f1(self, x2):
        return self.c.k / self.D(x2)

    def f2(self, x2):
        c = self.c
        return c.H ** 2 * x2.cos() ** 2 / (self.D(x2) * c.B0)

    @_mu_free
    def f3(self, x2):
        c = self.c
        return c.H * x2.cos() * self.f(x2) / (self.D(x2) * c.B0)

    @_mu_free
    def G(self, x2: arb) -> arb:
        """int_0^x2 cos f / D: closed form or quadrature on thin balls; on wide balls G is even and
        increasing in |x2| (integrand > 0 on (0, x2*], certified by the v_positive claim), so it is
        enclosed by its values at the smallest and largest |x2|. (Memoised per ball: F and F on a Dual
        number both need G of the same ball.)"""
        c = self.c
        if x2.rad() < arb(2) ** (-(current_precision() // 2)):
            return self.law.G(c.a, c.A0, c.C0, x2)
        lo_abs = arb(0) if x2.contains(0) else abs(x2).lower()
        hi_abs = abs(x2).upper()
        hull = self.law.G(c.a, c.A0, c.C0, lo_abs).union(self.law.G(c.a, c.A0, c.C0, hi_abs))
        if self.law.G_on_balls:
            direct = self.law.G(c.a, c.A0, c.C0, x2)
            if direct.overlaps(hull):
                return direct.intersection(hull)
        return hull

    @_mu_free
    def F(self, x2):
        """F = (H/B0) G; on a Dual its derivative is f3 (the definition of F)."""
        c = self.c
        if isinstance(x2, Dual):
            return Dual(c.H / c.B0 * self.G(x2.v), self.f3(x2.v) * x2.d)
        return c.H / c.B0 * self.G(x2)

    def rhs(self, x1, x2, x3):
        """The vector field (2)."""
        c = self.c
        D = self.D(x2)
        s2 = (2 * x2).sin() if not isinstance(x2, Dual) else 2 * x2.sin() * x2.cos()
        d1 = (c.C0 * s2 * x1 * x3 - c.H * x2.cos() * x3 - c.k * x1 - self.f(x2)) / D
        d3 = (-(c.C0 * s2 * x1 * x1) / 2 + c.H * x2.cos() * x1) / c.B0
        return d1, x3, d3

    def V(self, x1, x2, x3):
        """Lyapunov function (7)."""
        c = self.c
        cs = x2.cos()
        return (c.mu * self.F(x2) + x3 * self.f3(x2) + self.f2(x2) * x3 * x3 / 2 + c.mu * self.f1(x2) * x3 * x3 / 2
                + c.mu * c.H / c.B0 * cs * x1 * x3 + c.H ** 2 / (2 * c.B0 ** 2) * cs * cs * x1 * x1)

    def vdot(self, x1: arb, x2: arb, x3: arb) -> arb:
        """grad V . f at (x1, x2, x3) by forward-mode differentiation along f (no hand algebra)."""
        d1, d2, d3 = self.rhs(x1, x2, x3)
        return self.V(Dual(x1, d1), Dual(x2, d2), Dual(x3, d3)).d

    # --------------------------------------------------------------------- the Psi form
    @_per_ball
    def psi_coefficients(self, x2: arb, mu: arb | None = None) -> tuple[tuple[arb, arb, arb], tuple[arb, arb, arb]]:
        """((c10, c11, c13), (c20, c21, c23)) of Vdot = -Psi1 x1^2 - Psi2 x3^2, Psi_i = ci0 + ci1 x1 + ci3 x3,
        as Vdot actually is (derived from (7) and (2)); for every mu in the ball ``mu`` when given (the
        scene's mu otherwise)."""
        c = self.c
        H, B0, C0, k = c.H, c.B0, c.C0, c.k
        mu = c.mu if mu is None else mu
        return psi_from_parts(self._psi_parts(x2), H, B0, k, mu, mu * k * B0 * C0)

    @_mu_free
    def _psi_parts(self, x2):
        """The factors of :meth:`psi_coefficients` that do not depend on mu (memoised per ball: the branch and
        bounds over mu ask the same x2 for many mu balls)."""
        c = self.c
        H, B0, C0, A0 = c.H, c.B0, c.C0, c.A0
        s, cs = sin_cos(x2)
        # common factors computed once (a Dual operation costs several ball operations)
        iD = 1 / (A0 - C0 * s * s)                   # 1 / D
        fp = self.df(x2)
        cs2, sf = cs * cs, s * self.f(x2)
        scs_iD = s * cs * iD
        HB = H / B0
        C0HB2 = C0 * H / (B0 * B0)
        AH2 = (A0 - C0) * H * H
        P = A0 - C0 - C0 * cs2
        return s, cs, iD, fp, cs2, sf, scs_iD, HB, C0HB2, AH2, P

    def psi_printed_coefficients(self, x2: arb) -> tuple[tuple[arb, arb, arb], tuple[arb, arb, arb]]:
        """The same coefficients as printed in (8) (the x3 term of Psi2 carries sin 2x2)."""
        (c10, c11, c13), (c20, c21, _) = self.psi_coefficients(x2)
        c = self.c
        D = self.D(x2)
        c23p = ((c.A0 - c.C0) * c.H ** 2 - c.mu * c.k * c.B0 * c.C0) * (2 * x2).sin() / (c.B0 * D ** 2)
        return (c10, c11, c13), (c20, c21, c23p)

    def vdot_psi(self, x1, x2, x3, printed: bool = False) -> arb:
        """-Psi1 x1^2 - Psi2 x3^2 from the coefficient form (derived, or as printed)."""
        (c10, c11, c13), (c20, c21, c23) = (self.psi_printed_coefficients if printed else self.psi_coefficients)(x2)
        return -(c10 + c11 * x1 + c13 * x3) * x1 * x1 - (c20 + c21 * x1 + c23 * x3) * x3 * x3

    def vdot_monomials(self, x2: arb) -> dict[str, arb]:
        """Coefficients of grad V . f as a cubic polynomial in (x1, x3) at fixed x2, extracted from
        :meth:`vdot` at exact nodes (x1, x3 in {-1, 0, 1, 2}) by exact finite differences:
        keys '1', 'x1', 'x3', 'x1^2', 'x1x3', 'x3^2', 'x1^3', 'x1^2x3', 'x1x3^2', 'x3^3'."""
        v = {}

        def P(i, j):
            if (i, j) not in v:
                v[(i, j)] = self.vdot(arb(i), x2, arb(j))
            return v[(i, j)]

        def cubic(vals):  # values at t = -1, 0, 1, 2 -> coefficients of 1, t, t^2, t^3
            m1, z, p1, p2 = vals
            c2 = (p1 + m1) / 2 - z
            c3 = (p2 - 3 * p1 + 3 * z - m1) / 6
            c1 = (p1 - m1) / 2 - c3
            return z, c1, c2, c3
        a0, a1, a2, a3 = cubic([P(t, 0) for t in (-1, 0, 1, 2)])
        _, b1, b2, b3 = cubic([P(0, t) for t in (-1, 0, 1, 2)])

        def Q(i, j):
            return P(i, j) - P(i, 0) - P(0, j) + a0
        p21 = (Q(1, 1) + Q(-1, 1)) / 2
        p12 = (Q(1, 1) + Q(1, -1)) / 2
        p11 = Q(1, 1) - p21 - p12
        return {"1": a0, "x1": a1, "x1^2": a2, "x1^3": a3, "x3": b1, "x3^2": b2, "x3^3": b3,
                "x1x3": p11, "x1^2x3": p21, "x1x3^2": p12}

    # --------------------------------------------------------------------- positivity pieces
    def q(self, x2: arb) -> arb:
        """q = f^2 / (2 D G) on a ball x2 inside [0, x2*] (q is even). Closed form when the law has
        one; otherwise, for balls touching 0, the removable singularity is enclosed through
        G(x) = x^2 int_0^1 t g(x t) dt with g = cos f/(x D) > 0, so q in (f/x)^2 / (D hull g([0, |x|])),
        and away from 0 through the monotonicity of G."""
        c = self.c
        closed = self.law.q_closed(c.a, c.A0, c.C0, x2)
        if x2.lower() > 0 and not x2.rad().is_zero():
            # away from 0: the mean-value form (G' = cos f / D by definition), so that branch and bound
            # converges where q is flat (a maximum at an end with q' -> 0)
            mv = mean_value_enclosure(self._q_away)(x2)
            if not mv.is_finite():
                mv = self._q_away(x2)
            if closed is not None:
                return closed.intersection(mv) if closed.overlaps(mv) and mv.is_finite() else closed
            return mv
        if closed is not None:
            return closed
        fx = self.law.f_over_x(c.a, x2)
        if x2.contains(0) or not x2.lower() > 0:
            top = abs(x2).upper()
            y = arb(0).union(top)
            g = y.cos() * self.law.f_over_x(c.a, y) / self.D(y)
            return square(fx) / (self.D(x2) * g)
        return self.f(x2) ** 2 / (2 * self.D(x2) * self.G(x2))

    def _q_away(self, x2):
        """f^2 / (2 D G) for x2 > 0 (arb or Dual; dG/dx2 = cos f / D)."""
        if isinstance(x2, Dual):
            v = x2.v
            G = Dual(self.G(v), v.cos() * self.f(v) / self.D(v) * x2.d)
        else:
            G = self.G(x2)
        return self.f(x2) ** 2 / (2 * self.D(x2) * G)

    @_per_ball
    def S(self, x2):
        """f2 + mu (f1 - mu), D evaluated once (the same operations as f2 and f1 make: the same ball)."""
        c = self.c
        D = self.D(x2)
        return c.H ** 2 * x2.cos() ** 2 / (D * c.B0) + c.mu * (c.k / D - c.mu)

    def psi(self, x2: arb) -> arb:
        """psi = (H cos^2/(D B0)) (mu H - q) + mu^2 (f1 - mu): V > 0 off the origin iff psi > 0 on
        0 < |x2| <= x2* (given S > 0, G > 0)."""
        c = self.c
        return c.H * x2.cos() ** 2 / (self.D(x2) * c.B0) * (c.mu * c.H - self.q(x2)) + c.mu ** 2 * (self.f1(x2) - c.mu)

    @_per_ball
    def phi(self, x2: arb) -> arb:
        """phi = min over (x1, x3) of V at fixed x2 = mu F - f3^2/(2 S)."""
        return self.c.mu * self.F(x2) - square(self.f3(x2)) / (2 * self.S(x2))

    def phi_minimiser(self, x2: arb) -> tuple[arb, arb]:
        """(x1, x3) where V(., x2, .) attains phi(x2): x3 = -f3/S, x1 = -mu x3 B0/(H cos x2)."""
        c = self.c
        x3 = -self.f3(x2) / self.S(x2)
        return -c.mu * x3 * c.B0 / (c.H * x2.cos()), x3

    def m_quotient(self, x2: arb) -> arb:
        """|cos x2 f'(x2)| / (A0 - C0 sin^2 x2), the reading of m's misprinted definition."""
        return abs(x2.cos() * self.df(x2)) / self.D(x2)

    def m_signed(self, x2):
        """cos x2 f'(x2) / (A0 - C0 sin^2 x2) (accepts a Dual: for mean-value enclosures)."""
        return x2.cos() * self.df(x2) / self.D(x2)


# ------------------------------------------------------------------------------------ Vdot <= 0 on (17)
# Shared by the claim ``vdot_nonpositive`` and the audit of the paper's final region.

def _fmt(x: arb, digits: int = 12) -> str:
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def psi_min_functions(g: Gimbal, R: arb):
    """x2 piece -> enclosure of min over the disc of radius R of Psi1 (resp. Psi2)."""
    def psi1(x2):
        (c10, c11, c13), _ = g.psi_coefficients(x2)
        return c10 - R * hypot_ball(c11, c13)

    def psi2(x2):
        _, (c20, c21, c23) = g.psi_coefficients(x2)
        return c20 - R * hypot_ball(c21, c23)
    return psi1, psi2


def vdot_witness(g: Gimbal, R: arb, x2_points: list[arb]) -> tuple[arb, arb, arb, arb] | None:
    """A point of region (17) (x1^2 + x3^2 < R^2 exactly, |x2| <= x2*) where grad V . f > 0 certainly,
    searched on circles of radius R (1 - 2^-20), R/2, R/4 at 48 directions; None if none found."""
    Rq = exact_fraction(R.lower())
    for x2 in x2_points:
        for frac in (Fraction(1) - Fraction(1, 2 ** 20), Fraction(1, 2), Fraction(1, 4)):
            r = Rq * frac
            for j in range(48):
                th = 2 * math.pi * j / 48
                x1 = Fraction(math.cos(th)).limit_denominator(10 ** 6) * r
                x3 = Fraction(math.sin(th)).limit_denominator(10 ** 6) * r
                found = _vdot_positive_at(g, x1, x2, x3, Rq)
                if found is not None:
                    return found
    return None


def _vdot_positive_at(g: Gimbal, x1: Fraction, x2: arb, x3: Fraction, Rq: Fraction):
    """(x1, x2, x3, Vdot) as balls when the exact point (x1, x3) lies inside the disc of radius Rq and Vdot
    > 0 there is certified; None otherwise (a candidate only: nothing is claimed)."""
    if not x1 * x1 + x3 * x3 < Rq * Rq:
        return None
    b1, b3 = arb(fmpq(x1.numerator, x1.denominator)), arb(fmpq(x3.numerator, x3.denominator))
    v = g.vdot(b1, x2, b3)
    return (b1, x2, b3, v) if certainly_positive(v) else None


def psi_counterexample(g: Gimbal, x2: arb, R: arb, which: int):
    """A point (x1, x2, x3) of the open disc of radius R (exact rationals) where Psi_which <= 0 certainly,
    near the minimiser -R (ci1, ci3)/|(ci1, ci3)| of the affine Psi over the disc; None if not found."""
    c0, c1, c3 = g.psi_coefficients(x2)[which]
    d1, d3 = float(c1.mid()), float(c3.mid())
    norm = math.hypot(d1, d3)
    if norm == 0 or not math.isfinite(norm):
        return None
    Rq = exact_fraction(R.lower())
    for shrink in (Fraction(1) - Fraction(1, 2 ** 30), Fraction(1) - Fraction(1, 2 ** 16)):
        u1 = Fraction(-d1 / norm).limit_denominator(10 ** 15)
        u3 = Fraction(-d3 / norm).limit_denominator(10 ** 15)
        p1, p3 = u1 * Rq * shrink, u3 * Rq * shrink
        if not p1 * p1 + p3 * p3 < Rq * Rq:
            continue
        b1, b3 = arb(fmpq(p1.numerator, p1.denominator)), arb(fmpq(p3.numerator, p3.denominator))
        val = c0 + c1 * b1 + c3 * b3
        if certainly_le(val, 0):
            return b1, x2, b3, val
    return None


#: the rational candidates of a refutation near an irrational end (x2*): its exact lower end, then that end
#: rounded down to j binary digits after the point
INSIDE_STEPS = (0, 48, 40, 30, 20, 12)


def rational_points_inside(w: arb, xs: arb) -> list[arb]:
    """Exact rational points of [-x2*, x2*] near a point ``w`` where a refutation found f <= 0: ``w`` itself when
    it is an exact point, otherwise (the end ball x2* = pi/6, never exact) the exact lower end of the ball, then that end
    rounded down to 48, 40, 30, 20, 12 binary digits (each further inside). Only candidates: each is kept only when it lies certainly
    in (0, x2*], and the caller still certifies its counterexample at it (issue 37 part 3: an irrational end
    as the only witness left v_positive inconclusive at every precision)."""
    if w is None or not w.is_finite():
        return []
    if w.rad().is_zero():
        return [w] if certainly_le(abs(w), xs) else []
    if certainly_negative(w):          # the mirror image: the same candidates, negated
        return [-x for x in rational_points_inside(-w, xs)]
    if not certainly_positive(w):
        return []
    out = []
    lo = exact_fraction(w.lower())
    for j in INSIDE_STEPS:      # lo, then lo rounded down to j binary digits (exact at >= 64 bits)
        q = lo if j == 0 else Fraction(math.floor(lo * 2 ** j), 2 ** j)
        x = arb(fmpq(*_pair(q)))
        if x.rad().is_zero() and certainly_positive(x) and certainly_le(x, xs):
            out.append(x)
    return out


def _pair(q: Fraction) -> tuple[int, int]:
    return q.numerator, q.denominator


@dataclass
class VdotVerdict:
    """The outcome of :func:`certify_vdot_nonpositive`: status, the reason as the report prints it, the
    pieces used, the claim's details, and (when refuted) the certified point (x1, x2, x3, Vdot)."""

    status: Status
    reason: str
    pieces: int
    details: dict = field(default_factory=dict)
    witness: tuple[arb, arb, arb, arb] | None = None
    counterexample: dict | None = None
    decides: arb | None = None



def _refuted_at(how: str, R: arb, w, pieces: int) -> "VdotVerdict":
    """Vdot <= 0 refuted at the certified point ``w`` = (x1, x2, x3, Vdot) of the region of radius R."""
    x1, x2, x3, v = w
    point = {"x1": _fmt(x1, 20), "x2": _fmt(x2, 20), "x3": _fmt(x3, 20), "vdot": _fmt(v, 8)}
    exact = {"x1": ball_text(x1), "x2": ball_text(x2), "x3": ball_text(x3)}
    return VdotVerdict(Status.REFUTED,
                       f"{how} = {_fmt(R)}: grad V . f = {_fmt(v, 6)} > 0 at the point x1 = {_fmt(x1)}, "
                       f"x2 = {_fmt(x2)}, x3 = {_fmt(x3)} of the region (certified)", pieces,
                       {"witness": point}, w, {"point": exact, "vdot": _fmt(v, 20), "radius": _fmt(R, 20)})

def certify_psi_test(g: Gimbal, xs: arb, R: arb, how: str, max_pieces: int,
                     record: dict | None = None) -> VdotVerdict:
    """Decide the paper's test Psi1 > 0 and Psi2 > 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2 (which gives
    Vdot = -Psi1 x1^2 - Psi2 x3^2 <= 0 there).

    Guarantee: PROVED when min over the disc of Psi1 and of Psi2 is certified > 0 on x2 pieces covering
    [-x2*, x2*]; REFUTED only with a certified point of the region where grad V . f > 0 (automatic
    differentiation, not the Psi form: then some Psi_i < 0 there, since Vdot = -Psi1 x1^2 - Psi2 x3^2) or
    where a named Psi_i <= 0 (the test fails; ``counterexample["psi"]``); otherwise INCONCLUSIVE.
    ``how`` names the radius in the reason (e.g. "R = min(R1, R2) from (13), (14)")."""
    if not (R.is_finite() and certainly_positive(R)):
        return VdotVerdict(Status.INCONCLUSIVE, f"{how} = {_fmt(R)} is not certainly a positive radius (e.g. R2 of "
                           "(14) vanishes where mu H cos^2 x2* = A0 m): set option R", 0, decides=R)
    psi1, psi2 = psi_min_functions(g, R)
    results, pieces = {}, 0
    for name, fn in (("Psi1", psi1), ("Psi2", psi2)):
        kept: list = []
        r = certify_positive(fn, -xs, xs, max_pieces=max_pieces, record=kept)
        if record is not None and r.status is Status.PROVED:
            record[name] = pieces_text(kept)
        results[name] = r
        pieces += r.pieces
    if all(r.status is Status.PROVED for r in results.values()):
        return VdotVerdict(Status.PROVED,
                           f"{how} = {_fmt(R)}: min over the disc of Psi1 and of Psi2 certified > 0 on "
                           f"{results['Psi1'].pieces} + {results['Psi2'].pieces} x2 pieces of [-x2*, x2*]; "
                           "Vdot = 0 exactly on x1 = x3 = 0 by the factored form (checked against automatic "
                           "differentiation of (7) along (2))", pieces, {"pieces": pieces})
    # exact points of [-x2*, x2*] (the ends of the x2 range are balls: take its exact lower end)
    points = [r.witness for r in results.values() if r.witness is not None and r.witness.rad().is_zero()
              and certainly_le(abs(r.witness), xs)]
    xq = exact_fraction(xs.lower())
    points += [arb(fmpq((xq * j / 8).numerator, (xq * j / 8).denominator)) for j in range(-8, 9)]
    w = vdot_witness(g, R, points)
    if w is not None:
        return _refuted_at(how, R, w, pieces)
    # no point with Vdot > 0: the statement's "Psi1 > 0 and Psi2 > 0 on the region" may still fail at a
    # certified point (the paper's test, sufficient, not necessary)
    for name, r in results.items():
        if r.status is not Status.REFUTED:
            continue
        # an exact point of [-x2*, x2*]: the ends of the range are balls, take rational points inside
        point = None
        for w in rational_points_inside(r.witness, xs):
            point = psi_counterexample(g, w, R, 0 if name == "Psi1" else 1)
            if point is not None:
                break
        if point is not None:
            x1, x2, x3, val = point
            exact = {"x1": ball_text(x1), "x2": ball_text(x2), "x3": ball_text(x3)}
            return VdotVerdict(Status.REFUTED,
                               f"{how} = {_fmt(R)}: {name} = {_fmt(val, 6)} <= 0 at the point x1 = {_fmt(x1)}, "
                               f"x2 = {_fmt(x2)}, x3 = {_fmt(x3)} of the region (certified): the test Psi1, Psi2 > 0 "
                               "of the statement fails there (Vdot itself may still be <= 0: no point with "
                               "Vdot > 0 was found)", pieces, {}, None,
                               {"point": exact, "psi": name, "value": _fmt(val, 20), "radius": _fmt(R, 20)})
    bad = [f"{k}: {r.reason}" for k, r in results.items() if r.status is not Status.PROVED]
    stuck = next((r.stuck_value for r in results.values() if r.status is not Status.PROVED), None)
    return VdotVerdict(Status.INCONCLUSIVE,
                       f"{how} = {_fmt(R)}: " + "; ".join(bad) + "; no point with certified Vdot > 0 found "
                       "(try a smaller R, higher --maxprec or a larger max_pieces option)", pieces, decides=stuck)


def _direct_point(g: Gimbal, xs: arb, R: arb, witness: dict | None):
    """A point of the open disc of radius R at |x2| <= x2* where Vdot > 0 certainly, from a point (u, s) of the
    (x2, t) domain where A - R |B| <= 0 (the direct test's counterexample): Vdot = -r^2 (A + r B) > 0 at
    r = -sign(B) R' for R' < R close enough to R when A < R |B|; None if not certified."""
    if witness is None:
        return None
    try:
        u, s = (Fraction(str(witness[k])) if not isinstance(witness[k], arb) else exact_fraction(witness[k].mid())
                for k in ("u", "s"))
    except (KeyError, ValueError, TypeError, ZeroDivisionError):
        return None
    x2 = xs * arb(fmpq(u.numerator, u.denominator))
    x2 = arb(fmpq(*(lambda q: (q.numerator, q.denominator))(exact_fraction(x2.mid()))))
    if not certainly_le(abs(x2), xs):
        return None
    t = arb.pi() * arb(fmpq(s.numerator, s.denominator))
    _, B = vdot_polar(g, x2, t)
    if not (certainly_positive(B) or certainly_negative(B)):
        return None
    sgn = -1 if certainly_positive(B) else 1
    Rq = exact_fraction(R.lower())
    for shrink in (Fraction(1) - Fraction(1, 2 ** 40), Fraction(1) - Fraction(1, 2 ** 24), Fraction(1) - Fraction(1, 2 ** 12)):
        r = Rq * shrink
        p1 = Fraction(sgn * float(t.cos().mid())).limit_denominator(10 ** 15) * r
        p3 = Fraction(sgn * float(t.sin().mid())).limit_denominator(10 ** 15) * r
        found = _vdot_positive_at(g, p1, x2, p3, Rq)
        if found is not None:
            return found
    return None


def certify_vdot_nonpositive(g: Gimbal, xs: arb, R: arb, how: str, max_pieces: int,
                             record: dict | None = None) -> VdotVerdict:
    """Decide Vdot = grad V . f <= 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2 (region (17)).

    Guarantee: PROVED when the Psi test proves it (:func:`certify_psi_test`: Psi1, Psi2 > 0 there; the
    record gets its x2 pieces "Psi1", "Psi2") or, where the Psi test does not, when the direct test does
    (A - R |B| > 0 on (x2, t) boxes tiling the domain, :func:`direct_margin`: Vdot < 0 off x1 = x3 = 0; the
    record gets its "boxes"); REFUTED only with a certified point of the region where grad V . f > 0
    (automatic differentiation), never by the failure of a sufficient test; otherwise INCONCLUSIVE."""
    from ...core.subdivision import certify_positive_on_box
    from ...core.boxes import Box
    rec: dict = {}
    psi = certify_psi_test(g, xs, R, how, max_pieces, record=rec)
    if psi.status is Status.PROVED:
        if record is not None:
            record.update(rec)
        return VdotVerdict(Status.PROVED, psi.reason + " (the Psi test)", psi.pieces, {**psi.details, "test": "Psi"})
    if psi.status is Status.REFUTED and psi.witness is not None:       # a point where Vdot > 0 itself
        return psi
    if not (R.is_finite() and certainly_positive(R)):
        return psi
    cert = certify_positive_on_box(symmetric_in_x2(g, direct_margin(g, R)), Box.of(DIRECT_DOMAIN), max_pieces=max_pieces)
    psi_why = psi.reason.split(": ", 1)[-1]
    if cert.status is Status.PROVED:
        if record is not None:
            record["boxes"] = [b.to_json() for b in cert.leaves]
        return VdotVerdict(Status.PROVED,
                           f"{how} = {_fmt(R)}: A - R |B| > 0 certified on {len(cert.leaves)} boxes of (x2, t) (the "
                           "direct test: Vdot = -r^2 (A + r B) < 0 for 0 < r <= R), where the Psi test does not decide "
                           f"({psi_why[:200]})", psi.pieces + len(cert.leaves),
                           {"pieces": psi.pieces, "boxes": len(cert.leaves), "test": "direct"})
    w = _direct_point(g, xs, R, cert.witness) if cert.status is Status.REFUTED else None
    if w is not None:
        return _refuted_at(how, R, w, psi.pieces)
    stuck = cert.witness_value if cert.status is Status.REFUTED else None
    return VdotVerdict(Status.INCONCLUSIVE,
                       f"{how} = {_fmt(R)}: the Psi test does not decide ({psi_why[:300]}); the direct test "
                       f"A - R |B| > 0 does not either ({cert.reason[:200]}); no point with certified Vdot > 0 found "
                       "(try a smaller R, higher --maxprec or a larger max_pieces option)", psi.pieces,
                       decides=psi.decides if psi.decides is not None else stuck)

# ------------------------------------------------------------------------------------ constants, c*
# Closed forms shared by the claims and the checker (rigor-gyro check recomputes them from its own m, M).

def closed_form_constants(g: Gimbal, m: arb, M: arb) -> dict[str, arb]:
    """A0, B0, C0, p = max(M, A0 m / cos^2 x2*), k_min, the mu interval (16), R1 (13), R2 (14), R, for
    enclosures m, M of the maxima (every returned ball contains the value for every m, M in them)."""
    c = g.c
    A0, B0, C0, H, k, mu = c.A0, c.B0, c.C0, c.H, c.k, c.mu
    xs = c.x2_star
    s, cs = xs.sin(), xs.cos()
    pA = A0 * m / cs ** 2
    p = M.max(pA)
    out = {"A0": A0, "B0": B0, "C0": C0, "m": m, "M": M, "A0_m_over_cos2": pA, "p": p,
           "k_min": p * A0 / H, "mu_min": p / H, "mu_max": k / A0}
    Ds = A0 - C0 * s ** 2
    D1 = 108 * A0 * (A0 - C0) * H ** 4 * cs ** 4 * square(k / A0 - mu)
    D2 = 16 * mu ** 2 * A0 * (A0 - C0) * H ** 2 * C0 ** 2 + 27 * square(mu * k * B0 * C0 + (A0 - C0) * H ** 2)
    P = A0 - C0 - C0 * cs ** 2
    E1 = 4 * H ** 2 * square(mu * H * cs ** 2 - m * A0) * Ds ** 4
    E2 = A0 ** 2 * (4 * mu ** 2 * H ** 2 * square(P) * Ds ** 2 * s ** 2 + square(mu * k * B0 * C0 - (A0 - C0) * H ** 2))
    # D1, E1 are squares times positive factors and D2, E2 sums of squares: >= 0 exactly
    R1, R2 = sqrt_of_nonnegative(D1 / D2), sqrt_of_nonnegative(E1 / E2)
    out.update({"R1": R1, "R2": R2, "R": R1.min(R2), "R2_base": mu * H * cs ** 2 - m * A0})
    return out


#: the thresholds in k of the conditions damping_condition needs (mu > p/H of (16) is no threshold in k)
DAMPING_THRESHOLDS = ("k > k_min = p A0/H (18)", "k > mu A0 (mu < k/A0 of (16))")


def damping_margin(g: Gimbal, k_min: arb) -> tuple[arb, str, dict[str, arb]]:
    """The design margin in k of damping_condition: min over its thresholds t in k (k_min of (18) and mu A0,
    from mu < k/A0 of (16)) of k/t - 1, the name of the binding threshold (both names when the two are not
    separated at this precision) and every threshold's k/t - 1. Valid for every k_min in its ball."""
    c = g.c
    each = {name: c.k / t - 1 for name, t in zip(DAMPING_THRESHOLDS, (k_min, c.mu * c.A0))}
    (n1, a), (n2, b) = each.items()
    binding = n1 if certainly_lt(a, b) else n2 if certainly_lt(b, a) else f"{n1} and {n2} (not separated)"
    return a.min(b), binding, each


def _circle_directions(n: int = 32) -> list[tuple[Fraction, Fraction]]:
    """n exact rational points (c, s) of the unit circle, c^2 + s^2 = 1 exactly, near the angles 2 pi j / n:
    c = (1 - t^2) / (1 + t^2), s = 2 t / (1 + t^2) with t = tan(pi j / n) rounded to a float (any rational t
    gives a point of the circle; the float only places it)."""
    out = []
    for j in range(n):
        t = Fraction(math.tan(math.pi * j / n)) if 2 * j != n else None
        out.append((Fraction(-1), Fraction(0)) if t is None else ((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)))
    return out


#: the directions V is sampled in on the cylinder (an upper bound of c*: V at points of the cylinder)
CIRCLE_DIRECTIONS = _circle_directions()


def cylinder_points(R: arb, xs: arb) -> list[tuple[arb, arb, arb]]:
    """96 balls (x1, x2, x3), each containing a point of the cylinder x1^2 + x3^2 = R^2 with |x2| <= x2*
    (for every radius R's ball holds): the 32 CIRCLE_DIRECTIONS, exact rationals of the unit circle, times
    R, at x2 = 0, x2*/2, x2*. V's smallest upper end over them is >= V at a point of the cylinder, so it
    bounds c* (V's minimum over that cylinder piece) from above."""
    return [(R * arb(fmpq(c.numerator, c.denominator)), x2, R * arb(fmpq(s_.numerator, s_.denominator)))
            for x2 in (arb(0), xs / 2, xs) for c, s_ in CIRCLE_DIRECTIONS]


def faces_minimiser_inside(g: Gimbal, xs: arb, R: arb) -> bool:
    """The point (m1, m3) where V is smallest on the face x2 = x2* lies certainly inside the disc
    x1^2 + x3^2 < R^2 (then the faces' closed form phi(x2*) is V's minimum over the face piece of the
    region, and it bounds c* from above as well as below)."""
    m1, m3 = g.phi_minimiser(xs)
    return certainly_lt(m1 ** 2 + m3 ** 2, R ** 2)


def c_star_lower(face: arb, cyl: arb, inside: bool) -> arb:
    """A lower bound of c* = min(V on the faces |x2| = x2* inside the disc, V on the cylinder): ``cyl`` (a
    lower bound of V's minimum on the cylinder), and with the faces' minimiser inside the disc also the
    faces' value phi(x2*)'s lower end (``face`` encloses it). Without the minimiser inside, the faces' minimum
    over the disc lies on its rim, on the cylinder: cyl bounds it."""
    return face.lower().min(cyl) if inside else cyl


def c_star_upper(g: Gimbal, R: arb, xs: arb, face: arb, inside: bool) -> arb:
    """An upper bound of c* (an exact point): the smallest upper end of V over the cylinder points (each
    ball holds V at a point of the cylinder), and with the faces' minimiser inside the disc also the faces'
    value phi(x2*)'s upper end."""
    samples = [g.V(*p) for p in cylinder_points(R, xs)]
    upper = samples[0]
    for s in samples[1:]:
        upper = upper.min(s)
    return upper.upper().min(face.upper()) if inside else upper.upper()


def cylinder_lower_bound(g: Gimbal, R: arb):
    """x2 piece -> a lower bound of min over theta of V(R cos theta, x2, R sin theta).

    On the circle V = alpha + beta sin(th) + gamma cos(2 th) + delta sin(2 th) with
    alpha = mu F + (f2 + mu f1 + h^2) R^2/4, beta = f3 R, gamma = (h^2 - f2 - mu f1) R^2/4,
    delta = mu h R^2/2 (h = H cos x2 / B0), so V >= alpha - |beta| - sqrt(gamma^2 + delta^2)."""
    c = g.c

    def lb(x2):
        h = c.H * x2.cos() / c.B0
        e = g.f2(x2) + c.mu * g.f1(x2)
        alpha = c.mu * g.F(x2) + (e + h * h) * R * R / 4
        gamma = (h * h - e) * R * R / 4
        delta = c.mu * h * R * R / 2
        return alpha - abs(g.f3(x2)) * R - hypot_ball(gamma, delta)
    return lb


# --------------------------------------------------------------------------- Vdot <= 0 directly

#: the (x2, t) domain of the direct test, in exact coordinates: x2 = u x2*, t = pi s
DIRECT_DOMAIN = {"u": (Fraction(-1), Fraction(1)), "s": (Fraction(0), Fraction(1))}


def vdot_polar(g: Gimbal, x2, t, mu: arb | None = None):
    """(A, B) with Vdot(r cos t, x2, r sin t) = -r^2 (A + r B) for every r, exactly (Vdot's Psi form:
    A = c10 cos^2 t + c20 sin^2 t, B = c11 cos^3 t + c13 sin t cos^2 t + c21 cos t sin^2 t + c23 sin^3 t).
    Accepts balls or :class:`Dual` numbers in x2 and t; ``mu``: a ball, for every mu in it (default the
    scene's mu)."""
    (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(x2) if mu is None else g.psi_coefficients(x2, mu)
    c, s = t.cos(), t.sin()
    A = c10 * c * c + c20 * s * s
    B = c11 * c * c * c + c13 * s * c * c + c21 * c * s * s + c23 * s * s * s
    return A, B


def symmetric_in_x2(g: Gimbal, f):
    """The (u, s) box function ``f`` of :func:`direct_margin` or :func:`sublevel_lower_bound`, evaluating
    a box with u < 0 as its mirror image u -> -u and each box once (:func:`rigor_gyro.core.boxes.even_in`)
    when g's law is odd; ``f`` itself otherwise. The prover and the checker both wrap, so they get the
    same ball on every box.

    Why it is valid: with f odd (so f' even) and D, cos even in x2, the coefficients c10, c20 of
    :meth:`Gimbal.psi_coefficients` are even in x2 and c11, c13, c21, c23 odd, so in the polar form
    (:func:`vdot_polar`) A(-x2, t) = A(x2, t) and B(-x2, t) = -B(x2, t): A - R |B| is even in u. For V,
    F and the S term are even and f3 odd, so the part of {Vdot >= 0} above the box -U x S is the
    point reflection p -> -p of the part above U x S, where V takes the same values."""
    return even_in(f, "u") if law_is_odd(g.law) else f


def law_is_odd(law: MomentLaw) -> bool:
    """Whether the law declares itself odd in its own class (a subclass that changes f does not inherit
    the declaration) and f(-x) = -f(x) is not contradicted at three points (a check that can only
    refuse: the declaration is the law's theorem, read off its formula)."""
    if not type(law).__dict__.get("odd", False):
        return False
    a = arb(1)
    return all((law.f(a, -x) + law.f(a, x)).contains(0) for x in (arb("0.3"), arb("0.7"), arb("1.3")))


def direct_radius_upper(g: Gimbal, u: fmpq, s: fmpq, mu: arb) -> arb:
    """An upper bound, valid for every mu in the ball ``mu``, of the supremum radius of the direct test: the
    largest R with Vdot <= 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2 (R_dsup(mu)). +inf when nothing is known.

    Why: at the point x2 = u x2* (|u| <= 1 exact, inside the range), t = pi s, Vdot(r cos t, x2, r sin t)
    = -r^2 (A + r B) (:func:`vdot_polar`). Where B != 0, r = -sign(B) rho (1 + delta) with rho = A / |B|
    gives Vdot > 0 for every delta > 0 when A > 0, and any small r of that sign does when A <= 0: so
    R_dsup(mu) <= max(rho(mu), 0).

    How: where d rho / d mu (forward-mode over the ball) has one sign, max(rho, 0) is monotone on the
    ball and its maximum is taken at the exact end it points to (no dependency overestimation: mu enters
    A and B through terms of size H^2 that cancel); otherwise the ball evaluation over the whole ball.
    Either way the upper end of max(A, 0).upper / |B|.lower."""
    if not certainly_le(abs(arb(u)), 1):
        return arb("inf")
    X, T = g.c.x2_star * arb(u), arb.pi() * arb(s)
    A, B = vdot_polar(g, X, T, mu)
    if not (A.is_finite() and B.is_finite()) or not (certainly_positive(B) or certainly_negative(B)):
        return arb("inf")
    if not mu.rad().is_zero():
        Ad, Bd = vdot_polar(g, X, T, Dual(mu, arb(1)))
        slope = (Ad / Bd).d if certainly_positive(B) else -(Ad / Bd).d
        end = mu.upper() if certainly_le(arb(0), slope) else mu.lower() if certainly_le(slope, 0) else None
        if end is not None:
            A, B = vdot_polar(g, X, T, end)
            if not (A.is_finite() and (certainly_positive(B) or certainly_negative(B))):
                return arb("inf")
    num = A.upper() if certainly_positive(A.upper()) else arb(0)
    return (num / abs(B).lower()).upper()


def direct_margin(g: Gimbal, R: arb):
    """The box function {u, s} -> A - R |B| at x2 = u x2*, t = pi s (see :func:`vdot_polar`), enclosed
    in a centered (mean-value) form where B has one sign on the box, intersected with the direct one.

    Guarantee: if it is > 0 on boxes covering DIRECT_DOMAIN, then for every (x2, t) with |x2| <= x2*,
    A > R |B| >= 0, so A + r B > 0 for all 0 <= r <= R (affine in r): Vdot < 0 on the whole region
    |x2| <= x2*, 0 < x1^2 + x3^2 <= R^2 (B(t + pi) = -B(t), A(t + pi) = A(t): t in [0, pi] suffices)."""
    xs, pi = g.c.x2_star, arb.pi()

    def at(U, S):
        return vdot_polar(g, xs * U, pi * S)

    def f(box: dict) -> arb:
        U, S = box["u"], box["s"]
        A, B = at(U, S)
        direct = A - R * abs(B)
        if U.rad().is_zero() and S.rad().is_zero() or certainly_positive(direct):
            # a point, or already positive: the centered form (a subset of a positive ball) decides nothing
            # more (only the sign is used: leaves and refutations are the same with or without it)
            return direct
        if certainly_positive(B):
            sgn = 1
        elif certainly_negative(B):
            sgn = -1
        else:
            return direct
        # one direction at a time, the other argument a plain ball (no zero-derivative dual arithmetic:
        # the t-derivative needs psi_coefficients only as balls)
        Au, Bu = at(Dual(U, arb(1)), S)
        As, Bs = at(U, Dual(S, arb(1)))
        um, sm = arb(U.mid()), arb(S.mid())
        Am, Bm = at(um, sm)
        mv = (Am - R * abs(Bm) + (Au.d - R * sgn * Bu.d) * (U - um) + (As.d - R * sgn * Bs.d) * (S - sm))
        if not mv.is_finite():
            return direct
        return direct.intersection(mv) if direct.overlaps(mv) else mv
    return f


# --------------------------------------------------------------------------- the largest sublevel set

def v_polar(g: Gimbal, x2, t):
    """(alpha, beta, gamma) with V(r cos t, x2, r sin t) = alpha + beta r + gamma r^2 for every real r,
    exactly: alpha = mu F, beta = f3 sin t, gamma = ((h cos t + mu sin t)^2 + S sin^2 t) / 2 with
    h = H cos x2 / B0 (a sum of squares where S > 0: V is a convex quadratic in r)."""
    c = g.c
    ct, st = t.cos(), t.sin()
    h = c.H * x2.cos() / c.B0
    gamma = ((h * ct + c.mu * st) ** 2 + g.S(x2) * st * st) / 2
    if type(x2) is arb and type(t) is arb and not certainly_positive(gamma.lower()) and \
            not certainly_gt(x2.cos().lower(), GIMBAL_LOCK_COS):
        # near the gimbal lock h cos t and cos^2 x2 span wide balls and Arb's square, mid^2 - 2 |mid| rad - rad^2 at
        # its lower end, reaches below 0 ([-0.36, 13.3] for x2 within 1e-3 of pi/2): squares from the balls' ends
        # instead (>= 0, and > 0 where the ball excludes 0). Only near the lock (cos x2 <= GIMBAL_LOCK_COS on the
        # box) and only where the direct form does not decide: every certificate away from the lock is unchanged.
        # S = f2 + mu (f1 - mu) with f2 = H^2 cos^2 x2 / (D B0): its cos^2 from the ends too
        S = c.H ** 2 * square_from_ends(x2.cos()) / (g.D(x2) * c.B0) + c.mu * (g.f1(x2) - c.mu)
        tight = (square_from_ends(h * ct + c.mu * st) + S * square_from_ends(st)) / 2
        if tight.is_finite():
            gamma = tight
    return (c.mu * g.F(x2), g.f3(x2) * st, gamma)


#: v_polar squares from the balls' ends where cos x2 may be below this (the gimbal lock; see v_polar)
GIMBAL_LOCK_COS = arb(1) / 8


def square_from_ends(x: arb) -> arb:
    """A ball containing y^2 for every y in the ball x, from the ends of |x| (never below 0)."""
    a = abs(x)
    lo = arb(0) if x.contains(0) else a.lower()
    hi = a.upper()
    return (lo * lo).union(hi * hi)


def sublevel_lower_bound(g: Gimbal):
    """The box function {u, s} -> a ball whose lower end is <= V(r cos t, x2, r sin t) for every x2 = u x2*,
    t = pi s in the box and every real r != 0 with Vdot >= 0 there (Vdot = -r^2 (A + r B), see
    :func:`vdot_polar`, so those r are the half-line r B <= -A), i.e. a lower bound of V over the part of
    {Vdot >= 0, (x1, x3) != 0} above the box (+inf where that part is empty).

    How: where A > 0 certainly, |r| >= A/|B| (its lower end over the box) and, when B has one sign, the
    sign of r is known; V = alpha + beta r + gamma r^2 is then bounded below over that half-line by its
    lower-end quadratic (gamma's lower end must be > 0: S > 0 and cos x2 > 0). Where A may be <= 0 the
    whole line r != 0 is admitted (the global minimum of the quadratic). Valid for t in [0, pi] with r of
    either sign, which covers every direction of (x1, x3).

    Guarantee: a lower bound over the box, never an enclosure (a point's value is not V's minimum)."""
    xs, pi = g.c.x2_star, arb.pi()

    def f(box: dict) -> arb:
        X, T = xs * box["u"], pi * box["s"]
        A, B = vdot_polar(g, X, T)
        alpha, beta, gamma = v_polar(g, X, T)
        glo = gamma.lower()
        if not (glo.is_finite() and certainly_positive(glo) and alpha.is_finite() and beta.is_finite()):
            return arb("-inf")
        if certainly_positive(A):
            bhi = abs(B).upper()
            if not bhi.is_finite():
                return arb("-inf")
            if certainly_le(bhi, 0):
                return arb("inf")           # A + r B = A > 0 for every r: Vdot < 0 off r = 0
            rho = (A.lower() / bhi).lower()
            if certainly_positive(B):
                b = (-beta).lower()         # r = -s, s >= rho
            elif certainly_negative(B):
                b = beta.lower()            # r = s, s >= rho
            else:
                b = -(abs(beta).upper())
        else:
            rho, b = arb(0), -(abs(beta).upper())
        a = alpha.lower()
        # the minimum over s >= rho of a + b s + glo s^2 (valid below alpha + beta' s + gamma s^2 for s >= 0)
        if certainly_le(-b / (2 * glo), rho):
            return a + b * rho + glo * rho * rho
        return a - b * b / (4 * glo)
    return f


# --------------------------------------------------------------------------- extents of {V < c}

def slice_extent(g: Gimbal, c: arb, axis: str):
    """x2 (a ball) -> an upper bound of max |x_axis| over the slice {(x1, x3): V(x1, x2, x3) < c} (axis
    "x1" or "x3"), exact where the slice is certainly non-empty. At fixed x2, V is a convex quadratic in
    (x1, x3) with minimum phi(x2) at z0 = (mu f3/(h S), -f3/S) (h = H cos x2 / B0), so the slice is the
    ellipse 1/2 (z - z0)' P (z - z0) < c - phi, P^-1 = [[S + mu^2, -mu h], [-mu h, h^2]] / (h^2 S):

        max |x1| = (mu |f3| / S + sqrt(2 (c - phi) (S + mu^2) / S)) / h,  max |x3| = |f3| / S + sqrt(2 (c - phi) / S).

    Where c - phi < 0 certainly the slice is empty and 0 is returned (the set's maximum is >= 0: it
    contains the origin); where c - phi may be either sign, [0, its upper end] replaces it (an upper bound).
    Guarantee: an upper bound everywhere; the exact maximum (a ball containing it) where c > phi certainly."""
    mu = g.c.mu

    def smooth(x2):             # where c > phi and f3 > 0: no case split, so it takes Dual numbers
        S = g.S(x2)
        d, f3 = c - g.phi(x2), g.f3(x2)
        if axis == "x1":
            return (mu * f3 / S + (2 * d * (S + mu * mu) / S).sqrt()) / (g.c.H * x2.cos() / g.c.B0)
        return f3 / S + (2 * d / S).sqrt()
    centred = mean_value_enclosure(smooth)

    def e(x2):
        if not x2.rad().is_zero() and certainly_positive(c - g.phi(x2)) and certainly_positive(g.f3(x2)):
            # the mean-value form: at a flat maximum its overestimation is quadratic in the piece width
            v = centred(x2)
            if v.is_finite():
                return v
        S = g.S(x2)
        d = c - g.phi(x2)
        if certainly_lt(d, 0):
            return arb(0)
        if not certainly_positive(d):
            d = arb(0).union(d.upper())
        f3 = abs(g.f3(x2))
        # d is >= 0 here (d itself, or the hull of 0 and its upper end): its ball may reach below 0
        if axis == "x1":
            return (mu * f3 / S + sqrt_of_nonnegative(2 * d * (S + mu * mu) / S)) / (g.c.H * x2.cos() / g.c.B0)
        return f3 / S + sqrt_of_nonnegative(2 * d / S)
    return e


def slice_in_region(g: Gimbal, c: arb, R: arb, x2) -> bool:
    """Certainly: the slice {V(., x2, .) < c} is non-empty (c > phi(x2)) and its centre z0 lies inside
    the disc x1^2 + x3^2 < R^2. With V >= c on the cylinder of radius R (c <= c*), the whole slice then
    lies in the disc (it is convex and cannot cross the circle), so it is a slice of {x in (17): V < c}."""
    S = g.S(x2)
    f3 = g.f3(x2)
    h = g.c.H * x2.cos() / g.c.B0
    z1, z3 = g.c.mu * f3 / (h * S), -f3 / S
    return certainly_positive(c - g.phi(x2)) and certainly_lt(z1 * z1 + z3 * z3, R * R)
