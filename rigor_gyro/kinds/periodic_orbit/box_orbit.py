"""``orbit_genuine`` and ``stable`` over a box by continuing the centre's orbit (:mod:`.continuation`).

Both claims assert existence: some genuine orbit (``orbit_genuine``), some genuine orbit with every multiplier
modulus < 1 (``stable``). Over a box it is therefore enough to exhibit, for every member, one such orbit: the
point analysis at the box's centre (exact rationals) proposes the orbit (a genuine root, for ``stable`` one
certified stable there; with a tracked orbit (a model attribute ``orbit``, when the scene names one) the
tracked one), and :func:`.continuation.continue_orbit` proves, for every parameter in the box, that the
continued root theta*(P) is unique in its interval, genuine, and (for ``stable``) stable.

Guarantee: a claim returned here is ``proved`` for every parameter in the box; claims that this sufficient
test does not decide are left out of the result (the caller decides them otherwise; a failure here never
refutes). Precision: the current working precision. Fails when: never raises for a box it cannot decide.
"""
from __future__ import annotations

import dataclasses

from flint import acb, arb, fmpq

from ...core.balls import ball, current_precision
from ...core.boxes import Box
from ...core.polyroots import isolate_polynomial
from .claims import analyse
from .normed_orbit import continue_orbit_normed as continue_orbit
from .flow import PARAMETER_NAMES, RelayParams, nutation_cubic
from .similar_cover import cover
from .similarity import conjugacy_holds, similar_box, similar_point
from .parametric import PHYSICAL

__all__ = ["continued_outcomes", "centre_orbits", "box_directions"]


def box_directions(box: Box) -> list[str]:
    """The physical parameters the box varies (S, p, K never: see :mod:`.boxes`)."""
    return [k for k in box.names if k in PHYSICAL and box.interval(k)[0] != box.interval(k)[1]]


def _fmt(x: arb, digits: int = 10) -> str:
    return f"[{x.lower().str(digits, radius=False)}, {x.upper().str(digits, radius=False)}]"


def centre_orbits(model, want_stable: bool):
    """The genuine roots of the point analysis at the model's parameters (the box's centre), the ones to
    continue first: the tracked orbit if the model names one, else the stable ones first (only those with
    ``want_stable``). Returns (analysis, [RootVerdict])."""
    # a fresh cache of decided root-search pieces: the model's own one (shared by dataclasses.replace) may
    # hold pieces decided at other parameters, keyed only by the searched range
    an = analyse(dataclasses.replace(model, decided={}))
    genuine = [v for v in an.roots if v.kind == "genuine"]
    tracked = getattr(model, "orbit", None)
    if tracked is not None and genuine:
        t = ball(tracked.fmpq() if hasattr(tracked, "fmpq") else tracked)
        genuine = sorted(genuine, key=lambda v: float(abs(v.theta - t).mid()))[:1]
    if want_stable:
        genuine = [v for v in genuine if v.stable is True]
    else:
        genuine = sorted(genuine, key=lambda v: v.stable is not True)
    return an, genuine


def continued_outcomes(model, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: ("proved", reason)} for the claims among orbit_genuine and stable that the continuation
    proves on the box (module docstring); the others are left out. A box that varies A, H or tau is first
    decided on its similar box of (B, sigma, n) (:mod:`.similarity`), bisected adaptively
    (:mod:`.similar_cover`)."""
    wanted = [c for c in ("orbit_genuine", "stable") if c in claims]
    if not wanted or getattr(model, "orbit", None) is not None:
        # a tracked orbit (option orbit) is the root of g certified NEAREST the option for every member: the
        # continuation does not certify nearness over the box, so those claims go to the whole-range search
        return {}
    out: dict[str, tuple[str, str]] = {}
    red = similar_box(model.params, box)
    direct = red is not None and _spread(red[0]) > _spread(box)
    if direct:
        # the similar box spreads over more directions than the box (tau alone moves B', sigma' and n'):
        # one continuation over the box itself first (tau +-1 %: 0.35 s, against 28 s for the 3-D cover)
        out.update(_continued(model, box, wanted))
        wanted = [c for c in wanted if c not in out]
        if not wanted:
            return out
    if red is not None:
        rbox, fixed = red
        if not conjugacy_holds(model.params, similar_point(model.params, fixed)):
            raise AssertionError("the relay model is no longer similar across equal (a, b, s): a bug")
        got = _cover(model, rbox, fixed, wanted)
        lead = ("decided on the similar box " + ", ".join(f"{k}' in [{_frac(lo)}, {_frac(hi)}]" for k, lo, hi in rbox.edges)
                + f" at {', '.join(f'{k} = {_frac(v)}' for k, v in fixed.items())} (every member has the invariants "
                "H^2 tau^2/(A B), n tau/A, sigma/tau of a member of it: the same orbits up to time tau/tau' and a "
                "positive diagonal change of state, the same multipliers; theta* quoted for that system): ")
        out.update({c: (st, lead + why) for c, (st, why) in got.items()})
        wanted = [c for c in wanted if c not in out]
        if not wanted or direct:
            return out
    out.update(_continued(model, box, wanted))
    return out


def _spread(box: Box) -> int:
    """How many of the box's parameters vary over it."""
    return sum(1 for _, lo, hi in box.edges if lo != hi)


