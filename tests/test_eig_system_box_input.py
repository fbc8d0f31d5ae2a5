"""[system] scenes over boxes, defects a hostile fuzzer found: the structure of G (skew) and of M, K, D
(symmetric) over a box is decided as exact rational functions, not parse trees; a point of a paving where the
model has no value (a division by zero, a singular M) is an inconclusive point, never bad input for the whole
box; the box statement of ``roots`` says "for every parameter value in the box" once."""
import json
from fractions import Fraction as F

import pytest

from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.eigenfrequencies import validate
from rigor_gyro.kinds.eigenfrequencies.boxes import validate_box

from .test_eig_system import system

H_BOX = Box.of({"h": (F(5), F(6))})


def skew(g12: str, g21: str, g11: str = "0"):
    """M = diag(1, 2), G = [[g11, g12], [g21, 0]], K = diag(-1, -2), h at the box's midpoint 11/2."""
    return validate(system([["1", "0"], ["0", "2"]], [["-1", "0"], ["0", "-2"]], G=[[g11, g12], [g21, "0"]],
                           params={"h": "11/2"}))


@pytest.mark.parametrize("g21", ["-h/2", "-(h/2)", "h/(-2)", "(h*(-1))/(4-2)", "-h*1/2", "(h^2 - h*h - h)/2"])
def test_any_spelling_of_the_negation_is_skew_on_the_box(g21):
    """Fuzzing: '-h/2' parses as (-h)/2, not -(h/2), and the tree comparison refused a skew G (exit 2)."""
    validate_box(skew("h/2", g21), H_BOX)


@pytest.mark.parametrize("g21", ["-h/2 + (h - 11/2)^2", "h/2 - 11/2", "-11/4"])
def test_a_g_skew_only_at_the_midpoint_is_refused_naming_the_pair(g21):
    model = skew("h/2", g21)            # skew at h = 11/2 (the point validation passes)
    with pytest.raises(ParameterError, match=r"G\[1\]\[2\] = 'h/2' and G\[2\]\[1\] = .* not each other's negation "
                                             r"for every value in the box \(write G\[2\]\[1\] as '-\(h/2\)'\)"):
        validate_box(model, H_BOX)


def test_a_diagonal_of_g_zero_only_at_the_midpoint_is_refused():
    model = skew("h/2", "-h/2", g11="h - 11/2")
    with pytest.raises(ParameterError, match=r"G\[1\]\[1\] = 'h - 11/2' depends on a toleranced parameter and is not "
                                             r"0 for every value in the box: the diagonal of G .*must be 0"):
        validate_box(model, H_BOX)
    validate_box(skew("h/2", "-h/2", g11="h - h"), H_BOX)       # the zero function, however spelt


def test_the_point_message_for_a_diagonal_of_g_says_it_must_be_zero():
    """Fuzzing: it read "G[1][1] = '1' = 1 but G[1][1] = '1' = 1"."""
    with pytest.raises(ParameterError) as e:
        skew("h/2", "-h/2", g11="1")
    assert "G[1][1] = '1' = 1, but the diagonal of G must be 0" in str(e.value)
    assert "but G[1][1]" not in str(e.value)


def test_symmetric_entries_spelt_differently_pass_and_different_functions_fail():
    def sym(m12, m21):
        return validate(system([["2", m12], [m21, "2"]], [["1", "0"], ["0", "1"]], params={"p": "1/2"}))
    box = Box.of({"p": (F(1, 4), F(3, 4))})
    for a, b in (("2*p", "p+p"), ("p", "p^2/p"), ("1/(1+p)", "2/(2+2*p)")):
        validate_box(sym(a, b), box)
    with pytest.raises(ParameterError, match=r"M\[1\]\[2\] = 'p' and M\[2\]\[1\] = '1-p' .*not the same function"):
        validate_box(sym("p", "1-p"), box)


# --------------------------------------------------------------------------- a bad point inside a paving

DIV0 = """name = "box_point_div0"
kind = "eigenfrequencies"
[parameters]
a = "[-1/128, 127/128]"
{options}[system]
M = [["1", "0"], ["0", "1"]]
K = [["1", "0"], ["0", "2+1/a"]]
"""

MSING = """name = "box_point_msing"
kind = "eigenfrequencies"
[parameters]
a = "[127/128, 255/128]"
[system]
M = [["a", "1"], ["1", "1"]]
K = [["1", "0"], ["0", "2"]]
"""


def run(tmp_path, text: str, name: str) -> tuple[int, dict, int]:
    from rigor_gyro.cli import main
    (tmp_path / f"{name}.toml").write_text(text)
    code = main(["prove", str(tmp_path / f"{name}.toml"), "-o", str(tmp_path / "o"), "-q", "-j", "1"])
    data = json.loads((tmp_path / "o" / f"{name}.json").read_text())
    return code, data, main(["check", "-q", str(tmp_path / "o" / f"{name}.json")])


@pytest.mark.parametrize("text,name,point,why", [
    (DIV0.format(options=""), "box_point_div0", {"a": "0"}, "divides by zero"),
    (MSING, "box_point_msing", {"a": "1"}, "M is singular")], ids=["div0", "singular_M"])
def test_a_point_without_a_value_is_inconclusive_not_bad_input(tmp_path, text, name, point, why):
    """Fuzzing: a leaf midpoint where the model has no value aborted the whole paving with exit 2."""
    code, data, checked = run(tmp_path, text, name)
    assert code == 3 and checked == 0
    for c in data["claims"]:
        bad = [p for p in c["points"] if p["point"] == point]
        assert len(bad) == 1 and bad[0]["status"] == "inconclusive" and bad[0]["box_outcome"] == "undecided"
        assert why in bad[0]["reason"] and "neither a counterexample nor a proof" in bad[0]["reason"]
        assert c["status"] == "inconclusive"


