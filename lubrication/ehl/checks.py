"""A-posteriori checks of an EHL solution against closed-form film formulas and its own grid.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import logging
import numpy as np

from ..errors import ConvergenceError
from .contact import EHLContact
from .solution import EHLSolution
from ..laws.film import moes_line_central, nijenbanning_central
from ..laws.lubricant import Barus, Incompressible

log = logging.getLogger(__name__)

FORMULA_TOLERANCE = 0.10
COARSE_TOLERANCE = 0.13
#: a pure squeeze contact (u_m = 0) whose largest pressure exceeds this multiple of the Hertz pressure is
#: not a quasi-steady squeeze film: measured on two 6206 balls (paper B's oil, Roelands, 33 x 33 nodes), the
#: steady equations also admit trapped-oil states, 0.1 N at 1e-3 m/s from the squeeze start: p_max 19.5 GPa,
#: 55 x Hertz; 100 N at 0.1 m/s from an isoviscous continuation: 42 GPa, 12 x Hertz, h_c 72 um against a 5.7
#: um Hertz approach), while the isoviscous squeeze film at 100 N peaks at 1.04 x Hertz; EHL films' outlet
#: spikes reach 2-3 x (Venner & Lubrecht 2000)
SQUEEZE_PRESSURE_LIMIT = 3.0
# The resolution check for every density, viscosity and flow law (FORMULA_TOLERANCE and
# COARSE_TOLERANCE: lubrication/ehl/budget.py).  Chosen on Moes line contacts, M = 100 ... 2000,
# L = 5, 10, 20, with Barus, Dowson-Higginson (DH), Roelands + DH, Reynolds-Eyring (tau0 = 0.3 and 1 MPa)
# and Herschel-Bulkley (tau_y = 1 kPa, M = 20 ... 100) lubricants on 129 ... 1025 nodes, each against the
# same contact on 2049 nodes (or the finest that converged), and on circular contacts (Barus and DH,
# M = 20 ... 1000, Newton on 33 ... 129, multigrid on 65 ... 257, against the multigrid's 257/513
# Richardson value): tests/test_ehl_checks_all.py names the cases that the thresholds below separate.
# - The one-level-coarser comparison alone cannot tell: the film converges non-monotonically until the
#   inlet is resolved (DH, M = 300, L = 20: +100 %, +95 %, -2.2 %, 0.0 % on 65, 129, 257, 513 nodes), so
#   two wrong grids can agree (129 against 65: 1.2 %) and a right grid can differ from a wrong coarser one
#   (257 against 129: estimated 33 %).  Line contacts therefore solve the one-level-finer grid where the
#   coarser level did not converge, collapsed, differs by more than FINER_TRIGGER (5 %), or where the
#   inlet's piezoviscous rise (1 - eta0/eta from 0.1 to 0.9) spans fewer than INLET_CELLS_TRIGGER cells
#   (6): every line case more than 10 % off was flagged by one or the other (their inlets spanned 0.98 ...
#   6.4 cells; cases within 2 % spanned 3.4 cells and more, so the inlet alone cannot decide).
# - FINER_TOLERANCE: the estimated error from the finer grid, (4/3)|h_c/h_c,finer - 1| (second order),
#   beyond 10 % warns.  Line sweep, 215 cases on 129 ... 1025 nodes: of the 33 more than 10 % off, 32 warn
#   (the other: Eyring tau0 = 1 MPa, M = 1000, L = 20 on 513 nodes, -10.6 %, estimated 9.9 %); none of
#   those within 7 % warns; 3 of the 13 between 7 and 10 % do (DH M = 500, L = 10 on 257 nodes, +7.3 %,
#   estimated 11 %); on 1025 nodes none of 52 warns (all within 3.5 %).
# - INLET_CELLS_HARD: a safety net for line grids whose finer grid agrees while neither resolves the inlet
#   (< 2 cells here, < INLET_CELLS_TRIGGER there): the 7 sweep cases under 2 cells were -37 ... +280 % off
#   (one -9 %), and the finer comparison warned for each.
# - Point contacts (Newton methods): the same finer comparison, where the coarser level failed, collapsed
#   or is beyond COARSE_TOLERANCE, if the finer grid has at most FINER_POINT_NODES nodes (33 x 33 -> 65 x 65
#   in 1-10 s; 86 x 17 -> 171 x 33 took 11-37 s per solve, ten times paper B's map points, so not there);
#   else the coarser level's estimate against COARSE_TOLERANCE, if that level has COARSE_POINT_CELLS cells
#   across the Hertz contact (paper B's ball at M = 969 - 1077 on 86 x 17 nodes is within 0.05 % of
#   172 x 33, while its 43 x 9 level, 4 cells across, is 41 - 52 % off) (DH and Barus circles, M = 20 ...
#   1000, 48 Newton cases: every 65 x 65 and 129 x 129 film was within 7 % but Barus M = 1000, L = 20 on
#   65 x 65, +14 %, which the closed form catches; on 33 x 33 the three more than 10 % off warn, the two at
#   -8 ... -9 % do not; none within 7 % warns).
#   The multigrid keeps its FMG level (its errors fall 4 times per halving).
FINER_TRIGGER = 0.05
FINER_TOLERANCE = 0.10
INLET_CELLS_TRIGGER = 6.0
INLET_CELLS_HARD = 2.0
FINER_POINT_NODES = 4500
COARSE_POINT_CELLS = 8.0
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


def _halvings(est, tol):
    """Cell halvings that bring an estimated error ``est`` below ``tol`` at second order (4 times per halving)."""
    return 0 if est <= tol else int(np.ceil(np.log(est / tol) / np.log(4.0)))


def inlet_cells(sol: EHLSolution, lo: float = 0.1, hi: float = 0.9):
    """How many cells (fractional, along x on the centre line) the inlet's piezoviscous rise takes: the
    viscosity factor q = 1 - eta0/eta(p) (1 - exp(-alpha p) for Barus) going from ``lo`` to ``hi`` upstream
    of the point where it first reaches ``hi``.  That rise is where the film is made (the lubricant
    locks into the Hertz zone as q -> 1), so it is the zone a grid must resolve; None where q never
    reaches ``hi`` (isoviscous or lightly loaded films, whose inlet is wide)."""
    x, p = sol._centre_line(np.asarray(sol.pressure, dtype=float))
    visc = sol.contact.lubricant.viscosity
    if getattr(visc, "is_constant", False):
        return None
    eta = np.asarray(visc(np.maximum(p, 0.0)), dtype=float)
    q = 1.0 - visc.eta0 / eta
    above = np.flatnonzero(q >= hi)
    if above.size == 0 or above[0] == 0:
        return None
    j = int(above[0])
    below = np.flatnonzero(q[:j] <= lo)
    i = int(below[-1]) if below.size else 0
    k = np.arange(x.size, dtype=float)
    seg = slice(i, j + 1)
    # fractional node index of each crossing (q is increasing over [i, j] up to round-off: take its running max)
    qs = np.maximum.accumulate(q[seg])
    return float(np.interp(hi, qs, k[seg]) - np.interp(lo, qs, k[seg]))


def coarse_cells(sol: EHLSolution):
    """Cells of the one-level-coarser grid across the Hertz contact (2 semi-axes), the fewer of x and y
    (point contacts; None for lines or without a coarser level)."""
    coarse = sol.info.get("coarse_level")
    if sol.contact.is_line or coarse is None:
        return None
    g = sol.problem.g
    cells = 2.0 * (coarse["nx"] - 1) / (g.x_max - g.x_min)
    ny = coarse.get("ny")
    if ny:
        cells = min(cells, 2.0 * (ny - 1) / (2.0 * g.y_max))
    return float(cells)


def coarse_estimate(sol: EHLSolution, trusted_only: bool = True):
    """The discretisation error of ``sol``'s central film estimated from the one-level-coarser solution
    (``sol.info["coarse_level"]``), |h_c - h_c,coarse|/(3 h_c) (second order), or None where there is no
    converged coarser level with a film above zero, or (``trusted_only``) where a point contact's coarser
    Newton level has fewer than :data:`COARSE_POINT_CELLS` cells across the Hertz contact (too coarse to
    compare with: measured, paper B's ball at M = 969 - 1077 on 86 x 17 nodes is within 0.05 % of 172 x 33
    while its 43 x 9 level, 4 cells across, is 41 - 52 % off)."""
    coarse = sol.info.get("coarse_level")
    if coarse is None or not coarse.get("converged", True) or not np.isfinite(coarse.get("central_film", np.nan)):
        return None
    if coarse.get("collapsed") or coarse["central_film"] <= 0.0 or coarse["minimum_film"] <= 0.0:
        return None
    if (trusted_only and sol.info.get("method") != "multigrid" and not sol.contact.is_line
            and coarse_cells(sol) < COARSE_POINT_CELLS):
        return None
    hc = sol.central_film_thickness
    return abs(hc - coarse["central_film"]) / (3.0 * abs(hc))


def _nodes(rec) -> str:
    """'513 nodes' or '65 x 65 nodes' of a check level's record (nx, and ny for point contacts)."""
    return f"{rec['nx']} x {rec['ny']} nodes" if rec.get("ny") else f"{rec['nx']} nodes"


