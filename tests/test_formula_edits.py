"""Single edits of a printed formula (core.formula_edits) and their use by the audits."""
import pytest
from flint import arb, fmpq
from hypothesis import given
from hypothesis import strategies as st

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.formula_edits import evaluate, search_single_edits, single_edits


def _val(text, env):
    return evaluate(text, env)


def test_every_kind_of_edit_is_made_once_per_site():
    kinds = {}
    for e in single_edits("a * b ** 2 / sqrt(c) - sin(a)"):
        kinds.setdefault(e.kind, []).append(e.formula)
    assert "a * b ** 2 / sqrt(c) + sin(a)" in kinds["sign"]
    assert {"a * b ** 1 / sqrt(c) - sin(a)", "a * b ** 3 / sqrt(c) - sin(a)"} <= set(kinds["exponent"])
    assert "a * b ** 2 * sqrt(c) - sin(a)" in kinds["moved"]              # the denominator moved up
    assert "b ** 2 / a / sqrt(c) - sin(a)" in kinds["moved"]              # a moved down
    assert "1 * b ** 2 / sqrt(c) - sin(a)" in kinds["factor-dropped"]
    assert "a * b ** 2 / sqrt(c) - cos(a)" in kinds["label-swap"]
    assert "b * a ** 2 / sqrt(c) - sin(b)" in kinds["label-swap"]         # a and b exchanged everywhere
    assert "(a * b ** 2 / sqrt(c) - sin(a)) / 2" in kinds["factor-added"]
    assert any("_id(c)" in f for f in kinds["exponent"])                  # the square root removed
    descriptions = [e.description for e in single_edits("a * b + a * b")]
    assert len(descriptions) == len(set(descriptions))                   # two sites, two names (occurrences)


@given(st.integers(1, 50), st.integers(2, 50), st.integers(1, 50))
def test_a_planted_edit_is_found(a, b, c):
    env = {"a": arb(a), "b": arb(b), "c": arb(c)}
    with working_precision(128):
        planted = _val("a * b ** 3 / (c + 1)", env)                      # the misprint: b^3 for b^2
        printed = f"{float(planted.mid()):.6g}"
        r = search_single_edits("a * b ** 2 / (c + 1)", env, printed)
    if "e" in printed:
        return
    found = any(e.description == "b ** 2 -> b ** 3" for e in r.reproducing)
    assert found or r.undecided
    assert all(e.value is not None for e in r.reproducing)


def test_a_print_on_a_rounding_boundary_is_undecided_not_reproduced():
    # sqrt(2) * 0 + x with x = 0.125 +- 1e-30: '0.12' and '0.13' are both possible roundings
    env = {"x": arb("0.125", "1e-30")}
    r = search_single_edits("x * 2", env, "0.13")
    assert all(e.description != "the whole divided by 2" for e in r.reproducing)
    assert r.undecided >= 1


def test_definitions_carry_an_edit_to_every_use():
    env = {"a": arb(3)}
    # D = a^2 - 3 = 6, D + D = 12; the print 24 is D = a^2 + 3 = 12 in both uses (one edit, in D)
    r = search_single_edits("D + D", env, "24", {"D": "a ** 2 - 3"})
    assert r.tried == len(single_edits("D + D")) + len(single_edits("a ** 2 - 3"))
    hits = {e.description for e in r.reproducing}
    assert "in D: a ** 2 - 3 -> a ** 2 + 3" in hits
    assert "the whole times 2" in hits                                   # several edits: all reported
    for e in r.reproducing:
        assert e.value.is_finite() and e.value.overlaps(arb(24))


