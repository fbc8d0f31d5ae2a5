"""Second-order forms of the bracket gaps over a parameter box (issue 37: the bracket (8) layer).

Why: the gap omega_2 - lower_2 is 1e-5..1e-4 near the boundary of bracket (8) while each of omega_2 and
the bound moves by about 0.27 per unit eps. A first-order (centred) form encloses the gap's gradient over
the box as the difference of two wide sensitivities, far wider than the gap's true slope. Here the gap is
enclosed by its second-order Taylor form

    g(P) in g(M) + sum_i g_i(M) d_i + 1/2 sum_ij H_ij(B) d_i d_j,   d = P - M,

M the box's exact midpoint: the gradient at the point M is narrow (the two sensitivities cancel at a
point), only the Hessian is enclosed over the whole box B, and it is multiplied by the box width squared.

How: a :class:`Jet2` is an arb (its value) carrying a gradient and a Hessian (forward-mode AD to second
order in balls), so the model's bound formulas (:func:`.model.bracket`) run on it unchanged. The root
omega_j(P) enters as an implicit function of the quartic Q(omega, P) = 0 (:func:`.slack_forms.quartic_value`):
Q is evaluated on Jet2s in (omega, P) over (Omega, B), Omega a ball holding omega_j(P) for every P in B,
and the implicit function theorem gives, at (omega_j(P), P),

    w_i = -Q_i / Q_w,   w_ij = -(Q_ij + Q_wi w_j + Q_wj w_i + Q_ww w_i w_j) / Q_w,

so the same expressions evaluated on the enclosures contain them for every P in B (Q_w certainly
nonzero there). At the point M the root is the point implicit root (:func:`rigor_gyro.core.implicit_roots.
implicit_root` with constant parameters) and its gradient the first formula at that narrow ball.

Guarantee: :func:`gap_form` returns a ball containing the gap for every parameter value in the box
(Taylor's theorem with the Lagrange remainder along the segment from M to P, inside the convex box, the
Hessian there inside H(B)), or None where it cannot enclose (Q_w or a divisor not certainly nonzero, a
square root of a ball not certainly positive, a non-finite enclosure). Precondition: ``root_ball`` holds
omega_j(P) for every P in the box and is the only root there (the caller's family Newton proof).
Precision: the current working precision.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_nonzero
from ...core.boxes import Box
from ...core.dual_balls import constant, variable
from ...core.implicit_roots import implicit_root
from .model import NotReal, Params, bracket

__all__ = ["Jet2", "NotTwiceDifferentiable", "jet_variable", "jet_constant", "implicit_root_jet", "gap_form",
           "gap_sign"]

NAMES = ("a", "b", "eps", "Omega2")
#: the key of the unknown omega in Q's jets (never a parameter name)
W_KEY = "__omega__"


class NotTwiceDifferentiable(ArithmeticError):
    """A Jet2 operation whose derivatives are not enclosed on the whole set (sqrt of a ball not certainly > 0,
    a divisor not certainly nonzero)."""


def _exact(x) -> arb:
    if isinstance(x, bool):
        raise TypeError("a bool is not a number")
    if isinstance(x, (int, fmpq)):
        return arb(x)
    if isinstance(x, Fraction):
        return arb(fmpq(x.numerator, x.denominator))
    raise TypeError(f"operand {x!r} ({type(x).__name__}) in Jet2 arithmetic: only Jet2s and exact numbers")


def _key(i: str, j: str) -> tuple[str, str]:
    return (i, j) if i <= j else (j, i)


class Jet2(arb):
    """An arb value with ``g`` {name: ball of the first partial} and ``h`` {(i, j) with i <= j: ball of the
    second partial}; a missing entry is exactly 0."""

    def __init__(self, value, g: dict | None = None, h: dict | None = None):
        arb.__init__(self, value)
        self.g = dict(g or {})
        self.h = dict(h or {})

    @property
    def value(self) -> arb:
        return arb(self)

    @staticmethod
    def lift(x) -> "Jet2":
        return x if isinstance(x, Jet2) else Jet2(_exact(x))

    def _combine(self, o: "Jet2", value: arb, a: arb, b: arb) -> "Jet2":
        """value, with gradient a*self.g + b*o.g and Hessian a*self.h + b*o.h."""
        g = {k: a * v for k, v in self.g.items()}
        for k, v in o.g.items():
            g[k] = g[k] + b * v if k in g else b * v
        h = {k: a * v for k, v in self.h.items()}
        for k, v in o.h.items():
            h[k] = h[k] + b * v if k in h else b * v
        return Jet2(value, g, h)

    def __add__(self, other):
        o = Jet2.lift(other)
        return self._combine(o, self.value + o.value, arb(1), arb(1))

    __radd__ = __add__

    def __sub__(self, other):
        o = Jet2.lift(other)
        return self._combine(o, self.value - o.value, arb(1), arb(-1))

    def __rsub__(self, other):
        return Jet2.lift(other).__sub__(self)

    def __neg__(self):
        return Jet2(-self.value, {k: -v for k, v in self.g.items()}, {k: -v for k, v in self.h.items()})

    def __pos__(self):
        return self

    def __mul__(self, other):
        o = Jet2.lift(other)
        # (uv)_ij = u_ij v + u v_ij + u_i v_j + u_j v_i: cross terms counted once per ordered pair
        out = self._combine(o, self.value * o.value, o.value, self.value)
        for i, u in self.g.items():
            for j, w in o.g.items():
                k = _key(i, j)
                t = u * w if i != j else 2 * u * w
                out.h[k] = out.h[k] + t if k in out.h else t
        # i != j: the loop visits (i, j) and (j, i) once each when both are in both gradients, giving
        # u_i w_j + u_j w_i under one key; a name missing from one gradient contributes 0 there
        return out

    __rmul__ = __mul__

    def _unary(self, f0: arb, f1: arb, f2: arb) -> "Jet2":
        """f(self) from f, f', f'' at the value: (f u)_i = f' u_i, (f u)_ij = f' u_ij + f'' u_i u_j."""
        g = {k: f1 * v for k, v in self.g.items()}
        h = {k: f1 * v for k, v in self.h.items()}
        names = list(self.g)
        for x, i in enumerate(names):
            for j in names[x:]:
                k = _key(i, j)
                t = f2 * self.g[i] * self.g[j]
                h[k] = h[k] + t if k in h else t
        return Jet2(f0, g, h)

    def reciprocal(self) -> "Jet2":
        v = self.value
        if not certainly_nonzero(v):
            raise NotTwiceDifferentiable("a divisor not certainly nonzero")
        r = 1 / v
        return self._unary(r, -r * r, 2 * r * r * r)

    def __truediv__(self, other):
        return self * Jet2.lift(other).reciprocal()

    def __rtruediv__(self, other):
        return Jet2.lift(other) * self.reciprocal()

    def __pow__(self, n, modulo=None):
        if modulo is not None or isinstance(n, bool) or not isinstance(n, int) or n < 0:
            raise TypeError("Jet2 ** n: only a non-negative int exponent")
        out = Jet2(arb(1))
        for _ in range(n):
            out = out * self
        return out

    def sqrt(self):
        v = self.value
        if not (v > 0):
            raise NotTwiceDifferentiable("sqrt of a ball not certainly positive")
        s = v.sqrt()
        return self._unary(s, 1 / (2 * s), -1 / (4 * s * v))

    def finite(self) -> bool:
        return self.value.is_finite() and all(x.is_finite() for x in self.g.values()) and \
            all(x.is_finite() for x in self.h.values())


