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

__all__ = ["scene_model", "settings_json", "task_scene", "MODEL_KEY"]

#: the key under which a scene's own model table ([plant], [system], [moment]) travels in a task's settings JSON
#: beside the kind's options (never an option name: those are identifiers)
MODEL_KEY = "[model]"


def settings_json(options: dict, model: dict | None = None) -> str:
    """The kind's options and the scene's model table, as the one JSON string a worker task receives."""
    return json.dumps({**options, **({MODEL_KEY: model} if model else {})}, sort_keys=True)


def task_scene(name: str, kind: str, source: str, parameters: dict, settings: str,
               claims_only: list[str] | None = None) -> Scene:
    """The Scene a worker builds from a task's strings (``settings`` from :func:`settings_json`)."""
    opts = json.loads(settings)
    model = opts.pop(MODEL_KEY, {})
    return Scene(name=name, kind=kind, source=source, parameters=parameters, claims_only=claims_only,
                 options=opts, model=model)


@functools.lru_cache(maxsize=8)
def scene_model(kind: str, points_json: str, options_json: str, mid_json: str):
    """The model of the scene with these point parameters and options, at the box's midpoint."""
    module = kind_module(kind)
    params = {**json.loads(points_json), **json.loads(mid_json)}
    return module.validate(task_scene("box", kind, "", params, options_json))
