"""Property tests of the periodic-orbit kind over parameters near the physical example (each parameter
scaled by an exact decimal factor in [1/4, 4]) and wider (tau down to 1e-5, H up to 2000).

Oracles: mpmath at 40 digits (``approx_orbit_mpmath``) must lie in the certified theta* ball widened by
``MPMATH_TOL``; scipy's float theta* (brentq on the expm formulation, bracketed around the certified
value) and numpy's multipliers must lie in the balls widened by ``FLOAT_THETA_TOL`` /
``FLOAT_MULT_TOL``, otherwise the case is counted in ``FLOAT_FAILURES`` (a finding about floats, not a
test failure); the library at twice the final precision must never contradict a decided claim and its
balls must overlap the first ones.

The ``ci`` profile runs a handful of examples (each proof takes ~0.1-1 s); ``HYPOTHESIS_PROFILE=long``
runs a campaign.
"""
from decimal import Decimal

import mpmath
from flint import arb
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from rigor_gyro.kinds.periodic_orbit.approx import approx_g, approx_multipliers, approx_orbit_mpmath
from rigor_gyro.certificate import Status
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import parse_scene

#: examples per property, from the loaded hypothesis profile (--hypothesis-profile or HYPOTHESIS_PROFILE)
EXAMPLES = max(3, settings.default.max_examples // 7)

#: mpmath findroot at 40 (+10 guard) digits: good to ~1e-35 absolute on theta ~ 0.1-1
MPMATH_TOL = "1e-30"
#: brentq on float expm: g is evaluated with ~1e-16 relative error of terms ~a theta; theta* moves by
#: (that error)/g'(theta*), 1e-9 absolute accepts g' down to ~1e-7
FLOAT_THETA_TOL = 1e-9
#: numpy eigvals of a well-conditioned 4x4 float Jacobian built from float expm
FLOAT_MULT_TOL = 1e-7
FLOAT_FAILURES: dict = {}

BASE = dict(A="125", B="2/15", H="100", tau="0.01", sigma="0.13125", n="50", K="7.5", p="40", S="0.15")


def _scene(params):
    body = "\n".join(f'{k} = "{v}"' for k, v in params.items())
    return parse_scene(f'name = "prop"\nkind = "periodic_orbit"\n[parameters]\n{body}\n')


def _scaled(base: str, factor: Decimal) -> str:
    from fractions import Fraction
    q = Fraction(base) * Fraction(factor)
    return f"{q.numerator}/{q.denominator}"


factors = st.integers(25, 400).map(lambda k: Decimal(k) / 100)


@st.composite
def near_physical(draw):
    p = dict(BASE)
    for k in ("A", "B", "H", "sigma", "n", "K", "p", "S"):
        p[k] = _scaled(BASE[k], draw(factors))
    p["tau"] = draw(st.sampled_from(["0.01", "0.005", "0.02", "0.001", "0.00001"]))
    if draw(st.booleans()):
        p["H"] = draw(st.sampled_from(["300", "1000", "2000"]))
    return p


@settings(max_examples=EXAMPLES)
@given(params=near_physical())
@example(params=BASE)
@example(params={"A": "165/2", "B": "373/750", "H": "300", "tau": "0.02", "sigma": "567/16000", "n": "331/2",
                 "K": "573/40", "p": "10/1", "S": "3/80"})   # conjugate pair once listed in either order
def test_certified_orbit_against_float_mpmath_and_twice_the_precision(params):
    c = prove_scene(_scene(params), maxprec=1024)
    og = c.claim("orbit_genuine")
    assume(og.status is Status.PROVED)
    th = c.quantities["theta_star"]
    # mpmath 40 digits
    thm, _ = approx_orbit_mpmath(params, float(th.mid()), dps=40)
    assert th.is_finite() and th.overlaps(arb(mpmath.nstr(thm, 40), MPMATH_TOL)), (params, th, thm)
    # scipy brentq on the float expm formulation, bracketed around the certified value
    from scipy.optimize import brentq
    t = float(th.mid())
    h = 1e-6 * t
    ga, gb = approx_g(params, t - h), approx_g(params, t + h)
    if ga * gb < 0:
        tf = brentq(lambda x: approx_g(params, x), t - h, t + h, xtol=1e-16)
        if not th.overlaps(arb(tf, FLOAT_THETA_TOL)):
            FLOAT_FAILURES[tuple(params.items())] = f"theta float {tf} vs {th}"
        ev = approx_multipliers(params, tf)
        for z, j in zip(ev, range(1, 5)):
            m = c.quantities[f"multiplier_modulus_{j}"]
            if not m.overlaps(arb(abs(z), FLOAT_MULT_TOL * max(abs(z), 1e-12) + 1e-15)):
                FLOAT_FAILURES[tuple(params.items()) + (j,)] = f"|multiplier {j}| float {abs(z)} vs {m}"
    else:
        FLOAT_FAILURES[tuple(params.items())] = "float g has no sign change around theta*"
    # twice the precision: no contradiction, balls overlap
    c2 = prove_scene(_scene(params), prec=2 * c.precision_bits, maxprec=4 * c.precision_bits)
    for a, b in zip(c.claims, c2.claims):
        if Status.INCONCLUSIVE not in (a.status, b.status):
            assert a.status is b.status, (params, a.id, a.status, b.status)
    for k, v in c.quantities.items():
        if k in c2.quantities:
            assert v.is_finite() and c2.quantities[k].is_finite() and v.overlaps(c2.quantities[k]), (params, k)
