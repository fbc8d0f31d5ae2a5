"""Each Lyapunov claim proved on its own (``[claims] only``) on planted variants of the paper's scene,
and its certificate confirmed by the independent checker: the outcome each variant must get, the
quantities against mpmath (50 digits), and every status the checker re-derives.

One claim at a time costs 0.1-0.3 s, so this file is the quick net under the claims' decision code
(``kinds/lyapunov/claims.py``, ``sublevel.py``): mutation runs use it, and each test builds what it
checks afresh (no cached proof)."""
from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

import rigor_gyro.kinds.lyapunov.claims as C
import rigor_gyro.kinds.lyapunov.direct_claims as DC
import rigor_gyro.kinds.lyapunov.mu_claims as MC
from rigor_gyro import load_scene
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import certainly_lt, working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.stored import as_ball, interval
from rigor_gyro.kinds.lyapunov.approx import MpGimbal
from rigor_gyro.kinds.lyapunov.equilibria import Equilibria, Equilibrium

from tests.forgery import certificate
from tests.test_lyapunov import CSTAR_CASE
from tests.test_properties_lyapunov import contains_ref, mp_values

#: planted variants of the paper's scene (parameters changed, scene options) and, per claim, the outcome
#: each must get; a claim not listed must not be proved-and-wrong (the checker decides that)
VARIANTS = {
    "paper": ({}, {}),
    "faces below 1 (x2* = 1/10)": ({"x2_star": "1/10"}, {}),
    "Vdot binds (x2* = 1.3)": ({"x2_star": "1.3"}, {}),
    "origin refutes c_max (k = 0.2)": ({"k": "0.2"}, {}),
    "faces refute c_max (H = 3000)": ({"H": "3000"}, {}),
    "radius far too large (R = 0.5)": ({}, {"R": "0.5"}),
    "mu below (16) (mu = 0.01)": ({"mu": "0.01"}, {}),
    "linear law": ({"moment": "linear"}, {}),
    "budget of 100 boxes": ({}, {"max_pieces": "100"}),
    "radii above 1 (k = 40, mu = 1.5)": ({"k": "40", "mu": "1.5"}, {}),
    "(16) empty (k = 0.1)": ({"k": "0.1"}, {}),
    "budget of 4 pieces": ({}, {"max_pieces": "4"}),
}

EXPECTED = {
    ("paper", "v_positive"): "proved", ("paper", "vdot_nonpositive"): "proved",
    ("paper", "invariant_estimate"): "proved", ("paper", "largest_sublevel"): "proved",
    ("paper", "equilibria"): "proved", ("paper", "vdot_direct"): "proved", ("paper", "best_mu"): "proved",
    ("paper", "best_mu_direct"): "proved",
    ("faces below 1 (x2* = 1/10)", "largest_sublevel"): "proved",
    ("faces below 1 (x2* = 1/10)", "invariant_estimate"): "proved",
    ("Vdot binds (x2* = 1.3)", "largest_sublevel"): "proved",
    ("origin refutes c_max (k = 0.2)", "largest_sublevel"): "refuted",
    ("faces refute c_max (H = 3000)", "largest_sublevel"): "refuted",
    ("radius far too large (R = 0.5)", "vdot_nonpositive"): "refuted",
    ("origin refutes c_max (k = 0.2)", "vdot_direct"): "inconclusive",
    ("mu below (16) (mu = 0.01)", "vdot_direct"): "inconclusive",
    ("radius far too large (R = 0.5)", "invariant_estimate"): "inconclusive",
    ("mu below (16) (mu = 0.01)", "v_positive"): "refuted",
    ("mu below (16) (mu = 0.01)", "best_mu"): "proved",
    ("budget of 100 boxes", "largest_sublevel"): "inconclusive",     # best bound about -9.3: undecided, not refuted
    ("radii above 1 (k = 40, mu = 1.5)", "best_mu"): "proved",          # R_sup about 3: rho < 1 everywhere
    ("radii above 1 (k = 40, mu = 1.5)", "best_mu_direct"): "proved",
    ("(16) empty (k = 0.1)", "best_mu"): "refuted", ("(16) empty (k = 0.1)", "best_mu_direct"): "refuted",
    ("paper", "constants"): "proved", ("paper", "damping_condition"): "proved",
    ("budget of 4 pieces", "constants"): "inconclusive",      # m and M not to the requested width on 4 pieces
    ("budget of 4 pieces", "damping_condition"): "proved",    # decided on the wider m, M all the same
    ("(16) empty (k = 0.1)", "damping_condition"): "refuted",
    ("linear law", "invariant_estimate"): "proved", ("linear law", "v_positive"): "proved",
}

