"""Pressure-dependent lubricants: Newton against independent 1-D solutions.

Velocity convention: the lower surface moves at U, the upper is at rest, so
the mean (entrainment) speed is u_m = U/2.

Independent references
----------------------
* Barus, incompressible: the reduced pressure q = (1 - exp(-alpha p))/alpha
  obeys the *isoviscous* Reynolds equation (grad q = exp(-alpha p) grad p), so
  p = -ln(1 - alpha q)/alpha with q the isoviscous slider pressure, computed
  here by quadrature of the constant-flux form  q' = 12 eta0 (u_m h - Q)/h^3.
* Dowson-Higginson, isoviscous: the mass flux m = rho (u_m h - h^3 p'/(12 eta))
  is constant, so p' = 12 eta (u_m h - m/rho(p))/h^3; m is found by shooting
  (solve_ivp + brentq) so that p(L) = 0.
"""
import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from lubedyn.lubrication import (
    Barus, ConvergenceError, DowsonHigginson, Film, InclinedSlider, Incompressible,
    Lubricant, ConstantViscosity, Roelands, SolverOptions,
)
from lubedyn.lubrication import mesh

L, H_IN, H_OUT, U = 0.02, 2.0e-6, 1.0e-6, 2.0
ETA0 = 0.01
GAP = InclinedSlider(H_IN, H_OUT, L)
UM = U / 2


def isoviscous_q(x):
    """Isoviscous slider pressure by quadrature of the constant-flux equation."""
    h = GAP
    i1 = quad(lambda s: 1 / h([s]) ** 2, 0, L, epsabs=0, epsrel=1e-13)[0]
    i2 = quad(lambda s: 1 / h([s]) ** 3, 0, L, epsabs=0, epsrel=1e-13)[0]
    Q = UM * i1 / i2
    # absolute tolerance on the pressure scale: p returns to 0 at x = L, where a purely relative
    # tolerance cannot be met (scipy's IntegrationWarning: round-off prevents it)
    p_scale = float(12 * ETA0 * UM * L / np.ravel(h([L]))[0] ** 2)
    return np.array([12 * ETA0 * quad(lambda s: (UM * h([s]) - Q) / h([s]) ** 3, 0, xi, epsabs=1e-13 * p_scale / (12 * ETA0),
                                      epsrel=1e-13)[0] for xi in x])


def _solve(lub, n=160, element="P2", **kw):
    film = Film(mesh.interval(0, L, n), GAP, lub, velocity_lower=(U,), element=element, **kw)
    return film.solve()


def test_barus_matches_reduced_pressure_transform():
    q = isoviscous_q(np.linspace(0, L, 201))
    alpha = 0.85 / q.max()  # alpha q_max = 0.85: p_max is 2.2 times the isoviscous peak
    s = _solve(Lubricant(Barus(ETA0, alpha)))
    x = s.basis.doflocs[0]
    p_exact = -np.log1p(-alpha * isoviscous_q(x)) / alpha
    err = np.max(np.abs(s.pressure - p_exact)) / p_exact.max()
    # P2 on 160 elements: the isoviscous discretisation error is ~1e-7; the
    # transform amplifies it by exp(alpha p) ~ 7 at the peak.
    assert err < 2e-5
    assert s.p_max / q.max() > 2.0  # the law really was nonlinear here
    assert 2 <= s.info["iterations"] <= 20


def test_barus_beyond_pole_fails_clearly():
    """With alpha q_max > 1 no solution exists (p -> infinity): a clear error, no NaN field."""
    q = isoviscous_q(np.linspace(0, L, 201))
    alpha = 1.3 / q.max()
    with pytest.raises(ConvergenceError, match="did not converge|non-finite"):
        _solve(Lubricant(Barus(ETA0, alpha)), n=40, options=SolverOptions(max_iter=25))


def _dh_pressure(rho_law, n=400):
    def rhs(x, p, m):
        h = GAP([x[0] if np.ndim(x) else x])
        return 12 * ETA0 * (UM * h - m / rho_law(p)) / h**3

    def end(m):
        sol = solve_ivp(lambda x, p: rhs(x, p, m), (0, L), [0.0], rtol=1e-11, atol=1e-3)
        return sol.y[0, -1]

    m0 = rho_law(0.0) * UM * H_OUT
    m = brentq(end, 0.8 * m0, 2.0 * m0, xtol=1e-18, rtol=1e-14)
    x = np.linspace(0, L, n + 1)
    sol = solve_ivp(lambda x, p: rhs(x, p, m), (0, L), [0.0], t_eval=x, rtol=1e-11, atol=1e-3)
    return x, sol.y[0]


def test_dowson_higginson_against_shooting():
    # scale the speed so that the peak pressure is ~0.5 GPa (density +9 %)
    lub = Lubricant(ConstantViscosity(ETA0), DowsonHigginson(850.0))
    s = _solve(lub)
    x, p_ref = _dh_pressure(lub.density)
    load_ref = np.trapezoid(p_ref, x)
    p_iso = _solve(Lubricant.newtonian(ETA0, 850.0))
    assert abs(s.load / load_ref - 1) < 2e-4  # trapezoid rule on 400 intervals ~ 1e-5
    # compressibility changes the answer well beyond that tolerance
    assert abs(p_iso.load / s.load - 1) > 5e-3
    assert s.info["iterations"] >= 2


def test_roelands_reduces_to_barus_slope():
    """Roelands built from alpha has d(ln eta)/dp = alpha at p = 0, and is below Barus at high p."""
    r = Roelands(0.05, alpha=1.85e-8)
    b = Barus(0.05, 1.85e-8)
    dp = 1.0
    slope = (np.log(r(dp)) - np.log(r(0.0))) / dp
    assert slope == pytest.approx(1.85e-8, rel=1e-6)
    assert r(1e9) < b(1e9)
    # derivative against a centred difference
    p = 3e8
    assert r.derivative(p) == pytest.approx((r(p + 1e3) - r(p - 1e3)) / 2e3, rel=1e-6)
    d = DowsonHigginson(992.0)
    assert d.derivative(p) == pytest.approx((d(p + 1e3) - d(p - 1e3)) / 2e3, rel=1e-6)
    # Dowson-Higginson saturates at rho0 (1 + a/b) = 1.353 rho0
    assert d(1e15) / 992.0 == pytest.approx(1 + 0.6 / 1.7, rel=1e-5)
