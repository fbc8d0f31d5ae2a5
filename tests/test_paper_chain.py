"""The relay paper's own chain (issue 39): Roitenberg's numbers recomputed from his printed inputs."""
from __future__ import annotations

import random
from decimal import Decimal
from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.audit import half_unit
from rigor_gyro.core.balls import exact_endpoints, working_precision
from rigor_gyro.core.paper_chain import rounding_interval
from rigor_gyro.kinds.periodic_orbit.flow import RelayParams
from rigor_gyro.kinds.periodic_orbit.paper_chain import _quartic_roots, relay_chains
from rigor_gyro.kinds.periodic_orbit.paper_forms import a_from_exponents
from rigor_gyro.kinds.periodic_orbit.paper_identities import printed_rows, relations
from rigor_gyro.scene import load_scene


@pytest.fixture(scope="module")
def relay():
    sc = load_scene("roitenberg1947_b2over15")
    P = RelayParams.from_strings(**sc.parameters)
    with working_precision(128):
        chains, fixes = relay_chains(sc.paper, P)
    return sc, P, chains, fixes


#: the misprints the program finds by itself (the hand list it replaced had 15 of them)
EXPECTED = {"D1": "0.0417756", "i sin": "-0.202595", "b5,1": "-0.15", "h21": "0.191795", "c15": "-1.234394",
            "z4 (eps4)": "0.348720", "b1,13": "0.0000430652", "b1,18": "0.0638624", "b1,23": "-0.393749",
            "b3,3": "0.000135992", "b3,7": "1.003596", "b3,12": "-0.00359612", "b4,4": "-0.583083",
            "b4,7": "-6.33182", "c23": "0.00016867", "c45": "30.9511", "c21": "-0.945351", "h44": "-9.67965",
            "b4,5": "0.00518755", "b4,13": "1.00338", "c13": "-0.00146070", "Table 2 t=0.06 Omega": "0.0367751",
            "Table 2 t=theta beta'": "-1.234394", "Table 2 t=0.08 beta'": "-0.302404"}


def test_the_misprints_are_found_with_their_intended_numbers(relay):
    _, _, _, fixes = relay
    for rid, intended in EXPECTED.items():
        assert fixes.get(rid) == intended, (rid, fixes.get(rid))


def test_no_number_the_papers_own_inputs_reproduce_is_called_a_misprint(relay):
    """beta sin (= the paper's D1), h11, the k of (24), the quartic and its roots are the paper's arithmetic:
    they differ from the exact values but round the chain."""
    _, _, chains, fixes = relay
    for rid in ["beta sin", "h11", "h41", "D2", "k11", "k31", "k44", "k13", "z2 (eps2)", "b4,11", "b4,6",
                "quartic (25): coefficient of lambda^3",
                "lambda1", "Re lambda2,4", "|lambda2| = |lambda4|", "Table 2 t=0 beta'", "beta'*"]:
        assert rid not in fixes, rid
        assert rid in chains


def test_the_downstream_evidence_and_the_identities_are_named(relay):
    _, _, chains, _ = relay
    assert "h41" in chains["b4,5"].evidence and chains["b4,5"].accepted == "0.00518755"
    assert "D1 = beta sin = h11" in chains["D1"].identity and chains["D1"].computed is not None
    assert "b4,7 + b4,12 = 0" in chains["b4,7"].identity


def test_the_slack_covers_the_papers_own_rounding(relay):
    """DEFAULT_SLACK = 3: prints that lie within 3 units of the last digit outside their computed chain
    exist beyond 2 units (so a slack of 2 would call the paper's own rounding unexplained)."""
    _, _, chains, fixes = relay
    prints = printed_rows(load_scene("roitenberg1947_b2over15").paper)
    worst = Fraction(0)
    for rid, ch in chains.items():
        if rid not in prints or rid in fixes:
            continue
        lo, hi = exact_endpoints(ch.computed if ch.computed is not None else ch.value)
        x = Fraction(prints[rid])
        u = Fraction(10) ** Decimal(prints[rid]).as_tuple().exponent
        d = 0 if lo <= x <= hi else min(abs(x - lo), abs(x - hi)) / u
        if d <= 3:
            worst = max(worst, d)
    assert Fraction(2) < worst <= Fraction(3)


