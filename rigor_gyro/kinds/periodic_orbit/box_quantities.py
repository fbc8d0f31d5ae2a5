"""The relay's quantities over a parameter box (issue 37 part 2; the interface of :mod:`rigor_gyro.core.box_values`).

The orbit measured is the only genuine orbit at the box's centre (the centre's every other root of g certified
spurious; nothing is enclosed when the centre has several genuine or unclassified roots, or when the scene
tracks an orbit with option ``orbit``, whose nearness the continuation does not certify), continued over the box by
:func:`.continuation.continue_orbit`: theta*(P) is the unique root of g in the certified interval for every
P, on the branch through the centre's root, genuine for every P. Quantities:

* ``theta_star`` (s): its half-period, with dtheta*/dP_k over the box (implicit function, -g_P / g_theta);
* ``period`` (s): 2 theta*, gradient twice theta*'s (the point certificate's ``period`` is 2 theta* in s too);
* ``max_modulus``: the largest multiplier modulus for every P (no gradient): from the continuation over the box,
  or, where that gives none and the box varies A, H or tau, from pieces of its similar box
  (:mod:`.similar_modulus`: the multipliers depend on the three similarity invariants only; each piece's orbit
  shown to be this theta*(P));
* ``stability_margin``: 1 - max_modulus, the margin of claim ``stable`` (> 0 where it holds).

Each sub-box measures its own centre's orbit, so every value carries its :class:`~rigor_gyro.core.box_values.Branch`
(theta* at the centre and its gradient over the sub-box, and the ball U where theta*(P) is g's only root for every P
of the sub-box): touching sub-boxes measure one orbit where one's theta* over their common part lies in the
other's U. Without that, two sub-boxes could follow two orbits that coexist on their common face (a fold between
their centres), and the ranges layer states no inner range.

Guarantee: each returned value ball contains the quantity for every parameter in the box; a quantity not
certified on the box (the orbit not continued, its sign condition or multipliers not decided) is left
out. Precision: the current working precision. Fails when: never raises for a box it cannot enclose.
"""
from __future__ import annotations

import dataclasses

from flint import acb, arb

from ...core.box_values import BoxValue, Branch, QuantitySpec
from ...core.boxes import Box
from ...core.polyroots import isolate_polynomial
from .box_orbit import box_directions, centre_orbits
from .continuation import at_most_one_root, continue_orbit
from .flow import AMPLITUDE_PARAMETERS, nutation_cubic
from .plant_model import PlantModel
from .similar_modulus import modulus_on_similar_box

__all__ = ["BOX_QUANTITIES", "quantities_box"]

BOX_QUANTITIES = {
    "theta_star": QuantitySpec("half-period theta* of the orbit (the only genuine one at each sub-box's centre, continued over it)", "s"),
    "period": QuantitySpec("period 2 theta* of that orbit", "s"),
    "max_modulus": QuantitySpec("largest multiplier modulus of that orbit"),
    "stability_margin": QuantitySpec("stability margin 1 - largest multiplier modulus", claim="stable"),
}


def _q(x):
    from flint import fmpq
    return fmpq(x.numerator, x.denominator)


#: the widths (in theta*'s radii about its midpoint) tried for the branch's uniqueness ball, widest first
UNIQUE_WIDENING = (4, 2)


def _wider_unique(o, Pc, balls: dict, dirs: list[str], guesses: list) -> arb:
    """A ball where theta*(P) is g's only root for every P of the box, as wide as shown: the continuation's own U
    (which the band step leaves equal to theta*'s enclosure) or theta*'s enclosure widened UNIQUE_WIDENING times
    where dG/dtheta certainly excludes 0 on it (:func:`.continuation.at_most_one_root`). Touching sub-boxes meet
    where each one's theta* is at an end of its range, so each needs room beyond its own enclosure for the
    other's theta* over the common face (:func:`rigor_gyro.margins.ranges.one_branch`). A point box: U as is."""
    U = o.theta_unique_in
    if not dirs:
        return U
    for f in UNIQUE_WIDENING:
        W = arb(o.theta.mid(), f * o.theta.rad()).union(U)
        if at_most_one_root(Pc, balls, dirs, guesses, W):
            return W
    return U


def quantities_box(model, box: Box, names) -> dict[str, BoxValue]:
    """{quantity: BoxValue} for the requested names it can enclose on the box (module docstring)."""
    names = [k for k in names if k in BOX_QUANTITIES]
    if not names or isinstance(model, PlantModel):
        return {}           # a [plant] model: no quantity ranges over a box yet (its claims only: plant_box)
    mid = box.midpoint()
    fixed = {k: _q(box.interval(k)[0]) for k in AMPLITUDE_PARAMETERS if k in box.names}
    Pc = dataclasses.replace(model.params, **{**{k: _q(v) for k, v in mid.items()}, **fixed})
    centre = dataclasses.replace(model, params=Pc, paper={}, decided={})
    iso = isolate_polynomial(nutation_cubic(Pc))
    if not (iso.verified and iso.squarefree):
        return {}
    if getattr(model, "orbit", None) is not None:
        return {}           # a tracked orbit's nearness is not certified over a box (box_orbit.continued_outcomes)
    an, orbits = centre_orbits(centre, want_stable=False)
    if len(orbits) != 1 or sum(v.kind != "spurious" for v in an.roots) != 1 or an.unknown or not an.covers_all:
        # the orbit must be the centre's only one (every root of (0, oo) found and every other one certified
        # spurious): a point's value then measures the orbit every sub-box holding the point follows
        return {}
    dirs = box_directions(box)
    guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
    balls = {k: box.ball(k) for k in dirs}
    o = continue_orbit(Pc, balls, dirs, guesses, orbits[0].theta)
    if o.theta is None or not o.genuine:
        return {}
    grad = dict(zip(dirs, o.theta_gradient))
    # the orbit is the one whose theta* is g's only root in U; theta* about the centre by the mean value theorem
    branch = Branch(o.theta, {k: mid[k] for k in dirs}, o.theta_c, grad, _wider_unique(o, Pc, balls, dirs, guesses))
    out = {"theta_star": BoxValue(o.theta, grad, branch),
           "period": BoxValue(2 * o.theta, {k: 2 * g for k, g in grad.items()}, branch)}
    m = o.max_modulus if o.max_modulus is not None and o.max_modulus.is_finite() else None
    if m is None and {"max_modulus", "stability_margin"} & set(names):
        got = modulus_on_similar_box(model, box, o.theta, lambda W: at_most_one_root(Pc, balls, dirs, guesses, W))
        m = None if got is None else got[0]
    if m is not None:
        out["max_modulus"] = BoxValue(m, branch=branch)
        out["stability_margin"] = BoxValue(1 - m, branch=branch)
    return {k: v for k, v in out.items() if k in names}
