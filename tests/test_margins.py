"""Tolerance boxes, pavings and thresholds (rigor_gyro.margins, core.boxes, core.family_roots,
kinds/eigenfrequencies/boxes)."""
import json
import random
import re
from fractions import Fraction

import pytest
from flint import arb, fmpq
from hypothesis import given, strategies as st

from rigor_gyro.cli import main
from rigor_gyro.core.balls import interval, working_precision
from rigor_gyro.core.boxes import Box, parse_tolerance, split_parameters
from rigor_gyro.core.errors import ParameterError, SceneError
from rigor_gyro.core.family_roots import family_real_roots
from rigor_gyro.kinds.eigenfrequencies import validate
from rigor_gyro.kinds.eigenfrequencies.boxes import BOX_CLAIMS, _bounds_status, evaluate_box
from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.margins.report import paving_json
from rigor_gyro.margins.threshold import find_threshold
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import Scene, load_scene, parse_scene

from .forgery import reseal

RUDENKO_BOX = """
name = "rudenko_box"
kind = "eigenfrequencies"
source = "the issue's example: each bracket (7)-(10) for every eps in [0.1, 0.12] and Omega2 in [0.6, 0.65]"
[parameters]
a = "15.08"
b = "6.154"
eps = "[0.1, 0.12]"
Omega2 = "0.625 +- 0.025"
[claims]
only = ["roots", "nu_ordering", "branches", "bracket_1", "bracket_2", "bracket_3", "bracket_4"]
[options]
box_resolution = "1/16"
range_boxes = "0"
"""


# ----------------------------------------------------------------------------- boxes

def test_tolerances_parse_exactly():
    assert parse_tolerance("[0.132, 0.134]", "B") == (Fraction(132, 1000), Fraction(134, 1000))
    assert parse_tolerance("0.15 +- 0.01", "S") == (Fraction(14, 100), Fraction(16, 100))
    assert parse_tolerance("1/3 +/- 1/6", "x") == (Fraction(1, 6), Fraction(1, 2))
    assert parse_tolerance("[2, 2]", "x") == (2, 2)
    assert parse_tolerance("2 +- 0", "x") == (2, 2)          # a zero radius is a point, like [2, 2]
    assert parse_tolerance("0.15", "S") is None


def test_a_degenerate_edge_does_not_count_in_the_volume():
    box = Box.of({"a": (Fraction(1), Fraction(1)), "b": (Fraction(0), Fraction(2)), "c": (Fraction(1, 3), Fraction(1))})
    assert box.volume() == Fraction(4, 3)
    assert Box.of({"a": (Fraction(1), Fraction(1))}).volume() == 1


@pytest.mark.parametrize("text", ["[0.2, 0.1]", "0.1 +- -0.01", "[pi, 4]", "[1, 2, 3]", "[1,]", "[x, 2]",
                                  "1 +- ", "[1e9999, 2]"])
def test_bad_tolerances_name_the_parameter(text):
    with pytest.raises(ParameterError, match="'q'"):
        parse_tolerance(text, "q")


@given(st.lists(st.tuples(st.fractions(-10, 10), st.fractions(0, 5)), min_size=1, max_size=3))
def test_a_split_covers_the_box_and_keeps_the_volume(edges):
    box = Box.of({f"p{i}": (lo, lo + w) for i, (lo, w) in enumerate(edges)})
    if all(w == 0 for _, w in edges):
        with pytest.raises(ValueError):
            box.split(box)
        return
    left, right = box.split(box)
    assert left.volume() + right.volume() == box.volume()
    cut = [n for n in box.names if left.interval(n) != box.interval(n)]
    assert len(cut) == 1
    for name in box.names:
        lo, hi = box.interval(name)
        assert left.interval(name)[0] == lo and right.interval(name)[1] == hi
        if name in cut:
            assert left.interval(name)[1] == right.interval(name)[0] == (lo + hi) / 2
        else:
            assert left.interval(name) == right.interval(name) == (lo, hi)
        assert lo <= box.midpoint()[name] <= hi
        with working_precision(64):
            b = box.ball(name)
            assert b.lower() <= arb(fmpq(lo.numerator, lo.denominator)) and arb(fmpq(hi.numerator, hi.denominator)) <= b.upper()


def test_split_parameters_keeps_points_as_written():
    points, box = split_parameters({"a": "15.08", "eps": "[0.1, 0.12]"})
    assert points == {"a": "15.08"} and box.names == ("eps",)


# ----------------------------------------------------------------------------- family roots

@given(st.fractions(Fraction(1, 10), 10), st.fractions(0, 1))
def test_family_roots_contain_every_members_root(c0, w):
    """x^2 - c for every c in [c0, c0 + w]: the positive root ball contains sqrt(c0) and sqrt(c0 + w)."""
    c1 = c0 + w
    with working_precision(64):
        c = arb(fmpq(c0.numerator, c0.denominator)).union(arb(fmpq(c1.numerator, c1.denominator)))
        r = family_real_roots([-c, arb(0), arb(1)], [-(c.mid().sqrt()), c.mid().sqrt()])
        if r is None:           # a family too wide for one Newton proof is undecided, never wrong
            return
        lo, hi = r[1].lower(), r[1].upper()
        assert lo.is_finite() and (lo * lo <= arb(fmpq(c0.numerator, c0.denominator)) or (lo * lo).overlaps(arb(fmpq(c0.numerator, c0.denominator))))
        assert hi.is_finite() and (hi * hi >= arb(fmpq(c1.numerator, c1.denominator)) or (hi * hi).overlaps(arb(fmpq(c1.numerator, c1.denominator))))
        assert r[0].upper() < 0 < r[1].lower()


def test_family_roots_refuse_a_double_root_and_a_zero_leading_coefficient():
    with working_precision(64):
        assert family_real_roots([arb(1), arb(-2), arb(1)], [arb("0.9"), arb("1.1")]) is None    # (x-1)^2
        assert family_real_roots([arb(-1), arb(1), arb(0).union(arb(1))], [arb(1)]) is None


