"""Float (numpy/scipy) and mpmath cross-checks for the Lyapunov scene (Agafonov et al. 2013). No guarantees.

Nothing here decides a verdict: these are the ``approx`` side of :mod:`rigor_gyro.kinds.lyapunov.claims`. They take
the scene's parameters as exact strings (keys ``A, C, A1, B1, C1, A2, H, k, a, x2_star, mu, moment``),
parse them with :func:`rigor_gyro.core.exact.parse_exact` and build every formula again here, independently of
the ball code (:mod:`rigor_gyro.kinds.lyapunov.model`, :mod:`rigor_gyro.kinds.lyapunov.moments`).

Model (x1 = alpha-dot, x2 = beta, x3 = beta-dot; A0 = A + A1 + A2, B0 = A + B1, C0 = A + A1 - C1,
D = A0 - C0 sin^2 x2): system (2)

    x1' = [C0 sin 2x2 x1 x3 - H cos x2 x3 - k x1 - f(x2)] / D,   x2' = x3,
    x3' = [-1/2 C0 sin 2x2 x1^2 + H cos x2 x1] / B0,

Lyapunov function (7) V = mu F + x3 f3 + 1/2 (f2 + mu f1) x3^2 + mu (H/B0) cos x2 x1 x3
+ H^2/(2 B0^2) cos^2 x2 x1^2 with f1 = k/D, f2 = H^2 cos^2/(D B0), f3 = H cos f/(D B0), F = (H/B0) G,
G(x) = int_0^x cos f / D, and Vdot = grad V . f = -Psi1 x1^2 - Psi2 x3^2, Psi_i = ci0 + ci1 x1 + ci3 x3
with the *audited* coefficients (:meth:`FloatGimbal.psi_true`); the printed (8) differs only in the
x3-term of Psi2 (sin 2x2 where grad V . f has sin x2 cos x2: a factor 2), :meth:`FloatGimbal.psi_printed`.

What is here:

* :class:`FloatGimbal`: numpy-vectorised rhs (2), V (7), its analytic gradient dotted with (2), the
  Psi coefficients (audited and printed).
* :func:`mp_constants`: mpmath values (default 50 digits) of every quantity of the scene, by closed forms
  where the moment law has them and by quadrature otherwise; maxima and minima over x2 (and the boundary
  minimum c*) located on a float grid and refined in mpmath. A *search*, not a certificate: a grid can miss
  a narrow extremum. :func:`float_constants` is the same pipeline in float64.
* :func:`time_scales`: the linearisation at 0 (nutation frequency, decay rates).
* :func:`trajectories`, :func:`edge_points`: scipy ``solve_ivp`` runs from the edge of {V < c*} and
  from outside the box.

Guarantee: none. Every number is a float or mpmath estimate; the mpmath ones are good to about
``dps - 5`` digits where the extremum search found the right optimum (closed forms and quadrature are
accurate to working precision; golden-section refinement locates an optimum to ~dps/2 digits, which
gives its value to ~dps digits).

Requires: the parameter dict of the scene (strings; ``x2_star`` may be ``"pi/6"``, ``"0.5*pi"``, a decimal).

Fails when: a parameter is missing or malformed (ParameterError naming it); an mpmath extremum is
narrower than the float grid (it is then missed, silently: cross-check with the certificate).

Example:
    >>> from rigor_gyro.kinds.lyapunov.approx import mp_constants, AGAFONOV2013
    >>> c = mp_constants(AGAFONOV2013, dps=30)
    >>> print(mpmath.nstr(c["M"], 15), mpmath.nstr(c["R1"], 12))
    101.410404218403 0.0182811298149

Reference: Agafonov S. A., Kostyushko I. A., Shvydka S. P., Kuzemko A. V. (2013), On the stability of
steady motion of a gyroscope in gimbals (seed 000 in shared/seeds).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from fractions import Fraction

import mpmath
import numpy as np

from ...core.errors import ParameterError
from ...core.exact import parse_exact
from .search import compass, grid_then_compass

__all__ = ["AGAFONOV2013", "PARAMETER_NAMES", "FLOAT_MOMENTS", "FloatGimbal", "MpGimbal", "mp_constants",
           "float_constants", "time_scales", "trajectories", "TrajectoryOutcome", "edge_points", "EdgePoints",
           "V_MONOTONE_REL_TOL", "DEFAULT_METHOD", "DEFAULT_RTOL", "BENCH_NAMES", "bench_float", "bench_mpmath",
           "mp_polar_estimates"]

#: the paper's example (section 3), exactly as in rigor_gyro/scenes/agafonov2013.toml
AGAFONOV2013 = {"A": "2", "C": "3.3", "A1": "2.2", "B1": "2.2", "C1": "2.8", "A2": "8.5", "H": "1e4",
                "k": "0.4", "a": "100", "x2_star": "pi/6", "mu": "0.02", "moment": "sine"}
PARAMETER_NAMES = ("A", "C", "A1", "B1", "C1", "A2", "H", "k", "a", "x2_star", "mu", "moment")

#: solve_ivp defaults for :func:`trajectories` (see its docstring for the measured choice)
DEFAULT_METHOD = "LSODA"
DEFAULT_RTOL = 1e-9
#: V is "non-increasing along the samples" when no step-to-step increase exceeds this times the largest
#: |V| seen: the local error of one step is ~rtol relative in the state, so ~2 rtol in the quadratic V;
#: 1e-7 leaves two orders of slack over DEFAULT_RTOL while the true decrease over one nutation period at
#: the example is ~1e-4 relative (rate 2 a/H over 4.6 ms), so a real increase would not hide under it.
V_MONOTONE_REL_TOL = 1e-7
#: points returned by :func:`edge_points` are this fraction inside the bisected edge V = c* along the ray
EDGE_INSET = 1e-6
#: grid sizes of the float searches that mp_constants refines
X2_GRID = 2001
THETA_GRID = 720
MU_GRID = 121
#: Gauss-Legendre nodes for the float G of a law without a closed form (integrand analytic on [0, x2*])
GL_NODES = 64


# ------------------------------------------------------------------------------------ backends

class _NumpyLib:
    """Elementary functions for float64 arrays."""
    name = "float"
    sin, cos, sqrt, log1p, hypot, fabs = np.sin, np.cos, np.sqrt, np.log1p, np.hypot, np.abs
    pi = math.pi
    inf = math.inf

    @staticmethod
    def sinc(x):                       # sin(x)/x, 1 at 0 (numpy's sinc is sin(pi x)/(pi x))
        return np.sinc(np.asarray(x, dtype=float) / np.pi)

    @staticmethod
    def num(q: Fraction):
        return q.numerator / q.denominator if abs(q.numerator) < 2 ** 1000 else float(q)

    @staticmethod
    def one_like(x):
        return np.ones_like(np.asarray(x, dtype=float))


class _MpLib:
    """Elementary functions for mpmath scalars (at mpmath's current precision)."""
    name = "mpmath"
    sin, cos, sqrt, log1p, hypot, fabs, sinc = (staticmethod(mpmath.sin), staticmethod(mpmath.cos),
                                                staticmethod(mpmath.sqrt), staticmethod(mpmath.log1p),
                                                staticmethod(mpmath.hypot), staticmethod(mpmath.fabs),
                                                staticmethod(mpmath.sinc))
    inf = mpmath.inf

    @property
    def pi(self):
        return +mpmath.pi

    @staticmethod
    def num(q: Fraction):
        return mpmath.mpf(q.numerator) / q.denominator

    @staticmethod
    def one_like(x):
        return mpmath.mpf(1)


class _MathLib:
    """Python floats through the math module (the fast scalar rhs of one trajectory)."""
    name = "math"
    sin, cos, sqrt, log1p, hypot, fabs = math.sin, math.cos, math.sqrt, math.log1p, math.hypot, abs

    @staticmethod
    def sinc(x):
        return math.sin(x) / x if x else 1.0

    @staticmethod
    def one_like(x):
        return 1.0


NP, MP, MATH = _NumpyLib(), _MpLib(), _MathLib()


# ------------------------------------------------------------------------------------ moment laws

class _Law:
    """A moment law f(x2) for the float/mpmath side. ``lib`` is NP or MP. To add a law: a class here and
    a line in FLOAT_MOMENTS (and its ball twin in rigor_gyro/kinds/lyapunov/moments.py)."""
    name = ""
    odd = True                                   # f(-x) = -f(x): V, Psi are then symmetric in x2

    def f(self, a, x, lib):
        raise NotImplementedError

    def df(self, a, x, lib):
        raise NotImplementedError

    def f_over_x(self, a, x, lib):              # f(x)/x continued through 0 (removes the 0/0 of M)
        raise NotImplementedError

    def G(self, a, A0, C0, x, lib):             # closed form of int_0^x cos f / D, or None
        return None

    def q(self, a, A0, C0, x, lib):             # closed form of f^2 / (2 D G), or None
        return None


def _L(u, lib):
    """L(u) = -log(1 - u)/u, L(0) = 1 (series for small |u|, where the closed form loses digits)."""
    if lib is NP:
        u = np.asarray(u, dtype=float)
        small = np.abs(u) < 1e-4
        us = np.where(small, 0.5, u)
        direct = -np.log1p(-us) / us
        series = 1 + u / 2 + u * u / 3 + u ** 3 / 4
        return np.where(small, series, direct)
    if u == 0:
        return mpmath.mpf(1)
    return -mpmath.log1p(-u) / u


class _Sine(_Law):
    name = "sine"

    def f(self, a, x, lib):
        return a * lib.sin(x)

    def df(self, a, x, lib):
        return a * lib.cos(x)

    def f_over_x(self, a, x, lib):
        return a * lib.sinc(x)

    def G(self, a, A0, C0, x, lib):
        s2 = lib.sin(x) ** 2
        return a * s2 / (2 * A0) * _L(C0 * s2 / A0, lib)      # = a/(2 C0) ln(A0/D), also for C0 = 0

    def q(self, a, A0, C0, x, lib):
        u = C0 * lib.sin(x) ** 2 / A0
        return a / ((1 - u) * _L(u, lib))                     # the paper's closed form, 0/0 removed


class _Linear(_Law):
    name = "linear"

    def f(self, a, x, lib):
        return a * x

    def df(self, a, x, lib):
        return a * lib.one_like(x)

    def f_over_x(self, a, x, lib):
        return a * lib.one_like(x)


#: moment name -> law (float/mpmath side)
FLOAT_MOMENTS: dict[str, _Law] = {law.name: law for law in (_Sine(), _Linear())}


# ------------------------------------------------------------------------------------ parameters

def _parse(params: dict, moment: dict | None = None) -> tuple[dict[str, tuple[Fraction, int]], _Law]:
    """Exact values (rational, pi power) of the parameters, and the law (``moment``: the scene's [moment] table,
    for a law written in the scene, :mod:`.approx_moments`); ParameterError names the culprit."""
    if not isinstance(params, dict):
        raise ParameterError(f"parameters must be a dict of strings, got {type(params).__name__}")
    missing = [k for k in PARAMETER_NAMES if k not in params]
    if missing:
        raise ParameterError(f"missing parameter(s) {missing}")
    unknown = sorted(set(params) - set(PARAMETER_NAMES))
    if unknown:
        raise ParameterError(f"unknown parameter(s) {unknown}; expected {list(PARAMETER_NAMES)}")
    law = FLOAT_MOMENTS.get(params["moment"])
    if moment:
        from .approx_moments import float_scene_law
        law = float_scene_law(params, moment)
    if law is None:
        raise ParameterError(f"parameter 'moment' = {params['moment']!r}: unknown; known {sorted(FLOAT_MOMENTS)}")
    out = {}
    for k in PARAMETER_NAMES[:-1]:
        e = parse_exact(params[k], k)
        if e.pi_power and k != "x2_star":
            raise ParameterError(f"parameter {k!r}: must be rational (got {e.text!r})")
        out[k] = (e.rational, e.pi_power)
    q = {k: v[0] for k, v in out.items()}
    if not q["A"] + q["A1"] + q["A2"] > q["A"] + q["A1"] - q["C1"]:
        raise ParameterError("parameters 'A2', 'C1': need A0 > C0")
    xs = float(q["x2_star"]) * (math.pi if out["x2_star"][1] else 1)
    if not 0 < xs < math.pi / 2:
        raise ParameterError(f"parameter 'x2_star' = {params['x2_star']!r}: need 0 < x2_star < pi/2")
    for k in ("k", "mu", "H"):
        if not q[k] > 0:
            raise ParameterError(f"parameter {k!r} = {params[k]!r}: need > 0")
    return out, law


class _Model:
    """System (2), V (7) and the Psi form over one backend (float64 arrays or mpmath scalars)."""

    def __init__(self, params: dict, lib, moment: dict | None = None):
        exact, self.law = _parse(params, moment)
        self.params = dict(params)
        self.lib = lib
        n = {k: lib.num(r) * (lib.pi if pw else 1) for k, (r, pw) in exact.items()}
        self.A0 = n["A"] + n["A1"] + n["A2"]
        self.B0 = n["A"] + n["B1"]
        self.C0 = n["A"] + n["A1"] - n["C1"]
        self.H, self.k, self.a, self.mu, self.xs = n["H"], n["k"], n["a"], n["mu"], n["x2_star"]
        self.exact = exact

    # ---- the model's functions (x2 may be an array in the float backend)
    def D(self, x2):
        return self.A0 - self.C0 * self.lib.sin(x2) ** 2

    def f(self, x2):
        return self.law.f(self.a, x2, self.lib)

    def df(self, x2):
        return self.law.df(self.a, x2, self.lib)

    def f1(self, x2):
        return self.k / self.D(x2)

    def f2(self, x2):
        return self.H ** 2 * self.lib.cos(x2) ** 2 / (self.D(x2) * self.B0)

    def f3(self, x2):
        return self.H * self.lib.cos(x2) * self.f(x2) / (self.D(x2) * self.B0)

    def G(self, x2):
        """int_0^x2 cos f / D: the law's closed form, else Gauss-Legendre (float) / mpmath.quad."""
        lib = self.lib
        closed = self.law.G(self.a, self.A0, self.C0, x2, lib)
        if closed is not None:
            return closed
        if lib is NP:
            t, w = _gauss_legendre()
            x = np.asarray(x2, dtype=float)
            y = x[..., None] * t
            return x * np.sum(w * np.cos(y) * self.f(y) / self.D(y), axis=-1)
        if x2 == 0:
            return mpmath.mpf(0)
        return mpmath.quad(lambda s: mpmath.cos(s) * self.f(s) / self.D(s), [0, x2])

    def F(self, x2):
        return self.H / self.B0 * self.G(x2)

    def rhs3(self, x1, x2, x3):
        lib = self.lib
        s2 = lib.sin(2 * x2)
        D = self.D(x2)
        d1 = (self.C0 * s2 * x1 * x3 - self.H * lib.cos(x2) * x3 - self.k * x1 - self.f(x2)) / D
        d3 = (-self.C0 * s2 * x1 * x1 / 2 + self.H * lib.cos(x2) * x1) / self.B0
        return d1, x3, d3

    def V(self, x1, x2, x3, mu=None):
        mu = self.mu if mu is None else mu
        c = self.lib.cos(x2)
        return (mu * self.F(x2) + x3 * self.f3(x2) + (self.f2(x2) + mu * self.f1(x2)) * x3 * x3 / 2
                + mu * self.H / self.B0 * c * x1 * x3 + self.H ** 2 / (2 * self.B0 ** 2) * c * c * x1 * x1)

    def grad_V(self, x1, x2, x3, mu=None):
        """Analytic partial derivatives of V (7) (dF/dx2 = f3)."""
        mu = self.mu if mu is None else mu
        lib = self.lib
        H, B0, C0, A0, k = self.H, self.B0, self.C0, self.A0, self.k
        c, s = lib.cos(x2), lib.sin(x2)
        D = self.D(x2)
        f, fp = self.f(x2), self.df(x2)
        f3 = self.f3(x2)
        df3 = H / B0 * ((-s * f + c * fp) / D + 2 * C0 * s * c * c * f / D ** 2)
        df2 = -2 * H ** 2 * s * c * (A0 - C0) / (B0 * D ** 2)
        df1 = 2 * k * C0 * s * c / D ** 2
        v1 = mu * H / B0 * c * x3 + H ** 2 / B0 ** 2 * c * c * x1
        v2 = (mu * f3 + df3 * x3 + (df2 + mu * df1) * x3 * x3 / 2 - mu * H / B0 * s * x1 * x3
              - H ** 2 / B0 ** 2 * c * s * x1 * x1)
        v3 = f3 + (self.f2(x2) + mu * self.f1(x2)) * x3 + mu * H / B0 * c * x1
        return v1, v2, v3

    def grad_V_dot_f(self, x1, x2, x3, mu=None):
        g = self.grad_V(x1, x2, x3, mu)
        r = self.rhs3(x1, x2, x3)
        return g[0] * r[0] + g[1] * r[1] + g[2] * r[2]

    def psi_true(self, x2, mu=None):
        """((c10, c11, c13), (c20, c21, c23)) of Vdot = -Psi1 x1^2 - Psi2 x3^2 as grad V . f actually is."""
        mu = self.mu if mu is None else mu
        lib = self.lib
        H, B0, C0, A0, k = self.H, self.B0, self.C0, self.A0, self.k
        c, s = lib.cos(x2), lib.sin(x2)
        D = self.D(x2)
        f, fp = self.f(x2), self.df(x2)
        P = A0 - C0 - C0 * c * c
        c10 = H ** 2 * c * c / B0 ** 2 * (k / D - mu) + C0 * H * c * c * s * f / (D * B0 ** 2)
        c11 = mu * H * C0 * s * c * c / B0 ** 2
        c13 = (mu * k * B0 * C0 + (A0 - C0) * H ** 2) * s * c / (D * B0 ** 2)
        c20 = mu * H ** 2 * c * c / (B0 * D) - H * c * fp / (B0 * D) + H * P * s * f / (B0 * D ** 2)
        c21 = mu * H * P * s / (B0 * D)
        c23 = ((A0 - C0) * H ** 2 - mu * k * B0 * C0) * s * c / (B0 * D ** 2)
        return (c10, c11, c13), (c20, c21, c23)

    def psi_printed(self, x2, mu=None):
        """The coefficients as printed in (8): Psi2's x3-term carries sin 2x2 (the rest as derived)."""
        mu = self.mu if mu is None else mu
        (c10, c11, c13), (c20, c21, _) = self.psi_true(x2, mu)
        D = self.D(x2)
        c23 = ((self.A0 - self.C0) * self.H ** 2 - mu * self.k * self.B0 * self.C0) * self.lib.sin(2 * x2) / (
            self.B0 * D ** 2)
        return (c10, c11, c13), (c20, c21, c23)

    def vdot_psi(self, x1, x2, x3, printed: bool = False, mu=None):
        (c10, c11, c13), (c20, c21, c23) = (self.psi_printed if printed else self.psi_true)(x2, mu)
        return -(c10 + c11 * x1 + c13 * x3) * x1 * x1 - (c20 + c21 * x1 + c23 * x3) * x3 * x3

    # ---- the quotients whose maxima are m and M, and the radius ratios of R_sup
    def m_quotient(self, x2):
        """|cos x2 f'(x2)| / (A0 - C0 sin^2 x2): the reading of the misprinted m."""
        return self.lib.fabs(self.lib.cos(x2) * self.df(x2)) / self.D(x2)

    def q(self, x2):
        """f^2 / (2 D G): closed form, or h(x)^2 / (2 D(x) K(x)) with h = f/x and
        K(x) = int_0^1 t cos(xt) h(xt) / D(xt) dt = G(x)/x^2 (no 0/0 at x = 0: q(0) = f'(0))."""
        lib = self.lib
        closed = self.law.q(self.a, self.A0, self.C0, x2, lib)
        if closed is not None:
            return closed
        h = lambda y: self.law.f_over_x(self.a, y, lib)  # noqa: E731
        if lib is NP:
            t, w = _gauss_legendre()
            x = np.asarray(x2, dtype=float)
            y = x[..., None] * t
            K = np.sum(w * t * np.cos(y) * h(y) / self.D(y), axis=-1)
        else:
            K = mpmath.quad(lambda t: t * mpmath.cos(x2 * t) * h(x2 * t) / self.D(x2 * t), [0, 1])
        return h(x2) ** 2 / (2 * self.D(x2) * K)

    def radius_ratios(self, x2, mu=None):
        """(c10 / |(c11, c13)|, c20 / |(c21, c23)|): the largest disc radius on which Psi_i > 0 at x2
        (+inf where the x1, x3 coefficients vanish and ci0 > 0, -inf where ci0 <= 0 there)."""
        (c10, c11, c13), (c20, c21, c23) = self.psi_true(x2, mu)
        return _ratio(c10, self.lib.hypot(c11, c13), self.lib), _ratio(c20, self.lib.hypot(c21, c23), self.lib)

    def S(self, x2, mu=None):
        """f2 + mu (f1 - mu): the x3 curvature of V after x1 is minimised out."""
        mu = self.mu if mu is None else mu
        return self.f2(x2) + mu * (self.f1(x2) - mu)


def _ratio(num, den, lib):
    if lib is NP:
        num, den = np.broadcast_arrays(np.asarray(num, dtype=float), np.asarray(den, dtype=float))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = num / den
        return np.where(den == 0, np.where(num > 0, np.inf, -np.inf), r)
    if den == 0:
        return mpmath.inf if num > 0 else -mpmath.inf
    return num / den


_GL_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _gauss_legendre(n: int = GL_NODES):
    """Nodes and weights of n-point Gauss-Legendre on [0, 1]."""
    if n not in _GL_CACHE:
        t, w = np.polynomial.legendre.leggauss(n)
        _GL_CACHE[n] = ((t + 1) / 2, w / 2)
    return _GL_CACHE[n]


class FloatGimbal(_Model):
    """System (2), V (7), grad V . f and the Psi form in float64, vectorised over numpy arrays.

    Guarantee: none (float64). ``grad_V_dot_f`` is the analytic gradient of (7) dotted with (2);
    ``vdot_psi`` is -Psi1 x1^2 - Psi2 x3^2 from the audited coefficients (``printed=True``: as printed).

    Example:
        >>> g = FloatGimbal(AGAFONOV2013)
        >>> round(g.A0, 12), round(g.B0, 12), round(g.C0, 12)
        (12.7, 4.2, 1.4)
        >>> bool(abs(g.grad_V_dot_f(1e-3, 0.3, 2e-3) - g.vdot_psi(1e-3, 0.3, 2e-3)) < 1e-9 * abs(g.vdot_psi(1e-3, 0.3, 2e-3)))
        True
    """

    def __init__(self, params: dict, moment: dict | None = None):
        super().__init__(params, NP, moment)

    def rhs(self, t, y):
        """solve_ivp right-hand side: y of shape (3,) or (3, n) (also (3n,) for n stacked starts)."""
        y = np.asarray(y, dtype=float)
        if y.ndim == 1 and y.size > 3:
            Y = y.reshape(-1, 3)
            out = np.empty_like(Y)
            x1, x2, x3 = Y[:, 0], Y[:, 1], Y[:, 2]
            s, c = np.sin(x2), np.cos(x2)
            cs2x1 = self.C0 * 2 * s * c * x1
            Hcx1 = self.H * c
            out[:, 0] = (cs2x1 * x3 - Hcx1 * x3 - self.k * x1 - self.f(x2)) / (self.A0 - self.C0 * s * s)
            out[:, 1] = x3
            out[:, 2] = (-0.5 * cs2x1 * x1 + Hcx1 * x1) / self.B0
            return out.ravel()
        d = self.rhs3(y[0], y[1], y[2])
        return np.stack([np.asarray(v, dtype=float) for v in d])

    def rhs_scalar(self, t, y):
        """Fast right-hand side for one start (math module scalars)."""
        x1, x2, x3 = y
        s, c = math.sin(x2), math.cos(x2)
        s2 = 2 * s * c
        D = self.A0 - self.C0 * s * s
        f = self.law.f(self.a, x2, MATH)
        return [(self.C0 * s2 * x1 * x3 - self.H * c * x3 - self.k * x1 - f) / D, x3,
                (-0.5 * self.C0 * s2 * x1 * x1 + self.H * c * x1) / self.B0]

    def psi_true(self, x2, mu=None):
        return super().psi_true(x2, mu)

    def psi_printed(self, x2, mu=None):
        return super().psi_printed(x2, mu)

    def vdot_psi(self, x1, x2, x3, printed: bool = False, mu=None):
        return super().vdot_psi(x1, x2, x3, printed, mu)

    def in_region(self, x1, x2, x3, R):
        return (np.abs(x2) <= self.xs) & (np.asarray(x1) ** 2 + np.asarray(x3) ** 2 < R * R)

    def in_box(self, x1, x2, x3, R):
        return (np.abs(x2) <= self.xs) & (np.abs(x1) <= R) & (np.abs(x3) <= R)


class MpGimbal(_Model):
    """The same model in mpmath scalars at the caller's ``mpmath.mp.dps`` (no guarantee)."""

    def __init__(self, params: dict, moment: dict | None = None):
        super().__init__(params, MP, moment)


# ------------------------------------------------------------------------------------ 1-D searches

def _golden(fn, lo, hi, lib, tol, maximise=False):
    """Golden-section search for a local minimum (maximum) of fn on [lo, hi]; returns (x, fn(x))."""
    sgn = -1 if maximise else 1
    g = lambda x: sgn * fn(x)  # noqa: E731
    invphi = (lib.sqrt(5 * lib.one_like(0)) - 1) / 2 if lib is MP else (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    c, d = b - invphi * (b - a), a + invphi * (b - a)
    fc, fd = g(c), g(d)
    for _ in range(400):
        if abs(b - a) <= tol:
            break
        if fc < fd:
            b, d, fd = d, c, fc
            c = b - invphi * (b - a)
            fc = g(c)
        else:
            a, c, fc = c, d, fd
            d = a + invphi * (b - a)
            fd = g(d)
    best = min(((fc, c), (fd, d), (g(a), a), (g(b), b)), key=lambda p: p[0])
    return best[1], sgn * best[0]


def _x_tol(lib, scale):
    if lib is MP:
        return mpmath.mpf(10) ** (-(mpmath.mp.dps // 2 + 4)) * max(1, abs(scale))
    return 1e-9 * max(1.0, abs(float(scale)))


def _extremum(fl, fp, lo_f, hi_f, lo_p, hi_p, lib, maximise: bool, n: int = X2_GRID):
    """Global max/min of a function of x2 on [lo, hi]: float grid ``fl`` (vectorised) to locate it, the
    precise backend ``fp`` at both ends and, if the grid optimum is interior, golden-section refinement
    around it. Returns (value, argument)."""
    grid = np.linspace(lo_f, hi_f, n)
    with np.errstate(all="ignore"):
        vals = np.asarray(fl(grid), dtype=float)
    vals = np.where(np.isnan(vals), -np.inf if maximise else np.inf, vals)
    i = int(np.argmax(vals) if maximise else np.argmin(vals))
    cands = [(fp(lo_p), lo_p), (fp(hi_p), hi_p)]
    if 0 < i < n - 1:
        a = lib.num(Fraction(grid[i - 1])) if lib is MP else grid[i - 1]
        b = lib.num(Fraction(grid[i + 1])) if lib is MP else grid[i + 1]
        x, v = _golden(fp, a, b, lib, _x_tol(lib, hi_p), maximise)
        cands.append((v, x))
    return (max if maximise else min)(cands, key=lambda p: p[0])


def _domain(g: _Model):
    """The x2 range that suffices: [0, x2*] for an odd law (everything is even or symmetric), else [-x2*, x2*]."""
    return (0 * g.xs, g.xs) if g.law.odd else (-g.xs, g.xs)


# ------------------------------------------------------------------------------------ constants

def _constants(params: dict, lib, R=None, with_best_mu: bool = True) -> dict:
    g = _Model(params, lib)
    fg = FloatGimbal(params) if lib is MP else g
    lo, hi = _domain(g)
    lof, hif = float(lo), float(hi)
    out = {"A0": g.A0, "B0": g.B0, "C0": g.C0}
    m, x_m = _extremum(fg.m_quotient, g.m_quotient, lof, hif, lo, hi, lib, True)
    M, x_M = _extremum(fg.q, g.q, lof, hif, lo, hi, lib, True)
    cs2 = lib.cos(g.xs) ** 2
    A0m = g.A0 * m / cs2
    p = M if M > A0m else A0m
    out.update(m=m, M=M, A0_m_over_cos2=A0m, p=p, k_min=p * g.A0 / g.H, mu_min=p / g.H, mu_max=g.k / g.A0,
               argmax_m=x_m, argmax_M=x_M, q_at_0=g.q(0 * g.xs))
    out.update(_r12(g, m))
    out["R_sup"], out["R_sup_argmin"] = _r_sup(g, fg, g.mu)
    R_used = out["R"] if R is None else (lib.num(Fraction(R)) if isinstance(R, str) else R)
    out["R_used"] = R_used
    out.update(_c_star(g, fg, R_used))
    if with_best_mu:
        out.update(_best_mu(g, fg, out["mu_min"], out["mu_max"]))
    return out


def _r12(g: _Model, m) -> dict:
    """R1 (13) = sqrt(D1/D2), R2 (14) = sqrt(E1/E2) exactly as printed, and the signed radii of the
    chains (12), (13) they come from (negative: the chain's constant term is negative, no disc)."""
    lib = g.lib
    A0, B0, C0, H, k, mu = g.A0, g.B0, g.C0, g.H, g.k, g.mu
    s, cs = lib.sin(g.xs), lib.cos(g.xs)
    Ds = A0 - C0 * s * s
    D1 = 108 * A0 * (A0 - C0) * H ** 4 * cs ** 4 * (k / A0 - mu) ** 2
    D2 = 16 * mu ** 2 * A0 * (A0 - C0) * H ** 2 * C0 ** 2 + 27 * (mu * k * B0 * C0 + (A0 - C0) * H ** 2) ** 2
    P = A0 - C0 - C0 * cs ** 2
    E1 = 4 * H ** 2 * (mu * H * cs ** 2 - m * A0) ** 2 * Ds ** 4
    E2 = A0 ** 2 * (4 * mu ** 2 * H ** 2 * P ** 2 * Ds ** 2 * s ** 2 + (mu * k * B0 * C0 - (A0 - C0) * H ** 2) ** 2)
    R1, R2 = lib.sqrt(D1 / D2), lib.sqrt(E1 / E2)
    sign1 = 1 if k / A0 - mu > 0 else -1
    sign2 = 1 if mu * H * cs ** 2 - m * A0 > 0 else -1
    return {"R1": R1, "R2": R2, "R": R1 if R1 < R2 else R2, "R1_signed": sign1 * R1, "R2_signed": sign2 * R2}


def _r_sup_parts(g: _Model, fg: FloatGimbal, mu):
    """(min over x2 of c10/|(c11,c13)|, argmin), the same for Psi2: each Psi_i > 0 on the disc of radius
    R for all |x2| <= x2* iff R < its minimum."""
    lo, hi = _domain(g)
    muf = float(mu)
    out = []
    for i in (0, 1):
        fl = lambda x, i=i: fg.radius_ratios(x, muf)[i]  # noqa: E731
        fp = lambda x, i=i: g.radius_ratios(x, mu)[i]    # noqa: E731
        v, x = _extremum(fl, fp, float(lo), float(hi), lo, hi, g.lib, False)
        out.append((v, x))
    return out


def _r_sup(g: _Model, fg: FloatGimbal, mu):
    """R_sup(mu) = max(0, min over x2, i of ci0/|(ci1, ci3)|) and the x2 where it is attained."""
    (r1, x1), (r2, x2) = _r_sup_parts(g, fg, mu)
    v, x = (r1, x1) if r1 < r2 else (r2, x2)
    return (v if v > 0 else g.lib.num(Fraction(0))), x


def _best_mu(g: _Model, fg: FloatGimbal, mu_lo, mu_hi) -> dict:
    """mu in (mu_lo, mu_hi) maximising R_sup(mu): float scan, then the crossing R1sup = R2sup by a
    bracketing secant (Illinois) or golden section on a smooth interior maximum."""
    lib = g.lib
    if not mu_lo < mu_hi:
        return {"mu_best": None, "R_max": None, "mu_best_kind": "empty mu interval"}
    lo_f, hi_f = float(mu_lo), float(mu_hi)
    mus = np.linspace(lo_f, hi_f, MU_GRID)[1:-1]
    lo, hi = _domain(g)
    grid = np.linspace(float(lo), float(hi), X2_GRID)
    parts = []
    for mu in mus:
        r1, r2 = fg.radius_ratios(grid, mu)
        parts.append((np.min(r1), np.min(r2)))
    parts = np.array(parts)
    rs = np.maximum(np.min(parts, axis=1), 0)
    i = int(np.argmax(rs))
    diff = parts[:, 0] - parts[:, 1]

    def rsup(mu):
        return _r_sup(g, fg, mu)[0]
    to_p = (lambda x: lib.num(Fraction(x))) if lib is MP else float
    j = None
    for cand in (i - 1, i):
        if 0 <= cand < len(mus) - 1 and np.sign(diff[cand]) != np.sign(diff[cand + 1]):
            j = cand
    if rs[i] <= 0:
        return {"mu_best": None, "R_max": 0 * g.mu, "mu_best_kind": "R_sup = 0 on the whole mu interval"}
    if j is not None:
        a, b = to_p(mus[j]), to_p(mus[j + 1])

        def h(mu):
            (r1, _), (r2, _) = _r_sup_parts(g, fg, mu)
            return r1 - r2
        if lib is MP:
            mu_b = mpmath.findroot(h, (a, b), solver="illinois", tol=mpmath.mpf(10) ** (-2 * mpmath.mp.dps + 10),
                                   verify=False)
        else:
            from scipy.optimize import brentq
            mu_b = brentq(h, a, b, xtol=1e-300, rtol=4 * np.finfo(float).eps)
        return {"mu_best": mu_b, "R_max": rsup(mu_b), "mu_best_kind": "crossing R1sup = R2sup"}
    if 0 < i < len(mus) - 1:
        mu_b, R = _golden(rsup, to_p(mus[i - 1]), to_p(mus[i + 1]), lib, _x_tol(lib, mu_hi), True)
        return {"mu_best": mu_b, "R_max": R, "mu_best_kind": "smooth interior maximum"}
    end = mu_lo if i == 0 else mu_hi
    return {"mu_best": end, "R_max": rsup(end), "mu_best_kind": "supremum at an end of the open interval"}


def _theta_refine(W1, W2, th, lib):
    """Newton on W'(theta) = 0 from a grid start (falls back to the start when it does not converge)."""
    tol = mpmath.mpf(10) ** (-mpmath.mp.dps + 3) if lib is MP else 1e-15
    t = th
    for _ in range(80):
        d2 = W2(t)
        if not d2 > 0:
            return th
        step = W1(t) / d2
        t = t - step
        if abs(step) < tol:
            return t
    return t


def _c_star(g: _Model, fg: FloatGimbal, R) -> dict:
    """min of V over the boundary of {|x2| <= x2*, x1^2 + x3^2 < R^2}: the faces |x2| = x2* in closed form
    when the face minimiser lies inside the disc, the cylinder by a grid search in (x2, theta) refined by
    Newton in theta and a root of the envelope derivative in x2. Returns c_star and its parts."""
    lib = g.lib
    out = {}
    if not R > 0:
        return {"c_star": None, "c_star_face": None, "c_star_cylinder": None, "c_star_where": "R <= 0"}
    mu, H, B0 = g.mu, g.H, g.B0
    faces = []
    for xe in ((g.xs,) if g.law.odd else (g.xs, -g.xs)):
        Sm = g.S(xe)
        if Sm > 0:
            x3m = -g.f3(xe) / Sm
            x1m = -mu * B0 * x3m / (H * lib.cos(xe))
            val = mu * g.F(xe) - g.f3(xe) ** 2 / (2 * Sm)
            out.setdefault("face_minimiser", (x1m, xe, x3m))
            if x1m ** 2 + x3m ** 2 < R * R:
                faces.append(val)
            out.setdefault("c_star_face_unconstrained", val)
    face = min(faces) if faces else None
    # cylinder: V(R cos th, x2, R sin th) = c0 + f3 R sin + R^2/2 (a cos^2 + 2 b cos sin + c sin^2)
    lo, hi = _domain(g)
    Rf = float(R)

    def coeffs(m: _Model, x2):
        c = m.lib.cos(x2)
        return (m.mu * m.F(x2), m.f3(x2), m.H ** 2 * c * c / m.B0 ** 2, m.mu * m.H * c / m.B0,
                m.f2(x2) + m.mu * m.f1(x2))
    x2g = np.linspace(float(lo), float(hi), 801)
    thg = np.linspace(0, 2 * np.pi, THETA_GRID, endpoint=False)
    c0, f3, qa, qb, qc = (np.asarray(v, dtype=float)[:, None] for v in coeffs(fg, x2g))
    C, S = np.cos(thg)[None, :], np.sin(thg)[None, :]
    W = c0 + f3 * Rf * S + Rf * Rf / 2 * (qa * C * C + 2 * qb * C * S + qc * S * S)
    i, j = np.unravel_index(int(np.argmin(W)), W.shape)
    row_argmin = np.argmin(W, axis=1)

    def inner(x2, th0):
        """(min over theta near th0 of V on the circle at x2, theta*)."""
        k0, k3, qa_, qb_, qc_ = coeffs(g, x2)
        W0 = lambda t: k0 + k3 * R * lib.sin(t) + R * R / 2 * (qa_ * lib.cos(t) ** 2 + 2 * qb_ * lib.cos(t) * lib.sin(t)  # noqa: E731
                                                              + qc_ * lib.sin(t) ** 2)
        W1 = lambda t: k3 * R * lib.cos(t) + R * R * ((qc_ - qa_) * lib.cos(t) * lib.sin(t) + qb_ * lib.cos(2 * t))  # noqa: E731
        W2 = lambda t: -k3 * R * lib.sin(t) + R * R * ((qc_ - qa_) * lib.cos(2 * t) - 2 * qb_ * lib.sin(2 * t))  # noqa: E731
        t = _theta_refine(W1, W2, th0, lib)
        return W0(t), t
    to_p = (lambda x: lib.num(Fraction(x))) if lib is MP else float

    def phi(x2, th0):
        return inner(x2, th0)[0]

    if i == 0 or i == len(x2g) - 1:
        x2b = lo if i == 0 else hi
        cyl, th = inner(x2b, to_p(thg[j]))
    else:
        th_start = {k: to_p(thg[row_argmin[k]]) for k in (i - 1, i, i + 1)}

        def dphi(x2):     # envelope theorem: d/dx2 min_theta V = dV/dx2 at theta*
            _, t = inner(x2, th_start[i])
            return g.grad_V(R * lib.cos(t), x2, R * lib.sin(t))[1]
        a, b = to_p(x2g[i - 1]), to_p(x2g[i + 1])
        try:
            if lib is MP:
                x2b = mpmath.findroot(dphi, (a, b), solver="illinois", verify=False)
                if not a <= x2b <= b:
                    raise ValueError("envelope root left its bracket")
            else:
                from scipy.optimize import brentq
                x2b = brentq(dphi, a, b, xtol=1e-15)
            cyl, th = inner(x2b, th_start[i])
        except (ValueError, ZeroDivisionError):
            x2b, cyl = _golden(lambda x: phi(x, th_start[i]), a, b, lib, _x_tol(lib, hi))
            th = inner(x2b, th_start[i])[1]
    out["c_star_cylinder"] = cyl
    out["cylinder_argmin"] = (R * lib.cos(th), x2b, R * lib.sin(th))
    out["c_star_face"] = face
    if face is not None and face < cyl:
        out["c_star"], out["c_star_where"] = face, "face |x2| = x2* (minimiser inside the disc)"
    else:
        out["c_star"], out["c_star_where"] = cyl, "cylinder x1^2 + x3^2 = R^2"
    return out


def _extents(g: _Model, cstar, R) -> dict:
    """Where {V = c*} crosses the three axes (clipped to the region)."""
    lib = g.lib
    x1 = g.B0 * lib.sqrt(2 * cstar) / g.H
    x3 = lib.sqrt(2 * cstar / (g.f2(0 * g.xs) + g.mu * g.f1(0 * g.xs)))
    if g.mu * g.F(g.xs) <= cstar:
        x2 = g.xs
    elif lib is MP:
        x2 = mpmath.findroot(lambda x: g.mu * g.F(x) / cstar - 1, (0 * g.xs, g.xs), solver="anderson", verify=False)
    else:
        from scipy.optimize import brentq
        x2 = brentq(lambda x: g.mu * float(g.F(x)) - cstar, 0.0, g.xs, xtol=1e-15)
    return {"extent_x1_axis": min(x1, R), "extent_x2_axis": x2, "extent_x3_axis": min(x3, R)}


def mp_constants(params: dict, dps: int = 50, R: str | None = None, with_best_mu: bool = True) -> dict:
    """mpmath values of every quantity of the scene at ``dps`` digits (no guarantee).

    Keys: A0, B0, C0, m, M, A0_m_over_cos2, p, k_min, mu_min, mu_max, R1, R2, R (printed (13), (14);
    R1_signed/R2_signed are negative when the chain's constant term is, i.e. the formula's square hides a
    vacuous bound), R_sup (largest disc radius with Psi1, Psi2 > 0 at the scene's mu; 0 if none),
    c_star (min of V over the boundary of (17) with R = ``R`` or min(R1, R2)) with c_star_face,
    c_star_cylinder, c_star_where, the axis extents of {V < c*}, and mu_best, R_max (maximiser of R_sup
    over (mu_min, mu_max); None if the interval is empty), mu_best_kind.

    Requires: a valid parameter dict (see the module docstring). M by the law's closed form (sine) or
    by mpmath.quad of G(x)/x^2 = int_0^1 t cos(xt) (f/x)(xt) / D(xt) dt (the 0/0 at x2 = 0 removed
    exactly, q(0) = f'(0)); extrema over x2 by a 2001-point float grid plus mpmath golden-section
    refinement (interior optima) and the exact end points.

    Fails when: an extremum is narrower than the grid (missed silently).

    Example:
        >>> c = mp_constants(AGAFONOV2013, dps=30, with_best_mu=False)
        >>> print(mpmath.nstr(c["c_star"], 15), c["c_star_where"])
        23.4283841958463 face |x2| = x2* (minimiser inside the disc)
    """
    with mpmath.workdps(dps + 10):
        out = _constants(params, MP, R=R, with_best_mu=with_best_mu)
        if out.get("c_star") is not None and out["c_star"] > 0:
            out.update(_extents(MpGimbal(params), out["c_star"], out["R_used"]))
        return {k: (+v if isinstance(v, mpmath.mpf) else v) for k, v in out.items()}


def float_constants(params: dict, R: float | None = None, with_best_mu: bool = True) -> dict:
    """The same quantities as :func:`mp_constants` in float64 (grid + float refinement; no guarantee)."""
    out = _constants(params, NP, R=R, with_best_mu=with_best_mu)
    if out.get("c_star") is not None and out["c_star"] > 0:
        out.update(_extents(FloatGimbal(params), float(out["c_star"]), float(out["R_used"])))
    return {k: (float(v) if isinstance(v, (np.floating, float, np.ndarray)) and np.size(v) == 1 else v)
            for k, v in out.items()}


# ------------------------------------------------------------------------------------ time scales

def time_scales(params: dict, dps: int = 30) -> dict:
    """Time scales of the linearisation at the equilibrium (no guarantee).

    The characteristic polynomial of (2) linearised at 0 is
    lambda^3 + (k/A0) lambda^2 + H^2/(A0 B0) lambda + f'(0) H/(A0 B0)  (f'(0) = a for both laws).
    Returns the roots (mpmath at ``dps`` digits), the nutation frequency omega_n = max |Im lambda| (rad/s,
    and Hz; None if all roots are real), the decay rates -Re lambda, the slowest one (the time constant
    1/rate), and the number of nutation periods per slowest time constant (how many oscillations a
    trajectory needs to decay by 1/e: the cost driver of :func:`trajectories`).

    Example:
        >>> ts = time_scales(AGAFONOV2013)
        >>> round(float(ts["nutation_hz"]), 1), round(float(ts["slowest_rate"]), 6)
        (217.9, 0.01)
    """
    with mpmath.workdps(dps + 10):
        g = MpGimbal(params)
        fp0 = g.df(mpmath.mpf(0))
        coeffs = [1, g.k / g.A0, g.H ** 2 / (g.A0 * g.B0), fp0 * g.H / (g.A0 * g.B0)]
        roots = mpmath.polyroots(coeffs, maxsteps=400, extraprec=4 * dps + 100)
        rates = [-mpmath.re(r) for r in roots]
        nut = max(abs(mpmath.im(r)) for r in roots)
        slow = min(rates)
        out = {"eigenvalues": [mpmath.mpc(r) for r in roots], "characteristic_coefficients": coeffs,
               "decay_rates": rates, "slowest_rate": slow, "time_constant": 1 / slow if slow > 0 else mpmath.inf,
               "nutation_rad_s": nut if nut > 0 else None,
               "nutation_hz": nut / (2 * mpmath.pi) if nut > 0 else None,
               "nutation_period": 2 * mpmath.pi / nut if nut > 0 else None,
               "gyro_frequency_estimate": g.H / mpmath.sqrt(g.A0 * g.B0),
               "precession_rate_estimate": fp0 / g.H}
        out["periods_per_time_constant"] = (out["nutation_hz"] * out["time_constant"]
                                            if nut > 0 and slow > 0 else None)
        return out


# ------------------------------------------------------------------------------------ trajectories

@dataclass
class TrajectoryOutcome:
    """One solve_ivp run. Maxima are over the solver's accepted steps (it takes ~60 per nutation period
    with LSODA at rtol 1e-9: between steps r^2 is within ~1e-3 relative of its sampled maximum)."""
    start: tuple
    t_end: float
    method: str
    rtol: float
    success: bool
    message: str
    seconds: float
    nfev: int
    n_steps: int
    in_region_at_start: bool
    in_box_at_start: bool
    V0: float
    max_r2: float                 # max over time of x1^2 + x3^2
    max_abs_x2: float
    left_region: bool             # some sample outside (17) (|x2| > x2* or x1^2 + x3^2 >= R^2)
    left_box: bool
    V_nonincreasing: bool         # no step-to-step increase above V_MONOTONE_REL_TOL * max |V|
    max_V_increase: float
    V_final: float
    final_norm: float             # max-norm of the final state
    in_set_at_start: bool | None = None     # V0 < c* and in region (if c* given)
    stayed_in_set: bool | None = None       # max V <= c* (1 + tol) and never left the region
    extra: dict = field(default_factory=dict)


def trajectories(params: dict, starts, t_end: float, rtol: float = DEFAULT_RTOL, atol: float | None = None,
                 method: str = DEFAULT_METHOD, R: float | None = None, c_star: float | None = None,
                 joint: bool = False, max_step: float = np.inf) -> list[TrajectoryOutcome]:
    """scipy ``solve_ivp`` runs of system (2) from ``starts`` (rows (x1, x2, x3)) over [0, t_end] (no guarantee).

    For each start: whether it starts in region (17) / the box (|x2| <= x2*, |x1|, |x3| <= R; R defaults
    to min(R1, R2) in float), the max over time of x1^2 + x3^2 and |x2|, whether it ever left them,
    whether V (7) is non-increasing along the steps (to ``V_MONOTONE_REL_TOL``), the final state, the
    run time and the number of rhs evaluations.

    Method: the linearisation (:func:`time_scales`) has a fast, lightly damped nutation pair (1369 rad/s =
    217.9 Hz at the example, decay 0.0107/s) and a slow real mode (decay ~a/H = 0.01/s): ~2.2e4 nutation
    periods per slowest time constant. The problem is *not* stiff in the implicit-method sense: the fast
    mode is an oscillation, not a fast decay, so every method, implicit or not, must resolve it to follow
    V, and Radau/BDF pay a Newton solve per step for nothing while damping the oscillation numerically
    (which would fake a decrease of V). Measured at the example (benchmarks/lyapunov_crosscheck.py, one
    start from the edge of {V < c*}, 0.5 s = 109 periods; run time per simulated second):
    LSODA rtol 1e-9 0.29-0.36 s (~70 steps/period, ~2 rhs calls/step, Adams in a Fortran core; largest
    step-to-step V increase -1.3e-9 V0, i.e. V strictly decreasing); DOP853 rtol 1e-8 0.39-0.45 s
    (10 steps/period, 12 calls/step; -2.8e-7 V0); DOP853 rtol 1e-10 0.54-0.61 s; RK45 rtol 1e-8 1.16 s;
    Radau rtol 1e-8 18 s (164 steps/period). LSODA (it stays in its non-stiff Adams mode here) is the
    default for one start. ``joint=True`` integrates all starts as one stacked system (one step sequence
    for all: 10 starts over 100 s = 21792 periods took 121 s with DOP853 rtol 1e-8; LSODA is slower
    there); the per-start seconds are then the shared total. The horizon that shows convergence is
    several slowest time constants (100 s: V drops to ~e^-2 of V0); a few seconds (hundreds of periods)
    already shows whether a start leaves the box and whether V is monotone.

    Example:
        >>> out = trajectories(AGAFONOV2013, [(0.0, 0.1, 0.0)], t_end=0.2)
        >>> out[0].success, out[0].V_nonincreasing, out[0].left_box
        (True, True, False)
    """
    from scipy.integrate import solve_ivp
    g = FloatGimbal(params)
    if R is None:
        with mpmath.workdps(20):
            R = float(_r12(_Model(params, NP), _float_m(g))["R"])
    starts = np.atleast_2d(np.asarray(starts, dtype=float))
    atol = rtol * 1e-4 if atol is None else atol
    runs = []
    if joint:
        t0 = time.perf_counter()
        sol = solve_ivp(g.rhs, (0.0, t_end), starts.ravel(), method=method, rtol=rtol, atol=atol, max_step=max_step)
        dt = time.perf_counter() - t0
        Y = sol.y.reshape(len(starts), 3, sol.y.shape[1])     # rows were stacked start by start
        for n, y0 in enumerate(starts):
            runs.append((y0, sol, Y[n], dt))
    else:
        for y0 in starts:
            fun = g.rhs_scalar
            t0 = time.perf_counter()
            sol = solve_ivp(fun, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, max_step=max_step)
            runs.append((y0, sol, sol.y, time.perf_counter() - t0))
    out = []
    for y0, sol, y, dt in runs:
        x1, x2, x3 = y
        Vt = np.asarray(g.V(x1, x2, x3), dtype=float)
        scale = float(np.max(np.abs(Vt))) or 1.0
        inc = float(np.max(np.diff(Vt))) if Vt.size > 1 else 0.0
        r2 = x1 ** 2 + x3 ** 2
        inreg = g.in_region(x1, x2, x3, R)
        inbox = g.in_box(x1, x2, x3, R)
        o = TrajectoryOutcome(
            start=tuple(float(v) for v in y0), t_end=float(t_end), method=method, rtol=rtol,
            success=bool(sol.success), message=str(sol.message), seconds=dt, nfev=int(sol.nfev),
            n_steps=int(sol.t.size), in_region_at_start=bool(inreg[0]), in_box_at_start=bool(inbox[0]),
            V0=float(Vt[0]), max_r2=float(np.max(r2)), max_abs_x2=float(np.max(np.abs(x2))),
            left_region=bool(not np.all(inreg)), left_box=bool(not np.all(inbox)),
            V_nonincreasing=bool(inc <= V_MONOTONE_REL_TOL * scale), max_V_increase=inc,
            V_final=float(Vt[-1]), final_norm=float(np.max(np.abs(y[:, -1]))),
            extra={"R": R, "t_final": float(sol.t[-1])})
        if c_star is not None:
            o.in_set_at_start = bool(inreg[0] and Vt[0] < c_star)
            o.stayed_in_set = bool(np.all(inreg) and np.max(Vt) <= c_star * (1 + V_MONOTONE_REL_TOL))
        out.append(o)
    return out


def _float_m(g: FloatGimbal) -> float:
    lo, hi = _domain(g)
    return float(_extremum(g.m_quotient, g.m_quotient, float(lo), float(hi), float(lo), float(hi), NP, True)[0])


@dataclass
class EdgePoints:
    """Start points for :func:`trajectories`: ``edge`` just inside {V < c*} within region (17);
    ``outside`` outside the box (or the region), with a label each."""
    edge: np.ndarray
    outside: np.ndarray
    outside_labels: list[str]
    R: float
    c_star: float


def edge_points(params: dict, c_star: float, n: int = 8, R: float | None = None) -> EdgePoints:
    """Points on the edge of {V < c*} within region (17), found along rays from the origin (no guarantee).

    The rays are n directions u (a Fibonacci lattice on the unit sphere, deterministic) in the scaled
    coordinates (x1/R, x2/x2*, x3/R); along each, V(t d) - c* is sampled on (0, t_b] (t_b puts the point
    on the boundary of (17), where V >= c* by definition of c*), the first sign change is bisected
    (brentq) and the point is returned a relative ``EDGE_INSET`` inside (V < c* there, in float).
    ``outside`` holds points beyond |x2| = x2*, beyond |x1| = R, beyond |x3| = R, and a box corner that is
    in the box but outside the disc.

    Example:
        >>> pts = edge_points(AGAFONOV2013, 23.4283841958462670, n=4)
        >>> pts.edge.shape, len(pts.outside_labels)
        ((4, 3), 4)
    """
    from scipy.optimize import brentq
    g = FloatGimbal(params)
    if R is None:
        R = float(_r12(g, _float_m(g))["R"])
    xs = float(g.xs)
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    rho = np.sqrt(1 - z * z)
    phi = np.pi * (1 + 5 ** 0.5) * k
    U = np.stack([rho * np.cos(phi), z, rho * np.sin(phi)], axis=1)   # (u1, u2, u3), u2 along x2
    edge = []
    for u in U:
        d = np.array([R * u[0], xs * u[1], R * u[2]])
        tb = 1.0 / max(abs(u[1]), math.hypot(u[0], u[2]))
        h = lambda t: float(g.V(*(t * d))) - c_star  # noqa: E731
        ts = np.linspace(0, tb, 401)[1:]
        vals = np.array([h(t) for t in ts])
        hit = np.nonzero(vals >= 0)[0]
        if hit.size == 0:
            continue
        jj = hit[0]
        a = ts[jj - 1] if jj > 0 else 0.0
        t = brentq(h, a, ts[jj], xtol=1e-15) if jj > 0 or h(0.0) < 0 else ts[jj]
        edge.append(t * (1 - EDGE_INSET) * d)
    x2_out = min(1.2 * xs, (xs + math.pi / 2) / 2)
    outside = np.array([[0.0, x2_out, 0.0], [1.5 * R, 0.0, 0.0], [0.0, 0.0, 1.5 * R],
                        [0.95 * R, 0.5 * xs, -0.95 * R]])
    labels = ["|x2| > x2*", "|x1| > R", "|x3| > R", "in the box, outside the disc"]
    return EdgePoints(np.array(edge).reshape(-1, 3), outside, labels, R, float(c_star))


#: the quantities the bench compares (certificate names)
BENCH_NAMES = ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R", "c_star",
               "extent_x1_axis", "extent_x2_axis", "extent_x3_axis")


def bench_float(params: dict, hint=None) -> dict:
    """What an uncertified float script computes (:func:`float_constants`, without the mu search), by
    certificate name. No guarantee."""
    fl = float_constants(params, with_best_mu=False)
    return {k: float(fl[k]) for k in BENCH_NAMES if fl.get(k) is not None}


def bench_mpmath(params: dict, dps: int = 30, hint=None) -> dict:
    """The same by :func:`mp_constants` at ``dps`` digits (non-rigorous)."""
    mp = mp_constants(params, dps=dps, with_best_mu=False)
    return {k: mp[k] for k in BENCH_NAMES if mp.get(k) is not None}


def mp_polar_estimates(params: dict, dps: int = 30, mu_interval: tuple | None = None) -> dict:
    """mpmath estimates (no guarantee) of the quantities of the polar form that the claims
    ``vdot_direct``, ``largest_sublevel`` and ``best_mu_direct`` certify: R_direct ~ inf over (x2, t) of
    A / |B| where Vdot(r cos t, x2, r sin t) = -r^2 (A + r B), and c_max ~ the smallest V where Vdot
    turns >= 0 along a ray (at the threshold r = -A/B and at V's minimum beyond it) or on the faces
    |x2| = x2*; with ``mu_interval`` = (mu_min, mu_max), also mu_direct and R_direct_max, the maximiser
    and maximum of R_direct(mu) (a golden-section search, each R_direct by a compass search warm-started
    from the best point). Both by the prover's own search pattern (:func:`~.search.grid_then_compass` on
    a 17 x 33 grid, then 90 compass rounds) on mpmath values of the analytic grad V . f and V: the
    non-rigorous equivalent of those claims (for the speed benchmark: the same work, without enclosures)."""
    with mpmath.workdps(dps):
        return _polar_estimates(MpGimbal(params), mpmath.pi, mpmath.cos, mpmath.sin, mu_interval)


def float_polar_estimates(params: dict, mu_interval: tuple | None = None) -> dict:
    """The same as :func:`mp_polar_estimates` in float64 (no guarantee)."""
    return _polar_estimates(FloatGimbal(params), math.pi, math.cos, math.sin, mu_interval)


def _polar_estimates(g, pi, cos, sin, mu_interval) -> dict:
    xs = g.xs

    def ray(u: float, s: float, mu=None):
        x2, t = xs * u, pi * s
        c, sn = cos(t), sin(t)
        v1 = g.grad_V_dot_f(c, x2, sn, mu)
        v2 = g.grad_V_dot_f(2 * c, x2, 2 * sn, mu)
        B = -v2 / 4 + v1
        return x2, c, sn, -v1 - B, B

    def ratio(u: float, s: float, mu=None):
        _, _, _, A, B = ray(u, s, mu)
        return (float(A / abs(B)) if B != 0 and A > 0 else math.inf), None

    def level(u: float, s: float):
        x2, c, sn, A, B = ray(u, s)
        if B == 0:
            return math.inf, None
        r0 = -A / B
        v0 = g.V(0, x2, 0)
        vp, vm = g.V(c, x2, sn), g.V(-c, x2, -sn)
        beta, gamma = (vp - vm) / 2, (vp + vm) / 2 - v0
        best = g.V(r0 * c, x2, r0 * sn)
        if gamma > 0:
            rv = -beta / (2 * gamma)
            if A + rv * B <= 0:
                best = min(best, v0 + beta * rv + gamma * rv * rv)
        return float(best), None
    r_direct, u0, s0, _ = grid_then_compass(ratio, (17, 33), 90)
    c_rays = grid_then_compass(level, (17, 33), 90)[0]
    f3, S = g.f3(xs), g.S(xs)
    face = float(g.mu * g.F(xs) - f3 * f3 / (2 * S))
    out = {"R_direct": r_direct, "c_max": min(c_rays, face), "c_max_rays": c_rays, "c_max_face": face}
    if mu_interval is not None and mu_interval[0] < mu_interval[1]:
        start = [u0, s0]

        def R_of(mu: float) -> float:
            v0, _ = ratio(*start, mu)
            v, u, s, _ = compass(lambda a, b: ratio(a, b, mu), (v0, start[0], start[1], None), (1 / 64, 1 / 128), 40)
            start[:] = [u, s]
            return v
        lo, hi = float(mu_interval[0]), float(mu_interval[1])
        out["mu_direct"], out["R_direct_max"] = _golden(R_of, lo, hi, NP, (hi - lo) * 1e-9, maximise=True)
    return out
