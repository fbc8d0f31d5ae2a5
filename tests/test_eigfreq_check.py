"""The eigenfrequency checker item by item: its exact helpers (Sturm count, exact root refinement) and,
for each claim, the forgery that only that claim's re-decision can catch.

The checker's report fails as a whole for many reasons at once (an unverified quantity, a claim that
rests on it). These tests name the item that must fail, so a weakened gate is seen even where another
gate would also have rejected the certificate (mutmut found 276 such survivors in the checker).
"""
import copy
import functools
from fractions import Fraction

import pytest
from flint import arb, fmpq, fmpq_poly

from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.eigenfrequencies import check as eig_check
from rigor_gyro.kinds.eigenfrequencies.check import _refine, _sign, sturm_positive_roots

from .forgery import certificate, claim as _claim, flipped, items as _items, poly as _poly, refix as _refix

A, B = Fraction("15.08"), Fraction("6.154")
#: the scenes: rudenko1976 and variants where claims are refuted or undefined
SCENES = {
    "rudenko1976": {},
    "brackets_refuted": dict(eps="1.5", Omega2="5"),
    "order_refuted": dict(a="3", b="2", eps="50", Omega2="1"),
    "nu2_equals_nu3": dict(eps=str((A - B) * (B - 1) / (A * B - 2 * A + 1))),
    "r2_denominator_zero": dict(eps=str(B * B * (A - B) / (A * (B - 1)))),      # brackets (9), (10) undefined
}


_cert = functools.partial(certificate, "rudenko1976")


@pytest.fixture(scope="module", params=list(SCENES))
def cert(request):
    return _cert(**SCENES[request.param])


@pytest.fixture(scope="module")
def rudenko():
    return _cert()


def _iv(data, name) -> tuple[Fraction, Fraction]:
    q = data["quantities"][name]
    return Fraction(q["lo"]), Fraction(q["hi"])


def _set(data, name, lo, hi):
    data["quantities"][name]["lo"], data["quantities"][name]["hi"] = str(lo), str(hi)


# ---------------------------------------------------------------------------- the exact helpers

def test_sign_is_exact():
    assert [_sign(fmpq(x)) for x in (-3, 0, 2)] == [-1, 0, 1]
    assert _sign(fmpq(1, 10 ** 40)) == 1 and _sign(fmpq(-1, 10 ** 40)) == -1


@pytest.mark.parametrize("p, count", [
    (_poly(1, 2, 3, 4), 4),                                   # the quartic's case
    (_poly(Fraction(1, 3), 5, -2), 2),                        # a negative root is not counted
    (_poly(7), 1),
    (_poly(-7), 0),
    (_poly(5, extra=fmpq_poly([1, 0, 1])), 1),                # x^2 + 1: no real roots
    (fmpq_poly([5, -2, 1]), 0),                               # x^2 - 2x + 5: none
    (_poly(1, 1, 3), 2),                                      # a double root: distinct roots counted
    (_poly(2, 2, 2, 9, -1), 2),
    (fmpq_poly([-2, 0, 1]), 1),                               # the sequence ends on a constant 1... times 2
    (fmpq_poly([1, -3, 1]), 2),                               # x^2 - 3x + 1: remainder exactly 5/4
    (fmpq_poly([-1, 1, 1]) * 4, 1),
])
def test_sturm_counts_the_distinct_positive_roots_exactly(p, count):
    assert sturm_positive_roots(p) == count


def test_sturm_counts_whatever_constant_ends_the_sequence():
    """The last remainder of a squarefree p is a nonzero constant, of either sign and any value (1 too)."""
    import mpmath
    for coeffs in ([-6, 11, -6, 1], [6, -5, 1], [-1, 0, 0, 1], [2, -3, 0, 1], [-3, 7, -5, 1], [1, -3, 1],
                   [fmpq(-1, 4), 0, 1], [3, -4, 1], [-12, 19, -8, 1]):
        p = fmpq_poly(coeffs)
        roots = mpmath.polyroots([float(c) for c in reversed(coeffs)], maxsteps=200, extraprec=100)
        real = {round(float(mpmath.re(r)), 9) for r in roots if abs(mpmath.im(r)) < 1e-12 and mpmath.re(r) > 0}
        assert sturm_positive_roots(p) == len(real), coeffs


