"""A quantity over a parameter box: the interface each kind's ``box_quantities`` module gives the margins layer.

A kind that certifies numbers over boxes (not only verdicts) has a module ``kinds/<kind>/box_quantities.py``
(beside its ``boxes`` module, which decides the claims) that exports

* ``BOX_QUANTITIES``: ``{quantity_id: QuantitySpec}`` in report order;
* ``quantities_box(model, box, names) -> {quantity_id: BoxValue}``: for each requested quantity it can
  enclose on ``box`` at the current precision, a :class:`BoxValue` whose ``value`` ball contains q(P) for
  every parameter value P in the box, and (optionally) whose ``gradient`` balls contain dq/dP_k for every P
  in the box, for each box parameter k. A quantity it cannot enclose on this box (the object it measures
  not certified to exist there, or the enclosure not finite) is left out of the dict; it never raises for
  that. Called on a box whose edges are points (lo == hi) it gives the value at that point (a tight ball).

A ``margin`` quantity is one whose sign decides a claim (``QuantitySpec.claim``): the claim holds where the
margin is > 0. Its certified minimum over a box is the worst case an engineer designs with.

Guarantee: the caller (``rigor_gyro.margins.ranges``) turns these into statements over a box: the outer
range is the union of the ``value`` balls over sub-boxes that tile the box; the inner range is spanned by
values at two exact points of the box. That needs q to be one continuous function on the box: the kind's
theorem where q is a function of the parameters (continuous where enclosed). Where q measures an object chosen
per sub-box (the relay's orbit continued from each sub-box's centre), the kind gives each value a
:class:`Branch`: a key that identifies the object (theta*), enclosed over the sub-box by a mean-value form about
the sub-box's centre, and a ball U where, for every P of the sub-box, the object's key is the only candidate
(theta*(P) the only root of g(., P) in U). Two touching sub-boxes measure the same object on their common part
F when one's key over F lies inside the other's U; the caller states an inner range and tolerance effects only
when every two touching sub-boxes are shown to agree (:func:`rigor_gyro.margins.ranges.one_branch`). Such a
kind's value at a point (a box of zero width) must measure the object every sub-box holding the point measures
(the relay: the point's only orbit, every other root of (0, oo) certified spurious).

Fails when: never here; this module only names the interface.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from flint import arb

__all__ = ["QuantitySpec", "BoxValue", "Branch"]


@dataclass(frozen=True)
class QuantitySpec:
    """What a quantity is: a description for the report, its unit ("" when none), and for a margin the claim
    whose truth its sign decides (the claim holds where the margin is > 0); None for a plain value."""

    description: str
    unit: str = ""
    claim: str | None = None

    @property
    def is_margin(self) -> bool:
        return self.claim is not None


@dataclass(frozen=True)
class Branch:
    """Which object a sub-box's values measure (module docstring): its key is in ``key`` for every P in the
    sub-box, and key(P) - ``at_centre`` = sum_k dkey/dP_k (P_k - ``centre``[k]) with each dkey/dP_k in
    ``gradient``[k] over the sub-box (the key depends on no other parameter); for every P in the sub-box no other
    candidate object has its key in ``unique_in``."""

    key: arb
    centre: dict                    # {parameter: Fraction}, the sub-box's centre in the gradient's parameters
    at_centre: arb
    gradient: dict                  # {parameter: arb}
    unique_in: arb


@dataclass(frozen=True)
class BoxValue:
    """A quantity's enclosure over a box: ``value`` contains q(P) for every P in the box; ``gradient`` (may be
    empty) maps a box parameter k to a ball containing dq/dP_k for every P in the box; ``branch`` for a quantity
    of an object chosen per box (module docstring), None for a function of the parameters."""

    value: arb
    gradient: dict[str, arb] = field(default_factory=dict)
    branch: Branch | None = None
