"""The claims of a ``[system]`` scene (:mod:`.system_model`) over a box of its parameters (tolerances).

The characteristic polynomial's coefficients are exact polynomials in the box's parameters
(:mod:`.system_symbolic`: each row scaled by its entries' denominators, the determinant expanded exactly over
``fmpq_mpoly``; computed once per model and set of parameters). The structure is then decided exactly, never
from balls: lambda^z divides P for every member when c_0 .. c_(z-1) are the zero polynomial and c_z excludes 0
on the box; P is even when every odd coefficient above is the zero polynomial. The frequency family
Q~(omega; p) (lambda^2 = -omega) is evaluated in centred form about the box's midpoint (exact there) plus its
parameter gradient (exact polynomials evaluated on the box) times the offsets, intersected with the direct
enclosure; its m roots are verified for every member at once by one interval Newton step each
(:func:`rigor_gyro.core.family_roots.family_real_roots`, the midpoint's exact roots as guesses, the leading
coefficient certainly nonzero): m disjoint balls, each holding exactly one root of every member, all the roots.
Each row factor (a denominator) must exclude 0 on the box. Brackets are evaluated on the box's balls and in
centred form about the midpoint (forward-mode AD, :mod:`rigor_gyro.core.dual_balls`).

Guarantee: ``proved`` means the claim holds for every parameter value in the box; ``refuted`` that it fails for
every value of the box (a zero-root coefficient or an odd coefficient certainly nonzero on the whole box; a
bracket's bound certainly beyond the root's ball, or a square root of a certainly negative ball); ``undecided``
says neither was certified (the paving splits the box; its point proofs refute where a point fails). ``roots``
over a box states real, positive, simple roots for every member, without the point claim's relative width.

Precision: the caller's working precision; the box width dominates.

Fails when: a box edge is not a parameter of the scene, or a mirrored pair of matrix entries that a tolerance
enters is not the same rational function of the box's parameters (G: opposite ones, a zero diagonal; decided
exactly, symmetry must hold on the whole box): ParameterError naming it.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, arb_poly, fmpq, fmpq_poly

from ...core.balls import certainly_gt, certainly_le, certainly_nonzero, certainly_positive
from ...core.boxes import Box
from ...core.dual_balls import NotDifferentiable, constant, variable
from ...core.errors import ParameterError
from ...core.family_roots import family_real_roots
from ...core.polyroots import isolate_polynomial
from .system_claims import SYSTEM_CLAIMS
from .system_model import NotRealBound, SystemModel, ball_value
from .system_symbolic import characteristic_mpolys, entry_functions, mpoly_ball, same_function

__all__ = ["SYSTEM_BOX_CLAIMS", "validate_system_box", "evaluate_system_box", "system_box_roots"]

#: the claims a [system] scene decides over a box, with what each states at every point of it
SYSTEM_BOX_CLAIMS = {
    "roots": "The characteristic polynomial is lambda^z times an even polynomial whose frequency polynomial Q(omega) "
             "has only real, positive, simple roots.",
    "stability": SYSTEM_CLAIMS["stability"],
    "brackets": SYSTEM_CLAIMS["brackets"],
}


def validate_system_box(model: SystemModel, box: Box) -> None:
    """Every edge of the box names a parameter of the scene (not a def), and the symmetry of M, K, D and the
    skew-symmetry of G hold for every member of the box, not only at the midpoint where the scene was
    validated: a mirrored pair of entries that depends on a toleranced parameter (directly or through a def)
    must be the same rational function of the box's parameters (G: one the negation of the other, its diagonal
    the zero function), decided exactly (:func:`.system_symbolic.same_function`: any two spellings of one
    function pass, ``-h/2`` and ``-(h/2)`` alike; different functions, which differ somewhere in a box with
    interior, are refused). ParameterError naming the pair otherwise."""
    bad = [n for n in box.names if n not in model.params]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: a [system] scene takes tolerances only on its parameters "
                             f"{sorted(model.params)}")
    moving = _moving_names(model, set(box.names))
    pairs = []                          # (key, sign, i, j): the mirrored pairs a tolerance enters
    for key, sign in (("M", 1), ("K", 1), ("D", 1), ("G", -1)):
        rows = getattr(model, key)
        if rows is None:
            continue
        for i in range(model.n):
            for j in range(i, model.n):
                if (rows[i][j].names() | rows[j][i].names()) & moving:
                    pairs.append((key, sign, i, j))     # the others are fixed on the box: checked exactly at validation
    if not pairs:
        return
    exprs = [e for key, _, i, j in pairs for e in (getattr(model, key)[i][j], getattr(model, key)[j][i])]
    try:
        fns = entry_functions(model, box.names, _values(model, box), exprs)
    except ZeroDivisionError:
        raise ParameterError("[system]: an entry divides by an expression that is zero for every value in the box: "
                             "rewrite it") from None
    for k, (key, sign, i, j) in enumerate(pairs):
        a, b = getattr(model, key)[i][j], getattr(model, key)[j][i]
        fa, fb = fns[2 * k], fns[2 * k + 1]
        if sign < 0 and i == j:
            if not fa.num.is_zero():
                raise ParameterError(f"[system] G[{i + 1}][{i + 1}] = {a.text!r} depends on a toleranced parameter and "
                                     "is not 0 for every value in the box: the diagonal of G (skew-symmetric) must be "
                                     "0 (a term q_i' there is damping: move it to D)")
        elif not same_function(fa, fb, sign):
            what = ("the same function of the box's parameters (write them alike)" if sign > 0 else
                    f"each other's negation for every value in the box (write {key}[{j + 1}][{i + 1}] as "
                    f"'-({a.text})')")
            raise ParameterError(f"[system] {key}[{i + 1}][{j + 1}] = {a.text!r} and {key}[{j + 1}][{i + 1}] = "
                                 f"{b.text!r} depend on a toleranced parameter but are not {what}, so {key} would "
                                 f"not stay {'symmetric' if sign > 0 else 'skew-symmetric'} on the whole box")


def _moving_names(model: SystemModel, varied: set[str]) -> set[str]:
    """The toleranced parameters and the defs that depend on them."""
    out = set(varied)
    for name, e in model.defs:
        if e.names() & out:
            out.add(name)
    return out


def _values(model: SystemModel, box: Box) -> dict[str, Fraction]:
    """The exact parameter values at the box's midpoint (the model's own values off the box)."""
    out = {k: x.rational for k, x in model.params.items()}
    out.update(box.midpoint())
    return out


def _env(model: SystemModel, box: Box, values: dict[str, Fraction] | None = None,
         failed: dict | None = None) -> dict[str, arb]:
    """Balls of the parameters (the box's intervals, or the exact ``values``) and of the defs, in order. A def
    whose square root is certainly negative (or that uses such a def) is left out, its NotRealBound kept in
    ``failed`` (a bracket that uses it has no real value; the others are decided without it)."""
    if values is None:
        env = {k: (box.ball(k) if k in box.names else arb(fmpq(x.rational.numerator, x.rational.denominator)))
               for k, x in model.params.items()}
    else:
        env = {k: arb(fmpq(v.numerator, v.denominator)) for k, v in values.items()}
    failed = {} if failed is None else failed
    for name, e in model.defs:
        bad = [n for n in e.names() if n in failed]
        if bad:
            failed[name] = failed[bad[0]]
            continue
        try:
            env[name] = ball_value(e, env)
        except NotRealBound as exc:
            failed[name] = exc
    return env


class _Family:
    """The frequency family over the box from the exact coefficient polynomials (:mod:`.system_symbolic`)."""

    def __init__(self, q: list, names: tuple[str, ...], box: Box):
        mid = box.midpoint()
        self.balls = [box.ball(k) for k in names]
        mids = [fmpq(mid[k].numerator, mid[k].denominator) for k in names]
        self.offsets = [b - arb(m) for b, m in zip(self.balls, mids)]
        self.exact = [c(*mids) for c in q]                       # Q~ at the midpoint, exactly
        self.direct = arb_poly([mpoly_ball(c, self.balls) for c in q])
        self.mid = arb_poly([arb(c) for c in self.exact])
        self.grads = [arb_poly([mpoly_ball(c.derivative(k), self.balls) for c in q]) for k in names]
        self.d_direct, self.d_mid = self.direct.derivative(), self.mid.derivative()
        self.d_grads = [g.derivative() for g in self.grads]

    @staticmethod
    def _centred(direct: arb, mid: arb, parts: list[arb], offsets: list[arb]) -> arb:
        c = mid
        for g, o in zip(parts, offsets):
            c += g * o
        if not c.is_finite():
            return direct
        return direct.intersection(c) if direct.overlaps(c) else c

    def __call__(self, x: arb) -> tuple[arb, arb]:
        value = self._centred(self.direct(x), self.mid(x), [g(x) for g in self.grads], self.offsets)
        deriv = self._centred(self.d_direct(x), self.d_mid(x), [g(x) for g in self.d_grads], self.offsets)
        return value, deriv


def system_box_roots(model: SystemModel, box: Box, stability: bool = False) -> tuple[list[arb] | None, str, bool]:
    """(balls omega_1 < ... < omega_m, each holding exactly one root of Q for every member of the box, all
    certainly positive, or None; the reason; whether the structure fails for every member, a refutation).

    The coefficients are exact polynomials in the box's parameters (:func:`.system_symbolic.characteristic_mpolys`):
    lambda^z divides P for every member when c_0 .. c_(z-1) are the zero polynomial and c_z excludes 0 on the box;
    P is even when every odd coefficient above is the zero polynomial. The family Q~(omega; p) is evaluated in
    centred form about the box's midpoint (exact there), its roots verified by one interval Newton step each from
    the midpoint's exact roots. ``stability``: claim stability's roots instead, for which an over-declared
    zero_roots is no refutation (:func:`.system_claims.stability_at_multiplicity`): where lambda = 0 has one
    multiplicity mu < zero_roots for every member (the lower coefficients the zero polynomial, c_mu excluding 0),
    the roots of P / lambda^mu."""
    z, n = model.zero_roots, model.n
    names = box.names
    values = _values(model, box)
    key = ("mpolys", names, tuple(sorted((k, v) for k, v in values.items() if k not in names)))
    if key not in model.exact:           # the same for every box over these parameters: computed once
        try:
            model.exact[key] = characteristic_mpolys(model, names, values)
        except ZeroDivisionError:
            model.exact[key] = None
    if model.exact[key] is None:
        return None, "an entry divides by an identically zero expression on this box", False
    ctx, c, factors = model.exact[key]
    balls = [box.ball(k) for k in names]
    if not all(certainly_nonzero(mpoly_ball(L, balls)) for L in factors):
        return None, "an entry's denominator is not certainly nonzero on this box", False
    low = [k for k in range(z) if not c[k].is_zero()]
    if stability and low and certainly_nonzero(mpoly_ball(c[low[0]], balls)):
        z, low = low[0], []          # mu = low[0] < zero_roots for every member: the declared roots exempt all
    if low:
        if stability:       # mu < zero_roots somewhere, not one mu for the whole box: no refutation from it (review)
            return None, (f"the multiplicity of lambda = 0 is below zero_roots = {z} but not known to be one number on the "
                          f"whole box (the coefficient of lambda^{low[0]} may vanish in it)"), False
        sure = [k for k in low if certainly_nonzero(mpoly_ball(c[k], balls))]
        if sure:
            return None, (f"lambda^{z} does not divide P for any parameter in the box (the coefficient of lambda^{sure[0]} "
                          "is certainly nonzero): zero_roots is not the model's"), True
        return None, f"lambda^{z} divides P only where the coefficient of lambda^{low[0]} vanishes", False
    if not certainly_nonzero(mpoly_ball(c[z], balls)):
        return None, f"lambda = 0 may have multiplicity above {z} somewhere in the box", False
    odd = [k for k in range(z + 1, 2 * n + 1, 2) if not c[k].is_zero()]
    if odd:
        if any(certainly_nonzero(mpoly_ball(c[k], balls)) for k in odd):
            return None, (f"P / lambda^{z} has an odd term (lambda^{odd[0]}) for every parameter in the box: some root has "
                          "a nonzero real part (damping)"), True
        return None, "odd terms of P vanish only somewhere in the box", False
    q = [c[z + 2 * k] * (-1) ** k for k in range((2 * n - z) // 2 + 1)]
    fam = _Family(q, names, box)
    Q0 = fmpq_poly(fam.exact)
    if Q0.degree() != len(q) - 1:
        return None, "the midpoint's frequency polynomial has a lower degree", False
    mid = isolate_polynomial(Q0)
    if not (mid.squarefree and mid.verified) or mid.nonreal or not all(certainly_positive(x) for x in mid.real):
        return None, "the midpoint's frequency polynomial has no m real positive simple roots (its point proof decides)", False
    leading = fam._centred(fam.direct.coeffs()[-1], fam.mid.coeffs()[-1], [g.coeffs()[-1] if g.degree() == len(q) - 1
                                                                             else arb(0) for g in fam.grads], fam.offsets)
    roots = family_real_roots(fam, mid.real, leading=leading)
    if roots is None:
        return None, "the family's roots were not separated on this box", False
    if not all(certainly_positive(x) for x in roots):
        return None, "a root ball is not certainly positive on this box", False
    return roots, (f"{len(roots)} disjoint positive root balls, each verified by one interval Newton step for every "
                   f"parameter in the box (the coefficients exact polynomials in {list(names)}, centred form; "
                   f"lambda^{z} and the evenness exact)"), False


def evaluate_system_box(model: SystemModel, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box, status 'proved', 'refuted' or 'undecided' (module docstring)."""
    unknown = [c for c in claims if c not in SYSTEM_BOX_CLAIMS]
    if unknown:
        raise ParameterError(f"claim {unknown[0]!r} cannot be decided over a box; a [system] scene decides "
                             f"{list(SYSTEM_BOX_CLAIMS)} over boxes")
    roots, why, fails = system_box_roots(model, box)
    out: dict[str, tuple[str, str]] = {}
    for cid in claims:
        if cid in ("roots", "stability"):
            r, w, f = (system_box_roots(model, box, stability=True) if cid == "stability" and fails
                       else (roots, why, fails))
            out[cid] = ("proved", w) if r is not None else (("refuted" if f else "undecided"), w)
        elif cid == "brackets":
            out[cid] = _brackets(model, box, roots)
    return out


def _dual_sqrt(v):
    return (v if hasattr(v, "grad") else constant(v)).sqrt()


_DUAL_FUNCTIONS = {"sqrt": _dual_sqrt}


def _bound(e, env: dict, dual_env: dict, mid_env: dict, offsets: dict) -> arb:
    """A ball containing the bracket bound e(p) for every p in the box: the direct evaluation on the box's
    balls, intersected with the centred form e(mid) + grad e(box) . (p - mid) (Duals) where it is enclosed.
    NotRealBound when the direct evaluation takes the square root of a certainly negative ball."""
    direct = ball_value(e, env)
    try:
        d = e.evaluate(dual_env, functions=_DUAL_FUNCTIONS)
        if not hasattr(d, "grad"):
            return direct
        c = ball_value(e, mid_env)
        for k, o in offsets.items():
            g = d.grad.get(k)
            if g is not None:
                c += g * o
    except (NotDifferentiable, ZeroDivisionError, TypeError, NotRealBound):
        return direct
    if not c.is_finite():
        return direct
    return direct.intersection(c) if direct.overlaps(c) else c


def _brackets(model: SystemModel, box: Box, roots: list[arb] | None) -> tuple[str, str]:
    failed: dict = {}
    env = _env(model, box, failed=failed)
    mid_env = _env(model, box, _values(model, box), failed={})
    dual_env: dict = {}
    offsets: dict[str, arb] = {}
    for k, x in model.params.items():
        if k in box.names and box.interval(k)[1] > box.interval(k)[0]:
            dual_env[k] = variable(k, box.ball(k))
            offsets[k] = box.ball(k) - mid_env[k]
        else:
            dual_env[k] = _values(model, box)[k]
    try:
        for name, e in model.defs:
            dual_env[name] = e.evaluate(dual_env, functions=_DUAL_FUNCTIONS)
    except (NotDifferentiable, ZeroDivisionError, TypeError, NotRealBound, KeyError):
        dual_env = {}
    fails, open_ = [], []
    for j, (lo_e, hi_e) in enumerate(model.brackets, start=1):
        try:
            used = [name for name, _ in model.defs_needed((lo_e, hi_e)) if name in failed]
            if used:
                raise failed[used[0]]
            if dual_env and all(name in mid_env for name, _ in model.defs_needed((lo_e, hi_e))):
                lo, hi = (_bound(e, env, dual_env, mid_env, offsets) for e in (lo_e, hi_e))
            else:
                lo, hi = ball_value(lo_e, env), ball_value(hi_e, env)
        except NotRealBound as e:
            fails.append(f"omega_{j}: no real value anywhere in the box ({e})")
            continue
        if roots is None:
            open_.append(f"omega_{j}")
            continue
        w = roots[j - 1]
        if certainly_gt(lo, w) or certainly_gt(w, hi):
            fails.append(f"omega_{j} outside its bracket for every parameter in the box")
        elif not (certainly_le(lo, w) and certainly_le(w, hi)):
            open_.append(f"omega_{j}")
    if fails:
        return "refuted", "; ".join(fails)
    if open_:
        return "undecided", f"{', '.join(open_)} against its bracket undecided on this box"
    return "proved", f"lo_j <= omega_j <= hi_j for every parameter in the box, j = 1..{len(model.brackets)}"