def test_refine_a_point_interval_is_a_root_only_if_it_is_one():
    p = _poly(3, Fraction(1, 2))
    assert _refine(p, Fraction(3), Fraction(3), 128) == arb(3)
    assert _refine(p, Fraction(1, 2), Fraction(1, 2), 128) == arb(fmpq(1, 2))
    assert _refine(p, Fraction(2), Fraction(2), 128) is None
    assert _refine(p, Fraction(0), Fraction(0), 128) is None


def test_refine_needs_a_strict_sign_change():
    p = _poly(1, 3)                     # (x - 1)(x - 3): p(0) = 3, p(2) = -1, p(4) = 3
    assert _refine(p, Fraction(1), Fraction(2), 128) is None          # an end is the root: no strict change
    assert _refine(p, Fraction(0), Fraction(1), 128) is None
    assert _refine(p, Fraction(0), Fraction(4), 128) is None          # two roots: no sign change
    assert _refine(p, Fraction(4), Fraction(5), 128) is None
    r = _refine(p, Fraction(2), Fraction(4), 128)
    assert r is not None and r.is_finite() and r.contains(arb(3))
    q = fmpq_poly([1, -1])              # 1 - x: p(lo) = 1 at lo = 0
    r = _refine(q, Fraction(0), Fraction(2), 128)
    assert r.is_finite() and r.contains(arb(1))
    s = fmpq_poly([-1, 1])              # x - 1: p(hi) = 1 at hi = 2
    r = _refine(s, Fraction(0), Fraction(2), 128)
    assert r.is_finite() and r.contains(arb(1))


@pytest.mark.parametrize("bits", [64, 128, 300])
def test_refine_encloses_the_root_of_its_bracket_to_the_checkers_precision(bits):
    """Interval Newton on [lo, hi] (never on a wider piece holding another root), to relative width
    about 2^-bits: not looser than 2^(9 - bits), nor stopped at its start."""
    p = _poly(1, extra=fmpq_poly([-2, 0, 1]))     # (x - 1)(x^2 - 2): roots 1, +-sqrt 2
    with working_precision(bits):
        r = _refine(p, Fraction(5, 4), Fraction(3, 2), bits)
        assert r.is_finite() and (r.contains(arb(2).sqrt().mid()) or r.overlaps(arb(2).sqrt()))
        assert (r * r - 2).contains(0)
        rel = r.rad() / abs(r.mid())
        assert rel <= arb(2) ** (9 - bits), (bits, rel)
        assert r.lower() > 1.4 and r.upper() < 1.42
        # the bracket is used as given: the other roots (1 below it, -sqrt 2) never enter
        r1 = _refine(p, Fraction(9, 10), Fraction(11, 10), bits)
        assert r1.is_finite() and r1.contains(arb(1)) and r1.rad() / abs(r1.mid()) <= arb(2) ** (9 - bits)


def test_refine_bisects_exactly_where_newton_cannot_prove_uniqueness():
    """p' vanishes inside the bracket: the exact bisection runs (200 halvings; an exact midpoint root
    is returned as a point) and stays on the side of the sign change."""
    p = _poly(0, 1, 3)                 # x (x - 1)(x - 3): p' = 0 near 0.45 and 2.2
    with working_precision(256):
        _bisection_cases(p)


def _bisection_cases(p):
    r = _refine(p, Fraction(1, 4), Fraction(7, 4), 128)    # midpoint 1 is the root, exactly
    assert r == arb(1)
    r = _refine(p, Fraction(1, 5), Fraction(13, 10), 128)  # p(1/5) > 0 > p(13/10): the root 1, not a midpoint
    assert r.is_finite() and r.contains(arb(1)) and r.rad() < arb(2) ** -150
    r = _refine(p, Fraction(2, 1), Fraction(17, 5), 128)   # p' = 0 at 2.2: the root 3
    assert r.is_finite() and r.contains(arb(3)) and r.rad() < arb(2) ** -150


