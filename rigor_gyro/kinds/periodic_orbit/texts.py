"""How the relay kind writes a ball in a reason or a counterexample (shared by :mod:`.claims` and
:mod:`.tracked_claims`).

Guarantee: every text is an outward-rounded decimal interval containing the ball
(:func:`rigor_gyro.core.balls.decimal_bounds`); never python-flint's ``[mid +/- rad]`` form.
Precision: the ball's own. Fails when: never (an infinite ball prints as [-inf, +inf]).
"""
from __future__ import annotations

from flint import acb, arb

from ...core.balls import decimal_bounds, decimal_bounds_apart

__all__ = ["interval_text", "upper_text", "stored_bounds", "modulus_text", "complex_text"]


def interval_text(x: arb, digits: int = 12) -> str:
    """[lo, hi] to ``digits`` significant digits, rounded outward."""
    lo, hi = decimal_bounds(x, digits)
    return f"[{lo}, {hi}]"


def upper_text(x: arb, digits: int = 6) -> str:
    """An upper bound of the ball (its upper end rounded up) to ``digits`` significant digits."""
    return decimal_bounds(x, digits)[1]


def stored_bounds(x: arb) -> list[str]:
    """[lo, hi] as outward-rounded decimals to the ball's accuracy (the form a counterexample is
    stored in: a modulus certainly > 1 keeps the digits that show it)."""
    return list(decimal_bounds(x))


def modulus_text(x: arb, digits: int) -> str:
    """A modulus as [lo, hi], with the extra digits that keep it apart from 1 when it certainly is."""
    lo, hi = decimal_bounds_apart(x, 1, digits)
    return f"[{lo}, {hi}]"


def complex_text(z: acb, digits: int = 12) -> str:
    return f"{interval_text(z.real, digits)} + {interval_text(z.imag, digits)} i"
