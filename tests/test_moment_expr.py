"""Moment laws written in the scene (issue 42 part 2): expressions (moment_expr) and measured tables
(moment_table). The calculus on trees against sympy, every enclosure against mpmath samples (every sampled value
inside the certified range), the conditions (f(0) = 0, oddness, the table's data) refused with the entry named
(exit 2), the built-in laws rewritten as expressions giving the same verdicts and overlapping enclosures claim by
claim, the example scenes proved and confirmed by the checker, which rebuilds the law from the certificate."""
import json
import math
import random
import re
from fractions import Fraction
from pathlib import Path

import mpmath as mp
import pytest
from flint import arb, arb_series

from rigor_gyro import cli, load_scene, parse_scene, prove_scene
from rigor_gyro.check import check_certificate
from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.core.exact import parse_exact
from rigor_gyro.core.expressions import UNARY_FUNCTIONS, derivative, parity, parse
from rigor_gyro.kinds.lyapunov.model import Dual
from rigor_gyro.kinds.lyapunov.polar_forms import law_is_odd
from rigor_gyro.kinds.lyapunov import moment_scene
from rigor_gyro.kinds.lyapunov.moment_expr import FINITE, expression_law, exact_value
from rigor_gyro.kinds.lyapunov.moment_table import natural_spline, table_law

MOMENTS_DIR = Path(__file__).resolve().parents[1] / "rigor_gyro" / "scenes" / "moments"
PARAMS = dict(A="2", C="3.3", A1="2.2", B1="2.2", C1="2.8", A2="8.5", H="1e4", k="0.4", a="100",
              x2_star="pi/6", mu="0.02")


def scene_text(moment: str, table: str = "", claims=None, name="t") -> str:
    body = "\n".join(f'{k} = "{v}"' for k, v in PARAMS.items())
    only = f"\n[claims]\nonly = {json.dumps(claims)}\n" if claims else ""
    return f'name = "{name}"\nkind = "lyapunov"\n[parameters]\n{body}\nmoment = "{moment}"\n{only}{table}'


# ------------------------------------------------------------------------------------ calculus on trees

def _to_sympy(t, sp, x, syms):
    op = t[0]
    if op == "num":
        return sp.Rational(t[1].numerator, t[1].denominator)
    if op == "name":
        return x if t[1] == "x2" else syms[t[1]]
    if op == "neg":
        return -_to_sympy(t[1], sp, x, syms)
    if op == "^":
        return _to_sympy(t[1], sp, x, syms) ** t[2]
    if op == "call":
        u = _to_sympy(t[2][0], sp, x, syms)
        return {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "exp": sp.exp, "log": sp.log, "sqrt": sp.sqrt,
                "tanh": sp.tanh, "atan": sp.atan, "abs": sp.Abs, "sign": sp.sign}[t[1]](u)
    a, b = _to_sympy(t[1], sp, x, syms), _to_sympy(t[2], sp, x, syms)
    return {"+": a + b, "-": a - b, "*": a * b, "/": a / b}[op]


EXPRESSIONS = ["a*sin(x2) + b*x2^3", "tan(x2)*exp(x2^2)/(1 + x2^2)", "log(2 + cos(x2))*atan(b*x2)",
               "sqrt(1 + x2^2)*tanh(x2) - x2^-2", "x2*abs(x2) + (a - x2)^5", "exp(-x2)/(b + sin(x2))^2"]


@pytest.mark.parametrize("text", EXPRESSIONS)
def test_the_symbolic_derivative_is_sympys(text):
    sp = pytest.importorskip("sympy")
    x = sp.Symbol("x2", real=True)
    syms = {"a": sp.Symbol("a", real=True), "b": sp.Symbol("b", real=True)}
    e = parse(text, "t", names={"x2", "a", "b"}, functions=UNARY_FUNCTIONS)
    mine = _to_sympy(derivative(e, "x2").tree, sp, x, syms)
    theirs = sp.diff(_to_sympy(e.tree, sp, x, syms), x)
    for xv in (sp.Rational(3, 10), sp.Rational(7, 5)):
        sub = {x: xv, syms["a"]: sp.Rational(2), syms["b"]: sp.Rational(1, 3)}
        assert abs(sp.N((mine - theirs).subs(sub), 30)) < 1e-25


