"""Claims of the Lyapunov kind over a box of parameters (tolerances), for :mod:`rigor_gyro.margins`.

Every function of :class:`.model.Gimbal` is written in ball arithmetic over the parameter balls of
``Gimbal.c``. :class:`BoxGimbal` makes those balls contain the whole box (A0 = A + A1 + A2, B0, C0
formed from the box's balls), so each enclosure the claims compute (m and M as maxima over x2, p,
k_min, R1, R2, R, min over the disc of Psi1 and Psi2 on each x2 piece, Vdot at a point) contains the
value for every parameter in the box; the claims of :mod:`.claims` then run unchanged on it.

``vdot_nonpositive`` is tried first by :mod:`.box_vdot`: the Psi test with each parameter's own R coupled to
its Psi, bounded below over the box at faces where it is certified monotone and by centred forms
(:mod:`.box_forms`); this decides boxes of engineering width (the example with every parameter at +-5 % on 127
boxes) where the balls below lose the correlations (R2's mu H cos^2 x2* - A0 m is 150 - 100 in the example).
m and M (which depend on A, A1, A2, C1, a only) are shared by every box with the same intervals of those, and
enclosed to BOX_REL_WIDTH plus the box's own width; C enters no claim and is never split (UNSPLIT_PARAMETERS).

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
from .box_vdot import decide_vdot_box
from .claims import CLAIMS, RATIONAL, attempt
from .model import Gimbal, ParameterBalls

__all__ = ["BOX_CLAIMS", "BOX_PARAMETERS", "BoxGimbal", "validate_box", "evaluate_box", "raw_intervals", "boxed_model"]

BOX_CLAIMS = {c: CLAIMS[c] for c in ("damping_condition", "vdot_nonpositive", "v_positive")}
BOX_PARAMETERS = RATIONAL
BOX_MAX_PIECES = 4000
#: box parameters no box claim depends on (C, the rotor's polar inertia, enters neither A0, B0, C0 nor the
#: claims): the paving never splits them
UNSPLIT_PARAMETERS = ("C",)
#: the relative width m and M are enclosed to over a box (the box's own width dominates long before the
#: point scene's rel_width: a tighter tolerance only spends the piece budget)
BOX_REL_WIDTH = fmpq(1, 1000)
#: the parameters m and M depend on (D through A0, C0; f through a); their enclosures over a box are shared by
#: every box with the same intervals of these (a paving's split in k, mu, H or B1 reuses them)
EXTREMA_PARAMETERS = ("A", "A1", "A2", "C1", "a")
_EXTREMA_CACHE: dict = {}


class BoxGimbal(Gimbal):
    """A :class:`Gimbal` whose parameter balls contain a whole box of the scene's raw parameters."""

    def __init__(self, base: Gimbal, raw: dict[str, tuple]):
        super().__init__(base.A0, base.B0, base.C0, base.H, base.k, base.a, base.mu, base.x2_star, base.law)
        self.raw = raw          # name -> (lo, hi) exact rationals, for every rational parameter
        # m and M (claim_context.ClaimContext) are shared through this cache by boxes with the same intervals of the
        # parameters they depend on (and the same law and x2*)
        self.extrema_cache = _EXTREMA_CACHE
        self.extrema_key = (base.law.name, str(base.x2_star.ball().mid()),
                            tuple((k, raw[k]) for k in EXTREMA_PARAMETERS))

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


def raw_intervals(model, box: Box) -> dict[str, tuple]:
    """name -> (lo, hi) exact rationals for every rational parameter: the box's edges, the scene's point values
    (lo == hi) for the rest."""
    out = {}
    for k in RATIONAL:
        if k in box.names:
            out[k] = box.interval(k)
        else:
            q = model.params[k].rational
            out[k] = (q, q)
    return out


_raw = raw_intervals


def validate_box(model, box: Box) -> None:
    bad = [n for n in box.names if n not in BOX_PARAMETERS]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: kind 'lyapunov' takes a tolerance only for {list(BOX_PARAMETERS)}; "
                             f"write {bad[0]!r} as a single value")
    r = raw_intervals(model, box)
    for k in ("A", "C", "H", "k", "a", "mu"):
        if not r[k][0] > 0:
            raise ParameterError(f"parameter {k!r}: need {k} > 0 on the whole box (its lower end is {r[k][0]})")
    for k in ("A1", "B1", "C1", "A2"):
        if r[k][0] < 0:
            raise ParameterError(f"parameter {k!r}: need {k} >= 0 on the whole box (its lower end is {r[k][0]})")
    if not r["A2"][0] + r["C1"][0] > 0:
        raise ParameterError("parameters 'A2', 'C1': need A0 > C0, i.e. A2 + C1 > 0, on the whole box")


def boxed_model(model, raw: dict[str, tuple]):
    """The scene's model with a :class:`BoxGimbal` of ``raw``'s intervals (no paper audit, the piece budget
    capped at BOX_MAX_PIECES, maxima enclosed to BOX_REL_WIDTH)."""
    return dataclasses.replace(model, gimbal=BoxGimbal(model.gimbal, raw), paper={},
                               max_pieces=min(model.max_pieces, BOX_MAX_PIECES),
                               rel_width=max(model.rel_width, BOX_REL_WIDTH))


def evaluate_box(model, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box (see the module docstring). ``vdot_nonpositive`` is first tried
    by the coupled Psi test of :mod:`.box_vdot` (each parameter's R with its own Psi, centred forms and
    monotone faces); where that does not prove it, by the claims' own evaluation on the box's balls."""
    require_box_claims(claims, BOX_CLAIMS)
    raw = raw_intervals(model, box)
    out: dict[str, tuple[str, str]] = {}
    rest = list(claims)
    if "vdot_nonpositive" in rest:
        v = decide_vdot_box(model, raw, min(model.max_pieces, BOX_MAX_PIECES))
        if v is not None:
            out["vdot_nonpositive"] = v
            rest.remove("vdot_nonpositive")
    if rest:
        a = attempt(boxed_model(model, raw), rest, current_precision())
        out.update(box_outcomes(a, rest))
    return {c: out[c] for c in claims}
