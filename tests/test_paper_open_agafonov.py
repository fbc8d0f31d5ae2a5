"""Agafonov's audit rows for what the paper mislabels or leaves open (kinds/lyapunov/paper_open.py, issue 39):
rho1 at the scene's mu and the best mu of (13)-(14) against mpmath, region (17)'s exit against solve_ivp, the
label slips present."""
from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from flint import arb, fmpq

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.outcome import AuditStatus
from rigor_gyro.kinds.lyapunov.approx import AGAFONOV2013, MpGimbal, _r12, mp_constants
from rigor_gyro.kinds.lyapunov.claims import gimbal_from_parameters
from rigor_gyro.kinds.lyapunov.closed_forms import closed_form_constants
from rigor_gyro.kinds.lyapunov.paper_open import best_formula_mu_row, invariance_row, label_rows, rho1_row

DPS = 30


def _mpf(x: arb):
    return mpmath.mpf(x.mid().str(40, radius=False))


@pytest.fixture(scope="module")
def scene():
    g = gimbal_from_parameters(AGAFONOV2013)[0]
    mp = mp_constants(AGAFONOV2013, dps=DPS, with_best_mu=False)
    return g, mp


def _balls(mp, names):
    return [arb(mpmath.nstr(mp[n], 25)) * arb(1, arb("1e-20")) for n in names]


def test_rho1_row_holds_mpmath_radius_and_is_above_r1(scene):
    g, mp = scene
    with working_precision(64):
        k = closed_form_constants(g, *_balls(mp, ("m", "M")))
        row = rho1_row(g, g.c.x2_star, k["R1"], "0.018", 2000)
    assert row.status is AuditStatus.CONFIRMED
    with mpmath.workdps(DPS):
        mg = MpGimbal(AGAFONOV2013)

        def rho(x2):
            (c10, c11, c13), _ = mg.psi_true(x2)
            return mpmath.hypot(c11, c13) / c10
        xs = mg.xs
        grid = max(rho(xs * i / 400) for i in range(1, 401))
        exact = 1 / grid                                   # the grid's max is at x2* here (a grid point)
        lo, hi = _mpf(row.value.lower()), _mpf(row.value.upper())
        assert lo <= exact <= hi, (lo, exact, hi)
        assert exact > mp["R1"]


def test_best_mu_of_13_14_brackets_mpmath_maximum_of_min_r1_r2(scene):
    g, mp = scene
    with working_precision(64):
        m, M, lo, hi = _balls(mp, ("m", "M", "mu_min", "mu_max"))
        row = best_formula_mu_row(g, m, M, lo, hi)
    assert row.status is AuditStatus.CONFIRMED
    with mpmath.workdps(DPS):
        def R(mu, which):
            return _r12(MpGimbal(dict(AGAFONOV2013, mu=mpmath.nstr(mu, 28))), mp["m"])[which]
        mu_star = mpmath.findroot(lambda x: R(x, "R1") - R(x, "R2"), mpmath.mpf("0.0224"))
        best = R(mu_star, "R1")
        # the maximum of min(R1, R2) is at the crossing: R1 falls and R2 rises there (sampled)
        for d in ("-1e-4", "1e-4"):
            x = mu_star + mpmath.mpf(d)
            assert min(R(x, "R1"), R(x, "R2")) < best
        stated_hi = mpmath.mpf(row.note.split("gives more than ")[1].split(" ")[0])
        assert _mpf(row.value.lower()) <= best <= stated_hi
        assert (stated_hi - best) / best < 1e-8


def test_region_17_exit_is_confirmed_by_solve_ivp(scene):
    from scipy.integrate import solve_ivp
    from rigor_gyro.kinds.lyapunov.approx import FloatGimbal
    g, _ = scene
    R = Fraction("0.018")
    with working_precision(64):
        row = invariance_row(g, arb(fmpq(R.numerator, R.denominator)), g.c.x2_star, "0.018")
    assert row.status is AuditStatus.REFUTED
    start = Fraction(row.note.split("(x1, x2, x3) = (")[1].split(",")[0])
    t_end = Fraction(row.note.split(" at t = ")[1].split(" ")[0])
    fg = FloatGimbal(AGAFONOV2013)
    sol = solve_ivp(lambda t, y: list(fg.rhs3(*y)), (0, float(t_end)), [float(start), 0.0, 0.0], rtol=1e-11, atol=1e-14)
    x1, _, x3 = sol.y[:, -1]
    assert x1 * x1 + x3 * x3 > float(R) ** 2


def test_the_label_slips_are_rows():
    assert {r.id for r in label_rows()} == {"label (13)", "label (6)", "label Psi2"}
    assert all(r.status is AuditStatus.MISPRINT for r in label_rows())


@pytest.mark.parametrize("change", [{"k": "0.2"}, {"x2_star": "1.3"}])
def test_no_undecided_row_where_no_precision_could_decide_one(change):
    """k = 0.2: c10 < 0 at x2 = 0 (no radius has Psi1 > 0, no rho1 row); x2* = 1.3: (16) empty (no best-mu row).
    Undecided rows there escalated every claim of the scene to 4096 bits (minutes) for nothing."""
    import re
    from importlib.resources import files

    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import parse_scene
    text = (files("rigor_gyro") / "scenes" / "agafonov2013.toml").read_text(encoding="utf-8")
    for k, v in change.items():
        text = re.sub(rf'^{k} = ".*"', f'{k} = "{v}"', text, flags=re.M)
    cert = prove_scene(parse_scene(text))
    ids = {r.id: r.status for r in cert.paper}
    assert AuditStatus.UNDECIDED not in ids.values(), ids
    assert ("rho1 at mu" in ids) == ("k" not in change)
    assert ("best mu of (13)-(14)" in ids) == ("x2_star" not in change)


def test_no_invariance_row_and_no_exit_claimed_where_the_trajectory_stays():
    """H = 10, a = 1e4 (slow dynamics): the audit's trajectory from the edge of (17) does not leave within its steps:
    no row (it escalated the scene to 4096 bits), and the region rows do not say a trajectory leaves."""
    import re
    from importlib.resources import files

    from rigor_gyro.prover import prove_scene
    from rigor_gyro.scene import parse_scene
    text = (files("rigor_gyro") / "scenes" / "agafonov2013.toml").read_text(encoding="utf-8")
    for k, v in {"H": "10", "a": "1e4", "mu": "0.01", "k": "0.1"}.items():
        text = re.sub(rf'^{k} = ".*"', f'{k} = "{v}"', text, flags=re.M)
    rows = {r.id: r for r in prove_scene(parse_scene(text)).paper}
    assert "(17) positively invariant" not in rows
    assert all("trajectory leaves" not in r.note for r in rows.values())
    assert AuditStatus.UNDECIDED not in {r.status for r in rows.values()}
