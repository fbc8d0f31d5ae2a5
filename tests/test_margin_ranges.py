"""Quantity ranges over a box (rigor_gyro.margins.ranges): the stated numbers follow from the tiles'
and points' enclosures, and the checker re-derives them and rejects every edit.

A stand-in quantities module (exact closed forms over the eigenfrequency kind's (eps, Omega2) box) makes
the expected ranges known exactly, so these tests see the aggregation, the report and the checker, not
a kind's enclosures (each kind's own tests sample its enclosures in mpmath)."""
import json
import types
from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro.check import check_file
from rigor_gyro.core.box_values import BoxValue, QuantitySpec
from rigor_gyro.core.boxes import Box
from rigor_gyro.margins import paving as mpaving, ranges as mranges
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.margins.ranges import summarise
from rigor_gyro.margins.report import _render_ranges, paving_json, render_paving, write_paving
from rigor_gyro.scene import parse_scene

from .forgery import reseal

SCENE = """
name = "ranges_box"
kind = "eigenfrequencies"
source = "ranges over a small box"
[parameters]
a = "15.08"
b = "6.154"
eps = "[0.1, 0.12]"
Omega2 = "0.625 +- 0.025"
[claims]
only = ["roots"]
[options]
range_boxes = "24"
"""


def _fake_module():
    """q1 = eps + Omega2 (gradient 1, 1); margin m = 1 - 4 eps^2 - Omega2 (decreasing in both);
    'partial' enclosed only where eps <= 0.11."""
    specs = {"sum": QuantitySpec("eps + Omega2"),
             "m": QuantitySpec("the stand-in margin", claim="roots"),
             "partial": QuantitySpec("eps, where eps <= 0.11")}

    def quantities_box(model, box, names):
        e, o = box.ball("eps"), box.ball("Omega2")
        out = {"sum": BoxValue(e + o, {"eps": arb(1), "Omega2": arb(1)}),
               "m": BoxValue(1 - 4 * e * e - o, {"eps": -8 * e, "Omega2": arb(-1)})}
        if box.interval("eps")[1] <= Fraction(11, 100):
            out["partial"] = BoxValue(e)
        return {k: v for k, v in out.items() if k in names}
    return types.SimpleNamespace(BOX_QUANTITIES=specs, quantities_box=quantities_box)


@pytest.fixture
def fake(monkeypatch):
    mod = _fake_module()
    for m in (mranges, mpaving):
        monkeypatch.setattr(m, "quantities_module", lambda kind: mod)
    return mod


@pytest.fixture
def paving(fake):
    return pave(box_scene(parse_scene(SCENE)))


def _q(data, qid):
    return next(q for q in data["quantities"] if q["id"] == qid)


def test_outer_and_inner_ranges_bracket_the_exact_range(paving):
    data = paving_json(paving)
    s = _q(data, "sum")
    lo, hi = Fraction(s["outer"]["lo"]), Fraction(s["outer"]["hi"])
    exact_lo, exact_hi = Fraction(1, 10) + Fraction(6, 10), Fraction(12, 100) + Fraction(65, 100)
    assert lo <= exact_lo and hi >= exact_hi                      # outer contains the true range
    ilo, ihi = Fraction(s["inner"]["lo"]), Fraction(s["inner"]["hi"])
    assert exact_lo <= ilo <= ihi <= exact_hi                      # inner inside it
    assert (ihi - ilo) >= Fraction(9, 10) * (exact_hi - exact_lo)  # and not a sliver: the search widened it


def test_a_margins_worst_case_is_a_certified_lower_bound_with_a_small_gap(paving):
    m = _q(paving_json(paving), "m")
    true_min = 1 - 4 * Fraction(12, 100) ** 2 - Fraction(65, 100)
    w = m["worst_case"]
    assert Fraction(w["lower_bound"]) <= true_min <= Fraction(w["attained_at_most"])
    assert Fraction(w["relative_gap"]) <= Fraction(2, 100)
    sens = {s["parameter"]: s for s in m["sensitivities"]}
    assert sens["eps"]["monotone"] == "decreasing" and sens["Omega2"]["monotone"] == "decreasing"
    # effects: |dm/deps| <= 8 * 0.12 times 0.01, |dm/dOmega2| = 1 times 0.025: Omega2 ranks first
    assert [s["parameter"] for s in m["sensitivities"]] == ["Omega2", "eps"]


