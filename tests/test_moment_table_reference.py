"""Table laws (moment = "table") against an independent reference (issue 42 review): the natural cubic spline
through the points and their odd reflections, solved here as the full 4(n-1) linear system (interpolation,
C1, C2 at the inner knots, S'' = 0 at both ends) by Gauss-Jordan elimination in exact rationals (not the
law's Thomas algorithm). Values at rational sample points are exact and compared with the enclosures' exact
endpoints (no decimal rounding of the reference: a 35-digit reference printed and compared with a 128-bit
ball of radius 4e-34 was the review's false alarm); G and q against mpmath quadrature at 50 digits.

Samples: f, f' and f(x)/x on point balls and on small intervals (every sample of the interval inside its
certified outer range), G at points, q_closed near 0."""
from fractions import Fraction as Fr
import random

import mpmath as mp
import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.exact import Exact
from rigor_gyro.kinds.lyapunov.moment_table import table_law

TABLES = {
    "three": (["0", "0.3", "0.6"], ["0", "30", "60"]),
    "wiggle": (["0", "0.01", "0.6"], ["0", "100", "0.001"]),
    "huge": (["0", "1e-9", "0.6"], ["0", "1e20", "1e-20"]),
    "four": (["0", "0.1", "0.25", "0.6"], ["0", "5", "3", "40"]),
}


def reference(xs, ys):
    """The exact pieces (knot, coefficients in u = x - knot) of the natural spline through the odd extension."""
    K = [-x for x in reversed(xs[1:])] + xs
    Y = [-y for y in reversed(ys[1:])] + ys
    n = len(K) - 1
    N = 4 * n
    rows = []

    def row(entries, rhs):
        r = [Fr(0)] * (N + 1)
        for j, v in entries:
            r[j] += v
        r[N] = rhs
        rows.append(r)
    for i in range(n):
        h = K[i + 1] - K[i]
        row([(4 * i, Fr(1))], Y[i])
        row([(4 * i + k, h ** k) for k in range(4)], Y[i + 1])
        if i < n - 1:
            row([(4 * i + 1, Fr(1)), (4 * i + 2, 2 * h), (4 * i + 3, 3 * h * h), (4 * i + 5, Fr(-1))], Fr(0))
            row([(4 * i + 2, Fr(2)), (4 * i + 3, 6 * h), (4 * i + 6, Fr(-2))], Fr(0))
    row([(2, Fr(2))], Fr(0))
    hn = K[-1] - K[-2]
    row([(4 * (n - 1) + 2, Fr(2)), (4 * (n - 1) + 3, 6 * hn)], Fr(0))
    for c in range(N):                                   # Gauss-Jordan with exact pivots
        p = next(r for r in range(c, N) if rows[r][c] != 0)
        rows[c], rows[p] = rows[p], rows[c]
        piv = rows[c][c]
        rows[c] = [v / piv for v in rows[c]]
        for r in range(N):
            if r != c and rows[r][c] != 0:
                w = rows[r][c]
                rows[r] = [a - w * b for a, b in zip(rows[r], rows[c])]
    co = [[rows[4 * i + k][N] for k in range(4)] for i in range(n)]
    return K, Y, co


def S_ref(ref, x: Fr, order: int = 0) -> Fr:
    K, Y, co = ref
    if x <= K[0] or x >= K[-1]:                          # the tangent continuation
        i = 0 if x <= K[0] else len(co) - 1
        e = K[0] if x <= K[0] else K[-1]
        u = e - K[i]
        a, b, c, d = co[i]
        slope = b + 2 * c * u + 3 * d * u * u
        return (Y[0] if x <= K[0] else Y[-1]) + slope * (x - e) if order == 0 else slope if order == 1 else Fr(0)
    i = max(j for j in range(len(co)) if K[j] <= x)
    u = x - K[i]
    a, b, c, d = co[i]
    return (a + u * (b + u * (c + u * d)), b + u * (2 * c + 3 * d * u), 2 * c + 6 * d * u)[order]


