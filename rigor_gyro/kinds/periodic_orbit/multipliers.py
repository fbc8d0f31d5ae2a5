"""The multipliers of a relay orbit from the eigenvalue balls of its Jacobian, and the stability decision;
shared by the paper's path (:mod:`.claims`) and the user's plant (:mod:`.plant_claims`).

Guarantee: an eigenvalue is made exactly real only when its conjugate ball meets no other eigenvalue's ball
(the Jacobian is real, so its spectrum is closed under conjugation: the ball is its own conjugate); the
multipliers are ordered by modulus (floats order, balls decide nothing there), a conjugate pair with the member
of positive imaginary part first; ``stable`` is True only when every modulus is certainly < 1, False only when
one is certainly > 1, else None (undecided). A plant of dimension 1 (``eig`` empty: the section c . x = h is a
point, the return map's Jacobian is 0x0) has no multipliers: its orbit is stable (True) with margin 1 (the
spectral radius of the zero map): every nearby solution with the same relay state moves monotonically (a scalar
ODE whose field does not vanish on the orbit, else the orbit could not run from h to -h) to the switching point
and follows the orbit from there on. Precision: the balls'. Fails when: never.
"""
from __future__ import annotations

from flint import acb, arb

from ...core.balls import (certainly_gt, certainly_lt, certainly_negative, certainly_positive, current_precision,
                           working_precision)

__all__ = ["decide_multipliers", "disc_margin"]

#: bits above the working precision for the margin of :func:`disc_margin` (its union of two exact ends)
_MARGIN_GUARD = 64


def decide_multipliers(v, eig: list) -> None:
    """Set ``v.multipliers`` (ordered), ``v.moduli``, ``v.margin`` = 1 - max modulus and ``v.stable`` from the
    Jacobian's eigenvalue balls ``eig`` (each holding exactly one eigenvalue; changed in place where made real)."""
    for k, z in enumerate(eig):
        if z.imag.contains(0) and not any(z.conjugate().overlaps(w) for j, w in enumerate(eig) if j != k):
            eig[k] = acb(z.real, 0)
    mults = sorted(eig, key=lambda z: -float(abs(z).mid()))
    for k in range(len(mults) - 1):  # a conjugate pair (equal moduli): the member with Im > 0 first
        a, b = mults[k], mults[k + 1]
        if abs(a).overlaps(abs(b)) and certainly_negative(a.imag) and certainly_positive(b.imag):
            mults[k], mults[k + 1] = b, a
    v.multipliers = mults
    v.moduli = [abs(z) for z in mults]
    if not eig:                 # dimension 1: no nontrivial multiplier (module docstring)
        v.margin = arb(1)
        v.stable = True
        return
    mx = v.moduli[0]
    for m in v.moduli[1:]:
        mx = mx.max(m)
    v.margin = 1 - mx
    if all(certainly_lt(m, 1) for m in v.moduli):
        v.stable = True
    elif any(certainly_gt(m, 1) for m in v.moduli):
        v.stable = False


def disc_margin(U: arb) -> arb:
    """The stability margin 1 - max modulus enclosed from a bound U of every modulus alone (the multipliers not
    isolated): [1 - U, 1], the union taken with guard bits so that its upper end stays 1 where the lower end's bits
    allow. Shared by the prover and the checker (a two-line formula, not a decision)."""
    lo = (1 - U).lower()
    with working_precision(current_precision() + _MARGIN_GUARD):
        return arb(lo).union(arb(1))
