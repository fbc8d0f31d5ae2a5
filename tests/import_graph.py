"""The package's import graph, read from the source with ``ast`` (nothing is imported or run).

    python tests/import_graph.py            # modules, their package-internal imports, and the cycles

Every ``import`` / ``from ... import`` statement counts, including the ones inside functions (a lazy
import that closes a circle is still a circle in the design). An edge A -> B means module A imports
module B of the package; importing a name from a package's ``__init__`` counts as an edge to the
package, and ``from pkg import sub`` to ``pkg.sub`` when ``sub`` is a module. Parent packages are
not added as edges (Python runs them first, but they are not what the module depends on).

Used by ``tests/test_rules.py``; printed in the layout issue's closing note (cycles before and after).
"""
from __future__ import annotations

import ast
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PKG = "rigor_gyro"


@dataclass
class ImportEdge:
    """One import of a package module: where, what, and the names taken from it."""

    source: str
    target: str
    names: list[str] = field(default_factory=list)
    lineno: int = 0
    lazy: bool = False        # inside a function body


def module_name(path: Path, root: Path = ROOT) -> str:
    rel = path.relative_to(root).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def package_modules(root: Path = ROOT, pkg: str = PKG) -> dict[str, Path]:
    """Module name -> file, for every .py file of the package."""
    return {module_name(p, root): p for p in sorted((root / pkg).rglob("*.py"))}


def _resolve(mod: str, is_pkg: bool, level: int, target: str | None) -> str:
    if level == 0:
        return target or ""
    base = mod.split(".") if is_pkg else mod.split(".")[:-1]
    base = base[: len(base) - (level - 1)] if level > 1 else base
    return ".".join(base + ([target] if target else []))


def _function_lines(tree: ast.AST) -> set[int]:
    lines = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for sub in ast.walk(node):
                if isinstance(sub, (ast.Import, ast.ImportFrom)):
                    lines.add(sub.lineno)
    return lines


def imports_of(mod: str, path: Path, modules: dict[str, Path]) -> list[ImportEdge]:
    """Every import statement of ``mod`` that names a module of the package."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    lazy_lines = _function_lines(tree)
    is_pkg = path.name == "__init__.py"
    out: list[ImportEdge] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in modules:
                    out.append(ImportEdge(mod, alias.name, [], node.lineno, node.lineno in lazy_lines))
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(mod, is_pkg, node.level, node.module)
            if base not in modules:
                continue
            plain = []
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in modules:
                    out.append(ImportEdge(mod, sub, [], node.lineno, node.lineno in lazy_lines))
                else:
                    plain.append(alias.name)
            if plain:
                out.append(ImportEdge(mod, base, plain, node.lineno, node.lineno in lazy_lines))
    return out


def graph(root: Path = ROOT, pkg: str = PKG) -> dict[str, list[ImportEdge]]:
    modules = package_modules(root, pkg)
    return {m: [e for e in imports_of(m, p, modules) if e.target != m] for m, p in modules.items()}


def cycles(g: dict[str, list[ImportEdge]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    counter = [0]

    def visit(v: str) -> None:
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for e in g.get(v, []):
            w = e.target
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(g):
        if v not in index:
            visit(v)
    return sorted(out)


def private_imports(g: dict[str, list[ImportEdge]]) -> list[str]:
    """``from A import _name`` of a private name of another module."""
    return [f"{e.source}:{e.lineno} imports {e.target}.{n}" for edges in g.values() for e in edges
            for n in e.names if n.startswith("_") and not n.startswith("__")]


def main(argv: list[str]) -> int:
    root = Path(argv[1]).resolve() if len(argv) > 1 else ROOT
    g = graph(root)
    for m in sorted(g):
        targets = sorted({e.target + (" (lazy)" if e.lazy else "") for e in g[m]})
        print(f"{m}: {', '.join(targets) or '-'}")
    cyc = cycles(g)
    print(f"\n{len(g)} modules, {sum(len(v) for v in g.values())} package-internal imports, "
          f"{len(cyc)} import cycle(s)")
    for c in cyc:
        print("  cycle: " + " <-> ".join(c))
    priv = private_imports(g)
    print(f"{len(priv)} import(s) of another module's private name")
    for p in priv:
        print("  " + p)
    return 1 if cyc or priv else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
