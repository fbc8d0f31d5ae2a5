"""The relay kind's root isolation helpers on polynomials whose roots are known exactly.

The relay prover's g is a sum of exponentials, but the helpers that decide a piece of the root search
(:func:`_monotone_side`, :func:`_newton_bracket`, :func:`_critical_split`, :func:`_isolate`) see g only
through its Taylor coefficients ``coeffs(center, n)``. Fed the coefficients of a polynomial, their
verdicts can be checked against the exact roots: every piece called root-free holds no root, every
piece called unique holds exactly one, the pieces tile the range, and a helper that cannot decide says
None rather than guessing. A lying derivative (Newton's search misled) must never produce a bracket
whose signs were not certified.
"""
from math import factorial

import pytest
from flint import arb, arb_poly, fmpq, fmpq_poly

from rigor_gyro.core.balls import series_coefficients, working_precision
from rigor_gyro.core.roots import RootStatus
from rigor_gyro.kinds.periodic_orbit import claims
from rigor_gyro.kinds.periodic_orbit.claims import RootVerdict, _select
from rigor_gyro.kinds.periodic_orbit.g_roots import (ENVELOPE_REASON, _critical_split, _monotone_side, _newton_bracket,
                                                     _split_point, g_series_function as _g_series_function,
                                                     isolate_pieces as _isolate)


def poly_coeffs(coefficients, derivative_scale=1):
    """coeffs(center, n) of the polynomial with these rational coefficients (lowest degree first): balls
    containing p^(j)(c)/j! for every c in the ball ``center``. ``derivative_scale`` multiplies the
    derivative terms (j >= 1): a lying derivative, for the search-only paths."""
    P = fmpq_poly([fmpq(c) if not isinstance(c, fmpq) else c for c in coefficients])

    def coeffs(center, n):
        out, D = [], P
        for j in range(n):
            val = arb_poly([arb(D[i]) for i in range(D.degree() + 1)])(center) if D.degree() >= 0 else arb(0)
            out.append(val / factorial(j) * (derivative_scale if j >= 1 else 1))
            D = D.derivative()
        return out
    return coeffs


def _tiles(pieces, a, b):
    assert pieces[0].lo == a and pieces[-1].hi == b
    for p, q in zip(pieces, pieces[1:]):
        assert p.hi == q.lo, "pieces must tile the range with shared exact endpoints"


def _check_against_roots(pieces, roots):
    """Each root lies in exactly one unique piece's enclosure and in no empty piece."""
    for r in roots:
        holders = [p for p in pieces if p.lo <= r <= p.hi or p.lo.overlaps(r) or p.hi.overlaps(r)]
        assert not any(p.status is RootStatus.EMPTY and p.lo < r < p.hi for p in holders), \
            f"a piece called root-free holds the root {r}"
        unique = [p for p in holders if p.status is RootStatus.UNIQUE]
        assert len(unique) == 1 and unique[0].enclosure.is_finite() and unique[0].enclosure.overlaps(r)
    assert sum(p.status is RootStatus.UNIQUE for p in pieces) == len(roots)


def test_a_monotone_piece_with_one_root_is_split_around_it():
    # p(x) = x^3 + x - 1: increasing, one root 0.68232780382801932737...
    co = poly_coeffs([-1, 1, 0, 1])
    f = _g_series_function(None, co)
    a, b = arb(0), arb(1)
    pieces = _monotone_side(f, co, a, b)
    assert pieces is not None
    _tiles(pieces, a, b)
    root = arb("0.682327803828019327369483739711 +/- 1e-29")
    _check_against_roots(pieces, [root])
    assert [p.status for p in pieces].count(RootStatus.EMPTY) == len(pieces) - 1


def test_a_monotone_piece_without_a_sign_change_is_one_empty_piece():
    co = poly_coeffs([-1, 1, 0, 1])
    pieces = _monotone_side(_g_series_function(None, co), co, arb("0.7"), arb(1))
    assert len(pieces) == 1 and pieces[0].status is RootStatus.EMPTY


def test_a_monotone_piece_ending_on_a_root_is_not_decided():
    # x^3 + x - 2 has the root 1 exactly: g(1) has no strict sign
    co = poly_coeffs([-2, 1, 0, 1])
    assert _monotone_side(_g_series_function(None, co), co, arb(0), arb(1)) is None
    assert _monotone_side(_g_series_function(None, co), co, arb(1), arb(2)) is None


def test_newtons_bracket_is_narrow_and_certified():
    co = poly_coeffs([-1, 1, 0, 1])
    root = arb("0.682327803828019327369483739711 +/- 1e-29")
    lo, hi = _newton_bracket(co, arb(0), arb(1), -1)
    assert lo < root < hi
    assert arb(0) < lo and hi < arb(1)
    assert hi - lo < arb("1e-6")
    # the same from a start far from the root (a steep polynomial whose root is near an end)
    co2 = poly_coeffs([-1, 1000])                     # root 1/1000
    lo, hi = _newton_bracket(co2, arb(0), arb(1), -1)
    assert lo < arb(fmpq(1, 1000)) < hi and hi - lo < arb("1e-6")


