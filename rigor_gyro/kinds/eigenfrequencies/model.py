"""The mathematics of Rudenko (1976) shared by the claims and the paper audit: the characteristic
quartic (1)-(2), the nu quadratics (4), and the paper's estimates (5), (7)-(10), (12)-(13) in balls.

Model. With lambda = i sqrt(omega) the characteristic equation (1), read as

    lambda^2 P1(lambda^2) + Omega^2 P2(lambda^2) = 0,
    P1(l) = [l (b-1) + b] [l^2 (a-b)(b-1) + l (eps (a-1) + b (a-b)) + eps a],
    P2(l) = [l (b-1) + 1] [l^2 (a-b)(b-1) + l (eps (a-1) + a - b) + eps],

is the quartic Q(omega) = -omega P1(-omega) + Omega^2 P2(-omega) = 0 with exact rational coefficients,
i.e. the paper's form (2) Omega^2 = F(omega) = omega (omega-nu2)(omega-nu5)(omega-nu6) /
((omega-nu1)(omega-nu3)(omega-nu4)), with nu3 = 1/(b-1), nu5 = b/(b-1), nu1 < nu4 and nu2 < nu6 the
roots of the two quadratic factors (the paper's (4)).

Each bracket and approximation is written twice where the printed formula is a misprint: the
printed reading (evaluated for the audit only) and the reading the derivation intends (used by the
claims). The readings were recovered from the derivation (replace factors of F by extreme values
from (5), solve the quadratic) and checked against the paper's Hz numbers; see ``BRACKETS`` notes.

Guarantee: the polynomials are exact (``fmpq_poly``); every other function returns Arb balls
containing the exact value of the formula at the given ball parameters (no floats), or raises
:class:`NotReal` when a square root's argument is certainly negative.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, NamedTuple

from flint import arb, ctx, fmpq, fmpq_poly

from ...core.balls import certainly_lt, decimal_bounds, working_precision
from ...core.polyroots import refine_root

__all__ = ["characteristic_quartic", "quartic_value", "bracket_slack", "approx_rel_error", "SLACK_GUARD_BITS", "nu_quadratics", "nu_identities", "nus_exactly_equal", "r2_denominator", "NotReal", "Params", "nu_bounds", "Bracket", "BRACKETS",
           "bracket", "approximation", "APPROX_TEXT"]


# ----------------------------------------------------------------------------- exact polynomials

def characteristic_quartic(a: fmpq, b: fmpq, eps: fmpq, W: fmpq, factor: str = "Omega2") -> fmpq_poly:
    """Q(omega) = -omega P1(-omega) + c P2(-omega), exactly, with c = Omega2 (the reading used) or
    c = -omega (factor='lambda2', the equation as printed: lambda^2 in front of the second product)."""
    l = fmpq_poly([0, -1])  # lambda^2 = -omega
    p1 = (l * (b - 1) + b) * (l * l * ((a - b) * (b - 1)) + l * (eps * (a - 1) + b * (a - b)) + eps * a)
    p2 = (l * (b - 1) + 1) * (l * l * ((a - b) * (b - 1)) + l * (eps * (a - 1) + a - b) + eps)
    c = fmpq_poly([W]) if factor == "Omega2" else l
    return l * p1 + c * p2


def nu_quadratics(a: fmpq, b: fmpq, eps: fmpq) -> tuple[fmpq_poly, fmpq_poly]:
    """The paper's (4): roots nu1 < nu4 of the first, nu2 < nu6 of the second (in omega)."""
    c2 = (a - b) * (b - 1)
    q14 = fmpq_poly([eps, -(eps * (a - 1) + a - b), c2])
    q26 = fmpq_poly([eps * a, -(eps * (a - 1) + b * (a - b)), c2])
    return q14, q26


