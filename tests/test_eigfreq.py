"""The eigenfrequency scene (Rudenko 1976): the example's claims, the audit, bad input."""
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import certainly_lt, certainly_positive, working_precision
from rigor_gyro.certificate import AuditStatus, Status
from rigor_gyro.kinds.eigenfrequencies.claims import characteristic_quartic
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene, parse_scene

from .reference_values import REFERENCE

#: the reference values carry 50 significant digits: trust them to 1e-45 relative
REF_REL_TOL = arb("1e-45")


@pytest.fixture(scope="module")
def cert():
    return prove_scene(load_scene("rudenko1976"))


def test_every_claim_of_the_example_is_proved(cert):
    assert cert.verdict is Status.PROVED
    ids = [c.id for c in cert.claims]
    assert ids == ["roots", "nu_ordering", "branches", "nu_bounds", "bracket_1", "bracket_2", "bracket_3",
                   "bracket_4", "approximations"]


def test_roots_contain_reference_values_and_are_tight(cert):
    for row in REFERENCE:
        if row[1] != "eigenfrequencies" or row[3] not in cert.quantities:
            continue
        ball = cert.quantities[row[3]]
        with working_precision(256):
            ref = arb(row[4])
            assert ball.is_finite() and ball.overlaps(ref + arb(0, REF_REL_TOL * abs(ref))), row
    for j in range(1, 5):
        w = cert.quantities[f"omega_{j}"]
        assert certainly_positive(w)
        assert 2 * w.rad() <= arb("1e-30") * w.abs_lower()     # relative width <= 1e-30
    for j in range(1, 4):
        assert certainly_lt(cert.quantities[f"omega_{j}"], cert.quantities[f"omega_{j + 1}"])


def test_quartic_reading_matches_form_2_exactly():
    """Q(w) = (a-b)(b-1)^2 [w N(w) - W D(w)] with N, D the products of (2): check at exact points."""
    a, b, e, W = fmpq(1508, 100), fmpq(6154, 1000), fmpq(1076, 10000), fmpq(629, 1000)
    Q = characteristic_quartic(a, b, e, W)
    assert Q.degree() == 4
    assert Q(fmpq(0)) == W * e                      # lambda = 0: Omega^2 * P2(0) = W * eps
    assert Q(1 / (b - 1)) != 0                      # nu3 is a pole of F, not a root of Q


def test_audit_flags_known_misprints(cert):
    rows = {r.id: r for r in cert.paper}
    assert rows["(1) factor of the second product"].status is AuditStatus.MISPRINT
    assert rows["(7) lambda_1+ (Hz)"].status is AuditStatus.MISPRINT
    assert rows["(7) lambda_1- (Hz)"].status is AuditStatus.AGREES
    assert rows["(10) lambda_4- (Hz)"].status is AuditStatus.MISPRINT
    assert rows["(14) R4 term A2 H^2/A3"].status is AuditStatus.MISPRINT
    assert rows["'exact' values share one Hz scale"].status is AuditStatus.REFUTED
    assert rows["error <= 0.05 for root 2 (Hz)"].status is AuditStatus.REFUTED
    assert rows["error <= 0.05 for root 1 (Hz)"].status is AuditStatus.CONFIRMED


def test_every_printed_number_is_audited(cert):
    printed = {r.printed for r in cert.paper}
    scene = load_scene("rudenko1976")
    for key in ("hz_lower", "hz_upper", "hz_approx", "hz_exact"):
        for x in scene.paper[key]:
            assert x in printed, (key, x)


def _scene(**params):
    body = "\n".join(f'{k} = "{v}"' for k, v in params.items())
    return parse_scene(f'name = "t"\nkind = "eigenfrequencies"\n[parameters]\n{body}\n')