def _level(rec) -> str:
    """'the 129-node level' or 'the 17 x 17-node level'."""
    return f"the {_nodes(rec)[:-6]}-node level"


def _finer_nodes(sol: EHLSolution) -> int:
    shape = sol.problem.shape
    return int(np.prod([2 * (n - 1) + 1 for n in shape]))


def wants_finer(sol: EHLSolution):
    """Why the resolution check solves the one-level-finer grid too (None: it need not).  Line contacts:
    the one-level-coarser level did not converge, has a collapsed film, or differs by more than
    :data:`FINER_TRIGGER` (estimated error), or the inlet's piezoviscous rise spans fewer than
    :data:`INLET_CELLS_TRIGGER` cells: the states in which the coarser level alone cannot tell a
    resolved film from a wrong one.  Point contacts (Newton methods): the coarser level did not converge,
    collapsed or differs by more than :data:`COARSE_TOLERANCE`, where the finer grid has at most
    :data:`FINER_POINT_NODES` nodes (else the coarser level's estimate stands).  Multigrid: never (its
    FMG level is in the asymptotic range).  Module constants: from the sweeps described above them
    (tests/test_ehl_checks_all.py names the cases they separate)."""
    coarse = sol.info.get("coarse_level")
    if sol.info.get("method") == "multigrid":
        return None
    if not sol.contact.is_line:
        # point contacts: only where the coarser level failed, collapsed or is beyond COARSE_TOLERANCE (every
        # circle more than 10 % off in the sweep was flagged so; the inlet's cells do not separate the
        # multigrid's or the 33 x 33 Newton's cases), and only up to FINER_POINT_NODES
        if coarse is None or _finer_nodes(sol) > FINER_POINT_NODES:
            return None
        est = coarse_estimate(sol, trusted_only=False)
        if not coarse.get("converged", True):
            return f"{_level(coarse)} did not converge"
        if est is None:
            return f"{_level(coarse)}'s film collapsed (minimum {coarse['minimum_film']:.3g} m)"
        if est > COARSE_TOLERANCE:
            return (f"{_level(coarse)}'s central film {coarse['central_film']:.4g} m differs by "
                    f"{abs(sol.central_film_thickness / coarse['central_film'] - 1):.0%}")
        return None
    if coarse is not None:
        if not coarse.get("converged", True):
            return f"{_level(coarse)} did not converge"
        est = coarse_estimate(sol)
        if est is None:
            return f"{_level(coarse)}'s film collapsed (minimum {coarse['minimum_film']:.3g} m)"
        if est > FINER_TRIGGER:
            return (f"{_level(coarse)}'s central film {coarse['central_film']:.4g} m differs by "
                    f"{abs(sol.central_film_thickness / coarse['central_film'] - 1):.0%}")
    cells = inlet_cells(sol)
    if cells is not None and cells < INLET_CELLS_TRIGGER:
        return f"the inlet's piezoviscous rise spans {cells:.1f} cells (< {INLET_CELLS_TRIGGER:g})"
    return None


