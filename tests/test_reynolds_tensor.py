"""The structured path of the Reynolds solve (lubedyn.lubrication.reynolds.tensor): P1 on tensor quad meshes.

Independent references: scikit-fem's own assembly (``asm`` of the forms) and its basis' quadrature points;
the closed forms of lubedyn.lubrication.closed_form (infinitely wide inclined slider, finite slider's
Fourier series); and the general (scikit-fem) path of the same solver on the same film, which the
structured one must match to the linear solver's tolerance.  The "auto" switch to multigrid is lowered
below the test sizes so that the multigrid path runs.
"""
import numpy as np
import pytest
import skfem
from skfem import asm

from lubedyn.lubrication import Cavitation, Film, FunctionGap, InclinedSlider, Lubricant, SolverOptions
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.reynolds import forms, problem
from lubedyn.lubrication.reynolds.tensor import tensor_grid

ETA = 0.05
rng = np.random.default_rng(42)


def _graded(n, length, ratio=1.08):
    w = ratio ** np.arange(n)
    return np.concatenate([[0.0], np.cumsum(w)]) / np.sum(w) * length


def test_only_plain_p1_quad_tensor_meshes_take_the_structured_path():
    """Uniform and graded rectangles of quads with P1 are tensor grids; triangles, periodic quads, P2,
    a disk and a tensor mesh whose elements are listed in another order are not."""
    xs, ys = _graded(7, 2.0), np.linspace(-1.0, 1.0, 5)
    m = meshes.rectangle(xs, ys)
    grid = tensor_grid(m, "P1")
    assert grid is not None and np.array_equal(grid.xs, xs) and np.array_equal(grid.ys, ys)
    assert tensor_grid(meshes.rectangle(xs, ys, cell="tri"), "P1") is None
    assert tensor_grid(meshes.rectangle(xs, ys, periodic_x=True), "P1") is None
    assert tensor_grid(m, "P2") is None
    assert tensor_grid(meshes.disk(1.0, 2), "P1") is None
    shuffled = skfem.MeshQuad(m.p, m.t[:, rng.permutation(m.t.shape[1])])
    assert tensor_grid(shuffled, "P1") is None
    # the quadrature points are scikit-fem's, in its order
    basis = forms.make_basis(m, "P1")
    assert np.allclose(grid.quadrature_points(), basis.global_coordinates(), rtol=0, atol=1e-15)
    assert np.array_equal(grid.boundary_dofs(), np.unique(m.facets[:, m.boundary_facets()]))


def test_grid_assembly_equals_scikit_fem():
    """Diffusion matrix and both load vectors on a graded grid with random coefficients at the quadrature
    points, against scikit-fem's asm of the same forms: equal to rounding (1e-13 of the largest entry),
    and the matrix has the same sparsity."""
    m = meshes.rectangle(_graded(9, 3.0), _graded(6, 1.0, 0.9))
    basis, grid = forms.make_basis(m, "P1"), tensor_grid(m, "P1")
    shape = np.asarray(basis.global_coordinates()).shape
    a, g, f = rng.uniform(1, 3, shape[1:]), rng.normal(size=shape[1:]), rng.normal(size=shape)
    ref = asm(forms.diffusion_form, basis, a=a).tocsr()
    got = grid.diffusion(a)
    assert abs(got - ref).max() <= 1e-13 * abs(ref).max()
    assert got.nnz == ref.nnz and got.has_sorted_indices
    for mine, form, kw in ((grid.flux_load(f), forms.flux_load_form, {"f": f}),
                           (grid.source_load(g), forms.source_load_form, {"g": g})):
        ref = asm(form, basis, **kw)
        assert np.abs(mine - ref).max() <= 1e-13 * np.abs(ref).max()


