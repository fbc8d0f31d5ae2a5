"""The level c* over a parameter box by centred forms in the parameters (issue 37 part 2, Lyapunov kind).

c*(P) = min of V over the boundary of region (17): the faces |x2| = x2* inside the disc of radius R(P), and the
cylinder x1^2 + x3^2 = R(P)^2. :func:`.box_levels.c_star_box` evaluates both naively on the box's balls, which
loses every correlation: over a +-1 % box of the example its ball is [-29.7, 34.1] where c* varies in
[22.3, 24.7] (phi(x2*) = mu F - f3^2/(2S) is 47.6 - 24, and the cylinder bound alpha - |f3| R - |(gamma, delta)|
is 47.6 + 160 - 88 - 79 with every R^2 term taken at both ends of R's ball). Here, for an odd law (x2 in
[0, x2*]):

* the faces: phi(x2*) bounded below and above over the box by :class:`.box_forms.CentredBox` (monotonicity at
  faces, then a centred form), its parameter derivatives by forward mode in balls. G = int_0^x2 cos f / D (in F
  = (H/B0) G) is differentiated without its closed form: dG/dA0 = -int cos f / D^2 in G [1/D] (D's hull over
  [0, x2]) and dG/dC0 = int cos f sin^2 / D^2 in G [0, sin^2 x2 / D(x2)], by the mean value theorem for
  integrals (the weight cos f / D >= 0: f >= 0 on [0, x2*] is certified first, x2* < pi/2); dG/da = G/a for
  the laws f = a shape(x2) (sine, linear); another law with a varying a gets no form (the naive ball);
* the cylinder: on the circle of radius r, V >= mu F - |f3| r + K r^2 with K = (e + h^2 - |(h^2 - e, 2 mu h)|)/4
  (e = f2 + mu f1, h = H cos x2 / B0; :func:`.model.cylinder_lower_bound` with the r^2 factored out, so r
  enters once), a quadratic in r whose minimum over r in R's ball [R_lo, R_hi] is at R_lo where its vertex
  |f3|/(2K) <= R_lo over the whole box (at R_hi where >= R_hi; the vertex value mu F - f3^2/(4K) otherwise),
  the branch chosen per x2 piece on the whole box's balls; that bound is bounded below over the box by the
  centred form on x2 pieces. Where it is certified above phi(x2*)'s lower bound on every piece, c*'s lower
  end is phi's; otherwise the smaller, by branch and bound;
* c*'s upper end: phi(x2*)'s upper bound over the box where the faces' minimiser is inside every member's
  disc (certainly |(m1, m3)| < R_lo on the box's balls): V at that point of the region's boundary; otherwise
  V at t (m1, m3) with t = R_lo / max |(m1, m3)| < 1, a point of the face inside every disc, which is at most
  (1 - t) mu F(x2*) + t phi(x2*) (V convex in (x1, x3)), each bounded above over the box.

Guarantee: the ball returned contains c*(P) for every P in the box, R(P) in the ball ``R``, at the current
precision. Fails when: a law that is not odd, x2* not certainly < pi/2, f >= 0 on [0, x2*] or S(x2*) > 0 not
certified, R not certainly > 0, or an enclosure not finite: None (the caller keeps its naive ball).
"""
from __future__ import annotations

from flint import arb

from ...core.balls import certainly_lt, certainly_positive
from ...core.subdivision import certify_positive, enclose_max
from .box_forms import CentredBox, balls_of, parameter_balls
from .model import Dual, Gimbal, ParameterBalls
from .polar_forms import law_is_odd
from .moments import LinearMoment, SineMoment

__all__ = ["c_star_centred", "G_dual", "CYL_PIECES", "A_LINEAR_LAWS"]

#: x2 pieces of the cylinder's certification (and of its branch and bound where that fails)
CYL_PIECES = 64
#: the laws whose f is a times a function of x2 alone (then dG/da = G/a exactly)
A_LINEAR_LAWS = (SineMoment, LinearMoment)


def _v(x):
    return x.v if type(x) is Dual else x


