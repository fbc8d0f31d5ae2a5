"""[system] scenes over parameter boxes (kinds/eigenfrequencies/system_boxes.py): the certified root balls hold
the roots sampled in mpmath, verdicts agree with the specialised Rudenko box rigour and with point proofs, and
what the structure cannot certify stays undecided (never refuted)."""
import dataclasses
import random
from fractions import Fraction as F

import pytest

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.balls import exact_endpoints
from rigor_gyro.kinds.eigenfrequencies import validate
from rigor_gyro.kinds.eigenfrequencies.boxes import evaluate_box, validate_box
from rigor_gyro.kinds.eigenfrequencies.system_boxes import system_box_roots
from rigor_gyro.kinds.eigenfrequencies.system_claims import polynomial_facts

from .test_eig_system import system, two_dof

mpmath = pytest.importorskip("mpmath")


def rel_box(scene, rel: str, names=("Omega2", "eps")) -> Box:
    r = F(rel)
    return Box.of({k: (F(scene.parameters[k]) * (1 - r), F(scene.parameters[k]) * (1 + r)) for k in names})


def at(scene, point: dict):
    return validate(dataclasses.replace(scene, parameters=dict(scene.parameters, **{k: str(v) for k, v in point.items()})))


def sampled_roots(model) -> list:
    _, _, Q, _ = polynomial_facts(model)
    with mpmath.workdps(60):
        coeffs = [mpmath.mpf(int(c.p)) / int(c.q) for c in reversed(Q.coeffs())]
        return sorted(mpmath.re(r) for r in mpmath.polyroots(coeffs, maxsteps=200, extraprec=200))


@pytest.mark.parametrize("rel,names", [("0.001", ("Omega2", "eps")), ("0.002", ("a", "b", "Omega2", "eps"))])
def test_rudenko_system_box_roots_hold_every_sampled_root(rel, names):
    scene = load_scene("rudenko1976_system")
    box = rel_box(scene, rel, names)
    model = at(scene, box.midpoint())
    with working_precision(128):
        roots, why, fails = system_box_roots(model, box)
    assert roots is not None and not fails, why
    ends = [exact_endpoints(r) for r in roots]
    rng = random.Random(3)
    corners = [{k: (lo if (i >> n) & 1 else hi) for n, (k, lo, hi) in enumerate(box.edges)} for i in range(2 ** len(box.edges))]
    samples = corners + [{k: lo + (hi - lo) * F(rng.randint(0, 1000), 1000) for k, lo, hi in box.edges} for _ in range(12)]
    for p in samples:
        for w, (lo, hi) in zip(sampled_roots(at(scene, p)), ends):
            assert mpmath.mpf(lo.numerator) / lo.denominator <= w <= mpmath.mpf(hi.numerator) / hi.denominator, (p, w)


def test_rudenko_system_box_verdicts_match_the_specialised_box_rigour():
    general, special = load_scene("rudenko1976_system"), load_scene("rudenko1976")
    box = rel_box(general, "0.001")
    g = at(general, box.midpoint())
    s = validate(dataclasses.replace(special, parameters=dict(special.parameters, **{k: str(v) for k, v in box.midpoint().items()})))
    with working_precision(128):
        validate_box(g, box)
        out_g = evaluate_box(g, box, ["roots", "stability", "brackets"])
        out_s = evaluate_box(s, box, ["roots", "bracket_1", "bracket_2", "bracket_3", "bracket_4"])
    assert out_g["roots"][0] == out_s["roots"][0] == "proved"
    assert out_g["stability"][0] == "proved"
    assert out_g["brackets"][0] == "proved" and all(out_s[f"bracket_{j}"][0] == "proved" for j in range(1, 5))
    # the points agree: each corner's point proof proves what the box proved
    for i in range(4):
        p = {k: (lo if (i >> n) & 1 else hi) for n, (k, lo, hi) in enumerate(box.edges)}
        cert = prove_scene(dataclasses.replace(general, parameters=dict(general.parameters, **{k: str(v) for k, v in p.items()})))
        assert [c.status.value for c in cert.claims] == ["proved"] * 3


