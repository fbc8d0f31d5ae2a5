"""Issue 37 part 2, Lyapunov kind: quantities over a parameter box (``kinds/lyapunov/box_quantities.py``).

Every certified ball contains the quantity at every sampled point of the box (mpmath: the approx module's own
m, M, R1, R2 and R_sup); a box of points gives a tight ball; the damping margin's certified lower bound over a
box is <= a float optimiser's minimum, within a relative gap of 1e-3.
"""
import itertools
import random
from fractions import Fraction

import mpmath
import pytest

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.lyapunov import box_quantities as BQ
from rigor_gyro.kinds.lyapunov.approx import MP, FloatGimbal, MpGimbal, _domain, _extremum, _r12, _r_sup
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.scene import load_scene

F = Fraction
POINT = {"A": F(2), "A1": F(22, 10), "B1": F(22, 10), "C1": F(28, 10), "A2": F(85, 10),
         "H": F(10000), "k": F(4, 10), "a": F(100), "mu": F(2, 100)}


@pytest.fixture(scope="module")
def model():
    return validate(load_scene("agafonov2013"))


def _box(rel: Fraction, names=tuple(POINT)) -> Box:
    return Box.of({k: (POINT[k] * (1 - rel), POINT[k] * (1 + rel)) for k in names})


def mp_quantities(p: dict, psi: bool = False) -> dict:
    """The point quantities in mpmath (30 digits) from the approx module (no guarantee; a cross-check)."""
    params = {k: f"{v.numerator}/{v.denominator}" for k, v in {**POINT, **p}.items()}
    params.update(C="33/10", x2_star="pi/6", moment="sine")
    mpmath.mp.dps = 30
    g, fg = MpGimbal(params), FloatGimbal(params)
    lo, hi = _domain(g)
    m, _ = _extremum(fg.m_quotient, g.m_quotient, float(lo), float(hi), lo, hi, MP, True)
    M, _ = _extremum(fg.q, g.q, float(lo), float(hi), lo, hi, MP, True)
    p_ = max(M, g.A0 * m / mpmath.cos(g.xs) ** 2)
    r = _r12(g, m)
    out = {"A0": g.A0, "B0": g.B0, "C0": g.C0, "mu_max": g.k / g.A0, "mu_min": p_ / g.H, "k_min": p_ * g.A0 / g.H,
           "R1": r["R1"], "R2": r["R2"], "R": r["R"],
           "damping_margin": min(g.k * g.H / (p_ * g.A0), g.k / (g.mu * g.A0)) - 1}
    if psi:
        out["psi_margin"] = _r_sup(g, fg, g.mu)[0] / r["R"] - 1
    return out


def _samples(box: Box, n: int, seed: int) -> list[dict]:
    rng = random.Random(seed)
    names = box.names
    corners = [dict(zip(names, c)) for c in itertools.islice(itertools.product(*(box.interval(k) for k in names)),
                                                              0, 512, 61)]
    return corners + [{k: lo + (hi - lo) * F(rng.randint(0, 100), 100) for k, lo, hi in box.edges} for _ in range(n)]


def _inside(ball, x, rel=1e-12) -> bool:
    x = float(x)
    slack = abs(x) * rel + 1e-300
    return float(ball.lower()) <= x + slack and x - slack <= float(ball.upper())


@pytest.mark.parametrize("rel", [F(1, 20), F(1, 100)])
def test_every_sampled_value_lies_in_the_certified_ball(model, rel):
    box = _box(rel)
    with working_precision(128):
        q = BQ.quantities_box(model, box, list(BQ.BOX_QUANTITIES))
    assert {"A0", "k_min", "mu_min", "mu_max", "damping_margin", "R1", "R2", "R"} <= set(q)
    for i, p in enumerate(_samples(box, 25, 11)):
        v = mp_quantities(p, psi=i % 6 == 0 and "psi_margin" in q)
        for name, x in v.items():
            assert _inside(q[name].value, x), (name, p, float(x), q[name].value)


def test_gradients_contain_sampled_difference_quotients(model):
    box = _box(F(1, 50))
    with working_precision(128):
        q = BQ.quantities_box(model, box, ["R1", "damping_margin", "mu_max"])
    h = F(1, 10 ** 6)
    base = {k: (lo + hi) / 2 for k, lo, hi in box.edges}
    v0 = mp_quantities(base)
    for name in ("R1", "damping_margin", "mu_max"):
        for k, ball in q[name].gradient.items():
            step = base[k] * h
            v1 = mp_quantities({**base, k: base[k] + step})
            dq = (v1[name] - v0[name]) / (float(step))
            assert _inside(ball, dq, rel=1e-4), (name, k, float(dq), ball)


def test_a_box_of_points_gives_a_tight_ball(model):
    box = Box.of({k: (v, v) for k, v in POINT.items()})
    with working_precision(128):
        q = BQ.quantities_box(model, box, list(BQ.BOX_QUANTITIES))
    v = mp_quantities({}, psi=True)
    for name in ("A0", "B0", "C0", "mu_max", "mu_min", "k_min", "R1", "R2", "R", "damping_margin"):
        ball = q[name].value
        assert _inside(ball, v[name]) and float(ball.rad()) <= 1e-6 * abs(float(v[name])), (name, ball)
    # psi_margin: the bisection's resolution 2^-PSI_STEPS below, a point value above
    ball = q["psi_margin"].value
    assert _inside(ball, v["psi_margin"], rel=1e-9)
    assert float(ball.upper()) - float(ball.lower()) <= 2 * 4 / 2 ** BQ.PSI_STEPS


def test_the_damping_margin_lower_bound_is_below_a_float_optimisers_minimum_within_1e_3(model):
    from scipy.optimize import minimize
    box = _box(F(1, 20))
    with working_precision(128):
        lower = float(BQ.quantities_box(model, box, ["damping_margin"])["damping_margin"].value.lower())
    names = box.names
    bounds = [tuple(float(x) for x in box.interval(k)) for k in names]

    def f(x):
        p = {k: F(float(v)).limit_denominator(10 ** 9) for k, v in zip(names, x)}
        p = {k: min(max(v, box.interval(k)[0]), box.interval(k)[1]) for k, v in p.items()}
        return float(mp_quantities(p)["damping_margin"])
    x0 = [(a + b) / 2 for a, b in bounds]
    best = minimize(f, x0, bounds=bounds, method="L-BFGS-B", options={"maxiter": 50}).fun
    assert lower <= best
    assert best - lower <= 1e-3 * abs(best), (lower, best)


def test_the_psi_margin_contains_every_sampled_value_on_a_one_percent_box(model):
    """psi_margin = R_sup/R - 1 over a +-1 % box of every parameter: enclosed, and every sampled value (mpmath
    R_sup by the approx module's search) inside; its lower end is positive (the Psi test holds on the box)."""
    box = _box(F(1, 100))
    with working_precision(128):
        q = BQ.quantities_box(model, box, ["psi_margin"])
    ball = q["psi_margin"].value
    assert ball.lower() > 0
    for p in _samples(box, 6, 5):
        x = mp_quantities(p, psi=True)["psi_margin"]
        assert _inside(ball, x, rel=1e-9), (p, float(x), ball)
