"""Each Lyapunov claim proved on its own (``[claims] only``) on planted variants of the paper's scene,
and its certificate confirmed by the independent checker: the outcome each variant must get, the
quantities against mpmath (50 digits), and every status the checker re-derives.

One claim at a time costs 0.1-0.3 s, so this file is the quick net under the claims' decision code
(``kinds/lyapunov/claims.py``, ``sublevel.py``): mutation runs use it, and each test builds what it
checks afresh (no cached proof)."""
import dataclasses
import json
from fractions import Fraction

import pytest

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.check import check_certificate
from rigor_gyro.core.stored import as_ball, interval
from tests.test_properties_lyapunov import contains_ref, mp_values

#: planted variants of the paper's scene (parameters changed, scene options) and, per claim, the outcome
#: each must get; a claim not listed must not be proved-and-wrong (the checker decides that)
VARIANTS = {
    "paper": ({}, {}),
    "faces below 1 (x2* = 1/10)": ({"x2_star": "1/10"}, {}),
    "Vdot binds (x2* = 1.3)": ({"x2_star": "1.3"}, {}),
    "origin refutes c_max (k = 0.2)": ({"k": "0.2"}, {}),
    "faces refute c_max (H = 3000)": ({"H": "3000"}, {}),
    "radius far too large (R = 0.5)": ({}, {"R": "0.5"}),
    "mu below (16) (mu = 0.01)": ({"mu": "0.01"}, {}),
    "linear law": ({"moment": "linear"}, {}),
    "budget of 100 boxes": ({}, {"max_pieces": "100"}),
}

EXPECTED = {
    ("paper", "v_positive"): "proved", ("paper", "vdot_nonpositive"): "proved",
    ("paper", "invariant_estimate"): "proved", ("paper", "largest_sublevel"): "proved",
    ("paper", "equilibria"): "proved", ("paper", "vdot_direct"): "proved", ("paper", "best_mu"): "proved",
    ("paper", "best_mu_direct"): "proved",
    ("faces below 1 (x2* = 1/10)", "largest_sublevel"): "proved",
    ("faces below 1 (x2* = 1/10)", "invariant_estimate"): "proved",
    ("Vdot binds (x2* = 1.3)", "largest_sublevel"): "proved",
    ("origin refutes c_max (k = 0.2)", "largest_sublevel"): "refuted",
    ("faces refute c_max (H = 3000)", "largest_sublevel"): "refuted",
    ("radius far too large (R = 0.5)", "vdot_nonpositive"): "refuted",
    ("radius far too large (R = 0.5)", "invariant_estimate"): "inconclusive",
    ("mu below (16) (mu = 0.01)", "v_positive"): "refuted",
    ("mu below (16) (mu = 0.01)", "best_mu"): "proved",
    ("budget of 100 boxes", "largest_sublevel"): "inconclusive",     # best bound about -9.3: undecided, not refuted
    ("linear law", "invariant_estimate"): "proved", ("linear law", "v_positive"): "proved",
}

#: the claims a proof of CLAIM also asks for (the equilibria's membership needs the estimate)
WITH = {"equilibria": ["invariant_estimate", "equilibria"]}


def _prove(variant: str, claim: str) -> dict:
    params, options = VARIANTS[variant]
    scene = load_scene("agafonov2013")
    scene = dataclasses.replace(scene, name="variant", parameters=dict(scene.parameters, **params),
                                options=dict(scene.options, **options), claims_only=WITH.get(claim, [claim]))
    return json.loads(json.dumps(prove_scene(scene).to_json()))


def _confirm(variant: str, claim: str) -> dict:
    """Prove CLAIM on VARIANT, check the outcome it must get, and have the checker confirm every claim."""
    data = _prove(variant, claim)
    got = {c["id"]: c for c in data["claims"]}[claim]
    want = EXPECTED.get((variant, claim))
    assert want is None or got["status"] == want, (variant, claim, got["status"], got["reason"])
    report = check_certificate(data)
    assert report.ok, (variant, claim, [str(x) for x in report.items if not x.ok][:3])
    return data


def _q(data: dict, name: str) -> Fraction:
    return Fraction(data["quantities"][name]["lo"]), Fraction(data["quantities"][name]["hi"])


def _run(claim: str, variants=tuple(VARIANTS)):
    return {v: _confirm(v, claim) for v in variants}


