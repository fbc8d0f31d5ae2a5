"""The prover's equilibrium search (``kinds/lyapunov/equilibria.py``) against an independent one.

The reference finds the equilibria of system (2) with |x2| <= pi in mpmath at 50 digits from the float
side's model (``approx.MpGimbal``, written without balls): x3 = 0, x1 = -f(x2)/k, and x2 a root of f,
+-pi/2, or a root of h = k H + C0 sin x2 f(x2), each root bracketed by a dense sign scan and polished by
bisection-safe root finding; the stability of each from the eigenvalues of the Jacobian differentiated
numerically in mpmath. The search must find exactly those points, each ball containing its point, the
stated stability agreeing with the reference's eigenvalues, the isolation pieces tiling [-P, P], and
``complete`` false, with its reason, where a root cannot be separated. All of it takes about a second:
it is the net for a mutation run of the search itself (proofs/mutation.md section 14).
"""
import dataclasses
import functools
from fractions import Fraction

import mpmath
import pytest
from flint import acb, arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov import equilibria as E
from rigor_gyro.kinds.lyapunov.approx import MpGimbal
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.scene import load_scene
from tests.test_properties_lyapunov import contains_mp

F_CASE, COS_CASE, H_CASE = "f(x2) = 0", "cos x2 = 0", "k H + C0 sin x2 f(x2) = 0"

# C0 = A + A1 - C1 = 4.2 - C1; k H = 4000; a = 100
VARIANTS = {
    "paper (no root of h)": {},
    "C1 = 54.2: sin^2 x2 = 0.8 at four roots of h": {"C1": "54.2"},
    "C1 = 44.6: four roots of h near +-pi/2": {"C1": "44.6"},
    "C1 = 40: C0 < 0 and still no root of h": {"C1": "40"},
    "linear law": {"moment": "linear"},
    "linear law, C1 = 54.2: x2 sin x2 = 0.8 at four roots of h": {"moment": "linear", "C1": "54.2"},
    "k = 40, H = 10": {"k": "40", "H": "10"},
    # sin^2 x2 = 4e-5 (C0 about -1e6): roots of h at j pi +- 0.0063, two of them beyond |x2| = pi but inside
    # the search range [-P, P] (P = pi + 1/64): found, and not equilibria
    "C1 = 1e6: roots of h just beyond +-pi": {"C1": "1e6"},
}


def _params(variant: str) -> dict:
    return dict(load_scene("agafonov2013").parameters, **VARIANTS[variant])


def _gimbal(params: dict):
    scene = load_scene("agafonov2013")
    return validate(dataclasses.replace(scene, parameters=params)).gimbal


def _mp_roots(fn, lo, hi, n=3000):
    """Every sign change of fn on a grid of n cells of [lo, hi], polished (simple roots only)."""
    xs = [lo + (hi - lo) * i / n for i in range(n + 1)]
    ys = [fn(x) for x in xs]
    out = []
    for a, b, fa, fb in zip(xs, xs[1:], ys, ys[1:]):
        if fa == 0:
            out.append(a)
        elif fa * fb < 0:
            out.append(mpmath.findroot(fn, (a, b), solver="anderson"))
    return out


def _mp_jacobian(mg, x1, x2):
    """The Jacobian of (2) at (x1, x2, 0), each partial derivative by mpmath.diff."""
    point = [x1, x2, mpmath.mpf(0)]

    def comp(i, j):
        def along(t):
            p = list(point)
            p[j] = t
            return mg.rhs3(*p)[i]
        return mpmath.diff(along, point[j])
    return mpmath.matrix([[comp(i, j) for j in range(3)] for i in range(3)])


@functools.lru_cache(maxsize=None)
def roots_in_range(variant: str) -> dict[str, list]:
    """The roots of f and of h on the search range [-P, P], P = pi + 1/64, mpmath at 50 digits."""
    with mpmath.workdps(50):
        mg = MpGimbal(_params(variant))
        P = mpmath.pi + mpmath.mpf(1) / 64
        h = lambda x: mg.k * mg.H + mg.C0 * mpmath.sin(x) * mg.f(x)        # noqa: E731
        return {F_CASE: _mp_roots(mg.f, -P, P), H_CASE: _mp_roots(h, -P, P)}


