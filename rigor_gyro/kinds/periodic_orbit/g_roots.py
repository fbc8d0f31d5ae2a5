"""The roots of g(theta) on (0, T]: every root enclosed, each alone and simple in its piece, by Taylor
enclosures of g (point coefficients and a Lagrange remainder, order TAYLOR_ORDER), interval Newton, monotone
sides, critical splits and, for fast nutation, the envelope test and a phase walk. Shared by the paper's relay
(:mod:`.claims`) and a user's relay plant (:mod:`.plant_claims`).

Guarantee: a piece reported ``root`` holds exactly one simple root (interval Newton or a certified sign change
with a monotone g), a piece reported root-free has none (an enclosure of g certainly away from 0). Precision:
the working one. Fails when: a piece that neither test decides after ``max_depth`` bisections, or past
``max_pieces``, is returned ``undecided`` (never called root-free); the claims then stay inconclusive."""

from __future__ import annotations

import math
from fractions import Fraction

from flint import arb, arb_series

from ...core.balls import (ball_key, series_coefficients, certainly_gt, certainly_le, certainly_lt, certainly_negative,
                           certainly_positive, current_precision, interval)
from ...core.roots import Isolation, RootPiece, RootStatus, enclose_f_df, merge_shared_roots, newton_root
from .nutation_form import fast_form
from .phase_walk import phase_walk
from .flow import Spectrum, envelope_margin, g_coeffs, pole_free_coeffs, taylor_enclosure

__all__ = ["TAYLOR_ORDER", "ENVELOPE_REASON", "isolate_pieces", "phase_isolate", "g_series_function", "isolation_coeffs",
           "envelope_test", "dyadic_up"]

#: Taylor order of the enclosures over pieces (point coefficients + Lagrange remainder)
TAYLOR_ORDER = 8
MAX_PIECES = 200000
#: interval Newton steps on a bracketed root of a fast-nutation search (:func:`_monotone_side`)
NUTATION_NEWTON_STEPS = 12
#: omega times the width above which a fast-nutation piece is bisected without trying Newton (the widest
#: piece a Taylor model of order 8 decided on the H = 1e6 scenes spans 2.68 rad)
NUTATION_WIDE_PHASE = 6


def dyadic_up(x: Fraction, bits: int = 24) -> Fraction:
    """The smallest dyadic with ``bits`` significant bits that is >= x > 0."""
    if x <= 0:
        return Fraction(0)
    e = x.numerator.bit_length() - x.denominator.bit_length() - bits
    scale = Fraction(2) ** e
    return math.ceil(x / scale) * scale


def g_series_function(sp: Spectrum, coeffs=None):
    """g (or, given ``coeffs``, the function with those Taylor coefficients) as the series function
    :func:`rigor_gyro.core.roots.isolate_roots` expects: given arb_series([X, 1]) it returns [g(X), g'(X)]
    (Taylor-model enclosures over the ball X; the chain-rule factor is exactly 1)."""
    coeffs = coeffs or (lambda ctr, n: g_coeffs(sp, ctr, n))

    def f(s: arb_series) -> arb_series:
        c = series_coefficients(s, 2)
        if len(c) < 2 or not (c[1] - 1).is_zero():
            raise ValueError("expects the identity series [x, 1]")
        g, dg = taylor_enclosure(coeffs, c[0], TAYLOR_ORDER, (0, 1))
        return arb_series([g, dg], prec=2)
    return f


#: entries of a spectrum's memo of G's Taylor coefficients before it is cleared
COEFF_MEMO_LIMIT = 100_000


