"""Architecture rules, checked on the source text and its import graph (tests/import_graph.py):

* precision is set only in core/balls.py;
* core/ imports nothing from kinds/ or the application layer;
* no import cycles anywhere in the package, and no module imports another module's private name;
* a kind's rigorous modules (model, flow, moments, claims, paper) never import its approx or plots
  modules, nor numpy, scipy, mpmath or matplotlib (nor does any module outside the float side: the
  kinds' approx/plots/campaign modules and the benchmarks package rigor_gyro.bench); a kind never imports another kind; no kind imports
  the application layer;
* proving a built-in scene imports only its own kind package, and no float library.
"""
import re
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import import_graph  # noqa: E402

PKG = Path(__file__).resolve().parent.parent / "rigor_gyro"
GRAPH = import_graph.graph()
APPLICATION = {"rigor_gyro", "rigor_gyro.__main__", "rigor_gyro.cli", "rigor_gyro.scene", "rigor_gyro.prover",
               "rigor_gyro.certificate", "rigor_gyro.report", "rigor_gyro.progress", "rigor_gyro.reproduce"}
FLOAT_SIDE = ("approx", "plots", "campaign")
FLOAT_LIBRARIES = ("numpy", "scipy", "mpmath", "matplotlib")


def _kind_of(module: str) -> str | None:
    parts = module.split(".")
    return parts[2] if len(parts) >= 3 and parts[1] == "kinds" else None


def _is_float_side(module: str) -> bool:
    """A kind's approx/plots/campaign module (or one named ``approx_*``, ...: a float twin split off one of
    them), or the benchmarks package (it times the float paths)."""
    return module.rsplit(".", 1)[-1].split("_")[0] in FLOAT_SIDE or module == "rigor_gyro.bench" \
        or module.startswith("rigor_gyro.bench.")


RIGOROUS = [m for m in GRAPH if not _is_float_side(m)]


def _imports_text(module: str) -> str:
    path = import_graph.package_modules()[module]
    return path.read_text(encoding="utf-8")


def test_the_tree_has_the_documented_shape():
    kinds = {p.name for p in (PKG / "kinds").iterdir() if p.is_dir() and not p.name.startswith("__")}
    assert kinds == {"eigenfrequencies", "lyapunov", "periodic_orbit"}
    for k in kinds:
        names = {p.stem for p in (PKG / "kinds" / k).glob("*.py")}
        assert {"__init__", "claims", "paper", "approx"} <= names, (k, names)
    assert not list(PKG.glob("approx")), "float code lives in each kind's approx.py"
    flat = {p.stem for p in PKG.glob("*.py")}
    assert flat <= {"__init__", "__main__", "cli", "scene", "certificate", "prover", "report", "check", "campaign",
                    "progress", "reproduce", "version"}, flat


def test_only_balls_sets_precision():
    for path in PKG.rglob("*.py"):
        text = path.read_text()
        if path.relative_to(PKG).as_posix() != "core/balls.py":
            assert not re.search(r"ctx\.prec\s*=|ctx\.dps\s*=|ctx\.cap\s*=|workprec\(", text), path


def test_core_imports_no_kind_and_no_application_module():
    for module, edges in GRAPH.items():
        if module.startswith("rigor_gyro.core"):
            bad = [e.target for e in edges if not e.target.startswith("rigor_gyro.core")]
            assert not bad, f"{module} imports {bad}"


def test_no_import_cycles():
    assert import_graph.cycles(GRAPH) == []


def test_no_module_imports_a_private_name_of_another():
    assert import_graph.private_imports(GRAPH) == []


def test_the_graph_sees_the_imports_it_must_see():
    """The rules above are only as good as the graph: a known lazy import and a known edge are in it."""
    cli = {e.target for e in GRAPH["rigor_gyro.cli"] if e.lazy}
    assert "rigor_gyro.prover" in cli
    assert "rigor_gyro.core.outcome" in {e.target for e in GRAPH["rigor_gyro.core.subdivision"]}
    fake = {"a": [import_graph.ImportEdge("a", "b")], "b": [import_graph.ImportEdge("b", "a")]}
    assert import_graph.cycles(fake) == [["a", "b"]]


