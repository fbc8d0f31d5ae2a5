"""Issue 41: root counts of G on a nutation half-period (phase_pieces), its search (phase_walk) and the
checker's phase_empty / phase_unique pieces. Synthetic G = A + R cos(w t) + k t (exact Taylor
coefficients in Arb), sampled against mpmath; the checker on a short fast-nutation scene."""
from __future__ import annotations

import math

import mpmath
import pytest
from flint import arb

from rigor_gyro.core.balls import working_precision
from rigor_gyro.kinds.periodic_orbit import phase_pieces as PP

W = 1000


def synthetic(A, R, k=0.0):
    """coeffs(c, n): balls containing the Taylor coefficients of A + R cos(W t) + k t over the ball c."""
    A, R, k = arb(A), arb(R), arb(k)

    def coeffs(c, n):
        wc = W * c
        cs, sn = wc.cos(), wc.sin()
        ders = [cs, -sn, -cs, sn]
        out = []
        for j in range(n):
            out.append(R * ders[j % 4] * arb(W) ** j / math.factorial(j))
        out[0] += A + k * c
        if n > 1:
            out[1] += k
        return out
    return coeffs


def mp_g(A, R, k=0.0):
    return lambda t: mpmath.mpf(A) + mpmath.mpf(R) * mpmath.cos(W * t) + mpmath.mpf(k) * t


def roots_mp(A, R, lo, hi, k=0.0, n=400):
    f = mp_g(A, R, k)
    xs = [lo + (hi - lo) * i / n for i in range(n + 1)]
    return sum(1 for a, b in zip(xs, xs[1:]) if f(a) * f(b) < 0)


HALF = math.pi / W


@pytest.mark.parametrize("A,lo,hi,true", [
    (0.3, 0.0, HALF, 1),            # max to min through one root
    (1.5, 0.0, HALF, 0),            # G > 0 throughout
    (0.3, 0.1 * HALF, 1.9 * HALF, 2),   # around the minimum: two roots, same end signs
    (0.999, 0.2 * HALF, 1.8 * HALF, 2),  # a close pair next to the minimum
    (1.001, 0.2 * HALF, 1.8 * HALF, 0),  # a near miss
])
def test_phase_count_matches_the_roots(A, lo, hi, true):
    with working_precision(128):
        co = synthetic(A, 1)
        a, b = arb(lo), arb(hi)
        assert roots_mp(A, 1, lo, hi) == true
        for claim in (0, 1):
            ok, leaves = PP.phase_count(co, a, b, claim)
            assert not ok or claim == true, (claim, true)
        if true in (0, 1):
            assert PP.phase_count(co, a, b, true)[0]


def test_two_roots_never_counted_even_with_a_slope():
    # a sloped oscillation over two half-periods: ends of one sign, two crossings
    with working_precision(128):
        co = synthetic(0.2, 1, 50.0)
        lo, hi = 0.2 * HALF, 1.7 * HALF
        n = roots_mp(0.2, 1, lo, hi, 50.0)
        assert n == 2
        assert not PP.phase_count(co, arb(lo), arb(hi), 0)[0]
        assert not PP.phase_count(co, arb(lo), arb(hi), 1)[0]


def test_leaves_sampled_in_mpmath():
    """Every E leaf: G of one sign at mpmath samples; every M leaf: G' of the stated sign."""
    A = 0.3
    f = mp_g(A, 1)
    df = lambda t: -W * mpmath.sin(W * t)          # noqa: E731
    with working_precision(128):
        co = synthetic(A, 1)
        for lo, hi in ((0.0, HALF), (HALF, 2 * HALF), (0.3 * HALF, 0.9 * HALF)):
            for u0, v0 in ((lo, lo + (hi - lo) * 0.3), (lo + (hi - lo) * 0.3, hi), (lo, hi)):
                u, v = arb(u0), arb(v0)
                k = PP.leaf_kind(co, u, v, 0)
                ts = [mpmath.mpf(u0) + (v0 - u0) * mpmath.mpf(i) / 50 for i in range(51)]
                if k == "E":
                    assert len({mpmath.sign(f(t)) for t in ts}) == 1
                elif k in ("M+", "M-"):
                    s = 1 if k == "M+" else -1
                    assert all(s * df(t) > 0 for t in ts)


