"""Tests of the float/mpmath cross-check module rigor_gyro.kinds.lyapunov.approx (Agafonov et al. 2013).

These test the approximate side on its own (no balls): the float grad V . f against the audited Psi
form, the mpmath constants against reference values computed by independent scripts, the time scales,
and short scipy trajectories. Everything here is fast; the long horizon lives in
benchmarks/lyapunov_crosscheck.py.
"""
import mpmath
import numpy as np
import pytest

from rigor_gyro.kinds.lyapunov.approx import (AGAFONOV2013, FloatGimbal, MpGimbal, V_MONOTONE_REL_TOL, edge_points,
                                        float_constants, mp_constants, time_scales, trajectories)
from rigor_gyro.core.errors import ParameterError

#: float grad V . f sums products of size ~H^3 |x1 x3| / (B0^2 D) that cancel down to Vdot ~ Psi |x|^2
#: (a factor ~1e5 at the example); its rounding error is a few ulps of the *sum of the absolute values of
#: the products* (``cancellation_scale``). 1e-13 of that scale is ~500 ulps.
FLOAT_CANCEL_TOL = 1e-13
#: and relative to Vdot itself at the example (measured: max 2.9e-9 over 1e5 random points of (17),
#: where |Vdot| is smallest relative to its cancelling terms)
FLOAT_REL_TOL = 1e-8
#: reference values below come from 30-digit scripts: agreement to 1e-25 relative is asked
REF_REL_TOL = mpmath.mpf("1e-25")
#: mp_constants at 50 and at 60 digits must agree to this (relative)
SELF_REL_TOL = mpmath.mpf("1e-45")
#: digits at which mpmath values are compared (mpf arithmetic rounds to the *current* precision)
CMP_DPS = 80
#: float_constants against mp_constants (float grid + float refinement; crossing by brentq)
FLOAT_CONST_REL_TOL = 1e-9

#: The example's quantities, computed independently of rigor_gyro by the prior analysis scripts
#: (/tmp/agafonov_analysis/constants.py, hp.py: mpmath at 30 digits, closed forms of the paper's section 3,
#: R_sup and mu_best from the audited Psi coefficients, c* from the face formula).
_HP = "mpmath 30 digits, scratch analysis hp.py/constants.py (Agafonov 2013 section 3 parameters)"
EXAMPLE_REFERENCE = [
    ("ag.A0", "A0", "12.7", "exact"),
    ("ag.B0", "B0", "4.2", "exact"),
    ("ag.C0", "C0", "1.4", "exact"),
    ("ag.m", "m", "7.87401574803149606299212598425", _HP),                # a/A0
    ("ag.M", "M", "101.410404218403418905706409437", _HP),
    ("ag.p", "p", "133.333333333333333333333333333", _HP),                # A0 m / cos^2(pi/6) = 400/3
    ("ag.k_min", "k_min", "0.169333333333333333333333333333", _HP),
    ("ag.mu_min", "mu_min", "0.0133333333333333333333333333333", _HP),
    ("ag.mu_max", "mu_max", "0.031496062992125984251968503937", _HP),
    ("ag.R1", "R1", "0.0182811298148636971925013261826", _HP),
    ("ag.R2", "R2", "0.0106280050148468942667912768886", _HP),
    ("ag.R", "R", "0.0106280050148468942667912768886", _HP),
    ("ag.R_sup", "R_sup", "0.0239881372895834831078744294409566", _HP),
    ("ag.mu_best", "mu_best", "0.0199527665332816683669568132456", _HP),
    ("ag.R_max", "R_max", "0.0240775499389225657296992152869783", _HP),
    ("ag.c_star", "c_star", "23.4283841958462670497002457349932", _HP),
]
LINEAR = dict(AGAFONOV2013, moment="linear")
#: f = a x2: M = max q = q(x2*) (hp.py, quadrature at 30 digits)
LINEAR_M = "108.739687751432163295228546196"


@pytest.fixture(scope="module")
def example_mp():
    return mp_constants(AGAFONOV2013, dps=50)


def cancellation_scale(g: FloatGimbal, x1, x2, x3):
    """Sum over i of |dV/dx_i * x_i'|: the size of what grad V . f cancels."""
    gv, r = g.grad_V(x1, x2, x3), g.rhs3(x1, x2, x3)
    return sum(np.abs(a * b) for a, b in zip(gv, r))


