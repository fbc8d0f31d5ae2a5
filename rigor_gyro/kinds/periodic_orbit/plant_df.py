"""The describing-function (harmonic balance) estimate of a relay plant's oscillation, enclosed in Arb.

The estimate, not a proof of an orbit: the relay u = S sign(y) (h = 0) replaced by its first harmonic gain
N(A) = 4 S / (pi A) for y = A sin(w t), the loop y = G(s) u with G(s) = c (s I - M)^-1 e = N_c(s) / p(s)
balances when G(i w) N(A) = 1, i.e. Im G(i w) = 0 and A = 4 S Re G(i w) / pi > 0. The estimate's period is
2 pi / w. This module encloses every such (w, A) exactly as the estimate defines it: the w are the positive
real roots of the exact polynomial Im(N_c(i w) conj p(i w)) (squarefree part, real roots certified by
:func:`rigor_gyro.core.polyroots.isolate_polynomial`), so the difference between the estimate and the
certified orbit (claims) is itself enclosed.

Guarantee: each returned triple of balls contains the estimate's w, A and period 2 pi / w; every root
w > 0 with S Re G(i w) certainly > 0 is returned (a root where that sign is not certain at this precision
is left out). Precision: the current one. Only for h = 0 (the hysteresis estimate involves pi inside the
balance equation: not provided). Fails when: the roots are not isolated: an empty list and the reason.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from flint import arb, fmpq, fmpq_poly

from ...core.balls import ball, certainly_positive
from ...core.polyroots import isolate_polynomial
from .plant_model import PlantModel

__all__ = ["Estimate", "describing_function"]


@dataclass
class Estimate:
    omegas: list = field(default_factory=list)        # (omega, amplitude, period) balls
    reason: str = ""


def _parts(p: fmpq_poly) -> tuple[fmpq_poly, fmpq_poly]:
    """(Re, Im) of p(i w) as real polynomials in w."""
    deg = max(p.degree(), 0)
    re = [fmpq(0)] * (deg + 1)
    im = [fmpq(0)] * (deg + 1)
    for k in range(p.degree() + 1):
        sgn = 1 if k % 4 in (0, 1) else -1
        if k % 2 == 0:
            re[k] = sgn * p[k]
        else:
            im[k] = sgn * p[k]
    return fmpq_poly(re), fmpq_poly(im)


def _at(p: fmpq_poly, x: arb) -> arb:
    out = arb(0)
    for k in range(p.degree(), -1, -1):
        out = out * x + ball(p[k])
    return out


def describing_function(model: PlantModel) -> Estimate:
    """Every describing-function estimate (module docstring), ordered by omega."""
    if model.h != 0:
        return Estimate(reason="the describing-function estimate is given for h = 0 only")
    rn, in_ = _parts(model.numerator_c)
    rp, ip = _parts(model.charpoly)
    Q = in_ * rp - rn * ip
    if Q.degree() < 0:
        return Estimate(reason="Im G(i w) vanishes identically")
    while Q[0] == 0:
        Q = fmpq_poly([Q[k] for k in range(1, Q.degree() + 1)])
    if Q.degree() < 1:
        return Estimate(reason="Im G(i w) = 0 has no root w > 0")
    sq = Q / Q.gcd(Q.derivative())
    roots = isolate_polynomial(sq)
    if not roots.verified:
        return Estimate(reason=f"roots of Im G(i w) not isolated: {roots.reason}")
    out = Estimate()
    S = ball(model.S)
    for w in roots.real:
        if not certainly_positive(w):
            continue
        r, i = _at(rp, w), _at(ip, w)
        den = r * r + i * i                     # products: arb ** 2 of a ball about 0 is nan
        reG = (_at(rn, w) * _at(rp, w) + _at(in_, w) * _at(ip, w)) / den
        if certainly_positive(S * reG):
            out.omegas.append((w, 4 * S * reG / arb.pi(), 2 * arb.pi() / w))
    if not out.omegas:
        out.reason = "no w > 0 with Im G(i w) = 0 and S Re G(i w) > 0: the estimate predicts no oscillation"
    return out
