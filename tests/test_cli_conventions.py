"""The command line as Python users expect it: help with examples and exit codes, no abbreviations,
short options, errors that name the path once, a wall-clock budget, progress only on a terminal."""
from __future__ import annotations

import io
import json
import os
import time

import pytest

from rigor_gyro import cli
from rigor_gyro.cli import main
from rigor_gyro.core.deadline import Budget, TimeLimitReached, check_time_limit, time_limit
from rigor_gyro.core.outcome import Status

COMMANDS = ("prove", "margin", "check", "campaign", "bench", "list")


@pytest.mark.parametrize("command", (None,) + COMMANDS)
def test_help_shows_examples_and_exit_codes(command, capsys):
    with pytest.raises(SystemExit) as e:
        main(([command] if command else []) + ["--help"])
    assert e.value.code == 0
    text = capsys.readouterr().out
    assert "examples:" in text and "exit status" in text and "rigor-gyro " in text.split("examples:", 1)[1]
    if command in (None, "prove"):
        for code in ("0", "1", "2", "3", "4"):
            assert f"  {code}  " in text


@pytest.mark.parametrize("argv", [["prove", "rudenko1976", "--qui"], ["prove", "rudenko1976", "--ou", "x"],
                                  ["check", "x.json", "--qu"], ["margin", "rudenko1976", "--par", "a"]])