def isolation_coeffs(sp: Spectrum):
    """The Taylor coefficients of the function whose roots the search isolates, and its name in the
    witness: G = g K (:func:`~.flow.pole_free_coeffs`: same roots as g, no poles next to the real axis).

    Memoised per spectrum, keyed by the precision, the centre ball's exact midpoint and radius and the
    length: Arb is deterministic given those, so a memoised list holds the very balls a new call would
    return (certificates are unchanged; the root search asks for the same piece's coefficients again
    and again: about a third of the calls on the H = 1e4 stress scene). Non-finite or complex centres
    are computed, never memoised.

    For a fast nutation (:func:`.nutation_form.fast_form`) pole_free_coeffs gives G's nutation form,
    and the returned function carries ``nutation`` and ``omega``: the search then chooses its pieces
    and starts its Newton iterations by the nutation (:func:`_newton_bracket`, :func:`isolate_pieces`)."""
    form = fast_form(sp)
    compute = lambda ctr, n: pole_free_coeffs(sp, ctr, n)     # noqa: E731 (the nutation form when fast)
    memo = sp.__dict__.setdefault("_pole_free_memo", {})

    def coeffs(ctr, n):
        if type(ctr) is not arb or not ctr.is_finite():
            return pole_free_coeffs(sp, ctr, n)
        key = (current_precision(), *ball_key(ctr), n)
        hit = memo.get(key)
        if hit is None:
            if len(memo) >= COEFF_MEMO_LIMIT:
                memo.clear()
            hit = memo[key] = tuple(compute(ctr, n))
        return list(hit)
    coeffs.nutation = form is not None      # _newton_bracket starts where Newton cannot overshoot
    if form is not None:
        coeffs.omega = abs(form.lam.imag)   # isolate_pieces bisects pieces spanning much nutation phase at once
    return coeffs, "pole_free"


def _g_derivatives(coeffs, X: arb, derivs) -> list[arb]:
    return taylor_enclosure(coeffs, X, TAYLOR_ORDER, derivs)


def _dg_series_function(coeffs):
    """g' as a series function (for interval Newton on g' = 0: [g'(X), g''(X)])."""
    def f(s: arb_series) -> arb_series:
        c = series_coefficients(s, 2)
        if len(c) < 2 or not (c[1] - 1).is_zero():
            raise ValueError("expects the identity series [x, 1]")
        d1, d2 = _g_derivatives(coeffs, c[0], (1, 2))
        return arb_series([d1, d2], prec=2)
    return f


def _sign(x: arb) -> int:
    return 1 if certainly_positive(x) else -1 if certainly_negative(x) else 0


def _monotone(a: arb, b: arb, why: str) -> RootPiece:
    """A piece on which g is strictly monotone with no sign change: root-free (checker: kind empty, by
    monotone: g'' of one sign on it, g' of one strict sign at both ends, g of one strict sign at both)."""
    return RootPiece(a, b, RootStatus.EMPTY, reason="monotone: " + why)


