"""The package as users install it: the built wheel holds every file of the source tree.

A wheel that lacks a data folder (the stress scenes once) installs a tool in which no scene loads; the
editable checkout hides it. This builds the wheel the ordinary way (setuptools, no build isolation so no
network) and compares its file list with the tree; ``.ci/run`` then installs that kind of wheel into a
fresh venv without extras and proves the built-in scenes from there.
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _tree_files() -> set[str]:
    return {p.relative_to(ROOT).as_posix() for p in (ROOT / "rigor_gyro").rglob("*")
            if p.is_file() and "__pycache__" not in p.parts and p.suffix not in (".pyc", ".pyo")}


@pytest.fixture(scope="module")
def wheel_names(tmp_path_factory) -> set[str]:
    pytest.importorskip("setuptools")
    out = tmp_path_factory.mktemp("wheel")
    # from a clean copy: setuptools reuses a stale build/ folder of the checkout, which would hide a file
    # that the package data no longer names
    src = out / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, src / name)
    shutil.copytree(ROOT / "rigor_gyro", src / "rigor_gyro", ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps", "--no-build-isolation",
                    "-w", str(out), str(src)], check=True, capture_output=True, cwd=out)
    wheels = list(out.glob("rigor_gyro-*.whl"))
    assert len(wheels) == 1, wheels
    return set(zipfile.ZipFile(wheels[0]).namelist())


def test_the_wheel_holds_every_file_of_the_tree(wheel_names):
    missing = sorted(_tree_files() - wheel_names)
    assert not missing, f"the wheel lacks {missing[:10]}: widen [tool.setuptools.package-data] in pyproject.toml"
    assert any(n.startswith("rigor_gyro/scenes/stress/") for n in wheel_names)


def test_the_wheel_holds_no_stray_files_and_ships_the_license(wheel_names):
    ours = {n for n in wheel_names if n.startswith("rigor_gyro/")}
    assert ours == _tree_files() & ours and ours, sorted(ours - _tree_files())[:10]
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in wheel_names)
    meta = next(n for n in wheel_names if n.endswith(".dist-info/METADATA"))
    assert meta


def test_every_builtin_scene_loads_from_package_resources():
    """What `rigor-gyro list` does from an installed package: every group's scenes read through
    importlib.resources, none from the repository's paths."""
    from rigor_gyro.scene import GROUPS, builtin_scenes, load_scene
    for group in GROUPS:
        names = builtin_scenes(group)
        assert names, group
        for name in names:
            assert load_scene(name).name == name
