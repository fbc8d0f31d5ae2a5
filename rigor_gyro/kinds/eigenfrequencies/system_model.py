"""A gyroscopic system written in the scene file: ``M q'' + (G + D) q' + K q = 0`` (kind
``eigenfrequencies``, table ``[system]``; issue 42 part 3).

Scene format::

    [parameters]                 # exact rationals, any names (identifiers)
    a = "15.08"
    [system]
    M = [["a", "b"], ["b", "1"]]  # n x n, symmetric, nonsingular; entries expressions in the parameters
    G = [["0", "1"], ["-1", "0"]] # optional, skew-symmetric (gyroscopic forces)
    K = [["1", "0"], ["0", "2"]]  # symmetric (potential forces)
    D = ...                       # optional, symmetric (damping)
    defs = ["L = a - b", ...]     # optional named sub-expressions, in order (usable in every later entry)
    brackets = [["lo1", "hi1"], ...]   # optional: bounds on omega_1, omega_2, ... (may use sqrt)
    [options]
    rel_width = "1e-30"           # relative width of omega_j and freq_hz_j
    zero_roots = "0"              # multiplicity of lambda = 0 the model has by construction (cyclic coordinates)
    hz_scale = "617.75"           # optional: freq_hz_j = hz_scale * sqrt(omega_j); an expression in the parameters

Entries are read by :mod:`rigor_gyro.core.expressions` (+ - * / ^ with integer exponents, parentheses, exact
decimals; never ``eval``). Matrix entries and ``defs`` used in them are exact rationals at the scene's
parameters; brackets are evaluated in Arb balls and may also use ``sqrt``.

Mathematics. P(lambda) = det(lambda^2 M + lambda (G + D) + K) has degree 2n (M nonsingular) and is built
exactly (:func:`rigor_gyro.core.polymat.det_by_interpolation`). With ``zero_roots`` = z, P = lambda^z P~(lambda)
is expected. If P~ is even (always so when D = 0: P(-lambda) = det of the transpose), P~(lambda) = Q(omega) at
lambda^2 = -omega, the frequency polynomial, of degree m = (2n - z)/2: its roots omega_1 < ... < omega_m, when
real, positive and simple, give the 2m simple roots lambda = +-i sqrt(omega_j) on the imaginary axis and the
eigenfrequencies sqrt(omega_j) (in Hz: hz_scale sqrt(omega_j)). An odd term of P~ means some root has a
nonzero real part (purely imaginary simple roots come in pairs +-i y, whose product is even).

Guarantee: the polynomials are exact ``fmpq_poly``; every bad model is a ParameterError naming the entry.

Fails when: ``[system]`` lacks M or K, has an unknown key, a matrix is not square or not n x n, an entry does not
parse or names an unknown parameter, divides by zero, M or K or D is not symmetric, G not skew, M singular,
n > 12, ``zero_roots`` odd or > 2n, more brackets than frequencies, a parameter that no entry (matrix, def,
bracket, ``hz_scale``) names (as ``[plant]``: a misspelt name): :class:`ParameterError` (exit 2).
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction

from flint import arb, fmpq, fmpq_mat, fmpq_poly

from ...core.balls import certainly_lt, decimal_bounds
from ...core.errors import ParameterError
from ...core.exact import Exact, option_count, option_number, parse_exact, parse_options
from ...core.expressions import MAX_DEGREE, Expr, degree, parse
from ...core.polymat import det_by_interpolation
from .system_bounds import check_bracket_values

__all__ = ["SystemModel", "validate_system", "SYSTEM_OPTIONS", "SYSTEM_KEYS", "frequency_polynomial",
           "characteristic_polynomial", "NotRealBound", "MAX_DOF", "ball_value"]

SYSTEM_KEYS = ("M", "G", "K", "D", "defs", "brackets")
SYSTEM_OPTIONS = {"rel_width": "1e-30", "zero_roots": "0", "hz_scale": ""}
MAX_DOF = 12
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$", re.ASCII)
_FUNCTIONS = frozenset({"sqrt"})


class NotRealBound(ArithmeticError):
    """A bracket takes the square root of a certainly negative number (it has no real value)."""

    def __init__(self, message: str, radicand: arb):
        super().__init__(message)
        self.radicand = radicand


@dataclass(frozen=True)
class SystemModel:
    """A validated ``[system]`` scene: the parsed entries, the exact parameter values and the options."""

    values: dict[str, fmpq]                # the parameters and the defs that are rational, exact
    params: dict[str, Exact]
    n: int
    M: tuple
    G: tuple | None
    K: tuple
    D: tuple | None
    defs: tuple                            # ((name, Expr), ...)
    brackets: tuple                        # ((Expr, Expr), ...)
    hz_scale: Expr | None
    rel_width: Exact
    zero_roots: int
    wanted: tuple
    table: dict = field(default_factory=dict, compare=False)
    exact: dict = field(default_factory=dict, compare=False)   # the exact matrices, computed once

    def matrix(self, which: str) -> fmpq_mat:
        """The exact matrix M, G, K or D (zero when not given) at the scene's parameters."""
        m = self.exact.get(which)
        if m is None:
            rows = getattr(self, which)
            m = fmpq_mat(self.n, self.n) if rows is None else fmpq_mat([[_exact(e, self.values) for e in row] for row in rows])
            self.exact[which] = m
        return m

    def characteristic(self) -> fmpq_poly:
        """P(lambda) = det(lambda^2 M + lambda (G + D) + K), exactly."""
        return characteristic_polynomial(self.matrix("M"), self.matrix("G") + self.matrix("D"), self.matrix("K"))

    def hz(self) -> fmpq | None:
        return None if self.hz_scale is None else _exact(self.hz_scale, self.values)

    def defs_needed(self, exprs) -> list[tuple[str, Expr]]:
        """The defs the expressions use, directly or through other defs, in their order."""
        defs = dict(self.defs)
        want: set[str] = set()
        todo = [n for e in exprs for n in e.names() if n in defs]
        while todo:
            n = todo.pop()
            if n not in want:
                want.add(n)
                todo.extend(m for m in defs[n].names() if m in defs)
        return [(n, e) for n, e in self.defs if n in want]

    def bracket_balls(self, j: int) -> tuple[arb, arb]:
        """Balls of the lower and upper bound of bracket j (1-based) at the working precision; NotRealBound
        when a square root's argument is certainly negative in the bracket or in a def it uses (a def that
        only other brackets use never decides this one)."""
        lo, hi = self.brackets[j - 1]
        env = {k: arb(_q(x.rational)) for k, x in self.params.items()}   # defs with sqrt: in balls, in order
        for name, e in self.defs_needed((lo, hi)):
            env[name] = ball_value(e, env)
        return ball_value(lo, env), ball_value(hi, env)


