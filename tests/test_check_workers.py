"""``rigor-gyro check -j N``: a paving's decided sub-boxes re-evaluated on N processes, the same report."""
import json

from rigor_gyro.cli import main


def test_a_paving_checks_the_same_on_two_workers(tmp_path, capsys):
    from tests.test_paving_check import _mixed
    path = tmp_path / "p.json"
    path.write_text(json.dumps(_mixed()))
    assert main(["check", str(path)]) == 0
    one = [ln.rsplit(" (", 1)[0] for ln in capsys.readouterr().out.splitlines()]
    assert main(["check", "-j", "2", str(path)]) == 0
    two = [ln.rsplit(" (", 1)[0] for ln in capsys.readouterr().out.splitlines()]
    assert one == two and any("every decided sub-box re-evaluated" in ln for ln in one)
    data = json.loads(path.read_text())
    last = max(i for i, b in enumerate(data["claims"][0]["boxes"]) if b["status"] == "proved")
    data["claims"][0]["boxes"][last]["status"] = "refuted"
    from tests.forgery import reseal
    path.write_text(json.dumps(reseal(data)))
    assert main(["check", "-j", "2", str(path)]) == 1
    assert main(["check", "-j", "0", str(path)]) == 2
