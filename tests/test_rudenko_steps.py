"""Rudenko (1976): rows for the derivation's steps (issue 39): (5) for every parameter (exact identities), the
step of (6) (its sides against F on [0, nu1], the factor from (3) and (5)) and the statements in words after
(14). Cross-checked in mpmath; no row of the audit is undecided with no value."""
from __future__ import annotations

import random

import mpmath
from flint import arb, fmpq, fmpq_poly

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.outcome import AuditStatus
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.kinds.eigenfrequencies.model import characteristic_quartic
from rigor_gyro.kinds.eigenfrequencies.paper_steps import five_identities, positive_on, step_rows

A, B, E, W = fmpq(1508, 100), fmpq(6154, 1000), fmpq(1076, 10000), fmpq(629, 1000)


def _rows(a=A, b=B, e=E, w=W):
    with working_precision(128):
        om = sorted(isolate_polynomial(characteristic_quartic(a, b, e, w)).real, key=lambda x: float(x.mid()))
        return {r.id: r for r in step_rows(a, b, e, w, om)}


def _mp(x):
    return mpmath.mpf(int(x.p)) / int(x.q)


def _nus(a, b, e):
    c2 = (a - b) * (b - 1)
    n14 = sorted(mpmath.polyroots([c2, -(e * (a - 1) + a - b), e], extraprec=100))
    n26 = sorted(mpmath.polyroots([c2, -(e * (a - 1) + b * (a - b)), e * a], extraprec=100))
    return n14[0], n26[0], n14[1], n26[1]


def test_five_holds_for_every_parameter_identities_and_mpmath_samples():
    assert all(five_identities().values())
    assert _rows()["(5) for every parameter"].status is AuditStatus.CONFIRMED
    rnd = random.Random(3)
    mpmath.mp.dps = 40
    for _ in range(40):
        b = 1 + mpmath.mpf(10) ** rnd.uniform(-3, 2)
        a = b + mpmath.mpf(10) ** rnd.uniform(-3, 2)
        e = mpmath.mpf(10) ** rnd.uniform(-4, 2)
        nu1, nu2, nu4, nu6 = _nus(a, b, e)
        n4m = (1 + e) / (b - 1)
        n6m = (b * b + e) / (b * (b - 1))
        assert e / (a - b + e * (a - 1)) < nu1 < e / (a - b)
        assert e * a / (b * (a - b) + e * (a - 1)) < nu2 < e * a / (b * (a - b))
        assert n4m < nu4 < n4m + e * e * (a - 1) / ((a - b) * (a - b + e * (a - 1))) * (1 + mpmath.mpf(10) ** -30)
        assert n6m < nu6 < n6m + e * e * a * (a - 1) / (b * (a - b) * ((a - b) * b + e * (a - 1))) * (1 + mpmath.mpf(10) ** -30)


def test_six_rows_at_the_example_and_mpmath():
    rows = _rows()
    assert rows["(6) left side >= F on [0, nu1]"].status is AuditStatus.CONFIRMED
    assert rows["(6) F >= right side on [0, nu1] (printed)"].status is AuditStatus.CONFIRMED
    assert rows["(6) F >= right side on [0, nu1] (as read)"].status is AuditStatus.CONFIRMED
    step = rows["(6) step: the right side's factor from (3) and (5)"]
    assert step.status is AuditStatus.REFUTED and "34.09" in step.note and "38.000" in step.note
    mpmath.mp.dps = 30
    a, b, e = _mp(A), _mp(B), _mp(E)
    nu1, nu2, nu4, nu6 = _nus(a, b, e)
    nu3, nu5 = 1 / (b - 1), b / (b - 1)
    F = lambda w: w * (w - nu2) * (w - nu5) * (w - nu6) / ((w - nu1) * (w - nu3) * (w - nu4))  # noqa: E731
    lhs = lambda w: w * e * a * b / ((b - 1) * (a - b) * w * w - (e * (a - 1) + a - b) * w + e)  # noqa: E731
    lam = (b * (b - 1) + e) / (b * (b - 1))
    rhs = lambda w: w * (w - e * a / (b * (a - b) + e * (a - 1))) / (w - e / (a - b)) * lam * b * b  # noqa: E731
    for i in range(1, 100):
        w = nu1 * i / 100
        assert lhs(w) >= F(w) >= rhs(w)
    assert nu5 * nu6 / (nu3 * nu4) < lam * b * b


