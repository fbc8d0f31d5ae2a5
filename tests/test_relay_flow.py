"""The relay model's series near theta = 0 and its spectrum, against independent evaluations: the
power series of g near 0 (NearZeroSeries: its coefficients, its tail bound recomputed in mpmath from
the formula in its docstring, the Cauchy bound of its Taylor coefficients at a ball), G's coefficients
on a box spectrum (where g comes from that series), and a degenerate spectrum refused by name."""
import mpmath
import pytest
from flint import acb, arb, arb_mat, fmpq

from rigor_gyro import load_scene
from rigor_gyro.core.balls import exact_fraction, interval, working_precision
from rigor_gyro.kinds.periodic_orbit import validate as relay_validate
from rigor_gyro.kinds.periodic_orbit.boxes import BoxSpectrum
from rigor_gyro.kinds.periodic_orbit.flow import (DegenerateSpectrum, NearZeroSeries, RelayParams, Spectrum,
                                                  g_coeffs, pole_free_coeffs)

PREC = 128


def _printed():
    """The paper's scene at 128 bits: its parameters, point spectrum and near-zero series (800 terms).
    Built afresh by each test (0.2 s): a cached copy would hide a mutant of the code that builds it."""
    m = relay_validate(load_scene("roitenberg1947"))
    with working_precision(PREC):
        sp = Spectrum(m.params)
        S = arb(fmpq(m.params.S.p, m.params.S.q))
        return m.params, sp, NearZeroSeries(sp.M, sp.e, S), S


def _mp(x: arb) -> mpmath.mpf:
    q = exact_fraction(x.mid())
    return mpmath.mpf(q.numerator) / q.denominator


def _rel(a: arb, b, tol: float) -> bool:
    return abs(_mp(a) - b) <= tol * abs(b)


def test_the_series_coefficients_are_gs_taylor_coefficients_at_0():
    """a_j (g = sum a_j theta^(2j+1)) is g's Taylor coefficient 2j+1 at 0 from the spectral sum (g_coeffs),
    for j < 12 and to the last digits both carry; g is odd, so there is no other."""
    _, sp, nz, _ = _printed()
    with working_precision(PREC):
        gc = g_coeffs(sp, arb(0), 24)
    assert nz.J == 800 and len(nz.a) == 801
    for j in range(12):
        assert nz.a[j].is_finite() and gc[2 * j + 1].is_finite() and nz.a[j].overlaps(gc[2 * j + 1]), j
        assert nz.a[j].rad() <= abs(nz.a[j].mid()) * arb(2) ** -60 + arb(10) ** -30, j
        assert gc[2 * j].is_finite() and gc[2 * j].contains(0)
    assert abs(_mp(nz.a[2]) - 859.2910849) < 1e-7


def test_the_tail_bound_is_the_documented_formula():
    """T = (2 pi^2/3) S |e|_inf Cmax rho/pi^2 q^(J+1)/(1-q), with nu = max(|M^N|_inf, 1)^(1/N), Cmax = max over
    r < N of |M^r|_inf nu^-r, rho = 0.95 pi/nu, q = (rho nu/pi)^2, all recomputed here in mpmath at 60 digits
    from the matrix's midpoints (N = 64, J = 800): any factor of the bound shrunk or dropped is seen."""
    _, sp, nz, S = _printed()
    mpmath.mp.dps = 60
    M = mpmath.matrix([[_mp(sp.M[i, j]) for j in range(5)] for i in range(5)])
    norm = lambda W: max(sum(abs(W[i, j]) for j in range(5)) for i in range(5))        # noqa: E731
    W, norms = mpmath.eye(5), []
    for _ in range(64):
        norms.append(norm(W))
        W = W * M
    nu = max(norm(W), mpmath.mpf(1)) ** (mpmath.mpf(1) / 64)
    cmax = max(norms[r] / nu ** r for r in range(64))
    rho = mpmath.mpf("0.95") * mpmath.pi / nu
    q = (rho * nu / mpmath.pi) ** 2
    enorm = max(abs(_mp(x)) for x in sp.e)
    T = (2 * mpmath.pi ** 2 / 3) * abs(_mp(S)) * enorm * cmax * rho / mpmath.pi ** 2 * q ** 801 / (1 - q)
    assert _rel(nz.nu, nu, 1e-25) and _rel(nz.cmax, cmax, 1e-25) and _rel(nz.rho, rho, 1e-25)
    assert _rel(nz.tail, T, 1e-25) and nz.tail.lower() >= 0
    assert _rel(nz.reach, rho * mpmath.mpf(0.85), 1e-25)      # the float 0.85, exactly


