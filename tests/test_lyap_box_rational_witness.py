"""Issue 37 part 3: a refutation whose failing piece reaches the irrational end x2* = pi/6.

certify_positive's witness there is the end ball (never an exact point); ``v_positive`` then certifies its
counterexample at an exact rational point inside the range (:func:`model.rational_points_inside`). At mu = 0.0101
(psi <= 0 only near x2*, V < 0 at the minimiser of V on that slice) the claim is refuted at the first precision,
the stored x2 is an exact rational certainly inside [0, pi/6] (checked in mpmath here and by the checker).
"""
import json
from fractions import Fraction

import mpmath
from flint import arb

from rigor_gyro import prove_scene
from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov.approx import MpGimbal
from rigor_gyro.kinds.lyapunov.check import check
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.kinds.lyapunov.vdot_tests import rational_points_inside
from rigor_gyro.scene import load_scene, parse_scene


def _scene(mu: str):
    body = dict(load_scene("agafonov2013").parameters, mu=mu)
    text = 'name = "witness"\nkind = "lyapunov"\n[parameters]\n' + "".join(f'{k} = "{v}"\n' for k, v in body.items())
    return parse_scene(text + '[claims]\nonly = ["v_positive"]\n')


def _exact(pair) -> Fraction:
    """A stored ball [lo, hi] (exact texts) that is an exact point, as a Fraction; fails on a non-exact ball."""
    lo, hi = (Fraction(t) for t in pair)
    assert lo == hi, pair
    return lo


def test_v_positive_is_refuted_at_a_rational_point_inside_when_psi_fails_at_the_irrational_end():
    cert = prove_scene(_scene("0.0101"), maxprec=256)
    c = cert.claim("v_positive")
    assert c.status.value == "refuted", c.reason
    assert cert.precision_bits == 64                       # decided at the first precision, no escalation
    pt = c.counterexample["point"]
    x1, x2, x3 = (_exact(pt[k]) for k in ("x1", "x2", "x3"))
    mpmath.mp.dps = 40
    assert 0 < mpmath.mpf(x2.numerator) / x2.denominator < mpmath.pi / 6                         # a rational strictly inside the range
    params = dict(load_scene("agafonov2013").parameters, mu="0.0101")
    v = MpGimbal(params).V(mpmath.mpf(x1.numerator) / x1.denominator, mpmath.mpf(x2.numerator) / x2.denominator,
                           mpmath.mpf(x3.numerator) / x3.denominator)
    assert v < 0                                           # V < 0 there in mpmath too
    data = json.loads(json.dumps(cert.to_json()))
    with working_precision(128):
        bad = [(r.item, r.message) for r in check(validate(_scene("0.0101")), data) if not r.ok]
    assert not bad, bad


def test_rational_points_inside_are_exact_and_certainly_in_the_range():
    with working_precision(64):
        xs = arb.pi() / 6
        for w in (xs, -xs, arb("0.3"), arb(0)):
            pts = rational_points_inside(w, xs)
            assert pts, w
            for x in pts:
                assert x.rad() == 0 and abs(x) <= xs
        assert rational_points_inside(arb(1), xs) == []        # an exact point outside the range
        assert rational_points_inside(arb(0).union(arb(1)), xs) == []  # a ball of either sign
