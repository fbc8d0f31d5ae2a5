"""Certificates: what was proved about which exact parameters, in a form a machine can re-check.

A :class:`Certificate` holds the scene (exact parameter strings as written), the claims with their
:class:`Status`, the enclosures of the named quantities as outward-rounded decimal strings, and the
audit of the source paper. Claims are statements about the system; the audit is about the paper and
never changes the verdict or the exit status.

Guarantee: ``verdict`` is ``proved`` only if every claim is ``proved``; ``refuted`` if some claim is
refuted (a certified counterexample); otherwise ``inconclusive``. Every quantity's ``lo``/``hi``
certainly contain the exact value (see :func:`rigor_gyro.balls.quantity`).
"""
from __future__ import annotations

import json
import platform
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from flint import arb

from .balls import quantity
from .errors import CertificationFailed

__all__ = ["SCHEMA", "Status", "AuditStatus", "Claim", "AuditRow", "Certificate", "EXIT_CODES"]

SCHEMA = "rigor-gyro/certificate/1"


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


EXIT_CODES = {Status.PROVED: 0, Status.REFUTED: 1, Status.INCONCLUSIVE: 3}


@dataclass
class Claim:
    """One claim about the system. ``reason`` says why it holds, or what failed and what to try."""

    id: str
    statement: str
    status: Status
    reason: str
    precision_bits: int = 0
    details: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        d = {"id": self.id, "statement": self.statement, "status": self.status.value,
             "reason": self.reason, "precision_bits": self.precision_bits}
        if self.details:
            d["details"] = self.details
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

    def to_json(self) -> dict[str, Any]:
        q = quantity(self.value) if self.value is not None else {"lo": "", "hi": ""}
        return {"id": self.id, "printed": self.printed, "reading": self.reading, "lo": q["lo"],
                "hi": q["hi"], "status": self.status.value, "note": self.note}


@dataclass
class Certificate:
    """The whole outcome of proving one scene."""

    scene: dict[str, Any]
    precision_bits: int
    claims: list[Claim]
    quantities: dict[str, arb]
    paper: list[AuditRow] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    precisions_tried: list[int] = field(default_factory=list)
    formulas: list[dict[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def verdict(self) -> Status:
        statuses = {c.status for c in self.claims}
        if Status.REFUTED in statuses:
            return Status.REFUTED
        if Status.INCONCLUSIVE in statuses or not self.claims:
            return Status.INCONCLUSIVE
        return Status.PROVED

    @property
    def exit_code(self) -> int:
        return EXIT_CODES[self.verdict]

    def claim(self, claim_id: str) -> Claim:
        for c in self.claims:
            if c.id == claim_id:
                return c
        raise KeyError(f"no claim {claim_id!r}; claims are {[c.id for c in self.claims]}")

    def require(self) -> "Certificate":
        """Return self if every claim is proved, else raise CertificationFailed with the reasons."""
        bad = [c for c in self.claims if c.status is not Status.PROVED]
        if bad:
            lines = "; ".join(f"{c.id}: {c.status.value} ({c.reason})" for c in bad)
            raise CertificationFailed(self, f"scene {self.scene.get('name')!r} not proved: {lines}")
        return self

    def to_json(self) -> dict[str, Any]:
        import flint

        from . import __version__
        return {
            "schema": SCHEMA,
            "scene": self.scene,
            "software": {"rigor_gyro": __version__, "python_flint": flint.__version__,
                         "python": platform.python_version()},
            "precision_bits": self.precision_bits,
            "precisions_tried": self.precisions_tried,
            "verdict": self.verdict.value,
            "claims": [c.to_json() for c in self.claims],
            "quantities": {k: quantity(v) for k, v in self.quantities.items()},
            "paper": [r.to_json() for r in self.paper],
            "formulas": self.formulas,
            "notes": self.notes,
            **({"extra": self.extra} if self.extra else {}),
            "timings": self.timings,
        }

    def dumps(self) -> str:
        return json.dumps(self.to_json(), indent=2, ensure_ascii=False) + "\n"
