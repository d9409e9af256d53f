"""coupling: what joins films and dynamics -- case files, scenes, the CLI, run outputs.

=================  ==========================================================
module             responsibility
=================  ==========================================================
``units``          quantities at the input boundary: ``"50 um"`` -> 5e-05 m,
                   dimension checks ("has units of pressure, expected length")
``config``         case files: TOML -> ``[smoke]`` and ``--set`` merged ->
                   pydantic validation (unknown keys with "did you mean",
                   one-line errors naming key, value and what is allowed) ->
                   SI model; ``case.resolved.toml``
``film_scene``     film scene: case -> mesh, gap, lubricant -> ``Film`` ->
                   solve -> summary (units in names), ``.vtu``, ``.png``
``ehl_scene``      EHL scene: case -> ``EHLContact`` (radii, from a bearing,
                   or Moes M, L) -> ``solve_ehl`` -> summary with Hertz and
                   closed-form film values, ``ehl.vtu``, ``profiles.png``
``bearing``        one rolling-element/raceway contact of a bearing: radii,
                   entrainment speed, most loaded element (Stribeck,
                   quasi-static), contact angle under axial load
``film_points``    point kinds of film maps (ball-ball Reynolds film, EHL
                   race contacts: axes, outputs, evaluate) and paper B's
                   contact laws as plain-float reference functions
``maps``           FilmMap: sweeps over local processes or Dask, resume,
                   fitted power law, accuracy report, self-describing file
``map_scene``      map scene: a point kind swept over its axes -> map file,
                   PNG, ``.pvd`` series of the film fields
``dynamics_scene`` dynamics scene: the cage-less ball bearing of paper B ->
                   integrate -> collisions, Lyapunov exponents, spectrum,
                   time series, ``.pvd`` of balls, rings and films, PNGs
``outputs``        atomic writers (temporary file + rename) for run outputs
``cli``            ``lubedyn run | validate | cases | info``; exit codes
                   0 ok, 2 input error, 1 failed solve
=================  ==========================================================

Planned: the dynamics scene of paper A (tapered roller bearing).  ``coupling``
imports ``lubrication`` and ``dynamics``; never the other way round.
"""
from __future__ import annotations

try:
    from importlib.metadata import PackageNotFoundError, version

    __version__ = version("lubedyn")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"