@functools.lru_cache(maxsize=None)
def reference(variant: str) -> list[tuple]:
    """(case, x2, x1, eigenvalues) of every equilibrium with |x2| <= pi, mpmath at 50 digits."""
    roots = roots_in_range(variant)
    with mpmath.workdps(50):
        mg = MpGimbal(_params(variant))
        pts = [(F_CASE, r) for r in roots[F_CASE]]
        pts += [(COS_CASE, s * mpmath.pi / 2) for s in (1, -1)]
        pts += [(H_CASE, r) for r in roots[H_CASE]]
        out = []
        for case, x2 in pts:
            if abs(x2) > mpmath.pi:
                continue
            x1 = -mg.f(x2) / mg.k
            ev = mpmath.eig(_mp_jacobian(mg, x1, x2), left=False, right=False)
            out.append((case, x2, x1, ev))
        return out


def _found(variant: str):
    """The search run afresh (a few milliseconds; no module fixture, so a mutant of it is what runs)."""
    g = _gimbal(_params(variant))
    with working_precision(64):
        return variant, g, E.equilibria(g)


each_variant = pytest.mark.parametrize("variant", list(VARIANTS))


@each_variant
def test_every_equilibrium_is_found_once_with_its_case_and_its_point(variant):
    variant, g, eq = _found(variant)
    ref = reference(variant)
    assert eq.complete, eq.reason
    assert eq.reason == "every piece of [-P, P] decided for f and for h"
    assert len(eq.points) == len(ref), (variant, [(p.case, p.x2.str(6)) for p in eq.points])
    for case, x2, x1, _ in ref:
        hits = [p for p in eq.points if p.case == case and contains_mp(p.x2, x2)]
        assert len(hits) == 1, (variant, case, x2)
        p = hits[0]
        assert contains_mp(p.x1, x1), (variant, case, x2, p.x1)
        assert p.x2.rad() < arb(2) ** -40 and p.x1.rad() < arb(2) ** -40 * (1 + abs(p.x1)), (variant, p)


@each_variant
def test_the_exact_equilibria_are_named_exactly(variant):
    """x2 = j pi (zeros the sine law names) and +-pi/2 carry their exact text and a ball of the exact point."""
    variant, g, eq = _found(variant)
    named = {p.exact: p for p in eq.points if p.exact}
    want = {"pi/2", "-pi/2"} | ({"0", "pi", "-pi"} if g.law.name == "sine" else {"0"})
    assert set(named) == want, (variant, set(named))
    for text, p in named.items():
        r = {"0": 0, "pi": 1, "-pi": -1, "pi/2": Fraction(1, 2), "-pi/2": Fraction(-1, 2)}[text]
        with working_precision(64):
            assert p.x2.is_finite() and p.x2.overlaps(arb.pi() * arb(fmpq(Fraction(r).numerator, Fraction(r).denominator)))
        assert p.case == (COS_CASE if abs(r) == Fraction(1, 2) else F_CASE)
        if p.case == F_CASE:
            assert p.x1.is_exact() and p.x1 == 0
    assert all(bool(p.exact) == (p.case != H_CASE) for p in eq.points)


