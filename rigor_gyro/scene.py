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
    [plant] / [system] / [moment]   # optional, one per kind (MODEL_TABLES): the user's own model,
                        # entries strings (or lists of rows of strings); the kind parses and checks it

Fails when: the file is missing, unreadable, not UTF-8 or not TOML; a key is missing or unknown (with a
did-you-mean); the name is not a safe file stem; a section is not a table; a number is a TOML float (in
any section); the kind is unknown; ``[claims] only`` is empty: :class:`SceneError` /
:class:`ParameterError` naming what to change (CLI exit status 2).
"""
from __future__ import annotations

import difflib
import functools
import os
import re
import stat
import tomllib
from dataclasses import dataclass, field, replace
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
    #: the kind's model table (``[plant]``, ``[system]`` or ``[moment]``, see MODEL_TABLES), as written;
    #: empty for the papers' built-in parameterisations
    model: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        """The shape every scene has, however it was made (file or API): SceneError otherwise."""
        check_name(self.name, self.path or "scene")
        for label, value, kind in (("parameters", self.parameters, dict), ("options", self.options, dict),
                                   ("paper", self.paper, dict), ("source", self.source, str),
                                   ("model", self.model, dict),
                                   ("kind", self.kind, str)):
            if not isinstance(value, kind):
                raise SceneError(f"scene {self.name!r}: {label} must be a {kind.__name__}, got {type(value).__name__}")
        if not all(isinstance(k, str) for k in self.parameters):
            raise SceneError(f"scene {self.name!r}: parameter names must be strings")
        if self.claims_only is not None and (not isinstance(self.claims_only, list) or not self.claims_only
                                             or not all(isinstance(c, str) for c in self.claims_only)):
            raise SceneError(f"scene {self.name!r}: claims_only must be None or a non-empty list of claim names")

    def is_shipped(self) -> bool:
        """False for a scene whose ``path`` says ``builtin:NAME`` but which is not the built-in NAME as this
        version ships it (edited through the API): its certificate then names no file, so that no reader takes
        it for one about the shipped scene (the checker refuses a block that names a built-in and differs)."""
        if not (isinstance(self.path, str) and self.path.startswith("builtin:")):
            return True
        shipped = _shipped(self.path[len("builtin:"):])
        return shipped is not None and replace(shipped, path=None) == replace(self, path=None)

    @classmethod
    def from_header(cls, sc: dict[str, Any]) -> "Scene":
        """The scene a certificate's ``scene`` block (:meth:`header`) describes (its ``[paper]`` table when
        the block carries one). KeyError, TypeError or SceneError when the block is malformed."""
        return cls(name=sc["name"], kind=sc["kind"], source=sc.get("source", ""), parameters=dict(sc["parameters"]),
                   claims_only=sc.get("claims_only"), options=dict(sc.get("options") or {}),
                   paper=dict(sc.get("paper") or {}), path=sc.get("file"), model=dict(sc.get("model") or {}))

    def header(self, paper: bool = False) -> dict[str, Any]:
        """The ``scene`` block of a certificate: everything the result depends on (parameters exactly as
        written, the options and the claims asked for), so two certificates of different settings differ;
        with ``paper``, also the ``[paper]`` table (a point certificate's audit and its escalation depend on
        it, and the checker re-derives them from it)."""
        out = {"name": self.name, "kind": self.kind, "source": self.source,
               "parameters": dict(self.parameters),
               "options": {k: (v if isinstance(v, (str, int)) else str(v)) for k, v in self.options.items()},
               "claims_only": list(self.claims_only) if self.claims_only is not None else None,
               "file": self.path if self.is_shipped() else None}
        if self.model:
            out["model"] = self.model
        if paper and self.paper:
            out["paper"] = dict(self.paper)
        return out


@functools.lru_cache(maxsize=None)
def _shipped(name: str) -> "Scene | None":
    """The built-in scene ``name`` as shipped (None if there is none); shared: never edit it."""
    ref = builtin_scenes("all").get(name)
    return None if ref is None else parse_scene(ref.read_text(encoding="utf-8"), f"builtin:{name}")


def _builtin_dir():
    return resources.files("rigor_gyro") / "scenes"


#: groups of built-in scenes: the papers' worked examples (``prove --all``), demonstrations of
#: refuted and inconclusive outcomes (planted; ``prove --group demo``), and design margins and the
#: papers' general claims over parameter boxes (pavings; ``prove --group margin``), the stiff and
#: extreme catalog (``prove --group stress``; ``rigor-gyro bench --stress`` tabulates it), and users' own
#: relay plants written as ``[plant]`` tables (``prove --group plant``)
GROUPS = {"paper": "", "demo": "demos", "margin": "margins", "stress": "stress", "plant": "plants", "moment": "moments"}


def builtin_scenes(group: str = "paper") -> dict[str, Any]:
    """Built-in scene name -> resource (a TOML file shipped inside the package), for one group
    (``paper``: the worked examples, what ``prove --all`` proves; ``demo``; ``margin``; ``stress``;
    ``all``: every group)."""
    if group == "all":
        out: dict[str, Any] = {}
        for g in GROUPS:
            out.update(builtin_scenes(g))
        return out
    if group not in GROUPS:
        raise SceneError(f"unknown scene group {group!r}; groups: {', '.join(GROUPS)}, all")
    folder = _builtin_dir() / GROUPS[group] if GROUPS[group] else _builtin_dir()
    out = {}
    for entry in sorted(folder.iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            out[entry.name[:-5]] = entry
    return out


#: the top-level keys and tables a scene file may have
#: the table in which a scene of each kind may write its own model (issue 42): the kind's module parses it
MODEL_TABLES = {"periodic_orbit": "plant", "eigenfrequencies": "system", "lyapunov": "moment"}
TOP_LEVEL = ("name", "kind", "source", "parameters", "claims", "options", "paper", *MODEL_TABLES.values())
#: a scene name is also the stem of its output files: a safe character set and a length limit
NAME_PATTERN = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,99}$", re.ASCII)
MAX_SCENE_BYTES = 1_000_000


def _did_you_mean(word: str, choices) -> str:
    close = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def check_name(name: object, where: str = "scene") -> str:
    """The scene name, checked: letters, digits, '_', '.', '-', starting with a letter or digit, at most
    100 characters (it names the output files, which must stay inside the output folder)."""
    if (not isinstance(name, str) or not NAME_PATTERN.match(name) or ".." in name
            or name.lower().endswith(".timings")):
        shown = name if not isinstance(name, str) or len(name) < 60 else name[:60] + "..."
        raise SceneError(f"{where}: name = {shown!r} is not allowed: use 1-100 characters from A-Z a-z 0-9 _ . -, "
                         "starting with a letter or digit, without '..' and not ending in '.timings' (the name is "
                         "the output files' stem)")
    return name


def load_scene(ref: str) -> Scene:
    """Load a scene by built-in name or by path to a TOML file."""
    if not isinstance(ref, (str, os.PathLike)):
        raise SceneError(f"a scene is a built-in name or a path, got {type(ref).__name__}")
    ref = os.fspath(ref)
    builtins = builtin_scenes("all")
    if ref in builtins:
        text, where = builtins[ref].read_text(encoding="utf-8"), f"builtin:{ref}"
    else:
        _check_path(ref, builtins)
        path = Path(ref)
        try:
            if path.stat().st_size > MAX_SCENE_BYTES:
                raise SceneError(f"{ref}: larger than {MAX_SCENE_BYTES} bytes: not a scene file")
            text, where = path.read_bytes().decode("utf-8"), ref
        except UnicodeDecodeError as e:
            raise SceneError(f"{ref}: not UTF-8 text ({e.reason} at byte {e.start}): save the scene as UTF-8") from None
        except OSError as e:
            raise SceneError(f"{ref}: cannot be read ({e.strerror or e})") from None
    return parse_scene(text, where)


def _check_path(ref: str, builtins) -> None:
    """SceneError unless ``ref`` names a regular file, saying what it is instead (no such file, a
    directory, a FIFO or device: never opened, so a FIFO cannot block); the message starts with the path."""
    shown = ref if len(ref) <= 200 else ref[:200] + "..."
    try:
        st = os.stat(ref)
    except FileNotFoundError:
        looks_like_path = os.sep in ref or "/" in ref or ref.endswith(".toml")
        if looks_like_path:
            raise SceneError(f"{shown}: no such file") from None
        raise SceneError(f"{shown}: no such file, and not a built-in scene{_did_you_mean(ref, builtins)} "
                         "(`rigor-gyro list` names them)") from None
    except (OSError, ValueError) as e:
        raise SceneError(f"{shown}: not a usable path ({getattr(e, 'strerror', None) or e})") from None
    if stat.S_ISDIR(st.st_mode):
        raise SceneError(f"{shown}: is a directory: give a scene file (a .toml) or a built-in scene name")
    if not stat.S_ISREG(st.st_mode):
        raise SceneError(f"{shown}: not a regular file (a FIFO, socket or device): give a scene file (a .toml)")


def _table(data: dict, key: str, where: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, dict):
        raise SceneError(f"{where}: [{key}] must be a table (a [{key}] section), got {type(value).__name__}")
    return value


def _no_floats(table: dict, section: str, where: str) -> None:
    """TOML floats are rounded to binary before we see them: rejected in every table, as in [parameters]."""
    for k, v in table.items():
        items = v if isinstance(v, list) else [v]
        for x in items:
            if isinstance(x, float):
                raise ParameterError(f"{where}: [{section}] {k}: written as the TOML float {x!r}, which is rounded "
                                     f"to binary; quote it: {k} = \"{x!r}\"")


def parse_scene(text: str, where: str = "<string>") -> Scene:
    """Parse the TOML text of a scene; see the module docstring for the format."""
    if not isinstance(text, str):
        raise SceneError(f"{where}: scene text must be a string, got {type(text).__name__}")
    if text.startswith("\ufeff"):      # a byte-order mark, as some editors save UTF-8: not part of the TOML
        text = text[1:]
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"{where}: not valid TOML: {e}") from None
    except RecursionError:
        raise SceneError(f"{where}: nested too deeply to be a scene file (tables and arrays nest a few "
                         "levels at most)") from None
    unknown = [k for k in data if k not in TOP_LEVEL]
    if unknown:
        raise SceneError(f"{where}: unknown top-level key or table {unknown[0]!r}{_did_you_mean(unknown[0], TOP_LEVEL)}; "
                         f"a scene has {', '.join(TOP_LEVEL)} (kind-specific settings go in [options])")
    for key in ("name", "kind"):
        if key not in data:
            raise SceneError(f"{where}: missing top-level key {key!r}")
    if "parameters" not in data:
        raise SceneError(f"{where}: missing the table [parameters] (a scene without parameters writes an empty "
                         "[parameters] line; every number a model uses is named there)")
    name = check_name(data["name"], where)
    kind = data["kind"]
    if not isinstance(kind, str) or kind not in KINDS:
        hint = " (planned, not in this version)" if isinstance(kind, str) and kind in PLANNED_KINDS else ""
        shown = kind if isinstance(kind, str) else f"{kind!r} ({type(kind).__name__})"
        raise SceneError(f"{where}: unknown kind {shown!r}{hint}"
                         f"{_did_you_mean(kind, KINDS) if isinstance(kind, str) else ''}; known kinds: {', '.join(KINDS)}")
    source = data.get("source", "")
    if not isinstance(source, str):
        raise SceneError(f"{where}: source must be a string")
    params_raw = _table(data, "parameters", where)
    params: dict[str, str] = {}
    for k, v in params_raw.items():
        if isinstance(v, bool) or not isinstance(v, (str, int)):
            if isinstance(v, float):
                raise ParameterError(f"parameter {k!r}: written as the TOML float {v!r}, which is "
                                     f"rounded to binary; quote it: {k} = \"{v!r}\"")
            raise ParameterError(f"parameter {k!r}: expected a quoted exact number, got {v!r}")
        params[k] = str(v)
    claims = _table(data, "claims", where)
    bad_claim_keys = [k for k in claims if k != "only"]
    if bad_claim_keys:
        raise SceneError(f"{where}: [claims] has only the key 'only' (a list of claim names), got "
                         f"{bad_claim_keys[0]!r}{_did_you_mean(bad_claim_keys[0], ['only'])}")
    only = claims.get("only")
    if only is not None and (not isinstance(only, list) or not all(isinstance(c, str) for c in only)):
        raise SceneError(f"{where}: [claims] only must be a list of claim names")
    if only is not None and not only:
        raise SceneError(f"{where}: [claims] only = [] asks for no claim: name at least one, or drop the key")
    if only is not None and len(set(only)) != len(only):
        raise SceneError(f"{where}: [claims] only names a claim twice")
    options = _table(data, "options", where)
    paper = _table(data, "paper", where)
    _no_floats(options, "options", where)
    _no_floats(paper, "paper", where)
    model = _model_table(data, kind, where)
    return Scene(name=name, kind=kind, source=source, parameters=params, claims_only=only,
                 options=dict(options), paper=dict(paper), path=where, model=model)


def _model_table(data: dict, kind: str, where: str) -> dict[str, Any]:
    """The kind's model table as written: only the kind's own table name (``MODEL_TABLES``), its values
    strings, integers or (nested) lists of them; no TOML floats. Its meaning is checked by the kind."""
    own = MODEL_TABLES.get(kind)
    for key in MODEL_TABLES.values():
        if key in data and key != own:
            allowed = f"[{own}]" if own else "no model table"
            raise SceneError(f"{where}: [{key}] is a model table of another kind; a {kind} scene takes {allowed}")
    if own is None or own not in data:
        return {}
    table = _table(data, own, where)

    def plain(v, label):
        if isinstance(v, list):
            return [plain(x, label) for x in v]
        if isinstance(v, float):
            raise ParameterError(f"{where}: [{own}] {label}: written as the TOML float {v!r}, which is rounded "
                                 f"to binary; quote it: \"{v!r}\"")
        if isinstance(v, bool) or not isinstance(v, (str, int)):
            raise SceneError(f"{where}: [{own}] {label}: expected a quoted exact number or expression (or a list "
                             f"of them), got {type(v).__name__}")
        return v if isinstance(v, str) else str(v)

    return {k: plain(v, k) for k, v in table.items()}
