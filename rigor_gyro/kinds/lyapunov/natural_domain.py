"""The natural sublevel estimate of V (7): c_max over the x2 range where V is positive definite, decoupled
from the paper's x2*.

V > 0 off the origin on a range |x2| <= X exactly when S > 0, f(x)/x > 0 and psi > 0 on (0, X] (the
decomposition V = phi(x2) + S/2 (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2, phi = (F/S) psi, of
:mod:`rigor_gyro.kinds.lyapunov.model`). Nothing in it needs x2* (nor m, M, p, (16)-(18)), so the range is
taken as large as can be certified: X = pi/2 (1 - 2^-j) for the largest j of ``POSITIVITY_J`` for which the
three bisections succeed. X cannot reach pi/2: at cos x2 = 0, h = H cos x2 / B0 = 0, so on that slice V does
not depend on x1 (no sublevel set reaching it is bounded) and (-f(pi/2)/k, pi/2, 0) is an equilibrium of (2).

c_max(X) is defined as in :mod:`rigor_gyro.kinds.lyapunov.sublevel` with X for x2*: the infimum of V over
N_X = {Vdot >= 0, (x1, x3) != 0, |x2| <= X} and over the faces |x2| = X. It is bounded by three certified
pieces:

* a band: phi(x2) > n_upper on X_c <= |x2| <= X (1-D bisection; phi = min of V at fixed x2), so V > n_upper
  there for every (x1, x3): neither the band nor the faces bind, and c_max(X') is the same number for
  every X' in [X_c, X]. X_c is a multiple of 1/1024 just above the float root of phi = estimate.
* below: a best-first branch and bound over (x2, t) with |x2| <= X_c (x2 = u X_c, t = pi s) of
  :func:`natural_lower_bound`: the polar bound of :func:`~rigor_gyro.kinds.lyapunov.model.sublevel_lower_bound`,
  phi(x2) >= its lower end, and where the constraint is active (B of one sign and the vertex of the quadratic
  V(r) certainly outside the half-line r B <= -A) the exact minimum over that half-line,
  W(x2, t) = alpha + beta r0 + gamma r0^2 with r0 = -A/B, in a mean-value (centred) form in (u, s): its
  overestimation is quadratic in the box width at the minimiser on {Vdot = 0}, which is what brings the
  bound to a relative gap of 1e-6 (the polar bound alone stalls 18 % low).
* above: V at a certified point of N (Vdot > 0 by automatic differentiation, |x2| <= X_c).
* the x2 extent: phi < c_lower on [0, E] (1-D bisection), so the component of {V < c_lower} reaches
  |x2| = E; with the band it lies in |x2| < X_c.

Cost on the paper's example (64 bits): about 2 s and 1e4 boxes for the 1e-6 bracket [77.2245103,
77.2245866] (the issue's independent value 77.22458657 inside), most of them near the minimiser, which sits
in a flat valley along x2 (W varies by 0.2 % between x2 = 1.00 and the band at 1.14); hence opt-in.
A faces-binding range (phi below the level up to X, e.g. H = 1e6) is not handled: the claim is undecided.

Precision: the current working precision. The bounds are exact decimals (lower rounded down, upper up).
Fails when: no j of ``POSITIVITY_J`` certifies V > 0, the band is not certified, no point of N is found, or the
box budget runs out before a positive lower bound (each leaves the claim undecided with the reason); a
budget spent after a positive bound only widens the bracket (``gap_reached`` says so).
"""
from __future__ import annotations

import dataclasses

import math
from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_le, certainly_negative, certainly_positive, decimal_bounds, exact_fraction
from ...core.boxes import Box
from ...core.exact import Exact
from ...core.stored import pieces_text
from ...core.subdivision import certify_positive, lower_bound_on_box
from .model import Dual, Gimbal
from .polar_forms import DIRECT_DOMAIN, sublevel_lower_bound, symmetric_in_x2, v_polar, vdot_polar
from .sublevel import certified_point_of_n, search_over_n

__all__ = ["NaturalSublevel", "natural_sublevel", "natural_lower_bound", "with_range", "range_exact",
           "positivity_functions", "exact_range", "band_function", "NATURAL_GAP", "POSITIVITY_J", "BAND_STEP", "NATURAL_BOX_BUDGET"]

