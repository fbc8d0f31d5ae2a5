"""Interval Newton and polynomial root isolation: proofs on simple roots, honest 'unknown' otherwise."""
import pytest
from flint import arb, fmpq, fmpq_poly

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.polyroots import isolate_polynomial
from rigor_gyro.core.roots import RootStatus, isolate_roots, newton_root


def test_simple_root_proved_and_enclosed():
    with working_precision(128):
        r = newton_root(lambda x: x * x - 2, "1", "2", rel_tol="1e-30")
        assert r.status is RootStatus.UNIQUE
        assert (r.enclosure ** 2 - 2).contains(0)
        assert r.enclosure.rad() < arb(2) ** -100


def test_double_root_is_unknown_never_unique():
    with working_precision(128):
        r = newton_root(lambda x: (x - 1) ** 2, "0", "2")
        assert r.status is RootStatus.UNKNOWN and "f'" in r.reason
        iso = isolate_roots(lambda x: (x - 1) ** 2, "0", "2", max_depth=12)
        assert not iso.complete and not iso.roots


def test_bracket_without_root_is_empty():
    with working_precision(128):
        r = newton_root(lambda x: x * x - 2, "2", "3")
        assert r.status is RootStatus.EMPTY
        iso = isolate_roots(lambda x: x * x + 1, "-3", "3")
        assert iso.complete and iso.roots == []


def test_isolation_finds_all_roots_of_sin_including_one_on_a_bisection_point():
    with working_precision(128):
        iso = isolate_roots(lambda x: x.sin(), "-8", "8", rel_tol="1e-25")
        assert iso.complete and len(iso.roots) == 5
        pi = arb.pi()
        for k, r in zip(range(-2, 3), iso.roots):
            assert r.overlaps(k * pi)


def test_transcendental_root_with_pi_parameter():
    with working_precision(200):
        # cos(x) = x has one root on [0, 1]
        r = newton_root(lambda x: x.cos() - x, "0", "1", rel_tol="1e-50")
        assert r.status is RootStatus.UNIQUE and (r.enclosure.cos() - r.enclosure).contains(0)


def test_polynomial_real_roots_are_proved_real_and_simple():
    p = fmpq_poly([-2, 0, 1]) * fmpq_poly([1, 0, 1]) * fmpq_poly([fmpq(-1, 3), 1])
    with working_precision(128):
        r = isolate_polynomial(p, rel_tol="1e-30")
    assert r.squarefree and r.verified and r.width_met
    assert len(r.real) == 3 and len(r.nonreal) == 2
    assert r.real[1].contains(arb(fmpq(1, 3))) or r.real[1].overlaps(arb(fmpq(1, 3)))


def test_polynomial_with_multiple_root_is_not_squarefree():
    r = isolate_polynomial(fmpq_poly([-1, 1]) ** 2 * fmpq_poly([2, 1]))
    assert not r.squarefree and not r.real and "multiple" in r.reason


def test_polynomial_width_not_met_is_reported():
    with working_precision(64):
        r = isolate_polynomial(fmpq_poly([-2, 0, 1]), rel_tol="1e-300")
    assert r.verified and not r.width_met


def test_constant_polynomial_rejected():
    with pytest.raises(ValueError):
        isolate_polynomial(fmpq_poly([3]))


# ---------------------------------------------------------------- written against surviving mutants

def test_isolate_roots_finds_every_root_to_the_requested_width():
    """sin on [1, 10]: exactly the three roots pi, 2 pi, 3 pi, each to rel_tol, and complete."""
    with working_precision(128):
        iso = isolate_roots(lambda x: x.sin(), "1", "10", rel_tol="1e-30")
        assert iso.complete and len(iso.roots) == 3
        for k, r in enumerate(iso.roots, start=1):
            assert r.overlaps(k * arb.pi()) and r.sin().contains(0) and 2 * r.rad() <= arb("1e-30") * abs(r).lower()
        decided = {p.status for p in iso.pieces}
        assert decided <= {RootStatus.UNIQUE, RootStatus.EMPTY}


def test_isolate_roots_budget_leaves_pieces_unknown_with_the_diagnostic():
    with working_precision(128):
        iso = isolate_roots(lambda x: (x - 1) ** 2, "0", "2", max_depth=3)
        assert not iso.complete and iso.unknown
        for p in iso.unknown:
            assert "f' may vanish" in p.reason and "(after 3 bisections)" in p.reason


def test_isolate_roots_rejects_an_empty_bracket_with_a_message():
    with working_precision(64), pytest.raises(ValueError, match=r"bracket \[2, 1\]"):
        isolate_roots(lambda x: x, "2", "1")


def test_a_real_root_ball_without_an_exact_sign_change_is_not_verified(monkeypatch):
    """If the root finder returned a wrong real ball, the exact sign-change check must catch it."""
    from flint import acb
    from rigor_gyro.core import polyroots
    p = fmpq_poly([-2, 0, 1])                                      # x^2 - 2
    wrong = [(acb(arb("1.3", "0.01")), 1), (acb(arb("-1.4142135623730950488", "1e-15")), 1)]
    monkeypatch.setattr(polyroots, "arb_complex_roots", lambda q: wrong)
    monkeypatch.setattr(polyroots, "_refine", lambda q, x: x)
    with working_precision(64):
        r = isolate_polynomial(p)
    assert not r.verified and "sign change" in r.reason
