"""Relay plants written in the scene ([plant]; issue 42 part 1): the general path of kind periodic_orbit.

Roitenberg's stabiliser as its (2) in this form gives the specialised path's verdicts and enclosures; the
example scenes prove and the checker confirms them; every decision function is cross-checked against
mpmath or a float simulation (never the other way round); bad models are exit 2 naming the entry; the
checker refuses tampered certificates.
"""
from __future__ import annotations

import copy
import json
import subprocess
import sys
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from flint import arb, fmpq

from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.periodic_orbit import approx
from rigor_gyro.kinds.periodic_orbit.dispatch import validate
from rigor_gyro.kinds.periodic_orbit.plant_claims import tail_point, theta_min
from rigor_gyro.kinds.periodic_orbit.plant_model import markov
from rigor_gyro.kinds.periodic_orbit.plant_orbit import (PlantSpectrum, _norms, g_coeffs, liouville_product,
                                                         near_zero_bound, near_zero_order, tail_bound, x0_at)
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene, parse_scene

PLANTS = "rigor_gyro/scenes/plants/"


def _scene(M, e, c, S="1", h="0", params=None, extra=""):
    rows = ", ".join("[" + ", ".join(f'"{x}"' for x in r) + "]" for r in M)
    vec = lambda v: "[" + ", ".join(f'"{x}"' for x in v) + "]"        # noqa: E731
    ps = "\n".join(f'{k} = "{v}"' for k, v in (params or {}).items())
    return parse_scene(f'name = "t"\nkind = "periodic_orbit"\n[parameters]\n{ps}\n{extra}\n[plant]\nM = [{rows}]\n'
                       f'e = {vec(e)}\nc = {vec(c)}\nS = "{S}"\nh = "{h}"\n')


#: small plants covering the spectral cases: an integrator, a complex pair, an unstable real mode,
#: relative degree 1, hysteresis
CASES = {
    "integrator": (([0, 1, 0], [0, 0, 1], [0, -2, -3]), (0, 0, 1), (1, 0, 0), "-1", "0"),
    "pair_and_lag": (([0, 1, 0], [0, 0, 1], ["-2", "-3/2", "-3/2"]), (0, 0, 1), (1, 0, 0), "-1", "0"),
    "unstable_mode": (([1, 0, 0], [0, -2, 1], [0, 0, -5]), (1, 1, 1), (1, -1, "1/2"), "-1", "0"),
    "hysteresis_integrator": (([0, 1], [0, -1]), (0, 1), (1, 0), "-1", "1/10"),
    "relative_degree_one": (([-1, 0, 0], [0, -3, 1], [0, -1, -3]), (1, 0, 1), (1, 1, 0), "-1", "1/20"),
    # a tiny direct term c . e = -1e-4: g = -S (-1e-4 theta/2 + 0.2 theta^3/24 + ...) has a root near theta = 0.077
    "small_lead": (([0, 1], [-1, "-1/5"]), (0, 1), (1, "-1/10000"), "-1", "0"),
}


def _lags(n: int):
    """n first-order lags in series with time constants 1, 1/2, ..., 1/n (a 10-state plant for n = 10)."""
    M = [[0] * n for _ in range(n)]
    for i in range(n):
        M[i][i] = -(i + 1)
        if i + 1 < n:
            M[i][i + 1] = i + 1
    return tuple(M), tuple([0] * (n - 1) + [n]), tuple([1] + [0] * (n - 1)), "-1", "0"


#: dimension 10: two genuine orbits, the checker's monotone pieces next to a root
CASES["ten_lags"] = _lags(10)


def _model(name):
    M, e, c, S, h = CASES[name]
    return validate(_scene(M, e, c, S, h))


def _mp(q: fmpq):
    return mpmath.mpf(int(q.p)) / int(q.q)


@pytest.fixture(scope="module")
def pair():
    a = prove_scene(load_scene("roitenberg1947")).to_json()
    b = prove_scene(load_scene("roitenberg1947_plant")).to_json()
    return a, b


def _iv(q):
    return Fraction(q["lo"]), Fraction(q["hi"])


def _overlap(p, q):
    (a, b), (c, d) = _iv(p), _iv(q)
    return a <= d and c <= b


