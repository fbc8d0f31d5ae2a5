"""Option orbit of the relay kind (issue 37 part 2, tracked objects): the claims orbit_genuine,
initial_point, multipliers and stable are about the root of g nearest the option's value, certified
nearest, and only about it.

The figures (measured, then cross-checked here in mpmath, never decided by it): in the tau family of the
B = 2/15 scene the orbit near theta = 0.266 loses stability at tau in [0.0554086765365718, 0.0554086765366083]
(its complex pair of multipliers crosses modulus 1; theta* = 0.266069 there), while the orbit near
theta = 0.39 stays stable (modulus 0.67 at tau = 0.06), so the untracked 'stable' stays proved across
the crossing. ``rigor-gyro margin tests/corpus/relay_tracked_orbit_0266.toml --param tau --lo 0.05
--hi 0.06 --claim stable --width 1e-12`` brackets it (40 point proofs, ~4 s); the default run proves the
two bracket ends only, the whole bisection is behind ``--runslow``.
"""
import dataclasses
import random
import re
from fractions import Fraction as F
from pathlib import Path

import mpmath as mp
import pytest
from flint import arb, fmpq

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.periodic_orbit import CLAIMS, statements, validate
from rigor_gyro.kinds.periodic_orbit.approx import approx_orbit_mpmath
from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box
from rigor_gyro.kinds.periodic_orbit.check import _tracked_verdict, check as kind_check
from rigor_gyro.kinds.periodic_orbit.tracked import Nearest, nearest_root

SCENE = Path(__file__).resolve().parent / "corpus" / "relay_tracked_orbit_0266.toml"
#: the bracket `rigor-gyro margin SCENE --param tau --lo 0.05 --hi 0.06 --claim stable --width 1e-12` certified
PROVED_AT = F("0.0554086765365718747489154338836669921875")
REFUTED_AT = F("0.05540867653660825453698635101318359375")


def _scene(tau=None, **options):
    sc = load_scene(str(SCENE))
    params = dict(sc.parameters) if tau is None else {**sc.parameters, "tau": str(tau)}
    opts = {**sc.options, **options}
    return dataclasses.replace(sc, parameters=params, options={k: v for k, v in opts.items() if v is not None})


def _cert(scene):
    return prove_scene(scene).to_json()


def _claims(cert):
    return {c["id"]: c for c in cert["claims"]}


def _kind_check(scene, cert):
    """The kind's checker at the precision rigor-gyro check gives it (twice the certificate's, >= 128)."""
    with working_precision(max(2 * cert["precision_bits"], 128)):
        return kind_check(validate(scene), cert)


def _kind_check_ok(cert, scene):
    results = _kind_check(scene, cert)
    bad = [r for r in results if not r.ok]
    assert not bad, bad


# ------------------------------------------------------------------ the decision: nearest_root

def _iv(a, b):
    return arb(fmpq(F(a).numerator, F(a).denominator)).union(arb(fmpq(F(b).numerator, F(b).denominator)))


T266 = arb(fmpq(133, 500))


def test_nearest_certified_with_a_gap():
    nr = nearest_root(T266, [_iv("0.25", "0.2501"), _iv("0.38", "0.3801")])
    assert nr.index == 0 and nr.certified
    assert nr.reach > arb("0.0159") and nr.gap < arb("0.1141") and nr.decides > 0


def test_nearest_tie_is_never_certified():
    # t exactly midway between two exact roots: equal distances, no certificate (the claims stay inconclusive)
    t = arb(fmpq(5, 16))
    nr = nearest_root(t, [arb(fmpq(1, 4)), arb(fmpq(3, 8))])
    assert nr.index is not None and not nr.certified and "not certified" in nr.reason


def test_nearest_uses_the_farthest_point_of_the_chosen_enclosure():
    # the chosen enclosure's farthest point (0.2) is 0.06 away, the other root only 0.04: not certified
    nr = nearest_root(arb(fmpq(13, 50)), [_iv("0.2", "0.27"), _iv("0.3", "0.31")])
    assert nr.index == 0 and not nr.certified


def test_nearest_counts_undecided_pieces_and_unsearched_roots():
    roots = [_iv("0.25", "0.2501")]
    assert nearest_root(T266, roots).certified
    assert not nearest_root(T266, roots, unknown=[(arb("0.27"), arb("0.28"))]).certified
    assert not nearest_root(T266, roots, beyond=arb("0.27")).certified
    assert nearest_root(T266, roots, unknown=[(arb("0.3"), arb("0.31"))], beyond=arb("0.3")).certified


