"""Staged builds that start from the state of an earlier build (issue 41: the relay paper chain is built
about nine times per audit, each build differing from an earlier one only from some row on).

A *build* runs a fixed list of stages in order. Each stage reads the state the earlier stages left (a dict,
never mutated afterwards: a stage returns a new dict, or None to end the build) and asks a *reader* to take
rows, in order (the reader's ``order`` lists the rows it took). Within one :class:`StagedBuilds` (one call
of the caller) and one working precision, a build is a deterministic function of its *configuration*, and a row's
take depends on the configuration only through that row's part of it; ``changed(a, b)`` names every row whose
part differs between two configurations. So when build C's configuration agrees with an earlier build B's on
every row B took before position p, C's stages up to the last one that ended before p compute what B's did
(the same balls, bit for bit, and the same decisions, by induction over the rows): C restores B's state after
that stage and runs only the rest. A build that agrees with B everywhere B went costs one restore.

Guarantee: a resumed build's reader and result are those of the build run from its first stage, provided
(i) each stage is a deterministic function of its state, of the fixed inputs and of the reader's answers,
(ii) no stage mutates a container of an earlier state, (iii) ``changed`` covers everything a take reads
from the configuration, and (iv) the reader's ``snapshot``/``restore`` copy all it accumulates. The
precision is checked (a build reuses only the builds made at its own working precision). Failure mode: a
``changed`` that misses an input would reuse a stale prefix; the tests compare resumed builds with builds run
from the start.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

from flint import ctx

__all__ = ["StagedBuilds"]


@dataclass(frozen=True)
class _Snapshot:
    #: stages [0, stage) have run
    stage: int
    state: dict
    reader: Any
    #: how many rows the reader had taken
    rows: int
    #: the build ended after this stage
    done: bool


@dataclass
class _Record:
    config: Any
    #: the working precision the build ran at
    prec: int
    #: the rows the build took, in order (the reader's own list at the end of the build)
    order: list
    snaps: list
    pos: dict | None = field(default=None)

    def position(self) -> dict:
        if self.pos is None:
            self.pos = {r: i for i, r in enumerate(self.order)}
        return self.pos


class StagedBuilds:
    """The builds of one caller run (module docstring). ``stages``: callables ``(reader, state) -> dict |
    None``; ``changed(config_a, config_b)``: the rows whose takes may differ between the two configurations
    (a set of row ids)."""

    def __init__(self, stages: list[Callable], changed: Callable[[Any, Any], set]):
        self.stages, self.changed = stages, changed
        self.records: list[_Record] = []
        #: how many stages the builds ran and skipped (for the benchmarks and the tests)
        self.ran = self.skipped = 0

    def _start(self, config) -> tuple[list, _Snapshot | None]:
        """The snapshots to inherit and the latest one a build with ``config`` may start from."""
        best: tuple[list, _Snapshot | None] = ([], None)
        for rec in self.records:
            if rec.prec != ctx.prec or not rec.snaps or (best[1] is not None
                                                         and rec.snaps[-1].stage <= best[1].stage):
                continue
            pos = rec.position()
            first = min((pos[r] for r in self.changed(rec.config, config) if r in pos), default=len(rec.order))
            k = -1
            for i, s in enumerate(rec.snaps):
                if s.rows > first:
                    break
                k = i
            if k >= 0 and (best[1] is None or rec.snaps[k].stage > best[1].stage):
                best = (rec.snaps[:k + 1], rec.snaps[k])
        return best

    def run(self, reader, config, need: set | None = None):
        """Run a build with ``config`` on the fresh ``reader`` (from the latest reusable snapshot) and return
        the reader. ``need``: stop once the reader has taken all these rows (the caller reads no other row
        of this build; a later build may still continue from its last stage)."""
        snaps, snap = self._start(config)
        if snap is not None:
            reader.restore(snap.reader)
            state, i, done = snap.state, snap.stage, snap.done
            self.skipped += snap.stage
        else:
            state, i, done = {}, 0, False
        snaps = list(snaps)
        while not done and i < len(self.stages):
            out = self.stages[i](reader, state)
            i += 1
            self.ran += 1
            done = out is None or i == len(self.stages)
            state = state if out is None else out
            snaps.append(_Snapshot(i, state, reader.snapshot(), len(reader.order), done))
            if need is not None and not done and need.issubset(reader.order):
                break
        self.records.append(_Record(config, ctx.prec, reader.order, snaps))
        return reader
