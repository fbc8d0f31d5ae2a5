"""certificate.dumps_indented writes exactly json.dumps(obj, indent=2, ensure_ascii=False) (issue 41: the
json module's indented encoder was the slow part of writing a 400 kB certificate)."""
import glob
import json
import math
import random

import pytest

from rigor_gyro.certificate import dumps_indented


def _ref(obj):
    return json.dumps(obj, indent=2, ensure_ascii=False)


@pytest.mark.parametrize("path", sorted(glob.glob("proofs/*.json")) + sorted(glob.glob("proofs/**/*.json")))
def test_same_text_as_json_on_every_stored_certificate(path):
    data = json.loads(open(path, encoding="utf-8").read())
    assert dumps_indented(data) == _ref(data)


def _tree(rng, depth):
    kind = rng.randrange(12 if depth < 5 else 8)
    leaves = ["", "a", "ü \u2212 x", 'q"\\\n\t\x01', "\ud7ff", "2/3"]
    if kind == 0:
        return rng.choice(leaves)
    if kind == 1:
        return rng.choice([0, -7, 10 ** 40, True, False, None])
    if kind == 2:
        return rng.choice([0.0, -0.0, 1e-310, 1.5e300, math.inf, -math.inf, math.nan, 0.1, 1 / 3])
    if kind in (3, 4, 5, 6, 7):
        return rng.choice(leaves)
    if kind in (8, 9):
        return [_tree(rng, depth + 1) for _ in range(rng.randrange(4))]
    if kind == 10:
        return tuple(_tree(rng, depth + 1) for _ in range(rng.randrange(3)))
    return {rng.choice(leaves) + str(i): _tree(rng, depth + 1) for i in range(rng.randrange(4))}


def test_same_text_as_json_on_random_trees():
    rng = random.Random(41)
    for _ in range(3000):
        t = _tree(rng, 0)
        assert dumps_indented(t) == _ref(t)


def test_keys_and_types_it_does_not_know_go_to_json():
    assert dumps_indented({1: "a", "b": [1.5, None]}) == _ref({1: "a", "b": [1.5, None]})
    assert dumps_indented({"x": {True: 2}}) == _ref({"x": {True: 2}})

    class S(str):
        pass

    class L(list):
        pass
    v = {"s": S("x"), "l": L([1, "2"])}
    assert dumps_indented(v) == _ref(v)
    with pytest.raises(TypeError):
        dumps_indented({"x": object()})
