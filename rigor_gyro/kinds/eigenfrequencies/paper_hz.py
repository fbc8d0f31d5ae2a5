"""Rudenko (1976): the paper's own chain for every number it prints in Hz (issue 39).

The paper never prints its Hz scale sqrt(K3/A3)/(2 pi). Its four 'exact' values admit no common scale
at the printed eps = 0.1076 and one at eps = 0.1073 (:func:`.paper_scale.consistent_eps`): that scale
interval, [lo, hi] certified, is the paper's Hz scale here, the same for every Hz row (it is no hull of
mutually inconsistent ranges, which would make two 'exact' values reproduce themselves by construction).

A bracket or approximation row's chain is scale * sqrt(f(P)) over the paper's printed inputs P: a, b,
eps, Omega^2 each the interval of its printed rounding (:func:`input_box`), f the formula in the reading
the model uses, enclosed over that box in centred form (:func:`rigor_gyro.core.centred_forms.enclose`,
derivatives by forward-mode AD in balls; a naive interval evaluation of these cancelling formulas is
twenty times wider). An 'exact' row's chain is omega_j at the eps reading times the scales the *other
three* 'exact' values share there (leave one out: a value is never its own evidence).

Guarantee: each chain is an Arb enclosure of the set it names (the outer hull of the scale interval
times the square root of a ball containing f over the input box). Failure mode: a formula with no real
value on the input box, or a scale interval that is not certain, gives no chain (the row keeps its exact
reference only). Precision: the working precision.
"""
from __future__ import annotations

from fractions import Fraction

from flint import arb

from ...core.audit import half_unit
from ...core.balls import certainly_lt, certainly_positive, decimal_bounds
from ...core.boxes import Box
from ...core.centred_forms import enclose
from ...core.paper_chain import Chain
from .model import NotReal, Params
from .paper_scale import ScaleReading, fit_scales

__all__ = ["input_box", "hz_chain", "exact_chain", "RUDENKO_SLACK", "READ_FORMULAS", "DERIVED_READINGS", "WINDOW_READINGS",
           "derived_row"]

#: the author's own rounding beyond the chain, in units of the print's last digit: the prints that agree
#: with the exact value (39.5, 43.4, 514, 922, 923.5) are correct roundings; the arithmetic rows reproduced
#: by a chain sit within one unit of it (40.6 against 40.69, 513.4 against [513.48, 513.63])
RUDENKO_SLACK = 1

NAMES = ("a", "b", "eps", "Omega2")


def _fmt(x: arb, n: int = 7) -> str:
    lo, hi = decimal_bounds(x, n)
    return f"[{lo}, {hi}]"


def input_box(model) -> Box:
    """a, b, eps, Omega^2 as printed, each the interval of its rounding (exact for a text that is not a
    plain decimal, e.g. a fraction)."""
    edges = []
    for k in NAMES:
        ex = getattr(model, k)
        q = ex.rational
        try:
            h = half_unit(ex.text) if ex.text and "/" not in ex.text else Fraction(0)
        except (ValueError, ArithmeticError):
            h = Fraction(0)
        edges.append((k, q - h, q + h))
    return Box(tuple(edges))


def _over_box(f, box: Box) -> arb | None:
    """f(Params) over the box: the centred enclosure (None where it cannot enclose)."""
    def g(d):
        try:
            return f(Params(*(d[k] for k in NAMES)))
        except NotReal:
            return None
    enc = enclose(g, box)
    return None if enc is None or not enc.value.is_finite() else enc.value


def hz_chain(f, box: Box, scale: ScaleReading, what: str, eps_text: str) -> Chain | None:
    """The chain of a Hz row: scale * sqrt(f) over the printed inputs (module docstring)."""
    v = _over_box(f, box)
    if v is None or not certainly_positive(v):
        return None
    val = scale.outer() * v.sqrt()
    return Chain(val, f"{what} from the printed a, b, eps = {eps_text}, Omega^2 (each within its rounding) times "
                      f"the Hz scale {_fmt(scale.outer())} that the four 'exact' values share at eps = {scale.text}",
                 slack=RUDENKO_SLACK)


def exact_chain(j: int, exact: list[str], scale: ScaleReading) -> tuple[Chain, str] | None:
    """The chain of the 'exact' value j: omega_j at eps = scale.text times the scales the other three
    'exact' values share there (leave one out); with the text of those scales. None when the other three
    do not certainly share a scale (cannot happen when all four do, but checked)."""
    others = [(x, w) for i, (x, w) in enumerate(zip(exact, scale.omegas)) if i != j - 1]
    got = fit_scales([x for x, _ in others], [w for _, w in others])
    if got is None:
        return None
    lo, hi = got
    if not certainly_lt(lo, hi):
        return None
    s = lo.union(hi)
    val = s * scale.omegas[j - 1].sqrt()
    src = (f"omega_{j} at eps = {scale.text} (the reading under which the four 'exact' values share one scale) "
           f"times the scales {_fmt(s)} the other three 'exact' values share there")
    return Chain(val, src, slack=0), _fmt(s)


