"""The film to solve: Film (gap, surfaces, lubricant, mesh, boundaries, cavitation, solver options).

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
from dataclasses import dataclass, field, replace
from typing import Callable, Mapping

import skfem

from ..errors import InputError, unknown_choice
from ..gaps import Gap
from ..laws.lubricant import Lubricant
from ..laws.units import quantity, si_fields
from .options import ELEMENT_ORDERS, Cavitation, SolverOptions
from .solution import FilmSolution
from .solve import solve

log = logging.getLogger(__name__)

Field = float | tuple | Callable


@dataclass(frozen=True)
class Film:
    """A lubricant film problem (SI units; the velocities, ``squeeze`` and ``ambient_pressure`` also as strings
    with units, ``velocity_lower=("5 m/s",)``, read by the case files' parser
    :mod:`lubedyn.lubrication.laws.units`).

    Parameters
    ----------
    mesh : skfem.Mesh
        1-D (``MeshLine``) or 2-D (triangles, quadrilaterals; periodic in x
        allowed) mesh of the film plane, with named boundaries.
    gap : Gap
        Film thickness h(x) [m] and its rigid-body modes.
    lubricant : Lubricant
    velocity_lower, velocity_upper : tuple or callable
        Tangential velocity [m/s] of the surface at z = 0 and at z = h, each a
        constant vector (length = mesh dimension) or ``f(x) -> (dim, ...)``.
    squeeze : float or callable
        Extra local dh/dt [m/s] (negative = approach), added to the mode
        velocities ``mode_velocities`` (mode name -> dq/dt).
    dirichlet : mapping, optional
        Boundary name -> pressure [Pa].  ``None``: every boundary facet at
        ``ambient_pressure``.  An empty mapping is allowed only together with
        ``pressure_points``.
    pressure_points : tuple of ((x, y...), value)
        Extra nodes (nearest degree of freedom) held at a pressure, e.g. the
        Sommerfeld condition p(theta = 0) = 0 of an infinitely long journal.
    element : "P1" or "P2"
    cavitation : Cavitation
    ambient_pressure : float
        Gauge reference [Pa]; loads integrate p - ambient_pressure.
    """

    mesh: skfem.Mesh
    gap: Gap
    lubricant: Lubricant
    velocity_lower: Field = (0.0,)
    velocity_upper: Field = (0.0,)
    squeeze: Field = 0.0
    mode_velocities: Mapping[str, float] = field(default_factory=dict)
    dirichlet: Mapping[str, float] | None = None
    pressure_points: tuple = ()
    element: str = "P1"
    cavitation: Cavitation = Cavitation()
    ambient_pressure: float = 0.0
    options: SolverOptions = SolverOptions()

    def __post_init__(self):
        # velocities and pressures as numbers in SI or strings with units ("5 m/s"), as in a case file
        for name in ("velocity_lower", "velocity_upper"):
            value = getattr(self, name)
            if isinstance(value, (tuple, list)) and any(isinstance(v, str) for v in value):
                object.__setattr__(self, name, tuple(quantity(v, "velocity", f"Film.{name}") for v in value))
        si_fields(self, ambient_pressure="pressure", **({} if callable(self.squeeze) else {"squeeze": "velocity"}))
        if self.element not in ELEMENT_ORDERS:
            raise unknown_choice("film.element", self.element, ELEMENT_ORDERS)
        if self.lubricant.eyring_stress is not None:
            raise InputError(f"lubricant.eyring_stress = {self.lubricant.eyring_stress!r}: the Reynolds film solver is "
                             "Newtonian; only the EHL solver (lubedyn.lubrication.ehl, finite elements) has Eyring flow")
        if self.lubricant.herschel_bulkley is not None:
            raise InputError(f"lubricant.herschel_bulkley = {self.lubricant.herschel_bulkley!r}: the Reynolds film "
                             "solver is Newtonian; only the EHL solver (lubedyn.lubrication.ehl, finite elements) has "
                             "Herschel-Bulkley flow")
        modes = self.gap.modes()
        for name in self.mode_velocities:
            if name not in modes:
                raise unknown_choice("film.mode_velocities", name, modes)
        if self.cavitation.model == "jfo" and self.element == "P2":
            log.warning(
                "JFO cavitation with P2 elements is inaccurate (negative P2 vertex functions move the "
                "rupture one element early: 1.4 % pressure error against 3e-5 for P1 on the Fowell pocket at 100 "
                "elements, and only first-order convergence); use element P1"
            )

    def with_(self, **changes) -> "Film":
        """A copy with some fields replaced."""
        return replace(self, **changes)

    def solve(self, initial=None) -> FilmSolution:
        """Solve the film; see :func:`lubedyn.lubrication.reynolds.solve`."""
        return solve(self, initial=initial)
