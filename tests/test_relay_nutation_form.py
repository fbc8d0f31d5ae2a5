"""The nutation form of the pole-free G (kinds/periodic_orbit/nutation_form.py) and the fast-nutation root search
that uses it (g_roots.isolation_coeffs with T, _quadratic_start, the clipped bracket of _newton_bracket).

Oracles: G and its derivatives recomputed in mpmath from M's eigen-decomposition (50 digits), sampled over a
ball; the roots of the fast-nutation search compared with the default search's and with mpmath signs."""
from __future__ import annotations

import mpmath
import pytest
from flint import arb

from rigor_gyro.core.balls import exact_fraction, interval, working_precision
from rigor_gyro.core.roots import RootStatus
from rigor_gyro.kinds.periodic_orbit import g_roots as C
from rigor_gyro.kinds.periodic_orbit import nutation_form as NF
from rigor_gyro.kinds.periodic_orbit.flow import RelayParams, Spectrum, pole_free_coeffs, system_matrix

BASE = dict(A="125", B="0.133", H="100", tau="0.01", sigma="0.13125", n="50", K="7.5", p="40", S="0.15")


def _params(**kw) -> RelayParams:
    d = dict(BASE)
    d.update(kw)
    return RelayParams.from_strings(**d)


def _mp_G(P: RelayParams):
    """theta -> G(theta) = g(theta) |1 + exp(lambda theta)|^2 in mpmath (g from M's eigen-decomposition)."""
    mpmath.mp.dps = 50
    Mq = system_matrix(P)
    M = mpmath.matrix([[mpmath.mpf(int(Mq[i, j].p)) / int(Mq[i, j].q) for j in range(5)] for i in range(5)])
    e = mpmath.matrix([0, 0, 0, 0, 1 / (mpmath.mpf(int(P.sigma.p)) / int(P.sigma.q))])
    S = mpmath.mpf(int(P.S.p)) / int(P.S.q)
    lam, R = mpmath.eig(M)
    L = mpmath.inverse(R)
    pair = [z for z in lam if mpmath.im(z) > 0][0]

    def G(t):
        g = 0
        for k, z in enumerate(lam):
            w = R[0, k] * sum(L[k, j] * e[j] for j in range(5))
            g += w * (t / 2 if abs(z) < mpmath.mpf(10) ** -30 else mpmath.tanh(z * t / 2) / z)
        g = -S * mpmath.re(g)
        return g * abs(1 + mpmath.exp(pair * t)) ** 2
    return G


def _mp(x) -> mpmath.mpf:
    q = exact_fraction(x)
    return mpmath.mpf(q.numerator) / q.denominator


@pytest.mark.parametrize("H", ["100", "1e5"])
def test_the_nutation_form_encloses_G_and_its_derivatives_over_a_ball(H, monkeypatch):
    """Every mpmath value of G^(j)(t)/j! (j < 4) at points t of the ball lies in the certified ball, and the
    point coefficients overlap those of pole_free_coeffs' complex series algebra (the same function)."""
    monkeypatch.setattr(NF, "FAST_NUTATION_RATIO", 10 ** 12)      # pole_free_coeffs: the series algebra
    P = _params(H=H)
    G = _mp_G(P)
    with working_precision(128):
        sp = Spectrum(P)
        form = NF.nutation_form(sp)
        lo = arb("0.0123").mid()
        hi = (lo + arb("3e-6")).mid()
        X = interval(lo, hi)
        for n in (1, 2, 3, 4):                 # n <= 3: the closed forms without series; 4: the series
            over = form.coeffs(X, n)
            assert len(over) == n
            for k in range(5):
                t = _mp(lo) + (_mp(hi) - _mp(lo)) * k / 4
                for j in range(n):
                    v = mpmath.diff(G, t, j) / mpmath.factorial(j)
                    b = over[j]
                    slack = abs(v) * mpmath.mpf(10) ** -30
                    assert _mp(b.lower()) - slack <= v <= _mp(b.upper()) + slack, (H, n, k, j)
        for n in (1, 2, 3):                    # at a point the short path agrees with the series' coefficients
            for x, y in zip(form.coeffs(lo, n), form.coeffs(lo, 9)):
                assert x.overlaps(y)
        c = arb("0.0371")
        for x, y in zip(form.coeffs(c, 9), pole_free_coeffs(sp, c, 9)):
            assert x.overlaps(y)
            assert x.rad() < abs(x.mid()) * arb("1e-20") + arb("1e-60")


