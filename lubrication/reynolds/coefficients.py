"""film_coefficients: the linearised stiffness and damping of a solved Reynolds film.

Part of :mod:`lubedyn.lubrication.reynolds` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import numpy as np
import scipy.sparse.linalg as spla
from skfem import asm
from skfem.helpers import dot

from .forms import flux_load_form, interpolate, source_load_form
from .problem import _Problem, _select_columns


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
        dR_dq = asm(flux_load_form, b, f=dk_dh * g * c["gp"] - rho * g * theta * um)
        if jfo:
            dR_dq = dR_dq - asm(flux_load_form, b, f=prob.tau * rho * g * dot(um, c["gr"]) * um)
        dR_dqdot = asm(source_load_form, b, g=rho * theta * g)
        for kind, rhs, out in (("K", dR_dq, K), ("C", dR_dqdot, C)):
            z = np.zeros(prob.N)
            z[idx] = lu.solve(-rhs[idx])
            dp = np.where(full & prob.free, z, 0.0)
            dpq = np.asarray(interpolate(b, dp))
            for i, name_i in enumerate(names):
                out[i, j] = -float(np.sum(dpq * prob.modes[name_i] * b.dx))
    return names, K, C
