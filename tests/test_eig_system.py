"""Gyroscopic systems written as matrices ([system], issue 42 part 3): Rudenko's (1) as a system gives the
specialised scene's roots and verdicts, small systems with known answers are proved or refuted (each
re-derived by the checker), and every bad model is refused naming the entry."""
import copy
import dataclasses
import json
from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro import load_scene, prove_scene, reproduce
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.stored import interval, meets
from rigor_gyro.core.polymat import det_by_expansion, det_by_interpolation
from rigor_gyro.kinds.eigenfrequencies import validate
from rigor_gyro.kinds.eigenfrequencies.model import characteristic_quartic
from rigor_gyro.kinds.eigenfrequencies.system_claims import polynomial_facts
from rigor_gyro.scene import Scene

from .forgery import claim, items, refix


def system(M, K, G=None, D=None, params=None, options=None, brackets=None, claims=None, defs=None) -> Scene:
    if claims is None:
        claims = ("roots", "stability") + (("brackets",) if brackets else ())
    model = {"M": M, "K": K}
    for key, v in (("G", G), ("D", D), ("brackets", brackets), ("defs", defs)):
        if v is not None:
            model[key] = v
    return Scene(name="sys", kind="eigenfrequencies", source="test", parameters=dict(params or {}),
                 claims_only=list(claims), options=dict(options or {}), model=model)


def proved(scene: Scene) -> dict:
    raw = prove_scene(scene).to_json()
    reproduce.keep(raw)
    return json.loads(json.dumps(raw))


def confirmed(data: dict) -> bool:
    return check_certificate(data).ok


def status(data: dict, cid: str) -> str:
    return claim(data, cid)["status"]


def two_dof(g: str, k1: str = "-1", k2: str = "-1", **kw) -> Scene:
    """M = I, G = [[0, g], [-g, 0]], K = diag(k1, k2): Q(omega) = omega^2 - (k1 + k2 + g^2) omega + k1 k2."""
    return system([["1", "0"], ["0", "1"]], [["k1", "0"], ["0", "k2"]], G=[["0", "g"], ["-g", "0"]],
                  params={"g": g, "k1": k1, "k2": k2}, **kw)


# ----------------------------------------------------------------------------- Rudenko's (1) as a system

RUDENKO_VARIANTS = [{}, dict(a="3", b="2", eps="50", Omega2="1"), dict(eps="1.5", Omega2="5"),
                    dict(a="100", b="1.5", eps="0.01", Omega2="0.001")]


@pytest.mark.parametrize("params", RUDENKO_VARIANTS)
def test_rudenko_system_determinant_is_equation_1(params):
    """det(lambda^2 M + lambda G + K) = lambda^2 Q(omega) up to a constant: Q is Rudenko's quartic, exactly."""
    scene = load_scene("rudenko1976_system")
    scene = dataclasses.replace(scene, parameters=dict(scene.parameters, **params))
    model = validate(scene)
    P, mu, Q, odd = polynomial_facts(model)
    assert mu == 2 and odd == [] and Q is not None
    v = model.values
    R = characteristic_quartic(v["a"], v["b"], v["eps"], v["Omega2"])
    assert Q == R / R.leading_coefficient()
    K, C, M = model.matrix("K"), model.matrix("G"), model.matrix("M")
    assert det_by_expansion([K, C, M]) == P == det_by_interpolation([K, C, M])


