"""The largest sublevel set of V (7) on which Vdot <= 0: certified bounds of c_max.

c_max is the infimum of V over the set N = {Vdot >= 0, (x1, x3) != (0, 0), |x2| <= x2*} together with the
faces |x2| = x2* (the edge of the range where V > 0 is certified). (On the x2 axis x1 = x3 = 0, Vdot = 0
exactly while V = mu F(x2) -> 0: those points are left out of N; there x1' = -f(x2)/D != 0, so no
trajectory stays on the axis off the origin.) For every c <= c_max the connected component of {V < c}
that contains the origin lies in |x2| < x2*, and Vdot <= 0 on it with equality only on the axis: with
V > 0 off the origin (claim ``v_positive``) and x2 f(x2) > 0 it is positively invariant, bounded (V grows
like r^2 in x1, x3, see :func:`rigor_gyro.kinds.lyapunov.model.v_polar`) and, by LaSalle's principle,
inside the domain of attraction. This is the classic estimate for a given V; it needs no region (17)
and no radius R.

How:

* lower bound: in polar form x1 = r cos t, x3 = r sin t (t in [0, pi], r of either sign),
  Vdot = -r^2 (A + r B) and V = alpha + beta r + gamma r^2. Over a box of (x2, t) the part of N above
  it is the half-line r B <= -A, and V's minimum there is bounded below in closed form
  (:func:`rigor_gyro.kinds.lyapunov.model.sublevel_lower_bound`); a best-first bisection of the (x2, t)
  domain (:func:`rigor_gyro.core.subdivision.lower_bound_on_box`) raises the smallest bound towards
  the search's value. The faces add phi(+-x2*) = min of V there.
* upper bound: V at a certified point of N (Vdot > 0 certainly, evaluated by automatic
  differentiation, not through the polar form), found by a search on point values (ball midpoints; its
  grid scanned by a float twin, :mod:`.float_twin`, which only proposes where the compass search starts), or
  phi(x2*) at the face's minimiser, whichever is smaller. It bounds c_max as defined; it is not a
  proof that a larger sublevel set fails to be an estimate (that depends on which component).

Precision: the current working precision. The bounds are exact decimals (the lower rounded down, the
upper rounded up); their relative gap is a search setting (``GAP``, ``BOX_BUDGET``), never a width claimed.
Fails when: the box budget runs out before the gap is reached: the lower bound is still certified,
only further from the upper one; no lower bound > 0 at all leaves the claim undecided.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_gt, certainly_le, certainly_lt, certainly_positive, decimal_bounds, enclosure_text, exact_fraction
from ...core.boxes import Box
from ...core.subdivision import lower_bound_on_box
from .model import Gimbal
from .polar_forms import (DIRECT_DOMAIN, GIMBAL_LOCK_COS, square_from_ends, sublevel_lower_bound, symmetric_in_x2,
                          v_polar, vdot_polar)
from .float_twin import float_twin, half_line_value
from .search import grid_then_compass

__all__ = ["Sublevel", "largest_sublevel", "box_lower_bound", "phi_lower", "GAP", "GAP_FACES_BIND", "BOX_BUDGET"]

#: the relative gap below the point's value the lower bound aims at, and the box budget it may use (a search
#: setting: with the budget spent the lower bound is still certified, only further below)
GAP = "1e-3"
BOX_BUDGET = 3000
#: the gap aimed at when the faces clearly bind (their level is below half the point's value): then the
#: infimum over N only has to be shown above the faces, and a 10 % bracket of it (a quarter of the boxes
#: of a 1e-3 one) still says by how much
GAP_FACES_BIND = "0.1"


@dataclass
class Sublevel:
    """Certified c_lower <= c_max <= c_upper (exact decimals) with their witnesses, and the two parts
    c_max is the smaller of: the infimum of V over N (n_lower <= it <= n_upper) and over the faces
    (``face``, an enclosure of min(phi(x2*), phi(-x2*)))."""

    c_lower: str | None = None
    c_upper: str | None = None
    n_lower: str | None = None
    n_upper: str | None = None
    face: arb | None = None
    leaves: list = field(default_factory=list)
    boxes: int = 0
    #: the relative gap below the point's value the lower bound aimed at (GAP, or GAP_FACES_BIND)
    gap: str = GAP
    #: the point of N (exact balls) whose V gives n_upper
    point: tuple | None = None
    estimate: float = math.nan
    at: tuple = (math.nan, math.nan)
    reason: str = ""
    #: a certified reason why c_max <= 0 (no estimate at all): {"where": "faces", "phi": ball} or
    #: {"where": "origin", "s": Fraction, "A": ball} (A(0, pi s) < 0: Vdot > 0 arbitrarily near 0)
    refutation: dict | None = None
    #: when no positive lower bound over N was certified: the best one (it decides the claim; its
    #: progress over doublings of the precision steers the escalation)
    bound: arb | None = None
    #: set when the lower bound stayed unbounded below (-inf) on the whole box budget: what blows up, on
    #: which box (a subdivision and geometry matter, not the precision: the claim stops escalating)
    unbounded: str = ""

    @property
    def binding(self) -> str:
        """Which part decides c_max: "faces", "vdot" or "undecided" (certified comparison)."""
        if self.n_lower is None or self.face is None or not self.face.is_finite():
            return "undecided"
        if certainly_le(self.face.upper(), _q(Fraction(self.n_lower))):
            return "faces"
        if self.n_upper is not None and certainly_le(_q(Fraction(self.n_upper)), self.face.lower()):
            return "vdot"
        return "undecided"


def _q(fr: Fraction) -> arb:
    return arb(fmpq(fr.numerator, fr.denominator))


def _value_on_half_line(A: float, B: float, al: float, be: float, ga: float) -> tuple[float, float]:
    """(min of al + be r + ga r^2 over r != 0 with A + r B <= 0, the r attaining it) in floats: the
    vertex clamped into the half-line (a search helper; nothing is decided by it)."""
    rv = -be / (2 * ga)
    if B == 0:
        return ((al - be * be / (4 * ga)), rv) if A <= 0 else (math.inf, math.nan)
    r0 = -A / B
    r = max(rv, r0) if B < 0 else min(rv, r0)
    return al + be * r + ga * r * r, r


def _search(g: Gimbal, grid: tuple[int, int] = (33, 65)) -> tuple[float, float, float, float]:
    """A search on point values (ball midpoints) for the minimum of V over N: a grid of (u, s)
    (x2 = u x2*, t = pi s), refined by a pattern search. Returns (value, u, s, r). A heuristic: it only
    chooses where the upper bound's point is sought and which target the lower bound aims at."""
    xs, pi = g.c.x2_star, arb.pi()

    def val(u: float, s: float) -> tuple[float, float]:
        X, T = xs * arb(u), pi * arb(s)
        A, B = vdot_polar(g, X, T)
        al, be, ga = v_polar(g, X, T)
        fl = [float(v.mid()) for v in (A, B, al, be, ga)]
        if not all(math.isfinite(v) for v in fl) or fl[4] <= 0:
            return math.inf, math.nan
        return _value_on_half_line(*fl)
    # the grid scanned by the float twin (it only proposes the compass search's start; None: in balls)
    fg = float_twin(g)
    propose = half_line_value(fg, _value_on_half_line) if fg is not None else None
    return grid_then_compass(val, grid, 80, extra=math.nan, propose=propose)


