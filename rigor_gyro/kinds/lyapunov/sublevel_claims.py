"""The sublevel-set claims: ``invariant_estimate`` (c* on the boundary of region (17), the set {V < c_set} and
its extents), ``largest_sublevel`` (bounds of c_max without region (17)) and the opt-in ``natural_sublevel``.

Each bound is an Arb enclosure (branch and bound or closed form); a budget that runs out leaves a claim
inconclusive or a bound wider, never refuted. Precision: the attempt's (the x2 extent bisects with
EXTENT_EXTRA_BITS more)."""

from __future__ import annotations

from fractions import Fraction

from flint import arb

from ...core.balls import certainly_gt, certainly_lt, certainly_positive, decimal_bounds, working_precision
from ...core.outcome import Claim, Status
from ...core.stored import ball_text, pieces_text
from ...core.subdivision import certify_positive, enclose_max
from .sublevel import GAP as SUBLEVEL_GAP, largest_sublevel
from .natural_domain import NATURAL_GAP, natural_sublevel
from .polar_forms import slice_extent, slice_in_region
from .closed_forms import c_star_lower, c_star_upper, cylinder_lower_bound, faces_minimiser_inside
from .declarations import OPT_IN_CLAIMS
from .claim_context import ClaimContext, make_claim, to_fmpq, fmt, exact_ball

#: extra bits of the bisection for the x2 extent of the invariant estimate (see invariant_claim)
EXTENT_EXTRA_BITS = 16


# ------------------------------------------------------------------------------------ c_max

def largest_sublevel_claim(ctx: ClaimContext, quantities: dict[str, arb]) -> Claim:
    r = largest_sublevel(ctx.g, ctx.m.max_pieces)
    if r.refutation is not None:
        ref = r.refutation
        ce = ({"where": "faces", "phi": fmt(ref["phi"], 20)} if ref["where"] == "faces" else
              {"where": "origin", "x2": "0", "t_over_pi": str(ref["s"]), "A": fmt(ref["A"], 20)})
        tail = ("; so no sublevel set of V around the origin is an estimate" if ref["where"] == "origin" else
                "; so no sublevel set of V reaching the faces at this x2* is an estimate (a smaller x2* may still give one)")
        claim = make_claim("largest_sublevel", Status.REFUTED, r.reason + tail, ce)
        return claim
    if r.c_lower is None:
        if r.unbounded:
            # an enclosure unbounded below on the whole box budget: the boxes' width decides it, not the precision
            claim = make_claim("largest_sublevel", Status.INCONCLUSIVE,
                               r.reason + f": {r.unbounded}; more precision cannot bound it (try a smaller x2*)")
            claim.precision_cannot_help = f"the lower bound of V over {{Vdot >= 0}} is unbounded below: {r.unbounded}"
            return claim
        return make_claim("largest_sublevel", Status.INCONCLUSIVE, r.reason + "; try a larger max_pieces or --maxprec",
                          decides=r.bound)
    lo, hi = exact_ball(to_fmpq(Fraction(r.c_lower))), exact_ball(to_fmpq(Fraction(r.c_upper)))
    quantities["c_max_lower"], quantities["c_max_upper"] = lo, hi
    quantities["vdot_level_lower"] = exact_ball(to_fmpq(Fraction(r.n_lower)))
    if r.n_upper is not None:
        quantities["vdot_level_upper"] = exact_ball(to_fmpq(Fraction(r.n_upper)))
    quantities["face_level"] = r.face
    ctx.witnesses["largest_sublevel"] = {"boxes": [b.to_json() for b in r.leaves]}
    if r.point is not None:
        ctx.witnesses["largest_sublevel"]["point"] = {n: ball_text(x) for n, x in zip(("x1", "x2", "x3"), r.point)}
    aim = (f"aiming {r.gap} below the point's value" + (" (the faces bind by a factor > 2: the level of {Vdot >= 0} "
                                                       "only has to be shown above them)" if r.gap != SUBLEVEL_GAP else ""))
    vd = (f"over {{Vdot >= 0}}: V >= {r.n_lower} ({r.boxes} boxes of (x2, t), {aim})" + (f", and V = {fmt(ctx.g.V(*r.point), 10)} <= {r.n_upper} at the point x1 = {fmt(r.point[0], 8)}, "
                      f"x2 = {fmt(r.point[1], 8)}, x3 = {fmt(r.point[2], 8)} where Vdot = "
                      f"{fmt(ctx.g.vdot(*r.point), 4)} > 0" if r.point is not None else
                      " (no certified point where Vdot > 0 was found: no upper bound of that part)"))
    bind = {"faces": "the faces |x2| = x2* bind (c_max = min phi(+-x2*): the range of x2 where V > 0 is certified "
                     "limits the estimate, not the sign of Vdot)",
            "vdot": "the set {Vdot >= 0} binds (c_max is decided by the sign of Vdot, below the faces' level)",
            "undecided": "which part binds is not decided at this gap"}[r.binding]
    cmp = ""
    if "c_star" in quantities and quantities["c_star"].is_finite():
        cs = quantities["c_star"]
        if certainly_lt(cs.upper(), lo):
            cmp = (f"; c_max_lower exceeds c* = {fmt(cs, 10)} of invariant_estimate by a factor {fmt(lo / cs, 4)}: "
                   "a larger certified estimate than the region-bounded construction gives")
        elif cs.overlaps(lo.union(hi)):
            cmp = (f"; c* = {fmt(cs, 10)} of invariant_estimate agrees with c_max to the digits certified: the "
                   "region-bounded estimate is already the largest sublevel set of this V with |x2| <= x2*")
        else:
            cmp = f"; c* = {fmt(cs, 10)} of invariant_estimate"
    return make_claim("largest_sublevel", Status.PROVED,
                  f"c_max in [{r.c_lower}, {r.c_upper}]; faces: min phi(+-x2*) = {fmt(r.face, 12)}; {vd}; {bind}{cmp}",
                  c_max_lower=r.c_lower, c_max_upper=r.c_upper, vdot_level_lower=r.n_lower,
                  vdot_level_upper=r.n_upper, binds=r.binding, boxes=r.boxes)


