"""The rigorous primitives. They know nothing of gyroscopes; every scene kind is built on them.

* :mod:`~rigor_gyro.core.exact`        exact parameters: decimal strings -> rationals (times pi)
* :mod:`~rigor_gyro.core.balls`        precision, certified predicates, escalation, outward decimals
* :mod:`~rigor_gyro.core.roots`        interval Newton: existence and uniqueness of real roots
* :mod:`~rigor_gyro.core.polyroots`    roots of rational polynomials, reality and simplicity proved
* :mod:`~rigor_gyro.core.subdivision`  certified positivity and extrema over intervals (branch and bound)
* :mod:`~rigor_gyro.core.outcome`      Status, Claim, AuditStatus, AuditRow: what a proof or audit returns
* :mod:`~rigor_gyro.core.audit`        printed decimals against certified balls (correct rounding)
* :mod:`~rigor_gyro.core.errors`       bad input and failed certification, kept apart

Rule (tests/test_rules.py): nothing here imports a scene kind or the application layer, nor numpy,
scipy, mpmath or matplotlib. Only :mod:`~rigor_gyro.core.balls` sets the working precision.
"""
