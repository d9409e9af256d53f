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

``summary()`` names carry units; for 1-D films (per unit width in y) every
force, flow and coefficient name says so: ``"Load per unit width [N/m]"``,
``"Flow right per unit width [m^2/s]"``, ``"Stiffness K[h0,h0] per unit width
[N/m^2]"``.

Periodic meshes: ``mesh.t`` numbers vertices topologically (the seam is one
vertex) while ``mesh.p`` holds per-element copies; output takes vertex
coordinates from the element mapping (:func:`lubedyn.lubrication.mesh.element_vertices`)
and values from the vertex degrees of freedom (first in ``element_dofs``).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import skfem
from skfem import Functional, asm
from skfem.helpers import dot

from .. import mesh as meshes
from ..errors import InputError
from ..vtu import write_vtu
from .coefficients import film_coefficients
from .forms import as_vector_field, interpolate, unwrapped_dofs

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


@skfem.LinearForm
def _unit_load(v, w):
    return v


_PER_UNIT_WIDTH = (("[N]", "[N/m]"), ("[m^3/s]", "[m^2/s]"), ("[N/m]", "[N/m^2]"), ("[N s/m]", "[N s/m^2]"))


def per_unit_width(key: str) -> str:
    """The name of a per-area result of a 1-D film (per unit width in y).

    >>> per_unit_width("Load [N]"), per_unit_width("Flow left [m^3/s]")
    ('Load per unit width [N/m]', 'Flow left per unit width [m^2/s]')
    >>> per_unit_width("Maximum pressure [Pa]")
    'Maximum pressure [Pa]'
    """
    for unit, new in _PER_UNIT_WIDTH:
        if key.endswith(" " + unit):
            return f"{key[: -len(unit) - 1]} per unit width {new}"
    return key


# Elements across the minimum-gap zone (h < 2 h_min; FilmSolution.min_gap_elements) below which a
# film warns.  benchmarks/method_limits.py (sweep 3) measures the load error of the finite journal of
# cases/journal_finite.toml (L/D = 1, Reynolds cavitation) at eps 0.6 ... 0.999 on 32x8 ... 256x64 quads
# against the finest mesh, with the elements across the zone of each: P2 errors fall below 1 % at about
# 2 elements across and below 0.05 % from about 8, P1 ones need about 10 for 1 % (at small eccentricity
# a coarse P1 mesh's error is the whole film's resolution, not the zone's).  The P2 errors overlap near
# 2 elements, so 2.2 (P2) warns for every error beyond 1 % in that sweep and passes the bundled cases'
# smoke meshes (ball_ball_squeeze's has the fewest, about 2.4); 12 (P1) warns for every zone-limited
# error beyond 1 %.  The estimate depends on the geometry and mesh only, not on the solve, so round-off
# cannot move it; tests/test_film_resolution.py pins the element counts of the journal at eps 0.999.
MIN_GAP_ELEMENTS = {"P1": 12, "P2": 2.2}


