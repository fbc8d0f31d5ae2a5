"""Claims of the eigenfrequency kind over a box of parameters (tolerances): the parametric rigour that
the margins layer (:mod:`rigor_gyro.margins`) paves with.

For a box of (a, b, eps, Omega2) every parameter becomes a ball containing its interval. The quartic's
coefficients are then balls containing the coefficients of every member of the family, and
:func:`rigor_gyro.core.family_roots.family_real_roots` encloses its four roots by one interval Newton
proof for all members at once (the midpoint's exact roots are only the starting guesses). The nus of
(4) are enclosed the same way from the two quadratics; nu3, nu5, the bounds (5) and the brackets are
the model's formulas evaluated on the balls. At Newton's exact points the quartic's and the quadratics'
values are also enclosed in a centred (mean-value) form in the parameters, second order in the box
width, intersected with the direct enclosure. Where that one Newton step fails (a wide box), each root is
verified around its linear predictor (:func:`rigor_gyro.core.implicit_roots.parametric_newton`). Where both
fail or leave a root ball reaching 0 (small Omega2: omega_3, omega_4 move like sqrt(Omega2) across a
turning point of Q, omega_1 like Omega2/(a b) down to 0), each root is bracketed by a sign change
(:func:`_sign_change_roots`): Q is affine in (a, eps, Omega2), so its sign at an exact omega is certain on
the box when it is at the corners, and Q = h (Omega2 - F) with F = Omega2 of (2) strictly monotone on the
bracket (its numerator's sign certain, quadratic in eps and interpolated exactly) gives at most one root.
The roots cannot be separated by box-wide balls where their ranges overlap (eps -> 0 with a wide eps edge:
omega_1 ~ nu1 and omega_2 ~ nu2 both scale with eps); such boxes stay undecided and the paving splits them.

Where the direct evaluation leaves a claim undecided, the claim is read as its sign conditions (gaps:
omega_j - lower_j and upper_j - omega_j for a bracket, nu_{k+1} - nu_k for the ordering, the branch and
bound gaps; :mod:`.slack_forms`), each a function of the parameters with the roots as implicit functions,
and each decided by :func:`rigor_gyro.core.centred_forms.sign_over_box`: its centred form (derivatives by
forward-mode AD in balls), and where its derivative has a certain sign in a parameter, its minimum (or
maximum) on that face, exactly at a corner when every parameter is monotone; the reason says which.

Guarantee: ``proved`` for a claim means the claim holds for every parameter value in the box;
``refuted`` means it fails for every value in the box (a certified strict violation over the whole
box); ``undecided`` says neither was certified at this box size (the paving splits the box). The
``roots`` claim over a box is "four real positive simple roots for every value", without the relative
width of the point claim (a box's roots are as wide as the box makes them).

Precision: the caller's working precision (the paving fixes it); box width, not precision, dominates.

Fails when: a box violates the domain somewhere (b > 1, a > b, eps > 0, Omega2 > 0 must hold at every
point of the box, checked exactly on the box's corners, which suffices because each condition is
monotone in each parameter), or ``hz_scale`` is given as an interval: ParameterError (exit 2).
"""
from __future__ import annotations

import functools
from fractions import Fraction

from flint import arb, arb_poly, fmpq

from ...core.balls import (certainly_ge, certainly_gt, certainly_le, certainly_lt, certainly_nonzero,
                           certainly_positive)
from ...core.boxes import Box
from ...core.centred_forms import sign_over_box
from ...core.dual_balls import constant, variable
from ...core.implicit_roots import parametric_newton
from ...core.errors import ParameterError
from ...core.family_roots import family_real_roots
from ...core.polyroots import isolate_polynomial
from .. import require_box_claims
from .model import NotReal, Params, bracket, characteristic_quartic, nu_bounds, nu_quadratics
from .claims import CLAIMS, REQUIRED
from .system_boxes import SYSTEM_BOX_CLAIMS, evaluate_system_box, validate_system_box
from .system_model import SystemModel
from .slack_forms import GapSet, Roots, nu_value, quartic_value
from .second_order import gap_sign

