"""Rudenko (1976): rows for the derivation's text (issue 39): (11), Omega_2, (3)'s monotonicity, the
abstract, the 'exact' values' eps and the 5 % rows' readings."""
from __future__ import annotations

import mpmath
from flint import fmpq

from rigor_gyro.core.outcome import AuditStatus
from rigor_gyro.kinds.eigenfrequencies.paper_text import _eq11_row, _k_monotone_row, text_rows

A, B, E, W = fmpq(1508, 100), fmpq(6154, 1000), fmpq(1076, 10000), fmpq(629, 1000)


def test_eq11_as_printed_has_no_real_solution_and_the_reading_gives_12():
    row = _eq11_row(A, B, E, W)
    assert row.status is AuditStatus.MISPRINT and "no real solution" in row.note and "checked" in row.note
    # a large Omega^2 makes the printed quadratic's discriminant no better: it decreases with W
    assert "< 0" in _eq11_row(A, B, E, fmpq(10)).note


def test_k_is_increasing_on_0_nu1_and_mpmath_samples_agree():
    row = _k_monotone_row(A, B, E)
    assert row.status is AuditStatus.CONFIRMED
    mpmath.mp.dps = 30
    a, b, e = (mpmath.mpf(int(x.p)) / int(x.q) for x in (A, B, E))
    c2 = (a - b) * (b - 1)
    n14 = sorted(mpmath.polyroots([c2, -(e * (a - 1) + a - b), e]))
    n26 = sorted(mpmath.polyroots([c2, -(e * (a - 1) + b * (a - b)), e * a]))
    nu1, nu4, nu2, nu6 = n14[0], n14[1], n26[0], n26[1]
    nu3, nu5 = 1 / (b - 1), b / (b - 1)

    def K(w):
        return (w - nu5) * (w - nu6) / ((w - nu3) * (w - nu4))
    for i in range(50):
        w = nu1 * i / 50
        assert mpmath.diff(K, w) > 0


def test_the_text_rows_of_the_example():
    from rigor_gyro import load_scene, prove_scene
    rows = {r["id"]: r for r in prove_scene(load_scene("rudenko1976")).to_json()["paper"]}
    assert rows["(11) as printed"]["class"] == "misprint-reading"
    assert rows["example: 'Omega_2 = 0.629'"]["reading"] == "Omega^2 = 0.629"
    assert rows["abstract: 'the estimates are not asymptotic'"]["class"] == "assertion-refuted"
    assert rows["'exact' values: the eps that gives them one Hz scale"]["reading"].startswith("eps = 0.1073")
    five = rows["error <= 0.05 for root 2 (Hz)"]["note"]
    assert "verdict on: lower by (8) as read" in five and "approx, upper already exceed 5 %" in five
    assert len(text_rows(A, B, E, W, None)) == 4


def test_the_nu_order_threshold_is_where_nu2_meets_nu3():
    """The order nu1 < ... < nu6 holds for eps below 0.72286 (a, b of the example) and fails above: the
    smaller root of (4b) crosses nu3 = 1/(b-1) there (mpmath cross-check on both sides)."""
    from rigor_gyro.kinds.eigenfrequencies.paper_text import _nu_order_row
    row = _nu_order_row(A, B, E)
    assert row.status is AuditStatus.CONFIRMED and "11501151/15910580" in row.reading
    mpmath.mp.dps = 30
    a, b = (mpmath.mpf(int(x.p)) / int(x.q) for x in (A, B))
    t = mpmath.mpf(11501151) / 15910580
    for eps, below in ((t - mpmath.mpf("1e-6"), True), (t + mpmath.mpf("1e-6"), False)):
        c2 = (a - b) * (b - 1)
        nu2 = min(mpmath.polyroots([c2, -(eps * (a - 1) + b * (a - b)), eps * a]))
        assert (nu2 < 1 / (b - 1)) is below
