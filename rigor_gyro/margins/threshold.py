"""Certified thresholds: where a claim stops holding as one parameter moves (``rigor-gyro margin``).

The claim is proved by the point prover at the two ends of a search interval (or, when other
parameters of the scene are tolerances, by a paving of their box: "proved" then means for every point
of the box, "refuted" that some point of it certainly fails); when it is proved at one
and refuted at the other, the interval is bisected at exact rational midpoints, keeping the half whose
ends still disagree, until the bracket [l, r] is at most ``width`` relative to its magnitude. The
result is a theorem about two exact points: the claim holds at one end and fails at the other, so its
outcome changes somewhere in [l, r]. It does not say the change is unique (a claim may switch more
than once); a paving of the interval (a scene with a tolerance) says what happens between points.

An inconclusive midpoint does not stop the search: it tries the points :data:`AROUND` in the bracket
(3/8, 5/8, 1/4, 3/4, 1/8 and 7/8 of the way from the proved end) and goes on from the first one decided;
only when all are inconclusive does it stop there.

Exit status: 0 a bracket to the requested width was certified; 3 the search stopped (both ends the
same outcome, inconclusive points, or the bisection budget): never 1, a search is not a refutation;
2 bad input (the parameter is absent, not rational, not one the claim depends on; lo >= hi; an end
outside the kind's domain; a width out of range).
"""
from __future__ import annotations

import json
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

from ..core.balls import about_text, interval_text, rational_text, width_text
from ..core.boxes import fraction_text, is_tolerance
from ..core.deadline import Budget, check_time_limit
from ..core.errors import ParameterError, RigorGyroError
from ..core.exact import option_number, parse_exact
from ..kinds import kind_module, scene_claims
from ..scene import Scene
from .threshold_log import AROUND, MAX_STEPS, replay     # the bisection rule's constants live with its replay
from .threshold_witness import Witnesses, in_box, point_status, witness_json

__all__ = ["Threshold", "find_threshold", "search_range", "write_threshold", "check_threshold", "statement", "SCHEMA"]

SCHEMA = "rigor-gyro/threshold/1"


@dataclass
class Threshold:
    scene: Scene
    param: str
    claim: str
    lo: Fraction
    hi: Fraction
    width: Fraction
    proved_at: Fraction | None = None
    refuted_at: Fraction | None = None
    steps: list[dict[str, Any]] = field(default_factory=list)
    stopped: str = ""

    @property
    def certified(self) -> bool:
        return self.proved_at is not None and self.refuted_at is not None and not self.stopped

    @property
    def exit_code(self) -> int:
        return 0 if self.certified else 3

    def bracket(self) -> tuple[Fraction, Fraction] | None:
        if self.proved_at is None or self.refuted_at is None:
            return None
        return min(self.proved_at, self.refuted_at), max(self.proved_at, self.refuted_at)

    def lines(self) -> list[str]:
        """What the search certified, every number as what it is: the search ends and the two proved points
        as exact decimals (or fractions n/d when they do not terminate), the bracket as exact decimals or
        rounded outward (then said), its width rounded up."""
        head = f"{self.scene.name}: margin of {self.claim!r} in {self.param}"
        b = self.bracket()
        if b is None:
            return [f"{head}: no change of outcome certified in [{_d(self.lo)}, {_d(self.hi)}]: {self.stopped}"]
        l, r = b
        bl, bh, rounded = interval_text(l, r)
        text = (f"{head}: proved at {self.param} = {_d(self.proved_at)}, refuted at {self.param} = "
                f"{_d(self.refuted_at)}: the outcome changes in [{bl}, {bh}]{' (rounded outward)' if rounded else ''} "
                f"(width {_width(r - l)}, {len(self.steps)} proofs)")
        return [text] + ([f"{head}: stopped before the requested width: {self.stopped}"] if self.stopped else [])

    def to_json(self) -> dict[str, Any]:
        b = self.bracket()
        return {"schema": SCHEMA, "scene": self.scene.header(), "param": self.param,
                "claim": self.claim, "search": [fraction_text(self.lo), fraction_text(self.hi)],
                "requested_relative_width": fraction_text(self.width),
                "certified": self.certified,
                "statement": statement(self.claim, self.param, self.proved_at, self.refuted_at) if b else None,
                "proved_at": fraction_text(self.proved_at) if b else None,
                "refuted_at": fraction_text(self.refuted_at) if b else None,
                "bracket": [fraction_text(b[0]), fraction_text(b[1])] if b else None,
                "bracket_decimal": list(interval_text(*b)[:2]) if b else None,
                "stopped": self.stopped, "steps": self.steps}


