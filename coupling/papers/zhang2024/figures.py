"""Paper B's figures and the quantities behind them, from a dynamics run.

Paper B (Zhang et al., *Symmetry* 16 (2024) 741, sections 3.1-3.3 and 4.2)
studies a cage-less 6206 ball bearing whose rotor drops onto the inner ring.
This module turns a run of :mod:`lubedyn.scenes.dynamics` (its time series as
a name -> array mapping, the names of the run's time series) into numbers a user
can compare with the paper, and into the figures.  The analyses themselves are
the paper-independent ones of :mod:`lubedyn.dynamics.analysis`; this module
chooses which the paper's figures show, lays the figures out and holds the
paper's own rule for its zones:

- **settling times** (Fig. 3): :func:`lubedyn.dynamics.analysis.settling.settling_times`
  (the settling rule is in :mod:`lubedyn.dynamics.analysis.settling`) of ball
  ``analysis.ball``, per direction x, y, z, and the inner ring's spin-up time;
- **angular displacement** of three consecutive balls (Fig. 4,
  ``angular_displacement.png``): :func:`lubedyn.dynamics.analysis.rotation.angular_displacement`,
  with the paper's three zones (:func:`zones`);
- **collision map** (Fig. 5, ``collision_map.png``): each ball-ball collision
  a needle at its contact point around the inner ring's centre, length
  proportional to its force, coloured by time (quadrants:
  :mod:`lubedyn.dynamics.analysis.quadrants`);
- **Poincare sections** (not in the paper, ``poincare.png``): the ball's
  co-rotating (r, dr/dt) and (z, dz/dt) each time it passes the first slot's
  azimuth (:func:`section_azimuth`, :func:`lubedyn.dynamics.analysis.poincare.poincare_section`); with
  fewer than :data:`POINCARE_MIN_POINTS` (10) points the figure and the summary
  (``"Poincare points, ball j, note"``) say so and how long a record would give ten
  (:func:`poincare_shortfall`; measured: the 1 ms smoke run of the main job has none, and
  ball 0's mean orbital speed over that millisecond, the ball train starting from rest,
  gives one point per 196 ms);
- the dominant inner-ring acceleration frequency in a band (Fig. 11's
  950-1000 Hz at 3,000 rpm; :mod:`lubedyn.dynamics.analysis.frequency`);
- **phase portraits across speeds** (Figs. 6-8): :func:`compare_runs` reads
  several run folders.

Zones (Fig. 4)
--------------
The middle ball's axial angular rate (the rate of its z angular displacement,
the z component of R(q) w_body) is compared with the ball train's steady
pattern at its azimuth (the residual of
:func:`lubedyn.dynamics.analysis.settling.steady_residuals`; the rate is about 4 % lower in the
unloaded upper half and 4 % higher over the slot, so a plain level would call
every slot passage a surge).  *Unsteady* until the inner ring's spin-up ends
(:func:`lubedyn.dynamics.analysis.settling.spinup_time`) and the residual has come within ``SURGE_THRESHOLD``
(3 %) of the ball's steady rate (its spin has caught up); *smooth* from then;
*surge* from the first later departure beyond the same band lasting at least
``SURGE_MIN_DURATION`` (0.1 ms: a single collision's spike does not count).  A
run without a drop starts smooth; one that does not spin up within its record
is unsteady throughout.
"""
from __future__ import annotations

import functools
import json
import logging
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lubedyn.dynamics.analysis.dimension import correlation_dimension
from lubedyn.dynamics.analysis.frequency import vibration_entries
from lubedyn.dynamics.analysis.motion import ball_motion, n_balls
from lubedyn.dynamics.analysis.poincare import poincare_section
from lubedyn.dynamics.analysis.quadrants import collision_entries, collision_table
from lubedyn.dynamics.analysis.rotation import axial_rates, ball_angular_displacement
from lubedyn.dynamics.analysis.settling import final_start, settling_times, spinup_time, steady_residuals
from lubedyn.lubrication.errors import InputError
from lubedyn.outputs import panels, read_timeseries, save_figure, timeseries_path

log = logging.getLogger(__name__)

SURGE_THRESHOLD = 0.03
SURGE_MIN_DURATION = 1e-4
PNG_FILES = ("angular_displacement.png", "collision_map.png", "poincare.png")


