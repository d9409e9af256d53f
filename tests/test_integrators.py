"""Verification of lubedyn.dynamics.integrators: convergence orders, stability polynomials,
energy against the analytic amplification factor, scipy DOP853, status codes, cache."""
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from numba import njit
from scipy.integrate import solve_ivp

from lubedyn.dynamics import integrators as I
from lubedyn.dynamics.errors import DynamicsInputError, IntegrationError

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from benchmarks import dynamics_tools  # noqa: E402


@njit(cache=True)
def smooth(t, y, args, dydt):
    """y0' = y0 cos t, y1' = -2 t y1^2: exact y0 = exp(sin t), y1 = 1 / (1 + t^2)."""
    dydt[0] = y[0] * math.cos(t)
    dydt[1] = -2.0 * t * y[1] * y[1]


def smooth_exact(t):
    t = np.asarray(t)
    return np.stack([np.exp(np.sin(t)), 1.0 / (1.0 + t * t)], axis=-1)


@njit(cache=True)
def linear(t, y, args, dydt):
    """y' = A y with A = args[0] (decay: A = [[-lambda]]; oscillator: [[0, 1], [-omega^2, 0]])."""
    A = args[0]
    for i in range(y.shape[0]):
        s = 0.0
        for j in range(y.shape[0]):
            s += A[i, j] * y[j]
        dydt[i] = s


def decay(lam):
    return (np.array([[-lam]]),)


def oscillator(omega):
    return (np.array([[0.0, 1.0], [-omega * omega, 0.0]]),)


@njit(cache=True)
def van_der_pol(t, y, args, dydt):
    mu = args[0]
    dydt[0] = y[1]
    dydt[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0]


@njit(cache=True)
def robertson(t, y, args, dydt):
    """Robertson's stiff chemical kinetics (Hairer & Wanner II, sec. IV.1)."""
    dydt[0] = -0.04 * y[0] + 1e4 * y[1] * y[2]
    dydt[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1]
    dydt[2] = 3e7 * y[1] * y[1]


@njit(cache=True)
def robertson_jac(t, y, args, J):
    J[0, 0] = -0.04
    J[0, 1] = 1e4 * y[2]
    J[0, 2] = 1e4 * y[1]
    J[1, 0] = 0.04
    J[1, 1] = -1e4 * y[2] - 6e7 * y[1]
    J[1, 2] = -1e4 * y[1]
    J[2, 0] = 0.0
    J[2, 1] = 6e7 * y[1]
    J[2, 2] = 0.0


@njit(cache=True)
def failing(t, y, args, dydt):
    """args[0] = 0: y' = y^2 (y(0) = 1: y = 1 / (1 - t) blows up at t = 1); otherwise a NaN derivative."""
    if args[0] == 0.0:
        dydt[0] = y[0] * y[0]
    else:
        dydt[0] = math.sqrt(-1.0 - y[0] * y[0])


BLOW_UP, NOT_A_NUMBER = (0.0,), (1.0,)


def rk4(rhs, y0, t_out, dt, args):
    """The RK4 kernel bound to rhs (numba-cached across test sessions)."""
    return I.kernel_for("rk4", rhs)(y0, t_out, dt, args)


def dopri5(rhs, y0, t_out, args, rtol, atol, h0, h_max, max_steps):
    return I.kernel_for("dopri5", rhs)(y0, t_out, args, rtol, atol, h0, h_max, max_steps)


def _fixed_dopri5(rhs, y0, t_out, h, args):
    """DOPRI5 forced to constant steps h (huge rtol: every step accepted; h0 = h_max = h)."""
    return dopri5(rhs, y0, t_out, args, 1e6, 1e6, h, h, 10**8)


def test_rk4_convergence_order():
    t_out = np.linspace(0.0, 2.0, 3)
    hs = 2.0 / np.array([16, 32, 64, 128])
    err = [np.abs(rk4(smooth, np.array([1.0, 1.0]), t_out, h, ())[0] - smooth_exact(t_out)).max() for h in hs]
    order = np.polyfit(np.log(hs), np.log(err), 1)[0]
    assert order == pytest.approx(4.0, abs=0.15)