def statement(claim: str, param: str, proved_at: Fraction, refuted_at: Fraction) -> str:
    """What a threshold output states (exact rationals), as its checker re-derives it."""
    lo, hi = min(proved_at, refuted_at), max(proved_at, refuted_at)
    return (f"claim {claim!r} is proved at {param} = {fraction_text(proved_at)} and refuted at {param} = "
            f"{fraction_text(refuted_at)} (point proofs), so its outcome changes in [{fraction_text(lo)}, "
            f"{fraction_text(hi)}]")


def _d(q: Fraction | None) -> str:
    """An exact point as what it is: its exact decimal (1/5 -> "0.2"), or "n/d" when it does not
    terminate (1/3 -> "1/3"); never through a float."""
    if q is None:
        return "-"
    return rational_text(q)


def _width(w: Fraction) -> str:
    """An exact width: exact when it has at most 3 significant digits, else "<= " its value rounded up."""
    text = width_text(w)
    return text if Fraction(text) == w else f"<= {text}"


def _status(scene: Scene, param: str, value: Fraction, claim: str, seconds: float | None = None,
            leaves: list | None = None) -> tuple[str, str]:
    """The claim at ``param = value``: a point proof, or, when other parameters are tolerances, the
    paving of their box (proved: for every point of it; refuted: a certified counterexample in it),
    within ``seconds`` of wall clock (None: no limit; out of time: inconclusive). ``leaves``: a list that
    receives the paving's undecided leaves."""
    from ..prover import prove_scene
    s = Scene(name=scene.name, kind=scene.kind, source=scene.source,
              parameters={**scene.parameters, param: fraction_text(value)}, claims_only=[claim],
              options=dict(scene.options), model=dict(scene.model))
    try:
        if any(is_tolerance(v) for v in s.parameters.values()):
            from .paving import box_scene, pave
            p = pave(box_scene(s), time_limit=seconds)
            c = p.claims[0]
            v = c.volume(p.bs.box)
            if leaves is not None:
                leaves.extend(b for b, st in c.boxes if st == "undecided")
            return c.status, (f"paving of the other parameters' box: proved {about_text(v['proved'])}, refuted "
                              f"{about_text(v['refuted'])}, undecided {about_text(v['undecided'])} of the volume "
                              "(4 digits, to nearest)")
        c = prove_scene(s, time_limit=seconds).claim(claim)
    except ParameterError as e:
        raise ParameterError(f"{param} = {_d(value)} is outside the kind's domain: {e}") from None
    return c.status.value, c.reason


def _decide(res: "Threshold", scene: Scene, param: str, x: Fraction, claim: str, budget: Budget,
            witnesses: Witnesses | None) -> tuple[str, str]:
    """One step of the search at ``param = x``, recorded in ``res.steps``. With the other parameters as a box
    (``witnesses`` given): the kept witnesses first (a point proof refuting at one of them refutes the step),
    then the paving, then, where it is inconclusive, the corners of its undecided leaves
    (:mod:`.threshold_witness`)."""
    hit = None
    if witnesses is not None and witnesses.points:
        hit = witnesses.refute(scene, param, x, claim, None, budget)
    if hit is None:
        leaves: list = []
        more = {"leaves": leaves} if witnesses is not None else {}
        st, why = _status(scene, param, x, claim, budget.remaining(), **more)
        if witnesses is not None and st == "inconclusive" and leaves and not budget.expired():
            hit = witnesses.refute(scene, param, x, claim, leaves, budget)
    if hit is not None:
        point, reason = hit
        st, why = "refuted", (f"refuted at a point of the other parameters' box, {_point_text(point)} (point proof): "
                              f"{reason}")
        res.steps.append({"value": fraction_text(x), "status": st, "reason": why[:300], "witness": witness_json(point)})
        return st, why
    res.steps.append({"value": fraction_text(x), "status": st, "reason": why[:300]})
    return st, why


def _point_text(point: dict[str, Fraction]) -> str:
    return ", ".join(f"{k} = {_d(v)}" for k, v in sorted(point.items()))


