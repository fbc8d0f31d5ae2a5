"""``orbit_genuine`` and ``stable`` of a ``[plant]`` relay model over a box of its parameters (issue 42 part 1,
tolerance boxes).

What: the entries of M, e, c, S and h are the scene's expressions in its named parameters; over a box they
are evaluated in Arb balls containing their values for every member (:func:`plant_balls`). A
:class:`PlantBoxSpectrum` is the :class:`.plant_orbit.PlantSpectrum` of the whole box: the characteristic
polynomial's coefficients and the Krylov numerators' coefficients (the formula of :func:`.plant_model.numerators`)
in centred (mean-value) form in the parameters (:mod:`.plant_centred`: forward-mode derivatives in balls through
the entries' expressions and the Faddeev-LeVerrier recurrence), each intersected with the naive one from the
ball matrix (``arb_mat.charpoly``); each eigenvalue enclosed for every member by one interval Newton proof over
the coefficient family (:mod:`rigor_gyro.core.family_roots`; the centre's exact roots only guide it), the
residues N(lambda)/p'(lambda) on those balls. The point path's functions then run unchanged on it (every
enclosure they compute contains the value for every member):

1. theta*(P): the centre's genuine root (the point analysis at the box's midpoint) is re-enclosed for every
   member by interval Newton on g over Theta x box: N = t_c - g(t_c; box) / g'(Theta; box) inside Theta
   proves that every member has exactly one root of g in Theta (member by member: the mean value theorem);
   g(t_c; box) in centred form in the parameters (:func:`g_parametric`: the implicit-function derivatives of
   the eigenvalues and residues), g' over Theta x box by a Taylor form about Theta's midpoint
   (:func:`.flow.taylor_enclosure`).
2. orbit_genuine: :func:`.plant_claims.classify` on the box spectrum and Theta: c . x(t) + h > 0 on
   (0, theta*(P)) for every member (its enclosures hold every theta in Theta and every member).
3. stable: :func:`.plant_claims.plant_multipliers` on the box spectrum: Rump's method on the ball Jacobian
   (every member's), each modulus certainly < 1; where that does not isolate the multipliers, the Gershgorin
   bound of :mod:`.norm_stability` on the same ball Jacobian (:func:`disc_bound`).

A zero eigenvalue is kept over the box only where it is structural (a column or row of M whose entries are
all the constant 0, so det M = 0 for every member); a zero eigenvalue at the centre that is not structural
leaves the box undecided.

Guarantee: ``proved`` means that for every parameter value in the box some genuine symmetric orbit exists
(``orbit_genuine``), some genuine orbit has every multiplier modulus < 1 (``stable``). A box that these
sufficient tests do not decide is ``undecided`` (never refuted). Precision: the caller's (the paving's
``box_prec``). The polynomial data and g(t_c) are centred in the parameters, the rest (g', the sign condition,
the Jacobian) naive in the eigenvalue and residue balls: on the Roitenberg plant all six parameters at +-1e-5
relative are decided (naive: nothing at +-1e-6), all six at +-1e-4 for orbit_genuine, H alone at +-1e-4
(naive: +-1e-6); theta*'s ball over H +-1e-6 is 2.1e-7 wide (naive 5.6e-5). Fails when: an entry has no finite value over the box (a division by a
ball containing 0): ParameterError from :func:`validate_plant_box`.
"""
from __future__ import annotations

import dataclasses

from flint import acb, acb_poly, arb, arb_mat, fmpq, fmpq_poly

from ...core.balls import ball, certainly_lt, certainly_negative, certainly_nonzero, certainly_positive
from ...core.boxes import Box
from ...core.errors import ParameterError
from ...core.expressions import evaluate_exact, parse as parse_expression
from ...core.family_roots import newton_family_root, newton_family_root_complex, polynomial_family
from ...core.polyroots import isolate_polynomial
from .flow import DegenerateSpectrum, taylor_enclosure
from .plant_centred import centred_polynomial_data, centred_scalar
from .plant_claims import analyse, classify, plant_multipliers
from .plant_model import PlantModel
from .norm_stability import eigen_coordinate_family, largest_modulus_range
from .plant_orbit import PlantMode, PlantSpectrum, g_coeffs, jacobian, section_index
from .plant_statements import TAYLOR_ORDER
from .texts import upper_text