@pytest.mark.parametrize("params", [{}, dict(eps="1.5", Omega2="5")])
def test_rudenko_system_gives_the_specialised_roots_and_verdicts(params):
    special = load_scene("rudenko1976")
    special = dataclasses.replace(special, parameters=dict(special.parameters, **params))
    general = load_scene("rudenko1976_system")
    general = dataclasses.replace(general, parameters=dict(general.parameters, **params))
    s = json.loads(json.dumps(prove_scene(special).to_json()))
    g = proved(general)
    assert status(g, "roots") == status(s, "roots") == "proved"
    assert status(g, "stability") == "proved"
    for j in range(1, 5):     # the same exact polynomial, the same isolation: identical enclosures
        assert g["quantities"][f"omega_{j}"] == s["quantities"][f"omega_{j}"]
        assert g["quantities"][f"freq_hz_{j}"] == s["quantities"][f"freq_hz_{j}"]
    per_root = {r["root"]: r["status"] for r in claim(g, "brackets")["details"]["per_root"]}
    for j in range(1, 5):     # the brackets: the same formulas written as expressions
        assert per_root[f"omega_{j}"] == status(s, f"bracket_{j}"), j
        for side in ("lo", "hi"):
            a, b = s["quantities"][f"bracket_{j}_{side}"], g["quantities"][f"bracket_{j}_{side}"]
            assert Fraction(a["lo"]) <= Fraction(b["hi"]) and Fraction(b["lo"]) <= Fraction(a["hi"])
    expected = "proved" if not params else "refuted"
    assert status(g, "brackets") == expected
    assert confirmed(g)


def test_rudenko_system_certificate_forgeries_are_caught():
    g = proved(load_scene("rudenko1976_system"))
    assert confirmed(g)
    for cid in ("roots", "stability", "brackets"):
        f = copy.deepcopy(g)
        c = claim(f, cid)
        c["status"], c["counterexample"] = "refuted", {"forged": "yes"}
        assert items(f)[cid] is False, cid
    f = copy.deepcopy(g)
    q = f["quantities"]["omega_1"]
    lo, hi = Fraction(q["lo"]), Fraction(q["hi"])
    q["lo"], q["hi"] = str(hi + (hi - lo)), str(hi + 2 * (hi - lo))       # beside the root: no sign change
    assert items(f)["omega_1"] is False
    f = copy.deepcopy(g)
    q = f["quantities"]["bracket_2_hi"]
    q["lo"], q["hi"] = "1", "2"
    assert items(f)["bracket_2_hi"] is False


# ----------------------------------------------------------------------------- systems with known answers

def test_gyroscopic_stabilisation_proved_with_the_analytic_roots():
    """k1 = k2 = -1 (both unstable alone), g = 3: Q = omega^2 - 7 omega + 1, roots (7 -+ sqrt 45)/2 > 0."""
    data = proved(two_dof("3", options={"hz_scale": "2"}))
    assert [status(data, c) for c in ("roots", "stability")] == ["proved"] * 2
    with working_precision(256):
        exact = [(7 - arb(45).sqrt()) / 2, (7 + arb(45).sqrt()) / 2]
        for j, w in enumerate(exact, start=1):
            assert meets(interval(data["quantities"][f"omega_{j}"]), w)
            assert meets(interval(data["quantities"][f"freq_hz_{j}"]), 2 * w.sqrt())
    assert confirmed(data)


@pytest.mark.parametrize("g,k2,key,why", [
    ("1", "-1", "nonreal_roots", "flutter"),          # g^2 < 4: a complex pair omega
    ("2", "-1", "gcd_with_derivative", "multiple"),   # g^2 = 4: a double root, exactly
    ("1", "1", "negative_roots", "divergence"),       # k1 k2 < 0: a negative omega
])
def test_unstable_systems_are_refuted_with_the_reason(g, k2, key, why):
    data = proved(two_dof(g, k2=k2, brackets=[["0", "1"]]))
    for cid in ("roots", "stability"):
        c = claim(data, cid)
        assert c["status"] == "refuted" and key in c["counterexample"] and why in c["reason"], c
    assert status(data, "brackets") == "inconclusive"
    assert confirmed(data)


def test_damping_refutes_with_the_odd_terms():
    data = proved(two_dof("3", D=[["1/10", "0"], ["0", "0"]]))
    for cid in ("roots", "stability"):
        c = claim(data, cid)
        assert c["status"] == "refuted" and c["counterexample"]["odd_powers"] == [1, 3], c
        assert len(c["counterexample"]["offaxis_roots"]) == 4       # the damped pairs, each certainly off the axis
    assert confirmed(data)


