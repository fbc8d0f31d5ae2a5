"""The order in which a paving evaluates its boxes: a best-first queue of box groups, in batches.

A *group* is what is queued and evaluated together: the whole box at the start, then the two halves of
each split (so that a box's sibling is evaluated in the same batch and its status is known when the box's
own halves are queued). Each group carries the claims still open on it and a *score*.

Priorities (``prove --priority``):

* ``volume`` (default): the largest boxes first, ties in the order they were queued. Every box of one
  size comes before any smaller one, so this is the breadth-first order pavings always had (their
  certificates are unchanged), and batching does not change what is evaluated.
* ``boundary``: the boxes next to a decided region first. The halves of a box X are scored by the
  number of claims undecided on X that X's sibling decided (proved or refuted): X touches a region where
  the claim is decided, and the status changes inside X or at its face. A box whose sibling decided
  nothing passes on its own score less one (it still lies in a box that touched the decided region).
  Higher scores first, then larger boxes, then queue order. A heuristic, cheap to compute (no margin
  values are needed), in smaller batches than ``volume``.

The order never changes what a box's evaluation says, only which boxes a budget leaves pending; every
order gives the same leaves when the paving runs to its resolution (each box is split exactly when it is
undecided and not yet fine), listed in another order.

Determinism: :meth:`Frontier.pop_batch` takes the best groups up to :data:`BATCH` boxes, whatever the
executor and the worker count; a queue rebuilt from a partial paving (:mod:`.resume`) in its stored order
continues exactly as the interrupted run would have (new groups are queued after every stored one with
the same key, as they were).
"""
from __future__ import annotations

import heapq
from dataclasses import dataclass
from fractions import Fraction

from ..core.boxes import Box
from ..core.errors import ParameterError

__all__ = ["PRIORITIES", "DEFAULT_PRIORITY", "BATCH", "Group", "Frontier", "check_priority", "volume_depth"]

#: the priorities a paving may be evaluated in (see the module docstring)
PRIORITIES = ("volume", "boundary")
DEFAULT_PRIORITY = "volume"
#: boxes evaluated together at most, per priority (one executor map; the budgets and Ctrl-C are checked
#: between batches). The volume order does not depend on it (a batch never holds a box that a smaller one
#: queued in it would precede); the boundary order does, and refines the boundary in smaller steps.
BATCH = {"volume": 1024, "boundary": 128}


def check_priority(priority: object) -> str:
    """``priority`` if it is one of :data:`PRIORITIES`; ParameterError naming them otherwise."""
    if priority not in PRIORITIES:
        raise ParameterError(f"priority {priority!r}: choose one of {', '.join(PRIORITIES)}")
    return priority


@dataclass(frozen=True)
class Group:
    """Boxes queued together (the whole box, or the two halves of a split), the claims open on them (in the
    paving's claim order) and the boundary score of :data:`PRIORITIES` ``boundary``."""

    boxes: tuple[Box, ...]
    claims: tuple[str, ...]
    score: int = 0

    def to_json(self) -> dict:
        return {"boxes": [b.to_json() for b in self.boxes], "claims": list(self.claims), "score": self.score}

    @classmethod
    def from_json(cls, data: dict) -> "Group":
        return cls(tuple(Box.from_json(b) for b in data["boxes"]), tuple(data["claims"]), int(data["score"]))


class Frontier:
    """The queued groups, best first by ``priority``; ``len`` is the number of queued boxes."""

    def __init__(self, priority: str = DEFAULT_PRIORITY, groups: list[Group] = ()):
        self.priority = check_priority(priority)
        self._heap: list = []
        self._seq = 0
        self._boxes = 0
        self._last: list = []
        for g in groups:
            self.push(g)

    def _key(self, g: Group) -> tuple:
        volume = g.boxes[0].volume()
        if self.priority == "boundary":
            return (-g.score, -volume, self._seq)
        return (-volume, self._seq)

    def push(self, g: Group) -> None:
        heapq.heappush(self._heap, (self._key(g), g))
        self._seq += 1
        self._boxes += len(g.boxes)

    def __len__(self) -> int:
        return self._boxes

    def pop_batch(self, limit: int | None = None) -> list[Group]:
        """The best groups, as many as fit in ``limit`` boxes (default: the priority's :data:`BATCH`; at
        least one group), best first."""
        limit = BATCH[self.priority] if limit is None else limit
        self._last, n = [], 0
        while self._heap and (not self._last or n + len(self._heap[0][1].boxes) <= limit):
            self._last.append(heapq.heappop(self._heap))
            n += len(self._last[-1][1].boxes)
        self._boxes -= n
        return [g for _, g in self._last]

    def restore_batch(self) -> None:
        """Put back the last batch popped, unevaluated, with its keys (so its place in the order is kept)."""
        for item in self._last:
            heapq.heappush(self._heap, item)
            self._boxes += len(item[1].boxes)
        self._last = []

    def pop_item(self) -> tuple:
        """The best queued group with its key (for :meth:`put_back`), or None when nothing is queued."""
        if not self._heap:
            return None
        item = heapq.heappop(self._heap)
        self._boxes -= len(item[1].boxes)
        return item

    def put_back(self, items) -> None:
        """Queue again groups taken by :meth:`pop_item`, unevaluated, with their keys (their places kept)."""
        for item in items:
            heapq.heappush(self._heap, item)
            self._boxes += len(item[1].boxes)

    def groups(self) -> list[Group]:
        """The queued groups, best first (the order a partial paving stores them in)."""
        return [g for _, g in sorted(self._heap, key=lambda t: t[0])]


def volume_depth(whole: Box, box: Box) -> int:
    """How many splits made ``box`` from ``whole`` (each split halves the volume exactly)."""
    ratio = Fraction(whole.volume()) / box.volume()
    return ratio.numerator.bit_length() - 1
