"""The claims of a gyroscopic system written in the scene (``[system]``, :mod:`.system_model`): its
eigenfrequencies, its gyroscopic stability, the user's brackets.

* ``roots``: P(lambda) = lambda^z P~(lambda) with z = ``zero_roots`` exactly, P~ even, and its frequency
  polynomial Q(omega) (lambda^2 = -omega) has m = deg Q roots, all real, positive and simple, enclosed as
  omega_1 < ... < omega_m to ``rel_width`` (:func:`rigor_gyro.core.polyroots.isolate_polynomial`: exact
  squarefreeness, Arb isolation, exact sign changes). Refuted with the exact zero-root multiplicity, the exact
  odd terms of P~, the exact gcd(Q, Q'), or the certified non-real / non-positive roots (the pairs
  lambda = +-i sqrt(omega) that are not on the imaginary axis).
* ``stability``: gyroscopic stability, every root of P other than the z declared zero roots simple and on the
  imaginary axis. When lambda = 0 has multiplicity mu = z exactly: the first part of ``roots`` without the width
  requirement, decided by the same exact tests and refuted with the same certified data. When mu != z
  (``roots`` refuted by the multiplicity): refuted by it when mu >= 2 and mu > z (lambda = 0 a multiple root
  beyond the declared ones); otherwise (mu < z: every zero root is among the declared; or mu = 1 > z = 0, a
  simple root on the axis) decided by the same exact tests on P / lambda^mu (:func:`stability_at_multiplicity`),
  no root stored.
* ``brackets``: each user bracket [lo_j, hi_j] (expressions, Arb balls) contains omega_j; decided per root:
  proved when every one is certified, refuted when one is certainly violated (or has no real value, a
  certainly negative square root), the others listed in ``details.per_root``. A bound that certainly divides by
  zero is bad input at validation (:mod:`.system_bounds`); one that is not a finite ball with no such reason
  leaves its root undecided, and no non-finite bound or slack is stored.

Guarantee and precision: as :mod:`.claims` (balls at the prover's precision, escalated to meet rel_width).

Fails when: never on a validated model (bad models are refused by :func:`.system_model.validate_system`).
"""
from __future__ import annotations

from flint import arb, fmpq_poly

from ...core.balls import (ball, certainly_gt, certainly_le, certainly_nonzero, certainly_positive, decimal_bounds,
                              rel_width_at_most)
from ...core.outcome import Claim, Status
from ...core.polyroots import isolate_polynomial
from .. import Attempt, Phases
from .system_model import NotRealBound, SystemModel, frequency_polynomial

__all__ = ["SYSTEM_CLAIMS", "attempt_system", "polynomial_facts", "stability_at_multiplicity"]

SYSTEM_CLAIMS = {
    "roots": "The characteristic polynomial det(lambda^2 M + lambda (G + D) + K) is lambda^z times an even polynomial "
             "(z = option zero_roots) whose frequency polynomial Q(omega) (lambda^2 = -omega) has only real, positive, "
             "simple roots, enclosed as omega_1 < ... < omega_m to the requested relative width (eigenfrequencies "
             "sqrt(omega_j), times hz_scale in Hz).",
    "stability": "Gyroscopic stability: every root of det(lambda^2 M + lambda (G + D) + K) other than the zero_roots "
                 "declared roots lambda = 0 is simple and lies on the imaginary axis.",
    "brackets": "Each bracket of [system] brackets contains its root: lo_j <= omega_j <= hi_j for every j given.",
}


def _fmt(x: arb) -> str:
    lo, hi = decimal_bounds(x, 12)
    return f"[{lo}, {hi}]"


def _bounds(x: arb) -> list[str]:
    return list(decimal_bounds(x))


def polynomial_facts(model: SystemModel):
    """(P, mu, Q, odd): the exact characteristic polynomial, its zero-root multiplicity, the frequency
    polynomial (None unless mu = zero_roots and the rest is even) and the odd powers with nonzero coefficients."""
    P = model.characteristic()
    mu, Q, odd = frequency_polynomial(P, model.zero_roots)
    return P, mu, Q, odd


