"""Independent re-check of a [plant] periodic-orbit certificate (``rigor-gyro check``; :mod:`.plant_claims`).

The prover writes g through the residues N(lambda_k) / p'(lambda_k) of the exact characteristic and
numerator polynomials, isolates the pole-free G = g K and builds the multipliers from Arb's matrix
exponential. This checker takes another road to the same numbers, at twice the certificate's precision:

* the diagonalisation M = R diag(lambda) R^-1 by Rump's method (``acb_mat.eig(right=True)``: enclosures of
  eigenvalues and right eigenvectors valid for M itself; R^-1 by Arb's solver), the exact zero eigenvalue
  of an integrator set to 0 (the model decides it exactly, and exactly one eigenvalue ball contains 0);
  then g(theta) = -S sum_k Re(rho_k tanh(lambda_k theta/2)/lambda_k) - h with rho_k = (c R)_k (R^-1 e)_k over
  all n eigenvalues (the zero eigenvalue's rho_0 taken exactly from the model, r0 = N_c(0)/p'(0), after checking
  that the eigenvectors' ball contains it: an uncontrollable or unobservable integrator has r0 = 0, the slope
  of g at infinity exactly 0) (no pairing; the pieces are re-decided on g K, K = prod over the non-real eigenvalues of
  1 + E_k > 0, whose terms have no poles), y(t) = c . x(t) likewise, and exp(M theta) =
  R diag(e^(lambda theta)) R^-1 for the Jacobian;
* (0, theta_min] root-free by the exact near-0 bound (rational arithmetic, :func:`.plant_orbit.near_zero_bound`)
  or, with h = 0, by the sign of g's leading Taylor coefficient over [0, theta_min] from this diagonalisation;
* the stored pieces tile [theta_min, T]; each "empty" piece has no root of g (exclusion by a Taylor-model
  enclosure, interval Newton, or strict monotonicity with one sign at both ends; bisected up to
  :data:`SPLIT_DEPTH` times), each "unique" piece exactly one (interval Newton; or split into a unique part
  and empty parts);
* beyond T (when all of (0, oo) is claimed): the tail bound recomputed from this diagonalisation;
* per root its classification (witness t; or d1, right_start and each middle piece, re-evaluated);
* the multipliers of each genuine orbit by van der Hoeven-Mourrain (Rump if that fails), stability
  re-decided; every stored quantity contains the recomputed enclosure (the amplitude by its own branch and
  bound, tighter; the describing-function estimate recomputed).

Guarantee: an item is confirmed only when balls decide it. Precision: the checker's (twice the
certificate's). Fails when: a step cannot be re-decided at this precision: that item is not confirmed.
"""
from __future__ import annotations

from fractions import Fraction

from flint import acb, acb_mat, acb_series, arb, arb_mat, fmpq

from ...check import CheckResult
from ...core.balls import (ball, certainly_lt, certainly_negative, certainly_positive, interval,
                           series_coefficients, series_length)
from ...core.stored import fmpq_of, interval as stored_interval, number
from ...core.subdivision import enclose_max
from .check_verdicts import other_orbit_moduli, redecide
from .flow import ExpSum, taylor_enclosure
from .plant_check_rows import check_root_rows, encloses
from .plant_df import describing_function
from .multipliers import disc_margin
from .norm_stability import spectral_radius_bound
from .plant_orbit import leading_coefficient, matrix_ball, near_zero_bound, near_zero_order, section_index
from .plant_statements import AMPLITUDE_REL, TAYLOR_ORDER

__all__ = ["check", "Diagonal"]

NEWTON_STEPS = 60
SPLIT_DEPTH = 10


def _pt(text: str) -> arb:
    return arb(fmpq_of(number(text)))


