"""A report an engineer reads in a minute (issue 35, part 4): the summary's first lines give the verdict
and the kind's headline numbers, each derived from the certificate's stored decimal bounds and rounded
outward (checked here in exact rationals); wall times below 5 ms never print as "0.00 s"; no reason
carries python-flint's ball format "[m +/- r]"."""
from __future__ import annotations

import json
import re
from collections import Counter
from fractions import Fraction

import pytest

from rigor_gyro.core.seconds import seconds_text
from rigor_gyro.prover import prove_scene
from rigor_gyro.report import render_markdown
from rigor_gyro.scene import load_scene

_NUM = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"
_IV = rf"(?:\[({_NUM}), ({_NUM})\]|({_NUM}))"


@pytest.fixture(scope="module")
def certs() -> dict[str, dict]:
    """The built-in papers' certificates in their JSON form (what render_markdown is given)."""
    return {name: json.loads(json.dumps(prove_scene(load_scene(name)).to_json()))
            for name in ("roitenberg1947", "rudenko1976", "agafonov2013")}


def _summary(cert: dict) -> list[str]:
    md = render_markdown(cert)
    head = md.split("## Summary", 1)[1].split("## Parameters", 1)[0]
    return [ln for ln in head.splitlines() if ln.strip()]


def _interval(text: str) -> tuple[Fraction, Fraction]:
    """The first "[a, b]" (or single number) at the start of ``text``, as exact rationals."""
    m = re.match(_IV, text)
    assert m, text
    if m.group(3) is not None:
        return Fraction(m.group(3)), Fraction(m.group(3))
    return Fraction(m.group(1)), Fraction(m.group(2))


def _after(line: str, key: str) -> tuple[Fraction, Fraction]:
    assert key in line, (key, line)
    return _interval(line.split(key, 1)[1])


def _stored(q: dict) -> tuple[Fraction, Fraction]:
    return Fraction(q["lo"]), Fraction(q["hi"])


def test_the_relay_summary_opens_with_the_period_and_its_frequency_in_hz(certs):
    cert = certs["roitenberg1947"]
    lines = _summary(cert)
    assert lines[0] == "**Verdict: proved** (5 claims: 5 proved)."
    stable = [r for r in cert["extra"]["roots"] if r["kind"] == "genuine" and r["stable"] is True]
    assert len(stable) == 1
    head = lines[1]
    assert head.startswith("- **Self-oscillation** (genuine, stable): period 2 theta* = ")
    p_lo, p_hi = _after(head, "period 2 theta* = ")
    f_lo, f_hi = _after(head, "frequency 1/period = ")
    assert head.split("frequency 1/period = ", 1)[1].split("]", 1)[1].startswith(" Hz")
    # outward: the printed period contains 2 theta* of the stored root and the stored period quantity
    t_lo, t_hi = (Fraction(x) for x in stable[0]["theta"])
    per_lo, per_hi = _stored(cert["quantities"]["period"])
    assert p_lo <= 2 * t_lo and 2 * t_hi <= p_hi
    assert p_lo <= per_lo and per_hi <= p_hi
    # the frequency is 1/period, computed exactly from the stored bounds and rounded outward
    assert f_lo <= 1 / (2 * t_hi) and 1 / (2 * t_lo) <= f_hi
    assert f_lo <= 1 / per_hi and 1 / per_lo <= f_hi
    assert f_lo > 0 and (f_hi - f_lo) / f_lo < Fraction(1, 10 ** 8)         # ten digits, not a vague range
    assert 3 < f_lo < f_hi < 4                                               # about 3.62 Hz
    # the headline comes before the table of quantities
    assert lines.index(head) < next(i for i, ln in enumerate(lines) if ln.startswith("| quantity"))