def test_taylor_coefficients_at_a_ball_carry_the_cauchy_bound_of_the_tail():
    """coeffs(c, n)[k] = P^(k)(c)/k! (P the truncated series; recomputed in mpmath from the a_j) plus
    [+- T / (rho - |c|_upper)^k]: at a ball c of radius 1e-6 the radius covers both the ball's spread and
    the Cauchy bound with |c|'s upper end; at a point the coefficients agree with g's spectral ones; beyond
    the reach (0.85 rho) nothing is returned."""
    _, sp, nz, _ = _printed()
    mpmath.mp.dps = 60
    a = [_mp(x) for x in nz.a[:60]]
    with working_precision(PREC):
        t = (nz.reach * arb("0.5")).mid()
        got = nz.coeffs(t, 4)
        want = g_coeffs(sp, t, 4)
        c = _mp(t)
        for k in range(4):
            # P^(k)(c)/k! = sum_j a_j binom(2j+1, k) c^(2j+1-k)
            exact = sum(a[j] * mpmath.binomial(2 * j + 1, k) * c ** (2 * j + 1 - k) for j in range(60) if 2 * j + 1 >= k)
            assert abs(_mp(got[k]) - exact) <= abs(exact) * 1e-25 + 1e-40, k
            assert got[k].is_finite() and want[k].is_finite() and got[k].overlaps(want[k]) and got[k].rad() <= abs(want[k].mid()) * arb(10) ** -20, k
            cauchy = nz.tail / (nz.rho - abs(t)) ** k
            assert got[k].rad() >= cauchy.lower() * (1 - arb(10) ** -9), k
        wide = arb(t, arb("1e-6"))
        ball_coeffs = nz.coeffs(wide, 3)
        for k in range(3):
            cauchy = nz.tail / (nz.rho - abs(wide).upper()) ** k
            assert ball_coeffs[k].is_finite() and ball_coeffs[k].rad() >= cauchy.lower() and ball_coeffs[k].contains(got[k].mid()), k
            assert ball_coeffs[k].contains(nz.coeffs(wide.upper(), 3)[k].mid()), k
        assert nz.coeffs(nz.reach.lower(), 2) is not None and nz.coeffs(nz.reach * (1 + arb(10) ** -20), 2) is None


def test_on_a_box_spectrum_g_and_G_come_from_the_series_near_0():
    """A box of width 2e-20 around the printed n: near 0 the box spectrum's G (= g K) comes from the
    near-zero series times K's series; it agrees with the point spectrum's G (computed from the spectral
    terms) to 1e-15 relative, so a wrong Cauchy product (a term divided, a sum started at 1) is seen."""
    P, sp, nz, _ = _printed()
    h = fmpq(1, 10 ** 20)
    with working_precision(PREC):
        Pb = RelayParams(**{k: (interval(arb(v) - arb(h), arb(v) + arb(h)) if k == "n" else arb(v))
                            for k, v in vars(P).items()})
        box = BoxSpectrum(Pb, P)
        for frac in ("0.1", "0.5", "0.8"):
            t = (box.near_zero.reach * arb(frac)).mid()
            got, want = pole_free_coeffs(box, t, 3), pole_free_coeffs(sp, t, 3)
            for k in range(3):
                assert got[k].is_finite() and want[k].is_finite() and got[k].overlaps(want[k]), (frac, k)
                assert got[k].rad() <= abs(want[k].mid()) * arb(10) ** -15, (frac, k, got[k], want[k])


def test_minus_one_over_sigma_a_root_of_the_cubic_is_a_degenerate_spectrum():
    """A = B = H = tau = 1, n = 5/4, sigma = 2: -1/2 is a root of the cubic (4) too (a repeated eigenvalue of
    M); the spectrum refuses it by name instead of building projectors for a non-diagonalisable M."""
    P = RelayParams.from_strings(A="1", B="1", H="1", tau="1", sigma="2", n="5/4", K="1", p="1", S="1")
    with working_precision(PREC), pytest.raises(DegenerateSpectrum, match="-1/sigma is also a root"):
        Spectrum(P)
    Q = P.replace(n="1")        # one parameter moved: not degenerate, and the spectrum is built
    with working_precision(PREC):
        assert len(Spectrum(Q).eigenvalues()) == 5


