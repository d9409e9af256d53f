"""Paper B's figures and the quantities behind them, from a dynamics run.

Paper B (Zhang et al., *Symmetry* 16 (2024) 741, sections 3.1-3.3 and 4.2)
studies a cage-less 6206 ball bearing whose rotor drops onto the inner ring.
This module turns a run of :mod:`lubedyn.scenes.dynamics` (its time series as
a name -> array mapping, the names of ``timeseries.npz``) into numbers a user
can compare with the paper, and into the figures:

- **settling times** (Fig. 3): :func:`settling_time` (rule below) applied to
  ball ``analysis.ball``'s residuals against the steady pattern of the ball
  train (:func:`steady_residuals`), per direction x, y, z; the inner ring's
  spin-up time (:func:`spinup_time`: ring speed within 1 % of the rotor's);
- **angular displacement** of three consecutive balls (Fig. 4,
  ``angular_displacement.png``): the inertial angular velocity R(q) w_body
  integrated in time (:func:`angular_displacement`), with the paper's three
  zones (:func:`zones`);
- **collision map** (Fig. 5, ``collision_map.png``): each ball-ball collision
  a needle at its contact point around the inner ring's centre, length
  proportional to its force, coloured by time (:func:`quadrants`);
- **Poincare sections** (not in the paper, ``poincare.png``): the ball's
  co-rotating (r, dr/dt) and (z, dz/dt) each time it passes a fixed azimuth
  (:func:`poincare_section`);
- the **spectrum** axis limited to the bearing frequencies (:func:`spectrum_limit`)
  and the dominant inner-ring acceleration frequency in a band (Fig. 11's
  950-1000 Hz at 3,000 rpm; :func:`dominant_frequency`);
- **phase portraits across speeds** (Figs. 6-8): :func:`compare_runs` reads
  several run folders.

Settling rule (Fig. 3)
----------------------
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
*residuals*: the ball's co-rotating radial position r, axial position z and
velocities (radial, tangential, axial) minus the steady pattern at its
current azimuth, the median over every ball in the final window in
``AZIMUTH_BINS`` azimuth bins (every ball of the train follows the same
pattern once steady; 14 balls cover the ring within a few milliseconds).
The radial and tangential residuals are turned into x and y at the ball's
azimuth (e_x = e_r cos psi, e_vx = e_vr cos psi - e_vt sin psi, ...).
Direction d settles when both its position and its velocity residual have
settled (the later of the two).  The orbital speed's residual gets its own
settling time.

Zones (Fig. 4)
--------------
The middle ball's axial angular rate (the rate of its z angular displacement,
the z component of R(q) w_body) is compared with the ball train's steady
pattern at its azimuth (the residual above; the rate is about 4 % lower in the
unloaded upper half and 4 % higher over the slot, so a plain level would call
every slot passage a surge).  *Unsteady* until the inner ring's spin-up ends
(:func:`spinup_time`) and the residual has come within ``SURGE_THRESHOLD``
(3 %) of the ball's steady rate (its spin has caught up); *smooth* from then;
*surge* from the first later departure beyond the same band lasting at least
``SURGE_MIN_DURATION`` (0.1 ms: a single collision's spike does not count).  A
run without a drop starts smooth; one that does not spin up within its record
is unsteady throughout.
"""
from __future__ import annotations

import json
import logging
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

log = logging.getLogger(__name__)

FINAL_FRACTION = 0.25
BAND_FRACTION = 0.05
FINAL_MARGIN = 1.0
AZIMUTH_BINS = 72
SPINUP_TOLERANCE = 0.01
SURGE_THRESHOLD = 0.03
SURGE_MIN_DURATION = 1e-4
#: the bearing lines that set the spectrum's axis (their first harmonics 2 f included)
SPECTRUM_LINES = ("Shaft [Hz]", "Ball train (cage) [Hz]", "Ball spin [Hz]", "Ball defect (2 x spin) [Hz]",
                  "BPFO [Hz]", "BPFI [Hz]")
MAX_HARMONIC = 5
PNG_FILES = ("angular_displacement.png", "collision_map.png", "poincare.png")


# ---------------------------------------------------------------------------- reading a run
def run_columns(model, Y, diag, ring) -> dict:
    """The columns of ``timeseries.npz`` (views of the arrays, no copies) from a run's state,
    ball diagnostics (m, Z, k) and ring diagnostics."""
    from lubedyn.dynamics.cageless import DIAG_NAMES, RING_DIAG_NAMES

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


