"""Helpers of the checker tests that forge certificates: prove a built-in scene or a variant of it, make
a forged certificate's digest (and verdict) consistent (so that only the re-decision of its claims can
reject it), read the checker's report item by item or as its failures, and build polynomials from their roots."""
from __future__ import annotations

import copy
import dataclasses
import json
from contextlib import contextmanager
from fractions import Fraction
from unittest import mock

from flint import fmpq, fmpq_poly

from rigor_gyro import load_scene, prove_scene, reproduce
from rigor_gyro.certificate import digest
from rigor_gyro.check import check_certificate


def certificate(name: str, options: dict | None = None, *, claims_only: list[str] | None = None,
                prove: dict | None = None, **params) -> dict:
    """The certificate (as parsed JSON) of the built-in scene ``name``, or of its variant (named
    "variant") with the given parameters and options replaced and, with ``claims_only``, only those
    claims asked; ``prove``: keyword arguments of ``prove_scene`` (``maxprec``, ...)."""
    scene = load_scene(name)
    if params or options or claims_only:
        scene = dataclasses.replace(scene, name="variant", parameters=dict(scene.parameters, **params),
                                    options=dict(scene.options, **(options or {})),
                                    claims_only=claims_only or scene.claims_only)
    raw = prove_scene(scene, **(prove or {})).to_json()
    reproduce.keep(raw)         # the checker's re-proof of this scene at these settings is this very proof
    return json.loads(json.dumps(raw))


def refix(data: dict) -> dict:
    """The verdict recomputed from the claims' statuses and the digest from the content (in place)."""
    statuses = [c["status"] for c in data["claims"]]
    data["verdict"] = ("refuted" if "refuted" in statuses else
                       "proved" if all(s == "proved" for s in statuses) else "inconclusive")
    data["integrity"] = {"sha256": digest(data)}
    return data


def reseal(data: dict) -> dict:
    """A copy of data with the digest recomputed from its content (the verdict left as it is)."""
    data = copy.deepcopy(data)
    data["integrity"] = {"sha256": digest(data)}
    return data


#: the checker's re-derivation of every text by proving again (rigor_gyro.reproduce): it rejects every
#: forgery, so these helpers leave it out, so that each test sees whether the checker's OWN re-decision of
#: a claim rejects the forgery (tests/test_tamper_corpus.py tests the texts check itself)
TEXTS = "texts"


@contextmanager
def _texts_not_re_derived():
    """The ``texts`` check answered without proving the scene again, for the helpers below, which drop its
    result: on a certificate whose scene block was edited (another mu, x2*, ...) or whose re-proof left the
    store, that re-proof costs a whole proof per call and could change no answer of theirs."""
    with mock.patch.object(reproduce, "reproduction", lambda data, scene: (True, "not re-derived (tests/forgery.py)")):
        yield


def report_without_texts(data: dict):
    """The checker's report on data, its ``texts`` check not re-derived (see :func:`_texts_not_re_derived`)."""
    with _texts_not_re_derived():
        return check_certificate(data)


def failures(data: dict) -> list[tuple[str, str]]:
    """(item, message) of every check the checker's report on data fails, in order (``texts`` aside)."""
    return [(r.item, r.message) for r in report_without_texts(data).results if not r.ok and r.item != TEXTS]


def items(data: dict) -> dict[str, bool]:
    """item -> ok of the checker's report on data (the digest and verdict made consistent first; ``texts``
    aside)."""
    out: dict[str, bool] = {}
    for r in report_without_texts(refix(data)).results:
        if r.item == TEXTS:
            continue
        out[r.item] = out.get(r.item, True) and r.ok
    return out


def claim(data: dict, cid: str) -> dict:
    return next(c for c in data["claims"] if c["id"] == cid)


def poly(*roots, extra: fmpq_poly | None = None) -> fmpq_poly:
    """prod (x - r) over the given rational roots, times ``extra`` if given."""
    p = fmpq_poly([1])
    for r in roots:
        r = Fraction(r)
        p *= fmpq_poly([-fmpq(r.numerator, r.denominator), 1])
    return p * extra if extra is not None else p


def flipped(cert: dict):
    """For each decided claim: (its id, its status, the checker's items on a copy with that status
    flipped, proved <-> refuted, and its counterexample removed)."""
    import copy
    for c in cert["claims"]:
        if c["status"] == "inconclusive":
            continue
        bad = copy.deepcopy(cert)
        d = claim(bad, c["id"])
        d["status"] = "refuted" if c["status"] == "proved" else "proved"
        d.pop("counterexample", None)
        yield c["id"], c["status"], items(bad)
