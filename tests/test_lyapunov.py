"""The Lyapunov scene (Agafonov et al. 2013): claims, audit, witnesses, bad input, extreme cases.

Reference values are independent mpmath computations (30-50 digits, closed forms / quadrature) made
outside the library (see tests/reference_values.py for the eigenfrequency counterpart)."""
from fractions import Fraction

import pytest
from flint import arb

from rigor_gyro import cli
from rigor_gyro.core.balls import certainly_gt, certainly_lt, certainly_positive, working_precision
from rigor_gyro.certificate import AuditStatus, Status
from rigor_gyro.kinds.lyapunov.model import hypot_ball
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene, parse_scene

# independent mpmath references (closed forms for the sine law, quadrature for the linear law)
REF = {"m": "7.874015748031496062992125984251968503937", "M": "101.41040421840341890",
       "p": "133.3333333333333333333", "k_min": "0.16933333333333333333", "mu_max": "0.031496062992125984252",
       "R1": "0.0182811298148637", "R2": "0.0106280050148469", "c_star": "23.4283841958462670",
       "mu_best": "0.0199527665332817", "R_sup_at_mu_best": "0.0240775499389226"}
M_LINEAR = "108.73968775143216"

BASE = dict(load_scene("agafonov2013").parameters)


def scene(name="t", options=None, **changes):
    p = dict(BASE, **changes)
    text = f'name = "{name}"\nkind = "lyapunov"\n[parameters]\n' + "".join(f'{k} = "{v}"\n' for k, v in p.items())
    if options:
        text += "[options]\n" + "".join(f'{k} = "{v}"\n' for k, v in options.items())
    return parse_scene(text, name)


@pytest.fixture(scope="module")
def example():
    return prove_scene(load_scene("agafonov2013"))


def near(ball, ref, rel):
    r = Fraction(ref)
    with working_precision(128):
        return certainly_lt(abs(ball - arb(ref)), arb(str(float(abs(r) * Fraction(rel)))))


def test_example_every_claim_proved(example):
    assert {c.id: c.status for c in example.claims} == {c: Status.PROVED for c in (
        "constants", "damping_condition", "vdot_nonpositive", "psi_test", "vdot_direct", "v_positive", "invariant_estimate",
        "largest_sublevel", "equilibria", "best_mu", "best_mu_direct")}
    assert example.precision_bits == 64


@pytest.mark.parametrize("name", ["m", "M", "p", "k_min", "mu_max", "R1", "R2", "c_star"])
def test_example_quantities_contain_the_references(example, name):
    q = example.quantities[name]
    ref = REF[name]
    digits = len(ref.replace(".", "").lstrip("0")) - 1
    with working_precision(256):
        assert q.is_finite() and q.overlaps(arb(ref) + arb(0, 10.0 ** -(digits - 1) * abs(float(ref))))
    assert near(q, ref, "1e-12")


def test_example_best_mu_and_R_max(example):
    q = example.quantities
    assert near(q["mu_best"], REF["mu_best"], "1e-9")
    assert near(q["R_sup_at_mu_best"], REF["R_sup_at_mu_best"], "1e-10")
    # R_max is certified and no larger than the supremum, and beats the paper's R and ours
    assert certainly_lt(q["R_max"], q["R_sup_at_mu_best"] + arb("1e-15"))
    assert certainly_gt(q["R_max"], arb("0.018")) and certainly_gt(q["R_max"], q["R"])


