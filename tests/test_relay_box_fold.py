"""The certified obstruction to step 1 of the relay continuation (kinds/periodic_orbit/theta_fold.py) and the
similar-box cover's stop (box_orbit._cover): the sign change is confirmed in mpmath at members of the box, a
skipped attempt would have failed, and the cover bisects only where theta* was proved."""
from __future__ import annotations

import dataclasses
from fractions import Fraction as F
from types import SimpleNamespace

import pytest
from flint import acb, arb, fmpq

from rigor_gyro.core.balls import ball, interval, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.jets import Jet
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.periodic_orbit import box_orbit, validate
from rigor_gyro.kinds.periodic_orbit import continuation as C
from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, nutation_cubic
from rigor_gyro.kinds.periodic_orbit.theta_fold import _points, slope_ratio, slope_sign_change
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")

#: the stable orbit at H = 9325 (the roots of g crowd there: dG/dtheta ~ 1e-6 at each)
FAST_THETA = arb("0.11951111283810129367306640331937442928")


def _model():
    return validate(load_scene("roitenberg1947"))


def _q(x: F) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _guesses(P):
    iso = isolate_polynomial(nutation_cubic(P))
    return [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]


def _fast_box():
    """(centre params at H = 9325, {H: ball of [9000, 9650]}, guesses, models, tc)."""
    P = dataclasses.replace(_model().params, H=fmpq(9325))
    box = {"H": interval(ball(fmpq(9000)), ball(fmpq(9650)))}
    g = _guesses(P)
    models = C._Models(P, box, ["H"], g)
    tc = C._centre_root(models, FAST_THETA)
    assert tc is not None
    return P, box, g, models, arb(tc.mid())


def _G_theta_mp(vals: dict, theta) -> "mp.mpf":
    """dG/dtheta of G = g K (K = |1 + exp(lambda theta)|^2 over the cubic's complex pair) in mpmath, 40 digits."""
    with mp.workdps(40):
        v = {k: mp.mpf(x.mid().str(60, radius=False)) for k, x in vals.items()}
        M = mp.matrix([[0, 1, 0, 0, 0], [0, 0, -v["H"] / v["B"], 0, 0], [0, v["H"] / v["A"], 0, v["K"] / v["A"], 0],
                       [0, 0, -v["n"] / (v["K"] * v["tau"]), -1 / v["tau"], v["p"] / v["tau"]],
                       [0, 0, 0, 0, -1 / v["sigma"]]])
        aug = mp.zeros(6, 6)
        for i in range(5):
            for j in range(5):
                aug[i, j] = M[i, j]
        aug[4, 5] = v["S"] / v["sigma"]
        q2 = v["H"] ** 2 / (v["A"] * v["B"])
        roots = mp.polyroots([1, 1 / v["tau"], q2 + v["n"] / (v["tau"] * v["A"]), q2 / v["tau"]], maxsteps=200)
        lam = [z for z in roots if mp.im(z) > 0][0]

        def G(t):
            E = mp.expm(aug * t)
            Phi = mp.matrix([[E[i, j] for j in range(5)] for i in range(5)])
            w = mp.matrix([E[i, 5] for i in range(5)])
            g = mp.lu_solve(mp.eye(5) + Phi, -w)[0]
            return g * abs(1 + mp.exp(lam * t)) ** 2

        return mp.diff(G, mp.mpf(theta.mid().str(60, radius=False)))


def test_sign_change_of_the_slope_found_and_confirmed_at_members():
    with working_precision(128):
        P, box, g, models, tc = _fast_box()
        c = models.centre.G(Jet.variable(acb(tc), 1, 2)).d[1].real
        sc = slope_sign_change(models.cvals, box, ["H"], g, tc, c)
    assert sc is not None and "vanishes for some member" in sc.text
    (_, v1, d1), (_, v2, d2) = sc.points
    assert (d1 > 0 and d2 < 0) or (d1 < 0 and d2 > 0)
    for vals, d in ((v1, d1), (v2, d2)):
        assert vals["H"] >= 9000 and vals["H"] <= 9650            # members (certain comparisons)
        assert vals["H"].rad() == 0 and all(vals[k] is models.cvals[k] for k in PARAMETER_NAMES if k != "H")
        x = _G_theta_mp(vals, tc)
        assert float(d.lower()) <= float(x) <= float(d.upper())


def test_the_skipped_cell_attempt_would_have_failed():
    with working_precision(128):
        P, box, g, models, tc = _fast_box()
        res, why = C._theta_over_box(models, acb(tc).real, 8, lambda c, b: C._Models(c, b, ["H"], g))
        assert res is None
        o = C.continue_orbit(P, box, ["H"], g, FAST_THETA)
    assert o.theta is None and o.fold and "vanishes for some member" in o.problem


