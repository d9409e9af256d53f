"""The first-hour pages of the documentation run as written: every ``python`` code block of
docs/python.md ("From Python in 10 minutes") and docs/study_dask.md ("Run a study on many machines") is
executed (and the README's), in order, in one namespace per page, and what the page says it shows is checked against a
second source: the summary against the time series and the frame files, the bearing coefficients against
the load they carry, the study's loads against the film's linearity in the runner speed and the slider's
closed form (63.55 kN/m at 5 m/s)."""
from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import numpy as np
import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"


def blocks(page: str) -> list[str]:
    """The ``python`` fenced code blocks of a Markdown page (relative to docs/), in order."""
    return re.findall(r"^```python\n(.*?)^```", (DOCS / page).read_text(), flags=re.S | re.M)


def run_page(page: str, monkeypatch, tmp_path) -> dict:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYVISTA_OFF_SCREEN", "true")
    namespace: dict = {"__name__": f"docs_{Path(page).stem}"}
    code = blocks(page)
    assert code, f"{page} has no python block"
    for k, block in enumerate(code):
        exec(compile(block, f"{page} block {k + 1}", "exec"), namespace)
    return namespace


def test_from_python_page_runs(monkeypatch, tmp_path):
    ns = run_page("python.md", monkeypatch, tmp_path)
    summary, columns, out, reader = ns["summary"], ns["columns"], ns["out"], ns["reader"]
    assert ns["case"].scene == "tapered"
    assert summary["Largest cup load [N]"] == ns["result"].summary["Largest cup load [N]"]   # the file = the result
    t = columns["Time [s]"]
    assert t.size == summary["Samples [-]"]
    assert t[-1] == pytest.approx(summary["Simulated time [s]"], rel=1e-12)
    assert len(reader.time_values) == len(list((out / "frames").iterdir()))
    assert (out / "cone_y.png").stat().st_size > 10_000
    assert (ns["cone_y"] == columns["Cone y [m]"]).all()               # the result by name = the file
    assert all(note for note in ns["not_computed"].values())
    coef = ns["coef"]                                                 # the journal under 2 kN along -y
    assert np.allclose(coef.speed, np.array([1500, 3000, 6000]) * np.pi / 30, rtol=1e-12)
    assert np.all(np.abs(coef.force - [0.0, 2000.0]) <= 1e-8 * 2000.0)   # the film carries the load
    assert np.all(np.diff(coef["Eccentricity ratio [-]"]) < 0)         # faster: a thicker film (larger S)
    if ns["bearing"] is not None:                                     # with ROSS: its matrix at a given speed
        assert np.allclose(ns["bearing"].K(coef.speed[1])[:2, :2], coef.K[1], rtol=1e-9)
    assert (out / "mine.png").stat().st_size > 10_000                 # the figures drawn from Python
    assert len(ns["left"].axes) == 2 and "slip" in ns["result"].kinds
    from lubedyn.lubrication import closed_form as cf                   # the film built with units
    assert ns["slider_load"] == pytest.approx(cf.inclined_slider_load(40e-6, 20e-6, 0.05, 0.05, 2.5), rel=1e-3)


def test_readme_python_block_runs(monkeypatch, tmp_path):
    """The README's lines (the main job at smoke size, about 20 s, nothing written): the series by name, its
    xarray copy and the summary agree: the rotor's last speed in rad/s is the summary's in rpm times pi / 30,
    and the dataset has one sample per time of the result."""
    pytest.importorskip("xarray")
    ns = run_page("../README.md", monkeypatch, tmp_path)
    res, ds = ns["res"], ns["ds"]
    rotor = res["Rotor speed [rad/s]"]
    assert rotor.size == res.t.size == ds.sizes["time"]
    assert rotor[-1] * 30 / math.pi == pytest.approx(res.summary["Rotor speed at end [rpm]"], rel=1e-12)
    assert res.files == [] and list(tmp_path.iterdir()) == []       # no out_dir: nothing written
    assert len(ns["fig"].axes) == 3 and ns["fig"].axes[0].lines[0].get_ydata().size == res.t.size


def test_study_page_runs_on_a_local_cluster(monkeypatch, tmp_path):
    pytest.importorskip("distributed")
    ns = run_page("study_dask.md", monkeypatch, tmp_path)
    result = ns["result"]
    assert result.backend.startswith("dask") and result.total == 3 and not result.failed
    with open(ns["folder"] / "out" / "study.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    speed_col = next(c for c in rows[0] if c.startswith("motion.velocity_lower") and "SI" in c)
    per_speed = {float(r[speed_col]): float(r["Load per unit width [N/m]"]) for r in rows}
    assert sorted(per_speed) == [2.0, 5.0, 8.0]
    ratios = [load / u for u, load in per_speed.items()]
    assert max(ratios) == pytest.approx(min(ratios), rel=1e-9)       # the film is linear in the speed
    assert per_speed[5.0] == pytest.approx(63550, rel=1e-3)           # the slider's closed form
    load = ns["load"]                                                 # the table as a Dataset = study.csv
    assert load.attrs["units"] == "N/m" and list(load.dims) == ["motion.velocity_lower"]
    assert [float(v) for v in load.values] == [per_speed[u] for u in (2.0, 5.0, 8.0)]