@pytest.mark.parametrize("text,want", [
    ("a*sin(x2) + b*x2^3", "odd"), ("x2", "odd"), ("x2*cos(x2)", "odd"), ("tanh(x2)*x2^2", "odd"),
    ("atan(sin(x2))", "odd"), ("x2/(1 + x2^2)", "odd"), ("x2*abs(x2)", "odd"), ("cos(x2)", "even"),
    ("exp(x2^2)", "even"), ("sin(x2) + 1", None), ("exp(x2) - 1", None), ("sin(x2) + x2^2", None),
    ("log(1 + x2)", None), ("sqrt(x2)", None), ("x2*exp(x2)", None)])
def test_parity_is_read_off_the_formula_and_holds(text, want):
    e = parse(text, "t", names={"x2", "a", "b"}, functions=UNARY_FUNCTIONS)
    assert parity(e, "x2") == want
    if want is None:
        return
    mp.mp.dps = 30
    env = {"a": mp.mpf(2), "b": mp.mpf("0.5")}
    fns = {"sin": mp.sin, "cos": mp.cos, "tan": mp.tan, "exp": mp.exp, "log": mp.log, "sqrt": mp.sqrt,
           "tanh": mp.tanh, "atan": mp.atan, "abs": abs}
    for xv in ("0.3", "0.9", "1.7"):
        p = e.evaluate({**env, "x2": mp.mpf(xv)}, number=lambda q: mp.mpf(q.numerator) / q.denominator, functions=fns)
        m = e.evaluate({**env, "x2": -mp.mpf(xv)}, number=lambda q: mp.mpf(q.numerator) / q.denominator, functions=fns)
        assert abs(p + m if want == "odd" else p - m) < mp.mpf(10) ** -25


def test_exact_values_at_zero_and_multiples_of_pi():
    e = parse("a*sin(x2) + b*x2^3", "t", names={"x2", "a", "b"}, functions=UNARY_FUNCTIONS)
    p = {"b": Fraction(1, 3)}
    assert exact_value(e, Fraction(0), p) == 0
    assert exact_value(e, ("pi", Fraction(1)), p) is FINITE          # b pi^3: not exactly known
    s = parse("a*sin(x2)*cos(x2) + tan(x2)", "t", names={"x2", "a"}, functions=UNARY_FUNCTIONS)
    assert exact_value(s, ("pi", Fraction(1)), {}) == 0
    assert exact_value(s, ("pi", Fraction(1, 2)), {}) is None         # tan has a pole there
    assert exact_value(parse("x2/x2", "t", names={"x2"}), Fraction(0), {}) is None
    assert exact_value(parse("log(x2)*x2", "t", names={"x2"}, functions=UNARY_FUNCTIONS), Fraction(0), {}) is None
    assert exact_value(parse("sqrt(x2 + 9/4) - 3/2", "t", names={"x2"}, functions=UNARY_FUNCTIONS), Fraction(0), {}) == 0


def test_the_law_certifies_f0_and_oddness_before_use():
    with pytest.raises(ParameterError, match=r"f\(0\)"):
        expression_law({"f": "a*sin(x2)/x2^2"})
    with pytest.raises(ParameterError, match="not certified odd"):
        expression_law({"f": "a*sin(x2) + x2^2"})
    with pytest.raises(ParameterError, match="not certified odd"):
        expression_law({"f": "exp(x2) - 1"})
    assert expression_law({"f": "a*sin(x2)"}).zeros_over_pi() == (Fraction(-1), Fraction(0), Fraction(1))
    assert expression_law({"f": "a*x2"}).zeros_over_pi() == (Fraction(0),)
    assert expression_law({"f": "a*sin(2*x2)"}).zeros_over_pi() == tuple(Fraction(k, 2) for k in range(-2, 3))
    xs = parse_exact("pi/6")
    with pytest.raises(ParameterError, match=r"x2\[1\], f\[1\]: the first point"):
        table_law({"x2": ["0", "0.3", "0.6"], "f": ["1", "2", "3"]}, xs)
    with pytest.raises(ParameterError, match=r"x2\[3\] = 1/2: the table must reach"):
        table_law({"x2": ["0", "0.3", "0.5"], "f": ["0", "2", "3"]}, xs)
    assert table_law({"x2": ["0", "0.3", "0.6"], "f": ["0", "2", "3"]}, xs).zeros_over_pi() == (Fraction(0),)
    e = parse("sin(x2) + cos(x2)", "t", names={"x2"}, functions=UNARY_FUNCTIONS)
    assert exact_value(e, ("pi", Fraction(1, 2)), {}) == 1 and exact_value(e, ("pi", Fraction(1)), {}) == -1
    assert exact_value(e, ("pi", Fraction(-1, 2)), {}) == -1 and exact_value(e, ("pi", Fraction(3, 2)), {}) == -1


