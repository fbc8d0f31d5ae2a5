"""Real roots of a smooth scalar function: interval Newton with existence-and-uniqueness proofs.

python-flint has no ``arb_calc``; this module is its replacement, written on ``arb_series`` (Taylor
mode gives f and f' enclosed over a whole interval in one evaluation).

Guarantee (Moore's theorem): for a piece X and a point m in X, if the Newton image
N = m - f(m)/f'(X) lies in the interior of X, then f has exactly one root in X, and it lies in N.
If N and X are disjoint, or f(X) excludes 0, X holds no root. Every other outcome is
``RootStatus.UNKNOWN`` with the reason (derivative may vanish: a multiple root or a turning point;
too little precision; depth limit).

Requires: ``f`` maps an ``arb_series`` to an ``arb_series`` and is real analytic on the bracket;
it must be written with ball operations only (no floats).

Precision: the current working precision (use :func:`rigor_gyro.core.balls.escalate` around the call).

Fails when: a root is multiple (f' vanishes there): reported UNKNOWN, never as one root; a root
sits exactly on a bisection point: the two unique enclosures overlap and both are downgraded to
UNKNOWN.

Example:
    >>> from flint import ctx
    >>> from rigor_gyro.core.balls import working_precision, contains
    >>> with working_precision(128):
    ...     r = newton_root(lambda x: x * x - 2, "1", "2")
    ...     ok = contains(r.enclosure, arb(2).sqrt())
    >>> r.status.name, ok
    ('UNIQUE', True)
    >>> with working_precision(128):
    ...     newton_root(lambda x: (x - 1) ** 2, "0", "2").status.name
    'UNKNOWN'
"""
from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Callable

from flint import arb, arb_series

from .balls import (ball, certainly_gt, certainly_lt, certainly_nonzero, current_precision, interval,
                    possibly_zero, rel_width_at_most, series_coefficients, series_length)
from .errors import ParameterError

__all__ = ["RootStatus", "RootPiece", "Isolation", "enclose_f_df", "newton_root", "isolate_roots",
           "merge_shared_roots"]

SeriesFunction = Callable[[arb_series], arb_series]


class RootStatus(Enum):
    UNIQUE = "unique"      # exactly one root in the piece, enclosed
    EMPTY = "empty"        # certainly no root in the piece
    UNKNOWN = "unknown"    # undecided; see the reason


@dataclass
class RootPiece:
    """A piece [lo, hi] of the bracket with its verdict; ``enclosure`` is set when UNIQUE."""

    lo: arb
    hi: arb
    status: RootStatus
    enclosure: arb | None = None
    reason: str = ""
    iterations: int = 0
    #: the inner endpoints of the pieces merged into this one (a root on a shared endpoint)
    parts: tuple = ()


def enclose_f_df(f: SeriesFunction, x: arb) -> tuple[arb, arb]:
    """Balls containing f(t) and f'(t) for every t in the ball x (Taylor mode, order 1)."""
    # python-flint cuts series to ctx.cap terms silently: keep (at least) the two needed, and read
    # them through series_coefficients, which refuses a series cut shorter than that
    with series_length(2):
        s = f(arb_series([x, 1], prec=2))
        fx, dfx = series_coefficients(s if isinstance(s, arb_series) else ball(s), 2)
    return fx, dfx


def _disjoint(a: arb, b: arb) -> bool:
    return certainly_lt(a.upper(), b.lower()) or certainly_gt(a.lower(), b.upper())


def newton_root(f: SeriesFunction, lo: object, hi: object, *, rel_tol: object | None = None,
                max_iter: int = 200) -> RootPiece:
    """Decide the piece [lo, hi] by interval Newton; refine a unique root to ``rel_tol`` (relative
    width) when given, otherwise until the enclosure stops shrinking."""
    lo_b, hi_b = ball(lo), ball(hi)
    x = interval(lo_b, hi_b)
    fx, _ = enclose_f_df(f, x)
    if certainly_nonzero(fx):
        return RootPiece(lo_b, hi_b, RootStatus.EMPTY, reason="f excludes 0 on the piece")
    proved = False
    for it in range(1, max_iter + 1):
        m = x.mid()
        fm, _ = enclose_f_df(f, m)
        _, dfx = enclose_f_df(f, x)
        if possibly_zero(dfx):
            if proved:  # cannot happen for a proper refinement, but never claim more than we know
                return RootPiece(lo_b, hi_b, RootStatus.UNIQUE, x, "unique; refinement stopped: "
                                 "f' enclosure touches 0 (raise precision)", it)
            return RootPiece(lo_b, hi_b, RootStatus.UNKNOWN, reason="f' may vanish on the piece "
                             "(multiple root or turning point): bisect, or the root is not simple", iterations=it)
        n = m - fm / dfx
        if not n.is_finite():
            return RootPiece(lo_b, hi_b, RootStatus.UNKNOWN, reason="Newton image is not finite "
                             "(raise precision)", iterations=it)
        if _disjoint(n, x):
            if proved:
                raise AssertionError("Newton image left a proved enclosure: bug in f")
            return RootPiece(lo_b, hi_b, RootStatus.EMPTY, reason="Newton image disjoint from the piece",
                             iterations=it)
        inside = bool(x.contains_interior(n))
        proved = proved or inside
        # The root (if any) lies in x and in n: keep the intersection while it shrinks.
        y = n if inside else x.intersection(n)
        if not certainly_lt(y.rad(), x.rad()):
            if proved:
                reason = "Newton image inside the piece"
                if rel_tol is not None and not rel_width_at_most(x, rel_tol):
                    reason += f"; enclosure stopped shrinking before relative width {rel_tol} (raise precision)"
                return RootPiece(lo_b, hi_b, RootStatus.UNIQUE, x, reason, it)
            return RootPiece(lo_b, hi_b, RootStatus.UNKNOWN, reason="Newton image not inside the piece "
                             "and not shrinking it: bisect or raise precision", iterations=it)
        x = y
        if proved and rel_tol is not None and rel_width_at_most(x, rel_tol):
            return RootPiece(lo_b, hi_b, RootStatus.UNIQUE, x, "Newton image inside the piece", it)
    status = RootStatus.UNIQUE if proved else RootStatus.UNKNOWN
    return RootPiece(lo_b, hi_b, status, x if proved else None, f"stopped after {max_iter} iterations", max_iter)


