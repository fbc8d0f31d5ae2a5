"""Derivative enclosures of the relay's G = g K over (theta, parameter) boxes as unions over sub-boxes (issue 37
part 1: the parametric Newton step over a +-1 % box).

Why: the second-order forms of :mod:`.continuation` read dG/dtheta over Theta x box from Hessian balls that
the complex-ball evaluation of exp(lambda theta) overestimates by a factor ~30 (its excess is first order in
the box's width: the phase omega theta ~ 3.4 sits next to tanh's pole at pi). Over B +-1 % the enclosure of
dG/dtheta then contains 0 although the true derivative is 0.044 +- 0.01. Cutting Theta x box into cells and
enclosing the gradient on each by its own second-order form (gradient at the cell's centre plus the cell's
Hessian times the cell's deviations, intersected with the cell's direct enclosure) shrinks the excess with
the cell's width; the union over the cells contains every gradient value over the whole box. Only these
derivative bounds are subdivided: the Newton step that uses them stays one step over the whole box.

Guarantee: :func:`gradient_union` returns balls D_k (k over the box's directions, then theta) with
dG/dx_k (theta, P) in D_k for every theta in Theta and every P in the box: the cells cover Theta x box
(their ends are exact dyadic points, the first and last the box's own ends), and on each cell
:func:`rigor_gyro.core.jets.second_order_gradient` and the direct evaluation both enclose the gradient
(mean value theorem), so their intersection does. Precision: the current working precision. Fails when: a
cell's spectrum is degenerate (:class:`.flow.DegenerateSpectrum`) or a ball is not finite: returns None.
"""
from __future__ import annotations

from types import SimpleNamespace

from flint import acb, arb

from ...core.jets import Jet, second_order_gradient, second_order_value
from .flow import DegenerateSpectrum, PARAMETER_NAMES

__all__ = ["split_counts", "cells", "grid", "gradient_union", "band_root"]


def split_counts(weights: list[float], total: int) -> list[int]:
    """Pieces per direction, powers of 2 with product <= ``total``: the direction whose weight per piece
    is largest is halved first (a weight: the direction's half-width times |its partial derivative|)."""
    counts = [1] * len(weights)
    prod = 1
    while prod * 2 <= total and any(w > 0 for w in weights):
        i = max(range(len(weights)), key=lambda j: weights[j] / counts[j])
        counts[i] *= 2
        prod *= 2
    return counts


def cells(X: arb, n: int) -> list[tuple[arb, arb]]:
    """[(cell, centre)]: n cells covering the ball X's interval [lower, upper], with exact dyadic ends and
    centres (the first cell starts at X's lower end, the last ends at its upper end)."""
    lo, hi = arb(X.lower()), arb(X.upper())
    pts = [lo] + [arb((lo + (hi - lo) * i / n).mid()) for i in range(1, n)] + [hi]
    out = []
    for a, b in zip(pts, pts[1:]):
        out.append((a.union(b), arb(((a + b) / 2).mid())))
    return out


def grid(lists):
    """Every combination of one entry from each list (the cells of a product of subdivisions)."""
    out = [[]]
    for ls in lists:
        out = [o + [c] for o in out for c in ls]
    return out


def gradient_union(make_models, centre_values: dict[str, arb], box: dict[str, arb], dirs: list[str],
                   Theta: arb, counts: list[int]):
    """Balls containing each partial derivative of G (the box's directions, then theta) over Theta x box,
    as the union over ``counts`` cells per direction (the last count is theta's); None when a cell fails.

    ``make_models(centre_values, box)``: the :class:`.continuation._Models` of a parameter cell (centre point
    balls for all nine parameters, cell balls for ``dirs``)."""
    from .parametric import nested_variable
    k = len(dirs)
    m = k + 1
    pcells = grid([cells(box[d], counts[i]) for i, d in enumerate(dirs)])
    tcells = cells(Theta, counts[k])
    out = None
    for pc in pcells:
        cell = _cell_models(make_models, centre_values, dirs, pc)
        if cell is None:
            return None
        cv, cb, models = cell
        for T, tm in tcells:
            Gc = models.centre.G(Jet.variable(acb(tm), k, m))
            Gn = models.nested.G(nested_variable(T, k, m))
            grads = second_order_gradient(Gc, Gn, models.devs + [T - tm])
            direct = [Gn.v.d[i].real for i in range(m)]
            cellg = []
            for g, dv in zip(grads, direct):
                if g.is_finite() and dv.is_finite():
                    if not g.overlaps(dv):
                        raise AssertionError(f"a cell's gradient form {g} misses its direct enclosure {dv}: a bug")
                    g = g.intersection(dv)
                elif not g.is_finite():
                    g = dv
                if not g.is_finite():
                    return None
                cellg.append(g)
            out = cellg if out is None else [a.union(b) for a, b in zip(out, cellg)]
    return out


