"""Claims of the Lyapunov kind over a box of parameters (tolerances), for :mod:`rigor_gyro.margins`.

Every function of :class:`.model.Gimbal` is written in ball arithmetic over the parameter balls of
``Gimbal.c``. :class:`BoxGimbal` makes those balls contain the whole box (A0 = A + A1 + A2, B0, C0
formed from the box's balls), so each enclosure the claims compute (m and M as maxima over x2, p,
k_min, R1, R2, R, min over the disc of Psi1 and Psi2 on each x2 piece, Vdot at a point) contains the
value for every parameter in the box; the claims of :mod:`.claims` then run unchanged on it.

Guarantee: ``proved`` means the claim holds for every parameter value in the box: for
``vdot_nonpositive``, Vdot <= 0 on region (17) with each parameter's own R (the disc minimum of Psi
decreases in R, and so does A - R |B| of the direct test, its fallback; R's ball contains every R of the
box); ``refuted`` means it fails for every value
in the box (a certified inequality over the box, or a point of the region inside every parameter's
disc, where Vdot > 0 for every parameter); ``undecided`` otherwise.

Precision: the caller's (the paving fixes it). The subdivision budget per box evaluation is the scene's
``max_pieces`` capped at :data:`BOX_MAX_PIECES` (a wide box makes pieces undecidable at any width; the
paving splits the box instead).

Fails when: the domain fails somewhere in the box (A, C, H, k, a, mu > 0; inertias >= 0; A0 > C0, i.e.
A2 + C1 > 0), or x2_star / moment are given as tolerances: ParameterError naming the parameter.
"""
from __future__ import annotations

import dataclasses

from flint import fmpq

from ...core.boxes import Box
from ...core.errors import ParameterError
from ...core.balls import current_precision
from .. import box_outcomes, require_box_claims
from .claims import CLAIMS, RATIONAL, attempt
from .model import Gimbal, ParameterBalls

__all__ = ["BOX_CLAIMS", "BOX_PARAMETERS", "BoxGimbal", "validate_box", "evaluate_box"]

BOX_CLAIMS = {c: CLAIMS[c] for c in ("damping_condition", "vdot_nonpositive", "v_positive")}
BOX_PARAMETERS = RATIONAL
BOX_MAX_PIECES = 4000


class BoxGimbal(Gimbal):
    """A :class:`Gimbal` whose parameter balls contain a whole box of the scene's raw parameters."""

    def __init__(self, base: Gimbal, raw: dict[str, tuple]):
        super().__init__(base.A0, base.B0, base.C0, base.H, base.k, base.a, base.mu, base.x2_star, base.law)
        self.raw = raw          # name -> (lo, hi) exact rationals, for every rational parameter

    @property
    def c(self) -> ParameterBalls:
        p = current_precision()
        if p not in self._cache:
            b = {k: Box.of({k: v}).ball(k) for k, v in self.raw.items()}
            A0, B0, C0 = b["A"] + b["A1"] + b["A2"], b["A"] + b["B1"], b["A"] + b["A1"] - b["C1"]
            self._cache[p] = ParameterBalls(A0, B0, C0, b["H"], b["k"], b["a"], b["mu"], self.x2_star.ball())
        return self._cache[p]

    def with_mu(self, mu: fmpq) -> Gimbal:        # best_mu is not a box claim
        raise NotImplementedError("best_mu is not decided over a box")


def _raw(model, box: Box) -> dict[str, tuple]:
    out = {}
    for k in RATIONAL:
        if k in box.names:
            out[k] = box.interval(k)
        else:
            q = model.params[k].rational
            out[k] = (q, q)
    return out


def validate_box(model, box: Box) -> None:
    bad = [n for n in box.names if n not in BOX_PARAMETERS]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: kind 'lyapunov' takes a tolerance only for {list(BOX_PARAMETERS)}; "
                             f"write {bad[0]!r} as a single value")
    r = _raw(model, box)
    for k in ("A", "C", "H", "k", "a", "mu"):
        if not r[k][0] > 0:
            raise ParameterError(f"parameter {k!r}: need {k} > 0 on the whole box (its lower end is {r[k][0]})")
    for k in ("A1", "B1", "C1", "A2"):
        if r[k][0] < 0:
            raise ParameterError(f"parameter {k!r}: need {k} >= 0 on the whole box (its lower end is {r[k][0]})")
    if not r["A2"][0] + r["C1"][0] > 0:
        raise ParameterError("parameters 'A2', 'C1': need A0 > C0, i.e. A2 + C1 > 0, on the whole box")


def evaluate_box(model, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box (see the module docstring)."""
    require_box_claims(claims, BOX_CLAIMS)
    g = BoxGimbal(model.gimbal, _raw(model, box))
    boxed = dataclasses.replace(model, gimbal=g, paper={}, max_pieces=min(model.max_pieces, BOX_MAX_PIECES))
    a = attempt(boxed, list(claims), current_precision())
    return box_outcomes(a, claims)