def test_an_edit_in_a_definition_gives_the_ball_of_a_whole_re_evaluation():
    """The search reuses the unedited definitions an edit does not reach and shares an edited definition's
    subtrees: each edit's value is still the very ball of evaluating every definition afresh."""
    env = {"a": arb(3) / 7, "b": arb(5) / 11, "c": arb(2) / 3}
    defs = {"D": "a ** 2 - b * c", "E": "sqrt(a + c) / b", "F": "D * c + a", "G": "b - c"}
    text = "(D + E) * F / G"
    with working_precision(64):
        r = search_single_edits(text, env, "0.5", defs)
        seen = 0
        for where, body in defs.items():
            for e in single_edits(body):
                scope = dict(env)
                for name, t in defs.items():
                    scope[name] = evaluate(e.tree if name == where else t, scope)
                want = evaluate(text, scope)
                got = [x for x in r.reproducing if x.formula == f"{where} = {e.formula}"]
                assert all(x.value.mid() == want.mid() and x.value.rad() == want.rad() for x in got)
                seen += 1
        # every value the search computed (reproducing or not) is compared through a print that each one gives
        for where, body in defs.items():
            for e in single_edits(body)[:6]:
                scope = dict(env)
                for name, t in defs.items():
                    scope[name] = evaluate(e.tree if name == where else t, scope)
                want = evaluate(text, scope)
                if not want.is_finite():
                    continue
                printed = f"{float(want.mid()):.4g}"
                hit = search_single_edits(text, env, printed, defs)
                mine = [x for x in hit.reproducing if x.formula == f"{where} = {e.formula}"]
                assert all(x.value.mid() == want.mid() and x.value.rad() == want.rad() for x in mine)
                assert mine or hit.undecided or "e" in printed
    assert seen == sum(len(single_edits(b)) for b in defs.values())


def test_the_audit_formula_texts_are_the_model_functions():
    from rigor_gyro.kinds.eigenfrequencies.claims import validate
    from rigor_gyro.kinds.eigenfrequencies.model import BRACKETS, EDIT_FORMULAS, approximation
    m = validate(load_scene("rudenko1976"))
    with working_precision(128):
        p = tuple(arb(m.q(k)) for k in ("a", "b", "eps", "Omega2"))
        env = dict(zip(("a", "b", "eps", "W"), p))
        for (kind, j), (text, defs) in EDIT_FORMULAS.items():
            scope = dict(env)
            for name, body in defs.items():
                scope[name] = _val(body, scope)
            v = _val(text, scope)
            ref = (BRACKETS[j].lo(p) if kind == "lower" else BRACKETS[j].hi(p) if kind == "upper"
                   else approximation(j, p))
            assert v.is_finite() and ref.is_finite() and v.overlaps(ref) and v.rad() < 1e-30 * (1 + abs(ref).upper()), (kind, j)


def test_the_lyapunov_formula_texts_are_r1_and_r2():
    from rigor_gyro.kinds.lyapunov.paper import EDIT_FORMULAS, _edit_inputs
    cert = prove_scene(load_scene("agafonov2013"))
    from rigor_gyro.kinds.lyapunov.claims import validate
    g = validate(load_scene("agafonov2013")).gimbal
    with working_precision(128):
        env = _edit_inputs(g, arb(fmpq(1000, 127)))                      # m = a / A0 for the sine law
        for key in ("R1", "R2"):
            _, text, defs = EDIT_FORMULAS[key]
            scope = dict(env)
            for name, body in defs.items():
                scope[name] = _val(body, scope)
            v = _val(text, scope)
            assert v.is_finite() and cert.quantities[key].is_finite() and v.overlaps(cert.quantities[key]), key


@pytest.mark.parametrize("scene,row,expect", [
    ("agafonov2013", "R2", None),                                          # no single edit of (14) gives 0.0124
    ("rudenko1976", "(10) lambda_4+ (Hz)", "exponent: in R3: eps ** 2 -> eps ** 1"),
])
def test_the_audits_report_the_search(scene, row, expect):
    cert = prove_scene(load_scene(scene))
    r = next(x for x in cert.paper if x.id == row)
    fe = r.formula_edits
    assert fe is not None and fe["tried"] > 40
    if expect is None:
        assert fe["reproducing"] == [] and "none reproduces" in fe["summary"]
    else:
        assert expect in fe["reproducing"]
    assert fe["summary"] in r.note


