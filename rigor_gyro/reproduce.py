"""Re-derive every text of a certificate by proving its scene again (the checker's ``texts`` check).

A certificate states more than its verdicts: each claim's reason, details and counterexample, the
quantities, the audit rows, ``extra`` (roots, moduli, the moment formula), ``notes``, ``formulas``, the
witnesses. The
kinds' checkers re-decide the verdicts by their own path; this module makes every other field a
re-derived one: it runs :func:`~rigor_gyro.prover.prove_scene` on the certificate's scene at its
stored ``settings`` and compares the two certificates field by field. The prover is deterministic (CI
reproduces the built-in certificates byte for byte), so any edit of these fields, however consistent
it looks and whatever digest it carries, is named here.

Not independent of the prover: a wrong reason written by the prover itself would be reproduced. Not
compared: ``scene``, ``software``, ``settings``, ``integrity`` (checked elsewhere). The audit rows are
re-derived from the ``[paper]`` table the certificate's scene block carries.

A run stopped by ``--time-limit`` is re-derived from its finished attempts: the prover runs again with
``maxprec`` = the last finished attempt's precision and no limit, and the time-limit wording the prover
writes (the bracketed hint of an undecided claim, the time-limit note) is put in exactly before the two are
compared. A run in which no attempt finished must say exactly that, with nothing else. A certificate
written by another version is not confirmed: its texts can be re-derived only by that version.

Cost: one proof of the scene. A process keeps its last few re-proofs (:data:`KEPT`), keyed by the scene
block and the two precisions, so that checking several certificates of one scene (edited copies, a
campaign) proves it once; :func:`forget` empties that store (the tests do, around any test that patches
the prover).
"""
from __future__ import annotations

import json
from collections import OrderedDict
from typing import Any

from .prover import time_limit_note
from .version import __version__

__all__ = ["reproduction", "COMPARED", "forget"]

#: how many re-proved certificates a process keeps (each a few hundred kB of JSON at most)
KEPT = 4
_KEPT: OrderedDict[tuple[str, int, int], dict] = OrderedDict()


def forget() -> None:
    """Empty the store of re-proved certificates (after the prover's code was patched, say)."""
    _KEPT.clear()


def _key(scene_block: dict, prec: int, maxprec: int) -> tuple[str, int, int]:
    return json.dumps(scene_block, sort_keys=True), prec, maxprec


def keep(certificate: dict) -> None:
    """Store ``certificate``, exactly as :meth:`Certificate.to_json` returned it from ``prove_scene`` at its
    own settings (no time limit), as the re-proof of its scene: for callers that have just proved the scene
    and will check its certificate (the tests). Storing anything else would let the ``texts`` check
    compare against it: never call this on a certificate read from a file."""
    st = certificate["settings"]
    if st.get("time_limit") is None:
        _KEPT[_key(certificate["scene"], st["prec"], st["maxprec"])] = certificate
        while len(_KEPT) > KEPT:
            _KEPT.popitem(last=False)


def _reproved(data: dict, scene, prec: int, maxprec: int) -> dict:
    """The certificate the prover writes for ``scene`` (the one ``data['scene']`` describes) at these
    precisions: from the store when the same scene block was re-proved at them before in this process.
    The returned dict is shared: read it, never change it."""
    from .prover import prove_scene
    key = _key(data["scene"], prec, maxprec)
    if key in _KEPT:
        _KEPT.move_to_end(key)
        return _KEPT[key]
    again = prove_scene(scene, prec=prec, maxprec=maxprec).to_json()
    _KEPT[key] = again
    while len(_KEPT) > KEPT:
        _KEPT.popitem(last=False)
    return again

#: the fields compared, in the order a difference is reported
COMPARED = ("verdict", "precision_bits", "precisions_tried", "claims", "quantities", "paper", "formulas", "notes",
            "extra", "witnesses")
_HINT = " [undecided at every precision tried:"
_TIME = "time limit of "


def _first_difference(a: Any, b: Any, path: str) -> str | None:
    """The first place where ``a`` (stored) and ``b`` (re-derived) differ, as a JSON path, or None."""
    if isinstance(a, dict) and isinstance(b, dict):
        for k in list(a) + [k for k in b if k not in a]:
            if k not in a or k not in b:
                return f"{path}.{k}"
            d = _first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path} (length {len(a)}, re-derived {len(b)})"
        for i, (x, y) in enumerate(zip(a, b)):
            d = _first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    return None if a == b else path