def test_roitenberg_written_as_a_plant_gives_the_same_certificate(pair):
    """Claim by claim: the same ids and verdicts, the same roots and kinds, overlapping theta*, period, x(0)
    and multipliers."""
    a, b = pair
    assert [(c["id"], c["status"]) for c in a["claims"]] == [(c["id"], c["status"]) for c in b["claims"]]
    assert all(c["status"] == "proved" for c in b["claims"])
    qa, qb = a["quantities"], b["quantities"]
    for k in ["theta_star", "period", "stability_margin"] + [f"multiplier_modulus_{j}" for j in range(1, 5)] + \
            [f"multiplier_{j}_{p}" for j in range(1, 5) for p in ("re", "im")]:
        assert _overlap(qa[k], qb[k]), k
    for i, k in enumerate(("beta_dot_0", "Omega_0", "i_0", "I_0"), start=2):
        assert _overlap(qa[k], qb[f"x0_{i}"]), k
    ra, rb = a["extra"]["roots"], b["extra"]["roots"]
    assert [r["kind"] for r in ra] == [r["kind"] for r in rb] and len(ra) == 6
    for x, y in zip(ra, rb):
        assert Fraction(x["theta"][0]) <= Fraction(y["theta"][1]) and Fraction(y["theta"][0]) <= Fraction(x["theta"][1])


def test_the_plant_certificate_is_confirmed_by_the_checker(pair):
    rep = check_certificate(json.loads(json.dumps(pair[1])))
    assert rep.ok, [r for r in rep.results if not r.ok]


@pytest.mark.parametrize("name,genuine,stable", [("relay_autotune_integrator", 1, [True]),
                                                 ("relay_stiff_1e6", 1, [True]),
                                                 ("relay_two_modes", 3, [True, False, True])])
def test_example_scenes_prove_and_are_confirmed(name, genuine, stable):
    cert = json.loads(json.dumps(prove_scene(load_scene(PLANTS + name + ".toml")).to_json()))
    assert cert["verdict"] == "proved"
    roots = [r for r in cert["extra"]["roots"] if r["kind"] == "genuine"]
    assert len(roots) == genuine and [r["stable"] for r in roots] == stable
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_the_describing_function_estimate_beside_the_orbit():
    """The integrator plant 1/(s(s+1)(s+2)): the estimate is w = sqrt(2), A = 4/(6 pi) exactly; the certified
    orbit is longer (period 4.5511 against 4.4429) and the difference is enclosed."""
    q = prove_scene(load_scene(PLANTS + "relay_autotune_integrator.toml")).to_json()["quantities"]
    eps = Fraction(1, 10 ** 14)
    lo, hi = _iv(q["df_period"])
    assert lo - eps <= Fraction(2 * np.pi / np.sqrt(2)) <= hi + eps
    lo, hi = _iv(q["df_amplitude"])
    assert lo - eps <= Fraction(4 / (6 * np.pi)) <= hi + eps
    d_lo, d_hi = _iv(q["df_period_difference"])
    assert Fraction("0.108") < d_lo <= d_hi < Fraction("0.109")
    p_lo, _ = _iv(q["period"])
    assert abs(float(p_lo) - 4.551071026) < 1e-8


@pytest.mark.parametrize("name", ["relay_autotune_integrator", pytest.param("relay_stiff_1e6", marks=pytest.mark.slow),
                                  "relay_two_modes"])
def test_float_simulation_agrees_with_each_certified_orbit(name):
    """From the certified x(0), an event-driven simulation switches at theta* and lands on -x(0); the
    central-difference Jacobian has the certified multiplier moduli."""
    cert = prove_scene(load_scene(PLANTS + name + ".toml")).to_json()
    m = validate(load_scene(PLANTS + name + ".toml"))
    q = cert["quantities"]
    th = float(q["theta_star"]["mid"])
    x0 = np.array([float(q[f"x0_{i}"]["mid"]) for i in range(1, m.n + 1)])
    t, x = approx.plant_simulate_half(m, x0, 1.5 * th, steps=6000)
    assert abs(t - th) < 1e-9 * max(1, th) and np.max(np.abs(x + x0)) < 1e-9
    M_, e_, c_, S_, h_ = approx.plant_as_float(m)
    y = lambda t: c_ @ approx._plant_flow(M_, e_, S_, x0, t)       # noqa: E731
    ts = [th * k / 2000 for k in range(2001)]
    k = int(np.argmax([y(t) for t in ts]))
    from scipy.optimize import minimize_scalar
    best = -minimize_scalar(lambda t: -y(t), bounds=(ts[max(k - 1, 0)], ts[min(k + 1, 2000)]), method="bounded",
                            options={"xatol": 1e-12}).fun
    lo, hi = _iv(q["amplitude"])                      # the amplitude: max of |c . x| over the period
    assert float(lo) - 1e-12 <= best <= float(hi) + 1e-12
    J = approx.plant_jacobian_fd(m, x0, th, eps=1e-6)
    fd = sorted(np.abs(np.linalg.eigvals(J)))[::-1]
    cm = [float(q[f"multiplier_modulus_{j}"]["mid"]) for j in range(1, m.n)]
    assert np.allclose(fd, cm, atol=1e-5)
    for w, A, P in approx.plant_describing_function(m)[:1]:
        if "df_period" in q:
            assert _iv(q["df_period"])[0] - Fraction(1, 10 ** 6) <= Fraction(P) <= _iv(q["df_period"])[1] + Fraction(1, 10 ** 6)


