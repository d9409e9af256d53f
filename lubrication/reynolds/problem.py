"""_Problem: assembly of the Reynolds residual and Jacobian, cavitation sets, linear solves.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import warnings

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem import asm
from skfem.mesh.mesh_dg import MeshDG

from .. import mesh as meshes
from ..errors import InputError, unknown_choice
from .diagnosis import amg_probe_iterations
from .forms import (advection_form, as_scalar_field, as_vector_field, assemble_diffusion, assemble_flux_load,
                    assemble_source_load, interpolate, make_basis, mass_form, streamline_form)
from .options import AMG_STALL_FACTOR, DIRECT_SOLVER_MAX_DOFS
from .tensor import tensor_grid

log = logging.getLogger(__name__)


def _select_columns(Jp, Jr, full_mask):
    """Matrix whose column j is Jp[:, j] for full-film nodes and Jr[:, j] otherwise."""
    Df = sp.diags(full_mask.astype(float))
    if Jr is None:
        return Jp @ Df
    return Jp @ Df + Jr @ sp.diags((~full_mask).astype(float))


class _Problem:
    """Everything about a film (:class:`~lubedyn.lubrication.reynolds.film.Film`) that does not change
    during the Newton solve."""

    def __init__(self, film):
        self.film = film
        # a P1 tensor quad mesh takes the structured path (lubedyn.lubrication.reynolds.tensor): quadrature points,
        # assembly and multigrid from the grid, the scikit-fem basis built only when something reads it
        self.grid = tensor_grid(film.mesh, film.element) if film.options.structured else None
        self._basis = None if self.grid is not None else make_basis(film.mesh, film.element)
        self.dim = film.mesh.p.shape[0]
        # (dim, nel, nqp)
        self.x = self.grid.quadrature_points() if self.grid is not None else np.asarray(self.basis.global_coordinates())
        self.h = np.asarray(film.gap(self.x), dtype=float)
        if not np.all(np.isfinite(self.h)):
            raise InputError("gap h is not finite everywhere on the film domain")
        if np.min(self.h) <= 0.0:
            where = np.unravel_index(np.argmin(self.h), self.h.shape)
            xm = self.x[(slice(None),) + where]
            raise InputError(
                f"gap h = {np.min(self.h):.4g} m at x = {np.array2string(xm, precision=4)} m; "
                "the film thickness must be > 0 everywhere (the surfaces touch or overlap)"
            )
        ul = as_vector_field(film.velocity_lower, self.x, self.dim, "velocity_lower [m/s]")
        uu = as_vector_field(film.velocity_upper, self.x, self.dim, "velocity_upper [m/s]")
        self.u_lower, self.u_upper = ul, uu
        self.um = 0.5 * (ul + uu)
        self.modes = {k: np.asarray(f(self.x), dtype=float) for k, f in film.gap.modes().items()}
        hdot = as_scalar_field(film.squeeze, self.x, "squeeze dh/dt [m/s]")
        for k, qd in film.mode_velocities.items():
            hdot = hdot + float(qd) * self.modes[k]
        self.hdot = hdot
        self._tau = None
        self.N = self.grid.N if self.grid is not None else self.basis.N
        self._dirichlet()
        self.linear = film.lubricant.is_constant
        self.cav = film.cavitation

    @property
    def basis(self) -> skfem.CellBasis:
        """The scikit-fem basis of the film (built on first use on the structured path)."""
        if self._basis is None:
            self._basis = make_basis(self.film.mesh, self.film.element)
        return self._basis

    @property
    def tau(self):
        """Streamline-diffusion parameter h_K/(2 order |u_m|) at the quadrature points (0 where
        u_m = 0).  Computed on first use: only JFO cavitation (and its film coefficients) reads
        it, and the element sizes are costly on large quad meshes (the 1M-DOF benchmark of
        benchmarks/reynolds.py)."""
        if self._tau is None:
            speed = np.sqrt(np.sum(self.um**2, axis=0))
            order = 2.0 if self.film.element == "P2" else 1.0
            hk = np.broadcast_to(self._element_size()[:, None], speed.shape)
            self._tau = np.where(speed > 0, hk / (2.0 * order * np.where(speed > 0, speed, 1.0)), 0.0)
        return self._tau

    def _element_size(self):
        m = self.film.mesh
        # vertex coordinates from the element mapping: on periodic (DG-point)
        # meshes m.p[:, m.t] does not address the geometry
        pts = meshes.element_vertices(m)  # (dim, nverts, nel)
        if self.dim == 1:
            return np.abs(pts[0, 1] - pts[0, 0])
        # longest edge of each element
        nv = pts.shape[1]
        hk = np.zeros(pts.shape[2])
        for i in range(nv):
            for j in range(i + 1, nv):
                hk = np.maximum(hk, np.linalg.norm(pts[:, i] - pts[:, j], axis=0))
        if isinstance(m, skfem.MeshQuad1):
            hk = hk / np.sqrt(2.0)  # diagonal -> side length of a square cell
        return hk

    def _dirichlet(self):
        film = self.film
        values = np.full(self.N, np.nan)
        if film.dirichlet is None:
            values[self._boundary_dofs()] = film.ambient_pressure
        else:
            names = film.mesh.boundaries or {}
            for name, value in film.dirichlet.items():
                if name not in names:
                    raise unknown_choice("film.dirichlet boundary", name, list(names))
                values[self.basis.get_dofs(names[name]).all()] = float(value)
        # on a periodic mesh (periodic in x, lubedyn.lubrication.mesh.rectangle) the seam
        # dofs sit at x = x_max: measure x distances modulo the period
        period = float(np.ptp(film.mesh.p[0])) if isinstance(film.mesh, MeshDG) else None
        for point, value in film.pressure_points:
            point = np.atleast_1d(np.asarray(point, dtype=float))
            doflocs = film.mesh.p if self.grid is not None else self.basis.doflocs  # P1: dof i is vertex i
            diff = doflocs - point[:, None]
            if period:
                diff[0] = (diff[0] + 0.5 * period) % period - 0.5 * period
            d = np.linalg.norm(diff, axis=0)
            values[int(np.argmin(d))] = float(value)
        self.fixed = ~np.isnan(values)
        if not np.any(self.fixed):
            raise InputError(
                "the film has no Dirichlet boundary or pressure point: its pressure is "
                "undetermined (give film.dirichlet, or pressure_points for a periodic film)"
            )
        self.p_fixed = np.where(self.fixed, values, 0.0)
        self.free = ~self.fixed

    def _boundary_dofs(self):
        """The dofs on every boundary facet (``film.dirichlet is None``).

        P1 (vertex dofs only): the nodal dofs of :func:`lubedyn.lubrication.mesh.boundary_vertices`,
        which finds them without building the mesh's facets (scikit-fem's
        ``boundary_facets`` is a sizeable share of the 1M-DOF solve of benchmarks/reynolds.py).
        Other elements: scikit-fem's ``get_dofs(boundary_facets())`` (their basis has built the
        facets already, for the edge dofs).  Both give the same set
        (``tests/test_reynolds_fast_paths.py``).
        """
        if self.grid is not None:
            return self.grid.boundary_dofs()
        b, mesh = self.basis, self.film.mesh
        e = b.elem
        vertex_only = e.nodal_dofs == 1 and not (e.facet_dofs or e.interior_dofs or getattr(e, "edge_dofs", 0))
        verts = meshes.boundary_vertices(mesh) if vertex_only else None
        if verts is None:
            return b.get_dofs(mesh.boundary_facets()).all()
        return b.nodal_dofs[0, verts]

    # ------------------------------------------------------------------
    def coefficients(self, p, r, pressure: bool = True):
        """Quadrature-point fields for the current iterate.

        ``pressure=False`` (only for pressure-independent lubricants, ``self.linear``): the
        laws are evaluated at gauge pressure 0 instead of at the interpolated p, which they do
        not read, and ``pq``/``gp`` are None: this skips interpolating p and its gradient
        (a visible share of the 1M-DOF benchmark's assembly, benchmarks/reynolds.py).
        """
        lub = self.film.lubricant
        if pressure:
            pf = interpolate(self.basis, p)
            pq = np.asarray(pf) - self.film.ambient_pressure
            gp = pf.grad
            at = pq
        else:
            pq = gp = None
            at = np.zeros(self.h.shape)
        eta, deta = lub.viscosity(at), lub.viscosity.derivative(at)
        rho, drho = lub.density(at), lub.density.derivative(at)
        if not np.any(r):  # (no basis needed: the structured path may not have one)
            rf = skfem.element.DiscreteField(np.zeros(self.h.shape), np.zeros((self.dim,) + self.h.shape))
        else:
            rf = interpolate(self.basis, r)
        return dict(pq=pq, gp=gp, eta=eta, deta=deta, rho=rho, drho=drho, r=np.asarray(rf), gr=rf.grad)

    def assemble(self, p, r, with_void: bool):
        """Residual R, dR/dp and (if ``with_void``) dR/dr at (p, r).

        For pressure-independent lubricants R is affine, R = A p + Jr r + R(0, 0):
        the matrices are assembled once and reused.
        """
        if self.linear and getattr(self, "_cache", None) is not None and (self._cache[1] is not None or not with_void):
            A, Jr, R0 = self._cache
            R = A @ p + R0
            if with_void:
                R = R + Jr @ r
            return R, A, Jr
        c = self.coefficients(p, r, pressure=not self.linear)
        h, um, hdot = self.h, self.um, self.hdot
        theta = 1.0 - c["r"]
        k = c["rho"] * h**3 / (12.0 * c["eta"])
        grid = self.grid
        K0 = grid.diffusion(k) if grid is not None else assemble_diffusion(self.basis, k)
        A = K0
        if not self.linear:
            dk = h**3 / 12.0 * (c["drho"] / c["eta"] - c["rho"] * c["deta"] / c["eta"] ** 2)
            bvec = dk * c["gp"] - c["drho"] * h * theta * um
            b = self.basis
            A = (K0 + asm(advection_form, b, b=bvec) + asm(mass_form, b, c=c["drho"] * theta * hdot)).tocsr()
        # R = k grad p . grad v - rho h theta um . grad v + rho theta hdot v - SU(r)
        flux, source = -c["rho"] * h * theta * um, c["rho"] * theta * hdot
        if grid is not None:
            R = K0 @ p + grid.flux_load(flux) + grid.source_load(source)
        else:
            R = K0 @ p + assemble_flux_load(self.basis, flux) + assemble_source_load(self.basis, source)
        Jr = None
        if with_void:
            b = self.basis
            S = asm(streamline_form, b, s=self.tau * c["rho"] * h, beta=um)
            Jr = (asm(advection_form, b, b=c["rho"] * h * um) - asm(mass_form, b, c=c["rho"] * hdot) - S).tocsr()
            R = R - S @ r
        if self.linear:
            self._cache = (A, Jr, R - A @ p - (Jr @ r if Jr is not None else 0.0))
        return R, A, Jr

    def solve_linear(self, M, rhs, symmetric: bool, index=None):
        """Solve ``M x = rhs`` with the solver that ``film.options.linear_solver`` picks.

        ``"auto"`` checks AMG-CG on its first solve (:data:`AMG_STALL_FACTOR`): if CG has
        not reached ``amg_tol`` within :func:`amg_probe_iterations` iterations, AMG has
        stalled (graded meshes), this system and every later one of the solve go to SuperLU,
        and ``linear_solver_used`` says why.  On the structured path (a P1 tensor grid, ``index``:
        the grid dofs of the rows of ``M``) ``"auto"`` preconditions CG with the grid's geometric
        multigrid (:meth:`lubedyn.lubrication.reynolds.tensor.TensorGrid.multigrid`) instead of
        Ruge-Stuben AMG, with the same check; ``"amg"`` keeps Ruge-Stuben."""
        opts = self.film.options
        n = M.shape[0]
        use_amg = opts.linear_solver == "amg" or (
            opts.linear_solver == "auto" and symmetric and n > DIRECT_SOLVER_MAX_DOFS
            and getattr(self, "amg_stall", None) is None
        )
        if use_amg:
            import pyamg

            # classical AMG: on the 1M-DOF benchmark matrix (benchmarks/reynolds.py) its setup is
            # faster than smoothed aggregation's (whose Jacobi prolongation smoother estimates
            # spectral radii, slow on a busy machine) and CG needs fewer iterations.  On a tensor grid the
            # geometric hierarchy skips the strength, splitting and interpolation passes of the setup (0.45
            # against 1.9 s at 1M DOFs) and CG needs 7 instead of 9 iterations (benchmarks/reynolds.py)
            probe = opts.linear_solver == "auto" and not getattr(self, "amg_checked", False)
            maxiter = amg_probe_iterations(opts.amg_tol) if probe else 200
            geometric = opts.linear_solver == "auto" and self.grid is not None and index is not None
            kind = "geometric multigrid (tensor grid) + CG" if geometric else "amg (pyamg Ruge-Stuben + CG)"
            label = "multigrid-CG" if geometric else "AMG-CG"
            method = "geometric, tensor grid" if geometric else "Ruge-Stuben"
            residuals = []
            if geometric:  # CG in float64 on M, preconditioned by a float32 V-cycle of the grid's hierarchy
                from pyamg.krylov import cg

                x, _ = cg(M, rhs, M=self.grid.preconditioner(M, index), tol=opts.amg_tol, maxiter=maxiter,
                          residuals=residuals)
            else:
                ml = pyamg.ruge_stuben_solver(M.tocsr())
                x = ml.solve(rhs, tol=opts.amg_tol, accel="cg", maxiter=maxiter, residuals=residuals)
            iterations = len(residuals) - 1
            relative = residuals[-1] / max(residuals[0], 1e-300) if residuals else 0.0
            self.amg_checked = True
            if probe and relative > opts.amg_tol:
                self.amg_stall = (relative, iterations)
                self.linear_solver_used = (f"direct (SuperLU) after {label} stalled: residual {relative:.2e} "
                                           f"after {iterations} iterations")
                log.info("linear solver auto: %s (%s) stalled on the first of %d unknowns "
                         "(relative residual %.2e > amg_tol %.1e after %d iterations: mean convergence factor "
                         "%.2f > %.2f); SuperLU solves this system and the rest of the solve", label, method, n,
                         relative, opts.amg_tol, iterations, relative ** (1.0 / max(iterations, 1)), AMG_STALL_FACTOR)
                return self._direct(M, rhs)
            if relative > opts.amg_tol:
                log.warning("%s stopped at relative residual %.2e > amg_tol %.1e after %d iterations",
                            label, relative, opts.amg_tol, iterations)
            self.linear_solver_used = kind
            return x
        if getattr(self, "amg_stall", None) is None:
            self.linear_solver_used = "direct (SuperLU)"
        return self._direct(M, rhs)

    @staticmethod
    def _direct(M, rhs):
        # an exactly singular matrix gives non-finite values, which the Newton loop reports as
        # one clear ConvergenceError (no scipy MatrixRankWarning on the user's terminal)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", spla.MatrixRankWarning)
            return spla.spsolve(M.tocsc(), rhs)
