"""The tamper corpus: one forgery per class of field a report prints as certified (issue 36).

Each forgery edits a genuine certificate's text (a reason, a stored counterexample, a detail, ``extra``,
``notes``, ``formulas``) and recomputes the digest, so that only re-derivation can reject it. Before the
``texts`` check (rigor_gyro.reproduce) the checker confirmed every one of them. Each must now be
rejected, and by the ``texts`` check (the field named in its message). The paving forgeries are in
tests/test_paving_check.py's alteration table.
"""
from __future__ import annotations

import copy
import json

import pytest

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.check import check_certificate
from tests.forgery import claim, reseal


@pytest.fixture(scope="module")
def certs() -> dict[str, dict]:
    names = ("agafonov2013", "roitenberg1947", "rudenko1976", "demo_eig_nu_order_fails", "demo_lyap_v_not_positive")
    return {n: json.loads(json.dumps(prove_scene(load_scene(n)).to_json())) for n in names}


def _first_refuted(d: dict) -> dict:
    return next(c for c in d["claims"] if c["status"] == "refuted")


def _equilibrium(d: dict, x2: str) -> dict:
    return next(e for e in claim(d, "equilibria")["details"]["equilibria"] if e["x2"] == x2)


def _genuine_root(d: dict) -> dict:
    return next(r for r in d["extra"]["roots"] if r["kind"] == "genuine")