def test_dopri5_fixed_step_order_and_dense_output_order():
    y0 = np.array([1.0, 1.0])
    hs = 2.0 / np.array([16, 32, 64, 128])
    grid_err, dense_err = [], []
    for h in hs:
        n = int(round(2.0 / h))
        t_grid = np.linspace(0.0, 2.0, n + 1)
        t_mid = np.concatenate([[0.0], t_grid[:-1] + 0.37 * h, [2.0]])  # inside steps: dense output only
        Y, st = _fixed_dopri5(smooth, y0, t_grid, h, ())
        assert st[I.ACCEPTED] == n and st[I.REJECTED] == 0
        grid_err.append(np.abs(Y - smooth_exact(t_grid)).max())
        Y, st = _fixed_dopri5(smooth, y0, t_mid, h, ())
        dense_err.append(np.abs(Y[1:-1] - smooth_exact(t_mid[1:-1])).max())
    p_grid = np.log2(np.array(grid_err[:-1]) / grid_err[1:])
    p_dense = np.log2(np.array(dense_err[:-1]) / dense_err[1:])
    # pairwise orders approach 5 from above (measured 5.58, 5.32, 5.19): pre-asymptotic h^6 terms
    assert np.all(np.diff(p_grid) < 0) and p_grid[-1] == pytest.approx(5.0, abs=0.25)
    # 4th-order continuous extension: local interpolation error O(h^5) that does not accumulate,
    # on top of the O(h^5) global error, so the sampled error also falls like h^5 (at least h^4)
    assert np.all(p_dense > 3.8) and p_dense[-1] == pytest.approx(5.0, abs=0.25)


def test_dopri5_tolerance_sweep_work_order():
    """Adaptive runs: error against number of steps falls like N^-5 (fifth-order method)."""
    t_out = np.linspace(0.0, 2.0, 21)
    errs, steps = [], []
    for tol in [1e-6, 1e-8, 1e-10, 1e-12]:
        Y, st = dopri5(smooth, np.array([1.0, 1.0]), t_out, (), tol, tol, 0.0, 0.0, 10**6)
        errs.append(np.abs(Y - smooth_exact(t_out)).max())
        steps.append(st[I.ACCEPTED])
        assert st[I.STATUS] == 0
        assert errs[-1] < 50 * tol  # tolerance proportionality (global error a few x tol)
    slope = np.polyfit(np.log(steps), np.log(errs), 1)[0]
    assert slope == pytest.approx(-5.0, abs=0.6)


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_stability_limit_matches_simulation(method):
    """The polynomial root is where a fixed-step oscillation starts to grow."""
    lim_im = I.stability_limit(method, "imaginary")
    lim_re = I.stability_limit(method, "real")
    if method == "rk4":
        assert lim_im == pytest.approx(2.0 * math.sqrt(2.0), rel=1e-9)
        assert lim_re == pytest.approx(2.785293563, rel=1e-8)  # Hairer-Wanner II, table IV.2.1 region
    else:
        assert lim_re == pytest.approx(3.3066, abs=1e-3)  # Hairer-Wanner II, fig. IV.2.1 (DOPRI5)
    omega = 1.0
    for factor, grows in [(0.98, False), (1.02, True)]:
        h = factor * lim_im / omega
        t_out = np.array([0.0, 4000 * h])
        y0 = np.array([1.0, 0.0])
        Y, _ = rk4(linear, y0, t_out, h, oscillator(omega)) if method == "rk4" else \
            _fixed_dopri5(linear, y0, t_out, h, oscillator(omega))
        assert (np.hypot(Y[-1, 0], Y[-1, 1]) > 1.0) == grows
    lam = 1.0
    for factor, grows in [(0.98, False), (1.02, True)]:
        h = factor * lim_re / lam
        t_out = np.array([0.0, 400 * h])
        Y, _ = rk4(linear, np.array([1.0]), t_out, h, decay(lam)) if method == "rk4" else \
            _fixed_dopri5(linear, np.array([1.0]), t_out, h, decay(lam))
        assert (abs(Y[-1, 0]) > 1.0) == grows


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_energy_of_undamped_oscillator_matches_amplification_factor(method):
    """1000 periods at h omega = 0.3: energy factor = |R(i h omega)|^(2N) from the stability polynomial."""
    omega = 2.0 * math.pi * 50.0
    n_per_period = int(round(2 * math.pi / 0.3))
    h = 2 * math.pi / omega / n_per_period
    n_steps = 1000 * n_per_period
    t_out = np.linspace(0.0, n_steps * h, 11)
    y0 = np.array([1.0, 0.0])
    if method == "rk4":
        Y, _ = rk4(linear, y0, t_out, h * (1 + 1e-13), oscillator(omega))
    else:
        Y, _ = _fixed_dopri5(linear, y0, t_out, h, oscillator(omega))
    energy = Y[:, 0] ** 2 + (Y[:, 1] / omega) ** 2
    R = np.polynomial.Polynomial(I.STABILITY_POLYNOMIALS[method])(1j * h * omega)
    expected = abs(R) ** (2 * n_steps)
    assert energy[-1] == pytest.approx(expected, rel=1e-8)
    assert abs(energy[-1] - 1.0) > 1e-6  # the check above is not trivially 1 = 1


