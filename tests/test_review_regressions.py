"""Regressions for the defects an outside review found (issue 9). Each test failed before its fix.

Item numbers follow the issue: 1 series truncation, 2 restricted search refutes, 3 best_mu overstated,
4 crash exit codes, 5 hangs, 6 typos accepted, 7 scene name as a path, 8 half-written outputs,
9 escalation that cannot help, 10 invariant_estimate tolerance, 11 the smallest multiplier.
"""
import dataclasses

import pytest
from flint import ctx

from rigor_gyro import load_scene, prove_scene
from rigor_gyro.core.balls import SeriesTruncated, ball, series_coefficients, series_length, working_precision
from rigor_gyro.core.outcome import Status
from rigor_gyro.kinds.periodic_orbit import claims as relay_claims
from rigor_gyro.kinds.periodic_orbit.flow import RelayParams, Spectrum, g_coeffs

RELAY = load_scene("roitenberg1947")


def _relay(name: str, **params) -> object:
    return dataclasses.replace(RELAY, name=name, parameters=dict(RELAY.parameters, **params))


# ------------------------------------------------------------------ 1. series cut to ctx.cap terms

def test_1_series_coefficients_refuse_a_series_cut_by_the_cap():
    from flint import acb, acb_series
    cut = acb_series([acb(0.5), 1], prec=13).exp()          # python-flint keeps ctx.cap = 10 terms
    with pytest.raises(SeriesTruncated):
        series_coefficients(cut, 13)
    with series_length(13):
        whole = series_coefficients(acb_series([acb(0.5), 1], prec=13).exp(), 13)
    assert len(whole) == 13 and ctx.cap == 10
    assert not whole[12].contains(0)                        # e^0.5/12! is no zero to pad with


def test_1_g_coeffs_beyond_the_default_cap_are_the_true_coefficients():
    sp_params = RelayParams.from_strings(**RELAY.parameters)
    with working_precision(128):
        sp = Spectrum(sp_params)
        c13 = g_coeffs(sp, ball("0.1"), 13)
        c16 = g_coeffs(sp, ball("0.1"), 16)
    assert len(c13) == 13
    assert c13[12].is_finite() and c16[12].is_finite() and c13[12].overlaps(c16[12]) and not c13[12].contains(0)


@pytest.mark.parametrize("order", [8, 12, 16])
@pytest.mark.parametrize("H, roots", [("100", 6), ("1e3", 16)])
def test_1_relay_roots_do_not_depend_on_the_taylor_order(monkeypatch, order, H, roots):
    from rigor_gyro.kinds.periodic_orbit import g_roots
    monkeypatch.setattr(relay_claims, "TAYLOR_ORDER", order)        # the classification's enclosures
    monkeypatch.setattr(g_roots, "TAYLOR_ORDER", order)             # the root search's
    cert = prove_scene(_relay(f"order{order}", H=H))
    assert cert.verdict is Status.PROVED
    assert len(cert.extra["roots"]) == roots


# ------------------------------------------------------------------ 2. a restricted search never refutes

B215 = load_scene("roitenberg1947_b2over15")


def _b215(name: str, options: dict | None = None, **params):
    return dataclasses.replace(B215, name=name, parameters=dict(B215.parameters, **params),
                               options=dict(options or {}))


def test_2_t_max_below_the_orbit_is_inconclusive_not_refuted():
    cert = prove_scene(_b215("tmax013", {"T_max": "0.13"}))
    statuses = {c.id: c.status for c in cert.claims}
    assert Status.REFUTED not in statuses.values(), statuses
    assert cert.exit_code == 3
    assert statuses["half_period"] is Status.PROVED          # (0, 0.13] is fully searched
    assert "not a refutation" in cert.claim("orbit_genuine").reason


def test_2_stable_orbit_beyond_t_max_leaves_stable_inconclusive():
    """H = 1e3: three unstable genuine orbits below 0.13, the stable one at 0.14127 beyond it."""
    cert = prove_scene(_b215("tmax013h", {"T_max": "0.13"}, H="1000"))
    assert cert.claim("orbit_genuine").status is Status.PROVED
    assert cert.claim("stable").status is Status.INCONCLUSIVE
    assert "not searched" in cert.claim("stable").reason
    full = prove_scene(_b215("h1000", H="1000"))
    assert full.claim("stable").status is Status.PROVED


