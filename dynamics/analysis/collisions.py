"""Ball-ball collision events from sampled contact diagnostics, and slip ratios.

Plain numpy on sampled contact diagnostics (no numba needed: these run once
per run on arrays of a few thousand samples).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Collision:
    """One ball-ball collision: the contiguous samples where the normal force
    between balls ``pair`` and ``pair + 1`` exceeds the threshold."""

    pair: int
    t_start: float
    t_end: float
    t_peak: float
    peak_force: float  # normal force at the peak [N]
    force: tuple  # (Fx, Fy, Fz) on ball pair+1 at the peak [N]
    position: tuple  # contact point (x, y, z) at the peak [m]

    @property
    def duration(self) -> float:
        return self.t_end - self.t_start


def collision_events(t, normal_force, components, positions, threshold: float) -> list[Collision]:
    """Collisions from sampled pair forces.

    ``normal_force`` (m, Z): normal force of pair j (balls j, j+1) at each
    sample; ``components`` (m, Z, 3): its inertial components on ball j+1;
    ``positions`` (m, Z, 3): the contact point (mid-point of the two centres).
    An event is a maximal run of samples with ``normal_force > threshold``
    (a run cut by the start or end of the record counts too); its peak is
    the sample of largest normal force.  Events sorted by peak time.

    The sampling interval must resolve a collision (tens of microseconds for
    steel balls through an oil film): a run shorter than one sample is
    missed, and the run summary reports the sample interval next to the count.
    """
    t = np.asarray(t, dtype=float)
    F = np.asarray(normal_force, dtype=float)
    if F.ndim != 2 or F.shape[0] != t.size:
        raise ValueError(f"normal_force has shape {F.shape}; expected ({t.size}, Z)")
    events = []
    for j in range(F.shape[1]):
        above = F[:, j] > threshold
        if not above.any():
            continue
        edges = np.diff(np.concatenate(([0], above.astype(np.int8), [0])))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
        for a, b in zip(starts, ends):
            k = a + int(np.argmax(F[a:b + 1, j]))
            events.append(Collision(pair=j, t_start=float(t[a]), t_end=float(t[b]), t_peak=float(t[k]),
                                    peak_force=float(F[k, j]), force=tuple(float(x) for x in components[k, j]),
                                    position=tuple(float(x) for x in positions[k, j])))
    events.sort(key=lambda e: e.t_peak)
    return events


def collision_summary(events: list[Collision], n_pairs: int) -> dict:
    """Counts and largest forces by direction (names with units)."""
    out = {"Ball-ball collisions [-]": len(events)}
    per_pair = np.bincount([e.pair for e in events], minlength=n_pairs) if events else np.zeros(n_pairs, int)
    out["Collisions per pair, most [-]"] = int(per_pair.max()) if n_pairs else 0
    for i, axis in enumerate("xyz"):
        values = [abs(e.force[i]) for e in events]
        out[f"Largest collision force {axis} [N]"] = float(max(values)) if values else 0.0
    out["Largest collision normal force [N]"] = float(max((e.peak_force for e in events), default=0.0))
    out["Longest collision [s]"] = float(max((e.duration for e in events), default=0.0))
    return out


def slip_ratio(actual, ideal):
    """1 - actual/ideal (0: no slip; 1: standing still), elementwise; NaN where ideal is 0."""
    actual, ideal = np.asarray(actual, dtype=float), np.asarray(ideal, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(ideal != 0.0, 1.0 - actual / ideal, np.nan)
