"""Exact parameters: decimal strings parsed to rationals (times a power of pi).

Every number that a certificate is a theorem about enters here. ``parse_exact("15.08")`` is the
rational 1508/100 exactly; ``parse_exact("pi/6")`` is (1/6) * pi, with pi kept symbolic until a ball
is asked for at the working precision.

Guarantee: ``Exact.rational`` and ``Exact.pi_power`` represent the written number exactly; no binary
rounding happens before :meth:`Exact.ball`, which returns an Arb ball that contains the exact value at
the current precision (``flint.ctx.prec``).

Requires: a ``str`` (decimal, scientific, fraction, or a product/quotient of those and ``pi``), an
``int``, a ``fractions.Fraction`` or a ``flint.fmpq``.

Fails when: given a ``float`` (it is already rounded; pass the decimal string you mean) or a string
outside the grammar; both raise :class:`ParameterError` naming the parameter.

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

import re
from dataclasses import dataclass
from fractions import Fraction

from flint import arb, fmpq

from .errors import ParameterError

__all__ = ["Exact", "parse_exact", "to_fmpq"]

_NUMBER = re.compile(r"^(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?$")


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


def _factor(token: str, name: str | None) -> tuple[Fraction, int]:
    token = token.strip()
    if token == "pi":
        return Fraction(1), 1
    if not _NUMBER.match(token):
        raise ParameterError(_where(name) + f"cannot read {token!r} as an exact number "
                             "(use forms like 15.08, 1e4, 2/15, -3, pi/6, 0.5*pi)")
    return Fraction(token), 0


def _where(name: str | None) -> str:
    return f"parameter {name!r}: " if name else ""


def parse_exact(value: object, name: str | None = None) -> Exact:
    """Parse ``value`` exactly. See the module docstring for the grammar and the guarantee."""
    if isinstance(value, Exact):
        return value
    if isinstance(value, bool):
        raise ParameterError(_where(name) + f"got the boolean {value!r}; expected a number")
    if isinstance(value, float):
        raise ParameterError(_where(name) + f"got the float {value!r}, which is already rounded to "
                             f"binary; write it as a string, e.g. \"{value!r}\"")
    if isinstance(value, int):
        return Exact(Fraction(value), 0, str(value))
    if isinstance(value, Fraction):
        return Exact(value, 0, str(value))
    if isinstance(value, fmpq):
        return Exact(Fraction(int(value.p), int(value.q)), 0, str(value))
    if not isinstance(value, str):
        raise ParameterError(_where(name) + f"expected a string such as \"15.08\", got {type(value).__name__}")
    text = value.strip().replace(" ", "")
    if not text:
        raise ParameterError(_where(name) + "is empty")
    sign = 1
    body = text
    while body[:1] in "+-":
        if body[0] == "-":
            sign = -sign
        body = body[1:]
    # A product/quotient of factors: a*b/c*d ...
    parts = re.split(r"([*/])", body)
    rational, pi_power = Fraction(sign), 0
    op = "*"
    for part in parts:
        if part in ("*", "/"):
            op = part
            continue
        q, k = _factor(part, name)
        if op == "*":
            rational, pi_power = rational * q, pi_power + k
        else:
            if q == 0:
                raise ParameterError(_where(name) + f"division by zero in {value!r}")
            rational, pi_power = rational / q, pi_power - k
    if pi_power not in (0, 1):
        raise ParameterError(_where(name) + f"{value!r}: only rationals and rational multiples of pi are supported")
    return Exact(rational, pi_power, value.strip())


def to_fmpq(value: object, name: str | None = None) -> fmpq:
    """Parse ``value`` with :func:`parse_exact` and return it as an ``fmpq`` (rational only)."""
    return parse_exact(value, name).fmpq()


def parse_parameters(given: dict, kind: str, known, required, text_keys=()) -> dict[str, Exact]:
    """The parameters of a scene of ``kind``: names checked against ``known`` (unknown ones and
    missing ``required`` ones are a ParameterError listing them), every value but ``text_keys``
    parsed exactly (use :func:`require_rational` for the ones that must be rational)."""
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ParameterError(f"unknown parameter(s) {unknown} for kind {kind!r}; expected {list(known)}")
    missing = [k for k in required if k not in given]
    if missing:
        raise ParameterError(f"missing parameter(s) {missing} for kind {kind!r}")
    return {k: parse_exact(given[k], k) for k in given if k not in text_keys}


def require_rational(values: dict[str, Exact], names=None) -> None:
    """ParameterError naming the first parameter (of ``names``, default all) that involves pi."""
    for k, x in values.items():
        if (names is None or k in names) and not x.is_rational:
            raise ParameterError(f"parameter {k!r}: must be rational (got {x.text!r})")