__all__ = ["BOX_CLAIMS", "BOX_PARAMETERS", "box_claims", "validate_box", "evaluate_box", "box_roots"]

#: the claims decidable over a box, with what each states at every point of it (approximations: their
#: errors are quantities, not statements; roots: without the point claim's relative width)
BOX_CLAIMS = {
    "roots": "The characteristic quartic in omega has exactly four roots, all real, positive and simple.",
    **{c: CLAIMS[c] for c in ("nu_ordering", "branches", "nu_bounds", "bracket_1", "bracket_2", "bracket_3",
                              "bracket_4")},
}
#: the parameters that may be written as tolerances
BOX_PARAMETERS = ("a", "b", "eps", "Omega2")


def box_claims(model) -> dict[str, str]:
    """The claims this model decides over a box, with their statements: :data:`BOX_CLAIMS`, or for a
    ``[system]`` model :data:`.system_boxes.SYSTEM_BOX_CLAIMS` (a hook for the margins layer; not wired yet)."""
    return dict(SYSTEM_BOX_CLAIMS) if isinstance(model, SystemModel) else dict(BOX_CLAIMS)


def validate_box(model, box: Box) -> None:
    """The domain at every point of the box: b > 1, a > b, eps > 0, Omega2 > 0 (exact, on corners); a
    ``[system]`` model: :func:`.system_boxes.validate_system_box`."""
    if isinstance(model, SystemModel):
        return validate_system_box(model, box)
    bad = [n for n in box.names if n not in BOX_PARAMETERS]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: kind 'eigenfrequencies' takes a tolerance only for "
                             f"{list(BOX_PARAMETERS)}; write {bad[0]!r} as a single number")
    lo, hi = _range(model, box)
    if not lo["b"] > 1:
        raise ParameterError(f"parameter 'b': need b > 1 on the whole box (its lower end is {lo['b']})")
    if not lo["a"] > hi["b"]:
        raise ParameterError(f"parameter 'a': need a > b on the whole box (min a = {lo['a']} <= max b = {hi['b']})")
    if not lo["eps"] > 0:
        raise ParameterError(f"parameter 'eps': need eps > 0 on the whole box (its lower end is {lo['eps']})")
    if not lo["Omega2"] > 0:
        raise ParameterError(f"parameter 'Omega2': need Omega2 > 0 on the whole box (its lower end is {lo['Omega2']})")


def _range(model, box: Box) -> tuple[dict[str, Fraction], dict[str, Fraction]]:
    lo, hi = {}, {}
    for k in REQUIRED:
        if k in box.names:
            lo[k], hi[k] = box.interval(k)
        else:
            lo[k] = hi[k] = getattr(model, k).rational
    return lo, hi


def _balls(model, box: Box) -> Params:
    return Params(*(box.ball(k) if k in box.names else arb(model.q(k)) for k in REQUIRED))


def _midpoint(model, box: Box) -> list[fmpq]:
    mid = box.midpoint()
    return [fmpq(mid[k].numerator, mid[k].denominator) if k in mid else model.q(k) for k in REQUIRED]


def _dual_params(model, box: Box) -> dict:
    """{a, b, eps, Omega2} as Duals: variables over the box's edges, constants elsewhere (in this order)."""
    def one(k):
        if k not in box.names:
            return constant(arb(model.q(k)))
        lo, hi = box.interval(k)
        return variable(k, box.ball(k)) if hi > lo else constant(box.ball(k))
    return {k: one(k) for k in REQUIRED}


def _parametric_roots(G, guesses: list[arb], dp: dict, leading: arb) -> list[arb] | None:
    """Where one interval Newton step for the whole family fails (a wide box), each root verified around its
    linear predictor (:func:`rigor_gyro.core.implicit_roots.parametric_newton`): balls each holding exactly
    one root of every member; all the roots when there are as many as the degree (the caller's guesses are
    the midpoint's roots, all of them), the leading coefficient certainly nonzero, disjoint and certainly
    increasing (the labels); None otherwise."""
    if not certainly_nonzero(leading):
        return None
    out = []
    for g in guesses:
        r = parametric_newton(G, g, dp)
        if r is None:
            return None
        out.append(r)
    if any(not certainly_lt(out[i], out[i + 1]) for i in range(len(out) - 1)):
        return None
    return out