def search_range(scene: Scene, param: str, lo: str | None, hi: str | None) -> tuple[Fraction, Fraction]:
    """The exact ends of a search along ``param`` (``--lo``/``--hi``, default half and twice the scene's
    value): rationals with lo < hi (the bisection and scan points are exact rationals); ParameterError
    otherwise."""
    def end(text, name):
        x = parse_exact(text, name)
        if not x.is_rational:
            raise ParameterError(f"{name} {text!r} involves pi: give a rational end (the search points are exact "
                                 "rationals)")
        return x.rational
    value = parse_exact(scene.parameters[param], param)
    if (lo is None or hi is None) and not value.is_rational:
        raise ParameterError(f"--param {param!r} = {scene.parameters[param]!r} involves pi: give --lo and --hi")
    v = value.rational if value.is_rational else None
    lo_q = end(lo, "--lo") if lo is not None else min(v / 2, 2 * v)
    hi_q = end(hi, "--hi") if hi is not None else max(v / 2, 2 * v)
    if not lo_q < hi_q:
        raise ParameterError(f"need --lo < --hi (got {lo_q}, {hi_q})")
    return lo_q, hi_q


def find_threshold(scene: Scene, param: str, *, lo: str | None = None, hi: str | None = None,
                   claim: str | None = None, width: str = "1e-6", time_limit: float | None = None) -> Threshold:
    """Bisect ``param`` between ``lo`` and ``hi`` (default value/2 and 2 value) for ``claim``. With
    ``time_limit`` (seconds of wall clock) the search stops when it runs out: the bracket certified so
    far is kept and the result says "time limit" (exit 3, never a refutation)."""
    try:
        budget = Budget(check_time_limit(time_limit, "time_limit"))
    except ValueError as e:
        raise ParameterError(str(e)) from None
    module = kind_module(scene.kind)
    if param not in scene.parameters:
        raise ParameterError(f"--param {param!r} is not a parameter of scene {scene.name!r}; it has "
                             f"{sorted(scene.parameters)}")
    if is_tolerance(scene.parameters[param]):
        raise ParameterError(f"--param {param!r} is written as a tolerance: write it as a number (the search "
                             "range is --lo/--hi)")
    boxed = any(is_tolerance(v) for v in scene.parameters.values())
    if boxed:
        from .paving import box_scene
        box_scene(scene)                     # the other parameters' box, validated (exit 2 if bad)
    else:
        module.validate(scene)
    default, every = scene_claims(module, scene)        # a [system] scene's own claims, not the paper kind's
    claims = list(default) if scene.claims_only is None else [c for c in every if c in scene.claims_only]
    # the kind's table names its paper's parameters; a scene writing its own model ([plant], [system], [moment])
    # depends on a parameter wherever its entries use it
    independent = {} if getattr(scene, "model", None) else getattr(module, "CLAIMS_INDEPENDENT_OF", {})
    if claim is None:           # only a scene of one claim says which; otherwise ask (a default could be
        if len(claims) != 1:    # a claim that never changes, such as a constant or a root count)
            depends = [c for c in claims if c not in independent.get(param, ())]
            raise ParameterError(f"name the claim whose change in {param!r} to bracket: --claim CLAIM; the scene's "
                                 f"claims that depend on {param!r}: {', '.join(depends)}")
        claim = claims[0]
    if claim not in every:
        raise ParameterError(f"--claim {claim!r}: scene {scene.name!r} has {list(every)}")
    if claim in independent.get(param, ()):
        raise ParameterError(f"claim {claim!r} does not depend on {param!r}: no threshold to find")
    lo_q, hi_q = search_range(scene, param, lo, hi)
    w = option_number(width, "--width", above="0", at_most="1").rational
    res = Threshold(scene, param, claim, lo_q, hi_q, w)
    witnesses = Witnesses() if boxed else None
    ends = {}
    for x in (lo_q, hi_q):
        if budget.expired():
            res.stopped = f"{budget.reason()} before the claim was decided at both ends"
            return res
        st, why = _decide(res, scene, param, x, claim, budget, witnesses)
        ends[x] = st
    if budget.expired() and "inconclusive" in ends.values():
        res.stopped = f"{budget.reason()} before the claim was decided at both ends"
        return res
    if {ends[lo_q], ends[hi_q]} != {"proved", "refuted"}:
        res.stopped = (f"the claim is {ends[lo_q]} at {param} = {_d(lo_q)} and {ends[hi_q]} at {param} = {_d(hi_q)}; "
                       "a threshold needs one proved end and one refuted end (widen --lo/--hi)")
        return res
    p, r = (lo_q, hi_q) if ends[lo_q] == "proved" else (hi_q, lo_q)
    for _ in range(MAX_STEPS):
        if abs(r - p) <= w * max(abs(p), abs(r)):
            break
        if budget.expired():
            res.stopped = f"{budget.reason()}: the bracket certified so far is kept"
            break
        m = (p + r) / 2
        st, why = _decide(res, scene, param, m, claim, budget, witnesses)
        if st == "proved":
            p = m
        elif st == "refuted":
            r = m
        elif budget.expired():
            res.stopped = f"{budget.reason()} during the proof at {param} = {_d(m)}: the bracket certified so far is kept"
            break
        else:
            moved, tried = _step_around(res, scene, param, claim, p, r, budget, witnesses)
            if moved is None:
                res.stopped = (f"the claim is inconclusive at {param} = {_d(m)} and at the {len(AROUND)} points "
                               f"around it tried: {why[:200]}" if tried == len(AROUND) else
                               f"{budget.reason()} after {tried} of the {len(AROUND)} points around {param} = "
                               f"{_d(m)}: the bracket certified so far is kept")
                break
            p, r = moved
    else:
        res.stopped = f"bisection budget of {MAX_STEPS} point proofs reached"
    res.proved_at, res.refuted_at = p, r
    return res


