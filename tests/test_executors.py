"""The executors behind pavings and scans (``rigor_gyro.margins.executors``): ``map`` must return
``[fn(*t) for t in tasks]`` in order, whatever the worker count and batching, since a paving attaches
each result to its sub-box by position (a result moved by one would be a verdict for the wrong box).
A paving on a Dask local cluster is compared with the serial one in tests/test_margins.py; here the
in-process and process-pool paths, the Dask batching (with a stand-in client) and one local cluster's
shape: its workers are processes of one thread each (python-flint's precision and series cap are global
to a process, so two tasks in threads of one worker, or a worker in the caller's process, could change
each other's settings).
"""
import os

import pytest

from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins import executors as X


def _task(i: int, j: int) -> tuple[int, int, int]:
    return i, j, i * 1000 + j            # a module-level function: picklable for the pool


def _pid() -> int:
    return os.getpid()


def test_default_workers_are_the_cores_this_process_may_use(monkeypatch):
    assert X.default_workers() == len(os.sched_getaffinity(0)) >= 1
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0})
    assert X.default_workers() == 1
    monkeypatch.delattr(os, "sched_getaffinity")          # not Linux: the CPU count, at least 1
    for count, workers in ((5, 5), (1, 1), (None, 1)):
        monkeypatch.setattr(os, "cpu_count", lambda: count)
        assert X.default_workers() == workers, count
    with X.make_executor() as ex:
        assert ex.workers == X.default_workers()
    with X.make_executor(3) as ex:
        assert ex.workers == 3


def test_an_executor_runs_in_process_unless_told_otherwise():
    with X.Executor() as ex:
        assert ex.workers == 1 and ex._pool is None and ex._client is None and ex.label == "in process"


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
        assert ex._pool._max_workers == 4
        monkeypatch.setattr(ex._pool, "map", lambda *a, **k: pytest.fail("the pool was used"))
        assert ex.map(_task, [(1, 2), (3, 4), (5, 6)]) == [_task(1, 2), _task(3, 4), _task(5, 6)]


def test_as_many_tasks_as_workers_reach_the_pool(monkeypatch):
    used = []
    with X.make_executor(3) as ex:
        real = ex._pool.map
        monkeypatch.setattr(ex._pool, "map", lambda *a: used.append(1) or real(*a))
        tasks = [(1, 2), (3, 4), (5, 6)]
        assert ex.map(_task, tasks) == [_task(*t) for t in tasks] and used == [1]


class _Client:
    """A stand-in for a Dask client: records the batches it is given, runs them in order."""

    def __init__(self):
        self.seen = []

    def map(self, fn, fns, batches, pure=True):
        batches = list(batches)
        self.seen.append([len(b) for b in batches])
        return [fn(f, b) for f, b in zip(fns, batches)]

    def gather(self, futures):
        return list(futures)


def test_a_dask_client_gets_4_batches_per_worker_and_returns_every_result_in_order():
    ex = X.Executor(1)
    ex.workers, ex._client = 2, _Client()
    for n, sizes in ((70, [8] * 8 + [6]), (9, [1] * 9), (2, [1, 1])):   # 70 // (2 * 4) = 8
        tasks = [(i, n) for i in range(n)]
        assert ex.map(_task, tasks) == [_task(*t) for t in tasks]
        assert ex._client.seen[-1] == sizes, n
    ex._client.seen.clear()
    assert ex.map(_task, [(1, 1)]) == [_task(1, 1)] and ex._client.seen == []     # fewer than workers


@pytest.mark.parametrize("workers", [1, 3])
def test_a_local_dask_cluster_has_the_workers_asked_each_a_process_of_one_thread(workers):
    """One worker and three: Dask's own defaults (a worker per core, the cores shared out as threads) would
    differ from both on most machines, this one's 2 cores included."""
    pytest.importorskip("dask.distributed")
    with X.make_executor(workers, "local") as ex:
        assert ex.label == "dask (local)"
        assert sorted(ex._client.nthreads().values()) == [1] * workers
        pids = set(ex._client.run(os.getpid).values())
        assert len(pids) == workers and os.getpid() not in pids
        tasks = [(i, 0) for i in range(30)]
        assert ex.map(_task, tasks) == [_task(*t) for t in tasks]
        assert set(ex.map(_pid, [()] * 12)) <= pids                            # run on the workers


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
    with pytest.raises(ParameterError, match=r"--scheduler 'bogus'"):
        X.make_executor(1, "bogus")


_UNGUARDED = """
import sys
sys.path.insert(0, {root!r})
from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.paving import evaluate_task
ex = Executor(2, {scheduler!r})
print(ex.map(divmod, [(i, 3) for i in range(8)]))
print(ex.label)
ex.close()
"""


@pytest.mark.parametrize("scheduler", [None, "local"])
def test_a_script_without_a_main_guard_runs_the_pool_and_the_local_cluster(tmp_path, scheduler):
    """A user's script that makes an Executor at its top level, with no ``if __name__ == '__main__'``: the
    workers must not run the script again (Dask's would fail to start: 'Nanny failed to start')."""
    import subprocess
    import sys
    from pathlib import Path
    if scheduler:
        pytest.importorskip("dask.distributed")
    root = str(Path(__file__).resolve().parent.parent)
    script = tmp_path / "user_script.py"
    script.write_text(_UNGUARDED.format(root=root, scheduler=scheduler))
    run = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert run.returncode == 0, run.stderr[-2000:]
    lines = run.stdout.splitlines()
    assert lines[0] == str([divmod(i, 3) for i in range(8)])
    assert lines[1] == ("dask (local)" if scheduler else "process pool (2 workers)")
    assert "Nanny failed" not in run.stderr and "Port 8787 is already in use" not in run.stderr


@pytest.mark.parametrize("workers", [1, 2])
def test_submit_and_wait_any_stream_every_result_once(workers):
    import operator
    with X.Executor(workers) as ex:
        assert ex.parallel == (workers > 1) and ex.share((1, "a")) == (1, "a")
        futures = {ex.submit(operator.mul, i, 3): i for i in range(6)}
        seen = {}
        while len(seen) < 6:
            for f in ex.wait_any([f for f in futures if futures[f] not in seen]):
                seen[futures[f]] = ex.result(f)
        assert seen == {i: 3 * i for i in range(6)} and ex.wait_any([]) == []
        bad = ex.submit(operator.truediv, 1, 0)
        ex.wait_any([bad])
        with pytest.raises(ZeroDivisionError):
            ex.result(bad)
