"""coupling: what joins films and dynamics -- case files, scenes, the CLI, run outputs.

=====================  ==========================================================
module                 responsibility
=====================  ==========================================================
``units``              quantities at the input boundary: ``"50 um"`` -> 5e-05 m,
                       dimension checks ("has units of pressure, expected length")
``config``             case files: TOML -> ``[smoke]`` and ``--set`` merged ->
                       pydantic validation (unknown keys with "did you mean",
                       one-line errors naming key, value and what is allowed) ->
                       SI model; ``case.resolved.toml``
``film_scene``         film scene: case -> mesh, gap, lubricant -> ``Film`` ->
                       solve -> summary (units in names), ``.vtu``, ``.png``
``ehl_scene``          EHL scene: case -> ``EHLContact`` (radii, from a bearing,
                       or Moes M, L) -> ``solve_ehl`` -> summary with Hertz and
                       closed-form film values, ``ehl.vtu``, ``profiles.png``
``film_points``        point kinds of film maps (ball-ball Reynolds film, EHL
                       race contacts: axes, outputs, evaluate) and paper B's
                       contact laws as plain-float reference functions
``maps``               FilmMap: sweeps over local processes or Dask, resume,
                       fitted power law, accuracy report, self-describing file
``map_scene``          map scene: a point kind swept over its axes -> map file,
                       PNG, ``.pvd`` series of the film fields
``dynamics_scene``     dynamics scene: the cage-less ball bearing of paper B ->
                       integrate -> collisions, Lyapunov exponents, spectrum,
                       time series, ``.pvd`` of balls, rings and films, PNGs
``static_scene``       static scene: paper A's tapered roller bearing at quasi-static
                       equilibrium (``dynamics.tapered.quasistatic``) -> loads,
                       ``bearing.vtu``
``tapered_scene``      tapered scene: paper A's bearing in time -> tilt, skew,
                       slip, cage whirl, ``bearing.pvd``
``dynamics_lyapunov``  (see the dynamics scene) end of the transient,
                       co-rotating coordinates, Wolf's, Rosenstein's and
                       Benettin's exponents of a run
``paper_b_figures``    paper B's figures and the quantities behind them
``guide_land``         FEM map of the guide-land film of paper A's cage
``parameters``         each paper's data in one cited module (Zhang2024: paper
                       B, Wu2018: paper A)
``limits``             size limits: memory and work estimated before anything
                       is allocated
``validity``           validity warnings (pressure, film, Reynolds number)
``compilation``        says when numba compiles kernels on a first run
``outputs``            atomic writers (temporary file + rename) for run outputs;
                       a run's folder: staging, ``manifest.json``, stale
                       staging folders of killed runs removed
``study``              studies: a base case over axes of ``--set`` values and
                       ensemble members, each run a run folder (resumable,
                       local processes or Dask) -> ``study.csv``, ``.json``,
                       ``.png``
``cli``                ``lubedyn run | validate | study | cases | info``; exit codes
                       0 ok, 1 failed solve, 2 input error, 3 output not
                       writable, 130 interrupted, 141 stdout closed
=====================  ==========================================================

``coupling`` imports ``lubrication`` and ``dynamics``; never the other way round.
"""
from __future__ import annotations


def __getattr__(name: str):
    """``__version__`` looked up on first use: importing ``coupling`` (and so starting the CLI, whose
    SIGINT handling begins in ``cli.main``) stays free of ``importlib.metadata`` (40 ms)."""
    if name != "__version__":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from importlib.metadata import PackageNotFoundError, version

    try:
        value = version("lubedyn")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        value = "0+unknown"
    globals()["__version__"] = value
    return value
