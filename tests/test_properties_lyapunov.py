"""Property tests of the Lyapunov scene kind (Agafonov et al. 2013) against the float/mpmath side.

Parameters are drawn as exact decimal strings around the paper's instrument and far from it: moments
of inertia over two decades (A0 > C0 always, C0 < 0 allowed), H from 10 to 1e6, a from 1e-3 to 1e4,
x2* from pi/24 to 23 pi/48 (cos x2* -> 0) or a decimal in (0.05, 1.55), both moment laws; k and mu are
placed relative to the float k_min and mu interval (k from half to 20 times k_min; mu from below to
above (16)), then rounded to 4 significant digits (exact decimals). Oracles, from fair to weak:

* mpmath at 50 digits (:func:`rigor_gyro.kinds.lyapunov.approx.mp_constants`: closed forms, quadrature,
  grid + golden-section searches; no guarantee): the certified balls, widened by ``MPMATH_REL_TOL``,
  must contain A0 ... R, c_star and R_sup at the certified mu_best; R_max must not exceed the mpmath
  supremum;
* float64 grad V . f (analytic gradient of (7) dotted with (2)) at random points of the region: it must
  lie in the ball of Vdot (automatic differentiation in balls, :meth:`rigor_gyro.kinds.lyapunov.model.Gimbal.vdot`)
  widened by ``FLOAT_VDOT_TOL`` times its cancellation scale; a miss is a finding about floats,
  counted in ``FLOAT_FAILURES`` and listed in the test run's summary (tests/conftest.py), never a failure;
* the audited form (8) (float -Psi1 x1^2 - Psi2 x3^2) agrees with the ball Vdot to ``FLOAT_PSI_TOL``
  of its term scale; the printed (8) certainly does not, wherever x2 != 0 and x3 != 0;
* the library itself at twice the precision: no claim flips, enclosed quantities overlap;
* a proved best_mu lies inside (16) (the claim's own statement); a planted R far too large is refuted
  with a witness where float grad V . f > 0 too.

Run a campaign with ``HYPOTHESIS_PROFILE=long pytest tests/test_properties_lyapunov.py -s``.
"""
import decimal
import functools
import math
from decimal import Decimal

import mpmath
import numpy as np
import pytest
from flint import arb
from hypothesis import assume, event, example, given, settings
from hypothesis import strategies as st

from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, FloatGimbal, float_constants, mp_constants
from rigor_gyro.core.balls import certainly_le, certainly_lt, certainly_nonzero, working_precision
from rigor_gyro.certificate import Status
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import parse_scene

#: mp_constants works at 50 + 10 digits; closed forms and quadrature are good to ~1e-55, searched
#: optima (golden section to ~1e-29 in x) to ~1e-50 in value. 1e-40 leaves ten digits of slack and is
#: still far below the certified widths (rel_width 1e-15 for m, M, p, R1, R2).
MPMATH_REL_TOL = "1e-40"
MP_DPS = 50
#: digits of an mpmath value written out for the exact comparison
MPMATH_DIGITS = 60
#: working precision (bits) of the comparisons: ~77 digits > MPMATH_DIGITS
CHECK_PREC = 256
#: precision of the ball evaluation of Vdot at float points (the float inputs are exact binary numbers)
BALL_PREC = 128
#: float grad V . f is a sum of products ~H^3 |x1 x3| / (B0^2 D) that cancel to Vdot ~ Psi |x|^2; each
#: factor carries a few ulps, so its error is ~1e-15 of the cancellation scale sum_i |dV/dx_i x_i'|.
#: 1e-12 of that scale accepts ~4500 ulps.
FLOAT_VDOT_TOL = 1e-12
#: below ~1e-300 a float product of three coordinates has underflowed (hypothesis draws radii down to
#: 1e-300): an absolute slack of this size keeps underflow out of the findings
FLOAT_UNDERFLOW = 1e-300
#: the Psi form has no cancellation beyond the sum of its six terms: 1e-13 of sum |terms|
FLOAT_PSI_TOL = 1e-13
#: maxprec of the proofs here. The kind escalates until m, M, p, R1, R2 have relative width <= 1e-15;
#: where (16)'s  mu H cos^2 x2* - A0 m  nearly cancels, R2 inherits m's branch-and-bound tolerance
#: amplified and never gets there, so the prover climbs to DEFAULT_MAXPREC for nothing (up to ~40 s per
#: proof; a finding reported to the kind). Containment and consistency hold at any precision, so the
#: property runs cap it.
PROPERTY_MAXPREC = 256
#: the doubled proof may go to twice that
DOUBLE_MAXPREC = 2 * PROPERTY_MAXPREC
#: the certified mu_best must reach the mpmath supremum of R_sup to this relative gap (its golden-section
#: search runs on ball midpoints to 1e-14 and keeps 12 digits; at a kink, R_sup moves ~2 R/mu per unit mu)
MU_BEST_REL_GAP = "1e-8"
#: quantities that are *chosen* by the proof (decimals fixed from a bound, and what is computed from
#: them), not enclosures of one fixed number: they may differ between precisions
CHOSEN = ("c_set", "extent_x1_axis", "extent_x2_axis", "extent_x3_axis", "extent_x1", "extent_x2", "extent_x3", "mu_best",
          "R_max", "R_sup_at_mu_best", "R_sup_upper_bound", "R_max_relative_gap",
          "cylinder_margin_lower")   # a certified lower bound: it may rise with the precision
