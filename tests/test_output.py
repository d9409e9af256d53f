"""The film ``.vtu`` written by a run, read back with pyvista and with meshio.

Point data names carry units; points are 3-D; a journal film is wrapped onto
its cylinder of radius R; the values at the points are the solution's own
(vertex degrees of freedom at the same place) and the film thickness at the
points is the gap's closed form.
"""
from __future__ import annotations

import math

import meshio
import numpy as np
import pytest
import pyvista as pv

from lubedyn.scenes import film as film_scene
from lubedyn.config import CASES_DIR, load_case

NAMES = ("Pressure [Pa]", "Film thickness [m]", "Fluid fraction [-]")


def run_case(name, tmp_path, **overrides):
    case = load_case(CASES_DIR / f"{name}.toml", smoke=True, overrides=[f"{k}={v}" for k, v in overrides.items()])
    result = film_scene.run(case, tmp_path, name=name, smoke=True)
    return case, result.solution, tmp_path / "film.vtu"


def read_both(path):
    grid = pv.read(path)
    mesh = meshio.read(path)
    assert set(NAMES) <= set(grid.point_data.keys())
    assert set(NAMES) <= set(mesh.point_data.keys())
    assert grid.points.shape[1] == 3 and mesh.points.shape[1] == 3
    np.testing.assert_allclose(mesh.points, grid.points)
    for name in NAMES:
        np.testing.assert_array_equal(mesh.point_data[name], grid.point_data[name])
    return grid, mesh


def nearest_dof_values(solution, film_xy, period=None):
    """Solution dof values at the dofs located at ``film_xy`` (dim, n) (exact match required)."""
    doflocs = solution.basis.doflocs
    diff = doflocs[:, :, None] - film_xy[:, None, :]
    if period:
        diff[0] = (diff[0] + 0.5 * period) % period - 0.5 * period
    dist = np.linalg.norm(diff, axis=0)
    idx = np.argmin(dist, axis=0)
    scale = np.ptp(doflocs, axis=1).max()
    assert np.all(dist[idx, np.arange(film_xy.shape[1])] < 1e-9 * scale), "a VTU point is not at a vertex dof"
    return solution.pressure_dofs[idx], solution.fluid_fraction_dofs[idx]


def test_disk_film_vtu(tmp_path):
    """Sphere-plane squeeze on a disk: planar points at z = 0, h = h0 + r^2/(2R)."""
    case, solution, path = run_case("sphere_plane_squeeze", tmp_path)
    grid, mesh = read_both(path)
    pts = grid.points
    assert np.all(pts[:, 2] == 0.0)
    r2 = pts[:, 0] ** 2 + pts[:, 1] ** 2
    assert r2.max() == pytest.approx(case.mesh.radius**2, rel=1e-9)
    np.testing.assert_allclose(grid.point_data["Film thickness [m]"], case.gap.h0 + r2 / (2 * case.gap.radius), rtol=1e-12)
    p, theta = nearest_dof_values(solution, pts[:, :2].T)
    np.testing.assert_allclose(grid.point_data["Pressure [Pa]"], p, rtol=0, atol=1e-12 * p.max())
    np.testing.assert_array_equal(grid.point_data["Fluid fraction [-]"], theta)
    assert grid.n_cells == solution.film.mesh.t.shape[1]


