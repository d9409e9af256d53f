"""A ball's motion from a cage-less bearing run's time series (the columns of the run's time series file).

The run's columns are named by :meth:`lubedyn.dynamics.cageless.CagelessBearing.state_names` and the contact
diagnostics (:data:`lubedyn.dynamics.cageless.DIAG_NAMES`, ``RING_DIAG_NAMES``): ``"Ball j x [m]"``,
``"Ball j Orbital angle [rad]"``, ... (6-dof balls) or ``"Ball j radial position [m]"`` (planar balls).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from lubedyn.dynamics.cageless import DIAG_NAMES, RING_DIAG_NAMES



def run_columns(model, Y, diag, ring) -> dict:
    """The columns of the run's time series (views of the arrays, no copies) from a run's state,
    ball diagnostics (m, Z, k) and ring diagnostics."""
    columns = {n: Y[:, i] for i, n in enumerate(model.state_names())}
    for j in range(model.n_balls):
        for k, n in enumerate(DIAG_NAMES):
            columns[f"Ball {j} {n}"] = diag[:, j, k]
    for k, n in enumerate(RING_DIAG_NAMES):
        columns[n] = ring[:, k]
    return columns


def n_balls(series) -> int:
    """Number of balls in a time series."""
    n = 0
    while f"Ball {n} Orbital angle [rad]" in series:
        n += 1
    return n


@dataclass
class BallMotion:
    """A ball's centre in the inertial frame and in the frame turning with it (co-rotating)."""

    position: np.ndarray  # (m, 3) [m]
    velocity: np.ndarray  # (m, 3) [m/s]
    azimuth: np.ndarray  # (m,) orbital angle [rad]
    orbital_speed: np.ndarray  # (m,) [rad/s]

    @property
    def radius(self) -> np.ndarray:
        """Co-rotating radial position (distance from the bearing axis) [m]."""
        return np.hypot(self.position[:, 0], self.position[:, 1])

    @property
    def tangential_velocity(self) -> np.ndarray:
        """Velocity along the orbit (counter-clockwise) [m/s]."""
        p, v = self.position, self.velocity
        return (p[:, 0] * v[:, 1] - p[:, 1] * v[:, 0]) / self.radius

    @property
    def radial_velocity(self) -> np.ndarray:
        """d(radius)/dt [m/s]."""
        p, v = self.position, self.velocity
        return (p[:, 0] * v[:, 0] + p[:, 1] * v[:, 1]) / self.radius


def ball_motion(t, series, j: int) -> BallMotion:
    """Ball ``j``'s motion from the time-series columns (6-dof: position and velocity states;
    planar: orbital angle and radial position, velocities from their speeds, z = 0)."""
    b = f"Ball {j} "
    psi = np.asarray(series[b + "Orbital angle [rad]"], dtype=float)
    psidot = np.asarray(series[b + "Orbital speed [rad/s]"], dtype=float)
    if b + "x [m]" in series:
        pos = np.stack([series[b + f"{a} [m]"] for a in "xyz"], axis=1).astype(float)
        vel = np.stack([series[b + f"v{a} [m/s]"] for a in "xyz"], axis=1).astype(float)
    else:
        r, rdot = np.asarray(series[b + "radial position [m]"]), np.asarray(series[b + "radial speed [m/s]"])
        c, s = np.cos(psi), np.sin(psi)
        pos = np.stack([r * c, r * s, np.zeros_like(r)], axis=1)
        vel = np.stack([rdot * c - r * psidot * s, rdot * s + r * psidot * c, np.zeros_like(r)], axis=1)
    return BallMotion(pos, vel, psi, psidot)
