"""The relay checker (``kinds/periodic_orbit/check.py``) item by item: its helpers (the Newton test of a
piece, the monotone and merged pieces, a root's classification, the multipliers) against functions
with known roots, and for each step of the half-period witness and each claim the forgery that only
that step's re-decision can catch.

``tests/test_check.py`` rejects altered certificates as a whole, where a report fails for many
reasons at once; these tests name the item that must fail. A relay certificate is checked in about
0.1 s, so a mutant of the checker is judged in seconds.
"""
import copy
import dataclasses
import functools
import json
from fractions import Fraction
from math import comb

import pytest
from flint import arb, fmpq

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import ball, interval, working_precision
from rigor_gyro.kinds import kind_module
from rigor_gyro.kinds.periodic_orbit import check as pc
from rigor_gyro.kinds.periodic_orbit.flow import Spectrum

from .forgery import certificate, claim as _claim, flipped, items as _items


_cert = functools.partial(certificate, "roitenberg1947")


@pytest.fixture(scope="module")
def roit():
    """The paper's scene: one genuine orbit among six roots, every claim proved."""
    return _cert()


@pytest.fixture(scope="module")
def unstable():
    """H = 10000: four genuine orbits, every one unstable (stable refuted), envelope pieces."""
    return _cert(H="10000")


@pytest.fixture(scope="module", params=["stress_relay_sigma_1e-6", "stress_relay_tau_1e-4"])
def stiff(request):
    """The stress catalog's stiff relays: the smallest multiplier (1e-55701, 1e-572) is 0 to the
    eigenvalue algorithm; only the Liouville product (det J) separates it from 0."""
    return json.loads(json.dumps(prove_scene(load_scene(request.param)).to_json()))


@pytest.fixture(scope="module")
def short():
    """T_max = 0.05: the half-period equation searched on (0, 0.05] only, no root there; every other
    claim inconclusive."""
    return _cert(options={"T_max": "0.05"})


def _q(text) -> arb:
    f = Fraction(text)
    return arb(fmpq(f.numerator, f.denominator))


class _Poly(pc._G):
    """The checker's function object for the polynomial sum a_k t^k (exact Taylor coefficients)."""

    def __init__(self, *a):
        a = [fmpq(Fraction(x).numerator, Fraction(x).denominator) for x in a]
        self.coeffs = lambda c, n: [sum((comb(k, j) * arb(a[k]) * c ** (k - j) for k in range(j, len(a))), arb(0))
                                    for j in range(n)]


def _iv(lo, hi) -> arb:
    return interval(_q(lo), _q(hi))


def _hp(data) -> dict:
    return data["witnesses"]["half_period"]


# ------------------------------------------------------------------------------ the helpers

def test_strict_sign_is_a_certain_sign_or_zero():
    with working_precision(128):
        assert pc._strict_sign(arb(2)) == 1
        assert pc._strict_sign(arb(-2)) == -1
        assert pc._strict_sign(arb(0)) == 0
        assert pc._strict_sign(arb(1, 2)) == 0             # [-1, 3]
        assert pc._strict_sign(arb("nan")) == 0


def test_newton_finds_one_root_no_root_or_says_unknown():
    with working_precision(128):
        G = _Poly("2/3", "-7/3", 1)                          # (t - 1/3)(t - 2)
        st, e = pc._newton(G, _iv(0, 1))
        assert st == "unique" and e.is_finite() and e.contains(_q("1/3")) and e.rad() < arb(2) ** -100   # refined to the precision
        assert pc._newton(G, _iv("1/2", "3/2")) == ("empty", None)   # g excludes 0 on the box
        assert pc._newton(G, _iv(0, 3))[0] == "unknown"              # two roots: g' has both signs
        assert pc._newton(_Poly(1, -2, 1), _iv("1/2", "3/2"))[0] == "unknown"   # a double root
        H = _Poly(-1, 1, 0, 1)                               # t^3 + t - 1, its root 0.6823... left of the box
        X = _iv("0.69", "1.5")
        gX = H.both(X)[0]
        assert gX.is_finite() and gX.contains(0)             # g's enclosure does not exclude 0 ...
        assert pc._newton(H, X) == ("empty", None)           # ... the Newton image misses the box
        st, e = pc._newton(H, _iv("0.6", "0.7"))
        assert st == "unique" and abs(e ** 3 + e - 1) < arb(2) ** -100


