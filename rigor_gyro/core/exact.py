"""Exact parameters: decimal strings parsed to rationals (times a power of pi).

Every number that a certificate is a theorem about enters here. ``parse_exact("15.08")`` is the
rational 1508/100 exactly; ``parse_exact("pi/6")`` is (1/6) * pi, with pi kept symbolic until a ball
is asked for at the working precision.

Guarantee: ``Exact.rational`` and ``Exact.pi_power`` represent the written number exactly; no binary
rounding happens before :meth:`Exact.ball`, which returns an Arb ball that contains the exact value at
the current precision (``flint.ctx.prec``).

Requires: a ``str`` (decimal, scientific, fraction, or a product/quotient of those and ``pi``, with
one optional leading sign; ASCII digits; spaces only around ``*`` and ``/``), an ``int``, a
``fractions.Fraction`` or a ``flint.fmpq``. Limits, checked before any arithmetic: at most
:data:`MAX_DIGITS` digits per number, decimal exponents within +-:data:`MAX_EXPONENT`, at most
:data:`MAX_FACTORS` factors, and a nonzero value of magnitude within 10^+-:data:`MAX_MAGNITUDE`.

Fails when: given a ``float`` (it is already rounded; pass the decimal string you mean), a string
outside the grammar or beyond the limits: :class:`ParameterError` naming the parameter.

Example:
    >>> parse_exact("15.08").rational
    Fraction(377, 25)
    >>> parse_exact("0.5*pi").pi_power, parse_exact("0.5*pi").rational
    (1, Fraction(1, 2))
    >>> parse_exact(0.1, name="eps")
    Traceback (most recent call last):
    ...
    rigor_gyro.core.errors.ParameterError: parameter 'eps': got the float 0.1, which is already rounded to binary; write it as a string, e.g. "0.1"
"""
from __future__ import annotations

import difflib
import re
from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from .errors import ParameterError

__all__ = ["Exact", "parse_exact", "to_fmpq", "parse_parameters", "parse_options", "option_number",
           "option_count", "require_rational", "MAX_DIGITS", "MAX_EXPONENT", "MAX_FACTORS", "MAX_MAGNITUDE"]

_NUMBER = re.compile(r"^([0-9]+(?:\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?$", re.ASCII)


@dataclass(frozen=True)
class Exact:
    """The exact real number ``rational * pi**pi_power``, with the text it was written as."""

    rational: Fraction
    pi_power: int = 0
    text: str = ""

    def ball(self) -> arb:
        """An Arb ball containing the exact value, at the current working precision."""
        q = arb(fmpq(self.rational.numerator, self.rational.denominator))
        return q * arb.pi() ** self.pi_power if self.pi_power else q

    def fmpq(self) -> fmpq:
        """The value as an exact ``fmpq``; raises ParameterError if it involves pi."""
        if self.pi_power:
            raise ParameterError(f"{self.text!r} involves pi and is not rational")
        return fmpq(self.rational.numerator, self.rational.denominator)

    @property
    def is_rational(self) -> bool:
        return self.pi_power == 0

    def __str__(self) -> str:
        return self.text


#: limits on what an exact number may be, checked before any arithmetic (a ten-character string
#: must not be able to hang the parser or the proof): digits of one written number, its decimal
#: exponent, the number of factors in a product, and the magnitude of the value
MAX_DIGITS = 1000
MAX_EXPONENT = 400
MAX_FACTORS = 8
MAX_MAGNITUDE = 300          # a nonzero value must lie in 10^-300 <= |x| <= 10^300


def _factor(token: str, name: str | None, whole: str) -> tuple[Fraction, int]:
    if token == "pi":
        return Fraction(1), 1
    m = _NUMBER.match(token)
    if not m:
        raise ParameterError(_where(name) + f"cannot read {whole!r} as an exact number ({token!r} is not a "
                             "number; use forms like 15.08, 1e4, 2/15, -3, pi/6, 0.5*pi, ASCII digits, no spaces "
                             "inside a number)")
    mantissa, exponent = m.group(1), m.group(2)
    digits = sum(ch.isdigit() for ch in mantissa)
    if digits > MAX_DIGITS:
        raise ParameterError(_where(name) + f"{whole!r}: a number may have at most {MAX_DIGITS} digits "
                             f"(this one has {digits})")
    exp_digits = exponent.lstrip("eE+-").lstrip("0") if exponent is not None else ""
    if len(exp_digits) > len(str(MAX_EXPONENT)) or (exp_digits and int(exp_digits) > MAX_EXPONENT):
        raise ParameterError(_where(name) + f"{whole!r}: the decimal exponent must lie in "
                             f"[-{MAX_EXPONENT}, {MAX_EXPONENT}]")
    return Fraction(token), 0


def _where(name: str | None) -> str:
    return f"parameter {name!r}: " if name else ""


def _check_magnitude(q: Fraction, name: str | None, whole: str) -> None:
    if q == 0:
        return
    a = abs(q)
    big, small = Fraction(10) ** MAX_MAGNITUDE, Fraction(1, 10 ** MAX_MAGNITUDE)
    if a > big or a < small:
        raise ParameterError(_where(name) + f"{whole!r}: a nonzero exact number must have magnitude between "
                             f"1e-{MAX_MAGNITUDE} and 1e{MAX_MAGNITUDE}")


