"""The scene block of an output (a point certificate, a paving, threshold, scan or curve) that names a built-in scene.

A block whose ``file`` is ``builtin:NAME`` must be the scene NAME as this version ships it, field for field
(name, source, parameters, options, claims, model; the ``[paper]`` table when the block carries one): a reader
takes such an output for one about the shipped scene. A scene edited through the API names no file
(:meth:`rigor_gyro.scene.Scene.header`), and a scene file names its own path (not compared: the file may
have moved).

Fails when: never raises; :func:`builtin_differs` returns what is wrong, or None.
"""
from __future__ import annotations

import json
from typing import Any

__all__ = ["builtin_differs"]


def builtin_differs(block: Any, paper: bool | None = None) -> str | None:
    """What is wrong with a scene block that says ``builtin:NAME`` but is not that shipped scene, or None.
    ``paper``: whether the shipped scene's header has its ``[paper]`` table (a point certificate's always
    does); None: as the block does."""
    where = block.get("file") if isinstance(block, dict) else None
    if not (isinstance(where, str) and where.startswith("builtin:")):
        return None
    from ..scene import builtin_scenes, load_scene
    name = where[len("builtin:"):]
    if name not in builtin_scenes("all"):
        return f"the scene says it is the built-in {name!r}, which this version does not ship"
    header = json.loads(json.dumps(load_scene(name).header(paper=("paper" in block) if paper is None else paper)))
    differ = sorted(k for k in set(header) | set(block) if header.get(k) != block.get(k))
    if differ:
        return (f"the scene says it is the built-in {name!r} but differs from it in {differ}: an output of an edited "
                "scene names its own file")
    return None
