"""The claims of a ``[system]`` scene (:mod:`.system_model`) over a box of its parameters (tolerances).

Every parameter of the box becomes a ball containing its interval; the ``defs`` and the matrix entries are
evaluated on balls, and det(lambda^2 M + lambda (G + D) + K) is expanded along rows over ``arb_poly`` entries
(Laplace, memoised): its coefficient balls contain the coefficients of every member of the family. Two facts are
read from the model's structure, never from balls (a ball can contain 0 without the coefficient being 0):

* lambda^z divides P for every member when K has at least z rows whose entries are the constant 0 (each such
  row of lambda^2 M + lambda C + K is divisible by lambda): the z lowest coefficients are exactly 0;
* P is even for every member when D is absent (or all its entries are the constant 0): P(-lambda) is the
  determinant of the transpose.

The frequency family Q(omega) (lambda^2 = -omega) then has ball coefficients, and its m roots are verified for
all members at once by one interval Newton step each (:func:`rigor_gyro.core.family_roots.family_real_roots`,
the midpoint's exact roots as guesses, the leading coefficient det M certainly nonzero): m disjoint balls, each
holding exactly one root of every member, all the roots.

Guarantee: ``proved`` means the claim holds for every parameter value in the box; ``refuted`` (brackets only)
that a bracket fails for every value of the box (its bound's ball certainly beyond the root's, or a square root
of a certainly negative ball); ``undecided`` says neither was certified (the paving splits the box; its point
proofs refute where a point fails). ``roots`` over a box states real, positive, simple roots for every member,
without the point claim's relative width. Where the structure does not certify the zero roots or the evenness,
every claim is undecided, with that reason.

Precision: the caller's working precision; the box width dominates.

Fails when: a box edge is not a parameter of the scene: ParameterError naming it.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb, arb_poly, fmpq

from ...core.balls import certainly_gt, certainly_le, certainly_nonzero, certainly_positive
from ...core.boxes import Box
from ...core.dual_balls import NotDifferentiable, constant, variable
from ...core.errors import ParameterError
from ...core.family_roots import family_real_roots
from ...core.polyroots import isolate_polynomial
from .system_claims import SYSTEM_CLAIMS, polynomial_facts
from .system_model import NotRealBound, SystemModel, ball_value

__all__ = ["SYSTEM_BOX_CLAIMS", "validate_system_box", "evaluate_system_box", "system_box_roots"]

#: the claims a [system] scene decides over a box, with what each states at every point of it
SYSTEM_BOX_CLAIMS = {
    "roots": "For every parameter value in the box, the characteristic polynomial is lambda^z times an even polynomial "
             "whose frequency polynomial Q(omega) has only real, positive, simple roots.",
    "stability": SYSTEM_CLAIMS["stability"],
    "brackets": SYSTEM_CLAIMS["brackets"],
}


def validate_system_box(model: SystemModel, box: Box) -> None:
    """Every edge of the box names a parameter of the scene (not a def), and the symmetry of M, K, D and the
    skew-symmetry of G hold for every member of the box, not only at the midpoint where the scene was
    validated: a mirrored pair of entries that depends on a toleranced parameter (directly or through a def)
    must be written alike (G: one the negation of the other). ParameterError naming the pair otherwise."""
    bad = [n for n in box.names if n not in model.params]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: a [system] scene takes tolerances only on its parameters "
                             f"{sorted(model.params)}")
    moving = _moving_names(model, set(box.names))
    for key, sign in (("M", 1), ("K", 1), ("D", 1), ("G", -1)):
        rows = getattr(model, key)
        if rows is None:
            continue
        for i in range(model.n):
            for j in range(i, model.n):
                a, b = rows[i][j], rows[j][i]
                if not (a.names() | b.names()) & moving:
                    continue            # fixed on the box: checked exactly at validation
                if not _mirrored(a.tree, b.tree, sign):
                    what = "alike" if sign > 0 else "as each other's negation (and a zero diagonal)"
                    raise ParameterError(f"[system] {key}[{i + 1}][{j + 1}] = {a.text!r} and {key}[{j + 1}][{i + 1}] = "
                                         f"{b.text!r} depend on a toleranced parameter: write them {what}, so that "
                                         f"{key} stays {'symmetric' if sign > 0 else 'skew-symmetric'} on the whole box")


def _moving_names(model: SystemModel, varied: set[str]) -> set[str]:
    """The toleranced parameters and the defs that depend on them."""
    out = set(varied)
    for name, e in model.defs:
        if e.names() & out:
            out.add(name)
    return out


def _mirrored(a: tuple, b: tuple, sign: int) -> bool:
    """Whether the entries are identically equal (sign 1) or opposite (sign -1), read from their trees."""
    if sign > 0:
        return a == b
    return a == ("neg", b) or b == ("neg", a)


def _env(model: SystemModel, box: Box) -> dict[str, arb]:
    env = {k: (box.ball(k) if k in box.names else arb(x.rational.numerator) / x.rational.denominator)
           for k, x in model.params.items()}
    for name, e in model.defs:
        env[name] = ball_value(e, env)
    return env


def _pmul(p: list, q: list) -> list:
    out = [0] * (len(p) + len(q) - 1) if p and q else []
    for i, x in enumerate(p):
        if _zero(x):
            continue
        for j, y in enumerate(q):
            if not _zero(y):
                out[i + j] = out[i + j] + x * y
    return out


def _padd(p: list, q: list, sign: int) -> list:
    out = list(p) + [0] * max(0, len(q) - len(p))
    for j, y in enumerate(q):
        if not _zero(y):
            out[j] = out[j] + y if sign > 0 else out[j] - y
    return out


def _zero(x) -> bool:
    return isinstance(x, int) and x == 0


def _det_duals(entries: list[list[list]], n: int) -> list:
    """Coefficients (Duals, or exact 0) of the determinant of a matrix of polynomials (coefficient lists of
    Duals), by Laplace expansion along rows, memoised on the columns used."""
    memo: dict[int, list] = {}

    def minor(row: int, used: int) -> list:
        if row == n:
            return [1]
        if used in memo:
            return memo[used]
        total, sign = [], 1
        for col in range(n):
            if used >> col & 1:
                continue
            e = entries[row][col]
            if any(not _zero(x) for x in e):
                total = _padd(total, _pmul(e, minor(row + 1, used | (1 << col))), sign)
            sign = -sign
        memo[used] = total
        return total
    c = minor(0, 0)
    return c + [0] * (2 * n + 1 - len(c))


def _duals(model: SystemModel, box: Box):
    """(Duals of P's coefficients over the box, or exact 0 / Fraction where constant; the offsets of the box's
    parameters from the midpoint) by forward-mode AD in balls (:mod:`rigor_gyro.core.dual_balls`); None where
    an entry's derivative is not enclosed (a division by a ball around 0)."""
    env: dict = {}
    offsets: dict[str, arb] = {}
    for k, x in model.params.items():
        if k in box.names and box.interval(k)[1] > box.interval(k)[0]:
            ball = box.ball(k)
            env[k] = variable(k, ball)
            offsets[k] = ball - arb(fmpq(x.rational.numerator, x.rational.denominator))
        else:
            env[k] = x.rational
    for name, e in model.defs:
        if name in model.values:          # the rational defs (the matrices use no other)
            env[name] = e.evaluate(env)

    def entry(which: str, i: int, j: int):
        rows = getattr(model, which)
        if rows is None:
            return 0
        v = rows[i][j].evaluate(env)
        return 0 if isinstance(v, Fraction) and v == 0 else v
    n = model.n
    try:
        entries = [[[entry("K", i, j), _padd([entry("G", i, j)], [entry("D", i, j)], 1)[0], entry("M", i, j)]
                    for j in range(n)] for i in range(n)]
        return _det_duals(entries, n), offsets
    except (NotDifferentiable, ZeroDivisionError, TypeError):
        return None


