"""Defects found by a hostile review of the [system] path (2026-12-06), each now a test: a def that only another
bracket (or no bracket) uses never decides a bracket; nested powers, long chains and a function with two arguments
are bad input (exit 2), never a crash or a hang; a certainly negative sqrt in a def does not crash a paving."""
import pytest

from rigor_gyro.cli import main
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.expressions import MAX_DEGREE, parse

SCENE = """name = "rv"
kind = "eigenfrequencies"
source = "review"
[parameters]
k = "{k}"
[claims]
only = ["roots", "stability", "brackets"]
[system]
M = [["1","0"],["0","1"]]
K = [["k","0"],["0","2"]]
defs = ["S = sqrt(k-2)"]
brackets = [["{lo}","3/2"], ["1", "3"]]
"""


@pytest.mark.parametrize("k,lo,want", [("1", "1/2", 0), ("1 +- 1/10", "1/2", 0),      # S unused: proved
                                       ("1", "S", 1), ("1 +- 1/10", "S", 1)])         # S used: no real value
def test_a_def_decides_only_the_brackets_that_use_it(tmp_path, k, lo, want):
    (tmp_path / "s.toml").write_text(SCENE.format(k=k, lo=lo))
    assert main(["prove", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o"), "-q", "-j", "1"]) == want
    assert main(["check", "-q", str(tmp_path / "o" / "rv.json")]) == 0


@pytest.mark.parametrize("text,match", [
    ("((((((2^64)^64)^64)^64)^64)^64)", "degree"), ("(((((((1/3)^-64)^64)^64)^64)^64)^64)", "degree"),
    ("+".join(["1"] * 1990), "operations"), ("*".join(["k"] * 150), "degree"), ("sqrt(1,2)", "one argument")])
def test_expressions_that_would_crash_or_hang_are_bad_input(text, match):
    with pytest.raises(ParameterError, match=match):
        parse(text, "X", {"k"}, {"sqrt"})
    assert parse("(k^2)^64", "X", {"k"}).evaluate({"k": 2}) == 2 ** 128      # degree 128 = MAX_DEGREE: allowed
    assert MAX_DEGREE == 128


def test_a_chain_of_defs_cannot_multiply_degrees(tmp_path):
    text = SCENE.format(k="3", lo="1/2").replace('defs = ["S = sqrt(k-2)"]',
                                                  'defs = ["A = k^64", "B = A^64", "C = B^64"]')
    (tmp_path / "s.toml").write_text(text)
    assert main(["prove", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o"), "-q"]) == 2


FLUTTER = """name = "flutter"
kind = "eigenfrequencies"
source = "review"
[parameters]
k = "1"
[system]
M = [["1","0"],["0","1"]]
K = [["k","0"],["0","1"]]
G = [["0","1/2"],["-1/2","0"]]
D = [["1","0"],["0","-1"]]
"""
DAMPED = """name = "damped"
kind = "eigenfrequencies"
source = "review"
[parameters]
d = "1/1000000"
[system]
M = [["1"]]
K = [["1"]]
D = [["d"]]
"""


@pytest.mark.parametrize("text,key,value", [
    (FLUTTER, "nonreal_roots", [{"re": ["5", "6"], "im": ["1", "2"]}]), (FLUTTER, "frequency_polynomial", ["1", "2", "3"]),
    (DAMPED, "odd_coefficients", ["0"]), (DAMPED, "offaxis_roots", [{"re": ["5", "6"], "im": ["1", "2"]}])])
def test_the_checker_re_derives_a_refutations_counterexample(tmp_path, text, key, value):
    """Made-up counterexample data is refused even when the text comparison is off (another software version)."""
    import json

    from rigor_gyro.check import check_file, digest
    (tmp_path / "s.toml").write_text(text)
    assert main(["prove", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o"), "-q"]) == 1
    path = next((tmp_path / "o").glob("*.json"))
    assert check_file(path).ok
    data = json.loads(path.read_text())
    for c in data["claims"]:
        if c.get("counterexample"):
            c["counterexample"][key] = value
    data["software"]["rigor_gyro"] = "9.9.9"
    data["integrity"]["sha256"] = digest(data)
    path.write_text(json.dumps(data))
    report = check_file(path)
    assert not report.ok and "counterexample" in report.first_failure.item


def test_zero_roots_leaving_no_frequency_and_an_exact_division_by_zero_are_bad_input(tmp_path, capsys):
    base = SCENE.format(k="1", lo="1/2").replace('defs = ["S = sqrt(k-2)"]\n', "")
    (tmp_path / "z.toml").write_text(base.replace("[system]", '[options]\nzero_roots = "4"\n[system]'))
    assert main(["prove", str(tmp_path / "z.toml"), "-o", str(tmp_path / "o"), "-q"]) == 2
    assert "zero_roots" in capsys.readouterr().err
    (tmp_path / "d.toml").write_text(base.replace('[["1/2","3/2"]', '[["1/(k-1)","3/2"]'))
    assert main(["prove", str(tmp_path / "d.toml"), "-o", str(tmp_path / "o"), "-q"]) == 2
    assert "divides by zero" in capsys.readouterr().err
