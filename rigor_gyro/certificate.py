"""Certificates: what was proved about which exact parameters, in a form a machine can re-check.

A :class:`Certificate` holds the scene (exact parameter strings as written), the claims with their
:class:`Status`, the enclosures of the named quantities as outward-rounded decimal strings, and the
audit of the source paper. Claims are statements about the system; the audit is about the paper and
never changes the verdict or the exit status.

Guarantee: ``verdict`` is ``proved`` only if every claim is ``proved``; ``refuted`` if some claim is
refuted (a certified counterexample); otherwise ``inconclusive``. Every quantity's ``lo``/``hi``
certainly contain the exact value (see :func:`rigor_gyro.core.balls.quantity`).

The outcome records (:class:`Status`, :class:`Claim`, :class:`AuditStatus`, :class:`AuditRow`) are
defined in :mod:`rigor_gyro.core.outcome` and re-exported here, where a certificate's reader looks.
"""
from __future__ import annotations

import hashlib
import json
import math
import platform
from dataclasses import dataclass, field
from json.encoder import encode_basestring as _encode_string
from typing import Any

from flint import arb

from .core.balls import as_quantity, quantity, working_precision
from .core.misprints import classify_row
from .core.errors import CertificationFailed
from .core.outcome import AuditRow, AuditStatus, Claim, Status
from .version import __version__

__all__ = ["SCHEMA", "Status", "AuditStatus", "Claim", "AuditRow", "Certificate", "EXIT_CODES", "digest",
           "dumps_indented"]

SCHEMA = "rigor-gyro/certificate/2"