def nu_identities(a: fmpq, b: fmpq, eps: fmpq) -> dict[int, tuple]:
    """Exact descriptions of nu1 .. nu6: ("rational", r) for nu3 = 1/(b-1) and nu5 = b/(b-1),
    ("root", q, i) for the i-th smallest root (i = 0, 1) of the quadratic q of (4)."""
    q14, q26 = nu_quadratics(a, b, eps)
    return {1: ("root", q14, 0), 2: ("root", q26, 0), 3: ("rational", 1 / (b - 1)), 4: ("root", q14, 1),
            5: ("rational", b / (b - 1)), 6: ("root", q26, 1)}


def _root_index(q: fmpq_poly, r: fmpq) -> int | None:
    """0 or 1 if the rational r is the smaller or larger root of the quadratic q (with two distinct real
    roots), None if it is no root: exact (r is the smaller iff 2r < the sum of the roots, -q1/q2)."""
    if q(r) != 0:
        return None
    total = -q[1] / q[2]
    return 0 if 2 * r < total else 1


def nus_exactly_equal(u: tuple, v: tuple) -> bool:
    """Whether two nus given by :func:`nu_identities` are the same real number, decided exactly
    (rational arithmetic and polynomial gcds; no balls). Assumes each quadratic has two distinct real
    roots (the caller has isolated them)."""
    if u[0] == "rational" and v[0] == "rational":
        return u[1] == v[1]
    if u[0] == "rational" or v[0] == "rational":
        (_, r), (_, q, i) = (u, v) if u[0] == "rational" else (v, u)
        return _root_index(q, r) == i
    (_, q, i), (_, p, j) = u, v
    if q == p:
        return i == j
    g = q.gcd(p)
    if g.degree() == 2:                 # the same quadratic up to a factor: the same roots, in order
        return i == j
    if g.degree() == 1:
        r = -g[0] / g[1]
        return _root_index(q, r) == i and _root_index(p, r) == j
    return False


def r2_denominator(a: fmpq, b: fmpq, eps: fmpq) -> fmpq:
    """The denominator b/(b-1) - eps a/(b(a-b)) of R2 in (9), (10), exactly: where it is 0 the brackets
    (9) and (10) are undefined (the paper's nu5 - nu2^+ vanishes)."""
    return b / (b - 1) - eps * a / (b * (a - b))


# ----------------------------------------------------------------------------- the paper's estimates

class NotReal(ArithmeticError):
    """A formula takes the square root of a certainly negative number: it has no real value.
    ``radicand`` is the certified (negative) ball."""

    def __init__(self, message: str, radicand: arb):
        super().__init__(message)
        self.radicand = radicand


def _sqrt(x: arb, where: str) -> arb:
    """sqrt of a ball; raises NotReal when x < 0 certainly (a NaN ball would only say 'undecided')."""
    if certainly_lt(x, 0):
        lo, hi = decimal_bounds(x, 8)
        raise NotReal(f"{where}: radicand in [{lo}, {hi}] is negative", x)
    return x.sqrt()


class Params(NamedTuple):
    """Balls of the exact parameters a, b, eps, Omega^2 (W)."""

    a: arb
    b: arb
    eps: arb
    W: arb


def quartic_value(x, p: Params):
    """Q(x) = l P1(l) + Omega2 P2(l), l = -x (model (1)-(2)), with generic arithmetic (balls, Duals, jets):
    the one formula the box forms, the second-order forms and the paper audit's sensitivities share."""
    a, b, e, W = p
    l = -x
    c2 = (a - b) * (b - 1)
    p1 = (l * (b - 1) + b) * ((c2 * l + (e * (a - 1) + b * (a - b))) * l + e * a)
    p2 = (l * (b - 1) + 1) * ((c2 * l + (e * (a - 1) + a - b)) * l + e)
    return l * p1 + W * p2


