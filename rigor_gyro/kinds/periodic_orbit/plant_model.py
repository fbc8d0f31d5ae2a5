"""A relay feedback system written by the user: the ``[plant]`` table of a ``periodic_orbit`` scene.

Model. x' = M x + e u, u = S sign(c . x) (with a hysteresis width h >= 0: u switches to +S when c . x rises
through +h and to -S when it falls through -h), x in R^n, 1 <= n <= :data:`MAX_DIM`::

    [parameters]            # named exact numbers the entries may use
    H = "100"
    [plant]
    M = [["0", "1"], ["-2", "-H/B"]]     # rows of strings: exact rationals or expressions (core.expressions)
    e = ["0", "1"]
    c = ["1", "0"]
    S = "-1"                # optional, default "1" (S < 0: the relay in negative feedback)
    h = "0"                 # optional, default "0"

Guarantee: :func:`validate_plant` returns the exact rational M, e, c, S, h (``fmpq``), and the exact
transfer data the proofs use: the characteristic polynomial p(z) = det(z I - M), the numerator polynomials
N_i(z) = p(z) e_i^T (z I - M)^-1 e of every state component and N_c = sum c_i N_i of c . x, the Markov
parameters c M^k e. It also decides, exactly (rational arithmetic), the spectral conditions the kind needs
and refuses the models it does not handle, with a message naming what fails:

* p squarefree (every eigenvalue simple): a repeated eigenvalue (a double integrator, two equal time
  constants) is refused;
* no eigenvalue on the imaginary axis other than a simple 0 (p(i w) = 0 for a real w != 0 is decided by
  the gcd of the real and imaginary parts of p(i w)): there the half-period function has real poles;
* a simple zero eigenvalue (a pure integrator) is handled;
* G(s) = c (sI - M)^-1 e not identically 0 (no feedback loop otherwise), and not every even Markov parameter
  c M^(2j) e vanishes (otherwise g = -h identically: every theta a root when h = 0, none when h > 0; the message
  says which).

Precision: none (exact). Fails when: an entry is malformed (not a string, unknown name, division by zero),
the shapes disagree, a parameter is unused, an option is unknown, or a condition above fails:
:class:`~rigor_gyro.core.errors.ParameterError` (exit 2) naming the entry (``[plant] M[2][3]``).
"""
from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from flint import fmpq, fmpq_mat, fmpq_poly

from ...core.errors import ParameterError
from ...core.exact import Exact, option_number, parse_exact, parse_options
from ...core.expressions import evaluate_exact, parse as parse_expression

__all__ = ["MAX_DIM", "PLANT_KEYS", "PLANT_OPTIONS", "PlantModel", "validate_plant", "markov", "numerators"]

#: the largest state dimension accepted
MAX_DIM = 12
#: the keys of a [plant] table (M, e, c required)
PLANT_KEYS = ("M", "e", "c", "S", "h")
#: options of a plant scene (the Roitenberg scene's orbit option is not available here)
PLANT_OPTIONS = {"T_max": "auto", "theta_width": "1e-12"}


@dataclass(frozen=True)
class PlantModel:
    """A validated relay plant: exact data and the exact transfer quantities (module docstring)."""

    n: int
    M: fmpq_mat
    e: list
    c: list
    S: fmpq
    h: fmpq
    table: dict
    exact: dict[str, Exact]
    T_max: Exact | None
    theta_width: Exact
    charpoly: fmpq_poly
    #: N_i for every state component i, and N_c = sum c_i N_i
    numerators: list
    numerator_c: fmpq_poly
    zero_eigenvalue: bool
    paper: dict = field(default_factory=dict)
    orbit: None = None
    decided: dict = field(default_factory=dict, compare=False, repr=False)

    @property
    def params(self):
        """A plant scene has no Roitenberg parameters: the box and paper paths that read them refuse it."""
        raise ParameterError("a [plant] scene is proved at a point only: tolerance boxes, the paper audit and the "
                             "Roitenberg parameterisation's paths do not take a [plant] model yet")


def _did_you_mean(word: str, choices) -> str:
    close = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _entry(value: Any, label: str, names: dict[str, Fraction], used: set[str]) -> fmpq:
    if isinstance(value, bool) or not isinstance(value, (str, int)):
        raise ParameterError(f"[plant] {label}: expected a quoted exact number or expression, got "
                             f"{type(value).__name__}")
    expr = parse_expression(value, f"[plant] {label}", names=set(names))
    used.update(expr.names())
    q = Fraction(evaluate_exact(expr, names))
    return fmpq(q.numerator, q.denominator)