def test_dopri5_agrees_with_scipy_dop853_on_van_der_pol():
    mu = 2.0
    t_out = np.linspace(0.0, 20.0, 201)
    res = I.integrate(van_der_pol, [2.0, 0.0], t_out, (mu,), rtol=1e-10, atol=1e-12)
    ref = solve_ivp(lambda t, y: [y[1], mu * (1 - y[0] ** 2) * y[1] - y[0]], (0.0, 20.0), [2.0, 0.0],
                    method="DOP853", t_eval=t_out, rtol=1e-13, atol=1e-14)
    # three limit cycles; error growth along the cycle ~1e2-1e3 x tolerance
    assert np.abs(res.y - ref.y.T).max() < 1e-7
    assert res.stats["Accepted steps [-]"] > 0 and res.stats["RHS evaluations [-]"] >= 6 * res.stats[
        "Accepted steps [-]"]
    rk = I.integrate(van_der_pol, [2.0, 0.0], t_out, (mu,), method="rk4", dt=2e-3)
    assert np.abs(rk.y - ref.y.T).max() < 1e-7  # (h = 2e-3)^4 * C


@pytest.mark.parametrize("progress, n_chunks", [(False, 1), (True, None), (False, 7)])
def test_driver_chunks_keep_accuracy(progress, n_chunks):
    t_out = np.linspace(0.0, 2.0, 41)
    res = I.integrate(smooth, [1.0, 1.0], t_out, (), rtol=1e-10, atol=1e-12, progress=progress, n_chunks=n_chunks)
    assert np.abs(res.y - smooth_exact(t_out)).max() < 5e-9


@pytest.mark.parametrize("kernel", ["compiled", "py_func"])
def test_generic_rk4_kernel_against_amplification_factor(kernel):
    h, lam = 0.1, 1.5
    k = I.rk4 if kernel == "compiled" else I.rk4.py_func
    Y, st = k(linear, np.array([1.0]), np.array([0.0, 0.3, 0.5]), h, decay(lam))
    z = -lam * h
    R = 1 + z + z * z / 2 + z ** 3 / 6 + z ** 4 / 24
    assert Y[:, 0] == pytest.approx([1.0, R ** 3, R ** 5], rel=1e-13)
    assert st[I.ACCEPTED] == 5 and st[I.NFEV] == 20 and st[I.STATUS] == 0


@pytest.mark.parametrize("kernel", ["compiled", "py_func"])
def test_generic_dopri5_kernel_against_exact(kernel):
    t_out = np.array([0.0, 0.25, 1.0])
    k = I.dopri5 if kernel == "compiled" else I.dopri5.py_func
    Y, st = k(linear, np.array([1.0]), t_out, decay(2.0), 1e-9, 1e-12, 0.0, 0.0, 1000)
    assert st[I.STATUS] == 0
    assert Y[:, 0] == pytest.approx(np.exp(-2.0 * t_out), rel=2e-8)


