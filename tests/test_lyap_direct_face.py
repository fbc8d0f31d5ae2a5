"""The direct test's minimiser on a face |x2| = x2* (kinds/lyapunov/direct_face.py) and the direct radius over
mu (direct_mu.piece_upper): every certified bound against mpmath's values of A/|B| (MpGimbal's Psi
coefficients, an independent formula), sampled; the claims' brackets to 1e-9 relative (issue 40)."""
from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import certainly_positive, working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.subdivision import certify_positive_on_box
from rigor_gyro.core.outcome import Status
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, MpGimbal
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.direct_face import face_margin, face_min_lower, face_polish, face_series
from rigor_gyro.kinds.lyapunov.direct_mu import piece_upper
from rigor_gyro.kinds.lyapunov.polar_forms import DIRECT_DOMAIN, symmetric_in_x2

from tests.forgery import certificate

DPS = 40


def _g(mu: str | None = None):
    return gimbal_from_parameters(dict(AGAFONOV2013, **({"mu": mu} if mu else {})))[0]


def _mp_F(mg, u, s, mu=None):
    """A/|B| and A - R|B| parts at x2 = u x2*, t = pi s, in mpmath (the Psi coefficients of approx)."""
    (c10, c11, c13), (c20, c21, c23) = mg.psi_true(mg.xs * u, mu)
    c, sn = mpmath.cos(mpmath.pi * s), mpmath.sin(mpmath.pi * s)
    A = c10 * c * c + c20 * sn * sn
    B = c11 * c ** 3 + c13 * sn * c * c + c21 * c * sn * sn + c23 * sn ** 3
    return A, B


def _mp_face_min(mu: str | None = None, face: int = 1, s0: float = 0.5):
    """mpmath's minimum of A/|B| over s on the face (a root of the derivative near s0) and where it is."""
    with mpmath.workdps(DPS):
        mg = MpGimbal(dict(AGAFONOV2013, **({"mu": mu} if mu else {})))
        mu_v = None if mu is None else mpmath.mpf(Fraction(mu).numerator) / Fraction(mu).denominator

        def F(s):
            A, B = _mp_F(mg, face, s, mu_v)
            return A / abs(B)
        s = mpmath.findroot(lambda x: mpmath.diff(F, x), mpmath.mpf(s0))
        return F(s), s



def _mpf(x: arb):
    """An exact point ball as an mpmath number (40 digits: far below the margins tested)."""
    return mpmath.mpf(x.mid().str(40, radius=False))


def _mq(q: Fraction):
    return mpmath.mpf(q.numerator) / q.denominator


def test_face_series_encloses_mpmath_value_and_derivatives_over_an_interval():
    g, mg = _g(), MpGimbal(AGAFONOV2013)
    with working_precision(64):
        S = arb(fmpq(2, 5)).union(arb(fmpq(3, 5)))
        F, F1, F2 = face_series(g, 1, S)
        with mpmath.workdps(DPS):
            for k in range(11):
                s = mpmath.mpf(2) / 5 + mpmath.mpf(k) / 50
                f = lambda x: (lambda A, B: A / abs(B))(*_mp_F(mg, 1, x))  # noqa: E731
                for ball, d in ((F, 0), (F1, 1), (F2, 2)):
                    v = mpmath.diff(f, s, d)
                    assert float(ball.lower()) - 1e-12 * abs(v) <= v <= float(ball.upper()) + 1e-12 * abs(v), (k, d)


def test_face_min_lower_is_below_and_within_1e_13_of_mpmath_minimum_and_below_every_sample():
    g = _g()
    Fmin, smin = _mp_face_min()
    with working_precision(64):
        for face in (1, -1):
            low = face_min_lower(g, face, Fraction(31, 64), Fraction(33, 64))
            assert low is not None
            with mpmath.workdps(DPS):
                assert _mpf(low.lower()) <= Fmin
                assert (Fmin - _mpf(low.lower())) / Fmin < 1e-13
        # an interval without the critical point: the minimum at its end, every sample above the bound
        low = face_min_lower(g, 1, Fraction(1, 4), Fraction(17, 64))
        assert low is not None
        if low is not None:
            mg = MpGimbal(AGAFONOV2013)
            with mpmath.workdps(DPS):
                for k in range(17):
                    A, B = _mp_F(mg, 1, mpmath.mpf(1) / 4 + mpmath.mpf(k) / 1024)
                    assert A / abs(B) >= _mpf(low.lower())


@pytest.mark.parametrize("box", [((Fraction(15, 16), Fraction(1)), (Fraction(15, 32), Fraction(1, 2))),
                                 ((Fraction(7, 8), Fraction(15, 16)), (Fraction(1, 2), Fraction(17, 32))),
                                 ((Fraction(-1), Fraction(-63, 64)), (Fraction(63, 128), Fraction(1, 2)))])