def _step_around(res: Threshold, scene: Scene, param: str, claim: str, p: Fraction, r: Fraction,
                 budget: Budget, witnesses: Witnesses | None = None
                 ) -> tuple[tuple[Fraction, Fraction] | None, int]:
    """After an inconclusive midpoint: the claim at the points of :data:`AROUND` between ``p`` (proved)
    and ``r`` (refuted), until one is decided. Returns the new (p, r), or None when none was decided (all
    tried, or time ran out first), and how many points were tried (each is a step of the search)."""
    for n, t in enumerate(AROUND):
        if budget.expired():
            return None, n
        x = p + (r - p) * t
        st, why = _decide(res, scene, param, x, claim, budget, witnesses)
        if st == "proved":
            return (x, r), n + 1
        if st == "refuted":
            return (p, x), n + 1
    return None, len(AROUND)


def write_threshold(res: Threshold, out_dir: str) -> list[Path]:
    from ..report import write_pair
    data = res.to_json()
    md = "\n".join([f"# {line}" if i == 0 else line for i, line in enumerate(res.lines())] + ["", "| step | "
                    f"{res.param} | status |", "|---|---|---|"] + [f"| {i} | {_d(Fraction(s['value']))} | {s['status']} |"
                                                                   for i, s in enumerate(res.steps, 1)] + [""])
    return list(write_pair(out_dir, f"margin_{res.scene.name}_{res.param}", json.dumps(data, indent=1) + "\n", md, None))