def check_solution(sol: EHLSolution) -> list[str]:
    """A-posteriori checks of a converged EHL solution, for every density, viscosity and flow law:

    - its central film against the closed form where one applies (:func:`closed_form_central_film`,
      beyond :data:`FORMULA_TOLERANCE`);
    - its resolution: against the one-level-coarser solution (``info["coarse_level"]``: the nested
      start's or the FMG start's level, or solved by :func:`lubedyn.lubrication.ehl.solve._resolution_levels`),
      estimated discretisation error |h_c - h_c,coarse|/(3 h_c) beyond :data:`COARSE_TOLERANCE`
      (multigrid: or a coarse film <= 0); for line contacts, where that level did not converge, has
      a collapsed film or differs by more than :data:`FINER_TRIGGER`, against the one-level-finer
      solution (``info["finer_level"]``), the film's deviation beyond :data:`FINER_TOLERANCE`;
    - for line contacts, whether the inlet is long enough: the pressure a tenth of the inlet length
      from the inlet boundary must be below :data:`INLET_TOLERANCE` of the maximum, or the film is
      starved by the domain (too thin: the inlet of a light, fast contact scales with sqrt(2 R h), not
      with the Hertz half-width);
    - for pure squeeze contacts (u_m = 0) with a load, the largest pressure against
      :data:`SQUEEZE_PRESSURE_LIMIT` times the Hertz pressure (a trapped-oil state otherwise).

    Each failed check is one line naming the figures and the grid needed (the closed form and the
    resolution check, when both fail, share one line); they are logged (WARNING) and listed in
    ``sol.info["warnings"]``, or, with ``EHLOptions(strict=True)``, raised as
    :class:`~lubedyn.lubrication.errors.ConvergenceError`.  The figures of every check are in
    ``sol.info["checks"]``.  Returns the list (empty: nothing to report).
    """
    c, P, info = sol.contact, sol.problem, sol.info
    nx = int(P.shape[0])
    grid = f"{nx} nodes" if c.is_line else f"{P.shape[0]} x {P.shape[1]} nodes"
    where = f"at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}"
    hc = sol.central_film_thickness
    checks, out = {}, []
    ref = closed_form_central_film(c)
    formula = None
    if ref is not None:
        name, href = ref
        dev = hc / href - 1.0
        checks["closed_form"] = dict(formula=name, central_film=href, deviation=dev, tolerance=FORMULA_TOLERANCE)
        if abs(dev) > FORMULA_TOLERANCE:
            formula = (f"EHL central film {hc:.4g} m on {grid} {where} is {dev:+.0%} off {name} ({href:.4g} m; "
                       "converged solutions lie within 6 % of it)")
    cells = inlet_cells(sol)
    checks["inlet_resolution"] = dict(cells=cells)
    resolution, need = _resolution(sol, checks, grid, where, ref)
    if formula is not None:
        if need is None:
            need = _finer(nx)
            finer = info.get("finer_level")
            if (finer is not None and finer.get("converged")
                    and abs(finer["central_film"] / ref[1] - 1) > FORMULA_TOLERANCE):
                need = _finer(nx, 2)
        text = formula + (f"; {resolution}" if resolution else "")
        out.append(f"{text}: the grid does not resolve the contact; use grid.nx >= {need}")
    elif resolution is not None:
        out.append(f"EHL central film {hc:.4g} m on {grid} {where}: {resolution}; use grid.nx >= {need}")
    if c.is_line:
        x = np.asarray(P.doflocs[0], dtype=float)
        order = np.argsort(x)
        x, p = x[order], np.asarray(sol.pressure, dtype=float)[order]
        pmax = float(np.max(p))
        if pmax > 0.0 and x[0] < 0.0:
            ratio = float(np.interp((1.0 - INLET_PROBE) * x[0], x, p)) / pmax
            checks["inlet"] = dict(pressure_ratio=ratio, tolerance=INLET_TOLERANCE, x_min=float(P.g.x_min))
            if ratio > INLET_TOLERANCE:
                out.append(f"EHL inlet starved on {grid} {where}: the pressure a "
                           f"tenth of the inlet from its boundary (x_min = {P.g.x_min:g} Hertz half-widths) is "
                           f"{ratio:.1e} of the maximum (> {INLET_TOLERANCE:g}), so the film ({hc:.4g} m) is thinner "
                           f"than a flooded contact's (measured: 1.4e-2 gave -13 %); use grid.x_min <= "
                           f"{4.0 * P.g.x_min:g}")
    if c.U == 0.0 and c.load is not None:
        ratio = sol.maximum_pressure / P.ph
        checks["squeeze_pressure"] = dict(ratio=ratio, limit=SQUEEZE_PRESSURE_LIMIT)
        if ratio > SQUEEZE_PRESSURE_LIMIT:
            out.append(f"EHL pure squeeze film on {grid}: its largest pressure {sol.maximum_pressure:.4g} Pa is "
                       f"{ratio:.3g} x the Hertz pressure (> {SQUEEZE_PRESSURE_LIMIT:g}): a trapped-oil state of the "
                       "quasi-steady equations, not a squeeze film (at such loads the film in the Hertz zone is "
                       "frozen over an impact: a transient solve, lubedyn.lubrication.ehl.impact, is the reference)")
    info["checks"] = checks
    info["warnings"] = list(out)
    if out and P.o.strict:
        err = ConvergenceError("; ".join(out) + " (EHLOptions.strict)")
        err.stop = dict(reason="a-posteriori check failed", detail="; ".join(out))
        raise err
    for text in out:
        log.warning("%s", text)
    return out