def test_status_max_steps_raises_with_last_good_sample():
    t_out = np.linspace(0.0, 10.0, 11)
    with pytest.raises(IntegrationError, match="max_steps") as info:
        I.integrate(van_der_pol, [2.0, 0.0], t_out, (2.0,), rtol=1e-10, atol=1e-12, max_steps=50)
    e = info.value
    assert e.status == I.STATUS_MAX_STEPS and 0.0 < e.t_reached < 10.0
    assert np.all(np.isfinite(e.y)) and e.y.shape == (len(e.t), 2) and e.t[-1] <= e.t_reached


def test_status_underflow_at_finite_time_blow_up():
    with pytest.raises(IntegrationError, match="underflow") as info:
        I.integrate(failing, [1.0], [0.0, 0.5, 2.0], BLOW_UP, rtol=1e-8, atol=1e-8)
    e = info.value
    assert e.status == I.STATUS_UNDERFLOW
    assert e.t_reached == pytest.approx(1.0, abs=1e-3)  # exact blow-up time t = 1
    assert e.y[-1, 0] == pytest.approx(2.0, rel=1e-6)  # last good sample y(0.5) = 1 / (1 - 0.5)


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_status_non_finite(method):
    with pytest.raises(IntegrationError, match="non-finite") as info:
        I.integrate(failing, [0.0], [0.0, 1.0], NOT_A_NUMBER, method=method, dt=0.1)
    assert info.value.status == I.STATUS_NONFINITE
    with pytest.raises(IntegrationError, match="non-finite"):  # RK4 overflows to inf before t = 2
        I.integrate(failing, [1.0], [0.0, 2.0], BLOW_UP, method="rk4", dt=1e-3)


def test_driver_input_errors():
    t = [0.0, 1.0]
    with pytest.raises(DynamicsInputError, match="method"):
        I.integrate(linear, [1.0], t, decay(1.0), method="euler")
    with pytest.raises(DynamicsInputError, match="dt"):
        I.integrate(linear, [1.0], t, decay(1.0), method="rk4")
    with pytest.raises(DynamicsInputError, match="strictly increasing"):
        I.integrate(linear, [1.0], [0.0, 1.0, 1.0], decay(1.0))
    with pytest.raises(DynamicsInputError, match="rtol"):
        I.integrate(linear, [1.0], t, decay(1.0), rtol=-1.0)
    with pytest.raises(DynamicsInputError, match="@njit"):
        I.integrate(lambda t, y, a, d: None, [1.0], t, ())
    with pytest.raises(DynamicsInputError, match="y0"):
        I.integrate(linear, [np.nan], t, decay(1.0))
    # k = 1e9 N/m, m = 3.5 g: omega = 5.35e5 rad/s, RK4 limit 2.83 / omega = 5.29 us
    omega = math.sqrt(1e9 / 3.5e-3)
    with pytest.raises(DynamicsInputError, match="stability limit"):
        I.integrate(linear, [1.0], t, decay(1.0), method="rk4", dt=6e-6, omega_max=omega)
    I.integrate(linear, [1.0], [0.0, 1e-4], decay(1.0), method="rk4", dt=5e-6, omega_max=omega)


def test_contact_study_accuracy_limits_the_step():
    """Hertz impact with k = 1e9 N/m, 3.5 g: the step that accuracy needs is below the stability limit."""
    out = dynamics_tools.contact_step_study(rk4_h_omega=(0.2, 2.8), rtols=())  # DOPRI5 part: numbers in the docstring
    assert out["Omega [rad/s]"] == pytest.approx(math.sqrt(1e9 / 3.5e-3))
    # Hertz impact duration 2.943 delta_max / v (Johnson, Contact Mechanics, eq. 11.24), delta_max from energy
    d_max = math.sqrt(1.875 * 3.5e-3 * 0.25 / 1e9)
    assert out["Contact duration [s]"] == pytest.approx(2.943 * d_max / 0.5, rel=1e-3)
    err_small, err_limit = (r["Rebound speed error [-]"] for r in out["rk4"])
    assert err_small < 1e-4 < 1e-2 < err_limit  # stable but inaccurate at the limit


