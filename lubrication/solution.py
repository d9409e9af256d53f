"""FilmSolution: the solved film and every integral an engineer asks of it.

Conventions (SI):

- ``load_vector`` [N]: integral of (p - p_amb) n dA, with n the gap's
  ``surface_normal`` -- the force the film exerts on the *upper* body (for a
  journal bearing: on the journal, in the fixed frame).
- ``mode_forces`` [N]: generalised forces F_q = integral (p - p_amb) dh/dq dA.
- ``moment(point)`` [N m]: integral (X - point) x (p - p_amb) n dA in 3-D.
- ``friction_lower`` / ``friction_upper`` [N]: in-plane shear force of the fluid
  on the surface at z = 0 / z = h:  tau_lower = -(h/2) grad p + theta eta (U_u - U_l)/h,
  tau_upper = -(h/2) grad p - theta eta (U_u - U_l)/h  (Couette part scaled by
  the fluid fraction in cavitated zones).
- ``flow(boundary)`` [m^3/s]: outward volume flow q . n through a named
  boundary, q = -h^3/(12 eta) grad p + theta h u_m.
- ``h_min`` [m]: the smallest gap over nodes and quadrature points.
"""
from __future__ import annotations

import json
import logging
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import skfem
from skfem import Functional, asm
from skfem.helpers import dot

from .errors import InputError

log = logging.getLogger(__name__)

PRESSURE = "Pressure [Pa]"
THICKNESS = "Film thickness [m]"
FRACTION = "Fluid fraction [-]"


@Functional
def _integral(w):
    return w["f"]


@Functional
def _boundary_flux(w):
    return dot(w["q"], w.n)


