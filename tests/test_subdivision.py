"""Subdivision: positivity proofs with witnesses, and certified extrema."""
from flint import arb

from rigor_gyro.core.balls import certainly_lt, decimal_bounds, enclosure_text, working_precision
from rigor_gyro.certificate import Status
from rigor_gyro.core.subdivision import certify_positive, enclose_max, enclose_min, mean_value_form


def test_positivity_proved_refuted_and_inconclusive():
    with working_precision(128):
        thin = arb("1e-9")
        assert certify_positive(mean_value_form(lambda x: (x - arb(1) / 2) ** 2 + thin), "-2", "2").status is Status.PROVED
        r = certify_positive(lambda x: (x - arb(1) / 2) ** 2 - thin, "-2", "2")
        assert r.status is Status.REFUTED and (r.witness - arb(1) / 2).abs_upper() < arb("1e-4")
        assert r.witness_value < 0
        r = certify_positive(lambda x: (x - arb(1) / 3) ** 2, "-2", "2", max_pieces=300)
        assert r.status is Status.INCONCLUSIVE and r.stuck is not None


def test_max_with_removable_singularity_is_enclosed():
    with working_precision(128):
        m = enclose_max(lambda x: x.sinc(), "-1", "2", abs_tol="1e-20")     # sin(x)/x, max 1 at 0
        assert m.converged and m.ball.is_finite() and m.ball.contains(1) and m.ball.rad() < arb("1e-19")
        n = enclose_min(lambda x: x.cos(), "0", "4", abs_tol="1e-15")
        assert n.ball.is_finite() and n.ball.contains(-1)


def test_enclose_min_encloses_the_minimum_and_reports_its_point():
    from flint import arb
    with working_precision(64):
        m = enclose_min(lambda x: (x - arb("0.3")) ** 2 + 1, "-1", "2", abs_tol="1e-10")
        assert m.ball.is_finite() and m.ball.contains(1) and m.ball.lower() > arb("0.999999") and m.converged
        assert m.pieces > 1 and m.cover and abs(m.argpoint - arb("0.3")) < arb("0.01")
        loose = enclose_min(lambda x: (x - arb("0.3")) ** 2 + 1, "-1", "2", abs_tol="0.5")
        assert loose.ball.is_finite() and loose.ball.contains(1) and loose.ball.rad() > m.ball.rad()
        tight_rel = enclose_min(lambda x: (x - arb("0.3")) ** 2 + 1, "-1", "2", abs_tol="0", rel_tol="1e-9")
        assert tight_rel.ball.rad() < loose.ball.rad()


def test_a_box_is_refuted_only_where_its_midpoint_is_certainly_not_positive():
    """f(u) = u^2 + e, with e known only to lie in [0, 2e-40]: f > 0 cannot be proved near u = 0, and
    it cannot be refuted either (f(0) may be > 0): the outcome is inconclusive, never refuted."""
    from flint import arb

    from rigor_gyro.core.boxes import Box
    from rigor_gyro.core.outcome import Status
    from rigor_gyro.core.subdivision import certify_positive_on_box
    from fractions import Fraction
    e = arb("1e-40", "1e-40")
    out = certify_positive_on_box(lambda b: b["u"] * b["u"] + e, Box.of({"u": (Fraction(-1), Fraction(1))}),
                                  max_pieces=200)
    assert out.status is Status.INCONCLUSIVE
    out = certify_positive_on_box(lambda b: b["u"] * b["u"] - arb("1e-40"),
                                  Box.of({"u": (Fraction(-1), Fraction(1))}), max_pieces=200)
    assert out.status is Status.REFUTED and out.witness == {"u": Fraction(0)}