def test_the_complex_newton_image_must_lie_strictly_inside_the_candidate_in_each_coordinate():
    """The uniqueness test of newton_family_root_complex: the image strictly inside the candidate,
    below and above, in the real and the imaginary parts (touching or sticking out is no proof)."""
    from rigor_gyro.core.family_roots import _inside
    y = arb(0.5, 0.5)                                   # about [0, 1] (radii are rounded up)
    assert _inside(arb(0.5, 0.125), y)                  # about [0.375, 0.625]
    assert not _inside(y, y)                            # the same ends: not strictly inside
    for mid, rad in ((0.1875, 0.3125), (0.8125, 0.3125), (0.5, 1.5)):
        assert not _inside(arb(mid, rad), y), (mid - rad, mid + rad)     # out below, out above, around


def test_complex_family_roots_contain_every_members_root():
    """x^2 + c for every c in [1, 1.21]: the box found from i contains i and 1.1 i (the roots of the
    end members), and its real part contains 0."""
    from flint import acb
    from rigor_gyro.core.family_roots import newton_family_root_complex
    with working_precision(64):
        c = interval(arb(1), arb("1.21"))
        z = newton_family_root_complex([c, arb(0), arb(1)], acb(0, c.mid().sqrt()))
        assert z is not None and z.is_finite() and z.real.contains(0)
        assert z.imag.contains(arb(1)) and z.imag.contains(arb("1.1"))
        assert newton_family_root_complex([arb(1), arb(2), arb(1)], acb("-1", "0.01")) is None     # (x+1)^2


# ----------------------------------------------------------------------------- box decisions

def test_bounds_status_decides_only_when_certain():
    one, two = arb(1), arb(2)
    wide = arb(1).union(arb(3))
    assert _bounds_status([("x", one, arb("1.5"), two)])[0] == "proved"
    assert _bounds_status([("x", one, arb(1), two)])[0] == "proved"              # lo <= x is inclusive
    assert _bounds_status([("x", one, arb(3), two)])[0] == "refuted"
    assert _bounds_status([("x", one, arb("0.5"), two)])[0] == "refuted"
    assert _bounds_status([("x", one, wide, two)])[0] == "undecided"
    assert _bounds_status([("x", one, arb("1.5"), two), ("y", one, wide, two)])[0] == "undecided"
    assert _bounds_status([("x", one, arb(3), two), ("y", one, wide, two)])[0] == "refuted"


def _model():
    return validate(load_scene("rudenko1976"))


@pytest.mark.parametrize("seed", range(6))
def test_a_box_verdict_agrees_with_point_proofs_inside_it(seed):
    """Soundness against the point prover: a claim proved (refuted) over a random box is proved
    (refuted) at random exact points of it."""
    rng = random.Random(seed)
    m = _model()
    eps0, W0 = Fraction(rng.randint(1, 400), 1000), Fraction(rng.randint(1, 4000), 1000)
    box = Box.of({"eps": (eps0, eps0 * Fraction(1001, 1000)), "Omega2": (W0, W0 * Fraction(1001, 1000))})
    with working_precision(128):
        out = evaluate_box(m, box, list(BOX_CLAIMS))
    for _ in range(2):
        pt = {k: lo + (hi - lo) * Fraction(rng.randint(0, 100), 100) for k, lo, hi in box.edges}
        scene = Scene(name="pt", kind="eigenfrequencies", source="", parameters={
            "a": "15.08", "b": "6.154", "eps": f"{pt['eps'].numerator}/{pt['eps'].denominator}",
            "Omega2": f"{pt['Omega2'].numerator}/{pt['Omega2'].denominator}"})
        cert = prove_scene(scene)
        for cid, (status, _) in out.items():
            if status != "undecided":
                assert cert.claim(cid).status.value == status, (cid, pt)


# ----------------------------------------------------------------------------- pavings

def test_the_brackets_hold_on_the_issues_box_and_the_paving_is_executor_independent():
    bs = box_scene(parse_scene(RUDENKO_BOX))
    serial = paving_json(pave(bs, Executor(1)))
    assert serial["verdict"] == "proved"
    for c in serial["claims"]:
        assert c["status"] == "proved" and c["volume_fraction"]["proved"] == "1"
    with Executor(2) as pool:
        assert paving_json(pave(bs, pool)) == serial


def test_a_dask_local_cluster_gives_the_same_paving():
    pytest.importorskip("distributed")
    bs = box_scene(parse_scene(RUDENKO_BOX.replace('box_resolution = "1/16"', 'box_resolution = "1/4"')))
    serial = paving_json(pave(bs, Executor(1)))
    with Executor(2, scheduler="local") as ex:
        assert paving_json(pave(bs, ex)) == serial


def test_a_box_where_bracket_8_fails_is_refuted_with_reproved_counterexamples():
    text = RUDENKO_BOX.replace('"[0.1, 0.12]"', '"0.1076"').replace('"0.625 +- 0.025"', '"[0.001, 0.005]"')
    text = text.replace('only = [', 'only = ["bracket_2"] #')
    bs = box_scene(parse_scene(text))
    data = paving_json(pave(bs))
    c = data["claims"][0]
    assert data["verdict"] == "refuted" and c["status"] == "refuted"
    assert Fraction(c["volume_fraction"]["refuted"]) == 1
    assert c["points"] and all(p["status"] == "refuted" for p in c["points"])
    pt = c["points"][0]["point"]
    scene = Scene(name="pt", kind="eigenfrequencies", source="", parameters=pt, claims_only=["bracket_2"])
    assert prove_scene(scene).claim("bracket_2").status.value == "refuted"