def test_no_sign_change_on_a_decidable_box():
    P = _model().params
    with working_precision(128):
        box = {"B": interval(ball(_q(F(133, 1000) * F(99, 100))), ball(_q(F(133, 1000) * F(101, 100))))}
        g = _guesses(P)
        models = C._Models(P, box, ["B"], g)
        tc = arb(C._centre_root(models, arb("0.138133574136")).mid())
        c = models.centre.G(Jet.variable(acb(tc), 1, 2)).d[1].real
        assert slope_sign_change(models.cvals, box, ["B"], g, tc, c) is None
        assert slope_sign_change(models.cvals, box, ["B"], g, tc, -c) is not None   # a sign flip is seen
        # a centre value of uncertain sign counts for nothing (its midpoint has the other sign)
        assert slope_sign_change(models.cvals, box, ["B"], g, tc, arb(-c.mid(), 2 * abs(c).upper())) is None


def _h_box(rel: F) -> Box:
    return Box.of({"H": (F(100) * (1 - rel), F(100) * (1 + rel))})


def test_the_similar_box_is_bisected_only_where_theta_was_proved(monkeypatch):
    """A cover whose undivided similar box certified no theta* stops there (then the original box is tried);
    one that certified theta* but decided nothing bisects until its budget is spent."""
    from rigor_gyro.kinds.periodic_orbit import similar_cover
    m = _model()
    calls = []

    def fake(reached, ratio=None):
        def continue_orbit(centre, balls, dirs, guesses, theta0, **kw):
            calls.append(dict(balls))
            o = C.OrbitOverBox(theta_c=theta0, slope_ratio=ratio)
            if reached:
                o.theta = theta0
            return o
        return continue_orbit

    orbit = SimpleNamespace(theta=arb("0.138133574136"), stable=True, kind="genuine")
    monkeypatch.setattr(box_orbit, "centre_orbits", lambda model, want_stable: (None, [orbit]))   # no point analysis
    with working_precision(64):
        monkeypatch.setattr(box_orbit, "continue_orbit", fake(False))
        assert box_orbit.continued_outcomes(m, _h_box(F(1, 100)), ["stable"]) == {}
        assert [list(c) for c in calls] == [["B"], ["H"]]
        calls.clear()
        monkeypatch.setattr(box_orbit, "continue_orbit", fake(True))
        monkeypatch.setattr(similar_cover.cover, "__defaults__", (4, 5))
        assert box_orbit.continued_outcomes(m, _h_box(F(1, 100)), ["stable"]) == {}
        # the similar box, its left half, that half's left half (then the budget cannot pay for two more halves),
        # then the original box
        assert [list(c) for c in calls] == [["B"], ["B"], ["B"], ["H"]]
        for ratio, n in ((box_orbit.MIN_SLOPE_RATIO / 2, 1), (box_orbit.MIN_SLOPE_RATIO, 3)):
            calls.clear()       # step 1 failed: halved only where the slope ratio leaves hope
            monkeypatch.setattr(box_orbit, "continue_orbit", fake(False, ratio))
            assert box_orbit.continued_outcomes(m, _h_box(F(1, 100)), ["stable"]) == {}
            assert [list(c) for c in calls] == [["B"]] * n + [["H"]]


@pytest.mark.parametrize("rel", [F(1, 2), F(1, 1000), F(1, 10**12)])
def test_every_test_point_is_a_member_of_the_box(rel):
    """The points lie in the exact box although they are built from its balls (which exceed it a little)."""
    P = _model().params
    exact = {k: F(int(getattr(P, k).p), int(getattr(P, k).q)) for k in ("A", "B", "n")}
    iv = {k: (v * (1 - rel), v * (1 + rel)) for k, v in exact.items()}
    with working_precision(128):
        box = {k: interval(ball(_q(lo)), ball(_q(hi))) for k, (lo, hi) in iv.items()}
        cvals = {k: ball(getattr(P, k)) for k in PARAMETER_NAMES}
        pts = list(_points(cvals, box, list(iv)))
        assert len(pts) == 8 * 3 + 2
        for label, vals in pts:
            for k, (lo, hi) in iv.items():
                assert vals[k] >= _q(lo) and vals[k] <= _q(hi), (label, k)


def test_slope_ratio_hopeless_where_roots_crowd_and_not_at_the_printed_point():
    with working_precision(128):
        P, box, g, models, tc = _fast_box()
        fast = slope_ratio(models, tc)
        Q = _model().params
        B = F(133, 1000)
        sim = {"B": interval(ball(_q(B / F(26, 25) ** 2)), ball(_q(B / F(24, 25) ** 2)))}   # H = 100 +-4 %'s
        gq = _guesses(Q)
        mq = C._Models(Q, sim, ["B"], gq)
        slow = slope_ratio(mq, C._centre_root(mq, arb("0.138133574136")))
    assert fast < 1e-6 < box_orbit.MIN_SLOPE_RATIO < 0.01 < slow < 1
