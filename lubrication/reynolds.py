r"""Generalised Reynolds equation on scikit-fem meshes, with cavitation.

Equation (strong form, film plane x, gauge pressure p, fluid fraction theta)::

    div( rho h^3/(12 eta) grad p ) = div( rho h theta u_m ) + rho theta dh/dt

with u_m = (U_lower + U_upper)/2 the *mean* of the two surface velocities,
eta(p), rho(p) from :mod:`lubrication.laws.lubricant`, and dh/dt the local
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
---------------------------------------
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

JFO with P2 elements is inaccurate: use P1
-----------------------------------------
The complementarity ``(p - p_cav) r = 0`` is imposed at the nodes, but P2
vertex functions are negative over part of their support, so a nodal void
fraction r >= 0 does not keep the interpolated fluid fraction in [0, 1] and
the discrete rupture moves.  Measured on the Fowell pocket (rupture at the
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
iterate cannot fall below the backward error of the sparse LU (measured on
the nested Martin cylinder of tests/test_solver_paths.py: 1.05e-11 ||R_0||,
about 40 eps || |J| |p| ||; with residuals perturbed by 30 round-off units,
tests/roundoff.py, 1.5e-9 ||R_0|| > 10 rtol, while the Newton update was
2e-11 |p|: the old residual-only test ran out of iterations there).
Otherwise, after ``max_iter`` iterations,
:class:`~lubrication.errors.ConvergenceError`.

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
For a gap mode q_j (see :mod:`lubrication.gaps`), one extra linear solve with
the converged Jacobian (same active set) gives dp/dq_j and dp/d(dq_j/dt);
K_ij = -int (dp/dq_j) dh/dq_i dA and C_ij = -int (dp/d(dq_j/dt)) dh/dq_i dA.

References: Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film
Lubrication* (2004), ch. 7; Giacopini, Fowell, Dini & Strozzi (2010);
Woloszynski, Podsiadlo & Stachowiak (2015, Tribol. Lett. 58:18).
"""
from __future__ import annotations

import logging
import time
import warnings
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem import BilinearForm, LinearForm, asm
from skfem.helpers import dot, grad
from skfem.mesh.mesh_dg import MeshDG

from . import mesh as meshes
from .errors import ConvergenceError, InputError, unknown_choice
from .gaps import Gap
from .laws.lubricant import Lubricant

log = logging.getLogger(__name__)

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
    (:func:`lubrication.mesh.interval`/:func:`~lubrication.mesh.rectangle`)
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


Field = float | tuple | Callable


