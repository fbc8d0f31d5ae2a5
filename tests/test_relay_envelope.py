"""The envelope bound of the relay root search (issue 12, fast nutation): G = a + b cos phi + c sin phi
with slowly varying a, b, c, so sign(s) G >= M over every phase. Tested against the definition of G at
high precision, on wide pieces, and in the checker (a root hidden in an "envelope" piece is caught)."""
import copy
import json

from flint import acb, arb
from hypothesis import given, settings
from hypothesis import strategies as st

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.certificate import digest
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import certainly_positive, interval, working_precision
from rigor_gyro.kinds.periodic_orbit.claims import validate
from rigor_gyro.kinds.periodic_orbit.g_roots import envelope_test
from rigor_gyro.kinds.periodic_orbit.flow import Spectrum, envelope_margin, pole_free_coeffs

SCENES = ("stress_relay_H_1e4", "roitenberg1947")


def _spectrum(name):
    return Spectrum(validate(load_scene(name)).params)


def _naive_margin(sp, t):
    """sign(s) a - hypot(b, c) from the definitions (cancels: only at a high precision)."""
    pair = next(m for m in sp.modes if m.weight == 2)
    q = pair.pe[0] / pair.lam
    s = -sp.p0e[0] * t / 2
    for m in sp.modes:
        if m is not pair:
            s -= (m.pe[0] * (m.lam * acb(t) / 2).tanh() / m.lam).real
    rho = (pair.lam.real * t).exp()
    a, b, c = s * (1 + rho * rho) + 2 * q.real * (1 - rho * rho), 2 * s * rho, 4 * q.imag * rho
    sigma = 1 if certainly_positive(s) else -1
    return sigma, sigma * a - (b * b + c * c).sqrt(), a, b, c, pair.lam.imag * t


@settings(max_examples=60)
@given(st.sampled_from(SCENES), st.integers(1, 7000))
def test_the_margin_is_the_minimum_over_the_phase(name, k):
    with working_precision(64):
        sp = _spectrum(name)
        t = arb(k) / 10000
        r = envelope_margin(sp, t)
    if r is None:
        return
    sigma, M = r
    with working_precision(512):
        sp = _spectrum(name)
        t = arb(k) / 10000
        sig, naive, a, b, c, phi = _naive_margin(sp, t)
        assert sig == sigma
        assert M.is_finite() and M.overlaps(naive)          # the same number, written without cancellation
        G = pole_free_coeffs(sp, t, 1)[0]
        assert G.is_finite() and (a + b * phi.cos() + c * phi.sin()).overlaps(G)  # the decomposition of G is exact
        assert certainly_positive(sigma * G - naive + abs(naive) * arb(2) ** -400 + arb(2) ** -1000)


def test_wide_pieces_of_the_fast_nutation_are_decided_at_once():
    with working_precision(64):
        sp = _spectrum("stress_relay_H_1e4")
        test = envelope_test(sp)
        pair = next(m for m in sp.modes if m.weight == 2)
        period = 2 * arb.pi() / pair.lam.imag
        assert test(arb("0.3"), arb("0.7"))                 # about 150 nutation periods in one piece
        assert certainly_positive(arb("0.4") / period - 100)
        assert not test(arb("0.01"), arb("0.1"))            # where the roots are: never decided


def test_no_envelope_for_a_spectrum_it_does_not_fit():
    with working_precision(64):
        sp = _spectrum("roitenberg1947")
        assert envelope_margin(sp, interval(arb(-1), arb(1))) is None      # theta must be > 0
        sp.near_zero = object()                                             # a box spectrum near 0
        assert envelope_margin(sp, arb("0.5")) is None and envelope_test(sp) is None