@pytest.mark.slow
def test_two_modes_orbits_attract_and_repel_in_simulation():
    """The middle orbit of relay_two_modes is unstable (a multiplier > 1): a start nudged off it drifts
    away, while the certified stable orbits keep their half-period."""
    m = validate(load_scene(PLANTS + "relay_two_modes.toml"))
    cert = prove_scene(load_scene(PLANTS + "relay_two_modes.toml")).to_json()
    q = cert["quantities"]
    th = float(q["theta_star"]["mid"])
    x0 = np.array([float(q[f"x0_{i}"]["mid"]) for i in range(1, 5)])
    times = approx.plant_long_run(m, x0 * (1 + 1e-5), 300, 3 * th, steps=600)
    assert abs(times[-1] - th) < 1e-7 < abs(times[0] - th)
    th2 = q["theta_star_2"]["mid"]
    with working_precision(96):
        x2 = [float(v.mid()) for v in x0_at(PlantSpectrum(m), arb(th2))]
    times = approx.plant_long_run(m, np.array(x2) * (1 + 1e-7), 300, 3 * float(th2), steps=600)
    assert abs(times[0] - float(th2)) < 1e-6 and abs(times[-1] - float(th2)) > 1e-3


@pytest.mark.parametrize("name", sorted(CASES))
def test_g_and_x0_enclose_mpmath(name):
    """g (plain and pole-free times K), x0 at sampled theta contain mpmath's expm-based values."""
    m = _model(name)
    with working_precision(96):
        sp = PlantSpectrum(m)
        for th in ("0.05", "0.3", "1.1", "2.7", "6.5"):
            t = arb(th)
            g = g_coeffs(sp, t, 1, pole_free=False)[0]
            ref = approx.plant_g_mp(m, th, dps=40)
            assert g.contains(arb(mpmath.nstr(ref, 35))) or abs(float(g.mid()) - float(ref)) < float(g.rad()) + 1e-25
            x = x0_at(sp, t)
            xr = approx.plant_x0_mp(m, th, dps=40)
            for i in range(m.n):
                assert abs(float(x[i].mid()) - float(xr[i])) <= float(x[i].rad()) + 1e-25


@pytest.mark.parametrize("name", sorted(CASES) + ["roitenberg"])
def test_near_zero_bound_is_sound_and_can_fail(name):
    """Where the bound certifies (0, rho] root-free, g sampled in mpmath has no sign change there (h = 0: the
    leading coefficient's sign; h > 0: g < 0); at rho = 10 it cannot certify (a test that could fail).
    Roitenberg's plant has a root of g at 0.1056 < 1/2: a bound too generous would certify past it."""
    m = validate(load_scene("roitenberg1947_plant")) if name == "roitenberg" else _model(name)
    rho = theta_min(m, Fraction(1, 2))
    assert rho is not None
    sign = -1 if m.h > 0 else (1 if near_zero_order(m)[1] > 0 else -1)
    for k in range(1, 21):
        t = mpmath.mpf(rho.numerator) / rho.denominator * k / 20
        assert sign * approx.plant_g_mp(m, t, dps=50) > 0
    with working_precision(64):
        assert not near_zero_bound(m, arb(10))


@pytest.mark.parametrize("name", sorted(CASES))
def test_tail_bound_is_sound(name):
    """Beyond the certified tail point, g sampled in mpmath keeps the tail's sign, inside [lower, upper] at T."""
    m = _model(name)
    with working_precision(96):
        sp = PlantSpectrum(m)
        T = tail_point(sp, m)
        assert T is not None
        lo, hi = tail_bound(sp, arb(fmpq(T.numerator, T.denominator)))
        gT = approx.plant_g_mp(m, mpmath.mpf(T.numerator) / T.denominator)
        assert float(lo.lower()) <= gT <= float(hi.upper())
        sgn = 1 if float(lo.lower()) > 0 else -1
        for f in (1, 1.5, 2, 4, 10):
            assert sgn * approx.plant_g_mp(m, mpmath.mpf(T.numerator) / T.denominator * f) > 0


@pytest.mark.parametrize("name", sorted(CASES) + ["roitenberg"])
def test_markov_parameters_obey_the_norm_bound(name):
    m = validate(load_scene("roitenberg1947_plant")) if name == "roitenberg" else _model(name)
    L, C = _norms(m)
    for k, v in enumerate(markov(m.M, m.e, m.c, 40)):
        assert abs(v) <= C * L ** k


