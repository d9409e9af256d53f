"""The solver's choices: Cavitation (model and pressure), SolverOptions (Newton, linear solver, nested
iteration) and the constants that decide between solver paths.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, unknown_choice

CAVITATION_MODELS = ("none", "half_sommerfeld", "reynolds", "jfo")
ELEMENT_ORDERS = ("P1", "P2")
LINEAR_SOLVERS = ("auto", "direct", "amg")
# "auto": the largest symmetric system sent to SuperLU; above it Ruge-Stuben AMG + CG.  On uniform
# meshes SuperLU is faster below a few 10k DOFs, the two are about even between 40k and 80k (P2 favours
# AMG, P1 SuperLU) and AMG wins by a growing factor above 100k; AMG's pressures agree with SuperLU's to
# round-off (tests/test_solver_paths.py::test_amg_matches_direct_solver).  The crossover, one reduced
# system per point, is recorded with the Reynolds benchmarks (benchmarks/README.md); benchmarks/reynolds.py
# times the 1M-DOF AMG solve and benchmarks/method_limits.py (sweep 4) times auto, direct and AMG on either
# side of this size.
DIRECT_SOLVER_MAX_DOFS = 60_000
# "auto": AMG-CG whose first solve converges more slowly than this mean factor per CG iteration has
# stalled, and SuperLU takes over (SolverOptions).  The crossover above holds on uniform meshes, where
# AMG-CG needs 9-17 iterations (mean factor 0.1-0.25) from 14k to 1M DOFs; on geometrically graded
# meshes (cell ratio 1.02-1.1 about a contact, P2 quads) Ruge-Stuben AMG-CG degrades with the grading
# until it stops far from the tolerance and SuperLU is many times faster.  0.5 leaves a margin of 2x over
# the uniform factors and catches every graded sphere-plane film of benchmarks/method_limits.py (sweep 4:
# cell ratios 1.0, 1.05, 1.1); tests/test_solver_paths.py::test_auto_linear_solver_leaves_a_stalled_amg
# checks the switch on such a mesh.
AMG_STALL_FACTOR = 0.5
# automatic nested iteration (SolverOptions.warm_start_levels = None) from this many unknowns.  The
# active set moves the cavitation boundary by about one node column per iteration, so cold iteration
# counts grow with the mesh (a long P2 journal of about 1500 DOFs exceeds the default max_iter = 60
# cold); nested starts keep them flat and cost a few ms on small 2-D films.  benchmarks/reynolds.py
# times the journal cold and nested; tests/test_solver_paths.py checks the growth and the automatic switch.
WARM_START_MIN_DOFS = 1000


@dataclass(frozen=True)
class Cavitation:
    """Cavitation model (one of :data:`CAVITATION_MODELS`) and pressure [Pa] (gauge)."""

    model: str = "none"
    pressure: float = 0.0

    def __post_init__(self):
        if self.model not in CAVITATION_MODELS:
            raise unknown_choice("cavitation.model", self.model, CAVITATION_MODELS)


@dataclass(frozen=True)
class SolverOptions:
    """Newton / active-set controls and the linear solver choice.

    ``linear_solver``: ``"direct"`` (SuperLU), ``"amg"`` (pyamg classical
    Ruge-Stuben AMG preconditioned CG; symmetric problems only) or ``"auto"``
    (direct up to :data:`DIRECT_SOLVER_MAX_DOFS` unknowns, AMG above when the
    system is symmetric).  ``amg_tol`` is the relative residual of the CG
    iteration (1e-10 keeps AMG pressures within 1e-8 of SuperLU's).

    ``warm_start_levels``: coarser meshes solved first by :func:`solve`
    (nested iteration, :func:`solve_nested`).  ``None`` (default): 2 for
    ``"reynolds"``/``"jfo"`` cavitation on tensor meshes
    (:func:`lubedyn.lubrication.mesh.interval`/:func:`~lubedyn.lubrication.mesh.rectangle`)
    with at least :data:`WARM_START_MIN_DOFS` unknowns, falling back to a
    plain solve if a coarse level fails; 0 never; n > 0 always (the mesh must
    be a tensor mesh).

    ``structured``: on a P1 quad mesh of :func:`~lubedyn.lubrication.mesh.rectangle` (not periodic), assemble
    on the grid and precondition CG with geometric multigrid
    (:mod:`lubedyn.lubrication.reynolds.tensor`; chosen automatically, by the mesh); ``False`` takes
    scikit-fem's general path on every mesh.  The two agree to the solver tolerance.
    """

    rtol: float = 1e-10
    max_iter: int = 60
    linear_solver: str = "auto"
    amg_tol: float = 1e-10
    warm_start_levels: int | None = None
    structured: bool = True

    def __post_init__(self):
        if self.linear_solver not in LINEAR_SOLVERS:
            raise unknown_choice("solver.linear_solver", self.linear_solver, LINEAR_SOLVERS)
        if not 0 < self.rtol < 1:
            raise InputError(f"solver.rtol = {self.rtol!r} must be in (0, 1)")
        if not isinstance(self.structured, (bool, np.bool_)):
            raise InputError(f"solver.structured = {self.structured!r} must be true or false")
        if self.max_iter < 1:
            raise InputError(f"solver.max_iter = {self.max_iter!r} must be >= 1")
        if self.warm_start_levels is not None and (
            not isinstance(self.warm_start_levels, (int, np.integer)) or self.warm_start_levels < 0
        ):
            raise InputError(f"solver.warm_start_levels = {self.warm_start_levels!r} must be None or an integer >= 0")