def _vector(table: dict, key: str, n: int | None, names, used) -> list:
    v = table.get(key)
    if not isinstance(v, list) or not v or any(isinstance(x, list) for x in v):
        raise ParameterError(f"[plant] {key}: expected a list of strings (a vector), got {v!r}"[:300])
    if n is not None and len(v) != n:
        raise ParameterError(f"[plant] {key}: has {len(v)} entries, M is {n}x{n}")
    return [_entry(x, f"{key}[{i + 1}]", names, used) for i, x in enumerate(v)]


def _option(text: str, name: str, label: str, **bounds) -> Exact:
    """:func:`~rigor_gyro.core.exact.option_number`, its unreadable-number messages naming an option (they
    say "parameter")."""
    try:
        return option_number(text, label, **bounds)
    except ParameterError as e:
        msg, prefix = str(e), f"parameter {label!r}: "
        raise ParameterError(f"option {name!r}: " + msg[len(prefix):] if msg.startswith(prefix) else msg) from None


def markov(M: fmpq_mat, e: list, c: list, count: int) -> list[fmpq]:
    """c M^k e for k < count, exactly."""
    n = len(e)
    v = fmpq_mat([[x] for x in e])
    out = []
    for _ in range(count):
        out.append(sum((c[i] * v[i, 0] for i in range(n)), fmpq(0)))
        v = M * v
    return out


def numerators(M: fmpq_mat, e: list, p: fmpq_poly) -> list[fmpq_poly]:
    """N_i(z) = p(z) e_i^T (z I - M)^-1 e, i.e. adj(z I - M) e, exactly: with p = sum a_k z^k (a_n = 1),
    N(z) = sum_{k < n} z^k sum_{i = k+1..n} a_i M^(i-k-1) e (Krylov vectors; exact)."""
    n = len(e)
    a = [p[k] for k in range(n + 1)]
    krylov = [fmpq_mat([[x] for x in e])]
    for _ in range(n - 1):
        krylov.append(M * krylov[-1])
    coeffs = [[fmpq(0)] * n for _ in range(n)]      # coeffs[i][k]: z^k of N_i
    for k in range(n):
        for i in range(k + 1, n + 1):
            v = krylov[i - k - 1]
            for r in range(n):
                coeffs[r][k] += a[i] * v[r, 0]
    return [fmpq_poly(coeffs[r]) for r in range(n)]


def _imaginary_axis_roots(p: fmpq_poly) -> bool:
    """Whether p(i w) = 0 for some real w != 0. With p(i w) = A(w) + i B(w) (A even, B odd, rational
    coefficients), such a w is a common real root of A and B, i.e. a nonzero real root of gcd(A, B) (exact);
    the real roots of that gcd's squarefree part are isolated (:func:`~rigor_gyro.core.polyroots.isolate_polynomial`,
    real only when certified). True also when the isolation fails (conservative: the plant is refused)."""
    deg = p.degree()
    A = [fmpq(0)] * (deg + 1)
    B = [fmpq(0)] * (deg + 1)
    for k in range(deg + 1):
        ik = [1, 1, -1, -1][k % 4]          # i^k = 1, i, -1, -i: real part for even k, imaginary for odd
        if k % 2 == 0:
            A[k] = p[k] * ik
        else:
            B[k] = p[k] * ik
    g = fmpq_poly(A).gcd(fmpq_poly(B))
    while g.degree() >= 1 and g[0] == 0:     # w = 0 is the zero eigenvalue, handled separately
        g = fmpq_poly([g[k] for k in range(1, g.degree() + 1)])
    if g.degree() < 1:
        return False
    # g(w) is even or odd in w times a power of w; any real root? decide by real-root isolation of the
    # squarefree part (exact squarefreeness; real roots reported only when certified real)
    from ...core.polyroots import isolate_polynomial
    sq = g / g.gcd(g.derivative())
    roots = isolate_polynomial(sq)
    if not roots.verified:
        return True                          # cannot exclude: refuse (conservative)
    return bool(roots.real)


