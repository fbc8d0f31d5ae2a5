"""Property tests of the eigenfrequency scene kind (Rudenko 1976) over the whole parameter domain.

Parameters are drawn as exact decimal strings (integer mantissa times a power of ten) over the domain
b > 1, a > b, eps > 0, Omega2 > 0, with its edges: b - 1 and a - b down to 1e-6, eps from 1e-6 to
~100, Omega2 from 1e-6 to 1e4. Oracles, from fair to weak:

* mpmath ``polyroots`` at 50 digits (no guarantee, but ~1e-50 relative when it converges): the
  certified balls, widened by ``MPMATH_REL_TOL``, must contain it;
* numpy's companion-matrix roots (float): must lie in the ball widened by ``FLOAT_REL_TOL``; when they
  do not, that is a finding about floats (counted in ``FLOAT_FAILURES`` and listed in the test run's summary (tests/conftest.py)
  of the module), never a failure of the test;
* the library itself at twice the precision: a proved or refuted claim is never contradicted, and the
  balls of every quantity overlap.

Run a campaign with ``HYPOTHESIS_PROFILE=long pytest tests/test_properties_eigfreq.py -s``; the
summary test prints the float failures found. Every shrunk failure becomes an ``@example`` in
``PINNED`` (rational roots, once a library bug, are pinned in ``RATIONAL_ROOT_CASES``).
"""
import decimal
import functools
import math
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from flint import arb, fmpq, fmpq_poly
from hypothesis import assume, event, example, given, target
from hypothesis import strategies as st

from rigor_gyro.kinds.eigenfrequencies.approx import approx_roots_mpmath, approx_roots_numpy, quartic_coefficients
from rigor_gyro.core.balls import (DEFAULT_MAXPREC, certainly_gt, certainly_le, certainly_lt, certainly_positive,
                              working_precision)
from rigor_gyro.certificate import Status
from rigor_gyro.kinds.eigenfrequencies.claims import nu_quadratics
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import parse_scene

#: approx_roots_mpmath works at 50 + 20 digits with 200 extra bits inside polyroots; when it converges
#: its roots are good to ~1e-50 relative. 1e-45 leaves five digits of slack for the clustered roots
#: of the domain's edges and is still 15 orders of magnitude below the balls' width (<= 1e-30).
MPMATH_REL_TOL = "1e-45"
#: digits of the mpmath root written out for the exact comparison (more than it is accurate to)
MPMATH_DIGITS = 60
#: working precision (bits) for the comparisons: 256 bits ~ 77 digits > MPMATH_DIGITS, so parsing the
#: reference and widening the balls adds nothing near the 1e-45 scale
CHECK_PREC = 256
#: numpy.roots is backward stable: its roots are exact for coefficients perturbed by ~1e-16 relative,
#: so its forward error is ~ (condition number of the root) * 1e-16. 1e-6 accepts condition numbers up
#: to ~1e10; a root farther off than that is a float failure (a finding, counted, not a test failure).
#: (A long campaign steered by `target` towards numpy's worst case reached ~8e-9 over these ranges.)
FLOAT_REL_TOL = "1e-6"
#: the scene's default option rel_width: a proved `roots` claim promises omega_j to this relative width
ROOTS_REL_WIDTH = "1e-30"
#: the precision at which the doubled proof may escalate (twice the library default, so that 2p fits)
DOUBLE_MAXPREC = 2 * DEFAULT_MAXPREC

ALL_BUT_SLOW = ["roots", "nu_ordering", "branches", "bracket_1", "bracket_2", "bracket_3", "bracket_4"]
BRACKETS = [f"bracket_{j}" for j in range(1, 5)]

#: float failures found so far: (a, b, eps, Omega2, j) -> description. Reported by the last test.
FLOAT_FAILURES: dict[tuple, str] = {}
#: cases where numpy's roots were not four real positive numbers (skipped, counted for the summary)
FLOAT_SKIPS: set[tuple] = set()

