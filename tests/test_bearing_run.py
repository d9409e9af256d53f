"""The bearing scenes' one write path (lubedyn.outputs.write_bearing_run) and run driver
(lubedyn.scenes.bearing_run): what is written for each ``output.write`` choice, that the background
analysis completes the summary before the time series copies it, that an output not asked for is never
computed, and that an integrator failure reaches the user as the scene's error."""
from __future__ import annotations

import json

import numpy as np
import pytest

from lubedyn import outputs
from lubedyn.scenes import bearing_run


def _files(calls, **kw):
    t = np.linspace(0.0, 1e-3, 5)

    def columns():
        calls.append("columns")
        return {"x [m]": t * 2.0}

    def frames():
        import pyvista as pv

        calls.append("frames")
        for when in (t[0], t[-1]):
            yield when, pv.Sphere(radius=1.0, theta_resolution=6, phi_resolution=4)

    def figures():
        calls.append("figures")
        return {}

    def complete(summary):
        calls.append("complete")
        summary["Background [-]"] = 7
        return summary

    return outputs.RunFiles(t=t, columns=columns, meta=lambda full: {"Summary": full},
                            texts=lambda: {"extra.csv": "a,b\n1,2\n"}, frames=frames, frame_ext="vtp",
                            figures=figures, complete=complete, **kw)


@pytest.mark.parametrize("fmt", ["netcdf", "npz"])
def test_every_output_asked_for_is_written_and_the_time_series_carries_the_completed_summary(tmp_path, fmt,
                                                                                           monkeypatch):
    """The serial path's order (the output workers, which draw in forked processes whose calls this list
    cannot see, are tested against it in tests/test_output_workers.py)."""
    monkeypatch.setenv("LUBEDYN_OUTPUT_WORKERS", "0")
    calls = []
    written, summary = outputs.write_bearing_run(tmp_path, "# resolved\n", {"Case": "c", "Scene": "s"},
                                                 ["timeseries", "pvd", "png"], _files(calls, write_time=True), fmt)
    series_file = outputs.TIMESERIES_FILES[fmt]
    assert sorted(p.name for p in written) == ["bearing.pvd", "case.resolved.toml", "extra.csv", "frames",
                                               "summary.json", series_file]
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == ["frame_00000.vtp", "frame_00001.vtp"]
    # the frames and figures are made before the summary is completed, the time series after
    assert calls == ["frames", "figures", "complete", "columns"]
    series, meta = outputs.read_timeseries(tmp_path / series_file)
    np.testing.assert_array_equal(series["x [m]"], np.linspace(0.0, 2e-3, 5))
    assert meta["Summary"]["Background [-]"] == 7 and "Output write time [s]" not in meta["Summary"]
    on_disk = json.loads((tmp_path / "summary.json").read_text())
    assert on_disk["Background [-]"] == 7 and on_disk["Output write time [s]"] >= 0.0
    assert summary["Background [-]"] == 7 and "Output write time [s]" not in summary
    pvd = (tmp_path / "bearing.pvd").read_text()
    assert 'timestep="0.0"' in pvd and 'timestep="0.001"' in pvd and 'file="frames/frame_00001.vtp"' in pvd
    assert json.loads((tmp_path / "manifest.json").read_text())["files"] == [
        "bearing.pvd", "case.resolved.toml", "extra.csv", "frames/frame_00000.vtp", "frames/frame_00001.vtp",
        "summary.json", series_file]


def test_outputs_not_asked_for_are_neither_computed_nor_written(tmp_path):
    calls = []
    written, _ = outputs.write_bearing_run(tmp_path, "# resolved\n", {"Case": "c"}, [], _files(calls))
    assert sorted(p.name for p in written) == ["case.resolved.toml", "summary.json"]
    assert calls == ["complete"]  # the summary is still completed: summary.json carries it
    assert "Output write time [s]" not in json.loads((tmp_path / "summary.json").read_text())


def test_an_integrator_failure_reaches_the_user_as_the_scene_error(tmp_path):
    """A step budget of 10 DOPRI5 steps cannot reach the end of the tapered record: the integrator's IntegrationError
    reaches the user through the driver as the scene's ConvergenceError naming the case key, and nothing
    is written."""
    from lubedyn.config import load_case
    from lubedyn.lubrication.errors import ConvergenceError
    from lubedyn.scenes import tapered

    case = load_case("cases/trb_fig5_2400rpm.toml", smoke=True, overrides=["integrator.method=dopri5",
                                                                        "integrator.max_steps=10"])
    with pytest.raises(ConvergenceError, match=r"integrator\.rtol = "):
        bearing_run.drive(tapered.TaperedRunModel(case), tmp_path / "out", name="trb")
    assert not (tmp_path / "out").exists()