@pytest.mark.parametrize("params, name", [
    (dict(a="15", b="1", eps="0.1", Omega2="0.6"), "'b'"),
    (dict(a="6", b="6.1", eps="0.1", Omega2="0.6"), "'a'"),
    (dict(a="15", b="6", eps="0", Omega2="0.6"), "'eps'"),
    (dict(a="15", b="6", eps="0.1", Omega2="-1"), "'Omega2'"),
    (dict(a="15", b="6", eps="0.1"), "Omega2"),
    (dict(a="15", b="6", eps="0.1", Omega2="0.6", c="1"), "'c'"),
    (dict(a="15", b="6", eps="x", Omega2="0.6"), "'eps'"),
])
def test_bad_input_names_the_parameter(params, name):
    with pytest.raises(ParameterError, match=name):
        prove_scene(_scene(**params))


def test_refuted_ordering_is_a_verdict_not_a_crash():
    """Large eps pushes nu4 past nu5: the paper's ordering fails and is refuted with the witness."""
    cert = prove_scene(_scene(a="3", b="2", eps="50", Omega2="1"))
    c = cert.claim("nu_ordering")
    assert c.status is Status.REFUTED and ">=" in c.reason
    assert cert.claim("roots").status in (Status.PROVED, Status.REFUTED)


def test_a_root_straddling_its_branch_end_is_not_on_the_branch():
    """omega_1's ball reaches past nu1: 'branches' must not be proved (kills 'possibly inside')."""
    from flint import arb
    from rigor_gyro.kinds.eigenfrequencies.claims import _branch_claim
    nus = {k: arb(k) for k in range(1, 7)}
    omegas = [arb(1, arb("0.1")), arb("2.5"), arb("4.5"), arb(7)]
    c = _branch_claim(omegas, nus, True)
    assert c.status is Status.INCONCLUSIVE
    omegas[0] = arb("0.5")
    assert _branch_claim(omegas, nus, True).status is Status.PROVED


def test_nus_are_compared_exactly_in_every_case():
    """nus_exactly_equal decides when two nus (rationals or roots of the quadratics (4)) are one number:
    each branch, with an equal and an unequal case (mutation testing found these branches untested)."""
    from flint import fmpq, fmpq_poly
    from rigor_gyro.kinds.eigenfrequencies.model import _root_index, nus_exactly_equal
    q = fmpq_poly([2, -3, 1])           # (w - 1)(w - 2)
    p = fmpq_poly([6, -5, 1])           # (w - 2)(w - 3): shares the root 2 (q's larger, p's smaller)
    assert _root_index(q, fmpq(1)) == 0 and _root_index(q, fmpq(2)) == 1 and _root_index(q, fmpq(3)) is None
    assert _root_index(fmpq_poly([-6, 1, 1]), fmpq(2)) == 1        # (w - 2)(w + 3): 2 is the larger
    assert _root_index(3 * q, fmpq(1)) == 0 and _root_index(3 * q, fmpq(2)) == 1    # not monic
    assert _root_index(fmpq_poly([-6, -1, 1]), fmpq(-2)) == 0      # (w + 2)(w - 3): -2 is the smaller
    r = lambda x: ("rational", fmpq(x))                               # noqa: E731
    assert nus_exactly_equal(r(2), r(2)) and not nus_exactly_equal(r(2), r(3))
    assert nus_exactly_equal(r(2), ("root", q, 1)) and nus_exactly_equal(("root", q, 1), r(2))
    assert not nus_exactly_equal(r(2), ("root", q, 0)) and not nus_exactly_equal(("root", q, 0), r(5))
    assert nus_exactly_equal(("root", q, 0), ("root", q, 0)) and not nus_exactly_equal(("root", q, 0), ("root", q, 1))
    assert nus_exactly_equal(("root", q, 1), ("root", 3 * q, 1))      # the same quadratic up to a factor
    assert not nus_exactly_equal(("root", q, 1), ("root", 3 * q, 0))
    assert nus_exactly_equal(("root", q, 1), ("root", p, 0))          # the shared root, at its indices
    assert not nus_exactly_equal(("root", q, 0), ("root", p, 0))
    assert not nus_exactly_equal(("root", q, 1), ("root", p, 1))
    assert not nus_exactly_equal(("root", q, 0), ("root", fmpq_poly([-5, 0, 1]), 1))  # coprime


