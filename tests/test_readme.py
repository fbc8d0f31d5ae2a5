"""README sections generated from the certificates stay in step with them."""
from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _tool():
    spec = importlib.util.spec_from_file_location("papers_wrong", ROOT / "tools" / "papers_wrong.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_what_the_papers_got_wrong_is_generated_from_the_certificates():
    tool = _tool()
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert tool.BEGIN in readme and tool.END in readme
    current = tool.BEGIN + readme.split(tool.BEGIN, 1)[1].split(tool.END, 1)[0] + tool.END
    assert current == tool.section(), "regenerate with: python tools/papers_wrong.py --write"
    for title in tool.PAPERS:
        assert f"### {title}" in current
    assert "Assertions certified false" in current and "misprints found by the classifier" in current


def test_ci_runs_the_readme_test_command():
    """The README promises that CI runs exactly its test command: the set-up block's pytest line."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    block = readme.split("## Set-up: two commands", 1)[1].split("```sh", 1)[1].split("```", 1)[0]
    commands = [line.split("#", 1)[0].strip() for line in block.strip().splitlines()]
    assert len(commands) == 2, "the set-up block has two commands"
    test = commands[1].replace("python3 ", "python ", 1)
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert test in [line.strip() for line in ci.splitlines()], f"{test!r} is not what .ci/run runs"
