"""The executors behind pavings and scans (``rigor_gyro.margins.executors``): ``map`` must return
``[fn(*t) for t in tasks]`` in order, whatever the worker count and batching, since a paving attaches
each result to its sub-box by position (a result moved by one would be a verdict for the wrong box).
The Dask paths are exercised by tests/test_margins.py (a local cluster, slow); here the in-process and
process-pool paths, in a second or two.
"""
import os

import pytest

from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins import executors as X


def _task(i: int, j: int) -> tuple[int, int, int]:
    return i, j, i * 1000 + j            # a module-level function: picklable for the pool


def test_default_workers_are_the_cores_this_process_may_use():
    assert X.default_workers() == len(os.sched_getaffinity(0)) >= 1
    with X.make_executor() as ex:
        assert ex.workers == X.default_workers()
    with X.make_executor(3) as ex:
        assert ex.workers == 3


@pytest.mark.parametrize("workers", [0, 1, "1", -2])
def test_one_worker_or_fewer_maps_in_process(workers):
    with X.make_executor(workers) as ex:
        assert ex.workers == 1 and ex._pool is None and ex.label == "in process"
        assert ex.map(_task, [(i, -i) for i in range(7)]) == [_task(i, -i) for i in range(7)]
        assert ex.map(_task, []) == []


@pytest.mark.parametrize("n", [1, 2, 3, 31, 32, 33, 65, 200])
def test_a_pool_returns_every_result_once_in_the_order_of_the_tasks(n):
    """2 workers and 16 batches per worker: n tasks split into batches of n // 32 (at least 1), the last
    one shorter; fewer tasks than workers are run in process. Each result is at its task's position."""
    tasks = [(i, n - i) for i in range(n)]
    with X.make_executor(2) as ex:
        assert ex.label == "process pool (2 workers)" and ex._pool is not None
        assert ex.map(_task, tasks) == [_task(*t) for t in tasks]


def test_fewer_tasks_than_workers_never_reach_the_pool(monkeypatch):
    with X.make_executor(4) as ex:
        monkeypatch.setattr(ex._pool, "map", lambda *a, **k: pytest.fail("the pool was used"))
        assert ex.map(_task, [(1, 2), (3, 4), (5, 6)]) == [_task(1, 2), _task(3, 4), _task(5, 6)]


def test_the_batches_cover_the_tasks_in_order(monkeypatch):
    """What the pool is given: batches of len(tasks) // (workers * 16) consecutive tasks, all of them."""
    seen = []

    class Pool:
        def map(self, fn, fns, batches):
            batches = list(batches)
            seen.append([len(b) for b in batches])
            return [X._run_batch(f, b) for f, b in zip(fns, batches)]

        def shutdown(self):
            pass
    ex = X.Executor(1)
    ex.workers, ex._pool = 2, Pool()
    tasks = [(i, 0) for i in range(70)]
    assert ex.map(_task, tasks) == [_task(*t) for t in tasks]
    assert seen == [[2] * 35]                     # 70 // 32 = 2
    tasks = [(i, 1) for i in range(20)]
    assert ex.map(_task, tasks) == [_task(*t) for t in tasks]
    assert seen[-1] == [1] * 20                   # 20 // 32 = 0: batches of one
    ex.close()


def test_a_scheduler_that_cannot_be_reached_is_bad_input():
    pytest.importorskip("dask.distributed")
    with pytest.raises(ParameterError, match=r"--scheduler 'bogus': cannot reach a Dask scheduler.*'local'"):
        X.Executor(1, "bogus")                  # not an address: refused at once (a closed port waits 10 s)
