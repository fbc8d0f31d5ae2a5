"""Root counts of G on a piece spanning up to a nutation half-period, decided leaf by leaf (issue 41).

A fast nutation makes G (the pole-free half-period function) oscillate: between two critical points
G is monotone, so a piece from one critical point to the next holds at most one root. A Taylor model
of G cannot resolve such a piece (it spans ~pi of nutation phase; the root search cut it into ~5
pieces per root), but the ball form of G's first derivatives over a sub-interval X (``coeffs(X, 3)``:
the nutation form, whose exponentials of lambda X are the phase's cos and sin over X) can, when X
is cut at the few places where the oscillation changes character. This module decides a piece
[lo, hi] by an adaptive bisection into leaves, each of which is

* **E**: G has one strict sign on the whole leaf (G(X), or the mean-value form G(m) + G'(X)(X - m)
  excludes 0), or
* **M(sigma)**: sigma G' > 0 on the whole leaf: sigma G'(X) > 0, or sigma G'(u) > 0 with
  sigma G''(X) > 0 (G' moves away from 0 along the leaf), or sigma G'(v) > 0 with sigma G''(X) < 0
  (G' moves towards 0 and is still signed at the leaf's end v),

with one sigma for every M leaf of the piece. Then every root of G on [lo, hi] lies in an M leaf and
is a strict crossing in the direction sigma; two crossings in one direction need one in the other
between them, so there is at most one root, exactly one when G(lo), G(hi) have opposite strict
signs (and sigma = sign G(hi)), none when they have one strict sign.

Guarantee: :func:`phase_count` returns 0 or 1 only when that is the number of roots of the function
whose Taylor coefficients ``coeffs(c, n)`` encloses (balls containing G^(j)(t)/j! for every t in the
ball c), on the closed piece [lo, hi] (exact points). Precision: the current working precision.
Fails when: a leaf is neither E nor M within ``max_depth`` bisections or ``max_leaves`` leaves, or an
end sign is uncertain: None (undecided; never a wrong count).

:func:`root_bracket` narrows the one root of such a piece to a certified sign change (a proposal by
Newton's method, the signs at the bracket's ends certified; sign bisection otherwise).
"""
from __future__ import annotations

import math

from flint import arb

from ...core.balls import certainly_lt, current_precision, interval

__all__ = ["phase_count", "leaf_kind", "root_bracket", "MAX_DEPTH", "MAX_LEAVES"]

#: bisections of a piece before it is undecided (a close root pair next to a turning point needs ~45)
MAX_DEPTH = 64
#: the equal parts a piece is cut into before its leaves are tried
INITIAL_PARTS = 3
#: leaves of one piece before it is undecided
MAX_LEAVES = 400


def _sign(x: arb) -> int:
    """1 / -1 when x is certainly > 0 / < 0, else 0: :func:`~rigor_gyro.core.balls.compare`'s rule (a
    finite ball, Arb's certain comparison) without its conversions (this runs ~10^5 times a search)."""
    if not x.is_finite():
        return 0
    return 1 if x > 0 else -1 if x < 0 else 0


