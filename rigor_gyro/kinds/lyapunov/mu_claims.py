"""The claims over the mu interval (16): ``best_mu`` (the Psi test's best radius R_max at a searched mu_best, and
a certified bound of sup over (16) of R_sup) and ``best_mu_direct`` (the same for the direct test).

The mu values are search results (golden section, branch and bound on float point searches), named as such;
what is certified is computed at them afterwards, and the upper bounds hold for every mu in (16) whatever the
searches return. Precision: the attempt's."""

from __future__ import annotations

import math
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import (ball_key, certainly_le, certainly_lt, certainly_positive, decimal_bounds, exact_fraction,
                           interval)
from ...core.outcome import Claim, Status
from ...core.stored import ball_text, pieces_text
from ...core.subdivision import best_first_bisection, enclose_max
from .direct_mu import direct_sup_upper_bound, piece_upper
from .float_twin import float_twin, in_safe_range
from .search import PROPOSAL_WINDOW
from .model import Gimbal, hypot_ball
from .claim_context import ClaimContext, make_claim, to_fmpq, fmt, exact_ball, relative_gap, searched, unstate, vdot_claim
from .direct_claims import certify_direct

#: best_mu: branch and bound over mu stops once its upper bound is within this relative gap of R_max
BEST_MU_GAP = "1e-6"    # escalation beyond this only repeats the same subdivision (see attempt)
#: best_mu_direct: the branch and bound over mu stops once its bound is within this relative gap of the
#: search's best estimate (R_direct_max is certified FACE_MARGIN below the estimate where the minimiser is on a
#: face, else 4e-7: the gap stays below 1e-9, else below 1e-6)
DIRECT_MU_GAP = "5e-10"
DIRECT_MU_PIECES = 400
#: the box budget of the direct test at the searched mu_direct (past it, the scene's mu is tried)
DIRECT_MU_BOXES = 2000


# ------------------------------------------------------------------------------------ best mu

