"""Post-processing of bearing runs: plain numpy on sampled states and contact diagnostics (no numba: these
run once per run on arrays of a few thousand samples), independent of any paper's figures.

- :mod:`~lubedyn.dynamics.analysis.dimension`: correlation dimension of a sampled set (Grassberger-Procaccia;
  what "fractal" is measured as);
- :mod:`~lubedyn.dynamics.analysis.collisions`: ball-ball collision events and their summary; slip ratios;
- :mod:`~lubedyn.dynamics.analysis.motion`: a ball's motion (inertial and co-rotating) from a cage-less run's
  time-series columns;
- :mod:`~lubedyn.dynamics.analysis.settling`: settling times against the ball train's steady pattern, the
  inner ring's spin-up time;
- :mod:`~lubedyn.dynamics.analysis.rotation`: angular displacement (R(q) w_body integrated), axial rates;
- :mod:`~lubedyn.dynamics.analysis.poincare`: Poincare sections at a fixed azimuth;
- :mod:`~lubedyn.dynamics.analysis.frequency`: dominant frequency in a band, nearest bearing line;
- :mod:`~lubedyn.dynamics.analysis.quadrants`: collisions by quadrant around the inner ring;
- :mod:`~lubedyn.dynamics.analysis.windows`: a tapered roller bearing's per-zone window statistics (tilt,
  skew, slip) and periodicity.

Every public name of these modules is importable from ``lubedyn.dynamics.analysis``.
"""
from lubedyn.dynamics.analysis.collisions import Collision, collision_events, collision_summary, slip_ratio
from lubedyn.dynamics.analysis.dimension import CorrelationDimension, correlation_dimension
from lubedyn.dynamics.analysis.frequency import (
    MAX_HARMONIC, SPECTRUM_LINES, dominant_frequency, nearest_line, ring_acceleration, spectrum_limit,
    vibration_entries)
from lubedyn.dynamics.analysis.motion import BallMotion, ball_motion, n_balls, run_columns
from lubedyn.dynamics.analysis.poincare import poincare_section
from lubedyn.dynamics.analysis.quadrants import QUADRANTS, collision_entries, collision_table, quadrant_of
from lubedyn.dynamics.analysis.rotation import angular_displacement, axial_rates, ball_angular_displacement
from lubedyn.dynamics.analysis.settling import (
    AZIMUTH_BINS, BAND_FRACTION, FINAL_FRACTION, FINAL_MARGIN, SPINUP_TOLERANCE, final_start, settling_time,
    settling_times, spinup_time, steady_residuals)
from lubedyn.dynamics.analysis.windows import periodicity, window_stats, window_summary

__all__ = [
    "Collision", "collision_events", "collision_summary", "slip_ratio",
    "CorrelationDimension", "correlation_dimension",
    "MAX_HARMONIC", "SPECTRUM_LINES", "dominant_frequency", "nearest_line", "ring_acceleration", "spectrum_limit",
    "vibration_entries",
    "BallMotion", "ball_motion", "n_balls", "run_columns",
    "poincare_section",
    "QUADRANTS", "collision_entries", "collision_table", "quadrant_of",
    "angular_displacement", "axial_rates", "ball_angular_displacement",
    "AZIMUTH_BINS", "BAND_FRACTION", "FINAL_FRACTION", "FINAL_MARGIN", "SPINUP_TOLERANCE", "final_start",
    "settling_time", "settling_times", "spinup_time", "steady_residuals",
    "periodicity", "window_stats", "window_summary",
]