# ---------------------------------------------------------------------------- settling (Fig. 3)
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
    return float(t[k] + frac * (t[k + 1] - t[k])), half, ""


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
    """Summary entries of Fig. 3: ``"Settling time, ball j x [s]"`` (y, z), the orbital speed's and
    the inner ring's spin-up time, each ``None`` with a ``", note"`` when not reached."""
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


# ---------------------------------------------------------------------------- angular displacement (Fig. 4)
def angular_displacement(t, quaternion, body_rate) -> np.ndarray:
    """Angular displacement (m, 3) [rad] about the inertial x, y, z axes: the inertial angular
    velocity w = R(q) w_body (``q`` scalar first, body to inertial, :mod:`lubedyn.dynamics.rotations`)
    integrated by the trapezoidal rule from 0 at the first sample.  Unlike the rotation vector of q,
    it does not wrap at pi: a ball spinning at 2,000 rad/s turns 40 rad in 20 ms."""
    from scipy.integrate import cumulative_trapezoid
    from scipy.spatial.transform import Rotation

    from lubedyn.dynamics.rotations import to_scipy

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

    from lubedyn.dynamics.rotations import to_scipy

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


def zones(t, residual, level: float, t_spinup, threshold: float = SURGE_THRESHOLD,
          min_duration: float = SURGE_MIN_DURATION, scenario: str = "drop") -> dict:
    """Ends of the paper's zones (Fig. 4) by the rule of the module docstring:
    ``{"unsteady until": s, "surge from": s or None}``.  ``residual``: the middle ball's axial
    angular rate minus the ball train's steady pattern at its azimuth [rad/s]; ``level``: its
    typical steady rate [rad/s]."""
    t = np.asarray(t, dtype=float)
    if scenario != "drop":
        start = float(t[0])
    elif t_spinup is None:
        return {"unsteady until": float(t[-1]), "surge from": None}
    else:
        start = float(t_spinup)
    band = threshold * abs(level)
    inside = np.abs(np.asarray(residual, dtype=float)) <= band
    calm = np.flatnonzero(inside & (t >= start))
    if calm.size == 0:
        return {"unsteady until": float(t[-1]), "surge from": None}
    i0 = int(calm[0])
    edges = np.diff(np.concatenate(([0], (~inside[i0:]).astype(np.int8), [0])))
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
        if t[i0 + b - 1] - t[i0 + a] >= min_duration:
            return {"unsteady until": float(t[i0]), "surge from": float(t[i0 + a])}
    return {"unsteady until": float(t[i0]), "surge from": None}


def zone_times(t, series, ball: int, t_spinup, scenario: str = "drop") -> dict:
    """:func:`zones` of ball ``ball`` from the columns (the steady pattern of every ball's axial rate in
    the final window, :func:`steady_residuals`)."""
    rates = axial_rates(t, series)
    i_final = final_start(t)
    azimuth = np.stack([series[f"Ball {j} Orbital angle [rad]"] for j in range(rates.shape[1])], axis=1)
    residual = steady_residuals(azimuth, rates, i_final)[:, ball]
    return zones(t, residual, float(np.median(rates[i_final:, ball])), t_spinup, scenario=scenario)


# ---------------------------------------------------------------------------- collisions (Fig. 5)
QUADRANTS = ("I (x > 0, y > 0)", "II (x < 0, y > 0)", "III (x < 0, y < 0)", "IV (x > 0, y < 0)")


def quadrants(x, y) -> np.ndarray:
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
    quad = quadrants(pos[:, 0], pos[:, 1])
    out = {f"Collisions in quadrant {name} [-]": int(np.sum(quad == k + 1)) for k, name in enumerate(QUADRANTS)}
    if t_spinup is not None:
        out["Collisions during ring spin-up [-]"] = int(np.sum(tp < t_spinup))
        out["Collisions after ring spin-up [-]"] = int(np.sum(tp >= t_spinup))
    return out


# ---------------------------------------------------------------------------- Poincare sections
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


def section_azimuth(case) -> float:
    """The Poincare section: the first functional slot's azimuth, else 270 deg (the bottom)."""
    return float(case.slots.azimuths[0]) if case.slots.azimuths else 1.5 * math.pi


# ---------------------------------------------------------------------------- spectrum (Figs. 11)
def spectrum_limit(freqs: dict, factor: float = 1.5) -> float | None:
    """Upper limit [Hz] of the spectrum axis: ``factor`` times the highest first harmonic (2 f) of
    the bearing lines :data:`SPECTRUM_LINES` (not the collision rate); None without lines."""
    lines = [2.0 * freqs[k] for k in SPECTRUM_LINES if freqs.get(k, 0) > 0]
    return factor * max(lines) if lines else None


