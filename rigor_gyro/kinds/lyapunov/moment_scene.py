"""Which moment law a ``lyapunov`` scene writes: a built-in one by name (``moment = "sine"`` or ``"linear"``:
the specialised classes of :mod:`.moments`, the fast path, unchanged) or the user's own in a ``[moment]`` table
(issue 42): ``moment = "expression"`` (:mod:`.moment_expr`) or ``moment = "table"`` (:mod:`.moment_table`).

Guarantee: a scene without a ``[moment]`` table gets exactly the built-in law it names (certificates unchanged);
an expression that is exactly a built-in law (:data:`FAST_PATHS`: ``a*sin(x2)``, ``a*x2``) gets that law's class.
Fails when: the name and the table do not match, or the table is unusable: ParameterError naming the parameter
or the table's entry (exit 2).
"""
from __future__ import annotations

from typing import Mapping

from ...core.errors import ParameterError
from ...core.exact import Exact
from .moments import MOMENTS, MomentLaw

__all__ = ["USER_LAWS", "KNOWN", "FAST_PATHS", "scene_moment_law"]

#: expressions that are a built-in law exactly (as parsed trees, no parameters of the table): the specialised class
#: is used for them, the fast path (``a*sin(x2)`` gets SineMoment's closed forms of G and q); the generic path
#: gives the same verdicts and overlapping enclosures (tests/test_moment_expr.py) at about twice the cost
FAST_PATHS = {("*", ("name", "a"), ("call", "sin", (("name", "x2"),))): "sine",
              ("*", ("call", "sin", (("name", "x2"),)), ("name", "a")): "sine",
              ("*", ("name", "a"), ("name", "x2")): "linear",
              ("*", ("name", "x2"), ("name", "a")): "linear"}

#: the names of the laws a [moment] table defines
USER_LAWS = ("expression", "table")
KNOWN = sorted(MOMENTS) + list(USER_LAWS)


def scene_moment_law(moment: object, table: Mapping[str, object] | None, x2_star: Exact) -> MomentLaw:
    """The law of the scene's parameter ``moment`` and its ``[moment]`` table (empty or None: none given)."""
    table = dict(table or {})
    if not isinstance(moment, str) or moment not in KNOWN:
        raise ParameterError(f"parameter 'moment' = {moment!r}: unknown moment law; known: {KNOWN}")
    if moment in MOMENTS:
        if table:
            raise ParameterError(f"parameter 'moment' = {moment!r} is a built-in law, but the scene has a [moment] "
                                 "table: write moment = \"expression\" (f a formula) or \"table\" (measured points)")
        return MOMENTS[moment]
    if not table:
        raise ParameterError(f"parameter 'moment' = {moment!r} needs a [moment] table "
                             + ("with f = \"...\" (a formula in x2)" if moment == "expression" else
                                "with x2 = [...] and f = [...] (measured points)"))
    if moment == "expression":
        from .moment_expr import expression_law
        law = expression_law(table, x2_star)
        fast = FAST_PATHS.get(law.expr.tree) if not law.params else None
        return MOMENTS[fast] if fast else law
    from .moment_table import table_law
    return table_law(table, x2_star)
