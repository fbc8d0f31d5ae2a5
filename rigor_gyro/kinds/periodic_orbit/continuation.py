"""One symmetric orbit of the relay followed over a parameter box: theta*(P) as an implicit function, its
sign condition and its multipliers, all in centred forms (issue 37 part 1; the parametric Krawczyk / interval
Newton plan).

Given a box of the physical parameters (A, B, H, tau, sigma, n; S, p, K fixed, see :mod:`.boxes`), its centre
c and a root theta_c of g(., c) (from the point analysis at the centre):

1. theta*(P). With the jets of :mod:`.parametric`, for a candidate interval Theta around theta_c (a point),
   the parametric interval Newton operator N = theta_c - G0 / G_theta, where G0 = g(theta_c, c) +
   sum_k g_Pk(Theta x box) (P_k - c_k) contains g(theta_c, P) for every P (mean value theorem in P) and
   G_theta contains dg/dtheta on Theta x box. For each P, g(theta, P) = g(theta_c, P) + g_theta(xi, P)
   (theta - theta_c), so when G_theta excludes 0 and N lies inside Theta, g(., P) has exactly one root
   theta*(P) in Theta, and it lies in N (one-dimensional interval Newton, member by member). Its
   gradient over the box is enclosed as -g_P / g_theta over Theta x box (implicit function theorem), and
   theta* as theta*(c) + that gradient times the deviations (intersected with N). The root is the same
   continuous branch for every member: the one through theta_c.
   When these whole-box forms do not decide (their Hessian balls carry the complex-ball excess of
   exp(lambda theta), ~30x over A, B, H at +-1 %), step 1 runs again with G's derivatives enclosed as unions
   over cells of Theta x box (:mod:`.subbox_union`, ``SUBBOX_CELLS``): first the band Newton step
   (:func:`.subbox_union.band_root`: u = theta - tc - slope . (P - c) with the centre's tangent as slope, one
   Newton step in u over the whole box, its residual F(0, P) second order in the width), then uniqueness in
   the resulting Theta because dG/dtheta excludes 0 on Theta x box; failing that, the interval Newton and
   Krawczyk (preconditioner 1 / G_theta(c)) images over Theta, contracted while they narrow. Only the
   derivative bounds are subdivided: the Newton step is one step over the whole box.
2. orbit_genuine for every P: beta(t; P) > 0 on (0, theta*(P)), with beta(0) = beta(theta*(P)) = 0 exactly.
   beta(t; theta*(P), P) and beta'(t; ...) are enclosed on (t piece) x box by the centred form in (t, P) whose
   P-gradient is the total derivative (theta* a jet with its implicit gradient): beta' > 0 on [0, d1],
   beta' < 0 on [Theta_lo - d2, Theta_hi] (which holds [Theta_lo - d2, theta*(P)] for each P), beta > 0 on
   [d1, Theta_lo - d2] by bisection in t.
3. stable: the Jacobian of the half-period map J(theta*(P), P) in centred form, J(c) + sum_k (dJ/dP_k)
   (box) (P_k - c_k) with the total derivatives, and its eigenvalues for every member by Rump's method in
   the centre's eigenvector coordinates (:func:`.jacobian_box.eigen_coordinate_multipliers`) or on the
   ball matrix itself, the narrower; every modulus certainly < 1 proves the orbit stable for every P.
   Their product is checked against Liouville's -exp(-(1/tau + 1/sigma) theta*) over the box (a bug check).

Steps 2 and 3 over the whole box fall back to :mod:`.cellwise` (each parameter cell its own centre and jets,
every cell's root required inside the whole box's Theta) when they do not decide.

Guarantee: a returned :class:`OrbitOverBox` holds what it says for every parameter in the box; any step
that does not decide returns the reason (never a refutation: a failed sufficient test decides nothing).
Precision: the current working precision. Fails when: the cubic's roots are not isolated over the box,
Newton does not contract, or a sign is not certain: ``OrbitOverBox.problem`` says which.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from types import SimpleNamespace

from flint import acb, acb_mat, arb, arb_mat

from ...core.balls import certainly_lt, certainly_negative, certainly_nonzero, certainly_positive, interval
from ...core.jets import Jet, base, second_order_gradient, second_order_value
from .flow import DegenerateSpectrum, PARAMETER_NAMES, RelayParams
from .jacobian_box import centred_terms, eigen_coordinate_multipliers
from .parametric import RelayJets, nested_parameter_jets, nested_variable, parameter_jets
from .cellwise import decide_by_cells
from .subbox_union import band_root, gradient_union, split_counts
from .theta_fold import slope_ratio, slope_sign_change

__all__ = ["OrbitOverBox", "continue_orbit", "at_most_one_root", "MAX_PIECES"]

#: t pieces the sign condition may use on the middle of (0, theta*)
MAX_PIECES = 4000
#: cells of (theta, parameter) sub-boxes whose union encloses G's gradient when the whole-box form fails, in turn
SUBBOX_CELLS = (8, 32)


@dataclass
class OrbitOverBox:
    """What was certified over the box for the orbit continued from the centre's root theta_c."""

    theta_c: arb
    theta: arb | None = None                  # theta*(P) for every P
    theta_unique_in: arb | None = None        # g(., P) has no root but theta*(P) in this ball, for every P
    theta_method: str = ""                    # how theta*(P) was proved unique in ``theta``
    theta_gradient: list[arb] = field(default_factory=list)    # dtheta*/dP_k over the box, per direction
    genuine: bool = False
    genuine_reason: str = ""
    multipliers: list[acb] = field(default_factory=list)
    moduli: list[arb] = field(default_factory=list)
    max_modulus: arb | None = None
    stable: bool | None = None                # True: every modulus < 1 for every P; None: not decided
    problem: str = ""
    fold: str = ""                            # step 1 impossible: dG/dtheta(tc, P) = 0 for a member (theta_fold)
    slope_ratio: float | None = None          # where step 1 failed: theta_fold.slope_ratio (planning only)


