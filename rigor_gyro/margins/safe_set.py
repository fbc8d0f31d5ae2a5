"""The safe set of a paving: where every selected claim holds at once, and its certified yield.

A paving decides each claim on the leaves of its own bisection tree of the box. All trees follow one
split rule (:meth:`~rigor_gyro.core.boxes.Box.split`: halve the relatively widest edge), so two leaves of
different claims are either nested or disjoint; the trees' common refinement tiles the box with pieces
on which every claim has one status. A piece is

* ``proved`` (safe) when every selected claim is proved on it: every instrument built with parameters
  in it meets all of them;
* ``refuted`` when some selected claim is refuted on it (fails at every point of it);
* ``undecided`` otherwise.

The **yield** is the probability that an instrument whose parameters are drawn from a tolerance
distribution meets every selected claim: certified to lie in [P(safe pieces), 1 - P(refuted pieces)].
Distributions, per parameter and independent: ``uniform`` on its tolerance interval, or ``normal K``:
a normal law centred at the interval's midpoint with standard deviation half-width / K, truncated to
the interval (K = 3: the interval is +-3 sigma, the usual reading of a tolerance).

Guarantee: for ``uniform`` the bounds are exact rationals (volume fractions); for ``normal`` they are
Arb enclosures (erf) at the working precision, and the decimals printed are rounded outward (the lower
bound down, the upper up). A leaf set that is not the leaves of one bisection tree of the box (which
the paving checker rejects) raises ValueError; nothing is guessed.

Cost: linear in the number of pieces of the refinement (at most the sum of the claims' leaf counts).
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from flint import arb

from ..core.balls import ball, decimal_bounds
from ..core.boxes import Box, fraction_text
from ..core.errors import ParameterError

__all__ = ["Law", "parse_laws", "common_refinement", "conjunction", "piece_probability", "yield_bounds",
           "safe_set"]

_STATUSES = ("proved", "refuted", "undecided")


@dataclass(frozen=True)
class Law:
    """A parameter's tolerance law: ``uniform`` (k is None) or a normal truncated to the interval, with
    standard deviation half-width / k."""

    k: Fraction | None = None

    def text(self) -> str:
        return "uniform" if self.k is None else f"normal, truncated at +-{self.k} sigma"


def parse_laws(text: str, names: tuple[str, ...]) -> dict[str, Law]:
    """The laws of ``names`` from an option text: ``"uniform"``, ``"normal 3"`` (every parameter), or
    per parameter ``"H: normal 3, B: uniform"`` (the others uniform). ParameterError names what is wrong."""
    def one(t: str, where: str) -> Law:
        words = t.split()
        if words == ["uniform"]:
            return Law()
        if len(words) == 2 and words[0] == "normal":
            try:
                k = Fraction(words[1])
            except (ValueError, ZeroDivisionError):
                k = None
            if k is not None and k > 0:
                return Law(k)
        raise ParameterError(f"tolerance law {t!r}{where}: write 'uniform' or 'normal K' with K > 0 "
                             "(the tolerance is +-K standard deviations)")
    text = text.strip()
    if ":" not in text:
        law = one(text, "")
        return {n: law for n in names}
    out = {n: Law() for n in names}
    for part in text.split(","):
        name, _, t = part.partition(":")
        name = name.strip()
        if name not in names:
            raise ParameterError(f"tolerance law for {name!r}: not a parameter with a tolerance ({', '.join(names)})")
        out[name] = one(t.strip(), f" for {name}")
    return out


def common_refinement(whole: Box, frozen: tuple[str, ...],
                      leaves: dict[str, list[tuple[Box, str]]]) -> list[tuple[Box, dict[str, str]]]:
    """The pieces of the claims' common refinement, each with every claim's status on it (see the module
    docstring); ValueError when a claim's leaves are not the leaves of one bisection tree of ``whole``."""
    index = {c: {b.edges: s for b, s in ls} for c, ls in leaves.items()}
    counts = {c: 0 for c in leaves}
    out: list[tuple[Box, dict[str, str]]] = []
    budget = 2 * sum(len(ls) for ls in leaves.values()) + 2
    stack: list[tuple[Box, dict[str, str]]] = [(whole, {})]
    while stack:
        node, known = stack.pop()
        budget -= 1
        if budget < 0:
            raise ValueError("the claims' leaves are not the leaves of one bisection tree of the box")
        known = dict(known)
        for c in leaves:
            if c not in known and node.edges in index[c]:
                known[c] = index[c][node.edges]
                counts[c] += 1
        if len(known) == len(leaves):
            out.append((node, known))
            continue
        if all(hi == lo for n, lo, hi in node.edges if n not in frozen):
            raise ValueError("the claims' leaves are not the leaves of one bisection tree of the box")
        left, right = node.split(whole, frozen)
        stack.extend([(right, known), (left, known)])          # left first: the pieces come in tree order
    if any(counts[c] != len(leaves[c]) for c in leaves):
        raise ValueError("a claim's leaves overlap or lie outside the box")
    return out


def conjunction(statuses: dict[str, str]) -> str:
    """The status of "every claim holds" from the claims' statuses on one piece."""
    if any(s == "refuted" for s in statuses.values()):
        return "refuted"
    if statuses and all(s == "proved" for s in statuses.values()):
        return "proved"
    return "undecided"


