"""Scene kind ``eigenfrequencies``: the natural frequencies of an astatic gyroscope in an elastic
gimbal (Rudenko 1976, seed 002).

* :mod:`.model`: the characteristic quartic, the nu quadratics and the paper's estimates in balls;
* :mod:`.claims`: the claims (roots, nu ordering, branches, bounds (5), brackets (7)-(10), approximations);
* :mod:`.paper`: the formulas as printed and the audit of the example's numbers;
* :mod:`.boxes`: the claims over a box of parameters (tolerances; used by :mod:`rigor_gyro.margins`);
* :mod:`.approx`: numpy/mpmath cross-checks (never a verdict).
"""
from .claims import CLAIMS, HEADLINE, CLAIMS_INDEPENDENT_OF, PARAMETERS, attempt, validate

__all__ = ["CLAIMS", "HEADLINE", "CLAIMS_INDEPENDENT_OF", "PARAMETERS", "validate", "attempt"]
