"""Rudenko (1976): audit rows for the derivation's text (issue 39): (11) as printed has no real solution
(a factor misplaced), "Omega_2" for Omega^2 in the example, the monotonicity of K that (3) rests on,
the eps range of the nu order (exact thresholds), and the abstract's "the estimates are not asymptotic".

Guarantee: (11)'s discriminant is an exact rational; the reading's solution is checked equal to (12) in
exact rationals at the example; K' > 0 on [0, nu1] is decided by interval bisection of the numerator
of K' (a cubic in omega with the exact nu's as balls), refuted only by a certified point where K' < 0.
Failure mode: a bisection that does not decide within its budget gives no row (an undecided row without a
value would make the prover raise the precision to its limit).
"""
from __future__ import annotations

from flint import arb, fmpq

from ...core.balls import certainly_negative, certainly_positive, decimal_bounds
from ...core.outcome import AuditRow, AuditStatus
from ...core.polyroots import isolate_polynomial
from .model import nu_quadratics

__all__ = ["text_rows"]


def _fmt(x: arb) -> str:
    lo, hi = decimal_bounds(x, 8)
    return f"[{lo}, {hi}]"


def _eq11_row(a: fmpq, b: fmpq, e: fmpq, W: fmpq) -> AuditRow | None:
    """(11) printed Omega^2 = -omega eps a b (omega - nu1+)(a - b)^-1: a quadratic in omega; read
    Omega^2 = -omega eps a b [(omega - nu1+)(a - b)]^-1, whose solution is (12). A misprint whatever the sign of
    the printed quadratic's discriminant (exact): the reading is what (12) solves; at a small Omega^2 the print
    has real solutions, but not (12). None only if the exact check of (12) failed (it cannot: (12) solves the
    reading identically), never an undecided row (exact rationals: no precision changes them)."""
    nu1p = e / (a - b)
    k = e * a * b / (a - b)
    disc = (k * nu1p) ** 2 - 4 * k * W             # k w^2 - k nu1+ w + W = 0
    w12 = e * W / (W * (a - b) + e * a * b)
    read_ok = W == -w12 * e * a * b / ((w12 - nu1p) * (a - b))
    if not read_ok:
        return None
    status = AuditStatus.MISPRINT
    return AuditRow("(11) as printed", "Omega^2 = -omega eps a b (omega - nu1+) (a - b)^-1",
                    "Omega^2 = -omega eps a b [(omega - nu1+) (a - b)]^-1", None, status,
                    f"as printed, a quadratic in omega with discriminant {float(disc):.6g} "
                    f"({'< 0: no real solution' if disc < 0 else '>= 0: real solutions, but not (12)'}; exact rational "
                    "at the example); the "
                    "reading (the factor (omega - nu1+) in the denominator) is solved exactly by (12), omega = "
                    f"eps W/(W (a-b) + eps a b): {'checked' if read_ok else 'NOT reproduced'} in exact rationals "
                    "at the example; (11)-(12) then approximate omega_1 (see the row '(12) label')")


def _omega2_row() -> AuditRow:
    return AuditRow("example: 'Omega_2 = 0.629'", "Omega_2 = 0.629", "Omega^2 = 0.629", None, AuditStatus.MISPRINT,
                    "the paper defines only Omega^2 = H^2/(K3 A3) (no Omega_2); with Omega^2 = 0.629 the brackets "
                    "(7)-(10) and (12)-(13) reproduce the printed Hz values (rows above)")


def _k_monotone_row(a: fmpq, b: fmpq, e: fmpq, max_pieces: int = 4096) -> AuditRow | None:
    """K(omega) = (omega - nu5)(omega - nu6)/((omega - nu3)(omega - nu4)) increasing on [0, nu1], the
    property (3) uses (K(0) <= K <= K(nu1)): sign of N'D - N D' by bisection."""
    q14, q26 = nu_quadratics(a, b, e)
    r14, r26 = isolate_polynomial(q14), isolate_polynomial(q26)
    if len(r14.real) != 2 or len(r26.real) != 2:
        return None         # cannot happen (row '(5) for every parameter'); never an undecided row
    nu1, nu4 = sorted(r14.real, key=lambda x: float(x.mid()))
    nu2, nu6 = sorted(r26.real, key=lambda x: float(x.mid()))
    nu3, nu5 = arb(1 / (b - 1)), arb(b / (b - 1))

    def g(w: arb) -> arb:      # (N' D - N D'), N = (w - nu5)(w - nu6), D = (w - nu3)(w - nu4)
        N, Np = (w - nu5) * (w - nu6), 2 * w - nu5 - nu6
        D, Dp = (w - nu3) * (w - nu4), 2 * w - nu3 - nu4
        return Np * D - N * Dp
    todo, pieces, bad = [(arb(0), nu1)], 0, None
    while todo and pieces < max_pieces:
        lo, hi = todo.pop()
        pieces += 1
        box = lo.union(hi)
        if certainly_positive(g(box)):
            continue
        mid = arb(((lo + hi) / 2).mid())
        if certainly_negative(g(mid)):
            bad = mid
            break
        todo += [(lo, mid), (mid, hi)]
    if bad is not None:
        st, note = AuditStatus.REFUTED, f"K' < 0 at omega = {_fmt(bad)} (certified)"
    elif todo:
        return None         # a budget, not a fact: no row (an undecided row would escalate the precision)
    else:
        st, note = AuditStatus.CONFIRMED, (f"K is increasing on [0, nu1], nu1 = {_fmt(nu1)}: N'D - ND' > 0 on "
                                           f"{pieces} pieces (certified), so K(0) <= K(omega) <= K(nu1) as (3) uses")
    return AuditRow("(3) K monotone on [0, nu1]", "K(omega) is monotone on [0, nu1]", "K' > 0 there (example)", None,
                    st, note)