class Diagonal:
    """M = R diag(lam) L (L = R^-1) by Rump's method, with the weights of c and e."""

    def __init__(self, model):
        n = model.n
        self.model = model
        self.n = n
        A = acb_mat(matrix_ball(model.M))
        lam, R = A.eig(right=True, algorithm="rump")
        try:
            L = R.inv()
        except ZeroDivisionError:
            raise ValueError("the eigenvector matrix is not certainly invertible at this precision") from None
        lam = list(lam)
        if model.zero_eigenvalue:
            zeros = [k for k, z in enumerate(lam) if z.contains(0)]
            if len(zeros) != 1:
                raise ValueError("the zero eigenvalue is not separated from the others at this precision")
            lam[zeros[0]] = acb(0)
        for z in lam:
            if not z.is_zero() and z.real.contains(0):
                raise ValueError("a real part is not separated from 0 at this precision")
        self.lam, self.R, self.L = lam, R, L
        self.S, self.h = ball(model.S), ball(model.h)
        self.Le = [sum((L[k, j] * ball(model.e[j]) for j in range(n)), acb(0)) for k in range(n)]
        self.cR = [sum((ball(model.c[i]) * R[i, k] for i in range(n)), acb(0)) for k in range(n)]
        self.rho = [self.cR[k] * self.Le[k] for k in range(n)]
        if model.zero_eigenvalue:       # the integrator's residue exactly, from the model: r0 = N_c(0) / p'(0)
            k0 = next(k for k, z in enumerate(lam) if z.is_zero())
            Nc = model.numerator_c
            r0 = ball((Nc[0] if Nc.degree() >= 0 else fmpq(0)) / model.charpoly.derivative()[0])
            if not self.rho[k0].contains(r0):
                raise ValueError("the eigenvectors' residue at 0 misses the exact N_c(0)/p'(0)")
            self.rho[k0] = acb(r0)

    def phi(self, k: int, s):
        """tanh(lam_k s / 2) / lam_k (s / 2 for the zero eigenvalue), s a series or a ball."""
        z = self.lam[k]
        if z.is_zero():
            return s / 2
        if certainly_negative(z.real):
            E = (z * s).exp()
            return (E - 1) / ((E + 1) * z)
        F = (-z * s).exp()
        return (1 - F) / ((1 + F) * z)

    def g_coeffs(self, center: arb, n: int, pole_free: bool = False) -> list[arb]:
        """Taylor coefficients of g, or (``pole_free``) of g K with K = prod over the non-real eigenvalues
        (each of a pair on its own) of (1 + E_k), E_k = exp(-|Re lam_k| ...) as in :meth:`phi`: K > 0 on
        real theta > 0, the same roots, tanh's complex poles cancelled term by term."""
        tot = [arb(0)] * n
        with series_length(n):
            s = acb_series([acb(center), 1], prec=n)
            one = acb_series([1], prec=n)
            cx = [k for k in range(self.n) if pole_free and not self.lam[k].imag.contains(0)]
            E = {k: self._E(k, s) for k in cx}
            try:
                K = one
                for k in cx:
                    K = K * (1 + E[k])
                for k in range(self.n):
                    if k in E:
                        z = self.lam[k]
                        sg = -1 if certainly_negative(z.real) else 1
                        term = sg * (1 - E[k]) / z
                        for j in cx:
                            if j != k:
                                term = term * (1 + E[j])
                    else:
                        term = self.phi(k, s) * K
                    c = series_coefficients(term * self.rho[k], n)
                    for j in range(n):
                        tot[j] -= self.S * c[j].real
                hk = series_coefficients(K * self.h, n)
            except ValueError:
                return [arb("nan")] * n
        for j in range(n):
            tot[j] -= hk[j].real
        return tot

    def _E(self, k: int, s):
        z = self.lam[k]
        return (z * s).exp() if certainly_negative(z.real) else (-z * s).exp()

    def x0(self, theta: arb) -> list[arb]:
        """x0(theta) = -S R phi(diag lam) L e; a component whose exact numerator N_i is the zero polynomial (a
        state the relay never reaches: uncontrollable) is exactly 0."""
        t = acb(theta)
        w = [self.phi(k, t) * self.Le[k] for k in range(self.n)]
        return [arb(0) if self.model.numerators[i].degree() < 0 else
                -self.S * sum((self.R[i, k] * w[k] for k in range(self.n)), acb(0)).real for i in range(self.n)]

    def output(self, theta: arb) -> ExpSum:
        """y(t) = c . x(t) on the half-period: S sum_k rho_k (2 e^(lam t)/(1 + e^(lam theta)) - 1)/lam_k,
        the zero eigenvalue's term S rho_0 (t - theta/2)."""
        terms, c0, c1 = [], arb(0), arb(0)
        t = acb(theta)
        for k in range(self.n):
            z = self.lam[k]
            if z.is_zero():
                c0 -= (self.S * self.rho[k]).real * theta / 2
                c1 += (self.S * self.rho[k]).real
                continue
            if certainly_negative(z.real):
                alpha = 2 * self.S * self.rho[k] / ((1 + (z * t).exp()) * z)
            else:
                F = (-z * t).exp()
                alpha = 2 * self.S * self.rho[k] * F / ((1 + F) * z)
            terms.append((alpha, z, 1))
            c0 -= (self.S * self.rho[k] / z).real
        return ExpSum(terms, c0, c1)

    def expm(self, theta: arb) -> arb_mat:
        t = acb(theta)
        ez = [z.exp() if z.is_zero() else (z * t).exp() for z in self.lam]
        out = arb_mat(self.n, self.n)
        for i in range(self.n):
            for j in range(self.n):
                out[i, j] = sum((self.R[i, k] * ez[k] * self.L[k, j] for k in range(self.n)), acb(0)).real
        return out

    def tail_ok(self, T: arb) -> bool:
        """g of one strict sign on [T, oo): a theta + b -+ B (see plant_orbit's module docstring)."""
        a, b, B = arb(0), -self.h, arb(0)
        for k in range(self.n):
            z = self.lam[k]
            if z.is_zero():
                a -= (self.S * self.rho[k]).real / 2
                continue
            sg = -1 if certainly_negative(z.real) else 1
            b -= (self.S * sg * self.rho[k] / z).real
            q = (-abs(z.real) * T).exp()
            B += 2 * abs(self.S * self.rho[k] / z) * q / (1 - q)
        base = a * T + b
        if not a.is_zero() and not (certainly_positive(a) or certainly_negative(a)):
            return False
        up = certainly_positive(a) or a.is_zero()
        down = certainly_negative(a) or a.is_zero()
        return (up and certainly_positive(base - B)) or (down and certainly_negative(base + B))


