"""Audit rows for what Agafonov et al. (2013) mislabel or leave open (issue 39): the equation-label slips, the
exact radius behind R1 (13) at the scene's mu (rho1), the mu that the paper says it does not optimise in
(13)-(14), and whether region (17) is positively invariant (a certified trajectory).

Each row is decided in ball arithmetic (a label slip is a reading of the text, stated as such, with the
evidence in the paper's own cross-references). Precision: the working one. Fails when: never raises; a
computation that does not separate its balls gives an ``undecided`` row.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_gt, certainly_lt, certainly_positive, decimal_bounds, exact_fraction
from ...core.outcome import AuditRow, AuditStatus
from ...core.subdivision import best_first_bisection, enclose_max
from .model import Gimbal, hypot_ball
from .closed_forms import closed_form_constants
from .trajectories import fraction_text, region_exit

__all__ = ["label_rows", "rho1_row", "best_formula_mu_row", "invariance_row"]


def _fmt(x: arb, d: int = 10) -> str:
    lo, hi = decimal_bounds(x, d)
    return lo if lo == hi else f"[{lo}, {hi}]"


def label_rows() -> list[AuditRow]:
    """The equation-label slips of section 2: each a misprint of a label, read from the paper's own
    cross-references."""
    return [
        AuditRow("label (13)", "x1^2 + x3^2 < R1^2, R1^2 = D1/D2, (11)", "label (13)", None, AuditStatus.MISPRINT,
                 "the inequality defining R1 carries the label (11), already used for k > M A0/H; the example computes "
                 "R1 'by formulas (13), (14)' and (12), (14) stand around it: it is (13)"),
        AuditRow("label (6)", "the inequality (11) coincides with (11) (M = a)", "(11) coincides with (6) (M = a)", None,
                 AuditStatus.MISPRINT,
                 "in the linear setting f = a x2, M = a and (11) k > M A0/H becomes (6) k > a A0/H; the sentence compares "
                 "(11) with itself (the parallel sentence after (18) compares (18) with (6))"),
        AuditRow("label Psi2", "Psi1 > H/(A0 B0) (mu H cos^2 x2* - A0 m) - ...", "Psi2 > H/(A0 B0) (mu H cos^2 x2* - A0 m) - ...",
                 None, AuditStatus.MISPRINT,
                 "the bound after 'when bounding Psi2 from below' is a bound of Psi2 (its terms are Psi2's of (8): mu H^2 "
                 "cos^2/(B0 D), the f' term through m, the x1- and x3-terms of Psi2), printed with the name Psi1"),
    ]


def rho1_row(g: Gimbal, xs: arb, R1: arb, printed: str | None, max_pieces: int) -> AuditRow | None:
    """rho1 = max over |x2| <= x2* of |(c11, c13)| / c10 (Psi1 = c10 + c11 x1 + c13 x3, see
    :meth:`Gimbal.psi_coefficients`) at the scene's mu: Psi1 > 0 on the whole disc cylinder of radius r iff
    r < 1/rho1. R1 (13) is a lower bound of 1/rho1 (Cauchy-Schwarz and the bounds of section 2); the row says
    by how much. c10 > 0 is required on the range (else no radius works)."""
    def rho(x2: arb) -> arb:
        (c10, c11, c13), _ = g.psi_coefficients(x2)
        if not certainly_positive(c10):
            return arb("inf")
        return hypot_ball(c11, c13) / c10
    for x2 in (arb(0), arb(xs.lower())):        # exact points of the range
        # c10 <= 0 at a point of the range: Psi1 fails at x1 = x3 = 0 there, no radius works and 1/rho1 does not
        # exist (the claim psi_test reports it); no row, since no precision would decide one
        if certainly_positive(-g.psi_coefficients(x2)[0][0]) or g.psi_coefficients(x2)[0][0].is_zero():
            return None
    # rho1 is even in x2 (c10 even, c11 and c13 odd)
    e = enclose_max(rho, 0, xs, rel_tol="1e-9", max_pieces=max_pieces)
    r = e.ball
    if not (r.is_finite() and certainly_positive(r.lower())):
        return AuditRow("rho1 at mu", "R1 (13) at the scene's mu", "1/rho1: the largest radius with Psi1 > 0 on the "
                        "disc cylinder", None, AuditStatus.UNDECIDED, f"rho1 not enclosed: {_fmt(r, 6)}")
    exact = 1 / r
    ok = certainly_lt(R1, exact)
    note = (f"rho1 = max over |x2| <= x2* of |(c11, c13)| / c10 = {_fmt(r, 10)} (at x2 = {_fmt(e.argpoint, 6)}): Psi1 > 0 "
            f"on every disc of radius below 1/rho1 = {_fmt(exact, 10)}; R1 (13) = {_fmt(R1, 10)} is "
            f"{decimal_bounds(R1 / exact, 4)[1]} of it" + (f" (printed {printed})" if printed else "") +
            ": the bound (12) gives away the rest (Cauchy-Schwarz on the two terms, and the worst x2 for each factor "
            "separately)")
    return AuditRow("rho1 at mu", "R1 (13) at the scene's mu", "1/rho1: the largest radius with Psi1 > 0 on the disc "
                    "cylinder, above R1", exact, AuditStatus.CONFIRMED if ok else AuditStatus.UNDECIDED, note)


def _r12(g: Gimbal, m: arb, M: arb, mu: arb) -> tuple[arb, arb]:
    k = closed_form_constants(g.with_mu(mu), m, M)
    return k["R1"], k["R2"]


def best_formula_mu_row(g: Gimbal, m: arb, M: arb, mu_lo: arb, mu_hi: arb, max_pieces: int = 400) -> AuditRow | None:
    """The mu of (16) that maximises R = min(R1, R2) of (13)-(14) ('this problem is not solved here'): a
    certified bracket of max over (16) of min(R1, R2) (a lower end at an exact mu where both are enclosed, an
    upper end by best-first bisection of (16) with R1, R2 over each mu piece), and the mu attaining the lower
    end. R1 decreases and R2 increases through the optimum for the example, so it is where R1 = R2.
    None (no row) when (16) is certainly empty: there is no mu to choose (the claim best_mu says so), and no
    precision would decide a row about it."""
    lo, hi = exact_fraction(mu_lo.upper()), exact_fraction(mu_hi.lower())
    if not lo < hi:
        if certainly_gt(mu_lo, mu_hi) or (mu_lo - mu_hi).is_zero():     # (16) is open: certainly empty
            return None
        return AuditRow("best mu of (13)-(14)", "'the choice of mu ... is not solved here'", "max over (16) of "
                        "min(R1, R2)", None, AuditStatus.UNDECIDED, "the ends of the mu interval (16) are not separated at this precision")

    def q(x: Fraction) -> arb:
        return arb(fmpq(x.numerator, x.denominator))

    # the crossing R1 = R2 by bisection on exact rationals (a search: its result is only a point to evaluate)
    a, b = lo, hi
    for _ in range(60):
        c = (a + b) / 2
        R1, R2 = _r12(g, m, M, q(c))
        if certainly_gt(R1, R2):
            a = c
        elif certainly_lt(R1, R2):
            b = c
        else:
            break
        a, b = exact_fraction(q(a).mid()), exact_fraction(q(b).mid())
    mu_star = exact_fraction(q((a + b) / 2).mid())
    R1s, R2s = _r12(g, m, M, q(mu_star))
    best = R1s.min(R2s)
    target = best.lower()

    def bound(x: arb, y: arb) -> arb:
        R1, R2 = _r12(g, m, M, x.union(y))
        return R1.upper().min(R2.upper())
    pieces, count = best_first_bisection(q(lo), q(hi), bound, lambda mid: None,
                                         lambda up: certainly_lt(up, target * (1 + arb("1e-9"))) or
                                         not certainly_gt(up, target * (1 + arb("1e-9"))), max_pieces)
    U = pieces[0][2]
    for _, _, u in pieces:
        if certainly_gt(u, U):
            U = u
    status = AuditStatus.CONFIRMED if U.is_finite() else AuditStatus.UNDECIDED
    return AuditRow("best mu of (13)-(14)", "'the choice of mu from (16) ... is not solved here' (mu = 0.02 taken)",
                    "max over (16) of R = min(R1, R2) of (13)-(14)", best, status,
                    f"at mu = {float(mu_star):.10g} (R1 = R2 there to the digits shown: R1 = {_fmt(R1s, 8)}, R2 = "
                    f"{_fmt(R2s, 8)}) R = {_fmt(best, 10)}; no mu of (16) gives more than {decimal_bounds(U, 10)[1]} (R1, R2 "
                    f"over {count} mu pieces): the formulas' best radius, against R = R2 at the paper's mu = 0.02")


#: the audit's trajectory from the edge of region (17) takes at most this many steps (the paper's example leaves in
#: a few; a scene whose trajectory stays inside would otherwise integrate at every precision the prover tries)
AUDIT_EXIT_STEPS = 200


def invariance_row(g: Gimbal, R: arb, xs: arb, printed: str) -> AuditRow | None:
    """'the attraction region |x2| <= x2*, x1^2 + x3^2 < R^2' as a positively invariant set: refuted by a certified
    trajectory (validated Taylor flow of system (2), kinds/lyapunov/trajectories.py) that starts in region (17)
    and leaves it. (The points of (17) may still be attracted: leaving does not refute attraction; it refutes
    the argument, which needs the region positively invariant.) None (no row) when this trajectory does not
    certainly leave: that decides nothing (other points might leave), and no precision would."""
    tr = region_exit(g, R, xs, max_steps=AUDIT_EXIT_STEPS)
    if not tr.reached:
        return None
    end = tr.flow.steps[-1].end
    r2 = end[0] * end[0] + end[2] * end[2]
    return AuditRow("(17) positively invariant", f"region (17) with R = {printed} an attraction region",
                    "(17) positively invariant (what V > 0, Vdot <= 0 on it would need to make it one)", r2.sqrt(),
                    AuditStatus.REFUTED,
                    f"the solution from (x1, x2, x3) = ({fraction_text(tr.point[0])}, 0, 0), in the region, has x1^2 + x3^2 in "
                    f"{_fmt(r2, 8)} > R^2 = {_fmt(R * R, 8)} at t = {fraction_text(tr.time)} ({len(tr.steps)} steps of a "
                    f"certified Taylor flow, order {tr.order}; the opt-in claim region_not_invariant stores and re-checks it): "
                    "Vdot <= 0 on (17) does not keep solutions in it, so (17) is not shown to be an attraction region; the "
                    "certified sublevel sets (invariant_estimate, largest_sublevel) are")
