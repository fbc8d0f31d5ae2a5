"""The adaptive cover of a similar box (kinds/periodic_orbit/similar_cover.py), with stand-in evaluations: a claim
comes back only when the pieces that proved it partition the box exactly, within the budget."""
from __future__ import annotations

from fractions import Fraction as F

from rigor_gyro.core.boxes import Box
from rigor_gyro.kinds.periodic_orbit.similar_cover import cover, halves

BOX = Box.of({"B": (F(1), F(2)), "sigma": (F(3), F(5)), "n": (F(10), F(10))})


def _partition(pieces: list[Box], whole: Box) -> bool:
    """The pieces lie in ``whole``, their volumes add up to its volume and no two share interior points (exact)."""
    names = [k for k, lo, hi in whole.edges if hi > lo]
    for p in pieces:
        for k, lo, hi in whole.edges:
            a, b = p.interval(k)
            if not lo <= a <= b <= hi:
                return False
    for i, p in enumerate(pieces):
        for q in pieces[i + 1:]:
            if all(max(p.interval(k)[0], q.interval(k)[0]) < min(p.interval(k)[1], q.interval(k)[1]) for k in names):
                return False
    return sum(p.volume() for p in pieces) == whole.volume()


def _evaluator(width: dict, fail_at=None, log=None):
    """Proves each claim on pieces narrower than ``width[claim]`` along B (theta* always reached); a piece of width
    at most 1/4 holding ``fail_at`` (a B value) reaches nothing."""
    def evaluate(piece, need):
        lo, hi = piece.interval("B")
        if log is not None:
            log.append((piece, list(need)))
        if fail_at is not None and lo <= fail_at <= hi and hi - lo <= F(1, 4):
            return {}, False, None
        got = {c: ("proved", f"{c} on {lo}..{hi}") for c in need if hi - lo <= width[c]}
        return got, True, {"B": float(hi - lo), "sigma": 0.0}
    return evaluate


def test_a_claim_comes_back_only_from_a_partition():
    log = []
    got, spent = cover(BOX, ["stable", "orbit_genuine"], _evaluator({"stable": F(1, 8), "orbit_genuine": F(1, 2)}, log=log))
    assert got["stable"][0] == 8 and got["orbit_genuine"][0] == 2 and spent == len(log) == 15
    for c in ("stable", "orbit_genuine"):
        proved = [p for p, need in log if c in need and p.interval("B")[1] - p.interval("B")[0] <= {"stable": F(1, 8), "orbit_genuine": F(1, 2)}[c]]
        assert _partition(proved, BOX)
    # halved along B (the heaviest), sigma never
    assert all(p.interval("sigma") == (F(3), F(5)) for p, _ in log)


def test_one_piece_that_reaches_nothing_drops_the_claim():
    got, spent = cover(BOX, ["stable"], _evaluator({"stable": F(1, 8)}, fail_at=F(15, 8)))
    assert got == {}
    got, _ = cover(BOX, ["stable", "orbit_genuine"], _evaluator({"stable": F(1, 8), "orbit_genuine": F(1)}, fail_at=F(15, 8)))
    assert list(got) == ["orbit_genuine"]          # proved on the whole box before any piece failed


def test_the_budget_bounds_the_evaluations_and_pending_pieces_prove_nothing():
    for budget in range(1, 15):
        log = []
        got, spent = cover(BOX, ["stable"], _evaluator({"stable": F(1, 8)}, log=log), budget=budget)
        assert spent == len(log) <= budget and got == {}
    got, spent = cover(BOX, ["stable"], _evaluator({"stable": F(1, 8)}), budget=15)
    assert got["stable"][0] == 8 and spent == 15


def test_halves_are_exact():
    left, right = halves(BOX, "sigma")
    assert left.interval("sigma") == (F(3), F(4)) and right.interval("sigma") == (F(4), F(5))
    assert left.interval("B") == right.interval("B") == (F(1), F(2))


def test_no_piece_deeper_than_max_depth():
    log = []
    got, spent = cover(BOX, ["stable"], _evaluator({"stable": F(1, 8)}, log=log), max_depth=2)
    assert got == {} and max(F(1) / (p.interval("B")[1] - p.interval("B")[0]) for p, _ in log) == 4
    got, _ = cover(BOX, ["stable"], _evaluator({"stable": F(1, 8)}), max_depth=3)
    assert got["stable"][0] == 8


def test_a_cover_whose_first_pieces_prove_nothing_stops():
    from rigor_gyro.kinds.periodic_orbit.similar_cover import FIRST_PROOF_BY
    log = []
    got, spent = cover(BOX, ["stable"], _evaluator({"stable": F(1, 256)}, log=log), max_depth=9)
    assert got == {} and spent == len(log) == FIRST_PROOF_BY
