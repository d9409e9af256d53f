"""Settling and spin-up times of a cage-less bearing run (Zhang et al., *Symmetry* 16 (2024) 741, Fig. 3).

Settling rule
-------------
The *final window* is the last ``FINAL_FRACTION`` (25 %) of the record.  A
signal x(t) with final value x_f (its mean over the final window) has
settled once |x - x_f| stays within the band
``max(BAND_FRACTION * max_t |x - x_f|, FINAL_MARGIN * max |x - x_f| in the final window)``
(5 % of its largest excursion, as the 5 % settling time of control theory,
but never narrower than the final window's own largest deviation: the ball
keeps being kicked by collisions and the slot in its stable stage, and the
stable stage is what its final window does, so the settling time is when it
stops moving more than that for good); the settling time is the last exit
from the band, interpolated linearly between samples.  A signal whose
straight-line trend over the final window moves it by more than the band's
half-width has not reached a stable stage: ``None`` with a note.

A ball's x(t) and y(t) oscillate with its orbit and z(t) changes with the
azimuth (load zone, slot) even once it is steady, so the rule is applied to
*residuals* (:func:`steady_residuals`): the ball's co-rotating radial position r, axial position z and
velocities (radial, tangential, axial) minus the steady pattern at its
current azimuth, the median over every ball in the final window in
``AZIMUTH_BINS`` azimuth bins (every ball of the train follows the same
pattern once steady; 14 balls cover the ring within a few milliseconds).
The radial and tangential residuals are turned into x and y at the ball's
azimuth (e_x = e_r cos psi, e_vx = e_vr cos psi - e_vt sin psi, ...).
Direction d settles when both its position and its velocity residual have
settled (the later of the two).  A settling time within ``SATURATION_MARGIN`` (5 %) of the record before
the final window's start, with the band set by the final window itself, is the rule's edge, not a
settling time (a signal still decaying into the final window leaves the band there): ``None`` with the
note "record too short".  The orbital speed's residual gets its own
settling time.  The inner ring's spin-up time (:func:`spinup_time`): when its
speed comes within ``SPINUP_TOLERANCE`` (1 %) of the rotor's for good.
"""
from __future__ import annotations

import logging
import math

import numpy as np

from lubedyn.dynamics.analysis.motion import ball_motion, n_balls

log = logging.getLogger(__name__)


FINAL_FRACTION = 0.25
BAND_FRACTION = 0.05
FINAL_MARGIN = 1.0
AZIMUTH_BINS = 72
SPINUP_TOLERANCE = 0.01
#: a settling time within this fraction of the record before the final window's start is the rule's own
#: edge, not a settling time: a signal still decaying into the final window exits the band, which the final
#: window's largest deviation sets, right at that window's start (exactly there for a monotone decay)
SATURATION_MARGIN = 0.05


def final_start(t, fraction: float = FINAL_FRACTION) -> int:
    """Index of the first sample of the final window (the last ``fraction`` of the record)."""
    t = np.asarray(t, dtype=float)
    return int(np.searchsorted(t, t[-1] - fraction * (t[-1] - t[0])))


def settling_time(t, x, i_final: int, fraction: float = BAND_FRACTION, margin: float = FINAL_MARGIN,
                  floor: float = 0.0):
    """(settling time [s] or None, band half-width, note) of a signal by the rule of the module
    docstring: the last exit from the band around the final-window mean, interpolated.  ``floor``: the
    smallest half-width (round-off of a residual that is zero in exact arithmetic)."""
    t, x = np.asarray(t, dtype=float), np.asarray(x, dtype=float)
    final = x[i_final:]
    dev = np.abs(x - final.mean())
    # the final window's straight-line trend: a drift across it is not a stable stage
    slope = np.polyfit(t[i_final:] - t[i_final], final, 1)[0] if final.size > 2 else 0.0
    half = max(fraction * float(dev.max()), margin * float(dev[i_final:].max()), floor)
    drift = abs(float(slope)) * float(t[-1] - t[i_final])
    if drift > half:
        return None, half, (f"not settled: drifts by {drift:.3g} over the final window (from {t[i_final]:.4g} s), "
                            f"more than its band +-{half:.3g}; run longer")
    outside = np.flatnonzero(dev > half)
    if half == 0.0 or outside.size == 0:
        return float(t[0]), half, ""
    k = int(outside[-1])
    if k >= i_final or k + 1 >= t.size:
        return None, half, (f"not settled: leaves its band (+-{half:.3g}) at {t[k]:.4g} s, inside the final window "
                            f"(from {t[i_final]:.4g} s); run longer")
    frac = (dev[k] - half) / (dev[k] - dev[k + 1])
    settled = float(t[k] + frac * (t[k + 1] - t[k]))
    if settled >= t[i_final] - SATURATION_MARGIN * (t[-1] - t[0]) and half == margin * float(dev[i_final:].max()):
        return None, half, (f"record too short: it leaves its band (+-{half:.3g}, set by the final window's largest "
                            f"deviation) at {settled:.4g} s, within {SATURATION_MARGIN:.0%} of the record of the final "
                            f"window's start ({t[i_final]:.4g} s), so the record cannot tell when it settled; run longer")
    return settled, half, ""