# ------------------------------------------------------------------- the checker, item by item

def test_every_claim_of_a_genuine_certificate_confirms_at_its_own_item(cert):
    items = _items(copy.deepcopy(cert))
    assert all(items.values()), {k: v for k, v in items.items() if not v}
    assert {c["id"] for c in cert["claims"]} | {"roots", "quantities"} <= set(items)


def test_each_claim_with_its_status_flipped_fails_at_its_own_item(cert):
    """proved -> refuted (no counterexample), refuted -> proved: the claim's item fails and no other."""
    for cid, status, items in flipped(cert):
        assert items.get(cid) is False, (cid, status)
        # the schema also fails when a refuted claim has no counterexample (certificate-2.schema.json requires one)
        others = {k: v for k, v in items.items() if k != cid and not v
                  and not (k == "schema" and status == "proved")}
        assert not others, (cid, others)


def test_an_inconclusive_claim_claims_nothing_and_the_next_ones_are_still_checked(rudenko):
    for i in range(len(rudenko["claims"]) - 1):
        bad = copy.deepcopy(rudenko)
        bad["claims"][i]["status"] = "inconclusive"
        bad["claims"][i + 1]["status"] = "refuted"
        items = _items(bad)
        assert items[bad["claims"][i]["id"]] is True
        assert items[bad["claims"][i + 1]["id"]] is False


def test_an_unknown_claim_is_never_confirmed(rudenko):
    bad = copy.deepcopy(rudenko)
    bad["claims"].append(dict(bad["claims"][0], id="made_up"))
    assert _items(bad)["made_up"] is False


def test_omega_intervals_that_overlap_or_touch_are_rejected(rudenko):
    lo1, hi1 = _iv(rudenko, "omega_1")
    lo2, hi2 = _iv(rudenko, "omega_2")
    for name, new in (("overlap", (lo1, hi1 + (hi1 - lo1))), ("touching", (hi1, hi2))):
        bad = copy.deepcopy(rudenko)
        _set(bad, "omega_2", *new)
        items = _items(bad)
        assert items.get("omega") is False, name
        assert items["nu_ordering"] is True and items["roots"] is False and items["bracket_1"] is False, name


def test_an_omega_interval_without_its_root_fails_at_its_name(rudenko):
    lo, hi = _iv(rudenko, "omega_3")
    bad = copy.deepcopy(rudenko)
    _set(bad, "omega_3", hi + (hi - lo), hi + 2 * (hi - lo))
    items = _items(bad)
    assert items.get("omega_3") is False
    assert all(items[c] is False for c in ("roots", "branches", "bracket_3", "approximations"))


def test_omega_wider_than_rel_width_is_not_proved_to_it(rudenko):
    """The roots claim says 'to the requested relative width': a stored interval of relative width
    exactly rel_width passes, one of twice that does not (the width is hi - lo against rel_width |lo|)."""
    rel = Fraction(rudenko["scene"]["options"].get("rel_width", "1e-30"))
    for j in range(1, 5):
        lo, hi = _iv(rudenko, f"omega_{j}")
        for factor, ok in ((1, True), (2, False)):
            bad = copy.deepcopy(rudenko)
            _set(bad, f"omega_{j}", lo, lo + factor * rel * abs(lo))
            assert _items(bad)["roots"] is ok, (j, factor)


@pytest.mark.parametrize("tamper", ["nu4_over_nu1", "nu4_touching_nu1", "nu6_over_nu2", "nu2_reaching_nu6", "nu3_moved",
                                    "nu1_moved"])
