"""A cold numba cache is announced: each top-level kernel compilation is logged as it starts
("compiling kernels (first run only)"), a warm call logs nothing, and the CLI shows these lines on a
terminal without -v."""
from __future__ import annotations

import io
import logging

import numpy as np
from numba import njit

from lubedyn import cli
from lubedyn.compilation import kernel_name, report_compilation


def _fresh_kernels():
    """Two new dispatchers (no cache): ``outer`` calls ``inner``, so compiling outer compiles inner inside it."""

    @njit(cache=False)
    def inner(x):
        return 2.0 * x

    @njit(cache=False)
    def outer(x):
        return inner(x) + 1.0

    return inner, outer


def test_each_top_level_compilation_is_logged_once_and_a_warm_call_not(caplog):
    _, outer = _fresh_kernels()
    caplog.set_level(logging.INFO, logger="lubedyn.compilation")
    with report_compilation() as record:
        assert outer(np.float64(3.0)) == 7.0
        assert outer(np.float64(4.0)) == 9.0  # same signature: no compilation
    lines = [r.getMessage() for r in caplog.records if r.name == "lubedyn.compilation"]
    assert len(lines) == 2, lines  # one start line (inner is compiled inside outer), one total
    assert lines[0].startswith("compiling kernels (first run only): 1 ") and "outer" in lines[0]
    assert lines[1].startswith("compiled 1 kernels in ")
    assert record["Kernels compiled [-]"] == 1 and record["Compile time [s]"] > 0.0
    caplog.clear()
    with report_compilation() as record:
        outer(np.float64(5.0))
    assert record["Kernels compiled [-]"] == 0
    assert not [r for r in caplog.records if r.name == "lubedyn.compilation"]


def test_bound_kernels_get_readable_names():
    from lubedyn.dynamics import integrators

    assert kernel_name(integrators.resumable_kernel("dopri5", integrators.no_jac).dispatcher) == (
        "dopri5 kernel (lubedyn.dynamics.integrators)")
    _, outer = _fresh_kernels()
    name = kernel_name(outer)
    assert name.startswith("_fresh_kernels.<locals>.outer (") and name.endswith("test_compilation)")


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def _stderrs(monkeypatch):
    """A terminal's stderr, then a pipe's, each installed as sys.stderr: ``(stream, is_terminal)``."""
    for terminal in (True, False):
        err = _Terminal() if terminal else io.StringIO()
        monkeypatch.setattr("sys.stderr", err)
        yield err, terminal


def test_cli_shows_compilation_lines_on_a_terminal_without_verbose(monkeypatch):
    for err, shown in _stderrs(monkeypatch):
        _, outer = _fresh_kernels()
        with cli._logging_to_stderr(0), report_compilation():
            outer(np.float64(1.0))
        line = "lubedyn: INFO: lubedyn.compilation: compiling kernels (first run only): 1 "
        assert (line in err.getvalue()) == shown
    assert logging.getLogger("lubedyn.compilation").level == logging.NOTSET  # restored


def test_the_second_process_is_announced_on_a_terminal_without_verbose(monkeypatch):
    """The CLI shows lubedyn.dynamics.specialise's INFO line (the kernels compiled in a second process) on a
    terminal without -v, as it shows lubedyn.compilation's, and not in a pipe."""
    for err, shown in _stderrs(monkeypatch):
        with cli._logging_to_stderr(0):
            logging.getLogger("lubedyn.dynamics.specialise").info(
                "compiling kernels (first run only): x in a second process")
        assert ("in a second process" in err.getvalue()) == shown
    assert logging.getLogger("lubedyn.dynamics.specialise").level == logging.NOTSET  # restored
