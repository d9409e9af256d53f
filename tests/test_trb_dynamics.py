"""The tapered roller bearing's compiled right-hand side (dynamics.tapered.kernels, issue 23's first
step: rollers and cone, slices, flange, no traction or cage yet) against independent values: the
quasi-static solver's equilibrium (a separate 2-D implementation), the torque-free precession of an
axisymmetric body (analytic), and the return to equilibrium after a perturbation."""
from __future__ import annotations

import math

import numpy as np
import pytest

from coupling.parameters.wu2018 import tapered_geometry
from dynamics.integrators import integrate
from dynamics.tapered import kernels as K
from dynamics.tapered.model import TaperedBearing


@pytest.fixture(scope="module")
def axial():
    tb = TaperedBearing(tapered_geometry(), n_slices=5, axial="force", axial_load=15e3, damping_alpha=0.32)
    qs = tb.quasi_static()
    return tb, qs, tb.start_state(qs), tb.args()


def test_the_start_state_carries_the_quasi_static_loads(axial):
    """The 3-D contact kernel (slice_contact_3d at each roller's azimuth) at the start state gives the
    2-D quasi-static solver's cup, cone and flange loads of every roller, and no roller or cone
    accelerates: measured 1e-11 relative and 1.6e-5 m/s^2 (against ~1e6 m/s^2 for 1 um of approach)."""
    tb, qs, y0, args = axial
    L = K.loads_many(y0[None, :], args)[0]
    for k, ref in enumerate((qs.cup_loads, qs.cone_loads, qs.flange_loads)):
        assert L[:, k] == pytest.approx(ref, rel=1e-8)
    d = np.zeros_like(y0)
    K.rhs(0.0, y0, args, d)
    acc = np.concatenate([d[3:6]] + [d[K.N_CONE + j * K.NB + 7:K.N_CONE + j * K.NB + 10] for j in range(tb.n_rollers)])
    assert np.max(np.abs(acc)) < 1e-2


def test_a_perturbed_bearing_returns_to_the_quasi_static_loads(axial):
    """The cone pushed 1 um off centre under Fa = 15 kN (axial DOF free, alpha_e = 0.32 s/m): after 40 ms
    every roller's cup, cone and flange load is back at the quasi-static value within 1e-3 (measured
    5.2e-5, 5.2e-5, 2.0e-5; at 20 ms 1.4e-4 and 2.6e-4: the slowest mode decays at about 50 1/s)."""
    tb, qs, y0, args = axial
    y1 = y0.copy()
    y1[1] += 1e-6
    res = integrate(K.rhs, y1, np.linspace(0.0, 40e-3, 5), args, method="dopri5", rtol=1e-7, atol=1e-12)
    L = K.loads_many(res.y, args)
    assert np.max(np.abs(L[1, :, 0] / qs.cup_loads - 1)) > 1e-4  # it was perturbed
    for k, ref in enumerate((qs.cup_loads, qs.cone_loads, qs.flange_loads)):
        assert np.max(np.abs(L[-1, :, k] / ref - 1)) < 1e-3


def test_a_free_roller_precesses_as_euler_says():
    """Contacts off: a roller (I_x != I_y = I_z) spinning about its axis with a transverse component
    keeps omega_x and |omega_perp| and turns omega_perp about its axis at (I_x - I_y)/I_y omega_x
    (torque-free axisymmetric body, analytic); its kinetic energy and angular momentum hold to 1e-9."""
    g = tapered_geometry()
    tb = TaperedBearing(g, n_slices=3, contacts=False, axial="force", axial_load=15e3)
    P, U, RHO = tb.args()
    y0 = tb.start_state()
    b = K.N_CONE
    w0 = np.array([900.0, 40.0, 0.0])
    y0[b + 10:b + 13] = w0
    t = np.linspace(0.0, 5e-3, 11)
    res = integrate(K.rhs, y0, t, (P, U, RHO), method="dopri5", rtol=1e-11, atol=1e-14)
    ix, iy = P[K.P_IX], P[K.P_IY]
    rate = (ix - iy) / iy * w0[0]
    w = res.y[:, b + 10:b + 13]
    assert np.allclose(w[:, 0], w0[0], rtol=1e-9)
    assert np.allclose(w[:, 1], w0[1] * np.cos(rate * t), atol=1e-6 * w0[1])
    assert np.allclose(w[:, 2], w0[1] * np.sin(rate * t), atol=1e-6 * w0[1])
    energy = 0.5 * (ix * w[:, 0] ** 2 + iy * (w[:, 1] ** 2 + w[:, 2] ** 2))
    assert np.ptp(energy) < 1e-9 * energy[0]


