"""The checker's own gates (rigor_gyro.check.check_certificate, before and around the kind's checker) gate by
gate: each alteration of a genuine certificate (resealed, so the digest holds) fails exactly its gate,
named, with its message; the structure errors are CertificateError naming what is wrong.

tests/test_check.py asks that an altered certificate is rejected somewhere, so one gate weakened hid
behind another that also failed (proofs/mutation.md section 13).
"""
import copy

import pytest

from rigor_gyro.check import CertificateError, check_certificate
from rigor_gyro.kinds.eigenfrequencies import CLAIMS

from .forgery import certificate, failures as _failures, reseal as _reseal


def _one_claim():
    """rudenko1976 asked only for bracket_1: proved."""
    return certificate("rudenko1976", claims_only=["bracket_1"])


def test_the_genuine_certificate_passes_every_gate():
    data = _one_claim()
    report = check_certificate(data)
    assert report.ok and report.seconds > 0
    items = [r.item for r in report.results]
    assert items[:3] == ["integrity", "verdict", "claims"] and "bracket_1" in items


GATES = {
    # name: (change, [(item, fragment of the message)] of the failing results, in order)
    "a note added, not resealed": (lambda d: d["notes"].append("x"), [("integrity", "altered after it was written")]),
    "verdict refuted for proved": (lambda d: d.update(verdict="refuted"),
                                   [("verdict", "verdict 'refuted', but the claims give 'proved'")]),
    "verdict inconclusive for proved": (lambda d: d.update(verdict="inconclusive"),
                                        [("verdict", "but the claims give 'proved'")]),
    "an unknown status": (lambda d: (d["claims"][0].update(status="probably"), d.update(verdict="inconclusive")),
                          [("claims", "unknown status(es) ['probably']"), ("bracket_1", "re-decided"),
                           ("schema", "$.claims[0].status: 'probably' is not one of")]),
    "a scene outside the kind's domain": (lambda d: d["scene"]["parameters"].update(b="-1"),
                                          [("scene", "the certificate's scene is not valid")]),
    "scene parameters as a list": (lambda d: d["scene"].update(parameters=[["a", "1"]]),
                                   [("scene", "parameters and options must be objects")]),
    "a claim the scene does not ask": (lambda d: d["scene"].update(claims_only=["bracket_1", "bracket_2"]),
                                       [("claims", "claims ['bracket_1'] but the scene asks for ['bracket_1', "
                                                   "'bracket_2']")]),
    "the statement of another claim": (lambda d: d["claims"][0].update(statement=CLAIMS["bracket_2"]),
                                       [("bracket_1", "not the kind's statement")]),
    "precision 15 bits": (lambda d: d.update(precision_bits=15), [("precision_bits", "out of range")]),
    "precision 32769 bits": (lambda d: d.update(precision_bits=32769), [("precision_bits", "out of range")]),
    "precision as text": (lambda d: d.update(precision_bits="64"), [("precision_bits", "out of range")]),
    "a quantity the kind's checker cannot read": (lambda d: d["quantities"].update(omega_1=7),
                                                 [("data", "cannot be checked"),
                                                  ("schema", "$.quantities.omega_1: int is not of type object")]),
}


@pytest.mark.parametrize("name", sorted(GATES))
def test_each_alteration_fails_exactly_its_gate(name):
    change, expected = GATES[name]
    data = copy.deepcopy(_one_claim())
    assert data["verdict"] == "proved" and data["precision_bits"] in range(16, 32769)
    change(data)
    got = _failures(data if name.endswith("not resealed") else _reseal(data))
    assert len(got) == len(expected), got
    for (item, message), (want_item, fragment) in zip(got, expected):
        assert item == want_item and fragment in message, (got, expected)


@pytest.mark.parametrize("prec", [16, 32768])
def test_the_extreme_precisions_pass_the_gate(prec):
    data = copy.deepcopy(_one_claim())
    data["precision_bits"] = prec
    assert not any(item == "precision_bits" for item, _ in _failures(_reseal(data)))


@pytest.mark.parametrize("change, fragment", [
    (lambda d: d.pop("quantities"), "missing ['quantities']"),
    (lambda d: d.update(schema="rigor-gyro/certificate/0"), "this checker reads"),
    (lambda d: d["scene"].pop("kind"), "scene block incomplete"),
    (lambda d: d.update(claims={}), "claims must be a list"),
    (lambda d: d.update(quantities=[]), "claims must be a list and quantities an object"),
    (lambda d: d["claims"][0].pop("status"), "malformed claim"),
    (lambda d: d["claims"][0].update(details=[]), "counterexample and details must be objects"),
    (lambda d: d.update(witnesses=[]), "witnesses must be an object"),
])
def test_a_malformed_certificate_is_a_certificate_error_naming_the_fault(change, fragment):
    data = copy.deepcopy(_one_claim())
    change(data)
    with pytest.raises(CertificateError, match=fragment.replace("[", r"\[").replace("]", r"\]")):
        check_certificate(_reseal(data))
    with pytest.raises(CertificateError, match="a JSON object"):
        check_certificate([data])


def test_a_refuted_certificate_passes_and_its_verdict_relabelled_fails_at_the_verdict():
    data = certificate("rudenko1976", claims_only=["bracket_2"], eps="0.1076", Omega2="0.003")
    assert data["verdict"] == "refuted" and _failures(data) == []
    for other in ("proved", "inconclusive"):
        bad = copy.deepcopy(data)
        bad["verdict"] = other
        assert _failures(_reseal(bad)) == [("verdict", f"verdict {other!r}, but the claims give 'refuted'")]


def test_the_report_names_its_file_and_times_itself():
    report = check_certificate(_one_claim(), "some/where.json")
    assert report.file == "some/where.json" and 0 < report.seconds < 60


def test_a_scene_block_and_a_claim_with_only_the_required_keys_are_read():
    data = copy.deepcopy(_one_claim())
    data["scene"] = {k: data["scene"][k] for k in ("name", "kind", "parameters")}
    data["claims"][0] = {k: data["claims"][0][k] for k in ("id", "statement", "status")}
    report = check_certificate(_reseal(data))          # read (no CertificateError); the scene's claims differ
    assert ("claims", False) in [(r.item, r.ok) for r in report.results]


def test_a_kind_without_a_checker_is_never_confirmed(monkeypatch):
    import rigor_gyro.kinds
    monkeypatch.setattr(rigor_gyro.kinds, "checker", lambda kind: None)
    assert _failures(_one_claim()) == [("kind", "no checker for kind 'eigenfrequencies'")]
