"""Ball-ball collisions by quadrant around the inner ring's centre (Zhang et al., *Symmetry* 16 (2024)
741, Fig. 5: the collisions' positions and forces around the ring) and before / after its spin-up.
"""
from __future__ import annotations

import math

import numpy as np

QUADRANTS = ("I (x > 0, y > 0)", "II (x < 0, y > 0)", "III (x < 0, y < 0)", "IV (x > 0, y < 0)")


def quadrant_of(x, y) -> np.ndarray:
    """Quadrant 1-4 (counter-clockwise from +x, +y; the load zone at the bottom is III and IV) of
    points (x, y) relative to the inner ring's centre [m]; on an axis the point goes to the
    quadrant counter-clockwise of it."""
    angle = np.mod(np.arctan2(np.asarray(y, dtype=float), np.asarray(x, dtype=float)), 2 * math.pi)
    return np.minimum((angle // (0.5 * math.pi)).astype(int), 3) + 1


def collision_table(t, series, events):
    """(times, positions relative to the inner ring's centre (n, 3), normal forces, force components
    (n, 3)) of the collisions."""
    if not events:
        return np.zeros(0), np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3))
    tp = np.array([e.t_peak for e in events])
    centre = np.stack([np.interp(tp, t, series[f"Inner ring {a} [m]"]) for a in "xyz"], axis=1)
    pos = np.array([e.position for e in events]) - centre
    return tp, pos, np.array([e.peak_force for e in events]), np.array([e.force for e in events])


def collision_entries(t, series, events, t_spinup) -> dict:
    """Counts of collisions by quadrant around the inner ring and before / after its spin-up."""
    tp, pos, _, _ = collision_table(t, series, events)
    quad = quadrant_of(pos[:, 0], pos[:, 1])
    out = {f"Collisions in quadrant {name} [-]": int(np.sum(quad == k + 1)) for k, name in enumerate(QUADRANTS)}
    if t_spinup is not None:
        out["Collisions during ring spin-up [-]"] = int(np.sum(tp < t_spinup))
        out["Collisions after ring spin-up [-]"] = int(np.sum(tp >= t_spinup))
    return out
