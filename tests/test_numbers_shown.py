"""Numbers shown as what they are (issue 35, part 3): an exact number is never printed through a float,
a certified bound is rounded outward, a certified quantity from Python shows its certified digits.
"""
import dataclasses
from fractions import Fraction

import pytest

from rigor_gyro import load_scene
from rigor_gyro.core.balls import interval_text, rational_text, width_text
from rigor_gyro.margins.threshold import find_threshold


@pytest.mark.parametrize("q, text", [
    (Fraction(1, 5), "0.2"), (Fraction(4, 5), "0.8"), (Fraction(3, 40), "0.075"), (Fraction(-5, 2), "-2.5"),
    (Fraction(1200), "1200"), (Fraction(1, 3), "1/3"), (Fraction(-2, 7), "-2/7"), (Fraction(1, 10 ** 30), "1e-30"),
    (Fraction(0), "0"),
])
def test_an_exact_number_is_its_exact_decimal_or_its_fraction(q, text):
    assert rational_text(q) == text and Fraction(text) == q


def test_a_bracket_is_exact_when_it_terminates_and_rounded_outward_otherwise():
    assert interval_text(Fraction(1, 5), Fraction(4, 5)) == ("0.2", "0.8", False)
    lo, hi = Fraction(1, 3), Fraction(1, 3) + Fraction(1, 10 ** 9)
    bl, bh, rounded = interval_text(lo, hi)
    assert rounded and Fraction(bl) <= lo < hi <= Fraction(bh)
    assert Fraction(bh) - Fraction(bl) <= Fraction(102, 100) * (hi - lo)      # about 1/100 of the width added
    assert width_text(Fraction(3, 5) / 2 ** 20) == "5.73e-7" and Fraction("5.73e-7") >= Fraction(3, 5) / 2 ** 20


def test_a_thresholds_lines_show_exact_ends_and_an_outward_bracket():
    """The default search of agafonov2013's k (half and twice 0.4: ends 1/5 and 4/5) printed 0.20000000000000001
    and 0.80000000000000004, and its bracket as 17-digit floats."""
    s = load_scene("agafonov2013")
    scene = dataclasses.replace(s, claims_only=["damping_condition"])
    res = find_threshold(scene, "k", claim="damping_condition", width="1e-3")
    assert (res.lo, res.hi) == (Fraction(1, 5), Fraction(4, 5)) and res.certified
    line = res.lines()[0]
    assert "0000000000" not in line and "e-" not in line.split("(width")[0]
    p, r = res.proved_at, res.refuted_at
    assert f"proved at k = {rational_text(p)}, refuted at k = {rational_text(r)}" in line
    l, h = res.bracket()
    bl, bh, rounded = interval_text(l, h)
    assert f"changes in [{bl}, {bh}]" in line and Fraction(bl) <= l < h <= Fraction(bh)
    assert res.to_json()["bracket_decimal"] == [bl, bh]
    stopped = find_threshold(scene, "k", claim="damping_condition", lo="0.3", hi="1/3")
    assert not stopped.certified and "[0.3, 1/3]" in stopped.lines()[0]
    assert "k = 0.3 and" in stopped.stopped and "k = 1/3;" in stopped.stopped
