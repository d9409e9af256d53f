"""Why a film solve stopped: iteration histories, cycles, divergence, the round-off floor.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import numpy as np

from .options import AMG_STALL_FACTOR

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

    A 1-D inclined slider of 1e5 P1 cells (linear: one solve is exact up to round-off;
    tests/test_roundoff.py) sits at ||R|| = 0.2 eps || |J||p| ||, which is 1.8e-7 ||R_0|| because the terms cancel to a
    source 1e7 times smaller, with a Newton step of 5e-10 |p| (cond ~ N^2): neither 10 rtol
    ||R_0|| nor a step below rtol could be met and the solve ran out of iterations.  The nested
    Martin cylinder sits at 42 eps (the sparse LU's backward error).  Used only with a step below
    max(rtol, 1e-8) |p|."""
    terms = abs(Jp) @ np.abs(p)
    if Jr is not None:
        terms = terms + abs(Jr) @ np.abs(r)
    return bool(np.linalg.norm(R[mask]) <= ROUNDOFF_FLOOR * np.finfo(float).eps * np.linalg.norm(terms[mask]))
