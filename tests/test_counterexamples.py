"""Counterexamples searched over the whole box (margins/counterexamples.py, core/halton.py): on the built-in
general eigenfrequency box paved coarsely for bracket (7), the paving's midpoint proofs at its first 16
undecided leaves find nothing, the search finds counterexamples that the point prover refutes far from
them (confirmed independently in mpmath), and the Monte Carlo interval contains an independent float
estimate of the failing fraction."""
from __future__ import annotations

import math
from fractions import Fraction

import pytest

from rigor_gyro.core.boxes import Box
from rigor_gyro.core.halton import halton, points_in_boxes, radical_inverse
from rigor_gyro.margins import counterexamples as cx
from rigor_gyro.margins.paving import box_scene, pave
from rigor_gyro.scene import Scene

A, B = Fraction("15.08"), Fraction("6.154")


def _scene(eps="[0.001, 2]", W="[0.001, 10]", resolution="1/8"):
    return Scene(name="cx", kind="eigenfrequencies", source="test", claims_only=["bracket_1"],
                 parameters={"a": "15.08", "b": "6.154", "eps": eps, "Omega2": W},
                 options={"box_resolution": resolution, "range_boxes": "0"})


@pytest.fixture(scope="module")
def paved():
    bs = box_scene(_scene())
    return bs, pave(bs).claims[0]


# --------------------------------------------------------------------------- independent float / mpmath side

def _bracket7(a, b, e, W, sqrt):
    """(7) in its intended reading, written out again here (floats or mpf)."""
    lo = e * W / ((a - b) * W + e * ((a - 1) * W + a * b))
    lam = (b * (b - 1) + e) / (b * (b - 1))
    r = (e * a / (b * (a - b) + (a - 1) * e) + W / (lam * b * b)) / 2
    q = e * W / ((a - b) * lam * b * b)
    return lo, q / (r + sqrt(r * r - q))


def _fails_mpmath(point: dict[str, str]) -> bool:
    import mpmath
    from rigor_gyro.kinds.eigenfrequencies.approx import approx_roots_mpmath
    with mpmath.workdps(40):
        w1 = approx_roots_mpmath("15.08", "6.154", point["eps"], point["Omega2"], dps=40)[0]
        f = [mpmath.mpf(Fraction(x).numerator) / Fraction(x).denominator
             for x in ("15.08", "6.154", point["eps"], point["Omega2"])]
        lo, hi = _bracket7(*f, mpmath.sqrt)
        return bool(w1 < lo or w1 > hi)


def _float_fraction(box: Box, n: int, seed: int) -> float:
    import numpy as np
    from rigor_gyro.kinds.eigenfrequencies.approx import quartic_coefficients
    rng = np.random.default_rng(seed)
    (_, elo, ehi), (_, wlo, whi) = box.edges
    a, b = float(A), float(B)
    fails = 0
    for e, W in zip(rng.uniform(float(elo), float(ehi), n), rng.uniform(float(wlo), float(whi), n)):
        w1 = min(r.real for r in np.roots(quartic_coefficients(a, b, e, W)))
        lo, hi = _bracket7(a, b, e, W, math.sqrt)
        fails += w1 < lo or w1 > hi
    return fails / n


# --------------------------------------------------------------------------- the Halton points

def test_halton_is_exact_and_volume_weighted():
    assert radical_inverse(6, 2) == Fraction(3, 8) and radical_inverse(5, 3) == Fraction(7, 9)
    assert halton(0, 3) == (0, 0, 0) and halton(1, 2) == (Fraction(1, 2), Fraction(1, 3))
    big = Box.of({"x": (Fraction(0), Fraction(3)), "y": (Fraction(0), Fraction(1))})
    small = Box.of({"x": (Fraction(3), Fraction(4)), "y": (Fraction(0), Fraction(1))})
    pts = list(points_in_boxes([big, small], 256))
    assert all(cx.contains([big, small][k], p) for k, p in pts)
    assert sum(1 for k, _ in pts if k == 0) == 192          # 3/4 of the volume, 3/4 of 256 points exactly
    inside = [p["x"] for k, p in pts if k == 1]
    assert len(set(inside)) == len(inside)                   # spread inside a box, not a few repeated values
    assert list(points_in_boxes([big, small], 256)) == pts


# --------------------------------------------------------------------------- the search and the point proofs

def test_search_finds_counterexamples_far_from_the_first_16_undecided_leaves(paved):
    bs, claim = paved
    undecided = [i for i, (_, s) in enumerate(claim.boxes) if s == "undecided"]
    first16 = set(undecided[:16])
    mids = [cx.Candidate(claim.boxes[i][0].midpoint(), i, "undecided", None) for i in undecided[:16]]
    at_mids = cx.prove_candidates(bs, claim.boxes, "bracket_1", mids)      # what today's paving asks
    assert len(at_mids) == 16 and not cx.certified_counterexamples(at_mids)
    cands = cx.candidate_points(bs, claim.boxes, "bracket_1", 4, samples=64)
    assert cands and all(c.probe != "proved" for c in cands)
    proofs = cx.prove_candidates(bs, claim.boxes, "bracket_1", cands)
    found = cx.certified_counterexamples(proofs)
    assert found, proofs
    for p in found:
        assert p["leaf"] not in first16
        point = {k: Fraction(v) for k, v in p["point"].items()}
        assert cx.contains(claim.boxes[p["leaf"]][0], point)
        assert point["eps"] > 1                                # the first 16 leaves have eps <= 1
        assert _fails_mpmath(p["point"])                     # omega_1 outside (7) in mpmath too
        assert "omega_1" in p["reason"]


