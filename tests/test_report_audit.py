"""The report's audit section (issue 39): counts by class, the misprints found, the paper's arithmetic by
table, the unexplained with their nearest chain value."""
from __future__ import annotations

import pytest

from rigor_gyro.core.audit_report import audit_section, table_of as _table_of
from rigor_gyro.report import AUDIT_TABLES


@pytest.fixture(scope="module")
def relay_rows():
    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import load_scene
    return prove_scene(load_scene("roitenberg1947_b2over15")).to_json()["paper"]


def test_the_audit_opens_with_counts_then_misprints_then_arithmetic_then_unexplained(relay_rows):
    text = "\n".join(audit_section(relay_rows, tables=AUDIT_TABLES))
    heads = [text.index(h) for h in ("rows:**", "### Misprints found", "paper's arithmetic, by table",
                                     "unexplained: no chain")]
    assert heads == sorted(heads)
    assert "`D1`: **digit-substituted**: 0.0447756 -> 0.0417756" in text
    assert "`b5,1`: **digit-substituted**: -0.45 -> -0.15" in text and "h54" in text
    # a silent correction shows its reading
    assert "`reading: Table 1, second column c31..c35`: c31 = 0" in text and "-> c51 .. c55" in text
    assert "- **Table 3 (b of (16))**" in text and "nearest chain value" in text


def test_every_silent_correction_of_the_issue_is_a_row(relay_rows):
    from rigor_gyro.kinds.periodic_orbit.paper_silent import SILENT_IDS
    ids = {r["id"] for r in relay_rows}
    assert set(SILENT_IDS) <= ids
    b = next(r for r in relay_rows if r["id"] == "reading: B")
    assert b["class"] == "misprint-reading" and "2/15" in b["reading"]


def test_table_of():
    def table_of(rid):
        return _table_of(rid, AUDIT_TABLES)
    assert table_of("Table 2 t=0.01 alpha") == "Table 2"
    assert table_of("b4,13") == "Table 3 (b of (16))"
    assert table_of("z4 (eps4)") == table_of("k23") == table_of("beta'*") == "Table 4 (x*, z, h, c, k)"
    assert table_of("|lambda2| = |lambda4|") == "the quartic (25) and its roots"
    assert table_of("i sin") == table_of("D1") == "D and the closed form (7)"
    assert table_of("(7) lambda_1+ (Hz)") == "other rows"
