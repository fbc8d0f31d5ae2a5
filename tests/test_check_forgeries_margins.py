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
from tests.test_paving_search import SCENE


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


@pytest.fixture(scope="module")
def threshold():
    """rudenko1976's bracket_2 in Omega2: refuted at 1e-6, proved at 1, bisected to 1e-3."""
    return rg.find_threshold(rg.load_scene("rudenko1976"), "Omega2", lo="0.000001", hi="1", claim="bracket_2",
                             width="1e-3").to_json()


def test_the_genuine_threshold_checks(threshold):
    assert [s["status"] for s in threshold["steps"][:2]] == ["refuted", "proved"] and len(threshold["steps"]) > 6
    assert _failed(threshold) == []


def test_a_threshold_search_end_flipped_is_rejected(threshold):
    bad = copy.deepcopy(threshold)
    bad["steps"][0].update(status="proved", reason="bracket (8) holds at Omega2 = 1e-6, certified")
    items = {f.item for f in _failed(bad)}
    assert {"Omega2 = 0.000001", "search log"} <= items


def test_a_threshold_step_flipped_in_the_middle_is_rejected(threshold):
    bad = copy.deepcopy(threshold)
    k = 3                                   # neither an end nor the last step: the next midpoint depends on it
    bad["steps"][k]["status"] = {"proved": "refuted", "refuted": "proved"}[bad["steps"][k]["status"]]
    failed = _failed(bad)
    assert failed[0].item == "search log" and f"step {k + 2}:" in failed[0].message


def test_a_threshold_reason_at_its_proved_point_must_be_the_re_decisions(threshold):
    bad = copy.deepcopy(threshold)
    i = next(i for i, s in enumerate(bad["steps"]) if s["value"] == bad["proved_at"])
    bad["steps"][i]["reason"] = "omega_2 = 0.5 certified"
    failed = _failed(bad)
    assert [f.item for f in failed] == ["proved_at"] and "not the re-decision's own" in failed[0].message


def test_a_threshold_search_range_moved_is_rejected(threshold):
    bad = copy.deepcopy(threshold)
    bad["search"][1] = "2"
    bad["steps"][1]["value"] = "2"
    assert "search log" in {f.item for f in _failed(bad)}
    bad = copy.deepcopy(threshold)
    bad["stopped"] = "stopped by the user"
    assert "search log" in {f.item for f in _failed(bad)}


def test_a_threshold_cut_by_its_time_limit_still_checks(threshold):
    """A run stopped by --time-limit after 6 steps (written as find_threshold writes it; no timing in the test)."""
    from rigor_gyro.core.balls import interval_text
    from rigor_gyro.core.boxes import fraction_text
    from rigor_gyro.margins.threshold import statement
    data = copy.deepcopy(threshold)
    data["steps"] = data["steps"][:6]
    p, r = None, None
    for s in data["steps"]:
        if s["status"] == "proved":
            p = Fraction(s["value"]) if p is None or r is None or abs(Fraction(s["value"]) - r) < abs(p - r) else p
        else:
            r = Fraction(s["value"]) if r is None or p is None or abs(Fraction(s["value"]) - p) < abs(p - r) else r
    lo, hi = min(p, r), max(p, r)
    data.update(stopped="time limit of 5 s reached (--time-limit): the bracket certified so far is kept",
                certified=False, proved_at=fraction_text(p), refuted_at=fraction_text(r),
                bracket=[fraction_text(lo), fraction_text(hi)], bracket_decimal=list(interval_text(lo, hi)[:2]),
                statement=statement(data["claim"], data["param"], p, r))
    assert _failed(data) == []
    data["stopped"] = "the claim is inconclusive"
    assert [f.item for f in _failed(data)] == ["search log"]


# the counterexample search's scene (tests/test_paving_search.py) with a search and an estimate to forge
PAVING = (SCENE.replace('name = "cx_test"', 'name = "cx_forgery"', 1)
          + 'search_points = "4"\nmonte_carlo = "50"\n')