# ------------------------------------------------------------------------------------ enclosures against mpmath

def _mp(x: arb):
    return mp.mpf(x.mid().str(40, radius=False)) if x.rad() == 0 else None


def _samples(x: arb, n: int = 7):
    lo, hi = (mp.mpf(v.str(40, radius=False)) for v in (x.lower(), x.upper()))
    return [lo + (hi - lo) * k / (n - 1) for k in range(n)]


def _inside(ball: arb, v) -> bool:
    lo, hi = (mp.mpf(b.str(40, radius=False)) for b in (ball.lower(), ball.upper()))
    tol = mp.mpf(10) ** -30 * (1 + abs(v))
    return lo - tol <= v <= hi + tol


EXPR_LAW = {"f": "a*sin(x2) + b*x2^3 - c*atan(x2)*cos(x2)", "b": "20", "c": "1/3"}


def _mp_expr(a, x):
    return a * mp.sin(x) + 20 * x ** 3 - mp.mpf(1) / 3 * mp.atan(x) * mp.cos(x)


BALLS = [arb("0.3"), arb(0, "0.4"), arb("0.25", "0.1"), arb("-0.4", "0.05"), arb("1e-9", "1e-9"), arb(0, "1e-6")]


def test_expression_law_encloses_f_df_f_over_x_and_G():
    mp.mp.dps = 40
    L = expression_law(EXPR_LAW)
    A0, C0 = Fraction(127, 10), Fraction(7, 5)
    with working_precision(128):
        a = arb(100)
        d = mp.diff(lambda t: _mp_expr(100, t), mp.mpf(0))
        for X in BALLS:
            F, dF, Q = L.f(a, X), L.df(a, X), L.f_over_x(a, X)
            assert all(b.is_finite() for b in (F, dF, Q))
            for x in _samples(X):
                assert _inside(F, _mp_expr(100, x))
                assert _inside(dF, mp.diff(lambda t: _mp_expr(100, t), x))
                assert _inside(Q, _mp_expr(100, x) / x if x != 0 else d)
            du = L.f(a, Dual(X, arb(1)))                    # forward mode: f on a Dual gives f'
            assert du.d.overlaps(dF)
        for xs in ("0.3", "-0.5", "1e-3"):
            x = arb(xs)
            G = L.G(a, arb(127) / 10, arb(7) / 5, x)
            want = mp.quad(lambda s: mp.cos(s) * _mp_expr(100, s) / (mp.mpf(127) / 10 - mp.mpf(7) / 5 * mp.sin(s) ** 2),
                           [0, mp.mpf(xs)])
            assert _inside(G, want) and G.rad() < arb("1e-25") * (1 + abs(G))
    assert A0 > C0 and law_is_odd(L)


def test_G_of_a_law_with_a_kink_is_enclosed():
    """abs is not analytic at 0: the quadrature is told so (Arb's analyticity flag), and G stays enclosed."""
    mp.mp.dps = 40
    L = expression_law({"f": "a*x2*abs(x2) + x2"})
    with working_precision(128):
        for xs in ("0.5", "-0.3"):
            G = L.G(arb(3), arb(127) / 10, arb(7) / 5, arb(xs))
            want = mp.quad(lambda s: mp.cos(s) * (3 * s * abs(s) + s) / (mp.mpf(127) / 10 - mp.mpf(7) / 5 * mp.sin(s) ** 2),
                           [0, mp.mpf(xs)])
            assert _inside(G, want) and G.rad() < arb("1e-20")
        # a kink inside the path (|x2| = 1/4): Arb's quadrature must be told, or its bound is wrong
        K = expression_law({"f": "a*x2*abs(abs(x2) - 1/4) + x2"})
        G = K.G(arb(3), arb(127) / 10, arb(7) / 5, arb("0.5"))
        want = mp.quad(lambda s: mp.cos(s) * (3 * s * abs(abs(s) - mp.mpf(1) / 4) + s)
                       / (mp.mpf(127) / 10 - mp.mpf(7) / 5 * mp.sin(s) ** 2), [0, mp.mpf(1) / 4, mp.mpf(1) / 2])
        assert _inside(G, want) and G.rad() < arb("1e-20")


def test_the_series_path_of_an_expression_law_is_its_taylor_series():
    L = expression_law({"f": "a*tanh(x2)"})
    with working_precision(96):
        s = L.f(arb(2), arb_series([arb("0.4"), 1], prec=3))
        c = s.coeffs()
        t = mp.tanh(mp.mpf("0.4"))
        assert _inside(c[0], 2 * t) and _inside(c[1], 2 * (1 - t ** 2)) and _inside(c[2], -2 * t * (1 - t ** 2))