def test_counterexamples_beside_a_point_without_a_value_still_refute(tmp_path):
    """K22 = 2 + 1/a < 0 for a in (-1/2, 0): the leaf [-3/128, -1/128] is refuted at its midpoint -1/64 by the
    point prover, beside the leaf whose midpoint a = 0 has no value (the old code: exit 2 for the whole box)."""
    text = DIV0.format(options="").replace('"[-1/128, 127/128]"', '"[-3/128, 125/128]"')
    code, data, checked = run(tmp_path, text, "box_point_div0")
    assert code == 1 and checked == 0
    roots = next(c for c in data["claims"] if c["id"] == "roots")
    assert roots["status"] == "refuted"
    assert {"a": "0"} in [p["point"] for p in roots["points"] if p["status"] == "inconclusive"]
    refuted = [p["point"]["a"] for p in roots["points"] if p["status"] == "refuted"]
    assert "-1/64" in refuted and all(F(a) < 0 for a in refuted)


def test_the_counterexample_search_refutes_a_system_box_beside_a_point_without_a_value(tmp_path):
    """The fuzzer's box itself: at the default resolution no leaf midpoint lies in (-1/128, 0), but the search
    over the undecided leaves (search_points) finds a certified counterexample there (the search's margins took
    a [system] model for the paper's and crashed: exit 4)."""
    code, data, checked = run(tmp_path, DIV0.format(options='[options]\nsearch_points = "4"\n'), "box_point_div0")
    assert code == 1 and checked == 0
    roots = next(c for c in data["claims"] if c["id"] == "roots")
    found = [p for p in roots["counterexample_search"]["proofs"] if p["status"] == "refuted"]
    assert roots["status"] == "refuted" and found and all(-F(1, 128) <= F(p["point"]["a"]) < 0 for p in found)


def test_the_counterexample_search_runs_on_a_system_box(tmp_path):
    """The search's margins took a [system] model for the paper's (AttributeError, exit 4)."""
    text = DIV0.format(options='[options]\nsearch_points = "2"\n').replace('"2+1/a"', '"a"')
    code, data, checked = run(tmp_path, text, "box_point_div0")
    assert code == 1 and checked == 0
    assert all("counterexample_search" in c for c in data["claims"])


def test_point_task_at_a_point_without_a_value():
    from rigor_gyro.margins.models import settings_json
    from rigor_gyro.margins.point_proofs import point_task
    model = {"M": [["1", "0"], ["0", "1"]], "K": [["1", "0"], ["0", "2+1/a"]]}
    out = point_task("eigenfrequencies", json.dumps({"a": "0"}), settings_json({}, model), "roots", 64, 128)
    assert out["status"] == "inconclusive" and out["precision_bits"] == 64 and "divides by zero" in out["reason"]
    assert point_task("eigenfrequencies", json.dumps({"a": "-1/4"}), settings_json({}, model), "roots")["status"] \
        == "refuted"


# --------------------------------------------------------------------------- the box statement

def test_the_box_statement_of_roots_is_not_doubled(tmp_path):
    """Fuzzing: "For every parameter value in the box: For every parameter value in the box, ..."."""
    _, data, _ = run(tmp_path, MSING, "box_point_msing")
    for c in data["claims"]:
        assert c["statement"].count("or every parameter value in the box") == 1, c["statement"]
    roots = next(c for c in data["claims"] if c["id"] == "roots")
    assert roots["statement"].startswith("For every parameter value in the box: The characteristic polynomial")



@pytest.mark.parametrize("K,brackets", [
    ('[["2+a", "(1/a)^0 - 1"], ["(1/a)^0 - 1", "5"]]', ""),
    ('[["2+a", "0/a"], ["0/a", "5"]]', ""),
    ('[["2+a", "a/a - 1"], ["a/a - 1", "5"]]', ""),
], ids=["power0", "zero_over_a", "a_over_a"])
def test_a_box_holding_a_point_without_a_value_is_never_proved(tmp_path, K, brackets):
    """Review: entries that simplify to a function defined everywhere ((1/a)^0 - 1 is 0) but have no value at
    a = 0 were proved over a box holding 0 (the checker confirmed): every divisor an entry meets must be nonzero
    on a sub-box, not only the denominator left after simplifying."""
    text = ('name = "pz"\nkind = "eigenfrequencies"\n[parameters]\na = "[-1/2, 1]"\n[system]\n'
            f'M = [["1", "0"], ["0", "1"]]\nK = {K}\n')
    code, data, checked = run(tmp_path, text, "pz")
    assert code != 0 and all(c["status"] != "proved" for c in data["claims"]), [c["status"] for c in data["claims"]]


def test_a_bracket_bound_to_the_power_0_of_a_pole_is_never_proved_over_a_box(tmp_path):
    """Review: python-flint's nan ** 0 is 1, so (1/(a - 1))^0 over a box holding a = 1 had the value 1 and the
    brackets were proved there; a power 0 of a ball that is not finite now stays not finite."""
    text = ('name = "pbr"\nkind = "eigenfrequencies"\n[parameters]\na = "[1/2, 7/4]"\n[system]\n'
            'M = [["1", "0"], ["0", "1"]]\nK = [["a", "0"], ["0", "2"]]\n'
            'brackets = [["0", "2*(1/(a-1))^0"], ["(1/(a-1))^0", "3"]]\n')
    code, data, checked = run(tmp_path, text, "pbr")
    br = next(c for c in data["claims"] if c["id"] == "brackets")
    assert br["status"] != "proved" and code != 0