__all__ = ["PLANT_BOX_CLAIMS", "PlantBoxSpectrum", "plant_balls", "validate_plant_box", "evaluate_plant_box"]

PLANT_BOX_CLAIMS = ("orbit_genuine", "stable")


def _exprs(model: PlantModel):
    names = set(model.exact)
    t = model.table
    parse = lambda v, w: parse_expression(v, f"[plant] {w}", names=names)     # noqa: E731
    M = [[parse(x, f"M[{i + 1}][{j + 1}]") for j, x in enumerate(r)] for i, r in enumerate(t["M"])]
    e = [parse(x, f"e[{i + 1}]") for i, x in enumerate(t["e"])]
    c = [parse(x, f"c[{i + 1}]") for i, x in enumerate(t["c"])]
    return M, e, c, parse(t.get("S", "1"), "S"), parse(t.get("h", "0"), "h")


def plant_balls(model: PlantModel, box: Box):
    """(M, e, c, S, h) as balls containing their values for every member of the box (the other parameters at
    the model's exact values)."""
    env = {k: (box.ball(k) if k in box.names else ball(fmpq(ex.rational.numerator, ex.rational.denominator)))
           for k, ex in model.exact.items()}
    num = lambda q: arb(fmpq(q.numerator, q.denominator))      # noqa: E731
    M, e, c, S, h = _exprs(model)
    ev = lambda x: arb(x.evaluate(env, number=num))            # noqa: E731
    return arb_mat([[ev(x) for x in r] for r in M]), [ev(x) for x in e], [ev(x) for x in c], ev(S), ev(h)


def structural_zero_eigenvalue(model: PlantModel) -> bool:
    """Whether M has a column or a row of constant zeros (then det M = 0 for every parameter value)."""
    M = _exprs(model)[0]
    zero = lambda x: x.is_constant() and evaluate_exact(x, {}) == 0      # noqa: E731
    n = len(M)
    return any(all(zero(M[i][j]) for i in range(n)) for j in range(n)) or any(all(zero(x) for x in r) for r in M)


def validate_plant_box(model: PlantModel, box: Box) -> None:
    """ParameterError unless every box parameter is a parameter of the plant and every entry is finite over the box."""
    bad = [k for k in box.names if k not in model.exact]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: not a parameter of this [plant] scene")
    M, e, c, S, h = plant_balls(model, box)
    n = M.nrows()
    vals = [M[i, j] for i in range(n) for j in range(n)] + e + c + [S, h]
    if not all(v.is_finite() for v in vals):
        raise ParameterError("[plant]: an entry has no finite value on the whole box (a division by a parameter "
                             "interval containing 0?)")
    if model.h == 0 and not _exprs(model)[4].is_constant():
        raise ParameterError("[plant] h: zero at the box's midpoint but not a constant: write h = \"0\" or a width > 0 "
                             "on the whole box")
    if model.h != 0 and not certainly_positive(h):
        raise ParameterError("[plant] h: the hysteresis width must be > 0 on the whole box")


def _krylov_numerators(M: arb_mat, e: list[arb], p: list[arb]) -> list[list[arb]]:
    """Coefficients of N_i(z) = adj(z I - M) e for the ball matrix M (the formula of plant_model.numerators)."""
    n = len(e)
    krylov = [arb_mat([[x] for x in e])]
    for _ in range(n - 1):
        krylov.append(M * krylov[-1])
    coeffs = [[arb(0)] * n for _ in range(n)]
    for k in range(n):
        for i in range(k + 1, n + 1):
            v = krylov[i - k - 1]
            for r in range(n):
                coeffs[r][k] += p[i] * v[r, 0]
    return coeffs


