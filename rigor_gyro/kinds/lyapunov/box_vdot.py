"""``vdot_nonpositive`` over a box of parameters by the Psi test, each parameter's own R coupled to its Psi.

For every parameter value P in the box, region (17) has the radius R(P) = min(R1(P), R2(P)) <= R_j(P) for the
chosen j (the smaller at the box's midpoint), and the minimum over the disc of radius r of Psi_i,
ci0 - r |(ci1, ci3)|, decreases in r. So if

    h_i(x2, P) = ci0(x2, P) - R_j(P) |(ci1, ci3)(x2, P)| > 0   for every x2 in [0, x2*], P in the box, i = 1, 2

then Psi1, Psi2 > 0 on each parameter's own region (17) and Vdot = -Psi1 x1^2 - Psi2 x3^2 <= 0 there. R_j(P) is
the closed form of :func:`.box_forms.radius_formula` in P and w = A0 m(P) (w in its enclosure W over the box),
which equals sqrt(D1/D2) (sqrt(E1/E2)) where k/A0 - mu > 0 (mu H cos^2 x2* - A0 m > 0): both certified first,
as R1, R2 > 0 on the box (then R(P) > 0 for every P, as the point claim requires). h_i is bounded below on
x2 pieces by monotonicity at faces and centred forms (:class:`.box_forms.CentredBox`); x2 runs over [0, x2*]
only for an odd law (h_i is even in x2 then: c10, c20 even, c11, c13, c21, c23 odd; see
:func:`.model.symmetric_in_x2`), over [-x2*, x2*] otherwise.

Guarantee: PROVED only as above; otherwise None (the caller falls back to the claims' own box evaluation,
which can also refute). Precision: the caller's. Budget: ``max_pieces`` (at most MAX_PIECES) x2 pieces per Psi_i.
"""
from __future__ import annotations

from flint import arb

from ...core.balls import certainly_positive, decimal_bounds
from ...core.subdivision import certify_positive
from .box_forms import CentredBox, balls_of, psi_disc_margin, radius_formula, w_enclosure
from .polar_forms import law_is_odd

__all__ = ["decide_vdot_box", "radius_bounds", "MAX_PIECES"]

#: x2 pieces per Psi_i: a box this test proves at all needs a few dozen (15 + 9 on the +-2.5 % sub-box of
#: the example where the margin is smallest); past that the paving's split is cheaper than more pieces
MAX_PIECES = 64


def _fmt(x: arb, digits: int = 6) -> str:
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def radius_bounds(cb: CentredBox, which: str) -> tuple[arb, arb]:
    """(a lower bound, an upper bound) of R_which(P) = radius_formula over the box (P and w in W), each as a
    ball whose relevant end is the bound."""
    lo = cb.lower(lambda gm, w, X, d: radius_formula(gm.c, w, which), positivity=False)(arb(0))
    hi = -cb.lower(lambda gm, w, X, d: -radius_formula(gm.c, w, which), positivity=False)(arb(0))
    return lo, hi


def decide_vdot_box(model, raw: dict[str, tuple], max_pieces: int) -> tuple[str, str] | None:
    """("proved", reason) when the coupled Psi test proves vdot_nonpositive on the whole box (module docstring);
    None when it does not decide (nothing is claimed then)."""
    if model.R_option is not None:
        return None          # a fixed R: the claims' own evaluation over the box is already exact in R
    g = model.gimbal
    W = w_enclosure(g, balls_of(raw))
    if not W.is_finite():
        return None
    cb = CentredBox(g, raw, W)
    bounds = {j: radius_bounds(cb, j) for j in ("R1", "R2")}
    if not all(certainly_positive(lo.lower()) for lo, _ in bounds.values()):
        return None          # R1 or R2 not certainly > 0 on the box (nor their closed forms certainly valid)
    # the smaller radius at the midpoint binds; either is a valid upper bound of R(P)
    j = "R2" if bounds["R2"][1].upper() < bounds["R1"][1].upper() else "R1"
    xs = cb.xs
    lo_x = arb(0) if law_is_odd(g.law) else -xs
    pieces = []
    for i in (0, 1):
        r = certify_positive(cb.lower(psi_disc_margin(j, i)), lo_x, xs, max_pieces=min(max_pieces, MAX_PIECES))
        if r.status.value != "proved":
            return None
        pieces.append(r.pieces)
    fixed = ", ".join(sorted(cb.fixed_counts)) or "none"
    where = "[0, x2*] (even in x2: odd law)" if law_is_odd(g.law) else "[-x2*, x2*]"
    return ("proved",
            f"for every parameter in the box, each with its own R = min(R1, R2) <= {j}: {j} in "
            f"[{_fmt(bounds[j][0].lower())}, {_fmt(bounds[j][1].upper())}] (w = A0 m in {_fmt(W)}); min over the disc "
            f"of radius {j} of Psi1 and of Psi2 certified > 0 on {pieces[0]} + {pieces[1]} x2 pieces of {where}, each "
            f"bounded below over the box at the faces where it is certified monotone (parameters fixed at a face: "
            f"{fixed}) and by a centred form in the rest (the Psi test, each parameter's R coupled to its Psi)")
