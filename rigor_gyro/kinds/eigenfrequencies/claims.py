"""Eigenfrequencies of an astatic gyroscope with an elastic gimbal (Rudenko 1976): scene kind
``eigenfrequencies``.

The claims. Model: the characteristic quartic Q(omega) of (1)-(2) and the nu quadratics (4), in
:mod:`.model`.

Guarantee: every claim is decided by Arb balls over the exact rationals a, b, eps, Omega2 (and the
exact ``hz_scale`` if given). The roots omega_j are isolated by :mod:`rigor_gyro.core.polyroots` (exact
squarefreeness, exact sign changes), so "four real, positive, simple roots" is a theorem. Brackets
and approximations are evaluated in ball arithmetic; a bracket is proved when lo <= omega_j <= hi is
certain and refuted when a certified strict violation exists.

Precision: the caller's, escalated by :mod:`rigor_gyro.prover` until omega_j and freq_hz_j have
relative width <= ``rel_width`` (scene option, default 1e-30).

Fails when: parameters leave the domain b > 1, a > b, eps > 0, Omega2 > 0: ParameterError naming the
parameter (exit 2).

A scene with its own ``[system]`` table (a gyroscopic system written as matrices, issue 42) is validated by
:func:`.system_model.validate_system` and decided by :mod:`.system_claims` (claims ``roots``, ``stability``,
``brackets``, named in ``[claims] only``); this module only dispatches to them, so the paper's path stays the
fast path.

Reference: Rudenko V. M., Opredelenie sobstvennykh chastot astaticheskogo giroskopa s uprugim
kardanovym podvesom, Izv. AN SSSR MTT, 1976 (seed 002 in shared/seeds).
"""
from __future__ import annotations

from dataclasses import dataclass

from flint import arb, fmpq

from ...core.balls import (ball, certainly_ge, certainly_gt, certainly_le, certainly_lt,
                              certainly_positive, decimal_bounds, rel_width_at_most)
from ...core.errors import ParameterError
from ...core.audit import check_printed
from ...core.exact import Exact, option_number, parse_options, parse_parameters, require_rational
from ...core.outcome import Claim, Status
from ...core.polyroots import isolate_polynomial
from .. import Attempt, Phases
from .system_claims import SYSTEM_CLAIMS, attempt_system
from .system_model import SystemModel, validate_system
from .paper import PAPER_SCHEMA, audit as audit_paper, formula_table
from .model import (BRACKETS, NotReal, Params, approximation, approx_rel_error, bracket, bracket_slack, characteristic_quartic, nu_bounds,
                    nu_identities, nu_quadratics, nus_exactly_equal, r2_denominator)

__all__ = ["CLAIMS", "ALL_CLAIMS", "SYSTEM_ONLY_CLAIMS", "PARAMETERS", "RudenkoModel", "validate", "attempt",
           "statements", "available_claims", "characteristic_quartic", "nu_quadratics"]

PARAMETERS = {"a": "(A1+A2+A3)/A3", "b": "(A2+A3)/A3", "eps": "K2/K3", "Omega2": "H^2/(K3 A3)",
              "hz_scale": "optional: Hz per sqrt(omega), i.e. sqrt(K3/A3)/(2 pi)"}
REQUIRED = ("a", "b", "eps", "Omega2")
OPTIONS = {"rel_width": "1e-30"}

#: the numbers a report's summary opens with (quantity name -> what it is), in this order
#: (a [system] scene has up to 12 eigenfrequencies: the names beyond 4 appear only in its certificates)
HEADLINE = {**{f"freq_hz_{j}": f"eigenfrequency {j} (Hz)" for j in range(1, 13)},
            "omega_1": "omega_1 (root 1 of the quartic)",
            **{f"omega_{j}": f"omega_{j}" for j in range(2, 13)}}

