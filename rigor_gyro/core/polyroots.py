"""Roots of polynomials with exact rational coefficients: isolation, refinement, proof of reality.

Guarantee: for a squarefree p in Q[x] (checked exactly: gcd(p, p') = 1), :func:`isolate_polynomial`
returns disjoint balls, one per root: ``real`` holds every real root (each ball holds exactly one),
``nonreal`` every non-real root. A root is reported real only when Arb returns it with an imaginary
part exactly zero *and* p changes sign, in exact rational arithmetic, between the two endpoints of
its ball (an independent existence proof; a point ball, i.e. a rational root, must make p
exactly zero); a root is non-real only when its imaginary part excludes
zero. Multiplicity is decided exactly (squarefree factorisation), never from floating point.

Requires: coefficients as ``fmpq`` (parse parameters with :mod:`rigor_gyro.core.exact`).

Precision: balls at the current working precision; ``rel_tol`` reports whether each real root met
the requested relative width (use :func:`rigor_gyro.core.balls.escalate` to raise the precision until so).

Fails when: p is not squarefree (``squarefree`` False, roots reported with multiplicity and
``real``/``nonreal`` left empty), or the sign check does not separate at this precision
(``verified`` False, with the reason).

Example:
    >>> from flint import fmpq_poly, arb
    >>> from rigor_gyro.core.balls import working_precision
    >>> with working_precision(128):
    ...     r = isolate_polynomial(fmpq_poly([-2, 0, 1]), rel_tol="1e-30")
    ...     ok = (r.real[1] ** 2 - 2).contains(0) and r.real[1].overlaps(arb(2).sqrt())
    >>> len(r.real), len(r.nonreal), r.verified, r.width_met, ok
    (2, 0, True, True, True)
    >>> isolate_polynomial(fmpq_poly([-1, 4])).verified          # rational root 1/4, exact ball
    True
    >>> isolate_polynomial(fmpq_poly([1, -2, 1])).squarefree     # (x - 1)^2
    False
"""
from __future__ import annotations

from dataclasses import dataclass, field

from flint import acb, arb, fmpq, fmpq_poly

from .balls import certainly_nonzero, current_precision, exact_fraction, rel_width_at_most
from .errors import ParameterError
from .roots import RootStatus, newton_root

__all__ = ["PolynomialRoots", "isolate_polynomial", "series_function"]


@dataclass
class PolynomialRoots:
    """All roots of a rational polynomial, split into real (ascending) and non-real."""

    poly: fmpq_poly
    squarefree: bool
    real: list[arb] = field(default_factory=list)
    nonreal: list[acb] = field(default_factory=list)
    verified: bool = False
    width_met: bool = False
    reason: str = ""
    multiplicities: list[tuple[acb, int]] = field(default_factory=list)


def _fmpq(q) -> fmpq:
    return fmpq(q.numerator, q.denominator)


def arb_complex_roots(p: fmpq_poly) -> list:
    """Arb's isolation of the complex roots of p: [(acb, multiplicity)] (trusted only as far as the
    exact checks of :func:`isolate_polynomial` confirm it)."""
    return p.complex_roots()


def series_function(p: fmpq_poly):
    """p as the series function :func:`rigor_gyro.core.roots.newton_root` expects (Horner's rule on an
    arb_series: value and derivative over a ball, exact rational coefficients as balls)."""
    coeffs = [arb(c) for c in p.coeffs()]

    def f(s):
        acc = coeffs[-1] + 0 * s
        for c in reversed(coeffs[:-1]):
            acc = acc * s + c
        return acc
    return f


def _refine(p: fmpq_poly, x: arb) -> arb:
    """The root of p in the isolating ball x, refined by interval Newton to about 2^-(prec - 8) relative
    (x itself when Newton cannot improve it); the exact sign change is checked afterwards on the result."""
    if x.rad().is_zero():
        return x
    r = newton_root(series_function(p), x.lower(), x.upper(), rel_tol=arb(2) ** (8 - current_precision()))
    if r.status is RootStatus.UNIQUE and r.enclosure is not None and r.enclosure.is_finite():
        y = r.enclosure
        if x.contains(y) or y.rad() < x.rad():
            return y
    return x


def refine_root(p: fmpq_poly, x: arb) -> arb:
    """The root of the exact polynomial p in the ball x (which must hold exactly one root), refined by
    interval Newton to about 2^-(prec - 8) relative at the working precision; x itself when Newton cannot
    improve it. Guarantee: the result contains the root whenever x does (Newton's enclosure is verified)."""
    return _refine(p, x)


def isolate_polynomial(p: fmpq_poly, rel_tol: object | None = None) -> PolynomialRoots:
    """Isolate every root of ``p`` at the current precision; see the module docstring."""
    if p.degree() < 1:
        raise ParameterError(f"polynomial {p} has no roots to isolate (degree {p.degree()})")
    g = p.gcd(p.derivative())
    squarefree = g.degree() == 0
    found = arb_complex_roots(p)
    if not squarefree:
        return PolynomialRoots(p, False, multiplicities=found,
                               reason=f"not squarefree: gcd(p, p') = {g} (a multiple root)")
    real, nonreal, problems = [], [], []
    for z, mult in found:
        if mult != 1:  # impossible for a squarefree p; never trust it silently
            problems.append(f"root {z} reported with multiplicity {mult}")
        if z.imag.is_zero():
            real.append(z.real)
        elif certainly_nonzero(z.imag):
            nonreal.append(z)
        else:
            problems.append(f"root {z}: imaginary part neither exactly zero nor excluded from zero")
    real.sort(key=lambda x: float(x.mid()))  # float orders disjoint balls only
    # Arb's root finder stops at its own accuracy; refine each root to the working precision, so that
    # doubling the precision narrows every root (and whatever is decided on them) as it should
    real = [_refine(p, x) for x in real]
    # Independent existence proof of each real root: an exact sign change of p across its ball.
    for x in real:
        lo, hi = _fmpq(exact_fraction(x.lower())), _fmpq(exact_fraction(x.upper()))
        if lo == hi:  # an exact (point) ball: a rational root, verified by exact evaluation
            if p(lo) != 0:
                problems.append(f"point ball {x} is not an exact root of p")
        elif not (p(lo) * p(hi) < 0):
            problems.append(f"no exact sign change of p across {x}")
    for x, y in zip(real, real[1:]):
        if x.overlaps(y):
            problems.append(f"real root balls {x} and {y} overlap")
    if len(real) + 2 * (len(nonreal) // 2) != p.degree() or len(nonreal) % 2:
        problems.append(f"root count {len(real)} real + {len(nonreal)} non-real != degree {p.degree()}")
    width_met = rel_tol is None or all(rel_width_at_most(x, rel_tol) for x in real)
    return PolynomialRoots(p, True, real, nonreal, verified=not problems, width_met=width_met,
                           reason="; ".join(problems) or "all roots isolated, real ones by exact sign change",
                           multiplicities=found)
