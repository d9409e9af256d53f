"""Paper B's figures (coupling/papers/zhang2024/figures.py, Figs. 3-8 and 11) on synthetic data with known
answers: the zones of Fig. 4 on a built residual; the figures, the summary entries and compare_runs on a
ball train on a perfect circle (the analyses under them: tests/test_run_analyses.py); one smoke run of the
10,000 rpm drop through the CLI for the summary keys and the PNGs."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from lubedyn.papers.zhang2024 import figures as pb
from lubedyn.dynamics import analysis as an
from lubedyn.dynamics.analysis import Collision
from lubedyn.dynamics.spectra import bearing_frequencies

from test_run_analyses import R0, W, Z, circle_series  # tests/ is on sys.path (rootdir conftest)


# ---------------------------------------------------------------------------- Fig. 4: zones
def test_zones_unsteady_smooth_surge():
    """Residual of the axial rate: large until 3 ms, a one-sample collision spike at 6 ms (ignored), a
    0.5 ms departure from 8 ms (the surge); the ring spun up at 2 ms."""
    t = np.linspace(0.0, 0.012, 12001)
    level = -2000.0
    res = np.where(t < 3e-3, 300.0, 0.0)
    res[6000] = 500.0
    res[(t >= 8e-3) & (t < 8.5e-3)] = 100.0
    z = pb.zones(t, res, level, 2e-3)
    assert z["unsteady until"] == pytest.approx(3e-3, abs=1.01e-6)
    assert z["surge from"] == pytest.approx(8e-3, abs=1.01e-6)
    assert z["why"] is None
    short = pb.zones(t, res, level, None)
    assert (short["unsteady until"], short["surge from"]) == (t[-1], None)
    assert short["why"].startswith("record too short")
    calm = pb.zones(t, 0 * res, level, None, scenario="steady")
    assert (calm["unsteady until"], calm["surge from"]) == (0.0, None)
    assert calm["why"].startswith("no surge") and "0.012 s" in calm["why"]
    # a departure shorter than the minimum duration is no surge
    brief = pb.zones(t, np.where(t < 3e-3, 300.0, 0.0) + np.where((t >= 8e-3) & (t < 8.05e-3), 100.0, 0.0), level, 2e-3)
    assert brief["surge from"] is None and brief["why"].startswith("no surge")


# ---------------------------------------------------------------------------- figures and compare_runs
class _Case:
    """The few case values the figures read."""

    class analysis:
        ball = 0
        vibration_band = (500.0, 1500.0)
        transient = 0.0

    class operating:
        scenario = "drop"

    class bearing:
        pitch_diameter = 2 * R0

    class slots:
        azimuths = [1.5 * math.pi]


def test_figures_have_labelled_axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.linspace(0.0, 0.02, 2001)
    s = circle_series(t)
    event = Collision(pair=0, t_start=0.0, t_end=1e-4, t_peak=5e-5, peak_force=50.0, force=(1.0, 2.0, 3.0),
                      position=(0.0, -R0, 0.0))
    figs = pb.figures(_Case, t, s, [event])
    assert sorted(figs) == sorted(pb.PNG_FILES)
    for fig in figs.values():
        labelled = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
        assert all("[" in ax.get_ylabel() for ax in labelled)
        assert any("[" in ax.get_xlabel() for ax in labelled)
        assert all("[" in ax.get_xlabel() for ax in labelled if ax.get_xlabel())
        plt.close(fig)
    summary = pb.summary_entries(_Case, t, s, [event], bearing_frequencies(W / math.pi, 9.525e-3, 2 * R0, Z))
    assert summary["Poincare points, ball 0 [-]"] == 1  # 8 rad in 20 ms: one passage of 270 deg after the start
    # too few for a section: the note gives the orbit's period, 2 pi / (400 rad/s) = 15.7 ms, and ten of them
    assert "one per orbit, 15.7 ms" in summary["Poincare points, ball 0, note"]
    assert "about 157 ms would give 10" in summary["Poincare points, ball 0, note"]
    assert summary["Collisions in quadrant IV (x > 0, y < 0) [-]"] == 1  # on the -y axis: counter-clockwise of it
    assert summary["Zone surge from [s]"] is None


def _write_run(folder, t, series, rpm, summary_extra=None):
    from lubedyn.outputs import write_timeseries

    folder.mkdir()
    write_timeseries(folder / "timeseries.npz", t, {k: v for k, v in series.items() if k != "Time [s]"})
    (folder / "summary.json").write_text(json.dumps({"Rotor speed at start [rpm]": rpm, "Scenario": "drop",
                                                     **(summary_extra or {})}))
    (folder / "case.resolved.toml").write_text(f"[bearing]\npitch_diameter = {2 * R0}\nball_diameter = 9.525e-3\n"
                                               "[analysis]\nball = 0\n")


def test_compare_runs_reads_folders_and_draws_the_ideal_orbit(tmp_path):
    """A train on the pitch circle at the epicyclic speed of its ring lies on the ideal-state orbit; the
    settling times come from the summary when it has them, else from the time series."""
    gamma = 9.525e-3 / (2 * R0)
    t = np.linspace(0.0, 0.02, 2001)
    runs = []
    for rpm in (10000, 15000):
        ring = rpm * math.pi / 30
        s = circle_series(t, w=ring * (1 - gamma) / 2, ring=ring)
        extra = {"Settling time, ball 0 x [s]": 1e-3} if rpm == 15000 else None
        _write_run(tmp_path / f"r{rpm}", t, s, rpm, extra)
        runs.append(tmp_path / f"r{rpm}")
    run = pb.read_run(runs[0])
    m = an.ball_motion(run.t, run.series, 0)
    pos, vel = pb.ideal_orbit(run)
    # the reference is the ellipse (x/a)^2 + (vx/b)^2 = 1 with a = d_m/2, b = a w_c; the train lies on it
    a, b = np.max(pos[:, 0]), np.max(vel[:, 0])
    assert a == pytest.approx(R0) and b == pytest.approx(R0 * 10000 * math.pi / 30 * (1 - gamma) / 2)
    assert np.max(np.abs((m.position[:, 0] / a) ** 2 + (m.velocity[:, 0] / b) ** 2 - 1)) < 1e-12
    assert pb.settling_row(run)["Settling time, ball 0 x [s]"] == 0.0  # computed: perfect circle
    out = pb.compare_runs(runs, tmp_path / "compare.png")
    assert out.is_file() and out.stat().st_size > 10_000
    with pytest.raises(Exception, match=r"timeseries.nc \(or .npz\)"):
        pb.read_run(tmp_path)


def test_script_draws_the_comparison(tmp_path):
    import subprocess
    import sys
    from pathlib import Path

    t = np.linspace(0.0, 0.01, 501)
    _write_run(tmp_path / "a", t, circle_series(t), 10000)
    script = Path(__file__).resolve().parents[1] / "benchmarks" / "paper_b_figures.py"
    done = subprocess.run([sys.executable, str(script), str(tmp_path / "a"), "--out", str(tmp_path / "c.png")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "c.png").is_file()


# ---------------------------------------------------------------------------- through the scene
def test_smoke_run_writes_the_figures_and_the_summary(tmp_path):
    from lubedyn import cli
    from lubedyn.scenes.dynamics import FIELD_FILES

    assert {f for f, _ in FIELD_FILES} >= set(pb.PNG_FILES)
    assert cli.main(["run", "cageless_6206_10krpm_short", "--smoke", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    for name in pb.PNG_FILES:
        assert (tmp_path / name).stat().st_size > 10_000
    # 1 ms of a drop: the ring is still spinning up, nothing has settled
    assert s["Inner ring spin-up time [s]"] is None and "not spun up" in s["Inner ring spin-up time, note"]
    assert s["Zone unsteady until [s]"] == s["Simulated time [s]"]
    assert sum(s[f"Collisions in quadrant {q} [-]"] for q in an.QUADRANTS) == s["Ball-ball collisions [-]"]
    assert "Dominant inner ring acceleration frequency, 500-1500 Hz [Hz]" in s