#: the parameters in which the quartic Q(omega) (and each nu quadratic of (4)) is affine, the others fixed:
#: every coefficient of P1, P2 has degree <= 1 in each of a, eps, and Omega2 multiplies P2 once (checked
#: symbolically in tests/test_eig_box_cluster.py); so for a fixed omega and b its extremes over a box are
#: at the corners of (a, eps, Omega2)
AFFINE_IN = ("a", "eps", "Omega2")


def _affine_corners(model, box: Box) -> list[Params]:
    """Parameter balls at the corners of the box in :data:`AFFINE_IN` (exact), b as its ball over the box."""
    pts: list[list[arb]] = [[]]
    for k in REQUIRED:
        if k in box.names and k in AFFINE_IN:
            lo, hi = box.interval(k)
            vals = [arb(fmpq(v.numerator, v.denominator)) for v in ((lo,) if hi == lo else (lo, hi))]
        else:
            vals = [box.ball(k) if k in box.names else arb(model.q(k))]
        pts = [q + [v] for q in pts for v in vals]
    return [Params(*q) for q in pts]


#: the widenings tried for a root's proposal hull (shares of its width), narrowest first
PADS = (fmpq(1, 64), fmpq(1, 8))


def _one_sign(vals: list[arb]) -> int:
    """+1 / -1 when every ball is certainly of that sign, else 0."""
    if all(v > 0 for v in vals):
        return 1
    if all(v < 0 for v in vals):
        return -1
    return 0


def _sign_change_roots(families: list, leading: arb, proposals: list[list[arb]],
                       max_pieces: int = 64, ratio=None) -> list[arb] | None:
    """Root balls by a sign change and monotonicity, where the family Newton test fails because the roots
    move across their balls by more than their distance to a neighbour (the cluster omega_3, omega_4 at small
    Omega2 and eps, where they go like sqrt(Omega2); omega_1 ~ Omega2 / (a b) near 0, whose ball from
    Newton's inflation reached below 0).

    ``families``: the family (x -> (value, derivative)) at each corner of :data:`AFFINE_IN` (b a ball): the
    function is affine in those parameters at fixed omega, so a sign certain at every corner is certain on the
    whole box. ``proposals``: the roots at a few exact points of the box (only proposals). For root j the
    candidate [L, U] is the hull of the proposals' j-th roots widened by an eighth of its width (L kept
    above half the least proposal when that is positive). It holds exactly one root of every member when
    the values at the exact points L and U have certain opposite signs at every corner and the derivative
    has one certain sign on each of up to ``max_pieces`` equal pieces of [L, U] at every corner (Taylor form
    in omega): every member strictly monotone there; or F = Omega2 of (2) is (``ratio``, :func:`_monotone`). The balls must be certainly increasing; with as many as
    the degree and the leading coefficient certainly nonzero they are all the roots, each simple. None when
    a test is not certain (a proposal hull that misses an interior extreme fails the end test: never
    unsound)."""
    if not certainly_nonzero(leading) or not proposals or not families:
        return None
    n = len(proposals[0])
    if any(len(r) != n for r in proposals):
        return None
    out = []
    for j in range(n):
        lo = min((r[j].mid() for r in proposals), key=float)       # floats pick; the tests below decide
        hi = max((r[j].mid() for r in proposals), key=float)
        got = None
        for share in PADS:           # a narrow pad first: a wide one may reach a neighbour's turning point
            pad = (hi - lo) * share + abs(hi) * arb(2) ** -40
            L, U = arb((lo - pad).mid()), arb((hi + pad).mid())
            if certainly_positive(lo) and not certainly_positive(L):
                L = arb((lo / 2).mid())
            if not certainly_lt(L, U):
                continue
            sl, su = _one_sign([f(L)[0] for f in families]), _one_sign([f(U)[0] for f in families])
            if sl != 0 and su == -sl and _monotone(families, L, U, max_pieces, ratio):
                got = L.union(U)
                break
        if got is None:
            return None
        out.append(got)
    if any(not certainly_lt(out[i], out[i + 1]) for i in range(n - 1)):
        return None
    return out