#: X = pi/2 (1 - 2^-j): the j tried, largest first (the first whose positivity is certified is used)
POSITIVITY_J = (30, 20, 12, 8, 4)
#: below a certified failure at w: X = w (1 - 2^-k), the k tried in this order
SHRINK_K = (20, 12, 8, 5, 3, 2, 1)
#: X_c is a multiple of this, the first above the float root of phi = estimate (times 1 + BAND_MARGIN)
BAND_STEP = Fraction(1, 1024)
BAND_MARGIN = 0.002
#: the relative gap of the bracket aimed at when the scene option natural_sublevel does not set one
NATURAL_GAP = "1e-6"
#: the box budget of the branch and bound over (x2, t) (the scene's max_pieces caps it further)
NATURAL_BOX_BUDGET = 40000


def range_exact(j: int) -> Exact:
    """X = pi/2 (1 - 2^-j) as an exact number (a rational multiple of pi)."""
    return Exact(Fraction(1, 2) - Fraction(1, 2 ** (j + 1)), 1, f"pi/2 (1 - 2^-{j})")


def exact_range(text: str) -> Exact:
    """The stored text of X back to the exact number: "pi/2 (1 - 2^-j)" or a rational "p/q"."""
    if text.startswith("pi/2 (1 - 2^-") and text.endswith(")"):
        j = int(text[len("pi/2 (1 - 2^-"):-1])
        if not 1 <= j <= 200:
            raise ValueError(f"j = {j} out of range")
        return range_exact(j)
    q = Fraction(text)
    return Exact(q, 0, str(q))


def with_range(g: Gimbal, X: Exact) -> Gimbal:
    """The same gimbal with x2* replaced by X (the polar domain u in [-1, 1] then means |x2| <= X); every
    other field as it is (dataclasses.replace: no parameter read by name, see test_lyapunov_boxes)."""
    return dataclasses.replace(g, x2_star=X)


def positivity_functions(g: Gimbal) -> dict:
    """The three functions whose positivity on (0, X] is V > 0 off the origin for |x2| <= X (all even)."""
    return {"S": g.S, "f_over_x": lambda x: g.law.f_over_x(g.c.a, x), "psi": g.psi}


def band_function(g: Gimbal, level: arb):
    """x2 -> phi(x2) - level (phi = min over (x1, x3) of V at fixed x2; even in x2)."""
    return lambda x: g.phi(x) - level


def _q(fr: Fraction) -> arb:
    return arb(fmpq(fr.numerator, fr.denominator))


def natural_lower_bound(g: Gimbal, enough: arb | None = None):
    """The box function {u, s} -> a ball whose lower end is <= V(r cos t, x2, r sin t) for every x2 = u x2*,
    t = pi s in the box (x2* of ``g``: here X_c) and every real r != 0 with Vdot >= 0 there: the largest of
    three lower ends, each a valid bound over the box:

    * :func:`~rigor_gyro.kinds.lyapunov.model.sublevel_lower_bound` (the closed-form half-line bound);
    * phi(x2) over the box's x2 (V >= phi at fixed x2 for every (x1, x3));
    * where B has one sign, gamma > 0 and B (r_v - r0) > 0 certainly (r0 = -A/B, r_v = -beta/(2 gamma): the
      vertex of the convex quadratic V(r) lies outside the half-line {A + r B <= 0} = {r: B (r - r0) <= 0}),
      V's minimum over that half-line is W = alpha + beta r0 + gamma r0^2 exactly at each point; W is
      enclosed over the box directly and in the mean-value form W(m) + W_u(box) (U - m_u) + W_s(box) (S - m_s)
      (derivatives by forward-mode Dual numbers over the box: W is smooth there since B != 0), intersected.

    ``enough`` (optional, a level): once a cheaper bound reaches it, the centred form is skipped (each
    return is a valid lower bound either way; the prover passes its target, the checker the stated
    c_max_lower, so a box that the prover left at or above its target is confirmed by the same cheap bound).

    Guarantee: a lower bound over the box, never an enclosure of the minimum. Valid with u of either sign
    and t in [0, pi] (r of either sign covers every direction of (x1, x3))."""
    naive = sublevel_lower_bound(g)
    xs, pi = g.c.x2_star, arb.pi()

    def W(U, S):
        X, T = xs * U, pi * S
        A, B = vdot_polar(g, X, T)
        al, be, ga = v_polar(g, X, T)
        r0 = -A / B
        return al + be * r0 + ga * r0 * r0

    def better(low: arb, cand: arb) -> arb:
        c = cand.lower()
        if not c.is_finite():
            return low
        return c if (not low.is_finite() or c > low) else low

    def f(box: dict) -> arb:
        U, S = box["u"], box["s"]
        low = naive(box).lower()
        if float(low) == math.inf:      # +inf: no point of {Vdot >= 0} above the box
            return low
        X, T = xs * U, pi * S
        low = better(low, g.phi(X))
        if enough is not None and low.is_finite() and low >= enough:
            return low
        A, B = vdot_polar(g, X, T)
        al, be, ga = v_polar(g, X, T)
        if (certainly_positive(B) or certainly_negative(B)) and certainly_positive(ga):
            r0 = -A / B
            if certainly_positive(B * (-be / (2 * ga) - r0)):
                d = al + be * r0 + ga * r0 * r0
                low = better(low, d)
                if enough is not None and low.is_finite() and low >= enough:
                    return low
                if not (U.rad().is_zero() and S.rad().is_zero()):
                    um, sm = arb(U.mid()), arb(S.mid())
                    mv = W(um, sm) + W(Dual(U, arb(1)), S).d * (U - um) + W(U, Dual(S, arb(1))).d * (S - sm)
                    if mv.is_finite():
                        d = d.intersection(mv) if d.overlaps(mv) else mv
                low = better(low, d)
        return low
    return f