def test_a_coarse_refutation_is_found_on_the_first_box():
    """f = (x - 1/2)^2 - 1/100 with an exact-hull enclosure (centred above 0 on [0, 1]): its midpoint
    is a certified counterexample, found at once (the first boxes always try their midpoint)."""
    from fractions import Fraction

    from flint import arb

    from rigor_gyro.core.boxes import Box
    from rigor_gyro.core.outcome import Status
    from rigor_gyro.core.subdivision import certify_positive_on_box

    def f(b):
        x = b["x"]
        lo, hi = x.lower(), x.upper()
        m = arb(1) / 2
        d_lo = arb(0) if (lo <= m and m <= hi) else min(abs(lo - m), abs(hi - m), key=lambda v: float(v.mid()))
        d_hi = max(abs(lo - m), abs(hi - m), key=lambda v: float(v.mid()))
        return (d_lo * d_lo).union(d_hi * d_hi) - arb(1) / 100
    out = certify_positive_on_box(f, Box.of({"x": (Fraction(0), Fraction(1))}), max_pieces=2)
    assert out.status is Status.REFUTED and out.witness == {"x": Fraction(1, 2)}


def test_best_first_bisection_covers_the_interval_and_bounds_its_maximum():
    """The pieces returned tile [lo, hi] whatever the stopping reason, each with its bound; the largest
    bound is >= the maximum; refine is called once per piece before it is split; done stops early."""
    from fractions import Fraction
    from flint import arb
    from rigor_gyro.core.balls import certainly_le, exact_fraction
    from rigor_gyro.core.subdivision import best_first_bisection
    refined = []

    def bound(a, b):                    # 1 - (x - 1/3)^2 over [a, b], as a ball's upper end
        x = a.union(b)
        return (1 - (x - arb(1) / 3) ** 2).upper()
    for budget, target in ((7, arb("0.5")), (200, arb("1.0001")), (200, arb("0.9"))):
        refined.clear()
        pieces, count = best_first_bisection(arb(0), arb(1), bound, refined.append,
                                             lambda u: certainly_le(u, target), budget)
        assert _tiles(pieces, 0, 1)
        top = max(exact_fraction(u) for _, _, u in pieces)
        assert top >= 1 and count <= budget + 1 and len(refined) >= 1
        if target > arb(1):
            assert count < budget and top <= Fraction(10001, 10000)     # stopped because done



def _tiles(pieces, lo, hi) -> bool:
    from rigor_gyro.core.balls import exact_fraction
    ends = sorted((exact_fraction(a), exact_fraction(b)) for a, b, _ in pieces)
    return bool(ends) and ends[0][0] == lo and ends[-1][1] == hi and all(x[1] == y[0] for x, y in zip(ends, ends[1:]))


def _bisection_log(refined, budget=9, **kw):
    """Run best_first_bisection on [0, 1] with a flat bound (done never holds) and log its calls."""
    from rigor_gyro.core.balls import exact_fraction
    from rigor_gyro.core.subdivision import best_first_bisection
    log = []

    def bound(a, b):
        log.append(("bound", exact_fraction(a), exact_fraction(b)))
        return arb(1)

    def refine(m):
        log.append(("refine", exact_fraction(m)))
    args = {} if refined is None else {"refined": refined}
    pieces, count = best_first_bisection(arb(0), arb(1), bound, refine, lambda u: False, budget, **args)
    return log, pieces, count


def test_best_first_bisection_counts_every_bound_and_refines_each_piece_once_before_splitting():
    """``count`` is the number of bounds taken (the budget's unit, at most one over it); by default the
    whole interval is refined first; every piece is refined exactly once, at its midpoint, then bounded
    again, before it is split; with ``refined=True`` the whole interval is split at once."""
    from fractions import Fraction
    for refined in (None, False, True):
        log, pieces, count = _bisection_log(refined)
        bounds = [e[1:] for e in log if e[0] == "bound"]
        assert count == len(bounds) and 9 <= count <= 10 and _tiles(pieces, 0, 1)
        refines = [e[1] for e in log if e[0] == "refine"]
        assert len(set(refines)) == len(refines)                   # no piece refined twice
        for i, e in enumerate(log):
            if e[0] == "refine":                                   # the refined piece is bounded again
                assert log[i + 1][0] == "bound" and sum(log[i + 1][1:]) / 2 == e[1]
        # a split: the two halves bounded one after the other; the piece was refined before, except
        # the whole interval when it was handed in as refined
        for i in range(len(log) - 1):
            e, f = log[i], log[i + 1]
            if (e[0] == f[0] == "bound" and e[2] == f[1] and (f[2] - f[1]) == (e[2] - e[1])
                    and (e[1] / (2 * (e[2] - e[1]))).denominator == 1):       # halves of one dyadic piece
                whole, mid = (e[1], f[2]), e[2]
                if refined is True and whole == (0, 1):
                    assert mid not in refines
                else:
                    assert mid in refines and log.index(("refine", mid)) < i
        if refined is True:
            assert log[:3] == [("bound", 0, 1), ("bound", 0, Fraction(1, 2)), ("bound", Fraction(1, 2), 1)]
        else:
            assert log[:3] == [("bound", 0, 1), ("refine", Fraction(1, 2)), ("bound", 0, 1)]