#: the claims a proof of CLAIM also asks for (the equilibria's membership needs the estimate)
WITH = {"equilibria": ["invariant_estimate", "equilibria"], "constants": ["constants", "damping_condition"]}


#: variants proved with a lower precision ceiling in the default run: on 4 pieces the constants never converge,
#: so the prover escalates to its ceiling (4096 bits: 35 s a claim) and every attempt ends as the first ones do;
#: 128 bits still escalates once (64 -> 128) and costs 1-2 s. The full escalation is the slow twin
#: test_a_budget_of_4_pieces_decides_the_same_at_the_full_precision_ceiling (--runslow).
CEILING = {"budget of 4 pieces": 128}


def _prove(variant: str, claim: str, **prove) -> dict:
    params, options = VARIANTS[variant]
    if variant in CEILING:
        prove = {"maxprec": CEILING[variant], **prove}
    return certificate("agafonov2013", options, claims_only=WITH.get(claim, [claim]), prove=prove, **params)


def _confirm(variant: str, claim: str) -> dict:
    """Prove CLAIM on VARIANT, check the outcome it must get, and have the checker confirm every claim."""
    data = _prove(variant, claim)
    got = {c["id"]: c for c in data["claims"]}[claim]
    want = EXPECTED.get((variant, claim))
    assert want is None or got["status"] == want, (variant, claim, got["status"], got["reason"])
    report = check_certificate(data)
    assert report.ok, (variant, claim, report.first_failure)
    return data


def _q(data: dict, name: str) -> Fraction:
    return Fraction(data["quantities"][name]["lo"]), Fraction(data["quantities"][name]["hi"])


def _run(claim: str, variants=tuple(VARIANTS)):
    return {v: _confirm(v, claim) for v in variants}


def test_constants_and_damping_on_every_variant_and_against_mpmath():
    """m, M, p, k_min, R1, R2 (claim constants) contain mpmath's values where proved; not converged on 4
    pieces they are inconclusive, never proved; the damping condition k > p A0/H is decided either way."""
    out = _run("constants", ("paper", "budget of 4 pieces", "(16) empty (k = 0.1)", "linear law"))
    for variant in ("paper", "linear law"):
        params = dict(load_scene("agafonov2013").parameters, **VARIANTS[variant][0])
        ref = mp_values(tuple(sorted(params.items())))
        for name in ("m", "M", "p", "k_min", "R1", "R2"):
            assert contains_ref(as_ball(interval(out[variant]["quantities"][name])), ref[name]), (variant, name)
    for variant, data in out.items():
        damping = next(c for c in data["claims"] if c["id"] == "damping_condition")
        want = (EXPECTED.get((variant, "damping_condition")) or "proved")
        assert damping["status"] == want, (variant, damping["reason"])


def test_v_positive_on_every_variant():
    _run("v_positive")


def test_vdot_nonpositive_on_every_variant():
    _run("vdot_nonpositive")


def test_invariant_estimate_on_every_variant_and_c_star_against_mpmath():
    """c* (the boundary minimum of V over region (17)) contains mpmath's at 50 digits where mpmath has one;
    c_set is below c*'s lower end and the axis segments lie inside the extents."""
    out = _run("invariant_estimate")
    for variant in ("paper", "faces below 1 (x2* = 1/10)", "linear law"):
        data = out[variant]
        params = dict(load_scene("agafonov2013").parameters, **VARIANTS[variant][0])
        ref = mp_values(tuple(sorted(params.items())))
        lo, hi = _q(data, "c_star")
        if ref["c_star"] is not None:
            assert lo <= Fraction(ref["c_star"]) * (1 + Fraction(1, 10 ** 12)) and \
                Fraction(ref["c_star"]) * (1 - Fraction(1, 10 ** 12)) <= hi, (variant, lo, hi, ref["c_star"])
        inv = next(c for c in data["claims"] if c["id"] == "invariant_estimate")
        c_set = Fraction(inv["details"]["c_set"])
        assert 0 < c_set < lo
        for axis in ("x1", "x2", "x3"):
            assert _q(data, f"extent_{axis}_axis")[0] <= _q(data, f"extent_{axis}")[1], (variant, axis)