def test_at_speed_the_rollers_keep_the_ideal_kinematics():
    """2,400 rpm under Fa = 15 kN with eq. 12's traction, from the quasi-static start at the ideal
    speeds: every roller's orbital speed stays at the geometry's ideal cage speed omega_i (1 - gamma)/2
    and its spin at the ideal roller spin (the kernel's surface velocities against the geometry's
    analytic kinematics: zero sliding at the ideal speeds); measured 1e-8 over 5 ms, asserted 1e-6
    over 1 ms.  The centripetal acceleration omega_c^2 R of the orbit and the gyroscopic moment are
    carried by the contacts as in the quasi-static equilibrium."""
    g = tapered_geometry()
    w = 2400 * math.pi / 30
    tb = TaperedBearing(g, n_slices=5, axial="force", axial_load=15e3, damping_alpha=0.32, speed=w, traction="paper")
    y0 = tb.start_state()
    kin = g.kinematics(w)
    res = integrate(K.rhs, y0, np.linspace(0.0, 1e-3, 3), tb.args(), method="dopri5", rtol=1e-7, atol=1e-12)
    from dynamics.rotations import quat_rotate

    for j in range(tb.n_rollers):
        b = K.N_CONE + j * K.NB
        c, v = res.y[-1, b:b + 3], res.y[-1, b + 7:b + 10]
        orbital = (c[1] * v[2] - c[2] * v[1]) / (c[1] ** 2 + c[2] ** 2)
        assert orbital / kin["cage speed [rad/s]"] - 1 == pytest.approx(0.0, abs=1e-6)
        q = res.y[-1, b + 3:b + 7] / np.linalg.norm(res.y[-1, b + 3:b + 7])
        e, wi = np.empty(3), np.empty(3)
        quat_rotate(q, np.array([1.0, 0.0, 0.0]), e)
        quat_rotate(q, res.y[-1, b + 10:b + 13].copy(), wi)
        spin = (wi - np.array([orbital, 0.0, 0.0])) @ e
        assert spin / -kin["roller spin relative to cage [rad/s]"] - 1 == pytest.approx(0.0, abs=1e-6)


def _with_cage(speed):
    from coupling.parameters.wu2018 import VALUES

    v = lambda k: VALUES[k].si()  # noqa: E731  paper A's assumed cage values
    return TaperedBearing(tapered_geometry(), n_slices=5, axial="force", axial_load=15e3, damping_alpha=0.32,
                          speed=speed, traction="paper", cage=True, cage_mass=v("cage_mass"),
                          pocket_critical_film=v("pocket_critical_film"), pocket_stiffness=v("pocket_contact_stiffness"),
                          pocket_damping=v("pocket_contact_damping"), boundary_friction=v("boundary_friction"),
                          land_critical_film=v("guide_land_critical_film"))


