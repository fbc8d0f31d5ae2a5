"""Wall times as text, for whoever prints one (the CLI, campaign and benchmark tables).

A wall time is run-dependent data, never part of a certificate or a proof, and decides nothing.
"""
from __future__ import annotations

__all__ = ["SHORTEST", "seconds_text"]

#: times below this many seconds print as "< 0.005 s" (two decimals would print a run as "0.00 s")
SHORTEST = 0.005


def seconds_text(s: float, unit: bool = True) -> str:
    """``s`` seconds as text: "< 0.005 s" below 5 ms, otherwise two decimals ("0.12 s", "61.71 s").
    ``unit=False`` leaves out the " s" (for a table column headed in seconds)."""
    text = f"< {SHORTEST}" if s < SHORTEST else f"{s:.2f}"
    return text + (" s" if unit else "")