def _fmt(x: arb, digits: int = 10) -> str:
    if not x.is_finite():
        return str(x)
    return f"[{x.lower().str(digits, radius=False)}, {x.upper().str(digits, radius=False)}]"


def _real_centred(centre: arb, box: Jet, devs: list[arb]) -> arb:
    """centre + sum grad_k dev_k (the real part), intersected with the direct value where both are finite."""
    out = centre
    for d, dev in zip(box.d, devs):
        out = out + d.real * dev
    v = box.v.real
    if v.is_finite() and out.is_finite():
        if not v.overlaps(out):
            raise AssertionError(f"a centred form {out} misses the direct enclosure {v}: a bug")
        return out.intersection(v)
    return out if out.is_finite() else v


class _Models:
    """The jets of one box: ``centre`` (first order, at the centre point: values and gradients there),
    ``box`` (first order over the box) and ``nested`` (second order over the box), each with the box's
    parameters as directions followed by one extra direction (theta, or t)."""

    def __init__(self, centre: RelayParams, box: dict[str, arb], dirs: list[str], guesses: list[acb]):
        self.dirs = dirs
        m = len(dirs) + 1
        self.m = m
        cvals = {k: _point(getattr(centre, k)) for k in PARAMETER_NAMES}
        self.centre = RelayJets(parameter_jets(cvals, dirs, 1), m, guesses)
        bvals = {k: (box[k] if k in dirs else cvals[k]) for k in PARAMETER_NAMES}
        self.devs = [box[k] - cvals[k] for k in dirs]
        first = parameter_jets(bvals, dirs, 1)
        self.box = RelayJets(first, m, guesses, centre=self.centre.lams, devs=self.devs + [arb(0)],
                             centre_coeffs=self.centre.coeffs)
        self.nested = RelayJets(nested_parameter_jets(first, dirs, 1), m, lams=self.box.lam_jets)
        self.bvals = bvals
        self.cvals = cvals


