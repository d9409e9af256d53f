"""Shared builders for the film verification tests, and the round-off audit mode.

``LUBEDYN_ROUNDOFF_ULPS=N`` (and optionally ``LUBEDYN_ROUNDOFF_SEED``) perturbs every film and
EHL residual of the session by N units of round-off (tests/roundoff.py), to show that the
convergence decisions and tolerances of the tests hold on machines whose last bits differ from
this one's.  Measured on the solver tests (tests/test_ehl*.py, test_roundoff, cavitation,
nonlinear films, film coefficients, analytic Reynolds, convergence orders, film points, solver
paths, maps, traction maps, race films: 185 tests): every one passes at N = 1 (seeds 2, 5) and
N = 10 (seed 3), except the Dask map test, whose worker processes do not inherit the
perturbation.  At N = 30 three fail by construction, because they check the perturbed residual
itself (the finite-difference Jacobian test, the Swift-Stieber complementarity residual at 1e-9),
and the nested-vs-plain JFO bounds of test_solver_paths hold to about 10-20 units (measured
there).
"""
import os


import numpy as np
import pytest

from lubedyn.lubrication import Cavitation, Film, JournalBearing, Lubricant
from lubedyn.lubrication import mesh as meshes


@pytest.fixture
def long_journal_film():
    """Factory: an infinitely long journal bearing as a 1-D problem.

    A periodic strip (``mesh.rectangle(..., periodic_x=True)``) one element
    wide in the axial direction with no Dirichlet boundary (zero axial flux,
    so the solution is independent of z) and the Sommerfeld gauge
    p(theta = 0) = 0 applied at *every* dof of the column theta = 0 (pinning a
    single dof of the column would leave its neighbours free and break the
    z-invariance of the discrete solution).

    The journal is displaced along -x (``e_x = -eps c``), so that
    h = c (1 + eps cos theta): theta = 0 is the largest gap and theta equals
    the classical angle phi of :mod:`lubedyn.lubrication.closed_form`.  The journal
    is the upper surface, turning towards +theta with surface speed U
    (``velocity_upper = (U, 0)``, bearing fixed, so u_m = U/2).  With the
    displacement d = -x and n = d turned +90 deg in the direction of rotation
    = -y, the closed-form components map as F_x = +W_r, F_y = -W_t (per unit
    length: divide the mode forces by the strip width).
    """

    def build(radius, clearance, eps, eta, surface_speed, n, element="P2", cavitation="none", width=1e-3):
        xs = np.linspace(0.0, 2.0 * np.pi * radius, n + 1)
        m = meshes.rectangle(xs, [0.0, width], cell="quad", periodic_x=True)
        column = [0.0, width] if element == "P1" else [0.0, 0.5 * width, width]
        return Film(
            m,
            JournalBearing(radius, clearance, -eps * clearance, 0.0),
            Lubricant.newtonian(eta),
            velocity_upper=(surface_speed, 0.0),
            dirichlet={},
            pressure_points=tuple(((0.0, y), 0.0) for y in column),
            element=element,
            cavitation=Cavitation(cavitation, 0.0),
        )

    return build


def pytest_configure(config):
    ulps = os.environ.get("LUBEDYN_ROUNDOFF_ULPS")
    if ulps:
        from roundoff import perturb_residuals

        perturb_residuals(setattr, float(ulps), int(os.environ.get("LUBEDYN_ROUNDOFF_SEED", "1")))
    if os.environ.get("PYTEST_XDIST_WORKER"):
        _share_compilation_between_workers()


def _share_compilation_between_workers():
    """Under pytest-xdist, one worker compiles a cached numba kernel while the others wait for it,
    then load it from the on-disk cache, instead of compiling the same kernel at the same time.

    On a cold cache both workers reach the same kernels (the tapered and the cage-less models, the
    integrators, the Benettin kernel) within seconds of each other, and each compiled its own copy
    (measured: the tapered model 63-75 s of CPU in each worker).  A lock file per cached function
    (``fcntl.flock``, in the temp dir, named by the cache's index path) is taken around the
    outermost ``Dispatcher.compile`` of the process; the waiting worker's compile then finds the
    signature in the cache, as in a warm run.  Functions numba cannot cache are not locked.

    The workers also compile in process (``LUBEDYN_BACKGROUND_COMPILE=0``, unless set): the second
    core a run would compile on is the other worker's, and two workers would each start a compiler
    process for the same kernels.  The tests of that mechanism set the variable themselves."""
    import fcntl
    import hashlib
    import tempfile
    import threading
    from pathlib import Path

    from numba.core.caching import NullCache
    from numba.core.dispatcher import Dispatcher

    os.environ.setdefault("LUBEDYN_BACKGROUND_COMPILE", "0")
    folder = Path(tempfile.gettempdir()) / "lubedyn-numba-compile-locks"
    folder.mkdir(exist_ok=True)
    original = Dispatcher.compile
    state = threading.local()

    def compile_once(self, sig):
        index = getattr(getattr(getattr(self, "_cache", None), "_cache_file", None), "_index_path", None)
        if getattr(state, "depth", 0) or index is None or isinstance(self._cache, NullCache):
            return original(self, sig)
        lock = folder / (hashlib.sha1(index.encode()).hexdigest() + ".lock")
        with open(lock, "a") as fh:
            fcntl.flock(fh, fcntl.LOCK_EX)
            state.depth = 1
            try:
                return original(self, sig)
            finally:
                state.depth = 0
                fcntl.flock(fh, fcntl.LOCK_UN)

    Dispatcher.compile = compile_once


@pytest.fixture(autouse=True)
def _close_figures():
    """Close the figures a test leaves open (pyplot keeps them), so that the figures of later tests in the same
    worker do not pass matplotlib's 20-open-figures warning, an error under this suite's warning filter."""
    yield
    import sys

    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:
        plt.close("all")
