"""The largest multiplier modulus over a relay box, enclosed on pieces of its similar box (issue 37 part 2:
the stability margin's range and worst case over the six parameters at +-0.5 %).

Why: the continuation over a box of the six physical parameters (:mod:`.continuation`) encloses theta*(P) at
+-0.5 % on each, but its multipliers only on boxes some ten times narrower in B: the centred forms of the
half-period map's Jacobian grow faster than linearly with the width. The multipliers depend on the parameters
only through the three similarity invariants (:mod:`.similarity`), so they are enclosed on the similar box of
(B', sigma', n') instead, cut by :func:`.similar_cover.cover` along the direction theta* moves most, as the
claim ``stable`` is proved (:mod:`.box_orbit`).

What: :func:`modulus_on_similar_box` covers the similar box with pieces; a piece counts when its centre has
exactly one root of g that is not certified spurious, that root is genuine, and its continuation over the piece
encloses every multiplier modulus in a ball of width at most the stage's width (a wider ball is valid but
says little, so the piece is halved instead; :data:`MODULUS_STAGES`: a tight cover first, the loose one where the
tight one's budget or depth runs out). Then the pieces' orbits are shown to be the box's own: each
piece's half-period mapped back to the box (theta = theta' tau / tau_c, tau over the box) and the box's
theta*(P) lie in one interval W, and ``unique_in(W)`` (the caller's: :func:`.continuation.at_most_one_root` over
the box) shows that g(., P) has at most one root in W for every P; so the mapped root of each piece is theta*(P)
itself. The result is the hull of the pieces' balls.

Guarantee: for every parameter P of the box, the largest multiplier modulus of the orbit theta*(P) (the
caller's) lies in the returned ball. Precision: the current working precision. Fails when: never raises; returns None
when the box does not reduce (it varies none of A, H, tau), when every stage's cover ends first (a piece's centre
with another candidate orbit, the budget, the depth), or when uniqueness on W is not shown.
"""
from __future__ import annotations

import dataclasses
from typing import Callable

from flint import acb, arb, fmpq

from ...core.boxes import Box
from ...core.polyroots import isolate_polynomial
from .box_orbit import box_directions, centre_orbits
from .flow import PARAMETER_NAMES, RelayParams, nutation_cubic
from .normed_orbit import continue_orbit_normed
from .similar_cover import cover
from .similarity import similar_box

__all__ = ["modulus_on_similar_box", "MODULUS_WIDTH", "MODULUS_BUDGET", "MODULUS_STAGES"]

#: the widest ball of the largest modulus a piece may give (a piece with a wider one is halved; on A, H, tau at
#: +-0.5 % the pieces of B' +-0.3 % .. +-0.1 % give widths 0.12-0.16: their sigma' and n' widths dominate)
MODULUS_WIDTH = 0.2
#: continuations a cover may spend on one box
MODULUS_BUDGET = 24
#: the covers tried in turn, (width, budget) each: a tight one first (all six at +-0.25 %: the hull [0.93502,
#: 0.96140] with width 0.2 and 24 continuations, [0.95390, 0.95895] with width 0.01 and 64, 20 s -> 30 s; floats
#: give [0.9556, 0.9575]), then the loose one where the tight one's budget or depth runs out
MODULUS_STAGES = ((0.01, 64), (MODULUS_WIDTH, MODULUS_BUDGET))


def _q(x) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def modulus_on_similar_box(model, box: Box, theta_box: arb, unique_in: Callable[[arb], bool],
                           stages: tuple = MODULUS_STAGES) -> tuple[arb, int, int] | None:
    """(the hull of the largest multiplier modulus over the box, pieces, continuations spent) or None (module
    docstring). ``model``: the relay model (its parameters outside the box are used); ``theta_box``: an
    enclosure of theta*(P) over the box; ``unique_in(W)``: True only if g(., P) has at most one root in W for
    every P of the box. ``stages``: the covers' (width, budget), tried in turn until one gives a hull (each is
    a complete cover on its own: the first that succeeds is returned, its continuations counted with the
    earlier stages')."""
    spent = 0
    for width, budget in stages:
        got = _modulus_cover(model, box, theta_box, unique_in, width, budget)
        if got is None:                     # the box does not reduce, or uniqueness on W failed: final
            return None
        if got[0] is not None:
            return got[0], got[1], spent + got[2]
        spent += got[2]                     # the cover ran out of budget or depth: the next stage's turn
    return None


def _modulus_cover(model, box: Box, theta_box: arb, unique_in: Callable[[arb], bool], width: float,
                   budget: int) -> tuple[arb | None, int, int] | None:
    """One cover of :func:`modulus_on_similar_box` with pieces' balls at most ``width`` wide and ``budget``
    continuations: (hull, pieces, spent); (None, 0, spent) when the cover does not complete (a looser stage may);
    None when the box does not reduce or uniqueness on W is not shown (a looser cover's wider pieces cannot help
    there)."""
    red = similar_box(model.params, box)
    if red is None:
        return None
    rbox, fixed = red
    tau = box.ball("tau") if "tau" in box.names else arb(model.params.tau)
    alpha = tau / arb(_q(fixed["tau"]))
    base = {k: getattr(model.params, k) for k in PARAMETER_NAMES}
    base.update({k: _q(v) for k, v in fixed.items()})
    balls: list[arb] = []
    mapped: list[arb] = []

    def evaluate(piece: Box, need: list[str]):
        vals = dict(base)
        vals.update({k: _q(v) for k, v in piece.midpoint().items()})
        P = RelayParams(**vals)
        iso = isolate_polynomial(nutation_cubic(P))
        if not (iso.verified and iso.squarefree):
            return {}, False, None
        an, orbits = centre_orbits(dataclasses.replace(model, params=P, paper={}, decided={}), want_stable=False)
        if len(orbits) != 1 or sum(v.kind != "spurious" for v in an.roots) != 1:
            return {}, False, None
        dirs = box_directions(piece)
        pballs = {k: piece.ball(k) for k in dirs}
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        o = continue_orbit_normed(P, pballs, dirs, guesses, orbits[0].theta, stability=True)
        weights = None
        if o.theta is not None:
            weights = {k: float(abs(g).upper()) * float(pballs[k].rad()) for k, g in zip(dirs, o.theta_gradient)}
        m = o.max_modulus
        if o.genuine and m is not None and m.is_finite() and float(m.rad()) * 2 <= width:
            balls.append(m)
            mapped.append(alpha * o.theta)
            return {"max_modulus": ""}, True, weights
        return {}, o.theta is not None, weights

    got, spent = cover(rbox, ["max_modulus"], evaluate, budget=budget)
    if "max_modulus" not in got:
        return None, 0, spent
    W = theta_box
    for t in mapped:
        W = W.union(t)
    if not unique_in(W):
        return None
    hull = balls[0]
    for b in balls[1:]:
        hull = hull.union(b)
    return hull, got["max_modulus"][0], spent
