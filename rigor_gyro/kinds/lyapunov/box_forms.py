"""Centred (mean-value) forms of the Lyapunov kind's decision functions over a box of parameters.

Over a box P of the raw rational parameters (A, A1, A2, B1, C1, H, k, a, mu; C enters no claim), a function
h(x2, P) evaluated naively on the box's balls loses every correlation between parameters (R2 of (14) has
mu H cos^2 x2* - A0 m = 150 - 100 in the example, whose naive enclosure over a +-5 % box contains 0). Here

    h(X, P) in h(X, P_mid, w_mid) + sum_j dh/dP_j(X, box, W) (P_j - P_mid_j) + dh/dw(X, box, W) (W - w_mid)

with each partial derivative enclosed over the whole box by forward-mode differentiation in balls
(:class:`.model.Dual`, one direction at a time, the other parameters plain balls), intersected with the
naive enclosure. The quantity w = A0 m (A0 times the maximum m over x2) is a maximum, not a formula: it is an
independent variable with its own enclosure W over the box (:func:`w_enclosure`: max over [0, x2*] of
|cos x2 f'(x2)| / (1 - (C0/A0) sin^2 x2), which is A0 m exactly, with no A0 / A0 dependency), so the form
holds for every (P, w) in box x W, in particular at w = w(P).

Guarantee: every function returns a ball containing the exact value for every parameter value in the box
(and every x2 in its ball argument), at the current precision. What the caller decides from it (the box
proof of vdot_nonpositive) is in :mod:`.box_vdot`.

Precision: the caller's. Fails when: a derivative enclosure is not finite (a denominator or a square root's
argument reaching 0 over the box): the form falls back to the naive enclosure, never raises.
"""
from __future__ import annotations

import dataclasses
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_positive
from ...core.subdivision import enclose_max
from .model import Dual, Gimbal, ParameterBalls, hypot_ball

__all__ = ["FORM_PARAMETERS", "ParamGimbal", "balls_of", "parameter_balls", "w_enclosure", "radius_formula",
           "CentredBox"]

#: the raw parameters the claims depend on (C, the rotor's polar inertia, enters neither A0, B0, C0 nor H)
FORM_PARAMETERS = ("A", "A1", "A2", "B1", "C1", "H", "k", "a", "mu")


def _q(x: Fraction) -> arb:
    return arb(fmpq(x.numerator, x.denominator))


def balls_of(raw: dict[str, tuple]) -> dict[str, arb]:
    """Each raw parameter's interval (lo, hi) as a ball containing it."""
    out = {}
    for k, (lo, hi) in raw.items():
        b = _q(Fraction(lo))
        out[k] = b if lo == hi else b.union(_q(Fraction(hi)))
    return out


def parameter_balls(v: dict, xs: arb) -> ParameterBalls:
    """A0 = A + A1 + A2, B0 = A + B1, C0 = A + A1 - C1 and the rest from raw values (balls or Duals)."""
    return ParameterBalls(v["A"] + v["A1"] + v["A2"], v["A"] + v["B1"], v["A"] + v["A1"] - v["C1"], v["H"], v["k"],
                          v["a"], v["mu"], xs)


class ParamGimbal(Gimbal):
    """A :class:`Gimbal` whose parameters are given balls or :class:`Dual` numbers (one direction of the
    forward-mode derivative). A fresh instance per parameter set: the per-ball memo of Gimbal is per instance."""

    def __init__(self, template: Gimbal, pb: ParameterBalls):
        # the template's exact fields only initialise the dataclass: every read goes through ``c`` (pb)
        super().__init__(**{f.name: getattr(template, f.name) for f in dataclasses.fields(Gimbal)})
        self._pb = pb

    @property
    def c(self) -> ParameterBalls:
        return self._pb


def w_enclosure(base: Gimbal, balls: dict[str, arb], max_pieces: int = 400) -> arb:
    """A ball containing w(P) = A0 m(P) = max over 0 <= x2 <= x2* of |cos x2 f'(x2)| A0 / (A0 - C0 sin^2 x2)
    for every P in the box, written as |cos x2 f'(x2)| / (1 - r sin^2 x2), r = C0/A0 (exactly A0 m; no A0/A0
    dependency). Branch and bound to a relative 1e-6 (the box's own width dominates past that)."""
    pb = parameter_balls(balls, base.x2_star.ball())
    r = pb.C0 / pb.A0
    law, a = base.law, pb.a

    def fn(x):
        s = x.sin()
        return abs(x.cos() * law.df(a, x)) / (1 - r * s * s)
    v0 = fn(arb(0))
    return enclose_max(fn, 0, pb.x2_star, abs_tol=abs(v0) * arb("1e-6"), max_pieces=max_pieces).ball