class _G:
    def __init__(self, d: Diagonal):
        self.coeffs = lambda c, n: d.g_coeffs(c, n, pole_free=True)      # noqa: E731

    def both(self, X: arb) -> tuple[arb, arb]:
        g, dg = taylor_enclosure(self.coeffs, X, TAYLOR_ORDER, (0, 1))
        return g, dg

    def at(self, t: arb) -> arb:
        return self.coeffs(t, 1)[0]


def _newton(G: _G, X: arb) -> tuple[str, arb | None]:
    """("empty" | "unique" | "unknown", enclosure): Moore's theorem on the interval Newton operator."""
    g, _ = G.both(X)
    if g.is_finite() and not g.contains(0):
        return "empty", None
    x = X
    for _ in range(NEWTON_STEPS):
        m = arb(x.mid())
        gm = G.at(m)
        _, dg = G.both(x)
        if not dg.is_finite() or dg.contains(0) or not gm.is_finite():
            return "unknown", None
        n = m - gm / dg
        if not n.overlaps(x):
            return "empty", None
        if x.contains_interior(n):
            for _ in range(NEWTON_STEPS):
                m = arb(n.mid())
                _, dg = G.both(n)
                n2 = (m - G.at(m) / dg).intersection(n)
                if not certainly_lt(n2.rad(), n.rad()):
                    break
                n = n2
            return "unique", n
        x = x.intersection(n)
    return "unknown", None


def _sign(x: arb) -> int:
    return 1 if certainly_positive(x) else -1 if certainly_negative(x) else 0