def digest(data: dict[str, Any]) -> str:
    """sha256 of the canonical JSON (sorted keys, no spaces) of a certificate without ``integrity``."""
    body = {k: v for k, v in data.items() if k != "integrity"}
    text = json.dumps(body, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


class _Fallback(Exception):
    """A value :func:`dumps_indented` leaves to the json module (a non-string key, an unknown type)."""


def _float_text(x: float) -> str:
    """A float as ``json.dumps`` writes it (allow_nan: NaN, Infinity, -Infinity)."""
    if x != x:
        return "NaN"
    if x == math.inf:
        return "Infinity"
    if x == -math.inf:
        return "-Infinity"
    return float.__repr__(x)


def dumps_indented(obj: Any) -> str:
    """``json.dumps(obj, indent=2, ensure_ascii=False)``, the same text byte for byte, built by one recursive
    walk that joins each container's items in C (the json module's indented encoder is its pure-Python
    generator chain, about 2-3x slower on a 400 kB certificate). The same rules: dicts in insertion order,
    tuples as lists, strings by the json module's own escaping, floats and ints by their repr (NaN,
    Infinity), empty containers as ``{}`` / ``[]``. A value it does not know (a non-string dict key,
    another type) hands the whole object to ``json.dumps``, which decides (and raises TypeError where it
    would). tests/test_certificate_text.py compares it with ``json.dumps`` on every certificate of proofs/
    and on random trees."""
    enc = _encode_string

    def walk(o: Any, ind: str) -> str:
        t = type(o)
        if t is str:
            return enc(o)
        if t is dict or t is list or t is tuple:
            if not o:
                return "{}" if t is dict else "[]"
            inner = ind + "  "
            sep = "," + inner
            if t is dict:
                for k in o:
                    if type(k) is not str:
                        raise _Fallback
                return "{" + inner + sep.join([enc(k) + ": " + (enc(v) if type(v) is str else walk(v, inner))
                                               for k, v in o.items()]) + ind + "}"
            return "[" + inner + sep.join([enc(v) if type(v) is str else walk(v, inner) for v in o]) + ind + "]"
        if isinstance(o, str):
            return enc(o)
        if o is None:
            return "null"
        if o is True:
            return "true"
        if o is False:
            return "false"
        if isinstance(o, int):
            return int.__repr__(o)
        if isinstance(o, float):
            return _float_text(o)
        raise _Fallback         # subclasses of dict, list, tuple and other types: the json module's rules
    try:
        return walk(obj, "\n")
    except _Fallback:
        return json.dumps(obj, indent=2, ensure_ascii=False)


EXIT_CODES = {Status.PROVED: 0, Status.REFUTED: 1, Status.INCONCLUSIVE: 3}


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
    witnesses: dict[str, Any] = field(default_factory=dict)
    #: the prover's settings (prec, maxprec, and time_limit when one was given): what the checker re-runs
    settings: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        # each quantity shows its certified digits from Python (a Quantity is the arb itself)
        self.quantities = {k: as_quantity(v) for k, v in self.quantities.items()}

    def __repr__(self) -> str:
        """A few lines: the scene, its kind, the verdict, the claims by status, what else it holds."""
        by: dict[str, list[str]] = {}
        for c in self.claims:
            by.setdefault(c.status.value, []).append(c.id)
        counts = ", ".join(f"{len(by[s])} {s}" for s in ("proved", "refuted", "inconclusive") if s in by) or "none"
        lines = [f"<Certificate {self.scene.get('name')!r} (kind {self.scene.get('kind')!r}): "
                 f"{self.verdict.value}, {len(self.claims)} claims: {counts}>"]
        for s in ("refuted", "inconclusive"):
            for cid in by.get(s, [])[:5]:
                reason = self.claim(cid).reason
                lines.append(f"  {cid}: {s}: {reason[:100]}{'...' if len(reason) > 100 else ''}")
        lines.append(f"  {len(self.quantities)} quantities (.quantities[name]), {len(self.paper)} audit rows, "
                     f"{self.precision_bits} bits; .to_json(), rigor_gyro.write_outputs(cert, folder)")
        return "\n".join(lines)

    def _repr_markdown_(self) -> str:
        """For notebooks: the verdict, each claim with its status and reason, and the certified quantities
        (each to its certified digits; the full report is ``rigor_gyro.render_markdown(cert.to_json())``)."""
        esc = lambda t: str(t).replace("|", "\\|").replace("\n", " ")       # noqa: E731
        out = [f"**{esc(self.scene.get('name'))}** (kind `{self.scene.get('kind')}`): "
               f"**{self.verdict.value}** (final attempt at {self.precision_bits} bits)", "",
               "| claim | status | reason |", "|---|---|---|"]
        out += [f"| `{c.id}` | **{c.status.value}** | {esc(c.reason)[:300]} |" for c in self.claims]
        if self.quantities:
            out += ["", "| quantity | certified value |", "|---|---|"]
            items = list(self.quantities.items())
            out += [f"| `{k}` | {esc(v)} |" for k, v in items[:20]]
            if len(items) > 20:
                out.append(f"| ... | {len(items) - 20} more in `.quantities` |")
        return "\n".join(out) + "\n"

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

    def _paper_json(self) -> list[dict[str, Any]]:
        """The audit rows, each with its discrepancy ``class`` and the ``class_reading`` that explains it
        (core.misprints; computed at the certificate's precision plus a margin, so it is reproducible)."""
        out = []
        with working_precision(max(self.precision_bits, 64) + 64):
            for r in self.paper:
                row = r.to_json()
                c = classify_row(r)
                row["class"], row["class_reading"] = c.cls, c.reading
                if len(c.readings) > 1:
                    row["class_also"] = c.readings[1:]
                out.append(row)
        return out

    def to_json(self) -> dict[str, Any]:
        import flint

        data = {
            "schema": SCHEMA,
            "scene": self.scene,
            "software": {"rigor_gyro": __version__, "python_flint": flint.__version__,
                         "python": platform.python_version()},
            "precision_bits": self.precision_bits,
            "precisions_tried": self.precisions_tried,
            "settings": self.settings,
            "verdict": self.verdict.value,
            "claims": [c.to_json() for c in self.claims],
            "quantities": {k: quantity(v) for k, v in self.quantities.items()},
            "paper": self._paper_json(),
            "formulas": self.formulas,
            "notes": self.notes,
            **({"extra": self.extra} if self.extra else {}),
            **({"witnesses": self.witnesses} if self.witnesses else {}),
        }
        data["integrity"] = {"sha256": digest(data)}
        return data

    def timings_json(self) -> dict[str, Any]:
        """The run-dependent part, kept out of the certificate so that the same scene at the same
        settings gives byte-identical certificate and report files (written to timings/<name>.json)."""
        return {"scene": self.scene.get("name"), "precisions_tried": self.precisions_tried, **self.timings}

    def dumps(self) -> str:
        return dumps_indented(self.to_json()) + "\n"