def test_monotone_root_free_needs_every_sign_strict():
    with working_precision(128):
        G = _Poly(-4, 0, 1)                                  # t^2 - 4: g'' = 2, root 2
        assert pc._monotone_root_free(G, _q("1/2"), _q(1))
        assert not pc._monotone_root_free(G, _q(1), _q(3))          # g changes sign
        assert not pc._monotone_root_free(G, _q(0), _q(1))          # g'(0) = 0
        assert not pc._monotone_root_free(G, _q(1), _q("1/2"))      # an inverted piece
        assert not pc._monotone_root_free(G, _q(1), _q(1))          # a point
        assert not pc._monotone_root_free(_Poly(5, -2, 1), _q(0), _q(2))   # g' changes sign (no root: not decided)
        assert not pc._monotone_root_free(_Poly(-4, 1), _q("1/2"), _q(1))  # g'' = 0: not of strict sign
        assert pc._monotone_root_free(_Poly(4, 0, -1), _q("1/2"), _q(1))   # every sign negative
        assert not pc._monotone_root_free(_Poly(-4, 0, 0, 1), _q(-1), _q("1/2"))  # g'' = 6 t changes sign


def test_a_merged_piece_is_unique_only_with_unique_parts_in_order():
    with working_precision(128):
        G = _Poly("2/3", "-7/3", 1)
        ok, e = pc._merged_unique(G, _q(0), _q(1), [_q("1/3")])    # the split on the root: both parts hold it
        assert ok and e.is_finite() and e.contains(_q("1/3")) and e.rad() < arb(2) ** -100
        assert pc._merged_unique(G, _q(0), _q(1), [_q("1/2")]) == (False, None)   # one part holds no root
        assert pc._merged_unique(G, _q(0), _q(1), [_q(2)]) == (False, None)       # a split outside the piece
        assert pc._merged_unique(G, _q(0), _q(1), [_q("1/3"), _q("1/4")]) == (False, None)   # out of order
        assert pc._merged_unique(G, _q(0), _q(3), [_q("1/3")]) == (False, None)   # a part holds two roots
        assert pc._merged_unique(G, _q(0), _q(3), [_q(1)]) == (False, None)       # two roots, one in each part
        ok, e = pc._merged_unique(G, _q(0), _q(1), [_q("1/4"), _q("1/3")])    # three parts: the middle holds it
        assert not ok                                                          # the first part holds no root


def test_envelope_root_free_needs_a_positive_bound():
    with working_precision(128):
        sp = Spectrum(_model(_cert_params(H="10000")).params)
        lo, hi = _q("0.6"), _q("0.7")
        low = pc._envelope_lower(sp, lo, hi)
        assert low is not None and pc._envelope_root_free(sp, lo, hi) == bool(low > 0)
        assert pc._envelope_lower(sp, hi, lo) is None                       # an inverted piece
        assert pc._envelope_lower(sp, _q(0), hi) is None                    # the piece must start after 0
        assert not pc._envelope_root_free(sp, hi, lo)


def _cert_params(**params) -> dict:
    return dict(load_scene("roitenberg1947").parameters, **params)


def _model(params: dict):
    scene = dataclasses.replace(load_scene("roitenberg1947"), parameters=params)
    return kind_module("periodic_orbit").validate(scene)


def _roots(data) -> tuple[Spectrum, list[arb], list[dict]]:
    """The checker's spectrum, the root enclosures of the unique pieces and their stored classifications
    (call inside a working precision)."""
    sp = Spectrum(_model(data["scene"]["parameters"]).params)
    G = pc._G(sp, _hp(data).get("function", "g"))
    roots = [pc._newton(G, _iv(p["lo"], p["hi"]))[1] for p in _hp(data)["pieces"] if p["kind"] == "unique"]
    return sp, roots, _hp(data)["roots"]


def test_every_stored_classification_is_re_verified(roit):
    with working_precision(2 * roit["precision_bits"]):
        sp, roots, ws = _roots(roit)
        assert len(roots) == len(ws) == 6
        assert all(pc._classify(sp, th, w)[0] for th, w in zip(roots, ws))


