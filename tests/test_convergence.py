"""Measured convergence orders of the Reynolds solver (method of manufactured solutions).

Dimensionless unit square (eta = 1, rho = 1: the orders do not depend on
units).  Manufactured pressure and a variable gap::

    p = sin(pi x) sin(pi y)            (zero on the boundary: default Dirichlet)
    h = 1 + 0.4 x + 0.3 y^2            (FunctionGap)
    u_m = (1, 0.5)                     (both surfaces at (1, 0.5): u_m = (U_l + U_u)/2)

The solver's equation div(h^3/(12 eta) grad p) = div(h u_m) + dh/dt holds for
this p if the squeeze term carries the source

    dh/dt = h^3/(12 eta) lap p + h^2/(4 eta) grad h . grad p - u_m . grad h,

passed as a callable ``squeeze`` (the solver's residual contains
int rho theta dh/dt v, so this is exactly a volume source).  The L2 error is
integrated with a 10th-order quadrature and its order fitted by np.polyfit
over four meshes (n = 4, 8, 16, 32 cells per side).
"""
import numpy as np
import pytest
import skfem

from lubedyn.lubrication import Film, FunctionGap, Lubricant
from lubedyn.lubrication import mesh as meshes

ETA = 1.0
UM = np.array([1.0, 0.5])


def p_exact(x):
    return np.sin(np.pi * x[0]) * np.sin(np.pi * x[1])


def gap(x):
    return 1.0 + 0.4 * x[0] + 0.3 * x[1] ** 2


def source(x):
    """dh/dt that makes p_exact the solution (derivatives by hand)."""
    h = gap(x)
    hx, hy = 0.4 * np.ones_like(x[0]), 0.6 * x[1]
    px = np.pi * np.cos(np.pi * x[0]) * np.sin(np.pi * x[1])
    py = np.pi * np.sin(np.pi * x[0]) * np.cos(np.pi * x[1])
    lap = -2.0 * np.pi**2 * p_exact(x)
    div_flux = h**3 / (12.0 * ETA) * lap + h**2 / (4.0 * ETA) * (hx * px + hy * py)
    return div_flux - (UM[0] * hx + UM[1] * hy)


def l2_error(n, cell, element):
    grid = np.linspace(0.0, 1.0, n + 1)
    m = meshes.rectangle(grid, grid, cell=cell)
    film = Film(m, FunctionGap(gap), Lubricant.newtonian(ETA), velocity_lower=tuple(UM),
                velocity_upper=tuple(UM), squeeze=source, element=element)
    sol = film.solve()
    fine = skfem.Basis(m, sol.basis.elem, intorder=10)
    ph = fine.interpolate(sol.pressure)
    err = skfem.Functional(lambda w: (w["ph"] - p_exact(w.x)) ** 2).assemble(fine, ph=ph)
    return np.sqrt(err)


@pytest.mark.parametrize("cell", ["tri", "quad"])
@pytest.mark.parametrize("element, expected", [("P1", 2.0), ("P2", 3.0)])
def test_manufactured_solution_l2_order(cell, element, expected):
    """L2 order 2 for P1 and 3 for P2, on triangles and quadrilaterals.

    Measured orders: P1 1.96 (tri), 2.00 (quad); P2 2.99 (tri), 2.99 (quad);
    errors at n = 32: 1.3e-3, 4.5e-4, 8.6e-6, 3.8e-6 (|p|max = 1).
    Asserted > 1.9 (P1) and > 2.85 (P2): the coarsest mesh (n = 4) is not
    quite asymptotic for P1 triangles, which costs 0.04 in the fitted slope.
    """
    ns = np.array([4, 8, 16, 32])
    errors = np.array([l2_error(n, cell, element) for n in ns])
    order = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert order > expected - (0.1 if element == "P1" else 0.15)
    assert order < expected + 0.3  # not a lucky superconvergence hiding a wrong source
    assert errors[-1] < (2e-3 if element == "P1" else 2e-5)


# --------------------------------------------------------------------------
# P2 on the curved (isoparametric) disk: the squeeze film keeps its order

def squeeze_load_error(refinements, order):
    """Reynolds' sphere-plane squeeze film on a disk of radius a, ambient at
    r = a: F = 6 pi eta R^2 (-v)/h0 (1 - h0/h_e)^2, h_e = h0 + a^2/(2R)."""
    from lubedyn.lubrication import SpherePlane

    radius, h0, a, eta, v = 10e-3, 10e-6, 1e-3, 0.01, -1e-3
    h_edge = h0 + a * a / (2 * radius)
    exact = 6 * np.pi * eta * radius**2 * (-v) / h0 * (1 - h0 / h_edge) ** 2
    film = Film(meshes.disk(a, refinements, order=order), SpherePlane(radius, h0), Lubricant.newtonian(eta),
                squeeze=v, element="P2")
    return abs(film.solve().mode_forces["h0"] - exact) / exact


def test_p2_squeeze_load_order_on_curved_disk():
    """P2 load error on ``mesh.disk(order=2)`` (MeshTri2, boundary midpoints
    on the circle) against ``order=1`` (straight-sided), refinements 2..5
    (h halves each time).  Measured: curved 9.7e-3, 6.5e-4, 4.2e-5, 2.7e-6,
    order 3.94 (the load is a superconvergent functional); straight 2.0e-2,
    2.9e-3, 5.9e-4, 1.4e-4, order 2.38 and falling to 2: the polygon sits
    O(h^2) inside the circle."""
    ks = np.array([2, 3, 4, 5])
    curved = np.array([squeeze_load_error(k, 2) for k in ks])
    straight = np.array([squeeze_load_error(k, 1) for k in ks])
    order_curved = -np.polyfit(ks * np.log(2.0), np.log(curved), 1)[0]
    order_straight = -np.polyfit(ks * np.log(2.0), np.log(straight), 1)[0]
    assert order_curved > 3.7
    assert order_straight < 2.6
    assert curved[-1] < 5e-6 and curved[-1] < straight[-1] / 20