def validate_plant(scene) -> PlantModel:
    """Parse and check a scene's ``[plant]`` table (module docstring); ParameterError naming the entry."""
    table = dict(scene.model)
    unknown = sorted(set(table) - set(PLANT_KEYS))
    if unknown:
        raise ParameterError(f"[plant] {unknown[0]}: unknown key{_did_you_mean(unknown[0], PLANT_KEYS)}; a [plant] "
                             f"table has {list(PLANT_KEYS)}")
    for key in ("M", "e", "c"):
        if key not in table:
            raise ParameterError(f"[plant] {key}: missing (a [plant] table needs M, e and c)")
    exact = {}
    for k, v in scene.parameters.items():
        ex = parse_exact(v, k)
        if not ex.is_rational:
            raise ParameterError(f"parameter {k!r} = {v!r}: must be rational (pi is not allowed in a [plant] model)")
        exact[k] = ex
    names = {k: ex.rational for k, ex in exact.items()}
    used: set[str] = set()
    rows = table["M"]
    if not isinstance(rows, list) or not rows or not all(isinstance(r, list) for r in rows):
        raise ParameterError("[plant] M: expected a list of rows (lists of strings)")
    n = len(rows)
    if n > MAX_DIM:
        raise ParameterError(f"[plant] M: dimension {n} exceeds {MAX_DIM}")
    for i, r in enumerate(rows):
        if len(r) != n:
            raise ParameterError(f"[plant] M[{i + 1}]: has {len(r)} entries; M must be square ({n}x{n})")
    M = fmpq_mat([[_entry(x, f"M[{i + 1}][{j + 1}]", names, used) for j, x in enumerate(r)]
                  for i, r in enumerate(rows)])
    e = _vector(table, "e", n, names, used)
    c = _vector(table, "c", n, names, used)
    S = _entry(table.get("S", "1"), "S", names, used)
    h = _entry(table.get("h", "0"), "h", names, used)
    if S == 0:
        raise ParameterError("[plant] S: S = 0 means no relay output (no forcing, no self-oscillation)")
    if h < 0:
        raise ParameterError(f"[plant] h = {table['h']!r}: the hysteresis width must be >= 0")
    if all(x == 0 for x in c):
        raise ParameterError("[plant] c: c = 0: the relay input c . x is identically 0")
    if all(x == 0 for x in e):
        raise ParameterError("[plant] e: e = 0: the relay does not act on the plant")
    unused = sorted(set(exact) - used)
    if unused:
        raise ParameterError(f"parameter {unused[0]!r}: not used by any entry of [plant] (a misspelt name?)")
    opts = parse_options(scene.options, PLANT_OPTIONS, "periodic_orbit ([plant])")
    T_max = None if opts["T_max"] == "auto" else _option(opts["T_max"], "T_max", "T_max (or \"auto\")", above="0",
                                                          at_most="1e6")
    tw = _option(opts["theta_width"], "theta_width", "theta_width", above="0", at_most="1")
    if scene.paper:
        raise ParameterError("[paper]: the audit of printed numbers belongs to the paper's parameterisation; a "
                             "[plant] scene has none")
    p = M.charpoly()
    if p.gcd(p.derivative()).degree() > 0:
        raise ParameterError(f"[plant] M: a repeated eigenvalue (det(zI - M) = {p} is not squarefree): the "
                             "half-period map is built from simple eigenvalues; perturb the repeated time constant "
                             "or write the plant with distinct eigenvalues")
    zero = p[0] == 0
    if zero and n == 1:
        raise ParameterError("[plant] M = [[\"0\"]]: a lone integrator, whose only eigenvalue is 0; the half-period map "
                             "is built from the nonzero eigenvalues (with h = 0 the loop slides at y = 0 and has no "
                             "self-oscillation; with h > 0 its triangle wave is not treated by this path): give the "
                             "plant a lag, e.g. M = [[\"-1/T\"]]")
    if _imaginary_axis_roots(p):
        raise ParameterError("[plant] M: an eigenvalue on the imaginary axis other than 0 (an undamped "
                             "oscillation): I + exp(M theta) is singular at real theta, the half-period function "
                             "has real poles; add damping")
    Ns = numerators(M, e, p)
    Nc = sum((c[i] * Ns[i] for i in range(n)), fmpq_poly([]))
    m = markov(M, e, c, 2 * n)
    if all(x == 0 for x in m):
        raise ParameterError("[plant] c, e: G(s) = c (sI - M)^-1 e = 0 identically (every Markov parameter c M^k e "
                             "vanishes): the relay's output never reaches its input c . x, there is no feedback loop")
    if all(m[2 * j] == 0 for j in range(n)):
        what = ("so c . x0(theta) = 0 = h holds for every theta > 0: a continuum of symmetric solutions, no isolated "
                "root to certify" if h == 0 else
                f"so the condition c . x0(theta) = h = {h} has no root: no symmetric orbit with two switchings per "
                "period exists (this path isolates roots of g and does not treat g = -h as a model)")
        raise ParameterError("[plant] c, e: every even Markov parameter c M^(2j) e vanishes (G(s) has only even "
                             "powers of 1/s), so c . x0(theta) = 0 for every theta and g = -h identically, " + what)
    return PlantModel(n, M, e, c, S, h, table, exact, T_max, tw, p, Ns, Nc, zero)
