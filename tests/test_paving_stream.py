"""The streaming frontier (issue 38, parallel at any grain; rigor_gyro/margins/stream.py): on a pool or a
Dask cluster the volume order runs with no barrier between batches, and the certificate is byte-identical
to the in-process one whatever the worker count and the order results arrive in; budgets, time limits,
checkpoints, Ctrl-C and a broken executor leave partial pavings that check and resume to the whole one.

Most tests use a fake parallel executor that completes its tasks in a seeded random order (timing made
adversarial and reproducible, no processes); one runs a real pool."""
import json
import random
from concurrent.futures import Future
from concurrent.futures.process import BrokenProcessPool

import pytest

from rigor_gyro.check import check_certificate
from rigor_gyro.margins import stream
from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.paving import INTERRUPTED, pave
from rigor_gyro.margins.resume import resume_state
from tests.test_paving_anytime import LINE, _bs, _half_plane, _json, _resumed, half_plane  # noqa: F401


class Shuffled(Executor):
    """Parallel in name: ``submit`` queues, ``wait_any`` runs a random non-empty subset of the queued tasks
    (seeded) and reports them done: results arrive in any order, any number at a time."""

    def __init__(self, workers=3, seed=0, fail_at=None, error=KeyboardInterrupt):
        super().__init__(1)
        self.workers, self.rng, self.queued, self.waits = workers, random.Random(seed), [], 0
        self.fail_at, self.error, self.submitted = fail_at, error, []

    @property
    def parallel(self):
        return True

    def submit(self, fn, *args):
        f = Future()
        self.queued.append((f, fn, args))
        self.submitted.append(len(args[1]))
        return f

    def wait_any(self, futures, timeout=None):
        self.waits += 1
        if self.waits == self.fail_at:
            raise self.error("a worker died") if self.error is BrokenProcessPool else self.error()
        live = [q for q in self.queued if q[0] in set(futures)]
        picked = self.rng.sample(live, self.rng.randint(1, len(live)))
        for q in picked:
            self.queued.remove(q)
            q[0].set_result(q[1](*q[2]))
        return [q[0] for q in picked]


@pytest.fixture
def plane_fast(half_plane):      # noqa: F811  (an exact, instant box rigour: a few hundred boxes in no time)
    return half_plane


@pytest.mark.parametrize("seed,workers", [(0, 2), pytest.param(1, 3, marks=pytest.mark.slow), (2, 8)])
def test_results_in_any_order_give_the_in_process_certificate(plane_fast, seed, workers):
    ex = Shuffled(workers, seed)
    assert _json(pave(_bs(plane_fast), ex)) == _json(pave(_bs(plane_fast)))
    assert max(ex.submitted) > 1 and ex.waits > 1           # batched, and streamed


def test_the_max_boxes_cap_counts_in_commit_order_despite_speculation(plane_fast):
    text = plane_fast + 'max_boxes = "150"\n'
    whole = _json(pave(_bs(text)))
    assert whole["budget_exhausted"]
    for seed in range(3):
        assert _json(pave(_bs(text), Shuffled(4, seed))) == whole


@pytest.mark.parametrize("budget", [pytest.param(1, marks=pytest.mark.slow), 7, pytest.param(40, marks=pytest.mark.slow)])
def test_a_box_budget_stops_where_the_batched_loop_stops_and_resumes_to_the_whole(plane_fast, budget):
    whole = _json(pave(_bs(plane_fast)))
    data, runs = _json(pave(_bs(plane_fast), Shuffled(3, budget), box_budget=budget)), 0
    assert data == _json(pave(_bs(plane_fast), box_budget=budget))          # byte for byte, partial
    while data.get("stopped"):
        runs += 1
        bs, state = resume_state(data)
        data = _json(pave(bs, Shuffled(3, runs), state=state, box_budget=budget))
    assert runs >= 2 and data == whole


@pytest.mark.parametrize("error,why,at", [pytest.param(KeyboardInterrupt, INTERRUPTED, 2, marks=pytest.mark.slow),
                                          (BrokenProcessPool, "executor broke", 3)])
def test_ctrl_c_or_a_broken_pool_mid_stream_leaves_a_partial_paving_that_resumes_to_the_whole(error, why, at,
                                                                                                monkeypatch):
    # one box a batch, whatever the boxes' measured cost: LINE (9 evaluations) then has a wait number `at`
    # on every run (with ~50 ms batches sized from timings, a fast run finished in 3 waits: a flaky test)
    monkeypatch.setattr(stream, "TARGET_SECONDS", 0)
    p = pave(_bs(LINE), Shuffled(3, at, fail_at=at, error=error), keep_on_interrupt=True)
    assert why in p.stopped and p.pending
    data = _json(p)
    assert check_certificate(data).ok                       # the real box rigour re-checks it
    assert _resumed(data) == _json(pave(_bs(LINE)))


@pytest.mark.parametrize("at", [3, pytest.param(11, marks=pytest.mark.slow)])
def test_ctrl_c_at_any_wait_resumes_to_the_whole(plane_fast, at):
    with pytest.raises(KeyboardInterrupt):                  # a library call is not swallowed
        pave(_bs(plane_fast), Shuffled(3, at, fail_at=at))
    p = pave(_bs(plane_fast), Shuffled(3, at, fail_at=at), keep_on_interrupt=True)
    assert p.stopped == INTERRUPTED and p.pending
    bs, state = resume_state(_json(p))
    assert _json(pave(bs, Shuffled(2, at), state=state)) == _json(pave(_bs(plane_fast)))


