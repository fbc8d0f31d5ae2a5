"""Independent re-check of a Lyapunov certificate (``rigor-gyro check``).

The prover runs branch-and-bound searches (maxima m and M, the cylinder bound of c*, the radius over
mu) and bisections (Psi > 0, S, f/x, psi > 0). This checker does not search: it re-evaluates the
model's enclosures on the stored pieces only, at twice the certificate's precision (for the extents also
at the certificate's own, keeping the tighter enclosure of each piece: interval widths are not monotone
in the precision), and checks

* that the stored pieces cover their range (exact endpoints; overlaps allowed, gaps not);
* m, M: the largest upper bound over the stored cover, and the value at the stored point, give the
  checker's own enclosure of each maximum; every closed form after them (p, k_min, (16), R1, R2, R)
  is recomputed from those;
* Psi1, Psi2 > 0 over the disc on every stored piece (Vdot <= 0 on (17)); S, f/x, psi > 0 (V > 0);
* the direct test: the stored (x2, t) boxes are the leaves of a bisection tree of the domain, A - R|B| > 0
  on each at the stored R_direct, and Vdot > 0 at the stored point (|x2| <= x2*) whose radius bounds
  R_direct_upper;
  c* from the faces' closed form and the cylinder bound on the stored cover, the level c_set below it,
  the extents; at mu_best, Psi > 0 on the disc of radius R_max, R_sup(mu_best) on its cover, and the
  upper bound of R_sup over (16) re-derived from the stored mu pieces and x2 points; at mu_direct, the
  direct test's boxes at R_direct_max, and its bound over (16) re-derived from the stored mu pieces and
  (x2, t) points;
* c_max (the largest sublevel set): the stored (x2, t) boxes tile the domain and the model's lower bound
  of V over {Vdot >= 0} is >= the stated vdot_level_lower on each; the faces' phi(+-x2*) recomputed; Vdot > 0
  and V at the stored point re-evaluated; every stated bound compared with its exact decimal;
* the natural c_max (opt-in claim): X read exactly from its text and inside (0, pi/2); S, f/x, psi > 0 on
  stored pieces covering [0, X]; phi > c_max_upper on stored pieces covering [X_c, X]; the stored (x2, t) boxes
  over |x2| <= X_c tile the domain with the natural lower bound >= c_max_lower on each; Vdot > 0 and
  V <= c_max_upper at the stored point; phi < c_max_lower on stored pieces covering [0, reach] (the extent);
* the equilibria: the stored isolation pieces of f and of k H + C0 sin x2 f(x2) are contiguous, cover
  [-pi, pi] and are each decided (Newton); the equilibria are re-derived from them, each at its stated
  point (x2 by its exact text or its decimal interval, x1 by its decimal interval), with its case and
  its stability re-decided (the membership in the estimate and the eigenvalues' text are not re-checked);
  a stability the prover decided by Routh-Hurwitz (the row's ``routh_hurwitz``) is re-decided from the
  checker's own characteristic polynomial (Leibniz's sum, not the prover's cofactors), whose coefficients must
  meet the stored ones;
* a refuted claim's counterexample (a point where grad V . f > 0 or V <= 0, a violated inequality);
* every stored quantity contains the checker's recomputed enclosure (bounds: the certified side).
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb

from ...check import CheckResult
from ...core.balls import certainly_gt, certainly_le, certainly_lt, certainly_positive, exact_endpoints, working_precision
from ...core.stored import encloses, fmpq_of, interval as stored_interval, meets as stored_meets, number
from ...core.boxes import Box, tiles_by_bisection
from ...core.exact import Exact
from ...core.roots import RootStatus, enclose_f_df, newton_root
from .mu_claims import rho_function, rho_lower
from .direct_mu import piece_upper as direct_piece_upper
from .direct_face import face_margin
from .sublevel import box_lower_bound
from .equilibria import Equilibrium, classify as classify_equilibrium, jacobian as equilibrium_jacobian, pi_text
from .trajectory_claims import check_initial_point, check_paving, check_region_exit
from .trajectories import equilibrium_other_than_origin
from .natural_domain import band_function, exact_range, natural_lower_bound, positivity_functions, with_range
from .model import mean_value_enclosure
from .polar_forms import DIRECT_DOMAIN, slice_extent, slice_in_region, symmetric_in_x2, vdot_polar
from .closed_forms import (c_star_lower, c_star_upper, closed_form_constants, cylinder_lower_bound, damping_margin,
                           faces_minimiser_inside)
from .vdot_tests import psi_min_functions

__all__ = ["check"]


def _b(pair) -> arb:
    """The ball of a stored exact [lo, hi] pair."""
    lo, hi = (number(x) for x in pair)
    return arb(fmpq_of(lo)).union(arb(fmpq_of(hi)))


def _covers(pieces, lo: arb, hi: arb) -> bool:
    """The stored pieces (sorted by their lower ends) cover [lo, hi]: no gap, overlaps allowed."""
    if not pieces:
        return False
    ivs = sorted(((number(a), number(b)) for a, b in pieces), key=lambda p: p[0])
    lo_q = _lower(lo)
    hi_q = _upper(hi)
    if ivs[0][0] > lo_q:
        return False
    reach = ivs[0][1]
    for a, b in ivs[1:]:
        if a > reach:
            return False
        reach = max(reach, b)
    return reach >= hi_q


def _lower(x: arb) -> Fraction:
    return exact_endpoints(x)[0]


def _upper(x: arb) -> Fraction:
    return exact_endpoints(x)[1]


def _within(x: arb, lo: arb, hi: arb) -> bool:
    """The stored point ball x certainly meets the range [lo, hi] (some t of x lies in it): then an
    enclosure of f over x has its lower end <= f(t) <= the maximum over the range. A point outside the
    range proves nothing."""
    if not (x.is_finite() and lo.is_finite() and hi.is_finite()):
        return False
    (xl, xh), (_, lh), (hl, _) = exact_endpoints(x), exact_endpoints(lo), exact_endpoints(hi)
    return max(xl, lh) <= min(xh, hl)


#: per claim, the quantities its statement names: a proved claim without them is not confirmed
REQUIRED = {"constants": ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R"),
            "largest_sublevel": ("c_max_lower", "c_max_upper", "vdot_level_lower", "face_level"),
            "invariant_estimate": ("c_star", "c_set"),
            "best_mu": ("mu_best", "R_max", "R_sup_upper_bound", "R_max_relative_gap"),
            "vdot_direct": ("R_direct",),
            "best_mu_direct": ("mu_direct", "R_direct_max", "R_direct_sup_upper_bound", "R_direct_max_relative_gap")}


def _max_upper(f, pieces, target=None) -> arb:
    """The largest upper bound of f over the pieces (a certified bound of its maximum there); a piece
    whose bound exceeds ``target`` (an exact point, or None) is re-bounded by bisection (:func:`_refined_upper`)."""
    up = None
    for p in pieces:
        u = _refined_upper(f, _b(p), target)
        # the largest of exact points by exact comparison (arb's max of two balls widens)
        if up is None or not u.is_finite() or (up.is_finite() and certainly_gt(u, up)):
            up = u
    return up


#: bisection levels the checker may add below a stored piece whose bound exceeds the stored value by at
#: most REFINE_HAIR (relative; the discrepancies seen are 1e-22 .. 2e-9: arb's radius bits)
REFINE_LEVELS = 10
REFINE_HAIR = arb("1e-6")


def _refined_upper(f, X: arb, target, levels: int = REFINE_LEVELS) -> arb:
    """An upper bound of f over the ball X: f(X).upper(), and where that exceeds ``target`` (an exact
    point, or None: never), the larger of the two halves' bounds, bisecting down ``levels`` times. Each
    level is again an upper bound over X (the halves cover it); it only gets tighter. The checker uses it
    where its own enclosure of a maximum pokes above the stored one by arb's last radius bits, so that
    it re-derives the bound more tightly instead of rejecting a right certificate."""
    u = f(X).upper()
    if target is None or levels <= 0 or not u.is_finite() or certainly_le(u, target) or X.rad().is_zero():
        return u
    if not certainly_le(u, target * (1 + REFINE_HAIR)):
        return u        # more than radius bits above: a wrong stored value, rejected at once (no search)
    lo, hi = X.lower(), X.upper()
    mid = ((lo + hi) / 2).mid()
    if not (certainly_lt(lo, mid) and certainly_lt(mid, hi)):
        return u
    a = _refined_upper(f, lo.union(mid), target, levels - 1)
    b = _refined_upper(f, mid.union(hi), target, levels - 1)
    best = a if (not a.is_finite() or (b.is_finite() and certainly_le(b, a))) else b
    return best if best.is_finite() and certainly_lt(best, u) else u


def _bound_over_pieces(piece_bound, pieces, stored, cert_prec: int) -> arb | None:
    """The largest of ``piece_bound`` over the stored mu pieces (None if there are none): each piece's bound
    taken at the current precision and at ``cert_prec`` (both are upper bounds: the smaller is kept, arb's
    30-bit radii round differently), and re-bounded on its halves where it exceeds the ``stored`` bound by
    arb's last bits (:func:`_refined_upper`); the largest by exact comparison (arb's max of two balls widens)."""
    def both(Mu: arb) -> arb:
        u = piece_bound(Mu)
        with working_precision(cert_prec):
            u_cert = piece_bound(Mu)
        return u_cert if u_cert.is_finite() and (not u.is_finite() or certainly_lt(u_cert, u)) else u
    top = None
    for p in pieces:
        u = _refined_upper(both, _b(p), stored)
        top = u if top is None or not u.is_finite() or (top.is_finite() and certainly_gt(u, top)) else top
    return top


def _tighter(f, X: arb, prec: int) -> arb:
    """f over X at the current precision and at ``prec`` (the certificate's), intersected: both balls
    contain f(X), so their intersection does (a NaN or infinite one is dropped)."""
    hi = f(X)
    with working_precision(prec):
        lo = f(X)
    if not lo.is_finite():
        return hi
    if not hi.is_finite():
        return lo
    return hi.intersection(lo) if hi.overlaps(lo) else hi


def _box_lower_ends(make, boxes, prec: int) -> list[arb]:
    """For each box, the larger of the lower ends of the box function ``make()`` at the current precision
    and at ``prec`` (the certificate's): both are valid lower bounds (the (x2, t) functions evaluate a
    box with u < 0 as its mirror image where the law is odd, as the prover does:
    :func:`~rigor_gyro.kinds.lyapunov.model.symmetric_in_x2` states the theorem), and arb's 30-bit radii
    on wide balls round differently at two precisions (2e-9 relative seen on a c_max box), so neither one
    alone can confirm a bound stored from the other. ``make`` builds the function (it captures balls at the
    precision it is built at)."""
    f_here = make()
    here = [f_here({k: b.ball(k) for k in b.names}).lower() for b in boxes]
    with working_precision(prec):
        f_cert = make()
        there = [f_cert({k: b.ball(k) for k in b.names}).lower() for b in boxes]
    out = []
    for a, c in zip(here, there):       # exact ends (or +-inf, nan): compared exactly
        out.append(a if c.is_nan() else c if a.is_nan() else a if a >= c else c)
    return out


def _positive_end(low: arb) -> bool:
    """A lower end certainly > 0 (+inf counts: nothing to bound there)."""
    return float(low) == float("inf") or (low.is_finite() and certainly_positive(low))


def _same_number(a, b) -> bool:
    """Two stored numbers (decimal or p/q texts) are the same exact rational; False if either is unreadable."""
    try:
        return number(a) == number(b)
    except (TypeError, ValueError, ZeroDivisionError):
        return False


def _states_a_bound(text, bound: arb) -> bool:
    """The stated decimal ``text`` is >= the upper end of the checker's finite ``bound``."""
    try:
        return bound.is_finite() and number(text) >= _upper(bound)
    except (TypeError, ValueError, ZeroDivisionError):
        return False


def _direct_boxes_hold(g, R: arb, stored_boxes, cert_prec: int) -> bool:
    """R > 0, the stored (x2, t) boxes are the leaves of a bisection tree of the domain, and A - R |B| > 0
    on each (the better lower end of two precisions)."""
    boxes = [Box.from_json(b) for b in stored_boxes]
    return (certainly_positive(R) and tiles_by_bisection(Box.of(DIRECT_DOMAIN), boxes)
            and all(_positive_end(lo) for lo in _box_lower_ends(lambda: symmetric_in_x2(g, face_margin(g, R)), boxes,
                                                                 cert_prec)))


def rho_lower_at(rho, x2: arb, xs: arb) -> arb:
    """A lower bound of rho(x2) = max_i |(ci1, ci3)| / ci0 (``rho`` from mu_claims.rho_function): its lower end
    at x2 (an exact point, rounded down) when x2 is certainly in [-x2*, x2*], else 0 (no bound: R_sup is
    1 / the maximum of rho over the range only)."""
    return rho(x2).lower() if _within(abs(x2), arb(0), xs) else arb(0)


def m_lower_at(g, x2: arb) -> arb:
    """A lower bound of m = max over [0, x2*] of |cos x2 f'(x2)| / D(x2), from its value at the point x2 of
    that range: the larger lower end of its two enclosures there (an exact point, rounded down)."""
    return g.m_quotient(x2).lower().max(abs(g.m_signed(x2)).lower())


def M_lower_at(g, x2: arb) -> arb:
    """A lower bound of M = max over [0, x2*] of q: q's lower end at the point x2 of that range."""
    return g.q(x2).lower()


def _inside_16(K: dict, mu: arb) -> bool:
    """mu lies certainly inside (16), mu_min < mu < mu_max (``K``: the checker's constants)."""
    return certainly_lt(K["mu_min"], mu) and certainly_lt(mu, K["mu_max"])


def _covers_16(pieces, K: dict) -> bool:
    """The stored mu pieces cover all of (16): from mu_min's lower end to mu_max's upper end (a bound over
    (16) must hold wherever its ends may lie)."""
    return _covers(pieces, K["mu_min"].lower(), K["mu_max"].upper())


def psi_at_point(g, which: str, x1: arb, x2: arb, x3: arb) -> arb:
    """Psi1 (``which`` "Psi1") or else Psi2 at the point: ci0(x2) + ci1(x2) x1 + ci3(x2) x3, the factor of
    -x1^2 (Psi1) or -x3^2 (Psi2) in Vdot = -Psi1 x1^2 - Psi2 x3^2. An enclosure at the current precision."""
    c0, c1, c3 = g.psi_coefficients(x2)[0 if which == "Psi1" else 1]
    return c0 + c1 * x1 + c3 * x3


def r_sup_piece_upper(g, xs: arb, points: list[arb], Mu: arb) -> arb:
    """An upper bound (an exact point) of R_sup(mu) for every mu in the ball ``Mu``: 1 / the largest lower
    bound of rho(x2, mu) at the ``points`` x2 certainly in [-x2*, x2*] (R_sup <= 1 / rho(x2) at any x2 of
    the range; a point beyond it proves nothing and is skipped), rounded up. +inf (nothing bounded) when no
    point in range gives a finite positive bound, or when one gives +inf or NaN (rho_lower is +inf where no
    disc keeps Psi > 0: R_sup is 0 there, but +inf is the conservative answer). Precision: the current one,
    also for the points' balls (the caller makes them). Fails when: never raises for finite balls."""
    L = arb(0)
    for x in points:
        if not _within(abs(x), arb(0), xs):
            continue            # outside the range: proves nothing
        v = rho_lower(g, x, Mu)
        if not v.is_finite() or (L.is_finite() and certainly_gt(v, L)):
            L = v               # exact comparison: arb's max of two balls widens
    return (1 / L).upper() if certainly_positive(L) else arb("inf")


def cylinder_margin_lower(cyl: arb, c_star_up: arb) -> arb:
    """A lower bound (an exact point, rounded down) of min over the cylinder of V / c* - 1, from ``cyl`` (a
    lower bound of V's minimum there) and ``c_star_up`` (an upper bound of c*, positive): the lower end of
    cyl / c_star_up - 1. Precision: the current one. NaN when c_star_up's ball contains 0 (never a bound)."""
    return (cyl / c_star_up - 1).lower()


def slice_point_lower(g, cl: arb, R: arb, xs: arb, pt: arb, value, fallback: arb) -> arb:
    """A lower bound of an extent of the set {V < c_set} (``cl``) in the region from a stored slice point
    x2 = ``pt``: the lower end of ``value(pt)`` (the slice's half-width in x1 or x3, or pt itself for x2)
    when pt is certainly in [-x2*, x2*] and its slice certainly lies in the disc of radius R (then the set
    reaches that far); else the lower end of ``fallback`` (a ball that bounds the extent below, such as the
    axis segment's end). A point beyond x2* never counts: the region ends there, so its slice, however
    large, is not a slice of the set. Precision: the current one."""
    if _within(abs(pt), arb(0), xs) and slice_in_region(g, cl, R, pt):
        return value(pt).lower()
    return fallback.lower()


def _all_positive(f, pieces) -> bool:
    return all(certainly_positive(f(_b(p))) for p in pieces)


def check(model, data: dict) -> list[CheckResult]:
    """Re-decide every claim of a Lyapunov certificate; see the module docstring."""
    res: list[CheckResult] = []
    say = lambda item, ok, msg: res.append(CheckResult(item, ok, msg))  # noqa: E731
    q, W = data["quantities"], data.get("witnesses") or {}
    cert_prec = data["precision_bits"]
    claims = {c["id"]: c for c in data["claims"]}
    verified: set[str] = set()
    g = model.gimbal
    c = g.c
    xs = c.x2_star

    def contains(name: str, x: arb) -> bool:
        if name not in q:
            return True
        if _states_nothing(q[name]):
            verified.add(name)      # a stored nan or inf states nothing (a proved claim needs it finite: REQUIRED)
            return True
        ok = encloses(stored_interval(q[name]), x)
        if ok:
            verified.add(name)
        else:
            say(name, False, f"stored [{q[name]['lo']}, {q[name]['hi']}] does not contain the recomputed value")
        return ok

    def contains_exact(name: str, text: str) -> bool:
        """A searched decimal (mu_best, R_max, R_direct, mu_direct, R_direct_max): the stored [lo, hi] holds
        the exact number the witness names (a certificate stores it as that number, lo = hi)."""
        if name not in q:
            return True
        lo, hi = stored_interval(q[name])
        ok = lo <= number(text) <= hi
        if ok:
            verified.add(name)
        else:
            say(name, False, f"stored [{q[name]['lo']}, {q[name]['hi']}] does not contain the searched decimal {text}")
        return ok

    def contains_hull(name: str, low: arb, up: arb) -> bool:
        """A stored enclosure of a number between low's lower end and up's upper end: it must hold that exact
        interval (no midpoint-radius ball of the two: its radius, rounded up by 2^-30 relative, would widen
        it by 1e-10 over [0.36, 0.52])."""
        if name not in q:
            return True
        lo, hi = stored_interval(q[name])
        ok = low.is_finite() and up.is_finite() and lo <= _lower(low) and _upper(up) <= hi
        if ok:
            verified.add(name)
        else:
            say(name, False, f"stored [{q[name]['lo']}, {q[name]['hi']}] does not contain the recomputed bounds")
        return ok

    def upper_bound_holds(name: str, x: arb) -> bool:
        """A stored *bound* (a number the proof computed): its upper end is >= the checker's bound."""
        if name not in q:
            return True
        ok = x.is_finite() and stored_interval(q[name])[1] >= _upper(x)
        if ok:
            verified.add(name)
        else:
            say(name, False, "the stored bound is below the bound the checker re-derives")
        return ok

    def _stored_hi(name: str):
        """The stored interval's exact upper end as a ball (None if absent or unreadable)."""
        try:
            return arb(fmpq_of(stored_interval(q[name])[1]))
        except (KeyError, TypeError, ValueError):
            return None

    # ---------------------------------------------------------------- the maxima m and M
    K = None
    wc = W.get("constants")
    if wc:
        mv = mean_value_enclosure(g.m_signed)
        def m_fn(X):        # both enclose |cos f'|/D over X: keep the one with the lower upper end
            a, b = g.m_quotient(X), abs(mv(X))    # (arb's min of the two balls widens: (x + y - |x - y|)/2)
            return a if certainly_le(a.upper(), b.upper()) else b
        ok = (_covers(wc["m"]["cover"], arb(0), xs) and _covers(wc["M"]["cover"], arb(0), xs)
              and _within(_b(wc["m"]["point"]), arb(0), xs) and _within(_b(wc["M"]["point"]), arb(0), xs))
        if ok:
            pt = _b(wc["m"]["point"])       # m >= its value at the point: the tighter of the two forms there
            m_at = m_lower_at(g, pt)
            # each piece at this precision and at the certificate's, intersected (a 128-bit bound of m once
            # came out 1e-18 above the 64-bit one: arb's 30-bit radii round differently)
            m = m_at.union(_max_upper(lambda X: _tighter(m_fn, X, cert_prec), wc["m"]["cover"], _stored_hi("m")))
            M = M_lower_at(g, _b(wc["M"]["point"])).union(_max_upper(lambda X: _tighter(g.q, X, cert_prec),
                                                                   wc["M"]["cover"], _stored_hi("M")))
            if m.is_finite():       # M not enclosed (f = 0: q = 0/0) leaves p, k_min, mu_min nan; R1, R2 need m only
                K = closed_form_constants(g, m, M)
                for name in ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R"):
                    contains(name, K[name])
                contains("damping_margin", damping_margin(g, K["k_min"])[0])
        if K is None:
            say("constants", False, "the stored covers of m and M do not cover [0, x2*] or give no finite bound")
    R = None
    if model.R_option is not None:
        R = arb(model.R_option)
    elif K is not None:
        R = K["R"]
    if R is not None:
        contains("R_used", R)

    def vdot_holds(gm, radius, rec) -> bool:
        if not rec or not (radius.is_finite() and certainly_positive(radius)):
            return False
        p1, p2 = psi_min_functions(gm, radius)
        return all(_covers(rec[k], -xs, xs) for k in ("Psi1", "Psi2")) and \
            _all_positive(p1, rec["Psi1"]) and _all_positive(p2, rec["Psi2"])

    # ---------------------------------------------------------------- V > 0
    wv = W.get("v_positive")
    v_ok = False
    if wv and all(k in wv for k in ("S", "f_over_x", "psi")):
        v_ok = (all(_covers(wv[k], arb(0), xs) for k in ("S", "f_over_x", "psi"))
                and _all_positive(g.S, wv["S"]) and _all_positive(lambda x: g.law.f_over_x(c.a, x), wv["f_over_x"])
                and _all_positive(g.psi, wv["psi"]))
    wvn = W.get("vdot_nonpositive") or {}
    # Vdot <= 0 on (17): the Psi test's x2 pieces, or the direct test's (x2, t) boxes at R, re-evaluated
    vdot_ok = R is not None and (vdot_holds(g, R, wvn) if "Psi1" in wvn else
                                 bool(wvn.get("boxes")) and _direct_boxes_hold(g, R, wvn["boxes"], cert_prec))
    psi_ok = R is not None and vdot_holds(g, R, W.get("psi_test"))

    # ---------------------------------------------------------------- c*, the set, its extents
    inv_ok = False
    wi = W.get("invariant_estimate")
    ic = claims.get("invariant_estimate", {})
    # c* and its face term are stored whatever the claim's outcome (an inconclusive claim reports the c*
    # it could not prove positive): they are re-derived from the cylinder pieces whenever R is; the set
    # {V < c_set} and its extents only when the claim is proved (they need Vdot <= 0 and V > 0)
    if wi and R is not None:
        face = g.phi(xs)
        inside = faces_minimiser_inside(g, xs, R)
        lb = cylinder_lower_bound(g, R)
        cyl = None
        if _covers(wi["cylinder"], arb(0), xs):
            for p in wi["cylinder"]:
                v = lb(_b(p)).lower()
                cyl = v if cyl is None else cyl.min(v)
        if cyl is not None:
            lower = c_star_lower(face, cyl, inside)
            upper = c_star_upper(g, R, xs, face, inside)
            cstar_lo_ok = "c_star" in q and stored_interval(q["c_star"])[0] <= _lower(lower)
            cstar_hi_ok = "c_star" in q and stored_interval(q["c_star"])[1] >= _upper(upper)
            if cstar_lo_ok and cstar_hi_ok:
                verified.add("c_star")
            if "cylinder_margin_lower" in q:
                # a lower bound of min_cylinder V / c* - 1: valid when at most this checker's own bound
                # (its cylinder bound over its c*'s upper end; where the faces bind certainly, face.upper() <
                # cyl <= every cylinder sample, that upper end is the faces' phi(x2*).upper())
                own = cylinder_margin_lower(cyl, upper)
                if certainly_positive(lower) and stored_interval(q["cylinder_margin_lower"])[1] <= _lower(own):
                    verified.add("cylinder_margin_lower")
            contains("c_star_face", face)
            proved = vdot_ok and v_ok and ic.get("status") == "proved"
            c_text = ic.get("details", {}).get("c_set") if proved else None
            if c_text is not None:
                cl = arb(fmpq_of(number(c_text)))
                contains("c_set", cl)
                hx = c.H / c.B0
                axes = {"x1": ((2 * cl).sqrt() / hx).min(R),
                        "x3": ((2 * cl) / (g.f2(arb(0)) + c.mu * g.f1(arb(0)))).sqrt().min(R)}
                contains("extent_x1_axis", axes["x1"])
                contains("extent_x3_axis", axes["x3"])
                if "extent_x2_axis" in q:
                    e_lo, e_hi = stored_interval(q["extent_x2_axis"])
                    lo_b, hi_b = arb(fmpq_of(e_lo)), arb(fmpq_of(e_hi))
                    capped = certainly_lt(c.mu * g.F(xs), cl) and encloses((e_lo, e_hi), xs)
                    # the segment must lie in the range (mu F is increasing only there: the sine law's G is not)
                    root_in = certainly_le(lo_b, xs) and \
                        (certainly_lt(c.mu * g.F(lo_b), cl) or not certainly_positive(lo_b)) and \
                        (certainly_gt(c.mu * g.F(hi_b.min(xs)), cl) or encloses((e_lo, e_hi), xs))
                    if capped or root_in:
                        verified.add("extent_x2_axis")
                # the extents: the stored covers re-bounded above, the stored points re-checked to be slices
                # of the set (their value bounds below)
                # each piece re-evaluated at the certificate's precision and at the checker's, keeping the
                # tighter bound (both are valid; interval widths are not monotone in the precision, and a
                # bound the prover got at its precision must not look unconfirmed at another)
                for axis in ("x1", "x3"):
                    we_ = wi.get(f"extent_{axis}") or {}
                    fn = slice_extent(g, cl, axis)
                    if we_ and _covers(we_.get("cover", []), arb(0), xs):
                        up = _max_upper(lambda X: _tighter(fn, X, cert_prec), we_["cover"])
                        up = up if certainly_le(up, R.upper()) else R.upper()
                        pt = _b(we_["point"])
                        # else the axis segment, which lies in the set
                        low = slice_point_lower(g, cl, R, xs, pt, lambda y: _tighter(fn, y, cert_prec),
                                                axes[axis])
                        contains_hull(f"extent_{axis}", low, up)
                w2 = wi.get("extent_x2") or {}
                if w2:
                    pt = _b(w2["point"])
                    axis_low = (arb(fmpq_of(stored_interval(q["extent_x2_axis"])[0]))
                                if "extent_x2_axis" in verified else arb(0))
                    low = slice_point_lower(g, cl, R, xs, pt, lambda y: y, axis_low)
                    beyond = w2.get("beyond") or []
                    up = xs.upper()
                    if beyond:
                        start = arb(fmpq_of(min(number(p_[0]) for p_ in beyond)))
                        if _covers(beyond, start, xs) and _all_positive(lambda x: _tighter(
                                lambda y: g.phi(y) - cl, x, cert_prec), beyond):
                            up = start                  # phi > c_set from there to x2*: no slice beyond it
                    contains_hull("extent_x2", low, up)
                inv_ok = (cstar_lo_ok and cstar_hi_ok and certainly_positive(cl)
                          and certainly_le(cl, lower))

    # ---------------------------------------------------------------- best mu
    bm_ok = False
    wb = W.get("best_mu")
    bc = claims.get("best_mu", {})
    if wb and K is not None and bc.get("status") == "proved":
        d = bc.get("details", {})
        mu_b = fmpq_of(number(d["mu_best"]))
        R_max = arb(fmpq_of(number(d["R_max"])))
        gb = g.with_mu(mu_b)
        contains_exact("mu_best", d["mu_best"])
        contains_exact("R_max", d["R_max"])
        inside16 = _inside_16(K, arb(mu_b))
        at_R_max = vdot_holds(gb, R_max, wb["vdot_at_R_max"])
        rho = rho_function(gb)
        if _covers(wb["r_sup_cover"], arb(0), xs):
            top = _max_upper(rho, wb["r_sup_cover"])
            point = _b(wb["r_sup_point"])
            low = rho_lower_at(rho, point, xs)
            contains("R_sup_at_mu_best", (1 / top).union(1 / low) if certainly_positive(low) else arb("nan"))
        U = None
        if _covers_16(wb["mu_pieces"], K):       # the points made at each pass's precision, as the mu pieces
            U = _bound_over_pieces(lambda Mu: r_sup_piece_upper(g, xs, [_b(t) for t in wb["x2_points"]], Mu),
                                   wb["mu_pieces"], _stored_hi("R_sup_upper_bound"), cert_prec)
        if U is not None and U.is_finite():
            upper_bound_holds("R_sup_upper_bound", U)
            upper_bound_holds("R_max_relative_gap", (U - R_max) / R_max)
        bm_ok = (inside16 and at_R_max and U is not None and U.is_finite()
                 and _states_a_bound(d.get("R_sup_upper_bound"), U)
                 and _states_a_bound(d.get("relative_gap"), (U - R_max) / R_max))

    # ---------------------------------------------------------------- Vdot < 0 directly
    direct_ok = False
    wd = W.get("vdot_direct")
    if wd and claims.get("vdot_direct", {}).get("status") == "proved":
        Rd = arb(fmpq_of(number(wd["R"])))
        contains_exact("R_direct", wd["R"])
        direct_ok = _direct_boxes_hold(g, Rd, wd.get("boxes", []), cert_prec)
        pt = wd.get("point")
        if pt and direct_ok:
            x1, x2, x3 = (_b(_pair(pt[k])) for k in ("x1", "x2", "x3"))
            if certainly_le(abs(x2), xs) and certainly_positive(g.vdot(x1, x2, x3)):
                radius = (x1 * x1 + x3 * x3).sqrt()
                upper_bound_holds("R_direct_upper", radius)
                if "R_direct_upper" in q:
                    up = arb(fmpq_of(stored_interval(q["R_direct_upper"])[1]))
                    upper_bound_holds("R_direct_relative_gap", (up - Rd) / Rd)

    # ---------------------------------------------------------------- the direct test over (16)
    bd_ok = False
    wbd = W.get("best_mu_direct")
    if wbd and K is not None and claims.get("best_mu_direct", {}).get("status") == "proved":
        dd = claims["best_mu_direct"].get("details", {})
        mu_d = fmpq_of(number(wbd["mu"]))
        Rdm = arb(fmpq_of(number(wbd["R"])))
        # the claim's details state the same mu and radius as the witness, exactly (the campaign and a reader
        # take them from there)
        same = _same_number(dd.get("mu_direct"), wbd["mu"]) and _same_number(dd.get("R_direct_max"), wbd["R"])
        contains_exact("mu_direct", wbd["mu"])
        contains_exact("R_direct_max", wbd["R"])
        inside16 = _inside_16(K, arb(mu_d))
        at_mu = _direct_boxes_hold(g.with_mu(mu_d), Rdm, wbd.get("boxes", []), cert_prec)
        Ud = None
        try:
            pts = [(fmpq_of(number(u)), fmpq_of(number(t))) for u, t in wbd.get("points", [])]
        except (TypeError, ValueError, ZeroDivisionError):
            pts = []
        if pts and _covers_16(wbd.get("mu_pieces", []), K):
            Ud = _bound_over_pieces(lambda Mu: direct_piece_upper(g, Mu, pts), wbd["mu_pieces"],
                                    _stored_hi("R_direct_sup_upper_bound"), cert_prec)
        stated = False
        if Ud is not None and Ud.is_finite():
            upper_bound_holds("R_direct_sup_upper_bound", Ud)
            upper_bound_holds("R_direct_max_relative_gap", (Ud - Rdm) / Rdm)
            # the stated decimals are bounds too: at or above the checker's own
            stated = _states_a_bound(dd.get("R_direct_sup_upper_bound"), Ud) and \
                _states_a_bound(dd.get("relative_gap"), (Ud - Rdm) / Rdm)
        bd_ok = inside16 and at_mu and same and stated and Ud is not None and Ud.is_finite()

    # ---------------------------------------------------------------- the largest sublevel set
    sub_ok, sub_msg = False, "no stored boxes"
    wl = W.get("largest_sublevel")
    sc = claims.get("largest_sublevel", {})
    if wl and sc.get("status") == "proved":
        sub_ok, sub_msg = _check_sublevel(g, xs, wl, sc.get("details", {}), q, verified, cert_prec)

    # ---------------------------------------------------------------- the natural sublevel set
    nat_ok, nat_msg = False, "no stored witness"
    wn = W.get("natural_sublevel")
    ncl = claims.get("natural_sublevel", {})
    if wn and ncl.get("status") == "proved":
        nat_ok, nat_msg = _check_natural(g, wn, ncl.get("details", {}), q, verified, cert_prec)

    # ---------------------------------------------------------------- equilibria
    eq_ok, eq_msg = False, "no stored pieces"
    we = W.get("equilibria")
    if we and claims.get("equilibria", {}).get("status") == "proved":
        eq_ok, eq_msg = _check_equilibria(g, we["pieces"], claims["equilibria"].get("details", {}).get("equilibria", []))

    def region_point(ce: dict):
        """A stored counterexample's point (x1, x2, x3) and whether it certainly lies in region (17)."""
        pt = ce.get("point", {})
        x1, x2, x3 = (_b(_pair(pt[k])) for k in ("x1", "x2", "x3"))
        return x1, x2, x3, (R is not None and certainly_le(abs(x2), xs) and certainly_lt(x1 * x1 + x3 * x3, R * R))

    # ---------------------------------------------------------------- the claims
    for cid, cl_ in claims.items():
        st = cl_["status"]
        ce = cl_.get("counterexample") or {}
        if st == "inconclusive":
            say(cid, True, "inconclusive: claims nothing")
        elif cid == "constants":
            say(cid, st == "proved" and K is not None and all(v.is_finite() for v in K.values()),
                "m, M re-bounded on the stored covers; closed forms recomputed")
        elif cid == "damping_condition":
            if K is None:
                say(cid, False, "needs the re-verified constants")
                continue
            parts = [(c.k, K["k_min"]), (c.mu, K["mu_min"]), (K["mu_max"], c.mu)]
            # the binding threshold in k the details name: the checker's own comparison must not contradict it
            stated = (cl_.get("details") or {}).get("binding")
            if stated is not None:
                _, own, each = damping_margin(g, K["k_min"])
                single = stated in each
                if not (stated == own or (not single and all(n in stated for n in each)) or
                        (single and own not in each and stated in own)):
                    say(cid, False, f"the binding threshold {stated!r} is not the one re-derived ({own!r})")
                    continue
            if st == "proved":
                say(cid, all(certainly_gt(x, y) for x, y in parts), "k > k_min and mu inside (16), re-decided")
            else:
                say(cid, any(certainly_le(x, y) for x, y in parts), "a violated inequality re-derived")
        elif cid == "vdot_nonpositive":
            if st == "proved":
                say(cid, vdot_ok, "Psi1, Psi2 > 0 over the disc on every stored x2 piece, or A - R |B| > 0 on every "
                    "stored (x2, t) box (the boxes tile the domain), re-evaluated")
            else:
                # refuted only by a point where Vdot > 0: a failed Psi test is no counterexample to Vdot <= 0
                x1, x2, x3, in_region = region_point(ce)
                say(cid, "psi" not in ce and in_region and certainly_positive(g.vdot(x1, x2, x3)),
                    "grad V . f > 0 at the stored point of the region, re-evaluated")
        elif cid == "psi_test":
            if st == "proved":
                say(cid, psi_ok, "Psi1, Psi2 > 0 over the disc on every stored x2 piece, re-evaluated")
            else:
                x1, x2, x3, in_region = region_point(ce)
                if "psi" in ce:          # the statement's Psi test fails at the point
                    ok = in_region and certainly_le(psi_at_point(g, ce["psi"], x1, x2, x3), 0)
                    say(cid, ok, f"{ce['psi']} <= 0 at the stored point of the region, re-evaluated")
                else:
                    ok = in_region and certainly_positive(g.vdot(x1, x2, x3))
                    say(cid, ok, "grad V . f > 0 at the stored point of the region, re-evaluated")
        elif cid == "vdot_direct":
            say(cid, st == "proved" and direct_ok, "A - R_direct |B| > 0 on every stored (x2, t) box, the boxes "
                "tile the domain; the point above the radius re-evaluated")
        elif cid == "equilibria":
            say(cid, st == "proved" and eq_ok, eq_msg)
        elif cid == "largest_sublevel":
            if st == "proved":
                say(cid, sub_ok, sub_msg)
            elif ce.get("where") == "faces":
                say(cid, certainly_le(_face_level(g, xs), 0), "min phi(+-x2*) <= 0 re-evaluated")
            else:
                try:
                    t = number(ce.get("t_over_pi", ""))
                except (ValueError, ZeroDivisionError):
                    t = None
                A = vdot_polar(g, arb(0), arb.pi() * arb(fmpq_of(t)))[0] if t is not None else arb("nan")
                say(cid, certainly_lt(A, 0), "A(0, t) < 0 at the stored t re-evaluated (Vdot > 0 arbitrarily near 0)")
        elif cid == "natural_sublevel":
            say(cid, st == "proved" and nat_ok, nat_msg)
        elif cid == "attraction_paving":
            level, reach = _natural_level(nat_ok, claims, W)
            ok, msg = check_paving(g, level, reach, W.get("attraction_paving"), cl_.get("details") or {}) \
                if st == "proved" else (False, "only a proved attraction_paving is checked")
            say(cid, ok, msg)
        elif cid == "region_not_invariant":
            ok, msg = check_region_exit(g, R, xs, W.get("region_not_invariant")) if st == "proved" else \
                (False, "only a proved region_not_invariant is checked")
            say(cid, ok, msg)
        elif cid == "initial_point":
            if st == "proved":
                level, reach = _natural_level(nat_ok, claims, W)
                ok, msg = check_initial_point(g, model.initial_point, level, reach, W.get("initial_point"))
                say(cid, ok, msg)
            else:
                eq = (cl_.get("counterexample") or {}).get("equilibrium")
                pt = model.initial_point
                r = None if pt is None else (pt[1].rational if pt[1].pi_power == 1 else
                                             (Fraction(0) if pt[1].rational == 0 else None))
                say(cid, pt is not None and eq == [p.text for p in pt] and
                    equilibrium_other_than_origin(g, pt[0].rational, r, pt[2].rational),
                    "the initial point is exactly an equilibrium other than 0, re-derived")
        elif cid == "v_positive":
            if st == "proved":
                say(cid, v_ok, "S, f/x, psi > 0 on every stored piece of [0, x2*], re-evaluated")
            else:
                pt = ce.get("point", {})
                x1, x2, x3 = (_b(_pair(pt[k])) for k in ("x1", "x2", "x3"))
                off_origin = certainly_positive(x1 * x1 + x2 * x2 + x3 * x3)
                say(cid, off_origin and certainly_le(g.V(x1, x2, x3), 0) and certainly_le(abs(x2), xs),
                    "V <= 0 at the stored point (away from the origin), re-evaluated")
        elif cid == "invariant_estimate":
            say(cid, st == "proved" and inv_ok, "c* re-bounded on the stored cylinder cover; c_set below it")
        elif cid == "best_mu":
            if st == "proved":
                say(cid, bm_ok, "mu_best inside (16), Psi > 0 at R_max, the bound over (16) re-derived")
            else:
                say(cid, K is not None and certainly_le(K["mu_max"], K["mu_min"]), "the interval (16) is empty")
        elif cid == "best_mu_direct":
            if st == "proved":
                say(cid, bd_ok, "mu_direct inside (16), A - R_direct_max |B| > 0 on every stored (x2, t) box at "
                    "mu_direct (the boxes tile the domain), the bound over (16) re-derived from the stored mu pieces "
                    "and points")
            else:
                say(cid, K is not None and certainly_le(K["mu_max"], K["mu_min"]), "the interval (16) is empty")
        else:
            say(cid, False, f"unknown claim {cid!r}")
    for cid, names in REQUIRED.items():
        if claims.get(cid, {}).get("status") == "proved":
            missing = [n for n in names if n not in q or _states_nothing(q[n])]
            if missing:
                say(cid, False, f"a proved {cid} without finite values of the quantities its statement names: {missing}")
    unverified = sorted(set(q) - verified)
    say("quantities", not unverified, f"{len(verified)} stored enclosures verified"
        + (f"; not verified: {unverified}" if unverified else ""))
    return res


def _states_nothing(stored) -> bool:
    """Whether a stored quantity bounds nothing: both ends nan, or -inf and +inf (what the prover writes for a
    non-finite ball). One infinite end does not qualify: [-inf, 0.001] states "<= 0.001" (the prover never writes
    it; it is then read as a stored number and refused as not finite)."""
    if not isinstance(stored, dict):
        return False
    lo, hi = (str(stored.get(k, "")).strip() for k in ("lo", "hi"))
    return (lo, hi) == ("nan", "nan") or (lo == "-inf" and hi in ("inf", "+inf"))


def _face_level(g, xs: arb) -> arb:
    """min(phi(x2*), phi(-x2*)) as the prover encloses it (the smaller one when certain, else the hull)."""
    a, b = g.phi(xs), g.phi(-xs)
    if certainly_le(a.upper(), b.lower()):
        return a
    if certainly_le(b.upper(), a.lower()):
        return b
    return a.union(b)


def _check_sublevel(g, xs: arb, w: dict, details: dict, q: dict, verified: set, cert_prec: int) -> tuple[bool, str]:
    """Re-derive the bounds of c_max from the stored (x2, t) boxes (they must tile the domain; the
    model's lower bound re-evaluated on each), the faces' closed form and the stored point of
    {Vdot > 0} (Vdot and V re-evaluated). Each stated bound is compared with its exact decimal."""
    try:
        lo_t, hi_t, n_lo_t = (number(details[k]) for k in ("c_max_lower", "c_max_upper", "vdot_level_lower"))
        n_up_t = number(details["vdot_level_upper"]) if details.get("vdot_level_upper") else None
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "the bounds in the claim's details are missing or not numbers"
    for name, t in (("c_max_lower", lo_t), ("c_max_upper", hi_t), ("vdot_level_lower", n_lo_t),
                    ("vdot_level_upper", n_up_t)):
        if t is None:
            continue
        # a bound is one exact decimal: its stored ball must hold it and be no wider than a rounding of it
        iv = stored_interval(q[name]) if name in q else None
        if iv is None or not encloses(iv, arb(fmpq_of(t))) or (iv[1] - iv[0]) > abs(t) * Fraction(1, 2 ** 40):
            return False, f"the stored {name} is not the stated decimal {details.get(name)}"
        verified.add(name)
    if not lo_t > 0:
        return False, f"c_max_lower = {details['c_max_lower']} is not positive: the statement says c_max > 0"
    boxes = [Box.from_json(b) for b in w.get("boxes", [])]
    if not tiles_by_bisection(Box.of(DIRECT_DOMAIN), boxes):
        return False, "the stored (x2, t) boxes do not tile the domain"
    n_lo = fmpq_of(n_lo_t)
    for b, low in zip(boxes, _box_lower_ends(lambda: symmetric_in_x2(g, box_lower_bound(g)), boxes, cert_prec)):
        key = float(low)                # +inf: no point of {Vdot >= 0} above the box
        if not (key == float("inf") or (low.is_finite() and low >= n_lo)):
            return False, f"on the box {b.to_json()} the lower bound of V over {{Vdot >= 0}} is below {details['vdot_level_lower']}"
    face = _face_level(g, xs)
    if "face_level" not in q or not encloses(stored_interval(q["face_level"]), face):
        return False, "the stored face_level does not contain min phi(+-x2*) re-evaluated"
    verified.add("face_level")
    if not (face.is_finite() and lo_t <= n_lo_t and arb(fmpq_of(lo_t)) <= face.lower()):
        return False, "c_max_lower is not below both parts' lower bounds"
    upper = face.upper()
    pt = w.get("point")
    if pt is not None:
        x1, x2, x3 = (_b(_pair(pt[k])) for k in ("x1", "x2", "x3"))
        if not (certainly_le(abs(x2), xs) and certainly_positive(x1 * x1 + x3 * x3)
                and certainly_positive(g.vdot(x1, x2, x3))):
            return False, "the stored point is not certainly in {Vdot > 0, x1^2 + x3^2 > 0, |x2| <= x2*}"
        v = g.V(x1, x2, x3).upper()
        if n_up_t is None or not (v.is_finite() and v <= arb(fmpq_of(n_up_t))):
            return False, "V at the stored point exceeds vdot_level_upper"
        upper = upper if upper <= v else v
    elif n_up_t is not None:
        return False, "vdot_level_upper is stated without its point"
    if not (upper.is_finite() and upper <= arb(fmpq_of(hi_t))):
        return False, "c_max_upper is below the re-derived upper bound"
    binds = details.get("binds")
    if binds == "faces" and not face.upper() <= arb(fmpq_of(n_lo_t)):
        return False, "the faces are said to bind, but their level is not below vdot_level_lower"
    if binds == "vdot" and not (n_up_t is not None and arb(fmpq_of(n_up_t)) <= face.lower()):
        return False, "the set {Vdot >= 0} is said to bind, but its level is not below the faces'"
    return True, (f"c_max bounds re-derived: {len(boxes)} (x2, t) boxes tile the domain, the lower bound re-evaluated "
                  "on each; faces in closed form; the point of {Vdot > 0} re-evaluated")


def _natural_level(nat_ok: bool, claims: dict, W: dict):
    """(natural_c_max_lower, reach) as balls of the exact stated decimals, when the natural_sublevel check passed."""
    if not nat_ok:
        return None, None
    try:
        lo = number(claims["natural_sublevel"]["details"]["c_max_lower"])
        reach = number(W["natural_sublevel"]["reach"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return None, None
    return arb(fmpq_of(lo)), arb(fmpq_of(reach))


def _check_natural(g, w: dict, details: dict, q: dict, verified: set, cert_prec: int) -> tuple[bool, str]:
    """Re-derive the natural sublevel bounds from the stored pieces: V > 0 (S, f/x, psi > 0 on stored pieces
    covering [0, X], X read exactly from its stored text, inside (0, pi/2)), phi > c_max_upper on stored pieces covering
    [X_c, X], the stored (x2, t) boxes tiling the domain over |x2| <= X_c with the lower bound of V over
    {Vdot >= 0} >= c_max_lower on each, and Vdot > 0, V <= c_max_upper at the stored point (|x2| <= X_c).
    Each stated bound is compared with its exact decimal."""
    try:
        lo_t, hi_t = (number(details[k]) for k in ("c_max_lower", "c_max_upper"))
        Xe = exact_range(str(w["X"]))
        band_lo = number(w["band_lo"])
        stated_lo = number(details["band_lo"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "the bounds, X or X_c are missing or not numbers"
    if details.get("X") != w["X"] or stated_lo != band_lo:
        return False, "the details' X or X_c differ from the witness's"
    for name, t in (("natural_c_max_lower", lo_t), ("natural_c_max_upper", hi_t)):
        iv = stored_interval(q[name]) if name in q else None
        if iv is None or not encloses(iv, arb(fmpq_of(t))) or (iv[1] - iv[0]) > abs(t) * Fraction(1, 2 ** 40):
            return False, f"the stored {name} is not the stated decimal"
        verified.add(name)
    if not (0 < lo_t <= hi_t):
        return False, "natural c_max_lower is not positive, or above c_max_upper"
    X = Xe.ball()
    if not (certainly_positive(X) and certainly_lt(X, arb.pi() / 2)):
        return False, "X is not inside (0, pi/2)"
    if "natural_X" not in q or not encloses(stored_interval(q["natural_X"]), X):
        return False, "the stored natural_X does not contain X"
    verified.add("natural_X")
    for name, fn in positivity_functions(g).items():
        pieces = (w.get("positivity") or {}).get(name) or []
        if not (_covers(pieces, arb(0), X) and _all_positive(fn, pieces)):
            return False, f"{name} > 0 is not re-derived on stored pieces covering [0, X]"
    xc = arb(fmpq_of(band_lo))
    if not (band_lo > 0 and certainly_lt(xc, X)):
        return False, "X_c is not inside (0, X)"
    level = arb(fmpq_of(hi_t))
    if not (_covers(w.get("band") or [], xc, X) and _all_positive(band_function(g, level), w["band"])):
        return False, "phi > c_max_upper is not re-derived on stored pieces covering [X_c, X]"
    gC = with_range(g, Exact(band_lo, 0, str(band_lo)))
    boxes = [Box.from_json(b) for b in w.get("boxes", [])]
    if not tiles_by_bisection(Box.of(DIRECT_DOMAIN), boxes):
        return False, "the stored (x2, t) boxes over |x2| <= X_c do not tile the domain"
    lo_q = fmpq_of(lo_t)
    for b, low in zip(boxes, _box_lower_ends(lambda: symmetric_in_x2(gC, natural_lower_bound(gC, arb(lo_q))), boxes, cert_prec)):
        if not (float(low) == float("inf") or (low.is_finite() and low >= lo_q)):
            return False, f"on the box {b.to_json()} the lower bound of V over {{Vdot >= 0}} is below {details['c_max_lower']}"
    pt = w.get("point") or {}
    try:
        x1, x2, x3 = (_b(_pair(pt[k])) for k in ("x1", "x2", "x3"))
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return False, "no stored point of {Vdot > 0}"
    if not (certainly_le(abs(x2), xc) and certainly_positive(x1 * x1 + x3 * x3) and certainly_positive(g.vdot(x1, x2, x3))):
        return False, "the stored point is not certainly in {Vdot > 0, x1^2 + x3^2 > 0, |x2| <= X_c}"
    v = g.V(x1, x2, x3).upper()
    if not (v.is_finite() and v <= level):
        return False, "V at the stored point exceeds c_max_upper"
    reach = w.get("reach")
    if (reach is None) != ("natural_extent_x2" not in q) or (reach is None) != (details.get("reach") is None):
        return False, "the x2 extent is stated without its witness, or the reverse"
    if reach is not None:
        try:
            e = number(reach)
        except (TypeError, ValueError, ZeroDivisionError):
            return False, "the stored reach is not a number"
        eb = arb(fmpq_of(e))
        cl = arb(fmpq_of(lo_t))
        if not (number(details["reach"]) == e and 0 < e < band_lo and _covers(w.get("reach_pieces") or [], arb(0), eb)
                and _all_positive(lambda x: cl - g.phi(x), w["reach_pieces"])):
            return False, "phi < c_max_lower is not re-derived on stored pieces covering [0, reach]"
        if not encloses(stored_interval(q["natural_extent_x2"]), eb.union(xc)):
            return False, "the stored natural_extent_x2 does not contain [reach, X_c]"
        verified.add("natural_extent_x2")
    return True, (f"natural c_max bounds re-derived: V > 0 on [0, X] and phi > c_max_upper on [X_c, X] re-evaluated on "
                  f"the stored pieces, {len(boxes)} (x2, t) boxes tile the domain with the lower bound re-evaluated on "
                  "each, the point of {Vdot > 0} re-evaluated")


def _decided_roots(fn, pieces, pi: arb):
    """The roots of fn certified by the stored pieces, if the pieces are contiguous, cover [-pi, pi] and
    are each decided (empty: fn excludes 0, or one Newton image misses the piece; unique: a Newton image
    inside it); None otherwise. Returns [(lo, hi, enclosure)] of the unique pieces."""
    if not pieces:
        return None
    bounds = [(_b(p["lo"]), _b(p["hi"])) for p in pieces]
    if not (certainly_le(bounds[0][0], -pi) and certainly_le(pi, bounds[-1][1])):
        return None
    for (a, b), (c2, _) in zip(bounds, bounds[1:]):
        if not (a.rad().is_zero() and b.rad().is_zero() and b == c2):
            return None
    roots = []
    for (a, b), p in zip(bounds, pieces):
        if p["kind"] == "empty":
            fx, _ = enclose_f_df(fn, a.union(b))
            if not (fx.is_finite() and (certainly_positive(fx) or certainly_positive(-fx))):
                r = newton_root(fn, a, b)
                if r.status is not RootStatus.EMPTY:
                    return None
        elif p["kind"] == "unique":
            r = newton_root(fn, a, b)
            if r.status is not RootStatus.UNIQUE:
                return None
            roots.append((a, b, r.enclosure))
        else:
            return None
    return roots


def _check_equilibria(g, pieces: dict, rows: list) -> tuple[bool, str]:
    """Re-derive the equilibria from the stored isolation pieces of f and h, and their stability."""
    c = g.c
    pi = arb.pi()
    rf = _decided_roots(lambda x: g.f(x), pieces.get("f"), pi)
    rh = _decided_roots(lambda x: c.k * c.H + c.C0 * x.sin() * g.f(x), pieces.get("h"), pi)
    if rf is None or rh is None:
        return False, "the stored pieces do not cover [-pi, pi] with every piece decided"
    points = []
    zeros = [(arb(fmpq_of(r)) * pi, r) for r in g.law.zeros_over_pi()]
    for a, b, root in rf:
        named = [(z, r) for z, r in zeros if certainly_le(a, z) and certainly_le(z, b)]
        if len(named) == 1:
            z, r = named[0]
            if certainly_le(abs(z), pi * (1 + arb(2) ** -40)):
                points.append(Equilibrium(arb(0), z, "f(x2) = 0", exact=pi_text(r)))
        elif certainly_lt(abs(root), pi):
            points.append(Equilibrium(arb(0), root, "f(x2) = 0"))
        elif not certainly_lt(pi, abs(root)):
            return False, "a root of f is not separated from |x2| = pi"
    for sgn in (1, -1):
        points.append(Equilibrium(-g.f(sgn * pi / 2) / c.k, sgn * pi / 2, "cos x2 = 0", exact=pi_text(Fraction(sgn, 2))))
    for a, b, root in rh:
        if certainly_lt(pi, abs(root)):
            continue
        if not (certainly_lt(abs(root), pi) and (certainly_positive(root.cos()) or certainly_positive(-root.cos()))):
            return False, "a root of h is not separated from |x2| = pi or from cos x2 = 0"
        points.append(Equilibrium(-g.f(root) / c.k, root, "k H + C0 sin x2 f(x2) = 0"))
    if len(points) != len(rows):
        return False, f"{len(points)} equilibria re-derived, {len(rows)} stored"
    for e, r in zip(points, rows):
        classify_equilibrium(g, e)
        if e.case != r.get("case") or e.stability != r.get("stability"):
            return False, f"equilibrium at x2 = {r.get('x2')}: re-derived {e.case}, {e.stability}"
        if not (_stated_at(r.get("x2"), e.x2, e.exact) and _stated_at(r.get("x1"), e.x1)):
            return False, f"equilibrium at x2 = {r.get('x2')}, x1 = {r.get('x1')}: not where it is re-derived"
        if r.get("routh_hurwitz") is not None:
            ok, why = _hurwitz_confirms(equilibrium_jacobian(g, e.x1, e.x2, arb(0)), r["routh_hurwitz"], r["stability"])
            if not ok:
                return False, f"equilibrium at x2 = {r.get('x2')}: {why}"
    return True, f"{len(points)} equilibria re-derived from the stored pieces, at their stated points, stability re-decided"


#: the six permutations of (0, 1, 2) with their signs (Leibniz's determinant)
_PERMUTATIONS = (((0, 1, 2), 1), ((1, 2, 0), 1), ((2, 0, 1), 1), ((0, 2, 1), -1), ((2, 1, 0), -1), ((1, 0, 2), -1))


def _hurwitz_confirms(J, stored: dict, stability: str) -> tuple[bool, str]:
    """A Routh-Hurwitz stability re-decided: det(lambda I - J) = lambda^3 + a1 lambda^2 + a2 lambda + a3 with
    a1 = -trace J, a2 = the principal 2 x 2 minors, a3 = -det J by Leibniz's sum over the six permutations
    (written apart from the prover's cofactors); each must meet the stored decimal interval, and the Hurwitz
    determinants D1 = a1, D2 = a1 a2 - a3, D3 = a3 D2 must give the stated stability: all certainly > 0
    (asymptotically stable), or a1 < 0, a3 < 0 or (a1, a3 > 0 and D2 < 0) certainly (unstable: a root with
    real part > 0, see :func:`rigor_gyro.kinds.lyapunov.equilibria.routh_hurwitz`)."""
    a1 = -(J[0][0] + J[1][1] + J[2][2])
    a2 = sum((J[i][i] * J[j][j] - J[i][j] * J[j][i] for i, j in ((0, 1), (0, 2), (1, 2))), arb(0))
    det = arb(0)
    for perm, sign in _PERMUTATIONS:
        term = J[0][perm[0]] * J[1][perm[1]] * J[2][perm[2]]
        det = det + term if sign > 0 else det - term
    a3 = -det
    for name, v in (("a1", a1), ("a2", a2), ("a3", a3)):
        text = stored.get(name)
        if not _meets(text, v):
            return False, f"Routh-Hurwitz coefficient {name} = {text!r} does not meet the re-computed {v.str(10)}"
    d2 = a1 * a2 - a3
    if stability == "asymptotically stable":
        ok = certainly_positive(a1) and certainly_positive(d2) and certainly_positive(a3 * d2)
    elif stability == "unstable":
        ok = (certainly_lt(a1, 0) or certainly_lt(a3, 0)
              or certainly_positive(a1) and certainly_positive(a3) and certainly_lt(d2, 0))
    else:
        ok = False
    return ok, ("" if ok else f"the Routh-Hurwitz coefficients re-computed do not decide {stability!r}")


def _meets(text, x: arb) -> bool:
    """A stored decimal or ``[lo, hi]`` interval that shares a point with the finite ball x (exact ends)."""
    if not isinstance(text, str):
        return False
    try:
        iv = stored_interval(text[1:-1].split(", ")) if text.startswith("[") and text.endswith("]") else \
            (number(text), number(text))
    except ValueError:
        return False
    return stored_meets(iv, x)


def _stated_at(text, x: arb, exact: str = "") -> bool:
    """A row's coordinate ``text`` states x: the exact text (``"pi/2"``, ``"0"``) where x is a known
    multiple of pi, else a stored decimal or ``[lo, hi]`` enclosing the checker's ball x."""
    if exact:
        return text == exact
    if not isinstance(text, str):
        return False
    try:
        iv = stored_interval(text[1:-1].split(", ")) if text.startswith("[") and text.endswith("]") else \
            (number(text), number(text))
    except ValueError:                              # not a stored number, or lo > hi
        return False
    return encloses(iv, x)


def _pair(value) -> list[str]:
    """A counterexample coordinate as stored: an exact [lo, hi] pair of texts."""
    lo, hi = value
    return [lo, hi]
