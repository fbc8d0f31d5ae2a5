"""Rudenko's Hz rows against the paper's own chain (issue 39; kinds/eigenfrequencies/paper_hz.py): the
chains over the printed inputs (each within its rounding) times the scale the 'exact' values share at
eps = 0.1073 contain every mpmath-sampled value; the 'exact' rows use the other three values' scales
(leave one out); a derivation reading is stated only where its enclosure certainly rounds to the print."""
import random
from fractions import Fraction as Fr

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro import load_scene
from rigor_gyro.core.audit import half_unit
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.outcome import AuditRow, AuditStatus
from rigor_gyro.kinds.eigenfrequencies.claims import validate
from rigor_gyro.kinds.eigenfrequencies.model import BRACKETS, Params, approximation
from rigor_gyro.kinds.eigenfrequencies.paper_hz import (DERIVED_READINGS, READ_FORMULAS, derived_row, exact_chain,
                                                        hz_chain, input_box)
from rigor_gyro.kinds.eigenfrequencies.paper_scale import consistent_eps, fit_scales
from rigor_gyro.core.formula_edits import evaluate

EXACT = ["41.4", "121.5", "521.5", "935.7"]


@pytest.fixture(scope="module")
def setting():
    with working_precision(128):
        model = validate(load_scene("rudenko1976"))
        a, b, e, W = (model.q(k) for k in ("a", "b", "eps", "Omega2"))
        scale = consistent_eps(a, b, W, "0.1076", EXACT)
        return model, scale


def _mp(x: Fr):
    return mpmath.mpf(x.numerator) / x.denominator


def _mp_formulas():
    """The bounds and approximations in mpmath, written from the paper's text in the readings the model uses."""
    s = mpmath.sqrt

    def lo8(a, b, e, W):
        D, R1 = e / (b * (b - 1)), a * b * b / ((a - b) * (b - 1) * W)
        return 1 / (b - 1) + (D + R1) / 2 - s(((D + R1) / 2) ** 2 + R1 * (1 / (b - 1) - e * a / (b * (a - b))))

    def hi9(a, b, e, W):
        return (1 + e) / (b - 1) + e ** 2 * (a - 1) / ((a - b) * (a - b + e * (a - 1))) + (b - e) / (b + s(W * (b - 1) * b))

    def ap2(a, b, e, W):
        return (e * (b - 1) * a + W * (a - b)) / ((a - b) * (b - 1) * (b + W))

    def lin8(a, b, e, W):
        r1 = a * b * b / ((a - b) * (b - 1) * W)
        return (1 / (b - 1) + r1 * e * a / (b * (a - b))) / (1 + r1)
    return {"lower 2": (lo8, BRACKETS[2].lo_read), "upper 3": (hi9, BRACKETS[3].hi_read),
            "approx 2": (ap2, lambda p: approximation(2, p)), "linear 8": (lin8, DERIVED_READINGS[("lower", 2)][1])}


def test_the_scale_is_the_one_the_exact_values_share_at_eps_0_1073(setting):
    _, scale = setting
    assert scale.text == "0.1073" and scale.k == -3
    assert scale.outer().lower() < arb("617.7424") and scale.outer().upper() > arb("617.8083")
    assert scale.outer().upper() < arb("617.8085") and scale.outer().lower() > arb("617.7422")


