"""The half-period Jacobian over a parameter box in centred form (kinds/periodic_orbit/jacobian_box.py).

Its guarantee: for every theta in the ball and every parameter in the balls, each entry contains J's.
Tested at the corners and the centre of a box in three parameters (each J computed at the exact point
by the spectral route of flow.py, an independent formula), for width (the reason it exists), and for the
guard that combines it with the direct enclosure.
"""
from __future__ import annotations

import itertools
from fractions import Fraction as F

import pytest
from flint import acb_mat, arb, arb_mat, fmpq

from rigor_gyro.core.balls import interval, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.periodic_orbit import boxes, jacobian_box
from rigor_gyro.kinds.periodic_orbit.flow import PARAMETER_NAMES, RelayParams, Spectrum, half_period_jacobian, x0_at

PRINTED = dict(A=F(125), B=F("0.133"), H=F(100), tau=F("0.01"), sigma=F("0.13125"), n=F(50), K=F("7.5"),
               p=F(40), S=F("0.15"))
THETA = (F("0.13805"), F("0.13822"))          # around the printed orbit's theta* = 0.13813...


def _q(x: F) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _balls(spread: dict[str, tuple[F, F]]) -> RelayParams:
    return RelayParams(**{k: interval(_q(spread[k][0]), _q(spread[k][1])) if k in spread else arb(_q(PRINTED[k]))
                          for k in PARAMETER_NAMES})


def _point_jacobian(point: dict[str, F], theta: F) -> arb_mat:
    P = RelayParams(**{k: _q(point.get(k, PRINTED[k])) for k in PARAMETER_NAMES})
    sp = Spectrum(P)
    th = arb(_q(theta))
    return half_period_jacobian(sp, th, x0_at(sp, th))


def _max_rad(J: arb_mat) -> float:
    return max(float(J[i, j].rad()) for i in range(J.nrows()) for j in range(J.ncols()))


SPREAD = {"n": (F("49.9"), F("50.1")), "H": (F("99.95"), F("100.05")), "tau": (F("0.00999"), F("0.01001")),
          "sigma": (F("0.1312"), F("0.1313")), "S": (F("0.149"), F("0.151"))}


def test_the_centred_jacobian_contains_j_at_every_corner_and_the_centre():
    with working_precision(128):
        Jc = jacobian_box.centred_jacobian(_balls(SPREAD), interval(_q(THETA[0]), _q(THETA[1])))
        assert Jc is not None
        names = sorted(SPREAD)
        corners = [dict(zip(names, c)) for c in itertools.product(*(SPREAD[k] for k in names))]
        corners.append({k: (lo + hi) / 2 for k, (lo, hi) in SPREAD.items()})
        for point, theta in itertools.product(corners, THETA + (sum(THETA) / 2,)):
            Jp = _point_jacobian(point, theta)
            bad = [(i, j) for i in range(4) for j in range(4) if not (Jc[i, j].is_finite() and Jc[i, j].contains(Jp[i, j]))]
            assert not bad, (point, theta, bad)


def test_the_exponential_route_agrees_with_the_spectral_one_at_a_point():
    with working_precision(128):
        P = RelayParams(**{k: arb(_q(v)) for k, v in PRINTED.items()})
        Je = jacobian_box.jacobian_by_exponential(P, arb(_q(THETA[0])))
        Js = _point_jacobian({}, THETA[0])
        for i in range(4):
            for j in range(4):
                assert Je[i, j].is_finite() and Js[i, j].is_finite() and Je[i, j].overlaps(Js[i, j])
                assert float(abs(Je[i, j] - Js[i, j]).upper()) < 1e-25


@pytest.mark.parametrize("name", PARAMETER_NAMES + ("theta",))
def test_each_derivative_matches_a_difference_quotient(name):
    """On a box of half-width d in one variable the centred form is J(centre) + dJ/dx [-d, d]: its
    radius must be |dJ/dx| d, against the central difference (J(x + d) - J(x - d)) / 2 of the
    independent spectral route (dJ/dS = 0: J is homogeneous of degree 0 in S)."""
    with working_precision(192):
        theta, d = THETA[0], F(1, 10 ** 12)
        if name == "theta":
            diff = _point_jacobian({}, theta + d) - _point_jacobian({}, theta - d)
            Jc = jacobian_box.centred_jacobian(_balls({}), interval(_q(theta - d), _q(theta + d)))
        else:
            x = PRINTED[name]
            diff = _point_jacobian({name: x + d}, theta) - _point_jacobian({name: x - d}, theta)
            Jc = jacobian_box.centred_jacobian(_balls({name: (x - d, x + d)}), arb(_q(theta)))
        for i in range(4):
            for j in range(4):
                slope = abs(diff[i, j]) / 2
                err = float(abs(arb(Jc[i, j].rad()) - slope).upper())
                assert err <= 1e-6 * float(slope.upper()) + 1e-18, (i, j, Jc[i, j], slope)      # dJ/dx to 1e-6


