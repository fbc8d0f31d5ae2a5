"""The benchmarks (rigor-gyro bench): work-precision measurements and the stress catalog.

They measure and never decide, so these tests check that the measurements mean what they say:
widths and bits lost computed from the certificate's balls, the status classification, the float and
mpmath paths' errors against the certified values, and the command line's files and bad input.
Timings themselves are never asserted (benchmarks are commands, not timed tests).
"""
from __future__ import annotations

import json
import math

import pytest
from flint import arb

pytest.importorskip("mpmath")
pytest.importorskip("scipy")

from rigor_gyro.bench.stress import run_stress, stress_markdown  # noqa: E402
from rigor_gyro.bench.tables import scene_markdown  # noqa: E402
from rigor_gyro.bench.workprecision import (SceneBench, bench_scene, bits_lost, log2_width,  # noqa: E402
                                            relative_error, relative_width)
from rigor_gyro.core.balls import working_precision  # noqa: E402
from rigor_gyro.cli import main  # noqa: E402
from rigor_gyro.scene import builtin_scenes, load_scene  # noqa: E402


def test_widths_and_bits_lost_are_computed_from_the_ball():
    x = arb(1, 2.0 ** -60)               # rad 2^-60 around 1: w = 2^-59 (the radius rounded up a little)
    assert relative_width(x) == pytest.approx(2.0 ** -59, rel=1e-8)
    assert bits_lost(log2_width(x), 64) == pytest.approx(5.0, abs=1e-6)
    assert relative_width(arb(0, 1)) is None            # contains 0: no relative width
    assert relative_width(arb(3)) == 0.0 and bits_lost("exact", 64) is None
    assert log2_width(arb(3)) == "exact" and log2_width(arb(0, 1)) is None
    with working_precision(2048):         # 2^-2040: far below a double's range, kept as its log2
        tiny = arb(1) + arb(2) ** -2040 / 3
    assert relative_width(tiny) == 0.0                 # the float underflows ...
    assert log2_width(tiny) < -2000                    # ... its log2 does not
    assert bits_lost(log2_width(tiny), 2048) < 10


def test_relative_error_is_measured_at_high_precision():
    # a 40-digit mpmath-like text one part in 1e-35 off: must not be lost to 53-bit rounding
    ball = arb("1.5")
    assert relative_error("1.50000000000000000000000000000000000150", ball) == pytest.approx(1e-36, rel=1e-6)
    assert relative_error(float("nan"), ball) is None


def _bench(rows, requested=None):
    sb = SceneBench("s", "eigenfrequencies", requested or {})
    sb.rows = rows
    sb.quantities = sorted({q for r in rows for q in r["log2_widths"]})
    return sb


def _row(p, widths):
    lw = {k: ("exact" if w == 0 else math.log2(w)) for k, w in widths.items()}
    return {"prec": p, "verdict": "proved", "times": {"median_s": 0.1, "min_s": 0.1, "max_s": 0.1},
            "log2_widths": lw, "bits_lost": {k: bits_lost(w, p) for k, w in lw.items()}, "phases_s": {},
            "pieces": {}, "claims": {}}


def test_status_tells_following_losing_stuck_requested_and_exact_apart():
    rows = [_row(128, {"a": 2.0 ** -125, "b": 2.0 ** -110, "c": 1e-15, "d": 1e-15, "e": 0.0}),
            _row(256, {"a": 2.0 ** -253, "b": 2.0 ** -238, "c": 1e-15, "d": 1e-15, "e": 0.0})]
    sb = _bench(rows, requested={"d": math.log2(4e-15)})
    assert sb.status("a") == "follows 2^-p"
    assert sb.status("b") == "loses 18 bits"
    assert sb.status("c") == "stuck"
    assert sb.status("d") == "requested width met"
    assert sb.status("e") == "exact"
    md = scene_markdown(sb)
    assert "**Answer:** 2 of 5 quantities" in md and "`c` (stuck)" in md