def _monotone_root_free(G: _G, lo: arb, hi: arb) -> bool:
    """No root of g on [lo, hi] because g is strictly monotone there with one strict sign at both ends:
    g' of one strict sign on the piece, or g'' of one strict sign on it and g' of one strict sign at both
    ends (then g' cannot vanish between them). Decides the pieces the prover closed next to a root, where
    g is too small at the near end for an exclusion or a Newton step."""
    a, b = G.coeffs(lo, 2), G.coeffs(hi, 2)
    s0 = _sign(a[0])
    if s0 == 0 or _sign(b[0]) != s0:
        return False
    d1, d2 = taylor_enclosure(G.coeffs, interval(lo, hi), TAYLOR_ORDER, (1, 2))
    if _sign(d1) != 0:
        return True
    s1 = _sign(a[1])
    return _sign(d2) != 0 and s1 != 0 and _sign(b[1]) == s1


def _empty(G: _G, lo: arb, hi: arb, depth: int = 0) -> bool:
    st, _ = _newton(G, interval(lo, hi))
    if st == "empty" or _monotone_root_free(G, lo, hi):
        return True
    if depth >= SPLIT_DEPTH:
        return False
    mid = ((lo + hi) / 2).mid()
    return _empty(G, lo, mid, depth + 1) and _empty(G, mid, hi, depth + 1)


def _unique(G: _G, lo: arb, hi: arb, depth: int = 0) -> arb | None:
    """The enclosure of the one root of g on [lo, hi], or None when not re-decided."""
    st, e = _newton(G, interval(lo, hi))
    if st == "unique":
        return e
    if st == "empty" or depth >= SPLIT_DEPTH:
        return None
    w = hi - lo
    for fr in (Fraction(1, 2), Fraction(1, 3), Fraction(2, 3)):
        mid = (lo + w * fr.numerator / fr.denominator).mid()
        if _empty(G, lo, mid):
            e = _unique(G, mid, hi, depth + 1)
        elif _empty(G, mid, hi):
            e = _unique(G, lo, mid, depth + 1)
        else:
            continue
        if e is not None:
            return e
    return None


def _positive(f, lo: arb, hi: arb, depth: int = 0) -> bool:
    if certainly_positive(f(interval(lo, hi))):
        return True
    if depth >= SPLIT_DEPTH:
        return False
    mid = ((lo + hi) / 2).mid()
    return _positive(f, lo, mid, depth + 1) and _positive(f, mid, hi, depth + 1)


def _classify(d: Diagonal, theta: arb, w: dict) -> tuple[bool, str]:
    y = d.output(theta)
    h = d.h
    phi = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (0,))[0] + h      # noqa: E731
    dphi = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (1,))[0]         # noqa: E731
    if w["kind"] == "spurious":
        if "witness_t" in w:
            t = _pt(w["witness_t"])
            ok = certainly_positive(t) and certainly_lt(t, theta) and certainly_negative(phi(t))
            return ok, f"spurious: c . x(t) + h < 0 at the stored t: {ok}"
        ok = d.model.h == 0 and certainly_negative(y.coeffs(arb(0), 2)[1])
        return ok, f"spurious: y'(0) < 0 with h = 0: {ok}"
    if w["kind"] != "genuine":
        return False, f"root classified {w['kind']!r}"
    d1, rs = _pt(w["d1"]), _pt(w["right_start"])
    left = interval(arb(0), d1)
    left_ok = certainly_positive(dphi(left)) and d.model.h == 0 or d.model.h > 0 and certainly_positive(phi(left))
    ok = (left_ok and certainly_positive(d1) and certainly_lt(rs, theta)
          and certainly_negative(dphi(interval(rs, theta.upper()))))
    middle = [(number(a), number(b)) for a, b in w.get("middle", [])]
    d1q, rsq = number(w["d1"]), number(w["right_start"])
    if middle:
        tiles = middle[0][0] <= d1q and middle[-1][1] >= rsq and all(
            middle[i][1] >= middle[i + 1][0] for i in range(len(middle) - 1))
        pos = all(_positive(phi, arb(fmpq_of(a)), arb(fmpq_of(b))) for a, b in middle)
        ok = ok and tiles and pos
    else:
        ok = ok and d1q >= rsq
    return ok, f"genuine: ends and {len(middle)} middle pieces re-verified: {ok}"