def test_an_approximation_without_a_real_value_is_never_proved():
    """eps = 90 > b = 10: the radicand of (13) for omega_3, omega_4 is negative, so those approximations have
    no real value; the claim stays inconclusive (it must not be proved with two errors missing), and the
    brackets whose radicands are negative are refuted with the radicand as the reason."""
    import dataclasses
    from rigor_gyro import load_scene, prove_scene
    sc = load_scene("rudenko1976")
    sc = dataclasses.replace(sc, name="v", parameters=dict(sc.parameters, a="20", b="10", eps="90", Omega2="1.111"))
    claims = {c.id: c for c in prove_scene(sc).claims}
    ap = claims["approximations"]
    assert ap.status.value == "inconclusive" and "omega_3: approximation not real" in ap.reason
    assert "omega_4: approximation not real" in ap.reason and "omega_2:" in ap.reason
    assert claims["bracket_3"].status.value == "refuted" and claims["bracket_3"].counterexample["not_real"]


def test_hz_values_are_judged_at_the_paper_s_own_scale_interval():
    """The paper's four 'exact' Hz values need different scales sqrt(K3/A3)/(2 pi) at the printed eps; at
    eps = 0.1073 they share the scales [617.7423, 617.8084], which is the Hz scale of every Hz row's paper
    chain (issue 39): an 'exact' value is reproduced by the scales the other three share there (leave one
    out); a bracket's print by scale * sqrt(bound) over the printed inputs (each within its rounding)."""
    data = prove_scene(load_scene("rudenko1976")).to_json()
    rows = {r["id"]: r for r in data["paper"]}
    for j in (1, 2):                                                     # 41.4, 121.5: at eps = 0.1073
        r = rows[f"'exact' lambda_{j} (Hz)"]
        assert r["class"] == "propagated" and "eps = 0.1073" in r["class_reading"]
        assert "other three 'exact' values" in r["class_reading"]
    assert rows["(9) lambda_3- (Hz)"]["class"] == "last-digit"           # 513.4 against [513.49, 513.66]
    assert "[617.7423, 617.8084]" in rows["(9) lambda_3- (Hz)"]["class_reading"]
    r8 = rows["(8) lambda_2- (Hz)"]                                       # 119.5: the linear form of (8)
    assert r8["class"] == "propagated" and "linear form" in r8["class_reading"]
    assert "at eps = 0.1073: [119.4546, 119.4675] Hz (a correct rounding)" in r8["note"]
    r9 = rows["(9) lambda_3+ (Hz)"]                                       # 546: nu4^- and b (nu5 - nu4^-)
    assert r9["class"] == "propagated" and "nu4^-" in r9["class_reading"]
    assert "at the printed eps = 0.1076: [546.3596, 546.4181] Hz (a correct rounding)" in r9["note"]
    for rid in ("(8) lambda_2+ (Hz)", "(13) lambda_2~ (Hz)"):
        assert rows[rid]["class"] == "unexplained", rid                  # 130.4, 128
    r10 = rows["(10) lambda_4+ (Hz)"]                                     # 950.8: eps for eps^2, as (9) prints it
    assert r10["class"] == "propagated" and "eps for eps^2" in r10["class_reading"]
    assert rows["'exact' values share one Hz scale"]["class"] == "assertion-refuted"