@pytest.fixture(scope="module")
def searched():
    from rigor_gyro.margins.paving import box_scene, pave
    from rigor_gyro.margins.report import paving_json
    from rigor_gyro.scene import parse_scene
    return paving_json(pave(box_scene(parse_scene(PAVING))))


def _paving_failures(data, change):
    from tests.forgery import reseal
    bad = copy.deepcopy(data)
    change(bad)
    return [r for r in check_certificate(reseal(bad)).results if not r.ok]


def test_the_genuine_searched_paving_checks(searched):
    c = searched["claims"][0]
    assert "stopped" not in searched and c["counterexample_search"]["proofs"] and c["monte_carlo"]["samples"] == 50
    assert _paving_failures(searched, lambda d: None) == []


@pytest.mark.parametrize("change, says", [
    (lambda c: c["counterexample_search"]["settings"].update(points=4000, samples=100000, sequence="sobol"),
     "the counterexample search's settings"),
    (lambda c: c["counterexample_search"].update(undecided_leaves=0), "the counterexample search's settings"),
    (lambda c: c["monte_carlo"].update(confidence=0.5), "the Monte Carlo estimate's"),
    (lambda c: c["counterexample_search"]["proofs"][0].update(
        probe={"refuted": "undecided", "undecided": "refuted"}[c["counterexample_search"]["proofs"][0]["probe"]]),
     "the probe gives"),
])
def test_a_paving_search_must_be_the_scenes_own(searched, change, says):
    failed = _paving_failures(searched, lambda d: change(d["claims"][0]))
    assert failed and failed[0].item == "bracket_1" and says in failed[0].message, failed


def test_the_paving_schema_closes_the_monte_carlo_estimate_and_the_search_proofs(searched):
    for change in (lambda c: c["monte_carlo"].update(note="no failing sample in 10^6 further samples"),
                   lambda c: c["counterexample_search"]["proofs"][0].update(verified_by="referee"),
                   lambda c: c["counterexample_search"]["proofs"][0].update(probe="proved")):
        failed = _paving_failures(searched, lambda d: change(d["claims"][0]))
        assert [f.item for f in failed] == ["schema"] or "schema" in {f.item for f in failed}, failed


@pytest.mark.parametrize("stop, pending", [("time limit of 5 s reached", None),
                                           ("time limit of 5 s reached (--time-limit)", None),
                                           ("time limit of 5 s reached (--time-limit)", []),
                                           ("stopped by Ctrl-C before the searches", [])])
def test_a_complete_paving_cannot_say_it_stopped(searched, stop, pending):
    def change(d):
        d["stopped"] = stop
        if pending is not None:
            d["pending"] = pending
    assert "stopped" in {f.item for f in _paving_failures(searched, change)}


def test_a_paving_stopped_early_checks_and_its_stop_text_is_pinned():
    from rigor_gyro.margins.paving import box_scene, pave
    from rigor_gyro.margins.report import paving_json
    from rigor_gyro.scene import parse_scene
    data = paving_json(pave(box_scene(parse_scene(PAVING)), box_budget=3))
    assert data["stopped"] == "box budget of 3 evaluations reached (--box-budget)" and data["pending"]
    assert _paving_failures(data, lambda d: None) == []
    failed = _paving_failures(data, lambda d: d.update(stopped="stopped by the referee"))
    assert "stopped" in {f.item for f in failed}
    failed = _paving_failures(data, lambda d: d.update(budget_exhausted=False))
    assert [f.item for f in failed] == ["stopped"]


def test_a_skipped_search_must_give_the_time_limit(searched):
    def change(d):
        d["claims"][0]["counterexample_search"] = {"skipped": "not needed: the claim holds"}
    failed = _paving_failures(searched, change)
    assert any("skipped for 'not needed" in f.message for f in failed), failed


def _curve(**kw):
    from rigor_gyro.margins.threshold_curve import find_curve
    return find_curve(rg.load_scene("rudenko1976"), "eps", "Omega2", claim="bracket_1", **kw).to_json()


