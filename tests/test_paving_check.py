"""The paving checker (rigor_gyro.margins.check) check by check.

Each alteration of a genuine paving (resealed, so the digest holds) must fail exactly the check that is
there for it, with its message; genuine pavings with proved, refuted and undecided sub-boxes, point
proofs, and an edge that is never split are confirmed. (tests/test_margins.py asks only that a tampered
paving is rejected somewhere: with several checks failing at once, any one of them weakened went
unnoticed; see proofs/mutation.md section 13.)
"""
import json

import pytest

from rigor_gyro.check import check_certificate
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.margins.report import paving_json
from rigor_gyro.scene import Scene, load_scene, parse_scene
from tests.forgery import failures as _failures, reseal as _reseal
from tests.test_margins import RUDENKO_BOX


def _paving(text: str) -> dict:
    return paving_json(pave(box_scene(parse_scene(text))))


def _proved():
    """Two claims, each proved on every sub-box."""
    return _paving(RUDENKO_BOX.replace('only = [', 'only = ["bracket_1", "bracket_2"] #'))


def _refuted():
    """bracket (8) fails on every sub-box; its point proofs (one since the small-Omega2 roots are enclosed by sign changes), each refuted."""
    return _paving(RUDENKO_BOX.replace('"[0.1, 0.12]"', '"0.1076"').replace('"0.625 +- 0.025"', '"[0.001, 0.005]"')
                   .replace('only = [', 'only = ["bracket_2"] #'))


def _undecided():
    """Bracket (9) undecided on every sub-box at resolution 1/2 (eps in [0.1, 2]); the point proofs prove it."""
    return _paving(RUDENKO_BOX.replace('only = [', 'only = ["bracket_3"] #').replace('"1/16"', '"1/2"')
                   .replace('"[0.1, 0.12]"', '"[0.1, 2]"'))


def _mixed():
    """bracket (8) proved on some sub-boxes, undecided on others."""
    return _paving(RUDENKO_BOX.replace('"[0.1, 0.12]"', '"0.1076"').replace('"0.625 +- 0.025"', '"[0.001, 0.2]"')
                   .replace('only = [', 'only = ["bracket_2"] #'))


def test_genuine_pavings_with_every_kind_of_sub_box_are_confirmed():
    for make, statuses, points in [(_proved, {"proved"}, set()), (_refuted, {"refuted"}, {("refuted", "refuted")}),
                                   (_undecided, {"undecided"}, {("undecided", "proved")}),
                                   (_mixed, {"proved", "undecided"}, {("undecided", "proved")})]:
        data = make()
        assert {b["status"] for c in data["claims"] for b in c["boxes"]} == statuses, make.__name__
        assert {(p["box_outcome"], p["status"]) for c in data["claims"] for p in c["points"]} == points
        report = check_certificate(data)
        assert report.ok, (make.__name__, report.first_failure)
        messages = [r.message for r in report.results]
        assert "every decided sub-box re-evaluated" in messages
        assert any(m.endswith("point proofs re-run") for m in messages)


def test_a_paving_with_an_edge_never_split_is_confirmed():
    """S is an amplitude parameter of the relay kind: never split, so the sub-boxes are the leaves of a
    bisection tree along H alone (a checker that also splits S would not find them)."""
    base = load_scene("roitenberg1947")
    s = Scene(name="frozen", kind=base.kind, source="test",
              parameters={**base.parameters, "S": "[0.14, 0.16]", "H": "[100, 200]"},
              claims_only=["stable"], options={"box_resolution": "1/2", "range_boxes": "0"})
    data = paving_json(pave(box_scene(s)))
    c = data["claims"][0]
    assert data["settings"]["unsplit"] == ["S"] and len(c["boxes"]) >= 2     # H split (two undecided boxes: ~1 s)
    assert {tuple(b["box"]["S"]) for b in c["boxes"]} == {("7/50", "4/25")}
    assert _failures(data) == []
    assert any(ln.startswith("Not split: S (the box claims do not depend on it") for ln in _report_lines(data))


