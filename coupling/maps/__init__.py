"""Film maps: many film solves tabulated on axes, fitted, stored, handed to dynamics.

A map tabulates the outputs of a *point kind* (:mod:`lubedyn.film_points`:
``evaluate(params, point) -> {output: float}``, default axes, default
parameters) on the tensor grid of its axes.  :func:`build_map` runs the solves
(local processes by default, a Dask cluster when a scheduler is given, a
progress bar, every solved point persisted at once so that a killed build
resumes, the whole map rebuilt only when its inputs change) and returns a
:class:`FilmMap`.  Local workers store each point as they solve it, ignore
SIGINT (the parent handles Ctrl-C), and die with the parent (Linux
``PR_SET_PDEATHSIG``, else a thread that watches the parent's id); an
interrupt or any error cancels the pending points and stops the workers at
once, keeping every point already solved.

:class:`FilmMap`
    axes (:class:`MapAxis`: name with unit, nodes, ``log``/``linear``), one
    array of values per output, provenance (kind, parameters, axes, software
    versions, sha256 of every input), a fitted power law per output
    (:class:`PowerLawFit`, with its measured error), an accuracy report
    (interpolation against direct solves at random off-grid points),
    :meth:`FilmMap.save` / :meth:`FilmMap.load` (one ``.npz``: arrays plus a
    JSON header with a format version), :meth:`FilmMap.kernel_arrays` (plain
    arrays for :mod:`lubedyn.dynamics.interp`).

Interpolation (:mod:`lubedyn.dynamics.interp`): cubic Hermite on PCHIP node slopes
(``hermite``, default: C1, third order, the cheapest cubic query), sequential
monotone cubic (``pchip``) or multilinear (``linear``), in log space on ``log`` axes; the values are
interpolated in log space when every value of the output is > 0 and the kind does not declare it
``signed`` (the traction coefficient, odd in the slide-to-roll ratio), as they are otherwise (a force
over an approach-speed axis that crosses zero is signed).

Relative errors of the accuracy report are ``|a - b| / |b|`` for an output
that is nonzero and of one sign on the whole grid, and ``|a - b| / max(|b|,
1e-3 s)`` for an output that changes sign or vanishes somewhere (a force
through zero approach speed, the zero force of a separating, cavitated film),
s the largest |value| on the grid at the point's gap (its cell of the first
axis, which carries the scale): such an output is judged against its scale
there instead of against zero (:func:`local_floor`).

Coordinates matter more than nodes: a map is only as accurate as its function is smooth in the map's
coordinates.  The ball-ball film is tabulated on polar axes (gap, pressure number, squeeze angle) because
on (gap, squeeze number, entrainment speed) it has a cone at zero approach and entrainment speed, and the
EHL traction on a log slide-to-roll axis from 1e-3 because through SRR = 0 it is a step
(:mod:`lubedyn.film_points`).  :meth:`FilmMap.dynamics_film_map` hands a polar ball-ball map to the
bearing kernel (its polar arrays, tagged with their speed axis; :func:`cartesian_resample` gives the same
map on Cartesian nodes).

Accuracy tolerance: a map whose accuracy report shows a relative error above its tolerance (the
largest relative error of any output; :data:`ACCURACY_TOLERANCE` = 3 % unless the build says otherwise,
stored in the report as ``"tolerance"``) logs one WARNING line when it is built and whenever it is
loaded, naming the map, each output that misses, its worst error, the axis values of the worst point and
the tolerance (:meth:`FilmMap.accuracy_warning`); the map scene lists it under "Warnings" in summary.json.

Failed points: a point whose solve raises is recorded (its message kept) and
not cached, so a later build retries it.  With ``on_failure = "raise"`` (the
default) the build, after solving and persisting every other point, raises
:class:`~lubedyn.lubrication.errors.ConvergenceError` naming the failed points; with
``on_failure = "fill"`` each failed node takes the value of the nearest solved
node (in index space), and the map lists it under
``provenance["filled points"]``.

>>> import numpy as np
>>> m = FilmMap([MapAxis("Gap [m]", np.geomspace(1e-7, 1e-5, 9), "log")],
...             {"Force [N]": 1e-9 / np.geomspace(1e-7, 1e-5, 9)})
>>> float(np.round(m("Force [N]", 1e-6), 12))      # 1/h is exact in log-log
0.001
>>> round(m.fit_power_law("Force [N]").exponents[0], 9)
-1.0

Modules: ``registry`` (kinds, file format, axes), ``fit`` (power-law fits), ``filmmap`` (FilmMap),
``provenance`` (hashes, versions), ``sweep`` (solving points: processes, Dask, point store), ``build``
(build_map, accuracy report).  Every name is re-exported here.
"""
from __future__ import annotations

from lubedyn.maps.build import (  # noqa: F401  (the package's API)
    _fill_nearest, accuracy_report, build_map, random_points,
)
from lubedyn.maps.filmmap import (  # noqa: F401  (the package's API)
    CARTESIAN_ENTRAINMENT, CARTESIAN_SQUEEZE, FilmMap, KernelArrays, POLAR_AXES, _json_default,
    cartesian_resample,
)
from lubedyn.maps.fit import (  # noqa: F401  (the package's API)
    PowerLawFit, _significant, fit_power_law, local_floor, relative_error,
)
from lubedyn.maps.provenance import (  # noqa: F401  (the package's API)
    _canonical, code_fingerprint, point_hash, sha256_text, versions,
)
from lubedyn.maps.registry import (  # noqa: F401  (the package's API)
    ACCURACY_TOLERANCE, FORMAT, FORMAT_VERSION, METHODS, MapAxis, ZERO_FLOOR, _show_point, _unknown_key, axis_key,
    axis_unit, get_kind, kinds, register_kind, resolve_axes,
)
from lubedyn.maps.sweep import (  # noqa: F401  (the package's API)
    _PointStore, _chunks, _die_with_parent, init_worker, _limit_threads, sigint_blocked, _solve_chunk,
    _solve_dask, _solve_point, stop_pool, default_workers, solve_points,
)