def test_a_resolution_limit_never_refutes():
    """The general box (eps, Omega2 over decades) at resolution 1/2: bracket (9) stays undecided on every
    sub-box (the parametric forms decide the example's small box whole), and that never refutes."""
    text = RUDENKO_BOX.replace('only = [', 'only = ["bracket_3"] #').replace('"1/16"', '"1/2"')
    text = text.replace('"[0.1, 0.12]"', '"[0.001, 2]"').replace('"0.625 +- 0.025"', '"[0.001, 10]"')
    data = paving_json(pave(box_scene(parse_scene(text))))
    c = data["claims"][0]
    assert c["status"] == "inconclusive" and Fraction(c["volume_fraction"]["undecided"]) > 0
    assert all(p["status"] != "refuted" for p in c["points"])


@pytest.mark.parametrize("change, match", [
    (('hz_scale = "1"', 'hz_scale = "[1, 2]"'), "hz_scale"),
    (('b = "6.154"', 'b = "[0.5, 7]"'), "'b'"),
    (('box_resolution = "1/16"', 'box_resolution = "0"'), "box_resolution"),
    (('box_resolution = "1/16"', 'max_boxes = "0"'), "max_boxes"),
    (('only = [', 'only = ["approximations"] #'), "approximations"),
    (('eps = "[0.1, 0.12]"', 'eps = "[0.12, 0.1]"'), "'eps'"),
])
def test_bad_boxes_are_bad_input(change, match):
    text = RUDENKO_BOX.replace('[parameters]\n', '[parameters]\nhz_scale = "1"\n').replace(*change)
    with pytest.raises((ParameterError, SceneError), match=match):
        box_scene(parse_scene(text))


def _agafonov_text(**changes):
    from pathlib import Path
    import rigor_gyro
    src = (Path(rigor_gyro.__file__).parent / "scenes" / "agafonov2013.toml").read_text()
    src = src[:src.index("[paper]")]
    for k, v in changes.items():
        src = re.sub(rf'^{k} = "[^"]*"', f'{k} = "{v}"', src, flags=re.M)
    src = src.replace('name = "agafonov2013"', 'name = "agafonov_box"')
    return src.replace("[options]\n", '[options]\nrange_boxes = "0"\n') if "[options]" in src else \
        src + '\n[options]\nrange_boxes = "0"\n'      # these tests are about the claims, not the ranges


def test_a_parameter_the_kind_cannot_box_is_bad_input(tmp_path):
    (tmp_path / "s.toml").write_text(_agafonov_text(x2_star="[0.5, 0.52]"))
    assert main(["prove", str(tmp_path / "s.toml"), "--out", str(tmp_path / "o"), "--quiet"]) == 2
    assert not (tmp_path / "o").exists() or not list((tmp_path / "o").glob("*.json"))


def test_lyapunov_vdot_holds_for_every_k_in_the_issues_box():
    bs = box_scene(parse_scene(_agafonov_text(k="[0.35, 0.45]")))
    data = paving_json(pave(bs))
    assert {c["id"]: c["status"] for c in data["claims"]} == {
        "damping_condition": "proved", "vdot_nonpositive": "proved", "v_positive": "proved"}


def test_lyapunov_damping_paving_respects_the_closed_form_threshold():
    """damping_condition fails exactly for k <= mu A0 = 0.02 * 12.7 = 0.254 (mu < k/A0 binds): every
    refuted sub-box lies at or below it, every proved one at or above it."""
    bs = box_scene(parse_scene(_agafonov_text(k="[0.2, 0.3]") + '\n[claims]\nonly = ["damping_condition"]\n'))
    c = paving_json(pave(bs))["claims"][0]
    assert c["status"] == "refuted"
    edge = Fraction(254, 1000)
    for b in c["boxes"]:
        lo, hi = (Fraction(x) for x in b["box"]["k"])
        if b["status"] == "refuted":
            assert hi <= edge
        elif b["status"] == "proved":
            assert lo >= edge
    assert Fraction(c["volume_fraction"]["refuted"]) > Fraction(1, 2)
    assert all(p["status"] == "refuted" for p in c["points"] if p["box_outcome"] == "refuted")


def test_a_tiny_relay_box_decides_like_the_point_scene():
    from rigor_gyro.kinds.periodic_orbit import validate as relay_validate
    from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box as relay_box
    m = relay_validate(load_scene("roitenberg1947"))
    w = Fraction(1, 10 ** 9)
    box = Box.of({"B": (Fraction(133, 1000) * (1 - w), Fraction(133, 1000) * (1 + w)),
                  "S": (Fraction(15, 100) * (1 - w), Fraction(15, 100) * (1 + w))})
    with working_precision(128):
        out = relay_box(m, box, ["half_period", "orbit_genuine", "stable"])
    assert {k: v[0] for k, v in out.items()} == {"half_period": "proved", "orbit_genuine": "proved", "stable": "proved"}


def test_prove_writes_a_paving_pair(tmp_path):
    (tmp_path / "box.toml").write_text(RUDENKO_BOX)
    assert main(["prove", str(tmp_path / "box.toml"), "--out", str(tmp_path), "--quiet", "--workers", "1"]) == 0
    data = json.loads((tmp_path / "rudenko_box.json").read_text())
    assert data["schema"] == "rigor-gyro/paving/1" and data["verdict"] == "proved"
    assert "PROVED over the box" in (tmp_path / "rudenko_box.md").read_text()


# ----------------------------------------------------------------------------- thresholds

def test_the_omega2_below_which_bracket_8_fails_is_bracketed():
    res = find_threshold(load_scene("rudenko1976"), "Omega2", lo="1e-6", hi="1", claim="bracket_2", width="1e-6")
    assert res.certified and res.exit_code == 0
    lo, hi = res.bracket()
    assert hi - lo <= Fraction(1, 10 ** 6) * hi
    for value, want in ((res.proved_at, "proved"), (res.refuted_at, "refuted")):
        s = load_scene("rudenko1976")
        s.parameters["Omega2"] = f"{value.numerator}/{value.denominator}"
        s.claims_only = ["bracket_2"]
        assert prove_scene(s).claim("bracket_2").status.value == want