@pytest.mark.parametrize("scale", [arb(10) ** 30, arb(10) ** -30, arb(-1)])
def test_a_lying_derivative_never_gives_an_uncertified_bracket(scale):
    """Newton's search only proposes: with a derivative 1e30 too large (steps too short), 1e30 too small
    (steps overshoot) or of the wrong sign, a bracket comes back only if its signs are certified."""
    true, lying = poly_coeffs([-1, 1, 0, 1]), poly_coeffs([-1, 1, 0, 1], derivative_scale=scale)
    root = arb("0.682327803828019327369483739711 +/- 1e-29")
    out = _newton_bracket(lying, arb(0), arb(1), -1)
    if out is not None:
        lo, hi = out
        assert true(lo, 1)[0] < 0 < true(hi, 1)[0]
        assert lo < root < hi


def test_newtons_bracket_gives_up_on_a_vanishing_derivative():
    co = poly_coeffs([-1, 0, 0, 1], derivative_scale=0)
    assert _newton_bracket(co, arb(0), arb(2), -1) is None


@pytest.mark.parametrize("gap, roots", [
    (fmpq(1, 100), [fmpq(7, 30), fmpq(13, 30)]),          # (x - 1/3)^2 - 1/100: roots 1/3 -+ 1/10
    (fmpq(-1, 100), []),                                  # (x - 1/3)^2 + 1/100: no root, a minimum 1/100
    (fmpq(1, 10 ** 40), [fmpq(1, 3) - fmpq(1, 10 ** 20), fmpq(1, 3) + fmpq(1, 10 ** 20)]),   # 2e-20 apart
])
def test_a_convex_piece_is_decided_at_its_critical_point(gap, roots):
    # (x - 1/3)^2 - gap = x^2 - 2x/3 + 1/9 - gap (the critical point 1/3 is not a dyadic: its enclosure
    # has width, as the critical point of g has)
    co = poly_coeffs([fmpq(1, 9) - gap, fmpq(-2, 3), 1])
    f = _g_series_function(None, co)
    a, b = arb(0), arb(1)
    with working_precision(256):
        pieces = _critical_split(f, co, a, b)
        assert pieces is not None
        _tiles(pieces, a, b)
        _check_against_roots(pieces, [arb(r) for r in roots])


def test_a_piece_with_an_inflection_is_left_to_bisection():
    # x^3 - x/4 on [-1, 1]: g'' = 6x changes sign at 0
    co = poly_coeffs([0, fmpq(-1, 4), 0, 1])
    assert _critical_split(_g_series_function(None, co), co, arb(-1), arb(1)) is None


def test_a_critical_point_on_a_root_is_not_decided():
    # (x - 1/3)^2: a double root at the critical point; g there has no strict sign
    co = poly_coeffs([fmpq(1, 9), fmpq(-2, 3), 1])
    assert _critical_split(_g_series_function(None, co), co, arb(0), arb(1)) is None


@pytest.mark.parametrize("signed", [False, True])
def test_isolation_of_a_polynomial_finds_every_root_once(signed):
    # (x - 1/5)(x - 1/3)(x - 1/2)(x - 7/8)(x - 9/10): five simple roots in [0, 1]
    rs = [fmpq(1, 5), fmpq(1, 3), fmpq(1, 2), fmpq(7, 8), fmpq(9, 10)]
    P = fmpq_poly([1])
    for r in rs:
        P *= fmpq_poly([-r, 1])
    co = poly_coeffs([P[i] for i in range(P.degree() + 1)])
    iso = _isolate(_g_series_function(None, co), arb(0), arb(1), coeffs=co, signed_split=signed)
    assert not iso.unknown
    _tiles(iso.pieces, arb(0), arb(1))
    assert len(iso.roots) == 5
    for r, enc in zip(rs, sorted(iso.roots, key=lambda x: float(x.mid()))):
        assert enc.is_finite() and enc.overlaps(arb(r))
    assert all(p.status in (RootStatus.EMPTY, RootStatus.UNIQUE) for p in iso.pieces)


def test_isolation_stops_at_a_double_root_and_reports_the_rest_unexamined():
    # (x - 1/3)^2 (x - 3/4): the double root can never be proved simple
    P = fmpq_poly([-fmpq(1, 3), 1]) ** 2 * fmpq_poly([-fmpq(3, 4), 1])
    co = poly_coeffs([P[i] for i in range(P.degree() + 1)])
    iso = _isolate(_g_series_function(None, co), arb(0), arb(1), coeffs=co, max_depth=20)
    assert iso.unknown
    assert any(p.lo <= arb(fmpq(1, 3)) <= p.hi for p in iso.unknown)
    assert not any(p.status is RootStatus.EMPTY and p.lo < arb(fmpq(1, 3)) < p.hi for p in iso.pieces)
    assert iso.resume is not None
    decided, stop = iso.resume
    assert all(certainly_le_or_equal(p.hi, stop) for p in decided)


def certainly_le_or_equal(x, y):
    return x < y or x == y


