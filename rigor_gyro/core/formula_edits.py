"""Single edits of a printed formula that reproduce a printed number (misprints found by search).

A paper prints a formula and, computed from it, a number. When the certified value of the formula
does not give the print, a misprint in the formula (or in the paper's own use of it) may: this module
tries every *single* edit of the formula, evaluates each in ball arithmetic on the same inputs, and
reports those that reproduce the print.

Formulas are text in Python syntax over named symbols, integer (or decimal) constants, + - * / **,
and the functions ``sqrt``, ``sin``, ``cos``, ``tan``, ``exp``, ``log``. The edits (each one change):

* ``sign``: one binary ``+`` turned into ``-`` or back, or one unary minus removed;
* ``exponent``: one integer power n turned into n - 1 (when >= 1) or n + 1, or one ``sqrt`` removed;
* ``moved``: one factor of a product moved to the other side of a fraction (a * b -> a / b, b / a),
  or a whole denominator moved up (a / b -> a * b);
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
    (['a - b with + for -'], 8)
"""
from __future__ import annotations

import ast
import copy
import itertools
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Callable

from flint import arb, fmpq

from .audit import audit_printed
from .outcome import AuditStatus

__all__ = ["FormulaEdit", "EditSearch", "single_edits", "evaluate", "search_single_edits"]

#: the order reproducing edits are listed in: the commonest misprints of a typeset formula first
KIND_ORDER = ("sign", "exponent", "label-swap", "moved", "factor-dropped", "factor-added")

FUNCTIONS = {"sqrt": lambda x: x.sqrt(), "sin": lambda x: x.sin(), "cos": lambda x: x.cos(),
             "tan": lambda x: x.tan(), "exp": lambda x: x.exp(), "log": lambda x: x.log()}


@dataclass
class FormulaEdit:
    kind: str
    description: str
    formula: str
    value: arb | None = None


@dataclass
class EditSearch:
    """The outcome of :func:`search_single_edits`: how many edits were tried, those that reproduce the
    print, and how many were undecided or could not be evaluated."""

    printed: str
    tried: int
    reproducing: list[FormulaEdit] = field(default_factory=list)
    undecided: int = 0
    not_evaluated: int = 0

    def to_json(self, formula: str) -> dict:
        return {"formula": formula, "tried": self.tried,
                "reproducing": [f"{e.kind}: {e.description}" for e in self.reproducing],
                "summary": self.summary(formula)}

    def summary(self, name: str = "the formula") -> str:
        head = f"single edits of {name} tried: {self.tried}"
        tail = "" if not (self.undecided or self.not_evaluated) else \
            f" ({self.undecided} undecided at this precision, {self.not_evaluated} not evaluable)"
        if not self.reproducing:
            return f"{head}; none reproduces the print {self.printed}{tail}"
        shown = "; ".join(f"{e.kind}: {e.description}" for e in self.reproducing[:6])
        more = f"; and {len(self.reproducing) - 6} more" if len(self.reproducing) > 6 else ""
        count = "one reproduces" if len(self.reproducing) == 1 else f"{len(self.reproducing)} reproduce"
        return f"{head}; {count} the print {self.printed}: {shown}{more}{tail}"


def evaluate(tree: ast.AST, env: dict[str, arb]) -> arb:
    """The formula's ball at the current precision, every symbol from ``env`` (KeyError if missing).
    Raises ValueError for syntax outside the module's grammar."""
    if isinstance(tree, ast.Expression):
        return evaluate(tree.body, env)
    if isinstance(tree, ast.BinOp):
        a, b = evaluate(tree.left, env), evaluate(tree.right, env)
        op = type(tree.op)
        if op is ast.Add:
            return a + b
        if op is ast.Sub:
            return a - b
        if op is ast.Mult:
            return a * b
        if op is ast.Div:
            return a / b
        if op is ast.Pow:
            n = _int_constant(tree.right)
            if n is None:
                raise ValueError("only integer powers")
            out = arb(1)
            for _ in range(abs(n)):
                out = out * a
            return out if n >= 0 else 1 / out
        raise ValueError(f"operator {op.__name__} not supported")
    if isinstance(tree, ast.UnaryOp) and isinstance(tree.op, (ast.USub, ast.UAdd)):
        v = evaluate(tree.operand, env)
        return -v if isinstance(tree.op, ast.USub) else v
    if isinstance(tree, ast.Call) and isinstance(tree.func, ast.Name) and tree.func.id in FUNCTIONS \
            and len(tree.args) == 1:
        return FUNCTIONS[tree.func.id](evaluate(tree.args[0], env))
    if isinstance(tree, ast.Name):
        return env[tree.id]
    if isinstance(tree, ast.Constant) and isinstance(tree.value, (int, float)) and not isinstance(tree.value, bool):
        q = Fraction(repr(tree.value)) if isinstance(tree.value, float) else Fraction(tree.value)
        return arb(fmpq(q.numerator, q.denominator))
    raise ValueError(f"{ast.dump(tree)[:60]} is outside the formula grammar")


def _int_constant(node: ast.AST) -> int | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        return node.value
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        n = _int_constant(node.operand)
        return -n if n is not None else None
    return None


def _edited(tree: ast.Expression, index: int, change) -> ast.Expression:
    """A copy of ``tree`` with ``change`` applied to its index-th node (ast.walk order)."""
    t = copy.deepcopy(tree)
    node = list(ast.walk(t))[index]
    change(node)
    return t


