r"""Generalised Reynolds equation on scikit-fem meshes, with cavitation.

Equation (strong form, film plane x, gauge pressure p, fluid fraction theta)::

    div( rho h^3/(12 eta) grad p ) = div( rho h theta u_m ) + rho theta dh/dt

with u_m = (U_lower + U_upper)/2 the *mean* of the two surface velocities,
eta(p), rho(p) from :mod:`lubedyn.lubrication.laws.lubricant`, and dh/dt the local
(Eulerian) rate of change of the gap, including rigid-mode velocities.  The
squeeze term is quasi-steady (d(theta)/dt and d(rho)/dt are not carried).

Weak form (test function v, natural boundary = zero total flux), residual::

    R(p, r; v) = int k grad p . grad v  -  int rho h (1 - r) u_m . grad v
                 + int rho (1 - r) dh/dt v  -  int tau rho h (u_m . grad r)(u_m . grad v)

with k = rho h^3/(12 eta) and r = 1 - theta the *void fraction*.  The last
term is streamline artificial diffusion (tau = h_K/(2 order |u_m|)) acting on
r only: it turns the Galerkin transport of the cavitated fraction into an
upwind one (exactly first-order upwind on uniform 1-D P1 meshes) and vanishes
identically in the full film, so full-film solutions keep the Galerkin orders
(2 for P1, 3 for P2 in L2).

Cavitation models (``Cavitation.model``)
----------------------------------------
- ``"none"``: full Sommerfeld, r = 0, p free.
- ``"half_sommerfeld"``: the Guembel approximation -- the full-Sommerfeld
  solution with pressures below p_cav replaced by p_cav.  Not mass conserving
  and not a solution of a complementarity problem; provided because classical
  tables use it.
- ``"reynolds"`` (Swift-Stieber): the complementarity problem
  ``p - p_cav >= 0, R(p) >= 0, (p - p_cav) R(p) = 0`` solved as one by a
  semismooth (primal-dual active set) Newton method on
  ``min(p - p_cav, c R(p)) = 0``, c = 1/diag(J).
- ``"jfo"``: mass-conserving Jakobsson-Floberg-Olsson, in the complementarity
  form of Giacopini et al. (2010, J. Tribol. 132, 041702):
  ``p - p_cav >= 0, r >= 0, (p - p_cav) r = 0`` with R(p, r) = 0, solved by
  the same semismooth Newton on ``min(p - p_cav, c r) = 0``,
  c = |diag(dR/dr)|/diag(dR/dp).

Each Newton step solves one sparse linear system in the free nodes; a node is
either a pressure unknown (full film) or a void-fraction unknown (cavitated).
Symmetric systems (constant lubricant, no JFO) above
:data:`DIRECT_SOLVER_MAX_DOFS` unknowns go to classical (Ruge-Stuben) AMG
preconditioned CG, all others to SuperLU.  AMG-CG stalls on graded meshes: if
its first solve has not reached ``amg_tol`` in :func:`amg_probe_iterations`
iterations (mean factor :data:`AMG_STALL_FACTOR`), SuperLU takes over for the
rest of the solve and ``info["linear_solver"]`` says so.

Structured path: on a P1 quad mesh of :func:`lubedyn.lubrication.mesh.rectangle` (not periodic; recognised
exactly by :func:`~lubedyn.lubrication.reynolds.tensor.tensor_grid`) the quadrature points, the assembly of
the diffusion matrix and loads, the solution's integrals and, under ``linear_solver = "auto"``, a geometric
multigrid preconditioner come from the grid instead of scikit-fem's generic path (the 1M-DOF benchmark at
0.37-0.40 of the general path's CPU time); ``SolverOptions(structured=False)`` keeps the general path.  Both
give the same solution to the linear solver's tolerance (``tests/test_reynolds_tensor.py``).

JFO with P2 elements is inaccurate: use P1
------------------------------------------
The complementarity ``(p - p_cav) r = 0`` is imposed at the nodes, but P2
vertex functions are negative over part of their support, so a nodal void
fraction r >= 0 does not keep the interpolated fluid fraction in [0, 1] and
the discrete rupture moves.  On the Fowell pocket (rupture at the
2 mm pocket edge): on 100/200/400 elements P2 ruptures one element early
(1.90/1.95/1.975 mm) and its pressure error is 1.4e-2/6.8e-3/3.4e-3 of
p_max (first order), against 3.1e-5/7.8e-6/2.0e-6 for P1 (second order;
``tests/test_cavitation.py``).  A ``Film`` with ``cavitation="jfo"`` and
``element="P2"`` logs a warning.

Convergence test: the active set is unchanged from the previous iteration
(and feasible), and either ``||R||_2 <= 10 rtol ||R_0||_2`` (R_0: the residual
at the initial full-film ambient-pressure state, i.e. the norm of the
hydrodynamic sources) or at its round-off floor (``<= 1e3 eps || |J| |p|
||``, :func:`_at_roundoff_floor`: a 1e5-cell 1-D film sits there at 1.8e-7
||R_0||) with a last pressure update ``<= max(rtol, 1e-8) max|p|``, or a
last full Newton update ``<= rtol max|p|`` whatever the residual.  The last
branch is the round-off floor too: the residual of an
iterate cannot fall below the backward error of the sparse LU (on
the nested Martin cylinder of tests/test_solver_paths.py: 1.05e-11 ||R_0||,
about 40 eps || |J| |p| ||; with residuals perturbed by 30 round-off units,
tests/roundoff.py, 1.5e-9 ||R_0|| > 10 rtol, while the Newton update was
2e-11 |p|: the old residual-only test ran out of iterations there).
Otherwise, after ``max_iter`` iterations,
:class:`~lubedyn.lubrication.errors.ConvergenceError`.

Stop reasons: a converged solve records in ``info["stop reason"]`` which test
stopped it ("tolerance met", "Newton step below rtol", "round-off floor",
with |R|/|R0|, |dp|/|p| and the cavitated-node count).  A failed one says
what failed, read from its iteration history by :func:`_diagnose`
(active-set cycling with the node counts, line search stalled, residual
stagnating, steps not shrinking, still converging), with a hint computed from
the film (no supply above the cavitation pressure, the share of the film that
separates, the viscosity reached); the exception carries ``stop_reason`` and
``hint``.  Non-finite iterates name the viscosity reached for
pressure-dependent lubricants instead of the boundary conditions.

Linearised film coefficients
----------------------------
For a gap mode q_j (see :mod:`lubedyn.lubrication.gaps`), one extra linear solve with
the converged Jacobian (same active set) gives dp/dq_j and dp/d(dq_j/dt);
K_ij = -int (dp/dq_j) dh/dq_i dA and C_ij = -int (dp/d(dq_j/dt)) dh/dq_i dA.

References: Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film
Lubrication* (2004), ch. 7; Giacopini, Fowell, Dini & Strozzi (2010);
Woloszynski, Podsiadlo & Stachowiak (2015, Tribol. Lett. 58:18).

Modules: ``options`` (Cavitation, SolverOptions and the constants that choose between solver paths),
``film`` (Film), ``forms`` (weak forms, bases, interpolation; shared with the EHL solver), ``problem``
(assembly, cavitation sets, linear solves), ``diagnosis`` (stop reasons), ``solve`` (solve, solve_nested),
``solution`` (FilmSolution: loads, moments, friction, flow, VTK, plots), ``coefficients``
(film_coefficients), ``tensor`` (the structured path on P1 tensor grids: assembly, integrals, geometric
multigrid) with its compiled kernels in ``_tensor_kernels``.  The public names are re-exported here; the modules import one another, never this
package.
"""
from __future__ import annotations

# The package's public API, re-exported (no ``__all__``: autosummary would then document every name twice,
# here and in its module).
from .coefficients import film_coefficients  # noqa: F401
from .diagnosis import CYCLE_WINDOW, ROUNDOFF_FLOOR, amg_probe_iterations  # noqa: F401
from .film import Field, Film  # noqa: F401
from .forms import interpolate, make_basis, unwrapped_dofs  # noqa: F401
from .options import (  # noqa: F401
    AMG_STALL_FACTOR, CAVITATION_MODELS, DIRECT_SOLVER_MAX_DOFS, ELEMENT_ORDERS, LINEAR_SOLVERS, WARM_START_MIN_DOFS,
    Cavitation, SolverOptions,
)
from .solution import FilmSolution  # noqa: F401
from .solve import solve, solve_nested  # noqa: F401
