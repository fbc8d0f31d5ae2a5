"""The periodic-orbit scene (Roitenberg 1947): both built-in readings, the audit, cross-checks, the stiff
and extreme cases, a planted no-orbit case, bad input.

Slow campaigns (H = 1e4 in both readings, ~5-10 s each) run only with --runslow.
"""
import json
from fractions import Fraction
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, strategies as st
from flint import arb, arb_mat

from rigor_gyro.kinds.periodic_orbit.approx import (approx_multipliers, approx_orbit_mpmath, approx_relay_simulation,
                                           approx_x0)
from rigor_gyro.core.balls import certainly_le, certainly_lt, working_precision
from rigor_gyro.certificate import AuditStatus, Status
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.prover import prove_scene
from rigor_gyro.kinds.periodic_orbit.flow import (RelayParams, Spectrum, g_coeffs, half_period_jacobian, phi_at,
                                   taylor_enclosure, x0_at)
from rigor_gyro.scene import load_scene, parse_scene

SLOW = pytest.mark.slow          # runs with --runslow (or RIGOR_GYRO_SLOW=1), like every slow test

PAPER = dict(A="125", B="0.133", H="100", tau="0.01", sigma="0.13125", n="50", K="7.5", p="40", S="0.15")
B215 = dict(PAPER, B="2/15")

#: mpmath reference values (40 digits, independent code path: mpmath.expm of the augmented matrix +
#: findroot; see rigor_gyro/kinds/periodic_orbit/approx.py): trusted to 1e-25 absolute
REF = {
    "roitenberg1947_b2over15": {"theta_star": "0.138267429657315456875930107052",
                                "beta_dot_0": "1.23463963048819", "Omega_0": "1.39620523449802e-4",
                                "i_0": "-2.58868244091804", "I_0": "-0.0724319807226097",
                                "multiplier_modulus_1": "0.956671889445", "multiplier_modulus_2": "0.589175272104",
                                "stability_margin": "0.0433281105552"},
    "roitenberg1947": {"theta_star": "0.138133574136193353417", "multiplier_modulus_1": "0.956583896",
                       "multiplier_modulus_2": "0.589526806", "stability_margin": "0.0434161"},
}
#: the short references above carry 12-15 significant digits: accept half a unit of their last place
def _ref_ball(s):
    from decimal import Decimal
    d = Decimal(s)
    return arb(s, float(Decimal(1).scaleb(d.as_tuple().exponent)) / 2 + 1e-30)


#: scipy solve_ivp at rtol 1e-12 through ~60 switchings: the observed half-period approaches theta* like
#: the perturbation (dominant multiplier ~0.957 per half cycle, so ~1e-3 * 0.957^60 ~ 1e-4 * scale)
SIM_THETA_TOL = 1e-5
#: contraction ratio of the perturbation over the last half-cycles vs the dominant multiplier
SIM_RATIO_TOL = 1e-4
#: numpy eigvals of the float Jacobian (condition ~1): relative 1e-9
FLOAT_MULT_TOL = 1e-9


@pytest.fixture(scope="module")
def certs():
    return {name: prove_scene(load_scene(name)) for name in ("roitenberg1947", "roitenberg1947_b2over15")}


def _scene(name="t", options="", **params):
    body = "\n".join(f'{k} = "{v}"' for k, v in params.items())
    return parse_scene(f'name = "{name}"\nkind = "periodic_orbit"\n[parameters]\n{body}\n{options}')


def test_both_builtin_scenes_prove_every_claim(certs):
    for name, c in certs.items():
        assert c.verdict is Status.PROVED, name
        assert [x.id for x in c.claims] == ["half_period", "orbit_genuine", "initial_point", "multipliers", "stable"]
        assert "6 roots of g" in c.claim("half_period").reason and "1 genuine" in c.claim("half_period").reason
        assert "all of (0, oo)" in c.claim("half_period").reason


def test_quantities_contain_the_references(certs):
    for name, ref in REF.items():
        q = certs[name].quantities
        for k, v in ref.items():
            assert q[k].is_finite() and q[k].overlaps(_ref_ball(v)), (name, k, q[k], v)   # NaN overlaps all
        th = q["theta_star"]
        assert certainly_le(2 * th.rad(), arb("1e-15"))                # far tighter than the 1e-12 asked
        assert q["period"].is_finite() and q["period"].overlaps(2 * th)
        assert certainly_lt(q["multiplier_modulus_1"], 1) and certainly_lt(0, q["stability_margin"])