CLAIMS = {
    "roots": "The characteristic quartic in omega has exactly four roots, all real, positive and simple; "
             "they are enclosed as omega_1 < omega_2 < omega_3 < omega_4 to the requested relative width.",
    "nu_ordering": "The zeros and poles of F are ordered as the paper assumes: 0 < nu1 < nu2 < nu3 < nu4 < nu5 < nu6.",
    "branches": "Each root lies on the branch of F the paper assigns it: omega_1 in (0, nu1), omega_2 in "
                "(nu2, nu3), omega_3 in (nu4, nu5), omega_4 in (nu6, oo).",
    "nu_bounds": "The bounds (5) hold: nu1- <= nu1 <= nu1+, nu2- <= nu2 <= nu2+, nu4- <= nu4 <= nu4+, nu6- <= nu6 <= nu6+.",
    "bracket_1": "Bracket (7) contains omega_1.",
    "bracket_2": "Bracket (8) contains omega_2.",
    "bracket_3": "Bracket (9) contains omega_3.",
    "bracket_4": "Bracket (10) contains omega_4.",
    "approximations": "The relative errors of the approximations (12), (13) (equivalently (14)) against the "
                      "certified roots are enclosed (quantities approx_rel_error_j).",
}


#: the claims of a scene with its own ``[system]`` table (:mod:`.system_claims`): opt-in ids a scene names in
#: ``[claims] only``; "roots" is shared, with the system's statement (:func:`statements`)
SYSTEM_ONLY_CLAIMS = {k: v for k, v in SYSTEM_CLAIMS.items() if k not in CLAIMS}
ALL_CLAIMS = {**CLAIMS, **SYSTEM_ONLY_CLAIMS}


def available_claims(scene) -> tuple[dict[str, str], dict[str, str]]:
    """(the claims a scene gets by default, every claim it may name) for this scene: for a ``[system]`` scene
    :data:`SYSTEM_CLAIMS` (``brackets`` only when it gives brackets) and SYSTEM_CLAIMS; otherwise
    (:data:`CLAIMS`, :data:`ALL_CLAIMS`). The prover, the checker and the margins read it through
    :func:`rigor_gyro.kinds.scene_claims`."""
    if scene.model:
        default = {k: v for k, v in SYSTEM_CLAIMS.items() if k != "brackets" or scene.model.get("brackets")}
        return default, dict(SYSTEM_CLAIMS)
    return dict(CLAIMS), dict(ALL_CLAIMS)


def statements(model) -> dict[str, str]:
    """The statement of each claim for this model: the system's for a ``[system]`` scene, else :data:`CLAIMS`."""
    return dict(SYSTEM_CLAIMS) if isinstance(model, SystemModel) else dict(CLAIMS)


#: parameters a claim does not depend on (a threshold search over them is bad input)
CLAIMS_INDEPENDENT_OF = {"hz_scale": tuple(CLAIMS)}


@dataclass(frozen=True)
class RudenkoModel:
    """Validated exact parameters of an eigenfrequency scene."""

    a: Exact
    b: Exact
    eps: Exact
    Omega2: Exact
    hz_scale: Exact | None
    rel_width: Exact
    paper: dict

    def q(self, name: str) -> fmpq:
        return getattr(self, name).fmpq()


