"""Single edits of a printed formula that reproduce a printed number (misprints found by search).

A paper prints a formula and, computed from it, a number. When the certified value of the formula
does not give the print, a misprint in the formula (or in the paper's own use of it) may: this module
tries every *single* edit of the formula, evaluates each in ball arithmetic on the same inputs, and
reports those that reproduce the print.

Formulas are text in Python syntax over named symbols, integer (or decimal) constants, + - * / **,
and the functions ``sqrt``, ``sin``, ``cos``, ``tan``, ``exp``, ``log``. The edits (each one change):

* ``sign``: one binary ``+`` turned into ``-`` or back, or one unary minus removed;
* ``exponent``: one integer power n turned into n - 1 (when >= 1) or n + 1, or one ``sqrt`` removed;
* ``moved``: one factor of a product made a divisor (a * b -> a / b, b / a), or one divisor made a
  factor (a / b -> a * b): a factor moved across a fraction bar;
* ``factor-dropped``: one factor of a product left out;
* ``factor-added``: the whole formula times or divided by one of its symbols, or by 2;
* ``label-swap``: two symbols exchanged everywhere, or one ``sin`` read as ``cos`` (or back).

Guarantee: an edit *reproduces* the print only when its enclosure is certainly a correct rounding of
it at the printed digits (:func:`~rigor_gyro.core.audit.audit_printed` says ``agrees``); an edit whose
enclosure straddles a rounding boundary is counted ``undecided``, never as reproducing; an edit that
cannot be evaluated (a negative square root, a division by a ball containing 0) is skipped and
counted. The search is exhaustive over the edits listed, nothing else: "none reproduces" is a
statement about single edits of this text, not about every possible misprint. Precision: the current
working precision (the inputs are balls at it).

Example:
    >>> from flint import arb
    >>> r = search_single_edits("a - b", {"a": arb(5), "b": arb(3)}, "8")
    >>> [e.description for e in r.reproducing], r.tried
    (['a - b -> a + b'], 8)
"""
from __future__ import annotations

import ast
import itertools
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable

from flint import arb, fmpq

from .audit import printed_status
from .outcome import AuditStatus

__all__ = ["FormulaEdit", "EditSearch", "single_edits", "parse_formula", "evaluate", "show", "search_single_edits"]

#: the order reproducing edits are listed in: the commonest misprints of a typeset formula first
KIND_ORDER = ("sign", "exponent", "label-swap", "moved", "factor-dropped", "factor-added")

FUNCTIONS = {"sqrt": lambda x: x.sqrt(), "sin": lambda x: x.sin(), "cos": lambda x: x.cos(),
             "tan": lambda x: x.tan(), "exp": lambda x: x.exp(), "log": lambda x: x.log()}

#: a formula is an immutable tree of tuples: ("+" | "-" | "*" | "/", left, right), ("**", base, n),
#: ("neg", x), ("call", name, x), ("sym", name), ("num", Fraction, text); an edit copies one path only
Tree = tuple


@dataclass
class FormulaEdit:
    kind: str
    description: str
    formula: str
    value: arb | None = None
    tree: Tree | None = field(default=None, repr=False, compare=False)


@dataclass
class EditSearch:
    """The outcome of :func:`search_single_edits`: how many edits were tried, those that reproduce the
    print, and how many were undecided or could not be evaluated."""

    printed: str
    tried: int
    reproducing: list[FormulaEdit] = field(default_factory=list)
    undecided: int = 0
    not_evaluated: int = 0

    def to_json(self, formula: str, how: str = "") -> dict:
        return {"formula": formula, "tried": self.tried,
                "reproducing": [f"{e.kind}: {e.description}" for e in self.reproducing],
                "reproducing_formulas": [e.formula for e in self.reproducing],
                "summary": self.summary(formula, how)}

    def summary(self, name: str = "the formula", how: str = "") -> str:
        head = f"single edits of {name} tried: {self.tried}" + (f" (reproducing: {how})" if how else "")
        tail = "" if not (self.undecided or self.not_evaluated) else \
            f" ({self.undecided} undecided at this precision, {self.not_evaluated} not evaluable)"
        if not self.reproducing:
            return f"{head}; none reproduces the print {self.printed}{tail}"
        shown = "; ".join(f"{e.kind}: {e.description}" for e in self.reproducing[:6])
        more = f"; and {len(self.reproducing) - 6} more" if len(self.reproducing) > 6 else ""
        count = "one reproduces" if len(self.reproducing) == 1 else f"{len(self.reproducing)} reproduce"
        return f"{head}; {count} the print {self.printed}: {shown}{more}{tail}"