def test_nearest_without_roots():
    nr = nearest_root(T266, [])
    assert nr.index is None and not nr.certified and nr.decides is None


def test_nearest_is_sound_on_random_layouts():
    """Whenever the choice is certified, every point of the chosen enclosure is strictly nearer t than
    every point of every other enclosure (exact rationals, both ends of each tried)."""
    rng = random.Random(37)
    certified = 0
    for _ in range(400):
        edges = sorted({F(rng.randrange(1, 2000), 1000) for _ in range(8)})
        ivs = [(edges[i], edges[i + 1]) for i in range(0, len(edges) - 1, 2)]
        t = F(rng.randrange(1, 2000), 1000)
        with working_precision(64):
            nr = nearest_root(arb(fmpq(t.numerator, t.denominator)), [_iv(a, b) for a, b in ivs])
        if not nr.certified:
            continue
        certified += 1
        a, b = ivs[nr.index]
        far = max(abs(a - t), abs(b - t))
        for j, (c, d) in enumerate(ivs):
            if j != nr.index:
                near = F(0) if c <= t <= d else min(abs(c - t), abs(d - t))
                assert far < near, (t, ivs, nr.index)
    assert certified > 100


# ------------------------------------------------------------------ options, statements

def test_option_orbit_is_an_exact_positive_number():
    assert validate(_scene()).orbit.rational == F(133, 500)
    assert validate(_scene(orbit="")).orbit is None
    for bad in ("0", "-0.1", "abc", "1e7"):
        with pytest.raises(ParameterError, match="orbit"):
            validate(_scene(orbit=bad))


def test_statements_say_which_orbit():
    assert statements(validate(_scene(orbit=""))) == CLAIMS
    st = statements(validate(_scene()))
    assert st["half_period"] == CLAIMS["half_period"]
    for cid in ("orbit_genuine", "initial_point", "multipliers", "stable"):
        assert "nearest theta = 0.266" in st[cid] and st[cid] != CLAIMS[cid]
    assert "certainly less than that of every other root" in st["orbit_genuine"]


# ------------------------------------------------------------------ point proofs

@pytest.fixture(scope="module")
def certs():
    return {"0.05": _cert(_scene("0.05")), "0.06": _cert(_scene()), "0.06 untracked": _cert(_scene(orbit=None)),
            "proved_at": _cert(_scene(PROVED_AT)), "refuted_at": _cert(_scene(REFUTED_AT))}


def _confirmed_but_statements(cert):
    """The whole checker confirms everything except, until rigor_gyro/check.py compares statements with
    the kind's ``statements(model)`` instead of CLAIMS, the four tracked statements."""
    rep = check_certificate(cert)
    assert rep.ok, rep.first_failure


def test_tracked_orbit_stable_at_tau_005(certs):
    c = certs["0.05"]
    cl = _claims(c)
    assert all(x["status"] == "proved" for x in cl.values())
    assert "nearest 0.266 is theta = [0.25363379928" in cl["stable"]["reason"]
    assert c["extra"]["tracked_orbit"]["root"] == 2 and c["extra"]["tracked_orbit"]["certified_nearest"]
    m = c["quantities"]["stability_margin"]
    assert F(m["lo"]) > F("0.0221") and F(m["hi"]) < F("0.0222")      # this orbit's, not the 0.39 orbit's 0.258
    _kind_check_ok(c, _scene("0.05"))
    _confirmed_but_statements(c)


def test_tracked_orbit_unstable_at_tau_006_while_another_is_stable(certs):
    c, u = certs["0.06"], certs["0.06 untracked"]
    assert _claims(u)["stable"]["status"] == "proved"               # by the orbit near 0.395 ...
    assert "0.395254" in _claims(u)["stable"]["reason"]
    cl = _claims(c)
    assert cl["orbit_genuine"]["status"] == "proved"
    st = cl["stable"]
    assert st["status"] == "refuted"                                # ... but the orbit near 0.266 is unstable
    cx = st["counterexample"]
    assert cx["orbit"] == "0.266" and cx["theta"][0].startswith("0.27603089166")
    assert F(cx["modulus_above_1"][0]) > F("1.0191")
    assert F(cx["distance_at_most"]) < F(cx["others_at_least"])
    assert F(c["quantities"]["stability_margin"]["hi"]) < 0         # the margin printed is this orbit's
    _kind_check_ok(c, _scene())
    _confirmed_but_statements(c)