def test_a_quantity_enclosed_on_part_of_the_box_states_no_inner_range(paving):
    p = _q(paving_json(paving), "partial")
    assert Fraction(p["enclosed_fraction"]) == Fraction(1, 2)
    assert p["inner"] is None
    assert Fraction(p["outer"]["hi"]) >= Fraction(11, 100)


def test_the_report_leads_with_the_worst_case(paving):
    text = render_paving(paving_json(paving))
    head = text.split("## ")[0]
    assert "the stand-in margin >= " in head and "every value in the box lies in" in head


def test_summarise_uses_only_the_enclosures_given():
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    spec = {"q": QuantitySpec("q", claim="c")}
    left, right = whole.split(whole)
    tiles = [(left, {"q": {"value": ["-1", "2"], "gradient": {}}}), (right, {"q": {"value": ["0", "3"], "gradient": {}}})]
    points = [({"x": Fraction(1, 4)}, {"q": {"value": ["1/2", "1/2"], "gradient": {}}}),
              ({"x": Fraction(3, 4)}, {"q": {"value": ["5/2", "5/2"], "gradient": {}}})]
    (q,) = summarise(whole, spec, tiles, points)
    assert q["outer"] == {"lo": "-1", "hi": "3"}
    assert q["inner"] == {"lo": "0.5", "hi": "2.5"}
    assert q["worst_case"]["lower_bound"] == "-1" and q["worst_case"]["attained_at_most"] == "0.5"
    assert "sensitivities" not in q


def test_a_point_below_the_enclosed_parts_bound_is_reported_first_not_as_a_negative_gap(paving):
    """Where only part of the box was enclosed, a certified point value outside that part may lie below the part's
    lower bound: the report then leads with the point's value and says no bound over the whole box is certified
    (it printed ">= the part's bound for every parameter value in the box" with a negative gap)."""
    data = paving_json(paving)
    m = next(q for q in data["quantities"] if q.get("worst_case"))
    m["enclosed_fraction"] = "1/2"
    m["worst_case"].update(lower_bound="-0.25", attained_at_most="-0.5", gap="-0.25", relative_gap="-0.5")
    line = next(l for l in render_paving(data).splitlines() if l.startswith(f"- **{m['description']}"))
    assert ": a value <= -0.5 is attained at" in line and "below -0.25, the certified lower bound (on the 0.5 of" in line
    assert "no lower bound over the whole box is certified" in line and ">= -0.25**" not in line


def test_the_checker_confirms_the_ranges_and_rejects_each_edit(paving, fake, tmp_path):
    js, _ = write_paving(paving, tmp_path)
    rep = check_file(js)
    assert all(r.ok for r in rep.results), [r for r in rep.results if not r.ok]
    data = json.loads(js.read_text())

    def rejected(edit):
        d = json.loads(json.dumps(data))
        edit(d)
        p = tmp_path / "t.json"
        p.write_text(json.dumps(reseal(d)))
        bad = [r for r in check_file(p).results if not r.ok]
        return bad and any(r.item == "quantities" or "schema" in r.item for r in bad)

    assert rejected(lambda d: _q(d, "sum")["outer"].update(lo="0.71"))          # narrower than the truth
    assert rejected(lambda d: _q(d, "m")["worst_case"].update(lower_bound="0.3"))
    assert rejected(lambda d: _q(d, "sum")["inner"].update(hi="0.8"))
    assert rejected(lambda d: _q(d, "m")["sensitivities"][0].update(monotone="increasing"))
    assert rejected(lambda d: d["range_tiles"].pop())                            # no longer tiles the box
    assert rejected(lambda d: d["range_points"][0].update(eps="1/5"))            # outside the box
    assert rejected(lambda d: _q(d, "partial").update(enclosed_fraction="1"))


