"""The claims of a relay scene with option ``orbit`` (:mod:`.tracked`): orbit_genuine, initial_point,
multipliers and stable decided for the root of g nearest the option's value, and nothing else.

Guarantee: each claim is proved or refuted only when the tracked root is certified nearest
(:func:`.tracked.nearest_root` on the complete record of the root search: every root's enclosure, every
undecided piece, the unsearched [T, oo)); then
* proved: that root is genuine (the classification of :func:`.claims.classify_root`), and for
  ``stable`` every modulus of ITS multipliers is certainly < 1;
* refuted (a counterexample naming the root, its certified nearness and the witness): that root is
  spurious (certified witness), or for ``stable`` one of its moduli is certainly > 1; or g has no root
  at all on (0, oo) (exhaustive search, as the untracked claims refute "no genuine orbit");
* inconclusive otherwise: a nearness not certified (a tie, wide enclosures: never refuted for that
  reason; the ball gap - reach goes to the prover as what decides it), the root not classified, its
  moduli not separated from 1.
Other orbits never decide these claims; they are still isolated, classified and reported
(theta_star_2, ..., stability_margin_2, ...).

Precision: the attempt's (the tracked root's theta*, x(0) and multipliers at the guard precision of
:func:`.claims.analyse`).

Fails when: never raises for a valid analysis; AssertionError only for a bug (a refuted claim without
a counterexample, :class:`~rigor_gyro.core.outcome.Claim`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ...core.balls import ball, certainly_gt, decimal_bounds
from ...core.outcome import Claim, Status
from .texts import complex_text as _fmt_c, interval_text as _fmt, modulus_text as _fmt1, stored_bounds as _bounds
from .tracked import Nearest, nearest_root

__all__ = ["TRACKED", "Choice", "choose", "tracked_claims", "tracked_extra"]

#: the claims that follow the tracked orbit, in the order a certificate lists them
TRACKED = ("orbit_genuine", "initial_point", "multipliers", "stable")


@dataclass
class Choice:
    """The tracked root: ``nearest`` the certification, ``verdict`` the nearest root's verdict (None: g
    has no root), ``genuine`` that verdict when it is certified nearest and genuine (the scene's orbit)."""

    nearest: Nearest
    verdict: object | None        # a claims.RootVerdict
    genuine: object | None
    target: str

    @property
    def label(self) -> str:
        if self.verdict is None:
            return f"the tracked orbit (the root of g nearest {self.target}): no root of g"
        return (f"the tracked orbit, the root of g nearest {self.target} (" +
                ("certified nearest" if self.nearest.certified else "nearest NOT certified") +
                f", {self.verdict.kind})")


def choose(model, an) -> Choice:
    """The root of ``an`` (an :class:`.claims.Analysis` with a spectrum) nearest the option ``orbit``."""
    t = ball(model.orbit.fmpq())
    unknown = [(u.lo, u.hi) for u in an.unknown]
    beyond = None if an.covers_all else an.T_search
    nr = nearest_root(t, [v.theta for v in an.roots], unknown, beyond)
    v = an.roots[nr.index] if nr.index is not None else None
    g = v if v is not None and nr.certified and v.kind == "genuine" else None
    return Choice(nr, v, g, model.orbit.text)


def _nearness(ch: Choice) -> dict[str, Any]:
    nr = ch.nearest
    return {"orbit": ch.target, "theta": _bounds(ch.verdict.theta),
            "distance_at_most": decimal_bounds(nr.reach, 12)[1],
            "others_at_least": decimal_bounds(nr.gap, 12)[0] if nr.gap is not None else None,
            "nearest_other": nr.rival}


def tracked_extra(ch: Choice) -> dict[str, Any]:
    """What the certificate says about the tracked choice (``extra.tracked_orbit``): which root (1-based,
    as in ``extra.roots``) every orbit quantity and the four claims are about."""
    out: dict[str, Any] = {"orbit": ch.target, "certified_nearest": ch.nearest.certified,
                           "root": None if ch.nearest.index is None else ch.nearest.index + 1}
    if ch.verdict is not None:
        out.update(_nearness(ch), kind=ch.verdict.kind)
    return out


def tracked_claims(st: dict[str, str], an, ch: Choice, wanted: list[str], *, exhaustive: bool, no_orbit: dict | None,
                   searched: str, search_open: str = "") -> list[Claim]:
    """The claims of :data:`TRACKED` that are ``wanted``, decided for the tracked root (module docstring).
    ``st`` the scene's statements (:func:`.claims.statements`); ``searched`` names the range searched;
    ``search_open`` what the root search left open (empty when it decided every piece)."""
    nr, v, T = ch.nearest, ch.verdict, ch.target
    wanted = [c for c in TRACKED if c in wanted]

    def all_of(status: Status, reason: str, cx: dict | None = None, decides=None) -> list[Claim]:
        out = [Claim(c, st[c], status, reason, counterexample=cx) for c in wanted]
        for c in out:
            c.decides = decides
        return out

    if v is None:
        if exhaustive:
            return all_of(Status.REFUTED, f"g has no root on {searched}: there is no orbit near {T}", no_orbit)
        return all_of(Status.INCONCLUSIVE, f"no root of g certified on {searched}" +
                      (f": {search_open}" if search_open else " (option T_max: roots beyond it not searched)"))
    where = f"the root of g nearest {T} is theta = {_fmt(v.theta, 16)}"
    if not nr.certified:
        return all_of(Status.INCONCLUSIVE, f"{where}, but it is {nr.reason}", decides=nr.decides)
    head = f"{where}, certified nearest ({nr.reason})"
    if v.kind == "undecided":
        return all_of(Status.INCONCLUSIVE, f"{head}; not classified: {v.reason}")
    if v.kind == "spurious":
        cx = {**_nearness(ch), "spurious_because": v.reason,
              "witness_t": _bounds(v.witness_t) if v.witness_t is not None else None}
        return all_of(Status.REFUTED, f"{head}; it is not a genuine orbit: {v.reason}", cx)
    out = []
    for cid in wanted:
        if cid == "orbit_genuine":
            out.append(Claim(cid, st[cid], Status.PROVED, f"{head}; genuine: {v.reason}"))
        elif cid == "initial_point":
            out.append(Claim(cid, st[cid], Status.PROVED, f"{head}; x(0): beta' = {_fmt(v.x0[1], 14)}, Omega = "
                             f"{_fmt(v.x0[2], 14)}, i = {_fmt(v.x0[3], 14)}, I = {_fmt(v.x0[4], 14)} (beta = g(theta*) "
                             "= 0 exactly)"))
        elif cid == "multipliers":
            genuine = [w for w in an.roots if w.kind == "genuine"]
            bad = [w for w in genuine if not w.moduli]
            if bad:
                out.append(Claim(cid, st[cid], Status.INCONCLUSIVE,
                                 f"{head}; " + "; ".join(w.multiplier_reason for w in bad)))
                continue
            parts = [("THIS ORBIT " if w is v else "") + f"theta = {_fmt(w.theta, 10)}: " + ", ".join(
                f"{_fmt_c(z, 10)} (|.| = {_fmt(m, 10)})" for z, m in zip(w.multipliers, w.moduli)) for w in genuine]
            out.append(Claim(cid, st[cid], Status.PROVED, f"{head}; " + "; ".join(parts) + f"; {v.jacobian_note}"))
        elif cid == "stable":
            out.append(_stable(st[cid], ch, head))
    return out


def _stable(statement: str, ch: Choice, head: str) -> Claim:
    v = ch.verdict
    if v.stable is True:
        return Claim("stable", statement, Status.PROVED, f"{head}; its max modulus {_fmt1(v.moduli[0], 10)} < 1; "
                     f"stability margin {_fmt(v.margin, 10)} (of this orbit)")
    if v.stable is False:
        big = next(m for m in v.moduli if certainly_gt(m, 1))
        cx = {**_nearness(ch), "modulus_above_1": _bounds(big)}
        return Claim("stable", statement, Status.REFUTED, f"{head}; a multiplier of this orbit has modulus "
                     f"{_fmt1(big, 10)} > 1: unstable (stability margin {_fmt(v.margin, 10)})", counterexample=cx)
    c = Claim("stable", statement, Status.INCONCLUSIVE, f"{head}; " + (
        f"its moduli are not separated from 1 at this precision (stability margin {_fmt(v.margin, 10)})"
        if v.moduli else v.multiplier_reason or "multipliers not computed"))
    c.decides = v.margin
    return c