def validate(scene) -> RudenkoModel | SystemModel:
    """Check names and the domain b > 1, a > b, eps > 0, Omega2 > 0 (and hz_scale > 0); a scene with a
    ``[system]`` table is validated by :func:`.system_model.validate_system` instead (its claims: those it names
    among :data:`SYSTEM_CLAIMS`, by default :func:`available_claims`)."""
    if scene.model:
        only = scene.claims_only if scene.claims_only is not None else list(available_claims(scene)[0])
        other = [c for c in only if c not in SYSTEM_CLAIMS]
        if other:
            raise ParameterError(f"claim(s) {other} belong to the paper's parameterisation (Rudenko 1976), not to a "
                                 f"[system] scene, which has {list(SYSTEM_CLAIMS)}")
        return validate_system(scene, tuple(c for c in SYSTEM_CLAIMS if c in only))
    if scene.claims_only is not None:
        other = [c for c in scene.claims_only if c in SYSTEM_ONLY_CLAIMS]
        if other:
            raise ParameterError(f"claim(s) {other} need a [system] table (a gyroscopic system written as matrices)")
    p = scene.parameters
    v = parse_parameters(p, "eigenfrequencies", PARAMETERS, REQUIRED)
    require_rational(v)
    a, b, eps, W = (v[k].rational for k in REQUIRED)
    if not b > 1:
        raise ParameterError(f"parameter 'b' = {p['b']!r}: need b > 1 (b = (A2+A3)/A3)")
    if not a > b:
        raise ParameterError(f"parameter 'a' = {p['a']!r}: need a > b = {p['b']} (a = (A1+A2+A3)/A3)")
    if not eps > 0:
        raise ParameterError(f"parameter 'eps' = {p['eps']!r}: need eps > 0 (eps = K2/K3)")
    if not W > 0:
        raise ParameterError(f"parameter 'Omega2' = {p['Omega2']!r}: need Omega2 > 0 (Omega2 = H^2/(K3 A3))")
    hz = v.get("hz_scale")
    if hz is not None and not hz.rational > 0:
        raise ParameterError(f"parameter 'hz_scale' = {p['hz_scale']!r}: need hz_scale > 0")
    opts = parse_options(scene.options, OPTIONS, "eigenfrequencies")
    rel = option_number(opts["rel_width"], "rel_width", above="0", at_most="1")
    check_printed(scene.paper, PAPER_SCHEMA)
    return RudenkoModel(v["a"], v["b"], v["eps"], v["Omega2"], hz, rel, dict(scene.paper))


# ------------------------------------------------------------------------------- one attempt

def _claim(cid: str, status: Status, reason: str, counterexample: dict | None = None, **details) -> Claim:
    return Claim(cid, CLAIMS[cid], status, reason, details=details, counterexample=counterexample)


def _fmt(x: arb) -> str:
    lo, hi = decimal_bounds(x, 12)
    return f"[{lo}, {hi}]"


def _bounds(x: arb) -> list[str]:
    """[lo, hi] as outward-rounded decimals (the form a counterexample is stored in)."""
    return list(decimal_bounds(x))