def _frequency_family(model: SystemModel, box: Box):
    """The family Q(omega; p), p in the box, of monic-normalised frequency polynomials (q_k = (-1)^k
    c_(z+2k) / c_2n, the same normalisation at every p, so a common factor of the parameters cancels), as
    :data:`rigor_gyro.core.family_roots.Family`: at an exact omega its value is enclosed in centred form
    Q(omega; mid) (exact) + sum_i dQ/dp_i(omega; box) (p_i - mid_i), intersected with the direct enclosure
    from the coefficient balls; the derivative from the coefficient balls. None when not enclosed."""
    got = _duals(model, box)
    if got is None:
        return None
    duals, offsets = got
    n, z = model.n, model.zero_roots
    lead = duals[2 * n]
    P_mid = model.characteristic().coeffs()
    if _zero(lead) or len(P_mid) != 2 * n + 1:
        return None
    dual_lead = hasattr(lead, "grad")
    if dual_lead and not certainly_nonzero(lead.value):
        return None
    idx = [(z + 2 * k, (-1) ** k) for k in range((2 * n - z) // 2 + 1)]
    exact, direct, grads = [], [], {k: [] for k in offsets}
    for i, sign in idx:
        d = duals[i]
        exact.append(sign * P_mid[i] / P_mid[-1])
        if i == 2 * n:
            direct.append(arb(sign))
            for k in offsets:
                grads[k].append(arb(0))
            continue
        if _zero(d):
            q = None
        elif dual_lead or hasattr(d, "grad"):
            q = d / lead
        else:
            q = None                       # both constant: the exact midpoint value is every member's
        if q is None or not hasattr(q, "grad"):
            direct.append(arb(exact[-1]))
            for k in offsets:
                grads[k].append(arb(0))
            continue
        direct.append(sign * q.value)
        for k in offsets:
            g = q.grad.get(k)
            grads[k].append(arb(0) if g is None else sign * g)
    if not all(c.is_finite() for c in direct) or not all(c.is_finite() for g in grads.values() for c in g):
        return None
    P, P0 = arb_poly(direct), arb_poly([arb(c) for c in exact])
    dP, dP0 = P.derivative(), P0.derivative()
    G = {k: arb_poly(g) for k, g in grads.items()}
    dG = {k: g.derivative() for k, g in G.items()}

    def centred(direct_value: arb, mid_value: arb, parts) -> arb:
        c = mid_value
        for k, o in offsets.items():
            c += parts[k] * o
        if not c.is_finite():
            return direct_value
        return direct_value.intersection(c) if direct_value.overlaps(c) else c

    def family(x: arb) -> tuple[arb, arb]:
        value = centred(P(x), P0(x), {k: G[k](x) for k in offsets})
        deriv = centred(dP(x), dP0(x), {k: dG[k](x) for k in offsets})
        return value, deriv
    return family, arb(direct[-1])


def _structural_zero_rows(model: SystemModel) -> int:
    return sum(1 for row in model.K if all(e.is_constant() and e.evaluate({}) == 0 for e in row))


def _undamped(model: SystemModel) -> bool:
    return model.D is None or all(e.is_constant() and e.evaluate({}) == 0 for row in model.D for e in row)


def system_box_roots(model: SystemModel, box: Box) -> tuple[list[arb] | None, str]:
    """(balls omega_1 < ... < omega_m, each holding exactly one root of Q for every member of the box, all
    certainly positive; or None) and the reason."""
    z = model.zero_roots
    if _structural_zero_rows(model) < z:
        return None, (f"over a box, the zero_roots = {z} roots lambda = 0 must come from rows of K that are the "
                      "constant 0 (a ball cannot show a coefficient is exactly 0)")
    if not _undamped(model):
        return None, "over a box, D must be absent (P even for every member); a damped system is decided at points"
    _, mu, Q0, _ = polynomial_facts(model)        # the box's midpoint, exactly: the guesses
    if Q0 is None:
        return None, "the midpoint's characteristic polynomial is not lambda^z times an even polynomial"
    mid = isolate_polynomial(Q0)
    if not (mid.squarefree and mid.verified) or mid.nonreal or not all(certainly_positive(x) for x in mid.real):
        return None, "the midpoint's frequency polynomial has no m real positive simple roots (its point proof decides)"
    fam = _frequency_family(model, box)
    if fam is None:
        return None, ("the coefficients are not enclosed on this box (a division by a ball around 0, or det M not "
                      "certainly nonzero)")
    roots = family_real_roots(fam[0], mid.real, leading=fam[1])
    if roots is None:
        return None, "the family's roots were not separated on this box"
    if not all(certainly_positive(x) for x in roots):
        return None, "a root ball is not certainly positive on this box"
    return roots, (f"{len(roots)} disjoint positive root balls, each verified by one interval Newton step for every "
                   f"parameter in the box (leading coefficient certainly nonzero; lambda^{z} from K's zero rows, "
                   "evenness from D = 0)")


def evaluate_system_box(model: SystemModel, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box, status 'proved', 'refuted' or 'undecided' (module docstring)."""
    unknown = [c for c in claims if c not in SYSTEM_BOX_CLAIMS]
    if unknown:
        raise ParameterError(f"claim {unknown[0]!r} cannot be decided over a box; a [system] scene decides "
                             f"{list(SYSTEM_BOX_CLAIMS)} over boxes")
    roots, why = system_box_roots(model, box)
    out: dict[str, tuple[str, str]] = {}
    for cid in claims:
        if cid in ("roots", "stability"):
            out[cid] = ("proved", why) if roots is not None else ("undecided", why)
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
    env = _env(model, box)
    mid_env = _env(model, Box(()))
    dual_env: dict = {}
    offsets: dict[str, arb] = {}
    for k, x in model.params.items():
        if k in box.names and box.interval(k)[1] > box.interval(k)[0]:
            dual_env[k] = variable(k, box.ball(k))
            offsets[k] = box.ball(k) - mid_env[k]
        else:
            dual_env[k] = x.rational
    try:
        for name, e in model.defs:
            dual_env[name] = e.evaluate(dual_env, functions=_DUAL_FUNCTIONS)
    except (NotDifferentiable, ZeroDivisionError, TypeError):
        dual_env = {}
    fails, open_ = [], []
    for j, (lo_e, hi_e) in enumerate(model.brackets, start=1):
        try:
            if dual_env:
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