def test_the_direct_test_over_mu_beats_the_psi_test_and_bounds_every_mu(example):
    """best_mu_direct: R_direct_max certified at mu_direct, within 1e-6 of the certified bound over (16), and
    larger than the Psi test's best (R_max) and the direct test at the scene's mu. Independently, the
    mpmath estimate of the direct supremum (a point search on the analytic grad V . f) lies in
    [R_direct_max, bound] at mu_direct and below the bound at four mu across (16)."""
    q = example.quantities
    R, U, mu = q["R_direct_max"], q["R_direct_sup_upper_bound"], q["mu_direct"]
    assert certainly_lt(q["mu_min"], mu) and certainly_lt(mu, q["mu_max"])
    assert certainly_lt(R, U) and certainly_lt(q["R_direct_max_relative_gap"], arb("1e-6"))
    assert certainly_gt(R, q["R_max"] * arb("1.15")) and certainly_gt(R, q["R_direct"] * arb("1.15"))
    mu_text = example.claim("best_mu_direct").details["mu_direct"]
    est = mp_R_direct(dict(BASE, mu=mu_text), dps=30)
    assert float(R.lower()) <= est <= float(U.upper()) * (1 + 1e-9)
    lo, hi = float(q["mu_min"].mid()), float(q["mu_max"].mid())
    for j in (1, 3, 5, 7):
        m = lo + (hi - lo) * j / 8
        assert mp_R_direct(dict(BASE, mu=f"{m:.12g}"), dps=15) <= float(U.upper()) * (1 + 1e-9)


def mp_R_direct(params, dps):
    """An mpmath estimate of the direct supremum inf A/|B|: approx.mp_polar_estimates' R_direct alone (the same
    mpmath values of the analytic grad V . f, the same grid-then-compass search), without its c_max search,
    which the test above does not read (issue 41: half the cost)."""
    import math

    import mpmath
    from rigor_gyro.kinds.lyapunov.approx import MpGimbal
    from rigor_gyro.kinds.lyapunov.search import grid_then_compass
    with mpmath.workdps(dps):
        g = MpGimbal(params)

        def ratio(u, s):
            x2, t = g.xs * u, mpmath.pi * s
            c, sn = mpmath.cos(t), mpmath.sin(t)
            v1 = g.grad_V_dot_f(c, x2, sn)
            B = -g.grad_V_dot_f(2 * c, x2, 2 * sn) / 4 + v1
            A = -v1 - B
            return (float(A / abs(B)) if B != 0 and A > 0 else math.inf), None
        return grid_then_compass(ratio, (17, 33), 90)[0]


def test_a_warm_search_stuck_in_a_local_minimum_does_not_fix_a_poor_mu():
    """Review regression (A2 = 1e-6, C1 = 0): the warm-started point searches of the branch and bound over
    mu stuck at s ~ 0 and put the radius at 40667 where it is about 1470; the claim chose that mu and a gap
    of 26.7. The cold search at mu_direct now exposes it, the branch and bound is redone with cold searches,
    and the radius certified is within 1e-4 of the bound over (16)."""
    import dataclasses
    c = prove_scene(dataclasses.replace(scene("stuck", A2="1e-6", C1="0"), claims_only=["best_mu_direct"]))
    claim = c.claim("best_mu_direct")
    assert claim.status is Status.PROVED, claim.reason
    assert certainly_lt(c.quantities["R_direct_max_relative_gap"], arb("1e-4"))
    assert certainly_gt(c.quantities["R_direct_max"], arb(12000))


