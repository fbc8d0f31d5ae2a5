"""A scene's own model table ([plant], [system], [moment]; issue 42): kept as written, carried into the
certificate's scene block, one table per kind, no TOML floats."""
import pytest

from rigor_gyro.core.errors import ParameterError, SceneError
from rigor_gyro.scene import MODEL_TABLES, Scene, parse_scene

HEAD = "name = 'own'\nkind = '{kind}'\n[parameters]\nH = '3/2'\n"


@pytest.mark.parametrize("kind,table", sorted(MODEL_TABLES.items()))
def test_model_table_kept_and_round_trips(kind, table):
    text = HEAD.format(kind=kind) + f"[{table}]\nM = [['0', '1'], ['-1', '-H']]\ne = ['0', 1]\n"
    s = parse_scene(text)
    assert s.model == {"M": [["0", "1"], ["-1", "-H"]], "e": ["0", "1"]}
    header = s.header()
    assert header["model"] == s.model
    assert Scene.from_header(header).model == s.model


def test_no_model_table_leaves_the_header_as_before():
    s = parse_scene(HEAD.format(kind="lyapunov"))
    assert s.model == {} and "model" not in s.header()


def test_another_kinds_table_is_refused():
    with pytest.raises(SceneError, match=r"\[system\] is a model table of another kind.*\[plant\]"):
        parse_scene(HEAD.format(kind="periodic_orbit") + "[system]\nM = [['1']]\n")


def test_floats_and_odd_values_are_refused():
    with pytest.raises(ParameterError, match="TOML float"):
        parse_scene(HEAD.format(kind="periodic_orbit") + "[plant]\nM = [[1.5]]\n")
    with pytest.raises(SceneError, match="expected a quoted exact number"):
        parse_scene(HEAD.format(kind="periodic_orbit") + "[plant]\nM = [[true]]\n")


def test_header_with_model_validates_against_the_certificate_schema():
    import json
    from importlib import resources

    import jsonschema
    schema = json.loads((resources.files("rigor_gyro") / "schemas" / "certificate-2.schema.json").read_text())
    sub = schema["properties"]["scene"]
    sub = {**sub, "$defs": schema["$defs"]}
    s = parse_scene(HEAD.format(kind="eigenfrequencies") + "[system]\nM = [['1', '0'], ['0', '1']]\n")
    jsonschema.validate(s.header(), sub)
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate({**s.header(), "model": {"M": [[1]]}}, sub)


def test_a_model_table_travels_to_the_workers_with_the_options():
    """The margins' worker tasks receive one settings string: the kind's options and the scene's model table."""
    import json

    from rigor_gyro.margins.models import MODEL_KEY, settings_json, task_scene
    model = {"M": [["0", "1"], ["-1", "-H"]]}
    text = settings_json({"rel_width": "1e-9"}, model)
    s = task_scene("p", "periodic_orbit", "t", {"H": "1"}, text, ["stable"])
    assert s.model == model and s.options == {"rel_width": "1e-9"} and s.claims_only == ["stable"]
    plain = settings_json({"rel_width": "1e-9"}, {})
    assert MODEL_KEY not in json.loads(plain) and task_scene("p", "lyapunov", "", {}, plain).model == {}


def test_a_user_model_with_a_tolerance_is_paved_and_checked(tmp_path):
    """A [system] scene with a tolerance goes through the margins layer with its own model (not the paper's
    parameterisation) and its own default claims; the checker re-evaluates it the same way."""
    import re
    from importlib import resources

    from rigor_gyro.cli import main
    text = (resources.files("rigor_gyro") / "scenes" / "rudenko1976_system.toml").read_text()
    text = text.replace('eps = "0.1076"', 'eps = "0.1076 +- 0.001"').replace('name = "rudenko1976_system"',
                                                                          'name = "system_box"')
    text = re.sub(r'\[claims\]\nonly = \[[^\]]*\]\n', "", text)
    (tmp_path / "s.toml").write_text(text)
    assert main(["prove", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o"), "-q", "-j", "1"]) == 0
    md = (tmp_path / "o" / "system_box.md").read_text()
    assert "| roots | **proved** |" in md
    assert main(["check", "-q", str(tmp_path / "o" / "system_box.json")]) == 0
