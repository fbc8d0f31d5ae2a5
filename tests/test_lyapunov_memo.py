"""The per-ball memo of the Gimbal's functions and the Dual number rules (speed work of issue 12):
a memoised value is the very ball a fresh evaluation gives, at every precision; Dual derivatives
enclose the true derivative."""
from flint import arb, fmpq
from hypothesis import given
from hypothesis import strategies as st

from rigor_gyro import load_scene
from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.kinds.lyapunov.model import Dual, Gimbal

G = validate(load_scene("agafonov2013")).gimbal


def _same(a: arb, b: arb) -> bool:
    if not (a.is_finite() and b.is_finite()):
        return a.is_finite() == b.is_finite() and repr(a) == repr(b)
    return bool(a.mid() == b.mid()) and bool(arb(a.rad()) == arb(b.rad()))


def _flat(v):
    if isinstance(v, tuple):
        for x in v:
            yield from _flat(x)
    else:
        yield v


@given(st.integers(-500, 500), st.integers(0, 40), st.sampled_from([53, 64, 128]))
def test_a_memoised_value_is_the_fresh_ball(num, radexp, prec):
    with working_precision(prec):
        x2 = arb(fmpq(num, 1000)) + (arb(0, 2.0 ** -radexp) if radexp < 40 else 0)
        for name in ("psi_coefficients", "F", "f3", "S", "phi"):
            method = getattr(Gimbal, name)
            fresh = list(_flat(method.__wrapped__(G, x2)))
            for _ in range(2):                      # the first call fills the memo, the second reads it
                memo = list(_flat(method(G, x2)))
                assert all(_same(a, b) for a, b in zip(fresh, memo)), name


def test_the_memo_is_keyed_by_precision():
    x2 = arb(fmpq(3, 8))                            # exact: the same memo key at both precisions
    with working_precision(64):
        lo = G.psi_coefficients(x2)[0][0]
    with working_precision(256):
        hi = G.psi_coefficients(x2)[0][0]
    assert hi.rad() < lo.rad()                     # not the 64-bit ball handed back at 256 bits


def test_a_mu_ball_is_never_memoised():
    x2 = arb("0.4")
    a = G.psi_coefficients(x2, arb("0.01"))[0][0]
    b = G.psi_coefficients(x2, arb("0.02"))[0][0]
    assert not a.overlaps(b)


@given(st.floats(0.05, 1.4), st.floats(-3, 3))
def test_dual_rules_enclose_the_derivative(x, c):
    # h(x) = (x^2 + c) / sin x - c x + sqrt(x) cos x - 1/x, its derivative by hand
    with working_precision(64):
        _check_dual(arb(repr(x)), arb(repr(c)))


def _check_dual(X: arb, C: arb) -> None:

    def h(t):
        return (t ** 2 + C) / t.sin() - C * t + t.sqrt() * t.cos() - 1 / t + (2 - t)

    d = h(Dual(X, arb(1))).d
    s, co = X.sin(), X.cos()
    want = (2 * X * s - (X * X + C) * co) / (s * s) - C + co / (2 * X.sqrt()) - X.sqrt() * s + 1 / (X * X) - 1
    assert d.overlaps(want) and d.rad() < 1e-12 * (1 + abs(want).upper())
    assert h(Dual(X, arb(1))).v.overlaps(h(X))


@given(st.integers(-500, 500), st.integers(3, 30))
def test_a_memoised_dual_is_the_fresh_dual(num, radexp):
    with working_precision(64):
        X = arb(fmpq(num, 1000)) + arb(0, 2.0 ** -radexp)
        for name in ("psi_coefficients", "F", "f3", "S"):
            method = getattr(Gimbal, name)
            fresh = list(_flat(method.__wrapped__(G, Dual(X, arb(1)))))
            for _ in range(2):
                memo = list(_flat(method(G, Dual(X, arb(1)))))
                assert all(_same(a.v, b.v) and _same(a.d, b.d) for a, b in zip(fresh, memo)), name
            seeded = list(_flat(method(G, Dual(X, arb(2)))))     # another seed: another key
            assert all(_same(2 * a.d, b.d) or (2 * a.d).overlaps(b.d) for a, b in zip(fresh, seeded))
            assert not all(_same(a.d, b.d) for a, b in zip(fresh, seeded) if not a.d.is_zero())