def test_the_direct_radius_bound_holds_at_every_mu_of_a_ball():
    """direct_radius_upper over a mu ball (monotone end or ball evaluation) is >= the point value A/|B| at
    every mu sampled in the ball, at several (x2, t) points, and never below R_dsup at those mu."""
    from flint import fmpq
    from rigor_gyro.kinds.lyapunov.polar_forms import direct_radius_upper, vdot_polar
    g = validate(scene()).gimbal
    xs = g.c.x2_star
    cases = [(u, s, a, b) for u, s in ((fmpq(-1), fmpq(1, 2)), (fmpq(-1), fmpq(1, 3)), (fmpq(1, 3), fmpq(1, 5)),
                                       (fmpq(1), fmpq(9, 10)))
             for a, b in (("0.014", "0.016"), ("0.02", "0.0200001"), ("0.023", "0.0235"), ("0.028", "0.031"))]
    cases += [(fmpq(-1), fmpq(1, 2), "0.0005", "0.001"),     # A < 0 at every mu: the bound is 0
              (fmpq(1, 2), fmpq(0), "0.03", "1"),            # d rho/d mu of no certain sign: the ball evaluation
              (fmpq(1, 3), fmpq(1, 5), "0.03", "1")]
    for u, s, a, b in cases:
        Mu = arb(a).union(arb(b))
        bound = direct_radius_upper(g, u, s, Mu)
        best = arb(0)
        for j in range(41):
            m = arb(a) + (arb(b) - arb(a)) * j / 40
            A, B = vdot_polar(g, xs * arb(u), arb.pi() * arb(s), m)
            if certainly_positive(abs(B)):
                rho = A.max(arb(0)) / abs(B)
                assert not certainly_lt(bound, rho), (u, s, a, b, j)
                best = best.max(rho)
        # and tight: the maximum of rho at the end the slope points to (or the ball's own evaluation,
        # which the H^2 cancellation leaves within 1e-5 here), never the looser ball over a monotone piece
        assert bound.is_finite() and certainly_lt(bound, best * (1 + arb("1e-4")) + arb("1e-12")), (u, s, a, b)
    # a point outside the range |x2| <= x2* bounds nothing (Vdot > 0 there is not in the cylinder)
    Mu = arb("0.02").union(arb("0.021"))
    assert direct_radius_upper(g, fmpq(1), fmpq(1, 2), Mu).is_finite()
    for u in (fmpq(3, 2), fmpq(-2), fmpq(1) + fmpq(1, 10 ** 30)):
        assert not direct_radius_upper(g, u, fmpq(1, 2), Mu).is_finite()


def test_example_widths(example):
    for name in ("m", "M", "p", "R1", "R2", "c_star"):
        x = example.quantities[name]
        assert certainly_lt(x.rad() / abs(x), arb("1e-14")), name


def test_example_audit(example):
    rows = {r.id: r.status for r in example.paper}
    assert rows["(8)"] is AuditStatus.MISPRINT
    assert rows["m definition"] is AuditStatus.MISPRINT
    for key in ("A0", "B0", "C0", "m", "M", "p", "k_min", "mu_min", "mu_max", "R1"):
        assert rows[key] is AuditStatus.AGREES, key
    assert rows["R2"] is AuditStatus.DISAGREES
    assert rows["R = R1"] is AuditStatus.REFUTED
    assert rows["region as printed"] is AuditStatus.REFUTED          # x1^2 + x3^2 < 0.018: Vdot > 0 inside
    assert rows["region read with R^2"] is AuditStatus.CONFIRMED     # radius 0.018: Vdot <= 0 holds
    assert rows["limit"] is AuditStatus.CONFIRMED


def test_automatic_differentiation_agrees_with_the_derived_form_not_the_printed_one():
    g = validate(load_scene("agafonov2013")).gimbal
    with working_precision(128):
        for x1, x2, x3 in (("0.003", "0.3", "-0.004"), ("-0.01", "-0.5", "0.002"), ("0.001", "0.1", "0.01")):
            a, b, c = arb(x1), arb(x2), arb(x3)
            ad, form, printed = g.vdot(a, b, c), g.vdot_psi(a, b, c), g.vdot_psi(a, b, c, printed=True)
            assert ad.is_finite() and form.is_finite() and ad.overlaps(form)
            assert not ad.overlaps(printed)
        # on the x2 axis Vdot vanishes exactly
        on_axis = g.vdot(arb(0), arb("0.4"), arb(0))
        assert on_axis.is_finite() and on_axis.contains(0)