def _structural(model: SystemModel, P, mu: int, odd: list[int], z: int | None = None) -> tuple[str, dict]:
    """Why P is not lambda^z times an even polynomial (exact; z = zero_roots unless given), and the
    counterexample."""
    z = model.zero_roots if z is None else z
    if mu != z:
        return (f"lambda = 0 is a root of multiplicity {mu} exactly (P's lowest nonzero coefficient is that of "
                f"lambda^{mu}), not zero_roots = {z}" + (": a zero root beyond the declared ones is not simple"
                                                          if mu > max(z, 1) else ""),
                {"zero_root_multiplicity": mu, "zero_roots_declared": z,
                 "characteristic_coefficients": [str(c) for c in P.coeffs()]})
    c = P.coeffs()
    ce = {"odd_powers": [k + mu for k in odd], "odd_coefficients": [str(c[k + mu]) for k in odd],
          "characteristic_coefficients": [str(x) for x in c]}
    why = (f"P / lambda^{z} has nonzero odd terms (powers {[k + mu for k in odd]}), exactly: its roots are not "
           "pairs +-i y (some root has a nonzero real part; damping)")
    rest = fmpq_poly(c[mu:])
    if rest.degree() > 0:          # the roots off the imaginary axis, where Arb isolates them at this precision
        pr = isolate_polynomial(rest)
        if pr.squarefree and pr.verified:
            off = [z for z in pr.nonreal if certainly_nonzero(z.real)] + [x for x in pr.real if certainly_nonzero(x)]
            if off:
                ce["offaxis_roots"] = [{"re": _bounds(z.real), "im": _bounds(z.imag)} if hasattr(z, "imag")
                                       else {"re": _bounds(z), "im": ["0", "0"]} for z in off]
                why += ": " + "; ".join(f"lambda = {_fmt(z.real)} + {_fmt(z.imag)} i" if hasattr(z, "imag")
                                        else f"lambda = {_fmt(z)}" for z in off)
    return why, ce


