"""Time integrators: classical RK4, Dormand-Prince 5(4) and Rosenbrock ROS2, whole time loop in numba.

Right-hand side contract
------------------------
A right-hand side is an ``@njit`` function ``rhs(t, y, args, dydt) -> None``
(float64 ``t``, float64[:] ``y``, ``args`` any numba-typable tuple passed
through unchanged; it writes ``dydt`` in place).

Kernels
-------
``rk4(rhs, y0, t_out, dt, args)``
    Classical fourth-order Runge-Kutta (Butcher 1/2, 1/2, 1; weights
    1/6, 1/3, 1/3, 1/6).  It steps *exactly onto the output times*: the
    interval ``[t_out[i-1], t_out[i]]`` is cut into ``ceil(interval / dt)``
    equal steps, so every step is <= ``dt`` and no interpolation is involved.
``dopri5(rhs, y0, t_out, args, rtol, atol, h0, h_max, max_steps)``
    Dormand-Prince 5(4) (FSAL, local extrapolation) as in Hairer, Norsett and
    Wanner, *Solving ODEs I*, 2nd ed., sec. II.4-II.6 and their code DOPRI5:
    error norm ``sqrt(mean((e_i / (atol + rtol max(|y_i|, |y1_i|)))^2))``, PI
    (Lund-stabilised) step control ``h_new = h / max(1/10, min(5, err^(0.2 -
    0.75 beta) / err_old^beta / 0.9))`` with beta = 0.04, no step increase right
    after a rejection, initial step from Hairer's ``hinit`` when ``h0 <= 0``.
    Output times are filled by the 4th-order continuous extension (dense
    output coefficients d1..d7 of Dormand & Prince / Shampine); the last step
    is shortened to land exactly on ``t_out[-1]`` so that a continuation starts
    from a true step value.

Both return ``(Y, stats)``: ``Y`` of shape ``(len(t_out), len(y0))``, rows not
reached are NaN, and the float64 array ``stats`` indexed by the constants
``ACCEPTED, REJECTED, NFEV, STATUS, T_REACHED, H_NEXT, N_FILLED`` (status: 0 ok,
1 ``max_steps`` reached, 2 step-size underflow, 3 non-finite state, 4 unstable
fixed step (RK4's growth guard, on in :func:`integrate`; see its Notes); ``H_NEXT``
is the step proposed for a continuation; ``N_FILLED`` the number of valid rows).

Resumable runs
--------------
Underneath, each method is one *resumable* kernel ``kernel(t_out, args,
params, Y, work, i_stop)`` (callables first in the generic form): ``Y`` holds
the output rows, ``work`` the integrator's complete state (t, the next step h,
the PI controller's memory, the rejection flag, the step counters, the current
state and the derivative at it: DOPRI5's FSAL stage, ROS2's f0), and a call
returns as soon as ``i_stop`` rows are filled, after a whole step (rows that
step passed beyond ``i_stop`` come from its dense output as in one call).  The
next call goes on from ``work``, so a run split into any number of calls is
bit-identical to one call: :func:`integrate` splits a run only to update its
progress bar, and the bar cannot change a result (``tests/test_chunking.py``).
The one-call forms above (:class:`OneShot`) allocate ``Y`` and ``work``
(:func:`new_run`) and make a single call.

Caching
-------
:func:`specialise` binds a right-hand side to a kernel source through a numba function pointer
(:mod:`lubedyn.dynamics.specialise`): the kernel is compiled once per argument types, for any right-hand
side, and numba caches it across processes; the right-hand side is compiled once for the signature
the kernel calls it with.  The generic kernels ``rk4``/``dopri5``/``ros2`` take the right-hand side as
a plain argument (numba then specialises on its identity and cannot cache them across processes).

Stiff problems: ``ros2(rhs, jac, y0, t_out, args, rtol, atol, h0, h_max, max_steps, use_fd)``
-----------------------------------------------------------------------------------------------
The two-stage L-stable Rosenbrock method ROS2 of Verwer, Spee, Blom &
Hundsdorfer (SIAM J. Sci. Comput. 20, 1999), gamma = 1 + 1/sqrt(2):
(I - gamma h J) k1 = f(t, y), (I - gamma h J) k2 = f(t + h, y + h k1) - 2 k1,
y_new = y + h (3/2 k1 + 1/2 k2), second order (for any W, so an inexact J
costs no order), embedded first-order Rosenbrock-Euler y + h k1 for the error
estimate h (k1 + k2) / 2, step factor 0.9 err^(-1/2) in [0.2, 5], dense
output by cubic Hermite interpolation (3rd order).  J is a user ``jac(t, y,
args, J)`` or forward differences (n extra rhs calls per accepted step); one
inverse of W per step.  Same ``(Y, stats)`` contract as DOPRI5.

Stiffness of the ball contacts (measured with ``benchmarks/dynamics_tools.py``)
-------------------------------------------------------------------------------
A ball of 3.5 g on a contact of stiffness k = 1e9 N/m has omega = sqrt(k/m)
= 5.3e5 rad/s.  Explicit stability on the imaginary axis (:func:`stability_limit`,
computed from the stability polynomials): RK4 |h omega| <= 2 sqrt(2) = 2.83;
DOPRI5 only <= 0.997 strictly (|R(i y)| - 1 = 1.4e-6 at y = 1, 3e-3 at 1.5;
its real-axis limit is 3.31, the "~3.3" often quoted), so an undamped mode
must be resolved by DOPRI5 anyway.  For an elastic Hertz impact (3.5 g, 0.5
m/s, k = 1e9 N/m at the largest deflection, contact 7.5 us) the rebound speed
error of RK4 is 5e-8, 4.4e-6, 3.4e-4, 6.6e-3, 6.6e-2, 0.26 at h omega = 0.1,
0.2, 0.5, 1, 2, 2.8: a 1e-4 answer needs h omega ~ 0.3, about ten times below
the RK4 limit, and DOPRI5 chooses mean h omega = 0.58 / 0.22 / 0.086 across the
contact at rtol = 1e-4 / 1e-6 / 1e-8 (rebound errors 5e-4, 1.5e-5, 5.6e-7).
Accuracy, not stability, sets the step, so ROS2 (which would still have to
resolve the contact, at an n x n Jacobian and inverse per step) is not the
default for the ball collisions; it is there for scenes with a stiff mode
that is not of interest (e.g. a very stiff film damper).  The driver refuses
an RK4 step beyond the stability limit when the caller gives the highest
frequency ``omega_max`` (a callable ``omega_max(y)`` is checked again after
every chunk), and RK4's growth guard stops a run whose stages show a mode
beyond the limit that grows (:func:`integrate`, Notes).

Stiffness of the cage-less bearing (measured, benchmarks/dynamics.py)
----------------------------------------------------------------------
At the start of the rotor drop adaptive DOPRI5 is held near 2.3 us by a
*real* eigenvalue of -1.48e6 1/s (real-axis limit 3.31/1.48e6 = 2.2 us),
not by the contacts (largest |Im lambda| 2.7e5 rad/s): the linearised race
traction F_t = -(mu_lim Q / max(s0 u_e, v_reg)) v_s acts on a ball as a
dashpot of rate c_t (1/m + R^2/J) = 3.5 c_t/m.  With the balls at rest
(u_e = 0) the slope is set by the regularisation speed v_reg = 0.05 m/s, a
numerical choice (mu_lim = 0.07, Q ~ 620 N: c_t ~ 870 N s/m, rate 8.7e5 1/s
per contact, ~1.5e6 for a ball slipping on both races).  Once the
entrainment exceeds v_reg/s0 = 2.5 m/s the slope mu_lim/(s0 u_e) is the
closed-form EHL traction curve's (limit reached near SRR 2 %, as measured
traction curves) and falls as 1/u_e (about 2e5 1/s at 10,000 rpm, no longer
limiting).  Trade-off (2 ms of the drop, initial state): v_reg x 10 cuts
DOPRI5's steps 3.9 x at rtol 1e-3 but only 1.26 x at rtol 1e-6, where
accuracy limits the step; no race traction at all: 4.5 x fewer steps at
1e-6.  Implicit methods do not pay here: scipy's BDF and Radau (with the
bearing's ``jac_sparsity``) take 3-10 x fewer rhs calls than DOPRI5 before
the first ball collision, but across the collisions (1-2 ms) they do not get
below 1.9 delta_H of ball-position error up to rtol 1e-5 (the collision
phases switch the force law), and ROS2 with a finite-difference Jacobian
(n + 2 rhs calls and an n x n inverse per step, n = 205) costs ~100-200 x
DOPRI5 at equal error.  An implicit step would need a sparse analytic
Jacobian and a bordered block-tridiagonal solve to compete (not done).
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

import numpy as np
from numba import njit
from numba import types as _nt

from .errors import DynamicsInputError, IntegrationError
from .specialise import entry_point, register_kernel, specialise


# Copies into slices by explicit loops, in compiled kernels: numba compiles an array-to-slice assignment
# (``a[:] = b``) with its shape-mismatch error message (string formatting), about 1.7 s of compile time for
# each combination of dimensions in every process that compiles a kernel; the loops give the same values
# without it.  A row: ``put(Y[i], 0, y)``.
@njit(cache=True, inline="always")
def put(dst, start, src):
    """dst[start:start + len(src)] = src (1-D)."""
    for i in range(src.shape[0]):
        dst[start + i] = src[i]


@njit(cache=True, inline="always")
def put2(dst, src):
    """dst[:, :] = src (2-D)."""
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            dst[i, j] = src[i, j]


logger = logging.getLogger(__name__)

#: Largest ``integrator.rtol`` whose error DOPRI5 controls (the dynamics and tapered scenes refuse more).
#: Measured through :func:`integrate` on the undamped oscillator x'' = -(2 pi)^2 x
#: (x0 = 1, v0 = 0, atol = 1e-3 rtol): end error |(x, v / omega) - exact| / amplitude, as a multiple of
#: rtol, after 10 / 100 / 1,000 periods; after 10,000 periods the error and (the amplitude reached);
#: h omega is the mean accepted step (tests/test_dyn_health.py repeats the 1e-3 and 3e-3 rows)::
#:
#:     rtol   h omega   10 periods   100 periods   1,000 periods   10,000 periods
#:     1e-6   0.19      5.9 rtol     59 rtol       590 rtol        5.9e-3 (0.99)
#:     1e-4   0.50      7.9 rtol     79 rtol       780 rtol        0.62 (0.61: DOPRI5's own damping)
#:     1e-3   0.84      13 rtol      140 rtol      1,200 rtol      0.95 (0.21)
#:     2e-3   0.97      14 rtol      150 rtol      1,100 rtol      12 (12: growing)
#:     3e-3   1.05      15 rtol      170 rtol      960 rtol        2.3e4 (2.3e4)
#:     1e-2   1.28      18 rtol      300 rtol      3.6e6 rtol      3.8e45
#:     0.1    -         41 rtol      9.3e8 rtol    3.5e81 rtol     -
#:
#: Up to 1e-3 the error is proportional to rtol (within 2.3 x of its tight-tolerance multiple at every
#: run length).  Between 2e-3 and 3e-3 the accepted steps pass DOPRI5's stability limit on the imaginary
#: axis, h omega = 0.997 (:func:`stability_limit`): an undamped oscillation then
#: grows at every step and, since a relative tolerance grows with the solution, the error control never
#: rejects the growth; the error grows exponentially with the run's length (2.3e4 x the amplitude after
#: 1e4 periods at 3e-3; 4.1 x after only 10 periods at 0.1, 3.6e4 x at 0.9) while the run reports
#: "reached the last output time".  The bearings' contacts are such oscillations (1e5-5e5 rad/s:
#: thousands of periods in a run).
RTOL_MAX = 1e-3
#: Largest ``integrator.atol``.  An absolute tolerance does not grow with the solution, so its error
#: stays proportional at any size (same oscillator, amplitude A, rtol 1e-10: end error 40-44 atol per
#: 100 periods for atol / A = 1e-9 ... 1): what makes it meaningless is an atol near the smallest
#: motion a run resolves.  The bearing states are SI (m, m/s, rad, rad/s) and resolve contact
#: deflections and films of a micrometre and below; a 1 um vibration ends 100 periods 0.4 of its
#: amplitude off at atol = 1e-8, 1.2 x at 3e-8.
ATOL_MAX = 1e-8
RTOL_WHY = (f"DOPRI5's error control stops bounding the error above rtol = {RTOL_MAX:g}: measured on an undamped "
            "oscillator, its steps pass the stability limit h omega = 0.997 near rtol = 2e-3 and the error "
            "then grows without bound with the run's length, 2.3e4 x the amplitude after 1e4 periods at 3e-3")
ATOL_WHY = (f"an absolute error above {ATOL_MAX:g} (m, m/s, rad, rad/s) is not small against the micrometre "
            "contact deflections and films a bearing run resolves: measured, a 1 um oscillation ends 100 periods "
            "0.4 of its amplitude off at atol = 1e-8")

# stats indices and status codes ------------------------------------------------
ACCEPTED, REJECTED, NFEV, STATUS, T_REACHED, H_NEXT, N_FILLED = range(7)
N_STATS = 7
STATUS_OK, STATUS_MAX_STEPS, STATUS_UNDERFLOW, STATUS_NONFINITE, STATUS_UNSTABLE = 0, 1, 2, 3, 4
STATUS_MESSAGES = {
    STATUS_OK: "ok",
    STATUS_MAX_STEPS: "the step budget max_steps was used up",
    STATUS_UNDERFLOW: "the step size underflowed (h below 10 x machine epsilon x |t|)",
    STATUS_NONFINITE: "the state or its derivative became non-finite (NaN/inf)",
    STATUS_UNSTABLE: "the fixed step is beyond the RK4 stability limit (the solution grows from step to step)",
}

# Dormand-Prince 5(4) coefficients (Hairer's DOPRI5) ----------------------------
C2, C3, C4, C5 = 0.2, 0.3, 0.8, 8.0 / 9.0
A21 = 0.2
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
A71, A73, A74, A75, A76 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0,
                          22.0 / 525.0, -1.0 / 40.0)
D1, D3, D4, D5, D6, D7 = (-12715105075.0 / 11282082432.0, 87487479700.0 / 32700410799.0,
                          -10690763975.0 / 1880347072.0, 701980252875.0 / 199316789632.0,
                          -1453857185.0 / 822651844.0, 69997945.0 / 29380423.0)
BETA = 0.04
EXPO1 = 0.2 - 0.75 * BETA
SAFE = 0.9
FACC1 = 1.0 / 0.2  # largest step decrease 1/5
FACC2 = 1.0 / 10.0  # largest step increase 10
UROUND = 2.3e-16
MAX_NONFINITE_TRIALS = 20

#: stability polynomials R(z) (coefficients of z^0, z^1, ...) of the explicit methods
STABILITY_POLYNOMIALS = {
    "rk4": (1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0),
    "dopri5": (1.0, 1.0, 1.0 / 2.0, 1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0, 1.0 / 600.0),
}
METHODS = ("dopri5", "rk4", "ros2")


# small helpers (no rhs: ordinary cached kernels) ------------------------------
@njit(cache=True)
def _load_state(work):
    """The adaptive kernels' (DOPRI5, ROS2) resumable counters from ``work``: (t, h, accepted,
    rejected, nfev, status, h_next, filled, n_nonfinite, phase)."""
    return (work[W_T], work[W_H], int(work[W_ACCEPTED]), int(work[W_REJECTED]), int(work[W_NFEV]),
            int(work[W_STATUS]), work[W_H_NEXT], int(work[W_FILLED]), int(work[W_NONFINITE]), work[W_PHASE])


@njit(cache=True)
def _store_state(work, y, f, t, h, accepted, rejected, nfev, status, h_next, filled, n_nonfinite, phase):
    """Write back what :func:`_load_state` read, with the state ``y`` and its derivative ``f``."""
    n = y.shape[0]
    put(work, N_WORK_SCALARS, y)
    put(work, N_WORK_SCALARS + n, f)
    work[W_T] = t
    work[W_H] = h
    work[W_ACCEPTED] = accepted
    work[W_REJECTED] = rejected
    work[W_NFEV] = nfev
    work[W_STATUS] = status
    work[W_H_NEXT] = h_next
    work[W_FILLED] = filled
    work[W_NONFINITE] = n_nonfinite
    work[W_PHASE] = phase


@njit(cache=True)
def _budget_status(accepted, rejected, max_steps, t, h):
    """STATUS_MAX_STEPS when the step budget is spent, STATUS_UNDERFLOW when the step is below the
    round-off of t, else STATUS_OK (checked before every adaptive step)."""
    if accepted + rejected >= max_steps:
        return STATUS_MAX_STEPS
    if 0.1 * abs(h) <= abs(t) * UROUND or h <= 0.0:
        return STATUS_UNDERFLOW
    return STATUS_OK


@njit(cache=True)
def _all_finite(x):
    for v in x:
        if not np.isfinite(v):
            return False
    return True


@njit(cache=True)
def _dense_eval(rcont, theta, out):
    """Dormand-Prince continuous extension at ``theta = (t - t_old) / h`` (Hairer's CONTD5)."""
    theta1 = 1.0 - theta
    for j in range(out.shape[0]):
        out[j] = rcont[0, j] + theta * (rcont[1, j] + theta1 * (rcont[2, j] + theta * (
            rcont[3, j] + theta1 * rcont[4, j])))


# resumable kernels ---------------------------------------------------------------
# A kernel advances a run held in two arrays and may be called any number of times: ``Y`` (m, n) the
# output rows (row 0 = y0) and ``work`` the integrator's complete state (the scalars below, then the
# current state y and the derivative at it: DOPRI5's FSAL stage k1, ROS2's f0).  A call returns once
# ``i_stop`` rows are filled (a step is never cut short for it: rows the last step passed are filled from
# its dense output, and the next call goes on from the state after that step), when the run ends or
# when it fails.  Every quantity that decides the next step (t, h, the PI controller's memory, the
# rejection flag, the counters, the step budget) lives in ``work``, so any split into calls gives the
# bit-identical run of a single call: a progress display cannot change a result.
W_T, W_H, W_FACOLD, W_REJECT, W_ACCEPTED, W_REJECTED, W_NFEV, W_STATUS, W_H_NEXT, W_FILLED, W_NONFINITE, \
    W_PHASE, W_HRHO, W_HRHO_MAX, W_UNSTABLE_STEPS, W_STREAK_NORM, W_LIMIT = range(17)
N_WORK_SCALARS = 17  # y at [N_WORK_SCALARS, N_WORK_SCALARS + n), the derivative at y after it
PHASE_NEW, PHASE_RUNNING, PHASE_DONE = 0.0, 1.0, 2.0
# params (float64 array) of a kernel call
P_RTOL, P_ATOL, P_H_MAX, P_MAX_STEPS, P_USE_FD, P_DT, P_GUARD = range(7)
N_PARAMS = 7

# RK4 growth guard (see `_rk4_impl`): limits of |h lambda| on the imaginary and the real axis (values of
# `stability_limit`, pinned in tests/test_integrators.py), the consecutive steps beyond the limit and the
# growth of |f(y)| over them that stop a run
RK4_LIMIT_IMAGINARY = 2.0 * math.sqrt(2.0)
RK4_LIMIT_REAL = 2.785293563405282
GUARD_MIN_STEPS = 5
GUARD_GROWTH = 2.0


# kernel sources: the callables (rhs, jac) are the leading parameters; see `specialise` ------------
def _rk4_impl(rhs, t_out, args, params, Y, work, i_stop):
    n = Y.shape[1]
    m = t_out.shape[0]
    dt = params[P_DT]
    guard = params[P_GUARD] != 0.0
    y = work[N_WORK_SCALARS:N_WORK_SCALARS + n].copy()
    hrho_max = work[W_HRHO_MAX]
    last_hrho = work[W_HRHO]
    unstable_steps = int(work[W_UNSTABLE_STEPS])
    streak_norm = work[W_STREAK_NORM]
    last_limit = work[W_LIMIT]
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    accepted = int(work[W_ACCEPTED])
    filled = int(work[W_FILLED])
    status = int(work[W_STATUS])
    t_reached = work[W_T] if work[W_PHASE] != PHASE_NEW else t_out[0]
    if status == STATUS_OK and work[W_PHASE] != PHASE_DONE:
        for i in range(filled, min(i_stop, m)):
            t_start = t_out[i - 1]
            interval = t_out[i] - t_start
            nsub = max(1, int(math.ceil(interval / dt * (1.0 - 1e-12))))
            h = interval / nsub
            for s in range(nsub):
                t = t_start + s * h
                rhs(t, y, args, k1)
                for j in range(n):
                    tmp[j] = y[j] + 0.5 * h * k1[j]
                rhs(t + 0.5 * h, tmp, args, k2)
                for j in range(n):
                    tmp[j] = y[j] + 0.5 * h * k2[j]
                rhs(t + 0.5 * h, tmp, args, k3)
                for j in range(n):
                    tmp[j] = y[j] + h * k3[j]
                rhs(t + h, tmp, args, k4)
                for j in range(n):
                    tmp[j] = y[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                if not _all_finite(tmp):
                    status = STATUS_NONFINITE
                    break
                if guard:
                    # h^2 J^2 from the stages: k2 - k1 = J (h/2) k1 and k3 - k2 = J (h/2) (k2 - k1) (k2, k3 at
                    # the same time), so k3 - k2 = (h/2)^2 J^2 k1 to first order, a power iterate of J^2
                    s11 = 0.0
                    s21 = 0.0
                    s31 = 0.0
                    s33 = 0.0
                    for j in range(n):
                        d = k3[j] - k2[j]
                        s11 += k1[j] * k1[j]
                        s21 += (k2[j] - k1[j]) * k1[j]
                        s31 += d * k1[j]
                        s33 += d * d
                    if s11 > 0.0:
                        hrho = 2.0 * math.sqrt(math.sqrt(s33 / s11))
                        # sign of (h lambda)^2: negative for an oscillation (limit on the imaginary axis);
                        # a real lambda > 0 (k2 - k1 = (h/2) J k1 along k1) is growth of the exact solution,
                        # where RK4 is stable at any step (R(z) < e^z): never counted
                        if s31 < 0.0:
                            limit = RK4_LIMIT_IMAGINARY
                        elif s21 < 0.0:
                            limit = RK4_LIMIT_REAL
                        else:
                            limit = math.inf
                        if hrho > hrho_max:
                            hrho_max = hrho
                        if hrho > limit:
                            if unstable_steps == 0:
                                streak_norm = math.sqrt(s11)
                            unstable_steps += 1
                            last_hrho = hrho
                            last_limit = limit
                            if unstable_steps >= GUARD_MIN_STEPS and math.sqrt(s11) >= GUARD_GROWTH * streak_norm:
                                status = STATUS_UNSTABLE
                                work[W_H] = h  # the step taken (<= dt: output intervals are cut evenly)
                                break
                        else:
                            unstable_steps = 0
                put(y, 0, tmp)
                accepted += 1
                t_reached = t + h
            if status != STATUS_OK:
                break
            t_reached = t_out[i]
            put(Y[i], 0, y)
            filled = i + 1
    put(work, N_WORK_SCALARS, y)
    work[W_T] = t_reached
    work[W_ACCEPTED] = accepted
    work[W_NFEV] = 4 * accepted + (4 if (status == STATUS_NONFINITE or status == STATUS_UNSTABLE) else 0)
    work[W_HRHO] = last_hrho
    work[W_HRHO_MAX] = hrho_max
    work[W_UNSTABLE_STEPS] = unstable_steps
    work[W_STREAK_NORM] = streak_norm
    work[W_LIMIT] = last_limit
    work[W_STATUS] = status
    work[W_H_NEXT] = dt
    work[W_FILLED] = filled
    work[W_PHASE] = PHASE_DONE if (status != STATUS_OK or filled >= m) else PHASE_RUNNING


def _dopri5_impl(rhs, t_out, args, params, Y, work, i_stop):
    n = Y.shape[1]
    m = t_out.shape[0]
    rtol = params[P_RTOL]
    atol = params[P_ATOL]
    h_max = params[P_H_MAX]
    max_steps = params[P_MAX_STEPS]
    y = work[N_WORK_SCALARS:N_WORK_SCALARS + n].copy()
    k1 = work[N_WORK_SCALARS + n:N_WORK_SCALARS + 2 * n].copy()
    y1 = np.empty(n)
    ytmp = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    k5 = np.empty(n)
    k6 = np.empty(n)
    k7 = np.empty(n)
    rcont = np.empty((5, n))
    t_end = t_out[m - 1]
    if h_max <= 0.0:
        h_max = t_end - t_out[0]
    t, h, accepted, rejected, nfev, status, h_next, filled, n_nonfinite, phase = _load_state(work)
    facold = work[W_FACOLD]
    reject = work[W_REJECT] != 0.0
    if phase == PHASE_NEW:
        t = t_out[0]
        rhs(t, y, args, k1)
        nfev = 1
        h_next = 0.0
        facold = 1e-4
        reject = False
        n_nonfinite = 0
        phase = PHASE_RUNNING
        if not (_all_finite(y) and _all_finite(k1)):
            status = STATUS_NONFINITE
        elif m > 1:
            if h <= 0.0:  # Hairer's HINIT, order 5
                dnf = 0.0
                dny = 0.0
                for j in range(n):
                    sk = atol + rtol * abs(y[j])
                    dnf += (k1[j] / sk) ** 2
                    dny += (y[j] / sk) ** 2
                if dnf <= 1e-10 or dny <= 1e-10:
                    h = 1e-6
                else:
                    h = 0.01 * math.sqrt(dny / dnf)
                h = min(h, h_max)
                for j in range(n):
                    ytmp[j] = y[j] + h * k1[j]
                rhs(t + h, ytmp, args, k2)
                nfev += 1
                der2 = 0.0
                for j in range(n):
                    sk = atol + rtol * abs(y[j])
                    der2 += ((k2[j] - k1[j]) / sk) ** 2
                der2 = math.sqrt(der2) / h
                der12 = max(abs(der2), math.sqrt(dnf))
                if not np.isfinite(der12):
                    h1 = 1e-6 * h
                elif der12 <= 1e-15:
                    h1 = max(1e-6, abs(h) * 1e-3)
                else:
                    h1 = (0.01 / der12) ** 0.2
                h = min(100.0 * abs(h), h1, h_max)
            h = min(h, h_max)
    if status != STATUS_OK or filled >= m:
        phase = PHASE_DONE
    while phase == PHASE_RUNNING and filled < i_stop:
        status = _budget_status(accepted, rejected, max_steps, t, h)
        if status != STATUS_OK:
            break
        h_proposed = h
        last = False
        if t + 1.01 * h >= t_end:
            h = t_end - t
            last = True
        for j in range(n):
            ytmp[j] = y[j] + h * A21 * k1[j]
        rhs(t + C2 * h, ytmp, args, k2)
        for j in range(n):
            ytmp[j] = y[j] + h * (A31 * k1[j] + A32 * k2[j])
        rhs(t + C3 * h, ytmp, args, k3)
        for j in range(n):
            ytmp[j] = y[j] + h * (A41 * k1[j] + A42 * k2[j] + A43 * k3[j])
        rhs(t + C4 * h, ytmp, args, k4)
        for j in range(n):
            ytmp[j] = y[j] + h * (A51 * k1[j] + A52 * k2[j] + A53 * k3[j] + A54 * k4[j])
        rhs(t + C5 * h, ytmp, args, k5)
        for j in range(n):
            ytmp[j] = y[j] + h * (A61 * k1[j] + A62 * k2[j] + A63 * k3[j] + A64 * k4[j] + A65 * k5[j])
        rhs(t + h, ytmp, args, k6)
        for j in range(n):
            y1[j] = y[j] + h * (A71 * k1[j] + A73 * k3[j] + A74 * k4[j] + A75 * k5[j] + A76 * k6[j])
        rhs(t + h, y1, args, k7)
        nfev += 6
        err = 0.0
        for j in range(n):
            sk = atol + rtol * max(abs(y[j]), abs(y1[j]))
            e = h * (E1 * k1[j] + E3 * k3[j] + E4 * k4[j] + E5 * k5[j] + E6 * k6[j] + E7 * k7[j])
            err += (e / sk) ** 2
        err = math.sqrt(err / n)
        if not np.isfinite(err):
            rejected += 1
            n_nonfinite += 1
            if n_nonfinite >= MAX_NONFINITE_TRIALS:
                status = STATUS_NONFINITE
                break
            h = 0.1 * h
            if 0.1 * abs(h) <= abs(t) * UROUND:  # shrinking cannot cure it: say non-finite, not underflow
                status = STATUS_NONFINITE
                break
            reject = True
            continue
        n_nonfinite = 0
        fac11 = err ** EXPO1
        fac = fac11 / facold ** BETA
        fac = max(FACC2, min(FACC1, fac / SAFE))
        hnew = h / fac
        if err <= 1.0:
            facold = max(err, 1e-4)
            accepted += 1
            for j in range(n):
                rcont[0, j] = y[j]
                ydiff = y1[j] - y[j]
                rcont[1, j] = ydiff
                bspl = h * k1[j] - ydiff
                rcont[2, j] = bspl
                rcont[3, j] = ydiff - h * k7[j] - bspl
                rcont[4, j] = h * (D1 * k1[j] + D3 * k3[j] + D4 * k4[j] + D5 * k5[j] + D6 * k6[j]
                                   + D7 * k7[j])
            t_old = t
            t = t_end if last else t + h
            while filled < m and t_out[filled] <= t:
                if filled == m - 1 and last:
                    put(Y[filled], 0, y1)
                else:
                    _dense_eval(rcont, (t_out[filled] - t_old) / h, ytmp)
                    put(Y[filled], 0, ytmp)
                filled += 1
            put(y, 0, y1)
            put(k1, 0, k7)
            if hnew > h_max:
                hnew = h_max
            if reject:
                hnew = min(hnew, h)
            reject = False
            if last:
                h_next = h_proposed
                phase = PHASE_DONE
                break
            h = hnew
            h_next = hnew
        else:
            hnew = h / min(FACC1, fac11 / SAFE)
            reject = True
            rejected += 1
            h = hnew
    if status != STATUS_OK:
        phase = PHASE_DONE
    _store_state(work, y, k1, t, h, accepted, rejected, nfev, status, h_next, filled, n_nonfinite, phase)
    work[W_FACOLD] = facold
    work[W_REJECT] = 1.0 if reject else 0.0


ROS2_GAMMA = 1.0 + 1.0 / math.sqrt(2.0)
FD_SQRT_EPS = math.sqrt(2.2e-16)


@njit(cache=True)
def no_jac(t, y, args, J):
    """Placeholder Jacobian: the Rosenbrock kernel uses forward differences instead."""
    J[:, :] = np.nan


@njit(cache=True)
def _hermite(y0, f0, y1, f1, h, theta, out):
    """Cubic Hermite interpolant between (y0, f0) and (y1, f1) over a step h (Hairer I, II.6)."""
    for j in range(out.shape[0]):
        dy = y1[j] - y0[j]
        out[j] = (1.0 - theta) * y0[j] + theta * y1[j] + theta * (theta - 1.0) * (
            (1.0 - 2.0 * theta) * dy + (theta - 1.0) * h * f0[j] + theta * h * f1[j])


def _ros2_impl(rhs, jac, t_out, args, params, Y, work, i_stop):
    n = Y.shape[1]
    m = t_out.shape[0]
    rtol = params[P_RTOL]
    atol = params[P_ATOL]
    h_max = params[P_H_MAX]
    max_steps = params[P_MAX_STEPS]
    use_fd = params[P_USE_FD] != 0.0
    y = work[N_WORK_SCALARS:N_WORK_SCALARS + n].copy()
    f0 = work[N_WORK_SCALARS + n:N_WORK_SCALARS + 2 * n].copy()
    y1 = np.empty(n)
    ytmp = np.empty(n)
    f1 = np.empty(n)
    fnew = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    J = np.empty((n, n))
    W = np.empty((n, n))
    t_end = t_out[m - 1]
    if h_max <= 0.0:
        h_max = t_end - t_out[0]
    t, h, accepted, rejected, nfev, status, h_next, filled, n_nonfinite, phase = _load_state(work)
    # a call returns only after an accepted step (or at the end), where the Jacobian is due anyway,
    # so J itself need not be carried
    need_jac = True
    if phase == PHASE_NEW:
        t = t_out[0]
        rhs(t, y, args, f0)
        nfev = 1
        h_next = 0.0
        n_nonfinite = 0
        phase = PHASE_RUNNING
        if not (_all_finite(y) and _all_finite(f0)):
            status = STATUS_NONFINITE
        elif m > 1:
            if h <= 0.0:
                d0 = 0.0
                d1 = 0.0
                for j in range(n):
                    sk = atol + rtol * abs(y[j])
                    d0 += (y[j] / sk) ** 2
                    d1 += (f0[j] / sk) ** 2
                d0 = math.sqrt(d0 / n)
                d1 = math.sqrt(d1 / n)
                h = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
            h = min(h, h_max)
    if status != STATUS_OK or filled >= m:
        phase = PHASE_DONE
    while phase == PHASE_RUNNING and filled < i_stop:
        status = _budget_status(accepted, rejected, max_steps, t, h)
        if status != STATUS_OK:
            break
        if need_jac:
            if use_fd:
                for j in range(n):
                    delta = FD_SQRT_EPS * (abs(y[j]) + atol / rtol)
                    put(ytmp, 0, y)
                    ytmp[j] = y[j] + delta
                    rhs(t, ytmp, args, fnew)
                    for i in range(n):
                        J[i, j] = (fnew[i] - f0[i]) / delta
                nfev += n
            else:
                jac(t, y, args, J)
            need_jac = False
        h_proposed = h
        last = False
        if t + 1.01 * h >= t_end:
            h = t_end - t
            last = True
        for i in range(n):
            for j in range(n):
                W[i, j] = -ROS2_GAMMA * h * J[i, j]
            W[i, i] += 1.0
        ok = _all_finite(W.ravel())
        if ok:
            Winv = np.linalg.inv(W)
            put(k1, 0, Winv @ f0)
            for j in range(n):
                ytmp[j] = y[j] + h * k1[j]
            rhs(t + h, ytmp, args, f1)
            nfev += 1
            for j in range(n):
                f1[j] -= 2.0 * k1[j]
            put(k2, 0, Winv @ f1)
            err = 0.0
            for j in range(n):
                y1[j] = y[j] + h * (1.5 * k1[j] + 0.5 * k2[j])
                sk = atol + rtol * max(abs(y[j]), abs(y1[j]))
                err += (0.5 * h * (k1[j] + k2[j]) / sk) ** 2
            err = math.sqrt(err / n)
        else:
            err = np.nan
        if not np.isfinite(err):
            rejected += 1
            n_nonfinite += 1
            if n_nonfinite >= MAX_NONFINITE_TRIALS:
                status = STATUS_NONFINITE
                break
            h = 0.1 * h
            continue
        n_nonfinite = 0
        fac = min(5.0, max(0.2, 0.9 / math.sqrt(max(err, 1e-10))))
        if err <= 1.0:
            rhs(t + h, y1, args, fnew)
            nfev += 1
            if not _all_finite(fnew):
                rejected += 1
                h = 0.5 * h
                continue
            accepted += 1
            t_old = t
            t = t_end if last else t + h
            while filled < m and t_out[filled] <= t:
                if filled == m - 1 and last:
                    put(Y[filled], 0, y1)
                else:
                    _hermite(y, f0, y1, fnew, h, (t_out[filled] - t_old) / h, ytmp)
                    put(Y[filled], 0, ytmp)
                filled += 1
            put(y, 0, y1)
            put(f0, 0, fnew)
            need_jac = True
            hnew = min(h * fac, h_max)
            if last:
                h_next = h_proposed
                phase = PHASE_DONE
                break
            h = hnew
            h_next = hnew
        else:
            rejected += 1
            h = h * fac
    if status != STATUS_OK:
        phase = PHASE_DONE
    _store_state(work, y, f0, t, h, accepted, rejected, nfev, status, h_next, filled, n_nonfinite, phase)


def chunk_bounds(count: int, n_chunks: int) -> np.ndarray:
    """Boundaries 0 = b_0 < b_1 < ... = ``count`` of at most ``n_chunks`` nearly equal runs of ``count``
    items (output intervals of :func:`integrate`, orthonormalisation intervals of
    :func:`lubedyn.dynamics.lyapunov.lyapunov_spectrum`): where a chunked run returns to Python."""
    n = max(1, min(int(n_chunks), int(count)))
    return np.unique(np.linspace(0, count, n + 1).round().astype(np.int64))


def new_run(y0, t_out, h0=0.0):
    """Fresh ``(Y, work)`` of a run from ``y0`` at ``t_out[0]`` (``h0``: the adaptive methods' first step,
    0: automatic)."""
    n, m = y0.shape[0], t_out.shape[0]
    Y = np.full((m, n), np.nan)
    Y[0] = y0
    work = np.zeros(N_WORK_SCALARS + 2 * n)
    work[N_WORK_SCALARS:N_WORK_SCALARS + n] = y0
    work[W_H] = h0
    work[W_FILLED] = 1
    work[W_PHASE] = PHASE_NEW
    return Y, work


def run_stats(work):
    """The ``stats`` array (``ACCEPTED ... N_FILLED``) of a run's ``work``."""
    stats = np.zeros(N_STATS)
    stats[ACCEPTED] = work[W_ACCEPTED]
    stats[REJECTED] = work[W_REJECTED]
    stats[NFEV] = work[W_NFEV]
    stats[STATUS] = work[W_STATUS]
    stats[T_REACHED] = work[W_T]
    stats[H_NEXT] = work[W_H_NEXT]
    stats[N_FILLED] = work[W_FILLED]
    return stats


def make_params(rtol=0.0, atol=0.0, h_max=0.0, max_steps=0, use_fd=True, dt=0.0, guard=False):
    """The ``params`` array of a kernel call (``guard``: RK4's growth guard, see :func:`integrate`)."""
    params = np.zeros(N_PARAMS)
    params[P_RTOL], params[P_ATOL], params[P_H_MAX] = rtol, atol, h_max
    params[P_MAX_STEPS], params[P_USE_FD], params[P_DT] = max_steps, 1.0 if use_fd else 0.0, dt
    params[P_GUARD] = 1.0 if guard else 0.0
    return params


class OneShot:
    """A whole run in one call, ``(Y, stats) = kernel(y0, t_out, ...)``, over a resumable kernel.

    ``rk4(y0, t_out, dt, args)``, ``dopri5(y0, t_out, args, rtol, atol, h0, h_max, max_steps)``,
    ``ros2(y0, t_out, args, rtol, atol, h0, h_max, max_steps, use_fd)``; ``n_callables`` leading
    callables (the generic kernels' rhs, jac) are passed on first.  ``kernel`` is the resumable
    kernel (a numba dispatcher: its ``stats`` show cache hits); ``py_func`` the same call in plain Python.
    """

    def __init__(self, method, kernel, n_callables=0):
        self.method, self.kernel, self.n_callables = method, kernel, n_callables

    @property
    def stats(self):
        return self.kernel.stats

    @property
    def py_func(self):
        return OneShot(self.method, _PlainKernel(self.kernel.py_func), self.n_callables)

    def __call__(self, *a):
        callables, a = a[:self.n_callables], a[self.n_callables:]
        if self.method == "rk4":
            y0, t_out, dt, args = a
            h0, params = 0.0, make_params(dt=dt)
        else:
            y0, t_out, args, rtol, atol, h0, h_max, max_steps = a[:8]
            use_fd = a[8] if self.method == "ros2" else True
            params = make_params(rtol, atol, h_max, max_steps, use_fd)
        y0 = np.asarray(y0, dtype=np.float64)
        t_out = np.asarray(t_out, dtype=np.float64)
        Y, work = new_run(y0, t_out, h0)
        self.kernel(*callables, t_out, args, params, Y, work, t_out.shape[0])
        return Y, run_stats(work)


class _PlainKernel:
    def __init__(self, func):
        self.func = func
        self.py_func = func

    def __call__(self, *a):
        return self.func(*a)


#: generic kernels taking the callables as arguments (no cross-process cache: see module docstring)
_rk4_generic = njit(cache=False)(_rk4_impl)
_dopri5_generic = njit(cache=False)(_dopri5_impl)
_ros2_generic = njit(cache=False)(_ros2_impl)
rk4 = OneShot("rk4", _rk4_generic, 1)
dopri5 = OneShot("dopri5", _dopri5_generic, 1)
ros2 = OneShot("ros2", _ros2_generic, 2)


# binding to a right-hand side (lubedyn.dynamics.specialise): how each kernel calls its callables
def rhs_signature(types):
    """``rhs(t, y, args, dydt)`` as the kernels call it (y and dydt fresh C-contiguous arrays), from the
    numba ``types`` of the kernel's arguments (:func:`lubedyn.dynamics.specialise.register_kernel`)."""
    vec = _nt.float64[::1]
    return _nt.void(_nt.float64, vec, types["args"], vec)


def _jac_signature(types):
    return _nt.void(_nt.float64, _nt.float64[::1], types["args"], _nt.float64[:, ::1])


register_kernel(_rk4_impl, rhs=rhs_signature)
register_kernel(_dopri5_impl, rhs=rhs_signature)
register_kernel(_ros2_impl, rhs=rhs_signature, jac=_jac_signature)


# stability ----------------------------------------------------------------------
def stability_limit(method: str, axis: str = "imaginary") -> float:
    """Largest ``|h lambda|`` on an axis for which the explicit ``method`` is stable.

    Computed from the stability polynomial R(z) (``STABILITY_POLYNOMIALS``):
    the first ``y > 0`` where ``|R(i y)|`` (axis ``"imaginary"``) or
    ``|R(-y)|`` (axis ``"real"``) exceeds 1, found by a scan and bisection.
    RK4: 2 sqrt(2) = 2.828 (imaginary), 2.785 (real); DOPRI5 (R(z) = sum_k<=5
    z^k/k! + z^6/600, Hairer & Wanner, *Solving ODEs II*, sec. IV.2): 0.997
    (imaginary, where |R| exceeds 1 by 1.4e-6 only; 3e-3 at 1.5) and 3.307
    (real).
    """
    if method not in STABILITY_POLYNOMIALS:
        raise DynamicsInputError(f"method = {method!r} is not allowed; choose one of {sorted(STABILITY_POLYNOMIALS)}")
    if axis not in ("imaginary", "real"):
        raise DynamicsInputError(f"axis = {axis!r} is not allowed; choose 'imaginary' or 'real'")
    poly = np.polynomial.Polynomial(STABILITY_POLYNOMIALS[method])
    unit = 1j if axis == "imaginary" else -1.0

    def unstable(y):
        return abs(poly(unit * y)) > 1.0 + 1e-13

    ys = np.arange(1e-3, 10.0, 1e-3)
    bad = np.nonzero([unstable(y) for y in ys])[0]
    lo, hi = ys[bad[0] - 1], ys[bad[0]]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if unstable(mid) else (mid, hi)
    return float(lo)


def spectral_step(rhs, y0, args=(), method: str = "rk4", t: float = 0.0, rel_step: float = 1e-7,
                  floor: float = 1e-3) -> float:
    """The largest step h [s] of the explicit ``method`` whose amplification |R(h lambda)| <= 1 for every
    eigenvalue lambda of the Jacobian of ``rhs`` at (``t``, ``y0``) that does not grow (Re lambda <= 1e-6
    |lambda|_max, read with Re lambda <= 0: a growing mode has no step limit, as in the RK4 guard of
    :func:`integrate`); inf when none limits it.

    The Jacobian by forward differences of the compiled ``rhs`` (one call per state, step ``rel_step``
    max(|y_i|, ``floor``)), the eigenvalues by LAPACK (numpy), the step by bisection in log h to 1e-9 on
    the stability polynomial (``STABILITY_POLYNOMIALS``).  A linearisation at one state: where the
    system stiffens along the run (contact loads, sliding) the guard of :func:`integrate` still stops it."""
    if method not in STABILITY_POLYNOMIALS:
        raise DynamicsInputError(f"method = {method!r} is not allowed; choose one of {sorted(STABILITY_POLYNOMIALS)}")
    y0 = np.array(y0, dtype=np.float64, ndmin=1)
    n = y0.size
    f0 = np.empty(n)
    call = entry_point(rhs, t, y0, args, f0) if hasattr(rhs, "overloads") else rhs  # no typing per call
    call(t, y0, args, f0)
    J = np.empty((n, n))
    f = np.empty(n)
    for i in range(n):
        e = rel_step * max(abs(float(y0[i])), floor)
        y = y0.copy()
        y[i] += e
        call(t, y, args, f)
        J[:, i] = (f - f0) / e
    if not np.all(np.isfinite(J)):
        raise DynamicsInputError("spectral_step: the right-hand side is not finite near y0")
    ev = np.linalg.eigvals(J)
    big = float(np.abs(ev).max()) if ev.size else 0.0
    ev = ev[(ev.real <= 1e-6 * big) & (np.abs(ev) > 0.0)]
    if ev.size == 0:
        return math.inf
    # a neutral mode whose real part the differences leave slightly > 0 (a gyroscopic precession) is read
    # on the imaginary axis: with Re > 0 no step would be stable and the stable steps not an interval
    ev = np.minimum(ev.real, 0.0) + 1j * ev.imag
    coeffs = np.asarray(STABILITY_POLYNOMIALS[method], dtype=float)[::-1]  # highest power first

    def stable(h):
        return bool(np.abs(np.polyval(coeffs, h * ev)).max() <= 1.0 + 1e-12)

    top = float(np.abs(ev).max())
    lo, hi = 1e-3 / top, 10.0 / top  # |z| <= 1e-3 lies inside every method's region; 10 outside RK4's, DOPRI5's
    if stable(hi):
        return hi
    while hi / lo > 1.0 + 1e-9:
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


# Python driver --------------------------------------------------------------------
@dataclass(frozen=True)
class IntegrationResult:
    """Result of :func:`integrate`.

    Attributes
    ----------
    t : ndarray, shape (m,)
        Output times [s].
    y : ndarray, shape (m, n)
        States at ``t``.
    stats : dict
        ``"Accepted steps [-]"``, ``"Rejected steps [-]"``, ``"RHS evaluations [-]"``,
        ``"Wall time [s]"``, ``"Integrator stop reason"`` (a run that stops early
        raises instead, with the reason), and for RK4 ``"Largest estimated
        h*|lambda| (RK4) [-]"`` (the growth guard's largest stage estimate: the
        margin to the stability limit 2.785-2.828).
    method : str
    """

    t: np.ndarray
    y: np.ndarray
    stats: dict = field(default_factory=dict)
    method: str = "dopri5"


def resumable_kernel(method, rhs, jac=None):
    """The resumable kernel of ``method`` bound to ``rhs`` (cached across processes, :mod:`lubedyn.dynamics.specialise`):
    ``kernel(t_out, args, params, Y, work, i_stop)`` (see :func:`new_run`, :func:`make_params`)."""
    if method not in METHODS:
        raise DynamicsInputError(f"method = {method!r} is not allowed; choose one of {METHODS}")
    if method == "ros2":
        return specialise(_ros2_impl, rhs=rhs, jac=no_jac if jac is None else jac)
    impl = _rk4_impl if method == "rk4" else _dopri5_impl
    return specialise(impl, rhs=rhs)


def kernel_example(method, rhs, args, jac=None):
    """``(kernel, example arguments)`` of :func:`integrate`'s kernel for ``rhs`` and ``args``, for
    :func:`lubedyn.dynamics.specialise.compile_in_background` (the arguments have the types of its calls)."""
    Y, work = new_run(np.zeros(1), np.zeros(2))
    return resumable_kernel(method, rhs, jac), (np.zeros(2), args, make_params(), Y, work, 1)


def kernel_for(method, rhs, jac=None):
    """The compiled kernel of ``method`` bound to ``rhs`` (cached across processes), whole run in one call.

    Same call as the generic kernel without the leading callables:
    ``rk4: (y0, t_out, dt, args)``, ``dopri5: (y0, t_out, args, rtol, atol, h0, h_max, max_steps)``,
    ``ros2: (y0, t_out, args, rtol, atol, h0, h_max, max_steps, use_fd)``; returns ``(Y, stats)``.
    """
    return OneShot(method, resumable_kernel(method, rhs, jac))


def _check_positive(key, value):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise DynamicsInputError(f"{key} = {value!r} must be a positive number") from None
    if not (v > 0.0 and math.isfinite(v)):
        raise DynamicsInputError(f"{key} = {value!r} must be a finite number > 0")
    return v


def integrate(rhs, y0, t_out, args=(), method="dopri5", rtol=1e-6, atol=1e-9, dt=None, h_max=0.0,
              max_steps=10_000_000, progress=False, omega_max=None, h0=0.0, n_chunks=None, jac=None):
    """Integrate ``dy/dt = rhs(t, y, args)`` and sample at ``t_out``.

    Parameters
    ----------
    rhs : numba dispatcher
        ``@njit`` function ``rhs(t, y, args, dydt)``.
    y0 : array_like, shape (n,)
        State at ``t_out[0]``.
    t_out : array_like, shape (m,), m >= 2
        Strictly increasing output times [s]; integration starts at ``t_out[0]``.
    args : tuple
        Passed to ``rhs`` unchanged.
    method : {"dopri5", "rk4", "ros2"}
        ``"ros2"`` is the L-stable Rosenbrock method for stiff problems.
    rtol, atol : float
        DOPRI5 / ROS2 tolerances (scalars).
    dt : float
        RK4 largest step [s] (required for ``"rk4"``).
    h_max : float
        DOPRI5 largest step [s] (0: no limit).
    max_steps : int
        Step budget (accepted + rejected) of the whole run (DOPRI5).
    progress : bool
        Show a tqdm bar of simulated time.  The kernel then returns to Python
        after each of up to 200 chunks of output samples to update the bar; it
        carries its whole state across (step size, controller memory, FSAL
        stage, counters) and never shortens a step at a chunk boundary, so the
        result is bit-identical to a run without the bar.
    omega_max : float or callable, optional
        Highest angular frequency [rad/s] of the linearised system (e.g.
        sqrt(k_contact / m_ball)), or a callable ``omega_max(y) -> float``
        that estimates it at a state.  With RK4, ``dt * omega_max`` beyond
        :func:`stability_limit` is refused at ``y0`` (DynamicsInputError); a
        callable is evaluated again at the state reached after every chunk
        and a run whose contacts stiffen beyond the limit stops there
        (IntegrationError, status ``STATUS_UNSTABLE``, naming the stable
        step).  With DOPRI5 an ``h_max`` beyond the limit is reported in the
        log (the step control will reject there).
    h0 : float
        DOPRI5 initial step (0: automatic).
    n_chunks : int, optional
        Number of kernel calls (default 1, or up to 200 when ``progress``); it
        does not change the result.
    jac : numba dispatcher, optional
        ``jac(t, y, args, J)`` writing the n x n Jacobian (ROS2 only); forward differences if None.

    Returns
    -------
    IntegrationResult

    Notes
    -----
    RK4 growth guard (always on in this driver, with or without ``omega_max``).
    The stages give a power iterate of ``h^2 J^2`` for free: ``k2 - k1 =
    J (h/2) k1`` and ``k3 - k2 = J (h/2)(k2 - k1)`` (``k2``, ``k3`` at the same
    time), so ``(h rho)^2 ~ 4 |k3 - k2| / |k1|`` estimates the largest
    ``|h lambda|`` at the current state (exact for ``J^2 = -omega^2 I``, any
    state scaling), and the sign of ``(k3 - k2) . k1`` that of ``(h
    lambda)^2`` (negative: an oscillation, limit 2.828 on the imaginary axis;
    positive: a real lambda, whose sign is that of ``(k2 - k1) . k1``: a decay
    has the limit 2.785 on the real axis, a growth (lambda > 0, as in a
    blow-up) has none and is never counted).  A run stops with
    ``STATUS_UNSTABLE`` when the estimate exceeds the limit on
    ``GUARD_MIN_STEPS`` (5) consecutive steps *and* ``|f(y)|`` has grown by
    ``GUARD_GROWTH`` (2) over them: a single stiff contact (about one step long
    at h omega ~ 2.8) or rounding noise at an equilibrium does not stop a run,
    a mode that grows does.  The check adds three dot products per step and
    never changes a run that stays stable.

    Raises
    ------
    DynamicsInputError
        Bad input (one line: key, value, what is allowed).
    IntegrationError
        The kernel stopped early (status code, time reached and the samples
        filled so far are attributes of the exception).

    Examples
    --------
    >>> import numpy as np
    >>> from numba import njit
    >>> @njit
    ... def decay(t, y, args, dydt):
    ...     dydt[0] = -args[0] * y[0]
    >>> res = integrate(decay, [1.0], np.linspace(0.0, 1.0, 5), (2.0,), rtol=1e-10, atol=1e-12)
    >>> bool(abs(res.y[-1, 0] - np.exp(-2.0)) < 1e-9)
    True
    """
    if method not in METHODS:
        raise DynamicsInputError(f"method = {method!r} is not allowed; choose one of {METHODS}")
    if not hasattr(rhs, "py_func"):
        raise DynamicsInputError(f"rhs = {rhs!r} must be an @njit function rhs(t, y, args, dydt)")
    if jac is not None and (method != "ros2" or not hasattr(jac, "py_func")):
        raise DynamicsInputError(f"jac = {jac!r}: only method 'ros2' takes a Jacobian, an @njit jac(t, y, args, J)")
    if not isinstance(args, tuple):
        raise DynamicsInputError(f"args = {type(args).__name__} must be a tuple")
    y0 = np.array(y0, dtype=np.float64, ndmin=1)
    if y0.ndim != 1 or y0.size == 0 or not np.isfinite(y0).all():
        raise DynamicsInputError(f"y0 (shape {y0.shape}) must be a non-empty 1-D array of finite numbers")
    t_out = np.array(t_out, dtype=np.float64, ndmin=1)
    if t_out.ndim != 1 or t_out.size < 2 or not np.isfinite(t_out).all():
        raise DynamicsInputError(f"t_out (shape {t_out.shape}) must be a 1-D array of >= 2 finite times")
    if not (t_out[1:] > t_out[:-1]).all():
        raise DynamicsInputError("t_out must be strictly increasing")
    max_steps = int(_check_positive("max_steps", max_steps))
    if method == "rk4":
        if dt is None:
            raise DynamicsInputError("dt = None: method 'rk4' needs a step dt > 0 [s]")
        dt = _check_positive("dt", dt)
    else:
        rtol = _check_positive("rtol", rtol)
        atol = _check_positive("atol", atol)
        if rtol < 10 * UROUND:
            raise DynamicsInputError(f"rtol = {rtol!r} must be >= {10 * UROUND:g}")
        h_max = float(h_max)
        if not (h_max >= 0.0 and math.isfinite(h_max)):
            raise DynamicsInputError(f"h_max = {h_max!r} must be >= 0 (0: no limit)")
    omega_of_state = None
    if callable(omega_max):
        omega_of_state = omega_max
        omega_max = omega_of_state(y0)
    if omega_max is not None:
        omega_max = _check_positive("omega_max", omega_max)
        limit = stability_limit(method, "imaginary") if method != "ros2" else math.inf
        if method == "rk4" and dt * omega_max > limit:
            raise DynamicsInputError(
                f"dt = {dt:g} s is beyond the RK4 stability limit {limit / omega_max:g} s "
                f"(dt * omega_max = {dt * omega_max:.3g} > {limit:.3f} for omega_max = {omega_max:g} rad/s)")
        if method == "dopri5" and (h_max == 0.0 or h_max * omega_max > limit):
            logger.info("dopri5: steps are stability-limited near h = %.3g s (omega_max = %.3g rad/s)",
                        limit / omega_max, omega_max)

    kernel = resumable_kernel(method, rhs, jac)
    m = t_out.size
    if n_chunks is None:
        n_chunks = min(m - 1, 200) if progress else 1
    n_chunks = max(1, min(int(n_chunks), m - 1))
    # each call returns once the rows up to a chunk's last output time are filled; the integrator's whole
    # state stays in `work`, so the chunks only decide when control comes back for the bar (the run is
    # bit-identical to a one-chunk run, tests/test_chunking.py)
    # (a one-chunk run skips the chunk arithmetic: on a cheap rhs the Python steps cost more than the kernel)
    stops = [m] if n_chunks == 1 else (chunk_bounds(m - 1, n_chunks)[1:] + 1).tolist()
    params = make_params(rtol=rtol if method != "rk4" else 0.0, atol=atol if method != "rk4" else 0.0,
                         h_max=h_max if method != "rk4" else 0.0, max_steps=max_steps, use_fd=jac is None,
                         dt=dt if method == "rk4" else 0.0, guard=method == "rk4")
    Y, work = new_run(y0, t_out, float(h0) if method != "rk4" else 0.0)
    wall0 = time.perf_counter()
    bar = None
    if progress:
        # a first call that fills no row: it compiles (or loads) the kernel and makes the initial step
        # choice, so that the bar starts after any compilation message (the run resumes bit-identically)
        kernel(t_out, args, params, Y, work, 1)
        from tqdm.auto import tqdm

        bar = tqdm(total=float(t_out[-1] - t_out[0]), unit="s", desc=f"{method} simulated time", disable=None,
                   bar_format="{l_bar}{bar}| {n:.4g}/{total:.4g} s [{elapsed}<{remaining}]")
    try:
        shown = 1
        for i_stop in stops:
            kernel(t_out, args, params, Y, work, i_stop)
            filled = int(work[W_FILLED])
            status = int(work[W_STATUS])
            if status == STATUS_OK and omega_of_state is not None and method == "rk4" and filled < m:
                omega_now = float(omega_of_state(work[N_WORK_SCALARS:N_WORK_SCALARS + y0.size].copy()))
                limit = stability_limit("rk4", "imaginary")
                if not math.isfinite(omega_now) or dt * omega_now > limit:
                    status = STATUS_UNSTABLE
                    work[W_STATUS] = status
                    work[W_HRHO] = dt * omega_now
            if status != STATUS_OK:
                raise IntegrationError(_stop_message(method, status, work, t_out, dt, omega_of_state is not None),
                                       status=status, t_reached=work[W_T], t=t_out[:filled].copy(),
                                       y=Y[:filled].copy())
            if bar is not None and filled > shown:
                bar.update(float(t_out[filled - 1] - t_out[shown - 1]))
                shown = filled
            if filled >= m:
                break
    finally:
        if bar is not None:
            bar.close()
    wall = time.perf_counter() - wall0
    stats = {
        "Accepted steps [-]": int(work[W_ACCEPTED]),
        "Rejected steps [-]": int(work[W_REJECTED]),
        "RHS evaluations [-]": int(work[W_NFEV]),
        "Wall time [s]": wall,
        "Integrator stop reason": "reached the last output time",
    }
    if method == "rk4":
        stats["Largest estimated h*|lambda| (RK4) [-]"] = float(work[W_HRHO_MAX])
    logger.debug("%s: %s", method, stats)
    return IntegrationResult(t=t_out, y=Y, stats=stats, method=method)


def _stop_message(method, status, work, t_out, dt, by_state):
    """The one-line reason of an early stop, with the figures that show it."""
    head = (f"{method} stopped at t = {work[W_T]:.6g} s of {t_out[-1]:.6g} s: "
            f"{STATUS_MESSAGES.get(status, 'unknown status')}")
    counts = f"{int(work[W_ACCEPTED])} accepted, {int(work[W_REJECTED])} rejected steps"
    if status != STATUS_UNSTABLE:
        return f"{head} (status {status}; {counts})"
    hrho = float(work[W_HRHO])
    limit = stability_limit("rk4", "imaginary")
    h = dt
    if by_state and int(work[W_UNSTABLE_STEPS]) < GUARD_MIN_STEPS:
        figures = f"dt * omega_max(y) = {hrho:.4g} > {limit:.4g} at the state reached"
    else:
        h = float(work[W_H]) or dt
        limit = float(work[W_LIMIT])
        axis = "imaginary axis: an oscillation" if limit == RK4_LIMIT_IMAGINARY else "real axis: a decay"
        figures = (f"estimated |h lambda| = {hrho:.4g} > {limit:.4g} ({axis}) on {int(work[W_UNSTABLE_STEPS])} "
                   f"consecutive steps while |f(y)| grew {GUARD_GROWTH:g}x or more")
    now = f"dt = {dt:.4g} s now" if abs(h - dt) <= 1e-9 * dt else f"steps of {h:.4g} s now, dt = {dt:.4g} s"
    return (f"{head}: {figures}; a stable step is dt <= {h * limit / hrho:.4g} s "
            f"({now}; status {status}; {counts})")
