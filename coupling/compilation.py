"""Say when numba compiles kernels, so that a first run is not a blank terminal.

numba compiles a ``cache=True`` kernel on its first call in a process and
loads it from the on-disk cache afterwards; only a cold cache compiles, and
then the dynamics scene spends tens of seconds in the compiler before its
progress bar starts (rhs, DOPRI5 kernel, forces, Benettin kernel).
:func:`report_compilation` listens to numba's ``"numba:compile"`` event, which
fires only when a kernel is really compiled (a cache hit does not fire it), and
logs on the logger ``lubedyn.compilation``: one INFO line as each top-level
kernel starts to compile (``compiling kernels (first run only): 1 rhs
(lubedyn.dynamics.cageless) ...``) and one at the end with the count and the time.  A
warm run logs nothing.  The CLI shows these INFO lines on a terminal even
without ``-v``.
"""
from __future__ import annotations

import contextlib
import logging
import time

log = logging.getLogger(__name__)


def kernel_name(dispatcher) -> str:
    """A readable name of a numba dispatcher: ``rhs (lubedyn.dynamics.cageless.kernels)``; a kernel source bound
    by :mod:`lubedyn.dynamics.specialise` is named by its source, ``dopri5 kernel (lubedyn.dynamics.integrators)``."""
    py = getattr(dispatcher, "py_func", None)
    module = getattr(py, "__module__", "") or ""
    name = getattr(py, "__qualname__", repr(dispatcher))
    from lubedyn.dynamics.specialise import kernel_label  # deferred: numba

    name = kernel_label(name)
    return f"{name} ({module})" if module else name


@contextlib.contextmanager
def report_compilation(logger: logging.Logger = log):
    """Log each top-level numba compilation inside the block (see the module docstring).

    Yields a dict that holds ``"Kernels compiled [-]"`` and ``"Compile time [s]"`` once the block ends.
    """
    from numba.core import event

    record = {"Kernels compiled [-]": 0, "Compile time [s]": 0.0}
    state = {"depth": 0, "t0": 0.0}

    class _Listener(event.Listener):
        def on_start(self, ev):
            state["depth"] += 1
            if state["depth"] == 1:
                state["t0"] = time.perf_counter()
                record["Kernels compiled [-]"] += 1
                logger.info("compiling kernels (first run only): %d %s ...", record["Kernels compiled [-]"],
                            kernel_name(ev.data.get("dispatcher")))

        def on_end(self, ev):
            state["depth"] -= 1
            if state["depth"] == 0:
                record["Compile time [s]"] += time.perf_counter() - state["t0"]

    listener = _Listener()
    event.register("numba:compile", listener)
    try:
        yield record
    finally:
        event.unregister("numba:compile", listener)
        if record["Kernels compiled [-]"]:
            logger.info("compiled %d kernels in %.1f s; later runs load them from the cache",
                        record["Kernels compiled [-]"], record["Compile time [s]"])