def test_liouville_product_matches_the_float_jacobian():
    m = _model("relative_degree_one")
    cert = prove_scene(_scene(*CASES["relative_degree_one"])).to_json()
    q = cert["quantities"]
    th = float(q["theta_star"]["mid"])
    x0 = np.array([float(q[f"x0_{i}"]["mid"]) for i in range(1, 4)])
    J = approx.plant_jacobian_fd(m, x0, th, eps=1e-6)
    with working_precision(96):
        sp = PlantSpectrum(m)
        lp = liouville_product(sp, arb(q["theta_star"]["mid"]), [arb(q[f"x0_{i}"]["mid"]) for i in range(1, 4)])
    assert abs(np.linalg.det(J) - float(lp.mid())) < 1e-6


@pytest.mark.parametrize("name", sorted(CASES))
def test_small_plants_prove_to_a_verdict_the_checker_confirms(name):
    cert = json.loads(json.dumps(prove_scene(_scene(*CASES[name])).to_json()))
    assert all(c["status"] != "inconclusive" for c in cert["claims"]), cert["claims"]
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


# ---------------------------------------------------------------------------- bad models (exit 2)

BAD = [
    ({"M": "[['0', '1'], ['-a', '-x']]"}, {"a": "2"}, r"\[plant\] M\[2\]\[2\].*'x'"),
    ({"M": "[['0', '1'], ['-1']]"}, {}, r"\[plant\] M\[2\]: has 1 entries"),
    ({"e": "['0', '1', '2']"}, {}, r"\[plant\] e: has 3 entries"),
    ({"c": "['0', '0']"}, {}, r"\[plant\] c: c = 0"),
    ({"S": "'0'"}, {}, r"\[plant\] S"),
    ({"h": "'-1/10'"}, {}, r"\[plant\] h"),
    ({"M": "[['0', '1'], ['-1/(a-a)', '-1']]"}, {"a": "1"}, r"\[plant\] M\[2\]\[1\].*divides by zero"),
    ({"M": "[['-1', '0'], ['0', '-1']]"}, {}, r"repeated eigenvalue"),
    ({"M": "[['0', '1'], ['-4', '0']]"}, {}, r"imaginary axis"),
    ({"M": "[['0', '1'], ['0', '0']]"}, {}, r"repeated eigenvalue"),
    ({"M": "[['0']]", "e": "['1']", "c": "['1']"}, {}, r"lone integrator.*give the plant a lag"),
    ({"x": "'1'"}, {}, r"\[plant\] x: unknown key"),
    ({}, {"zz": "1"}, r"parameter 'zz': not used"),
    ({"c": "['0', '1']", "e": "['1', '0']", "M": "[['-1', '0'], ['0', '-2']]"}, {}, r"Markov"),
]


@pytest.mark.parametrize("edit,params,match", BAD)
def test_bad_models_name_the_entry(edit, params, match):
    table = {"M": "[['0', '1'], ['-2', '-3']]", "e": "['0', '1']", "c": "['1', '0']", "S": "'-1'"}
    table.update(edit)
    body = "\n".join(f"{k} = {v}" for k, v in table.items())
    ps = "\n".join(f'{k} = "{v}"' for k, v in params.items())
    with pytest.raises(ParameterError, match=match):
        validate(parse_scene(f'name = "b"\nkind = "periodic_orbit"\n[parameters]\n{ps}\n[plant]\n{body}\n'))


def test_a_too_large_plant_and_unknown_options_are_refused():
    n = 13
    M = [["-1" if i == j else "0" for j in range(n)] for i in range(n)]
    with pytest.raises(ParameterError, match="dimension 13"):
        validate(_scene(M, ["1"] * n, ["1"] * n))
    with pytest.raises(ParameterError, match="orbit"):
        validate(_scene(*CASES["integrator"], extra='[options]\norbit = "2"'))