def test_best_first_bisection_stops_at_a_piece_the_precision_cannot_split():
    """[1, 1 + 2^-63] at 64 bits has no representable midpoint strictly inside: the piece is kept whole
    (with its bound) and the search stops after three bounds, never splitting a piece into empty ones."""
    from fractions import Fraction
    from rigor_gyro.core.subdivision import best_first_bisection
    with working_precision(64):
        lo, hi = arb(1), arb(1) + arb(2) ** -63
        assert hi.is_exact()
        pieces, count = best_first_bisection(lo, hi, lambda a, b: arb(1), lambda m: None, lambda u: False, 50)
        assert count == 3 and _tiles(pieces, 1, 1 + Fraction(1, 2 ** 63)) and len(pieces) == 1


def test_best_first_bisection_takes_infinite_bounds_and_keeps_them():
    """A bound of +inf (a piece where the function may be unbounded) is a valid bound: the search goes
    on, the pieces still tile the interval and the largest bound returned is +inf."""
    from rigor_gyro.core.subdivision import best_first_bisection

    def bound(a, b):                    # +inf on the pieces whose closure holds 3/10
        return arb("inf") if a <= arb(3) / 10 <= b else arb(1)
    pieces, count = best_first_bisection(arb(0), arb(1), bound, lambda m: None, lambda u: u.is_finite(), 12)
    assert _tiles(pieces, 0, 1) and count <= 13
    assert any(not u.is_finite() for _, _, u in pieces) and not pieces[0][2].is_finite()


def test_lower_bound_on_box_counts_its_evaluations_keeps_the_budget_and_accepts_infinite_leaves():
    """``boxes`` is the number of evaluations of f, never above ``max_pieces``, and the budget is used
    to its end (9 = 1 + 2 * 4 splits); a leaf where f is +inf (nothing asked there) is kept as a leaf
    and never lowers the bound; the leaves tile the box."""
    from fractions import Fraction
    from rigor_gyro.core.boxes import Box, tiles_by_bisection
    from rigor_gyro.core.subdivision import lower_bound_on_box
    calls = []

    def f(b):
        calls.append(b["x"])
        x = b["x"]
        # f(x) = x, asked only for x < 1/2 (a dyadic sub-box of [0, 1] other than [0, 1] lies in [1/2, 1] iff its centre is above 1/2)
        return arb("inf") if x.mid() > arb(1) / 2 else x
    whole = Box.of({"x": (Fraction(0), Fraction(1))})
    with working_precision(64):
        out = lower_bound_on_box(f, whole, "0.25", max_pieces=9)
    assert out.boxes == len(calls) == 9 and not out.reached
    assert len(out.leaves) == 5 and tiles_by_bisection(whole, out.leaves)
    assert out.bound.is_finite() and out.bound <= 0 and out.bound > arb("-1e-6")
    assert any(b.interval("x")[0] >= Fraction(1, 2) for b in out.leaves)     # the +inf leaf, kept