def test_the_margin_bracket_ends(certs):
    """The two points the threshold search certified: stable proved at PROVED_AT, refuted at REFUTED_AT,
    1e-9 relative apart; mpmath (a cross-check, 30 digits) agrees on the side of 1 at both ends."""
    assert (REFUTED_AT - PROVED_AT) / PROVED_AT < F(1, 10**9)
    assert _claims(certs["proved_at"])["stable"]["status"] == "proved"
    assert _claims(certs["refuted_at"])["stable"]["status"] == "refuted"
    for key, tau, sign in (("proved_at", PROVED_AT, -1), ("refuted_at", REFUTED_AT, 1)):
        th, mod = _mp_max_modulus(tau)
        assert sign * (mod - 1) > 0
        q = certs[key]["quantities"]
        assert F(q["theta_star"]["lo"]) <= F(mp.nstr(th, 25)) * (1 + F(1, 10**20))
        assert F(mp.nstr(th, 25)) * (1 - F(1, 10**20)) <= F(q["theta_star"]["hi"])
        margin = F(mp.nstr(1 - mod, 20))
        assert F(q["stability_margin"]["lo"]) - abs(margin) * F(1, 10**12) <= margin
        assert margin <= F(q["stability_margin"]["hi"]) + abs(margin) * F(1, 10**12)


def test_a_spurious_tracked_root_refutes(certs):
    """orbit = "0.127": the nearest root of g (0.1271) is spurious, so the claims about it are refuted
    (the untracked ones are proved by the genuine orbits)."""
    sc = _scene("0.05", orbit="0.127")
    c = _cert(sc)
    cl = _claims(c)
    for cid in ("orbit_genuine", "initial_point", "multipliers", "stable"):
        assert cl[cid]["status"] == "refuted", cid
        assert "spurious_because" in cl[cid]["counterexample"]
    assert "theta_star" not in c["quantities"] and "theta_star_2" in c["quantities"]
    _kind_check_ok(c, sc)


def test_an_uncertified_nearest_root_is_inconclusive_never_refuted():
    """T_max = 0.5 leaves roots beyond 0.5 unsearched; orbit = 0.45 is nearer 0.5 than the root 0.3935."""
    sc = _scene("0.05", orbit="0.45", T_max="0.5")
    c = _cert(sc)
    cl = _claims(c)
    assert cl["half_period"]["status"] == "proved"
    for cid in ("orbit_genuine", "initial_point", "multipliers", "stable"):
        assert cl[cid]["status"] == "inconclusive" and "not certified nearest" in cl[cid]["reason"], cid
    assert "theta_star" not in c["quantities"]
    _kind_check_ok(c, sc)


# ------------------------------------------------------------------ the kind checker

def _near(ok=True):
    return Nearest(0, ok, arb(1), arb(2), "", "")


def test_checker_tracked_verdicts():
    stable, unstable, touching = [arb("0.5")], [arb("1.02")], [arb(1).union(arb("1.01"))]
    main = arb("0.27")
    assert _tracked_verdict("stable", "proved", (_near(), "genuine"), main, stable, True, False)[0]
    assert not _tracked_verdict("stable", "proved", (_near(False), "genuine"), main, stable, True, False)[0]
    assert not _tracked_verdict("stable", "proved", (_near(), "genuine"), main, unstable, True, False)[0]
    assert _tracked_verdict("stable", "refuted", (_near(), "genuine"), main, unstable, True, False)[0]
    assert not _tracked_verdict("stable", "refuted", (_near(), "genuine"), main, touching, True, False)[0]
    assert not _tracked_verdict("stable", "refuted", (_near(False), "genuine"), main, unstable, True, False)[0]
    assert _tracked_verdict("orbit_genuine", "refuted", (_near(), "spurious"), None, None, True, False)[0]
    assert not _tracked_verdict("orbit_genuine", "refuted", (_near(False), "spurious"), None, None, True, False)[0]
    assert not _tracked_verdict("orbit_genuine", "refuted", (_near(), "genuine"), main, stable, True, False)[0]
    assert _tracked_verdict("orbit_genuine", "refuted", None, None, None, True, True)[0]
    assert not _tracked_verdict("multipliers", "proved", (_near(), "genuine"), main, stable, False, False)[0]