def _point(q) -> arb:
    from ...core.balls import ball
    return ball(q)


def _centre_root(models: _Models, theta0: arb) -> arb | None:
    """The root of G(., c) near theta0, by interval Newton at the centre (G' over the candidate)."""
    k = models.m - 1
    G = lambda X: models.centre.G(Jet.variable(acb(X), k, models.m))
    x = theta0
    for _ in range(30):
        c = arb(x.mid())
        r = (2 * arb(x.rad()) + abs(c) * arb(2) ** -60).upper()
        X = arb(c, r)
        dg = G(X).d[k].real
        if not certainly_nonzero(dg):
            return None
        N = c - G(c).v.real / dg
        if not N.is_finite():
            return None
        if certainly_lt(X.lower(), N.lower()) and certainly_lt(N.upper(), X.upper()):
            for _ in range(4):        # contract inside the verified ball
                c = arb(N.mid())
                M = c - G(c).v.real / G(N).d[k].real
                if not (M.is_finite() and M.overlaps(N)):
                    break
                M = M.intersection(N)
                if M.rad() > 0.9 * N.rad():
                    N = M
                    break
                N = M
            return N
        x = N
    return None


def _refined(grads: list[arb], union: list[arb] | None) -> list[arb]:
    """The gradient balls intersected with the sub-box union's (both enclose the same values)."""
    if union is None:
        return grads
    out = []
    for g, u in zip(grads, union):
        if g.is_finite() and u.is_finite():
            if not g.overlaps(u):
                raise AssertionError(f"a gradient form {g} misses its sub-box union {u}: a bug")
            out.append(g.intersection(u))
        else:
            out.append(g if g.is_finite() else u)
    return out


def _band(models: _Models, tc: arb, Gc: Jet, cells: int, make_models) -> arb | None:
    """theta*(P) over the box by :func:`.subbox_union.band_root` (the centre's tangent as predictor, one
    Newton step in the offset u over the whole box, ``cells`` parameter cells for the enclosures): a ball
    containing theta*(P) for every P, the band's unique root, or None."""
    k = len(models.dirs)
    slope = [arb((-(Gc.d[i].real) / Gc.d[k].real).mid()) for i in range(k)]
    weights = [float(dev.rad()) * abs(float(Gc.d[i].real.mid())) for i, dev in enumerate(models.devs)]
    counts = split_counts(weights, cells)
    rho = abs(tc) * arb(2) ** -40
    for _ in range(12):
        res = band_root(make_models, models.cvals, models.bvals, models.dirs, tc, slope, rho, counts)
        if res is None:
            return None
        image = res[0]
        if not image.is_finite():
            return None
        if certainly_lt(-rho, image.lower()) and certainly_lt(image.upper(), rho):
            out = tc + image
            for s, dev in zip(slope, models.devs):
                out = out + s * dev
            return out
        rho = (2 * abs(image).upper()).max(2 * rho)
    return None


