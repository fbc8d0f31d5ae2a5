"""Scene kind ``eigenfrequencies``: the natural frequencies of an astatic gyroscope in an elastic
gimbal (Rudenko 1976, seed 002).

* :mod:`.model`: the characteristic quartic, the nu quadratics and the paper's estimates in balls;
* :mod:`.claims`: the claims (roots, nu ordering, branches, bounds (5), brackets (7)-(10), approximations);
* :mod:`.paper`: the formulas as printed and the audit of the example's numbers;
* :mod:`.boxes`: the claims over a box of parameters (tolerances; used by :mod:`rigor_gyro.margins`);
* :mod:`.system_model`, :mod:`.system_claims`, :mod:`.system_check`: a gyroscopic system M q'' + (G + D) q' + K q = 0
  written in the scene's ``[system]`` table (issue 42), its eigenfrequencies, stability and brackets;
* :mod:`.approx`: numpy/mpmath cross-checks (never a verdict).
"""
from .claims import (ALL_CLAIMS, CLAIMS, HEADLINE, CLAIMS_INDEPENDENT_OF, PARAMETERS, attempt, available_claims,
                     statements, validate)

__all__ = ["CLAIMS", "ALL_CLAIMS", "HEADLINE", "CLAIMS_INDEPENDENT_OF", "PARAMETERS", "validate", "attempt", "statements",
           "available_claims"]
