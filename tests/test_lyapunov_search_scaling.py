"""The direct test's float search compares A/|B| even where A and B leave the double range (issue 41: at
H = 1e300 both are about H^2 = 1e600, their floats were inf and the search reported "inf A/|B| ~ inf")."""
import math

import pytest

from flint import arb

from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.direct_mu import direct_point_search
from rigor_gyro.kinds.lyapunov.search import scaled_ratio


def _ratio(A, B):
    return scaled_ratio(A, B, float(A.mid()), float(B.mid()))


def test_scaled_ratio_in_and_beyond_the_double_range():
    assert _ratio(arb(3), arb(-2)) == 1.5                       # the common case: a / |b|, unchanged
    assert _ratio(arb(3), arb(0)) == math.inf
    big = arb(10) ** 600
    assert math.isclose(_ratio(3 * big, -2 * big), 1.5, rel_tol=1e-15)
    assert math.isclose(_ratio(-3 * big, 2 * big), -1.5, rel_tol=1e-15)
    tiny = arb(10) ** -600                                       # floats underflow to 0
    assert math.isclose(_ratio(3 * tiny, 2 * tiny), 1.5, rel_tol=1e-15)
    assert math.isclose(_ratio(arb(3) * tiny, arb(1)), 0.0, abs_tol=1e-300)
    assert math.isclose(_ratio(arb(1), 2 * tiny), math.inf) or _ratio(arb(1), 2 * tiny) > 1e300
    assert math.isclose(_ratio(3 * big, arb(2) * 10 ** 300 * big), 1.5e-300, rel_tol=1e-12)


def _gimbal(H):
    return gimbal_from_parameters(dict(AGAFONOV2013, H=H))[0]


def test_the_search_at_H_1e300_finds_the_radius_it_finds_at_H_1e30():
    # A/|B| depends on H only through terms of relative size 1/H^2: the same minimiser and value
    v30, u30, s30, a30 = direct_point_search(_gimbal("1e30"))
    v300, u300, s300, a300 = direct_point_search(_gimbal("1e300"))
    assert math.isfinite(v300) and v300 > 0 and a300 > 0
    assert math.isclose(v300, v30, rel_tol=1e-9)
    assert abs(u300 - u30) < 1e-6 and abs(s300 - s30) < 1e-6


# ------------------------------------------------------------------ the extremes end to end (issue 41)

def _extreme_scene(param, value):
    import dataclasses
    from rigor_gyro.scene import load_scene
    base = load_scene("agafonov2013")
    return dataclasses.replace(base, name=f"agafonov2013_{param}_{value}", paper={},
                               parameters=dict(base.parameters, **{param: value}))


def test_a_1e300_meets_the_widths_at_64_bits_and_decides_the_linear_row():
    """a = 1e-300: m, M to the relative width 1e-15 at 64 bits (the floor of the tolerance is relative to the
    value where it is below 1: an absolute 2^-prec floor escalated the scene to 2048 bits), and the audit row
    'p = M = A0 m = a' decided (its M for f = a x2 enclosed relative to a; G by quadrature with a factored out).
    Each enclosure contains the mpmath value at 30 digits: m, M against q and the quotient sampled at 40 points
    (below the certified maximum), and G(x) of the linear law against mpmath.quad."""
    import mpmath
    from rigor_gyro.core.balls import working_precision
    from rigor_gyro.core.outcome import AuditStatus
    from rigor_gyro.kinds.lyapunov.approx import MpGimbal
    from rigor_gyro.kinds.lyapunov.claim_context import ClaimContext as _Ctx
    from rigor_gyro.kinds.lyapunov.claims import validate
    from rigor_gyro.kinds.lyapunov.moments import MOMENTS
    from rigor_gyro.kinds.lyapunov.paper import linear_section_rows
    scene = _extreme_scene("a", "1e-300")
    model = validate(scene)
    g = model.gimbal
    with working_precision(64):
        ctx = _Ctx(model, 64)
        m, M = ctx.m_max().ball, ctx.M_max().ball
        for v in (m, M):
            assert v.is_finite() and v.rad() < abs(v) * arb("1e-15") and abs(v) < arb("1e-299")
        row = next(r for r in linear_section_rows(g, g.c.x2_star, model.max_pieces)
                   if r.id.startswith("linear setting"))
        assert row.status is AuditStatus.REFUTED, row.note
        law = MOMENTS["linear"]
        Gs = [(x, law.G(g.c.a, g.c.A0, g.c.C0, arb(x))) for x in ("0.1", "0.5")]
    with mpmath.workdps(30):
        mg = MpGimbal(dict(AGAFONOV2013, a="1e-300"))
        xs = mpmath.pi / 6
        qs = [mg.q(xs * i / 40) for i in range(1, 41)]
        assert max(qs) <= mpmath.mpf(M.upper().str(30, radius=False)) * (1 + mpmath.mpf(10) ** -25)
        lin = MpGimbal(dict(AGAFONOV2013, a="1e-300", moment="linear"))
        for x, G in Gs:
            # a outside the quadrature here too: mpmath.quad's absolute tolerance stops at 1e-12 relative otherwise
            ref = lin.a * mpmath.quad(lambda s: s * mpmath.cos(s) / (lin.A0 - lin.C0 * mpmath.sin(s) ** 2),
                                      [0, mpmath.mpf(x)])
            assert G.is_finite() and G.rad() < abs(G) * arb("1e-15")
            with working_precision(256):
                assert (G + arb(0, "1e-25") * abs(G)).contains(arb(mpmath.nstr(ref, 30))), (G, ref)


@pytest.mark.slow
@pytest.mark.parametrize("param, value", [("H", "1e300"), ("a", "1e-300")])
def test_the_gimbal_extremes_finish_at_64_or_128_bits(param, value):
    """Issue 41's gimbal extremes (1-3 s each): no escalation to 2048 bits; H = 1e300 inconclusive only for
    largest_sublevel (V's lower bound unbounded below, precision cannot help), a = 1e-300 proved."""
    from rigor_gyro.prover import prove_scene
    cert = prove_scene(_extreme_scene(param, value))
    st = {c.id: c.status.value for c in cert.claims}
    assert max(cert.precisions_tried) <= 128, cert.precisions_tried
    assert st["equilibria"] == "proved"
    if param == "H":
        assert [k for k, v in st.items() if v != "proved"] == ["largest_sublevel"]
    else:
        assert set(st.values()) == {"proved"}
