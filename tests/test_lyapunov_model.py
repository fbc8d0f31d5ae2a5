"""The Lyapunov model's bounds, each against an independent evaluation: the hypot ball against its
exact range, the cylinder bound of V against V's own Fourier coefficients on the circle, the disc
minimum of Psi against Psi on the disc's boundary, the slice centre against V's own minimiser.

Each bound is checked both ways: it is valid (never above what it bounds, a ball containing the
range) and it is the bound its docstring states (within rounding), so a term dropped, scaled or
mis-signed fails here rather than only making some proof harder."""
import dataclasses
import itertools
from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import certainly_gt, certainly_le, exact_endpoints, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.outcome import Status
from rigor_gyro.kinds.lyapunov import vdot_tests as M
from rigor_gyro.kinds.lyapunov.approx import MpGimbal, _r12, float_constants
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.kinds.lyapunov.model import Dual, hypot_ball, sin_cos
from rigor_gyro.kinds.lyapunov.polar_forms import (direct_margin, slice_extent, slice_in_region, sublevel_lower_bound,
                                                   v_polar, vdot_polar)
from rigor_gyro.kinds.lyapunov.closed_forms import closed_form_constants, cylinder_lower_bound
from rigor_gyro.kinds.lyapunov.vdot_tests import certify_vdot_nonpositive, psi_min_functions
from rigor_gyro.scene import load_scene
from tests.test_properties_lyapunov import contains_mp

TINY = arb("1e-25")


def _ends(x: arb) -> tuple[arb, arb]:
    """(min, max) of |t| over the ball x, from its exact ends."""
    lo, hi = x.lower(), x.upper()
    return (arb(0) if lo <= 0 <= hi else min(abs(lo), abs(hi))), max(abs(lo), abs(hi))


@pytest.mark.parametrize("a_mid,a_rad", [("-2", "0"), ("-0.5", "0.4"), ("0", "1e-3"), ("0.3", "2"), ("1.5", "0.25")])
def test_hypot_ball_is_the_range_of_the_hypotenuse_over_the_balls(a_mid, a_rad):
    with working_precision(128):
        a = arb(a_mid, a_rad)
        for b_mid, b_rad in (("-1", "0"), ("0", "0"), ("0.2", "0.5"), ("3", "1e-6")):
            b = arb(b_mid, b_rad)
            h = hypot_ball(a, b)
            (al, au), (bl, bu) = _ends(a), _ends(b)
            low, high = (al * al + bl * bl).sqrt(), (au * au + bu * bu).sqrt()
            assert h.is_finite()
            assert h.contains(low) and h.contains(high)                      # the whole range, both ends
            slack = (high - low) * arb(2) ** -28 + TINY                     # a ball's radius has 30 bits
            assert h.lower() > low - slack and h.upper() < high + slack       # and no more than the range
            for x, y in itertools.product((a.lower(), a.mid(), a.upper()), (b.lower(), b.mid(), b.upper())):
                assert h.contains((x * x + y * y).sqrt())


@pytest.fixture(scope="module")
def gimbal():
    return validate(load_scene("agafonov2013")).gimbal


def _circle_fourier(g, R: arb, x2: arb, n: int = 8):
    """alpha, beta, gamma, delta of V(R cos th, x2, R sin th) = alpha + beta sin th + gamma cos 2th +
    delta sin 2th, by the discrete Fourier transform of V at n >= 5 points (exact for a trigonometric
    polynomial of degree 2): independent of the closed forms in cylinder_lower_bound."""
    th = [2 * arb.pi() * j / n for j in range(n)]
    v = [g.V(R * t.cos(), x2, R * t.sin()) for t in th]
    alpha = sum(v, arb(0)) / n
    beta = 2 * sum((vj * t.sin() for vj, t in zip(v, th)), arb(0)) / n
    gamma = 2 * sum((vj * (2 * t).cos() for vj, t in zip(v, th)), arb(0)) / n
    delta = 2 * sum((vj * (2 * t).sin() for vj, t in zip(v, th)), arb(0)) / n
    cos1 = 2 * sum((vj * t.cos() for vj, t in zip(v, th)), arb(0)) / n              # no cos th term
    return alpha, beta, gamma, delta, cos1


@pytest.mark.parametrize("R", ["0.01", "0.0240775", "0.3"])
def test_the_cylinder_bound_is_alpha_minus_beta_minus_hypot_of_vs_fourier_coefficients(gimbal, R):
    g = gimbal
    with working_precision(128):
        Rb = arb(R)
        lb = cylinder_lower_bound(g, Rb)
        xs = g.c.x2_star
        for j in (0, 1, 3, 5, 7):
            x2 = xs * j / 7
            alpha, beta, gamma, delta, cos1 = _circle_fourier(g, Rb, x2)
            assert abs(cos1) < arb("1e-30")
            ref = alpha - abs(beta) - (gamma * gamma + delta * delta).sqrt()
            got = lb(x2)
            assert got.is_finite() and got.overlaps(ref) and abs(got - ref) < arb("1e-25") * (1 + abs(ref)), (j, got, ref)
            for k in range(24):                                            # a lower bound of V on the circle
                t = 2 * arb.pi() * k / 24
                assert certainly_le(got, g.V(Rb * t.cos(), x2, Rb * t.sin()))
        # over an x2 piece: below V at every x2 of the piece
        piece = xs * arb("0.5", "0.1")
        low = lb(piece)                                                    # a ball: its lower end bounds V
        for u in ("0.4", "0.45", "0.5", "0.6"):
            x2 = xs * arb(u)
            for k in range(12):
                t = 2 * arb.pi() * k / 12
                assert certainly_le(low.lower(), g.V(Rb * t.cos(), x2, Rb * t.sin()))


