"""The relay's spectral forms as jets in the parameters (first-order forward-mode AD in balls), for centred
forms over a parameter box (issue 37: parametric forms).

What: :class:`RelayJets` evaluates the closed forms of :mod:`.flow` (the eigenvalues of M, the rank-one
projectors, x0(theta), g(theta) = beta0(theta), the components x_i(t) of the half-period solution and the
half-period Jacobian) with every input a :class:`rigor_gyro.core.jets.Jet`: a ball and its gradient
with respect to the box's parameters (and, when asked, theta or t). The eigenvalues of the nutation cubic
(4) C(z; P) are jets by the implicit function theorem, dlambda/dP_k = -(dC/dP_k)(lambda) / C'(lambda),
their value balls by interval Newton over the family (:mod:`rigor_gyro.core.family_roots`) or, where that
fails (the coefficients vary independently there: over tau +-5 % the stiff real root near -1/tau is lost), by
parametric Newton around a linear predictor (:func:`rigor_gyro.core.implicit_roots.polynomial_root_over_box`,
as written or in the scaled variable z / c_2), narrowed by their own centred form; the three enclosures are
disjoint (one real, the pair's in the upper half plane), so they hold the three roots of every member.

Guarantee: given parameter jets whose value balls contain the box and whose gradients are the unit
vectors, every output's value ball contains its value and every gradient ball contains its partial
derivative, for every parameter in the box (and every theta / t in their balls); with point balls and no
directions (``m = 0``) it is the point evaluation at the centre. A centred form (value at the centre plus
gradient over the box times the deviation, :func:`rigor_gyro.core.jets.centred`) then encloses each
quantity over the box with an excess of second order in the box's width.

Precision: the current working precision. Fails when: the cubic's roots are not isolated over the box
(a root ball not verified, or two overlapping), or an eigenvector normalisation may vanish:
:class:`.flow.DegenerateSpectrum`; a quantity whose ball is not finite is the caller's to reject.
"""
from __future__ import annotations

from flint import acb, arb

from ...core.balls import certainly_nonzero, certainly_positive
from ...core.family_roots import newton_family_root, newton_family_root_complex, polynomial_family
from ...core.implicit_roots import polynomial_root_over_box
from ...core.jets import Jet, base, jet_sum
from .flow import DegenerateSpectrum

__all__ = ["PHYSICAL", "RelayJets", "parameter_jets", "nested_parameter_jets", "nested_variable"]

#: the parameters a box varies as jets (S, p, K enter only the amplitude: boxes.py fixes them)
PHYSICAL = ("A", "B", "H", "tau", "sigma", "n")


def _nonzero(z: acb) -> bool:
    """z certainly != 0: its real or its imaginary part certainly nonzero, or |z| certainly positive (acb's
    abs of a wide box can reach down to 0 although the box is far from 0)."""
    return certainly_nonzero(z.real) or certainly_nonzero(z.imag) or certainly_nonzero(abs(z))


def _narrow(j: Jet, centre_value: acb | None, devs) -> Jet:
    """``j`` with its value intersected with its centred form (centre value + gradient x deviations)."""
    if centre_value is None:
        return j
    re, im = centre_value.real, centre_value.imag
    for d, dev in zip(j.d, devs):
        re, im = re + d.real * dev, im + d.imag * dev
    v = j.v
    if not (v.real.overlaps(re) and v.imag.overlaps(im)):
        raise AssertionError(f"an eigenvalue's ball {v} misses its centred form {re} + {im} i: a bug")
    vr = v.real.intersection(re) if v.real.is_finite() else re
    vi = v.imag.intersection(im) if v.imag.is_finite() else im
    return Jet(acb(vr, vi), j.d)


