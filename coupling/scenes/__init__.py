"""Scenes: what a case file runs (``scene = "film"`` ...), one module each, behind one interface.

=============  =====================================================================================
scene          module: what it runs
=============  =====================================================================================
``film``       :mod:`lubedyn.scenes.film`: a Reynolds film by finite elements -> pressure, load
``ehl``        :mod:`lubedyn.scenes.ehl`: an elastohydrodynamic point or line contact
``map``        :mod:`lubedyn.scenes.map`: a film-point kind swept over its axes -> a film map
``dynamics``   :mod:`lubedyn.scenes.dynamics`: the cage-less ball bearing in time
``static``     :mod:`lubedyn.scenes.static`: the tapered roller bearing at quasi-static equilibrium
``tapered``    :mod:`lubedyn.scenes.tapered`: the tapered roller bearing in time
=============  =====================================================================================

and :mod:`lubedyn.scenes.study`, a runner over them (a base case over axes of ``--set`` values).
The two bearings in time (``dynamics``, ``tapered``) run through one driver,
:mod:`lubedyn.scenes.bearing_run` (build, integrate, analyse, write through
:func:`lubedyn.outputs.write_bearing_run`): each hands it a run model.

A scene module implements :class:`Scene` (the module itself is the object: its functions and
constants are the protocol's members).  :data:`SCENES` is the one registry: the case loader
(:func:`lubedyn.config.case_model`), the command line and the study runner
(:mod:`lubedyn.scenes.runner`) find a scene through :func:`get` and nowhere else.  A new scene is one
module here and one line in :data:`SCENES`.

(Inside this package ``map`` names the map scene's module once it is imported, not the builtin.)  This
package's ``__init__`` imports nothing heavy (no scene module, no numpy): the registry is read
before a case is validated.
"""
from __future__ import annotations

import importlib
from typing import Any, Protocol, runtime_checkable

from lubedyn.lubrication.errors import InputError, did_you_mean

# scene name -> module; a scene's module is imported when a case of that scene is read
SCENES = {
    "film": "lubedyn.scenes.film",
    "ehl": "lubedyn.scenes.ehl",
    "map": "lubedyn.scenes.map",
    "dynamics": "lubedyn.scenes.dynamics",
    "static": "lubedyn.scenes.static",
    "tapered": "lubedyn.scenes.tapered",
}


class SceneResult(Protocol):
    """What a scene's ``run`` returns: the summary (names with units, :mod:`lubedyn.outputs`) and the
    files written (empty without ``out_dir``); scenes add their own fields (the film, the time series)."""

    summary: dict
    files: list


@runtime_checkable
class Scene(Protocol):
    """The interface of a scene module.

    - ``CaseModel``: the pydantic model of its case file (the schema; :mod:`lubedyn.config`'s base
      model, quantities with units);
    - ``FIELD_FILES``: ``((file name, output.write key), ...)``, the files a run may write besides
      ``summary.json``, ``case.resolved.toml`` and ``manifest.json`` (the dry-run plan);
    - ``build(case)``: everything the schema cannot check (geometry, positive gaps, sizes against
      the limits); raises :class:`~lubedyn.lubrication.errors.InputError`; returns what ``describe``
      reads;
    - ``describe(case, built) -> str``: one line, the plan of a run (``lubedyn run --dry-run``,
      ``lubedyn validate``);
    - ``run(case, out_dir=None, *, name, source, smoke) -> SceneResult``: solve, check the bounds,
      write the outputs into ``out_dir`` when given;
    - ``headline(summary) -> list[str]``: the lines ``lubedyn run`` prints.
    """

    CaseModel: type
    FIELD_FILES: tuple

    def build(self, case) -> Any: ...

    def describe(self, case, built) -> str: ...

    def run(self, case, out_dir=None, *, name: str, source: str = "", smoke: bool = False) -> SceneResult: ...

    def headline(self, summary: dict) -> list[str]: ...


def get(name: str) -> Scene:
    """The module of scene ``name`` (imported on first use); an unknown name is an InputError with the
    scenes there are."""
    if name not in SCENES:
        raise InputError(f"scene = {name!r} is not allowed; choose one of {', '.join(repr(s) for s in SCENES)}"
                         + did_you_mean(str(name), list(SCENES)))
    module = importlib.import_module(SCENES[name])
    if not isinstance(module, Scene):  # pragma: no cover - a scene module that lost a member
        missing = [m for m in ("CaseModel", "FIELD_FILES", "build", "describe", "run", "headline")
                   if not hasattr(module, m)]
        raise TypeError(f"{module.__name__} does not implement lubedyn.scenes.Scene: it lacks {', '.join(missing)}")
    return module