@pytest.mark.parametrize("R", ["0.005", "0.0240775", "0.2"])
def test_the_psi_disc_minimum_is_psi_at_the_minimising_boundary_point(gimbal, R):
    """psi_min_functions: min over the disc of radius R of the affine Psi_i = ci0 + ci1 x1 + ci3 x3 is
    ci0 - R |(ci1, ci3)|: never above Psi_i at a point of the boundary circle, and Psi_i at the point
    -R (ci1, ci3)/|(ci1, ci3)| (each function reads its own triple: Psi1 the first, Psi2 the second)."""
    g = gimbal
    with working_precision(128):
        Rb = arb(R)
        fns = psi_min_functions(g, Rb)
        xs = g.c.x2_star
        for j in (0, 2, 6):
            x2 = xs * j / 6
            for which, fn in enumerate(fns):
                c0, c1, c3 = g.psi_coefficients(x2)[which]
                got = fn(x2)
                norm = (c1 * c1 + c3 * c3).sqrt()
                if c1 == 0 and c3 == 0:                                        # x2 = 0: Psi_i is constant
                    at_min = c0
                else:
                    at_min = c0 + c1 * (-Rb * c1 / norm) + c3 * (-Rb * c3 / norm)
                assert at_min.is_finite()
                assert got.is_finite() and got.overlaps(at_min) and abs(got - at_min) < arb("1e-25") * (1 + abs(at_min)), (which, j)
                for k in range(16):
                    t = 2 * arb.pi() * k / 16
                    assert not certainly_gt(got, c0 + c1 * Rb * t.cos() + c3 * Rb * t.sin())   # equal where tangent
        assert not fns[0](xs / 3).overlaps(fns[1](xs / 3))                  # two different functions


def _slice_centre(g, x2: arb) -> tuple[arb, arb]:
    """The minimiser (x1, x3) of the quadratic V(., x2, .), from V's values at six points (its
    coefficients exactly, V being quadratic in x1, x3) and the 2x2 system grad V = 0: independent of
    the closed form mu f3/(h S), -f3/S in slice_in_region."""
    V = lambda x1, x3: g.V(arb(x1), x2, arb(x3))                         # noqa: E731
    v0 = V(0, 0)
    p11, p33 = (V(1, 0) + V(-1, 0) - 2 * v0) / 2, (V(0, 1) + V(0, -1) - 2 * v0) / 2
    l1, l3 = (V(1, 0) - V(-1, 0)) / 2, (V(0, 1) - V(0, -1)) / 2
    p13 = V(1, 1) - v0 - l1 - l3 - p11 - p33
    det = 4 * p11 * p33 - p13 * p13                                       # [2 p11, p13; p13, 2 p33] z = -l
    return (-l1 * 2 * p33 + l3 * p13) / det, (-l3 * 2 * p11 + l1 * p13) / det


def test_slice_in_region_puts_the_centre_of_the_slice_where_v_has_its_minimum(gimbal):
    """slice_in_region(g, c, R, x2) is true just outside the centre's radius |z0| and false just inside
    it (c above phi(x2), so the slice is not empty), with z0 the minimiser of V(., x2, .) found here
    from V itself; and false for every R when c <= phi(x2) (an empty slice)."""
    g = gimbal
    with working_precision(128):
        xs = g.c.x2_star
        for j in (1, 3, 6):
            x2 = xs * j / 7
            z1, z3 = _slice_centre(g, x2)
            r = (z1 * z1 + z3 * z3).sqrt()
            assert certainly_gt(r, 0) and certainly_gt(abs(z1), 0)        # off the axes: both coordinates count
            c = g.phi(x2) + 1
            # |z1| / |z3| = mu B0 / (H cos x2), about 1e-5 here: z1 moves |z0| by about 1e-11 relative only
            assert slice_in_region(g, c, r * (1 + arb("1e-15")), x2)
            assert not slice_in_region(g, c, r * (1 - arb("1e-15")), x2)
            assert not slice_in_region(g, g.phi(x2) - arb("1e-9"), r * 10, x2)


# ------------------------------------------------------------------ V and Vdot along a ray, their monomials

_RAYS = [("0", "0.1"), ("0.2", "0.35"), ("-0.4", "0.8"), ("0.5", "0.5"), ("0.05", "0.97")]     # (x2/x2*, t/pi)


def _ray(g, x2, t):
    """(alpha, beta, gamma, A, B) with V = alpha + beta r + gamma r^2 and Vdot = -r^2 (A + r B) along the ray
    (r cos t, x2, r sin t), read from V at r = -1, 0, 1 and Vdot at r = -1, 1 (not from the model's closed
    forms)."""
    vm, v0, vp = (g.V(r * t.cos(), x2, r * t.sin()) for r in (arb(-1), arb(0), arb(1)))
    dm, dp = (g.vdot(r * t.cos(), x2, r * t.sin()) for r in (arb(-1), arb(1)))
    return v0, (vp - vm) / 2, (vp + vm) / 2 - v0, -(dp + dm) / 2, (dm - dp) / 2


def _half_line_min(alpha, beta, gamma, A, B):
    """(min of alpha + beta r + gamma r^2 over {r : r B <= -A}, whether the vertex was clamped to its end);
    for numbers (mpf, or exact arb midpoints), B != 0."""
    r, edge = -beta / (2 * gamma), -A / B
    clamped = (B > 0 and r > edge) or (B < 0 and r < edge)
    r = edge if clamped else r
    return alpha + beta * r + gamma * r * r, clamped


