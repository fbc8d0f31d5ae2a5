"""Forged margin outputs that `rigor-gyro check` used to accept (hostile test, sections C and D): scans, threshold
search logs, threshold curves and pavings. Each test edits a genuine output the way the forger did and asserts
the checker now rejects it (and that the genuine output still checks)."""
import copy
import json
from fractions import Fraction

import pytest

import rigor_gyro as rg
from rigor_gyro.check import check_certificate
from rigor_gyro.margins import scan as scan_module


def _failed(data):
    report = check_certificate(data)
    return [r for r in report.results if not r.ok]


@pytest.fixture(scope="module")
def scan5():
    """rudenko1976's bracket_2 and omega_2 at 5 values of Omega2: refuted at the first ones, proved at the last."""
    return rg.run_scan(rg.load_scene("rudenko1976"), "Omega2", 5, lo="0.001", hi="0.02", claim="bracket_2",
                       quantities=["omega_2"]).to_json()


def test_the_genuine_scan_checks(scan5):
    assert _failed(scan5) == []


def test_a_scan_longer_than_64_points_has_every_point_re_proved():
    data = rg.run_scan(rg.load_scene("rudenko1976"), "Omega2", 66, lo="0.001", hi="0.02", claim="bracket_2").to_json()
    assert _failed(data) == []
    n, k = 66, 64                           # the points the former 64-point sample skipped
    skipped = sorted(set(range(n)) - {round(i * (n - 1) / (k - 1)) for i in range(k)})
    i = next(j for j in skipped if data["points"][j]["claims"]["bracket_2"]["status"] == "refuted")
    bad = copy.deepcopy(data)
    bad["points"][i]["claims"]["bracket_2"] = {"status": "proved", "reason": "bracket (8) holds, certified"}
    c = bad["counts"]["bracket_2"]
    c["proved"], c["refuted"] = c["proved"] + 1, c["refuted"] - 1
    failed = _failed(bad)
    assert [f.item for f in failed] == ["re-proved"] and "stored proved, re-decided refuted" in failed[0].message


def test_a_sampled_scan_check_is_never_a_confirmation(scan5):
    results = scan_module.check_scan(scan5, max_points=2)
    item = [r for r in results if r[0] == "re-proved"]
    assert item and item[0][1] is False and "only a sample was re-proved (2 of 5 points" in item[0][2]


@pytest.mark.parametrize("edit, says", [
    (lambda p: p["claims"]["bracket_2"].update(status="inconclusive"), "stored inconclusive, re-decided refuted"),
    (lambda p: p["claims"]["bracket_2"].update(reason="[0.02, 0.0294] <= omega_2 <= [0.05, 0.06] certified"),
     "the stored reason is not the re-proof's own"),
    (lambda p: p.update(precision_bits=32768), "precision_bits 32768, the re-proof's"),
    (lambda p: p["quantities"].update(omega_2=None), "not the re-computed"),
])
def test_a_scan_point_must_be_its_re_proof_exactly(scan5, edit, says):
    assert scan5["points"][0]["claims"]["bracket_2"]["status"] == "refuted"
    bad = copy.deepcopy(scan5)
    edit(bad["points"][0])
    bad["counts"]["bracket_2"] = {k: sum(p["claims"]["bracket_2"]["status"] == k for p in bad["points"])
                                  for k in ("proved", "refuted", "inconclusive")}
    failed = _failed(bad)
    assert [f.item for f in failed] == ["re-proved"] and says in failed[0].message, failed