def _value_gimbal(gm: Gimbal) -> Gimbal:
    """A gimbal with the plain balls of ``gm``'s parameters (the Duals' values)."""
    from .box_forms import ParamGimbal
    c = gm.c
    pb = ParameterBalls(*(_v(getattr(c, f)) for f in ("A0", "B0", "C0", "H", "k", "a", "mu", "x2_star")))
    return ParamGimbal(gm, pb)


def G_dual(gm: Gimbal, X: arb):
    """G(X) = int_0^X cos f / D for every parameter of ``gm`` (balls or one-direction :class:`.model.Dual`s) and
    X inside [0, x2*]: a ball, or a Dual whose derivative encloses dG along the Duals' direction (module
    docstring), or None where a varying a enters a law not linear in a. The caller certifies f >= 0 on [0, x2*]
    and x2* < pi/2 (the weight's sign)."""
    c = gm.c
    Gv = _value_gimbal(gm).G(X)
    if not any(type(x) is Dual for x in (c.a, c.A0, c.C0)):
        return Gv
    av, A0v, C0v = _v(c.a), _v(c.A0), _v(c.C0)
    d = arb(0)
    if type(c.a) is Dual:
        if type(gm.law) not in A_LINEAR_LAWS:
            return None
        d = d + c.a.d * Gv / av
    s2 = arb(X.upper()).sin() ** 2
    Dend = A0v - C0v * s2
    if not (certainly_positive(A0v) and certainly_positive(Dend)):
        return None
    if type(c.A0) is Dual:
        d = d - c.A0.d * Gv / A0v.union(Dend)
    if type(c.C0) is Dual:
        d = d + c.C0.d * Gv * arb(0).union(s2 / Dend)
    return Dual(Gv, d)


def _parts(gm: Gimbal, X: arb):
    """(mu H G, f, D, Q) at x2 in X: the pieces of phi and of the cylinder bound, each written so that a
    parameter enters as few times as it can (Q = H^2 cos^2 x2 / B0); None where G has no form."""
    G = G_dual(gm, X)
    if G is None:
        return None
    c = gm.c
    cs = X.cos()
    return c.mu * c.H * G, gm.f(X), c.A0 - c.C0 * X.sin() ** 2, c.H * c.H * cs * cs / c.B0


def _phi(gm: Gimbal, w, X: arb, dual: bool):
    """phi = mu F - f3^2/(2 S), V's minimum over (x1, x3) at x2 (the form of :meth:`CentredBox.lower`), as
    (mu H G - f^2 / (2 D (1 + eps))) / B0 with eps = mu (k - mu D) / (D Q) (S D B0 = H^2 cos^2 + mu B0 (k - mu D)):
    mu H G and f^2/(2D) (200 and 100 in the example) carry the parameters once each."""
    parts = _parts(gm, X)
    if parts is None:
        return None
    muHG, f, D, Q = parts
    c = gm.c
    eps = c.mu * (c.k - c.mu * D) / (D * Q)
    return (muHG - f * f / (2 * D * (1 + eps))) / c.B0


def _neg_phi(gm, w, X, dual):
    p = _phi(gm, w, X, dual)
    return None if p is None else -p


def _K(gm: Gimbal, X: arb, parts=None):
    """K = (e + h^2 - |(h^2 - e, 2 mu h)|)/4 (e = f2 + mu f1, h = H cos x2/B0) as (Q/4) (4 p q - t) / (p + q +
    sqrt((q - p)^2 + t)), p = (1 + mu k/Q)/D, q = 1/B0, t = 4 mu^2/(Q B0) (e = Q p, h^2 = Q q, (2 mu h)^2 = Q^2 t):
    no difference of nearly equal terms."""
    c = gm.c
    _, _, D, Q = parts if parts is not None else _parts(gm, X)
    p = (1 + c.mu * c.k / Q) / D
    q = 1 / c.B0
    t = 4 * c.mu * c.mu / (Q * c.B0)
    return Q / 4 * (4 * p * q - t) / (p + q + ((q - p) ** 2 + t).sqrt())