def test_largest_sublevel_on_every_variant():
    """Which part binds is stated as the theory has it: the faces where c_max = min phi(+-x2*) (the paper's
    x2* and 1/10), the set {Vdot >= 0} at x2* = 1.3; the stored cover has at most the boxes counted."""
    out = _run("largest_sublevel")
    binds = {"paper": "faces", "faces below 1 (x2* = 1/10)": "faces", "Vdot binds (x2* = 1.3)": "vdot"}
    for variant, want in binds.items():
        claim = next(c for c in out[variant]["claims"] if c["id"] == "largest_sublevel")
        assert claim["details"]["binds"] == want and claim["details"]["boxes"] > 0, variant
        assert 0 < len(out[variant]["witnesses"]["largest_sublevel"]["boxes"]) <= claim["details"]["boxes"]


def test_equilibria_on_every_variant():
    _run("equilibria")


def test_vdot_direct_on_every_variant():
    """Where A(0, t) < 0 for some t (k = 0.2) or min A is about -1e-34 (mu = 0.01) no radius can be certified:
    inconclusive, never a radius."""
    out = _run("vdot_direct", ("paper", "faces below 1 (x2* = 1/10)", "Vdot binds (x2* = 1.3)", "linear law",
                               "origin refutes c_max (k = 0.2)", "mu below (16) (mu = 0.01)"))
    for variant in ("origin refutes c_max (k = 0.2)", "mu below (16) (mu = 0.01)"):
        assert "R_direct" not in out[variant]["quantities"], variant


def test_best_mu_on_every_variant_and_R_sup_against_mpmath():
    """R_sup at the chosen mu_best contains mpmath's value there; mu_best lies inside (16)."""
    out = _run("best_mu", ("paper", "mu below (16) (mu = 0.01)", "linear law", "radii above 1 (k = 40, mu = 1.5)",
                           "(16) empty (k = 0.1)"))
    for variant, data in out.items():
        claim = next(c for c in data["claims"] if c["id"] == "best_mu")
        if claim["status"] != "proved":
            continue
        params = dict(load_scene("agafonov2013").parameters, **VARIANTS[variant][0])
        at = mp_values(tuple(sorted(dict(params, mu=claim["details"]["mu_best"]).items())))
        assert contains_ref(as_ball(interval(data["quantities"]["R_sup_at_mu_best"])), at["R_sup"]), variant
        lo, hi = _q(data, "mu_min")[0], _q(data, "mu_max")[1]
        assert lo < Fraction(claim["details"]["mu_best"]) < hi


def test_best_mu_direct_on_every_variant():
    _run("best_mu_direct", ("paper", "linear law", "radii above 1 (k = 40, mu = 1.5)", "(16) empty (k = 0.1)"))


@pytest.mark.slow
@pytest.mark.parametrize("claim", ["constants", "v_positive", "vdot_nonpositive", "invariant_estimate",
                                   "largest_sublevel", "equilibria"])
def test_a_budget_of_4_pieces_decides_the_same_at_the_full_precision_ceiling(claim):
    """The slow twin of the default run's CEILING: proved to the prover's own ceiling (4096 bits, about 35 s a
    claim), the budget of 4 pieces gives every claim the status it gets at 128 bits, and the checker
    confirms the certificate."""
    low = _prove("budget of 4 pieces", claim)
    params, options = VARIANTS["budget of 4 pieces"]
    full = certificate("agafonov2013", options, claims_only=WITH.get(claim, [claim]), **params)
    assert full["precisions_tried"][-1] > low["precisions_tried"][-1] == CEILING["budget of 4 pieces"]
    assert [(c["id"], c["status"]) for c in full["claims"]] == [(c["id"], c["status"]) for c in low["claims"]]
    want = EXPECTED.get(("budget of 4 pieces", claim))
    assert want is None or {c["id"]: c["status"] for c in full["claims"]}[claim] == want
    report = check_certificate(full)
    assert report.ok, report.first_failure


@pytest.mark.parametrize("variant", ["paper", "radius far too large (R = 0.5)"])
def test_every_claim_at_once_matches_the_claims_one_at_a_time(variant):
    """The orchestration (``attempt``): proving every claim together gives each claim the status it gets
    alone (the shared memo of constants changes nothing), and the checker confirms the whole."""
    params, options = VARIANTS[variant]
    whole = certificate("agafonov2013", options, **params)
    assert check_certificate(whole).ok
    for c in whole["claims"]:
        if (variant, c["id"]) in EXPECTED:
            assert c["status"] == EXPECTED[(variant, c["id"])], (variant, c["id"], c["reason"])


