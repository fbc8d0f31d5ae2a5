"""kinds/periodic_orbit/similar_modulus.py: the largest multiplier modulus over a relay box, enclosed on pieces of
its similar box, holds float samples of the box; a piece whose orbit is not shown to be the box's own is refused."""
from __future__ import annotations

from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.box_quantities import quantities_box
from rigor_gyro.kinds.periodic_orbit.similar_modulus import modulus_on_similar_box
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
from tests.test_relay_box_continuation import _theta_mp  # noqa: E402
from tests.test_relay_box_quantities import _params  # noqa: E402

PRINTED = {"A": Fraction(125), "B": Fraction(133, 1000), "H": Fraction(100), "tau": Fraction(1, 100),
           "sigma": Fraction(13125, 100000), "n": Fraction(50)}
#: all six at +-0.25 % (about a range tile of margin_roitenberg_all_half_percent): the continuation over the box
#: encloses theta* but not the multipliers
BOX = {k: (v * Fraction(399, 400), v * Fraction(401, 400)) for k, v in PRINTED.items()}
#: A, H and tau at +-0.05 %: one piece of the similar box encloses the moduli (a quick box for the refusals)
SMALL = {k: (PRINTED[k] * Fraction(1999, 2000), PRINTED[k] * Fraction(2001, 2000)) for k in ("A", "H", "tau")}


#: all six at +-0.15 %: the smallest such box whose multipliers still need the similar box (at +-0.1 % the
#: continuation encloses them itself); a third of BOX's cost, for the default run
MID = {k: (v * Fraction(1997, 2000), v * Fraction(2003, 2000)) for k, v in PRINTED.items()}


def _corners_and_centre(box):
    names = list(box)
    for mask in range(0, 2 ** len(names), 7):      # 10 of the 64 corners
        yield {k: box[k][(mask >> i) & 1] for i, k in enumerate(names)}
    yield {k: (lo + hi) / 2 for k, (lo, hi) in box.items()}


@pytest.mark.parametrize("box, radius", [
    pytest.param(BOX, 0.005, marks=pytest.mark.slow, id="quarter_percent"),   # the tight cover: [0.95390, 0.95895]
    pytest.param(MID, 0.01, id="0.15_percent"),                                # (floats: [0.9556, 0.9575])
])
def test_max_modulus_over_the_box_holds_float_samples(box, radius, monkeypatch):
    from rigor_gyro.kinds.periodic_orbit import box_quantities
    used = []
    monkeypatch.setattr(box_quantities, "modulus_on_similar_box",
                        lambda *a: used.append(modulus_on_similar_box(*a)) or used[-1])
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        q = quantities_box(m, Box.of(box), ["theta_star", "max_modulus", "stability_margin"])
    assert {"theta_star", "max_modulus", "stability_margin"} <= set(q)
    assert len(used) == 1 and used[0] is not None       # the moduli came from the similar box
    th, mx = q["theta_star"].value, q["max_modulus"].value
    assert mx.upper() < 1 and mx.rad() < radius
    for pt in _corners_and_centre(box):
        p = _params(m, **pt)
        t = _theta_mp(p, float(th.lower()) - 1e-6, float(th.upper()) + 1e-6)
        mods = [abs(z) for z in approx.approx_multipliers(p, float(t))]
        assert mx.lower() < max(mods) < mx.upper()


def test_pieces_count_only_where_their_orbit_is_shown_to_be_the_boxs():
    m = validate(load_scene("roitenberg1947"))
    asked = []

    def unique_in(W):
        asked.append(W)
        return False                        # uniqueness not shown: the pieces' orbits may be other orbits
    with working_precision(128):
        theta = arb("0.1300", "1e-6")       # a wrong enclosure of the box's theta*, far from the pieces' orbits
        assert modulus_on_similar_box(m, Box.of(SMALL), theta, unique_in) is None
        # W holds the given theta and every piece's half-period mapped back (theta' tau / tau_c, about 0.13813)
        assert len(asked) == 1 and asked[0].contains(theta) and asked[0].contains(arb("0.13813", "1e-5"))
        got = modulus_on_similar_box(m, Box.of(SMALL), theta, lambda W: True)
    assert got is not None and got[0].upper() < 1


def test_a_box_varying_none_of_a_h_tau_does_not_reduce():
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        assert modulus_on_similar_box(m, Box.of({"n": (Fraction(49), Fraction(51))}), arb("0.138", "0.01"),
                                      lambda W: True) is None


def test_at_most_one_root_only_where_g_is_monotone():
    from flint import acb
    from rigor_gyro.core.polyroots import isolate_polynomial
    from rigor_gyro.kinds.periodic_orbit.continuation import at_most_one_root
    from rigor_gyro.kinds.periodic_orbit.flow import nutation_cubic
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        box = Box.of(SMALL)
        dirs = list(SMALL)
        balls = {k: box.ball(k) for k in dirs}
        iso = isolate_polynomial(nutation_cubic(m.params))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        assert at_most_one_root(m.params, balls, dirs, guesses, arb("0.1381", "0.0005"))
        # g has six roots on (0, 0.73] at the printed point (roitenberg1947's certificate): not monotone there
        assert not at_most_one_root(m.params, balls, dirs, guesses, arb("0.3", "0.29"))
        # one form over a wide W spans 0 where four pieces of it decide (the pieces are what makes it work)
        W = arb("0.1381", "0.004")
        wide = Box.of({k: (v * Fraction(399, 400), v * Fraction(401, 400)) for k, v in PRINTED.items()})
        wballs = {k: wide.ball(k) for k in PRINTED}
        assert not at_most_one_root(m.params, wballs, list(PRINTED), guesses, W, pieces=(1,))
        assert at_most_one_root(m.params, wballs, list(PRINTED), guesses, W)


def test_a_piece_is_signed_only_about_a_point_inside_it():
    from flint import acb
    from rigor_gyro.core.polyroots import isolate_polynomial
    from rigor_gyro.kinds.periodic_orbit.continuation import _Models, _slope_sign
    from rigor_gyro.kinds.periodic_orbit.flow import nutation_cubic
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        box = Box.of(SMALL)
        iso = isolate_polynomial(nutation_cubic(m.params))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        models = _Models(m.params, {k: box.ball(k) for k in SMALL}, list(SMALL), guesses)
        assert _slope_sign(models, arb("0.1381", "0.0002"), arb("0.1381")) != 0
        assert _slope_sign(models, arb("0.1381", "0.0002"), arb("0.1385")) == 0


def test_at_most_one_root_refuses_a_centre_outside_the_box():
    import dataclasses
    from flint import acb, fmpq
    from rigor_gyro.core.polyroots import isolate_polynomial
    from rigor_gyro.kinds.periodic_orbit.continuation import at_most_one_root
    from rigor_gyro.kinds.periodic_orbit.flow import nutation_cubic
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        box = Box.of(SMALL)
        balls = {k: box.ball(k) for k in SMALL}
        iso = isolate_polynomial(nutation_cubic(m.params))
        guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
        outside = dataclasses.replace(m.params, A=fmpq(126))          # A's box is [124.9375, 125.0625]
        assert not at_most_one_root(outside, balls, list(SMALL), guesses, arb("0.1381", "0.0005"))