def test_v_polar_and_vdot_polar_are_v_and_vdot_along_every_ray(gimbal):
    """V(r cos t, x2, r sin t) = alpha + beta r + gamma r^2 and Vdot = -r^2 (A + r B) for every r: the
    coefficients read back from V and Vdot themselves at r = -1, 0, 1, and checked at r = 2, -3, 1/7."""
    g = gimbal
    with working_precision(128):
        for u, s in _RAYS:
            x2, t = g.c.x2_star * arb(u), arb.pi() * arb(s)
            ref = _ray(g, x2, t)
            alpha, beta, gamma = v_polar(g, x2, t)
            for mine, want in zip((alpha, beta, gamma), ref):
                assert mine.is_finite() and mine.overlaps(want) and abs(mine - want).upper() < arb("1e-25") * (1 + abs(want).upper())
            A, B = vdot_polar(g, x2, t)
            assert A.is_finite() and B.is_finite() and A.overlaps(ref[3]) and B.overlaps(ref[4])
            for r in (arb(2), arb(-3), arb(1) / 7):
                v, vd = g.V(r * t.cos(), x2, r * t.sin()), g.vdot(r * t.cos(), x2, r * t.sin())
                assert v.is_finite() and v.overlaps(alpha + beta * r + gamma * r * r)
                assert vd.is_finite() and vd.overlaps(-r * r * (A + r * B))


def test_vdot_monomials_sum_to_vdot_off_their_nodes(gimbal):
    g = gimbal
    with working_precision(128):
        for u in ("0", "0.3", "-0.9"):
            x2 = g.c.x2_star * arb(u)
            mono = g.vdot_monomials(x2)
            for x1, x3 in ((arb("0.3"), arb("-0.7")), (arb("-1.25"), arb("0.5")), (arb("2.5"), arb("3"))):
                powers = {"1": arb(1), "x1": x1, "x3": x3, "x1^2": x1 ** 2, "x1x3": x1 * x3, "x3^2": x3 ** 2,
                          "x1^3": x1 ** 3, "x1^2x3": x1 ** 2 * x3, "x1x3^2": x1 * x3 ** 2, "x3^3": x3 ** 3}
                total = sum((mono[k] * p for k, p in powers.items()), arb(0))
                direct = g.vdot(x1, x2, x3)
                assert total.is_finite() and total.overlaps(direct) and abs(total - direct).upper() < arb("1e-20")


@pytest.mark.parametrize("k", ["0.4", "0.2"])          # the paper's k; k = 0.2, where A(0, t) < 0
def test_the_sublevel_lower_bound_is_below_v_on_the_half_line_of_vdot_ge_0_and_tight_there(k):
    """On tiny (u, s) boxes, the bound's lower end is at most the minimum of V over the half-line
    {r : Vdot(r cos t, x2, r sin t) >= 0} at the box's centre (from V's and Vdot's own values along the ray,
    the minimum of the quadratic clamped to the half-line in mpmath) and within 1e-5 of it where the
    bound is that minimum (A > 0, or the vertex on the half-line): a term dropped or scaled in either
    branch of the bound shows here."""

    scene = load_scene("agafonov2013")
    g = validate(dataclasses.replace(scene, parameters=dict(scene.parameters, k=k))).gimbal
    f = sublevel_lower_bound(g)
    seen = set()
    with working_precision(128), mpmath.workdps(40):
        for i, j in itertools.product(range(1, 12, 2), range(1, 24, 3)):
            u, s = arb(i) / 12, arb(j) / 24
            box = {"u": arb(u.mid(), arb("1e-9")), "s": arb(s.mid(), arb("1e-9"))}
            bound = f(box)
            x2, t = g.c.x2_star * u, arb.pi() * s
            al, be, ga, A, B = (mpmath.mpf(x.mid().str(40, radius=False)) for x in _ray(g, x2, t))
            if B == 0:
                continue
            true_min, clamped = _half_line_min(al, be, ga, A, B)
            low = mpmath.mpf(bound.lower().str(40, radius=False))
            assert low <= true_min + mpmath.mpf("1e-20"), (i, j, low, true_min)
            if A > 0 or not clamped:
                seen.add(clamped)
                assert true_min - low < mpmath.mpf("1e-5") * (1 + abs(true_min)), (i, j, low, true_min)
    assert seen == ({True} if k == "0.4" else {False, True})     # k = 0.2: both branches tight somewhere
    with working_precision(128), mpmath.workdps(40):               # wide boxes: below V at points inside
        for i, j in itertools.product(range(6), range(6)):
            box = {"u": arb(i) / 6 + arb(1) / 12 + arb(0, arb(1) / 12), "s": arb(j) / 6 + arb(1) / 12 + arb(0, arb(1) / 12)}
            low = f(box).lower()
            for du, ds in itertools.product((-1, 0, 1), repeat=2):
                u, s = box["u"].mid() + arb(du) / 13, box["s"].mid() + arb(ds) / 13
                x2, t = g.c.x2_star * u, arb.pi() * s
                al, be, ga, A, B = (x.mid() for x in _ray(g, x2, t))
                if B == 0:
                    continue
                assert low <= _half_line_min(al, be, ga, A, B)[0] + arb("1e-20"), (i, j, du, ds)


def test_the_faces_minimiser_is_where_v_takes_phi_and_v_is_larger_around_it(gimbal):
    """phi(x2) = min V(., x2, .) and phi_minimiser(x2) is where: V there equals phi, and V is larger at
    points 1e-3 away in x1 and in x3 (V is a convex quadratic in (x1, x3)); the minimiser feeds the
    'inside' flag of c*'s face bound (proofs/mutation.md section 12's gap)."""
    g = gimbal
    with working_precision(128):
        for u in ("0.1", "0.5", "1", "-0.7"):
            x2 = g.c.x2_star * arb(u)
            m1, m3 = g.phi_minimiser(x2)
            phi = g.phi(x2)
            at = g.V(m1, x2, m3)
            assert at.is_finite() and at.overlaps(phi) and abs(at - phi).upper() < arb("1e-25")
            h = arb("1e-3")
            for d1, d3 in ((h, 0), (-h, 0), (0, h), (0, -h), (h, h)):
                assert certainly_gt(g.V(m1 + d1, x2, m3 + d3), phi)