_BINARY = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/"}


def parse_formula(text: str) -> Tree:
    """The tree of a formula text; ValueError for syntax outside the grammar of the module docstring."""
    def conv(n: ast.AST) -> Tree:
        if isinstance(n, ast.Expression):
            return conv(n.body)
        if isinstance(n, ast.BinOp) and type(n.op) in _BINARY:
            return (_BINARY[type(n.op)], conv(n.left), conv(n.right))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow):
            k = _int_constant(n.right)
            if k is None:
                raise ValueError("only integer powers")
            return ("**", conv(n.left), k)
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.USub):
            return ("neg", conv(n.operand))
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.UAdd):
            return conv(n.operand)
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in FUNCTIONS and len(n.args) == 1:
            return ("call", n.func.id, conv(n.args[0]))
        if isinstance(n, ast.Name):
            return ("sym", n.id)
        if isinstance(n, ast.Constant) and isinstance(n.value, (int, float)) and not isinstance(n.value, bool):
            q = Fraction(repr(n.value)) if isinstance(n.value, float) else Fraction(n.value)
            return ("num", q, repr(n.value))
        raise ValueError(f"{ast.dump(n)[:60]} is outside the formula grammar")
    return conv(ast.parse(text, mode="eval"))


def _int_constant(node: ast.AST) -> int | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        n = _int_constant(node.operand)
        return -n if n is not None else None
    return None


def evaluate(tree: Tree | str, env: dict[str, arb], memo: dict | None = None) -> arb:
    """The formula's ball at the current precision, every symbol from ``env`` (KeyError if missing).

    ``memo``: a dict shared by evaluations of trees with common subtrees on the same ``env`` at the
    same precision (the edits of one formula share all but one path), keyed by the subtree's identity
    (kept with its value). Arb arithmetic is deterministic, so a memoised ball is the very ball the
    evaluation would give: only repeated work goes. An error (a division by a ball containing 0) is
    raised again, never memoised."""
    t = parse_formula(tree) if isinstance(tree, str) else tree
    if memo is not None:
        hit = memo.get(id(t))
        if hit is not None and hit[0] is t:
            return hit[1]
        value = _evaluate(t, env, memo)
        memo[id(t)] = (t, value)
        return value
    return _evaluate(t, env, None)


def _evaluate(t: Tree, env: dict[str, arb], memo: dict | None) -> arb:
    op = t[0]
    if op == "+":
        return evaluate(t[1], env, memo) + evaluate(t[2], env, memo)
    if op == "-":
        return evaluate(t[1], env, memo) - evaluate(t[2], env, memo)
    if op == "*":
        return evaluate(t[1], env, memo) * evaluate(t[2], env, memo)
    if op == "/":
        return evaluate(t[1], env, memo) / evaluate(t[2], env, memo)
    if op == "**":
        a, n = evaluate(t[1], env, memo), t[2]
        out = arb(1)
        for _ in range(abs(n)):
            out = out * a
        return out if n >= 0 else 1 / out
    if op == "neg":
        return -evaluate(t[1], env, memo)
    if op == "call":
        return FUNCTIONS[t[1]](evaluate(t[2], env, memo))
    if op == "id":                       # a removed square root
        return evaluate(t[1], env, memo)
    if op == "sym":
        return env[t[1]]
    if op == "num":
        return arb(fmpq(t[1].numerator, t[1].denominator))
    raise ValueError(f"unknown node {op!r}")


_LEVEL = {"+": 1, "-": 1, "*": 2, "/": 2, "neg": 3, "**": 4}


def _level(t: Tree) -> int:
    return _LEVEL.get(t[0], 5)