@pytest.mark.parametrize("name", ["lower 2", "upper 3", "approx 2", "linear 8"])
def test_hz_chains_contain_every_sampled_value_over_the_printed_inputs(setting, name):
    """scale * sqrt(f) over the box of the printed inputs' roundings: every mpmath sample (inputs drawn in
    the box, the scale drawn in the certified interval, corners included) lies inside the chain."""
    model, scale = setting
    mp_f, f = _mp_formulas()[name]
    box = input_box(model)
    with working_precision(128):
        ch = hz_chain(f, box, scale, name, "0.1076")
    lo_s, hi_s = Fr(scale.lo.upper().str(30, radius=False)), Fr(scale.hi.lower().str(30, radius=False))
    rnd = random.Random(7)
    c_lo = mpmath.mpf(ch.value.lower().str(30, radius=False))
    c_hi = mpmath.mpf(ch.value.upper().str(30, radius=False))
    with mpmath.workdps(40):
        for i in range(40):
            pick = (lambda lo, hi: lo if (i >> rnd.randint(0, 3)) & 1 else hi) if i < 16 else \
                (lambda lo, hi: lo + (hi - lo) * Fr(rnd.randint(0, 1000), 1000))
            P = [_mp(pick(lo, hi)) for _, lo, hi in box.edges]
            sc = _mp(lo_s + (hi_s - lo_s) * Fr(rnd.randint(0, 100), 100))
            v = sc * mpmath.sqrt(mp_f(*P))
            assert c_lo <= v <= c_hi, (name, P, v)
    # the box is each printed input's rounding interval (a chain at the exact inputs would be narrower)
    assert dict((k, hi - lo) for k, lo, hi in box.edges) == {"a": Fr(1, 100), "b": Fr(1, 1000), "eps": Fr(1, 10000),
                                                            "Omega2": Fr(1, 1000)}


def test_the_exact_rows_use_the_other_three_values_scales(setting):
    """Leave one out: the scales behind 'exact' lambda_4 are those 41.4, 121.5 and 521.5 share at eps = 0.1073
    (wider than the four's: 935.7 is the tightest of them), never the interval 935.7 itself helped make."""
    _, scale = setting
    with working_precision(128):
        ch, text = exact_chain(4, EXACT, scale)
        lo, hi = fit_scales(EXACT[:3], scale.omegas[:3])
    assert text != "[617.7423, 617.8084]"
    want = lo.union(hi) * scale.omegas[3].sqrt()
    assert abs(ch.value.lower() - want.lower()) < arb("1e-9") and abs(ch.value.upper() - want.upper()) < arb("1e-9")
    assert ch.value.lower() < scale.outer().lower() * scale.omegas[3].sqrt()


def test_a_derivation_reading_is_stated_only_where_it_certainly_rounds_to_the_print(setting):
    """(8)'s linear form at eps = 0.1073 is [119.4546, 119.4675] Hz: it certainly gives 119.5; a print
    its enclosure only partly rounds to (119.46) or does not round to (119.4) gets no reading."""
    model, scale = setting
    box = input_box(model)
    with working_precision(128):
        p = Params(*(arb(model.q(k)) for k in ("a", "b", "eps", "Omega2")))
        pe = Params(p.a, p.b, arb(scale.eps), p.W)
        for printed, expected in (("119.5", True), ("119.46", False), ("119.4", False), ("119.6", True)):
            row = AuditRow("x", printed, "", None, AuditStatus.DISAGREES, "")
            assert derived_row(row, ("lower", 2), printed, box, scale, "0.1076", p, pe) is expected, printed
            assert (row.propagated is not None) is expected
        row = AuditRow("x", "130.4", "", None, AuditStatus.DISAGREES, "")
        assert derived_row(row, ("upper", 2), "130.4", box, scale, "0.1076", p, pe) is False   # no reading known


@pytest.mark.parametrize("key", sorted(READ_FORMULAS))
def test_the_reading_texts_are_the_models_readings(key):
    """READ_FORMULAS (the edit search's second step) evaluates to the model's reading of the same bound."""
    kind, j = key
    text, defs = READ_FORMULAS[key]
    with working_precision(128):
        p = Params(arb(fmpq(1508, 100)), arb(fmpq(6154, 1000)), arb(fmpq(1076, 10000)), arb(fmpq(629, 1000)))
        env = {"a": p.a, "b": p.b, "eps": p.eps, "W": p.W}
        for k, v in defs.items():
            env[k] = evaluate(v, env)
        v = evaluate(text, env)
        br = BRACKETS[j]
        want = (br.lo_read if kind == "lower" else br.hi_read)(p)
        assert v.overlaps(want) and (v - want).rad() < arb("1e-30")