def test_face_margin_lower_end_is_below_mpmath_samples_of_a_minus_r_abs_b(box):
    g, mg = _g(), MpGimbal(AGAFONOV2013)
    Fmin, _ = _mp_face_min()
    R = Fraction(str(mpmath.nstr(Fmin * (1 - mpmath.mpf("1e-11")), 25)))
    with working_precision(64):
        f = face_margin(g, arb(fmpq(R.numerator, R.denominator)))
        b = Box.of({"u": box[0], "s": box[1]})
        v = f({k: b.ball(k) for k in b.names})
        lo = _mpf(v.lower())
        with mpmath.workdps(DPS):
            for i in range(6):
                for j in range(6):
                    u = _mq(box[0][0]) + (_mq(box[0][1]) - _mq(box[0][0])) * i / 5
                    s = _mq(box[1][0]) + (_mq(box[1][1]) - _mq(box[1][0])) * j / 5
                    A, B = _mp_F(mg, u, s)
                    assert A - mpmath.mpf(R.numerator) / R.denominator * abs(B) >= lo, (i, j)


@pytest.mark.parametrize("u_box, s_box", [
    ((Fraction(7, 8), Fraction(1)), (Fraction(1, 4), Fraction(17, 64))),
    ((Fraction(7, 8), Fraction(15, 16)), (Fraction(1, 4), Fraction(17, 64))),
    ((Fraction(-1), Fraction(-7, 8)), (Fraction(1, 4), Fraction(17, 64))),
    # dF/du < 0 on the box itself, > 0 between it and the face
    ((Fraction(7, 8), Fraction(113, 128)), (Fraction(7, 32), Fraction(29, 128)))])
def test_face_margin_where_a_over_b_grows_towards_the_face_stays_below_mpmath_samples(u_box, s_box):
    """x2* = 1.3, s near 1/4: there A/|B| is smaller inside than on the face u = 1, so the face's minimum is no
    bound for the box; R between the box's sampled minimum and the face's: A - R |B| < 0 at a sample, and
    the box function's lower end must stay below it."""
    params = dict(AGAFONOV2013, x2_star="1.3")
    g, mg = gimbal_from_parameters(params)[0], MpGimbal(params)
    with mpmath.workdps(DPS):
        grid = [(_mq(u_box[0]) + (_mq(u_box[1]) - _mq(u_box[0])) * i / 8, _mq(s_box[0]) + (_mq(s_box[1]) - _mq(s_box[0])) * j / 8)
                for i in range(9) for j in range(9)]
        vals = [(lambda A, B: (A, B))(*_mp_F(mg, u, s)) for u, s in grid]
        box_min = min(A / abs(B) for A, B in vals)
        face = 1 if u_box[1] > 0 else -1
        face_min = min(A / abs(B) for A, B in (_mp_F(mg, face, _mq(s_box[0]) + (_mq(s_box[1]) - _mq(s_box[0])) * j / 64)
                                               for j in range(65)))
        assert box_min < face_min
        R = Fraction(mpmath.nstr((box_min + face_min) / 2, 20))
        worst = min(A - _mq(R) * abs(B) for A, B in vals)
        assert worst < 0
    with working_precision(64):
        b = Box.of({"u": u_box, "s": s_box})
        v = face_margin(g, arb(fmpq(R.numerator, R.denominator)))({k: b.ball(k) for k in b.names})
    with mpmath.workdps(DPS):
        assert _mpf(v.lower()) <= worst


def test_the_face_argument_decides_the_minimiser_s_box_below_the_infimum_and_never_above_it():
    """At R 1e-11 below mpmath's infimum the box around the minimiser is decided at once; at R 1e-10 above
    it no box function may certify the whole domain (that would be a radius above the supremum)."""
    g = _g()
    Fmin, _ = _mp_face_min()
    whole = Box.of(DIRECT_DOMAIN)
    with working_precision(64):
        for rel, proved in (("-1e-11", True), ("1e-10", False)):
            R = Fraction(str(mpmath.nstr(Fmin * (1 + mpmath.mpf(rel)), 25)))
            f = face_margin(g, arb(fmpq(R.numerator, R.denominator)))
            b = Box.of({"u": (Fraction(63, 64), Fraction(1)), "s": (Fraction(63, 128), Fraction(1, 2))})
            assert certainly_positive(f({k: b.ball(k) for k in b.names})) is proved
            cert = certify_positive_on_box(symmetric_in_x2(g, f), whole, max_pieces=1500)
            assert (cert.status is Status.PROVED) is proved, cert.status


def test_face_polish_reaches_mpmath_minimiser():
    g = _g()
    Fmin, smin = _mp_face_min()
    with working_precision(64):
        v, s = face_polish(g, 1, 0.4999)
    assert abs(v - float(Fmin)) <= 1e-15 * float(Fmin)
    assert abs(float(s) - float(smin)) < 1e-7