def test_root_bracket_holds_the_root():
    with working_precision(128):
        co = synthetic(0.3, 1)
        a, b = PP.root_bracket(co, arb(0), arb(HALF), 1)
        f = mp_g(0.3, 1)
        with mpmath.workdps(60):
            assert f(mpmath.mpf(a.mid().str(50, radius=False))) > 0 > f(mpmath.mpf(b.mid().str(50, radius=False)))
        assert float((b - a).mid()) < 1e-15


def test_uncertain_end_signs_decide_nothing():
    with working_precision(128):
        co = synthetic(-1, 1)
        # G(0) = 0 exactly: the end sign is uncertain
        assert PP.phase_count(co, arb(0), arb(HALF), 1) == (False, 0)
        assert PP.phase_count(co, arb(0), arb(HALF), 0) == (False, 0)


def test_three_roots_are_not_one():
    # from above the maximum's level to below: three crossings, opposite end signs
    with working_precision(128):
        co = synthetic(0.3, 1)
        lo, hi = 0.1 * HALF, 2.9 * HALF
        assert roots_mp(0.3, 1, lo, hi) == 3
        assert not PP.phase_count(co, arb(lo), arb(hi), 1)[0]
        assert not PP.phase_count(co, arb(lo), arb(hi), 0)[0]


# ------------------------------------------------------------------------------ the checker

@pytest.fixture(scope="module")
def fast():
    """H = 1e5 (a fast nutation) searched on (0, 0.002]: 15 roots in phase_unique pieces (0.3 s)."""
    from .forgery import certificate
    return certificate("roitenberg1947", H="100000", options={"T_max": "0.002"})


def _hp(data):
    return data["witnesses"]["half_period"]


@pytest.mark.slow
def test_the_checker_confirms_phase_pieces(fast):
    from .forgery import items
    kinds = {p["kind"] for p in _hp(fast)["pieces"]}
    assert "phase_unique" in kinds
    assert items(fast)["half_period"] is True


def test_two_roots_stored_as_one_phase_empty_piece_are_rejected(fast):
    import copy
    from .forgery import items
    bad = copy.deepcopy(fast)
    w = _hp(bad)
    pcs = w["pieces"]
    i = next(k for k in range(len(pcs) - 1) if pcs[k]["kind"] == pcs[k + 1]["kind"] == "phase_unique")
    r = sum(p["kind"].endswith("unique") for p in pcs[:i])      # roots before the pair
    pcs[i: i + 2] = [{"lo": pcs[i]["lo"], "hi": pcs[i + 1]["hi"], "kind": "phase_empty"}]
    del w["roots"][r: r + 2]
    assert items(bad)["half_period"] is False


def test_a_phase_unique_piece_relabelled_empty_is_rejected(fast):
    import copy
    from .forgery import items
    bad = copy.deepcopy(fast)
    w = _hp(bad)
    i = next(k for k, p in enumerate(w["pieces"]) if p["kind"] == "phase_unique")
    w["pieces"][i]["kind"] = "phase_empty"
    r = sum(p["kind"].endswith("unique") for p in w["pieces"][:i])
    del w["roots"][r]
    assert items(bad)["half_period"] is False


def test_an_unknown_piece_kind_is_rejected(fast):
    """What an older checker does with a phase piece: an unknown kind fails the witness."""
    import copy
    from .forgery import items
    bad = copy.deepcopy(fast)
    _hp(bad)["pieces"][0]["kind"] = "phase_other"
    assert items(bad)["half_period"] is False