def attempt_system(model: SystemModel, prec: int, wanted=None) -> Attempt:
    """Evaluate the requested claims (default ``model.wanted``) at the current precision."""
    wanted = model.wanted if wanted is None else wanted
    claims: list[Claim] = []
    quantities: dict[str, arb] = {}
    phase = Phases()
    rel = model.rel_width.fmpq()
    with phase("characteristic polynomial"):
        P, mu, Q, odd = polynomial_facts(model)
    omegas: list[arb] = []
    width_met = True
    details = {"dof": model.n, "zero_roots": mu}
    only_stability = False        # Q below is P / lambda^mu's, for stability alone (roots refuted: mu != z)
    if Q is None:
        why, ce = _structural(model, P, mu, odd)
        st = Status.REFUTED
        stab = (Status.REFUTED, why, ce)
        roots_verdict = (st, why, ce)
        if stability_at_multiplicity(model.zero_roots, mu):
            only_stability = True
            _, Q, odd = frequency_polynomial(P, mu)
            if Q is None:
                stab = (Status.REFUTED, *_structural(model, P, mu, odd, z=mu))
    if Q is not None:
        if not only_stability:
            details["frequencies"] = Q.degree()
        with phase("roots: isolation"):
            pr = isolate_polynomial(Q, rel_tol=None if only_stability else rel)
        ce = None
        if not pr.squarefree:
            st, why = Status.REFUTED, f"Q(omega) has a multiple root ({pr.reason}), exactly: lambda = +-i sqrt(omega) is multiple"
            ce = {"frequency_polynomial": [str(c) for c in Q.coeffs()], "gcd_with_derivative": str(Q.gcd(Q.derivative()))}
        elif not pr.verified:
            st, why = Status.INCONCLUSIVE, pr.reason
        else:
            nonpos = [x for x in pr.real if not certainly_positive(x)]
            bad_real = [x for x in nonpos if certainly_le(x, 0)]
            if pr.nonreal or bad_real:
                parts = []
                if pr.nonreal:
                    parts.append(f"{len(pr.nonreal)} roots omega are certainly non-real (flutter: lambda off the "
                                 "imaginary axis): " + "; ".join(f"{_fmt(z.real)} + {_fmt(z.imag)} i" for z in pr.nonreal))
                if bad_real:
                    parts.append("roots omega certainly < 0 (divergence: a real lambda > 0): "
                                 + ", ".join(_fmt(x) for x in bad_real))
                st, why = Status.REFUTED, "; ".join(parts)
                ce = {}
                if pr.nonreal:
                    ce["nonreal_roots"] = [{"re": _bounds(z.real), "im": _bounds(z.imag)} for z in pr.nonreal]
                if bad_real:
                    ce["negative_roots"] = [_bounds(x) for x in bad_real]
                ce["frequency_polynomial"] = [str(c) for c in Q.coeffs()]
            elif nonpos:
                st, why = Status.INCONCLUSIVE, f"sign of root(s) {[_fmt(x) for x in nonpos]} undecided"
            else:
                omegas = pr.real
                st, why = Status.PROVED, (f"P = lambda^{mu} P~ with P~ even, exactly; gcd(Q, Q') = 1 exactly; Arb isolated "
                                          f"{len(omegas)} roots of Q with imaginary part exactly 0, each confirmed by an "
                                          f"exact sign change, all > 0")
        stab = (st, why, ce)
        if only_stability:        # the roots other than lambda = 0 decide it; no root is stored (roots refuted)
            if st is Status.PROVED:
                why = (f"lambda = 0 is a root of multiplicity {mu} exactly ({model.zero_roots} declared), and "
                       + why)
            elif ce is not None:
                ce = {"zero_root_multiplicity": mu, **ce}
            stab = (st, why, ce)
            st, why, ce = roots_verdict
            omegas = []
        if pr.verified and not pr.nonreal and not only_stability:
            for j, w in enumerate(pr.real, start=1):
                quantities[f"omega_{j}"] = w
        # refuted with no root stored (a multiple or non-real root): no width is asked of anything, so the
        # escalation stops here (it doubled to --maxprec for nothing)
        width_met = pr.width_met or (st is Status.REFUTED and not any(k.startswith("omega_") for k in quantities))
        if st is Status.PROVED and not pr.width_met:
            st, why = Status.INCONCLUSIVE, (f"roots isolated but not yet to relative width {model.rel_width} "
                                            "(raise --maxprec or relax option rel_width)")
    if "roots" in wanted:
        claims.append(Claim("roots", SYSTEM_CLAIMS["roots"], st, why, details=dict(details), counterexample=ce))
    if "stability" in wanted:
        s_st, s_why, s_ce = stab
        if s_st is Status.PROVED:
            s_why = ("every root other than the declared zero roots is +-i sqrt(omega_j) with omega_j real, positive "
                     "and simple: " + s_why)
        claims.append(Claim("stability", SYSTEM_CLAIMS["stability"], s_st, s_why, details=dict(details),
                            counterexample=s_ce))
    if "brackets" in wanted:
        c = _brackets_claim(model, omegas, quantities)
        if st is Status.REFUTED and c.status is Status.INCONCLUSIVE:
            c.reason = "needs the certified roots, and claim roots is refuted: omega_j are not all real and positive"
            c.precision_cannot_help = "it rests on the refuted claim roots"
        claims.append(c)
    hz = model.hz()
    if hz is not None and omegas:
        s = ball(hz)
        for j, w in enumerate(omegas, start=1):
            quantities[f"freq_hz_{j}"] = f = s * w.sqrt()
            width_met = width_met and rel_width_at_most(f, rel)
    return Attempt(claims, quantities, [], [], [], width_met, phase_seconds=phase.seconds,
                   width_quantities=tuple(k for k in quantities if k.startswith(("omega_", "freq_hz_"))
                                          and not rel_width_at_most(quantities[k], rel)))