def test_a_forged_classification_is_not_verified(roit):
    with working_precision(2 * roit["precision_bits"]):
        sp, roots, ws = _roots(roit)
        g = next(i for i, w in enumerate(ws) if w["kind"] == "genuine")
        s = next(i for i, w in enumerate(ws) if w["kind"] == "spurious")
        th, gw, th_s, sw = roots[g], ws[g], roots[s], ws[s]

        def bad(theta, w, **edit):
            w = dict(w, **edit)
            for k, v in list(w.items()):
                if v is None:
                    del w[k]
            return not pc._classify(sp, theta, w)[0]

        # the genuine root's evidence: each end interval, each middle piece, the tiling
        assert bad(th, gw, kind="spurious", witness_t=None, d1=None, right_start=None, middle=None)  # beta'(0) > 0
        assert bad(th, gw, kind="spurious", witness_t=sw["witness_t"])   # a t past theta: beta(t) < 0 claimed there
        assert bad(th, gw, kind="spurious", witness_t=str(Fraction(gw["d1"]) / 2))   # beta > 0 there
        assert bad(th, gw, kind="maybe")
        assert bad(th, gw, d1="0")                                        # d1 > 0
        assert bad(th, gw, d1=str(Fraction(gw["right_start"]) * 2))      # beta' > 0 on [0, d1]: not past the top
        assert bad(th, gw, right_start=gw["d1"])                          # beta' < 0 on [right_start, theta]
        assert bad(th, gw, right_start=str(Fraction(th.upper().mid().str(40, radius=False)) * 2))  # past theta
        assert bad(th, gw, middle=[])                                     # nothing between d1 and right_start
        a, b = gw["middle"][0]
        mid = str((Fraction(a) + Fraction(b)) / 2)
        assert bad(th, gw, middle=[[mid, b]])                             # the middle starts after d1
        assert bad(th, gw, middle=[[a, mid]])                             # the middle ends before right_start
        q = str((Fraction(a) + 3 * Fraction(b)) / 4)
        assert bad(th, gw, middle=[[a, mid], [q, b]])                     # a gap in the middle
        assert not bad(th, gw, middle=[[a, q], [mid, b]])                 # overlapping pieces tile
        assert bad(th, gw, middle=[["0", b]])                             # beta(0) = 0 on the first piece
        # a spurious root's witness
        assert bad(th_s, sw, witness_t="0")                               # t > 0
        assert bad(th_s, sw, witness_t=str(Fraction(th_s.upper().mid().str(40, radius=False)) * 2))   # t < theta
        assert bad(th_s, sw, witness_t=None) == (not _bd0_negative(sp, th_s))   # then beta'(0) < 0 decides
        assert bad(th, gw, kind="spurious", witness_t=gw["right_start"])  # beta > 0 before theta* (the top of beta)


def _bd0_negative(sp, theta) -> bool:
    from rigor_gyro.kinds.periodic_orbit.flow import x0_at
    return x0_at(sp, theta)[1] < 0


def test_the_multipliers_are_the_stored_ones_sorted_with_the_liouville_product(roit, unstable, stiff):
    from rigor_gyro.core.stored import encloses, interval as stored_interval
    for data in (roit, unstable, stiff):
        q = data["quantities"]
        with working_precision(2 * data["precision_bits"]):
            sp, roots, ws = _roots(data)
            main = next(th for th in roots if encloses(stored_interval(q["theta_star"]), th))
            m = pc._multipliers(sp, main)
            assert len(m) == 4
            mods = [abs(z) for z in m]
            assert all(not (mods[i + 1] > mods[i]) for i in range(3))          # decreasing moduli
            for j, z in enumerate(m, start=1):
                assert encloses(stored_interval(q[f"multiplier_{j}_re"]), z.real)
                assert encloses(stored_interval(q[f"multiplier_{j}_im"]), z.imag)
                assert encloses(stored_interval(q[f"multiplier_modulus_{j}"]), mods[j - 1])
            P = sp.P
            det = m[0] * m[1] * m[2] * m[3]
            liou = -(-((1 / ball(P.tau) + 1 / ball(P.sigma)) * main)).exp()
            assert det.is_finite() and det.overlaps(liou)   # Liouville: det J = -exp(-(1/tau + 1/sigma) theta) (the half-period map's -1)
            for z in m:                     # real multipliers have an exact zero imaginary part
                if not any(z.conjugate().overlaps(w) for w in m if w is not z):
                    assert z.imag.is_zero()
            assert mods[3] > 0 and mods[3].rad() < mods[3] * arb(2) ** -20   # the smallest: separated from 0
            for k in range(3):              # a conjugate pair: Im > 0 first
                if m[k].conjugate().overlaps(m[k + 1]) and not m[k].imag.is_zero():
                    assert m[k].imag > 0 and m[k + 1].imag < 0


# ------------------------------------------------------------------------------ whole certificates