def test_the_eigenfrequency_summary_gives_the_hz_the_audit_counts_and_the_refuted_five_percent(certs):
    cert = certs["rudenko1976"]
    lines = _summary(cert)
    assert lines[0].startswith("**Verdict: proved**")
    freq = lines[1]
    assert freq.startswith("- **Eigenfrequencies** (Hz): ")
    shown = re.findall(rf"\[({_NUM}), ({_NUM})\]", freq)
    assert len(shown) == 4
    for j, (a, b) in enumerate(shown, 1):
        lo, hi = _stored(cert["quantities"][f"freq_hz_{j}"])
        assert Fraction(a) <= lo and hi <= Fraction(b)
    # the audit: every row counted once, by class, in one line
    audit = next(ln for ln in lines if ln.startswith("- **Audit of the paper**"))
    counts = Counter(r.get("class", r["status"]) for r in cert["paper"])
    assert f": {len(cert['paper'])} rows: " in audit
    for cls, n in counts.items():
        assert f"{n} {cls}" in audit, (cls, n, audit)
    # the refuted "error does not exceed 5%" in one line: where it fails, with the certified errors
    rows = {int(re.search(r"root (\d+)", r["id"]).group(1)): r for r in cert["paper"]
            if r["id"].startswith("error <= 0.05 for root")}
    assert sorted(rows) == [1, 2, 3, 4]
    refuted = [j for j, r in sorted(rows.items()) if r["status"] == "refuted"]
    held = [j for j, r in sorted(rows.items()) if r["status"] == "confirmed"]
    assert refuted == [2, 3] and held == [1, 4]
    pct = [ln for ln in lines if "error does not exceed 5%" in ln]
    assert len(pct) == 1 and pct[0].startswith('- **Refuted: "error does not exceed 5%"**')
    assert "exceeded for roots 2 and 3" in pct[0] and "holds for roots 1 and 4" in pct[0]
    for j in refuted:
        exceeding = rows[j]["note"].split(";", 1)[0].removeprefix("exceeds: ")
        assert f"root {j}: {exceeding}" in pct[0]
    assert "approx [7.4713615, 7.4713616] %" in pct[0]           # root 2's approximation: 7.47 % off
    other = next(ln for ln in lines if ln.startswith("- **Other assertions of the paper certified false**"))
    assert "`general claim: no smallness assumption`" in other and "error <=" not in other
    # answer first: all of it before the table of quantities
    table = next(i for i, ln in enumerate(lines) if ln.startswith("| quantity"))
    assert lines.index(pct[0]) < table


def test_the_lyapunov_summary_gives_the_extents_and_the_papers_r_beside_the_certified_radii(certs):
    cert = certs["agafonov2013"]
    q = cert["quantities"]
    lines = _summary(cert)
    assert lines[0].startswith("**Verdict: proved**")
    est = lines[1]
    assert est.startswith("- **Estimate of the domain of attraction** {V < c*}")
    for axis in ("x1", "x2", "x3"):
        a, b = _after(est, f"max |{axis}| = ")
        lo, hi = _stored(q[f"extent_{axis}"])
        assert a <= lo and hi <= b and (b - a) <= Fraction(1, 10 ** 5) * b, axis
    a, b = _after(est, "c* = ")
    assert a <= _stored(q["c_star"])[0] and _stored(q["c_star"])[1] <= b
    radii = lines[2]
    assert radii.startswith("- **Radius R of region (17)**")
    rows = {r["id"]: r for r in cert["paper"]}
    # the paper's printed R (audit rows R1, R2, "R = R1") beside the certified radii
    assert f"R1 = {rows['R1']['printed']}" in radii and f"R2 = {rows['R2']['printed']}" in radii
    assert f"\"{rows['R = R1']['printed']}\" (refuted: " in radii
    certified = radii.split("certified: ", 1)[1]
    for key, label in (("R", "R = min(R1, R2) = "), ("R_direct", "R_direct (direct test, scene's mu) = "),
                       ("R_max", "R_max (Psi test, mu_best) = "),
                       ("R_direct_max", "R_direct_max (direct test, mu_direct) = ")):
        a, b = _after(certified, label)
        lo, hi = _stored(q[key])
        assert a <= lo and hi <= b, key
    assert radii.index("the paper prints") < radii.index("certified: ")
    assert any(ln.startswith("- **Audit of the paper**") for ln in lines[:5])


