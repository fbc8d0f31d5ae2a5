"""Progress on a terminal, quiet everywhere else (display only: nothing here decides or is written).

A bar is shown only when standard error is a terminal, ``CI`` is not set, the command was not asked to
be quiet and `tqdm <https://pypi.org/project/tqdm/>`_ is installed (the ``progress`` extra; the package
works without it, silently). tqdm sizes each line to the terminal's width (``dynamic_ncols``), and a
bar with ``delay`` appears only once the work has taken that long, so quick proofs print nothing extra.

Example (on a pipe, as here, the bar is a no-op):
    >>> with progress_bar("prove", enabled=True) as bar:
    ...     bar.update(1); bar.status("vdot_direct, 64 bits")
"""
from __future__ import annotations

import contextlib
import io
import os
import shutil
import sys
from typing import Iterator

__all__ = ["progress_bar", "wanted", "Bar"]


def wanted(enabled: bool = True) -> bool:
    """Whether a bar would be drawn: ``enabled``, standard error a terminal, not under CI, tqdm importable."""
    if not enabled or os.environ.get("CI") or not _isatty(sys.stderr):
        return False
    from importlib.util import find_spec
    return find_spec("tqdm") is not None


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class Bar:
    """A tqdm bar, or nothing: ``update(n)``, ``status(text)`` (the text after the counts)."""

    def __init__(self, bar=None):
        self._bar = bar

    def update(self, n: int = 1) -> None:
        if self._bar is not None:
            self._bar.update(n)

    def status(self, text: str) -> None:
        if self._bar is not None:
            self._bar.set_postfix_str(text, refresh=True)

    def total(self, n: int) -> None:
        if self._bar is not None and self._bar.total != n:
            self._bar.total = n
            self._bar.refresh()


@contextlib.contextmanager
def progress_bar(desc: str, *, total: int | None = None, unit: str = "it", delay: float = 0.0,
                 enabled: bool = True) -> Iterator[Bar]:
    """A :class:`Bar` for the block, closed (its line cleared) on exit; see the module docstring."""
    if not wanted(enabled):
        yield Bar()
        return
    from tqdm import tqdm
    try:        # a real terminal: tqdm follows its width as it changes
        os.get_terminal_size(sys.stderr.fileno())
        width = {"dynamic_ncols": True}
    except (AttributeError, OSError, ValueError, io.UnsupportedOperation):
        width = {"ncols": shutil.get_terminal_size((80, 24)).columns}       # $COLUMNS, else 80
    bar = tqdm(desc=desc, total=total, unit=unit, delay=delay, leave=False, file=sys.stderr, mininterval=0.2,
               **width)
    try:
        yield Bar(bar)
    finally:
        bar.close()
