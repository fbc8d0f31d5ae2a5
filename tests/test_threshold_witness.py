"""Robust thresholds reach the requested width (issue 38): with the other parameters as a box, a step near the
threshold is refuted at a witness point of the box (a corner of an undecided leaf, then kept), where the paving
alone leaves the failing sliver undecided; the checker re-proves the witness and refuses one outside the box or
one where the claim holds."""
import json
from fractions import Fraction

import pytest

from rigor_gyro.check import check_file
from rigor_gyro.margins.threshold import find_threshold, write_threshold
from rigor_gyro.margins.threshold_witness import KEEP, Witnesses, _corners, in_box
from rigor_gyro.core.boxes import Box
from rigor_gyro.scene import parse_scene

from .test_margins import _agafonov_text

F = Fraction


@pytest.fixture(scope="module")
def robust(tmp_path_factory):
    """damping_condition with mu in [0.019, 0.021]: it holds for every mu of the box iff k > 0.021 A0 = 0.2667."""
    text = _agafonov_text(mu="[0.019, 0.021]") + '\n[claims]\nonly = ["damping_condition"]\n'
    res = find_threshold(parse_scene(text), "k", lo="0.1", hi="0.4", claim="damping_condition", width="1e-6")
    out = tmp_path_factory.mktemp("robust")
    write_threshold(res, str(out))
    return res, out / "margin_agafonov_box_k.json"


def test_the_robust_bracket_reaches_the_requested_width_and_holds_the_true_threshold(robust):
    res, _ = robust
    assert res.certified and not res.stopped
    lo, hi = res.bracket()
    assert lo <= F(2667, 10000) <= hi and hi - lo <= F(1, 10 ** 6) * hi
    step = next(s for s in res.steps if F(s["value"]) == res.refuted_at)
    assert step["witness"] == {"mu": "21/1000"}           # the failing corner of the box


def test_the_checker_re_proves_the_witness(robust, tmp_path):
    _, path = robust
    assert check_file(path).ok
    data = json.loads(path.read_text())
    step = next(s for s in data["steps"] if s["value"] == data["refuted_at"])
    for bad in ({"mu": "22/1000"}, {"mu": "19/1000"}, {"k": "1/10"}):
        step["witness"] = bad            # outside the box; inside but the claim holds there; not a box parameter
        (tmp_path / "bad.json").write_text(json.dumps(data))
        report = check_file(tmp_path / "bad.json")
        assert not report.ok, bad
        if bad == {"mu": "22/1000"}:     # refuted there too, so only the box test itself can say it is outside
            assert any("not a point of the other parameters' box" in r.message for r in report.results if not r.ok), \
                [r.message for r in report.results if not r.ok]


def test_witnesses_keep_the_most_recent_first_and_corners_cover_a_leaf():
    w = Witnesses()
    for i in range(KEEP + 2):
        w.keep({"a": F(i)})
    w.keep({"a": F(KEEP)})
    assert [p["a"] for p in w.points] == [KEEP, KEEP + 1, KEEP - 1, KEEP - 2]
    leaf = Box.of({"a": (F(0), F(1)), "b": (F(2), F(3)), "c": (F(5), F(5))})
    corners = _corners(leaf)
    assert len(corners) == 4 and all(in_box(leaf, c) for c in corners)
    assert {(c["a"], c["b"]) for c in corners} == {(0, 2), (0, 3), (1, 2), (1, 3)}
    assert not in_box(leaf, {"a": F(0), "b": F(2)}) and not in_box(leaf, {"a": F(2), "b": F(2), "c": F(5)})


def test_only_a_refuting_point_proof_makes_a_witness(monkeypatch):
    """An inconclusive (or proved) point proof at a corner never refutes the step nor becomes a witness."""
    from rigor_gyro.margins import threshold_witness as tw
    scene = parse_scene(_agafonov_text(mu="[0.019, 0.021]") + '\n[claims]\nonly = ["damping_condition"]\n')
    leaf = Box.of({"mu": (F(19, 1000), F(21, 1000))})
    for outcome in ("inconclusive", "proved"):
        monkeypatch.setattr(tw, "point_status", lambda *a, **k: (outcome, "stand-in"))
        w = Witnesses()
        assert w.refute(scene, "k", F(1, 4), "damping_condition", [leaf], None) is None and w.points == []
    calls = []

    def fake(scene, param, value, claim, point, seconds=None):
        calls.append(point)
        return ("refuted", "stand-in") if point["mu"] == F(21, 1000) else ("inconclusive", "stand-in")
    monkeypatch.setattr(tw, "point_status", fake)
    w = Witnesses()
    assert w.refute(scene, "k", F(1, 4), "damping_condition", [leaf], None)[0] == {"mu": F(21, 1000)}
    assert w.points == [{"mu": F(21, 1000)}] and calls == [{"mu": F(19, 1000)}, {"mu": F(21, 1000)}]
    calls.clear()                        # the kept witness is tried first, alone
    assert w.refute(scene, "k", F(1, 4), "damping_condition", None, None)[0] == {"mu": F(21, 1000)}
    assert calls == [{"mu": F(21, 1000)}]
