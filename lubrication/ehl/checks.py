"""A-posteriori checks of an EHL solution against closed-form film formulas and its own grid.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import numpy as np

from ..errors import ConvergenceError
from .contact import EHLContact
from .solution import EHLSolution

log = logging.getLogger(__name__)

FORMULA_TOLERANCE = 0.10
COARSE_TOLERANCE = 0.13
# where the closed forms were compared with converged solutions (Barus, incompressible, Newtonian):
FORMULA_ENVELOPE = dict(M=(10.0, 2000.0), L=(5.0, 20.0))
# inlet check (line contacts): the pressure a tenth of the inlet length from the inlet boundary, over the
# maximum pressure.  Measured on paper A's roller line contact (L = 55-73, 257 nodes): 1.4e-2 with the film
# 13 % thinner than on a 4-times-longer inlet (20 kN/m, 25 m/s, x_min -20 b), 5.5e-4 with it 0.8 % thinner
# (-80 b), 0.11 at 1 kN/m on -80 b (the film 3-10 times too thin); flooded contacts 1e-8 .. 1.1e-4 (paper
# A's 100-250 kN/m on -20 b, Moes M = 10, 100, 1000 at L = 10 on the default -4.5 b).
INLET_TOLERANCE = 1e-3
INLET_PROBE = 0.1


def closed_form_central_film(contact: EHLContact):
    """``(name, h_c [m])`` of the closed-form central film this project checks ``contact`` against,
    or None outside the conditions it was fitted and measured for: a Barus, incompressible,
    Newtonian lubricant, given load, a line or circular contact, and Moes' M and L inside
    :data:`FORMULA_ENVELOPE` (Moes' line formula; Nijenbanning-Venner-Moes for circles)."""
    from ..laws.film import moes_line_central, nijenbanning_central
    from ..laws.lubricant import Barus, Incompressible

    lub = contact.lubricant
    if (contact.load is None or not lub.is_newtonian or not isinstance(lub.viscosity, Barus)
            or not isinstance(lub.density, Incompressible) or contact.squeeze_velocity != 0.0):
        return None
    if not contact.is_line and contact.radius_y != contact.radius_x:
        return None
    M, L = contact.moes_M, contact.moes_L
    (m0, m1), (l0, l1) = FORMULA_ENVELOPE["M"], FORMULA_ENVELOPE["L"]
    if not (m0 <= M <= m1 and l0 <= L <= l1):
        return None
    scale = contact.radius_x * np.sqrt(2 * contact.U)
    if contact.is_line:
        return "Moes' line formula", float(moes_line_central(M, L) * scale)
    return "Nijenbanning-Venner-Moes", float(nijenbanning_central(M, L) * scale)


def _finer(nx, times=1):
    for _ in range(times):
        nx = 2 * (nx - 1) + 1
    return nx


def check_solution(sol: EHLSolution) -> list[str]:
    """A-posteriori checks of a converged EHL solution: its central film against the closed form
    (:func:`closed_form_central_film`, beyond :data:`FORMULA_TOLERANCE`) and against the
    one-level-coarser solution that nested iteration (Newton) or the FMG start (multigrid) computed
    (estimated discretisation error beyond :data:`COARSE_TOLERANCE`; multigrid: or a coarse film <= 0),
    and, for line contacts, whether the inlet is long enough: the pressure a tenth of the inlet length
    from the inlet boundary must be below :data:`INLET_TOLERANCE` of the maximum, or the film is
    starved by the domain (too thin: the inlet of a light, fast contact scales with sqrt(2 R h), not with
    the Hertz half-width).

    Each failed check is one line naming the figures and the grid needed; they are logged (WARNING)
    and listed in ``sol.info["warnings"]``, or, with ``EHLOptions(strict=True)``, raised as
    :class:`~lubedyn.lubrication.errors.ConvergenceError`.  Returns the list (empty: nothing to report).
    """
    c, P, info = sol.contact, sol.problem, sol.info
    nx = int(P.shape[0])
    grid = f"{nx} nodes" if c.is_line else f"{P.shape[0]} x {P.shape[1]} nodes"
    hc = sol.central_film_thickness
    checks, out = {}, []
    ref = closed_form_central_film(c)
    if ref is not None:
        name, href = ref
        dev = hc / href - 1.0
        checks["closed_form"] = dict(formula=name, central_film=href, deviation=dev, tolerance=FORMULA_TOLERANCE)
        if abs(dev) > FORMULA_TOLERANCE:
            out.append(f"EHL central film {hc:.4g} m on {grid} at M = {c.moes_M:.4g}, L = {c.moes_L:.4g} is {dev:+.0%} "
                       f"off {name} ({href:.4g} m; converged solutions lie within 6 % of it): the grid does not "
                       f"resolve the contact; use grid.nx >= {_finer(nx)}")
    coarse = info.get("coarse_level")
    if coarse is not None and np.isfinite(coarse.get("central_film", np.nan)):
        hcc, hmc = coarse["central_film"], coarse["minimum_film"]
        est = abs(hc - hcc) / (3.0 * abs(hc))
        checks["coarse_level"] = dict(coarse, estimated_error=est, tolerance=COARSE_TOLERANCE)
        collapsed = hmc <= 0.0 or hcc <= 0.0
        if collapsed and info.get("method") == "multigrid":
            out.append(f"EHL solution on {grid} at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}: the one-level-coarser "
                       f"FMG grid ({coarse['nx']} nodes along x) has a collapsed film (minimum {hmc:.3g} m), so this "
                       f"grid is at its resolution limit (central film {hc:.4g} m against {hcc:.4g} m there); use "
                       f"grid.nx >= {_finer(nx)}")
        elif not collapsed and coarse.get("converged", True) and est > COARSE_TOLERANCE:
            # second order: the error falls 4 times per halving of the cells
            k = int(np.ceil(np.log(est / COARSE_TOLERANCE) / np.log(4.0)))
            out.append(f"EHL central film {hc:.4g} m on {grid} differs by {abs(hc / hcc - 1):.0%} from the "
                       f"one-level-coarser grid's {hcc:.4g} m (estimated discretisation error {est:.0%} > "
                       f"{COARSE_TOLERANCE:.0%}) at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}; use grid.nx >= "
                       f"{_finer(nx, max(k, 1))}")
    if c.is_line:
        x = np.asarray(P.doflocs[0], dtype=float)
        order = np.argsort(x)
        x, p = x[order], np.asarray(sol.pressure, dtype=float)[order]
        pmax = float(np.max(p))
        if pmax > 0.0 and x[0] < 0.0:
            ratio = float(np.interp((1.0 - INLET_PROBE) * x[0], x, p)) / pmax
            checks["inlet"] = dict(pressure_ratio=ratio, tolerance=INLET_TOLERANCE, x_min=float(P.g.x_min))
            if ratio > INLET_TOLERANCE:
                out.append(f"EHL inlet starved on {grid} at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}: the pressure a "
                           f"tenth of the inlet from its boundary (x_min = {P.g.x_min:g} Hertz half-widths) is "
                           f"{ratio:.1e} of the maximum (> {INLET_TOLERANCE:g}), so the film ({hc:.4g} m) is thinner "
                           f"than a flooded contact's (measured: 1.4e-2 gave -13 %); use grid.x_min <= "
                           f"{4.0 * P.g.x_min:g}")
    info["checks"] = checks
    info["warnings"] = list(out)
    if out and P.o.strict:
        err = ConvergenceError("; ".join(out) + " (EHLOptions.strict)")
        err.stop = dict(reason="a-posteriori check failed", detail="; ".join(out))
        raise err
    for text in out:
        log.warning("%s", text)
    return out
