"""A scene's own moment law (issue 42 part 2) is not the paper's model: its report does not audit the paper's
section-2 statements about a sin x2 and its linearisation (the built-in laws keep those rows)."""
from rigor_gyro.prover import prove_scene
from rigor_gyro.scene import load_scene

SECTION_2 = {"(4) linearised system", "Vdot of (5) along (4)", "linear setting: p = M = A0 m = a"}


def _audit_ids(name: str) -> set[str]:
    cert = prove_scene(load_scene(name))
    return {r.id for r in cert.paper}


def test_a_scene_s_own_law_is_not_audited_against_the_paper_s_section_2():
    assert not SECTION_2 & _audit_ids("agafonov2013_sine_cubic")


def test_the_paper_s_law_keeps_its_section_2_rows():
    assert "linear setting: p = M = A0 m = a" in _audit_ids("agafonov2013")