def test_the_checker_rejects_a_root_hidden_in_an_envelope_piece():
    data = json.loads(json.dumps(prove_scene(load_scene("stress_relay_H_1e3")).to_json()))
    pcs = data["witnesses"]["half_period"]["pieces"]
    assert any(p.get("by") == "envelope" for p in pcs)
    assert check_certificate(data).ok
    bad = copy.deepcopy(data)
    i = next(j for j, p in enumerate(bad["witnesses"]["half_period"]["pieces"]) if p["kind"] == "unique")
    piece = bad["witnesses"]["half_period"]["pieces"][i]
    piece.clear()
    piece.update({"lo": data["witnesses"]["half_period"]["pieces"][i]["lo"],
                  "hi": data["witnesses"]["half_period"]["pieces"][i]["hi"], "kind": "empty", "by": "envelope"})
    bad["integrity"] = {"sha256": digest(bad)}
    report = check_certificate(bad)
    assert not report.ok and report.first_failure.item == "half_period"


def test_the_checker_re_derives_each_envelope_piece():
    """A root-free piece relabelled "by": "envelope" where the envelope bound does not hold (in the
    stretch where the roots are) is rejected, though it holds no root: the checker re-derives the
    bound the certificate names, not any bound."""
    data = json.loads(json.dumps(prove_scene(load_scene("stress_relay_H_1e3")).to_json()))
    bad = copy.deepcopy(data)
    pcs = bad["witnesses"]["half_period"]["pieces"]
    i = next(j for j, p in enumerate(pcs) if p["kind"] == "empty" and "by" not in p)
    pcs[i]["by"] = "envelope"
    bad["integrity"] = {"sha256": digest(bad)}
    report = check_certificate(bad)
    assert not report.ok and report.first_failure.item == "half_period"


def test_no_envelope_where_one_minus_rho_is_not_certainly_positive():
    """expm1 over a wide piece reaching down near 0 may dip below 0: no bound is given there (the
    products of positive balls by their ends would then be wrong)."""
    with working_precision(64):
        sp = _spectrum("stress_relay_H_1e4")
        X = interval(arb("1e-7"), arb(1))
        pair = next(m for m in sp.modes if m.weight == 2)
        assert not certainly_positive(-(pair.lam.real * X).expm1())   # arb's expm1 dips below 0 here
        assert envelope_margin(sp, X) is None
        # the same piece with a slow part of one certain sign (a linear term made large): still no bound
        import copy
        sp2 = copy.copy(sp)
        sp2.p0e = [arb(-1000000)] + list(sp.p0e[1:])
        assert envelope_margin(sp2, X) is None
        assert envelope_margin(sp2, interval(arb("0.1"), arb(1))) is not None   # where 1 - rho > 0: a bound
        from rigor_gyro.kinds.periodic_orbit.check import _envelope_lower
        assert _envelope_lower(sp2, arb("1e-7"), arb(1)) is None                 # nor the checker's
        assert _envelope_lower(sp2, arb("0.1"), arb(1)) is not None


def test_the_checkers_envelope_refuses_what_it_cannot_bound():
    """The checker's own envelope bound says "root-free" only where its premises hold: exactly one
    complex pair with Re lambda < 0, 0 < lo < hi, a slow part of one certain sign, and a margin
    certainly > 0. Each premise is broken on a piece that the bound would otherwise be asked about."""
    import dataclasses

    from rigor_gyro.kinds.periodic_orbit.check import _envelope_root_free
    with working_precision(128):
        sp = _spectrum("stress_relay_H_1e4")
        assert _envelope_root_free(sp, arb("0.3"), arb("0.7"))             # a genuine wide piece
        assert not _envelope_root_free(sp, arb("0.7"), arb("0.3"))         # lo > hi
        assert not _envelope_root_free(sp, arb("-0.1"), arb("0.7"))        # lo <= 0
        assert not _envelope_root_free(sp, arb("0.2"), arb("0.3"))         # s changes sign on the piece
        assert not _envelope_root_free(sp, arb("0.01"), arb("0.1"))        # the roots are there: M <= 0
        base = load_scene("roitenberg1947")
        slow_rotor = dataclasses.replace(base, parameters=dict(base.parameters, H="0.1"))
        sp0 = Spectrum(validate(slow_rotor).params)                        # four real modes, no pair
        assert all(m.weight == 1 for m in sp0.modes)
        assert not _envelope_root_free(sp0, arb("0.3"), arb("0.7"))
        import copy
        sp_up = copy.copy(sp)                                              # the pair made unstable
        sp_up.modes = [dataclasses.replace(m, lam=acb(-m.lam.real, m.lam.imag)) if m.weight == 2 else m
                       for m in sp.modes]
        assert not _envelope_root_free(sp_up, arb("0.3"), arb("0.7"))
        sp_box = copy.copy(sp)
        sp_box.near_zero = object()
        assert not _envelope_root_free(sp_box, arb("0.3"), arb("0.7"))