def test_certify_positive_on_box_reports_what_it_decided_on():
    """A refutation carries its witness point and f's certified value there (<= 0) and the leaves
    proved so far; an inconclusive result the box it stopped on (a caller searches again from its
    midpoint) and its reason the number of boxes evaluated; a proof the number of its leaves."""
    from fractions import Fraction
    from rigor_gyro.core.boxes import Box
    from rigor_gyro.core.outcome import Status
    from rigor_gyro.core.subdivision import certify_positive_on_box
    whole = Box.of({"u": (Fraction(-1), Fraction(1))})
    calls = []

    def f(b):
        calls.append(b)
        return b["u"] * b["u"] + arb("1e-40", "1e-40")       # never certainly positive near 0
    out = certify_positive_on_box(f, whole, max_pieces=50)
    assert out.status is Status.INCONCLUSIVE and out.stuck is not None and out.stuck.interval("u")[0] <= 0 <= out.stuck.interval("u")[1]
    boxes = sum(1 for b in calls if b["u"].rad() > 0)
    assert f"undecided after {boxes} boxes" in out.reason and out.leaves
    out = certify_positive_on_box(lambda b: b["u"] - arb("0.3"), whole, max_pieces=50)
    assert out.status is Status.REFUTED and out.witness_value is not None and out.witness_value <= 0
    assert out.witness_value.is_finite() and out.witness_value.contains(arb(out.witness["u"].numerator) / out.witness["u"].denominator - arb("0.3"))
    assert isinstance(out.leaves, list)
    out = certify_positive_on_box(lambda b: b["u"] * b["u"] + 1, whole)
    assert out.status is Status.PROVED and out.reason == f"f > 0 certified on {len(out.leaves)} boxes"


def _counted(fn):
    """fn, and the list of the intervals (balls of positive radius) it is evaluated on."""
    calls = []

    def f(x):
        if x.rad() > 0:
            calls.append(x)
        return fn(x)
    return f, calls


def _noisy(fn, rad: str):
    """fn with every value widened by a ball of radius ``rad`` about 0: an enclosure of fn, as a
    function evaluated with rounding error gives (point values are then balls, not points)."""
    noise = arb(0, arb(rad))
    return lambda x: fn(x) + noise


def test_the_max_enclosure_holds_the_maximum_when_point_values_are_wide():
    # the lower end of the max is f at a point, taken at its lower end: its upper end (larger than the
    # maximum by up to the radius) would put the whole enclosure above the true maximum
    with working_precision(64):
        inside = enclose_max(_noisy(lambda x: x * (1 - x), "1e-6"), "0", "1", abs_tol="1e-9")   # max 1/4 at 1/2
        assert inside.ball.is_finite() and inside.ball.contains(arb(1) / 4) and inside.ball.lower() < arb(1) / 4
        at_end = enclose_max(_noisy(lambda x: x, "1e-6"), "0", "1", abs_tol="1e-9")              # max 1 at the end 1
        assert at_end.ball.is_finite() and at_end.ball.contains(1) and at_end.ball.lower() < 1
        low_end = enclose_max(_noisy(lambda x: -x, "1e-6"), "0", "1", abs_tol="1e-9")            # max 0 at the end 0
        assert low_end.ball.is_finite() and low_end.ball.contains(0) and low_end.ball.lower() < 0
        third = enclose_max(_noisy(lambda x: -(x - arb(1) / 3) ** 2, "1e-6"), "0", "1", abs_tol="1e-9")
        assert third.ball.is_finite() and third.ball.contains(0) and third.ball.lower() < 0    # max 0 at 1/3, met by midpoints


def test_the_max_is_taken_over_the_interval_only():
    # a first guess outside [lo, hi] (where -x is larger) would lift the enclosure above the maximum
    with working_precision(64):
        for lo, hi in (("1", "2"), ("2", "3"), ("-3", "-2")):
            m = enclose_max(lambda x: -x, lo, hi, abs_tol="1e-12")
            assert m.ball.is_finite() and m.ball.contains(-arb(lo)) and m.ball.upper() < -arb(lo) + arb("1e-9")
            assert arb(lo) <= m.argpoint <= arb(hi)


def test_the_max_reports_its_pieces_and_whether_it_converged():
    with working_precision(64):
        f, calls = _counted(lambda x: (3 * x).sin())
        m = enclose_max(f, "-1", "2", abs_tol="1e-6")
        assert m.converged and m.pieces == len(calls) > 1                 # a piece is one interval evaluation
        cut = enclose_max(lambda x: (x * 7).sin(), "-1", "2", abs_tol="1e-30", max_pieces=9)
        assert not cut.converged and cut.pieces == 9 and cut.ball.is_finite() and cut.ball.contains(1)
        default = enclose_max(lambda x: -(x - arb("0.3")) ** 2, "-1", "2")  # the default tolerance 1e-12
        assert default.converged and default.ball.is_finite() and default.ball.contains(0) and default.ball.rad() < arb("1e-11")


