"""The Reynolds solver against closed-form and semi-analytic film solutions.

Every reference comes from :mod:`lubedyn.lubrication.closed_form` (literature
formulas, or scipy quadratures/ODE solves independent of the finite elements).
Velocity convention of the solver: u_m = (U_lower + U_upper)/2; each test
states which surface moves.  Tolerances are set from the discretisation error
measured at the mesh used (quoted in each test) with a margin of about 2-3,
or from the accuracy of the reference.
"""
import numpy as np
import pytest
from scipy import optimize

from lubedyn.lubrication import (
    Film, FunctionGap, InclinedSlider, Lubricant, SpherePlane, SphereSphere, StepSlider,
)
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes

ETA = 0.05  # Pa s
LUB = Lubricant.newtonian(ETA)


# --------------------------------------------------------------------------
# 1. infinitely wide inclined slider

LENGTH, H_OUT, RUNNER = 0.05, 20e-6, 5.0  # m, m, m/s


def slider_film(K, n=16, element="P2"):
    """Runner (lower surface) at U = 5 m/s, pad (upper) fixed: u_m = U/2."""
    gap = InclinedSlider(H_OUT * (1.0 + K), H_OUT, LENGTH)
    return Film(meshes.interval(0.0, LENGTH, n), gap, LUB, velocity_lower=(RUNNER,), element=element)


def test_inclined_slider_pressure_load_and_peak():
    """Pressure profile, load and peak position, K = h_in/h_out - 1 = 1, u_m = U_runner/2.

    P2, 16 elements.  Measured: nodal pressure error 2.9e-5 p_max (P1 at
    32 elements: 5.6e-4), load error 1.05e-5; the peak of the P2 field (found
    with scipy between nodes) is 4.9e-4 L from x_m and 7.2e-5 below p_max,
    both falling 4x per halving (the P2 gradient error is O(h^2)).
    """
    K, um = 1.0, RUNNER / 2
    sol = slider_film(K).solve()
    x = sol.basis.doflocs[0]
    p_exact = cf.inclined_slider_pressure(x, H_OUT * (1 + K), H_OUT, LENGTH, ETA, um)
    x_m = cf.inclined_slider_max_pressure_position(H_OUT * (1 + K), H_OUT, LENGTH)
    p_max = float(cf.inclined_slider_pressure(x_m, H_OUT * (1 + K), H_OUT, LENGTH, ETA, um))
    assert x_m == pytest.approx(2.0 / 3.0 * LENGTH)
    assert np.max(np.abs(sol.pressure - p_exact)) < 1e-4 * p_max
    W = cf.inclined_slider_load(H_OUT * (1 + K), H_OUT, LENGTH, ETA, um)
    assert sol.load == pytest.approx(W, rel=3e-5)
    assert sol.mode_forces["h0"] == pytest.approx(W, rel=3e-5)
    # peak of the finite-element pressure field (not just the best node)
    probe = lambda s: -float((sol.basis.probes(np.array([[s]])) @ sol.pressure)[0])
    x0 = float(sol.p_max_location[0])
    res = optimize.minimize_scalar(probe, bounds=(x0 - LENGTH / 16, x0 + LENGTH / 16), method="bounded",
                                   options=dict(xatol=1e-9 * LENGTH))
    assert res.x == pytest.approx(x_m, abs=1e-3 * LENGTH)
    assert -res.fun == pytest.approx(p_max, rel=1.5e-4)


def test_inclined_slider_optimum_convergence_ratio():
    """The K maximising the finite-element load at fixed h_out is the analytic 1.1887.

    Maximise the P2 (16 elements) load over K with scipy; its load error
    (1e-5 relative, smooth in K) moves the argmax by far less than the
    1e-3 asserted (the load is flat at the optimum, so the argmax is only
    determined to about sqrt(xatol-level noise)).
    """
    K_opt = cf.inclined_slider_optimum_ratio()
    assert K_opt == pytest.approx(1.1887, abs=1e-4)  # Hamrock et al. 2004, sec. 8.6.2: K = 1.19
    res = optimize.minimize_scalar(lambda K: -slider_film(K).solve().load, bounds=(0.3, 3.0), method="bounded",
                                   options=dict(xatol=1e-6))
    assert res.x == pytest.approx(K_opt, abs=1e-3)


