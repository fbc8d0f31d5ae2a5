"""The planted corpus (tests/corpus/*.toml): scenes whose claims are false or undecidable at their
settings, each with the outcome it must get. None is ever proved; every certificate they produce is
confirmed by the independent checker; a refuted claim carries a counterexample the checker re-derives.
Three of them are also built in as demos (``rigor-gyro list``, ``prove --group demo``)."""
import json
from fractions import Fraction
from pathlib import Path

import mpmath
import pytest

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.check import check_certificate
from rigor_gyro.scene import builtin_scenes

CORPUS = Path(__file__).resolve().parent / "corpus"

#: scene -> {claim: the status it must get}; the planted claims are never "proved"
EXPECTED = {
    "eig_brackets_exclude_roots": {"bracket_2": "refuted", "bracket_4": "refuted", "nu_ordering": "refuted"},
    "eig_nu_order_fails": {"nu_ordering": "refuted", "branches": "refuted"},
    "eig_near_double_nu": {"nu_ordering": "refuted"},
    "relay_sign_condition_fails": {"half_period": "proved", "orbit_genuine": "inconclusive", "stable": "inconclusive"},
    "relay_no_root_below_t_max": {"half_period": "proved", "orbit_genuine": "inconclusive"},
    "relay_unstable": {"orbit_genuine": "proved", "stable": "refuted"},
    "relay_multiplier_near_one": {"orbit_genuine": "proved", "stable": "refuted"},
    "relay_tracked_orbit_0266": {"orbit_genuine": "proved", "stable": "refuted"},
    "lyap_radius_above_sup_psi1": {"psi_test": "refuted"},        # Vdot <= 0 holds there (direct test)
    "lyap_radius_above_sup_psi2": {"vdot_nonpositive": "refuted"},
    "lyap_v_not_positive": {"v_positive": "refuted", "damping_condition": "refuted"},
    "lyap_region_far_too_large": {"vdot_nonpositive": "refuted"},
}


def test_every_corpus_file_has_an_expected_outcome():
    assert {p.stem for p in CORPUS.glob("*.toml")} == set(EXPECTED)


@pytest.fixture(scope="module")
def certs():
    return {name: json.loads(json.dumps(prove_scene(load_scene(str(CORPUS / f"{name}.toml"))).to_json()))
            for name in EXPECTED}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_planted_outcome_and_never_proved(certs, name):
    cert = certs[name]
    got = {c["id"]: c["status"] for c in cert["claims"]}
    for claim, status in EXPECTED[name].items():
        assert got[claim] == status, (name, claim, got[claim])
    assert cert["verdict"] != "proved"
    report = check_certificate(cert)
    assert report.ok, (name, report.first_failure)


def test_the_refutations_carry_the_right_counterexamples(certs):
    psi1 = next(c for c in certs["lyap_radius_above_sup_psi1"]["claims"] if c["id"] == "psi_test")
    assert psi1["counterexample"]["psi"] == "Psi1"        # Psi1, not Psi2, binds at mu = 0.025
    psi2 = next(c for c in certs["lyap_radius_above_sup_psi2"]["claims"] if c["id"] == "vdot_nonpositive")
    assert "vdot" in psi2["counterexample"]               # Psi2 binds at mu = 0.014: Vdot > 0 on x1 = 0
    og = next(c for c in certs["relay_sign_condition_fails"]["claims"] if c["id"] == "orbit_genuine")
    assert "beta(t) = [-" in og["reason"] and "not a refutation" in og["reason"]


def test_a_modulus_within_1e_30_of_one_is_refuted_only_with_the_digits_that_show_it(certs):
    """The orbit theta* ~ 0.12113 has modulus 1 + ~1e-33: the stored lower bound is certainly > 1 and
    within 1e-30 of 1 (so the counterexample really is the knife edge, printed to the digits that show it)."""
    stable = next(c for c in certs["relay_multiplier_near_one"]["claims"] if c["id"] == "stable")
    lows = [Fraction(o["modulus_above_1"][0]) for o in stable["counterexample"]["orbits"]]
    assert all(lo > 1 for lo in lows)
    assert any(lo < 1 + Fraction(1, 10 ** 30) for lo in lows)
    assert "max |.| = [1.0000000000000000000000000000000" in stable["reason"]


def test_a_modulus_within_1e_30_of_one_is_inconclusive_at_64_bits():
    """Precision caps never refute: pinned at 64 bits, the knife-edge orbit's stability is undecided."""
    cert = prove_scene(load_scene(str(CORPUS / "relay_multiplier_near_one.toml")), prec=64, maxprec=64)
    assert cert.claim("stable").status.value == "inconclusive"
    assert cert.claim("orbit_genuine").status.value == "proved"


def test_the_near_double_case_is_decided_the_way_mpmath_says():
    """nu2 and nu3 are 1e-30 apart: the certificate's ordering verdict agrees with mpmath at 100 digits."""
    with mpmath.workdps(100):
        a, b = mpmath.mpf("15.08"), mpmath.mpf("6.154")
        eps = mpmath.mpf(11501151) / 15910580 * (1 + mpmath.mpf(10) ** -30)
        c2 = (a - b) * (b - 1)
        s1 = eps * (a - 1) + b * (a - b)
        nu2 = (s1 - mpmath.sqrt(s1 * s1 - 4 * c2 * eps * a)) / (2 * c2)
        nu3 = 1 / (b - 1)
        assert 0 < abs(nu2 - nu3) < mpmath.mpf(10) ** -28
        order_holds = nu2 < nu3
    cert = prove_scene(load_scene(str(CORPUS / "eig_near_double_nu.toml")))
    assert (cert.claim("nu_ordering").status.value == "proved") is order_holds


def test_the_demos_are_corpus_scenes():
    demos = builtin_scenes("demo")
    assert demos
    for name, res in demos.items():
        twin = CORPUS / f"{name.removeprefix('demo_')}.toml"
        assert res.read_text().replace(f'name = "{name}"', f'name = "{twin.stem}"') == twin.read_text()
