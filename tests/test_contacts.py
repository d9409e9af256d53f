"""Contact kernels of lubedyn.dynamics.contacts against independent references: the analytic circular Hertz
contact, Thornton's closed-form restitution of elastic-plastic spheres, Hunt and
Crossley's small-damping restitution, the analytic rigid squeeze-film approach,
and a scipy brentq reference of the film/solid series law."""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from lubedyn.dynamics import contacts as C
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import collision as LC
from lubedyn.lubrication.laws.traction import traction_coefficient
from lubedyn.dynamics import interp
from lubedyn.lubrication.laws.contact import hunt_crossley_alpha, reduced_modulus

D, DM, RI, RO = 9.525e-3, 46.005e-3, 4.905e-3, 4.953e-3  # paper B, Table 4
ES_RACE = reduced_modulus(207e9, 0.29, 208e9, 0.3)
ES_BALL = reduced_modulus(207e9, 0.29, 207e9, 0.29)
M_BALL = 7850.0 * math.pi / 6.0 * D**3


def _k(kernel, compiled):
    return kernel if compiled else kernel.py_func


def _no_map():
    return (np.zeros(2), np.zeros(2), np.zeros(2), np.zeros((1, 2, 2, 2)), np.zeros(C.MO_SIZE, dtype=np.int64),
            np.zeros(1, dtype=np.int64))


def test_ball_ball_stiffness_is_the_circular_hertz_law():
    """Two balls: K = (4/3) E* sqrt(R/2) (Hertz, sphere on sphere; Johnson 1985, eq. 4.23)."""
    R = 0.5 * D
    p = LC.ball_ball_parameters(ball_radius=R, e_star=ES_BALL)
    assert p.k == pytest.approx(4 / 3 * ES_BALL * math.sqrt(R / 2), rel=1e-14)


def _impact(force, v0, mass, dt):
    """RK4 of m x'' = -force(x, x') from first touch to separation; returns v_out/v_in."""
    def acc(x, v):
        return -force(x, v) / mass

    s = np.array([0.0, v0])
    while True:
        k1 = np.array([s[1], acc(s[0], s[1])])
        k2 = np.array([s[1] + 0.5 * dt * k1[1], acc(s[0] + 0.5 * dt * k1[0], s[1] + 0.5 * dt * k1[1])])
        k3 = np.array([s[1] + 0.5 * dt * k2[1], acc(s[0] + 0.5 * dt * k2[0], s[1] + 0.5 * dt * k2[1])])
        k4 = np.array([s[1] + dt * k3[1], acc(s[0] + dt * k3[0], s[1] + dt * k3[1])])
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if s[0] <= 0.0 and s[1] < 0.0:
            return -s[1] / v0


@pytest.mark.parametrize("compiled", [True, False])
def test_hunt_crossley_restitution(compiled):
    """Hunt & Crossley: 1 - e = (2/3) alpha v for small alpha v (first order)."""
    hf = _k(LC.hertz_force, compiled)
    K, v0 = 3e10, 0.5
    alpha = hunt_crossley_alpha(0.999, v0)
    e = _impact(lambda x, v: hf(x, v, K, alpha), v0, M_BALL, 2e-8)
    assert (1.0 - e) / 0.001 == pytest.approx(1.0, rel=0.01)
    e0 = _impact(lambda x, v: hf(x, v, K, 0.0), v0, M_BALL, 2e-8)
    # undamped: elastic; the residual is RK4's error at the non-smooth first touch
    # (force ~ x^1.5: local error O(dt^2.5)), ~3e-9 at this step
    assert e0 == pytest.approx(1.0, abs=1e-7)