@settings(max_examples=40)
@given(st.sampled_from(SCENES), st.integers(1, 7000))
def test_the_checkers_bound_is_the_margin(name, k):
    """The checker's own formula gives the same number as the definition: on a piece of width 2^-200
    its bound is sign(s) a - hypot(b, c) computed naively at 512 bits, to ~45 digits (a mutated term is not)."""
    from rigor_gyro.kinds.periodic_orbit.check import _envelope_lower
    with working_precision(256):
        sp = _spectrum(name)
        t = arb(k) / 10000
        low = _envelope_lower(sp, t, t + arb(2) ** -200)
    if low is None:
        return
    with working_precision(512):
        sp = _spectrum(name)
        sig, naive, *_ = _naive_margin(sp, arb(k) / 10000)
        # a lower bound (its first term is taken at its lower end), and the same number to ~45 digits
        assert low.lower() <= naive.upper(), (name, k)
        assert abs(low - naive).upper() < abs(naive).upper() * arb(2) ** -150 + arb(2) ** -190, (name, k)


def test_the_prover_gives_no_envelope_without_its_premises():
    import copy
    import dataclasses
    with working_precision(64):
        base = load_scene("roitenberg1947")
        sp0 = Spectrum(validate(dataclasses.replace(base, parameters=dict(base.parameters, H="0.1"))).params)
        assert envelope_margin(sp0, interval(arb("0.3"), arb("0.7"))) is None      # no complex pair
        sp = _spectrum("stress_relay_H_1e4")
        assert envelope_margin(sp, interval(arb("0.3"), arb("0.7"))) is not None
        sp_up = copy.copy(sp)
        sp_up.modes = [dataclasses.replace(m, lam=acb(-m.lam.real, m.lam.imag)) if m.weight == 2 else m
                       for m in sp.modes]
        assert envelope_margin(sp_up, interval(arb("0.3"), arb("0.7"))) is None    # Re lambda > 0


def test_a_product_of_positive_balls_from_their_ends():
    from rigor_gyro.kinds.periodic_orbit.flow import _positive_product
    p = _positive_product(interval(arb(1), arb(2)), interval(arb(3), arb(4)))
    assert p.is_finite() and p.contains(3) and p.contains(8) and p.lower() >= 3 - arb("1e-7") and p.upper() <= 8 + arb("1e-7")
    w = interval(arb("0.001"), arb(1))
    assert _positive_product(w, w).lower() > 0                     # midpoint-radius w * w would reach < 0


def test_a_product_of_positive_balls_contains_the_exact_product_to_the_last_bit():
    """(1 + 2^-40)^2 needs 81 bits: at 53 the product's lower end must be rounded down and its upper
    end up (mutmut: either end rounded the other way excludes the exact product by one ulp)."""
    from fractions import Fraction
    from rigor_gyro.core.balls import exact_endpoints
    from rigor_gyro.kinds.periodic_orbit.flow import _positive_product
    with working_precision(53):
        x = arb(1) + arb(2) ** -40
        for factors in ((x, x), (x, x, x), (arb(3) / 7, x)):
            lo_exact, hi_exact = Fraction(1), Fraction(1)      # the products of the factors' exact ends
            for f in factors:
                a, b = exact_endpoints(f)
                lo_exact, hi_exact = lo_exact * a, hi_exact * b
            lo_p, hi_p = exact_endpoints(_positive_product(*factors))
            assert lo_p <= lo_exact and hi_exact <= hi_p


