"""The claims of kind ``periodic_orbit`` for a user's relay plant (a scene with a ``[plant]`` table).

Model: :mod:`.plant_model` (x' = M x + e u, u = S sign(c . x), hysteresis h), mathematics in
:mod:`.plant_orbit`. The claims have the ids of the Roitenberg path (:data:`.claims.CLAIMS`) and say the
same things of y = c . x:

* ``half_period``: every root of g(theta) = c . x0(theta) - h on (0, oo) isolated: (0, theta_min] root-free
  by the exact near-0 bound (:func:`~.plant_orbit.near_zero_bound`), [theta_min, T] tiled by pieces each
  root-free or with exactly one root (interval Newton on Taylor models of the pole-free G = g K,
  :func:`.g_roots.isolate_pieces`), (T, oo) root-free by the tail bound (or the searched (0, T_max] stated); each
  root classified genuine (y > -h on (0, theta)) or spurious with a certified witness;
* ``orbit_genuine``: for the scene's orbit, y(t) + h > 0 on the whole open interval (0, theta*): near 0 by an
  enclosure of y + h (h > 0) or of y' > 0 (h = 0), near theta* by y' < 0, in between by subdivision;
* ``initial_point``: x(0) enclosed (quantities x0_1 .. x0_n);
* ``multipliers``: eigenvalues of the (n-1)x(n-1) Jacobian of the half-period map on the section
  (switching-time correction, symmetry; Arb's matrix exponential; Rump's method), checked against the
  exact Liouville product (:func:`~.plant_orbit.liouville_product`);
* ``stable``: every modulus certainly < 1 for a genuine orbit.

Also reported (quantities, not claims): the orbit's amplitude max y over the period (branch and bound), and
for h = 0 the describing-function estimate of period and amplitude (:mod:`.plant_df`) with the differences.

Guarantee, precision and refutation rules: those of :mod:`.claims` (a restricted search never refutes).
Fails when: the model is bad input (ParameterError from :func:`~.plant_model.validate_plant`, exit 2); the
spectrum is not resolved at this precision (claims inconclusive, the prover escalates).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from flint import acb, acb_mat, arb, fmpq

from ...core.balls import (ball, certainly_gt, certainly_lt, certainly_negative, certainly_positive,
                           current_precision, exact_fraction, interval, working_precision)
from ...core.outcome import Status
from ...core.roots import RootStatus, newton_root
from ...core.subdivision import certify_positive
from .. import Attempt, Phases
from .claims import RootVerdict
from .g_roots import dyadic_up as _dyadic_up, g_series_function as _g_series_function, isolate_pieces as _isolate
from .flow import DegenerateSpectrum, taylor_enclosure
from .multipliers import decide_multipliers
from .norm_stability import spectral_radius_bound
from .plant_model import PlantModel, validate_plant
from .plant_report import assemble
from .plant_statements import GUARD_BITS, PLANT_CLAIMS, TAYLOR_ORDER
from .plant_orbit import (PlantSpectrum, g_coeffs, jacobian, leading_coefficient, liouville_product, near_zero_bound,
                          near_zero_order, orbit_output, section_index, tail_bound, x0_at)
from .texts import interval_text as _fmt, upper_text

__all__ = ["PLANT_CLAIMS", "validate", "statements", "attempt", "analyse", "classify", "plant_multipliers",
           "tail_point", "theta_min"]

TAIL_CAP_FACTOR = 100


def validate(scene) -> PlantModel:
    return validate_plant(scene)


def statements(model: PlantModel) -> dict[str, str]:
    return dict(PLANT_CLAIMS)


# ------------------------------------------------------------------------------ near 0 and the tail

def theta_min(model: PlantModel, start: Fraction, sp: PlantSpectrum | None = None) -> Fraction | None:
    """The largest start / 2^j (j < 200) with (0, start / 2^j] certainly root-free (exact dyadic): by the
    exact bound :func:`~.plant_orbit.near_zero_bound`, or (h = 0, given ``sp``) by the sign of g's leading
    Taylor coefficient over [0, rho] (:func:`~.plant_orbit.leading_coefficient`; g + h = O(theta^(2 j0 + 1))
    exactly)."""
    k = 2 * near_zero_order(model)[0] + 1 if model.h == 0 else None
    for j in range(200):
        rho = start / 2 ** j
        r = ball(fmpq(rho.numerator, rho.denominator))
        if near_zero_bound(model, r):
            return rho
        if sp is not None and k is not None:
            lead = leading_coefficient(lambda ctr, n: g_coeffs(sp, ctr, n, pole_free=False), k, r)
            if certainly_positive(lead) or certainly_negative(lead):
                return rho
    return None


def tail_sign(sp: PlantSpectrum, model: PlantModel) -> int:
    """The sign of g at infinity: of the slope a (exact: -S r_0 / 2) or, without one, of b (0: unknown)."""
    if model.zero_eigenvalue:
        dp = model.charpoly.derivative()
        r0 = model.numerator_c[0] / dp[0] if model.numerator_c.degree() >= 0 else fmpq(0)
        a = -model.S * r0
        if a != 0:
            return 1 if a > 0 else -1
    b = sp.b
    return 1 if certainly_positive(b) else -1 if certainly_negative(b) else 0


def exact_offset(model: PlantModel) -> fmpq | None:
    """b = lim g(theta) as theta -> oo, exactly, for a plant without an integrator whose eigenvalues all have
    Re < 0 (the caller checks that on the spectrum): then sum_k r_k / lambda_k = -G(0), so b = -h - S G(0)
    with G(0) = N_c(0) / p(0) (exact rationals). None with an integrator (g grows linearly)."""
    if model.zero_eigenvalue:
        return None
    p0 = model.charpoly[0]
    Nc0 = model.numerator_c[0] if model.numerator_c.degree() >= 0 else fmpq(0)
    return -model.h - model.S * Nc0 / p0


def approx(x: arb) -> Fraction:
    """A rational near the ball's midpoint, for choices only (never a decision): the nearest double when the
    midpoint is within the double range (as the choices were made in floats), else the exact midpoint (an
    entry like 1e400 or 1e-400 overflows or underflows a double: no float conversion, no crash)."""
    m = x.mid()
    if m.is_zero() or not m.is_finite():
        return Fraction(0)
    v = float(m)
    if math.isfinite(v) and abs(v) >= 2.0 ** -1000:
        return Fraction(v)
    return exact_fraction(m)


def tail_point(sp: PlantSpectrum, model: PlantModel) -> Fraction | None:
    """An exact dyadic T with g of one strict sign on [T, oo) (a geometric ladder from the balls' midpoints,
    chosen in doubles, or in exact rationals (:func:`approx`) when a double overflows or underflows; the
    ladder goes on by doubling up to its cap when 600 steps of 9/8 do not reach it), or None."""
    sgn = tail_sign(sp, model)
    if sgn == 0:
        return None
    try:            # in doubles (the choices of every plant within the double range)
        rates = [float(abs(m.lam.real).mid()) for m in sp.modes]
        fastest = max([float(abs(m.lam).mid()) for m in sp.modes] + [1.0])
        a, b = float(sp.a.mid()), float(sp.b.mid())
        s0 = max(abs(b / a) if a else 0.0, 1.0 / (int(fastest) + 1))
        cap = 100 * TAIL_CAP_FACTOR * (1.0 / min(rates) if rates else 1.0) + 2 * s0
        if not (math.isfinite(cap) and s0 > 0):
            raise OverflowError
        s0, cap = Fraction(s0), Fraction(cap)
    except (OverflowError, ZeroDivisionError, ValueError):       # beyond it: exact rationals
        rates = [approx(abs(m.lam.real)) for m in sp.modes]
        fastest = max([approx(abs(m.lam)) for m in sp.modes] + [Fraction(1)])
        a, b = approx(sp.a), approx(sp.b)
        s0 = max(abs(b / a) if a else Fraction(0), Fraction(1, int(fastest) + 1))
        cap = 100 * TAIL_CAP_FACTOR * (1 / min(rates) if rates and min(rates) else Fraction(1)) + 2 * s0
    start = _dyadic_up(s0)
    ladder = [_dyadic_up(start * Fraction(9, 8) ** k) for k in range(600)]
    while ladder[-1] <= cap and len(ladder) < 600 + 4000:     # widely spread time scales: go on by doubling
        ladder.append(2 * ladder[-1])
    for Tq in ladder:
        if Tq > cap:
            return None
        lo, hi = tail_bound(sp, ball(fmpq(Tq.numerator, Tq.denominator)))
        if (sgn > 0 and certainly_positive(lo.lower())) or (sgn < 0 and certainly_negative(hi.upper())):
            return Tq
    return None


# ------------------------------------------------------------------------------ roots

def classify(sp: PlantSpectrum, theta: arb) -> RootVerdict:
    """Genuine (y + h > 0 on (0, theta), certified) or spurious (a certified witness) or undecided."""
    x0 = x0_at(sp, theta)
    y = orbit_output(sp, theta)
    h = sp.h
    h_zero = sp.model.h == 0
    phi = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (0,))[0] + h      # noqa: E731
    dphi = lambda X: taylor_enclosure(y.coeffs, X, TAYLOR_ORDER, (1,))[0]         # noqa: E731
    th_lo, th_hi = theta.lower(), theta.upper()
    yd0 = y.coeffs(arb(0), 2)[1]

    def witness() -> RootVerdict | None:
        for k in range(1, 64):
            t = (th_lo * k / 64).mid()
            v = phi(t)
            if certainly_negative(v):
                return RootVerdict(theta, x0, "spurious", f"c . x(t) + h = {_fmt(v, 6)} < 0 at t = {_fmt(t, 10)} in "
                                   "(0, theta): the relay switches early", witness_t=t)
        return None

    d1 = None
    if h_zero:
        if certainly_negative(yd0):
            for j in range(1, 80):
                t = th_lo * arb(2) ** (-j)
                if certainly_negative(phi(t)):
                    return RootVerdict(theta, x0, "spurious", f"y'(0) = {_fmt(yd0, 8)} < 0: c . x(t) = "
                                       f"{_fmt(phi(t), 6)} < 0 at t = {_fmt(t, 10)} in (0, theta)", witness_t=t)
            return RootVerdict(theta, x0, "spurious", f"y'(0) = {_fmt(yd0, 8)} < 0 with y(0) = 0: c . x < 0 just "
                               "after the switching")
        if not certainly_positive(yd0):
            return witness() or RootVerdict(theta, x0, "undecided", f"sign of y'(0) = {_fmt(yd0, 8)} undecided")
        for j in range(1, 60):
            d = th_lo * arb(2) ** (-j)
            if certainly_positive(dphi(interval(arb(0), d))):
                d1 = d
                break
    else:
        for j in range(1, 60):
            d = th_lo * arb(2) ** (-j)
            if certainly_positive(phi(interval(arb(0), d))):
                d1 = d
                break
    d2 = None
    for j in range(1, 60):
        d = th_lo * arb(2) ** (-j)
        if certainly_negative(dphi(interval((th_lo - d).lower(), th_hi))):
            d2 = d
            break
    if d1 is None or d2 is None:
        return witness() or RootVerdict(theta, x0, "undecided", "could not certify the sign of c . x near the "
                                        "switchings (raise precision)")
    lo, hi = d1, (th_lo - d2).lower()
    middle: list = []
    if certainly_lt(lo, hi):
        pos = certify_positive(phi, lo, hi, max_pieces=50000, record=middle)
        if pos.status is Status.REFUTED:
            return RootVerdict(theta, x0, "spurious", f"c . x(t) + h = {_fmt(pos.witness_value, 6)} <= 0 at "
                               f"t = {_fmt(pos.witness, 10)} in (0, theta): the relay switches early",
                               witness_t=pos.witness)
        if pos.status is not Status.PROVED:
            return RootVerdict(theta, x0, "undecided", f"c . x + h > 0 on the middle not decided: {pos.reason}")
        mid = f"c . x + h > 0 on [{_fmt(lo, 6)}, {_fmt(hi, 6)}] ({pos.pieces} pieces)"
    else:
        mid = "the two end intervals cover (0, theta*)"
    left = f"y' > 0 on [0, {_fmt(d1, 6)}]" if h_zero else f"c . x + h > 0 on [0, {_fmt(d1, 6)}]"
    return RootVerdict(theta, x0, "genuine", f"y'(0) = {_fmt(yd0, 10)}; {left}; y' < 0 on "
                       f"[theta* - {_fmt(d2, 6)}, theta*]; {mid}", d1=d1, right_start=hi, middle=middle)


def plant_multipliers(sp: PlantSpectrum, v: RootVerdict) -> None:
    """The multipliers of a genuine root (in place), by Rump's method, checked against Liouville's product;
    the smallest replaced by that product over the others when tighter (a stiff plant's tiny multiplier)."""
    model = sp.model
    k = model.n - 1
    if k == 0:      # dimension 1: the section is a point, no multipliers; stable (multipliers.decide_multipliers)
        v.jacobian_note = ("dimension 1: the section c . x = h is a point, the return map's Jacobian is 0x0 (no "
                           "multipliers); a nearby solution runs monotonically to the switching point and follows "
                           "the orbit from there")
        decide_multipliers(v, [])
        return
    J = jacobian(sp.M, sp.e, sp.c, sp.S, v.theta, v.x0, section_index(model))
    liou = liouville_product(sp, v.theta, v.x0)
    try:
        eig = list(acb_mat(J).eig(algorithm="rump"))
    except ValueError:
        v.multiplier_reason = ("eigenvalues of the Jacobian not isolated at this precision (Rump's method: they are "
                               "clustered or multiple at its resolution)" + tiny_product_note(liou, k))
        stable_by_discs(v, J)
        return
    if not all(z.is_finite() for z in eig):
        v.multiplier_reason = "eigenvalue enclosures not finite at this precision" + tiny_product_note(liou, k)
        stable_by_discs(v, J)
        return
    prod = acb(1)
    for z in eig:
        prod *= z
    det = J.det()
    if not (det.is_finite() and liou.is_finite() and prod.real.overlaps(liou) and det.overlaps(liou)):
        raise AssertionError(f"Liouville check failed: prod {prod}, det {det}, expected {liou}: a bug")
    v.jacobian_note = (f"det = product of multipliers = {_fmt(det, 10)} contains (-1)^(n-1) exp(tr M theta*) "
                       f"(c . f0)/(c . f1) = {_fmt(liou, 10)} (Liouville check)")
    if k > 1:
        s = min(range(k), key=lambda i: float(abs(eig[i]).upper()))
        rest = acb(1)
        for i in range(k):
            if i != s:
                rest *= eig[i]
        if rest.is_finite() and certainly_positive(abs(rest)):
            z = acb(liou) / rest
            if z.is_finite() and not z.overlaps(eig[s]):
                raise AssertionError(f"Liouville quotient {z} misses the eigenvalue ball {eig[s]}: a bug")
            if z.is_finite() and (not certainly_positive(abs(eig[s])) or certainly_lt(z.rad(), eig[s].rad())):
                eig[s] = z
                v.jacobian_note += "; the smallest multiplier is enclosed as that product divided by the others"
    decide_multipliers(v, eig)


def tiny_product_bits(liou: arb, k: int) -> int | None:
    """log2 of 1 / the geometric mean of the k multipliers' moduli, |det J|^(-1/k), from Liouville's product
    ``liou`` (enclosed without cancellation: an exponential times a quotient), rounded down (from the ball's
    midpoint: an estimate, exact integers throughout, so no exponent overflows); None when it is not finite, not
    certainly nonzero, or the mean is not below 1. At least one multiplier has a modulus at most about 2^-N."""
    if k < 1 or not liou.is_finite() or not certainly_positive(abs(liou)):
        return None
    log2 = abs(liou).log() / arb(2).log()
    if not log2.is_finite() or not certainly_lt(log2, 0):
        return None
    m = (-log2 / k).mid()                       # exact; an integer already when it has more bits than the precision
    n = m.floor().unique_fmpz()
    if n is None:
        return None
    return int(n) + (1 if certainly_gt(m - n, 1 - arb("1e-9")) else 0)     # an exact power of 2 gives its exponent


def tiny_product_note(liou: arb, k: int) -> str:
    """The reason's addendum where the multipliers may lie far below the precision's resolution (their geometric
    mean 2^-N with N more than twice the working precision, :func:`tiny_product_bits`): a hint, not a claim. One
    tiny multiplier alone does not stop Rump's method (it gets its own disc near 0), so nothing is decided from
    it: the prover keeps raising the precision as for any undecided claim."""
    n = tiny_product_bits(liou, k)
    if n is None or n <= 2 * current_precision():
        return ""
    return (f"; Liouville's product of the {k} multipliers has modulus about 2^-{k * n}, so one has modulus at most "
            f"about 2^-{n}: if several are that small, resolving them from the Jacobian's entries takes roughly {n} "
            "bits")


def stable_by_discs(v: RootVerdict, J) -> None:
    """Where the multipliers are not isolated (clustered, e.g. all about e^(-lambda theta*) with theta* ~ 1e6):
    the orbit is stable when Gershgorin's discs of the Jacobian J (:func:`.norm_stability.spectral_radius_bound`,
    rows or columns, with diagonal scalings) put every eigenvalue in |z| <= U with U certainly < 1. Sets
    ``v.radius_bound`` = U and ``v.stable`` = True then; the multipliers stay unenclosed (``v.margin`` None)."""
    U = spectral_radius_bound(acb_mat(J))
    if U is not None and certainly_lt(U, 1):
        v.radius_bound, v.stable = U, True
        v.multiplier_reason += (f"; every multiplier modulus is at most {upper_text(U)} < 1 all the same (Gershgorin "
                                "discs of the Jacobian), so the orbit is stable")


# ------------------------------------------------------------------------------ analysis

@dataclass
class PlantAnalysis:
    sp: PlantSpectrum | None
    theta_min: Fraction | None = None
    T_tail: Fraction | None = None
    T_search: Fraction | None = None
    covers_all: bool = False
    pieces: int = 0
    piece_list: list = field(default_factory=list)
    unknown: list = field(default_factory=list)
    roots: list = field(default_factory=list)
    problem: str = ""
    #: the spectrum at the guard precision the genuine orbits' quantities were recomputed with
    sp_fine: PlantSpectrum | None = None
    #: True when more precision cannot decide what is open (the prover stops escalating)
    stalled: bool = False


def _q(x: Fraction) -> arb:
    return ball(fmpq(x.numerator, x.denominator))


def _memoised(sp: PlantSpectrum):
    """G's Taylor coefficients, memoised by (precision, centre's exact midpoint and radius, length): Arb is
    deterministic given those, so a memoised list holds the very balls a new call returns (the root search
    asks for the same points again and again). Non-finite centres are computed, never memoised."""
    memo: dict = {}

    def coeffs(ctr, n):
        if type(ctr) is not arb or not ctr.is_finite():
            return g_coeffs(sp, ctr, n)
        key = (current_precision(), ctr.mid().man_exp(), ctr.rad().man_exp(), n)
        hit = memo.get(key)
        if hit is None:
            if len(memo) >= 100_000:
                memo.clear()
            hit = memo[key] = tuple(g_coeffs(sp, ctr, n))
        return list(hit)
    return coeffs


def analyse(model: PlantModel, phase: Phases | None = None) -> PlantAnalysis:
    """Isolate and classify every root of g at the current precision."""
    phase = phase if phase is not None else Phases()
    try:
        with phase("spectrum"):
            sp = PlantSpectrum(model)
    except DegenerateSpectrum as e:
        return PlantAnalysis(None, problem=str(e))
    an = PlantAnalysis(sp)
    with phase("tail point"):
        an.T_tail = tail_point(sp, model)
    if model.T_max is not None:
        Tm = model.T_max.rational
        if an.T_tail is not None and an.T_tail < Tm:
            an.T_search, an.covers_all = an.T_tail, True
        else:
            an.T_search, an.covers_all = Tm, False
    elif an.T_tail is not None:
        an.T_search, an.covers_all = an.T_tail, True
    else:
        b0 = exact_offset(model) if all(m.sigma < 0 for m in sp.modes) else None
        if b0 == 0:
            an.problem = ("g tends to 0 at infinity (no integrator, a stable plant and b = -h - S G(0) = 0 exactly, "
                          "G(s) = c (sI - M)^-1 e): no tail bound exists at any precision; set option T_max to search "
                          "a finite range")
            an.stalled = True
        else:
            an.problem = ("the tail of g (its sign beyond some T) is not certified: g tends to a constant of no "
                          "certain sign or the slowest mode is too slow; set option T_max to search a finite range")
        return an
    fastest = max([float(abs(m.lam).mid()) for m in sp.modes] + [1.0])
    if not math.isfinite(fastest):          # beyond the double range: the exact midpoints
        fastest = max(approx(abs(m.lam)) for m in sp.modes)
    start = Fraction(1, 2 ** max(1, math.ceil(math.log2(int(fastest) + 1))))
    while not 4 * start < an.T_search:
        start /= 2
    with phase("theta_min (near 0)"):
        an.theta_min = theta_min(model, start, sp)
    if an.theta_min is None:
        an.problem = "could not certify that g has no root near theta = 0"
        return an
    with phase("half_period: root isolation"):
        coeffs = _memoised(sp)
        iso = _isolate(_g_series_function(None, coeffs), _q(an.theta_min), _q(an.T_search), coeffs=coeffs)
    an.pieces = len(iso.pieces)
    an.piece_list = iso.pieces
    an.unknown = iso.unknown
    with phase("orbit_genuine: classification"):
        for r in iso.roots:
            an.roots.append(classify(sp, r))
    with phase("multipliers"):
        genuine = [v for v in an.roots if v.kind == "genuine"]
        if genuine:
            # guard bits (as the Roitenberg path): theta*, x(0) and the multipliers recomputed GUARD_BITS above
            # the working precision, each root re-enclosed by interval Newton inside its enclosure
            with working_precision(current_precision() + GUARD_BITS):
                try:
                    fine = PlantSpectrum(model)
                except DegenerateSpectrum:
                    fine = sp
                gf = _g_series_function(None, lambda ctr, n: g_coeffs(fine, ctr, n))
                for v in genuine:
                    piece = newton_root(gf, v.theta.lower(), v.theta.upper())
                    if piece.status is RootStatus.UNIQUE and piece.enclosure.is_finite():
                        v.theta = piece.enclosure.intersection(v.theta)
                        v.x0 = x0_at(fine, v.theta)
                    plant_multipliers(fine, v)
                an.sp_fine = fine
    return an


def attempt(model: PlantModel, wanted: list[str], prec: int) -> Attempt:
    """Evaluate the requested claims at the current precision (set by the prover)."""
    phase = Phases()
    an = analyse(model, phase)
    return assemble(model, an, wanted, phase)
