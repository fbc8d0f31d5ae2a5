"""The kind's model of a box scene's midpoint, built once per worker process (a small cache).

The tasks of :mod:`.paving` and :mod:`.ranges` run in workers that receive strings (the point parameters,
the options and the box's midpoint as JSON); each builds the model with the kind's ``validate`` and
reuses it for the next boxes of the same scene.

Fails when: the kind's ``validate`` raises (ParameterError), which the caller reports as bad input.
"""
from __future__ import annotations

import functools
import json

from ..kinds import kind_module
from ..scene import Scene

__all__ = ["scene_model"]


@functools.lru_cache(maxsize=8)
def scene_model(kind: str, points_json: str, options_json: str, mid_json: str):
    """The model of the scene with these point parameters and options, at the box's midpoint."""
    module = kind_module(kind)
    params = {**json.loads(points_json), **json.loads(mid_json)}
    return module.validate(Scene(name="box", kind=kind, source="", parameters=params,
                                 options=json.loads(options_json)))
