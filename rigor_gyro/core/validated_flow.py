"""A validated Taylor integrator for autonomous systems x' = f(x) in Arb balls (Lohner's method, C^1).

One step of size h from a set S of initial values, stored in Lohner's doubleton form

    S = { c + B r + Q s : r in r0, s in s0 }          (c a point, B and Q point matrices, r0 and s0 ball vectors),

goes as follows (CAPD's C^1 Lohner algorithm and TaylorModels.jl follow the same plan):

1. the box X = hull(S) and the Taylor coefficients of order 0..n of x(t) and of its Jacobian dx(t)/dx0 over X
   (:func:`rigor_gyro.core.taylor_jets.taylor_coefficients`);
2. an a-priori enclosure (Y, W) of (x(t), dx(t)/dx0) over t in [0, h] for every x0 in X, verified by the high-order
   Picard test of Corliss and Rihm (Nedialkov, Jackson and Corliss 1999, eq. (4.5)): if
   sum_{k<=n} [0, h]^k F_k(X, I) + [0, h]^{n+1} F_{n+1}(Y, W) is contained in (Y, W), then for every x0 in X the
   solution exists on [0, h] and (x, dx/dx0) stays in that sum. A guess that fails the test is inflated and tried
   again (``APRIORI_TRIES`` times); then the step is refused;
3. the remainder: x(h) = sum_{k<=n} h^k x_k(x0) + h^{n+1} F_{n+1}(x(xi)) with x(xi) in Y (Lagrange), the same for
   the Jacobian with (Y, W);
4. the mean-value form: x(h; x0) in x(h; c) + J (x0 - c), J the Jacobian's enclosure over X (X convex, contains c
   and S), so the image is c' + B' r + Q' s' with c' = mid x(h; c), B' = mid(J B), Q' an orthonormal basis of
   mid(J Q) (columns ordered by the size of their part of the set: Lohner's QR, which stops the error part s from
   wrapping under rotations), and s' = (Q'^-1 J Q) s + Q'^-1 (x(h; c) - c' + (J B - B') r0), all in balls
   (Q'^-1 is a ball enclosure of the exact inverse of the point matrix Q').

The step size is proposed from the Taylor coefficients at c (floats: (tol / |x_k|)^(1/k) for the last two k), rounded
down to a dyadic rational of 6 significant bits (stored exactly); a step whose test fails is halved, and below
``h_min`` the integration stops and says so. A given step sequence (``steps=``) is used as it is: that is how a
checker re-runs a stored integration (any refused step fails the re-run).

Guarantee: for every x0 in the initial box and every completed step [t0, t0 + h], ``end`` contains x(t0 + h; x0) and
``over`` contains x(t; x0) for all t in [t0, t0 + h] (the solution exists there), at the current working precision.
Floats only propose step sizes and the basis Q'; neither can make an enclosure wrong.

Fails when: the test cannot be verified (a step below ``h_min``, a non-finite coefficient, a field that divides by a
ball containing 0): the integration stops there, ``complete`` is False and ``reason`` says at which time and why;
the steps done so far stay valid. Never an enclosure that was not verified.

Example:
    >>> from fractions import Fraction
    >>> from flint import arb
    >>> from rigor_gyro.core.balls import working_precision
    >>> with working_precision(64):
    ...     fl = validated_flow(lambda x: [x[1], -x[0]], [arb(1), arb(0)], Fraction(1), order=12)
    ...     fl.complete and fl.steps[-1].end[0].contains(arb(1).cos()) and fl.steps[-1].end[1].contains(-arb(1).sin())
    True
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable, Sequence

from flint import arb, arb_mat

from .balls import SeriesTruncated, contains, current_precision, interval
from .taylor_jets import Field, taylor_coefficients

__all__ = ["FlowStep", "Flow", "LohnerSet", "validated_flow", "apriori_enclosure", "dyadic_below", "box_hull",
           "DEFAULT_ORDER", "APRIORI_TRIES", "STEP_BITS"]

DEFAULT_ORDER = 20
#: inflations of the a-priori guess tried before a step is refused (then halved)
APRIORI_TRIES = 3
#: significant bits of a proposed step (a dyadic rational m 2^-e with m < 2^STEP_BITS)
STEP_BITS = 6


def _q(x: Fraction) -> arb:
    return arb(x.numerator) / x.denominator


def dyadic_below(x: float) -> Fraction:
    """The largest m 2^-e <= x with m < 2^STEP_BITS (x > 0 a float): an exact step size."""
    if not (x > 0 and math.isfinite(x)):
        raise ValueError(f"step proposal {x!r}")
    e = STEP_BITS - math.frexp(x)[1]
    m = math.floor(x * 2.0 ** e)
    return Fraction(m) / Fraction(2) ** e if e >= 0 else Fraction(m * 2 ** (-e))


def box_hull(a: arb, b: arb) -> arb:
    return a.union(b)


@dataclass
class FlowStep:
    """One verified step: ``end`` contains x(t0 + h) and ``over`` x(t) on [t0, t0 + h], for every start."""

    t0: Fraction
    h: Fraction
    end: list[arb]
    over: list[arb]


@dataclass
class LohnerSet:
    """{c + B r + Q s : r in r0, s in s}: c, B, Q exact points, r0 and s balls (module docstring)."""

    c: list[arb]
    B: list[list[arb]]
    r0: list[arb]
    Q: list[list[arb]]
    s: list[arb]

    @classmethod
    def from_box(cls, box: Sequence[arb]) -> "LohnerSet":
        n = len(box)
        c = [x.mid() for x in box]
        eye = [[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)]
        return cls(c, eye, [x - m for x, m in zip(box, c)], [row[:] for row in eye], [arb(0)] * n)

    def box(self) -> list[arb]:
        n = len(self.c)
        return [self.c[i] + sum((self.B[i][j] * self.r0[j] for j in range(n)), arb(0))
                + sum((self.Q[i][j] * self.s[j] for j in range(n)), arb(0)) for i in range(n)]


@dataclass
class Flow:
    """The steps done (in order), the order, whether t_end (or the stop condition) was reached, and why not."""

    order: int
    steps: list[FlowStep] = field(default_factory=list)
    complete: bool = False
    stopped_early: bool = False
    reason: str = ""
    state: LohnerSet | None = None

    @property
    def step_sizes(self) -> list[Fraction]:
        return [s.h for s in self.steps]

    @property
    def t(self) -> Fraction:
        return self.steps[-1].t0 + self.steps[-1].h if self.steps else Fraction(0)


def _poly_over(coeffs: list[arb], top: arb, h: Fraction) -> arb:
    """sum_{k<=n} [0, h]^k coeffs[k] + [0, h]^(n+1) top (every t in [0, h])."""
    out = coeffs[0]
    hk = Fraction(1)
    for c in coeffs[1:]:
        hk *= h
        out = out + interval(0, _q(hk)) * c
    return out + interval(0, _q(hk * h)) * top


def _poly_at(coeffs: list[arb], top: arb, h: Fraction) -> arb:
    """sum_{k<=n} h^k coeffs[k] + h^(n+1) top (Horner at the exact point h)."""
    hb = _q(h)
    out = top
    for c in reversed(coeffs):
        out = out * hb + c
    return out


def _inflate(x: arb, extra: arb) -> arb:
    """x widened by |extra| + 2^-(prec-4) |x| + 2^-1000 on both sides (a larger guess for the Picard test)."""
    w = abs(extra).upper() + abs(x).upper() * arb(2) ** (4 - current_precision()) + arb(2) ** -1000
    return x + arb(0, w) if w.is_finite() else x + arb("inf")


def _widen(x: arb) -> arb:
    """x with its radius doubled (plus the relative and absolute floor of :func:`_inflate`)."""
    return _inflate(x, x.rad())


def apriori_enclosure(field: Field, X: Sequence[arb], h: Fraction, order: int, tc=None):
    """(Y, W, x_top, J_top, tc): Y contains x(t; x0) and W dx(t)/dx0 for t in [0, h], x0 in X, verified by the
    high-order Picard test (module docstring, step 2), with the coefficients of order n + 1 over (Y, W); or None
    when the test fails ``APRIORI_TRIES`` times. ``tc``: the coefficients over X (order n + 1, gradients) if known."""
    n = len(X)
    if tc is None:
        tc = taylor_coefficients(field, X, order + 1, gradients=True)
    if not tc.is_finite():
        return None
    Zx = [_poly_over(tc.values[i][:order + 1], tc.values[i][order + 1], h) for i in range(n)]
    Zw = [[_poly_over(tc.jacobian[i][j][:order + 1], tc.jacobian[i][j][order + 1], h) for j in range(n)]
          for i in range(n)]
    hn = _q(h ** (order + 1))
    Y = [_inflate(Zx[i], 4 * hn * tc.values[i][order + 1]) for i in range(n)]
    W = [[_inflate(Zw[i][j], 4 * hn * tc.jacobian[i][j][order + 1]) for j in range(n)] for i in range(n)]
    for _ in range(APRIORI_TRIES):
        tops = top_coefficients(field, Y, W, order + 1)
        if tops is None:
            return None
        topx, topw = tops
        Zx = [_poly_over(tc.values[i][:order + 1], topx[i], h) for i in range(n)]
        Zw = [[_poly_over(tc.jacobian[i][j][:order + 1], topw[i][j], h) for j in range(n)] for i in range(n)]
        if verified(Y, W, Zx, Zw):
            return Zx, Zw, topx, topw, tc
        Y = [_widen(Y[i].union(Zx[i])) for i in range(n)]
        W = [[_widen(W[i][j].union(Zw[i][j])) for j in range(n)] for i in range(n)]
    return None


def top_coefficients(field: Field, Y: Sequence[arb], W, k: int):
    """(x_k over Y, V_k over (Y, W)): the Taylor coefficient of order k of x(t) for every x0 in Y, in mean-value form
    x_k(m) + D x_k(Y) (Y - m) intersected with the direct enclosure (the direct one wraps like (width factor)^k
    under a rotation), and that of V(t) = Phi(t; x0) W, V_k = D x_k(x0) W, for x0 in Y and W in the balls ``W``.
    None when a coefficient is not finite."""
    n = len(Y)
    ty = taylor_coefficients(field, Y, k, gradients=True)
    if not ty.is_finite():
        return None
    m = [y.mid() for y in Y]
    tm = taylor_coefficients(field, m, k)
    if not tm.is_finite():
        return None
    D = [[ty.jacobian[i][j][k] for j in range(n)] for i in range(n)]
    topx = []
    for i in range(n):
        direct = ty.values[i][k]
        mv = tm.values[i][k] + sum((D[i][j] * (Y[j] - m[j]) for j in range(n)), arb(0))
        topx.append(mv.intersection(direct) if mv.overlaps(direct) else mv)
    topw = _matmul(D, W)
    return topx, topw


def verified(Y, W, Zx, Zw) -> bool:
    """The Picard test's decision: every new enclosure finite and contained in the guess."""
    return all(z.is_finite() and contains(y, z) for y, z in zip(Y, Zx)) and \
        all(z.is_finite() and contains(w, z) for rw, rz in zip(W, Zw) for w, z in zip(rw, rz))


