"""Regressions of a hostile review of the [plant] path (issue 42 part 1): each test failed before its fix."""
from __future__ import annotations

import copy
import json
import subprocess
import sys

import pytest

from rigor_gyro.certificate import digest
from rigor_gyro.check import check_certificate
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene, parse_scene

PLANTS = "rigor_gyro/scenes/plants/"


def _scene(M, e, c, S="1", h="0", params=None, extra="", name="t"):
    rows = ", ".join("[" + ", ".join(f'"{x}"' for x in r) + "]" for r in M)
    vec = lambda v: "[" + ", ".join(f'"{x}"' for x in v) + "]"        # noqa: E731
    ps = "\n".join(f'{k} = "{v}"' for k, v in (params or {}).items())
    return parse_scene(f'name = "{name}"\nkind = "periodic_orbit"\n[parameters]\n{ps}\n{extra}\n[plant]\nM = [{rows}]\n'
                       f'e = {vec(e)}\nc = {vec(c)}\nS = "{S}"\nh = "{h}"\n')


def _cert(scene):
    return json.loads(json.dumps(prove_scene(scene).to_json()))


def _foreign(cert, edit=None):
    """The certificate edited by ``edit``, signed as another version (texts then not compared), digest refixed."""
    d = copy.deepcopy(cert)
    if edit:
        edit(d)
    d["software"]["rigor_gyro"] = "0.0.0-other"
    d["integrity"]["sha256"] = digest(d)
    return d


def _items(cert):
    return {r.item: (r.ok, r.message) for r in check_certificate(cert).results}


# ---------------------------------------------------------------- 1. extra.roots re-verified, whatever the version

@pytest.fixture(scope="module")
def two_modes():
    return _cert(load_scene(PLANTS + "relay_two_modes.toml"))


def test_a_foreign_certificate_is_not_confirmed_but_its_re_verified_items_are(two_modes):
    """Another version's texts (audit rows, counterexamples' values, extra's words) cannot be re-derived here, so
    the certificate is not confirmed (a forger would otherwise only change the version string); every item this
    version re-verifies independently still passes."""
    it = _items(_foreign(two_modes))
    assert all(ok for item, (ok, _) in it.items() if item != "texts"), it
    assert it["extra.roots"][0] and it["texts"][0] is False and "is not confirmed" in it["texts"][1]


def _unstable_row(d):
    return next(r for r in d["extra"]["roots"] if r["stable"] is False)


@pytest.mark.parametrize("edit", [
    lambda d: _unstable_row(d).update(stable=True),
    lambda d: _unstable_row(d).update(stable=True, moduli=[["0.5", "0.5"], ["0.6", "0.6"], ["0.6", "0.6"]]),
    lambda d: _unstable_row(d).update(moduli=_unstable_row(d)["moduli"][1:]),
    lambda d: next(r for r in d["extra"]["roots"] if r["stable"] is True).update(stable=False),
    lambda d: next(r for r in d["extra"]["roots"] if r["kind"] == "spurious").update(stable=True),
    lambda d: next(r for r in d["extra"]["roots"] if r["kind"] == "spurious").update(kind="genuine"),
    lambda d: d["extra"]["roots"][0].update(theta=["1.47", "1.471"]),
    lambda d: d["extra"]["roots"].pop(),
], ids=["unstable_called_stable", "moduli_and_flag", "a_modulus_dropped", "stable_called_unstable",
        "spurious_flagged", "spurious_called_genuine", "theta_moved", "row_dropped"])
def test_a_tampered_roots_table_is_refused_whatever_the_version(two_modes, edit):
    it = _items(_foreign(two_modes, edit))
    assert it["extra.roots"][0] is False, it["extra.roots"]


def test_rows_without_a_reverified_half_period_locate_their_roots(two_modes):
    """The isolation witness dropped (the half-period then fails): each row's moduli and flag are still
    re-verified at a root located inside its own theta."""
    d = copy.deepcopy(two_modes)
    d["witnesses"].pop("half_period")
    ok, msg = _items(_foreign(d))["extra.roots"]
    assert ok and "kinds are not" in msg
    _unstable_row(d).update(stable=True)
    assert _items(_foreign(d))["extra.roots"][0] is False


