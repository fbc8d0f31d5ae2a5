"""A [plant] relay model over a box of its parameters (kinds/periodic_orbit/plant_box.py, issue 42 part 1): the same
verdicts as the paper's parameterisation over the same boxes, every certified enclosure against mpmath samples
of the box, the refusals."""
from __future__ import annotations

import dataclasses
import itertools
import random
from fractions import Fraction as F

import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.boxes import box_claims, evaluate_box, validate_box
from rigor_gyro.kinds.periodic_orbit.flow import DegenerateSpectrum
from rigor_gyro.kinds.periodic_orbit.plant_box import PlantBoxSpectrum, _theta_over_box, disc_bound, plant_balls
from rigor_gyro.kinds.periodic_orbit.plant_claims import analyse, classify, plant_multipliers
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
np = pytest.importorskip("numpy")

SIX = ("A", "B", "H", "tau", "sigma", "n")


def _scene(name="roitenberg1947_plant"):
    return load_scene(name)


def _exact(scene) -> dict:
    return {k: F(str(v)) for k, v in scene.parameters.items()}


def _box(scene, rel: F, names) -> Box:
    ex = _exact(scene)
    return Box.of({k: (ex[k] * (1 - rel), ex[k] * (1 + rel)) for k in names})


def _member(scene, point: dict):
    """The validated [plant] model at a point of the box (exact)."""
    params = dict(scene.parameters)
    params.update({k: f"{v.numerator}/{v.denominator}" for k, v in point.items()})
    return validate(dataclasses.replace(scene, parameters=params))


def _samples(box: Box, n: int, seed: int = 7):
    rng = random.Random(seed)
    ivs = [box.interval(k) for k in box.names]
    for c in itertools.product(*ivs):
        yield dict(zip(box.names, c))
    for _ in range(n):
        yield {k: lo + (hi - lo) * F(rng.randrange(1001), 1000) for k, (lo, hi) in zip(box.names, ivs)}


@pytest.mark.parametrize("rel,names", [(F(1, 10 ** 6), ("H",)), (F(1, 10 ** 6), ("A", "H")), (F(1, 10 ** 8), SIX)])
def test_plant_and_paper_give_the_same_verdicts_over_the_same_box(rel, names):
    plant, paper = _scene(), _scene("roitenberg1947")
    with working_precision(128):
        outs = []
        for sc in (plant, paper):
            m = validate(sc)
            box = _box(sc, rel, names)
            validate_box(m, box)
            outs.append(evaluate_box(m, box, ["orbit_genuine", "stable"]))
    assert {c: st for c, (st, _) in outs[0].items()} == {c: st for c, (st, _) in outs[1].items()} == \
        {"orbit_genuine": "proved", "stable": "proved"}


def test_box_claims_of_a_plant_model_are_genuine_and_stable():
    assert set(box_claims(validate(_scene()))) == {"orbit_genuine", "stable"}


def _theta_mp(model, lo: float, hi: float) -> float:
    with mp.workdps(20):
        a, b = mp.mpf(lo), mp.mpf(hi)
        ga = approx.plant_g_mp(model, a, 20)
        assert ga * approx.plant_g_mp(model, b, 20) < 0
        for _ in range(32):
            c = (a + b) / 2
            if approx.plant_g_mp(model, c, 20) * ga > 0:
                a = c
            else:
                b = c
        return float((a + b) / 2)


@pytest.mark.parametrize("rel,names", [(F(1, 10 ** 6), ("A", "H")),
                                       pytest.param(F(1, 10 ** 5), SIX, marks=pytest.mark.slow)])