def test_kinds_import_neither_other_kinds_nor_the_application():
    for module, edges in GRAPH.items():
        kind = _kind_of(module)
        if module.startswith("rigor_gyro.kinds"):
            up = [e.target for e in edges if e.target in APPLICATION]
            assert not up, f"{module} imports the application layer: {up}"
        if kind is None:
            continue
        others = [e.target for e in edges if _kind_of(e.target) not in (None, kind)]
        assert not others, f"{module} imports another kind: {others}"


def test_rigorous_modules_import_no_float_module():
    for module in RIGOROUS:
        # the command line's campaign and --plots are float-side entry points, imported lazily there only
        bad = [e.target for e in GRAPH[module] if _is_float_side(e.target)
               and not (module == "rigor_gyro.cli" and e.lazy)]
        assert not bad, f"{module} imports float-side module(s) {bad}"
        text = _imports_text(module)
        libs = "|".join(FLOAT_LIBRARIES)
        if module == "rigor_gyro.cli":   # --plots checks that the optional extra is installed
            text = re.sub(r"^\s*import matplotlib  # noqa: F401.*$", "", text, flags=re.M)
        assert not re.search(rf"^\s*(import|from)\s+({libs})\b", text, re.M), module


def test_no_float_literals_fed_to_balls_in_rigorous_modules():
    """arb(0.1)-style construction from a float literal would round silently."""
    for module in RIGOROUS:
        assert not re.search(r"arb\(\s*-?\d+\.\d*", _imports_text(module)), module