def jet_variable(name: str, value: arb) -> Jet2:
    return Jet2(value, {name: arb(1)})


def jet_constant(value) -> Jet2:
    return Jet2(value if isinstance(value, arb) else _exact(value))


def _q_jet(quartic, w: Jet2, p: dict) -> Jet2:
    return quartic(w, Params(*(p[k] for k in ("a", "b", "eps", "Omega2"))))


def implicit_root_jet(quartic, root_ball: arb, params: dict[str, Jet2]) -> Jet2 | None:
    """omega(P) as a Jet2 over the parameter jets ``params`` (variables on the box, constants elsewhere):
    value ``root_ball``, first and second partials by the implicit function theorem (module docstring);
    None where Q_w is not certainly nonzero or an enclosure is not finite."""
    try:
        Q = _q_jet(quartic, jet_variable(W_KEY, root_ball), params)
    except NotTwiceDifferentiable:
        return None
    qw = Q.g.get(W_KEY)
    if qw is None or not certainly_nonzero(qw) or not Q.finite():
        return None
    names = sorted({k for p in params.values() for k in p.g})
    wi = {i: -Q.g.get(i, arb(0)) / qw for i in names}
    qww = Q.h.get((W_KEY, W_KEY), arb(0))
    h = {}
    for x, i in enumerate(names):
        for j in names[x:]:
            qij = Q.h.get(_key(i, j), arb(0))
            qwi, qwj = Q.h.get(_key(W_KEY, i), arb(0)), Q.h.get(_key(W_KEY, j), arb(0))
            h[(i, j)] = -(qij + qwi * wi[j] + qwj * wi[i] + qww * wi[i] * wi[j]) / qw
    out = Jet2(root_ball, wi, h)
    return out if out.finite() else None


