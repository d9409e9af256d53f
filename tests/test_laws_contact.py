"""The contact laws written once (lubedyn.lubrication.laws.contact) against their published sources and an
independent evaluation: Johnson (1985) for the circle and the line, a quadrature of Boussinesq's
integral for the approach of the elliptical contact, Hamrock & Brewe's (1983) stated accuracy for
their fits, and the definitions of the contact stiffness and of springs in series."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import contact as L

E_STAR = L.reduced_modulus(207e9, 0.29, 208e9, 0.3)


def test_reduced_modulus_of_steel_on_steel():
    """1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson 1985, eq. 4.22): 207/208 GPa, 0.29/0.3."""
    assert E_STAR == pytest.approx(1.0 / ((1 - 0.29**2) / 207e9 + (1 - 0.3**2) / 208e9), rel=1e-15)
    assert L.reduced_modulus(210e9, 0.3, 210e9, 0.3) == pytest.approx(210e9 / (2 * (1 - 0.09)), rel=1e-15)


@pytest.mark.parametrize("load", [1.0, 250.0, 5000.0])
def test_circular_contact_is_johnsons(load):
    """R_a = R_b = R: a^3 = 3 W R/(4 E*), delta = a^2/R, p0 = 3 W/(2 pi a^2) (Johnson 1985, eqs. 4.22-4.23)."""
    R = 3e-3
    hp = L.point_contact(load, R, R, E_STAR)
    a = (3 * load * R / (4 * E_STAR)) ** (1 / 3)
    assert hp.a == pytest.approx(a, rel=1e-14) and hp.b == pytest.approx(a, rel=1e-14)
    assert hp.approach == pytest.approx(a * a / R, rel=1e-14)
    assert hp.p0 == pytest.approx(3 * load / (2 * math.pi * a * a), rel=1e-14)
    assert L.hertz_constant(R, R, E_STAR) == pytest.approx(4 / 3 * E_STAR * math.sqrt(R), rel=1e-13)


def _boussinesq_approach(hp):
    """Approach of the two surfaces at the centre of an elliptical Hertz pressure, by quadrature of
    Boussinesq's integral u(0) = (1/(pi E*)) int p/r dA.  In polar coordinates about the centre the
    radial integral of p0 sqrt(1 - rho^2/rho_max^2) is p0 rho_max pi/4, with rho_max(theta) =
    (cos^2/a^2 + sin^2/b^2)^-1/2, so u(0) = p0/(4 E*) int_0^2pi rho_max d theta: no elliptic integral."""
    def rho_max(t):
        return 1.0 / math.sqrt((math.cos(t) / hp.a) ** 2 + (math.sin(t) / hp.b) ** 2)

    integral, _ = quad(rho_max, 0.0, 2 * math.pi, epsabs=0.0, epsrel=1e-13, limit=200)
    return hp.p0 / (4 * E_STAR) * integral


@pytest.mark.parametrize("ratio", [1.0 + 1e-7, 1.5, 7.6, 25.0, 300.0])
def test_elliptical_approach_against_boussinesq_quadrature(ratio):
    """The exact method's approach equals Boussinesq's integral of its own pressure (1e-10), and the
    pressure carries the load: W = (2/3) pi a b p0."""
    Rb = 1e-3
    hp = L.point_contact(100.0, ratio * Rb, Rb, E_STAR)
    assert hp.a >= hp.b
    assert _boussinesq_approach(hp) == pytest.approx(hp.approach, rel=1e-10)
    assert 2 / 3 * math.pi * hp.a * hp.b * hp.p0 == pytest.approx(100.0, rel=1e-14)


@pytest.mark.parametrize("ratio", [1.5, 5.0, 7.6, 20.0, 30.0])
def test_hamrock_brewe_within_their_stated_accuracy(ratio):
    """Hamrock & Brewe (1983) fit k = a/b, E and F to within a few per cent of the exact solution:
    over the ball-bearing range R_a/R_b <= 30, approach, semi-axes and peak pressure within 3 %."""
    Rb = 1e-3
    exact = L.point_contact(300.0, ratio * Rb, Rb, E_STAR)
    fit = L.point_contact(300.0, ratio * Rb, Rb, E_STAR, method="hamrock_brewe")
    for name in ("a", "b", "approach", "p0"):
        assert getattr(fit, name) == pytest.approx(getattr(exact, name), rel=0.03), name
    k, _, _ = L.hamrock_brewe(ratio * Rb, Rb)
    assert L.hamrock_brewe_radius_ratio(k) == pytest.approx(ratio, rel=1e-13)


def test_hamrock_brewe_leaves_3_percent_at_very_elongated_contacts():
    """Where the fits stop: at R_a/R_b = 100 the major semi-axis errs 4.2 % (measured), beyond 3 %."""
    exact = L.point_contact(300.0, 0.1, 1e-3, E_STAR)
    fit = L.point_contact(300.0, 0.1, 1e-3, E_STAR, method="hamrock_brewe")
    assert 0.03 < fit.a / exact.a - 1 < 0.06


@pytest.mark.parametrize("method", L.METHODS)
def test_stiffness_constant_gives_the_approach_at_every_load(method):
    """Q = K delta^1.5 with K from Q = 1 N (the approach grows as Q^(2/3) in Hertz's theory)."""
    K = L.hertz_constant(9e-3, 2e-3, E_STAR, method)
    for load in (0.3, 10.0, 3000.0):
        delta = L.point_contact(load, 9e-3, 2e-3, E_STAR, method).approach
        assert load / delta**1.5 == pytest.approx(K, rel=1e-12)


def test_series_constant_is_two_hertz_springs():
    """Two contacts carrying the same load in series: the approaches add."""
    K1, K2 = 3.0e10, 2.0e10
    Kn = L.series_constant(K1, K2)
    Q = 250.0
    assert (Q / Kn) ** (2 / 3) == pytest.approx((Q / K1) ** (2 / 3) + (Q / K2) ** (2 / 3), rel=1e-13)


def test_line_contact_is_johnsons():
    """b = sqrt(4 W' R/(pi E*)), p0 = 2 W'/(pi b) (Johnson 1985, eq. 4.45); the elliptical pressure
    integrates to W'."""
    hl = L.line_contact(1e6, 8e-3, E_STAR)
    assert hl.b == pytest.approx(math.sqrt(4 * 1e6 * 8e-3 / (math.pi * E_STAR)), rel=1e-15)
    x = np.linspace(-hl.b, hl.b, 200001)
    p = hl.p0 * np.sqrt(np.clip(1 - (x / hl.b) ** 2, 0, None))
    assert np.trapezoid(p, x) == pytest.approx(1e6, rel=1e-6)


def test_hunt_crossley_alpha():
    """alpha = 3 (1 - e)/(2 v) (Hunt & Crossley 1975)."""
    assert L.hunt_crossley_alpha(0.9, 0.5) == pytest.approx(0.3, rel=1e-14)


@pytest.mark.parametrize("call, match", [
    (lambda: L.point_contact(1.0, 1e-3, 1e-3, E_STAR, "hamrok"), "hertz method = 'hamrok'.*did you mean 'hamrock_brewe'"),
    (lambda: L.point_contact(-1.0, 1e-3, 1e-3, E_STAR), r"contact load \[N\] = -1.0 must be a finite number > 0"),
    (lambda: L.point_contact(1.0, 1e-3, float("nan"), E_STAR), r"relative radius R_b \[m\] = nan"),
    (lambda: L.reduced_modulus(2e11, 0.6, 2e11, 0.3), r"Poisson ratio nu1 = 0.6 must lie in \(-1, 0.5\)"),
    (lambda: L.ellipticity_parameter(0.5), "radius ratio R_a/R_b = 0.5 must be >= 1"),
    (lambda: L.relative_radii([1.0, -2.0], [1.0, 1.0]), "must not conform"),
])
def test_bad_input_is_one_line(call, match):
    with pytest.raises(InputError, match=match) as info:
        call()
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("ratio", [1.00001, 1.01, 1.05, 1.5, 4.0, 10.0])
def test_ellipse_radius_ratio_inverts_the_ellipticity(ratio):
    """Johnson (1985) eqs. 4.30-4.32: R_a/R_b = (E/(1 - m) - K)/(K - E) and its inverse."""
    m = L.ellipticity_parameter(ratio)
    assert L.ellipse_radius_ratio(m) == pytest.approx(ratio, rel=1e-9)
