"""Anytime and resumable pavings (issue 38): best-first order, box budget, Ctrl-C, checkpoints, --resume
and --refine. The done-when: a paving stopped by a budget (or killed after a checkpoint) and resumed is
exactly the uninterrupted one; a partial paving checks; a tampered one is refused by check and resume."""
import json
from fractions import Fraction

import pytest

from rigor_gyro.check import check_certificate
from rigor_gyro.cli import main
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins.executors import Executor
from rigor_gyro.margins.order import Frontier, Group
from rigor_gyro.margins.paving import INTERRUPTED, box_scene, pave
from rigor_gyro.margins.report import paving_json, render_paving
from rigor_gyro.margins.resume import resume_state
from rigor_gyro.scene import parse_scene
from tests.forgery import failures, reseal
from tests.test_margins import RUDENKO_BOX

#: two brackets over eps x Omega2, decided on sub-boxes of several sizes (79 evaluations)
PLANE = (RUDENKO_BOX.replace('"[0.1, 0.12]"', '"[0.1, 0.2]"').replace('"0.625 +- 0.025"', '"[0.001, 0.2]"')
         .replace('only = [', 'only = ["bracket_2", "bracket_4"] #').replace('"1/16"', '"1/8"') + 'max_points = "1"\n')
#: bracket (8) along Omega2 alone: proved on sub-boxes of several sizes, undecided near Omega2 = 0 (9 evaluations,
#: batches of 1, 2, 2, 2, 2 boxes)
LINE = (RUDENKO_BOX.replace('"[0.1, 0.12]"', '"0.1076"').replace('"0.625 +- 0.025"', '"[0.001, 0.2]"')
        .replace('only = [', 'only = ["bracket_2"] #') + 'max_points = "2"\n')


def _bs(text, priority="volume"):
    bs = box_scene(parse_scene(text))
    bs.priority = priority
    return bs


def _json(p):
    return json.loads(json.dumps(paving_json(p)))


def _resumed(data, **kw):
    bs, state = resume_state(data)
    return _json(pave(bs, state=state, **kw))


@pytest.mark.parametrize("text,priority,budget", [(PLANE, "volume", 5),
                                                  (LINE, "volume", 3), (LINE, "boundary", 2)])
def test_a_paving_stopped_by_a_box_budget_and_resumed_is_the_uninterrupted_one(text, priority, budget):
    full = _json(pave(_bs(text, priority)))
    data, runs = _json(pave(_bs(text, priority), box_budget=budget)), 0
    while data.get("stopped"):
        runs += 1
        assert "box budget" in data["stopped"] and data["pending"] and data["budget_exhausted"]
        assert all(not c["points"] for c in data["claims"]) and data["verdict"] != "proved"
        data = _resumed(data, box_budget=budget)
    assert runs >= 2
    assert data == full                   # every byte: leaves, order, statuses, reasons, point proofs, verdict


def _half_plane(kind, pj, oj, mj, box_json, claims, prec):
    """A stand-in for a kind's box rigour, exact and instant: bracket_2 is "eps + Omega2 > 1", bracket_4
    "eps > 1/3", each proved where it holds on the whole box, refuted where it fails on the whole box."""
    box = Box.from_json(json.loads(box_json))
    (elo, ehi), (olo, ohi) = box.interval("eps"), box.interval("Omega2")
    ends = {"bracket_2": (elo + olo - 1, ehi + ohi - 1), "bracket_4": (elo - Fraction(1, 3), ehi - Fraction(1, 3))}
    return {c: ["proved", "holds"] if ends[c][0] > 0 else ["refuted", "fails"] if ends[c][1] <= 0 else
            ["undecided", "both"] for c in claims}


@pytest.fixture
def half_plane(monkeypatch):
    import rigor_gyro.margins.paving as paving
    import rigor_gyro.margins.resume as resume
    from rigor_gyro.margins import order
    monkeypatch.setattr(paving, "evaluate_task", _half_plane)
    monkeypatch.setattr(resume, "evaluate_task", _half_plane)
    monkeypatch.setitem(order.BATCH, "boundary", 6)
    text = (RUDENKO_BOX.replace('"[0.1, 0.12]"', '"[0.001, 1]"').replace('"0.625 +- 0.025"', '"[0.001, 1]"')
            .replace('only = [', 'only = ["bracket_2", "bracket_4"] #').replace('"1/16"', '"1/32"')
            + 'max_points = "0"\n')
    return text


