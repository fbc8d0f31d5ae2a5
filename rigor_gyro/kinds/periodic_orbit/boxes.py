"""Claims of the relay (periodic orbit) kind over a box of parameters, for :mod:`rigor_gyro.margins`.

:class:`BoxSpectrum` is the :class:`.flow.Spectrum` of a whole box: the parameters are balls containing
their intervals, the three roots of the nutation cubic (4) are enclosed for every member of the box by
one interval Newton proof each (real roots on the line, the complex pair in the plane:
:mod:`rigor_gyro.core.family_roots`; the midpoint's exact roots are only starting guesses), and the
projectors, the forcing and the system matrix are the same ball formulas on the parameter balls. The
claims of :mod:`.claims` then run unchanged on it: every enclosure they compute (g and g' on a theta
piece, the tail bound, the sign of beta on a time piece, the Jacobian of the half-period map, its
eigenvalues by Rump's method, which encloses the eigenvalues of every matrix in the ball matrix)
contains the value for every parameter in the box, so a root piece with a certified sign change and a
derivative excluding 0 holds exactly one root of g for every member, a piece with |g| > 0 none.

Guarantee: ``proved`` means the claim holds for every parameter value in the box (for example
``stable``: for every member, every genuine orbit found ... as the claim states, with the box's
enclosures); ``refuted`` means it fails for every member; ``undecided`` otherwise. The algebraic moment
identities e1^T M^j e = 0 (j <= 3) hold for all parameters; they are checked exactly at the box's
midpoint (a bug check, not a proof step).

The amplitude parameters S, p and K (:data:`.flow.AMPLITUDE_PARAMETERS`) are not taken as balls: the
claims do not depend on them (homogeneity in S; p and K enter only the amplitude K p S, an exact
similarity that :func:`.flow.amplitude_similarity` checks in rationals), so the box is decided at their
lower ends, and the paving never splits them.

Precision: the caller's (the paving fixes it).

Near theta = 0, g = O(theta^5) is the small difference of spectral terms of size O(theta) whose
projectors depend on the parameters independently, so on a box the spectral form loses about a factor
10^6 there; :class:`BoxSpectrum` therefore carries a :class:`.flow.NearZeroSeries` (g's power series
from matrix powers, certified tail) that :func:`.flow.g_coeffs` uses up to its reach.

Over a box a root of g is an interval (its value for each member). The root search therefore splits a
piece where g has a certain sign for every member (:func:`.g_roots._split_point`), so that a root's
whole spread stays in one piece, and a root whose beta'(0) has no certain sign over the box is still
proved spurious by a point where beta is certainly negative (:func:`.claims.classify_root`).

The half-period Jacobian whose eigenvalues decide ``stable`` is the direct enclosure intersected with
the centred (mean-value) form of :mod:`.jacobian_box` (:meth:`BoxSpectrum.jacobian`; the direct one
alone was 12 times wider than J varies over n in 50 +- 0.01), and its eigenvalues are enclosed both by
Rump's method on that ball matrix and on the centred form in the centre's eigenvector coordinates
(:meth:`BoxSpectrum.multipliers`), whichever is narrower: J's entries move with n far more than its
eigenvalues do, and in eigenvector coordinates the motion is mostly off the diagonal.

Known limits (measured at 128 bits on the printed Roitenberg parameters): ``stable`` decides a box of
n in 50 +- 0.5 (relative width 0.02; with the direct Jacobian alone 50 +- 0.01, with the centred
Jacobian but Rump's method on it 50 +- 0.156); at 50 +- 0.625 the eigenvector-coordinate ball is too
wide to isolate the four eigenvalues. (Tried and not kept: the characteristic polynomial in centred
form, first order, its constant term from Liouville's det J: 50 +- 0.2.) On the paving of n in
[40, 60], ``stable`` needs 22 sub-boxes (512 with the direct Jacobian alone), ``orbit_genuine`` 8.
``half_period`` (every root of g isolated,
simple) can never be decided on a box holding a parameter where two roots merge: near n = 50.7 the
two spurious roots beside the pole of tanh at theta = 5 pi / omega = 0.640 meet and vanish (a fold),
so there the paving keeps an undecided sliver whatever the resolution (never refuted: the claim
fails to be provable there, not to hold). ``orbit_genuine`` and ``stable`` do not need every root
classified and hold across the fold.

A box that varies A, H or tau is first decided on its similar box of (B, sigma, n) at the midpoint's A, H, tau
(:mod:`.similarity`: the orbit's existence, genuineness and multipliers depend only on H^2 tau^2/(A B),
n tau/A and sigma/tau; checked by an exact conjugacy), bisected adaptively along the direction theta* moves
most while theta* is proved on the piece (:mod:`.similar_cover`, at most 40 continuations), and
``stable`` also by a Gershgorin bound of the spectral radius where Rump's method does not isolate the
multipliers (:mod:`.norm_stability`, :mod:`.normed_orbit`). Measured at 128 bits, all six at once (evaluate_box,
one box, 2026-12-06, helper H5): ``orbit_genuine`` +-0.5 % proved in 10.8 s (was undecided; +-0.25 % before),
``stable`` +-0.2 % in 21.5 s and +-0.15 % in 10.8 s (was +-0.1 %); ``stable`` +-0.25 % undecided (54 s), +-0.5 %
undecided (103 s even with 64 leaves of the similar box): the centred Jacobian over a box is still far wider
than J moves (theta*'s gradient over B' +-0.75 % encloses [-0.95, 0.95] where it is 0.4). With the adaptive
cover (2026-12-06, helper H5, user CPU on a loaded machine): ``stable`` and ``orbit_genuine`` at +-0.5 % both
proved in one evaluate_box, 59 s (the similar box B' +-3 %, sigma' +-1 %, n' +-1 %: 16 pieces, B' halved three
times then sigma', 31 continuations). One parameter, ``stable``, one evaluate_box (before -> after the adaptive
cover, user CPU): H +-4 % proved 9.3 -> 9.5 s, H +-6 % undecided 7.4 s -> proved 15.7 s (H +-10 % undecided, 3.4 s:
the slope ratio is hopeless), A +-6 % proved 25.6 -> 25.5 s, A +-10 % undecided 8.5 s -> proved 102 s; tau +-10 %
undecided (0.6 s: theta* not proved on its similar box B' +-20 %, sigma' +-10 %, n' +-10 %, not halved). A box that varies only B, sigma, n has no similar box
and is unchanged.

A ``[plant]`` model (:class:`.plant_model.PlantModel`) is decided over a box by :mod:`.plant_box` (naive ball
forms of its matrices over the box: ``orbit_genuine`` and ``stable`` over boxes of relative width ~1e-6 in A and
H, ~1e-8 in all six of the Roitenberg plant, the same verdicts as this path there).

``orbit_genuine`` and ``stable`` are first tried by continuing the centre's orbit over the whole box
(:mod:`.box_orbit`, :mod:`.continuation`, with the band Newton step of :mod:`.subbox_union` and the cell
fallback of :mod:`.cellwise`). Measured at 128 bits (one box, no paving split, evaluate_box; 2026-12-06): both
claims proved at +-1 % in each of A, B, H, tau, sigma, n (0.1-1 s user each), and at +-50 % in n (3.2 s),
+-11 % in sigma (3.6 s), +-5 % in A and B (4.8 s, 4.5 s), +-8.5 % in tau (3.7 s; the cubic's roots by the
parametric Newton of :func:`rigor_gyro.core.implicit_roots.polynomial_root_over_box` where the family Newton
fails: it did from +-5 %), +-2.75 % in H (6.7 s; the monotone stretches of beta near the switchings extended
piece by piece, :func:`.continuation._extend`: +-2.5 % before); not at sigma +-12 % (no genuine root
certified), A, B +-6 %, H +-3 % and tau +-9 % (the sign of beta' near the switchings not certified over the box,
nor beta > 0 in the middle on the cells). All six at once:
+-0.1 % both (2.3 s), +-0.25 % orbit_genuine only (8 s), +-0.5 % neither (2 s): over a six-parameter box the
derivative enclosures of the spectral forms (:mod:`.parametric`) are far wider than the quantities move (at
+-0.1 %, dJ/dB over the box has radius 154 where it is -3.0 at the centre; on B alone 1.88).

Fails when: the domain fails somewhere in the box (every parameter > 0): ParameterError. A box where
the cubic's roots cannot be separated, or -1/sigma may be one of them, is undecided (the paving splits it).
"""
from __future__ import annotations

