"""lubedyn.lubrication: lubricant films by finite elements (scikit-fem).

=================  ==========================================================
module             responsibility
=================  ==========================================================
``errors``         ``InputError`` (exit 2), ``ConvergenceError`` (exit 1)
``laws``           the laws written once for films and dynamics (also
                   imported by ``dynamics``): ``contact`` (Hertz point and
                   line, reduced modulus, stiffness), ``bearing`` (geometry,
                   kinematics, Stribeck, load distribution), ``lubricant``
                   (viscosity, density, d/dp), ``film`` (closed-form EHL film
                   thickness: Hamrock-Dowson, Nijenbanning, Dowson-Toyoda,
                   Pan-Hamrock, Moes), ``collision`` (ball-ball), ``traction``
``gaps``           film thickness h(x) of sliders, journals, spheres,
                   cylinders, ellipsoids, pockets; rigid-body modes
``mesh``           1-D, rectangle (periodic in x), disk (straight or curved)
                   meshes with named boundaries; unwrapping of periodic ones
``reynolds``       the generalised Reynolds equation: forms, Newton and
                   complementarity (Reynolds, JFO) solvers, film K and C,
                   ``FilmSolution`` (loads, moments, friction, flow, VTK,
                   plots)
``closed_form``    analytic film results used for verification
``elastic``        half-space deflection by FFT of exact influence
                   coefficients (point and line contacts)
``ehl``            isothermal EHL line and point contacts (a package: contact,
                   options, problem, assembly, newton, multigrid, solve,
                   budget, checks, solution, coefficients): Reynolds FEM + FFT
                   elasticity + load balance, Newton or FAS multigrid
``vtu``            ``write_vtu``: the atomic ``.vtu`` writer of film and EHL
                   results
=================  ==========================================================

Nothing here imports ``lubedyn.dynamics``; ``lubedyn`` itself (the coupling layer) joins the two.
"""
import importlib

from .errors import ConvergenceError, InputError, LubedynError

# The solvers load on first use (PEP 562), so that ``import lubedyn.lubrication.laws`` -- the ground floor that
# :mod:`dynamics` imports -- does not import scikit-fem.
_LAZY = {
    **dict.fromkeys(("CylinderPlane", "EllipsoidPlane", "FunctionGap", "Gap", "InclinedSlider", "JournalBearing",
                     "PocketedSlider", "SpherePlane", "SphereSphere", "StepSlider"), ".gaps"),
    **dict.fromkeys(("Barus", "ConstantViscosity", "DowsonHigginson", "HerschelBulkleyFlow", "Incompressible",
                     "Lubricant", "Roelands"),
                    ".laws.lubricant"),
    **dict.fromkeys(("Cavitation", "Film", "FilmSolution", "SolverOptions", "film_coefficients", "solve",
                     "solve_nested"), ".reynolds"),
}


def __getattr__(name):
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "Barus", "Cavitation", "ConstantViscosity", "ConvergenceError", "CylinderPlane",
    "DowsonHigginson", "EllipsoidPlane", "Film", "FilmSolution", "FunctionGap", "Gap", "HerschelBulkleyFlow",
    "InclinedSlider", "Incompressible", "InputError", "JournalBearing", "LubedynError",
    "Lubricant", "PocketedSlider", "Roelands", "SolverOptions", "SpherePlane",
    "SphereSphere", "StepSlider", "film_coefficients", "solve", "solve_nested",
]
