"""The dynamics scene through the CLI: bad input is one line with exit code 2, a
film map queried outside its axes is counted and reported, and a failed
integration is exit code 1 without overwriting earlier outputs."""
from __future__ import annotations

import json

import pytest

from coupling import cli
from coupling.config import CASES_DIR, load_case
from lubrication.errors import InputError

SHORT = CASES_DIR / "cageless_6206_10krpm_short.toml"


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err, *fragments):
    assert err.startswith("lubedyn: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    for fragment in fragments:
        assert fragment in err, (fragment, err)


@pytest.mark.parametrize("overrides, fragments", [
    (["bearing.n_balls=16"], ["bearing.n_balls = 16", "do not fit the pitch circle"]),
    (["films.map=maps/ehl_ball_inner_race.npz"], ["films.map = 'maps/ehl_ball_inner_race.npz' is a map of kind",
                                                  "ball_ball is needed"]),
    (["films.ball_ball=map", "films.map=maps/nope.npz"], ["films.map = 'maps/nope.npz' not found"]),
    (["integrator.method=rk4"], ["integrator.dt", "required with method = 'rk4'"]),
    (["integrator.method=rk4", "integrator.dt='20 us'"], ["beyond the RK4 stability limit"]),
    (["operating.axial_load='200 kN'"], ["operating.axial_load = 200000 N", "beyond the groove shoulders"]),
    (["model.dof=planar"], ["operating.axial_load", "needs model.dof = '6dof'"]),
    (["analysis.ball=14"], ["analysis.ball = 14", "must be < bearing.n_balls = 14"]),
    (["operating.speed='100 m'"], ["operating.speed", "expected angular velocity"]),
])
def test_bad_input_is_one_line_exit_2(capsys, tmp_path, overrides, fragments):
    argv = ["run", SHORT, "--smoke", "--out", tmp_path / "out"]
    for o in overrides:
        argv += ["--set", o]
    code, _, err = run(capsys, *argv)
    assert code == 2
    one_line(err, *fragments)
    assert not (tmp_path / "out" / "summary.json").exists()


def test_the_main_job_runs_the_film_map_and_stays_inside_its_axes(capsys, tmp_path, caplog):
    """The shipped ball-ball map stops at pressure number 0.9 (a rigid Barus film has no solution at 1)
    and at a 50 um gap; a smoke drop with collisions (force above 100 N) queries it only inside its
    axes: thinner films are locked (the solids carry the load), thicker ones scaled self-similarly.
    Before the lock the same run clamped about 24,000 queries."""
    code, _, _ = run(capsys, "run", SHORT, "--smoke", "--set", "analysis.lyapunov_exponents=0",
                     "--set", "output.write=[]", "--out", tmp_path)
    assert code == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["Ball-ball film"] == "map" and s["Largest collision normal force [N]"] > 100.0
    assert s["Film map queries outside axes [-]"] == 0
    assert not any("queried outside their axes" in r.getMessage() for r in caplog.records)


def test_main_job_smoke_states_why_a_lyapunov_exponent_is_missing_without_a_warning(capsys, tmp_path, caplog):
    """The main job's [smoke] run (1 ms, 501 samples) is far too short for Rosenstein's method on
    ball 0 (delay ~170 samples x 5 = ~850 > 501): the summary says so per direction, and nothing is
    logged at WARNING (it used to warn on every run of the main job, smoke or not)."""
    caplog.set_level("INFO")
    code, _, err = run(capsys, "run", SHORT, "--smoke", "--set", "output.write=[]", "--out", tmp_path)
    assert code == 0, err
    assert "WARNING" not in err and not [r for r in caplog.records if r.levelname == "WARNING"]
    s = json.loads((tmp_path / "summary.json").read_text())
    for axis in "xyz":
        assert s[f"Largest Lyapunov exponent, ball 0 {axis} [1/s]"] is None
        note = s[f"Largest Lyapunov exponent, ball 0 {axis}, note"]
        assert note.startswith("not computed: the record after analysis.transient (0.001 s) has 501 samples: too short")
    assert s["Lyapunov exponent 1, whole system (Benettin) [1/s]"] > 0.0  # the whole-system exponents still come


def test_rosenstein_shortfall_agrees_with_the_estimator():
    """The reason the scene writes is the estimator's own check: a record it accepts gives '', one it
    refuses gives the refusal's text."""
    import numpy as np

    from dynamics.errors import DynamicsInputError
    from dynamics.lyapunov import largest_lyapunov_rosenstein, rosenstein_shortfall

    t = np.arange(4000) * 1e-3
    x = np.sin(2 * np.pi * 7.0 * t) + 0.3 * np.sin(2 * np.pi * 7.0 * np.sqrt(2.0) * t)
    assert rosenstein_shortfall(x, 1e-3, dim=4, delay=10) == ""
    short = x[:300]
    reason = rosenstein_shortfall(short, 1e-3, dim=4, delay=30)
    assert reason.startswith("300 samples: too short for dim = 4, delay = 30")
    with pytest.raises(DynamicsInputError, match="too short") as info:
        largest_lyapunov_rosenstein(short, 1e-3, dim=4, delay=30)
    assert str(info.value) == f"x has {reason}"


def test_case_tables_are_the_model_groups_one_to_one():
    """Every table of a dynamics case is one frozen group of the model with the same field names (the
    group may hold more: numerical settings the case leaves at their defaults), every required field of a
    group is a key of its table, and a model error from a case names the case key without translation."""
    import dataclasses

    from coupling import dynamics_scene as ds
    from dynamics.cageless import CagelessBearing

    for table, attr in ds.GROUP_OF_TABLE.items():
        group = {f.name: f for f in dataclasses.fields(CagelessBearing)}[attr].type
        cls = getattr(__import__("dynamics.cageless.groups", fromlist=[group]), group)
        assert cls.TABLE == table
        keys = set(ds.DynamicsCase.model_fields[table].annotation.model_fields)
        names = {f.name: f for f in dataclasses.fields(cls)}
        assert keys <= set(names), (table, keys - set(names))
        required = {n for n, f in names.items() if f.default is dataclasses.MISSING}
        assert required <= keys, (table, required - keys)
    case = load_case(CASES_DIR / "cageless_6206_steady.toml")
    model = ds.build(case).model
    assert model.slots.width == case.slots.width and model.fidelity.dof == case.model.dof
    assert model.films.ball_ball == case.films.ball_ball == "map" and model.films.map is not None
    with pytest.raises(InputError, match=r"^slots.width = 0.01 m must be < the groove diameter"):
        ds.build(case.model_copy(update={"slots": case.slots.model_copy(update={"width": 0.01})}))