def _matmul(A, B):
    n, m, p = len(A), len(B), len(B[0])
    return [[sum((A[i][k] * B[k][j] for k in range(m)), arb(0)) for j in range(p)] for i in range(n)]


def _matvec(A, v):
    return [sum((A[i][k] * v[k] for k in range(len(v))), arb(0)) for i in range(len(A))]


def _orthonormal(N, weights) -> list[list[arb]]:
    """A point matrix with orthonormal columns (to float accuracy) spanning mid(N), columns taken in the order of
    decreasing |column| * weight (Lohner's QR with pivoting); floats only propose it."""
    n = len(N)
    cols = [[float(N[i][j].mid()) for i in range(n)] for j in range(n)]
    order = sorted(range(n), key=lambda j: -math.sqrt(sum(x * x for x in cols[j])) * weights[j])
    basis: list[list[float]] = []
    for j in order:
        v = cols[j][:]
        for _ in range(2):
            for b in basis:
                d = sum(x * y for x, y in zip(v, b))
                v = [x - d * y for x, y in zip(v, b)]
        nv = math.sqrt(sum(x * x for x in v))
        if not (nv > 1e-300 and math.isfinite(nv)):
            v = [1.0 if i == len(basis) else 0.0 for i in range(n)]
            for b in basis:
                d = sum(x * y for x, y in zip(v, b))
                v = [x - d * y for x, y in zip(v, b)]
            nv = math.sqrt(sum(x * x for x in v))
        basis.append([x / nv for x in v])
    # the original column slots keep their order in B; Q's columns are in pivot order (s is re-derived)
    return [[arb(basis[j][i]) for j in range(n)] for i in range(n)]