def test_checker_rejects_a_tracked_claim_about_another_orbit(certs):
    """The certificate at tau = 0.06 re-checked as if it tracked the orbit near 0.39: the stored theta*
    (0.276) is not the root the checker finds nearest, so nothing tracked is confirmed."""
    res = _kind_check(_scene(orbit="0.39"), certs["0.06"])
    bad = {r.item for r in res if not r.ok}
    assert {"orbit_genuine", "stable"} <= bad


# ------------------------------------------------------------------ over a box (boxes.evaluate_box)

def test_tracked_claims_over_a_tau_box():
    """The same claims over tau +- 1e-7 relative: proved for every member at 0.05, refuted for every
    member at 0.06 (the tracked root certified nearest for each); the printed modulus enclosure holds
    mpmath's max modulus at the box's ends and middle."""
    model = validate(_scene())
    for c, want in ((F("0.05"), "proved"), (F("0.06"), "refuted")):
        lo, hi = c * (1 - F(1, 10**7)), c * (1 + F(1, 10**7))
        with working_precision(128):
            out = evaluate_box(model, Box.of({"tau": (lo, hi)}), ["orbit_genuine", "stable"])
        assert out["orbit_genuine"][0] == "proved" and out["stable"][0] == want, out
        enc = re.search(r"modulus (?:in )?\[([0-9.e-]+), ([0-9.e-]+)\]", out["stable"][1])
        a, b = F(enc.group(1)), F(enc.group(2))
        for tau in (lo, c, hi):
            _, mod = _mp_max_modulus(tau, dps=20)
            assert a <= F(mp.nstr(mod, 20)) <= b


def test_a_box_never_proves_the_tracked_claims_about_a_farther_orbit():
    """orbit = "0.127" near tau = 0.05: the root of g nearest 0.127 is spurious (the point proof refutes
    orbit_genuine and stable, test_a_spurious_tracked_root_refutes); a box around that point must not
    prove them (by the genuine orbit at 0.2536)."""
    model = validate(_scene("0.05", orbit="0.127"))
    c = F("0.05")
    with working_precision(128):
        out = evaluate_box(model, Box.of({"tau": (c * (1 - F(1, 10**7)), c * (1 + F(1, 10**7)))}),
                           ["orbit_genuine", "stable"])
    assert out["orbit_genuine"][0] != "proved" and out["stable"][0] != "proved", out


@pytest.mark.slow
def test_margin_brackets_the_crossing_to_1e_9():
    """The whole threshold search of the issue: proved at 0.05, refuted at 0.06, bisected to 1e-12."""
    from rigor_gyro.margins.threshold import find_threshold
    res = find_threshold(load_scene(str(SCENE)), "tau", claim="stable", lo="0.05", hi="0.06", width="1e-12")
    assert res.certified
    l, r = res.bracket()
    assert (r - l) / l < F(1, 10**9) and l <= PROVED_AT <= r and l <= REFUTED_AT <= r


# ------------------------------------------------------------------ mpmath (cross-check only)

PARAMS = {"A": "125", "B": "2/15", "H": "100", "sigma": "0.13125", "n": "50", "K": "7.5", "p": "40", "S": "0.15"}


def _mp_max_modulus(tau: F, guess: float = 0.266, dps: int = 30):
    """theta* near ``guess`` and the largest multiplier modulus, by mpmath.expm of the flow (no balls)."""
    P = {**PARAMS, "tau": f"{tau.numerator}/{tau.denominator}"}
    th, x0 = approx_orbit_mpmath(P, guess, dps)
    with mp.workdps(dps + 10):
        A, B, H, ta, sig, n, K, p, S = [mp.mpf(F(P[k]).numerator) / F(P[k]).denominator
                                         for k in ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")]
        M = mp.matrix([[0, 1, 0, 0, 0], [0, 0, -H / B, 0, 0], [0, H / A, 0, K / A, 0],
                       [0, 0, -n / (K * ta), -1 / ta, p / ta], [0, 0, 0, 0, -1 / sig]])
        e = mp.matrix([0, 0, 0, 0, 1 / sig])
        Phi = mp.expm(M * th)
        f = M * (-mp.matrix(x0)) + e * S
        C = mp.matrix(5, 5)
        for i in range(5):
            C[i, 0] = f[i] / f[0]
        Q = (mp.eye(5) - C) * Phi
        J = mp.matrix([[-Q[i, j] for j in range(1, 5)] for i in range(1, 5)])
        return th, max(abs(z) for z in mp.eig(J, left=False, right=False))