def test_the_summary_is_rendered_from_the_stored_certificate_alone(certs):
    """The headline is the same when the certificate is re-read from its JSON text (nothing recomputed)."""
    for cert in certs.values():
        again = json.loads(json.dumps(cert))
        assert render_markdown(again) == render_markdown(cert)


@pytest.mark.parametrize("s, text", [(0.0, "< 0.005 s"), (1e-9, "< 0.005 s"), (0.0049, "< 0.005 s"),
                                     (0.0051, "0.01 s"), (0.12, "0.12 s"), (61.714, "61.71 s"), (1234.5, "1234.50 s")])
def test_times_below_five_milliseconds_never_print_as_zero(s, text):
    assert seconds_text(s) == text
    assert seconds_text(s, unit=False) == text[:-2]
    assert seconds_text(s) != "0.00 s"


def test_no_reason_or_report_carries_the_ball_format(certs):
    """python-flint's "[m +/- r]" never reaches a reason, an audit note or a report: bounds are decimals
    rounded outward."""
    for name, cert in certs.items():
        for c in cert["claims"]:
            assert "+/-" not in c["reason"], (name, c["id"], c["reason"])
        for r in cert.get("paper") or []:
            assert "+/-" not in json.dumps(r), (name, r["id"])
        assert "+/-" not in render_markdown(cert), name


def test_complex_roots_are_reported_as_decimal_intervals(monkeypatch):
    """The roots claim refuted by non-real roots names them as outward-rounded decimals, not as python-flint
    balls."""
    from flint import fmpq_poly

    from rigor_gyro.core.balls import working_precision
    from rigor_gyro.kinds.eigenfrequencies import claims as ec
    model = ec.validate(load_scene("rudenko1976"))
    Q = fmpq_poly([10, -19, 13, -5, 1])           # (x - 1)(x - 2)(x^2 - 2x + 5): roots 1, 2, 1 +- 2i
    monkeypatch.setattr(ec, "characteristic_quartic", lambda *a: Q)
    with working_precision(128):
        att = ec.attempt(model, list(ec.CLAIMS), 128)
    r = next(c for c in att.claims if c.id == "roots")
    assert "2 roots are certainly non-real" in r.reason and "+/-" not in r.reason
    shown = re.findall(rf"\[({_NUM}), ({_NUM})\] \+ \[({_NUM}), ({_NUM})\] i", r.reason)
    assert len(shown) == 2
    for re_lo, re_hi, im_lo, im_hi in shown:       # each contains 1 + 2i or 1 - 2i
        assert Fraction(re_lo) <= 1 <= Fraction(re_hi)
        assert Fraction(im_lo) <= 2 <= Fraction(im_hi) or Fraction(im_lo) <= -2 <= Fraction(im_hi)


def test_no_reason_of_the_demos_carries_the_ball_format():
    """The planted refutations and inconclusive outcomes too (V <= 0 on a face, a sign condition that
    fails): their reasons print outward-rounded decimals (core.balls.enclosure_text)."""
    from rigor_gyro.scene import builtin_scenes
    for name in builtin_scenes("demo"):
        cert = json.loads(json.dumps(prove_scene(load_scene(name)).to_json()))
        for c in cert["claims"]:
            assert "+/-" not in c["reason"], (name, c["id"], c["reason"])


def test_enclosure_text_rounds_outward_and_never_prints_a_flint_ball():
    from flint import arb

    from rigor_gyro.core.balls import enclosure_text
    x = arb("-240987.88") + arb(0, "1.84e-3")
    text = enclosure_text(x, 8)
    lo, hi = (Fraction(t) for t in text.strip("[]").split(", "))
    assert lo <= Fraction("-240987.88") - Fraction("1.84e-3") and hi >= Fraction("-240987.88") + Fraction("1.84e-3")
    assert "+/-" not in text and enclosure_text(arb(3), 5) == "3"
    assert enclosure_text(arb(0, "inf")) == "[-inf, +inf]" and enclosure_text(arb("nan")) == "nan"
