"""solve_ehl: the grid sequence (coarse to fine), the choice of method, the multigrid driver.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import time

import numpy as np

from ..errors import ConvergenceError, InputError
from ..laws import contact as hertz
from .budget import DEFAULT_MAX_WORK, _BUDGET, _grid_nodes
from .checks import check_solution, inlet_cells
from .contact import EHLContact
from .newton import _active_set_newton, _fb_newton, _film_guess, _heavy, _hertz_guess, _nodes, _prolong, _stopped
from .options import EHLGrid, EHLOptions
from .problem import _Problem
from .solution import EHLSolution
from ..laws.lubricant import Barus
from .checks import wants_finer
from .multigrid import MultigridEHL, MultigridOptions
from .newton import hb_apparent_start

log = logging.getLogger(__name__)

def solve_ehl(contact: EHLContact, grid: EHLGrid = EHLGrid(), options: EHLOptions = EHLOptions(),
              initial=None, sequence: bool = True, _final: bool = True, _stage_info=None,
              _check: bool = True) -> EHLSolution:
    """Solve an EHL contact; see the module docstring for the method.

    With ``sequence=True`` (default) and no ``initial``, grids finer than 129
    (line) or 33 (point contact) nodes along x are reached by nested iteration: the contact is solved on
    the grid with (nx - 1)/2 + 1 nodes first (recursively) and its pressure,
    interpolated, starts the Newton iteration on the finer grid.  This is what
    makes heavily loaded contacts converge on fine grids (measured: M = 100,
    L = 10 line contact on 513 nodes fails from the Hertz start and converges
    from the 257-node solution).  Where the nested start fails on one of its coarser levels
    (one that does not resolve a heavily loaded contact), the requested grid is solved once
    more from the Hertz start (``sequence=False``; measured: Dowson-Higginson line contacts at
    M = 500, L = 5 and Barus at M = 1000, L = 5 on 513 nodes, whose 257- and 129-node levels fail,
    converge so); if that fails too, the error names the level that failed and the
    grid asked for.

    The solution is then checked a posteriori (:func:`_a_posteriori`: the one-level-coarser grid's
    solution and, where that cannot tell, the one-level-finer one;
    :func:`lubedyn.lubrication.ehl.checks.check_solution`).
    """
    from threadpoolctl import threadpool_limits

    if contact.lubricant.herschel_bulkley is not None and initial is None and _final \
            and options.method != "multigrid" and sequence:
        sol = _solve_hb(contact, grid, options)
        if _check:
            _a_posteriori(sol, options)
        return sol
    outer = _BUDGET.get()
    token = None
    if outer is None:  # the outermost call owns the budget; nested calls (a map's points) spend their own
        limit = options.max_work if options.max_work is not None else \
            DEFAULT_MAX_WORK["line" if contact.is_line else "point"]
        token = _BUDGET.set(dict(limit=limit, spent=0.0, nodes=_grid_nodes(contact, grid), nx=grid.nx))
    try:
        with threadpool_limits(limits=1, user_api="blas"):
            try:
                sol = _solve_ehl(contact, grid, options, initial, sequence, _final, _stage_info)
            except ConvergenceError as exc:
                level = getattr(exc, "level", None)
                if token is None or getattr(exc, "budget", False) or level is None or level >= grid.nx:
                    raise
                sol = _direct_start(contact, grid, options, _final, exc)
        if token is not None:
            sol.info["work"] = _BUDGET.get()["spent"]
    except ConvergenceError as exc:
        if token is not None:  # the work this failure took, next to its reason
            exc.stop = dict(getattr(exc, "stop", None) or dict(reason="not converged", detail=str(exc)),
                            work=_BUDGET.get()["spent"])
        raise
    finally:
        if token is not None:
            _BUDGET.reset(token)
    if _final and _check:
        _a_posteriori(sol, options)
    return sol


def _direct_start(contact, grid, options, final, nested):
    """The requested grid solved from the Hertz start (no nested iteration) after the nested start
    failed on a coarser level (``nested``, the error, carries that level's nx as ``.level``).  If this
    fails too, the :class:`ConvergenceError` names both failures, the level that failed and the grid
    asked for (each failure's own hint says what to change: Moes' M where the grid does not resolve it)."""
    level = nested.level
    log.info("EHL: the nested start failed on its %d-node level (%s); solving the grid.nx = %d asked for from "
             "the Hertz start", level, nested, grid.nx)
    try:
        sol = _solve_ehl(contact, grid, options, None, False, final)
    except ConvergenceError as exc:
        if getattr(exc, "budget", False):
            raise
        err = ConvergenceError(
            f"EHL solve on the grid.nx = {grid.nx} asked for failed from both starts: from the Hertz start on those "
            f"nodes, {exc}; before that, the nested start failed on its coarser {level}-node level: {nested}")
        err.stop = dict(getattr(exc, "stop", None) or dict(reason="not converged"), detail=str(err),
                        nested_level=level)
        raise err from exc
    sol.info["fallback"] = dict(failed_start=f"nested start, {level}-node level: {nested}", start="Hertz")
    return sol


# ---------------------------------------------------------------- work budget

HB_START_FACTORS = (1.0, 0.5, 0.25, 0.125)  # Newtonian starts: eta_app times these, in turn


def _attempt(failures, label, solve, *args, **kwargs):
    """``(solve(*args, **kwargs), None)``, or ``(None, error)`` for a :class:`ConvergenceError`, whose
    message is appended to ``failures`` under ``label``; a work-budget error (``budget`` set) is
    re-raised: the caller's budget is spent, no further start may be tried."""
    try:
        return solve(*args, **kwargs), None
    except ConvergenceError as exc:
        if getattr(exc, "budget", False):
            raise
        failures.append(f"{label}: {exc}")
        return None, exc


def _solve_hb(contact, grid, options):
    """A Herschel-Bulkley contact from a Newtonian start: the Newtonian contact (Barus, the grease's
    alpha) with the apparent viscosity eta_app of :func:`hb_apparent_start` is solved first, its state
    starts the Herschel-Bulkley iteration (measured: the Hertz start stalls for polyurea and calcium at
    135 kN/m, 10 m/s on paper A's cone; the Newtonian start converges in 5-6 steps).  Where that
    Newtonian contact, or the Herschel-Bulkley iteration from it, fails, the next start is the
    Newtonian contact with eta_app times the next of :data:`HB_START_FACTORS` (thinner, more heavily
    loaded: inside the Newtonian solver's reach at paper A's light loads, M ~ 1-2 with L ~ 60).  Where a
    Newtonian start converges and the Herschel-Bulkley iteration from it does not, the grease is reached
    from it by the homotopy of :func:`_hb_homotopy` before the next start is tried.  If all
    fail, :class:`ConvergenceError` names every start and its failure."""
    import dataclasses

    eta_app, _ = hb_apparent_start(contact)
    lub = contact.lubricant
    hint = (f"Herschel-Bulkley lubricant {lub.herschel_bulkley!r}, consistency phi0 = {lub.viscosity.eta0:g} Pa s^n "
            f"(M and L read phi0 as Pa s), apparent viscosity {eta_app:.4g} Pa s")
    failures = []
    last = None
    for factor in HB_START_FACTORS:
        eta = eta_app * factor
        newtonian = dataclasses.replace(contact, lubricant=dataclasses.replace(
            lub, viscosity=Barus(eta, lub.viscosity.pressure_viscosity), herschel_bulkley=None))
        start, exc = _attempt(failures, f"Newtonian start eta = {eta:.4g} Pa s", solve_ehl, newtonian, grid,
                              options, _check=False)
        if start is None:
            last = exc
            continue
        homotopy = None
        sol, exc = _attempt(failures, f"from the Newtonian start eta = {eta:.4g} Pa s", solve_ehl, contact,
                            grid, options, initial=start, _check=False)
        if sol is None:
            last = exc
            reached, exc = _attempt(failures, f"homotopy from the Newtonian start eta = {eta:.4g} Pa s",
                                    _hb_homotopy, contact, grid, options, start, eta)
            if reached is None:
                last = exc
                continue
            sol, homotopy = reached
        sol.info["hb_start"] = dict(apparent_viscosity=eta_app, start_viscosity=eta,
                                    central_film=start.central_film_thickness, failed_starts=failures,
                                    homotopy=homotopy)
        if failures:
            log.info("EHL Herschel-Bulkley: converged from the start eta = %.4g Pa s after %d failed", eta,
                     len(failures))
        return sol
    err = ConvergenceError(f"EHL Herschel-Bulkley contact did not converge from any Newtonian start ({hint}): "
                           + " | ".join(failures))
    err.stop = getattr(last, "stop", None)
    raise err from last


HB_HOMOTOPY_STEPS = (0.25, 1.0 / 64.0)  # first step and smallest step of the homotopy parameter s


def _hb_homotopy(contact, grid, options, start, eta):
    """The Herschel-Bulkley contact reached from the converged Newtonian ``start`` (viscosity ``eta``
    [Pa s]) by continuation along the greases H(s), s: 0 -> 1, with yield stress s tau_y, exponent
    n_s = 1 - s (1 - n) and the consistency that keeps the apparent viscosity at the shear rate D where
    the grease's own is eta (tau_y/D + phi0 D^(n-1) = eta) equal to eta: phi_s = (eta - s tau_y/D)
    D^(1 - n_s), so H(0) is the Newtonian start and H(1) the grease.  Each step is a Newton solve from
    the previous state; a failed step is halved (down to :data:`HB_HOMOTOPY_STEPS` [1]), a converged one
    doubles the next (up to the first step).  Why: the Herschel-Bulkley iteration from the Newtonian
    state stalls where the flow factor is far from 1 (lithium, n = 0.31: measured on paper A's rib,
    500 N, 11.3 m/s, 65 x 57 nodes: the direct step stalled; the continuation converged, 6 Newton
    iterations per step, central film 0.187 um (Newtonian start) -> 0.240 um).  Returns ``(solution,
    record)``; the record lists the steps (s, central film [m]) and the failed s."""
    import dataclasses

    from scipy.optimize import brentq

    lub = contact.lubricant
    hb = lub.herschel_bulkley
    alpha = lub.viscosity.pressure_viscosity
    phi0, n, ty = lub.viscosity.eta0, hb.exponent, hb.yield_stress

    def excess(lnD):
        D_ = np.exp(lnD)
        return np.log(ty / D_ + phi0 * D_ ** (n - 1.0)) - np.log(eta)

    try:  # the grease's apparent viscosity falls through eta between these rates when n < 1
        D = float(np.exp(brentq(excess, np.log(1e-6), np.log(1e12), xtol=1e-12)))
    except ValueError:
        raise ConvergenceError(f"EHL Herschel-Bulkley homotopy: the grease's apparent viscosity tau_y/D + phi0 D^(n-1) "
                               f"does not pass {eta:.4g} Pa s for D in 1e-6 ... 1e12 1/s ({hb!r}, phi0 = "
                               f"{phi0:g})") from None

    def grease(s_):
        if s_ >= 1.0:
            return contact
        n_s = 1.0 - s_ * (1.0 - n)
        phi = (eta - s_ * ty / D) * D ** (1.0 - n_s)
        return dataclasses.replace(contact, lubricant=dataclasses.replace(
            lub, viscosity=Barus(phi, alpha), herschel_bulkley=dataclasses.replace(hb, yield_stress=s_ * ty,
                                                                                  exponent=n_s)))

    first, smallest = HB_HOMOTOPY_STEPS
    s_done, step, sol = 0.0, first, start
    steps, failed = [], []
    while s_done < 1.0:
        s_next = min(1.0, s_done + step)
        try:
            sol = solve_ehl(grease(s_next), grid, options, initial=sol, _check=False)
        except ConvergenceError as exc:
            if getattr(exc, "budget", False):
                raise
            failed.append(round(s_next, 6))
            step *= 0.5
            if step < smallest:
                raise ConvergenceError(f"EHL Herschel-Bulkley homotopy stopped at s = {s_done:.4g} (failed steps to "
                                       f"s = {failed}; the last: {exc})") from exc
            continue
        s_done = s_next
        steps.append((s_done, sol.central_film_thickness))
        step = min(2.0 * step, first)
    return sol, dict(steps=steps, failed=failed, shear_rate=D)


def _solve_ehl(contact, grid, options, initial=None, sequence=True, _final=True, _stage_info=None, _coarse=False,
               _loose=False, _fallback=True):
    """:func:`solve_ehl` body (BLAS limited to one thread by the caller: the dense LUs of a few hundred
    unknowns are many times slower with two OpenBLAS threads than with one on a shared 2-core machine;
    benchmarks/ehl.py times the solves)."""
    t0 = time.perf_counter()
    if options.method == "multigrid":
        return _solve_multigrid(contact, grid, options, initial)
    if not contact.is_line and grid.nx > options.max_point_grid:
        raise InputError(
            f"grid.nx = {grid.nx} for a point contact: point contacts are solved up to {options.max_point_grid} "
            f"nodes per side by the Newton methods (lubedyn.lubrication.ehl.EHLOptions.max_point_grid: the largest grid measured to converge, "
            f"M = 100, L = 10; a Newton step costs about 5 s of one core on 257 x 257 and the sparse-LU "
            f"preconditioner's fill grows faster than the grid); use nx <= {options.max_point_grid}, or "
            f"solver.method = 'multigrid'"
        )
    coarsest = 129 if contact.is_line else 33
    nests = initial is None and sequence and grid.nx > coarsest and (grid.nx - 1) % 2 == 0
    first_start = options.first_order_start
    if first_start == "auto":
        # points finer than 129 x 129: every grid (measured on 257 x 257, M =
        # 100 and 200: the second-order iteration from the prolonged
        # second-order solution never converged, every step damped)
        first_start = "every_grid" if (contact.is_line or grid.nx > 129) else "coarsest"
    if options.consistent_supg and _stage_info is None and not (nests and first_start == "coarsest"):
        # defect-correction start: the first-order (plain SUPG) solution on the
        # same grid starts the second-order Newton iteration; started from a
        # Hertz or prolonged pressure, the second-order scheme alone stalls on
        # 2-D grids (measured: M = 20, L = 10 on 65 x 65 nodes)
        import dataclasses

        try:
            first = _solve_ehl(contact, grid, dataclasses.replace(options, consistent_supg=False), initial=initial,
                               sequence=sequence, _final=False, _coarse=_coarse, _loose=True)
            out = _solve_ehl(contact, grid, options, initial=first, sequence=False, _final=_final, _coarse=_coarse,
                             _stage_info=dict(first_order_iterations=first.info["iterations"],
                                              first_order_central_film=first.central_film_thickness,
                                              first_order_time=first.info["wall_time"]))
        except ConvergenceError as exc:
            if getattr(exc, "budget", False):  # the work budget is spent: no fallback
                raise
            if not (_fallback and not _coarse and nests and options.first_order_start == "auto"):
                raise
            # the second-order iteration from the first-order solution of the
            # same grid failed: the other start, second order from the
            # prolonged coarse second-order solution (measured need: line
            # contact M = 20, L = 10 on 1025 nodes, where the outlet-spike node
            # oscillates from the first-order start and 15 steps converge from
            # the 513-node solution)
            log.info("EHL: %s; retrying from the prolonged second-order solution on %d nodes", exc, grid.nx)
            try:
                out = _solve_ehl(contact, grid, dataclasses.replace(options, first_order_start="coarsest"),
                                 sequence=sequence, _final=_final, _fallback=False)
            except ConvergenceError as exc2:
                if getattr(exc2, "budget", False):
                    raise
                err = ConvergenceError(f"{exc2}; before that, from the first-order start: {exc}")
                err.stop = getattr(exc2, "stop", None)
                err.level = getattr(exc2, "level", None)
                raise err from exc2
            out.info["fallback"] = dict(failed_start=str(exc))
        out.info["wall_time"] = time.perf_counter() - t0
        return out
    P = _Problem(contact, grid, options)
    if nests:
        coarse_grid = grid.coarser()
        try:
            coarse = _solve_ehl(contact, coarse_grid, options, sequence=True, _final=False, _coarse=True)
        except ConvergenceError as exc:
            if getattr(exc, "budget", False):  # the work budget is spent: no fallback
                raise
            # a coarse level is only a start: where it cannot resolve the
            # outlet constriction (heavy loads), its last iterate still is one
            if getattr(exc, "partial", None) is None:
                raise
            log.info("EHL coarse level %s did not converge (%s); its last iterate starts %d nodes",
                     coarse_grid.nx, exc, P.N)
            coarse = exc.partial
        Pc = coarse.problem
        coarse_hn = Pc.film(coarse.pressure, coarse.h00)
        # the coarser level's films, for the a-posteriori check (check_solution)
        coarse_level = dict(nx=int(Pc.shape[0]), ny=None if contact.is_line else int(Pc.shape[1]),
                            central_film=float(coarse_hn[np.argmin(np.linalg.norm(
            Pc.doflocs, axis=0))]), minimum_film=float(np.min(coarse_hn)),
            converged=coarse.film_thickness is not None, scheme=coarse.info.get("scheme"), source="nested start",
            collapsed=bool(np.min(coarse_hn) <= options.h_floor * Pc.hscale * 1.0001))
        initial = EHLSolution(contact, P, _prolong(coarse, P), None, coarse.h00,
                              dict(coarse_iterations=coarse.info.get("iterations")))
    balance = contact.load is not None
    W = contact.load if balance else None
    if not nests:
        coarse_level = None
    if initial is not None and initial.pressure.shape == (P.N,):
        p, h00 = initial.pressure.copy(), float(initial.h00)
    elif initial is not None and getattr(initial, "problem", None) is not None:
        # a solution on another grid (other nx or inlet): its pressure
        # interpolated (multilinear, 0 outside its domain) onto this grid
        p, h00 = _prolong(initial, P), float(initial.h00)
    else:
        p = _hertz_guess(P)
        if not balance:
            p *= 0.0
        hc = _film_guess(contact)
        h00 = contact.approach if not balance else hc - float(P.deflect(p)[np.argmin(np.abs(P.rigid))])
    if not balance:
        h00 = contact.approach
    p[P.fixed] = 0.0
    method = options.method
    if method == "auto":
        # Herschel-Bulkley lines too go to Fischer-Burmeister: with a plug (Phi_HB = 0) in and next to
        # the cavitated zone the active set kept changing (measured: Moes M = 20, L = 10, tau_y = 10 Pa,
        # 257 nodes, from the Newtonian state: active set never converged, FB in 7 steps)
        hb = contact.lubricant.herschel_bulkley is not None
        method = "active_set" if contact.is_line and not hb else "fischer_burmeister"
    newton = _fb_newton if method == "fischer_burmeister" else _active_set_newton
    budget = {}
    if method == "fischer_burmeister":
        if _coarse:
            budget["max_iter"] = options.coarse_max_iter
        if _coarse or _loose:
            # a start for the next stage: converged to coarse_rtol, well below
            # the change the next grid (or scheme) makes (measured: max|dp| of
            # 0.2 - 0.5 p_Hertz at the outlet spike from 65 to 129 and 129 to 257)
            budget["rtol"] = max(options.rtol, options.coarse_rtol)
        elif options.consistent_supg and _stage_info is None and nests:
            # second order from the prolonged coarse solution: where it
            # wanders (damped steps at the outlet spike: measured on 257 x 257,
            # every step damped, |dp| capped at the spike), fall back early
            budget["max_damped"] = options.max_damped
    try:
        p, h00, history, gm = newton(P, p.copy(), h00, W, **budget)
    except ConvergenceError as exc:
        if getattr(exc, "level", None) is None:
            exc.level = int(P.shape[0])  # the grid level that failed (solve_ehl: a nested start's coarser level)
        if getattr(exc, "budget", False):  # the work budget is spent: no fallback
            raise
        if _coarse and getattr(exc, "iterate", None) is not None:
            exc.partial = EHLSolution(contact, P, exc.iterate[0], None, exc.iterate[1], {})
        if _coarse or not (options.consistent_supg and _stage_info is None and nests and _fallback):
            raise
        # second order from the prolonged coarse solution failed: the full
        # defect-correction chain instead (first-order nested iteration from
        # the coarsest grid, then second order on this grid); measured need:
        # M = 20, L = 10 on 129 x 129 (the second-order iteration from the
        # 65 x 65 solution wanders into an oscillating outlet spike)
        import dataclasses

        log.info("EHL: %s; retrying with first-order nested iteration on %d nodes", exc, P.N)
        out = _solve_ehl(contact, grid, dataclasses.replace(options, first_order_start="every_grid"),
                         sequence=True, _final=_final, _coarse=_coarse)
        out.info["fallback"] = dict(failed_start=str(exc))
        out.info["wall_time"] = time.perf_counter() - t0
        return out
    hn = P.film(p, h00)
    if _final and np.min(hn) <= options.h_floor * P.hscale * 1.0001:
        raise _stopped("film collapsed",
            f"EHL solution touches the film-thickness floor ({options.h_floor:g} of b^2/R_x): the film "
            f"has collapsed at M = {contact.moes_M:.4g}, L = {contact.moes_L:.4g} ({_nodes(P)}): the grid does not "
            "resolve the outlet constriction; "
            + (_heavy(P) or f"use a finer grid ([grid] nx >= {2 * (grid.nx - 1) + 1}) or a lower load")
        )
    dense = P.N <= (options.dense_max_line if contact.is_line else options.dense_max)
    linear = "dense LU" if dense else ("GMRES + ILU" if method == "active_set" else "GMRES + sparse LU (local K)")
    info = dict(iterations=len(history), history=history, wall_time=time.perf_counter() - t0,
                gmres_iterations=gm, unknowns=int(P.N), linear=linear, method=method,
                scheme="second order" if options.consistent_supg else "first order", **(_stage_info or {}))
    info.update(stop_reason=P.stop["reason"], stop_detail=P.stop["detail"])
    if coarse_level is not None:
        info["coarse_level"] = coarse_level
    log.info("EHL M=%.4g L=%.4g: %d unknowns, %d Newton iterations, %.2f s", contact.moes_M, contact.moes_L,
             P.N, len(history), info["wall_time"])
    return EHLSolution(contact, P, p, hn, h00, info)


# ---------------------------------------------------------------- a-posteriori resolution check

# Newton steps of one check solve (the one-level-coarser or -finer grid, started from the solution)
CHECK_MAX_ITER = 30
# work budget of the check's solves, as a fraction of the solve's default budget (DEFAULT_MAX_WORK, in Newton
# steps on the requested grid): 100 steps for lines, 25 for points
CHECK_WORK = 0.25


def _a_posteriori(sol: EHLSolution, options: EHLOptions):
    """The one-level-coarser (and, where it is needed, one-level-finer) solutions the resolution check
    compares ``sol`` with (:func:`_resolution_levels`), then :func:`~lubedyn.lubrication.ehl.checks.check_solution`."""
    if options.check_resolution and sol.info.get("method") != "multigrid":
        from threadpoolctl import threadpool_limits

        with threadpool_limits(limits=1, user_api="blas"):
            _resolution_levels(sol, options)
    check_solution(sol)


def _resolution_levels(sol: EHLSolution, options: EHLOptions):
    """Record ``sol.info["coarse_level"]`` and, where :func:`checks.wants_finer` asks for it, ``sol.info[
    "finer_level"]``: the central and minimum film of the same contact on the one-level-coarser grid
    ((nx - 1)/2 + 1 nodes, ny likewise, same range and grading) and on the one-level-finer one (2 nx - 1,
    ny likewise), each solved by the same scheme from ``sol`` (restricted or interpolated; the
    second-order Newton iteration at once, then with its first-order start, then, for the coarser grid,
    its own nested start), at most :data:`CHECK_MAX_ITER` Newton steps per start, and :data:`CHECK_WORK`
    of the solve's work budget for the coarser level, twice CHECK_MAX_ITER steps for the finer one.  The
    nested start's coarser level is used where it is a converged solution of the same scheme (point
    contacts up to 129 x 129, most of them: no extra solve).  Multigrid: the FMG level (:func:`_solve_multigrid`).
    Cost: for line contacts both levels cost less than the solve itself; for point contacts the
    coarser level is reused where the nested start converged, and the finer one is solved only up to
    :data:`~lubedyn.lubrication.ehl.checks.FINER_POINT_NODES` nodes (33 x 33 -> 65 x 65), where it
    costs seconds; ``EHLOptions(check_resolution=False)`` skips both (benchmarks/method_limits.py
    records each solve's time with its checks)."""
    import dataclasses

    info, c, g = sol.info, sol.contact, sol.problem.g
    nested = info.get("coarse_level")
    if not (nested is not None and nested.get("converged") and nested.get("scheme") == info.get("scheme")
            and not nested.get("collapsed")) and g.nx >= 17 and (g.ny is None or g.ny >= 9):
        info["coarse_level"] = _level(sol, g.coarser(), options, coarser=True)
    if wants_finer(sol):
        finer = dataclasses.replace(g, nx=2 * (g.nx - 1) + 1, ny=None if g.ny is None else 2 * (g.ny - 1) + 1)
        info["finer_level"] = _level(sol, finer, options, coarser=False)


def _level(sol, grid, options, coarser):
    """One check solve of ``sol.contact`` on ``grid`` (see :func:`_resolution_levels`): a dict with nx,
    central_film, minimum_film, converged, collapsed (film at the floor), start, iterations, work (Newton
    steps on the solution's grid) and wall_time; or, where every start failed, converged False and
    ``failed`` (the last error)."""
    import dataclasses

    c = sol.contact
    opts = dataclasses.replace(options, max_iter=min(options.max_iter, CHECK_MAX_ITER), strict=False,
                               max_work=None)
    if coarser:
        limit = CHECK_WORK * DEFAULT_MAX_WORK["line" if c.is_line else "point"]
        if options.max_work is not None:
            limit = min(limit, CHECK_WORK * options.max_work)
    else:  # two starts of CHECK_MAX_ITER steps on the finer grid
        limit = 2 * CHECK_MAX_ITER * _grid_nodes(c, grid) / _grid_nodes(c, sol.problem.g)
    token = _BUDGET.set(dict(limit=limit, spent=0.0, nodes=_grid_nodes(c, sol.problem.g), nx=grid.nx))
    t0 = time.perf_counter()
    starts = [("this solution, second order", lambda: _solve_ehl(c, grid, opts, initial=sol, sequence=False,
                                                                 _final=False, _stage_info={})),
              ("this solution, first-order start", lambda: _solve_ehl(c, grid, opts, initial=sol, sequence=False,
                                                                      _final=False))]
    if coarser:
        # (the public path: Herschel-Bulkley contacts start from their Newtonian solutions; a film at the floor
        # raises "film collapsed", recorded below)
        starts.append(("its own nested start", lambda: solve_ehl(c, grid, opts, _check=False)))
    rec = dict(nx=int(grid.nx), source="solved by the check")
    if not c.is_line:
        rec["ny"] = grid.ny  # (None: set from the solved level's nodes)
    try:
        for name, run in starts:
            try:
                lv = run()
            except (ConvergenceError, np.linalg.LinAlgError) as exc:
                rec.update(converged=False, failed=str(exc)[:400],
                           collapsed=(getattr(exc, "stop", None) or {}).get("reason") == "film collapsed")
                if getattr(exc, "budget", False):
                    break
                continue
            P = lv.problem
            hn = lv.film_thickness
            if not c.is_line:
                rec["ny"] = int(P.shape[1])
            rec.update(central_film=lv.central_film_thickness, minimum_film=float(np.min(hn)), converged=True,
                       collapsed=bool(np.min(hn) <= options.h_floor * P.hscale * 1.0001), start=name,
                       iterations=lv.info.get("iterations"), scheme=lv.info.get("scheme"),
                       inlet_cells=inlet_cells(lv))
            rec.pop("failed", None)
            break
        rec.update(work=_BUDGET.get()["spent"], wall_time=time.perf_counter() - t0)
    finally:
        _BUDGET.reset(token)
    if not rec.get("converged"):
        rec.update(central_film=np.nan, minimum_film=np.nan)
    log.info("EHL resolution check: %d-node level %s in %.2f s (%.1f work units)", grid.nx,
             f"h_c {rec['central_film']:.4g} m" if rec["converged"] else "failed", rec["wall_time"], rec["work"])
    return rec


def multigrid_grid(contact: EHLContact, grid: EHLGrid, coarsest_cells: int = 16) -> EHLGrid:
    """The grid that ``method="multigrid"`` solves on: ``grid`` with ``ny``
    chosen (if not given) so that both cell counts halve down to the coarsest
    grid (``coarsest_cells`` cells along x).  nx must be coarsest_cells 2^k + 1
    (17, 33, 65, 129, 257, 513, 1025 by default)."""
    if contact.is_line:
        raise InputError("solver.method = 'multigrid' solves point contacts; line contacts use 'auto' "
                         "(active set) or 'fischer_burmeister'")
    if contact.lubricant.eyring_stress is not None:
        raise InputError(f"lubricant.eyring_stress = {contact.lubricant.eyring_stress!r}: solver.method = 'multigrid' "
                         "is Newtonian; use 'auto', 'fischer_burmeister' or 'active_set' for Eyring flow")
    if contact.lubricant.herschel_bulkley is not None:
        raise InputError(f"lubricant.herschel_bulkley = {contact.lubricant.herschel_bulkley!r}: solver.method = "
                         "'multigrid' is Newtonian; use 'auto', 'fischer_burmeister' or 'active_set' for "
                         "Herschel-Bulkley flow")
    cells = grid.nx - 1
    k = 0
    while cells % 2 == 0 and cells // 2 >= coarsest_cells:
        cells //= 2
        k += 1
    if cells != coarsest_cells:
        allowed = ", ".join(str(coarsest_cells * 2**i + 1) for i in range(7))
        raise InputError(f"grid.nx = {grid.nx} for solver.method = 'multigrid': nx - 1 must be {coarsest_cells} "
                         f"times a power of 2 (the coarsest grid has {coarsest_cells} cells); use one of {allowed}")
    step = 2**k
    if grid.ny is not None:
        if (grid.ny - 1) % step or (grid.ny - 1) // step < 4:
            raise InputError(f"grid.ny = {grid.ny} for solver.method = 'multigrid' with nx = {grid.nx}: ny - 1 must be "
                             f"a multiple of {step} and at least {4 * step}")
        return grid
    hp = hertz.point_contact(contact.hertz_load(), contact.radius_x, contact.radius_y, contact.e_star)
    bx, by = (hp.b, hp.a) if contact.radius_y >= contact.radius_x else (hp.a, hp.b)
    cy = (grid.nx - 1) * 2 * grid.y_max * by / ((grid.x_max - grid.x_min) * bx)
    ny = max(4, int(round(cy / step))) * step + 1
    import dataclasses

    return dataclasses.replace(grid, ny=ny)


def _solve_multigrid(contact: EHLContact, grid: EHLGrid, options: EHLOptions, initial=None) -> EHLSolution:
    """``method="multigrid"``: FAS multigrid (:mod:`lubedyn.lubrication.ehl.multigrid`) on the
    nodes of :class:`_Problem` (same grid, kernel, film and outputs as the Newton
    methods).  Steady point contacts, given load or approach."""
    t0, c0 = time.perf_counter(), time.process_time()
    mopt = options.multigrid if options.multigrid is not None else MultigridOptions()
    if contact.squeeze_velocity != 0.0:
        raise InputError(f"squeeze_velocity = {contact.squeeze_velocity!r} with solver.method = 'multigrid': the "
                         "multigrid solver is steady; use the Newton methods (solver.method = 'auto') for squeeze")
    g = multigrid_grid(contact, grid, mopt.coarsest_cells)
    P = _Problem(contact, g, options)
    P.uniform_weights()  # load and outputs without the FEM assembly templates
    t_setup = time.perf_counter() - t0
    if contact.load is not None:
        if initial is not None and getattr(initial, "h00", None) is not None:
            h00 = float(initial.h00)
        else:
            p = _hertz_guess(P)
            h00 = _film_guess(contact) - float(P.deflect(p)[np.argmin(np.abs(P.rigid))])
    else:
        h00 = contact.approach
    mg = MultigridEHL(P, contact, mopt)
    Pg, H00, history = mg.solve(h00 / P.hscale)
    p = P.ph * Pg.ravel()[P.flat]
    h00 = H00 * P.hscale
    hn = P.film(p, h00)
    if np.min(hn) <= 0.0:
        raise _stopped("film collapsed",
            f"EHL multigrid solution at M = {contact.moes_M:.4g}, L = {contact.moes_L:.4g} on {g.nx} x {g.ny} "
            f"nodes has a film thickness <= 0 (min {np.min(hn) / P.hscale:.3g} b^2/R_x): the grid does not "
            f"resolve the outlet constriction; use [grid] nx >= {2 * (g.nx - 1) + 1}"
            + (" (M is large: a very heavily loaded or slow contact)" if contact.moes_M >= 1000 else ""))
    info = dict(iterations=len(history) - 1, cycles=len(history) - 1, history=history,
                work_units=float(mg.work), wall_time=time.perf_counter() - t0, cpu_time=time.process_time() - c0,
                setup_time=t_setup, unknowns=int(P.N), levels=[lv.shape for lv in mg.levels], method="multigrid",
                scheme=f"finite differences, order-{mopt.order} upstream wedge", linear="line relaxation (FAS)",
                residual=history[-1]["residual"], load_error=history[-1]["load_error"],
                stop_reason="tolerance met", stop_detail=f"{history[-1].get('stop')} stop: "
                f"{history[-1].get('stop_detail', '')} after {len(history) - 1} cycles")
    coarse = history[0].get("coarse")
    if coarse is not None:  # the FMG solution of the next-coarser grid (check_solution)
        info["coarse_level"] = dict(nx=int(mg.levels[-2].shape[0]), central_film=coarse["H_centre"] * P.hscale,
                                    minimum_film=coarse["H_min"] * P.hscale, converged=True)
    log.info("EHL multigrid M=%.4g L=%.4g: %d x %d nodes, %d cycles, %.1f work units, %.2f s", contact.moes_M,
             contact.moes_L, g.nx, g.ny, info["cycles"], info["work_units"], info["wall_time"])
    return EHLSolution(contact, P, p, hn, h00, info)
