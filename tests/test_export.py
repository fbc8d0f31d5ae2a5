"""A paving's leaves as CSV (rigor_gyro.margins.export)."""
import csv
import io
from fractions import Fraction

from hypothesis import given
from hypothesis import strategies as st

from rigor_gyro.core.boxes import Box, tiles_by_bisection
from rigor_gyro.core.boxes import exact_decimal
from rigor_gyro.margins.export import leaves_csv


@given(st.integers(-10 ** 12, 10 ** 12), st.integers(0, 30), st.integers(0, 30), st.sampled_from([1, 3, 7]))
def test_an_exact_decimal_reads_back_to_the_same_rational(p, twos, fives, odd):
    q = Fraction(p, 2 ** twos * 5 ** fives * odd)
    text = exact_decimal(q)
    assert Fraction(text) == q
    assert ("/" in text) == (q.denominator % 3 == 0 or q.denominator % 7 == 0)


def test_the_csv_rows_tile_the_box_with_every_claims_status():
    from tests.test_paving_check import _mixed
    data = _mixed()
    rows = list(csv.reader(io.StringIO(leaves_csv(data))))
    names = list(data["box"])
    assert rows[0] == [f"{n}_{e}" for n in names for e in ("lo", "hi")] + ["bracket_2", "all"]
    pieces = [Box.of({n: (Fraction(r[2 * i]), Fraction(r[2 * i + 1])) for i, n in enumerate(names)}) for r in rows[1:]]
    assert tiles_by_bisection(Box.from_json(data["box"]), pieces, tuple(data["settings"]["unsplit"]))
    stored = {tuple(tuple(v) for v in b["box"].values()): b["status"] for b in data["claims"][0]["boxes"]}
    for r in rows[1:]:
        key = tuple((r[2 * i], r[2 * i + 1]) for i in range(len(names)))
        want = stored[tuple(tuple(str(Fraction(x)) for x in e) for e in key)]
        assert r[-2] == want and r[-1] == want      # one claim: "all" is its status