class PlantBoxSpectrum(PlantSpectrum):
    """The spectrum and residues of every member of the box (module docstring). ``model``: the centre's model
    (exact data, for the shapes, the root guesses and h = 0 or not). DegenerateSpectrum when the eigenvalues
    are not separated over the box."""

    def __init__(self, model: PlantModel, box: Box):
        self.model = model
        n = model.n
        M, e, c, S, h = plant_balls(model, box)
        P = M.charpoly()
        p = [P[k] for k in range(n + 1)]
        Mx, ex, cx, Sx, hx = _exprs(model)
        exact = {k: v.rational for k, v in model.exact.items()}
        self.grads: dict | None = {}
        cd = centred_polynomial_data((Mx, ex, cx), exact, box, self.grads)
        self.box = box
        self.scalars = (centred_scalar(Sx, exact, box), centred_scalar(hx, exact, box))
        if cd is None or any(x is None for x in self.scalars):
            self.grads = None
        if cd is not None:          # the centred coefficients (each also the naive one's intersection)
            p = [_meet(a, b) for a, b in zip(p, cd[0])]
        zero = model.zero_eigenvalue
        if zero and not structural_zero_eigenvalue(model):
            raise DegenerateSpectrum("a zero eigenvalue at the centre that is not structural (a zero row or column "
                                     "of M): not kept over the box")
        if not zero and not certainly_nonzero(p[0]):
            raise DegenerateSpectrum("det M may vanish on the box")
        qc = p[1:] if zero else p                 # the coefficients whose roots are the nonzero eigenvalues
        centre = model.charpoly
        qexact = fmpq_poly([centre[k] for k in range(1, n + 1)]) if zero else centre
        guesses = isolate_polynomial(qexact)
        if not (guesses.verified and guesses.squarefree):
            raise DegenerateSpectrum("the centre's eigenvalues are not isolated")
        family = polynomial_family(qc)
        real = [newton_family_root(family, g) for g in guesses.real]
        upper = [newton_family_root_complex(qc, z) for z in guesses.nonreal if certainly_positive(z.imag)]
        if any(r is None for r in real + upper) or len(real) + 2 * len(upper) != len(qc) - 1:
            raise DegenerateSpectrum("the eigenvalues were not separated on this box")
        if not all(certainly_positive(z.imag) for z in upper):
            raise DegenerateSpectrum("a complex eigenvalue's imaginary part may vanish on this box")
        for i in range(len(real)):
            for j in range(i + 1, len(real)):
                if real[i].overlaps(real[j]):
                    raise DegenerateSpectrum("two real eigenvalues overlap on this box")
        if zero and not certainly_nonzero(p[1]):
            raise DegenerateSpectrum("the zero eigenvalue may not be simple on this box")
        Ns = _krylov_numerators(M, e, p)
        Nc = [sum((c[i] * Ns[i][k] for i in range(n)), arb(0)) for k in range(n)]
        if cd is not None:
            Ns = [[_meet(a, b) for a, b in zip(r, s)] for r, s in zip(Ns, cd[1])]
            Nc = [_meet(a, b) for a, b in zip(Nc, cd[2])]
        dp = acb_poly([acb(k * p[k]) for k in range(1, n + 1)])
        Nsp = [acb_poly([acb(x) for x in N]) for N in Ns]
        Ncp = acb_poly([acb(x) for x in Nc])
        self.modes = []
        for lam, w in [(acb(x), 1) for x in real] + [(z, 2) for z in upper]:
            if certainly_negative(lam.real):
                sg = -1
            elif certainly_positive(lam.real):
                sg = 1
            else:
                raise DegenerateSpectrum("the real part of an eigenvalue is not separated from 0 on this box")
            d = dp(lam)
            self.modes.append(PlantMode(lam, w, sg, Ncp(lam) / d, [N(lam) / d for N in Nsp]))
        self.S, self.h = S, h
        if zero:
            d0 = p[1]
            self.r0c, self.r0x = Nc[0] / d0, [N[0] / d0 for N in Ns]
        else:
            self.r0c, self.r0x = arb(0), [arb(0)] * n
        self.M, self.e, self.c = M, e, c
        self.p, self.Nc = p, Nc


def _horner(coeffs, z: acb) -> acb:
    out = acb(0)
    for c in reversed(coeffs):
        out = out * z + c
    return out


