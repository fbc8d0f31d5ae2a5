"""core/quadrature.py: a quadrature's ball depends on its arguments and the precision only, whatever the process
computed before (Arb's Gauss-Legendre node cache otherwise leaks the history into the radius's last bits)."""
import random

from flint import acb, arb, ctx

from rigor_gyro.core import quadrature
from rigor_gyro.core.balls import working_precision


def _f(t, analytic):
    return t.cos() * (t / (arb(3) / 10)).tanh() / (2 + t.sin() ** 2)


def _text(v: acb) -> tuple[str, str]:
    r = v.real
    return r.mid().str(60, radius=False), r.rad().str(15, radius=False)


def test_repeated_quadratures_at_interleaved_precisions_give_the_same_ball():
    rnd = random.Random(7)
    cases = [(rnd.choice([53, 64, 128, 200]), rnd.randint(-20, 20), rnd.choice([7, 16, 64])) for _ in range(40)]
    first: dict = {}
    for p, n, d in cases + cases[::-1] + cases:
        with working_precision(p):
            v = _text(quadrature.integral(_f, 0, acb(arb(n) / d)))
        assert first.setdefault((p, n, d), v) == v, (p, n, d)


def test_a_quadrature_gives_what_a_fresh_cache_gives():
    x = acb(arb(8) / 16)
    with working_precision(53):
        ctx.cleanup()
        fresh = _text(acb.integral(_f, 0, x))
    with working_precision(200):            # nodes cached at 200 bits, then reused at 53 by plain acb.integral
        quadrature.integral(_f, 0, x)
    with working_precision(53):
        assert _text(quadrature.integral(_f, 0, x)) == fresh