def test_the_identities_hold_on_the_certified_values():
    """Each consistency identity is a theorem about the exact values: on the certified balls of the audit
    rows (B = 2/15) every relation contains its constant."""
    from rigor_gyro.prover import prove_scene
    cert = prove_scene(load_scene("roitenberg1947_b2over15"))
    val = {r.id: r.value for r in cert.paper if r.value is not None}
    rels = relations(Fraction(1, 750), list(load_scene("roitenberg1947_b2over15").paper["table2"]))
    checked = 0
    for rel in rels:
        if not all(r in val for r, _ in rel.terms):
            continue
        s = sum((arb(fmpq(c.numerator, c.denominator)) * val[r] for r, c in rel.terms), arb(0))
        assert s.contains(arb(fmpq(rel.const.numerator, rel.const.denominator))) or \
            abs(s - arb(fmpq(rel.const.numerator, rel.const.denominator))) < arb("1e-12"), rel.name
        checked += 1
    assert checked >= 80


def _mp_a(mu1, om, mu2, isg, P):
    """a_ij of (7) in mpmath (the same eigenvector formulas), at one point."""
    A, B, H, K, p, tau, n = (mpmath.mpf(int(getattr(P, k).p)) / int(getattr(P, k).q)
                             for k in ("A", "B", "H", "K", "p", "tau", "n"))

    def comp(lam):
        return [1, lam, -(B / H) * lam ** 2, (-(A * B / H) * lam ** 3 - H * lam) / K]
    c1, c3 = comp(mpmath.mpc(-mu1, om)), comp(mpmath.mpc(-mu2))
    out = {}
    for g in range(1, 4):
        out[(g + 1, 1)] = c1[g].real
        out[(g + 1, 3)] = c1[g].imag
        out[(g + 1, 5)] = c3[g].real
    lam = -isg
    Om = K * p / ((A * lam + H ** 2 / (B * lam)) * (1 + tau * lam) + n)
    i_ = (p - (n / K) * Om) / (1 + tau * lam)
    bd = -H * Om / (B * lam)
    out[(1, 6)], out[(2, 6)], out[(3, 6)], out[(4, 6)] = bd / lam, bd, Om, i_
    return out


def test_the_a_ij_chain_contains_every_sample_of_the_printed_exponents_intervals():
    """a_from_exponents over the rounding intervals of the printed mu1, omega, mu2, 1/sigma: every value at a
    sampled point of that box (mpmath, 40 digits) lies in the certified enclosure."""
    sc = load_scene("roitenberg1947_b2over15")
    P = RelayParams.from_strings(**sc.parameters)
    texts = [sc.paper[k] for k in ("mu1", "omega", "mu2", "inv_sigma")]
    with working_precision(128):
        encl = a_from_exponents(*(rounding_interval(t) for t in texts), P)
    rng = random.Random(39)
    mpmath.mp.dps = 40
    for _ in range(25):
        pt = []
        for t in texts:
            lo, hi = Fraction(t) - half_unit(t), Fraction(t) + half_unit(t)     # the exact input box
            f = lo + (hi - lo) * Fraction(rng.randint(0, 1000), 1000)
            pt.append(mpmath.mpf(f.numerator) / f.denominator)
        got = _mp_a(*pt, P)
        for key, v in got.items():
            lo, hi = exact_endpoints(encl[key])
            assert mpmath.mpf(lo.numerator) / lo.denominator <= v <= mpmath.mpf(hi.numerator) / hi.denominator, key


