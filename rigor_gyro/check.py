"""Re-verify a certificate from its own data: ``rigor-gyro check CERT.json``.

A certificate is worth exactly its soundness, so the checker does not trust the prover's search: it
rebuilds the exact model from the certificate's parameters and options, and re-decides each claim
from the stored enclosures and witnesses by a separate, simpler path (exact rational sign changes
and comparisons, re-evaluation of the stored subdivision pieces, recomputation at a higher precision
of every closed-form quantity). Checking an inclusion is cheaper than finding it.

What is checked:

* integrity: the certificate's ``integrity.sha256`` is the digest of everything else (an accidental
  or careless edit of any field is rejected; a deliberate edit that also fixes the digest meets the
  semantic checks below);
* structure: the schema, the verdict rule (proved iff every claim proved, refuted iff some claim
  refuted), the claim ids (exactly those the scene asks for), each claim's statement as the kind
  words it, parameters and options valid for the kind;
* every claim: a ``proved`` claim is re-proved from the stored data, a ``refuted`` one has its
  counterexample re-certified, an ``inconclusive`` one claims nothing and is not checked;
* every quantity the kind's checker knows: its stored [lo, hi] must contain the value (a quantity
  the checker cannot re-verify is reported as such and makes the check fail).

* every text the certificate states (each claim's reason, details and counterexample, the quantities,
  the audit rows, ``extra``, ``notes``, ``formulas``, the witnesses, the precisions): re-derived by running the prover
  again on the certificate's scene at its stored ``settings`` and compared field by field (the prover
  is deterministic: CI reproduces the built-in certificates byte for byte). This check is not
  independent of the prover: it says the text is what rigor_gyro writes for these parameters, while
  the checks above re-decide every verdict by their own path. A run stopped by ``--time-limit`` is
  re-derived from its last finished attempt (``maxprec`` = its ``precision_bits``), the time-limit
  wording aside. A certificate written by another version of rigor_gyro is not compared (the check
  says so).

The audit of the paper (rows about the source, never a verdict) is re-derived by that check only, from
the ``[paper]`` table the scene block carries (no independent path).

A certificate whose scene block names a built-in scene (``builtin:NAME``) it is not fails its ``scene`` check and
is not confirmed; its claims, quantities and texts are then not re-derived (results marked ``skipped``, never
``ok``: re-proving an edited scene costs as much as proving it and cannot make the certificate the built-in's).
``stop_at_failure`` (``check -q``) ends a certificate's checks at the first that fails.

Every output kind has a JSON Schema in ``rigor_gyro/schemas/`` (certificate, paving, threshold, scan), and
:func:`check_certificate` dispatches on the file's ``schema``: each file is first validated against its
schema (by :func:`schema_errors`, a small validator of the JSON Schema keywords those files use: the
installed package needs no jsonschema; the tests validate with jsonschema too), then re-verified by its
kind's checker (pavings: :mod:`rigor_gyro.margins.check`; thresholds and scans:
:func:`~rigor_gyro.margins.threshold.check_threshold`, :func:`~rigor_gyro.margins.scan.check_scan`).

Guarantee: :func:`check_certificate` returns a report whose ``ok`` is True only when every check
passed. Fails when: the file is not readable JSON of this schema: :class:`CertificateError`.
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .certificate import SCHEMA, digest
from .core.errors import RigorGyroError
from .margins.identity import builtin_differs

__all__ = ["CertificateError", "CheckResult", "CheckReport", "check_certificate", "check_file", "digest", "SCHEMA_FILES",
           "load_schema", "schema_errors"]

#: the schema of each output kind, by the ``schema`` field of the file
SCHEMA_FILES = {SCHEMA: "certificate-2", "rigor-gyro/paving/1": "paving-1", "rigor-gyro/threshold/1": "threshold-1",
                "rigor-gyro/scan/1": "scan-1", "rigor-gyro/threshold-curve/1": "threshold-curve-1"}
_SCHEMAS: dict[str, dict] = {}


def load_schema(name: str) -> dict[str, Any]:
    """The JSON Schema ``rigor_gyro/schemas/<name>.schema.json`` (cached)."""
    if name not in _SCHEMAS:
        from importlib import resources
        _SCHEMAS[name] = json.loads((resources.files("rigor_gyro") / "schemas" / f"{name}.schema.json")
                                    .read_text(encoding="utf-8"))
    return _SCHEMAS[name]


_TYPES = {"object": dict, "array": list, "string": str, "boolean": bool, "null": type(None)}
_ANNOTATIONS = {"$schema", "$id", "$defs", "title", "description"}


def _type_ok(x: Any, t: str) -> bool:
    if t == "integer":
        return isinstance(x, int) and not isinstance(x, bool)
    if t == "number":
        return isinstance(x, (int, float)) and not isinstance(x, bool)
    return isinstance(x, _TYPES[t])


def schema_errors(data: Any, schema: dict[str, Any], root: dict[str, Any] | None = None, path: str = "$",
                  limit: int = 5) -> list[str]:
    """The first ``limit`` places where ``data`` breaks ``schema`` (JSON Schema 2020-12, the keywords the
    schemas of rigor_gyro use: type, const, enum, pattern, minimum, maximum, required, properties,
    additionalProperties, minProperties, items, minItems, maxItems, $ref to #/$defs, anyOf, oneOf, not,
    if/then/else); [] when it conforms. A keyword outside this set is an error of the schema (ValueError),
    so a schema never asks for a check this validator silently skips."""
    import re
    root = root or schema
    errors: list[str] = []

    def err(msg: str) -> None:
        errors.append(f"{path}: {msg}")

    unknown = set(schema) - _ANNOTATIONS - {"type", "const", "enum", "pattern", "minimum", "maximum", "required",
                                            "properties", "additionalProperties", "minProperties", "items", "minItems",
                                            "maxItems", "$ref", "anyOf", "oneOf", "not", "if", "then", "else"}
    if unknown:
        raise ValueError(f"schema keyword(s) {sorted(unknown)} not supported by rigor_gyro's validator")
    if "$ref" in schema:
        ref = schema["$ref"]
        if not ref.startswith("#/$defs/"):
            raise ValueError(f"unsupported $ref {ref!r}")
        errors += schema_errors(data, root["$defs"][ref[len("#/$defs/"):]], root, path, limit)
    if "type" in schema:
        types = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(_type_ok(data, t) for t in types):
            err(f"{type(data).__name__} is not of type {'/'.join(types)}")
            return errors[:limit]
    if "const" in schema and data != schema["const"]:
        err(f"{str(data)[:60]!r} is not {schema['const']!r}")
    if "enum" in schema and data not in schema["enum"]:
        err(f"{str(data)[:60]!r} is not one of {schema['enum']}")
    if isinstance(data, str) and "pattern" in schema and not re.search(schema["pattern"], data):
        err(f"{data[:60]!r} does not match {schema['pattern']!r}")
    if _type_ok(data, "number"):
        if "minimum" in schema and data < schema["minimum"]:
            err(f"{data} < {schema['minimum']}")
        if "maximum" in schema and data > schema["maximum"]:
            err(f"{data} > {schema['maximum']}")
    if isinstance(data, dict):
        for k in schema.get("required", []):
            if k not in data:
                err(f"missing {k!r}")
        if len(data) < schema.get("minProperties", 0):
            err(f"fewer than {schema['minProperties']} properties")
        props = schema.get("properties", {})
        extra = schema.get("additionalProperties", True)
        for k, v in data.items():
            if len(errors) >= limit:
                break
            if k in props:
                errors += schema_errors(v, props[k], root, f"{path}.{k}", limit)
            elif extra is False:
                err(f"unexpected {k!r}")
            elif isinstance(extra, dict):
                errors += schema_errors(v, extra, root, f"{path}.{k}", limit)
    if isinstance(data, list):
        if len(data) < schema.get("minItems", 0):
            err(f"fewer than {schema['minItems']} items")
        if "maxItems" in schema and len(data) > schema["maxItems"]:
            err(f"more than {schema['maxItems']} items")
        if "items" in schema:
            for i, v in enumerate(data):
                if len(errors) >= limit:
                    break
                errors += schema_errors(v, schema["items"], root, f"{path}[{i}]", limit)
    if "anyOf" in schema and not any(not schema_errors(data, s, root, path, 1) for s in schema["anyOf"]):
        err("matches none of anyOf")
    if "oneOf" in schema and sum(not schema_errors(data, s, root, path, 1) for s in schema["oneOf"]) != 1:
        err("does not match exactly one of oneOf")
    if "not" in schema and not schema_errors(data, schema["not"], root, path, 1):
        err("matches a schema it must not")
    if "if" in schema:
        branch = "then" if not schema_errors(data, schema["if"], root, path, 1) else "else"
        if branch in schema:
            errors += schema_errors(data, schema[branch], root, path, limit)
    return errors[:limit]


class CertificateError(RigorGyroError, ValueError):
    """The file is not a readable certificate (not JSON, wrong schema, missing fields)."""


@dataclass
class CheckResult:
    """One check: what was checked (a claim id, a quantity, 'integrity', ...), whether it passed, why.
    ``skipped``: the check was not run (an earlier check made it meaningless); it is never ``ok``."""

    item: str
    ok: bool
    message: str
    skipped: bool = False


@dataclass
class CheckReport:
    file: str
    results: list[CheckResult] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return bool(self.results) and all(r.ok for r in self.results)

    @property
    def first_failure(self) -> CheckResult | None:
        return next((r for r in self.results if not r.ok), None)


def _conformance(data: Any, name: str) -> list[str]:
    try:
        return schema_errors(data, load_schema(name))
    except RecursionError:
        return ["$: nested too deeply to validate"]


class _DuplicateKey(ValueError):
    pass


def _unique_keys(pairs: list) -> dict:
    """A JSON object's pairs as a dict; _DuplicateKey when a key repeats (Python keeps the last value, other
    readers the first: a file could show one verdict to a person and another to the checker)."""
    out = {}
    for k, v in pairs:
        if k in out:
            raise _DuplicateKey(k)
        out[k] = v
    return out


def check_file(path: str | Path, samples: int | None = None, executor=None, stop_at_failure: bool = False) -> CheckReport:
    """Read and check an output file: a certificate, a paving, a threshold or a scan (by its ``schema``
    field); CertificateError if it cannot be read as one. ``samples``: a paving's decided sub-boxes per
    claim cross-checked by the point prover (:mod:`rigor_gyro.margins.sampled`; None: its default);
    ``executor`` (:class:`rigor_gyro.margins.executors.Executor`): where a paving's decided sub-boxes are
    re-evaluated (the verdicts do not depend on where). ``stop_at_failure``: a certificate's checks stop at the
    first that fails (``check -q``: only the verdict is wanted; the report holds the checks run)."""
    p = Path(path)
    try:
        data = json.loads(p.read_text(encoding="utf-8"), object_pairs_hook=_unique_keys)
    except _DuplicateKey as e:
        raise CertificateError(f"{path}: key {str(e)[:100]!r} appears twice in one object: readers disagree on "
                               "which value counts (rigor-gyro never writes a key twice)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as e:
        raise CertificateError(f"{path}: not a readable certificate ({type(e).__name__}: {str(e)[:200]})") from None
    if isinstance(data, dict) and "total_s" in data and "schema" not in data:
        raise CertificateError(f"{path}: a timings file (timings/<name>.json), not a certificate")
    try:
        report = check_certificate(data, str(path), samples=samples, executor=executor, stop_at_failure=stop_at_failure)
    except CertificateError as e:
        raise CertificateError(f"{path}: {e}") from None
    return report


def _structure(data: Any) -> None:
    if not isinstance(data, dict):
        raise CertificateError("a certificate is a JSON object")
    missing = [k for k in ("schema", "scene", "precision_bits", "verdict", "claims", "quantities", "integrity")
               if k not in data]
    if missing:
        raise CertificateError(f"not a certificate: missing {missing}")
    if data["schema"] != SCHEMA:
        raise CertificateError(f"schema {data['schema']!r}: this checker reads {sorted(SCHEMA_FILES)}")
    scene = data["scene"]
    if not isinstance(scene, dict) or not {"name", "kind", "parameters"} <= set(scene):
        raise CertificateError("scene block incomplete")
    if not isinstance(data["claims"], list) or not isinstance(data["quantities"], dict):
        raise CertificateError("claims must be a list and quantities an object")
    for c in data["claims"]:
        if not isinstance(c, dict) or not {"id", "statement", "status"} <= set(c):
            raise CertificateError(f"malformed claim {c!r}"[:200])
        if not isinstance(c.get("counterexample", {}), dict) or not isinstance(c.get("details", {}), dict):
            raise CertificateError(f"claim {c['id']!r}: counterexample and details must be objects")
    if not isinstance(data.get("witnesses", {}), dict):
        raise CertificateError("witnesses must be an object")


#: the message of the checks a certificate whose scene is not the built-in it names does not run
SCENE_MISMATCH_SKIP = "skipped: the scene does not match the built-in it names"


class _Stop(Exception):
    """A check failed and the caller asked to stop at the first failure."""


def check_certificate(data: Any, file: str = "<data>", samples: int | None = None, executor=None,
                      stop_at_failure: bool = False) -> CheckReport:
    """Check a certificate given as parsed JSON; see the module docstring (``samples``, ``stop_at_failure``: see
    :func:`check_file`). A certificate whose scene block names a built-in scene it is not (the ``scene`` check
    fails) is not confirmed whatever its data say: its claims are not re-decided nor its texts re-derived (those
    results say :data:`SCENE_MISMATCH_SKIP`; they cost as much as a proof, and answer nothing once the scene is
    not the one named)."""
    t0 = time.perf_counter()
    report = CheckReport(file)
    try:
        _check_certificate(data, report, samples, executor, stop_at_failure)
    except _Stop:
        pass
    report.seconds = time.perf_counter() - t0
    return report


def _check_certificate(data: Any, report: CheckReport, samples, executor, stop_at_failure: bool) -> None:
    """The checks of :func:`check_certificate`, appended to ``report``; _Stop at the first failure when
    ``stop_at_failure``."""
    from .core.balls import MAX_PREC, working_precision
    from .kinds import checker, claim_statements, kind_module, scene_claims
    from .prover import requested_claims
    from .scene import Scene

    kind = data.get("schema") if isinstance(data, dict) else None
    if kind in ("rigor-gyro/paving/1", "rigor-gyro/threshold/1", "rigor-gyro/scan/1", "rigor-gyro/threshold-curve/1"):
        errors = _conformance(data, SCHEMA_FILES[kind])
        schema = CheckResult("schema", not errors, f"conforms to {SCHEMA_FILES[kind]}.schema.json" if not errors
                             else f"does not conform to {SCHEMA_FILES[kind]}.schema.json: " + "; ".join(errors))
        # a threshold or scan is read only once it conforms; a paving's checks run whatever (each names what
        # it cannot read), its schema last, as a certificate's
        if kind != "rigor-gyro/paving/1":
            report.results.append(schema)
        if not errors or kind == "rigor-gyro/paving/1":
            try:
                if kind == "rigor-gyro/paving/1":
                    from .margins.check import check_paving as check_kind
                elif kind == "rigor-gyro/threshold/1":
                    from .margins.threshold import check_threshold as check_kind
                elif kind == "rigor-gyro/threshold-curve/1":
                    from .margins.threshold_curve import check_curve as check_kind
                else:
                    from .margins.scan import check_scan as check_kind
                extra = {} if kind != "rigor-gyro/paving/1" else {
                    **({"samples": samples} if samples is not None else {}),
                    **({"executor": executor} if executor is not None else {})}
                report.results.extend(CheckResult(*t) for t in check_kind(data, **extra))
            except (RigorGyroError, KeyError, TypeError, ValueError, ArithmeticError, AttributeError, IndexError) as e:
                report.results.append(CheckResult("data", False, f"the {kind.split('/')[1]}'s data cannot be checked: "
                                                  f"{type(e).__name__}: {e}"))
        if kind == "rigor-gyro/paving/1":
            report.results.append(schema)
        return
    _structure(data)

    def add(result: CheckResult) -> None:
        report.results.append(result)
        if stop_at_failure and not result.ok:
            raise _Stop
    integrity = data.get("integrity")
    ok = isinstance(integrity, dict) and integrity.get("sha256") == digest(data)
    add(CheckResult("integrity", ok, "digest matches" if ok else "the digest does not match the content: "
                    "the certificate was altered after it was written"))
    statuses = [c["status"] for c in data["claims"]]
    verdict = ("refuted" if "refuted" in statuses else
               "proved" if statuses and all(s == "proved" for s in statuses) else "inconclusive")
    add(CheckResult("verdict", data["verdict"] == verdict,
                    f"verdict {data['verdict']!r}" + ("" if data["verdict"] == verdict else f", but the claims give {verdict!r}")))
    bad_status = [s for s in statuses if s not in ("proved", "refuted", "inconclusive")]
    if bad_status:
        add(CheckResult("claims", False, f"unknown status(es) {bad_status}"))
    sc = data["scene"]
    try:
        if not all(isinstance(sc.get(k, {}), dict) for k in ("parameters", "options")):
            raise CertificateError("scene parameters and options must be objects")
        scene = Scene.from_header(sc)
        module = kind_module(scene.kind)
        model = module.validate(scene)
        wanted = requested_claims(scene, *scene_claims(module, scene))
    except (RigorGyroError, TypeError, ValueError) as e:
        add(CheckResult("scene", False, f"the certificate's scene is not valid: {e}"))
        return
    shipped = builtin_differs(sc, paper=True)
    if shipped:
        add(CheckResult("scene", False, shipped))
    ids = [c["id"] for c in data["claims"]]
    add(CheckResult("claims", ids == wanted, "the claims the scene asks for" if ids == wanted else
                    f"claims {ids} but the scene asks for {wanted}"))
    statements = claim_statements(module, model)
    for c in data["claims"]:
        if c["id"] in statements and c["statement"] != statements[c["id"]]:
            add(CheckResult(c["id"], False, "the statement is not the kind's statement of this claim"))
    prec = data["precision_bits"]
    if not isinstance(prec, int) or not 16 <= prec <= 32768:
        add(CheckResult("precision_bits", False, f"precision_bits {prec!r} out of range"))
        return
    kind_check = checker(scene.kind)
    if shipped:
        add(CheckResult("claims and quantities", False, SCENE_MISMATCH_SKIP, skipped=True))
    elif kind_check is None:
        add(CheckResult("kind", False, f"no checker for kind {scene.kind!r}"))
    else:
        with working_precision(min(max(2 * prec, 128), MAX_PREC)):
            try:
                results = kind_check(model, data)
            except (KeyError, TypeError, ValueError, ArithmeticError, AttributeError, IndexError, RecursionError) as e:
                results = [CheckResult("data", False, f"the certificate's data cannot be checked: {type(e).__name__}: {e}")]
        for r in results:
            add(r)
    errors = _conformance(data, SCHEMA_FILES[SCHEMA])
    if not errors and shipped:
        add(CheckResult("texts", False, SCENE_MISMATCH_SKIP, skipped=True))
    elif not errors:
        from .reproduce import reproduction
        ok, msg = reproduction(data, scene)
        add(CheckResult("texts", ok, msg))
    add(CheckResult("schema", not errors, "conforms to certificate-2.schema.json" if not errors else
                    "does not conform to certificate-2.schema.json: " + "; ".join(errors)))