def test_the_built_in_and_refuted_certificates_confirm_item_by_item(roit, unstable, short, stiff):
    for data in (roit, unstable, short, stiff):
        it = _items(copy.deepcopy(data))
        assert all(it.values()), {k: v for k, v in it.items() if not v}
    assert {"half_period", "orbit_genuine", "initial_point", "multipliers", "stable", "quantities",
            "roots"} <= set(_items(copy.deepcopy(roit)))
    assert _claim(unstable, "stable")["status"] == "refuted" and _claim(roit, "stable")["status"] == "proved"
    assert _hp(short)["covers_all"] is False and _claim(short, "half_period")["status"] == "proved"


def test_each_claim_with_its_status_flipped_is_not_confirmed(roit, unstable):
    for data in (roit, unstable):
        for cid, status, it in flipped(data):
            assert it[cid] is False, (cid, status)


def test_a_claim_left_inconclusive_by_a_search_to_t_max_cannot_be_refuted(short):
    for cid in ("orbit_genuine", "initial_point", "multipliers", "stable"):
        bad = copy.deepcopy(short)
        _claim(bad, cid)["status"] = "refuted"
        assert _items(bad)[cid] is False, cid
    for cid in ("orbit_genuine", "initial_point", "multipliers", "stable"):
        bad = copy.deepcopy(short)
        _claim(bad, cid)["status"] = "proved"
        assert _items(bad)[cid] is False, cid


def test_an_inconclusive_claim_claims_nothing(roit):
    for cid in ("half_period", "orbit_genuine", "stable"):
        bad = copy.deepcopy(roit)
        _claim(bad, cid)["status"] = "inconclusive"
        assert _items(bad)[cid] is True


def test_an_unknown_claim_or_function_is_never_confirmed(roit):
    bad = copy.deepcopy(roit)
    bad["claims"].append(dict(_claim(bad, "stable"), id="bounded"))
    assert _items(bad)["bounded"] is False
    bad = copy.deepcopy(roit)
    _hp(bad)["function"] = "h"
    it = _items(bad)
    assert it["half_period"] is False and "quantities" not in it      # nothing else is decided without it


def _split_piece(pcs, i, kind_left, kind_right):
    p = pcs[i]
    mid = str((Fraction(p["lo"]) + Fraction(p["hi"])) / 2)
    pcs[i:i + 1] = [dict(p, hi=mid, kind=kind_left), dict(p, lo=mid, kind=kind_right)]


def _forge_half_period(data, edit) -> dict:
    bad = copy.deepcopy(data)
    w = _hp(bad)
    pcs = w["pieces"]
    u = next(i for i, p in enumerate(pcs) if p["kind"] == "unique")
    e = next(i for i, p in enumerate(pcs) if p["kind"] == "empty" and "by" not in p)
    m = next(i for i, p in enumerate(pcs) if p.get("by") == "monotone")
    if edit == "a gap at theta_min":
        pcs[0]["lo"] = str(Fraction(pcs[0]["lo"]) * 2)
    elif edit == "short of T":
        pcs[-1]["hi"] = str((Fraction(pcs[-1]["lo"]) + Fraction(pcs[-1]["hi"])) / 2)
    elif edit == "a gap between pieces":
        pcs[e]["lo"] = str((Fraction(pcs[e]["lo"]) + Fraction(pcs[e]["hi"])) / 2)
    elif edit == "a gap before the last piece":
        pcs[-1]["lo"] = str((Fraction(pcs[-1]["lo"]) + Fraction(pcs[-1]["hi"])) / 2)
    elif edit == "an empty piece called unique, the classifications unchanged":
        pcs[e]["kind"] = "unique"
    elif edit == "no pieces":
        pcs.clear()
    elif edit == "T beyond the pieces":
        w["T"] = str(Fraction(w["T"]) * 2)
    elif edit == "theta_min before the pieces":
        w["theta_min"] = str(Fraction(pcs[0]["lo"]) / 2)
    elif edit == "the tail cut short":
        k = len(pcs) // 2
        del pcs[k:]
        w["T"] = pcs[-1]["hi"]
        w["roots"] = w["roots"][:sum(p["kind"] == "unique" for p in pcs)]
    elif edit == "not all of (0, oo)":
        w["covers_all"] = False
    elif edit == "a root called empty":
        pcs[u]["kind"] = "empty"
        del w["roots"][0]
    elif edit == "a root called monotone-empty":
        pcs[u]["kind"] = "empty"
        pcs[u]["by"] = "monotone"
        del w["roots"][0]
    elif edit == "a root called envelope-empty":
        pcs[u]["kind"] = "empty"
        pcs[u]["by"] = "envelope"
        del w["roots"][0]
    elif edit == "an empty piece called unique":
        pcs[e]["kind"] = "unique"
        k = sum(p["kind"] == "unique" for p in pcs[:e])
        w["roots"].insert(k, dict(w["roots"][0]))
    elif edit == "a monotone piece called unique":
        pcs[m]["kind"] = "unique"
        pcs[m].pop("by")
        k = sum(p["kind"] == "unique" for p in pcs[:m])
        w["roots"].insert(k, dict(w["roots"][0]))
    elif edit == "an unknown piece kind":
        pcs[e]["kind"] = "probably empty"
    elif edit == "a unique piece split in two":
        _split_piece(pcs, u, "unique", "unique")
        w["roots"].insert(0, dict(w["roots"][0]))
    elif edit == "a unique piece with a split off its root":
        pcs[u]["splits"] = [str((Fraction(pcs[u]["lo"]) + 3 * Fraction(pcs[u]["hi"])) / 4)]
    elif edit == "a classification missing":
        del w["roots"][-1]
    elif edit == "a classification too many":
        w["roots"].append(dict(w["roots"][0]))
    elif edit == "a genuine root called spurious":
        g = next(i for i, r in enumerate(w["roots"]) if r["kind"] == "genuine")
        w["roots"][g] = {"kind": "spurious"}
    elif edit == "a spurious witness moved":
        s = next(i for i, r in enumerate(w["roots"]) if r["kind"] == "spurious")
        w["roots"][s]["witness_t"] = "0"
    else:
        raise AssertionError(edit)
    return bad


