"""A scan's map (rigor_gyro.margins.scan): the exact points it proves at, the decimals that name them, its
lines, table and files, its limits and its domain check before any work.

tests/test_margins.py checks the statuses of a scan; what it writes (the table, the files, the decimals
naming each point) was not tested at all (proofs/mutation.md section 13).
"""
import json
from fractions import Fraction

import pytest

from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins import scan as scan_module
from rigor_gyro.margins.scan import MAX_POINTS, _d, run_scan, scan_points, write_scan
from rigor_gyro.scene import load_scene


@pytest.mark.parametrize("q, text", [
    (Fraction(1, 8), "0.125"), (Fraction(3, 40), "0.075"), (Fraction(-5, 2), "-2.5"), (Fraction(7), "7"),
    (Fraction(1200), "1200"), (Fraction(1, 3), "1/3"), (Fraction(1, 6), "1/6"),    # no decimal: the fraction
    (Fraction(10 ** 45 + 1, 10 ** 45), "1." + "0" * 44 + "1"),      # an exact decimal of 46 digits, exactly
    (Fraction(1, 5), "0.2"), (Fraction(4, 5), "0.8"),
    (Fraction(123456789012, 10 ** 11), "1.23456789012"),
])
def test_a_point_is_named_by_its_exact_decimal_when_it_has_one(q, text):
    assert _d(q) == text


def test_scan_points_are_exact_increasing_and_inside():
    assert scan_points(Fraction(0), Fraction(1), 5, False) == [0, Fraction(1, 4), Fraction(1, 2), Fraction(3, 4), 1]
    assert scan_points(Fraction(1), Fraction(1000), 4, True) == [1, 10, 100, 1000]
    assert scan_points(Fraction(1, 2), Fraction(50), 3, True) == [Fraction(1, 2), 5, 50]
    assert scan_points(Fraction(2), Fraction(3), 2, False) == [2, 3]
    # interior points that round (to 12 significant digits) onto an end are left out, never repeated
    one, tiny = Fraction(1), Fraction(1, 10 ** 13)
    assert scan_points(one, one + tiny, 5, False) == [one, one + tiny]
    assert scan_points(one - tiny, one, 5, False) == [one - tiny, one]


def _scan(**kw):
    return run_scan(load_scene("roitenberg1947"), "n", 3, lo="1", hi="100", claim="stable",
                    quantities=["stability_margin"], workers=1, **kw)


def test_a_scans_lines_table_and_files_say_what_each_point_proof_says(tmp_path):
    res = _scan()
    assert res.values == [1, Fraction(101, 2), 100] and res.counts() == {"stable": {"proved": 3, "refuted": 0,
                                                                                     "inconclusive": 0}}
    assert res.lines() == ["roitenberg1947: scan of n over [1, 100] (3 exact points; point proofs, nothing is "
                           "claimed between the points)", "  stable: proved at 3, refuted at 0, inconclusive at 0 "
                           "of 3 points"]
    md = res.markdown().splitlines()
    assert md[0] == "# " + res.lines()[0] and md[2] == "- " + res.lines()[1].strip()
    i = md.index("| n | stable | stability_margin |")
    assert md[i + 1] == "|---|---|---|"
    rows = md[i + 2:]
    assert len(rows) == 3
    for row, v, r in zip(rows, res.values, res.results):
        lo, hi = r["quantities"]["stability_margin"]
        assert Fraction(lo) <= Fraction(hi)
        assert row == f"| {_d(v)} | proved | [{lo}, {hi}] |"
    assert [row.split(" | ")[0] for row in rows] == ["| 1", "| 50.5", "| 100"]
    paths = sorted(write_scan(res, str(tmp_path)), key=lambda p: p.suffix)
    assert [p.name for p in paths] == ["scan_roitenberg1947_n.json", "scan_roitenberg1947_n.md"]
    assert json.loads(paths[0].read_text()) == json.loads(json.dumps(res.to_json()))
    assert paths[1].read_text() == res.markdown()
    data = res.to_json()
    assert [p["value"] for p in data["points"]] == ["1", "101/2", "100"]
    assert [p["claims"]["stable"]["status"] for p in data["points"]] == ["proved"] * 3
    assert data["counts"] == res.counts() and data["quantities"] == ["stability_margin"] and data["log"] is False


def test_a_log_scan_says_so_and_counts_each_outcome():
    res = run_scan(load_scene("stress_relay_H_1e4"), "n", 2, lo="50", hi="500", claim="stable", log=True)
    assert res.counts() == {"stable": {"proved": 1, "refuted": 1, "inconclusive": 0}}
    assert ", log-spaced;" in res.lines()[0]
    assert res.markdown().splitlines()[-2:] == ["| 50 | proved |", "| 500 | refuted |"]


def _no_work(*args):
    raise AssertionError("a point proof started")


def _stub(kind, params_json, options_json, claims, quantities):
    return {"claims": {c: {"status": "proved", "reason": ""} for c in claims}, "quantities": {}, "precision_bits": 64}


def test_the_largest_scan_allowed_has_max_points_and_one_more_is_refused(monkeypatch):
    monkeypatch.setattr(scan_module, "scan_task", _stub)
    res = run_scan(load_scene("roitenberg1947"), "n", MAX_POINTS, lo="1", hi="100", claim="stable", workers=1)
    assert len(res.values) == len(res.results) == MAX_POINTS
    with pytest.raises(ParameterError, match="--scan"):
        run_scan(load_scene("roitenberg1947"), "n", MAX_POINTS + 1, lo="1", hi="100", claim="stable", workers=1)


def test_a_log_scan_may_start_below_one(monkeypatch):
    monkeypatch.setattr(scan_module, "scan_task", _stub)
    res = run_scan(load_scene("roitenberg1947"), "n", 3, lo="0.5", hi="50", claim="stable", log=True, workers=1)
    assert res.values == [Fraction(1, 2), 5, 50]


@pytest.mark.parametrize("scene, param, lo, hi", [
    ("roitenberg1947", "n", "-1", "100"),          # only the lower end is outside (n > 0)
    ("agafonov2013", "x2_star", "0.5", "2"),       # only the upper end is outside (x2* < pi/2; 1.5 is inside)
])
def test_both_ends_are_in_the_domain_before_any_point_is_proved(monkeypatch, scene, param, lo, hi):
    monkeypatch.setattr(scan_module, "scan_task", _no_work)
    with pytest.raises(ParameterError, match="outside the kind's domain"):
        run_scan(load_scene(scene), param, 4, lo=lo, hi=hi, workers=1)
    monkeypatch.setattr(scan_module, "scan_task", _stub)
    inside = {"n": ("1", "100"), "x2_star": ("0.5", "1.5")}[param]
    assert len(run_scan(load_scene(scene), param, 4, lo=inside[0], hi=inside[1], workers=1).values) == 4
