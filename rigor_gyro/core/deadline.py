"""Wall-clock budgets: ``--time-limit`` for a proof or a threshold search.

A budget never decides anything: when it runs out, the caller reports every claim it had not yet
decided as inconclusive with the reason "time limit", and keeps what it had decided before.

:func:`time_limit` arms a real-time alarm (``signal.setitimer``) for the block; when it fires,
:class:`TimeLimitReached` is raised inside whatever Python code runs at that moment (an Arb call in C
finishes first). It derives from ``BaseException``, like ``KeyboardInterrupt``, so the ``except
Exception`` of a search or a claim cannot swallow it; python-flint's precision contexts are restored by
their ``with`` blocks on the way out. The alarm needs Unix and the main thread: elsewhere the budget is
checked only between steps (:meth:`Budget.expired`), which the docstring of each caller states.

Example:
    >>> with time_limit(None) as budget:
    ...     budget.expired(), budget.remaining() is None
    (False, True)
"""
from __future__ import annotations

import contextlib
import math
import signal
import threading
import time
from typing import Iterator

__all__ = ["TimeLimitReached", "Budget", "time_limit", "until", "check_time_limit"]

#: the largest budget accepted, in seconds (a week): anything larger is a typo
MAX_SECONDS = 7 * 24 * 3600


class TimeLimitReached(BaseException):
    """The wall-clock budget ran out inside a computation (raised by the alarm of :func:`time_limit`)."""


class Budget:
    """A deadline ``seconds`` after creation (``None``: no limit). ``fired`` is set when the alarm went
    off, so an exception that the alarm caused inside a C callback (seen as another exception type) can
    still be told apart from a bug."""

    def __init__(self, seconds: float | None):
        self.seconds = seconds
        self.start = time.monotonic()
        self.fired = False

    def remaining(self) -> float | None:
        """Seconds left (never below 0), or None without a limit."""
        if self.seconds is None:
            return None
        return max(0.0, self.seconds - (time.monotonic() - self.start))

    def expired(self) -> bool:
        return self.fired or (self.seconds is not None and self.remaining() == 0.0)

    def reason(self) -> str:
        return f"time limit of {self.seconds:g} s reached (--time-limit)"


def check_time_limit(seconds: object, name: str = "time limit") -> float | None:
    """``seconds`` as a float in (0, MAX_SECONDS], or None for no limit; ValueError naming ``name``."""
    if seconds is None:
        return None
    if isinstance(seconds, bool) or not isinstance(seconds, (int, float)):
        raise ValueError(f"{name} must be a number of seconds, got {seconds!r}")
    s = float(seconds)
    if not (math.isfinite(s) and 0 < s <= MAX_SECONDS):
        raise ValueError(f"{name} must be > 0 and at most {MAX_SECONDS} seconds (a week), got {seconds!r}")
    return s


def _can_alarm() -> bool:
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


@contextlib.contextmanager
def time_limit(seconds: float | None) -> Iterator[Budget]:
    """Run the block under a budget of ``seconds`` (None: no limit); see the module docstring. The
    previous alarm handler and timer are restored on exit (a nested budget is not supported: the inner
    one replaces the outer for its duration, and the outer's remaining time is re-armed after it)."""
    budget = Budget(check_time_limit(seconds))
    if budget.seconds is None or not _can_alarm():
        yield budget
        return

    def fire(signum, frame):
        budget.fired = True
        raise TimeLimitReached(budget.reason())

    old_handler = signal.signal(signal.SIGALRM, fire)
    old_delay, _ = signal.setitimer(signal.ITIMER_REAL, budget.seconds)
    t0 = time.monotonic()
    try:
        yield budget
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old_handler)
        if old_delay:
            signal.setitimer(signal.ITIMER_REAL, max(1e-3, old_delay - (time.monotonic() - t0)))


@contextlib.contextmanager
def until(budget: Budget) -> Iterator[None]:
    """Run the block under what is left of ``budget`` (a :class:`Budget` made earlier): :class:`TimeLimitReached`
    inside the block when it runs out (``budget.fired`` is then set), at once when it has run out already.
    Without a limit nothing is armed. Where the alarm does not work (not Unix, not the main thread) the block
    runs to its end, as :func:`time_limit` says."""
    left = budget.remaining()
    if left is None:
        yield
        return
    if left <= 0:
        budget.fired = True
        raise TimeLimitReached(budget.reason())
    try:
        with time_limit(left):
            yield
    except TimeLimitReached:
        budget.fired = True
        raise
