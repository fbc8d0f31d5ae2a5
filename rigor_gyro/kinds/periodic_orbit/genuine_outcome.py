"""The ``orbit_genuine`` claim from a classified root search of g, shared by the paper's relay model
(:mod:`.claims`) and the user's state-space plant (:mod:`.plant_report`), so both say the same thing.

Guarantee: proved only for a root certified genuine (``main``); refuted only when the search was exhaustive
(all of (0, oo), every root classified) and no root is genuine, with the record of that search; otherwise
inconclusive, saying what is missing. Precision: the texts' balls' own. Fails when: never.
"""
from __future__ import annotations

from typing import Any

from ...core.outcome import Status
from .texts import interval_text as _fmt, stored_bounds as _bounds

__all__ = ["no_orbit_record", "orbit_genuine_outcome"]


def no_orbit_record(tail_point, theta_min, spurious: list) -> dict[str, Any]:
    """The stored record of an exhaustive search that found no genuine orbit: the tail point, the root-free
    start and each spurious root with why it is spurious."""
    return {"searched": "(0, oo)", "tail_point": _bounds(tail_point), "theta_min": _bounds(theta_min),
            "roots": [{"theta": _bounds(v.theta), "spurious_because": v.reason,
                       "witness_t": _bounds(v.witness_t) if v.witness_t is not None else None}
                      for v in spurious]}


def orbit_genuine_outcome(main, why_main: str, genuine: list, spurious: list, rng: str, *, complete: bool,
                          exhaustive: bool, no_orbit: dict | None, beyond: str, undecided_reason: str,
                          whose: str = "") -> tuple:
    """(status, reason[, counterexample]) of ``orbit_genuine``: ``main`` is the scene's orbit (a genuine root)
    or None, ``rng`` the searched range's text, ``beyond`` what a search short of (0, oo) leaves out,
    ``undecided_reason`` half_period's reason when not every root was classified, ``whose`` words after
    "genuine orbit" (" of the relay system")."""
    if main is not None:
        return (Status.PROVED, f"{why_main}, theta* = {_fmt(main.theta, 16)}: {main.reason}"
                + (f"; {len(genuine) - 1} further genuine orbit(s) proved likewise" if len(genuine) > 1 else ""))
    if not complete:
        return Status.INCONCLUSIVE, "no genuine orbit certified and not every root classified: " + undecided_reason
    wit = "; ".join(f"theta = {_fmt(v.theta, 10)}: {v.reason}" for v in spurious[:4])
    text = (f"none of the {len(spurious)} root(s) of g on {rng} is a genuine orbit{whose}: {wit}"
            + (" ..." if len(spurious) > 4 else "") if spurious else
            f"g has no root on {rng}: there is no symmetric orbit with two switchings per period")
    return (Status.REFUTED, text, no_orbit) if exhaustive else (Status.INCONCLUSIVE, text + beyond)