def test_grid_interpolation_and_integral_equal_scikit_fem():
    """A random dof vector and its gradient at the quadrature points, and the integral of a quadrature-point
    field, against the basis' interpolation (forms.interpolate, scikit-fem's sum) and asm of the integral."""
    from lubedyn.lubrication.reynolds.solution import _integral

    m = meshes.rectangle(_graded(9, 3.0), _graded(6, 1.0, 0.9))
    basis, grid = forms.make_basis(m, "P1"), tensor_grid(m, "P1")
    u = rng.normal(size=basis.N)
    ref, got = forms.interpolate(basis, u), grid.interpolate(u)
    assert np.allclose(np.asarray(got), np.asarray(ref), rtol=0, atol=1e-14)
    assert np.allclose(got.grad, ref.grad, rtol=0, atol=1e-13)
    f = rng.normal(size=np.asarray(ref).shape)
    assert grid.integrate(f) == pytest.approx(float(asm(_integral, basis, f=f)), rel=1e-13)


@pytest.fixture
def multigrid_from_200(monkeypatch):
    from lubedyn.lubrication.reynolds import tensor

    monkeypatch.setattr(problem, "DIRECT_SOLVER_MAX_DOFS", 200)  # where the solver looks it up
    monkeypatch.setattr(tensor, "MULTIGRID_MAX_COARSE", 40)  # several levels at these sizes