POINTS = ["0", "0.05", "0.1", "0.15", "0.2", "0.3", "0.45", "0.6"]


def _table():
    fs = ["0"] + [f"{100 * float(x) + 60 * float(x) ** 3:.3f}" for x in POINTS[1:]]
    return {"x2": POINTS, "f": fs}


def test_the_spline_coefficients_are_scipys_natural_spline():
    scipy = pytest.importorskip("scipy.interpolate")
    t = _table()
    xs = [Fraction(v) for v in t["x2"]]
    fs = [Fraction(v) for v in t["f"]]
    X = [-v for v in xs[:0:-1]] + xs
    Y = [-v for v in fs[:0:-1]] + fs
    polys = natural_spline(X, Y)
    cs = scipy.CubicSpline([float(v) for v in X], [float(v) for v in Y], bc_type="natural")
    for i, p in enumerate(polys):
        for k in range(4):
            assert math.isclose(float(p[k]), cs.c[3 - k][i], rel_tol=1e-9, abs_tol=1e-9)
    # odd by construction: the piece at 0 has no constant and no square term
    p0 = polys[len(xs) - 1]
    assert p0[0] == 0 and p0[2] == 0


def _mp_spline(L, x):
    """The spline at an mpmath point from its exact pieces (the tangent continuations included)."""
    q = lambda v: mp.mpf(v.numerator) / v.denominator  # noqa: E731
    for s, e, b, co in L.pieces:
        if (s is None or x >= q(s)) and (e is None or x <= q(e)):
            u = x - mp.mpf(b.numerator) / b.denominator
            return sum(mp.mpf(c.numerator) / c.denominator * u ** k for k, c in enumerate(co))
    raise AssertionError


def test_table_law_encloses_its_spline_its_derivative_f_over_x_and_G():
    mp.mp.dps = 40
    L = table_law(_table(), parse_exact("pi/6"))
    assert law_is_odd(L) and L.zeros_over_pi() == (Fraction(0),)
    with working_precision(128):
        a = arb(100)
        balls = BALLS + [arb("0.6", "0.01"), arb("0.9"), arb("-0.1", "0.06"), arb("0.05")]
        for X in balls:
            F, dF, Q = L.f(a, X), L.df(a, X), L.f_over_x(a, X)
            for x in _samples(X):
                assert _inside(F, _mp_spline(L, x))
                assert _inside(dF, mp.diff(lambda t: _mp_spline(L, t), x))
                q = _mp_spline(L, x) / x if x != 0 else mp.diff(lambda t: _mp_spline(L, t), mp.mpf(0))
                assert _inside(Q, q)
        for xs in ("0.3", "-0.5", "0.05", "0.7", "1e-3"):
            G = L.G(a, arb(127) / 10, arb(7) / 5, arb(xs))
            x = mp.mpf(xs)
            cuts = sorted({mp.mpf(0), x} | {mp.mpf(Fraction(v).numerator) / Fraction(v).denominator * (1 if x > 0 else -1)
                                             for v in POINTS if Fraction(v) < abs(Fraction(xs))})
            want = mp.quad(lambda s: mp.cos(s) * _mp_spline(L, s) / (mp.mpf(127) / 10 - mp.mpf(7) / 5 * mp.sin(s) ** 2),
                           cuts) * (1 if x > 0 else -1)
            assert _inside(G, want) and G.rad() < arb("1e-25") * (1 + abs(G)), xs
        # a ball across a knot: the mean-value step
        X = arb("0.1", "1e-6")
        G = L.G(a, arb(127) / 10, arb(7) / 5, X)
        assert G.rad() < arb("1e-3")
        for x in _samples(X, 3):
            want = mp.quad(lambda s: mp.cos(s) * _mp_spline(L, s) / (mp.mpf(127) / 10 - mp.mpf(7) / 5 * mp.sin(s) ** 2),
                           [0, mp.mpf("0.05"), mp.mpf("0.1"), x])
            assert _inside(G, want)


# ------------------------------------------------------------------------------------ bad models: exit 2, entry named