def _theta_over_box(models: _Models, tc_ball: arb, cells: int = 1, make_models=None):
    """((Theta, gradient, centre gradient, nested theta*, U), "") of theta*(P) over the box (step 1 of the module
    docstring; second-order forms in (theta, P)), or (None, reason). U contains Theta, and for every P of the
    box theta*(P) is the only root of G(., P) in U (dG/dtheta excludes 0 on U x box). With ``cells`` > 1 the gradient of G
    over Theta x box is also enclosed as a union over that many cells (:mod:`.subbox_union`)."""
    tc = arb(tc_ball.mid())
    k = len(models.dirs)
    m = models.m
    zero_devs = models.devs + [arb(0)]
    Gc = models.centre.G(Jet.variable(acb(tc), k, m))
    r = 2 * arb(tc_ball.rad()) + abs(tc) * arb(2) ** -60
    weights = [float(dev.rad()) * abs(float(Gc.d[i].real.mid())) for i, dev in enumerate(models.devs)]
    C = 1 / arb(Gc.d[k].real.mid())          # Krawczyk's preconditioner: 1 / dG/dtheta at the centre (a point)

    def images(Theta: arb):
        """(Newton image or None, Krawczyk image or None, gradient balls over Theta x box); each image
        contains every root theta*(P) in Theta (Theta must contain tc)."""
        Gn = models.nested.G(nested_variable(Theta, k, m))
        G0 = second_order_value(Gc, Gn, zero_devs)
        grads = second_order_gradient(Gc, Gn, models.devs + [Theta - tc])
        if cells > 1:
            rr = float(abs(Theta - tc).upper())
            counts = split_counts(weights + [rr * abs(float(Gc.d[k].real.mid()))], cells)
            union = gradient_union(make_models, models.cvals, models.bvals, models.dirs, Theta, counts)
            grads = _refined(grads, union)
            if union is not None:
                # G(tc, P) by the mean value theorem in P with the union's G_P (it covers {tc} x box)
                G0 = _refined([G0], [Gc.v.real + sum((u * d for u, d in zip(union, models.devs)), arb(0))])[0]
        gth = grads[k]
        N = tc - G0 / gth if certainly_nonzero(gth) else None
        K = tc - C * G0 + (1 - C * gth) * (Theta - tc)
        return (N if N is not None and N.is_finite() else None), (K if K.is_finite() else None), grads

    def inside(X, Theta):
        return X is not None and certainly_lt(Theta.lower(), X.lower()) and certainly_lt(X.upper(), Theta.upper())

    band = _band(models, tc, Gc, cells, make_models) if cells > 1 else None
    if band is not None:
        # the band's root enclosure; unique in Theta too when G_theta excludes 0 on Theta x box
        N = band
        Theta = N.union(tc)
        _, _, grads = images(Theta)
        gth = grads[k]
        if certainly_nonzero(gth):
            unique_in = Theta
        else:
            band = None
    for _ in range(0 if band is not None else 24):
        Theta = arb(tc, r.upper())
        N, K, grads = images(Theta)
        gth = grads[k]
        if not certainly_nonzero(gth):
            return None, f"dG/dtheta = {_fmt(gth, 6)} may vanish on theta in {_fmt(Theta)} over the box"
        ok = [X for X in (N, K) if inside(X, Theta)]
        if ok:
            unique_in = Theta
            # one unique root theta*(P) in Theta for every P (interval Newton, or Krawczyk's K inside Theta);
            # it lies in both images: contract while that narrows it
            N = ok[0].intersection(ok[-1])
            for _ in range(3):
                T2 = N.union(tc)
                N2, K2, g2 = images(T2)
                new = [X for X in (N2, K2) if X is not None]
                if not new or not certainly_nonzero(g2[k]):
                    break
                M = N
                for X in new:
                    if not X.overlaps(M):
                        raise AssertionError(f"a Newton / Krawczyk image {X} misses the root's enclosure {M}: a bug")
                    M = M.intersection(X)
                Theta, grads, gth = T2, g2, g2[k]
                shrunk = M.rad() < 0.8 * N.rad()
                N = M
                if not shrunk:
                    break
            break
        if N is None:
            return None, "the Newton image is not finite"
        r = (3 * abs(N - tc).upper() / 2).max(3 * r.upper() / 2)
    else:
        if band is None:
            return None, f"parametric interval Newton on G did not contract around theta = {_fmt(tc_ball)}"
    # theta*'s gradient over the box: -G_P / G_theta on Theta x box
    grad = [-g / gth for g in grads[:k]]
    cen = tc_ball
    for gk, dev in zip(grad, models.devs):
        cen = cen + gk * dev
    if not cen.overlaps(N):
        raise AssertionError(f"theta*'s centred form {cen} misses its Newton image {N}: a bug")
    Theta = N.intersection(cen)
    # at the centre: theta*(c) and its gradient -G_P(c) / G_theta(c)
    Gcc = models.centre.G(Jet.variable(acb(tc_ball), k, m))
    cgrad = [-(Gcc.d[i].real) / Gcc.d[k].real for i in range(k)]
    # second derivatives of theta* over the box: the same quotient in first-order jet arithmetic, with
    # theta the first-order jet (Theta, grad) (implicit differentiation once more)
    inner = Jet(acb(Theta), [acb(g) for g in grad] + [acb(0)])
    Gt = models.nested.G(Jet(inner, [acb(0)] * k + [acb(1)]))
    # each partial's value ball over the box also lies in its gradient enclosure ``grads`` (theta*(P) in Theta)
    parts = [_with_value(Gt.d[i].real, grads[i]) for i in range(k + 1)]
    inner_grads = []
    for i in range(k):
        q = -parts[i] / parts[k]
        qv = q.v.real
        if not (qv.is_finite() and qv.overlaps(grad[i])):
            return None, "the implicit second derivatives of theta* are not finite over the box"
        inner_grads.append(Jet(acb(qv.intersection(grad[i])), q.d))
    nested_theta = Jet(inner, inner_grads + [acb(0)])
    centre_theta = Jet(acb(tc_ball), [acb(g) for g in cgrad] + [acb(0)])
    if band is not None:
        method = (f"one interval Newton step in the offset from the centre's tangent over the whole box, G's "
                  f"derivatives as unions over {cells} cells; unique in Theta as dG/dtheta excludes 0 on it")
    elif cells > 1:
        method = f"parametric interval Newton / Krawczyk on G = g K, G's derivatives as unions over {cells} cells"
    else:
        method = "parametric interval Newton on G = g K, second-order forms in (theta, P)"
    return (Theta, grad, centre_theta, nested_theta, unique_in), method


