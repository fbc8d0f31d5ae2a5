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
        assert r.enclosure.is_finite() and (r.enclosure ** 2 - 2).contains(0)
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
            assert r.is_finite() and r.overlaps(k * pi)


def test_transcendental_root_with_pi_parameter():
    with working_precision(200):
        # cos(x) = x has one root on [0, 1]
        r = newton_root(lambda x: x.cos() - x, "0", "1", rel_tol="1e-50")
        assert r.status is RootStatus.UNIQUE and r.enclosure.is_finite() and (r.enclosure.cos() - r.enclosure).contains(0)


def test_polynomial_real_roots_are_proved_real_and_simple():
    p = fmpq_poly([-2, 0, 1]) * fmpq_poly([1, 0, 1]) * fmpq_poly([fmpq(-1, 3), 1])
    with working_precision(128):
        r = isolate_polynomial(p, rel_tol="1e-30")
    assert r.squarefree and r.verified and r.width_met
    assert len(r.real) == 3 and len(r.nonreal) == 2
    assert r.real[1].is_finite() and (r.real[1].contains(arb(fmpq(1, 3))) or r.real[1].overlaps(arb(fmpq(1, 3))))


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
            assert r.is_finite() and r.overlaps(k * arb.pi()) and r.sin().contains(0) and 2 * r.rad() <= arb("1e-30") * abs(r).lower()
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


@pytest.mark.parametrize("prec", [64, 128, 256])
def test_refine_narrows_a_loose_isolating_ball_to_the_working_precision(prec):
    """polyroots._refine (interval Newton on the polynomial's Horner series): from a loose ball around
    a simple root it returns a ball inside it, still containing the root, about 2^-(prec - 8) wide
    relative (Arb's own isolation is usually that tight already, so only a loose start shows it); a
    ball where Newton cannot certify a unique root is returned unchanged."""
    from flint import fmpq, fmpq_poly
    from rigor_gyro.core.balls import working_precision
    from rigor_gyro.core.polyroots import _refine
    p = fmpq_poly([fmpq(-2), 0, 3]) * fmpq_poly([fmpq(5, 7), 1])        # roots +-sqrt(2/3), -5/7
    with working_precision(prec):
        root = (arb(2) / 3).sqrt()
        loose = arb(fmpq(4, 5), fmpq(1, 20))                             # [0.75, 0.85] holds sqrt(2/3) only
        y = _refine(p, loose)
        assert y.is_finite() and y.contains(root) and loose.contains(y)
        assert y.rad() <= abs(root) * arb(2) ** (8 - prec)
        x = arb(fmpq(-5, 7), fmpq(1, 100))
        assert _refine(p, x).is_finite() and _refine(p, x).contains(arb(fmpq(-5, 7))) and _refine(p, x).rad() <= arb(2) ** (8 - prec)
        both = arb(0, 1)                                                   # holds two roots: unchanged
        assert _refine(p, both).mid() == both.mid() and _refine(p, both).rad() == both.rad()


def test_a_linear_polynomial_has_its_one_root_and_a_constant_is_refused():
    """isolate_polynomial accepts every degree >= 1 (a linear factor is a polynomial too) and refuses a
    constant with a message that names its degree."""
    from rigor_gyro.core.errors import ParameterError
    r = isolate_polynomial(fmpq_poly([fmpq(-1, 3), 1]))
    from fractions import Fraction
    from rigor_gyro.core.balls import exact_fraction
    assert r.verified and len(r.real) == 1 and not r.nonreal
    assert exact_fraction(r.real[0].lower()) <= Fraction(1, 3) <= exact_fraction(r.real[0].upper())
    with pytest.raises(ParameterError, match="degree 0"):
        isolate_polynomial(fmpq_poly([fmpq(2)]))