def test_the_relative_tolerance_scales_with_the_maximum_and_the_precision_stops_the_search():
    with working_precision(64):
        m = enclose_max(lambda x: 100 - (x - arb("0.3")) ** 2, "-1", "2", abs_tol="0", rel_tol="1e-6")
        # converged to about rel_tol * |max| = 1e-4: not looser, and not 100 times tighter than asked
        assert m.converged and m.ball.is_finite() and m.ball.contains(100) and arb("1e-6") < 2 * m.ball.rad() <= arb("1e-4")
    with working_precision(16):
        # abs_tol 0 cannot be met: the search stops where the precision can no longer split a piece
        cut = enclose_max(lambda x: 100 - (x - arb(1) / 3) ** 2, "-1", "2", abs_tol="0", max_pieces=20000)
        assert not cut.converged and cut.pieces < 500 and cut.ball.is_finite() and cut.ball.contains(100)


def test_positivity_counts_its_pieces_and_stops_at_its_budget():
    """certify_positive's ``pieces`` is the number of interval evaluations of f, and the budget counts
    the pieces done plus those waiting: (x - 1/3)^2 (touching 0) stops just below 300."""
    with working_precision(128):
        f, calls = _counted(lambda x: (x - arb(1) / 3) ** 2 + arb("1e-3"))
        r = certify_positive(f, "-2", "2")
        assert r.status is Status.PROVED and r.pieces == len(calls) > 1
        assert r.reason == f"f > 0 certified on {r.pieces} pieces"
        f, calls = _counted(lambda x: (x - arb(1) / 3) ** 2)
        r = certify_positive(f, "-2", "2", max_pieces=300)
        assert r.status is Status.INCONCLUSIVE and r.pieces == len(calls) and 250 < r.pieces < 300


def test_positivity_is_refuted_at_an_end_of_the_interval_with_the_end_as_witness():
    with working_precision(64):
        for f, end in ((lambda x: x, 0), (lambda x: 1 - x, 1)):             # f > 0 inside, f = 0 at one end
            r = certify_positive(f, "0", "1")
            assert r.status is Status.REFUTED and r.witness == end and r.witness.rad() == 0
            assert r.witness_value == 0 and r.reason == f"f(t) <= 0 at the point t = {enclosure_text(arb(end), 20)}"
        r = certify_positive(lambda x: (x - arb(1) / 2) ** 2 - arb("1e-9"), "-2", "2")   # refuted at a midpoint
        assert r.status is Status.REFUTED and r.reason == f"f(t) <= 0 at the point t = {enclosure_text(r.witness, 20)}"


def test_an_undecided_piece_is_reported_with_f_over_it_and_min_width_stops_the_search():
    """INCONCLUSIVE names the undecided piece [a, b], keeps f over it (what the prover watches: a
    narrower stuck value is progress) and says how many pieces were spent; ``min_width`` stops the
    bisection at a piece narrower than it (before the budget or the precision would)."""
    f = lambda x: (x - arb(1) / 3) ** 2                                   # noqa: E731 (touches 0 at 1/3)
    with working_precision(128):
        r = certify_positive(f, "-2", "2", max_pieces=300)
        a, b = r.stuck
        assert certainly_lt(a, b) and r.stuck_value is not None
        fx = f(a.union(b))
        assert r.stuck_value.is_finite() and r.stuck_value.overlaps(fx) and abs(r.stuck_value.rad() - fx.rad()) <= fx.rad() * arb("1e-6")
        assert r.reason == (f"f not separated from 0 on [{decimal_bounds(a, 12)[0]}, {decimal_bounds(b, 12)[1]}] after "
                            f"{r.pieces} pieces "
                            "(raise precision or max_pieces; f may touch 0 there)")
        w = certify_positive(f, "-2", "2", min_width="1e-3")
        a, b = w.stuck
        assert w.status is Status.INCONCLUSIVE and certainly_lt(b - a, arb("1e-3")) and w.pieces < 100
        assert not certainly_lt(b - a, arb("0.5e-3")) and abs(a - arb(1) / 3) < arb("1e-2")     # next to the touch
