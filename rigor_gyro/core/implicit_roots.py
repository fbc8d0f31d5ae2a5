"""A root of G(x, P) = 0 as a function of parameters P, over a set of parameters: its enclosure contracted by
interval Newton and its partial derivatives by the implicit function theorem, as a Dual
(:mod:`.dual_balls`) that parametric forms (:mod:`.centred_forms`) can use like any other formula.

Precondition (the caller's theorem, e.g. :func:`rigor_gyro.core.family_roots.family_real_roots` on a box
containing the set): for every P in the set, the root of interest x*(P) lies in the ball X, and G_x is
certainly nonzero on X times the set (so x*(P) is the only root in X).

Then, for every P in the set: x*(P) lies in N = m - G(m, P) / G_x(X, P) (the mean value theorem between m
and x*(P), both in X), so X intersected with N still contains it; repeated while it shrinks. By the implicit
function theorem x* is C^1 with dx*/dp_k = -G_p_k / G_x at (x*(P), P), so the ball -G_p_k(X, set) /
G_x(X, set) contains it. G(m, set) is enclosed in a centred form in the parameters (at the exact mid of each
parameter ball, with the parameter gradient of G at m over the set), intersected with the direct value.
Then (``centred``) X is narrowed to the root's own centred form x*(M) + sum_k (dx*/dp_k)(P_k - M_k), M the
parameter balls' exact mids (the mean value theorem for x* on the convex set of parameters: every x*(P)
stays in it), and the gradient is enclosed again on the narrower X, while it shrinks.

Guarantee: :func:`implicit_root` returns a Dual whose value contains x*(P) and whose gradient contains
dx*/dP for every P in the set, given the precondition; None when G_x is not certainly nonzero on X or
an image misses X (which, under the precondition, cannot happen unless the enclosures are too wide).
Precision: the current working precision. G must be written with Dual-safe operations.
"""
from __future__ import annotations

from typing import Callable

from flint import arb

from .balls import certainly_nonzero
from .dual_balls import Dual, NotDifferentiable, constant, gradient_finite

__all__ = ["implicit_root", "dual_family", "parametric_newton", "polynomial_root_over_box", "ROOT"]

#: the gradient key of the unknown x inside G (never a parameter name)
ROOT = "__root__"


def _value_at(G: Callable, m: arb, params: dict) -> arb | None:
    D = G(constant(m), params)
    if not gradient_finite(D):
        return None
    v = D.value
    wide = {k: p for k, p in params.items() if p.grad}
    # the centred form needs each varying parameter to be a variable (gradient {k: 1}); constants stay as given
    if wide and all(set(p.grad) == {k} for k, p in wide.items()):
        mids = {k: (constant(arb(p.value.mid())) if k in wide else p) for k, p in params.items()}
        c = G(constant(m), mids).value
        for k, p in wide.items():
            g = D.grad.get(k)
            if g is not None:
                c = c + g * (p.value - arb(p.value.mid()))
        if c.is_finite():
            v = v.intersection(c) if v.overlaps(c) else c
    return v


def implicit_root(G: Callable[[Dual, dict], Dual], X: arb, params: dict, steps: int = 12,
                  centred: bool = True) -> Dual | None:
    """The root of G(., P) in X as a Dual over the parameter Duals ``params`` (see the module docstring)."""
    try:
        for _ in range(steps):
            m = arb(X.mid())
            gm = _value_at(G, m, params)
            gx = G(Dual(X, {ROOT: arb(1)}), params).grad.get(ROOT)
            if gm is None or gx is None or not certainly_nonzero(gx):
                return None
            n = m - gm / gx
            if not n.is_finite() or not n.overlaps(X):
                return None
            n = n.intersection(X)
            shrunk = n.rad() < 0.9 * X.rad()
            X = n
            if not shrunk:
                break
        D = G(Dual(X, {ROOT: arb(1)}), params)
    except NotDifferentiable:
        return None
    gx = D.grad.get(ROOT)
    if gx is None or not certainly_nonzero(gx) or not gradient_finite(D):
        return None
    out = Dual(X, {k: -v / gx for k, v in D.grad.items() if k != ROOT})
    return _centred(G, out, params, steps) if centred else out


