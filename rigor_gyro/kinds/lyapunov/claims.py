"""Attraction estimate of a gimbal gyroscope with viscous friction (Agafonov et al. 2013): scene kind
``lyapunov``.

Model: system (2) and Lyapunov function (7) of :mod:`rigor_gyro.kinds.lyapunov.model`, moment law from
:mod:`rigor_gyro.kinds.lyapunov.moments` (the scene names it). Claims, each decided in Arb ball arithmetic over the
exact parameters:

* ``constants``: A0, B0, C0 exactly; m, M certified maxima over |x2| <= x2* (branch and bound; the
  0/0 of M at x2 = 0 enclosed through f(x)/x); p, k_min, the mu interval (16), R1 (13), R2 (14), R.
* ``damping_condition``: k > p A0 / H (18) and mu inside (16).
* ``vdot_nonpositive``: Vdot <= 0 on region (17) (|x2| <= x2*, x1^2 + x3^2 <= R^2): by the Psi test of
  ``psi_test``, else by the direct test of ``vdot_direct`` at R (A - R |B| > 0 on (x2, t) boxes). Refuted only
  with a certified point of the region where grad V . f > 0 (evaluated by automatic differentiation, not
  through the Psi form): the failure of a sufficient test is never a refutation.
* ``psi_test``: Psi1, Psi2 > 0 on region (17), Vdot = -Psi1 x1^2 - Psi2 x3^2: over an x2 piece X the minimum
  of Psi_i over the disc is ci0 - R sqrt(ci1^2 + ci3^2), enclosed on X; Psi1, Psi2 > 0 by subdivision of
  [-x2*, x2*]. Vdot vanishes on the x2 axis (x1 = x3 = 0) exactly by the factored form. Refuted with a
  certified point of the region where a Psi_i <= 0 (or where Vdot > 0).
* ``v_positive``: V > 0 off the origin for |x2| <= x2*, through the exact decomposition
  V = phi(x2) + 1/2 S (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2 (see :mod:`rigor_gyro.kinds.lyapunov.model`): certified
  f1 > mu (so S > 0), f(x)/x > 0 (so F > 0 off 0) and psi > 0 (so phi > 0 off 0; psi is finite at
  x2 = 0, the removable singularity of phi/F). This is necessary and sufficient, sharper than (9).
* ``invariant_estimate``: c* = min of V over the boundary of region (17) (faces |x2| = x2* in closed form,
  the cylinder x1^2 + x3^2 = R^2 by 2-D branch and bound), so {x in (17): V < c*} is positively
  invariant and (LaSalle, x2 f(x2) > 0) inside the domain of attraction; its certified extents.
* ``largest_sublevel``: bounds of c_max, the infimum of V over {Vdot >= 0, (x1, x3) != 0, |x2| <= x2*} and the
  faces |x2| = x2* (:mod:`rigor_gyro.kinds.lyapunov.sublevel`): the largest sublevel set of V that is an
  estimate without region (17); refuted when c_max <= 0 is certified.
* ``natural_sublevel`` (opt-in, ``OPT_IN_CLAIMS``: a scene names it in claims_only; option
  ``natural_sublevel`` = the relative gap aimed at, default 1e-6): V > 0 on the largest certified range
  |x2| <= X (below pi/2, independent of x2*), c_max over it bracketed by branch and bound with a centred form
  at the active constraint, the band where phi > c_max_upper and the set's x2 extent
  (:mod:`rigor_gyro.kinds.lyapunov.natural_domain`); compared with c*, c_max(x2*) and the paper's R.
* ``best_mu``: R_sup(mu) = min over x2 of min_i ci0 / |(ci1, ci3)| is the supremum of the radii for
  which the Psi test of ``psi_test`` holds. A search picks mu_best in (16) (not proved
  optimal); R_max is certified at mu_best, and a branch and bound over mu certifies an upper bound of
  sup over (16) of R_sup, so the relative gap says how close R_max is to the best this test can do.

Precision: the caller's, escalated by :mod:`rigor_gyro.prover` until every claim is decided and the
maxima m, M have relative width <= ``rel_width`` (option, default 1e-15).

Fails when: parameters are outside the model (A0 <= C0, x2* not in (0, pi/2), k, mu, H, a not
positive, unknown moment, missing names): ParameterError naming the parameter (exit 2). A mu outside
(16) or k below k_min is not bad input: ``damping_condition`` is refuted.

Reference: Agafonov S. A., Kostyushko I. A., Shvydka S. P., Kuzemko A. V., On the stability of steady
motion of a gyroscope in gimbals, 2013 (seed 000 in shared/seeds).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import (ball_key, certainly_gt, certainly_le, certainly_lt, certainly_positive, decimal_bounds,
                           Quantity, exact_fraction, interval, rel_width_at_most, stored_hull,
                           working_precision)
from ...core.audit import check_printed
from ...core.errors import ParameterError
from ...core.exact import (Exact, option_count, option_number, parse_options, parse_parameters,
                           require_rational)
from ...core.outcome import Claim, Status
from ...core.stored import ball_text, pieces_text
from ...core.boxes import Box
from ...core.subdivision import best_first_bisection, certify_positive, certify_positive_on_box, enclose_max
from .. import Attempt, Phases
from .equilibria import equilibria
from .direct_mu import direct_point_search, direct_sup_upper_bound, piece_upper
from .direct_face import face_margin, face_polish
from .float_twin import float_twin, in_safe_range
from .search import PROPOSAL_WINDOW
from .sublevel import GAP as SUBLEVEL_GAP, largest_sublevel
from .natural_domain import NATURAL_GAP, natural_sublevel
from .trajectory_claims import (TRAJECTORY_CLAIMS, TRAJECTORY_OPTIONS, initial_point_claim, parse_initial_point,
                                paving_claim, region_not_invariant_claim)
from .model import (DIRECT_DOMAIN, Gimbal, c_star_lower, c_star_upper, certify_psi_test, certify_vdot_nonpositive,
                    closed_form_constants, cylinder_lower_bound, damping_margin, faces_minimiser_inside, hypot_ball,
                    mean_value_enclosure, rational_points_inside, slice_extent, slice_in_region, symmetric_in_x2, vdot_polar)
from .moments import MOMENTS
from .moment_scene import KNOWN as KNOWN_MOMENTS, scene_moment_law
from .moment_expr import QuadratureBudgetSpent, quadrature_budget
from .paper import PAPER_SCHEMA, audit as audit_paper

__all__ = ["CLAIMS", "OPT_IN_CLAIMS", "ALL_CLAIMS", "PARAMETERS", "LyapunovModel", "validate", "attempt", "gimbal_from_parameters", "maximum_M"]

PARAMETERS = {"A": "equatorial moment of inertia of the rotor", "C": "polar moment of inertia of the rotor",
              "A1": "inner ring", "B1": "inner ring", "C1": "inner ring", "A2": "outer ring about its axis",
              "H": "cyclic constant (angular momentum)", "k": "viscous friction on the outer axis",
              "a": "amplitude of the moment f", "x2_star": "half-width of the x2 range, in (0, pi/2)",
              "mu": "parameter of V (7)", "moment": "moment law: " + ", ".join(sorted(MOMENTS))}
RATIONAL = ("A", "C", "A1", "B1", "C1", "A2", "H", "k", "a", "mu")
#: best_mu: branch and bound over mu stops once its upper bound is within this relative gap of R_max
BEST_MU_GAP = "1e-6"    # escalation beyond this only repeats the same subdivision (see attempt)
#: best_mu_direct: the branch and bound over mu stops once its bound is within this relative gap of the
#: search's best estimate (R_direct_max is certified FACE_MARGIN below the estimate where the minimiser is on a
#: face, else 4e-7: the gap stays below 1e-9, else below 1e-6)
DIRECT_MU_GAP = "5e-10"
DIRECT_MU_PIECES = 400
#: the box budget of the direct test at the searched mu_direct (past it, the scene's mu is tried)
DIRECT_MU_BOXES = 2000
OPTIONS = {"rel_width": "1e-15", "R": "", "max_pieces": "20000", "natural_sublevel": "", **TRAJECTORY_OPTIONS}
MAX_PIECES_LIMIT = 1_000_000

#: the numbers a report's summary opens with (quantity name -> what it is), in this order
HEADLINE = {"R_used": "radius R of region (17) used", "c_star": "level c* of the invariant estimate {V < c*}",
            "c_max_lower": "certified lower bound of the largest sublevel level c_max",
            "natural_c_max_lower": "certified lower bound of c_max over the natural x2 range where V > 0 (opt-in claim)",
            "R_direct": "radius with Vdot < 0 certified directly (scene's mu)",
            "R_direct_upper": "Vdot > 0 at a certified point of this radius",
            "R_max": "certified radius R_max at mu_best (Psi test)", "mu_best": "mu_best (a search result)",
            "R_sup_upper_bound": "no mu in (16) gives the Psi test a radius above this",
            "R_direct_max": "certified radius with Vdot < 0 at mu_direct (direct test)",
            "mu_direct": "mu_direct (a search result)",
            "R_direct_sup_upper_bound": "no mu in (16) gives Vdot <= 0 on a disc cylinder of larger radius",
            "k_min": "k_min = p A0 / H of (18)", "damping_margin": "design margin in k: min(k/k_min, k/(mu A0)) - 1",
            "cylinder_margin_lower": "c* against the region's side: V >= (1 + this) c* on x1^2 + x3^2 = R^2 "
                                     "(a certified lower bound)"}

CLAIMS = {
    "constants": "Enclosures of A0, B0, C0, m, M, p, k_min = p A0/H, the mu interval (p/H, k/A0), R1, R2 and "
                 "R = min(R1, R2); m and M are certified maxima over |x2| <= x2*.",
    "damping_condition": "k > p A0 / H (18) and p/H < mu < k/A0 (16).",
    "vdot_nonpositive": "Vdot = grad V . f <= 0 on region (17) (|x2| <= x2*, x1^2 + x3^2 <= R^2), = 0 only on "
                        "x1 = x3 = 0: certified by the Psi test (Psi1 > 0 and Psi2 > 0 there, see psi_test) or, where "
                        "that test does not decide, by the direct test at R (A - R |B| > 0 on (x2, t) boxes covering "
                        "the domain, see vdot_direct); refuted only by a certified point of the region where Vdot > 0.",
    "psi_test": "Psi1 > 0 and Psi2 > 0 on region (17) (|x2| <= x2*, x1^2 + x3^2 <= R^2), where Vdot = -Psi1 x1^2 - "
                "Psi2 x3^2: the paper's sufficient test for Vdot <= 0 there.",
    "vdot_direct": "Vdot < 0 on |x2| <= x2*, 0 < x1^2 + x3^2 <= R_direct^2 (so Vdot <= 0 there, = 0 only on "
                   "x1 = x3 = 0), certified on Vdot itself (polar form Vdot = -r^2 (A + r B): A - R_direct |B| > 0 "
                   "on boxes covering the (x2, t) domain), not through Psi1 > 0 and Psi2 > 0 separately; and Vdot > 0 "
                   "at a certified point with |x2| <= x2* at radius R_direct_upper, so the largest radius for which "
                   "Vdot <= 0 on the whole disc cylinder lies in [R_direct, R_direct_upper] (at the scene's mu; "
                   "R_direct is a search result, fixed as a decimal, and certified).",
    "v_positive": "V > 0 for |x2| <= x2*, (x1, x2, x3) != 0.",
    "invariant_estimate": "c* = min of V over the boundary of region (17) is enclosed and positive: "
                          "{x in (17): V(x) < c*} is positively invariant and lies in the domain of attraction.",
    "largest_sublevel": "c_max, the infimum of V over the set where Vdot >= 0 with (x1, x3) != (0, 0) and |x2| <= x2*, "
                        "and over the faces |x2| = x2*, is positive and lies in [c_max_lower, c_max_upper]: for every "
                        "c <= c_max_lower the connected component of {V < c} that contains 0 lies in |x2| < x2*, and "
                        "Vdot <= 0 on it with equality only where x1 = x3 = 0 (with v_positive and x2 f(x2) > 0, "
                        "LaSalle: positively invariant, bounded, inside the domain of attraction; no region (17) or "
                        "radius R is used). Each part is bounded separately: over {Vdot >= 0, (x1, x3) != 0} in "
                        "[vdot_level_lower, vdot_level_upper] (branch and bound over (x2, t) in polar form below, V at "
                        "a certified point where Vdot > 0 above), over the faces by phi(+-x2*) in closed form; the "
                        "reason says which part binds and compares c_max with c*.",
    "equilibria": "The equilibria of system (2) with |x2| <= pi are exactly the points listed in the reason (x3 = 0, "
                  "x1 = -f(x2)/k, and f(x2) = 0, cos x2 = 0 or k H + C0 sin x2 f(x2) = 0; every root isolated on a "
                  "certified cover of [-pi - 1/64, pi + 1/64]), each with the eigenvalues of its linearisation and its "
                  "stability (asymptotically stable: every real part < 0; unstable: one > 0; not hyperbolic: at "
                  "cos x2 = 0, eigenvalues -k/(A0 - C0) and +-i w, real part exactly 0, so linearisation decides "
                  "nothing), and whether it lies in the estimate {V < c_set} of invariant_estimate.",
    "best_mu": "At mu = mu_best (a decimal in (16) chosen by a search, not proved optimal), Psi1 > 0 and Psi2 > 0 "
               "on the disc of radius R_max, so Vdot <= 0 there (the test of psi_test); and R_sup(mu) <= R_sup_upper_bound for "
               "every mu in (16), where R_sup(mu) is the supremum of the radii for which Psi1, Psi2 > 0 on the disc: "
               "R_max is within R_max_relative_gap of the largest radius this test certifies at any admissible mu.",
    "best_mu_direct": "At mu = mu_direct (a decimal in (16) chosen by a search, not proved optimal), Vdot < 0 on "
                      "|x2| <= x2*, 0 < x1^2 + x3^2 <= R_direct_max^2 (the direct test of vdot_direct, at that mu); and "
                      "R_dsup(mu) <= R_direct_sup_upper_bound for every mu in (16), where R_dsup(mu) is the supremum of "
                      "the radii R with Vdot <= 0 on |x2| <= x2*, x1^2 + x3^2 <= R^2: R_direct_max is within "
                      "R_direct_max_relative_gap of the largest such radius at any admissible mu.",
}


#: claims a scene must ask for by name (claims_only): not in the default list (CLAIMS), since they cost seconds
OPT_IN_CLAIMS = {
    "natural_sublevel": "V > 0 off the origin for |x2| <= X (X = pi/2 (1 - 2^-j), or a rational below a point where that test fails; S, f/x, psi > 0 on (0, X], "
                        "independent of x2*, m, M and (16)-(18)); c_max(X), the infimum of V over the set where Vdot >= 0 "
                        "with (x1, x3) != (0, 0) and |x2| <= X, and over the faces |x2| = X, lies in [natural_c_max_lower, "
                        "natural_c_max_upper]; phi(x2) > natural_c_max_upper on X_c <= |x2| <= X (so c_max(X') is the same "
                        "number for every X' in [X_c, X] and the component of {V < c} around 0 lies in |x2| < X_c for "
                        "c <= natural_c_max_upper); where natural_extent_x2 is stated, phi < natural_c_max_lower on [0, E] (E its "
                        "lower end), so the component of {V < natural_c_max_lower} reaches |x2| = E. For every c <= natural_c_max_lower that component has Vdot <= 0 on it, "
                        "with equality only where x1 = x3 = 0 (LaSalle, x2 f(x2) > 0: positively invariant, bounded, "
                        "inside the domain of attraction). The bracket aims at the relative gap of the scene option "
                        "natural_sublevel (default 1e-6).",
}

#: the trajectory claims of issue 40 (validated flow of system (2); trajectory_claims.py)
OPT_IN_CLAIMS.update(TRAJECTORY_CLAIMS)

#: every claim in report order, the opt-in ones at their place (after largest_sublevel): the order attempt emits
#: them in, so a scene whose claims_only names an opt-in claim gets its claims in this order
ALL_CLAIMS = {}
for _cid, _text in CLAIMS.items():
    ALL_CLAIMS[_cid] = _text
    if _cid == "largest_sublevel":
        ALL_CLAIMS.update(OPT_IN_CLAIMS)


@dataclass
class LyapunovModel:
    gimbal: Gimbal
    params: dict[str, Exact]
    text: dict[str, str]
    rel_width: fmpq
    R_option: fmpq | None
    max_pieces: int
    paper: dict
    #: the relative gap the natural_sublevel claim aims at ("" = not asked by option)
    natural_gap: str = ""
    #: option initial_point (x1, x2, x3) exactly, or None; option initial_point_time (model time allowed)
    initial_point: tuple | None = None
    initial_time: Fraction = Fraction(1)
    #: options of attraction_paving: grid size, half-width in units of the slice's extents, model time
    paving: tuple = (8, Fraction(3), Fraction(3))


def _err(name, text, need):
    return ParameterError(f"parameter {name!r} = {text!r}: need {need}")


def gimbal_from_parameters(text: dict[str, str], table: dict | None = None) -> tuple[Gimbal, dict[str, Exact]]:
    """Parse and check the parameters (exact strings) of the lyapunov kind and the scene's [moment] table
    (``table``, issue 42: :func:`.moment_scene.scene_moment_law`); ParameterError names the parameter to change."""
    v = parse_parameters(text, "lyapunov", PARAMETERS, PARAMETERS, text_keys=("moment",))
    moment = text["moment"]
    if not isinstance(moment, str) or moment not in KNOWN_MOMENTS:
        raise ParameterError(f"parameter 'moment' = {moment!r}: unknown moment law; known: {KNOWN_MOMENTS}")
    require_rational(v, RATIONAL)
    q = {k: v[k].rational for k in RATIONAL}
    for k in ("A", "C", "H", "k", "a", "mu"):
        if not q[k] > 0:
            raise _err(k, text[k], "> 0")
    for k in ("A1", "B1", "C1", "A2"):
        if q[k] < 0:
            raise _err(k, text[k], ">= 0 (a moment of inertia)")
    A0, B0, C0 = q["A"] + q["A1"] + q["A2"], q["A"] + q["B1"], q["A"] + q["A1"] - q["C1"]
    if not A0 > C0:
        raise ParameterError(f"parameters 'A2' = {text['A2']!r}, 'C1' = {text['C1']!r}: need A0 > C0, i.e. "
                             f"A2 + C1 > 0 (A0 = A + A1 + A2 = {A0}, C0 = A + A1 - C1 = {C0})")
    xs = v["x2_star"]
    r, pw = xs.rational, xs.pi_power
    if pw == 1:
        ok = 0 < r < Fraction(1, 2)
    elif pw == 0 and r > 0:
        with working_precision(256):   # r rational, pi/2 irrational: never equal, decided by balls
            ok = certainly_lt(arb(fmpq(r.numerator, r.denominator)), arb.pi() / 2)
    else:
        ok = False
    if not ok:
        raise _err("x2_star", text["x2_star"], "0 < x2_star < pi/2 (e.g. \"pi/6\")")
    f = {k: fmpq(x.numerator, x.denominator) for k, x in
         {"A0": A0, "B0": B0, "C0": C0, **q}.items()}
    g = Gimbal(f["A0"], f["B0"], f["C0"], f["H"], f["k"], f["a"], f["mu"], xs, scene_moment_law(moment, table, xs))
    return g, v


def validate(scene) -> LyapunovModel:
    g, v = gimbal_from_parameters(dict(scene.parameters), getattr(scene, "model", None))
    opts = parse_options(scene.options, OPTIONS, "lyapunov")
    rel = option_number(opts["rel_width"], "rel_width", above="0", at_most="1").fmpq()
    R = option_number(opts["R"], "R", above="0", at_most="1e6").fmpq() if opts["R"] else None
    pieces = option_count(opts["max_pieces"], "max_pieces", 1, MAX_PIECES_LIMIT)
    check_printed(scene.paper, PAPER_SCHEMA)
    nat = ""
    if opts["natural_sublevel"]:
        option_number(opts["natural_sublevel"], "natural_sublevel", above="0", at_most="1/2")
        nat = str(opts["natural_sublevel"])
    point = parse_initial_point(opts["initial_point"]) if opts["initial_point"] else None
    t_ip = option_number(opts["initial_point_time"], "initial_point_time", above="0", at_most="1000")
    if not t_ip.is_rational:
        raise ParameterError(f"option 'initial_point_time' = {opts['initial_point_time']!r}: need a rational number")
    grid = option_count(opts["paving_grid"], "paving_grid", 1, 64)
    scale = option_number(opts["paving_scale"], "paving_scale", above="0", at_most="100")
    t_pv = option_number(opts["paving_time"], "paving_time", above="0", at_most="1000")
    if not (scale.is_rational and t_pv.is_rational):
        raise ParameterError("options 'paving_scale' and 'paving_time' must be rational numbers")
    return LyapunovModel(g, v, dict(scene.parameters), rel, R, pieces, dict(scene.paper), nat, point, t_ip.rational,
                         (grid, scale.rational, t_pv.rational))


# ------------------------------------------------------------------------------------ helpers

def _claim(cid: str, status: Status, reason: str, counterexample: dict | None = None, decides: arb | None = None,
           **details) -> Claim:
    return Claim(cid, CLAIMS[cid], status, reason, details=details, counterexample=counterexample, decides=decides)


def _fmt(x: arb, digits: int = 12) -> str:
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def _q(x: fmpq) -> arb:
    return arb(x)


def _fmpq(fr: Fraction) -> fmpq:
    return fmpq(fr.numerator, fr.denominator)


def _relative_gap(upper: Fraction, lower: Fraction) -> arb:
    """(upper - lower) / lower of two exact decimals, computed exactly and made a ball once (one rounding:
    about 1 bit lost at any precision; the difference of the two balls lost log2(lower / (upper - lower)) bits,
    23-26 for the gaps of 1e-7)."""
    return _q(_fmpq((upper - lower) / lower))


def _searched(x: fmpq | Fraction) -> Quantity:
    """A decimal chosen by a search (mu_best, R_max, R_direct, ...): exact, shown and stored as that number
    (radius 0), while the ball it carries contains it at the current precision."""
    return Quantity.of_exact(Fraction(int(x.p), int(x.q)) if isinstance(x, fmpq) else Fraction(x))


class _Ctx:
    """Everything one attempt computes, each piece only when a claim needs it."""

    def __init__(self, model: LyapunovModel, prec: int):
        self.m = model
        self.g = model.gimbal
        self.prec = prec
        self._memo: dict = {}
        #: per claim, the data rigor-gyro check re-evaluates (pieces, points; exact texts)
        self.witnesses: dict = {}

    def memo(self, key, fn):
        if key not in self._memo:
            self._memo[key] = fn()
        return self._memo[key]

    @property
    def xs(self) -> arb:
        return self.g.c.x2_star

    def tol(self, value: arb) -> arb:
        """The width a maximum is enclosed to: rel_width of it, and over a box (a gimbal with an extrema
        cache) also 4 radii of the value at a point, which the box's own width gives and no subdivision of
        x2 removes (the point prover's tolerance is unchanged). The floor 2^-prec (for a value 0) is relative,
        2^-prec |value|, where 0 < |value| < 1 certainly: an absolute floor kept a = 1e-300's m and M from their
        relative width until 2^-prec < 1e-315 (2048 bits; issue 41)."""
        mag = abs(value)
        floor = arb(2) ** (-self.prec)
        if certainly_lt(mag, 1) and certainly_positive(mag):
            floor = floor * mag.lower()
        t = mag * _q(self.m.rel_width) / 4 + floor
        if getattr(self.g, "extrema_cache", None) is not None:
            t = t + 4 * value.rad()
        return t

    # ------------------------------------------------------------------ constants
    def shared(self, name: str, run):
        """``run()`` memoised in this attempt, and across attempts in the gimbal's ``extrema_cache`` when it has
        one (a box's gimbal: m and M depend only on the parameters its ``extrema_key`` names, so every box with
        the same intervals of those gets the very same enclosure; the point prover has no such cache)."""
        cache = getattr(self.g, "extrema_cache", None)
        if cache is None:
            return self.memo(name, run)
        key = (name, self.g.extrema_key, self.prec, self.m.max_pieces, self.m.rel_width.p, self.m.rel_width.q)
        if key not in cache:
            if len(cache) >= 512:
                cache.clear()
            cache[key] = run()
        return self.memo(name, lambda: cache[key])

    def m_max(self):
        def run():
            # where cos f' / D > 0 on the whole range (certified), |.| is itself: use the mean-value form
            fn = self.g.m_quotient
            signed = mean_value_enclosure(self.g.m_signed)
            if certify_positive(signed, 0, self.xs, max_pieces=200).status is Status.PROVED:
                fn = signed
            return enclose_max(fn, 0, self.xs, abs_tol=self.tol(fn(arb(0))), max_pieces=self.m.max_pieces)
        return self.shared("m", run)

    def M_max(self):
        def run():
            v = self.g.q(self.xs)
            return enclose_max(self.g.q, 0, self.xs, abs_tol=self.tol(v), max_pieces=self.m.max_pieces)
        return self.shared("M", run)

    def constants(self) -> dict[str, arb]:
        def run():
            # derived from the hulls of m's and M's stored decimal intervals: a checker's own m, M (confirmed
            # inside those intervals) then give p, k_min, ... inside the stored ones (no decimal slack escapes)
            m, M = self.m_max().ball, self.M_max().ball
            k = closed_form_constants(self.g, stored_hull(m), stored_hull(M))
            k["m"], k["M"] = m, M
            return k
        return self.memo("constants", run)

    def R_used(self) -> tuple[arb, str]:
        if self.m.R_option is not None:
            return _q(self.m.R_option), f"R = {self.m.R_option} (scene option)"
        R = self.constants()["R"]
        return R, "R = min(R1, R2) from (13), (14)"


# ------------------------------------------------------------------------------------ Vdot

def _vdot_claim(ctx: _Ctx, R: arb, how: str, cid: str = "vdot_nonpositive") -> tuple[Claim, dict]:
    """``vdot_nonpositive`` (Vdot <= 0: the Psi test, else the direct test; refuted only where Vdot > 0) or
    ``psi_test`` (Psi1, Psi2 > 0: refuted where one is <= 0, or where Vdot > 0)."""
    record: dict = {}
    fn = certify_vdot_nonpositive if cid == "vdot_nonpositive" else certify_psi_test
    v = fn(ctx.g, ctx.xs, R, how, ctx.m.max_pieces, record=record)
    info = {"pieces": v.pieces, "record": record}      # the record: the checker's witness
    claim = _claim(cid, v.status, v.reason, v.counterexample, **v.details)
    claim.decides = v.decides
    return claim, info


# ------------------------------------------------------------------------------------ Vdot < 0 directly

#: extra bits of the bisection for the x2 extent of the invariant estimate (see _invariant)
EXTENT_EXTRA_BITS = 16

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


def _unstate(quantities: dict, *names: str) -> None:
    """Drop the quantities an inconclusive claim had stored: the checker verifies them only from a proved claim's
    witnesses, and a certificate states nothing its checker cannot confirm."""
    for n in names:
        quantities.pop(n, None)


def _certify_direct(g: Gimbal, max_pieces: int, cap: float | None = None) -> _Direct:
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
            d.cert = certify_positive_on_box(symmetric_in_x2(g, face_margin(g, _q(_fmpq(Fraction(d.R_text))))),
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
    x2p = _q(_fmpq(exact_fraction((xs * arb(u0)).mid())))
    x2p = x2p if certainly_le(abs(x2p), xs) else (xs.lower() if u0 > 0 else -xs.lower())
    for m, digits, _ in margins:
        rr = arb(est) * (1 + arb(m))
        t = pi * arb(s0)
        x1, x3 = (_q(_fmpq(exact_fraction((rr * t.cos()).mid()))), _q(_fmpq(exact_fraction((rr * t.sin()).mid()))))
        if certainly_le(abs(x2p), xs) and certainly_positive(g.vdot(x1, x2p, x3)):
            d.point = (x1, x2p, x3)
            d.up_text = decimal_bounds((x1 * x1 + x3 * x3).sqrt(), max(12, digits))[1]
            break
    return d


def _vdot_direct(ctx: _Ctx, quantities: dict[str, arb]) -> Claim:
    g = ctx.g
    d = ctx.memo("direct at the scene's mu", lambda: _certify_direct(g, ctx.m.max_pieces))
    est = d.est
    if not (math.isfinite(est) and est > 0 and d.amin > 0):
        claim = _claim("vdot_direct", Status.INCONCLUSIVE,
                       f"the search found no positive radius (inf A/|B| ~ {est:.6g}, min A ~ {d.amin:.3g}): the direct "
                       "test gives nothing here (A <= 0 somewhere means Vdot > 0 arbitrarily near x1 = x3 = 0)")
        claim.precision_cannot_help = "the float search finds A <= 0: no radius to certify at any precision"
        return claim
    cert, R_text = d.cert, d.R_text
    if cert.status is not Status.PROVED:
        return _claim("vdot_direct", Status.INCONCLUSIVE,
                      f"A - R |B| > 0 not certified at R = {R_text} (search estimate {est:.10g}): {cert.reason}; "
                      "try a larger max_pieces or --maxprec")
    R_direct = _searched(Fraction(R_text))
    point = d.point
    ctx.witnesses["vdot_direct"] = {"R": R_text, "boxes": [b.to_json() for b in cert.leaves]}
    quantities["R_direct"] = R_direct
    if point is None:
        return _claim("vdot_direct", Status.PROVED,
                      f"A - R |B| > 0 certified at R_direct = {R_text} on {len(cert.leaves)} boxes of (x2, t) (search "
                      f"estimate of the supremum {est:.10g}); no certified point above it was found, so no upper bound "
                      "of the supremum is stated", R_direct=R_text, boxes=len(cert.leaves))
    ctx.witnesses["vdot_direct"]["point"] = {"x1": ball_text(point[0]), "x2": ball_text(point[1]),
                                            "x3": ball_text(point[2])}
    up_text = d.up_text
    quantities["R_direct_upper"] = _searched(Fraction(up_text))
    gap = _relative_gap(Fraction(up_text), Fraction(R_text))
    quantities["R_direct_relative_gap"] = gap
    return _claim("vdot_direct", Status.PROVED,
                  f"A - R |B| > 0 certified at R_direct = {R_text} on {len(cert.leaves)} boxes of (x2, t) (centered "
                  f"form; the search put the supremum at x2 = {float(d.u0):.6g} x2*, t = {float(d.s0):.6g} pi); Vdot = "
                  f"{_fmt(g.vdot(*point), 4)} > 0 at the point x1 = {_fmt(point[0], 8)}, x2 = {_fmt(point[1], 8)}, "
                  f"x3 = {_fmt(point[2], 8)} (radius <= {up_text}), so the supremum radius lies in [{R_text}, {up_text}] "
                  f"(relative gap {decimal_bounds(gap, 2)[1]})",
                  R_direct=R_text, R_direct_upper=up_text, boxes=len(cert.leaves))


# ------------------------------------------------------------------------------------ c_max

def _largest_sublevel(ctx: _Ctx, quantities: dict[str, arb]) -> Claim:
    r = largest_sublevel(ctx.g, ctx.m.max_pieces)
    if r.refutation is not None:
        ref = r.refutation
        ce = ({"where": "faces", "phi": _fmt(ref["phi"], 20)} if ref["where"] == "faces" else
              {"where": "origin", "x2": "0", "t_over_pi": str(ref["s"]), "A": _fmt(ref["A"], 20)})
        tail = ("; so no sublevel set of V around the origin is an estimate" if ref["where"] == "origin" else
                "; so no sublevel set of V reaching the faces at this x2* is an estimate (a smaller x2* may still give one)")
        claim = _claim("largest_sublevel", Status.REFUTED, r.reason + tail, ce)
        return claim
    if r.c_lower is None:
        if r.unbounded:
            # an enclosure unbounded below on the whole box budget: the boxes' width decides it, not the precision
            claim = _claim("largest_sublevel", Status.INCONCLUSIVE,
                           r.reason + f": {r.unbounded}; more precision cannot bound it (try a smaller x2*)")
            claim.precision_cannot_help = f"the lower bound of V over {{Vdot >= 0}} is unbounded below: {r.unbounded}"
            return claim
        return _claim("largest_sublevel", Status.INCONCLUSIVE, r.reason + "; try a larger max_pieces or --maxprec",
                      decides=r.bound)
    lo, hi = _q(_fmpq(Fraction(r.c_lower))), _q(_fmpq(Fraction(r.c_upper)))
    quantities["c_max_lower"], quantities["c_max_upper"] = lo, hi
    quantities["vdot_level_lower"] = _q(_fmpq(Fraction(r.n_lower)))
    if r.n_upper is not None:
        quantities["vdot_level_upper"] = _q(_fmpq(Fraction(r.n_upper)))
    quantities["face_level"] = r.face
    ctx.witnesses["largest_sublevel"] = {"boxes": [b.to_json() for b in r.leaves]}
    if r.point is not None:
        ctx.witnesses["largest_sublevel"]["point"] = {n: ball_text(x) for n, x in zip(("x1", "x2", "x3"), r.point)}
    aim = (f"aiming {r.gap} below the point's value" + (" (the faces bind by a factor > 2: the level of {Vdot >= 0} "
                                                       "only has to be shown above them)" if r.gap != SUBLEVEL_GAP else ""))
    vd = (f"over {{Vdot >= 0}}: V >= {r.n_lower} ({r.boxes} boxes of (x2, t), {aim})" + (f", and V = {_fmt(ctx.g.V(*r.point), 10)} <= {r.n_upper} at the point x1 = {_fmt(r.point[0], 8)}, "
                      f"x2 = {_fmt(r.point[1], 8)}, x3 = {_fmt(r.point[2], 8)} where Vdot = "
                      f"{_fmt(ctx.g.vdot(*r.point), 4)} > 0" if r.point is not None else
                      " (no certified point where Vdot > 0 was found: no upper bound of that part)"))
    bind = {"faces": "the faces |x2| = x2* bind (c_max = min phi(+-x2*): the range of x2 where V > 0 is certified "
                     "limits the estimate, not the sign of Vdot)",
            "vdot": "the set {Vdot >= 0} binds (c_max is decided by the sign of Vdot, below the faces' level)",
            "undecided": "which part binds is not decided at this gap"}[r.binding]
    cmp = ""
    if "c_star" in quantities and quantities["c_star"].is_finite():
        cs = quantities["c_star"]
        if certainly_lt(cs.upper(), lo):
            cmp = (f"; c_max_lower exceeds c* = {_fmt(cs, 10)} of invariant_estimate by a factor {_fmt(lo / cs, 4)}: "
                   "a larger certified estimate than the region-bounded construction gives")
        elif cs.overlaps(lo.union(hi)):
            cmp = (f"; c* = {_fmt(cs, 10)} of invariant_estimate agrees with c_max to the digits certified: the "
                   "region-bounded estimate is already the largest sublevel set of this V with |x2| <= x2*")
        else:
            cmp = f"; c* = {_fmt(cs, 10)} of invariant_estimate"
    return _claim("largest_sublevel", Status.PROVED,
                  f"c_max in [{r.c_lower}, {r.c_upper}]; faces: min phi(+-x2*) = {_fmt(r.face, 12)}; {vd}; {bind}{cmp}",
                  c_max_lower=r.c_lower, c_max_upper=r.c_upper, vdot_level_lower=r.n_lower,
                  vdot_level_upper=r.n_upper, binds=r.binding, boxes=r.boxes)


# ------------------------------------------------------------------------------------ natural c_max

def _natural_claim(status: Status, reason: str, decides: arb | None = None, **details) -> Claim:
    return Claim("natural_sublevel", OPT_IN_CLAIMS["natural_sublevel"], status, reason, details=details,
                 counterexample=None, decides=decides)


def _natural_sublevel(ctx: _Ctx, quantities: dict[str, arb]) -> Claim:
    gap = ctx.m.natural_gap or NATURAL_GAP
    r = natural_sublevel(ctx.g, ctx.m.max_pieces, gap)
    if r.c_lower is None:
        claim = _natural_claim(Status.INCONCLUSIVE, r.reason + "; try a larger max_pieces or --maxprec", decides=r.bound)
        if r.bound is None:
            claim.precision_cannot_help = r.reason
        return claim
    lo, hi = _q(_fmpq(Fraction(r.c_lower))), _q(_fmpq(Fraction(r.c_upper)))
    X = r.X
    quantities["natural_c_max_lower"], quantities["natural_c_max_upper"] = lo, hi
    # the certified level and reach the trajectory claims test against (trajectory_claims.initial_point_claim)
    ctx.natural = (lo, None if r.reach is None else _fmpq(r.reach))
    quantities["natural_X"] = X.ball()
    ctx.witnesses["natural_sublevel"] = {
        "X": X.text, "band_lo": str(r.band_lo), "positivity": r.positivity, "band": r.band,
        "boxes": [b.to_json() for b in r.leaves],
        "point": {n: ball_text(x) for n, x in zip(("x1", "x2", "x3"), r.point)}}
    extent = ""
    if r.reach is not None:
        quantities["natural_extent_x2"] = _q(_fmpq(r.reach)).union(_q(_fmpq(r.band_lo)))
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
        cmp.append(f"c* = {_fmt(cs, 10)} of invariant_estimate: the natural level is larger, natural_c_max_lower / c* = "
                   f"{_fmt(lo / cs, 6)}, natural_c_max_lower - c* = {_fmt(lo - cs, 8)}")
    if "c_max_lower" in quantities:
        cl, cu = quantities["c_max_lower"], quantities["c_max_upper"]
        cmp.append(f"c_max(x2*) in [{_fmt(cl, 10)}, {_fmt(cu, 10)}] of largest_sublevel (natural_c_max_lower / "
                   f"c_max_upper(x2*) = {_fmt(lo / cu, 6)})")
    if "R_used" in quantities:
        printed = ctx.m.paper.get("R")
        cmp.append(f"region (17) of invariant_estimate has |x2| <= x2* = {_fmt(ctx.xs, 8)} and radius R = "
                   f"{_fmt(quantities['R_used'], 6)}" + (f" (printed R = {printed})" if printed else ""))
    larger = ("; compared: " + "; ".join(cmp)) if cmp else ""
    if r.limit is None:
        why = ("X cannot reach pi/2: there h = H cos x2 / B0 = 0, V does not depend on x1, and (-f(pi/2)/k, pi/2, 0) "
               "is an equilibrium")
    else:
        why = (f"X cannot reach x2 = {_fmt(r.limit[0], 10)}: {r.limit[1]} <= 0 there (certified), so the test of "
               "v_positive fails")
    reached = "reached" if r.gap_reached else "not reached (box budget): the bracket is wider"
    return _natural_claim(
        Status.PROVED,
        f"V > 0 off the origin for |x2| <= X = {X.text} = {_fmt(X.ball(), 12)} (S, f/x, psi > 0 on "
        f"{sum(len(v) for v in r.positivity.values())} pieces; {why}); c_max(X) in "
        f"[{r.c_lower}, {r.c_upper}] (relative gap {_fmt(rel, 3)}; {r.boxes} boxes of (x2, t) over |x2| <= X_c, "
        f"aiming {gap}: {reached}), the upper end V = {_fmt(g.V(*pt), 12)} at the point x1 = {_fmt(pt[0], 8)}, "
        f"x2 = {_fmt(pt[1], 8)}, x3 = {_fmt(pt[2], 8)} where Vdot = {_fmt(g.vdot(*pt), 4)} > 0; phi > "
        f"{r.c_upper} on X_c = {r.band_lo} <= |x2| <= X ({len(r.band)} pieces): the faces do not bind and the set "
        f"lies in |x2| < X_c = {float(r.band_lo):.6f}" + extent + larger,
        c_max_lower=r.c_lower, c_max_upper=r.c_upper, X=X.text, band_lo=str(r.band_lo), boxes=r.boxes,
        gap=gap, gap_reached=r.gap_reached, reach=None if r.reach is None else str(r.reach))


# ------------------------------------------------------------------------------------ equilibria

def _hurwitz_row(coeffs) -> dict:
    """The Routh-Hurwitz coefficients of an equilibrium's row (enclosures as text; rigor-gyro check recomputes
    them from the Jacobian and re-decides the stability)."""
    a1, a2, a3 = coeffs
    return {"polynomial": "lambda^3 + a1 lambda^2 + a2 lambda + a3 = det(lambda I - J)", "a1": _fmt(a1, 8),
            "a2": _fmt(a2, 8), "a3": _fmt(a3, 8), "a1 a2 - a3": _fmt(a1 * a2 - a3, 8)}


def _equilibria_claim(ctx: _Ctx, inv: Claim | None, R: arb | None) -> Claim:
    g, xs = ctx.g, ctx.xs
    E = equilibria(g)
    ctx.witnesses["equilibria"] = {"pieces": E.pieces}
    c_set = _q(_fmpq(Fraction(inv.details["c_set"]))) if inv is not None and "c_set" in inv.details else None
    rows, texts = [], []
    for e in E.points:
        where = "in {V < c_set} or not: not decided (invariant_estimate not proved)"
        if c_set is not None and R is not None:
            if certainly_lt(xs, abs(e.x2)):
                where = "outside the estimate (|x2| > x2*)"
            elif certainly_le(abs(e.x2), xs) and certainly_lt(e.x1 * e.x1, R * R) and \
                    certainly_lt(g.V(e.x1, e.x2, arb(0)), c_set):
                where = "inside the estimate"
            elif certainly_lt(R * R, e.x1 * e.x1) or certainly_le(c_set, g.V(e.x1, e.x2, arb(0))):
                where = "outside the estimate"
            else:
                where = "undecided"
        x2 = e.exact or _fmt(e.x2, 10)
        rows.append({"x1": _fmt(e.x1, 12), "x2": x2, "case": e.case, "stability": e.stability, "estimate": where,
                     "eigenvalues": [f"{_fmt(z.real, 8)} + {_fmt(z.imag, 8)} i" for z in e.eigenvalues],
                     **({"routh_hurwitz": _hurwitz_row(e.hurwitz)} if e.hurwitz is not None else {})})
        # a Routh-Hurwitz row lists no eigenvalues (acb_mat.eig did not separate them): the statement's
        # "each with the eigenvalues" is met by its characteristic polynomial's coefficients instead
        by = (" (by Routh-Hurwitz from the coefficients of det(lambda I - J), row routh_hurwitz: the eigenvalues "
              "were not separated at this precision, so none are listed)") if e.hurwitz is not None else ""
        texts.append(f"({_fmt(e.x1, 8)}, {x2}, 0) [{e.case}]: {e.stability}{by}, {where}")
    undecided = [r for r in rows if r["stability"] == "undecided" or r["estimate"] == "undecided"]
    if not E.complete or undecided:
        return _claim("equilibria", Status.INCONCLUSIVE,
                      (E.reason if not E.complete else f"{len(undecided)} equilibria with undecided stability or "
                       "membership: raise --maxprec") + "; found: " + "; ".join(texts), equilibria=rows)
    return _claim("equilibria", Status.PROVED, f"{len(rows)} equilibria with |x2| <= pi: " + "; ".join(texts),
                  equilibria=rows)


# ------------------------------------------------------------------------------------ V > 0

def _v_positive_claim(ctx: _Ctx) -> Claim:
    g, xs = ctx.g, ctx.xs
    c = g.c
    steps = [("S = f2 + mu (f1 - mu) > 0", g.S),
             ("f(x2)/x2 > 0 (so F > 0 for x2 != 0)", lambda x: g.law.f_over_x(c.a, x)),
             ("psi > 0 (so phi = (F/S) psi > 0 for x2 != 0)", g.psi)]
    pieces = 0
    record: dict = {}
    for key, (text, fn) in zip(("S", "f_over_x", "psi"), steps):
        kept: list = []
        r = certify_positive(fn, 0, xs, max_pieces=ctx.m.max_pieces, record=kept)
        pieces += r.pieces
        if r.status is Status.PROVED:
            record[key] = pieces_text(kept)
            ctx.witnesses["v_positive"] = record
            continue
        # a rational point of (0, x2*] (the witness may be the irrational end x2*: issue 37 part 3)
        # psi <= 0 or f <= 0 at a point (a law that destabilises: F < 0 there): V at the point minimising phi's
        # squares is then phi(x2) = (F/S) psi, certified <= 0 or not
        for x2 in (rational_points_inside(r.witness, xs) if r.status is Status.REFUTED and key in ("psi", "f_over_x")
                   else ()):
            if not certainly_positive(x2):
                continue
            x1, x3 = g.phi_minimiser(x2)
            x1q, x3q = (_q(_fmpq(exact_fraction(y.mid()))) for y in (x1, x3))
            v = g.V(x1q, x2, x3q)
            if certainly_le(v, 0):
                return _claim("v_positive", Status.REFUTED,
                              f"V = {_fmt(v, 6)} <= 0 at x1 = {_fmt(x1q)}, x2 = {_fmt(x2)}, x3 = {_fmt(x3q)} "
                              + ("(certified; psi <= 0 there, i.e. mu H - q + ... fails)" if key == "psi" else
                                 "(certified; f <= 0 at a point of (0, x2*]: the law destabilises)"),
                              {"point": {"x1": ball_text(x1q), "x2": ball_text(x2), "x3": ball_text(x3q)},
                               "V": _fmt(v, 20)},
                              witness={"x1": _fmt(x1q, 20), "x2": _fmt(x2, 20), "x3": _fmt(x3q, 20)})
        hint = ("certified false at that point, so no precision changes it (V itself was not certified <= 0 at a "
                "rational point there)" if r.status is Status.REFUTED else "try --maxprec or max_pieces")
        return _claim("v_positive", Status.INCONCLUSIVE, f"could not certify {text} on [0, x2*]: {r.reason}; {hint}",
                      decides=r.stuck_value)
    return _claim("v_positive", Status.PROVED,
                  "on [0, x2*]: " +
                  "; ".join(t for t, _ in steps) + f" certified on {pieces} pieces (S, f/x and psi are even); hence "
                  "V = phi(x2) + S/2 (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2 > 0 off the origin (at x2 = 0, "
                  "phi = 0 and the squares vanish only at x1 = x3 = 0; psi is enclosed through x2 = 0 "
                  "by the removable form of q)", pieces=pieces)


# ------------------------------------------------------------------------------------ c*

def _invariant(ctx: _Ctx, R: arb, quantities: dict[str, arb]) -> Claim:
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
        quantities["cylinder_margin_lower"] = _q(_fmpq(Fraction(margin_text)))
    if not certainly_positive(cstar):
        return _claim("invariant_estimate", Status.INCONCLUSIVE,
                      f"c* = {_fmt(cstar)} is not certainly positive (cylinder bound on {cyl.pieces} pieces); "
                      "try a larger max_pieces or higher --maxprec (a smaller R makes c* smaller too)",
                      decides=cstar, pieces=cyl.pieces)
    # the set is {V < c_set}, c_set = c*'s certified lower end, less a margin of 4 relative widths of R
    # (c* moves like R^2: a checker with its own enclosure of R must still find c_set below its bound),
    # rounded down to 10 digits (exact)
    margin = 4 * R.rad() / R.abs_lower() + arb(2) ** -40
    c_text = decimal_bounds((cstar.lower() * (1 - margin)).lower(), 10)[0]
    cl = _q(_fmpq(Fraction(c_text)))
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
    return _claim("invariant_estimate", Status.PROVED,
                  f"c* = {_fmt(cstar)} ({where}; cylinder x1^2 + x3^2 = R^2: V >= {_fmt(cyl_lb, 8)} on {cyl.pieces} "
                  "x2 pieces). "
                  f"The set {{V < c_set = {c_text}}} within (17) contains the axis segments "
                  f"|x1| < {_fmt(ext['x1_axis'], 6)}, |x2| < {_fmt(ext['x2_axis'], 6)}, |x3| < {_fmt(ext['x3_axis'], 6)}; "
                  f"its extents (the maxima of |x1|, |x2|, |x3| over it, enclosed from its x2 slices, which are ellipses) "
                  f"are {_fmt(tight['x1'], 6)}, {_fmt(tight['x2'], 6)}, {_fmt(tight['x3'], 6)}",
                  c_set=c_text,
                  pieces=cyl.pieces)


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
        points.append(_argmax_x2(g, xs, _fmpq(exact_fraction(mid))))
    pieces, count = best_first_bisection(mu_lo, mu_hi, bound, refine, lambda u: certainly_le(u, target), max_pieces)
    upper = pieces[0][2]
    for _, _, u in pieces:          # the pieces cover [mu_lo, mu_hi]
        upper = upper.max(u)
    return upper, count, [(a, b) for a, b, _ in pieces], points


def _decimal_inside(mu: Fraction, lo: arb, hi: arb) -> str | None:
    """A short exact decimal near ``mu`` certainly inside (lo, hi) (the optimum may sit at an end), or None."""
    for digits in (12, 16, 20, 30, 45, 60):
        for cand in decimal_bounds(_q(_fmpq(mu)), digits):
            if certainly_lt(lo, _q(_fmpq(Fraction(cand)))) and certainly_lt(_q(_fmpq(Fraction(cand))), hi):
                return cand
    return None


def _no_mu_interval(cid: str, lo: arb, hi: arb) -> Claim:
    """The claim over (16) when (16) is not certainly non-empty: refuted when it is certainly empty."""
    empty = certainly_le(hi, lo)
    return _claim(cid, Status.REFUTED if empty else Status.INCONCLUSIVE,
                  f"the mu interval (16) ({_fmt(lo)}, {_fmt(hi)}) is " + ("empty: no admissible mu" if empty else
                                                                          "not certainly non-empty"),
                  {"mu_min": _fmt(lo, 20), "mu_max": _fmt(hi, 20)} if empty else None)


def _best_mu(ctx: _Ctx, quantities: dict[str, arb]) -> Claim:
    g, xs = ctx.g, ctx.xs
    k = ctx.constants()
    lo, hi = k["mu_min"], k["mu_max"]
    if not certainly_lt(lo, hi):
        return _no_mu_interval("best_mu", lo, hi)

    def est(mu: Fraction) -> float:
        return _r_sup_search(g.with_mu(_fmpq(mu)), xs)[0]
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
        return _claim("best_mu", Status.INCONCLUSIVE,
                      f"no decimal mu certainly inside (16) near the optimum {float(mu_mid):.15g} (the interval is "
                      f"({_fmt(lo)}, {_fmt(hi)})): raise --maxprec")
    mu_best = _fmpq(Fraction(mu_text))
    gb = g.with_mu(mu_best)
    # to rel_width, on at most 2000 pieces (R_max keeps 10 digits: a wider R_sup only costs digits)
    R_enc, e = r_sup(gb, xs, rel=_q(ctx.m.rel_width) / 4 + arb(2) ** (-ctx.prec), max_pieces=min(ctx.m.max_pieces, 2000))
    if not (R_enc.is_finite() and certainly_positive(R_enc)):
        return _claim("best_mu", Status.INCONCLUSIVE, f"R_sup(mu_best) not enclosed: {_fmt(R_enc)}", decides=R_enc)
    estimate = max(f1, f2, float(R_enc.mid()))
    quantities["mu_best"] = _searched(mu_best)
    quantities["R_sup_at_mu_best"] = R_enc
    sub = _Ctx(ctx.m, ctx.prec)
    sub.g = gb
    claim = None
    # R_max: R_sup's certified lower end to 10 digits; if Psi's margin is too thin to re-certify by
    # subdivision, 1e-6 (then 1e-3) below it
    for shrink in ("1", "0.999999", "0.999"):
        R_text = decimal_bounds(R_enc.lower() * arb(shrink), 10)[0]
        R_max = _fmpq(Fraction(R_text))
        claim, info = _vdot_claim(sub, _q(R_max), "at mu = mu_best, R = R_max", "psi_test")
        if claim.status is Status.PROVED:
            break
    if claim.status is not Status.PROVED:
        _unstate(quantities, "mu_best", "R_sup_at_mu_best")
        return _claim("best_mu", Status.INCONCLUSIVE, f"R_max could not be re-certified: {claim.reason}",
                      decides=claim.decides)
    quantities["R_max"] = _searched(R_max)
    # how good is R_max: a certified upper bound of sup over (16) of R_sup (branch and bound over mu,
    # on the hull of (16), which contains it)
    # over the hull of (16), padded by 4 radii of its ends: a checker's own enclosure of (16) must lie inside
    U, u_pieces, u_cover, u_points = r_sup_upper_bound(g, xs, (lo.lower() - 4 * lo.rad()).lower(),
                                                       (hi.upper() + 4 * hi.rad()).upper(),
                                                       _q(R_max) * (1 + arb(BEST_MU_GAP)), max_pieces=ctx.m.max_pieces)
    ctx.witnesses["best_mu"] = {"vdot_at_R_max": info["record"], "r_sup_cover": pieces_text(e.cover),
                                "r_sup_point": ball_text(e.argpoint), "mu_pieces": pieces_text(u_cover),
                                "x2_points": [ball_text(x) for x in u_points]}
    if not (U.is_finite() and certainly_le(_q(R_max), U)):
        _unstate(quantities, "mu_best", "R_sup_at_mu_best", "R_max")
        return _claim("best_mu", Status.INCONCLUSIVE, f"no finite upper bound of sup R_sup over (16): {_fmt(U)}",
                      decides=U)
    # stored as its 15-digit decimal rounded up: a re-derivation on the same pieces at another precision
    # differs in the last bits of arb's radius arithmetic (30-bit radii on wide mu pieces; 1.4e-24 relative
    # seen), so the exact upper end of U would be a bound only this run can confirm
    U_text = decimal_bounds(U, 15)[1]
    U = _q(_fmpq(Fraction(U_text)))
    quantities["R_sup_upper_bound"] = U
    gap = _relative_gap(Fraction(U_text), Fraction(R_text))
    quantities["R_max_relative_gap"] = gap
    return _claim("best_mu", Status.PROVED,
                  f"mu_best = {mu_text} (chosen by a golden-section search over (16) on point estimates of R_sup, then fixed "
                  f"as an exact decimal: a search result, not proved optimal); at mu_best, R_sup = {_fmt(R_enc, 14)} "
                  f"(certified maximum over x2, {e.pieces} pieces); R_max = {R_text} certified: Psi1, Psi2 > 0 on the "
                  f"disc of radius R_max ({info['pieces']} pieces). Certified: R_sup(mu) <= {decimal_bounds(U, 12)[1]} "
                  f"for every mu in (16) (branch and bound over mu, {u_pieces} pieces), so R_max is within a relative "
                  f"{decimal_bounds(gap, 3)[1]} of the largest radius this Psi test can certify",
                  mu_best=mu_text, R_max=R_text, R_sup_upper_bound=decimal_bounds(U, 15)[1],
                  relative_gap=decimal_bounds(gap, 3)[1], float_estimate=f"{estimate:.15g}")


def _best_mu_direct(ctx: _Ctx, quantities: dict[str, arb]) -> Claim:
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
            return _claim("best_mu_direct", Status.INCONCLUSIVE,
                          f"no finite bound of the direct test's radius over (16) ({n_pieces} mu pieces): A <= 0 or B = 0 "
                          "at every point tried", decides=U)
        # the search's optimum may sit in the padding: the nearest point of (16), or its midpoint
        mu_text = _decimal_inside(min(max(best_mu, a), b), lo, hi) or _decimal_inside((a + b) / 2, lo, hi)
        if mu_text is None:
            return _claim("best_mu_direct", Status.INCONCLUSIVE,
                          f"no decimal mu certainly inside (16) near the search's optimum {float(best_mu):.15g}: raise --maxprec")
        mu = _fmpq(Fraction(mu_text))
        known = piece_upper(g, _q(mu), points)            # certified, at mu_direct: the radius is at most this
        d = _certify_direct(g.with_mu(mu), min(ctx.m.max_pieces, DIRECT_MU_BOXES),
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
            mu = _fmpq(frac)
            chosen = (f"the scene's own mu: the searched optimum {float(best_mu):.12g} could not be certified within "
                      f"{min(ctx.m.max_pieces, DIRECT_MU_BOXES)} boxes of (x2, t)")
            # the same computation as vdot_direct's (done once: at the scene's mu, g is the scene's gimbal)
            d = ctx.memo("direct at the scene's mu", lambda: _certify_direct(g, ctx.m.max_pieces))
    if d.cert is None or d.cert.status is not Status.PROVED:
        why = d.cert.reason if d.cert is not None else f"the search found no positive radius (~{d.est:.6g})"
        return _claim("best_mu_direct", Status.INCONCLUSIVE,
                      f"at mu_direct = {mu_text}, A - R |B| > 0 not certified at R = {d.R_text or '-'}: {why}; try a "
                      "larger max_pieces or --maxprec")
    R = _searched(Fraction(d.R_text))
    # stored as its 15-digit decimal rounded up (as best_mu's bound: a re-derivation at another precision
    # differs in arb's last radius bits)
    U_text = decimal_bounds(U, 15)[1]
    U = _q(_fmpq(Fraction(U_text)))
    if not certainly_le(R, U):      # R <= R_dsup(mu_direct) <= U: both certified, so this cannot happen
        raise AssertionError(f"best_mu_direct: certified R {d.R_text} above the certified bound {U}")
    gap = _relative_gap(Fraction(U_text), Fraction(d.R_text))
    quantities.update({"mu_direct": _searched(mu), "R_direct_max": R, "R_direct_sup_upper_bound": U,
                       "R_direct_max_relative_gap": gap})
    ctx.witnesses["best_mu_direct"] = {"mu": mu_text, "R": d.R_text, "boxes": [b.to_json() for b in d.cert.leaves],
                                       "mu_pieces": pieces_text(cover),
                                       "points": [[str(u), str(s)] for u, s in points]}
    compare = []
    for name, what in (("R_max", "the Psi test's best radius R_max"), ("R_direct", "the direct test at the scene's mu")):
        if name in quantities and certainly_positive(quantities[name]):
            compare.append(f"{decimal_bounds(R / quantities[name], 6)[0]} times {what}")
    return _claim("best_mu_direct", Status.PROVED,
                  f"mu_direct = {mu_text} ({chosen}); at mu_direct, A - R |B| > 0 certified at "
                  f"R_direct_max = {d.R_text} on {len(d.cert.leaves)} boxes of (x2, t) (search estimate {d.est:.10g}). "
                  f"Certified: R_dsup(mu) <= {decimal_bounds(U, 12)[1]} for every mu in (16) (branch and bound over "
                  f"mu, {n_pieces} pieces, {len(points)} points of (x2, t)), so R_direct_max is within a relative "
                  f"{decimal_bounds(gap, 3)[1]} of the largest radius with Vdot <= 0 on the disc cylinder at any "
                  f"admissible mu" + (f"; R_direct_max is {' and '.join(compare)}" if compare else ""),
                  mu_direct=mu_text, R_direct_max=d.R_text, R_direct_sup_upper_bound=decimal_bounds(U, 15)[1],
                  relative_gap=decimal_bounds(gap, 3)[1], boxes=len(d.cert.leaves), mu_pieces=n_pieces)


# ------------------------------------------------------------------------------------ attempt

def maximum_M(model: LyapunovModel, prec: int):
    """The certified maximum M of q over [0, x2*] (an Extremum), as ``constants`` computes it (shared through a
    box gimbal's extrema cache)."""
    return _Ctx(model, prec).M_max()


def attempt(model: LyapunovModel, wanted: list[str], prec: int) -> Attempt:
    """Evaluate the requested claims at the current precision (set by the prover). An expression law's
    quadratures share one budget per attempt (:func:`.moment_expr.quadrature_budget`): when it is spent, the
    claims not yet decided are inconclusive, naming it (never refuted, never a crash)."""
    ctx = _Ctx(model, prec)
    with quadrature_budget(ctx.g.law):
        return _attempt(ctx, model, wanted)


def _natural_level(ctx) -> tuple:
    """(the natural sublevel's level, its reach as a ball) when natural_sublevel ran, else (None, None)."""
    nat = getattr(ctx, "natural", None)
    return (nat[0], None if nat[1] is None else arb(nat[1])) if nat else (None, None)


def _attempt(ctx: "_Ctx", model: LyapunovModel, wanted: list[str]) -> Attempt:
    claims: list[Claim] = []
    quantities: dict[str, arb] = {}
    widths_met = True
    notes: list[str] = []
    phase = Phases()
    try:
        need_constants = any(c in wanted for c in ("constants", "damping_condition", "best_mu", "best_mu_direct")) or model.R_option is None
        if need_constants:
            with phase("constants (m, M by subdivision)"):
                k = ctx.constants()
            for name in ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R"):
                quantities[name] = k[name]
            widths_met = all(rel_width_at_most(k[n], model.rel_width) for n in ("m", "M", "p", "R1", "R2"))
        if need_constants:
            ctx.witnesses["constants"] = {n: {"cover": pieces_text(e.cover), "point": ball_text(e.argpoint)}
                                          for n, e in (("m", ctx.m_max()), ("M", ctx.M_max()))}
        if "constants" in wanted:
            k = ctx.constants()
            finite = all(v.is_finite() for v in k.values())
            conv = ctx.m_max().converged and ctx.M_max().converged
            note = ""
            if certainly_lt(k["R2_base"], 0):
                note = "; note: mu H cos^2 x2* < A0 m, so (15) fails and R2 (14) (which squares that difference) is meaningless"
            claims.append(_claim(
                "constants", Status.PROVED if finite and conv else Status.INCONCLUSIVE,
                (f"m = {_fmt(k['m'])} ({ctx.m_max().pieces} pieces), M = {_fmt(k['M'])} ({ctx.M_max().pieces} pieces), "
                 f"p = {_fmt(k['p'])}, k_min = {_fmt(k['k_min'])}, mu in ({_fmt(k['mu_min'])}, {_fmt(k['mu_max'])}), "
                 f"R1 = {_fmt(k['R1'])}, R2 = {_fmt(k['R2'])}" + note) if finite and conv else
                "the maxima m, M did not converge to the requested width: raise --maxprec or the max_pieces option",
                decides=None if finite and conv else (k["m"] if not ctx.m_max().converged else k["M"]),
                m_pieces=ctx.m_max().pieces, M_pieces=ctx.M_max().pieces))
        if "damping_condition" in wanted:
            k = ctx.constants()
            c = ctx.g.c
            parts = [("k > p A0/H (18)", c.k, k["k_min"]), ("mu > p/H", c.mu, k["mu_min"]), ("mu < k/A0", k["mu_max"], c.mu)]
            holds = [certainly_gt(x, y) for _, x, y in parts]
            fails = [certainly_le(x, y) for _, x, y in parts]
            desc = "; ".join(f"{t}: {_fmt(x)} vs {_fmt(y)}" for t, x, y in parts)
            ce, decides = None, None
            if all(holds):
                st, why = Status.PROVED, "certified: " + desc
            elif any(fails):
                bad = [t for (t, _, _), f in zip(parts, fails) if f]
                st, why = Status.REFUTED, f"fails ({', '.join(bad)}): " + desc
                ce = {"violated": [{"inequality": t, "left": _fmt(x, 20), "right": _fmt(y, 20)}
                                   for (t, x, y), f in zip(parts, fails) if f]}
            else:
                st, why = Status.INCONCLUSIVE, "not separated at this precision: " + desc
                decides = next(x - y for (_, x, y), h in zip(parts, holds) if not h)
            # the margin in k to the nearest threshold of every condition (k_min of (18), mu A0 of (16))
            margin, binding, each = damping_margin(ctx.g, k["k_min"])
            quantities["damping_margin"] = margin
            claims.append(_claim("damping_condition", st, why + f"; design margin in k = min(k/k_min, k/(mu A0)) - 1 = "
                                 f"{_fmt(margin, 6)}, binding: {binding}", ce, decides, binding=binding,
                                 margins={n: _fmt(v, 6) for n, v in each.items()}))
        R, how = (None, "")
        if any(c in wanted for c in ("vdot_nonpositive", "psi_test", "invariant_estimate")):
            R, how = ctx.R_used()
            quantities["R_used"] = R
        vclaim = None
        if "vdot_nonpositive" in wanted or "invariant_estimate" in wanted:
            with phase("vdot_nonpositive"):
                vclaim, vinfo = _vdot_claim(ctx, R, how)
            if vclaim.status is Status.PROVED:
                ctx.witnesses["vdot_nonpositive"] = {"R": ball_text(R), **vinfo["record"]}
            if "vdot_nonpositive" in wanted:
                claims.append(vclaim)
        if "psi_test" in wanted:
            with phase("psi_test"):
                pclaim_psi, pinfo = _vdot_claim(ctx, R, how, "psi_test")
            if pclaim_psi.status is Status.PROVED:
                ctx.witnesses["psi_test"] = {"R": ball_text(R), **pinfo["record"]}
            claims.append(pclaim_psi)
        if "vdot_direct" in wanted:
            with phase("vdot_direct"):
                claims.append(_vdot_direct(ctx, quantities))
        pclaim = None
        if "v_positive" in wanted or "invariant_estimate" in wanted:
            with phase("v_positive"):
                pclaim = _v_positive_claim(ctx)
            if "v_positive" in wanted:
                claims.append(pclaim)
        if "invariant_estimate" in wanted:
            if vclaim.status is Status.PROVED and pclaim.status is Status.PROVED:
                with phase("invariant_estimate"):
                    claims.append(_invariant(ctx, R, quantities))
            else:
                dep = vclaim if vclaim.status is not Status.PROVED else pclaim
                claims.append(_claim("invariant_estimate", Status.INCONCLUSIVE,
                                     "rests on vdot_nonpositive and v_positive, which are not both proved",
                                     decides=dep.decides if dep.status is Status.INCONCLUSIVE else None))
                if dep.status is Status.REFUTED:
                    claims[-1].precision_cannot_help = f"it rests on {dep.id}, which is refuted"
        if "largest_sublevel" in wanted:
            with phase("largest_sublevel"):
                claims.append(_largest_sublevel(ctx, quantities))
        # opt-in (about 2 s and 1e4 boxes on the example): only when claims_only names it (OPT_IN_CLAIMS)
        if "natural_sublevel" in wanted:
            with phase("natural_sublevel"):
                claims.append(_natural_sublevel(ctx, quantities))
        if "region_not_invariant" in wanted:
            with phase("region_not_invariant"):
                Rr = R if R is not None else ctx.R_used()[0]
                claims.append(region_not_invariant_claim(ctx.g, Rr, ctx.xs, quantities.get("c_star"), ctx.witnesses))
        if "initial_point" in wanted:
            with phase("initial_point"):
                level, reach = _natural_level(ctx)
                claims.append(initial_point_claim(ctx.g, model.initial_point, model.initial_time, level, reach,
                                                  ctx.witnesses))
        if "attraction_paving" in wanted:
            with phase("attraction_paving"):
                level, reach = _natural_level(ctx)
                claims.append(paving_claim(ctx.g, level, reach, *model.paving, ctx.witnesses))
        if "equilibria" in wanted:
            with phase("equilibria"):
                inv = next((c for c in claims if c.id == "invariant_estimate" and c.status is Status.PROVED), None)
                claims.append(_equilibria_claim(ctx, inv, R))
        if "best_mu" in wanted:
            with phase("best_mu"):
                claims.append(_best_mu(ctx, quantities))
        if "best_mu_direct" in wanted:
            with phase("best_mu_direct"):
                claims.append(_best_mu_direct(ctx, quantities))
    except QuadratureBudgetSpent as e:
        # a budget never decides: the claim being decided and those not reached are undecided, naming it
        # (more precision cannot help: it only makes each quadrature dearer)
        done_ids = {c.id for c in claims}
        for cid in wanted:
            if cid not in done_ids and cid in CLAIMS:
                c = _claim(cid, Status.INCONCLUSIVE, f"undecided: {e}; a law with a closed-form G (moment = \"table\", "
                           "or a built-in law) or a shorter x2* avoids the quadrature")
                c.precision_cannot_help = "the quadrature budget of the [moment] law was spent"
                claims.append(c)
        notes.append(str(e))
        with phase("paper audit"):
            try:
                paper, formulas, audit_notes = audit_paper(ctx, quantities)
            except QuadratureBudgetSpent:
                paper, formulas, audit_notes = [], [], []
        notes += audit_notes
        return Attempt(claims, quantities, paper, formulas, notes, widths_met=False, width_quantities=(), stalled=True,
                       extra={"moment": {"name": ctx.g.law.name, "formula": ctx.g.law.formula}},
                       witnesses=ctx.witnesses, phase_seconds=phase.seconds)
    with phase("paper audit"):
        paper, formulas, audit_notes = audit_paper(ctx, quantities)
    notes += audit_notes
    # an undecided claim says what would decide it (Claim.decides): the prover stops when doubling the
    # precision no longer shrinks it (a subdivision budget, a tolerance), not at a fixed precision
    return Attempt(claims, quantities, paper, formulas, notes, widths_met=widths_met,
                   width_quantities=tuple(n for n in ("m", "M", "p", "R1", "R2")
                                          if n in quantities and not rel_width_at_most(quantities[n], model.rel_width)),
                   extra={"moment": {"name": ctx.g.law.name, "formula": ctx.g.law.formula}},
                   witnesses=ctx.witnesses, phase_seconds=phase.seconds)