def test_the_nutation_form_refuses_what_it_does_not_fit():
    with working_precision(64):
        sp = Spectrum(_params(tau="1"))            # three real roots of the cubic: no pair
        if sum(m.weight == 2 for m in sp.modes) == 0:
            assert NF.nutation_form(sp) is None
            assert NF.fast_form(sp) is None
        sp = Spectrum(_params())
        assert NF.nutation_form(sp) is not None


def test_only_a_fast_nutation_takes_the_form_in_pole_free_coeffs():
    """The paper scene (H = 100) and H = 1e4 keep the complex series algebra (certificate bytes); H = 1e5
    gets the nutation form from pole_free_coeffs itself (the checker's function too)."""
    with working_precision(64):
        for H in ("100", "1e4"):
            sp = Spectrum(_params(H=H))
            assert NF.fast_form(sp) is None
            coeffs, _ = C.isolation_coeffs(sp)
            assert not coeffs.nutation
        sp5 = Spectrum(_params(H="1e5"))
        form = NF.fast_form(sp5)
        assert form is not None and NF.fast_form(sp5) is form
        c = arb("0.0123").mid()
        assert all(x.mid() == y.mid() and x.rad() == y.rad() for x, y in zip(pole_free_coeffs(sp5, c, 9), form.coeffs(c, 9)))
        coeffs, name = C.isolation_coeffs(sp5)
        assert name == "pole_free" and coeffs.nutation


def _roots(H: str, fast: bool, monkeypatch, lo: str, hi: str):
    monkeypatch.setattr(NF, "FAST_NUTATION_RATIO", 0 if fast else 10 ** 12)
    with working_precision(64):
        sp = Spectrum(_params(H=H))
        coeffs, _ = C.isolation_coeffs(sp)
        assert coeffs.nutation == fast
        iso = C.isolate_pieces(C.g_series_function(sp, coeffs), arb(lo), arb(hi), coeffs=coeffs,
                         root_free=C.envelope_test(sp))
    assert not iso.unknown
    return iso


@pytest.mark.parametrize("H, lo, hi", [("1e4", "0.001", "0.03"), ("1e3", "0.004", "0.2")])
def test_the_fast_search_finds_the_default_searchs_roots_and_mpmath_sees_each_sign_change(H, lo, hi, monkeypatch):
    """Same number of roots as the default search (the complex series algebra, midpoint Newton start), pairwise
    overlapping enclosures; G changes sign across every UNIQUE piece's enclosure (mpmath, 50 digits,
    at the enclosure's ends widened by its radius: a root counted that is not there would fail)."""
    fast = _roots(H, True, monkeypatch, lo, hi)
    slow = _roots(H, False, monkeypatch, lo, hi)
    assert len(fast.roots) == len(slow.roots) > 4
    for a, b in zip(fast.roots, slow.roots):
        assert a.overlaps(b)
    G = _mp_G(_params(H=H))
    pieces = fast.pieces
    assert all(pieces[i].hi.overlaps(pieces[i + 1].lo) for i in range(len(pieces) - 1))   # a tiling
    for r in fast.roots:
        w = _mp(r.rad()) + abs(_mp(r.mid())) * mpmath.mpf(2) ** -60
        assert G(_mp(r.mid()) - w) * G(_mp(r.mid()) + w) < 0


def test_a_bracket_next_to_an_end_is_clipped_to_that_end(monkeypatch):
    """A monotone stretch whose root lies within the bracket's half-width of an end: the clipped bracket uses
    that end (its sign certified by the caller) and interval Newton then proves the root inside it."""
    monkeypatch.setattr(NF, "FAST_NUTATION_RATIO", 0)
    with working_precision(64):
        sp = Spectrum(_params(H="1e4"))
        coeffs, _ = C.isolation_coeffs(sp)
        f = C.g_series_function(sp, coeffs)
        iso = C.isolate_pieces(f, arb("0.001"), arb("0.03"), coeffs=coeffs, root_free=C.envelope_test(sp))
        r = iso.roots[len(iso.roots) // 2]
        a, b = (r.mid() - arb("1e-14")).mid(), (r.mid() + arb("1e-7")).mid()
        ga = C._sign(coeffs(a, 1)[0])
        assert ga != 0 and C._sign(coeffs(b, 1)[0]) == -ga
        br = C._newton_bracket(coeffs, arb(a), arb(b), ga)
        assert br is not None
        lo, hi = br
        assert lo.overlaps(arb(a)) or hi.overlaps(arb(b))
        piece = C.newton_root(f, lo, hi)
        assert piece.status is RootStatus.UNIQUE and piece.enclosure.overlaps(r)
