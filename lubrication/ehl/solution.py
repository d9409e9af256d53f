"""EHLSolution: pressure, film, load, traction and their outputs (VTK, plots).

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from skfem import asm

from ..reynolds.forms import source_load_form
from ..vtu import write_vtu
from .contact import EHLContact


@dataclass
class EHLSolution:
    """Converged EHL contact.  Arrays are on the dofs of ``problem.basis``."""

    contact: EHLContact
    problem: object
    pressure: np.ndarray
    film_thickness: np.ndarray
    h00: float
    info: dict = field(default_factory=dict)

    @property
    def deflection(self) -> np.ndarray:
        return self.problem.deflect(self.pressure)

    def _centre_line(self, values):
        P = self.problem
        loc = P.doflocs
        on = np.ones(P.N, dtype=bool) if P.c.is_line else np.abs(loc[1]) < 0.5 * P.dy
        order = np.argsort(loc[0][on])
        return loc[0][on][order], values[on][order]

    @property
    def central_film_thickness(self) -> float:
        """h at x = y = 0 [m]."""
        P = self.problem
        d = np.linalg.norm(P.doflocs, axis=0)
        return float(self.film_thickness[np.argmin(d)])

    @property
    def minimum_film_thickness(self) -> float:
        return float(np.min(self.film_thickness))

    @property
    def maximum_pressure(self) -> float:
        return float(np.max(self.pressure))

    @property
    def pressure_spike_position(self) -> float:
        """x [m] of the pressure spike: the most downstream local maximum of the
        centre-line pressure with x > 0 (the global maximum if there is none)."""
        x, p = self._centre_line(self.pressure)
        inner = np.flatnonzero((p[1:-1] > p[:-2]) & (p[1:-1] >= p[2:]) & (x[1:-1] > 0)) + 1
        if inner.size:
            return float(x[inner[-1]])
        return float(x[np.argmax(p)])

    @property
    def load(self) -> float:
        return float(self.problem.weights @ self.pressure)

    def _shear_integrals(self, sliding=None):
        P, c = self.problem, self.contact
        b = P.basis
        pf = b.interpolate(self.pressure)
        pq = np.maximum(np.asarray(pf), 0.0)
        hq = np.asarray(b.interpolate(np.maximum(self.film_thickness, P.o.h_floor * P.hscale)))
        eta = c.lubricant.viscosity(pq)
        if sliding is None:
            sliding = c.slide_to_roll * c.mean_speed
        couette = c.traction.stress(eta, sliding, hq, pq)
        poiseuille = -0.5 * hq * pf.grad[0]
        ones = np.ones(P.N)
        return (float(asm(source_load_form, b, g=couette) @ ones), float(asm(source_load_form, b, g=poiseuille) @ ones))

    def friction(self, sliding: float | None = None) -> float:
        """Sliding (Couette) friction force [N, or N/m for lines] that the fluid
        exerts on the slower surface, from the chosen traction law; at the sliding speed
        ``sliding`` [m/s] when given (post-processing: the isothermal pressure does not depend
        on it), else the contact's slide_to_roll x mean_speed."""
        return self._shear_integrals(sliding)[0]

    def rolling_resistance(self) -> float:
        """Poiseuille shear force -(h/2) dp/dx integrated [N or N/m] (rolling friction)."""
        return self._shear_integrals()[1]

    def traction_coefficient(self) -> float:
        return self.friction() / self.load

    def to_pyvista(self):
        """Grid with 3-D points (z = 0) and point data "Pressure [Pa]",
        "Film thickness [m]", "Elastic deflection [m]"."""
        import pyvista as pv

        P = self.problem
        pts = np.zeros((P.N, 3))
        pts[:, : P.doflocs.shape[0]] = P.doflocs.T
        t = P.mesh.t
        nv = t.shape[0]
        kind = pv.CellType.LINE if nv == 2 else pv.CellType.QUAD
        cells = np.hstack([np.full((t.shape[1], 1), nv), t.T]).ravel()
        grid = pv.UnstructuredGrid(cells, np.full(t.shape[1], kind, dtype=np.uint8), pts)
        # P1 on a tensor mesh: dof i is vertex i
        grid.point_data["Pressure [Pa]"] = self.pressure
        grid.point_data["Film thickness [m]"] = self.film_thickness
        grid.point_data["Elastic deflection [m]"] = self.deflection
        return grid

    def save(self, path):
        """Write the fields to a ``.vtu`` file (temporary file + rename)."""
        return write_vtu(self.to_pyvista(), path)

    def plot_profiles(self):
        """Centre-line pressure and film thickness against x/b.  Returns the figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        P = self.problem
        x, p = self._centre_line(self.pressure)
        _, h = self._centre_line(self.film_thickness)
        fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
        ax.plot(x / P.bx, p / 1e9, "C0-", label="pressure")
        ax.set_xlabel("x / b [-]")
        ax.set_ylabel("Pressure [GPa]", color="C0")
        ax2 = ax.twinx()
        ax2.plot(x / P.bx, h * 1e6, "C1-", label="film thickness")
        ax2.set_ylabel("Film thickness [um]", color="C1")
        ax2.set_ylim(0, 4 * self.central_film_thickness * 1e6)
        ax.set_title(f"EHL centre line (M = {self.contact.moes_M:.3g}, L = {self.contact.moes_L:.3g})")
        return fig

    def summary(self) -> dict:
        c = self.contact
        out = {
            "Central film thickness [m]": self.central_film_thickness,
            "Minimum film thickness [m]": self.minimum_film_thickness,
            "Maximum pressure [Pa]": self.maximum_pressure,
            "Hertz pressure [Pa]": float(self.problem.ph),
            "Pressure spike position [m]": self.pressure_spike_position,
            "Load [N]" if not c.is_line else "Load per length [N/m]": self.load,
            "Approach h00 [m]": float(self.h00),
            "Friction [N]" if not c.is_line else "Friction per length [N/m]": self.friction(),
            "Traction coefficient [-]": self.traction_coefficient(),
            "Rolling resistance [N]" if not c.is_line else "Rolling resistance per length [N/m]": self.rolling_resistance(),
            "Moes M [-]": c.moes_M,
            "Moes L [-]": c.moes_L,
            ("Multigrid cycles [-]" if self.info.get("method") == "multigrid" else "Newton iterations [-]"):
                int(self.info.get("iterations", 0)),
            "Solve time [s]": float(self.info.get("wall_time", 0.0)),
        }
        return out