def test_the_split_point_keeps_to_the_midpoint_unless_asked():
    co = poly_coeffs([fmpq(-1, 2), 1])                # x - 1/2: g(1/2) = 0 exactly
    assert _split_point(co, arb(0), arb(1), False) == arb(fmpq(1, 2))
    assert _split_point(co, arb(0), arb(1), True) == arb(fmpq(3, 8))
    assert _split_point(None, arb(0), arb(1), True) == arb(fmpq(1, 2))


def _verdict(stable):
    return RootVerdict(arb(1), [], "genuine", "", stable=stable)


def test_the_selected_orbit_is_a_stable_one_whenever_one_is():
    """Issue 37: a margin is never reported of an unstable orbit while `stable` holds by another."""
    a, b, c = _verdict(None), _verdict(True), _verdict(False)
    v, why = _select([a, b, c])
    assert v is b and why == "the stable genuine orbit"
    d = _verdict(True)
    v, why = _select([a, b, d])
    assert v is b and why == "the shortest stable genuine orbit (several are stable)"
    v, why = _select([a, c])
    assert v is a and why == "the shortest genuine orbit (none is certified stable)"
    assert _select([]) == (None, "no genuine orbit")


def _five_roots():
    rs = [fmpq(1, 5), fmpq(1, 3), fmpq(1, 2), fmpq(7, 8), fmpq(9, 10)]
    P = fmpq_poly([1])
    for r in rs:
        P *= fmpq_poly([-r, 1])
    return rs, poly_coeffs([P[i] for i in range(P.degree() + 1)])


def test_pieces_a_root_free_test_decides_are_kept_and_the_search_goes_on():
    """``root_free`` (the envelope bound) decides whole pieces; the search must still cover the rest of
    the range: the pieces tile [0, 1], every root is found, and the envelope's pieces say so (the
    certificate's witness names them by that reason)."""
    rs, co = _five_roots()
    lo_free, hi_free = arb(fmpq(11, 20)), arb(fmpq(17, 20))      # no root in [0.55, 0.85]
    calls = []

    def root_free(a, b):
        calls.append((a, b))
        return lo_free <= a and b <= hi_free
    iso = _isolate(_g_series_function(None, co), arb(0), arb(1), coeffs=co, root_free=root_free)
    assert not iso.unknown and calls
    _tiles(iso.pieces, arb(0), arb(1))
    assert len(iso.roots) == 5
    by_envelope = [p for p in iso.pieces if p.reason == ENVELOPE_REASON]
    assert by_envelope and all(p.status is RootStatus.EMPTY and lo_free <= p.lo and p.hi <= hi_free
                               for p in by_envelope)


def test_a_close_pair_of_roots_is_decided_at_the_critical_point_within_the_depth_limit():
    """(x - 1/3)^2 - 1e-40: two roots 2e-20 apart. Bisection alone would need about 66 levels to
    separate them (the depth limit is 48); the critical-point split decides the piece holding both."""
    co = poly_coeffs([fmpq(1, 9) - fmpq(1, 10 ** 40), fmpq(-2, 3), 1])
    with working_precision(256):
        iso = _isolate(_g_series_function(None, co), arb(0), arb(1), coeffs=co)
        assert not iso.unknown
        _tiles(iso.pieces, arb(0), arb(1))
        _check_against_roots(iso.pieces, [arb(fmpq(1, 3) - fmpq(1, 10 ** 20)), arb(fmpq(1, 3) + fmpq(1, 10 ** 20))])


def test_a_resumed_search_keeps_the_decided_part_and_searches_only_the_rest():
    """A search stopped at a double root keeps (decided pieces, stop point); resumed (at a higher
    precision, by the prover) it must not examine the decided part again, and its pieces still tile."""
    P = fmpq_poly([-fmpq(1, 3), 1]) ** 2 * fmpq_poly([-fmpq(3, 4), 1]) * fmpq_poly([-fmpq(1, 10), 1])
    co = poly_coeffs([P[i] for i in range(P.degree() + 1)])
    f = _g_series_function(None, co)
    first = _isolate(f, arb(0), arb(1), coeffs=co, max_depth=12)
    assert first.unknown and first.resume is not None
    decided, stop = first.resume
    assert decided and all(p.hi < stop or p.hi == stop for p in decided)
    assert any(p.status is RootStatus.UNIQUE and p.enclosure.is_finite() and p.enclosure.overlaps(arb(fmpq(1, 10))) for p in decided)
    seen = []

    def counting(s):
        seen.append(s)
        return f(s)
    again = _isolate(counting, arb(0), arb(1), coeffs=co, max_depth=12, resume=first.resume)
    _tiles(again.pieces, arb(0), arb(1))
    assert seen
    for s in seen:          # nothing left of the stop point is evaluated again (a ball over [stop, b] has
        X = series_coefficients(s, 2)[0]         # its centre right of stop; its radius is rounded up)
        assert X.mid() >= stop, f"the resumed search evaluated g around {X.mid()}, left of its stop point {stop}"
    assert [p.lo for p in again.pieces[:len(decided)]] == [p.lo for p in decided]


# ----------------------------------------------------------------------------- classify_root on a known beta

class _PolyBeta:
    """A switching function beta(t) given as a polynomial: what classify_root needs of an ExpSum."""

    def __init__(self, coefficients):
        self.coeffs = poly_coeffs(coefficients)

    def __call__(self, t):
        return self.coeffs(arb(t), 1)[0]


