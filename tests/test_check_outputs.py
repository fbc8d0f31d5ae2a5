"""`rigor-gyro check` reads every output kind (issue 35, part 3): certificates, pavings, thresholds and scans,
each validated against its JSON Schema (rigor_gyro/schemas/) by the checker's own validator and here by
jsonschema too, then re-verified; a tampered status or bracket is rejected.
"""
import copy
import dataclasses
import json

import pytest

import rigor_gyro as rg
from rigor_gyro.check import SCHEMA_FILES, check_certificate, load_schema, schema_errors
from rigor_gyro.cli import main
from rigor_gyro.core.balls import interval_text
from rigor_gyro.core.boxes import fraction_text
from rigor_gyro.margins.threshold import statement

jsonschema = pytest.importorskip("jsonschema")


def _agafonov(**params):
    s = rg.load_scene("agafonov2013")
    return dataclasses.replace(s, parameters={**s.parameters, **params}, claims_only=["damping_condition"])


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    out = tmp_path_factory.mktemp("outputs")
    rg.write_outputs(rg.prove_scene(rg.load_scene("rudenko1976")), out)
    box = _agafonov(k="[0.35, 0.45]")
    box = dataclasses.replace(box, options={**box.options, "range_boxes": "8"})  # a few tiles: ranges checked cheaply
    rg.write_paving(rg.pave(rg.box_scene(box)), out)
    rg.write_threshold(rg.find_threshold(_agafonov(), "k", lo="0.2", hi="0.8", width="1e-2"), out)
    rg.write_threshold(rg.find_threshold(_agafonov(), "mu", lo="0.001", hi="0.01"), out)      # refuted at both ends
    rg.write_scan(rg.run_scan(rg.load_scene("roitenberg1947"), "n", 3, lo="1", hi="100", claim="stable",
                              quantities=["stability_margin"]), out)
    return {"certificate": out / "rudenko1976.json", "paving": out / "agafonov2013.json",
            "threshold": out / "margin_agafonov2013_k.json", "threshold_none": out / "margin_agafonov2013_mu.json",
            "scan": out / "scan_roitenberg1947_n.json"}


def _load(path):
    return json.loads(path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("kind", ["certificate", "paving", "threshold", "threshold_none", "scan"])
def test_every_output_kind_conforms_to_its_schema_and_checks(outputs, kind):
    data = _load(outputs[kind])
    schema = load_schema(SCHEMA_FILES[data["schema"]])
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.validate(data, schema)
    assert schema_errors(data, schema) == []
    report = rg.check_file(outputs[kind])
    assert report.ok, report.first_failure
    assert any(r.item == "schema" and r.ok for r in report.results)
    assert main(["check", "--quiet", str(outputs[kind])]) == 0


@pytest.mark.parametrize("kind", ["certificate", "paving", "threshold", "scan"])
def test_the_checkers_validator_agrees_with_jsonschema_on_broken_files(outputs, kind):
    data = _load(outputs[kind])
    schema = load_schema(SCHEMA_FILES[data["schema"]])
    for edit in (lambda d: d.pop("scene"), lambda d: d.update(surplus=1), lambda d: d["scene"].update(name=7),
                 lambda d: d.update(schema="rigor-gyro/other/1")):
        bad = copy.deepcopy(data)
        edit(bad)
        assert schema_errors(bad, schema), edit
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, schema)


def test_a_file_that_breaks_its_schema_fails_the_schema_check(outputs):
    bad = _load(outputs["threshold"])
    bad["steps"][0]["status"] = "maybe"
    report = check_certificate(bad)
    assert not report.ok and report.first_failure.item == "schema" and "$.steps[0].status" in report.first_failure.message
    bad = _load(outputs["scan"])
    bad["points"][0]["value"] = 1.5
    assert check_certificate(bad).first_failure.item == "schema"


def test_a_threshold_with_its_proved_and_refuted_points_swapped_is_rejected(outputs):
    from fractions import Fraction
    data = _load(outputs["threshold"])
    bad = copy.deepcopy(data)
    p, r = bad["proved_at"], bad["refuted_at"]
    bad["proved_at"], bad["refuted_at"] = r, p
    bad["statement"] = statement(bad["claim"], bad["param"], Fraction(r), Fraction(p))
    for s in bad["steps"]:
        s["status"] = {"proved": "refuted", "refuted": "proved"}.get(s["status"], s["status"])
    report = check_certificate(bad)
    assert not report.ok
    failed = {r.item for r in report.results if not r.ok}
    assert {"proved_at", "refuted_at"} <= failed


