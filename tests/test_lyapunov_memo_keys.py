"""The memos of the Lyapunov model and its branch and bounds (issue 41): a memoised value is the very ball the
computation gives, at the precision it is asked at, for the ball it is asked for (the keys hold the whole ball,
the precision and, for the bounds over mu pieces, the piece)."""
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov import mu_claims as C
from rigor_gyro.kinds.lyapunov import direct_mu
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters


def _gimbal():
    return gimbal_from_parameters(AGAFONOV2013)[0]


def _same(a: arb, b: arb) -> bool:
    return a.mid() == b.mid() and a.rad() == b.rad() if a.is_finite() else not b.is_finite()


def test_the_same_ball_object_at_two_precisions_gets_each_precisions_value():
    """One ball object asked at 64 bits, then at 128: the second answer has 128-bit accuracy (the memo's key,
    and the key remembered for the last argument object, both hold the precision)."""
    g = _gimbal()
    x = arb(5) / 16                     # exact at every precision used here
    with working_precision(64):
        lo = g.psi_coefficients(x)[0][0]
        g.S(x)
    with working_precision(128):
        hi = g.psi_coefficients(x)[0][0]
        S = g.S(x)
        fresh = _gimbal().psi_coefficients(x)[0][0]
    assert hi.rad() < lo.rad() * arb(2) ** -40          # the 128-bit value, not the 64-bit one again
    assert _same(hi, fresh) and S.rad() < abs(S) * arb(2) ** -100


def test_a_memoised_ball_is_the_computed_one_for_each_argument():
    """Two balls with the same midpoint and different radii, and two midpoints: each gets its own value."""
    g = _gimbal()
    with working_precision(64):
        a, b, c = arb(1) / 4, arb(1) / 4 + arb(0, 2.0 ** -20), arb(1) / 5
        got = [g.phi(x) for x in (a, b, c, a, b)]
        want = [_gimbal().phi(x) for x in (a, b, c, a, b)]
    assert all(_same(x, y) for x, y in zip(got, want))


class _Forgets(dict):
    """A memo that keeps nothing (every value computed afresh)."""

    def get(self, key, default=None):
        return default

    def __setitem__(self, key, value):
        pass


def test_r_sup_upper_bound_with_and_without_its_memo():
    """The point bounds over mu pieces, remembered per (point, piece): the same pieces and bounds as computed
    afresh each time (a key without the piece would hand one piece's bound to another)."""
    g = _gimbal()
    xs = g.c.x2_star
    with working_precision(64):
        lo, hi = arb(fmpq(27, 2000)).lower(), arb(fmpq(61, 2000)).upper()     # exact ends
        target = arb("0.02401")
        U1, n1, cover1, pts1 = C.r_sup_upper_bound(g, xs, lo, hi, target, max_pieces=60)
        orig = C._bound_memo
        try:
            C._bound_memo = _Forgets
            U2, n2, cover2, pts2 = C.r_sup_upper_bound(g, xs, lo, hi, target, max_pieces=60)
        finally:
            C._bound_memo = orig
    assert n1 == n2 and _same(U1, U2) and len(cover1) == len(cover2) and n1 > 3
    assert all(_same(a, c) and _same(b, d) for (a, b), (c, d) in zip(cover1, cover2))


def test_direct_sup_upper_bound_with_and_without_its_memo(monkeypatch):
    """piece_upper's memo (a point's bound over a mu ball, kept across a piece's re-bounding): the same bound,
    pieces and points as without it."""
    g = _gimbal()
    with working_precision(64):
        lo, hi = arb(fmpq(27, 2000)).lower(), arb(fmpq(61, 2000)).upper()     # exact ends
        r1 = direct_mu.direct_sup_upper_bound(g, lo, hi, arb("1e-4"), max_pieces=14)
        real = direct_mu.piece_upper
        monkeypatch.setattr(direct_mu, "piece_upper", lambda g_, Mu, points, memo=None: real(g_, Mu, points))
        r2 = direct_mu.direct_sup_upper_bound(g, lo, hi, arb("1e-4"), max_pieces=14)
    assert _same(r1[0], r2[0]) and r1[1] == r2[1] and r1[3] == r2[3] and r1[4] == r2[4]
    assert all(_same(a, c) and _same(b, d) for (a, b), (c, d) in zip(r1[2], r2[2]))


def test_with_mu_shares_only_what_does_not_depend_on_mu():
    """Gimbals made by with_mu share the memo of the mu-free functions (f3, G, F, psi's x2 factors); every
    function of mu (S, phi, psi's coefficients) is the one a fresh gimbal at that mu computes."""
    g = _gimbal()
    mu2 = fmpq(23, 1000)
    with working_precision(64):
        xs = [arb(5) / 16, arb(1) / 4 + arb(0, 2.0 ** -20)]
        for x in xs:
            g.S(x), g.phi(x), g.psi_coefficients(x), g.f3(x), g.F(x)
        gm = g.with_mu(mu2)
        fresh = _gimbal().with_mu(mu2)
        for x in xs:
            for name in ("S", "phi", "f3", "F", "G"):
                assert _same(getattr(gm, name)(x), getattr(fresh, name)(x)), name
            for a, b in zip(gm.psi_coefficients(x), fresh.psi_coefficients(x)):
                assert all(_same(p, q) for p, q in zip(a, b))
        assert gm._shared is g._shared


def test_a_subclass_with_ball_parameters_shares_nothing_with_with_mu():
    """A ParamGimbal (parameters are balls over a box) memoises f3 over its own parameters; the plain Gimbal
    its with_mu makes must not read that memo."""
    from rigor_gyro.kinds.lyapunov.box_forms import ParamGimbal
    from rigor_gyro.kinds.lyapunov.model import ParameterBalls
    g = _gimbal()
    with working_precision(64):
        c = g.c
        wide = ParameterBalls(c.A0, c.B0, c.C0, c.H * arb(1, 0.01), c.k, c.a, c.mu, c.x2_star)
        pg = ParamGimbal(g, wide)
        x = arb(5) / 16
        boxed = pg.f3(x)
        plain = pg.with_mu(fmpq(23, 1000))
        assert _same(plain.f3(x), _gimbal().f3(x)) and not _same(plain.f3(x), boxed)