def test_a_wide_box_is_undecided_never_refuted():
    scene = load_scene("rudenko1976_system")
    box = rel_box(scene, "0.05", ("a", "b", "Omega2", "eps"))
    with working_precision(128):
        out = evaluate_box(at(scene, box.midpoint()), box, ["roots", "stability", "brackets"])
    assert {v[0] for v in out.values()} == {"undecided"}


def test_a_bracket_missed_by_every_member_is_refuted_over_the_box():
    """g in [2.99, 3.01], k1 = k2 = -1: omega_2 = (g^2 - 2 + sqrt((g^2 - 2)^2 - 4))/2 in about [6.80, 6.91]."""
    scene = two_dof("3", brackets=[["1/10", "1/5"], ["7", "8"]])
    box = Box.of({"g": (F("2.99"), F("3.01"))})
    with working_precision(128):
        out = evaluate_box(at(scene, box.midpoint()), box, ["roots", "stability", "brackets"])
    assert out["roots"][0] == out["stability"][0] == "proved"
    assert out["brackets"][0] == "refuted" and "omega_2" in out["brackets"][1]
    scene = two_dof("3", brackets=[["1/10", "1/5"], ["6", "sqrt(g^2 - 10)"]])     # sqrt(< 0) on the whole box
    with working_precision(128):
        out = evaluate_box(at(scene, box.midpoint()), box, ["brackets"])
    assert out["brackets"][0] == "refuted" and "no real value" in out["brackets"][1]


def test_the_structure_is_decided_exactly_on_the_whole_box():
    """The coefficients are exact polynomials in the box's parameters: an odd term or a missing zero root that is
    certainly nonzero on the whole box refutes; one that vanishes somewhere in the box leaves it undecided."""
    box = Box.of({"g": (F("2.9"), F("3.1"))})
    damped = two_dof("3", D=[["1/10", "0"], ["0", "0"]])
    with working_precision(128):
        out = evaluate_box(at(damped, box.midpoint()), box, ["roots", "stability"])
    assert out["stability"][0] == out["roots"][0] == "refuted" and "odd term" in out["stability"][1]
    somewhere = two_dof("3", D=[["g - 3", "0"], ["0", "0"]])           # undamped at g = 3 only
    with working_precision(128):
        out = evaluate_box(at(somewhere, box.midpoint()), box, ["stability"])
    assert out["stability"][0] == "undecided" and "vanish only somewhere" in out["stability"][1]
    zero = dataclasses.replace(two_dof("3"), options={"zero_roots": "2"})       # det K = 1: no zero root
    with working_precision(128):
        out = evaluate_box(at(zero, box.midpoint()), box, ["roots"])
    assert out["roots"][0] == "refuted" and "zero_roots is not the model's" in out["roots"][1]
    tilted = system([["1", "0"], ["0", "1"]], [["-1", "0"], ["0", "g - 3"]], G=[["0", "g"], ["-g", "0"]],
                    params={"g": "3"}, options={"zero_roots": "2"})          # det K = 0 at g = 3 only
    with working_precision(128):
        out = evaluate_box(at(tilted, box.midpoint()), box, ["roots"])
    assert out["roots"][0] == "undecided"
    cyclic = system([["1", "0"], ["0", "1"]], [["0", "0"], ["0", "k"]], G=[["0", "g"], ["-g", "0"]],
                    params={"g": "3", "k": "1"}, options={"zero_roots": "2"})
    with working_precision(128):
        out = evaluate_box(at(cyclic, box.midpoint()), box, ["roots", "stability"])
    assert out["roots"][0] == out["stability"][0] == "proved"