def _cylinder(r: arb | None):
    """mu F - f3 r + K r^2 at the exact radius r, or the vertex value mu F - f3^2/(4K) (r None); mu F = mu H G / B0,
    f3 = H cos x2 f / (D B0)."""
    def h(gm: Gimbal, w, X: arb, dual: bool):
        parts = _parts(gm, X)
        if parts is None:
            return None
        muHG, f, D, Q = parts
        c = gm.c
        f3B0 = c.H * X.cos() * f / D
        K = _K(gm, X, parts)
        if r is None:
            return (muHG - f3B0 * f3B0 / (4 * K * c.B0)) / c.B0
        return (muHG - f3B0 * r) / c.B0 + K * r * r
    return h


def c_star_centred(g: Gimbal, raw: dict[str, tuple], R: arb) -> tuple[arb, arb | None] | None:
    """(lower, upper): exact balls with lower <= c*(P) for every P in the box ``raw`` (name -> (lo, hi)), R(P) in
    ``R``, and upper >= c*(P) (None where the faces' minimiser is not certainly inside every disc); module
    docstring. None when no bound is stated."""
    if not law_is_odd(g.law):
        return None
    if not (R.is_finite() and certainly_positive(R.lower())):
        return None
    xs = g.x2_star.ball()
    if not certainly_lt(xs, arb.pi() / 2):
        return None
    b = balls_of(raw)
    whole = parameter_balls(b, xs)
    if not certainly_positive(g.law.f_over_x(whole.a, arb(0).union(xs))):
        return None                     # f >= 0 on [0, x2*] not certified: the weight of G's derivatives
    from .box_forms import ParamGimbal
    gb = ParamGimbal(g, whole)
    if not certainly_positive(gb.S(xs)):
        return None                     # S > 0: phi is V's minimum over the face, V convex in (x1, x3) there
    cb = CentredBox(g, raw, arb(0))
    phi_lo = cb.lower(_phi, positivity=False)(xs)
    phi_hi = -cb.lower(_neg_phi, positivity=False)(xs)
    if not (phi_lo.is_finite() and phi_hi.is_finite()):
        return None
    Rlo, Rhi = arb(R.lower()), arb(R.upper())

    def cyl(X: arb) -> arb:
        K = _K(gb, X)
        if not certainly_positive(K):
            return arb("-inf")
        vert = gb.f3(X) / (2 * K)
        r = Rlo if certainly_lt(vert.upper(), Rlo) else Rhi if certainly_lt(Rhi, vert.lower()) else None
        return cb.lower(_cylinder(r), positivity=False)(X)
    target = arb(phi_lo.lower())
    if certify_positive(lambda X: cyl(X) - target, 0, xs, max_pieces=CYL_PIECES).status.value == "proved":
        lower = target
    else:
        m = enclose_max(lambda X: -cyl(X), 0, xs, abs_tol=abs(target) * arb("1e-4") + arb("1e-12"),
                        max_pieces=CYL_PIECES)
        lower = target.min(arb((-m.ball).lower()))
    if not lower.is_finite():
        return None
    m1, m3 = gb.phi_minimiser(xs)
    if certainly_lt(m1 ** 2 + m3 ** 2, Rlo ** 2):
        return arb(lower.lower()), arb(phi_hi.upper())
    # the face point t (m1, m3), t = R_lo / max |(m1, m3)| < 1 exact, is inside every member's disc, and V is
    # convex in (x1, x3): V(t m) <= (1 - t) V(0) + t V(m) = (1 - t) mu F(x2*) + t phi(x2*)
    norm = (m1 ** 2 + m3 ** 2).sqrt()
    if not (norm.is_finite() and certainly_positive(norm)):
        return arb(lower.lower()), None
    t = arb((Rlo / arb(norm.upper())).lower())
    if not (certainly_positive(t) and certainly_lt(t, arb(1))):
        return arb(lower.lower()), None
    muF_hi = -cb.lower(_neg_mu_F, positivity=False)(xs)
    upper = (1 - t) * arb(muF_hi.upper()) + t * arb(phi_hi.upper())
    return arb(lower.lower()), (arb(upper.upper()) if upper.is_finite() else None)


def _neg_mu_F(gm: Gimbal, w, X: arb, dual: bool):
    """-mu F = -mu H G / B0 (V at the face's point x1 = x3 = 0)."""
    parts = _parts(gm, X)
    return None if parts is None else -parts[0] / gm.c.B0