def test_2_an_exhaustive_search_without_a_genuine_orbit_refutes_with_its_counterexample(monkeypatch):
    """The same analysis (one spurious root, no genuine one) refutes only once the range is all of (0, oo)."""
    restricted = _b215("tmax012", {"T_max": "0.12"})
    model = relay_claims.validate(restricted)
    with working_precision(64):
        an = relay_claims.analyse(model)
        assert not an.covers_all and [v.kind for v in an.roots] == ["spurious"]
        inconclusive = relay_claims.attempt(model, list(relay_claims.CLAIMS), 64)
        an.covers_all, an.T_tail = True, an.T_search        # as if the tail bound had covered the rest
        monkeypatch.setattr(relay_claims, "analyse", lambda m, spectrum=None, phase=None: an)
        refuted = relay_claims.attempt(model, list(relay_claims.CLAIMS), 64)
    assert all(c.status is not Status.REFUTED for c in inconclusive.claims)
    og = next(c for c in refuted.claims if c.id == "orbit_genuine")
    assert og.status is Status.REFUTED
    assert og.counterexample["searched"] == "(0, oo)" and len(og.counterexample["roots"]) == 1


def test_2_a_refutation_without_a_counterexample_is_a_bug_not_a_verdict():
    from rigor_gyro.core.outcome import Claim
    with pytest.raises(AssertionError):
        Claim("x", "statement", Status.REFUTED, "a search limit was hit")
    Claim("x", "statement", Status.REFUTED, "certified", counterexample={"point": "1"})


# ------------------------------------------------------------------ 3. best_mu says what it proves

def test_3_best_mu_states_a_search_result_and_certifies_how_good_it_is():
    from rigor_gyro.core.exact import parse_exact
    from rigor_gyro.kinds.lyapunov import claims as lyap, mu_claims as lyap_mu
    cert = prove_scene(load_scene("agafonov2013"))
    claim = cert.claim("best_mu")
    assert claim.status is Status.PROVED
    assert "not proved optimal" in claim.statement and "maximises" not in claim.statement
    q = cert.quantities
    U, R_max = q["R_sup_upper_bound"], q["R_max"]
    assert (U - R_max).lower() >= 0 and q["R_max_relative_gap"].upper() < 1e-5
    # the bound holds at other admissible mu, computed independently of the branch and bound
    model = lyap.validate(load_scene("agafonov2013"))
    with working_precision(64):
        xs = model.gimbal.x2_star.ball()
        for mu in ("0.014", "0.018", "0.02", "0.022", "0.03"):
            R, _ = lyap_mu.r_sup(model.gimbal.with_mu(parse_exact(mu).fmpq()), xs)
            assert R.lower() <= U.upper(), mu


# ------------------------------------------------------------------ 4-7. bad input: exit 2, one line, in time

import os  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

from rigor_gyro import cli  # noqa: E402
from rigor_gyro.core.errors import ParameterError, SceneError  # noqa: E402
from rigor_gyro.scene import parse_scene  # noqa: E402

GOOD = '''name = "t"
kind = "eigenfrequencies"
[parameters]
a = "15.08"
b = "6.154"
eps = "0.1076"
Omega2 = "0.629"
'''


def _cli(capsys, *argv):
    t0 = time.perf_counter()
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err, time.perf_counter() - t0


