"""Guide-land film map of paper A's cage (issue 22): the project's Reynolds FEM journal with Reynolds
(Swift-Stieber) cavitation, tabulated for :func:`lubedyn.lubrication.laws.cage.guide_land_map_force`.

The cavitated finite journal is positively homogeneous in the Reynolds right-hand side g = A sin(theta)
- e' cos(theta) (line-of-centres frame, A = e (u_m/r - psi'), e' the radial speed), so one table over
eps and beta = atan2(e', A) in [-pi/2, pi/2] serves every speed, whirl and viscosity of one geometry
(r, c, b); the mirror theta -> -theta gives A < 0 (lubrication/laws/cage.py).  Each node is one FEM
solve: journal centre at (eps c, 0), surface speeds summing to U = 2 A r/e, squeeze dh/dt = -e'
cos(theta), G = |(A, e')| = 1 m/s, eta = 1 Pa s; the stored value is Phi = F c^3 (1 - eps^2)^2 /(eta G r
b^3) (radial along +x, tangential along +y).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubedyn.lubrication import Cavitation, Film, JournalBearing, Lubricant
from lubedyn.lubrication import mesh as meshes


@dataclass(frozen=True)
class GuideLandMap:
    """Axes and tables of the guide-land map (arguments of ``guide_land_map_force``)."""

    eps_axis: np.ndarray
    beta_axis: np.ndarray
    radial: np.ndarray
    tangential: np.ndarray
    radius: float
    clearance: float
    width: float
    stop_reasons: tuple

    def arrays(self):
        return self.eps_axis, self.beta_axis, self.radial, self.tangential


def journal_film_force(radius, clearance, width, eta, eps, surface_speed, e_dot=0.0, n_theta=256, n_z=4,
                       cavitation="reynolds"):
    """``(F_x, F_y, solution)``: the FEM finite journal with the journal centre at (eps c, 0) [N, on the
    journal], surface speeds summing to ``surface_speed`` [m/s], radial speed ``e_dot`` [m/s]
    (dh/dt = -e_dot cos(theta)), p = 0 on both land edges, P2 on ``n_theta`` x ``n_z`` quads."""
    m = meshes.rectangle(np.linspace(0.0, 2.0 * math.pi * radius, n_theta + 1), np.linspace(0.0, width, n_z + 1),
                         cell="quad", periodic_x=True)

    def squeeze(x):
        return -e_dot * np.cos(np.asarray(x[0]) / radius)

    film = Film(m, JournalBearing.from_ratio(radius, clearance, eps), Lubricant.newtonian(eta),
                velocity_upper=(surface_speed, 0.0), squeeze=squeeze if e_dot != 0.0 else 0.0,
                dirichlet={"bottom": 0.0, "top": 0.0}, element="P2", cavitation=Cavitation(cavitation, 0.0))
    sol = film.solve()
    return sol.mode_forces["x"], sol.mode_forces["y"], sol


def build_guide_land_map(radius, clearance, width, eps_axis, beta_axis, n_theta=256, n_z=4,
                         cavitation="reynolds") -> GuideLandMap:
    """One FEM solve per (eps, beta) node (module docstring)."""
    eps_axis = np.asarray(eps_axis, dtype=float)
    beta_axis = np.asarray(beta_axis, dtype=float)
    radial = np.zeros((eps_axis.size, beta_axis.size))
    tangential = np.zeros_like(radial)
    reasons = []
    for i, eps in enumerate(eps_axis):
        e = eps * clearance
        for j, beta in enumerate(beta_axis):
            A, e_dot = math.cos(beta), math.sin(beta)
            U = 2.0 * A * radius / e
            fx, fy, sol = journal_film_force(radius, clearance, width, 1.0, eps, U, e_dot, n_theta, n_z, cavitation)
            scale = radius * width ** 3 / clearance ** 3 / (1.0 - eps * eps) ** 2
            radial[i, j], tangential[i, j] = fx / scale, fy / scale
            reasons.append(getattr(sol, "stop_reason", ""))
    return GuideLandMap(eps_axis, beta_axis, radial, tangential, radius, clearance, width, tuple(reasons))
