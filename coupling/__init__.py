"""lubedyn: lubricant films, film maps and rolling-bearing dynamics; this package is the coupling layer,
what joins films and dynamics -- case files, scenes, the CLI, run outputs.

One installed namespace over three layers (``pyproject.toml`` maps each onto its folder of the checkout):

========================  ==========================================  ================
package                   what                                        folder
========================  ==========================================  ================
``lubedyn``               the coupling layer (modules below)          ``coupling/``
``lubedyn.lubrication``   lubricant films by finite elements          ``lubrication/``
``lubedyn.dynamics``      compiled rolling-bearing dynamics           ``dynamics/``
``lubedyn.cases``         the bundled case files and film maps        ``cases/``
========================  ==========================================  ================

The main API, loaded on first use (importing ``lubedyn`` imports nothing heavy):

- cases: ``load_case`` (a TOML file, ``smoke``, ``--set``-style ``overrides``), ``load_case_text``,
  ``CaseError``, ``CASES_DIR`` and ``bundled_cases`` (the bundled cases), of :mod:`lubedyn.config`;
- runs: :func:`run` (any scene, by ``case.scene``) and each scene's own ``run``: ``run_film``, ``run_ehl``,
  ``run_map``, ``run_dynamics``, ``run_static``, ``run_tapered`` (``lubedyn.<scene>_scene.run``); each
  returns the scene's result (``summary``, ``files``) and writes its outputs into ``out_dir`` when given;
- films: ``Film`` and ``solve`` of :mod:`lubedyn.lubrication`; maps: ``FilmMap`` of :mod:`lubedyn.maps`;
- the sub-packages :mod:`lubedyn.lubrication`, :mod:`lubedyn.dynamics` and ``lubedyn.cases``.

>>> import lubedyn
>>> case = lubedyn.load_case(lubedyn.CASES_DIR / "inclined_slider.toml", smoke=True)
>>> result = lubedyn.run(case)                 # nothing written: no out_dir
>>> round(result.summary["Load per unit width [N/m]"])   # N/m
63549

The modules of the coupling layer:

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
                       equilibrium (``lubedyn.dynamics.tapered.quasistatic``) -> loads,
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

``lubedyn`` (the coupling layer) imports ``lubedyn.lubrication`` and ``lubedyn.dynamics``; never the
other way round.
"""
from __future__ import annotations

import importlib

# name -> (module, attribute), imported on first use (PEP 562): importing ``lubedyn`` (and so starting the
# CLI, whose SIGINT handling begins in ``cli.main``) stays free of numpy, scikit-fem, numba and
# ``importlib.metadata`` (40 ms)
_LAZY = {
    **{name: (".config", name) for name in ("CASES_DIR", "CaseError", "bundled_cases", "load_case",
                                            "load_case_text")},
    **{f"run_{scene}": (f".{scene}_scene", "run") for scene in ("film", "ehl", "map", "dynamics", "static",
                                                                "tapered")},
    "Film": (".lubrication", "Film"),
    "solve": (".lubrication", "solve"),
    "FilmMap": (".maps", "FilmMap"),
}
_SUBPACKAGES = ("lubrication", "dynamics", "cases")

# no ``__all__``: the names above live in their own modules, where the API reference documents them


def run(case, out_dir=None, *, name: str | None = None, source: str = "", smoke: bool = False):
    """Run a validated case (:func:`load_case`) with its scene's ``run`` (``lubedyn.<scene>_scene.run``,
    what ``lubedyn run`` calls) and return the scene's result; with ``out_dir`` the outputs are written
    there.  ``name`` (default: the scene) and ``source`` (the case file) label the summary, ``smoke`` marks
    it as a smoke run."""
    module = importlib.import_module(f".{case.scene}_scene", __name__)
    return module.run(case, out_dir, name=name or case.scene, source=source, smoke=smoke)


def __getattr__(name: str):
    if name in _LAZY:
        module, attribute = _LAZY[name]
        value = getattr(importlib.import_module(module, __name__), attribute)
    elif name in _SUBPACKAGES:
        value = importlib.import_module(f".{name}", __name__)
    elif name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            value = version("lubedyn")
        except PackageNotFoundError:  # pragma: no cover - not installed
            value = "0+unknown"
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY) | set(_SUBPACKAGES) | {"__version__"})
