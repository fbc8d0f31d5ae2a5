"""Roots of a polynomial family: one interval Newton proof for every polynomial whose coefficients lie
in given balls (the parametric version of :mod:`rigor_gyro.core.polyroots`).

Let the coefficient balls C_0 .. C_n contain the coefficients of every member p of a family (for
example the characteristic polynomial over a box of parameters). For a candidate interval Y, the
interval Newton operator N(Y) = m - P(m) / P'(Y), with P(m) enclosing {p(m)} and P'(Y) enclosing
{p'(y) : y in Y} over the whole family, contains m - p(m)/p'(xi) for each member. When P'(Y) excludes
0 and N(Y) lies in the interior of Y, every member has exactly one root in Y, and it lies in N(Y)
(the mean value theorem and Brouwer's fixed point theorem, member by member).

Guarantee: :func:`family_real_roots` returns disjoint balls, each containing exactly one root of every
member; when it returns ``n`` of them for a degree-n family whose leading coefficient ball excludes 0,
every member has n real simple roots and these are all of them, in the order given. Starting guesses
(e.g. the roots of the family's midpoint polynomial) only guide the search; they are never trusted.

Precision: the current working precision. The enclosures are as wide as the family makes them (a wide
coefficient ball gives a wide root ball); a caller that needs them narrower subdivides the family.

Fails when: some guess does not converge to a verified root ball within ``iterations`` inflations, or
two root balls overlap: returns None (undecided, never a claim that a root is absent).

Example:
    >>> from flint import arb
    >>> from rigor_gyro.core.balls import working_precision
    >>> with working_precision(64):
    ...     c = arb(2).union(arb(3))            # x^2 - c for every c in [2, 3]
    ...     r = family_real_roots([-c, arb(0), arb(1)], [arb("-1.6"), arb("1.6")])
    ...     ok = r is not None and r[1].lower() <= arb(2).sqrt() and arb(3).sqrt() <= r[1].upper()
    >>> ok
    True
"""
from __future__ import annotations

from typing import Callable

from flint import acb, acb_poly, arb, arb_poly

from .balls import certainly_lt, certainly_nonzero

__all__ = ["newton_family_root", "newton_family_root_complex", "family_real_roots", "polynomial_family"]

#: a family of functions given by enclosures: x (a ball) -> (F(x), F'(x)), each containing the value
#: and the derivative of every member at every point of x
Family = Callable[[arb], tuple[arb, arb]]


def polynomial_family(coefficients: list[arb]) -> Family:
    """The family of polynomials whose coefficients lie in the balls (constant term first). Each
    coefficient varies independently: when the coefficients depend on shared parameters, an
    evaluation that keeps the dependence (e.g. c(x) = A(x) + W B(x)) gives much tighter enclosures."""
    P = arb_poly(coefficients)
    dP = P.derivative()
    return lambda x: (P(x), dP(x))


def newton_family_root(F: Family, guess: arb, iterations: int = 40) -> arb | None:
    """A ball containing exactly one root of every member of the family F, found by epsilon-inflated
    interval Newton from ``guess``; None if no verified ball was found."""
    x = guess
    for _ in range(iterations):
        if not x.is_finite():
            return None
        c = x.mid()                                   # an exact point ball
        # the candidate Y: twice the current radius plus a relative and an absolute floor, so that a
        # converged Newton image lies strictly inside it
        width = (2 * arb(x.rad()) + abs(c) * arb(2) ** -50 + arb(2) ** -1070).upper()
        y = arb(c, width)
        d = F(y)[1]
        if not certainly_nonzero(d):
            return None
        n = c - F(c)[0] / d
        if not n.is_finite():
            return None
        if certainly_lt(y.lower(), n.lower()) and certainly_lt(n.upper(), y.upper()):
            return _contract(F, n)
        x = n
    return None


def _contract(F: Family, x: arb, steps: int = 12) -> arb:
    """Newton steps inside a verified root ball x (each member's root stays in every image, so the
    intersections stay valid) until the radius stops shrinking by a tenth."""
    for _ in range(steps):
        c = x.mid()
        n = c - F(c)[0] / F(x)[1]
        if not n.is_finite() or not n.overlaps(x):
            return x
        n = n.intersection(x)
        if n.rad() > 0.9 * x.rad():
            return n
        x = n
    return x


def family_real_roots(family: "Family | list[arb]", guesses: list[arb], iterations: int = 40,
                      leading: arb | None = None) -> list[arb] | None:
    """Verified, pairwise disjoint root balls of the family (a :data:`Family`, or a list of coefficient
    balls, constant term first), one per guess (ascending guesses), certainly increasing; None when any
    is not verified, two overlap, or they are not in the guesses' order. When len(guesses) is the degree and the leading coefficient (``leading``, or the last
    coefficient ball) excludes 0, these are all the roots of every member."""
    if isinstance(family, list):
        leading = family[-1] if family else None
        family = polynomial_family(family) if family else None
    if family is None or leading is None or not certainly_nonzero(leading):
        return None
    out = []
    for g in guesses:
        r = newton_family_root(family, g, iterations)
        if r is None:
            return None
        out.append(r)
    for i in range(len(out)):
        for j in range(i + 1, len(out)):
            if out[i].overlaps(out[j]):
                return None
    # callers number the roots by the guesses' order (ascending): a Newton run that wandered to
    # another root would swap labels, so the balls must be certainly increasing in that order
    if any(not certainly_lt(out[i], out[i + 1]) for i in range(len(out) - 1)):
        return None
    return out


def _inside(n: arb, y: arb) -> bool:
    return certainly_lt(y.lower(), n.lower()) and certainly_lt(n.upper(), y.upper())


def newton_family_root_complex(coefficients: list[arb], guess: acb, iterations: int = 40) -> acb | None:
    """A complex box containing exactly one root of every member of the real polynomial family with
    coefficient balls ``coefficients`` (constant term first), by epsilon-inflated complex interval
    Newton from ``guess`` (the image strictly inside the candidate box, the derivative's box excluding
    0: the same theorem as :func:`newton_family_root`, in the plane, member by member); None if none
    was verified."""
    P = acb_poly([acb(c) for c in coefficients])
    dP = P.derivative()
    x = guess
    for _ in range(iterations):
        if not x.is_finite():
            return None
        c = acb(x.real.mid(), x.imag.mid())
        scale = abs(c) * arb(2) ** -50 + arb(2) ** -1070
        wr = (2 * arb(x.real.rad()) + scale).upper()
        wi = (2 * arb(x.imag.rad()) + scale).upper()
        y = acb(arb(c.real, wr), arb(c.imag, wi))
        d = dP(y)
        if d.contains(0) or not d.is_finite():
            return None
        n = c - P(c) / d
        if not n.is_finite():
            return None
        if _inside(n.real, y.real) and _inside(n.imag, y.imag):
            return n
        x = n
    return None