def region_points(g: FloatGimbal, R: float, n: int, seed: int):
    rng = np.random.default_rng(seed)
    x2 = rng.uniform(-g.xs, g.xs, n)
    r = R * np.sqrt(rng.uniform(0, 1, n))
    th = rng.uniform(0, 2 * np.pi, n)
    return r * np.cos(th), x2, r * np.sin(th)


# ------------------------------------------------------------------------------------ grad V . f

@pytest.mark.parametrize("params", [AGAFONOV2013, LINEAR, dict(AGAFONOV2013, H="1e6", x2_star="1.4"),
                                    dict(AGAFONOV2013, C1="10", a="0.001")],
                         ids=["paper", "linear", "H=1e6,x2*=1.4", "C0<0,a tiny"])
def test_float_grad_v_dot_f_equals_the_audited_psi_form(params):
    """The analytic gradient of (7) dotted with (2) equals -Psi1 x1^2 - Psi2 x3^2 (audited coefficients)
    within FLOAT_CANCEL_TOL of the cancellation scale, at 2000 random points of the region (R = 0.02)."""
    g = FloatGimbal(params)
    x1, x2, x3 = region_points(g, 0.02, 2000, seed=1)
    vd = g.grad_V_dot_f(x1, x2, x3)
    vp = g.vdot_psi(x1, x2, x3)
    scale = cancellation_scale(g, x1, x2, x3)
    assert np.all(np.abs(vd - vp) <= FLOAT_CANCEL_TOL * scale), np.max(np.abs(vd - vp) / scale)


def test_float_grad_v_dot_f_relative_agreement_at_the_example():
    g = FloatGimbal(AGAFONOV2013)
    x1, x2, x3 = region_points(g, 0.0106, 2000, seed=2)
    vd, vp = g.grad_V_dot_f(x1, x2, x3), g.vdot_psi(x1, x2, x3)
    assert np.all(np.abs(vd - vp) <= FLOAT_REL_TOL * np.abs(vp))
    assert np.all(vp <= 0)                    # Vdot <= 0 on the region of R = min(R1, R2), in floats


def test_grad_v_matches_finite_differences():
    """The hand-written gradient of V against central differences (mpmath, 40 digits)."""
    with mpmath.workdps(40):
        g = MpGimbal(LINEAR)
        x = [mpmath.mpf("0.003"), mpmath.mpf("0.4"), mpmath.mpf("-0.002")]
        grad = g.grad_V(*x)
        for i in range(3):
            def h(t, i=i):
                y = list(x)
                y[i] = t
                return g.V(*y)
            num = mpmath.diff(h, x[i])
            assert abs(num - grad[i]) <= mpmath.mpf("1e-25") * (abs(num) + 1), (i, num, grad[i])


def test_printed_formula_8_differs_by_the_sin_2x2_term():
    """Printed (8) minus audited = -c23 x3^3 (its x3-term of Psi2 is twice the true one); equal at x2 = 0
    or x3 = 0, and the difference is far above float noise elsewhere."""
    g = FloatGimbal(AGAFONOV2013)
    x1, x2, x3 = region_points(g, 0.0106, 500, seed=3)
    true, printed = g.vdot_psi(x1, x2, x3), g.vdot_psi(x1, x2, x3, printed=True)
    c23 = g.psi_true(x2)[1][2]
    assert np.allclose(printed - true, -c23 * x3 ** 3, rtol=1e-6, atol=0)
    vd = g.grad_V_dot_f(x1, x2, x3)
    far = (np.abs(x2) > 0.05) & (np.abs(x3) > 0.003)
    scale = cancellation_scale(g, x1, x2, x3)
    assert np.all(np.abs(printed - vd)[far] > 1e3 * FLOAT_CANCEL_TOL * scale[far])
    for xa in (0.0,):
        assert g.vdot_psi(1e-3, xa, 2e-3, printed=True) == g.vdot_psi(1e-3, xa, 2e-3)
    assert g.vdot_psi(1e-3, 0.3, 0.0, printed=True) == g.vdot_psi(1e-3, 0.3, 0.0)


