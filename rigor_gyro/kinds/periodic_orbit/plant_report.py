"""From a plant analysis (:func:`.plant_claims.analyse`) to an :class:`~rigor_gyro.kinds.Attempt`: the
claims' verdicts with the rules of :mod:`.claims` (a restricted search never refutes; non-existence only
from an exhaustive search), the quantities of the scene's orbit, the notes, the roots' table and the
witnesses :mod:`.plant_check` re-verifies.

Guarantee: every verdict is the analysis's (decided by Arb balls); this module only words and stores it.
Quantities: theta_star, period, x0_1 .. x0_n, multiplier_j_re/_im, multiplier_modulus_j, stability_margin,
amplitude; with h = 0 and an estimate, df_period, df_amplitude, df_period_difference (period - estimate),
df_amplitude_difference; theta_star_k and stability_margin_k of further genuine orbits.
"""
from __future__ import annotations

from typing import Any

from flint import arb, fmpq

from ...core.balls import (ball, certainly_gt, certainly_le, current_precision, decimal_bounds, decimal_bounds_apart,
                           exact_fraction, working_precision)
from ...core.outcome import Claim, Status
from ...core.stored import exact_text
from .. import Attempt, Phases
from .genuine_outcome import no_orbit_record, orbit_genuine_outcome
from .plant_df import describing_function
from .multipliers import disc_margin
from .plant_orbit import amplitude, neutral_multiplier
from .plant_statements import GUARD_BITS, PLANT_CLAIMS
from .texts import complex_text as _fmt_c, interval_text as _fmt, upper_text, modulus_text as _fmt1, stored_bounds as _bounds

__all__ = ["assemble", "select_orbit"]


def select_orbit(genuine: list) -> tuple[Any, str]:
    """The orbit of the headline quantities: the shortest stable genuine orbit, else the shortest genuine."""
    stable = [v for v in genuine if v.stable is True]
    if stable:
        return stable[0], "the shortest stable genuine orbit" if len(stable) > 1 else "the stable genuine orbit"
    if genuine:
        return genuine[0], "the shortest genuine orbit (none is certified stable)"
    return None, "no genuine orbit"


def _qb(x) -> arb:
    """The ball of an exact rational (no magnitude limit: a dyadic search bound may be below 1e-300)."""
    return arb(fmpq(x.numerator, x.denominator))


def _q(x) -> str:
    return exact_text(exact_fraction(x))


def _claim(cid: str, status: Status, reason: str, counterexample: dict | None = None, **details) -> Claim:
    return Claim(cid, PLANT_CLAIMS[cid], status, reason, details=details, counterexample=counterexample)


