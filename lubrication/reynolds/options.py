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
# "auto": the largest symmetric system sent to SuperLU; above it Ruge-Stuben
# AMG + CG.  Measured crossover (benchmark machine: 2-core AMD EPYC, scipy 1.17
# SuperLU/COLAMD, pyamg 5.4, amg_tol 1e-10; median of 3, one reduced system):
#   ~30-40k DOFs: direct 0.19-0.69 s, AMG 0.26-1.23 s (direct up to 2.5x faster)
#   ~50-80k DOFs: within 20 % either way (P2 journal 50k/65k: AMG 0.76/0.74 s
#                 against 0.92/0.94 s; P1 slider 60k/80k: direct 0.42/0.60 s
#                 against 0.58/0.66 s)
#   ~100-150k DOFs: AMG 1.2-3.9x faster (sphere P2 131k: 2.4 against 4.1 s;
#                 P2 journal 147k: 1.2 against 4.7 s)
# AMG pressures agreed with SuperLU's to 4e-12 (max norm) on all of them.
DIRECT_SOLVER_MAX_DOFS = 60_000
# "auto": AMG-CG whose first solve converges more slowly than this mean factor per CG
# iteration has stalled, and SuperLU takes over (SolverOptions).  The crossover above was
# measured on uniform meshes; on geometrically graded ones (cell ratio 1.02-1.1 about a
# contact, P2 quads) Ruge-Stuben AMG-CG degrades with the grading.  Measured (sphere-plane,
# full film, one reduced system, amg_tol 1e-10, maxiter 200; iterations, mean factor, time
# against SuperLU):
#   14k DOFs: uniform 13 its, 0.14, 0.34 s vs 0.08 s; ratio 1.05: 50 its, 0.63, 0.37 s;
#             ratio 1.1: 133 its, 0.84, 1.10 s
#   25k DOFs, ratio 1.1: 200 its stopped at 7e-8 (5.2 s vs 0.20 s)
#   57k DOFs, ratio 1.05: 200 its stopped at 1.3e-7 (11.6 s vs 0.65 s); ratio 1.1: 200 its
#             stopped at 1.2e-2 (10.1 s vs 0.62 s; pressure error 3.4e-3 of max p)
#   89k DOFs, ratio 1.05: 200 its stopped at 5e-4 (smoothed aggregation: 200 its, 2e-7: no
#             better, so the fallback is SuperLU); the whole Reynolds-cavitation solve (nested,
#             8 Newton iterations) took 92.8 s against 15.3 s with SuperLU, 22.6 s with the
#             fallback (same load to 1e-15)
# while uniform meshes need 9-17 iterations (factor 0.1-0.25) from 14k to 1M DOFs.  0.5 leaves
# a margin of 2x over the uniform factors and catches every graded case above.
AMG_STALL_FACTOR = 0.5
# automatic nested iteration (SolverOptions.warm_start_levels = None) from this
# many unknowns.  Measured (median of 7, nested against cold): long journal P2
# 768/1152/1536 DOFs 27/29/32 ms against 27/44/74 ms (cold needs 41/-/80
# iterations: 1536 DOFs fails the default max_iter = 60); finite journal
# 1088 DOFs 23-29 ms against 16-20 ms, 4224 DOFs 64-78 ms against 100-104 ms.
# 1000 costs a few ms on small 2-D films and keeps long 1-D films converging.
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
    """

    rtol: float = 1e-10
    max_iter: int = 60
    linear_solver: str = "auto"
    amg_tol: float = 1e-10
    warm_start_levels: int | None = None

    def __post_init__(self):
        if self.linear_solver not in LINEAR_SOLVERS:
            raise unknown_choice("solver.linear_solver", self.linear_solver, LINEAR_SOLVERS)
        if not 0 < self.rtol < 1:
            raise InputError(f"solver.rtol = {self.rtol!r} must be in (0, 1)")
        if self.max_iter < 1:
            raise InputError(f"solver.max_iter = {self.max_iter!r} must be >= 1")
        if self.warm_start_levels is not None and (
            not isinstance(self.warm_start_levels, (int, np.integer)) or self.warm_start_levels < 0
        ):
            raise InputError(f"solver.warm_start_levels = {self.warm_start_levels!r} must be None or an integer >= 0")