def _monotone(families: list, L: arb, U: arb, max_pieces: int, ratio=None) -> bool:
    """Every member has at most one root in [L, U], on 1, 2, 4, ... equal pieces (exact ends) until decided or
    ``max_pieces`` is passed: the derivative has one certain sign on every piece at every corner family
    (strictly monotone), or, with ``ratio`` (x -> (h, N) over the box: Q = W h - g, N = g' h - g h'), h and N
    each of one certain sign on all of [L, U]: then Q = h (W - F) with F = g/h strictly monotone, so Q has at
    most one zero there for every Omega2 (this holds where Q itself is not monotone for every member: the
    cluster omega_3, omega_4, whose turning point moves with Omega2 through the hull of a root)."""
    k = 1
    while k <= max_pieces:
        ends = [arb((L + (U - L) * i / k).mid()) if 0 < i < k else (L if i == 0 else U) for i in range(k + 1)]
        pieces = [ends[i].union(ends[i + 1]) for i in range(k)]
        if _one_sign([f(y)[1] for y in pieces for f in families]) != 0:
            return True
        if ratio is not None:
            hn = [ratio(y) for y in pieces]
            if _one_sign([h for h, _ in hn]) != 0 and _one_sign([n for _, n in hn]) != 0:
                return True
        k *= 2
    return False


def _quartic_ratio(p: Params):
    """x -> (h(x), N(x)) over the box, each in Taylor form about the ball's centre: Q(x) = W h(x) - g(x) with
    g(x) = x P1(-x), h(x) = P2(-x) (so Omega2 = F(x) = g/h at a root), N = g' h - g h' (the numerator of F').
    Neither depends on Omega2. N is quadratic in eps: it is built exactly at the three points em - d, em,
    em + d (em, d the exact centre and radius of the eps ball) and enclosed as N(em) + t N_1 + t^2 N_2,
    t in [-d, d] (the interpolation is exact for a quadratic; the eps dependence across N's coefficients,
    which a direct evaluation loses, is kept)."""
    a, b, e, _ = p
    l = arb_poly([0, -1])                                   # lambda^2 = -x

    def parts(e):
        p1 = (l * (b - 1) + b) * (l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + b * (a - b)) + e * a)
        h = (l * (b - 1) + 1) * (l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + a - b) + e)
        g = arb_poly([0, 1]) * p1
        return h, g.derivative() * h - g * h.derivative()
    h, _ = parts(e)
    em, d = arb(e.mid()), arb(e.rad())
    _, Nm = parts(em)
    if d.is_zero():
        return lambda x: (_taylor_at(h, x), _taylor_at(Nm, x))
    _, Nn = parts(em - d)
    _, Np = parts(em + d)
    N1 = (Np - Nn) * (1 / (2 * d))
    N2 = (Np - 2 * Nm + Nn) * (1 / (2 * d * d))
    t = arb(0, d)
    t2 = (d * d).union(arb(0))

    def ratio(x):
        return _taylor_at(h, x), _taylor_at(Nm, x) + t * _taylor_at(N1, x) + t2 * _taylor_at(N2, x)
    return ratio


def _proposals(model, box: Box, poly_at) -> list[list[arb]]:
    """The real roots of ``poly_at(point)`` at the box's corners and midpoint (exact points), for
    :func:`_sign_change_roots`; points whose roots are not isolated are left out."""
    pts: list[list[fmpq]] = [[]]
    for k in REQUIRED:
        if k in box.names:
            lo, hi = box.interval(k)
            vals = [fmpq(v.numerator, v.denominator) for v in ((lo,) if hi == lo else (lo, hi))]
        else:
            vals = [model.q(k)]
        pts = [q + [v] for q in pts for v in vals]
    out = []
    for pt in pts + [_midpoint(model, box)]:
        g = _guesses(poly_at(*pt))
        if g is not None:
            out.append(g)
    return out


