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

Where each claim lives: the statements in :mod:`.declarations`; what the claims share (the claim context, which
computes m, M and the constants once) in :mod:`.claim_context`; ``vdot_direct`` in :mod:`.direct_claims`;
``invariant_estimate``, ``largest_sublevel`` and ``natural_sublevel`` in :mod:`.sublevel_claims`; ``best_mu`` and
``best_mu_direct`` in :mod:`.mu_claims`; the trajectory claims in :mod:`.trajectory_claims`; this module parses the
scene, decides ``constants`` to ``v_positive`` and ``equilibria``, and runs an attempt in the kind's order.

Reference: Agafonov S. A., Kostyushko I. A., Shvydka S. P., Kuzemko A. V., On the stability of steady
motion of a gyroscope in gimbals, 2013 (seed 000 in shared/seeds).
"""

from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import (certainly_gt, certainly_le, certainly_lt, certainly_positive, exact_fraction,
                           rel_width_at_most, working_precision)
from ...core.audit import check_printed
from ...core.errors import ParameterError
from ...core.exact import Exact, option_count, option_number, parse_options, parse_parameters, require_rational
from ...core.outcome import Claim, Status
from ...core.stored import ball_text, pieces_text
from ...core.subdivision import certify_positive
from .. import Attempt, Phases
from .equilibria import equilibria
from .trajectory_claims import initial_point_claim, parse_initial_point, paving_claim, region_not_invariant_claim
from .model import Gimbal
from .closed_forms import damping_margin
from .vdot_tests import rational_points_inside
from .moment_scene import KNOWN as KNOWN_MOMENTS, scene_moment_law
from .moment_expr import QuadratureBudgetSpent, quadrature_budget
from .paper import PAPER_SCHEMA, audit as audit_paper
from .declarations import (ALL_CLAIMS, CLAIMS, HEADLINE, MAX_PIECES_LIMIT, OPT_IN_CLAIMS, OPTIONS, PARAMETERS,
                         RATIONAL)
from .claim_context import ClaimContext, LyapunovModel, exact_ball, fmt, make_claim, to_fmpq, vdot_claim
from .direct_claims import vdot_direct_claim
from .sublevel_claims import invariant_claim, largest_sublevel_claim, natural_sublevel_claim
from .mu_claims import best_mu_claim, best_mu_direct_claim

__all__ = ["CLAIMS", "OPT_IN_CLAIMS", "ALL_CLAIMS", "HEADLINE", "PARAMETERS", "RATIONAL", "LyapunovModel", "validate",
           "attempt", "gimbal_from_parameters", "maximum_M"]


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



# ------------------------------------------------------------------------------------ equilibria

def _hurwitz_row(coeffs) -> dict:
    """The Routh-Hurwitz coefficients of an equilibrium's row (enclosures as text; rigor-gyro check recomputes
    them from the Jacobian and re-decides the stability)."""
    a1, a2, a3 = coeffs
    return {"polynomial": "lambda^3 + a1 lambda^2 + a2 lambda + a3 = det(lambda I - J)", "a1": fmt(a1, 8),
            "a2": fmt(a2, 8), "a3": fmt(a3, 8), "a1 a2 - a3": fmt(a1 * a2 - a3, 8)}


def _equilibria_claim(ctx: ClaimContext, inv: Claim | None, R: arb | None) -> Claim:
    g, xs = ctx.g, ctx.xs
    E = equilibria(g)
    ctx.witnesses["equilibria"] = {"pieces": E.pieces}
    c_set = exact_ball(to_fmpq(Fraction(inv.details["c_set"]))) if inv is not None and "c_set" in inv.details else None
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
        x2 = e.exact or fmt(e.x2, 10)
        rows.append({"x1": fmt(e.x1, 12), "x2": x2, "case": e.case, "stability": e.stability, "estimate": where,
                     "eigenvalues": [f"{fmt(z.real, 8)} + {fmt(z.imag, 8)} i" for z in e.eigenvalues],
                     **({"routh_hurwitz": _hurwitz_row(e.hurwitz)} if e.hurwitz is not None else {})})
        # a Routh-Hurwitz row lists no eigenvalues (acb_mat.eig did not separate them): the statement's
        # "each with the eigenvalues" is met by its characteristic polynomial's coefficients instead
        by = (" (by Routh-Hurwitz from the coefficients of det(lambda I - J), row routh_hurwitz: the eigenvalues "
              "were not separated at this precision, so none are listed)") if e.hurwitz is not None else ""
        texts.append(f"({fmt(e.x1, 8)}, {x2}, 0) [{e.case}]: {e.stability}{by}, {where}")
    undecided = [r for r in rows if r["stability"] == "undecided" or r["estimate"] == "undecided"]
    if not E.complete or undecided:
        return make_claim("equilibria", Status.INCONCLUSIVE,
                          (E.reason if not E.complete else f"{len(undecided)} equilibria with undecided stability or "
                       "membership: raise --maxprec") + "; found: " + "; ".join(texts), equilibria=rows)
    return make_claim("equilibria", Status.PROVED, f"{len(rows)} equilibria with |x2| <= pi: " + "; ".join(texts),
                      equilibria=rows)


# ------------------------------------------------------------------------------------ V > 0

def _v_positive_claim(ctx: ClaimContext) -> Claim:
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
            x1q, x3q = (exact_ball(to_fmpq(exact_fraction(y.mid()))) for y in (x1, x3))
            v = g.V(x1q, x2, x3q)
            if certainly_le(v, 0):
                return make_claim("v_positive", Status.REFUTED,
                                  f"V = {fmt(v, 6)} <= 0 at x1 = {fmt(x1q)}, x2 = {fmt(x2)}, x3 = {fmt(x3q)} "
                                  + ("(certified; psi <= 0 there, i.e. mu H - q + ... fails)" if key == "psi" else
                                 "(certified; f <= 0 at a point of (0, x2*]: the law destabilises)"),
                                  {"point": {"x1": ball_text(x1q), "x2": ball_text(x2), "x3": ball_text(x3q)},
                               "V": fmt(v, 20)},
                                  witness={"x1": fmt(x1q, 20), "x2": fmt(x2, 20), "x3": fmt(x3q, 20)})
        hint = ("certified false at that point, so no precision changes it (V itself was not certified <= 0 at a "
                "rational point there)" if r.status is Status.REFUTED else "try --maxprec or max_pieces")
        return make_claim("v_positive", Status.INCONCLUSIVE, f"could not certify {text} on [0, x2*]: {r.reason}; {hint}",
                          decides=r.stuck_value)
    return make_claim("v_positive", Status.PROVED,
                  "on [0, x2*]: " +
                  "; ".join(t for t, _ in steps) + f" certified on {pieces} pieces (S, f/x and psi are even); hence "
                  "V = phi(x2) + S/2 (x3 + f3/S)^2 + 1/2 (mu x3 + h x1)^2 > 0 off the origin (at x2 = 0, "
                  "phi = 0 and the squares vanish only at x1 = x3 = 0; psi is enclosed through x2 = 0 "
                  "by the removable form of q)", pieces=pieces)



# ------------------------------------------------------------------------------------ attempt

def maximum_M(model: LyapunovModel, prec: int):
    """The certified maximum M of q over [0, x2*] (an Extremum), as ``constants`` computes it (shared through a
    box gimbal's extrema cache)."""
    return ClaimContext(model, prec).M_max()


def attempt(model: LyapunovModel, wanted: list[str], prec: int) -> Attempt:
    """Evaluate the requested claims at the current precision (set by the prover). An expression law's
    quadratures share one budget per attempt (:func:`.moment_expr.quadrature_budget`): when it is spent, the
    claims not yet decided are inconclusive, naming it (never refuted, never a crash)."""
    ctx = ClaimContext(model, prec)
    with quadrature_budget(ctx.g.law):
        return _attempt(ctx, model, wanted)


def _natural_level(ctx) -> tuple:
    """(the natural sublevel's level, its reach as a ball) when natural_sublevel ran, else (None, None)."""
    nat = getattr(ctx, "natural", None)
    return (nat[0], None if nat[1] is None else arb(nat[1])) if nat else (None, None)


def _attempt(ctx: "ClaimContext", model: LyapunovModel, wanted: list[str]) -> Attempt:
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
            claims.append(make_claim(
                "constants", Status.PROVED if finite and conv else Status.INCONCLUSIVE,
                (f"m = {fmt(k['m'])} ({ctx.m_max().pieces} pieces), M = {fmt(k['M'])} ({ctx.M_max().pieces} pieces), "
                 f"p = {fmt(k['p'])}, k_min = {fmt(k['k_min'])}, mu in ({fmt(k['mu_min'])}, {fmt(k['mu_max'])}), "
                 f"R1 = {fmt(k['R1'])}, R2 = {fmt(k['R2'])}" + note) if finite and conv else
                "the maxima m, M did not converge to the requested width: raise --maxprec or the max_pieces option",
                decides=None if finite and conv else (k["m"] if not ctx.m_max().converged else k["M"]),
                m_pieces=ctx.m_max().pieces, M_pieces=ctx.M_max().pieces))
        if "damping_condition" in wanted:
            k = ctx.constants()
            c = ctx.g.c
            parts = [("k > p A0/H (18)", c.k, k["k_min"]), ("mu > p/H", c.mu, k["mu_min"]), ("mu < k/A0", k["mu_max"], c.mu)]
            holds = [certainly_gt(x, y) for _, x, y in parts]
            fails = [certainly_le(x, y) for _, x, y in parts]
            desc = "; ".join(f"{t}: {fmt(x)} vs {fmt(y)}" for t, x, y in parts)
            ce, decides = None, None
            if all(holds):
                st, why = Status.PROVED, "certified: " + desc
            elif any(fails):
                bad = [t for (t, _, _), f in zip(parts, fails) if f]
                st, why = Status.REFUTED, f"fails ({', '.join(bad)}): " + desc
                ce = {"violated": [{"inequality": t, "left": fmt(x, 20), "right": fmt(y, 20)}
                                   for (t, x, y), f in zip(parts, fails) if f]}
            else:
                st, why = Status.INCONCLUSIVE, "not separated at this precision: " + desc
                decides = next(x - y for (_, x, y), h in zip(parts, holds) if not h)
            # the margin in k to the nearest threshold of every condition (k_min of (18), mu A0 of (16))
            margin, binding, each = damping_margin(ctx.g, k["k_min"])
            quantities["damping_margin"] = margin
            claims.append(make_claim("damping_condition", st, why + f"; design margin in k = min(k/k_min, k/(mu A0)) - 1 = "
                                     f"{fmt(margin, 6)}, binding: {binding}", ce, decides, binding=binding,
                                     margins={n: fmt(v, 6) for n, v in each.items()}))
        R, how = (None, "")
        if any(c in wanted for c in ("vdot_nonpositive", "psi_test", "invariant_estimate")):
            R, how = ctx.R_used()
            quantities["R_used"] = R
        vclaim = None
        if "vdot_nonpositive" in wanted or "invariant_estimate" in wanted:
            with phase("vdot_nonpositive"):
                vclaim, vinfo = vdot_claim(ctx, R, how)
            if vclaim.status is Status.PROVED:
                ctx.witnesses["vdot_nonpositive"] = {"R": ball_text(R), **vinfo["record"]}
            if "vdot_nonpositive" in wanted:
                claims.append(vclaim)
        if "psi_test" in wanted:
            with phase("psi_test"):
                pclaim_psi, pinfo = vdot_claim(ctx, R, how, "psi_test")
            if pclaim_psi.status is Status.PROVED:
                ctx.witnesses["psi_test"] = {"R": ball_text(R), **pinfo["record"]}
            claims.append(pclaim_psi)
        if "vdot_direct" in wanted:
            with phase("vdot_direct"):
                claims.append(vdot_direct_claim(ctx, quantities))
        pclaim = None
        if "v_positive" in wanted or "invariant_estimate" in wanted:
            with phase("v_positive"):
                pclaim = _v_positive_claim(ctx)
            if "v_positive" in wanted:
                claims.append(pclaim)
        if "invariant_estimate" in wanted:
            if vclaim.status is Status.PROVED and pclaim.status is Status.PROVED:
                with phase("invariant_estimate"):
                    claims.append(invariant_claim(ctx, R, quantities))
            else:
                dep = vclaim if vclaim.status is not Status.PROVED else pclaim
                claims.append(make_claim("invariant_estimate", Status.INCONCLUSIVE,
                                         "rests on vdot_nonpositive and v_positive, which are not both proved",
                                         decides=dep.decides if dep.status is Status.INCONCLUSIVE else None))
                if dep.status is Status.REFUTED:
                    claims[-1].precision_cannot_help = f"it rests on {dep.id}, which is refuted"
        if "largest_sublevel" in wanted:
            with phase("largest_sublevel"):
                claims.append(largest_sublevel_claim(ctx, quantities))
        # opt-in (about 2 s and 1e4 boxes on the example): only when claims_only names it (OPT_IN_CLAIMS)
        if "natural_sublevel" in wanted:
            with phase("natural_sublevel"):
                claims.append(natural_sublevel_claim(ctx, quantities))
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
                claims.append(best_mu_claim(ctx, quantities))
        if "best_mu_direct" in wanted:
            with phase("best_mu_direct"):
                claims.append(best_mu_direct_claim(ctx, quantities))
    except QuadratureBudgetSpent as e:
        # a budget never decides: the claim being decided and those not reached are undecided, naming it
        # (more precision cannot help: it only makes each quadrature dearer)
        done_ids = {c.id for c in claims}
        for cid in wanted:
            if cid not in done_ids and cid in CLAIMS:
                c = make_claim(cid, Status.INCONCLUSIVE, f"undecided: {e}; a law with a closed-form G (moment = \"table\", "
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