PAPER = ("15.08", "6.154", "0.1076", "0.629")
#: pinned cases: the paper's example, the corners of the domain, and every shrunk failure
PINNED = [
    PAPER,
    ("1.0002", "1.0001", "0.000001", "10000"),    # b near 1, a near b, eps tiny, Omega2 huge
    ("1.0002", "1.0001", "10", "0.000001"),       # b near 1, a near b, eps large, Omega2 tiny
    ("1000", "1.0001", "0.000001", "0.000001"),   # numpy loses 3e-10 relative on omega_3, omega_4
    ("1000", "999.9999", "10", "10000"),          # nu ordering and bracket (7) fail
    ("3", "2", "50", "1"),                        # large eps: nu4 > nu5 (tests/test_eigfreq.py)
]
#: Regression pins (fixed bug in polyroots.isolate_polynomial): a rational root that Arb returns as an
#: exact ball (radius 0) failed the strict exact sign-change test p(lo) * p(hi) < 0 at every precision,
#: so the claim that needed it stayed inconclusive. Found by test_decidable_claims_are_decided.
RATIONAL_ROOT_CASES = [
    ("5", "3", "0.1", "4.25"),                    # Q(1/4) = 0: `roots` inconclusive
    ("4", "2", "0.5", "1.75"),                    # Q(7/4) = 0: `roots` inconclusive
    ("1.000002", "1.000001", "0.000001", "1"),    # eps = a - b makes nu = 1 a root of (4): nus not isolated
    ("1.000002", "1.000001", "1.2", "1.2"),       # (4) has the roots 4e5, 3e6: nus isolated at 64 bits (ordering
]                                                 # refuted), not from 128 bits on, where bracket_3 sends it


# ----------------------------------------------------------------------------------------- strategies

_EXACT = decimal.Context(prec=80, traps=[decimal.Inexact, decimal.Rounded])


def _decimals(min_exp: int, max_exp: int, digits: int = 4) -> st.SearchStrategy[Decimal]:
    """m * 10**e with 1 <= m < 10**digits and min_exp <= e <= max_exp: exact, positive, log-spread."""
    return st.builds(lambda m, e: Decimal(m).scaleb(e, _EXACT),
                     st.integers(1, 10 ** digits - 1), st.integers(min_exp, max_exp))


def _text(x: Decimal) -> str:
    return format(x, "f")   # plain positional notation, e.g. "0.000001", "10000"


@st.composite
def parameter_sets(draw) -> tuple[str, str, str, str]:
    """(a, b, eps, Omega2) as exact decimal strings with b > 1, a > b, eps > 0, Omega2 > 0."""
    edge = st.sampled_from
    delta = draw(st.one_of(edge([Decimal("0.0001"), Decimal("0.000001")]), _decimals(-6, -2)))  # b - 1
    gap = draw(st.one_of(edge([Decimal("0.0001"), Decimal("0.000001")]), _decimals(-6, -1)))    # a - b
    eps = draw(st.one_of(edge([Decimal("0.000001"), Decimal("10")]), _decimals(-6, -2)))
    omega2 = draw(st.one_of(edge([Decimal("0.000001"), Decimal("10000")]), _decimals(-6, 0)))
    b = _EXACT.add(1, delta)
    a = _EXACT.add(b, gap)
    return _text(a), _text(b), _text(eps), _text(omega2)


def pinned(test):
    """Apply an @example for every pinned parameter set."""
    for params in reversed(PINNED):
        test = example(params=params)(test)
    return test


# ------------------------------------------------------------------------------------------- helpers

def scene(params: tuple[str, str, str, str], claims: list[str]):
    a, b, eps, omega2 = params
    only = ", ".join(f'"{c}"' for c in claims)
    return parse_scene(f'name = "property"\nkind = "eigenfrequencies"\n'
                       f'[parameters]\na = "{a}"\nb = "{b}"\neps = "{eps}"\nOmega2 = "{omega2}"\n'
                       f'[claims]\nonly = [{only}]\n')


