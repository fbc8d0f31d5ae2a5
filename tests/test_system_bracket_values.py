"""A [system] bracket whose bound has no finite value (a fuzzer's find, 2026-12-07): ``1/sqrt(a - 1)`` at a = 1 or
``1/(sqrt(2)^2 - 2)`` escalated to 4096 bits, stored "nan" and the checker then failed on the honest certificate.
Such a bound is now bad input (exit 2) when a certain reason is found (system_bounds: an exact 0 divisor, with
exact square roots of squares and exact even powers of square roots); with no certain reason the claim stays
inconclusive and nothing non-finite is stored; the checker reports a stored "nan" without failing to read the
certificate."""
import copy
import json

import pytest

from rigor_gyro.check import check_certificate
from rigor_gyro.certificate import digest
from rigor_gyro.cli import main
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.eigenfrequencies import validate

from .forgery import claim
from .test_eig_system import confirmed, proved, system

I2 = [["1", "0"], ["0", "1"]]
K = [["a", "0"], ["0", "2"]]


@pytest.mark.parametrize("lo,defs,words", [
    ("1/sqrt(a-1)", None, "it divides by sqrt(a - 1), which is exactly 0"),
    ("1/(sqrt(2)^2 - 2)", None, "it divides by sqrt(2)^2 - 2, which is exactly 0"),
    ("1/(sqrt(9/4) - 3/2)", None, "which is exactly 0"),
    ("sqrt(a-1)^(-2)", None, "divides by sqrt(a - 1), which is exactly 0"),
    ("1/S", ["S = sqrt(a) - 1"], "it divides by S, which is exactly 0"),
    ("S", ["S = 1/(sqrt(4*a) - 2)"], "the def S = '1/(sqrt(4*a) - 2)' that it uses has no value"),
])
def test_a_bound_that_certainly_divides_by_zero_is_bad_input(lo, defs, words):
    scene = system(I2, K, params={"a": "1"}, brackets=[[lo, "2"]], defs=defs)
    with pytest.raises(ParameterError) as e:
        validate(scene)
    assert "[system] brackets[1]" in str(e.value) and words in str(e.value), str(e.value)
    assert "no finite value" in str(e.value) or "has no value" in str(e.value)


def test_the_fuzzers_scene_exits_2_naming_the_bracket(tmp_path, capsys):
    (tmp_path / "n.toml").write_text('name = "n"\nkind = "eigenfrequencies"\n[parameters]\na = "1"\n[system]\n'
                                     'M = [["1", "0"], ["0", "1"]]\nK = [["a", "0"], ["0", "2"]]\n'
                                     'brackets = [["1/sqrt(a-1)", "2"]]\n')
    assert main(["prove", str(tmp_path / "n.toml"), "-o", str(tmp_path / "o"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "brackets[1]" in err and "'1/sqrt(a-1)' has no finite value" in err


@pytest.mark.parametrize("brackets,defs", [([["1/sqrt(4)", "2"]], None),             # sqrt(4) = 2 exactly: fine
                                           ([["1/2", "2"], ["1", "3"]], ["S = 1/(sqrt(a) - 1)"]),   # S unused
                                           ([["1/(sqrt(2)^3 - 2) - 2", "2"]], None),    # an odd power: not 2
                                           ([["1/(sqrt(1/2) - 1) + 3", "2"]], None),    # 1/2 is no square
                                           ([["1/(sqrt(2) - 1) - 2", "2"]], None)])
def test_a_defined_bound_or_an_unused_def_is_no_reason(brackets, defs):
    data = proved(system(I2, K, params={"a": "1"}, brackets=brackets, defs=defs))
    assert claim(data, "brackets")["status"] == "proved"
    assert confirmed(data)


def test_no_certain_reason_stays_inconclusive_and_stores_nothing_non_finite():
    """sqrt(a) - sqrt(3) at a = 3 is 0, but no exact structure shows it: inconclusive, the bound not stored."""
    data = proved(system(I2, [["a", "0"], ["0", "2"]], params={"a": "3"}, brackets=[["1/(sqrt(a) - sqrt(3))", "5"]],
                         claims=("roots", "brackets")))
    assert claim(data, "brackets")["status"] == "inconclusive"
    q = data["quantities"]
    assert "bracket_1_lo" not in q and "bracket_1_slack" not in q and "bracket_1_hi" in q
    assert not any("nan" in json.dumps(v) or "inf" in json.dumps(v) for v in q.values())
    assert confirmed(data)


def test_the_checker_reports_a_stored_nan_instead_of_failing_to_read():
    data = proved(system(I2, K, params={"a": "1"}, brackets=[["1/2", "2"]]))
    f = copy.deepcopy(data)
    f["quantities"]["bracket_1_lo"]["lo"] = "nan"
    f["integrity"] = {"sha256": digest(f)}
    report = check_certificate(f)
    assert not report.ok
    failed = {r.item for r in report.results if not r.ok}
    assert "bracket_1_lo" in failed and "data" not in failed, failed
