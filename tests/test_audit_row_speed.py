"""The memoised audit of a print and the stored ends of an audit row are the unmemoised ones (issue 41)."""
from __future__ import annotations

import random

from flint import arb

from rigor_gyro.core import audit
from rigor_gyro.core.balls import Quantity, quantity, working_precision
from rigor_gyro.core.outcome import AuditRow, AuditStatus


def _balls(n: int = 200):
    rnd = random.Random(41)
    for _ in range(n):
        mid = rnd.uniform(-2, 2) * 10 ** rnd.randint(-8, 6)
        yield arb(mid, abs(mid) * 10 ** -rnd.randint(2, 14))


def test_the_memoised_audit_of_a_print_is_the_unmemoised_one():
    rnd = random.Random(7)
    for x in _balls():
        printed = f"{float(x.mid()):.{rnd.randint(1, 9)}g}"
        for prec in (53, 64, 200):
            with working_precision(prec):
                assert audit.audit_printed(printed, x) == audit._audit_printed(printed, x)
                assert audit.audit_printed(printed, x) == audit._audit_printed(printed, x)      # now a hit
    inf = arb("inf")
    assert audit.audit_printed("1.5", inf) == audit._audit_printed("1.5", inf)


def test_the_status_alone_is_the_status_of_the_audit():
    rnd = random.Random(8)
    seen = set()
    for x in _balls():
        printed = f"{float(x.mid()) * (1 + rnd.uniform(-1e-6, 1e-6)):.{rnd.randint(1, 9)}g}"
        with working_precision(rnd.choice((53, 128))):
            st = audit.printed_status(printed, x)
            assert st is audit._audit_printed(printed, x)[0]
            seen.add(st)
    assert {AuditStatus.AGREES, AuditStatus.DISAGREES} <= seen


def test_the_memo_separates_the_precisions():
    audit._AUDITED.clear()
    x = arb(1)
    with working_precision(64):
        audit.audit_printed("1.0", x)
    with working_precision(128):
        audit.audit_printed("1.0", x)
    assert len(audit._AUDITED) == 2


def test_an_audit_rows_stored_ends_are_those_of_quantity():
    for x in list(_balls(100)) + [Quantity.of_exact(__import__("fractions").Fraction(3, 40)), arb("inf")]:
        row = AuditRow("r", "1.0", "", x, AuditStatus.AGREES).to_json()
        q = quantity(x)
        assert (row["lo"], row["hi"]) == (q["lo"], q["hi"])
    assert AuditRow("r", "1.0", "", None, AuditStatus.UNDECIDED).to_json()["lo"] == ""


def test_the_integer_ends_of_a_ball_are_its_exact_ends():
    from fractions import Fraction

    from flint import fmpq

    from rigor_gyro.core.balls import exact_endpoint_integers, exact_endpoints
    rnd = random.Random(3)
    balls = [arb(0), arb(0, 1), arb(5), arb(-3, 2 ** -80), arb(fmpq(1, 3)), arb(2) ** 200 + arb(0, 1)]
    for _ in range(2000):
        m = rnd.uniform(-1, 1) * 10 ** rnd.randint(-30, 30) if rnd.random() > 0.05 else 0
        r = rnd.uniform(0, 1) * 10 ** rnd.randint(-40, 30) if rnd.random() > 0.1 else 0
        balls.append(arb(m, r))
    for prec in (53, 200):
        with working_precision(prec):
            for x in balls:
                ln, ld, hn, hd = exact_endpoint_integers(x)
                assert ld > 0 and hd > 0 and (Fraction(ln, ld), Fraction(hn, hd)) == exact_endpoints(x)


def test_chain_text_rounds_the_exact_ends_outward_at_the_print_place_plus_two():
    from decimal import Decimal
    from fractions import Fraction
    from math import ceil, floor

    from rigor_gyro.core.balls import exact_endpoints
    from rigor_gyro.core.chain_classify import chain_text
    rnd = random.Random(9)
    for x in _balls(500):
        printed = f"{float(x.mid()):.{rnd.randint(1, 8)}f}"
        e = Decimal(printed).as_tuple().exponent - 2
        lo, hi = exact_endpoints(x)
        a = format(Decimal(floor(lo / Fraction(10) ** e)).scaleb(e), "f")
        b = format(Decimal(ceil(hi / Fraction(10) ** e)).scaleb(e), "f")
        assert chain_text(x, printed) == (a if a == b else f"[{a}, {b}]")


def test_quantity_from_integer_ends_is_quantity_from_fractions():
    """decimal_bounds and quantity round the ends, midpoint and radius from integer ratios: the strings of
    the same roundings of the Fraction ends (the form they had before issue 41)."""
    from rigor_gyro.core.balls import _digits_for, _round_decimal, decimal_bounds, exact_endpoints
    rnd = random.Random(11)
    balls = [arb(0), arb(0, 1), arb(-3, 2 ** -80), arb(2) ** 200 + arb(0, 1)]
    for _ in range(1500):
        m = rnd.uniform(-1, 1) * 10 ** rnd.randint(-300, 300) if rnd.random() > 0.05 else 0
        r = abs(m) * 10 ** -rnd.randint(0, 18) if rnd.random() > 0.1 else rnd.random() * 10 ** rnd.randint(-300, 300)
        balls.append(arb(m, r))
    for prec in (53, 200):
        with working_precision(prec):
            for x in balls:
                a, b = exact_endpoints(x)
                for digits in (None, 3, 12):
                    d = digits or _digits_for(x)
                    want = {"lo": _round_decimal(a, d, "down"), "hi": _round_decimal(b, d, "up"),
                            "mid": _round_decimal((a + b) / 2, d, "nearest"),
                            "rad": _round_decimal((b - a) / 2, 3, "up")}
                    assert quantity(x, digits) == want
                    assert decimal_bounds(x, digits) == (want["lo"], want["hi"])