def test_theta_star_contains_mpmath_40_digits():
    th, x0 = approx_orbit_mpmath(B215, 0.1382674, dps=40)
    c = prove_scene(load_scene("roitenberg1947_b2over15"))
    with working_precision(256):
        import mpmath
        ref = arb(mpmath.nstr(th, 40))
        assert c.quantities["theta_star"].is_finite() and c.quantities["theta_star"].overlaps(arb(ref.mid(), arb("1e-35")))


def test_spectral_flow_matches_arb_matrix_exponential():
    """exp(M t) from the spectral projectors against arb_mat.exp: two rigorous routes must overlap."""
    P = RelayParams.from_strings(**B215)
    with working_precision(128):
        sp = Spectrum(P)
        for t in ("0.01", "0.1382674296573154568759", "0.5"):
            d = phi_at(sp, arb(t)) - (sp.M * arb(t)).exp()
            assert all(x.is_finite() for x in d.entries()) and d.contains(arb_mat(5, 5)), t


def test_liouville_and_saltation_structure():
    """det of the half-period Jacobian = -exp(-(1/tau + 1/sigma) theta*) (product of the multipliers)."""
    P = RelayParams.from_strings(**B215)
    with working_precision(128):
        sp = Spectrum(P)
        th = arb("0.138267429657315456875930107052", arb("1e-29"))
        J = half_period_jacobian(sp, th, x0_at(sp, th))
        det = J.det()
        assert det.is_finite() and det.overlaps(-((-(1 / arb("0.01") + 1 / arb("0.13125"))) * th).exp())


def test_g_vanishes_to_fifth_order_at_zero():
    P = RelayParams.from_strings(**B215)
    with working_precision(128):
        sp = Spectrum(P)
        c = g_coeffs(sp, arb(0), 7)
        assert all(x.is_finite() and x.contains(0) for x in c[:5])
        assert c[5].is_finite() and c[5].overlaps(arb("857.142857142857142857", arb("1e-15")))   # S kappa/(240 sigma) = 6000/7
        g, dg = taylor_enclosure(lambda ctr, n: g_coeffs(sp, ctr, n), arb("0.1382674296573", "1e-13"), 8, (0, 1))
        assert g.is_finite() and g.contains(0) and certainly_lt(0, dg)


def test_scipy_relay_simulation_converges_to_the_certified_orbit(certs):
    c = certs["roitenberg1947_b2over15"]
    th = float(c.quantities["theta_star"].mid())
    x0 = approx_x0(B215, th)
    x = x0.copy()
    x[1:] += [1e-3, 1e-5, 1e-3, 1e-4]
    halves, pts = approx_relay_simulation(B215, x, half_cycles=60)
    assert abs(halves[-1] - th) < SIM_THETA_TOL
    d = [np.linalg.norm(p - x0[1:]) for p in pts]
    assert abs(d[-1] / d[-2] - float(c.quantities["multiplier_modulus_1"].mid())) < SIM_RATIO_TOL
    ev = approx_multipliers(B215, th)
    for z, m in zip(ev, [c.quantities[f"multiplier_modulus_{j}"] for j in range(1, 5)]):
        assert m.is_finite() and m.overlaps(arb(abs(z), FLOAT_MULT_TOL * max(abs(z), 1e-6)))


def test_audit_identifies_the_reading(certs):
    rows_b = {r.id: r for r in certs["roitenberg1947_b2over15"].paper}
    rows_p = {r.id: r for r in certs["roitenberg1947"].paper}
    for k in ("cubic (4): coefficient of lambda", "cubic (4): coefficient of 1"):
        assert rows_b[k].status is AuditStatus.AGREES and rows_p[k].status is AuditStatus.DISAGREES
    for k in ("mu1", "omega", "a22", "a45"):
        assert rows_b[k].status is AuditStatus.AGREES, k
        assert rows_p[k].status is AuditStatus.DISAGREES, k
    assert rows_b["D1"].status is AuditStatus.MISPRINT
    assert rows_b["i sin"].status is AuditStatus.MISPRINT
    assert rows_b["b5,1"].status is AuditStatus.MISPRINT
    assert rows_b["g(x) table: sign pattern"].status is AuditStatus.DISAGREES
    assert "agrees to 5 of 8" in rows_b["theta*"].note and "agrees to 3 of 8" in rows_p["theta*"].note
    assert "agrees to 4 of 6" in rows_b["|lambda2| = |lambda4|"].note
    assert rows_b["'all roots of (25) have modulus < 1: the motion is stable'"].status is AuditStatus.CONFIRMED