def test_dual_numbers_carry_the_derivative_of_every_operation():
    """Each Dual rule against mpmath's numerical derivative of the same expression at 30 digits."""
    exprs = [
        (lambda x: -x + 3, lambda x: -x + 3), (lambda x: 2 - x, lambda x: 2 - x), (lambda x: x - 5, lambda x: x - 5),
        (lambda x: x * x * 3, lambda x: 3 * x * x), (lambda x: (x + 1) / (x * x + 2), lambda x: (x + 1) / (x * x + 2)),
        (lambda x: 7 / x, lambda x: 7 / x), (lambda x: x / 4, lambda x: x / 4), (lambda x: x ** 2, lambda x: x ** 2),
        (lambda x: x.sin() * x.cos(), lambda x: mpmath.sin(x) * mpmath.cos(x)),
        (lambda x: (x * x + 1).sqrt(), lambda x: mpmath.sqrt(x * x + 1)),
        (lambda x: sin_cos(x)[0] - sin_cos(x)[1], lambda x: mpmath.sin(x) - mpmath.cos(x)),
        (lambda x: (x - 2 * x) * x, lambda x: -x * x),
    ]
    with working_precision(128), mpmath.workdps(30):
        for x0 in ("0.3", "-1.7", "2.5"):
            for seed in (1, 3):
                for mine, ref in exprs:
                    d = mine(Dual(arb(x0), arb(seed)))
                    want_v = ref(mpmath.mpf(x0))
                    want_d = seed * mpmath.diff(ref, mpmath.mpf(x0))
                    for got, want in ((d.v, want_v), (d.d, want_d)):
                        assert abs(mpmath.mpf(got.mid().str(30, radius=False)) - want) < mpmath.mpf("1e-20"), (x0, seed)


def test_vdot_polar_over_a_mu_ball_contains_it_at_every_mu_of_the_ball(gimbal):
    g = gimbal
    with working_precision(128):
        mu = arb("0.03", "0.01")
        for u, s in _RAYS:
            x2, t = g.c.x2_star * arb(u), arb.pi() * arb(s)
            A, B = vdot_polar(g, x2, t, mu)
            for m in ("0.02", "0.025", "0.03", "0.04"):
                Am, Bm = vdot_polar(g.with_mu(arb(m)), x2, t)
                assert A.is_finite() and B.is_finite() and A.contains(Am) and B.contains(Bm), (u, s, m)


def test_slice_extents_are_the_ellipses_own_from_v_itself(gimbal):
    """max |x1| and max |x3| over {V(., x2, .) < c}: from V's own values (the quadratic form's gradient and
    Hessian at six points, the ellipse's centre and axes solved in mpmath), at points (the direct form)
    and on tiny balls (the mean-value form), and 0 where c < phi(x2)."""
    g = gimbal
    with working_precision(128), mpmath.workdps(40):
        c = g.phi(g.c.x2_star) * arb("1.5")
        mp = lambda x: mpmath.mpf(x.mid().str(40, radius=False))      # noqa: E731
        for u in ("0.05", "0.4", "0.8", "-0.6"):
            x2 = g.c.x2_star * arb(u)
            V = lambda a, b: mp(g.V(arb(a), x2, arb(b)))               # noqa: E731
            v0 = V(0, 0)
            g1, g3 = (V(1, 0) - V(-1, 0)) / 2, (V(0, 1) - V(0, -1)) / 2
            q11, q33 = V(1, 0) + V(-1, 0) - 2 * v0, V(0, 1) + V(0, -1) - 2 * v0
            q13 = V(1, 1) - v0 - g1 - g3 - (q11 + q33) / 2
            Q = mpmath.matrix([[q11, q13], [q13, q33]])
            z0 = -(Q ** -1) * mpmath.matrix([g1, g3])
            vmin = v0 + (g1 * z0[0] + g3 * z0[1]) / 2
            Qi = Q ** -1
            level = mp(c) - vmin
            assert level > 0
            want = {"x1": abs(z0[0]) + mpmath.sqrt(2 * level * Qi[0, 0]),
                    "x3": abs(z0[1]) + mpmath.sqrt(2 * level * Qi[1, 1])}
            for axis in ("x1", "x3"):
                e = slice_extent(g, c, axis)
                at = e(x2)
                assert abs(mp(at) - want[axis]) < mpmath.mpf("1e-20") * (1 + want[axis]), (u, axis)
                ball = e(arb(x2.mid(), arb("1e-10")))
                assert ball.upper() >= at.upper() and mp(ball) - want[axis] < mpmath.mpf("1e-6"), (u, axis)
                assert slice_extent(g, g.phi(x2) - arb("0.1"), axis)(x2) == 0          # an empty slice


@pytest.mark.parametrize("params", [{}, {"mu": "0.3"}, {"k": "0.1", "mu": "0.005"}])
def test_psi_is_the_faces_minimum_of_v_up_to_a_positive_factor(params):
    """v_positive rests on psi: phi(x2) = min V(., x2, .) and psi have the same sign because
    phi S = K psi G with one constant K > 0 for all x2 (G, S > 0): checked at eight x2 to 1e-20, so a term
    of psi changed shows as a ratio that moves."""
    scene = load_scene("agafonov2013")
    g = validate(dataclasses.replace(scene, parameters=dict(scene.parameters, **params))).gimbal
    with working_precision(128):
        ratios = []
        for u in ("0.05", "0.2", "0.35", "0.5", "0.65", "0.8", "0.95", "-0.7"):
            x2 = g.c.x2_star * arb(u)
            ratios.append(g.phi(x2) * g.S(x2) / (g.psi(x2) * g.G(x2)))
        assert all(certainly_gt(r, 0) for r in ratios)
        assert all(abs(r / ratios[0] - 1).upper() < arb("1e-20") for r in ratios)