def test_zero_roots_must_be_declared_exactly():
    free = dict(M=[["1", "0"], ["0", "1"]], K=[["0", "0"], ["0", "1"]], G=[["0", "1"], ["-1", "0"]])
    data = proved(system(**free))                        # lambda = 0 twice, none declared
    c = claim(data, "stability")
    assert c["status"] == "refuted" and c["counterexample"]["zero_root_multiplicity"] == 2
    assert confirmed(data)
    data = proved(system(**free, options={"zero_roots": "2"}))
    assert status(data, "stability") == "proved" and status(data, "roots") == "proved"
    assert confirmed(data)
    data = proved(system(**dict(free, K=[["1", "0"], ["0", "1"]]), options={"zero_roots": "2"}))
    assert claim(data, "roots")["counterexample"]["zero_root_multiplicity"] == 0
    assert confirmed(data)


def test_brackets_are_decided_per_root():
    """omega = (7 -+ sqrt 45)/2 = 0.1459..., 6.854...: the first bracket holds, the second misses, a third
    bracket form has no real value."""
    data = proved(two_dof("3", brackets=[["1/10", "1/5"], ["7", "8"]]))
    c = claim(data, "brackets")
    assert c["status"] == "refuted"
    assert [r["status"] for r in c["details"]["per_root"]] == ["proved", "refuted"]
    assert [v["root"] for v in c["counterexample"]["violations"]] == ["omega_2"]
    assert confirmed(data)
    data = proved(two_dof("3", brackets=[["sqrt(-1)", "1"], ["(7 - sqrt(45))/2 + 6", "7"]],
                          claims=("roots", "brackets")))
    c = claim(data, "brackets")
    assert c["status"] == "refuted" and [r["status"] for r in c["details"]["per_root"]] == ["refuted", "proved"]
    assert "no real value" in c["details"]["per_root"][0]["reason"]
    assert confirmed(data)
    data = proved(two_dof("3", brackets=[["(7 - sqrt(45))/2", "(7 - sqrt(45))/2"]]))
    assert status(data, "brackets") == "inconclusive"     # the exact root itself: never certified strictly
    data = proved(two_dof("3", brackets=[["0", "s"]], defs=["s = sqrt(g) / 10"]))
    assert status(data, "brackets") == "proved"


def test_a_bracket_bound_that_is_not_a_finite_ball_is_named_as_such():
    """1/(sqrt(g) - sqrt(3)) at g = 3 divides by a ball about 0 (never exact: sqrt 3 is irrational): the claim is
    inconclusive (a precision may not help, but is never a refutation) and says the bound could not be evaluated."""
    data = proved(two_dof("3", brackets=[["1/(sqrt(g)-sqrt(3))", "1"]], claims=("roots", "brackets")))
    c = claim(data, "brackets")
    assert c["status"] == "inconclusive"
    assert ("omega_1 (its lower bound '1/(sqrt(g)-sqrt(3))' could not be evaluated: not a finite ball at this "
            "precision (it may divide by zero") in c["reason"]
    assert "could not be evaluated" in c["details"]["per_root"][0]["reason"]
    data = proved(two_dof("3", brackets=[["(7 - sqrt(45))/2", "(7 - sqrt(45))/2"]]))
    assert "could not be evaluated" not in claim(data, "brackets")["reason"]    # finite bounds: no such words


def test_a_forged_bracket_refutation_is_caught():
    data = proved(two_dof("3", brackets=[["1/10", "1/5"], ["7", "8"]]))
    f = copy.deepcopy(data)
    per = claim(f, "brackets")["details"]["per_root"]
    per[0]["status"], per[1]["status"] = "refuted", "proved"
    assert items(refix(f))["brackets"] is False


