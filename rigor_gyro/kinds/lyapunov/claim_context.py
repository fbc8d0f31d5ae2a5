"""What the claims of one attempt share: the model they run on (:class:`LyapunovModel`), the claim constructor,
number formats, exact decimals, and :class:`ClaimContext`, which computes each piece (m, M, the constants, R) once, when a claim first needs it.
Precision: the attempt's (the prover sets it). Fails when: never by itself; the pieces fail as their modules say."""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from ...core.balls import certainly_lt, certainly_positive, decimal_bounds, Quantity, stored_hull
from ...core.exact import Exact
from ...core.outcome import Claim, Status
from ...core.subdivision import certify_positive, enclose_max
from .model import Gimbal, mean_value_enclosure
from .closed_forms import closed_form_constants
from .vdot_tests import certify_psi_test, certify_vdot_nonpositive
from .declarations import CLAIMS

@dataclass
class LyapunovModel:
    gimbal: Gimbal
    params: dict[str, Exact]
    text: dict[str, str]
    rel_width: fmpq
    R_option: fmpq | None
    max_pieces: int
    paper: dict
    #: the relative gap the natural_sublevel claim aims at ("" = not asked by option)
    natural_gap: str = ""
    #: option initial_point (x1, x2, x3) exactly, or None; option initial_point_time (model time allowed)
    initial_point: tuple | None = None
    initial_time: Fraction = Fraction(1)
    #: options of attraction_paving: grid size, half-width in units of the slice's extents, model time
    paving: tuple = (8, Fraction(3), Fraction(3))


def make_claim(cid: str, status: Status, reason: str, counterexample: dict | None = None, decides: arb | None = None,
               **details) -> Claim:
    return Claim(cid, CLAIMS[cid], status, reason, details=details, counterexample=counterexample, decides=decides)


def fmt(x: arb, digits: int = 12) -> str:
    lo, hi = decimal_bounds(x, digits)
    return lo if lo == hi else f"[{lo}, {hi}]"


def exact_ball(x: fmpq) -> arb:
    return arb(x)


def to_fmpq(fr: Fraction) -> fmpq:
    return fmpq(fr.numerator, fr.denominator)


def relative_gap(upper: Fraction, lower: Fraction) -> arb:
    """(upper - lower) / lower of two exact decimals, computed exactly and made a ball once (one rounding:
    about 1 bit lost at any precision; the difference of the two balls lost log2(lower / (upper - lower)) bits,
    23-26 for the gaps of 1e-7)."""
    return exact_ball(to_fmpq((upper - lower) / lower))


def searched(x: fmpq | Fraction) -> Quantity:
    """A decimal chosen by a search (mu_best, R_max, R_direct, ...): exact, shown and stored as that number
    (radius 0), while the ball it carries contains it at the current precision."""
    return Quantity.of_exact(Fraction(int(x.p), int(x.q)) if isinstance(x, fmpq) else Fraction(x))