def _product(*factors):
    P = fmpq_poly([1])
    for f in factors:
        P *= fmpq_poly([fmpq(c) if not isinstance(c, fmpq) else c for c in f])
    return [P[i] for i in range(P.degree() + 1)]


HALF = [fmpq(1, 2), -1]                          # 1/2 - t: the root of g at theta = 1/2
T = [0, 1]                                       # t: beta(0) = 0 (the switching)
BETAS = {
    # beta > 0 on (0, 1/2): a genuine orbit
    "positive": (_product(T, HALF, [1, 1]), "genuine"),
    # beta < 0 on (0.44, 0.46), just before theta, while beta' < 0 at theta: spurious, and only the
    # middle check sees it (the right end's beta' < 0 must be certified up to theta, not beyond it)
    "dip_before_theta": (_product(T, HALF, [fmpq(45 ** 2, 10 ** 4) - fmpq(1, 10 ** 4), fmpq(-9, 10), 1]), "spurious"),
    # beta'(0) < 0: the orbit starts into beta < 0; the witness must be a point of (0, theta)
    "starts_negative": (_product(T, HALF, [fmpq(-1, 4), 1]), "spurious"),
}


#: beta'(0) as x(0) gives it, when it is not the polynomial's own (the branches where the two
#: certificates of the left end disagree: a unit test of each branch's decision)
SLOPES = {
    # x(0) says beta'(0) > 0, but beta' > 0 cannot be certified on any [0, d]: undecided, never genuine
    "no_left_end": (_product(T, T, HALF), "undecided", arb(1)),
    # beta'(0) < 0 certified, beta > 0 at every tried point: still spurious (the orbit starts into
    # beta < 0), without a witness point
    "negative_slope_without_witness": (_product(T, HALF), "spurious", arb(-1)),
}


@pytest.mark.parametrize("name", list(BETAS) + list(SLOPES))
def test_a_root_is_classified_by_the_sign_of_beta_on_the_whole_of_0_theta(monkeypatch, name):
    from rigor_gyro.kinds.periodic_orbit import claims as relay_claims
    coefficients, verdict, slope = BETAS[name] + (None,) if name in BETAS else SLOPES[name]
    beta = _PolyBeta(coefficients)
    theta = arb("0.5 +/- 1e-25")
    bd0 = beta.coeffs(arb(0), 2)[1] if slope is None else slope
    monkeypatch.setattr(relay_claims, "x0_at", lambda sp, th: [arb(0), bd0, arb(0), arb(0), arb(0)])
    monkeypatch.setattr(relay_claims, "orbit_expsums", lambda sp, x0: [beta])
    v = relay_claims.classify_root(None, theta)
    assert v.kind == verdict, v.reason
    assert v.theta is theta and v.x0[1] is bd0 and v.reason
    if name == "negative_slope_without_witness":
        assert v.witness_t is None and "starts into beta < 0" in v.reason
        return
    if verdict == "undecided":
        assert "could not certify the sign of beta'" in v.reason
        return
    if verdict == "spurious":
        t = v.witness_t
        assert t is not None and arb(0) < t < theta and beta(t) < 0, (t, v.reason)
    else:          # the witness of "genuine", re-checked on the polynomial
        assert beta.coeffs(arb(0).union(v.d1), 2)[1] > 0
        assert beta.coeffs(v.right_start.union(theta.upper()), 2)[1] < 0
        pieces = sorted(v.middle, key=lambda p: float(p[0].mid()))
        assert pieces[0][0] == v.d1 and pieces[-1][1] == v.right_start
        assert all(beta.coeffs(a.union(b), 1)[0] > 0 for a, b in pieces)


@pytest.mark.parametrize("kind, theta", [("XXspuriousXX", arb(1)), (None, arb(1)), ("genuine", None)])
def test_a_malformed_root_verdict_is_refused(kind, theta):
    """A verdict of another kind would be counted neither classified nor undecided (and the half-period
    claim proved with a root nobody classified): refused where it is made."""
    with pytest.raises(AssertionError, match="malformed root verdict"):
        RootVerdict(theta, [], kind, "")


# --------------------------------------------------------------------------- _multipliers (mutmut survivors)

class _StubSpectrum:
    """A spectrum whose Jacobian and eigenvalue enclosures are given: _multipliers' bookkeeping (the
    Liouville checks, the order, the moduli, the margin) tested apart from the flow."""

    def __init__(self, eigenvalues, det_shift=0, enclosures=None):
        from rigor_gyro.kinds.periodic_orbit.flow import RelayParams
        self.P = RelayParams.from_strings(A="125", B="0.133", H="100", tau="0.01", sigma="0.13125", n="50",
                                          K="7.5", p="40", S="0.15")
        self.eigenvalues = eigenvalues              # J's (exact) eigenvalues
        self.enclosures = enclosures or eigenvalues  # what the eigenvalue method returns for them
        self.det_shift = det_shift

    @staticmethod
    def liouville(P, theta):
        from rigor_gyro.core.balls import ball
        return -((-(1 / ball(P.tau) + 1 / ball(P.sigma))) * theta).exp()

    def jacobian(self, theta, x0):
        """A real block-diagonal matrix with the stub's eigenvalues (a 2 x 2 rotation-scaling block per
        conjugate pair) and det shifted by det_shift."""
        from flint import arb_mat
        J = arb_mat(4, 4)
        i, seen = 0, set()
        for z in self.eigenvalues:
            key = (str(z.real.mid()), str(abs(z.imag).mid()))
            if z.imag.contains(0):
                J[i, i] = z.real
                i += 1
            elif key not in seen:
                seen.add(key)
                a, b = z.real, abs(z.imag)
                J[i, i], J[i, i + 1], J[i + 1, i], J[i + 1, i + 1] = a, -b, b, a
                i += 2
        J[3, 3] += self.det_shift
        return J

    def multipliers(self, J, theta):
        return list(self.enclosures)