def test_a_checkpoint_mid_stream_resumes_to_the_whole(plane_fast):
    written = []

    def checkpoint(p):
        written.append(_json(p))
        if len(written) == 5:
            raise SystemExit("killed")

    with pytest.raises(SystemExit):
        pave(_bs(plane_fast), Shuffled(3, 5), checkpoint=checkpoint, checkpoint_every=0.0)
    last = written[-1]
    assert "checkpoint after" in last["stopped"] and last["pending"]
    bs, state = resume_state(last)
    assert _json(pave(bs, Shuffled(2, 9), state=state)) == _json(pave(_bs(plane_fast)))


def test_a_time_limit_mid_stream_resumes_to_the_whole(plane_fast, monkeypatch):
    from rigor_gyro.core import deadline
    calls = []
    with monkeypatch.context() as m:            # the clock runs out at the 31st look
        m.setattr(deadline.Budget, "expired", lambda self: calls.append(1) or len(calls) > 30)
        m.setattr(deadline.Budget, "reason", lambda self: "time limit of 1 s reached (--time-limit)")
        data = _json(pave(_bs(plane_fast), Shuffled(3, 4), time_limit=1.0))
    assert data["stopped"] == "time limit of 1 s reached (--time-limit)" and data["pending"]
    whole = _json(pave(_bs(plane_fast)))
    assert 0 < data["boxes_evaluated"] < whole["boxes_evaluated"]
    bs, state = resume_state(data)
    assert _json(pave(bs, Shuffled(2, 1), state=state)) == whole


def test_the_boundary_priority_keeps_the_batched_loop(plane_fast):
    ex = Shuffled(3, 0)
    assert _json(pave(_bs(plane_fast, "boundary"), ex)) == _json(pave(_bs(plane_fast, "boundary")))
    assert not ex.submitted                                  # map, not the stream


def test_a_real_pool_streams_the_same_certificate_and_budgeted_partial():
    with Executor(2) as pool:
        assert pool.parallel
        assert _json(pave(_bs(LINE), pool)) == _json(pave(_bs(LINE)))
        assert _json(pave(_bs(LINE), pool, box_budget=3)) == _json(pave(_bs(LINE), box_budget=3))


def test_a_worker_batch_evaluates_each_box_in_order_and_times_it(plane_fast):
    from rigor_gyro.core.boxes import Box
    boxes = [Box.of({"eps": (0, 1), "Omega2": (0, 1)}), Box.of({"eps": (2, 3), "Omega2": (0, 1)})]
    out = stream.evaluate_batch((_half_plane, "eigenfrequencies", "{}", "{}", "{}", 64),
                                [(json.dumps(b.to_json()), ["bracket_4"]) for b in boxes])
    assert [o for o, _ in out] == [{"bracket_4": ["undecided", "both"]}, {"bracket_4": ["proved", "holds"]}]
    assert all(t >= 0 for _, t in out)


def test_refine_streams_to_the_in_process_refinement(plane_fast):
    coarse = _json(pave(_bs(plane_fast.replace('"1/32"', '"1/8"'))))
    bs, state = resume_state(coarse, refine="1/32")
    alone = _json(pave(bs, state=state))
    bs, state = resume_state(coarse, refine="1/32")
    assert _json(pave(bs, Shuffled(4, 7), state=state)) == alone


@pytest.mark.parametrize("scheduler", [None, "tcp://scheduler:8786"])
def test_a_dask_executor_gets_batches_of_its_own_target_seconds(plane_fast, scheduler, monkeypatch):
    # the pool's target 0 (one box a batch) and Dask's large, or the other way round: each executor's batches
    # follow its own target (Dask's round trip through the scheduler costs more: larger batches)
    big, zero = (("DASK_TARGET_SECONDS", "TARGET_SECONDS") if scheduler is None else
                 ("TARGET_SECONDS", "DASK_TARGET_SECONDS"))
    monkeypatch.setattr(stream, big, 10.0)
    monkeypatch.setattr(stream, zero, 0)
    ex = Shuffled(2, 0)
    ex.scheduler = scheduler
    assert _json(pave(_bs(plane_fast), ex)) == _json(pave(_bs(plane_fast)))
    assert max(ex.submitted) == 1 and len(ex.submitted) > 10


@pytest.mark.parametrize("executor", ["in process", "shuffled stream"])
def test_a_time_limit_ends_an_evaluation_of_the_whole_box_that_outlasts_it(plane_fast, monkeypatch, executor):
    """A one-box paving whose single evaluation outlasts --time-limit (the relay at +-0.5 % in six parameters
    takes a minute in one box) stops at the limit with the box pending, instead of at the end of the
    evaluation; the partial paving checks and resumes to the whole one. (The stand-in evaluation here sleeps
    on the whole box: the alarm interrupts it, as it interrupts Python code between Arb calls.)"""
    import time
    import rigor_gyro.margins.paving as paving
    from tests.test_paving_anytime import _half_plane as instant
    whole_box = _json(pave(_bs(plane_fast)))["box"]

    def slow(kind, pj, oj, mj, box_json, claims, prec):
        if json.loads(box_json) == whole_box:
            time.sleep(30)
        return instant(kind, pj, oj, mj, box_json, claims, prec)

    monkeypatch.setattr(paving, "evaluate_task", slow)
    ex = Executor(1) if executor == "in process" else Shuffled(3, 0)
    t0 = time.monotonic()
    data = _json(pave(_bs(plane_fast), ex, time_limit=0.5))
    assert time.monotonic() - t0 < 20            # not the 30 s of the evaluation
    assert "time limit" in data["stopped"] and data["boxes_evaluated"] == 0
    assert [g["boxes"] for g in data["pending"]] == [[whole_box]]
    assert check_certificate(data).ok
    monkeypatch.setattr(paving, "evaluate_task", instant)
    bs, state = resume_state(data)
    assert _json(pave(bs, state=state)) == _json(pave(_bs(plane_fast)))