def _nu_order_row(a: fmpq, b: fmpq, e: fmpq) -> AuditRow | None:
    """The eps range of the zeros' and poles' order nu1 < nu2 < nu3 < nu4 < nu5 < nu6 that the branches
    assume, with a, b of the example, in exact rationals: nu3 = 1/(b-1) and nu5 = b/(b-1) meet a root of
    (4) only where that quadratic vanishes there, which is linear in eps; the two quadratics of (4) share
    a root only at eps = 0 (their difference is linear in omega). So the order, true at the example,
    holds for 0 < eps < the least positive threshold."""
    from flint import fmpq_poly
    c2 = (a - b) * (b - 1)
    nu3, nu5 = 1 / (b - 1), b / (b - 1)

    def q14(w, eps):
        return c2 * w * w - (eps * (a - 1) + a - b) * w + eps

    def q26(w, eps):
        return c2 * w * w - (eps * (a - 1) + b * (a - b)) * w + eps * a
    found = []
    for name, q, w in (("nu3 meets a root of (4b) (nu2 = nu3)", q26, nu3), ("nu5 meets a root of (4a) (nu4 = nu5)", q14, nu5),
                       ("nu3 meets a root of (4a)", q14, nu3), ("nu5 meets a root of (4b)", q26, nu5)):
        f0, f1 = q(w, fmpq(0)), q(w, fmpq(1))          # q(w, eps) is affine in eps
        if f1 != f0:
            t = -f0 / (f1 - f0)
            if t > 0 and q(w, t) == 0:
                found.append((t, name))
    # a common root of the two quadratics: omega = eps (a-1)/c2 (their difference), then q14 = eps (1 - k (a-b)),
    # k = (a-1)/c2: zero only at eps = 0 unless a = b
    k = (a - 1) / c2
    common = fmpq_poly([0, 1 - k * (a - b)])             # eps (1 - k (a - b)) in eps
    shared_only_at_zero = common.degree() == 1
    found.sort(key=lambda tn: tn[0])
    if not found or not shared_only_at_zero or e >= found[0][0]:
        return None          # exact: no threshold below the scene's eps; more precision cannot change it

    t0, n0 = found[0]
    rest = "; ".join(f"{n} at eps = {t.p}/{t.q} = {float(t.p) / float(t.q):.6g}" for t, n in found[1:])
    return AuditRow("nu order: eps range", "nu1 < nu2 < nu3 < nu4 < nu5 < nu6 (the branches of F; the text: 'at small "
                    "eps (~0.2)')", f"holds for 0 < eps < {t0.p}/{t0.q} = {float(t0.p) / float(t0.q):.6g} (a, b of the "
                    "example)", None, AuditStatus.CONFIRMED,
                    f"exact: the order can change only where {n0} (eps = {t0.p}/{t0.q}, the least positive threshold)"
                    + (f"; then {rest}" if rest else "") + "; the quadratics (4) share a root only at eps = 0; the "
                    "order holds at the example's eps (claims), so on the whole range")


def _abstract_row(general: AuditRow | None) -> AuditRow | None:
    if general is None:
        return None
    return AuditRow("abstract: 'the estimates are not asymptotic'",
                    "upper and lower estimates for each frequency, and these estimates are not asymptotic",
                    "the brackets (7)-(10) bound the roots for every parameter", general.value,
                    general.status, f"the same counterexample as the row '{general.id}': {general.note}")


def text_rows(a: fmpq, b: fmpq, e: fmpq, W: fmpq, general: AuditRow | None) -> list[AuditRow]:
    rows = [r for r in (_eq11_row(a, b, e, W), _omega2_row(), _k_monotone_row(a, b, e), _nu_order_row(a, b, e))
            if r is not None]
    ab = _abstract_row(general)
    return rows + ([ab] if ab is not None else [])
