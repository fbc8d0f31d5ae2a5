"""Numbers shown as what they are (issue 35, part 3): an exact number is never printed through a float,
a certified bound is rounded outward, a certified quantity from Python shows its certified digits.
"""
import dataclasses
from fractions import Fraction

import pytest

from rigor_gyro import load_scene
from rigor_gyro.core.balls import interval_text, rational_text, width_text
from rigor_gyro.margins.threshold import find_threshold


@pytest.mark.parametrize("q, text", [
    (Fraction(1, 5), "0.2"), (Fraction(4, 5), "0.8"), (Fraction(3, 40), "0.075"), (Fraction(-5, 2), "-2.5"),
    (Fraction(1200), "1200"), (Fraction(1, 3), "1/3"), (Fraction(-2, 7), "-2/7"), (Fraction(1, 10 ** 30), "1e-30"),
    (Fraction(0), "0"),
])
def test_an_exact_number_is_its_exact_decimal_or_its_fraction(q, text):
    assert rational_text(q) == text and Fraction(text) == q


def test_a_bracket_is_exact_when_it_terminates_and_rounded_outward_otherwise():
    assert interval_text(Fraction(1, 5), Fraction(4, 5)) == ("0.2", "0.8", False)
    lo, hi = Fraction(1, 3), Fraction(1, 3) + Fraction(1, 10 ** 9)
    bl, bh, rounded = interval_text(lo, hi)
    assert rounded and Fraction(bl) <= lo < hi <= Fraction(bh)
    assert Fraction(bh) - Fraction(bl) <= Fraction(102, 100) * (hi - lo)      # about 1/100 of the width added
    assert width_text(Fraction(3, 5) / 2 ** 20) == "5.73e-7" and Fraction("5.73e-7") >= Fraction(3, 5) / 2 ** 20


def test_a_thresholds_lines_show_exact_ends_and_an_outward_bracket():
    """The default search of agafonov2013's k (half and twice 0.4: ends 1/5 and 4/5) printed 0.20000000000000001
    and 0.80000000000000004, and its bracket as 17-digit floats."""
    s = load_scene("agafonov2013")
    scene = dataclasses.replace(s, claims_only=["damping_condition"])
    res = find_threshold(scene, "k", claim="damping_condition", width="1e-3")
    assert (res.lo, res.hi) == (Fraction(1, 5), Fraction(4, 5)) and res.certified
    line = res.lines()[0]
    assert "0000000000" not in line and "e-" not in line.split("(width")[0]
    p, r = res.proved_at, res.refuted_at
    assert f"proved at k = {rational_text(p)}, refuted at k = {rational_text(r)}" in line
    l, h = res.bracket()
    bl, bh, rounded = interval_text(l, h)
    assert f"changes in [{bl}, {bh}]" in line and Fraction(bl) <= l < h <= Fraction(bh)
    assert res.to_json()["bracket_decimal"] == [bl, bh]
    stopped = find_threshold(scene, "k", claim="damping_condition", lo="0.3", hi="1/3")
    assert not stopped.certified and "[0.3, 1/3]" in stopped.lines()[0]
    assert "k = 0.3 and" in stopped.stopped and "k = 1/3;" in stopped.stopped


# ---------------------------------------------------------------- certified quantities from Python

def test_a_certified_quantity_shows_its_certified_digits_and_stays_an_arb():
    from flint import arb, fmpq

    from rigor_gyro import prove_scene
    from rigor_gyro.core.balls import Quantity, certainly_lt, exact_endpoints
    cert = prove_scene(load_scene("rudenko1976"))
    w = cert.quantities["omega_1"]
    assert isinstance(w, Quantity) and isinstance(w, arb)
    assert isinstance(w + 1, arb) and certainly_lt(w, arb(1)) and w.rad() < arb("1e-70")
    text = repr(w)
    assert text == str(w) and text.startswith("[0.00450240157250983917602386831672844424486") and "e-79]" in text
    mid, rad = text[1:-1].split(" +/- ")
    lo, hi = exact_endpoints(w)         # the printed ball contains the certified one
    assert Fraction(mid) - Fraction(rad) <= lo and hi <= Fraction(mid) + Fraction(rad)
    exact = Quantity.of_exact(Fraction(17, 100))
    assert repr(exact) == "0.17" and exact.exact == Fraction(17, 100) and exact.rad() > 0   # the ball encloses it
    assert exact.contains(arb(fmpq(17, 100)))


def test_a_certificate_has_a_concise_repr_and_a_markdown_one():
    from rigor_gyro import prove_scene
    from rigor_gyro.report import render_markdown
    cert = prove_scene(load_scene("rudenko1976"))
    text = repr(cert)
    assert len(text) < 400 and len(text.splitlines()) <= 8
    assert "'rudenko1976'" in text and "eigenfrequencies" in text and "proved, 9 claims: 9 proved" in text
    md = cert._repr_markdown_()
    assert md.startswith("**rudenko1976** (kind `eigenfrequencies`): **proved**")
    assert all(f"| `{c.id}` | **proved** |" in md for c in cert.claims)
    assert f"| `omega_1` | {cert.quantities['omega_1']!r} |" in md and "more in `.quantities`" in md
    assert render_markdown(cert.to_json()).startswith("# rudenko1976: PROVED")    # the full report, exported
    import rigor_gyro
    assert rigor_gyro.render_markdown is render_markdown
    demo = prove_scene(load_scene("roitenberg1947_b2over15"))
    if demo.verdict.value != "proved":              # a claim not proved is named with its reason
        bad = [c for c in demo.claims if c.status.value != "proved"][0]
        assert f"  {bad.id}: {bad.status.value}: " in repr(demo)