def attempt(model: RudenkoModel, wanted: list[str], prec: int) -> Attempt:
    """Evaluate the requested claims at the current precision (set by the prover)."""
    if isinstance(model, SystemModel):
        return attempt_system(model, prec, wanted)
    a, b, eps, W = (model.q(k) for k in REQUIRED)
    claims: list[Claim] = []
    quantities: dict[str, arb] = {}
    notes: list[str] = []
    phase = Phases()
    Q = characteristic_quartic(a, b, eps, W)
    with phase("roots: isolation"):
        pr = isolate_polynomial(Q, rel_tol=model.rel_width.fmpq())
    # --- roots
    omegas: list[arb] = []
    ce = None
    if not pr.squarefree:
        st, why = Status.REFUTED, f"the quartic has a multiple root ({pr.reason}), exactly"
        ce = {"quartic": [str(c) for c in Q.coeffs()], "gcd_with_derivative": str(Q.gcd(Q.derivative()))}
    elif not pr.verified:
        st, why = Status.INCONCLUSIVE, pr.reason
    else:
        nonpos = [x for x in pr.real if not certainly_positive(x)]
        if pr.nonreal:
            st, why = Status.REFUTED, (f"{len(pr.nonreal)} roots are certainly non-real: "
                                       + "; ".join(f"{_fmt(z.real)} + {_fmt(z.imag)} i" for z in pr.nonreal))
            ce = {"nonreal_roots": [{"re": _bounds(z.real), "im": _bounds(z.imag)} for z in pr.nonreal]}
        elif any(certainly_le(x, 0) for x in nonpos):
            st, why = Status.REFUTED, f"a root is certainly <= 0: {[_fmt(x) for x in nonpos]}"
            ce = {"nonpositive_roots": [_bounds(x) for x in nonpos if certainly_le(x, 0)]}
        elif nonpos:
            st, why = Status.INCONCLUSIVE, f"sign of root(s) {[_fmt(x) for x in nonpos]} undecided"
        else:
            omegas = pr.real
            st, why = Status.PROVED, ("gcd(Q, Q') = 1 exactly (simple roots); Arb isolated 4 roots with "
                                      "imaginary part exactly 0, each confirmed by an exact sign change of Q; "
                                      f"relative widths <= {model.rel_width}")
            if not pr.width_met:
                st, why = Status.INCONCLUSIVE, (f"roots isolated but not yet to relative width {model.rel_width} "
                                                "(raise --maxprec or relax option rel_width)")
    if "roots" in wanted:
        claims.append(_claim("roots", st, why, ce))
    for j, w in enumerate(pr.real if pr.verified and not pr.nonreal else [], start=1):
        quantities[f"omega_{j}"] = w
    widths_met = pr.width_met
    # --- nus
    q14, q26 = nu_quadratics(a, b, eps)
    r14, r26 = isolate_polynomial(q14), isolate_polynomial(q26)
    nus: dict[int, arb] = {3: arb(1 / (b - 1)), 5: arb(b / (b - 1))}
    if r14.verified and len(r14.real) == 2:
        nus[1], nus[4] = r14.real
    if r26.verified and len(r26.real) == 2:
        nus[2], nus[6] = r26.real
    for k in sorted(nus):
        quantities[f"nu_{k}"] = nus[k]
    have_nus = len(nus) == 6
    ordered, equal, odec = None, set(), None
    if {"nu_ordering", "branches"} & set(wanted) or any(w.startswith("bracket") for w in wanted):
        if not have_nus:
            ordered, oce = None, None
            ost, owhy = Status.INCONCLUSIVE, f"nu quadratics not isolated: {r14.reason}; {r26.reason}"
        else:
            chain = [arb(0)] + [nus[k] for k in range(1, 7)]
            names = ["0"] + [f"nu{k}" for k in range(1, 7)]
            bad = [(names[i], names[i + 1]) for i in range(6) if certainly_ge(chain[i], chain[i + 1])]
            und = [(names[i], names[i + 1]) for i in range(6)
                   if not certainly_lt(chain[i], chain[i + 1]) and not certainly_ge(chain[i], chain[i + 1])]
            # overlapping balls of two nus may be the same number: decided exactly (rationals, gcds)
            ident = nu_identities(a, b, eps)
            equal = {(x, y) for x, y in und if x != "0" and nus_exactly_equal(ident[int(x[2])], ident[int(y[2])])}
            und = [pair for pair in und if pair not in equal]
            bad += sorted(equal)
            oce = None
            if bad:
                ordered = False
                ost, owhy = Status.REFUTED, "certified violation(s): " + "; ".join(
                    f"{x} = {_fmt(chain[names.index(x)])} " + ("= (exactly) " if (x, y) in equal else ">= ")
                    + f"{y} = {_fmt(chain[names.index(y)])}" for x, y in bad)
                oce = {"violations": [{"left": x, "left_value": _bounds(chain[names.index(x)]), "right": y,
                                       "right_value": _bounds(chain[names.index(y)]),
                                       **({"exactly_equal": "decided in rational arithmetic (root of the exact "
                                           "quadratic (4) / common root of both)"} if (x, y) in equal else {})}
                                      for x, y in bad]}
            elif und:
                ost, owhy = Status.INCONCLUSIVE, f"order of {und} undecided at this precision"
                x, y = und[0]
                odec = chain[names.index(y)] - chain[names.index(x)]
            else:
                ordered = True
                ost, owhy = Status.PROVED, "all six strict inequalities certified"
        if "nu_ordering" in wanted:
            claims.append(_claim("nu_ordering", ost, owhy, oce))
            claims[-1].decides = odec
    if "branches" in wanted:
        claims.append(_branch_claim(omegas, nus, ordered, equal))
    if "nu_bounds" in wanted:
        claims.append(_nu_bounds_claim(model, nus, quantities))
    balls = Params(ball(model.a.fmpq()), ball(model.b.fmpq()), ball(model.eps.fmpq()), ball(model.Omega2.fmpq()))
    for j in range(1, 5):
        cid = f"bracket_{j}"
        if cid in wanted:
            claims.append(_bracket_claim(j, balls, omegas, quantities, model))
    if "approximations" in wanted:
        claims.append(_approx_claim(balls, omegas, quantities, tuple(model.q(k) for k in REQUIRED)))
    if model.hz_scale is not None and omegas:
        s = ball(model.hz_scale.fmpq())
        for j, w in enumerate(omegas, start=1):
            quantities[f"freq_hz_{j}"] = f = s * w.sqrt()
            widths_met = widths_met and rel_width_at_most(f, model.rel_width.fmpq())
    paper, formulas = [], formula_table()
    if model.paper:
        with phase("paper audit"):
            paper = audit_paper(model, balls, omegas)
    return Attempt(claims, quantities, paper, formulas, notes, widths_met, phase_seconds=phase.seconds,
                   width_quantities=tuple(k for k in quantities if k.startswith(("omega_", "freq_hz_"))
                                          and not rel_width_at_most(quantities[k], model.rel_width.fmpq())))