def test_the_search_is_deterministic(paved):
    bs, claim = paved
    one = cx.candidate_points(bs, claim.boxes, "bracket_1", 3, samples=32)
    assert one == cx.candidate_points(bs, claim.boxes, "bracket_1", 3, samples=32)
    assert cx.failing_fraction_estimate(bs, samples=20, seed=3) == cx.failing_fraction_estimate(bs, samples=20, seed=3)
    with cx.Executor(2) as ex:                                   # the same wherever the probes and proofs run
        assert cx.candidate_points(bs, claim.boxes, "bracket_1", 3, samples=32, executor=ex) == one
        assert cx.failing_fraction_estimate(bs, samples=20, seed=3, executor=ex) == \
            cx.failing_fraction_estimate(bs, samples=20, seed=3)


def test_local_steps_stay_in_the_leaf_and_never_rank_worse(paved):
    bs, claim = paved
    leaf = next(i for i, (b, _) in enumerate(claim.boxes) if b.interval("eps")[0] >= 1 and b.interval("Omega2")[0] == Fraction(1, 1000))
    box = claim.boxes[leaf][0]
    start = cx.Candidate(box.midpoint(), leaf, "proved", 1.0)
    moved = cx._improve(bs, start, box, "bracket_1", 2, cx.PROBE_PREC, cx.Executor(1))
    assert cx.contains(box, moved.point) and moved.key() <= start.key()


def test_only_a_refuted_point_proof_is_a_counterexample():
    proofs = [{"status": "inconclusive", "probe": "refuted"}, {"status": "proved", "probe": "refuted"},
              {"status": "refuted", "probe": "undecided"}]
    assert cx.certified_counterexamples(proofs) == [proofs[2]]


def test_a_point_proof_contradicting_its_leaf_is_an_error(paved):
    bs, claim = paved
    cands = cx.candidate_points(bs, claim.boxes, "bracket_1", 1, samples=32)
    assert cands and cands[0].probe == "refuted"
    forged = list(claim.boxes)
    forged[cands[0].leaf] = (forged[cands[0].leaf][0], "proved")     # a leaf "proved" that holds a counterexample
    with pytest.raises(AssertionError, match="unsound"):
        cx.prove_candidates(bs, forged, "bracket_1", cands)
    elsewhere = cx.Candidate(cands[0].point, (cands[0].leaf + 1) % len(claim.boxes), "refuted", None)
    with pytest.raises(AssertionError, match="not in leaf"):
        cx.prove_candidates(bs, claim.boxes, "bracket_1", [elsewhere])


def test_contains_is_closed_and_checks_every_edge():
    box = Box.of({"x": (Fraction(0), Fraction(1)), "y": (Fraction(2), Fraction(3))})
    assert cx.contains(box, {"x": Fraction(0), "y": Fraction(3)})
    assert not cx.contains(box, {"x": Fraction(1, 2), "y": Fraction(7, 2)})
    assert not cx.contains(box, {"x": Fraction(-1), "y": Fraction(5, 2)})


# --------------------------------------------------------------------------- the Monte Carlo cross-check

@pytest.mark.parametrize("classifier", ["point", "box"])
def test_the_estimate_contains_an_independent_float_estimate(paved, classifier):
    bs, claim = paved
    est = cx.failing_fraction_estimate(bs, samples=300, seed=1, classifier=classifier)["bracket_1"]
    lo, hi = est["interval"]
    assert est["unknown"] == 0 and 0.1 < est["fraction"] < 0.35
    assert lo <= _float_fraction(bs.box, 3000, seed=7) <= hi
    ok, text = cx.agrees_with_paving(claim.volume(bs.box), est)
    assert ok and "consistent" in text


def test_wilson_and_the_agreement_check():
    lo, hi = cx.wilson_interval(20, 100, 0.95)
    assert lo == pytest.approx(0.1333, abs=1e-3) and hi == pytest.approx(0.2888, abs=1e-3)
    assert cx.wilson_interval(0, 50, 0.95)[0] == 0.0
    est = {"samples": 100, "failing": 20, "fraction": 0.2, "interval": [0.13, 0.29], "confidence": 0.95}
    vol = lambda r, u: {"proved": 1 - Fraction(r) - Fraction(u), "refuted": Fraction(r), "undecided": Fraction(u)}
    assert cx.agrees_with_paving(vol("1/10", "1/5"), est)[0]
    assert not cx.agrees_with_paving(vol("1/2", "1/10"), est)[0]        # the paving certifies >= 1/2 failing
    assert not cx.agrees_with_paving(vol("0", "1/10"), est)[0]          # ... or at most 1/10
    assert cx.agrees_with_paving(vol("29/100", "0"), est)[0]            # ends count


def test_unknown_samples_widen_the_interval(paved, monkeypatch):
    bs, _ = paved
    monkeypatch.setattr(cx, "_point_statuses", lambda *a: {"bracket_1": "inconclusive"})
    est = cx.failing_fraction_estimate(bs, samples=10)["bracket_1"]
    assert est["failing"] == 0 and est["unknown"] == 10 and est["interval"][0] == 0.0 and est["interval"][1] == 1.0


def test_paving_searches_gives_each_claim_its_search_and_estimate(paved):
    bs, claim = paved
    out = cx.paving_searches(bs, [claim], 2, samples=16, mc_samples=30, seed=4)["bracket_1"]
    assert out["counterexample_search"]["refuted"] >= 1 and out["monte_carlo"]["samples"] == 30
    assert out["monte_carlo"]["consistent"] is True

    class Spent:
        def expired(self):
            return True

        def reason(self):
            return "time limit of 1 s reached (--time-limit)"
    spent = cx.paving_searches(bs, [claim], 2, mc_samples=30, budget=Spent())["bracket_1"]
    assert spent == {"counterexample_search": {"skipped": Spent().reason()}, "monte_carlo": {"skipped": Spent().reason()}}
