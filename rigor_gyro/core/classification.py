"""The result of classifying a printed number (core.misprints, core.chain_classify): the class, the
reading that explains the print, every class that fits, and for a misprint the intended number.

Guarantee: a plain record (no computation). Failure mode: none.
"""
from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Classification"]


@dataclass
class Classification:
    cls: str
    reading: str
    #: every class that fits, in the order of CLASSES (the first is ``cls``)
    readings: list[str] = field(default_factory=list)
    #: for a misprint class decided against a paper chain: the print with the edit undone
    intended: str | None = None
    #: for ``propagated-misprint``: the upstream row whose misprint the print carries
    upstream: str | None = None