def _with_value(j: Jet, enclosure: arb) -> Jet:
    """The jet ``j`` with its (real) value ball intersected with ``enclosure``, another enclosure of it."""
    v = j.v.real
    if v.is_finite() and enclosure.is_finite():
        if not v.overlaps(enclosure):
            raise AssertionError(f"a jet's value {v} misses its enclosure {enclosure}: a bug")
        v = v.intersection(enclosure)
    elif enclosure.is_finite():
        v = enclosure
    return Jet(acb(v), j.d)


def continue_orbit(centre: RelayParams, box: dict[str, arb], dirs: list[str], guesses: list[acb],
                   theta0: arb, genuine: bool = True, stability: bool = True, *, decide=None) -> OrbitOverBox:
    """The orbit through the centre's root near ``theta0`` over the box (module docstring). ``box``:
    {name: ball containing the interval} for the names in ``dirs`` (the parameters the box varies);
    ``guesses``: approximate roots of the centre's cubic (real ones, then the complex one with Im > 0).
    ``decide(models, out, th_c, th_n, genuine, stability)``: the genuineness and stability step (default
    :func:`_decide`; :mod:`.normed_orbit` passes one that falls back on a norm bound of the spectral radius)."""
    decide = decide or _decide
    out = OrbitOverBox(theta_c=theta0)
    try:
        models = _Models(centre, box, dirs, guesses)
    except DegenerateSpectrum as e:
        out.problem = str(e)
        return out
    tc = _centre_root(models, theta0)
    if tc is None:
        out.problem = f"the centre's root near {_fmt(theta0)} was not verified by interval Newton"
        return out
    out.theta_c = tc
    res, why = _theta_over_box(models, tc)
    if res is None and why.startswith("dG/dtheta"):
        # no form can prove theta* unique where dG/dtheta(tc, .) certainly changes sign (:mod:`.theta_fold`)
        tcp = arb(tc.mid())
        fold = slope_sign_change(models.cvals, box, dirs, guesses, tcp,
                                 models.centre.G(Jet.variable(acb(tcp), len(dirs), models.m)).d[len(dirs)].real)
        if fold is not None:
            out.problem, out.fold = why + "; " + fold.text, fold.text
            out.slope_ratio = slope_ratio(models, tc)
            return out
    for cells in SUBBOX_CELLS[:1] if len(dirs) > 2 else SUBBOX_CELLS:    # the nested jets cost ~ (k + 1)^2
        if res is not None:
            break
        res, why = _theta_over_box(models, tc, cells, lambda c, b: _Models(c, b, dirs, guesses))
    if res is None:
        out.problem = why
        out.slope_ratio = slope_ratio(models, tc)
        return out
    out.theta, out.theta_gradient, th_c, th_n, out.theta_unique_in = res
    out.theta_method = why
    decide(models, out, th_c, th_n, genuine, stability)
    if (genuine or stability) and (not out.genuine or (stability and out.stable is not True)):
        steps = SimpleNamespace(OrbitOverBox=OrbitOverBox, SUBBOX_CELLS=SUBBOX_CELLS, models=_Models,
                                centre_root=_centre_root, decide=decide, point=_point, theta_over_box=_theta_over_box)
        decide_by_cells(centre, box, dirs, guesses, out, genuine, stability, steps)
    return out