# ---------------------------------------------------------------- searched decimals, derived widths

def test_searched_decimals_are_exact_numbers_in_the_certificate_and_the_check_still_reverifies():
    import copy

    from rigor_gyro import prove_scene
    from rigor_gyro.certificate import digest
    from rigor_gyro.check import check_certificate
    from rigor_gyro.report import _short
    cert = prove_scene(load_scene("agafonov2013"))
    data = cert.to_json()
    q = data["quantities"]
    names = ["mu_best", "R_max", "R_direct", "R_direct_upper", "mu_direct", "R_direct_max"]
    for name in names:
        assert q[name]["lo"] == q[name]["hi"] == q[name]["mid"] and q[name]["rad"] == "0", name
        assert repr(cert.quantities[name]) == q[name]["lo"] and "+/-" not in repr(cert.quantities[name])
        assert _short(q[name]) == q[name]["lo"] + " (exact)"
    details = {c["id"]: c.get("details", {}) for c in data["claims"]}
    assert q["mu_best"]["lo"] == details["best_mu"]["mu_best"] and q["R_max"]["lo"] == details["best_mu"]["R_max"]
    assert check_certificate(data).ok
    bad = copy.deepcopy(data)                  # another searched decimal, the digest recomputed: rejected
    x = Fraction(q["mu_best"]["lo"]) * Fraction(1000001, 1000000)
    bad["quantities"]["mu_best"] = {"lo": str(float(x)), "hi": str(float(x)), "mid": str(float(x)), "rad": "0"}
    bad["integrity"] = {"sha256": digest(bad)}
    rep = check_certificate(bad)
    assert not rep.ok and any(r.item == "mu_best" and not r.ok for r in rep.results)


def test_the_period_is_as_narrow_as_theta_star_and_the_precision_is_stated():
    from rigor_gyro import prove_scene
    cert = prove_scene(load_scene("roitenberg1947"))
    data = cert.to_json()
    t, p = data["quantities"]["theta_star"], data["quantities"]["period"]
    assert Fraction(p["rad"]) <= 2 * Fraction(t["rad"]) * Fraction(101, 100)        # was 5e8 times wider
    assert Fraction(p["lo"]) <= 2 * Fraction(t["hi"]) and 2 * Fraction(t["lo"]) <= Fraction(p["hi"])    # they meet
    bits = data["precision_bits"]
    assert any(n.startswith(f"Precision: the roots of g are isolated and classified at the working precision ({bits} "
                            f"bits)") and f"recomputed at {bits + 32} bits" in n for n in data["notes"])


# ---------------------------------------------------------------- the library API

def test_prove_scene_on_a_tolerance_scene_points_to_the_paving_api():
    import rigor_gyro as rg
    s = load_scene("agafonov2013")
    box = dataclasses.replace(s, parameters={**s.parameters, "k": "[0.35, 0.45]"})
    with pytest.raises(rg.ParameterError) as e:
        rg.prove_scene(box)
    text = str(e.value)
    assert "has tolerances (parameter k = '[0.35, 0.45]')" in text
    assert "rigor_gyro.pave(rigor_gyro.box_scene(scene))" in text and "rigor-gyro prove" in text
    assert "cannot read" not in text


def test_writing_checking_and_paving_are_exported_lazily():
    import subprocess
    import sys
    code = ("import sys, rigor_gyro as rg; before = sorted(m for m in sys.modules if m.startswith('rigor_gyro.margins') "
            "or m in ('rigor_gyro.check', 'rigor_gyro.report')); "
            "names = ['write_outputs', 'check_file', 'check_certificate', 'box_scene', 'pave', 'write_paving', "
            "'find_threshold', 'run_scan', 'write_threshold', 'write_scan']; "
            "assert all(n in rg.__all__ and n in dir(rg) and callable(getattr(rg, n)) for n in names); "
            "print(before, sorted(m for m in ('numpy', 'scipy', 'matplotlib', 'mpmath') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[] []"
    import rigor_gyro
    with pytest.raises(AttributeError):
        rigor_gyro.no_such_name


def test_the_readmes_library_example_runs(tmp_path, monkeypatch):
    import re
    from pathlib import Path
    readme = (Path(__file__).resolve().parent.parent / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("## Library use"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.setattr("tempfile.mkdtemp", lambda *a, **k: str(tmp_path))
    env: dict = {}
    exec(compile(code, "README.md (Library use)", "exec"), env)
    assert env["cert"].verdict.value == "proved" and env["paving"].claims[0].status == "proved"
    assert env["t"].certified and str(env["w"]).startswith("[0.00450240157250983917602386831672844424486401")
    names = sorted(p.name for p in tmp_path.iterdir())
    assert {"rudenko1976.json", "rudenko1976.md", "agafonov2013.json", "margin_agafonov2013_k.json"} <= set(names)
