"""What the library finds wrong with a result or an input
reaches the user from Python as well as from the CLI, once, in one line.

- a film map whose accuracy report exceeds its tolerance (lubedyn.maps.ACCURACY_TOLERANCE, 3 %, or the
  build's ``accuracy_tolerance``) logs one WARNING when built and when loaded, naming the map, the output,
  the worst error, where, and the tolerance; the map scene lists it under "Warnings" in summary.json;
- a JFO film with a negative fluid fraction, solved from Python, logs its WARNING and lists it in
  ``solution.warnings``; the film scene reuses that (one line, not two);
- a text file given as ``films.map`` is a one-line InputError naming the key, the file and what is
  expected, without numpy's advice to unpickle it;
- a periodic film mesh of more than 1000 vertices gives scikit-fem nothing to log ("Transforming over
  1000 vertices to C_CONTIGUOUS.").
"""
from __future__ import annotations

import json
import logging
import math

import numpy as np
import pytest

from lubedyn import cli, maps
from lubedyn.config import CASES_DIR
from lubedyn.maps import FilmMap, build_map
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.errors import InputError


class _Axis:  # the AxisDef protocol of lubedyn.film_points (duck-typed by lubedyn.maps)
    def __init__(self, name, lo, hi, n, scale):
        self.name, self.lo, self.hi, self.n, self.scale = name, lo, hi, n, scale


class _Kind:
    def __init__(self, name, axes, outputs, evaluate, default_params):
        self.name, self.axes, self.outputs, self.evaluate = name, axes, outputs, evaluate
        self.default_params, self.field, self.description = default_params, None, "a bump on 3 nodes"


def _bump(params, point):
    """1 + a Gaussian bump of width 0.1 at x = 0.4: three nodes on [0, 1] cannot interpolate it."""
    x = point["Position [m]"]
    return {"Value [N]": 1.0 + params["height"] * math.exp(-(((x - 0.4) / 0.1) ** 2)), "Flat [N]": 2.0 + 0 * x}


BUMP = _Kind("test_health_bump", (_Axis("Position [m]", 0.0, 1.0, 3, "linear"),), ("Value [N]", "Flat [N]"), _bump,
             lambda: {"height": 1.0})
maps.register_kind(BUMP)


def _warnings(caplog, fragment=""):
    return [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING and fragment in r.getMessage()]


def test_map_above_its_accuracy_tolerance_warns_when_built_and_when_loaded(tmp_path, caplog):
    """The bump map's interpolation misses by tens of percent: one WARNING at the build and one at every
    load, naming the map, the output (not the flat one, exact), its worst error and point, and the 3 %
    tolerance; a build that states a larger tolerance stores it and stays quiet, also when loaded."""
    caplog.set_level(logging.WARNING)
    fmap = build_map("test_health_bump", workers=1, progress=False, accuracy_points=8, seed=1,
                     cache_dir=tmp_path / "cache")
    rep = fmap.accuracy["Value [N]"]
    assert rep["max"] > 0.1 and fmap.accuracy["Flat [N]"]["max"] == 0.0 and fmap.accuracy["tolerance"] == 0.03
    [built] = _warnings(caplog)
    cached = next((tmp_path / "cache").glob("test_health_bump-*.npz"))
    assert built.startswith(f"map file {str(cached)!r}: interpolation error above the map's accuracy tolerance 3 %")
    assert f"Value [N] up to {100 * rep['max']:.3g} % at (Position [m] = {rep['worst point'][0]:.4g})" in built
    assert "Flat" not in built and "\n" not in built
    caplog.clear()
    path = fmap.save(tmp_path / "bump.npz")
    again = FilmMap.load(path)
    [loaded] = _warnings(caplog)
    assert loaded.startswith(f"map file {str(path)!r}: interpolation error above") and "Value [N] up to" in loaded
    assert again.accuracy_warning() is not None and FilmMap.load(path, check=False) is not None
    assert len(_warnings(caplog)) == 1
    # the build from the cache warns once more, judged against the tolerance that build states
    caplog.clear()
    loose = build_map("test_health_bump", workers=1, progress=False, accuracy_points=8, seed=1,
                      cache_dir=tmp_path / "cache", accuracy_tolerance=0.9)
    assert loose.provenance.get("loaded from cache") and loose.accuracy["tolerance"] == 0.9
    loose.save(tmp_path / "loose.npz")
    FilmMap.load(tmp_path / "loose.npz")
    assert _warnings(caplog) == []
    with pytest.raises(InputError, match="accuracy_tolerance = 0 must be a relative error > 0"):
        build_map("test_health_bump", workers=1, progress=False, accuracy_points=2, accuracy_tolerance=0)


def test_shipped_maps_meet_their_tolerance_and_would_name_their_worst_output():
    """Every bundled map loads without an accuracy warning (3 %); the ball-ball map's worst output is its
    damping at 2.98 %, which a 2 % tolerance would report with its point."""
    for path in sorted((CASES_DIR / "maps").glob("*.npz")):
        fmap = FilmMap.load(path, check=False)
        assert fmap.accuracy_tolerance == 0.03 and fmap.accuracy_warning() is None, path.name
    ball = FilmMap.load(CASES_DIR / "maps" / "ball_ball.npz", check=False)
    ball.accuracy["tolerance"] = 0.02
    text = ball.accuracy_warning("cases/maps/ball_ball.npz")
    assert text.startswith("cases/maps/ball_ball.npz: interpolation error above the map's accuracy tolerance 2 %: "
                           "Damping [N s/m] up to 2.98 % at (Central gap [m] = 7.206e-07, Pressure number [-] = "
                           "0.002299, Squeeze angle [rad] = -1.346), median 0.57 % of 40 points; ")