def _inverse(Q) -> list[list[arb]] | None:
    try:
        inv = arb_mat(Q).inv()
    except (ZeroDivisionError, ValueError):
        return None
    n = len(Q)
    out = [[inv[i, j] for j in range(n)] for i in range(n)]
    return out if all(x.is_finite() for row in out for x in row) else None


def lohner_step(field: Field, S: LohnerSet, h: Fraction, order: int):
    """One step of size h (module docstring): (new set, end box, over-step box), or None if not verified (also when
    the field raises on a ball, e.g. python-flint's series division by a series whose leading ball contains 0)."""
    try:
        return _lohner_step(field, S, h, order)
    except SeriesTruncated:
        raise                       # a cap bug, never a refused step
    except (ArithmeticError, ValueError):
        return None


def _lohner_step(field: Field, S: LohnerSet, h: Fraction, order: int):
    n = len(S.c)
    X = [b.union(c) for b, c in zip(S.box(), S.c)]
    if not all(x.is_finite() for x in X):
        return None
    enc = apriori_enclosure(field, X, h, order)
    if enc is None:
        return None
    Zx, _, topx, topw, tc = enc
    tcc = taylor_coefficients(field, S.c, order)
    if not tcc.is_finite():
        return None
    Pc = [_poly_at(tcc.values[i][:order + 1], topx[i], h) for i in range(n)]
    J = [[_poly_at(tc.jacobian[i][j][:order + 1], topw[i][j], h) for j in range(n)] for i in range(n)]
    c2 = [p.mid() for p in Pc]
    M = _matmul(J, S.B)
    B2 = [[x.mid() for x in row] for row in M]
    N = _matmul(J, S.Q)
    weights = [float(abs(x).upper()) for x in S.s]
    Q2 = _orthonormal(N, [w if w > 0 else 1.0 for w in weights])
    Qi = _inverse(Q2)
    if Qi is None:
        return None
    err = [Pc[i] - c2[i] + sum(((M[i][j] - B2[i][j]) * S.r0[j] for j in range(n)), arb(0)) for i in range(n)]
    s2 = [a + b for a, b in zip(_matvec(_matmul(Qi, N), S.s), _matvec(Qi, err))]
    new = LohnerSet(c2, B2, S.r0, Q2, s2)
    end = new.box()
    # the end box: the doubleton's hull, intersected with the direct (wrapped) enclosure of the a-priori step
    end = [e.intersection(z) if e.overlaps(z) else e for e, z in zip(end, _end_direct(tc, topx, h, order))]
    if not all(x.is_finite() for x in end + s2):
        return None
    return new, end, Zx