def test_one_dimensional_jfo_film_vtu(tmp_path):
    """Fowell pocket: points (x, 0, 0); in the cavitated zone the Couette flow
    theta h U/2 carries exactly the film's flow rate (JFO mass conservation)."""
    case, solution, path = run_case("fowell_pocket", tmp_path)
    grid, _ = read_both(path)
    pts = grid.points
    assert np.all(pts[:, 1:] == 0.0)
    p, theta = nearest_dof_values(solution, pts[:, :1].T)
    np.testing.assert_allclose(grid.point_data["Pressure [Pa]"], p, rtol=0, atol=1e-9 * p.max())
    theta_vtu = grid.point_data["Fluid fraction [-]"]
    np.testing.assert_array_equal(theta_vtu, theta)
    cavitated = theta_vtu < 1.0 - 1e-6
    assert cavitated.sum() >= 10
    x = pts[cavitated, 0]
    assert np.all((x >= case.gap.pocket_start - 1e-12) & (x <= case.gap.pocket_end))
    # inside the cavitated zone theta h U / 2 = q; measured within 1.3e-4 (P1 theta
    # times nodal h, 100 elements).  Left out: the node on the pocket edge (h
    # jumps there) and the last one, within an element of the re-formation front
    # (the upwinded void fraction is smeared over one element).
    order = np.flatnonzero(cavitated)[np.argsort(pts[cavitated, 0])]
    inside = order[1:-1]
    assert inside.size >= 10
    q = solution.flow("right")
    U = case.motion.velocity_lower[0]
    h = grid.point_data["Film thickness [m]"][inside]
    np.testing.assert_allclose(theta_vtu[inside] * h * U / 2, q, rtol=1e-3)


def test_journal_vtu_lies_on_the_cylinder(tmp_path):
    case, solution, path = run_case("journal_finite", tmp_path)
    grid, mesh = read_both(path)
    pts = grid.points
    R, L = case.gap.radius, case.gap.length
    np.testing.assert_allclose(np.hypot(pts[:, 0], pts[:, 1]), R, rtol=1e-12)
    assert pts[:, 2].min() == pytest.approx(-L / 2) and pts[:, 2].max() == pytest.approx(L / 2)
    theta = np.mod(np.arctan2(pts[:, 1], pts[:, 0]), 2 * math.pi)
    c, eps = case.gap.clearance, case.gap.eccentricity_ratio
    np.testing.assert_allclose(grid.point_data["Film thickness [m]"], c * (1 - eps * np.cos(theta)), rtol=1e-9)


def test_journal_vtu_values_are_the_solution(tmp_path):
    """Every VTU point carries the pressure of the solution's dof at that place
    (theta = atan2(y, x), z), and every cell joins points that are neighbours
    on the cylinder (no cell spans more than one mesh cell)."""
    case, solution, path = run_case("journal_finite", tmp_path)
    grid, _ = read_both(path)
    pts = grid.points
    R = case.gap.radius
    theta = np.mod(np.arctan2(pts[:, 1], pts[:, 0]), 2 * math.pi)
    film_xy = np.vstack([R * theta, pts[:, 2]])
    p, _ = nearest_dof_values(solution, film_xy, period=2 * math.pi * R)
    np.testing.assert_allclose(grid.point_data["Pressure [Pa]"], p, rtol=0, atol=1e-9 * p.max())
    cell_size = math.hypot(2 * math.pi * R / case.mesh.nx, case.gap.length / case.mesh.ny)
    cells = grid.cells_dict[pv.CellType.QUAD]
    edges = np.linalg.norm(pts[cells] - pts[np.roll(cells, 1, axis=1)], axis=2)
    assert edges.max() < 1.01 * cell_size


def test_pvd_collection_reads_back_in_pyvista(tmp_path):
    """pyvista's own PVD reader (an independent parser) sees the times and the data."""
    import pyvista as pv

    from lubedyn.outputs import write_pvd

    entries = []
    for k, t in enumerate((0.0, 2.5e-4, 1e-3)):
        mesh = pv.Sphere(radius=1.0 + k)
        mesh.point_data["Pressure [Pa]"] = np.full(mesh.n_points, float(k))
        mesh.save(tmp_path / f"step_{k}.vtp")
        entries.append((t, f"step_{k}.vtp"))
    write_pvd(tmp_path / "series.pvd", entries)
    reader = pv.get_reader(str(tmp_path / "series.pvd"))
    assert np.allclose(reader.time_values, [0.0, 2.5e-4, 1e-3])
    reader.set_active_time_value(1e-3)
    block = reader.read()[0]
    assert np.allclose(block.point_data["Pressure [Pa]"], 2.0)
    assert abs(block.bounds[1] - 3.0) < 1e-2  # sphere of radius 3