def _scene_file(tmp_path, text, name="scene.toml"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return str(p)


BAD_SCENES = {
    "kind as a list": GOOD.replace('kind = "eigenfrequencies"', 'kind = ["eigenfrequencies"]'),
    "options not a table": GOOD + 'options = "x"\n',
    "paper not a table": GOOD + 'paper = 3\n',
    "malformed paper value": GOOD + '[paper]\nhz_exact = "41.4"\n',
    "paper list too long": GOOD + '[paper]\nhz_exact = ["1", "2", "3", "4", "5"]\n',
    "unknown paper key": GOOD + '[paper]\nhz_exct = ["41.4"]\n',
    "4301-digit number": GOOD.replace('a = "15.08"', 'a = "' + "1" * 4301 + '"'),
    "huge exponent": GOOD.replace('Omega2 = "0.629"', 'Omega2 = "1e99999"'),
    "hanging exponent": GOOD.replace('Omega2 = "0.629"', 'Omega2 = "1e999999999"'),
    "[option] typo": GOOD + '[option]\nrel_width = "1e-10"\n',
    "[claim] typo": GOOD + '[claim]\nonly = ["roots"]\n',
    "top-level rel_width": GOOD.replace('kind = "eigenfrequencies"\n', 'kind = "eigenfrequencies"\nrel_width = "1e-10"\n'),
    "space inside a number": GOOD.replace('a = "15.08"', 'a = "15 08"'),
    "double sign": GOOD.replace('b = "6.154"', 'b = "--6.154"'),
    "non-ASCII digits": GOOD.replace('b = "6.154"', 'b = "\u0666.154"'),
    "TOML float in options": GOOD + '[options]\nrel_width = 1e-10\n',
    "TOML float in paper": GOOD + '[paper]\nerror_bound = 0.05\n',
    "empty claims": GOOD + '[claims]\nonly = []\n',
    "name with a path": GOOD.replace('name = "t"', 'name = "../README"'),
    "absolute name": GOOD.replace('name = "t"', 'name = "/tmp/x"'),
    "name with a slash": GOOD.replace('name = "t"', 'name = "a/b"'),
    "name with a newline": GOOD.replace('name = "t"', 'name = "t\\n# PROVED"'),
    "300-character name": GOOD.replace('name = "t"', 'name = "' + "n" * 300 + '"'),
    "max_pieces zero": GOOD.replace("eigenfrequencies", "lyapunov"),   # replaced below
}
LYAP = load_scene("agafonov2013")


def _lyap_text(options: str) -> str:
    params = "\n".join(f'{k} = "{v}"' for k, v in LYAP.parameters.items())
    return f'name = "l"\nkind = "lyapunov"\n[parameters]\n{params}\n[options]\n{options}\n'


BAD_SCENES["max_pieces zero"] = _lyap_text('max_pieces = "0"')
BAD_SCENES["max_pieces negative"] = _lyap_text('max_pieces = "-5"')
BAD_SCENES["[option] R typo"] = _lyap_text('Rr = "0.05"')


@pytest.mark.parametrize("case", sorted(BAD_SCENES))
def test_4_to_7_bad_scene_is_exit_2_in_a_second_with_one_line_and_nothing_written(tmp_path, capsys, case):
    path = _scene_file(tmp_path, BAD_SCENES[case])
    out = tmp_path / "out"
    code, stdout, err, secs = _cli(capsys, "prove", path, "--out", str(out))
    assert code == 2, (case, stdout, err)
    assert secs < 2, secs
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    assert not list(out.glob("*")), "nothing written"
    assert not (tmp_path.parent / "README.json").exists()


def test_4_typo_messages_suggest_the_right_key(tmp_path, capsys):
    _, _, err, _ = _cli(capsys, "prove", _scene_file(tmp_path, BAD_SCENES["[option] typo"]), "--out", str(tmp_path))
    assert "did you mean 'options'" in err
    _, _, err, _ = _cli(capsys, "prove", _scene_file(tmp_path, BAD_SCENES["[option] R typo"]), "--out", str(tmp_path))
    assert "did you mean 'R'" in err


def test_4_unreadable_and_non_utf8_files_are_bad_input(tmp_path, capsys):
    p = tmp_path / "latin1.toml"
    p.write_bytes(GOOD.replace('"t"', '"t\xe9"').encode("latin-1"))
    assert _cli(capsys, "prove", str(p), "--out", str(tmp_path))[0] == 2
    d = tmp_path / "dir.toml"
    d.mkdir()
    assert _cli(capsys, "prove", str(d), "--out", str(tmp_path))[0] == 2


@pytest.mark.parametrize("argv", [["--prec", "1000000000"], ["--maxprec", "100000000"], ["--prec", "8"],
                                  ["--prec", "128", "--maxprec", "64"]])
def test_5_precisions_out_of_range_are_exit_2_at_once(capsys, argv, tmp_path):
    code, _, err, secs = _cli(capsys, "prove", "rudenko1976", "--out", str(tmp_path), *argv)
    assert code == 2 and secs < 1 and "--prec" in err


def test_4_bad_out_is_checked_before_proving(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    code, stdout, err, _ = _cli(capsys, "prove", "rudenko1976", "--out", str(f))
    assert code == 2 and "is a file" in err and "verdict" not in stdout
    if os.geteuid() != 0:             # root writes anywhere
        ro = tmp_path / "ro"
        ro.mkdir(mode=0o500)
        assert _cli(capsys, "prove", "rudenko1976", "--out", str(ro))[0] == 2


def test_7_two_scenes_with_one_name_in_one_call_are_refused(tmp_path, capsys):
    a = _scene_file(tmp_path, GOOD, "a.toml")
    b = _scene_file(tmp_path, GOOD.replace('"0.629"', '"0.7"'), "b.toml")
    code, stdout, err, _ = _cli(capsys, "prove", a, b, "--out", str(tmp_path / "o"))
    assert code == 2 and "'t'" in err and not (tmp_path / "o" / "t.json").exists()


def test_4_an_internal_error_is_exit_4_with_one_line_and_the_traceback_only_with_debug(monkeypatch, capsys, tmp_path):
    from rigor_gyro.kinds.eigenfrequencies import claims as eig

    def boom(*a, **k):
        raise ZeroDivisionError("planted bug")
    monkeypatch.setattr(eig, "isolate_polynomial", boom)
    code, _, err, _ = _cli(capsys, "prove", "rudenko1976", "--out", str(tmp_path))
    assert code == 4 and "internal error" in err and "Traceback" not in err
    code, _, err, _ = _cli(capsys, "--debug", "prove", "rudenko1976", "--out", str(tmp_path))
    assert code == 4 and "Traceback" in err


def test_4_list_into_a_closed_pipe_is_not_a_crash():
    r = subprocess.run(f"{sys.executable} -m rigor_gyro list | head -c 1 >/dev/null; exit ${{PIPESTATUS[0]}}",
                       shell=True, executable="/bin/bash", capture_output=True, text=True)
    assert r.returncode == 0 and "Traceback" not in r.stderr


@pytest.mark.parametrize("call", [
    lambda: load_scene(123), lambda: parse_scene(b"name = 1"), lambda: prove_scene("rudenko1976"),
    lambda: prove_scene(load_scene("rudenko1976"), prec=8), lambda: prove_scene(load_scene("rudenko1976"), maxprec=10**9),
    lambda: parse_scene(GOOD.replace('name = "t"', 'name = 5')),
    lambda: dataclasses.replace(load_scene("rudenko1976"), name="../x"),
    lambda: prove_scene(dataclasses.replace(load_scene("rudenko1976"), options={"rel_width": [1]})),
])
def test_4_the_api_raises_only_documented_errors(call):
    with pytest.raises((ParameterError, SceneError)):
        call()


def test_8_certificate_records_options_and_claims_asked_for():
    text = GOOD + '[claims]\nonly = ["roots"]\n[options]\nrel_width = "1e-20"\n'
    cert = prove_scene(parse_scene(text))
    scene = cert.to_json()["scene"]
    assert scene["options"] == {"rel_width": "1e-20"} and scene["claims_only"] == ["roots"]
    default = prove_scene(parse_scene(GOOD)).to_json()["scene"]
    assert default["options"] == {} and default["claims_only"] is None


def test_8_outputs_are_written_whole_or_not_at_all(tmp_path, monkeypatch):
    from rigor_gyro import report
    cert = prove_scene(parse_scene(GOOD))
    report.write_outputs(cert, tmp_path)
    before = {p.name: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}

    def failing(data):
        raise OSError("disk full")
    monkeypatch.setattr(report, "render_markdown", failing)
    with pytest.raises(OSError):
        report.write_outputs(cert, tmp_path)
    after = {p.name: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert after == before          # the old pair intact, no temporary file left behind


# ------------------------------------------------------------------ 9. escalation that cannot help

from fractions import Fraction  # noqa: E402

from rigor_gyro.core.outcome import Claim  # noqa: E402
from rigor_gyro.kinds import Attempt  # noqa: E402
from rigor_gyro.prover import no_progress  # noqa: E402

RUDENKO = load_scene("rudenko1976")
_A, _B = Fraction("15.08"), Fraction("6.154")


def _rudenko(name, **params):
    return dataclasses.replace(RUDENKO, name=name, parameters=dict(RUDENKO.parameters, **params), paper={})


def test_9_nu2_equal_to_nu3_is_decided_exactly_without_escalating():
    eps = (_A - _B) * (_B - 1) / (_A * _B - 2 * _A + 1)       # q26(1/(b-1)) = 0: nu2 = nu3 exactly
    t0 = time.perf_counter()
    cert = prove_scene(_rudenko("nu23", eps=str(eps)))
    assert time.perf_counter() - t0 < 2 and max(cert.precisions_tried) <= 128
    order = cert.claim("nu_ordering")
    assert order.status is Status.REFUTED and "exactly" in order.reason
    assert any("exactly_equal" in v for v in order.counterexample["violations"])
    assert cert.claim("branches").status is Status.REFUTED


def test_9_the_exact_pole_of_r2_makes_brackets_9_and_10_undefined_at_once():
    eps = _B * _B * (_A - _B) / (_A * (_B - 1))                # b/(b-1) = eps a/(b(a-b))
    cert = prove_scene(_rudenko("pole", eps=str(eps)))
    assert max(cert.precisions_tried) <= 128
    for j in (3, 4):
        c = cert.claim(f"bracket_{j}")
        assert c.status is Status.REFUTED and "undefined" in c.counterexample


@pytest.fixture(scope="module")
def tiny_c_star():
    """agafonov2013 at mu = 0.01333333334, just inside (16) (c* about 1e-16): one proof for issues 9 and 10."""
    return prove_scene(dataclasses.replace(LYAP, name="mu", parameters=dict(LYAP.parameters, mu="0.01333333334")))


def test_9_a_width_set_by_a_subdivision_tolerance_is_not_escalated(tiny_c_star):
    cert = tiny_c_star
    assert max(cert.precisions_tried) <= 256           # two doublings without progress, then stop
    assert any("did not shrink" in n for n in cert.notes)


def _attempt(claim_decides, prec_pairs=None):
    return Attempt([Claim("c", "s", Status.INCONCLUSIVE, "r", decides=claim_decides)], {})


@pytest.mark.parametrize("before, after, prec, stuck", [
    ("0.5 +/- 1e-10", "0.5 +/- 0.6e-10", 128, True),       # no shrink: a tolerance, not the precision
    ("0 +/- 1e-19", "0 +/- 1e-38", 128, False),            # shrinking; too early to call it zero
    ("0 +/- 1e-38", "0 +/- 1e-77", 256, False),            # shrinking around 0: more precision may decide
    ("1e-40 +/- 1e-38", "1e-40 +/- 1e-77", 256, False),    # shrinking, no longer contains 0
    ("nan", "nan", 256, False),                            # no information: may still progress
    ("0 +/- inf", "0 +/- inf", 256, True),                 # unbounded at both: a budget, not the precision
    ("0 +/- inf", "0.5 +/- 1e-10", 256, False),            # bounded now: may still progress
    ("0 +/- inf", "nan", 256, False),
])
def test_9_no_progress_rule(before, after, prec, stuck):
    """One doubling's evidence (the prover stops only after two doublings running say the same)."""
    from flint import arb
    prev = (prec // 2, _attempt(arb(before)))
    now = (prec, _attempt(arb(after)))
    assert (no_progress(prev, now) is not None) is stuck


def test_9_a_claim_without_a_deciding_ball_may_always_progress():
    assert no_progress((64, _attempt(None)), (128, _attempt(None))) is None


# ------------------------------------------------------------------ 10. a tiny positive c* is certified

def test_10_invariant_estimate_with_a_tiny_positive_c_star_is_proved(tiny_c_star):
    cert = tiny_c_star
    assert cert.claim("invariant_estimate").status is Status.PROVED
    c = cert.quantities["c_star"]
    assert c.lower() > 0 and c.upper() < 1e-15


# ------------------------------------------------------------------ 11. the smallest multiplier of a stiff case

@pytest.mark.parametrize("tau", ["1e-3", "1e-4"])
def test_11_every_multiplier_modulus_is_positive_with_a_relative_width(tau):
    from flint import arb
    cert = prove_scene(_relay(f"tau{tau}", tau=tau))
    assert cert.verdict is Status.PROVED and cert.precisions_tried == [64]
    moduli = [cert.quantities[f"multiplier_modulus_{j}"] for j in range(1, 5)]
    for m in moduli:
        assert m.lower() > 0 and 2 * m.rad() <= arb("1e-10") * m.lower()
    # Liouville: the product of the moduli is exp(-(1/tau + 1/sigma) theta*)
    P = RelayParams.from_strings(**dict(RELAY.parameters, tau=tau))
    with working_precision(64):
        theta = cert.quantities["theta_star"]
        liou = (-(1 / ball(P.tau) + 1 / ball(P.sigma)) * theta).exp()
        prod = moduli[0] * moduli[1] * moduli[2] * moduli[3]
    assert prod.is_finite() and liou.is_finite() and prod.overlaps(liou)


# ------------------------------------------------------------------ found by a second (hostile) review

def test_review_a_scene_name_cannot_produce_another_scenes_timings_file(tmp_path, capsys):
    text = GOOD.replace('name = "t"', 'name = "foo.timings"')
    assert _cli(capsys, "prove", _scene_file(tmp_path, text), "--out", str(tmp_path / "o"))[0] == 2


def test_review_bad_input_creates_no_output_folder(tmp_path, capsys):
    out = tmp_path / "new" / "a" / "b"
    assert _cli(capsys, "prove", str(tmp_path / "nonexist.toml"), "--out", str(out))[0] == 2
    assert not (tmp_path / "new").exists()
    assert _cli(capsys, "prove", "rudenko1976", "--out", "")[0] == 2


def test_review_a_folder_in_the_way_is_refused_before_anything_is_removed(tmp_path, capsys):
    (tmp_path / "rudenko1976.json").mkdir()
    (tmp_path / "rudenko1976.md").write_text("old")
    code, stdout, _, _ = _cli(capsys, "prove", "rudenko1976", "--out", str(tmp_path))
    assert code == 2 and "verdict" not in stdout and (tmp_path / "rudenko1976.md").read_text() == "old"


def test_review_outputs_follow_the_umask(tmp_path, capsys):
    old = os.umask(0o022)
    try:
        assert _cli(capsys, "prove", "rudenko1976", "--quiet", "--out", str(tmp_path))[0] == 0
    finally:
        os.umask(old)
    assert (tmp_path / "rudenko1976.json").stat().st_mode & 0o777 == 0o644


def test_review_a_path_too_long_for_the_os_is_bad_input(tmp_path, capsys):
    assert _cli(capsys, "prove", "a" * 5000, "--out", str(tmp_path))[0] == 2
    assert _cli(capsys, "prove", "rudenko1976", "--out", "a" * 5000)[0] == 2
    with pytest.raises(SceneError):
        load_scene("a" * 5000)


def test_review_stated_widths_are_the_printed_widths():
    """omega = 1 exactly a root (a midpoint with few bits): the decimals still have the claimed width."""
    from fractions import Fraction as F
    cert = prove_scene(_rudenko("om1", Omega2="1102300000/18522268523"))
    q = cert.to_json()["quantities"]["omega_3"]
    lo, hi = F(q["lo"]), F(q["hi"])
    assert lo <= 1 <= hi and hi - lo <= F(1, 10 ** 30)


def test_review_a_tiny_nonzero_margin_is_decided_by_precision_not_called_zero():
    cert = prove_scene(dataclasses.replace(RUDENKO, name="tiny", paper={}, claims_only=["nu_ordering"],
                                           parameters=dict(a="3", b="2", eps="1e-160", Omega2="0.5")))
    assert cert.claim("nu_ordering").status is Status.PROVED and max(cert.precisions_tried) >= 512


def test_review_a_degenerate_lyapunov_case_stops_early_with_a_finite_radius():
    cert = prove_scene(dataclasses.replace(LYAP, name="mu75", parameters=dict(LYAP.parameters, mu="1/75")))
    assert max(cert.precisions_tried) <= 256
    assert "did not shrink" in cert.claim("damping_condition").reason
    assert cert.quantities["R2"].is_finite()


# ------------------------------------------------------------------ soundness mutants that survived

def test_a_spurious_witness_is_a_point_where_beta_is_certainly_negative(monkeypatch):
    """beta'(0) < 0; beta(t) straddles 0 for t > theta/8 and is certainly < 0 below: the stored witness
    must be one of the certain points (a witness accepted on 'possibly <= 0' is not one)."""
    from flint import arb
    theta = arb("0.1")

    class Beta:
        def __call__(self, t):
            return arb(0, 1) if t > theta / 8 else arb(-1)
    monkeypatch.setattr(relay_claims, "x0_at", lambda sp, th: [arb(0), arb(-1), arb(0), arb(0), arb(0)])
    monkeypatch.setattr(relay_claims, "orbit_expsums", lambda sp, x0: [Beta()])
    with working_precision(64):
        v = relay_claims.classify_root(None, theta)
    assert v.kind == "spurious" and v.witness_t is not None
    assert Beta()(v.witness_t).upper() < 0


def test_stability_needs_every_modulus_certainly_below_1(monkeypatch):
    """A multiplier ball straddling 1 leaves stability undecided (never 'possibly < 1')."""
    from flint import arb, arb_mat
    P = RelayParams.from_strings(**RELAY.parameters)
    with working_precision(64):
        theta = arb("0.13")
        liou = -((-(1 / ball(P.tau) + 1 / ball(P.sigma))) * theta).exp()
        z1 = arb(1, arb("1e-12"))
        z4 = liou / (z1 * arb("0.5") * arb("0.25"))
        J = arb_mat([[z1, 0, 0, 0], [0, arb("0.5"), 0, 0], [0, 0, arb("0.25"), 0], [0, 0, 0, z4]])
        from rigor_gyro.kinds.periodic_orbit.flow import Spectrum

        class Sp:                                   # the point spectrum's eigenvalue method on J
            multipliers = Spectrum.multipliers

            def jacobian(self, th, x0):
                return J
        sp = Sp()
        sp.P = P
        v = relay_claims.RootVerdict(theta, [arb(0)] * 5, "genuine", "")
        relay_claims._multipliers(sp, v)
    assert v.moduli and v.stable is None


def test_9_a_margin_decided_only_at_256_bits_is_not_given_up_at_128():
    """Found by the campaign: nu4 vs its lower bound (5) differ by 1e-31 relative; the polynomial roots
    are refined to the working precision and the prover waits for two doublings without progress."""
    cert = prove_scene(_rudenko("tight", a="120.392", b="1.00000001", eps="4.46363e-11", Omega2="3.25847e+09"))
    assert cert.verdict is Status.PROVED and 256 in cert.precisions_tried


def test_a_relay_start_beyond_floats_is_inconclusive_not_an_internal_error():
    """H = 1e-300 (fuzzing, session 9): -b/a ~ 1e600 overflowed the float that picks the tail ladder's start
    (OverflowError, exit 4). The tail bound cannot be certified below the cap there: inconclusive."""
    cert = prove_scene(_relay("tiny_h", H="1e-300"), maxprec=128)
    hp = next(c for c in cert.claims if c.id == "half_period")
    assert hp.status is Status.INCONCLUSIVE and "tail bound" in hp.reason


def test_closed_form_radii_at_k_equal_to_mu_a0_are_finite():
    """k = mu A0 exactly (fuzzing, session 9): k/A0 - mu is a ball centred at 0, and python-flint's ``** 2`` of
    such a ball is nan; the checker's recomputed R1 was nan and rejected the prover's certificate."""
    from flint import arb
    from rigor_gyro.core.balls import square
    from rigor_gyro.kinds.lyapunov.claims import validate
    from rigor_gyro.kinds.lyapunov.closed_forms import closed_form_constants
    scene = load_scene("agafonov2013")
    g = validate(dataclasses.replace(scene, parameters=dict(scene.parameters, k="0.254"))).gimbal   # mu A0 = 0.254
    with working_precision(128):
        out = closed_form_constants(g, arb(1), arb(2))
        assert out["R1"].is_finite() and out["R1"].contains(0)
        z = arb(0, 1e-10)
        assert square(z).is_finite() and square(z).contains(0)


def test_an_inconclusive_best_mu_states_no_quantity_its_checker_cannot_confirm(monkeypatch):
    """max_pieces = 1 (fuzzing, session 9): best_mu stored mu_best and R_sup_at_mu_best, then R_max was not
    re-certified and the claim ended inconclusive; the checker verifies those only from a proved best_mu, so it
    rejected the certificate. Here R_max's re-certification is made to fail."""
    from rigor_gyro.check import check_certificate
    from rigor_gyro.kinds.lyapunov import mu_claims as lyap      # best_mu's own reference to _vdot_claim
    real = lyap.vdot_claim

    def failing(ctx, R, how, cid="vdot_nonpositive"):
        claim, info = real(ctx, R, how, cid)
        if how.startswith("at mu = mu_best"):
            claim = dataclasses.replace(claim, status=Status.INCONCLUSIVE, reason="made to fail")
        return claim, info
    monkeypatch.setattr(lyap, "vdot_claim", failing)
    scene = dataclasses.replace(load_scene("agafonov2013"), claims_only=["constants", "best_mu"])
    data = prove_scene(scene, maxprec=64).to_json()          # one attempt: precision cannot help here
    best = next(c for c in data["claims"] if c["id"] == "best_mu")
    assert best["status"] == "inconclusive" and "mu_best" not in data["quantities"]
    assert "R_sup_at_mu_best" not in data["quantities"]
    assert check_certificate(data).ok


def test_a_stored_nan_states_nothing_and_never_stands_for_a_required_quantity():
    """f = 0 (fuzzing, session 9): M = max f^2/(2 D G) is 0/0, stored nan; the checker rejected the certificate
    for a bound it stated nothing about. A nan or infinite stored interval now states nothing; a proved claim
    still needs every quantity its statement names finite."""
    from rigor_gyro.kinds.lyapunov.check import _states_nothing
    assert _states_nothing({"lo": "nan", "hi": "nan", "mid": "nan", "rad": "inf"})
    assert _states_nothing({"lo": "-inf", "hi": "+inf", "mid": "inf", "rad": "inf"})
    assert not _states_nothing({"lo": "0", "hi": "0"}) and not _states_nothing({"lo": "-1e-5", "hi": "2.5"})
    # one infinite end bounds the other (hostile review, session 10: damping_margin [-inf, 0.001] was accepted
    # although the true value is 0.5748)
    assert not _states_nothing({"lo": "-inf", "hi": "2"}) and not _states_nothing({"lo": "1", "hi": "+inf"})


def test_a_half_infinite_stored_quantity_is_checked_not_waved_through():
    """agafonov2013's damping_margin stored as [-inf, 0.001] (the true value is 0.5748): refused by the kind's
    checker, whatever the texts check says."""
    import copy
    import json
    from rigor_gyro.check import check_certificate
    from rigor_gyro.certificate import digest
    data = json.loads(json.dumps(prove_scene(load_scene("agafonov2013")).to_json()))
    bad = copy.deepcopy(data)
    bad["quantities"]["damping_margin"].update(lo="-inf", hi="0.001", mid="0.001", rad="0")
    bad["software"]["rigor_gyro"] = "0.0.0-other"          # the texts check aside: the kind's check alone
    bad["integrity"]["sha256"] = digest(bad)
    items = {r.item: r for r in check_certificate(bad).results}
    assert not all(r.ok for k, r in items.items() if k != "texts"), {k: r.message for k, r in items.items() if not r.ok}