class RelayJets:
    """The relay's closed forms over jets (module docstring).

    ``P``: {name: Jet} for all nine parameters (S, p, K usually constants), all with ``m`` directions;
    ``guesses``: approximate eigenvalues [real roots..., complex root with Im > 0] of the cubic (only
    starting guesses: the roots are verified here); ``centre``: the centre's eigenvalue balls in the same
    order (to narrow the box's by their centred form) and ``devs`` the deviation balls of the m
    directions (both None at the centre itself)."""

    def __init__(self, P: dict[str, Jet], m: int, guesses: list[acb] | None = None, centre: list[acb] | None = None,
                 devs=None, lams: list | None = None, centre_coeffs: list[acb] | None = None):
        self.P, self.m = P, m
        A, B, H, tau, sigma, n, K, p, S = (P[k] for k in ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S"))
        q2 = H * H / (A * B)
        zero = A * 0
        one = zero + 1
        c = [q2 / tau, q2 + n / (tau * A), 1 / tau, one]
        self.coeffs = [base(x) for x in c]      # the cubic's coefficient balls (constant term first)
        if lams is not None:
            # nested jets: ``lams`` are the eigenvalues' first-order jets over the box (the inner level);
            # the outer gradient is -(dC/dP_k)(lambda) / C'(lambda) in inner (jet) arithmetic
            nested = []
            for idx, (lam, w) in enumerate(lams):
                dC = 3 * lam * lam + 2 * c[2].v * lam + c[1].v
                if not _nonzero(base(dC)):
                    # C'(lambda) as the product of lambda minus the member's other roots (C is monic)
                    dC = _product_derivative(lams, idx)
                if not _nonzero(base(dC)):
                    raise DegenerateSpectrum("C'(lambda) may vanish over the box")
                grad = [-(c[0].d[i] + c[1].d[i] * lam + c[2].d[i] * lam * lam) / dC for i in range(m)]
                nested.append((Jet(lam, grad), w))
            lams = nested
        else:
            lams = self._eigen_jets(c, m, guesses, centre, devs, centre_coeffs)
        for i in range(len(lams)):
            for j in range(i + 1, len(lams)):
                if base(lams[i][0]).overlaps(base(lams[j][0])):
                    raise DegenerateSpectrum("two roots of the cubic (4) overlap over the box")
        self.lam_jets = lams
        self.lams = [l.v for l, _ in lams]
        self.modes = []         # (lambda, weight, proj 5x5 of jets)
        for lam, w in lams:
            r = [one, lam, -(B / H) * lam * lam, (-(A * B / H) * lam * lam * lam - H * lam) / K, zero]
            a = lam + 1 / tau
            # the left eigenvector of flow.Spectrum._cubic_mode times a = lambda + 1/tau (the projector
            # r l^T / (l^T r) does not change): no division by a, which is small where lambda ~ -1/tau
            l = [zero, a * (H / A) / lam, a, K / A, (p / tau) * (K / A) / (lam + 1 / sigma)]
            d = jet_sum((l[i] * r[i] for i in range(5)), m)
            if not _nonzero(base(d)):
                raise DegenerateSpectrum("an eigenvector normalisation l^T r may vanish over the box")
            self.modes.append((lam, w, [[r[i] * l[j] / d for j in range(5)] for i in range(5)]))
        nu = -1 / sigma
        rho2 = -(B / H) * nu * nu
        rho3 = (-(A * B / H) * nu * nu * nu - H * nu) / K
        den = (n / (K * tau)) * rho2 + (nu + 1 / tau) * rho3
        if not _nonzero(base(den)):
            raise DegenerateSpectrum("the -1/sigma eigenvector may be degenerate over the box")
        if any(base(nu).overlaps(base(lam)) for lam, _ in lams):
            raise DegenerateSpectrum("-1/sigma may be a root of the cubic (4) over the box")
        r0 = (p / tau) / den
        r = [r0, r0 * nu, r0 * rho2, r0 * rho3, one]
        self.modes.append((nu, 1, [[r[i] if j == 4 else zero for j in range(5)] for i in range(5)]))
        self.l0 = [one, B * n / (H * H), -A / H, -tau * K / H, -sigma * p * K / H]
        self.s_over_sigma = S / sigma
        z = zero
        self.M = [[z, one, z, z, z], [z, z, -H / B, z, z], [z, H / A, z, K / A, z],
                  [z, z, -n / (K * tau), -1 / tau, p / tau], [z, z, z, z, -1 / sigma]]
        self.eS = [z, z, z, z, S / sigma]

    @staticmethod
    def _eigen_jets(c, m, guesses, centre, devs, centre_coeffs=None):
        """First-order jets of the cubic's roots (module docstring). A root that one interval Newton step over
        the coefficient balls does not verify (they vary independently: over tau +-5 % the real root's family is
        too wide) is verified around its linear predictor in the parameters instead
        (:func:`rigor_gyro.core.implicit_roots.polynomial_root_over_box`, which keeps the coefficients'
        dependence on the parameters), given the centre's roots and coefficients."""
        coeff_balls = [base(x).real for x in c]
        family = polynomial_family(coeff_balls)
        lams, found = [], []
        for k, z in enumerate(guesses):
            if z.imag.is_zero():
                r = newton_family_root(family, z.real)
                v = acb(r) if r is not None else None
                weight = 1
            else:
                v = newton_family_root_complex(coeff_balls, z)
                weight = 2
            if v is None and centre is not None and centre_coeffs is not None and devs is not None:
                v = _root_over_box(c, centre_coeffs, centre[k], list(devs)[:m], weight == 1)
            if weight == 2 and v is not None and not certainly_positive(v.imag):
                v = None
            if v is None or not v.is_finite():
                raise DegenerateSpectrum("a root of the cubic (4) was not verified over the box")
            found.append((v, weight))
        if sum(w for _, w in found) != 3:
            raise DegenerateSpectrum("the cubic's roots were not all found over the box")
        for k, (v, weight) in enumerate(found):
            # C'(lambda) directly, and as the product of lambda minus the other roots (C is monic; the other
            # balls hold the member's other roots): the narrower where both are finite
            dC = 3 * v * v + 2 * c[2].v * v + c[1].v
            prod = _product_derivative(found, k)
            if prod is not None and prod.is_finite():
                if not (prod.real.overlaps(dC.real) and prod.imag.overlaps(dC.imag)):
                    raise AssertionError(f"C'(lambda) = {dC} misses the product of root differences {prod}: a bug")
                if not (dC.is_finite() and _nonzero(dC)):
                    dC = prod
            if not _nonzero(dC):
                raise DegenerateSpectrum("C'(lambda) may vanish over the box")
            grad = [-(c[0].d[i] + c[1].d[i] * v + c[2].d[i] * v * v) / dC for i in range(m)]
            lams.append((_narrow(Jet(v, grad), centre[k] if centre is not None else None, devs or []), weight))
        return lams

    def _pe(self, proj, i: int) -> Jet:
        return proj[i][4] * self.s_over_sigma

    def x0(self, theta: Jet, rows=range(5)) -> list[Jet]:
        """x0(theta) = -tanh(M theta / 2) M^{-1} e S, the listed components (others None)."""
        out = [None] * 5
        p0e0 = self.l0[4] * self.s_over_sigma
        for i in rows:
            tot = -(p0e0 * theta) / 2 if i == 0 else Jet.constant(acb(0), self.m)
            for lam, w, proj in self.modes:
                E = (lam * theta).exp()
                h = (E - 1) / ((E + 1) * lam)
                tot = tot - w * (h * self._pe(proj, i)).real
            out[i] = tot
        return out

    def g(self, theta: Jet) -> Jet:
        """g(theta) = beta0(theta), the half-period function."""
        return self.x0(theta, rows=(0,))[0]

    def G(self, theta: Jet) -> Jet:
        """G = g K, K = prod over the complex pairs of (1 + E)(1 + conj E), E = exp(lambda theta) (as
        :func:`.flow.pole_free_coeffs`): K > 0 for real theta > 0, so G has g's roots, and G has no pole
        where E = -1 (tanh's pole next to theta = pi / omega, which makes g's enclosures over a box wide)."""
        m = self.m
        one = Jet.constant(acb(1), m)
        Es = {}
        K = one
        for idx, (lam, w, proj) in enumerate(self.modes):
            if w == 2:
                E = (lam * theta).exp()
                Es[idx] = E
                K = K * ((1 + E) * (1 + E.conjugate())).real
        tot = -(self.l0[4] * self.s_over_sigma * theta) / 2 * K
        for idx, (lam, w, proj) in enumerate(self.modes):
            pe0 = self._pe(proj, 0)
            if w == 2:
                E = Es[idx]
                others = one
                for o, Eo in Es.items():
                    if o != idx:
                        others = others * ((1 + Eo) * (1 + Eo.conjugate())).real
                term = (E - 1) * (1 + E.conjugate()) / lam * others
            else:
                E = (lam * theta).exp()
                term = (E - 1) / ((E + 1) * lam) * K
            tot = tot - w * (term * pe0).real
        return tot

    def component(self, i: int, x0: list[Jet]):
        """x_i(t) = sum w Re(alpha e^{lambda t}) + c0 + c1 t from x(0) = x0 with u = +S:
        ([(alpha, lambda, w)], c0, c1)."""
        terms = []
        c1 = self.l0[4] * self.s_over_sigma if i == 0 else Jet.constant(acb(0), self.m)
        c0 = jet_sum((self.l0[j] * x0[j] for j in range(5)), self.m) if i == 0 else Jet.constant(acb(0), self.m)
        for lam, w, proj in self.modes:
            pe = self._pe(proj, i)
            q = pe / lam
            alpha = jet_sum((proj[i][j] * x0[j] for j in range(5)), self.m) + q
            terms.append((alpha, lam, w))
            c0 = c0 - w * q.real
        return terms, c0, c1

    @staticmethod
    def evaluate(comp, t: Jet, derivative: int = 0) -> Jet:
        """x_i(t) (derivative 0) or x_i'(t) (1) from :meth:`component`."""
        terms, c0, c1 = comp
        tot = c1 if derivative else c0 + c1 * t
        for alpha, lam, w in terms:
            a = alpha * lam if derivative else alpha
            tot = tot + w * (a * (lam * t).exp()).real
        return tot

    def jacobian(self, theta: Jet, x0: list[Jet]) -> list[list[Jet]]:
        """The half-period Jacobian -(Phi - f e1^T Phi / f_0) on rows/columns 1..4 (as
        :func:`.flow.half_period_jacobian`), Phi = exp(M theta), f = -M x0 + e S."""
        Phi = [[(self.l0[j] if i == 0 else Jet.constant(acb(0), self.m)) for j in range(5)] for i in range(5)]
        for lam, w, proj in self.modes:
            E = (lam * theta).exp()
            for i in range(5):
                for j in range(1, 5):
                    Phi[i][j] = Phi[i][j] + w * (E * proj[i][j]).real
        f = [self.eS[i] - jet_sum((self.M[i][j] * x0[j] for j in range(5)), self.m) for i in range(5)]
        return [[-(Phi[i][j] - f[i] * Phi[0][j] / f[0]) for j in range(1, 5)] for i in range(1, 5)]


def _root_over_box(c: list, centre_coeffs: list, centre_root: acb, devs: list, is_real: bool) -> acb | None:
    """The root of the cubic C(z; P) = sum c_i z^i continuing ``centre_root`` over the box
    (:func:`rigor_gyro.core.implicit_roots.polynomial_root_over_box`; a ball containing it for every member, or
    None), first as written, then in the scaled variable w = z / c_2 (C(c_2 w) / c_2^3 has the coefficients
    c_0 / c_2^3, c_1 / c_2^2, 1, 1; its roots move far less over a box of tau, where the stiff real root is
    about -1/tau = -c_2): then z = c_2 w, enclosed as the product of the two balls."""
    r = polynomial_root_over_box(c, centre_coeffs, centre_root, devs, is_real)
    if r is None:
        s = c[2]
        scaled = [c[0] / (s * s * s), c[1] / (s * s), c[3], c[3]]     # c[3] = 1 exactly
        sc = centre_coeffs[2]
        scaled_centre = [centre_coeffs[0] / (sc * sc * sc), centre_coeffs[1] / (sc * sc), acb(1), acb(1)]
        w = polynomial_root_over_box(scaled, scaled_centre, centre_root / sc, devs, is_real)
        if w is None:
            return None
        r = acb(w) * base(s)
        return acb(r.real) if is_real else r
    return acb(r)


def _product_derivative(lams, idx: int):
    """C'(lambda) for the root number ``idx`` of the monic cubic (4) as the product of lambda minus the other
    roots (the other entries of ``lams`` and the conjugates of the complex ones, each holding the member's other
    roots): no cancellation, where the direct 3 lambda^2 + 2 lambda / tau + q2 + n / (tau A) over a wide box of
    tau may reach 0. Jets or balls alike."""
    lam = lams[idx][0]
    out = None
    for j, (mu, w) in enumerate(lams):
        for o in ([mu] if j != idx else []) + ([mu.conjugate()] if w == 2 else []):
            out = (lam - o) if out is None else out * (lam - o)
    return out


def parameter_jets(values: dict[str, arb], dirs: list[str], extra: int = 0) -> dict[str, Jet]:
    """{name: Jet}: the names in ``dirs`` free variables (unit gradients, in that order), the rest
    constants; ``extra`` further directions (theta, t) after them."""
    m = len(dirs) + extra
    return {k: (Jet.variable(acb(v), dirs.index(k), m) if k in dirs else Jet.constant(acb(v), m))
            for k, v in values.items()}


def nested_parameter_jets(first_order: dict[str, Jet], dirs: list[str], extra: int = 0) -> dict[str, Jet]:
    """Second-order (nested) parameter jets from first-order ones over the box: the outer gradient of a
    free variable is its unit vector, the inner level the first-order jet (see :mod:`rigor_gyro.core.jets`)."""
    m = len(dirs) + extra
    return {k: Jet(j, [acb(1) if (k in dirs and dirs.index(k) == i) else acb(0) for i in range(m)])
            for k, j in first_order.items()}


def nested_variable(value, k: int, m: int) -> Jet:
    """A free variable (number k of m) as a nested jet over its ball."""
    return Jet(Jet.variable(acb(value), k, m), [acb(1) if i == k else acb(0) for i in range(m)])