# ---------------------------------------------------------------- 3. dimension 1

N1 = dict(M=[["-1"]], e=["1"], c=["1"], S="-1", h="1/2")


def test_a_one_state_plant_with_an_orbit_is_stable_and_checked():
    """x' = -x - sign(x) with hysteresis 1/2: the orbit runs between x = 1/2 and -1/2, theta = ln 3; the
    section is a point, no multipliers, stable (a nearby solution reaches the switching point)."""
    cert = _cert(_scene(**N1))
    st = {c["id"]: c["status"] for c in cert["claims"]}
    assert set(st.values()) == {"proved"}, cert["claims"]
    row = cert["extra"]["roots"][0]
    assert row["kind"] == "genuine" and row["moduli"] == [] and row["stable"] is True
    lo, hi = (float(x) for x in row["theta"])
    assert lo <= 1.0986122886681098 <= hi
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]
    bad = _foreign(cert, lambda d: d["extra"]["roots"][0].update(stable=None))
    assert _items(bad)["extra.roots"][0] is False


def test_a_one_state_plant_on_the_command_line_exits_0(tmp_path):
    f = tmp_path / "n1.toml"
    f.write_text('name = "n1"\nkind = "periodic_orbit"\n[parameters]\n[plant]\nM = [["1"]]\ne = ["1"]\nc = ["1"]\nS = "-1"\n'
                 'h = "1/2"\n')
    r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", str(f), "-o", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


# ---------------------------------------------------------------- 4. entries beyond the double range

@pytest.mark.parametrize("M,e", [
    ([["-1e400", "0"], ["1", "-1"]], ["1e400", "0"]),
    ([["-1e-400", "0"], ["1", "-1"]], ["1", "0"]),
    ([["-(1e400)^8", "0"], ["1", "-1"]], ["1", "0"]),
    ([["0", "1", "0"], ["0", "0", "1"], ["-6e-400", "-11e-400", "-6e-400"]], ["0", "0", "6e-400"]),
], ids=["1e400", "1e-400", "1e3200", "all_tiny"])
def test_entries_beyond_the_double_range_do_not_crash(M, e):
    """Float conversions overflowed (int(inf)) or underflowed (1/0.0) in the tail point, the start of the
    search and the balancing: the choices are now exact rationals; the plant proves or stays inconclusive."""
    c = ["0", "1"] if len(M) == 2 else ["1", "0", "0"]
    cert = _cert_at(_scene(M, e, c, S="-1", h="1/10" if len(M) == 2 else "0"), 64)
    assert {c["status"] for c in cert["claims"]} <= {"proved", "inconclusive"}
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def _cert_at(scene, maxprec):
    return json.loads(json.dumps(prove_scene(scene, maxprec=maxprec).to_json()))


def test_balancing_beyond_the_double_range_is_the_identity():
    from rigor_gyro.kinds.periodic_orbit.dispatch import validate
    from rigor_gyro.kinds.periodic_orbit.plant_orbit import balancing
    m = validate(_scene([["-1e400", "1e-400"], ["1e400", "-1"]], ["1", "0"], ["0", "1"], S="-1"))
    assert balancing(m) == [0, 0]


# ---------------------------------------------------------------- 5. an integrator the relay does not excite

U0 = dict(M=[["0", "0", "0", "0"], ["0", "0", "1", "0"], ["0", "0", "0", "1"], ["0", "-6", "-11", "-6"]],
          e=["0", "0", "0", "1"], c=["1", "1", "0", "0"], S="-1")


