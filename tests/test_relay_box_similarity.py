"""Relay boxes decided on their similar box of (B, sigma, n) (kinds/periodic_orbit/similarity.py) and ``stable``
by the Gershgorin bound (norm_stability.py, normed_orbit.py): exact conjugacy, containment of every member's
image, and every certified range against mpmath / float samples of the box."""
from __future__ import annotations

import itertools
import random
from fractions import Fraction as F

import pytest
from flint import acb, acb_mat, arb, fmpq

from rigor_gyro.core.balls import ball, interval, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.boxes import evaluate_box
from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, RelayParams, nutation_cubic
from rigor_gyro.kinds.periodic_orbit.norm_stability import largest_modulus_range, spectral_radius_bound
from rigor_gyro.kinds.periodic_orbit.normed_orbit import continue_orbit_normed
from rigor_gyro.kinds.periodic_orbit.similarity import conjugacy_holds, similar_box, similar_point
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
np = pytest.importorskip("numpy")
brentq = pytest.importorskip("scipy.optimize").brentq

SIX = ("A", "B", "H", "tau", "sigma", "n")


def _model():
    return validate(load_scene("roitenberg1947"))


def _frac(x: fmpq) -> F:
    return F(int(x.p), int(x.q))


def _q(x: F) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _box(P, rel: F, names=SIX) -> Box:
    return Box.of({k: (_frac(getattr(P, k)) * (1 - rel), _frac(getattr(P, k)) * (1 + rel)) for k in names})


def _point(P, **kw) -> RelayParams:
    vals = {k: getattr(P, k) for k in PARAMETER_NAMES}
    vals.update({k: _q(v) for k, v in kw.items()})
    return RelayParams(**vals)


def _corners_and_samples(box: Box, n: int, seed: int = 3):
    rng = random.Random(seed)
    ivs = [box.interval(k) for k in box.names]
    for c in itertools.product(*ivs):
        yield dict(zip(box.names, c))
    for _ in range(n):
        yield {k: lo + (hi - lo) * F(rng.randrange(1001), 1000) for k, (lo, hi) in zip(box.names, ivs)}


def test_similar_points_are_exactly_conjugate_and_other_points_are_not():
    P = _model().params
    box = _box(P, F(1, 20))
    _, fixed = similar_box(P, box)
    for pt in _corners_and_samples(box, 20):
        Pp = _point(P, **pt)
        assert conjugacy_holds(Pp, similar_point(Pp, fixed))
    Q = similar_point(P, fixed)
    for k in ("B", "sigma", "n"):        # a point with other invariants is not conjugate
        assert not conjugacy_holds(P, _point(Q, **{k: _frac(getattr(Q, k)) * F(101, 100)}))


def test_similar_box_holds_the_image_of_every_corner_and_sample():
    P = _model().params
    for rel in (F(1, 200), F(1, 20)):
        box = _box(P, rel)
        rbox, fixed = similar_box(P, box)
        assert fixed == {k: _frac(getattr(P, k)) for k in ("A", "H", "tau")}
        for pt in _corners_and_samples(box, 30):
            Q = similar_point(_point(P, **pt), fixed)
            for k in rbox.names:
                lo, hi = rbox.interval(k)
                assert lo <= _frac(getattr(Q, k)) <= hi, (k, pt)
        # tight: the extreme corners reach both ends of each edge
        for k in rbox.names:
            vals = [_frac(getattr(similar_point(_point(P, **pt), fixed), k)) for pt in _corners_and_samples(box, 0)]
            assert (min(vals), max(vals)) == rbox.interval(k)


def test_no_similar_box_when_A_H_tau_are_fixed():
    P = _model().params
    assert similar_box(P, _box(P, F(1, 100), ("B", "n"))) is None


def _floats(R: RelayParams) -> dict:
    return {k: _frac(getattr(R, k)) for k in PARAMETER_NAMES}