def _quartic_family(p: Params):
    """Q(omega) = -omega P1(-omega) + Omega2 P2(-omega) over the box, as a family (value, derivative):
    P1 and P2 have ball coefficients (a, b, eps) and Omega2 multiplies P2 once, so the enclosure keeps
    Q's linear dependence on Omega2 (coefficient by coefficient it would not: much wider). Also the
    leading coefficient (b-1)^2 (a-b) of Q."""
    a, b, e, W = p
    l = arb_poly([0, 1])
    p1 = (l * (b - 1) + b) * (l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + b * (a - b)) + e * a)
    p2 = (l * (b - 1) + 1) * (l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + a - b) + e)
    d1, d2 = p1.derivative(), p2.derivative()

    # the centred form in the parameters: at the box's midpoint p0 (exact) plus the parameter gradient
    # over the box times (P - p0); second order in the box width where the direct form is first order
    mids = [arb(t.mid()) for t in (a, b, e, W)]
    offsets = [t - m for t, m in zip((a, b, e, W), mids)]
    am, bm, em, Wm = mids
    p1m = (l * (bm - 1) + bm) * (l * l * ((am - bm) * (bm - 1)) + l * (em * (am - 1) + bm * (am - bm)) + em * am)
    p2m = (l * (bm - 1) + 1) * (l * l * ((am - bm) * (bm - 1)) + l * (em * (am - 1) + am - bm) + em)
    q1 = l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + b * (a - b)) + e * a
    q2 = l * l * ((a - b) * (b - 1)) + l * (e * (a - 1) + a - b) + e
    u1, u2 = l * (b - 1) + b, l * (b - 1) + 1
    grads = [   # d/da, d/db, d/deps of P1 and P2 over the box, and d/dOmega2 of the value (P2)
        (u1 * (l * l * (b - 1) + l * (e + b) + e), u2 * (l * l * (b - 1) + l * (e + 1))),
        ((l + 1) * q1 + u1 * (l * l * (a - 2 * b + 1) + l * (a - 2 * b)), l * q2 + u2 * (l * l * (a - 2 * b + 1) - l)),
        (u1 * (l * (a - 1) + a), u2 * (l * (a - 1) + 1)),
    ]
    centred = any(not o.rad().is_zero() for o in offsets)

    def family(x: arb) -> tuple[arb, arb]:
        lam = -x                               # lambda^2 = -omega
        value = lam * p1(lam) + W * p2(lam)
        if centred and x.rad().is_zero():
            mv = lam * p1m(lam) + Wm * p2m(lam) + p2(lam) * offsets[3]
            for (g1, g2), o in zip(grads, offsets[:3]):
                if not o.rad().is_zero():
                    mv += (lam * g1(lam) + W * g2(lam)) * o
            if mv.is_finite():
                value = value.intersection(mv) if value.overlaps(mv) else mv
        deriv = -(p1(lam) + lam * d1(lam)) - W * d2(lam)
        if not x.rad().is_zero():
            # Q' in Taylor form about the ball's exact centre (issue 37: near the cluster omega_3, omega_4 at
            # small Omega2 and eps, Horner on a wide ball loses the cancellation and the derivative's
            # enclosure meets 0 although every member's Q' is bounded away from 0 there)
            dt = _taylor_at(dq1, lam) + W * _taylor_at(d2, lam)
            if dt.is_finite():
                deriv = deriv.intersection(-dt) if deriv.overlaps(-dt) else -dt
        return value, deriv
    dq1 = (l * p1).derivative()
    return family, (b - 1) * (b - 1) * (a - b)


def _taylor_at(poly: arb_poly, x: arb) -> arb:
    """poly over the ball x by its Taylor expansion about x's exact centre: poly(c + t) expanded in t (ball
    coefficients, exact composition) and evaluated at t in [-r, r]. Contains poly(x) for every point of x; much
    narrower than Horner on x where poly's terms cancel."""
    c = arb(x.mid())
    shifted = poly(arb_poly([c, 1]))
    return shifted(arb(0, x.rad()))


