"""The Lyapunov kind over a box of parameters (``kinds/lyapunov/boxes.py``), piece by piece.

:class:`BoxGimbal` must give parameter balls that contain A0 = A + A1 + A2, B0 = A + B1, C0 = A + A1 - C1,
H, k, a, mu at *every* point of the box (checked at all its corners, where these sums take their extremes,
and at random points) and be no wider than the box makes them; ``validate_box`` must reject each domain
condition failing anywhere in the box, on its lower end, naming the parameter; ``evaluate_box`` must hand
the claims a model of the box (no paper audit, the piece budget capped) and read their statuses as box
statuses, checked here against the closed-form damping threshold k = mu A0 on both sides.
"""
import dataclasses
import itertools
import random
from fractions import Fraction

import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.boxes import Box
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.kinds.lyapunov import boxes as B
from rigor_gyro.kinds.lyapunov.claims import validate
from rigor_gyro.scene import load_scene

F = Fraction


@pytest.fixture
def model():
    return validate(load_scene("agafonov2013"))


def _point(model) -> dict[str, Fraction]:
    return {k: F(model.params[k].rational) for k in B.BOX_PARAMETERS}


def _box(model, rel: Fraction, names=B.BOX_PARAMETERS) -> Box:
    """Every parameter of NAMES widened by the relative tolerance REL about the scene's value."""
    p = _point(model)
    return Box.of({k: (p[k] * (1 - rel), p[k] * (1 + rel)) if p[k] else (F(0), rel) for k in names})


def _derived(v: dict[str, Fraction]) -> dict[str, Fraction]:
    return {"A0": v["A"] + v["A1"] + v["A2"], "B0": v["A"] + v["B1"], "C0": v["A"] + v["A1"] - v["C1"],
            "H": v["H"], "k": v["k"], "a": v["a"], "mu": v["mu"]}


def _q(x: Fraction) -> arb:
    return arb(fmpq(x.numerator, x.denominator))


def test_the_box_balls_contain_every_point_of_the_box_and_no_more(model):
    box = _box(model, F(1, 10))
    g = B.BoxGimbal(model.gimbal, B._raw(model, box))
    names = box.names
    corners = [_derived(dict(zip(names, c))) for c in itertools.product(*(box.interval(k) for k in names))]
    rng = random.Random(5)
    inner = [_derived({k: lo + (hi - lo) * F(rng.randint(0, 1000), 1000) for k, lo, hi in box.edges}) for _ in range(50)]
    with working_precision(64):
        c = g.c
        balls = {"A0": c.A0, "B0": c.B0, "C0": c.C0, "H": c.H, "k": c.k, "a": c.a, "mu": c.mu}
        for name, ball in balls.items():
            values = [v[name] for v in corners + inner]
            assert ball.is_finite() and all(ball.contains(_q(x)) for x in values), name
            lo, hi = min(values), max(values)           # the extremes are at corners (each is a sum)
            slack = (hi - lo) / 10 ** 6 + abs(hi) / 10 ** 15
            assert ball.lower() >= _q(lo - slack) and ball.upper() <= _q(hi + slack), (name, ball, lo, hi)
        assert c.x2_star.is_finite() and c.x2_star.overlaps(arb.pi() / 6) and c.x2_star.rad() < arb(2) ** -60


def test_parameters_outside_the_box_stay_at_their_scene_values(model):
    box = _box(model, F(1, 10), names=("k",))
    raw = B._raw(model, box)
    p = _point(model)
    assert set(raw) == set(B.BOX_PARAMETERS)
    assert raw["k"] == box.interval("k")
    assert all(raw[k] == (p[k], p[k]) for k in raw if k != "k")
    g = B.BoxGimbal(model.gimbal, raw)
    with working_precision(64):
        assert g.c.H.is_finite() and g.c.H.contains(_q(p["H"])) and g.c.H.rad() < arb(2) ** -50 * g.c.H
        assert g.c.k.is_finite() and g.c.k.contains(_q(F(36, 100))) and g.c.k.contains(_q(F(44, 100)))


def test_the_balls_are_cached_per_precision(model):
    g = B.BoxGimbal(model.gimbal, B._raw(model, _box(model, F(1, 3))))
    with working_precision(64):
        c64 = g.c
        assert g.c is c64
    with working_precision(256):
        c256 = g.c
        assert c256 is not c64 and c256.x2_star.rad() < c64.x2_star.rad() * arb(2) ** -150


def test_best_mu_is_not_decided_over_a_box(model):
    g = B.BoxGimbal(model.gimbal, B._raw(model, _box(model, F(1, 10))))
    with pytest.raises(NotImplementedError, match="best_mu"):
        g.with_mu(fmpq(1, 50))


@pytest.mark.parametrize("name", ["A", "C", "H", "k", "a", "mu"])
def test_a_parameter_that_must_be_positive_is_rejected_when_its_box_reaches_zero(model, name):
    p = _point(model)
    B.validate_box(model, Box.of({name: (p[name] / 10 ** 9, p[name])}))       # just above 0: accepted
    with pytest.raises(ParameterError, match=rf"parameter '{name}': need {name} > 0 .*lower end is 0"):
        B.validate_box(model, Box.of({name: (F(0), p[name])}))