@pytest.mark.parametrize("scene", ["rudenko1976", "agafonov2013", "roitenberg1947"])
def test_proving_a_scene_imports_only_its_own_kind(scene):
    code = ("import sys; from rigor_gyro import load_scene, prove_scene;"
            f"s = load_scene({scene!r}); c = prove_scene(s); print(s.kind);"
            "print(sorted({m.split('.')[2] for m in sys.modules if m.startswith('rigor_gyro.kinds.')}));"
            f"print(sorted(m for m in {FLOAT_LIBRARIES!r} if m in sys.modules));"
            "print(sorted(m for m in sys.modules if m.endswith(('.approx', '.plots')) and 'rigor_gyro' in m))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    kind, kinds, floats, float_side = r.stdout.strip().splitlines()
    assert kinds == str([kind])
    assert floats == "[]"
    assert float_side == "[]"


def _tool(name: str):
    import importlib.util
    spec = importlib.util.spec_from_file_location(name, PKG.parent / "tools" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _named_mutants():
    return _tool("soundness_mutants").MUTANTS


def test_the_named_mutant_runs_put_last_times_killer_first_and_keep_every_test(tmp_path, monkeypatch):
    """tools/pytest_first.py only reorders (the same tests run); soundness_mutants reads each mutant's last
    killer from tools/mutant_kills.json (an order hint: a stale one moves nothing) and --record writes it."""
    plugin = _tool("pytest_first")

    class Item:
        def __init__(self, nodeid):
            self.nodeid = nodeid
    items = [Item(f"tests/t.py::t{i}") for i in range(6)] + [Item("tests/t.py::p[a b]")]
    monkeypatch.setenv("PYTEST_FIRST", "tests/t.py::t4\ntests/gone.py::x\ntests/t.py::p[a\ntests/t.py::t2\n")
    plugin.pytest_collection_modifyitems(None, None, items)
    assert [it.nodeid[-1] for it in items] == ["4", "]", "2", "0", "1", "3", "5"]
    monkeypatch.setenv("PYTEST_FIRST", "")
    plugin.pytest_collection_modifyitems(None, None, items)
    assert [it.nodeid[-1] for it in items] == ["4", "]", "2", "0", "1", "3", "5"]
    tool = _tool("soundness_mutants")
    # three mutants of one file, one of another: a new name takes the group of its file's mutants
    by_file = {}
    for name, file, *_ in tool.MUTANTS:
        by_file.setdefault(file, []).append(name)
    a, b, c = next(ns for ns in by_file.values() if len(ns) >= 3)[:3]
    d = next(ns for f, ns in by_file.items() if a not in ns)[0]
    kills = tmp_path / "kills.json"
    tool.write_kills({a: {"group": "g", "killed_by": "tests/t.py::t1[p q]", "run": "whole", "date": "x"},
                      b: {"group": "g", "killed_by": None, "run": "whole", "date": "x"},
                      d: {"group": "h", "killed_by": "tests/v.py", "run": "targeted", "date": "x"}}, kills)
    assert tool.killer_hints(kills) == {a: "tests/t.py::t1[p q]", d: "tests/v.py"}
    rows = [(a, "", "killed by tests/u.py::t2 (error)", 1.0), (b, "", "killed by tests/u.py::t3", 1.0),
            (c, "", "SURVIVED", 1.0), (d, "", "NOT RUN (pytest exit 4)", 1.0)]
    got = tool.record_kills(rows, None, targeted=True, path=kills, today="2026-12-06")
    assert got == tool.read_kills(kills)
    assert got[a] == {"group": "g", "killed_by": "tests/u.py::t2", "run": "targeted", "date": "2026-12-06"}
    assert got[b]["killed_by"] == "tests/u.py::t3"
    assert got[c] == {"group": "g", "killed_by": None, "run": "targeted", "date": "2026-12-06"}
    assert got[d] == {"group": "h", "killed_by": "tests/v.py", "run": "targeted", "date": "x"}
    assert list(got) == [a, b, d, c]
    assert tool.killer_hints(kills) == {a: "tests/u.py::t2", b: "tests/u.py::t3", d: "tests/v.py"}


def _mutation_md_groups() -> dict[str, int]:
    """The group table of proofs/mutation.md: | `group` | what | mutants | ... |, and its total row."""
    out = {}
    for line in (PKG.parent / "proofs" / "mutation.md").read_text(encoding="utf-8").splitlines():
        cells = [c.strip().strip("*") for c in line.split("|")]
        if len(cells) > 4 and re.fullmatch(r"`\w+`|all", cells[1]) and cells[3].isdigit():
            out[cells[1].strip("`")] = int(cells[3])
    return out


def test_every_named_mutant_is_recorded_killed_and_its_group_counted_in_mutation_md():
    """tools/mutant_kills.json holds one entry per mutant of tools/soundness_mutants.py, each with the test
    that killed it (a recorded survivor fails here), and proofs/mutation.md counts each group."""
    tool = _tool("soundness_mutants")
    names = [m[0] for m in tool.MUTANTS]
    kills = tool.read_kills()
    how = ("run `python tools/soundness_mutants.py --only NAME ... --tests FILE ... --record [--group GROUP]` "
           "and count the mutant in its group's row of proofs/mutation.md")
    assert not [n for n in names if n not in kills], f"mutants without a kill record: {how}"
    assert not [n for n in kills if n not in names], "tools/mutant_kills.json names mutants no longer listed"
    assert not [n for n, e in kills.items() if not e.get("killed_by")], "mutants recorded as surviving"
    assert all(e.get("run") in ("whole", "targeted") and e.get("date") for e in kills.values())
    counts = {}
    for e in kills.values():
        counts[e["group"]] = counts.get(e["group"], 0) + 1
    table = _mutation_md_groups()
    assert table.pop("all", None) == len(names), "proofs/mutation.md's total row"
    assert table == counts, f"proofs/mutation.md's group rows: {how}"


@pytest.mark.parametrize("mutant", _named_mutants(), ids=lambda m: m[0])
def test_every_named_soundness_mutant_still_applies(mutant):
    """A refactor that rewrites a mutant's target text would make tools/soundness_mutants.py report it
    'NOT APPLIED' only when someone runs it: each target must occur exactly once, and the mutation must
    change the file."""
    name, path, old, new, _ = mutant
    text = (PKG.parent / path).read_text(encoding="utf-8")
    assert text.count(old) == 1, f"mutant {name}: its text occurs {text.count(old)} times in {path}"
    assert old != new