@pytest.mark.parametrize("a, b, eps", [("15.08", "6.154", "0.1076"), ("3.5", "1.25", "1.7"), ("40", "19", "0.01")])
def test_the_nu_bounds_are_the_printed_formulas_5(a, b, eps):
    """Each bound of (5) against the printed formula evaluated in mpmath at 40 digits (a mutated formula
    that still brackets its nu would pass the claim; it does not pass this), and the bracket holds."""
    import mpmath
    from flint import fmpq
    from rigor_gyro.kinds.eigenfrequencies.model import Params, nu_bounds
    from fractions import Fraction
    mpmath.mp.dps = 40
    A, B, E = (mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in (a, b, eps))
    ref = {1: (E / (A - B + E * (A - 1)), E / (A - B)),
           2: (E * A / (B * (A - B) + E * (A - 1)), E * A / (B * (A - B))),
           4: ((1 + E) / (B - 1), (1 + E) / (B - 1) + E ** 2 * (A - 1) / ((A - B) * (A - B + E * (A - 1)))),
           6: ((B * B + E) / (B * (B - 1)),
               (B * B + E) / (B * (B - 1)) + E ** 2 * A * (A - 1) / (B * (A - B) * ((A - B) * B + E * (A - 1))))}
    q = lambda x: arb(fmpq(Fraction(x).numerator, Fraction(x).denominator))     # noqa: E731
    with working_precision(128):
        got = nu_bounds(Params(q(a), q(b), q(eps), arb(1)))
        for k, (lo, hi) in ref.items():
            for ball_, r in zip(got[k], (lo, hi)):
                assert certainly_lt(abs(ball_ - arb(mpmath.nstr(r, 38))), arb("1e-30") * (1 + abs(ball_))), (k, r)


def test_the_branch_claim_decides_each_side_of_each_branch():
    """_branch_claim on synthetic enclosures (mutation testing found these cases untested): a root on
    either wrong side of its own branch, a root inside a neighbouring branch, an empty branch (nu4 = nu5
    exactly), missing roots; each decided only from certain comparisons."""
    from rigor_gyro.kinds.eigenfrequencies.claims import _branch_claim
    nus = {1: arb("0.1"), 2: arb("0.2"), 3: arb("0.3"), 4: arb("0.4"), 5: arb("0.5"), 6: arb("0.6")}
    good = [arb("0.05"), arb("0.25"), arb("0.45"), arb("0.7")]
    assert _branch_claim(good, nus, True).status is Status.PROVED

    def outside(omegas, nus=nus, equal=frozenset()):
        c = _branch_claim(omegas, nus, True, equal)
        return c.status, sorted(x["root"] for x in (c.counterexample or {}).get("outside", []))
    assert outside([arb("0.05"), arb("0.15"), arb("0.45"), arb("0.7")]) == (Status.REFUTED, ["omega_2"])   # below nu2
    assert outside([arb("0.05"), arb("0.35"), arb("0.45"), arb("0.7")]) == (Status.REFUTED, ["omega_2"])   # in (nu3, nu4)
    assert outside([arb("0.05"), arb("0.25"), arb("0.55"), arb("0.7")]) == (Status.REFUTED, ["omega_3"])   # in (nu5, nu6)
    assert outside([arb("0.15"), arb("0.25"), arb("0.45"), arb("0.7")]) == (Status.REFUTED, ["omega_1"])   # above nu1
    assert outside([arb("0.05"), arb("0.25"), arb("0.45"), arb("0.55")]) == (Status.REFUTED, ["omega_4"])  # below nu6
    # nu4 = nu5 exactly: (nu4, nu5) is empty, so omega_3 is outside it whatever its ball; omega_4 is not touched
    flat = {**nus, 4: arb("0.45"), 5: arb("0.45")}
    touching = [arb("0.05"), arb("0.25"), arb("0.45") + arb(0).union(arb("1e-20")), arb("0.7")]
    assert outside(touching, flat, {("nu4", "nu5")}) == (Status.REFUTED, ["omega_3"])
    assert _branch_claim(touching, flat, True).status is Status.INCONCLUSIVE          # not known equal: undecided
    assert _branch_claim([], nus, True).status is Status.INCONCLUSIVE
    assert _branch_claim(good, {1: nus[1]}, True).status is Status.INCONCLUSIVE