def test_frames_read_back_as_written_and_unwritable_frames_name_the_path(tmp_path):
    """``write_frame`` (zlib level 1 through VTK's writer): pyvista and meshio (two independent readers)
    read back the points, cells and arrays of a PolyData and an UnstructuredGrid (meshio: the latter) exactly; a frame that
    cannot be written is an OutputError naming its path."""
    from lubedyn.outputs import OutputError, write_frame

    poly = pv.Sphere(radius=2.0, theta_resolution=24, phi_resolution=12)
    poly.point_data["Film pressure [Pa]"] = np.linspace(0.0, 3e8, poly.n_points)
    poly.point_data["Body [-]"] = np.arange(poly.n_points, dtype=np.int32) % 5
    grid = pv.ImageData(dimensions=(4, 3, 2)).triangulate()  # tetrahedra (meshio reads no voxels)
    grid.cell_data["Body [-]"] = np.arange(grid.n_cells, dtype=np.int32)
    for mesh, name in ((poly, "f.vtp"), (grid, "g.vtu")):
        write_frame(tmp_path / name, mesh)
        back = pv.read(tmp_path / name)
        assert type(back) is type(mesh)
        assert np.array_equal(back.points, mesh.points)
        for data, ref in ((back.point_data, mesh.point_data), (back.cell_data, mesh.cell_data)):
            assert sorted(data.keys()) == sorted(ref.keys())
            for key in ref.keys():
                assert np.array_equal(data[key], ref[key]) and data[key].dtype == ref[key].dtype
    m = meshio.read(tmp_path / "g.vtu")  # meshio reads .vtu, not .vtp
    assert np.array_equal(m.points, grid.points)
    assert np.array_equal(m.cell_data["Body [-]"][0], grid.cell_data["Body [-]"])
    assert np.array_equal(pv.read(tmp_path / "f.vtp").faces, poly.faces)
    assert np.array_equal(pv.read(tmp_path / "g.vtu").cells, grid.cells)
    (tmp_path / "a_file").write_text("")
    with pytest.raises(OutputError, match="a_file"):
        write_frame(tmp_path / "a_file" / "f.vtp", poly)


def test_timeseries_roundtrip_and_refuses_ragged_columns(tmp_path):
    from lubedyn.outputs import read_timeseries, write_timeseries

    t = np.linspace(0, 1e-3, 5)
    path = write_timeseries(tmp_path / "ts.npz", t, {"Ball 1 x [m]": np.sin(t)}, {"Case": "demo"})
    columns, meta = read_timeseries(path)
    assert np.array_equal(columns["Time [s]"], t) and np.array_equal(columns["Ball 1 x [m]"], np.sin(t))
    assert meta["Case"] == "demo" and meta["columns"] == ["Time [s]", "Ball 1 x [m]"]
    with pytest.raises(ValueError, match="Ball 2"):
        write_timeseries(tmp_path / "bad.npz", t, {"Ball 2 x [m]": np.ones(4)})
    assert not (tmp_path / "bad.npz").exists()


def test_timeseries_round_trip_plain_and_compressed(tmp_path):
    """write_timeseries stores plain .npz by default and zip-deflated with compress=True; read_timeseries
    gives back the same columns and meta bit for bit either way, and the plain file is the larger one for
    data that compresses (a smooth signal)."""
    import numpy as np

    from lubedyn.outputs import read_timeseries, write_timeseries

    t = np.linspace(0.0, 1.0, 2001)
    cols = {"Smooth [m]": np.round(np.sin(t), 3), "Flag [-]": (t > 0.5).astype(float)}
    for name, compress in (("plain.npz", False), ("deflated.npz", True)):
        write_timeseries(tmp_path / name, t, cols, {"case": "x"}, compress=compress)
        back, meta = read_timeseries(tmp_path / name)
        assert np.array_equal(back["Time [s]"], t) and meta["case"] == "x"
        assert all(np.array_equal(back[k], v) for k, v in cols.items())
    assert (tmp_path / "plain.npz").stat().st_size > (tmp_path / "deflated.npz").stat().st_size
