"""A small expression language for model entries written in scene files: + - * / ^, parentheses, exact
numbers, named parameters and (where the caller allows them) named functions; parsed by a recursive-descent
grammar of its own (never ``eval``), evaluated on whatever numbers the caller gives (``Fraction`` or ``fmpq``
exactly, ``arb`` balls, series).

Grammar (whitespace ignored between tokens)::

    expr   := term (('+' | '-') term)*
    term   := unary (('*' | '/') unary)*
    unary  := ('+' | '-') unary | power
    power  := atom ('^' unary)?            # right-associative; the exponent must be an integer constant
    atom   := NUMBER | NAME | NAME '(' expr (',' expr)* ')' | '(' expr ')'
    NUMBER := digits ['.' digits] [('e' | 'E') ['+' | '-'] digits]      # an exact decimal: "0.1" is 1/10

``a^-2`` is 1/a^2; ``-a^2`` is -(a^2). ``**`` is accepted as a synonym of ``^``.

Guarantee: :func:`parse` returns an :class:`Expr` whose :meth:`Expr.evaluate` computes exactly the written
formula with the operations of the values given (exact for ``Fraction``/``fmpq``: no rounding anywhere;
with balls, a ball containing the exact value). Every number is read as an exact rational.

Limits (checked while parsing, before any arithmetic): at most :data:`MAX_LENGTH` characters, nesting depth
:data:`MAX_DEPTH`, :data:`MAX_OPERATIONS` binary operations, a degree of at most :data:`MAX_DEGREE` (so nested
powers cannot multiply without bound), integer exponents of magnitude <= :data:`MAX_POWER`, functions of one
argument, each number at most
:data:`rigor_gyro.core.exact.MAX_DIGITS` digits and a decimal exponent within +-``MAX_EXPONENT``.

Fails when: the text is not in the grammar, names an unknown parameter or function, or exceeds a limit
(:class:`ParameterError` naming ``where``, the entry being read); evaluation divides by an exact zero
(:class:`ParameterError` naming ``where``, from :meth:`Expr.evaluate` with exact values).

Precision: none of its own (the values' arithmetic decides).

Calculus on trees (for callers that allow the standard functions :data:`UNARY_FUNCTIONS`): :func:`derivative`
is the exact symbolic derivative in one name (the chain rule with each function's own rule; ``abs``' derivative
is ``sign``, which a caller must evaluate as undefined where its argument may vanish), and :func:`parity` decides
from the tree alone whether an expression is odd or even in one name (a sufficient, exact test: an expression it
calls odd satisfies e(-x) = -e(x) identically wherever both sides are defined; None means "not shown", never
"not odd").

This module knows nothing of gyroscopes: any kind may read its model entries with it.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Callable, Mapping

from .errors import ParameterError
from .exact import MAX_DIGITS, MAX_EXPONENT

__all__ = ["Expr", "parse", "compile_expr", "degree", "evaluate_exact", "derivative", "parity", "tree_size", "UNARY_FUNCTIONS", "MAX_LENGTH",
           "MAX_DEPTH", "MAX_POWER", "MAX_OPERATIONS", "MAX_DEGREE", "MAX_DERIVATIVE_NODES"]

MAX_LENGTH = 4000
MAX_DEPTH = 60
MAX_POWER = 64
#: binary operations in one expression (each adds a level to the tree's evaluation)
MAX_OPERATIONS = 200
#: the degree of an expression as a polynomial in its numbers and names (sums: the larger, products and quotients:
#: the sum, a power: times the exponent): nested powers such as ((2^64)^64)^64 multiply, and exact arithmetic
#: on them would exhaust memory
MAX_DEGREE = 128

#: the standard unary functions a caller may allow (``parse(..., functions=UNARY_FUNCTIONS)``); their derivative
#: rules are in :func:`derivative` and their parities in :func:`parity`. ``sign`` is not written by users: it is
#: abs' derivative, produced by :func:`derivative`
UNARY_FUNCTIONS = frozenset({"sin", "cos", "tan", "exp", "log", "sqrt", "tanh", "atan", "abs"})
#: a derivative tree larger than this many nodes is refused (ParameterError): products of long factors grow it
MAX_DERIVATIVE_NODES = 20000
_ODD_FUNCTIONS = frozenset({"sin", "tan", "tanh", "atan", "sign"})
_EVEN_FUNCTIONS = frozenset({"cos", "abs"})

_TOKEN = re.compile(r"\s*(?:(?P<num>(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
                    r"|(?P<op>\*\*|[-+*/^(),]))", re.ASCII)


@dataclass(frozen=True)
class Expr:
    """A parsed expression: a tree of tuples (``("num", Fraction)``, ``("name", str)``, ``("neg", e)``,
    ``("+"|"-"|"*"|"/", e1, e2)``, ``("^", e, int)``, ``("call", name, (args))``) with the text it was read from."""

    tree: tuple
    text: str
    where: str

    def names(self) -> set[str]:
        """The parameter names the expression uses."""
        out: set[str] = set()

        def walk(t):
            if t[0] == "name":
                out.add(t[1])
            elif t[0] == "call":
                for a in t[2]:
                    walk(a)
            elif t[0] in ("neg",):
                walk(t[1])
            elif t[0] == "^":
                walk(t[1])
            elif t[0] in "+-*/":
                walk(t[1])
                walk(t[2])
        walk(self.tree)
        return out

    def is_constant(self) -> bool:
        return not self.names()

    def evaluate(self, env: Mapping[str, Any], number: Callable[[Fraction], Any] = lambda q: q,
                 functions: Mapping[str, Callable] | None = None, power: Callable[[Any, int], Any] | None = None,
                 guard: Callable[[tuple, tuple], None] | None = None) -> Any:
        """The value with ``env[name]`` for each name and ``number(q)`` for each written rational q
        (default: the Fraction itself); ``power(base, n)`` for each integer power when given (n of either sign;
        default ``base ** n``, and 1/base^-n for n < 0). ``guard(sub_tree, operand values)``, when given, sees
        each function call, integer power and division before it is done (it may raise: how
        :mod:`.expression_domain` finds where an expression has no value). An exact division by zero
        (ZeroDivisionError of the values' arithmetic) is a ParameterError naming ``where``."""
        fns = functions or {}

        def ev(t):
            op = t[0]
            if op == "num":
                return number(t[1])
            if op == "name":
                return env[t[1]]
            if op == "neg":
                return -ev(t[1])
            if op == "call":
                args = tuple(ev(a) for a in t[2])
                if guard is not None:
                    guard(t, args)
                return fns[t[1]](*args)
            if op == "^":
                base, n = ev(t[1]), t[2]
                if guard is not None:
                    guard(t, (base,))
                if power is not None:
                    return power(base, n)
                if n < 0:
                    return number(Fraction(1)) / _int_power(base, -n)
                return _int_power(base, n)
            x, y = ev(t[1]), ev(t[2])
            if op == "+":
                return x + y
            if op == "-":
                return x - y
            if op == "*":
                return x * y
            if guard is not None:
                guard(t, (x, y))
            return x / y
        try:
            return ev(self.tree)
        except ZeroDivisionError:
            raise ParameterError(f"{self.where}: {self.text!r} divides by zero") from None


def _int_power(base, n: int):
    """``base ** n`` (n >= 0), except where a ball type returns nan for it (python-flint's ``arb ** n`` of a ball
    centred exactly at 0 with a positive radius, e.g. a parameter's box [-1, 1]): there the product of n
    factors, which encloses every x^n of the ball (wider for even n: it has negative values); and a ball that is
    not finite to the power 0 stays not finite (its base may have no value: (1/(a - 1))^0 over a box holding 1)."""
    if n == 0:          # x^0 = 1 only where x has a value: a ball that is not finite (a pole inside) stays so
        finite = getattr(base, "is_finite", None)
        if finite is not None and not finite():
            return base * 0             # nan or [+/- inf]: decides nothing (python-flint's nan ** 0 is 1: review)
    y = base ** n
    is_nan = getattr(y, "is_nan", None)
    if is_nan is not None and n >= 2 and is_nan() and base.is_finite():
        y = base
        for _ in range(n - 1):
            y = y * base
    return y


def compile_expr(expr: "Expr", number: Callable[[Fraction], Any], functions: Mapping[str, Callable] | None = None,
                 power: Callable[[Any, int], Any] | None = None) -> Callable[[Mapping[str, Any]], Any]:
    """``expr`` as a function of ``env`` computing exactly what :meth:`Expr.evaluate` computes with these
    arguments, the tree walked once (nested closures; ``number(q)`` called once per written number, so the
    caller recompiles where numbers depend on a context such as Arb's precision). Not ``eval``: no code is
    generated from text."""
    fns = functions or {}

    def c(t):
        op = t[0]
        if op == "num":
            v = number(t[1])
            return lambda env: v
        if op == "name":
            n = t[1]
            return lambda env: env[n]
        if op == "neg":
            f = c(t[1])
            return lambda env: -f(env)
        if op == "call":
            g, f = fns[t[1]], c(t[2][0])
            return lambda env: g(f(env))
        if op == "^":
            f, n = c(t[1]), t[2]
            if power is not None:
                return lambda env: power(f(env), n)
            if n < 0:
                one = number(Fraction(1))
                return lambda env: one / _int_power(f(env), -n)
            return lambda env: _int_power(f(env), n)
        f1, f2 = c(t[1]), c(t[2])
        if op == "+":
            return lambda env: f1(env) + f2(env)
        if op == "-":
            return lambda env: f1(env) - f2(env)
        if op == "*":
            return lambda env: f1(env) * f2(env)
        return lambda env: f1(env) / f2(env)
    run = c(expr.tree)

    def call(env):
        try:
            return run(env)
        except ZeroDivisionError:
            raise ParameterError(f"{expr.where}: {expr.text!r} divides by zero") from None
    return call


def parse(text: object, where: str, names: set[str] | frozenset[str] | Mapping = frozenset(),
          functions: set[str] | frozenset[str] = frozenset()) -> Expr:
    """Parse ``text`` (a string, or an int) into an :class:`Expr`; ``names`` are the parameter names it may
    use, ``functions`` the function names; see the module docstring."""
    if isinstance(text, bool) or not isinstance(text, (str, int)):
        raise ParameterError(f"{where}: expected an expression written as a string, got {type(text).__name__}")
    s = str(text)
    if len(s) > MAX_LENGTH:
        raise ParameterError(f"{where}: an expression may have at most {MAX_LENGTH} characters")
    key = (s, frozenset(names), frozenset(functions))
    tree = _TREES.get(key)
    if tree is not None:
        return Expr(tree, s, where)
    tokens, pos, end = [], 0, len(s.rstrip())
    while pos < end:
        m = _TOKEN.match(s, pos)
        if not m:
            bad = s[pos:].lstrip()[:1]
            raise ParameterError(f"{where}: cannot read {s!r}: unexpected character {bad!r} (the grammar has numbers, "
                                 "names, + - * / ^ and parentheses)")
        kind = m.lastgroup
        tokens.append((kind, m.group(kind)))
        pos = m.end()
    if not tokens:
        raise ParameterError(f"{where}: empty expression")
    p = _Parser(tokens, s, where, set(names), set(functions))
    tree = p.expr(0)
    if p.i != len(tokens):
        raise ParameterError(f"{where}: cannot read {s!r}: unexpected {tokens[p.i][1]!r}")
    if _degree(tree) > MAX_DEGREE:
        raise ParameterError(f"{where}: cannot read {s!r}: its degree (powers multiplied through nested powers "
                             f"and products) exceeds {MAX_DEGREE}; expand or simplify it")
    if len(_TREES) < 65536:
        _TREES[key] = tree
    return Expr(tree, s, where)


#: parsed trees by (text, names, functions): a scene re-validated (the checker, a paving's boxes) parses once
_TREES: dict[tuple, tuple] = {}


class _Parser:
    def __init__(self, tokens, text, where, names, functions):
        self.t, self.text, self.where, self.names, self.functions, self.i = tokens, text, where, names, functions, 0
        self.n = len(tokens)
        self.operations = 0

    def operation(self):
        self.operations += 1
        if self.operations > MAX_OPERATIONS:
            self.fail(f"more than {MAX_OPERATIONS} operations; split it with defs")

    def fail(self, what: str):
        raise ParameterError(f"{self.where}: cannot read {self.text!r}: {what}")

    def peek(self):
        i = self.i
        return self.t[i] if i < self.n else _END

    def take(self, value=None):
        tok = self.peek()
        if tok[0] is None:
            self.fail("it ends too early")
        if value is not None and tok[1] != value:
            self.fail(f"expected {value!r}, found {tok[1]!r}")
        self.i += 1
        return tok

    def _plus_minus(self):
        """'+' then '-' (spaces aside): the tolerance syntax, refused (it would read as mid - rad)."""
        self.fail("'+-' is a tolerance, which an expression cannot hold (it would read as mid - rad): write a "
                  "tolerance as a parameter in [parameters] (\"mid +- rad\", if the kind takes boxes), and a sum "
                  "with a negative term as a - b or a + (-b)")

    def expr(self, depth):
        if depth > MAX_DEPTH:
            self.fail(f"nested deeper than {MAX_DEPTH}")
        left = self.term(depth)
        while self.peek()[1] in ("+", "-"):
            op = self.take()[1]
            if op == "+" and self.peek()[1] == "-":
                self._plus_minus()
            self.operation()
            left = (op, left, self.term(depth))
        return left

    def term(self, depth):
        left = self.unary(depth)
        while self.peek()[1] in ("*", "/"):
            op = self.take()[1]
            self.operation()
            left = (op, left, self.unary(depth))
        return left

    def unary(self, depth):
        if depth > MAX_DEPTH:
            self.fail(f"nested deeper than {MAX_DEPTH}")
        if self.peek()[1] in ("+", "-"):
            op = self.take()[1]
            if op == "+" and self.peek()[1] == "-":
                self._plus_minus()
            inner = self.unary(depth + 1)
            return ("neg", inner) if op == "-" else inner
        return self.power(depth)

    def power(self, depth):
        base = self.atom(depth)
        if self.peek()[1] in ("^", "**"):
            self.take()
            exponent = self.unary(depth + 1)
            n = _integer_constant(exponent)
            if n is None:
                self.fail("an exponent must be an integer constant (such as 2 or -1)")
            if abs(n) > MAX_POWER:
                self.fail(f"an exponent must have magnitude at most {MAX_POWER}")
            return ("^", base, n)
        return base

    def atom(self, depth):
        kind, value = self.take()
        if kind == "num":
            return ("num", _number(value, self))
        if kind == "name":
            if self.peek()[1] == "(":
                if value not in self.functions:
                    allowed = f"; allowed here: {sorted(self.functions)}" if self.functions else " (no functions here)"
                    self.fail(f"unknown function {value!r}{allowed}")
                self.take("(")
                args = [self.expr(depth + 1)]
                while self.peek()[1] == ",":
                    self.take()
                    args.append(self.expr(depth + 1))
                self.take(")")
                if len(args) != 1:
                    self.fail(f"{value}() takes one argument, given {len(args)}")
                return ("call", value, tuple(args))
            if value not in self.names:
                import difflib
                close = difflib.get_close_matches(value, sorted(self.names), n=1, cutoff=0.6)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                self.fail(f"unknown name {value!r}{hint}; known: {sorted(self.names)}")
            return ("name", value)
        if value == "(":
            inner = self.expr(depth + 1)
            self.take(")")
            return inner
        self.fail(f"unexpected {value!r}")


_SMALL: dict[str, Fraction] = {}
_END = (None, None)


def _number(token: str, parser: "_Parser") -> Fraction:
    """The exact rational a number token (already in the grammar's shape) denotes, within
    :mod:`rigor_gyro.core.exact`'s limits on digits and decimal exponent."""
    q = _SMALL.get(token)
    if q is not None:
        return q
    mantissa, _, exponent = token.lower().partition("e")
    if len(mantissa.replace(".", "")) > MAX_DIGITS:
        parser.fail(f"a number may have at most {MAX_DIGITS} digits")
    if exponent and abs(int(exponent)) > MAX_EXPONENT:
        parser.fail(f"a decimal exponent must lie in [-{MAX_EXPONENT}, {MAX_EXPONENT}]")
    q = Fraction(token)
    if len(token) <= 8 and len(_SMALL) < 4096:
        _SMALL[token] = q
    return q


def _integer_constant(t: tuple) -> int | None:
    """The value of a constant subtree (numbers only) when it is an integer, else None."""
    e = Expr(t, "", "exponent")
    if e.names() or _has_call(t):
        return None
    try:
        v = e.evaluate({})
    except ParameterError:
        return None
    return int(v) if v.denominator == 1 else None


def _degree(t: tuple, names: Mapping[str, int] | None = None) -> int:
    """The degree bound of the module docstring (MAX_DEGREE); ``names``: the degree a name stands for (a def's
    own degree), 1 otherwise."""
    op = t[0]
    if op == "num":
        return 1
    if op == "name":
        return (names or {}).get(t[1], 1)
    if op == "neg":
        return _degree(t[1], names)
    if op == "call":
        return max(_degree(a, names) for a in t[2])
    if op == "^":
        return _degree(t[1], names) * abs(t[2])
    a, b = _degree(t[1], names), _degree(t[2], names)
    return max(a, b) if op in "+-" else a + b


def degree(expr: "Expr", names: Mapping[str, int] | None = None) -> int:
    """The expression's degree with each name in ``names`` standing for that degree (a chain of defs each of
    degree 64 multiplies: callers bound the result by MAX_DEGREE)."""
    return _degree(expr.tree, names)


def _has_call(t: tuple) -> bool:
    return t[0] == "call" or any(_has_call(x) for x in t[1:] if isinstance(x, tuple))


def evaluate_exact(expr: Expr, env: Mapping[str, Fraction]) -> Fraction:
    """The exact rational value of an expression without functions at exact rational ``env``
    (ParameterError naming the entry on a division by zero)."""
    return expr.evaluate(env)


# ------------------------------------------------------------------------------------ calculus on trees

_ZERO, _ONE = ("num", Fraction(0)), ("num", Fraction(1))


def _num(t) -> Fraction | None:
    return t[1] if t[0] == "num" else None


def _add(a, b):
    if _num(a) == 0:
        return b
    if _num(b) == 0:
        return a
    if _num(a) is not None and _num(b) is not None:
        return ("num", a[1] + b[1])
    return ("+", a, b)


def _sub(a, b):
    if _num(b) == 0:
        return a
    if _num(a) == 0:
        return _neg(b)
    return ("-", a, b)


def _neg(a):
    if _num(a) is not None:
        return ("num", -a[1])
    return a[1] if a[0] == "neg" else ("neg", a)


def _mul(a, b):
    if _num(a) == 0 or _num(b) == 0:
        return _ZERO
    if _num(a) == 1:
        return b
    if _num(b) == 1:
        return a
    if _num(a) is not None and _num(b) is not None:
        return ("num", a[1] * b[1])
    return ("*", a, b)


def _div(a, b):
    if _num(a) == 0:
        return _ZERO
    if _num(b) == 1:
        return a
    return ("/", a, b)


def _call(name, u):
    return ("call", name, (u,))


def _pow(u, n: int):
    if n == 0:
        return _ONE
    if n == 1:
        return u
    return ("^", u, n)


def _d(t, x: str):
    op = t[0]
    if op == "num":
        return _ZERO
    if op == "name":
        return _ONE if t[1] == x else _ZERO
    if op == "neg":
        return _neg(_d(t[1], x))
    if op in "+-":
        a, b = _d(t[1], x), _d(t[2], x)
        return _add(a, b) if op == "+" else _sub(a, b)
    if op == "*":
        return _add(_mul(_d(t[1], x), t[2]), _mul(t[1], _d(t[2], x)))
    if op == "/":
        # (u/v)' = u'/v - u v'/v^2
        u, v = t[1], t[2]
        du, dv = _d(u, x), _d(v, x)
        return _sub(_div(du, v), _div(_mul(u, dv), _pow(v, 2)))
    if op == "^":
        u, n = t[1], t[2]
        du = _d(u, x)
        if n == 0 or _num(du) == 0:
            return _ZERO
        # n u^(n-1) u'  (n < 0 included: u^(n-1) is a negative power again)
        return _mul(_mul(("num", Fraction(n)), _pow(u, n - 1)), du)
    if op == "call":
        name, (u,) = t[1], t[2]
        du = _d(u, x)
        if _num(du) == 0:
            return _ZERO
        rule = {
            "sin": lambda: _call("cos", u),
            "cos": lambda: _neg(_call("sin", u)),
            "tan": lambda: _add(_ONE, _pow(_call("tan", u), 2)),
            "exp": lambda: _call("exp", u),
            "log": lambda: _div(_ONE, u),
            "sqrt": lambda: _div(_ONE, _mul(("num", Fraction(2)), _call("sqrt", u))),
            "tanh": lambda: _sub(_ONE, _pow(_call("tanh", u), 2)),
            "atan": lambda: _div(_ONE, _add(_ONE, _pow(u, 2))),
            "abs": lambda: _call("sign", u),
            "sign": lambda: _ZERO,
        }.get(name)
        if rule is None:
            raise ParameterError(f"no derivative rule for the function {name!r}")
        return _mul(rule(), du)
    raise ValueError(f"unknown node {op!r}")


def tree_size(t: tuple) -> int:
    """The number of nodes of a tree."""
    if t[0] in ("num", "name"):
        return 1
    if t[0] == "call":
        return 1 + sum(tree_size(a) for a in t[2])
    if t[0] in ("neg", "^"):
        return 1 + tree_size(t[1])
    return 1 + tree_size(t[1]) + tree_size(t[2])


def derivative(expr: Expr, name: str) -> Expr:
    """The exact derivative of ``expr`` in ``name`` (the other names constants), as an Expr over the same names
    and the functions of :data:`UNARY_FUNCTIONS` plus ``sign`` (abs' derivative). Guarantee: where the expression
    and every function in the derivative are defined, the derivative's value is the derivative of the value (the
    rules are the textbook ones, applied symbolically; light simplification of exact 0 and 1 only). Fails when: a
    function has no rule, or the derivative has more than :data:`MAX_DERIVATIVE_NODES` nodes (ParameterError
    naming the entry)."""
    t = _d(expr.tree, name)
    if tree_size(t) > MAX_DERIVATIVE_NODES:
        raise ParameterError(f"{expr.where}: the derivative of {expr.text!r} has more than {MAX_DERIVATIVE_NODES} "
                             "nodes; simplify the expression")
    return Expr(t, f"d/d{name} ({expr.text})", expr.where)


def parity(expr: Expr, name: str) -> str | None:
    """"odd" or "even" when the tree shows e(-x) = -e(x) (resp. e(x)) identically in ``name`` (every other name
    and number a constant, so even); None when it does not show either (not a proof of the contrary). Rules:
    sums of odd (even) terms, products by the sign rule, integer powers, odd functions (sin, tan, tanh, atan,
    sign) keep their argument's parity, even ones (cos, abs) make it even, any function of an even argument is
    even; anything else (exp, log, sqrt of an odd argument, a sum of an odd and an even term) is None."""
    def p(t):
        op = t[0]
        if op == "num":
            return "even"
        if op == "name":
            return "odd" if t[1] == name else "even"
        if op == "neg":
            return p(t[1])
        if op in "+-":
            a, b = p(t[1]), p(t[2])
            if _num(t[1]) == 0:
                return b
            if _num(t[2]) == 0:
                return a
            return a if a == b else None
        if op in "*/":
            a, b = p(t[1]), p(t[2])
            if a is None or b is None:
                return None
            return "even" if a == b else "odd"
        if op == "^":
            a = p(t[1])
            if a is None:
                return None
            return "odd" if a == "odd" and t[2] % 2 else "even"
        if op == "call":
            a = p(t[2][0])
            if a == "even":
                return "even"
            if a == "odd":
                if t[1] in _ODD_FUNCTIONS:
                    return "odd"
                if t[1] in _EVEN_FUNCTIONS:
                    return "even"
            return None
        return None
    return p(expr.tree)