def assemble(model, an, wanted: list[str], phase: Phases) -> Attempt:
    """The Attempt of an analysis (module docstring)."""
    claims, quantities, notes, extra = [], {}, [], {}
    if an.sp is None or an.problem:
        why = an.problem or "spectrum unavailable"
        claims = [_claim(c, Status.INCONCLUSIVE, why) for c in wanted]
        if an.stalled:
            for c in claims:
                c.precision_cannot_help = why
        return Attempt(claims, quantities, notes=notes, widths_met=False, stalled=an.stalled)
    sp = an.sp
    T = _qb(an.T_search)
    rng = (f"(0, {_fmt(T, 8)}]" + (" and beyond it by the tail bound, i.e. all of (0, oo)" if an.covers_all
                                   else " (option T_max; roots beyond it not searched)"))
    genuine = [v for v in an.roots if v.kind == "genuine"]
    spurious = [v for v in an.roots if v.kind == "spurious"]
    undecided = [v for v in an.roots if v.kind == "undecided"]
    complete = not an.unknown and not undecided
    exhaustive = complete and an.covers_all
    beyond = (f"; roots beyond T_max = {_fmt(T, 8)} were not searched, so this is not a refutation"
              if not an.covers_all else "")
    no_orbit = (no_orbit_record(_qb(an.T_tail), _qb(an.theta_min), spurious) if exhaustive and not genuine
                else None)
    if an.unknown:
        hp = (Status.INCONCLUSIVE, f"{len(an.unknown)} piece(s) of {rng} undecided, first "
              f"[{_fmt(an.unknown[0].lo, 10)}, {_fmt(an.unknown[0].hi, 10)}]: {an.unknown[0].reason}")
    elif undecided:
        hp = (Status.INCONCLUSIVE, f"{len(an.roots)} roots isolated on {rng}; {len(undecided)} not classified: "
              + "; ".join(f"theta = {_fmt(v.theta, 10)}: {v.reason}" for v in undecided[:3]))
    else:
        hp = (Status.PROVED, f"{len(an.roots)} roots of g on {rng}, each simple and alone in its piece "
              f"({an.pieces} pieces by interval Newton; (0, {_fmt(_qb(an.theta_min), 4)}] root-free near 0: exact "
              f"series bound or the sign of g's leading Taylor coefficient); {len(genuine)} genuine ({', '.join(_fmt(v.theta, 10) for v in genuine)}), "
              f"{len(spurious)} spurious with certified witnesses")
    if "half_period" in wanted:
        claims.append(_claim("half_period", *hp, pieces=an.pieces, roots=len(an.roots)))
    main, why_main = select_orbit(genuine)
    og = orbit_genuine_outcome(main, why_main, genuine, spurious, rng, complete=complete, exhaustive=exhaustive,
                               no_orbit=no_orbit, beyond=beyond, undecided_reason=hp[1])
    if "orbit_genuine" in wanted:
        claims.append(_claim("orbit_genuine", *og))
    none_exists = main is None and exhaustive
    widths_met = True
    if main is not None:
        quantities["theta_star"] = main.theta
        with working_precision(current_precision() + GUARD_BITS):     # exact doubling
            quantities["period"] = 2 * main.theta
        for i, x in enumerate(main.x0, start=1):
            quantities[f"x0_{i}"] = x
        widths_met = certainly_le(2 * main.theta.rad(), ball(model.theta_width.fmpq()))
    if "initial_point" in wanted:
        if main is not None:
            st = (Status.PROVED, f"x(0) of {why_main}: (" + ", ".join(_fmt(x, 12) for x in main.x0)
                  + f") (c . x(0) = h = {model.h} exactly at the exact root)")
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine): there is no initial point", no_orbit)
        else:
            st = (Status.INCONCLUSIVE, "no genuine orbit certified yet" + beyond)
        claims.append(_claim("initial_point", *st))
    if main is not None and main.margin is not None:
        for j, m in enumerate(main.moduli, start=1):
            quantities[f"multiplier_modulus_{j}"] = m
        for j, z in enumerate(main.multipliers, start=1):
            quantities[f"multiplier_{j}_re"] = z.real
            quantities[f"multiplier_{j}_im"] = z.imag
        quantities["stability_margin"] = main.margin
    elif main is not None and main.radius_bound is not None:
        quantities["stability_margin"] = disc_margin(main.radius_bound)
    others = [v for v in genuine if v is not main]
    for k, v in enumerate(others, start=2):
        quantities[f"theta_star_{k}"] = v.theta
        if v.margin is not None:
            quantities[f"stability_margin_{k}"] = v.margin
        elif v.radius_bound is not None:
            quantities[f"stability_margin_{k}"] = disc_margin(v.radius_bound)
    if "multipliers" in wanted:
        bad = [v for v in genuine if v.margin is None]
        if genuine and not bad:
            st = (Status.PROVED, "; ".join(f"theta = {_fmt(v.theta, 10)}: " + (", ".join(
                f"{_fmt_c(z, 10)} (|.| = {_fmt(m, 10)})" for z, m in zip(v.multipliers, v.moduli)) or "none")
                for v in genuine)
                + f"; {main.jacobian_note}")
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine)", no_orbit)
        else:
            st = (Status.INCONCLUSIVE, "; ".join(v.multiplier_reason for v in bad) or
                  "no genuine orbit certified yet" + beyond)
        claims.append(_claim("multipliers", *st))
    if "stable" in wanted:
        stable = [v for v in genuine if v.stable is True]
        if stable:
            s = main if main in stable else stable[0]
            top = (f"has max modulus {_fmt1(s.moduli[0], 10)} < 1" if s.moduli else
                   f"has every multiplier modulus at most {upper_text(s.radius_bound)} < 1 (Gershgorin discs of the "
                   "Jacobian; the multipliers themselves are not isolated)" if s.radius_bound is not None else
                   "has no multipliers (dimension 1: the section is a point, a nearby solution reaches the switching "
                   "point and follows the orbit)")
            margin = s.margin if s.margin is not None else disc_margin(s.radius_bound)
            st = (Status.PROVED, f"the orbit theta* = {_fmt(s.theta, 12)} {top}; stability margin {_fmt(margin, 10)}"
                  + (f"; {len(stable)} stable genuine orbits" if len(stable) > 1 else "")
                  + (f"; unstable: {', '.join(_fmt(v.theta, 8) for v in genuine if v.stable is False)}"
                     if any(v.stable is False for v in genuine) else ""))
        elif complete and genuine and all(v.stable is False for v in genuine):
            text = ("every genuine orbit (symmetric, two switchings per period: the only orbits searched) has a "
                    "multiplier of modulus certainly > 1: "
                    + "; ".join(f"theta = {_fmt(v.theta, 10)}: max |.| = {_fmt1(v.moduli[0], 10)}" for v in genuine))
            unstable = {"searched": "(0, oo)", "tail_point": _bounds(_qb(an.T_tail)) if an.T_tail is not None else None,
                        "orbits": [{"theta": _bounds(v.theta),
                                    "modulus_above_1": _bounds(next(m for m in v.moduli if certainly_gt(m, 1)))}
                                   for v in genuine]}
            st = (Status.REFUTED, text, unstable) if exhaustive else (Status.INCONCLUSIVE, text + beyond)
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine), so no stable symmetric orbit with two "
                  "switchings per period (the only orbits searched; other self-oscillations, asymmetric or with more "
                  "switchings, are not excluded)", no_orbit)
        elif genuine and neutral_multiplier(model):
            st = (Status.INCONCLUSIVE, "every symmetric orbit of this plant has the multiplier -1 exactly (the zero "
                  "eigenvalue of M is uncontrollable or unobservable: N_c(0) = 0 exactly, a combination w . x is "
                  "conserved by the flow and mirrored by the symmetry), a modulus exactly 1 that no precision "
                  "decides: no orbit can be certified stable (asymptotically), and this is not a refutation")
        else:
            st = (Status.INCONCLUSIVE, "stability of the genuine orbits not decided at this precision"
                  if genuine else "no genuine orbit certified yet" + beyond)
        claims.append(_claim("stable", *st))
        if genuine and neutral_multiplier(model) and claims[-1].status is Status.INCONCLUSIVE:
            claims[-1].precision_cannot_help = "a multiplier is exactly -1 (see the reason)"
    if complete and not an.covers_all:
        for c in claims:
            if c.status is Status.INCONCLUSIVE:
                c.precision_cannot_help = ("the scene restricts the search to (0, T_max] and every root there is "
                                           "decided; set option T_max = \"auto\" to search all of (0, oo)")
    witnesses: dict[str, Any] = {}
    if main is not None:
        with phase("amplitude"), working_precision(current_precision() + (GUARD_BITS if an.sp_fine else 0)):
            A, t_star = amplitude(an.sp_fine or sp, main.theta)
        quantities["amplitude"] = A
        witnesses["amplitude"] = {"t": _q(t_star)}
        est = describing_function(model)
        if est.omegas:
            w, Adf, Pdf = min(est.omegas, key=lambda o: abs(float(o[2].mid()) - float(2 * main.theta.mid())))
            quantities["df_period"] = Pdf
            quantities["df_amplitude"] = Adf
            quantities["df_period_difference"] = 2 * main.theta - Pdf
            quantities["df_amplitude_difference"] = A - Adf
            notes.append(f"Describing-function estimate (harmonic balance, h = 0; not a proof): period "
                         f"{_fmt(Pdf, 10)}, amplitude {_fmt(Adf, 10)}; the certified orbit's period minus it "
                         f"{_fmt(2 * main.theta - Pdf, 6)}, amplitude minus it {_fmt(A - Adf, 6)}"
                         + (f" ({len(est.omegas)} estimates; the one nearest in period)" if len(est.omegas) > 1 else ""))
        elif est.reason:
            notes.append(f"Describing-function estimate: {est.reason}.")
    rows = []
    for k, v in enumerate(an.roots, start=1):
        line = f"root {k}: theta = {_fmt(v.theta, 14)}: {v.kind}: {v.reason}"
        if v.margin is not None:
            line += "; multipliers " + ", ".join(_fmt_c(z, 8) for z in v.multipliers) + "; moduli " + ", ".join(
                _fmt1(m, 8) for m in v.moduli) + ("; STABLE" if v.stable else "; UNSTABLE" if v.stable is False else "")
        elif v.radius_bound is not None:
            line += f"; every multiplier modulus <= {upper_text(v.radius_bound)} (Gershgorin discs); STABLE"
        rows.append({"theta": list(decimal_bounds(v.theta, 20)), "kind": v.kind, "reason": v.reason,
                     "moduli": [list(decimal_bounds_apart(m, 1, 12)) for m in v.moduli], "stable": v.stable})
        notes.append(line)
    eigs = ", ".join(_fmt_c(z, 8) for z in sp.eigenvalues())
    notes.insert(0, f"Plant of dimension {model.n}, eigenvalues {eigs}; searched range {rng}; theta_min = "
                 f"{_fmt(_qb(an.theta_min), 6)}; tail point "
                 f"{_fmt(_qb(an.T_tail), 8) if an.T_tail is not None else 'not certified'}; scene orbit: {why_main}.")
    extra["roots"] = rows
    if hp[0] is Status.PROVED:
        witnesses["half_period"] = _witness(an)
    return Attempt(claims, quantities, [], [], notes, widths_met, extra, width_quantities=("theta_star",),
                   witnesses=witnesses, phase_seconds=phase.seconds)


def _witness(an) -> dict[str, Any]:
    pieces = []
    for pc in an.piece_list:
        item = {"lo": _q(pc.lo.lower()), "hi": _q(pc.hi.upper()), "kind": pc.status.value}
        if pc.parts:
            item["splits"] = [_q(s) for s in pc.parts]
        pieces.append(item)
    roots = []
    for v in an.roots:
        r: dict[str, Any] = {"kind": v.kind}
        if v.witness_t is not None:
            r["witness_t"] = _q(v.witness_t)
        if v.kind == "genuine":
            r["d1"] = _q(v.d1)
            r["right_start"] = _q(v.right_start)
            r["middle"] = [[_q(a.lower()), _q(b.upper())] for a, b in v.middle]
        roots.append(r)
    return {"theta_min": exact_text(an.theta_min), "T": exact_text(an.T_search), "covers_all": an.covers_all,
            "function": "pole_free", "pieces": pieces, "roots": roots}
