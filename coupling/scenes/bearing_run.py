"""One run driver for the bearing scenes in the time domain: build -> integrate -> analyse -> write.

A scene hands :func:`drive` a *bearing run model* (:class:`BearingRunModel`): an object that knows its
case and builds its kernel model, says how to integrate it (:class:`Integration`: the right-hand side,
initial state, output times, packed arguments, integrator options and how an integrator failure reads as a
case error), turns the sampled states into the scene's summary entries (:meth:`BearingRunModel.analyse`),
and names the files (:class:`lubedyn.outputs.RunFiles`: time-series columns, extra text files, ParaView
frames, figures, a background analysis to wait for).  The driver times the build and the integration
(integrated in chunks with a progress bar of simulated time on a terminal; a Ctrl-C is taken between
chunks), passes the scene's entries through :func:`lubedyn.outputs.run_summary` (identity, bounds,
assumed values, timings) and writes everything through :func:`lubedyn.outputs.write_bearing_run`.

The cage-less ball bearing (:mod:`lubedyn.scenes.dynamics`) and the tapered roller bearing
(:mod:`lubedyn.scenes.tapered`) run through it; a third bearing is its model module, its parameter module and
a run model here.
"""
from __future__ import annotations

import logging
import sys
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Protocol

from lubedyn import outputs
from lubedyn.compilation import report_compilation
from lubedyn.config import resolved_toml
from lubedyn.results import TimeSeries
from lubedyn.dynamics.errors import DynamicsInputError, IntegrationError
from lubedyn.dynamics.integrators import integrate as run_integrator

log = logging.getLogger(__name__)


@dataclass
class Integration:
    """What :func:`integrate` needs from a run model: ``options`` are the keyword arguments of
    :func:`lubedyn.dynamics.integrators.integrate` (method, tolerances, step, omega_max, max_steps);
    ``on_error(exc)`` turns its :class:`~lubedyn.dynamics.errors.DynamicsInputError` or
    :class:`~lubedyn.dynamics.errors.IntegrationError` into the error the user reads (naming the case keys)."""

    rhs: Any
    y0: Any
    t_out: Any
    args: tuple
    options: dict = field(default_factory=dict)
    n_chunks: int = 100
    on_error: Callable[[Exception], Exception] | None = None


@dataclass
class Timing:
    """Wall-clock marks of a run [s]: its start (``time.perf_counter``), the build's and the integration's
    durations."""

    t0: float
    build: float = 0.0
    integration: float = 0.0


class BearingRunModel(Protocol):
    """A scene's side of :func:`drive`."""

    case: Any

    def build(self) -> None:
        """Build the kernel model and its initial state (raises InputError naming the case key)."""

    def describe(self) -> str:
        """One line for the log before the integration."""

    def integration(self) -> Integration:
        """How to integrate the built model."""

    def analyse(self, res, timing: Timing) -> dict:
        """The scene's summary entries from the integrator's result (``res.t``, ``res.y``, ``res.stats``)."""

    def files(self, summary: dict, timing: Timing) -> outputs.RunFiles:
        """The run's files (computed only if written) and any background analysis to wait for."""

    def result(self, summary: dict, files: list):
        """The scene's run object returned to the caller."""


def integrate(spec: Integration):
    """:func:`lubedyn.dynamics.integrators.integrate` of ``spec`` in ``spec.n_chunks`` kernel calls (bit-identical
    to one call; control comes back to Python between them, so a Ctrl-C is taken within one chunk), a progress
    bar on a terminal; an integrator error re-raised as ``spec.on_error`` makes it."""
    try:
        return run_integrator(spec.rhs, spec.y0, spec.t_out, spec.args, progress=sys.stderr.isatty(),
                              n_chunks=spec.n_chunks, **spec.options)
    except (DynamicsInputError, IntegrationError) as exc:
        if spec.on_error is None:
            raise
        raise spec.on_error(exc) from None


def import_in_background(names) -> threading.Thread | None:
    """Import the modules ``names`` in a daemon thread, while the integration runs: its compiled kernels
    release the GIL (:mod:`lubedyn.dynamics.specialise`), so the second core loads what the analysis and the
    outputs import later (scipy.signal for the spectra, xarray and pandas for the time series, matplotlib and
    VTK for figures and frames, which the forked output workers then inherit).  Measured on the README's
    main job: benchmarks/main_job.py.  An import that fails is left to the code that needs it (it raises
    there, as without this).  Nothing is started with no names or with ``LUBEDYN_BACKGROUND_IMPORTS=0``."""
    import os

    names = [n for n in names if n not in sys.modules]
    if not names or os.environ.get("LUBEDYN_BACKGROUND_IMPORTS", "1") == "0":
        return None

    def target():
        import importlib

        for name in names:
            try:
                importlib.import_module(name)
            except Exception as exc:  # noqa: BLE001 - the code that needs it raises, in its own thread
                log.debug("background import of %s failed: %s", name, exc)

    thread = threading.Thread(target=target, name="lubedyn-imports", daemon=True)
    thread.start()
    return thread


def drive(model: BearingRunModel, out_dir=None, *, name: str, source: str = "", smoke: bool = False):
    """Build, integrate, analyse and (with ``out_dir``) write a bearing run; kernels compiled on a cold cache
    are reported as they compile (:func:`lubedyn.compilation.report_compilation`).  Returns
    ``model.result(summary, files)``."""
    with report_compilation():
        timing = Timing(t0=time.perf_counter())
        model.build()
        timing.build = time.perf_counter() - timing.t0
        log.info("integrating %s", model.describe())
        # what the analysis and the outputs will import, imported meanwhile (the kernels release the GIL)
        imports = import_in_background(model.modules(writing=out_dir is not None)) if hasattr(model, "modules") \
            else None
        res = integrate(model.integration())
        timing.integration = time.perf_counter() - timing.t0 - timing.build
        scene = model.analyse(res, timing)
        if imports is not None:  # done before anything forks (a module lock held by a thread the child lacks)
            while imports.is_alive():
                imports.join(0.1)  # short joins: a Ctrl-C is taken at once
        summary = outputs.run_summary(model.case, name, smoke, scene, timing.t0, timing.build)
        files = model.files(summary, timing)
        written = []
        if out_dir is None:
            if files.complete is not None:
                summary = files.complete(summary)
        else:
            resolved = resolved_toml(model.case, outputs.resolved_header(name, source, smoke))
            written, summary = outputs.write_bearing_run(out_dir, resolved, summary, model.case.output.write, files,
                                                          model.case.output.timeseries_format)
        result = model.result(summary, written)
        if files.columns is not None:
            result.series = TimeSeries(files.t, files.columns)  # the names the time series file uses, computed on read
        return result
