"""Bearing kinematics and load sharing (lubedyn.lubrication.laws.bearing) against what they must satisfy.

The 6206 of paper B: D = 9.525 mm, d_m = 46.005 mm, r_i = 4.905 mm,
r_o = 4.953 mm, Z = 14, E* = 113.6 GPa.
"""
import math

import numpy as np
import pytest

from lubedyn.lubrication.laws import bearing
from lubedyn.lubrication.laws.contact import reduced_modulus

D, DM, Z = 9.525e-3, 46.005e-3, 14
RI, RO = 4.905e-3, 4.953e-3  # groove radii [m]
E_STAR = reduced_modulus(207e9, 0.29, 208e9, 0.3)
K_N = bearing.deflection_constant(D, DM, RI, RO, 0.0, E_STAR)


def test_quasi_static_radial_load_recovers_stribecks_constant():
    """Zero clearance, radial load only: Z Q_max / F_r = 4.37 (Stribeck's
    value for point contacts, Harris & Kotzalas sec. 7.4); measured 4.373
    with 14 balls.  With clearance the constant grows (the classical 5)."""
    Q, beta, delta_a, _ = bearing.ball_load_distribution(2000.0, 0.0, Z, D, RI, RO, K_N)
    assert Z * Q.max() / 2000.0 == pytest.approx(4.37, rel=2e-3)
    assert np.all(beta == 0.0) and delta_a == 0.0
    Q, _, _, _ = bearing.ball_load_distribution(2000.0, 0.0, Z, D, RI, RO, K_N, clearance=20e-6)
    assert 4.9 < Z * Q.max() / 2000.0 < 5.5  # measured 5.17


def test_quasi_static_axial_load_is_the_thrust_solution():
    """Axial load only: every ball at the thrust contact angle, carrying F_a/(Z sin a)."""
    Q, beta, _, _ = bearing.ball_load_distribution(0.0, 200.0, Z, D, RI, RO, K_N)
    alpha = bearing.thrust_contact_angle(200.0, Z, D, RI, RO, K_N)
    assert math.degrees(alpha) == pytest.approx(9.027, abs=1e-3)
    np.testing.assert_allclose(beta, alpha, rtol=1e-12)
    np.testing.assert_allclose(Q, 200.0 / (Z * math.sin(alpha)), rtol=1e-9)


def test_combined_load_balance_and_stribeck_upper_estimate():
    """The equilibrium carries F_r and F_a; the Stribeck estimate with the
    axial share (723 N) lies above the equilibrium's most loaded ball (611 N)."""
    Fr, Fa = 2000.0, 200.0
    Q, beta, _, _ = bearing.ball_load_distribution(Fr, Fa, Z, D, RI, RO, K_N)
    psi = 2 * np.pi * np.arange(Z) / Z
    assert np.sum(Q * np.cos(beta) * np.cos(psi)) == pytest.approx(Fr, rel=1e-9)
    assert np.sum(Q * np.sin(beta)) == pytest.approx(Fa, rel=1e-9)
    alpha = bearing.thrust_contact_angle(Fa, Z, D, RI, RO, K_N)
    stribeck = bearing.stribeck_max_load(Fr, Fa, Z, alpha, 4.37)
    assert Q.max() < stribeck
    assert Q.max() == pytest.approx(610.8, rel=1e-3) and stribeck == pytest.approx(723.2, rel=1e-3)


@pytest.mark.parametrize("omega_inner, omega_outer", [(1000.0, 0.0), (0.0, 1000.0), (300.0, -200.0)])
def test_rolling_speed_is_the_same_at_both_races(omega_inner, omega_outer):
    """No slip: in the cage frame the inner race surface, the outer race
    surface and the ball surface all move at u_m."""
    alpha = math.radians(9.0)
    gamma = D * math.cos(alpha) / DM
    wc = bearing.cage_speed(D, DM, alpha, omega_inner, omega_outer)
    inner = abs(omega_inner - wc) * DM * (1 - gamma) / 2
    outer = abs(wc - omega_outer) * DM * (1 + gamma) / 2
    um = bearing.entrainment_speed(D, DM, alpha, omega_inner, omega_outer)
    assert inner == pytest.approx(um, rel=1e-12) and outer == pytest.approx(um, rel=1e-12)


def test_bad_bearing_geometry():
    from lubedyn.lubrication.errors import InputError

    with pytest.raises(InputError, match="conformity r/D > 0.5"):
        bearing.conformity(D, 0.45 * D, "inner_groove_radius")
    with pytest.raises(InputError, match="gamma"):
        bearing.pitch_ratio(D, 0.5 * D, 0.0)
    with pytest.raises(InputError, match="contact angle > 0"):
        bearing.stribeck_max_load(1000.0, 100.0, Z, 0.0, 4.37)


def test_cage_speed_of_pure_rolling():
    """Harris & Kotzalas, Essential Concepts of Bearing Technology (5th ed.),
    ch. 8: with the outer ring fixed the cage turns at omega_i (1 - gamma)/2,
    with the inner ring fixed at omega_o (1 + gamma)/2, gamma = D cos(alpha)/d_m;
    and rings turning together carry the cage with them."""
    for alpha in (0.0, math.radians(15.0), math.radians(40.0)):
        gamma = D * math.cos(alpha) / DM
        assert bearing.pitch_ratio(D, DM, alpha) == pytest.approx(gamma, rel=1e-15)
        assert bearing.cage_speed(D, DM, alpha, 1000.0) == pytest.approx(500.0 * (1 - gamma), rel=1e-14)
        assert bearing.cage_speed(D, DM, alpha, 0.0, 1000.0) == pytest.approx(500.0 * (1 + gamma), rel=1e-14)
        assert bearing.cage_speed(D, DM, alpha, 700.0, 700.0) == pytest.approx(700.0, rel=1e-14)
    # the 6206 at 10 000 rpm: gamma = 0.207043 -> 3964.8 rpm
    assert bearing.cage_speed(D, DM, 0.0, 10000.0) == pytest.approx(3964.8, abs=0.05)


def test_free_contact_angle_is_the_groove_geometry():
    """Harris & Kotzalas (5th ed.), ch. 2: the groove curvature centres are
    B D = r_i + r_o - D apart; a radial play P_d/2 tilts that line to
    cos(beta_f) = 1 - P_d/(2 B D).  Checked by placing the ball: both centres
    at distance r - D/2 from the ball centre, radially P_d/2 apart."""
    BD = RI + RO - D
    for clearance in (5e-6, 20e-6, 0.1e-3):
        beta = bearing.free_contact_angle(D, RI, RO, clearance)
        # axial offset of the curvature centres when the radial one is BD - P_d/2
        assert BD * math.cos(beta) == pytest.approx(BD - 0.5 * clearance, rel=1e-12)
    assert bearing.free_contact_angle(D, RI, RO, 0.0) == 0.0
    assert bearing.free_contact_angle(D, RI, RO, -1e-6) == 0.0


def test_stribeck_constants_are_harris():
    """Stribeck's constants for zero clearance: 4.37 for point contacts,
    4.08 for line contacts (Harris & Kotzalas, Essential Concepts, 5th ed., sec. 7.4)."""
    assert bearing.STRIBECK == {"point": 4.37, "line": 4.08}
