"""The declared zero roots (option zero_roots) against the exact multiplicity mu of lambda = 0 (a fuzzer's
false refutation, 2026-12-07): ``roots`` states P = lambda^z P~ with z declared, so any mismatch refutes it;
``stability`` states that every root other than the declared lambda = 0 roots is simple and on the imaginary
axis, so an over-declared z (mu < z) leaves it to the other roots, a multiple zero root beyond the declared ones
(mu >= 2, mu > z) refutes it, and a simple zero root (mu = 1, z = 0) is on the axis. The checker re-decides the
same way, and re-derives the counterexamples of systems with zero roots and damping."""
import copy

import pytest

from .forgery import claim, items, refix
from .test_eig_system import confirmed, proved, system

I2 = [["1", "0"], ["0", "1"]]


def test_over_declared_zero_roots_refute_roots_but_not_a_true_stability():
    """The fuzzer's scene: P = (lambda^2 + 1)(lambda^2 + 2), lambda = 0 is no root, zero_roots = 2 declared."""
    data = proved(system([["a", "0"], ["0", "1"]], [["1", "0"], ["0", "2"]], params={"a": "1"},
                         options={"zero_roots": "2"}))
    assert claim(data, "roots")["status"] == "refuted"
    assert claim(data, "roots")["counterexample"]["zero_root_multiplicity"] == 0
    s = claim(data, "stability")
    assert s["status"] == "proved", s
    assert "multiplicity 0 exactly (2 declared)" in s["reason"]
    assert not any(k.startswith("omega_") for k in data["quantities"])     # roots refuted: none stored
    assert confirmed(data)
    f = copy.deepcopy(data)                    # the old, false verdict is refused by the checker
    claim(f, "stability")["status"] = "refuted"
    assert items(refix(f))["stability"] is False


@pytest.mark.parametrize("K,G,why,key", [
    ([["-1", "0"], ["0", "-2"]], None, "certainly < 0", "negative_roots"),            # divergence, z over-declared
    ([["-1", "0"], ["0", "-1"]], [["0", "1"], ["-1", "0"]], "non-real", "nonreal_roots"),   # flutter
])
def test_over_declared_zero_roots_still_refute_a_false_stability(K, G, why, key):
    data = proved(system(I2, K, G=G, options={"zero_roots": "2"}))
    s = claim(data, "stability")
    assert s["status"] == "refuted" and why in s["reason"], s
    assert s["counterexample"]["zero_root_multiplicity"] == 0 and key in s["counterexample"]
    assert confirmed(data)                     # the counterexample re-derived on P / lambda^0's Q
    f = copy.deepcopy(data)
    claim(f, "stability")["status"] = "proved"
    claim(f, "stability").pop("counterexample")
    assert items(refix(f))["stability"] is False


def test_under_declared_zero_roots_refute_stability_by_the_multiple_zero_root():
    """M = I, K = 0, G = 0: lambda = 0 of multiplicity 4; zero_roots = 2 leaves a double root at 0."""
    data = proved(system(I2, [["0", "0"], ["0", "1"]], options={"zero_roots": "0"}))
    s = claim(data, "stability")
    assert s["status"] == "refuted" and "not simple" in s["reason"]
    assert s["counterexample"]["zero_root_multiplicity"] == 2
    assert confirmed(data)
    f = copy.deepcopy(data)
    claim(f, "stability")["status"] = "proved"
    claim(f, "stability").pop("counterexample")
    assert items(refix(f))["stability"] is False


def test_a_simple_zero_root_is_not_called_multiple_and_the_damped_rest_refutes():
    """M = 1, D = 1, K = 0: P = lambda (lambda + 1); lambda = 0 is simple (on the axis), lambda = -1 is not."""
    data = proved(system([["1"]], [["0"]], D=[["1"]]))
    for cid in ("roots", "stability"):
        assert "not simple" not in claim(data, cid)["reason"]
    s = claim(data, "stability")
    assert s["status"] == "refuted" and s["counterexample"]["offaxis_roots"], s
    assert confirmed(data)


def test_the_checker_re_derives_the_odd_terms_of_a_damped_system_with_zero_roots():
    """zero_roots = 2 and damping: P = lambda^2 (lambda^2 + d lambda + 1); the stored odd power 3 is P's (the
    checker once shifted it by mu twice and crashed)."""
    data = proved(system(I2, [["1", "0"], ["0", "0"]], D=[["1/10", "0"], ["0", "0"]], options={"zero_roots": "2"}))
    assert claim(data, "stability")["counterexample"]["odd_powers"] == [3]
    assert confirmed(data)