def _derivative(coeffs) -> list:
    return [k * coeffs[k] for k in range(1, len(coeffs))]


def g_parametric(sp: PlantBoxSpectrum, t: arb) -> arb | None:
    """g(t; P) at an exact t for every member of the box, in centred form in the parameters:
    g(t; P0) + sum_j dg/dP_j(box) (P_j - P0_j), P0 the box's exact midpoint (its own spectrum), intersected with
    the naive g(t; box). g = -Re(t r0c S/2 + h + sum_m w sigma S rc_m Th_m / lambda_m), Th = (1 - E)/(1 + E) =
    tanh(sigma lambda t/2); the derivatives over the box by the implicit function theorem on each simple
    eigenvalue (d lambda = -(d_j p)(lambda)/p'(lambda), the family Newton proof's uniqueness makes lambda(P) the
    continuous branch in its ball), d rc from rc = Nc(lambda)/p'(lambda), d r0c from Nc_0/p_1, dTh/d lambda =
    (sigma t/2)(1 - Th^2), d S and d h from the entries' expressions (:mod:`.plant_centred`). None when a part is
    not enclosed (the caller keeps the naive g)."""
    if sp.grads is None or not sp.grads:
        return None
    box = sp.box
    mid = box.midpoint()
    try:
        centre = PlantBoxSpectrum(sp.model, Box(tuple((k, mid[k], mid[k]) for k in box.names)))
    except DegenerateSpectrum:
        return None
    g0 = g_coeffs(centre, t, 1, pole_free=False)[0]
    naive = g_coeffs(sp, t, 1, pole_free=False)[0]
    (Sv, Sg), (_, hg) = sp.scalars
    p, Nc = sp.p, sp.Nc
    dp, dNc = _derivative(p), _derivative(Nc)
    ddp = _derivative(dp)
    zero = sp.model.zero_eigenvalue
    tt = acb(t)
    out = g0
    for j, (gp, gN) in sp.grads.items():
        tot = acb(hg[j])
        if zero:
            r0c_j = (gN[0] - sp.r0c * gp[1]) / p[1]
            tot += t / 2 * (r0c_j * Sv + sp.r0c * Sg[j])
        gdp = _derivative(gp)
        for m in sp.modes:
            lam = m.lam
            d1 = _horner(dp, lam)
            lam_j = -_horner(gp, lam) / d1
            rc_j = (_horner(gN, lam) + _horner(dNc, lam) * lam_j) / d1 - m.rc * (_horner(gdp, lam) + _horner(ddp, lam) * lam_j) / d1
            E = (m.lam * tt).exp() if m.sigma < 0 else (-m.lam * tt).exp()     # |E| < 1: plant_orbit's E
            Th = (1 - E) / (1 + E)
            dTh = m.sigma * tt / 2 * (1 - Th * Th)
            tot += m.weight * m.sigma * (Sg[j] * m.rc * Th / lam + Sv * rc_j * Th / lam
                                         + Sv * m.rc * lam_j * (dTh / lam - Th / (lam * lam)))
        dg = -tot.real
        if not dg.is_finite():
            return None
        out = out + dg * (box.ball(j) - arb(fmpq(mid[j].numerator, mid[j].denominator)))
    if not out.is_finite():
        return None
    return _meet(naive, out) if naive.is_finite() else out


def _meet(a: arb, b: arb) -> arb:
    """The intersection of two balls that both contain the value (the tighter one if they do not overlap,
    which only rounding could make happen: both contain every member's value)."""
    if a.overlaps(b):
        return a.intersection(b)
    return a if a.rad() < b.rad() else b