# --------------------------------------------------------------------------
# 2. Rayleigh step


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_rayleigh_step(element):
    """Step pressure and load; runner (lower) at U, pad fixed: u_m = U/2.

    Optimum Rayleigh proportions (h_in/h_out = 1.866, l_in/l_out = 2.588).
    The exact pressure is piecewise linear with its kink at the step, where a
    mesh node sits: it lies in the P1 (and P2) space and the 1-D Galerkin
    solution reproduces it, so the match is to round-off (1e-10).
    """
    h_out, l_out = 20e-6, 10e-3
    h_in, l_in = 1.866 * h_out, 2.588 * l_out
    pts = np.concatenate([np.linspace(0.0, l_in, 9), np.linspace(l_in, l_in + l_out, 5)[1:]])
    film = Film(meshes.interval(0, 0, 0, points=pts), StepSlider(h_in, h_out, l_in), LUB,
                velocity_lower=(RUNNER,), element=element)
    sol = film.solve()
    step = int(np.argmin(np.abs(sol.basis.doflocs[0] - l_in)))
    p_s = cf.rayleigh_step_pressure(h_in, h_out, l_in, l_out, ETA, RUNNER / 2)
    assert sol.pressure[step] == pytest.approx(p_s, rel=1e-10)
    assert sol.load == pytest.approx(cf.rayleigh_step_load(h_in, h_out, l_in, l_out, ETA, RUNNER / 2), rel=1e-10)


# --------------------------------------------------------------------------
# 3. infinitely long journal bearing (periodic strip, see conftest.long_journal_film)

R, C, U_J = 0.05, 50e-6, 10.0  # radius, radial clearance [m], journal surface speed omega R [m/s]


@pytest.mark.parametrize("eps", [0.3, 0.7])
def test_long_journal_full_sommerfeld(long_journal_film, eps):
    """Full Sommerfeld: pressure profile, load W = 12 pi eta U R^2 eps/(c^2 (2+eps^2) sqrt(1-eps^2)),
    attitude 90 deg (F_x = W_r = 0, F_y = -W).

    Journal surface speed U = omega R (upper surface), bearing fixed.  P2, 64
    elements.  Measured: pressure error 6.7e-7 (eps 0.3) and 1.6e-5 (eps 0.7)
    of p_max, load error 4e-7 and 3.7e-6, |F_x| < 1e-12 W.  This test also
    pins the gauge node on the periodic seam (it failed, with a pressure
    offset of p(dtheta), before the seam fix in reynolds.problem._Problem._dirichlet).
    """
    width = 1e-3
    sol = long_journal_film(R, C, eps, ETA, U_J, 64, width=width).solve()
    theta = sol.basis.doflocs[0] / R
    p_exact = cf.long_journal_sommerfeld_pressure(theta, R, C, eps, ETA, U_J)
    assert np.max(np.abs(sol.pressure - p_exact)) < 5e-5 * np.max(p_exact)
    W = cf.long_journal_sommerfeld_load(R, C, eps, ETA, U_J)
    Fx, Fy = sol.mode_forces["x"] / width, sol.mode_forces["y"] / width
    assert abs(Fx) < 1e-9 * W
    assert -Fy == pytest.approx(W, rel=1e-5)
    assert np.degrees(np.arctan2(-Fy, Fx)) == pytest.approx(90.0, abs=1e-6)


@pytest.mark.parametrize("eps", [0.3, 0.7])
def test_long_journal_half_sommerfeld(long_journal_film, eps):
    """Half Sommerfeld (Guembel): W_r = 12 eta U R^2 eps^2/(c^2 (2+eps^2)(1-eps^2)),
    W_t = 6 pi eta U R^2 eps/(c^2 (2+eps^2) sqrt(1-eps^2)); F_x = W_r, F_y = -W_t.

    U = omega R of the journal.  The zeros of the Sommerfeld pressure
    (theta = 0, pi) are mesh nodes, so the clipping is exact; P2 64
    elements, measured errors 5.7e-6 (W_r) and 3.7e-6 (W_t) at eps = 0.7.
    """
    width = 1e-3
    sol = long_journal_film(R, C, eps, ETA, U_J, 64, cavitation="half_sommerfeld", width=width).solve()
    W_r, W_t = cf.long_journal_half_sommerfeld_load(R, C, eps, ETA, U_J)
    assert sol.mode_forces["x"] / width == pytest.approx(W_r, rel=3e-5)
    assert -sol.mode_forces["y"] / width == pytest.approx(W_t, rel=3e-5)
    assert np.min(sol.pressure) == 0.0