def test_a_threshold_search_without_a_change_is_inconclusive_not_refuted():
    res = find_threshold(load_scene("rudenko1976"), "Omega2", lo="0.1", hi="1", claim="bracket_4")
    assert not res.certified and res.exit_code == 3


def test_relay_thresholds_refuse_s_and_pi_ends():
    assert main(["margin", "roitenberg1947", "--param", "S", "--claim", "stable"]) == 2
    # the gains p and K enter only the amplitude K p S (flow.amplitude_similarity): no threshold either
    assert main(["margin", "roitenberg1947", "--param", "p", "--claim", "stable"]) == 2
    assert main(["margin", "roitenberg1947", "--param", "K", "--claim", "half_period"]) == 2
    assert main(["margin", "roitenberg1947", "--param", "K", "--claim", "initial_point"]) == 2
    assert main(["margin", "rudenko1976", "--param", "Omega2", "--lo", "pi/1000", "--hi", "1"]) == 2


def test_family_roots_must_come_back_in_the_guesses_order():
    with working_precision(64):
        coeffs = [arb(2), arb(-3), arb(1)]                   # (x - 1)(x - 2)
        assert family_real_roots(coeffs, [arb("0.9"), arb("2.1")]) is not None
        assert family_real_roots(coeffs, [arb("2.1"), arb("0.9")]) is None


@pytest.mark.parametrize("argv", [["--param", "hz_scale", "--claim", "bracket_1"], ["--param", "nope"],
                                  ["--param", "Omega2", "--lo", "1", "--hi", "0.5"],
                                  ["--param", "Omega2", "--lo", "-1", "--hi", "1"],
                                  ["--param", "Omega2", "--width", "0"]])
def test_bad_threshold_searches_are_bad_input(argv):
    assert main(["margin", "rudenko1976", *argv]) == 2


# ----------------------------------------------------------------------------- checking a paving

def _paving_data():
    text = RUDENKO_BOX.replace('only = [', 'only = ["bracket_1", "bracket_2"] #')
    return paving_json(pave(box_scene(parse_scene(text))))


def test_a_paving_is_confirmed_by_the_checker():
    from rigor_gyro.check import check_certificate
    report = check_certificate(_paving_data())
    assert report.ok, report.first_failure


@pytest.mark.parametrize("tamper", ["status", "drop_box", "volume", "verdict", "point", "point_elsewhere",
                                    "duplicate_box"])
def test_a_tampered_paving_is_rejected_even_with_a_fixed_digest(tamper):
    from rigor_gyro.check import check_certificate
    data = json.loads(json.dumps(_paving_data()))
    c = data["claims"][1]
    if tamper == "status":
        c["boxes"][0]["status"] = "refuted"
    elif tamper == "drop_box":
        c["boxes"].pop()
    elif tamper == "volume":
        c["volume_fraction"]["proved"] = "1/2"
    elif tamper == "verdict":
        data["verdict"] = "refuted"
    elif tamper == "point":
        c["points"].append({"box_outcome": "undecided", "point": {"a": "15.08", "b": "6.154", "eps": "1/10",
                                                                "Omega2": "3/5"}, "status": "refuted", "reason": "",
                            "precision_bits": 64})
    elif tamper == "duplicate_box":       # same volumes and statuses, but the boxes no longer tile
        same = [(i, j) for i, bi in enumerate(c["boxes"]) for j, bj in enumerate(c["boxes"])
                if i < j and bi["status"] == bj["status"] and
                Box.from_json(bi["box"]).volume() == Box.from_json(bj["box"]).volume()]
        if same:
            i, j = same[0]
            c["boxes"][i] = json.loads(json.dumps(c["boxes"][j]))
        else:                             # one box: two copies of its first half, the same total volume
            whole = Box.from_json(c["boxes"][0]["box"])
            half = whole.split(whole)[0].to_json()
            c["boxes"] = [{"box": half, "status": c["boxes"][0]["status"]}] * 2
    elif tamper == "point_elsewhere":     # a genuine refutation, but at other fixed parameters (review finding)
        c["points"].append({"box_outcome": "undecided", "point": {"a": "1.2", "b": "1.1", "eps": "11/100",
                                                                "Omega2": "5/8"}, "status": "refuted", "reason": "",
                            "precision_bits": 64})
        c["status"] = data["verdict"] = "refuted"
    assert not check_certificate(reseal(data)).ok
    assert not check_certificate(data).ok          # the digest alone already rejects it


def test_every_built_in_margin_scene_is_a_valid_box_scene():
    from rigor_gyro.scene import builtin_scenes
    scenes = builtin_scenes("margin")
    assert len(scenes) >= 5
    for name in scenes:
        bs = box_scene(load_scene(name))
        assert bs.claims and bs.box.edges


def test_the_built_in_lyapunov_tolerance_scene_is_proved():
    data = paving_json(pave(box_scene(load_scene("margin_agafonov_k_tolerance"))))
    assert data["verdict"] == "proved"


def test_a_paving_figure_is_an_image_with_content(tmp_path):
    pytest.importorskip("matplotlib")
    from rigor_gyro.margins.plots import paving_plots
    paths = paving_plots(_paving_data(), tmp_path)
    assert len(paths) == 2
    import matplotlib.image as mpimg
    img = mpimg.imread(paths[0])
    assert img.shape[0] > 100 and img.std() > 0.01


def test_the_audit_refutes_the_no_smallness_claim_with_a_point_below_the_threshold():
    """The row's counterexample Omega2 lies below the certified threshold of bracket (8) (~0.0071039)."""
    cert = prove_scene(load_scene("rudenko1976"))
    row = next(r for r in cert.paper if r.id == "general claim: no smallness assumption")
    assert row.status.value == "refuted" and "bracket (8)" in row.note
    w = Fraction(row.reading.split("Omega2 = ")[1].split(",")[0])
    assert w < Fraction(71039, 10 ** 7)
    s = load_scene("rudenko1976")
    s.parameters["Omega2"] = f"{w.numerator}/{w.denominator}"
    s.claims_only = ["bracket_2"]
    assert prove_scene(s).claim("bracket_2").status.value == "refuted"


