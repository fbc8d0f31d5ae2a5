"""The campaign driver: a small derandomized slice, the per-case time limit, and the summary table.

The long campaigns (10,000 cases per kind) are commands, summarised in proofs/campaign.md.
"""
from __future__ import annotations

import pytest

pytest.importorskip("mpmath")
pytest.importorskip("scipy")

from rigor_gyro.campaign import run_campaign, run_case, summary_table  # noqa: E402
from rigor_gyro.cli import main  # noqa: E402


def test_eigenfrequency_slice_has_no_failure():
    results = run_campaign("eigenfrequencies", 12, seed=7)
    assert len(results) == 12
    assert all(r["verdict"] in ("proved", "refuted") for r in results)
    assert not any(r["containment_failures"] or r["verdict_disagreements"] or r["error"] for r in results)
    assert sum(r["compared"] for r in results) >= 12 * 5


def test_a_case_over_its_time_limit_is_inconclusive_never_agreement():
    from rigor_gyro.kinds.lyapunov.campaign import draw
    import random
    params = draw(random.Random(3))
    r = run_case("lyapunov", params, None, timeout=1e-4)
    assert r["timed_out"] and r["verdict"] == "inconclusive"
    assert r["compared"] == 0 and not r["containment_failures"] and not r["error"]
    table = summary_table("lyapunov", 3, [r])
    assert "1 (1 timed out)" in table


def test_the_time_limit_is_disarmed_after_a_case():
    import signal
    from rigor_gyro.kinds.eigenfrequencies.campaign import draw
    import random
    r = run_case("eigenfrequencies", draw(random.Random(1)), None, timeout=30)
    assert not r["timed_out"]
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)


@pytest.mark.parametrize("value", ["-1", "inf", "nan"])
def test_bad_case_timeout_is_bad_input(value, capsys):
    assert main(["campaign", "--kind", "eigenfrequencies", "--cases", "1", "--case-timeout", value]) == 2
    assert "--case-timeout" in capsys.readouterr().err


def test_every_case_is_re_verified_by_the_checker(monkeypatch):
    results = run_campaign("eigenfrequencies", 3, seed=11)
    assert all(r["check_failures"] == [] for r in results)
    import rigor_gyro.check as check

    class Bad:
        ok = False
        first_failure = check.CheckResult("roots", False, "planted")
    monkeypatch.setattr(check, "check_certificate", lambda data: Bad())
    r = run_case("eigenfrequencies", results[0]["params"])
    assert r["check_failures"] == ["roots: planted"]
    table = summary_table("eigenfrequencies", 11, [r])
    assert "check failures" in table and "FAILED" in table and "planted" in table


def test_a_timeout_inside_a_c_callback_is_a_timeout_not_a_crash(monkeypatch):
    """Found by the campaign: the alarm fired inside acb.integral's callback, which python-flint turns
    into a SystemError; that case must count as timed out, never as a crash."""
    import rigor_gyro.campaign as campaign
    import rigor_gyro.prover as prover

    def slow(*a, **k):
        campaign._FIRED[0] = True           # as the alarm handler does, then python-flint's wrapping
        raise SystemError("<cyfunction acb.integral> returned a result with an exception set")
    monkeypatch.setattr(prover, "prove_scene", slow)
    from rigor_gyro.kinds.eigenfrequencies.campaign import draw
    import random
    r = run_case("eigenfrequencies", draw(random.Random(2)), None, timeout=30)
    assert r["timed_out"] and r["verdict"] == "inconclusive" and not r["error"]


def test_the_lyapunov_references_catch_an_inflated_radius_or_level():
    """The sampled decisions of vdot_direct and largest_sublevel (grad V . f and V in floats, confirmed
    in mpmath) report a certificate whose R_direct or c_max_lower is too large."""
    from flint import arb

    from rigor_gyro import load_scene, prove_scene
    from rigor_gyro.campaign import CaseResult
    from rigor_gyro.kinds.lyapunov.campaign import compare
    scene = load_scene("agafonov2013")
    params = dict(scene.parameters)
    cert = prove_scene(scene)
    res = CaseResult(params=params)
    compare(params, cert, res)
    assert res.verdict_disagreements == []
    for name, factor, claim in (("R_direct", 3, "vdot_direct"), ("c_max_lower", 2, "largest_sublevel"),
                                ("R_direct_max", 1.2, "best_mu_direct")):
        bad = prove_scene(scene)
        bad.quantities[name] = bad.quantities[name] * arb(factor)
        res = CaseResult(params=params)
        compare(params, bad, res)
        assert any(d.startswith(claim) for d in res.verdict_disagreements), (name, res.verdict_disagreements)


def test_the_ray_samples_catch_a_level_above_the_vdot_bound():
    """x2* = 1.3: {Vdot >= 0} binds (c_max in [63.5, 77.3]), not the faces; a level 1.5 x too high is
    caught by V along the rays where grad V . f turns >= 0."""
    import dataclasses

    from flint import arb

    from rigor_gyro import load_scene, prove_scene
    from rigor_gyro.campaign import CaseResult
    from rigor_gyro.kinds.lyapunov.campaign import compare
    base = load_scene("agafonov2013")
    scene = dataclasses.replace(base, name="x2s", parameters=dict(base.parameters, x2_star="1.3"))
    params = dict(scene.parameters)
    cert = prove_scene(scene)
    assert cert.claim("largest_sublevel").details.get("binds") == "vdot"
    res = CaseResult(params=params)
    compare(params, cert, res)
    assert res.verdict_disagreements == []
    cert.quantities["c_max_lower"] = cert.quantities["c_max_lower"] * arb("1.5")
    res = CaseResult(params=params)
    compare(params, cert, res)
    assert any(d.startswith("largest_sublevel proved") for d in res.verdict_disagreements)
