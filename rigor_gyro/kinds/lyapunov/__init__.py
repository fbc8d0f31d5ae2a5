"""Scene kind ``lyapunov``: the attraction estimate of a gimbal gyroscope with viscous friction
(Agafonov et al. 2013, seed 000).

* opt-in claims (``OPT_IN_CLAIMS``; a scene names them in ``claims_only``): ``natural_sublevel``
  (:mod:`.natural_domain`);
* :mod:`.moments`: the moment laws f(x2) ("sine", "linear"; a new law is one class and one line);
* :mod:`.model`: system (2) and V (7) in balls, Vdot by automatic differentiation and by the Psi form,
  and the Vdot <= 0 decision shared by the claims and the audit;
* :mod:`.claims`: the claims (constants, damping, Vdot <= 0, V > 0, invariant set, best mu);
* :mod:`.paper`: the formulas as printed and the audit of the example's numbers;
* :mod:`.boxes`: the claims over a box of parameters (for :mod:`rigor_gyro.margins`);
* :mod:`.approx`: float/mpmath cross-checks (never a verdict); :mod:`.plots`: the figures.
"""
from .claims import ALL_CLAIMS, CLAIMS, HEADLINE, OPT_IN_CLAIMS, PARAMETERS, attempt, validate

__all__ = ["CLAIMS", "OPT_IN_CLAIMS", "ALL_CLAIMS", "HEADLINE", "PARAMETERS", "validate", "attempt"]