def _multipliers(d: Diagonal, theta: arb) -> list[acb] | None:
    """The orbit's multipliers (ordered as the prover orders them), or None when they are not isolated."""
    return _spectrum(d, theta)[0]


def _disc_bound(d: Diagonal, theta: arb) -> arb | None:
    """Where the multipliers are not isolated: Gershgorin's bound U of every modulus when certainly < 1, else None
    (the prover's :func:`.plant_claims.stable_by_discs`, recomputed on this checker's own Jacobian)."""
    mults, J = _spectrum(d, theta)
    return None if mults is not None else _bound_below_1(J)


def _bound_below_1(J: arb_mat | None) -> arb | None:
    """Gershgorin's bound of every eigenvalue modulus of J when certainly < 1, else None."""
    U = None if J is None else spectral_radius_bound(acb_mat(J))
    return U if U is not None and certainly_lt(U, 1) else None


def _spectrum(d: Diagonal, theta: arb) -> tuple[list[acb] | None, arb_mat | None]:
    """(the multipliers, None), or (None, the Jacobian) when its eigenvalues are not isolated."""
    model, n = d.model, d.n
    if n == 1:          # the section is a point: no multipliers (multipliers.decide_multipliers)
        return [], None
    x0 = d.x0(theta)
    E = d.expm(theta)
    M = matrix_ball(model.M)
    e = [ball(v) for v in model.e]
    c = [ball(v) for v in model.c]
    f1 = [-sum((M[i, k] * x0[k] for k in range(n)), arb(0)) + e[i] * d.S for i in range(n)]
    f0 = [sum((M[i, k] * x0[k] for k in range(n)), arb(0)) + e[i] * d.S for i in range(n)]
    cf1 = sum((c[i] * f1[i] for i in range(n)), arb(0))
    cf0 = sum((c[i] * f0[i] for i in range(n)), arb(0))
    j = section_index(model)
    idx = [i for i in range(n) if i != j]
    cE = [sum((c[i] * E[i, k] for i in range(n)), arb(0)) for k in range(n)]
    P = [[-(E[i, k] - f1[i] * cE[k] / cf1) for k in range(n)] for i in range(n)]
    J = arb_mat([[P[i][k] - P[i][j] * c[k] / c[j] for k in idx] for i in idx])
    try:
        eig = list(acb_mat(J).eig(algorithm="vdhoeven_mourrain"))
    except ValueError:
        try:
            eig = list(acb_mat(J).eig(algorithm="rump"))
        except ValueError:
            return None, J
    if not all(z.is_finite() for z in eig):
        return None, J
    tr = sum((M[i, i] for i in range(n)), arb(0))
    liou = acb((-1) ** (n - 1) * (tr * theta).exp() * cf0 / cf1)
    m = n - 1
    if m > 1:
        s = min(range(m), key=lambda i: float(abs(eig[i]).upper()))
        rest = acb(1)
        for i in range(m):
            if i != s:
                rest *= eig[i]
        if rest.is_finite() and certainly_positive(abs(rest)):
            z = liou / rest
            if z.is_finite() and z.overlaps(eig[s]) and (not certainly_positive(abs(eig[s]))
                                                         or certainly_lt(z.rad(), eig[s].rad())):
                eig[s] = z
    for i, z in enumerate(eig):
        if z.imag.contains(0) and not any(z.conjugate().overlaps(w) for k, w in enumerate(eig) if k != i):
            eig[i] = acb(z.real, 0)
    out = sorted(eig, key=lambda z: -float(abs(z).mid()))
    for i in range(m - 1):
        a, b = out[i], out[i + 1]
        if abs(a).overlaps(abs(b)) and certainly_negative(a.imag) and certainly_positive(b.imag):
            out[i], out[i + 1] = b, a
    return out, None


