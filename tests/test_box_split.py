"""Box.split by integer cross products (issue 41) chooses the same edge and the same midpoint as the
Fraction rule it replaced: the edge widest relative to the whole box (the first on ties), never a frozen one,
halved at its exact midpoint."""
import random
from fractions import Fraction as F

import pytest

from rigor_gyro.core.boxes import Box


def _fraction_rule(box, whole, frozen=()):
    rel = box.relative_widths(whole)
    names = [n for n in box.names if n not in frozen]
    if not names:
        raise ValueError("every edge of the box is frozen")
    k = max(names, key=lambda n: (rel[n], -box.names.index(n)))
    lo, hi = box.interval(k)
    if rel[k] == 0:
        raise ValueError("a box of points cannot be split")
    mid = (lo + hi) / 2
    return (Box(tuple((n, a, mid) if n == k else (n, a, b) for n, a, b in box.edges)),
            Box(tuple((n, mid, b) if n == k else (n, a, b) for n, a, b in box.edges)))


def test_split_is_the_fraction_rule_on_random_bisection_trees():
    rng = random.Random(41)
    whole = Box.of({"u": (F(-1), F(1)), "s": (F(0), F(1)), "p": (F(1, 3), F(1, 3)), "q": (F(-7, 5), F(22, 7))})
    boxes = [whole]
    for _ in range(1500):
        b = boxes[rng.randrange(len(boxes))]
        frozen = rng.choice([(), ("u",), ("s", "q"), ("u", "s", "q")])
        try:
            want = _fraction_rule(b, whole, frozen)
        except ValueError as e:
            with pytest.raises(ValueError, match=str(e)):
                b.split(whole, frozen)
            continue
        got = b.split(whole, frozen)
        assert got == want
        boxes.extend(got)
    assert len(boxes) > 1000


def test_a_box_of_points_and_an_all_frozen_box_are_not_split():
    pt = Box.of({"a": (F(1, 3), F(1, 3))})
    with pytest.raises(ValueError, match="points"):
        pt.split(pt)
    b = Box.of({"a": (F(0), F(1))})
    with pytest.raises(ValueError, match="frozen"):
        b.split(b, ("a",))
    assert b.split(b) == (Box.of({"a": (F(0), F(1, 2))}), Box.of({"a": (F(1, 2), F(1))}))
