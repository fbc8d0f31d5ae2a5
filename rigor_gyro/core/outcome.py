"""Outcomes: the three-valued :class:`Status` of a claim, the :class:`Claim` record, and the
:class:`AuditStatus` / :class:`AuditRow` of a printed number checked against a certified ball.

These records know nothing of gyroscopes: subdivision returns a Status, every scene kind returns
Claims and AuditRows, and :mod:`rigor_gyro.certificate` collects them into a certificate. They live in
the core (not beside the certificate) so that the rigorous primitives and the kinds can return them
without importing the application layer.

Guarantee: ``Status.REFUTED`` is only ever set for a claim that is certainly false (a certified
counterexample); ``Status.of`` refuses a claim that is both proved and refuted.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from flint import arb

from .balls import decimal_bounds

__all__ = ["Status", "AuditStatus", "Claim", "AuditRow"]


class Status(Enum):
    """The outcome of a claim. REFUTED only for a claim that is certainly false."""

    PROVED = "proved"
    REFUTED = "refuted"
    INCONCLUSIVE = "inconclusive"

    @classmethod
    def of(cls, holds: bool, fails: bool) -> "Status":
        """PROVED if ``holds`` was certified, REFUTED if ``fails`` was, else INCONCLUSIVE."""
        if holds and fails:
            raise AssertionError("a claim cannot be both proved and refuted: a bug in the caller")
        return cls.PROVED if holds else cls.REFUTED if fails else cls.INCONCLUSIVE


class AuditStatus(Enum):
    """The outcome of an audit row about the paper."""

    AGREES = "agrees"            # printed number is a correct rounding of the certified value
    DISAGREES = "disagrees"      # it is certainly not
    MISPRINT = "misprint"        # the printed formula disagrees, another reading reproduces it
    CONFIRMED = "confirmed"      # a verbal assertion certified true
    REFUTED = "refuted"          # a verbal assertion certified false
    UNDECIDED = "undecided"      # the balls did not separate (raise the precision)


@dataclass
class Claim:
    """One claim about the system. ``reason`` says why it holds, or what failed and what to try.

    A REFUTED claim must carry its ``counterexample``: the certified data that make the statement
    false as written (a point and the certified value there, a violated inequality with both balls,
    an exhaustive list of roots each with its witness). A search that stopped at a limit (a range,
    a budget, a grid) has no counterexample, so it cannot refute: constructing a REFUTED claim
    without one raises :class:`AssertionError` (a bug in the kind, exit 4), never a verdict.
    """

    id: str
    statement: str
    status: Status
    reason: str
    precision_bits: int = 0
    details: dict[str, Any] = field(default_factory=dict)
    counterexample: dict[str, Any] | None = None
    #: for an INCONCLUSIVE claim, the ball whose certain sign would decide it (a margin, a difference);
    #: the prover compares it across precisions to tell whether doubling the precision still helps
    decides: arb | None = field(default=None, compare=False, repr=False)
    #: for an INCONCLUSIVE claim that no precision can decide (it rests on a refuted claim, or on a
    #: search range the scene restricts), why: the prover stops escalating for it
    precision_cannot_help: str | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.status is Status.REFUTED and not self.counterexample:
            raise AssertionError(f"claim {self.id!r} refuted without a certified counterexample "
                                 f"({self.reason}): a bug in the kind")

    def to_json(self) -> dict[str, Any]:
        d = {"id": self.id, "statement": self.statement, "status": self.status.value,
             "reason": self.reason, "precision_bits": self.precision_bits}
        if self.details:
            d["details"] = self.details
        if self.counterexample:
            d["counterexample"] = self.counterexample
        return d


@dataclass
class AuditRow:
    """One printed number (or formula, or assertion) of the paper against the certified value."""

    id: str
    printed: str
    reading: str
    value: arb | None
    status: AuditStatus
    note: str = ""
    #: a ball containing the value recomputed from the paper's own printed inputs, when the kind has one
    #: (the classifier then tells the paper's computation from a misprint: class ``propagated``)
    propagated: Any = field(default=None, compare=False, repr=False)
    #: what ``propagated`` was recomputed from, for the reading (default: "the paper's own printed inputs")
    propagated_from: str | None = field(default=None, compare=False, repr=False)
    #: the single-edit search of the printed formula (core.formula_edits), when the kind ran one:
    #: {"formula", "tried", "reproducing" (descriptions), "summary"}
    formula_edits: dict | None = field(default=None, compare=False, repr=False)

    def to_json(self) -> dict[str, Any]:
        # the row stores the ball's outward-rounded ends only: those of balls.quantity, without its midpoint and
        # radius (decimal_bounds is where quantity takes them from: the same strings)
        lo, hi = decimal_bounds(self.value) if self.value is not None else ("", "")
        out = {"id": self.id, "printed": self.printed, "reading": self.reading, "lo": lo,
               "hi": hi, "status": self.status.value, "note": self.note}
        if self.formula_edits is not None:
            out["formula_edits"] = self.formula_edits
        return out