def test_box_enclosures_hold_mpmath_samples(rel, names):
    """Eigenvalues, theta*(P) and the largest multiplier modulus over a box of A and H (+-1e-6 relative) and of
    all six (+-1e-5, decided since the centred coefficients): each sampled member's value (mpmath; the
    multipliers by scipy) inside the certified enclosure."""
    sc = _scene()
    m = validate(sc)
    box = _box(sc, rel, names)
    with working_precision(128):
        sp = PlantBoxSpectrum(m, box)
        v = [r for r in analyse(m).roots if r.kind == "genuine"][0]
        Theta = _theta_over_box(sp, v.theta)
        assert Theta is not None
        w = classify(sp, Theta)
        assert w.kind == "genuine"
        mx = disc_bound(sp, w)
        plant_multipliers(sp, w)
        Mb = plant_balls(m, box)[0]
    ranges = [mx] if mx is not None and mx < 1 else []
    if w.stable is True:
        top = w.moduli[0]
        for r in w.moduli[1:]:
            top = top.max(r)
        ranges.append(top)
    assert ranges, "neither Rump's method nor the discs decided the box"
    for pt in itertools.islice(_samples(box, 2), 0, None, 1 if len(names) < 3 else 16):
        mm = _member(sc, pt)
        M = mp.matrix([[mp.mpf(int(mm.M[i, j].p)) / int(mm.M[i, j].q) for j in range(5)] for i in range(5)])
        with working_precision(128):
            assert all(Mb[i, j].contains(arb(mm.M[i, j])) for i in range(5) for j in range(5))
        ev = mp.eig(M)[0]
        for mode in sp.modes:                    # every enclosed eigenvalue holds one of the member's
            assert any(mode.lam.real.lower() <= float(mp.re(z)) <= mode.lam.real.upper() and
                       abs(float(mp.im(z))) >= float(abs(mode.lam.imag).lower()) - 1e-12 and
                       abs(float(mp.im(z))) <= float(abs(mode.lam.imag).upper()) + 1e-12 for z in ev)
        th = _theta_mp(mm, float(Theta.lower()) - 1e-6, float(Theta.upper()) + 1e-6)
        assert float(Theta.lower()) <= th <= float(Theta.upper())
        pd = {k: F(str(v)) for k, v in sc.parameters.items()}
        pd.update(pt)
        mods = [abs(z) for z in approx.approx_multipliers(pd, th)]
        for r in ranges:
            assert float(r.lower()) <= max(mods) <= float(r.upper())
        if w.stable is True:          # every modulus (sorted) inside its ball
            for r, z in zip(sorted(w.moduli, key=lambda b: float(b.mid())), sorted(mods)):
                assert float(r.lower()) - 1e-12 <= z <= float(r.upper()) + 1e-12


def test_stable_not_claimed_where_the_multipliers_are_not_decided():
    """All six at +-1e-4: the box forms prove orbit_genuine (the centred coefficients and g; the naive ones did
    not at 1e-6) but not stable (neither Rump nor the discs; the Jacobian is naive in the parameters)."""
    sc = _scene()
    m = validate(sc)
    with working_precision(128):
        out = evaluate_box(m, _box(sc, F(1, 10 ** 4), SIX), ["orbit_genuine", "stable"])
    assert out["orbit_genuine"][0] == "proved"
    assert out["stable"][0] == "undecided"


_NONSTRUCTURAL = """
name = "plant_nonstructural_zero"
kind = "periodic_orbit"
source = "test"
[parameters]
a = "2"
[plant]
M = [["0", "1", "0"], ["0", "-a", "1"], ["0", "0", "-1"]]
e = ["0", "0", "1"]
c = ["1", "0", "0"]
[options]
T_max = "20"
"""


def test_zero_eigenvalue_kept_only_when_structural(tmp_path):
    sc = _scene()
    m = validate(sc)
    with working_precision(128):
        PlantBoxSpectrum(m, _box(sc, F(1, 10 ** 6), ("H",)))        # first column zero: structural
    p = tmp_path / "z.toml"
    # a zero eigenvalue at a = 2 only through a cancellation: M[2][1] = a - 2 (0 at the centre, not a constant)
    p.write_text(_NONSTRUCTURAL.replace('M = [["0", "1", "0"], ["0", "-a", "1"]',
                                        'M = [["a - 2", "1", "0"], ["0", "-a", "1"]'), encoding="utf-8")
    m2 = validate(load_scene(str(p)))
    assert m2.zero_eigenvalue
    with working_precision(128), pytest.raises(DegenerateSpectrum, match="not structural"):
        PlantBoxSpectrum(m2, Box.of({"a": (F(199, 100), F(201, 100))}))


def test_box_refusals_name_what_fails(tmp_path):
    sc = _scene()
    m = validate(sc)
    with working_precision(128), pytest.raises(ParameterError, match="not a parameter"):
        validate_box(m, Box.of({"zeta": (F(1), F(2))}))
    p = tmp_path / "h.toml"
    p.write_text(_NONSTRUCTURAL.replace('c = ["1", "0", "0"]', 'c = ["1", "0", "0"]\nh = "a - 2"'), encoding="utf-8")
    m2 = validate(load_scene(str(p)))
    with working_precision(128), pytest.raises(ParameterError, match="h"):
        validate_box(m2, Box.of({"a": (F(199, 100), F(201, 100))}))