def test_numpy_eigenvalues_lie_in_the_enclosures():
    """Cross-check (floats only check): random 3-DOF systems, the companion linearisation's eigenvalues."""
    np = pytest.importorskip("numpy")
    rng = np.random.default_rng(7)
    for _ in range(4):
        A = rng.integers(-3, 4, (3, 3))
        M = A @ A.T + 3 * np.eye(3, dtype=int)
        B = rng.integers(-3, 4, (3, 3))
        K = B @ B.T + np.eye(3, dtype=int)
        C = rng.integers(-3, 4, (3, 3))
        G = C - C.T
        text = lambda X: [[str(int(x)) for x in row] for row in X]
        data = proved(system(text(M), text(K), G=text(G), claims=("roots", "stability")))
        assert status(data, "stability") == "proved"       # M, K > 0: stable whatever G
        Mi = np.linalg.inv(M.astype(float))
        L = np.block([[np.zeros((3, 3)), np.eye(3)], [-Mi @ K, -Mi @ G]])
        omegas = sorted({round(float(-(z * z).real), 9) for z in np.linalg.eigvals(L)})
        for j, w in enumerate(omegas, start=1):
            q = data["quantities"][f"omega_{j}"]
            assert abs(w - float(Fraction(q["lo"]))) <= 1e-7 * max(1.0, w)


# ----------------------------------------------------------------------------- bad models: exit 2, entry named

HEAD = """name = "bad"
kind = "eigenfrequencies"
[parameters]
k = "2"
[claims]
only = {claims}
[options]
{options}
[system]
{system}
"""
GOOD = {"M": '[["1", "0"], ["0", "1"]]', "K": '[["k", "0"], ["0", "1"]]', "G": '[["0", "1"], ["-1", "0"]]'}


def _toml(system=None, options="", claims='["roots", "stability"]', drop=()):
    table = dict(GOOD, **(system or {}))
    body = "\n".join(f"{k} = {v}" for k, v in table.items() if k not in drop)
    return HEAD.format(system=body, options=options, claims=claims)


BAD = [
    (dict(system={"M": '[["1", "0"], ["0"]]'}), r"\[system\] M: row 2 has 1 entries"),
    (dict(system={"K": '[["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]]'}), r"\[system\] K: has 3 rows; M is 2 x 2"),
    (dict(system={"M": '[["1", "2"], ["3", "1"]]'}), r"\[system\] M must be symmetric: M\[1\]\[2\] = '2'"),
    (dict(system={"K": '[["k", "1"], ["0", "1"]]'}), r"\[system\] K must be symmetric: K\[1\]\[2\]"),
    (dict(system={"G": '[["1", "1"], ["-1", "0"]]'}), r"\[system\] G must be skew-symmetric .*G\[1\]\[1\]"),
    (dict(system={"G": '[["0", "1"], ["1", "0"]]'}), r"\[system\] G must be skew-symmetric .*G\[1\]\[2\]"),
    (dict(system={"D": '[["0", "1"], ["0", "0"]]'}), r"\[system\] D must be symmetric \(its skew part belongs in G\)"),
    (dict(system={"K": '[["kk", "0"], ["0", "1"]]'}), r"\[system\] K\[1\]\[1\]: .*unknown name 'kk' \(did you mean 'k'\?\)"),
    (dict(system={"M": '[["1/(k-2)", "0"], ["0", "1"]]'}), r"\[system\] M\[1\]\[1\]: '1/\(k-2\)' divides by zero"),
    (dict(system={"M": '[["k", "k"], ["k", "k"]]'}), r"\[system\] M is singular"),
    (dict(system={"M": '[["1", "0"], ["0", "sqrt(2)"]]'}), r"M\[2\]\[2\]: .*unknown function 'sqrt'"),
    (dict(system={"M": '[["1", "0"], ["0", "1 +"]]'}), r"M\[2\]\[2\]: cannot read '1 \+': it ends too early"),
    (dict(system={"M": '"1"'}), r"\[system\] M: expected a list of rows"),
    (dict(drop=("K",)), r"\[system\]: missing K"),
    (dict(system={"Mass": '[["1"]]'}), r"\[system\]: unknown key 'Mass' \(did you mean 'M'\?\)"),
    (dict(options='zero_roots = "1"'), r"option 'zero_roots' = '1': must be even"),
    (dict(options='zero_roots = "6"'), r"option 'zero_roots' = '6': need an integer from 0 to 4"),
    (dict(options='hz_scale = "k - 2"'), r"option 'hz_scale' = 'k - 2': must be positive"),
    (dict(options='hz_scale = "q"'), r"option 'hz_scale'.*unknown name 'q'"),
    (dict(options='tolerance = "1"'), r"unknown option\(s\) \['tolerance'\]"),
    (dict(system={"brackets": '[["0", "1"], ["0", "2"], ["0", "3"]]'}), r"\[system\] brackets: 3 brackets but the system has 2"),
    (dict(system={"brackets": '[["0"]]'}), r"\[system\] brackets: expected a list of \[lower, upper\] pairs"),
    (dict(system={"brackets": '[["0", "z"]]'}), r"\[system\] brackets\[1\] upper: .*unknown name 'z'"),
    (dict(system={"defs": '["k = 2"]'}), r"\[system\] defs\[1\]: the name 'k' is already"),
    (dict(system={"defs": '["2 = k"]'}), r"\[system\] defs\[1\]: expected \"name = expression\""),
    (dict(system={"defs": '["r = sqrt(k)"]', "K": '[["r", "0"], ["0", "1"]]'}),
     r"\[system\] K\[1\]\[1\]: uses the def 'r', which takes a square root"),
    (dict(system={"defs": '["sqrt = k"]'}), r"\[system\] defs\[1\]: the name 'sqrt' is a function's"),
    (dict(claims='["roots", "brackets"]'), r"claim 'brackets' is asked for but \[system\] gives no brackets"),
    (dict(claims='["roots", "nu_ordering"]'), r"claim\(s\) \['nu_ordering'\] belong to the paper's parameterisation"),
    (dict(system={"K": '[["2", "0"], ["0", "1"]]'}), r"parameter 'k': not used by any entry of \[system\] \(a misspelt"),
]


