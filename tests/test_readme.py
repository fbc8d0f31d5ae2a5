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
