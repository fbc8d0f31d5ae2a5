"""Steps 2 and 3 of :mod:`.continuation` (the sign condition, the multipliers) decided cell by cell once step 1
(theta*(P), unique in Theta for every P of the whole box) is proved (issue 37 part 1: one relay box of +-1 %).

Why: the sign condition and the multipliers are properties of each member's orbit. Their second-order forms
over the whole box carry the Hessian balls' excess (first order in the width, ~30x for A, B, H at +-1 %), so
over a wide box they decide nothing. Cutting the parameter box into cells and running steps 1-3 of
:mod:`.continuation` on each cell (its own centre, its own theta* jets) shrinks the excess with the cell's
width; the box is still decided in one piece (one Newton step proves theta*(P) over the whole box, one
result is returned), only these enclosures are subdivided.

Guarantee: each cell's root enclosure is required to lie inside the whole box's Theta, where G(., P) has one
root for every P, so every cell follows the same orbit theta*(P); then ``out.genuine`` is set only when
every cell proves the sign condition, ``out.stable`` only when every cell proves every modulus < 1, and
the multipliers / moduli are the unions of the cells' balls (index by index, each cell sorted by modulus),
which contain the four multipliers of every member. Precision: the current working precision. Fails when:
a cell is not decided (``out`` keeps the whole-box result and its problem; a failure never refutes).
"""
from __future__ import annotations

from types import SimpleNamespace

from flint import arb

from ...core.balls import certainly_lt
from .flow import DegenerateSpectrum, PARAMETER_NAMES
from .subbox_union import cells, grid, split_counts

__all__ = ["decide_by_cells", "CELL_COUNTS", "MAX_CELLS"]

#: the first grid of parameter cells (a power of 2, split along the directions that move theta* most); a cell
#: that does not decide is bisected along its heaviest direction, up to MAX_CELLS cells decided in all (a
#: quarter of that for a box in more than two parameters); none further when no cell of the grid is genuine
CELL_COUNTS = (4,)
MAX_CELLS = 64


def decide_by_cells(centre, box: dict[str, arb], dirs: list[str], guesses, out, genuine: bool,
                    stability: bool, steps) -> None:
    """Decide ``out`` (an :class:`.continuation.OrbitOverBox` whose step 1 holds over the whole box) cell by
    cell (module docstring); ``out`` is changed only when every cell decides. ``steps``: continuation's
    steps (attributes OrbitOverBox, SUBBOX_CELLS, models, centre_root, decide, point, theta_over_box),
    passed in so that this module does not import continuation (which calls it)."""
    OrbitOverBox, SUBBOX_CELLS, _Models = steps.OrbitOverBox, steps.SUBBOX_CELLS, steps.models
    _centre_root, _decide, _point, _theta_over_box = steps.centre_root, steps.decide, steps.point, steps.theta_over_box
    Theta = out.theta
    cvals = {k: _point(getattr(centre, k)) for k in PARAMETER_NAMES}
    devs = [box[d] - cvals[d] for d in dirs]
    weights = [float(dv.rad()) * float(abs(g).upper()) for dv, g in zip(devs, out.theta_gradient)]

    def one_cell(cb: dict[str, arb]):
        """(OrbitOverBox of the cell, "") when steps 1-3 decide it, (that, "split") when it is genuine but not
        proved stable and (None, "split") when not genuine (a finer cell might decide them), (None, "stop")
        when the cell does not follow the whole box's orbit (nothing finer can help)."""
        cv = dict(cvals)
        for d in dirs:
            cv[d] = arb(cb[d].mid())
        try:
            models = _Models(SimpleNamespace(**cv), cb, dirs, guesses)
        except DegenerateSpectrum:
            return None, "split"
        guess = out.theta_c
        for g, d in zip(out.theta_gradient, dirs):
            guess = guess + arb(g.mid()) * (cv[d] - cvals[d])
        tc = _centre_root(models, arb(guess.mid()))
        if tc is None or not Theta.contains(tc):
            return None, "stop"
        res, _ = _theta_over_box(models, tc)
        for n in SUBBOX_CELLS[:1]:           # a cell is narrow: the first count suffices or a finer cell
            if res is not None:
                break
            res, _ = _theta_over_box(models, tc, n, lambda c, b: _Models(c, b, dirs, guesses))
        if res is None or not Theta.contains(res[0]):    # a finer cell narrows its root's enclosure
            return None, "split"
        o = OrbitOverBox(theta_c=tc)
        o.theta, o.theta_gradient, th_c, th_n, o.theta_unique_in = res
        _decide(models, o, th_c, th_n, genuine, stability)
        if not o.genuine:
            return None, "split"
        return o, ("split" if stability and o.stable is not True else "")

    counts = split_counts(weights, CELL_COUNTS[0])
    # (cell, weights, genuine already proved on a cell containing it); the stack's cells and the decided
    # ones always cover the box
    stack = []
    for pc in grid([cells(box[d], counts[i]) for i, d in enumerate(dirs)]):
        stack.append(({d: cell for d, (cell, _) in zip(dirs, pc)}, [w / c for w, c in zip(weights, counts)], False))
    results = []
    reason = ""
    evaluated = 0
    first = len(stack)
    budget = MAX_CELLS if len(dirs) <= 2 else MAX_CELLS // 4    # a cell of a k-D box costs ~ (k + 1)^2
    while stack and evaluated < budget:
        if evaluated == first and not reason:
            return                  # no cell of the first grid is even genuine: finer cells are unlikely to be
        cb, wts, known = stack.pop(0)         # breadth first: every cell of the grid gets its turn
        evaluated += 1
        o, why = one_cell(cb)
        if why == "stop":
            return
        if o is not None and not reason:
            reason = o.genuine_reason
        if why == "":
            results.append(o)
            continue
        # bisect the cell along its heaviest direction (exact dyadic cut) and decide both halves
        i = max(range(len(dirs)), key=lambda j: wts[j])
        halves = wts[:i] + [wts[i] / 2] + wts[i + 1:]
        for half, _ in cells(cb[dirs[i]], 2):
            stack.append((dict(cb, **{dirs[i]: half}), halves, known or o is not None))
    if not all(known for _, _, known in stack) or not reason:
        return                      # some part of the box has no cell proved genuine
    out.genuine = True
    out.genuine_reason = (reason.split(", each for every")[0]
                          + f" (on the first parameter cell decided), each for every parameter in its cell, in "
                          f"{evaluated} cells covering the box (second-order forms in t and P about each cell's "
                          f"centre)")
    out.problem = ""
    if stability and not stack:
        mx = results[0].max_modulus
        for o in results[1:]:
            mx = mx.union(o.max_modulus)
        out.max_modulus = mx
        if all(len(o.moduli) == 4 for o in results):
            out.multipliers = [_union([o.multipliers[i] for o in results]) for i in range(4)]
            out.moduli = [_union([o.moduli[i] for o in results]) for i in range(4)]
            out.stable = all(certainly_lt(mm, 1) for mm in out.moduli)
        else:       # some cell bounded the spectral radius without isolating the multipliers (normed_orbit)
            out.multipliers, out.moduli = [], []
            out.stable = all(o.stable is True for o in results) and certainly_lt(mx, 1)
    if stability and out.stable is not True:
        out.problem = f"the multipliers were not decided in {evaluated} parameter cells"


def _union(balls):
    u = balls[0]
    for b in balls[1:]:
        u = u.union(b)
    return u