@dataclass
class NaturalSublevel:
    """Certified c_lower <= c_max(X) <= c_upper (exact decimals) and the pieces that certify them."""

    X: Exact | None = None               # the natural range |x2| <= X (pi/2 (1 - 2^-j), or a rational)
    #: (w, name): a point of (0, pi/2) where the function ``name`` is certainly <= 0 (None: only pi/2 limits X)
    limit: tuple | None = None
    positivity: dict = field(default_factory=dict)      # name -> pieces of [0, X] where it is > 0
    band_lo: Fraction | None = None      # X_c
    band: list = field(default_factory=list)            # pieces of [X_c, X] where phi > n_upper
    #: E: phi < c_lower on [0, E] (pieces ``reach_pieces``): the component of {V < c_lower} reaches |x2| = E
    reach: Fraction | None = None
    reach_pieces: list = field(default_factory=list)
    c_lower: str | None = None
    c_upper: str | None = None
    point: tuple | None = None
    leaves: list = field(default_factory=list)
    boxes: int = 0
    gap: str = "1e-6"
    gap_reached: bool = False
    estimate: float = math.nan
    at: tuple = (math.nan, math.nan)
    reason: str = ""
    bound: arb | None = None
    pieces: int = 0


def _certify_range(g: Gimbal, X: Exact, max_pieces: int, out: NaturalSublevel) -> tuple[bool, arb | None, str]:
    """(certified, a point w in (0, X] where one function is <= 0 (certified) or None, its name)."""
    rec: dict = {}
    for name, fn in positivity_functions(g).items():
        kept: list = []
        r = certify_positive(fn, 0, X.ball(), max_pieces=max_pieces, record=kept)
        out.pieces += r.pieces
        if r.status.name == "REFUTED":
            return False, r.witness, name
        if r.status.name != "PROVED":
            return False, None, name
        rec[name] = pieces_text(kept)
    out.X, out.positivity = X, rec
    return True, None, ""


def _positive_range(g: Gimbal, max_pieces: int, out: NaturalSublevel) -> bool:
    """The largest X tried on which V > 0 is certified: X = pi/2 (1 - 2^-j), j in POSITIVITY_J; where a
    function is certified <= 0 at some w, X = w' (1 - 2^-k) below it instead (w' a rational <= w), and
    ``out.limit`` records w: no range reaching |x2| = w has V positive definite through the test."""
    for j in POSITIVITY_J:
        ok, w, name = _certify_range(g, range_exact(j), max_pieces, out)
        if ok:
            return True
        if w is not None and w.is_finite() and certainly_positive(w):
            out.limit = (w, name)
            wq = exact_fraction(w.lower())
            for k in SHRINK_K:
                Xq = wq * (1 - Fraction(1, 2 ** k))
                if Xq > 0 and _certify_range(g, Exact(Xq, 0, str(Xq)), max_pieces, out)[0]:
                    return True
            return False
    return False


def _band_start(g: Gimbal, est: float, X: float) -> Fraction | None:
    """A search: the multiple of BAND_STEP just above the last float x in [0, X) with phi(x) <= est (1 +
    BAND_MARGIN), scanning down from X (a heuristic; the band is certified afterwards)."""
    top = est * (1 + BAND_MARGIN)
    n = int(Fraction(X) / BAND_STEP)
    for k in range(n, 0, -1):
        x = float(k * BAND_STEP)
        if float(g.phi(arb(x)).mid()) <= top:
            return (k + 1) * BAND_STEP if (k + 1) * BAND_STEP < Fraction(X) else None
    return None


