"""Scene kind ``periodic_orbit``: the self-oscillation of a relay gyro-stabiliser (Roitenberg 1947,
seed 001).

* :mod:`.flow`: the exact flow between switchings (spectral form in balls), the half-period function
  g, Taylor-model enclosures, the tail bound;
* :mod:`.claims`: the claims (half-period roots, genuineness, initial point, multipliers, stability);
* :mod:`.tracked`, :mod:`.tracked_claims`: option ``orbit``, the claims about the root of g nearest a given
  half-period (certified nearest), with their own statements (:func:`statements`);
* :mod:`.paper`: the paper's own forms (a_ij, determinant (12), Tables 2-4, (25)) and the audit;
* :mod:`.boxes`: the claims over a box of parameters (for :mod:`rigor_gyro.margins`);
* :mod:`.approx`: numpy/scipy/mpmath cross-checks (never a verdict); :mod:`.plots`: the figure;
* :mod:`.dispatch`: a scene with a ``[plant]`` table (the user's own relay plant, issue 42) goes to
  :mod:`.plant_model`, :mod:`.plant_orbit`, :mod:`.plant_claims` (checker :mod:`.plant_check`).
"""
from .claims import CLAIMS, HEADLINE, CLAIMS_INDEPENDENT_OF, OPTIONS, PARAMETERS
from .dispatch import attempt, statements, validate

__all__ = ["CLAIMS", "HEADLINE", "CLAIMS_INDEPENDENT_OF", "PARAMETERS", "OPTIONS", "validate", "attempt", "statements"]