# ------------------------------------------------------------------------------ constants and Vdot <= 0, directly
# (the claims tests reach these through whole proofs, minutes a mutant under mutmut; these take a second)

def _g_and_mp(params: dict):
    scene = load_scene("agafonov2013")
    full = dict(scene.parameters, **params)
    with mpmath.workdps(50):
        mg = MpGimbal(full)
    return validate(dataclasses.replace(scene, parameters=full)).gimbal, mg, full


@pytest.mark.parametrize("params, m, M", [({}, "1.7", "150"), ({}, "30", "100"), ({"C1": "54.2"}, "2.5", "90"),
                                          ({"k": "40", "mu": "1.5"}, "0.9", "3"), ({"moment": "linear"}, "110", "95")],
                         ids=["paper, M binds", "paper, A0 m/cos^2 binds", "C0 < 0", "radii above 1", "linear"])
def test_closed_form_constants_are_the_printed_formulas_for_every_m_and_M_of_their_balls(params, m, M):
    """p = max(M, A0 m / cos^2 x2*), k_min = p A0/H, (16) = (p/H, k/A0), R1 (13), R2 (14), R = min: each ball
    contains the float side's mpmath transcription of the paper's formula (``approx._r12``) at 50 digits, at
    both ends of an m ball and an M ball (the result is valid for every m, M in them)."""
    g, mg, _ = _g_and_mp(params)
    m_lo, M_lo = arb(m), arb(M)
    with working_precision(128):
        mb, Mb = m_lo.union(m_lo * arb("1.001")), M_lo.union(M_lo * arb("1.001"))
        K = closed_form_constants(g, mb, Mb)
    with mpmath.workdps(50):
        cs2 = mpmath.cos(mg.xs) ** 2
        for scale in ("1", "1.001"):
            mm, MM = mpmath.mpf(m) * mpmath.mpf(scale), mpmath.mpf(M) * mpmath.mpf(scale)
            pA = mg.A0 * mm / cs2
            p = max(MM, pA)
            ref = {"A0": mg.A0, "B0": mg.B0, "C0": mg.C0, "m": mm, "M": MM, "A0_m_over_cos2": pA, "p": p,
                   "k_min": p * mg.A0 / mg.H, "mu_min": p / mg.H, "mu_max": mg.k / mg.A0,
                   "R2_base": mg.mu * mg.H * cs2 - mm * mg.A0}
            r12 = _r12(mg, mm)
            ref.update(R1=r12["R1"], R2=r12["R2"], R=r12["R"])
            for name, value in ref.items():
                assert contains_mp(K[name], value), (name, scale, K[name], value)
    assert set(K) == set(ref)


def _pi_over_6() -> Fraction:
    with mpmath.workdps(50):
        return Fraction(mpmath.nstr(mpmath.pi / 6, 45))


def _r_sup(params) -> float:
    return float_constants(dict(load_scene("agafonov2013").parameters, **params), with_best_mu=False)["R_sup"]


def _radius(params, scale: str) -> arb:
    r = Fraction(_r_sup(params)).limit_denominator(10 ** 12) * Fraction(scale)
    return arb(fmpq(r.numerator, r.denominator))


@pytest.mark.parametrize("scale", ["0.9", "0.5"])
def test_vdot_nonpositive_is_proved_below_r_sup_on_pieces_covering_the_x2_range(scale):
    """Below the supremum of the Psi radius (the float side's R_sup = 0.023988 on the paper's scene) both disc
    minima are certified > 0 on pieces that tile [-x2*, x2*]: the pieces are recorded and counted, and the
    disc minimum of Psi1, Psi2 is positive at the pieces' ends in mpmath too."""
    g, mg, _ = _g_and_mp({})
    R = _radius({}, scale)
    record: dict = {}
    with working_precision(64):
        v = certify_vdot_nonpositive(g, g.c.x2_star, R, "R", 20000, record)
    assert v.status is Status.PROVED, v.reason
    assert set(record) == {"Psi1", "Psi2"} and v.details == {"pieces": v.pieces, "test": "Psi"}
    assert v.pieces >= len(record["Psi1"]) + len(record["Psi2"]) and v.witness is None and v.counterexample is None
    xs = _pi_over_6()
    for name, pieces in record.items():
        ends = [(Fraction(a), Fraction(b)) for a, b in pieces]
        assert ends[0][0] <= -xs and ends[-1][1] >= xs and all(b >= c for (_, b), (c, _) in zip(ends, ends[1:]))
        with mpmath.workdps(50):
            i = 0 if name == "Psi1" else 1
            r = mpmath.mpf(mpmath.nstr(mpmath.mpf(R.mid().str(30, radius=False)), 30))
            for a in sorted({e for pair in ends for e in pair}):
                if abs(a) > xs:
                    continue        # the outermost ends lie a hair beyond x2* (a ball's ends)
                c0, c1, c3 = mg.psi_true(mpmath.mpf(a.numerator) / a.denominator)[i]
                assert c0 - r * mpmath.hypot(c1, c3) > 0, (name, a)
    assert "certified > 0 on" in v.reason and "x2 pieces of [-x2*, x2*]" in v.reason


@pytest.mark.parametrize("params, scale", [({}, "1.1"), ({}, "3"), ({"mu": "0.01"}, "1"), ({"k": "0.2"}, "1")],
                         ids=["just above R_sup", "far above", "mu below (16)", "k = 0.2"])
