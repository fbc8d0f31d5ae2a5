"""The float twins of the point searches (rigor_gyro.kinds.lyapunov.float_twin, issue 41): they agree with the
ball midpoints they replace on the grids, and a twin that lies only moves where a search starts: every
certified number stays certified (a wrong proposal never makes a wrong statement)."""
import math

from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov import direct_claims as DC, mu_claims as MC
from rigor_gyro.kinds.lyapunov import direct_mu, float_twin, sublevel
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.polar_forms import v_polar, vdot_polar
from rigor_gyro.kinds.lyapunov.search import grid_then_compass


def _gimbal(**kw):
    return gimbal_from_parameters(dict(AGAFONOV2013, **kw))[0]


def _close(x: float, ball: arb, scale: float) -> bool:
    return abs(x - float(ball.mid())) <= 1e-12 * scale


def test_the_twin_agrees_with_the_ball_midpoints():
    """psi's polar forms, V's polar coefficients and rho: the twin against the ball functions' midpoints at
    64 bits (1e-12 of the quantities' scale), for the sine and the linear law (the linear law has no float G:
    no v_polar twin)."""
    for law in ("sine", "linear"):
        g = _gimbal(moment=law)
        fg = float_twin.float_twin(g)
        assert fg is not None
        with working_precision(64):
            xs = g.c.x2_star
            for u, s in ((-1, 0.3), (-0.4, 0.9), (0.25, 0.05), (1, 0.71)):
                X, T = xs * arb(u), arb.pi() * arb(s)
                A, B = vdot_polar(g, X, T)
                a, b = fg.vdot_polar(fg.xs * u, math.pi * s)
                scale = abs(float(A.mid())) + abs(float(B.mid()))
                assert _close(a, A, scale) and _close(b, B, scale)
                rho = MC.rho_function(g)(X.mid())
                assert _close(fg.rho(fg.xs * u), rho, float(rho.mid()))
                if law == "sine":
                    al, be, ga = v_polar(g, X, T)
                    tw = fg.v_polar(fg.xs * u, math.pi * s)
                    for x, y in zip(tw, (al, be, ga)):
                        assert _close(x, y, abs(float(al.mid())) + abs(float(ga.mid())))
                else:
                    assert fg.v_polar(fg.xs * u, math.pi * s) is None


def test_no_twin_for_other_laws_and_nan_out_of_range():
    g = _gimbal()

    class Other(type(g.law)):
        pass
    other = _gimbal()
    object.__setattr__(other, "law", Other())
    assert float_twin.float_twin(other) is None
    fg = float_twin.float_twin(_gimbal(H="1e300"))
    assert not float_twin.in_safe_range(*fg.vdot_polar(0.5, 0.3))
    assert float_twin.in_safe_range(0.0, 1.0, -1e100) and not float_twin.in_safe_range(math.nan)


def test_grid_then_compass_with_a_twin_gives_the_ball_grids_answer_and_survives_a_liar():
    calls = []

    def f(u, s):
        return (u - 0.3) ** 2 + (s - 0.6) ** 2 + (u * s) ** 4

    def value(u, s):
        calls.append((u, s))
        return f(u, s), u + s

    plain = grid_then_compass(value, (9, 9), 30)
    n_plain = len(calls)
    calls.clear()
    twin = grid_then_compass(value, (9, 9), 30, propose=lambda u, s: f(u, s) * (1 + 1e-14))
    assert twin == plain and len(calls) < n_plain
    # a twin that lies (the worst point proposed): the compass search starts there, the value is a real one
    liar = grid_then_compass(value, (9, 9), 30, propose=lambda u, s: -f(u, s))
    assert liar[0] == value(liar[1], liar[2])[0]
    # NaN anywhere: the grid in balls, as without a twin
    assert grid_then_compass(value, (9, 9), 30, propose=lambda u, s: math.nan) == plain


def _liar(monkeypatch):
    """Every twin proposes a wrong grid point: A/|B| scrambled (A keeps its sign: the smallest A seen is part
    of the direct search's answer), V's coefficients and rho negated (the worst point)."""
    class Liar(float_twin.FloatGimbal):
        __slots__ = ()

        def vdot_polar(self, x2, t):
            A, B = super().vdot_polar(x2, t)
            return A, B * (1 + 10 * abs(math.sin(37 * x2 + 11 * t)))

        def v_polar(self, x2, t):
            return tuple(-v for v in super().v_polar(x2, t))

        def rho(self, x2):
            return -super().rho(x2)

    def make(g):
        return Liar(g)
    for mod in (float_twin, MC, direct_mu, sublevel):
        monkeypatch.setattr(mod, "float_twin", make)


def test_a_lying_twin_leaves_every_certified_number_true(monkeypatch):
    """With the worst grid points proposed, the largest sublevel's certified bracket, the direct test's
    certified radius and the Psi test's R_sup search stay consistent with the honest run's certified
    numbers: c_lower <= the honest c_upper, the direct radius certified (or nothing) is below the honest
    run's certified point above the supremum; a search that starts badly only certifies less."""
    g = _gimbal()
    with working_precision(64):
        honest_s = sublevel.largest_sublevel(g, 3000)
        honest_d = DC.certify_direct(g, 3000)
        honest_r = MC._r_sup_search(g, g.c.x2_star)
    _liar(monkeypatch)
    with working_precision(64):
        lied_s = sublevel.largest_sublevel(g, 3000)
        lied_d = DC.certify_direct(g, 3000)
        est, at = MC._r_sup_search(g, g.c.x2_star)
    if lied_s.c_lower is not None:
        assert float(lied_s.c_lower) <= float(honest_s.c_upper)
    if lied_d.cert is not None and lied_d.cert.status.value == "proved":
        assert float(lied_d.R_text) <= float(honest_d.up_text)
    assert est > 0 and math.isfinite(est)
    assert est != honest_r[0]           # the liar did move the R_sup search (it only chooses: nothing certified)


def test_a_twin_value_rounded_to_zero_never_stops_the_direct_search():
    """A hostile review's scene: mu just below k/A0 (= 4/127), where A(x2 = 0, t = 0) = (H/B0)^2 (k/A0 - mu) is
    1e-12, certainly > 0 in balls and exactly 0.0 in the float twin. The smallest A the direct search reports
    (which, when <= 0, makes vdot_direct give up at any precision) comes from the ball there, as before the
    twin: positive."""
    from flint import arb
    from rigor_gyro.core.balls import certainly_positive, working_precision
    from rigor_gyro.kinds.lyapunov.claims import validate
    from rigor_gyro.kinds.lyapunov.direct_mu import direct_point_search
    from rigor_gyro.kinds.lyapunov.float_twin import float_twin
    from rigor_gyro.kinds.lyapunov.polar_forms import vdot_polar
    from rigor_gyro.scene import load_scene, parse_scene
    text = load_scene("agafonov2013").parameters
    params = "\n".join(f'{k} = "{v}"' for k, v in text.items() if k != "mu")
    g = validate(parse_scene(f'name = "edge"\nkind = "lyapunov"\nsource = "t"\n[parameters]\n{params}\n'
                             f'mu = "0.031496062992125984"\n')).gimbal
    with working_precision(64):
        A, _ = vdot_polar(g, arb(0), arb(0))
        assert certainly_positive(A) and float_twin(g).vdot_polar(0.0, 0.0)[0] == 0.0
        assert direct_point_search(g)[3] > 0