def _nu_family(p: Params, which: str):
    """The quadratic of (4) whose roots are nu1, nu4 (``which`` = "14") or nu2, nu6 ("26") over the box,
    as a family (value, derivative) whose value at an exact point is also enclosed in a centred form in
    (a, b, eps) (second order in the box width), intersected with the direct one."""
    a, b, e, _ = p
    mids = [arb(t.mid()) for t in (a, b, e)]
    offs = [t - m for t, m in zip((a, b, e), mids)]

    def coefs(a, b, e):
        c2 = (a - b) * (b - 1)
        if which == "14":
            return [e, -(e * (a - 1) + a - b), c2]
        return [e * a, -(e * (a - 1) + b * (a - b)), c2]

    def grads(x):          # d/da, d/db, d/deps of the value at x, over the box
        if which == "14":
            return [-(e + 1) * x + (b - 1) * x * x, x + (a - 2 * b + 1) * x * x, 1 - (a - 1) * x]
        return [e - (e + b) * x + (b - 1) * x * x, -(a - 2 * b) * x + (a - 2 * b + 1) * x * x, a - (a - 1) * x]
    c = coefs(a, b, e)
    cm = coefs(*mids)
    P, Pm = arb_poly(c), arb_poly(cm)
    dP = P.derivative()
    centred = any(not o.rad().is_zero() for o in offs)

    def family(x: arb) -> tuple[arb, arb]:
        value = P(x)
        if centred and x.rad().is_zero():
            mv = Pm(x) + sum((g * o for g, o in zip(grads(x), offs) if not o.rad().is_zero()), arb(0))
            if mv.is_finite():
                value = value.intersection(mv) if value.overlaps(mv) else mv
        return value, dP(x)
    return family, c[2]


def _guesses(poly) -> list[arb] | None:
    pr = isolate_polynomial(poly)
    return pr.real if pr.verified and not pr.nonreal else None


def box_roots(model, box: Box, omegas: bool = True, nus: bool = True) -> tuple[Roots, Params]:
    """The whole box's root balls (``Roots``; each ball holds exactly one root of every member, verified by
    one family interval Newton proof: :func:`rigor_gyro.core.family_roots.family_real_roots`, the family's
    value in centred form; where that fails, each root around its linear predictor, :func:`_parametric_roots`;
    the four omegas certainly positive) and the parameter balls. The midpoint's exact roots are only the
    starting guesses."""
    p = _balls(model, box)
    a, b, e, W = _midpoint(model, box)
    dp = _dual_params(model, box)
    ws = None
    guesses = _guesses(characteristic_quartic(a, b, e, W)) if omegas else None
    if guesses is not None and len(guesses) == 4:
        fam, leading = _quartic_family(p)
        G = lambda x, q: quartic_value(x, Params(*(q[k] for k in REQUIRED)))
        ws = family_real_roots(fam, guesses, leading=leading)
        if ws is None:
            ws = _parametric_roots(G, guesses, dp, leading)
        if ws is None or not all(certainly_positive(w) for w in ws):
            corners = [_quartic_family(c)[0] for c in _affine_corners(model, box)]
            ws = _sign_change_roots(corners, leading, _proposals(model, box, characteristic_quartic),
                                    ratio=_quartic_ratio(p)) or ws
    if ws is not None and not all(certainly_positive(w) for w in ws):
        ws = None
    ns = None
    if nus:
        q14, q26 = nu_quadratics(a, b, e)
        g14, g26 = _guesses(q14), _guesses(q26)
        (f14, l14), (f26, l26) = _nu_family(p, "14"), _nu_family(p, "26")
        r14 = r26 = None
        if g14 is not None and len(g14) == 2:
            r14 = family_real_roots(f14, g14, leading=l14) or _parametric_roots(
                lambda x, q: nu_value("14", x, Params(*(q[k] for k in REQUIRED))), g14, dp, l14)
        if g26 is not None and len(g26) == 2:
            r26 = family_real_roots(f26, g26, leading=l26) or _parametric_roots(
                lambda x, q: nu_value("26", x, Params(*(q[k] for k in REQUIRED))), g26, dp, l26)
        if r14 is not None and r26 is not None:
            ns = {1: r14[0], 2: r26[0], 4: r14[1], 6: r26[1]}
    return Roots(ws, ns), p