# ------------------------------------------------------------------------------------ constants

@pytest.mark.parametrize("rid, name, value, source", EXAMPLE_REFERENCE, ids=[r[0] for r in EXAMPLE_REFERENCE])
def test_mp_constants_reproduce_the_reference_values(example_mp, rid, name, value, source):
    with mpmath.workdps(CMP_DPS):
        got, ref = example_mp[name], mpmath.mpf(value)
        assert abs(got - ref) <= REF_REL_TOL * abs(ref), (rid, got, value, source)


def test_mp_constants_example_details(example_mp):
    c = example_mp
    with mpmath.workdps(CMP_DPS):
        assert c["c_star_where"].startswith("face")
        assert c["c_star_cylinder"] > c["c_star_face"]
        assert c["mu_best_kind"] == "crossing R1sup = R2sup"
        assert c["q_at_0"] == 100                       # the removable 0/0 of M: q(0) = f'(0) = a
        assert c["argmax_m"] == 0 and abs(c["argmax_M"] - mpmath.pi / 6) < mpmath.mpf("1e-40")
        assert c["mu_min"] < c["mu_best"] < c["mu_max"]
        assert c["R"] < c["R_sup"] < c["R_max"]


def test_mp_constants_are_stable_in_precision(example_mp):
    """50 and 60 digits agree to SELF_REL_TOL (the searches converged to the same optimum)."""
    hi = mp_constants(AGAFONOV2013, dps=60)
    with mpmath.workdps(CMP_DPS):
        for k in ("m", "M", "p", "R1", "R2", "R_sup", "c_star", "c_star_cylinder", "mu_best", "R_max"):
            assert abs(example_mp[k] - hi[k]) <= SELF_REL_TOL * abs(hi[k]), k


def test_linear_moment_M_and_the_removable_singularity():
    """f = a x2: M by quadrature (q(x) = a / (2 D(x) K(x)), K = G/x^2 continued through 0) matches the
    reference; near 0, q follows its series a (1 + (1/4 + C0/(2 A0)) x^2); the sine law's closed form
    follows a (1 + C0/(2 A0) x^2)."""
    c = mp_constants(LINEAR, dps=40, with_best_mu=False)
    with mpmath.workdps(40):
        assert abs(c["M"] - mpmath.mpf(LINEAR_M)) <= REF_REL_TOL * 108
        for params, c2 in ((LINEAR, mpmath.mpf(1) / 4 + mpmath.mpf("1.4") / (2 * mpmath.mpf("12.7"))),
                           (AGAFONOV2013, mpmath.mpf("1.4") / (2 * mpmath.mpf("12.7")))):
            g = MpGimbal(params)
            assert g.q(mpmath.mpf(0)) == 100
            x = mpmath.mpf("1e-6")
            assert abs(g.q(x) - 100 * (1 + c2 * x ** 2)) < mpmath.mpf("1e-20")
    fg = FloatGimbal(LINEAR)
    assert fg.q(np.array([0.0]))[0] == pytest.approx(100, rel=1e-14)


def test_float_constants_agree_with_mpmath(example_mp):
    f = float_constants(AGAFONOV2013, with_best_mu=False)
    for k in ("m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R", "R_sup", "c_star", "c_star_cylinder",
              "extent_x1_axis", "extent_x2_axis", "extent_x3_axis"):
        assert f[k] == pytest.approx(float(example_mp[k]), rel=FLOAT_CONST_REL_TOL), k