def test_an_uncontrollable_integrator_is_checked_and_its_minus_one_multiplier_stops_escalation():
    """r0 = N_c(0)/p'(0) = 0 exactly: the checker takes it from the model (its eigenvectors gave a ball around
    0 and the tail bound failed); the state x1 is never reached (x0_1 = 0 exactly). Every orbit has the
    multiplier -1 exactly: stable is inconclusive at once (128 bits), never refuted."""
    cert = _cert(_scene(**U0))
    st = {c["id"]: c for c in cert["claims"]}
    assert st["half_period"]["status"] == "proved" and st["multipliers"]["status"] == "proved"
    assert st["stable"]["status"] == "inconclusive" and "exactly -1" in st["stable"]["reason"]
    assert cert["precision_bits"] <= 128
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_an_excited_integrator_has_no_neutral_multiplier():
    from rigor_gyro.kinds.periodic_orbit.dispatch import validate
    from rigor_gyro.kinds.periodic_orbit.plant_orbit import neutral_multiplier
    assert neutral_multiplier(validate(_scene(**U0)))
    assert not neutral_multiplier(validate(_scene(**{**U0, "e": ["1", "0", "0", "1"]})))
    assert not neutral_multiplier(validate(_scene([["0", "1"], ["0", "-1"]], ["0", "1"], ["1", "0"], S="-1")))
    # G(s) = s/((s+1)(s+2)): N_c(0) = 0 without a zero eigenvalue
    assert not neutral_multiplier(validate(_scene([["0", "1"], ["-2", "-3"]], ["0", "1"], ["0", "1"], S="-1")))


# ---------------------------------------------------------------- 6. margins of a plant's own parameters

def test_a_plant_parameter_has_a_threshold_for_orbit_genuine(tmp_path):
    """K a pole location in 1/((s+1)(s+2)(s+K)), h = 0.1: the paper's table of claims independent of
    Roitenberg's parameters (K among them) no longer applies to a [plant] scene."""
    from rigor_gyro.margins.threshold import find_threshold
    sc = _scene([["-1", "1", "0"], ["0", "-2", "1"], ["0", "0", "-K"]], ["0", "0", "1"], ["1", "0", "0"], S="-1",
                h="1/10", params={"K": "3"})
    th = find_threshold(sc, "K", lo="3", hi="1000", claim="orbit_genuine", width="1e-2")
    assert th.certified and th.proved_at < 5 < th.refuted_at, th.lines()


# ---------------------------------------------------------------- 7. messages

def _refusal(scene):
    from rigor_gyro.core.errors import ParameterError
    from rigor_gyro.kinds.periodic_orbit.dispatch import validate
    with pytest.raises(ParameterError) as e:
        validate(scene)
    return str(e.value)


def test_an_empty_plant_table_is_named(tmp_path):
    f = tmp_path / "empty.toml"
    f.write_text('name = "e"\nkind = "periodic_orbit"\nsource = "x"\n[parameters]\n[plant]\n')
    r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", str(f), "-o", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "the [plant] table is empty: give M, e and c" in r.stderr, r.stderr
    msg = _refusal(parse_scene('name = "e"\nkind = "periodic_orbit"\n[parameters]\n[plant]\n'))
    assert "missing parameter" in msg and "[plant] table with M, e and c" in msg


def test_a_plant_without_feedback_or_with_g_identically_minus_h_says_what_holds():
    assert "G(s) = c (sI - M)^-1 e = 0 identically" in _refusal(
        _scene([["-1", "0"], ["0", "-2"]], ["1", "0"], ["0", "1"], S="-1"))
    odd = dict(M=[["0", "1"], ["1", "-0"]], e=["0", "1"], c=["1", "0"], S="-1")     # G = 1/(s^2 - 1)
    assert "every theta > 0: a continuum" in _refusal(_scene(**odd, h="0"))
    assert "has no root: no symmetric orbit" in _refusal(_scene(**odd, h="1/10"))


def test_an_option_is_called_an_option():
    msg = _refusal(_scene([["-1"]], ["1"], ["1"], extra='[options]\ntheta_width = "abc"'))
    assert msg.startswith("option 'theta_width'"), msg


def test_no_orbit_refutes_stable_only_for_the_orbits_searched():
    """No genuine orbit (the relay's amplitude below the hysteresis): stable is refuted for symmetric orbits
    with two switchings per period, and says that other self-oscillations are not excluded."""
    cert = _cert(_scene([["-1", "1", "0"], ["0", "-2", "1"], ["0", "0", "-50"]], ["0", "0", "1"], ["1", "0", "0"],
                        S="-1", h="1/10"))
    st = {c["id"]: c for c in cert["claims"]}
    assert st["stable"]["status"] == "refuted", st["stable"]
    assert "not excluded" in st["stable"]["reason"] and "self-oscillation" in st["stable"]["reason"]


# ---------------------------------------------------------------- 2. stiff plants: a multiplier exp(-2.65e8)