def test_bound_kernel_hits_numba_cache_in_a_new_process(tmp_path):
    """The kernel bound to a module-level rhs compiles once (a fresh numba cache) and loads from the
    cache in the next process."""
    script = textwrap.dedent("""
        import numpy as np, sys
        sys.path.insert(0, sys.argv[1])
        from test_integrators import linear
        from lubedyn.dynamics import integrators as I
        k = I.kernel_for("rk4", linear)
        Y, st = k(np.array([1.0]), np.array([0.0, 1.0]), 0.5, (np.array([[-1.0]]),))
        print(len(k.stats.cache_hits), len(k.stats.cache_misses), Y[-1, 0])
    """)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    here = os.path.dirname(__file__)
    runs = [subprocess.run([sys.executable, "-c", script, here], env=env, capture_output=True, text=True,
                           check=True).stdout.split() for _ in range(2)]
    R = 1 - 0.5 + 0.125 - 0.5 ** 3 / 6 + 0.5 ** 4 / 24
    assert float(runs[1][2]) == pytest.approx(R * R, rel=1e-14)
    assert runs[0][:2] == ["0", "1"] and runs[1][:2] == ["1", "0"]


def test_ros2_fixed_step_order_two_py_func():
    """Plain-Python ROS2 kernel with constant steps (huge tolerances), forward-difference Jacobian."""
    y0 = np.array([1.0, 1.0])
    errs = []
    for n in (32, 64, 128):
        h = 2.0 / n
        t = np.linspace(0.0, 2.0, n + 1)
        Y, st = I.ros2.py_func(smooth, I.no_jac, y0, t, (), 1e6, 1e6, h, h, 10**6, True)
        assert st[I.ACCEPTED] == n and st[I.STATUS] == 0
        errs.append(np.abs(Y - smooth_exact(t)).max())
    orders = np.log2(np.array(errs[:-1]) / errs[1:])  # measured 2.14, 2.07
    assert orders[-1] == pytest.approx(2.0, abs=0.1)


def test_ros2_solves_stiff_robertson_against_radau():
    """Robertson to t = 40 against scipy Radau (rtol 1e-12), which reproduces Hairer & Wanner's
    reference y(40) = (0.7158270687, 9.185534764e-6, 0.2841637457).  ROS2 at rtol 1e-6 (global error
    ~1e-6 relative measured) in ~7000 steps with the analytic Jacobian."""
    t_out = np.array([0.0, 0.4, 4.0, 40.0])
    ref = solve_ivp(lambda t, y: [-0.04 * y[0] + 1e4 * y[1] * y[2],
                                  0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] ** 2, 3e7 * y[1] ** 2],
                    (0.0, 40.0), [1.0, 0.0, 0.0], method="Radau", t_eval=t_out, rtol=1e-12, atol=1e-16)
    assert ref.y[:, -1] == pytest.approx([0.7158270687, 9.185534764e-6, 0.2841637457], rel=1e-9)
    res = I.integrate(robertson, [1.0, 0.0, 0.0], t_out, (), method="ros2", rtol=1e-6, atol=1e-12,
                      jac=robertson_jac)
    assert np.abs(res.y[1:] / ref.y.T[1:] - 1.0).max() < 1e-5
    assert res.stats["Accepted steps [-]"] < 10_000


def test_dopri5_step_count_on_stiff_linear_problem_is_set_by_the_real_stability_limit():
    """y' = diag(-1e4, -1) y over 1 s: accuracy alone would need a few dozen steps; DOPRI5 takes
    lambda T / 3.3066 (real-axis stability limit) = 3024 steps whatever the tolerance (measured 3029,
    3037, 3057 at 1e-3, 1e-5, 1e-7: the controller rides the stability boundary)."""
    A = (np.array([[-1e4, 0.0], [0.0, -1.0]]),)
    counts = [I.integrate(linear, [1.0, 1.0], [0.0, 1.0], A, rtol=tol, atol=tol).stats["Accepted steps [-]"]
              for tol in (1e-3, 1e-5)]
    expected = 1e4 / I.stability_limit("dopri5", "real")
    assert counts[0] == pytest.approx(expected, rel=0.03)
    assert counts[1] == pytest.approx(expected, rel=0.03)