#: the slope ratio (:func:`.theta_fold.slope_ratio`) below which halves cannot prove theta*: 4^-5 (five halvings,
#: each shrinking the slope's enclosure at most 4 times); measured 2e-9 and 3e-7 at H = 9325 +-3.5 % (undecided at
#: every depth), 0.037 and 0.0037 on the similar boxes of H = 100 +-4 % and +-6 %
MIN_SLOPE_RATIO = 4.0 ** -5


def _frac(q) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def _cover(model, rbox: Box, fixed: dict, wanted: list[str]) -> dict[str, tuple[str, str]]:
    """The claims proved on every piece of an adaptive bisection of the similar box ``rbox``
    (:func:`.similar_cover.cover`; each piece continued from its own centre's orbit: both claims assert existence
    per member, so pieces may follow different orbits)."""
    q = lambda x: fmpq(x.numerator, x.denominator)
    base = {k: getattr(model.params, k) for k in PARAMETER_NAMES}
    base.update({k: q(v) for k, v in fixed.items()})

    def evaluate(piece: Box, need: list[str]):
        vals = dict(base)
        vals.update({k: q(v) for k, v in piece.midpoint().items()})
        return _continued(dataclasses.replace(model, params=RelayParams(**vals)), piece, need, report=True)

    got, spent = cover(rbox, wanted, evaluate)
    out = {}
    for c, (n, why) in got.items():
        out[c] = ("proved", why[1] if n == 1 else f"on each of {n} pieces of a bisection of it ({spent} continuations), "
                  f"e.g. on the first: {why[1]}")
    return out


def _continued(model, box: Box, wanted: list[str], report: bool = False):
    """The claims of ``wanted`` proved by continuing the centre's orbits over ``box`` (``model`` at its centre).
    With ``report``: (those claims, whether halves of the box may decide more: theta*(P) was proved over it for a
    continued orbit, or step 1 failed with a slope ratio of at least MIN_SLOPE_RATIO (:func:`.theta_fold.slope_ratio`);
    the motion of that theta* along each direction: |dtheta*/dP_k| over the box times the half-width, or None)."""
    dirs = box_directions(box)
    balls = {k: box.ball(k) for k in dirs}
    iso = isolate_polynomial(nutation_cubic(model.params))
    if not (iso.verified and iso.squarefree):
        return ({}, False, None) if report else {}
    guesses = [acb(r) for r in iso.real] + [z for z in iso.nonreal if z.imag > 0]
    out: dict[str, tuple[str, str]] = {}
    _, orbits = centre_orbits(model, want_stable="stable" in wanted)
    if "stable" not in wanted:
        orbits = orbits[:1]
    reached, weights = False, None
    for v in orbits:
        o = continue_orbit(model.params, balls, dirs, guesses, v.theta, stability="stable" in wanted)
        if o.theta is not None and weights is None:
            weights = {k: float(abs(g).upper()) * float(balls[k].rad()) for k, g in zip(dirs, o.theta_gradient)}
        reached = reached or o.theta is not None or (o.slope_ratio or 0.0) >= MIN_SLOPE_RATIO
        if not o.genuine:
            continue
        head = (f"for every parameter in the box, the orbit continued from the centre's theta* = {_fmt(v.theta, 12)}: "
                f"theta*(P) in {_fmt(o.theta)} is the only root of g there ({o.theta_method}, "
                f"{current_precision()} bits); ")
        if "orbit_genuine" in wanted and "orbit_genuine" not in out:
            out["orbit_genuine"] = ("proved", head + o.genuine_reason)
        if "stable" in wanted and o.stable is True:
            out["stable"] = ("proved", head + f"max multiplier modulus in {_fmt(o.max_modulus)} < 1 "
                             f"(stability margin >= {(1 - o.max_modulus).lower().str(6, radius=False)}); "
                             + o.genuine_reason)
            break
    return (out, reached, weights) if report else out
