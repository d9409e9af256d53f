"""Post-processed integrals of FilmSolution against quadrature of the exact slider.

Infinitely wide inclined slider, lower surface at U, upper at rest (mean speed
u_m = U/2).  Exact: constant flux Q = u_m h - h^3 p'/(12 eta), so
p' = 12 eta (u_m h - Q)/h^3 with Q fixed by p(0) = p(L) = 0.  The references
below are scipy quadratures of that ODE, independent of the finite elements.
"""
import numpy as np
import pytest
from scipy.integrate import quad

from lubedyn.lubrication import Film, InclinedSlider, Lubricant
from lubedyn.lubrication import mesh

L, H_IN, H_OUT, U, ETA = 0.01, 3e-6, 1e-6, 1.5, 0.02
GAP = InclinedSlider(H_IN, H_OUT, L)
UM = 0.5 * U


def h(x):
    return GAP([x])


Q = UM * quad(lambda x: h(x) ** -2, 0, L, epsrel=1e-13)[0] / quad(lambda x: h(x) ** -3, 0, L, epsrel=1e-13)[0]


def dpdx(x):
    return 12 * ETA * (UM * h(x) - Q) / h(x) ** 3


P_SCALE = 12 * ETA * UM * L / H_OUT**2  # pressure scale [Pa]


def p_exact(x):
    # absolute tolerance on the pressure scale: p returns to 0 at x = L, where a purely relative
    # tolerance cannot be met (scipy's IntegrationWarning: round-off prevents it)
    return quad(dpdx, 0, x, epsrel=1e-12, epsabs=1e-13 * P_SCALE, limit=200)[0]


@pytest.fixture(scope="module")
def sol():
    return Film(mesh.interval(0, L, 200), GAP, Lubricant.newtonian(ETA), velocity_lower=(U,), element="P2").solve()


def test_load_moment_and_centre_of_pressure(sol):
    W = quad(p_exact, 0, L, epsrel=1e-11)[0]
    Mx = quad(lambda x: x * p_exact(x), 0, L, epsrel=1e-11)[0]
    # P2 on 200 elements: relative discretisation error ~1e-9 (measured < 1e-8)
    assert sol.load == pytest.approx(W, rel=1e-7)
    assert sol.mode_forces["h0"] == pytest.approx(W, rel=1e-7)
    assert sol.centre_of_pressure[0] == pytest.approx(Mx / W, rel=1e-7)
    # moment about the origin of a +z force at x: M_y = -x F_z
    assert sol.moment((0.0, 0.0, 0.0))[1] == pytest.approx(-Mx, rel=1e-7)


def test_friction_on_both_surfaces(sol):
    # shear of the fluid on the lower surface (z = 0) and on the upper (z = h)
    f_lower = quad(lambda x: -0.5 * h(x) * dpdx(x) - ETA * U / h(x), 0, L, epsrel=1e-12)[0]
    f_upper = quad(lambda x: -0.5 * h(x) * dpdx(x) + ETA * U / h(x), 0, L, epsrel=1e-12)[0]
    assert sol.friction_lower[0] == pytest.approx(f_lower, rel=1e-6)
    assert sol.friction_upper[0] == pytest.approx(f_upper, rel=1e-6)
    # the moving lower surface is dragged back; the fixed pad is dragged along
    assert sol.friction_lower[0] < 0 < sol.friction_upper[0]


def test_flow_through_ends(sol):
    # the flux is constant: Q leaves through the right end and enters on the left
    assert sol.flow("right") == pytest.approx(Q, rel=1e-6)
    assert sol.flow("left") == pytest.approx(-Q, rel=1e-6)


def test_minimum_thickness_and_peak(sol):
    assert sol.h_min == pytest.approx(H_OUT, rel=1e-12)
    xs = np.linspace(0, L, 2001)
    ps = np.array([p_exact(x) for x in xs])
    assert sol.p_max == pytest.approx(ps.max(), rel=1e-5)
    assert sol.p_max_location[0] == pytest.approx(xs[np.argmax(ps)], abs=L / 200)