def _as_time_limited(again: dict, data: dict, seconds: float) -> dict:
    """What the prover writes when ``seconds`` ran out after the attempts of ``data['precisions_tried']``, from
    ``again`` (the same scene re-proved without a limit up to the last finished attempt's precision): each
    undecided claim's hint names the time limit, the widths notes (written only without a time-out) go, and
    the time-limit note is added. Every text is then compared exactly (an added or reworded note is named)."""
    why = f"time limit of {seconds:g} s reached (--time-limit)"
    out = {k: again.get(k) for k in COMPARED}
    out["claims"] = [{**c, "reason": f"{c['reason'].split(_HINT, 1)[0]}{_HINT} {again['precisions_tried']} bits; {why}]"}
                     if c.get("status") == "inconclusive" else c for c in again.get("claims", [])]
    out["notes"] = [n for n in again.get("notes", []) if not n.startswith("requested enclosure widths not met")] + \
        [time_limit_note(why, again["precision_bits"], again["precisions_tried"][-1])]
    return out


def _nothing_finished(data: dict, seconds: float, settings: dict) -> tuple[bool, str]:
    """A run whose first attempt did not finish: every claim inconclusive for the time limit at the precision
    the prover starts at, nothing else (no quantity, audit row, extra field, formula or other note)."""
    from .kinds import claim_statements, kind_module
    from .prover import starting_precision
    from .scene import Scene
    module = kind_module(data["scene"]["kind"])
    model = module.validate(Scene.from_header(data["scene"]))
    statements = claim_statements(module, model)
    why = f"time limit of {seconds:g} s reached (--time-limit)"
    p0 = starting_precision(model, settings["prec"], settings["maxprec"])
    bad = [c["id"] for c in data["claims"]
           if c.get("status") != "inconclusive" or c.get("statement") != statements.get(c["id"])
           or c.get("reason") != f"not decided: {why} before the first attempt ({p0} bits) finished"
           or c.get("precision_bits", p0) != p0
           or set(c) - {"id", "statement", "status", "reason", "precision_bits"}]
    empty = not data.get("quantities") and not data.get("extra") and not data.get("witnesses") \
        and not data.get("formulas") and not data.get("paper") \
        and data.get("precisions_tried") == [p0] and data.get("precision_bits") == p0
    notes = data.get("notes") == [f"{why}: the certificate is the last attempt that finished (none did: nothing was "
                                  "decided)"]
    ok = not bad and empty and notes
    return ok, ("no attempt finished before the time limit, and the certificate says exactly that" if ok else
                "the certificate says no attempt finished before its time limit, but " +
                (f"claim {bad[0]!r} is not the time limit's inconclusive claim" if bad else
                 "it holds more than an empty attempt" if not empty else "its notes differ"))


def reproduction(data: dict, scene) -> tuple[bool, str]:
    """(ok, message) of the ``texts`` check for the certificate ``data`` of ``scene`` (already validated
    against its schema): see the module docstring."""
    written_by = (data.get("software") or {}).get("rigor_gyro")
    if written_by != __version__:
        return False, (f"not re-derived: written by rigor_gyro {written_by}, this is {__version__}: the audit rows, "
                       "reasons, counterexamples' values, extra fields and notes are re-derived only by the version "
                       f"that wrote them, so the certificate is not confirmed (check it with rigor_gyro {written_by})")
    settings = data["settings"]
    limit = settings.get("time_limit")
    fired = limit is not None and any(n.startswith(_TIME) for n in data.get("notes", []))
    if fired and any(n.endswith("(none did: nothing was decided)") for n in data["notes"]):
        return _nothing_finished(data, limit, settings)
    tried = data.get("precisions_tried")
    if fired and not (isinstance(tried, list) and tried and all(type(p) is int and 16 <= p <= 32768 for p in tried)):
        return False, f"precisions_tried {tried!r} is not a list of precisions"
    # a time-limited run is re-proved up to its last finished attempt (the certificate may be an earlier one)
    maxprec = max(tried) if fired else settings["maxprec"]
    if not settings["prec"] <= maxprec:
        return False, f"settings prec {settings['prec']} above the last attempt's {maxprec} bits"
    again = _reproved(data, scene, settings["prec"], maxprec)
    stored, derived = (data, _as_time_limited(again, data, limit)) if fired else (data, again)
    for key in COMPARED:
        where = _first_difference(stored.get(key), derived.get(key), key)
        if where:
            return False, (f"{where} is not what the prover writes for this scene at these settings (re-proved at "
                           f"prec {settings['prec']}, maxprec {maxprec}): an edited or foreign certificate")
    return True, ("every reason, detail, counterexample, quantity, audit row, note, formula and extra field re-derived by "
                  "proving the scene again" + (" (its last finished attempt, the time limit aside)" if fired else ""))