def _stub_eigenvalues(theta, big, order):
    """A real multiplier ``big``, the pair 0.3 +- 0.4 i (modulus 0.5) and the fourth real one that makes
    the product the Liouville value, in the given order of indices."""
    from flint import acb
    P = _StubSpectrum([]).P
    last = _StubSpectrum.liouville(P, theta) / (big * arb("0.25"))
    zs = [acb(big), acb(arb("0.3"), arb("-0.4")), acb(arb("0.3"), arb("0.4")), acb(last)]
    return [zs[k] for k in order]


@pytest.mark.parametrize("order", [(0, 1, 2, 3), (0, 2, 1, 3), (1, 2, 0, 3), (3, 1, 2, 0), (1, 2, 3, 0)])
def test_multipliers_keep_every_eigenvalue_whatever_order_they_come_in(order):
    """The conjugate pair arrives with Im < 0 first; the reordering must swap the pair, never drop or
    duplicate another multiplier (mutmut: swapping with mults[k - 1] lost the largest, 1.5, and the orbit
    was called stable)."""
    theta = arb("0.1381")
    v = claims.RootVerdict(theta, [arb(0)] * 4, "genuine", "")
    sp = _StubSpectrum(_stub_eigenvalues(theta, arb("1.5"), order))
    claims._multipliers(sp, v)
    assert v.stable is False
    assert len(v.multipliers) == 4 and v.moduli[0].is_finite() and v.moduli[0].overlaps(arb("1.5"))
    mids = [float(m.mid()) for m in v.moduli]
    assert mids == sorted(mids, reverse=True)                       # by decreasing modulus
    assert all(w.is_finite() for w in v.multipliers)                # a NaN ball overlaps every z
    for z in sp.eigenvalues:
        assert sum(1 for w in v.multipliers if w.overlaps(z)) == 1
    pair = [w for w in v.multipliers if not w.imag.contains(0)]
    assert len(pair) == 2 and pair[0].imag > 0 > pair[1].imag      # the pair: Im > 0 first
    assert v.margin.is_finite() and v.margin.overlaps(arb("-0.5"))


@pytest.mark.parametrize("first", [0, 1])
def test_the_margin_is_one_minus_the_largest_modulus_of_all(first):
    """Two real multipliers whose moduli overlap: the margin must come from the larger upper end,
    whichever is listed first (mutmut: the maximum taken over moduli[2:] skipped the second)."""
    from flint import acb
    theta = arb("0.1381")
    P = _StubSpectrum([]).P
    a, b, c = arb("0.9", "0.01"), arb("-0.9", "0.05"), arb("0.2")       # |b| reaches 0.95
    last = _StubSpectrum.liouville(P, theta) / (a * b * c)
    pair = [acb(a), acb(b)] if first == 0 else [acb(b), acb(a)]
    v = claims.RootVerdict(theta, [arb(0)] * 4, "genuine", "")
    claims._multipliers(_StubSpectrum(pair + [acb(c), acb(last)]), v)
    assert v.margin.lower() <= 1 - arb("0.95")
    assert v.stable is True and v.margin > 0


def test_a_determinant_that_misses_liouville_is_a_bug_even_when_the_product_matches():
    theta = arb("0.1381")
    sp = _StubSpectrum(_stub_eigenvalues(theta, arb("0.9"), (0, 1, 2, 3)), det_shift=arb("0.001"))
    v = claims.RootVerdict(theta, [arb(0)] * 4, "genuine", "")
    with pytest.raises(AssertionError, match="Liouville"):
        claims._multipliers(sp, v)


def test_a_ball_straddling_the_real_axis_is_made_real_only_when_its_conjugate_meets_no_other_ball():
    """A pair 0.5 +- 0.001 i whose Im > 0 member's ball reaches below the axis: its conjugate ball meets
    the other member's, so it is not a real eigenvalue and must not be made real (mutmut: `not any` ->
    `any` snapped it to 0.5, whose modulus ball then missed |0.5 + 0.001 i| = 0.500001)."""
    from flint import acb
    theta = arb("0.1381")
    P = _StubSpectrum([]).P
    lam = acb(arb("0.5"), arb("0.001"))
    real = arb("0.9")
    last = _StubSpectrum.liouville(P, theta) / (real * abs(lam) ** 2)
    true = [acb(real), lam, lam.conjugate(), acb(last)]
    enclosures = [acb(real), acb(arb("0.5", "1e-9"), arb("0.0008", "0.0009")),
                  acb(arb("0.5", "1e-9"), arb("-0.00105", "0.0001")), acb(last)]
    v = claims.RootVerdict(theta, [arb(0)] * 4, "genuine", "")
    claims._multipliers(_StubSpectrum(true, enclosures=enclosures), v)
    assert all(w.is_finite() for w in v.multipliers)                # a NaN ball contains every z
    for z in true:
        assert sum(1 for w in v.multipliers if w.contains(z)) == 1, (z, v.multipliers)
    for z, m in zip(v.multipliers, v.moduli):
        assert m.is_finite() and m.overlaps(abs(z))


