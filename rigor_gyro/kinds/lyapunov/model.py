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

What is built on the model lives beside it: the certified Vdot <= 0 on region (17) in :mod:`.vdot_tests`, the
polar forms of Vdot and V over (x2, t) in :mod:`.polar_forms`, the closed forms of the constants and of c* in
:mod:`.closed_forms`.

Guarantee: every method returns a ball containing the exact value for every argument in the ball
arguments, at the current working precision; parameters are exact rationals (x2* may be a rational
multiple of pi).
"""

from __future__ import annotations

from dataclasses import dataclass

from flint import arb, ctx as _ctx, fmpq

from ...core.balls import ball_key, current_precision, square
from ...core.exact import Exact
from .moments import MomentLaw

__all__ = ["Dual", "Gimbal", "MEMO_LIMIT", "ParameterBalls", "hypot_ball", "mean_value_enclosure", "psi_from_parts",
           "sin_cos"]

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