def test_the_checker_rebuilds_the_tree_without_splitting_a_frozen_edge():
    """Two levels of H-only bisection with S frozen tile the box for the checker; the same leaves are not a
    tree of Box.split's rule when S may be split (after one H split, S is the relatively widest edge), so
    a checker that forgets the frozen edges rejects every such paving deeper than one split."""
    from fractions import Fraction as F
    from rigor_gyro.core.boxes import Box
    from rigor_gyro.margins.check import _tiles
    whole = Box.of({"H": (F(100), F(200)), "S": (F(7, 50), F(4, 25))})
    leaves = [Box.of({"H": (F(100 + 25 * i), F(125 + 25 * i)), "S": (F(7, 50), F(4, 25))}) for i in range(4)]
    assert _tiles(whole, leaves, ("S",))
    assert not _tiles(whole, leaves)                     # the rule without the frozen edge splits S second
    assert not _tiles(whole, leaves[:3], ("S",))         # a leaf missing


def _claim(data, i=0):
    return data["claims"][i]


def _last_proved(claim):
    statuses = [b["status"] for b in claim["boxes"]]
    i = len(statuses) - 1 - statuses[::-1].index("proved")
    assert "undecided" in statuses[:i]
    return claim["boxes"][i]


ALTERATIONS = {
    # name: (paving, change, the failing checks as (item, a fragment of the message))
    "scene source, not resealed": (_proved, lambda d: d["scene"].update(source="another source"),
                                   [("integrity", "digest does not match")]),
    "a box scene no longer": (_proved, lambda d: d["scene"]["parameters"].update(eps="[0.12, 0.1]"),
                              [("scene", "not a valid box scene")]),
    "box": (_proved, lambda d: d["box"]["eps"].__setitem__(1, "1/8"), [("box", "re-derived")]),
    "settings": (_proved, lambda d: d["settings"].update(max_boxes=7), [("settings", "re-derived")]),
    "claims reordered": (_proved, lambda d: d["claims"].reverse(), [("claims", "claims")]),
    "a point claim listed as not decided over boxes": (_proved, lambda d: d["not_box_claims"].append("roots"),
                                                       [("claims", "not decided over boxes are")]),
    "statement": (_proved, lambda d: _claim(d).update(statement=_claim(d)["statement"] + " Also for eps = 1."),
                  [("bracket_1", "not the kind's box statement")]),
    "unknown sub-box status": (_proved, lambda d: _claim(d)["boxes"][0].update(status="maybe"),
                               [("bracket_1", "unknown sub-box status"),
                                ("schema", "$.claims[0].boxes[0].status: 'maybe' is not one of")]),
    "the last proved sub-box relabelled refuted": (       # after undecided ones: each decided box is re-evaluated
        _mixed, lambda d: _last_proved(_claim(d)).update(status="refuted"),
        [("bracket_2", "volume fractions or sub-box counts"), ("bracket_2", "stored refuted, re-evaluated proved"),
         ("bracket_2", "the point prover proved the claim at the midpoint"),
         ("bracket_2", "not the midpoints"), ("bracket_2", "but the sub-boxes give 'refuted'"),
         ("verdict", "verdict")]),
    "a proved sub-box dropped": (_mixed, lambda d: _claim(d)["boxes"].remove(_last_proved(_claim(d))),
                                 [("bracket_2", "do not tile"), ("bracket_2", "volume fractions or sub-box counts")]),
    "volume fraction": (_mixed, lambda d: _claim(d)["volume_fraction"].update(proved="1/3"),
                        [("bracket_2", "volume fractions or sub-box counts")]),
    "a sub-box count": (_mixed, lambda d: _claim(d)["sub_boxes"].update(proved=_claim(d)["sub_boxes"]["proved"] + 1),
                        [("bracket_2", "volume fractions or sub-box counts")]),
    "a decimal volume fraction": (_mixed, lambda d: _claim(d)["volume_fraction_decimal"].update(proved="1"),
                                  [("bracket_2", "volume fractions or sub-box counts")]),
    "a point's status": (_refuted, lambda d: _claim(d)["points"][-1].update(status="inconclusive"),
                         [("bracket_2", "stored inconclusive, re-proved refuted")]),
    "a point moved": (_undecided, lambda d: _claim(d)["points"][0]["point"].update(eps="11/100"),
                      [("bracket_3", "not the midpoints")]),
    "a point dropped": (_refuted, lambda d: _claim(d)["points"].pop(), [("bracket_2", "not the midpoints")]),
    "every point dropped, no time limit": (_refuted, lambda d: _claim(d)["points"].clear(),
                                           [("bracket_2", "not the midpoints")]),
    "a refuted claim relabelled inconclusive": (_refuted, lambda d: _claim(d).update(status="inconclusive"),
                                                [("bracket_2", "but the sub-boxes give 'refuted'")]),
    "an undecided claim relabelled proved": (_undecided, lambda d: _claim(d).update(status="proved"),
                                             [("bracket_3", "but the sub-boxes give 'inconclusive'")]),
    "a mixed claim relabelled proved": (_mixed, lambda d: _claim(d).update(status="proved"),
                                        [("bracket_2", "but the sub-boxes give 'inconclusive'")]),
    "verdict proved for refuted": (_refuted, lambda d: d.update(verdict="proved"), [("verdict", "verdict")]),
    "verdict refuted for proved": (_proved, lambda d: d.update(verdict="refuted"), [("verdict", "verdict")]),
    "verdict proved for inconclusive": (_undecided, lambda d: d.update(verdict="proved"), [("verdict", "verdict")]),
    # the texts the report prints as what the paving holds (issue 36: these were confirmed unread)
    "point parameters changed, the scene not": (_proved, lambda d: d["point_parameters"].update(a="15.09"),
                                                [("point_parameters", "not the scene's values")]),
    "a point proof's reason forged": (_refuted, lambda d: _claim(d)["points"][0].update(
        reason="f(t) <= 0 at the point t = 3 (a forged counterexample)"), [("bracket_2", "stored reason or precision")]),
    "a point proof's precision": (_refuted, lambda d: _claim(d)["points"][-1].update(precision_bits=16),
                                  [("bracket_2", "stored reason or precision")]),
    "the proved sub-boxes' reason forged": (_proved, lambda d: _claim(d)["reasons"].update(proved="holds by symmetry"),
                                            [("bracket_1", "stored reasons are not")]),
    "the refuted sub-boxes' reason forged": (_refuted, lambda d: _claim(d)["reasons"].update(refuted="omega_2 = 7"),
                                             [("bracket_2", "stored reasons are not")]),
    "the undecided reason forged": (_mixed, lambda d: _claim(d)["reasons"].update(undecided="budget"),
                                    [("bracket_2", "stored reasons are not")]),
    "a reason added for a status no sub-box has": (_proved, lambda d: _claim(d)["reasons"].update(refuted="x"),
                                                   [("bracket_1", "stored reasons are not")]),
}