def test_vdot_nonpositive_is_refuted_only_at_a_point_of_the_region_where_vdot_is_positive(params, scale):
    """The refuting point: balls x1, x3 (about exact rationals) with x1^2 + x3^2 < R^2 and |x2| <= x2* over
    the whole balls, and grad V . f > 0 there in mpmath (the float side's own gradient of V along (2)), inside
    the stated ball."""
    g, mg, _ = _g_and_mp(params)
    R = _radius(params, scale) if _r_sup(params) > 0 else arb("0.01")
    with working_precision(64):
        v = certify_vdot_nonpositive(g, g.c.x2_star, R, "R", 20000, {})
    assert v.status is Status.REFUTED, v.reason
    x1, x2, x3, val = v.witness
    with working_precision(256):
        assert (x1 * x1 + x3 * x3 < R * R) and abs(x2) <= g.c.x2_star
    with mpmath.workdps(50):
        pt = [mpmath.mpf(x.mid().str(60, radius=False)) for x in (x1, x2, x3)]
        ref = mg.grad_V_dot_f(*pt)
        assert ref > 0 and contains_mp(val, ref), (ref, val)
    assert v.counterexample["point"]["x1"] and v.counterexample["radius"] and "> 0 at the point" in v.reason


def test_a_psi_counterexample_refutes_the_test_at_a_certified_point_when_no_vdot_point_is_found(monkeypatch):
    """With the Vdot search on circles finding nothing, R above R_sup refutes the Psi test on Psi alone: a
    point of the open disc where the named Psi (the float side's mpmath coefficients) is <= 0, the value inside
    the stated ball; with a budget too small to decide and R below R_sup, nothing is refuted. Vdot <= 0 itself
    (certify_vdot_nonpositive) is then refuted only from the direct test's point where Vdot > 0, never on Psi."""
    g, mg, _ = _g_and_mp({})
    monkeypatch.setattr(M, "vdot_witness", lambda *a, **k: None)
    R = _radius({}, "1.1")
    with working_precision(64):
        whole = M.certify_vdot_nonpositive(g, g.c.x2_star, R, "R", 20000, {})
        assert whole.status is Status.REFUTED and "psi" not in whole.counterexample and whole.witness is not None
        assert certainly_gt(g.vdot(*whole.witness[:3]), 0)
        v = M.certify_psi_test(g, g.c.x2_star, R, "R", 20000, {})
    assert v.status is Status.REFUTED and v.witness is None, v.reason
    name = v.counterexample["psi"]
    assert name in ("Psi1", "Psi2") and f"{name} = " in v.reason and "<= 0 at the point" in v.reason
    ends = {k: (Fraction(s[0]), Fraction(s[1])) for k, s in v.counterexample["point"].items()}
    far = {k: max(abs(a), abs(b)) for k, (a, b) in ends.items()}          # the whole ball in the region
    assert far["x1"] ** 2 + far["x3"] ** 2 < Fraction(R.lower().str(40, radius=False)) ** 2
    assert far["x2"] <= _pi_over_6()
    pt = {k: (a + b) / 2 for k, (a, b) in ends.items()}
    with mpmath.workdps(50):
        c0, c1, c3 = mg.psi_true(mpmath.mpf(pt["x2"].numerator) / pt["x2"].denominator)[0 if name == "Psi1" else 1]
        x1 = mpmath.mpf(pt["x1"].numerator) / pt["x1"].denominator
        x3 = mpmath.mpf(pt["x3"].numerator) / pt["x3"].denominator
        ref = c0 + c1 * x1 + c3 * x3
        assert ref <= 0 and contains_mp(arb(v.counterexample["value"].strip("[]").split(",")[0]).union(
            arb(v.counterexample["value"].strip("[]").split(",")[-1])), ref)
    with working_precision(64):
        small = M.certify_psi_test(g, g.c.x2_star, _radius({}, "0.999"), "R", 3, {})
    assert small.status is Status.INCONCLUSIVE and "no point with certified Vdot > 0 found" in small.reason
    assert small.decides is not None


@pytest.mark.parametrize("R", ["0", "-0.01", "nan", "0 +/- 0.001", "inf"])
def test_a_radius_not_certainly_positive_and_finite_decides_nothing(R):
    g, _, _ = _g_and_mp({})
    with working_precision(64):
        v = certify_vdot_nonpositive(g, g.c.x2_star, arb(R), "R = min(R1, R2)", 20000, {})
    assert v.status is Status.INCONCLUSIVE and v.pieces == 0 and "is not certainly a positive radius" in v.reason
    assert v.reason.startswith("R = min(R1, R2) = ")


@pytest.mark.parametrize("params", [{}, {"moment": "linear"}, {"C1": "54.2"}, {"moment": "linear", "x2_star": "1.3"}],
                         ids=["sine", "linear (no closed form)", "sine, C0 < 0", "linear, x2* = 1.3"])
def test_q_encloses_f2_over_2DG_at_points_and_over_balls_through_zero(params):
    """q = f^2 / (2 D G), whose maximum is M: at exact points, over balls away from 0 (the mean-value form),
    over balls touching or straddling 0 (the removable singularity, q(0) = a) it contains the float side's
    mpmath q (closed form for the sine law, quadrature for the linear one) at every sample of the ball,
    and it is tight on a tiny ball."""
    g, mg, _ = _g_and_mp(params)
    xs = float(mpmath.mpf(mg.xs))
    balls = [("0", "0"), ("0", "0.2"), ("-0.1", "0.1"), ("-0.3", "-0.1"), ("0.1", "0.3"), ("0.25", "0.26"),
             (str(xs * 0.9), str(xs)), ("0.001", "0.001"), ("0.3", "0.3")]
    with working_precision(64):
        for lo, hi in balls:
            X = arb(lo).union(arb(hi))
            Q = g.q(X)
            assert Q.is_finite(), (lo, hi)
            with mpmath.workdps(40):
                for j in range(9):
                    x = mpmath.mpf(lo) + (mpmath.mpf(hi) - mpmath.mpf(lo)) * j / 8
                    ref = mpmath.mpf(mg.a) if x == 0 else mg.q(abs(x))
                    assert contains_mp(Q, ref), (params, lo, hi, x, Q, ref)
        tiny = g.q(arb("0.3").union(arb("0.3") + arb("1e-12")))
        assert tiny.rad() < arb("1e-8") * abs(tiny), tiny
        point = g.q(arb("0.25"))                # an exact point away from 0: f^2/(2 D G) itself, tight
        assert point.rad() < arb("1e-15") * abs(point), point