def _centred(G, root: Dual, params: dict, steps: int) -> Dual:
    """The root's own centred form: x*(P) in x*(M) + sum_k dx*/dp_k (P_k - M_k) with M the exact mids of the
    parameter balls (x*(M) by the point Newton above, inside the same X); X shrinks to that, the gradient is
    enclosed again on the narrower X, while X shrinks by a tenth."""
    wide = {k: p for k, p in params.items() if p.grad}
    if not wide or not all(set(p.grad) == {k} for k, p in wide.items()):
        return root
    mids = {k: (constant(arb(p.value.mid())) if k in wide else p) for k, p in params.items()}
    x0 = implicit_root(G, root.value, mids, steps, centred=False)
    if x0 is None:
        return root
    for _ in range(4):
        c = x0.value
        for k, p in wide.items():
            g = root.grad.get(k)
            if g is not None:
                c = c + g * (p.value - arb(p.value.mid()))
        X = root.value
        if not c.is_finite() or not c.overlaps(X):
            return root
        n = c.intersection(X)
        if not n.rad() < 0.9 * X.rad():
            return root
        try:
            D = G(Dual(n, {ROOT: arb(1)}), params)
        except NotDifferentiable:
            return root
        gx = D.grad.get(ROOT)
        if gx is None or not certainly_nonzero(gx) or not gradient_finite(D):
            return root
        root = Dual(n, {k: -v / gx for k, v in D.grad.items() if k != ROOT})
    return root


def dual_family(G: Callable[[Dual, dict], Dual], params: dict):
    """The family {G(., P) : P in the set} as :data:`rigor_gyro.core.family_roots.Family` (x -> (value,
    derivative)), for :func:`~rigor_gyro.core.family_roots.family_real_roots`: the value at x in centred form
    in the parameters intersected with the direct one, the derivative in x by AD over x and the set (a
    non-finite pair where it cannot enclose, which the Newton test rejects)."""
    nan = arb("nan")

    def family(x: arb) -> tuple[arb, arb]:
        try:
            v = _value_at(G, x, params)
            d = G(Dual(x, {ROOT: arb(1)}), params).grad.get(ROOT)
        except NotDifferentiable:
            return nan, nan
        return (nan if v is None else v), (nan if d is None else d)
    return family