def test_nu_intervals_that_hold_no_nu_or_the_wrong_one_are_rejected(rudenko, tamper):
    bad = copy.deepcopy(rudenko)
    lo1, hi1 = _iv(rudenko, "nu_1")
    lo2, hi2 = _iv(rudenko, "nu_2")
    lo4, hi4 = _iv(rudenko, "nu_4")
    lo3, hi3 = _iv(rudenko, "nu_3")
    item = "nu"
    if tamper == "nu4_over_nu1":
        _set(bad, "nu_4", lo1, hi1 + (hi1 - lo1))
    elif tamper == "nu4_touching_nu1":
        _set(bad, "nu_1", lo1, (hi1 + lo4) / 2)
        _set(bad, "nu_4", (hi1 + lo4) / 2, hi4)
    elif tamper == "nu6_over_nu2":
        _set(bad, "nu_6", lo2, hi2 + (hi2 - lo2))
    elif tamper == "nu2_reaching_nu6":          # each still one sign change of its quadratic, but overlapping
        lo6, hi6 = _iv(rudenko, "nu_6")
        _set(bad, "nu_2", lo2, (lo6 + Fraction(str(rudenko["quantities"]["nu_6"]["mid"]))) / 2)
    elif tamper == "nu3_moved":
        item = "nu_3"
        _set(bad, "nu_3", hi3 + (hi3 - lo3), hi3 + 2 * (hi3 - lo3))
    else:
        item = "nu_1"
        _set(bad, "nu_1", hi1 + (hi1 - lo1), hi1 + 2 * (hi1 - lo1))
    items = _items(bad)
    assert items.get(item) is False, (tamper, items)
    assert items["nu_ordering"] is False and items["roots"] is True


def test_a_rational_nu_is_checked_against_its_exact_value():
    data = _cert(**SCENES["order_refuted"])          # nu3 = 1/(b-1) = 1, nu5 = b/(b-1) = 2 exactly
    assert _items(copy.deepcopy(data))["nu_ordering"] is True
    bad = copy.deepcopy(data)
    _set(bad, "nu_5", Fraction(2) + Fraction(1, 10 ** 40), Fraction(3))
    assert _items(bad).get("nu_5") is False


@pytest.mark.parametrize("drop, item", [("nu_1_lower_bound", "nu_bounds"), ("nu_6_upper_bound", "nu_bounds"),
                                        ("bracket_1_lo", "bracket_1"), ("bracket_4_hi", "bracket_4"),
                                        ("approx_omega_1", "approximations"),
                                        ("approx_rel_error_4", "approximations")])
def test_a_proved_claim_without_a_quantity_it_names_fails_at_its_item(rudenko, drop, item):
    bad = copy.deepcopy(rudenko)
    del bad["quantities"][drop]
    assert _items(bad)[item] is False


def test_nu_bounds_are_decided_on_the_checkers_own_bounds(rudenko, monkeypatch):
    """The checker's nu_bounds verdict is its own: bounds (5) that exclude nu (here forced) fail it."""
    real = eig_check.nu_bounds
    for k in (1, 2, 4, 6):
        for side in (0, 1):
            def moved(P, k=k, side=side):
                out = dict(real(P))
                lo, hi = out[k]
                out[k] = (hi + 1, hi + 2) if side == 0 else (lo - 2, lo - 1)
                return out
            monkeypatch.setattr(eig_check, "nu_bounds", moved)
            bad = copy.deepcopy(rudenko)          # the stored bounds stay (they fail at their own names):
            _claim(bad, "nu_bounds")["status"] = "proved"     # the claim's item is its re-decision alone
            items = _items(bad)
            assert items["nu_bounds"] is False, (k, side)
            _claim(bad, "nu_bounds")["status"] = "refuted"
            assert _items(bad)["nu_bounds"] is True, (k, side)


# ------------------------------------------------------------------ stored counterexamples

@pytest.fixture(scope="module")
def order_refuted():
    return _cert(**SCENES["order_refuted"])


@pytest.fixture(scope="module")
def nu_equal():
    return _cert(**SCENES["nu2_equals_nu3"])


@pytest.mark.parametrize("edit", ["no_violations_key", "empty", "bogus_name", "nu7", "not_adjacent",
                                  "left_value_wrong", "right_value_wrong", "reversed"])
