"""The direct test's minimiser on a face |x2| = x2* (the active constraint): an interval-Newton lower bound
of A/|B| near it, so the direct radius is certified to the precision's digits instead of to the width of
the boxes around the minimiser.

The direct test (:func:`~rigor_gyro.kinds.lyapunov.model.direct_margin`) proves A - R |B| > 0 on (u, s)
boxes (x2 = u x2*, t = pi s); its supremum radius is inf A/|B|. For the paper's example that infimum sits
on a face u = +-1 (F = A/|B| decreases towards the face). A box's centred form overestimates by the square
of the box's width, so a margin of 1e-9 below the infimum needs boxes of width ~1e-5 around the minimiser.
:func:`face_margin` decides such a box at once:

* F decreases towards the face: dF/du has one sign on the box extended to the face (forward mode), so
  F(u, s) >= F(+-1, s) on the box;
* on the face, every critical point of F(+-1, .) in the box's s-range S lies in the interval-Newton
  iterates N = m - F'(m) / F''(X), X <- N cap X (F'' excluding 0 on X; F' and F'' from a Taylor series in
  s, ``arb_series``): the minimum of F(+-1, .) over S is at an end of S or in the last X, where a
  mean-value form encloses F to the working precision's digits;
* so A - R |B| = |B| (F - R) >= |B|.lower (min - R) > 0 when that minimum's lower bound exceeds R.

:func:`face_polish` (floats of balls' midpoints: a heuristic that only chooses a radius and a point) puts
the search's minimiser on the face to the working precision by Newton steps on F'(s) = 0.

Guarantee: :func:`face_margin` returns, on every box, a ball containing the range of A - R |B| or a
positive point below that range (the face argument; only the sign is used); where the face argument does not apply it returns the direct form's ball. Precision: the
working one. Fails when: never raises on finite balls; the face argument gives up (returns the direct ball)
when B or F'' may vanish, when dF/du may vanish, or when a ball is not finite.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, arb_series, fmpq

from ...core.balls import certainly_negative, certainly_positive, current_precision, exact_fraction
from .model import Dual, Gimbal
from .polar_forms import direct_margin, vdot_polar

__all__ = ["face_series", "face_min_lower", "face_margin", "face_polish", "FACE_BOX_U", "FACE_BOX_S"]

#: the face argument is tried on boxes within this distance of a face (in u) ...
FACE_BOX_U = Fraction(1, 8)
#: ... and of at most this width in s
FACE_BOX_S = Fraction(1, 16)
#: interval-Newton iterations on the face (each squares the width until the precision's floor)
NEWTON_STEPS = 8


def face_series(g: Gimbal, face: int, S: arb, mu: arb | None = None) -> tuple[arb, arb, arb] | None:
    """(F, F', F'') of F(s) = A/|B| at x2 = face * x2* (face = +-1), t = pi s, enclosed over the ball ``S``
    (a Taylor series in s, so F' and F'' hold for every s in S), or None when B may vanish on S."""
    x2 = g.c.x2_star * face
    A, B = vdot_polar(g, x2, arb_series([arb.pi() * S, arb.pi()], prec=3), mu)
    b0 = B.coeffs()[0] if B.coeffs() else arb(0)
    if certainly_positive(b0):
        F = A / B
    elif certainly_negative(b0):
        F = -A / B
    else:
        return None
    c = list(F.coeffs()) + [arb(0)] * 3
    return c[0], c[1], 2 * c[2]


def _point(q: Fraction) -> arb:
    return arb(fmpq(q.numerator, q.denominator))


def face_min_lower(g: Gimbal, face: int, s_lo: Fraction, s_hi: Fraction, mu: arb | None = None) -> arb | None:
    """A lower bound of min over s in [s_lo, s_hi] (exact) of F(face, s) = A/|B| (see :func:`face_series`),
    or None when it cannot be given (B or F'' may vanish on the interval, a ball is not finite).

    Why: F is smooth where B != 0, so its minimum over the interval is at an end or at a critical point; with
    F'' != 0 on X every zero of F' in X lies in m - F'(m) / F''(X) (mean value theorem), so the interval-Newton
    iterates X keep all critical points of the interval; F over the last X by the mean-value form."""
    S = _point(s_lo).union(_point(s_hi))
    whole = face_series(g, face, S, mu)
    if whole is None:
        return None
    ends = []
    for q in (s_lo, s_hi):
        e = face_series(g, face, _point(q), mu)
        if e is None or not e[0].is_finite():
            return None
        ends.append(e[0].lower())
    low = ends[0].min(ends[1])
    X = S
    for _ in range(NEWTON_STEPS):
        sX = face_series(g, face, X, mu)
        if sX is None or not (certainly_positive(sX[2]) or certainly_negative(sX[2])):
            return None
        m = arb(X.mid())
        sm = face_series(g, face, m, mu)
        if sm is None or not sm[1].is_finite():
            return None
        N = m - sm[1] / sX[2]
        if not N.overlaps(X):
            return low                    # no critical point in the interval: the minimum is at an end
        new = N.intersection(X)
        if not (new.rad() < X.rad()):     # the precision's floor
            X = new
            break
        X = new
    sX, sm = face_series(g, face, X, mu), face_series(g, face, arb(X.mid()), mu)
    if sX is None or sm is None:
        return None
    inner = sm[0] + sX[1] * (X - arb(X.mid()))
    inner = inner.intersection(sX[0]) if inner.overlaps(sX[0]) else inner
    if not inner.is_finite():
        return None
    return low.min(inner.lower())


_NONE = object()


def _face_min_lower_memo(g: Gimbal, face: int, s_lo: Fraction, s_hi: Fraction) -> arb | None:
    """:func:`face_min_lower` at g's mu, memoised on the gimbal by (face, s-range, precision): boxes of one s-range
    at different u, and the certifications at several radii, ask the same face minimum (about half the calls
    were repeats on agafonov2013). The value is a function of these and g's parameters alone."""
    memo = g.__dict__.setdefault("_face_min_lower", {})
    key = (face, s_lo, s_hi, current_precision())
    hit = memo.get(key, _NONE)
    if hit is _NONE:
        hit = memo[key] = face_min_lower(g, face, s_lo, s_hi)
    return hit


def _face_of(U: arb) -> int | None:
    """The face (+1 or -1) whose distance from the u-ball's midpoint is at most FACE_BOX_U, or None (a choice
    of which boxes to try: the argument holds on any box, extended to its face)."""
    near, m = _point(1 - FACE_BOX_U), arb(U.mid())
    if m >= near:
        return 1
    if m <= -near:
        return -1
    return None


def face_margin(g: Gimbal, R: arb):
    """The box function {u, s} -> A - R |B| of :func:`~rigor_gyro.kinds.lyapunov.model.direct_margin`,
    with the face argument of this module where that form does not decide a box near a face (see the
    module's docstring). Its lower end is a lower bound of A - R |B| on the box (only the sign is used); on
    boxes the face argument decides, the ball is that bound, a positive point. Used with
    :func:`~rigor_gyro.kinds.lyapunov.model.symmetric_in_x2` as the direct form is (A - R |B| is even in u for
    an odd law; the face argument is valid on either face)."""
    base = direct_margin(g, R)
    xs, pi = g.c.x2_star, arb.pi()

    def f(box: dict) -> arb:
        v = base(box)
        U, S = box["u"], box["s"]
        if certainly_positive(v) or (U.rad().is_zero() and S.rad().is_zero()):
            return v
        face = _face_of(U)
        if face is None or not S.rad() * 2 <= _point(FACE_BOX_S):
            return v
        Ue = U.union(arb(face))              # the box extended to its face
        Ad, Bd = vdot_polar(g, xs * Dual(Ue, arb(1)), pi * S)
        if certainly_positive(Bd.v):
            sgn = 1
        elif certainly_negative(Bd.v):
            sgn = -1
        else:
            return v
        # sign of dF/du = sgn (A_u B - A B_u) / B^2: F decreases towards the face
        du = sgn * (Ad.d * Bd.v - Ad.v * Bd.d)
        if not (certainly_negative(du) if face == 1 else certainly_positive(du)):
            return v
        lo_s, hi_s = exact_fraction(S.lower()), exact_fraction(S.upper())
        low = _face_min_lower_memo(g, face, lo_s, hi_s)
        if low is None or not certainly_positive(low - R):
            return v
        _, B = vdot_polar(g, xs * U, pi * S)
        bound = (abs(B).lower() * (low - R)).lower()
        if not certainly_positive(bound):
            return v
        # the bound itself (a point ball): the hull [bound, v.upper] would be stored as mid +- rad with the
        # radius rounded up, and its lower end could dip below a bound of 1e-12 next to an upper end of 1e2
        return bound
    return f


def face_polish(g: Gimbal, face: int, s0: float, steps: int = 6, mu: arb | None = None) -> tuple[float, Fraction]:
    """Newton steps on F'(s) = 0 on the face from s0 (a heuristic in the balls' midpoints): (F at the last
    iterate as a float, that iterate as an exact rational). Stops early where F'' is not positive (no local
    minimum there) or a step leaves [0, 1]; returns s0's value then."""
    s = Fraction(s0)
    best = None
    for _ in range(steps):
        r = face_series(g, face, _point(s), mu)
        if r is None:
            break
        F0, F1, F2 = (float(x.mid()) for x in r)
        if best is None or F0 <= best[0]:
            best = (F0, s)
        if not F2 > 0:
            break
        nxt = s - Fraction(F1) / Fraction(F2)
        if not 0 <= nxt <= 1 or nxt == s:
            break
        s = exact_fraction(arb(fmpq(nxt.numerator, nxt.denominator)).mid())
    r = face_series(g, face, _point(s), mu)
    if r is not None and (best is None or float(r[0].mid()) <= best[0]):
        best = (float(r[0].mid()), s)
    return best if best is not None else (float("inf"), Fraction(s0))