# --------------------------------------------------------------------------- analyse (mutmut survivors)

def _relay_model(**options):
    import dataclasses
    from rigor_gyro import load_scene
    from rigor_gyro.kinds import kind_module
    scene = load_scene("roitenberg1947")
    scene = dataclasses.replace(scene, options=dict(scene.options, **options))
    return kind_module("periodic_orbit").validate(scene)


def test_a_finite_search_range_reaches_t_max_and_claims_no_more():
    """T_max = 1/3 has no exact ball: the search must end at an exact point at or above it (mutmut: the
    ball's lower end left (that point, 1/3] unsearched while the claim said (0, T_max])."""
    with working_precision(128):
        an = claims.analyse(_relay_model(T_max="1/3"))
        assert an.T_search.rad() == 0 and an.T_search - arb(fmpq(1, 3)) >= 0    # exact, at or above 1/3
    assert an.covers_all is False and not an.problem
    assert any(v.kind == "genuine" and 0.1381 < float(v.theta.mid()) < 0.1382 for v in an.roots)


def test_a_t_max_beyond_the_tail_point_searches_all_of_the_half_line():
    with working_precision(128):
        an = claims.analyse(_relay_model(T_max="10"))
    assert an.covers_all is True and an.T_tail is not None and an.T_search is an.T_tail
    assert an.T_tail < 10


@pytest.mark.parametrize("moments", [[0, 0, 0, 1, 1], [0, 0, 0, 0, 0], [1, 0, 0, 0, 1]])
def test_a_failed_moment_identity_stops_the_analysis_as_a_bug(monkeypatch, moments):
    """e1^T M^j e = 0 for j <= 3 and != 0 for j = 4 hold for every parameter (exactly): a failure means
    the model is not the one the search assumes, and nothing may be searched or claimed."""
    monkeypatch.setattr(claims, "moment_zero_orders", lambda P: [fmpq(m) for m in moments])
    with working_precision(128):
        an = claims.analyse(_relay_model())
    assert an.problem and "moment identities" in an.problem and "a bug" in an.problem
    assert an.roots == [] and not an.covers_all


def test_a_search_range_shorter_than_the_default_start_is_still_searched_from_below():
    """T_max = 1/1000 is below four times the default start of the near-zero interval (2^-7 here): the
    start is halved until the range holds it (mutmut: that loop was never entered by the tests)."""
    with working_precision(128):
        an = claims.analyse(_relay_model(T_max="1/1000"))
        assert an.theta_min is not None and 4 * an.theta_min <= an.T_search
        assert an.T_search - arb(fmpq(1, 1000)) >= 0
    assert not an.problem and an.covers_all is False
    assert [v for v in an.roots if v.kind == "genuine"] == []       # theta* = 0.138 is beyond the range


def _box_spectrum_factory(model, name, lo, hi):
    """A BoxSpectrum over ``name`` in [lo, hi] (the other parameters as in the model), and the box's
    midpoint model, as boxes.evaluate_box builds them."""
    import dataclasses
    from rigor_gyro.core.balls import interval
    from rigor_gyro.kinds.periodic_orbit.boxes import BoxSpectrum
    from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, RelayParams
    P = model.params
    lo, hi = (fmpq(x.numerator, x.denominator) for x in (lo, hi))
    Pb = RelayParams(**{k: interval(lo, hi) if k == name else arb(getattr(P, k)) for k in PARAMETER_NAMES})
    Pmid = dataclasses.replace(P, **{name: (lo + hi) / 2})
    return (lambda: BoxSpectrum(Pb, Pmid)), dataclasses.replace(model, params=Pmid, paper={})


def test_a_box_analysis_neither_reads_nor_writes_the_point_cache():
    """The memo of decided root pieces (model.decided) is keyed by the search range, not by the
    parameters: a box must never take a point's pieces, nor leave its own for a point. And every
    enclosure of a box analysis is over the box."""
    import dataclasses

    class Forbidden(dict):
        def get(self, *a):
            raise AssertionError("a box analysis read the point cache")

        def __setitem__(self, *a):
            raise AssertionError("a box analysis wrote the point cache")

    base = _relay_model(T_max="1/3")
    from fractions import Fraction
    factory, boxed = _box_spectrum_factory(base, "n", Fraction("49.99"), Fraction("50.01"))
    boxed = dataclasses.replace(boxed, decided=Forbidden())
    with working_precision(128):
        an = claims.analyse(boxed, spectrum=factory)
        assert not an.problem and an.roots
        # the genuine orbit's theta*, x(0) and multipliers at the guard precision come from a spectrum
        # of the whole box too, never the midpoint's (mutmut: `fine = Spectrum(P)` proved a box stable
        # from its midpoint alone)
        from rigor_gyro.kinds.periodic_orbit.boxes import BoxSpectrum
        assert isinstance(an.sp_fine, BoxSpectrum)
        genuine = [v for v in an.roots if v.kind == "genuine"]
        assert genuine and all(len(v.moduli) == 4 for v in genuine)
        point = claims.analyse(base)
    assert len(base.decided) == 1 and not point.problem          # a point analysis does keep its pieces


