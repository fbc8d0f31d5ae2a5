"""The prover's precision schedule: start where the requested width can be met, double from there."""
from types import SimpleNamespace

from flint import fmpq

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.exact import parse_exact
from rigor_gyro.prover import WIDTH_GUARD_BITS, starting_precision


def test_the_start_is_raised_to_what_the_width_needs():
    m = SimpleNamespace(rel_width=parse_exact("1e-30", "rel_width"))       # 100 bits + guard
    assert starting_precision(m, 64, 4096) == 128
    assert starting_precision(m, 64, 64) == 64                              # never above maxprec
    assert starting_precision(SimpleNamespace(rel_width=fmpq(1, 10 ** 15)), 64, 4096) == 64
    assert starting_precision(SimpleNamespace(rel_width=fmpq(1, 2 ** (64 - WIDTH_GUARD_BITS))), 64, 4096) == 64
    assert starting_precision(SimpleNamespace(rel_width=fmpq(1, 2 ** (65 - WIDTH_GUARD_BITS))), 64, 4096) == 128
    assert starting_precision(SimpleNamespace(), 64, 4096) == 64            # a kind without rel_width
    assert starting_precision(SimpleNamespace(rel_width=parse_exact("1e-300", "r")), 64, 4096) == 1024   # 997 + 8 bits


def test_no_attempt_is_run_that_cannot_meet_the_width():
    cert = prove_scene(load_scene("rudenko1976"))                           # rel_width 1e-30
    assert cert.precisions_tried == [128]
    assert all(c.precision_bits == 128 for c in cert.claims)