def _orbit_float(pd: dict, lo=0.12, hi=0.16):
    th = brentq(lambda t: approx.approx_g(pd, t), lo, hi, xtol=1e-15)
    return th, sorted(abs(z) for z in approx.approx_multipliers(pd, th))


def test_similar_points_have_the_same_multipliers_and_scaled_half_period():
    P = _model().params
    box = _box(P, F(1, 50))
    _, fixed = similar_box(P, box)
    for pt in list(_corners_and_samples(box, 3))[::9]:
        Pp = _point(P, **pt)
        Q = similar_point(Pp, fixed)
        alpha = float(_frac(Pp.tau) / _frac(Q.tau))
        th_p, mod_p = _orbit_float(_floats(Pp), 0.12, 0.16)
        th_q, mod_q = _orbit_float(_floats(Q), 0.12 / alpha, 0.16 / alpha)
        assert th_p == pytest.approx(alpha * th_q, rel=1e-9)
        assert mod_p == pytest.approx(mod_q, rel=1e-7, abs=1e-9)


def _sample_matrix(K: acb_mat, rng) -> "mp.matrix":
    n = K.nrows()
    M = mp.matrix(n, n)
    for i in range(n):
        for j in range(n):
            z = K[i, j]
            re = float(z.real.mid()) + float(z.real.rad()) * (2 * rng.random() - 1) * 0.999
            im = float(z.imag.mid()) + float(z.imag.rad()) * (2 * rng.random() - 1) * 0.999
            M[i, j] = mp.mpc(re, im)
    return M


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_spectral_radius_bound_holds_sampled_members(seed):
    rng = random.Random(seed)
    diag = [0.95, 0.6 + 0.3j, 0.6 - 0.3j, 0.01]
    K = acb_mat(4, 4)
    for i in range(4):
        for j in range(4):
            c = diag[i] if i == j else complex(rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01))
            K[i, j] = acb(arb(c.real, 0.004), arb(c.imag, 0.004))
    bound = spectral_radius_bound(K)
    rng_ = largest_modulus_range(K)
    assert bound is not None and rng_ is not None and bound < 1
    assert rng_.lower() > 0.85             # the disc of 0.95 is isolated: a lower end from it
    for _ in range(40):
        ev = mp.eig(_sample_matrix(K, rng))[0]
        r = max(abs(z) for z in ev)
        assert r <= float(bound.upper())
        assert float(rng_.lower()) <= r <= float(rng_.upper())


def test_spectral_radius_bound_is_not_below_the_largest_modulus():
    # a matrix with its spectral radius 1.05 (a non-normal one): the bound must not claim < 1
    K = acb_mat([[acb(0.9), acb(0.3)], [acb(0.1), acb(0.8)]])
    ev = mp.eig(mp.matrix([[0.9, 0.3], [0.1, 0.8]]))[0]
    r = max(abs(z) for z in ev)
    assert r > 1
    b = spectral_radius_bound(K)
    assert b >= r and not b < 1
    assert largest_modulus_range(K).contains(arb(r)) or largest_modulus_range(K).upper() >= r


def _moduli_samples(P, box: dict, n: int, seed: int = 5):
    rng = random.Random(seed)
    ivs = {k: (float(b.lower()), float(b.upper())) for k, b in box.items()}
    pts = []
    for c in itertools.product(*[[0, 1]] * len(ivs)):
        pts.append({k: iv[s] for (k, iv), s in zip(ivs.items(), c)})
    for _ in range(n):
        pts.append({k: rng.uniform(*iv) for k, iv in ivs.items()})
    out = []
    for pt in pts:
        pd = {k: float(_frac(getattr(P, k))) for k in PARAMETER_NAMES}
        pd.update({k: F(v) for k, v in pt.items()})
        out.append(_orbit_float({k: F(v) for k, v in pd.items()}))
    return out


