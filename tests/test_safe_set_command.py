"""``rigor-gyro safe-set``: the safe set of a written paving, its yield, the CSV and the figure."""
import json

from rigor_gyro.cli import main
from tests.forgery import reseal


def _paving_file(tmp_path):
    from tests.test_paving_check import _mixed
    path = tmp_path / "p.json"
    path.write_text(json.dumps(_mixed()))
    return path


def test_the_yield_the_csv_and_bad_input(tmp_path, capsys):
    path = _paving_file(tmp_path)
    assert main(["safe-set", str(path), "--law", "normal 3", "--csv", "-o", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "safe volume fraction in [" in out and "certified yield (every parameter normal, truncated at +-3 sigma) in [" in out
    rows = (tmp_path / "o" / f"{json.loads(path.read_text())['scene']['name']}_leaves.csv").read_text().splitlines()
    assert rows[0].endswith(",bracket_2,all") and len(rows) > 2
    assert main(["safe-set", str(path), "--claims", "nope"]) == 2
    assert main(["safe-set", str(path), "--law", "gauss"]) == 2
    data = json.loads(path.read_text())
    data["claims"][0]["boxes"][0]["status"] = "proved" if data["claims"][0]["boxes"][0]["status"] != "proved" else "refuted"
    path.write_text(json.dumps(data))
    assert main(["safe-set", str(path)]) == 2                       # the digest no longer matches
    path.write_text(json.dumps(reseal(data)))
    assert main(["safe-set", str(path)]) == 0                       # resealed: the statuses are check's to verify
    assert "digest" in capsys.readouterr().err


def test_the_safe_set_figure_on_chosen_axes_and_formats(tmp_path, capsys):
    import pytest
    pytest.importorskip("matplotlib")
    path = _paving_file(tmp_path)
    assert main(["safe-set", str(path), "--plots", "--format", "png,svg", "-o", str(tmp_path / "f")]) == 0
    assert sorted(p.suffix for p in (tmp_path / "f").iterdir()) == [".png", ".svg"]
    assert main(["safe-set", str(path), "--plots", "--axes", "nope", "-o", str(tmp_path / "f")]) == 2
    assert main(["safe-set", str(path), "--plots", "--format", "gif", "-o", str(tmp_path / "f")]) == 2