def single_edits(text: str) -> list[FormulaEdit]:
    """Every single edit of the formula ``text`` (see the module docstring), as edited formulas."""
    tree = ast.parse(text, mode="eval")
    nodes = list(ast.walk(tree))
    out: list[FormulaEdit] = []

    def add(kind: str, what: str, t: ast.Expression) -> None:
        out.append(FormulaEdit(kind, what, ast.unparse(t)))

    for i, n in enumerate(nodes):
        src = ast.unparse(n)
        if isinstance(n, ast.BinOp) and isinstance(n.op, (ast.Add, ast.Sub)):
            flip = ast.Sub if isinstance(n.op, ast.Add) else ast.Add
            add("sign", f"{src} with {'-' if flip is ast.Sub else '+'} for {'+' if flip is ast.Sub else '-'}",
                _edited(tree, i, lambda m, f=flip: setattr(m, "op", f())))
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.USub):
            where = next(((j, fld, k) for j, p in enumerate(nodes) for fld, val in ast.iter_fields(p)
                          for k, v in (enumerate(val) if isinstance(val, list) else [(None, val)]) if v is n), None)
            if where is not None:
                j, fld, k = where

                def drop_minus(p, fld=fld, k=k):
                    if k is None:
                        setattr(p, fld, getattr(p, fld).operand)
                    else:
                        getattr(p, fld)[k] = getattr(p, fld)[k].operand
                add("sign", f"{src} without its minus", _edited(tree, j, drop_minus))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Pow):
            k = _int_constant(n.right)
            if k is not None:
                base = ast.unparse(n.left)
                for e in (k - 1, k + 1):
                    if e >= 1:
                        add("exponent", f"{src} -> {base} ** {e}",
                            _edited(tree, i, lambda m, e=e: setattr(m, "right", ast.Constant(e))))
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "sqrt":
            add("exponent", f"{src} without the square root",
                _edited(tree, i, lambda m: (setattr(m.func, "id", "_id"),)))
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in ("sin", "cos"):
            other = "cos" if n.func.id == "sin" else "sin"
            add("label-swap", f"{src} read as {other}",
                _edited(tree, i, lambda m, o=other: setattr(m.func, "id", o)))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Mult):
            for side, other in (("left", "right"), ("right", "left")):
                moved = ast.unparse(getattr(n, side))

                def move(m, side=side, other=other):
                    num, den = getattr(m, other), getattr(m, side)
                    m.op, m.left, m.right = ast.Div(), num, den
                add("moved", f"{moved} moved to the denominator", _edited(tree, i, move))
                add("factor-dropped", f"the factor {moved} left out",
                    _edited(tree, i, lambda m, side=side: setattr(m, side, ast.Constant(1))))
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Div):
            add("moved", f"the denominator {ast.unparse(n.right)} moved up",
                _edited(tree, i, lambda m: setattr(m, "op", ast.Mult())))
    seen: dict[str, int] = {}
    for e in out:                       # the same words for two sites: number the occurrences
        seen[e.description] = seen.get(e.description, 0) + 1
    dup = {d for d, n in seen.items() if n > 1}
    count: dict[str, int] = {}
    for e in out:
        if e.description in dup:
            count[e.description] = count.get(e.description, 0) + 1
            e.description += f" (occurrence {count[e.description]})"
    names = sorted({n.id for n in nodes if isinstance(n, ast.Name) and n.id not in FUNCTIONS and n.id != "_id"})
    for a, b in itertools.combinations(names, 2):
        t = copy.deepcopy(tree)
        for x in ast.walk(t):
            if isinstance(x, ast.Name) and x.id in (a, b):
                x.id = b if x.id == a else a
        add("label-swap", f"{a} and {b} exchanged", t)
    for name in names + ["2"]:
        for op, word in ((ast.Mult, "times"), (ast.Div, "divided by")):
            factor = ast.Constant(2) if name == "2" else ast.Name(name, ast.Load())
            add("factor-added", f"the whole {word} {name}",
                ast.Expression(ast.BinOp(copy.deepcopy(tree.body), op(), factor)))
    return out


def search_single_edits(text: str, env: dict[str, arb], printed: str, defs: dict[str, str] | None = None,
                        reproduces: Callable[[arb], bool | None] | None = None) -> EditSearch:
    """Which single edits of ``text`` (evaluated on ``env``) reproduce the decimal ``printed``.

    ``defs``: named sub-formulas the text uses (name -> formula, evaluated in order, each may use the
    earlier ones): an edit is made in the text or in one definition (a misprint in a definition
    changes every use of it). ``reproduces(value)``: True when the value certainly gives the print,
    None when undecided (default: the value is certainly a correct rounding of ``printed``)."""
    defs = dict(defs or {})
    res = EditSearch(printed.strip(), 0)

    def decide(v: arb) -> bool | None:
        if reproduces is not None:
            return reproduces(v)
        status, _ = audit_printed(res.printed, v)
        return True if status is AuditStatus.AGREES else None if status is AuditStatus.UNDECIDED else False

    def value(main: str, parts: dict[str, str]) -> arb:
        scope = dict(env)
        for name, body in parts.items():
            scope[name] = evaluate(_strip_identity(ast.parse(body, mode="eval")), scope)
        return evaluate(_strip_identity(ast.parse(main, mode="eval")), scope)

    sites = [(None, text)] + list(defs.items())
    for where, body in sites:
        for e in single_edits(body):
            res.tried += 1
            parts = dict(defs)
            main = text
            if where is None:
                main = e.formula
            else:
                parts[where] = e.formula
                e.description = f"in {where}: {e.description}"
            try:
                v = value(main, parts)
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


def _strip_identity(tree: ast.AST) -> ast.AST:
    """Replace the calls ``_id(x)`` (a removed square root) by x."""
    class _Strip(ast.NodeTransformer):
        def visit_Call(self, node):
            self.generic_visit(node)
            if isinstance(node.func, ast.Name) and node.func.id == "_id":
                return node.args[0]
            return node
    return _Strip().visit(tree)