def _phi(x: arb) -> arb:
    """The standard normal distribution function, enclosed."""
    return (1 + (x / arb(2).sqrt()).erf()) / 2


def piece_probability(piece: Box, whole: Box, laws: dict[str, Law]) -> arb | Fraction:
    """P(parameters in ``piece``) under independent ``laws`` on ``whole``'s intervals: an exact Fraction
    when every law of an edge the piece cuts is uniform, otherwise a ball."""
    exact, prod = Fraction(1), None
    for name, lo, hi in piece.edges:
        wlo, whi = whole.interval(name)
        if (lo, hi) == (wlo, whi):
            continue
        law = laws.get(name, Law())
        if law.k is None:
            exact *= (hi - lo) / (whi - wlo)
            continue
        mid, sigma = ball((wlo + whi) / 2), ball((whi - wlo) / 2) / ball(law.k)
        z = lambda v: (ball(v) - mid) / sigma
        part = (_phi(z(hi)) - _phi(z(lo))) / (_phi(z(whi)) - _phi(z(wlo)))
        prod = part if prod is None else prod * part
    return exact if prod is None else prod * ball(exact)


def yield_bounds(pieces: list[tuple[Box, str]], whole: Box, laws: dict[str, Law]) -> dict[str, object]:
    """{"lower", "upper"} (decimal strings, outward; exact fractions too when every law is uniform) and the
    undecided probability, for pieces labelled proved/refuted/undecided."""
    mass = {s: Fraction(0) for s in _STATUSES}
    balls = {s: arb(0) for s in _STATUSES}
    inexact = False
    for box, status in pieces:
        p = piece_probability(box, whole, laws)
        if isinstance(p, Fraction):
            mass[status] += p
        else:
            balls[status] += p
            inexact = True
    if not inexact:
        lo, hi = mass["proved"], 1 - mass["refuted"]
        return {"lower": _dec(ball(lo), "down"), "upper": _dec(ball(hi), "up"), "lower_exact": fraction_text(lo),
                "upper_exact": fraction_text(hi), "exact": True}
    # the pieces partition the box, so P(safe) = 1 - P(failing) - P(undecided): each bound is taken from
    # whichever side is enclosed tighter (with no failing or undecided piece the lower bound is 1 exactly)
    p = {st: balls[st] + ball(mass[st]) for st in _STATUSES}
    lo = _dec(p["proved"], "down")
    rest = p["refuted"] + p["undecided"]
    if mass["refuted"] == mass["undecided"] == 0 and not any(st != "proved" for _, st in pieces):
        lo = "1"
    else:
        lo = max(lo, _dec(1 - rest, "down"), key=Fraction)
    hi = min(_dec(1 - p["refuted"], "up"), _dec(p["proved"] + p["undecided"], "up"), key=Fraction)
    if not any(st == "refuted" for _, st in pieces):
        hi = "1"
    return {"lower": lo, "upper": hi, "exact": False}


def _dec(x: arb, side: str) -> str:
    """x's lower (side "down") or upper end as an outward decimal of 6 significant digits, clamped to [0, 1]."""
    lo, hi = decimal_bounds(x, 6)
    v = lo if side == "down" else hi
    q = Fraction(v)
    if q < 0:
        return "0"
    if q > 1:
        return "1"
    return v


def safe_set(whole: Box, frozen: tuple[str, ...], leaves: dict[str, list[tuple[Box, str]]],
             laws: dict[str, Law]) -> dict[str, object]:
    """The safe set of ``leaves``' claims and its yield: {"claims", "pieces": [(box, status)], "counts",
    "volume" (uniform yield), "yield" (under ``laws``), "laws"}; see the module docstring."""
    refined = common_refinement(whole, frozen, leaves)
    pieces = [(b, conjunction(st)) for b, st in refined]
    counts = {s: sum(1 for _, x in pieces if x == s) for s in _STATUSES}
    uniform = {n: Law() for n in whole.names}
    return {"claims": list(leaves), "pieces": pieces, "counts": counts,
            "volume": yield_bounds(pieces, whole, uniform), "yield": yield_bounds(pieces, whole, laws),
            "laws": {n: laws.get(n, Law()).text() for n in whole.names}}


def from_paving(data: dict, claims: list[str] | None = None, laws_text: str = "uniform") -> dict[str, object]:
    """:func:`safe_set` of a paving certificate (schema ``rigor-gyro/paving/1``, as written by ``prove``):
    of ``claims`` (default: every claim it paves) under the laws of ``laws_text`` (:func:`parse_laws`).
    Check the paving first (``rigor-gyro check``): this reads its leaves as they are."""
    whole = Box.from_json(data["box"])
    frozen = tuple(data.get("settings", {}).get("unsplit", ()))
    by_id = {c["id"]: c for c in data["claims"]}
    claims = list(claims or by_id)
    unknown = [c for c in claims if c not in by_id]
    if unknown:
        raise ParameterError(f"claims {unknown} are not paved here (paved: {', '.join(by_id)})")
    leaves = {c: [(Box.from_json(b["box"]), b["status"]) for b in by_id[c]["boxes"]] for c in claims}
    return safe_set(whole, frozen, leaves, parse_laws(laws_text, whole.names))