def test_an_undecided_vdot_test_below_r_sup_is_never_refuted():
    """R = 0.99 R_sup with 3 pieces: the disc minima stay undecided, and the point search (on x2 = j x2*/8,
    |j| <= 8: only points of the region) finds nothing, because Vdot <= 0 on the whole region. One step
    beyond, at x2 = 9 x2*/8, Vdot > 0 on the same circles: a search reaching past x2* would refute falsely."""
    g, _, _ = _g_and_mp({})
    R = _radius({}, "0.99")
    with working_precision(64):
        v = M.certify_vdot_nonpositive(g, g.c.x2_star, R, "R", 3, {})
        beyond = M.exact_fraction(g.c.x2_star.lower()) * Fraction(9, 8)
        assert M.vdot_witness(g, R, [arb(fmpq(beyond.numerator, beyond.denominator))]) is not None
    assert v.status is Status.INCONCLUSIVE and v.witness is None and v.counterexample is None, v.reason
    assert "no point with certified Vdot > 0 found" in v.reason


@pytest.mark.parametrize("params", [{}, {"moment": "linear"}, {"C1": "54.2"}], ids=["sine", "linear", "C0 < 0"])
def test_the_quotients_of_m_and_the_psi_forms_against_the_float_sides_mpmath(params):
    """|cos f'|/D and cos f'/D (whose maxima give m), -Psi1 x1^2 - Psi2 x3^2 from the derived coefficients
    (= grad V . f) and from the coefficients as printed in (8) (Psi2's x3 term with sin 2x2): each ball
    contains the float side's mpmath value at exact points and at every sample of a ball."""
    g, mg, _ = _g_and_mp(params)
    with working_precision(64):
        for lo, hi in (("0.3", "0.3"), ("-0.4", "-0.4"), ("0.1", "0.2"), ("-0.05", "0.05")):
            X = arb(lo).union(arb(hi))
            mq, ms = g.m_quotient(X), g.m_signed(X)
            with mpmath.workdps(40):
                for j in range(5):
                    x = mpmath.mpf(lo) + (mpmath.mpf(hi) - mpmath.mpf(lo)) * j / 4
                    assert contains_mp(mq, mg.m_quotient(x)), (lo, hi, x)
                    assert contains_mp(ms, mpmath.cos(x) * mg.df(x) / mg.D(x)), (lo, hi, x)
        for x1, x2, x3 in (("0.01", "0.3", "-0.02"), ("-0.5", "-0.2", "0.7"), ("2", "0.45", "1.5")):
            b = [arb(v) for v in (x1, x2, x3)]
            exact = g.vdot_psi(*b)
            printed = g.vdot_psi(*b, printed=True)
            with mpmath.workdps(40):
                p = [mpmath.mpf(v) for v in (x1, x2, x3)]
                assert contains_mp(exact, mg.vdot_psi(*p)) and contains_mp(exact, mg.grad_V_dot_f(*p)), (x1, x2, x3)
                assert contains_mp(printed, mg.vdot_psi(*p, printed=True)), (x1, x2, x3)
                assert abs(mg.vdot_psi(*p, printed=True) - mg.vdot_psi(*p)) > 1e-6 * abs(mg.vdot_psi(*p))


@pytest.mark.parametrize("u, s", [(("0.95", "1"), ("0.4", "0.5")), (("0.9", "1"), ("0.2", "0.3")),
                                  (("-1", "-0.95"), ("0.45", "0.5")), (("-0.6", "-0.5"), ("0.4", "0.5"))],
                         ids=["B > 0", "B > 0, wider", "B < 0", "B < 0, inside"])
def test_the_direct_margin_over_a_box_contains_a_minus_r_abs_b_at_every_point_of_it(u, s):
    """direct_margin's box function (the direct form intersected with a mean-value form centred at the box's
    midpoint) against A - R |B| at 25 points of the box, each evaluated on its own. The boxes are ones where
    the direct form is not certainly positive and B has one sign (both signs), so the centred form is what
    is returned: strictly narrower than the direct one."""
    g, _, _ = _g_and_mp({})
    R = arb("0.02")
    with working_precision(64):
        box = Box.of({"u": tuple(Fraction(x) for x in u), "s": tuple(Fraction(x) for x in s)})
        balls = {"u": box.ball("u"), "s": box.ball("s")}
        F = direct_margin(g, R)(balls)
        A, B = vdot_polar(g, g.c.x2_star * balls["u"], arb.pi() * balls["s"])
        direct = A - R * abs(B)
        assert not certainly_gt(direct, 0) and (certainly_gt(B, 0) or certainly_gt(-B, 0))
        assert F.is_finite() and F.upper() <= direct.upper() and F.lower() >= direct.lower() and F.rad() < direct.rad()
        for i, j in itertools.product(range(5), range(5)):
            uu = Fraction(u[0]) + (Fraction(u[1]) - Fraction(u[0])) * i / 4
            ss = Fraction(s[0]) + (Fraction(s[1]) - Fraction(s[0])) * j / 4
            a, b = vdot_polar(g, g.c.x2_star * arb(fmpq(uu.numerator, uu.denominator)),
                              arb.pi() * arb(fmpq(ss.numerator, ss.denominator)))
            pt = a - R * abs(b)
            assert F.lower() <= pt.upper() and pt.lower() <= F.upper(), (uu, ss, F, pt)   # meets each point's ball