@pytest.mark.parametrize("compiled", [True, False])
@pytest.mark.parametrize("ratio", [1.5, 6.0, 25.0])
def test_thornton_restitution(compiled, ratio):
    """Elastic / elastic-plastic / recovery phases against Thornton's (1997) closed form
    e = sqrt(6 sqrt3/5) sqrt(1 - x^2/6) [x/(x + 2 sqrt(6/5 - x^2/5))]^(1/4), x = V_y/V_i."""
    tf, rate = _k(LC.thornton_force, compiled), _k(C.plastic_memory_rate, compiled)
    p = LC.ball_ball_parameters(ball_radius=0.5 * D, e_star=ES_BALL, yield_stress=1.7e9)
    ms = 0.5 * M_BALL
    K, dy = p.k, p.dy
    vy = math.sqrt(4.0 * K * dy**2.5 / (5.0 * ms))  # (2/5) K dy^2.5 = m* Vy^2/2
    v0 = ratio * vy
    dt = 1e-3 * (ms / (1.5 * K * dy**0.5)) ** 0.5 / ratio**0.2

    def f(s):
        F, _, _ = tf(s[0], s[2], p)
        return np.array([s[1], -F / ms, rate(s[0], s[1], s[2], F, p)])

    s = np.array([1e-15, v0, 0.0])
    phases = set()
    while True:
        k1 = f(s)
        k2 = f(s + 0.5 * dt * k1)
        k3 = f(s + 0.5 * dt * k2)
        k4 = f(s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        F, _, ph = tf(s[0], s[2], p)
        phases.add(ph)
        if s[1] < 0.0 and F <= 0.0:
            break
    x = 1.0 / ratio
    e_th = math.sqrt(6 * math.sqrt(3) / 5) * math.sqrt(1 - x * x / 6) * (x / (x + 2 * math.sqrt(6 / 5 - x * x / 5))) ** 0.25
    assert -s[1] / v0 == pytest.approx(e_th, rel=1e-5)
    assert {LC.PHASE_ELASTIC, LC.PHASE_PLASTIC, LC.PHASE_RECOVERY} <= phases
    # the residual indentation is where the recovery curve reaches zero
    dp = LC.residual_indentation(s[2], p)
    assert tf(dp * (1 + 1e-9) + 1e-18, s[2], p)[0] == pytest.approx(0.0, abs=1e-6 * K * dy**1.5)
    assert dp > 0.0


@pytest.mark.parametrize("compiled", [True, False])
def test_series_law_matches_brentq_reference(compiled):
    """Film (rigid isoviscous squeeze film, R_eff = R/2) in series with Hertz:
    F = K x^1.5 = C0 v (1/(g + x + h_r) - 1/(h_cut + h_r)), solved by brentq here."""
    bbn = _k(C.ball_ball_normal, compiled)
    R = 0.5 * D
    eta = 0.05
    p = LC.ball_ball_parameters(ball_radius=R, e_star=ES_BALL, viscosity=eta, rupture_thickness=1e-7)
    K, C0, hr, hcut = p.k, 6 * math.pi * eta * (R / 2) ** 2, 1e-7, 0.1 * R
    dummy = _no_map()
    for g, v in [(5e-6, 0.3), (2e-7, 0.05), (-1e-7, 0.5), (-1e-6, 2.0)]:
        F, h, x, phase, share = bbn(g, v, 0.0, 0.0, p, C.FILM_CLOSED_FORM, *dummy)

        def phi(x):
            return K * x**1.5 - C0 * v * (1 / (g + x + hr) - 1 / (hcut + hr))

        xr = brentq(phi, max(-g, 0.0), 1e-3, xtol=1e-20, rtol=1e-14)
        assert F == pytest.approx(K * xr**1.5, rel=1e-8)
        assert h == pytest.approx(g + xr, rel=1e-6, abs=1e-15)
        assert phase == LC.PHASE_FILM
        # share of the approach taken by the solids: d(x)/d(-g) of the reference root (finite difference)
        eps = 1e-4 * max(abs(g), xr)
        x2 = brentq(lambda y: K * y**1.5 - C0 * v * (1 / (g - eps + y + hr) - 1 / (hcut + hr)), max(eps - g, 0.0),
                    1e-3, xtol=1e-22, rtol=1e-15)
        assert share == pytest.approx((x2 - xr) / eps, rel=1e-3)
    # separation: the film cavitates, Hertz unloads through the ruptured film
    F, h, x, phase, share = bbn(-1e-6, -0.5, 0.0, 0.0, p, C.FILM_CLOSED_FORM, *dummy)
    assert F == pytest.approx(K * 1e-6**1.5, rel=1e-12) and h == 0.0 and phase == LC.PHASE_ELASTIC
    assert bbn(1e-6, -0.5, 0.0, 0.0, p, C.FILM_CLOSED_FORM, *dummy)[0] == 0.0
    # film "none": plain Hertz
    assert bbn(-2e-6, 0.3, 0.0, 0.0, p, C.FILM_NONE, *dummy)[0] == pytest.approx(K * 2e-6**1.5, rel=1e-12)


def test_rigid_squeeze_film_approach_is_analytic():
    """Two balls approaching through the film from 100 um: in the rigid regime
    (h >> elastic approach) m* dv/dh = C0 (1/(h + h_r) - 1/(h_cut + h_r)) integrates to
    v(h) = v0 - (C0/m*) [ln((h0 + h_r)/(h + h_r)) - (h0 - h)/(h_cut + h_r)]."""
    R = 0.5 * D
    eta = 0.05
    p = LC.ball_ball_parameters(ball_radius=R, e_star=ES_BALL, viscosity=eta)
    C0, hr, hcut = p.c0, p.hr, p.hcut
    ms = 0.5 * M_BALL
    dummy = _no_map()
    g0, v0 = 1e-4, 0.02
    s = np.array([g0, v0])  # gap, approach speed
    dt = 2e-6

    def f(s):
        F = C.ball_ball_normal(s[0], s[1], 0.0, 0.0, p, C.FILM_CLOSED_FORM, *dummy)[0]
        return np.array([-s[1], -F / ms])

    while s[0] > 1e-5:
        k1 = f(s)
        k2 = f(s + 0.5 * dt * k1)
        k3 = f(s + 0.5 * dt * k2)
        k4 = f(s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    g = s[0]
    v_th = v0 - C0 / ms * (math.log((g0 + hr) / (g + hr)) - (g0 - g) / (hcut + hr))
    assert v_th < 0.9 * v0  # the film has taken a good part of the speed
    # the elastic approach delta_e = (F/K)^(2/3) ~ 1e-8 m << g = 10 um changes v by
    # ~ (C0/m*) int delta_e/g^2 dg ~ 2e-4 relative here
    assert s[1] == pytest.approx(v_th, rel=5e-4)


@pytest.mark.parametrize("method, speed_axis", [(interp.PCHIP, "approach_speed"), (interp.HERMITE, "approach_speed"),
                                                (interp.PCHIP, "squeeze_number")])
def test_map_option_reproduces_tabulated_closed_form(method, speed_axis):
    """The map slot: a force table of the closed form over (gap, approach speed) or
    (gap, squeeze number, entrainment speed), read through lubedyn.dynamics.interp, gives the
    same series force within the table's interpolation error."""
    from lubedyn.dynamics.cageless import _map_arrays

    R = 0.5 * D
    alpha = 1.85e-8
    p = LC.ball_ball_parameters(ball_radius=R, e_star=ES_BALL, viscosity=0.05, pressure_viscosity=alpha)
    gaps = np.geomspace(1e-9, 4e-4, 161)
    ax0 = interp.prepare_axis(gaps, True)
    if speed_axis == "approach_speed":
        speeds = np.geomspace(1e-4, 10.0, 41)
        vals = np.array([[LC.squeeze_film_closed_form(h, v, p)[0] for v in speeds] for h in gaps])
        axes, logs = (ax0, interp.prepare_axis(speeds, True)), (1, 1)
    else:  # Lambda = 3 alpha eta R_eff v/h^2; a third (entrainment) axis on which nothing depends
        lam = np.geomspace(1e-16, 1e10, 131)  # isoviscous: any Lambda (a Barus map stops below 1)
        ue = np.array([0.0, 0.05])
        vals = np.array([[[LC.squeeze_film_closed_form(h, L * h * h / p.sqf, p)[0]] * 2 for L in lam]
                         for h in gaps])
        axes, logs = (ax0, interp.prepare_axis(lam, True), interp.prepare_axis(ue, False)), (1, 1, 0)
    u = interp.prepare_values(np.maximum(vals, 1e-300), True)
    if method == interp.HERMITE:
        u = interp.hermite_data(axes, u)
    arrays = _map_arrays((axes, logs, u, 1, method), speed_axis)
    counter = np.zeros(1, dtype=np.int64)
    dummy = _no_map()
    for g, v in [(5e-6, 0.3), (2e-7, 0.05), (-5e-7, 0.5), (3e-5, 3e-5)]:
        Fm = C.ball_ball_normal(g, v, 0.01, 0.0, p, C.FILM_MAP, *arrays, counter)[0]
        Fc = C.ball_ball_normal(g, v, 0.01, 0.0, p, C.FILM_CLOSED_FORM, *dummy)[0]
        assert Fm == pytest.approx(Fc, rel=2e-3)
    assert counter[0] == 0
    # outside the axes: clamped and counted
    C.ball_ball_normal(1e-6, 1e3 if speed_axis == "approach_speed" else 0.1, 1.0, 0.0, p, C.FILM_MAP, *arrays,
                       counter)
    assert counter[0] >= 1


@pytest.mark.parametrize("compiled", [True, False])
def test_traction_curve_limits(compiled):
    tc = _k(traction_coefficient, compiled)
    assert tc(5.0, 10.0, 0.07, 0.02, 0.05) == pytest.approx(0.07, rel=1e-12)  # SRR 0.5 >> 0.02: limiting
    # initial slope mu_lim/s0 in SRR
    assert tc(1e-5, 10.0, 0.07, 0.02, 0.05) / 1e-6 == pytest.approx(0.07 / 0.02, rel=1e-8)
    # no entrainment: regularised Coulomb on the sliding speed
    assert tc(1e-4, 0.0, 0.07, 0.02, 0.05) == pytest.approx(0.07 * math.tanh(1e-4 / 0.05), rel=1e-14)


def test_film_rupture_friction_blend():
    """Law "exponential_share": mu_b at h = 0, e^-1 mix at h = h_r, mu_f for h >> h_r."""
    p = LC.ball_ball_parameters(ball_radius=0.5 * D, e_star=ES_BALL, mu_film=0.03, mu_boundary=0.12,
                               rupture_thickness=1e-7)
    f = LC.ball_ball_friction_coefficient
    assert f(0.0, 10.0, 1.0, p) == pytest.approx(0.12, rel=1e-15)
    assert f(1e-7, 10.0, 1.0, p) == pytest.approx(0.12 / math.e + 0.03 * (1 - 1 / math.e))
    assert f(5e-6, 10.0, 1.0, p) == pytest.approx(0.03, rel=1e-12)


def _paper_law(**kw):
    args = dict(ball_radius=0.5 * D, e_star=ES_BALL, mu_film=0.03, mu_boundary=0.12, rupture_thickness=1e-7,
                viscosity=0.05, pressure_viscosity=2e-8, friction_law="paper", asperity_slope=0.02)
    args.update(kw)
    return LC.ball_ball_parameters(**args)


def _hertz_circle(load, reff):
    """a and p0 of a circular Hertz contact (Johnson 1985, eqs. 4.22-4.23)."""
    a = (3 * load * reff / (4 * ES_BALL)) ** (1 / 3)
    return a, 3 * load / (2 * math.pi * a * a)


@pytest.mark.parametrize("compiled", [True, False])
def test_paper_b_friction_law_limits(compiled):
    """Law "paper" (eqs. 17-21 rebuilt) in each of its limits, against values computed here from
    Johnson's Hertz circle and the isoviscous shear of eq. 17 (1.5 eta U/(h p0))."""
    f = _k(LC.ball_ball_friction_coefficient, compiled)
    reff, load = 0.25 * D, 50.0
    a, p0 = _hertz_circle(load, reff)
    # thick film (lambda = 50: no asperity load), isoviscous, slow sliding: Newtonian eq. 17 (tanh ~ its argument)
    p = _paper_law(pressure_viscosity=0.0)
    h, U = 5e-6, 1e-4
    newton = 1.5 * 0.05 * U / (h * p0)
    assert f(h, load, U, p) == pytest.approx(0.03 * math.tanh(newton / 0.03), rel=1e-12)
    assert f(h, load, U, p) == pytest.approx(newton, rel=1e-6)
    # piezoviscous (alpha p0 ~ 50): limiting shear mu_f
    p = _paper_law()
    assert 2e-8 * p0 > 40
    assert f(h, load, 1.0, p) == pytest.approx(0.03, rel=1e-14)
    # no sliding, no load: no friction
    assert f(h, load, 0.0, p) == 0.0 and f(h, 0.0, 1.0, p) == 0.0
    # no film, a light load: the asperities carry it all (Q_a > F_n) -> boundary friction mu_b
    light = 0.5
    a_l, _ = _hertz_circle(light, reff)
    f0 = 17.0 + 1.44e-4 * 4.0**7.8
    assert ES_BALL * a_l**2 * 0.02 * f0 / (2 * math.pi * light) > 1.0
    assert f(0.0, light, 1.0, p) == pytest.approx(0.12, rel=1e-14)
    # lambda = 1 under the 50 N load: the mix of eq. 20 with Q_a/F_n = E' pi a^2 sigma_theta f(1)/(4 pi^2 F_n)
    s = 2 * ES_BALL * math.pi * a * a * 0.02 * (17 * math.exp(-2.84) + 1.44e-4 * 3.0**7.8) / (4 * math.pi**2 * load)
    assert 0.01 < s < 0.5
    assert f(1e-7, load, 1.0, p) == pytest.approx(0.03 * (1 - s) + 0.12 * s, rel=1e-12)


def test_paper_b_asperity_share_scaling():
    """Eq. 19 as read: the share falls as F_n^(-1/3) at a fixed film ratio (Hertz area ~ F_n^(2/3)),
    falls with the film ratio, and is continuous where its power-law term ends (lambda = 4)."""
    share = LC.asperity_load_share
    reff = 0.25 * D
    assert share(80.0, 1.0, reff, ES_BALL, 0.02) / share(10.0, 1.0, reff, ES_BALL, 0.02) == pytest.approx(0.5, rel=1e-12)
    lams = np.linspace(0.0, 6.0, 601)
    f = np.array([LC.asperity_load_function(x) for x in lams])
    assert np.all(np.diff(f) < 0)
    assert LC.asperity_load_function(4.0 - 1e-9) == pytest.approx(17 * math.exp(-2.84 * 4.0), rel=1e-6)
    assert LC.asperity_load_function(0.0) == pytest.approx(17.0 + 1.44e-4 * 4.0**7.8, rel=1e-14)
    with pytest.raises(InputError, match="friction_law = 'coulomb' is not allowed"):
        _paper_law(friction_law="coulomb")