def natural_sublevel(g: Gimbal, max_pieces: int, gap: str = "1e-6") -> NaturalSublevel:
    """Certified bounds of c_max over the natural range (see the module docstring), at the current precision."""
    out = NaturalSublevel(gap=gap)
    if not _positive_range(g, max_pieces, out):
        out.reason = ("V > 0 (S, f/x, psi > 0) was not certified on [0, pi/2 (1 - 2^-j)] for any j in "
                      f"{POSITIVITY_J}" + (f", nor below x2 = {out.limit[0].mid()} where {out.limit[1]} <= 0"
                                           if out.limit else ""))
        return out
    Xe = out.X
    Xb = Xe.ball()
    gX = with_range(g, Xe)
    est, u, s, r = search_over_n(gX)
    if not math.isfinite(est):
        out.reason = "the search found no point of {Vdot >= 0} over the natural range"
        return out
    xc = _band_start(g, est, float(Xb.mid()))
    if xc is None:
        out.reason = f"phi stays below the search's level {est:.10g} up to X: the faces |x2| = X bind (not handled here)"
        return out
    gC = with_range(g, Exact(xc, 0, str(xc)))
    xcb = _q(xc)
    found = certified_point_of_n(gX, u, s, r) if math.isfinite(r) and r != 0 else None
    if found is None or not certainly_le(abs(found[0][1]), xcb):
        est, u, s, r = search_over_n(gC)          # the minimiser beyond X_c (not expected: phi > est there)
        found = certified_point_of_n(gC, u, s, r) if math.isfinite(est) and math.isfinite(r) and r != 0 else None
    else:
        u = float((found[0][1] / xcb).mid())
    out.estimate, out.at = est, (u, s)
    if found is None or not found[1].is_finite():
        out.reason = "no certified point of {Vdot > 0} was found near the search's minimiser"
        return out
    out.point = found[0]
    out.c_upper = decimal_bounds(found[1].upper(), 15)[1]
    n_up = _q(Fraction(out.c_upper))
    kept: list = []
    band = certify_positive(band_function(g, n_up), _q(xc), Xb, max_pieces=max_pieces, record=kept)
    out.pieces += band.pieces
    if band.status.name != "PROVED":
        out.reason = f"phi > {out.c_upper} on [{xc}, X] was not certified ({band.reason})"
        return out
    out.band_lo, out.band = xc, pieces_text(kept)
    target = n_up * (1 - arb(gap))
    lb = symmetric_in_x2(gC, natural_lower_bound(gC, target.lower()))
    best = lower_bound_on_box(lb, Box.of(DIRECT_DOMAIN), target, max_pieces=min(max_pieces, NATURAL_BOX_BUDGET))
    out.boxes, out.bound = best.boxes, best.bound
    if not (best.bound.is_finite() and certainly_positive(best.bound)):
        out.reason = (f"no positive lower bound of V over {{Vdot >= 0, (x1, x3) != 0, |x2| <= {xc}}} was certified "
                      f"(best {best.bound} on {best.boxes} boxes)")
        return out
    out.leaves = best.leaves
    out.gap_reached = bool(best.reached)
    lo = decimal_bounds(best.bound, 15)[0]
    # never above the band's level (then the band would not be shown not to bind): it is not, since
    # bound <= V(point) <= n_upper; kept explicit for the checker's comparison
    out.c_lower = lo if certainly_le(_q(Fraction(lo)), n_up) else out.c_upper
    _reach(g, xc, max_pieces, out)
    return out


def _reach(g: Gimbal, xc: Fraction, max_pieces: int, out: NaturalSublevel) -> None:
    """A certified lower end of the set's x2 extent: E, a multiple of BAND_STEP just below the float root of
    phi = c_lower, with c_lower - phi > 0 on [0, E] certified (then every slice {V(., x2, .) < c_lower},
    |x2| <= E, is a non-empty ellipse whose centre moves continuously with x2: their union is connected,
    contains 0, and reaches |x2| = E). Left unset when the certification fails (nothing is claimed)."""
    cl = _q(Fraction(out.c_lower))
    top = float(cl.mid()) * (1 - BAND_MARGIN)
    k = int(xc / BAND_STEP)
    while k > 0 and float(g.phi(_q(k * BAND_STEP)).mid()) >= top:
        k -= 1
    if k <= 0:
        return
    kept: list = []
    r = certify_positive(lambda x: cl - g.phi(x), 0, _q(k * BAND_STEP), max_pieces=max_pieces, record=kept)
    out.pieces += r.pieces
    if r.status.name == "PROVED":
        out.reach, out.reach_pieces = k * BAND_STEP, pieces_text(kept)
