"""The work budget of an EHL solve (units of one Newton iteration on the finest grid).

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

import contextvars

from ..errors import ConvergenceError
from .problem import _Problem

_BUDGET = contextvars.ContextVar("ehl_work_budget", default=None)
# Default EHLOptions.max_work, about 2.5 times the most work any converging contact of the EHL limit
# sweeps needs (Newton steps on the requested grid, all starts and fallbacks; benchmarks/method_limits.py,
# sweeps 1 and 2): points about 40 (M = 1000, L = 10 on 129 x 129, and M = 20 through the fallback
# chain), lines about 140 (M = 20, L = 10 on 1025 nodes through the fallback); the bundled ball and
# roller-slice cases need a third of that.  A line step is cheap (a dense LU), a point step on 129 x 129
# costs seconds (benchmarks/ehl.py times them).
DEFAULT_MAX_WORK = {"point": 100.0, "line": 400.0}


def _grid_nodes(contact, grid):
    if contact.is_line:
        return grid.nx
    return grid.nx * (grid.ny or grid.nx)


def _spend(P: _Problem):
    """Count one Newton step of ``P`` in work units (steps on the requested grid: a step on a grid
    of n nodes costs n/N of one on the N-node grid asked for) and stop the whole solve, every start
    and fallback included, when ``EHLOptions.max_work`` is spent."""
    budget = _BUDGET.get()
    if budget is None:
        return
    budget["spent"] += P.N / budget["nodes"]
    if budget["limit"] is not None and budget["spent"] > budget["limit"]:
        c = P.c
        err = ConvergenceError(
            f"EHL solve at M = {c.moes_M:.4g}, L = {c.moes_L:.4g} stopped: its work budget of "
            f"{budget['limit']:g} Newton steps on the requested grid (EHLOptions.max_work, every start and "
            f"fallback counted) is spent, on a {P.shape[0]}-node level; the Newton methods do not converge "
            "here in that work: " + ("use solver.method = 'multigrid' (point contacts) or a lower load"
                                     if not c.is_line else "use a finer grid or a lower load"))
        err.budget = True
        err.stop = dict(reason="work budget", detail=str(err))
        raise err


# ---------------------------------------------------------------- a-posteriori checks
# Thresholds, from the sweep recorded in tests/test_ehl_limits.py (Moes M = 10 ... 1000 (2000 for
# the multigrid), L = 5, 10, 20; line contacts on 129 ... 1025 nodes with the active set, circular
# contacts on 65 ... 257 nodes with the multigrid):
# - FORMULA_TOLERANCE: converged solutions (1025 line nodes; 257 x 257 multigrid up to M = 200)
#   lie within -5.6 % ... +5.4 % of Moes' line and Nijenbanning's point formula (the fits' own
#   scatter: "a few per cent", "within about 5 %"); under-resolved grids give +86 % (line,
#   257 nodes, M = 1000) and -35 % (multigrid, 129 x 129, M = 1000).  10 %: twice the scatter.
# - COARSE_TOLERANCE: the discretisation error estimated from the one-level-coarser solution,
#   |h_c - h_c,coarse|/((2^2 - 1) h_c) (second order).  Multigrid cases within 5 % of the formula
#   reach 10.8 % (M = 1000, L = 20, 257 x 257, -4.4 %); those more than 10 % off start at 15.5 %
#   (M = 100, L = 10, 65 x 65, -11.6 %).  13 % lies between.
#   The Newton methods' nested levels (points, 65 x 65 from 33 x 33, M = 20 ... 500, L = 5, 10)
#   reach 10.4 % (M = 500, L = 10, +1.7 % off the formula).  A coarse level whose film went to or
#   below zero (or that did not converge) is outside the asymptotic range: no estimate.
# - multigrid only: an FMG coarser level whose film went to zero or below marks a grid at its
#   resolution limit: every such case of the sweep was 8 % ... 46 % off the formula (M = 1000,
#   L = 10, 257 x 257: -8.4 %).  (The Newton methods' floored film is not such a sign: M = 500,
#   L = 10 on 65 x 65 is +1.7 % off with a 33 x 33 level at -6.8e-8 m.)