def test_the_quartic_roots_enclose_every_sampled_quartic_of_the_family():
    """_quartic_roots over the printed quartic's rounding intervals (Rouche): the roots of sampled members
    (mpmath polyroots) lie in the enclosures."""
    qs = ["-0.0749939", "-0.496319", "-0.332073", "-0.000000348"]
    with working_precision(128):
        roots = _quartic_roots([rounding_interval(t) for t in qs])
    assert roots is not None
    rng = random.Random(25)
    mpmath.mp.dps = 40

    def inside(x, ball):
        lo, hi = exact_endpoints(ball)
        return mpmath.mpf(lo.numerator) / lo.denominator <= x <= mpmath.mpf(hi.numerator) / hi.denominator
    for _ in range(25):
        c = []
        for t in qs:
            lo, hi = Fraction(t) - half_unit(t), Fraction(t) + half_unit(t)     # the exact input box
            f = lo + (hi - lo) * Fraction(rng.randint(0, 1000), 1000)
            c.append(mpmath.mpf(f.numerator) / f.denominator)
        zs = mpmath.polyroots([1] + c, maxsteps=200, extraprec=200)
        real = sorted([z.real for z in zs if abs(z.imag) < mpmath.mpf("1e-30")], key=lambda x: -abs(x))
        cplx = [z for z in zs if z.imag > mpmath.mpf("1e-30")]
        assert inside(real[0], roots["lambda1"]) and inside(real[1], roots["lambda3"])
        assert inside(cplx[0].real, roots["re_complex"]) and inside(cplx[0].imag, roots["im_complex"])
        assert inside(abs(cplx[0]), roots["modulus"])


def test_rudenko_exact_values_share_one_scale_at_the_nearest_eps():
    """The four 'exact' frequencies admit no common Hz scale at the printed eps = 0.1076; the nearest
    four-digit eps that gives them one is 0.1073 (a one-digit change), with a certified witness scale, and
    nothing nearer works (0.1074 .. 0.1078 are refused in balls)."""
    from flint import arb, fmpq
    from rigor_gyro.core.audit import audit_printed
    from rigor_gyro.core.outcome import AuditStatus
    from rigor_gyro.kinds.eigenfrequencies.paper_scale import _fit, _omegas, consistent_eps_row
    a, b, W = fmpq(1508, 100), fmpq(6154, 1000), fmpq(629, 1000)
    exact = ["41.4", "121.5", "521.5", "935.7"]
    row = consistent_eps_row(a, b, fmpq(1076, 10000), W, "0.1076", exact)
    assert row.status is AuditStatus.MISPRINT and row.reading.startswith("eps = 0.1073")
    for k in (1074, 1075, 1076, 1077, 1078):
        assert _fit(exact, _omegas(a, b, fmpq(k, 10000), W)) is None, k
    om = _omegas(a, b, fmpq(1073, 10000), W)
    s = arb(fmpq(3089, 5))
    assert all(audit_printed(x, s * w.sqrt())[0] is AuditStatus.AGREES for x, w in zip(exact, om))
    assert audit_printed("41.4", s * _omegas(a, b, fmpq(1076, 10000), W)[0].sqrt())[0] is not AuditStatus.AGREES \
        or audit_printed("121.5", s * _omegas(a, b, fmpq(1076, 10000), W)[1].sqrt())[0] is not AuditStatus.AGREES


def test_theta_star_is_unexplained_against_the_root_of_12_with_the_printed_inputs(relay):
    """(12) with the printed a_ij read exactly has a root at 0.13826727 (certified sign change): the printed
    theta* = 0.13826994 is neither that nor one edit from it."""
    from rigor_gyro.core.chain_classify import classify_against_chain
    _, _, chains, fixes = relay
    ch = chains["theta*"]
    assert ch.value.contains(arb("0.1382672724705")) and ch.value.rad() < arb("1e-11") and "theta*" not in fixes
    c = classify_against_chain("0.13826994", arb("0.13826742966"), ch)
    assert c.cls == "unexplained" and "0.1382672724" in c.reading