@pytest.mark.parametrize("name", sorted(ALTERATIONS))
def test_each_alteration_fails_exactly_its_own_check(name):
    make, change, expected = ALTERATIONS[name]
    data = json.loads(json.dumps(make()))
    change(data)
    if name.endswith("not resealed"):
        got = _failures(data)
    else:
        got = _failures(_reseal(data))
        assert not any(item == "integrity" for item, _ in got)
    assert len(got) == len(expected), got
    for (item, message), (want_item, fragment) in zip(got, expected):
        assert item == want_item and fragment in message, (got, expected)


def test_an_unknown_status_in_one_claim_leaves_the_next_claim_checked():
    data = _proved()
    _claim(data)["boxes"][0]["status"] = "maybe"
    results = check_certificate(_reseal(data)).results
    second = [r for r in results if r.item == "bracket_2"]
    assert second and all(r.ok for r in second)
    assert any(r.message == "every decided sub-box re-evaluated" for r in second)


def test_a_paving_whose_data_cannot_be_read_fails_at_data():
    data = _proved()
    del _claim(data)["boxes"][0]["box"]
    report = check_certificate(_reseal(data), "p.json")
    assert report.file == "p.json" and 0 < report.seconds < 60
    assert [(r.item, r.ok) for r in report.results][-2:] == [("data", False), ("schema", False)]
    assert "cannot be checked: KeyError" in report.results[-2].message
    assert "$.claims[0].boxes[0]: missing 'box'" in report.results[-1].message


