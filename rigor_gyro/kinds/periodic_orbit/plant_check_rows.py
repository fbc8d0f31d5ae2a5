"""The plant checker's re-verification of the roots' table ``extra.roots`` of a [plant] certificate
(:mod:`.plant_check`): every number and flag in it, independently of the software version that wrote it.

Each row states a root theta of g (decimal bounds), its kind, the moduli of its multipliers and a ``stable``
flag. The texts of a row (its ``reason``) are words, compared only by the ``texts`` check of the version
that wrote them; everything else is re-decided here from the checker's own enclosures:

* with the half-period re-verified (the isolation witness's pieces, in order): one row per re-verified root,
  in order; each row's theta bounds contain the re-verified root and its kind is the re-verified
  classification;
* without it: each row that states moduli or a stability flag locates its root by interval Newton inside its
  own theta bounds (a unique root of g there, or the row is not confirmed); its kind is not re-verified (the
  message says so);
* a genuine row's moduli: exactly n - 1 of them, and each recomputed modulus (the checker's Jacobian, another
  eigenvalue algorithm) lies inside one stored [lo, hi] of its own (a matching, each row used once);
* its ``stable`` flag: ``true`` only when every recomputed modulus is certainly < 1, ``false`` only when one
  is certainly > 1, ``null`` claims nothing; a plant of dimension 1 has no multipliers (the monodromy on the
  0-dimensional section) and its flag follows :func:`.multipliers.decide_multipliers` (``true``);
* a genuine row whose multipliers the prover did not isolate states no moduli, and ``stable: true`` only when
  the checker's own moduli are certainly below 1 or, where it does not isolate them either, Gershgorin's discs
  of its own Jacobian bound every modulus certainly below 1;
* a row of another kind (spurious, undecided) states no moduli and no flag.

Guarantee: ``ok`` only when every row is re-decided as above by balls. Precision: the checker's. Fails when:
a root or a multiplier is not re-decided at this precision: the item is not confirmed (never a crash: bad
data is a failed item).
"""
from __future__ import annotations

from flint import arb

from ...core.balls import certainly_gt, certainly_lt, is_far
from ...core.stored import encloses as exact_encloses, fmpq_of, interval as stored_interval

__all__ = ["check_root_rows", "encloses"]


def encloses(stored: tuple, x: arb) -> bool:
    """:func:`~rigor_gyro.core.stored.encloses` (exact), except for a ball beyond 10^+-315653
    (:func:`~rigor_gyro.core.balls.is_far`: a stiff plant's multiplier exp(-2.65e8)), whose exact endpoints
    have hundreds of millions of bits: there the stored ends, as balls, certainly below / above the ball's
    ends (sound; not confirmed when it cannot tell)."""
    if not x.is_finite():
        return False
    if not is_far(x):
        return exact_encloses(stored, x)
    lo, hi = (arb(fmpq_of(q)) for q in stored)
    return bool(lo <= x.lower() and x.upper() <= hi)


def _match(stored: list, moduli: list) -> bool:
    """Every recomputed modulus inside one stored interval of its own (bipartite matching; n <= 12)."""
    if len(stored) != len(moduli):
        return False
    owner: dict[int, int] = {}

    def place(i: int, seen: set) -> bool:
        for j, s in enumerate(stored):
            if j in seen or not encloses(s, moduli[i]):
                continue
            seen.add(j)
            if j not in owner or place(owner[j], seen):
                owner[j] = i
                return True
        return False
    return all(place(i, set()) for i in range(len(moduli)))


def _flag_ok(flag, moduli: list) -> bool:
    if flag is None:
        return True
    if flag is True:
        return all(certainly_lt(m, 1) for m in moduli)
    if flag is False:
        return any(certainly_gt(m, 1) for m in moduli)
    return False


