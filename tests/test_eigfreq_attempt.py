"""The eigenfrequency ``attempt``'s decisions in the branches valid parameters do not reach.

For every valid scene the quartic Q has four simple positive roots and the quadratics (4) two simple
real roots each (the 10,000-case campaign never found otherwise), so the roots claim's refutations, its
inconclusive outcomes and the unisolated-nu path ran in no test: mutmut found each of them replaceable
by a crash or a wrong status (``st, why = None``; ``r14.verified or ...``). Here the model's polynomials
are replaced (monkeypatch) by ones with a double root, complex roots, a negative or a zero root, and the
isolation of the quadratics by an unverified one, and each outcome is pinned: status, counterexample,
and what is stored.
"""
from fractions import Fraction

import pytest
from flint import arb, fmpq_poly

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.outcome import Status
from rigor_gyro.core.polyroots import PolynomialRoots, isolate_polynomial
from rigor_gyro.kinds.eigenfrequencies import claims as ec
from rigor_gyro.scene import load_scene

from .forgery import poly as _poly

ALL = list(ec.CLAIMS)


@pytest.fixture(scope="module")
def model():
    return ec.validate(load_scene("rudenko1976"))


def _run(model, monkeypatch, quartic=None, wanted=ALL, prec=128):
    if quartic is not None:
        monkeypatch.setattr(ec, "characteristic_quartic", lambda *a: quartic)
    with working_precision(prec):
        return ec.attempt(model, list(wanted), prec)


def _claim(att, cid):
    return next(c for c in att.claims if c.id == cid)


def test_the_scene_itself_proves_the_roots_claim(model, monkeypatch):
    att = _run(model, monkeypatch)
    assert _claim(att, "roots").status is Status.PROVED and _claim(att, "roots").counterexample is None
    assert [f"omega_{j}" in att.quantities for j in range(1, 5)] == [True] * 4


def test_a_double_root_refutes_the_roots_claim_with_the_exact_gcd(model, monkeypatch):
    Q = _poly(1, 1, 2, 3)
    att = _run(model, monkeypatch, Q)
    r = _claim(att, "roots")
    assert r.status is Status.REFUTED and "multiple root" in r.reason and "exactly" in r.reason
    # the quartic's exact coefficients (constant first) and gcd(Q, Q') = x - 1, the double root
    assert r.counterexample == {"quartic": ["6", "-17", "17", "-7", "1"], "gcd_with_derivative": str(fmpq_poly([-1, 1]))}
    assert not any(k.startswith("omega_") for k in att.quantities)          # nothing isolated is stored
    # the claims resting on the roots are not proved, and nothing crashes
    for cid in ("branches", "bracket_1", "bracket_4", "approximations"):
        assert _claim(att, cid).status is not Status.PROVED, cid


def test_complex_roots_refute_the_roots_claim_with_their_enclosures(model, monkeypatch):
    Q = _poly(1, 2, extra=fmpq_poly([5, -2, 1]))         # (x - 1)(x - 2)(x^2 - 2x + 5): 1 +- 2i
    att = _run(model, monkeypatch, Q)
    r = _claim(att, "roots")
    assert r.status is Status.REFUTED and "2 roots are certainly non-real" in r.reason
    rows = r.counterexample["nonreal_roots"]
    assert len(rows) == 2
    for row in rows:
        re_lo, re_hi = (Fraction(x) for x in row["re"])
        im_lo, im_hi = (Fraction(x) for x in row["im"])
        assert re_lo <= 1 <= re_hi and re_hi - re_lo < Fraction(1, 10 ** 20)
        assert (im_lo <= 2 <= im_hi or im_lo <= -2 <= im_hi) and im_hi - im_lo < Fraction(1, 10 ** 20)
    assert sorted(Fraction(row["im"][0]) > 0 for row in rows) == [False, True]
    assert not any(k.startswith("omega_") for k in att.quantities)
    assert _claim(att, "branches").status is Status.INCONCLUSIVE


@pytest.mark.parametrize("roots, n_bad", [((-1, 2, 3, 4), 1), ((-2, -1, 3, 4), 2), ((0, 2, 3, 4), 1)])
def test_a_root_at_or_below_zero_refutes_the_roots_claim(model, monkeypatch, roots, n_bad):
    att = _run(model, monkeypatch, _poly(*roots))
    r = _claim(att, "roots")
    assert r.status is Status.REFUTED and "certainly <= 0" in r.reason
    bad = r.counterexample["nonpositive_roots"]
    assert len(bad) == n_bad
    for (lo, hi), x in zip(bad, sorted(x for x in roots if x <= 0)):
        assert Fraction(lo) <= x <= Fraction(hi)
    # the real roots are stored (they were isolated and verified), but not claimed to be omegas
    assert "omega_1" in att.quantities and _claim(att, "branches").status is Status.INCONCLUSIVE


def test_only_the_roots_certainly_at_or_below_zero_are_the_counterexample(model, monkeypatch):
    """Roots -1, 2, 3, 4 with the root 2 blurred to straddle 0: refuted by -1 alone (the blurred root
    is certainly <= 1 but not <= 0, and is no counterexample)."""
    real_iso = ec.isolate_polynomial

    def blurred(p, rel_tol=None):
        out = real_iso(p, rel_tol=rel_tol)
        if p.degree() == 4:
            out.real[1] = arb(0, 1e-10) + arb("1e-12")
        return out
    monkeypatch.setattr(ec, "isolate_polynomial", blurred)
    att = _run(model, monkeypatch, _poly(-1, 2, 3, 4))
    r = _claim(att, "roots")
    assert r.status is Status.REFUTED
    (lo, hi), = r.counterexample["nonpositive_roots"]
    assert Fraction(lo) <= -1 <= Fraction(hi)