def test_cli_exits_2_on_a_bad_model(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('name = "bad"\nkind = "periodic_orbit"\n[parameters]\na = "2"\n[plant]\n'
                 'M = [["0", "1"], ["-a", "-x"]]\ne = ["0", "1"]\nc = ["1", "0"]\n')
    r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", str(p), "-o", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "M[2][2]" in r.stderr


# ---------------------------------------------------------------------------- the checker refuses tampering

@pytest.fixture(scope="module")
def integrator_cert():
    return json.loads(json.dumps(prove_scene(load_scene(PLANTS + "relay_autotune_integrator.toml")).to_json()))


def _items(cert):
    return {r.item: r.ok for r in check_certificate(cert).results}


def _shift(q, by):
    lo, hi = _iv(q)
    return {**q, "lo": str(lo + by), "hi": str(hi + by)}


def test_checker_refuses_a_moved_theta_star(integrator_cert):
    c = copy.deepcopy(integrator_cert)
    c["quantities"]["theta_star"] = _shift(c["quantities"]["theta_star"], Fraction(1, 1000))
    it = _items(c)
    assert it["orbit_genuine"] is False


def test_checker_refuses_a_moved_multiplier_and_amplitude(integrator_cert):
    c = copy.deepcopy(integrator_cert)
    c["quantities"]["multiplier_modulus_1"] = _shift(c["quantities"]["multiplier_modulus_1"], Fraction(1, 10 ** 6))
    c["quantities"]["amplitude"] = _shift(c["quantities"]["amplitude"], Fraction(1, 10 ** 6))
    assert _items(c)["quantities"] is False


def test_checker_refuses_a_root_dropped_from_the_pieces(integrator_cert):
    c = copy.deepcopy(integrator_cert)
    pcs = c["witnesses"]["half_period"]["pieces"]
    for pc in pcs:
        if pc["kind"] == "unique":
            pc["kind"] = "empty"
    c["witnesses"]["half_period"]["roots"] = []
    assert _items(c)["half_period"] is False


def test_checker_refuses_a_tail_point_too_early(integrator_cert):
    """The search cut before the root, the root dropped: only the tail bound can notice."""
    c = copy.deepcopy(integrator_cert)
    w = c["witnesses"]["half_period"]
    first = next(i for i, pc in enumerate(w["pieces"]) if pc["kind"] == "unique")
    assert first >= 1
    w["pieces"] = w["pieces"][:first]
    w["T"] = w["pieces"][-1]["hi"]
    w["roots"] = []
    assert all(pc["kind"] == "empty" for pc in w["pieces"])
    it = _items(c)
    assert it["half_period"] is False


def test_checker_refuses_a_genuine_root_called_spurious(integrator_cert):
    """A made-up witness t (c . x(t) > 0 there in truth) does not make the orbit spurious."""
    c = copy.deepcopy(integrator_cert)
    w = c["witnesses"]["half_period"]
    theta = Fraction(c["quantities"]["theta_star"]["lo"])
    w["roots"] = [{"kind": "spurious", "witness_t": str(theta / 2)}]
    assert _items(c)["half_period"] is False


def test_checker_refuses_a_spurious_root_called_genuine():
    cert = json.loads(json.dumps(prove_scene(load_scene("roitenberg1947_plant")).to_json()))
    w = cert["witnesses"]["half_period"]
    k = next(i for i, r in enumerate(w["roots"]) if r["kind"] == "spurious")
    g = next(r for r in w["roots"] if r["kind"] == "genuine")
    w["roots"][k] = dict(g)
    assert _items(cert)["half_period"] is False


def test_a_plant_whose_g_tends_to_zero_needs_t_max():
    """c . x a derivative of the output (G(0) = 0, no integrator, stable): g -> 0 at infinity, no tail bound at
    any precision: inconclusive at once (no escalation), and with T_max the searched range is stated and
    nothing is refuted."""
    M = ([0, 1, 0], [0, 0, 1], [-6, -11, -6])
    cert = prove_scene(_scene(M, (0, 0, 1), (0, 1, 1), "-1")).to_json()
    assert all(c["status"] == "inconclusive" for c in cert["claims"]) and cert["precision_bits"] == 64
    assert "T_max" in cert["claims"][0]["reason"]
    cert = json.loads(json.dumps(prove_scene(_scene(M, (0, 0, 1), (0, 1, 1), "-1",
                                                    extra='[options]\nT_max = "20"')).to_json()))
    assert cert["claims"][0]["status"] == "proved" and "T_max" in cert["claims"][0]["reason"]
    assert all(c["status"] == "inconclusive" for c in cert["claims"][1:])
    assert check_certificate(cert).ok


def test_a_plant_scene_draws_its_orbit():
    pytest.importorskip("matplotlib")
    from rigor_gyro.kinds.periodic_orbit.plots import build_figures
    scene = load_scene(PLANTS + "relay_autotune_integrator.toml")
    figs = build_figures(scene, prove_scene(scene))
    (name, fig), = figs.items()
    line = [ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid() == "orbit"][0]
    ys = line.get_ydata()
    assert name == "relay_autotune_integrator_orbit.png" and abs(max(ys) - 0.2200370) < 1e-4 and abs(ys[0]) < 1e-12


def test_a_plant_scene_with_a_tolerance_is_paved(tmp_path):
    """A [plant] scene takes tolerance boxes (kinds/periodic_orbit/plant_box.py): K only scales e, so orbit_genuine
    holds on the whole box; the sub-boxes' naive forms leave stable undecided (never refuted)."""
    p = tmp_path / "box.toml"
    p.write_text('name = "box"\nkind = "periodic_orbit"\n[parameters]\nK = "[0.9, 1.1]"\n[plant]\n'
                 'M = [["0", "1", "0"], ["0", "0", "1"], ["0", "-2", "-3"]]\ne = ["0", "0", "K"]\nc = ["1", "0", "0"]\n'
                 'S = "-1"\n[claims]\nonly = ["orbit_genuine"]\n')
    r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", str(p), "-o", str(tmp_path), "-j", "1"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "orbit_genuine: proved over the box" in r.stdout


# ---------------------------------------------------------------------------- random plants against a simulation

from hypothesis import given, settings, strategies as st  # noqa: E402


@settings(max_examples=16)
@given(st.lists(st.integers(min_value=1, max_value=40), min_size=3, max_size=3, unique=True),
       st.one_of(st.none(), st.integers(min_value=-3, max_value=3)), st.booleans())
def test_random_third_order_plants_agree_with_a_simulation(poles, zero, integrator):
    """G(s) = 1 or (s + z), over (s + p1/4)(s + p2/4)(s + p3/4) (one pole at 0 when ``integrator``), u = -sign(y):
    every orbit the prover calls genuine is one in an event-driven float simulation (it switches at theta* and
    lands on -x(0)), and every spurious root's orbit switches early in the simulation (or dips below 0 at once)."""
    lam = [Fraction(0)] + [Fraction(p, 4) for p in poles[1:]] if integrator else [Fraction(p, 4) for p in poles]
    a2 = sum(lam)
    a1 = lam[0] * lam[1] + lam[0] * lam[2] + lam[1] * lam[2]
    a0 = lam[0] * lam[1] * lam[2]
    M = ((0, 1, 0), (0, 0, 1), (str(-a0), str(-a1), str(-a2)))
    if zero is None:
        c = (1, 0, 0)               # relative degree 3: genuine orbits are common
    else:
        z = Fraction(zero) if zero or a0 else Fraction(1)    # not s / (s ...): a cancelled integrator
        c = (str(z), 1, 0)          # relative degree 2: mostly refuted (no orbit), spurious roots
    cert = prove_scene(_scene(M, (0, 0, 1), c, "-1"), maxprec=512).to_json()
    m = validate(_scene(M, (0, 0, 1), c, "-1"))
    roots = (cert.get("extra") or {}).get("roots", [])
    with working_precision(128):
        sp = PlantSpectrum(m)
        for r in roots:
            th = (Fraction(r["theta"][0]) + Fraction(r["theta"][1])) / 2
            x0 = np.array([float(v.mid()) for v in x0_at(sp, arb(fmpq(th.numerator, th.denominator)))])
            t, x = approx.plant_simulate_half(m, x0, 1.2 * float(th), steps=3000)
            if r["kind"] == "genuine":
                assert t is not None and abs(t - float(th)) < 1e-7 * max(1, float(th)), (r, t)
                assert np.max(np.abs(x + x0)) < 1e-7 * max(1, np.max(np.abs(x0)))
            elif r["kind"] == "spurious":      # it switches before theta*, or c . x goes below 0 at once
                early = t is not None and t < float(th) * (1 - 1e-9)
                M_, e_, c_, S_, h_ = approx.plant_as_float(m)
                dip = approx._plant_flow(M_, e_, S_, x0, float(th) * 1e-3) @ c_ < 0
                assert early or dip, (r, t)


def test_the_imaginary_axis_test_is_exact():
    """(s^2 + 4)(s + 1) is refused (eigenvalues +-2i), (s^2 + 1e-20 s + 1) accepted (off the axis by 5e-21)."""
    with pytest.raises(ParameterError, match="imaginary axis"):
        validate(_scene(([0, 1, 0], [0, 0, 1], [-4, -4, -1]), (0, 0, 1), (1, 0, 0), "-1"))
    m = validate(_scene(([0, 1], [-1, "-1/10^20"]), (0, 1), (1, 0), "-1"))
    assert m.n == 2 and not m.zero_eigenvalue


# ------------------------------------------------------------------- stable by Gershgorin's discs

def test_clustered_multipliers_stable_by_gershgorin_discs_and_confirmed():
    """The integrator plant at h = 1e6: theta* ~ 4e6, the two multipliers ~e^(-4e6) and e^(-8e6) are not isolated
    at any precision tried, yet Gershgorin's discs of the Jacobian bound both far below 1: ``stable`` is proved
    (the multipliers stay inconclusive), the margin is enclosed by [1 - U, 1], and the checker re-decides it on its
    own Jacobian (the roots' table says stable without moduli)."""
    cert = json.loads(json.dumps(prove_scene(_scene(*CASES["integrator"][:4], h="1e6"), maxprec=128).to_json()))
    st = {c["id"]: c for c in cert["claims"]}
    assert st["stable"]["status"] == "proved" and "Gershgorin" in st["stable"]["reason"]
    assert st["multipliers"]["status"] == "inconclusive" and "not isolated" in st["multipliers"]["reason"]
    margin = cert["quantities"]["stability_margin"]
    assert Fraction(margin["hi"]) >= 1 > Fraction(margin["lo"]) > Fraction(999, 1000)
    assert not any(k.startswith("multiplier_") for k in cert["quantities"])
    row = cert["extra"]["roots"][0]
    assert row["kind"] == "genuine" and row["moduli"] == [] and row["stable"] is True
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]
    from rigor_gyro.kinds.periodic_orbit import plant_check
    saved = plant_check._bound_below_1     # a checker whose discs decide nothing: stable and the row not confirmed
    try:
        plant_check._bound_below_1 = lambda J: None
        failed = {r.item for r in check_certificate(cert).results if not r.ok}
        assert {"stable", "extra.roots"} <= failed
    finally:
        plant_check._bound_below_1 = saved


