"""The lyapunov kind's vocabulary: its parameters, options and the statement of each claim (what a
``proved`` verdict asserts, word for word), in report order. Data only: nothing here computes."""

from __future__ import annotations

from .trajectory_claims import TRAJECTORY_CLAIMS, TRAJECTORY_OPTIONS
from .moments import MOMENTS

PARAMETERS = {"A": "equatorial moment of inertia of the rotor", "C": "polar moment of inertia of the rotor",
              "A1": "inner ring", "B1": "inner ring", "C1": "inner ring", "A2": "outer ring about its axis",
              "H": "cyclic constant (angular momentum)", "k": "viscous friction on the outer axis",
              "a": "amplitude of the moment f", "x2_star": "half-width of the x2 range, in (0, pi/2)",
              "mu": "parameter of V (7)", "moment": "moment law: " + ", ".join(sorted(MOMENTS))}
RATIONAL = ("A", "C", "A1", "B1", "C1", "A2", "H", "k", "a", "mu")
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