def test_every_printed_number_is_audited(certs):
    scene = load_scene("roitenberg1947_b2over15")
    printed = [r.printed for r in certs["roitenberg1947_b2over15"].paper]
    p = scene.paper
    # the g table: its rows, the sign pattern, and the table against (12) with the printed a_ij
    expected = (len(p["cubic"]) + 1 + 3 + len(p["a"]) + 1 + len(p["g_table_g"]) + 2 + len(p["D"])
                + sum(1 for v in p["orbit"].values() for x in v if x) + sum(len(v) for v in p["table2"].values())
                + len(p["table3"]) + 4 + 4 + len(p["table4"]["h"]) + len(p["table4"]["c"]) + len(p["table4"]["k"])
                + len(p["quartic"]) + len(p["lambda"]) + 1 + len(p.get("as_transcribed", {})))
    gains = [r for r in certs["roitenberg1947_b2over15"].paper if r.id.startswith("conclusion across the gains")]
    from rigor_gyro.kinds.periodic_orbit.paper_silent import SILENT_IDS
    # + the gains row (beyond the paper) and the silent corrections made when reading the paper (issue 39)
    assert len(printed) == expected + 1 + len(SILENT_IDS) and len(gains) == 1
    assert gains[0].status is AuditStatus.CONFIRMED and "K p S" in gains[0].note


# ----------------------------------------------------------------------------- stiff and extreme cases

@pytest.mark.parametrize("change, theta, bits", [
    (dict(tau="1e-4"), "0.1316036787107", 64),
    (dict(tau="1e-6"), "0.1315792147245", 128),
    (dict(H="1000"), "0.1412748052096", 64),
])
def test_stiff_cases_prove_at_recorded_precision(change, theta, bits):
    c = prove_scene(_scene(**dict(B215, **change)))
    assert c.verdict is Status.PROVED
    assert c.quantities["theta_star"].is_finite() and c.quantities["theta_star"].overlaps(arb(theta, "1e-13"))
    assert c.precision_bits == bits


def test_fast_nutation_has_several_orbits_and_names_the_stable_one():
    c = prove_scene(_scene(**dict(B215, H="1000")))
    assert "4 genuine" in c.claim("half_period").reason
    assert {"theta_star_2", "theta_star_3", "theta_star_4"} <= set(c.quantities)
    assert "unstable" in c.claim("stable").reason


@SLOW
def test_h_1e4_b_reading_one_stable_orbit_between_close_pairs():
    c = prove_scene(_scene(**dict(B215, H="10000")))
    assert c.verdict is Status.PROVED and "106 roots" in c.claim("half_period").reason
    assert c.quantities["theta_star"].is_finite() and c.quantities["theta_star"].overlaps(arb("0.11928101173524", "1e-13"))
    assert c.quantities["multiplier_modulus_1"].is_finite()
    assert c.quantities["multiplier_modulus_1"].overlaps(arb("0.9951181668", "1e-9"))


@SLOW
def test_h_1e4_as_printed_no_stable_orbit_is_refuted():
    c = prove_scene(_scene(**dict(PAPER, H="10000")))
    assert c.claim("orbit_genuine").status is Status.PROVED
    assert c.claim("stable").status is Status.REFUTED and "certainly > 1" in c.claim("stable").reason


def test_relay_amplitude_scales_the_orbit_not_its_period():
    """S tiny or huge: theta* is the same, x0 scales with S (linearity in the forcing)."""
    c1 = prove_scene(_scene(**dict(B215, S="1e-6")))
    c2 = prove_scene(_scene(**dict(B215, S="1e6")))
    for c in (c1, c2):
        assert c.verdict is Status.PROVED
        th = c.quantities["theta_star"]
        assert th.is_finite() and th.overlaps(arb("0.1382674296573154568", "1e-18"))
    ratio = c2.quantities["beta_dot_0"] / c1.quantities["beta_dot_0"]
    assert ratio.is_finite() and ratio.overlaps(arb("1e12", "1e-3"))