def test_the_cage_starts_under_the_land_drag_and_the_pocket_couples():
    """At 2,400 rpm, cage concentric at the ideal speed, rollers centred in their pockets: the cage's
    angular acceleration is (T_land - Z 2 rho_m f cos(alpha_r))/I_x, T_land = 2 pi eta r^3 b (Omega -
    omega_c)/c the land's Couette drag and f eq. 34's film traction of a roller surface sliding at
    omega_s rho_m past each crossbeam at the clearance (the two sides' traction make a couple rho_m f
    cos(alpha_r) each), I_x of the cage ring: computed here from the closed forms (1.628 and 0.693 N m;
    264.7 rad/s^2), against the kernel to 1e-5 (measured 4e-7); the Martin loads of the two sides cancel."""
    from lubrication.laws.cage import cylinder_plane_traction

    w = 2400 * math.pi / 30
    tb = _with_cage(w)
    g = tb.geometry
    y0 = tb.start_state()
    d = np.zeros_like(y0)
    K.rhs(0.0, y0, tb.args(), d)
    kin = g.kinematics(w)
    r, c, width = g.land_radius, 0.5 * g.guide_land_clearance, g.guide_land_width
    t_land = 2 * math.pi * tb.viscosity * r**3 * width * (w - kin["cage speed [rad/s]"]) / c
    rho = g.mean_roller_radius
    f = cylinder_plane_traction(g.pocket_clearance, kin["roller spin relative to cage [rad/s]"] * rho, rho,
                                g.effective_length, tb.viscosity)
    ro, ri = 0.5 * g.cage_outer_diameter, 0.5 * g.cage_inner_diameter
    i_x = 0.5 * tb.cage_mass * (ro**2 + ri**2)
    expected = (t_land - g.n_rollers * 2 * rho * f * math.cos(g.roller_axis_angle)) / i_x
    b = K.N_CONE + K.NB * g.n_rollers
    assert d[b + 10] == pytest.approx(expected, rel=1e-5)
    assert np.max(np.abs(d[b + 7:b + 10])) < 1e-6  # no net force on the concentric cage


def test_the_cage_runs_with_its_rollers():
    """2 ms at 2,400 rpm with the cage: the pocket loads stay film loads (below 1 kN: no roller driven
    through a crossbeam), the cage stays within the land's clearance, and it runs within 0.5 % of the ideal
    speed (measured -0.10 % to -0.16 %: the land drags it ahead, paper A's Fig. 9 has 0-0.03 % at 2 krpm
    with its grease: the drag scales with the assumed 0.1 Pa s)."""
    w = 2400 * math.pi / 30
    tb = _with_cage(w)
    g = tb.geometry
    y0 = tb.start_state()
    res = integrate(K.rhs, y0, np.linspace(0.0, 2e-3, 5), tb.args(), method="dopri5", rtol=1e-7, atol=1e-12)
    b = K.N_CONE + K.NB * g.n_rollers
    ideal = g.kinematics(w)["cage speed [rad/s]"]
    assert np.all(np.abs(res.y[:, b + 10] / ideal - 1) < 5e-3)
    assert np.all(np.hypot(res.y[:, b + 1] - res.y[:, 1], res.y[:, b + 2] - res.y[:, 2]) < 0.5 * g.guide_land_clearance)
    L = K.loads_many(res.y, tb.args())
    assert np.all(L[:, :, 3] < 1e3)  # pocket loads stay film loads (N), no crossbeam crushed


def test_the_guide_land_contact_pushes_the_cage_back_to_centre():
    """At rest (no film force), the cage displaced along -y until its bore is 1 um from the land (below
    the 2 um critical film): the boundary contact pushes the cage back along +y by k_h (h_crit - h)
    = 1e8 x 1e-6 = 100 N and the cone (the land) along -y by the same (a sign error once pushed them
    further together)."""
    tb = _with_cage(0.0)
    g = tb.geometry
    y = tb.start_state()
    b = K.N_CONE + K.NB * g.n_rollers
    c = 0.5 * g.guide_land_clearance
    y[b + 1] = y[1] - (c - 1e-6)
    P, U, RHO = tb.args()
    Z = g.n_rollers
    F, T, Fc, Fg, Tg = np.empty((Z, 3)), np.empty((Z, 3)), np.empty(3), np.empty(3), np.empty(3)
    loads = np.empty((Z, 4))
    K.contact_forces(y, P, U, RHO, F, T, Fc, loads, Fg, Tg)
    y_free = y.copy()
    y_free[b + 1] = y[1]  # the same state with the cage centred: no land contact
    F0, Fc0, Fg0 = np.empty((Z, 3)), np.empty(3), np.empty(3)
    K.contact_forces(y_free, P, U, RHO, F0, T, Fc0, loads, Fg0, Tg)
    assert Fg[1] - Fg0[1] - (F0[:, 1].sum() - F[:, 1].sum()) == pytest.approx(100.0, rel=1e-6)
    assert Fc[1] - Fc0[1] == pytest.approx(-100.0, rel=1e-6)
