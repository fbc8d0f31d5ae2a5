"""Regressions for the defects an outside review found (issue 9). Each test failed before its fix.

Item numbers follow the issue: 1 series truncation, 2 restricted search refutes, 3 best_mu overstated,
4 crash exit codes, 5 hangs, 6 typos accepted, 7 scene name as a path, 8 half-written outputs,
9 escalation that cannot help, 10 invariant_estimate tolerance, 11 the smallest multiplier.
"""
import dataclasses

import pytest
from flint import ctx

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import SeriesTruncated, ball, series_coefficients, series_length, working_precision
from rigor_gyro.core.outcome import Status
from rigor_gyro.kinds.periodic_orbit import claims as relay_claims
from rigor_gyro.kinds.periodic_orbit.flow import RelayParams, Spectrum, g_coeffs

RELAY = load_scene("roitenberg1947")


def _relay(name: str, **params) -> object:
    return dataclasses.replace(RELAY, name=name, parameters=dict(RELAY.parameters, **params))


# ------------------------------------------------------------------ 1. series cut to ctx.cap terms

def test_1_series_coefficients_refuse_a_series_cut_by_the_cap():
    from flint import acb, acb_series
    cut = acb_series([acb(0.5), 1], prec=13).exp()          # python-flint keeps ctx.cap = 10 terms
    with pytest.raises(SeriesTruncated):
        series_coefficients(cut, 13)
    with series_length(13):
        whole = series_coefficients(acb_series([acb(0.5), 1], prec=13).exp(), 13)
    assert len(whole) == 13 and ctx.cap == 10
    assert not whole[12].contains(0)                        # e^0.5/12! is no zero to pad with


def test_1_g_coeffs_beyond_the_default_cap_are_the_true_coefficients():
    sp_params = RelayParams.from_strings(**RELAY.parameters)
    with working_precision(128):
        sp = Spectrum(sp_params)
        c13 = g_coeffs(sp, ball("0.1"), 13)
        c16 = g_coeffs(sp, ball("0.1"), 16)
    assert len(c13) == 13
    assert c13[12].overlaps(c16[12]) and not c13[12].contains(0)


@pytest.mark.parametrize("order", [8, 12, 16])
@pytest.mark.parametrize("H, roots", [("100", 6), ("1e3", 16)])
def test_1_relay_roots_do_not_depend_on_the_taylor_order(monkeypatch, order, H, roots):
    monkeypatch.setattr(relay_claims, "TAYLOR_ORDER", order)
    cert = prove_scene(_relay(f"order{order}", H=H))
    assert cert.verdict is Status.PROVED
    assert len(cert.extra["roots"]) == roots


# ------------------------------------------------------------------ 2. a restricted search never refutes

B215 = load_scene("roitenberg1947_b2over15")


def _b215(name: str, options: dict | None = None, **params):
    return dataclasses.replace(B215, name=name, parameters=dict(B215.parameters, **params),
                               options=dict(options or {}))


def test_2_t_max_below_the_orbit_is_inconclusive_not_refuted():
    cert = prove_scene(_b215("tmax013", {"T_max": "0.13"}))
    statuses = {c.id: c.status for c in cert.claims}
    assert Status.REFUTED not in statuses.values(), statuses
    assert cert.exit_code == 3
    assert statuses["half_period"] is Status.PROVED          # (0, 0.13] is fully searched
    assert "not a refutation" in cert.claim("orbit_genuine").reason


def test_2_stable_orbit_beyond_t_max_leaves_stable_inconclusive():
    """H = 1e3: three unstable genuine orbits below 0.13, the stable one at 0.14127 beyond it."""
    cert = prove_scene(_b215("tmax013h", {"T_max": "0.13"}, H="1000"))
    assert cert.claim("orbit_genuine").status is Status.PROVED
    assert cert.claim("stable").status is Status.INCONCLUSIVE
    assert "not searched" in cert.claim("stable").reason
    full = prove_scene(_b215("h1000", H="1000"))
    assert full.claim("stable").status is Status.PROVED


def test_2_an_exhaustive_search_without_a_genuine_orbit_refutes_with_its_counterexample(monkeypatch):
    """The same analysis (one spurious root, no genuine one) refutes only once the range is all of (0, oo)."""
    restricted = _b215("tmax012", {"T_max": "0.12"})
    model = relay_claims.validate(restricted)
    with working_precision(64):
        an = relay_claims.analyse(model)
        assert not an.covers_all and [v.kind for v in an.roots] == ["spurious"]
        inconclusive = relay_claims.attempt(model, list(relay_claims.CLAIMS), 64)
        an.covers_all, an.T_tail = True, an.T_search        # as if the tail bound had covered the rest
        monkeypatch.setattr(relay_claims, "analyse", lambda m: an)
        refuted = relay_claims.attempt(model, list(relay_claims.CLAIMS), 64)
    assert all(c.status is not Status.REFUTED for c in inconclusive.claims)
    og = next(c for c in refuted.claims if c.id == "orbit_genuine")
    assert og.status is Status.REFUTED
    assert og.counterexample["searched"] == "(0, oo)" and len(og.counterexample["roots"]) == 1


def test_2_a_refutation_without_a_counterexample_is_a_bug_not_a_verdict():
    from rigor_gyro.core.outcome import Claim
    with pytest.raises(AssertionError):
        Claim("x", "statement", Status.REFUTED, "a search limit was hit")
    Claim("x", "statement", Status.REFUTED, "certified", counterexample={"point": "1"})


# ------------------------------------------------------------------ 3. best_mu says what it proves

def test_3_best_mu_states_a_search_result_and_certifies_how_good_it_is():
    from rigor_gyro.kinds.lyapunov import claims as lyap
    cert = prove_scene(load_scene("agafonov2013"))
    claim = cert.claim("best_mu")
    assert claim.status is Status.PROVED
    assert "not proved optimal" in claim.statement and "maximises" not in claim.statement
    q = cert.quantities
    U, R_max = q["R_sup_upper_bound"], q["R_max"]
    assert (U - R_max).lower() >= 0 and q["R_max_relative_gap"].upper() < 1e-5
    # the bound holds at other admissible mu, computed independently of the branch and bound
    model = lyap.validate(load_scene("agafonov2013"))
    with working_precision(64):
        xs = model.gimbal.x2_star.ball()
        for mu in ("0.014", "0.018", "0.02", "0.022", "0.03"):
            R, _ = lyap.r_sup(model.gimbal.with_mu(lyap.parse_exact(mu).fmpq()), xs)
            assert R.lower() <= U.upper(), mu
