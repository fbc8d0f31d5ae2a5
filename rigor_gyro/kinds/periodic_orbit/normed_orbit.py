"""The orbit continued over a box (:func:`.continuation.continue_orbit`) with ``stable`` also decided by the
Gershgorin bound of :mod:`.norm_stability` where Rump's method does not isolate the four multipliers.

Step 1 (theta*(P) unique in Theta for every P) and step 2 (the sign condition) are :mod:`.continuation`'s,
unchanged. Step 3 first runs :mod:`.continuation`'s (Rump's method on the centred forms); if that does not
prove every modulus < 1, the same centred forms of J (the total derivatives through theta*(P) by nested jets,
and the exponential form of :mod:`.jacobian_box` with theta a separate direction) are taken into the
centre's eigenvector coordinates and bounded by :func:`.norm_stability.spectral_radius_bound`. The cell
fallback (:mod:`.cellwise`) uses the same step 3 on each cell.

Guarantee: as :func:`.continuation.continue_orbit`: ``stable`` True only when rho(J(theta*(P), P)) < 1 for
every P of the box; ``max_modulus`` then encloses the largest modulus (its lower end possibly 0 when the
bound came from the discs), ``multipliers``/``moduli`` are those of step 3 when it isolated them, else empty.
Precision: the current working precision. Fails when: as continuation (``problem`` says why).
"""
from __future__ import annotations

from flint import arb

from ...core.balls import certainly_lt
from ...core.jets import Jet
from . import continuation as C
from .flow import RelayParams
from .jacobian_box import centred_terms
from .norm_stability import eigen_coordinate_family, largest_modulus_range

__all__ = ["continue_orbit_normed", "normed_decide"]


def _jacobian_families(models, out, th_n: Jet, th_c: Jet):
    """[(J(c), [(dJ_k, dev_k)])]: centred forms of J(theta*(P), P) over the box (see the module docstring)."""
    Jc, terms, *_ = C.centred_jacobian(models, th_n, th_c, models.nested.x0(th_n), models.centre.x0(th_c))
    fams = [(Jc, terms)]
    parts = centred_terms(RelayParams(**models.bvals), out.theta)
    if parts is not None:
        fams.append(parts)
    return fams


def normed_decide(models, out, th_c: Jet, th_n: Jet, genuine: bool, stability: bool) -> None:
    """Steps 2 and 3 (module docstring): fills ``out`` like :func:`.continuation._decide`."""
    C._decide(models, out, th_c, th_n, genuine, stability)
    if not (stability and out.genuine and out.stable is not True):
        return
    best = None
    for Jc, terms in _jacobian_families(models, out, th_n, th_c):
        K = eigen_coordinate_family(Jc, terms)
        r = largest_modulus_range(K) if K is not None else None
        if r is not None and (best is None or certainly_lt(r.upper(), best.upper())):
            best = r
    if best is not None and certainly_lt(best, 1):
        out.stable = True
        out.max_modulus = best
        out.multipliers, out.moduli = [], []
        out.problem = ""
    elif best is not None:
        out.problem += f"; Gershgorin bound of the spectral radius {best.upper().str(6, radius=False)} not < 1"


def continue_orbit_normed(centre: RelayParams, box: dict[str, arb], dirs: list[str], guesses, theta0: arb,
                          genuine: bool = True, stability: bool = True):
    """:func:`.continuation.continue_orbit` with step 3 as in the module docstring (same arguments, same result
    type :class:`.continuation.OrbitOverBox`)."""
    return C.continue_orbit(centre, box, dirs, guesses, theta0, genuine, stability, decide=normed_decide)
