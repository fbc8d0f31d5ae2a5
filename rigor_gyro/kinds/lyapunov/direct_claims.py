"""``vdot_direct``: Vdot < 0 on the disc cylinder of radius R_direct, certified directly (A - R |B| > 0 on
boxes of (x2, t), :func:`~rigor_gyro.kinds.lyapunov.model.direct_margin`) at a radius a float search proposes,
and a certified point above it where Vdot > 0 (so the supremum radius is bracketed).

The search only chooses; the certification decides. A failed certification is inconclusive, never refuted.
Precision: the attempt's."""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from flint import arb

from ...core.balls import certainly_le, certainly_positive, decimal_bounds, exact_fraction
from ...core.outcome import Claim, Status
from ...core.stored import ball_text
from ...core.boxes import Box
from ...core.subdivision import certify_positive_on_box
from .direct_mu import direct_point_search
from .direct_face import face_margin, face_polish
from .model import Gimbal
from .polar_forms import DIRECT_DOMAIN, symmetric_in_x2, vdot_polar
from .claim_context import ClaimContext, make_claim, to_fmpq, fmt, exact_ball, relative_gap, searched

# ------------------------------------------------------------------------------------ Vdot < 0 directly


#: relative distance of R_direct below, and of the counterexample's radius above, the searched infimum
DIRECT_MARGINS = ("4e-7", "4e-6", "4e-5", "4e-4", "4e-3")
#: where the search's minimiser lies on a face |x2| = x2* (direct_face: interval Newton there), first this
#: margin, R_direct and R_direct_upper with FACE_DIGITS significant digits, on at most FACE_BOXES boxes
FACE_MARGIN, FACE_DIGITS, FACE_BOXES = "2e-11", 15, 3000


#: how many times the direct test searches again from the point where a certification failed
DIRECT_RESEARCHES = 4


def _lower_ratio(g: Gimbal, cert, R: float) -> tuple[float, float, float] | None:
    """(A/|B|, u, s) at the point where a failed certification of A - R' |B| > 0 stopped (its certified
    counterexample, or the midpoint of the box it could not decide), when that ratio is below ``R``
    (the radius of the loosest margin): the float search missed the minimiser of A/|B| (a heuristic;
    it only chooses where to search again)."""
    pt = cert.witness if cert.status is Status.REFUTED else cert.stuck.midpoint() if cert.stuck is not None else None
    if pt is None:
        return None
    u, s = float(pt["u"]), float(pt["s"])
    A, B = vdot_polar(g, g.c.x2_star * arb(u), arb.pi() * arb(s))
    a, b = float(A.mid()), abs(float(B.mid()))
    r = a / b if b > 0 else math.inf
    return (r, u, s) if 0 < r < R else None


@dataclass
class _Direct:
    """The direct test certified at one mu: the search's estimate and point, the radius certified (or None)
    with its boxes, and a certified point above it where Vdot > 0 (or None)."""
    est: float
    u0: float
    s0: float
    amin: float
    R_text: str = ""
    cert: object = None
    point: tuple | None = None
    up_text: str = ""