class ClaimContext:
    """Everything one attempt computes, each piece only when a claim needs it."""

    def __init__(self, model: LyapunovModel, prec: int):
        self.m = model
        self.g = model.gimbal
        self.prec = prec
        self._memo: dict = {}
        #: per claim, the data rigor-gyro check re-evaluates (pieces, points; exact texts)
        self.witnesses: dict = {}

    def memo(self, key, fn):
        if key not in self._memo:
            self._memo[key] = fn()
        return self._memo[key]

    @property
    def xs(self) -> arb:
        return self.g.c.x2_star

    def tol(self, value: arb) -> arb:
        """The width a maximum is enclosed to: rel_width of it, and over a box (a gimbal with an extrema
        cache) also 4 radii of the value at a point, which the box's own width gives and no subdivision of
        x2 removes (the point prover's tolerance is unchanged). The floor 2^-prec (for a value 0) is relative,
        2^-prec |value|, where 0 < |value| < 1 certainly: an absolute floor kept a = 1e-300's m and M from their
        relative width until 2^-prec < 1e-315 (2048 bits; issue 41)."""
        mag = abs(value)
        floor = arb(2) ** (-self.prec)
        if certainly_lt(mag, 1) and certainly_positive(mag):
            floor = floor * mag.lower()
        t = mag * exact_ball(self.m.rel_width) / 4 + floor
        if getattr(self.g, "extrema_cache", None) is not None:
            t = t + 4 * value.rad()
        return t

    # ------------------------------------------------------------------ constants
    def shared(self, name: str, run):
        """``run()`` memoised in this attempt, and across attempts in the gimbal's ``extrema_cache`` when it has
        one (a box's gimbal: m and M depend only on the parameters its ``extrema_key`` names, so every box with
        the same intervals of those gets the very same enclosure; the point prover has no such cache)."""
        cache = getattr(self.g, "extrema_cache", None)
        if cache is None:
            return self.memo(name, run)
        key = (name, self.g.extrema_key, self.prec, self.m.max_pieces, self.m.rel_width.p, self.m.rel_width.q)
        if key not in cache:
            if len(cache) >= 512:
                cache.clear()
            cache[key] = run()
        return self.memo(name, lambda: cache[key])

    def m_max(self):
        def run():
            # where cos f' / D > 0 on the whole range (certified), |.| is itself: use the mean-value form
            fn = self.g.m_quotient
            signed = mean_value_enclosure(self.g.m_signed)
            if certify_positive(signed, 0, self.xs, max_pieces=200).status is Status.PROVED:
                fn = signed
            return enclose_max(fn, 0, self.xs, abs_tol=self.tol(fn(arb(0))), max_pieces=self.m.max_pieces)
        return self.shared("m", run)

    def M_max(self):
        def run():
            v = self.g.q(self.xs)
            return enclose_max(self.g.q, 0, self.xs, abs_tol=self.tol(v), max_pieces=self.m.max_pieces)
        return self.shared("M", run)

    def constants(self) -> dict[str, arb]:
        def run():
            # derived from the hulls of m's and M's stored decimal intervals: a checker's own m, M (confirmed
            # inside those intervals) then give p, k_min, ... inside the stored ones (no decimal slack escapes)
            m, M = self.m_max().ball, self.M_max().ball
            k = closed_form_constants(self.g, stored_hull(m), stored_hull(M))
            k["m"], k["M"] = m, M
            return k
        return self.memo("constants", run)

    def R_used(self) -> tuple[arb, str]:
        if self.m.R_option is not None:
            return exact_ball(self.m.R_option), f"R = {self.m.R_option} (scene option)"
        R = self.constants()["R"]
        return R, "R = min(R1, R2) from (13), (14)"


# ------------------------------------------------------------------------------------ Vdot

def vdot_claim(ctx: ClaimContext, R: arb, how: str, cid: str = "vdot_nonpositive") -> tuple[Claim, dict]:
    """``vdot_nonpositive`` (Vdot <= 0: the Psi test, else the direct test; refuted only where Vdot > 0) or
    ``psi_test`` (Psi1, Psi2 > 0: refuted where one is <= 0, or where Vdot > 0)."""
    record: dict = {}
    fn = certify_vdot_nonpositive if cid == "vdot_nonpositive" else certify_psi_test
    v = fn(ctx.g, ctx.xs, R, how, ctx.m.max_pieces, record=record)
    info = {"pieces": v.pieces, "record": record}      # the record: the checker's witness
    claim = make_claim(cid, v.status, v.reason, v.counterexample, **v.details)
    claim.decides = v.decides
    return claim, info



def unstate(quantities: dict, *names: str) -> None:
    """Drop the quantities an inconclusive claim had stored: the checker verifies them only from a proved claim's
    witnesses, and a certificate states nothing its checker cannot confirm."""
    for n in names:
        quantities.pop(n, None)
