"""Running a case: a validated case handed to its scene (:data:`lubedyn.scenes.SCENES`), as ``lubedyn run``,
the study runner (:mod:`lubedyn.scenes.study`) and :func:`lubedyn.run` do it.

>>> from lubedyn.config import load_case_file
>>> path, raw, case = load_case_file("inclined_slider", smoke=True)   # a bundled case, by name
>>> round(run(case).summary["Load per unit width [N/m]"])              # nothing written: no out_dir
63549
"""
from __future__ import annotations

from pathlib import Path

from lubedyn import scenes
from lubedyn.config import check_smoke
from lubedyn.lubrication.errors import InputError


def run(case, out_dir=None, *, name: str | None = None, source: str = "", smoke: bool = False):
    """Run a validated case (:func:`lubedyn.config.load_case`) with its scene's ``run`` and return the
    scene's result; with ``out_dir`` the outputs are written there.  ``name`` (default: the scene) and
    ``source`` (the case file) label the summary, ``smoke`` marks it as a smoke run."""
    return scenes.get(case.scene).run(case, out_dir, name=name or case.scene, source=source, smoke=smoke)


def run_loaded(path: Path, raw: dict, case, out, *, smoke: bool = False, overrides=()):
    """Run a case loaded by :func:`lubedyn.config.load_case_file` into the folder ``out`` (the call of
    ``lubedyn run``); returns the scene's result.  An InputError that only the ``[smoke]`` variant's
    build has is worded to say so."""
    scene = scenes.get(case.scene)
    try:
        return scene.run(case, out, name=path.stem, source=str(path), smoke=smoke)
    except InputError as exc:
        if not smoke:
            raise
        try:  # an error of the smoke variant's build: say that it lives in [smoke]
            scene.build(case)
        except InputError:
            raise check_smoke(raw, list(overrides or ()), exc) from None
        raise