# ------------------------------------------------------------------------------------ natural c_max

def _natural_claim(status: Status, reason: str, decides: arb | None = None, **details) -> Claim:
    return Claim("natural_sublevel", OPT_IN_CLAIMS["natural_sublevel"], status, reason, details=details,
                 counterexample=None, decides=decides)


def natural_sublevel_claim(ctx: ClaimContext, quantities: dict[str, arb]) -> Claim:
    gap = ctx.m.natural_gap or NATURAL_GAP
    r = natural_sublevel(ctx.g, ctx.m.max_pieces, gap)
    if r.c_lower is None:
        claim = _natural_claim(Status.INCONCLUSIVE, r.reason + "; try a larger max_pieces or --maxprec", decides=r.bound)
        if r.bound is None:
            claim.precision_cannot_help = r.reason
        return claim
    lo, hi = exact_ball(to_fmpq(Fraction(r.c_lower))), exact_ball(to_fmpq(Fraction(r.c_upper)))
    X = r.X
    quantities["natural_c_max_lower"], quantities["natural_c_max_upper"] = lo, hi
    # the certified level and reach the trajectory claims test against (trajectory_claims.initial_point_claim)
    ctx.natural = (lo, None if r.reach is None else to_fmpq(r.reach))
    quantities["natural_X"] = X.ball()
    ctx.witnesses["natural_sublevel"] = {
        "X": X.text, "band_lo": str(r.band_lo), "positivity": r.positivity, "band": r.band,
        "boxes": [b.to_json() for b in r.leaves],
        "point": {n: ball_text(x) for n, x in zip(("x1", "x2", "x3"), r.point)}}
    extent = ""
    if r.reach is not None:
        quantities["natural_extent_x2"] = exact_ball(to_fmpq(r.reach)).union(exact_ball(to_fmpq(r.band_lo)))
        ctx.witnesses["natural_sublevel"].update({"reach": str(r.reach), "reach_pieces": r.reach_pieces})
        extent = (f"; the component of {{V < natural_c_max_lower}} around 0 reaches |x2| = {r.reach} = "
                  f"{float(r.reach):.6f} (phi < natural_c_max_lower on [0, {r.reach}], {len(r.reach_pieces)} pieces) "
                  f"and stays in |x2| < {float(r.band_lo):.6f}: its x2 extent is in natural_extent_x2")
    rel = (hi - lo) / lo
    g = ctx.g
    pt = r.point
    cmp = []
    if "c_star" in quantities and quantities["c_star"].is_finite():
        cs = quantities["c_star"]
        cmp.append(f"c* = {fmt(cs, 10)} of invariant_estimate: the natural level is larger, natural_c_max_lower / c* = "
                   f"{fmt(lo / cs, 6)}, natural_c_max_lower - c* = {fmt(lo - cs, 8)}")
    if "c_max_lower" in quantities:
        cl, cu = quantities["c_max_lower"], quantities["c_max_upper"]
        cmp.append(f"c_max(x2*) in [{fmt(cl, 10)}, {fmt(cu, 10)}] of largest_sublevel (natural_c_max_lower / "
                   f"c_max_upper(x2*) = {fmt(lo / cu, 6)})")
    if "R_used" in quantities:
        printed = ctx.m.paper.get("R")
        cmp.append(f"region (17) of invariant_estimate has |x2| <= x2* = {fmt(ctx.xs, 8)} and radius R = "
                   f"{fmt(quantities['R_used'], 6)}" + (f" (printed R = {printed})" if printed else ""))
    larger = ("; compared: " + "; ".join(cmp)) if cmp else ""
    if r.limit is None:
        why = ("X cannot reach pi/2: there h = H cos x2 / B0 = 0, V does not depend on x1, and (-f(pi/2)/k, pi/2, 0) "
               "is an equilibrium")
    else:
        why = (f"X cannot reach x2 = {fmt(r.limit[0], 10)}: {r.limit[1]} <= 0 there (certified), so the test of "
               "v_positive fails")
    reached = "reached" if r.gap_reached else "not reached (box budget): the bracket is wider"
    return _natural_claim(
        Status.PROVED,
        f"V > 0 off the origin for |x2| <= X = {X.text} = {fmt(X.ball(), 12)} (S, f/x, psi > 0 on "
        f"{sum(len(v) for v in r.positivity.values())} pieces; {why}); c_max(X) in "
        f"[{r.c_lower}, {r.c_upper}] (relative gap {fmt(rel, 3)}; {r.boxes} boxes of (x2, t) over |x2| <= X_c, "
        f"aiming {gap}: {reached}), the upper end V = {fmt(g.V(*pt), 12)} at the point x1 = {fmt(pt[0], 8)}, "
        f"x2 = {fmt(pt[1], 8)}, x3 = {fmt(pt[2], 8)} where Vdot = {fmt(g.vdot(*pt), 4)} > 0; phi > "
        f"{r.c_upper} on X_c = {r.band_lo} <= |x2| <= X ({len(r.band)} pieces): the faces do not bind and the set "
        f"lies in |x2| < X_c = {float(r.band_lo):.6f}" + extent + larger,
        c_max_lower=r.c_lower, c_max_upper=r.c_upper, X=X.text, band_lo=str(r.band_lo), boxes=r.boxes,
        gap=gap, gap_reached=r.gap_reached, reach=None if r.reach is None else str(r.reach))