def _branch_claim(omegas: list[arb], nus: dict[int, arb], ordered: bool | None, equal: set = frozenset()) -> Claim:
    if len(omegas) != 4 or len(nus) != 6:
        return _claim("branches", Status.INCONCLUSIVE, "needs the four roots and six nus enclosed")
    intervals = [(arb(0), nus[1], "(0, nu1)"), (nus[2], nus[3], "(nu2, nu3)"),
                 (nus[4], nus[5], "(nu4, nu5)"), (nus[6], None, "(nu6, oo)")]
    fails, undecided, ce = [], [], []
    empty = {2: ("nu2", "nu3") in equal, 3: ("nu4", "nu5") in equal}    # an open interval (x, x) is empty
    decides = None
    for j, (w, (lo, hi, label)) in enumerate(zip(omegas, intervals), start=1):
        inside = certainly_lt(lo, w) and (hi is None or certainly_lt(w, hi))
        outside = certainly_ge(lo, w) or (hi is not None and certainly_ge(w, hi)) or empty.get(j, False)
        if not inside and not outside and decides is None:
            decides = (w - lo) if not certainly_lt(lo, w) else (hi - w)
        if outside:
            fails.append(f"omega_{j} = {_fmt(w)} not in {label}")
            ce.append({"root": f"omega_{j}", "value": _bounds(w), "branch": label, "branch_lo": _bounds(lo),
                       "branch_hi": _bounds(hi) if hi is not None else "oo"})
        elif not inside:
            undecided.append(f"omega_{j} vs {label}")
    if fails:
        why = "; ".join(fails) + ("" if ordered else " (the nu ordering the paper assumes fails)")
        return _claim("branches", Status.REFUTED, why, {"outside": ce})
    if undecided:
        c = _claim("branches", Status.INCONCLUSIVE, "undecided: " + "; ".join(undecided))
        c.decides = decides
        return c
    return _claim("branches", Status.PROVED, "each omega_j certainly strictly inside its branch interval")


def _check_bounds(items: list[tuple[str, arb, arb, arb]]) -> tuple[Status, str, dict | None, arb | None]:
    """items: (label, lo, x, hi); proved when lo <= x <= hi certainly for all; refuted (with the
    violations as counterexample) when some x is certainly outside its [lo, hi]; otherwise
    inconclusive, with the first undecided margin (x - lo or hi - x) as what decides it."""
    fails, und, ce, decides = [], [], [], None
    for label, lo, x, hi in items:
        if certainly_le(lo, x) and certainly_le(x, hi):
            continue
        if certainly_gt(lo, x) or certainly_gt(x, hi):
            fails.append(f"{label}: {_fmt(x)} not in [{_fmt(lo)}, {_fmt(hi)}]")
            ce.append({"quantity": label, "value": _bounds(x), "lower_bound": _bounds(lo), "upper_bound": _bounds(hi)})
        else:
            und.append(label)
            margin = (x - lo) if not certainly_le(lo, x) else (hi - x)
            if decides is None or margin.rad() > decides.rad():     # the widest undecided margin
                decides = margin
    if fails:
        return Status.REFUTED, "certified violation(s): " + "; ".join(fails), {"violations": ce}, None
    if und:
        return Status.INCONCLUSIVE, "undecided at this precision: " + ", ".join(und), None, decides
    return Status.PROVED, "all inequalities certified", None, None


