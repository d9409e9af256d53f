"""Grid and solver options of the EHL solvers.

Part of :mod:`lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError, unknown_choice

@dataclass(frozen=True)
class EHLGrid:
    """Uniform grid: ``nx`` x ``ny`` nodes on x in [x_min, x_max] b_x and
    |y| <= y_max b_y (b_x, b_y: Hertz semi-axes along x and y)."""

    nx: int = 129
    ny: int | None = None
    x_min: float = -4.5
    x_max: float = 1.5
    y_max: float = 3.0

    def __post_init__(self):
        if self.nx < 9:
            raise InputError(f"grid nx = {self.nx!r} must be >= 9")
        if not self.x_min < 0 < self.x_max:
            raise InputError(f"grid x range [{self.x_min}, {self.x_max}] must contain 0")


@dataclass(frozen=True)
class EHLOptions:
    rtol: float = 1e-7
    max_iter: int = 80
    dense_max: int = 1200  # point contacts; line contacts stay dense up to dense_max_line
    dense_max_line: int = 2100
    max_step: float = 2.0
    stencil: int = 1
    gmres_rtol: float = 1e-9
    h_floor: float = 1e-4  # relative to the Hertz film scale b^2/R_x
    consistent_supg: bool = True  # second-order SUPG (recovered Poiseuille flux); False: first order
    active_set_passes: int = 1  # >1: re-solve after moving newly negative nodes to the cavitated set
    max_point_grid: int = 257  # largest point-contact grid (nodes per side) measured to converge
    method: str = "auto"  # "fischer_burmeister", "active_set"; auto: FB for points, active set for lines
    line_search: int = 12  # Armijo halvings of the FB Newton step
    first_order_start: str = "auto"  # "every_grid", "coarsest"; auto: lines every grid, points coarsest
    max_damped: int = 8  # second order from a prolonged start: fall back after this many damped steps
    coarse_rtol: float = 1e-3  # FB Newton tolerance of a start (nested coarse level, first-order stage)
    coarse_max_iter: int = 30  # FB Newton iterations on a nested coarse level (only a start for the next)
    max_stalls: int = 4  # FB Newton: give up after this many stalled line searches (< 1/64 of the step)
    gmres_forcing: float = 1e-3  # largest GMRES rtol of an inexact Newton step (min with |Phi|)
    precond_refresh: int = 20  # refactorise the sparse preconditioner when GMRES needs this many iterations
    # method="multigrid": lubrication.ehl.multigrid.MultigridOptions (None: its defaults)
    multigrid: object = None
    # a-posteriori checks (closed-form film, coarser level; :func:`check_solution`): False logs a
    # WARNING and lists it in info["warnings"], True raises ConvergenceError instead (tests)
    strict: bool = False
    # work budget of one solve_ehl call, in Newton steps on the requested grid (a step on a coarser
    # level counts its share of the nodes), every start and fallback included; None: the default of
    # the contact kind, DEFAULT_MAX_WORK (math.inf: unbounded)
    max_work: float | None = None

    def __post_init__(self):
        for key, value, allowed in (("method", self.method, EHL_METHODS),
                                    ("first_order_start", self.first_order_start, FIRST_ORDER_STARTS)):
            if value not in allowed:
                raise unknown_choice(f"solver.{key}", value, allowed)
        if self.multigrid is not None:
            from .multigrid import MultigridOptions

            if not isinstance(self.multigrid, MultigridOptions):
                raise InputError(f"ehl.multigrid = {self.multigrid!r} must be a MultigridOptions (or None)")


# "multigrid": FAS multigrid of lubrication.ehl.multigrid (point contacts only)
EHL_METHODS = ("auto", "fischer_burmeister", "active_set", "multigrid")
FIRST_ORDER_STARTS = ("auto", "every_grid", "coarsest")
