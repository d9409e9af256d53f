"""Grid and solver options of the EHL solvers.

Part of :mod:`lubedyn.lubrication.ehl` (the package docstring gives the equations and sources)."""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import InputError, unknown_choice
from .multigrid import MultigridOptions

@dataclass(frozen=True)
class EHLGrid:
    """``nx`` x ``ny`` nodes on x in [x_min, x_max] b_x and |y| <= y_max b_y (b_x, b_y: Hertz
    semi-axes along x and y); uniform unless ``refine`` > 1.

    Graded line grids (line contacts only): with ``refine`` = r > 1 the nodes are equidistant in
    the node density rho(x) = 1 + (r - 1) S(x), S a smooth bump, 1 on ``refine_zone`` = (x_lo, x_hi)
    [b] and falling to 0 over ``refine_width`` [b] either side (S = (tanh((x - x_lo)/w) - tanh((x -
    x_hi)/w))/2): cells inside the zone are r times shorter than outside, and neighbouring cells
    differ by a factor close to 1 (smooth grading keeps P1/SUPG second order).  The node
    positions (:meth:`x_nodes`) depend only on the grid's fields, so the grid with (nx - 1)/2 + 1
    nodes on the same fields is nested in this one to round-off (every second node).  Why
    (the roller maps of the coupling layer): the outlet pressure spike of a line contact is a fraction of a
    cell wide on a uniform 257-node grid, and the traction's low-slip slope and transition slip,
    which the spike carries, jitter by +-10 % between neighbouring loads; 1025 uniform nodes
    resolve it but do not converge at every load."""

    nx: int = 129
    ny: int | None = None
    x_min: float = -4.5
    x_max: float = 1.5
    y_max: float = 3.0
    refine: float = 1.0
    refine_zone: tuple = (-1.2, 1.2)
    refine_width: float = 0.25

    def __post_init__(self):
        if self.nx < 9:
            raise InputError(f"grid nx = {self.nx!r} must be >= 9")
        if not self.x_min < 0 < self.x_max:
            raise InputError(f"grid x range [{self.x_min}, {self.x_max}] must contain 0")
        if not (self.refine >= 1.0 and self.refine <= 100.0):
            raise InputError(f"grid refine = {self.refine!r} must be in [1, 100] (1: uniform)")
        lo, hi = (float(v) for v in self.refine_zone)
        if not lo < hi:
            raise InputError(f"grid refine_zone = {self.refine_zone!r} must be (x_lo, x_hi) with x_lo < x_hi [b]")
        if not self.refine_width > 0:
            raise InputError(f"grid refine_width = {self.refine_width!r} must be > 0 [b]")
        if self.refine != 1.0 and self.ny is not None:
            raise InputError(f"grid refine = {self.refine!r} with ny = {self.ny!r}: graded grids are for line "
                             "contacts (ny = None)")

    @property
    def graded(self) -> bool:
        return self.refine != 1.0

    def x_nodes(self) -> "np.ndarray":
        """Node positions along x [b_x] (nx of them, from x_min to x_max)."""
        import numpy as np
        from scipy.integrate import cumulative_trapezoid

        if not self.graded:
            return np.linspace(self.x_min, self.x_max, self.nx)
        # cumulative node density on a fine sampling (40 samples per transition width, 4096 at least; not
        # depending on nx, so that coarser() grids are nested), inverted by linear interpolation
        lo, hi = (float(v) for v in self.refine_zone)
        w = float(self.refine_width)
        span = self.x_max - self.x_min
        n = int(max(4096, 40 * span / w)) + 1
        s = np.linspace(self.x_min, self.x_max, n)
        rho = 1.0 + (self.refine - 1.0) * 0.5 * (np.tanh((s - lo) / w) - np.tanh((s - hi) / w))
        cum = cumulative_trapezoid(rho, s, initial=0.0)
        x = np.interp(np.linspace(0.0, cum[-1], self.nx), cum, s)
        x[0], x[-1] = self.x_min, self.x_max
        return x

    def coarser(self) -> "EHLGrid":
        """The nested grid with (nx - 1)/2 + 1 nodes (ny likewise), same range and grading."""
        import dataclasses

        return dataclasses.replace(self, nx=(self.nx - 1) // 2 + 1,
                                   ny=None if self.ny is None else (self.ny - 1) // 2 + 1)


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
    max_point_grid: int = 257  # largest point-contact grid (nodes per side) known to converge
    method: str = "auto"  # "fischer_burmeister", "active_set"; auto: FB for points, active set for lines
    line_search: int = 12  # Armijo halvings of the FB Newton step
    first_order_start: str = "auto"  # "every_grid", "coarsest"; auto: lines every grid, points coarsest
    max_damped: int = 8  # second order from a prolonged start: fall back after this many damped steps
    coarse_rtol: float = 1e-3  # FB Newton tolerance of a start (nested coarse level, first-order stage)
    coarse_max_iter: int = 30  # FB Newton iterations on a nested coarse level (only a start for the next)
    max_stalls: int = 4  # FB Newton: give up after this many stalled line searches (< 1/64 of the step)
    gmres_forcing: float = 1e-3  # largest GMRES rtol of an inexact Newton step (min with |Phi|)
    precond_refresh: int = 20  # refactorise the sparse preconditioner when GMRES needs this many iterations
    # method="multigrid": lubedyn.lubrication.ehl.multigrid.MultigridOptions (None: its defaults)
    multigrid: object = None
    # a-posteriori checks (closed-form film, coarser level; :func:`check_solution`): False logs a
    # WARNING and lists it in info["warnings"], True raises ConvergenceError instead (tests)
    strict: bool = False
    # the resolution check's solves (solve.py, _resolution_levels): the one-level-coarser grid, and for line
    # contacts where that differs the one-level-finer one; False: the closed form and the inlet are checked only
    check_resolution: bool = True
    # work budget of one solve_ehl call, in Newton steps on the requested grid (a step on a coarser
    # level counts its share of the nodes), every start and fallback included; None: the default of
    # the contact kind, DEFAULT_MAX_WORK (math.inf: unbounded)
    max_work: float | None = None
    # pseudo-transient continuation of the active-set Newton iteration: the initial pseudo time step in
    # transit times of the domain, its length over u_m (0: off); see newton._pseudo_transient
    pseudo_transient: float = 0.0

    def __post_init__(self):
        if not self.pseudo_transient >= 0:
            raise InputError(f"solver.pseudo_transient = {self.pseudo_transient!r} must be >= 0 (transit times of the domain; "
                             "0: off)")
        for key, value, allowed in (("method", self.method, EHL_METHODS),
                                    ("first_order_start", self.first_order_start, FIRST_ORDER_STARTS)):
            if value not in allowed:
                raise unknown_choice(f"solver.{key}", value, allowed)
        if self.multigrid is not None:
            if not isinstance(self.multigrid, MultigridOptions):
                raise InputError(f"ehl.multigrid = {self.multigrid!r} must be a MultigridOptions (or None)")


# "multigrid": FAS multigrid of lubedyn.lubrication.ehl.multigrid (point contacts only)
EHL_METHODS = ("auto", "fischer_burmeister", "active_set", "multigrid")
FIRST_ORDER_STARTS = ("auto", "every_grid", "coarsest")