@each_variant
def test_each_stability_agrees_with_the_eigenvalues_in_mpmath(variant):
    """Asymptotically stable: every real part < 0; unstable: one > 0; undecided only where the largest
    real part is 0 to 30 digits (a centre the linearisation cannot decide)."""
    variant, g, eq = _found(variant)
    for case, x2, x1, ev in reference(variant):
        re_max = max(mpmath.re(z) for z in ev)
        p = next(p for p in eq.points if p.case == case and contains_mp(p.x2, x2))
        assert len(p.eigenvalues) == 3, (variant, case)
        for z in ev:        # each reference eigenvalue in one of the balls (the linearisation at the point)
            assert any(contains_mp(w.real, mpmath.re(z)) and contains_mp(w.imag, mpmath.im(z)) for w in p.eigenvalues), \
                (variant, case, x2, z, p.eigenvalues)
        if p.stability == "asymptotically stable":
            assert re_max < -mpmath.mpf(10) ** -30, (variant, case, x2, re_max)
        elif p.stability == "unstable":
            assert re_max > mpmath.mpf(10) ** -30, (variant, case, x2, re_max)
        else:
            # undecided, or (at x2 = +-pi/2, the linearisation in closed form) "not hyperbolic": a real part 0 exactly
            assert p.stability == "undecided" or p.stability.startswith("not hyperbolic") and case == "cos x2 = 0", \
                (variant, case, p.stability)
            assert abs(re_max) < mpmath.mpf(10) ** -30, (variant, case, x2, re_max)
    got = [p.stability for p in eq.points]
    assert "undecided" not in got or variant.startswith(("C1 = 54.2", "C1 = 44.6", "C1 = 1e6", "linear law, C1"))


@each_variant
def test_the_isolation_pieces_tile_the_search_range_and_hold_the_roots(variant):
    variant, g, eq = _found(variant)
    for name, case in (("f", F_CASE), ("h", H_CASE)):
        pieces = eq.pieces[name]
        assert all(p[e][0] == p[e][1] for p in pieces for e in ("lo", "hi"))      # exact ends
        ends = [(Fraction(p["lo"][0]), Fraction(p["hi"][0])) for p in pieces]
        # the range is [-P, P] with P the upper end of a ball of pi + 1/64: just above it, symmetric
        with mpmath.workdps(50):
            top = Fraction(mpmath.nstr(mpmath.pi + mpmath.mpf(1) / 64, 45))     # P = pi + 1/64
        assert top < ends[-1][1] < top + Fraction(1, 10 ** 15) and ends[0][0] == -ends[-1][1], (variant, name)
        assert all(a < b for a, b in ends)
        assert all(b == c for (_, b), (c, _) in zip(ends, ends[1:])), (variant, name)
        assert {p["kind"] for p in pieces} <= {"unique", "empty"}
        unique = [p for p in pieces if p["kind"] == "unique"]
        roots = roots_in_range(variant)[case]        # with those just beyond |x2| = pi
        assert len(unique) == len(roots), (variant, name, len(unique), len(roots))
        for p, r in zip(unique, sorted(roots)):
            r = Fraction(mpmath.nstr(r, 40))
            tol = Fraction(1, 10 ** 35)
            assert Fraction(p["lo"][0]) <= r <= Fraction(p["hi"][0])
            assert Fraction(p["root"][0]) - tol <= r <= Fraction(p["root"][1]) + tol, (variant, name, p["root"], r)
        assert all("root" not in p for p in pieces if p["kind"] == "empty")


def test_a_root_of_f_the_law_does_not_name_must_be_separated_from_pi(monkeypatch):
    """With no named zeros the sine law's roots at +-pi cannot be separated from |x2| = pi: the list is
    then not complete and says why; the root at 0 is still an equilibrium, from its isolation ball."""
    g = _gimbal(_params("paper (no root of h)"))
    monkeypatch.setattr(type(g.law), "zeros_over_pi", lambda self: ())
    with working_precision(64):
        eq = E.equilibria(g)
    assert not eq.complete and eq.reason.count("is not separated from |x2| = pi") == 2, eq.reason
    at0 = [p for p in eq.points if p.case == F_CASE]
    assert len(at0) == 1 and at0[0].exact == "" and at0[0].x2.is_finite() and at0[0].x2.contains(0) and at0[0].x2.rad() < 1e-15 and at0[0].x1 == 0
    assert len(eq.points) == 3
    # naming only 0 and pi leaves -pi unseparated; naming a zero beyond pi names no piece
    monkeypatch.setattr(type(g.law), "zeros_over_pi", lambda self: (Fraction(0), Fraction(1), Fraction(2)))
    with working_precision(64):
        eq = E.equilibria(g)
    assert not eq.complete and eq.reason.count("not separated") == 1 and "-3.14" in eq.reason, eq.reason
    assert sorted(p.exact for p in eq.points if p.case == F_CASE) == ["0", "pi"]