def parse_exact(value: object, name: str | None = None) -> Exact:
    """Parse ``value`` exactly. See the module docstring for the grammar, the limits and the guarantee."""
    if isinstance(value, Exact):
        return value
    if isinstance(value, bool):
        raise ParameterError(_where(name) + f"got the boolean {value!r}; expected a number")
    if isinstance(value, float):
        raise ParameterError(_where(name) + f"got the float {value!r}, which is already rounded to "
                             f"binary; write it as a string, e.g. \"{value!r}\"")
    if isinstance(value, int):
        if value.bit_length() > 4 * MAX_DIGITS:
            raise ParameterError(_where(name) + f"integer with more than {MAX_DIGITS} digits")
        _check_magnitude(Fraction(value), name, str(value))
        return Exact(Fraction(value), 0, str(value))
    if isinstance(value, Fraction):
        _check_magnitude(value, name, str(value))
        return Exact(value, 0, str(value))
    if isinstance(value, fmpq):
        q = Fraction(int(value.p), int(value.q))
        _check_magnitude(q, name, str(value))
        return Exact(q, 0, str(value))
    if not isinstance(value, str):
        raise ParameterError(_where(name) + f"expected a string such as \"15.08\", got {type(value).__name__}")
    text = value.strip()
    if not text:
        raise ParameterError(_where(name) + "is empty")
    if len(text) > 4 * MAX_DIGITS:
        raise ParameterError(_where(name) + f"is {len(text)} characters long; an exact number has at most "
                             f"{MAX_DIGITS} digits")
    body = text
    sign = 1
    if body[0] in "+-":
        sign = -1 if body[0] == "-" else 1
        body = body[1:].lstrip()
    # A product/quotient of factors: a*b/c*d ... (spaces allowed around the operators only)
    parts = [s.strip() for s in re.split(r"([*/])", body)]
    if len(parts) > 2 * MAX_FACTORS - 1:
        raise ParameterError(_where(name) + f"{value!r}: at most {MAX_FACTORS} factors")
    rational, pi_power = Fraction(sign), 0
    op = "*"
    for i, part in enumerate(parts):
        if i % 2:
            op = part
            continue
        q, k = _factor(part, name, text)
        if op == "*":
            rational, pi_power = rational * q, pi_power + k
        else:
            if q == 0:
                raise ParameterError(_where(name) + f"division by zero in {value!r}")
            rational, pi_power = rational / q, pi_power - k
    if pi_power not in (0, 1):
        raise ParameterError(_where(name) + f"{value!r}: only rationals and rational multiples of pi are supported")
    _check_magnitude(rational, name, text)
    return Exact(rational, pi_power, text)


def to_fmpq(value: object, name: str | None = None) -> fmpq:
    """Parse ``value`` with :func:`parse_exact` and return it as an ``fmpq``; a multiple of pi is a
    ParameterError naming ``name``."""
    exact = parse_exact(value, name)
    if not exact.is_rational:
        raise ParameterError(_where(name) + f"{exact.text!r} involves pi; expected a rational number")
    return exact.fmpq()


def _did_you_mean(word: str, choices) -> str:
    close = difflib.get_close_matches(word, [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def parse_parameters(given: dict, kind: str, known, required, text_keys=()) -> dict[str, Exact]:
    """The parameters of a scene of ``kind``: names checked against ``known`` (unknown ones, with a
    did-you-mean, and missing ``required`` ones are a ParameterError listing them), every value but
    ``text_keys`` parsed exactly (use :func:`require_rational` for the ones that must be rational)."""
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ParameterError(f"unknown parameter(s) {unknown}{_did_you_mean(unknown[0], known)} for kind {kind!r}; "
                             f"expected {list(known)}")
    missing = [k for k in required if k not in given]
    if missing:
        raise ParameterError(f"missing parameter(s) {missing} for kind {kind!r}")
    return {k: parse_exact(given[k], k) for k in given if k not in text_keys}


def parse_options(given: dict, defaults: dict[str, str], kind: str) -> dict[str, str]:
    """The options of a scene of ``kind`` as strings, defaults filled in; an unknown option is a
    ParameterError with a did-you-mean, a value that is not a string or an integer names the option."""
    unknown = sorted(set(given) - set(defaults))
    if unknown:
        raise ParameterError(f"unknown option(s) {unknown}{_did_you_mean(unknown[0], defaults)}; kind {kind!r} "
                             f"has {list(defaults)}")
    out = dict(defaults)
    for k, v in given.items():
        if isinstance(v, bool) or not isinstance(v, (str, int)):
            raise ParameterError(f"option {k!r}: expected a quoted value such as \"{defaults[k] or '...'}\", got {v!r}")
        out[k] = str(v)
    return out


def option_number(text: str, name: str, *, above: object = None, at_most: object = None) -> Exact:
    """The option ``name`` as an exact rational with ``above < value <= at_most`` (bounds optional);
    ParameterError naming the option and the range otherwise."""
    x = parse_exact(text, name)
    lo = None if above is None else parse_exact(above).rational
    hi = None if at_most is None else parse_exact(at_most).rational
    ok = x.is_rational and (lo is None or x.rational > lo) and (hi is None or x.rational <= hi)
    if not ok:
        rng = (f"{above} < {name}" if above is not None else name) + (f" <= {at_most}" if at_most is not None else "")
        raise ParameterError(f"option {name!r} = {text!r}: need a rational number with {rng}")
    return x


def option_count(text: str, name: str, lo: int, hi: int) -> int:
    """The option ``name`` as an integer in [lo, hi]; ParameterError naming it otherwise."""
    if not re.fullmatch(r"[0-9]{1,9}", text.strip(), re.ASCII) or not lo <= int(text) <= hi:
        raise ParameterError(f"option {name!r} = {text!r}: need an integer from {lo} to {hi}")
    return int(text)


def require_rational(values: dict[str, Exact], names=None) -> None:
    """ParameterError naming the first parameter (of ``names``, default all) that involves pi."""
    for k, x in values.items():
        if (names is None or k in names) and not x.is_rational:
            raise ParameterError(f"parameter {k!r}: must be rational (got {x.text!r})")

