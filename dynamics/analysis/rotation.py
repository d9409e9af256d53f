"""Angular displacement of the balls of a cage-less bearing run: the inertial angular velocity
R(q) w_body integrated in time (Zhang et al., *Symmetry* 16 (2024) 741, Fig. 4 plots it), and the axial
angular rate of every ball.
"""
from __future__ import annotations

import numpy as np

from lubedyn.dynamics.analysis.motion import n_balls
from lubedyn.dynamics.rotations import to_scipy



def angular_displacement(t, quaternion, body_rate) -> np.ndarray:
    """Angular displacement (m, 3) [rad] about the inertial x, y, z axes: the inertial angular
    velocity w = R(q) w_body (``q`` scalar first, body to inertial, :mod:`lubedyn.dynamics.rotations`)
    integrated by the trapezoidal rule from 0 at the first sample.  Unlike the rotation vector of q,
    it does not wrap at pi: a ball spinning at 2,000 rad/s turns 40 rad in 20 ms."""
    from scipy.integrate import cumulative_trapezoid
    from scipy.spatial.transform import Rotation

    q = np.asarray(quaternion, dtype=float)
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    omega = Rotation.from_quat(to_scipy(q)).apply(np.asarray(body_rate, dtype=float))
    return cumulative_trapezoid(omega, np.asarray(t, dtype=float), axis=0, initial=0.0)


def ball_angular_displacement(t, series, j: int) -> np.ndarray | None:
    """Ball ``j``'s angular displacement (m, 3) from the columns; planar: z from its spin angle
    (x, y zero); ``None`` without either."""
    b = f"Ball {j} "
    if b + "q0 [-]" in series:
        q = np.stack([series[b + f"q{i} [-]"] for i in range(4)], axis=1)
        w = np.stack([series[b + f"body w{a} [rad/s]"] for a in "xyz"], axis=1)
        return angular_displacement(t, q, w)
    if b + "spin angle [rad]" in series:
        out = np.zeros((len(t), 3))
        out[:, 2] = np.asarray(series[b + "spin angle [rad]"]) - series[b + "spin angle [rad]"][0]
        return out
    return None


def axial_rates(t, series) -> np.ndarray:
    """Every ball's axial angular rate (m, Z) [rad/s]: the z component of its inertial angular
    velocity R(q) w_body (planar: its spin speed), the rate of its z angular displacement."""
    from scipy.spatial.transform import Rotation

    out = np.zeros((len(t), n_balls(series)))
    for j in range(out.shape[1]):
        b = f"Ball {j} "
        if b + "q0 [-]" in series:
            q = np.stack([series[b + f"q{i} [-]"] for i in range(4)], axis=1)
            q = q / np.linalg.norm(q, axis=1, keepdims=True)
            w = np.stack([series[b + f"body w{a} [rad/s]"] for a in "xyz"], axis=1)
            out[:, j] = Rotation.from_quat(to_scipy(q)).apply(w)[:, 2]
        else:
            out[:, j] = series[b + "spin speed [rad/s]"]
    return out