def _decide(models: _Models, out: OrbitOverBox, th_c: Jet, th_n: Jet, genuine: bool, stability: bool) -> None:
    """Steps 2 and 3 of the module docstring over the models' box, given theta*'s jets: fills ``out``."""
    x0n = models.nested.x0(th_n)
    x0c = models.centre.x0(th_c)
    if genuine or stability:
        ok, why = _sign_condition(models, x0n, x0c, out.theta)
        out.genuine, out.genuine_reason = ok, why
        if not ok:
            out.problem = why
            return
    if stability:
        _stability(models, out, th_n, th_c, x0n, x0c)


def _sign_condition(models: _Models, x0n, x0c, Theta: arb) -> tuple[bool, str]:
    """Step 2 of the module docstring: (True, reason) when beta > 0 on (0, theta*(P)) for every P."""
    k = len(models.dirs)
    m = models.m
    comp_n = models.nested.component(0, x0n)
    comp_c = models.centre.component(0, x0c)
    devs = models.devs

    def enc(lo: arb, hi: arb, derivative: int) -> arb:
        T = interval(lo, hi)
        tcp = arb(T.mid())
        centre = RelayJets.evaluate(comp_c, Jet.variable(acb(tcp), k, m), derivative)
        box = RelayJets.evaluate(comp_n, nested_variable(T, k, m), derivative)
        out = second_order_value(centre, box, devs + [T - tcp])
        direct = base(box).real
        if direct.is_finite() and out.is_finite():
            if not direct.overlaps(out):
                raise AssertionError(f"beta's second-order form {out} misses its direct enclosure {direct}: a bug")
            return out.intersection(direct)
        return out

    th_lo, th_hi = Theta.lower(), Theta.upper()
    d1 = d2 = None
    for j in range(1, 40):
        d = th_lo * arb(2) ** (-j)
        if certainly_positive(enc(arb(0), d, 1)):
            d1 = d
            break
    for j in range(1, 40):
        d = th_lo * arb(2) ** (-j)
        if certainly_negative(enc((th_lo - d).lower(), th_hi, 1)):
            d2 = d
            break
    if d1 is None or d2 is None:
        return False, "the sign of beta' near the switchings was not certified over the box"
    # extend both monotone stretches piece by piece towards the middle (beta' > 0 on [0, lo] with beta(0) = 0
    # gives beta > 0 on (0, lo]; beta' < 0 on [hi, theta*(P)] with beta(theta*) = 0 gives beta > 0 on
    # [hi, theta*)): near the ends beta is small and its enclosure over the box is not, so bisecting beta
    # itself there reaches the precision limit
    lo = _extend(lambda a, b: certainly_positive(enc(a, b, 1)), d1, (th_lo / 2).lower(), +1)
    hi = _extend(lambda a, b: certainly_negative(enc(a, b, 1)), (th_lo - d2).lower(), (th_lo / 2).upper(), -1)
    pieces = 0
    if certainly_lt(lo, hi):
        stack = [(lo, hi)]
        while stack:
            a, b = stack.pop()
            pieces += 1
            if pieces > MAX_PIECES:
                return False, f"beta > 0 on the middle not decided in {MAX_PIECES} pieces over the box"
            v = enc(a, b, 0)
            if certainly_positive(v):
                continue
            mid = ((a + b) / 2).mid()
            if not (certainly_lt(a, mid) and certainly_lt(mid, b)):
                return False, "beta > 0 on the middle not decided (piece at the precision limit)"
            stack += [(mid, b), (a, mid)]
        middle = f"beta > 0 on [{_fmt(lo, 6)}, {_fmt(hi, 6)}] ({pieces} t pieces)"
    else:
        middle = "the two end intervals cover (0, theta*)"
    return True, (f"beta' > 0 on [0, {_fmt(lo, 6)}], beta' < 0 on [{_fmt(hi, 6)}, theta*_hi], "
                  f"{middle}, each for every parameter in the box (second-order forms in t and P)")


