"""The scenes' one interface and one registry (lubedyn.scenes): every registered scene implements the
protocol; the case loader, the runner and ``lubedyn.run`` find scenes through the registry only."""
import inspect

import pytest

import lubedyn
from lubedyn import scenes
from lubedyn.config import CaseError, case_model, load_case, load_case_text
from lubedyn.lubrication.errors import InputError
from lubedyn.scenes import runner


@pytest.mark.parametrize("name", sorted(scenes.SCENES))
def test_every_registered_scene_implements_the_protocol(name):
    module = scenes.get(name)
    assert isinstance(module, scenes.Scene)
    assert module.__name__ == scenes.SCENES[name] == f"lubedyn.scenes.{name}"
    assert case_model(name) is module.CaseModel
    run = inspect.signature(module.run)
    assert list(run.parameters)[:2] == ["case", "out_dir"] and run.parameters["out_dir"].default is None
    assert {"name", "source", "smoke"} <= {p.name for p in run.parameters.values()
                                          if p.kind is inspect.Parameter.KEYWORD_ONLY}
    assert all(isinstance(f, str) and isinstance(k, str) for f, k in module.FIELD_FILES)


def test_an_unknown_scene_is_one_line_with_the_choices():
    with pytest.raises(InputError, match=r"scene = 'flim' is not allowed; choose one of 'film', .*did you mean 'film'"):
        scenes.get("flim")
    with pytest.raises(CaseError, match=r"scene = 'flim' is not allowed; choose one of 'film'"):
        load_case_text('scene = "flim"\n')


def test_a_bundled_case_loads_by_name_and_runs_through_the_registry():
    """``load_case`` takes a bundled case's name as the CLI does; ``lubedyn.run`` is the runner's ``run``;
    the smoke inclined slider's load per unit width is the closed form 6 eta u L^2/s^2 (ln((H+1)/H) -
    2/(1+2H)), s = h_in - h_out the shoulder height and H = h_out/s (Hamrock, Schmid & Jacobson,
    Fundamentals of Machine Elements / Fluid Film Lubrication, the fixed-incline slider bearing), to the
    discretisation error of its smoke mesh (10 P2 elements)."""
    import math

    case = load_case("inclined_slider", smoke=True)
    assert lubedyn.run is runner.run
    w = lubedyn.run(case).summary["Load per unit width [N/m]"]
    g, eta, u = case.gap, case.lubricant.viscosity.eta0, case.motion.velocity_lower[0]
    s = g.h_in - g.h_out
    h = g.h_out / s
    exact = 6 * eta * u * g.length ** 2 / s ** 2 * (math.log((h + 1) / h) - 2 / (1 + 2 * h))
    assert w == pytest.approx(exact, rel=1e-3)