def test_v_positive_on_every_variant():
    _run("v_positive")


def test_vdot_nonpositive_on_every_variant():
    _run("vdot_nonpositive")


def test_invariant_estimate_on_every_variant_and_c_star_against_mpmath():
    """c* (the boundary minimum of V over region (17)) contains mpmath's at 50 digits where mpmath has one;
    c_set is below c*'s lower end and the axis segments lie inside the extents."""
    out = _run("invariant_estimate")
    for variant in ("paper", "faces below 1 (x2* = 1/10)", "linear law"):
        data = out[variant]
        params = dict(load_scene("agafonov2013").parameters, **VARIANTS[variant][0])
        ref = mp_values(tuple(sorted(params.items())))
        lo, hi = _q(data, "c_star")
        if ref["c_star"] is not None:
            assert lo <= Fraction(ref["c_star"]) * (1 + Fraction(1, 10 ** 12)) and \
                Fraction(ref["c_star"]) * (1 - Fraction(1, 10 ** 12)) <= hi, (variant, lo, hi, ref["c_star"])
        inv = next(c for c in data["claims"] if c["id"] == "invariant_estimate")
        c_set = Fraction(inv["details"]["c_set"])
        assert 0 < c_set < lo
        for axis in ("x1", "x2", "x3"):
            assert _q(data, f"extent_{axis}_axis")[0] <= _q(data, f"extent_{axis}")[1], (variant, axis)


def test_largest_sublevel_on_every_variant():
    """Which part binds is stated as the theory has it: the faces where c_max = min phi(+-x2*) (the paper's
    x2* and 1/10), the set {Vdot >= 0} at x2* = 1.3; the stored cover has at most the boxes counted."""
    out = _run("largest_sublevel")
    binds = {"paper": "faces", "faces below 1 (x2* = 1/10)": "faces", "Vdot binds (x2* = 1.3)": "vdot"}
    for variant, want in binds.items():
        claim = next(c for c in out[variant]["claims"] if c["id"] == "largest_sublevel")
        assert claim["details"]["binds"] == want and claim["details"]["boxes"] > 0, variant
        assert 0 < len(out[variant]["witnesses"]["largest_sublevel"]["boxes"]) <= claim["details"]["boxes"]


def test_equilibria_on_every_variant():
    _run("equilibria")


def test_vdot_direct_on_every_variant():
    _run("vdot_direct", ("paper", "faces below 1 (x2* = 1/10)", "Vdot binds (x2* = 1.3)", "linear law"))


def test_best_mu_on_every_variant_and_R_sup_against_mpmath():
    """R_sup at the chosen mu_best contains mpmath's value there; mu_best lies inside (16)."""
    out = _run("best_mu", ("paper", "mu below (16) (mu = 0.01)", "linear law"))
    for variant, data in out.items():
        claim = next(c for c in data["claims"] if c["id"] == "best_mu")
        if claim["status"] != "proved":
            continue
        params = dict(load_scene("agafonov2013").parameters, **VARIANTS[variant][0])
        at = mp_values(tuple(sorted(dict(params, mu=claim["details"]["mu_best"]).items())))
        assert contains_ref(as_ball(interval(data["quantities"]["R_sup_at_mu_best"])), at["R_sup"]), variant
        lo, hi = _q(data, "mu_min")[0], _q(data, "mu_max")[1]
        assert lo < Fraction(claim["details"]["mu_best"]) < hi


def test_best_mu_direct_on_every_variant():
    _run("best_mu_direct", ("paper", "linear law"))


@pytest.mark.parametrize("variant", ["paper", "radius far too large (R = 0.5)"])
def test_every_claim_at_once_matches_the_claims_one_at_a_time(variant):
    """The orchestration (``attempt``): proving every claim together gives each claim the status it gets
    alone (the shared memo of constants changes nothing), and the checker confirms the whole."""
    params, options = VARIANTS[variant]
    scene = load_scene("agafonov2013")
    scene = dataclasses.replace(scene, name="variant", parameters=dict(scene.parameters, **params),
                                options=dict(scene.options, **options))
    whole = json.loads(json.dumps(prove_scene(scene).to_json()))
    assert check_certificate(whole).ok
    for c in whole["claims"]:
        if (variant, c["id"]) in EXPECTED:
            assert c["status"] == EXPECTED[(variant, c["id"])], (variant, c["id"], c["reason"])
