"""An adaptive cover of a relay box's similar box (issue 37: the six parameters at +-0.5 % at once).

Why: a box of all six physical parameters reduces to its similar box of (B', sigma', n') (:mod:`.similarity`),
three directions instead of six, but at +-0.5 % that box is B' +-3 %, sigma' +-1 %, n' +-1 %, and the continuation
(:mod:`.continuation`) decides ``stable`` only on pieces of about B' +-0.19 % there (the centred forms of the
Jacobian through theta*(P) grow with the width faster than linearly). Halving every direction in turn, as a paving
does, needs 2^3 pieces per halving of B'; halving the direction along which theta*(P) moves most (its certified
gradient times the half-width) needs one.

What: :func:`cover` keeps a stack of pieces, each with the claims still to be proved on it. A piece is decided by
``evaluate`` (the continuation from the piece's own centre); the claims it proves are done there, the others go to
its two halves along the heaviest direction (``weights``), while halves may decide more (``reached``: the piece
proved theta*(P), so that halving sharpens steps 2 and 3, or its step 1 failed but not hopelessly, see
:func:`.theta_fold.slope_ratio`), the budget of evaluations lasts and the piece is at most MAX_DEPTH halvings deep; a cover whose first
FIRST_PROOF_BY pieces proved nothing stops. A claim that a piece neither proves nor may
pass to its halves is not proved by the cover, and no further piece works on it.

Guarantee: a claim is returned only when every piece of a partition of the box (the leaves of the bisection tree,
exact rational halves) proved it: both claims assert, for every member, the existence of an orbit with a property,
so proofs on the pieces of a partition make a proof on the box. Precision: exact rationals (the pieces);
``evaluate`` works at the caller's precision. Fails when: never raises; an undecided claim is left out.
"""
from __future__ import annotations

from fractions import Fraction
from typing import Callable

from ...core.boxes import Box

__all__ = ["cover", "COVER_BUDGET", "MAX_DEPTH", "FIRST_PROOF_BY", "halves"]

#: evaluations a cover may spend (the six parameters at +-0.5 %: 31, 16 pieces at about 1 s each)
COVER_BUDGET = 40
#: halvings of one piece at most (the six parameters at +-0.5 %: 4): bounds the cost of a piece that never
#: decides, e.g. one holding a stability threshold, to 1 + 2 MAX_DEPTH evaluations along its chain
MAX_DEPTH = 5
#: a cover none of whose first FIRST_PROOF_BY pieces proved anything stops (the six parameters at +-0.5 % and A +-10 %
#: proved their first piece at the 5th and the 4th evaluation): bounds the cost of a box that no piece decides
FIRST_PROOF_BY = 8


def halves(box: Box, name: str) -> tuple[Box, Box]:
    """The two halves of ``box`` at the exact midpoint of the edge ``name``."""
    lo, hi = box.interval(name)
    mid = (lo + hi) / 2
    edges = [(k, a, b) for k, a, b in box.edges]
    left = Box.of({k: ((a, mid) if k == name else (a, b)) for k, a, b in edges})
    right = Box.of({k: ((mid, b) if k == name else (a, b)) for k, a, b in edges})
    return left, right


def _heaviest(box: Box, weights: dict[str, float] | None) -> str:
    """The edge to halve: the largest weight (the motion of theta* along it), else the widest relative one."""
    wide = [(k, a, b) for k, a, b in box.edges if b > a]
    if weights:
        cand = [(weights.get(k, 0.0), k) for k, _, _ in wide]
        w, k = max(cand)
        if w > 0:
            return k
    return max(wide, key=lambda e: (e[2] - e[1]) / max(abs(e[1]), abs(e[2]), Fraction(1, 10**30)))[0]


def cover(box: Box, claims: list[str], evaluate: Callable, budget: int = COVER_BUDGET, max_depth: int = MAX_DEPTH):
    """({claim: (pieces, first piece's reason)} proved on every piece of a partition of ``box``, evaluations spent).

    ``evaluate(piece, claims) -> (proved {claim: reason}, reached, weights {edge: float} or None)``."""
    alive = list(claims)
    first: dict[str, str] = {}
    pieces = {c: 0 for c in claims}
    stack = [(box, list(claims), 0)]
    spent = 0
    while stack:
        piece, need, depth = stack.pop()
        need = [c for c in need if c in alive]
        if not need:
            continue
        if spent >= budget:
            alive = [c for c in alive if c not in need]
            continue
        if spent >= FIRST_PROOF_BY and not any(pieces.values()):
            break
        spent += 1
        got, reached, weights = evaluate(piece, need)
        for c in need:
            if c in got:
                pieces[c] += 1
                first.setdefault(c, got[c])
        rest = [c for c in need if c not in got]
        if not rest:
            continue
        if not reached or spent + 2 > budget or depth >= max_depth or not any(hi > lo for _, lo, hi in piece.edges):
            alive = [c for c in alive if c not in rest]
            continue
        left, right = halves(piece, _heaviest(piece, weights))
        stack.append((right, rest, depth + 1))
        stack.append((left, rest, depth + 1))
    if stack:               # stopped early: pending pieces decided nothing
        return {}, spent
    return {c: (pieces[c], first[c]) for c in alive if c in first}, spent
