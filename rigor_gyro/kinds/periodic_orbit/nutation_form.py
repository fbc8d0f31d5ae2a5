"""The pole-free half-period function G of a fast, lightly damped nutation, in its nutation form.

With one complex pair lambda = d + i omega (d < 0) and real modes only otherwise, the pole-free
G = g K of :func:`~.flow.pole_free_coeffs` (K = |1 + E|^2, E = exp(lambda theta)) is exactly

    G(theta) = s(theta) (1 + 2 Re E + |E|^2) + 4 q_i Im E + 2 q_r (1 - |E|^2),

q = pe_0 / lambda (q_r, q_i its real and imaginary parts), s = g's slow part: -p0e_0 theta / 2 minus
the real modes' pe_0 tanh(lambda_r theta / 2) / lambda_r (the algebra: -2 Re[q (E - 1)(1 + conj E)]
= 4 q_i Im E + 2 q_r (1 - |E|^2); the same identity the envelope bound uses,
:func:`~.flow.envelope_margin`). Its Taylor coefficients at a point c are then a few exponentials
at c times precomputed powers lambda^j / j! and (2 d)^j / j!, one real series for s and one real
series product: a fraction of the cost of :func:`~.flow.pole_free_coeffs`' complex series algebra
(the root search of the fast-nutation scenes calls it tens of thousands of times).

Guarantee: :meth:`NutationForm.coeffs` returns balls containing G^(j)(c)/j!, j < n, for every point c
of the ball ``center`` (ball arithmetic on an exact identity; the same function as pole_free_coeffs,
other balls). Precision: the current working precision; the powers are recomputed when it changes.
Fails when: the spectrum has not exactly one complex pair, or carries ``near_zero`` (a box
spectrum): :func:`nutation_form` returns None and the caller keeps pole_free_coeffs.

Used only for a fast nutation (:func:`fast_form`), by :func:`~.flow.pole_free_coeffs` itself (so the
prover and rigor-gyro check evaluate the same form): the built-in paper scenes keep the complex series
algebra and their certificates byte for byte.
"""
from __future__ import annotations


from contextlib import nullcontext

from flint import acb, arb, arb_series, ctx

from ...core.balls import current_precision, series_length

__all__ = ["NutationForm", "nutation_form", "fast_form", "FAST_NUTATION_RATIO"]

#: a spectrum is a fast nutation when its pair's omega is at least this multiple of the slowest real
#: rate |lambda_r| (the searched range (0, T] then spans thousands of nutation half-periods): the
#: paper scenes' ratio is 3.2, the stress scenes' H = 1e3, 1e4 32 and 322, H = 1e5 3227
FAST_NUTATION_RATIO = 1000

#: exact constants (arb balls are immutable: sharing them is safe; converting a Python int costs more than
#: the arithmetic it feeds, and coeffs runs ~10^5 times a search)
_ZERO, _ONE, _TWO = arb(0), arb(1), arb(2)


def fast_form(sp) -> "NutationForm | None":
    """The spectrum's nutation form when it is a fast nutation (a point spectrum, one complex pair,
    omega >= FAST_NUTATION_RATIO min |lambda_r|), else None; cached on the spectrum. Float comparison:
    it chooses which correct enclosure of G is computed, it decides nothing (the prover and the
    checker evaluate the same spectrum, so they choose alike)."""
    hit = sp.__dict__.get("_fast_form", 0)
    if hit != 0:
        return hit
    form = None
    pairs = [m for m in getattr(sp, "modes", []) if m.weight == 2]
    real = [abs(float(m.lam.real.mid())) for m in getattr(sp, "modes", []) if m.weight == 1]
    if getattr(sp, "near_zero", None) is None and len(pairs) == 1 and real and \
            abs(float(pairs[0].lam.imag.mid())) >= FAST_NUTATION_RATIO * min(real):
        form = NutationForm(sp)
    sp.__dict__["_fast_form"] = form
    return form