@pytest.mark.parametrize("rel,names", [(F(1, 10 ** 5), SIX), (F(1, 10 ** 4), ("H",))])
def test_centred_forms_decide_boxes_the_naive_ones_did_not(rel, names):
    """All six at +-1e-5 (the naive charpoly of the ball matrix left an eigenvalue's real part not separated
    from 0 there, and at +-1e-6 theta* not continued), H alone at +-1e-4 (naive: nothing from 1e-5 on): both
    claims proved now."""
    sc = _scene()
    m = validate(sc)
    with working_precision(128):
        out = evaluate_box(m, _box(sc, rel, names), ["orbit_genuine", "stable"])
    assert {c: st for c, (st, _) in out.items()} == {"orbit_genuine": "proved", "stable": "proved"}


def test_parametric_g_holds_every_sampled_member_and_is_narrow():
    """g(t; P) at the centre's root t over a box of all six at +-1e-4: the centred ball (g_parametric) holds
    each sampled member's g(t) (mpmath) and is at least 10 times narrower than the naive one (14)."""
    from rigor_gyro.kinds.periodic_orbit.plant_box import g_parametric
    from rigor_gyro.kinds.periodic_orbit.plant_orbit import g_coeffs
    sc = _scene()
    m = validate(sc)
    box = _box(sc, F(1, 10 ** 4), SIX)
    with working_precision(128):
        sp = PlantBoxSpectrum(m, box)
        v = [r for r in analyse(m).roots if r.kind == "genuine"][0]
        t = arb(v.theta.mid())
        gc = g_parametric(sp, t)
        naive = g_coeffs(sp, t, 1, pole_free=False)[0]
    assert gc is not None and gc.rad() * 10 < naive.rad()
    tf = mp.mpf(t.mid().str(40, radius=False))
    for pt in itertools.islice(_samples(box, 2), 0, None, 31):
        with mp.workdps(40):
            val = approx.plant_g_mp(_member(sc, pt), tf, 40)
        assert float(gc.lower()) - 1e-25 <= float(val) <= float(gc.upper()) + 1e-25, pt


def test_centred_coefficients_hold_every_sampled_members_exact_ones():
    """p_k, N_i,k and c . N_k over a box of all six at +-1e-3: each sampled member's exact rational coefficient
    (from its exact matrix) inside the ball; the charpoly's recurrence agrees with the exact one at the centre;
    the centred balls are narrower than the naive ones (arb_mat.charpoly of the ball matrix)."""
    from flint import fmpq, fmpq_mat

    from rigor_gyro.kinds.periodic_orbit.plant_box import _exprs
    from rigor_gyro.kinds.periodic_orbit.plant_centred import centred_polynomial_data
    sc = _scene()
    m = validate(sc)
    box = _box(sc, F(1, 10 ** 3), SIX)
    Mx, ex, cx, _, _ = _exprs(m)
    with working_precision(128):
        p, Ns, Nc = centred_polynomial_data((Mx, ex, cx), {k: v.rational for k, v in m.exact.items()}, box)
        naive = plant_balls(m, box)[0].charpoly()
        # -tr M (k = 4) is linear in the entries: no better; the others are 3 to 200 times narrower
        assert all(p[k].rad() * 3 < naive[k].rad() for k in range(4))
        assert p[4].rad() <= naive[4].rad() * (1 + arb("1e-6"))
    for pt in itertools.islice(_samples(box, 3), 0, None, 8):
        mm = _member(sc, pt)
        n = 5
        Mq = fmpq_mat(n, n, [mm.M[i, j] for i in range(n) for j in range(n)])
        P = Mq.charpoly()
        assert all(p[k].contains(arb(P[k])) for k in range(n + 1))
        e = [fmpq(F(str(x)).numerator, F(str(x)).denominator) if not isinstance(x, fmpq) else x for x in mm.e]
        # N_i(z) = adj(z I - M) e: at z = 3 (not an eigenvalue), adj = det (zI - M) (zI - M)^-1
        z = 3
        A = fmpq_mat(n, n, [(z if i == j else 0) - mm.M[i, j] for i in range(n) for j in range(n)])
        ev = fmpq_mat(n, 1, e)
        N = A.solve(ev) * A.det()
        for i in range(n):
            val = sum((Ns[i][k] * z ** k for k in range(n)), arb(0))
            assert val.contains(arb(N[i, 0])), (pt, i)