def _cell_models(make_models, centre_values: dict[str, arb], dirs: list[str], pc):
    """(centre values, cell balls, models) of one parameter cell ``pc`` (pairs of cell ball and its centre per
    direction), or None when the cell's spectrum is degenerate."""
    cv = dict(centre_values)
    cb = {}
    for d, (cell, mid) in zip(dirs, pc):
        cv[d] = mid
        cb[d] = cell
    try:
        return cv, cb, make_models(SimpleNamespace(**{n: cv[n] for n in PARAMETER_NAMES}), cb)
    except DegenerateSpectrum:
        return None


def band_root(make_models, centre_values: dict[str, arb], box: dict[str, arb], dirs: list[str], tc: arb,
              slope: list[arb], rho: arb, counts: list[int]):
    """theta*(P) in the band tc + slope . (P - c) + U, U = [-rho, rho], by one interval Newton step in u for
    F(u, P) = G(tc + slope . (P - c) + u, P) over the whole box (the parametric Newton of the implicit function
    with the centre's tangent as predictor): returns (image, F0, dF/du) with image = -F0 / dF/du, where F0
    contains F(0, P) and dF/du = G_theta on the band, both for every P in the box (unions over the parameter
    cells, each by the second-order form in (P, u) about its centre, intersected with its direct enclosure).
    When 0 is not in dF/du and the image lies in the interior of U, G(., P) has exactly one root in the band
    for every P, u*(P) in the image (1-D interval Newton member by member). None when a cell fails.
    ``tc``, ``slope`` exact points; c = the box's centre ``centre_values``."""
    k = len(dirs)
    slope_acb = [acb(s) for s in slope] + [acb(1)]
    pcells = grid([cells(box[d], counts[i]) for i, d in enumerate(dirs)])
    U = arb(0, rho.upper())
    F0 = gu = None
    for pc in pcells:
        cell = _cell_models(make_models, centre_values, dirs, pc)
        if cell is None:
            return None
        cv, cb, models = cell
        shift_c = tc + sum((s * (cv[d] - centre_values[d]) for s, d in zip(slope, dirs)), arb(0))
        shift_b = tc + sum((s * (cb[d] - centre_values[d]) for s, d in zip(slope, dirs)), arb(0))
        th_c = Jet(acb(shift_c), slope_acb)
        inner = Jet(acb(shift_b + U), slope_acb)
        th_n = Jet(inner, slope_acb)
        Fc = models.centre.G(th_c)
        Fn = models.nested.G(th_n)
        val = second_order_value(Fc, Fn, models.devs + [arb(0)])
        du = second_order_gradient(Fc, Fn, models.devs + [U])[k]
        # direct enclosures: F(0, P) by the first-order box evaluation at u = 0, G_theta on the band
        direct_du = Fn.v.d[k].real
        if direct_du.is_finite() and du.is_finite():
            if not du.overlaps(direct_du):
                raise AssertionError(f"dF/du's form {du} misses its direct enclosure {direct_du}: a bug")
            du = du.intersection(direct_du)
        if not (val.is_finite() and du.is_finite()):
            return None
        F0 = val if F0 is None else F0.union(val)
        gu = du if gu is None else gu.union(du)
    if F0 is None or gu.contains(0):
        return None
    return -F0 / gu, F0, gu
