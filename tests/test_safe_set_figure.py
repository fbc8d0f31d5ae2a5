"""The safe-set figure, the choice of axes and the figure formats (rigor_gyro.margins.plots)."""
import pytest

from rigor_gyro.core.balls import working_precision
from rigor_gyro.core.errors import ParameterError
from rigor_gyro.margins.safe_set import from_paving

pytest.importorskip("matplotlib")
from rigor_gyro.margins.plots import BOX_GID, build_paving_figure, build_safe_set_figure, paving_plots  # noqa: E402


def _boxes(fig):
    return next(c for c in fig.axes[0].collections if c.get_gid() == BOX_GID)


def test_the_safe_set_figure_draws_every_piece_and_states_the_yield():
    from tests.test_paving_check import _mixed
    data = _mixed()
    with working_precision(128):
        safe = from_paving(data, laws_text="normal 3")
    fig = build_safe_set_figure(data, safe)
    assert len(_boxes(fig).get_paths()) == len(safe["pieces"])
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert any(t.startswith("yield (") and f"[{safe['yield']['lower']}, {safe['yield']['upper']}]" in t for t in labels)
    assert any(f"[{safe['volume']['lower']}, {safe['volume']['upper']}]" in t for t in labels)


def test_axes_are_chosen_by_name_and_a_wrong_name_is_bad_input(tmp_path):
    from tests.test_paving_check import _proved
    data = _proved()
    names = list(data["box"])
    assert len(names) == 2
    fig = build_paving_figure(data, data["claims"][0], axes=(names[-1], names[0]))
    assert fig.axes[0].get_xlabel() == names[-1] and fig.axes[0].get_ylabel() == names[0]
    for bad in (("nope",), (names[0], names[0]), tuple(names) + ("x",)):
        with pytest.raises(ParameterError):
            build_paving_figure(data, data["claims"][0], axes=bad)
    paths = paving_plots(data, tmp_path, formats=("svg", "pdf"))
    assert sorted(p.suffix for p in paths) == [".pdf", ".pdf", ".svg", ".svg"] and all(p.stat().st_size > 0 for p in paths)
    with pytest.raises(ParameterError):
        paving_plots(data, tmp_path, formats=("gif",))