def rho_function(g: Gimbal):
    """x2 piece -> enclosure of max_i |(ci1, ci3)| / ci0 (1/radius; +inf where ci0 may be <= 0)."""
    def rho(x2):
        (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(x2)
        r1 = hypot_ball(c11, c13) / c10 if certainly_positive(c10) else arb("inf")
        r2 = hypot_ball(c21, c23) / c20 if certainly_positive(c20) else arb("inf")
        return r1.max(r2)
    return rho


def _float_candidates(g: Gimbal, pts: list[float]) -> list[int] | None:
    """The indices (in order) where the float-twin rho (:mod:`.float_twin`) at x2 = t x2*, t in ``pts``, is
    within PROPOSAL_WINDOW (relative) of its largest value, or None (no twin, a NaN, a value outside the
    doubles' safe range, or no finite largest value: scan in balls). A proposal: the caller evaluates the
    candidates in balls."""
    fg = float_twin(g)
    if fg is None:
        return None
    vals = []
    for t in pts:
        try:
            r = fg.rho(fg.xs * t)
        except (OverflowError, ZeroDivisionError, ValueError):
            return None
        if r != r or not in_safe_range(r if math.isfinite(r) else 0.0):
            return None
        vals.append(r)
    top = max(vals)
    if not math.isfinite(top):
        return None
    return [i for i, v in enumerate(vals) if v >= top - PROPOSAL_WINDOW * abs(top)]


def _r_sup_search(g: Gimbal, xs: arb, grid: int = 16, steps: int = 24) -> tuple[float, arb]:
    """A float estimate of R_sup(mu) = 1 / max over [0, x2*] of rho, and the point x2 (an exact ball)
    where it was found, from point values of rho (no subdivision): the largest of ``grid`` + 1 equally
    spaced points (scanned by the float twin when the law has one, :func:`_float_candidates`; its near-best
    points in balls), refined by ``steps`` golden-section steps around it. A search heuristic (it may miss a
    narrow peak): it only chooses mu_best and the points of the upper bound's branch and bound; what is
    certified is computed afterwards at those choices."""
    rho = rho_function(g)

    def point(t: float) -> arb:
        return arb(0) if t == 0.0 else xs if t == 1.0 else (xs * arb(t)).mid()

    def val(t: float) -> float:
        r = rho(point(t))
        return float(r.mid()) if r.is_finite() else math.inf
    pts = [j / grid for j in range(grid + 1)]
    near = _float_candidates(g, pts)
    if near is None:
        vals = [val(t) for t in pts]
        j = max(range(len(vals)), key=vals.__getitem__)
    else:
        # only the twin's candidates in balls (the other entries are never read): the first largest, as above
        vals = [-math.inf] * len(pts)
        for i in near:
            vals[i] = val(pts[i])
        j = max(near, key=vals.__getitem__)
    if math.isinf(vals[j]):
        return 0.0, point(pts[j])
    lo, hi = pts[max(j - 1, 0)], pts[min(j + 1, grid)]
    invphi = (math.sqrt(5) - 1) / 2
    t1, t2 = hi - invphi * (hi - lo), lo + invphi * (hi - lo)
    f1, f2 = val(t1), val(t2)
    best, at = max((vals[j], pts[j]), (f1, t1), (f2, t2))
    if j in (0, grid) and ((f1 < f2 < vals[j]) if j == grid else (f2 < f1 < vals[j])):
        # rising towards the end of the range on both probes: the golden steps would keep the end
        # (the common case: the faces x2 = +-x2* bind), so skip them
        return (1 / vals[j] if vals[j] > 0 else 0.0), point(pts[j])
    for _ in range(steps):
        if f1 > f2:
            hi, t2, f2 = t2, t1, f1
            t1 = hi - invphi * (hi - lo)
            f1 = val(t1)
        else:
            lo, t1, f1 = t1, t2, f2
            t2 = lo + invphi * (hi - lo)
            f2 = val(t2)
        best, at = max((best, at), (f1, t1), (f2, t2))
    return (1 / best if best > 0 else 0.0), point(at)


def r_sup(g: Gimbal, xs: arb, rel: str | arb = "1e-10", max_pieces: int = 4000):
    """Enclosure of R_sup(mu) = 1 / max over [0, x2*] of rho (rho is even in x2), to relative width
    about ``rel`` (a subdivision tolerance; at most ``max_pieces`` pieces, then wider)."""
    rho = rho_function(g)
    e = enclose_max(rho, 0, xs, abs_tol=abs(rho(xs)) * arb(rel), max_pieces=max_pieces)
    return 1 / e.ball, e


def rho_lower(g: Gimbal, x2: arb, mu: arb) -> arb:
    """A lower bound of rho(x2, m) = max_i |(ci1, ci3)| / ci0 valid for every m in the ball ``mu``
    (+inf when some ci0 <= 0 certainly: then no disc of positive radius keeps Psi_i > 0).
    Where ci0 may be <= 0 the bound |(ci1, ci3)|.lower / ci0.upper still holds (rho is +inf there)."""
    (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(x2, mu)
    best = arb(0)
    for c0, h in ((c10, hypot_ball(c11, c13)), (c20, hypot_ball(c21, c23))):
        up = c0.upper()
        if certainly_le(up, 0):
            return arb("inf")
        best = best.max((h.lower() / up).lower())
    return best


def _argmax_x2(g: Gimbal, xs: arb, mu: fmpq) -> arb:
    """A point x2 near the maximiser of rho at mu (a search on point values, :func:`_r_sup_search`:
    any point gives a valid bound)."""
    return _r_sup_search(g.with_mu(mu), xs)[1]


def _bound_memo() -> dict:
    """The memo of :func:`r_sup_upper_bound`'s point bounds (a plain dict; the tests swap in one that forgets,
    to compare)."""
    return {}


def r_sup_upper_bound(g: Gimbal, xs: arb, mu_lo: arb, mu_hi: arb, target: arb, max_pieces: int = 2000):
    """A certified upper bound U of sup over mu in [mu_lo, mu_hi] of R_sup(mu), by branch and bound
    over mu: on a piece Mu, max over x2 of rho(x2, m) >= max over a point set P of rho_lower(x, Mu) for
    every m in Mu, so R_sup <= 1 / that on Mu. The piece with the largest bound is first given its own
    maximiser (added to P), then bisected, until the largest bound is <= ``target`` or ``max_pieces``.

    Guarantee: U (returned as an exact ball, its upper end) is >= R_sup(mu) for every mu in the
    interval, whatever the stopping reason; the pieces count says how much work it took."""
    points = [xs * j / 16 for j in range(17)]
    lows: dict = _bound_memo()  # (point index, piece ends) -> rho_lower: a piece re-bounded after a new point
                                # keeps the old points' values (each computed once)

    def bound(a: arb, b: arb) -> arb:
        M = interval(a, b)
        ends = (*ball_key(a), *ball_key(b))
        L = arb(0)
        for i, x in enumerate(points):
            low = lows.get((i, ends))
            if low is None:
                low = lows[(i, ends)] = rho_lower(g, x, M)
            L = L.max(low)
        return (1 / L).upper() if certainly_positive(L) else arb("inf")

    def refine(mid: arb) -> None:
        points.append(_argmax_x2(g, xs, to_fmpq(exact_fraction(mid))))
    pieces, count = best_first_bisection(mu_lo, mu_hi, bound, refine, lambda u: certainly_le(u, target), max_pieces)
    upper = pieces[0][2]
    for _, _, u in pieces:          # the pieces cover [mu_lo, mu_hi]
        upper = upper.max(u)
    return upper, count, [(a, b) for a, b, _ in pieces], points


def _decimal_inside(mu: Fraction, lo: arb, hi: arb) -> str | None:
    """A short exact decimal near ``mu`` certainly inside (lo, hi) (the optimum may sit at an end), or None."""
    for digits in (12, 16, 20, 30, 45, 60):
        for cand in decimal_bounds(exact_ball(to_fmpq(mu)), digits):
            if certainly_lt(lo, exact_ball(to_fmpq(Fraction(cand)))) and certainly_lt(exact_ball(to_fmpq(Fraction(cand))), hi):
                return cand
    return None


def _no_mu_interval(cid: str, lo: arb, hi: arb) -> Claim:
    """The claim over (16) when (16) is not certainly non-empty: refuted when it is certainly empty."""
    empty = certainly_le(hi, lo)
    return make_claim(cid, Status.REFUTED if empty else Status.INCONCLUSIVE,
                      f"the mu interval (16) ({fmt(lo)}, {fmt(hi)}) is " + ("empty: no admissible mu" if empty else
                                                                        "not certainly non-empty"),
                      {"mu_min": fmt(lo, 20), "mu_max": fmt(hi, 20)} if empty else None)


def best_mu_claim(ctx: ClaimContext, quantities: dict[str, arb]) -> Claim:
    g, xs = ctx.g, ctx.xs
    k = ctx.constants()
    lo, hi = k["mu_min"], k["mu_max"]
    if not certainly_lt(lo, hi):
        return _no_mu_interval("best_mu", lo, hi)

    def est(mu: Fraction) -> float:
        return _r_sup_search(g.with_mu(to_fmpq(mu)), xs)[0]
    a = exact_fraction(lo.upper())
    b = exact_fraction(hi.lower())
    invphi = (math.sqrt(5) - 1) / 2
    x1 = b - Fraction(invphi).limit_denominator(10 ** 9) * (b - a)
    x2 = a + Fraction(invphi).limit_denominator(10 ** 9) * (b - a)
    f1, f2 = est(x1), est(x2)
    for _ in range(48):         # golden-section search on point estimates (a heuristic: it only chooses mu)
        if f1 < f2:
            a, x1, f1 = x1, x2, f2
            x2 = a + Fraction(invphi).limit_denominator(10 ** 9) * (b - a)
            f2 = est(x2)
        else:
            b, x2, f2 = x2, x1, f1
            x1 = b - Fraction(invphi).limit_denominator(10 ** 9) * (b - a)
            f1 = est(x1)
        if (b - a) < Fraction(1, 10 ** 14) * b:
            break
    mu_mid = (a + b) / 2
    mu_text = _decimal_inside(mu_mid, lo, hi)
    if mu_text is None:
        return make_claim("best_mu", Status.INCONCLUSIVE,
                          f"no decimal mu certainly inside (16) near the optimum {float(mu_mid):.15g} (the interval is "
                          f"({fmt(lo)}, {fmt(hi)})): raise --maxprec")
    mu_best = to_fmpq(Fraction(mu_text))
    gb = g.with_mu(mu_best)
    # to rel_width, on at most 2000 pieces (R_max keeps 10 digits: a wider R_sup only costs digits)
    R_enc, e = r_sup(gb, xs, rel=exact_ball(ctx.m.rel_width) / 4 + arb(2) ** (-ctx.prec), max_pieces=min(ctx.m.max_pieces, 2000))
    if not (R_enc.is_finite() and certainly_positive(R_enc)):
        return make_claim("best_mu", Status.INCONCLUSIVE, f"R_sup(mu_best) not enclosed: {fmt(R_enc)}", decides=R_enc)
    estimate = max(f1, f2, float(R_enc.mid()))
    quantities["mu_best"] = searched(mu_best)
    quantities["R_sup_at_mu_best"] = R_enc
    sub = ClaimContext(ctx.m, ctx.prec)
    sub.g = gb
    claim = None
    # R_max: R_sup's certified lower end to 10 digits; if Psi's margin is too thin to re-certify by
    # subdivision, 1e-6 (then 1e-3) below it
    for shrink in ("1", "0.999999", "0.999"):
        R_text = decimal_bounds(R_enc.lower() * arb(shrink), 10)[0]
        R_max = to_fmpq(Fraction(R_text))
        claim, info = vdot_claim(sub, exact_ball(R_max), "at mu = mu_best, R = R_max", "psi_test")
        if claim.status is Status.PROVED:
            break
    if claim.status is not Status.PROVED:
        unstate(quantities, "mu_best", "R_sup_at_mu_best")
        return make_claim("best_mu", Status.INCONCLUSIVE, f"R_max could not be re-certified: {claim.reason}",
                          decides=claim.decides)
    quantities["R_max"] = searched(R_max)
    # how good is R_max: a certified upper bound of sup over (16) of R_sup (branch and bound over mu,
    # on the hull of (16), which contains it)
    # over the hull of (16), padded by 4 radii of its ends: a checker's own enclosure of (16) must lie inside
    U, u_pieces, u_cover, u_points = r_sup_upper_bound(g, xs, (lo.lower() - 4 * lo.rad()).lower(),
                                                       (hi.upper() + 4 * hi.rad()).upper(),
                                                       exact_ball(R_max) * (1 + arb(BEST_MU_GAP)), max_pieces=ctx.m.max_pieces)
    ctx.witnesses["best_mu"] = {"vdot_at_R_max": info["record"], "r_sup_cover": pieces_text(e.cover),
                                "r_sup_point": ball_text(e.argpoint), "mu_pieces": pieces_text(u_cover),
                                "x2_points": [ball_text(x) for x in u_points]}
    if not (U.is_finite() and certainly_le(exact_ball(R_max), U)):
        unstate(quantities, "mu_best", "R_sup_at_mu_best", "R_max")
        return make_claim("best_mu", Status.INCONCLUSIVE, f"no finite upper bound of sup R_sup over (16): {fmt(U)}",
                          decides=U)
    # stored as its 15-digit decimal rounded up: a re-derivation on the same pieces at another precision
    # differs in the last bits of arb's radius arithmetic (30-bit radii on wide mu pieces; 1.4e-24 relative
    # seen), so the exact upper end of U would be a bound only this run can confirm
    U_text = decimal_bounds(U, 15)[1]
    U = exact_ball(to_fmpq(Fraction(U_text)))
    quantities["R_sup_upper_bound"] = U
    gap = relative_gap(Fraction(U_text), Fraction(R_text))
    quantities["R_max_relative_gap"] = gap
    return make_claim("best_mu", Status.PROVED,
                  f"mu_best = {mu_text} (chosen by a golden-section search over (16) on point estimates of R_sup, then fixed "
                  f"as an exact decimal: a search result, not proved optimal); at mu_best, R_sup = {fmt(R_enc, 14)} "
                  f"(certified maximum over x2, {e.pieces} pieces); R_max = {R_text} certified: Psi1, Psi2 > 0 on the "
                  f"disc of radius R_max ({info['pieces']} pieces). Certified: R_sup(mu) <= {decimal_bounds(U, 12)[1]} "
                  f"for every mu in (16) (branch and bound over mu, {u_pieces} pieces), so R_max is within a relative "
                  f"{decimal_bounds(gap, 3)[1]} of the largest radius this Psi test can certify",
                  mu_best=mu_text, R_max=R_text, R_sup_upper_bound=decimal_bounds(U, 15)[1],
                  relative_gap=decimal_bounds(gap, 3)[1], float_estimate=f"{estimate:.15g}")


def best_mu_direct_claim(ctx: ClaimContext, quantities: dict[str, arb]) -> Claim:
    g = ctx.g
    k = ctx.constants()
    lo, hi = k["mu_min"], k["mu_max"]
    if not certainly_lt(lo, hi):
        return _no_mu_interval("best_mu_direct", lo, hi)
    a, b = exact_fraction(lo.upper()), exact_fraction(hi.lower())     # certainly inside (16)
    for cold_every in (8, 1):
        # over the hull of (16), padded by 4 radii of its ends (a checker's own enclosure of (16) must lie inside)
        U, n_pieces, cover, points, (best_est, best_mu) = direct_sup_upper_bound(
            g, (lo.lower() - 4 * lo.rad()).lower(), (hi.upper() + 4 * hi.rad()).upper(), arb(DIRECT_MU_GAP),
            max_pieces=min(ctx.m.max_pieces, DIRECT_MU_PIECES), cold_every=cold_every)
        if best_mu is None or not U.is_finite():
            return make_claim("best_mu_direct", Status.INCONCLUSIVE,
                          f"no finite bound of the direct test's radius over (16) ({n_pieces} mu pieces): A <= 0 or B = 0 "
                          "at every point tried", decides=U)
        # the search's optimum may sit in the padding: the nearest point of (16), or its midpoint
        mu_text = _decimal_inside(min(max(best_mu, a), b), lo, hi) or _decimal_inside((a + b) / 2, lo, hi)
        if mu_text is None:
            return make_claim("best_mu_direct", Status.INCONCLUSIVE,
                          f"no decimal mu certainly inside (16) near the search's optimum {float(best_mu):.15g}: raise --maxprec")
        mu = to_fmpq(Fraction(mu_text))
        known = piece_upper(g, exact_ball(mu), points)            # certified, at mu_direct: the radius is at most this
        d = certify_direct(g.with_mu(mu), min(ctx.m.max_pieces, DIRECT_MU_BOXES),
                           float(known.lower()) if known.is_finite() else None)
        # a warm-started point search stuck in a local minimum overestimates the radius (and stops the branch
        # and bound early at a poor mu): the whole-grid search at mu_direct tells; then every point is searched cold
        if not (math.isfinite(d.est) and d.est < best_est * (1 - 1e-6)):
            break
    c = g.c
    chosen = ("chosen by a branch and bound over (16) on float point searches, then fixed as an exact decimal: a "
              "search result, not proved optimal")
    if (d.cert is None or d.cert.status is not Status.PROVED) and certainly_lt(lo, c.mu) and certainly_lt(c.mu, hi):
        # near an end of (16) the radius may fall steeply on a narrow set of (x2, t) the searches miss (the
        # certification then fails): the scene's own mu, inside (16), is a valid choice too (the gap says how good)
        exact = ctx.m.params.get("mu")
        if exact is not None and exact.is_rational:
            frac = exact.rational
            mu_text = f"{frac.numerator}/{frac.denominator}" if frac.denominator != 1 else str(frac.numerator)
            try:
                if Fraction(exact.text) == frac:
                    mu_text = exact.text
            except (ValueError, ZeroDivisionError):
                pass
            mu = to_fmpq(frac)
            chosen = (f"the scene's own mu: the searched optimum {float(best_mu):.12g} could not be certified within "
                      f"{min(ctx.m.max_pieces, DIRECT_MU_BOXES)} boxes of (x2, t)")
            # the same computation as vdot_direct's (done once: at the scene's mu, g is the scene's gimbal)
            d = ctx.memo("direct at the scene's mu", lambda: certify_direct(g, ctx.m.max_pieces))
    if d.cert is None or d.cert.status is not Status.PROVED:
        why = d.cert.reason if d.cert is not None else f"the search found no positive radius (~{d.est:.6g})"
        return make_claim("best_mu_direct", Status.INCONCLUSIVE,
                      f"at mu_direct = {mu_text}, A - R |B| > 0 not certified at R = {d.R_text or '-'}: {why}; try a "
                      "larger max_pieces or --maxprec")
    R = searched(Fraction(d.R_text))
    # stored as its 15-digit decimal rounded up (as best_mu's bound: a re-derivation at another precision
    # differs in arb's last radius bits)
    U_text = decimal_bounds(U, 15)[1]
    U = exact_ball(to_fmpq(Fraction(U_text)))
    if not certainly_le(R, U):      # R <= R_dsup(mu_direct) <= U: both certified, so this cannot happen
        raise AssertionError(f"best_mu_direct: certified R {d.R_text} above the certified bound {U}")
    gap = relative_gap(Fraction(U_text), Fraction(d.R_text))
    quantities.update({"mu_direct": searched(mu), "R_direct_max": R, "R_direct_sup_upper_bound": U,
                       "R_direct_max_relative_gap": gap})
    ctx.witnesses["best_mu_direct"] = {"mu": mu_text, "R": d.R_text, "boxes": [b.to_json() for b in d.cert.leaves],
                                       "mu_pieces": pieces_text(cover),
                                       "points": [[str(u), str(s)] for u, s in points]}
    compare = []
    for name, what in (("R_max", "the Psi test's best radius R_max"), ("R_direct", "the direct test at the scene's mu")):
        if name in quantities and certainly_positive(quantities[name]):
            compare.append(f"{decimal_bounds(R / quantities[name], 6)[0]} times {what}")
    return make_claim("best_mu_direct", Status.PROVED,
                  f"mu_direct = {mu_text} ({chosen}); at mu_direct, A - R |B| > 0 certified at "
                  f"R_direct_max = {d.R_text} on {len(d.cert.leaves)} boxes of (x2, t) (search estimate {d.est:.10g}). "
                  f"Certified: R_dsup(mu) <= {decimal_bounds(U, 12)[1]} for every mu in (16) (branch and bound over "
                  f"mu, {n_pieces} pieces, {len(points)} points of (x2, t)), so R_direct_max is within a relative "
                  f"{decimal_bounds(gap, 3)[1]} of the largest radius with Vdot <= 0 on the disc cylinder at any "
                  f"admissible mu" + (f"; R_direct_max is {' and '.join(compare)}" if compare else ""),
                  mu_direct=mu_text, R_direct_max=d.R_text, R_direct_sup_upper_bound=decimal_bounds(U, 15)[1],
                  relative_gap=decimal_bounds(gap, 3)[1], boxes=len(d.cert.leaves), mu_pieces=n_pieces)