def test_a_named_zero_outside_the_range_is_not_an_equilibrium(monkeypatch):
    """A law naming 3 pi/2 in a piece of [-P, P]: f has no root there, so no piece is UNIQUE about it and
    nothing changes; naming the root at pi as 1 keeps it, and a named r with |r| > 1 is never listed."""
    g = _gimbal(_params("paper (no root of h)"))
    base = E.equilibria(g)
    monkeypatch.setattr(type(g.law), "zeros_over_pi",
                        lambda self: (Fraction(-1), Fraction(0), Fraction(1), Fraction(3, 2), Fraction(-3, 2)))
    with working_precision(64):
        eq = E.equilibria(g)
    assert eq.complete and [p.exact for p in eq.points] == [p.exact for p in base.points]


def test_a_named_zero_just_beyond_pi_names_the_root_there_and_it_is_not_an_equilibrium(monkeypatch):
    """A law naming 251/250 (pi 1.004 < P) and not 1: the piece holding f's root near pi names that zero,
    so its one root is 1.004 pi, beyond |x2| = pi: not listed (the list stays complete)."""
    g = _gimbal(_params("paper (no root of h)"))
    monkeypatch.setattr(type(g.law), "zeros_over_pi", lambda self: (Fraction(-1), Fraction(0), Fraction(251, 250)))
    with working_precision(64):
        eq = E.equilibria(g)
    assert eq.complete, eq.reason
    assert sorted(p.exact for p in eq.points if p.case == F_CASE) == ["-pi", "0"]


def test_two_named_zeros_in_one_piece_name_neither(monkeypatch):
    """A law naming 0 and 1/5 (both in the piece around 0, which holds one root): neither is trusted; the
    root is taken from its isolation ball, with no exact text."""
    g = _gimbal(_params("paper (no root of h)"))
    monkeypatch.setattr(type(g.law), "zeros_over_pi",
                        lambda self: (Fraction(-1), Fraction(0), Fraction(1, 5), Fraction(1)))
    with working_precision(64):
        eq = E.equilibria(g)
    assert eq.complete, eq.reason
    at0 = [p for p in eq.points if p.case == F_CASE and p.x2.is_finite() and p.x2.contains(0)]
    assert len(at0) == 1 and at0[0].exact == "" and sorted(p.exact for p in eq.points if p.case == F_CASE) == ["", "-pi", "pi"]


def test_a_double_root_of_h_on_cos_zero_leaves_the_list_incomplete():
    """C1 = 44.2: C0 a = -k H, so h = k H cos^2 x2 has double roots at +-pi/2: the isolation cannot decide
    them, the list is not complete, and the reason counts the undecided pieces."""
    g = _gimbal(_params("paper (no root of h)") | {"C1": "44.2"})
    with working_precision(64):
        eq = E.equilibria(g)
    assert not eq.complete and "undecided piece(s)" in eq.reason, eq.reason
    assert [p.case for p in eq.points].count(COS_CASE) == 2
    assert H_CASE not in [p.case for p in eq.points]


@pytest.mark.parametrize("near, ball, problem", [
    (1.1071, arb(1.5, 0.2), "is not separated from cos x2 = 0"),
    (-2.0344, arb(-3.1, 0.1), "is not separated from |x2| = pi"),
], ids=["over pi/2", "over -pi (the first root)"])
def test_a_root_of_h_not_separated_from_cos_zero_or_pi_is_a_problem_not_a_point(monkeypatch, near, ball, problem):
    """A root of h whose ball contains pi/2 (the cos x2 = 0 case) or -pi is reported, never listed, and the
    other roots of h are still listed."""
    g = _gimbal(_params("C1 = 54.2: sin^2 x2 = 0.8 at four roots of h"))
    real = E.isolate_roots

    def widened(fn, lo, hi):
        iso = real(fn, lo, hi)
        if len(iso.roots) != 4:         # f's three roots: unchanged
            return iso
        for p in iso.pieces:            # the h roots: the one near NEAR stretched to BALL
            if p.enclosure is not None and p.enclosure.overlaps(arb(near, 1e-3)):
                p.enclosure = ball
        return iso
    monkeypatch.setattr(E, "isolate_roots", widened)
    with working_precision(64):
        eq = E.equilibria(g)
    assert not eq.complete and problem in eq.reason, eq.reason
    assert [p.case for p in eq.points].count(H_CASE) == 3