BOX = """name = "zbox"
kind = "eigenfrequencies"
source = "fuzz"
[parameters]
a = "1 +- 1/10"
[options]
zero_roots = "{z}"
[system]
M = [["a", "0"], ["0", "1"]]
K = {K}
"""


def paved(tmp_path, z: str, K: str) -> dict:
    import json

    from rigor_gyro.check import check_file
    from rigor_gyro.cli import main
    (tmp_path / "z.toml").write_text(BOX.format(z=z, K=K))
    main(["prove", str(tmp_path / "z.toml"), "-o", str(tmp_path / "o"), "-q", "-j", "1"])
    path = tmp_path / "o" / "zbox.json"
    assert check_file(path).ok
    return {c["id"]: c["status"] for c in json.loads(path.read_text())["claims"]}


@pytest.mark.parametrize("K,want", [('[["1", "0"], ["0", "2"]]', "proved"), ('[["-1", "0"], ["0", "-2"]]', "refuted")])
def test_over_declared_zero_roots_over_a_box(tmp_path, K, want):
    """The same over a box (a = 1 +- 1/10): lambda = 0 is no root anywhere in it, so stability is decided by the
    other roots for every member (it was refuted over the box while its midpoint was proved: an internal error)."""
    assert paved(tmp_path, "2", K) == {"roots": "refuted", "stability": want}


def test_under_declared_zero_roots_over_a_box_refute_stability(tmp_path):
    assert paved(tmp_path, "0", '[["0", "0"], ["0", "1"]]') == {"roots": "refuted", "stability": "refuted"}


def test_a_multiplicity_of_zero_below_zero_roots_not_fixed_on_a_box_never_refutes_stability(tmp_path):
    """Review: K = diag(a^2, 3, 3 + 1e-9), a in [1/4, 3/4], zero_roots = 4: lambda = 0 is no root anywhere in the box
    and stability holds at every point, but the ball of a^2 on a wide sub-box contains 0, so no one multiplicity
    is known there; the box path then refuted stability from a higher coefficient (certainly nonzero), and the
    checker confirmed the false refutation. Such a sub-box is undecided; the claim is never refuted."""
    import json

    from rigor_gyro.check import check_file
    from rigor_gyro.cli import main
    text = ('name = "z4lo"\nkind = "eigenfrequencies"\n[parameters]\na = "[1/4, 3/4]"\n[options]\nzero_roots = "4"\n'
            '[claims]\nonly = ["stability"]\n[system]\nM = [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]]\n'
            'K = [["a^2", "0", "0"], ["0", "3", "0"], ["0", "0", "3 + 1/1000000000"]]\n')
    (tmp_path / "z.toml").write_text(text)
    code = main(["prove", str(tmp_path / "z.toml"), "-o", str(tmp_path / "o"), "-q", "-j", "1",
                 "--prec", "16", "--maxprec", "16"])
    data = json.loads((tmp_path / "o" / "z4lo.json").read_text())
    status = {c["id"]: c["status"] for c in data["claims"]}["stability"]
    assert status != "refuted" and code != 1, status
    assert check_file(tmp_path / "o" / "z4lo.json").ok


def test_a_rational_off_axis_root_stored_as_a_point_is_checked_exactly():
    """Review: a damped system whose P has the rational root lambda = 1 stores it as the point box [1, 1]; the
    checker fitted Arb's ball around the root inside the box, which a point can never hold, and rejected the
    honest refutation. A point box is now decided exactly (p(x + i y) = 0); a point that is no root is rejected."""
    data = proved(system(M=[["1", "2"], ["2", "2"]], G=[["0", "2"], ["-2", "0"]], D=[["-1", "1"], ["1", "0"]],
                         K=[["-1", "-1"], ["-1", "-2"]]))
    assert claim(data, "roots")["status"] == "refuted"
    boxes = claim(data, "roots")["counterexample"]["offaxis_roots"]
    assert {"re": ["1", "1"], "im": ["0", "0"]} in boxes
    assert confirmed(data)
    forged = copy.deepcopy(data)
    for c in forged["claims"]:
        for b in c["counterexample"]["offaxis_roots"]:
            if b == {"re": ["1", "1"], "im": ["0", "0"]}:
                b["re"] = ["2", "2"]
    assert not items(forged)["roots counterexample"]
