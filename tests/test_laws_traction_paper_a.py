"""Paper A's raceway and flange traction (lubedyn.lubrication.laws.traction) against independent values: eq. 12
against a scipy quadrature of the gap integral it stands for and its wide-strip Couette limit, the
limited Herschel-Bulkley law against closed forms in its Newtonian/Barus limits (modified Bessel and
Struve functions, elementary integrals) and against adaptive quadrature with the limit active, its bound,
oddness in slip, and a hand estimate of the unbounded eq. 26 (about 5e13 Pa at 0.43 GPa,
5e5 1/s)."""
import math

import pytest
from scipy.integrate import quad
from scipy.special import iv, modstruve

from lubedyn.lubrication.laws import grease as G
from lubedyn.lubrication.laws import traction as T

ALPHA = 4.662e-8


def _k(fn, compiled):
    return fn if compiled else fn.py_func


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("b, R, h0", [(1.1e-4, 9.41e-3, 5.4e-6), (1.26e-4, 11.93e-3, 2e-6), (3e-6, 1e-2, 1e-6),
                                      (2e-3, 1e-2, 1e-7)])
def test_eq12_is_the_gap_integral_it_stands_for(compiled, b, R, h0):
    """f' = eta v_s int_{-b}^{b} 2 (h - h0)/h^2 dx with h = h0 + 2 x^2/R' (quadrature, 1e-10), for z from
    0.07 to 9e2 (the series branch included); linear and odd in slip."""
    law = _k(T.paper_raceway_traction, compiled)
    eta, vs = 0.1, 0.37
    gap = lambda x: h0 + 2 * x * x / R  # noqa: E731
    c = math.sqrt(R * h0 / 2)
    integral, _ = quad(lambda x: 2 * (gap(x) - h0) / gap(x) ** 2, -b, b, points=[-c, 0.0, c] if c < b else None,
                       epsabs=0.0, epsrel=1e-13, limit=400)
    assert law(vs, eta, R, h0, b) == pytest.approx(eta * vs * integral, rel=1e-10)
    assert law(-vs, eta, R, h0, b) == -law(vs, eta, R, h0, b)
    assert law(3 * vs, eta, R, h0, b) == pytest.approx(3 * law(vs, eta, R, h0, b), rel=1e-14)


def test_eq12_wide_strip_is_couette():
    """b >> (R' h0)^(1/2): eps -> 1 - 4/(pi z) and f' -> eta v_s int dx/h = eta v_s pi (R'/(2 h0))^(1/2)
    (z = 4.5e6 here: 3e-7 short of the limit)."""
    R, h0 = 1e-2, 1e-7
    assert T.paper_raceway_traction(1.0, 1.0, R, h0, 100.0) == pytest.approx(math.pi * math.sqrt(R / (2 * h0)),
                                                                          rel=1e-6)


def test_eq13_series_joins_the_closed_form():
    """eps's series (z < 1e-2) and closed form agree at the switch (the closed form still has 9 digits)."""
    R, h0 = 1e-2, 1e-6
    b = 1e-2 * math.sqrt(R * h0 / 2)
    below, above = T.paper_epsilon(b * (1 - 1e-12), R, h0), T.paper_epsilon(b * (1 + 1e-12), R, h0)
    assert below == pytest.approx(above, rel=1e-8)
    assert below == pytest.approx(2 / math.pi * (2 / 3 * 1e-6 - 4 / 5 * 1e-10), rel=1e-8)  # (2/3) z^3 - (4/5) z^5


def _newtonian(eta, alpha=0.0):
    return T.rheology(G.Grease(0.0, eta, 1.0, alpha))


@pytest.mark.parametrize("compiled", [True, False])
def test_limited_law_newtonian_and_barus_limits(compiled):
    """No yield, n = 1, no limit.  alpha = 0: strip 2 b eta D, ellipse pi a b eta D.  Barus
    (a = alpha p0): strip b eta D (pi (I1(a) + L1(a)) + 2), ellipse 2 pi a b eta D (e^a (a - 1) + 1)/a^2
    (int_0^pi e^(a sin t) sin t dt and int_0^1 e^(a s) s ds in closed form); 32-point Gauss: 1e-12."""
    strip, ell = _k(T.limited_strip_traction, compiled), _k(T.limited_ellipse_traction, compiled)
    eta, vs, h, a_, b_ = 0.1, 0.5, 1e-6, 9e-4, 8e-4
    D = vs / h
    assert strip(vs, h, b_, 5e8, _newtonian(eta)) == pytest.approx(2 * b_ * eta * D, rel=1e-13)
    assert ell(vs, h, a_, b_, 5e8, _newtonian(eta)) == pytest.approx(math.pi * a_ * b_ * eta * D, rel=1e-13)
    for p0 in (1e8, 4.3e8):
        a = ALPHA * p0
        line = b_ * eta * D * (math.pi * (iv(1, a) + modstruve(1, a)) + 2)
        assert strip(vs, h, b_, p0, _newtonian(eta, ALPHA)) == pytest.approx(line, rel=1e-12)
        ellipse = 2 * math.pi * a_ * b_ * eta * D * (math.exp(a) * (a - 1) + 1) / a**2
        assert ell(vs, h, a_, b_, p0, _newtonian(eta, ALPHA)) == pytest.approx(ellipse, rel=1e-12)


# grease of paper A (polyurea, 30 C) with a limit active over part of the contact
POLYUREA = G.Grease(351.8, 8.44, 0.7196, ALPHA)