def test_piece_upper_from_a_polished_point_bounds_mpmath_radius_at_every_sampled_mu_of_a_ball():
    """A point polished on the face at some mu of the ball (the piece bounds of best_mu_direct) bounds A/|B| there."""
    g = _g()
    with mpmath.workdps(DPS):
        mg = MpGimbal(AGAFONOV2013)
    for lo, hi, at in (("0.02318", "0.023182", None), ("0.0231", "0.0233", None), ("0.020", "0.021", None),
                       ("0.02317958", "0.02318358", "0.02318058")):
        a, b = Fraction(lo), Fraction(hi)
        c = (a + b) / 2 if at is None else Fraction(at)
        with working_precision(64):
            Mu = arb(fmpq(a.numerator, a.denominator)).union(arb(fmpq(b.numerator, b.denominator)))
            _, sp = face_polish(g.with_mu(fmpq(c.numerator, c.denominator)), 1, 0.332)
            up = piece_upper(g, Mu, [(fmpq(1), fmpq(sp.numerator, sp.denominator))])
        assert up.is_finite()
        with mpmath.workdps(DPS):
            for k in range(17):
                mu = _mq(a) + _mq(b - a) * k / 16
                A, B = _mp_F(mg, 1, mpmath.mpf(sp.numerator) / sp.denominator, mu)
                assert A / abs(B) <= _mpf(up.upper()), (lo, k)


def test_direct_radius_and_its_supremum_over_mu_bracket_mpmath_to_1e_9():
    """vdot_direct's [R_direct, R_direct_upper] holds mpmath's infimum (on the face) with relative gap <= 1e-9;
    best_mu_direct's [R_direct_max, R_direct_sup_upper_bound] holds mpmath's maximum over mu of that infimum,
    gap <= 1e-9; the checker confirms both."""
    data = certificate("agafonov2013", {}, claims_only=["vdot_direct", "best_mu_direct"])
    claims = {c["id"]: c for c in data["claims"]}
    assert claims["vdot_direct"]["status"] == claims["best_mu_direct"]["status"] == "proved"
    q = data["quantities"]
    lo, hi = Fraction(claims["vdot_direct"]["details"]["R_direct"]), Fraction(claims["vdot_direct"]["details"]["R_direct_upper"])
    Fmin, _ = _mp_face_min()
    with mpmath.workdps(DPS):
        assert _mq(lo) < Fmin < _mq(hi)
    assert (hi - lo) / lo <= Fraction(1, 10 ** 9)
    assert Fraction(q["R_direct_relative_gap"]["hi"]) <= Fraction(1, 10 ** 9)
    with mpmath.workdps(DPS):
        def R_of(mu):
            return _mp_face_min(mpmath.nstr(mu, 35), 1, 0.332)[0]
        # golden-section search for the maximum over mu (unimodal near the optimum: float scans)
        a, b = mpmath.mpf("0.0230"), mpmath.mpf("0.0234")
        r = (mpmath.sqrt(5) - 1) / 2
        c, d = b - r * (b - a), a + r * (b - a)
        fc, fd = R_of(c), R_of(d)
        while b - a > mpmath.mpf("1e-12"):
            if fc > fd:
                b, d, fd = d, c, fc
                c = b - r * (b - a)
                fc = R_of(c)
            else:
                a, c, fc = c, d, fd
                d = a + r * (b - a)
                fd = R_of(d)
        Rmax = max(fc, fd)
    d = claims["best_mu_direct"]["details"]
    Rm, U = Fraction(d["R_direct_max"]), Fraction(q["R_direct_sup_upper_bound"]["hi"])
    with mpmath.workdps(DPS):
        assert _mq(Rm) <= Rmax <= _mq(U), (Rm, Rmax, U)
    assert (U - Rm) / Rm <= Fraction(1, 10 ** 9)
    assert check_certificate(data).ok


def test_the_face_minimum_memo_gives_each_s_range_and_precision_its_own_value():
    """face_margin asks face_min_lower through a memo on the gimbal: a repeated s-range gets the very ball, another
    s-range or precision its own (a key without the range would hand one range's minimum to another)."""
    from rigor_gyro.kinds.lyapunov.direct_face import _face_min_lower_memo
    g = _g()
    ranges = [(Fraction(1, 4), Fraction(5, 16)), (Fraction(5, 16), Fraction(3, 8)), (Fraction(1, 4), Fraction(5, 16))]
    for prec in (64, 128, 64):
        with working_precision(prec):
            for lo, hi in ranges:
                got, want = _face_min_lower_memo(g, 1, lo, hi), face_min_lower(_g(), 1, lo, hi)
                assert (got is None) == (want is None)
                if got is not None:
                    assert got.mid() == want.mid() and got.rad() == want.rad()
    assert len(g._face_min_lower) == 4
