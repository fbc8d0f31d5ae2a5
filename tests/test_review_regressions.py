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