def test_a_pavings_counters_and_budget_are_what_it_did():
    data = _undecided()                     # resolution 1/2: the whole box, 2 halves, 4 quarters
    assert (data["boxes_evaluated"], data["levels"], data["budget_exhausted"]) == (7, 3, False)
    short = _paving(RUDENKO_BOX.replace('only = [', 'only = ["bracket_3"] #').replace('"[0.1, 0.12]"', '"[0.1, 2]"')
                    .replace('box_resolution = "1/16"', 'box_resolution = "1/16"\nmax_boxes = "7"'))
    assert short["budget_exhausted"] is True and short["boxes_evaluated"] <= 7
    assert _failures(short) == []


def test_a_degenerate_edge_is_a_point_of_every_proof():
    """eps = [0.1076, 0.1076]: a point, not an edge of the box, and every point proof takes eps there."""
    data = _paving(RUDENKO_BOX.replace('"[0.1, 0.12]"', '"[0.1076, 0.1076]"').replace('"0.625 +- 0.025"', '"[0.001, 0.005]"')
                   .replace('only = [', 'only = ["bracket_2"] #'))
    c = _claim(data)
    assert c["status"] == "refuted" and c["points"]
    assert all(p["point"]["eps"] == "269/2500" for p in c["points"])
    assert list(data["box"]) == ["Omega2"] and data["point_parameters"]["eps"] == "269/2500"
    assert _failures(data) == []


def _report_lines(data: dict) -> list[str]:
    from rigor_gyro.margins.report import render_paving
    return render_paving(data).splitlines()


@pytest.mark.parametrize("make", [_proved, _refuted, _undecided, _mixed], ids=["proved", "refuted", "undecided", "mixed"])
def test_the_report_states_what_the_paving_holds_answer_first(make):
    """The Markdown report: the verdict and the box first, then per claim its status, its volume fractions
    and sub-box counts (the data's own, which the checker re-derives), the first certified counterexample
    with how many points were re-proved refuted, the undecided sub-boxes' midpoints by outcome, and the
    settings with the budget."""
    data = make()
    lines = _report_lines(data)
    assert lines[0].startswith(f"# {data['scene']['name']}: {data['verdict'].upper()} over the box ")
    from fractions import Fraction
    from rigor_gyro.margins.report import decimal_text
    for k, (lo, hi) in data["box"].items():
        assert f"{k} in [{decimal_text(Fraction(lo), 10)}, {decimal_text(Fraction(hi), 10)}]" in lines[0]
    for c in data["claims"]:
        v, n = c["volume_fraction_decimal"], c["sub_boxes"]
        assert n == {k: sum(1 for b in c["boxes"] if b["status"] == k) for k in ("proved", "refuted", "undecided")}
        row = (f"| {c['id']} | **{c['status']}** | {v['proved']} | {v['refuted']} | {v['undecided']} | "
               f"{n['proved']}/{n['refuted']}/{n['undecided']} |")
        assert row in lines, (row, lines)
        assert f"## {c['id']}: {c['status']}" in lines
        refuted = [p for p in c["points"] if p["status"] == "refuted"]
        ce = [ln for ln in lines if ln.startswith("- certified counterexample")]
        if refuted:
            first = refuted[0]
            assert len(ce) == 1 and f"({len(refuted)} point(s) re-proved refuted; the first): " in ce[0]
            shown = [f"{k} = {val}" for k, val in first["point"].items() if k in data["box"]]
            assert shown and ", ".join(shown) in ce[0] and ce[0].endswith(f": {first['reason']}")
        else:
            assert not ce
        und = [p for p in c["points"] if p["box_outcome"] == "undecided"]
        mid = [ln for ln in lines if ln.startswith("- the midpoints of")]
        if und:
            counts = ", ".join(f"{s}: {sum(1 for p in und if p['status'] == s)}" for s in ("proved", "refuted", "inconclusive"))
            assert mid == [f"- the midpoints of {len(und)} undecided sub-box(es), proved point by point: {counts}"]
        else:
            assert not mid
    settings = next(ln for ln in lines if ln.startswith("Settings:"))
    n, lv = data["boxes_evaluated"], data["levels"]
    assert f"{n} {'box' if n == 1 else 'boxes'} evaluated in {lv} {'level' if lv == 1 else 'levels'}." in settings
    assert "budget was exhausted" not in settings


