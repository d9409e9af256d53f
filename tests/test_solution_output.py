"""FilmSolution output and post-processing on every mesh kind, periodic included.

scikit-fem's periodic meshes (``MeshQuad1DG``/``MeshTri1DG``, from
``mesh.rectangle(..., periodic_x=True)``) number vertices topologically in
``mesh.t`` but keep one copy of the vertices per element in ``mesh.p``, and
have no boundary mapping.  Pinned here: the VTK grid, the pressure plot, the
flow through a sealed boundary and the element size of such meshes; the
summary's names and cavitation measures; the file mode of ``save``; the fast
scalar interpolation against scikit-fem's own.
"""
from __future__ import annotations

import math
import os
import stat

import numpy as np
import pytest
import skfem
from scipy.integrate import quad

from lubedyn.lubrication import Cavitation, Film, InclinedSlider, JournalBearing, Lubricant, SpherePlane
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.reynolds import interpolate, make_basis
from lubedyn.lubrication.reynolds.problem import _Problem

R, C, L, ETA, OMEGA = 0.025, 50e-6, 0.025, 0.02, 300.0


def journal(nx, ny, cell="quad", element="P1", **kw):
    m = meshes.rectangle(np.linspace(0, 2 * np.pi * R, nx + 1), np.linspace(-L / 2, L / 2, ny + 1), cell,
                         periodic_x=True)
    return Film(m, JournalBearing.from_ratio(R, C, 0.6), Lubricant.newtonian(ETA), velocity_upper=(OMEGA * R, 0.0),
                element=element, **kw)


# ---------------------------------------------------------------- VTK and plot


@pytest.mark.parametrize("cell", ["quad", "tri"])
def test_periodic_vtu_is_watertight_and_carries_the_dofs(cell):
    """One point per topological vertex (nx (ny + 1)); the only open edges are
    the two bearing ends (2 nx edges at z = -L/2 and +L/2); every point
    carries the pressure dof at its place (theta = atan2(y, x), z)."""
    nx, ny = 16, 4
    s = journal(nx, ny, cell).solve()
    grid = s.to_pyvista()
    assert grid.n_points == nx * (ny + 1)
    assert grid.n_cells == s.film.mesh.t.shape[1]
    edges = grid.extract_surface(algorithm="dataset_surface").extract_feature_edges(
        boundary_edges=True, feature_edges=False, manifold_edges=False, non_manifold_edges=False)
    assert edges.n_cells == 2 * nx
    np.testing.assert_allclose(np.abs(edges.points[:, 2]), L / 2, rtol=1e-12)
    pts = grid.points
    theta = np.mod(np.arctan2(pts[:, 1], pts[:, 0]), 2 * np.pi)
    film_xy = np.vstack([R * theta, pts[:, 2]])
    doflocs = s.basis.doflocs
    diff = doflocs[:, :, None] - film_xy[:, None, :]
    period = 2 * np.pi * R
    diff[0] = (diff[0] + 0.5 * period) % period - 0.5 * period
    dist = np.linalg.norm(diff, axis=0)
    nearest = np.argmin(dist, axis=0)
    assert np.max(dist[nearest, np.arange(pts.shape[0])]) < 1e-9 * period
    np.testing.assert_array_equal(grid.point_data["Pressure [Pa]"], s.pressure[nearest])
    np.testing.assert_allclose(grid.point_data["Film thickness [m]"], C * (1 - 0.6 * np.cos(theta)), rtol=1e-9)


@pytest.mark.parametrize("cell, element", [("quad", "P1"), ("tri", "P2")])
def test_periodic_pressure_plot_covers_the_film_once(cell, element):
    """The plotted triangles tile the unwrapped film (total area 2 pi R L, no
    triangle longer than a cell diagonal) and the plotted values are the
    vertex pressures (the seam column appears on both sides)."""
    import matplotlib.pyplot as plt

    nx, ny = 16, 4
    s = journal(nx, ny, cell, element).solve()
    fig = s.plot_pressure()
    try:
        trimesh = fig.axes[0].collections[0]
        tris = np.array([p.vertices[:3] for p in trimesh.get_paths()])  # mm
        a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
        area = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1]))
        assert area.sum() == pytest.approx(2 * np.pi * R * L * 1e6, rel=1e-12)
        longest = max(np.linalg.norm(tris[:, i] - tris[:, (i + 1) % 3], axis=1).max() for i in range(3))
        assert longest <= 1.0001 * math.hypot(2 * np.pi * R / nx, L / ny) * 1e3
        vertex_dofs = np.unique(s.basis.element_dofs[: s.film.mesh.t.shape[0]])
        np.testing.assert_array_equal(np.unique(trimesh.get_array()), np.unique(s.pressure[vertex_dofs] / 1e6))
        assert trimesh.get_array().size == (nx + 1) * (ny + 1)
    finally:
        plt.close(fig)