HALF_PERIOD_FORGERIES = [
    "a gap at theta_min", "short of T", "a gap between pieces", "no pieces", "T beyond the pieces",
    "theta_min before the pieces", "the tail cut short", "a gap before the last piece",
    "an empty piece called unique, the classifications unchanged", "not all of (0, oo)", "a root called empty",
    "a root called monotone-empty", "a root called envelope-empty", "an empty piece called unique",
    "a monotone piece called unique", "an unknown piece kind", "a unique piece split in two",
    "a unique piece with a split off its root", "a classification missing", "a classification too many",
    "a genuine root called spurious", "a spurious witness moved"]


@pytest.mark.parametrize("edit", HALF_PERIOD_FORGERIES)
def test_a_forged_half_period_witness_fails_at_half_period(roit, edit):
    it = _items(_forge_half_period(roit, edit))
    assert it["half_period"] is False, edit


def test_a_forged_witness_of_the_refuted_scene_fails_too(unstable):
    for edit in ("a root called envelope-empty", "the tail cut short", "a genuine root called spurious"):
        it = _items(_forge_half_period(unstable, edit))
        assert it["half_period"] is False and it["stable"] is False, edit
    bad = copy.deepcopy(unstable)
    env = next(p for p in _hp(bad)["pieces"] if p.get("by") == "envelope")
    env["lo"], env["hi"] = env["hi"], env["lo"]                 # an inverted envelope piece
    assert _items(bad)["half_period"] is False


def test_a_search_to_t_max_must_reach_t_max(short):
    bad = copy.deepcopy(short)
    w = _hp(bad)
    w["T"] = str(Fraction(w["T"]) / 2)
    assert _items(bad)["half_period"] is False
    bad = copy.deepcopy(short)
    del _hp(bad)["pieces"][-1]
    _hp(bad)["T"] = _hp(bad)["pieces"][-1]["hi"]
    assert _items(bad)["half_period"] is False
    bad = copy.deepcopy(short)
    _hp(bad)["covers_all"] = True                                # the tail bound fails at T = 0.05
    assert _items(bad)["half_period"] is False


def test_a_half_period_witness_must_be_stored(roit):
    bad = copy.deepcopy(roit)
    del bad["witnesses"]["half_period"]
    it = _items(bad)
    assert it["half_period"] is False and it["orbit_genuine"] is False and it["stable"] is False


def test_theta_star_must_hold_a_re_verified_genuine_root(roit, unstable):
    for data in (roit, unstable):
        with working_precision(2 * data["precision_bits"]):
            sp, roots, ws = _roots(data)
            spurious = next(th for th, w in zip(roots, ws) if w["kind"] == "spurious")
            text = {"lo": spurious.lower().str(40, radius=False), "hi": spurious.upper().str(40, radius=False)}
        bad = copy.deepcopy(data)
        bad["quantities"]["theta_star"] = dict(bad["quantities"]["theta_star"], **text)
        it = _items(bad)
        assert it["orbit_genuine"] is False and it["quantities"] is False