def test_the_jacobian_is_the_derivative_of_the_vector_field():
    """At points off the equilibria (x3 != 0 too), against mpmath.diff of the float side's field."""
    params = _params("C1 = 54.2: sin^2 x2 = 0.8 at four roots of h")
    g = _gimbal(params)
    with mpmath.workdps(40):
        mg = MpGimbal(params)           # its parameters at the working digits
        for x1, x2, x3 in ((0.3, 0.2, -0.1), (-120.0, 1.1, 2.0), (5.0, -2.9, 0.7)):
            with working_precision(128):
                J = E.jacobian(g, arb(x1), arb(x2), arb(x3))
            p = [mpmath.mpf(x1), mpmath.mpf(x2), mpmath.mpf(x3)]
            for i in range(3):
                for j in range(3):
                    def along(t, i=i, j=j):
                        q = list(p)
                        q[j] = t
                        return mg.rhs3(*q)[i]
                    ref = mpmath.diff(along, p[j])
                    assert contains_mp(J[i][j], ref), (i, j, J[i][j], ref)


def _classified(matrix) -> E.Equilibrium:
    e = E.Equilibrium(arb(0), arb(0), "planted")
    E.jacobian, real = (lambda g, x1, x2, x3: matrix), E.jacobian
    try:
        E.classify(None, e)
    finally:
        E.jacobian = real
    return e


@pytest.mark.parametrize("matrix, want", [
    ([[-1, 0, 0], [0, -2, 0], [0, 0, -3]], "asymptotically stable"),
    ([[-1, 0, 0], [0, -2, 0], [0, 0, fmpq(1, 10 ** 30)]], "unstable"),
    ([[-1, 0, 0], [0, -2, 0], [0, 0, fmpq(-1, 10 ** 30)]], "asymptotically stable"),
    ([[-1, 0, 0], [0, -2, 0], [0, 0, 0]], "undecided"),
    ([[0, 1, 0], [-1, 0, 0], [0, 0, -1]], "undecided"),                         # a centre: +-i
    ([[fmpq(1, 10 ** 30), 1, 0], [-1, fmpq(1, 10 ** 30), 0], [0, 0, -1]], "unstable"),
    ([[-1, 0, 0], [0, -2, 0], [0, 0, arb(0, 1e-3)]], "undecided"),              # a real part not separated
    ([[-1, 0, 0], [0, 5, 0], [0, 0, arb(0, 1e-3)]], "unstable"),                # one certainly > 0 decides
    ([[-1, 0, 0], [0, -2, 0], [0, 0, arb("nan")]], "undecided"),
], ids=["stable", "tiny positive", "tiny negative", "zero", "centre", "tiny spiral out", "wide", "wide but one > 0",
        "nan"])
def test_classify_decides_on_certain_signs_of_the_real_parts(matrix, want):
    with working_precision(128):
        e = _classified([[arb(v) for v in row] for row in matrix])
    assert e.stability == want, e.eigenvalues
    if want != "undecided" or matrix[2][2] == 0:
        assert len(e.eigenvalues) == 3 and all(isinstance(z, acb) for z in e.eigenvalues)


@pytest.mark.parametrize("r, text", [(0, "0"), (1, "pi"), (-1, "-pi"), (Fraction(1, 2), "pi/2"),
                                     (Fraction(-1, 2), "-pi/2"), (Fraction(2, 3), "2 pi/3"),
                                     (Fraction(-3, 4), "-3 pi/4"), (3, "3 pi"), (-2, "-2 pi")])