import dataclasses

from flint import acb, arb, arb_mat

from ...core.balls import ball, certainly_nonzero, certainly_positive
from ...core.boxes import Box
from ...core.errors import ParameterError
from ...core.family_roots import newton_family_root, newton_family_root_complex, polynomial_family
from ...core.polyroots import isolate_polynomial
from .. import box_outcomes, require_box_claims
from .claims import CLAIMS, attempt
from .box_orbit import continued_outcomes
from .plant_box import PLANT_BOX_CLAIMS, evaluate_plant_box, validate_plant_box
from .plant_claims import statements as plant_statements
from .plant_model import PlantModel
from .jacobian_box import centred_jacobian, centred_terms, eigen_coordinate_multipliers
from .flow import AMPLITUDE_PARAMETERS, PARAMETER_NAMES, amplitude_similarity, DegenerateSpectrum, NearZeroSeries, RelayParams, Spectrum, nutation_cubic

__all__ = ["BOX_CLAIMS", "BOX_PARAMETERS", "BoxSpectrum", "box_claims", "validate_box", "evaluate_box"]

BOX_CLAIMS = {c: CLAIMS[c] for c in ("half_period", "orbit_genuine", "stable")}
BOX_PARAMETERS = PARAMETER_NAMES
#: the box claims do not depend on S, p, K (homogeneity and :func:`~.flow.amplitude_similarity`, see
#: evaluate_box): the paving never splits them
UNSPLIT_PARAMETERS = AMPLITUDE_PARAMETERS