def stability_at_multiplicity(z: int, mu: int) -> bool:
    """Whether claim ``stability`` is decided by the roots of P / lambda^mu (mu the exact multiplicity of
    lambda = 0, z = zero_roots declared) when mu != z: when mu < z (over-declared: every zero root is among the
    declared ones, the statement is about the others alone) and when mu = 1 > z = 0 (lambda = 0 is then a
    simple root on the imaginary axis). False when mu >= 2 and mu > z: lambda = 0 is then a multiple root beyond
    the declared ones, not simple, and the claim is refuted by the multiplicity alone."""
    return mu != z and (mu < z or mu == 1)


def _brackets_claim(model: SystemModel, omegas: list[arb], quantities: dict[str, arb]) -> Claim:
    statement = SYSTEM_CLAIMS["brackets"]
    if not omegas:
        return Claim("brackets", statement, Status.INCONCLUSIVE, "needs the certified roots (claim roots)")
    per_root, violations, decides = [], [], None
    for j in range(1, len(model.brackets) + 1):
        w = omegas[j - 1]
        try:
            lo, hi = model.bracket_balls(j)
        except NotRealBound as e:
            per_root.append({"root": f"omega_{j}", "status": "refuted", "reason": f"no real value: {e}"})
            violations.append({"root": f"omega_{j}", "not_real": str(e), "radicand": _bounds(e.radicand)})
            continue
        # a bound that is not a finite ball here (no certain reason found: system_bounds) is not stored: a
        # certificate holds finite enclosures only ("nan" is no number the checker can read)
        for name, x in ((f"bracket_{j}_lo", lo), (f"bracket_{j}_hi", hi), (f"bracket_{j}_slack", (w - lo).min(hi - w))):
            if x.is_finite():
                quantities[name] = x
        if certainly_le(lo, w) and certainly_le(w, hi):
            per_root.append({"root": f"omega_{j}", "status": "proved"})
        elif certainly_gt(lo, w) or certainly_gt(w, hi):
            per_root.append({"root": f"omega_{j}", "status": "refuted",
                             "reason": f"{_fmt(w)} not in [{_fmt(lo)}, {_fmt(hi)}]"})
            violations.append({"root": f"omega_{j}", "value": _bounds(w), "lower_bound": _bounds(lo),
                               "upper_bound": _bounds(hi)})
        else:
            entry = {"root": f"omega_{j}", "status": "undecided"}
            unbounded = [f"{side} bound {e.text!r}" for side, e, b in zip(("lower", "upper"), model.brackets[j - 1],
                                                                        (lo, hi)) if not b.is_finite()]
            if unbounded:
                entry["reason"] = (f"its {' and '.join(unbounded)} could not be evaluated: not a finite ball at this "
                                   "precision (it may divide by zero, or by a number too close to 0 for it)")
            per_root.append(entry)
            margin = (w - lo) if not certainly_le(lo, w) else (hi - w)
            decides = margin if decides is None else decides
    statuses = [r["status"] for r in per_root]
    if violations:
        c = Claim("brackets", statement, Status.REFUTED,
                  "certified violation(s): " + "; ".join(f"{r['root']}: {r['reason']}" for r in per_root
                                                         if r["status"] == "refuted"),
                  details={"per_root": per_root}, counterexample={"violations": violations})
    elif "undecided" in statuses:
        c = Claim("brackets", statement, Status.INCONCLUSIVE, "undecided at this precision: "
                  + ", ".join(r["root"] + (f" ({r['reason']})" if "reason" in r else "") for r in per_root
                              if r["status"] == "undecided"), details={"per_root": per_root})
        c.decides = decides
    else:
        c = Claim("brackets", statement, Status.PROVED, f"lo_j <= omega_j <= hi_j certified for j = 1..{len(per_root)}",
                  details={"per_root": per_root})
    return c