def nu_bounds(p: Params) -> dict[int, tuple[arb, arb]]:
    """The bounds (5): {k: (nu_k^-, nu_k^+)} for k = 1, 2, 4, 6 (printed formulas, no misprint found)."""
    a, b, e, _ = p
    n1m, n1p = e / (a - b + e * (a - 1)), e / (a - b)
    n2m, n2p = e * a / (b * (a - b) + e * (a - 1)), e * a / (b * (a - b))
    n4m = (1 + e) / (b - 1)
    n4p = n4m + e * e * (a - 1) / ((a - b) * (a - b + e * (a - 1)))
    n6m = (b * b + e) / (b * (b - 1))
    n6p = n6m + e * e * a * (a - 1) / (b * (a - b) * ((a - b) * b + e * (a - 1)))
    return {1: (n1m, n1p), 2: (n2m, n2p), 4: (n4m, n4p), 6: (n6m, n6p)}


# ----------------------------------------------------------------------------- brackets (7)-(10)

def _lo7(p: Params) -> arb:
    a, b, e, W = p
    return e * W / ((a - b) * W + e * ((a - 1) * W + a * b))


def _hi7(p: Params, sign: int) -> arb:
    a, b, e, W = p
    lam = (b * (b - 1) + e) / (b * (b - 1))
    r = (e * a / (b * (a - b) + sign * (a - 1) * e) + W / (lam * b * b)) / 2
    q = e * W / ((a - b) * lam * b * b)
    # r - sqrt(r^2 - q) = q / (r + sqrt(r^2 - q)): the same number, without the cancellation that
    # makes a ball over a parameter box hundreds of times wider than the bound's range
    root = _sqrt(r * r - q, "(7) upper")
    return q / (r + root) if certainly_lt(0, r) else r - root


def _lo8(p: Params, sign: int) -> arb:
    """1/(b-1) + h - sqrt(h^2 + R1 c), h = (D + R1)/2, c = 1/(b-1) + sign eps a/(b(a-b)), evaluated as
    1/(b-1) - c / (h' + sqrt(h'^2 + c s)) with s = 1/R1 and h' = (D s + 1)/2: the same number (divide
    by R1 > 0), without the cancellation h - sqrt(...) and with Omega2 only in s (a ball over a box of
    parameters stays as narrow as the bound's range)."""
    a, b, e, W = p
    s = (a - b) * (b - 1) * W / (a * b * b)
    c = 1 / (b - 1) + sign * e * a / (b * (a - b))
    h = (e / (b * (b - 1)) * s + 1) / 2
    return 1 / (b - 1) - c / (h + _sqrt(h * h + c * s, "(8) lower"))


def _hi8(p: Params) -> arb:
    a, b, e, W = p
    return (e * a * (b - 1) + W * (1 + e) * (a - b)) / ((a - b) * (b - 1) * (b + W * (1 + e)))


def _r2(p: Params) -> arb:
    a, b, e, W = p
    return W * (b - 1) / b * (b / (b - 1) - e / (a - b)) / (b / (b - 1) - e * a / (b * (a - b)))


def _lo9_10(p: Params, root: int, squared: bool, c_reading: bool) -> arb:
    """nu5 + (D + R2)/2 -+ sqrt((D + R2)^2/4 + R2 c); printed c = 1 + eps/b, read c = nu5 - nu4^- =
    1 - eps/(b-1); the printed (10) lacks the square on [D + R2]."""
    a, b, e, W = p
    d, r2 = e / (b * (b - 1)), _r2(p)
    s = d + r2
    c = 1 - e / (b - 1) if c_reading else 1 + e / b
    inner = (s * s if squared else s) / 4 + r2 * c
    if squared and root < 0 and certainly_lt(0, s):
        # s/2 - sqrt(s^2/4 + r2 c) = -r2 c / (s/2 + sqrt(s^2/4 + r2 c)): cancellation-free
        return b / (b - 1) - r2 * c / (s / 2 + _sqrt(inner, "(9)/(10) lower"))
    return b / (b - 1) + s / 2 + root * _sqrt(inner, "(9)/(10) lower")