def test_rudenko_work_precision_follows_the_precision_and_the_paths_are_close():
    sb = bench_scene(load_scene("rudenko1976"), schedule=(53, 128), repeat=1)
    assert [r["prec"] for r in sb.rows] == [53, 128]
    assert all(r["verdict"] == "proved" for r in sb.rows)
    for j in range(1, 5):
        assert sb.status(f"omega_{j}") in ("follows 2^-p", "requested width met")
    fl, mp = sb.methods["float"], sb.methods["mpmath30"]
    assert fl["found"] == 4
    assert all(e < 1e-12 for e in fl["errors"].values())          # numpy is fine on the paper's example
    assert all(e < 1e-28 for e in mp["errors"].values())          # and mpmath at 30 digits is better
    js = json.loads(json.dumps(sb.as_json(), default=str))
    assert js["quantities"] and js["precisions"][0]["bits_lost"]["omega_1"] is not None
    assert sb.rows[-1]["bits_lost"]["omega_1"] == sb.rows[-1]["log2_widths"]["omega_1"] + 128


def test_stress_group_is_listed_and_runs(capsys):
    names = list(builtin_scenes("stress"))
    assert len(names) >= 14 and any(n.startswith("stress_relay_tau") for n in names)
    rows = run_stress(["stress_eig_b_near_1"])
    r = rows[0]
    assert r["verdict"] == "refuted"          # b = 1 + 1e-8: the paper's nu ordering certainly fails
    assert {c["id"]: c["status"] for c in r["claims"]}["roots"] == "proved"
    assert r["certified_roots"] == 4
    md = stress_markdown(rows)
    assert "| `stress_eig_b_near_1` |" in md and "**refuted**" in md
    assert main(["list"]) == 0
    assert "stress_relay_H_1e5" in capsys.readouterr().out


def test_bench_command_writes_markdown_json_and_figure(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["bench", "rudenko1976", "--out", str(tmp_path), "--schedule", "53,64", "--repeat", "1",
                 "--plots"]) == 0
    md = (tmp_path / "rudenko1976.md").read_text()
    assert md.startswith("# Work-precision: `rudenko1976`") and "**Answer:**" in md
    data = json.loads((tmp_path / "rudenko1976.json").read_text())
    assert [r["prec"] for r in data["precisions"]] == [53, 64]
    png = tmp_path / "rudenko1976.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    import matplotlib.image as mpimg
    img = mpimg.imread(png)
    assert img.shape[0] > 200 and img[..., :3].std() > 0.05         # a drawn figure, not a blank canvas
    assert "Benchmarks: error against run time" in capsys.readouterr().out


@pytest.mark.parametrize("argv, needle", [
    (["bench", "--schedule", "53,x"], "--schedule"),
    (["bench", "--schedule", "8"], "--schedule"),
    (["bench", "--repeat", "0"], "--repeat"),
    (["bench", "rudenko1976", "--stress"], "--stress"),
    (["bench", "margin_agafonov_k_tolerance"], "tolerances"),
])
def test_bench_bad_usage_is_exit_2(argv, needle, capsys, tmp_path):
    assert main(argv + ["--out", str(tmp_path)]) == 2
    assert needle in capsys.readouterr().err


def test_bits_lost_is_log2_of_the_ratio():
    assert bits_lost(-50.0, 64) == pytest.approx(14.0)
    assert math.isclose(bits_lost(0.0, 53), 53.0)


def test_stress_command_keeps_json_out_of_the_certificate_folder(tmp_path, monkeypatch):
    import rigor_gyro.bench.stress as stress
    real = stress.run_stress
    monkeypatch.setattr(stress, "run_stress", lambda progress=None: real(["stress_eig_a_near_b"]))
    assert main(["bench", "--stress", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "stress.md").read_text().startswith("# Stress catalog")
    assert json.loads((tmp_path / "bench" / "stress.json").read_text())[0]["scene"] == "stress_eig_a_near_b"
    assert not list(tmp_path.glob("*.json"))     # proofs/*.json are certificates only
