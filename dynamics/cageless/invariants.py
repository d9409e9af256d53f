"""Energy and angular momentum of a state (checks of the right-hand side).

Part of :mod:`lubedyn.dynamics.cageless` (the package docstring gives the overview)."""
from __future__ import annotations

import math

import numpy as np

from .model import CagelessBearing
from ..rotations import quat_rotate as _qr

def bearing_energy(model: CagelessBearing, y: np.ndarray) -> float:
    """Mechanical energy [J] of a state: kinetic energy of balls, ring (and
    rotor when free), Hertz potential 2/5 K delta^2.5 of every ball-race
    contact and elastic ball-ball contact, gravity and the potential -F.x of
    the constant applied ring load.  (Exact invariant of a frictionless,
    undamped, film-free, elastic run with a free ring.)"""
    args = model.args()
    P = args.P[0]
    Z = model.n_balls
    y = np.asarray(y, dtype=float)
    m, J = model.mass, model.ball_inertia
    E = 0.5 * model.bearing.ring_mass * float(np.sum(y[4:7] ** 2)) + 0.5 * model.bearing.ring_inertia * y[7] ** 2
    E += model.bearing.ring_mass * model.operating.gravity * y[1] - (P.fx * y[0] + P.fy * y[1] + P.fz * y[2])
    pos = np.zeros((Z, 3))
    for j in range(Z):
        b = model.ball_offset(j)
        if model.fidelity.dof == "6dof":
            pos[j] = y[b:b + 3]
            E += 0.5 * m * float(np.sum(y[b + 7:b + 10] ** 2)) + 0.5 * J * float(np.sum(y[b + 10:b + 13] ** 2))
        else:
            phi, r, phid, rd, om = y[b], y[b + 1], y[b + 3], y[b + 4], y[b + 5]
            pos[j] = r * math.cos(phi), r * math.sin(phi), 0.0
            E += 0.5 * m * (rd * rd + (r * phid) ** 2) + 0.5 * J * om * om
        E += m * model.operating.gravity * pos[j, 1]
        for race in (0, 1):
            ctr = np.zeros(3) if race == 0 else y[0:3]
            Rgc, rg, K = (P.roc, P.ro, P.ko) if race == 0 else (P.ric, P.ri, P.ki)
            d = pos[j] - ctr
            rho = math.hypot(d[0], d[1])
            delta = math.hypot(rho - Rgc, d[2]) - (rg - 0.5 * model.bearing.ball_diameter)
            if delta > 0.0:
                E += 0.4 * K * delta**2.5
    if model.fidelity.ball_ball:
        Kbb = args.bbp[0].k
        for j in range(Z):
            k = (j + 1) % Z
            gap = float(np.linalg.norm(pos[k] - pos[j])) - model.bearing.ball_diameter
            if gap < 0.0:
                E += 0.4 * Kbb * (-gap) ** 2.5
    return E


def angular_momentum_z(model: CagelessBearing, y: np.ndarray) -> float:
    """Angular momentum [kg m^2/s] about the bearing axis of balls and inner ring."""
    Z = model.n_balls
    m, J = model.mass, model.ball_inertia
    L = model.bearing.ring_mass * (y[0] * y[5] - y[1] * y[4]) + model.bearing.ring_inertia * y[7]
    for j in range(Z):
        b = model.ball_offset(j)
        if model.fidelity.dof == "6dof":
            w = np.empty(3)
            q = y[b + 3:b + 7] / np.linalg.norm(y[b + 3:b + 7])
            _qr(q, y[b + 10:b + 13].copy(), w)
            L += m * (y[b] * y[b + 8] - y[b + 1] * y[b + 7]) + J * w[2]
        else:
            L += m * y[b + 1] ** 2 * y[b + 3] + J * y[b + 5]
    return float(L)