def _point_of_n(g: Gimbal, u: float, s: float, r: float) -> tuple[tuple[arb, arb, arb], arb] | None:
    """A certified point of N near the search's (u, s, r): exact rationals x1, x2, x3 with |x2| <= x2*
    and Vdot > 0 certainly (automatic differentiation along (2)); with V's enclosure there. Moves r
    outwards by growing relative steps until Vdot > 0 is certain."""
    xs, pi = g.c.x2_star, arb.pi()
    x2 = _q(exact_fraction((xs * arb(u)).mid()))
    if not certainly_le(abs(x2), xs):
        x2 = xs.lower() if u > 0 else -xs.lower()
    t = pi * arb(s)
    for step in ("1e-9", "1e-7", "1e-5", "1e-3", "1e-2"):
        rr = arb(r) * (1 + arb(step))
        x1 = _q(exact_fraction((rr * t.cos()).mid()))
        x3 = _q(exact_fraction((rr * t.sin()).mid()))
        if (x1 != 0 or x3 != 0) and certainly_le(abs(x2), xs) and certainly_positive(g.vdot(x1, x2, x3)):
            return (x1, x2, x3), g.V(x1, x2, x3)
    return None


def _origin_counterexample(g: Gimbal, n: int = 64) -> tuple[Fraction, arb] | None:
    """An exact t = pi s (s = j/n) with A(0, t) < 0 certainly, if the grid has one: then Vdot > 0 at
    (r cos t, 0, r sin t) for every small r > 0, where V = gamma r^2 -> 0, so inf V over N = 0."""
    pi = arb.pi()
    for j in range(n + 1):
        s = Fraction(j, n)
        A, _ = vdot_polar(g, arb(0), pi * _q(s))
        if A.is_finite() and certainly_le(A, 0) and not A.contains(0):
            return s, A
    return None