def test_a_threshold_with_a_tampered_bracket_is_rejected(outputs):
    from fractions import Fraction
    data = _load(outputs["threshold"])
    p, r = Fraction(data["proved_at"]), Fraction(data["refuted_at"])
    fake = r - (p - r) * 4                  # on the refuted side of r, claimed proved there
    bad = copy.deepcopy(data)
    bad["proved_at"] = fraction_text(fake)
    lo, hi = min(fake, r), max(fake, r)
    bad["bracket"] = [fraction_text(lo), fraction_text(hi)]
    bad["bracket_decimal"] = list(interval_text(lo, hi)[:2])
    bad["statement"] = statement(bad["claim"], bad["param"], fake, r)
    bad["steps"].append({"value": fraction_text(fake), "status": "proved", "reason": "forged"})
    report = check_certificate(bad)
    assert not report.ok and any(x.item == "proved_at" and not x.ok for x in report.results)
    narrow = copy.deepcopy(data)            # the bracket alone narrowed: it no longer follows from the points
    narrow["bracket"] = [data["bracket"][0], fraction_text((p + r) / 2)]
    assert any(x.item == "bracket" and not x.ok for x in check_certificate(narrow).results)
    wide = copy.deepcopy(data)              # 'certified' with a requested width the bracket does not meet
    wide["requested_relative_width"] = fraction_text(abs(p - r) / max(abs(p), abs(r)) / 2)
    assert any(x.item == "certified" and not x.ok for x in check_certificate(wide).results)


def test_a_search_without_a_bracket_is_checked_at_its_ends(outputs):
    data = _load(outputs["threshold_none"])
    assert data["bracket"] is None and not data["certified"]
    bad = copy.deepcopy(data)
    bad["steps"][1]["status"] = "proved"
    assert not check_certificate(bad).ok
    bad = copy.deepcopy(data)
    bad["certified"] = True
    assert any(x.item == "bracket" and not x.ok for x in check_certificate(bad).results)


def test_a_scan_with_a_tampered_status_or_quantity_is_rejected(outputs):
    data = _load(outputs["scan"])
    bad = copy.deepcopy(data)
    bad["points"][1]["claims"]["stable"]["status"] = "refuted"
    bad["counts"]["stable"] = {"proved": 2, "refuted": 1, "inconclusive": 0}
    report = check_certificate(bad)
    assert not report.ok and report.first_failure.item == "re-proved" and "stored refuted" in report.first_failure.message
    bad = copy.deepcopy(data)
    bad["counts"]["stable"]["proved"] = 2
    assert check_certificate(bad).first_failure.item == "counts"
    bad = copy.deepcopy(data)
    lo, hi = bad["points"][0]["quantities"]["stability_margin"]
    bad["points"][0]["quantities"]["stability_margin"] = [hi, hi]
    assert check_certificate(bad).first_failure.item == "re-proved"
    assert main(["check", "--quiet", str(outputs["scan"])]) == 0


def test_a_scan_rechecked_on_a_sample_is_not_confirmed(outputs, monkeypatch):
    from rigor_gyro.margins import scan as scan_module
    calls = []
    real = scan_module.scan_task
    monkeypatch.setattr(scan_module, "scan_task", lambda *a: calls.append(a) or real(*a))
    results = scan_module.check_scan(_load(outputs["scan"]), max_points=2)
    assert len(calls) == 2 and '"n": "1"' in calls[0][1] and '"n": "100"' in calls[1][1]
    assert ("re-proved", False, "only a sample was re-proved (2 of 3 points, evenly spread, both ends): the other "
            "points are not verified (re-prove every point: the default)") in results
    calls.clear()
    assert ("re-proved", True, "all 3 points re-proved (status, reason, precision, quantities)") in \
        scan_module.check_scan(_load(outputs["scan"]))
    assert len(calls) == 3