#: the readings of :data:`.model.BRACKETS` as formula text (Python syntax over a, b, eps, W = Omega2), for the
#: edit search widened to two edits of the print (one edit of the reading); tests: each text evaluates to
#: its reading's function
READ_FORMULAS: dict[tuple[str, int], tuple[str, dict[str, str]]] = {
    ("upper", 1): ("R - sqrt(R**2 - eps*W/((a-b)*L*b**2))",
                   {"L": "(b*(b-1) + eps)/(b*(b-1))", "R": "(eps*a/(b*(a-b) + (a-1)*eps) + W/(L*b**2))/2"}),
    ("lower", 2): ("1/(b-1) + (D+R1)/2 - sqrt(((D+R1)/2)**2 + R1*(1/(b-1) - eps*a/(b*(a-b))))",
                   {"D": "eps/(b*(b-1))", "R1": "a*b**2/((a-b)*(b-1)*W)"}),
    ("lower", 3): ("b/(b-1) + (D+R2)/2 - sqrt((D+R2)**2/4 + R2*(1 - eps/(b-1)))",
                   {"D": "eps/(b*(b-1))", "R2": "W*(b-1)/b*(b/(b-1) - eps/(a-b))/(b/(b-1) - eps*a/(b*(a-b)))"}),
    ("upper", 3): ("(1+eps)/(b-1) + eps**2*(a-1)/((a-b)*(a-b+eps*(a-1))) + (b-eps)/(b + sqrt(W*(b-1)*b))", {}),
    ("lower", 4): ("b/(b-1) + (D+R2)/2 + sqrt((D+R2)**2/4 + R2*(1 - eps/(b-1)))",
                   {"D": "eps/(b*(b-1))", "R2": "W*(b-1)/b*(b/(b-1) - eps/(a-b))/(b/(b-1) - eps*a/(b*(a-b)))"}),
}


# ----------------------------------------------------------------------------- readings of the derivation

def _linear_8(p: Params):
    """(8)'s lower bound in its linear form: the branch factor (omega - nu2^+)/(nu3 - omega) kept and the rest
    of F replaced by the constant C = a b^2/((a-b)(b-1)) = R1 Omega^2 of (8), i.e. Omega^2 = C (omega -
    nu2^+)/(nu3 - omega): omega = (nu3 + R1 nu2^+)/(1 + R1), (8)'s quadratic without its x^2 term and with D
    read as 1 (x = omega - nu3)."""
    a, b, e, W = p
    r1 = a * b * b / ((a - b) * (b - 1) * W)
    return (1 / (b - 1) + r1 * (e * a / (b * (a - b)))) / (1 + r1)


def _upper_9_nu4m(p: Params):
    """(9)'s upper bound with nu4^- = (1+eps)/(b-1) for its first two terms (the correction term left out)
    and b (nu5 - nu4^-) = b (1 - eps/(b-1)) for the printed numerator b - eps (nu5 - nu4^- as in (9)'s lower
    bound as read)."""
    a, b, e, W = p
    return (1 + e) / (b - 1) + b * (1 - e / (b - 1)) / (b + (W * (b - 1) * b).sqrt())


def _upper_10_eps1(p: Params):
    """(10)'s upper bound with eps (not eps^2) in R3's correction term eps^2 a (a-1)/(b (a-b)((a-b) b + eps (a-1))):
    the exponent the paper prints in (9)'s upper bound for the same correction of nu4^+."""
    a, b, e, W = p
    r3 = (e / (b * (b - 1)) + e * a * (a - 1) / (b * (a - b) * ((a - b) * b + e * (a - 1))) + W) / 2
    return b / (b - 1) + r3 + (r3 * r3 + W).sqrt()


#: readings accepted when the print lies in the reading's chain window (the chain over the printed inputs times
#: the scale hull; the class then says ``propagated``), where the point test at the scale hull straddles a
#: rounding boundary: their evidence is the paper's own print of the same term elsewhere
WINDOW_READINGS: dict[tuple[str, int], tuple[str, object]] = {
    ("upper", 4): ("(10)'s upper bound with eps for eps^2 in R3's correction term eps^2 a (a-1)/(b (a-b)((a-b) b + "
                   "eps (a-1))): the exponent the paper prints for the same correction of nu4^+ in (9)'s upper "
                   "bound (one of the two single edits of (10) that reproduce the print)", _upper_10_eps1),
}


#: readings of a printed bound found from the derivation's intermediate forms (the branch factor kept, the
#: rest of F a constant; the factors of the other bounds), each stated in its row only where an Arb
#: enclosure of it times the paper's scale is a correct rounding of the print; they are readings of the
#: paper's arithmetic, not the bounds the claims prove
DERIVED_READINGS: dict[tuple[str, int], tuple[str, object]] = {
    ("lower", 2): ("(8)'s lower bound in its linear form omega = (nu3 + R1 nu2^+)/(1 + R1), i.e. Omega^2 = "
                   "R1 Omega^2 (omega - nu2^+)/(nu3 - omega): the rest of F replaced by the constant a b^2/((a-b)(b-1)) "
                   "of R1, (8)'s quadratic without its x^2 term and with D read as 1", _linear_8),
    ("upper", 3): ("(9)'s upper bound with nu4^- = (1+eps)/(b-1) for its first two terms (the correction "
                   "eps (a-1)/(...) left out) and b (1 - eps/(b-1)) = b (nu5 - nu4^-) for the printed numerator "
                   "b - eps", _upper_9_nu4m),
}