def ring_acceleration(t, series):
    """The inner ring's vertical acceleration [m/s^2] (derivative of its vy), as spectrum.png."""
    return np.gradient(np.asarray(series["Inner ring vy [m/s]"], dtype=float), np.asarray(t, dtype=float))


def dominant_frequency(t, signal, band):
    """(frequency [Hz], amplitude) of the largest line of the Hann-windowed amplitude spectrum
    (:func:`lubedyn.dynamics.spectra.amplitude_spectrum`) within ``band`` = (low, high) [Hz]; (None, None)
    when the band holds no bin."""
    from lubedyn.dynamics.spectra import amplitude_spectrum

    t = np.asarray(t, dtype=float)
    f, amp = amplitude_spectrum(signal, 1.0 / float(t[1] - t[0]))
    inside = np.flatnonzero((f >= band[0]) & (f <= band[1]))
    if inside.size == 0:
        return None, None
    k = int(inside[np.argmax(amp[inside])])
    return float(f[k]), float(amp[k])


def nearest_line(frequency: float, freqs: dict) -> str:
    """The bearing line harmonic n x f (n <= ``MAX_HARMONIC``: a high harmonic of the cage frequency
    lies near anything) nearest to ``frequency``, e.g. "3 x BPFO (+1.2 %)"."""
    best = None
    for name in SPECTRUM_LINES:
        f0 = freqs.get(name, 0.0)
        if f0 > 0:
            n = min(MAX_HARMONIC, max(1, round(frequency / f0)))
            dev = frequency / (n * f0) - 1.0
            if best is None or abs(dev) < abs(best[2]):
                best = (n, name, dev)
    return "" if best is None else f"{best[0]} x {best[1].replace(' [Hz]', '')} ({100 * best[2]:+.1f} %)"


def vibration_entries(t, series, freqs, band, transient: float = 0.0) -> dict:
    """Dominant inner-ring acceleration frequency within ``band`` after ``transient`` (paper B,
    Fig. 11: 950-1,000 Hz at 3,000 rpm), with the nearest bearing line."""
    t = np.asarray(t, dtype=float)
    keep = t >= transient
    lo, hi = band
    key = f"Dominant inner ring acceleration frequency, {lo:g}-{hi:g} Hz"
    if keep.sum() < 16:
        return {f"{key} [Hz]": None, f"{key}, note": "not computed: fewer than 16 samples after the transient"}
    f, amp = dominant_frequency(t[keep], ring_acceleration(t, series)[keep], band)
    if f is None:
        return {f"{key} [Hz]": None, f"{key}, note": "not computed: the band lies beyond the Nyquist frequency "
                f"or is narrower than the resolution 1/T = {1 / (t[keep][-1] - t[keep][0]):.3g} Hz"}
    return {f"{key} [Hz]": f, f"{key} amplitude [m/s^2]": amp, f"{key}, nearest bearing line": nearest_line(f, freqs),
            f"{key}, resolution [Hz]": 1.0 / float(t[keep][-1] - t[keep][0])}


# ---------------------------------------------------------------------------- run summary
def summary_entries(case, t, series, events, freqs) -> dict:
    """Everything this module adds to a dynamics run's summary: settling and spin-up times, zones,
    collisions by quadrant, Poincare points, the dominant vibration frequency."""
    j = case.analysis.ball
    scenario = case.operating.scenario
    out = settling_times(t, series, j, scenario)
    t_spin = out.get("Inner ring spin-up time [s]")
    z = zone_times(t, series, j, t_spin, scenario)
    out["Zone unsteady until [s]"] = z["unsteady until"]
    out["Zone surge from [s]"] = z["surge from"]
    out.update(collision_entries(t, series, events, t_spin))
    motion = ball_motion(t, series, j)
    times, _ = poincare_section(t, motion.azimuth, motion.radius, section_azimuth(case))
    out[f"Poincare points, ball {j} [-]"] = int(times.size)
    out.update(vibration_entries(t, series, freqs, case.analysis.vibration_band, case.analysis.transient))
    return out


# ---------------------------------------------------------------------------- figures
ZONE_COLOURS = {"unsteady": "C3", "smooth": "C2", "surge": "C1"}