def test_the_boundary_priority_goes_deeper_next_to_the_decided_regions_and_resumes_exactly(half_plane):
    """On a stand-in rigour (two half-planes): run to the end, both orders give the same leaves; on a budget,
    the boundary order has refined the boxes next to the decided regions further than breadth-first, its
    pending boxes are in score order, and the paving stopped and resumed in pieces is the uninterrupted one."""
    volume, boundary = _json(pave(_bs(half_plane))), _json(pave(_bs(half_plane, "boundary")))
    leaves = lambda d: sorted((json.dumps(b["box"]), b["status"]) for c in d["claims"] for b in c["boxes"])
    assert leaves(volume) == leaves(boundary) and volume["levels"] == boundary["levels"]
    assert boundary["settings"]["priority"] == "boundary" and "priority" not in volume["settings"]
    part_v, part_b = _json(pave(_bs(half_plane), box_budget=60)), _json(pave(_bs(half_plane, "boundary"), box_budget=60))
    assert part_b["levels"] > part_v["levels"] + 2
    scores = [g["score"] for g in part_b["pending"]]
    assert scores == sorted(scores, reverse=True) and scores[0] >= 1
    data, runs = part_b, 1
    while data.get("stopped"):
        data, runs = _resumed(data, box_budget=97), runs + 1
    assert runs >= 3 and data == boundary


def test_the_order_is_the_same_on_a_process_pool():
    with Executor(2) as pool:
        assert _json(pave(_bs(LINE, "boundary"), pool, box_budget=6)) == _json(pave(_bs(LINE, "boundary"), box_budget=6))


def test_a_partial_paving_is_confirmed_by_the_checker_and_says_how_to_continue():
    data = _json(pave(_bs(PLANE), box_budget=20))
    report = check_certificate(data)
    assert report.ok, report.first_failure
    assert any(r.item == "pending" and r.ok and "pending sub-box" in r.message for r in report.results)
    for c in data["claims"]:
        assert c["reasons"]["undecided"] == data["stopped"] and c["sub_boxes"]["undecided"] >= 1
    assert "pending sub-box(es) left undecided (`rigor-gyro prove --resume" in render_paving(data)


def _pending_box(data):
    return data["pending"][0]["boxes"][0]


def _relabel_pending(data, status):
    box = _pending_box(data)
    for c in data["claims"]:
        for b in c["boxes"]:
            if b["box"] == box:
                b["status"] = status


TAMPERS = {
    # a pending box (never evaluated) stated proved: the re-evaluation may well agree, the pending list not
    "a pending box stated proved": (lambda d: _relabel_pending(d, "proved"), "pending"),
    "a pending box dropped from the list, its claims' reason kept": (
        lambda d: d["pending"].pop(0) and d["pending"].clear(), "bracket_2"),
    "a pending pair that is not the halves of a split": (
        lambda d: d["pending"][0]["boxes"].reverse(), "pending"),
    "a pending box claimed for a claim it is decided for": (lambda d: d["pending"].append(
        {"boxes": [next(b["box"] for b in d["claims"][0]["boxes"] if b["status"] == "proved")],
         "claims": ["bracket_2"], "score": 0}), "pending"),
    "pending boxes in a paving that ran its course": (lambda d: d.pop("stopped"), "pending"),
    "a negative score": (lambda d: d["pending"][0].update(score=-1), "schema"),
}


@pytest.mark.parametrize("name", sorted(TAMPERS))
def test_a_tampered_partial_paving_is_rejected_by_check_and_by_resume(name):
    change, item = TAMPERS[name]
    data = _json(pave(_bs(LINE), box_budget=3))
    assert any(b["status"] == "proved" for b in data["claims"][0]["boxes"])
    change(data)
    reseal(data)
    assert item in {i for i, _ in failures(data)}, failures(data)
    with pytest.raises(ParameterError, match="fails its check|does not conform"):
        resume_state(data)


def test_resume_refuses_a_paving_that_ran_its_course_and_a_coarser_refinement():
    data = _json(pave(_bs(LINE)))
    with pytest.raises(ParameterError, match="nothing to resume"):
        resume_state(data)
    with pytest.raises(ParameterError, match="at most that"):
        resume_state(data, refine="1/8")


