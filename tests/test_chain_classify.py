"""core.chain_classify: a print against the exact value and the paper's own chain (issue 39)."""
from __future__ import annotations

from flint import arb, fmpq

from rigor_gyro.core.chain_classify import classify_against_chain, decide
from rigor_gyro.core.misprints import classify_row
from rigor_gyro.core.outcome import AuditRow, AuditStatus
from rigor_gyro.core.paper_chain import Chain, Relation, relation_refs, rounding_interval
from fractions import Fraction


def q(s: str) -> arb:
    f = Fraction(s)
    return arb(fmpq(f.numerator, f.denominator))


EXACT = q("0.0417857382")                  # beta sin's exact value (B = 2/15)


def test_a_print_of_the_chain_is_the_papers_arithmetic_however_far_from_the_exact_value():
    c = classify_against_chain("0.0417756", EXACT, Chain(q("0.04177555"), "test"))
    assert c.cls == "propagated" and "paper chain" in c.reading


def test_within_the_slack_is_last_digit_and_beyond_it_unexplained():
    ch = Chain(q("0.0417753"), "test", slack=3)           # the print is 3 units off
    assert classify_against_chain("0.0417756", EXACT, ch).cls == "last-digit"
    ch = Chain(q("0.0417753"), "test", slack=2)
    assert classify_against_chain("0.0417756", EXACT, ch).cls == "unexplained"


def test_an_edit_into_the_chain_is_a_misprint_even_where_the_exact_value_disagrees():
    c = classify_against_chain("0.0447756", EXACT, Chain(q("0.0417756"), "test"))
    assert c.cls == "digit-substituted" and c.intended == "0.0417756"


def test_an_edit_that_reproduces_only_the_exact_value_is_no_evidence():
    """0.0449957 is one substitution from an exact 0.0419957 but three from the chain 0.0417756."""
    c = classify_against_chain("0.0449957", q("0.0419957"), Chain(q("0.0417756"), "test"))
    assert c.cls == "unexplained" and "nearest chain value" in c.reading


def test_agreement_with_the_exact_value_comes_first():
    assert classify_against_chain("0.0417857", EXACT, Chain(q("0.5"), "test")).cls == "agrees"


def test_a_narrowing_identity_that_only_rejects_the_print_leaves_the_computed_chain_to_decide():
    """The identity (another print) says 0.0508353; the print 0.0508374 is 21 units away and no edit lands
    there: the computed chain holds it, so it is the paper's arithmetic."""
    ch = Chain(q("0.0508353"), "test", identity="x + y = 0", computed=q("0.05083741"))
    kind, _, narrowed = decide("0.0508374", ch)
    assert kind == "propagated" and not narrowed


def test_a_narrowing_identity_decides_a_misprint_the_wide_chain_allows():
    wide = q("0.04") + arb(0, q("0.02"))                  # D1's chain from the ill-conditioned (9)
    ch = Chain(q("0.0417756"), "test", identity="D1 = beta sin = h11", computed=wide)
    kind, e, narrowed = decide("0.0447756", ch)
    assert kind == "edit" and e.intended == "0.0417756" and narrowed
    c = classify_against_chain("0.0447756", EXACT, ch)
    assert c.cls == "digit-substituted" and "D1 = beta sin = h11" in c.reading


def test_an_accepted_candidate_and_an_upstream_misprint():
    """A non-evidential edit is a misprint only when the chain carries it as accepted (downstream
    evidence); a print reproduced only by an alternate (an upstream misprint left as printed) is
    propagated-misprint naming that row."""
    wide = q("0.00518") + arb(0, q("0.00006"))
    assert classify_against_chain("0.00548755", q("0.0051888"), Chain(wide, "t")).cls == "unexplained"
    ch = Chain(wide, "t", accepted="0.00518755", evidence="downstream rows reproduce only with it: h41")
    c = classify_against_chain("0.00548755", q("0.0051888"), ch)
    assert c.cls == "digit-substituted" and c.intended == "0.00518755" and "h41" in c.reading
    ch = Chain(q("-0.0741734"), "t", alternates=((q("-0.2133024"), "c15"),))
    c = classify_against_chain("-0.213302", q("-0.2132366"), ch)
    assert c.cls == "propagated-misprint" and c.upstream == "c15"


def test_classify_row_sends_a_chain_to_the_two_reference_classifier_and_writes_schema_classes():
    row = AuditRow("k31", "-0.213302", "r", q("-0.2132366"), AuditStatus.DISAGREES)
    row.propagated = Chain(q("-0.0741734"), "t", alternates=((q("-0.2133024"), "c15"),))
    c = classify_row(row)
    assert c.cls in ("propagated-misprint", "propagated") and "c15" in c.reading


def test_relation_refs_solve_an_identity_for_a_row_from_the_other_prints():
    rel = Relation((("b47", Fraction(1)), ("b412", Fraction(1))), Fraction(0), "b47 + b412 = 0")
    (ref, name), = relation_refs("b47", {"b412": "6.33182"}, [rel], slack=0)
    assert name == "b47 + b412 = 0" and ref.contains(q("-6.331825")) and ref.contains(q("-6.331815"))
    assert relation_refs("b47", {}, [rel]) == []
    r = rounding_interval("0.15")
    assert r.contains(q("0.145")) and r.contains(q("0.155")) and not r.contains(q("0.1551"))
