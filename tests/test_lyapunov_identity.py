"""Exact symbolic proof that Vdot = grad V . f of (7) along (2) equals -Psi1 x1^2 - Psi2 x3^2 with the
coefficients of rigor_gyro.kinds.lyapunov.model.Gimbal.psi_coefficients (the form every Lyapunov claim rests on),
and that the printed (8) does not: sympy, with sin x2 = s, cos x2 = c reduced modulo s^2 + c^2 - 1,
f, f' and F kept as independent symbols (F' = f3 by definition). The formulas below are checked
against the library's ball evaluation at sample points, so the symbolic identity is about the code."""
import pytest
from flint import arb, fmpq

sympy = pytest.importorskip("sympy")
from sympy import Rational, symbols  # noqa: E402

from rigor_gyro.core.balls import working_precision  # noqa: E402
from rigor_gyro.core.exact import parse_exact  # noqa: E402
from rigor_gyro.kinds.lyapunov.model import Gimbal  # noqa: E402
from rigor_gyro.kinds.lyapunov.moments import MOMENTS  # noqa: E402

A0, B0, C0, H, k, mu = symbols("A0 B0 C0 H k mu", positive=True)
x1, x3, s, c, f, fp, F = symbols("x1 x3 s c f fp F")


def model():
    D = A0 - C0 * s ** 2
    f1, f2, f3 = k / D, H ** 2 * c ** 2 / (D * B0), H * c * f / (D * B0)
    V = mu * F + x3 * f3 + f2 * x3 ** 2 / 2 + mu * f1 * x3 ** 2 / 2 + mu * H / B0 * c * x1 * x3 \
        + H ** 2 / (2 * B0 ** 2) * c ** 2 * x1 ** 2
    s2 = 2 * s * c
    rhs1 = (C0 * s2 * x1 * x3 - H * c * x3 - k * x1 - f) / D
    rhs3 = (-C0 * s2 * x1 ** 2 / 2 + H * c * x1) / B0

    def d_dx2(e):  # chain rule: s' = c, c' = -s, f' = fp, F' = f3 (fp'' never appears in V)
        return sympy.diff(e, s) * c - sympy.diff(e, c) * s + sympy.diff(e, f) * fp + sympy.diff(e, F) * f3
    vdot = sympy.diff(V, x1) * rhs1 + d_dx2(V) * x3 + sympy.diff(V, x3) * rhs3
    return D, vdot


def psi_form(D, printed=False):
    P = A0 - C0 - C0 * c ** 2
    c10 = H ** 2 * c ** 2 / B0 ** 2 * (k / D - mu) + C0 * H * c ** 2 * s * f / (D * B0 ** 2)
    c11 = mu * H * C0 * s * c ** 2 / B0 ** 2
    c13 = (mu * k * B0 * C0 + (A0 - C0) * H ** 2) * s * c / (D * B0 ** 2)
    c20 = mu * H ** 2 * c ** 2 / (B0 * D) - H * c * fp / (B0 * D) + H * P * s * f / (B0 * D ** 2)
    c21 = mu * H * P * s / (B0 * D)
    c23 = ((A0 - C0) * H ** 2 - mu * k * B0 * C0) * (2 * s * c if printed else s * c) / (B0 * D ** 2)
    return (c10, c11, c13), (c20, c21, c23)


def reduce_trig(expr):
    num, _ = sympy.fraction(sympy.together(expr))
    _, r = sympy.reduced(sympy.expand(num), [c ** 2 + s ** 2 - 1], c, s)
    return sympy.expand(r)


def test_vdot_equals_the_derived_psi_form_exactly():
    D, vdot = model()
    (c10, c11, c13), (c20, c21, c23) = psi_form(D)
    form = -(c10 + c11 * x1 + c13 * x3) * x1 ** 2 - (c20 + c21 * x1 + c23 * x3) * x3 ** 2
    assert reduce_trig(vdot - form) == 0


def test_printed_form_8_differs_only_in_the_x3_term_of_psi2():
    D, vdot = model()
    (c10, c11, c13), (c20, c21, c23) = psi_form(D, printed=True)
    form = -(c10 + c11 * x1 + c13 * x3) * x1 ** 2 - (c20 + c21 * x1 + c23 * x3) * x3 ** 2
    diff = reduce_trig(vdot - form)
    assert diff != 0
    # the difference is exactly the halved coefficient times x3^3
    (_, _, _), (_, _, c23_true) = psi_form(D)
    assert reduce_trig(vdot - form - c23_true * x3 ** 3) == 0