def test_an_interrupted_paving_is_partial_checks_and_resumes_to_the_uninterrupted_one():
    class CtrlC(Executor):
        calls = 0

        def map(self, fn, tasks):
            CtrlC.calls += 1
            if CtrlC.calls == 4:
                raise KeyboardInterrupt
            return super().map(fn, tasks)

    with pytest.raises(KeyboardInterrupt):        # a library call (a threshold's paving) is not swallowed
        pave(_bs(LINE), CtrlC(1))
    CtrlC.calls = 0
    p = pave(_bs(LINE), CtrlC(1), keep_on_interrupt=True)
    assert p.stopped == INTERRUPTED and p.pending and p.evaluated == 5       # three batches: 1 + 2 + 2 boxes
    data = _json(p)
    assert check_certificate(data).ok
    assert _resumed(data) == _json(pave(_bs(LINE)))


def test_a_run_killed_after_a_checkpoint_resumes_from_it_to_the_uninterrupted_one():
    written = []

    def checkpoint(p):
        written.append(_json(p))
        if len(written) == 3:
            raise SystemExit("killed")      # as if the process died right after writing it

    with pytest.raises(SystemExit):
        pave(_bs(LINE, "boundary"), checkpoint=checkpoint, checkpoint_every=0.0)
    last = written[-1]
    assert "checkpoint after" in last["stopped"] and check_certificate(last).ok
    assert _resumed(last) == _json(pave(_bs(LINE, "boundary")))


def test_refine_splits_only_the_undecided_sub_boxes_and_gives_a_fresh_paving_s_leaves():
    coarse = _json(pave(_bs(LINE.replace('"1/16"', '"1/8"'))))
    bs, state = resume_state(coarse, refine="1/16")
    fine = _json(pave(bs, state=state))
    assert fine["settings"]["box_resolution"] == "1/16" and fine["scene"]["options"]["box_resolution"] == "1/16"
    assert check_certificate(fine).ok
    old, new = coarse["claims"][0]["boxes"], fine["claims"][0]["boxes"]
    decided = [b for b in old if b["status"] != "undecided"]
    assert decided and new[:len(decided)] == decided              # kept, first, as they were
    undecided = [Box.from_json(b["box"]) for b in old if b["status"] == "undecided"]
    for b in new[len(decided):]:                                  # the rest lie in the old undecided ones
        x = Box.from_json(b["box"])
        assert any(all(u.interval(n)[0] <= x.interval(n)[0] and x.interval(n)[1] <= u.interval(n)[1]
                       for n in x.names) for u in undecided)
    fresh = _json(pave(_bs(LINE)))
    leaves = lambda d: sorted((json.dumps(b["box"]), b["status"]) for b in d["claims"][0]["boxes"])
    assert leaves(fine) == leaves(fresh) and fine["verdict"] == fresh["verdict"]


def test_the_frontier_pops_best_first_and_puts_a_batch_back_in_place():
    whole = Box.of({"x": (0, 1)})
    halves = whole.split(whole)
    quarters = halves[0].split(whole)
    f = Frontier("boundary", [Group(halves, ("c",), 0), Group(quarters, ("c",), 1)])
    assert len(f) == 4
    assert [g.score for g in f.pop_batch(2)] == [1]
    f.restore_batch()
    assert [g.score for g in f.groups()] == [1, 0]
    v = Frontier("volume", [Group(quarters, ("c",), 1), Group(halves, ("c",), 0)])
    assert [g.boxes for g in v.pop_batch(10)] == [halves, quarters]
    with pytest.raises(ParameterError, match="choose one of volume, boundary"):
        Frontier("deepest")


