"""The tracked orbit of a relay scene (option ``orbit``): which root of g the scene's claims are about.

With ``[options] orbit = "0.266"`` the claims ``orbit_genuine``, ``initial_point``, ``multipliers`` and
``stable`` are about one orbit: the root theta* of the half-period function g on (0, oo) nearest the
option's exact value t (here the rational 133/500), instead of "some genuine orbit", which another orbit
can keep true across a boundary (in the tau family of the B = 2/15 scene the orbit near 0.266 loses
stability at tau ~ 0.0554 while the orbit near 0.39 stays stable). Their statements
(:func:`statements`) say so; ``half_period`` (every root isolated and classified) is unchanged.

Guarantee (:func:`nearest_root`): the choice is certified only when the farthest point of the chosen
root's enclosure is certainly closer to t than the nearest point of every other place a root of g can
be: every other root's enclosure, every undecided piece of the searched range, and [T, oo) when the
search stops at T (option T_max). The caller supplies these from a complete record of the search
((0, theta_min] is root-free by g = O(theta^5) with g^(5) > 0; each decided piece holds exactly the
roots listed), so every root of g lies in one of them, and the root in the chosen enclosure is then the
unique root of g nearest t, for every parameter the enclosures hold (a point, or every member of a
box). A tie or enclosures too wide to separate the distances leave the choice uncertified (the claims
inconclusive, never refuted for that reason); the ball ``gap - reach`` is what would decide it.

Precision: the caller's (t is the ball of the exact rational at the working precision; the distances
are ball differences of the enclosures' exact ends and t).

Fails when: never raises for balls; floats only pick the candidate (the distances decide).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

from flint import arb

from ...core.balls import certainly_lt, decimal_bounds, enclosure_text

__all__ = ["Nearest", "nearest_root", "statements", "TRACKED_STATEMENTS"]

#: the statements of the claims that follow the tracked orbit ({t}: the option's value as written)
TRACKED_STATEMENTS = {
    "orbit_genuine": "The root theta* of the half-period equation g(theta) = 0 (the paper's (13)) on (0, oo) nearest "
                     "theta = {t} (option orbit) is unique, certified by a gap: its distance to {t} is certainly less "
                     "than that of every other root of g; and it is a genuine orbit: beta(t) > 0 on the whole open "
                     "interval (0, theta*) (the relay does not switch early), proved for all t, not sampled.",
    "initial_point": "For the root theta* of g on (0, oo) nearest theta = {t} (option orbit; certified nearest, as in "
                     "orbit_genuine), a genuine orbit: the point x(0) = (beta', Omega, i, I) where it crosses the "
                     "section beta = 0 is enclosed (quantities beta_dot_0, Omega_0, i_0, I_0), with the constants "
                     "D1..D5 of the paper's form (7)/(9).",
    "multipliers": "For the root theta* of g on (0, oo) nearest theta = {t} (option orbit; certified nearest), a "
                   "genuine orbit, and for every other genuine orbit found: the Jacobian of the half-period point "
                   "map on the section (switching-time correction and symmetry x -> -x included) has the enclosed "
                   "eigenvalues (roots of the paper's (25)) and moduli (multiplier_* quantities: the orbit nearest "
                   "{t}).",
    "stable": "The root theta* of g on (0, oo) nearest theta = {t} (option orbit; certified nearest: a gap to every "
              "other root) is a genuine orbit and it is stable: every multiplier modulus of THAT orbit is "
              "certainly < 1 (stability_margin = 1 - its max modulus, enclosed). Other orbits do not decide it.",
}


def statements(base: dict[str, str], target_text: str | None) -> dict[str, str]:
    """The statement of every claim of a scene: ``base`` (the kind's CLAIMS) without the option, with it
    the tracked statements for the claims that follow the orbit."""
    if target_text is None:
        return dict(base)
    return {cid: TRACKED_STATEMENTS[cid].format(t=target_text) if cid in TRACKED_STATEMENTS else text
            for cid, text in base.items()}


@dataclass(frozen=True)
class Nearest:
    """The root nearest the target, and whether that is certified.

    ``index`` indexes the ``roots`` given (None: no root at all); ``reach`` is an upper bound of the
    distance from t to every point of the chosen enclosure; ``gap`` a lower bound of the distance from
    t to every other place a root can be (None when there is none); ``rival`` names the place that
    bounds ``gap``."""

    index: int | None
    certified: bool
    reach: arb | None = None
    gap: arb | None = None
    rival: str = ""
    reason: str = ""

    @property
    def decides(self) -> arb | None:
        """gap - reach: certainly > 0 is the certificate; its sign decides an uncertified choice."""
        return None if self.reach is None or self.gap is None else self.gap - self.reach


def _distance_lower(t: arb, lo: arb, hi: arb | None) -> arb:
    """A lower bound (as a ball) of the distance from t to [lo, hi] (hi None: [lo, oo))."""
    d = (lo - t).max(arb(0))
    return d if hi is None else d.max(t - hi)


def nearest_root(t: arb, roots: Sequence[arb], unknown: Sequence[tuple[arb, arb]] = (),
                 beyond: arb | None = None) -> Nearest:
    """The root enclosure of ``roots`` nearest ``t``, certified nearest against every other root
    enclosure, every ``unknown`` piece [lo, hi] (may hold roots) and [beyond, oo) (roots not searched);
    see the module docstring."""
    if not roots:
        return Nearest(None, False, reason="no root of g was found")
    tm = float(t.mid())
    k = min(range(len(roots)), key=lambda i: abs(float(roots[i].mid()) - tm))    # floats pick only
    X = roots[k]
    lo, hi = arb(X.lower()), arb(X.upper())
    reach = (t - lo).max(hi - t)
    rivals: list[tuple[arb, str]] = []
    for i, Y in enumerate(roots):
        if i != k:
            rivals.append((_distance_lower(t, arb(Y.lower()), arb(Y.upper())), f"the root {enclosure_text(Y, 10)}"))
    for a, b in unknown:
        rivals.append((_distance_lower(t, arb(a.lower()), arb(b.upper())),
                       f"the undecided piece [{enclosure_text(a, 8)}, {enclosure_text(b, 8)}]"))
    if beyond is not None:
        rivals.append((_distance_lower(t, arb(beyond.upper()), None),
                       f"roots beyond the searched range (> {enclosure_text(beyond, 8)})"))
    if not rivals:
        return Nearest(k, reach.is_finite(), reach, None, "", "the only root of g on (0, oo)")
    gap, rival = min(rivals, key=lambda r: float(r[0].lower()))
    ok = reach.is_finite() and all(certainly_lt(reach, d) for d, _ in rivals)
    bad = next((name for d, name in rivals if not certainly_lt(reach, d)), "")
    up = decimal_bounds(reach, 6)[1]
    why = (f"|theta* - t| <= {up} < {decimal_bounds(gap, 6)[0]} <= the distance to {rival}" if ok
           else f"not certified nearest: |theta* - t| <= {up} is not certainly less than the distance to {bad}")
    return Nearest(k, ok, reach, gap, rival, why)