@dataclass(frozen=True)
class Film:
    """A lubricant film problem (SI units).

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
        if self.element not in ELEMENT_ORDERS:
            raise unknown_choice("film.element", self.element, ELEMENT_ORDERS)
        if self.lubricant.eyring_stress is not None:
            raise InputError(f"lubricant.eyring_stress = {self.lubricant.eyring_stress!r}: the Reynolds film solver is "
                             "Newtonian; only the EHL solver (lubrication.ehl, finite elements) has Eyring flow")
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
        import dataclasses

        return dataclasses.replace(self, **changes)

    def solve(self, initial=None) -> "FilmSolution":
        """Solve the film; see :func:`solve`."""
        return solve(self, initial=initial)


# --------------------------------------------------------------------------
# small generic forms (coefficients are arrays at quadrature points)


@BilinearForm
def _diffusion(u, v, w):
    return w["a"] * dot(grad(u), grad(v))


@BilinearForm
def _advection(u, v, w):
    return u * dot(w["b"], grad(v))


@BilinearForm
def _mass(u, v, w):
    return w["c"] * u * v


@BilinearForm
def _streamline(u, v, w):
    return w["s"] * dot(w["beta"], grad(u)) * dot(w["beta"], grad(v))


@LinearForm
def _flux_load(v, w):
    return dot(w["f"], grad(v))


@LinearForm
def _source_load(v, w):
    return w["g"] * v


_ELEMENTS = {
    ("line", "P1"): skfem.ElementLineP1,
    ("line", "P2"): skfem.ElementLineP2,
    ("tri", "P1"): skfem.ElementTriP1,
    ("tri", "P2"): skfem.ElementTriP2,
    ("quad", "P1"): skfem.ElementQuad1,
    ("quad", "P2"): skfem.ElementQuad2,
}


def _cell_kind(mesh) -> str:
    if isinstance(mesh, skfem.MeshLine1):
        return "line"
    if isinstance(mesh, skfem.MeshTri1):
        return "tri"
    if isinstance(mesh, skfem.MeshQuad1):
        return "quad"
    raise InputError(f"mesh type {type(mesh).__name__} is not supported; use line, triangle or quad meshes")


def make_basis(mesh, element: str = "P1") -> skfem.CellBasis:
    """The scalar Lagrange basis (``P1``/``P2``) of ``mesh``."""
    elem = _ELEMENTS[(_cell_kind(mesh), element)]()
    intorder = 4 if element == "P2" else 3
    return skfem.Basis(mesh, elem, intorder=intorder)


def unwrapped_dofs(basis) -> tuple[skfem.Mesh, np.ndarray]:
    """``(mesh, index)``: the unwrapped mesh of ``basis`` (:func:`lubrication.mesh.unwrapped`)
    and, for a field u of ``basis``, ``u[index]`` is the same field for
    ``basis.elem`` on that mesh.  On non-periodic meshes: the mesh itself and
    the identity."""
    mesh = meshes.unwrapped(basis.mesh)
    if mesh is basis.mesh:
        return mesh, np.arange(basis.N)
    dofs = skfem.Dofs(mesh, basis.elem)
    index = np.empty(dofs.N, dtype=np.int64)
    index[dofs.element_dofs] = basis.element_dofs  # same elements, same local order
    return mesh, index


def interpolate(basis, u, zero: bool = False) -> skfem.element.DiscreteField:
    """Scalar field ``u`` (values at the dofs of ``basis``) and its gradient at
    the quadrature points: sum_i u[element_dofs[i]] phi_i(x_q).

    The same numbers as ``basis.interpolate(u)`` (same sum in the same order),
    without the ``np.unique`` over all element dofs that scikit-fem spends on
    splitting a vector field.  ``zero=True``: ``u`` is known to be zero; return
    zero arrays without the sum.
    """
    ed = basis.element_dofs
    ref = basis.basis[0][0]
    if zero:
        return skfem.element.DiscreteField(np.zeros(ref.shape), np.zeros(ref.grad.shape))
    value = np.zeros(ref.shape)
    grad_ = np.zeros(ref.grad.shape)
    for i in range(ed.shape[0]):
        phi = basis.basis[i][0]
        ui = u[ed[i]][:, None]
        value += ui * np.asarray(phi)
        grad_ += ui * phi.grad
    return skfem.element.DiscreteField(value, grad_)


def _as_vector_field(value, x, dim, key):
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        arr = np.atleast_1d(np.asarray(value, dtype=float))
        if arr.size == 1 and dim > 1 and float(arr[0]) == 0.0:
            arr = np.zeros(dim)
        if arr.shape != (dim,):
            raise InputError(f"{key} = {value!r} must have {dim} component(s) for a {dim}-D film")
        out = arr.reshape((dim,) + (1,) * (x.ndim - 1)) * np.ones(x.shape[1:])
    if out.shape != x.shape:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape}")
    return out


def _as_scalar_field(value, x, key):
    if callable(value):
        out = np.asarray(value(x), dtype=float)
    else:
        out = float(value) * np.ones(x.shape[1:])
    if out.shape != x.shape[1:]:
        raise InputError(f"{key} returned shape {out.shape}, expected {x.shape[1:]}")
    return out


class _Problem:
    """Everything about a Film that does not change during the Newton solve."""

    def __init__(self, film: Film):
        self.film = film
        self.basis = make_basis(film.mesh, film.element)
        b = self.basis
        self.dim = film.mesh.p.shape[0]
        self.x = np.asarray(b.global_coordinates())  # (dim, nel, nqp)
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
        ul = _as_vector_field(film.velocity_lower, self.x, self.dim, "velocity_lower [m/s]")
        uu = _as_vector_field(film.velocity_upper, self.x, self.dim, "velocity_upper [m/s]")
        self.u_lower, self.u_upper = ul, uu
        self.um = 0.5 * (ul + uu)
        self.modes = {k: np.asarray(f(self.x), dtype=float) for k, f in film.gap.modes().items()}
        hdot = _as_scalar_field(film.squeeze, self.x, "squeeze dh/dt [m/s]")
        for k, qd in film.mode_velocities.items():
            hdot = hdot + float(qd) * self.modes[k]
        self.hdot = hdot
        speed = np.sqrt(np.sum(self.um**2, axis=0))
        order = 2.0 if film.element == "P2" else 1.0
        hk = np.broadcast_to(self._element_size()[:, None], speed.shape)
        self.tau = np.where(speed > 0, hk / (2.0 * order * np.where(speed > 0, speed, 1.0)), 0.0)
        self.N = b.N
        self._dirichlet()
        self.linear = film.lubricant.is_constant
        self.cav = film.cavitation

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
        film, b = self.film, self.basis
        values = np.full(self.N, np.nan)
        if film.dirichlet is None:
            facets = film.mesh.boundary_facets()
            dofs = b.get_dofs(facets).all()
            values[dofs] = film.ambient_pressure
        else:
            names = film.mesh.boundaries or {}
            for name, value in film.dirichlet.items():
                if name not in names:
                    raise unknown_choice("film.dirichlet boundary", name, list(names))
                values[b.get_dofs(names[name]).all()] = float(value)
        # on a periodic mesh (periodic in x, lubrication.mesh.rectangle) the seam
        # dofs sit at x = x_max: measure x distances modulo the period
        period = float(np.ptp(film.mesh.p[0])) if isinstance(film.mesh, MeshDG) else None
        for point, value in film.pressure_points:
            point = np.atleast_1d(np.asarray(point, dtype=float))
            diff = b.doflocs - point[:, None]
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

    # ------------------------------------------------------------------
    def coefficients(self, p, r):
        """Quadrature-point fields for the current iterate."""
        lub = self.film.lubricant
        pf = interpolate(self.basis, p)
        pq = np.asarray(pf) - self.film.ambient_pressure
        gp = pf.grad
        eta, deta = lub.viscosity(pq), lub.viscosity.derivative(pq)
        rho, drho = lub.density(pq), lub.density.derivative(pq)
        rf = interpolate(self.basis, r, zero=not np.any(r))
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
        b = self.basis
        c = self.coefficients(p, r)
        h, um, hdot = self.h, self.um, self.hdot
        theta = 1.0 - c["r"]
        k = c["rho"] * h**3 / (12.0 * c["eta"])
        K0 = asm(_diffusion, b, a=k).tocsr()
        A = K0
        if not self.linear:
            dk = h**3 / 12.0 * (c["drho"] / c["eta"] - c["rho"] * c["deta"] / c["eta"] ** 2)
            bvec = dk * c["gp"] - c["drho"] * h * theta * um
            A = (K0 + asm(_advection, b, b=bvec) + asm(_mass, b, c=c["drho"] * theta * hdot)).tocsr()
        # R = k grad p . grad v - rho h theta um . grad v + rho theta hdot v - SU(r)
        R = K0 @ p + asm(_flux_load, b, f=-c["rho"] * h * theta * um) + asm(_source_load, b, g=c["rho"] * theta * hdot)
        Jr = None
        if with_void:
            S = asm(_streamline, b, s=self.tau * c["rho"] * h, beta=um)
            Jr = (asm(_advection, b, b=c["rho"] * h * um) - asm(_mass, b, c=c["rho"] * hdot) - S).tocsr()
            R = R - S @ r
        if self.linear:
            self._cache = (A, Jr, R - A @ p - (Jr @ r if Jr is not None else 0.0))
        return R, A, Jr

    def solve_linear(self, M, rhs, symmetric: bool):
        """Solve ``M x = rhs`` with the solver that ``film.options.linear_solver`` picks.

        ``"auto"`` checks AMG-CG on its first solve (:data:`AMG_STALL_FACTOR`): if CG has
        not reached ``amg_tol`` within :func:`amg_probe_iterations` iterations, AMG has
        stalled (graded meshes), this system and every later one of the solve go to SuperLU,
        and ``linear_solver_used`` says why."""
        opts = self.film.options
        n = M.shape[0]
        use_amg = opts.linear_solver == "amg" or (
            opts.linear_solver == "auto" and symmetric and n > DIRECT_SOLVER_MAX_DOFS
            and getattr(self, "amg_stall", None) is None
        )
        if use_amg:
            import pyamg

            # classical AMG: on the 1M-DOF benchmark matrix setup 0.9-1.0 s against
            # 1.5-7.5 s for smoothed aggregation (whose Jacobi prolongation smoother
            # estimates spectral radii; 7.5 s with both cores busy), 9 CG
            # iterations against 11
            probe = opts.linear_solver == "auto" and not getattr(self, "amg_checked", False)
            maxiter = amg_probe_iterations(opts.amg_tol) if probe else 200
            ml = pyamg.ruge_stuben_solver(M.tocsr())
            residuals = []
            x = ml.solve(rhs, tol=opts.amg_tol, accel="cg", maxiter=maxiter, residuals=residuals)
            iterations = len(residuals) - 1
            relative = residuals[-1] / max(residuals[0], 1e-300) if residuals else 0.0
            self.amg_checked = True
            if probe and relative > opts.amg_tol:
                self.amg_stall = (relative, iterations)
                self.linear_solver_used = (f"direct (SuperLU) after AMG-CG stalled: residual {relative:.2e} "
                                           f"after {iterations} iterations")
                log.info("linear solver auto: AMG-CG (Ruge-Stuben) stalled on the first of %d unknowns "
                         "(relative residual %.2e > amg_tol %.1e after %d iterations: mean convergence factor "
                         "%.2f > %.2f); SuperLU solves this system and the rest of the solve", n, relative,
                         opts.amg_tol, iterations, relative ** (1.0 / max(iterations, 1)), AMG_STALL_FACTOR)
                return self._direct(M, rhs)
            if relative > opts.amg_tol:
                log.warning("AMG-CG stopped at relative residual %.2e > amg_tol %.1e after %d iterations",
                            relative, opts.amg_tol, iterations)
            self.linear_solver_used = "amg (pyamg Ruge-Stuben + CG)"
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


def amg_probe_iterations(amg_tol: float) -> int:
    """CG iterations that AMG-CG gets on its first solve under ``linear_solver = "auto"``:
    those that reach ``amg_tol`` at the mean convergence factor :data:`AMG_STALL_FACTOR`
    (34 at 1e-10).

    >>> amg_probe_iterations(1e-10)
    34
    """
    return int(np.ceil(np.log(amg_tol) / np.log(AMG_STALL_FACTOR)))


CYCLE_WINDOW = 10  # last iterations that _diagnose reads


def _divergence_hint(prob, p_last) -> str:
    """Why the pressure may have diverged, from the lubricant and the last finite iterate."""
    lub = prob.film.lubricant
    if prob.linear:
        return ("a film with constant lubricant properties is linear: a non-finite pressure means a singular "
                "or ill-posed system; check the gap and the boundary pressures")
    gauge = float(np.max(p_last) - prob.film.ambient_pressure)
    with np.errstate(over="ignore", invalid="ignore"):
        eta0, eta = float(lub.viscosity(np.array(0.0))), float(lub.viscosity(np.array(gauge)))
    return (f"the viscosity rose from {eta0:.3g} to {eta:.3g} Pa s at the last finite iterate's largest "
            f"pressure {gauge:.3g} Pa: the film may have no solution at this load and speed (e.g. beyond the "
            "Barus pole); reduce them, or use a viscosity law that stays finite")


def _diagnose(history, repeat, prob, complementarity, steps_taken=()) -> tuple[str, str]:
    """Why a Reynolds solve ran out of iterations, and what to do, from its iteration history
    (``(|R|/|R0|, |dp|/|p|, cavitated nodes)`` per iteration) and its state.

    Criteria, in this order: active-set cycling (a set seen before, or a cavitated-node count
    that changed in each of the last :data:`CYCLE_WINDOW` iterations), line search stalled
    (backtracking below 0.05 in each of them), a residual stagnating (the last window brought
    it no lower than half its earlier best), Newton steps not shrinking, else still converging
    (more iterations)."""
    film = prob.film
    last = history[-CYCLE_WINDOW:]
    res = np.array([h[0] for h in history])
    steps = np.array([h[1] for h in history])
    counts = [h[2] for h in last]
    pairs = list(zip(history[:-1], history[1:]))[-CYCLE_WINDOW:]
    changes = sum(1 for a, b in pairs if a[2] != b[2])
    recent_repeat = repeat is not None and repeat[0] > len(history) - CYCLE_WINDOW
    tail = f"|R|/|R0| = {res[-1]:.3e}, |dp|/|p| = {steps[-1]:.3e}"
    if complementarity and (recent_repeat or (len(pairs) == CYCLE_WINDOW and changes == CYCLE_WINDOW)):
        what = (f"the cavitated set of iteration {repeat[0]} repeats that of iteration {repeat[1]}"
                if recent_repeat else f"the cavitated node count changed in each of the last {CYCLE_WINDOW} iterations")
        reason = (f"active-set cycling: {what}; {min(counts)} to {max(counts)} cavitated nodes over the last "
                  f"{len(last)} iterations, |R|/|R0| between {min(h[0] for h in last):.2e} and "
                  f"{max(h[0] for h in last):.2e}")
        supply = prob.p_fixed[prob.fixed]
        hdot = prob.hdot
        separating = float(np.sum((hdot > 0) * prob.basis.dx) / np.sum(prob.basis.dx))
        if prob.cav.model == "jfo" and np.all(supply <= prob.cav.pressure):
            hint = (f"every boundary pressure is at or below cavitation.pressure = {prob.cav.pressure:.4g} Pa: "
                    "a JFO film without lubricant supply has starved solutions besides the flooded one; give a "
                    "boundary pressure above the cavitation pressure")
        elif separating > 0:
            hint = (f"the gap opens (dh/dt > 0) over {100 * separating:.0f} % of the film, max dh/dt = "
                    f"{np.max(hdot):.3g} m/s: the semismooth active-set Newton method does not settle on the "
                    "cavitation boundary of a separating squeeze; reduce the separating velocity, or use "
                    "cavitation.model = 'reynolds'")
        else:
            hint = "the cavitation boundary does not settle on this mesh; try a finer mesh or solver.max_iter"
        return reason, hint
    damped = list(steps_taken)[-CYCLE_WINDOW:]
    if len(damped) >= min(CYCLE_WINDOW, len(history)) and damped and max(damped) < 0.05:
        reason = (f"line search stalled: backtracking cut the Newton step to at most {max(damped):.3g} in each "
                  f"of the last {len(damped)} iterations, {tail}")
        return reason, ("the Newton direction does not reduce the residual: the pressure-dependent lubricant may "
                        "have no film at this load and speed; reduce them, or check the viscosity law")
    earlier = res[:-CYCLE_WINDOW]
    if earlier.size and np.min(res[-CYCLE_WINDOW:]) >= 0.5 * np.min(earlier):
        best = int(np.argmin(res)) + 1
        reason = (f"residual stagnating at {res[-1]:.3e} of |R0| (best {res[best - 1]:.3e} at iteration {best}), "
                  f"|dp|/|p| = {steps[-1]:.3e}")
        if not prob.linear:
            hint = ("the pressure-dependent lubricant makes the Newton iteration stall: the film may have no "
                    "solution at this load and speed; reduce them, or check the viscosity law")
        else:
            hint = f"solver.rtol = {film.options.rtol:.0e} may be below what round-off allows on this mesh"
        return reason, hint
    if len(steps) > CYCLE_WINDOW and steps[-1] >= 0.5 * steps[-CYCLE_WINDOW - 1]:
        reason = (f"Newton steps not shrinking: |dp|/|p| = {steps[-1]:.3e}, {steps[-CYCLE_WINDOW - 1]:.3e} "
                  f"{CYCLE_WINDOW} iterations earlier, |R|/|R0| = {res[-1]:.3e}")
        return reason, "the iteration does not contract here; check the gap, boundary pressures and speeds"
    return (f"still converging: {tail}, residual from {res[max(0, len(res) - CYCLE_WINDOW - 1)]:.3e} over the last "
            f"{min(len(res), CYCLE_WINDOW + 1) - 1} iterations",
            f"raise solver.max_iter = {film.options.max_iter}")


ROUNDOFF_FLOOR = 1e3  # machine epsilons of the residual's terms: see _at_roundoff_floor


def _at_roundoff_floor(R, Jp, Jr, p, r, mask) -> bool:
    """||R|| <= ROUNDOFF_FLOOR eps || |J| |u| || on ``mask``: the residual is as small as the
    round-off of its own terms (|J| |u|, u = (p, r)) lets it be.

    Measured: a 1-D inclined slider of 1e5 P1 cells (linear: one solve is exact up to round-off)
    sits at ||R|| = 0.2 eps || |J||p| ||, which is 1.8e-7 ||R_0|| because the terms cancel to a
    source 1e7 times smaller, with a Newton step of 5e-10 |p| (cond ~ N^2): neither 10 rtol
    ||R_0|| nor a step below rtol could be met and the solve ran out of iterations.  The nested
    Martin cylinder sits at 42 eps (the sparse LU's backward error).  Used only with a step below
    max(rtol, 1e-8) |p|."""
    terms = abs(Jp) @ np.abs(p)
    if Jr is not None:
        terms = terms + abs(Jr) @ np.abs(r)
    return bool(np.linalg.norm(R[mask]) <= ROUNDOFF_FLOOR * np.finfo(float).eps * np.linalg.norm(terms[mask]))


def _select_columns(Jp, Jr, full_mask):
    """Matrix whose column j is Jp[:, j] for full-film nodes and Jr[:, j] otherwise."""
    Df = sp.diags(full_mask.astype(float))
    if Jr is None:
        return Jp @ Df
    return Jp @ Df + Jr @ sp.diags((~full_mask).astype(float))


def _auto_warm_start(film: Film) -> int:
    """Levels of nested iteration for ``SolverOptions.warm_start_levels = None``."""
    if film.cavitation.model not in ("reynolds", "jfo"):
        return 0
    elem = _ELEMENTS[(_cell_kind(film.mesh), film.element)]()
    if skfem.Dofs(film.mesh, elem).N < WARM_START_MIN_DOFS or _tensor_axes(film.mesh) is None:
        return 0
    return 2


def solve(film: Film, initial=None) -> "FilmSolution":
    """Solve ``film``; return a :class:`~lubrication.solution.FilmSolution`.

    Without ``initial``, ``film.options.warm_start_levels`` may first solve
    coarser meshes (:func:`solve_nested`; by default for Reynolds/JFO
    cavitation on tensor meshes of at least :data:`WARM_START_MIN_DOFS`
    unknowns).

    ``initial`` may be a previous solution of a film on the same mesh and
    element (continuation in a sweep): its pressure, fluid fraction and active
    set start the iteration.  (:func:`solve_nested` starts from coarser
    meshes.)

    Well-posedness of JFO: the cavitated fraction is transported along the
    mean velocity, so a JFO film needs lubricant supply -- a boundary whose
    pressure is above the cavitation pressure, or an inflow boundary.  A
    periodic film whose only boundaries sit *at* the cavitation pressure admits
    starved solutions (theta h constant, p = p_cav everywhere) besides the
    flooded one; the active-set iteration then cycles and stops with
    :class:`ConvergenceError`.
    """
    if initial is None:
        levels = film.options.warm_start_levels
        if levels is None:
            if _auto_warm_start(film):
                try:
                    return solve_nested(film, 2)
                except ConvergenceError as exc:
                    log.info("nested (coarse-to-fine) start failed (%s); solving on the mesh itself", exc)
        elif levels > 0:
            return solve_nested(film, levels)
    return _solve_single(film, initial)


def _solve_single(film: Film, initial=None) -> "FilmSolution":
    """:func:`solve` on ``film.mesh`` alone."""
    from .solution import FilmSolution

    t0 = time.perf_counter()
    prob = _Problem(film)
    model = prob.cav.model
    pcav = prob.cav.pressure
    jfo = model == "jfo"
    complementarity = model in ("reynolds", "jfo")
    N, free, fixed = prob.N, prob.free, prob.fixed

    if initial is not None and initial.pressure_dofs.shape == (N,):
        p = np.where(fixed, prob.p_fixed, initial.pressure_dofs)
        r = np.where(fixed, 0.0, 1.0 - initial.fluid_fraction_dofs) if jfo else np.zeros(N)
    else:
        p = np.where(fixed, prob.p_fixed, film.ambient_pressure)
        r = np.zeros(N)

    R, Jp, Jr = prob.assemble(p, r, with_void=jfo)
    ref = max(np.linalg.norm(R[free]), 1e-300)
    full = np.ones(N, dtype=bool)  # full-film (pressure unknown) nodes
    history = []
    converged = False
    prev_full = None
    steps_taken = []  # Newton step length of each iteration (< 1: damped by backtracking)
    seen_sets = {}  # active set (bytes of the full-film mask) -> first iteration that had it
    repeat = None  # (iteration, earlier iteration) of the last active set seen before
    for it in range(1, film.options.max_iter + 1):
        if complementarity and (it > 1 or initial is not None):
            if jfo:
                cscale = np.abs(Jr.diagonal()) / np.maximum(np.abs(Jp.diagonal()), 1e-300)
                cscale = np.where(cscale > 0, cscale, 1.0)
                full = (p - pcav) >= cscale * r
            else:
                cscale = 1.0 / np.maximum(np.abs(Jp.diagonal()), 1e-300)
                full = (p - pcav) >= cscale * R
            full |= fixed
        # known increments: cavitated nodes go to p_cav, full-film nodes to r = 0
        dp_known = np.where(~full & free, pcav - p, 0.0)
        dr_known = np.where(full & free, -r, 0.0) if jfo else np.zeros(N)
        rhs = -R - Jp @ dp_known - (Jr @ dr_known if jfo else 0.0)
        M = _select_columns(Jp, Jr, full) if jfo else Jp
        if jfo:
            idx = np.flatnonzero(free)
        else:
            idx = np.flatnonzero(free & full)
        symmetric = prob.linear and not jfo
        Mred = M[idx][:, idx]
        z = np.zeros(N)
        if idx.size:
            z[idx] = prob.solve_linear(Mred, rhs[idx], symmetric)
        if not np.all(np.isfinite(z)):
            why = ("singular Jacobian: check boundary conditions and the gap" if prob.linear and np.all(np.isfinite(p))
                   else _divergence_hint(prob, p))
            exc = ConvergenceError(
                f"Reynolds Newton iteration {it}: the linear solve produced non-finite values ({why})")
            exc.stop_reason = f"non-finite linear solve at iteration {it}"
            raise exc
        dp = dp_known + np.where(full & free, z, 0.0)
        dr = dr_known + (np.where(~full & free, z, 0.0) if jfo else 0.0)
        # damped update for nonlinear laws (simple backtracking on ||R||)
        step = 1.0
        p_new, r_new = p + dp, r + dr
        if not prob.linear and not complementarity:
            for _ in range(8):
                with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                    R_try = prob.assemble(p + step * dp, r, with_void=False)[0]
                if np.linalg.norm(R_try[free]) <= max(np.linalg.norm(R[free]), 1e-300) * (1 - 1e-4 * step) or step < 0.02:
                    break
                step *= 0.5
            p_new = p + step * dp
        p_old = p
        p, r = p_new, r_new
        steps_taken.append(step)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            R, Jp, Jr = prob.assemble(p, r, with_void=jfo)
        if not (np.all(np.isfinite(R)) and np.all(np.isfinite(p))):
            exc = ConvergenceError(
                f"Reynolds Newton iteration {it}: the pressure diverged (non-finite residual; "
                f"max pressure {np.nanmax(np.abs(p)):.3e} Pa): {_divergence_hint(prob, p_old)}"
            )
            exc.stop_reason = f"film diverged at iteration {it}"
            raise exc
        if complementarity:
            res_mask = free & (full if not jfo else np.ones(N, dtype=bool))
        else:
            res_mask = free
        rnorm = np.linalg.norm(R[res_mask]) / ref
        pscale = max(np.max(np.abs(p - film.ambient_pressure)), 1e-300)
        dnorm = step * np.max(np.abs(dp)) / pscale
        history.append((rnorm, dnorm, int(np.sum(~full))))
        log.debug("Reynolds iteration %d: |R|/|R0| = %.3e, |dp|/|p| = %.3e, cavitated nodes %d", it, rnorm, dnorm, np.sum(~full))
        same_set = (not complementarity) or (prev_full is not None and np.array_equal(full, prev_full))
        prev_full = full.copy()
        if complementarity:
            key = np.packbits(full).tobytes()
            if key in seen_sets and not same_set:
                repeat = (it, seen_sets[key])
            seen_sets.setdefault(key, it)
        if complementarity:
            # is the complementarity system itself satisfied at the new iterate?
            if jfo:
                feasible = np.all(p[free] >= pcav - 1e-9 * pscale) and np.all(r[free] >= -1e-9)
            else:
                feasible = np.all(p[free] >= pcav - 1e-9 * pscale) and np.all(R[free & ~full] >= -1e-9 * ref)
        else:
            feasible = True
        # converged: a step below max(rtol, 1e-8) |p| with the residual at 10 rtol of R_0 or at its
        # round-off floor, or a full Newton step below rtol |p| whatever the residual (module
        # docstring)
        small_step = dnorm <= max(film.options.rtol, 1e-8)
        tiny_step = np.max(np.abs(dp)) / pscale <= film.options.rtol
        if same_set and feasible and (tiny_step or (small_step and (
                rnorm <= film.options.rtol * 10 or _at_roundoff_floor(R, Jp, Jr, p, r, res_mask)))):
            converged = True
            step_text = f"|dp|/|p| = {np.max(np.abs(dp)) / pscale:.2e}"
            if rnorm <= film.options.rtol * 10:
                stop = f"tolerance met: |R|/|R0| = {rnorm:.2e} <= 10 rtol, {step_text}"
            elif tiny_step:
                stop = f"Newton step below rtol: {step_text} <= {film.options.rtol:.0e} (|R|/|R0| = {rnorm:.2e})"
            else:
                stop = f"round-off floor: |R|/|R0| = {rnorm:.2e} at the round-off of its terms, {step_text}"
            if complementarity:
                stop += f"; active set unchanged ({history[-1][2]} cavitated nodes)"
            break
        if prob.linear and not complementarity and rnorm <= film.options.rtol * 10:
            converged = True
            stop = f"tolerance met: |R|/|R0| = {rnorm:.2e} <= 10 rtol (linear film)"
            break
    if not converged:
        reason, hint = _diagnose(history, repeat, prob, complementarity, steps_taken)
        exc = ConvergenceError(
            f"Reynolds solve ({model} cavitation) did not converge in {film.options.max_iter} "
            f"iterations: {reason} ({hint})"
        )
        exc.stop_reason = f"iteration limit: {reason}"
        exc.hint = hint
        raise exc
    if model == "half_sommerfeld":
        p = np.maximum(p, pcav)
        full = (p > pcav) | fixed
    theta = 1.0 - r
    info = dict(
        iterations=len(history),
        history=history,
        wall_time=time.perf_counter() - t0,
        linear_solver=getattr(prob, "linear_solver_used", "direct (SuperLU)"),
        dofs=N,
    )
    info["stop reason"] = stop
    log.info(
        "Reynolds %s/%s: %d dofs, %d iterations, %.3f s, %s; %s",
        film.element, model, N, info["iterations"], info["wall_time"], info["linear_solver"], stop,
    )
    return FilmSolution(film=film, problem=prob, pressure_dofs=p, fluid_fraction_dofs=theta, full_film=full, info=info)


@dataclass(frozen=True)
class _Guess:
    """Starting fields for :func:`solve` (what it reads of ``initial``)."""

    pressure_dofs: np.ndarray
    fluid_fraction_dofs: np.ndarray


def _prolong(solution, axes, doflocs) -> _Guess:
    """Pressure and fluid fraction of ``solution`` (on the tensor mesh of
    ``axes``) at the points ``doflocs`` of a finer mesh of the same domain.

    On these meshes the P1 dofs sit on the grid ``axes`` and the P2 dofs on
    the grid refined once (vertices, edge midpoints, cell centres: the
    diagonal midpoints of the triangles are cell centres): the dof values are
    put on that grid (positions from the element mapping, so a periodic seam
    dof fills both sides) and interpolated multi-linearly.
    """
    if solution.film.element == "P2":
        axes = tuple(np.sort(np.concatenate([a, 0.5 * (a[1:] + a[:-1])])) for a in axes)
    basis = solution.basis
    X = np.ascontiguousarray(np.asarray(basis.elem.doflocs, dtype=float).T)
    xy = np.asarray(basis.mapping.F(X))  # (dim, nel, nbfun)
    cell = tuple(np.searchsorted(0.5 * (a[1:] + a[:-1]), xy[d]) for d, a in enumerate(axes))
    dofs = basis.element_dofs.T  # (nel, nbfun), like xy[d]
    filled = np.zeros(tuple(a.size for a in axes), dtype=bool)
    filled[cell] = True
    if not np.all(filled):  # pragma: no cover - the meshes of _tensor_axes fill their grid
        raise InputError("solve_nested: the degrees of freedom do not fill the tensor grid")
    out = []
    for values in (solution.pressure_dofs, solution.fluid_fraction_dofs):
        grid = np.zeros(filled.shape)
        grid[cell] = values[dofs]
        if len(axes) == 1:
            out.append(np.interp(doflocs[0], axes[0], grid))
        else:
            from scipy.interpolate import RegularGridInterpolator

            out.append(RegularGridInterpolator(axes, grid, bounds_error=False, fill_value=None)(doflocs.T))
    return _Guess(out[0], np.clip(out[1], 0.0, 1.0))


def _tensor_axes(mesh):
    """``(xs,)`` or ``(xs, ys)`` if ``mesh`` is what :func:`lubrication.mesh.interval`
    or :func:`lubrication.mesh.rectangle` builds on those coordinates, else None."""
    if type(mesh) is skfem.MeshLine1:
        xs = np.unique(mesh.p[0])
        return (xs,) if mesh.t.shape[1] == xs.size - 1 else None
    kinds = {skfem.MeshQuad1: ("quad", False), skfem.MeshQuad1DG: ("quad", True),
             skfem.MeshTri1: ("tri", False), skfem.MeshTri1DG: ("tri", True)}
    if type(mesh) not in kinds:
        return None
    cell, periodic = kinds[type(mesh)]
    xs, ys = np.unique(mesh.p[0]), np.unique(mesh.p[1])
    if mesh.t.shape[1] != (xs.size - 1) * (ys.size - 1) * (1 if cell == "quad" else 2):
        return None
    rebuilt = meshes.rectangle(xs, ys, cell=cell, periodic_x=periodic)
    same = (np.array_equal(rebuilt.t, mesh.t) and np.array_equal(rebuilt.p, mesh.p)
            and sorted(rebuilt.boundaries) == sorted(mesh.boundaries or {}))
    return (xs, ys) if same else None


def _coarser(mesh, axes):
    """The mesh on every second grid line (ends kept) of each axis with at
    least 4 cells; None when no axis can be coarsened."""
    out = []
    for a in axes:
        c = a[::2] if a.size - 1 >= 4 else a
        if c[-1] != a[-1]:
            c = np.append(c, a[-1])
        out.append(c)
    if all(c.size == a.size for c, a in zip(out, axes)):
        return None, axes
    if len(out) == 1:
        return meshes.interval(out[0][0], out[0][-1], out[0].size - 1, points=out[0]), tuple(out)
    cell = "quad" if isinstance(mesh, skfem.MeshQuad1) else "tri"
    return meshes.rectangle(out[0], out[1], cell=cell, periodic_x=isinstance(mesh, MeshDG)), tuple(out)


def solve_nested(film: Film, levels: int = 2) -> "FilmSolution":
    """Solve ``film`` by nested iteration: first on ``levels`` coarser versions
    of its tensor mesh (every second grid line per level), each solution
    interpolated (multi-linearly, on the coarse grid) to start the next finer
    solve.

    For cavitation (``"reynolds"``, ``"jfo"``) the active-set iteration moves
    the cavitation boundary about one node column per iteration, so its
    iteration count grows with the mesh; started from the coarse solution it
    needs a few per level.  The mesh must come from
    :func:`lubrication.mesh.interval` or :func:`lubrication.mesh.rectangle`
    (periodic or not); ``InputError`` otherwise.  The answer is that of
    :func:`solve` (same convergence test on the finest mesh).
    ``info["nested"]`` lists (dofs, iterations, seconds) per level, coarsest
    first; ``info["nested_wall_time"]`` is the whole chain.

    >>> import numpy as np
    >>> from lubrication import CylinderPlane, Cavitation, Film, Lubricant, mesh
    >>> b = np.sqrt(2 * 10e-3 * 1e-6)
    >>> film = Film(mesh.interval(-30 * b, 3 * b, 400), CylinderPlane(10e-3, 1e-6), Lubricant.newtonian(0.05),
    ...             velocity_lower=(2.0,), velocity_upper=(2.0,), cavitation=Cavitation("reynolds"))
    >>> abs(solve_nested(film).load / film.solve().load - 1) < 1e-12
    True
    """
    if levels < 0:
        raise InputError(f"levels = {levels!r} must be >= 0")
    axes = _tensor_axes(film.mesh)
    if axes is None:
        raise InputError(
            f"solve_nested needs a tensor mesh from lubrication.mesh.interval or mesh.rectangle; "
            f"got a {type(film.mesh).__name__} that is not one"
        )
    t0 = time.perf_counter()
    chain = [(film, axes)]
    mesh = film.mesh
    for _ in range(levels):
        mesh, axes = _coarser(mesh, axes)
        if mesh is None:
            break
        chain.append((film.with_(mesh=mesh), axes))
    solution, record = None, []
    for k in range(len(chain) - 1, -1, -1):
        level = chain[k][0]
        guess = None
        if solution is not None:
            elem = _ELEMENTS[(_cell_kind(level.mesh), level.element)]()
            doflocs = skfem.CellBasis(level.mesh, elem, intorder=1).doflocs
            guess = _prolong(solution, chain[k + 1][1], doflocs)
        solution = _solve_single(level, initial=guess)
        record.append((solution.info["dofs"], solution.info["iterations"], solution.info["wall_time"]))
    solution.info["nested"] = record
    solution.info["nested_wall_time"] = time.perf_counter() - t0
    return solution


def film_coefficients(solution) -> tuple[list[str], np.ndarray, np.ndarray]:
    """Linearised stiffness K and damping C of the film about ``solution``.

    Returns ``(names, K, C)`` with ``names`` the gap's modes (e.g. ``["x", "y"]``
    for a journal, ``["h0"]`` for planar films), ``K[i, j] = -dF_i/dq_j`` [N/m]
    and ``C[i, j] = -dF_i/d(dq_j/dt)`` [N s/m], from the perturbation equations
    (one linear solve with the converged Jacobian per mode and kind).  The
    active set (cavitated nodes) is frozen: cavitated pressures do not vary.
    """
    prob: _Problem = solution.problem
    film = prob.film
    jfo = film.cavitation.model == "jfo"
    p, r = solution.pressure_dofs, 1.0 - solution.fluid_fraction_dofs
    _, Jp, Jr = prob.assemble(p, r, with_void=jfo)
    c = prob.coefficients(p, r)
    full = solution.full_film
    M = _select_columns(Jp, Jr, full) if jfo else Jp
    # half-Sommerfeld: p = max(p_full, p_cav), so dp = dp_full masked to the
    # positive zone (solve on every free node); complementarity models freeze
    # the active set.
    gumbel = film.cavitation.model == "half_sommerfeld"
    idx = np.flatnonzero(prob.free) if (jfo or gumbel) else np.flatnonzero(prob.free & full)
    Mred = M[idx][:, idx].tocsc()
    lu = spla.splu(Mred)
    names = list(prob.modes)
    n = len(names)
    K = np.zeros((n, n))
    C = np.zeros((n, n))
    b = prob.basis
    h, um, theta = prob.h, prob.um, 1.0 - c["r"]
    rho, eta = c["rho"], c["eta"]
    dk_dh = rho * 3.0 * h**2 / (12.0 * eta)
    for j, name in enumerate(names):
        g = prob.modes[name]
        dR_dq = asm(_flux_load, b, f=dk_dh * g * c["gp"] - rho * g * theta * um)
        if jfo:
            dR_dq = dR_dq - asm(_flux_load, b, f=prob.tau * rho * g * dot(um, c["gr"]) * um)
        dR_dqdot = asm(_source_load, b, g=rho * theta * g)
        for kind, rhs, out in (("K", dR_dq, K), ("C", dR_dqdot, C)):
            z = np.zeros(prob.N)
            z[idx] = lu.solve(-rhs[idx])
            dp = np.where(full & prob.free, z, 0.0)
            dpq = np.asarray(interpolate(b, dp))
            for i, name_i in enumerate(names):
                out[i, j] = -float(np.sum(dpq * prob.modes[name_i] * b.dx))
    return names, K, C
