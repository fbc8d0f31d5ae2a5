"""The relay checker's re-decision of each stored claim status from what it re-verified, shared by the
paper's path (:mod:`.check`) and the user's plant (:mod:`.plant_check`): both re-verify the same things (the
half-period cover, the genuine roots, the main orbit, the multipliers) by their own computations, then
decide the five claims the same way.

Guarantee: a stored ``proved`` is confirmed only by what was re-verified (the stored theta* a re-verified
genuine root; every modulus certainly < 1 for ``stable``), a stored ``refuted`` only by an exhaustive
re-verified search (every root spurious, or every genuine orbit with a modulus certainly > 1). An
``inconclusive`` claim claims nothing. Precision: the caller's balls. Fails when: never (an unknown claim
id is a failed item).
"""
from __future__ import annotations

from ...core.balls import certainly_gt, certainly_lt

__all__ = ["ORBIT_CLAIMS", "other_orbit_moduli", "redecide"]

#: the claims whose stored status :func:`redecide` re-decides
ORBIT_CLAIMS = ("half_period", "orbit_genuine", "initial_point", "multipliers", "stable")


def other_orbit_moduli(genuine: list, main, multipliers_of, contains) -> tuple[list, dict]:
    """(the genuine roots other than ``main``, {k: their recomputed moduli}), k = 2, 3, ... in order; each root's
    stored theta_star_k and, where its multipliers are recomputed (``multipliers_of(theta)``, None when not),
    its stored stability_margin_k checked through ``contains(name, ball)``."""
    others = [th for th in genuine if th is not main]
    other_moduli = {}
    for k, th in enumerate(others, start=2):
        contains(f"theta_star_{k}", th)
        mm = multipliers_of(th)
        if mm is not None:
            other_moduli[k] = [abs(z) for z in mm]
            mx = other_moduli[k][0]
            for m in other_moduli[k][1:]:
                mx = mx.max(m)
            contains(f"stability_margin_{k}", 1 - mx)
    return others, other_moduli


def redecide(cid: str, st: str, *, half_ok: bool, why: str, main, genuine: list, exhaustive: bool,
             moduli_ok: bool, all_moduli: list, bounded: list = ()) -> tuple[bool, str]:
    """(ok, message) for claim ``cid`` stored with status ``st`` (proved or refuted). ``main``: the
    re-verified orbit inside the stored theta* (None: none); ``genuine``: the re-verified genuine roots;
    ``exhaustive``: the search range covered to infinity and the half-period re-verified; ``moduli_ok``: the
    main orbit's and the other genuine orbits' multipliers recomputed; ``all_moduli``: their moduli;
    ``bounded``: for genuine orbits whose multipliers are not isolated, [[0, U]] with U a bound of every
    modulus (Gershgorin): they confirm ``stable`` proved, never the multipliers nor a refutation."""
    if cid == "half_period":
        return st == "proved" and half_ok, why
    if cid == "orbit_genuine":
        if st == "proved":
            return main is not None, ("the stored theta* is a re-verified genuine root" if main is not None
                                      else "no re-verified genuine root inside the stored theta*")
        return exhaustive and not genuine, "exhaustive search with every root spurious, re-verified"
    if cid == "initial_point":
        return ((main is not None) if st == "proved" else (exhaustive and not genuine),
                "x(0) of the re-verified orbit recomputed")
    if cid == "multipliers":
        return (moduli_ok if st == "proved" else (exhaustive and not genuine),
                "eigenvalues of the recomputed Jacobian (another algorithm)")
    if cid == "stable":
        if st == "proved":
            ok = any(m is not None and all(certainly_lt(x, 1) for x in m) for m in [*all_moduli, *bounded])
            return ok, "a genuine orbit with every modulus < 1, re-decided"
        ok = exhaustive and (not genuine or (len(all_moduli) == len(genuine) and
                                             all(any(certainly_gt(x, 1) for x in m) for m in all_moduli)))
        return ok, "exhaustive: no genuine orbit, or every one with a modulus > 1, re-decided"
    return False, f"unknown claim {cid!r}"