def certify_direct(g: Gimbal, max_pieces: int, cap: float | None = None) -> _Direct:
    """Search the supremum radius of the direct test at g's mu, certify A - R |B| > 0 a little below it
    (DIRECT_MARGINS) and a point a little above it where Vdot > 0. ``cap``: a known upper bound of the
    supremum (the search's estimate is lowered to it: a search that misses the global minimiser of A/|B|
    overestimates the radius, and a radius above the supremum cannot be certified)."""
    xs = g.c.x2_star
    est, u0, s0, amin = direct_point_search(g)
    if cap is not None and math.isfinite(cap) and 0 < cap < est:
        est = cap
    face = int(u0) if abs(u0) == 1 else None
    if face is not None and math.isfinite(est):
        # on the face the minimiser solves F'(s) = 0: Newton steps put it there to the precision's digits
        Fp, sp = face_polish(g, face, s0)
        if math.isfinite(Fp) and Fp <= est and (cap is None or not math.isfinite(cap) or Fp <= cap):
            est, s0 = Fp, float(sp)
    d = _Direct(est, u0, s0, amin)
    if not (math.isfinite(est) and est > 0 and amin > 0):
        return d
    whole = Box.of(DIRECT_DOMAIN)
    margins = ((FACE_MARGIN, FACE_DIGITS, min(max_pieces, FACE_BOXES)),) if face is not None else ()
    margins += tuple((m, 10, max_pieces) for m in DIRECT_MARGINS)
    for _ in range(DIRECT_RESEARCHES + 1):
        better = None
        for m, digits, boxes in margins:
            d.R_text = decimal_bounds(arb(d.est) * (1 - arb(m)), digits)[0]
            d.cert = certify_positive_on_box(symmetric_in_x2(g, face_margin(g, exact_ball(to_fmpq(Fraction(d.R_text))))),
                                             whole, max_pieces=boxes)
            if d.cert.status is Status.PROVED:
                break
            # below the loosest margin's radius: no margin can succeed, the search missed the minimiser
            better = _lower_ratio(g, d.cert, d.est * (1 - float(DIRECT_MARGINS[-1])))
            if better is not None:      # search again from there
                break
        if d.cert.status is Status.PROVED or better is None:
            break
        est, u0, s0, amin = direct_point_search(g, better[1:])
        d.est, d.u0, d.s0, d.amin = min(est, better[0]), u0, s0, min(amin, d.amin)
        if not (math.isfinite(d.est) and d.est > 0 and d.amin > 0):
            return d
    if d.cert.status is not Status.PROVED:
        return d
    # an upper bound of the supremum: a certified point of the region where Vdot > 0
    pi = arb.pi()
    x2p = exact_ball(to_fmpq(exact_fraction((xs * arb(u0)).mid())))
    x2p = x2p if certainly_le(abs(x2p), xs) else (xs.lower() if u0 > 0 else -xs.lower())
    for m, digits, _ in margins:
        rr = arb(est) * (1 + arb(m))
        t = pi * arb(s0)
        x1, x3 = (exact_ball(to_fmpq(exact_fraction((rr * t.cos()).mid()))), exact_ball(to_fmpq(exact_fraction((rr * t.sin()).mid()))))
        if certainly_le(abs(x2p), xs) and certainly_positive(g.vdot(x1, x2p, x3)):
            d.point = (x1, x2p, x3)
            d.up_text = decimal_bounds((x1 * x1 + x3 * x3).sqrt(), max(12, digits))[1]
            break
    return d


def vdot_direct_claim(ctx: ClaimContext, quantities: dict[str, arb]) -> Claim:
    g = ctx.g
    d = ctx.memo("direct at the scene's mu", lambda: certify_direct(g, ctx.m.max_pieces))
    est = d.est
    if not (math.isfinite(est) and est > 0 and d.amin > 0):
        claim = make_claim("vdot_direct", Status.INCONCLUSIVE,
                       f"the search found no positive radius (inf A/|B| ~ {est:.6g}, min A ~ {d.amin:.3g}): the direct "
                       "test gives nothing here (A <= 0 somewhere means Vdot > 0 arbitrarily near x1 = x3 = 0)")
        claim.precision_cannot_help = "the float search finds A <= 0: no radius to certify at any precision"
        return claim
    cert, R_text = d.cert, d.R_text
    if cert.status is not Status.PROVED:
        return make_claim("vdot_direct", Status.INCONCLUSIVE,
                          f"A - R |B| > 0 not certified at R = {R_text} (search estimate {est:.10g}): {cert.reason}; "
                          "try a larger max_pieces or --maxprec")
    R_direct = searched(Fraction(R_text))
    point = d.point
    ctx.witnesses["vdot_direct"] = {"R": R_text, "boxes": [b.to_json() for b in cert.leaves]}
    quantities["R_direct"] = R_direct
    if point is None:
        return make_claim("vdot_direct", Status.PROVED,
                      f"A - R |B| > 0 certified at R_direct = {R_text} on {len(cert.leaves)} boxes of (x2, t) (search "
                      f"estimate of the supremum {est:.10g}); no certified point above it was found, so no upper bound "
                      "of the supremum is stated", R_direct=R_text, boxes=len(cert.leaves))
    ctx.witnesses["vdot_direct"]["point"] = {"x1": ball_text(point[0]), "x2": ball_text(point[1]),
                                            "x3": ball_text(point[2])}
    up_text = d.up_text
    quantities["R_direct_upper"] = searched(Fraction(up_text))
    gap = relative_gap(Fraction(up_text), Fraction(R_text))
    quantities["R_direct_relative_gap"] = gap
    return make_claim("vdot_direct", Status.PROVED,
                  f"A - R |B| > 0 certified at R_direct = {R_text} on {len(cert.leaves)} boxes of (x2, t) (centered "
                  f"form; the search put the supremum at x2 = {float(d.u0):.6g} x2*, t = {float(d.s0):.6g} pi); Vdot = "
                  f"{fmt(g.vdot(*point), 4)} > 0 at the point x1 = {fmt(point[0], 8)}, x2 = {fmt(point[1], 8)}, "
                  f"x3 = {fmt(point[2], 8)} (radius <= {up_text}), so the supremum radius lies in [{R_text}, {up_text}] "
                  f"(relative gap {decimal_bounds(gap, 2)[1]})",
                  R_direct=R_text, R_direct_upper=up_text, boxes=len(cert.leaves))
