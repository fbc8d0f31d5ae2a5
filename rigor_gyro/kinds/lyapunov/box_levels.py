"""Two of the Lyapunov kind's quantities over a parameter box: the level c* and the margin of ``v_positive``.

* ``c_star``: c*(P) = min of V over the boundary of region (17) (the faces |x2| = x2* inside the disc and the
  cylinder x1^2 + x3^2 = R(P)^2), the level of the invariant estimate {V < c*} of the point claim
  ``invariant_estimate``. Over the box, with R's enclosure R_box over it (the scene's option R, or the hull of
  R = min(R1, R2) that the caller certified positive):

  - lower end: min(phi(x2*) lower end, a lower bound of V on the cylinder) over the box's balls, the cylinder
    bound :func:`.model.cylinder_lower_bound` evaluated with R_box (its closed form in R holds for every R
    in the ball) and bounded over x2 by branch and bound. phi(x2*) = min of V over the whole face plane, so
    the minimum over the face inside the disc is at least that, wherever the face's minimiser lies;
  - upper end: :func:`.model.c_star_upper` on the box's balls: V at 96 points of every parameter's own
    cylinder (R_box times exact unit vectors) and, where the faces' minimiser is certainly inside every
    parameter's disc, phi(x2*), each an upper bound over the box;
  - for an odd law, each end is then tightened (the larger lower end, the smaller upper end: both bound every
    member) by the centred forms of :mod:`.box_cstar` (phi(x2*) and the cylinder bound as a quadratic in R,
    in the parameters by monotonicity at faces and mean-value forms; over a +-1 % box of the example
    [21.98, 24.93] where the naive balls give [-29.7, 34.1]).

* ``v_positive_margin``: min over |x2| <= x2* (over [0, x2*] for an odd law) of
  min(1 - mu/f1(x2), psi(x2)/P(x2)) with P = H^2 mu cos^2 x2/(D B0) + mu^2 f1 > 0 the positive part of psi
  (psi = P - (H cos^2 x2/(D B0)) q - mu^3). It is <= 1, and > 0 exactly when f1 > mu and psi > 0 on the range:
  with f(x)/x > 0 (a property of the law, certified by the point claim), V > 0 off the origin
  (``v_positive``). Lower end: branch and bound over x2 of the naive enclosure on the box's balls; upper end:
  the smallest upper end over the box at V_PROBES exact points of the range.

Guarantee: each ball contains the quantity for every parameter value in the box. Precision: the caller's.
Fails when: never raises; None where an enclosure is not finite (a denominator reaching 0 over the box, R not
positive): the quantity is then not stated on that box.
"""
from __future__ import annotations

from flint import arb

from ...core.balls import certainly_lt, certainly_positive
from ...core.subdivision import enclose_max
from .box_cstar import c_star_centred
from .polar_forms import law_is_odd
from .closed_forms import c_star_upper, cylinder_lower_bound

__all__ = ["c_star_box", "v_positive_margin_box", "V_PROBES"]

#: exact x2 points at which the upper end of v_positive_margin is bounded
V_PROBES = 16
#: pieces of the x2 branch and bound (each quantity)
LEVEL_PIECES = 400


def _x2_range(g) -> tuple[arb, arb]:
    xs = g.x2_star.ball()
    return (arb(0) if law_is_odd(g.law) else -xs), xs


def _probes(lo: arb, hi: arb) -> list[arb]:
    """``lo`` and V_PROBES - 1 exact points strictly inside [lo, hi] (never past x2*)."""
    return [lo] + [arb((lo + (hi - lo) * j / V_PROBES).mid()) for j in range(1, V_PROBES)]


def c_star_box(g, R: arb) -> arb | None:
    """A ball containing c*(P) for every P of the box whose balls ``g`` (a BoxGimbal) holds, R(P) in ``R``."""
    if not (R.is_finite() and certainly_positive(R.lower())):
        return None
    lo_x, xs = _x2_range(g)
    lb = cylinder_lower_bound(g, R)
    scale = abs(g.phi(xs)) + R * R
    if not scale.is_finite():
        return None
    cyl = enclose_max(lambda x: -lb(x), lo_x, xs, abs_tol=scale * arb("1e-8"), max_pieces=LEVEL_PIECES)
    cyl_lb = (-cyl.ball).lower()
    faces = [g.phi(xs)] + ([] if law_is_odd(g.law) else [g.phi(-xs)])
    face_lo = faces[0].lower() if len(faces) == 1 else faces[0].lower().min(faces[1].lower())
    lower = arb(face_lo).min(arb(cyl_lb))
    m1, m3 = g.phi_minimiser(xs)
    inside = law_is_odd(g.law) and certainly_lt(m1 ** 2 + m3 ** 2, arb(R.lower()) ** 2)
    upper = c_star_upper(g, R, xs, faces[0], inside)
    raw = getattr(g, "raw", None)
    centred = c_star_centred(g, raw, R) if raw is not None else None
    if centred is not None:        # both bounds hold for every member: the tighter of each
        clo, cup = centred
        lower = arb(lower.lower()).max(clo) if lower.is_finite() else clo
        if cup is not None:
            upper = arb(upper.upper()).min(cup) if upper.is_finite() else cup
    if not (lower.is_finite() and upper.is_finite()):
        return None
    return arb(lower.lower()).union(arb(upper.upper()))


def _margin(g, x2: arb) -> arb:
    c = g.c
    f1, cs = g.f1(x2), x2.cos()
    t = c.H * cs * cs / (g.D(x2) * c.B0)
    pos = t * c.mu * c.H + c.mu * c.mu * f1
    return (1 - c.mu / f1).min(g.psi(x2) / pos)


def v_positive_margin_box(g) -> arb | None:
    """A ball containing the v_positive margin (module docstring) for every P of the box ``g`` holds."""
    lo_x, xs = _x2_range(g)
    scale = _margin(g, arb(0))
    if not scale.is_finite():
        return None
    worst = enclose_max(lambda x: -_margin(g, x), lo_x, xs, abs_tol=arb("1e-8"), max_pieces=LEVEL_PIECES)
    lower = (-worst.ball).lower()
    upper = None
    for x in _probes(lo_x, xs):
        u = _margin(g, x).upper()
        if arb(u).is_finite():
            upper = u if upper is None else upper.min(u)
    if upper is None or not arb(lower).is_finite():
        return None
    return arb(lower).union(arb(upper))