def test_isolate_polynomial_reports_each_inconsistency_of_the_root_finder(monkeypatch):
    """The exact checks of isolate_polynomial do not trust Arb's root list: a planted list with a
    multiplicity, an undecided imaginary part, a point ball that is not a root, a ball without a sign
    change, two overlapping balls (adjacent or not) or a wrong count is never verified, and the reason
    names what failed; a genuine isolation says how the real roots were proved."""
    from flint import acb
    from rigor_gyro.core import polyroots as P
    p = fmpq_poly([fmpq(-1), 0, 1]) * fmpq_poly([fmpq(-4), 1])            # roots -1, 1, 4
    good = isolate_polynomial(p)
    assert good.verified and good.poly == p and good.squarefree and len(good.multiplicities) == 3
    assert "exact sign change" in good.reason
    assert [round(float(x.mid()), 9) for x in good.real] == [-1, 1, 4]
    one = isolate_polynomial(fmpq_poly([fmpq(-1), 1]))                    # x - 1: the root may be a point ball
    assert one.verified and len(one.real) == 1
    r = lambda m, rad=fmpq(1, 10**6): acb(arb(m, rad))                 # noqa: E731
    cases = {
        "multiplicity": [(r(-1), 2), (r(1), 1), (r(4), 1)],
        "imaginary part": [(r(-1), 1), (r(1), 1), (acb(arb(4, fmpq(1, 10**6)), arb(0, fmpq(1, 10**3))), 1)],
        "not an exact root": [(acb(arb(fmpq(-1, 2))), 1), (r(1), 1), (r(4), 1)],
        "no exact sign change": [(r(-1), 1), (r(1), 1), (r(fmpq(9, 2), fmpq(1, 10)), 1)],
        "overlap": [(r(-1), 1), (r(1, fmpq(6)), 1), (r(4), 1)],
        "root count": [(r(-1), 1), (r(1), 1)],
    }
    for word, planted in cases.items():
        monkeypatch.setattr(P, "arb_complex_roots", lambda q, planted=planted: planted)
        out = isolate_polynomial(p)
        assert not out.verified and word in out.reason, (word, out.reason)
    monkeypatch.setattr(P, "arb_complex_roots", lambda q: [(r(-1, fmpq(3)), 1), (r(1, fmpq(1, 10)), 1), (r(4, fmpq(4)), 1)])
    out = isolate_polynomial(p)                                           # -1's and 4's balls overlap (not adjacent)
    assert not out.verified and "overlap" in out.reason


def test_a_multiple_root_is_reported_not_isolated():
    p = fmpq_poly([fmpq(-1), 1]) ** 2 * fmpq_poly([fmpq(2), 1])
    out = isolate_polynomial(p)
    assert out.poly == p and out.squarefree is False and not out.verified and "multiple root" in out.reason
    assert sorted(m for _, m in out.multiplicities) == [1, 2]


def test_a_root_ball_ending_on_the_root_has_no_strict_sign_change(monkeypatch):
    """The sign-change check is strict: a ball about [3, 4] whose upper end is exactly the root h of
    (x^2 - 1)(x - h) is reported (p(lo) p(h) = 0 is no sign change), never accepted and never a crash
    (p(h) = 0 divides nothing)."""
    from flint import acb
    from rigor_gyro.core import polyroots as P
    from rigor_gyro.core.balls import exact_fraction
    end = arb(fmpq(7, 2), fmpq(1, 2))              # Arb rounds the radius up: the ends are dyadic, not 3 and 4
    h = exact_fraction(end.upper())
    p = fmpq_poly([fmpq(-1), 0, 1]) * fmpq_poly([-fmpq(h.numerator, h.denominator), 1])   # roots -1, 1, h
    assert p(fmpq(h.numerator, h.denominator)) == 0
    r = lambda m, rad=fmpq(1, 10**6): acb(arb(m, rad))                 # noqa: E731
    monkeypatch.setattr(P, "arb_complex_roots", lambda q: [(r(-1), 1), (r(1), 1), (acb(end), 1)])
    monkeypatch.setattr(P, "_refine", lambda q, x: x)
    out = isolate_polynomial(p)
    assert not out.verified and "no exact sign change of p across" in out.reason


def test_the_horner_series_holds_p_and_its_slope_on_a_ball_through_zero():
    """polyroots.series_function(p) on the series X + t (X a ball through 0): the value encloses p on X
    and the t coefficient p' on X (finite: nothing is divided by the series)."""
    from flint import arb_series
    from rigor_gyro.core.polyroots import series_function
    p = fmpq_poly([fmpq(-2), fmpq(1, 3), 1])                              # x^2 + x/3 - 2
    with working_precision(64):
        X = arb(0, fmpq(1, 2))
        s = series_function(p)(arb_series([X, 1], prec=2))
        assert s[0].is_finite() and s[1].is_finite()
        for x in (fmpq(-1, 2), fmpq(0), fmpq(1, 5), fmpq(1, 2)):
            assert s[0].contains(arb(p(x))) and s[1].contains(arb(p.derivative()(x)))
        const = series_function(fmpq_poly([fmpq(3), 0, 0]))(arb_series([X, 1], prec=2))
        assert const[0].is_finite() and const[0].contains(3) and const[0].rad() == 0
