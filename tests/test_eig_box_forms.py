"""Parametric forms over a box (issue 37 part 1): forward-mode AD in balls (core.dual_balls), centred forms and
monotone faces (core.centred_forms), implicit roots (core.implicit_roots), and the eigenfrequency claims'
gaps over boxes (kinds/eigenfrequencies/slack_forms, boxes). Every certified range is checked against
mpmath at sampled points (roots by mpmath.polyroots on the quartic at the exact sampled parameters)."""
import random
from fractions import Fraction as Fr

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.centred_forms import enclose, extreme, sign_over_box
from rigor_gyro.core.dual_balls import Dual, NotDifferentiable, constant, variable
from rigor_gyro.core.implicit_roots import implicit_root
from rigor_gyro.kinds.eigenfrequencies.boxes import box_roots, evaluate_box
from rigor_gyro.kinds.eigenfrequencies.claims import validate
from rigor_gyro.kinds.eigenfrequencies.model import Params, bracket, characteristic_quartic, nu_quadratics
from rigor_gyro.kinds.eigenfrequencies.slack_forms import GapSet, nu_value, quartic_value
from rigor_gyro.scene import Scene

EXAMPLE = {"a": Fr("15.08"), "b": Fr("6.154"), "eps": Fr("0.1076"), "Omega2": Fr("0.629")}


def _box(rel: dict) -> Box:
    return Box(tuple((k, v * (1 - rel.get(k, 0)), v * (1 + rel.get(k, 0))) for k, v in EXAMPLE.items()))


#: the issue's target: a, b, Omega2 at +-1 %, eps at +-2 %
TARGET = _box({"a": Fr(1, 100), "b": Fr(1, 100), "eps": Fr(2, 100), "Omega2": Fr(1, 100)})


def _model(box: Box):
    mid = box.midpoint()
    return validate(Scene(name="t", kind="eigenfrequencies", source="",
                          parameters={k: f"{v.numerator}/{v.denominator}" for k, v in mid.items()}))


def _samples(box: Box, n: int, seed: int = 1):
    rnd = random.Random(seed)
    corners = [{k: (lo if (i >> j) & 1 else hi) for j, (k, lo, hi) in enumerate(box.edges)} for i in range(2)]
    pts = corners + [{k: lo + (hi - lo) * Fr(rnd.randint(0, 1000), 1000) for k, lo, hi in box.edges}
                     for _ in range(n - 2)]
    return pts


def _mp_roots(P) -> list:
    """The quartic's four roots at exact parameters, by mpmath.polyroots (50 digits)."""
    with mpmath.workdps(50):
        Q = characteristic_quartic(*(fmpq(P[k].numerator, P[k].denominator) for k in ("a", "b", "eps", "Omega2")))
        c = [mpmath.mpf(int(x.p)) / int(x.q) for x in reversed(Q.coeffs())]
        return sorted(mpmath.re(r) for r in mpmath.polyroots(c, maxsteps=200, extraprec=200))


def _mp_bracket(j, P):
    with working_precision(200):
        lo, hi = bracket(j, Params(*(arb(fmpq(P[k].numerator, P[k].denominator)) for k in ("a", "b", "eps", "Omega2"))))
        return mpmath.mpf(lo.mid().str(60, radius=False)), mpmath.mpf(hi.mid().str(60, radius=False))


def _inside(ball: arb, x) -> bool:
    return mpmath.mpf(ball.lower().str(40, radius=False)) - mpmath.mpf("1e-35") <= x <= \
        mpmath.mpf(ball.upper().str(40, radius=False)) + mpmath.mpf("1e-35")


# ----------------------------------------------------------------------------- core: Duals

def test_dual_gradients_of_the_bracket_formulas_match_finite_differences():
    with working_precision(300):
        P0 = {k: arb(fmpq(v.numerator, v.denominator)) for k, v in EXAMPLE.items()}
        for j in range(1, 5):
            for end in (0, 1):
                d = bracket(j, Params(*(variable(k, P0[k]) for k in P0)))[end]
                assert isinstance(d, Dual)
                for k in P0:
                    h = arb(10) ** -40
                    up = bracket(j, Params(*(P0[n] + (h if n == k else 0) for n in P0)))[end]
                    dn = bracket(j, Params(*(P0[n] - (h if n == k else 0) for n in P0)))[end]
                    fd = (up - dn) / (2 * h)
                    assert abs(float((fd - d.grad[k]).mid())) < 1e-30, (j, end, k)