MAP_CASE = """
scene = "map"
kind = "test_health_bump"
[build]
workers = 1
accuracy_points = 6
[output]
write = ["map"]
"""


def test_map_scene_lists_the_accuracy_warning_in_its_summary(tmp_path, capsys):
    """Through the CLI: one WARNING line on stderr naming the written map file, the same line under
    "Warnings" in summary.json, and the tolerance in the summary."""
    case = tmp_path / "bump.toml"
    case.write_text(MAP_CASE)
    assert cli.main(["run", str(case), "--out", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    [text] = s["Warnings"]
    assert text.startswith(f"map file {str(tmp_path / 'out' / 'test_health_bump.npz')!r}: interpolation error above "
                           "the map's accuracy tolerance 3 %: Value [N] up to")
    assert s["Accuracy tolerance [-]"] == 0.03
    lines = [line for line in err.splitlines() if "interpolation error above" in line]
    assert len(lines) == 1 and lines[0].startswith("lubedyn: WARNING: ") and lines[0].endswith(text)


def test_jfo_negative_fluid_fraction_is_logged_from_python(caplog):
    """The journal of tests/test_film_stop_reasons.py with JFO cavitation, its centre moving along -x at
    0.2 m/s on 64 x 16 P1, "converges" with a fluid fraction down to -0.27: lubedyn.lubrication.solve logs the
    line (WARNING) and the solution lists it; the film without the motion (theta >= 0.106) logs nothing.
    The film scene reuses the solution's line: logged once, listed in its summary."""
    from test_film_stop_reasons import journal_jfo

    caplog.set_level(logging.WARNING)
    bad = journal_jfo(64, 16, -0.2).solve()
    [text] = _warnings(caplog, "Fluid fraction")
    assert text.startswith("Fluid fraction down to -0.26") and "JFO allows [0, 1]" in text
    assert bad.warnings == [text] and bad.info["warnings"] == [text]
    caplog.clear()
    good = journal_jfo(64, 16, 0.0).solve()
    assert good.warnings == [] and _warnings(caplog) == []

    from lubedyn.scenes import film as film_scene
    from lubedyn.config import load_case

    case = load_case(CASES_DIR / "journal_finite.toml", overrides=[
        "cavitation.model=jfo", "mesh.element=P1", "boundary.pressures.bottom=1e5", "boundary.pressures.top=1e5",
        "motion.mode_velocities.x=-0.2"])
    caplog.clear()
    run = film_scene.run(case)
    logged = _warnings(caplog, "Fluid fraction down to")
    assert len(logged) == 1 and logged == run.solution.warnings
    assert [w for w in run.summary["Warnings"] if w.startswith("Fluid fraction")] == logged


def test_text_file_as_films_map_is_one_line_without_pickle_advice(tmp_path, capsys):
    """A text file given as films.map (numpy's np.load would advise loading it "unsafely using
    allow_pickle="): exit 2 and one line naming the key, the file and what a film map is."""
    notes = tmp_path / "notes.npz"
    notes.write_text("gap, force\n1e-6, 3.2\n")
    code = cli.main(["run", str(CASES_DIR / "cageless_6206_10krpm_short.toml"), "--smoke", "--set",
                     "films.ball_ball=map", "--set", f"films.map={notes}", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith(f"lubedyn: error: films.map = {str(notes)!r} is a text file, not a film map: "
                          "expected a film map .npz written by `lubedyn run` of a map case"), err
    assert "pickle" not in err
    # an .npz holding an object array (numpy's other "allow_pickle" message), from Python
    np.savez(tmp_path / "objects.npz", header=np.array([{"format": "x"}], dtype=object))
    with pytest.raises(InputError) as info:
        FilmMap.load(tmp_path / "objects.npz", key="films.map")
    assert "pickle" not in str(info.value) and str(info.value).startswith("films.map = ")
    assert "expected a film map .npz written by `lubedyn run` of a map case" in str(info.value)


@pytest.mark.parametrize("cell", ["quad", "tri"])
def test_periodic_film_mesh_gives_scikit_fem_nothing_to_log(cell, caplog, tmp_path):
    """A periodic journal mesh of 121 x 21 vertices (> 1000), its unwrapped copy, a solve and its .vtu:
    no record from scikit-fem at WARNING (it logged "Transforming over 1000 vertices to C_CONTIGUOUS."
    for the mesh and again for its unwrapped copy); the mesh is scikit-fem's own periodic tensor mesh,
    array for array."""
    import skfem

    from lubedyn.lubrication import Cavitation, Film, JournalBearing, Lubricant

    caplog.set_level(logging.WARNING, logger="skfem")
    xs, ys = np.linspace(0.0, 2 * np.pi * 0.025, 121), np.linspace(-0.025, 0.025, 21)
    mesh = meshes.rectangle(xs, ys, cell, periodic_x=True)
    meshes.unwrapped(mesh)
    film = Film(mesh, JournalBearing.from_ratio(0.025, 50e-6, 0.6), Lubricant.newtonian(0.02),
                velocity_upper=(100 * np.pi * 0.025, 0.0), cavitation=Cavitation("half_sommerfeld", 0.0),
                dirichlet={"bottom": 0.0, "top": 0.0})
    film.solve().save(tmp_path / "journal.vtu")
    assert [r.getMessage() for r in caplog.records if r.name.startswith("skfem")] == []
    own = (skfem.MeshQuad1DG if cell == "quad" else skfem.MeshTri1DG).init_tensor(xs, ys, periodic=[0])
    assert type(mesh) is type(own)
    for name in ("p", "t", "doflocs", "facets"):
        assert np.array_equal(getattr(mesh, name), getattr(own, name)), name