@pytest.mark.parametrize("name", ["theta_star", "period", "beta_dot_0", "Omega_0", "i_0", "I_0", "D1", "D5",
                                  "multiplier_modulus_1", "multiplier_modulus_4", "multiplier_1_re",
                                  "multiplier_2_im", "multiplier_3_re", "multiplier_4_im", "stability_margin"])
def test_a_stored_quantity_moved_off_its_value_fails(roit, name):
    bad = copy.deepcopy(roit)
    q = bad["quantities"][name]
    w = Fraction(q["hi"]) - Fraction(q["lo"])
    shift = w * 4 + abs(Fraction(q["hi"])) / 10**6 + Fraction(1, 10**12)
    q["lo"], q["hi"] = str(Fraction(q["lo"]) + shift), str(Fraction(q["hi"]) + shift)
    it = _items(bad)
    assert it.get(name) is False or it["quantities"] is False
    assert it["quantities"] is False


@pytest.mark.parametrize("name", ["theta_star_2", "theta_star_4", "stability_margin_2", "stability_margin_3"])
def test_another_orbits_quantity_moved_off_its_value_fails(unstable, name):
    bad = copy.deepcopy(unstable)
    q = bad["quantities"][name]
    shift = (Fraction(q["hi"]) - Fraction(q["lo"])) * 4 + Fraction(1, 10**9)
    q["lo"], q["hi"] = str(Fraction(q["lo"]) + shift), str(Fraction(q["hi"]) + shift)
    it = _items(bad)
    assert it[name] is False and it["quantities"] is False


def test_an_extra_stored_quantity_is_not_verified(roit):
    bad = copy.deepcopy(roit)
    bad["quantities"]["theta_star_2"] = dict(bad["quantities"]["theta_star"])
    assert _items(bad)["quantities"] is False


@pytest.mark.parametrize("cid, name", [("orbit_genuine", "period"), ("initial_point", "I_0"),
                                       ("initial_point", "beta_dot_0"), ("multipliers", "multiplier_modulus_3"),
                                       ("multipliers", "multiplier_2_im"), ("stable", "stability_margin")])
def test_a_proved_claim_without_a_quantity_it_names_fails_at_its_item(roit, cid, name):
    bad = copy.deepcopy(roit)
    del bad["quantities"][name]
    it = _items(bad)
    assert it[cid] is False and it["quantities"] is True


def test_stable_is_refuted_only_when_every_genuine_orbit_has_a_modulus_above_1(unstable, roit):
    assert _items(copy.deepcopy(unstable))["stable"] is True
    bad = copy.deepcopy(roit)
    _claim(bad, "stable")["status"] = "refuted"
    assert _items(bad)["stable"] is False
    forged = _forge_half_period(unstable, "a classification missing")     # the roots no longer re-verified
    assert _items(forged)["stable"] is False


def test_a_witness_end_at_16384_bits_is_written_and_read_back_exactly():
    """A piece's end at 16384 bits has about 4900 digits: past Python's int-to-text limit (the prover
    crashed writing such a certificate, exit 4, before the texts were written by FLINT)."""
    from rigor_gyro.core.balls import exact_fraction
    from rigor_gyro.core.stored import number
    from rigor_gyro.kinds.periodic_orbit.claims import _q as witness_text
    with working_precision(16384):
        x = arb(arb(fmpq(1, 3)).mid())                      # an exact dyadic point, 16384 bits of mantissa
        assert x.rad() == 0 and exact_fraction(x).denominator.bit_length() > 16000
        assert number(witness_text(x)) == exact_fraction(x)


def _acb_mat_whose_eig(eig):
    """A stand-in for flint's ``acb_mat`` in the checker: ``eig(J, algorithm)`` gives the eigenvalues
    (or raises ValueError, as Arb does when it cannot isolate them)."""
    class Fake:
        def __init__(self, J):
            self.J = J

        def eig(self, algorithm):
            return eig(self.J, algorithm)
    return Fake