def _row_moduli(row: dict, dim: int, moduli) -> str:
    """'' when the row's moduli and flag are re-verified against the recomputed ``moduli`` (None: not
    recomputed), else why not."""
    if dim == 1:
        if row.get("moduli") != [] or row.get("stable") is not True:
            return "a plant of dimension 1 has no multipliers and its orbit is stable: moduli [] and stable true"
        return ""
    if moduli is None:
        if row.get("moduli") or row.get("stable") is not None:
            return "moduli or a stability flag stated, but the multipliers are not recomputed at this precision"
        return ""
    stored = [stored_interval(p) for p in row.get("moduli") or []]
    if stored and not _match(stored, moduli):
        return (f"the stored moduli do not contain the {len(moduli)} recomputed moduli "
                f"({len(stored)} stored)")
    if not stored and row.get("stable") is not None:
        return "a stability flag without moduli"
    if not _flag_ok(row.get("stable"), moduli):
        return f"stable = {row.get('stable')!r} is not what the recomputed moduli decide"
    return ""


def check_root_rows(rows, dim: int, roots: list, kinds: list | None, moduli_of, locate,
                    stable_by_discs=None) -> tuple[bool, str]:
    """(ok, message) for the table ``rows`` (``extra.roots``) of a plant of dimension ``dim``. ``roots``:
    the re-verified roots in order with their re-verified ``kinds`` (None: the half-period was not
    re-verified); ``moduli_of(theta)``: the recomputed moduli of the orbit at the root ball theta (None: not
    recomputed); ``locate(lo, hi)``: the enclosure of the unique root of g in [lo, hi] (None: not re-decided);
    ``stable_by_discs(theta)``: whether Gershgorin's discs of the recomputed Jacobian bound every modulus
    certainly below 1 (a row without moduli may then say ``stable: true``)."""
    if not isinstance(rows, list):
        return False, "extra.roots is not a list"
    problems: list[str] = []
    located = 0
    if kinds is not None and len(rows) != len(roots):
        return False, f"{len(rows)} rows for {len(roots)} re-verified roots"
    for k, row in enumerate(rows, start=1):
        if not isinstance(row, dict) or not isinstance(row.get("moduli", []), list):
            problems.append(f"root {k}: not a row")
            continue
        lo, hi = stored_interval(row["theta"])
        if kinds is not None:
            th, kind = roots[k - 1], kinds[k - 1]
            if not encloses((lo, hi), th):
                problems.append(f"root {k}: the stored theta does not contain the re-verified root")
                continue
            if row.get("kind") != kind:
                problems.append(f"root {k}: kind {row.get('kind')!r}, re-verified {kind!r}")
                continue
        else:
            kind = row.get("kind")
            if kind != "genuine" or dim > 1 and not row.get("moduli") and row.get("stable") is None:
                th = None
            else:
                th = locate(arb(fmpq_of(lo)), arb(fmpq_of(hi)))
                if th is None:
                    problems.append(f"root {k}: no root of g re-decided inside the stored theta")
                    continue
                located += 1
        if kind != "genuine":
            if row.get("moduli") or row.get("stable") is not None:
                problems.append(f"root {k}: a {kind} root with moduli or a stability flag")
            continue
        if th is None:
            continue
        moduli = None if dim == 1 else moduli_of(th)
        if dim > 1 and row.get("moduli") == [] and row.get("stable") is True and (
                all(certainly_lt(m, 1) for m in moduli) if moduli is not None else
                stable_by_discs is not None and stable_by_discs(th)):
            continue        # the prover's multipliers were not isolated (stable by its discs): stable re-decided
        why = _row_moduli(row, dim, moduli)
        if why:
            problems.append(f"root {k}: {why}")
    if problems:
        return False, "; ".join(problems[:3]) + (" ..." if len(problems) > 3 else "")
    how = ("each row's theta, kind, moduli and stable flag re-verified" if kinds is not None else
           f"the half-period is not re-verified, so the kinds are not; {located} rows' roots located by interval "
           "Newton and their moduli and stable flags re-verified")
    return True, f"{len(rows)} rows: {how} (the reasons are texts: see the texts check)"
