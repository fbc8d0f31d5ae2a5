"""Staged builds that start from an earlier build's state (core.staged_build, issue 41): a resumed build is
the build run from its first stage, row for row and ball for ball."""
from __future__ import annotations

from functools import partial

import pytest
from flint import arb

from rigor_gyro.core.balls import ball_key, working_precision
from rigor_gyro.core.staged_build import StagedBuilds
from rigor_gyro.kinds.periodic_orbit import paper_chain as pc
from rigor_gyro.kinds.periodic_orbit.flow import RelayParams
from rigor_gyro.scene import load_scene


class _Toy:
    """A reader whose take adds the configuration's offset for a row to the value."""

    def __init__(self, offsets: dict[str, int]):
        self.offsets, self.order, self.got = offsets, [], {}

    def take(self, rid: str, value: arb) -> arb:
        self.order.append(rid)
        self.got[rid] = value + self.offsets.get(rid, 0)
        return self.got[rid]

    def snapshot(self):
        return tuple(self.order), dict(self.got)

    def restore(self, snap):
        self.order, self.got = list(snap[0]), dict(snap[1])


def _toy_stages():
    def s0(R, st):
        return {"x": R.take("a", arb(1)) + R.take("b", arb(2))}

    def s1(R, st):
        return {**st, "y": R.take("c", st["x"] * 3)}

    def s2(R, st):
        R.take("d", st["y"] - st["x"])
        return st
    return [s0, s1, s2]


def _toy_changed(a: dict, b: dict) -> set:
    return {r for r in a.keys() | b.keys() if a.get(r) != b.get(r)}


def test_a_toy_build_restarts_at_its_first_changed_row_and_equals_a_fresh_build():
    builds = StagedBuilds(_toy_stages(), _toy_changed)
    builds.run(_Toy({}), {})
    for cfg in ({"c": 5}, {"d": 1}, {"a": 1}, {}, {"c": 5}):
        fresh = StagedBuilds(_toy_stages(), _toy_changed).run(_Toy(cfg), cfg)
        resumed = builds.run(_Toy(cfg), cfg)
        assert resumed.order == fresh.order
        assert {k: ball_key(v) for k, v in resumed.got.items()} == {k: ball_key(v) for k, v in fresh.got.items()}
    # {"c": 5} restarts at stage 1, {"d": 1} at stage 2, {"a": 1} at 0, {} and the second {"c": 5} reuse all
    assert builds.skipped == 1 + 2 + 0 + 3 + 3


def test_a_changed_that_misses_a_row_gives_a_stale_build():
    """The comparison above can fail: with a ``changed`` that names nothing, the forced row is not seen."""
    builds = StagedBuilds(_toy_stages(), lambda a, b: set())
    builds.run(_Toy({}), {})
    stale = builds.run(_Toy({"c": 5}), {"c": 5})
    fresh = StagedBuilds(_toy_stages(), _toy_changed).run(_Toy({"c": 5}), {"c": 5})
    assert ball_key(stale.got["c"]) != ball_key(fresh.got["c"])


def test_a_build_stops_once_it_has_the_rows_it_needs_and_a_later_one_continues():
    builds = StagedBuilds(_toy_stages(), _toy_changed)
    part = builds.run(_Toy({}), {}, need={"c"})
    assert part.order == ["a", "b", "c"]
    whole = builds.run(_Toy({}), {})
    assert whole.order == ["a", "b", "c", "d"] and builds.skipped == 2


def test_a_build_reuses_only_builds_made_at_its_own_precision():
    with working_precision(64):
        builds = StagedBuilds(_toy_stages(), _toy_changed)
        builds.run(_Toy({}), {})
    with working_precision(128):
        builds.run(_Toy({}), {})
        assert builds.skipped == 0
        builds.run(_Toy({}), {})
        assert builds.skipped == 3          # the build at 128 bits
    with working_precision(64):
        builds.run(_Toy({"d": 1}), {"d": 1})
        assert builds.skipped == 3 + 2      # the first build, at 64 bits


def _signature(R) -> tuple:
    chains = tuple((k, ball_key(c.value), c.source, c.slack, c.identity,
                    None if c.computed is None else ball_key(c.computed), c.accepted) for k, c in R.chains.items())
    return tuple(R.order), chains, tuple(R.fixes.items()), tuple(R.candidates.items()), tuple(R.strong.items())


@pytest.mark.parametrize("scene", ["roitenberg1947", "roitenberg1947_b2over15"])
def test_the_relay_builds_resumed_equal_the_builds_from_the_start(scene):
    """Every build relay_chains asks for (the passes, one trial per candidate, the one with the printed
    corrections kept), resumed from the earlier ones, equals the same build run from its first stage."""
    sc = load_scene(scene)
    P = pc._paper_parameters(sc.paper, RelayParams.from_strings(**sc.parameters))
    calls = []
    real = pc._build

    def spy(paper, P_, prints, rels, keep=(), forced=None, memo=None, builds=None, need=None):
        R = real(paper, P_, prints, rels, keep, forced, memo, builds, need)
        calls.append((prints, rels, set(keep), dict(forced or {}), need, R))
        return R
    with working_precision(64):
        pc._build = spy
        try:
            pc.relay_chains(sc.paper, RelayParams.from_strings(**sc.parameters))
        finally:
            pc._build = real
        assert len(calls) >= 4 and any(keep for _, _, keep, _, _, _ in calls)
        assert sum(bool(forced) for _, _, _, forced, _, _ in calls) >= 2
        for prints, rels, keep, forced, need, R in calls:
            fresh = real(sc.paper, P, prints, rels, keep, forced)
            if need is None:
                assert _signature(R) == _signature(fresh)
            else:           # a build that stopped early: its rows are the first rows of the whole build
                n = len(R.order)
                assert need <= set(R.order) and R.order == fresh.order[:n]
                assert _signature(R)[1] == _signature(fresh)[1][:n]