def test_pi_text_writes_r_pi_as_the_report_does(r, text):
    assert E.pi_text(Fraction(r)) == text


# ------------------------------------------------------------------ Routh-Hurwitz (issue 41: the gimbal extremes)

def _poly_from_roots(r, pair=None):
    """(a1, a2, a3) of (l - r0)(l - r1)(l - r2) for three real roots ``r``, or of (l - r0)(l - re - i im)(l - re + i
    im) for one real root r = (r0,) and ``pair`` = (re, im); exact Fractions."""
    if pair is None:
        r0, r1, r2 = (Fraction(x) for x in r)
        return -(r0 + r1 + r2), r0 * r1 + r0 * r2 + r1 * r2, -r0 * r1 * r2
    r0, (re, im) = Fraction(r[0]), (Fraction(pair[0]), Fraction(pair[1]))
    n = re * re + im * im
    return -(r0 + 2 * re), 2 * r0 * re + n, -r0 * n


@pytest.mark.parametrize("roots, pair, want", [
    ((-1, -2, -3), None, "asymptotically stable"),
    ((Fraction(-1, 10 ** 30), -2, -3), None, "asymptotically stable"),                # a tiny stable root
    ((Fraction(1, 10 ** 30), -2, -3), None, "unstable"),                              # a3 < 0
    ((-1,), (Fraction(-1, 100), 1000), "asymptotically stable"),
    ((-1,), (Fraction(1, 100), 1000), "unstable"),                                   # a1, a3 > 0, a1 a2 - a3 < 0
    ((-1,), (0, 2), "undecided"),                                                    # a centre: a1 a2 = a3 exactly
    ((0, -2, -3), None, "undecided"),                                                # a zero root: a3 = 0
    ((5, 6, -1), None, "unstable"),                                                  # a1 < 0
    ((-5, -6, 1), None, "unstable"),                                                 # a3 < 0 only
], ids=["stable", "tiny stable", "tiny positive", "stable spiral", "spiral out", "centre", "zero", "trace > 0",
        "one positive"])
def test_routh_hurwitz_decides_as_the_roots_do(roots, pair, want):
    """Exact coefficients from known roots: the verdict is the sign of the largest real part, and 'undecided'
    only where a real part is 0 exactly."""
    with working_precision(64):
        a = _poly_from_roots(roots, pair)
        got = E.routh_hurwitz(*(arb(fmpq(x.numerator, x.denominator)) for x in a))
    assert got == want, (roots, pair, a)


def test_routh_hurwitz_on_balls_decides_only_certain_signs():
    with working_precision(64):
        # a1 a2 - a3 = 1 +- 2: not separated from 0; a3 +- 2 around 1: not separated
        assert E.routh_hurwitz(arb(1), arb(2), arb(1) + arb(0, 2)) == "undecided"
        assert E.routh_hurwitz(arb(1), arb(2) + arb(0, 3), arb(1)) == "undecided"
        assert E.routh_hurwitz(arb(1), arb(2), arb("inf")) == "undecided"
        assert E.routh_hurwitz(arb(1), arb(2), arb("nan")) == "undecided"
        assert E.routh_hurwitz(arb(-1) + arb(0, "0.5"), arb(2) + arb(0, 10), arb(0, 10)) == "unstable"


def test_the_characteristic_coefficients_are_flints_on_exact_matrices():
    """Against fmpq_mat.charpoly on random exact matrices (and zeros kept)."""
    import random
    from flint import fmpq_mat
    rng = random.Random(41)
    with working_precision(64):
        for _ in range(25):
            M = [[fmpq(rng.randint(-99, 99), rng.choice((1, 2, 4, 8))) if rng.random() < 0.7 else fmpq(0) for _ in range(3)]
                 for _ in range(3)]
            want = fmpq_mat(M).charpoly().coeffs()[::-1][1:]          # a1, a2, a3
            got = E.characteristic_coefficients([[arb(x) for x in row] for row in M])
            for g_, w in zip(got, want):
                assert g_.is_exact() and g_ == arb(w)           # dyadic entries: every product exact