def test_a_plain_arb_in_dual_arithmetic_is_refused_and_sqrt_needs_a_positive_ball():
    x = variable("x", arb(2))
    with pytest.raises(TypeError):
        x + arb(1)
    with pytest.raises(TypeError):
        arb(1) * x
    assert (x + 1).grad["x"] == 1 and (3 - x).grad["x"] == -1
    with pytest.raises(NotDifferentiable):
        variable("x", arb(0, 1)).sqrt()
    y = (x * x * x - 4 / x + x ** 2).sqrt()      # at x = 2: sqrt(8 - 2 + 4); d = (12 + 1 + 4) / (2 sqrt 10)
    assert y.grad["x"].overlaps(arb(17) / (2 * arb(10).sqrt())) and y.grad["x"].rad() < 1e-10


# ----------------------------------------------------------------------------- core: centred forms

def _f_example(d):
    x, y = d["x"], d["y"]
    return x * x * y - y / (x + 3) + (x * y + 1).sqrt()


def _f_mp(x, y):
    return x * x * y - y / (x + 3) + mpmath.sqrt(x * y + 1)


def test_centred_enclosure_and_extremes_contain_sampled_values():
    box = Box((("x", Fr(1), Fr(11, 10)), ("y", Fr(2), Fr(21, 10))))
    with working_precision(128):
        enc = enclose(_f_example, box)
        lo, hi = extreme(_f_example, box, -1), extreme(_f_example, box, +1)
    with mpmath.workdps(50):
        vals = [_f_mp(mpmath.mpf(x.numerator) / x.denominator, mpmath.mpf(y.numerator) / y.denominator)
                for x in (Fr(1), Fr(21, 20), Fr(11, 10)) for y in (Fr(2), Fr(41, 20), Fr(21, 10))]
    assert all(_inside(enc.value, v) for v in vals)
    # f increases in x and y on the box: min at the corner (1, 2), max at (1.1, 2.1), exactly
    assert lo.faces == {"x": ("lo", Fr(1)), "y": ("lo", Fr(2))} and hi.faces == {"x": ("hi", Fr(11, 10)), "y": ("hi", Fr(21, 10))}
    assert _inside(lo.value, min(vals)) and _inside(hi.value, max(vals))
    assert lo.value.rad() < 1e-30 and "corner" in lo.text(-1) and "exactly" in lo.text(-1)
    # the centred form is narrower than the naive enclosure
    with working_precision(128):
        naive = _f_example({"x": variable("x", box.ball("x")), "y": variable("y", box.ball("y"))}).value
    assert enc.value.rad() < naive.rad()


def test_sign_over_box_decides_both_ways_and_leaves_a_straddling_box_undecided():
    f = lambda d: d["x"] * d["x"] - 2
    with working_precision(128):
        assert sign_over_box(f, Box((("x", Fr(3, 2), Fr(2)),)))[0] == "positive"
        assert sign_over_box(f, Box((("x", Fr(1), Fr(14, 10)),)))[0] == "negative"
        assert sign_over_box(f, Box((("x", Fr(1), Fr(2)),)))[0] == "undecided"
        # touching zero at a corner: >= 0 holds (not strict), > 0 is undecided
        g = lambda d: d["x"] - 1
        assert sign_over_box(g, Box((("x", Fr(1), Fr(2)),)), strict=False)[0] == "positive"
        assert sign_over_box(g, Box((("x", Fr(1), Fr(2)),)), strict=True)[0] == "undecided"


def test_implicit_root_encloses_the_root_and_its_derivative():
    G = lambda x, q: x * x * x + q["c"] * x - 3
    with working_precision(128):
        r = implicit_root(G, arb(1).union(arb(2)) - arb(1) / 2, {"c": variable("c", arb(1).union(arb(2)))})
    with mpmath.workdps(50):
        for c in (1, mpmath.mpf("1.25"), mpmath.mpf("1.5"), mpmath.mpf("1.75"), 2):
            x = mpmath.findroot(lambda t: t ** 3 + c * t - 3, 1)
            assert _inside(r.value, x)
            assert _inside(r.grad["c"], -x / (3 * x * x + c))