def test_planted_radius_far_too_large_is_refuted_with_a_checked_witness():
    cert = prove_scene(scene(options={"R": "0.5"}))
    claim = cert.claim("vdot_nonpositive")
    assert claim.status is Status.REFUTED
    w = claim.details["witness"]
    g = validate(scene()).gimbal
    with working_precision(128):
        x1, x2, x3 = (arb(Fraction(w[k].strip("[]").split(",")[0]).__str__()) if "/" in w[k] else
                      arb(w[k].strip("[]").split(",")[0]) for k in ("x1", "x2", "x3"))
        assert certainly_lt(x1 * x1 + x3 * x3, arb("0.25"))
        assert certainly_positive(g.vdot(x1, x2, x3))
    assert cert.claim("invariant_estimate").status is Status.INCONCLUSIVE
    assert cert.exit_code == 1


def test_mu_below_the_range_is_refuted_not_a_crash():
    cert = prove_scene(scene(mu="0.01"))
    assert cert.claim("damping_condition").status is Status.REFUTED
    assert cert.claim("v_positive").status is Status.REFUTED      # mu H < M: V takes values <= 0
    assert cert.claim("best_mu").status is Status.PROVED          # best_mu does not depend on the scene's mu


def test_k_below_k_min_refutes_the_damping_condition():
    cert = prove_scene(scene(k="0.1"))
    assert cert.claim("damping_condition").status is Status.REFUTED
    assert "k > p A0/H" in cert.claim("damping_condition").reason


def test_linear_moment_M_is_not_a():
    cert = prove_scene(scene(moment="linear"))
    M = cert.quantities["M"]
    assert near(M, M_LINEAR, "1e-12")
    assert certainly_gt(M, arb(100))            # the paper's 'M = a in the linear approximation' is not M
    assert cert.verdict is Status.PROVED


@pytest.mark.parametrize("changes", [{"H": "1e6"}, {"a": "1e-6"}, {"x2_star": "1.5"}])
def test_extreme_cases_are_decided_or_honest(changes):
    cert = prove_scene(scene(**changes))
    for c in cert.claims:
        if c.status is Status.INCONCLUSIVE:
            assert "try" in c.reason or "rests on" in c.reason, (c.id, c.reason)
    assert cert.claim("constants").status is Status.PROVED
    assert cert.claim("v_positive").status is not Status.INCONCLUSIVE


def test_removable_singularity_of_q_is_enclosed_at_zero():
    g = validate(load_scene("agafonov2013")).gimbal
    lin = validate(scene(moment="linear")).gimbal
    with working_precision(64):
        for gg in (g, lin):
            q0 = gg.q(arb(0))
            assert q0.is_finite() and q0.contains(100)
            qb = gg.q(arb("0 +/- 0.001"))
            assert qb.is_finite() and qb.contains(100) and certainly_lt(qb.rad(), arb("0.01"))


def test_hypot_ball_never_takes_sqrt_of_negative():
    with working_precision(64):
        h = hypot_ball(arb("0 +/- 1e-3"), arb("0 +/- 1e-3"))
        assert h.is_finite() and h.contains(0) and h.contains(arb(2).sqrt() * arb("1e-3") * arb("0.999"))


def test_twice_the_precision_overlaps():
    a = prove_scene(load_scene("agafonov2013"), prec=64)
    b = prove_scene(load_scene("agafonov2013"), prec=128)
    assert [c.status for c in a.claims] == [c.status for c in b.claims]
    for name, x in a.quantities.items():
        # a float estimate and certified bounds (numbers computed by a search, valid at either precision)
        # are not enclosures of one exact value
        if name in b.quantities and name not in ("R_sup_float_estimate", "R_sup_upper_bound", "R_max_relative_gap",
                                                    "c_max_lower", "c_max_upper", "vdot_level_lower", "vdot_level_upper"):
            assert x.is_finite() and b.quantities[name].is_finite() and x.overlaps(b.quantities[name]), name


BAD = [({"A2": "0", "C1": "0"}, "A0 > C0"), ({"x2_star": "pi/2"}, "x2_star"), ({"x2_star": "2"}, "x2_star"),
       ({"x2_star": "0"}, "x2_star"), ({"k": "0"}, "'k'"), ({"mu": "-1"}, "'mu'"), ({"moment": "cubic"}, "moment"),
       ({"H": "abc"}, "H")]