def test_clustered_multipliers_say_how_many_bits_isolating_them_may_take():
    """At h = 1e6 the multipliers (~e^(-4e6), e^(-8e6)) are not isolated at any precision tried: the reason gives
    Liouville's estimate of the bits (about 8.7 million) as a hint, not python-flint's own advice (nonstop=True)."""
    cert = prove_scene(_scene(*CASES["integrator"][:4], h="1e6"), maxprec=128)
    c = next(c for c in cert.claims if c.id == "multipliers")
    assert c.status.value == "inconclusive" and "nonstop" not in c.reason
    assert "roughly 8656176 bits" in c.reason, c.reason


def test_one_tiny_multiplier_does_not_stop_the_escalation():
    """Review of the hint above: a plant with one very fast stable mode (an actuator lag of 1 us) has one tiny
    multiplier (Liouville's geometric mean ~2^-1.1e7) beside moderate ones (3e-10, -3.5e-21) that Rump's method
    separates only at 256 bits; the tiny one gets its own disc near 0. An early stop of the escalation on the
    estimate left the claim inconclusive at 128 bits; it is proved at 256."""
    sc = parse_scene('name = "t"\nkind = "periodic_orbit"\n[parameters]\nT3 = "1e-6"\nh = "5"\n[plant]\n'
                     'M = [["0", "1", "0", "0"], ["0", "0", "1", "0"], ["0", "-2", "-3", "1"], ["0", "0", "0", "-1/T3"]]\n'
                     'e = ["0", "0", "0", "1/T3"]\nc = ["1", "0", "0", "0"]\nS = "-1"\nh = "h"\n')
    cert = prove_scene(sc, maxprec=1024)
    c = next(c for c in cert.claims if c.id == "multipliers")
    assert c.status.value == "proved" and c.precision_bits >= 256, c.reason