class NutationForm:
    """G's Taylor coefficients from the nutation form (see the module docstring)."""

    def __init__(self, sp):
        pairs = [m for m in sp.modes if m.weight == 2]
        if len(pairs) != 1 or getattr(sp, "near_zero", None) is not None:
            raise ValueError("the nutation form needs exactly one complex pair and a point spectrum")
        pair = pairs[0]
        self.lam = pair.lam
        self.two_d = 2 * pair.lam.real
        q = pair.pe[0] / pair.lam
        self.four_qi = 4 * q.imag
        self.two_qr = 2 * q.real
        self.real = [(m.lam.real, (m.pe[0] / m.lam).real) for m in sp.modes if m.weight == 1]
        # per real mode, the constants of _short's terms: 2 c_r lam_r, c_r lam_r^2 and c_r lam_r / 6
        self._short_consts = [(lam_r, c_r, 2 * c_r * lam_r, c_r * lam_r * lam_r, c_r * lam_r / 6)
                              for lam_r, c_r in self.real]
        self.half_p0 = sp.p0e[0] / 2
        self._prec = None
        self._pow: tuple = ([], [], [])

    def _powers(self, n: int) -> tuple[list[acb], list[arb], list[list[arb]]]:
        prec = current_precision()
        if self._prec != prec or len(self._pow[0]) < n:
            m = max(n, 12)
            L, D = [acb(1)], [arb(1)]
            R = [[arb(1)] for _ in self.real]
            for j in range(1, m):
                L.append(L[-1] * self.lam / j)
                D.append(D[-1] * self.two_d / j)
                for (lam_r, _), Rr in zip(self.real, R):
                    Rr.append(Rr[-1] * lam_r / j)
            self._prec, self._pow = prec, (L, D, R)
        return self._pow

    def coeffs(self, center: arb, n: int) -> list[arb]:
        """Balls containing G^(j)(c)/j!, j < n, for every point c of ``center``."""
        L, D, R = self._powers(n)
        Ec = (self.lam * acb(center)).exp()
        R2c = (self.two_d * center).exp()
        ImE, R2, U = [], [], []
        one = _ONE
        for j in range(n):
            e = Ec * L[j]
            ImE.append(e.imag)
            r2 = R2c * D[j]
            R2.append(r2)
            U.append(r2 + _TWO * e.real)
        U[0] += one
        if n <= 4:
            return self._short(center, n, U, ImE, R2)
        # s = -p0e_0 theta / 2 - sum_r c_r (E_r - 1) / (E_r + 1), E_r = exp(lam_r theta), real series
        s = [-self.half_p0 * center, -self.half_p0] + [arb(0)] * (n - 2) if n > 1 else [-self.half_p0 * center]
        with series_length(n) if n > ctx.cap else nullcontext():     # (python-flint cuts at ctx.cap)
            for (lam_r, c_r), Rr in zip(self.real, R):
                Erc = (lam_r * center).exp()
                Er = [Erc * Rr[j] for j in range(n)]
                num, den = list(Er), list(Er)
                num[0] -= one
                den[0] += one
                y = arb_series(num, prec=n) / arb_series(den, prec=n)
                for j in range(n):
                    s[j] -= c_r * y[j]
            sU = arb_series(s, prec=n) * arb_series(U, prec=n)
            out = [sU[j] + self.four_qi * ImE[j] - self.two_qr * R2[j] for j in range(n)]
        out[0] += self.two_qr
        return out


    def _short(self, center: arb, n: int, U: list[arb], ImE: list[arb], R2: list[arb]) -> list[arb]:
        """coeffs for n <= 4 without series: with E_r = exp(lam_r c) and y = (E_r - 1)/(E_r + 1)
        (= tanh(lam_r theta / 2)), y' = 2 lam_r E_r/(E_r + 1)^2, y''/2 = lam_r^2 E_r (1 - E_r)/(E_r + 1)^3
        (from y' = (lam_r / 2)(1 - y^2)), y'''/6 = -lam_r (y'^2 - lam_r y^2 y') / 6; then the product s U
        term by term."""
        s = [-self.half_p0 * center, -self.half_p0, _ZERO, _ZERO][:n]
        for lam_r, c_r, two_c_lam, c_lam2, c_lam_6 in self._short_consts:
            E = (lam_r * center).exp()
            ip = _ONE / (E + _ONE)
            y = (E - _ONE) * ip
            s[0] -= c_r * y
            if n > 1:
                Eip2 = E * ip * ip
                s[1] -= two_c_lam * Eip2                # c_r y', y' = 2 lam_r E / (E + 1)^2
            if n > 2:
                s[2] -= c_lam2 * Eip2 * (_ONE - E) * ip  # c_r lam_r^2 E (1 - E) / (E + 1)^3
            if n > 3:           # y''' = -lam_r (y'^2 + y y''), y'' = -lam_r y y': the coefficient y'''/6
                y1 = _TWO * lam_r * Eip2
                s[3] += c_lam_6 * (y1 * y1 - lam_r * y * y * y1)
        out = []
        for j in range(n):
            sU = s[0] * U[j]
            for i in range(1, j + 1):
                sU += s[i] * U[j - i]
            out.append(sU + self.four_qi * ImE[j] - self.two_qr * R2[j])
        out[0] += self.two_qr
        return out


def nutation_form(sp) -> NutationForm | None:
    """The spectrum's :class:`NutationForm`, or None where it does not apply."""
    try:
        return NutationForm(sp)
    except ValueError:
        return None