def _end_direct(tc, topx, h, order):
    return [_poly_at(tc.values[i][:order + 1], topx[i], h) for i in range(len(topx))]


def propose_step(field: Field, c: Sequence[arb], order: int, tol: float) -> float:
    """A float step proposal from the Taylor coefficients at c: min over k in {n-1, n} of (tol / |x_k|)^(1/k)
    (the terms' size; no guarantee: the a-priori test decides). NaN when the field raises at c."""
    try:
        tc = taylor_coefficients(field, c, order)
    except SeriesTruncated:
        raise
    except (ArithmeticError, ValueError):
        return math.nan
    best = math.inf
    for k in (order - 1, order):
        if k < 1:
            continue
        size = max(float(abs(tc.values[i][k]).upper()) for i in range(len(c)))
        if size > 0 and math.isfinite(size):
            best = min(best, (tol / size) ** (1.0 / k))
    return best


def validated_flow(field: Field, box: Sequence[arb], t_end: Fraction, order: int = DEFAULT_ORDER, *,
                   steps: Sequence[Fraction] | None = None, h_min: Fraction = Fraction(1, 2 ** 40),
                   h_max: Fraction | None = None, tol: float | None = None, max_steps: int = 100000,
                   stop: Callable[[FlowStep], bool] | None = None) -> Flow:
    """Integrate from every x0 in ``box`` (balls) over [0, t_end] (module docstring). ``steps``: a stored step
    sequence to re-run exactly (the adaptive choice is skipped; a refused step ends the flow incomplete).
    ``stop(step)`` True ends the flow after that step (``stopped_early``; complete)."""
    t_end = Fraction(t_end)
    fl = Flow(order)
    S = LohnerSet.from_box(list(box))
    scale = max([1.0] + [float(abs(x).upper()) for x in box])
    tol = tol if tol is not None else scale * 2.0 ** (-current_precision())
    t = Fraction(0)
    fixed = list(steps) if steps is not None else None
    while t < t_end:
        if len(fl.steps) >= max_steps:
            fl.reason = f"step budget of {max_steps} steps spent at t = {float(t):.6g}"
            break
        if fixed is not None:
            if len(fl.steps) >= len(fixed):
                fl.reason = f"the stored steps end at t = {t} before t_end = {t_end}"
                break
            h = Fraction(fixed[len(fl.steps)])
            if not (0 < h <= t_end - t):
                fl.reason = f"stored step {h} not in (0, {t_end - t}]"
                break
        else:
            prop = propose_step(field, S.c, order, tol)
            remaining = t_end - t
            h = remaining if not (0 < prop < float(remaining)) else min(dyadic_below(prop), remaining)
            if h_max is not None:
                h = min(h, h_max)
            if h < h_min and h < remaining:
                fl.reason = (f"the enclosure at t = {float(t):.9g} could not be verified with any step >= h_min = "
                             f"{h_min} (the terms of the Taylor series ask for a step of {prop:.3g})")
                break
        while True:
            res = lohner_step(field, S, h, order)
            if res is not None:
                break
            if fixed is not None or h / 2 < h_min:
                fl.reason = (f"the enclosure over [{float(t):.9g}, {float(t + h):.9g}] could not be verified"
                             + ("" if fixed is not None else f" with any step >= h_min = {h_min}"))
                fl.state = S
                return fl
            h = h / 2
        S, end, over = res
        st = FlowStep(t, h, end, over)
        fl.steps.append(st)
        t += h
        if stop is not None and stop(st):
            fl.complete, fl.stopped_early, fl.state = True, True, S
            return fl
    fl.state = S
    fl.complete = t >= t_end and not fl.reason
    return fl