def test_the_infinity_norm_bounds_every_row_sum_and_is_not_looser_than_rounding():
    """|W|_inf for a ball matrix: at least every row's sum of |entries| (upper ends), and within
    rounding of the largest exact one."""
    from fractions import Fraction
    from flint import arb_mat
    from rigor_gyro.core.balls import exact_endpoints
    from rigor_gyro.kinds.periodic_orbit.flow import _inf_norm
    with working_precision(64):
        W = arb_mat([[arb(1) / 3, arb(-2) / 3, arb(1) / 7], [arb("0.5", "0.5"), arb(1) / 5, arb(-1) / 9],
                     [arb("0.01"), arb(0), arb("-0.02")]])
        for scale in (1, arb(1) / 10):          # the largest row sum (the ball row) above and below 1
            A = W * scale
            n = _inf_norm(A)
            sums = [sum(max(abs(v) for v in exact_endpoints(A[i, j])) for j in range(3)) for i in range(3)]
            assert exact_endpoints(n)[0] >= max(sums) and exact_endpoints(n)[1] <= max(sums) * (1 + Fraction(1, 2 ** 50))


def test_the_tail_bound_lies_below_g_beyond_its_point():
    """tail_bound(T) is a lower bound of g on [T, oo): checked at 400 points of [T, 3 T] for a ladder of
    T on the built-in relay scenes and a slow-mode one (tau = 2, sigma = 3: |lambda| < 1, where an
    amplitude |p e / lambda| taken as |p e lambda| would be too small)."""
    from rigor_gyro.kinds.periodic_orbit.flow import g_coeffs, tail_bound
    import dataclasses
    scenes = [load_scene(n) for n in ("roitenberg1947", "stress_relay_H_1e4")]
    slow = load_scene("roitenberg1947")
    scenes.append(dataclasses.replace(slow, parameters=dict(slow.parameters, tau="2", sigma="3")))
    with working_precision(64):
        for scene in scenes:
            sp = Spectrum(validate(scene).params)
            for T in (arb(1) / 8, arb(1) / 2, arb(2), arb(8), arb(32)):
                lower = tail_bound(sp, T).lower()
                for k in range(400):
                    t = T * (1 + arb(k) / 200)
                    g = g_coeffs(sp, t, 1)[0]
                    assert lower <= g.upper(), (scene.name, T, t)
    # and it is tight where the nutation has died out (printed scene, T = 8: min g on [8, 24] is
    # 1.73605, the bound 1.73316): a looser one only moves the tail point out, but is a regression
    sp = Spectrum(validate(scenes[0]).params)
    with working_precision(64):
        gmin = min((g_coeffs(sp, arb(8) * (1 + arb(k) / 200), 1)[0] for k in range(400)), key=lambda b: b.mid())
        assert (gmin - tail_bound(sp, arb(8))).upper() < arb("0.01")


def test_the_fifth_taylor_coefficient_bound_contains_its_value_at_every_point_of_the_piece():
    """taylor5_leading_coefficient(X) encloses g^(5)(xi)/5! for every xi in X (what makes (0, theta_min]
    root-free), checked at 41 points of X = [0, t] for t up to the start of the search, and for a point
    X; never wider than the direct enclosure it is intersected with."""
    from rigor_gyro.kinds.periodic_orbit.flow import g_coeffs, taylor5_leading_coefficient
    with working_precision(64):
        for name in SCENES:
            sp = _spectrum(name)
            for t in (arb(1) / 1024, arb(1) / 256, arb(1) / 64):
                X = interval(arb(0), t)
                enc = taylor5_leading_coefficient(sp, X)
                if not enc.is_finite():         # too wide a piece (the fast nutation): it decides nothing
                    assert t > arb(1) / 1024, name
                    continue
                assert enc.rad() <= g_coeffs(sp, X, 6)[5].rad() * (1 + arb("1e-6"))
                for k in range(41):
                    x = t * k / 40
                    assert enc.overlaps(g_coeffs(sp, x, 6)[5]), (name, t, k)
                point = taylor5_leading_coefficient(sp, t)
                assert point.is_finite() and point.overlaps(g_coeffs(sp, t, 6)[5]) and point.rad() < arb("1e-10") * abs(point).upper()