def _params(model, values: dict[str, arb], varying: set[str]) -> dict[str, Jet2]:
    return {k: (jet_variable(k, v) if k in varying else jet_constant(v)) for k, v in values.items()}


def gap_form(model, box: Box, j: int, side: str, root_ball: arb, point_root: arb) -> arb | None:
    """The gap omega_j - lower_j (``side`` "lower") or upper_j - omega_j ("upper") of bracket j, in the
    reading the claims use, enclosed over ``box`` by its second-order Taylor form (module docstring).
    ``root_ball``: omega_j(P) for every P in the box (the only root there); ``point_root``: a ball
    containing omega_j at the box's exact midpoint (the only root of Q(., M) in it). None where it
    cannot enclose."""
    from .slack_forms import quartic_value
    names = ("a", "b", "eps", "Omega2")
    varying = {k for k, lo, hi in box.edges if hi > lo}
    mid = box.midpoint()

    def q(k):
        return model.q(k)
    whole = {k: (box.ball(k) if k in box.names else arb(q(k))) for k in names}
    at_mid = {k: (arb(fmpq(mid[k].numerator, mid[k].denominator)) if k in box.names else arb(q(k))) for k in names}
    try:
        P_B = _params(model, whole, varying)
        P_M = _params(model, at_mid, varying)
        wB = implicit_root_jet(quartic_value, root_ball, P_B)
        wM = implicit_root_jet(quartic_value, point_root, P_M)
        if wB is None or wM is None:
            return None
        bB = bracket(j, Params(*(P_B[k] for k in names)), reading="intended")
        bM = bracket(j, Params(*(P_M[k] for k in names)), reading="intended")
    except (NotTwiceDifferentiable, NotReal, ZeroDivisionError, ValueError):
        return None
    if side == "lower":
        gB, gM = wB - bB[0], wM - bM[0]
    else:
        gB, gM = bB[1] - wB, bM[1] - wM
    if not (isinstance(gB, Jet2) and isinstance(gM, Jet2) and gB.finite() and gM.finite()):
        return None
    d = {k: box.ball(k) - at_mid[k] for k in varying}
    out = gM.value
    for k in varying:
        out += gM.g.get(k, arb(0)) * d[k]
    ks = sorted(varying)
    for x, i in enumerate(ks):
        for k2 in ks[x:]:
            H = gB.h.get((i, k2), arb(0))
            if i == k2:
                sq = d[i] * d[i]
                sq = sq.union(arb(0))                   # d_i^2 ranges over [0, r^2]
                out += H * sq / 2
            else:
                out += H * d[i] * d[k2]                 # 1/2 (H_ij + H_ji) d_i d_j
    return out if out.is_finite() else None