def test_relay_gains_p_and_k_change_the_amplitude_not_the_period_or_the_multipliers():
    """amplitude_similarity: the same theta* and moduli for p, K far apart; x0 scales with K p S."""
    c1 = prove_scene(_scene(**dict(B215, p="4", K="0.75")))
    c2 = prove_scene(_scene(**dict(B215, p="4000", K="75")))
    for c in (c1, c2):
        assert c.verdict is Status.PROVED
        th = c.quantities["theta_star"]
        assert th.is_finite() and th.overlaps(arb("0.1382674296573154568", "1e-18"))
    for k in ("multiplier_modulus_1", "multiplier_modulus_4"):
        assert c1.quantities[k].is_finite() and c2.quantities[k].is_finite() and c1.quantities[k].overlaps(c2.quantities[k])
    ratio = c2.quantities["beta_dot_0"] / c1.quantities["beta_dot_0"]
    assert ratio.is_finite() and ratio.overlaps(arb("1e5", "1e-6"))


@given(st.fractions(min_value=Fraction(1, 100), max_value=100), st.fractions(min_value=Fraction(1, 100), max_value=100),
       st.fractions(min_value=Fraction(1, 100), max_value=100))
def test_the_amplitude_similarity_is_exact_and_fails_on_a_changed_model(p, K, n):
    from rigor_gyro.kinds.periodic_orbit import flow as F
    P = F.RelayParams.from_strings(A="125", B="0.133", H="100", tau="0.01", sigma="0.13125", n=str(n), K=str(K),
                                   p=str(p), S="0.15")
    assert F.amplitude_similarity(P)
    bad = F.system_matrix(P)
    bad[3, 2] = bad[3, 2] * P.p            # p in the back-emf term: no longer an amplitude
    orig = F.system_matrix
    try:
        F.system_matrix = lambda Q, _b=bad, _P=P: _b if Q is _P else orig(Q)
        assert F.amplitude_similarity(P) == (p == 1)
    finally:
        F.system_matrix = orig


def test_restricted_search_with_no_orbit_is_inconclusive_not_refuted():
    """Searching only (0, 0.12]: the single root there (0.10566) starts into beta < 0 (certified witness),
    but the genuine orbit theta* = 0.13827 lies beyond T_max: a restricted search never refutes."""
    c = prove_scene(_scene(options='[options]\nT_max = "0.12"', **B215))
    og = c.claim("orbit_genuine")
    assert og.status is Status.INCONCLUSIVE and "beta(t) = [-" in og.reason and "< 0 at t" in og.reason
    assert "not a refutation" in og.reason
    assert "roots beyond it not searched" in c.claim("half_period").reason
    assert c.claim("half_period").status is Status.PROVED
    assert c.claim("stable").status is Status.INCONCLUSIVE and c.exit_code == 3


# ----------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("change, word", [
    (dict(S="0"), "'S'"), (dict(A="0"), "'A'"), (dict(B="-1"), "'B'"), (dict(n="0"), "'n'"),
    (dict(tau="0"), "'tau'"), (dict(H="pi"), "'H'"),
])
def test_bad_parameters_name_the_parameter(change, word):
    with pytest.raises(ParameterError, match=word):
        prove_scene(_scene(**dict(B215, **change)))


def test_missing_and_unknown_parameters():
    p = dict(B215)
    del p["sigma"]
    with pytest.raises(ParameterError, match="sigma"):
        prove_scene(_scene(**p))
    with pytest.raises(ParameterError, match="zeta"):
        prove_scene(_scene(**dict(B215, zeta="1")))
    with pytest.raises(ParameterError, match="T_max"):
        prove_scene(_scene(options='[options]\nT_max = "-1"', **B215))


def test_cli_bad_input_is_exit_2(tmp_path):
    for body, word in (('S = "0"', "'S'"), ('S = 0.15', "'S'"), ('A = "0"', "'A'")):
        params = "\n".join(f'{k} = "{v}"' for k, v in B215.items() if k not in ("S", "A")) + "\n"
        params += body + "\n" + ('A = "125"' if not body.startswith("A") else 'S = "0.15"')
        path = tmp_path / "bad.toml"
        path.write_text(f'name = "bad"\nkind = "periodic_orbit"\n[parameters]\n{params}\n')
        r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", str(path), "--out", str(tmp_path)],
                           capture_output=True, text=True)
        assert r.returncode == 2 and word in r.stderr and "Traceback" not in r.stderr, (body, r.stderr)


