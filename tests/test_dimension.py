"""Correlation dimension (lubedyn.dynamics.analysis.dimension), the measure behind paper B's "fractal"
phase portraits (Figs. 6-8), on sets of known dimension: the Henon attractor 1.21 and the Lorenz
attractor 2.05 (Grassberger & Procaccia 1983, Physica D 9, 189), a circle 1, points on a sphere 2,
uniform noise in the plane 2; the verdicts a reader gets for each; and the summary entries of a run."""
from __future__ import annotations

import numpy as np
import pytest

from lubedyn.dynamics.analysis import correlation_dimension


def henon(n=20000):
    x = np.empty((n, 2))
    x[0] = (0.1, 0.1)
    for i in range(1, n):
        a, b = x[i - 1]
        x[i] = (1.0 - 1.4 * a * a + b, 0.3 * a)
    return x[1000:]


def test_henon_attractor_is_fractal():
    """Measured 1.198 (published 1.21 +- 0.01) with the Theiler window one map step."""
    res = correlation_dimension(henon(), theiler=1)
    assert res.value == pytest.approx(1.21, abs=0.05)
    assert res.verdict == "non-integer (fractal)"
    assert res.r_range[1] / res.r_range[0] >= 4.0


def test_lorenz_attractor_and_its_plane_projection():
    """Lorenz (sigma 10, rho 28, beta 8/3) sampled every 0.02 over 500 time units: measured 2.10 in three
    dimensions (published 2.05); within 0.1 of 2, so "integer": the stated limit of the verdict."""
    from scipy.integrate import solve_ivp

    def lorenz(t, y):
        return [10 * (y[1] - y[0]), y[0] * (28 - y[2]) - y[1], y[0] * y[1] - 8 / 3 * y[2]]

    s = solve_ivp(lorenz, [0, 520], [1, 1, 20], t_eval=np.arange(20, 520, 0.02), rtol=1e-9, atol=1e-9)
    res = correlation_dimension(s.y.T)
    assert res.value == pytest.approx(2.05, abs=0.1)


def test_curve_plane_and_sphere():
    """A closed curve (a periodic portrait) 1, noise that fills the plane 2 (measured 1.96), uniform
    points on a sphere 2 (a surface in 3-D, measured 1.997); an AR(1) noise's (x, dx) portrait, the
    kind of portrait a noisy coordinate draws, fills the plane too."""
    t = np.linspace(0.0, 2000.0, 20000)
    circle = correlation_dimension(np.c_[np.cos(t), -np.sin(t)])
    assert circle.value == pytest.approx(1.0, abs=0.05) and circle.verdict == "curve (periodic)"
    rng = np.random.default_rng(0)
    plane = correlation_dimension(rng.uniform(size=(20000, 2)))
    assert plane.value == pytest.approx(2.0, abs=0.1) and plane.verdict == "fills the space (d = 2)"
    v = rng.standard_normal((20000, 3))
    sphere = correlation_dimension(v / np.linalg.norm(v, axis=1)[:, None])
    assert sphere.value == pytest.approx(2.0, abs=0.05) and sphere.verdict == "integer"
    e = rng.standard_normal(20000)
    a = np.zeros(20000)
    for i in range(1, 20000):
        a[i] = 0.95 * a[i - 1] + e[i]
    assert correlation_dimension(np.c_[a[1:], np.diff(a)]).verdict == "fills the space (d = 2)"


def test_bad_and_degenerate_sets():
    with pytest.raises(ValueError, match="n >= 100"):
        correlation_dimension(np.zeros((10, 2)))
    with pytest.raises(ValueError, match="non-finite"):
        correlation_dimension(np.full((200, 2), np.nan))
    t = np.linspace(0, 10, 500)
    res = correlation_dimension(np.c_[t, np.zeros_like(t)])
    assert res.value is None and res.verdict == "no scaling range: a coordinate does not move"


def test_the_phase_portrait_entries_of_a_synthetic_ball():
    """paper B's figures module: a ball on a circle at constant speed whose z is a sine: the x, y and z
    portraits are closed curves, D2 1 within 0.05, "curve (periodic)"; a record shorter than 100 samples
    after the transient gives a note, not a number."""
    from types import SimpleNamespace

    from lubedyn.papers.zhang2024.figures import phase_portrait_dimensions

    t = np.linspace(0.0, 0.5, 20000)
    w = 2 * np.pi * 67.0
    pos = np.c_[0.023 * np.cos(w * t), 0.023 * np.sin(w * t), 1e-5 * np.sin(3.3 * w * t)]
    vel = np.c_[-0.023 * w * np.sin(w * t), 0.023 * w * np.cos(w * t), 3.3e-5 * w * np.cos(3.3 * w * t)]
    out = phase_portrait_dimensions(t, SimpleNamespace(position=pos, velocity=vel), 0, 0.0)
    for d in "xyz":
        assert out[f"Correlation dimension, ball 0 {d} phase portrait [-]"] == pytest.approx(1.0, abs=0.05)
        assert out[f"Correlation dimension, ball 0 {d} phase portrait verdict"] == "curve (periodic)"
    short = phase_portrait_dimensions(t, SimpleNamespace(position=pos, velocity=vel), 0, 0.4999)
    assert short["Correlation dimension, ball 0 x phase portrait [-]"] is None
    assert short["Correlation dimension, ball 0 x phase portrait, note"].startswith("not computed")
    # the orbit rule: with the azimuth, 33.5 orbits pass; 3.35 orbits (the last 0.05 s) are an arc of the
    # orbit, "record too short" and the record that would do (5 orbits: 0.0746 s), unless forced
    ball = SimpleNamespace(position=pos, velocity=vel, azimuth=w * t)
    assert phase_portrait_dimensions(t, ball, 0, 0.0)["Correlation dimension, ball 0 x phase portrait [-]"] == \
        pytest.approx(1.0, abs=0.05)
    arc = phase_portrait_dimensions(t, ball, 0, 0.45)
    assert arc["Correlation dimension, ball 0 z phase portrait [-]"] is None
    note = arc["Correlation dimension, ball 0 z phase portrait, note"]
    assert note.startswith("not computed: record too short: 3.35 orbits of ball 0") and "74.6 ms" in note
    forced = phase_portrait_dimensions(t, ball, 0, 0.45, force=True)
    assert forced["Correlation dimension, ball 0 x phase portrait [-]"] is not None
    assert forced["Correlation dimension, ball 0 x phase portrait, note"].startswith("forced")


def test_a_slope_above_the_space_is_no_dimension(monkeypatch):
    """The guard against an impossible value: pair counts made to grow as r^2.5 for a set in the plane (no set
    in 2 dimensions does) give value None and the verdict "no dimension", not a D2 of 2.5."""
    from lubedyn.dynamics.analysis import dimension as dm

    monkeypatch.setattr(dm, "pair_counts", lambda y, r, theiler: np.round(1e6 * (r / r[-1]) ** 2.5).astype(np.int64))
    t = np.linspace(0.0, 200.0, 4000)
    res = dm.correlation_dimension(np.c_[np.cos(t), np.sin(t)])
    assert res.value is None and res.verdict.startswith("no dimension: the slope 2.5 exceeds the space's dimension 2")
    monkeypatch.setattr(dm, "pair_counts", lambda y, r, theiler: np.round(1e6 * (r / r[-1]) ** 1.5).astype(np.int64))
    assert dm.correlation_dimension(np.c_[np.cos(t), np.sin(t)]).value == pytest.approx(1.5, abs=1e-6)