def test_a_misprinted_exact_hz_value_neither_hides_itself_nor_stretches_the_scales():
    """An 'exact' Hz value 10 times off is judged against the scales the *other* 'exact' values imply (its
    own range is left out), so it stays a decimal shift, and the interval used for the other rows stays
    the consistent one (a hostile review found the hull including each row's own range)."""
    import dataclasses
    sc = load_scene("rudenko1976")
    paper = dict(sc.paper, hz_exact=["41.4", "121.5", "521.5", "9357"])
    rows = {r["id"]: r for r in prove_scene(dataclasses.replace(sc, name="v", paper=paper)).to_json()["paper"]}
    assert rows["'exact' lambda_4 (Hz)"]["class"] == "decimal-shift"
    assert rows["'exact' lambda_3 (Hz)"]["class"] in ("agrees", "propagated")
    assert rows["(9) lambda_3- (Hz)"]["class"] == "propagated"           # still at a consistent scale
    assert "616.2" in rows["(9) lambda_3- (Hz)"]["class_reading"]


def test_the_approximations_are_the_printed_formulas_12_13():
    """approximation(j) against (12) and (13) evaluated in mpmath at the example (a swapped label or formula
    would pass the claim, which only encloses errors; it does not pass this)."""
    import mpmath
    from fractions import Fraction
    from rigor_gyro.kinds.eigenfrequencies.model import Params, approximation
    mpmath.mp.dps = 40
    a, b, e, W = (mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for x in ("15.08", "6.154", "0.1076", "0.629"))
    r3 = (e / (b * (b - 1)) + (b - 1) * W / b) / 2
    root = mpmath.sqrt(r3 ** 2 + (b - 1) * W * (b - e) / b ** 2)
    ref = {1: e * W / (W * (a - b) + e * a * b), 2: (e * (b - 1) * a + W * (a - b)) / ((a - b) * (b - 1) * (b + W)),
           3: b / (b - 1) + r3 - root, 4: b / (b - 1) + r3 + root}
    q = lambda x: arb(fmpq(Fraction(x).numerator, Fraction(x).denominator))     # noqa: E731
    with working_precision(128):
        p = Params(q("15.08"), q("6.154"), q("0.1076"), q("0.629"))
        for j, r in ref.items():
            v = approximation(j, p)
            assert certainly_lt(abs(v - arb(mpmath.nstr(r, 38))), arb("1e-30") * (1 + abs(v))), j


#: the brackets (7)-(10) as the report states them, written out here in mpmath from the readings'
#: text (BRACKETS[j].lo_reading / hi_reading, or the printed formula where it is the reading): the
#: model's cancellation-free forms must be these numbers
_INTENDED = {
    1: ("E*W/((A-B)*W + E*((A-1)*W + A*B))",
        "R - sqrt(R**2 - E*W/((A-B)*L*B**2))",
        {"L": "(B*(B-1) + E)/(B*(B-1))", "R": "(E*A/(B*(A-B) + (A-1)*E) + W/(L*B**2))/2"}),
    2: ("1/(B-1) + (D+R1)/2 - sqrt(((D+R1)/2)**2 + R1*(1/(B-1) - E*A/(B*(A-B))))",
        "(E*A*(B-1) + W*(1+E)*(A-B))/((A-B)*(B-1)*(B + W*(1+E)))",
        {"D": "E/(B*(B-1))", "R1": "A*B**2/((A-B)*(B-1)*W)"}),
    3: ("B/(B-1) + (D+R2)/2 - sqrt((D+R2)**2/4 + R2*(1 - E/(B-1)))",
        "(1+E)/(B-1) + E**2*(A-1)/((A-B)*(A-B+E*(A-1))) + (B-E)/(B + sqrt(W*(B-1)*B))",
        {"D": "E/(B*(B-1))", "R2": "W*(B-1)/B*(B/(B-1) - E/(A-B))/(B/(B-1) - E*A/(B*(A-B)))"}),
    4: ("B/(B-1) + (D+R2)/2 + sqrt((D+R2)**2/4 + R2*(1 - E/(B-1)))",
        "B/(B-1) + R3 + sqrt(R3**2 + W)",
        {"D": "E/(B*(B-1))", "R2": "W*(B-1)/B*(B/(B-1) - E/(A-B))/(B/(B-1) - E*A/(B*(A-B)))",
         "R3": "(E/(B*(B-1)) + E**2*A*(A-1)/(B*(A-B)*((A-B)*B + E*(A-1))) + W)/2"}),
}


