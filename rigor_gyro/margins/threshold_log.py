"""The search log of a threshold (its ``steps``), replayed by the bisection rule of :func:`.threshold.find_threshold`.

The rule: the two search ends first (lo, then hi); when one is proved and the other refuted, the midpoint of
the proved point p and the refuted point r, which becomes p when proved and r when refuted, until the bracket
is within the requested relative width; after an inconclusive midpoint, the points :data:`.threshold.AROUND`
of the way from p to r, in order, until one is decided (it moves p or r). So the statuses of the steps fix
every next value: :func:`replay` re-derives the values, the final proved and refuted points, and the texts
``stopped`` may carry, from the stored statuses alone. A status flipped anywhere but at the last step
changes a later value and fails the replay; the checker re-decides the ends and the final two points.

Guarantee: :func:`replay` returns the texts the search could have written for these statuses (a time limit
can stop it between any two steps: its text, ``time limit of S s reached (--time-limit)...``, is matched by
pattern, S being the run's own); ``error`` names the first step that the rule does not produce.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from ..core.balls import rational_text

__all__ = ["Replay", "replay"]

_BUDGET = r"time limit of \S+ s reached \(--time-limit\)"


@dataclass
class Replay:
    proved_at: Fraction | None = None
    refuted_at: Fraction | None = None
    stopped: list[str] = field(default_factory=list)      # regular expressions, any one of them (full match)
    error: str = ""

    def stopped_ok(self, text: Any) -> bool:
        return isinstance(text, str) and any(re.fullmatch(p, text, flags=re.S) for p in self.stopped)

    @property
    def budget_only(self) -> bool:
        """Whether only a time limit can explain the stop (then an inconclusive step may be out of time)."""
        return bool(self.stopped) and all(p.startswith(_BUDGET) for p in self.stopped)


#: the most steps a threshold search takes
MAX_STEPS = 200
#: where the search tries next, as fractions of the way from the proved end to the refuted end, when a
#: midpoint is inconclusive: any decided point in between still halves part of the bracket
AROUND = (Fraction(3, 8), Fraction(5, 8), Fraction(1, 4), Fraction(3, 4), Fraction(1, 8), Fraction(7, 8))


def replay(steps: list[dict[str, Any]], lo: Fraction, hi: Fraction, width: Fraction, param: str) -> Replay:
    """The bisection rule run on the stored statuses (module docstring)."""
    out = Replay()
    values = [Fraction(s["value"]) for s in steps]
    sts = [s["status"] for s in steps]
    d = rational_text
    if len(steps) < 2 and values == [lo, hi][:len(steps)]:    # the time limit came before both ends were decided
        out.stopped = [_BUDGET + re.escape(" before the claim was decided at both ends")]
        return out
    if len(steps) < 2 or values[:2] != [lo, hi]:
        out.error = "the steps do not start at the search's two ends (lo, then hi)"
        return out
    if {sts[0], sts[1]} != {"proved", "refuted"}:
        if len(steps) != 2:
            out.error = "steps after search ends that are not one proved and one refuted"
            return out
        out.stopped = [re.escape(f"the claim is {sts[0]} at {param} = {d(lo)} and {sts[1]} at {param} = {d(hi)}; "
                                 "a threshold needs one proved end and one refuted end (widen --lo/--hi)")]
        if "inconclusive" in sts:
            out.stopped.append(_BUDGET + re.escape(" before the claim was decided at both ends"))
        return out
    p, r = (lo, hi) if sts[0] == "proved" else (hi, lo)
    i = 2

    def expect(x: Fraction) -> bool:
        if values[i] != x:
            out.error = (f"step {i + 1}: {param} = {d(values[i])}, but the bisection rule's next point after the "
                         f"statuses before it is {d(x)}")
            return False
        return True

    kept = _BUDGET + re.escape(": the bracket certified so far is kept")
    for _ in range(MAX_STEPS):
        if abs(r - p) <= width * max(abs(p), abs(r)):
            out.stopped = [""]
            break
        if i == len(steps):
            out.stopped = [kept]
            break
        m = (p + r) / 2
        if not expect(m):
            return out
        st, why, i = sts[i], steps[i].get("reason", ""), i + 1
        if st == "proved":
            p = m
            continue
        if st == "refuted":
            r = m
            continue
        tried_all = re.escape(f"the claim is inconclusive at {param} = {d(m)} and at the {len(AROUND)} points "
                              f"around it tried: {str(why)[:200]}")
        def short(n: int) -> str:       # time ran out after n < len(AROUND) points around m
            return _BUDGET + re.escape(f" after {n} of the {len(AROUND)} points around {param} = {d(m)}: the bracket "
                                       "certified so far is kept")
        if i == len(steps):
            out.stopped = [_BUDGET + re.escape(f" during the proof at {param} = {d(m)}: the bracket certified so "
                                               "far is kept"), short(0)]
            break
        moved = None
        for n, t in enumerate(AROUND):
            if i == len(steps):
                tried_all = short(n)
                break
            x = p + (r - p) * t
            if not expect(x):
                return out
            st, i = sts[i], i + 1
            if st == "proved":
                moved = (x, r)
                break
            if st == "refuted":
                moved = (p, x)
                break
        if moved is None:
            out.stopped = [tried_all]
            break
        p, r = moved
    else:
        out.stopped = [re.escape(f"bisection budget of {MAX_STEPS} point proofs reached")]
    if i != len(steps):
        out.error = f"step {i + 1} and after: steps after the search stopped by its rule"
        return out
    out.proved_at, out.refuted_at = p, r
    return out