def _extend(holds, start: arb, limit: arb, direction: int, max_pieces: int = 64) -> arb:
    """The farthest exact point x from ``start`` towards ``limit`` (``direction`` +1: to the right, -1: to the
    left) such that ``holds(a, b)`` was certified on pieces [a, b] covering [start, x] (or [x, start]): steps
    double on success and halve on failure, at most ``max_pieces`` tries; ``start`` when none succeeds.
    Pieces share their exact end points, so they cover the stretch."""
    if start.rad() != 0:
        return start
    x = start
    h = abs(limit - x) / 8
    floor = h / 256
    for _ in range(max_pieces):
        rest = (limit - x) * direction
        if not certainly_positive(rest):
            break
        h = h.min(rest)
        y = arb((x + direction * h).mid())
        a, b = (x, y) if direction > 0 else (y, x)
        if certainly_lt(a, b) and holds(a, b):
            x, h = y, 2 * h
        else:
            h = h / 2
            if certainly_lt(h, floor):
                break
    return x


def centred_jacobian(models: _Models, th_n: Jet, th_c: Jet, x0n, x0c):
    """The centred form of J(theta*(P), P) over the box: (J at the centre, [(dJ/dp_q over the box, dev_q)]),
    and the jets it came from (nested Jn, centre Jcj, the deviations with theta's 0 appended)."""
    Jn = models.nested.jacobian(th_n, x0n)
    Jcj = models.centre.jacobian(th_c, x0c)
    Jc = arb_mat([[Jcj[i][j].v.real for j in range(4)] for i in range(4)])
    devs0 = models.devs + [arb(0)]
    grads = [[second_order_gradient(Jcj[i][j], Jn[i][j], devs0) for j in range(4)] for i in range(4)]
    terms = [(arb_mat([[grads[i][j][q] for j in range(4)] for i in range(4)]), models.devs[q])
             for q in range(len(models.dirs))]
    return Jc, terms, Jn, Jcj, devs0