def _quad_strip(vs, h, b, p0, rheo):
    f = lambda x: T.limited_stress.py_func(vs / h, p0 * math.sqrt(max(1 - (x / b) ** 2, 0.0)), rheo)  # noqa: E731
    return quad(f, -b, b, epsabs=0.0, epsrel=1e-12, limit=500)[0]


def _quad_ellipse(vs, h, a, b, p0, rheo):
    f = lambda r: T.limited_stress.py_func(vs / h, p0 * math.sqrt(max(1 - r * r, 0.0)), rheo) * r  # noqa: E731
    return 2 * math.pi * a * b * quad(f, 0.0, 1.0, epsabs=0.0, epsrel=1e-12, limit=500)[0]


@pytest.mark.parametrize("vs", [1e-6, 1e-4, 1e-2, 4.7])
@pytest.mark.parametrize("tau_l0, gamma", [(1e6, 0.07), (2e7, 0.0), (1e5, 0.1)])
def test_limited_law_against_adaptive_quadrature(vs, tau_l0, gamma):
    """The fixed 32-point rules against scipy's adaptive quad of int tau dx and int tau dA over the raw
    Hertz pressure (x and r, not the substituted variables; quad in theta agrees with quad in x to 1e-15):
    within 5e-4 for the strip and 1e-5 for the ellipse where the Bair-Winer limit switches on inside the
    contact (measured worst over tau_L0 1e5-5e7 Pa, gamma_L 0-0.1, slip 1e-8-4.7 m/s: 3.0e-4 and 1.4e-6;
    the knee of the integrand where tau_HB reaches tau_L limits the fixed rule)."""
    rheo = T.rheology(POLYUREA, tau_l0, gamma, 1.0)
    h, b, p0 = 5e-6, 1.1e-4, 6.6e8
    assert T.limited_strip_traction(vs, h, b, p0, rheo) == pytest.approx(_quad_strip(vs, h, b, p0, rheo), rel=5e-4)
    a_, b_, p0f = 9.05e-4, 7.84e-4, 4.0e8
    assert T.limited_ellipse_traction(vs, h, a_, b_, p0f, rheo) == pytest.approx(
        _quad_ellipse(vs, h, a_, b_, p0f, rheo), rel=1e-5)


def test_limited_law_is_bounded_and_odd():
    """|tau| < tau_L0 + gamma_L p: the strip's traction stays below 2 b tau_L0 + gamma_L W' (W' = pi b p0/2)
    and tends to it at large slip; odd in slip."""
    rheo = T.rheology(POLYUREA, 1e6, 0.07, 1.0)
    h, b, p0 = 5e-6, 1.1e-4, 6.6e8
    bound = 2 * b * 1e6 + 0.07 * math.pi * b * p0 / 2
    for vs in (1e-8, 1e-3, 1.0, 30.0):
        f = T.limited_strip_traction(vs, h, b, p0, rheo)
        assert 0 < f < bound
        assert T.limited_strip_traction(-vs, h, b, p0, rheo) == -f
    assert T.limited_strip_traction(30.0, h, b, p0, rheo) == pytest.approx(bound, rel=1e-3)


def test_eq26_as_printed_is_unbounded():
    """No limit (tau_L0 = inf): at p = 0.43 GPa and D = 5e5 1/s the polyurea stress is about 5e13 Pa."""
    tau = T.limited_stress(5e5, 4.3e8, T.rheology(POLYUREA))
    assert tau == pytest.approx(351.8 + 8.44 * math.exp(ALPHA * 4.3e8) * 5e5**0.7196, rel=1e-14)
    assert 4e13 < tau < 6e13


def test_elastic_slope_is_the_maxwell_strain_integral():
    """The elastic limit's slope 2 G b^2/(u_e h): an element strained by v_s (x + b)/(u_e h) at x carries
    tau = G times that; its integral over [-b, b] by quadrature (a paper-A cone slice: b 0.2 mm, h 5 um,
    u_e 10 m/s, G 1 GPa) agrees to 1e-12; G = inf gives inf (no compliance)."""
    g, b, ue, h, vs = 1e9, 2e-4, 10.0, 5e-6, 1e-3
    direct, _ = quad(lambda x: g * vs * (x + b) / (ue * h), -b, b, epsabs=0.0, epsrel=1e-13)
    assert T.elastic_strip_slope(g, b, ue, h) * vs == pytest.approx(direct, rel=1e-12)
    assert T.elastic_strip_slope(math.inf, b, ue, h) == math.inf


@pytest.mark.parametrize("compiled", [False, True])
def test_elastic_limited_joins_the_elastic_and_viscous_limits(compiled):
    """F = F_v tanh(k v/F_v): k v at small slip (the elastic film: 1e-6 relative when k v = 1e-3 F_v),
    F_v at large slip (1e-9 when k v = 20 F_v), never above either, monotone in v for a fixed F_v; k = inf
    returns F_v exactly and F_v = 0 gives 0."""
    f = T.elastic_limited if compiled else T.elastic_limited.py_func
    fv, k = 200.0, 3.4e4
    v = 1e-3 * fv / k
    assert f(fv, k, v) == pytest.approx(k * v, rel=1e-6)
    v = 20 * fv / k
    assert f(fv, k, v) == pytest.approx(fv, rel=1e-9)
    vs = [10.0**e for e in range(-9, 1)]
    out = [f(fv, k, x) for x in vs]
    assert all(o <= min(fv, k * x) * (1 + 1e-15) for o, x in zip(out, vs))
    assert all(b > a for a, b in zip(out, out[1:]) if b < fv * (1 - 1e-12))
    assert f(fv, math.inf, 1e-12) == fv and f(0.0, k, 1.0) == 0.0