def _nu_bounds_claim(model: RudenkoModel, nus: dict[int, arb], quantities: dict[str, arb]) -> Claim:
    if len(nus) != 6:
        return _claim("nu_bounds", Status.INCONCLUSIVE, "nus not enclosed")
    p = Params(*(ball(model.q(k)) for k in REQUIRED))
    bounds = nu_bounds(p)
    items = []
    for k in (1, 2, 4, 6):
        lo, hi = bounds[k]
        quantities[f"nu_{k}_lower_bound"], quantities[f"nu_{k}_upper_bound"] = lo, hi
        items.append((f"nu{k}", lo, nus[k], hi))
    st, why, ce, decides = _check_bounds(items)
    c = _claim("nu_bounds", st, why, ce)
    c.decides = decides
    return c


def _bracket_claim(j: int, p: Params, omegas: list[arb], quantities: dict[str, arb], model: RudenkoModel) -> Claim:
    cid = f"bracket_{j}"
    if len(omegas) != 4:
        return _claim(cid, Status.INCONCLUSIVE, "needs the certified roots")
    if j in (3, 4) and r2_denominator(*(model.q(k) for k in ("a", "b", "eps"))) == 0:
        return _claim(cid, Status.REFUTED, f"bracket {BRACKETS[j].eq} is undefined for these parameters: the "
                      "denominator b/(b-1) - eps a/(b(a-b)) of R2 is exactly 0, so the bracket gives no bound",
                      {"undefined": "R2 denominator b/(b-1) - eps a/(b(a-b)) = 0 (exact rational arithmetic)"})
    try:
        lo, hi = bracket(j, p, reading="intended")
        # the design margin of the bracket: how far omega_j is from the nearer bound (< 0: outside); with its
        # guard bits it may find a radicand certainly negative that the working precision left straddling 0
        slack = bracket_slack(j, tuple(model.q(k) for k in REQUIRED), omegas[j - 1])
    except NotReal as e:
        return _claim(cid, Status.REFUTED, f"the bracket has no real value for these parameters: {e}",
                      {"not_real": str(e), "radicand": _bounds(e.radicand)})
    quantities[f"bracket_{j}_lo"], quantities[f"bracket_{j}_hi"] = lo, hi
    quantities[f"bracket_{j}_slack"] = slack
    st, why, ce, decides = _check_bounds([(f"omega_{j}", lo, omegas[j - 1], hi)])
    if st is Status.PROVED:
        why = f"{_fmt(lo)} <= omega_{j} <= {_fmt(hi)} certified (reading: {BRACKETS[j].reading_note})"
    c = _claim(cid, st, why, ce)
    c.decides = decides
    return c


def _approx_claim(p: Params, omegas: list[arb], quantities: dict[str, arb], exact: tuple) -> Claim:
    if len(omegas) != 4:
        return _claim("approximations", Status.INCONCLUSIVE, "needs the certified roots")
    parts = []
    for j in range(1, 5):
        try:
            approx = approximation(j, p)
            err = approx_rel_error(j, exact, omegas[j - 1])     # its guard bits may settle a radicand's sign
        except NotReal as e:
            parts.append(f"omega_{j}: approximation not real ({e})")
            continue
        quantities[f"approx_omega_{j}"] = approx
        quantities[f"approx_rel_error_{j}"] = err
        parts.append(f"omega_{j}: {_fmt(err)}")
    finite = all(quantities.get(f"approx_rel_error_{j}", arb("nan")).is_finite() for j in range(1, 5))
    st = Status.PROVED if finite else Status.INCONCLUSIVE
    return _claim("approximations", st, "relative errors (approx - omega)/omega enclosed: " + "; ".join(parts))