def test_a_time_constant_ratio_of_1e9_proves_and_checks_in_seconds():
    """T3 = 1e-9 s in the stiff example: the fast multiplier exp(-2.65e8) was formatted exactly (10^e with
    1e8 digits: a hang); it prints from its exponent, beyond 10^-999999 as the bound [0, 1e-999999]."""
    import time
    text = open(PLANTS + "relay_stiff_1e6.toml").read().replace('T3 = "1e-6"', 'T3 = "1e-9"')
    t = time.perf_counter()
    cert = _cert(parse_scene(text))
    assert time.perf_counter() - t < 20
    assert cert["verdict"] == "proved"
    q = cert["quantities"]["multiplier_modulus_2"]
    assert (q["lo"], q["hi"]) == ("0", "1e-999999")
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]
    bad = copy.deepcopy(cert)
    bad["quantities"]["multiplier_modulus_2"].update(lo="1e-999999", hi="1e-999998")
    assert _items(_foreign(bad))["quantities"][0] is False


@pytest.mark.parametrize("k", [300, 5000, 20000, 200000])
def test_far_formatting_is_outward_and_agrees_with_the_exact_path(monkeypatch, k):
    """With the far threshold lowered, the far path's bounds contain the exact endpoints (and their exact
    rounding) and differ from it at most in the last digit."""
    from fractions import Fraction
    from flint import arb
    import rigor_gyro.core.balls as balls
    from rigor_gyro.core.balls import decimal_bounds, exact_endpoints, quantity, working_precision
    with working_precision(128):
        for x in (arb(-k).exp() * arb("1.234"), -arb(k).exp() / 7, arb(k).exp() * arb("3.5", "1e-20")):
            exact = decimal_bounds(x, 12)
            monkeypatch.setattr(balls, "FAR_EXPONENT", 100)
            far = decimal_bounds(x, 12)
            q = quantity(x)
            monkeypatch.setattr(balls, "FAR_EXPONENT", 2 ** 20)
            a, b = exact_endpoints(x)
            assert Fraction(far[0]) <= a and b <= Fraction(far[1]), (exact, far)
            assert Fraction(far[0]) <= Fraction(exact[0]) and Fraction(exact[1]) <= Fraction(far[1])
            assert far[0][:10] == exact[0][:10] or abs(Fraction(far[0]) - Fraction(exact[0])) <= abs(a) / 10 ** 10
            assert Fraction(q["lo"]) <= a and b <= Fraction(q["hi"])


def test_beyond_the_stored_exponent_the_bounds_are_zero_and_a_power_of_ten():
    from flint import arb
    from rigor_gyro.core.balls import decimal_bounds, working_precision
    with working_precision(128):
        x = arb(-3 * 10 ** 6).exp()
        assert decimal_bounds(x, 12) == ("0", "1e-999999")
        assert decimal_bounds(-x, 12) == ("-1e-999999", "0")
        assert decimal_bounds(1 / x, 12) == ("1e+999999", "+inf")


def test_a_far_multiplier_cut_by_its_stored_interval_is_refused():
    """T3 = 2e-7: the fast multiplier is about 1.36e-575867, far (its exact ends have 1.9e6 bits) but within
    the stored format: the checker compares it as a ball; a stored interval ending at a far ball's midpoint
    (meeting the ball, not enclosing it) is refused."""
    text = open(PLANTS + "relay_stiff_1e6.toml").read().replace('T3 = "1e-6"', 'T3 = "2e-7"')
    cert = _cert(parse_scene(text))
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]
    q = cert["quantities"]["multiplier_modulus_2"]
    assert q["hi"].endswith("e-575867")
    from flint import arb
    from rigor_gyro.core.balls import is_far, quantity, working_precision
    from rigor_gyro.core.stored import interval
    from rigor_gyro.kinds.periodic_orbit.plant_check_rows import encloses
    with working_precision(128):
        x = arb(-1400000).exp() * arb("1.25", "1e-30")
        assert is_far(x)
        st = quantity(x)
        assert encloses(interval(st), x)
        assert not encloses(interval({"lo": st["lo"], "hi": st["mid"]}), x)
        assert not encloses(interval({"lo": st["mid"], "hi": st["hi"]}), x)