#: quantities of `constants` checked against mpmath
CONSTANTS = ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1", "R2", "R")

#: float failures found so far: key -> description (reported by the last test)
FLOAT_FAILURES: dict[tuple, str] = {}

PAPER = tuple(sorted(AGAFONOV2013.items()))
#: pinned parameter sets: the paper, its linear law, and the issue's extreme cases that prove quickly
PINNED = [
    PAPER,
    tuple(sorted(dict(AGAFONOV2013, moment="linear").items())),
    tuple(sorted(dict(AGAFONOV2013, H="1e6").items())),
    tuple(sorted(dict(AGAFONOV2013, x2_star="0.49*pi").items())),
    tuple(sorted(dict(AGAFONOV2013, a="1e6").items())),
]


def _n_examples(fraction: int) -> settings:
    """A share of the profile's max_examples (proofs are ~1 s each; the ci run stays well under a minute)."""
    return settings(max_examples=max(3, settings.default.max_examples // fraction))


# ----------------------------------------------------------------------------------------- strategies

_EXACT = decimal.Context(prec=80, traps=[decimal.Inexact, decimal.Rounded])


def _decimals(min_exp: int, max_exp: int, digits: int = 3) -> st.SearchStrategy[Decimal]:
    return st.builds(lambda m, e: Decimal(m).scaleb(e, _EXACT), st.integers(1, 10 ** digits - 1),
                     st.integers(min_exp, max_exp))


def _text(x: Decimal) -> str:
    return format(x.normalize(), "f")


def _round4(x: float) -> str:
    return _text(Decimal(f"{x:.4g}"))


@functools.lru_cache(maxsize=1024)
def _float_p(items: tuple) -> tuple[float, float, float]:
    """(p, A0, H) in floats: where k_min and the mu interval are, to place k and mu."""
    g = FloatGimbal(dict(items))
    x = np.linspace(0, g.xs, 2001)
    m, M = float(np.max(g.m_quotient(x))), float(np.max(g.q(x)))
    return max(M, g.A0 * m / math.cos(g.xs) ** 2), g.A0, g.H


@st.composite
def parameter_sets(draw, near_paper: bool = False, laws: tuple[str, ...] = ("sine", "linear")) -> tuple:
    """A valid parameter dict (as a sorted tuple of items) of exact decimal strings."""
    if near_paper:
        pick = lambda v, lo, hi: _text(Decimal(v) * Decimal(draw(st.integers(lo, hi))) / 100)  # noqa: E731
        p = {k: pick(AGAFONOV2013[k], 80, 125) for k in ("A", "C", "A1", "B1", "C1", "A2")}
        p["H"] = _text(Decimal(draw(st.sampled_from(["3e3", "1e4", "3e4", "1e5"]))))
        p["a"] = _text(Decimal(draw(st.sampled_from(["30", "100", "200"]))))
        p["x2_star"] = draw(st.sampled_from(["pi/8", "pi/6", "pi/5", "0.4", "0.6"]))
    else:
        A = draw(_decimals(-1, 0))
        p = {"A": _text(A), "C": _text(draw(_decimals(-1, 0))), "A1": _text(draw(_decimals(-1, 0))),
             "B1": _text(draw(_decimals(-1, 0))), "A2": _text(draw(_decimals(-2, 0)))}
        A0 = Decimal(p["A"]) + Decimal(p["A1"]) + Decimal(p["A2"])
        c1_frac = draw(st.integers(0, 120))          # C1 from 0 to 1.2 (A + A1): C0 from A + A1 down to < 0
        p["C1"] = _text((Decimal(c1_frac) * (Decimal(p["A"]) + Decimal(p["A1"])) / 100).quantize(Decimal("0.001")))
        assert A0 > Decimal(p["A"]) + Decimal(p["A1"]) - Decimal(p["C1"])
        p["H"] = _text(draw(_decimals(1, 5, digits=1)))
        p["a"] = _text(draw(_decimals(-3, 3, digits=2)))
        p["x2_star"] = draw(st.one_of(st.builds(lambda j: f"{j}/48*pi", st.integers(2, 23)),
                                      st.builds(lambda j: _text(Decimal(j) / 100), st.integers(5, 155))))
    p["moment"] = draw(st.sampled_from(laws))
    p["k"], p["mu"] = "1", "1"
    pf, A0f, Hf = _float_p(tuple(sorted(p.items())))
    kfac = draw(st.sampled_from([1.5, 2, 3, 10]) if near_paper else st.sampled_from([0.5, 1.01, 1.2, 2, 5, 20]))
    p["k"] = _round4(kfac * pf * A0f / Hf)
    lo, hi = pf / Hf, float(Decimal(p["k"])) / A0f
    frac = draw(st.sampled_from([0.25, 0.4, 0.5, 0.6, 0.75]) if near_paper
                else st.sampled_from([-0.2, 0.05, 0.3, 0.5, 0.7, 0.95, 1.2]))
    mu = lo + frac * (hi - lo)
    assume(mu > 0)
    p["mu"] = _round4(mu)
    return tuple(sorted(p.items()))


def pinned(test, which=None):
    for params in reversed(PINNED if which is None else which):
        test = example(params=params)(test)
    return test


#: pinned points (u2, r, theta) for the pointwise property: the corner x2 = x2* on the rim, x2 = 0
#: (where printed and derived (8) agree), and the origin (Vdot = 0 exactly)
PINNED_POINTS = [(1.0, 1.0, 1.0), (-0.5, 0.7, 4.0), (0.0, 1.0, 2.0), (0.3, 0.0, 0.0)]


def pinned_points(test):
    for params in reversed(PINNED):
        for u2, r, th in PINNED_POINTS:
            test = example(params=params, u2=u2, r=r, th=th)(test)
    return test


# ------------------------------------------------------------------------------------------- helpers

def scene(params: tuple, claims: tuple[str, ...]):
    body = "".join(f'{k} = "{v}"\n' for k, v in params)
    only = ", ".join(f'"{c}"' for c in claims)
    return parse_scene(f'name = "property"\nkind = "lyapunov"\n[parameters]\n{body}[claims]\nonly = [{only}]\n')


@functools.lru_cache(maxsize=256)
def prove(params: tuple, claims: tuple[str, ...], prec: int | None = None):
    kw = {"maxprec": PROPERTY_MAXPREC} if prec is None else {"prec": prec, "maxprec": max(DOUBLE_MAXPREC, prec)}
    return prove_scene(scene(params, claims), **kw)


@functools.lru_cache(maxsize=256)
def mp_values(params: tuple, with_best_mu: bool = False) -> dict:
    """mp_constants as decimal strings with MPMATH_DIGITS digits (None where undefined)."""
    c = mp_constants(dict(params), dps=MP_DPS, with_best_mu=with_best_mu)
    with mpmath.workdps(MPMATH_DIGITS + 10):
        return {k: (mpmath.nstr(v, MPMATH_DIGITS) if isinstance(v, mpmath.mpf) else v) for k, v in c.items()}


def widened(x: arb, rel_tol: str) -> arb:
    return x + arb(0, arb(rel_tol) * abs(x))


def contains_ref(ball: arb, ref: str, rel_tol: str = MPMATH_REL_TOL) -> bool:
    with working_precision(CHECK_PREC):
        return ball.is_finite() and widened(ball, rel_tol).contains(arb(ref))     # a NaN ball "contains" all


def contains_mp(ball: arb, ref) -> bool:
    """ball contains the mpmath number ref, computed at 50 digits (widened by 1e-40 relative for ref's own
    error). A NaN ball "contains" every number in Arb: it never passes here."""
    with working_precision(256):
        r = arb(mpmath.nstr(ref, 50))
        return ball.is_finite() and (ball + arb(0, 1e-40) * (1 + abs(r))).contains(r)


@functools.lru_cache(maxsize=256)
def float_R(params: tuple) -> float:
    return float(float_constants(dict(params), with_best_mu=False)["R"])


# ------------------------------------------------------------------------------------------ properties

@pinned_points
@given(params=parameter_sets(), u2=st.floats(-1, 1), r=st.floats(0, 1), th=st.floats(0, 2 * math.pi))
def test_float_vdot_lies_in_the_ball_and_matches_the_audited_form(params, u2, r, th):
    """(a) At a point of region (17) (x2 = u2 x2*, x1^2 + x3^2 = (r R)^2, R = min(R1, R2) capped at 0.1):
    float grad V . f lies in the ball enclosure of Vdot (AD in balls) widened by FLOAT_VDOT_TOL of its
    cancellation scale (else: counted finding); the float audited form (8) lies within FLOAT_PSI_TOL of
    the ball (else: counted finding); the ball AD Vdot and the ball derived form overlap (a library
    identity: asserted); the printed (8) certainly differs from the ball Vdot when x2 != 0 != x3."""
    p = dict(params)
    fg = FloatGimbal(p)
    R = min(float_R(params), 0.1)
    x1, x2, x3 = r * R * math.cos(th), u2 * float(fg.xs), r * R * math.sin(th)
    vd = float(fg.grad_V_dot_f(x1, x2, x3))
    scale = float(sum(abs(a * b) for a, b in zip(fg.grad_V(x1, x2, x3), fg.rhs3(x1, x2, x3))))
    (c10, c11, c13), (c20, c21, c23) = fg.psi_true(x2)
    terms = [c10 * x1 ** 2, c11 * x1 ** 3, c13 * x1 ** 2 * x3, c20 * x3 ** 2, c21 * x1 * x3 ** 2, c23 * x3 ** 3]
    vp = float(fg.vdot_psi(x1, x2, x3))
    psi_scale = float(sum(abs(t) for t in terms))
    g, _ = gimbal_from_parameters(p)
    with working_precision(BALL_PREC):
        b1, b2, b3 = arb(x1), arb(x2), arb(x3)            # exact: the floats themselves
        ball = g.vdot(b1, b2, b3)
        ball_psi = g.vdot_psi(b1, b2, b3)
        ball_printed = g.vdot_psi(b1, b2, b3, printed=True)
        assert ball.overlaps(ball_psi), (params, x1, x2, x3, ball, ball_psi)
        ok = (ball + arb(0, FLOAT_VDOT_TOL * scale + FLOAT_UNDERFLOW)).contains(arb(vd))
        ok_psi = (ball + arb(0, FLOAT_PSI_TOL * psi_scale + FLOAT_UNDERFLOW)).contains(arb(vp))
        if x2 != 0 and x3 != 0 and x1 ** 2 + x3 ** 2 > 0:
            differs = certainly_nonzero(ball_printed - ball)
            event(f"printed (8) certainly differs: {differs}")
            # the difference is -c23 x3^3, tiny only when x3 or sin x2 cos x2 is tiny
            if abs(float(c23) * x3 ** 3) > 1e-6 * psi_scale:
                assert differs, (params, x1, x2, x3, ball_printed, ball)
    key = (params, x1, x2, x3)
    if not ok:
        FLOAT_FAILURES[key + ("gradV.f",)] = (f"float grad V . f = {vd!r} outside Vdot ball {ball.str(10)} "
                                              f"+- {FLOAT_VDOT_TOL} * {scale:.3g}")
        event("float grad V . f outside the ball (finding)")
    if not ok_psi:
        FLOAT_FAILURES[key + ("psi",)] = (f"float -Psi1 x1^2 - Psi2 x3^2 = {vp!r} outside Vdot ball {ball.str(10)} "
                                          f"+- {FLOAT_PSI_TOL} * {psi_scale:.3g}")
        event("float Psi form outside the ball (finding)")


@pinned
@_n_examples(8)
@given(params=parameter_sets())
def test_certified_constants_contain_the_mpmath_values(params):
    """(b) The enclosures of claim `constants` (proved or not) contain the 50-digit mpmath values."""
    cert = prove(params, ("constants",))
    event(f"constants {cert.claim('constants').status.value}")
    ref = mp_values(params)
    for name in CONSTANTS:
        q = cert.quantities.get(name)
        if q is None or not q.is_finite():
            continue
        assert contains_ref(q, ref[name]), (name, q.str(30, radius=True), ref[name], params)


def assert_mu_best_inside_16(cert):
    """The claim reads "mu_best in (16) maximises ...": a proved best_mu lies certainly inside (p/H, k/A0)."""
    q = cert.quantities
    assert certainly_lt(q["mu_min"], q["mu_best"]) and certainly_lt(q["mu_best"], q["mu_max"]), (
        f"mu_best = {cert.claim('best_mu').details.get('mu_best')} not inside (16): "
        f"({q['mu_min'].str(20, radius=True)}, {q['mu_max'].str(20, radius=True)})")


#: laws of the random draws of the proof-heavy properties: proofs with the linear law (G by Arb
#: quadrature) take ~4x longer, so the short ci profile draws the sine law only (the linear law stays
#: pinned); longer profiles draw both
HEAVY_LAWS = ("sine",) if settings.default.max_examples <= 100 else ("sine", "linear")


@functools.partial(pinned, which=PINNED[:2])
@_n_examples(10)
@given(params=parameter_sets(near_paper=True, laws=HEAVY_LAWS))
def test_c_star_and_best_mu_agree_with_mpmath(params):
    """(b) Near the paper: a certified c* contains the mpmath boundary minimum (faces and cylinder);
    R_sup at the certified mu_best contains mpmath's R_sup there; R_max <= the mpmath supremum, and the
    certified mu_best is nearly optimal: mpmath's R_sup there is within MU_BEST_REL_GAP of the supremum
    (mu_best is a heuristic choice, its distance to mpmath's maximiser is only reported)."""
    cert = prove(params, ("invariant_estimate", "best_mu"))
    ref = mp_values(params, with_best_mu=True)
    inv, best = cert.claim("invariant_estimate"), cert.claim("best_mu")
    event(f"invariant_estimate {inv.status.value}, best_mu {best.status.value}")
    if "c_star" in cert.quantities and ref["c_star"] is not None:
        assert contains_ref(cert.quantities["c_star"], ref["c_star"]), (
            cert.quantities["c_star"].str(30, radius=True), ref["c_star"], ref["c_star_where"], params)
    if best.status is Status.PROVED:
        assert_mu_best_inside_16(cert)
    if best.status is Status.PROVED and ref["mu_best"] is not None:
        mu_text = best.details["mu_best"]            # the exact decimal the certificate fixed
        at = mp_values(tuple(sorted(dict(params, mu=mu_text).items())))
        assert contains_ref(cert.quantities["R_sup_at_mu_best"], at["R_sup"]), (
            cert.quantities["R_sup_at_mu_best"].str(20, radius=True), at["R_sup"], mu_text)
        with working_precision(CHECK_PREC):
            sup = arb(ref["R_max"])
            assert certainly_le(cert.quantities["R_max"], widened(sup, MPMATH_REL_TOL)), (
                cert.quantities["R_max"].str(20), ref["R_max"])
            assert certainly_le(sup * (1 - arb(MU_BEST_REL_GAP)), widened(arb(at["R_sup"]), MPMATH_REL_TOL)), (
                f"R_sup(mu_best = {mu_text}) = {at['R_sup']} vs supremum {ref['R_max']} at mu = {ref['mu_best']}")


@functools.partial(pinned, which=PINNED[:1])
@_n_examples(10)
@given(params=parameter_sets(near_paper=True, laws=HEAVY_LAWS))
def test_twice_the_precision_never_contradicts(params):
    """(c) Proving again at twice the final precision: no claim flips between proved and refuted, a
    decided claim stays decided, and every enclosed quantity's two balls overlap (the CHOSEN ones are
    decimals the proof fixes from a bound, e.g. c_set = c*'s lower end to 10 digits, and may move)."""
    claims = ("constants", "damping_condition", "vdot_nonpositive", "v_positive", "invariant_estimate")
    first = prove(params, claims)
    p = first.precision_bits
    second = prove(params, claims, prec=2 * p)
    for c1 in first.claims:
        s2 = second.claim(c1.id).status
        assert {c1.status, s2} != {Status.PROVED, Status.REFUTED}, (c1.id, c1.reason, second.claim(c1.id).reason)
        if c1.status is not Status.INCONCLUSIVE:
            assert s2 is c1.status, (c1.id, c1.reason[:300], second.claim(c1.id).reason[:300])
    for name, x in first.quantities.items():
        if name in second.quantities and name not in CHOSEN:
            assert x.overlaps(second.quantities[name]), (name, x, second.quantities[name])


def _mid(text: str) -> float:
    """A decimal or "[lo, hi]" from a witness, as a float (its midpoint)."""
    if text.startswith("["):
        lo, hi = text[1:-1].split(",")
        return (float(lo) + float(hi)) / 2
    return float(text)


@pytest.mark.parametrize("R", ["0.5", "0.03"])
def test_planted_refutation_agrees_with_floats(R):
    """A scene with R far too large (option R) refutes vdot_nonpositive with a witness point; the float
    side agrees: mpmath's R_sup (largest radius with Psi1, Psi2 > 0) is below R, and float grad V . f
    at the witness is positive (and equals the certified value to FLOAT_VDOT_TOL of its scale)."""
    body = "".join(f'{k} = "{v}"\n' for k, v in PAPER)
    cert = prove_scene(parse_scene(f'name = "planted"\nkind = "lyapunov"\n[parameters]\n{body}'
                                   f'[claims]\nonly = ["vdot_nonpositive"]\n[options]\nR = "{R}"\n'))
    claim = cert.claim("vdot_nonpositive")
    assert claim.status is Status.REFUTED, claim.reason
    ref = mp_values(PAPER)
    with mpmath.workdps(MPMATH_DIGITS):
        assert mpmath.mpf(ref["R_sup"]) < mpmath.mpf(R)
    w = claim.details["witness"]
    x1, x2, x3 = (_mid(w[k]) for k in ("x1", "x2", "x3"))
    fg = FloatGimbal(dict(PAPER))
    assert abs(x2) <= fg.xs * (1 + 1e-15) and x1 ** 2 + x3 ** 2 < float(R) ** 2
    vd = float(fg.grad_V_dot_f(x1, x2, x3))
    scale = float(sum(abs(a * b) for a, b in zip(fg.grad_V(x1, x2, x3), fg.rhs3(x1, x2, x3))))
    assert vd > 0
    assert abs(vd - _mid(w["vdot"])) <= FLOAT_VDOT_TOL * scale + 1e-6 * abs(vd)   # vdot is printed to 8 digits


@pytest.mark.slow
def test_best_mu_stays_inside_16_when_the_optimum_is_at_its_end():
    """Regression (found by this cross-check): with k just above k_min, R_sup(mu) increases towards the
    lower end p/H of (16) (mpmath: supremum 0.00026092386970903924 at mu -> p/H = 1/75), and the golden
    section's 12-digit decimal rounded *down* gave mu_best = 0.0133333333333 < p/H: a proved best_mu
    outside (16). Slow (30-180 s: R_sup at mu_best exhausts max_pieces)."""
    params = tuple(sorted(dict(AGAFONOV2013, k="0.1694", mu="0.0133339").items()))
    cert = prove(params, ("constants", "best_mu"))
    if cert.claim("best_mu").status is Status.PROVED:
        assert_mu_best_inside_16(cert)
