"""Issue 37 part 1, Lyapunov kind: the centred forms with monotone faces over a parameter box
(``kinds/lyapunov/box_forms.py``) and the coupled Psi test that decides vdot_nonpositive over a box
(``kinds/lyapunov/box_vdot.py``), checked against mpmath at sampled points of the box.

* the lower bound of h_i(x2, P) = ci0 - R_j(P) |(ci1, ci3)| that CentredBox gives on an x2 piece is <= h_i at
  every sampled (x2, P) (mpmath, the approx module's own Psi coefficients and R1, R2);
* radius_bounds contain R1, R2 at every sampled point;
* the +-2.5 % sub-box of the +-5 % example box where the Psi test's margin is smallest is proved in one
  evaluation, and the reason names the faces.
"""
import itertools
import random
from fractions import Fraction

import mpmath
import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov.approx import MP, FloatGimbal, MpGimbal, _domain, _extremum, _r12
from rigor_gyro.kinds.lyapunov.box_forms import CentredBox, balls_of, psi_disc_margin, w_enclosure
from rigor_gyro.kinds.lyapunov.box_vdot import decide_vdot_box, radius_bounds
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.scene import load_scene

F = Fraction
POINT = {"A": F(2), "C": F(33, 10), "A1": F(22, 10), "B1": F(22, 10), "C1": F(28, 10), "A2": F(85, 10),
         "H": F(10000), "k": F(4, 10), "a": F(100), "mu": F(2, 100)}
#: the +-2.5 % sub-box (of the +-5 % box) holding the smallest Psi-test margin found by a float search
WORST = {"A": (F(2), F(21, 10)), "A1": (F(209, 100), F(22, 10)), "A2": (F(85, 10), F(8925, 1000)),
         "B1": (F(22, 10), F(231, 100)), "C1": (F(28, 10), F(294, 100)), "H": (F(10000), F(10500)),
         "k": (F(38, 100), F(4, 10)), "a": (F(95), F(100)), "mu": (F(2, 100), F(21, 1000)), "C": (F(33, 10), F(33, 10))}


@pytest.fixture(scope="module")
def model():
    return validate(load_scene("agafonov2013"))


def _box(rel: Fraction, centre=None) -> dict:
    c = centre or POINT
    return {k: (v * (1 - rel), v * (1 + rel)) for k, v in c.items()}


def _mp_point(p: dict) -> MpGimbal:
    params = {k: f"{v.numerator}/{v.denominator}" for k, v in p.items()}
    params.update(x2_star="pi/6", moment="sine")
    return MpGimbal(params)


def _mp_radii(g: MpGimbal):
    lo, hi = _domain(g)
    m, _ = _extremum(FloatGimbal(g.params).m_quotient, g.m_quotient, float(lo), float(hi), lo, hi, MP, True)
    return _r12(g, m)


def _samples(raw: dict, n: int, seed: int) -> list[dict]:
    rng = random.Random(seed)
    names = list(raw)
    corners = [dict(zip(names, c)) for c in itertools.islice(itertools.product(*(raw[k] for k in names)), 0, 1024, 97)]
    inner = [{k: lo + (hi - lo) * F(rng.randint(0, 64), 64) for k, (lo, hi) in raw.items()} for _ in range(n)]
    return corners + inner


@pytest.mark.parametrize("raw", [_box(F(1, 20)), WORST, _box(F(1, 100), {**POINT, "mu": F(3, 100)})])
def test_the_lower_form_is_below_h_at_every_sampled_point(model, raw):
    mpmath.mp.dps = 30
    with working_precision(128):
        cb = CentredBox(model.gimbal, raw, w_enclosure(model.gimbal, balls_of(raw)))
        pieces = [(F(1, 10), F(2, 10)), (F(3, 10), F(4, 10)), (F(45, 100), F(52, 100))]
        forms = {(j, i): cb.lower(psi_disc_margin(j, i), positivity=False) for j in ("R1", "R2") for i in (0, 1)}
        bounds = {(j, i): [forms[(j, i)](arb(float(a)).union(arb(float(b)))) for a, b in pieces]
                  for j in ("R1", "R2") for i in (0, 1)}
    for p in _samples(raw, 12, 7):
        g = _mp_point(p)
        r = _mp_radii(g)
        for (j, i), bs in bounds.items():
            for (a, b), bound in zip(pieces, bs):
                for t in (0, F(1, 2), 1):
                    x2 = mpmath.mpf(float(a + (b - a) * t))
                    c0, c1, c3 = g.psi_true(x2)[i]
                    h = c0 - r[j] * mpmath.sqrt(c1 * c1 + c3 * c3)
                    assert bound.lower() <= float(h) * (1 + 1e-12) + 1e-12, (j, i, p, float(x2), bound, h)


@pytest.mark.parametrize("raw", [_box(F(1, 20)), WORST])
def test_radius_bounds_contain_R1_and_R2_at_every_sampled_point(model, raw):
    mpmath.mp.dps = 30
    with working_precision(128):
        cb = CentredBox(model.gimbal, raw, w_enclosure(model.gimbal, balls_of(raw)))
        rb = {j: radius_bounds(cb, j) for j in ("R1", "R2")}
    for p in _samples(raw, 20, 3):
        r = _mp_radii(_mp_point(p))
        for j, (lo, hi) in rb.items():
            assert lo.lower() <= float(r[j]) <= hi.upper(), (j, p, float(r[j]), lo, hi)


def test_the_tightest_sub_box_is_proved_in_one_evaluation_by_the_coupled_psi_test(model):
    with working_precision(128):
        v = decide_vdot_box(model, WORST, 4000)
    assert v is not None and v[0] == "proved"
    assert "fixed at a face" in v[1] and "Psi1 and of Psi2 certified > 0" in v[1]


def test_a_fixed_R_option_is_left_to_the_claims_own_box_evaluation(model):
    import dataclasses
    from flint import fmpq
    with working_precision(128):
        assert decide_vdot_box(dataclasses.replace(model, R_option=fmpq(1, 100)), WORST, 4000) is None


@pytest.mark.slow
def test_the_all_parameters_five_percent_scene_is_proved_by_the_paving():
    """margin_agafonov_all_5_percent (every rational parameter +-5 %): every claim proved over the whole box
    (127 box evaluations, about 30 s of CPU on one worker; issue 37's target)."""
    from rigor_gyro.margins.paving import box_scene, pave
    bs = box_scene(load_scene("margin_agafonov_all_5_percent"))
    p = pave(bs)
    assert p.verdict == "proved", [(c.id, c.status) for c in p.claims]
    assert p.evaluated <= 200