@dataclass
class FilmSolution:
    """Result of :func:`lubrication.reynolds.solve` (see module docstring)."""

    film: object
    problem: object
    pressure_dofs: np.ndarray
    fluid_fraction_dofs: np.ndarray
    full_film: np.ndarray
    info: dict = field(default_factory=dict)

    # ------------------------------------------------------------ fields
    @property
    def basis(self) -> skfem.CellBasis:
        return self.problem.basis

    @property
    def pressure(self) -> np.ndarray:
        """Pressure [Pa] at the degrees of freedom (``basis.doflocs``)."""
        return self.pressure_dofs

    @property
    def fluid_fraction(self) -> np.ndarray:
        return self.fluid_fraction_dofs

    @property
    def film_thickness(self) -> np.ndarray:
        """Gap h [m] at the degrees of freedom."""
        return np.asarray(self.film.gap(self.basis.doflocs), dtype=float)

    def _gauge_q(self):
        return np.asarray(self.basis.interpolate(self.pressure_dofs)) - self.film.ambient_pressure

    def integrate(self, values_q) -> float:
        """Integral over the film of an array given at quadrature points."""
        return float(asm(_integral, self.basis, f=values_q))

    # ------------------------------------------------------------ loads
    @property
    def mode_forces(self) -> dict:
        pq = self._gauge_q()
        return {k: self.integrate(pq * g) for k, g in self.problem.modes.items()}

    @property
    def load_vector(self) -> np.ndarray:
        pq = self._gauge_q()
        n = self.film.gap.surface_normal(self.problem.x)
        return np.array([self.integrate(pq * n[i]) for i in range(3)])

    @property
    def load(self) -> float:
        """Magnitude of the load vector [N] (per unit width for 1-D films)."""
        return float(np.linalg.norm(self.load_vector))

    def moment(self, point=(0.0, 0.0, 0.0)) -> np.ndarray:
        pq = self._gauge_q()
        X = self.film.gap.surface_points(self.problem.x) - np.asarray(point, dtype=float).reshape(3, 1, 1)
        n = self.film.gap.surface_normal(self.problem.x)
        F = pq * n
        cross = np.stack([X[1] * F[2] - X[2] * F[1], X[2] * F[0] - X[0] * F[2], X[0] * F[1] - X[1] * F[0]])
        return np.array([self.integrate(cross[i]) for i in range(3)])

    @property
    def centre_of_pressure(self) -> np.ndarray:
        """Pressure-weighted mean position in the film plane [m]."""
        pq = self._gauge_q()
        total = self.integrate(pq)
        if total == 0.0:
            raise InputError("centre of pressure is undefined: the film carries no load")
        return np.array([self.integrate(pq * self.problem.x[i]) / total for i in range(self.problem.dim)])

    # ------------------------------------------------------------ friction and flow
    def _shear(self):
        prob = self.problem
        pf = self.basis.interpolate(self.pressure_dofs)
        eta = self.film.lubricant.viscosity(np.asarray(pf) - self.film.ambient_pressure)
        theta = np.asarray(self.basis.interpolate(self.fluid_fraction_dofs))
        couette = theta * eta * (prob.u_upper - prob.u_lower) / prob.h
        poiseuille = -0.5 * prob.h * pf.grad
        return poiseuille, couette

    @property
    def friction_lower(self) -> np.ndarray:
        pois, cou = self._shear()
        return np.array([self.integrate(pois[i] + cou[i]) for i in range(self.problem.dim)])

    @property
    def friction_upper(self) -> np.ndarray:
        pois, cou = self._shear()
        return np.array([self.integrate(pois[i] - cou[i]) for i in range(self.problem.dim)])

    def flow(self, boundary: str) -> float:
        """Outward volume flow [m^3/s] (per unit width in 1-D) through ``boundary``.

        On a Dirichlet (pressure) boundary the flow is the *consistent* flux:
        minus the sum of the Reynolds residual over the boundary's degrees of
        freedom, divided by the density there.  It is exactly mass conserving
        (the flows of all boundaries and the squeeze volume add to zero) and
        converges at the rate of the pressure itself.  Elsewhere the normal
        flux q . n is integrated pointwise over the facets.
        """
        mesh = self.film.mesh
        names = mesh.boundaries or {}
        if boundary not in names:
            raise InputError(f"boundary = {boundary!r} is unknown; the mesh has {sorted(names)}")
        prob = self.problem
        dofs = self.basis.get_dofs(names[boundary]).all()
        if dofs.size and np.all(prob.fixed[dofs]):
            jfo = self.film.cavitation.model == "jfo"
            R = prob.assemble(self.pressure_dofs, 1.0 - self.fluid_fraction_dofs, with_void=jfo)[0]
            p_b = float(np.mean(self.pressure_dofs[dofs])) - self.film.ambient_pressure
            return float(-np.sum(R[dofs]) / self.film.lubricant.density(p_b))
        fb = skfem.FacetBasis(mesh, self.basis.elem, facets=names[boundary], intorder=4)
        x = np.asarray(fb.global_coordinates())
        pf = fb.interpolate(self.pressure_dofs)
        theta = np.asarray(fb.interpolate(self.fluid_fraction_dofs))
        h = np.asarray(self.film.gap(x), dtype=float)
        eta = self.film.lubricant.viscosity(np.asarray(pf) - self.film.ambient_pressure)
        from .reynolds import _as_vector_field

        dim = prob.dim
        um = 0.5 * (
            _as_vector_field(self.film.velocity_lower, x, dim, "velocity_lower")
            + _as_vector_field(self.film.velocity_upper, x, dim, "velocity_upper")
        )
        q = -(h**3) / (12.0 * eta) * pf.grad + theta * h * um
        return float(asm(_boundary_flux, fb, q=q))

    # ------------------------------------------------------------ extremes
    @property
    def h_min(self) -> float:
        return float(min(np.min(self.problem.h), np.min(self.film_thickness)))

    @property
    def p_max(self) -> float:
        return float(np.max(self.pressure_dofs))

    @property
    def p_max_location(self) -> np.ndarray:
        return self.basis.doflocs[:, int(np.argmax(self.pressure_dofs))]

    def coefficients(self):
        """``(names, K, C)``: see :func:`lubrication.reynolds.film_coefficients`."""
        from .reynolds import film_coefficients

        return film_coefficients(self)

    # ------------------------------------------------------------ output
    def summary(self) -> dict:
        """Flat mapping of scalar results; names carry units."""
        out = {
            "Load [N]": self.load,
            "Maximum pressure [Pa]": self.p_max,
            "Minimum film thickness [m]": self.h_min,
            "Cavitated area fraction [-]": float(1.0 - self.integrate(np.asarray(self.basis.interpolate(self.fluid_fraction_dofs))) / self.integrate(np.ones_like(self.problem.h))),
            "Newton iterations [-]": int(self.info.get("iterations", 0)),
            "Degrees of freedom [-]": int(self.info.get("dofs", 0)),
            "Solve time [s]": float(self.info.get("wall_time", 0.0)),
        }
        for axis, value in zip("xyz", self.load_vector):
            out[f"Load {axis} [N]"] = float(value)
        for name, value in self.mode_forces.items():
            out[f"Mode force {name} [N]"] = float(value)
        for axis, value in zip("xy", self.friction_lower):
            out[f"Friction lower {axis} [N]"] = float(value)
        for axis, value in zip("xy", self.friction_upper):
            out[f"Friction upper {axis} [N]"] = float(value)
        return out

    def _vertex_values(self, dofs):
        """Values at mesh vertices (works on periodic DG-point meshes too)."""
        mesh = self.film.mesh
        ed = self.basis.element_dofs  # (ndofs_per_elem, nel), vertex dofs first
        nv = mesh.t.shape[0]
        out = np.zeros(mesh.p.shape[1])
        out[mesh.t] = dofs[ed[:nv]]
        return out

    def to_pyvista(self):
        """A ``pyvista.UnstructuredGrid`` with 3-D points and point data with units."""
        import pyvista as pv

        mesh = self.film.mesh
        pts = self.film.gap.surface_points(mesh.p).T.copy()
        kind = {2: pv.CellType.LINE, 3: pv.CellType.TRIANGLE, 4: pv.CellType.QUAD}[mesh.t.shape[0]]
        nv = mesh.t.shape[0]
        cells = np.hstack([np.full((mesh.t.shape[1], 1), nv), mesh.t.T]).ravel()
        grid = pv.UnstructuredGrid(cells, np.full(mesh.t.shape[1], kind, dtype=np.uint8), pts)
        grid.point_data[PRESSURE] = self._vertex_values(self.pressure_dofs)
        grid.point_data[THICKNESS] = np.asarray(self.film.gap(mesh.p), dtype=float)
        grid.point_data[FRACTION] = self._vertex_values(self.fluid_fraction_dofs)
        return grid

    def save(self, path) -> Path:
        """Write a ``.vtu`` file (atomically: a crash never leaves half a file)."""
        path = Path(path)
        if path.suffix != ".vtu":
            raise InputError(f"output path = {str(path)!r} must end in .vtu")
        path.parent.mkdir(parents=True, exist_ok=True)
        grid = self.to_pyvista()
        fd, tmp = tempfile.mkstemp(suffix=".vtu", dir=path.parent)
        os.close(fd)
        try:
            grid.save(tmp)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.remove(tmp)
        log.info("wrote %s", path)
        return path

    def plot_pressure(self, ax=None):
        """Pressure field (2-D: filled contours; 1-D: line).  Returns the figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt
        import matplotlib.tri as mtri

        mesh = self.film.mesh
        if ax is None:
            fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
        else:
            fig = ax.figure
        pv_ = self._vertex_values(self.pressure_dofs)
        if mesh.p.shape[0] == 1:
            order = np.argsort(mesh.p[0])
            ax.plot(mesh.p[0, order] * 1e3, pv_[order] / 1e6, "-")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("Pressure [MPa]")
        else:
            t = mesh.t
            tris = t.T if t.shape[0] == 3 else np.vstack([t[[0, 1, 2]].T, t[[0, 2, 3]].T])
            tri = mtri.Triangulation(mesh.p[0] * 1e3, mesh.p[1] * 1e3, tris)
            cs = ax.tripcolor(tri, pv_ / 1e6, shading="gouraud", cmap="viridis")
            fig.colorbar(cs, ax=ax, label="Pressure [MPa]")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            ax.set_aspect("auto")
        ax.set_title("Film pressure")
        return fig
