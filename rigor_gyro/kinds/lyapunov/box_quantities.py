"""The Lyapunov kind's quantities over a parameter box (issue 37 part 2; the interface of
:mod:`rigor_gyro.core.box_values`).

Quantities, named as the point certificate names them (:mod:`.claims`):

* ``A0``, ``B0``, ``C0``: the sums of the raw inertias, exactly (their ends are the boxes' corner sums);
* ``mu_max`` = k/A0 (the upper end of (16)), exact at the corners, with its gradient;
* ``k_min`` = p A0/H and ``mu_min`` = p/H, p = max(M, A0 m / cos^2 x2*) = max(M, w / cos^2 x2*) with w = A0 m:
  monotone in A0, H and in the maxima M and w, whose enclosures over the box bound them (no gradient: M and w
  are maxima);
* ``R1`` (13), ``R2`` (14), ``R`` = min(R1, R2): the region's radius, by monotonicity at faces and centred forms
  (:func:`.box_vdot.radius_bounds`); given only where k/A0 - mu > 0 and mu H cos^2 x2* - A0 m > 0 are certified
  over the box (the closed forms' signs); R1's gradient (it does not involve m);
* ``damping_margin`` (margin of ``damping_condition``): min(k/k_min, k/(mu A0)) - 1 = min(k H/(A0 M),
  k H cos^2 x2*/(A0 w), k/(mu A0)) - 1, each term monotone (increasing in k, H; decreasing in A0, mu, M, w):
  its range from the box's exact corners and the enclosures of M and w. > 0 implies k > k_min and mu < k/A0
  (the third condition of the claim, mu > p/H, is not in this margin, as at a point); its gradient where
  k/(mu A0) certainly binds;
* ``psi_margin`` (margin of ``psi_test``, which proves ``vdot_nonpositive``): R_sup/R - 1, R_sup = min over
  |x2| <= x2* and i of ci0 / |(ci1, ci3)|, the largest radius at which the Psi test holds. Its lower end over
  the box is the largest t of a short bisection with ci0 - (1 + t) R |(ci1, ci3)| > 0 certified over the box
  (:class:`.box_forms.CentredBox`); its upper end, the ratio at the x2 where that bound binds, bounded above
  over the box.

Guarantee: each value ball contains the quantity for every parameter value in the box; each gradient ball
the partial derivative for every parameter value in the box. A quantity is left out where it is not enclosed
(the closed forms' signs not certified, a maximum not finite). A box of points gives the point's values,
as narrow as the precision allows (psi_margin's lower end to the bisection's resolution, ``PSI_STEPS``).
Precision: the current working precision. Fails when: never raises for a box it cannot enclose.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_lt, certainly_positive, current_precision
from ...core.box_values import BoxValue, QuantitySpec
from ...core.boxes import Box
from ...core.subdivision import certify_positive
from .box_levels import c_star_box, v_positive_margin_box
from .box_forms import CentredBox, balls_of, radius_formula, w_enclosure
from .box_vdot import radius_bounds
from .boxes import boxed_model, raw_intervals
from .claims import maximum_M
from .polar_forms import law_is_odd
from .vdot_tests import rational_points_inside

__all__ = ["BOX_QUANTITIES", "quantities_box", "PSI_STEPS"]

BOX_QUANTITIES = {
    "A0": QuantitySpec("A0 = A + A1 + A2"),
    "B0": QuantitySpec("B0 = A + B1"),
    "C0": QuantitySpec("C0 = A + A1 - C1"),
    "k_min": QuantitySpec("k_min = p A0/H of (18)"),
    "mu_min": QuantitySpec("lower end p/H of the mu interval (16)"),
    "mu_max": QuantitySpec("upper end k/A0 of the mu interval (16)"),
    "R1": QuantitySpec("R1 of (13)"),
    "R2": QuantitySpec("R2 of (14)"),
    "R": QuantitySpec("radius R = min(R1, R2) of region (17)"),
    "damping_margin": QuantitySpec("design margin in k: min(k/k_min, k/(mu A0)) - 1", claim="damping_condition"),
    "psi_margin": QuantitySpec("Psi test margin R_sup/R - 1 (R_sup: the largest disc radius with Psi1, Psi2 > 0; "
                               "> 0 proves vdot_nonpositive on region (17))", claim="psi_test"),
    "c_star": QuantitySpec("level c* = min of V over the boundary of region (17) (the invariant estimate {V < c*})"),
    "v_positive_margin": QuantitySpec("V > 0 margin: min over |x2| <= x2* of min(1 - mu/f1, psi/P) (P the positive "
                                      "part of psi; > 0 with f(x)/x > 0 gives V > 0 off the origin)",
                                      claim="v_positive"),
}

#: bisection steps of psi_margin's lower bound (resolution 2^-PSI_STEPS of the bracket [-1, PSI_TOP], or of [t, 2t] when the top
#: PSI_TOP holds and is doubled to the first t that fails)
PSI_STEPS = 6
PSI_TOP = 3
#: the largest top the bracket doubles to (R_sup/R - 1 above it is not bounded)
PSI_CAP = 3 * 2 ** 8
#: exact x2 points of the loose upper bound of psi_margin (:func:`_psi_upper_loose`)
PSI_PROBES = 16
#: x2 pieces per certification of the psi margin's bisection
PSI_PIECES = 32


def _q(x: Fraction) -> arb:
    return arb(fmpq(x.numerator, x.denominator))


def _hull(lo: arb, hi: arb) -> arb:
    return arb(lo.lower()).union(arb(hi.upper()))


def _maxima(model, raw) -> tuple[arb, arb] | None:
    """(M, w) enclosures over the box: M = max q over [0, x2*] (the claims' own branch and bound on the box's
    balls, shared across boxes), w = A0 m (:func:`.box_forms.w_enclosure`)."""
    M = maximum_M(boxed_model(model, raw), current_precision()).ball
    W = w_enclosure(model.gimbal, balls_of(raw))
    if not (M.is_finite() and W.is_finite()):
        return None
    return M, W


def _damping(raw, M: arb, W: arb, cs2: arb) -> BoxValue:
    """min(kH/(A0 M), kH cs2/(A0 w), k/(mu A0)) - 1 over the box (module docstring)."""
    q = {k: (_q(Fraction(lo)), _q(Fraction(hi))) for k, (lo, hi) in raw.items()}
    A0lo = q["A"][0] + q["A1"][0] + q["A2"][0]
    A0hi = q["A"][1] + q["A1"][1] + q["A2"][1]
    (klo, khi), (Hlo, Hhi), (mlo, mhi) = q["k"], q["H"], q["mu"]
    terms_lo = [klo * Hlo / (A0hi * arb(M.upper())), klo * Hlo * cs2 / (A0hi * arb(W.upper())), klo / (mhi * A0hi)]
    terms_hi = [khi * Hhi / (A0lo * arb(M.lower())), khi * Hhi * cs2 / (A0lo * arb(W.lower())), khi / (mlo * A0lo)]
    lo = terms_lo[0].min(terms_lo[1]).min(terms_lo[2]) - 1
    hi = terms_hi[0].min(terms_hi[1]).min(terms_hi[2]) - 1
    grad = {}
    # k/(mu A0) binds on the whole box when its largest value is below both others' smallest
    if certainly_lt(terms_hi[2], terms_lo[0]) and certainly_lt(terms_hi[2], terms_lo[1]):
        b = balls_of(raw)
        A0 = b["A"] + b["A1"] + b["A2"]
        dA0 = -b["k"] / (b["mu"] * A0 * A0)
        grad = {"k": 1 / (b["mu"] * A0), "mu": -b["k"] / (b["mu"] * b["mu"] * A0), "A": dA0, "A1": dA0, "A2": dA0}
    return BoxValue(_hull(lo, hi), grad)


def _psi_margin(model, cb: CentredBox, rb: dict) -> arb | None:
    """A ball containing R_sup(P)/R(P) - 1 for every P in the box (module docstring), or None. R(P) <= R_j(P) for
    both j, so ci0 - (1 + t) R_j |(ci1, ci3)| > 0 over the box (j the one with the smaller upper end) gives the
    margin >= t; R_sup/R - 1 = max_j R_sup/R_j - 1, bounded above by the larger of the two upper bounds."""
    g = model.gimbal
    xs = cb.xs
    lo_x = arb(0) if law_is_odd(g.law) else -xs
    which = "R2" if rb["R2"][1].upper() < rb["R1"][1].upper() else "R1"

    def holds(t: Fraction) -> bool:
        scale = _q(1 + t)
        for i in (0, 1):
            fn = cb.lower(_scaled(which, i, scale))
            if certify_positive(fn, lo_x, xs, max_pieces=PSI_PIECES).status.value != "proved":
                return False
        return True
    a, b = Fraction(-1), Fraction(PSI_TOP)
    if not holds(a + Fraction(1, 2 ** PSI_STEPS)):
        return None
    a = a + Fraction(1, 2 ** PSI_STEPS)
    while holds(b):            # the bracket's top holds: double it (a box with a small R somewhere)
        if b >= PSI_CAP:
            return None        # above the largest bracket: no upper bound stated
        a, b = b, 2 * b
    for _ in range(PSI_STEPS):
        m = (a + b) / 2
        if holds(m):
            a = m
        else:
            b = m
    # upper end: at the x2 where ci0 - (1 + b) R |.| > 0 fails, an upper bound over the box of each ratio
    ups = [_psi_upper(model, cb, j, b, lo_x, which) for j in ("R1", "R2")]
    if any(u is None for u in ups):
        loose = _psi_upper_loose(cb, rb, lo_x)
        if loose is None:
            return None
        return _q(a).union(loose)
    return _q(a).union(ups[0].max(ups[1]))


def _psi_upper_loose(cb: CentredBox, rb: dict, lo_x: arb) -> arb | None:
    """An upper bound over the box of R_sup/R - 1 that needs no formula of R: R_sup(P) <= ci0/|(ci1, ci3)| at any
    fixed x2 (R_sup is the minimum over x2 and i), bounded above over the box by the naive enclosure on its
    balls at PSI_PROBES exact points of the x2 range; R(P) = min(R1, R2) >= the smaller of their lower bounds
    over the box (``rb``). Used where the coupled bound of :func:`_psi_upper` is not finite (a wide box over
    which R's formula reaches 0). None when neither is finite or R's lower bound is not positive."""
    r_lo = arb(rb["R1"][0].lower()).min(arb(rb["R2"][0].lower()))
    if not certainly_positive(r_lo):
        return None
    gm = cb._gimbal({n: cb.WHOLE for n in cb.raw})
    best = None
    for j in range(PSI_PROBES):     # lo_x, then exact points strictly inside the range (never past x2*)
        x = arb((lo_x + (cb.xs - lo_x) * j / PSI_PROBES).mid()) if j else lo_x
        for c0, c1, c3 in gm.psi_coefficients(x):
            n = c1 * c1 + c3 * c3
            if not certainly_positive(n):
                continue
            u = (c0 / n.sqrt()).upper()
            if arb(u).is_finite():
                best = u if best is None else best.min(u)
    if best is None:
        return None
    return arb((arb(best) / r_lo - 1).upper())


def _scaled(which: str, i: int, scale: arb):
    """ci0 - scale R |(ci1, ci3)| in the form of :func:`.box_forms.psi_disc_margin`."""
    from .box_forms import hypot_ball
    from .model import Dual

    def h(gm, w, X, dual):
        c0, c1, c3 = gm.psi_coefficients(X)[i]
        R = scale * radius_formula(gm.c, w, which)
        if not dual:
            return c0 - R * hypot_ball(c1, c3)
        n = c1 * c1 + c3 * c3
        if type(n) is Dual and not certainly_positive(n.v):
            return None
        if type(n) is not Dual:
            return c0 - R * hypot_ball(c1, c3)
        return c0 - R * n.sqrt()
    return h


def _psi_upper(model, cb: CentredBox, which: str, t: Fraction, lo_x: arb, found: str) -> arb | None:
    """An upper bound over the box of min over x2, i of ci0/(R_which |(ci1, ci3)|) - 1: at the exact x2 points
    where ci0 - (1 + t) R_found |.| > 0 was refuted or not decided (only where to look), the smallest upper
    bound over the box of the ratio there (each is >= the minimum over x2, for every P); None if none."""
    best = None
    for i in (0, 1):
        r = certify_positive(cb.lower(_scaled(found, i, _q(1 + t))), lo_x, cb.xs, max_pieces=PSI_PIECES)
        # exact points: the refutation's witness, or rational points just inside when it is the end ball x2*
        pts = rational_points_inside(r.witness, cb.xs)[:1] if r.witness is not None else []
        if r.stuck is not None:
            a, b = r.stuck
            pts.append(((a + b) / 2).mid())
        for x in pts:
            if not x.rad().is_zero():
                continue
            ratio = cb.lower(lambda gm, w, X, d, i=i: _neg_ratio(gm, w, X, d, i, which))(x)
            if not ratio.is_finite():
                continue
            u = -ratio.lower() - 1
            best = u if best is None else best.min(u)
    return None if best is None else arb(best.upper())


def _neg_ratio(gm, w, X, dual, i, which):
    """-ci0 / (R |(ci1, ci3)|) (its lower bound over the box bounds the ratio above)."""
    from .model import Dual
    c0, c1, c3 = gm.psi_coefficients(X)[i]
    n = c1 * c1 + c3 * c3
    R = radius_formula(gm.c, w, which)
    if type(n) is Dual:
        if not certainly_positive(n.v):
            return None
        return -c0 / (R * n.sqrt())
    if not certainly_positive(n):
        return arb("nan")
    return -c0 / (R * n.sqrt())


def quantities_box(model, box: Box, names) -> dict[str, BoxValue]:
    """{quantity: BoxValue} for the requested names it can enclose on the box (module docstring)."""
    names = [k for k in names if k in BOX_QUANTITIES]
    if not names:
        return {}
    raw = raw_intervals(model, box)
    b = balls_of(raw)
    out: dict[str, BoxValue] = {}
    q = {k: (_q(Fraction(lo)), _q(Fraction(hi))) for k, (lo, hi) in raw.items()}
    sums = {"A0": ("A", "A1", "A2"), "B0": ("A", "B1")}
    for name, parts in sums.items():
        lo = sum((q[p][0] for p in parts), arb(0))
        hi = sum((q[p][1] for p in parts), arb(0))
        out[name] = BoxValue(_hull(lo, hi), {p: arb(1) for p in parts})
    out["C0"] = BoxValue(_hull(q["A"][0] + q["A1"][0] - q["C1"][1], q["A"][1] + q["A1"][1] - q["C1"][0]),
                         {"A": arb(1), "A1": arb(1), "C1": arb(-1)})
    A0 = b["A"] + b["A1"] + b["A2"]
    out["mu_max"] = BoxValue(_hull(q["k"][0] / (out["A0"].value.upper()), q["k"][1] / out["A0"].value.lower()),
                             {"k": 1 / A0, **{p: -b["k"] / (A0 * A0) for p in ("A", "A1", "A2")}})
    want = set(names)
    if want & {"k_min", "mu_min", "damping_margin", "R", "R1", "R2", "psi_margin"} or ("c_star" in want and model.R_option is None):
        mw = _maxima(model, raw)
        if mw is not None:
            M, W = mw
            cs2 = model.gimbal.x2_star.ball().cos() ** 2
            A0v = out["A0"].value
            # p = max(M, A0 m / cos^2 x2*) = max(M, w / cos^2 x2*): increasing in M and w
            plo = arb(M.lower()).max(arb(W.lower()) / cs2)
            phi = arb(M.upper()).max(arb(W.upper()) / cs2)
            out["mu_min"] = BoxValue(_hull(plo / q["H"][1], phi / q["H"][0]))
            out["k_min"] = BoxValue(_hull(plo * arb(A0v.lower()) / q["H"][1], phi * arb(A0v.upper()) / q["H"][0]))
            out["damping_margin"] = _damping(raw, M, W, cs2)
            if want & {"R", "R1", "R2", "psi_margin", "c_star"}:
                cb = CentredBox(model.gimbal, raw, W)
                rb = {j: radius_bounds(cb, j) for j in ("R1", "R2")}
                if all(certainly_positive(lo.lower()) and hi.is_finite() for lo, hi in rb.values()):
                    for j, (lo, hi) in rb.items():
                        out[j] = BoxValue(_hull(lo, hi))
                    (l1, h1), (l2, h2) = rb["R1"], rb["R2"]
                    out["R"] = BoxValue(_hull(arb(l1.lower()).min(arb(l2.lower())), arb(h1.upper()).min(arb(h2.upper()))))
                    # R1 does not involve m: its gradient by forward mode over the box
                    grads = {}
                    for k in cb.varying:
                        gm = cb._gimbal({n: cb.WHOLE for n in cb.raw}, k)
                        d = radius_formula(gm.c, W, "R1")
                        grads[k] = d.d if hasattr(d, "d") else arb(0)
                    if all(v.is_finite() for v in grads.values()):
                        out["R1"] = BoxValue(out["R1"].value, grads)
                    if "psi_margin" in want:
                        v = _psi_margin(model, cb, rb)
                        if v is not None:
                            out["psi_margin"] = BoxValue(v)
    if want & {"c_star", "v_positive_margin"}:
        g = boxed_model(model, raw).gimbal
        if "v_positive_margin" in want:
            v = v_positive_margin_box(g)
            if v is not None:
                out["v_positive_margin"] = BoxValue(v)
        R = arb(model.R_option) if model.R_option is not None else (out["R"].value if "R" in out else None)
        if "c_star" in want and R is not None:
            v = c_star_box(g, R)
            if v is not None:
                out["c_star"] = BoxValue(v)
    varying = {k for k, lo, hi in box.edges if lo != hi}
    return {k: BoxValue(v.value, {p: d for p, d in v.gradient.items() if p in varying})
            for k, v in out.items() if k in want and v.value.is_finite()}