def test_an_exact_repeated_eigenvalue_stops_the_escalation_at_once():
    """The same point as a scene: the degeneracy is exact, so every claim is inconclusive at the first
    precision, says that no precision lifts it and does not suggest a higher --maxprec (it escalated to
    4096 bits and suggested --maxprec 8192)."""
    from rigor_gyro import parse_scene, prove_scene
    text = ('name = "rep"\nkind = "periodic_orbit"\n[parameters]\n'
            + "".join(f'{k} = "{v}"\n' for k, v in dict(A="1", B="1", H="1", tau="1", sigma="2", n="5/4", K="1",
                                                         p="1", S="1").items()))
    cert = prove_scene(parse_scene(text))
    assert cert.verdict.value == "inconclusive" and cert.precisions_tried == [64], cert.precisions_tried
    assert all("no precision lifts it" in c.reason and c.status.value == "inconclusive" for c in cert.claims)


def test_with_few_terms_the_cauchy_bound_uses_the_far_end_of_a_ball():
    """With 4 terms the tail (about 0.15) dominates every coefficient: at a ball c of radius 1e-3 the
    radius of coefficient k must cover T / (rho - |c|_upper)^k, the bound at the ball's far end (|c|'s
    lower end would give one about 20 % smaller for k = 2 here)."""
    P, sp, _, S = _printed()
    with working_precision(PREC):
        nz = NearZeroSeries(sp.M, sp.e, S, terms=4)
        wide = arb((nz.reach * arb("0.5")).mid(), arb("1e-3"))
        got = nz.coeffs(wide, 3)
        for k in range(3):
            assert got[k].rad() >= (nz.tail / (nz.rho - abs(wide).upper()) ** k).lower(), k
        assert nz.coeffs(arb(nz.reach.lower().mid(), arb("1e-3")), 2) is None       # reaches past the reach


def test_a_series_the_cap_cut_gives_nan_coefficients_not_a_crash(monkeypatch):
    """pole_free_coeffs: where series_coefficients refuses a series cut by ctx.cap (ValueError), the
    coefficients are NaN (they decide nothing), not an exception."""
    from rigor_gyro.kinds.periodic_orbit import flow

    def refuse(s, n):
        raise ValueError("cut by the cap")
    _, sp, _, _ = _printed()
    monkeypatch.setattr(flow, "series_coefficients", refuse)
    with working_precision(PREC):
        out = pole_free_coeffs(sp, arb("0.1"), 3)
    assert len(out) == 3 and all(x.is_nan() for x in out)


def test_the_spectrum_is_ms_eigenvalues_and_the_multipliers_a_matrixs():
    """eigenvalues(): 0, the cubic's roots (a complex pair as both conjugates) and -1/sigma: each contains
    one of mpmath's eigenvalues of M (midpoints, 40 digits), and each of those is in one. multipliers(J):
    the eigenvalues of a ball matrix J (Rump's method), each containing one of mpmath's for J's midpoint."""
    _, sp, _, _ = _printed()
    mpmath.mp.dps = 40
    M = mpmath.matrix([[_mp(sp.M[i, j]) for j in range(5)] for i in range(5)])
    ref = mpmath.eig(M)[0]
    with working_precision(PREC):
        got = sp.eigenvalues()
        assert len(got) == 5 and got[0] == 0
        assert all(g.is_finite() for g in got)                       # a NaN ball would hold every z
        for z in ref:
            w = acb(arb(mpmath.nstr(z.real, 35)), arb(mpmath.nstr(z.imag, 35)))
            assert sum(1 for g in got if (g - w).contains(0) or abs(g - w) < arb(10) ** -25) == 1, z
        J = arb_mat([[arb(mpmath.nstr(M[i, j] / 50 + (i == j), 40)) for j in range(4)] for i in range(4)])
        eig = sp.multipliers(J, arb("0.1"))
        refJ = mpmath.eig(mpmath.matrix([[M[i, j] / 50 + (i == j) for j in range(4)] for i in range(4)]))[0]
        assert len(eig) == 4
        for z in refJ:
            w = acb(arb(mpmath.nstr(z.real, 35)), arb(mpmath.nstr(z.imag, 35)))
            assert any(abs(g - w) < arb(10) ** -25 for g in eig), z