def check_threshold(data: dict[str, Any]) -> list[tuple[str, bool, str]]:
    """Re-verify a threshold output (schema ``rigor-gyro/threshold/1``, already validated against its JSON
    Schema) as (item, ok, message) triples.

    Checked: the scene, parameter and claim valid for the kind (as :func:`find_threshold` requires); the
    search range and width; the search log replayed by the bisection rule (:mod:`.threshold_log`): every
    step's value is the one the rule gives after the statuses before it, the proved and refuted points are
    where it ends and ``stopped`` is a text it writes there; the bracket, its decimals, ``certified`` and the
    statement re-derived from the proved and refuted points and the requested width (the bracket's relative
    width); the two search ends and the proved and refuted points re-decided by the prover (a point proof,
    the paving of the other parameters' box when they are tolerances, or the point proof at a stored witness),
    each status and reason as stored (an inconclusive end of a search stopped by its time limit claims
    nothing). Not re-decided: the statuses of the steps in between (the replay ties each to the values after
    it; the theorem is about the two points)."""
    out: list[tuple[str, bool, str]] = []

    def add(item: str, ok: bool, message: str) -> None:
        out.append((item, bool(ok), message))

    sc = data["scene"]
    try:
        scene = Scene.from_header(sc)
        module = kind_module(scene.kind)
        param, claim = data["param"], data["claim"]
        if param not in scene.parameters or is_tolerance(scene.parameters[param]):
            raise ParameterError(f"{param!r} is not a number parameter of the scene")
        if claim not in scene_claims(module, scene)[1]:
            raise ParameterError(f"claim {claim!r} is not one of scene {scene.name!r}")
        if any(is_tolerance(v) for v in scene.parameters.values()):
            from .paving import box_scene
            box_scene(scene)
        else:
            module.validate(scene)
    except (RigorGyroError, TypeError, ValueError, KeyError) as e:
        add("scene", False, f"the threshold's scene, parameter or claim is not valid: {e}")
        return out
    from .identity import builtin_differs
    differs = builtin_differs(sc)
    add("scene", differs is None, differs or f"scene {scene.name!r}, parameter {param!r}, claim {claim!r} valid for "
        "the kind")
    lo, hi = (Fraction(t) for t in data["search"])
    w = Fraction(data["requested_relative_width"])
    add("search", lo < hi and 0 < w <= 1, f"search [{_d(lo)}, {_d(hi)}], relative width {_d(w)}")
    steps = data["steps"]
    values = [Fraction(s["value"]) for s in steps]
    step_of = {v: s for v, s in zip(values, steps)}
    # fewer than two steps: the time limit came before both ends were decided (the replay below checks the text)
    add("steps", values[:2] == [lo, hi][:min(2, len(values))] and len(set(values)) == len(values)
        and all(lo <= v <= hi for v in values), "the steps start at the search's two ends, each value once, inside it")
    log = replay(steps, lo, hi, w, param) if lo < hi and 0 < w <= 1 else None
    if log is not None:
        ok = not log.error and log.stopped_ok(data["stopped"])
        add("search log", ok, "the steps replayed by the bisection rule: each value the rule's next point, "
            "'stopped' a text it writes there" if ok else log.error or
            f"'stopped' {str(data['stopped'])[:120]!r} is not what the search writes after these steps")
    redecided: dict[Fraction, tuple[str, str]] = {}

    def redecide(x: Fraction, want: str | None, item: str) -> None:
        """The step at ``x`` re-decided: its status (``want`` when given, else the stored one) and its reason."""
        step = step_of.get(x, {})
        stored = step.get("status")
        if want is None and stored == "inconclusive" and log is not None and log.budget_only:
            add(item, True, f"{param} = {_d(x)}: inconclusive when the time limit stopped the search (claims nothing)")
            return
        if step.get("witness") is not None:
            # a refutation at a point of the other parameters' box: inside it, and refuted there by the point prover
            w_text = step["witness"]
            point = {k: Fraction(t) for k, t in w_text.items()}
            from .paving import box_scene
            box = box_scene(scene).box if any(is_tolerance(v) for v in scene.parameters.values()) else None
            if stored != "refuted" or want == "proved" or box is None or not in_box(box, point):
                add(item, False, f"{param} = {_d(x)}: a witness {w_text} that is not a point of the other "
                    "parameters' box, or on a step that is not refuted")
                return
            if x not in redecided:
                st, why = point_status(scene, param, x, claim, point)
                redecided[x] = st, (f"refuted at a point of the other parameters' box, {_point_text(point)} "
                                    f"(point proof): {why}")[:300]
            how = f" at the witness {_point_text(point)} (point proof)"
        else:
            if x not in redecided:
                st, why = _status(scene, param, x, claim)
                redecided[x] = st, why[:300]
            how = ""
        st, why = redecided[x]
        target = want or stored
        ok = st == target == stored and step.get("reason") == why
        add(item, ok, f"{param} = {_d(x)}: re-decided {st}{how}" + (
            "" if ok else f", stored {stored} ({why[:160]})" if st != stored else
            f", but this step must be {target}" if st != target else ": the stored reason is not the re-decision's own"))

    for x in (lo, hi):
        if x in step_of:                # an end the time limit left undecided has no step to re-decide
            redecide(x, None, f"{param} = {_d(x)}")
    if data["proved_at"] is None or data["refuted_at"] is None:
        ok = (data["proved_at"] is None and data["refuted_at"] is None and data["bracket"] is None
              and data["bracket_decimal"] is None and data["statement"] is None and not data["certified"]
              and bool(data["stopped"]) and (log is None or log.proved_at is None))
        add("bracket", ok, "no bracket stated, not certified, stopped" if ok else
            "a bracket, a statement or 'certified' without both a proved and a refuted point, or no bracket where "
            "the steps give one")
        return out
    p, r = Fraction(data["proved_at"]), Fraction(data["refuted_at"])
    l, h = min(p, r), max(p, r)
    width_ok = h - l <= w * max(abs(l), abs(h))
    add("bracket", p != r and data["bracket"] == [fraction_text(l), fraction_text(h)]
        and data["bracket_decimal"] == list(interval_text(l, h)[:2])
        and data["statement"] == statement(claim, param, p, r)
        and (log is None or (log.proved_at, log.refuted_at) == (p, r))
        and step_of.get(p, {}).get("status") == "proved" and step_of.get(r, {}).get("status") == "refuted",
        "the bracket, its decimals and the statement re-derived from the proved and refuted points (where the "
        "steps of the search end)")
    add("certified", data["certified"] == (width_ok and not data["stopped"]),
        f"certified {data['certified']}: relative width {'within' if width_ok else 'above'} {_d(w)}"
        + (", stopped" if data["stopped"] else ""))
    for x, want in ((p, "proved"), (r, "refuted")):
        redecide(x, want, f"{want}_at")
    return out