def _shade_zones(ax, t0, t1, zone, label=False):
    """Shade the zones (seconds) on an axis in milliseconds."""
    u, s = zone["unsteady until"], zone["surge from"]
    spans = [("unsteady", t0, u), ("smooth", u, s if s is not None else t1), ("surge", s, t1)]
    for name, a, b in spans:
        if a is not None and b is not None and b > a:
            ax.axvspan(a * 1e3, b * 1e3, color=ZONE_COLOURS[name], alpha=0.12, lw=0, label=name if label else None)


def angular_displacement_figure(t, series, ball: int, zone: dict | None, title: str = ""):
    """Paper B, Fig. 4: angular displacement of balls ``ball - 1, ball, ball + 1`` about the inertial
    x, y, z axes against time (:func:`angular_displacement`: R(q) w_body integrated), the zones
    shaded."""
    import matplotlib.pyplot as plt

    z = n_balls(series)
    fig, axes = plt.subplots(3, 1, figsize=(8, 7.5), sharex=True)
    ms = np.asarray(t) * 1e3
    for n, (j, role) in enumerate(zip(((ball - 1) % z, ball, (ball + 1) % z), ("front", "middle", "back"))):
        ang = ball_angular_displacement(t, series, j)
        if ang is None:
            continue
        for i, axis in enumerate("xyz"):
            axes[i].plot(ms, ang[:, i], lw=0.8, color=f"C{n}", label=f"ball {j} ({role})")
    for i, axis in enumerate("xyz"):
        axes[i].set_ylabel(f"angle about {axis} [rad]")
        if zone is not None:
            _shade_zones(axes[i], t[0], t[-1], zone, label=(i == 0))
    axes[0].legend(fontsize=7, ncol=2)
    axes[-1].set_xlabel("time [ms]")
    axes[-1].set_xlim(ms[0], ms[-1])
    axes[0].set_title(title or "angular displacement of three consecutive balls (paper B, Fig. 4)")
    fig.tight_layout()
    return fig


def collision_map_figure(t, series, events, pitch_radius: float, t_spinup=None, title: str = ""):
    """Paper B, Fig. 5: each ball-ball collision a needle at its contact point in the x-y plane around
    the inner ring's centre (quadrants I-IV, load zone at the bottom), pointing outward for a
    positive force (inward for a negative component), length proportional to the force, coloured by
    the time of its peak; panels: normal force, Fx, Fy, Fz."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    tp, pos, fn, comp = collision_table(t, series, events)
    fig, axes = plt.subplots(2, 2, figsize=(10, 9), layout="constrained")
    norm = plt.Normalize(float(t[0]) * 1e3, float(t[-1]) * 1e3)
    circle = np.linspace(0, 2 * math.pi, 361)
    for ax, (label, force) in zip(axes.ravel(), [("normal force", fn)] + [(f"F{a}", comp[:, i])
                                                                        for i, a in enumerate("xyz")]):
        ax.plot(pitch_radius * 1e3 * np.cos(circle), pitch_radius * 1e3 * np.sin(circle), color="0.6", lw=0.6)
        ax.axhline(0, color="k", lw=0.5)
        ax.axvline(0, color="k", lw=0.5)
        ax.axhspan(-1.6 * pitch_radius * 1e3, 0, color="C0", alpha=0.05, lw=0)
        biggest = float(np.max(np.abs(force))) if force.size else 0.0
        ax.text(0.0, -0.75 * pitch_radius * 1e3, "load zone", ha="center", fontsize=8, color="C0")
        if biggest > 0:
            radial = pos[:, :2] / np.linalg.norm(pos[:, :2], axis=1, keepdims=True)
            tip = pos[:, :2] + radial * (0.5 * pitch_radius * force / biggest)[:, None]
            lc = LineCollection(np.stack([pos[:, :2], tip], axis=1) * 1e3, cmap="viridis", norm=norm, lw=1.0)
            lc.set_array(tp * 1e3)
            ax.add_collection(lc)
        for k, (sx, sy) in enumerate(((1, 1), (-1, 1), (-1, -1), (1, -1))):
            ax.text(sx * 1.45 * pitch_radius * 1e3, sy * 1.45 * pitch_radius * 1e3, ("I", "II", "III", "IV")[k],
                    ha="center", va="center", fontsize=9, color="0.4")
        lim = 1.6 * pitch_radius * 1e3
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_aspect("equal")
        ax.set_xlabel("x from inner ring centre [mm]")
        ax.set_ylabel("y from inner ring centre [mm]")
        ax.set_title(f"{label}: longest needle {biggest:.3g} N", fontsize=9)
    sm = plt.cm.ScalarMappable(norm=norm, cmap="viridis")
    bar = fig.colorbar(sm, ax=axes, shrink=0.6, label="time of the force peak [ms]")
    if t_spinup is not None:
        bar.ax.axhline(t_spinup * 1e3, color="r", lw=1.5)
        bar.ax.text(1.05, t_spinup * 1e3, " spin-up end", transform=bar.ax.get_yaxis_transform(), fontsize=7,
                    color="r", va="center")
    fig.suptitle(title or f"ball-ball collisions by position around the ring ({len(tp)}; paper B, Fig. 5)")
    return fig


def poincare_figure(t, series, ball: int, section: float, title: str = ""):
    """Poincare sections: ball ``ball``'s co-rotating (r, dr/dt) and (z, dz/dt) at each passage of the
    azimuth ``section`` (large dots, coloured by time), and every other ball's passages (small grey
    dots: the ball train shares one steady pattern, so they fill a short run's section)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.3))
    z = n_balls(series)
    scatter = None
    for j in [k for k in range(z) if k != ball] + [ball]:
        m = ball_motion(t, series, j)
        times, vals = poincare_section(t, m.azimuth, np.stack([m.radius, m.radial_velocity, m.position[:, 2],
                                                              m.velocity[:, 2]], axis=1), section)
        for ax, (a, b), scale in zip(axes, ((0, 1), (2, 3)), (1e3, 1e6)):
            if j == ball:
                scatter = ax.scatter(vals[:, a] * scale, vals[:, b], c=times * 1e3, s=30, cmap="viridis",
                                     vmin=t[0] * 1e3, vmax=t[-1] * 1e3, edgecolors="k", lw=0.5, zorder=3,
                                     label=f"ball {ball} ({times.size})")
            else:
                ax.plot(vals[:, a] * scale, vals[:, b], ".", color="0.6", ms=3,
                        label="other balls" if j == (ball + 1) % z else None)
    axes[0].set_xlabel("co-rotating radial position r [mm]")
    axes[0].set_ylabel("dr/dt [m/s]")
    axes[1].set_xlabel("axial position z [um]")
    axes[1].set_ylabel("dz/dt [m/s]")
    for ax in axes:
        ax.ticklabel_format(useOffset=False)
        ax.legend(fontsize=7)
    if scatter is not None:
        fig.colorbar(scatter, ax=axes, label="time [ms]")
    fig.suptitle(title or f"Poincare sections at azimuth {math.degrees(section):.0f} deg, once per revolution")
    return fig