# ------------------------------------------------------------------------------------ c*

def invariant_claim(ctx: ClaimContext, R: arb, quantities: dict[str, arb]) -> Claim:
    g, xs = ctx.g, ctx.xs
    face = g.phi(xs)
    inside = faces_minimiser_inside(g, xs, R)
    # V(-x) = V(x), so the cylinder over [0, x2*] with every theta covers |x2| <= x2*
    # the tolerance is relative to the minimum being certified (a tiny positive c* must come out positive),
    # with an absolute floor at the precision's resolution of V's scale
    cyl = enclose_max(lambda x: -cylinder_lower_bound(g, R)(x), 0, xs, rel_tol=arb("1e-6"),
                      abs_tol=(abs(face) + R * R) * arb(2) ** (-ctx.prec // 2), max_pieces=ctx.m.max_pieces)
    cyl_lb = (-cyl.ball).lower()
    ctx.witnesses["invariant_estimate"] = {"cylinder": pieces_text(cyl.cover)}
    # an upper bound of the boundary minimum: V at points of the cylinder (and the faces' value when inside);
    # with the minimiser outside, the face minimum is on its rim, which belongs to the cylinder
    upper = c_star_upper(g, R, xs, face, inside)
    lower = c_star_lower(face, cyl_lb, inside)
    if inside and certainly_lt(face.upper(), cyl_lb):
        cstar, where = face, "attained on the faces |x2| = x2* (minimiser inside the disc), closed form"
    else:
        cstar = lower.union(upper)
        where = "lower bound from the cylinder's certified bound" + (" and the faces' closed form" if inside else "")
    quantities["c_star"] = cstar
    quantities["c_star_face"] = face
    if certainly_positive(cstar):
        # c* against the region's side: V >= cyl_lb on the cylinder x1^2 + x3^2 = R^2, so V >= (1 + margin) c*
        # there (0 or below when the cylinder binds; a certified lower bound, not the exact ratio), rounded
        # down to 10 digits (an exact decimal: a checker's own bound, at its precision, stays above it)
        margin_text = decimal_bounds((cyl_lb / cstar.upper() - 1).lower(), 10)[0]
        quantities["cylinder_margin_lower"] = exact_ball(to_fmpq(Fraction(margin_text)))
    if not certainly_positive(cstar):
        return make_claim("invariant_estimate", Status.INCONCLUSIVE,
                          f"c* = {fmt(cstar)} is not certainly positive (cylinder bound on {cyl.pieces} pieces); "
                          "try a larger max_pieces or higher --maxprec (a smaller R makes c* smaller too)",
                          decides=cstar, pieces=cyl.pieces)
    # the set is {V < c_set}, c_set = c*'s certified lower end, less a margin of 4 relative widths of R
    # (c* moves like R^2: a checker with its own enclosure of R must still find c_set below its bound),
    # rounded down to 10 digits (exact)
    margin = 4 * R.rad() / R.abs_lower() + arb(2) ** -40
    c_text = decimal_bounds((cstar.lower() * (1 - margin)).lower(), 10)[0]
    cl = exact_ball(to_fmpq(Fraction(c_text)))
    quantities["c_set"] = cl
    # inner extents: the set contains these segments of the axes
    hx = g.c.H / g.c.B0
    ext = {"x1_axis": ((2 * cl).sqrt() / hx).min(R),
           "x3_axis": ((2 * cl) / (g.f2(arb(0)) + g.c.mu * g.f1(arb(0)))).sqrt().min(R)}
    # along x2: the root of mu F(x2) = c_set (F increasing), enclosed by bisection
    lo, hi = arb(0), xs
    if certainly_lt(g.c.mu * g.F(xs), cl):
        ext["x2_axis"] = xs
    else:   # bisection to the precision's resolution (it stops earlier where balls cannot decide)
        for _ in range(ctx.prec + 8):
            mid = ((lo + hi) / 2).mid()
            val = g.c.mu * g.F(mid)
            if certainly_lt(val, cl):
                lo = mid
            elif certainly_gt(val, cl):
                hi = mid
            else:
                break
        ext["x2_axis"] = lo.union(hi)
    # the extents: enclosures of max |x1|, |x2|, |x3| over the set, from its x2 slices (ellipses, see
    # model.slice_extent); to the scene's rel_width (or the precision's resolution)
    tight = {}
    for axis in ("x1", "x3"):
        fn = slice_extent(g, cl, axis)
        # to the scene's rel_width on at most 2000 pieces (a valid enclosure, only wider, if the budget runs
        # out: the slice's half-width grows like sqrt(c - phi) where the slices vanish)
        e = enclose_max(fn, 0, xs, abs_tol=ctx.tol(R), max_pieces=min(ctx.m.max_pieces, 2000))
        p = e.argpoint
        # the lower end is a slice's exact maximum only where that slice certainly belongs to the set
        low = fn(p).lower() if slice_in_region(g, cl, R, p) else ext[f"{axis}_axis"].lower()
        up = e.ball.upper().min(R.upper())
        tight[axis] = low.union(up)
        ctx.witnesses["invariant_estimate"][f"extent_{axis}"] = {"cover": pieces_text(e.cover), "point": ball_text(p)}
    # along x2: the last x2 where the slice is non-empty, c_set = phi(x2), by bisection (phi(x2*) >= c* > c_set),
    # with phi > c_set certified on [hi, x2*] (then no slice beyond hi)
    # (EXTENT_EXTRA_BITS above the working precision: phi = mu F - f3^2/(2S) cancels near 0, and at the working
    # precision alone the bisection stopped 7-11 bits short of it)
    lo, hi = arb(0), xs
    with working_precision(ctx.prec + EXTENT_EXTRA_BITS):
        for _ in range(ctx.prec + EXTENT_EXTRA_BITS + 8):
            mid = ((lo + hi) / 2).mid()
            d = cl - g.phi(mid)
            if certainly_positive(d):
                lo = mid
            elif certainly_lt(d, 0):
                hi = mid
            else:
                break
        beyond: list = []
        r = certify_positive(lambda x: g.phi(x) - cl, hi, xs, max_pieces=ctx.m.max_pieces, record=beyond)
        x2_lo = lo if slice_in_region(g, cl, R, lo) else ext["x2_axis"].lower()
    x2_up = hi if r.status is Status.PROVED else xs
    tight["x2"] = x2_lo.union(x2_up.upper())
    ctx.witnesses["invariant_estimate"]["extent_x2"] = {"point": ball_text(lo), "beyond": pieces_text(beyond)
                                                        if r.status is Status.PROVED else []}
    for k, v in ext.items():
        quantities[f"extent_{k}"] = v
    for k, v in tight.items():
        quantities[f"extent_{k}"] = v
    return make_claim("invariant_estimate", Status.PROVED,
                  f"c* = {fmt(cstar)} ({where}; cylinder x1^2 + x3^2 = R^2: V >= {fmt(cyl_lb, 8)} on {cyl.pieces} "
                  "x2 pieces). "
                  f"The set {{V < c_set = {c_text}}} within (17) contains the axis segments "
                  f"|x1| < {fmt(ext['x1_axis'], 6)}, |x2| < {fmt(ext['x2_axis'], 6)}, |x3| < {fmt(ext['x3_axis'], 6)}; "
                  f"its extents (the maxima of |x1|, |x2|, |x3| over it, enclosed from its x2 slices, which are ellipses) "
                  f"are {fmt(tight['x1'], 6)}, {fmt(tight['x2'], 6)}, {fmt(tight['x3'], 6)}",
                  c_set=c_text,
                  pieces=cyl.pieces)