def ends(b: arb) -> tuple[Fr, Fr]:
    m, e = b.mid().man_exp()
    r, re = b.rad().man_exp()
    mid, rad = Fr(int(m)) * Fr(2) ** int(e), Fr(int(r)) * Fr(2) ** int(re)
    return mid - rad, mid + rad


def inside(v: Fr, b: arb) -> bool:
    lo, hi = ends(b)
    return b.is_finite() and lo <= v <= hi


def _law(name):
    xs, ys = TABLES[name]
    return table_law({"x2": xs, "f": ys}, Exact(Fr(1, 6), 1, "pi/6")), reference([Fr(x) for x in xs],
                                                                                  [Fr(y) for y in ys])


SLOW = pytest.mark.slow


@pytest.mark.parametrize("name,prec", [("wiggle", 128)] + [pytest.param(n, p, marks=SLOW) for n in sorted(TABLES)
                                                            for p in (64, 128) if (n, p) != ("wiggle", 128)])
def test_f_f_over_x_df_sampled(name, prec):
    law, ref = _law(name)
    rng = random.Random(7)
    a = arb(100)
    with working_precision(prec):
        for _ in range(25 if name == "wiggle" else 60):
            c = Fr(rng.uniform(-0.8, 0.8))
            w = Fr(rng.choice([0, 1e-9, 1e-4, 0.01, 0.1]))
            ball = arb(float(c)) if w == 0 else arb(float(c - w)).union(arb(float(c + w)))
            lo, hi = ends(ball)
            f, fx, df = law.f(a, ball), law.f_over_x(a, ball), law.df(a, ball)
            for t in (lo, hi, (lo + hi) / 2, lo + (hi - lo) * Fr(rng.random())):
                assert inside(S_ref(ref, t), f), (name, t)
                assert inside(S_ref(ref, t, 1), df), (name, t)
                if t != 0:
                    assert inside(S_ref(ref, t) / t, fx), (name, t, fx)
        # the review's point
        x = Fr(0.1741)
        assert inside(S_ref(ref, x) / x, law.f_over_x(a, arb(0.1741)))


@pytest.mark.parametrize("name,xs", [("wiggle", ("1/1000", "1/5", "3/5"))]
                         + [pytest.param(n, ("1/1000", "7/1000", "1/5", "1/2", "3/5", "7/10"), marks=SLOW)
                            for n in ("three", "wiggle", "four")])
def test_G_and_q_against_mpmath(name, xs):
    law, ref = _law(name)
    A0, C0 = Fr(127, 10), Fr(14, 10)
    with mp.workdps(40):
        A0m, C0m = mp.mpf(A0.numerator) / A0.denominator, mp.mpf(C0.numerator) / C0.denominator

        def Sm(s):
            m, e = s.man_exp                            # s an mpf: an exact binary rational
            v = S_ref(ref, Fr(int(m)) * Fr(2) ** int(e))
            return mp.mpf(v.numerator) / v.denominator
        knots = sorted({Fr(0), *[abs(k) for k in ref[0]]})
        for x in map(Fr, xs):
            xm = mp.mpf(x.numerator) / x.denominator
            pts = [mp.mpf(k.numerator) / k.denominator for k in knots if k < x] + [xm]
            Gm = mp.quad(lambda s: mp.cos(s) * Sm(s) / (A0m - C0m * mp.sin(s) ** 2), pts)
            g = law.G(arb(100), arb(127) / 10, arb(14) / 10, arb(x.numerator) / x.denominator)
            assert g.overlaps(arb(mp.nstr(Gm, 38))) and g.rad() < abs(g) * arb("1e-12"), (name, x, g, Gm)
            q = law.q_closed(arb(100), arb(127) / 10, arb(14) / 10, arb(x.numerator) / x.denominator)
            if q is not None:
                qm = Sm(xm) ** 2 / (2 * (A0m - C0m * mp.sin(xm) ** 2) * Gm)
                assert q.overlaps(arb(mp.nstr(qm, 38))), (name, x, q, qm)