def test_a_forged_nu_ordering_violation_is_rejected(order_refuted, nu_equal, edit):
    for data in (order_refuted, nu_equal):
        bad = copy.deepcopy(data)
        ce = _claim(bad, "nu_ordering")["counterexample"]
        v = ce["violations"][0]
        if edit == "no_violations_key":
            ce.pop("violations")
        elif edit == "empty":
            ce["violations"] = []
        elif edit == "bogus_name":
            v["left"] = "nu0"
        elif edit == "nu7":
            v["right"] = "nu7"
        elif edit == "not_adjacent":
            v["right"] = "nu" + str(int(v["right"][2]) + 1)
            v.pop("right_value")
        elif edit == "left_value_wrong":
            v["left_value"] = ["100", "101"]
        elif edit == "right_value_wrong":
            v["right_value"] = ["-3", "-2"]
        else:
            v["left"], v["right"] = v["right"], v["left"]
            v["left_value"], v["right_value"] = v["right_value"], v["left_value"]
        assert _items(bad)["nu_ordering"] is False, (edit, data["scene"]["parameters"])


def test_an_exact_equality_is_only_accepted_where_it_holds(nu_equal, order_refuted):
    """'exactly_equal' is re-decided in rational arithmetic: on a violation by inequality it is false."""
    v = _claim(nu_equal, "nu_ordering")["counterexample"]["violations"]
    assert any("exactly_equal" in x for x in v)
    bad = copy.deepcopy(order_refuted)
    for x in _claim(bad, "nu_ordering")["counterexample"]["violations"]:
        x["exactly_equal"] = "forged"
    assert _items(bad)["nu_ordering"] is False


@pytest.mark.parametrize("edit", ["inside_root", "omega_0", "omega_5", "value_elsewhere", "no_outside_key"])
def test_a_forged_branch_counterexample_is_rejected(edit):
    data = _cert(**SCENES["brackets_refuted"])
    bad = copy.deepcopy(data)
    ce = _claim(bad, "branches")["counterexample"]
    items = ce["outside"]
    named = {o["root"] for o in items}
    if edit == "inside_root":
        j = next(j for j in range(1, 5) if f"omega_{j}" not in named)
        q = data["quantities"][f"omega_{j}"]
        items.append({"root": f"omega_{j}", "value": [q["lo"], q["hi"]]})
    elif edit in ("omega_0", "omega_5"):
        items[0]["root"] = edit
    elif edit == "value_elsewhere":
        items[0]["value"] = ["1000", "1001"]
    else:
        ce.pop("outside")
    assert _items(bad)["branches"] is False, edit


def test_a_stored_quantity_off_its_value_fails_at_its_own_name_with_its_bounds(rudenko):
    """Each closed-form quantity is reported under its own name, not ok, quoting the stored bounds (and
    left unverified, so that the report fails as a whole too)."""
    for name in ("bracket_1_lo", "bracket_3_hi", "bracket_2_slack", "nu_2_upper_bound", "approx_omega_3",
                 "approx_rel_error_4", "freq_hz_1"):
        if name not in rudenko["quantities"]:
            continue
        bad = copy.deepcopy(rudenko)
        lo, hi = _iv(bad, name)
        w = max(hi - lo, abs(hi) / 10 ** 12)
        _set(bad, name, hi + w, hi + 2 * w)
        report = check_certificate(_refix(bad))
        rows = [r for r in report.results if r.item == name]
        assert len(rows) == 1 and rows[0].ok is False, (name, rows)
        assert f"stored [{hi + w}, {hi + 2 * w}] does not contain" in rows[0].message, rows[0].message
        assert not next(r for r in report.results if r.item == "quantities").ok


NUS = {1: arb(1), 2: arb(2), 3: arb(3), 4: arb(4), 5: arb(5), 6: arb(6)}