# RK4 growth guard ---------------------------------------------------------------------------------
def _rk4_oscillator(h_omega, omega=1e5, periods=20):
    """integrate() with RK4 on x'' = -omega^2 x (unscaled state (x, v): |v| = omega |x|), one step per
    output interval, no omega_max: the bare call the guard must protect."""
    h = h_omega / omega
    n = int(round(periods * 2 * math.pi / h_omega))
    return I.integrate(linear, [1.0, 0.0], np.arange(n + 1) * h, oscillator(omega), method="rk4",
                       dt=h * (1 + 1e-13))


def test_rk4_guard_pins_the_oscillation_limit():
    """RK4 without omega_max past its stability limit used to return finite garbage
    (|x|/x0 = 20 after 20 periods at h omega = 2.86, 1e20 at 3.49).  Just below the limit 2 sqrt 2 =
    2.828 the run completes and equals the amplification factor |R(i h omega)|^N (the guard changes
    nothing); at 2.86 and 3.49 it stops with STATUS_UNSTABLE, names the imaginary-axis limit and the
    stable step 2.828/omega, within the first quarter of the run (10 and 4 steps), and the samples have grown to
    2.1x (2.86) and 76x (3.49: |R| = 3.7 a step) instead of 20x and 1e20 (the guard stops once |f(y)|
    has doubled over >= 5 steps above the limit; bounds asserted 2.5x and 200x).  The stage estimate of h omega is exact
    for J^2 = -omega^2 I at any state scaling (omega = 1e5 here); margins: 2.80 is 1 % below the
    limit, 2.86 1.1 % above it."""
    res = _rk4_oscillator(2.80)
    n = res.t.size - 1
    R = abs(np.polynomial.Polynomial(I.STABILITY_POLYNOMIALS["rk4"])(2.80j))
    amp = np.hypot(res.y[-1, 0], res.y[-1, 1] / 1e5)
    assert amp == pytest.approx(R ** n, rel=1e-8) and amp < 0.1
    assert res.stats["Largest estimated h*|lambda| (RK4) [-]"] == pytest.approx(2.80, rel=1e-9)
    assert res.stats["Integrator stop reason"] == "reached the last output time"
    for h_omega, growth in ((2.86, 2.5), (3.49, 200.0)):
        with pytest.raises(IntegrationError, match=r"beyond the RK4 stability limit.*estimated \|h lambda\| = "
                           rf"{h_omega:.3g} > 2\.828 \(imaginary axis: an oscillation\).*a stable step is "
                           r"dt <= 2\.828e-05 s") as info:
            _rk4_oscillator(h_omega)
        e = info.value
        assert e.status == I.STATUS_UNSTABLE
        assert np.abs(e.y[:, 0]).max() < growth and e.t_reached < 0.25 * 20 * 2 * math.pi / 1e5


def test_rk4_guard_pins_the_real_axis_limit_and_ignores_growth():
    """A decay y' = -y: h = 2.78 runs (below the real-axis limit 2.785, the result is R(-2.78)^N
    exactly), h = 2.80 stops naming the real-axis limit.  A growing solution is not an instability:
    y' = +y at h = 3 (|h lambda| beyond every limit, but lambda > 0) runs to its (inaccurate) end, and
    the blow-up y' = y^2 still stops as non-finite (test_status_non_finite), not as unstable."""
    t_out = np.arange(201) * 2.78
    res = I.integrate(linear, [1.0], t_out, decay(1.0), method="rk4", dt=2.78 * (1 + 1e-13))
    R = np.polynomial.Polynomial(I.STABILITY_POLYNOMIALS["rk4"])(-2.78)
    assert res.y[-1, 0] == pytest.approx(R ** 200, rel=1e-10)
    with pytest.raises(IntegrationError, match=r"> 2\.785 \(real axis: a decay\).*a stable step is dt <= 2\.785 s"):
        I.integrate(linear, [1.0], np.arange(201) * 2.80, decay(1.0), method="rk4", dt=2.80 * (1 + 1e-13))
    grow = I.integrate(linear, [1.0], np.arange(21) * 3.0, decay(-1.0), method="rk4", dt=3.0 * (1 + 1e-13))
    R = np.polynomial.Polynomial(I.STABILITY_POLYNOMIALS["rk4"])(3.0)
    assert grow.y[-1, 0] == pytest.approx(R ** 20, rel=1e-10)