# ---------------------------------------------------------------------------- zones (Fig. 4)
def zones(t, residual, level: float, t_spinup, threshold: float = SURGE_THRESHOLD,
          min_duration: float = SURGE_MIN_DURATION, scenario: str = "drop") -> dict:
    """Ends of the paper's zones (Fig. 4) by the rule of the module docstring:
    ``{"unsteady until": s, "surge from": s or None, "why": reason}``.  ``residual``: the middle ball's
    axial angular rate minus the ball train's steady pattern at its azimuth [rad/s]; ``level``: its
    typical steady rate [rad/s].  ``why`` says why a zone is missing: a record that ends inside the
    unsteady zone (its end is then the record's: "record too short"), or a smooth zone with no surge;
    None when both were found."""
    t = np.asarray(t, dtype=float)
    if scenario != "drop":
        start = float(t[0])
    elif t_spinup is None:
        return {"unsteady until": float(t[-1]), "surge from": None,
                "why": "record too short: the inner ring is still spinning up at its end"}
    else:
        start = float(t_spinup)
    band = threshold * abs(level)
    inside = np.abs(np.asarray(residual, dtype=float)) <= band
    calm = np.flatnonzero(inside & (t >= start))
    if calm.size == 0:
        return {"unsteady until": float(t[-1]), "surge from": None,
                "why": f"record too short: the axial rate never comes within {threshold:.0%} of its steady level"}
    i0 = int(calm[0])
    edges = np.diff(np.concatenate(([0], (~inside[i0:]).astype(np.int8), [0])))
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
        if t[i0 + b - 1] - t[i0 + a] >= min_duration:
            return {"unsteady until": float(t[i0]), "surge from": float(t[i0 + a]), "why": None}
    return {"unsteady until": float(t[i0]), "surge from": None,
            "why": (f"no surge: after {t[i0]:.4g} s the axial rate leaves the {threshold:.0%} band around its "
                    f"steady level for less than {min_duration * 1e3:.3g} ms at a time, to the record's end "
                    f"({t[-1]:.4g} s)")}


def zone_times(t, series, ball: int, t_spinup, scenario: str = "drop") -> dict:
    """:func:`zones` of ball ``ball`` from the columns (the steady pattern of every ball's axial rate in
    the final window, :func:`steady_residuals`)."""
    rates = axial_rates(t, series)
    i_final = final_start(t)
    azimuth = np.stack([series[f"Ball {j} Orbital angle [rad]"] for j in range(rates.shape[1])], axis=1)
    residual = steady_residuals(azimuth, rates, i_final)[:, ball]
    return zones(t, residual, float(np.median(rates[i_final:, ball])), t_spinup, scenario=scenario)


# ---------------------------------------------------------------------------- Poincare sections
#: fewer passages than this and ``poincare.png`` says so on the figure, and the summary why (a section of a
#: few points shows no structure: a periodic orbit, a torus and chaos all look like scattered dots)
POINCARE_MIN_POINTS = 10


def _duration(seconds: float) -> str:
    return f"{seconds * 1e3:.3g} ms" if seconds < 1.0 else f"{seconds:.3g} s"


def poincare_shortfall(t, azimuth, points: int, minimum: int = POINCARE_MIN_POINTS) -> str | None:
    """None when a section has at least ``minimum`` points, else why not and how long a run would give
    them: one point per orbit of the ball, whose period is taken from its mean orbital speed over the
    record (unwrapped ``azimuth`` [rad] against ``t`` [s])."""
    if points >= minimum:
        return None
    t = np.asarray(t, dtype=float)
    u = np.unwrap(np.asarray(azimuth, dtype=float))
    span = float(t[-1] - t[0]) if t.size > 1 else 0.0
    rate = abs(float(u[-1] - u[0])) / span if span > 0 else 0.0
    why = f"only {points} section point{'s' if points != 1 else ''} (fewer than {minimum}) in {span * 1e3:.3g} ms"
    if rate > 0:
        period = 2 * math.pi / rate
        why += (f": one per orbit, {_duration(period)} at the ball's mean orbital speed; a record of about "
                f"{_duration(minimum * period)} would give {minimum}")
    return why