def _stability(models: _Models, out: OrbitOverBox, th_n: Jet, th_c: Jet, x0n, x0c) -> None:
    """Step 3 of the module docstring: fills out.multipliers, moduli, max_modulus, stable."""
    Jc, terms, Jn, Jcj, devs0 = centred_jacobian(models, th_n, th_c, x0n, x0c)
    candidates = []
    eig = eigen_coordinate_multipliers(None, None, (Jc, terms))
    if eig is not None:
        candidates.append(eig)
    J = arb_mat([[second_order_value(Jcj[i][j], Jn[i][j], devs0) for j in range(4)] for i in range(4)])
    try:
        candidates.append(list(acb_mat(J).eig(algorithm="rump")))
    except ValueError:
        pass
    # the exponential-based centred form of jacobian_box on Theta x box (theta a separate direction)
    Pb = RelayParams(**models.bvals)
    parts = centred_terms(Pb, out.theta)
    if parts is not None:
        other = eigen_coordinate_multipliers(Pb, out.theta, parts)
        if other is not None:
            candidates.append(other)
    candidates = [c for c in candidates if len(c) == 4 and all(z.is_finite() for z in c)]
    if not candidates:
        out.problem = "the four multipliers were not isolated over the box"
        return
    eig = min(candidates, key=lambda c: max(float(z.real.rad()) + float(z.imag.rad()) for z in c))
    prod = acb(1)
    for z in eig:
        prod *= z
    tau, sigma = models.bvals["tau"], models.bvals["sigma"]
    liou = -((-(1 / tau + 1 / sigma)) * out.theta).exp()
    if not prod.real.overlaps(liou):
        raise AssertionError(f"Liouville check failed over the box: prod {prod}, expected {liou}: a bug")
    order = sorted(range(4), key=lambda i: -float(abs(eig[i]).mid()))
    out.multipliers = [eig[i] for i in order]
    out.moduli = [abs(z) for z in out.multipliers]
    mx = out.moduli[0]
    for mm in out.moduli[1:]:
        mx = mx.max(mm)
    out.max_modulus = mx
    if all(certainly_lt(mm, 1) for mm in out.moduli):
        out.stable = True
    else:
        out.problem = f"max multiplier modulus {_fmt(mx)} not certainly < 1 over the box"



def at_most_one_root(centre: RelayParams, box: dict[str, arb], dirs: list[str], guesses: list[acb], W: arb,
                     pieces: tuple[int, ...] = (1, 4, 16)) -> bool:
    """True when dG/dtheta (G = g K, K > 0) certainly excludes 0 on W x box: then, for every P of the box, G(., P)
    is strictly monotone on W, and g(., P) has at most one root in W. W is cut into n equal pieces for n in
    ``pieces`` in turn, each piece's dG/dtheta enclosed by a second-order form about the centre and the piece's
    midpoint (on the +-0.25 % boxes of margin_roitenberg_all_half_percent, one form over W of width 0.004 spans 0;
    four pieces exclude it); the signs must agree. False when not shown (never a claim that there are two).
    ``W``: an interval of theta > 0; ``centre`` a member of the box; arguments otherwise as :func:`continue_orbit`'s."""
    if not certainly_positive(W.lower()):
        return False
    if not all(box[k].contains(_point(getattr(centre, k))) for k in dirs):
        return False                    # the form's Hessian is taken over the box: the centre must lie in it
    try:
        models = _Models(centre, box, dirs, guesses)
    except DegenerateSpectrum:
        return False
    lo, hi = W.lower(), W.upper()
    for n in pieces:
        parts = [interval(lo + (hi - lo) * i / n, lo + (hi - lo) * (i + 1) / n) for i in range(n)]
        signs = {_slope_sign(models, Wi, arb(Wi.mid())) for Wi in parts}
        if len(signs) == 1 and 0 not in signs:
            return True
    return False


def _slope_sign(models: _Models, Wi: arb, ti: arb) -> int:
    """The certain sign of dG/dtheta on Wi x box (0: not certain), by the second-order form about the centre and
    ``ti``, a point of Wi."""
    if not Wi.contains(ti):
        return 0
    k, m = len(models.dirs), models.m
    Gc = models.centre.G(Jet.variable(acb(ti), k, m))
    Gn = models.nested.G(nested_variable(Wi, k, m))
    d = second_order_gradient(Gc, Gn, models.devs + [Wi - ti])[k]
    return 1 if certainly_positive(d) else -1 if certainly_negative(d) else 0
