"""The eigenfrequency claims' sign conditions as functions of the parameters (a, b, eps, Omega2) over a box:
each claim is a list of gaps (bracket slacks, ordering gaps, branch gaps, bound gaps) that must be > 0 (or
>= 0), each a Dual-safe formula (:mod:`rigor_gyro.core.dual_balls`) so that
:mod:`rigor_gyro.core.centred_forms` can enclose it in centred form and decide it at monotone faces.

The roots omega_j and nu_k enter as implicit functions (:func:`rigor_gyro.core.implicit_roots.implicit_root`)
of the quartic Q(omega) = -omega P1(-omega) + Omega2 P2(-omega) and the quadratics (4), written here with
generic arithmetic (the same expressions as :func:`.model.characteristic_quartic` and
:func:`.model.nu_quadratics`; the tests compare them at exact points). The bounds are the model's own
formulas (:func:`.model.bracket`, :func:`.model.nu_bounds`) evaluated on Duals.

Precondition for every function built here: ``Roots`` holds, for the whole box given, balls each
containing exactly one root of every member (verified by the family interval Newton of :mod:`.boxes`):
then each gap function encloses the gap for every parameter in any sub-box or face of that box.

Guarantee: a gap function returns a Dual containing the gap and its parameter gradient over the Duals it
is given, or None where it cannot enclose it (a root not contracted, a bound with no derivative there).
Precision: the current working precision.
"""
from __future__ import annotations

from dataclasses import dataclass

from flint import arb

from ...core.boxes import Box
from ...core.dual_balls import Dual, constant
from ...core.implicit_roots import implicit_root
from .claims import REQUIRED
from .model import Params, bracket, nu_bounds, quartic_value

__all__ = ["Roots", "quartic_value", "nu_value", "GapSet"]


def nu_value(which: str, x, p: Params):
    """The quadratic (4) at x: roots nu1 < nu4 (which = "14") or nu2 < nu6 ("26")."""
    a, b, e, _ = p
    c2 = (a - b) * (b - 1)
    if which == "14":
        return (c2 * x - (e * (a - 1) + a - b)) * x + e
    return (c2 * x - (e * (a - 1) + b * (a - b))) * x + e * a


@dataclass(frozen=True)
class Roots:
    """Whole-box root balls (each with exactly one root of every member; see the module docstring):
    ``omegas`` the four roots of Q, ``nus`` {1, 2, 4, 6: ball}; either may be None (not verified)."""

    omegas: list | None
    nus: dict | None


def _params(model, duals: dict) -> Params:
    return Params(*(duals[k] if k in duals else constant(arb(model.q(k))) for k in REQUIRED))


class GapSet:
    """The gap functions of one box (``model`` fixes the parameters the box leaves out)."""

    def __init__(self, model, box: Box, roots: Roots):
        self.model, self.box, self.roots = model, box, roots
        self._cache: dict = {}

    def _cached(self, key, duals: dict, make):
        """make() once per root and per parameter Duals (keyed exactly by each Dual's ball and the names it
        varies in: the same Duals give the same enclosure, so reuse is sound)."""
        fp = (key, tuple((k, v.value.mid().man_exp(), v.value.rad().man_exp(), tuple(sorted(v.grad)))
                         for k, v in sorted(duals.items())))
        if fp not in self._cache:
            self._cache[fp] = make()
        return self._cache[fp]

    def params(self, duals: dict) -> Params:
        return _params(self.model, duals)

    def _full(self, duals: dict) -> dict:
        p = self.params(duals)
        return dict(zip(REQUIRED, p))

    # ------------------------------------------------------------------ roots as implicit functions
    def omega(self, j: int, duals: dict) -> Dual | None:
        if self.roots.omegas is None:
            return None
        full = self._full(duals)
        return self._cached(("omega", j), duals, lambda: implicit_root(
            lambda x, q: quartic_value(x, Params(*(q[k] for k in REQUIRED))), self.roots.omegas[j - 1], full))

    def nu(self, k: int, duals: dict) -> Dual | None:
        p = self.params(duals)
        if k == 3:
            return 1 / (p.b - 1)
        if k == 5:
            return p.b / (p.b - 1)
        if self.roots.nus is None:
            return None
        which = "14" if k in (1, 4) else "26"
        full = self._full(duals)
        return self._cached(("nu", k), duals, lambda: implicit_root(
            lambda x, q: nu_value(which, x, Params(*(q[n] for n in REQUIRED))), self.roots.nus[k], full))

    # ------------------------------------------------------------------ the gaps of each claim
    def _diff(self, upper, lower):
        """duals -> upper(duals) - lower(duals), None if either is None (each a callable or a constant 0)."""
        def f(duals):
            u = upper(duals)
            v = lower(duals)
            return None if u is None or v is None else u - v
        return f

    def bracket_gaps(self, j: int) -> list[tuple[str, object, bool]]:
        """(label, gap function, strict): omega_j - lower bound and upper bound - omega_j, both >= 0."""
        lo = lambda d: bracket(j, self.params(d), reading="intended")[0]
        hi = lambda d: bracket(j, self.params(d), reading="intended")[1]
        w = lambda d: self.omega(j, d)
        return [(f"omega_{j} - lower (bracket_{j})", self._diff(w, lo), False),
                (f"upper - omega_{j} (bracket_{j})", self._diff(hi, w), False)]

    def ordering_gaps(self) -> list[tuple[str, object, bool]]:
        out = [("nu1 - 0", lambda d: self.nu(1, d), True)]
        for k in range(1, 6):
            out.append((f"nu{k + 1} - nu{k}", self._diff(lambda d, k=k: self.nu(k + 1, d),
                                                          lambda d, k=k: self.nu(k, d)), True))
        return out

    def branch_gaps(self) -> list[tuple[str, object, bool]]:
        w = lambda j: (lambda d: self.omega(j, d))
        n = lambda k: (lambda d: self.nu(k, d))
        return [("omega_1 - 0", w(1), True), ("nu1 - omega_1", self._diff(n(1), w(1)), True),
                ("omega_2 - nu2", self._diff(w(2), n(2)), True), ("nu3 - omega_2", self._diff(n(3), w(2)), True),
                ("omega_3 - nu4", self._diff(w(3), n(4)), True), ("nu5 - omega_3", self._diff(n(5), w(3)), True),
                ("omega_4 - nu6", self._diff(w(4), n(6)), True)]

    def bound_gaps(self) -> list[tuple[str, object, bool]]:
        out = []
        for k in (1, 2, 4, 6):
            lo = lambda d, k=k: nu_bounds(self.params(d))[k][0]
            hi = lambda d, k=k: nu_bounds(self.params(d))[k][1]
            x = lambda d, k=k: self.nu(k, d)
            out += [(f"nu{k} - nu{k}^-", self._diff(x, lo), False), (f"nu{k}^+ - nu{k}", self._diff(hi, x), False)]
        return out