def _monotone_side(f, coeffs, a: arb, b: arb) -> list[RootPiece] | None:
    """[a, b] with g strictly monotone on it (g'' one sign, g'(a), g'(b) one strict sign): no root when
    g(a), g(b) have one strict sign; else exactly one, bracketed by sign bisection until interval Newton
    proves it: [a, lo] monotone, [lo, hi] unique, [hi, b] monotone. None if a sign is not certain."""
    ga, gb = _sign(coeffs(a, 1)[0]), _sign(coeffs(b, 1)[0])
    if ga == 0 or gb == 0:
        return None
    if ga == gb:
        return [_monotone(a, b, "g' and g of one sign")]
    lo, hi = a, b
    near = _newton_bracket(coeffs, a, b, ga)
    if near is not None:                    # usually one interval Newton step away from a unique root
        lo, hi = near
    # fast nutation: a unique root is refined a few steps only (Newton contracts slowly next to a turning
    # point; classification needs no more, and a genuine orbit's theta* is refined at guard bits later)
    nutation = getattr(coeffs, "nutation", False)
    steps = NUTATION_NEWTON_STEPS if nutation else 200
    tol = arb(2) ** (-(current_precision() // 2)) if nutation else None
    for _ in range(200):
        piece = newton_root(f, lo, hi, max_iter=steps, rel_tol=tol)
        if piece.status is RootStatus.UNIQUE:
            out = [_monotone(a, lo, "before the root")] if certainly_lt(a, lo) else []
            out.append(piece)
            if certainly_lt(hi, b):
                out.append(_monotone(hi, b, "after the root"))
            return out
        mid = ((lo + hi) / 2).mid()
        gm = _sign(coeffs(mid, 1)[0])
        if gm == 0 or not (certainly_lt(lo, mid) and certainly_lt(mid, hi)):
            return None
        lo, hi = (lo, mid) if gm != ga else (mid, hi)
    return None


def _newton_bracket(coeffs, a: arb, b: arb, ga: int) -> tuple[arb, arb] | None:
    """A narrow bracket [lo, hi] inside [a, b] around the one root of a monotone g with sign ga at a
    and -ga at b: Newton's method on point values proposes the root (a search: nothing is assumed of
    it), then the signs at lo and hi are certified (g(lo) has sign ga, g(hi) sign -ga), so the root
    is in [lo, hi]. None when no certified bracket is found (the caller bisects)."""
    x = ((a + b) / 2).mid()
    nutation = getattr(coeffs, "nutation", False)
    if nutation:
        x = _quadratic_start(coeffs, a, b, x)
    step = b - a
    prec = current_precision()
    for _ in range(64):
        c = coeffs(x, 3 if nutation else 2)
        if not (c[0].is_finite() and c[1].is_finite()) or certainly_le(abs(c[1]), 0):
            return None
        step = (c[0].mid() / c[1].mid()).mid()
        if nutation and c[0].contains(0):   # g's midpoint is noise below its radius: stop chasing it
            step = ((abs(c[0].mid()) + c[0].rad()) / abs(c[1].mid())).mid()
            break
        if nutation:            # the root of the local quadratic (third order; Newton's step otherwise)
            t = _quadratic_root(c[0].mid(), c[1].mid(), c[2].mid())
            step = (-t).mid() if t is not None else step
        xn = (x - step).mid()
        if not (certainly_lt(a, xn) and certainly_lt(xn, b)):      # stay inside: halve towards that end
            end = a if certainly_lt(xn, (a + b) / 2) else b
            xn = ((x + end) / 2).mid()
        x = xn
        if certainly_le(abs(step), abs(x) * arb(2) ** (8 - prec)):
            break
    d = abs(step) * 4 + abs(x) * arb(2) ** (-(prec // 2))
    clip = getattr(coeffs, "nutation", False)
    for _ in range(8):
        lo = (x - d).mid()
        hi = (x + d).mid()
        if clip:        # a root next to an end: that end's sign is the caller's (certified ga, -ga)
            lo_in, hi_in = certainly_lt(a, lo), certainly_lt(hi, b)
            lo, hi = (lo if lo_in else a), (hi if hi_in else b)
            if certainly_lt(lo, hi) and (not lo_in or _sign(coeffs(lo, 1)[0]) == ga) \
                    and (not hi_in or _sign(coeffs(hi, 1)[0]) == -ga):
                return arb(lo), arb(hi)
        elif certainly_lt(a, lo) and certainly_lt(hi, b) and _sign(coeffs(lo, 1)[0]) == ga \
                and _sign(coeffs(hi, 1)[0]) == -ga:
            return arb(lo), arb(hi)
        d = d * 16
    return None


def _quadratic_start(coeffs, a: arb, b: arb, x: arb) -> arb:
    """A starting point for :func:`_newton_bracket` (a proposal: it decides nothing): the root of the
    quadratic Taylor model of g at the end of [a, b] nearer a turning point (the smaller |g'|), when it
    lies inside (a, b), else ``x``. Why: next to a turning point g is quadratic and Newton from the
    midpoint only halves the distance per step (24 steps on the fast-nutation pairs); the quadratic
    model lands next to the root and Newton then converges quadratically."""
    ends = []
    for e in (a, b):
        c = [v.mid() for v in coeffs(e, 3)]
        ends.append((abs(c[1]), e, c))
    _, e, (c0, c1, c2) = min(ends, key=lambda t: float(t[0]))      # float only picks the end
    disc = c1 * c1 - 4 * c0 * c2
    if not (disc.is_finite() and certainly_le(0, disc)) or c2.is_zero():
        return x
    r = disc.sqrt().mid()
    qq = -(c1 + r) / 2 if certainly_le(0, c1) else -(c1 - r) / 2
    for t in ((qq / c2).mid(), (c0 / qq).mid() if not qq.is_zero() else None):
        if t is not None and t.is_finite():
            xn = (e + t).mid()
            if certainly_lt(a, xn) and certainly_lt(xn, b):
                return xn
    return x


def _quadratic_root(c0: arb, c1: arb, c2: arb) -> arb | None:
    """The root nearest 0 of c0 + c1 t + c2 t^2 (exact midpoints in; a proposal, decides nothing), by
    the form without cancellation -2 c0 / (c1 + sign(c1) sqrt(c1^2 - 4 c0 c2)); None if it has none."""
    disc = c1 * c1 - 4 * c0 * c2
    if not (disc.is_finite() and certainly_le(0, disc)):
        return None
    r = disc.sqrt().mid()
    den = c1 + r if certainly_le(0, c1) else c1 - r
    if den.is_zero() or not den.is_finite():
        return None
    return (-2 * c0 / den).mid()


def _widen_critical(coeffs, a: arb, b: arb, c_lo: arb, c_hi: arb, da: int, db: int) -> tuple[arb, arb]:
    """[c_lo, c_hi] widened (by 2^k times its width, k = 1, 2, ...) until g' has the signs da at its
    lower and db at its upper end, as :func:`_critical_split` needs, staying inside (a, b); unchanged
    if that happens at once or never. Why: Newton refines the critical point until its enclosure is as
    narrow as g' can resolve, so g' at the enclosure's ends is noise of no certain sign (seen at
    H = 1e7: the fast nutation's close pairs). The widened piece is still checked (g excludes 0 on
    it, g' signs at its ends) by the caller: this only chooses which piece is tried."""
    if _sign(coeffs(c_lo, 2)[1]) == da and _sign(coeffs(c_hi, 2)[1]) == db:
        return c_lo, c_hi
    w = c_hi - c_lo
    for _ in range(48):
        w = 2 * w
        lo, hi = (c_lo - w).lower(), (c_hi + w).upper()
        if not (certainly_lt(a, lo) and certainly_lt(hi, b)):
            break
        if _sign(coeffs(lo, 2)[1]) == da and _sign(coeffs(hi, 2)[1]) == db:
            return lo, hi
    return c_lo, c_hi


def _critical_split(f, coeffs, a: arb, b: arb) -> list[RootPiece] | None:
    """Decide [a, b] where g'' has one sign (g strictly convex or concave: at most one critical point,
    at most two roots), instead of bisecting towards a close pair of roots or a near-tangency:
    the critical point c (g' = 0) enclosed by interval Newton on g', the pieces beside it monotone
    (:func:`_monotone_side`), the one around it root-free by the sign of g there. None when g'' may
    vanish on [a, b] or a sign is not certain (the caller bisects)."""
    d2 = _g_derivatives(coeffs, interval(a, b), (2,))[0]
    if _sign(d2) == 0:
        return None
    da, db = _sign(coeffs(a, 2)[1]), _sign(coeffs(b, 2)[1])
    if da == 0 or db == 0:
        return None
    if da == db:
        return _monotone_side(f, coeffs, a, b)
    crit = newton_root(_dg_series_function(coeffs), a, b)
    if crit.status is not RootStatus.UNIQUE or not crit.enclosure.is_finite():
        return None
    c_lo, c_hi = crit.enclosure.lower(), crit.enclosure.upper()
    if getattr(coeffs, "nutation", False):
        c_lo, c_hi = _widen_critical(coeffs, a, b, c_lo, c_hi, da, db)
    if not (certainly_lt(a, c_lo) and certainly_lt(c_hi, b)):
        return None
    mid = RootPiece(c_lo, c_hi, RootStatus.EMPTY, reason="g excludes 0 around its critical point")
    if _sign(enclose_f_df(f, interval(c_lo, c_hi))[0]) == 0:
        return None
    if _sign(coeffs(c_lo, 2)[1]) != da or _sign(coeffs(c_hi, 2)[1]) != db:
        return None
    left, right = _monotone_side(f, coeffs, a, c_lo), _monotone_side(f, coeffs, c_hi, b)
    if left is None or right is None:
        return None
    return left + [mid] + right


#: the reason of a piece decided by :func:`envelope_test` (its witness says ``"by": "envelope"``)
ENVELOPE_REASON = "envelope: sigma G >= |s|(1-rho)^2 + 2 sigma q_r (1-rho^2) - 16 rho q_i^2/(...) > 0 over every phase"


def envelope_test(sp: Spectrum):
    """(a, b) -> whether g certainly has no root on [a, b] by the envelope bound of
    :func:`~.flow.envelope_margin` (sigma G >= M > 0 over every nutation phase), or None when that bound
    does not apply to this spectrum. It decides, in one step, a piece spanning many nutation periods
    where the slow part of G dominates its oscillation, which a Taylor model resolves only period by
    period (the relay's fast nutation: pieces grew like H)."""
    if getattr(sp, "near_zero", None) is not None or sum(m.weight == 2 for m in sp.modes) != 1:
        return None

    def root_free(a: arb, b: arb) -> bool:
        r = envelope_margin(sp, interval(a, b))
        return r is not None and certainly_positive(r[1])
    return root_free


#: where :func:`isolate_pieces` tries to split a piece of a box spectrum, as fractions of the piece (first the
#: midpoint): the first point where g has a certain sign for every member of the box is taken
SPLIT_FRACTIONS = (Fraction(1, 2), Fraction(3, 8), Fraction(5, 8), Fraction(1, 4), Fraction(3, 4), Fraction(1, 8),
                   Fraction(7, 8))


def _split_point(coeffs, a: arb, b: arb, signed: bool) -> arb:
    """Where to bisect [a, b]: its midpoint, or with ``signed`` (a box spectrum) the first point of
    :data:`SPLIT_FRACTIONS` where g certainly has one sign for every member (the midpoint if none).
    Why: over a parameter box a root of g is spread over an interval (its value for each member); a
    split inside that spread leaves both halves with a root for some members and none for others,
    undecidable at any depth, while a split where g has one sign keeps the whole spread in one piece,
    where interval Newton (its derivative enclosed over the box) proves one root for every member.
    Any split point is sound: the pieces still tile [a, b]; this only chooses which tiling."""
    mid = ((a + b) / 2).mid()
    if not signed or coeffs is None:
        return mid
    w = b - a
    for fr in SPLIT_FRACTIONS:
        x = mid if fr == Fraction(1, 2) else (a + w * fr.numerator / fr.denominator).mid()
        if not (certainly_lt(a, x) and certainly_lt(x, b)):
            continue
        if _sign(coeffs(x, 1)[0]) != 0:
            return x
    return mid


def isolate_pieces(f, lo: arb, hi: arb, *, coeffs=None, max_depth: int = 48,
             max_pieces: int = MAX_PIECES, resume: tuple | None = None, root_free=None,
             signed_split: bool = False) -> Isolation:
    """:func:`rigor_gyro.core.roots.isolate_roots` with three changes. A piece where interval Newton fails
    and the second derivative has one sign is decided at once by :func:`_critical_split` (given the
    Taylor ``coeffs`` of f) instead of being bisected towards a close pair of roots. A fail-fast rule:
    when a piece is still undecided at the depth limit or at a width the precision cannot resolve (< 2^(-prec/2) relative), the search
    stops and the rest of the range is reported undecided (the prover then raises the precision)
    instead of bisecting every piece of a cancellation-dominated stretch to the depth limit; the
    decided pieces before the stop and the stop point are kept in ``Isolation.resume``, and a later
    call given them as ``resume`` searches only the rest. ``root_free(a, b)``, when given, is tried on
    each piece first: True means certainly no root there (:func:`envelope_test`), an empty piece. And
    with ``signed_split`` (a box spectrum) a piece is bisected where g has a certain sign
    (:func:`_split_point`), not always at its midpoint."""
    done: list[RootPiece] = list(resume[0]) if resume else []
    stack: list[tuple[arb, arb, int]] = [(resume[1], hi, 1)] if resume else [(lo, hi, 0)]
    stopped = None
    rel = arb(2) ** (-(current_precision() // 2))
    wide = getattr(coeffs, "omega", None)       # the nutation frequency of a fast-nutation search
    while stack:
        a, b, depth = stack.pop()
        if root_free is not None and root_free(a, b):
            done.append(RootPiece(a, b, RootStatus.EMPTY, reason=ENVELOPE_REASON))
            continue
        if wide is not None and certainly_gt((b - a) * wide, NUTATION_WIDE_PHASE):
            # fast nutation: a piece spanning this much phase is never decided by a Taylor model of
            # G (nor split at one turning point): bisect at once (which pieces are tried is no proof)
            piece = RootPiece(a, b, RootStatus.UNKNOWN, reason="wider than a Taylor model of G resolves")
        else:
            piece = newton_root(f, a, b)
        if piece.status is RootStatus.UNKNOWN and coeffs is not None and depth > 0 and wide is None \
                or piece.status is RootStatus.UNKNOWN and wide is not None and depth > 0 \
                and not certainly_gt((b - a) * wide, NUTATION_WIDE_PHASE):
            split = _critical_split(f, coeffs, a, b)
            if split is not None:
                done.extend(split)
                continue
        if piece.status is RootStatus.UNKNOWN:
            small = certainly_lt(b - a, b.abs_upper() * rel)
            if depth < max_depth and not small and len(done) + len(stack) < max_pieces:
                mid = _split_point(coeffs, a, b, signed_split)
                stack.append((mid, b, depth + 1))
                stack.append((a, mid, depth + 1))
                continue
            piece.reason += f" (after {depth} bisections; width at the precision limit)" if small else \
                f" (after {depth} bisections)"
            decided = sorted(done, key=lambda p: float(p.lo.mid()))
            stopped = (decided, a)          # depth-first, left first: the decided pieces tile [lo, a]
            done.append(piece)
            done.extend(RootPiece(a2, b2, RootStatus.UNKNOWN, reason="not examined: the search stopped at an "
                                  "undecided piece (raise --maxprec)") for a2, b2, _ in stack)
            break
        done.append(piece)
    done.sort(key=lambda p: float(p.lo.mid()))  # float only orders disjoint pieces
    iso = Isolation(merge_shared_roots(f, done, None))
    iso.resume = stopped
    return iso


def phase_isolate(sp: Spectrum, coeffs, lo: arb, hi: arb) -> Isolation | None:
    """A fast nutation's root search by half-periods (:func:`.phase_walk.phase_walk`: one piece per
    nutation half-period, decided by :mod:`.phase_pieces`; its uncertain stretches by :func:`isolate_pieces`),
    or None when the spectrum is not a fast nutation or a stretch stayed undecided (the caller then runs
    :func:`isolate_pieces` over the whole range, which stops fast and resumes at a higher precision)."""
    omega = getattr(coeffs, "omega", None)
    if omega is None or getattr(sp, "near_zero", None) is not None:
        return None
    f = g_series_function(sp, coeffs)
    root_free = envelope_test(sp)

    def fallback(a: arb, b: arb) -> list[RootPiece]:
        return isolate_pieces(f, a, b, coeffs=coeffs, root_free=root_free).pieces
    pieces = phase_walk(coeffs, lo, hi, float(omega.mid()), fallback, root_free, envelope_reason=ENVELOPE_REASON)
    if not pieces or any(p.status is RootStatus.UNKNOWN for p in pieces) or not certainly_le(hi, pieces[-1].hi):
        return None
    return Isolation(pieces)