def test_the_multipliers_fall_back_to_rumps_algorithm_and_to_none(roit, monkeypatch):
    """When one eigenvalue algorithm cannot isolate the spectrum (a ValueError) the other is used; when
    neither can, there are no multipliers, and a proved multipliers claim is not confirmed."""
    from flint import acb_mat
    from rigor_gyro.core.stored import encloses, interval as stored_interval
    refused = []

    def only(allowed):
        def eig(J, algorithm):
            if algorithm not in allowed:
                refused.append(algorithm)
                raise ValueError(f"{algorithm} refused")
            return acb_mat(J).eig(algorithm=algorithm)
        return _acb_mat_whose_eig(eig)

    q = roit["quantities"]
    with working_precision(2 * roit["precision_bits"]):
        sp, roots, ws = _roots(roit)
        main = next(th for th in roots if encloses(stored_interval(q["theta_star"]), th))
        monkeypatch.setattr(pc, "acb_mat", only({"rump"}))
        m = pc._multipliers(sp, main)
        assert refused == ["vdhoeven_mourrain"] and m is not None
        for j, z in enumerate(m, start=1):
            assert encloses(stored_interval(q[f"multiplier_modulus_{j}"]), abs(z))
        monkeypatch.setattr(pc, "acb_mat", only(set()))
        assert pc._multipliers(sp, main) is None
    it = _items(copy.deepcopy(roit))
    assert it["multipliers"] is False and it["stable"] is False and it["half_period"] is True


def test_a_degenerate_spectrum_leaves_every_claim_inconclusive_and_confirms_nothing_else():
    """-1/sigma a root of the cubic (4) (A = B = H = tau = 1, n = 5/4, sigma = 2): no closed form; the
    prover says inconclusive, and the checker confirms exactly that."""
    data = _cert(A="1", B="1", H="1", tau="1", sigma="2", n="5/4")
    assert {c["status"] for c in data["claims"]} == {"inconclusive"}
    it = _items(copy.deepcopy(data))
    assert set(pc.REQUIRED) | {"half_period"} <= set(it) and all(it.values())
    for cid in ("half_period", "orbit_genuine", "stable"):
        for status in ("proved", "refuted"):
            bad = copy.deepcopy(data)
            _claim(bad, cid)["status"] = status
            assert _items(bad)[cid] is False, (cid, status)


def test_the_tail_bound_must_be_certainly_positive(roit, monkeypatch):
    from flint import arb as _arb
    monkeypatch.setattr(pc, "tail_bound", lambda sp, T: _arb(0, 1))          # [-1, 1]: undecided
    assert _items(copy.deepcopy(roit))["half_period"] is False
    monkeypatch.setattr(pc, "tail_bound", lambda sp, T: _arb(1))
    assert _items(copy.deepcopy(roit))["half_period"] is True


def test_a_search_that_ends_exactly_at_t_max_is_complete(short):
    """T = T_max = 1/20 exactly (not a dyadic number: the prover's T lies above it): still the whole
    range (0, T_max]."""
    bad = copy.deepcopy(short)
    w = _hp(bad)
    assert Fraction(w["T"]) > Fraction(1, 20) >= Fraction(w["pieces"][-1]["lo"])
    w["T"] = w["pieces"][-1]["hi"] = "1/20"
    assert _items(bad)["half_period"] is True


def test_a_spurious_root_relabelled_genuine_is_no_orbit(roit):
    """theta* moved onto a spurious root relabelled genuine (with the genuine root's classification):
    the classification fails, and so does every claim about the orbit."""
    bad = copy.deepcopy(roit)
    w = _hp(bad)
    with working_precision(2 * roit["precision_bits"]):
        sp, roots, ws = _roots(roit)
        s = next(i for i, r in enumerate(ws) if r["kind"] == "spurious")
        th = roots[s]
        bad["quantities"]["theta_star"] = dict(bad["quantities"]["theta_star"], lo=th.lower().str(40, radius=False),
                                               hi=th.upper().str(40, radius=False))
    w["roots"][s] = dict(next(r for r in ws if r["kind"] == "genuine"))
    it = _items(bad)
    assert it["half_period"] is False and it["orbit_genuine"] is False and it["initial_point"] is False
    assert it["stable"] is False and it["multipliers"] is False


def test_multipliers_are_proved_only_with_the_main_orbits_own(unstable, monkeypatch):
    """The four orbits of H = 10000: without the main orbit's multipliers (its eigenvalues not
    isolated) the multipliers claim is not confirmed, even with the other three's."""
    from rigor_gyro.core.stored import encloses, interval as stored_interval
    real = pc._multipliers
    s = stored_interval(unstable["quantities"]["theta_star"])
    monkeypatch.setattr(pc, "_multipliers", lambda sp, th: None if encloses(s, th) else real(sp, th))
    it = _items(copy.deepcopy(unstable))
    assert it["multipliers"] is False and it["half_period"] is True