@pytest.mark.parametrize("law", sorted(MOMENTS))
def test_the_formulas_above_are_the_librarys(law):
    """The symbolic psi_form is what Gimbal.psi_coefficients computes (at sample x2, in balls)."""
    g = Gimbal(fmpq(127, 10), fmpq(42, 10), fmpq(14, 10), fmpq(10000), fmpq(4, 10), fmpq(100), fmpq(1, 50),
               parse_exact("pi/6"), MOMENTS[law])
    with working_precision(128):
        for x2s in ("0.1", "0.4", "-0.5"):
            x2 = arb(x2s)
            subs = {A0: Rational(127, 10), B0: Rational(42, 10), C0: Rational(14, 10), H: 10000, k: Rational(4, 10),
                    mu: Rational(1, 50), s: sympy.sin(sympy.Rational(x2s)), c: sympy.cos(sympy.Rational(x2s)),
                    f: sympy.Float(float(g.f(x2).mid()), 20), fp: sympy.Float(float(g.df(x2).mid()), 20)}
            D = A0 - C0 * s ** 2
            sym = psi_form(D)
            lib = g.psi_coefficients(x2)
            for i in range(2):
                for j in range(3):
                    want = float(sym[i][j].subs(subs).evalf(30))
                    got = float(lib[i][j].mid())
                    assert abs(got - want) <= 1e-12 * max(1.0, abs(want)), (i, j, got, want)


def test_section_2_first_approximation_identities():
    """Exact (sympy, with x2 a symbol and f = a x2 + O(x2^3), F = int f3): the Jacobian of (2) at 0 is the
    printed (4); the second-order part of (7) is (5) with the x2 x3 coefficient a H/(A0 B0) (printed with a
    spurious 1/2); its derivative along (4) is -(H^2/(A0 B0^2))(k - A0 mu) x1^2 - (H/(A0 B0))(mu H - a) x3^2
    (printed without the 1/B0^2); with the printed (5) a cross term in x1 x2 remains. These are the readings
    the audit rows of rigor_gyro.kinds.lyapunov.paper.linear_section_rows report."""
    a, x2, t = symbols("a x2 t")
    Cc = symbols("Cc", positive=True)                  # C0 in this test (C0 is taken above)
    D = A0 - Cc * sympy.sin(x2) ** 2
    fx = a * sympy.sin(x2)                             # f'(0) = a; any odd law gives the same second order
    f3 = H * sympy.cos(x2) * fx / (D * B0)
    F = sympy.integrate(sympy.series(f3, x2, 0, 4).removeO(), x2)
    V = mu * F + x3 * f3 + H ** 2 * sympy.cos(x2) ** 2 / (D * B0) * x3 ** 2 / 2 + mu * k / D * x3 ** 2 / 2 \
        + mu * H / B0 * sympy.cos(x2) * x1 * x3 + H ** 2 / (2 * B0 ** 2) * sympy.cos(x2) ** 2 * x1 ** 2
    rhs = [(Cc * sympy.sin(2 * x2) * x1 * x3 - H * sympy.cos(x2) * x3 - k * x1 - fx) / D, x3,
           (-Cc * sympy.sin(2 * x2) * x1 ** 2 / 2 + H * sympy.cos(x2) * x1) / B0]
    X = [x1, x2, x3]
    J = sympy.Matrix([[sympy.diff(r, v).subs({x1: 0, x2: 0, x3: 0}) for v in X] for r in rhs])
    assert sympy.simplify(J - sympy.Matrix([[-k / A0, -a / A0, -H / A0], [0, 0, 1], [H / B0, 0, 0]])) == sympy.zeros(3)
    quad = sympy.expand(sympy.series(V.subs({x1: t * x1, x2: t * x2, x3: t * x3}), t, 0, 3).removeO().coeff(t, 2))
    assert sympy.simplify(quad.coeff(x2, 1).coeff(x3, 1) - a * H / (A0 * B0)) == 0
    Vlin = quad
    vdot = sympy.expand(sum(sympy.diff(Vlin, v) * r for v, r in zip(X, (J * sympy.Matrix(X)))))
    expected = -(H ** 2 / (A0 * B0 ** 2)) * (k - A0 * mu) * x1 ** 2 - (H / (A0 * B0)) * (mu * H - a) * x3 ** 2
    assert sympy.simplify(vdot - expected) == 0
    printed5 = Vlin - (a * H / (2 * A0 * B0)) * x2 * x3
    vdot5 = sympy.expand(sum(sympy.diff(printed5, v) * r for v, r in zip(X, (J * sympy.Matrix(X)))))
    assert sympy.simplify(vdot5.coeff(x1, 1).coeff(x2, 1)) != 0