def check(model, data: dict) -> list[CheckResult]:
    """Re-decide every claim of a [plant] periodic-orbit certificate; see the module docstring."""
    res: list[CheckResult] = []
    say = lambda item, ok, msg: res.append(CheckResult(item, ok, msg))  # noqa: E731
    q = data["quantities"]
    verified: set[str] = set()

    def contains(name: str, x: arb) -> None:
        if name not in q:
            return
        if encloses(stored_interval(q[name]), x):
            verified.add(name)
        else:
            say(name, False, f"stored [{q[name]['lo']}, {q[name]['hi']}] does not contain the recomputed value")

    claims = {c["id"]: c for c in data["claims"]}
    try:
        d = Diagonal(model)
    except ValueError as e:
        for cid, c in claims.items():
            say(cid, c["status"] == "inconclusive", f"diagonalisation not re-decided ({e})")
        return res
    G = _G(d)
    w = (data.get("witnesses") or {}).get("half_period")
    roots: list[arb] = []
    classes: list[tuple[bool, str]] = []
    half_ok, why = False, "no isolation witness stored"
    if w is not None:
        t_min, T = _pt(w["theta_min"]), _pt(w["T"])
        near = near_zero_bound(model, t_min)
        if not near and model.h == 0:      # g + h = O(theta^k) exactly: the sign of its k-th coefficient on [0, t]
            k = 2 * near_zero_order(model)[0] + 1
            lead = leading_coefficient(d.g_coeffs, k, t_min, extra=10)
            near = certainly_positive(lead) or certainly_negative(lead)
        steps = [("(0, theta_min] root-free (near-0 bound or leading Taylor coefficient)", near)]
        pcs = w["pieces"]
        tiles = bool(pcs) and number(pcs[0]["lo"]) <= number(w["theta_min"]) and number(pcs[-1]["hi"]) >= number(w["T"])
        tiles = tiles and all(number(pcs[i]["hi"]) == number(pcs[i + 1]["lo"]) for i in range(len(pcs) - 1))
        steps.append(("the pieces tile [theta_min, T]", tiles))
        if w["covers_all"]:
            steps.append(("tail bound beyond T", d.tail_ok(T)))
        elif model.T_max is not None:
            steps.append(("T >= T_max", number(w["T"]) >= model.T_max.rational))
        else:
            steps.append(("covers (0, oo)", False))
        pieces_ok = True
        for pc in pcs:
            lo, hi = _pt(pc["lo"]), _pt(pc["hi"])
            if pc["kind"] == "empty":
                ok = _empty(G, lo, hi)
            elif pc["kind"] == "unique":
                e = _unique(G, lo, hi)
                ok = e is not None
                if ok:
                    roots.append(e)
            else:
                ok = False
            if not ok:
                pieces_ok = False
                steps.append((f"piece [{float(number(pc['lo'])):.6g}, {float(number(pc['hi'])):.6g}] ({pc['kind']})",
                              False))
                break
        steps.append(("every piece re-decided", pieces_ok))
        steps.append(("one classification per root", len(w.get("roots", [])) == len(roots)))
        if pieces_ok and len(w.get("roots", [])) == len(roots):
            classes = [_classify(d, th, rw) for th, rw in zip(roots, w["roots"])]
            steps.append(("every classification re-verified", all(ok for ok, _ in classes)))
        half_ok = all(ok for _, ok in steps)
        why = "; ".join(f"{name}: {'ok' if ok else 'FAILED'}" for name, ok in steps)
    genuine = [th for th, rw in zip(roots, (w or {}).get("roots", [])) if rw["kind"] == "genuine"] if half_ok else []
    main = None
    if "theta_star" in q and genuine:
        s = stored_interval(q["theta_star"])
        main = next((th for th in genuine if encloses(s, th)), None)
    moduli_main, bounded = None, []
    if main is not None:
        verified.add("theta_star")
        contains("period", 2 * main)
        for i, x in enumerate(d.x0(main), start=1):
            contains(f"x0_{i}", x)
        mults, J = _spectrum(d, main)
        if mults is not None:
            moduli_main = [abs(z) for z in mults]
            for j, (z, m) in enumerate(zip(mults, moduli_main), start=1):
                contains(f"multiplier_modulus_{j}", m)
                contains(f"multiplier_{j}_re", z.real)
                contains(f"multiplier_{j}_im", z.imag)
            mx = moduli_main[0] if moduli_main else arb(0)      # dimension 1: the zero map's radius
            for m in moduli_main[1:]:
                mx = mx.max(m)
            contains("stability_margin", 1 - mx)
        elif (U := _bound_below_1(J)) is not None:
            bounded.append([arb(0).union(U)])               # every modulus in [0, U]: decides stable only
            contains("stability_margin", disc_margin(U))
        if "amplitude" in q:
            y = d.output(main)
            f = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (0,))[0]     # noqa: E731
            tol = ball(fmpq(AMPLITUDE_REL.numerator, AMPLITUDE_REL.denominator * 100))
            ext = enclose_max(f, arb(0), main.upper(), abs_tol=0, rel_tol=tol, max_pieces=40000)
            t = ext.argpoint
            low = f(t).lower() if certainly_lt(t, main.lower()) else d.h
            A = interval(low, ext.ball.upper())
            contains("amplitude", A)
            if "df_period" in q:
                est = describing_function(model)
                if est.omegas:
                    _, Adf, Pdf = min(est.omegas, key=lambda o: abs(float(o[2].mid()) - float(2 * main.mid())))
                    contains("df_period", Pdf)
                    contains("df_amplitude", Adf)
                    contains("df_period_difference", 2 * main - Pdf)
                    contains("df_amplitude_difference", A - Adf)
    others, other_moduli = other_orbit_moduli(genuine, main, lambda th: _multipliers(d, th), contains)
    for k, th in enumerate(others, start=2):
        if k not in other_moduli and (U := _disc_bound(d, th)) is not None:
            bounded.append([arb(0).union(U)])
            contains(f"stability_margin_{k}", disc_margin(U))
    exhaustive = half_ok and w["covers_all"]
    all_moduli = ([moduli_main] if moduli_main is not None else []) + list(other_moduli.values())
    for cid, c in claims.items():
        st = c["status"]
        if st == "inconclusive":
            say(cid, True, "inconclusive: claims nothing")
        else:
            say(cid, *redecide(cid, st, half_ok=half_ok, why=why, main=main, genuine=genuine, exhaustive=exhaustive,
                               moduli_ok=(moduli_main is not None and len(other_moduli) == len(others)),
                               all_moduli=all_moduli, bounded=bounded))
    required = {"orbit_genuine": ("theta_star", "period"),
                "initial_point": tuple(f"x0_{i}" for i in range(1, model.n + 1)),
                "multipliers": tuple(f"multiplier_modulus_{j}" for j in range(1, model.n)),
                "stable": ("stability_margin",)}
    for cid, names in required.items():
        if claims.get(cid, {}).get("status") == "proved":
            missing = [n for n in names if n not in q]
            if missing:
                say(cid, False, f"a proved {cid} without the quantities its statement names: {missing}")
    unverified = sorted(set(q) - verified)
    say("quantities", not unverified, f"{len(verified)} stored enclosures verified"
        + (f"; not verified: {unverified}" if unverified else ""))
    if classes:
        say("roots", all(ok for ok, _ in classes), f"{len(classes)} roots classified: "
            + "; ".join(m for _, m in classes[:3]) + (" ..." if len(classes) > 3 else ""))
    if "roots" in (data.get("extra") or {}):
        say("extra.roots", *_rows(d, G, data["extra"]["roots"], roots, (w or {}).get("roots") if classes and all(
            ok for ok, _ in classes) else None, main, moduli_main))
    return res


def _rows(d: Diagonal, G: _G, rows, roots: list, kinds_w, main, moduli_main) -> tuple[bool, str]:
    """The roots' table re-verified (:mod:`.plant_check_rows`); the main orbit's moduli reused."""
    kinds = [r["kind"] for r in kinds_w] if kinds_w is not None and len(kinds_w) == len(roots) else None

    def moduli_of(th):
        if th is main and moduli_main is not None:
            return moduli_main
        mm = _multipliers(d, th)
        return None if mm is None else [abs(z) for z in mm]
    return check_root_rows(rows, d.n, roots, kinds, moduli_of, lambda lo, hi: _unique(G, lo, hi),
                           lambda th: _disc_bound(d, th) is not None)