def test_log1m_tail_bounds_the_series_remainder_and_is_within_1_over_1_minus_r_of_it():
    """sum_{k>=n} r^k / (k + 1) <= log1m_tail(r, n) <= that / (1 - r), the remainder from mpmath at 60 digits
    (L(r) less the first n terms): a tail shrunk ((n + 2), (1 + r), (2 - r)) falls below the remainder."""
    import mpmath
    from rigor_gyro.kinds.lyapunov.moments import log1m_tail
    with mpmath.workdps(60):
        for num, den in ((0, 1), (1, 100), (1, 10), (1, 4), (1, 2)):
            rq = mpmath.mpf(num) / den
            L = mpmath.mpf(1) if num == 0 else -mpmath.log(1 - rq) / rq
            for n in (1, 2, 3, 5, 10, 30):
                rem = L - mpmath.fsum(rq ** k / (k + 1) for k in range(n))
                t = log1m_tail(arb(fmpq(num, den)), n)
                lo, hi = (mpmath.mpf(e.numerator) / e.denominator for e in exact_endpoints(t))
                assert t.is_finite() and hi >= rem - mpmath.mpf(10) ** -55, (num, den, n)
                assert lo <= rem / (1 - rq) * (1 + mpmath.mpf(10) ** -15) + mpmath.mpf(10) ** -55, (num, den, n)


def test_log1m_ratio_encloses_minus_log_1_minus_u_over_u_tightly():
    """L(u) = -log(1 - u) / u at points of [-3/4, 3/4] (the series up to |u| = 1/2, log1p beyond) and at 0:
    contains mpmath's value (60 digits), radius below 2^-50 at 64 bits; NaN for a ball beyond 1/2 through 0."""
    import mpmath
    from rigor_gyro.kinds.lyapunov.moments import log1m_ratio
    with working_precision(64), mpmath.workdps(60):
        for num, den in ((-3, 4), (-1, 2), (-1, 3), (-1, 1000), (0, 1), (1, 1000), (1, 3), (1, 2), (3, 4)):
            v = log1m_ratio(arb(fmpq(num, den)))
            uq = mpmath.mpf(num) / den
            ref = mpmath.mpf(1) if num == 0 else -mpmath.log(1 - uq) / uq
            assert contains_mp(v, ref) and v.rad() < arb(2) ** -50, (num, den, v)
        assert not log1m_ratio(arb(0, 0.9)).is_finite()


@pytest.mark.parametrize("law", ["sine", "linear"])
def test_each_moment_law_against_mpmath_f_its_derivative_f_over_x_g_and_q(law):
    """Each law's f, f', f/x, G(x) = int_0^x cos(s) f(s) / (A0 - C0 sin^2 s) ds (mpmath quadrature at 50
    digits) and, where it has one, q's closed form f^2 / (2 D G): enclosed, at points of both signs and
    C0 = 0 (the sine law's own branch), C0 > 0 and C0 < 0. mutmut's first run over moments.py found G's
    C0 = 0 branch, f/x and the linear law's G untested."""
    from rigor_gyro.kinds.lyapunov.moments import moment_law
    L = moment_law(law)
    fm = {"sine": mpmath.sin, "linear": lambda t: t}[law]
    dfm = {"sine": mpmath.cos, "linear": lambda t: 1}[law]

    with working_precision(128), mpmath.workdps(50):
        for a_, A0_, C0_ in (("3/2", "127/10", "0"), ("3/2", "127/10", "7/5"), ("1/3", "2", "-5/2")):
            a, A0, C0 = (arb(fmpq(*map(int, t.split("/"))) if "/" in t else fmpq(int(t))) for t in (a_, A0_, C0_))
            am, A0m, C0m = (mpmath.mpf(Fraction(t).numerator) / Fraction(t).denominator for t in (a_, A0_, C0_))
            assert contains_mp(L.G(a, A0, C0, arb(0)), 0)
            for xq in (Fraction(3, 10), Fraction(-7, 10), Fraction(6, 5)):
                x = arb(fmpq(xq.numerator, xq.denominator))
                xm = mpmath.mpf(xq.numerator) / xq.denominator
                assert contains_mp(L.f(a, x), am * fm(xm)) and contains_mp(L.df(a, x), am * dfm(xm))
                assert contains_mp(L.f_over_x(a, x), am * fm(xm) / xm)
                G = mpmath.quad(lambda t: mpmath.cos(t) * am * fm(t) / (A0m - C0m * mpmath.sin(t) ** 2), [0, xm])
                assert contains_mp(L.G(a, A0, C0, x), G), (law, a_, C0_, xq)
                q = L.q_closed(a, A0, C0, x)
                if q is not None:
                    D = A0m - C0m * mpmath.sin(xm) ** 2
                    assert contains_mp(q, (am * fm(xm)) ** 2 / (2 * D * G)), (law, a_, C0_, xq)


def test_log1m_ratio_adds_the_whole_tail_bound_from_the_balls_largest_modulus(monkeypatch):
    """White box: the tail is below 2^-(prec+8), under the partial sums' own rounding, so no value can show
    it dropped. With log1m_tail stood in by a ball [1, 2] (never below eps: the loop runs to its cap) the
    result's radius must reach 2 (the tail's upper end, as a radius); and the tail is asked at |u|'s upper
    end (0.3 for u = [0.2 +/- 0.1])."""
    from rigor_gyro.kinds.lyapunov import moments
    asked = []

    def stand_in(r, n):
        asked.append(r)
        return arb("1.5") + arb(0, 0.5)
    monkeypatch.setattr(moments, "log1m_tail", stand_in)
    with working_precision(64):
        v = moments.log1m_ratio(arb("0.2") + arb(0, 0.1))
    assert v.is_finite() and v.rad() >= 2 and abs(v.mid() - arb("1.116")) < 1
    assert all(r >= arb("0.3") for r in asked) and asked