def figures(case, t, series, events) -> dict:
    """``{file name: figure}`` of :data:`PNG_FILES` for a dynamics run (Agg backend set by the caller)."""
    j = case.analysis.ball
    scenario = case.operating.scenario
    t_spin = (spinup_time(t, series["Inner ring speed [rad/s]"], series["Rotor speed [rad/s]"])[0]
              if scenario == "drop" else None)
    zone = zone_times(t, series, j, t_spin, scenario)
    pitch = 0.5 * case.bearing.pitch_diameter
    return {"angular_displacement.png": angular_displacement_figure(t, series, j, zone),
            "collision_map.png": collision_map_figure(t, series, events, pitch, t_spin),
            "poincare.png": poincare_figure(t, series, j, section_azimuth(case))}


# ---------------------------------------------------------------------------- across speeds (Figs. 6-8)
@dataclass
class RunData:
    """What :func:`compare_runs` reads from a run folder."""

    folder: Path
    t: np.ndarray
    series: dict
    summary: dict
    case: dict  # case.resolved.toml (SI)

    @property
    def ball(self) -> int:
        return int(self.case.get("analysis", {}).get("ball", 0))

    @property
    def label(self) -> str:
        rpm = self.summary.get("Rotor speed at start [rpm]")
        return f"{rpm:,.0f} rpm" if isinstance(rpm, (int, float)) else self.folder.name


def read_run(folder) -> RunData:
    """A dynamics run folder: ``timeseries.npz``, ``summary.json`` and ``case.resolved.toml``."""
    import tomllib

    from lubedyn.lubrication.errors import InputError

    from lubedyn.outputs import read_timeseries

    folder = Path(folder)
    missing = [n for n in ("timeseries.npz", "summary.json", "case.resolved.toml") if not (folder / n).is_file()]
    if missing:
        raise InputError(f"{folder} is not a dynamics run folder with its time series: {', '.join(missing)} "
                         "missing (output.write must include 'timeseries')")
    series, _ = read_timeseries(folder / "timeseries.npz")
    return RunData(folder, np.asarray(series["Time [s]"]), series, json.loads((folder / "summary.json").read_text()),
                   tomllib.loads((folder / "case.resolved.toml").read_text()))