@pytest.mark.parametrize("kw", [dict(options='hz_scale = "k"'), dict(system={"defs": '["w = k"]'}),
                                dict(system={"brackets": '[["0", "k"]]'}, claims='["roots", "brackets"]')],
                         ids=["hz_scale", "defs", "brackets"])
def test_a_parameter_named_only_outside_the_matrices_is_used(kw):
    """The unused-parameter check reads every entry, not only M, G, K, D."""
    from rigor_gyro import parse_scene
    from rigor_gyro.kinds.eigenfrequencies.claims import validate
    text = _toml(**dict(kw, system={"K": '[["2", "0"], ["0", "1"]]', **kw.get("system", {})}))
    assert validate(parse_scene(text)).params.keys() == {"k"}


@pytest.mark.parametrize("kw,match", BAD, ids=[m[:40] for _, m in BAD])
def test_bad_models_exit_2_naming_the_entry(tmp_path, capsys, kw, match):
    import re

    from rigor_gyro.cli import main
    path = tmp_path / "bad.toml"
    path.write_text(_toml(**kw))
    assert main(["prove", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert re.search(match, err), err


def test_a_system_scene_gets_its_own_claims_by_default_and_a_paper_scene_has_no_system_claims():
    from rigor_gyro.kinds import kind_module, scene_claims
    from rigor_gyro.prover import requested_claims
    bare = dataclasses.replace(system(GOOD_M, GOOD_K), claims_only=None)
    validate(bare)
    assert requested_claims(bare, *scene_claims(kind_module("eigenfrequencies"), bare)) == ["roots", "stability"]
    with pytest.raises(ParameterError, match=r"need a \[system\] table"):
        validate(dataclasses.replace(load_scene("rudenko1976"), claims_only=["roots", "stability"]))
    with pytest.raises(ParameterError, match=r"takes no \[paper\] table"):
        validate(dataclasses.replace(system(GOOD_M, GOOD_K), paper={"hz_exact": ["1"]}))
    with pytest.raises(ParameterError, match="13 degrees of freedom; at most 12"):
        n = 13
        eye = [["1" if i == j else "0" for j in range(n)] for i in range(n)]
        validate(system(eye, eye))


GOOD_M = [["1", "0"], ["0", "1"]]
GOOD_K = [["1", "0"], ["0", "2"]]


@pytest.mark.parametrize("scene", [two_dof("1"), two_dof("2"), two_dof("3", D=[["1/10", "0"], ["0", "0"]]),
                                   system([["1", "0"], ["0", "1"]], [["0", "0"], ["0", "1"]], G=[["0", "1"], ["-1", "0"]])],
                         ids=["flutter", "double_root", "damped", "zero_roots_undeclared"])
def test_a_forged_stability_proof_of_an_unstable_system_is_caught(scene):
    data = proved(scene)
    f = copy.deepcopy(data)
    for cid in ("roots", "stability"):
        c = claim(f, cid)
        assert c["status"] == "refuted"
        c["status"] = "proved"
        c.pop("counterexample")
    assert items(refix(f))["stability"] is False
    g = copy.deepcopy(data)
    c = claim(g, "stability")
    c["reason"] = "forged"
    assert items(refix(g))["stability"] is True        # a true refutation stays confirmed by re-derivation


def test_an_upper_bound_below_the_root_refutes():
    """omega_1 = 0.1459...: [0, 1/10] misses it from above."""
    data = proved(two_dof("3", brackets=[["0", "1/10"]]))
    c = claim(data, "brackets")
    assert c["status"] == "refuted" and c["details"]["per_root"][0]["status"] == "refuted"
    assert confirmed(data)


def test_a_forged_bracket_proof_is_caught():
    data = proved(two_dof("3", brackets=[["0", "1/10"]]))
    f = copy.deepcopy(data)
    c = claim(f, "brackets")
    c["status"] = "proved"
    c.pop("counterexample")
    assert items(refix(f))["brackets"] is False


def test_the_claim_hooks_for_the_lead():
    from rigor_gyro.kinds.eigenfrequencies.boxes import BOX_CLAIMS, box_claims
    from rigor_gyro.kinds.eigenfrequencies.claims import ALL_CLAIMS, CLAIMS, SYSTEM_CLAIMS, available_claims, statements
    from rigor_gyro.kinds.eigenfrequencies.system_boxes import SYSTEM_BOX_CLAIMS
    assert available_claims(load_scene("rudenko1976")) == (CLAIMS, ALL_CLAIMS)
    sys_scene = load_scene("rudenko1976_system")
    assert list(available_claims(sys_scene)[0]) == ["roots", "stability", "brackets"]
    assert list(available_claims(two_dof("3"))[0]) == ["roots", "stability"]
    assert statements(validate(sys_scene)) == SYSTEM_CLAIMS and statements(validate(load_scene("rudenko1976"))) == CLAIMS
    assert box_claims(validate(sys_scene)) == SYSTEM_BOX_CLAIMS and box_claims(validate(load_scene("rudenko1976"))) == BOX_CLAIMS


@pytest.mark.parametrize("scene", [
    system([["1", "0"], ["0", "2"]], [["1", "0"], ["0", "-3"]], G=[["0", "1"], ["-1", "0"]]),    # det M = 2
    system([["-1"]], [["4"]]),                                                                   # one degree
    system([["1", "0"], ["0", "1"]], [["-1", "0"], ["0", "-1"]], G=[["0", "1"], ["-1", "0"]])], # flutter, monic
    ids=["det_M_2", "one_dof", "flutter"])
def test_a_refutation_with_a_non_monic_characteristic_polynomial_is_confirmed(scene):
    """Fuzzing (session 9): the certificate states the frequency polynomial monic; the checker compared its own
    unnormalised one (det M != 1, or an odd number of degrees of freedom), and fitted the stored root boxes,
    refined beyond the certificate's precision, with roots at that precision only: every such refutation failed
    its check."""
    data = proved(scene)
    assert data["verdict"] == "refuted" and confirmed(data)
    ce = next(c["counterexample"] for c in data["claims"] if c["status"] == "refuted")
    assert Fraction(ce["frequency_polynomial"][-1]) == 1
    bad = copy.deepcopy(data)
    for c in bad["claims"]:
        for r in (c.get("counterexample") or {}).get("negative_roots", []):
            r[0], r[1] = "-1000.5", "-1000.25"            # a box holding no root
    if bad != data:
        assert not confirmed(refix(bad))


def test_a_stored_root_box_must_hold_a_root_of_the_checkers_polynomial():
    """counterexample_ok on the det M = 2 system (Q = omega^2 - 3/2): the stored negative root box around
    -sqrt(3/2) at 260 bits holds a root (found at doubled precisions); a box beside it does not."""
    from rigor_gyro.kinds.eigenfrequencies.system_check import counterexample_ok, frequency_data
    data = proved(system([["1", "0"], ["0", "2"]], [["1", "0"], ["0", "-3"]], G=[["0", "1"], ["-1", "0"]]))
    ce = next(c["counterexample"] for c in data["claims"] if c["status"] == "refuted")
    model = validate(Scene.from_header(data["scene"]))
    with working_precision(128):
        P, mu, odd, Q = frequency_data(model)
        assert counterexample_ok(ce, P, mu, odd, Q, model.zero_roots)[0]
        moved = dict(ce, negative_roots=[["-1.2", "-1.1"]])
        assert not counterexample_ok(moved, P, mu, odd, Q, model.zero_roots)[0]


def test_an_exact_double_root_is_refuted_at_the_first_precision():
    """M = K = I: Q has the double root omega = 1, refuted exactly; no enclosure width is asked of a root that is
    not stored, so the escalation stops at the first precision (it doubled to --maxprec, hostile fuzzing)."""
    from rigor_gyro import parse_scene, prove_scene
    text = ('name = "d"\nkind = "eigenfrequencies"\n[parameters]\na = "1"\n[system]\n'
            'M = [["1", "0"], ["0", "1"]]\nK = [["1", "0"], ["0", "a"]]\n')
    cert = prove_scene(parse_scene(text))
    assert cert.verdict.value == "refuted" and len(cert.precisions_tried) == 1, cert.precisions_tried


def test_maxprec_32768_leaves_room_for_guard_bits():
    """--maxprec 32768 is documented; the claims add guard bits to the working precision (32768 + 64 stopped a
    scene with exit 2, hostile fuzzing). Beyond the guard room it is still refused."""
    from rigor_gyro.core.balls import GUARD_ROOM, MAX_PREC, current_precision, working_precision
    from rigor_gyro.core.errors import ParameterError
    with working_precision(MAX_PREC):
        with working_precision(current_precision() + 64):
            assert current_precision() == MAX_PREC + 64
    with pytest.raises(ParameterError, match="guard bits"):
        working_precision(MAX_PREC + GUARD_ROOM + 1).__enter__()


def test_margin_and_scan_take_a_system_scenes_own_claims(tmp_path):
    """`rigor-gyro margin --claim stability` on a [system] scene was refused with the paper kind's claim list
    (hostile fuzzing); the threshold (k = -2 for the top: H^2 + 4 J k = 0 with J = 2, H = 4) and a scan are
    found, written and confirmed by the checker."""
    from rigor_gyro.cli import main
    scene = tmp_path / "top.toml"
    scene.write_text('name = "top"\nkind = "eigenfrequencies"\n[parameters]\nJ = "2"\nH = "4"\nk = "-1"\n[system]\n'
                     'M = [["J", "0"], ["0", "J"]]\nG = [["0", "H"], ["-H", "0"]]\nK = [["k", "0"], ["0", "k"]]\n')
    out = tmp_path / "out"
    assert main(["margin", str(scene), "--param", "k", "--lo", "-2.5", "--hi", "-1", "--claim", "stability",
                 "--width", "1e-3", "-o", str(out)]) == 0
    data = json.loads((out / "margin_top_k.json").read_text())
    lo, hi = sorted(Fraction(data[k]) for k in ("proved_at", "refuted_at"))
    assert lo <= -2 <= hi and hi - lo <= Fraction(1, 100)
    assert main(["margin", str(scene), "--param", "k", "--lo", "-2.5", "--hi", "-1", "--scan", "3", "--claim",
                 "stability", "-o", str(out)]) == 0
    assert main(["check", "-q", str(out / "margin_top_k.json"), str(out / "scan_top_k.json")]) == 0
