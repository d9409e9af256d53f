"""A display never changes a result: the integrators give bit-identical trajectories and step
statistics however the run is cut into kernel calls (the progress bar cuts it into up to 200),
and the CLI writes the same summary.json with stderr on a terminal and on a pipe."""
from __future__ import annotations

import fcntl
import json
import math
import os
import pty
import struct
import subprocess
import sys
import termios
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from lubedyn.config import CASES_DIR
from lubedyn.dynamics import integrators as I

ROOT = Path(__file__).resolve().parents[1]
TIMINGS = ("Wall time [s]", "Integration wall time [s]", "Simulated time per wall second [s/s]", "Build time [s]",
           "Run time [s]", "Output write time [s]", "Benettin time [s]")
STAT_KEYS = ("Accepted steps [-]", "Rejected steps [-]", "RHS evaluations [-]")


@njit(cache=True)
def relaxation(t, y, args, dydt):
    """Van der Pol with mu = args[0]: slow drift and fast jumps, so the adaptive step (and the
    PI controller's memory, the rejections) changes by orders of magnitude along the run."""
    mu = args[0]
    dydt[0] = y[1]
    dydt[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0]


def _solve(method, n_chunks, progress=False):
    t_out = np.linspace(0.0, 12.0, 1201)
    kw = {"dt": 2e-3} if method == "rk4" else {"rtol": 1e-6, "atol": 1e-8}
    return I.integrate(relaxation, [2.0, 0.0], t_out, (8.0,), method=method, n_chunks=n_chunks,
                       progress=progress, **kw)


@pytest.mark.parametrize("method", ["dopri5", "ros2", "rk4"])
def test_chunked_runs_are_bit_identical(method):
    ref = _solve(method, 1)
    if method != "rk4":  # the case is a real adaptive history: rejections and a wide range of steps
        assert ref.stats["Rejected steps [-]"] > 2 and ref.stats["Accepted steps [-]"] > 150
    for n_chunks in (7, 200):
        res = _solve(method, n_chunks)
        assert np.array_equal(res.y, ref.y), (n_chunks, np.abs(res.y - ref.y).max())
        assert [res.stats[k] for k in STAT_KEYS] == [ref.stats[k] for k in STAT_KEYS], n_chunks


def test_progress_bar_does_not_change_the_result():
    ref = _solve("dopri5", 1)
    res = _solve("dopri5", None, progress=True)  # up to 200 chunks, a tqdm bar (off when not on a terminal)
    assert np.array_equal(res.y, ref.y)
    assert [res.stats[k] for k in STAT_KEYS] == [ref.stats[k] for k in STAT_KEYS]


@pytest.fixture(scope="module")
def bearing():
    """The main job's bearing (10 krpm rotor drop, 205 states) and 0.3 ms of it sampled every 2 us."""
    from lubedyn.scenes import dynamics as ds
    from lubedyn.config import load_case

    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml", smoke=True)
    setup = ds.build(case)
    return setup.model, setup.y0, np.linspace(0.0, 3e-4, 151)


@pytest.mark.parametrize("method", ["dopri5", "rk4"])
def test_bearing_chunked_runs_are_bit_identical(bearing, method):
    from lubedyn.dynamics.cageless import rhs

    model, y0, t_out = bearing
    kw = {"dt": 2e-7} if method == "rk4" else {"rtol": 1e-6, "atol": 1e-9}
    runs = [I.integrate(rhs, y0, t_out, model.args(), method=method, n_chunks=k, **kw) for k in (1, 7, 150)]
    ref = runs[0]
    assert ref.stats["Accepted steps [-]"] > 100
    for res in runs[1:]:
        assert np.array_equal(res.y, ref.y), np.abs(res.y - ref.y).max()
        assert [res.stats[k] for k in STAT_KEYS] == [ref.stats[k] for k in STAT_KEYS]


def _run_cli(out, terminal):
    """The CLI on a short drop with stderr on a pseudo-terminal (isatty() true) or on a pipe."""
    argv = [sys.executable, "-m", "lubedyn.cli", "run", str(CASES_DIR / "cageless_6206_10krpm_short.toml"),
            "--smoke", "--set", "integrator.duration='0.4 ms'", "--set", "analysis.lyapunov_exponents=0",
            "--set", "analysis.lyapunov=false", "--set", "output.write=[]", "--out", str(out)]
    if not terminal:
        proc = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=600)
        return proc.returncode, proc.stderr
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a 100-column terminal
    try:
        proc = subprocess.Popen(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=slave)
        os.close(slave)
        chunks = []
        while True:  # drain the terminal so that the child never blocks on a full pty buffer
            try:
                data = os.read(master, 4096)
            except OSError:  # EIO: the child closed its end
                break
            if not data:
                break
            chunks.append(data)
        proc.communicate(timeout=600)
    finally:
        os.close(master)
    return proc.returncode, b"".join(chunks).decode(errors="replace")


def test_cli_summary_is_the_same_on_a_terminal_and_on_a_pipe(tmp_path):
    code_tty, err_tty = _run_cli(tmp_path / "tty", terminal=True)
    code_pipe, err_pipe = _run_cli(tmp_path / "pipe", terminal=False)
    assert code_tty == 0 and code_pipe == 0, (err_tty, err_pipe)
    assert "simulated time" in err_tty and "simulated time" not in err_pipe  # the bar is shown on the terminal only
    tty = json.loads((tmp_path / "tty" / "summary.json").read_text())
    pipe = json.loads((tmp_path / "pipe" / "summary.json").read_text())

    def physics(summary):  # everything but the timings
        return {k: v for k, v in summary.items() if k not in TIMINGS}

    a, b = physics(tty), physics(pipe)
    assert a.keys() == b.keys()
    differ = {k: (a[k], b[k]) for k in a if a[k] != b[k] and not (isinstance(a[k], float) and math.isnan(a[k]))}
    assert not differ
    assert a["Accepted steps [-]"] > 100 and a["Simulated time [s]"] == pytest.approx(4e-4)


def test_background_result_hands_progress_and_errors_to_the_waiting_thread():
    """The whole-system spectrum runs in a thread (lubedyn.scenes.dynamics._BackgroundResult): with a label
    the function gets ``progress=``, whose last fraction the waiting thread reads (its bar, on a terminal,
    only displays it), the result is the function's own, and its exception reaches the caller."""
    import threading

    from lubedyn.scenes.dynamics import _BackgroundResult

    go = threading.Event()

    def work(x, progress=None):
        go.wait(5.0)
        for k in range(1, 5):
            progress(k / 4)
        return 2 * x

    job = _BackgroundResult(work, 21, progress_label="test")
    assert job.fraction == 0.0
    go.set()
    assert job.result() == 42 and job.fraction == 1.0

    def fails():
        raise ValueError("from the thread")

    with pytest.raises(ValueError, match="from the thread"):
        _BackgroundResult(fails).result()