@pytest.mark.parametrize("changes,needle", BAD)
def test_bad_input_is_exit_2_naming_the_parameter(tmp_path, capsys, changes, needle):
    p = dict(BASE, **changes)
    f = tmp_path / "bad.toml"
    f.write_text('name = "bad"\nkind = "lyapunov"\n[parameters]\n' + "".join(f'{k} = "{v}"\n' for k, v in p.items()))
    assert cli.main(["prove", str(f), "--out", str(tmp_path)]) == 2
    assert needle in capsys.readouterr().err


def test_missing_parameter_and_float_are_exit_2(tmp_path, capsys):
    p = dict(BASE)
    del p["mu"]
    f = tmp_path / "m.toml"
    f.write_text('name = "m"\nkind = "lyapunov"\n[parameters]\n' + "".join(f'{k} = "{v}"\n' for k, v in p.items()))
    assert cli.main(["prove", str(f), "--out", str(tmp_path)]) == 2
    assert "mu" in capsys.readouterr().err
    g = tmp_path / "f.toml"
    g.write_text(f.read_text() + "mu = 0.02\n")
    assert cli.main(["prove", str(g), "--out", str(tmp_path)]) == 2
    assert "mu" in capsys.readouterr().err


@pytest.mark.slow
def test_k_just_above_k_min_is_decided_or_honest():
    cert = prove_scene(scene(k="0.16934", mu="0.0133335"))
    assert cert.claim("damping_condition").status is Status.PROVED
    assert cert.claim("vdot_nonpositive").status is Status.PROVED
    c = cert.claim("invariant_estimate")
    assert c.status is Status.PROVED or "try a smaller R" in c.reason


def test_plots_are_drawn(tmp_path):
    pytest.importorskip("matplotlib")
    assert cli.main(["prove", "agafonov2013", "--out", str(tmp_path), "--quiet", "--plots"]) == 0
    names = sorted(p.name for p in tmp_path.glob("*.png"))
    assert names == ["agafonov2013_psi.png", "agafonov2013_slices.png", "agafonov2013_trajectories.png"]
    assert_figures_have_content(tmp_path.glob("*.png"))


def assert_figures_have_content(paths):
    """Each figure opens as an image of a sensible size that is not one flat colour."""
    import matplotlib.image as mpimg
    import numpy as np
    for path in paths:
        img = mpimg.imread(path)
        assert img.shape[0] > 200 and img.shape[1] > 200, path
        assert float(np.std(img[..., :3])) > 0.02, f"{path} is (nearly) blank"


def test_the_relay_figure_is_drawn(tmp_path):
    pytest.importorskip("matplotlib")
    assert cli.main(["prove", "roitenberg1947", "--out", str(tmp_path), "--quiet", "--plots"]) == 0
    assert [p.name for p in tmp_path.glob("*.png")] == ["roitenberg1947_orbit.png"]
    assert_figures_have_content(tmp_path.glob("*.png"))


def test_mu_best_is_certainly_inside_the_interval(example):
    q = example.quantities
    assert certainly_lt(q["mu_min"], q["mu_best"]) and certainly_lt(q["mu_best"], q["mu_max"])


def test_negative_C0_puts_M_at_the_removable_singularity():
    """C1 > A + A1 makes C0 < 0: q decreases, so M = q(0) = f'(0) = a, attained at the 0/0 point."""
    cert = prove_scene(scene(C1="5"))
    assert cert.claim("constants").status is Status.PROVED
    with working_precision(128):
        assert cert.quantities["M"].is_finite() and cert.quantities["M"].contains(100)
        assert certainly_lt(cert.quantities["M"].rad(), arb("1e-12"))