def phi_lower(g: Gimbal, X: arb) -> arb | None:
    """A lower bound of phi(x2) = mu F - f3^2 / (2 S) over the ball X (so of V over {x2 in X}: V = phi +
    S/2 (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2 >= phi where S > 0), or None where S > 0 is not certain on X.

    The form without cancellation: with S = f2 + mu (f1 - mu), f2 = H^2 cos^2 x2 / (D B0) and f3 = H cos x2 f /
    (D B0), f3^2 / S = f^2 / (D B0 (1 + e)), e = mu (f1 - mu) D B0 / (H^2 cos^2 x2): cos x2 cancels (near the
    gimbal lock it spans a wide ball, and f3^2 / S evaluated as it stands is wild). Where mu (f1 - mu) > 0
    certainly, S > 0 and e >= e_lo = its lower end over X (cos^2 from the ball's ends, never below 0), so
    f3^2 / (2 S) <= f^2 / (2 D B0 (1 + e_lo)); elsewhere the plain form with S certainly > 0."""
    c = g.c
    DB = g.D(X) * c.B0
    m = c.mu * (g.f1(X) - c.mu)
    if certainly_positive(m) and certainly_positive(DB):
        e = m.lower() * DB.lower() / (c.H ** 2 * square_from_ends(X.cos()).upper())
        e_lo = e.lower() if e.is_finite() and certainly_positive(e.lower()) else arb(0)
        q = square_from_ends(g.f(X)).upper() / (2 * DB.lower() * (1 + e_lo))
    else:
        S = c.H ** 2 * square_from_ends(X.cos()) / DB + m
        if not (S.is_finite() and certainly_positive(S)):
            return None
        q = square_from_ends(g.f3(X)) / (2 * S)
    low = (c.mu * g.F(X) - q).lower()
    return low if low.is_finite() else None


def box_lower_bound(g: Gimbal):
    """The box function of :func:`largest_sublevel` (and of its checker): a ball whose lower end is <= V over
    the part of N above the (u, s) box: the polar half-line bound of
    :func:`~rigor_gyro.kinds.lyapunov.model.sublevel_lower_bound`, or where it is below 0 (or -inf) and
    :func:`phi_lower` is larger, that bound (a point ball; V >= phi(x2) holds at every point above the box,
    in N or not). Only where cos x2 may be below GIMBAL_LOCK_COS on the box (the gimbal lock, as in
    :func:`~rigor_gyro.kinds.lyapunov.model.v_polar`): there the polar form's A, B and gamma span wide balls on
    boxes the budget can afford, and phi does not depend on t; away from it the boxes, their order and every
    certificate are those of the polar bound alone."""
    polar, xs = sublevel_lower_bound(g), g.c.x2_star

    def f(box: dict) -> arb:
        v = polar(box)
        lo = v.lower()
        X = xs * box["u"]
        if lo.is_finite() and certainly_positive(lo) or certainly_gt(X.cos().lower(), GIMBAL_LOCK_COS):
            return v
        p = phi_lower(g, X)
        if p is not None and (not lo.is_finite() or certainly_lt(lo, p)):
            return p
        return v
    return f


def _what_blows_up(g: Gimbal, leaves: list, lb) -> str:
    """Why the lower bound of V over N is -inf: on the first leaf where it is, which enclosure is not
    usable (gamma, V's coefficient of r^2, not certainly > 0; alpha or beta, or |B|, unbounded)."""
    xs, pi = g.c.x2_star, arb.pi()
    bad = [b for b in leaves if not lb({"u": b.ball("u"), "s": b.ball("s")}).is_finite()]
    if not bad:
        return "the lower bound over the boxes is unbounded below"
    box = bad[0]
    X, T = xs * box.ball("u"), pi * box.ball("s")
    A, B = vdot_polar(g, X, T)
    alpha, beta, gamma = v_polar(g, X, T)
    where = (f"on {len(bad)} of {len(leaves)} boxes of (x2, t), e.g. x2/x2* in [{float(box.interval('u')[0]):.6g}, "
             f"{float(box.interval('u')[1]):.6g}], t/pi in [{float(box.interval('s')[0]):.6g}, {float(box.interval('s')[1]):.6g}]")
    if not (gamma.lower().is_finite() and certainly_positive(gamma.lower())):
        what = (f"gamma = ((h cos t + mu sin t)^2 + S sin^2 t)/2, V's coefficient of r^2, is not certainly positive "
                f"({enclosure_text(gamma, 4)}; h = H cos x2/B0 = {enclosure_text(g.c.H * X.cos() / g.c.B0, 4)})")
    elif not (alpha.is_finite() and beta.is_finite()):
        what = "V's coefficients alpha = mu F, beta = f3 sin t are unbounded"
    else:
        what = f"|B| is unbounded ({enclosure_text(B, 4)})"
    return what + " " + where


