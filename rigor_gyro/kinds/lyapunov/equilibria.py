"""Every equilibrium of system (2) with |x2| <= pi, certified, with its linearisation's stability.

With x3 = 0 (from x2' = x3), x3' = 0 reads cos x2 . x1 . (H - C0 sin x2 . x1) = 0 and x1' = 0 reads
k x1 + f(x2) = 0. So the equilibria are exactly (x1, x2, 0) with x1 = -f(x2)/k and one of

* (i)   x1 = 0:       f(x2) = 0;
* (ii)  cos x2 = 0:   x2 = +-pi/2;
* (iii) H = C0 sin x2 x1:   h(x2) = k H + C0 sin x2 f(x2) = 0 (and cos x2 != 0; otherwise it is (ii)).

The roots of f and of h are isolated on [-P, P], P = pi + 1/64 (so no root sits on an end), by
interval Newton with bisection (:func:`rigor_gyro.core.roots.isolate_roots`): every piece is certified
root-free or to hold exactly one root. A root of f whose enclosure contains an exact zero the law
names (:meth:`MomentLaw.zeros_over_pi`, multiples of pi) certainly inside its piece is that zero (the
piece holds exactly one root); any other root must lie
certainly inside or certainly outside |x2| <= pi. The linearisation's Jacobian is computed by
forward-mode differentiation of (2) (dual numbers over balls) and its eigenvalues by Arb
(``acb_mat.eig``): *asymptotically stable* when every real part is certainly < 0, *unstable* when one is
certainly > 0, otherwise *undecided* (a real part not separated from 0 at this precision). Where Arb's eigenvalues
leave the stability undecided, the Routh-Hurwitz test on the characteristic polynomial decides it when it can
(:func:`routh_hurwitz`: its coefficients are sums of principal minors, which keep the Jacobian's exact zeros, so
they stay narrow where the eigenvalues separate only at thousands of bits: H = 1e300, a = 1e-300). At cos x2 = 0
the eigenvalues are in closed form (:func:`classify_at_cos_zero`): -k/(A0 - C0) and +-sqrt(J32), so a pair
with real part exactly 0 (J32 < 0, e.g. C0 < -H k/a for the sine law) is decided *not hyperbolic* exactly,
where Arb's eigenvalues of the matrix would escalate forever.

Guarantee: the list is complete on |x2| <= pi exactly when every piece is decided (``complete``);
each equilibrium is a ball containing the exact point. Fails when: a piece stays undecided (a double
root of h, a precision too low): the result says so and claims nothing about completeness.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from flint import acb_mat, arb, fmpq

from ...core.balls import (certainly_le, certainly_lt, certainly_negative, certainly_nonzero, certainly_positive,
                           enclosure_text)
from ...core.roots import RootStatus, isolate_roots
from .model import Dual, Gimbal

__all__ = ["Equilibrium", "Equilibria", "equilibria", "classify", "classify_at_cos_zero", "NOT_HYPERBOLIC", "RANGE_PAD",
           "characteristic_coefficients", "jacobian", "pi_text", "routh_hurwitz"]

#: the search range is [-(pi + RANGE_PAD), pi + RANGE_PAD]
RANGE_PAD = Fraction(1, 64)


@dataclass
class Equilibrium:
    x1: arb
    x2: arb
    case: str                         # "f(x2) = 0", "cos x2 = 0", "k H + C0 sin x2 f(x2) = 0"
    exact: str = ""                   # the exact x2 when known ("0", "pi", "pi/2", ...)
    eigenvalues: list = field(default_factory=list)
    stability: str = "undecided"      # "asymptotically stable" | "unstable" | NOT_HYPERBOLIC | "undecided"
    #: when the Routh-Hurwitz test decided the stability (Arb's eigenvalues did not): (a1, a2, a3) of
    #: det(lambda I - J) = lambda^3 + a1 lambda^2 + a2 lambda + a3; None otherwise
    hurwitz: tuple | None = None


@dataclass
class Equilibria:
    points: list[Equilibrium]
    complete: bool
    reason: str
    #: the isolation pieces of f and h on [-P, P] (exact texts), for the checker
    pieces: dict = field(default_factory=dict)


def _q(r: Fraction) -> arb:
    return arb(fmpq(r.numerator, r.denominator))


def jacobian(g: Gimbal, x1: arb, x2: arb, x3: arb) -> list[list[arb]]:
    """The Jacobian of (2) at (x1, x2, x3) by forward-mode differentiation in balls."""
    cols = []
    for j in range(3):
        args = [Dual(v, arb(1) if i == j else arb(0)) for i, v in enumerate((x1, x2, x3))]
        cols.append([d.d if isinstance(d, Dual) else arb(0) for d in g.rhs(*args)])
    return [[cols[j][i] for j in range(3)] for i in range(3)]


#: the stability of an equilibrium whose linearisation has eigenvalues with real part exactly 0 and none > 0
NOT_HYPERBOLIC = "not hyperbolic (eigenvalues +-i w, real part exactly 0: the linearisation decides nothing)"


def classify_at_cos_zero(g: Gimbal, e: Equilibrium) -> None:
    """The linearisation at x2 = s pi/2 (s = +-1, cos x2 = 0 exactly), x3 = 0, x1 = -f(x2)/k, in closed form.

    Why: with cos x2 = 0 and sin 2x2 = 0 exactly, the Jacobian of (2) is [[-k/D, J12, 0], [0, 0, 1],
    [0, J32, 0]] (dx1'/dx3 = (C0 sin 2x2 x1 - H cos x2)/D = 0, dx3'/dx1 = (-C0 sin 2x2 x1 + H cos x2)/B0 = 0),
    D = A0 - C0 > 0 and J32 = dx3'/dx2 = (-C0 cos 2x2 x1^2 - H sin x2 x1)/B0 = x1 (C0 x1 - s H)/B0. Its
    eigenvalues are exactly -k/D < 0 and the roots of lambda^2 = J32: J32 > 0 gives +-sqrt(J32) (unstable),
    J32 < 0 gives +-i sqrt(-J32), real part exactly 0 (not hyperbolic: no ball arithmetic on the 3 x 3 matrix
    can separate that real part from 0, at any precision). J32 not separated from 0: undecided."""
    from flint import acb
    c = g.c
    s = 1 if certainly_positive(e.x2) else -1
    lam1 = -c.k / (c.A0 - c.C0)
    J32 = e.x1 * (c.C0 * e.x1 - s * c.H) / c.B0
    if certainly_positive(J32):
        w = J32.sqrt()
        e.eigenvalues = [acb(lam1), acb(w), acb(-w)]
        e.stability = "unstable"
    elif certainly_negative(J32):
        w = (-J32).sqrt()
        e.eigenvalues = [acb(lam1), acb(0, w), acb(0, -w)]
        e.stability = NOT_HYPERBOLIC
    else:
        e.eigenvalues = [acb(lam1), acb(0, abs(J32).sqrt()), acb(0, -abs(J32).sqrt())]
        e.stability = "undecided"


def characteristic_coefficients(J) -> tuple[arb, arb, arb]:
    """(a1, a2, a3) with det(lambda I - J) = lambda^3 + a1 lambda^2 + a2 lambda + a3, for a 3 x 3 matrix of balls.

    Guarantee: each ball contains the coefficient for every real matrix in the balls of J (a1 = -trace, a2 = the
    sum of the principal 2 x 2 minors, a3 = -det by cofactors along the first row). Exact zeros of J stay exact
    in the products (arb_mat.charpoly's elimination mixes them with the large entries: at H = 1e300 it returns
    a3 = [+/- 1e579] where this gives a3 to 18 digits). Precision: the current one."""
    a1 = -(J[0][0] + J[1][1] + J[2][2])
    a2 = ((J[0][0] * J[1][1] - J[0][1] * J[1][0]) + (J[0][0] * J[2][2] - J[0][2] * J[2][0])
          + (J[1][1] * J[2][2] - J[1][2] * J[2][1]))
    det = (J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0])
           + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]))
    return a1, a2, -det


def routh_hurwitz(a1: arb, a2: arb, a3: arb) -> str:
    """The stability of the roots of lambda^3 + a1 lambda^2 + a2 lambda + a3 (real coefficients in balls).

    Guarantee (Routh-Hurwitz for a monic cubic): "asymptotically stable" (every root has real part < 0) when
    a1 > 0, a3 > 0 and a1 a2 - a3 > 0 certainly; "unstable" (a root with real part > 0) when a1 < 0 (the roots
    sum to -a1 > 0), or a3 < 0 (the polynomial is a3 < 0 at 0 and +inf at +inf: a positive real root), or a1 > 0,
    a3 > 0 and a1 a2 - a3 < 0 (Routh's first column 1, a1, (a1 a2 - a3)/a1, a3 changes sign twice: two roots in
    the right half-plane), each certainly; "undecided" otherwise (a sign not separated from 0, e.g. a centre
    with a1 a2 = a3 exactly, a zero root with a3 = 0, or a ball that is not finite). Precision: the current one."""
    if not all(v.is_finite() for v in (a1, a2, a3)):
        return "undecided"
    hurwitz2 = a1 * a2 - a3
    if certainly_positive(a1) and certainly_positive(a3) and certainly_positive(hurwitz2):
        return "asymptotically stable"
    if certainly_negative(a1) or certainly_negative(a3) or \
            certainly_positive(a1) and certainly_positive(a3) and certainly_negative(hurwitz2):
        return "unstable"
    return "undecided"


def classify(g: Gimbal, e: Equilibrium) -> None:
    """Set ``e.eigenvalues`` and ``e.stability`` from the linearisation at ``e`` (in closed form at
    cos x2 = 0, :func:`classify_at_cos_zero`; by Arb's eigenvalues of the Jacobian elsewhere, and where they
    leave it undecided by :func:`routh_hurwitz` on :func:`characteristic_coefficients`, which sets
    ``e.hurwitz``; ``e.eigenvalues`` is then what Arb returned, or empty where it could not isolate them)."""
    if e.case == "cos x2 = 0" and e.exact in ("pi/2", "-pi/2"):
        classify_at_cos_zero(g, e)
        return
    J = jacobian(g, e.x1, e.x2, arb(0))
    try:
        ev = acb_mat(J).eig(algorithm="rump")
    except ValueError:
        ev = None
    if ev is not None:
        e.eigenvalues = list(ev)
    if ev is None or not all(z.is_finite() for z in ev):
        e.stability = "undecided"
    elif all(certainly_negative(z.real) for z in ev):
        e.stability = "asymptotically stable"
    elif any(certainly_positive(z.real) for z in ev):
        e.stability = "unstable"
    else:
        e.stability = "undecided"
    if e.stability == "undecided":
        coeffs = characteristic_coefficients(J)
        verdict = routh_hurwitz(*coeffs)
        if verdict != "undecided":
            e.stability, e.hurwitz = verdict, coeffs
            if ev is not None and not all(z.is_finite() for z in ev):
                e.eigenvalues = []


def _pieces_text(iso) -> list[dict]:
    from ...core.stored import ball_text
    return [{"lo": ball_text(p.lo), "hi": ball_text(p.hi), "kind": p.status.value,
             **({"root": ball_text(p.enclosure)} if p.enclosure is not None else {})} for p in iso.pieces]


def equilibria(g: Gimbal) -> Equilibria:
    """Every equilibrium with |x2| <= pi (see the module docstring), at the current precision."""
    c = g.c
    pi = arb.pi()
    P = (pi + arb(fmpq(RANGE_PAD.numerator, RANGE_PAD.denominator))).upper()
    f = lambda x: g.f(x)                                            # noqa: E731
    h = lambda x: c.k * c.H + c.C0 * x.sin() * g.f(x)               # noqa: E731
    iso_f, iso_h = isolate_roots(f, -P, P), isolate_roots(h, -P, P)     # ball code accepts series too
    unknown = iso_f.unknown + iso_h.unknown
    points: list[Equilibrium] = []
    problems = []
    zeros = [r for r in g.law.zeros_over_pi()]
    for piece in (p for p in iso_f.pieces if p.status is RootStatus.UNIQUE):
        root = piece.enclosure
        # f has exactly one root in the piece; an exact zero of the law certainly in the piece is that root
        named = [r for r in zeros if certainly_le(piece.lo, pi * _q(r)) and certainly_le(pi * _q(r), piece.hi)]
        if len(named) == 1:
            r = named[0]
            x2 = pi * _q(r)
            if abs(r) <= 1:
                points.append(Equilibrium(arb(0), x2, "f(x2) = 0", exact=pi_text(r)))
        elif certainly_lt(abs(root), pi):
            points.append(Equilibrium(arb(0), root, "f(x2) = 0"))
        elif not certainly_lt(pi, abs(root)):
            problems.append(f"a root of f at {enclosure_text(root, 10)} is not separated from |x2| = pi")
    for sgn in (1, -1):
        x2 = sgn * pi / 2
        points.append(Equilibrium(-g.f(x2) / c.k, x2, "cos x2 = 0", exact=pi_text(Fraction(sgn, 2))))
    for root in iso_h.roots:
        if certainly_lt(pi, abs(root)):
            continue
        if not certainly_lt(abs(root), pi):
            problems.append(f"a root of h at {enclosure_text(root, 10)} is not separated from |x2| = pi")
            continue
        if not certainly_nonzero(root.cos()):
            problems.append(f"a root of h at {enclosure_text(root, 10)} is not separated from cos x2 = 0")
            continue
        points.append(Equilibrium(-g.f(root) / c.k, root, "k H + C0 sin x2 f(x2) = 0"))
    for e in points:
        classify(g, e)
    complete = not unknown and not problems
    reason = ("every piece of [-P, P] decided for f and for h" if complete else
              "; ".join(problems + [f"{len(unknown)} undecided piece(s): {unknown[0].reason}" if unknown else ""]))
    return Equilibria(points, complete, reason, {"f": _pieces_text(iso_f), "h": _pieces_text(iso_h)})


def pi_text(r: Fraction) -> str:
    """r pi as the report writes it: "0", "pi", "-pi/2", "2 pi/3"."""
    if r == 0:
        return "0"
    num = "pi" if abs(r.numerator) == 1 else f"{abs(r.numerator)} pi"
    s = num if r.denominator == 1 else f"{num}/{r.denominator}"
    return ("-" if r < 0 else "") + s