def test_a_root_of_undecided_sign_leaves_the_roots_claim_open(model, monkeypatch):
    """A root within the isolation's width of 0 (here exactly 0, with Arb's ball kept wide): neither
    certainly <= 0 nor certainly > 0."""
    real_iso = ec.isolate_polynomial

    def blurred(p, rel_tol=None):
        out = real_iso(p, rel_tol=rel_tol)
        if p.degree() == 4:
            out.real[0] = arb(0, 1e-10) + arb("1e-12")            # straddles 0
        return out
    monkeypatch.setattr(ec, "isolate_polynomial", blurred)
    att = _run(model, monkeypatch)
    r = _claim(att, "roots")
    assert r.status is Status.INCONCLUSIVE and "undecided" in r.reason and r.counterexample is None
    assert _claim(att, "branches").status is Status.INCONCLUSIVE


def test_roots_not_isolated_to_the_width_leave_the_claim_open(model, monkeypatch):
    real_iso = ec.isolate_polynomial

    def short(p, rel_tol=None):
        out = real_iso(p, rel_tol=rel_tol)
        if p.degree() == 4:
            out.width_met = False
        return out
    monkeypatch.setattr(ec, "isolate_polynomial", short)
    att = _run(model, monkeypatch)
    r = _claim(att, "roots")
    assert r.status is Status.INCONCLUSIVE and "relative width" in r.reason and "--maxprec" in r.reason
    assert att.widths_met is False


def test_an_unverified_isolation_is_inconclusive_and_stores_no_omega(model, monkeypatch):
    real_iso = ec.isolate_polynomial

    def unverified(p, rel_tol=None):
        out = real_iso(p, rel_tol=rel_tol)
        if p.degree() == 4:
            out.verified, out.reason = False, "planted: not verified"
        return out
    monkeypatch.setattr(ec, "isolate_polynomial", unverified)
    att = _run(model, monkeypatch)
    r = _claim(att, "roots")
    assert r.status is Status.INCONCLUSIVE and r.reason == "planted: not verified"
    assert not any(k.startswith("omega_") for k in att.quantities)
    for cid in ("branches", "bracket_1", "bracket_2", "bracket_3", "bracket_4", "approximations"):
        assert _claim(att, cid).status is not Status.PROVED, cid


@pytest.mark.parametrize("which", [2, 4])
def test_nus_from_an_unverified_isolation_decide_nothing(model, monkeypatch, which):
    """A quadratic (4) whose isolation is not verified gives no nus, even with two real balls in hand:
    the ordering, the branches and the bounds (5) stay open (a verdict on unverified balls is unsound)."""
    real_iso = ec.isolate_polynomial
    calls = []

    def flaky(p, rel_tol=None):
        out = real_iso(p, rel_tol=rel_tol)
        if p.degree() == 2:
            calls.append(p)
            if len(calls) == which // 2:
                out.verified, out.reason = False, "planted: quadratic not verified"
                assert len(out.real) == 2
        return out
    monkeypatch.setattr(ec, "isolate_polynomial", flaky)
    att = _run(model, monkeypatch)
    o = _claim(att, "nu_ordering")
    assert o.status is Status.INCONCLUSIVE and "planted: quadratic not verified" in o.reason
    assert _claim(att, "branches").status is Status.INCONCLUSIVE
    assert _claim(att, "nu_bounds").status is not Status.PROVED
    missing = {2: ("nu_1", "nu_4"), 4: ("nu_2", "nu_6")}[which]
    assert not any(m in att.quantities for m in missing)
    assert "nu_3" in att.quantities and "nu_5" in att.quantities       # exact rationals, always


def test_the_nu_block_runs_for_the_claims_that_need_it_only(model, monkeypatch):
    """nu_ordering is evaluated when a bracket, the branches or the ordering is asked for; asked alone,
    each of those gets its own verdict, and the brackets do not depend on the ordering's outcome."""
    for wanted in (["bracket_2"], ["branches"], ["nu_ordering"], ["roots", "bracket_4"]):
        att = _run(model, monkeypatch, wanted=wanted)
        assert [c.id for c in att.claims] == wanted
        assert all(c.status is Status.PROVED for c in att.claims), wanted


def test_an_empty_branch_refutes_the_branches_asked_alone():
    """nu2 = nu3 exactly (a rational eps): the branch (nu2, nu3) of omega_2 is empty, decided in rational
    arithmetic by the nu block, which must run when the branches are asked for alone."""
    import dataclasses
    a, b = Fraction("15.08"), Fraction("6.154")
    base = load_scene("rudenko1976")
    scene = dataclasses.replace(base, parameters=dict(base.parameters, eps=str((a - b) * (b - 1) / (a * b - 2 * a + 1))),
                                claims_only=["branches"])
    m = ec.validate(scene)
    with working_precision(128):
        att = ec.attempt(m, ["branches"], 128)
    (c,) = att.claims
    assert c.status is Status.REFUTED and any(o["root"] == "omega_2" for o in c.counterexample["outside"])


def test_isolate_polynomial_is_what_the_claims_see():
    """The planted polynomials above are isolated by the real code: a sanity check of the plants."""
    assert not isolate_polynomial(_poly(1, 1, 2, 3)).squarefree
    iso = isolate_polynomial(_poly(1, 2, extra=fmpq_poly([5, -2, 1])))
    assert iso.verified and len(iso.nonreal) == 2 and len(iso.real) == 2
    assert isinstance(iso, PolynomialRoots)
