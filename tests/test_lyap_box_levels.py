"""Issue 37 part 2, Lyapunov kind: c* and the v_positive margin over a parameter box
(``kinds/lyapunov/box_levels.py``, through ``box_quantities.quantities_box``).

Every certified ball contains the quantity at every sampled point of the box (mpmath: the approx module's c*
search; the margin as a dense x2 grid refined by golden section); a box of points agrees with the point
certificate's c*; the margin's sign agrees with the point verdict of ``v_positive`` on both sides.
"""
from fractions import Fraction

import mpmath
import pytest

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.lyapunov import box_quantities as BQ
from rigor_gyro.kinds.lyapunov.approx import MP, FloatGimbal, MpGimbal, _c_star
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene

from .test_lyap_box_quantities import POINT, _box, _inside, _samples, mp_quantities

F = Fraction
LEVELS = ["c_star", "v_positive_margin"]


@pytest.fixture(scope="module")
def model():
    return validate(load_scene("agafonov2013"))


def _params(p: dict) -> dict:
    params = {k: f"{v.numerator}/{v.denominator}" for k, v in {**POINT, **p}.items()}
    params.update(C="33/10", x2_star="pi/6", moment="sine")
    return params


def mp_margin(p: dict, n: int = 400) -> mpmath.mpf:
    """min over [0, x2*] of min(1 - mu/f1, psi/P) in mpmath: a grid, then golden section around its best."""
    mpmath.mp.dps = 30
    g = MpGimbal(_params(p))

    def m(x):
        c = mpmath.cos(x)
        t = g.H * c * c / (g.D(x) * g.B0)
        f1 = g.f1(x)
        psi = t * (g.mu * g.H - g.q(x)) + g.mu ** 2 * (f1 - g.mu)
        return min(1 - g.mu / f1, psi / (t * g.mu * g.H + g.mu ** 2 * f1))
    xs = g.xs
    grid = [xs * j / n for j in range(n + 1)]
    vals = [m(x) for x in grid]
    i = min(range(len(vals)), key=vals.__getitem__)
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, n)]
    for _ in range(60):
        a, b = lo + (hi - lo) / 3, hi - (hi - lo) / 3
        if m(a) < m(b):
            hi = b
        else:
            lo = a
    return min(vals[i], m((lo + hi) / 2))


def mp_c_star(p: dict) -> mpmath.mpf:
    mpmath.mp.dps = 30
    params = _params(p)
    g, fg = MpGimbal(params), FloatGimbal(params)
    return _c_star(g, fg, mp_quantities(p)["R"])["c_star"]


def test_every_sampled_value_lies_in_the_certified_ball(model):
    box = _box(F(1, 100))
    with working_precision(128):
        q = BQ.quantities_box(model, box, LEVELS)
    assert set(q) == set(LEVELS)
    for p in _samples(box, 6, 5):
        assert _inside(q["v_positive_margin"].value, mp_margin(p), rel=1e-9), p
        assert _inside(q["c_star"].value, mp_c_star(p), rel=1e-9), p


def test_a_box_of_points_gives_a_tight_ball_and_the_point_certificates_c_star(model):
    box = Box.of({k: (v, v) for k, v in POINT.items()})
    with working_precision(128):
        q = BQ.quantities_box(model, box, LEVELS)
    cert = prove_scene(load_scene("agafonov2013"))
    point = cert.quantities["c_star"]
    assert q["c_star"].value.overlaps(point)
    assert q["c_star"].value.rad() < 1e-6 * abs(q["c_star"].value.mid())
    v = q["v_positive_margin"].value
    assert v.rad() < 1e-6 and 0 < v.lower() and v.upper() < 1
    assert _inside(v, mp_margin({}), rel=1e-9)


@pytest.mark.parametrize("mu,sign", [("1/100", -1), ("2/100", 1)])
def test_the_margins_sign_agrees_with_the_point_verdict_of_v_positive(model, mu, sign):
    """mu = 0.01 is below the range where V > 0 (v_positive refuted at a point), 0.02 the example."""
    mu = F(mu)
    box = Box.of({**{k: (v, v) for k, v in POINT.items()}, "mu": (mu, mu)})
    with working_precision(128):
        v = BQ.quantities_box(model, box, ["v_positive_margin"])["v_positive_margin"].value
    scene = load_scene("agafonov2013")
    scene.parameters["mu"] = f"{mu.numerator}/{mu.denominator}"
    scene.claims_only = ["v_positive"]
    status = prove_scene(scene).claim("v_positive").status.value
    assert status == ("proved" if sign > 0 else "refuted")
    assert (v.lower() > 0) if sign > 0 else (v.upper() < 0)


def test_the_psi_margin_is_enclosed_on_the_whole_five_percent_box(model):
    """Over the +-5 % box R's formula reaches near 0 and the coupled upper bound is not finite: the loose upper
    bound (R_sup's naive bound at exact x2 points over R's lower bound) still states a ball containing every
    sampled value."""
    box = _box(F(1, 20))
    with working_precision(128):
        q = BQ.quantities_box(model, box, ["psi_margin"])
    assert "psi_margin" in q
    v = q["psi_margin"].value
    for p in _samples(box, 2, 3)[:4]:
        assert _inside(v, mp_quantities(p, psi=True)["psi_margin"]), p