@pytest.mark.slow
def test_the_h_where_a_multiplier_crosses_one_is_bracketed():
    """The planted knife edge: |mu| = 1 at H_c ~ 9623.03639881332791437 (secant at 320 bits); the
    certified threshold bracket must contain it."""
    from pathlib import Path
    corpus = Path(__file__).resolve().parent / "corpus" / "relay_multiplier_near_one.toml"
    res = find_threshold(load_scene(str(corpus)), "H", lo="9620", hi="9630", claim="stable", width="1e-7")
    assert res.certified
    lo, hi = res.bracket()
    assert lo < Fraction("9623.03639881332791437") < hi


@pytest.mark.parametrize("terms", [4, 12, 40])
def test_the_near_zero_series_encloses_g_whatever_its_length(terms):
    """Few terms make the tail bound carry the truncation: the enclosure must still contain the
    point spectrum's g and g' (computed without the series) at points up to its reach."""
    from rigor_gyro.kinds.periodic_orbit import validate as relay_validate
    from rigor_gyro.kinds.periodic_orbit.flow import NearZeroSeries, Spectrum, g_coeffs
    m = relay_validate(load_scene("roitenberg1947"))
    with working_precision(128):
        sp = Spectrum(m.params)
        nz = NearZeroSeries(sp.M, sp.e, arb(fmpq(m.params.S.p, m.params.S.q)), terms=terms)
        for frac in ("0.1", "0.4", "0.8"):
            t = (nz.reach * arb(frac)).mid()
            got = nz.coeffs(t, 3)
            want = g_coeffs(sp, t, 3)
            for g, w in zip(got, want):
                assert g.is_finite() and w.is_finite() and g.overlaps(w) and w.rad() < g.rad() + abs(w.mid()) * arb(2) ** -20, (terms, frac)
                assert (g - w).contains(0)
        assert nz.coeffs(nz.rho, 2) is None            # beyond its reach it declines


def test_the_whole_box_rule():
    """Proved only if every sub-box is; refuted if one is refuted or a point proof refutes; else
    inconclusive (a resolution limit never refutes)."""
    from rigor_gyro.margins.paving import ClaimPaving
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    left, right = whole.split(whole)
    def status(outcomes, points=()):
        c = ClaimPaving("c", "s", boxes=list(zip((left, right), outcomes)), points=[{"status": s} for s in points])
        return c.status
    assert status(["proved", "proved"]) == "proved"
    assert status(["proved", "undecided"]) == "inconclusive"
    assert status(["undecided", "proved"]) == "inconclusive"
    assert status(["proved", "refuted"]) == "refuted"
    assert status(["proved", "undecided"], ["proved", "refuted"]) == "refuted"
    assert status(["undecided", "undecided"], ["proved", "inconclusive"]) == "inconclusive"
    assert ClaimPaving("c", "s").status == "inconclusive"
    vol = ClaimPaving("c", "s", boxes=[(left, "proved"), (right, "undecided")]).volume(whole)
    assert vol == {"proved": Fraction(1, 2), "refuted": 0, "undecided": Fraction(1, 2)}


def test_a_threshold_with_the_other_parameters_as_a_box_is_the_robust_one():
    """With mu in [0.019, 0.021], damping holds for every mu only when k > 0.021 A0 = 0.2667: the
    bracket found by pavings at each step contains it."""
    text = _agafonov_text(mu="[0.019, 0.021]") + '\n[claims]\nonly = ["damping_condition"]\n'
    res = find_threshold(parse_scene(text), "k", lo="0.1", hi="0.4", claim="damping_condition", width="1e-3")
    lo, hi = res.bracket()
    assert lo <= Fraction(2667, 10000) <= hi and hi - lo <= Fraction(1, 1000)
    assert res.refuted_at < res.proved_at
    assert res.certified or "inconclusive" in res.stopped     # a step near the edge may stay undecided


def test_margin_and_check_on_the_command_line(tmp_path):
    out = tmp_path / "m"
    assert main(["margin", "rudenko1976", "--param", "Omega2", "--claim", "bracket_2", "--lo", "1e-6", "--hi", "1",
                 "--width", "1e-3", "--out", str(out)]) == 0
    data = json.loads((out / "margin_rudenko1976_Omega2.json").read_text())
    assert data["certified"] and Fraction(data["bracket"][0]) < Fraction(71039, 10 ** 7) < Fraction(data["bracket"][1])
    assert "proved at Omega2" in (out / "margin_rudenko1976_Omega2.md").read_text()
    (tmp_path / "box.toml").write_text(RUDENKO_BOX)
    assert main(["prove", str(tmp_path / "box.toml"), "--out", str(tmp_path), "--quiet", "--workers", "1"]) == 0
    assert main(["check", "--quiet", str(tmp_path / "rudenko_box.json")]) == 0
    data = json.loads((tmp_path / "rudenko_box.json").read_text())
    data["claims"][0]["boxes"][0]["status"] = "refuted"
    (tmp_path / "bad.json").write_text(json.dumps(data))
    assert main(["check", "--quiet", str(tmp_path / "bad.json")]) == 1