def _hi9(p: Params, eps_power: int) -> arb:
    a, b, e, W = p
    return ((1 + e) / (b - 1) + e ** eps_power * (a - 1) / ((a - b) * (a - b + e * (a - 1)))
            + (b - e) / (b + _sqrt(W * (b - 1) * b, "(9) upper")))


def _hi10(p: Params) -> arb:
    a, b, e, W = p
    r3 = (e / (b * (b - 1)) + e * e * a * (a - 1) / (b * (a - b) * ((a - b) * b + e * (a - 1))) + W) / 2
    return b / (b - 1) + r3 + _sqrt(r3 * r3 + W, "(10) upper")


@dataclass(frozen=True)
class Bracket:
    """One two-sided bracket: printed and intended readings of its lower and upper bound."""

    eq: str
    lo_printed: str
    hi_printed: str
    lo: Callable[[Params], arb]
    hi: Callable[[Params], arb]
    lo_read: Callable[[Params], arb] | None = None   # None: the printed formula is the reading
    hi_read: Callable[[Params], arb] | None = None
    lo_reading: str = ""
    hi_reading: str = ""
    reading_note: str = "as printed"


BRACKETS: dict[int, Bracket] = {
    1: Bracket("(7)",
               "eps W / ((a-b) W + eps((a-1) W + a b))",
               "R - sqrt(R^2 - eps W/((a-b) Lambda b^2)), R = [eps a/(b(a-b) - (a-1) eps) + W/(Lambda b^2)]/2, "
               "Lambda = (b(b-1)+eps)/(b(b-1))",
               _lo7, lambda p: _hi7(p, -1), None, lambda p: _hi7(p, +1), "",
               "R = [eps a/(b(a-b) + (a-1) eps) + W/(Lambda b^2)]/2, i.e. the first term is nu2^- of (5)",
               "upper: '+' in R (nu2^-), the sign printed '-' is a misprint"),
    2: Bracket("(8)",
               "1/(b-1) + (D+R1)/2 - sqrt(((D+R1)/2)^2 + R1 (1/(b-1) + eps a/(b(a-b)))), D = eps/(b(b-1)), "
               "R1 = a b^2/((a-b)(b-1) W)",
               "(eps a (b-1) + W (1+eps)(a-b)) / ((a-b)(b-1)(b + W(1+eps)))",
               lambda p: _lo8(p, +1), _hi8, lambda p: _lo8(p, -1), None,
               "... + R1 (1/(b-1) - eps a/(b(a-b))) = R1 (nu3 - nu2^+)", "",
               "lower: '-' before eps a/(b(a-b)) (the printed '+' makes the bound negative); the paper's 119.5 Hz "
               "is another reading of it, its linear form (see the audit), not the bound proved here"),
    3: Bracket("(9)",
               "b/(b-1) + (D+R2)/2 - sqrt((D+R2)^2/4 + R2 (1 + eps/b)), R2 = W (b-1)/b (b/(b-1) - eps/(a-b)) "
               "(b/(b-1) - eps a/(b(a-b)))^-1",
               "(1+eps)/(b-1) + eps (a-1)/((a-b)(a-b+eps(a-1))) + (b-eps)/(b + sqrt(W (b-1) b))",
               lambda p: _lo9_10(p, -1, True, False), lambda p: _hi9(p, 1),
               lambda p: _lo9_10(p, -1, True, True), lambda p: _hi9(p, 2),
               "... + R2 (1 - eps/(b-1)) = R2 (nu5 - nu4^-)",
               "(1+eps)/(b-1) + eps^2 (a-1)/(...) + ...: the first two terms are nu4^+ of (5)",
               "lower: c = nu5 - nu4^- = 1 - eps/(b-1) for the printed 1 + eps/b; upper: eps^2 as in (5); the "
               "paper's 546 Hz is another reading of the upper bound (see the audit), not the bound proved here"),
    4: Bracket("(10)",
               "b/(b-1) + (D+R2)/2 + sqrt((D+R2)/4 + R2 (1 + eps/b))",
               "b/(b-1) + R3 + sqrt(R3^2 + W), R3 = [eps/(b(b-1)) + eps^2 a(a-1)/(b(a-b)((a-b)b + eps(a-1))) + W]/2",
               lambda p: _lo9_10(p, +1, False, False), _hi10,
               lambda p: _lo9_10(p, +1, True, True), None,
               "b/(b-1) + (D+R2)/2 + sqrt((D+R2)^2/4 + R2 (1 - eps/(b-1))): the other root of (9)'s quadratic",
               "", "lower: square restored on [D+R2] and c = nu5 - nu4^- as in (9)"),
}