# ----------------------------------------------------------------------------- the eigenfrequency gaps

def test_generic_quartic_and_quadratics_are_the_models_polynomials():
    with working_precision(128):
        for P in _samples(TARGET, 4):
            q = [fmpq(P[k].numerator, P[k].denominator) for k in ("a", "b", "eps", "Omega2")]
            Q, (q14, q26) = characteristic_quartic(*q), nu_quadratics(*q[:3])
            for x in (fmpq(1, 7), fmpq(3, 2)):
                p = Params(*(constant(arb(t)) for t in q))
                assert quartic_value(constant(arb(x)), p).value.contains(arb(Q(x)))
                assert nu_value("14", constant(arb(x)), p).value.contains(arb(q14(x)))
                assert nu_value("26", constant(arb(x)), p).value.contains(arb(q26(x)))


def test_bracket_slacks_over_the_target_box_contain_the_sampled_slacks():
    model = _model(TARGET)
    with working_precision(128):
        roots, _ = box_roots(model, TARGET, nus=False)
        gaps = GapSet(model, TARGET, roots)
        encs = {j: [enclose(f, TARGET) for _, f, _ in gaps.bracket_gaps(j)] for j in range(1, 5)}
        omegas = [enclose(lambda d, j=j: gaps.omega(j, d), TARGET) for j in range(1, 5)]
    for P in _samples(TARGET, 24):
        w = _mp_roots(P)
        for j in range(1, 5):
            lo, hi = _mp_bracket(j, P)
            assert _inside(omegas[j - 1].value, w[j - 1])
            assert _inside(encs[j][0].value, w[j - 1] - lo) and _inside(encs[j][1].value, hi - w[j - 1])


def test_the_target_box_decides_the_ordering_and_brackets_at_once():
    """The issue's target box: nu_ordering (undecided on it before) and every bracket proved by one box
    evaluation; the reasons name how (centred form, monotone faces)."""
    model = _model(TARGET)
    with working_precision(128):
        out = evaluate_box(model, TARGET, ["roots", "nu_ordering", "branches", "bracket_1", "bracket_2", "bracket_3",
                                           "bracket_4"])
    assert {k: v[0] for k, v in out.items()} == dict.fromkeys(out, "proved")
    assert "parametric form" in out["nu_ordering"][1] and "centred form" in out["nu_ordering"][1]


def _b2(edges: dict):
    """A box of (eps, Omega2) edges with a, b of the example (an edge lo == hi is a point)."""
    box = Box(tuple((k, lo, hi) for k, (lo, hi) in edges.items() if lo != hi))
    mid = {k: (lo + hi) / 2 for k, (lo, hi) in edges.items()}
    model = validate(Scene(name="t", kind="eigenfrequencies", source="", parameters={
        "a": "15.08", "b": "6.154", **{k: f"{v.numerator}/{v.denominator}" for k, v in mid.items()}}))
    return model, box


EPS = (Fr(1076, 10000), Fr(1076, 10000))


@pytest.mark.parametrize("edges, status", [
    ({"eps": (Fr(1, 10), Fr(11, 100)), "Omega2": (Fr(5, 100), Fr(6, 100))}, "proved"),   # beside the boundary
    ({"eps": EPS, "Omega2": (Fr(6, 1000), Fr(7, 1000))}, "refuted"),                     # fails everywhere
])
def test_bracket_2_decided_by_the_parametric_form_beside_its_boundary(edges, status):
    model, box = _b2(edges)
    with working_precision(128):
        st, why = evaluate_box(model, box, ["bracket_2"])["bracket_2"]
    assert st == status and "parametric form" in why, why
    for e in sorted(set(edges["eps"])):
        for w in (edges["Omega2"][0], sum(edges["Omega2"]) / 2, edges["Omega2"][1]):
            P = {"a": Fr("15.08"), "b": Fr("6.154"), "eps": e, "Omega2": w}
            lo, hi = _mp_bracket(2, P)
            assert (lo <= _mp_roots(P)[1] <= hi) == (status == "proved")