def parametric_newton(G: Callable[[Dual, dict], Dual], guess: arb, params: dict, rounds: int = 8) -> arb | None:
    """A ball Y containing exactly one root of G(., P) for every P in the set, verified by an interval Newton
    test around a linear predictor (a first-order Taylor model of the root in the parameters), or None.

    Let x0 be the verified root at the parameter balls' exact mids M (point interval Newton from ``guess``,
    :func:`rigor_gyro.core.family_roots.newton_family_root`), g_k its partial derivatives there (implicit
    function theorem at M), and m(P) = x0 + sum_k g_k (P_k - M_k) (x0, g_k: fixed numbers inside their balls).
    h(P) = G(m(P), P) is second order in the set's width; it is enclosed in centred form. With Y = m(set) +-
    rho and D containing G_x on Y times the set, certainly nonzero: if r = sup|h| / min|D| < rho, then for each
    P the Newton image of [m(P) - rho, m(P) + rho] lies inside it, so G(., P) has exactly one root there, in
    m(P) +- r; G_x != 0 on Y makes it the only root in Y. Returned: m(set) +- r (contained in Y). rho is inflated
    from the first r. Only the variables of ``params`` vary (each a Dual with gradient {name: 1})."""
    from .family_roots import newton_family_root
    wide = {k: p for k, p in params.items() if p.grad}
    if not all(set(p.grad) == {k} for k, p in wide.items()):
        return None
    mid_of = {k: arb(p.value.mid()) for k, p in wide.items()}
    mids = {k: (constant(mid_of[k]) if k in wide else p) for k, p in params.items()}
    x0 = newton_family_root(dual_family(G, mids), guess)
    if x0 is None or not wide:
        return x0
    try:
        at_mid = {k: (Dual(mid_of[k], {k: arb(1)}) if k in wide else p) for k, p in params.items()}
        D0 = G(Dual(x0, {ROOT: arb(1)}), at_mid)
        gx0 = D0.grad.get(ROOT)
        if gx0 is None or not certainly_nonzero(gx0):
            return None
        g = {k: -D0.grad.get(k, arb(0)) / gx0 for k in wide}
        m = constant(x0)
        for k in wide:
            m = m + constant(g[k]) * (params[k] - constant(mid_of[k]))
        H = G(m, params)
        h = H.value
        c = G(constant(x0), mids).value
        for k in wide:
            if k in H.grad:
                c = c + H.grad[k] * (wide[k].value - mid_of[k])
        if c.is_finite():
            h = h.intersection(c) if h.overlaps(c) else c
        if not h.is_finite():
            return None
        hmax = abs(h).upper()
        centre = m.value
        rho = None
        for _ in range(rounds):
            if rho is None:
                y = centre
            else:
                y = centre + arb(0, rho)
            d = G(Dual(y, {ROOT: arb(1)}), params).grad.get(ROOT)
            if d is None or not d.is_finite() or not certainly_nonzero(d):
                return None
            mig = d.lower() if d > 0 else -d.upper()
            r = (hmax / mig).upper()
            if rho is not None and r < rho:
                return centre + arb(0, r)
            rho = (2 * r + abs(centre).upper() * arb(2) ** -60 + arb(2) ** -1000).upper()
    except NotDifferentiable:
        return None
    return None