def derived_row(row, key: tuple[str, int], printed: str, box: Box, scale: ScaleReading, eps_text: str,
                exact_params: Params, eps_reading: Params) -> bool:
    """Where :data:`DERIVED_READINGS` has a reading of this row and its Arb enclosure times the paper's scale
    (the hull) is certainly a correct rounding of the print, at the printed parameters or at the eps reading of
    the 'exact' values: the row's chain becomes that reading over the printed inputs and its note says so.
    Returns whether it did. Precision: the working precision; the decision is audit_printed's."""
    from ...core.audit import audit_printed
    from ...core.outcome import AuditStatus
    if key in WINDOW_READINGS:
        return _window_row(row, key, printed, box, scale, eps_text)
    if key not in DERIVED_READINGS:
        return False
    text, f = DERIVED_READINGS[key]
    found = []
    for where, p in ((f"the printed eps = {eps_text}", exact_params), (f"eps = {scale.text}", eps_reading)):
        try:
            v = f(p)
        except (NotReal, ZeroDivisionError):
            continue
        if not certainly_positive(v):
            continue
        hz = scale.outer() * v.sqrt()
        found.append((where, hz, audit_printed(printed, hz)[0] is AuditStatus.AGREES))
    if not any(ok for _, _, ok in found):
        return False
    ch = hz_chain(f, box, scale, f"the reading: {text},", eps_text)
    if ch is None:
        return False
    row.propagated = ch
    parts = [f"at {w}: {_fmt(hz)} Hz ({'a correct rounding' if ok else 'not a correct rounding'})" for w, hz, ok in found]
    row.note += (f"; {printed} Hz is {text}: " + "; ".join(parts) + f" (times the Hz scale {_fmt(scale.outer())}); "
                 "a reading of the paper's arithmetic found from the derivation's intermediate forms, not the bound "
                 "the claims prove")
    return True


def _window_row(row, key, printed: str, box: Box, scale: ScaleReading, eps_text: str) -> bool:
    """A :data:`WINDOW_READINGS` reading becomes the row's chain when the print lies in its window at slack 0
    (:func:`rigor_gyro.core.chain_classify.decide` says ``propagated``) and not in the window of the chain the
    row already has (the model's reading): the reading explains the print where the model's does not."""
    from ...core.chain_classify import decide
    text, f = WINDOW_READINGS[key]
    ch = hz_chain(f, box, scale, f"the reading: {text},", eps_text)
    if ch is None or decide(printed.strip(), ch)[0] != "propagated":
        return False
    old = row.propagated if isinstance(row.propagated, Chain) else None
    if old is not None and decide(printed.strip(), old)[0] in ("propagated", "last-digit"):
        return False
    row.propagated = ch
    row.note += (f"; {printed} Hz lies in the chain of {text}: {_fmt(ch.value)} Hz over the printed inputs times the Hz "
                 f"scale {_fmt(scale.outer())} (a correct rounding for part of it, not certainly for all: the "
                 "reading's evidence is the paper's own print of that term in (9)); a reading of the paper's "
                 "arithmetic, not the bound the claims prove")
    return True


#: what was tried on the Hz prints that no chain reproduces (issue 39), for their rows' notes
TRIED = ("tried: the formula as printed and as read, with every single edit and every pair of single edits (two "
         "edits: none reproduces 130.4; for 128 only three implausible pairs, e.g. 'a divides' with 'a - b -> a + "
         "b'), the derivation's intermediate forms, the chain at eps = 0.1076 and 0.1073 over the printed inputs "
         "within their rounding, one- and two-digit edits, transpositions and decimal shifts of one or two of a, b, "
         "eps, Omega^2 (explored in floats: coincidences for the 3-digit 128 alone, none natural), and unit slips "
         "(2 pi, rad/s, omega without its square root: factors of 2.5 and more, far from the ~2 % gaps)")


def shared_scale_note(prints: list[tuple[str, arb]], scale: ScaleReading) -> str | None:
    """Whether the prints (each with a ball containing the value it should be the Hz of, in omega) are
    certainly correct roundings at one common Hz scale, and that scale against the paper's: a note (None when
    no common scale is certain). The intersection is certified with :func:`.paper_scale.fit_scales`."""
    got = fit_scales([x for x, _ in prints], [w for _, w in prints])
    if got is None:
        return None
    lo, hi = got
    if not certainly_lt(lo, hi):
        return None
    rel = (lo.union(hi) / scale.outer() - 1) * 100
    return (f"the prints {', '.join(x for x, _ in prints)} are correct roundings at one common Hz scale, "
            f"{_fmt(lo.union(hi))} (certified), {_fmt(rel, 3)} % from the scale {_fmt(scale.outer())} of the 'exact' "
            "values: both omega_2 prints look computed with another Hz factor (or another omega_2 than the formulas "
            "give) by the same ~2 %; no reading of it found")