@given(st.integers(min_value=0, max_value=10 ** 6))
def test_the_quartic_family_encloses_every_member_at_a_point(seed):
    """The centred (mean-value) form of the quartic over a parameter box contains the value of members
    drawn inside the box, at exact points omega (a mutated gradient term would leave some member out)."""
    from rigor_gyro.kinds.eigenfrequencies.boxes import _quartic_family
    from rigor_gyro.kinds.eigenfrequencies.model import Params, characteristic_quartic
    rng = random.Random(seed)
    q = lambda x: fmpq(x.numerator, x.denominator)                              # noqa: E731
    b = Fraction(rng.randint(1100, 9000), 1000)
    a = b + Fraction(rng.randint(50, 20000), 1000)
    e = Fraction(rng.randint(1, 2000), 1000)
    W = Fraction(rng.randint(1, 10000), 1000)
    # relative half-widths from 1e-7 (where the centred form is sharp: a wrong gradient shows) to 1e-2
    rel = Fraction(1, 10 ** rng.randint(2, 7))
    hb = rel * (b - 1)
    edges = [(a - rel * (a - b - hb), a + rel * a), (b - hb, b + hb), (e * (1 - rel), e * (1 + rel)),
             (W * (1 - rel), W * (1 + rel))]
    with working_precision(64):
        p = Params(*(arb(q(lo)).union(arb(q(hi))) for lo, hi in edges))
        fam, _ = _quartic_family(p)
        for _ in range(6):
            pt = [lo + (hi - lo) * Fraction(rng.choice((0, 1, 1000, 999, rng.randint(0, 1000))), 1000)
                  for lo, hi in edges]
            om = Fraction(rng.randint(1, 4096), 1024)          # dyadic: an exact ball, as Newton evaluates
            exact = characteristic_quartic(*(q(x) for x in pt))(q(om))
            val, _ = fam(arb(q(om)))
            assert val.is_finite() and val.contains(arb(exact)), (pt, om)


@given(st.integers(min_value=0, max_value=10 ** 6))
def test_the_nu_quadratic_families_enclose_every_member_at_a_point(seed):
    """The centred form of the quadratics (4) over narrow boxes contains every sampled member's value."""
    from rigor_gyro.kinds.eigenfrequencies.boxes import _nu_family
    from rigor_gyro.kinds.eigenfrequencies.model import Params, nu_quadratics
    rng = random.Random(seed)
    q = lambda x: fmpq(x.numerator, x.denominator)                              # noqa: E731
    b = Fraction(rng.randint(1100, 9000), 1000)
    a = b + Fraction(rng.randint(50, 20000), 1000)
    e = Fraction(rng.randint(1, 2000), 1000)
    rel = Fraction(1, 10 ** rng.randint(2, 7))
    hb = rel * (b - 1)
    edges = [(a - rel * (a - b - hb), a + rel * a), (b - hb, b + hb), (e * (1 - rel), e * (1 + rel))]
    with working_precision(64):
        p = Params(*(arb(q(lo)).union(arb(q(hi))) for lo, hi in edges), arb(1))
        for which, idx in (("14", 0), ("26", 1)):
            fam, _ = _nu_family(p, which)
            for _ in range(4):
                pt = [lo + (hi - lo) * Fraction(rng.choice((0, 1000, rng.randint(0, 1000))), 1000) for lo, hi in edges]
                x = Fraction(rng.randint(1, 4096), 2048)
                exact = nu_quadratics(*(q(v) for v in pt))[idx](q(x))
                val = fam(arb(q(x)))[0]
                assert val.is_finite() and val.contains(arb(exact)), (which, pt, x)


def test_a_relay_box_in_the_gains_p_and_k_is_decided_whole():
    """p, K (and S) are never split: the box claims are decided at the box's lower ends, which
    amplitude_similarity makes exact; the paving is one proved box over p in [20, 80], K in [5, 10]."""
    base = load_scene("roitenberg1947")
    s = Scene(name="gains", kind=base.kind, source="test",
              parameters={**base.parameters, "p": "[20, 80]", "K": "[5, 10]"},
              claims_only=["half_period", "orbit_genuine", "stable"], options={})
    bs = box_scene(s)
    assert set(bs.frozen) == {"p", "K"} or len(bs.frozen) == 1     # one edge must stay splittable
    pv = pave(bs)
    assert all(c.status == "proved" for c in pv.claims)
    assert all(len(c.boxes) == 1 for c in pv.claims), [len(c.boxes) for c in pv.claims]
    # the reasons quote amplitudes at the lower ends: they say so
    assert all("lower end" in why for c in pv.claims for why in c.reasons.values())


def test_a_relay_box_across_the_stability_threshold_is_never_proved_stable():
    """H in [9000, 9650] at the printed parameters: stable at H = 9000, refuted at H = 9600 (point
    proofs, checked here), so the box can never be proved stable. Only S, p, K may be taken at a box's
    lower end; H (or n) never: a box taken at its lower end would be 'proved'."""
    from rigor_gyro.kinds.periodic_orbit import validate as relay_validate
    from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box as relay_box
    base = load_scene("roitenberg1947")
    def point(h):
        s = Scene(name="x", kind=base.kind, source="test", parameters={**base.parameters, "H": h},
                  claims_only=["stable"], options=dict(base.options))
        return prove_scene(s).claim("stable").status.value
    assert (point("9000"), point("9600")) == ("proved", "refuted")
    m = relay_validate(base)
    with working_precision(128):
        out = relay_box(m, Box.of({"H": (Fraction(9000), Fraction(9650))}), ["half_period", "orbit_genuine", "stable"])
    assert out["stable"][0] != "proved"


@pytest.mark.parametrize("name", ["S", "p", "K", "n", "tau"])
def test_only_the_amplitude_parameters_leave_the_orbit_unchanged(name):
    """theta* and the largest multiplier modulus at a parameter and ten times it: unchanged exactly for
    the amplitude parameters (S, p, K), changed for any other (n, tau): AMPLITUDE_PARAMETERS is right."""
    from rigor_gyro.kinds.periodic_orbit.flow import AMPLITUDE_PARAMETERS
    base = load_scene("roitenberg1947")
    def at(v):
        s = Scene(name="x", kind=base.kind, source="test", parameters={**base.parameters, name: v},
                  claims_only=None, options=dict(base.options))
        q = prove_scene(s).quantities
        return q["theta_star"], q["multiplier_modulus_1"]
    t1, m1 = at(base.parameters[name])
    t2, m2 = at(str(Fraction(base.parameters[name]) * 10))
    assert all(x.is_finite() for x in (t1, m1, t2, m2))              # a NaN ball overlaps every ball
    same = t1.overlaps(t2) and m1.overlaps(m2)
    assert same == (name in AMPLITUDE_PARAMETERS)