def test_the_printer_reads_back_to_the_same_formula():
    import ast

    from rigor_gyro.core.formula_edits import parse_formula, show
    from rigor_gyro.kinds.eigenfrequencies.model import EDIT_FORMULAS
    from rigor_gyro.kinds.lyapunov.paper import EDIT_FORMULAS as LYAP
    texts = [t for t, d in EDIT_FORMULAS.values()] + [x for t, d in EDIT_FORMULAS.values() for x in d.values()]
    texts += [x for _, t, d in LYAP.values() for x in [t, *d.values()]]
    texts += ["-(a + b) ** 2", "(-a) ** 2", "a - (b - c)", "a / (b / c)", "a - -b", "-a * b"]
    for t in texts:
        tree = parse_formula(t)
        assert show(tree) == ast.unparse(ast.parse(t, mode="eval")), t
        assert parse_formula(show(tree)) == tree, t


def test_the_json_names_each_reproducing_edit_by_its_formula():
    r = search_single_edits("D + D", {"a": arb(3)}, "24", {"D": "a ** 2 - 3"})
    out = r.to_json("(x)", "as a test")
    assert len(out["reproducing_formulas"]) == len(out["reproducing"])
    assert "D = a ** 2 + 3" in out["reproducing_formulas"]
    assert "(reproducing: as a test)" in out["summary"]


def test_an_hz_edit_reproduces_only_at_a_scale_certainly_inside_the_papers_interval():
    """The eigenfrequency rows: an edit counts only with an exact scale certainly inside the (inner)
    interval of the paper's implied scales at which the edited value is a correct rounding."""
    from rigor_gyro.kinds.eigenfrequencies import paper as P
    from rigor_gyro.core.outcome import AuditRow, AuditStatus
    with working_precision(128):
        w = arb(2)
        lo, hi = P._scale_inner("100", w)              # scales s with s sqrt(2) in [99.95, 100.05]
        assert lo < hi
        hull = lo.union(hi)
        row = AuditRow("r", "100", "", None, AuditStatus.DISAGREES, "")
        # a formula that is exactly 2: reproduces at the scales of the interval
        out = P._with_edits(row, ("approx", 1), "(t)", "100", (fmpq(1), fmpq(1), fmpq(1), fmpq(1)),
                            arb(1), hull, (lo, hi))
        assert out.formula_edits is not None
        # an interval pushed just outside: never a reproduction
        far = (hi + 1, hi + 2)
        row2 = AuditRow("r", "100", "", None, AuditStatus.DISAGREES, "")
        out2 = P._with_edits(row2, ("approx", 1), "(t)", "100", (fmpq(1), fmpq(1), fmpq(1), fmpq(1)),
                             arb(1), far[0].union(far[1]), far)
        assert out2.formula_edits["reproducing"] == []


def test_a_propagated_hz_value_needs_a_scale_certainly_inside_the_inner_interval():
    """`_at_paper_scale` (the `propagated` class) and the edit search share `_scale_reproduces`: the
    scale must be exact, certainly inside the inner interval, and give a correct rounding; an outer
    hull that merely touches the print's scales proves nothing."""
    from rigor_gyro.kinds.eigenfrequencies import paper as P
    from rigor_gyro.core.outcome import AuditRow, AuditStatus
    with working_precision(128):
        w = arb(2)
        lo, hi = P._scale_inner("100", w)
        m, a, b = P._scale_reproduces("100", w, (lo, hi))
        assert lo <= m <= hi and a <= m <= b
        assert P._scale_reproduces("100", w, (hi + 1, hi + 2)) is None
        assert P._scale_reproduces("100", arb(-1), (lo, hi)) is None
        row = AuditRow("r", "100", "", None, AuditStatus.DISAGREES, "")
        out = P._at_paper_scale(row, "100", w, (lo, hi), lo.union(hi))
        assert out.propagated is not None and "hz_scale =" in out.propagated_from
        # the outer hull reaches the print's scales, the inner interval does not: not propagated
        row2 = AuditRow("r", "100", "", None, AuditStatus.DISAGREES, "")
        out2 = P._at_paper_scale(row2, "100", w, (hi + 1, hi + 2), lo.union(hi + 2))
        assert out2.propagated is None
        assert P._inner_of([]) is None
        assert P._inner_of([(arb(1), arb(2)), (arb(3), arb(5))]) == (arb(1), arb(5))