def test_example_equilibria_are_listed_and_classified(example):
    rows = example.claim("equilibria").details["equilibria"]
    by_x2 = {r["x2"]: r for r in rows}
    assert set(by_x2) == {"0", "pi", "-pi", "pi/2", "-pi/2"}
    assert by_x2["0"]["stability"] == "asymptotically stable" and by_x2["0"]["estimate"] == "inside the estimate"
    assert by_x2["pi/2"]["stability"] == "unstable" and by_x2["-pi/2"]["stability"] == "unstable"
    assert all(r["estimate"].startswith("outside") for x, r in by_x2.items() if x != "0")
    # x1 = -f(pi/2)/k = -a/k = -250 at the equilibrium x2 = pi/2
    assert "-250.00001" in by_x2["pi/2"]["x1"] or "-250" in by_x2["pi/2"]["x1"]


@pytest.mark.parametrize("step, witness", [
    ("S", "0.1"),            # only a psi failure builds a counterexample (S > 0 failing says nothing of V)
    ("f_over_x", "0.1"),
    ("psi", "0"),            # x2 = 0: V = 0 at the origin is no counterexample
    ("psi", "2"),            # beyond x2* (pi/6): outside the region
    ("psi", "inexact"),      # a witness that is not an exact point
    ("psi", "0.0625"),       # exact, but psi > 0 there in fact: V = 0.37 > 0 at the minimiser, no counterexample
])
def test_v_positive_refutes_only_at_an_exact_psi_witness_inside_the_range(monkeypatch, step, witness):
    """The refutation branch of v_positive (mutmut: its guards were untested): a subdivision 'refuted'
    with a witness the claim cannot use leaves the claim inconclusive, never refuted."""
    import rigor_gyro.kinds.lyapunov.claims as C
    from rigor_gyro.core.subdivision import Positivity
    order = ["S", "f_over_x", "psi"]
    calls = []
    real = C.certify_positive

    def fake(fn, lo, hi, **kw):
        if len(calls) >= 3 or kw.get("record") is None:
            return real(fn, lo, hi, **kw)
        calls.append(fn)
        if order[len(calls) - 1] != step:
            return real(fn, lo, hi, **kw)
        w = arb("0.1", "1e-3") if witness == "inexact" else arb(witness)
        return Positivity(Status.REFUTED, 1, witness=w, witness_value=arb(-1), reason="planted")
    monkeypatch.setattr(C, "certify_positive", fake)
    sc = parse_scene('name = "x"\nkind = "lyapunov"\nsource = "t"\n[parameters]\n' +
                     "".join(f'{k} = "{v}"\n' for k, v in BASE.items()) + '[claims]\nonly = ["v_positive"]\n')
    c = prove_scene(sc, maxprec=64).claim("v_positive")
    assert c.status is Status.INCONCLUSIVE, (step, witness, c.reason)


CSTAR_CASE = {"A": "1.43357", "C": "8.88046", "A1": "0.569612", "B1": "5.99438", "C1": "1.98079", "A2": "2.12752",
              "H": "138.715", "k": "0.0808509", "a": "1.25074", "x2_star": "pi/6", "mu": "0.0134819",
              "moment": "sine"}