def show(t: Tree, memo: dict | None = None) -> str:
    """The formula as text (Python syntax, the parentheses the precedence needs). ``memo``: a dict
    shared by calls on trees with common subtrees (the edits of one formula), keyed by the subtree's
    identity (the subtree is kept with its text, so the identity is never reused)."""
    if memo is not None:
        hit = memo.get(id(t))
        if hit is not None and hit[0] is t:
            return hit[1]
    op = t[0]
    if op in ("+", "-", "*", "/"):
        p = _LEVEL[op]
        left = show(t[1], memo) if _level(t[1]) >= p else f"({show(t[1], memo)})"
        right = show(t[2], memo) if _level(t[2]) > p else f"({show(t[2], memo)})"
        text = f"{left} {op} {right}"
    elif op == "**":
        base = show(t[1], memo) if _level(t[1]) > 4 else f"({show(t[1], memo)})"
        text = f"{base} ** {t[2]}"
    elif op == "neg":
        inner = show(t[1], memo) if _level(t[1]) >= 3 else f"({show(t[1], memo)})"
        text = f"-{inner}"
    elif op == "call":
        text = f"{t[1]}({show(t[2], memo)})"
    elif op == "id":
        text = f"_id({show(t[1], memo)})"
    elif op == "sym":
        text = t[1]
    else:
        text = t[2]
    if memo is not None:
        memo[id(t)] = (t, text)
    return text


def _symbols(t: Tree) -> set[str]:
    """The names of the symbols a formula tree reads."""
    return {n[1] for _, n in _sites(t) if n[0] == "sym"}


def _sites(t: Tree, path: tuple = ()):
    """(path, subtree) for every node, breadth first (child indices: 1, 2 of binary nodes, 1 of neg/**,
    2 of call)."""
    queue = [(path, t)]
    while queue:
        path, node = queue.pop(0)
        yield path, node
        op = node[0]
        if op in ("+", "-", "*", "/"):
            queue += [(path + (1,), node[1]), (path + (2,), node[2])]
        elif op in ("**", "neg", "id"):
            queue.append((path + (1,), node[1]))
        elif op == "call":
            queue.append((path + (2,), node[2]))


def _replace(t: Tree, path: tuple, new: Tree) -> Tree:
    if not path:
        return new
    i = path[0]
    return t[:i] + (_replace(t[i], path[1:], new),) + t[i + 1:]


def _rename(t: Tree, a: str, b: str) -> Tree:
    if t[0] == "sym":
        return ("sym", b if t[1] == a else a if t[1] == b else t[1])
    if t[0] in ("num",):
        return t
    return tuple(_rename(x, a, b) if isinstance(x, tuple) else x for x in t)


def single_edits(text: str) -> list[FormulaEdit]:
    """Every single edit of the formula ``text`` (see the module docstring), as edited formulas."""
    tree = parse_formula(text)
    out: list[FormulaEdit] = []
    memo: dict = {}                     # the edits share every subtree but one path: each shown once

    def shown(t: Tree) -> str:
        return show(t, memo)

    def add(kind: str, what: str, t: Tree) -> None:
        out.append(FormulaEdit(kind, what, shown(t), tree=t))

    for path, n in _sites(tree):
        op, src = n[0], shown(n)
        if op in ("+", "-"):
            flip = "-" if op == "+" else "+"
            add("sign", f"{src} -> {shown((flip, n[1], n[2]))}", _replace(tree, path, (flip, n[1], n[2])))
        if op == "neg":
            add("sign", f"{src} without its minus", _replace(tree, path, n[1]))
        if op == "**":
            base = shown(n[1]) if _level(n[1]) > 4 else f"({shown(n[1])})"
            for e in (n[2] - 1, n[2] + 1):
                if e >= 1:
                    add("exponent", f"{src} -> {base} ** {e}", _replace(tree, path, ("**", n[1], e)))
        if op == "call" and n[1] == "sqrt":
            add("exponent", f"{src} without the square root", _replace(tree, path, ("id", n[2])))
        if op == "call" and n[1] in ("sin", "cos"):
            other = "cos" if n[1] == "sin" else "sin"
            add("label-swap", f"{src} read as {other}", _replace(tree, path, ("call", other, n[2])))
        if op == "*":
            for side, other in ((1, 2), (2, 1)):
                moved = shown(n[side])
                add("moved", f"the factor {moved} divides instead of multiplying", _replace(tree, path, ("/", n[other], n[side])))
                kept = (n[0], ("num", Fraction(1), "1"), n[2]) if side == 1 else (n[0], n[1], ("num", Fraction(1), "1"))
                add("factor-dropped", f"the factor {moved} left out", _replace(tree, path, kept))
        if op == "/":
            add("moved", f"the divisor {shown(n[2])} multiplies instead of dividing", _replace(tree, path, ("*", n[1], n[2])))
    seen: dict[str, int] = {}
    for e in out:                       # the same words for two sites: number the occurrences
        seen[e.description] = seen.get(e.description, 0) + 1
    dup = {d for d, c in seen.items() if c > 1}
    count: dict[str, int] = {}
    for e in out:
        if e.description in dup:
            count[e.description] = count.get(e.description, 0) + 1
            e.description += f" (occurrence {count[e.description]})"
    names = sorted({n[1] for _, n in _sites(tree) if n[0] == "sym"})
    for a, b in itertools.combinations(names, 2):
        add("label-swap", f"{a} and {b} exchanged", _rename(tree, a, b))
    for name in names + ["2"]:
        factor = ("num", Fraction(2), "2") if name == "2" else ("sym", name)
        add("factor-added", f"the whole times {name}", ("*", tree, factor))
        add("factor-added", f"the whole divided by {name}", ("/", tree, factor))
    return out