# --------------------------------------------------------------------------- attempt (mutmut survivors)

def _crafted_attempt(monkeypatch, roots, covers_all=True, problem="", unknown=(), keep=None):
    """attempt() on an analysis given here (its root verdicts and undecided pieces; exact dyadic points,
    as the certificate's witnesses need)."""
    def fake(model, spectrum=None, phase=None):
        return claims.Analysis(sp=object(), theta_min=arb("0.0078125"), T_tail=arb("0.625"), T_search=arb("0.625"),
                               covers_all=covers_all, pieces=len(roots), roots=roots, problem=problem,
                               unknown=list(unknown))
    monkeypatch.setattr(claims, "analyse", fake)
    with working_precision(64):
        a = claims.attempt(_relay_model(), ["half_period", "orbit_genuine", "initial_point", "multipliers", "stable"], 64)
    if keep is not None:
        keep.append(a)
    expected_roots = [{"theta": claims._bounds(v.theta), "spurious_because": v.reason,
                       "witness_t": claims._bounds(v.witness_t) if v.witness_t is not None else None}
                      for v in roots if v.kind == "spurious"]
    for c in a.claims:          # a refutation carries its certificate: the search of all of (0, oo)
        if c.status.value == "refuted":
            assert c.counterexample == {"searched": "(0, oo)", "tail_point": ["0.625", "0.625"],
                                        "theta_min": ["0.0078125", "0.0078125"], "roots": expected_roots}, c.id
        if problem:
            assert problem in c.reason
    if not problem:         # no genuine orbit: no enclosure width was asked for, none to escalate for
        assert a.widths_met is True
    hp = next((c for c in a.claims if c.id == "half_period"), None)
    if hp is not None and not problem and not unknown:      # the search's size, reported with the claim
        assert hp.details == {"pieces": len(roots), "roots": len(roots)}
    return {c.id: c.status.value for c in a.claims}


def test_a_root_left_unclassified_forbids_refuting_the_orbit(monkeypatch):
    """All of (0, oo) searched, no undecided piece, one root spurious and one not classified: that root
    may be the orbit, so neither orbit_genuine nor stable is refuted (mutmut: `complete` as 'no unknown
    piece OR no undecided root', or with the undecided list dropped, refuted the orbit's existence)."""
    roots = [RootVerdict(arb("0.0625"), [arb(0)] * 5, "spurious", "beta < 0 at t = 1/32", witness_t=arb("0.03125")),
             RootVerdict(arb("0.125"), [arb(0)] * 5, "undecided", "beta'(0) of no certain sign")]
    status = _crafted_attempt(monkeypatch, roots)
    assert status == {"half_period": "inconclusive", "orbit_genuine": "inconclusive",
                      "initial_point": "inconclusive", "multipliers": "inconclusive", "stable": "inconclusive"}


def test_every_root_spurious_over_all_of_the_half_line_refutes_the_orbit(monkeypatch):
    roots = [RootVerdict(arb("0.0625"), [arb(0)] * 5, "spurious", "beta < 0 at t = 1/32", witness_t=arb("0.03125"))]
    status = _crafted_attempt(monkeypatch, roots)
    assert status == {"half_period": "proved", "orbit_genuine": "refuted", "initial_point": "refuted",
                      "multipliers": "refuted", "stable": "refuted"}
    # a spurious root decided without a grid point (beta'(0) < 0) stores no witness point
    two = roots + [RootVerdict(arb("0.25"), [arb(0)] * 5, "spurious", "beta'(0) < 0")]
    assert _crafted_attempt(monkeypatch, two)["orbit_genuine"] == "refuted"
    assert _crafted_attempt(monkeypatch, roots, covers_all=False)["orbit_genuine"] == "inconclusive"


def test_an_analysis_with_a_problem_decides_nothing(monkeypatch):
    """A problem (a failed bug check, a tail bound not certified) makes every claim inconclusive even
    when the spectrum exists (mutmut: `sp is None and problem` went on to decide the claims)."""
    roots = [RootVerdict(arb("0.0625"), [arb(0)] * 5, "spurious", "beta < 0 at t = 1/32", witness_t=arb("0.03125"))]
    status = _crafted_attempt(monkeypatch, roots, problem="moment identities fail: a bug")
    assert set(status.values()) == {"inconclusive"}


