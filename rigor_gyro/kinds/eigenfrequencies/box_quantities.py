"""The eigenfrequency kind's quantities over a parameter box (issue 37 part 2; the interface of
:mod:`rigor_gyro.core.box_values`).

Quantities, named as the point certificate names them (:mod:`.claims`):

* ``omega_1`` .. ``omega_4``: the roots of the characteristic quartic, omega_1 < ... < omega_4, with their
  gradients in the box's parameters (implicit function theorem, :mod:`rigor_gyro.core.implicit_roots`);
* ``freq_hz_1`` .. ``freq_hz_4`` (Hz), only when the scene gives ``hz_scale``: hz_scale sqrt(omega_j), with
  gradients;
* ``bracket_1_slack`` .. ``bracket_4_slack``: the design margin of bracket j, as the point certificate
  defines it: min(omega_j - lower_j, upper_j - omega_j), absolute (in units of omega); >= 0 exactly where
  the claim ``bracket_j`` holds (lower <= omega_j <= upper), < 0 where it fails. Its gradient is given only
  where one end binds on the whole box (that end's slack certainly the smaller one); elsewhere the minimum
  of the two is not differentiable and no gradient is stated.

How: the whole box's roots are verified once (:func:`.boxes.box_roots`); each quantity's minimum and
maximum over the box are enclosed by :func:`rigor_gyro.core.centred_forms.extreme` (centred form, and at the
exact face or corner where the quantity is certified monotone in a parameter), and its gradient by forward-mode
AD in balls over the box.

Guarantee: each value ball contains the quantity for every parameter in the box, each gradient ball the
partial derivative for every parameter in the box. A quantity is left out where the roots (or the bracket's
bounds) are not enclosed on the box. On a box of points (lo == hi everywhere) the values are the point's, as
narrow as the precision allows. Precision: the current working precision. Fails when: never raises for a box
it cannot enclose.
"""
from __future__ import annotations

from flint import arb

from ...core.box_values import BoxValue, QuantitySpec
from ...core.boxes import Box
from ...core.centred_forms import enclose, refined_extreme
from ...core.dual_balls import constant
from .boxes import box_roots
from .slack_forms import GapSet
from .system_model import SystemModel

__all__ = ["BOX_QUANTITIES", "quantity_names", "quantities_box"]

BOX_QUANTITIES = {
    **{f"omega_{j}": QuantitySpec(f"omega_{j}, root {j} of the characteristic quartic") for j in range(1, 5)},
    **{f"freq_hz_{j}": QuantitySpec(f"eigenfrequency {j}, hz_scale sqrt(omega_{j}) (only with hz_scale)", "Hz")
       for j in range(1, 5)},
    **{f"bracket_{j}_slack": QuantitySpec(f"slack of bracket {eq}: min(omega_{j} - lower, upper - omega_{j}), "
                                          "absolute", claim=f"bracket_{j}")
       for j, eq in zip(range(1, 5), ("(7)", "(8)", "(9)", "(10)"))},
}


def quantity_names(model) -> list[str]:
    """The quantities this scene has: the frequencies in Hz only when it gives ``hz_scale``; none yet for a
    ``[system]`` model (its ranges over a box are not built: its claims are still decided over boxes)."""
    if isinstance(model, SystemModel):
        return []
    return [k for k in BOX_QUANTITIES if model.hz_scale is not None or not k.startswith("freq_hz_")]


def _range(f, box: Box, refine: int) -> tuple[arb, arb, dict] | None:
    """(ball containing min f, ball containing max f, gradient over the box) or None."""
    enc = enclose(f, box)
    if enc is None:
        return None
    lo, hi = refined_extreme(f, box, -1, refine), refined_extreme(f, box, +1, refine)
    mn = lo if lo is not None else enc.value
    mx = hi if hi is not None else enc.value
    return mn, mx, enc.gradient


def _value(mn: arb, mx: arb) -> arb:
    """The ball [min's lower end, max's upper end]."""
    return arb(mn.lower()).union(arb(mx.upper()))


def quantities_box(model, box: Box, names, refine: int = 0) -> dict[str, BoxValue]:
    """{quantity: BoxValue} for the requested names it can enclose on the box (module docstring). ``refine``:
    bisections spent narrowing each minimum and maximum inside the box
    (:func:`rigor_gyro.core.centred_forms.refined_extreme`); 0 (the margins layer tiles the box itself)."""
    names = [k for k in names if k in BOX_QUANTITIES]
    if not names:
        return {}
    roots, _ = box_roots(model, box, omegas=True, nus=False)
    if roots.omegas is None:
        return {}
    gaps = GapSet(model, box, roots)
    out: dict[str, BoxValue] = {}
    hz = constant(arb(model.hz_scale.fmpq())) if model.hz_scale is not None else None
    for j in range(1, 5):
        w = lambda d, j=j: gaps.omega(j, d)
        if f"omega_{j}" in names:
            r = _range(w, box, refine)
            if r is not None:
                out[f"omega_{j}"] = BoxValue(_value(r[0], r[1]), r[2])
        if f"freq_hz_{j}" in names and hz is not None:
            def f(d, w=w):
                x = w(d)
                return None if x is None else hz * x.sqrt()
            r = _range(f, box, refine)
            if r is not None:
                out[f"freq_hz_{j}"] = BoxValue(_value(r[0], r[1]), r[2])
        if f"bracket_{j}_slack" in names:
            (_, f_lo, _), (_, f_hi, _) = gaps.bracket_gaps(j)
            r_lo, r_hi = _range(f_lo, box, refine), _range(f_hi, box, refine)
            if r_lo is None or r_hi is None:
                continue
            # min over the box of min(s_lo, s_hi) = min(min s_lo, min s_hi); its max is at most min(max, max)
            mn = r_lo[0].min(r_hi[0])
            mx = r_lo[1].min(r_hi[1])
            grad = {}
            if r_lo[1] < r_hi[0]:          # s_lo < s_hi on the whole box: the lower end binds
                grad = r_lo[2]
            elif r_hi[1] < r_lo[0]:
                grad = r_hi[2]
            out[f"bracket_{j}_slack"] = BoxValue(_value(mn, mx), grad)
    return out