BAD = [
    ("expression without a table", "expression", "", "[moment] table"),
    ("a table with a built-in name", "sine", '[moment]\nf = "a*sin(x2)"\n', "[moment] table"),
    ("unknown law", "cubic", "", "'moment'"),
    ("f missing", "expression", '[moment]\nb = "1"\n', "missing f"),
    ("f not odd", "expression", '[moment]\nf = "a*sin(x2) + x2^2"\n', "[moment] f"),
    ("f(0) != 0 and not odd", "expression", '[moment]\nf = "a*cos(x2)"\n', "[moment] f"),
    ("f undefined at 0", "expression", '[moment]\nf = "a*sin(x2)/x2^2"\n', "f(0)"),
    ("f without x2", "expression", '[moment]\nf = "a"\n', "does not depend on x2"),
    ("f divides by x2 - x2", "expression", '[moment]\nf = "a*x2/(x2-x2)"\n',
     "f has no value for any x2: it divides by x2 - x2, which is exactly 0 for every x2"),
    ("f even, divides by x2 - x2", "expression", '[moment]\nf = "a*x2^2/(x2-x2)"\n', "divides by x2 - x2"),
    ("sqrt of a negative constant", "expression", '[moment]\nf = "a*x2*sqrt(-1)"\n',
     "sqrt(-1) has no real value: its argument is -1, certainly outside sqrt's domain x >= 0 (a constant)"),
    ("f identically 0", "expression", '[moment]\nf = "0*x2"\n',
     "f(x2) = 0 exactly for every x2 (it does not depend on x2): the method needs a restoring moment"),
    ("a pole inside x2*", "expression", '[moment]\nf = "a*x2/(1 - 4*x2^2)"\n',
     "f(1/2) has no value: it divides by 1 - 4*x2^2, which is exactly 0 at x2 = 1/2, inside |x2| <= x2* = pi/6"),
    ("unknown name in f", "expression", '[moment]\nf = "a*sin(x2) + c*x2"\n', "'c'"),
    ("unknown function", "expression", '[moment]\nf = "a*sinh(x2)"\n', "sinh"),
    ("eval attempt", "expression", '[moment]\nf = "__import__(\'os\')"\n', "[moment] f"),
    ("reserved parameter name", "expression", '[moment]\nf = "a*sin(x2)"\nsin = "1"\n', "[moment] sin"),
    ("parameter not a number", "expression", '[moment]\nf = "b*x2"\nb = "x2"\n', "[moment] b"),
    ("float in the table", "expression", '[moment]\nf = "b*x2"\nb = 0.1\n', "[moment] b"),
    ("table lengths", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "1"]\n', "[moment] f"),
    ("table not from 0", "table", '[moment]\nx2 = ["0.1", "0.3", "0.6"]\nf = ["1", "2", "3"]\n', "x2[1], f[1]"),
    ("table not increasing", "table", '[moment]\nx2 = ["0", "0.3", "0.3", "0.6"]\nf = ["0", "1", "2", "3"]\n', "x2[3] = 3/10"),
    ("table f(0) != 0", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["1", "2", "3"]\n', "x2[1], f[1]"),
    ("table f <= 0", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "1", "-2"]\n', "f[3] = -2"),
    ("table short of x2*", "table", '[moment]\nx2 = ["0", "0.3", "0.5"]\nf = ["0", "1", "2"]\n', "x2[3] = 1/2"),
    ("table bad number", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "1", "two"]\n', "f[3]"),
    ("table point with pi", "table", '[moment]\nx2 = ["0", "pi/12", "pi/6"]\nf = ["0", "1", "2"]\n',
     "x2[2] = 'pi/12': table points are exact rational numbers such as 1/12"),
    ("table value with a name", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "a/4", "a/2"]\n',
     "'a': write the value, not the name"),
    ("table linear interpolant", "table",
     '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "1", "2"]\ninterpolant = "linear"\n', "interpolant"),
    ("table unknown entry", "table", '[moment]\nx2 = ["0", "0.3", "0.6"]\nf = ["0", "1", "2"]\nb = "1"\n', "[moment] b"),
]