@pytest.mark.parametrize("a,b,eps,W", [("15.08", "6.154", "0.1076", "0.629"), ("20", "3", "0.05", "1.5"),
                                       ("9", "2.5", "0.3", "0.2"), ("40", "12", "0.01", "0.03")])
def test_the_intended_brackets_are_their_stated_formulas_in_mpmath(a, b, eps, W):
    """bracket(j, p) (the intended reading, what the claims certify) and bracket(j, p, 'printed'), each
    bound against its formula evaluated in mpmath at 40 digits (the printed texts are pinned to the
    functions by test_formula_edits at the paper's parameters; here both readings at four parameter
    sets, so a term that cancels at one point cannot hide)."""
    import mpmath
    from fractions import Fraction
    from flint import fmpq
    from rigor_gyro.kinds.eigenfrequencies.model import EDIT_FORMULAS, Params, bracket
    mpmath.mp.dps = 40
    vals = {k: mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator for k, x in zip("ABEW", (a, b, eps, W))}

    def ev(text, defs):
        scope = dict(vals, sqrt=mpmath.sqrt)
        for name, body in defs.items():
            scope[name] = eval(body, {}, scope)
        return eval(text, {}, scope)

    q = lambda x: arb(fmpq(Fraction(x).numerator, Fraction(x).denominator))     # noqa: E731
    with working_precision(128):
        p = Params(q(a), q(b), q(eps), q(W))
        for j, (lo_text, hi_text, defs) in _INTENDED.items():
            for got, text in zip(bracket(j, p), (lo_text, hi_text)):
                r = ev(text, defs)
                assert certainly_lt(abs(got - arb(mpmath.nstr(r, 38))), arb("1e-30") * (1 + abs(got))), (j, text)
            for got, kind in zip(bracket(j, p, "printed"), ("lower", "upper")):
                text, pdefs = EDIT_FORMULAS[(kind, j)]
                pdefs = {k: v.replace("eps", "E").replace("a", "A").replace("b", "B") for k, v in pdefs.items()}
                r = ev(text.replace("eps", "E").replace("a", "A").replace("b", "B"), pdefs)
                assert certainly_lt(abs(got - arb(mpmath.nstr(r, 38))), arb("1e-30") * (1 + abs(got))), (j, kind)


def test_a_certainly_negative_radicand_is_not_real_with_its_bounds_in_the_message():
    from rigor_gyro.kinds.eigenfrequencies.model import NotReal, _sqrt
    with working_precision(64):
        with pytest.raises(NotReal) as e:
            _sqrt(arb("-2.5") + arb(0, arb("1e-12")), "(7) upper")
        assert str(e.value) == "(7) upper: radicand in [-2.5000001, -2.4999999] is negative"
        assert e.value.radicand.is_finite() and e.value.radicand.contains(arb("-2.5"))
        _sqrt(arb(0, 1), "(7) upper")                                   # undecided: no error (Arb gives a ball
        #                                                                 that decides nothing)
        assert _sqrt(arb(4), "x") == 2


def test_any_positive_hz_scale_is_accepted_and_scales_the_frequencies():
    """hz_scale > 0 is the whole domain condition (a scale below 1 too): freq_hz_j = hz_scale sqrt(omega_j)."""
    import dataclasses
    base = load_scene("rudenko1976")
    for s in ("0.5", "1", "617.5"):
        scene = dataclasses.replace(base, parameters=dict(base.parameters, hz_scale=s))
        c = prove_scene(scene)
        assert c.verdict is Status.PROVED, s
        for j in range(1, 5):
            want = arb(s) * c.quantities[f"omega_{j}"].sqrt()
            f = c.quantities[f"freq_hz_{j}"]
            assert f.is_finite() and want.is_finite() and f.overlaps(want) and f.rad() < 1e-20 * want, (s, j)