def test_a_certificate_of_some_claims_only_confirms():
    for only in (["half_period"], ["half_period", "stable"]):
        scene = dataclasses.replace(load_scene("roitenberg1947"), name="variant", claims_only=only)
        data = json.loads(json.dumps(prove_scene(scene).to_json()))
        it = _items(data)
        assert [c["id"] for c in data["claims"]] == only and all(it.values()) and set(only) <= set(it), it


def test_the_checkers_functions_are_g_and_the_pole_free_g_with_the_same_signs(roit):
    """A witness may name g itself (older certificates) or G = g K (K > 0): the checker evaluates the one
    named, and the two have the same sign at every point where both are decided."""
    from rigor_gyro.kinds.periodic_orbit.flow import g_coeffs, pole_free_coeffs
    with working_precision(128):
        sp = Spectrum(_model(roit["scene"]["parameters"]).params)
        g, G = pc._G(sp, "g"), pc._G(sp, "pole_free")
        for t in ("0.01", "0.05", "0.1", "0.2", "0.5"):
            x = _q(t)
            ref_g, ref_G = g_coeffs(sp, x, 1)[0], pole_free_coeffs(sp, x, 1)[0]
            assert g.at(x).is_finite() and ref_g.is_finite() and g.at(x).overlaps(ref_g) and g.at(x).rad() < arb(2) ** -60 * (1 + abs(g.at(x)))
            assert G.at(x).is_finite() and ref_G.is_finite() and G.at(x).overlaps(ref_G)
            assert not g.at(x).overlaps(G.at(x))                  # different functions
            assert pc._strict_sign(g.at(x)) * pc._strict_sign(G.at(x)) == 1
            gx, dgx = g.both(_iv(t, t))
            ref_dg = g_coeffs(sp, x, 2)[1]
            assert gx.is_finite() and gx.overlaps(g.at(x)) and dgx.is_finite() and ref_dg.is_finite() and dgx.overlaps(ref_dg)


def test_the_multipliers_order_and_realness_on_a_made_up_spectrum(roit, monkeypatch):
    """The algorithm's balls replaced by made-up ones (the Liouville product then matches none): sorted
    by decreasing modulus, a conjugate pair with Im > 0 first, a real eigenvalue's Im set to exactly 0,
    and a pair whose imaginary parts straddle 0 kept complex (its conjugate overlaps its twin)."""
    from flint import acb
    from rigor_gyro.core.stored import encloses, interval as stored_interval
    eps = arb(0, arb(2) ** -20)                                   # [+-2^-20]: straddles 0

    q = roit["quantities"]
    with working_precision(2 * roit["precision_bits"]):
        sp, roots, ws = _roots(roit)
        main = next(th for th in roots if encloses(stored_interval(q["theta_star"]), th))
        cases = [
            # (made-up eigenvalues, expected order of (Re, sign of Im) after sorting)
            ([acb("0.5", "-0.1"), acb("0.9", eps), acb("0.5", "0.1"), acb("0.2", eps)],
             [("0.9", 0), ("0.5", 1), ("0.5", -1), ("0.2", 0)]),
            ([acb("0.9"), acb("0.5", "0.1"), acb("0.5", "-0.1"), acb("0.2")],
             [("0.9", 0), ("0.5", 1), ("0.5", -1), ("0.2", 0)]),
            ([acb("0.7", eps), acb("0.7", eps), acb("0.3"), acb("0.1")],     # a close pair straddling the axis
             [("0.7", None), ("0.7", None), ("0.3", 0), ("0.1", 0)]),
        ]
        for spectrum, expected in cases:
            monkeypatch.setattr(pc, "acb_mat", _acb_mat_whose_eig(lambda J, algorithm, spectrum=spectrum: list(spectrum)))
            m = pc._multipliers(sp, main)
            for z, (re, im) in zip(m, expected):
                assert z.real.is_finite() and z.real.overlaps(arb(re)) and abs(z.real - arb(re)) < arb("1e-6"), (spectrum, m)
                if im == 0:
                    assert z.imag.is_zero(), m                        # real: exactly 0
                elif im is None:
                    assert not z.imag.is_zero() and z.imag.is_finite() and z.imag.contains(0), m   # kept a complex ball
                else:
                    assert (z.imag > 0) if im > 0 else (z.imag < 0), m