def evaluate_box(model, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box; status is 'proved', 'refuted' or 'undecided' (see the
    module docstring for what each means); a ``[system]`` model: :func:`.system_boxes.evaluate_system_box`."""
    if isinstance(model, SystemModel):
        return evaluate_system_box(model, box, claims)
    require_box_claims(claims, BOX_CLAIMS)
    out: dict[str, tuple[str, str]] = {}
    need_roots = any(c in ("roots", "branches") or c.startswith("bracket_") for c in claims)
    need_nus = any(c in ("nu_ordering", "branches", "nu_bounds") for c in claims)
    roots, p = box_roots(model, box, need_roots, need_nus)
    omegas, roots_ok = roots.omegas, roots.omegas is not None
    nus = None
    if roots.nus is not None:
        nus = {**roots.nus, 3: 1 / (p.b - 1), 5: p.b / (p.b - 1)}
    gaps = GapSet(model, box, roots)
    for cid in claims:
        if cid == "roots":
            out[cid] = ("proved", "four disjoint positive root balls, each verified by one interval Newton step for "
                        "every parameter in the box (leading coefficient certainly nonzero)") if roots_ok else \
                ("undecided", "the family's roots were not separated on this box")
        elif cid == "nu_ordering":
            out[cid] = _parametric(_ordering(nus), nus is not None, gaps.ordering_gaps, box)
        elif cid == "branches":
            out[cid] = _parametric(_branches(omegas, nus), omegas is not None and nus is not None,
                                   gaps.branch_gaps, box)
        elif cid == "nu_bounds":
            out[cid] = _five_everywhere(model, box) or _parametric(_nu_bounds(p, nus), nus is not None,
                                                                   gaps.bound_gaps, box)
        elif cid.startswith("bracket_"):
            j = int(cid[-1])
            second = None
            if omegas is not None:
                second = lambda i, strict, j=j: gap_sign(model, box, j, ("lower", "upper")[i], omegas[j - 1], strict)
            out[cid] = _parametric(_bracket(j, p, omegas), omegas is not None, lambda j=j: gaps.bracket_gaps(j), box,
                                   second)
    return out


def _parametric(direct: tuple[str, str], enclosed: bool, gaps, box: Box, second=None) -> tuple[str, str]:
    """The direct verdict, or where it is undecided and the roots are enclosed, the verdict of the claim's
    gaps (each must be > 0, or >= 0) in centred form with monotone faces decided exactly
    (:func:`rigor_gyro.core.centred_forms.sign_over_box`), and where that is undecided, by ``second(i,
    strict)`` for the i-th gap when given (a bracket's second-order form, :func:`.second_order.gap_sign`):
    refuted when one gap is certainly negative on the whole box, proved when every gap is certainly positive
    (non-negative)."""
    if direct[0] != "undecided" or not enclosed:
        return direct
    hows, open_ = [], []
    for i, (label, f, strict) in enumerate(gaps()):
        st, how, _, _ = sign_over_box(f, box, strict)
        if st == "undecided" and second is not None:
            st, how = second(i, strict)
        if st == "negative":
            return "refuted", f"{label} < 0 for every parameter in the box: {how} (parametric form)"
        if st == "undecided":
            open_.append(label)
        else:
            hows.append(f"{label}: {how}")
    if open_:
        return "undecided", f"{', '.join(open_)} undecided on this box (direct and centred forms)"
    return "proved", "for every parameter in the box (parametric form): " + "; ".join(hows)


def _ordering(nus) -> tuple[str, str]:
    if nus is None:
        return "undecided", "the nu quadratics' roots were not separated on this box"
    chain = [arb(0)] + [nus[k] for k in range(1, 7)]
    names = ["0"] + [f"nu{k}" for k in range(1, 7)]
    bad = [f"{names[i]} >= {names[i + 1]}" for i in range(6) if certainly_ge(chain[i], chain[i + 1])]
    if bad:
        return "refuted", "for every parameter in the box: " + ", ".join(bad)
    if all(certainly_lt(chain[i], chain[i + 1]) for i in range(6)):
        return "proved", "0 < nu1 < ... < nu6 certified for every parameter in the box"
    return "undecided", "the nu balls overlap on this box"


def _branches(omegas, nus) -> tuple[str, str]:
    if omegas is None or nus is None:
        return "undecided", "needs the roots and the nus enclosed on this box"
    iv = [(arb(0), nus[1]), (nus[2], nus[3]), (nus[4], nus[5]), (nus[6], None)]
    fails, und = [], []
    for j, (w, (lo, hi)) in enumerate(zip(omegas, iv), start=1):
        if certainly_ge(lo, w) or (hi is not None and certainly_ge(w, hi)):
            fails.append(f"omega_{j}")
        elif not (certainly_lt(lo, w) and (hi is None or certainly_lt(w, hi))):
            und.append(f"omega_{j}")
    if fails:
        return "refuted", f"{', '.join(fails)} outside its branch for every parameter in the box"
    if und:
        return "undecided", f"{', '.join(und)} against its branch undecided on this box"
    return "proved", "each omega_j strictly inside its branch for every parameter in the box"


def _bounds_status(items) -> tuple[str, str]:
    fails = [label for label, lo, x, hi in items if certainly_gt(lo, x) or certainly_gt(x, hi)]
    if fails:
        return "refuted", f"{', '.join(fails)} outside its bounds for every parameter in the box"
    und = [label for label, lo, x, hi in items if not (certainly_le(lo, x) and certainly_le(x, hi))]
    if und:
        return "undecided", f"{', '.join(und)} against its bounds undecided on this box"
    return "proved", "every inequality certified for every parameter in the box"


def _five_everywhere(model, box: Box) -> tuple[str, str] | None:
    """``nu_bounds`` for the whole box at once, by the theorem that (5) holds for every a > b > 1, eps > 0
    (:func:`.paper_steps.five_identities`: exact polynomial identities over fmpq_mpoly, and the sign argument
    of that audit row): ("proved", reason) when the box's exact ends put every member in that region (a's
    lower end above b's upper end, b's lower end above 1, eps's lower end above 0) and every identity holds;
    None otherwise (the enclosures decide). Exact rational comparisons; no precision involved."""
    fixed = {k: Fraction(int(model.q(k).p), int(model.q(k).q)) for k in ("a", "b", "eps") if k not in box.names}
    end = {k: box.interval(k) if k in box.names else (fixed[k], fixed[k]) for k in ("a", "b", "eps")}
    if not (end["a"][0] > end["b"][1] and end["b"][0] > 1 and end["eps"][0] > 0):
        return None
    if not all(_five_identities_hold()):
        return None
    return ("proved", "for every a > b > 1, eps > 0 the bounds (5) hold (exact polynomial identities in (a, b, eps) "
                      "over fmpq_mpoly and signs of products of positive factors: the audit row '(5) for every "
                      "parameter'), and every member of the box lies there (exact ends: a >= "
                      f"{end['a'][0]} > {end['b'][1]} >= b, b >= {end['b'][0]} > 1, eps >= {end['eps'][0]} > 0)")


@functools.lru_cache(maxsize=1)
def _five_identities_hold() -> tuple[bool, ...]:
    """The identities of :func:`.paper_steps.five_identities`, checked once per process."""
    from .paper_steps import five_identities
    return tuple(five_identities().values())


def _nu_bounds(p: Params, nus) -> tuple[str, str]:
    if nus is None:
        return "undecided", "needs the nus enclosed on this box"
    bounds = nu_bounds(p)
    return _bounds_status([(f"nu{k}", bounds[k][0], nus[k], bounds[k][1]) for k in (1, 2, 4, 6)])


def _bracket(j: int, p: Params, omegas) -> tuple[str, str]:
    try:
        lo, hi = bracket(j, p, reading="intended")
    except NotReal as e:
        return "refuted", f"the bracket has no real value anywhere in the box: {e}"
    if omegas is None:
        return "undecided", "needs the roots enclosed on this box"
    return _bounds_status([(f"omega_{j}", lo, omegas[j - 1], hi)])
