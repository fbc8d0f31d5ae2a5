"""Moment laws f(x2) on the outer-ring axis of the gimbal gyroscope (Agafonov et al. 2013).

A law is everything the Lyapunov scene needs to know about f: the values f, f' and f(x)/x (the
last continued analytically through x = 0, so quotients that are 0/0 at the equilibrium are
enclosed rigorously, never skipped), and G(x) = int_0^x cos(s) f(s) / D(s) ds with
D(s) = A0 - C0 sin^2 s (so that F = (H/B0) G is the integral in the Lyapunov function (7)).

A scene may also write its own law in a ``[moment]`` table (issue 42): ``moment = "expression"`` (a formula,
:mod:`.moment_expr`) or ``moment = "table"`` (measured points, :mod:`.moment_table`), chosen by
:mod:`.moment_scene`; an expression that is exactly ``a*sin(x2)`` or ``a*x2`` gets the class here (the fast
path). To add a built-in law, write a class with these methods and add one line to :data:`MOMENTS`; a scene
names it with ``moment = "<name>"``. Every law must be odd (certified, never assumed: the claims use the
symmetry x2 -> -x2) with x f(x) > 0 for 0 < |x| < pi/2 (the scene certifies f(x)/x > 0 over its range; a law
violating it is not proved, not trusted).

Guarantee: each method returns a ball containing the exact value for every x in the ball argument,
at the current working precision (set by the caller through :mod:`rigor_gyro.core.balls`).

Fails when: a ball argument is too wide for the method (e.g. G's quadrature on a wide ball returns a
wide or non-finite enclosure; callers then subdivide further or report inconclusive).
"""
from __future__ import annotations

from fractions import Fraction

from flint import acb, arb

from ...core import quadrature
from ...core.balls import certainly_lt, current_precision

__all__ = ["MOMENTS", "MomentLaw", "SineMoment", "LinearMoment", "log1m_ratio", "log1m_tail", "moment_law"]


def log1m_tail(r: arb, n: int) -> arb:
    """An upper bound of the series' remainder sum_{k>=n} r^k / (k + 1) for 0 <= r < 1 (``r`` an exact
    point): r^n / ((n + 1)(1 - r)), the geometric series of r^n / (n + 1). Precision: the current one."""
    return r ** n / ((n + 1) * (1 - r))


def log1m_ratio(u: arb) -> arb:
    """L(u) = -log(1 - u) / u = sum_{n>=0} u^n / (n + 1), with L(0) = 1, for every u in the ball.

    For |u| <= 1/2 by the series (no 0/0, and no dependency blow-up on balls where u changes by a
    large factor), summed until the tail bound |u|^N / ((N+1)(1-|u|)) is below 2^-(prec+8);
    otherwise directly as -log1p(-u)/u (u then excludes 0)."""
    r = abs(u).upper()
    if not r <= arb(1) / 2:
        if u.contains(0):
            return arb("nan")
        return -(-u).log1p() / u
    eps = arb(2) ** (-(current_precision() + 8))
    s, p, n = arb(0), arb(1), 0
    while True:
        s += p / (n + 1)
        p *= u
        n += 1
        tail = log1m_tail(r, n)
        if tail < eps or n > 8 * current_precision():
            return s + arb(0, tail.upper())