class BoxSpectrum(Spectrum):
    """Eigenvalues and projectors of M for every parameter in a box (see the module docstring)."""

    def __init__(self, Pb: RelayParams, Pmid: RelayParams):
        self.P = Pb
        tau, sigma, A, n = Pb.tau, Pb.sigma, Pb.A, Pb.n
        q2 = Pb.H * Pb.H / (Pb.A * Pb.B)
        coeffs = [q2 / tau, q2 + n / (tau * A), 1 / tau, arb(1)]
        family = polynomial_family(coeffs)
        guesses = isolate_polynomial(nutation_cubic(Pmid))
        if not guesses.verified or not guesses.squarefree:
            raise DegenerateSpectrum("the midpoint's cubic (4) is not isolated")
        real = [newton_family_root(family, g) for g in guesses.real]
        upper = [newton_family_root_complex(coeffs, z) for z in guesses.nonreal if certainly_positive(z.imag)]
        if any(r is None for r in real + upper) or len(real) + 2 * len(upper) != 3:
            raise DegenerateSpectrum("the cubic's roots were not separated on this box")
        if not all(certainly_positive(z.imag) for z in upper):
            raise DegenerateSpectrum("a complex root's imaginary part may vanish on this box")
        for i in range(len(real)):
            for j in range(i + 1, len(real)):
                if real[i].overlaps(real[j]):
                    raise DegenerateSpectrum("two real roots of the cubic overlap on this box")
        nu = -1 / sigma
        if not certainly_nonzero(family(nu)[0]):
            raise DegenerateSpectrum("-1/sigma may be a root of the cubic (4) on this box")
        S = ball(Pb.S)
        modes = [self._cubic_mode(acb(lam), 1, "real root of (4)") for lam in real]
        modes += [self._cubic_mode(z, 2, "complex pair of (4)") for z in upper]
        modes.append(self._sigma_mode(nu))
        self.modes = modes
        P = Pb
        l0 = [arb(1), P.B * P.n / (P.H * P.H), -P.A / P.H, -P.tau * P.K / P.H, -P.sigma * P.p * P.K / P.H]
        self.P0 = arb_mat([l0] + [[arb(0)] * 5 for _ in range(4)])
        self.p0e = [l0[4] / P.sigma * S if r == 0 else arb(0) for r in range(5)]
        self.e = [arb(0), arb(0), arb(0), arb(0), 1 / P.sigma]
        z = arb(0)
        self.M = arb_mat([[z, 1, z, z, z],
                          [z, z, -P.H / P.B, z, z],
                          [z, P.H / P.A, z, P.K / P.A, z],
                          [z, z, -P.n / (P.K * P.tau), -1 / P.tau, P.p / P.tau],
                          [z, z, z, z, -1 / P.sigma]])
        # near theta = 0 the spectral terms cancel on a box: g from its power series there
        self.near_zero = NearZeroSeries(self.M, self.e, S)
        self._centred = None        # (theta, centred_terms at theta): see _centred_terms

    def jacobian(self, theta: arb, x0) -> arb_mat:
        """The half-period Jacobian for every parameter in the box and every theta in the ball: the
        direct enclosure intersected entrywise with the centred form of :mod:`.jacobian_box` (both
        contain J for every member; the centred one is about as wide as J actually varies, the
        direct one about 12 times wider on a box of n in 50 +- 0.01). Disjoint entries would mean one
        enclosure is wrong: AssertionError."""
        direct = super().jacobian(theta, x0)
        parts = self._centred_terms(theta)
        centred = centred_jacobian(self.P, theta, parts) if parts is not None else None
        if centred is None:
            return direct
        out = arb_mat(4, 4)
        for i in range(4):
            for j in range(4):
                a, b = direct[i, j], centred[i, j]
                if not a.overlaps(b):
                    raise AssertionError(f"the Jacobian's direct and centred enclosures are disjoint at ({i}, {j}): {a}, {b}: a bug")
                out[i, j] = a.intersection(b) if a.is_finite() else b
        return out

    def _centred_terms(self, theta: arb):
        """:func:`.jacobian_box.centred_terms` at this box and ``theta``, computed once for the Jacobian
        and the multipliers of the same orbit (the same ball object)."""
        if self._centred is None or self._centred[0] is not theta:
            self._centred = (theta, centred_terms(self.P, theta))
        return self._centred[1]

    def multipliers(self, J: arb_mat, theta: arb) -> list[acb]:
        """Enclosures of J's eigenvalues for every member: Rump's method on the ball matrix J and on
        the centred form in the centre's eigenvector coordinates
        (:func:`.jacobian_box.eigen_coordinate_multipliers`), the narrower of the two (a float compares
        the widths; both are enclosures). ``theta`` must be the ball J was computed at (the second
        enclosure is rebuilt from it and the box, not from J). ValueError if neither isolates the four."""
        candidates = []
        try:
            candidates.append(super().multipliers(J, theta))
        except ValueError:
            pass
        parts = self._centred_terms(theta)
        other = eigen_coordinate_multipliers(self.P, theta, parts) if parts is not None else None
        if other is not None:
            candidates.append(other)
        if not candidates:
            raise ValueError("neither Rump's method on the Jacobian nor on its centred form in eigenvector "
                             "coordinates isolated the four multipliers on this box")
        return min(candidates, key=lambda c: max(float(z.real.rad()) + float(z.imag.rad()) for z in c))

    def _sigma_mode(self, nu: arb):
        P = self.P
        rho2 = -(P.B / P.H) * nu * nu
        rho3 = (-(P.A * P.B / P.H) * nu ** 3 - P.H * nu) / P.K
        den = (P.n / (P.K * P.tau)) * rho2 + (nu + 1 / P.tau) * rho3
        if not certainly_nonzero(den):
            raise DegenerateSpectrum("the -1/sigma eigenvector may be degenerate on this box")
        r0 = (P.p / P.tau) / den
        r = [acb(x) for x in (r0, r0 * nu, r0 * rho2, r0 * rho3, arb(1))]
        l = [acb(0)] * 4 + [acb(1)]
        return self._mode(acb(nu), 1, r, l, "-1/sigma (current I)")


