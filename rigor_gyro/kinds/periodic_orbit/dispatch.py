"""Which model a ``periodic_orbit`` scene writes: the paper's parameterisation of Roitenberg's stabiliser
(:mod:`.claims`, the fast specialised path) or the user's own relay plant in a ``[plant]`` table
(:mod:`.plant_claims`, issue 42). The kind's ``validate``, ``attempt`` and ``statements`` are these: each
hands the scene or model to the path it belongs to and adds nothing.

Guarantee: a scene without a ``[plant]`` table goes exactly where it went before (certificates unchanged).
Fails when: as the path's own functions (ParameterError for bad input).
"""
from __future__ import annotations

from . import claims, plant_claims
from .plant_model import PlantModel

__all__ = ["validate", "attempt", "statements"]


def validate(scene):
    """The model of the scene: a PlantModel when it has a [plant] table, else the paper's RelayModel."""
    if getattr(scene, "model", None):
        return plant_claims.validate(scene)
    return claims.validate(scene)


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