def test_abbreviated_options_are_usage_errors(argv, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert argv[-1] in err or argv[-2] in err, err
    assert not any(tmp_path.iterdir()), "nothing is written on a usage error"


def test_short_options_o_q_j(tmp_path, capsys):
    assert main(["prove", "rudenko1976", "-q", "-o", str(tmp_path), "-j", "1"]) == 0
    out = capsys.readouterr().out
    assert (tmp_path / "rudenko1976.json").is_file()
    assert out.count("\n") == 1 and "verdict proved" in out       # -q: the verdict line only
    assert main(["check", "-q", str(tmp_path / "rudenko1976.json")]) == 0
    assert capsys.readouterr().out.count("\n") == 1


@pytest.mark.parametrize("command", [["prove", "rudenko1976"], ["margin", "rudenko1976", "--param", "eps"],
                                     ["campaign", "--kind", "eigenfrequencies", "--cases", "1"]])
def test_out_dash_is_an_error_not_a_folder(command, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(command + ["--out", "-"]) == 2
    assert "--out -" in capsys.readouterr().err
    assert not (tmp_path / "-").exists()


def test_scheduler_on_point_scenes_is_an_error(tmp_path, capsys):
    assert main(["prove", "rudenko1976", "--scheduler", "local", "-o", str(tmp_path)]) == 2
    assert "--scheduler" in capsys.readouterr().err
    assert not (tmp_path / "rudenko1976.json").exists()


def _fifo(tmp_path):
    if not hasattr(os, "mkfifo"):
        pytest.skip("no FIFOs here")
    path = tmp_path / "pipe.toml"
    os.mkfifo(path)
    return path


@pytest.mark.parametrize("make, says", [
    (lambda p: p / "missing.toml", "no such file"),
    (lambda p: p, "is a directory"),
    (_fifo, "not a regular file"),
])
def test_a_bad_scene_path_says_what_it_is_once(make, says, tmp_path, capsys):
    path = str(make(tmp_path))
    t0 = time.monotonic()
    assert main(["prove", path, "-o", str(tmp_path / "out")]) == 2
    assert time.monotonic() - t0 < 5, "a FIFO is never opened"
    err = capsys.readouterr().err
    assert says in err and err.count(path) == 1 and len(err) < 300, err
    assert "agafonov2013" not in err, "no list of built-in names"


def test_a_misspelt_builtin_name_suggests_the_nearest(capsys):
    assert main(["prove", "rudenko1967"]) == 2
    err = capsys.readouterr().err
    assert "did you mean 'rudenko1976'" in err and err.count("rudenko1967") == 1


def test_deeply_nested_inputs_are_bad_input(tmp_path, capsys):
    scene = tmp_path / "deep.toml"
    scene.write_text('name = "deep"\nkind = "lyapunov"\n[parameters]\nq = ' + "[" * 5000 + "]" * 5000 + "\n")
    assert main(["prove", str(scene), "-o", str(tmp_path)]) == 2
    assert "nested too deeply" in capsys.readouterr().err
    cert = tmp_path / "deep.json"
    cert.write_text("[" * 100000 + "]" * 100000)
    assert main(["check", str(cert)]) == 2
    assert "internal error" not in capsys.readouterr().err


def test_campaign_out_is_checked_before_any_case_runs(tmp_path, monkeypatch, capsys):
    import rigor_gyro.campaign as campaign

    def must_not_run(*a, **k):
        raise AssertionError("a case ran before --out was checked")
    monkeypatch.setattr(campaign, "run_campaign", must_not_run)
    blocker = tmp_path / "file"
    blocker.write_text("")
    assert main(["campaign", "--kind", "eigenfrequencies", "--cases", "1", "-o", str(blocker)]) == 2
    assert "is a file" in capsys.readouterr().err


# --- the wall-clock budget ------------------------------------------------------------------------------

def test_time_limit_is_checked_as_input(capsys):
    for bad in ("0", "-1", "nan", "inf", "abc", "1e9"):
        with pytest.raises(SystemExit) as e:
            main(["prove", "rudenko1976", "--time-limit", bad])
        assert e.value.code == 2
    assert check_time_limit(None) is None and check_time_limit(2) == 2.0
    with pytest.raises(ValueError):
        check_time_limit(True)


def test_time_limit_alarm_interrupts_and_restores():
    import signal
    with pytest.raises(TimeLimitReached):
        with time_limit(0.05) as budget:
            while True:
                pass
    assert budget.fired and budget.expired()
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)
    with time_limit(5) as budget:
        pass
    assert not budget.expired() and 0 < budget.remaining() <= 5
    assert Budget(None).remaining() is None and not Budget(None).expired()


def test_a_proof_out_of_time_writes_an_inconclusive_certificate_that_checks(tmp_path, capsys, monkeypatch):
    """No attempt finished: every claim inconclusive for the time limit; nothing is refuted."""
    from rigor_gyro.kinds import lyapunov

    real = lyapunov.attempt

    def slow(*a, **k):
        time.sleep(0.5)                       # Python code: the alarm interrupts it
        return real(*a, **k)
    monkeypatch.setattr(lyapunov, "attempt", slow)
    assert main(["prove", "agafonov2013", "-o", str(tmp_path), "--time-limit", "0.2"]) == 3
    cert = json.loads((tmp_path / "agafonov2013.json").read_text())
    assert cert["verdict"] == "inconclusive"
    assert all(c["status"] == "inconclusive" and "time limit of 0.2 s" in c["reason"] for c in cert["claims"])
    assert any("time limit" in n for n in cert["notes"])
    capsys.readouterr()
    assert main(["check", "-q", str(tmp_path / "agafonov2013.json")]) == 0


def test_a_proof_out_of_time_keeps_the_last_finished_attempt(monkeypatch):
    """The first attempt finishes with one claim undecided; the second is interrupted: the certificate is
    the first attempt, its decided claims kept, the undecided one inconclusive for the time limit."""
    from rigor_gyro import load_scene, prove_scene
    from rigor_gyro.kinds import eigenfrequencies

    real = eigenfrequencies.attempt
    calls = []

    def staged(model, wanted, prec):
        calls.append(prec)
        if len(calls) > 1:
            time.sleep(10)
        a = real(model, wanted, prec)
        a.claims[1].status = Status.INCONCLUSIVE    # nu_ordering left undecided: escalation goes on
        return a
    monkeypatch.setattr(eigenfrequencies, "attempt", staged)
    t0 = time.monotonic()
    cert = prove_scene(load_scene("rudenko1976"), time_limit=1.0)
    assert time.monotonic() - t0 < 5
    assert len(calls) == 2
    statuses = {c.id: c.status for c in cert.claims}
    assert statuses["roots"] is Status.PROVED and statuses[cert.claims[1].id] is Status.INCONCLUSIVE
    assert "time limit of 1 s" in cert.claims[1].reason
    assert cert.precision_bits == calls[0]
    assert cert.quantities, "the finished attempt's enclosures are kept"


def test_without_a_time_limit_nothing_changes(tmp_path):
    from rigor_gyro import load_scene, prove_scene
    a = prove_scene(load_scene("rudenko1976")).to_json()
    b = prove_scene(load_scene("rudenko1976"), time_limit=600).to_json()
    assert b.pop("settings") == {**a.pop("settings"), "time_limit": 600}
    a.pop("integrity"), b.pop("integrity")
    assert a == b


def test_a_paving_out_of_time_leaves_undecided_leaves_that_check():
    from rigor_gyro.margins.check import check_paving
    from rigor_gyro.margins.paving import box_scene, pave
    from rigor_gyro.margins.report import paving_json
    from rigor_gyro.scene import load_scene
    bs = box_scene(load_scene("margin_rudenko_general_eps_omega2"))     # not decided on the first level
    p = pave(bs, time_limit=1e-6)        # the alarm ends the first batch: nothing evaluated, the whole box pending
    assert p.evaluated == 0 and p.verdict == "inconclusive" and p.pending
    for c in p.claims:
        if any(s == "undecided" for _, s in c.boxes):
            assert "time limit" in c.reasons["undecided"]
    data = json.loads(json.dumps(paving_json(p)))
    assert "time limit" in data["stopped"]
    results = check_paving(data)
    assert all(ok for _, ok, _ in results), [r for r in results if not r[1]]
    from rigor_gyro.margins.report import render_paving
    assert "stopped: time limit" in render_paving(data)


# --- progress -------------------------------------------------------------------------------------------

class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_progress_only_on_a_terminal_outside_ci(monkeypatch):
    from rigor_gyro import progress
    monkeypatch.delenv("CI", raising=False)
    monkeypatch.setattr("sys.stderr", io.StringIO())
    assert not progress.wanted()
    monkeypatch.setattr("sys.stderr", _Tty())
    from importlib.util import find_spec
    assert progress.wanted() is (find_spec("tqdm") is not None)
    assert not progress.wanted(enabled=False)
    monkeypatch.setenv("CI", "true")
    assert not progress.wanted()


def test_paving_progress_fits_an_80_column_terminal(monkeypatch, tmp_path):
    pytest.importorskip("tqdm")
    monkeypatch.delenv("CI", raising=False)
    monkeypatch.setenv("COLUMNS", "80")
    tty = _Tty()
    monkeypatch.setattr("sys.stderr", tty)
    code = main(["prove", "margin_rudenko_brackets_tolerance", "-o", str(tmp_path), "-j", "1"])
    assert code in (0, 1, 3)
    lines = [x for x in tty.getvalue().replace("\r", "\n").split("\n") if x.strip()]
    assert lines, "a terminal shows progress"
    assert max(len(x.replace("\x1b[A", "")) for x in lines) <= 80, max(lines, key=len)


def test_point_progress_names_the_phase_and_precision(monkeypatch, tmp_path):
    pytest.importorskip("tqdm")
    seen = []
    from rigor_gyro import load_scene, prove_scene
    prove_scene(load_scene("rudenko1976"), progress=lambda phase, bits: seen.append((phase, bits)))
    assert seen[0][0] == "" and all(b >= 64 for _, b in seen)
    assert any(p for p, _ in seen), "the kind's phases are reported"


def test_the_prove_line_prints_short_times_honestly(tmp_path, capsys):
    assert main(["prove", "rudenko1976", "-q", "-o", str(tmp_path)]) == 0
    line = capsys.readouterr().out
    assert " 0.00 s" not in line


def test_no_hand_written_carriage_return_printers_are_left():
    import inspect
    assert "\\r" not in inspect.getsource(cli)


def test_a_threshold_out_of_time_keeps_its_certified_bracket(monkeypatch, capsys):
    from rigor_gyro.margins import threshold
    real = threshold._status
    seconds_given = []

    def slow(*a):
        seconds_given.append(a[-1])
        time.sleep(0.2)
        return real(*a)
    monkeypatch.setattr(threshold, "_status", slow)
    scene = threshold.Scene(**{**vars(__import__("rigor_gyro").load_scene("rudenko1976"))})
    res = threshold.find_threshold(scene, "Omega2", lo="1e-6", hi="1", claim="bracket_2", width="1e-12",
                                   time_limit=1.0)
    assert "time limit of 1 s" in res.stopped and res.exit_code == 3
    assert 3 <= len(res.steps) <= 7
    assert all(s is not None and 0 < s <= 1.0 for s in seconds_given), "each proof gets what is left"
    p, r = res.proved_at, res.refuted_at
    by_value = {s["value"]: s["status"] for s in res.steps}
    assert by_value[threshold.fraction_text(p)] == "proved" and by_value[threshold.fraction_text(r)] == "refuted"
    assert main(["margin", "rudenko1976", "--param", "Omega2", "--scan", "3", "--time-limit", "5"]) == 2


@pytest.mark.parametrize("stalled", [False, True], ids=["escalated", "stalled"])
def test_more_precision_that_decides_less_does_not_weaken_the_certificate(monkeypatch, stalled):
    """A higher precision can spend a budget sooner and leave undecided what a lower one decided (a [moment]
    law's quadrature: refuted with 60 s, all inconclusive at 2048 bits without a limit; hostile fuzzing). The
    certificate is then the last attempt that decided every claim any attempt decided."""
    from rigor_gyro import load_scene, prove_scene
    from rigor_gyro.core.outcome import Status
    from rigor_gyro.kinds import eigenfrequencies
    real = eigenfrequencies.attempt
    calls = []

    def staged(model, wanted, prec):
        calls.append(prec)
        a = real(model, wanted, prec)
        a.widths_met, a.width_quantities = False, ()         # escalation goes on
        if prec > 128:                                       # the higher precision decides nothing
            for c in a.claims:
                c.status, c.decides, c.reason = Status.INCONCLUSIVE, None, "budget spent"
            a.stalled = stalled                              # "more precision does not help": escalation stops
        return a
    monkeypatch.setattr(eigenfrequencies, "attempt", staged)
    cert = prove_scene(load_scene("rudenko1976"), prec=128, maxprec=256)
    assert cert.precisions_tried == [128, 256] and cert.precision_bits == 128
    assert all(c.status is Status.PROVED for c in cert.claims), [c.status for c in cert.claims]
    from rigor_gyro.check import check_certificate
    from rigor_gyro.reproduce import forget
    forget()                                  # the texts check re-proves with the same (patched) kind
    report = check_certificate(json.loads(json.dumps(cert.to_json())))
    forget()
    assert report.ok, report.first_failure


def test_a_time_limited_run_keeps_its_best_finished_attempt_and_checks(monkeypatch):
    """The same with a time limit: 128 bits decides every claim, 256 bits none, 512 bits outlasts the limit. The
    certificate is the 128-bit attempt, its note says so, and the checker's re-proof (up to the last finished
    attempt, 256 bits, without a limit) re-derives it."""
    from rigor_gyro import load_scene, prove_scene
    from rigor_gyro.check import check_certificate
    from rigor_gyro.core.outcome import Status
    from rigor_gyro.kinds import eigenfrequencies
    from rigor_gyro.reproduce import forget
    real = eigenfrequencies.attempt

    def staged(model, wanted, prec):
        if prec > 256:
            time.sleep(30)
        a = real(model, wanted, prec)
        a.widths_met, a.width_quantities = False, ()
        if prec > 128:
            for c in a.claims:
                c.status, c.decides, c.reason = Status.INCONCLUSIVE, None, "budget spent"
        return a
    monkeypatch.setattr(eigenfrequencies, "attempt", staged)
    cert = json.loads(json.dumps(prove_scene(load_scene("rudenko1976"), prec=128, maxprec=1024,
                                             time_limit=3.0).to_json()))
    assert cert["precisions_tried"] == [128, 256] and cert["precision_bits"] == 128
    assert all(c["status"] == "proved" for c in cert["claims"])
    assert any("the attempt at 128 bits" in n and "at 256 bits, decided fewer" in n for n in cert["notes"]), cert["notes"]
    forget()
    report = check_certificate(cert)
    forget()
    assert report.ok, report.first_failure