def test_positive_on_decides_both_ways():
    x = fmpq_poly([0, 1])
    st, _, _ = positive_on((x - fmpq(1, 3)) ** 2 + fmpq(1, 100), arb(0), arb(1))
    assert st == "positive"
    st, pt, _ = positive_on((x - fmpq(1, 3)) ** 2 - fmpq(1, 100), arb(0), arb(1))
    assert st == "negative" and abs(float(pt.mid()) - 1 / 3) < 0.1
    st, _, _ = positive_on((x - fmpq(1, 3)) ** 2, arb(0), arb(1), max_pieces=64)     # touches 0: never positive
    assert st != "positive"


def test_fourteen_rows_and_the_sensitivities_against_mpmath():
    rows = _rows()
    for rid in ("(14) infinitely stiff gimbal", "(14) lambda_1, lambda_2 nearly independent of K3",
                "(14) lambda_3, lambda_4 independent of A1 and K2 at small eps"):
        assert rows[rid].status is AuditStatus.CONFIRMED, rid
    # the K2 sensitivity of lambda_1 by a finite difference of mpmath roots: d ln lambda/d ln K2 = eps/2 d ln w/d eps
    mpmath.mp.dps = 40

    def w1(e):
        a, b, w = _mp(A), _mp(B), _mp(W)
        c2 = (a - b) * (b - 1)
        # P1(l) = (l(b-1) + b)(c2 l^2 + (e(a-1) + b(a-b)) l + e a), P2(l) = (l(b-1) + 1)(c2 l^2 + (e(a-1) + a-b) l + e)
        p1 = [(b - 1) * c2, (b - 1) * (e * (a - 1) + b * (a - b)) + b * c2, (b - 1) * e * a + b * (e * (a - 1) + b * (a - b)), b * e * a]
        p2 = [(b - 1) * c2, (b - 1) * (e * (a - 1) + a - b) + c2, (b - 1) * e + (e * (a - 1) + a - b), e]
        # Q(x) = l p1(l) + w p2(l), l = -x: polynomial in l, then roots in x = -l
        coeffs = [p1[0], p1[1] + w * p2[0], p1[2] + w * p2[1], p1[3] + w * p2[2], w * p2[3]]
        return sorted(-r.real for r in mpmath.polyroots(coeffs, extraprec=100))
    e0, h = _mp(E), mpmath.mpf(10) ** -12
    for j, w in enumerate(w1(e0)):
        w_plus = w1(e0 + h)[j]
        fd = e0 / 2 * (mpmath.log(w_plus) - mpmath.log(w)) / h
        txt = rows["(14) lambda_3, lambda_4 independent of A1 and K2 at small eps"].note
        part = txt.split("d ln lambda_j / d ln K2 = ")[1].split(" for j")[0]
        lo, hi = (float(x) for x in part.split("], [")[j].strip("[]").split(", "))
        assert lo - 1e-6 <= float(fd) <= hi + 1e-6


def test_no_undecided_row_without_a_value_in_the_audit():
    from rigor_gyro import load_scene, prove_scene
    rows = prove_scene(load_scene("rudenko1976")).to_json()["paper"]
    ids = {r["id"] for r in rows}
    assert "(5) for every parameter" in ids and "(6) step: the right side's factor from (3) and (5)" in ids
    for r in rows:
        assert not (r["status"] == "undecided" and r["lo"] == ""), r["id"]


def test_the_audit_and_the_box_forms_share_one_quartic():
    from rigor_gyro.kinds.eigenfrequencies import model, paper_steps, slack_forms
    assert paper_steps.quartic_value is slack_forms.quartic_value is model.quartic_value


def _paper_rows():
    from rigor_gyro import load_scene, prove_scene
    return {r["id"]: r for r in prove_scene(load_scene("rudenko1976")).to_json()["paper"]}