def radius_formula(c: ParameterBalls, w, which: str):
    """R1 (13) or R2 (14) as a formula of the parameters (balls or Duals) and w = A0 m:
    R1 = sqrt(108 A0 (A0 - C0)) H^2 cos^2 x2* (k/A0 - mu) / sqrt(D2),
    R2 = 2 H (mu H cos^2 x2* - w) Ds^2 / (A0 sqrt(4 mu^2 H^2 P^2 Ds^2 sin^2 x2* + (mu k B0 C0 - (A0 - C0) H^2)^2)),
    evaluated with numerator and root divided by H^2 (H enters as w/H and in two terms of relative size 1e-10
    in the example, so its derivative has a certain sign over a +-5 % box),
    equal to sqrt(D1/D2), sqrt(E1/E2) of :func:`.model.closed_form_constants` where k/A0 - mu > 0 (resp.
    mu H cos^2 x2* - w > 0): the caller certifies that sign over the box."""
    A0, B0, C0, H, k, mu = c.A0, c.B0, c.C0, c.H, c.k, c.mu
    xs = c.x2_star
    s, cs = xs.sin(), xs.cos()
    if which == "R1":
        D2 = 16 * mu * mu * A0 * (A0 - C0) * H * H * C0 * C0 + 27 * (mu * k * B0 * C0 + (A0 - C0) * H * H) ** 2
        return (108 * A0 * (A0 - C0)).sqrt() * H * H * cs * cs * (k / A0 - mu) / D2.sqrt()
    Ds = A0 - C0 * s * s
    P = A0 - C0 - C0 * cs * cs
    # numerator and the square root both divided by H^2: H enters as w/H and in two small terms, so the
    # derivative in H (2 w/H^2 > 0 dominant) has a certain sign over wide boxes
    iH = 1 / H
    inner = 4 * mu * mu * P * P * Ds * Ds * s * s * iH * iH + (mu * k * B0 * C0 * iH * iH - (A0 - C0)) ** 2
    return 2 * (mu * cs * cs - w * iH) * Ds * Ds / (A0 * inner.sqrt())