@pytest.mark.parametrize("case,moment,table,word", BAD, ids=[b[0] for b in BAD])
def test_a_bad_moment_law_is_exit_2_naming_the_entry(tmp_path, capsys, case, moment, table, word):
    path = tmp_path / "s.toml"
    path.write_text(scene_text(moment, table))
    code = cli.main(["prove", str(path), "--out", str(tmp_path / "out")])
    _, err = capsys.readouterr()
    assert code == 2, err
    assert word in err and "Traceback" not in err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_f_without_a_value_at_0_or_at_a_point_inside_x2_star_is_refused_and_f_with_one_is_not():
    """The input checks refuse f only where it certainly has no value for |x2| <= x2* (every a): a denominator
    that is an exact 0, sqrt/log certainly outside their domain; the domain's boundary (sqrt(0)), a ball merely
    containing 0, or a point beyond x2* is no reason."""
    xs = parse_exact("pi/6")
    for f, word in [("a*x2*sqrt(1/5 - x2^2)", "f(1/2) has no value: sqrt(1/5 - x2^2) has no real value: its "
                     "argument 1/5 - x2^2 is [-0.0500000 +/- 1e-12] at x2 = 1/2 (inside |x2| <= x2*"),
                    ("a*x2*sqrt(x2 - 1)", "f(0) has no value: sqrt(x2 - 1) has no real value"),
                    ("a*x2*log(x2^2)", "f(0) has no value: log(x2^2) has no real value"),
                    ("a*sin(x2)/x2", "f(0) has no value: it divides by x2, which is exactly 0 at x2 = 0"),
                    ("a*x2/(sin(x2) - sin(x2))", "f(0) has no value: it divides by sin(x2) - sin(x2), which is "
                     "exactly 0 at x2 = 0"),
                    ("x2*(b - b)^-1", "f has no value for any x2: it divides by b - b, which is exactly 0")]:
        with pytest.raises(ParameterError, match=re.escape(word)):
            expression_law({"f": f, "b": "2/7"} if "b" in f else {"f": f}, xs)
    for f, x2_star in [("a*x2*sqrt(1/4 - x2^2)", "0.5"), ("a*x2*sqrt(1/5 - x2^2)", "0.4"), ("a*x2 - a*x2", "pi/6"),
                       ("a*x2*log(1 + x2^2)", "pi/6"), ("a*x2/(2 + x2^2)", "pi/6"), ("a*x2/(1 - x2^2)", "pi/6")]:
        assert expression_law({"f": f}, parse_exact(x2_star)).expr.text == f


def test_a_pole_at_an_exact_rational_point_inside_x2_star_is_refused_and_one_beyond_it_is_not():
    xs = parse_exact("pi/6")
    with pytest.raises(ParameterError, match=re.escape("f(2/7) has no value: it divides by x2 - b, which is exactly "
                                                       "0 at x2 = 2/7, inside |x2| <= x2* = pi/6")):
        expression_law({"f": "a*x2*(x2 - b)^-2", "b": "2/7"}, xs)
    with pytest.raises(ParameterError, match=r"at x2 = 1/2, inside \|x2\| <= x2\* = 0.5"):
        expression_law({"f": "a*x2/(1 - 4*x2^2)"}, parse_exact("0.5"))
    with pytest.raises(ParameterError, match=r"f\(1/3\) has no value: it divides by 1 - 9\*x2\^2"):
        expression_law({"f": "a*x2/(1 - 9*x2^2)"}, xs)
    for f, x2_star in [("a*x2/(1 - 4*x2^2)", "0.49"), ("a*x2/(1 - 4*x2^2)", "pi/7"), ("a*x2/(3/10 - x2^2)", "pi/6"),
                       ("a*x2/(1 - 9*x2^2)", "0.33")]:
        assert expression_law({"f": f}, parse_exact(x2_star)).expr.text == f


def test_a_tiny_x2_star_tries_no_point_beyond_it():
    """x2* = 1e-30 is below every 2^-k tried (k <= 60): no second point is evaluated, so the pole at x2 = 2^-60,
    far beyond x2*, is not reported as "inside |x2| <= x2*" (it was, when 2^-60 was tried all the same)."""
    law = expression_law({"f": "a*x2/(x2^2 - b)", "b": f"1/{2 ** 120}"}, parse_exact("1e-30"))
    assert law.expr.text == "a*x2/(x2^2 - b)"


def test_a_constant_f_is_refused():
    for f in ("a*x2*(1 - 1)", "0*sin(x2)", "x2*0 + 0*x2^3"):
        with pytest.raises(ParameterError, match=re.escape("f(x2) = 0 exactly for every x2 (it does not depend on "
                                                           "x2): the method needs a restoring moment")):
            expression_law({"f": f}, parse_exact("pi/6"))


def test_a_bad_law_is_a_parameter_error_in_the_api():
    with pytest.raises(ParameterError, match=r"\[moment\] f"):
        prove_scene(parse_scene(scene_text("expression", '[moment]\nf = "exp(x2) - 1"\n')))


# ------------------------------------------------------------------------------------ the built-in laws as expressions

CHEAP = ["constants", "damping_condition", "vdot_nonpositive", "psi_test", "v_positive", "invariant_estimate",
         "equilibria"]


def _iv(q):
    return Fraction(q["lo"]), Fraction(q["hi"])