def _set_first_string(obj, value):
    """Replace the first string leaf of a counterexample (a stored value) by ``value``."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if isinstance(v, str):
                obj[k] = value
                return True
            if _set_first_string(v, value):
                return True
    if isinstance(obj, list):
        for i, v in enumerate(obj):
            if isinstance(v, str):
                obj[i] = value
                return True
            if _set_first_string(v, value):
                return True
    return False


FORGERIES = {
    # reasons
    "equilibria reason: the origin unstable": (
        "agafonov2013", lambda d: claim(d, "equilibria").update(
            reason="the origin is unstable (a certified eigenvalue with positive real part)"), "reason"),
    "a refuted claim's reason with an invented counterexample": (
        "demo_eig_nu_order_fails", lambda d: _first_refuted(d).update(
            reason="refuted: omega_2 = 0.5 lies outside the bracket (certified)"), "reason"),
    # a refuted claim's stored counterexample value moved
    "counterexample value moved": (
        "demo_lyap_v_not_positive", lambda d: _set_first_string(_first_refuted(d)["counterexample"], "0.001"),
        "counterexample"),
    # details
    "an equilibrium marked inside the estimate": (
        "agafonov2013", lambda d: _equilibrium(d, "-pi").update(estimate="inside the estimate"), "details"),
    "an eigenvalue with a positive real part": (
        "agafonov2013", lambda d: _equilibrium(d, "0")["eigenvalues"].__setitem__(0, "[0.01, 0.010000001] + 0 i"),
        "details"),
    "a details radius different from the quantity": (
        "agafonov2013", lambda d: claim(d, "vdot_direct")["details"].update(R_direct="0.03"), "details"),
    "a root count": (
        "roitenberg1947", lambda d: claim(d, "half_period").setdefault("details", {}).update(roots=7), "details"),
    # extra
    "a spurious relay root relabelled genuine and stable": (
        "roitenberg1947", lambda d: d["extra"]["roots"][0].update(kind="genuine", stable=True,
                                                                   moduli=[["0.5", "0.5"]] * 4), "extra"),
    "the stable orbit's moduli set to 1.5": (
        "roitenberg1947", lambda d: _genuine_root(d).update(moduli=[["1.5", "1.5"]] * len(_genuine_root(d)["moduli"])),
        "extra"),
    "a root moved": ("roitenberg1947", lambda d: d["extra"]["roots"][0].update(theta=["0.2", "0.21"]), "extra"),
    "the moment formula's text": (
        "agafonov2013", lambda d: d["extra"]["moment"].update(formula="f(x2) = a x2"), "extra"),
    # notes and formulas
    "a note appended": ("agafonov2013", lambda d: d["notes"].append("R = R1 = 0.018 (certified)"), "notes"),
    "a note of the relay edited": ("roitenberg1947", lambda d: d["notes"].__setitem__(0, "all of (0, oo) searched"),
                                   "notes"),
    "a formula's text": ("rudenko1976", lambda d: d["formulas"][0].update(
        {k: "F(omega) = Omega^2 (certified)" for k in list(d["formulas"][0])[1:2]}), "formulas"),
}


@pytest.mark.parametrize("name", sorted(FORGERIES))
def test_each_forgery_is_rejected_by_re_derivation(name, certs):
    scene, forge, field = FORGERIES[name]
    genuine = certs[scene]
    data = copy.deepcopy(genuine)
    forge(data)
    assert data != genuine, "the forgery changed nothing"
    report = check_certificate(reseal(data))
    failed = [(r.item, r.message) for r in report.results if not r.ok]
    assert not report.ok and failed, f"{name}: confirmed"
    texts = [m for item, m in failed if item == "texts"]
    assert texts, (name, failed)
    where = texts[0].split(" is not what", 1)[0]                # the JSON path of the first difference
    assert field in where, (name, where)


def test_the_genuine_certificates_are_confirmed_with_their_texts(certs):
    for name, data in certs.items():
        report = check_certificate(data)
        assert report.ok, (name, report.first_failure)
        assert any(r.item == "texts" and "re-derived" in r.message for r in report.results)


def test_a_certificate_without_settings_is_not_a_certificate_of_this_version(certs):
    data = copy.deepcopy(certs["rudenko1976"])
    del data["settings"]
    report = check_certificate(reseal(data))
    assert not report.ok and report.first_failure.item == "schema"


def test_another_versions_certificate_is_not_confirmed(certs):
    data = copy.deepcopy(certs["rudenko1976"])
    data["software"]["rigor_gyro"] = "0.0.1"
    data["notes"].append("forged, but by another version")
    report = check_certificate(reseal(data))
    texts = next(r for r in report.results if r.item == "texts")
    assert not texts.ok and texts.message.startswith("not re-derived: written by rigor_gyro 0.0.1")
    assert not report.ok and report.first_failure.item == "texts"


# --- a run stopped by its time limit is re-derived too -------------------------------------------------

def _time_limited(monkeypatch, stage: str) -> dict:
    """rudenko1976 stopped by a 1 s limit during its first attempt."""
    import time

    from rigor_gyro.core.outcome import Status
    from rigor_gyro.kinds import eigenfrequencies
    real = eigenfrequencies.attempt
    calls = []

    def staged(model, wanted, prec):
        calls.append(prec)
        if stage == "first" or len(calls) > 1:
            time.sleep(5)
        a = real(model, wanted, prec)
        a.claims[1].status = Status.INCONCLUSIVE
        a.claims[1].decides = None
        return a
    with monkeypatch.context() as m:
        m.setattr(eigenfrequencies, "attempt", staged)
        cert = json.loads(json.dumps(prove_scene(load_scene("rudenko1976"), time_limit=1.0).to_json()))
    return cert


def test_a_run_stopped_before_any_attempt_finished_is_confirmed_and_forgeries_are_not(monkeypatch):
    cert = _time_limited(monkeypatch, "first")
    assert cert["settings"]["time_limit"] == 1.0 and not cert["quantities"]
    assert check_certificate(cert).ok
    forged = copy.deepcopy(cert)
    forged["claims"][0]["reason"] += " (roots certified anyway)"
    assert not check_certificate(reseal(forged)).ok
    # hostile review, session 10: an audit row or a claim's precision in a run that says nothing finished
    genuine = json.loads(json.dumps(prove_scene(load_scene("rudenko1976")).to_json()))
    row = next(r for r in genuine["paper"] if r["status"] == "refuted")
    for edit in (lambda d: d["paper"].append({**row, "status": "confirmed"}),
                 lambda d: d["claims"][0].update(precision_bits=32768)):
        forged = copy.deepcopy(cert)
        edit(forged)
        assert not check_certificate(reseal(forged)).ok


def test_a_run_stopped_after_a_finished_attempt_is_re_derived_from_it(monkeypatch):
    """The kind leaves nu_ordering undecided at every precision; the second attempt is slow, so a 1 s limit
    stops it. The checker re-proves at maxprec = the certificate's precision (the same kind, not slow):
    the stopped run is confirmed, and a forged reason in it is not."""
    import time

    from rigor_gyro.core.outcome import Status
    from rigor_gyro.kinds import eigenfrequencies
    real = eigenfrequencies.attempt
    slow = [True]
    calls = []

    def staged(model, wanted, prec):
        calls.append(prec)
        if slow[0] and len(calls) > 1:
            time.sleep(5)
        a = real(model, wanted, prec)
        a.claims[1].status = Status.INCONCLUSIVE
        return a
    monkeypatch.setattr(eigenfrequencies, "attempt", staged)
    cert = json.loads(json.dumps(prove_scene(load_scene("rudenko1976"), time_limit=1.0).to_json()))
    slow[0] = False
    assert any(n.startswith("time limit of 1 s") for n in cert["notes"]) and cert["quantities"]
    assert "time limit of 1 s" in cert["claims"][1]["reason"]
    report = check_certificate(cert)
    assert report.ok, report.first_failure
    forged = copy.deepcopy(cert)
    forged["claims"][0]["reason"] = "isolated by hand"
    texts = next(r for r in check_certificate(reseal(forged)).results if r.item == "texts")
    assert not texts.ok and texts.message.startswith("claims[0].reason")
    # hostile review, session 10: the time-limit wording is the prover's exactly, not a free-text prefix
    for edit in (lambda d: d["notes"].append("time limit of 1000 s reached; every bracket holds (certified)"),
                 lambda d: d["notes"].append("requested enclosure widths not met; the brackets hold everywhere"),
                 lambda d: d["claims"][1].update(reason=d["claims"][1]["reason"].split(" [undecided")[0]
                                                 + " [undecided at every precision tried: it holds (certified)]")):
        forged = copy.deepcopy(cert)
        edit(forged)
        texts = next(r for r in check_certificate(reseal(forged)).results if r.item == "texts")
        assert not texts.ok, texts.message


def test_a_genuine_time_limited_run_that_finished_in_time_is_confirmed():
    cert = json.loads(json.dumps(prove_scene(load_scene("rudenko1976"), time_limit=600).to_json()))
    assert cert["settings"]["time_limit"] == 600
    report = check_certificate(cert)
    assert report.ok, report.first_failure


def test_an_audit_row_forged_is_rejected(certs):
    """The audit rows are re-derived from the [paper] table the certificate's scene block carries."""
    data = copy.deepcopy(certs["rudenko1976"])
    assert data["scene"]["paper"], "the scene block carries the paper's printed numbers"
    row = next(r for r in data["paper"] if r["status"] == "disagrees")
    row.update(status="agrees", note="agrees to every printed digit")
    texts = next(r for r in check_certificate(reseal(data)).results if r.item == "texts")
    assert not texts.ok and texts.message.startswith("paper[")