def test_g_coefficients_do_not_depend_on_how_many_are_asked():
    """g_coeffs(c, n)[j] encloses the same g^(j)(c)/j! whatever n > j (mutmut: the linear term's
    derivative dropped for n = 2, the order Newton asks for), and c_1 is g's slope (a central
    difference agrees to 1e-6)."""
    from rigor_gyro.kinds.periodic_orbit.flow import g_coeffs
    with working_precision(128):
        for name in SCENES:
            sp = _spectrum(name)
            for x in (arb("0.05"), arb("0.3"), arb("1.7")):
                ref = g_coeffs(sp, x, 8)
                for n in range(1, 8):
                    got = g_coeffs(sp, x, n)
                    assert len(got) == n and all(got[j].is_finite() and ref[j].is_finite() and got[j].overlaps(ref[j])
                                                 for j in range(n)), (name, x, n)
                h = arb("1e-12")
                slope = (g_coeffs(sp, x + h, 1)[0] - g_coeffs(sp, x - h, 1)[0]) / (2 * h)
                assert abs(slope - ref[1]) < arb("1e-6") * (1 + abs(ref[1]))


def test_taylor_enclosure_of_a_known_function_and_its_derivatives():
    """f = exp through taylor_enclosure: f, f', f'' over a ball contain exp at its ends and are not
    wider than the direct enclosure; at a point they are exp itself (mutmut: j! divided instead of
    multiplied at a point, the intersection with the direct enclosure dropped)."""
    from math import factorial
    from rigor_gyro.kinds.periodic_orbit.flow import taylor_enclosure

    def coeffs(c, n):                       # exp^(j)(c)/j! for every c in the ball c
        return [c.exp() / factorial(j) for j in range(n)]
    with working_precision(64):
        X = interval(arb("0.5"), arb("0.75"))
        out = taylor_enclosure(coeffs, X, 8, (0, 1, 2))
        for k, e in enumerate(out):
            assert e.is_finite() and e.contains(arb("0.5").exp()) and e.contains(arb("0.75").exp()), k
            assert e.rad() <= (X.exp()).rad() * (1 + arb("1e-6")), k
        point = taylor_enclosure(coeffs, arb("0.5"), 8, (0, 1, 2))
        assert all(p.is_finite() and p.overlaps(arb("0.5").exp()) and p.rad() < arb("1e-15") for p in point)


def test_taylor_enclosure_falls_back_to_whichever_enclosure_is_finite():
    """Where the Taylor form is not finite (the point coefficients NaN) the direct enclosure is
    returned; where the direct one is not finite, the Taylor form (NaN included: it decides nothing),
    never a missing value."""
    from math import factorial
    from rigor_gyro.kinds.periodic_orbit.flow import taylor_enclosure
    nan = arb("nan")
    with working_precision(64):
        X = interval(arb("0.5"), arb("0.75"))
        no_point = lambda c, n: [nan] * n if c.rad() == 0 else [c.exp() / factorial(j) for j in range(n)]
        got = taylor_enclosure(no_point, X, 8, (0, 1))
        assert all(g.is_finite() and g.contains(arb("0.5").exp()) for g in got)
        nowhere = lambda c, n: [nan] * n
        got = taylor_enclosure(nowhere, X, 8, (0, 1))
        assert len(got) == 2 and all(isinstance(g, arb) and not g.is_finite() for g in got)