def _overlap(p, q):
    (a, b), (c, d) = _iv(p), _iv(q)
    return a <= d and c <= b


@pytest.mark.parametrize("builtin,formula", [("sine", "a*sin(x2)"), ("linear", "a*x2")])
def test_a_builtin_law_written_as_an_expression_gives_the_same_certificate(builtin, formula, monkeypatch):
    """The generic path (the fast path of recognised built-in forms switched off), claim by claim: the same ids
    and verdicts, overlapping quantities (agafonov2013, the cheap claims)."""
    monkeypatch.setattr(moment_scene, "FAST_PATHS", {})
    a = prove_scene(parse_scene(scene_text(builtin, claims=CHEAP))).to_json()
    b = prove_scene(parse_scene(scene_text("expression", f'[moment]\nf = "{formula}"\n', claims=CHEAP))).to_json()
    assert [(c["id"], c["status"]) for c in a["claims"]] == [(c["id"], c["status"]) for c in b["claims"]]
    assert all(c["status"] == "proved" for c in a["claims"])
    assert set(a["quantities"]) == set(b["quantities"])
    for k in a["quantities"]:
        assert _overlap(a["quantities"][k], b["quantities"][k]), k
    eq = lambda cert: [(e["x2"], e["case"], e["stability"], e["estimate"])  # noqa: E731
                       for c in cert["claims"] if c["id"] == "equilibria" for e in c["details"]["equilibria"]]
    assert eq(a) == eq(b)
    assert b["extra"]["moment"]["formula"] == f"f(x2) = {formula}"


def test_an_expression_that_is_a_builtin_law_takes_its_fast_path():
    """a*sin(x2) written in the scene is the SineMoment class: the certificate's claims and quantities are the
    built-in scene's, byte for byte; a*sin(x2) with a table parameter, or another spelling, is generic."""
    claims = ["constants", "v_positive", "vdot_nonpositive"]
    a = prove_scene(parse_scene(scene_text("sine", claims=claims))).to_json()
    b = prove_scene(parse_scene(scene_text("expression", '[moment]\nf = "sin(x2)*a"\n', claims=claims))).to_json()
    assert json.dumps(a["claims"]) == json.dumps(b["claims"]) and json.dumps(a["quantities"]) == json.dumps(b["quantities"])
    assert b["extra"]["moment"]["name"] == "sine"
    assert moment_scene.scene_moment_law("expression", {"f": "a*x2"}, parse_exact("pi/6")).name == "linear"
    assert moment_scene.scene_moment_law("expression", {"f": "b*sin(x2)", "b": "100"}, parse_exact("pi/6")).name \
        .startswith("expression")


# ------------------------------------------------------------------------------------ example scenes and the checker

@pytest.fixture(scope="module")
def cubic_cert():
    sc = load_scene(MOMENTS_DIR / "agafonov2013_sine_cubic.toml")
    sc = parse_scene(Path(MOMENTS_DIR / "agafonov2013_sine_cubic.toml").read_text().replace(
        "[moment]", '[claims]\nonly = ["constants", "vdot_nonpositive", "v_positive", "equilibria"]\n\n[moment]'))
    return json.loads(json.dumps(prove_scene(sc).to_json()))


def test_the_sine_cubic_scene_proves_and_the_checker_confirms_it(cubic_cert):
    assert cubic_cert["verdict"] == "proved"
    assert cubic_cert["scene"]["model"]["f"] == "a*sin(x2) + b*x2^3"
    rep = check_certificate(cubic_cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


@pytest.mark.slow
def test_the_checker_rebuilds_the_law_from_the_certificate(cubic_cert):
    """A certificate whose scene block carries another law is not confirmed (the law is the scene's, not the
    prover's): the stored pieces and quantities no longer hold for it."""
    bad = json.loads(json.dumps(cubic_cert))
    bad["scene"]["model"]["b"] = "40"
    rep = check_certificate(bad)
    assert not rep.ok


def test_the_checker_refuses_a_certificate_whose_law_is_not_odd(cubic_cert):
    worse = json.loads(json.dumps(cubic_cert))
    worse["scene"]["model"]["f"] = "a*sin(x2) + b*x2^2"
    rep = check_certificate(worse)
    assert not rep.ok and any(r.item == "scene" and not r.ok for r in rep.results)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["agafonov2013_sine_cubic", "agafonov2013_measured"])