@pytest.mark.parametrize("omegas, inside, outside", [
    ((0.5, 2.5, 4.5, 7), [True] * 4, [False] * 4),                         # each in its own branch
    ((1.5, 2.5, 4.5, 7), [False, True, True, True], [True, False, False, False]),     # omega_1 in (nu1, nu2)
    ((0.5, 3.5, 4.5, 7), [True, False, True, True], [False, True, False, False]),     # omega_2 in (nu3, nu4)
    ((0.5, 1.5, 4.5, 7), [True, False, True, True], [False, True, False, False]),     # omega_2 below nu2
    ((0.5, 2.5, 5.5, 7), [True, True, False, True], [False, False, True, False]),     # omega_3 in (nu5, nu6)
    ((0.5, 2.5, 3.5, 7), [True, True, False, True], [False, False, True, False]),     # omega_3 below nu4
    ((0.5, 2.5, 4.5, 5.5), [True, True, True, False], [False, False, False, True]),   # omega_4 below nu6
    ((1, 2, 4, 6), [False] * 4, [True] * 4),                              # on the ends: outside (open branches)
    ((-1, 2.5, 4.5, 7), [False, True, True, True], [True, False, False, False]),      # omega_1 below 0
])
def test_branch_sides_decide_each_end_of_each_branch(omegas, inside, outside):
    from rigor_gyro.kinds.eigenfrequencies.check import branch_sides
    got = branch_sides([arb(w) for w in omegas], NUS, {})
    assert got == (inside, outside)


def test_an_inverted_branch_holds_no_omega_on_either_side():
    """Where the ordering fails a branch can be inverted (nu3 < nu2): a root above both ends, or below
    both, is not inside (one end alone proves nothing), and is certainly outside."""
    from rigor_gyro.kinds.eigenfrequencies.check import branch_sides
    nus = {**NUS, 2: arb(3), 3: arb(2), 4: arb(5), 5: arb(4)}             # (3, 2) and (5, 4)
    for w2, w3 in ((3.5, 5.5), (1.5, 3.5), (2.5, 4.5)):
        inside, outside = branch_sides([arb(0.5), arb(w2), arb(w3), arb(7)], nus, {})
        assert inside == [True, False, False, True], (w2, w3)
        assert outside == [False, True, True, False], (w2, w3)


def test_an_exactly_empty_branch_is_outside_and_an_undecided_one_is_neither():
    from rigor_gyro.kinds.eigenfrequencies.check import branch_sides
    omegas = [arb(0.5), arb(2.5), arb(4.5), arb(7)]
    assert branch_sides(omegas, NUS, {2: True})[1] == [False, True, False, False]
    assert branch_sides(omegas, NUS, {3: True})[1] == [False, False, True, False]
    assert branch_sides(omegas, NUS, {2: False, 3: False})[1] == [False] * 4
    wide = [arb(1, 0.1), arb(3, 0.1), arb(4, 0.1), arb(6, 0.1)]             # each ball through an end
    assert branch_sides(wide, NUS, {}) == ([False] * 4, [False] * 4)


@pytest.mark.parametrize("j", [1, 2, 3, 4])
def test_a_refutation_naming_a_root_inside_its_branch_is_rejected(rudenko, j):
    """In the paper's scene every omega_j is inside its branch and no branch is empty: a 'refuted' branches
    claim naming omega_j at its true value is a forgery, whichever j."""
    bad = copy.deepcopy(rudenko)
    c = _claim(bad, "branches")
    q = bad["quantities"][f"omega_{j}"]
    c["status"] = "refuted"
    c["counterexample"] = {"outside": [{"root": f"omega_{j}", "value": [q["lo"], q["hi"]]}]}
    assert _items(bad)["branches"] is False


@pytest.mark.parametrize("params", [("15.08", "6.154", "0.1076", "0.629"), ("9", "2.5", "0.7", "3.1"),
                                    ("40", "1.5", "0.02", "0.05")])