@pytest.mark.parametrize("params", [
    dict(AGAFONOV2013, x2_star="0.49*pi"),       # cos x2* -> 0: mu interval empty, R1 tiny
    dict(AGAFONOV2013, H="10"),                  # H tiny: V not positive definite, c* < 0
    dict(AGAFONOV2013, H="1e6"),
    dict(AGAFONOV2013, a="0.000001"),
    dict(AGAFONOV2013, a="1e6"),
    dict(AGAFONOV2013, k="0.1694", mu="0.0133339"),   # k just above k_min
    dict(AGAFONOV2013, C1="10"),                 # C0 < 0: q decreasing, M = q(0) = a
], ids=["x2*=0.49pi", "H=10", "H=1e6", "a=1e-6", "a=1e6", "k~k_min", "C0<0"])
def test_mp_constants_on_extreme_cases(params):
    """Every quantity is finite (or None where undefined: empty mu interval), and R_sup >= 0."""
    c = mp_constants(params, dps=30)
    for k in ("m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R", "R_sup", "c_star"):
        assert mpmath.isfinite(c[k]), k
    assert c["R_sup"] >= 0
    if c["mu_min"] < c["mu_max"]:
        assert c["mu_min"] <= c["mu_best"] <= c["mu_max"] and c["R_max"] >= c["R_sup"] * (1 - 1e-20)
    else:
        assert c["mu_best"] is None
    if params.get("C1") == "10":
        assert c["M"] == 100                     # maximum at x2 = 0, through the removable singularity


@pytest.mark.slow
def test_mp_constants_linear_near_pi_over_2():
    c = mp_constants(dict(LINEAR, x2_star="1.5"), dps=50)
    assert mpmath.isfinite(c["M"]) and c["M"] > 100 and c["mu_best"] is None


def test_bad_parameters_name_the_culprit():
    with pytest.raises(ParameterError, match="x2_star"):
        FloatGimbal(dict(AGAFONOV2013, x2_star="0.5*pi"))
    with pytest.raises(ParameterError, match="moment"):
        FloatGimbal(dict(AGAFONOV2013, moment="cubic"))
    p = dict(AGAFONOV2013)
    del p["mu"]
    with pytest.raises(ParameterError, match="mu"):
        mp_constants(p)
    with pytest.raises(ParameterError, match="float"):
        FloatGimbal(dict(AGAFONOV2013, k=0.4))


# ------------------------------------------------------------------------------------ time scales

def test_time_scales_of_the_example():
    """Nutation ~ H/sqrt(A0 B0) = 1369.22 rad/s (217.9 Hz), slowest decay ~ a/H = 0.01 /s: ~2.2e4 nutation
    periods per time constant (reference: hp.py, mpmath polyroots at 30 digits)."""
    ts = time_scales(AGAFONOV2013)
    with mpmath.workdps(40):
        assert abs(ts["nutation_rad_s"] - mpmath.mpf("1369.22082001506701357665301080664")) < mpmath.mpf("1e-20")
        assert abs(ts["nutation_hz"] - mpmath.mpf("217.918261689736256684003381307")) < mpmath.mpf("1e-20")
        assert abs(ts["slowest_rate"] - mpmath.mpf("0.0100000000011466000002017786680366")) < mpmath.mpf("1e-25")
        assert abs(ts["time_constant"] - mpmath.mpf("99.9999999885339999992969048799")) < mpmath.mpf("1e-20")
        assert abs(ts["periods_per_time_constant"] - mpmath.mpf("21791.8261664749748797126049452")) < mpmath.mpf("1e-15")
        rates = sorted(ts["decay_rates"])
        assert abs(rates[1] - mpmath.mpf("0.010748031495489692125883362634486")) < mpmath.mpf("1e-25")
    # numpy agrees on the cubic (float)
    roots = np.roots([float(x) for x in ts["characteristic_coefficients"]])
    assert max(abs(roots.imag)) == pytest.approx(float(ts["nutation_rad_s"]), rel=1e-12)


def test_time_scales_when_all_roots_are_real():
    ts = time_scales(dict(AGAFONOV2013, H="1", k="10", a="0.001"))   # overdamped: (k/A0)^2 > 4 H^2/(A0 B0)
    assert ts["nutation_rad_s"] is None and ts["periods_per_time_constant"] is None
    assert all(r > 0 for r in ts["decay_rates"])


# ------------------------------------------------------------------------------------ trajectories

#: 0.5 s = 109 nutation periods at the example: cheap (LSODA ~0.3 s per start) yet many oscillations
SHORT_HORIZON = 0.5


@pytest.fixture(scope="module")
def example_edges(example_mp):
    return edge_points(AGAFONOV2013, float(example_mp["c_star"]), n=6)