def test_equilibria_membership_in_the_estimate_is_decided_point_by_point(monkeypatch):
    """Which equilibria lie in the estimate {V < c_set, x1^2 + x3^2 < R^2, |x2| <= x2*}: on planted
    equilibria (the paper's scene has only the origin inside and +-pi/2 beyond x2*), each row's label is
    the one an mpmath evaluation of V gives (40 digits), and a point straddling the disc's edge is
    'undecided', which leaves the claim inconclusive."""
    base = _prove("paper", "equilibria")
    inv = next(c for c in base["claims"] if c["id"] == "invariant_estimate")
    c_set, R = Fraction(inv["details"]["c_set"]), _q(base, "R_used")
    xs = float(Fraction(_q(base, "extent_x2")[1]))          # below x2* = pi/6 = 0.5236
    mpmath.mp.dps = 40
    mg = MpGimbal(load_scene("agafonov2013").parameters)
    r = float(R[0])
    planted = [(0.0, 0.0), (2 * r, 0.0), (0.5 * r, 0.0), (0.9 * r, 0.0), (0.0, 0.5), (0.0, 0.3), (0.01, 0.6)]

    def label(x1, x2):
        if abs(x2) > float(mpmath.pi / 6):
            return "outside the estimate (|x2| > x2*)"
        inside = x1 * x1 < r * r and mg.V(mpmath.mpf(x1), mpmath.mpf(x2), 0) < mpmath.mpf(c_set.numerator) / c_set.denominator
        return "inside the estimate" if inside else "outside the estimate"
    want = [label(x1, x2) for x1, x2 in planted]
    assert "inside the estimate" in want and "outside the estimate" in want and xs > 0
    assert len(set(want)) == 3

    def fake(points):
        return lambda g: Equilibria([Equilibrium(x1, x2, "planted", stability="asymptotically stable")
                                     for x1, x2 in points], True, "", {})
    monkeypatch.setattr(C, "equilibria", fake([(arb(x1), arb(x2)) for x1, x2 in planted]))
    data = _prove("paper", "equilibria")
    claim = next(c for c in data["claims"] if c["id"] == "equilibria")
    assert claim["status"] == "proved", claim["reason"]
    assert [row["estimate"] for row in claim["details"]["equilibria"]] == want
    # V(x1, 0, 0) is quadratic in x1: it meets c_set at x1 = r sqrt(c_set / V(r, 0, 0)); a ball of relative
    # radius 1e-3 there straddles the level set
    edge = r * float(mpmath.sqrt(mpmath.mpf(c_set.numerator) / c_set.denominator / mg.V(mpmath.mpf(r), 0, 0)))
    monkeypatch.setattr(C, "equilibria", fake([(arb(0), arb(0)), (arb(edge, edge * 1e-3), arb(0))]))
    claim = next(c for c in _prove("paper", "equilibria", maxprec=128)["claims"] if c["id"] == "equilibria")
    assert claim["status"] == "inconclusive" and claim["details"]["equilibria"][1]["estimate"] == "undecided"


def test_vdot_direct_states_an_upper_bound_only_at_a_point_where_vdot_is_positive(monkeypatch):
    """A search that puts the supremum 10 % too low: A - R |B| > 0 is still certified there (below the
    supremum), but every candidate point above it lies where Vdot < 0, so no upper bound of the supremum
    may be stated; the checker confirms what is stated."""
    real = DC.direct_point_search

    def low(g, *args):
        est, u0, s0, amin = real(g, *args)
        return 0.9 * est, u0, s0, amin
    monkeypatch.setattr(DC, "direct_point_search", low)
    data = _prove("paper", "vdot_direct")
    claim = next(c for c in data["claims"] if c["id"] == "vdot_direct")
    assert claim["status"] == "proved" and "R_direct_upper" not in data["quantities"], claim["reason"]
    assert "no upper bound" in claim["reason"] and check_certificate(data).ok