def test_the_centred_form_is_much_narrower_than_the_direct_enclosure():
    """The reason it exists: on n in 50 +- 0.01 (theta* spread over the box as the paving finds it),
    the direct enclosure was measured 12 times wider."""
    with working_precision(128):
        h = F(1, 100)
        Pb = _balls({"n": (50 - h, 50 + h)})
        Pmid = RelayParams(**{k: _q(v) for k, v in PRINTED.items()})
        sp = boxes.BoxSpectrum(Pb, Pmid)
        theta = interval(_q(F("0.1381313")), _q(F("0.1381359")))
        direct = half_period_jacobian(sp, theta, x0_at(sp, theta))
        centred = jacobian_box.centred_jacobian(Pb, theta)
        assert _max_rad(centred) * 10 < _max_rad(direct)
        combined = sp.jacobian(theta, x0_at(sp, theta))
        assert _max_rad(combined) <= _max_rad(centred) * (1 + 1e-6)      # the intersection's radius is rounded up
        for i in range(4):
            for j in range(4):
                c = combined[i, j]        # the intersection (its radius rounded up a little)
                assert direct[i, j].is_finite() and centred[i, j].is_finite()
                assert direct[i, j].contains(arb(c.mid())) and centred[i, j].contains(arb(c.mid()))
                assert float(c.rad()) <= min(float(direct[i, j].rad()), float(centred[i, j].rad())) * (1 + 1e-6)


def test_disjoint_enclosures_are_a_bug_not_a_tighter_jacobian(monkeypatch):
    with working_precision(128):
        h = F(1, 100)
        Pb = _balls({"n": (50 - h, 50 + h)})
        sp = boxes.BoxSpectrum(Pb, RelayParams(**{k: _q(v) for k, v in PRINTED.items()}))
        theta = interval(_q(F("0.1381313")), _q(F("0.1381359")))
        real = jacobian_box.centred_jacobian(Pb, theta)
        shifted = arb_mat([[real[i, j] + (1 if (i, j) == (2, 1) else 0) for j in range(4)] for i in range(4)])
        monkeypatch.setattr(boxes, "centred_jacobian", lambda P, t, parts=None: shifted)
        with pytest.raises(AssertionError, match="disjoint"):
            sp.jacobian(theta, x0_at(sp, theta))
        monkeypatch.setattr(boxes, "centred_jacobian", lambda P, t, parts=None: None)
        direct = half_period_jacobian(sp, theta, x0_at(sp, theta))
        got = sp.jacobian(theta, x0_at(sp, theta))
        assert all(got[i, j].mid() == direct[i, j].mid() and got[i, j].rad() == direct[i, j].rad()
                   for i in range(4) for j in range(4))


def test_a_parameter_ball_reaching_zero_gives_no_centred_form():
    with working_precision(128):
        assert jacobian_box.centred_jacobian(_balls({"tau": (F(-1, 100), F(1, 100))}), arb(_q(THETA[0]))) is None


def _printed_model():
    from rigor_gyro.kinds import kind_module
    from rigor_gyro.scene import Scene
    scene = Scene(name="t", kind="periodic_orbit", source="", parameters={k: str(v) for k, v in PRINTED.items()},
                  claims_only=None, options={}, paper={}, path=None)
    return kind_module("periodic_orbit").validate(scene)


#: n in 50 +- 0.5 and the theta* spread the box analysis finds there
WIDE_N = (F("49.5"), F("50.5"))
WIDE_THETA = (F("0.138012457029"), F("0.138254664321"))


def test_the_eigen_coordinate_multipliers_contain_every_members_multipliers():
    with working_precision(128):
        Pb = _balls({"n": WIDE_N})
        enclosures = jacobian_box.eigen_coordinate_multipliers(Pb, interval(_q(WIDE_THETA[0]), _q(WIDE_THETA[1])))
        assert enclosures is not None and len(enclosures) == 4
        assert all(e.is_finite() for e in enclosures)                 # a NaN ball would contain every z
        for n, theta in itertools.product(WIDE_N + (sum(WIDE_N) / 2,), WIDE_THETA + (sum(WIDE_THETA) / 2,)):
            for z in acb_mat(_point_jacobian({"n": n}, theta)).eig(algorithm="rump"):
                assert sum(1 for e in enclosures if e.contains(z)) == 1, (n, theta, z, enclosures)


def test_eigen_coordinates_decide_where_rump_on_the_jacobian_ball_cannot():
    with working_precision(128):
        Pb = _balls({"n": WIDE_N})
        sp = boxes.BoxSpectrum(Pb, RelayParams(**{k: _q(v) for k, v in PRINTED.items()}))
        theta = interval(_q(WIDE_THETA[0]), _q(WIDE_THETA[1]))
        J = sp.jacobian(theta, x0_at(sp, theta))
        with pytest.raises(ValueError):
            acb_mat(J).eig(algorithm="rump")
        moduli = [abs(z) for z in sp.multipliers(J, theta)]
        assert all(m < 1 for m in moduli)         # certainly below 1: the box is stable


def test_stable_is_decided_on_a_box_25_times_wider_than_before():
    """Before the centred forms, the printed scene's stable claim was decided on sub-boxes of n about
    0.04 wide (the paving of n in [40, 60]: 512 of width 20/512, none wider); now on n in 50 +- 0.5."""
    with working_precision(128):
        out = boxes.evaluate_box(_printed_model(), Box.of({"n": WIDE_N}), ["stable"])
    assert out["stable"][0] == "proved", out
