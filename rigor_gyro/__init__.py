"""rigor_gyro: verified numerics for gyroscopic instruments.

Every number it calls proved comes from Arb ball arithmetic (python-flint) over the exact decimal
parameters the user wrote. Floats (numpy, scipy, in each kind's ``approx`` module) only cross-check.

Architecture, bottom up (imports point down; tests/test_rules.py checks it):

* :mod:`rigor_gyro.core`: rigorous primitives that know nothing of gyroscopes:
  :mod:`~rigor_gyro.core.exact` (exact parameters), :mod:`~rigor_gyro.core.balls` (precision,
  certified predicates, escalation, outward decimals), :mod:`~rigor_gyro.core.roots` (interval Newton),
  :mod:`~rigor_gyro.core.polyroots` (rational polynomials), :mod:`~rigor_gyro.core.subdivision`
  (positivity and extrema by branch and bound), :mod:`~rigor_gyro.core.outcome` (Status, Claim,
  AuditRow), :mod:`~rigor_gyro.core.audit` (printed numbers against balls), :mod:`~rigor_gyro.core.errors`.
* :mod:`rigor_gyro.kinds`: the kind interface and registry; one package per scene kind, only the
  scene's own imported when it is proved:
  - ``eigenfrequencies`` (Rudenko 1976): model, claims, paper, approx;
  - ``lyapunov`` (Agafonov et al. 2013): moments, model, claims, paper, approx, plots;
  - ``periodic_orbit`` (Roitenberg 1947): flow, claims, paper, approx, plots.
* the application: :mod:`~rigor_gyro.scene` (TOML scene files, built-in scenes),
  :mod:`~rigor_gyro.prover` (validate -> attempt at escalating precision -> certificate),
  :mod:`~rigor_gyro.certificate` (Certificate, JSON), :mod:`~rigor_gyro.report` (Markdown),
  :mod:`~rigor_gyro.cli` (``rigor-gyro list | prove``).

Writing, checking and paving are exported too, imported on first use (``import rigor_gyro`` stays cheap):
``write_outputs`` (certificate and report files), ``check_file`` / ``check_certificate`` (the independent
checker: certificates, pavings, thresholds, scans), ``box_scene`` / ``pave`` / ``write_paving`` (a scene
with tolerances), ``find_threshold`` / ``write_threshold`` and ``run_scan`` / ``write_scan`` (one parameter).
"""
from .certificate import Certificate
from .core.balls import (certainly_ge, certainly_gt, certainly_le, certainly_lt, certainly_negative,
                         certainly_positive, compare, decimal_bounds, escalate, possibly_zero, quantity,
                         working_precision)
from .core.errors import CertificationFailed, ParameterError, RigorGyroError, SceneError
from .core.exact import Exact, parse_exact
from .core.outcome import AuditRow, AuditStatus, Claim, Status
from .core.polyroots import PolynomialRoots, isolate_polynomial
from .core.roots import Isolation, RootPiece, RootStatus, isolate_roots, newton_root
from .prover import prove_scene
from .scene import Scene, builtin_scenes, load_scene, parse_scene
from .version import __version__

__all__ = [
    "Exact", "parse_exact",
    "working_precision", "escalate", "compare", "certainly_lt", "certainly_le", "certainly_gt",
    "certainly_ge", "certainly_positive", "certainly_negative", "possibly_zero", "decimal_bounds",
    "quantity",
    "RootStatus", "RootPiece", "Isolation", "newton_root", "isolate_roots",
    "PolynomialRoots", "isolate_polynomial",
    "Status", "AuditStatus", "Claim", "AuditRow", "Certificate",
    "Scene", "load_scene", "parse_scene", "builtin_scenes", "prove_scene",
    "RigorGyroError", "ParameterError", "SceneError", "CertificationFailed",
    "__version__",
    "write_outputs", "render_markdown", "check_file", "check_certificate", "CheckReport", "CertificateError",
    "box_scene", "pave", "has_tolerances", "write_paving", "find_threshold", "write_threshold", "run_scan",
    "write_scan",
]

#: public names imported on first use (module-level __getattr__): writing, checking, paving, margins
_LAZY = {"write_outputs": "report", "render_markdown": "report",
         "check_file": "check", "check_certificate": "check", "CheckReport": "check", "CertificateError": "check",
         "box_scene": "margins.paving", "pave": "margins.paving", "has_tolerances": "margins.paving",
         "write_paving": "margins.report", "find_threshold": "margins.threshold",
         "write_threshold": "margins.threshold", "run_scan": "margins.scan", "write_scan": "margins.scan"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