def test_gershgorin_decides_a_box_rump_does_not_and_holds_samples(monkeypatch):
    """B +-0.4 %, n +-0.2 %, sigma +-0.15 % at once (the similar box of a six-parameter box): stable by the disc bound
    where the isolation of the four multipliers fails; the certified largest modulus and theta* hold samples."""
    import rigor_gyro.kinds.periodic_orbit.continuation as C
    monkeypatch.setattr(C, "decide_by_cells", lambda *a, **k: None)
    m = _model()
    P = m.params
    with working_precision(128):
        rel = {"B": F(1, 250), "n": F(1, 500), "sigma": F(3, 2000)}
        box = {k: interval(ball(_q(_frac(getattr(P, k)) * (1 - r))), ball(_q(_frac(getattr(P, k)) * (1 + r))))
               for k, r in rel.items()}
        iso = isolate_polynomial(nutation_cubic(P))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        o = continue_orbit_normed(P, box, list(box), guesses, arb("0.138133574136"))
    assert o.genuine and o.stable is True
    assert o.moduli == []          # decided by the discs: Rump's method did not isolate the four multipliers
    for th, mods in _moduli_samples(P, box, 12):
        assert o.theta.lower() < th < o.theta.upper()
        assert o.max_modulus.lower() <= max(mods) <= o.max_modulus.upper()


@pytest.mark.slow
def test_all_six_at_a_fifth_percent_stable_and_half_percent_genuine():
    m = _model()
    with working_precision(128):
        out = evaluate_box(m, _box(m.params, F(1, 500)), ["stable"])
        assert out["stable"][0] == "proved" and "similar box" in out["stable"][1]
        out = evaluate_box(m, _box(m.params, F(1, 200)), ["orbit_genuine"])
        assert out["orbit_genuine"][0] == "proved" and "similar box" in out["orbit_genuine"][1]


@pytest.mark.slow
def test_all_six_at_half_a_percent_stable_on_pieces_of_the_similar_box():
    """The six parameters at +-0.5 % at once: stable on 16 pieces of the similar box (B' halved three times, then
    sigma'), about a minute of CPU."""
    m = _model()
    with working_precision(128):
        out = evaluate_box(m, _box(m.params, F(1, 200)), ["stable", "orbit_genuine"])
    assert out["stable"][0] == "proved" and "pieces of a bisection" in out["stable"][1]
    assert out["orbit_genuine"][0] == "proved"


def test_lower_end_only_from_an_isolated_disc():
    # eigenvalues 0, 0 (nilpotent) although |K_11| - R_1 = 1 > 0: the discs overlap, so no lower end from them
    K = acb_mat([[acb(3), acb(2)], [acb("-4.5"), acb(-3)]])
    r = largest_modulus_range(K)
    assert r.contains(0) and spectral_radius_bound(K) >= 0


def test_stable_not_claimed_where_the_disc_bound_reaches_one(monkeypatch):
    """B +-0.75 % alone without the cell fallback: neither Rump's method nor the discs decide (bound > 1), so
    the orbit is not called stable over the box."""
    import rigor_gyro.kinds.periodic_orbit.continuation as C
    monkeypatch.setattr(C, "decide_by_cells", lambda *a, **k: None)
    P = _model().params
    with working_precision(128):
        box = {"B": interval(ball(_q(_frac(P.B) * F(397, 400))), ball(_q(_frac(P.B) * F(403, 400))))}
        iso = isolate_polynomial(nutation_cubic(P))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        o = continue_orbit_normed(P, box, ["B"], guesses, arb("0.138133574136"))
    assert o.genuine and o.stable is not True and "Gershgorin bound" in o.problem


def test_a_box_in_tau_alone_is_continued_directly_before_its_three_dimensional_similar_box():
    """tau alone moves B', sigma' and n' of the similar box: a +-1 % box in tau is decided by one continuation over
    the box itself (the similar box's cover is the fall-back); a box of all six is still reduced."""
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        out = evaluate_box(m, Box.of({"tau": (F("0.0099"), F("0.0101"))}), ["orbit_genuine", "stable"])
    assert {k: s for k, (s, _) in out.items()} == {"orbit_genuine": "proved", "stable": "proved"}
    assert not any("similar box" in why for _, why in out.values())