def _theta_over_box(sp: PlantBoxSpectrum, tc_ball: arb) -> arb | None:
    """A ball Theta around the centre's root holding exactly one root of g for every member (interval Newton
    over the box, inflated from the centre's enclosure), or None."""
    tc = arb(tc_ball.mid())
    r = 2 * arb(tc_ball.rad()) + abs(tc) * arb(2) ** -40
    for _ in range(30):
        Theta = arb(tc, r.upper())
        if not certainly_positive(Theta):
            return None
        d = taylor_enclosure(lambda ctr, k: g_coeffs(sp, ctr, k, pole_free=False), Theta, TAYLOR_ORDER, (1,))[0]
        if not certainly_nonzero(d):
            return None
        gc = g_parametric(sp, tc) if isinstance(sp, PlantBoxSpectrum) else None
        N = tc - (gc if gc is not None else g_coeffs(sp, tc, 1, pole_free=False)[0]) / d
        if not N.is_finite():
            return None
        if certainly_lt(Theta.lower(), N.lower()) and certainly_lt(N.upper(), Theta.upper()):
            return N
        r = (2 * abs(N - tc).upper()).max(2 * r.upper())
    return None


def disc_bound(sp: PlantBoxSpectrum, v) -> arb | None:
    """A ball holding the largest multiplier modulus of every member (:mod:`.norm_stability`: the ball Jacobian J
    written as J_mid + (J - J_mid), J_mid its exact midpoint matrix, in J_mid's eigenvector coordinates), or None."""
    J = jacobian(sp.M, sp.e, sp.c, sp.S, v.theta, v.x0, section_index(sp.model))
    k = J.nrows()
    Jm = arb_mat([[arb(J[i, j].mid()) for j in range(k)] for i in range(k)])
    K = eigen_coordinate_family(Jm, [(J - Jm, arb(1))])
    return largest_modulus_range(K) if K is not None else None


def evaluate_plant_box(model: PlantModel, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box for ``orbit_genuine`` and ``stable`` (module docstring)."""
    out = {c: ("undecided", "") for c in claims}
    try:
        sp = PlantBoxSpectrum(model, box)
    except DegenerateSpectrum as e:
        return {c: ("undecided", f"over the box: {e}") for c in claims}
    an = analyse(dataclasses.replace(model, decided={}))
    genuine = [v for v in an.roots if v.kind == "genuine"]
    if "stable" in claims:
        genuine.sort(key=lambda v: v.stable is not True)
    why = "no genuine orbit at the box's midpoint" if not genuine else ""
    for v in genuine:
        Theta = _theta_over_box(sp, v.theta)
        if Theta is None:
            why = f"the centre's root {v.theta} not continued over the box by interval Newton"
            continue
        w = classify(sp, Theta)
        if w.kind != "genuine":
            why = f"theta*(P) in {Theta}: {w.reason}"
            continue
        head = (f"for every parameter in the box: g has exactly one root theta*(P) in {_fmt(Theta)} (interval "
                f"Newton over the box), genuine: {w.reason}")
        if "orbit_genuine" in claims and out["orbit_genuine"][0] != "proved":
            out["orbit_genuine"] = ("proved", head)
        if "stable" in claims and out["stable"][0] != "proved":
            plant_multipliers(sp, w)
            if w.stable is True and w.radius_bound is not None:     # the multipliers not isolated over the box
                out["stable"] = ("proved", head + f"; every multiplier modulus <= {upper_text(w.radius_bound)} < 1 (the "
                                 "Gershgorin discs of the Jacobian over the box; the multipliers are not isolated)")
                continue
            if w.stable is True:
                mx = w.moduli[0]
                for m in w.moduli[1:]:
                    mx = mx.max(m)
                out["stable"] = ("proved", head + f"; every multiplier modulus < 1 (largest in {_fmt(mx)}, Rump's "
                                 "method on the Jacobian over the box)")
                continue
            mx = disc_bound(sp, w)
            if mx is not None and certainly_lt(mx, 1):
                out["stable"] = ("proved", head + f"; every multiplier modulus < 1 (largest in {_fmt(mx)}: the "
                                 "Gershgorin discs of the Jacobian over the box in the midpoint's eigenvector coordinates)")
            else:
                why = f"the multipliers over the box: {w.multiplier_reason or 'a modulus not certainly < 1'}"
        if all(out[c][0] == "proved" for c in claims):
            break
    return {c: (st, r or f"not decided over the box: {why}") for c, (st, r) in out.items()}


def _fmt(x: arb, digits: int = 10) -> str:
    return f"[{x.lower().str(digits, radius=False)}, {x.upper().str(digits, radius=False)}]"
