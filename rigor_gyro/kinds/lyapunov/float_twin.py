"""Float twins of the polar forms, for the point searches' grids only: they *propose*, nothing else.

The searches of :mod:`.search` (the direct test's inf A/|B|, the largest sublevel's minimum of V over
{Vdot >= 0}, the Psi test's max rho over x2) first scan a grid of point values and keep the best grid point.
Scanning that grid in Arb balls costs a few tens of microseconds a point; in plain Python floats (``math``)
about a tenth of it. The twins here give the same quantities as the ball midpoints would, to about 1e-15
relative, so they pick the same grid point; the chosen point is then evaluated again in balls by the caller,
and everything after it (the compass or golden-section refinement, every certification) is unchanged.

Guarantee: none, by design. A twin's value is a heuristic number: a wrong or missing twin can only make a
search start elsewhere (every claim still certifies its result in balls, or stays undecided). A twin exists
only for the built-in laws whose f, f' (and G) have a plain float formula (:class:`.moments.SineMoment`,
:class:`.moments.LinearMoment`; G only for the sine law); for any other law :func:`float_twin` returns None
and the searches scan their grids in balls as before. Values outside the doubles' safe range (overflow,
underflow, NaN: H = 1e300, a = 1e-300) come back as NaN, which makes the caller fall back to the ball grid.
Precision: IEEE double. Rigorous modules never import numpy: this one uses ``math`` only.
"""
from __future__ import annotations

import math

from .model import Gimbal, psi_from_parts
from .moments import LinearMoment, SineMoment

__all__ = ["FloatGimbal", "float_twin", "half_line_value", "in_safe_range", "SAFE"]

#: magnitudes a twin's result may have; outside (or NaN) the caller falls back to the ball grid
SAFE = (1e-280, 1e280)


def in_safe_range(*xs: float) -> bool:
    """Whether every x is a finite double of magnitude in SAFE (or exactly 0)."""
    lo, hi = SAFE
    for x in xs:
        a = abs(x)
        if not (a <= hi) or (a != 0.0 and a < lo):
            return False
    return True