def test_a_pavings_point_proofs_keep_to_the_precisions_asked(tmp_path):
    """Issue 37 part 3: `prove --maxprec` bounds a paving's point proofs (they ran to 4096 bits before)."""
    from rigor_gyro.cli import main
    scene = tmp_path / "box.toml"
    scene.write_text(SCENE.replace('only = ["roots"]', 'only = ["bracket_2"]')
                     .replace('Omega2 = "0.625 +- 0.025"', 'Omega2 = "[0.0070, 0.0072]"')
                     .replace('range_boxes = "24"', 'range_boxes = "0"\nbox_resolution = "1/2"\nmax_points = "2"'))
    assert main(["prove", str(scene), "-q", "-o", str(tmp_path), "--prec", "32", "--maxprec", "48"]) in (1, 3)
    data = json.loads((tmp_path / "ranges_box.json").read_text())
    assert data["settings"]["point_prec"] == 32 and data["settings"]["point_maxprec"] == 48
    points = [p for c in data["claims"] for p in c["points"]]
    assert points and all(p["precision_bits"] <= 48 for p in points)
    assert check_file(tmp_path / "ranges_box.json").ok


def test_a_threshold_without_a_claim_asks_for_one_unless_the_scene_has_one():
    from rigor_gyro.core.errors import ParameterError
    from rigor_gyro.margins.threshold import find_threshold
    from rigor_gyro.scene import load_scene
    with pytest.raises(ParameterError, match="--claim CLAIM.*damping_condition"):
        find_threshold(load_scene("agafonov2013"), "k")


def test_the_checker_re_evaluates_the_range_tiles_on_the_executor_it_is_given(paving, fake, tmp_path):
    """``rigor-gyro check -j N`` re-evaluates the range tiles and points on the workers (each once), and
    the re-derivation still rejects an edited range: the executor only says where the evaluations run."""
    js, _ = write_paving(paving, tmp_path)
    data = json.loads(js.read_text())
    seen = []

    class Recording:
        def map(self, fn, tasks):
            tasks = list(tasks)
            seen.append((fn.__name__, len(tasks)))
            return [fn(*t) for t in tasks]
    rep = check_file(js, executor=Recording())
    assert all(r.ok for r in rep.results), [r for r in rep.results if not r.ok]
    n = len(data["range_tiles"]) + len(data["range_points"])
    assert ("range_task", n) in seen
    _q(data, "sum")["outer"].update(lo="0.71")
    p = tmp_path / "t.json"
    p.write_text(json.dumps(reseal(data)))
    bad = [r for r in check_file(p, executor=Recording()).results if not r.ok]
    assert any(r.item == "quantities" for r in bad)


def _branch(key, unique, at_centre, centre, gradient):
    return {"key": key, "unique_in": unique, "at_centre": at_centre, "centre": {"x": centre}, "gradient": {"x": gradient}}


def _two_tiles(right_unique, right_gradient=("1", "2")):
    """Two tiles of x in [0, 1] measuring an object chosen per tile (a ``branch``). Left: key 3/2 at its centre
    1/4, gradient [1, 2], so over the common point x = 1/2 its key is in [7/4, 2]; its unique_in [1, 2]. Right: key
    5/2 at 3/4 with ``right_gradient``, over x = 1/2 in [2, 9/4] for the default; its unique_in ``right_unique``.
    Point values 1/2 at x = 1/4 and 5/2 at x = 3/4; gradients of certain sign."""
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    left, right = whole.split(whole)
    lb = _branch(["1", "2"], ["1", "2"], ["3/2", "3/2"], "1/4", ["1", "2"])
    rb = _branch(["3/2", "4"], right_unique, ["5/2", "5/2"], "3/4", list(right_gradient))

    def v(lo, hi, branch):
        return {"q": {"value": [lo, hi], "gradient": {"x": ["1", "2"]}, "branch": branch}}
    tiles = [(left, v("0", "2", lb)), (right, v("1", "3", rb))]
    points = [({"x": Fraction(1, 4)}, {"q": {"value": ["1/2", "1/2"], "gradient": {}}}),
              ({"x": Fraction(3, 4)}, {"q": {"value": ["5/2", "5/2"], "gradient": {}}})]
    (q,) = summarise(whole, {"q": QuantitySpec("q")}, tiles, points)
    return q


