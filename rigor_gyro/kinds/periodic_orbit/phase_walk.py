"""The root search of a fast nutation by half-periods (issue 41): one piece per nutation half-period.

Walks [lo, hi] from critical point to critical point of G (proposed by Newton's method on G' from the
phase the oscillation predicts: a search, it proves nothing). Each piece [u, c] between consecutive
proposed critical points is decided by :func:`.phase_pieces.phase_count` (0 or 1 root, the number
the end signs of G say), a root's enclosure by :func:`.phase_pieces.root_bracket`. Stretches the
envelope bound covers (``root_free``) are taken whole, with a galloping length. Where anything is
uncertain (a sign of G at a proposed end, a piece the leaves do not decide) the stretch up to the next
well-signed critical point goes to ``fallback`` (the Taylor-model search of :mod:`.claims`).

Guarantee: the returned pieces tile [lo, hi]; each is decided by a sound test (phase pieces carry the
reason prefix ``PHASE_REASON``) or is one of ``fallback``'s pieces. Precision: the current one.
Fails when: the oscillation cannot be followed (no proposal of a next critical point): the rest of the
range goes to ``fallback`` whole; an undecided fallback piece is returned as such (the caller escalates).
"""
from __future__ import annotations

import math

from flint import arb

from ...core.balls import certainly_lt, interval
from ...core.roots import RootPiece, RootStatus
from .phase_pieces import phase_count, root_bracket

__all__ = ["phase_walk", "PHASE_REASON"]

#: the reason prefix of a piece decided by phase_count (its witness kind is phase_empty / phase_unique)
PHASE_REASON = "phase:"


def _sign(x: arb) -> int:
    """1 / -1 when x is certainly > 0 / < 0, else 0: :func:`~rigor_gyro.core.balls.compare`'s rule (a
    finite ball, Arb's certain comparison) without its conversions (this runs ~10^5 times a search)."""
    if not x.is_finite():
        return 0
    return 1 if x > 0 else -1 if x < 0 else 0


def _next_critical(coeffs, u: arb, omega: float) -> arb | None:
    """A proposal (an exact point) of G's first critical point beyond u + a tenth of a half-period,
    by the local phase of G' = R cos(phi) (phi from G'(u), G''(u)) and Newton's method on G'."""
    try:
        c = coeffs(u, 3)
        g1, g2 = float(c[1].mid()), 2 * float(c[2].mid())
        phi0 = math.atan2(-g2 / omega, g1)
        t = (math.pi / 2 - phi0) % math.pi
        if t < 0.2:
            t += math.pi
        x = arb((u + arb(t / omega)).mid())
        half = math.pi / omega
        for _ in range(12):
            c = coeffs(x, 3)
            if _sign(c[2]) == 0:
                return None
            step = arb((c[1].mid() / (2 * c[2].mid())).mid())
            if abs(float(step.mid())) > half / 4:       # damped: stay near the predicted phase
                step = arb(math.copysign(half / 4, float(step.mid())))
            x = arb((x - step).mid())
            if not certainly_lt(abs(step), abs(x) * arb(2) ** -90):
                continue
            break
        off = float((x - u).mid()) * omega / math.pi
        if not (0.05 < off < 1.6):
            return None
        return x
    except (ValueError, OverflowError, ZeroDivisionError):
        return None


def phase_walk(coeffs, lo: arb, hi: arb, omega: float, fallback, root_free=None,
               envelope_reason: str = "envelope") -> list[RootPiece]:
    """Pieces tiling [lo, hi] (exact points), see the module docstring. ``fallback(a, b)`` returns
    pieces tiling [a, b]; ``root_free(a, b)`` True means no root (an envelope piece)."""
    out: list[RootPiece] = []
    half = math.pi / omega
    chunk = 4 * half
    u = lo
    su = _sign(coeffs(u, 1)[0])
    while certainly_lt(u, hi):
        if root_free is not None:
            b = arb((u + arb(chunk)).mid())
            b = hi if not certainly_lt(b, hi) else b
            if root_free(u, b):
                out.append(RootPiece(u, b, RootStatus.EMPTY, reason=envelope_reason))
                u, su, chunk = b, _sign(coeffs(b, 1)[0]), chunk * 2
                continue
            chunk = max(chunk / 4, 4 * half)
        c = _next_critical(coeffs, u, omega) if su != 0 else None
        if c is None:
            pcs = fallback(u, hi)
            out.extend(pcs)
            return out
        if not certainly_lt(c, hi):
            c = hi
        sc = _sign(coeffs(c, 1)[0])
        if sc == 0 or su == 0:
            nxt = _next_critical(coeffs, c, omega) if c is not hi else None
            end = hi if nxt is None or not certainly_lt(nxt, hi) else nxt
            pcs = fallback(u, end)
            out.extend(pcs)
            if any(p.status is RootStatus.UNKNOWN for p in pcs):
                return out
            u, su = end, _sign(coeffs(end, 1)[0])
            continue
        claim = 1 if sc != su else 0
        ok, leaves = phase_count(coeffs, u, c, claim)
        br = root_bracket(coeffs, u, c, su) if ok and claim else None
        if not ok or (claim and br is None):
            pcs = fallback(u, c)
            out.extend(pcs)
            if any(p.status is RootStatus.UNKNOWN for p in pcs):
                return out
        elif claim:
            out.append(RootPiece(u, c, RootStatus.UNIQUE, enclosure=interval(*br),
                                 reason=f"{PHASE_REASON} one root, {leaves} leaves"))
        else:
            out.append(RootPiece(u, c, RootStatus.EMPTY, reason=f"{PHASE_REASON} no root, {leaves} leaves"))
        u, su = c, sc
    return out