class MomentLaw:
    """Interface (see the module docstring). ``a`` is the law's amplitude parameter as a ball."""

    name = ""
    formula = ""
    G_on_balls = False                 # True: G's formula encloses G over wide balls directly
    #: True only for a law that is odd by its formula (f(-x) = -f(x), so f' is even): the polar forms of
    #: Vdot and V are then symmetric under x2 -> -x2, and the (x2, t) branch and bounds evaluate a box
    #: as its mirror image (:func:`rigor_gyro.kinds.lyapunov.model.symmetric_in_x2`). Declare it in the
    #: law's own class: a subclass that changes f does not inherit it (``model.law_is_odd``)
    odd = False

    def f(self, a: arb, x):            # f(x); x may be an arb or a rigor_gyro.kinds.lyapunov.model.Dual
        raise NotImplementedError

    def df(self, a: arb, x):           # f'(x)
        raise NotImplementedError

    def f_over_x(self, a: arb, x: arb) -> arb:   # f(x)/x, analytic through 0
        raise NotImplementedError

    def G(self, a: arb, A0: arb, C0: arb, x: arb) -> arb:
        """int_0^x cos(s) f(s) / (A0 - C0 sin^2 s) ds for a point (or thin ball) x."""
        raise NotImplementedError

    def q_closed(self, a: arb, A0: arb, C0: arb, x: arb) -> arb | None:
        """Optional closed form of f^2 / (2 D G) on a ball x (None: use the generic enclosure)."""
        return None

    def zeros_over_pi(self) -> tuple:
        """Exact zeros of f with |x| <= pi, as rational multiples r of pi (f(r pi) = 0 exactly); a root the
        equilibrium search finds elsewhere must be certainly inside or outside |x| <= pi."""
        return ()


class SineMoment(MomentLaw):
    """f = a sin x2 (the paper's example). G = a/(2 C0) ln(A0/D) in closed form and
    q = f^2/(2 D G) = a / ((1 - u) L(u)), u = C0 sin^2 x2 / A0, L from :func:`log1m_ratio`."""

    name = "sine"
    formula = "f(x2) = a sin x2"
    G_on_balls = True
    odd = True

    def f(self, a, x):
        return a * x.sin()

    def zeros_over_pi(self):
        return (Fraction(-1), Fraction(0), Fraction(1))

    def df(self, a, x):
        return a * x.cos()

    def f_over_x(self, a, x):
        return a * x.sinc()

    def G(self, a, A0, C0, x):
        u = C0 * x.sin() ** 2 / A0
        if C0.is_zero():
            return a * x.sin() ** 2 / (2 * A0)
        return a / (2 * C0) * (-(-u).log1p())

    def q_closed(self, a, A0, C0, x):
        u = C0 * x.sin() ** 2 / A0
        return a / ((1 - u) * log1m_ratio(u))


class LinearMoment(MomentLaw):
    """f = a x2 (the paper's 'linear approximation', taken here as the law of a nonlinear system).
    G by rigorous quadrature (Arb's acb.integral) at points; no closed form of q."""

    name = "linear"
    formula = "f(x2) = a x2"
    odd = True

    def f(self, a, x):
        return a * x

    def zeros_over_pi(self):
        return (Fraction(0),)

    def df(self, a, x):
        return a + 0 * x

    def f_over_x(self, a, x):
        return a + 0 * x

    def G(self, a, A0, C0, x):
        if x.is_zero():
            return arb(0)
        # a factored out where |a| < 1: the quadrature's absolute tolerance (2^-prec) swamped a = 1e-300 (G a ball
        # around 0, q = f^2/(2 D G) NaN); |a| >= 1 keeps a inside (the same enclosure as before, bit for bit)
        small = certainly_lt(abs(a), 1)
        A0c, C0c, ac = acb(A0), acb(C0), acb(1 if small else a)

        def integrand(t, analytic):
            return ac * t * t.cos() / (A0c - C0c * t.sin() ** 2)
        integral = quadrature.integral(integrand, 0, acb(x)).real
        return a * integral if small else integral


#: moment name (as written in a scene) -> law
MOMENTS: dict[str, MomentLaw] = {law.name: law for law in (SineMoment(), LinearMoment())}


def moment_law(name: str) -> MomentLaw:
    """The law called ``name``; KeyError lists the known ones."""
    try:
        return MOMENTS[name]
    except KeyError:
        raise KeyError(f"unknown moment {name!r}; known: {sorted(MOMENTS)}") from None