@functools.lru_cache(maxsize=4096)
def prove(params: tuple[str, str, str, str], claims: tuple[str, ...] = ("roots",), prec: int | None = None):
    """The certificate (cached: several properties look at the same proof)."""
    kw = {} if prec is None else {"prec": prec, "maxprec": max(DOUBLE_MAXPREC, prec)}
    return prove_scene(scene(params, list(claims)), **kw)


@functools.lru_cache(maxsize=4096)
def mpmath_roots(params: tuple[str, str, str, str]) -> tuple | None:
    """The four 50-digit mpmath roots in increasing order (exact mpf comparison, not float), or None
    when polyroots did not converge (that says nothing against the balls)."""
    try:
        roots = approx_roots_mpmath(*params, dps=50)
    except mpmath.libmp.NoConvergence:
        return None
    with mpmath.workdps(MPMATH_DIGITS + 20):
        return tuple(mpmath.nstr(x, MPMATH_DIGITS) for x in sorted(roots))


def omegas(cert) -> list[arb]:
    return [cert.quantities[f"omega_{j}"] for j in range(1, 5) if f"omega_{j}" in cert.quantities]


def widened(x: arb, rel_tol: str) -> arb:
    """x grown by rel_tol * |x| on each side (call inside working_precision)."""
    return x + arb(0, arb(rel_tol) * abs(x))


def status(cert, claim: str) -> Status:
    return cert.claim(claim).status


def _fmpq(text: str) -> fmpq:
    q = Fraction(text)
    return fmpq(q.numerator, q.denominator)


def has_rational_root(params: tuple[str, str, str, str]) -> bool:
    """True when the quartic or a nu quadratic (4) has a rational root (exact factorisation over Q)."""
    a, b, eps, omega2 = (_fmpq(x) for x in params)
    quartic = fmpq_poly(list(reversed(quartic_coefficients(a, b, eps, omega2))))   # independent expansion
    return any(f.degree() == 1 for p in (quartic, *nu_quadratics(a, b, eps)) for f, _ in p.factor()[1])


# ------------------------------------------------------------------------------------------ properties

@pinned
@given(params=parameter_sets())
def test_proved_roots_contain_the_mpmath_roots(params):
    """(a) A proved `roots` claim encloses the 50-digit mpmath roots (widened by MPMATH_REL_TOL)."""
    cert = prove(params)
    event(f"roots {status(cert, 'roots').value}")
    if status(cert, "roots") is not Status.PROVED:
        return
    ref = mpmath_roots(params)
    assume(ref is not None)
    ws = omegas(cert)
    assert len(ws) == len(ref) == 4, (ws, ref)
    with working_precision(CHECK_PREC):
        for j, (w, r) in enumerate(zip(ws, ref), start=1):
            x = arb(r)
            assert w.is_finite() and widened(w, MPMATH_REL_TOL).contains(x), f"omega_{j} = {w.str(40, radius=True)} misses mpmath {r}"