def test_edge_points_lie_just_inside_the_set(example_mp, example_edges):
    g = FloatGimbal(AGAFONOV2013)
    cs, R = float(example_mp["c_star"]), float(example_mp["R"])
    assert example_edges.edge.shape == (6, 3)
    for p in example_edges.edge:
        v = g.V(*p)
        assert 0 < cs - v <= 1e-4 * cs                        # on the edge V = c*, inside by EDGE_INSET
        assert g.in_region(*p, R)
    for p in example_edges.outside:
        assert not g.in_region(*p, R)


def test_short_trajectories_from_the_edge_stay_inside_with_v_decreasing(example_mp, example_edges):
    """Trajectories from just inside {V < c*}: never leave the box nor the set, V non-increasing."""
    cs = float(example_mp["c_star"])
    runs = trajectories(AGAFONOV2013, example_edges.edge[:2], SHORT_HORIZON, c_star=cs)
    for o in runs:
        assert o.success, o.message
        assert o.in_set_at_start and o.stayed_in_set
        assert not o.left_box and not o.left_region
        assert o.V_nonincreasing, o.max_V_increase
        assert o.max_V_increase <= V_MONOTONE_REL_TOL * o.V0
        assert o.V_final < o.V0
        assert o.max_abs_x2 <= float(mpmath.pi / 6)


def test_dop853_agrees_with_lsoda_on_a_short_run(example_mp, example_edges):
    cs = float(example_mp["c_star"])
    a = trajectories(AGAFONOV2013, example_edges.edge[:1], 0.2, c_star=cs)[0]
    b = trajectories(AGAFONOV2013, example_edges.edge[:1], 0.2, c_star=cs, method="DOP853", rtol=1e-10)[0]
    assert b.V_nonincreasing and b.stayed_in_set
    assert a.V_final == pytest.approx(b.V_final, rel=1e-6)


def test_trajectories_from_outside_the_box_are_reported(example_mp, example_edges):
    """Starts with |x2| > x2* and |x1| > R are reported outside the box (and outside the region)."""
    runs = trajectories(AGAFONOV2013, example_edges.outside[:2], 0.05, c_star=float(example_mp["c_star"]))
    for o in runs:
        assert not o.in_box_at_start and not o.in_region_at_start and not o.in_set_at_start
        assert o.left_box and o.left_region
        assert o.stayed_in_set is False


def test_float_polar_estimates_agree_with_mpmath_and_lie_above_the_certified_infima():
    """The float polar-form estimates (the speed benchmark's uncertified equivalent of vdot_direct,
    largest_sublevel and best_mu_direct) agree with mpmath at the example; R_direct and R_direct_max are
    searches for an infimum over (x2, t), so up to rounding they lie above the certified R_direct and
    R_direct_max (which the prover certifies a little below the supremum)."""
    from rigor_gyro.kinds.lyapunov.approx import float_polar_estimates, mp_polar_estimates
    k = float_constants(AGAFONOV2013, with_best_mu=False)
    fl = float_polar_estimates(AGAFONOV2013, (k["mu_min"], k["mu_max"]))
    mp = mp_polar_estimates(AGAFONOV2013, dps=20)
    assert abs(fl["R_direct"] - float(mp["R_direct"])) <= 1e-9 * fl["R_direct"]
    assert abs(fl["c_max"] - float(mp["c_max"])) <= 1e-9 * fl["c_max"]
    from rigor_gyro import load_scene
    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import Scene
    sc = load_scene("agafonov2013")
    cert = prove_scene(Scene(name="x", kind="lyapunov", source="", parameters=dict(sc.parameters),
                             options=dict(sc.options), claims_only=["vdot_direct", "best_mu_direct"]))
    details = {c.id: c.details for c in cert.claims}
    R_direct = float(details["vdot_direct"]["R_direct"])
    R_max, mu_d = float(details["best_mu_direct"]["R_direct_max"]), float(details["best_mu_direct"]["mu_direct"])
    assert fl["R_direct"] >= R_direct * (1 - 1e-12)
    assert R_max * (1 - 1e-12) <= fl["R_direct_max"] <= R_max * (1 + 1e-4)
    assert k["mu_min"] < fl["mu_direct"] < k["mu_max"] and abs(fl["mu_direct"] - mu_d) < 1e-5
    assert "mu_direct" not in float_polar_estimates(AGAFONOV2013, (0.02, 0.01))