def section_azimuth(case) -> float:
    """The Poincare section: the first functional slot's azimuth, else 270 deg (the bottom)."""
    return float(case.slots.azimuths[0]) if case.slots.azimuths else 1.5 * math.pi


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
    if z["why"]:
        out["Zones, note"] = z["why"]
    out.update(collision_entries(t, series, events, t_spin))
    motion = ball_motion(t, series, j)
    times, _ = poincare_section(t, motion.azimuth, motion.radius, section_azimuth(case))
    out[f"Poincare points, ball {j} [-]"] = int(times.size)
    short = poincare_shortfall(t, motion.azimuth, int(times.size))
    if short is not None:
        out[f"Poincare points, ball {j}, note"] = f"poincare.png is not a section yet: {short}"
    out.update(vibration_entries(t, series, freqs, case.analysis.vibration_band, case.analysis.transient))
    from lubedyn.scenes.dynamics_lyapunov import forced  # the record rule's analysis.force

    out.update(phase_portrait_dimensions(t, motion, j, case.analysis.transient, force=forced(case)))
    return out


#: orbits of the ball a phase portrait must hold for its correlation dimension (a fraction of an orbit is
#: an arc: "a curve" whatever the motion; the 0.1 s bundled drops hold 5.9 at 10,000 rpm, 0.4 s studies 25)
D2_MIN_ORBITS = 5.0


def phase_portrait_dimensions(t, motion, j: int, transient: float, force: bool = False) -> dict:
    """Figs. 6-8's "fractal", measured: the correlation dimension of ball ``j``'s phase portrait (inertial
    displacement against velocity) per direction after ``transient``
    (:func:`lubedyn.dynamics.analysis.dimension.correlation_dimension`): 1 a closed curve, 2 a portrait
    that fills the plane, in between a fractal; with its verdict, or a note where it has none.  A record
    holding fewer than :data:`D2_MIN_ORBITS` orbits of the ball (its mean orbital speed from
    ``motion.azimuth`` when given) gives a note "not computed: record too short ..." unless ``force``
    (``analysis.force``), as the Lyapunov estimators' record rule does."""
    keep = np.asarray(t) >= transient
    out = {}
    why = None
    azimuth = getattr(motion, "azimuth", None)
    if azimuth is not None and np.count_nonzero(keep) > 1:
        u = np.unwrap(np.asarray(azimuth, dtype=float)[keep])
        orbits = abs(float(u[-1] - u[0])) / (2 * math.pi)
        if orbits < D2_MIN_ORBITS:
            span = float(np.asarray(t)[keep][-1] - np.asarray(t)[keep][0])
            need = D2_MIN_ORBITS * span / orbits if orbits > 0 else float("inf")
            why = (f"record too short: {orbits:.3g} orbits of ball {j} after the transient (at least "
                   f"{D2_MIN_ORBITS:g}: about {_duration(need)} of record at its mean orbital speed)")
    for i, d in enumerate("xyz"):
        key = f"Correlation dimension, ball {j} {d} phase portrait [-]"
        pts = np.c_[motion.position[keep, i], motion.velocity[keep, i]]
        if pts.shape[0] < 100:
            out[key], out[key[:-4] + ", note"] = None, f"not computed: {pts.shape[0]} samples after the transient (at least 100)"
            continue
        if why is not None:
            if not force:
                out[key], out[key[:-4] + ", note"] = None, f"not computed: {why}"
                continue
            out[key[:-4] + ", note"] = f"forced (analysis.force = true): {why}; the value describes an arc"
        res = correlation_dimension(pts)
        out[key] = res.value
        out[key[:-4] + " verdict"] = res.verdict
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


def angular_displacement_figure(t, series, ball: int, zone: dict | None, title: str = "", into=None):
    """Paper B, Fig. 4: angular displacement of balls ``ball - 1, ball, ball + 1`` about the inertial
    x, y, z axes against time (:func:`lubedyn.dynamics.analysis.rotation.angular_displacement`: R(q) w_body
    integrated), the zones
    shaded."""
    z = n_balls(series)
    fig, axes = panels(into, 3, 1, figsize=(8, 7.5), sharex=True)
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
    if into is None:  # the caller's figure keeps its own layout
        fig.tight_layout()
    return fig