@dataclass
class Isolation:
    """The pieces covering a bracket, each UNIQUE, EMPTY or UNKNOWN."""

    pieces: list[RootPiece]
    #: when a search stopped early: (the decided pieces, tiling [lo, x]; the point x) to resume from
    resume: tuple | None = field(default=None, compare=False)

    @property
    def roots(self) -> list[arb]:
        return [p.enclosure for p in self.pieces if p.status is RootStatus.UNIQUE]

    @property
    def unknown(self) -> list[RootPiece]:
        return [p for p in self.pieces if p.status is RootStatus.UNKNOWN]

    @property
    def complete(self) -> bool:
        """True when every piece is decided: then ``roots`` are all the roots in the bracket."""
        return not self.unknown


def isolate_roots(f: SeriesFunction, lo: object, hi: object, *, rel_tol: object | None = None,
                  max_depth: int = 30, max_pieces: int = 20000) -> Isolation:
    """Cover [lo, hi] by pieces, each certified root-free or holding exactly one (enclosed) root.

    Pieces that stay undecided after ``max_depth`` bisections are returned as UNKNOWN with the
    reason; ``Isolation.complete`` tells whether all roots in the bracket were found.
    """
    lo_b, hi_b = ball(lo), ball(hi)
    if not certainly_lt(lo_b, hi_b):
        raise ParameterError(f"bracket [{lo}, {hi}] is empty or not ordered")
    done: list[RootPiece] = []
    stack: list[tuple[arb, arb, int]] = [(lo_b, hi_b, 0)]
    while stack:
        a, b, depth = stack.pop()
        piece = newton_root(f, a, b, rel_tol=rel_tol)
        if piece.status is RootStatus.UNKNOWN and depth < max_depth and len(done) + len(stack) < max_pieces:
            mid = ((a + b) / 2).mid()
            stack.append((mid, b, depth + 1))
            stack.append((a, mid, depth + 1))
            continue
        if piece.status is RootStatus.UNKNOWN:
            piece.reason += f" (after {depth} bisections)"
        done.append(piece)
    done.sort(key=lambda p: float(p.lo.mid()))  # float only orders pieces, decides nothing
    return Isolation(merge_shared_roots(f, done, rel_tol))


def merge_shared_roots(f: SeriesFunction, pieces: list[RootPiece], rel_tol: object | None) -> list[RootPiece]:
    """A root on a shared endpoint is found by both neighbours. Their enclosures then overlap; if
    Newton proves a unique root on the hull of the two enclosures, both found the same root and the
    two pieces merge into one holding exactly one root. Otherwise both become UNKNOWN."""
    out: list[RootPiece] = []
    for p in pieces:
        q = out[-1] if out else None
        if (q is not None and q.status is RootStatus.UNIQUE and p.status is RootStatus.UNIQUE
                and q.enclosure.overlaps(p.enclosure)):
            hull = q.enclosure.union(p.enclosure)
            # Pad the hull so that Newton has an interior to land in (the enclosures may be exact).
            pad = hull.rad() + (hull.abs_upper() + 1) * arb(2) ** (16 - current_precision())
            r = newton_root(f, hull.lower() - pad, hull.upper() + pad, rel_tol=rel_tol)
            if r.status is RootStatus.UNIQUE:
                out[-1] = RootPiece(q.lo, p.hi, RootStatus.UNIQUE, r.enclosure,
                                    "root on a piece boundary, unique on the hull of both enclosures",
                                    q.iterations + p.iterations + r.iterations, parts=q.parts + (q.hi,) + p.parts)
            else:
                for x in (q, p):
                    x.status, x.enclosure = RootStatus.UNKNOWN, None
                    x.reason = "enclosure overlaps a neighbour's (root on a piece boundary?)"
                out.append(p)
            continue
        out.append(p)
    return out
