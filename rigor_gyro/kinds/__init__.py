"""Scene kinds: the interface every kind implements, and the registry of kinds.

A kind is a package ``rigor_gyro.kinds.<kind>`` whose ``__init__`` exports

* ``CLAIMS``: ``{claim_id: statement}`` in report order;
* ``validate(scene) -> model``: checks the scene's parameters and options, raising
  :class:`~rigor_gyro.core.errors.ParameterError` naming the parameter (CLI exit 2);
* ``attempt(model, claims, prec) -> Attempt``: one evaluation at ``prec`` bits of the requested claims
  (it computes only what they need);

and has a ``check`` module with ``check(model, certificate_json) -> [CheckResult]`` that re-decides
every claim from the certificate's stored data (used by ``rigor-gyro check``), and may have a
``plots`` module with ``plots(scene, cert, out_dir) -> [paths]`` (the figures; float
drawing code, imported by the driver only when ``--plots`` is given). Inside a kind, ``model``
(or ``flow``) holds the mathematics shared by the claims and the paper audit, ``claims`` the claims,
``paper`` the printed formulas and the audit, ``approx`` the float/mpmath cross-checks (never a
verdict), ``plots`` the figures. The rigorous modules (model, claims, paper) never import approx or
plots, nor numpy, scipy or matplotlib (tests/test_rules.py).

Only the package of the scene's kind is imported when a scene is proved (:func:`kind_module`).
"""
from __future__ import annotations

import importlib
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any, Callable

from flint import arb

from ..core.errors import ParameterError, SceneError
from ..core.outcome import AuditRow, AuditStatus, Claim, Status

__all__ = ["KINDS", "PLANNED_KINDS", "Attempt", "Phases", "kind_module", "claim_statements", "optional_module", "plots_hook", "checker", "require_box_claims",
           "box_outcomes", "scene_claims", "box_claims"]

#: kind -> package implementing it (imported only when a scene of that kind is proved)
KINDS = {
    "eigenfrequencies": "rigor_gyro.kinds.eigenfrequencies",
    "lyapunov": "rigor_gyro.kinds.lyapunov",
    "periodic_orbit": "rigor_gyro.kinds.periodic_orbit",
}
#: kinds described in the documentation whose modules are not in this version yet
PLANNED_KINDS: set[str] = set()


class Phases:
    """Wall time per phase of one attempt (a claim, or a stage such as root isolation), in seconds.

    ``with phases("vdot_nonpositive"): ...`` adds the block's time to that phase. Timing only: it never
    enters a certificate (the prover writes it to the timings file), so certificates stay byte-identical."""

    #: called with each phase's name as it starts (the prover's progress display); None: nobody listens
    listener: Callable[[str], None] | None = None

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {}

    @contextmanager
    def __call__(self, name: str):
        if Phases.listener is not None:
            Phases.listener(name)
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.seconds[name] = self.seconds.get(name, 0.0) + time.perf_counter() - t0