def test_tiles_whose_branches_agree_state_the_inner_range_and_the_sensitivities():
    # the left key over x = 1/2, [7/4, 2], lies in the right's unique_in (its whole-tile enclosure [1, 2] does not)
    q = _two_tiles(["7/4", "5"])
    assert q["inner"] == {"lo": "0.5", "hi": "2.5"} and q["sensitivities"][0]["monotone"] == "increasing"
    assert "branches" not in q


def test_tiles_whose_branches_are_not_shown_to_agree_state_no_inner_range_and_no_sensitivities():
    # two orbits may coexist on the common face (a fold between the centres): nothing joins the tiles
    q = _two_tiles(["1.8", "5"])            # [7/4, 2] not inside [1.8, 5]; [2, 9/4] not inside [1, 2]
    assert q["inner"] is None and "sensitivities" not in q and "no inner range" in q["branches"]
    assert q["outer"] == {"lo": "0", "hi": "3"}          # the outer range still holds tile by tile
    # the other direction suffices: with gradient [2, 4] the right key over x = 1/2 is [3/2, 2], inside [1, 2]
    assert _two_tiles(["1.8", "5"], ("2", "4"))["inner"] is not None


def test_branches_are_checked_on_every_touching_pair_only():
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    a, rest = whole.split(whole)
    b, c = rest.split(whole)
    near = lambda lo, hi: _branch([lo, hi], [lo, hi], [lo, lo], "1/2", ["0", "0"])
    val = lambda br: {"value": ["0", "1"], "gradient": {}, "branch": br}    # one quantity's values on a tile
    # a and c choose different objects, but do not touch: b agrees with both
    b_branch = _branch(["1", "1"], ["0", "20"], ["1", "1"], "5/8", ["0", "0"])
    assert mranges.one_branch([(a, val(near("1", "1"))), (b, val(b_branch)), (c, val(near("10", "10")))])
    # a and b touch and do not agree
    assert not mranges.one_branch([(a, val(near("10", "10"))), (b, val(near("1", "1"))), (c, val(near("1", "1")))])
    # a tile whose object was not located (branch None) beside tiles that were: not joined
    assert not mranges.one_branch([(a, val(near("1", "1"))), (b, val(None))])
    # no branch anywhere: a function of the parameters
    assert mranges.one_branch([(a, {"value": ["0", "1"], "gradient": {}}), (b, {"value": ["0", "1"], "gradient": {}})])


def test_the_report_says_why_a_range_has_no_inner_part():
    q = _two_tiles(["1.8", "5"])
    lines = _render_ranges({"quantities": [q], "range_tiles": [{}, {}]})
    row = next(x for x in lines if x.startswith("| q: q |"))
    assert row.split("|")[4].strip() == "-"              # no inner range in the table
    assert any(x.startswith("- q: ") and "no inner range" in x for x in lines)


def test_a_branch_key_over_the_common_part_keeps_its_gradient_term():
    """The left tile's key is 3/2 at its centre x = 1/4 and moves by [1, 2] per unit: at the common point x = 1/2 it
    is in [7/4, 2], outside the right tile's unique_in [1.4, 1.6], though its centre value 3/2 is inside. The
    right key there, 3/2, is outside the left's unique_in [1.7, 2.1]: the tiles are not shown to agree."""
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    left, right = whole.split(whole)
    lb = _branch(["1", "2"], ["1.7", "2.1"], ["3/2", "3/2"], "1/4", ["1", "2"])
    rb = _branch(["1.45", "1.55"], ["1.4", "1.6"], ["3/2", "3/2"], "3/4", ["0", "0"])
    val = lambda br: {"value": ["0", "1"], "gradient": {}, "branch": br}
    assert not mranges.one_branch([(left, val(lb)), (right, val(rb))])
    assert mranges._key_over(lb, Box.of({"x": (Fraction(1, 2), Fraction(1, 2))})) == (Fraction(7, 4), Fraction(2))