@pytest.fixture(scope="module")
def curve():
    """Two cells of Omega2 in [0.6, 0.65], each bracketed to 1e-2 in eps."""
    return _curve(lo="1/2", hi="2", along_lo="0.6", along_hi="0.65", cells=2, width="1e-2", max_depth=0)


def test_the_genuine_curve_checks(curve):
    assert curve["certified"] and all(c["stopped"] == "" for c in curve["cells"])
    assert _failed(curve) == []


@pytest.mark.parametrize("change, item", [
    (lambda d: d.update(statement="for every Omega2 > 0 claim 'bracket_1' holds for every eps > 0 (certified)"),
     "statement"),
    (lambda d: d.update(search=["1/1000", "1000"]), "search"),
    (lambda d: d.update(search=["1/2", "1"]), "search"),
    (lambda d: d["cells"][0].update(stopped="stopped by the user"), "Omega2 in [0.6, 0.625] stopped"),
    (lambda d: d.update(stopped="stopped by the user"), "stopped"),
])
def test_a_curve_edited_outside_its_bands_is_rejected(curve, change, item):
    bad = copy.deepcopy(curve)
    change(bad)
    assert item in {f.item for f in _failed(bad)}


def test_a_curve_cell_left_mixed_or_without_a_band_says_so_truly():
    mixed = _curve(lo="1", hi="1.4", along_lo="0.5", along_hi="0.7", cells=1, width="1e-4", max_depth=0)
    cell = mixed["cells"][0]
    assert cell["stopped"].startswith("neither proved nor refuted over the whole cell at eps = ")
    assert _failed(mixed) == []
    bad = copy.deepcopy(mixed)
    bad["cells"][0]["stopped"] = "neither proved nor refuted over the whole cell at eps = 1"
    assert "Omega2 in [0.5, 0.7] stopped" in {f.item for f in _failed(bad)}
    none = _curve(lo="1.3", hi="1.4", along_lo="0.6", along_hi="0.65", cells=1, width="1e-2", max_depth=0)
    assert none["cells"][0]["band"] is None and _failed(none) == []
    bad = copy.deepcopy(none)
    bad["cells"][0]["stopped"] = "the pavings were not needed"
    assert "Omega2 in [0.6, 0.65] stopped" in {f.item for f in _failed(bad)}


@pytest.mark.parametrize("change", [lambda d: d.update(boxes_evaluated=d["boxes_evaluated"] + 1),
                                    lambda d: d.update(levels=12),
                                    lambda d: d.update(budget_exhausted=not d["budget_exhausted"])])
def test_a_complete_pavings_counters_are_its_sub_boxes_own(searched, change):
    assert [f.item for f in _paving_failures(searched, change)] == ["counters"]


def test_a_paving_of_another_version_or_with_more_software_keys_is_not_confirmed(searched):
    failed = _paving_failures(searched, lambda d: d["software"].update(rigor_gyro="9.9"))
    assert [f.item for f in failed] == ["software"] and "check it with the version that wrote it" in failed[0].message
    failed = _paving_failures(searched, lambda d: d["software"].update(checked_by="referee"))
    assert [f.item for f in failed] == ["schema"]


def test_a_margin_output_naming_a_built_in_scene_must_be_that_scene(scan5, threshold, curve):
    for data in (scan5, threshold, curve):
        assert data["scene"]["file"] == "builtin:rudenko1976"
        bad = copy.deepcopy(data)
        bad["scene"]["source"] = bad["scene"]["source"].replace("0.629", "0.0071")
        assert bad["scene"]["source"] != data["scene"]["source"]
        failed = _failed(bad)
        assert [f.item for f in failed] == ["scene"] and "differs from it in ['source']" in failed[0].message
    edited = rg.find_threshold(_rudenko(Omega2="0.0071"), "eps", lo="0.01", hi="2", claim="bracket_1",
                               width="1e-2").to_json()
    assert edited["scene"]["file"] is None and _failed(edited) == []


def _rudenko(**params):
    import dataclasses
    s = rg.load_scene("rudenko1976")
    return dataclasses.replace(s, parameters={**s.parameters, **params})