@pytest.mark.parametrize("name", ["A1", "B1", "C1", "A2"])
def test_an_inertia_that_must_be_nonnegative_is_rejected_when_its_box_goes_below_zero(model, name):
    p = _point(model)
    B.validate_box(model, Box.of({name: (F(0), p[name])}))                   # 0 allowed
    with pytest.raises(ParameterError, match=rf"parameter '{name}': need {name} >= 0"):
        B.validate_box(model, Box.of({name: (F(-1, 10 ** 9), p[name])}))


def test_a0_above_c0_is_required_on_the_whole_box(model):
    B.validate_box(model, Box.of({"A2": (F(0), F(1)), "C1": (F(1, 10 ** 9), F(1))}))
    B.validate_box(model, Box.of({"A2": (F(1, 10 ** 9), F(1)), "C1": (F(0), F(1))}))
    with pytest.raises(ParameterError, match="A2 \\+ C1 > 0"):
        B.validate_box(model, Box.of({"A2": (F(0), F(1)), "C1": (F(0), F(1))}))


@pytest.mark.parametrize("name", ["x2_star", "moment", "R"])
def test_only_the_rational_parameters_take_a_tolerance(model, name):
    with pytest.raises(ParameterError, match=rf"parameter '{name}'.*only for.*single value"):
        B.validate_box(model, Box.of({"k": (F(3, 10), F(4, 10)), name: (F(1, 2), F(1))}))


def _evaluated(model, monkeypatch, **changes):
    """The model evaluate_box hands to ``attempt`` (recorded, not run)."""
    seen = {}

    def fake(m, claims, prec):
        seen.update(model=m, claims=claims, prec=prec)
        raise RuntimeError("recorded")
    monkeypatch.setattr(B, "attempt", fake)
    with working_precision(96), pytest.raises(RuntimeError, match="recorded"):
        B.evaluate_box(dataclasses.replace(model, **changes), _box(model, F(1, 100), ("k",)), ["v_positive"])
    return seen


def test_evaluate_box_runs_the_claims_on_the_box_model_without_the_audit(model, monkeypatch):
    seen = _evaluated(model, monkeypatch, max_pieces=10 ** 6)
    m = seen["model"]
    assert isinstance(m.gimbal, B.BoxGimbal) and m.gimbal.raw["k"] == _box(model, F(1, 100), ("k",)).interval("k")
    assert m.paper == {} and m.max_pieces == B.BOX_MAX_PIECES and seen["prec"] == 96
    assert seen["claims"] == ["v_positive"]
    assert _evaluated(model, monkeypatch, max_pieces=10)["model"].max_pieces == 10


def test_evaluate_box_takes_only_the_box_claims(model):
    with pytest.raises(ParameterError, match="cannot be decided over a box"):
        B.evaluate_box(model, _box(model, F(1, 100), ("k",)), ["best_mu"])
    assert set(B.BOX_CLAIMS) == {"damping_condition", "vdot_nonpositive", "v_positive"}


@pytest.mark.parametrize("k, want", [((F(2, 10), F(25, 100)), "refuted"), ((F(26, 100), F(3, 10)), "proved"),
                                     ((F(25, 100), F(26, 100)), "undecided")])
def test_damping_over_a_box_of_k_against_the_threshold_k_equal_mu_a0(model, k, want):
    """(16) holds exactly for k > mu A0 = 0.02 x 12.7 = 0.254: a box below is refuted, one above proved, one
    across undecided (never proved nor refuted: the box holds both)."""
    with working_precision(64):
        out = B.evaluate_box(model, Box.of({"k": k}), ["damping_condition"])
    assert set(out) == {"damping_condition"}
    status, reason = out["damping_condition"]
    assert status == want, reason


def test_the_claims_read_the_parameters_only_through_their_balls():
    """Why the box is sound: :class:`BoxGimbal` overrides ``c`` (and ``with_mu``), so every function that
    reads a parameter through ``g.c`` sees the whole box. A read of the exact scene value (``self.H`` in a
    Gimbal method other than those two, ``g.mu`` in a rigorous module) would be decided at the scene's
    point only, and the box's ``proved`` would be false. (The paper audit, ``paper.py``, is never run
    over a box; ``approx.py`` is the float side.)"""
    import ast
    import pathlib
    params = {"A0", "B0", "C0", "H", "k", "a", "mu"}
    root = pathlib.Path(B.__file__).parent
    bad = []
    for path in sorted(root.glob("*.py")):
        if path.name in ("approx.py", "paper.py", "plots.py", "campaign.py"):
            continue
        tree = ast.parse(path.read_text())
        allowed = set()         # the Gimbal methods that may read self.<parameter>
        for cls in (n for n in ast.walk(tree) if isinstance(n, ast.ClassDef) and n.name == "Gimbal"):
            allowed |= {id(m) for m in cls.body if isinstance(m, ast.FunctionDef) and m.name in ("c", "with_mu")}
        inside_allowed = {id(n) for m in ast.walk(tree) if id(m) in allowed for n in ast.walk(m)}
        for n in ast.walk(tree):
            if (isinstance(n, ast.Attribute) and n.attr in params and isinstance(n.value, ast.Name)
                    and n.value.id in ("self", "g", "gb", "gimbal", "base") and id(n) not in inside_allowed):
                if n.value.id == "base" and path.name == "boxes.py":
                    continue            # BoxGimbal hands the base's fields to Gimbal.__init__ (never read)
                if n.value.id == "self" and path.name != "model.py":
                    continue            # other classes' own fields
                bad.append(f"{path.name}:{n.lineno} {n.value.id}.{n.attr}")
    assert not bad, bad