def test_multigrid_hierarchy_on_a_graded_grid_with_holes():
    """The grid hierarchy on a graded 64 x 48 grid, with the boundary and a scattered tenth of the nodes
    removed (as an active set removes cavitated nodes): four or more levels; Galerkin operators (R = P^T);
    as CG's preconditioner (rough coefficients: independent random values at every quadrature point) it
    reaches 1e-10 in at most 20 iterations (measured 14-15, float64 and float32 cycles), where plain CG
    needs more than 100 (measured 133-339)."""
    from pyamg.krylov import cg

    rng = np.random.default_rng(3)
    m = meshes.rectangle(_graded(64, 2.0, 1.03), _graded(48, 1.0, 0.97))
    grid = tensor_grid(m, "P1")
    basis = forms.make_basis(m, "P1")
    a = rng.uniform(0.5, 2.0, np.asarray(basis.global_coordinates()).shape[1:])
    free = np.ones(grid.N, dtype=bool)
    free[grid.boundary_dofs()] = False
    free[rng.choice(grid.N, grid.N // 10, replace=False)] = False
    idx = np.flatnonzero(free)
    A = grid.diffusion(a)[idx][:, idx].tocsr()
    ml = grid.multigrid(A, idx, max_coarse=40)
    assert len(ml.levels) >= 4
    P = ml.levels[0].P
    assert abs(ml.levels[0].R - P.T).max() == 0
    assert abs(ml.levels[1].A - P.T @ A @ P).max() <= 1e-12 * abs(ml.levels[1].A).max()
    b = rng.normal(size=idx.size)
    its, plain = [], []
    cg(A, b, M=ml.aspreconditioner(), tol=1e-10, maxiter=200, residuals=its)
    cg(A, b, tol=1e-10, maxiter=100, residuals=plain)
    assert len(its) - 1 <= 20 and len(plain) - 1 >= 100
    # the preconditioner of the solver (float32 cycle) does as well
    pre = []
    cg(A, b, M=grid.preconditioner(A, idx), tol=1e-10, maxiter=200, residuals=pre)
    assert len(pre) - 1 <= 20


def _both_paths(film):
    fast = film.solve()
    general = film.with_(options=SolverOptions(structured=False)).solve()
    return fast, general


def test_wide_slider_on_both_paths(multigrid_from_200):
    """Infinitely wide inclined slider (K = 1, p = 0 at inlet and outlet, no flow across y: Dirichlet on
    left/right only), P1 on a graded 48 x 6 grid: the structured path (chosen automatically, with the
    multigrid) and the general path (Ruge-Stuben AMG) agree to 1e-8 of p_max (amg_tol 1e-10); both
    meet the closed-form pressure to 1.5e-3 of p_max (measured 6.1e-4 on both: P1 at 48 cells; the paths
    agree to 1.4e-12)."""
    L, h_out = 0.05, 20e-6
    m = meshes.rectangle(_graded(48, L, 1.02), np.linspace(0.0, 0.01, 7))
    film = Film(m, InclinedSlider(2 * h_out, h_out, L), Lubricant.newtonian(ETA), velocity_lower=(5.0, 0.0),
                dirichlet={"left": 0.0, "right": 0.0})
    fast, general = _both_paths(film)
    assert fast.info["linear_solver"] == "geometric multigrid (tensor grid) + CG"
    assert general.info["linear_solver"] == "amg (pyamg Ruge-Stuben + CG)"
    assert np.max(np.abs(fast.pressure_dofs - general.pressure_dofs)) <= 1e-8 * general.p_max
    x = fast.basis.doflocs[0]
    exact = cf.inclined_slider_pressure(x, 2 * h_out, h_out, L, ETA, 2.5)
    assert np.max(np.abs(fast.pressure_dofs - exact)) <= 1.5e-3 * np.max(exact)


def test_finite_slider_on_both_paths(multigrid_from_200):
    """Square pad, p = 0 on all edges (the benchmark's 1M-DOF scene at 40 x 40): load against the Fourier
    series (P1 error measured 1.7e-3 at 40 x 40 on both: bound 4e-3), the paths agree to 1e-8 of p_max
    (measured 7e-13)."""
    h_out, h_in, L = 20e-6, 44e-6, 0.05
    ref = cf.finite_slider_load(h_in, h_out, L, L, ETA, 2.5, n_terms=161)
    xs = np.linspace(0.0, L, 41)
    film = Film(meshes.rectangle(xs, xs), InclinedSlider(h_in, h_out, L), Lubricant.newtonian(ETA),
                velocity_lower=(5.0, 0.0))
    fast, general = _both_paths(film)
    assert fast.info["linear_solver"].startswith("geometric multigrid")
    assert np.max(np.abs(fast.pressure_dofs - general.pressure_dofs)) <= 1e-8 * general.p_max
    assert fast.load == pytest.approx(ref, rel=4e-3)
    assert fast.load == pytest.approx(general.load, rel=1e-9)


def test_cavitating_film_on_both_paths(multigrid_from_200):
    """Reynolds (Swift-Stieber) cavitation on a wavy pad (h = h0 (1 + 0.6 cos(2 pi x / L))): the active-set
    iterations reduce the system to the full-film nodes, so the multigrid runs on grid subsets; the
    pressures, the cavitated set (327 of 861 nodes) and the load agree with the general path (to 1e-8 of
    p_max; measured 2e-15: both Newton iterations end on the same discrete solution)."""
    L, h0 = 0.02, 10e-6
    xs, ys = np.linspace(0.0, L, 41), np.linspace(0.0, L / 2, 21)
    gap = FunctionGap(lambda x: h0 * (1 + 0.6 * np.cos(2 * np.pi * x[0] / L)))
    film = Film(meshes.rectangle(xs, ys), gap, Lubricant.newtonian(ETA), velocity_lower=(2.0, 0.0),
                cavitation=Cavitation("reynolds"), options=SolverOptions(warm_start_levels=0))
    fast, general = _both_paths(film)
    assert fast.info["linear_solver"].startswith("geometric multigrid")
    assert 0 < np.count_nonzero(~fast.full_film) < fast.full_film.size // 2
    assert np.array_equal(fast.full_film, general.full_film)
    assert np.max(np.abs(fast.pressure_dofs - general.pressure_dofs)) <= 1e-8 * general.p_max
    assert fast.load == pytest.approx(general.load, rel=1e-8)


def test_structured_option_is_checked():
    from lubedyn.lubrication.errors import InputError

    with pytest.raises(InputError, match="solver.structured = 'no' must be true or false"):
        SolverOptions(structured="no")