def leaf_kind(coeffs, u: arb, v: arb, sigma: int) -> str | None:
    """'E' or 'M' for the leaf [u, v] (exact points, u < v), see the module docstring; an M leaf only
    with the given sigma (0: either, returned as 'M+' or 'M-'); None when neither is certain.
    G and G' are enclosed over X = [u, v] by Taylor forms at its midpoint m with Lagrange remainders
    (G(m) + G'(m) t + G''(m)/2 t^2 + G'''(X)/6 t^3, G'(m) + G''(m) t + G'''(X)/2 t^2, t = X - m: the
    ball form alone overestimates by the leaf's phase width, these by its cube); failing those, by the
    forms at an end e: G(e) + G'(e)(X - e) + G''(X)/2 (X - e)^2 for E (tight next to a turning point),
    sigma G'(u) > 0 with sigma G'' > 0 on X, or sigma G'(v) > 0 with sigma G'' < 0 on X, for M."""
    X = interval(u, v)
    c = coeffs(X, 4)
    if _sign(c[0]) != 0:
        return "E"
    m = arb(X.mid())
    cm = coeffs(m, 3)
    # t = X - m covers [u - m, v - m] whatever the rounding of X's midpoint (m need not be (u + v)/2)
    h = arb(max(abs(u - m).upper(), abs(v - m).upper()))
    t = interval(-h, h)
    t2 = interval(arb(0), (h * h).upper())
    d1 = cm[1] + 2 * cm[2] * t + 3 * c[3] * t2
    for s in ((sigma,) if sigma else (1, -1)):
        if _sign(d1) == s or _sign(c[1]) == s:
            return "M" if sigma else ("M+" if s > 0 else "M-")
    if _sign(cm[0] + cm[1] * t + cm[2] * t2 + c[3] * t * t2) != 0:
        return "E"
    a, b = coeffs(u, 2), coeffs(v, 2)
    d2 = _sign(c[2])
    for s in ((sigma,) if sigma else (1, -1)):
        end = a if d2 == s else b
        if d2 != 0 and _sign(end[1]) == s:
            return "M" if sigma else ("M+" if s > 0 else "M-")
    w = v - u
    w2 = interval(arb(0), (w * w).upper())
    for e, te in ((a, interval(arb(0), w.upper())), (b, interval(-w.upper(), arb(0)))):
        if _sign(e[0] + e[1] * te + c[2] * w2) != 0:
            return "E"
    return None


def _sliver(coeffs, u: arb, v: arb, e: arb, direction: int) -> arb:
    """Where to cut the leaf [u, v] touching the piece's end e (a proposal; any cut is sound): at
    distance sqrt(|G(e)| / |G''(e)|) / 2 from e (about half way to where G's quadratic model at a
    turning point e reaches 0, so the cut-off leaf is E and the rest starts where G' is signed), when
    that lies inside; else 1/16 of the leaf."""
    w = v - u
    try:
        c = coeffs(e, 3)
        d = math.sqrt(abs(float(c[0].mid())) / abs(2 * float(c[2].mid()))) / 2
        x = arb((e + direction * arb(d)).mid())
        if d > 0 and certainly_lt(u, x) and certainly_lt(x, v):
            return x
    except (ValueError, OverflowError, ZeroDivisionError):
        pass
    return arb((e + direction * w / 16).mid())


def phase_count(coeffs, lo: arb, hi: arb, claim: int, *, max_depth: int = MAX_DEPTH,
                max_leaves: int = MAX_LEAVES) -> tuple[bool, int]:
    """(decided, leaves): decided is True when [lo, hi] certainly holds exactly ``claim`` roots
    (claim 0 or 1), by the leaves of the module docstring. ``lo``, ``hi`` exact points."""
    if claim not in (0, 1) or not certainly_lt(lo, hi):
        return False, 0
    s_lo, s_hi = _sign(coeffs(lo, 1)[0]), _sign(coeffs(hi, 1)[0])
    if s_lo == 0 or s_hi == 0 or (s_lo != s_hi) != (claim == 1):
        return False, 0
    sigma = s_hi if claim == 1 else 0           # claim 0: fixed by the first M leaf
    # a half-period is never one leaf: start from INITIAL_PARTS equal parts (any tiling is sound)
    cuts = [lo] + [arb((lo + (hi - lo) * k / INITIAL_PARTS).mid()) for k in range(1, INITIAL_PARTS)] + [hi]
    if not all(certainly_lt(cuts[k], cuts[k + 1]) for k in range(INITIAL_PARTS)):
        cuts = [lo, hi]
    stack = [(cuts[k], cuts[k + 1], 0) for k in range(len(cuts) - 2, -1, -1)]
    leaves = 0
    while stack:
        u, v, depth = stack.pop()
        k = leaf_kind(coeffs, u, v, sigma)
        if k is not None:
            leaves += 1
            if k.startswith("M") and not sigma:
                sigma = 1 if k == "M+" else -1
            if leaves > max_leaves:
                return False, leaves
            continue
        # next to a piece's end (a turning point) the undecided part is a sliver: cut it off at 1/16
        # (midpoint bisection would take 4 levels for one); any cut is sound, this only chooses leaves
        # or, better, where G's quadratic model at that end has come halfway to 0 (a float proposal)
        m = _sliver(coeffs, u, v, u, 1) if u is lo and v is not hi else \
            _sliver(coeffs, u, v, v, -1) if v is hi and u is not lo else arb(((u + v) / 2).mid())
        if depth >= max_depth or not (certainly_lt(u, m) and certainly_lt(m, v)):
            return False, leaves
        stack.append((m, v, depth + 1))
        stack.append((u, m, depth + 1))
    return True, leaves