def test_the_width_asked_of_theta_star_is_its_diameter():
    """Option theta_width bounds the diameter 2 rad of theta*'s ball: met with a width 2.5 times the
    radius obtained, not met with 1.5 times it (mutmut: 3 rad for 2 rad)."""
    from fractions import Fraction
    from rigor_gyro.core.balls import exact_fraction
    with working_precision(64):
        a = claims.attempt(_relay_model(), ["orbit_genuine"], 64)
        r = exact_fraction(arb(a.quantities["theta_star"].rad()))
        for factor, met in ((Fraction(5, 2), True), (Fraction(3, 2), False)):
            w = r * factor
            text = f"{w.numerator}/{w.denominator}"
            assert claims.attempt(_relay_model(theta_width=text), ["orbit_genuine"], 64).widths_met is met, factor


def test_every_genuine_orbit_unstable_refutes_stable_only_over_all_of_the_half_line(monkeypatch):
    """relay_unstable (H = 1e4): every genuine orbit has a modulus certainly > 1 and (0, oo) is searched,
    so stable is refuted, with the search and each orbit's modulus above 1 as its counterexample. The
    same analysis restricted to (0, T] (as option T_max would) refutes nothing: a stable orbit could lie
    beyond T (mutmut: the refutation made unconditional); every claim then left inconclusive says more
    precision cannot help, and no decided claim says so."""
    import dataclasses
    from pathlib import Path
    from rigor_gyro import load_scene
    from fractions import Fraction
    from rigor_gyro.certificate import Status
    from rigor_gyro.core.balls import certainly_gt
    model = claims.validate(load_scene(str(Path(__file__).parent / "corpus" / "relay_unstable.toml")))
    wanted = ["half_period", "orbit_genuine", "multipliers", "stable"]
    with working_precision(64):
        an = claims.analyse(model)
        assert an.covers_all and not an.unknown
        genuine = [v for v in an.roots if v.kind == "genuine"]
        assert genuine and all(v.stable is False for v in genuine)
        full = {c.id: c for c in claims.attempt(model, wanted, 64).claims}
        restricted_an = dataclasses.replace(an, covers_all=False)
        monkeypatch.setattr(claims, "analyse", lambda m, spectrum=None, phase=None: restricted_an)
        restricted = {c.id: c for c in claims.attempt(model, wanted, 64).claims}
    st = full["stable"]
    assert st.status is Status.REFUTED and st.precision_cannot_help is None
    cx = st.counterexample
    assert cx["searched"] == "(0, oo)" and cx["tail_point"] == claims._bounds(an.T_tail)
    assert [o["theta"] for o in cx["orbits"]] == [claims._bounds(v.theta) for v in genuine]
    assert all(Fraction(o["modulus_above_1"][0]) > 1 for o in cx["orbits"])
    assert all(certainly_gt(max(v.moduli, key=lambda m: m.upper()), 1) for v in genuine)
    assert restricted["stable"].status is Status.INCONCLUSIVE and "not searched" in restricted["stable"].reason
    for c in restricted.values():
        assert (c.precision_cannot_help is not None) == (c.status is Status.INCONCLUSIVE), c.id
    assert {c.id for c in restricted.values() if c.status is Status.INCONCLUSIVE} == {"stable"}
    assert all(c.precision_cannot_help is None for c in full.values())


def test_a_claim_more_precision_can_decide_is_not_marked_hopeless():
    """relay_multiplier_near_one: all of (0, oo) searched and every root classified, stability undecided
    at 64 bits (a modulus 1e-30 from 1): more precision can decide it, so the claim must not say that
    precision cannot help (mutmut: the T_max condition as 'complete OR restricted')."""
    from pathlib import Path
    from rigor_gyro import load_scene
    from rigor_gyro.certificate import Status
    model = claims.validate(load_scene(str(Path(__file__).parent / "corpus" / "relay_multiplier_near_one.toml")))
    with working_precision(64):
        out = {c.id: c for c in claims.attempt(model, ["half_period", "orbit_genuine", "stable"], 64).claims}
    assert out["stable"].status is Status.INCONCLUSIVE and out["stable"].precision_cannot_help is None


def test_an_undecided_piece_leaves_every_claim_open_and_is_what_would_decide_them(monkeypatch):
    """One piece of the range undecided by a piece budget: every claim inconclusive, its reason names
    the piece, and each claim's `decides` (what the prover watches for progress between precisions) is
    that piece (mutmut: the second undecided piece read, `decides` dropped or set on decided claims)."""
    from rigor_gyro.core.roots import RootPiece, RootStatus
    from rigor_gyro.core.balls import interval
    roots = [RootVerdict(arb("0.0625"), [arb(0)] * 5, "spurious", "beta < 0 at t = 1/32", witness_t=arb("0.03125"))]
    piece = RootPiece(arb("0.25"), arb("0.375"), RootStatus.UNKNOWN, reason="piece budget exhausted")
    kept = []
    status = _crafted_attempt(monkeypatch, roots, unknown=[piece], keep=kept)
    assert set(status.values()) == {"inconclusive"}
    want = interval(arb("0.25"), arb("0.375"))
    for c in kept[0].claims:
        assert "piece budget exhausted" in c.reason or c.id != "half_period"
        assert c.decides is not None and c.decides.lower() == want.lower() and c.decides.upper() == want.upper(), c.id