def largest_sublevel(g: Gimbal, max_pieces: int) -> Sublevel:
    """Certified bounds c_lower <= c_max <= c_upper (see the module docstring), at the current
    precision, on at most min(``max_pieces``, BOX_BUDGET) boxes of (x2, t)."""
    xs = g.c.x2_star
    out = Sublevel()
    face = g.phi(xs)                # phi = min over (x1, x3) of V at fixed x2 (Gimbal.phi)
    other = g.phi(-xs)
    face = face if certainly_le(face.upper(), other.lower()) else (
        other if certainly_le(other.upper(), face.lower()) else face.union(other))
    out.face = face
    if face.is_finite() and certainly_le(face, 0):
        out.refutation = {"where": "faces", "phi": face}
        out.reason = f"min of V on the faces |x2| = x2* is {enclosure_text(face, 8)} <= 0 (certified): c_max <= 0 at this x2*"
        return out
    origin = _origin_counterexample(g)
    if origin is not None:
        out.refutation = {"where": "origin", "s": origin[0], "A": origin[1]}
        out.reason = (f"at x2 = 0, t = pi * {origin[0]}: A = {enclosure_text(origin[1], 8)} < 0 (certified), so Vdot = -r^2 (A + r B) "
                      "> 0 for all small r > 0 there while V -> 0: c_max <= 0")
        return out
    if not (face.is_finite() and certainly_positive(face)):
        out.reason = f"the minimum of V on the faces |x2| = x2* is not certainly positive ({enclosure_text(face, 6)})"
        return out
    est, u, s, r = _search(g)
    out.estimate, out.at = est, (u, s)
    n_up = None
    if math.isfinite(est) and math.isfinite(r) and r != 0:
        found = _point_of_n(g, u, s, r)
        if found is not None and found[1].is_finite():
            out.point, n_up = found[0], found[1].upper()
            out.n_upper = decimal_bounds(n_up, 12)[1]
    lb = symmetric_in_x2(g, box_lower_bound(g))
    whole = Box.of(DIRECT_DOMAIN)
    # aim at the point's value (or, without a point, at the faces' minimum: N then only has to stay above)
    top = _q(Fraction(out.n_upper)) if out.n_upper is not None else face.lower()
    out.gap = GAP
    if out.n_upper is not None and certainly_le(2 * face.upper(), top * (1 - arb(GAP_FACES_BIND))):
        out.gap = GAP_FACES_BIND
    best = lower_bound_on_box(lb, whole, top * (1 - arb(out.gap)), max_pieces=min(max_pieces, BOX_BUDGET))
    if not (best.bound.is_finite() and certainly_positive(best.bound)):
        out.reason = ("no positive lower bound of V over {Vdot >= 0, (x1, x3) != 0, |x2| <= x2*} was certified "
                      f"(best {enclosure_text(best.bound, 6)} on {best.boxes} boxes)")
        out.bound = best.bound
        if not best.bound.is_finite():
            out.unbounded = _what_blows_up(g, best.leaves, lb)
        return out
    out.n_lower = decimal_bounds(best.bound, 12)[0]      # each end rounded to its own 12 digits: still > 0
    out.leaves, out.boxes = best.leaves, best.boxes
    n_lo = _q(Fraction(out.n_lower))
    out.c_lower = out.n_lower if certainly_le(n_lo, face.lower()) else decimal_bounds(face.lower(), 12)[0]
    if n_up is None or certainly_le(face.upper(), n_up):
        out.c_upper = decimal_bounds(face.upper(), 12)[1]
    else:
        out.c_upper = out.n_upper
    return out


def search_over_n(g: Gimbal) -> tuple[float, float, float, float]:
    """The point search of :func:`largest_sublevel` for the minimum of V over N (x2* of ``g``; ball midpoints,
    the grid scanned by a float twin):
    (value, u, s, r) with x2 = u x2*, t = pi s. A heuristic: it decides nothing."""
    return _search(g)


def certified_point_of_n(g: Gimbal, u: float, s: float, r: float) -> tuple[tuple[arb, arb, arb], arb] | None:
    """A certified point of N near the search's (u, s, r) (exact rationals, |x2| <= x2* of ``g``, Vdot > 0
    certainly) with V's enclosure there; None if none was found (see :func:`largest_sublevel`)."""
    return _point_of_n(g, u, s, r)
