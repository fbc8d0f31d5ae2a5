"""Where independent tasks run: in this process, on a process pool, or on a Dask distributed cluster.

Tasks and results are plain strings and JSON-able data (exact rationals as text; balls are never
pickled), and every executor returns the results in the order of the tasks, so a paving is
byte-identical whatever the executor and the worker count.

``map`` runs a list of tasks and returns when all are done (a barrier); ``submit``/``wait_any``/``result``
stream them (the paving's frontier, :mod:`.stream`: results taken as they come), and ``share`` sends a
value every task needs to each Dask worker once.

Dask is an optional extra (``pip install 'rigor_gyro[dask]'``): ``--scheduler ADDRESS`` connects to an
existing scheduler (``tcp://host:8786``), ``--scheduler local`` starts a ``LocalCluster`` of
``workers`` processes for the run.

A library call needs no ``if __name__ == "__main__":`` guard: the worker processes are started with the
calling script hidden from them (:func:`_main_hidden`; Python's spawn and forkserver start methods would
otherwise run the script again in each worker, and Dask's workers fail to start), and the pool forks
where the platform can. Tasks are functions of this package, so the workers never need the script.

Dask always runs an HTTP server beside its scheduler, even with ``dashboard_address=None`` (an upstream
bug, dask/distributed#8136): the local cluster binds it, and the scheduler, to 127.0.0.1 on a free
port, so it neither collides with a running dashboard on :8787 nor listens beyond this machine.

Fails when: Dask is asked for and not installed: :class:`~rigor_gyro.core.errors.ParameterError`
naming the extra (exit 2).
"""
from __future__ import annotations

import contextlib
import multiprocessing
import os
import sys
from typing import Any, Callable, Iterator, Sequence

from ..core.errors import ParameterError

__all__ = ["Executor", "make_executor", "default_workers"]


#: batches per worker and map call: small batches balance uneven tasks, few batches keep the scheduler's
#: share of the CPU low (on a machine with as many cores as workers, Dask's scheduler competes with them:
#: measured on 2 cores, 4 per worker paves the eigenfrequency benchmark in 3.7-4.2 s, 16 in 4.7 s)
BATCHES_PER_WORKER = {"pool": 16, "dask": 4}