@pytest.mark.parametrize("params, mu, x2", [
    (None, None, "0"), (None, None, "0.01"), (None, None, "0.3"), (None, None, "0.5"),
    (CSTAR_CASE, "0.016", "0.5"),        # c10 = 0.969: a ci0 in (0, 1]
    (CSTAR_CASE, "0.02", "0.3"),         # c10 < 0: rho = +inf
])
def test_rho_lower_is_a_tight_lower_bound_of_rho(params, mu, x2):
    """rho = max_i |(ci1, ci3)| / ci0 at a point, +inf where some ci0 <= 0 (mutmut: a floor of 1 on the
    bound, 'ci0 <= 1' for 'ci0 <= 0', and |(ci1, ci3)|'s upper end survived: rho is about 25 wherever the
    tests looked). The bound at 64 bits must lie below rho enclosed at 256 bits, and within 1e-15 of it."""
    from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
    from rigor_gyro.kinds.lyapunov.mu_claims import rho_lower
    g, _ = gimbal_from_parameters(params or load_scene("agafonov2013").parameters)

    def direct():
        m = arb(mu) if mu else g.c.mu
        (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(arb(x2), m)
        if not (c10 > 0 and c20 > 0):
            return None
        return ((c11 ** 2 + c13 ** 2).sqrt() / c10).max((c21 ** 2 + c23 ** 2).sqrt() / c20)
    with working_precision(256):
        ref = direct()
    with working_precision(64):
        low = rho_lower(g, arb(x2), arb(mu) if mu else g.c.mu)
    if ref is None:
        assert low == arb("inf")
        return
    assert low <= ref.upper() and low >= ref.lower() * (1 - arb("1e-15"))


def test_rho_lower_over_a_ball_lies_below_rho_at_every_point_of_it():
    """Over a wide x2 ball the bound must stay below rho at each point of the ball (kills |(ci1, ci3)|'s
    upper end used in place of its lower end, which a point test cannot see at 1e-19)."""
    from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
    from rigor_gyro.kinds.lyapunov.mu_claims import rho_lower
    g, _ = gimbal_from_parameters(load_scene("agafonov2013").parameters)
    with working_precision(64):
        low = rho_lower(g, arb("0.3", "0.02"), g.c.mu)
    with working_precision(256):
        pts = []
        for i in range(11):
            (c10, c11, c13), (c20, c21, c23) = g.psi_coefficients(arb("0.28") + arb("0.004") * i, g.c.mu)
            pts.append(((c11 ** 2 + c13 ** 2).sqrt() / c10).max((c21 ** 2 + c23 ** 2).sqrt() / c20))
    assert all(low <= p.lower() for p in pts) and low > 0


def test_a_direct_search_that_misses_the_minimiser_searches_again(monkeypatch):
    """When the float search puts the supremum too high (it found a local minimum of A/|B| only), the
    certification fails at a point where A/|B| is lower; the direct test searches again from there and
    certifies a radius below the supremum, with a certified point above it (stress scene x2* near pi/2:
    inconclusive after 4096 bits before)."""
    from rigor_gyro.kinds.lyapunov import direct_claims as C
    g = validate(load_scene("agafonov2013")).gimbal
    real = C.direct_point_search
    calls = []

    def missing(gg, start=None):
        calls.append(start)
        est, u, s, amin = real(gg, start)
        return (est * 1.3, 0.0, 0.25, amin) if start is None else (est, u, s, amin)
    monkeypatch.setattr(C, "direct_point_search", missing)
    with working_precision(64):
        d = C.certify_direct(g, 4000)
        assert d.cert.status is Status.PROVED and d.point is not None
        assert len(calls) >= 2 and calls[0] is None and calls[1] is not None
        R, up = Fraction(d.R_text), Fraction(d.up_text)
        assert R < up < R * Fraction(1001, 1000)
        assert certainly_positive(g.vdot(*d.point))


def test_a_failed_direct_certification_without_a_lower_point_does_not_search_again():
    from rigor_gyro.core.subdivision import BoxPositivity
    from rigor_gyro.kinds.lyapunov import direct_claims as C
    g = validate(load_scene("agafonov2013")).gimbal
    with working_precision(64):
        sup = C.direct_point_search(g)[0]
        refuted = BoxPositivity(Status.REFUTED, [], witness={"u": Fraction(-1), "s": Fraction(1, 2)})
        assert C._lower_ratio(g, refuted, sup * 0.9) is None                    # A/|B| there is above R
        hit = C._lower_ratio(g, refuted, sup * 1.1)
        assert hit is not None and hit[0] < sup * 1.1 and hit[1:] == (-1.0, 0.5)
        assert C._lower_ratio(g, BoxPositivity(Status.INCONCLUSIVE, [], stuck=None), sup * 2) is None


def test_a_psi_counterexample_lies_in_the_disc_for_every_radius_in_the_ball():
    """psi_counterexample(g, x2, R, which) with R a wide ball (as R = min(R1, R2) over a parameter box
    is): the point must lie in the open disc of radius R.lower(), inside the region whatever R's
    value in the ball, with Psi certainly <= 0 there (mutmut: the disc taken at R.upper() put the
    point outside the region for the smaller radii, a counterexample to nothing)."""
    from rigor_gyro.core.balls import certainly_le
    from rigor_gyro.kinds.lyapunov.vdot_tests import psi_counterexample
    g = validate(load_scene("agafonov2013")).gimbal
    with working_precision(64):
        x2 = arb("0.3")
        # Psi1 = c0 + c1 x1 + c3 x3 at x2 = 0.3: c0 = 61566, |(c1, c3)| = 1437874: <= 0 on the disc's edge
        # from R = 0.04282 on
        R = arb("0.0429").union(arb("0.1"))
        point = psi_counterexample(g, x2, R, 0)
        assert point is not None
        x1, y2, x3, val = point
        assert y2 is x2          # x1, x3: balls around exact rationals (ball_text stores them exactly)
        assert certainly_lt(x1 * x1 + x3 * x3, R.lower() * R.lower())
        (c0, c1, c3), _ = g.psi_coefficients(x2)
        assert certainly_le(val, 0) and val.is_finite() and val.overlaps(c0 + c1 * x1 + c3 * x3)
        assert psi_counterexample(g, x2, arb("0.04"), 0) is None       # Psi1 > 0 on that whole disc


def test_a_vdot_witness_lies_in_the_region_for_every_radius_in_the_ball():
    """vdot_witness with R a wide ball [0.02, 0.3] (agafonov2013: Vdot < 0 is certified up to radius
    0.0241, and a point with Vdot > 0 exists at radius 0.05): the search may only use circles inside the
    disc of radius R.lower(), where Vdot <= 0, so it finds nothing (mutmut-style: circles of R.upper()
    found a point with Vdot > 0 outside the region for the smaller radii); with R = 0.05 it finds one,
    certainly inside that disc."""
    from rigor_gyro.kinds.lyapunov.vdot_tests import vdot_witness
    g = validate(load_scene("agafonov2013")).gimbal
    points = [arb(j) / 20 for j in range(-6, 7)]
    with working_precision(64):
        assert vdot_witness(g, arb("0.02").union(arb("0.3")), points) is None
        x1, x2, x3, v = vdot_witness(g, arb("0.05"), points)
        assert certainly_lt(x1 * x1 + x3 * x3, arb("0.0025")) and certainly_positive(v)
        ref = g.vdot(x1, x2, x3)
        assert v.is_finite() and ref.is_finite() and v.overlaps(ref)


@pytest.mark.parametrize("bounds, U", [((1, 5, 3), 5), ((5, 1), 5), ((2, float("inf"), 1), float("inf"))])
def test_the_direct_bound_over_mu_is_the_largest_piece_bound_in_any_order(monkeypatch, bounds, U):
    """direct_sup_upper_bound takes the largest of the pieces' bounds by exact comparison (+inf if any is
    infinite), not the heap's first piece: the heap orders by a key, and a misordered or tied key must not
    lower the bound (mutmut: U from the first piece only survived, since the heap put the largest first)."""
    from rigor_gyro.kinds.lyapunov import direct_mu
    pieces = [(arb(i), arb(i + 1), arb(b)) for i, b in enumerate(bounds)]
    monkeypatch.setattr(direct_mu, "best_first_bisection", lambda *a, **k: (pieces, len(pieces)))
    monkeypatch.setattr(direct_mu, "direct_point_search", lambda gm, start=None: (0.02, 0.5, 0.25, 0))
    g = validate(load_scene("agafonov2013")).gimbal
    got = direct_mu.direct_sup_upper_bound(g, arb(0), arb(len(bounds)), arb("0.01"))[0]
    assert (got == U) if U != float("inf") else not got.is_finite()