@dataclass
class FilmSolution:
    """Result of :func:`lubedyn.lubrication.reynolds.solve` (see module docstring)."""

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

    def _field_q(self, dofs):
        grid = getattr(self.problem, "grid", None)  # the structured path needs no scikit-fem basis here
        return grid.interpolate(dofs) if grid is not None else interpolate(self.basis, dofs)

    def _gauge_q(self):
        return np.asarray(self._field_q(self.pressure_dofs)) - self.film.ambient_pressure

    def integrate(self, values_q) -> float:
        """Integral over the film of an array given at quadrature points."""
        grid = getattr(self.problem, "grid", None)
        if grid is not None:
            return grid.integrate(values_q)
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
        pf = self._field_q(self.pressure_dofs)
        eta = self.film.lubricant.viscosity(np.asarray(pf) - self.film.ambient_pressure)
        theta = np.asarray(self._field_q(self.fluid_fraction_dofs))
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
        flux q . n is integrated pointwise over the facets: on a sealed
        (natural) boundary it is the discretisation's leakage, which vanishes
        with the mesh.
        """
        names = self.film.mesh.boundaries or {}
        if boundary not in names:
            raise InputError(f"boundary = {boundary!r} is unknown; the mesh has {sorted(names)}")
        prob = self.problem
        dofs = self.basis.get_dofs(names[boundary]).all()
        if dofs.size and np.all(prob.fixed[dofs]):
            R = self._residual()
            p_b = float(np.mean(self.pressure_dofs[dofs])) - self.film.ambient_pressure
            return float(-np.sum(R[dofs]) / self.film.lubricant.density(p_b))
        return self._pointwise_flow(boundary)

    def _residual(self):
        if getattr(self, "_residual_cache", None) is None:
            jfo = self.film.cavitation.model == "jfo"
            self._residual_cache = self.problem.assemble(
                self.pressure_dofs, 1.0 - self.fluid_fraction_dofs, with_void=jfo)[0]
        return self._residual_cache

    def _pointwise_flow(self, boundary: str) -> float:
        """Integral of q . n over the facets of ``boundary``.

        A facet basis needs a boundary mapping, which scikit-fem's periodic
        (DG-point) meshes lack: there the integral runs over the unwrapped mesh
        (same elements, seam cut open) with the fields carried over dof by dof.
        """
        mesh, index = unwrapped_dofs(self.basis)
        fb = skfem.FacetBasis(mesh, self.basis.elem, facets=mesh.boundaries[boundary], intorder=4)
        x = np.asarray(fb.global_coordinates())
        pf = fb.interpolate(self.pressure_dofs[index])
        theta = np.asarray(fb.interpolate(self.fluid_fraction_dofs[index]))
        h = np.asarray(self.film.gap(x), dtype=float)
        eta = self.film.lubricant.viscosity(np.asarray(pf) - self.film.ambient_pressure)
        dim = self.problem.dim
        um = 0.5 * (
            as_vector_field(self.film.velocity_lower, x, dim, "velocity_lower")
            + as_vector_field(self.film.velocity_upper, x, dim, "velocity_upper")
        )
        q = -(h**3) / (12.0 * eta) * pf.grad + theta * h * um
        return float(asm(_boundary_flux, fb, q=q))

    # ------------------------------------------------------------ extremes
    @property
    def h_min(self) -> float:
        return float(min(np.min(self.problem.h), np.min(self.film_thickness)))

    def min_gap_elements(self) -> float:
        """Elements across the minimum-gap zone (where h < 2 h_min), estimated from the gap's
        slope: ``4 h_min / max(|grad h| h_K)`` over the elements of the zone (h_K: element size;
        for a parabolic gap h_min (1 + (x/a)^2) the zone is 2a wide and the slope at its edge
        gives exactly its number of elements).  Central differences of the gap at the
        quadrature points (step 1e-3 h_K), so a step in the gap (zero slope on both sides) does
        not count; a gap with no slope in the zone gives ``inf``."""
        prob = self.problem
        x, h = prob.x, prob.h
        hk = prob._element_size()
        h_min = float(np.min(h))
        zone = np.min(h, axis=1) < 2.0 * h_min
        xz = x[:, zone]
        delta = 1e-3 * hk[zone][None, :, None] * np.ones(xz.shape[1:])
        slope2 = np.zeros(xz.shape[1:])
        for d in range(xz.shape[0]):
            step = np.zeros_like(xz)
            step[d] = delta[0]
            dh = np.asarray(self.film.gap(xz + step)) - np.asarray(self.film.gap(xz - step))
            slope2 = slope2 + (dh / (2.0 * delta[0])) ** 2
        rise = np.max(np.sqrt(slope2) * hk[zone][:, None])
        return float(4.0 * h_min / rise) if rise > 0 else float("inf")

    def resolution_warning(self) -> str | None:
        """One line if the minimum-gap zone has fewer than :data:`MIN_GAP_ELEMENTS` elements
        across (:meth:`min_gap_elements`) for the element order, else None.  The text names the
        refinement needed (``refine`` below: the factor, rounded up)."""
        n = self.min_gap_elements()
        need = MIN_GAP_ELEMENTS[self.film.element]
        if not n < need:
            return None
        factor = int(np.ceil(need / max(n, 1e-3)))
        self.info["min_gap_refine"] = factor
        return (f"Minimum-gap zone (h < 2 h_min = {2 * self.h_min:.3g} m) resolved by {n:.2g} elements across, "
                f"fewer than {need} for {self.film.element}: the load converges in the iterations but not in "
                f"the mesh; refine the mesh about {factor}x across that zone")

    @property
    def warnings(self) -> list[str]:
        """One-line warnings about this solution (empty: none), each logged (WARNING, logger
        ``lubedyn.lubrication.reynolds.solution``) once by :func:`lubedyn.lubrication.reynolds.solve` when it returned the
        solution; today the JFO fluid fraction below 0 (:meth:`fluid_fraction_warning`).  Also in
        ``info["warnings"]``; the film scene lists them under "Warnings" in summary.json."""
        return list(self.info.get("warnings", ()))

    def report_warnings(self) -> "FilmSolution":
        """Check the solution (:meth:`fluid_fraction_warning`), keep what it finds in
        ``info["warnings"]`` (:attr:`warnings`) and log each line at WARNING; returns ``self``.
        :func:`lubedyn.lubrication.reynolds.solve` calls it on the solution it returns."""
        found = [text for text in (self.fluid_fraction_warning(),) if text]
        self.info["warnings"] = found
        for text in found:
            log.warning("%s", text)
        return self

    def fluid_fraction_warning(self) -> str | None:
        """One line if a JFO film's fluid fraction leaves [0, 1] at a node (below -1e-9): the
        complementarity bounds the void fraction r = 1 - theta from below only, so a film that
        would need more gas than gap (theta < 0) converges to a state no fluid can be in.
        The bundled journal with JFO cavitation whose centre moves sideways shows it
        (tests/test_film_stop_reasons.py, tests/test_film_health.py)."""
        if self.film.cavitation.model != "jfo":
            return None
        theta = self.fluid_fraction_dofs[self.problem.free]
        low = float(np.min(theta)) if theta.size else 1.0
        if low >= -1e-9:
            return None
        where = self.basis.doflocs[:, self.problem.free][:, int(np.argmin(theta))]
        return (f"Fluid fraction down to {low:.3g} at x = {np.array2string(where, precision=4)} m (JFO allows "
                "[0, 1]): the Newton iteration converged to a state with more gas than gap, which is no film; "
                "the mass-conserving transport does not hold here (e.g. a separating squeeze); do not use its "
                "loads, or use cavitation model 'reynolds'")

    @property
    def p_max(self) -> float:
        return float(np.max(self.pressure_dofs))

    @property
    def p_max_location(self) -> np.ndarray:
        return self.basis.doflocs[:, int(np.argmax(self.pressure_dofs))]

    def coefficients(self):
        """``(names, K, C)``: see :func:`lubedyn.lubrication.reynolds.film_coefficients`."""
        return film_coefficients(self)

    # ------------------------------------------------------------ output
    @property
    def cavitated_area_fraction(self) -> float:
        """Area of the cavitated region over the film area [-]: the indicator
        of the cavitated nodes (not ``full_film``) integrated as a field of the
        solution's element (nodal weights int phi_i dA)."""
        weights = asm(_unit_load, self.basis)
        return float(np.dot(weights, ~self.full_film) / np.sum(weights))

    @property
    def mean_void_fraction(self) -> float:
        """1 - (mean fluid fraction) over the film area [-] (JFO: the share of the
        film volume that is gas; 0 for the other models)."""
        area = self.integrate(np.ones_like(self.problem.h))
        return float(1.0 - self.integrate(np.asarray(self._field_q(self.fluid_fraction_dofs))) / area)

    def summary(self, boundaries=None, coefficients=None) -> dict:
        """Flat mapping of scalar results; names carry units.

        1-D films are per unit width: their names say so
        (:func:`per_unit_width`), e.g. ``"Load per unit width [N/m]"``.

        Parameters
        ----------
        boundaries : iterable of str, optional
            Boundaries whose :meth:`flow` is listed (``"Flow <name> [m^3/s]"``);
            default: the Dirichlet (pressure) boundaries.
        coefficients : tuple, optional
            ``(names, K, C)`` from :meth:`coefficients`, listed as
            ``"Stiffness K[a,b] [N/m]"`` and ``"Damping C[a,b] [N s/m]"``.
        """
        out = {
            "Load [N]": self.load,
            "Maximum pressure [Pa]": self.p_max,
            "Minimum film thickness [m]": self.h_min,
            "Cavitated area fraction [-]": self.cavitated_area_fraction,
            "Mean void fraction [-]": self.mean_void_fraction,
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
        if boundaries is None:
            names = sorted((self.film.mesh.boundaries or {}).keys())
            dirichlet = self.film.dirichlet
            boundaries = names if dirichlet is None else [n for n in names if n in dirichlet]
        for name in boundaries:
            out[f"Flow {name} [m^3/s]"] = self.flow(name)
        if coefficients is not None:
            modes, K, C = coefficients
            for i, a in enumerate(modes):
                for j, b in enumerate(modes):
                    out[f"Stiffness K[{a},{b}] [N/m]"] = float(K[i, j])
            for i, a in enumerate(modes):
                for j, b in enumerate(modes):
                    out[f"Damping C[{a},{b}] [N s/m]"] = float(C[i, j])
        if self.problem.dim == 1:
            out = {per_unit_width(k): v for k, v in out.items()}
        return out

    def _vertex_values(self, dofs):
        """Values at the mesh's topological vertices (``mesh.t`` numbering)."""
        t = self.film.mesh.t
        out = np.zeros(int(t.max()) + 1)
        out[t] = dofs[self.basis.element_dofs[: t.shape[0]]]  # vertex dofs come first
        return out

    def _vertex_points(self):
        """Film-plane coordinates (dim, n) of the topological vertices.  On a
        periodic mesh a seam vertex gets the coordinates of one side (both map
        to the same point on the wrapped surface)."""
        t = self.film.mesh.t
        x = np.zeros((self.problem.dim, int(t.max()) + 1))
        x[:, t] = meshes.element_vertices(self.film.mesh)
        return x

    def to_pyvista(self):
        """A ``pyvista.UnstructuredGrid`` with 3-D points and point data with units.

        One point per topological vertex: on a periodic mesh the two sides of
        the seam are one point, so the wrapped journal surface is watertight.
        """
        import pyvista as pv

        mesh = self.film.mesh
        x = self._vertex_points()
        pts = np.asarray(self.film.gap.surface_points(x)).T.copy()
        nv, nel = mesh.t.shape
        kind = {2: pv.CellType.LINE, 3: pv.CellType.TRIANGLE, 4: pv.CellType.QUAD}[nv]
        cells = np.hstack([np.full((nel, 1), nv), mesh.t.T]).ravel()
        grid = pv.UnstructuredGrid(cells, np.full(nel, kind, dtype=np.uint8), pts)
        grid.point_data[PRESSURE] = self._vertex_values(self.pressure_dofs)
        grid.point_data[THICKNESS] = np.asarray(self.film.gap(x), dtype=float)
        grid.point_data[FRACTION] = self._vertex_values(self.fluid_fraction_dofs)
        return grid

    def save(self, path) -> Path:
        """Write a ``.vtu`` file (atomically: a crash never leaves half a file)."""
        return write_vtu(self.to_pyvista(), path)

    def plot_pressure(self, ax=None):
        """Pressure field (2-D: filled contours; 1-D: line).  Returns the figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt
        import matplotlib.tri as mtri

        if ax is None:
            fig, ax = plt.subplots(figsize=(6.4, 4.2), constrained_layout=True)
        else:
            fig = ax.figure
        # the unwrapped mesh: same elements, periodic seam cut open, so that no
        # triangle spans the film
        t = meshes.unwrapped(self.film.mesh).t
        n = int(t.max()) + 1
        values = np.zeros(n)
        values[t] = self.pressure_dofs[self.basis.element_dofs[: t.shape[0]]]  # vertex dofs come first
        xy = np.zeros((self.problem.dim, n))
        xy[:, t] = meshes.element_vertices(self.film.mesh)
        if xy.shape[0] == 1:
            order = np.argsort(xy[0])
            ax.plot(xy[0, order] * 1e3, values[order] / 1e6, "-")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("Pressure [MPa]")
        else:
            tris = t.T if t.shape[0] == 3 else np.vstack([t[[0, 1, 2]].T, t[[0, 2, 3]].T])
            tri = mtri.Triangulation(xy[0] * 1e3, xy[1] * 1e3, tris)
            cs = ax.tripcolor(tri, values / 1e6, shading="gouraud", cmap="viridis")
            fig.colorbar(cs, ax=ax, label="Pressure [MPa]")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            ax.set_aspect("auto")
        ax.set_title("Film pressure")
        return fig