def test_save_gives_the_usual_file_mode(tmp_path):
    s = Film(meshes.interval(0, 0.01, 10), InclinedSlider(2e-6, 1e-6, 0.01), Lubricant.newtonian(0.01),
             velocity_lower=(1.0,)).solve()
    old = os.umask(0o022)
    try:
        path = s.save(tmp_path / "film.vtu")
    finally:
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


# ---------------------------------------------------------------- flow


V_SQUEEZE = -1e-4  # m/s, uniform approach


@pytest.mark.parametrize("cell, element, balance_order, top_order",
                         [("quad", "P1", 0.95, 0.95), ("tri", "P1", 1.5, 0.8), ("tri", "P2", 1.8, 1.8)])
def test_flow_through_sealed_boundary_of_periodic_mesh(cell, element, balance_order, top_order):
    """Journal with only ``top`` at ambient, ``bottom`` sealed, squeezed at
    v = -0.1 mm/s: flow(top) + flow(bottom) + int dh/dt dA = 0.  ``top`` is a
    pressure boundary (consistent flux: exact to round-off); ``bottom`` is
    integrated pointwise over the unwrapped mesh, and its leakage vanishes with
    the mesh.  Measured balance errors (n = 4, 8, 16; nx = 4 n): quad P1
    1.25e-1, 6.25e-2, 3.1e-2; tri P1 7.5e-1, 2.2e-1, 7.1e-2; tri P2 3.1e-1,
    7.6e-2, 1.9e-2.  The pointwise flux through ``top`` converges to the
    consistent one: relative gaps quad P1 1.25e-1, 6.3e-2, 3.1e-2; tri P2
    4.9e-1, 1.3e-1, 3.4e-2; tri P1 5.2, 2.9, 1.5 (first order with a large
    constant: the Couette-driven x-gradient leaks into the y-flux of the
    diagonal-split cells; the non-periodic tri mesh shows the same, 5.5, 3.2,
    1.7)."""
    volume = V_SQUEEZE * 2 * np.pi * R * L
    ns = np.array([4, 8, 16])
    balance, top_gap = [], []
    for n in ns:
        s = journal(4 * n, n, cell, element, squeeze=V_SQUEEZE, dirichlet={"top": 0.0}).solve()
        top, bottom = s.flow("top"), s.flow("bottom")
        assert top == pytest.approx(-volume, rel=1e-10)
        balance.append(abs(top + bottom + volume) / abs(volume))
        top_gap.append(abs(s._pointwise_flow("top") - top) / abs(top))
    assert -np.polyfit(np.log(ns), np.log(balance), 1)[0] > balance_order
    assert -np.polyfit(np.log(ns), np.log(top_gap), 1)[0] > top_order
    assert balance[-1] < 0.1


def test_flow_through_sealed_boundary_p2_quads_is_exact():
    """Biquadratic elements carry this film's solution across the width: the
    sealed boundary leaks nothing (measured 1e-20 m^3/s against 4e-7)."""
    volume = V_SQUEEZE * 2 * np.pi * R * L
    s = journal(16, 4, "quad", "P2", squeeze=V_SQUEEZE, dirichlet={"top": 0.0}).solve()
    assert abs(s.flow("top") + s.flow("bottom") + volume) < 1e-12 * abs(volume)


def test_element_size_on_periodic_mesh_is_the_cell_size():
    """The streamline-diffusion length h_K of a periodic mesh equals that of
    the same grid without the identification (it used to read DG points with
    topological numbers: sizes up to 8 times too large)."""
    xs, ys = np.linspace(0, 2 * np.pi * R, 33), np.linspace(-L / 2, L / 2, 9)
    for cell in ("quad", "tri"):
        periodic = journal(32, 8, cell, cavitation=Cavitation("jfo"))
        plain = periodic.with_(mesh=meshes.rectangle(xs, ys, cell))
        np.testing.assert_allclose(_Problem(periodic)._element_size(), _Problem(plain)._element_size(), rtol=1e-12)


# ---------------------------------------------------------------- summary


def test_cavitated_area_fraction_long_journal(long_journal_film):
    """Swift-Stieber long journal, eps = 0.7: the film is cavitated from
    phi_c to 2 pi, area fraction 1 - phi_c/(2 pi) = 0.42602.  P2 on 64, 128,
    256 elements: measured 0.43229, 0.42708, 0.42578 (the film may end a node
    early).  The fluid fraction stays 1 (not JFO): mean void fraction 0."""
    ref = cf.long_journal_reynolds(0.05, 50e-6, 0.7, 0.02, 10.0)
    expected = 1 - ref.phi_cavitation / (2 * np.pi)
    s = long_journal_film(0.05, 50e-6, 0.7, 0.02, 10.0, 128, cavitation="reynolds").solve()
    summary = s.summary()
    assert summary["Cavitated area fraction [-]"] == pytest.approx(expected, abs=2e-3)
    assert summary["Mean void fraction [-]"] == 0.0
    assert s.cavitated_area_fraction == summary["Cavitated area fraction [-]"]