class CentredBox:
    """One box for centred forms with monotonicity: the raw parameters' balls and exact ends, and W (the
    enclosure of w = A0 m over the box). ``lower(h)`` wraps h(gimbal, w, X, dual) -> ball or Dual (None: no
    derivative on X; a plain ball for a direction: h does not depend on that parameter) into X -> a ball whose
    lower end is <= h(x2, P, w) for every x2 in X, P in the box, w in W (a lower bound, for positivity proofs;
    not an enclosure of h's range).

    How (Hansen's monotonicity test, then a centred form): each partial derivative dh/dP_j over X x box x W
    by forward mode (that parameter a Dual with seed 1, the others balls); where one is certainly >= 0 (<= 0),
    h's minimum over the box lies on the face P_j = lo_j (hi_j), so P_j is fixed there, exactly, and the
    derivatives are enclosed again on the smaller box (up to ``ROUNDS`` times, while a parameter gets fixed).
    On what is left, the mean-value form h(X, P_mid, w_mid) + sum_j dh/dP_j (P_j - P_mid_j), intersected
    with the naive enclosure on that face box."""

    ROUNDS = 4

    #: the state of an edge while faces get fixed: the whole interval, its lower end, its upper end, its midpoint
    WHOLE, LO, HI, MID = 0, 1, 2, 3

    def __init__(self, base: Gimbal, raw: dict[str, tuple], W: arb):
        self.base = base
        self.xs = base.x2_star.ball()
        self.raw = {k: (Fraction(lo), Fraction(hi)) for k, (lo, hi) in raw.items()}
        self.W = W
        self.fixed_counts: dict[str, int] = {}      # parameter -> how many evaluations fixed it at a face
        self._balls: dict = {}                      # (name, state) -> its ball at this precision
        for k, (lo, hi) in self.raw.items():
            lq, hq, mq = _q(lo), _q(hi), _q((lo + hi) / 2)
            whole = lq if lo == hi else lq.union(hq)
            self._balls.update({(k, self.WHOLE): whole, (k, self.LO): lq, (k, self.HI): hq, (k, self.MID): mq})
        self.width = {k: self._balls[(k, self.WHOLE)] - self._balls[(k, self.MID)] for k in self.raw}
        self.varying = [k for k in FORM_PARAMETERS if self.raw[k][0] != self.raw[k][1]]

    def _gimbal(self, sub: dict, dual: str | None = None) -> "ParamGimbal":
        v = {k: self._balls[(k, st)] for k, st in sub.items()}
        if dual is not None:
            v[dual] = Dual(v[dual], arb(1))
        return ParamGimbal(self.base, parameter_balls(v, self.xs))

    def lower(self, h, positivity: bool = True):
        """See the class docstring. ``positivity``: return the naive enclosure as soon as it is certainly > 0
        (enough for a positivity proof); False: always the tightest lower bound (a range's end)."""
        W0, LO, HI, MID = self.WHOLE, self.LO, self.HI, self.MID

        def g(X: arb) -> arb:
            sub = {k: W0 for k in self.raw}
            W = self.W
            naive = h(self._gimbal(sub), W, X, False)
            if positivity and certainly_positive(naive):
                return naive
            grads: dict = {}
            for _ in range(self.ROUNDS):
                grads, moved = {}, False
                for k in self.varying:
                    if sub[k] != W0:
                        continue
                    d = h(self._gimbal(sub, k), W, X, True)
                    if d is None:
                        return naive
                    if type(d) is not Dual:
                        continue
                    if not d.d.is_finite():
                        return naive
                    if d.d >= 0 or d.d <= 0:            # certainly one sign: the minimum is on a face
                        sub[k] = LO if d.d >= 0 else HI
                        self.fixed_counts[k] = self.fixed_counts.get(k, 0) + 1
                        moved = True
                    else:
                        grads[k] = d.d
                if not W.rad().is_zero():
                    d = h(self._gimbal(sub), Dual(W, arb(1)), X, True)
                    if d is None:
                        return naive
                    if type(d) is Dual and d.d.is_finite() and (d.d >= 0 or d.d <= 0):
                        W = arb(W.lower()) if d.d >= 0 else arb(W.upper())
                        moved = True
                    elif type(d) is Dual and d.d.is_finite():
                        grads["w"] = d.d
                    elif type(d) is Dual:
                        return naive
                if not moved:
                    break
            face = h(self._gimbal(sub), W, X, False)
            if face.overlaps(naive):
                face = face.intersection(naive)
            if (positivity and certainly_positive(face)) or not grads:
                return face
            mid = {k: (MID if st == W0 else st) for k, st in sub.items()}
            w_mid = arb(W.mid())
            mv = h(self._gimbal(mid), w_mid, X, False)
            for k, d in grads.items():
                mv = mv + d * ((W - w_mid) if k == "w" else self.width[k])
            if not mv.is_finite():
                return face
            return face.intersection(mv) if face.overlaps(mv) else mv
        return g


def psi_disc_margin(which_R: str, i: int, R_fixed: arb | None = None):
    """h(gimbal, w, X, dual) = ci0 - R |(ci1, ci3)|: the minimum over the disc of radius R of Psi_i at x2 in X
    (:func:`.model.psi_min_functions`), R = R1 or R2 of :func:`radius_formula` at the gimbal's parameters (or
    the fixed ``R_fixed``). ``dual``: evaluated for a derivative (|(ci1, ci3)| as a Dual square root; a
    non-finite derivative where it vanishes, and the form falls back)."""
    def h(gm: Gimbal, w, X: arb, dual: bool):
        c0, c1, c3 = gm.psi_coefficients(X)[i]
        R = R_fixed if R_fixed is not None else radius_formula(gm.c, w, which_R)
        if not dual:
            return c0 - R * hypot_ball(c1, c3)
        n = c1 * c1 + c3 * c3
        if type(n) is Dual and not certainly_positive(n.v):
            return None                # |(ci1, ci3)| not differentiable on X: no centred form
        if type(n) is not Dual:
            return c0 - R * hypot_ball(c1, c3)
        return c0 - R * n.sqrt()
    return h