@pinned
@given(params=parameter_sets())
def test_numpy_roots_lie_in_the_balls_or_are_counted(params):
    """(b) numpy's roots lie within FLOAT_REL_TOL of the balls; otherwise the miss is recorded as a
    float failure (a finding about floats, reported by the summary test, never a failure here)."""
    cert = prove(params)
    assume(status(cert, "roots") is Status.PROVED)
    floats = [float(Fraction(x)) for x in params]
    raw = np.roots(quartic_coefficients(*floats))
    real_positive = bool(np.all(raw.imag == 0) and np.all(raw.real > 0) and np.all(np.isfinite(raw.real)))
    if not real_positive:
        FLOAT_SKIPS.add(params)
        event("numpy: not four real positive roots (skipped)")
    assume(real_positive)
    approx = approx_roots_numpy(*params)
    assert len(approx) == 4
    worst = 0.0
    for j, (w, f) in enumerate(zip(omegas(cert), approx), start=1):
        with working_precision(CHECK_PREC):
            assert w.is_finite(), (params, j, w)       # a NaN ball would "contain" numpy's value
            ok = widened(w, FLOAT_REL_TOL).contains(arb(f))   # arb(float) is exact
            rel = abs(arb(f) - w) / abs(w)
        worst = max(worst, float(rel.mid()))   # a float for hypothesis' search only; the ball decided `ok`
        if not ok:
            FLOAT_FAILURES[params + (j,)] = (f"numpy omega_{j} = {f!r}, certified {w.str(20)}, "
                                             f"relative error ~ {rel.str(3)}")
            event("numpy: float failure")
    target(math.log10(max(worst, 1e-300)), label="log10 of numpy's worst relative error")   # hunt for misses


@pinned
@given(params=parameter_sets())
def test_twice_the_precision_never_contradicts(params):
    """(c) Proving again at twice the final precision: no claim flips between proved and refuted, a
    decided claim stays decided, the roots stay proved, and
    every quantity's two balls overlap (in particular each omega_j)."""
    claims = tuple(ALL_BUT_SLOW)
    first = prove(params, claims)
    p = first.precision_bits
    second = prove(params, claims, prec=2 * p)
    for c1 in first.claims:
        s2 = status(second, c1.id)
        assert {c1.status, s2} != {Status.PROVED, Status.REFUTED}, (c1.id, c1.reason, second.claim(c1.id).reason)
        if c1.status is not Status.INCONCLUSIVE:   # more bits never lose a verdict
            assert s2 is c1.status, (c1.id, c1.reason, second.claim(c1.id).reason[:300])
    if status(first, "roots") is Status.PROVED:
        assert status(second, "roots") is Status.PROVED
        assert len(omegas(first)) == len(omegas(second)) == 4
    for name, x in first.quantities.items():
        if name in second.quantities:
            y = second.quantities[name]
            # the roots and the nu's are finite whenever stored (a NaN ball overlaps every ball); a bracket's
            # ends may be NaN where a radicand's ball straddles 0, the float formulas' errors unbounded
            if name.startswith(("omega_", "nu_")):
                assert x.is_finite() and y.is_finite(), (name, x, y)
            assert x.overlaps(y), (name, x, y)


@pinned
@given(params=parameter_sets())
def test_proved_roots_are_four_increasing_positive_and_tight(params):
    """(d) A proved `roots` claim means exactly four omega quantities, certainly positive, certainly
    strictly increasing, each to the promised relative width."""
    cert = prove(params)
    if status(cert, "roots") is not Status.PROVED:
        # not proved: then it says why (a refutation names its witness, inconclusive says what to try)
        assert cert.claim("roots").reason
        return
    names = sorted(k for k in cert.quantities if k.startswith("omega_"))
    assert names == ["omega_1", "omega_2", "omega_3", "omega_4"]
    ws = omegas(cert)
    assert all(certainly_positive(w) for w in ws)
    assert all(certainly_lt(x, y) for x, y in zip(ws, ws[1:]))
    with working_precision(CHECK_PREC):
        for w in ws:
            assert certainly_le(2 * w.rad(), arb(ROOTS_REL_WIDTH) * w.abs_lower()), w.str(radius=True)


@pinned
@given(params=parameter_sets())
def test_nu_ordering_proved_implies_branches_proved(params):
    """(e) Under the paper's ordering 0 < nu1 < ... < nu6, F = Omega^2 has exactly one root on each of
    (0, nu1), (nu2, nu3), (nu4, nu5), (nu6, oo) (sign and limit analysis of (2)): a proved ordering
    must come with proved branches."""
    cert = prove(params, ("roots", "nu_ordering", "branches"))
    event(f"nu_ordering {status(cert, 'nu_ordering').value}")
    if status(cert, "nu_ordering") is Status.PROVED:
        assert status(cert, "roots") is Status.PROVED, cert.claim("roots").reason
        assert status(cert, "branches") is Status.PROVED, cert.claim("branches").reason
    if status(cert, "branches") is Status.REFUTED:
        assert "not in" in cert.claim("branches").reason