def test_cli_proves_builtin_and_writes_json(tmp_path):
    r = subprocess.run([sys.executable, "-m", "rigor_gyro", "prove", "roitenberg1947", "--out", str(tmp_path)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cert = json.loads((tmp_path / "roitenberg1947.json").read_text())
    assert cert["verdict"] == "proved" and "theta_star" in cert["quantities"]
    assert {"multiplier_modulus_1", "multiplier_modulus_4", "stability_margin", "beta_dot_0", "I_0", "period",
            "D1", "D5"} <= set(cert["quantities"])


def test_proving_the_orbit_imports_neither_numpy_nor_scipy():
    code = ("import sys; from rigor_gyro.prover import prove_scene; from rigor_gyro.scene import load_scene;"
            "prove_scene(load_scene('roitenberg1947'));"
            "print(sorted(m for m in ('numpy', 'scipy', 'mpmath', 'matplotlib') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"


@pytest.mark.parametrize("order", [2, 3, 8])
def test_taylor_enclosure_contains_the_function_on_the_whole_box(order):
    """The Lagrange remainder is what makes a Taylor model an enclosure: for exp (coefficients known
    exactly) the enclosure of f and f' over X must contain their values at points of X. The direct
    enclosure over X is made deliberately loose here (still valid), so the Taylor part decides: a
    remainder shrunk even by half misses the values at the ends of X."""
    from math import factorial
    from flint import arb as A

    def coeffs(center, n):
        c = [center.exp() / factorial(j) for j in range(n)]
        if not center.rad().is_zero() and n == 2:   # the direct enclosure: valid but loose
            c = [x + A(0, 10 * abs(x).upper()) for x in c]
        return c
    with working_precision(128):
        X = A("0.5").union(A("1.5"))
        f, df = taylor_enclosure(coeffs, X, order, (0, 1))
        for t in ("0.5", "0.75", "1", "1.5"):
            v = A(t).exp()
            assert f.is_finite() and f.contains(v) and df.is_finite() and df.contains(v), (order, t)


def test_the_memo_of_g_coefficients_keys_on_the_whole_ball():
    """A ball and its own midpoint have the same centre: the memo must not hand back the point's
    coefficients for the ball (they would enclose G at one point only)."""
    from rigor_gyro.kinds.periodic_orbit.g_roots import isolation_coeffs
    from rigor_gyro.kinds.periodic_orbit import validate
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        sp = Spectrum(m.params)
        coeffs, _ = isolation_coeffs(sp)
        x = arb("0.1")
        point = coeffs(x, 4)
        wide = coeffs(arb(x.mid(), "1e-3"), 4)
        edge = coeffs(arb(x.mid() + arb("0.0009")), 4)      # a point inside the ball, computed fresh
        for j in range(4):
            assert wide[j].is_finite() and wide[j].contains(edge[j]) and wide[j].rad() > point[j].rad()
        assert [str(c) for c in coeffs(x, 4)] == [str(c) for c in point]     # a hit is the same balls


def test_the_g_table_is_recomputed_from_the_papers_printed_inputs():
    """Issue 13's example of a propagated check: (12) with the paper's own printed a_ij, mu1, omega, mu2 and
    1/sigma. It changes sign between the printed x = 0.138254 and 0.13826977 and no single scale maps it to
    the printed table: the row says the table does not come from (12) as written. With a table that is one
    scale times the recomputed values, the same row agrees."""
    from flint import arb
    from rigor_gyro.certificate import AuditStatus
    from rigor_gyro.kinds.periodic_orbit.paper import _g_from_printed_row
    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import load_scene
    cert = prove_scene(load_scene("roitenberg1947_b2over15"))
    row = next(r for r in cert.paper if r.id == "g(x) table from (12) with the printed a_ij")
    assert row.status is AuditStatus.DISAGREES
    assert "between x = 0.13825400 and 0.13826977" in row.note and "no common scale" in row.note
    g_rows = [r for r in cert.paper if r.id.startswith("g(0.1") and r.id.endswith("of (12)")]
    assert len(g_rows) == 6 and all(r.propagated is not None and r.propagated.is_finite() for r in g_rows)
    made = [("0.1", arb(-2)), ("0.2", arb(3)), ("0.3", arb(5))]
    same = _g_from_printed_row(["0.1", "0.2", "0.3"], ["-14", "21", "35"], made)
    assert same.status is AuditStatus.AGREES and "one scale fits" in same.note
    other = _g_from_printed_row(["0.1", "0.2", "0.3"], ["-14", "21", "40"], made)     # 8 against 7
    assert other.status is AuditStatus.DISAGREES