def _resolution(sol, checks, grid, where, ref):
    """The resolution check of :func:`check_solution`: ``(clause, grid needed)`` of a failed check, or
    ``(None, None)``; its figures go to ``checks``."""
    info = sol.info
    nx = int(sol.problem.shape[0])
    hc = sol.central_film_thickness
    coarse, finer = info.get("coarse_level"), info.get("finer_level")
    est = coarse_estimate(sol)
    if coarse is not None:
        checks["coarse_level"] = dict(coarse, estimated_error=est, tolerance=COARSE_TOLERANCE)
        if est is None and coarse_estimate(sol, trusted_only=False) is not None:
            checks["coarse_level"]["untrusted"] = (f"{coarse_cells(sol):.1f} cells across the Hertz contact "
                                                   f"(< {COARSE_POINT_CELLS:g}): too coarse to compare with")
    cells = checks.get("inlet_resolution", {}).get("cells")
    if finer is not None:
        why = wants_finer(sol)
        if finer.get("converged") and finer["central_film"] > 0.0:
            hf, nf = finer["central_film"], finer["nx"]
            dev = hc / hf - 1.0
            # second order: h - h* ~ dx^2, so this grid's error is 4/3 of its difference from the finer grid
            est_f = 4.0 / 3.0 * abs(dev)
            checks["finer_level"] = dict(finer, deviation=dev, estimated_error=est_f, tolerance=FINER_TOLERANCE,
                                         reason=why)
            if est_f > FINER_TOLERANCE:
                fc = finer.get("inlet_cells")
                if ref is not None:  # the finer solution against the closed form
                    need = nf if abs(hf / ref[1] - 1) <= FORMULA_TOLERANCE else _finer(nf)
                elif sol.contact.is_line and fc is not None and fc >= INLET_CELLS_TRIGGER:  # it resolves the inlet
                    need = nf
                else:  # the finer film's own error, second order from the pair (this grid, the finer one)
                    need = _finer(nf, _halvings(abs(hf - hc) / (3.0 * hf), FINER_TOLERANCE))
                return (f"it is {dev:+.0%} off the one-level-finer grid's {hf:.4g} m ({_nodes(finer)}; estimated "
                        f"discretisation error {est_f:.0%} > {FINER_TOLERANCE:.0%}; the resolution check solved "
                        f"them because {why})"), need
            fc = finer.get("inlet_cells")
            if sol.contact.is_line and cells is not None and cells < INLET_CELLS_HARD and (
                    fc is None or fc < INLET_CELLS_TRIGGER):
                # both grids leave the inlet unresolved: their agreement proves nothing (measured: Barus M = 500,
                # L = 10 on 129 nodes, +30 % off, is 9 % off 257 nodes, itself +19 % off)
                return (f"its inlet's piezoviscous rise, where the film is made, spans {cells:.1f} cells (< "
                        f"{INLET_CELLS_HARD:g}), and {fc if fc is not None else float('nan'):.1f} on the "
                        f"one-level-finer grid ({_nodes(finer)}) it agrees with ({dev:+.0%}): neither resolves it"), \
                    _finer(nx, int(np.ceil(np.log2(INLET_CELLS_TRIGGER / max(cells, 1e-3)))))
            return None, None
        checks["finer_level"] = dict(finer, reason=why)
    if coarse is None:
        return None, None
    hcc, hmc = coarse.get("central_film", np.nan), coarse.get("minimum_film", np.nan)
    failed_finer = "" if finer is None or finer.get("converged") else (
        f"; the one-level-finer solve ({_nodes(finer)}) that would confirm it did not converge")
    if est is None:
        collapsed = coarse.get("collapsed") or not (hcc > 0.0 and hmc > 0.0)
        if not coarse.get("converged", True) or not collapsed:
            return None, None  # no coarser solution, or one too coarse to compare with
        # a collapsed coarser film marks a grid at its resolution limit (multigrid: measured, every such
        # case of the sweep was 8 ... 46 % off; the Newton methods: where the finer grid could not say otherwise)
        if info.get("method") == "multigrid":
            return (f"the one-level-coarser FMG grid ({coarse['nx']} nodes along x) has a collapsed film (minimum "
                    f"{hmc:.3g} m), so this grid is at its resolution limit (central film {hc:.4g} m against "
                    f"{hcc:.4g} m there)"), _finer(nx)
        if finer is not None:
            return (f"the one-level-coarser grid ({_nodes(coarse)}) has a collapsed film (minimum "
                    f"{hmc:.3g} m), so this grid is at its resolution limit{failed_finer}"), _finer(nx)
        return None, None
    if est > COARSE_TOLERANCE:
        # second order: the error falls 4 times per halving of the cells
        return (f"it differs by {abs(hc / hcc - 1):.0%} from the one-level-coarser grid's {hcc:.4g} m (estimated "
                f"discretisation error {est:.0%} > {COARSE_TOLERANCE:.0%}){failed_finer}"), \
            _finer(nx, max(_halvings(est, COARSE_TOLERANCE), 1))
    return None, None