def default_workers() -> int:
    """The cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover (not Linux)
        return max(1, os.cpu_count() or 1)


@contextlib.contextmanager
def _main_hidden() -> Iterator[None]:
    """While worker processes start: ``__main__`` without ``__file__`` and with ``__spec__`` None, so that a
    spawned or forkserver child does not import and run the calling script again (see the module docstring)."""
    main = sys.modules.get("__main__")
    saved = {k: getattr(main, k) for k in ("__file__", "__spec__") if main is not None and hasattr(main, k)}
    try:
        if "__file__" in saved:
            del main.__file__
        if "__spec__" in saved:
            main.__spec__ = None
        yield
    finally:
        for k, v in saved.items():
            setattr(main, k, v)


def _pool_context():
    """fork where the platform has it (no script is re-run, the parent's imports are inherited); else the
    platform's default start method."""
    return multiprocessing.get_context("fork") if "fork" in multiprocessing.get_all_start_methods() else None


def _run_batch(fn: Callable, batch: list) -> list:
    return [fn(*args) for args in batch]


class Executor:
    """``map(fn, tasks)``: ``[fn(*t) for t in tasks]`` in order, possibly in parallel (in batches)."""

    def __init__(self, workers: int = 1, scheduler: str | None = None):
        self.workers = max(1, int(workers))
        self.scheduler = scheduler
        self._pool = None
        self._client = None
        self._cluster = None
        if scheduler is not None:
            try:
                from dask.distributed import Client, LocalCluster
            except ImportError:
                raise ParameterError("--scheduler needs Dask distributed: pip install 'rigor_gyro[dask]'") from None
            if scheduler == "local":
                with _main_hidden():
                    self._cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1, processes=True,
                                                 host="127.0.0.1", dashboard_address="127.0.0.1:0")
                self._client = Client(self._cluster)
            else:
                try:
                    self._client = Client(scheduler, timeout=10)
                except (OSError, ValueError, TypeError, TimeoutError) as e:
                    raise ParameterError(f"--scheduler {scheduler!r}: cannot reach a Dask scheduler there "
                                         f"({type(e).__name__}: {e}); give tcp://host:port of a running "
                                         "scheduler, or 'local'") from None
        elif self.workers > 1:
            from concurrent.futures import ProcessPoolExecutor   # only when used: 20 ms of every start-up
            self._pool = ProcessPoolExecutor(max_workers=self.workers, mp_context=_pool_context())

    @property
    def label(self) -> str:
        if self._client is not None:
            return f"dask ({self.scheduler})"
        return f"process pool ({self.workers} workers)" if self._pool is not None else "in process"

    def map(self, fn: Callable, tasks: Sequence[tuple]) -> list[Any]:
        tasks = list(tasks)
        if not tasks:
            return []
        if self.runs_here(len(tasks)):
            return [fn(*t) for t in tasks]
        # small batches balance uneven tasks (a hard box takes 100 times an easy one); batches of
        # many cheap tasks keep the per-task overhead of the pool or the scheduler low
        parts = self.workers * BATCHES_PER_WORKER["dask" if self._client is not None else "pool"]
        size = max(1, len(tasks) // parts)
        batches = [tasks[i:i + size] for i in range(0, len(tasks), size)]
        if self._client is not None:
            futures = self._client.map(_run_batch, [fn] * len(batches), batches, pure=False)
            results = self._client.gather(futures)
        else:
            results = list(self._pool.map(_run_batch, [fn] * len(batches), batches))
        return [r for batch in results for r in batch]

    def runs_here(self, n: int) -> bool:
        """Whether :meth:`map` runs ``n`` tasks in this process: without a pool or a cluster, or with fewer tasks
        than workers (the first levels of a paving: nothing to gain from the pool or the scheduler but their round
        trip; the results are the same wherever a task runs). A time limit's alarm can then interrupt them."""
        return self._pool is None and self._client is None or n < self.workers

    @property
    def parallel(self) -> bool:
        """Whether tasks run elsewhere (a pool or a Dask cluster): :meth:`submit` then returns at once."""
        return self._pool is not None or self._client is not None

    def submit(self, fn: Callable, *args) -> Any:
        """Start ``fn(*args)`` on a worker: a future (:meth:`wait_any` reports it done). In process, it runs
        now and the future returned is already done."""
        if self._client is not None:
            return self._client.submit(fn, *args, pure=False)
        if self._pool is not None:
            return self._pool.submit(fn, *args)
        from concurrent.futures import Future
        f: Future = Future()
        try:
            f.set_result(fn(*args))
        except Exception as e:          # noqa: BLE001 (handed to the caller by result())
            f.set_exception(e)
        return f

    def share(self, value: Any) -> Any:
        """``value`` as a task argument sent to each worker once: on Dask scattered to every worker (a task
        then carries a reference); elsewhere ``value`` itself (a pool task pickles it, a few hundred bytes)."""
        if self._client is not None:
            return self._client.scatter([value], broadcast=True, hash=False)[0]
        return value

    def wait_any(self, futures: Sequence[Any], timeout: float | None = None) -> list[Any]:
        """The futures among ``futures`` that are done, waiting until one is (or ``timeout`` seconds)."""
        if not futures:
            return []
        if self._client is not None:
            from dask.distributed import wait
            try:
                done, _ = wait(list(futures), timeout=timeout, return_when="FIRST_COMPLETED")
            except TimeoutError:
                return []
            return list(done)
        from concurrent.futures import FIRST_COMPLETED, wait as cf_wait
        done, _ = cf_wait(list(futures), timeout=timeout, return_when=FIRST_COMPLETED)
        return list(done)

    @staticmethod
    def result(future: Any) -> Any:
        """A done future's result (its exception raised: a lost Dask worker's task is retried by Dask)."""
        return future.result()

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown()
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()

    def __enter__(self) -> "Executor":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def make_executor(workers: int | None = None, scheduler: str | None = None) -> Executor:
    return Executor(default_workers() if workers is None else workers, scheduler)
