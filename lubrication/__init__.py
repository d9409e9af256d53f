"""lubrication: lubricant films by finite elements (scikit-fem).

=================  ==========================================================
module             responsibility
=================  ==========================================================
``errors``         ``InputError`` (exit 2), ``ConvergenceError`` (exit 1)
``lubricant``      viscosity (constant, Barus, Roelands) and density
                   (incompressible, Dowson-Higginson) laws with d/dp
``gaps``           film thickness h(x) of sliders, journals, spheres,
                   cylinders, ellipsoids, pockets; rigid-body modes
``mesh``           1-D, rectangle (periodic in x), disk (straight or curved)
                   meshes with named boundaries; unwrapping of periodic ones
``reynolds``       the generalised Reynolds equation: forms, Newton and
                   complementarity (Reynolds, JFO) solvers, film K and C
``solution``       ``FilmSolution``: loads, moments, friction, flow, VTK, plots
``closed_form``    analytic film results used for verification
``hertz``          Hertz point (exact elliptic integrals, Hamrock-Brewe) and
                   line contact
``elastic``        half-space deflection by FFT of exact influence
                   coefficients (point and line contacts)
``ehl``            isothermal EHL line and point contacts: Reynolds FEM +
                   FFT elasticity + load balance, Newton, traction laws
``ehl_multigrid``  FAS multigrid EHL point-contact solver (Venner & Lubrecht;
                   numba line relaxation, FFT deflection)
``film_formulas``  closed-form EHL film thickness (Hamrock-Dowson,
                   Nijenbanning, Dowson-Toyoda, Pan-Hamrock, Moes)
=================  ==========================================================

Nothing here imports ``dynamics``; ``coupling`` joins the two.
"""
from .errors import ConvergenceError, InputError, LubedynError
from .gaps import (
    CylinderPlane,
    EllipsoidPlane,
    FunctionGap,
    Gap,
    InclinedSlider,
    JournalBearing,
    PocketedSlider,
    SpherePlane,
    SphereSphere,
    StepSlider,
)
from .lubricant import Barus, ConstantViscosity, DowsonHigginson, Incompressible, Lubricant, Roelands
from .reynolds import Cavitation, Film, SolverOptions, film_coefficients, solve, solve_nested
from .solution import FilmSolution

__all__ = [
    "Barus", "Cavitation", "ConstantViscosity", "ConvergenceError", "CylinderPlane",
    "DowsonHigginson", "EllipsoidPlane", "Film", "FilmSolution", "FunctionGap", "Gap",
    "InclinedSlider", "Incompressible", "InputError", "JournalBearing", "LubedynError",
    "Lubricant", "PocketedSlider", "Roelands", "SolverOptions", "SpherePlane",
    "SphereSphere", "StepSlider", "film_coefficients", "solve", "solve_nested",
]