def ideal_orbit(run: RunData, samples: int = 361):
    """The ideal state (Figs. 6-8's reference): a ball on the pitch circle at the epicyclic
    ball-train speed w_c = w_i (1 - D/d_m)/2 of the ring's final speed: (positions (n, 3) [m],
    velocities (n, 3) [m/s]) over one revolution (z = 0, dz/dt = 0)."""
    b = run.case["bearing"]
    radius, gamma = 0.5 * b["pitch_diameter"], b["ball_diameter"] / b["pitch_diameter"]
    w_c = float(run.series["Inner ring speed [rad/s]"][-1]) * (1.0 - gamma) / 2.0
    th = np.linspace(0.0, 2 * math.pi, samples)
    pos = np.stack([radius * np.cos(th), radius * np.sin(th), np.zeros_like(th)], axis=1)
    vel = np.stack([-radius * w_c * np.sin(th), radius * w_c * np.cos(th), np.zeros_like(th)], axis=1)
    return pos, vel


SETTLING_COLUMNS = ("x", "y", "z", "orbital speed")


def settling_row(run: RunData) -> dict:
    """Settling and spin-up times [s] of a run: from its summary, computed from its time series when
    the summary predates them."""
    j = run.ball
    keys = [f"Settling time, ball {j} {c} [s]" for c in SETTLING_COLUMNS] + ["Inner ring spin-up time [s]"]
    source = run.summary
    if not all(k in source for k in keys):
        source = settling_times(run.t, run.series, j, run.summary.get("Scenario", "drop"))
    return {k: source.get(k) for k in keys}


def compare_runs(run_dirs, out_png) -> Path:
    """Paper B, Figs. 6-8: phase portraits of ball ``analysis.ball`` in x, y, z (one row per direction)
    for several runs (one column each, e.g. the four drop speeds) with the ideal-state orbit
    (:func:`ideal_orbit`, dashed), and a table of the settling and spin-up times
    (:func:`settling_row`).  Writes ``out_png`` (Agg) and returns its path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lubedyn.outputs import save_figure

    runs = [read_run(d) for d in run_dirs]
    if not runs:
        from lubedyn.lubrication.errors import InputError

        raise InputError("compare_runs needs at least one run folder")
    n = len(runs)
    fig = plt.figure(figsize=(3.4 * n + 1.0, 11))
    grid = fig.add_gridspec(4, n, height_ratios=(1, 1, 1, 0.45))
    for c, run in enumerate(runs):
        m = ball_motion(run.t, run.series, run.ball)
        ref_p, ref_v = ideal_orbit(run)
        for i, axis in enumerate("xyz"):
            ax = fig.add_subplot(grid[i, c])
            scale, unit = (1e6, "um") if axis == "z" else (1e3, "mm")
            ax.plot(m.position[:, i] * scale, m.velocity[:, i], lw=0.4, color="C0", label="model")
            ax.plot(ref_p[:, i] * scale, ref_v[:, i], "--", lw=1.0, color="C3", label="ideal state")
            if axis == "z":
                ax.plot([0], [0], "o", color="C3", ms=4)
            ax.set_xlabel(f"{axis} [{unit}]")
            ax.set_ylabel(f"d{axis}/dt [m/s]")
            if i == 0:
                ax.set_title(f"{run.label}, ball {run.ball}", fontsize=10)
            if i == 0 and c == 0:
                ax.legend(fontsize=7)
    rows = [settling_row(run) for run in runs]
    table_ax = fig.add_subplot(grid[3, :])
    table_ax.axis("off")
    head = [f"settling {c} [ms]" for c in SETTLING_COLUMNS] + ["ring spin-up [ms]"]
    cells = [["-" if v is None else f"{v * 1e3:.2f}" for v in row.values()] for row in rows]
    table = table_ax.table(cellText=cells, rowLabels=[r.label for r in runs], colLabels=head, loc="center")
    table.scale(1.0, 1.3)
    fig.suptitle("phase portraits across drop speeds with the ideal-state orbit (paper B, Figs. 6-8)")
    fig.tight_layout()
    try:
        out = save_figure(Path(out_png), fig)
    finally:
        plt.close(fig)
    log.info("wrote %s (%d runs)", out, n)
    return out