def test_the_report_says_when_the_budget_ran_out_and_which_edges_were_not_split():
    short = _paving(RUDENKO_BOX.replace('only = [', 'only = ["bracket_3"] #').replace('"[0.1, 0.12]"', '"[0.1, 2]"')
                    .replace('box_resolution = "1/16"', 'box_resolution = "1/16"\nmax_boxes = "7"'))
    assert any(ln.startswith("Settings:") and ln.endswith("levels; the box budget was exhausted.")
               for ln in _report_lines(short))
    assert not any(ln.startswith("Not split:") for ln in _report_lines(short))


def test_the_paving_files_are_the_data_as_written_and_the_timings_beside_them(tmp_path):
    """write_paving: the JSON file is the data itself (one-space indent, non-ASCII kept, a final newline),
    the Markdown is the report, and the wall time goes to timings/<name>.json, never into the pair. The
    decimals for reading have six significant digits (the exact fractions sit beside them)."""
    from fractions import Fraction
    from rigor_gyro.margins.report import decimal_text, render_paving, write_paving
    assert [decimal_text(Fraction(1, 3)), decimal_text(Fraction(2, 3), 10), decimal_text(Fraction(1))] == \
        ["0.333333", "0.6666666667", "1"]
    text = RUDENKO_BOX.replace('only = [', 'only = ["bracket_1"] #').replace("the issue's example", "Руденко (1976)")
    p = pave(box_scene(parse_scene(text)))          # a source in Cyrillic: written as it is, not \u-escaped
    jpath, mpath = write_paving(p, tmp_path)
    data = paving_json(p)
    assert jpath.read_text(encoding="utf-8") == json.dumps(data, indent=1, ensure_ascii=False) + "\n"
    assert "Руденко" in jpath.read_text(encoding="utf-8") and "Руденко" in data["scene"]["source"]
    assert mpath.read_text(encoding="utf-8") == render_paving(data)
    timings = json.loads((tmp_path / "timings" / jpath.name).read_text())
    assert set(timings) == {"total_s", "executor"} and timings["executor"] == p.executor
    assert timings["total_s"] == round(p.seconds, 3) and "total_s" not in jpath.read_text()


def test_a_box_rigour_that_proves_a_false_claim_is_caught_by_the_point_prover(monkeypatch):
    """The issue-36 scenario: a bug in the kind's box code (here: every box 'proved') is re-evaluated by
    that same code, and confirmed by it; the point prover, asked at sampled points of the decided
    sub-boxes, refutes the claim there and the check fails, naming the sub-box."""
    from rigor_gyro.kinds.eigenfrequencies import boxes
    text = (RUDENKO_BOX.replace('"[0.1, 0.12]"', '"0.1076"').replace('"0.625 +- 0.025"', '"[0.001, 0.005]"')
            .replace('only = [', 'only = ["bracket_2"] #'))
    assert _refuted()["claims"][0]["status"] == "refuted"          # (8) fails on this box
    monkeypatch.setattr(boxes, "evaluate_box", lambda model, box, claims: {c: ("proved", "sabotaged") for c in claims})
    data = _paving(text)
    assert data["claims"][0]["status"] == "proved"
    got = _failures(data)
    assert [item for item, _ in got] == ["bracket_2"], got
    assert "the point prover refuted the claim at the midpoint" in got[0][1]
    assert "the box rigour and the point rigour disagree" in got[0][1]


def test_the_point_prover_cross_check_can_be_turned_off_and_says_so():
    from rigor_gyro.check import check_certificate as check
    data = _proved()
    on = [r.message for r in check(data).results]
    off = [r.message for r in check(data, samples=0).results]
    assert sum("the point prover (code apart from the box rigour) agrees at 3 of 3 points" in m for m in on) == 2
    assert sum("not cross-checked by the point prover" in m for m in off) == 2
