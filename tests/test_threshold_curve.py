"""Threshold curves (issue 38): the threshold of bracket (7)-lower (``bracket_1``) in eps as Omega2 moves, a
certified band per cell of Omega2. Every band is checked at sampled Omega2 of its cell by the point prover (a
path apart from the box rigour that decided it): proved at the band's proved end, refuted at its refuted end;
the checker re-paves each cell and refuses altered bands and a range the cells do not tile."""
import json
import random
from fractions import Fraction

import pytest

from rigor_gyro.check import check_file
from rigor_gyro.cli import main
from rigor_gyro.core.boxes import fraction_text
from rigor_gyro.margins.threshold_curve import find_curve, write_curve
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene

F = Fraction


@pytest.fixture(scope="module")
def curve(tmp_path_factory):
    c = find_curve(load_scene("rudenko1976"), "eps", "Omega2", lo="1", hi="1.4", along_lo="0.5", along_hi="0.7",
                   claim="bracket_1", cells=2, width="1e-2", max_depth=1)
    out = tmp_path_factory.mktemp("curve")
    write_curve(c, str(out))
    return c, out / "curve_rudenko1976_eps_Omega2.json"


def test_the_bands_reach_the_width_after_splitting_and_tile_the_range(curve):
    c, _ = curve
    assert c.certified and c.exit_code == 0
    assert [x.along for x in c.cells] == [(F(1, 2), F(11, 20)), (F(11, 20), F(3, 5)), (F(3, 5), F(13, 20)),
                                          (F(13, 20), F(7, 10))]
    lows = [x.band()[0] for x in c.cells]
    assert lows == sorted(lows)                         # the threshold rises with Omega2 here
    for x in c.cells:
        lo, hi = x.band()
        assert hi - lo <= F(1, 100) * hi and x.proved_at < x.refuted_at   # holds below, fails above


def test_each_band_holds_at_sampled_points_of_its_cell_by_the_point_prover(curve):
    c, _ = curve
    rng = random.Random(7)
    base = load_scene("rudenko1976")
    for cell in c.cells:
        for _ in range(2):
            w = cell.along[0] + (cell.along[1] - cell.along[0]) * F(rng.randint(0, 1000), 1000)
            for eps, want in ((cell.proved_at, "proved"), (cell.refuted_at, "refuted")):
                s = load_scene("rudenko1976")
                s.parameters.update(eps=fraction_text(eps), Omega2=fraction_text(w))
                s.claims_only = ["bracket_1"]
                s.paper = {}
                assert prove_scene(s).claim("bracket_1").status.value == want, (cell.along, w, eps)
    assert base.parameters["eps"] == "0.1076"


def test_the_checker_re_paves_every_cell_and_refuses_edits(curve, tmp_path):
    _, path = curve
    assert check_file(path).ok
    data = json.loads(path.read_text())
    edits = []
    d = json.loads(json.dumps(data))
    d["cells"][1]["proved_at"], d["cells"][1]["refuted_at"] = d["cells"][1]["refuted_at"], d["cells"][1]["proved_at"]
    edits.append(d)
    d = json.loads(json.dumps(data))
    d["cells"].pop(2)                                  # a gap in Omega2
    edits.append(d)
    d = json.loads(json.dumps(data))
    d["cells"][0]["band"] = [d["cells"][0]["band"][0], "2"]
    edits.append(d)
    for i, d in enumerate(edits):
        (tmp_path / f"bad{i}.json").write_text(json.dumps(d))
        assert not check_file(tmp_path / f"bad{i}.json").ok, i


def test_the_command_line_writes_and_checks_a_curve(tmp_path):
    out = tmp_path / "o"
    code = main(["margin", "rudenko1976", "--param", "eps", "--along", "Omega2", "--from", "0.5", "--to", "0.55",
                 "--cells", "1", "--max-depth", "0", "--lo", "1", "--hi", "1.4", "--claim", "bracket_1",
                 "--width", "0.05", "-o", str(out), "-q"])
    assert code == 0
    assert main(["check", "-q", str(out / "curve_rudenko1976_eps_Omega2.json")]) == 0
    assert main(["margin", "rudenko1976", "--param", "eps", "--along", "Omega2", "--from", "0.5", "--to", "0.55",
                 "--lo", "1", "--hi", "1.4"]) == 2          # no --claim
    assert main(["margin", "rudenko1976", "--param", "eps", "--from", "0.5", "--claim", "bracket_1"]) == 2
