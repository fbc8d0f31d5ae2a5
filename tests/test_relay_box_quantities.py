"""kinds/periodic_orbit/box_quantities.py: every certified range holds mpmath / float samples of the box, and a
point box gives a tight ball."""
from __future__ import annotations

from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.periodic_orbit import validate
from rigor_gyro.kinds.periodic_orbit.box_quantities import BOX_QUANTITIES, quantities_box
from rigor_gyro.scene import load_scene

mp = pytest.importorskip("mpmath")
approx = pytest.importorskip("rigor_gyro.kinds.periodic_orbit.approx")
from tests.test_relay_box_continuation import _theta_mp  # noqa: E402


def _params(m, **kw):
    d = {k: Fraction(int(getattr(m.params, k).p), int(getattr(m.params, k).q)) for k in
         ("A", "B", "H", "tau", "sigma", "n", "K", "p", "S")}
    d.update(kw)
    return d


def test_box_quantities_hold_samples_of_a_half_percent_box():
    m = validate(load_scene("roitenberg1947"))
    lo, hi = Fraction(4975, 100), Fraction(5025, 100)
    with working_precision(128):
        q = quantities_box(m, Box.of({"n": (lo, hi)}), list(BOX_QUANTITIES))
    assert set(q) == set(BOX_QUANTITIES)
    th, per, mx, margin = (q[k].value for k in ("theta_star", "period", "max_modulus", "stability_margin"))
    assert BOX_QUANTITIES["stability_margin"].claim == "stable" and margin.lower() > 0
    for k in range(10):
        n = lo + (hi - lo) * Fraction(k, 9)
        t = _theta_mp(_params(m, n=n), float(th.lower()) - 1e-6, float(th.upper()) + 1e-6)
        assert th.contains(arb(mp.nstr(t, 18))) and per.contains(arb(mp.nstr(2 * t, 18)))
        mods = [abs(z) for z in approx.approx_multipliers(_params(m, n=n), float(t))]
        assert mx.lower() < max(mods) < mx.upper() and margin.lower() < 1 - max(mods) < margin.upper()


def test_box_quantities_tight_on_a_point_box():
    m = validate(load_scene("roitenberg1947"))
    with working_precision(128):
        q = quantities_box(m, Box.of({"n": (Fraction(50), Fraction(50))}), ["theta_star", "stability_margin"])
    assert q["theta_star"].value.rad() < 1e-14
    assert q["theta_star"].value.overlaps(arb("0.138133574136193", 1e-15))
    assert q["stability_margin"].value.rad() < 1e-10
