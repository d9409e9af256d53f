"""Film stiffness and damping of an EHL contact (linearised normal coefficients).

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import time
from typing import NamedTuple

import numpy as np
from skfem import asm

from ..errors import InputError, unknown_choice
from ..reynolds.forms import source_load_form
from .contact import EHLContact
from .newton import _FBLinear, _row_scale
from .options import EHLGrid, EHLOptions
from .problem import _supg_load
from .solution import EHLSolution
from .solve import _solve_ehl, solve_ehl

log = logging.getLogger(__name__)

class NormalCoefficients(NamedTuple):
    """Normal film coefficients about a steady state (unpacks as ``K, C, solution``).

    ``stiffness`` K = -dF/dh00 [N/m] and ``damping`` C = -dF/d(dh00/dt)
    [N s/m] (per unit length, [N/m^2] and [N s/m^2], for line contacts),
    F = int p dA the film force that pushes the bodies apart, h00 the
    rigid-body separation (so K = dF/d(delta) for the approach delta =
    -h00); both > 0.  ``solution`` is the steady state; its
    ``info["normal_coefficients"]`` holds the method and its details.
    """

    stiffness: float
    damping: float
    solution: EHLSolution


def ehl_normal_coefficients(contact: EHLContact, grid: EHLGrid = EHLGrid(nx=33),
                            options: EHLOptions = EHLOptions(), method: str = "linearised",
                            rel_step: float = 1e-3, steady: EHLSolution | None = None) -> NormalCoefficients:
    r"""Normal stiffness and damping of an EHL film about its steady state.

    The steady state is ``contact`` solved with its load (or taken from
    ``steady``, solved on ``grid`` with ``options``).  Then, with the
    discrete system R(p, h00, hdot) = 0 (Reynolds with the squeeze source
    rho hdot, hdot = dh00/dt; elasticity inside h) and F = w . p:

    ``method="linearised"`` (default, one extra factorisation): on the nodes
    that carry pressure (the cavitated set held fixed: at the Reynolds
    free boundary p and grad p vanish, so to first order the load does not
    depend on where the boundary moves)::

        (A + D K) dp/dh00 = -dR/dh00 = -D 1,   (A + D K) dp/dhdot = -dR/dhdot
        dR_i/dhdot = int rho phi_i dA + int tau rho (u_m . grad phi_i) dA     (SUPG part)
        K = -w . dp/dh00,   C = -w . dp/dhdot

    ``method="finite_difference"``: four prescribed-approach solves on the
    same grid (``scale_load`` = the steady load), started from the steady
    pressure: central differences in h00 (step ``rel_step`` h_c) and in
    dh00/dt (step ``rel_step`` u_m h_c / b_x).

    Parameters
    ----------
    contact : EHLContact
        With ``load`` given (the steady state).
    grid, options : EHLGrid, EHLOptions
        Moderate grids are meant (33 x 33 points, 257 line nodes: well under a
        second each for the linearised method here).
    method : {"linearised", "finite_difference"}
    rel_step : float
        Relative finite-difference step.
    steady : EHLSolution, optional
        A converged steady state of ``contact`` on ``grid`` (skips its solve).

    Returns
    -------
    NormalCoefficients
        ``(K, C, steady_solution)``.

    Examples
    --------
    >>> K, C, s = ehl_normal_coefficients(EHLContact.from_moes(100, 10, line=True), EHLGrid(nx=257))
    >>> bool(K > 0 and C > 0)
    True
    """
    import dataclasses

    from threadpoolctl import threadpool_limits

    methods = ("linearised", "finite_difference")
    if method not in methods:
        raise unknown_choice("normal coefficients method", method, methods)
    if contact.load is None:
        raise InputError("ehl_normal_coefficients needs a contact with 'load' (the steady state), not 'approach'")
    if options.method == "multigrid":
        raise InputError("solver.method = 'multigrid' for normal coefficients: the multigrid solver is steady and has "
                         "no Jacobian; use solver.method = 'auto' (Newton) for stiffness and damping")
    t0 = time.perf_counter()
    sol = steady if steady is not None else solve_ehl(contact, grid, options)
    P = sol.problem
    with threadpool_limits(limits=1, user_api="blas"):
        if method == "linearised":
            p, h00 = sol.pressure, float(sol.h00)
            R, hn, A, D, aux = P.assemble(p, h00)
            # the Reynolds set: interior nodes where the pressure, not the
            # (row-scaled) residual, is the larger member of the complementary pair
            inner = np.flatnonzero(P.free0)
            s_row = _row_scale(P, A, D, inner)
            idx = inner[p[inner] / P.ph > s_row * R[inner]]
            lin = _FBLinear(P, A, D, np.zeros(idx.size), np.ones(idx.size), idx)
            b = P.basis
            dR_dh = D @ np.ones(P.N)
            dR_dv = np.asarray(asm(source_load_form, b, g=aux["rho"])) + np.asarray(
                asm(_supg_load, b, t=aux["tau"] * aux["rho"], u=P.u))
            w = P.weights[idx]
            K = -float(w @ lin.solve(-dR_dh[idx]))
            C = -float(w @ lin.solve(-dR_dv[idx]))
            details = dict(method=method, free_nodes=int(idx.size), gmres_iterations=lin.gmres_iters)
        else:
            hc = sol.central_film_thickness
            base = dataclasses.replace(contact, load=None, approach=float(sol.h00), scale_load=contact.load)
            dh = rel_step * hc
            dv = rel_step * contact.mean_speed * hc / P.bx

            def force(**change):
                s2 = _solve_ehl(dataclasses.replace(base, **change), grid, options, initial=sol, sequence=False,
                                _final=False, _stage_info={})
                return s2.load, s2.info["iterations"]

            (fp, ip), (fm, im) = force(approach=sol.h00 + dh), force(approach=sol.h00 - dh)
            (vp, jp), (vm, jm) = (force(squeeze_velocity=contact.squeeze_velocity + dv),
                                  force(squeeze_velocity=contact.squeeze_velocity - dv))
            K = -(fp - fm) / (2 * dh)
            C = -(vp - vm) / (2 * dv)
            details = dict(method=method, h00_step=dh, squeeze_step=dv, newton_iterations=[ip, im, jp, jm])
    details["wall_time"] = time.perf_counter() - t0
    sol.info["normal_coefficients"] = details
    log.info("EHL normal coefficients (%s): K = %.4g, C = %.4g, %.2f s", method, K, C, details["wall_time"])
    return NormalCoefficients(K, C, sol)
