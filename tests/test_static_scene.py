"""The static scene (``scene = "static"``, coupling/scenes/static.py) through the command line: the preload's
growth, the echo of every assumed value, ParaView output (bad input: rows of tests/test_bad_input_table.py).  The bundled cases' physics checks
(force triangles, the cone's balance, Stribeck) are in tests/test_cases.py."""
from __future__ import annotations

import json
import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR


def _run(capsys, tmp_path, case, *sets):
    out = tmp_path / case
    args = ["run", str(CASES_DIR / f"{case}.toml"), "--smoke", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    code = cli.main(args)
    _, err = capsys.readouterr()
    assert code == 0, err
    return json.loads((out / "summary.json").read_text())


def test_preload_grows_faster_than_the_displacement(capsys, tmp_path):
    """40 um of preload needs more than twice the axial force of 20 um and at most 2^(10/9) times
    (the slices' 10/9 law; the crown's growing contact length lies between), each physics check of a
    bundled case being in tests/test_cases.py."""
    s20 = _run(capsys, tmp_path, "trb_static_preload")
    s40 = _run(capsys, tmp_path, "trb_static_preload", "operating.axial_displacement=40 um")
    assert 2.0 < s40["Axial load [N]"] / s20["Axial load [N]"] < 2.0 ** (10 / 9) * 1.05


def test_a_value_given_by_the_case_is_not_echoed_as_assumed(capsys, tmp_path):
    s = _run(capsys, tmp_path, "trb_static_axial", "bearing.rib_height=7 mm", "bearing.profile=straight")
    assert "bearing.rib_height" not in s["Assumed values"] and "bearing.profile" not in s["Assumed values"]
    assert "bearing.density" in s["Assumed values"]


def test_bearing_vtu_for_paraview(capsys, tmp_path):
    """bearing.vtu: cup, cone and 17 rollers as bodies; each roller carries its summary loads; the
    rollers lie between the raceway surfaces (radii about the axis within the cone's and cup's range,
    to 0.1 mm: the crowned frustum's rim, tilted by micro-radians); the load zone faces +y."""
    import numpy as np
    import pyvista as pv

    s = _run(capsys, tmp_path, "trb_static_radial")
    m = pv.read(tmp_path / "trb_static_radial" / "bearing.vtu")
    body = m.cell_data["Body [-]"]
    assert sorted(set(body.tolist())) == list(range(2 + s["Rollers [-]"]))
    rollers = m.extract_cells(np.flatnonzero(body >= 2))
    r = np.hypot(rollers.points[:, 1], rollers.points[:, 2])
    rings = [np.hypot(*m.extract_cells(np.flatnonzero(body == k)).points[:, 1:].T) for k in (0, 1)]
    assert rings[1].min() - 1e-4 < r.min() and r.max() < rings[0].max() + 1e-4
    for j in (0, 8):
        cells = m.extract_cells(np.flatnonzero(body == 2 + j))
        assert np.allclose(cells.point_data["Cup load [N]"], s["Cup loads [N]"][j])
    loaded = m.extract_cells(np.flatnonzero(body == 2))  # roller 0 at azimuth 0: on +y
    assert loaded.points[:, 1].mean() > 0.08


def test_the_python_twin_is_the_cases_bearing():
    """lubedyn.papers.wu2018.parameters.tapered_geometry() and a static case naming Wu2018 build the same
    geometry (one table, SCENES["static"], maps the parameters onto both)."""
    from lubedyn.config import load_case
    from lubedyn.papers.wu2018.parameters import tapered_geometry
    from lubedyn.scenes.static import build

    import dataclasses

    case = load_case(CASES_DIR / "trb_static_axial.toml")
    a, b = build(case), tapered_geometry()
    inputs = [f.name for f in dataclasses.fields(a) if f.init]
    assert len(inputs) == 24 and all(getattr(a, k) == getattr(b, k) for k in inputs)


def test_literal_preload_is_flagged_as_a_near_mechanism(capsys, tmp_path):
    """Table 1 read literally under a 20 um preload at 2,500 rpm: no roller touches the cone raceway (the
    rollers tilt into the 0.11 mm large-end gap) and the flange carries the axial force alone; the
    summary says so instead of passing it as a bearing in service (common apex: no warning)."""
    s = _run(capsys, tmp_path, "trb_static_preload", "bearing.reconciliation=literal")
    assert max(s["Cone loads [N]"]) == 0.0 and s["Axial load [N]"] > 0.0
    assert "no roller touches the cone raceway" in s["Warnings"][0]
    assert "Warnings" not in _run(capsys, tmp_path / "apex", "trb_static_preload")