def test_a_box_straddling_the_bracket_2_boundary_is_undecided():
    """omega_2 crosses the lower end of (8) between Omega2 = 0.006 and 0.008 (eps = 0.1076): a box that
    contains the crossing must stay undecided (neither sign holds on all of it)."""
    model, box = _b2({"eps": EPS, "Omega2": (Fr(6, 1000), Fr(8, 1000))})
    P = lambda w: {"a": Fr("15.08"), "b": Fr("6.154"), "eps": EPS[0], "Omega2": w}
    signs = {(_mp_roots(P(w))[1] >= _mp_bracket(2, P(w))[0]) for w in (Fr(6, 1000), Fr(8, 1000))}
    assert signs == {True, False}
    with working_precision(128):
        assert evaluate_box(model, box, ["bracket_2"])["bracket_2"][0] == "undecided"


def test_parametric_newton_encloses_every_members_root_and_refuses_a_double_root():
    """x^2 - c for c in [2, 3]: the ball holds sqrt(c) for every c (the ends lie outside the linear predictor's
    range, so the Newton radius r is needed); x^2 - c for c in [-1, 1] has a double root at c = 0: None."""
    from rigor_gyro.core.implicit_roots import parametric_newton
    G = lambda x, q: x * x - q["c"]
    with working_precision(128):
        r = parametric_newton(G, arb("1.58"), {"c": variable("c", arb(2).union(arb(3)))})
        assert r is not None
        assert r.contains(arb(2).sqrt()) and r.contains(arb(3).sqrt()) and r.rad() < 0.2
        assert parametric_newton(G, arb("0.1"), {"c": variable("c", arb(-1).union(arb(1)))}) is None


# ----------------------------------------------------------------------------- (5) on a whole box by the theorem

def test_nu_bounds_on_a_wide_box_in_one_evaluation_and_mpmath_samples_agree():
    """(5) holds for every a > b > 1, eps > 0: a box far wider than any tolerance is proved in one evaluation,
    citing the theorem, and at sampled members the nus (mpmath roots of the quadratics (4), 50 digits) lie
    inside the bounds (5) evaluated at 200 bits."""
    from rigor_gyro.kinds.eigenfrequencies.model import nu_bounds
    box = Box((("a", Fr(10), Fr(20)), ("b", Fr(2), Fr(9)), ("eps", Fr(1, 100), Fr(2)), ("Omega2", Fr(1, 10), Fr(5))))
    with working_precision(128):
        st, why = evaluate_box(_model(box), box, ["nu_bounds"])["nu_bounds"]
    assert st == "proved" and "for every a > b > 1, eps > 0" in why
    for P in _samples(box, 12, seed=5):
        a, b, e = (fmpq(P[k].numerator, P[k].denominator) for k in ("a", "b", "eps"))
        with working_precision(200):
            bounds = nu_bounds(Params(*(arb(x) for x in (a, b, e)), arb(1)))
        for k, q in zip((1, 2), nu_quadratics(a, b, e)):
            with mpmath.workdps(50):
                c = [mpmath.mpf(int(x.p)) / int(x.q) for x in reversed(q.coeffs())]
                small, large = sorted(mpmath.re(r) for r in mpmath.polyroots(c, maxsteps=200, extraprec=100))
            for nu, j in ((small, k), (large, {1: 4, 2: 6}[k])):
                lo, hi = bounds[j]
                assert _inside(lo.union(hi), nu), (P, j)


def test_nu_bounds_by_the_theorem_only_where_the_box_lies_in_its_region():
    """A box reaching a <= b (outside the theorem's a > b > 1) is not proved by the theorem: the enclosures
    decide, or leave it undecided."""
    box = Box((("a", Fr(6), Fr(7)), ("b", Fr(5), Fr(6)), ("eps", Fr(1, 10), Fr(1, 5)), ("Omega2", Fr(1, 2), Fr(1))))
    with working_precision(128):
        st, why = evaluate_box(_model(Box((("a", Fr(7), Fr(7)), ("b", Fr(5), Fr(5)), ("eps", Fr(1, 10), Fr(1, 10)),
                                           ("Omega2", Fr(1, 2), Fr(1, 2))))), box, ["nu_bounds"])["nu_bounds"]
    assert "for every a > b > 1, eps > 0" not in why
