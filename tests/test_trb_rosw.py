"""ROSW (ROS34PW2, a Rosenbrock-W method) with the tapered bearing's raceway traction in W.

Checked against: the method's stability function written from its tableau in matrix form (Hairer &
Wanner II, IV.7), its order measured on a nonlinear problem with a closed-form solution for three W's
(a W-method keeps its order for any W), the finite-difference Jacobian of the bearing's right-hand side
(the W blocks), RK4 on the bearing at a small step, and its order measured on the bearing at smoke size.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.integrators import (ROSW_ALPHA, ROSW_B, ROSW_GAMMA, ROSW_GAMMAS, STABILITY_POLYNOMIALS,
                                          integrate, stability_limit)
from lubedyn.dynamics.tapered import kernels as K
from lubedyn.dynamics.tapered import layout as L

from test_trb_dynamics import RPM, bearing


def _stability(z, w):
    """R = 1 + z b^T (I - (z alpha + w Gamma))^-1 1 of y' = lambda y with W = mu (z = h lambda, w = h mu):
    the tableau in matrix form (Gamma with gamma on its diagonal)."""
    A = np.zeros((4, 4))
    G = ROSW_GAMMA * np.eye(4)
    A[:, :3] = ROSW_ALPHA
    G[:, :3] += ROSW_GAMMAS
    # stage i: k_i = z (1 + sum_j alpha_ij k_j) + w sum_j gamma_ij k_j (gamma_ii included)
    M = np.eye(4) - z * A - w * G
    k = np.linalg.solve(M, z * np.ones(4))
    return 1.0 + ROSW_B @ k


@njit(cache=True)
def _scalar_rhs(t, y, args, dydt):
    dydt[0] = args[0] * y[0]


@njit(cache=True)
def _scalar_w(t, y, args, dydt, Jb, idx):
    dydt[0] = args[0] * y[0]
    Jb[0, 0, 0] = args[1]
    idx[0, 0] = 0


@pytest.mark.parametrize("z, w", [(-0.5, -0.5), (-3.0, -3.0), (-1e6, -1e6), (1j * 1.2, 0.0), (-1.0, -0.2)])
def test_one_step_is_the_stability_function_of_the_tableau(z, w):
    """One step of the kernel on y' = lambda y (W = mu) equals R(z, w) of the tableau in matrix form;
    with W = 0 that is the polynomial the step estimates use (STABILITY_POLYNOMIALS['rosw']); with W = J
    the method is L-stable (|R(-1e6)| = 2.9e-6)."""
    if isinstance(z, complex):
        assert abs(np.polyval(STABILITY_POLYNOMIALS["rosw"][::-1], z) - _stability(z, w)) < 1e-14
        return
    res = integrate(_scalar_rhs, [1.0], [0.0, 1.0], (z, w), method="rosw", dt=1.0, jac=_scalar_w, blocks=(1, 1))
    assert res.y[-1, 0] == pytest.approx(_stability(z, w), rel=1e-12, abs=1e-15)
    if z == w == -1e6:
        assert abs(res.y[-1, 0]) < 1e-5


def test_explicit_stability_limits():
    """ROS34PW2 on the modes W leaves out: stable to |h lambda| = 1.504 on the imaginary axis and 1.992 on
    the real axis (RK4: 2.828, 2.785), read off |R| of the tableau."""
    im, re = stability_limit("rosw", "imaginary"), stability_limit("rosw", "real")
    assert im == pytest.approx(1.504, abs=2e-3) and re == pytest.approx(1.992, abs=2e-3)
    assert abs(_stability(1j * (im - 1e-3), 0.0)) <= 1.0 < abs(_stability(1j * (im + 1e-2), 0.0))
    assert abs(_stability(-(re - 1e-3), 0.0)) <= 1.0 < abs(_stability(-(re + 1e-2), 0.0))


@njit(cache=True)
def _pendulum(t, y, args, dydt):
    # y1' = y2, y2' = -y1 - k (y1^2 - 1) y2 ... a smooth nonlinear oscillator (van der Pol, mu = args[0])
    dydt[0] = y[1]
    dydt[1] = args[0] * (1.0 - y[0] * y[0]) * y[1] - y[0]


@njit(cache=True)
def _pendulum_w(t, y, args, dydt, Jb, idx):
    _pendulum(t, y, args, dydt)
    idx[0, 0], idx[0, 1] = 0, 1
    # args[1]: 0 -> W = 0, 1 -> the exact Jacobian, 2 -> a fixed matrix unrelated to J
    if args[1] == 0.0:
        Jb[0, :, :] = 0.0
    elif args[1] == 1.0:
        Jb[0, 0, 0], Jb[0, 0, 1] = 0.0, 1.0
        Jb[0, 1, 0] = -2.0 * args[0] * y[0] * y[1] - 1.0
        Jb[0, 1, 1] = args[0] * (1.0 - y[0] * y[0])
    else:
        Jb[0, 0, 0], Jb[0, 0, 1], Jb[0, 1, 0], Jb[0, 1, 1] = -3.0, 0.7, 0.2, -1.5


@pytest.mark.parametrize("which", [0.0, 1.0, 2.0])
def test_order_three_for_any_w(which):
    """A W-method's order holds for any W: van der Pol (mu = 0.5) over 2 s against DOPRI5 at rtol 1e-12,
    end error at h = 0.1, 0.05, 0.025, 0.0125; the fitted order lies within 2.8-3.3 for W = 0, W = J and
    a fixed W unrelated to J (measured 3.11, 3.02, 2.87)."""
    t = np.array([0.0, 2.0])
    y0 = [2.0, 0.0]
    ref = integrate(_pendulum, y0, t, (0.5,), method="dopri5", rtol=1e-12, atol=1e-14).y[-1]
    hs = np.array([0.1, 0.05, 0.025, 0.0125])
    err = [np.max(np.abs(integrate(_pendulum, y0, t, (0.5, which), method="rosw", dt=h, jac=_pendulum_w,
                                   blocks=(1, 2)).y[-1] - ref)) for h in hs]
    order = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert 2.8 < order < 3.3, (order, err)


def test_bad_settings_are_one_line_errors():
    t = [0.0, 1.0]
    with pytest.raises(DynamicsInputError, match="jac = None: method 'rosw' needs"):
        integrate(_scalar_rhs, [1.0], t, (-1.0, -1.0), method="rosw", dt=0.1)
    with pytest.raises(DynamicsInputError, match="blocks = None"):
        integrate(_scalar_rhs, [1.0], t, (-1.0, -1.0), method="rosw", dt=0.1, jac=_scalar_w)
    with pytest.raises(DynamicsInputError, match="dt = None: method 'rosw'"):
        integrate(_scalar_rhs, [1.0], t, (-1.0, -1.0), method="rosw", jac=_scalar_w, blocks=(1, 1))
    with pytest.raises(DynamicsInputError, match="blocks = \\(1, 0\\)"):
        integrate(_scalar_rhs, [1.0], t, (-1.0, -1.0), method="rosw", dt=0.1, jac=_scalar_w, blocks=(1, 0))


@pytest.fixture(scope="module")
def limited():
    """The smoke bearing at 2,400 rpm, Fa = 15 kN, 5 slices, the limited traction with the film's elastic
    shear (G = 1 GPa: its slope sets RK4's step, tests/test_trb_dynamics.py), the contact-only cage."""
    from dataclasses import replace

    tb = bearing(speed=2400 * RPM, traction="limited", pocket="contact")
    tb = replace(tb, lubricant=replace(tb.lubricant, shear_modulus=1e9))
    return tb, tb.args(), tb.start_state()


def test_w_blocks_are_the_traction_part_of_the_jacobian(limited):
    """rhs_w's blocks against the finite-difference Jacobian of rhs on each loaded roller's (v, omega_body)
    block (the normal loads' damping and the gyroscopic terms are left out of W: within 5 % of the
    block's largest entry, measured 1.1-1.5 % on all 17 rollers), and J - W has no decay faster than the
    contact modes: its spectral step for ROSW is the contact modes' 1.504/omega_max to 10 % (measured
    9.974 against 9.979 us), twice RK4's 4.69 us set by the traction."""
    tb, args, y0 = limited
    n = y0.size
    d = np.empty(n)
    Jb, idx = np.zeros((tb.n_rollers, L.W_BLOCK, L.W_BLOCK)), np.zeros((tb.n_rollers, L.W_BLOCK), dtype=np.int64)
    K.rhs_w(0.0, y0, args, d, Jb, idx)
    f0 = np.empty(n)
    K.rhs(0.0, y0, args, f0)
    assert np.array_equal(d, f0)
    loaded = np.nonzero(K.loads_many(y0[None, :], args)[0, :, 0] > 0.5 * K.loads_many(y0[None, :], args)[0, :, 0].max())[0]
    for j in loaded:
        ii = idx[j]
        J = np.empty((6, 6))
        for c, i in enumerate(ii):
            e = 1e-7 * max(abs(y0[i]), 1e-3)
            y = y0.copy()
            y[i] += e
            f = np.empty(n)
            K.rhs(0.0, y, args, f)
            J[:, c] = (f[ii] - f0[ii]) / e
        assert np.max(np.abs(Jb[j] - J)) < 0.05 * np.max(np.abs(J)), j
    rk4 = tb.stable_step(y0=y0, args=args)
    rosw = tb.stable_step(y0=y0, args=args, method="rosw")
    assert rosw == pytest.approx(stability_limit("rosw", "imaginary") / tb.omega_max(), rel=0.1)
    assert rosw > 2.0 * rk4


def test_the_scene_names_bad_integrator_settings():
    """integrator.method outside the list and a fixed ROSW step beyond its stable-step estimate are one-line
    errors naming the key."""
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.lubrication.errors import InputError
    from lubedyn.scenes import tapered as S

    with pytest.raises(InputError, match="integrator.method"):
        load_case(CASES_DIR / "trb_fig5_2400rpm.toml", overrides=["integrator.method=rk5"])
    c = load_case(CASES_DIR / "trb_fig5_2400rpm.toml", overrides=["integrator.method=rosw", "integrator.dt=50 us",
                                                                   "integrator.duration=0.1 ms", "model.slices=5",
                                                                   "output.write=[]"])
    with pytest.raises(InputError, match="integrator.dt = 5e-05 s is beyond ROSW's stable-step estimate"):
        S.run(c)


@pytest.mark.slow
def test_rosw_converges_at_third_order_on_the_bearing_and_agrees_with_rk4(limited):
    """0.2 ms of the smoke bearing: the contact loads of ROSW at 1, 0.5, 0.25 us against RK4 at 0.1 us;
    the fitted order of the largest load error is >= 2.5 (measured 2.84: errors 1.18e-6, 1.72e-7, 2.30e-8
    of the largest cup load, pairwise 2.78 and 2.90, tending to the method's 3), and at 0.5 us ROSW and
    RK4 at 0.5 us agree to 1e-6 of it (measured 1.7e-7; RK4's own error there 7.7e-9)."""
    tb, args, y0 = limited
    t = np.linspace(0.0, 2e-4, 11)
    ref = K.loads_many(integrate(K.rhs, y0, t, args, method="rk4", dt=1e-7).y, args)
    scale = ref[:, :, 0].max()
    hs = np.array([1e-6, 5e-7, 2.5e-7])
    loads = {h: K.loads_many(integrate(K.rhs, y0, t, args, method="rosw", dt=h, jac=K.rhs_w,
                                       blocks=(tb.n_rollers, L.W_BLOCK)).y, args) for h in hs}
    err = [np.max(np.abs(loads[h] - ref)) / scale for h in hs]
    order = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert order >= 2.5, (order, err)
    rk4 = K.loads_many(integrate(K.rhs, y0, t, args, method="rk4", dt=5e-7).y, args)
    assert np.max(np.abs(loads[5e-7] - rk4)) < 1e-6 * scale


def test_the_summary_reports_the_rosw_step_taken():
    """The summary's "ROSW step [s]" is the step the integrator took (its accepted steps times it make the
    duration), at most the bound 0.8 x the estimate, which is the contact modes' limit (not the traction's)."""
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.scenes import tapered as S

    c = load_case(CASES_DIR / "trb_fig5_2400rpm.toml", overrides=["integrator.method=rosw", "integrator.duration=0.2 ms",
                                                                   "model.slices=5", "output.write=[]"])
    s = S.run(c).summary
    assert s["Accepted steps [-]"] * s["ROSW step [s]"] == pytest.approx(2e-4, rel=1e-9)
    assert s["ROSW step [s]"] <= s["ROSW step bound [s]"] == pytest.approx(0.8 * s["ROSW stable step estimate [s]"])
    assert "RK4 step [s]" not in s