def test_box_budget_resume_and_refine_on_the_command_line(tmp_path, capsys):
    (tmp_path / "line.toml").write_text(LINE)
    full, part, resumed = tmp_path / "full", tmp_path / "part", tmp_path / "resumed"
    assert main(["prove", str(tmp_path / "line.toml"), "-o", str(full), "-q", "-j", "1"]) == 3
    assert main(["prove", str(tmp_path / "line.toml"), "-o", str(part), "-q", "-j", "1", "--box-budget", "3"]) == 3
    assert "--resume" in capsys.readouterr().out
    name = "rudenko_box"
    assert main(["check", "-q", str(part / f"{name}.json")]) == 0
    assert main(["prove", "--resume", str(part / f"{name}.json"), "-o", str(resumed), "-q", "-j", "1"]) == 3
    assert (resumed / f"{name}.json").read_text() == (full / f"{name}.json").read_text()
    assert main(["prove", "--resume", str(full / f"{name}.json"), "-o", str(resumed), "-q"]) == 2
    assert "nothing to resume" in capsys.readouterr().err
    assert main(["prove", "--resume", str(full / f"{name}.json"), "--refine", "1/32", "-o", str(resumed), "-q",
                 "-j", "1"]) == 1     # at 1/32 a point proof in an undecided sub-box refutes bracket (8)
    assert json.loads((resumed / f"{name}.json").read_text())["settings"]["box_resolution"] == "1/32"
    assert main(["prove", str(tmp_path / "line.toml"), "--refine", "1/32", "-o", str(part)]) == 2
    assert main(["prove", "rudenko1976", "--box-budget", "3", "-o", str(part)]) == 2
    bad = json.loads((part / f"{name}.json").read_text())
    _relabel_pending(bad, "proved")
    reseal(bad)
    (tmp_path / "bad.json").write_text(json.dumps(bad))
    assert main(["prove", "--resume", str(tmp_path / "bad.json"), "-o", str(resumed), "-q"]) == 2
    assert "fails its check" in capsys.readouterr().err


def test_ctrl_c_on_the_command_line_writes_the_paving_so_far_and_exits_130(tmp_path, monkeypatch, capsys):
    from rigor_gyro.margins import executors
    real, calls = executors.Executor.map, []

    def interrupted(self, fn, tasks):
        calls.append(fn)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(self, fn, tasks)

    monkeypatch.setattr(executors.Executor, "map", interrupted)
    (tmp_path / "line.toml").write_text(LINE)
    assert main(["prove", str(tmp_path / "line.toml"), "rudenko1976", "-o", str(tmp_path), "-q", "-j", "1"]) == 130
    data = json.loads((tmp_path / "rudenko_box.json").read_text())
    assert data["stopped"] == INTERRUPTED and data["pending"] and check_certificate(data).ok
    assert not (tmp_path / "rudenko1976.json").exists()          # no further scene after Ctrl-C
    monkeypatch.setattr(executors.Executor, "map", real)
    resumed, whole = _resumed(data), _json(pave(_bs(LINE)))
    assert resumed["claims"] == whole["claims"] and resumed["verdict"] == whole["verdict"]    # the scene's file differs


def test_a_run_killed_by_sigkill_resumes_from_its_last_checkpoint(tmp_path):
    """A real process, killed (SIGKILL) once its first checkpoint is on disk: the file there is a partial
    certificate that checks, and --resume makes it the uninterrupted paving, byte for byte."""
    import os
    import signal
    import subprocess
    import sys
    import time
    (tmp_path / "plane.toml").write_text(PLANE.replace('max_points = "1"', 'max_points = "0"'))
    out = tmp_path / "killed"
    proc = subprocess.Popen([sys.executable, "-m", "rigor_gyro.cli", "prove", str(tmp_path / "plane.toml"), "-o",
                             str(out), "-q", "-j", "1", "--checkpoint-every", "0.01"])
    path, t0 = out / "rudenko_box.json", time.monotonic()
    while not path.exists() and proc.poll() is None and time.monotonic() - t0 < 60:
        time.sleep(0.005)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    data = json.loads(path.read_text())
    if not data.get("stopped"):
        pytest.skip("the run ended before it could be killed")
    assert "checkpoint after" in data["stopped"] and check_certificate(data).ok
    assert main(["prove", "--resume", str(path), "-o", str(out), "-q", "-j", "1"]) == 3
    assert main(["prove", str(tmp_path / "plane.toml"), "-o", str(tmp_path / "whole"), "-q", "-j", "1"]) == 3
    assert path.read_text() == (tmp_path / "whole" / "rudenko_box.json").read_text()


def test_a_broken_worker_pool_leaves_the_batch_in_flight_pending():
    from concurrent.futures.process import BrokenProcessPool

    class Broken(Executor):
        calls = 0

        def map(self, fn, tasks):
            Broken.calls += 1
            if Broken.calls == 3:
                raise BrokenProcessPool("a worker died")
            return super().map(fn, tasks)

    p = pave(_bs(LINE), Broken(1))
    assert "executor broke (BrokenProcessPool: a worker died)" in p.stopped and p.evaluated == 3
    assert sum(len(g.boxes) for g in p.pending) == 2                    # the third batch, not evaluated
    data = _json(p)
    assert check_certificate(data).ok and _resumed(data) == _json(pave(_bs(LINE)))
