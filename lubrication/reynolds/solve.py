"""solve, solve_nested (nested iteration): the Reynolds solve drivers.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np
import skfem
from skfem.mesh.mesh_dg import MeshDG

from .. import mesh as meshes
from ..errors import ConvergenceError, InputError
from .diagnosis import _at_roundoff_floor, _diagnose, _divergence_hint
from .forms import ELEMENTS, cell_kind
from .options import WARM_START_MIN_DOFS
from .problem import _Problem, _select_columns
from .solution import FilmSolution

log = logging.getLogger(__name__)

def _auto_warm_start(film) -> int:
    """Levels of nested iteration for ``SolverOptions.warm_start_levels = None``."""
    if film.cavitation.model not in ("reynolds", "jfo"):
        return 0
    elem = ELEMENTS[(cell_kind(film.mesh), film.element)]()
    if skfem.Dofs(film.mesh, elem).N < WARM_START_MIN_DOFS or _tensor_axes(film.mesh) is None:
        return 0
    return 2


def solve(film, initial=None) -> FilmSolution:
    """Solve ``film`` (a :class:`~lubedyn.lubrication.reynolds.film.Film`); return a
    :class:`~lubedyn.lubrication.reynolds.solution.FilmSolution`.

    Without ``initial``, ``film.options.warm_start_levels`` may first solve
    coarser meshes (:func:`solve_nested`; by default for Reynolds/JFO
    cavitation on tensor meshes of at least :data:`WARM_START_MIN_DOFS`
    unknowns).

    ``initial`` may be a previous solution of a film on the same mesh and
    element (continuation in a sweep): its pressure, fluid fraction and active
    set start the iteration.  (:func:`solve_nested` starts from coarser
    meshes.)

    The returned solution has checked itself (:meth:`FilmSolution.report_warnings`): a JFO
    fluid fraction below 0 is logged at WARNING and listed in ``solution.warnings``.

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
    return _solve_single(film, initial).report_warnings()


def _solve_single(film, initial=None) -> FilmSolution:
    """:func:`solve` on ``film.mesh`` alone."""

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
            z[idx] = prob.solve_linear(Mred, rhs[idx], symmetric, index=idx)
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
    """``(xs,)`` or ``(xs, ys)`` if ``mesh`` is what :func:`lubedyn.lubrication.mesh.interval`
    or :func:`lubedyn.lubrication.mesh.rectangle` builds on those coordinates, else None."""
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


def solve_nested(film, levels: int = 2) -> FilmSolution:
    """Solve ``film`` by nested iteration: first on ``levels`` coarser versions
    of its tensor mesh (every second grid line per level), each solution
    interpolated (multi-linearly, on the coarse grid) to start the next finer
    solve.

    For cavitation (``"reynolds"``, ``"jfo"``) the active-set iteration moves
    the cavitation boundary about one node column per iteration, so its
    iteration count grows with the mesh; started from the coarse solution it
    needs a few per level.  The mesh must come from
    :func:`lubedyn.lubrication.mesh.interval` or :func:`lubedyn.lubrication.mesh.rectangle`
    (periodic or not); ``InputError`` otherwise.  The answer is that of
    :func:`solve` (same convergence test on the finest mesh).
    ``info["nested"]`` lists (dofs, iterations, seconds) per level, coarsest
    first; ``info["nested_wall_time"]`` is the whole chain.

    >>> import numpy as np
    >>> from lubedyn.lubrication import CylinderPlane, Cavitation, Film, Lubricant, mesh
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
            f"solve_nested needs a tensor mesh from lubedyn.lubrication.mesh.interval or mesh.rectangle; "
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
            elem = ELEMENTS[(cell_kind(level.mesh), level.element)]()
            doflocs = skfem.CellBasis(level.mesh, elem, intorder=1).doflocs
            guess = _prolong(solution, chain[k + 1][1], doflocs)
        solution = _solve_single(level, initial=guess)
        record.append((solution.info["dofs"], solution.info["iterations"], solution.info["wall_time"]))
    solution.info["nested"] = record
    solution.info["nested_wall_time"] = time.perf_counter() - t0
    return solution.report_warnings()
