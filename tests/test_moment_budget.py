"""The quadrature budget of expression laws (issue 42 review: laws such as a*tan(x2) or a*x2*log(1 - 4 x2^2)
that pass the [moment] checks made `rigor-gyro prove` run for hours). A budget never decides: when it is
spent, G raises, and the attempt leaves its undecided claims inconclusive, naming the budget; one acb.integral
call is capped (Arb's eval_limit) and a non-finite G stays non-finite (undecided upstream)."""
import json

import pytest
from flint import arb

from rigor_gyro import parse_scene, prove_scene
from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov import moment_expr
from rigor_gyro.kinds.lyapunov.moment_expr import (EVAL_LIMIT, EVAL_LIMIT_PER_BIT, QuadratureBudgetSpent,
                                                   expression_law, quadrature_budget)

A0, C0 = arb(127) / 10, arb(14) / 10


def test_a_spent_budget_raises_and_a_closed_one_does_not():
    law = expression_law({"f": "a*tan(x2)"})
    with working_precision(64):
        with quadrature_budget(law, amount=10) as qb:
            g = law.G(arb(100), A0, C0, arb("0.3"))          # allowed: the budget was not spent yet
            assert g.is_finite() and qb.spent() > 10           # charged with its integrand evaluations
            with pytest.raises(QuadratureBudgetSpent, match="quadrature budget"):
                law.G(arb(100), A0, C0, arb("0.4"))
            assert law.G(arb(100), A0, C0, arb("0.3")) is g    # a memoised value costs nothing
        assert law.budget is None
        assert law.G(arb(100), A0, C0, arb("0.4")).is_finite()  # no budget outside an attempt (boxes, direct use)


def test_one_quadrature_is_capped_and_a_branch_point_stays_undecided():
    """G of a*x2*log(1 - 4 x2^2) at x = 0.52 crosses the branch point 0.5: Arb's default limits let this one
    call run ~3 s; capped, it is bounded and its value is not finite (never a finite wrong number)."""
    law = expression_law({"f": "a*x2*log(1 - 4*x2^2)"})
    with working_precision(64), quadrature_budget(law) as qb:
        g = law.G(arb(100), A0, C0, arb("0.52"))
        assert not g.is_finite()
        assert qb.spent() <= EVAL_LIMIT + 64 * EVAL_LIMIT_PER_BIT + 2000


def test_a_spent_budget_leaves_claims_inconclusive_naming_it(monkeypatch):
    monkeypatch.setattr(moment_expr, "QUADRATURE_BUDGET", 300)
    params = dict(A="2", C="3.3", A1="2.2", B1="2.2", C1="2.8", A2="8.5", H="1e4", k="0.4", a="100",
                  x2_star="pi/6", mu="0.02")
    body = "\n".join(f'{k} = "{v}"' for k, v in params.items())
    text = (f'name = "t"\nkind = "lyapunov"\n[parameters]\n{body}\nmoment = "expression"\n[claims]\n'
            f'only = {json.dumps(["constants", "v_positive"])}\n[moment]\nf = "a*tan(x2)"\n')
    cert = prove_scene(parse_scene(text)).to_json()
    assert cert["verdict"] == "inconclusive"
    assert [c["status"] for c in cert["claims"]] == ["inconclusive", "inconclusive"]
    for c in cert["claims"]:
        assert "quadrature budget" in c["reason"] and "[64] bits" in c["reason"]   # no escalation
