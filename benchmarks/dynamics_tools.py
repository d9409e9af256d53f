"""Measuring tools of the integrators, kept out of the library: the first-call (compile) time
of a kernel in a fresh process, and the step-size study of a Hertz impact that the integrator choice
of the bearing runs rests on (numbers in dynamics/integrators.py, "Stiffness of the ball contacts").
"""
from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
from numba import njit

from lubedyn.dynamics.integrators import ACCEPTED, H_NEXT, _check_positive, kernel_for, stability_limit

_FIRST_CALL_SCRIPT = """
import sys, time, importlib
import numpy as np
t0 = time.perf_counter()
from lubedyn.dynamics import integrators as I
rhs = getattr(importlib.import_module(sys.argv[1]), sys.argv[2])
y0 = np.array([float(v) for v in sys.argv[4].split(",")])
args = tuple(float(v) for v in sys.argv[5].split(",") if v)
t1 = time.perf_counter()
t_out = np.array([0.0, 1e-3])
if sys.argv[3] == "generic":
    I.dopri5(rhs, y0, t_out, args, 1e-6, 1e-9, 0.0, 0.0, 10**6)
else:
    I.kernel_for(sys.argv[3], rhs)(y0, t_out, args, 1e-6, 1e-9, 0.0, 0.0, 10**6) if sys.argv[3] == "dopri5" \
        else I.kernel_for("rk4", rhs)(y0, t_out, 1e-5, args)
print(t1 - t0, time.perf_counter() - t1)
"""


def first_call_seconds(rhs_module, rhs_name, y0, args=(), method="dopri5", cache_dir=None, extra_path=None):
    """Import and first-call times [s] of a kernel in a *fresh* Python process.

    ``method``: "dopri5" or "rk4" (bound by pointer, cross-process cached kernel) or
    "generic" (the argument-taking DOPRI5 kernel, compiled in every process).
    The rhs must be importable as ``rhs_module.rhs_name`` (``extra_path`` is
    prepended to ``sys.path``) and take a tuple of floats ``args``.  Call
    twice with the same ``cache_dir`` to see cold and warm numbers.

    Returns
    -------
    dict: "Import time [s]", "First call [s]".
    """
    import subprocess

    env = dict(os.environ)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    if extra_path:
        env["PYTHONPATH"] = os.pathsep.join([str(extra_path), env.get("PYTHONPATH", "")])
    cmd = [sys.executable, "-c", _FIRST_CALL_SCRIPT, rhs_module, rhs_name, method,
           ",".join(repr(float(v)) for v in np.atleast_1d(y0)), ",".join(repr(float(a)) for a in args)]
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True).stdout.split()
    return {"Import time [s]": float(out[-2]), "First call [s]": float(out[-1])}


# stiffness study ----------------------------------------------------------------
@njit(cache=True)
def _contact_rhs(t, y, args, dydt):
    """Ball of mass m (args[1]) hitting a Hertz half-space: F = k_h delta^1.5 for delta = -x > 0."""
    k_h = args[0]
    mass = args[1]
    dydt[0] = y[1]
    delta = -y[0]
    dydt[1] = k_h * delta ** 1.5 / mass if delta > 0.0 else 0.0


def contact_step_study(stiffness=1e9, mass=3.5e-3, approach_speed=0.5,
                       rk4_h_omega=(0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 2.8), rtols=(1e-4, 1e-6, 1e-8)):
    """Measure whether contact stiffness makes the explicit integrators stability-limited.

    A ball of ``mass`` [kg] hits a Hertzian half-space (F = k_h delta^1.5) at
    ``approach_speed`` [m/s]; k_h is chosen so that the contact stiffness at
    the largest deflection, k = 1.5 k_h delta_max^0.5, equals ``stiffness``
    [N/m] (energy: m v^2 / 2 = 0.4 k_h delta_max^2.5 gives delta_max = (1.875 m
    v^2 / k)^(1/2)).  The impact is elastic, so the exact rebound speed equals the
    approach speed; the contact lasts 2.943 delta_max / v (Hertz impact).
    omega = sqrt(stiffness / mass).

    RK4 runs at fixed ``h omega`` values (below the 2.83 stability limit) and
    DOPRI5 at the given tolerances; for each the relative rebound-speed error
    is returned, and for DOPRI5 the mean ``h omega`` of the steps it takes
    across the contact.  If the step that accuracy needs is well below the
    stability limit, an implicit method would buy nothing: that is the
    measured argument of the module docstring.

    Returns
    -------
    dict: "Omega [rad/s]", "Contact duration [s]", "RK4 stable step [s]",
    "DOPRI5 stable step [s]", "rk4": list of {"h*omega [-]", "Rebound speed
    error [-]"}, "dopri5": list of {"rtol [-]", "Rebound speed error [-]",
    "Mean h*omega in contact [-]", "Steps in contact [-]"}.
    """
    stiffness = _check_positive("stiffness", stiffness)
    mass = _check_positive("mass", mass)
    v = _check_positive("approach_speed", approach_speed)
    d_max = math.sqrt(1.875 * mass * v * v / stiffness)
    k_h = stiffness / (1.5 * math.sqrt(d_max))
    omega = math.sqrt(stiffness / mass)
    duration = 2.9432 * d_max / v
    x0 = 0.5 * v * duration  # contact starts at t = duration / 2, ends near 1.5 duration
    t_end = 2.0 * duration
    args = (k_h, mass)
    y0 = np.array([x0, -v])
    out = {
        "Omega [rad/s]": omega,
        "Contact duration [s]": duration,
        "RK4 stable step [s]": stability_limit("rk4") / omega,
        "DOPRI5 stable step [s]": stability_limit("dopri5") / omega,
        "rk4": [],
        "dopri5": [],
    }
    rk4_kernel = kernel_for("rk4", _contact_rhs)
    for ho in rk4_h_omega:
        Y, st = rk4_kernel(y0, np.array([0.0, t_end]), ho / omega, args)
        out["rk4"].append({"h*omega [-]": ho, "Rebound speed error [-]": abs(Y[-1, 1] - v) / v})
    dp_kernel = kernel_for("dopri5", _contact_rhs)
    t_in, t_exit = 0.5 * duration, 1.5 * duration
    for rtol in rtols:
        atol = rtol * d_max
        Y, st = dp_kernel(y0, np.array([0.0, t_in, t_end]), args, rtol, atol, 0.0, 0.0, 10**7)
        Yc, sc = dp_kernel(Y[1], np.array([t_in, t_exit]), args, rtol, atol, st[H_NEXT], 0.0, 10**7)
        out["dopri5"].append({
            "rtol [-]": rtol,
            "Rebound speed error [-]": abs(Y[-1, 1] - v) / v,
            "Steps in contact [-]": int(sc[ACCEPTED]),
            "Mean h*omega in contact [-]": omega * (t_exit - t_in) / max(sc[ACCEPTED], 1.0),
        })
    return out
