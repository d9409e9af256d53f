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
- runs: :func:`run` (any scene, by ``case.scene``: :mod:`lubedyn.scenes`) and each scene's own ``run``:
  ``run_film``, ``run_ehl``, ``run_map``, ``run_dynamics``, ``run_static``, ``run_tapered``
  (``lubedyn.scenes.<scene>.run``); each returns the scene's result (``summary``, ``files``) and writes
  its outputs into ``out_dir`` when given; the bearing scenes' results read their time series by name
  (:class:`lubedyn.results.BearingResult`: ``res["Cage speed [rad/s]"]``, ``res.to_xarray()``);
- films: ``Film`` and ``solve`` of :mod:`lubedyn.lubrication`; maps: ``FilmMap`` of :mod:`lubedyn.maps`;
- rotordynamics: ``bearing_coefficients`` (a journal's K and C over speed) and ``to_ross`` (a ROSS
  bearing element of them), of :mod:`lubedyn.rotordynamics`;
- the sub-packages :mod:`lubedyn.lubrication`, :mod:`lubedyn.dynamics`, :mod:`lubedyn.scenes`,
  :mod:`lubedyn.papers` and ``lubedyn.cases``.

>>> import lubedyn
>>> case = lubedyn.load_case(lubedyn.CASES_DIR / "inclined_slider.toml", smoke=True)
>>> result = lubedyn.run(case)                 # nothing written: no out_dir
>>> round(result.summary["Load per unit width [N/m]"])   # N/m
63549

The rooms of the coupling layer:

=====================  ==========================================================
module / package       responsibility
=====================  ==========================================================
``units``              quantities at the input boundary: ``"50 um"`` -> 5e-05 m,
                       dimension checks ("has units of pressure, expected length");
                       the public name of the one parser, which lives on the
                       ground floor (``lubedyn.lubrication.laws.units``) so that
                       the films' constructors take the same strings
``config``             case files: TOML -> ``[smoke]`` and ``--set`` merged ->
                       pydantic validation (unknown keys with "did you mean",
                       one-line errors naming key, value and what is allowed) ->
                       SI model; bundled cases by name; ``case.resolved.toml``
``scenes``             one module per scene behind one interface
                       (:class:`lubedyn.scenes.Scene`) and the one registry
                       ``SCENES``: ``film``, ``ehl`` (+ ``ehl_case``, its
                       schema), ``map``, ``dynamics`` (+ ``dynamics_lyapunov``),
                       ``static``, ``tapered``; ``runner`` (a case -> its
                       scene), ``study`` (a runner over many cases)
``film_points``        point kinds of film maps (ball-ball Reynolds film, EHL
                       race and roller contacts: axes, outputs, evaluate)
``maps``               FilmMap: sweeps over local processes or Dask, resume,
                       fitted power law, accuracy report, self-describing file
``papers``             each paper's room: its parameter set, its claims or
                       figures (``wu2018``: paper A, ``zhang2024``: paper B)
``results``            a bearing run's result by name: ``res["Rotor speed [rad/s]"]``,
                       units, warnings, ``to_xarray()``
``rotordynamics``      journal-bearing K and C over speed (under a load or at a
                       fixed centre); ``to_ross``: a ROSS bearing element
``bounds``             physical bounds every output is checked against
``limits``             size limits: memory and work estimated before anything
                       is allocated
``validity``           validity warnings (pressure, film, Reynolds number)
``compilation``        says when numba compiles kernels on a first run
``outputs``            atomic writers (temporary file + rename) for run outputs;
                       a run's folder: staging, ``manifest.json``, stale
                       staging folders of killed runs removed
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
    **{f"run_{scene}": (f".scenes.{scene}", "run") for scene in ("film", "ehl", "map", "dynamics", "static",
                                                                "tapered")},
    "Film": (".lubrication", "Film"),
    "solve": (".lubrication", "solve"),
    "FilmMap": (".maps", "FilmMap"),
    "run": (".scenes.runner", "run"),
    **{name: (".rotordynamics", name) for name in ("bearing_coefficients", "to_ross", "BearingCoefficients")},
}
_SUBPACKAGES = ("lubrication", "dynamics", "cases", "scenes", "papers")

# no ``__all__``: the names above live in their own modules, where the API reference documents them


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
