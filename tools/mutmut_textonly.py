"""Which of a mutated module's mutants change only text, and what each mutant changes.

    python tools/mutmut_textonly.py MUTANTS_PY MODULE [NAME ...]          -> name<TAB>text|code
    python tools/mutmut_textonly.py --show MUTANTS_PY NAME [NAME ...]     -> the changed lines

MUTANTS_PY is mutmut's mutated copy of a module (``MUTMUT_DIR/mutants/rigor_gyro/...py``), MODULE its
dotted name (``rigor_gyro.kinds.lyapunov.claims``); NAMEs filter (short or full mutant names; ``-``
reads them from stdin). "text": the mutant's function differs from the original only in string
literals, or in a string literal replaced by None (a message, a label, a reason). That is a heuristic:
a string that is a key the code reads (a witness field, a status) is "text" here too, so each text
mutant of such a line is read by hand before it is called a message. Reads the file once (mutmut's
``show`` costs a second per mutant).
"""
from __future__ import annotations

import ast
import difflib
import io
import re
import sys
import textwrap
import tokenize

_STRING = {tokenize.STRING} | {getattr(tokenize, n) for n in ("FSTRING_START", "FSTRING_MIDDLE", "FSTRING_END")
                               if hasattr(tokenize, n)}
_SKIP = {tokenize.NL, tokenize.NEWLINE, tokenize.ENDMARKER, tokenize.INDENT, tokenize.DEDENT, tokenize.COMMENT}


def functions(path: str) -> dict[str, str]:
    src = open(path, encoding="utf-8").read()
    lines = src.splitlines(keepends=True)
    out: dict[str, str] = {}

    def visit(body):
        for n in body:
            if isinstance(n, ast.ClassDef):
                visit(n.body)
            elif isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
                out[n.name] = "".join(lines[n.lineno - 1:n.end_lineno])
    visit(ast.parse(src).body)
    return out


def _tokens(code: str) -> list[str]:
    toks = tokenize.generate_tokens(io.StringIO(textwrap.dedent(code)).readline)
    return ["<S>" if t.type in _STRING else t.string for t in toks if t.type not in _SKIP][2:]   # no 'def NAME'


def kind(funcs: dict[str, str], short: str) -> str:
    base = short.rsplit("__mutmut_", 1)[0]
    a, b = _tokens(funcs[base + "__mutmut_orig"]), _tokens(funcs[short])
    if a == b:
        return "text"
    if len(a) == len(b) and all(x == "<S>" and y == "None" for x, y in zip(a, b) if x != y):
        return "text"
    return "code"


def changed_lines(funcs: dict[str, str], short: str) -> list[str]:
    base = short.rsplit("__mutmut_", 1)[0]
    o, m = funcs[base + "__mutmut_orig"].splitlines()[1:], funcs[short].splitlines()[1:]
    return [d.strip() for d in difflib.unified_diff(o, m, lineterm="", n=0) if d[:1] in "+-" and d[:3] not in ("+++", "---")]


def main(argv: list[str]) -> int:
    show = argv[:1] == ["--show"]
    argv = argv[1:] if show else argv
    if len(argv) < (2 if show else 2):
        print(__doc__, file=sys.stderr)
        return 2
    path, rest = argv[0], argv[1:]
    module = None if show else rest.pop(0)
    names = sys.stdin.read().split() if rest == ["-"] else rest
    funcs = functions(path)
    if show:
        for full in names:
            short = full.rsplit(".", 1)[-1] if "." in full else full
            print(f"## {short}")
            for line in changed_lines(funcs, short):
                print("   ", line[:200])
        return 0
    wanted = {n.rsplit(".", 1)[-1] for n in names}
    for short in funcs:
        if re.search(r"__mutmut_\d+$", short) and (not wanted or short in wanted):
            print(f"{module}.{short}\t{kind(funcs, short)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