def polynomial_root_over_box(coefficients: list, centre_coefficients: list, centre_root, deviations: list,
                             is_real: bool, rounds: int = 8):
    """A ball (``is_real``: an arb on the real line) or complex box (an acb) containing, for every member of a
    polynomial family C(z; P) = sum_i c_i(P) z^i over a parameter box, the root that continues the centre's root
    (unique near the linear predictor, see below), by an interval Newton test around a linear predictor (the
    parametric Newton of :func:`parametric_newton`, for jets and complex roots); None when not verified.

    ``coefficients``: first-order :class:`rigor_gyro.core.jets.Jet` s of c_i over the box (value balls containing
    c_i(P), gradients containing dc_i/dP_k, for every P in the box), constant term first, leading one last;
    ``centre_coefficients``: balls containing c_i(c) at the centre point c; ``centre_root``: a ball / box near
    the root z*(c) of C(.; c) to follow (its midpoint starts the predictor); ``deviations``: balls containing P_k - c_k.

    Theorem (member by member). z0 = the exact midpoint of ``centre_root``, g_k exact points (midpoints of
    -C_Pk(z0) / C'(z0) over the box: only a predictor), m(P) = z0 + sum_k g_k (P_k - c_k). By the mean value
    theorem in P along the segment from c (jets' gradients over the box), h(P) = C(m(P); P) lies in
    C(z0; c) + sum_k (dh/dP_k)(box) (P_k - c_k), C(z0; c) evaluated on the centre's coefficient balls
    (nothing is assumed of ``centre_root``). For u in U = [-rho, rho] (on the line, or that square in the plane),
    D contains C'(m(P) + u; P) for every P and u, in the same centred form in P (U a ball); D certainly does not
    contain 0, and r = sup |h| / inf |D|. If r < rho: for each P, the interval Newton image of Y_P = m(P) + U lies
    in m(P) + [-r, r] (that disc in the plane), inside Y_P, so C(.; P) has a root in Y_P, in m(P) + [-r, r] (the
    one-dimensional theorem; in the plane through C(y) - C(m) = (y - m) int_0^1 C'(m + t (y - m)) dt, the integral
    in the convex box D, and Brouwer), and it is C(.; P)'s only root in Y_P: on the line C' has one sign there; in
    the plane the convex box D excludes 0, so it lies in an open half plane and C is injective on the convex Y_P
    (Noshiro-Warschawski). Returned: m(box) + [-r, r], containing that root of every member (a caller that needs
    all the roots takes enclosures that are pairwise disjoint, one per root). Precision: the current working
    precision. Fails when: D may contain 0, a ball is not finite, or r does not fall below rho in ``rounds``
    inflations: None."""
    from flint import acb

    from .jets import Jet

    m = len(deviations)
    z0 = acb(centre_root.real.mid(), centre_root.imag.mid()) if isinstance(centre_root, acb) else acb(centre_root.mid())
    n = len(coefficients) - 1

    def poly(cs, z):
        out = cs[n]
        for i in range(n - 1, -1, -1):
            out = out * z + cs[i]
        return out

    def dpoly(cs, z):
        out = cs[n] * n
        for i in range(n - 1, 0, -1):
            out = out * z + cs[i] * i
        return out

    def centred(jet, at_centre):
        """at_centre + sum_k jet.d[k] dev_k, intersected with the jet's direct value (both contain it)."""
        out = at_centre
        for k in range(m):
            out = out + jet.d[k] * deviations[k]
        v = jet.v
        if v.is_finite() and out.is_finite():
            if not (v.real.overlaps(out.real) and v.imag.overlaps(out.imag)):
                raise AssertionError(f"a centred form {out} misses its direct enclosure {v}: a bug")
            return acb(out.real.intersection(v.real), out.imag.intersection(v.imag))
        return out if out.is_finite() else v

    vals = [c.v for c in coefficients]
    d0 = dpoly(vals, z0)
    if d0.contains(0) or not d0.is_finite():
        return None
    slope = []
    for k in range(m):
        s = -poly([c.d[k] for c in coefficients], z0) / d0
        if not s.is_finite():
            return None
        slope.append(acb(s.real.mid()) if is_real else acb(s.real.mid(), s.imag.mid()))
    pred_value = z0
    for s, dev in zip(slope, deviations):
        pred_value = pred_value + s * dev
    h = centred(poly(coefficients, Jet(pred_value, slope)), poly(centre_coefficients, z0))
    if is_real:
        h = acb(h.real)
    if not h.is_finite():
        return None
    hmax = abs(h).upper()
    rho = None
    for _ in range(rounds):
        U = acb(0) if rho is None else (acb(arb(0, rho)) if is_real else acb(arb(0, rho), arb(0, rho)))
        D = centred(dpoly(coefficients, Jet(pred_value + U, slope)), dpoly(centre_coefficients, z0 + U))
        if is_real:
            D = acb(D.real)
        if D.contains(0) or not D.is_finite():
            return None
        mig = _mignitude(D)
        if not mig > 0:
            return None
        r = (hmax / mig).upper()
        if rho is not None and r < rho:
            out = pred_value + (acb(arb(0, r)) if is_real else acb(arb(0, r), arb(0, r)))
            return out.real if is_real else out
        rho = (2 * r + abs(pred_value).upper() * arb(2) ** -60 + arb(2) ** -1000).upper()
    return None


def _mignitude(D) -> arb:
    """A lower bound of |d| over the complex box D (0 if D may contain 0): the distance from 0 to the box."""
    re, im = D.real, D.imag
    dx = arb(0) if re.contains(0) else (re.lower() if re > 0 else -re.upper())
    dy = arb(0) if im.contains(0) else (im.lower() if im > 0 else -im.upper())
    out = (arb(dx) * dx + arb(dy) * dy).sqrt()
    return arb(out.lower())
