"""Issue 41's work-precision goal for the Lyapunov kind's quantities that lost bits: the three relative gaps
(were 22-26 bits lost to the cancellation of (U - R) / R in balls: now computed exactly, one rounding) and the
x2 extent of the invariant estimate (its bisection stopped 7-11 bits short: now 16 bits above the working
precision). Each at most 10 bits lost at 64 and 256 bits, pinned (no escalation)."""
from __future__ import annotations

import pytest

import dataclasses

from rigor_gyro import load_scene
from rigor_gyro.bench.workprecision import bits_lost, log2_width
from rigor_gyro.prover import prove_scene

QUANTITIES = ("R_direct_relative_gap", "R_max_relative_gap", "R_direct_max_relative_gap", "extent_x2")


@pytest.mark.parametrize("prec", [64, 256])
def test_the_gaps_and_the_x2_extent_lose_at_most_10_bits(prec):
    scene = dataclasses.replace(load_scene("agafonov2013"), name="variant",
                                claims_only=["invariant_estimate", "vdot_direct", "best_mu", "best_mu_direct"])
    q = prove_scene(scene, prec=prec, maxprec=prec).quantities     # the balls, not their stored decimals
    for name in QUANTITIES:
        lost = bits_lost(log2_width(q[name]), prec)
        assert lost is not None and lost <= 10, (name, prec, lost)