def test_rk4_guard_never_changes_a_stable_run():
    """The guard only reads the stages: van der Pol (a nonlinear relaxation cycle) gives bit-identical
    states and counters with the guard on and off, and the estimate stays far below the limit."""
    kernel = I.resumable_kernel("rk4", van_der_pol)
    t_out = np.linspace(0.0, 20.0, 201)
    out = []
    for guard in (False, True):
        Y, work = I.new_run(np.array([2.0, 0.0]), t_out)
        kernel(t_out, (2.0,), I.make_params(dt=2e-3, guard=guard), Y, work, t_out.size)
        out.append((Y, I.run_stats(work)))
        assert work[I.W_STATUS] == I.STATUS_OK
    assert np.array_equal(out[0][0], out[1][0]) and np.array_equal(out[0][1], out[1][1])
    assert 0.0 < work[I.W_HRHO_MAX] < 0.1  # van der Pol mu = 2 has |lambda| <~ 10: h |lambda| <~ 0.02


@njit(cache=True)
def stiffening(t, y, args, dydt):
    """x'' = -omega0^2 (1 + s) x with s' = args[1]: a contact that stiffens along the run."""
    dydt[0] = y[1]
    dydt[1] = -args[0] ** 2 * (1.0 + y[2]) * y[0]
    dydt[2] = args[1]


def test_rk4_omega_max_callable_is_checked_after_every_chunk():
    """The dynamics scene passes model.omega_max (a callable): it is evaluated at y0 (refused there as
    input beyond the limit) and at the state after every chunk.  Here omega = omega0 sqrt(1 + s) with s
    = 1.1 t (omega0 = 1): dt omega crosses 2.828 at s = (2.828/dt)^2 - 1 = 7 (t = 6.36) for dt = 1; with
    20 chunks of 1 s the run stops at the chunk end t = 7 (s = 7.7, dt omega = 2.950), naming dt *
    omega_max(y) and the stable step 2.828 / 2.950 = 0.9589 s.  With a float at t0 only, the growth
    guard stops it later (t = 13, the estimate 3.98 then; true dt omega = 3.9), before the state
    overflows."""
    omega_of = lambda y: math.sqrt(1.0 + y[2])  # noqa: E731
    t_out = np.arange(21.0)  # one step of dt = 1 s per output interval
    with pytest.raises(IntegrationError, match=r"dt \* omega_max\(y\) = 2\.95 > 2\.828 at the state reached; "
                                               r"a stable step is dt <= 0\.9589 s") as info:
        I.integrate(stiffening, [1.0, 0.0, 0.0], t_out, (1.0, 1.1), method="rk4", dt=1.0, omega_max=omega_of,
                    n_chunks=20)
    assert info.value.status == I.STATUS_UNSTABLE and info.value.t_reached == pytest.approx(7.0)
    with pytest.raises(DynamicsInputError, match="beyond the RK4 stability limit"):
        I.integrate(stiffening, [1.0, 0.0, 9.0], t_out, (1.0, 1.1), method="rk4", dt=1.0, omega_max=omega_of)
    with pytest.raises(IntegrationError, match="estimated") as info:
        I.integrate(stiffening, [1.0, 0.0, 0.0], t_out, (1.0, 1.1), method="rk4", dt=1.0, omega_max=1.0)
    assert 7.0 < info.value.t_reached < 16.0 and np.isfinite(info.value.y).all()