def test_jfo_void_and_cavitated_fractions_fowell():
    """Fowell pocket, JFO, U = 1 m/s, P1 on 200 elements.  Cavitated region
    [2 mm, x_r = 3.611 mm] of L = 10 mm: 0.16113 (measured 0.165: the nodal
    indicator reaches half an element beyond each end).  Mean void fraction
    int (1 - theta) dx / L = 0.0783518 (measured 0.0783511).  Full film
    (U = 0.02 m/s): both 0."""
    from test_cavitation import LENGTH, fowell, fowell_fem

    ref = fowell(1.0)
    void = quad(lambda x: 1 - ref.fluid_fraction(np.array([x]))[0], 0, LENGTH,
                points=[2e-3, ref.x_reformation, 5e-3], limit=200)[0] / LENGTH
    s = fowell_fem(1.0, 200).summary()
    assert s["Cavitated area fraction [-]"] == pytest.approx((ref.x_reformation - 2e-3) / LENGTH, abs=1 / 200)
    assert s["Mean void fraction [-]"] == pytest.approx(void, rel=1e-4)
    full = fowell_fem(0.02, 50).summary()
    assert full["Cavitated area fraction [-]"] == 0.0 and abs(full["Mean void fraction [-]"]) < 1e-14


def test_one_dimensional_summary_is_per_unit_width():
    s = Film(meshes.interval(0, 0.01, 20), InclinedSlider(2e-6, 1e-6, 0.01), Lubricant.newtonian(0.01),
             velocity_lower=(1.0,)).solve()
    summary = s.summary(coefficients=s.coefficients())
    for key in ("Load per unit width [N/m]", "Load z per unit width [N/m]", "Mode force h0 per unit width [N/m]",
                "Friction lower x per unit width [N/m]", "Friction upper x per unit width [N/m]",
                "Flow left per unit width [m^2/s]", "Flow right per unit width [m^2/s]",
                "Stiffness K[h0,h0] per unit width [N/m^2]", "Damping C[h0,h0] per unit width [N s/m^2]",
                "Maximum pressure [Pa]", "Cavitated area fraction [-]"):
        assert key in summary, key
    assert not [k for k in summary if k.endswith(("[N]", "[m^3/s]"))]
    assert summary["Load per unit width [N/m]"] == s.load
    assert summary["Flow right per unit width [m^2/s]"] == pytest.approx(-summary["Flow left per unit width [m^2/s]"])


def test_two_dimensional_summary_names():
    s = Film(meshes.disk(1e-3, 2), SpherePlane(10e-3, 10e-6), Lubricant.newtonian(0.01), squeeze=-1e-3).solve()
    summary = s.summary()
    assert {"Load [N]", "Load z [N]", "Flow edge [m^3/s]", "Friction lower x [N]"} <= set(summary)
    assert not [k for k in summary if "per unit width" in k]


# ---------------------------------------------------------------- interpolation


@pytest.mark.parametrize("build, element", [
    (lambda: meshes.interval(0, 1, 7), "P1"),
    (lambda: meshes.interval(0, 1, 7), "P2"),
    (lambda: meshes.rectangle(np.linspace(0, 1, 5), np.linspace(0, 1, 4), "quad", periodic_x=True), "P1"),
    (lambda: meshes.rectangle(np.linspace(0, 1, 5), np.linspace(0, 1, 4), "quad", periodic_x=True), "P2"),
    (lambda: meshes.rectangle(np.linspace(0, 1, 5), np.linspace(0, 1, 4), "tri"), "P2"),
    (lambda: meshes.disk(1.0, 2, order=2), "P2"),
])
def test_interpolate_matches_scikit_fem(build, element):
    """Same sum in the same order as ``basis.interpolate``: bit for bit."""
    basis = make_basis(build(), element)
    u = np.random.default_rng(0).normal(size=basis.N)
    ours, theirs = interpolate(basis, u), basis.interpolate(u)
    np.testing.assert_array_equal(np.asarray(ours), np.asarray(theirs))
    np.testing.assert_array_equal(ours.grad, theirs.grad)
    zero = interpolate(basis, np.zeros(basis.N), zero=True)
    assert zero.shape == ours.shape and zero.grad.shape == ours.grad.shape and not np.any(zero) and not np.any(zero.grad)