# --------------------------------------------------------------------------
# 5. squeeze films (no sliding; approach velocity v = dh/dt < 0)

V = -1e-3  # m/s


def test_parallel_disks_squeeze():
    """F = 3 pi eta R^4 (-dh/dt)/(2 h^3), via the h0 mode velocity.

    The exact pressure is quadratic in r, so P2 is exact on the mesh's own
    domain; what remains is the polygonal approximation of the disk, an
    O(h^2) error: measured -1.35e-2 (refinement 3), -3.3e-3 (refinement 4).
    """
    radius, h = 5e-3, 10e-6
    errors = []
    for refinements in (3, 4):
        film = Film(meshes.disk(radius, refinements), FunctionGap(lambda x: np.full(x.shape[1:], h)), LUB,
                    mode_velocities={"h0": V}, element="P2")
        F = film.solve().mode_forces["h0"]
        errors.append(F / cf.parallel_disk_squeeze_force(radius, h, ETA, V) - 1.0)
    assert abs(errors[-1]) < 5e-3
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.1)  # second order in the mesh size


@pytest.mark.parametrize(
    "gap, r_eff",
    [(SpherePlane(5e-3, 1e-6), 5e-3), (SphereSphere(6e-3, 4e-3, 1e-6), 2.4e-3)],
    ids=["sphere-plane", "sphere-sphere"],
)
def test_sphere_squeeze_finite_domain(gap, r_eff):
    """F = 6 pi eta R^2 (-dh/dt)/h0 (1 - h0/h_edge)^2, parabolic gap, p = 0 on r = a.

    Domain radius a = 3 sqrt(2 R_eff h0) (h_edge = 10 h0), P2 on
    ``mesh.disk(a, 4)`` (545 vertices).  Measured error 4.2e-4 (2.7e-3 at
    refinement 3); asserted 1e-3 (the brief's 0.5 % at a modest mesh holds
    with a margin).  The squeeze enters once through ``squeeze=v`` and once
    through the ``h0`` mode velocity: the same force to round-off.
    """
    h0 = 1e-6
    a = 3.0 * np.sqrt(2.0 * r_eff * h0)
    m = meshes.disk(a, 4)
    F_mode = Film(m, gap, LUB, mode_velocities={"h0": V}, element="P2").solve().mode_forces["h0"]
    F_sq = Film(m, gap, LUB, squeeze=V, element="P2").solve().mode_forces["h0"]
    assert F_sq == pytest.approx(F_mode, rel=1e-12)
    assert F_mode == pytest.approx(cf.sphere_plane_squeeze_force(r_eff, h0, ETA, V, a), rel=1e-3)
    # the finite-domain correction matters at this domain size: 19 % below Reynolds' 6 pi eta R^2 v/h0
    assert F_mode < 0.85 * cf.sphere_plane_squeeze_force(r_eff, h0, ETA, V)


# --------------------------------------------------------------------------
# 7. finite-width inclined slider against its Fourier series


@pytest.mark.parametrize("cell, tol", [("quad", 1e-4), ("tri", 2e-4)])
def test_finite_slider_fourier(cell, tol):
    """Square pad (L = B = 50 mm), h_in = 2.2 h_out, p = 0 on all edges;
    runner (lower) at U along x, pad fixed: u_m = U/2.

    Reference: Fourier series in y, each mode ODE solved by Richardson-
    extrapolated finite differences (1e-9), 161 terms (truncation < 1e-7).
    P2 on a 16 x 16 mesh: measured errors 3.3e-5 (quad), 7.9e-5 (tri); both
    fall about 15x per halving.  The finite pad carries 44 % of the
    infinitely wide slider's load, so the side leakage is really tested.
    """
    h_out, h_in, L, B = 20e-6, 44e-6, 0.05, 0.05
    W_ref = cf.finite_slider_load(h_in, h_out, L, B, ETA, RUNNER / 2, n_terms=161)
    m = meshes.rectangle(np.linspace(0, L, 17), np.linspace(0, B, 17), cell=cell)
    sol = Film(m, InclinedSlider(h_in, h_out, L), LUB, velocity_lower=(RUNNER, 0.0), element="P2").solve()
    assert sol.load == pytest.approx(W_ref, rel=tol)
    W_wide = cf.inclined_slider_load(h_in, h_out, L, ETA, RUNNER / 2) * B
    assert 0.40 < W_ref / W_wide < 0.48