def test_box_edges_must_be_parameters():
    scene = two_dof("3")
    with pytest.raises(ParameterError, match=r"parameter 'h': a \[system\] scene takes tolerances only on its parameters"):
        validate_box(validate(scene), Box.of({"h": (F(1), F(2))}))
    with pytest.raises(ParameterError, match=r"cannot be decided over a box"):
        evaluate_box(validate(scene), Box.of({"g": (F(2), F(3))}), ["nu_ordering"])


def test_symmetry_must_hold_on_the_whole_box():
    """b and c equal at the midpoint but toleranced apart: M symmetric there, not on the box."""
    scene = dataclasses.replace(two_dof("3"), parameters={"g": "3", "k1": "-1", "k2": "-1", "p": "1/10", "q": "1/10"},
                                model={"M": [["1", "p"], ["q", "1"]], "K": [["k1", "0"], ["0", "k2"]],
                                       "G": [["0", "g"], ["-g", "0"]]})
    model = validate(scene)                       # the midpoint: p = q
    with pytest.raises(ParameterError, match=r"\[system\] M\[1\]\[2\] = 'p' and M\[2\]\[1\] = 'q' depend on a toleranced"):
        validate_box(model, Box.of({"p": (F("0.09"), F("0.11"))}))
    validate_box(model, Box.of({"g": (F("2.9"), F("3.1"))}))            # M fixed on this box: fine
    fixed_m = {"g": "3", "k1": "-1", "k2": "-1"}      # p, q unused once M is fixed (an unused parameter is bad input)
    skew = dataclasses.replace(scene, parameters=fixed_m,
                               model={**scene.model, "M": [["1", "0"], ["0", "1"]], "G": [["0", "g"], ["-(g)", "0"]]})
    validate_box(validate(skew), Box.of({"g": (F("2.9"), F("3.1"))}))   # -(g) is the function -g
    same = dataclasses.replace(scene, parameters=fixed_m,
                               model={**scene.model, "M": [["1", "0"], ["0", "1"]], "G": [["0", "g"], ["-g*1", "0"]]})
    validate_box(validate(same), Box.of({"g": (F("2.9"), F("3.1"))}))   # -g*1 too (decided as functions)
    bad = dataclasses.replace(scene, parameters=fixed_m, model={**scene.model, "M": [["1", "0"], ["0", "1"]],
                                                                "G": [["0", "g"], ["-g+(g-3)^2", "0"]]})
    with pytest.raises(ParameterError, match=r"G\[1\]\[2\] = 'g' and G\[2\]\[1\] = '-g\+\(g-3\)\^2'.*skew-symmetric on the whole box"):
        validate_box(validate(bad), Box.of({"g": (F("2.9"), F("3.1"))}))


def test_a_sub_box_with_the_whole_box_model_holds_every_sampled_root():
    """A paving evaluates sub-boxes with the model of the whole box's midpoint: the centred form must expand
    about the sub-box's own midpoint."""
    scene = load_scene("rudenko1976_system")
    whole = rel_box(scene, "0.01")
    model = at(scene, whole.midpoint())
    (_, lo1, hi1), (_, lo2, hi2) = whole.edges
    sub = Box.of({"Omega2": (lo1, lo1 + (hi1 - lo1) / 4), "eps": (hi2 - (hi2 - lo2) / 4, hi2)})
    with working_precision(128):
        roots, why, fails = system_box_roots(model, sub)
        out = evaluate_box(model, sub, ["roots", "brackets"])
    assert roots is not None, why
    assert out["roots"][0] == "proved" and out["brackets"][0] == "proved"
    ends = [exact_endpoints(r) for r in roots]
    rng = random.Random(5)
    for _ in range(8):
        p = {k: lo + (hi - lo) * F(rng.randint(0, 1000), 1000) for k, lo, hi in sub.edges}
        for w, (lo, hi) in zip(sampled_roots(at(scene, p)), ends):
            assert mpmath.mpf(lo.numerator) / lo.denominator <= w <= mpmath.mpf(hi.numerator) / hi.denominator, (p, w)