def test_tiny_product_bits_from_liouvilles_product():
    from rigor_gyro.kinds.periodic_orbit.plant_claims import tiny_product_bits
    assert tiny_product_bits(arb(2) ** -100, 2) == 50
    assert tiny_product_bits(-(arb(2) ** -99), 3) == 33
    assert tiny_product_bits(arb("0.5") ** 3, 1) == 3
    assert tiny_product_bits(arb(1), 2) is None and tiny_product_bits(arb(3), 1) is None
    assert tiny_product_bits(arb(0, 1e-30), 2) is None and tiny_product_bits(arb("inf"), 2) is None
    assert tiny_product_bits(arb((1, -2 ** 1030)), 2) == 2 ** 1029     # beyond a double's exponent: no overflow


def test_the_disc_bound_holds_the_isolated_moduli_and_decides_nothing_at_or_above_1():
    """Where the multipliers are isolated, Gershgorin's bound U lies above every certified modulus; a Jacobian
    with an eigenvalue 1 or above (1; 3; 3/2 of [[1/2, 1], [1, 1/2]]) is never called stable."""
    from flint import arb_mat
    from rigor_gyro.kinds.periodic_orbit.claims import RootVerdict
    from rigor_gyro.kinds.periodic_orbit.norm_stability import spectral_radius_bound
    from rigor_gyro.kinds.periodic_orbit.plant_claims import stable_by_discs
    from rigor_gyro.kinds.periodic_orbit.plant_orbit import jacobian, section_index
    from flint import acb_mat
    model = validate(_scene(*CASES["pair_and_lag"]))
    an = __import__("rigor_gyro.kinds.periodic_orbit.plant_claims", fromlist=["analyse"]).analyse(model)
    v = next(r for r in an.roots if r.kind == "genuine")
    sp = an.sp_fine
    J = jacobian(sp.M, sp.e, sp.c, sp.S, v.theta, v.x0, section_index(model))
    U = spectral_radius_bound(acb_mat(J))
    assert v.moduli and all(m.upper() <= U for m in v.moduli)
    for entries in ([["1", "0"], ["0", "1/2"]], [["3", "0"], ["0", "1/10"]], [["1/2", "1"], ["1", "1/2"]]):
        w = RootVerdict(arb(1), [], "genuine", "")
        stable_by_discs(w, arb_mat([[arb(fmpq(Fraction(x).numerator, Fraction(x).denominator)) for x in r]
                                    for r in entries]))
        assert w.stable is None and w.radius_bound is None
    w = RootVerdict(arb(1), [], "genuine", "")
    stable_by_discs(w, arb_mat([[arb("0.5"), arb("0.25")], [arb(0), arb("0.5")]]))
    assert w.stable is True and w.radius_bound < 1
    from rigor_gyro.kinds.periodic_orbit.multipliers import disc_margin
    m = disc_margin(arb("0.25"))        # every modulus in [0, 1/4]: the margin anywhere in [3/4, 1]
    assert m.contains(arb("0.75")) and m.contains(1)


