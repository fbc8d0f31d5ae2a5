"""A certified obstruction to step 1 of :mod:`.continuation`: dG/dtheta vanishes at the centre's root for some
member of the box (a cheap precheck that saves the sub-box unions, issue 37's cost regression).

Why: every form by which :func:`.continuation._theta_over_box` proves theta*(P) unique (the parametric interval
Newton and Krawczyk operators, with G's gradient over the whole box or as a union over cells, and the band
step) needs an enclosure of dG/dtheta over Theta x box that excludes 0, where Theta is an interval holding the
centre's root tc. If G_theta(tc, P1) and G_theta(tc, P2) have certainly opposite signs for two members P1, P2
of the box, then G_theta(tc, P) = 0 for some P on the segment between them (the intermediate value theorem:
G = g K is continuous in P over the box once the box's own jets were built, as they are before step 1 runs:
that fixes the cubic's root structure over the box, one real root and a pair with Im > 0 or three separated
real roots, so K has one formula and g K no pole there), every such enclosure contains 0, and none of those
forms can succeed: the cell unions (most of the cost of a failing continuation) are then skipped. The centre c
itself is one of the points.

What: :func:`slope_sign_change` evaluates G_theta(tc, P) at the centre, at points on each direction's axis
(the others at the centre) 1/4, 1/2, 3/4 and 15/16 of the way from the centre to either end of the box's ball,
and at the two opposite corners at 15/16 (members: the ball holding the exact interval exceeds it by less than
2^-25 of its radius, Arb's radius being a 30-bit magnitude, plus the ends' own rounding at the working
precision).

Guarantee: a returned :class:`SignChange` names two members at which G_theta(tc, .) has certainly opposite signs
(point evaluations in balls); None says nothing (no sign change found, or an evaluation not certain).
Precision: the current working precision. Fails when: never raises (a degenerate spectrum at a point is
skipped).

:func:`slope_ratio` is a planning figure, not a proof step: |G_theta(tc, c)| over the radius of G_theta's enclosure
on {tc} x box. Halving the box shrinks that radius by 2 to 4 per halving, so a ratio far below 1 (1e-9 at
H = 9325 +-3.5 %, where g's roots crowd; 0.037 at H = 100 +-4 %, whose halves decide) says whether pieces of the
box can prove theta*(P) at all (:mod:`.similar_cover` halves only pieces where they can).
"""
from __future__ import annotations

from dataclasses import dataclass

from flint import acb, arb

from ...core.balls import certainly_negative, certainly_positive
from ...core.jets import Jet, second_order_gradient
from .flow import DegenerateSpectrum
from .parametric import RelayJets, nested_variable

__all__ = ["SignChange", "slope_sign_change", "slope_ratio", "FRACTIONS"]

#: how far towards the ball's end the test points lie (members of the box, module docstring): G_theta(tc, .)
#: oscillates in the parameters where the nutation is fast (H = 9325: six sign changes over H +-3.5 %)
FRACTIONS = (arb(1) / 4, arb(1) / 2, arb(3) / 4, arb(15) / 16)


def _sign(x: arb) -> int:
    return 1 if certainly_positive(x) else -1 if certainly_negative(x) else 0


def _points(cvals: dict[str, arb], box: dict[str, arb], dirs: list[str]):
    """The test points (module docstring) as {name: exact ball} dicts, with a short label."""
    def towards(k: str, side: int, f: arb) -> arb:
        end = box[k].upper() if side > 0 else box[k].lower()
        return arb((cvals[k] + f * (end - cvals[k])).mid())

    for f in FRACTIONS:
        for k in dirs:
            for side in (-1, 1):
                yield f"{k} {'+' if side > 0 else '-'}{f.str(3)}", {**cvals, k: towards(k, side, f)}
    if len(dirs) > 1:
        for side in (-1, 1):
            yield f"corner {'+' if side > 0 else '-'}", {**cvals, **{k: towards(k, side, FRACTIONS[-1]) for k in dirs}}


def _slope(vals: dict[str, arb], guesses, tc: arb) -> arb | None:
    """G_theta(tc, P) at the point ``vals`` (all nine parameters as exact balls), or None."""
    try:
        jets = RelayJets({k: Jet.constant(acb(v), 1) for k, v in vals.items()}, 1, guesses)
    except DegenerateSpectrum:
        return None
    d = jets.G(Jet.variable(acb(tc), 0, 1)).d[0].real
    return d if d.is_finite() else None


@dataclass
class SignChange:
    """Two members ``points`` ((label, {name: exact ball}, G_theta ball), twice) where G_theta(tc, .) has certainly
    opposite signs; ``text`` says so for a reason."""
    points: tuple
    text: str


def slope_sign_change(cvals: dict[str, arb], box: dict[str, arb], dirs: list[str], guesses, tc: arb,
                      centre_slope: arb) -> SignChange | None:
    """Two members where G_theta(tc, .) has certainly opposite signs, or None (module docstring). ``cvals``: the
    centre's nine parameters (exact balls); ``box``: the directions' balls; ``centre_slope``: G_theta(tc, c),
    already enclosed by the caller; ``tc`` an exact ball."""
    seen = {}
    s0 = _sign(centre_slope)
    if s0 != 0:
        seen[s0] = ("centre", dict(cvals), centre_slope)
    for label, vals in _points(cvals, box, dirs):
        d = _slope(vals, guesses, tc)
        s = _sign(d) if d is not None else 0
        if s == 0:
            continue
        if -s in seen:
            first = seen[-s]
            return SignChange((first, (label, vals, d)),
                              f"dG/dtheta at theta = {tc.str(10, radius=False)} is {first[2].str(3)} at the point "
                              f"{first[0]} and {d.str(3)} at the point {label} of the box: it vanishes for some member")
        seen.setdefault(s, (label, vals, d))
    return None


def slope_ratio(models, tc: arb) -> float | None:
    """|G_theta(tc, c)| / radius of G_theta over {tc} x box (the second-order form of ``models``, a
    :class:`.continuation._Models`), or None when not finite (module docstring: a planning figure)."""
    k = len(models.dirs)
    m = models.m
    tcp = arb(tc.mid())
    try:
        Gc = models.centre.G(Jet.variable(acb(tcp), k, m))
        Gn = models.nested.G(nested_variable(tcp, k, m))
        g = second_order_gradient(Gc, Gn, models.devs + [arb(0)])[k]
    except (ValueError, ZeroDivisionError):
        return None
    c = Gc.d[k].real
    if not (g.is_finite() and c.is_finite()):
        return None
    r = float(g.rad())
    return float("inf") if r == 0 else abs(float(c.mid())) / r