#: each printed bound and approximation as formula text (Python syntax over a, b, eps, W = Omega2), with
#: its named sub-formulas, for the single-edit search of the audit (:mod:`rigor_gyro.core.formula_edits`);
#: as printed, so that an edit is a misprint of the print (tests: each text evaluates to its function)
EDIT_FORMULAS: dict[tuple[str, int], tuple[str, dict[str, str]]] = {
    ("lower", 1): ("eps*W/((a-b)*W + eps*((a-1)*W + a*b))", {}),
    ("upper", 1): ("R - sqrt(R**2 - eps*W/((a-b)*L*b**2))",
                   {"L": "(b*(b-1) + eps)/(b*(b-1))", "R": "(eps*a/(b*(a-b) - (a-1)*eps) + W/(L*b**2))/2"}),
    ("lower", 2): ("1/(b-1) + (D+R1)/2 - sqrt(((D+R1)/2)**2 + R1*(1/(b-1) + eps*a/(b*(a-b))))",
                   {"D": "eps/(b*(b-1))", "R1": "a*b**2/((a-b)*(b-1)*W)"}),
    ("upper", 2): ("(eps*a*(b-1) + W*(1+eps)*(a-b))/((a-b)*(b-1)*(b + W*(1+eps)))", {}),
    ("lower", 3): ("b/(b-1) + (D+R2)/2 - sqrt((D+R2)**2/4 + R2*(1 + eps/b))",
                   {"D": "eps/(b*(b-1))", "R2": "W*(b-1)/b*(b/(b-1) - eps/(a-b))/(b/(b-1) - eps*a/(b*(a-b)))"}),
    ("upper", 3): ("(1+eps)/(b-1) + eps*(a-1)/((a-b)*(a-b+eps*(a-1))) + (b-eps)/(b + sqrt(W*(b-1)*b))", {}),
    ("lower", 4): ("b/(b-1) + (D+R2)/2 + sqrt((D+R2)/4 + R2*(1 + eps/b))",
                   {"D": "eps/(b*(b-1))", "R2": "W*(b-1)/b*(b/(b-1) - eps/(a-b))/(b/(b-1) - eps*a/(b*(a-b)))"}),
    ("upper", 4): ("b/(b-1) + R3 + sqrt(R3**2 + W)",
                   {"R3": "(eps/(b*(b-1)) + eps**2*a*(a-1)/(b*(a-b)*((a-b)*b + eps*(a-1))) + W)/2"}),
    ("approx", 1): ("eps*W/(W*(a-b) + eps*a*b)", {}),
    ("approx", 2): ("(eps*(b-1)*a + W*(a-b))/((a-b)*(b-1)*(b+W))", {}),
    ("approx", 3): ("b/(b-1) + R3 - sqrt(R3**2 + (b-1)*W*(b-eps)/b**2)", {"R3": "(eps/(b*(b-1)) + (b-1)*W/b)/2"}),
    ("approx", 4): ("b/(b-1) + R3 + sqrt(R3**2 + (b-1)*W*(b-eps)/b**2)", {"R3": "(eps/(b*(b-1)) + (b-1)*W/b)/2"}),
}