@dataclass
class Attempt:
    """What one evaluation of a kind's claims at one precision established."""

    claims: list[Claim]
    quantities: dict[str, arb]
    paper: list[AuditRow] = field(default_factory=list)
    formulas: list[dict[str, str]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    widths_met: bool = True
    extra: dict[str, Any] = field(default_factory=dict)
    #: the quantities whose requested widths are not met yet (the prover watches them shrink)
    width_quantities: tuple[str, ...] = ()
    #: JSON-able data for rigor-gyro check, per claim (pieces, points), exact rationals as text
    witnesses: dict[str, Any] = field(default_factory=dict)
    #: set by a kind when more precision cannot help the undecided claims (e.g. subdivision budgets
    #: exhausted on wide pieces): escalation stops there and the claims say what to change instead
    stalled: bool = False
    #: wall time per phase (claim or stage), seconds: timing only, never part of a certificate
    phase_seconds: dict[str, float] = field(default_factory=dict, compare=False)

    @property
    def settled(self) -> bool:
        return (self.widths_met and all(c.status is not Status.INCONCLUSIVE for c in self.claims)
                and all(r.status is not AuditStatus.UNDECIDED for r in self.paper))


def claim_statements(module: ModuleType, model: Any) -> dict[str, str]:
    """``{claim_id: statement}`` for this model: the kind's ``statements(model)`` where a scene's options
    change what a claim states (a relay scene's option ``orbit``), otherwise its ``CLAIMS`` and the opt-in
    claims a scene must name (``OPT_IN_CLAIMS``)."""
    statements = getattr(module, "statements", None)
    if statements is not None:
        return statements(model)
    return {**module.CLAIMS, **getattr(module, "OPT_IN_CLAIMS", {})}


def scene_claims(module: ModuleType, scene: Any) -> tuple[dict[str, str], dict[str, str]]:
    """(the claims a scene gets by default, every claim it may name): the kind's ``available_claims(scene)``
    where the scene's own model changes them (a ``[system]`` scene), else (``CLAIMS``, ``ALL_CLAIMS`` or
    ``CLAIMS``)."""
    hook = getattr(module, "available_claims", None)
    if hook is not None:
        return hook(scene)
    return dict(module.CLAIMS), dict(getattr(module, "ALL_CLAIMS", None) or module.CLAIMS)


def box_claims(boxes: ModuleType, model: Any) -> dict[str, str]:
    """The claims a kind's ``boxes`` module decides over a box for this model: its ``box_claims(model)``
    where the model class changes them, else its ``BOX_CLAIMS``."""
    hook = getattr(boxes, "box_claims", None)
    return dict(hook(model)) if hook is not None else dict(boxes.BOX_CLAIMS)


def require_box_claims(claims: list[str], box_claims) -> None:
    """ParameterError unless every claim is one the kind decides over a box (its ``BOX_CLAIMS``)."""
    unknown = [c for c in claims if c not in box_claims]
    if unknown:
        raise ParameterError(f"claim {unknown[0]!r} cannot be decided over a box; over boxes the kind decides "
                             f"{list(box_claims)}")


#: a point claim's status, read over a box: an inconclusive claim leaves the sub-box undecided
_BOX_STATUS = {Status.PROVED: "proved", Status.REFUTED: "refuted", Status.INCONCLUSIVE: "undecided"}


def box_outcomes(attempt: Attempt, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} of an attempt run on box balls (a kind's ``evaluate_box``)."""
    return {c.id: (_BOX_STATUS[c.status], c.reason) for c in attempt.claims if c.id in claims}


def kind_module(kind: str) -> ModuleType:
    """Import and return the package implementing ``kind`` (and nothing else)."""
    try:
        return importlib.import_module(KINDS[kind])
    except KeyError:
        raise SceneError(f"unknown kind {kind!r}; known kinds: {', '.join(KINDS)}") from None


def optional_module(kind: str, name: str) -> ModuleType | None:
    """The kind's optional module ``name`` (``boxes``, ``box_quantities``, ``check``, ``plots``), imported now,
    or None when the kind has none (an import error inside an existing module propagates)."""
    if kind not in KINDS:
        raise SceneError(f"unknown kind {kind!r}; known kinds: {', '.join(KINDS)}")
    try:
        return importlib.import_module(f"{KINDS[kind]}.{name}")
    except ModuleNotFoundError as e:
        if e.name == f"{KINDS[kind]}.{name}":
            return None
        raise


def _optional(kind: str, name: str, attr: str) -> Callable[..., list] | None:
    """``attr`` of the kind's optional module ``name`` (imported now), or None when the kind has none."""
    module = optional_module(kind, name)
    return None if module is None else getattr(module, attr)


def plots_hook(kind: str) -> Callable[..., list] | None:
    """The kind's ``plots(scene, cert, out_dir)`` function, or None when the kind draws no figures.
    Imports the kind's float drawing module: call it only when figures were asked for."""
    return _optional(kind, "plots", "plots")


def checker(kind: str) -> Callable[..., list] | None:
    """The kind's ``check(model, data)`` function (:mod:`rigor_gyro.check`), or None if it has none."""
    return _optional(kind, "check", "check")