def steady_residuals(azimuth, values, i_final: int, bins: int = AZIMUTH_BINS):
    """``values`` (m, Z) of every ball minus the steady pattern at each ball's azimuth (m, Z): the
    median over every ball's final-window samples in ``bins`` azimuth bins (empty bins take the
    nearest filled one around the ring)."""
    az = np.mod(np.asarray(azimuth, dtype=float), 2 * math.pi)
    idx = np.minimum((az / (2 * math.pi) * bins).astype(int), bins - 1)
    vals = np.asarray(values, dtype=float)
    ref = np.full(bins, np.nan)
    fi, fv = idx[i_final:].ravel(), vals[i_final:].ravel()
    for b in np.unique(fi):
        ref[b] = np.median(fv[fi == b])
    filled = np.flatnonzero(np.isfinite(ref))
    if filled.size < bins:
        centres = np.arange(bins)
        ref = np.interp(centres, filled, ref[filled], period=bins)
    return vals - ref[idx]


def spinup_time(t, ring_speed, rotor_speed, tolerance: float = SPINUP_TOLERANCE):
    """(time [s] or None, note): when the inner ring's speed comes within ``tolerance`` of the
    rotor's for good (the last exit from the band, interpolated)."""
    t = np.asarray(t, dtype=float)
    rotor = np.asarray(rotor_speed, dtype=float)
    dev = np.abs(1.0 - np.asarray(ring_speed, dtype=float) / np.where(rotor != 0, rotor, np.nan))
    dev = np.where(np.isfinite(dev), dev, np.inf)
    outside = np.flatnonzero(dev > tolerance)
    if outside.size == 0:
        return float(t[0]), ""
    k = int(outside[-1])
    if k + 1 >= t.size:
        return None, (f"not spun up: the ring is {dev[-1]:.3g} off the rotor's speed at the end ({t[-1]:.4g} s); "
                      "run longer")
    frac = (dev[k] - tolerance) / (dev[k] - dev[k + 1]) if np.isfinite(dev[k]) else 1.0
    return float(t[k] + frac * (t[k + 1] - t[k])), ""


def settling_times(t, series, ball: int, scenario: str = "drop") -> dict:
    """Summary entries of paper B's Fig. 3 (Zhang et al. 2024): ``"Settling time, ball j x [s]"`` (y, z),
    the orbital speed's and the inner ring's spin-up time, each ``None`` with a ``", note"`` when not reached."""
    t = np.asarray(t, dtype=float)
    i_final = final_start(t)
    z = n_balls(series)
    motions = [ball_motion(t, series, k) for k in range(z)]
    azimuth = np.stack([m.azimuth for m in motions], axis=1)
    out = {}

    def residual(values):
        return steady_residuals(azimuth, np.stack(values, axis=1), i_final)[:, ball]

    # residuals in the co-rotating frame (radial, tangential, axial), which change slowly with the azimuth,
    # then turned into x and y at the ball's azimuth (binning x itself would leave R 2 pi/bins of spread)
    e = {"r": residual([m.radius for m in motions]), "z": residual([m.position[:, 2] for m in motions]),
         "vr": residual([m.radial_velocity for m in motions]), "vz": residual([m.velocity[:, 2] for m in motions]),
         "vt": residual([m.tangential_velocity for m in motions])}
    c, s_ = np.cos(motions[ball].azimuth), np.sin(motions[ball].azimuth)
    # round-off floors: 1e-12 of the orbit's radius and speed
    length = 1e-12 * float(np.max(motions[ball].radius))
    speed = 1e-12 * float(np.max(np.abs(motions[ball].tangential_velocity)))
    pairs = {"x": (e["r"] * c, e["vr"] * c - e["vt"] * s_), "y": (e["r"] * s_, e["vr"] * s_ + e["vt"] * c),
             "z": (e["z"], e["vz"])}
    for axis, signals in pairs.items():
        key = f"Settling time, ball {ball} {axis} [s]"
        if np.ptp(np.stack([m.position[:, "xyz".index(axis)] for m in motions])) == 0.0:
            out[key], out[key[:-4] + ", note"] = None, "not computed: the coordinate does not move (planar model)"
            continue
        results = [settling_time(t, x, i_final, floor=f) for x, f in zip(signals, (length, speed))]
        notes = [n for _, _, n in results if n]
        out[key] = None if notes else max(r for r, _, _ in results)
        if notes:
            out[key[:-4] + ", note"] = notes[0]
    key = f"Settling time, ball {ball} orbital speed [s]"
    out[key], _, note = settling_time(t, residual([m.orbital_speed for m in motions]), i_final,
                                      floor=1e-12 * float(np.max(np.abs(motions[ball].orbital_speed))))
    if note:
        out[key[:-4] + ", note"] = note
    key = "Inner ring spin-up time [s]"
    if scenario == "drop":
        out[key], note = spinup_time(t, series["Inner ring speed [rad/s]"], series["Rotor speed [rad/s]"])
    else:
        out[key], note = None, f"not computed: scenario {scenario!r} has no rotor drop"
    if note:
        out[key[:-4] + ", note"] = note
    out["Settling final window from [s]"] = float(t[i_final])
    for k, v in out.items():
        if k.endswith(", note"):
            log.info("%s: %s", k[:-6], v)
    return out
