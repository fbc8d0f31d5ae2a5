"""Self-oscillation of a relay gyro-stabiliser (Roitenberg 1947): scene kind ``periodic_orbit``.

Model: system (2) of the paper, linear between switchings of the relay u = S sign(beta); see
:mod:`rigor_gyro.kinds.periodic_orbit.flow` for the exact flow. A symmetric periodic solution of half-period theta
starts on the section beta = 0 at x0(theta) = -tanh(M theta/2) M^{-1} e S (the unique solution of
(I + exp(M theta)) x0 = -w(theta), i.e. x(theta) = -x(0)); it closes when its beta component
g(theta) = beta0(theta) vanishes: the paper's equation (13) g(x) = 0. A root is a *genuine* orbit of the
relay system only if beta(t) > 0 on the whole open interval (0, theta) (claim ``orbit_genuine``).

Guarantee: every claim is decided by Arb balls over the exact rational parameters.
* ``half_period``: (0, theta_min] is root-free because g(0) = ... = g^(4)(0) = 0 exactly (e1^T M^j e = 0,
  j <= 3, checked in rational arithmetic; g is odd) and g^(5)/5! is certified > 0 on [0, theta_min];
  [theta_min, T] is covered by pieces each certified root-free or holding exactly one root
  (interval Newton on Taylor-model enclosures of g and g' over the piece,
  :func:`rigor_gyro.core.roots.isolate_roots`); (T, oo) is root-free by the tail bound
  g(theta) >= a theta + b - B(theta) > 0 (:func:`rigor_gyro.kinds.periodic_orbit.flow.tail_bound`) when T is the
  certified tail point, otherwise the searched range (0, T_max] is stated. Each root is classified:
  spurious with a certified witness (beta'(0) <= 0 and a point t with beta(t) < 0, or a point t in
  (0, theta) with beta(t) <= 0), or genuine (claim 2 proved for it).
* ``orbit_genuine``: beta > 0 on (0, theta*): beta' > 0 on [0, d1] and beta' < 0 on [theta* - d2, theta*]
  (enclosures of beta' over these time intervals; beta(0) = beta(theta*) = 0 exactly), beta > 0 on
  the middle by Taylor-model enclosures over sub-intervals (:func:`rigor_gyro.core.subdivision.certify_positive`).
* ``multipliers``: eigenvalues of the 4x4 ball Jacobian of the half-period map (switching-time
  correction and symmetry included) by ``acb_mat.eig(algorithm="rump")`` (valid for every matrix in
  the ball; each output ball holds exactly one eigenvalue; over a parameter box also in eigenvector
  coordinates, :meth:`.boxes.BoxSpectrum.multipliers`); checked against Liouville: their product is
  -exp(-(1/tau + 1/sigma) theta*). A multiplier is reported exactly real when its conjugate ball meets
  no other eigenvalue's ball (the Jacobian is real, so the spectrum is closed under conjugation).
* ``stable``: every modulus certainly < 1 for some genuine orbit (named).

With option ``orbit = "t"`` (an exact t > 0; :mod:`.tracked`, :mod:`.tracked_claims`) orbit_genuine,
initial_point, multipliers and stable are about one orbit only: the root of g on (0, oo) nearest t,
certified nearest (a gap to every other root, undecided piece and unsearched range); their statements
say so (:func:`statements`), and the orbit quantities (theta_star, multiplier_*, stability_margin) are
that root's. A nearness that is not certified leaves them inconclusive, never refuted.

Precision: the prover's, escalated until every claim is decided and theta* has width <= option
``theta_width`` (default 1e-12; Newton usually gives ~2^-prec relative).

Fails when: non-physical parameters (A, B, H, tau, sigma, K, p, S must be > 0, n > 0): ParameterError
(exit 2). A repeated eigenvalue, or a piece of the range left undecided: claims inconclusive with the
reason and what to try (``--maxprec``, option ``T_max``).

Reference: Roitenberg Ya. N. (1947), Avtokolebaniya giroskopicheskikh stabilizatorov (seed 001).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from flint import acb, arb, fmpq

from ...core.balls import (ball, certainly_gt, certainly_le, certainly_lt, certainly_negative, certainly_positive,
                           current_precision, decimal_bounds, decimal_bounds_apart, exact_fraction, interval,
                           working_precision)
from ...core.errors import ParameterError
from ...core.audit import check_printed
from ...core.exact import Exact, option_number, parse_options, parse_parameters, require_rational
from ...core.outcome import Claim, Status
from ...core.roots import Isolation, RootStatus, newton_root
from ...core.stored import exact_text
from ...core.subdivision import certify_positive
from .. import Attempt, Phases
from .texts import complex_text as _fmt_c, interval_text as _fmt, modulus_text as _fmt1, stored_bounds as _bounds
from .genuine_outcome import no_orbit_record, orbit_genuine_outcome
from .tracked import statements as tracked_statements
from .tracked_claims import choose, tracked_claims, tracked_extra
from .paper import PAPER_SCHEMA, audit as audit_paper, formula_table, orbit_quantities
from .multipliers import decide_multipliers
from .phase_walk import PHASE_REASON
from .g_roots import (ENVELOPE_REASON, TAYLOR_ORDER, dyadic_up, envelope_test, g_series_function, isolate_pieces,
                      isolation_coeffs, phase_isolate)
from .flow import (AMPLITUDE_PARAMETERS, PARAMETER_NAMES, DegenerateSpectrum, RelayParams, Spectrum, g_coeffs,
                   moment_zero_orders, orbit_expsums, tail_bound, taylor5_leading_coefficient, taylor_enclosure, x0_at)

__all__ = ["CLAIMS", "PARAMETERS", "OPTIONS", "RelayModel", "RootVerdict", "Analysis", "validate", "attempt",
           "analyse", "classify_root", "statements"]

PARAMETERS = {
    "A": "moment of inertia of the outer ring with object, gyro and motor armature (kg m s^2)",
    "B": "equatorial moment of inertia of the gyroscope (kg m s^2)",
    "H": "angular momentum of the rotor (kg m s)",
    "tau": "time constant of the motor armature circuit (s)",
    "sigma": "time constant of the amplifier circuit (s)",
    "n": "K n1: back-emf coefficient times torque constant (kg m s)",
    "K": "motor torque per ampere (kg m / A)",
    "p": "amplifier gain (dimensionless)",
    "S": "relay output S sign(beta) (A)",
}
#: ``orbit``: "" (no tracked orbit) or an exact t > 0: the claims after half_period are about the root of g
#: nearest t (:mod:`.tracked`; their statements say so, :func:`statements`)
OPTIONS = {"T_max": "auto", "theta_width": "1e-12", "orbit": ""}

#: the numbers a report's summary opens with (quantity name -> what it is), in this order
#: theta_star and its quantities belong to the shortest stable genuine orbit when one is stable, else to
#: the shortest genuine orbit (claims._select); the others are theta_star_2, ... with their own margins.
#: With option orbit: to the root of g certified nearest it when that root is genuine (else no theta_star)
HEADLINE = {"theta_star": "half-period theta* (s)", "period": "period 2 theta* (s)",
            "multiplier_modulus_1": "largest multiplier modulus", "multiplier_modulus_2": "multiplier modulus 2",
            "multiplier_modulus_3": "multiplier modulus 3", "multiplier_modulus_4": "multiplier modulus 4",
            "stability_margin": "stability margin 1 - max modulus",
            # a [plant] scene's (plant_report): the orbit's amplitude and the describing-function estimate
            "amplitude": "amplitude: max over the period of abs(c . x)", "df_period": "describing-function period estimate",
            "df_period_difference": "period minus the estimate", "df_amplitude": "describing-function amplitude estimate",
            "df_amplitude_difference": "amplitude minus the estimate"}

CLAIMS = {
    "half_period": "Every root of the half-period equation g(theta) = 0 (the paper's (13); g = beta(0) of the "
                   "symmetric solution) on the searched range is isolated: each piece of the range is certified "
                   "root-free or to hold exactly one root; each root is classified as a genuine symmetric orbit "
                   "or as spurious with a certified witness.",
    "orbit_genuine": "For the orbit of the scene (and every root reported genuine), beta(t) > 0 on the whole "
                     "open interval (0, theta*): the relay does not switch early; proved for all t, not sampled.",
    "initial_point": "The point x(0) = (beta', Omega, i, I) where the orbit crosses the section beta = 0 is "
                     "enclosed (quantities beta_dot_0, Omega_0, i_0, I_0), with the constants D1..D5 of the "
                     "paper's form (7)/(9).",
    "multipliers": "The Jacobian of the half-period point map on the section (switching-time correction and "
                   "symmetry x -> -x included) has the enclosed eigenvalues (roots of the paper's (25)) and "
                   "moduli, for every genuine orbit.",
    "stable": "A genuine orbit is stable: every multiplier modulus is certainly < 1 (stability_margin = "
              "1 - max modulus, enclosed).",
}

#: bits above the working precision at which a genuine orbit's final quantities are recomputed
GUARD_BITS = 32
#: the tail point is searched up to this multiple of the slowest time scale 1/min|Re lambda|
TAIL_CAP_FACTOR = 100


#: claims that do not depend on a parameter (a threshold search over it is bad input): the relay
#: amplitude S scales the orbit (x(t; S) = S x(t; 1)), and the gains p and K enter only through the
#: amplitude K p S (:func:`~.flow.amplitude_similarity`, an exact identity), so the half-period roots,
#: the sign condition and the multipliers are the same for every S, p, K > 0 (initial_point: whether a
#: genuine orbit exists; its x(0) scales with K p S)
#: (kinds/periodic_orbit/boxes.py uses the same fact)
CLAIMS_INDEPENDENT_OF = {k: ("half_period", "orbit_genuine", "initial_point", "multipliers", "stable")
                         for k in AMPLITUDE_PARAMETERS}

@dataclass(frozen=True)
class RelayModel:
    """Validated exact parameters and options of a periodic-orbit scene."""

    params: RelayParams
    exact: dict[str, Exact]
    T_max: Exact | None           # None: auto (the certified tail point)
    theta_width: Exact
    paper: dict
    #: option ``orbit``: the claims follow the root of g nearest this value (None: not set)
    orbit: Exact | None = None
    #: root-search pieces decided by an earlier attempt of the same proof (lower precision), keyed by the
    #: searched function and range: a later attempt resumes where that one stopped (the pieces are
    #: theorems about the exact g at any precision; the checker re-verifies them at its own)
    decided: dict = field(default_factory=dict, compare=False, repr=False)


def validate(scene) -> RelayModel:
    """Names, presence and domain: A, B, H, tau, sigma, K, p, S > 0 and n > 0 (exact rationals)."""
    p = scene.parameters
    v = parse_parameters(p, "periodic_orbit", PARAMETERS, PARAMETER_NAMES)
    require_rational(v)
    why = {"A": "zero or negative inertia", "B": "zero or negative inertia",
           "H": "the gyroscope must spin (H > 0)", "tau": "time constants are > 0",
           "sigma": "time constants are > 0", "K": "motor torque constant must be > 0",
           "p": "amplifier gain must be > 0",
           "S": "S = 0 means no relay signal (no forcing, no self-oscillation); S < 0 is the same system "
                "with beta -> -beta: write |S|",
           "n": "n = K n1 > 0 (back-emf damping; n = 0 leaves the nutation undamped and g has poles)"}
    for k in PARAMETER_NAMES:
        if not v[k].rational > 0:
            raise ParameterError(f"parameter {k!r} = {p[k]!r}: need {k} > 0 ({why[k]})")
    opts = parse_options(scene.options, OPTIONS, "periodic_orbit")
    T_max = None
    if opts["T_max"] != "auto":
        T_max = option_number(opts["T_max"], "T_max (or \"auto\")", above="0", at_most="1e6")
    tw = option_number(opts["theta_width"], "theta_width", above="0", at_most="1")
    orbit = None
    if opts["orbit"].strip():
        orbit = option_number(opts["orbit"].strip(), "orbit (a half-period theta > 0, or \"\" for none)",
                              above="0", at_most="1e6")
    check_printed(scene.paper, PAPER_SCHEMA)
    params = RelayParams(**{k: v[k].fmpq() for k in PARAMETER_NAMES})
    return RelayModel(params, v, T_max, tw, dict(scene.paper), orbit)


def statements(model: RelayModel) -> dict[str, str]:
    """The statement of each claim for this scene: :data:`CLAIMS`, or with option ``orbit`` the statements
    of :data:`.tracked.TRACKED_STATEMENTS` for the claims that follow that orbit (the certificate's
    ``statement`` fields; a checker compares against these, not against CLAIMS, for such a scene)."""
    return tracked_statements(CLAIMS, model.orbit.text if model.orbit is not None else None)


# ------------------------------------------------------------------------------ per-root analysis

@dataclass
class RootVerdict:
    """One root theta of g and what was certified about it."""

    theta: arb
    x0: list[arb]
    kind: str                      # "genuine" | "spurious" | "undecided"
    reason: str
    witness_t: arb | None = None
    multipliers: list[acb] = field(default_factory=list)   # sorted by decreasing modulus (float order)
    moduli: list[arb] = field(default_factory=list)
    stable: bool | None = None     # True certified stable, False certified unstable, None undecided
    margin: arb | None = None
    jacobian_note: str = ""
    multiplier_reason: str = ""
    #: where the multipliers are not isolated: an upper bound of every multiplier's modulus (Gershgorin discs of
    #: the Jacobian, :mod:`.norm_stability`), set only when certainly < 1 (then ``stable`` is True)
    radius_bound: arb | None = None
    #: the witness of "genuine": beta' > 0 on [0, d1], beta' < 0 on [right_start, theta], beta > 0 on
    #: the middle pieces (exact endpoints), for rigor-gyro check
    d1: arb | None = None
    right_start: arb | None = None
    middle: list = field(default_factory=list)

    def __post_init__(self):
        # a verdict of another kind would be counted as neither classified nor undecided (and the
        # half-period claim proved with a root nobody classified): a bug, refused where it is made
        if self.kind not in ROOT_KINDS or not isinstance(self.theta, arb) or not isinstance(self.reason, str):
            raise AssertionError(f"malformed root verdict: kind {self.kind!r}, theta {self.theta!r}, "
                                 f"reason {self.reason!r}: a bug")


#: what :func:`classify_root` can say of a root
ROOT_KINDS = ("genuine", "spurious", "undecided")


def _beta_positive_on(beta, lo: arb, hi: arb, record: list | None = None):
    f = lambda X: taylor_enclosure(beta.coeffs, X, TAYLOR_ORDER, (0,))[0]
    return certify_positive(f, lo, hi, max_pieces=50000, record=record)


def _dbeta(beta, X: arb) -> arb:
    return taylor_enclosure(beta.coeffs, X, TAYLOR_ORDER, (1,))[0]


#: where beta'(0) has no certain sign, beta is tried at theta_lo k / WITNESS_GRID, 0 < k < WITNESS_GRID
WITNESS_GRID = 32


def classify_root(sp: Spectrum, theta: arb) -> RootVerdict:
    """Decide whether the root theta of g is a genuine orbit (beta > 0 on (0, theta)) or spurious."""
    x0 = x0_at(sp, theta)
    beta = orbit_expsums(sp, x0)[0]
    th_lo, th_hi = theta.lower(), theta.upper()
    bd0 = x0[1]
    if certainly_negative(bd0):
        for j in range(1, 80):
            t = th_lo * arb(2) ** (-j)
            if certainly_negative(beta(t)):
                return RootVerdict(theta, x0, "spurious", f"beta'(0) = {_fmt(bd0, 8)} < 0: beta(t) = "
                                   f"{_fmt(beta(t), 6)} < 0 at t = {_fmt(t, 10)} in (0, theta)", witness_t=t)
        return RootVerdict(theta, x0, "spurious", f"beta'(0) = {_fmt(bd0, 8)} < 0: beta < 0 just after the "
                           "switching (the orbit starts into beta < 0)")
    if not certainly_positive(bd0):
        # beta'(0) of no certain sign (a box spectrum's wide enclosure, say): beta certainly < 0 at a
        # point of (0, theta) still proves the root spurious (the relay would switch there first)
        for k in range(1, WITNESS_GRID):
            t = (th_lo * k / WITNESS_GRID).mid()
            bt = beta(t)
            if certainly_negative(bt):
                return RootVerdict(theta, x0, "spurious", f"beta(t) = {_fmt(bt, 6)} < 0 at t = {_fmt(t, 10)} "
                                   f"in (0, theta) (beta'(0) = {_fmt(bd0, 8)} of no certain sign)", witness_t=t)
        return RootVerdict(theta, x0, "undecided", f"sign of beta'(0) = {_fmt(bd0, 8)} undecided and beta not "
                           f"certainly < 0 at {WITNESS_GRID - 1} points of (0, theta) (raise precision)")
    # left end: beta' > 0 on [0, d1]
    d1 = None
    for j in range(1, 60):
        d = th_lo * arb(2) ** (-j)
        if certainly_positive(_dbeta(beta, interval(arb(0), d))):
            d1 = d
            break
    d2 = None
    for j in range(1, 60):
        d = th_lo * arb(2) ** (-j)
        if certainly_negative(_dbeta(beta, interval((th_lo - d).lower(), th_hi))):
            d2 = d
            break
    if d1 is None or d2 is None:
        return RootVerdict(theta, x0, "undecided", "could not certify the sign of beta' near the switchings "
                           "(raise precision)")
    lo, hi = d1, (th_lo - d2).lower()
    middle_pieces: list = []
    if certainly_lt(lo, hi):
        pos = _beta_positive_on(beta, lo, hi, middle_pieces)
        if pos.status is Status.REFUTED:
            t = pos.witness
            return RootVerdict(theta, x0, "spurious", f"beta(t) = {_fmt(pos.witness_value, 6)} <= 0 at "
                               f"t = {_fmt(t, 10)} in (0, theta): the relay switches early", witness_t=t)
        if pos.status is not Status.PROVED:
            return RootVerdict(theta, x0, "undecided", f"beta > 0 on the middle not decided: {pos.reason}")
        middle = f"beta > 0 on [{_fmt(lo, 6)}, {_fmt(hi, 6)}] ({pos.pieces} pieces)"
    else:
        middle = "the two end intervals cover (0, theta*)"
    return RootVerdict(theta, x0, "genuine",
                       f"beta'(0) = {_fmt(bd0, 10)} > 0; beta' > 0 on [0, {_fmt(d1, 6)}]; beta' < 0 on "
                       f"[theta* - {_fmt(d2, 6)}, theta*]; {middle}", d1=d1, right_start=hi, middle=middle_pieces)


def _multipliers(sp: Spectrum, v: RootVerdict) -> None:
    J = sp.jacobian(v.theta, v.x0)
    try:
        eig = sp.multipliers(J, v.theta)
    except ValueError:
        v.multiplier_reason = ("eigenvalues of the Jacobian not isolated at this precision (Rump's method: they are "
                               "clustered or multiple at its resolution)")
        return
    if not all(z.is_finite() for z in eig):
        v.multiplier_reason = "eigenvalue enclosures not finite at this precision"
        return
    prod = acb(1)
    for z in eig:
        prod *= z
    P = sp.P
    liou = -((-(1 / ball(P.tau) + 1 / ball(P.sigma))) * v.theta).exp()
    det = J.det()
    if not (det.is_finite() and prod.real.overlaps(liou) and det.overlaps(liou)):   # (a NaN ball overlaps anything)
        raise AssertionError(f"Liouville check failed: prod {prod}, det {det}, expected {liou}: a bug")
    v.jacobian_note = (f"det = product of multipliers = {_fmt(det, 10)} contains -exp(-(1/tau+1/sigma) theta*) "
                       f"= {_fmt(liou, 10)} (Liouville check)")
    # The smallest multiplier of a stiff case (1e-56 and far below) comes back from eig as a ball around
    # 0. The product of the four is exactly the Liouville value, so the smallest is that divided by the
    # other three: an enclosure with a positive modulus and a relative width like the others'.
    eig = list(eig)
    k = min(range(4), key=lambda i: float(abs(eig[i]).upper()))      # float picks; balls enclose
    rest = acb(1)
    for i in range(4):
        if i != k:
            rest *= eig[i]
    if rest.is_finite() and certainly_positive(abs(rest)):
        z = acb(liou) / rest
        if z.is_finite() and eig[k].is_finite() and not z.overlaps(eig[k]):
            raise AssertionError(f"Liouville quotient {z} misses the eigenvalue ball {eig[k]}: a bug")
        if z.is_finite() and (not eig[k].is_finite() or not certainly_positive(abs(eig[k]))
                              or certainly_lt(z.rad(), eig[k].rad())):
            eig[k] = z
            v.jacobian_note += "; the smallest multiplier is enclosed as that product divided by the other three"
    # J is real: exactly real eigenvalues, ordered multipliers, moduli, margin and the stability decision
    decide_multipliers(v, eig)


@dataclass
class Analysis:
    """Everything one attempt established."""

    sp: Spectrum | None
    theta_min: arb | None = None
    T_tail: arb | None = None
    T_search: arb | None = None
    covers_all: bool = False
    pieces: int = 0
    unknown: list = field(default_factory=list)
    roots: list[RootVerdict] = field(default_factory=list)
    problem: str = ""
    #: the problem is an exact degeneracy of the parameters (a repeated eigenvalue): no precision lifts it
    exact_problem: bool = False
    piece_list: list = field(default_factory=list)
    #: the function whose roots were isolated: "pole_free" (G = g K) or "g"
    isolated: str = "g"
    #: the spectrum at the guard precision (current + GUARD_BITS) that the genuine orbits' final
    #: quantities (theta*, x(0), multipliers, D1..D5) were computed with; None if there are none
    sp_fine: Spectrum | None = None


def _slowest_scale(sp: Spectrum) -> arb:
    rs = [abs(m.lam.real) for m in sp.modes]
    mn = rs[0]
    for r in rs[1:]:
        mn = mn.min(r)
    return 1 / mn


def _theta_min(sp: Spectrum, start: arb) -> arb | None:
    """Largest start/2^j with g^(5)/5! certified > 0 on [0, start/2^j]."""
    for j in range(0, 80):
        t = start * arb(2) ** (-j)
        if certainly_positive(taylor5_leading_coefficient(sp, interval(arb(0), t))):
            return t
    return None


def _tail_point(sp: Spectrum) -> arb | None:
    """A T with g(theta) > 0 certified for every theta >= T (T from a geometric ladder)."""
    a, b = sp.a, sp.b
    fastest = max((float(abs(m.lam).mid()) for m in sp.modes))  # floats pick a start only
    ratio = float((-b / a).mid()) if certainly_negative(b) else 0.0
    if not (math.isfinite(fastest) and math.isfinite(ratio)):
        return None         # a start beyond floats (e.g. H = 1e-300: -b/a ~ 1e600): no ladder can be climbed
    s0 = max(ratio, 1.0 / (int(fastest) + 1))
    # exact dyadic rungs, the same at every precision (a later attempt then searches the same range)
    start = dyadic_up(Fraction(s0))
    cap = _slowest_scale(sp) * TAIL_CAP_FACTOR
    for k in range(400):
        Tq = dyadic_up(start * Fraction(9, 8) ** k)
        T = arb(fmpq(Tq.numerator, Tq.denominator))
        if certainly_positive(tail_bound(sp, T).lower()):
            return T
        if certainly_gt(T, cap):
            return None
    return None


def analyse(model: RelayModel, spectrum=None, phase: Phases | None = None) -> Analysis:
    """Isolate and classify every root at the current precision. ``spectrum``: a callable returning
    the :class:`Spectrum` to use (default: ``Spectrum(model.params)``; the box version passes one whose
    balls contain a whole parameter box, :mod:`.boxes`); ``phase`` records the time of each stage."""
    P = model.params
    phase = phase if phase is not None else Phases()
    try:
        with phase("spectrum"):
            sp = spectrum() if spectrum is not None else Spectrum(P)
    except DegenerateSpectrum as e:
        return Analysis(None, problem=str(e), exact_problem=e.exact)
    mom = moment_zero_orders(P)
    if any(m != 0 for m in mom[:4]) or mom[4] == 0:
        return Analysis(sp, problem=f"moment identities e1^T M^j e = 0 (j <= 3) fail: {mom}: a bug")
    an = Analysis(sp)
    with phase("tail point"):
        an.T_tail = _tail_point(sp)
    if model.T_max is not None:
        Tm = ball(model.T_max.fmpq()).upper()        # an exact point >= T_max: the search covers (0, T_max]
        if an.T_tail is not None and certainly_lt(an.T_tail, Tm):
            an.T_search, an.covers_all = an.T_tail, True
        else:
            an.T_search, an.covers_all = Tm, False
    elif an.T_tail is not None:
        an.T_search, an.covers_all = an.T_tail, True
    else:
        an.problem = (f"tail bound a theta + b - B(theta) > 0 not certified up to {TAIL_CAP_FACTOR} x the slowest "
                      "time scale: set option T_max to search a finite range")
        return an
    fastest = max((float(abs(m.lam).mid()) for m in sp.modes))  # float picks a start only
    # a power of two below 1/(fastest + 1) (and T/4): the same exact point at every precision, so a later
    # attempt can resume the root search of an earlier one (same theta_min, same range)
    start = arb(2) ** (-max(1, math.ceil(math.log2(int(fastest) + 1))))
    while not certainly_lt(4 * start, an.T_search):
        start = start / 2
    with phase("theta_min (g = O(theta^5))"):
        an.theta_min = _theta_min(sp, start)
    if an.theta_min is None:
        an.problem = "could not certify g^(5) > 0 near theta = 0 (raise precision)"
        return an
    with phase("half_period: root isolation"):
        coeffs, an.isolated = isolation_coeffs(sp)
        key = (an.isolated, exact_fraction(an.theta_min), exact_fraction(an.T_search))
        cached = model.decided.get(key) if spectrum is None else None
        if cached is not None and cached[1] is None:        # an earlier attempt isolated every root:
            pieces = []                                     # keep its pieces, refine each root here
            f = g_series_function(sp, coeffs)
            for pc in cached[0]:
                if pc.status is RootStatus.UNIQUE and not pc.parts and not pc.reason.startswith(PHASE_REASON):
                    again = newton_root(f, pc.lo, pc.hi)
                    pc = again if again.status is RootStatus.UNIQUE else pc
                pieces.append(pc)
            iso = Isolation(pieces)
        else:
            # (an earlier attempt's partial search is not resumed here: the walk restarts at theta_min)
            iso = phase_isolate(sp, coeffs, an.theta_min, an.T_search)
            if iso is None:
                iso = isolate_pieces(g_series_function(sp, coeffs), an.theta_min, an.T_search, coeffs=coeffs, resume=cached,
                               root_free=envelope_test(sp), signed_split=getattr(sp, "near_zero", None) is not None)
        if spectrum is None:
            model.decided[key] = iso.resume if iso.resume is not None else \
                ((list(iso.pieces), None) if not iso.unknown else None)
    an.pieces = len(iso.pieces)
    an.piece_list = iso.pieces
    an.unknown = iso.unknown
    with phase("orbit_genuine: classification"):
        for r in iso.roots:
            an.roots.append(classify_root(sp, r))
    with phase("multipliers"):
        genuine = [v for v in an.roots if v.kind == "genuine"]
        if genuine:
            # guard bits: theta*, x(0) and the multipliers are recomputed GUARD_BITS above the working
            # precision, so their widths follow 2^-prec instead of losing the bits that the spectral
            # sums and the eigenvalue problem cancel (the checker works at >= 2 prec, above this)
            with working_precision(current_precision() + GUARD_BITS):
                fine = spectrum() if spectrum is not None else Spectrum(P)
                gf = g_series_function(fine)
                for v in genuine:
                    piece = newton_root(gf, v.theta.lower(), v.theta.upper())
                    if piece.status is RootStatus.UNIQUE and piece.enclosure.is_finite():
                        v.theta = piece.enclosure.intersection(v.theta)
                        v.x0 = x0_at(fine, v.theta)
                    _multipliers(fine, v)
            an.sp_fine = fine
    return an


# ------------------------------------------------------------------------------ claims

def _claim(cid: str, status: Status, reason: str, counterexample: dict | None = None, **details) -> Claim:
    return Claim(cid, CLAIMS[cid], status, reason, details=details, counterexample=counterexample)


def _select(genuine: list[RootVerdict]) -> tuple[RootVerdict | None, str]:
    """The orbit the headline quantities (theta*, period, moduli, stability margin) are about: a stable
    genuine orbit whenever one is certified stable (the shortest when several are), so that a margin is
    never reported of an unstable orbit while ``stable`` holds by another; else the shortest genuine one."""
    stable = [v for v in genuine if v.stable is True]
    if len(stable) == 1:
        return stable[0], "the stable genuine orbit"
    if stable:
        return stable[0], "the shortest stable genuine orbit (several are stable)"
    if genuine:
        return genuine[0], "the shortest genuine orbit (none is certified stable)"
    return None, "no genuine orbit"


def attempt(model: RelayModel, wanted: list[str], prec: int, spectrum=None) -> Attempt:
    """Evaluate the requested claims at the current precision (set by the prover); ``spectrum`` as in
    :func:`analyse`."""
    phase = Phases()
    an = analyse(model, spectrum, phase)
    claims: list[Claim] = []
    quantities: dict[str, arb] = {}
    notes: list[str] = []
    extra: dict[str, Any] = {}
    if an.sp is None or an.problem:
        why = an.problem or "spectrum unavailable"
        if an.exact_problem:
            why += (" (decided in exact arithmetic: no precision lifts it; the closed form needs five simple "
                    "eigenvalues, so move one parameter off this point)")
        for cid in wanted:
            claims.append(_claim(cid, Status.INCONCLUSIVE, why))
            if an.exact_problem:
                claims[-1].precision_cannot_help = why
        return Attempt(claims, quantities, notes=notes, widths_met=False, stalled=an.exact_problem)
    sp = an.sp
    rng = (f"(0, {_fmt(an.T_search, 8)}]" + (" and beyond it by the tail bound, i.e. all of (0, oo)"
                                              if an.covers_all else " (option T_max; roots beyond it not searched)"))
    genuine = [v for v in an.roots if v.kind == "genuine"]
    spurious = [v for v in an.roots if v.kind == "spurious"]
    undecided = [v for v in an.roots if v.kind not in ("genuine", "spurious")]
    complete = not an.unknown and not undecided      # every root in the searched range classified
    # A search restricted by option T_max never refutes: an orbit may lie beyond it. Non-existence is
    # certified only when the range is all of (0, oo) (tail bound) and every root in it is classified.
    exhaustive = complete and an.covers_all
    beyond = (f"; roots beyond T_max = {_fmt(an.T_search, 8)} were not searched, so this is not a refutation "
              "(set option T_max = \"auto\" to search all of (0, oo))") if not an.covers_all else ""
    no_orbit = no_orbit_record(an.T_tail, an.theta_min, spurious) if exhaustive and not genuine else None
    # ---- half_period
    if an.unknown:
        hp = (Status.INCONCLUSIVE, f"{len(an.unknown)} piece(s) of {rng} undecided, first "
              f"[{_fmt(an.unknown[0].lo, 10)}, {_fmt(an.unknown[0].hi, 10)}]: {an.unknown[0].reason}")
    elif undecided:
        hp = (Status.INCONCLUSIVE, f"{len(an.roots)} roots isolated on {rng}; {len(undecided)} not classified: "
              + "; ".join(f"theta = {_fmt(v.theta, 10)}: {v.reason}" for v in undecided[:3]))
    else:
        hp = (Status.PROVED, f"{len(an.roots)} roots of g on {rng}, each simple and alone in its piece "
              f"({an.pieces} pieces by interval Newton; (0, {_fmt(an.theta_min, 4)}] root-free since g = O(theta^5) "
              f"with g^(5) > 0 there); {len(genuine)} genuine "
              f"({', '.join(_fmt(v.theta, 10) for v in genuine)}), {len(spurious)} spurious with certified witnesses")
    if "half_period" in wanted:
        claims.append(_claim("half_period", *hp, pieces=an.pieces, roots=len(an.roots)))
    main, why_main = _select(genuine)
    tracked = None
    if model.orbit is not None:     # option orbit: the scene's orbit is the root of g nearest it, or none
        tracked = choose(model, an)
        main, why_main = tracked.genuine, tracked.label
    # ---- orbit_genuine
    og = orbit_genuine_outcome(main, why_main, genuine, spurious, rng, complete=complete, exhaustive=exhaustive,
                               no_orbit=no_orbit, beyond=beyond, undecided_reason=hp[1], whose=" of the relay system")
    if "orbit_genuine" in wanted and tracked is None:
        claims.append(_claim("orbit_genuine", *og))
    none_exists = main is None and exhaustive
    # ---- quantities of the scene's orbit
    widths_met = True
    if main is not None:
        quantities["theta_star"] = main.theta
        with working_precision(current_precision() + GUARD_BITS):     # exact doubling: theta*'s own width
            quantities["period"] = 2 * main.theta
        for name, k in (("beta_dot_0", 1), ("Omega_0", 2), ("i_0", 3), ("I_0", 4)):
            quantities[name] = main.x0[k]
        widths_met = certainly_le(2 * main.theta.rad(), ball(model.theta_width.fmpq()))
    if "initial_point" in wanted and tracked is None:
        if main is not None:
            st = (Status.PROVED, f"x(0) of {why_main}: beta' = {_fmt(main.x0[1], 14)}, Omega = {_fmt(main.x0[2], 14)}, "
                  f"i = {_fmt(main.x0[3], 14)}, I = {_fmt(main.x0[4], 14)} (beta = g(theta*) = 0 exactly)")
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine): there is no initial point", no_orbit)
        else:
            st = (Status.INCONCLUSIVE, "no genuine orbit certified yet" + beyond)
        claims.append(_claim("initial_point", *st))
    # ---- multipliers, stability
    if main is not None and main.moduli:
        for j, (z, m) in enumerate(zip(main.multipliers, main.moduli), start=1):
            quantities[f"multiplier_modulus_{j}"] = m
        for j, z in enumerate(main.multipliers, start=1):
            quantities[f"multiplier_{j}_re"] = z.real
            quantities[f"multiplier_{j}_im"] = z.imag
        quantities["stability_margin"] = main.margin
    others = [v for v in genuine if v is not main]
    for k, v in enumerate(others, start=2):
        quantities[f"theta_star_{k}"] = v.theta
        if v.margin is not None:
            quantities[f"stability_margin_{k}"] = v.margin
    if "multipliers" in wanted and tracked is None:
        bad = [v for v in genuine if not v.moduli]
        if genuine and not bad:
            parts = []
            for v in genuine:
                parts.append(f"theta = {_fmt(v.theta, 10)}: " + ", ".join(
                    f"{_fmt_c(z, 10)} (|.| = {_fmt(m, 10)})" for z, m in zip(v.multipliers, v.moduli)))
            st = (Status.PROVED, "; ".join(parts) + f"; {main.jacobian_note}")
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine)", no_orbit)
        else:
            st = (Status.INCONCLUSIVE, "; ".join(v.multiplier_reason for v in bad) or
                  "no genuine orbit certified yet" + beyond)
        claims.append(_claim("multipliers", *st))
    if "stable" in wanted and tracked is None:
        stable = [v for v in genuine if v.stable is True]
        if stable:
            s = stable[0] if main not in stable else main
            st = (Status.PROVED, f"the orbit theta* = {_fmt(s.theta, 12)} has max modulus {_fmt1(s.moduli[0], 10)} < 1; "
                  f"stability margin {_fmt(s.margin, 10)}" + (f"; {len(stable)} stable genuine orbits" if len(stable) > 1 else "")
                  + (f"; unstable: {', '.join(_fmt(v.theta, 8) for v in genuine if v.stable is False)}"
                     if any(v.stable is False for v in genuine) else ""))
        elif complete and genuine and all(v.stable is False for v in genuine):
            text = ("every genuine orbit has a multiplier of modulus certainly > 1: "
                    + "; ".join(f"theta = {_fmt(v.theta, 10)}: max |.| = {_fmt1(v.moduli[0], 10)}" for v in genuine))
            unstable = {"searched": "(0, oo)", "tail_point": _bounds(an.T_tail) if an.T_tail is not None else None,
                        "orbits": [{"theta": _bounds(v.theta),
                                    "modulus_above_1": _bounds(next(m for m in v.moduli if certainly_gt(m, 1)))}
                                   for v in genuine]}
            st = (Status.REFUTED, text, unstable) if exhaustive else (Status.INCONCLUSIVE, text + beyond)
        elif none_exists:
            st = (Status.REFUTED, "no genuine orbit exists (see orbit_genuine), so no stable self-oscillation",
                  no_orbit)
        else:
            st = (Status.INCONCLUSIVE, "stability of the genuine orbits not decided at this precision"
                  if genuine else "no genuine orbit certified yet" + beyond)
        claims.append(_claim("stable", *st))
    if tracked is not None:
        claims.extend(tracked_claims(statements(model), an, tracked, wanted, exhaustive=exhaustive, no_orbit=no_orbit,
                                     searched=rng, search_open="" if hp[0] is Status.PROVED else hp[1]))
        extra["tracked_orbit"] = tracked_extra(tracked)
    # what would decide the claims left open by an undecided piece of the range: g over that piece (the
    # prover stops escalating when doubling the precision no longer shrinks it, e.g. at a depth limit)
    if complete and not an.covers_all:      # everything in (0, T_max] decided: precision cannot add more
        for c in claims:
            if c.status is Status.INCONCLUSIVE:
                c.precision_cannot_help = ("the scene restricts the search to (0, T_max] and every root there is "
                                           "decided; set option T_max = \"auto\" to search all of (0, oo)")
    if an.unknown:
        u = an.unknown[0]
        if "precision limit" in u.reason:     # more precision resolves a narrower piece: watch g there
            gu = taylor_enclosure(lambda ctr, n: g_coeffs(sp, ctr, n), interval(u.lo, u.hi), TAYLOR_ORDER, (0,))[0]
        else:                                 # a depth or piece budget: the same piece again means no progress
            gu = interval(u.lo, u.hi)
        for c in claims:
            if c.status is Status.INCONCLUSIVE:
                c.decides = gu
    # ---- notes and extra: every root with its verdict
    rows = []
    for k, v in enumerate(an.roots, start=1):
        line = f"root {k}: theta = {_fmt(v.theta, 14)}: {v.kind}: {v.reason}"
        if v.moduli:
            line += "; multipliers " + ", ".join(_fmt_c(z, 8) for z in v.multipliers) + "; moduli " + ", ".join(
                _fmt1(m, 8) for m in v.moduli) + ("; STABLE" if v.stable else "; UNSTABLE" if v.stable is False else "")
        rows.append({"theta": list(decimal_bounds(v.theta, 20)), "kind": v.kind, "reason": v.reason,
                     "moduli": [list(decimal_bounds_apart(m, 1, 12)) for m in v.moduli],
                     "stable": v.stable})
        notes.append(line)
    notes.insert(0, f"Searched range {rng}; theta_min = {_fmt(an.theta_min, 6)}; tail point "
                 f"{_fmt(an.T_tail, 8) if an.T_tail is not None else 'not certified'}; "
                 f"scene orbit: {why_main}.")
    if an.sp_fine is not None:
        p = current_precision()
        notes.append(f"Precision: the roots of g are isolated and classified at the working precision ({p} bits); "
                     f"theta* (and the period 2 theta*), the initial point x(0), the multipliers, the stability margin "
                     f"and the orbit's quantities are recomputed at {p + GUARD_BITS} bits, so their widths are those "
                     "of that computation.")
    extra["roots"] = rows
    witnesses = _witnesses(an) if hp[0] is Status.PROVED else {}
    paper: list = []
    formulas = formula_table()
    if main is not None:
        with working_precision(current_precision() + (GUARD_BITS if an.sp_fine is not None else 0)):
            fq, fnotes = orbit_quantities(model, an.sp_fine or sp, main)
        quantities.update(fq)
        notes.extend(fnotes)
        if model.paper:
            with phase("paper audit"):
                paper = audit_paper(model, sp, main)
    return Attempt(claims, quantities, paper, formulas, notes, widths_met, extra, width_quantities=("theta_star",),
                   witnesses=witnesses, phase_seconds=phase.seconds)


def _q(x: arb) -> str:
    """An exact ball (a dyadic point) as the exact rational text a checker reads back."""
    return exact_text(exact_fraction(x))


def _witnesses(an: Analysis) -> dict[str, Any]:
    """What rigor-gyro check re-verifies: the isolation of every root of g on the searched range (the
    pieces with their verdicts, theta_min, the tail point) and, per root, its classification."""
    pieces = []
    for pc in an.piece_list:
        item = {"lo": _q(pc.lo.lower()), "hi": _q(pc.hi.upper()), "kind": pc.status.value}
        if pc.reason.startswith(PHASE_REASON):
            item["kind"] = "phase_" + pc.status.value
        elif pc.reason.startswith("monotone"):
            item["by"] = "monotone"
        elif pc.reason == ENVELOPE_REASON:
            item["by"] = "envelope"
        if pc.parts:
            item["splits"] = [_q(s) for s in pc.parts]
        pieces.append(item)
    roots = []
    for v in an.roots:
        r: dict[str, Any] = {"kind": v.kind}
        if v.witness_t is not None:
            r["witness_t"] = _q(v.witness_t)
        if v.kind == "genuine":
            r["d1"] = _q(v.d1)
            r["right_start"] = _q(v.right_start)
            r["middle"] = [[_q(a.lower()), _q(b.upper())] for a, b in v.middle]
        roots.append(r)
    return {"half_period": {"theta_min": _q(an.theta_min), "T": _q(an.T_search), "covers_all": an.covers_all,
                            "function": an.isolated, "pieces": pieces, "roots": roots}}