EXTREMES = {"H = 1e300": {"H": "1e300"}, "a = 1e-300": {"a": "1e-300"}}


@pytest.mark.parametrize("which", list(EXTREMES))
def test_the_gimbal_extremes_are_classified_at_64_bits(which):
    """H = 1e300 and a = 1e-300 (the eigenvalues separate only at 1024-2048 bits): every equilibrium decided at
    64 bits, those off cos x2 = 0 asymptotically stable by Routh-Hurwitz, whose coefficients contain the closed
    forms at x1 = 0, x2 = j pi (D = A0, cos^2 = 1): a1 = k/A0, a2 = H^2/(A0 B0), a3 = a H/(A0 B0), computed in
    mpmath; all of them > 0 with a1 a2 > a3 there, so stable is the truth."""
    params = _params("paper (no root of h)") | EXTREMES[which]
    g = _gimbal(params)
    with working_precision(64):
        eq = E.equilibria(g)
    assert eq.complete and [p.stability for p in eq.points].count("undecided") == 0
    with mpmath.workdps(30):
        mg = MpGimbal(params)
        a1, a2, a3 = mg.k / mg.A0, mg.H ** 2 / (mg.A0 * mg.B0), mg.a * mg.H / (mg.A0 * mg.B0)
        assert a1 > 0 and a3 > 0 and a1 * a2 > a3
        for p in eq.points:
            if p.case == COS_CASE:
                assert p.hurwitz is None and p.stability == "unstable"
                continue
            assert p.stability == "asymptotically stable" and p.hurwitz is not None
            for ball, ref in zip(p.hurwitz, (a1, a2, a3)):
                assert contains_mp(ball, ref), (ball, ref)


def _extreme_rows(params):
    from rigor_gyro.kinds.lyapunov.claim_context import ClaimContext as _Ctx
    from rigor_gyro.kinds.lyapunov.claims import _equilibria_claim
    model = validate(dataclasses.replace(load_scene("agafonov2013"), parameters=params))
    with working_precision(64):
        ctx = _Ctx(model, 64)
        claim = _equilibria_claim(ctx, None, None)
    return model.gimbal, ctx.witnesses["equilibria"]["pieces"], claim


def test_the_checker_re_decides_a_routh_hurwitz_stability_and_rejects_tampered_rows():
    from rigor_gyro.kinds.lyapunov import check as lc
    g, pieces, claim = _extreme_rows(_params("paper (no root of h)") | {"H": "1e300"})
    rows = claim.details["equilibria"]
    assert claim.status.value == "proved" and "Routh-Hurwitz" in claim.reason
    assert sum("routh_hurwitz" in r for r in rows) == 3
    with working_precision(128):
        ok, msg = lc._check_equilibria(g, pieces, rows)
        assert ok, msg
        i = next(i for i, r in enumerate(rows) if "routh_hurwitz" in r)
        for key, text in (("a3", "[-1.8747657e+300, -1.8747656e+300]"), ("a1", "0.5"), ("a2", "junk")):
            bad = [dict(r) for r in rows]
            bad[i] = dict(bad[i], routh_hurwitz=dict(bad[i]["routh_hurwitz"], **{key: text}))
            ok, msg = lc._check_equilibria(g, pieces, bad)
            assert not ok and "Routh-Hurwitz coefficient " + key in msg, (key, msg)
        # the stored stability must follow from the checker's coefficients (not only from classify's)
        real = lc.classify_equilibrium

        def planted(g_, e):
            real(g_, e)
            if e.hurwitz is not None:
                e.stability = "unstable"
        bad = [dict(r) for r in rows]
        bad[i] = dict(bad[i], stability="unstable")
        lc.classify_equilibrium = planted
        try:
            ok, msg = lc._check_equilibria(g, pieces, bad)
        finally:
            lc.classify_equilibrium = real
        assert not ok and "do not decide 'unstable'" in msg, msg