def test_a_scan_is_a_map_of_point_proofs_the_same_on_a_pool(tmp_path):
    from rigor_gyro.margins.scan import run_scan, scan_points
    pts = scan_points(Fraction(1, 100), Fraction(10000), 7, True)
    assert pts[0] == Fraction(1, 100) and pts[-1] == 10000 and len(pts) == 7
    assert all(a < b for a, b in zip(pts, pts[1:])) and pts[3] == 10
    lo, hi = Fraction("49.999999999990"), Fraction("49.999999999999")    # rounding to 12 digits collapses
    for log in (False, True):
        close = scan_points(lo, hi, 4, log)
        assert close[0] == lo and close[-1] == hi and all(lo <= x <= hi for x in close)
        assert all(a < b for a, b in zip(close, close[1:]))
    one = run_scan(load_scene("roitenberg1947"), "n", 3, lo="1", hi="100", claim="stable",
                   quantities=["stability_margin"], workers=1)
    assert one.exit_code == 0 and one.counts() == {"stable": {"proved": 3, "refuted": 0, "inconclusive": 0}}
    margins = [Fraction(r["quantities"]["stability_margin"][0]) for r in one.results]
    assert margins == sorted(margins) and margins[0] > 0          # the back-emf damping stabilises
    two = run_scan(load_scene("roitenberg1947"), "n", 3, lo="1", hi="100", claim="stable",
                   quantities=["stability_margin"], workers=2)
    assert json.dumps(one.to_json()) == json.dumps(two.to_json())
    assert [p["value"] for p in one.to_json()["points"]] == ["1", "101/2", "100"]     # exact


def test_a_scan_where_stability_is_lost_says_refuted_at_those_points():
    from rigor_gyro.margins.scan import run_scan
    res = run_scan(load_scene("stress_relay_H_1e4"), "n", 2, lo="50", hi="500", claim="stable")
    assert [r["claims"]["stable"]["status"] for r in res.results] == ["proved", "refuted"]
    assert res.exit_code == 0          # a map: every point decided


@pytest.mark.parametrize("argv", [
    ["--scan", "1"], ["--scan", "3", "--lo", "2", "--hi", "1"], ["--scan", "3", "--log", "--lo", "0", "--hi", "1"],
    ["--scan", "3", "--quantity", "no_such_quantity"], ["--log"], ["--quantity", "theta_star"],
    ["--scan", "3", "--lo", "-1", "--hi", "1"], ["--scan", "3", "--workers", "0"], ["--scan", "3", "--width", "0"],
    ["--scan", "2", "--scheduler", "bogus"],
])
def test_bad_scans_are_bad_input(argv):
    assert main(["margin", "roitenberg1947", "--param", "n", "--claim", "stable"] + argv) == 2


def test_a_scan_of_a_tolerance_scene_is_bad_input(tmp_path):
    (tmp_path / "box.toml").write_text(RUDENKO_BOX)
    assert main(["margin", str(tmp_path / "box.toml"), "--param", "a", "--scan", "3"]) == 2


def test_margin_figures_are_images_with_content(tmp_path):
    """`margin --plots`: the scan's points against the quantity, the threshold's proofs and bracket."""
    pytest.importorskip("matplotlib")
    import matplotlib.image as mpimg
    assert main(["margin", "roitenberg1947", "--param", "n", "--scan", "3", "--lo", "1", "--hi", "100", "--claim",
                 "stable", "--quantity", "stability_margin", "--out", str(tmp_path), "--plots"]) == 0
    assert main(["margin", "rudenko1976", "--param", "Omega2", "--claim", "bracket_2", "--lo", "1e-6", "--hi", "1",
                 "--width", "1e-3", "--out", str(tmp_path), "--plots"]) == 0
    for stem in ("scan_roitenberg1947_n", "margin_rudenko1976_Omega2"):
        img = mpimg.imread(tmp_path / f"{stem}.png")
        assert img.shape[0] > 100 and img.std() > 0.01
    assert main(["margin", "roitenberg1947", "--param", "n", "--scan", "3", "--plots"]) == 2     # no --out


def test_a_split_point_of_a_box_spectrum_is_where_g_has_a_sign():
    """Over a box a root of g is spread over an interval; a split inside that spread can never be
    decided, so a box spectrum's pieces are split where g has a certain sign (the first of the
    tried fractions), the midpoint otherwise; a point spectrum always at the midpoint."""
    from rigor_gyro.kinds.periodic_orbit.g_roots import _split_point
    a, b = arb(0), arb(1)
    # g's ball contains 0 on [0.45, 0.55] (the spread), has a sign elsewhere
    g = lambda x, n: [arb(0, 1) if 0.45 <= float(x.mid()) <= 0.55 else arb(float(x.mid()) - 0.5)]
    assert _split_point(g, a, b, True) == arb(fmpq(3, 8))
    assert _split_point(g, a, b, False) == arb(fmpq(1, 2))
    g_sign_at_mid = lambda x, n: [arb(1)]
    assert _split_point(g_sign_at_mid, a, b, True) == arb(fmpq(1, 2))
    g_nowhere = lambda x, n: [arb(0, 1)]
    assert _split_point(g_nowhere, a, b, True) == arb(fmpq(1, 2))     # no sign anywhere: the midpoint
    for fr in (fmpq(3, 8), fmpq(5, 8), fmpq(1, 4)):                     # the chosen point is inside (a, b)
        x = _split_point(lambda x, n, fr=fr: [arb(1) if x == arb(fr) else arb(0, 1)], a, b, True)
        assert x == arb(fr) and a < x < b