def _q(x: Fraction) -> fmpq:
    return fmpq(x.numerator, x.denominator)


def _exact(e: Expr, values: dict[str, fmpq]) -> fmpq:
    """The exact value of an entry (fmpq arithmetic: the same rationals as Fraction's, faster)."""
    return fmpq(e.evaluate(values, number=_q))


def _sqrt(x: arb) -> arb:
    if certainly_lt(x, 0):
        lo, hi = decimal_bounds(x, 8)
        raise NotRealBound(f"sqrt of [{lo}, {hi}] (certainly negative)", x)
    return x.sqrt()


def ball_value(e: Expr, env: dict[str, arb]) -> arb:
    """A ball containing the entry's value for every value in the balls of ``env`` (sqrt allowed; NotRealBound
    when its argument is certainly negative)."""
    return e.evaluate(env, number=lambda q: arb(_q(q)), functions={"sqrt": _sqrt})


def characteristic_polynomial(M: fmpq_mat, C: fmpq_mat, K: fmpq_mat) -> fmpq_poly:
    """det(lambda^2 M + lambda C + K) exactly (by interpolation, :mod:`rigor_gyro.core.polymat`)."""
    return det_by_interpolation([K, C, M])


def frequency_polynomial(P: fmpq_poly, z: int) -> tuple[int, fmpq_poly | None, list[int]]:
    """(multiplicity of lambda = 0 in P, Q or None, odd powers): P = lambda^mu P~; when mu == z and P~ is even,
    Q(omega) = P~(lambda) at lambda^2 = -omega, made monic; otherwise Q is None and the odd powers of P~ with
    nonzero coefficients are listed (exactly)."""
    c = P.coeffs()
    mu = next(i for i, x in enumerate(c) if x != 0)
    rest = c[mu:]
    odd = [k for k in range(1, len(rest), 2) if rest[k] != 0]
    if mu != z or odd:
        return mu, None, odd
    q = fmpq_poly([rest[2 * k] * (-1) ** k for k in range((len(rest) + 1) // 2)])
    return mu, q / q.leading_coefficient() if q.degree() >= 0 else q, odd


# ------------------------------------------------------------------------------ validation

def _matrix(table: dict, key: str, n: int | None, names: set[str], defs: set[str] = frozenset()) -> tuple:
    rows = table[key]
    where = f"[system] {key}"
    if not isinstance(rows, list) or not rows or not all(isinstance(r, list) for r in rows):
        raise ParameterError(f"{where}: expected a list of rows (lists of strings), e.g. [[\"1\", \"0\"], [\"0\", \"1\"]]")
    size = len(rows) if n is None else n
    if len(rows) != size:
        raise ParameterError(f"{where}: has {len(rows)} rows; M is {size} x {size}, so {key} must be too")
    for i, r in enumerate(rows, start=1):
        if len(r) != size:
            raise ParameterError(f"{where}: row {i} has {len(r)} entries; the matrix must be square ({size} x {size})")
    return tuple(tuple(_entry(e, f"{where}[{i}][{j}]", names, defs) for j, e in enumerate(r, start=1))
                 for i, r in enumerate(rows, start=1))


def _entry(text, where: str, names: set[str], defs: set[str]):
    """A matrix entry parsed over the exact names; one that uses a def with a square root is refused naming it
    (it read "unknown name 'r'", though r is defined: matrix entries are exact rationals of the parameters)."""
    try:
        return parse(text, where, names)
    except ParameterError:
        if isinstance(text, str):
            used = [d for d in sorted(defs - names) if re.search(rf"\b{re.escape(d)}\b", text)]
            if used:
                raise ParameterError(f"{where}: uses the def {used[0]!r}, which takes a square root: M, G, K and D "
                                     "must be rational in the parameters (sqrt is allowed in brackets and in defs "
                                     "only they use)") from None
        raise


def _structure(key: str, rows: tuple, values: dict, sign: int) -> fmpq_mat:
    """The exact matrix; ParameterError naming the first pair of entries that breaks symmetry (sign +1) or
    skew-symmetry (sign -1)."""
    exact = [[_exact(e, values) for e in row] for row in rows]
    n = len(rows)
    for i in range(n):
        for j in range(i, n):
            if exact[i][j] != sign * exact[j][i]:
                what = "symmetric" if sign > 0 else "skew-symmetric (G[i][j] = -G[j][i], zero diagonal)"
                hint = " (its skew part belongs in G)" if key == "D" else ""
                if i == j:          # only a skew matrix fails on its diagonal: x != -x means x != 0
                    raise ParameterError(f"[system] {key} must be {what}: {key}[{i + 1}][{i + 1}] = {rows[i][i].text!r} = "
                                         f"{exact[i][i]}, but the diagonal of {key} must be 0 (a term q_i' there is "
                                         "damping: move it to D)")
                raise ParameterError(f"[system] {key} must be {what}{hint}: {key}[{i + 1}][{j + 1}] = {rows[i][j].text!r} = "
                                     f"{exact[i][j]} but {key}[{j + 1}][{i + 1}] = {rows[j][i].text!r} = {exact[j][i]}")
    return fmpq_mat(exact)


def validate_system(scene, wanted: tuple) -> SystemModel:
    """Parse and check a ``[system]`` scene (see the module docstring); ``wanted`` are the claims asked for."""
    table = scene.model
    unknown = sorted(set(table) - set(SYSTEM_KEYS))
    if unknown:
        import difflib
        close = difflib.get_close_matches(unknown[0], SYSTEM_KEYS, n=1, cutoff=0.3)
        raise ParameterError(f"[system]: unknown key {unknown[0]!r}" + (f" (did you mean {close[0]!r}?)" if close else "")
                             + f"; the table takes {list(SYSTEM_KEYS)}")
    for key in ("M", "K"):
        if key not in table:
            raise ParameterError(f"[system]: missing {key} (a list of rows of strings); M and K are required, G and D optional")
    params: dict[str, Exact] = {}
    for k, v in scene.parameters.items():
        if not _NAME.match(k):
            raise ParameterError(f"parameter {k!r}: a name in a [system] scene must be an identifier (letters, digits, _)")
        x = parse_exact(v, k)
        if not x.is_rational:
            raise ParameterError(f"parameter {k!r}: must be rational in a [system] scene (got {v!r})")
        params[k] = x
    values: dict[str, fmpq] = {k: _q(x.rational) for k, x in params.items()}
    defs = []
    raw_defs = table.get("defs", [])
    if not isinstance(raw_defs, list) or not all(isinstance(d, str) for d in raw_defs):
        raise ParameterError("[system] defs: expected a list of strings \"name = expression\"")
    rational = dict(values)        # names with exact values (defs without sqrt)
    def_degrees: dict[str, int] = {}
    for i, d in enumerate(raw_defs, start=1):
        name, eq, text = d.partition("=")
        name = name.strip()
        if not eq or not _NAME.match(name):
            raise ParameterError(f"[system] defs[{i}]: expected \"name = expression\", got {d!r}")
        if name in ("sqrt",):
            raise ParameterError(f"[system] defs[{i}]: the name {name!r} is a function's; choose another name")
        if name in values:
            raise ParameterError(f"[system] defs[{i}]: the name {name!r} is already a parameter or an earlier def")
        e = parse(text, f"[system] defs[{i}] ({name})", set(values), _FUNCTIONS)
        def_degrees[name] = degree(e, def_degrees)
        if def_degrees[name] > MAX_DEGREE:
            raise ParameterError(f"[system] defs[{i}] ({name}): its degree through the defs it uses is "
                                 f"{def_degrees[name]}, above {MAX_DEGREE} (nested powers multiply); simplify it")
        defs.append((name, e))
        values[name] = fmpq(0)              # a placeholder: known name
        if not _uses_sqrt(e) and set(e.names()) <= set(rational):
            rational[name] = _exact(e, rational)
    exact_names = set(rational)
    M = _matrix(table, "M", None, exact_names, set(values))
    n = len(M)
    if n > MAX_DOF:
        raise ParameterError(f"[system] M: {n} degrees of freedom; at most {MAX_DOF} are supported")
    G = _matrix(table, "G", n, exact_names, set(values)) if "G" in table else None
    K = _matrix(table, "K", n, exact_names, set(values))
    D = _matrix(table, "D", n, exact_names, set(values)) if "D" in table else None
    exact = {"M": _structure("M", M, rational, +1), "K": _structure("K", K, rational, +1)}
    if G is not None:
        exact["G"] = _structure("G", G, rational, -1)
    if D is not None:
        exact["D"] = _structure("D", D, rational, +1)
    Mq = exact["M"]
    if Mq.det() == 0:
        raise ParameterError("[system] M is singular (det M = 0 exactly): the system is not of second order in every "
                             "coordinate; M must be nonsingular")
    opts = parse_options(scene.options, SYSTEM_OPTIONS, "eigenfrequencies ([system])")
    rel = option_number(opts["rel_width"], "rel_width", above="0", at_most="1")
    z = option_count(opts["zero_roots"], "zero_roots", 0, 2 * n)
    if z == 2 * n:
        raise ParameterError(f"option 'zero_roots' = {opts['zero_roots']!r}: every root of the {n}-degree-of-freedom "
                             f"system would be lambda = 0, leaving no frequency; at most {2 * n - 2}")
    if z % 2:
        raise ParameterError(f"option 'zero_roots' = {opts['zero_roots']!r}: must be even (lambda = 0 roots of a system "
                             "M q'' + G q' + K q come in pairs)")
    hz = None
    if opts["hz_scale"]:
        hz = parse(opts["hz_scale"], "option 'hz_scale'", exact_names)
        if not _exact(hz, rational) > 0:
            raise ParameterError(f"option 'hz_scale' = {opts['hz_scale']!r}: must be positive")
    raw = table.get("brackets", [])
    if not isinstance(raw, list) or not all(isinstance(b, list) and len(b) == 2 for b in raw):
        raise ParameterError("[system] brackets: expected a list of [lower, upper] pairs of strings, one per omega_j")
    m = (2 * n - z) // 2
    if len(raw) > m:
        raise ParameterError(f"[system] brackets: {len(raw)} brackets but the system has {m} frequencies omega_j")
    if "brackets" in wanted and not raw:
        raise ParameterError("claim 'brackets' is asked for but [system] gives no brackets: add "
                             "brackets = [[\"lower\", \"upper\"], ...] or leave the claim out of [claims] only")
    names = set(values)
    brackets = tuple((parse(lo, f"[system] brackets[{j}] lower", names, _FUNCTIONS),
                      parse(hi, f"[system] brackets[{j}] upper", names, _FUNCTIONS))
                     for j, (lo, hi) in enumerate(raw, start=1))
    for j, pair in enumerate(brackets, start=1):      # an exact bound (no sqrt) is computed exactly: a division by
        for side, e in zip(("lower", "upper"), pair):   # an exact zero is bad input, not a precision to escalate
            if not _uses_sqrt(e) and set(e.names()) <= set(rational):
                _exact(e, rational)
    used = {v for mat in (M, G, K, D) if mat is not None for row in mat for e in row for v in e.names()}
    used |= {v for _, e in defs for v in e.names()} | (hz.names() if hz is not None else set())
    used |= {v for pair in brackets for e in pair for v in e.names()}
    unused = sorted(set(params) - used)
    if unused:
        raise ParameterError(f"parameter {unused[0]!r}: not used by any entry of [system] (a misspelt name?): remove it "
                             "from [parameters], or use it in M, G, K, D, defs, brackets or hz_scale")
    if scene.paper:
        raise ParameterError("a [system] scene takes no [paper] table (the audit is the paper scene's)")
    model = SystemModel(rational, params, n, M, G, K, D, tuple(defs), brackets, hz, rel, z, tuple(wanted), dict(table),
                        exact)
    check_bracket_values(model)          # a bound that divides by an exact 0 (through sqrt too): bad input
    return model


def _uses_sqrt(e: Expr) -> bool:
    def walk(t):
        if t[0] == "call":
            return True
        return any(walk(x) for x in t[1:] if isinstance(x, tuple))
    return walk(e.tree)
