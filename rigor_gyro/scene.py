"""Scenes are data: TOML files naming a model kind, its exact parameters, the claims, the paper.

A scene is found by built-in name (``rigor-gyro list``) or by path. Loading checks the file's shape
(required keys, known kind, parameters written as exact strings or integers); the kind's module then
checks the model's domain. Only the module of the scene's kind is imported.

File format::

    name = "rudenko1976"
    kind = "eigenfrequencies"
    source = "..."
    [parameters]        # strings (or integers): "15.08", "1e4", "2/15", "pi/6"; never floats
    a = "15.08"
    [claims]            # optional
    only = ["roots", "brackets"]
    [options]           # optional, kind-specific
    [paper]             # optional: numbers printed in the source, for the audit table

Fails when: the file is missing or not TOML, a key is missing, a parameter is a float, the kind is
unknown: :class:`SceneError` / :class:`ParameterError` naming what to change (CLI exit status 2).
"""
from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from .core.errors import ParameterError, SceneError
from .kinds import KINDS, PLANNED_KINDS

__all__ = ["Scene", "load_scene", "builtin_scenes", "parse_scene"]


@dataclass
class Scene:
    """A parsed scene file. ``parameters`` keep the exact strings as written."""

    name: str
    kind: str
    source: str
    parameters: dict[str, str]
    claims_only: list[str] | None = None
    options: dict[str, Any] = field(default_factory=dict)
    paper: dict[str, Any] = field(default_factory=dict)
    path: str | None = None

    def header(self) -> dict[str, Any]:
        """The ``scene`` block of a certificate."""
        return {"name": self.name, "kind": self.kind, "source": self.source,
                "parameters": dict(self.parameters), "file": self.path}


def _builtin_dir():
    return resources.files("rigor_gyro") / "scenes"


def builtin_scenes() -> dict[str, Any]:
    """Built-in scene name -> resource (a TOML file shipped inside the package)."""
    out = {}
    for entry in sorted(_builtin_dir().iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            out[entry.name[:-5]] = entry
    return out


def load_scene(ref: str) -> Scene:
    """Load a scene by built-in name or by path to a TOML file."""
    builtins = builtin_scenes()
    if ref in builtins:
        text, where = builtins[ref].read_text(encoding="utf-8"), f"builtin:{ref}"
    else:
        path = Path(ref)
        if not path.is_file():
            raise SceneError(f"no scene {ref!r}: not a built-in scene (see `rigor-gyro list`: "
                             f"{', '.join(builtins)}) and not a file")
        text, where = path.read_text(encoding="utf-8"), str(path)
    return parse_scene(text, where)


def parse_scene(text: str, where: str = "<string>") -> Scene:
    """Parse the TOML text of a scene; see the module docstring for the format."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"{where}: not valid TOML: {e}") from None
    for key in ("name", "kind", "parameters"):
        if key not in data:
            raise SceneError(f"{where}: missing top-level key {key!r}")
    kind = data["kind"]
    if kind not in KINDS:
        hint = " (planned, not in this version)" if kind in PLANNED_KINDS else ""
        raise SceneError(f"{where}: unknown kind {kind!r}{hint}; known kinds: {', '.join(KINDS)}")
    params_raw = data["parameters"]
    if not isinstance(params_raw, dict):
        raise SceneError(f"{where}: [parameters] must be a table")
    params: dict[str, str] = {}
    for k, v in params_raw.items():
        if isinstance(v, bool) or not isinstance(v, (str, int)):
            if isinstance(v, float):
                raise ParameterError(f"parameter {k!r}: written as the TOML float {v!r}, which is "
                                     f"rounded to binary; quote it: {k} = \"{v!r}\"")
            raise ParameterError(f"parameter {k!r}: expected a quoted exact number, got {v!r}")
        params[k] = str(v)
    claims = data.get("claims", {})
    only = claims.get("only") if isinstance(claims, dict) else None
    if only is not None and (not isinstance(only, list) or not all(isinstance(c, str) for c in only)):
        raise SceneError(f"{where}: [claims] only must be a list of claim names")
    return Scene(name=str(data["name"]), kind=kind, source=str(data.get("source", "")),
                 parameters=params, claims_only=only, options=dict(data.get("options", {})),
                 paper=dict(data.get("paper", {})), path=where)