@pinned
@given(params=parameter_sets())
def test_bracket_verdicts_agree_with_mpmath(params):
    """(f) A proved bracket_j has enclosures lo <= omega_j <= hi and contains the mpmath root; a
    refuted one names its violation, and the mpmath root certainly lies outside it (or the bracket has
    no real value)."""
    cert = prove(params, tuple(["roots"] + BRACKETS))
    assume(status(cert, "roots") is Status.PROVED)
    ref = mpmath_roots(params)
    ws = omegas(cert)
    for j in range(1, 5):
        claim = cert.claim(f"bracket_{j}")
        event(f"bracket_{j} {claim.status.value}")
        lo, hi = cert.quantities.get(f"bracket_{j}_lo"), cert.quantities.get(f"bracket_{j}_hi")
        with working_precision(CHECK_PREC):
            r = widened(arb(ref[j - 1]), MPMATH_REL_TOL) if ref is not None else None
            if claim.status is Status.PROVED:
                assert lo is not None and hi is not None
                assert certainly_le(lo, ws[j - 1]) and certainly_le(ws[j - 1], hi), (j, lo, ws[j - 1], hi)
                if r is not None:
                    assert not certainly_gt(lo, r) and not certainly_gt(r, hi), (j, lo, ref[j - 1], hi)
            elif claim.status is Status.REFUTED:
                if "no real value" in claim.reason:
                    assert lo is None and hi is None and "negative" in claim.reason
                    continue
                assert f"omega_{j}" in claim.reason and "not in" in claim.reason, claim.reason
                assert certainly_gt(lo, ws[j - 1]) or certainly_gt(ws[j - 1], hi)
                if r is not None:
                    assert certainly_gt(lo, r) or certainly_gt(r, hi), (j, lo, ref[j - 1], hi)


DECIDABLE = ("roots", "nu_ordering", "branches")


def assert_decided(cert):
    """roots, nu_ordering and branches are decided, and all six nus are enclosed."""
    for c in DECIDABLE:
        assert status(cert, c) is not Status.INCONCLUSIVE, (c, cert.claim(c).reason[:300])
    assert all(f"nu_{k}" in cert.quantities for k in range(1, 7)), sorted(cert.quantities)


@pinned
@given(params=parameter_sets())
def test_decidable_claims_are_decided(params):
    """(g) Within the domain both nu quadratics (4) have positive discriminant (AM-GM: s^2 > 4 c2 eps),
    so the six nus are simple, real and positive; Q has no root <= 0 (Q(-l) = l P1(l) + W P2(l) > 0)
    and, when squarefree, simple roots. Distinct algebraic numbers are separated by balls at some
    precision, so `roots`, `nu_ordering` and `branches` must be decided (never inconclusive) by the
    default maxprec, rational roots included (RATIONAL_ROOT_CASES)."""
    event(f"rational root: {has_rational_root(params)}")
    assert_decided(prove(params, DECIDABLE))


@pytest.mark.parametrize("params", RATIONAL_ROOT_CASES)
def test_rational_root_cases_do_have_rational_roots(params):
    """The pins below stay meaningful: each case has an exact rational root (and is in the domain)."""
    assert has_rational_root(params)
    assert status(prove(params), "roots") is not Status.REFUTED


@pytest.mark.parametrize("params", RATIONAL_ROOT_CASES)
def test_rational_roots_are_isolated(params):
    """A rational root (an exact point ball) is verified like any other: every decidable claim decided."""
    assert_decided(prove(params, tuple(ALL_BUT_SLOW)))
