"""Frames and figures written by forked workers (issue 42, decision 2: outputs off the critical path):
the same files as the serial path, byte for byte; a worker's error is one line and fails the run."""
from __future__ import annotations

import json
import os

import numpy as np
import pytest

from lubedyn import outputs
from lubedyn.config import CASES_DIR, load_case, resolved_toml
from lubedyn.outputs import OutputError, RunFiles, read_timeseries, write_bearing_run
from lubedyn.scenes.bearing_run import Timing, drive
from lubedyn.scenes.dynamics import CagelessRunModel

forking = pytest.mark.skipif(not hasattr(os, "fork"), reason="forked workers need os.fork")
TIMES = ("Run time [s]", "Output write time [s]", "Build time [s]", "Integration wall time [s]", "Wall time [s]",
         "Simulated time per wall second [s/s]")


def files_below(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@forking
@pytest.mark.slow  # a smoke integration and two writes: 6-16 s on 2 shared cores
def test_workers_write_the_files_of_the_serial_path(tmp_path):
    """The main job's smoke run (5 frames and the collision frames, 7 figures, the time series) analysed once
    and written twice, by the workers and serially: every frame, the .pvd, every PNG and collisions.csv the
    same bytes; the time series the same arrays (the netCDF file carries its write time); the summaries the
    same but for the timings."""
    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml", smoke=True,  # the analyses are not the point
                     overrides=["analysis.lyapunov=false", "analysis.lyapunov_exponents=0"])
    model = CagelessRunModel(case)
    res = drive(model, None, name="main", smoke=True)
    resolved = resolved_toml(case, "test")
    written = {}
    for workers in (True, False):
        out = tmp_path / ("workers" if workers else "serial")
        files = model.files(dict(res.summary), Timing(t0=0.0))
        paths, _ = write_bearing_run(out, resolved, dict(res.summary), case.output.write, files, workers=workers)
        written[workers] = (out, files_below(out))
    (a, fa), (b, fb) = written[True], written[False]
    assert sorted(fa) == sorted(fb)
    assert sum(name.startswith("frames/") for name in fa) >= 5 and sum(name.endswith(".png") for name in fa) == 7
    for name in fa:
        if name.startswith("frames/") or name.endswith((".png", ".pvd", ".csv", ".toml")):
            assert fa[name] == fb[name], name
    ca, ma = read_timeseries(a / "timeseries.nc")
    cb, mb = read_timeseries(b / "timeseries.nc")
    assert list(ca) == list(cb) and all(np.array_equal(ca[k], cb[k]) for k in ca)
    sa, sb = (json.loads((d / "summary.json").read_text()) for d in (a, b))
    assert {k: v for k, v in sa.items() if k not in TIMES} == {k: v for k, v in sb.items() if k not in TIMES}


def _files(figure_error=None, frame_error=None):
    """A tiny run: 3 samples, one column, 2 frames of a sphere, one figure; ``*_error`` raised by that worker."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    def figures():
        if figure_error is not None:
            raise figure_error
        fig = Figure(figsize=(2, 2))
        fig.subplots().plot([0, 1], [1, 0])
        yield "line.png", fig

    def frames():
        import pyvista as pv

        if frame_error is not None:
            raise frame_error
        for k in range(2):
            yield float(k), pv.Sphere(radius=1.0 + k)

    return RunFiles(t=np.arange(3.0), columns=lambda: {"x [m]": np.arange(3.0)}, frames=frames, figures=figures)


@forking
@pytest.mark.parametrize("where", ["figures", "frames"])
def test_a_worker_error_is_one_line_and_nothing_is_committed(tmp_path, where):
    """A drawing that raises in its worker: OutputError naming the worker and the error in one line, the
    run not committed (no summary.json, no staging folder left), the other worker ended."""
    boom = ValueError("boom\nsecond line")
    files = _files(**{f"{where[:-1]}_error": boom})
    with pytest.raises(OutputError) as info:
        write_bearing_run(tmp_path / "out", "", {"Case": "x"}, ["timeseries", "pvd", "png"], files, "npz", workers=True)
    message = str(info.value)
    assert f"the {where} worker failed: ValueError: boom second line" in message and "\n" not in message
    assert not (tmp_path / "out" / "summary.json").exists() and not list((tmp_path / "out").glob(".staging-*"))


@forking
def test_a_worker_that_cannot_write_names_the_file(tmp_path, monkeypatch):
    """An OSError in a worker (disk full while saving a figure) is the serial path's message: the file as
    the user knows it and the cause."""
    import errno

    real = outputs.write_bytes

    def full(path, data):
        if str(path).endswith(".png"):
            raise OSError(errno.ENOSPC, "No space left on device", str(path))
        return real(path, data)

    monkeypatch.setattr(outputs, "write_bytes", full)
    out = tmp_path / "out"
    with pytest.raises(OutputError) as info:
        write_bearing_run(out, "", {"Case": "x"}, ["png"], _files(), "npz", workers=True)
    assert str(info.value) == f"cannot write {out / 'line.png'}: No space left on device"


def test_workers_off_where_asked(monkeypatch):
    """LUBEDYN_OUTPUT_WORKERS=0 (set in the pool workers of studies and map sweeps) writes serially."""
    monkeypatch.setenv("LUBEDYN_OUTPUT_WORKERS", "0")
    assert not outputs.output_workers()
    monkeypatch.setenv("LUBEDYN_OUTPUT_WORKERS", "1")
    assert outputs.output_workers() == (hasattr(os, "fork") and len(os.sched_getaffinity(0)) >= 2)


@forking
def test_an_interrupt_ends_the_writers_before_the_staging_folder_goes(tmp_path):
    """On Ctrl-C the CLI calls discard_staging: a writer still running is ended and reaped first, so it
    cannot write into (and so recreate) the staging folder being removed."""
    import time

    writer = outputs.ForkedWriter("figures", lambda: time.sleep(60), tmp_path)
    pid = writer.pid
    outputs.discard_staging()
    assert writer.pid is None and writer not in outputs._writers
    with pytest.raises(ChildProcessError):  # reaped already: no such child
        os.waitpid(pid, os.WNOHANG)