def test_the_slacks_and_relative_errors_hold_an_mpmath_reference_and_lose_no_bits_to_cancellation(params):
    """bracket_j_slack and approx_rel_error_j (issue 41, work-precision): each contains the mpmath value at
    60 digits (the quartic's roots by polyroots, the bounds and approximations by the model at 400 bits), and at
    128 bits its relative radius is below 2^-124 although omega_j and the bound agree to 8-12 bits."""
    mpmath = pytest.importorskip("mpmath")
    from rigor_gyro.core.polyroots import isolate_polynomial
    from rigor_gyro.kinds.eigenfrequencies.model import characteristic_quartic
    exact = tuple(fmpq(*Fraction(x).as_integer_ratio()) for x in params)
    with mpmath.workdps(60):
        Q = characteristic_quartic(*exact)
        roots = sorted(mpmath.re(r) for r in mpmath.polyroots([mpmath.mpf(int(c.p)) / int(c.q) for c in reversed(Q.coeffs())],
                                                               maxsteps=300, extraprec=300))
    with working_precision(128):
        omegas = isolate_polynomial(characteristic_quartic(*exact)).real
    assert len(omegas) == 4
    mpmath.mp.dps, dps = 60, mpmath.mp.dps
    try:
        checked = _slack_rows(exact, omegas, roots, mpmath)
    finally:
        mpmath.mp.dps = dps
    assert checked >= 2


def _slack_rows(exact, omegas, roots, mpmath) -> int:
    """How many brackets j have a real value; for each, the slack and relative error checked (60 digits)."""
    from rigor_gyro.kinds.eigenfrequencies.model import (NotReal, Params, approx_rel_error, approximation, bracket,
                                                         bracket_slack)
    checked = 0
    for j in range(1, 5):
        with working_precision(400):
            P = Params(*(arb(x) for x in exact))
            try:
                lo, hi = bracket(j, P, reading="intended")
            except NotReal:
                continue
            ref_ap = mpmath.mpf(approximation(j, P).mid().str(70, radius=False))
        w = roots[j - 1]
        ref_slack = min(w - mpmath.mpf(lo.mid().str(70, radius=False)), mpmath.mpf(hi.mid().str(70, radius=False)) - w)
        with working_precision(128):
            s, e = bracket_slack(j, exact, omegas[j - 1]), approx_rel_error(j, exact, omegas[j - 1])
        for ball, ref in ((s, ref_slack), (e, (ref_ap - w) / w)):
            lo_, hi_ = (mpmath.mpf(x.str(50, radius=False)) for x in (ball.lower(), ball.upper()))
            assert lo_ - mpmath.mpf("1e-45") * abs(ref) <= ref <= hi_ + mpmath.mpf("1e-45") * abs(ref), (j, ball, ref)
            assert ball.rad() <= abs(ball.mid()) * arb(2) ** -124, (j, ball)
        checked += 1
    return checked


@pytest.mark.parametrize("eps, omega2, claims, want", [
    ("20", "3.4037869954943623161860840475034175994290869710", ["bracket_3", "bracket_4"], "refuted"),
    ("8", "0.76393202250021030359082633126872376456038164000", ["approximations"], "inconclusive")])
def test_a_radicand_settled_only_by_the_guard_bits_gives_a_verdict_not_a_crash(eps, omega2, claims, want):
    """A radicand about 1e-40 below 0 (a hostile review's scenes): at 128 bits bracket (9)/(10) and
    approximation (13) still evaluate, and only the slack's 32 guard bits find the radicand negative. The
    claims then say so (the bracket has no real value: refuted; the approximation is not real: the
    relative errors are not all enclosed), as a higher precision would; they never stop the proof, and the
    checker confirms."""
    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import parse_scene
    scene = parse_scene(f'name = "nr"\nkind = "eigenfrequencies"\nsource = "t"\n[parameters]\na = "10"\nb = "3"\n'
                        f'eps = "{eps}"\nOmega2 = "{omega2}"\n[claims]\nonly = {["roots"] + claims!r}\n'.replace("'", '"'))
    cert = prove_scene(scene, maxprec=256)
    assert {c.id: c.status.value for c in cert.claims if c.id != "roots"} == {c: want for c in claims}
    assert all(r.ok for r in check_certificate(cert.to_json()).results)