def test_the_checkers_disc_bound_is_none_at_or_above_1(monkeypatch):
    """The checker's own Gershgorin bound decides stable only below 1: a Jacobian [[2]] (its multipliers taken as
    not isolated) gives no bound, [[1/2]] gives one."""
    from flint import arb_mat
    from rigor_gyro.kinds.periodic_orbit import plant_check
    monkeypatch.setattr(plant_check, "_spectrum", lambda d, th: (None, arb_mat([[arb(2)]])))
    assert plant_check._disc_bound(None, arb(1)) is None
    monkeypatch.setattr(plant_check, "_spectrum", lambda d, th: (None, arb_mat([[arb("0.5")]])))
    assert plant_check._disc_bound(None, arb(1)) < 1


def test_a_row_stable_by_the_provers_discs_is_confirmed_where_the_checker_isolates_the_multipliers():
    """The integrator plant at h = 1e3: the prover's Jacobian (Arb's exponential) does not isolate the multipliers
    (~1e-1739) at any precision up to 4096 bits and its discs prove stable; the checker's tighter Jacobian does
    isolate them. Its row (moduli [], stable true) is re-decided from the checker's own moduli, so the honest
    certificate is confirmed (it was rejected: 'a stability flag without moduli')."""
    cert = json.loads(json.dumps(prove_scene(_scene(*CASES["integrator"][:4], h="1e3")).to_json()))
    row = cert["extra"]["roots"][0]
    assert row["moduli"] == [] and row["stable"] is True
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_a_box_whose_multipliers_are_not_isolated_is_stable_by_the_discs():
    """The integrator plant at h = 1e6 with S = -d, d in 1 +- 1e-6: over the box the ball Jacobian's discs bound
    every modulus (it crashed with an IndexError: the box path read the largest isolated modulus)."""
    from rigor_gyro.margins.executors import Executor
    from rigor_gyro.margins.paving import box_scene, pave
    from rigor_gyro.margins.report import paving_json
    scene = parse_scene('name = "t"\nkind = "periodic_orbit"\n[parameters]\nd = "1 +- 0.000001"\n[claims]\n'
                        'only = ["orbit_genuine", "stable"]\n[options]\nbox_resolution = "1/4"\nmax_boxes = "4"\n'
                        '[plant]\nM = [["0", "1", "0"], ["0", "0", "1"], ["0", "-2", "-3"]]\ne = ["0", "0", "1"]\n'
                        'c = ["1", "0", "0"]\nS = "-d"\nh = "1e6"\n')
    data = json.loads(json.dumps(paving_json(pave(box_scene(scene), Executor(1)))))
    assert [(c["id"], c["status"]) for c in data["claims"]] == [("orbit_genuine", "proved"), ("stable", "proved")]
    rep = check_certificate(data)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_a_row_emptied_of_moduli_may_say_stable_only_where_every_recomputed_modulus_is_below_1():
    """relay_two_modes: a stable row emptied of its moduli is still re-decided stable (the checker's moduli are
    below 1), the unstable middle orbit's row emptied and marked stable is not."""
    cert = json.loads(json.dumps(prove_scene(load_scene(PLANTS + "relay_two_modes.toml")).to_json()))
    rows = cert["extra"]["roots"]
    up = next(i for i, r in enumerate(rows) if r["stable"] is False)
    down = next(i for i, r in enumerate(rows) if r["stable"] is True)
    ok = copy.deepcopy(cert)
    ok["extra"]["roots"][down]["moduli"] = []
    assert _items(ok)["extra.roots"]
    bad = copy.deepcopy(cert)
    bad["extra"]["roots"][up].update(moduli=[], stable=True)
    assert not _items(bad)["extra.roots"]