def root_bracket(coeffs, lo: arb, hi: arb, s_lo: int, rel_bits: int | None = None) -> tuple[arb, arb] | None:
    """(a, b), lo <= a < b <= hi exact points with G(a) of sign s_lo and G(b) of sign -s_lo certified
    (or a = lo, b = hi: the caller's certified end signs), b - a <= |a| 2^-rel_bits (default the
    precision less 16 bits: the classification needs a narrow theta) when reachable: a sign change,
    so a root in [a, b]. Newton's method on point values
    proposes (nothing assumed of it); sign bisection when it does not land. None if a sign is
    uncertain before the width is reached and no bracket narrower than [lo, hi] was certified."""
    prec = current_precision()
    rel = arb(2) ** (-(rel_bits if rel_bits is not None else prec - 16))
    a, b = lo, hi
    x = arb(((a + b) / 2).mid())
    try:        # start: the root of A + R cos on a half-period from turning point to turning point
        g1, g2 = float(coeffs(lo, 1)[0].mid()), float(coeffs(hi, 1)[0].mid())
        frac = math.acos(max(-1.0, min(1.0, -(g1 + g2) / (g1 - g2)))) / math.pi
        xs = arb((lo + (hi - lo) * arb(frac)).mid())
        if not (0.01 < frac < 0.99):    # next to a near-tangent end e: the root of G's quadratic model at e
            e, dirn = (lo, 1) if frac <= 0.01 else (hi, -1)
            ce = coeffs(e, 3)
            xs = arb((e + dirn * arb(math.sqrt(abs(float(ce[0].mid())) / abs(float(ce[2].mid()))))).mid())
        if certainly_lt(a, xs) and certainly_lt(xs, b):
            x = xs
    except (ValueError, OverflowError, ZeroDivisionError):
        pass
    for _ in range(40):
        c = coeffs(x, 2)
        if not (c[0].is_finite() and c[1].is_finite()) or _sign(c[1]) == 0 or c[0].contains(0):
            break               # (G(x) is noise: x is as near the root as this precision tells)
        xn = arb((x - c[0].mid() / c[1].mid()).mid())
        if not (certainly_lt(a, xn) and certainly_lt(xn, b)):      # stay inside: halve towards that end
            xn = arb(((x + (a if certainly_lt(xn, x) else b)) / 2).mid())
        done = certainly_lt(abs(xn - x), abs(x) * rel / 16)
        x = xn
        if done:
            break
    d = abs(x) * rel / 4
    c = coeffs(x, 2)
    if c[0].is_finite() and _sign(c[1]) != 0:       # start past G's noise at x: 4 rad(G) / |G'|
        d = arb(max(d, 4 * arb(c[0].rad()) / abs(c[1])).mid())
    for _ in range(16):         # certify a bracket around the proposal, widened past G's noise
        p, q = arb((x - d).mid()), arb((x + d).mid())
        if certainly_lt(a, p) and certainly_lt(q, b) and _sign(coeffs(p, 1)[0]) == s_lo \
                and _sign(coeffs(q, 1)[0]) == -s_lo:
            return p, q
        d = d * 8
    for _ in range(4 * prec):                       # sign bisection
        if certainly_lt(b - a, abs(a) * rel):
            return a, b
        m = arb(((a + b) / 2).mid())
        sm = _sign(coeffs(m, 1)[0])
        if sm == 0 or not (certainly_lt(a, m) and certainly_lt(m, b)):
            return (a, b) if (a, b) != (lo, hi) else None
        a, b = (m, b) if sm == s_lo else (a, m)
    return a, b
