"""rigor_gyro: verified numerics for gyroscopic instruments.

Every number it calls proved comes from Arb ball arithmetic (python-flint) over the exact decimal
parameters the user wrote. Floats (numpy, scipy, in :mod:`rigor_gyro.approx`) only cross-check.

Architecture, bottom up:

* :mod:`~rigor_gyro.exact`        exact parameters: decimal strings -> rationals (times pi)
* :mod:`~rigor_gyro.balls`        precision, certified predicates, escalation, outward decimals
* :mod:`~rigor_gyro.roots`        interval Newton: existence and uniqueness of real roots
* :mod:`~rigor_gyro.polyroots`    roots of rational polynomials, reality and simplicity proved
* :mod:`~rigor_gyro.audit`        printed numbers against certified balls
* :mod:`~rigor_gyro.certificate`  Status, Claim, AuditRow, Certificate (JSON)
* :mod:`~rigor_gyro.scene`        TOML scene files, built-in scenes, kind registry
* :mod:`~rigor_gyro.prover`       validate -> attempt at escalating precision -> Certificate
* :mod:`~rigor_gyro.report`       Certificate -> Markdown
* :mod:`~rigor_gyro.cli`          ``rigor-gyro list | prove``
* :mod:`~rigor_gyro.subdivision`  certified positivity and extrema over intervals (branch and bound)
* scene kinds (one imported per scene):
  - ``eigenfrequencies``: :mod:`~rigor_gyro.eigfreq` (+ :mod:`~rigor_gyro.eigfreq_formulas`)
  - ``lyapunov``: :mod:`~rigor_gyro.lyapunov` on :mod:`~rigor_gyro.gimbal` and :mod:`~rigor_gyro.moments`
    (+ :mod:`~rigor_gyro.lyapunov_audit`)
  - ``periodic_orbit``: :mod:`~rigor_gyro.relay_orbit` on :mod:`~rigor_gyro.relay_flow`
    (+ :mod:`~rigor_gyro.relay_formulas`)
"""
from .balls import (certainly_ge, certainly_gt, certainly_le, certainly_lt, certainly_negative,
                    certainly_positive, compare, decimal_bounds, escalate, possibly_zero, quantity,
                    working_precision)
from .certificate import AuditRow, AuditStatus, Certificate, Claim, Status
from .errors import CertificationFailed, ParameterError, RigorGyroError, SceneError
from .exact import Exact, parse_exact
from .polyroots import PolynomialRoots, isolate_polynomial
from .prover import prove_scene
from .roots import Isolation, RootPiece, RootStatus, isolate_roots, newton_root
from .scene import Scene, builtin_scenes, load_scene, parse_scene

__version__ = "0.1.0"

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
]