def search_single_edits(text: str, env: dict[str, arb], printed: str, defs: dict[str, str] | None = None,
                        reproduces: Callable[[arb], bool | None] | None = None) -> EditSearch:
    """Which single edits of ``text`` (evaluated on ``env``) reproduce the decimal ``printed``.

    ``defs``: named sub-formulas the text uses (name -> formula, evaluated in order, each may use the
    earlier ones): an edit is made in the text or in one definition (a misprint in a definition
    changes every use of it). ``reproduces(value)``: True when the value certainly gives the print,
    None when undecided (default: the value is certainly a correct rounding of ``printed``)."""
    defs = {k: parse_formula(v) for k, v in (defs or {}).items()}
    main = parse_formula(text)
    res = EditSearch(printed.strip(), 0)

    def decide(v: arb) -> bool | None:
        if reproduces is not None:
            return reproduces(v)
        status = printed_status(res.printed, v)
        return True if status is AuditStatus.AGREES else None if status is AuditStatus.UNDECIDED else False

    base = dict(env)                    # the unedited definitions, for edits made elsewhere
    order = list(defs)
    for name in order:
        base[name] = evaluate(defs[name], base)
    used = {name: _symbols(defs[name]) for name in order}

    memo: dict = {}                     # the edits of the text share all its subtrees but one path
    # an edit in a definition: the definitions before it keep their unedited values, the edits of one
    # definition share all its subtrees but one path (a memo per definition, on the same scope), and a later
    # definition that reads no changed name keeps its unedited value (the same inputs give the same ball)
    scopes: dict[str, tuple[dict, dict]] = {}

    def value(where: str | None, edited: Tree) -> arb:
        if where is None:
            return evaluate(edited, base, memo)
        if where not in scopes:
            before = order[:order.index(where)]
            scopes[where] = ({**env, **{n: base[n] for n in before}}, {})
        scope, def_memo = scopes[where]
        scope = dict(scope)
        scope[where] = evaluate(edited, scope, def_memo)
        changed = {where}
        for name in order[order.index(where) + 1:]:
            if used[name] & changed:
                scope[name] = evaluate(defs[name], scope)
                changed.add(name)
            else:
                scope[name] = base[name]
        return evaluate(main, scope)

    sites = [(None, text)] + [(k, show(v)) for k, v in defs.items()]
    for where, body in sites:
        for e in single_edits(body):
            res.tried += 1
            if where is not None:
                e.description = f"in {where}: {e.description}"
                e.formula = f"{where} = {e.formula}"
            try:
                v = value(where, e.tree)
            except (ValueError, ZeroDivisionError, KeyError):
                res.not_evaluated += 1
                continue
            if not v.is_finite():
                res.not_evaluated += 1
                continue
            e.value = v
            verdict = decide(v)
            if verdict:
                res.reproducing.append(e)
            elif verdict is None:
                res.undecided += 1
    res.reproducing.sort(key=lambda e: KIND_ORDER.index(e.kind))   # stable: in formula order within a kind
    return res