@pytest.mark.parametrize("beta_values, verdict", [
    ({16: -0.25}, "spurious"),          # beta < 0 at one grid point (certainly): a witness
    ({}, "undecided"),                  # beta's balls all contain 0: no witness
    ({16: "wide"}, "undecided"),        # a ball that may be negative is no witness
])
def test_a_root_with_beta_dot_of_no_sign_is_spurious_only_on_a_certain_negative_point(monkeypatch, beta_values,
                                                                                     verdict):
    """beta'(0) of no certain sign (a box spectrum's wide enclosure): the root is spurious only if
    beta is *certainly* negative at a point of (0, theta), the point kept as the witness."""
    from rigor_gyro.kinds.periodic_orbit import claims as relay_claims
    theta = arb(1)
    grid = relay_claims.WITNESS_GRID

    def beta(t):
        k = round(float(t.mid()) * grid)
        v = beta_values.get(k)
        if v == "wide":
            return arb(-1, 2)
        return arb(v) if v is not None else arb(0, 1)
    monkeypatch.setattr(relay_claims, "x0_at", lambda sp, th: [arb(0), arb(0, 1), arb(0), arb(0), arb(0)])
    monkeypatch.setattr(relay_claims, "orbit_expsums", lambda sp, x0: [beta])
    v = relay_claims.classify_root(None, theta)
    assert v.kind == verdict, v.reason
    if verdict == "spurious":
        assert v.witness_t == arb(fmpq(16, grid)) and "no certain sign" in v.reason


def test_a_relay_box_in_n_decides_a_spurious_root_by_a_point_of_beta_below_zero():
    """n in [48, 48.25] (the rest as printed): the spurious root near theta = 0.638 (beside the pole
    of tanh at 5 pi / omega) has beta'(0) = -0.009 at n = 48.25, of no certain sign over the box; it is
    classified spurious by beta < 0 at a point of (0, theta), so every root is isolated and classified
    for every n in the box (before: undecided)."""
    from rigor_gyro.kinds.periodic_orbit import validate as relay_validate
    from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box as relay_box
    m = relay_validate(load_scene("roitenberg1947"))
    with working_precision(128):
        out = relay_box(m, Box.of({"n": (Fraction(48), Fraction(193, 4))}), ["half_period", "orbit_genuine"])
    assert out["half_period"][0] == "proved", out["half_period"][1]
    assert out["orbit_genuine"][0] == "proved"


def test_even_in_evaluates_a_box_and_its_mirror_image_once_and_gives_both_the_same_ball():
    from rigor_gyro.core.boxes import even_in
    calls = []

    def f(balls):                        # even in u; records what it was asked
        calls.append({k: (v.mid(), v.rad()) for k, v in balls.items()})
        return balls["u"] * balls["u"] + balls["v"]

    g = even_in(f, "u")
    with working_precision(64):
        box = {"u": arb("-0.75", "0.25"), "v": arb("2", "0.5")}
        mirror = {"u": arb("0.75", "0.25"), "v": arb("2", "0.5")}
        a, b = g(box), g(mirror)
        assert len(calls) == 1 and calls[0]["u"][0] > 0          # evaluated once, at the image with u >= 0
        assert a is b and a.is_finite() and a.contains(arb("0.25") + arb("1.5")) and a.contains(arb(1) + arb("2.5"))
        other = g({"u": arb("0.75", "0.25"), "v": arb("3", "0.5")})     # another v: a new evaluation
        assert len(calls) == 2 and other.is_finite() and other.contains(arb("3.5625"))
        nan = {"u": arb("nan"), "v": arb("1")}
        g(nan), g(nan)                                              # non-finite: passed on as it is, never kept
        assert len(calls) == 4
        zero = g({"u": arb("0", "0.5"), "v": arb("1")})             # midpoint 0: not mirrored
        assert calls[-1]["u"][0] == 0 and zero.is_finite() and zero.contains(arb(1))


def test_spread_takes_points_evenly_with_both_ends():
    from rigor_gyro.margins.point_proofs import spread
    assert spread(list(range(10)), 4) == [0, 3, 6, 9] and spread(list(range(64)), 16)[-1] == 63
    assert spread(list(range(5)), 5) == list(range(5)) == spread(list(range(5)), 16)
    assert spread(list(range(7)), 1) == [3] and spread(list(range(7)), 0) == []
    got = spread(list(range(1000)), 16)
    assert len(set(got)) == 16 and max(b - a for a, b in zip(got, got[1:])) <= 67


def test_midpoints_proved_point_by_point_are_spread_over_the_box_and_find_a_counterexample():
    """A relay plant box in h straddling the existence threshold h = G(0) = 0.0282916536...: 64 % of the box has
    no orbit, but the first 16 undecided sub-boxes in order all lie below the threshold, where the orbit exists
    (fuzz report: the paving said inconclusive with 'refuted: 0'). Spread over the box, the point proofs find a
    certified counterexample, so orbit_genuine is refuted over the box; the checker re-derives the points."""
    from rigor_gyro.check import check_certificate
    scene = parse_scene('name = "straddle"\nkind = "periodic_orbit"\n[parameters]\nd = "1"\n'
                        'hh = "[0.02829165, 0.02829166]"\n[claims]\nonly = ["orbit_genuine"]\n[plant]\n'
                        'M = [["0", "1", "0", "0"], ["0", "0", "1", "0"], ["0", "0", "0", "1"], '
                        '["-70692227/1000000", "-10237449/100000", "-535843/10000", "-121/10"]]\n'
                        'e = ["0", "0", "0", "2"]\nc = ["1", "0", "0", "0"]\nS = "-d"\nh = "hh"\n')
    data = json.loads(json.dumps(paving_json(pave(box_scene(scene), Executor(1)))))
    c = data["claims"][0]
    points = [p for p in c["points"] if p["box_outcome"] == "undecided"]
    assert len(points) == 16 and {p["status"] for p in points} == {"proved", "refuted"}
    assert c["status"] == "refuted" and data["verdict"] == "refuted"
    rep = check_certificate(data)
    assert rep.ok, [r for r in rep.results if not r.ok]