def bracket(j: int, p: Params, reading: str = "intended") -> tuple[arb, arb]:
    """(lower, upper) bound of bracket j: reading 'intended' (used by claims) or 'printed'."""
    br = BRACKETS[j]
    if reading == "printed":
        return br.lo(p), br.hi(p)
    return (br.lo_read or br.lo)(p), (br.hi_read or br.hi)(p)


#: guard bits of a bracket's slack: omega_j and the nearer bound nearly cancel (Rudenko's example: omega_3 -
#: lower_3 is 2^-11.5 of omega_3, so the difference of two balls of relative width 2^-p is 2^(11.5-p) wide)
SLACK_GUARD_BITS = 32


def bracket_slack(j: int, exact: tuple, omega: arb) -> arb:
    """min(omega_j - lower_j, upper_j - omega_j) at the exact parameters ``exact`` = (a, b, eps, Omega2)
    (fmpq), computed with :data:`SLACK_GUARD_BITS` more bits than the working precision: omega_j refined by
    interval Newton on the exact quartic from the ball ``omega`` (which must hold exactly that root), the
    bracket recomputed from the exact parameters. Guarantee: an enclosure of the slack that loses no more
    of the working precision to the cancellation than the guard bits absorb. Raises NotReal as
    :func:`bracket` does."""
    with working_precision(ctx.prec + SLACK_GUARD_BITS):
        w, P = _guarded(exact, omega)
        lo, hi = bracket(j, P, reading="intended")
        s = (w - lo).min(hi - w)
    return +s                   # rounded to the working precision: 2^-p relative, none of it lost


def approx_rel_error(j: int, exact: tuple, omega: arb) -> arb:
    """(approx_j - omega_j) / omega_j for the approximation (12)/(13) at the exact parameters, with the guard
    bits of :func:`bracket_slack` (the approximation agrees with omega_j to 2^-8 .. 2^-11: the same
    cancellation). Raises NotReal as :func:`approximation` does."""
    with working_precision(ctx.prec + SLACK_GUARD_BITS):
        w, P = _guarded(exact, omega)
        r = (approximation(j, P) - w) / w
    return +r


def _guarded(exact: tuple, omega: arb) -> tuple[arb, Params]:
    """omega_j refined on the exact quartic from the ball ``omega``, and the parameters' balls, both at the
    (raised) working precision: the inputs of :func:`bracket_slack` and :func:`approx_rel_error`."""
    return refine_root(characteristic_quartic(*exact), omega), Params(*(arb(x) for x in exact))


# ----------------------------------------------------------------------------- approximations

def approximation(j: int, p: Params) -> arb:
    """Approximation of omega_j: (12) for j = 1 (printed under the label omega_4), (13) for 2, 3, 4."""
    a, b, e, W = p
    if j == 1:
        return e * W / (W * (a - b) + e * a * b)
    if j == 2:
        return (e * (b - 1) * a + W * (a - b)) / ((a - b) * (b - 1) * (b + W))
    r3 = (e / (b * (b - 1)) + (b - 1) * W / b) / 2
    root = _sqrt(r3 * r3 + (b - 1) * W * (b - e) / (b * b), f"(13) omega_{j}")
    return b / (b - 1) + r3 + (root if j == 4 else -root)


APPROX_TEXT = {
    1: "(12) eps W [W (a-b) + eps a b]^-1 (printed as 'omega_4 ~'; it is the omega_1 formula)",
    2: "(13) (eps (b-1) a + W (a-b)) / ((a-b)(b-1)(b+W))",
    3: "(13) b/(b-1) + R3 - sqrt(R3^2 + (b-1) W (b-eps)/b^2), R3 = (eps/(b(b-1)) + (b-1) W/b)/2",
    4: "(13) b/(b-1) + R3 + sqrt(R3^2 + (b-1) W (b-eps)/b^2)",
}