def test_the_example_scenes_prove_and_are_confirmed(name):
    cert = json.loads(json.dumps(prove_scene(load_scene(MOMENTS_DIR / f"{name}.toml")).to_json()))
    assert cert["verdict"] == "proved"
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_the_measured_scene_proves_its_cheap_claims():
    text = (MOMENTS_DIR / "agafonov2013_measured.toml").read_text().replace(
        "[moment]", '[claims]\nonly = ["constants", "damping_condition", "v_positive", "equilibria"]\n\n[moment]')
    cert = json.loads(json.dumps(prove_scene(parse_scene(text)).to_json()))
    assert [c["status"] for c in cert["claims"]] == ["proved"] * 4
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_a_saturating_law_gets_its_maximum_M_at_0():
    """f = a c tanh(x2/c): M = f'(0) = a, attained at x2 = 0 (the Taylor form of q through 0 lets the branch and
    bound converge there); the law's q contains mpmath's on balls about and near 0."""
    text = (MOMENTS_DIR / "agafonov2013_saturating.toml").read_text().replace(
        "[moment]", '[claims]\nonly = ["constants", "v_positive"]\n\n[moment]')
    cert = json.loads(json.dumps(prove_scene(parse_scene(text)).to_json()))
    assert [c["status"] for c in cert["claims"]] == ["proved"] * 2
    lo, hi = _iv(cert["quantities"]["M"])
    assert lo <= 100 <= hi and hi - lo < Fraction(1, 10 ** 9)
    L = expression_law({"f": "a*c*tanh(x2/c)", "c": "0.3"})
    mp.mp.dps = 40
    A0, C0 = mp.mpf(127) / 10, mp.mpf(7) / 5

    def q(x):
        f = 30 * mp.tanh(x / mp.mpf("0.3"))
        G = mp.quad(lambda s: mp.cos(s) * 30 * mp.tanh(s / mp.mpf("0.3")) / (A0 - C0 * mp.sin(s) ** 2), [0, x])
        return f * f / (2 * (A0 - C0 * mp.sin(x) ** 2) * G)
    with working_precision(96):
        for X in (arb(0, "0.05"), arb("0.01", "1e-4"), arb("0.1", "1e-3"), arb("0.2"), arb("0.24"),
                  arb("0.1"), arb("0.05"), arb("0.02")):
            Q = L.q_closed(arb(100), arb(127) / 10, arb(7) / 5, X)
            assert Q is not None and (Q.rad() < 5 or not X.contains(0) and X.lower() > arb("0.05"))
            for x in _samples(X, 5):
                assert _inside(Q, q(x) if x != 0 else mp.mpf(100))


def test_the_saturating_laws_equilibria_are_confirmed_by_the_checker():
    """tanh of a wide ball from its ends (Arb's own gave +-3.8e4 on [-5.3, 5.3]): interval Newton decides the
    pieces of [-pi, pi] at the prover's and at the checker's precision alike."""
    with working_precision(64):
        t = expression_law({"f": "a*c*tanh(x2/c)", "c": "0.3"}).f(arb(1), arb(0, "1.6"))
        assert abs(t) <= arb("0.3")
    text = (MOMENTS_DIR / "agafonov2013_saturating.toml").read_text().replace(
        "[moment]", '[claims]\nonly = ["equilibria"]\n\n[moment]')
    cert = json.loads(json.dumps(prove_scene(parse_scene(text)).to_json()))
    assert cert["verdict"] == "proved"
    rep = check_certificate(cert)
    assert rep.ok, [r for r in rep.results if not r.ok]


def test_random_expression_laws_are_enclosed():
    """A few random odd polynomial-trigonometric laws: f and f' at random balls contain mpmath's values."""
    rng = random.Random(7)
    mp.mp.dps = 40
    for _ in range(6):
        c = [Fraction(rng.randint(1, 9), rng.randint(1, 9)) for _ in range(3)]
        L = expression_law({"f": "p*x2 + q*sin(x2)^3 + r*x2^3*cos(x2)", "p": str(c[0]), "q": str(c[1]), "r": str(c[2])})
        cm = [mp.mpf(v.numerator) / v.denominator for v in c]
        fm = lambda t: cm[0] * t + cm[1] * mp.sin(t) ** 3 + cm[2] * t ** 3 * mp.cos(t)  # noqa: E731
        with working_precision(96):
            for _ in range(4):
                X = arb(str(rng.uniform(-1, 1)), str(rng.uniform(0, 0.2)))
                F, dF = L.f(arb(1), X), L.df(arb(1), X)
                for x in _samples(X, 5):
                    assert _inside(F, fm(x)) and _inside(dF, mp.diff(fm, x))