def test_a_decimal_inside_an_open_interval_is_inside_it():
    """_decimal_inside: the short decimal chosen for mu lies certainly inside (lo, hi) however close mu is
    to either end (rounded the other way, or with more digits), and there is none when no decimal of up to
    60 digits near mu fits."""
    lo, hi = Fraction(1, 3), Fraction(2, 3)
    for mu in (lo + Fraction(1, 10 ** 15), hi - Fraction(1, 10 ** 15), Fraction(1, 2), lo + Fraction(1, 10 ** 40)):
        got = MC._decimal_inside(mu, arb(fmpq(1, 3)), arb(fmpq(2, 3)))
        assert got is not None and lo < Fraction(got) < hi and abs(Fraction(got) - mu) < Fraction(1, 10 ** 11), (mu, got)
    tiny = Fraction(1, 3) + Fraction(1, 10 ** 70)
    assert MC._decimal_inside(tiny, arb(fmpq(1, 3)), arb(fmpq(tiny.numerator, tiny.denominator))) is None


def test_rho_is_infinite_where_a_disc_coefficient_is_not_positive():
    """rho_function: where c10 (or c20) is <= 0 no disc of positive radius keeps Psi_i > 0, so rho = +inf
    (here c10 < 0 at x2 = 0.3 for the parameters of test_lyapunov's CSTAR_CASE with mu = 0.02); elsewhere it
    is finite and positive."""
    g, _ = C.gimbal_from_parameters(dict(CSTAR_CASE, mu="0.02"))
    with working_precision(64):
        (c10, _, _), _ = g.psi_coefficients(arb("0.3"))
        assert c10 < 0
        assert not MC.rho_function(g)(arb("0.3")).is_finite()
        g2, _ = C.gimbal_from_parameters(dict(CSTAR_CASE, mu="0.016"))
        r = MC.rho_function(g2)(arb("0.3"))
        assert r.is_finite() and r > 0


@pytest.mark.parametrize("params, where", [
    ({}, "end"), ({"x2_star": "1/10"}, "end"), ({"x2_star": "1.3"}, "end"), ({"k": "40", "mu": "1.5"}, "end"),
    ({"x2_star": "1", "k": "4"}, "inside"), ({"x2_star": "1.4", "mu": "0.1", "k": "40"}, "inside"),
    ({"mu": "0.01"}, "none"), ({"C1": "54.2"}, "none")],
    ids=["paper", "x2* = 1/10", "x2* = 1.3", "R_sup = 2.83 > 1", "peak at 0.813", "peak at 1.253", "mu = 0.01", "C0 < 0"])
def test_the_r_sup_search_finds_the_float_sides_r_sup_and_where_it_is_attained(params, where):
    """_r_sup_search (a float heuristic choosing mu_best and the bound's points) against the float side's own
    R_sup(mu) = min over x2 of ci0/|(ci1, ci3)| in mpmath: the same value to 1e-9 and the same x2, at the end
    x2* (returned as the ball x2* itself), at an interior peak (refined by the golden steps to 1e-6, an exact
    point), or 0 where some ci0 <= 0 (no disc)."""
    from rigor_gyro.kinds.lyapunov.approx import FloatGimbal, _r_sup
    full = dict(load_scene("agafonov2013").parameters, **params)
    g, _ = C.gimbal_from_parameters(full)
    with working_precision(64):
        est, at = MC._r_sup_search(g, g.c.x2_star)
        xs = g.c.x2_star
    with mpmath.workdps(30):
        mg = MpGimbal(full)
        ref, x = _r_sup(mg, FloatGimbal(full), mg.mu)
    if where == "none":
        assert ref == 0 and est == 0.0
        return
    assert abs(est / float(ref) - 1) < 1e-9, (est, ref)
    if where == "end":
        assert abs(float(x) - float(xs.mid())) < 1e-9, x          # the reference's argmax is x2* too
        assert at is xs or (at.is_finite() and at.overlaps(xs) and at.rad() <= xs.rad()), at
    else:
        assert at.rad() == 0 and abs(float(at) - float(x)) < 1e-6 and certainly_lt(at, xs), (at, x)


def test_x2_star_is_admissible_exactly_below_pi_over_2():
    """The domain condition 0 < x2* < pi/2, decided exactly: 49 pi/100 and 1.5707 are admissible, pi/2 and
    1.5708 (just above pi/2 = 1.570796...) are not, whether x2* is written with pi or as a decimal."""
    base = load_scene("agafonov2013").parameters
    for ok in ("49*pi/100", "1.5707", "pi/3", "1/1000"):
        C.gimbal_from_parameters(dict(base, x2_star=ok))
    for bad in ("pi/2", "1.5708", "51*pi/100", "0*pi", "-1/1000"):
        with pytest.raises(ParameterError, match="x2_star"):
            C.gimbal_from_parameters(dict(base, x2_star=bad))