class FloatGimbal:
    """The parameters of a :class:`.model.Gimbal` as doubles, with float twins of ``psi_coefficients``,
    ``vdot_polar``, ``v_polar`` and the Psi test's rho (a heuristic; see the module docstring)."""

    __slots__ = ("A0", "B0", "C0", "H", "k", "a", "mu", "xs", "sine", "_k", "_psi")

    def __init__(self, g) -> None:
        pb = g.c                # the parameter balls (exact points here): their midpoints as doubles
        self.A0, self.B0, self.C0, self.H, self.k, self.a, self.mu = (
            float(v.mid()) for v in (pb.A0, pb.B0, pb.C0, pb.H, pb.k, pb.a, pb.mu))
        x = g.x2_star
        self.xs = float(x.rational) * math.pi ** x.pi_power
        self.sine = type(g.law) is SineMoment
        self._psi: dict = {}            # x2 -> psi_coefficients, ("v", x2) -> v_polar's x2 parts (a grid has
                                        # few distinct x2)
        H, B0, C0, A0, k, mu = self.H, self.B0, self.C0, self.A0, self.k, self.mu
        HB = H / B0
        self._k = (HB, C0 * H / (B0 * B0), mu * k * B0 * C0, (A0 - C0) * H * H)

    def f_df(self, x: float) -> tuple[float, float]:
        if self.sine:
            return self.a * math.sin(x), self.a * math.cos(x)
        return self.a * x, self.a

    def psi_coefficients(self, x2: float):
        """((c10, c11, c13), (c20, c21, c23)) as :meth:`.model.Gimbal.psi_coefficients`, in floats (kept per x2)."""
        hit = self._psi.get(x2)
        if hit is None:
            hit = self._psi[x2] = self._psi_coefficients(x2)
        return hit

    def _psi_coefficients(self, x2: float):
        H, B0, C0, A0, k, mu = self.H, self.B0, self.C0, self.A0, self.k, self.mu
        HB, C0HB2, mkBC, AH2 = self._k
        s, cs = math.sin(x2), math.cos(x2)
        iD = 1 / (A0 - C0 * s * s)
        f, fp = self.f_df(x2)
        cs2, sf = cs * cs, s * f
        scs_iD = s * cs * iD
        P = A0 - C0 - C0 * cs2
        return psi_from_parts((s, cs, iD, fp, cs2, sf, scs_iD, HB, C0HB2, AH2, P), H, B0, k, mu, mkBC)

    def vdot_polar(self, x2: float, t: float) -> tuple[float, float]:
        """(A, B) of :func:`.model.vdot_polar` in floats."""
        (c10, c11, c13), (c20, c21, c23) = self.psi_coefficients(x2)
        c, s = math.cos(t), math.sin(t)
        A = c10 * c * c + c20 * s * s
        B = c11 * c * c * c + c13 * s * c * c + c21 * c * s * s + c23 * s * s * s
        return A, B

    def v_polar(self, x2: float, t: float) -> tuple[float, float, float] | None:
        """(alpha, beta, gamma) of :func:`.model.v_polar` in floats (the sine law only: G in closed form; None
        otherwise)."""
        if not self.sine:
            return None
        key = ("v", x2)
        hit = self._psi.get(key)
        if hit is None:
            H, B0, C0, A0, k, mu, a = self.H, self.B0, self.C0, self.A0, self.k, self.mu, self.a
            s2, cs = math.sin(x2), math.cos(x2)
            D = A0 - C0 * s2 * s2
            if C0 == 0:
                G = a * s2 * s2 / (2 * A0)
            else:
                G = a / (2 * C0) * -math.log1p(-(C0 * s2 * s2 / A0))
            f = a * s2
            f3 = H * cs * f / (D * B0)
            S = H * H * cs * cs / (D * B0) + mu * (k / D - mu)
            hit = self._psi[key] = (mu * (H / B0 * G), f3, S, H * cs / B0)
        alpha, f3, S, h = hit
        mu = self.mu
        ct, st = math.cos(t), math.sin(t)
        gamma = ((h * ct + mu * st) ** 2 + S * st * st) / 2
        return alpha, f3 * st, gamma

    def rho(self, x2: float) -> float:
        """max_i |(ci1, ci3)| / ci0 (+inf where ci0 <= 0), as the Psi test's rho at a point, in floats."""
        (c10, c11, c13), (c20, c21, c23) = self.psi_coefficients(x2)
        r1 = math.hypot(c11, c13) / c10 if c10 > 0 else math.inf
        r2 = math.hypot(c21, c23) / c20 if c20 > 0 else math.inf
        return max(r1, r2)


def float_twin(g) -> FloatGimbal | None:
    """The float twin of the gimbal ``g`` (a point :class:`.model.Gimbal`, not a subclass whose parameters are
    balls over a box; its law one of the built-in sine and linear laws, exactly those classes), or None."""
    if type(g) is not Gimbal or type(g.law) not in (SineMoment, LinearMoment):
        return None
    try:
        return FloatGimbal(g)
    except (OverflowError, ZeroDivisionError, ValueError):
        return None


def half_line_value(fg: FloatGimbal, on_half_line):
    """(u, s) -> the sublevel search's value (``on_half_line``: sublevel's ``_value_on_half_line``) in floats;
    None when the twin has no v_polar (a law without a float G)."""
    if not fg.sine:
        return None
    xs, pi = fg.xs, math.pi

    def value(u: float, s: float) -> float:
        try:
            X, T = xs * u, pi * s
            A, B = fg.vdot_polar(X, T)
            al, be, ga = fg.v_polar(X, T)
        except (OverflowError, ZeroDivisionError, ValueError):
            return math.nan
        if not in_safe_range(A, B, al, be, ga):
            return math.nan
        if ga <= 0:
            return math.inf
        return on_half_line(A, B, al, be, ga)[0]
    return value