def _root(params: dict, root_ball: arb, centred: bool) -> arb | None:
    from .slack_forms import quartic_value
    r = implicit_root(lambda x, p: quartic_value(x, Params(*(p[k] for k in NAMES))), root_ball, params,
                      centred=centred)
    return None if r is None else r.value


def point_root(model, box: Box, root_ball: arb) -> arb | None:
    """omega_j at the box's exact midpoint, narrowed inside ``root_ball`` by the point implicit root
    (interval Newton at exact parameters), or None."""
    mid = box.midpoint()
    return _root({k: constant(arb(fmpq(mid[k].numerator, mid[k].denominator)) if k in box.names else arb(model.q(k)))
                  for k in NAMES}, root_ball, False)


def box_root(model, box: Box, root_ball: arb) -> arb | None:
    """omega_j(P) for every P in the box, narrowed inside ``root_ball`` (which holds it, the only root there)
    by the implicit root in centred form (:func:`rigor_gyro.core.implicit_roots.implicit_root`), or None."""
    return _root({k: (variable(k, box.ball(k)) if k in box.names and box.interval(k)[1] > box.interval(k)[0]
                      else constant(box.ball(k) if k in box.names else arb(model.q(k)))) for k in NAMES},
                 root_ball, True)


def _one_sign(model, box: Box, j: int, side: str, root_ball: arb, strict: bool) -> tuple[str, arb | None]:
    narrow = box_root(model, box, root_ball)
    if narrow is not None:
        root_ball = narrow
    pr = point_root(model, box, root_ball)
    if pr is None:
        return "undecided", None
    g = gap_form(model, box, j, side, root_ball, pr)
    if g is None:
        return "undecided", None
    if (g.lower() > 0) if strict else (g.lower() >= 0):
        return "positive", g
    if g.upper() < 0:
        return "negative", g
    return "undecided", g


def _quarters(box: Box) -> list[Box]:
    """The box halved along every non-degenerate edge (2^k sub-boxes tiling it, exact rational edges)."""
    out = [[]]
    for k, lo, hi in box.edges:
        if hi > lo:
            m = (lo + hi) / 2
            out = [e + [(k, lo, m)] for e in out] + [e + [(k, m, hi)] for e in out]
        else:
            out = [e + [(k, lo, hi)] for e in out]
    return [Box(tuple(e)) for e in out]


def gap_sign(model, box: Box, j: int, side: str, root_ball: arb, strict: bool) -> tuple[str, str]:
    """("positive" | "negative" | "undecided", how) for the gap of :func:`gap_form` over the box; where the
    whole box's form straddles 0, the same form on the sub-boxes of one halving of every edge decides when
    all of them agree (they tile the box; ``root_ball`` holds the root for each, the only one there)."""
    st, g = _one_sign(model, box, j, side, root_ball, strict)
    if st != "undecided":
        word = ">=" if st == "positive" else "<="
        end = g.lower() if st == "positive" else g.upper()
        return st, f"second-order Taylor form of the gap, {word} {end.str(3, radius=False)}"
    subs = [_one_sign(model, b, j, side, root_ball, strict)[0] for b in _quarters(box)]
    if len(subs) > 1 and all(x == subs[0] for x in subs) and subs[0] != "undecided":
        return subs[0], f"second-order Taylor form of the gap on {len(subs)} sub-boxes tiling the box, each {subs[0]}"
    return "undecided", "second-order form straddles 0"
