"""The command line, end to end: exit codes, files written, user scene files, bad input."""
import json
import subprocess
import sys

import pytest

SCENE = """name = "{name}"
kind = "eigenfrequencies"
source = "test scene"
[parameters]
{params}
{extra}
"""


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "rigor_gyro", *args], capture_output=True, text=True, cwd=cwd)


def write_scene(tmp_path, name="user", params='a = "15.08"\nb = "6.154"\neps = "0.1076"\nOmega2 = "0.629"', extra=""):
    path = tmp_path / f"{name}.toml"
    path.write_text(SCENE.format(name=name, params=params, extra=extra))
    return path


def test_list_shows_builtin_scenes():
    r = run("list")
    assert r.returncode == 0 and "rudenko1976" in r.stdout and "eigenfrequencies" in r.stdout


def test_prove_builtin_writes_certificate_and_report(tmp_path):
    r = run("prove", "rudenko1976", "--out", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "rudenko1976: roots: proved" in r.stdout
    cert = json.loads((tmp_path / "rudenko1976.json").read_text())
    assert cert["schema"] == "rigor-gyro/certificate/2" and cert["verdict"] == "proved"
    assert set(cert) >= {"scene", "software", "precision_bits", "verdict", "claims", "quantities", "paper"}
    assert "timings" not in cert
    assert cert["scene"]["parameters"]["a"] == "15.08"
    assert {"id", "statement", "status", "reason", "precision_bits"} <= set(cert["claims"][0])
    assert {"lo", "hi", "mid", "rad"} == set(cert["quantities"]["omega_1"])
    assert {"id", "printed", "reading", "lo", "hi", "status", "note"} <= set(cert["paper"][0])
    md = (tmp_path / "rudenko1976.md").read_text()
    assert "PROVED" in md and "Audit of the paper" in md and "15.08" in md


def test_user_scene_file(tmp_path):
    path = write_scene(tmp_path, extra='[claims]\nonly = ["roots", "branches"]')
    r = run("prove", str(path), "--out", str(tmp_path / "out"))
    assert r.returncode == 0, r.stderr
    cert = json.loads((tmp_path / "out" / "user.json").read_text())
    assert [c["id"] for c in cert["claims"]] == ["roots", "branches"]
    assert cert["paper"] == [] or all(row["id"].startswith("(1)") for row in cert["paper"])


@pytest.mark.parametrize("params, word", [
    ('a = "15.08"\nb = "0.5"\neps = "0.1"\nOmega2 = "0.6"', "'b'"),
    ('a = "15.08"\nb = "6"\neps = "0.1"', "Omega2"),
    ('a = 15.08\nb = "6"\neps = "0.1"\nOmega2 = "0.6"', "'a'"),
    ('a = "15.08"\nb = "6"\neps = "zero"\nOmega2 = "0.6"', "'eps'"),
    ('a = "15.08"\nb = "6"\neps = "0.1"\nOmega2 = "0.6"\nfoo = "1"', "foo"),
])
def test_bad_input_is_exit_2_naming_the_parameter(tmp_path, params, word):
    path = write_scene(tmp_path, params=params)
    r = run("prove", str(path), "--out", str(tmp_path))
    assert r.returncode == 2
    assert word in r.stderr and "Traceback" not in r.stderr


def test_usage_errors_are_exit_2(tmp_path):
    assert run("prove").returncode == 2
    assert run("prove", "no-such-scene").returncode == 2
    assert run("prove", "rudenko1976", "--prec", "8").returncode == 2
    assert run("frobnicate").returncode == 2


def test_refuted_claim_is_exit_1(tmp_path):
    path = write_scene(tmp_path, params='a = "3"\nb = "2"\neps = "50"\nOmega2 = "1"')
    r = run("prove", str(path), "--out", str(tmp_path))
    assert r.returncode == 1 and "nu_ordering: refuted" in r.stdout


def test_inconclusive_is_exit_3(tmp_path):
    path = write_scene(tmp_path, extra='[options]\nrel_width = "1e-300"')
    r = run("prove", str(path), "--out", str(tmp_path), "--maxprec", "256")
    assert r.returncode == 3 and "roots: inconclusive" in r.stdout
    assert "--maxprec" in r.stdout


def test_proving_imports_neither_numpy_nor_scipy():
    code = ("import sys; from rigor_gyro.prover import prove_scene; from rigor_gyro.scene import load_scene;"
            "prove_scene(load_scene('rudenko1976'));"
            "print(sorted(m for m in ('numpy', 'scipy', 'mpmath', 'matplotlib') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"


def test_the_same_scene_gives_byte_identical_outputs(tmp_path):
    """Run-dependent data (timings) live in timings/<name>.json; certificate and report are reproducible."""
    for d in ("a", "b"):
        assert run("prove", "rudenko1976", "agafonov2013", "--quiet", "--out", str(tmp_path / d)).returncode == 0
    for name in ("rudenko1976.json", "rudenko1976.md", "agafonov2013.json", "agafonov2013.md"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name
    assert json.loads((tmp_path / "a" / "timings" / "rudenko1976.json").read_text())["total_s"] > 0


def test_timings_file_breaks_the_proof_down_by_phase_and_counts_pieces(tmp_path):
    from rigor_gyro.cli import main
    assert main(["prove", "agafonov2013", "--out", str(tmp_path), "--quiet"]) == 0
    t = json.loads((tmp_path / "timings" / "agafonov2013.json").read_text())
    assert t["attempts_s"] and t["attempts_s"][-1][0] == t["precisions_tried"][-1]
    phases = t["final_attempt_phases_s"]
    assert {"best_mu", "vdot_nonpositive", "paper audit"} <= set(phases)
    assert sum(phases.values()) <= t["total_s"] + 1e-3
    assert t["pieces"]["constants.m_pieces"] >= 1 and t["pieces"]["invariant_estimate.pieces"] >= 1


def test_a_report_opens_with_the_answer_and_keeps_the_audit_compact(tmp_path):
    from rigor_gyro.cli import main
    assert main(["prove", "roitenberg1947_b2over15", "--out", str(tmp_path), "--quiet"]) == 0
    md = (tmp_path / "roitenberg1947_b2over15.md").read_text()
    head = md.split("## Parameters", 1)[0]
    assert "## Summary" in head and "**Verdict: proved**" in head and "`theta_star`" in head
    assert "How to read this report" in head
    audit = md.split("## Audit of the paper", 1)[1]
    assert audit.index("rows:**") < audit.index("### Misprints") < audit.index("unexplained:")
    assert len(md) < 45000, len(md)          # 63 KB before the audit was grouped by class


def test_plots_without_matplotlib_are_bad_input(monkeypatch, tmp_path):
    """Every --plots says which extra to install (exit 2) when matplotlib is missing, and writes no figure."""
    from rigor_gyro import cli
    monkeypatch.setattr(cli, "_has_matplotlib", lambda: False)
    assert cli.main(["margin", "roitenberg1947", "--param", "n", "--scan", "2", "--lo", "1", "--hi", "2",
                     "--claim", "stable", "--out", str(tmp_path), "--plots"]) == 2
    assert cli.main(["prove", "roitenberg1947", "--out", str(tmp_path), "--quiet", "--plots"]) == 2
    assert not list(tmp_path.glob("*.png"))


def test_several_scenes_on_worker_processes_give_the_same_files_and_lines(tmp_path):
    """One scene per worker process: the files and the printed lines are those of one process, in order."""
    outs = {}
    for w in ("1", "2"):
        (tmp_path / w).mkdir()
        r = run("prove", "roitenberg1947", "rudenko1976", "--workers", w, "--out", "out", cwd=tmp_path / w)
        assert r.returncode == 0, r.stderr
        outs[w] = [line.split(" in ")[0] if "verdict" in line else line for line in r.stdout.splitlines()]
    assert outs["1"] == outs["2"] and outs["1"][-1] == "rudenko1976: verdict proved"
    for name in ("roitenberg1947.json", "roitenberg1947.md", "rudenko1976.json", "rudenko1976.md"):
        assert (tmp_path / "1" / "out" / name).read_bytes() == (tmp_path / "2" / "out" / name).read_bytes(), name


@pytest.mark.parametrize("how", ["raises", "dies"])
def test_a_failing_worker_is_an_internal_error_never_a_verdict(monkeypatch, tmp_path, capsys, how):
    """A bug in one scene's worker (an exception, or the process killed) exits 4 naming it; the other
    scene is still proved and written."""
    import os
    from rigor_gyro import cli, prover
    real = prover.prove_scene

    def broken(scene, **kw):
        if scene.name == "rudenko1976":
            if how == "dies":
                os._exit(9)
            raise RuntimeError("planted")
        return real(scene, **kw)
    monkeypatch.setattr(prover, "prove_scene", broken)
    code = cli.main(["prove", "roitenberg1947_b2over15", "rudenko1976", "--workers", "2", "--quiet",
                     "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 4 and "internal error" in err
    assert ("rudenko1976: internal error: RuntimeError: planted" in err) if how == "raises" else "worker" in err
    assert not (tmp_path / "rudenko1976.json").exists()
    if how == "raises":
        assert (tmp_path / "roitenberg1947_b2over15.json").exists()