def box_claims(model) -> dict[str, str]:
    """The claims decided over a box for this model: a ``[plant]`` model's are those of :mod:`.plant_box`."""
    if isinstance(model, PlantModel):
        st = plant_statements(model)
        return {c: st[c] for c in PLANT_BOX_CLAIMS}
    return dict(BOX_CLAIMS)


def validate_box(model, box: Box) -> None:
    if isinstance(model, PlantModel):
        validate_plant_box(model, box)
        return
    bad = [n for n in box.names if n not in BOX_PARAMETERS]
    if bad:
        raise ParameterError(f"parameter {bad[0]!r}: not a parameter of kind 'periodic_orbit'")
    for k in box.names:
        lo, _ = box.interval(k)
        if not lo > 0:
            raise ParameterError(f"parameter {k!r}: need {k} > 0 on the whole box (its lower end is {lo})")


def evaluate_box(model, box: Box, claims: list[str]) -> dict[str, tuple[str, str]]:
    """{claim: (status, reason)} over the box (see the module docstring; a ``[plant]`` model: :mod:`.plant_box`)."""
    if isinstance(model, PlantModel):
        require_box_claims(claims, box_claims(model))
        return evaluate_plant_box(model, box, claims)
    require_box_claims(claims, BOX_CLAIMS)
    # S enters homogeneously: x(t; S) = S x(t; 1) (linear plant, relay amplitude S > 0), so the roots of
    # g = S g_1, the signs of beta and the multipliers (the half-period map is homogeneous of degree 1,
    # its Jacobian of degree 0) are the same for every S > 0: the box claims are decided at one S (the
    # box's lower end). Taking S as a ball instead would widen every spectral term by the same factor
    # independently and lose the cancellation that makes g small near 0. The gains p and K enter only
    # through the amplitude K p S (flow.amplitude_similarity, checked exactly at the box's lower ends),
    # so they too are taken at the box's lower ends.
    fixed = {k: _q(box.interval(k)[0]) for k in AMPLITUDE_PARAMETERS if k in box.names}
    Pb = RelayParams(**{k: ball(fixed[k]) if k in fixed else box.ball(k) if k in box.names else
                        ball(getattr(model.params, k)) for k in PARAMETER_NAMES})
    if fixed and not amplitude_similarity(dataclasses.replace(model.params, **fixed)):
        raise AssertionError("the relay model no longer enters p, K only through the amplitude K p S")
    mid = box.midpoint()
    Pmid = dataclasses.replace(model.params, **{k: _q(v) for k, v in mid.items()})
    boxed = dataclasses.replace(model, params=Pmid, paper={})
    out = continued_outcomes(dataclasses.replace(boxed, params=dataclasses.replace(Pmid, **fixed)), box, claims)
    rest = [c for c in claims if c not in out]
    if rest:
        a = attempt(boxed, rest, 0, spectrum=lambda: BoxSpectrum(Pb, Pmid))
        out.update(box_outcomes(a, rest))
    out = {c: out[c] for c in claims}
    spread = [k for k in fixed if box.interval(k)[0] != box.interval(k)[1]]
    if spread:      # the statuses hold on the whole box; amplitudes quoted in the reasons (x(0)) do not
        tag = (f" [evaluated at the box's lower end of {', '.join(spread)}: the status holds for every value "
               "(the claims do not depend on them); amplitudes quoted here scale with K p S]")
        out = {k: (st, why + tag) for k, (st, why) in out.items()}
    return out


def _q(x):
    from flint import fmpq
    return fmpq(x.numerator, x.denominator)
