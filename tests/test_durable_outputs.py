"""Output durability (rigor_gyro.report.write_pair): atomic always, flushed to the disk only when asked."""
import os

from rigor_gyro import report


def test_outputs_are_flushed_only_with_the_durable_variable(tmp_path, monkeypatch):
    calls = []
    real = os.fsync
    monkeypatch.setattr(os, "fsync", lambda fd: calls.append(fd) or real(fd))
    monkeypatch.delenv(report.DURABLE_ENV, raising=False)
    report.write_pair(tmp_path, "x", "{}\n", "# x\n", {"total_s": 1})
    assert calls == [] and (tmp_path / "x.json").read_text() == "{}\n" and (tmp_path / "x.md").read_text() == "# x\n"
    monkeypatch.setenv(report.DURABLE_ENV, "1")
    report.write_pair(tmp_path, "y", "{}\n", "# y\n", {"total_s": 1})
    assert len(calls) == 3                      # the certificate, the report, the folder; never the timings
    assert sorted(p.name for p in tmp_path.iterdir()) == ["timings", "x.json", "x.md", "y.json", "y.md"]
