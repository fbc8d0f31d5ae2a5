"""Which model a ``periodic_orbit`` scene writes: the paper's parameterisation of Roitenberg's stabiliser
(:mod:`.claims`, the fast specialised path) or the user's own relay plant in a ``[plant]`` table
(:mod:`.plant_claims`, issue 42). The kind's ``validate``, ``attempt`` and ``statements`` are these: each
hands the scene or model to the path it belongs to and adds nothing.

Guarantee: a scene without a ``[plant]`` table goes exactly where it went before (certificates unchanged).
Fails when: as the path's own functions (ParameterError for bad input).
"""
from __future__ import annotations

from ...core.errors import ParameterError
from . import claims, plant_claims
from .plant_model import PlantModel

__all__ = ["validate", "attempt", "statements"]


def validate(scene):
    """The model of the scene: a PlantModel when it has a [plant] table, else the paper's RelayModel. An empty
    [plant] table (the scene keeps it as an empty dict, like no table) is refused as such when the scene's file
    shows it; otherwise a refusal of the paper's model adds that a [plant] table needs M, e and c."""
    if getattr(scene, "model", None):
        return plant_claims.validate(scene)
    if _empty_plant_table(getattr(scene, "path", None)):
        raise ParameterError("the [plant] table is empty: give M, e and c (and optionally S, h); without a [plant] "
                             "table the scene is Roitenberg's parameterisation")
    try:
        return claims.validate(scene)
    except ParameterError as e:
        if "missing parameter" in str(e):
            raise ParameterError(f"{e} (or write your own relay plant in a [plant] table with M, e and c)") from None
        raise


def _empty_plant_table(path) -> bool:
    """Whether the scene file at ``path`` (when it is one) has a [plant] table with nothing in it."""
    if not isinstance(path, str) or not path.endswith(".toml"):
        return False
    try:
        import tomllib
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except (OSError, ValueError):
        return False
    return isinstance(data.get("plant"), dict) and not data["plant"]


def attempt(model, wanted: list[str], prec: int, spectrum=None):
    if isinstance(model, PlantModel):
        if spectrum is not None:
            raise TypeError("a [plant] model is proved at a point: no box spectrum")
        return plant_claims.attempt(model, wanted, prec)
    return claims.attempt(model, wanted, prec, spectrum=spectrum)


def statements(model) -> dict[str, str]:
    if isinstance(model, PlantModel):
        return plant_claims.statements(model)
    return claims.statements(model)
