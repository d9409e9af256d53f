"""Poincare sections: the crossings of a fixed azimuth by an orbiting body, interpolated between samples.
"""
from __future__ import annotations

import math

import numpy as np



def poincare_section(t, azimuth, values, section: float):
    """Crossings of a fixed azimuth ``section`` [rad] in the direction of motion (increasing
    unwrapped azimuth): (times (n,), values (n, k)) interpolated linearly between the samples;
    ``values`` is (m, k).  Once per ball-train revolution for one ball."""
    t = np.asarray(t, dtype=float)
    u = np.unwrap(np.asarray(azimuth, dtype=float))
    turns = np.floor((u - section) / (2 * math.pi))
    i = np.flatnonzero(turns[1:] > turns[:-1])
    target = section + 2 * math.pi * turns[i + 1]
    frac = (target - u[i]) / (u[i + 1] - u[i])
    vals = np.asarray(values, dtype=float).reshape(len(t), -1)
    return t[i] + frac * (t[i + 1] - t[i]), vals[i] + frac[:, None] * (vals[i + 1] - vals[i])