def collision_map_figure(t, series, events, pitch_radius: float, t_spinup=None, title: str = "", into=None):
    """Paper B, Fig. 5: each ball-ball collision a needle at its contact point in the x-y plane around
    the inner ring's centre (quadrants I-IV, load zone at the bottom), pointing outward for a
    positive force (inward for a negative component), length proportional to the force, coloured by
    the time of its peak; panels: normal force, Fx, Fy, Fz."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    tp, pos, fn, comp = collision_table(t, series, events)
    fig, axes = panels(into, 2, 2, figsize=(10, 9), layout="constrained")
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


def poincare_figure(t, series, ball: int, section: float, title: str = "", into=None):
    """Poincare sections: ball ``ball``'s co-rotating (r, dr/dt) and (z, dz/dt) at each passage of the
    azimuth ``section`` (large dots, coloured by time), and every other ball's passages (small grey
    dots: the ball train shares one steady pattern, so they fill a short run's section)."""
    fig, axes = panels(into, 1, 2, figsize=(10, 4.3), layout="constrained")
    z = n_balls(series)
    scatter = None
    own = 0
    for j in [k for k in range(z) if k != ball] + [ball]:
        m = ball_motion(t, series, j)
        times, vals = poincare_section(t, m.azimuth, np.stack([m.radius, m.radial_velocity, m.position[:, 2],
                                                              m.velocity[:, 2]], axis=1), section)
        for ax, (a, b), scale in zip(axes, ((0, 1), (2, 3)), (1e3, 1e6)):
            if j == ball:
                own = times.size
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
    short = poincare_shortfall(t, ball_motion(t, series, ball).azimuth, own)
    if short is not None:
        for ax in axes:
            ax.text(0.5, 0.5, "too few points for a section:\n" + short.replace(": one per", ":\none per")
                    .replace("; a record", ";\na record"), transform=ax.transAxes, ha="center", va="center",
                    fontsize=8, color="C3", wrap=True, bbox=dict(facecolor="white", alpha=0.85, edgecolor="C3"))
    return fig


def drawings(case, t, series, events) -> dict:
    """``{file name: draw}`` of :data:`PNG_FILES` for a dynamics run, ``draw(into=None)`` returning the
    figure (new, or drawn in ``into``: :func:`lubedyn.outputs.panels`); the spin-up time and zones are
    computed on the first draw that needs them."""
    j = case.analysis.ball
    scenario = case.operating.scenario
    pitch = 0.5 * case.bearing.pitch_diameter

    @functools.cache
    def spin_and_zone():
        t_spin = (spinup_time(t, series["Inner ring speed [rad/s]"], series["Rotor speed [rad/s]"])[0]
                  if scenario == "drop" else None)
        return t_spin, zone_times(t, series, j, t_spin, scenario)

    return {"angular_displacement.png":
            lambda into=None: angular_displacement_figure(t, series, j, spin_and_zone()[1], into=into),
            "collision_map.png":
            lambda into=None: collision_map_figure(t, series, events, pitch, spin_and_zone()[0], into=into),
            "poincare.png": lambda into=None: poincare_figure(t, series, j, section_azimuth(case), into=into)}


def figures(case, t, series, events) -> dict:
    """``{file name: figure}`` of :data:`PNG_FILES` for a dynamics run (Agg backend set by the caller)."""
    return {name: draw() for name, draw in drawings(case, t, series, events).items()}


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
    """A dynamics run folder: its time series (``timeseries.nc`` or ``.npz``,
    :func:`lubedyn.outputs.timeseries_path`), ``summary.json`` and ``case.resolved.toml``."""
    import tomllib

    folder = Path(folder)
    missing = [n for n in ("summary.json", "case.resolved.toml") if not (folder / n).is_file()]
    try:
        path = timeseries_path(folder)
    except FileNotFoundError:
        missing.insert(0, "timeseries.nc (or .npz)")
    if missing:
        raise InputError(f"{folder} is not a dynamics run folder with its time series: {', '.join(missing)} "
                         "missing (output.write must include 'timeseries')")
    series, _ = read_timeseries(path)
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

    runs = [read_run(d) for d in run_dirs]
    if not runs:
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