def test_950_8_is_the_eps1_reading_of_10_and_mpmath():
    r = _paper_rows()["(10) lambda_4+ (Hz)"]
    assert r["class"] == "propagated" and "eps for eps^2" in r["note"]
    mpmath.mp.dps = 30
    a, b, e, w = _mp(A), _mp(B), _mp(E), _mp(W)

    def f(k):
        r3 = (e / (b * (b - 1)) + e ** k * a * (a - 1) / (b * (a - b) * ((a - b) * b + e * (a - 1))) + w) / 2
        return b / (b - 1) + r3 + mpmath.sqrt(r3 * r3 + w)
    s_lo = mpmath.mpf("617.7423")
    assert abs(s_lo * mpmath.sqrt(f(1)) - mpmath.mpf("950.8")) < mpmath.mpf("0.05")        # eps: rounds to 950.8
    assert abs(s_lo * mpmath.sqrt(f(2)) - mpmath.mpf("950.8")) > mpmath.mpf("0.5")         # eps^2: far from it


def test_the_omega2_prints_share_one_scale_and_say_what_was_tried():
    rows = _paper_rows()
    for rid in ("(8) lambda_2+ (Hz)", "(13) lambda_2~ (Hz)"):
        assert rows[rid]["class"] == "unexplained"
        assert "tried: the formula as printed" in rows[rid]["note"] and "one common Hz scale" in rows[rid]["note"]
    mpmath.mp.dps = 30
    a, b, e, w = _mp(A), _mp(B), _mp(E), _mp(W)
    w8 = (e * a * (b - 1) + w * (1 + e) * (a - b)) / ((a - b) * (b - 1) * (b + w * (1 + e)))
    w13 = (e * (b - 1) * a + w * (a - b)) / ((a - b) * (b - 1) * (b + w))
    lo = max((mpmath.mpf("130.35")) / mpmath.sqrt(w8), mpmath.mpf("127.5") / mpmath.sqrt(w13))
    hi = min((mpmath.mpf("130.45")) / mpmath.sqrt(w8), mpmath.mpf("128.5") / mpmath.sqrt(w13))
    assert 606 < lo < hi < 606.5


def test_window_reading_needs_the_print_in_its_chain():
    from types import SimpleNamespace
    from rigor_gyro import load_scene
    from rigor_gyro.kinds.eigenfrequencies.claims import validate
    from rigor_gyro.kinds.eigenfrequencies.paper_hz import _window_row, input_box
    from rigor_gyro.kinds.eigenfrequencies.paper_scale import consistent_eps
    model = validate(load_scene("rudenko1976"))
    with working_precision(128):
        sc = consistent_eps(A, B, W, "0.1076", ["41.4", "121.5", "521.5", "935.7"])
        box = input_box(model)
        for printed, ok in (("950.8", True), ("951.9", False), ("949.9", False)):
            row = SimpleNamespace(propagated=None, note="")
            assert _window_row(row, ("upper", 4), printed, box, sc, "0.1076") is ok, printed


PAPER_TABLE = """
[paper]
hz_lower = ["39.5", "119.5", "513.4", "923.5"]
hz_approx = ["40.6", "128", "514", "922"]
hz_upper = ["43.4", "130.4", "546", "950.8"]
hz_exact = ["41.4", "121.5", "521.5", "935.7"]
error_bound = "0.05"
"""


def test_no_row_escalates_without_hz_scale_or_at_a_small_omega2(tmp_path):
    """An undecided audit row without a value makes the prover raise the precision to 4096 bits: without
    hz_scale there is no Hz row, and (11) at an Omega^2 where its discriminant is >= 0 is still decided."""
    from rigor_gyro import load_scene, prove_scene
    for name, extra in (("nohz", 'Omega2 = "0.629"'), ("smallw", 'Omega2 = "0.00001"\nhz_scale = "617.75"')):
        f = tmp_path / f"{name}.toml"
        f.write_text(f'name = "{name}"\nkind = "eigenfrequencies"\nsource = "t"\n\n[parameters]\na = "15.08"\n'
                     f'b = "6.154"\neps = "0.1076"\n{extra}\n' + PAPER_TABLE)
        data = prove_scene(load_scene(str(f))).to_json()
        assert data["precision_bits"] <= 128 and max(data["precisions_tried"]) <= 128, name
        rows = data["paper"]
        assert not [r["id"] for r in rows if r["status"] == "undecided" and r["lo"] == ""], name
        if name == "smallw":
            r11 = next(r for r in rows if r["id"] == "(11) as printed")
            assert r11["status"] == "misprint" and ">= 0: real solutions, but not (12)" in r11["note"]
