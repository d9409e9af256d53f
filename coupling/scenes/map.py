"""Map scene: a point kind's film solves swept over its axes -> :class:`~lubedyn.maps.FilmMap` -> outputs.

Case layout (``scene = "map"``; quantities as numbers in SI or strings with
units, checked against the unit in the axis name)::

    scene = "map"
    description = "one line shown by `lubedyn cases`"
    kind = "ball_ball"          # a kind of lubedyn.film_points.KINDS
    [axes.<key>]                # key: the axis name without unit, lower case, "_" for spaces
                                # ("Central gap [m]" -> central_gap); overrides the kind's default
    lo = "0.05 um"; hi = "50 um"; n = 19; scale = "log" | "linear"
                                # or nodes = [...] (explicit, increasing; e.g. refined near a kink)
    [params]                    # overrides of the kind's default_params() (numbers in SI; a string
                                # "<number> <unit>" is converted to SI; other strings as they are)
    resolution = "default"
    [build]
    method = "hermite" | "pchip" | "linear"   # interpolation (lubedyn.dynamics.interp)
    workers = 0                 # local processes; 0: every usable core; capped at the points of a pass
    scheduler = ""              # Dask scheduler address ("tcp://host:8786"): solve there instead
    cache_dir = ""              # solved points and built maps; "" -> <out>/.map-cache
    accuracy_points = 20        # random off-grid points solved directly for the accuracy report
    accuracy_tolerance = 0.03   # largest relative error of that report without a WARNING (at build and load)
    seed = 0
    on_failure = "raise" | "fill"
    [output]
    write = ["map", "png", "pvd"]
    map_file = ""               # "" -> <kind>.npz
    field_frames = 6            # .pvd frames: nodes of the first axis (evenly picked) ...
    field_at = {}               # ... with the other axes at their middle node unless given here
    [limits]                    # memory = "40 GiB", map_points = 1000000 (lubedyn.limits)
    [smoke]                     # partial case merged by --smoke

Outputs of ``run``: ``<kind>.npz`` (:meth:`FilmMap.save`), ``map.png`` (each
output against the first axis, lines over the second), ``fields.pvd`` with
``field_NNN.vtu`` (the kind's film fields, a series along the first axis;
open ``fields.pvd`` in ParaView; the "time" of each frame is the first axis'
value), ``summary.json`` (accuracy report, fit errors, build information; under "Warnings" the map's
accuracy warning when an output's error exceeds ``build.accuracy_tolerance``, also logged),
``case.resolved.toml``.  Everything is written through a staging folder
(:func:`lubedyn.outputs.staged`): a failed build leaves the output folder
as it was (solved points stay in the cache, so the next run resumes).
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal
from xml.sax.saxutils import quoteattr

import numpy as np
from pydantic import Field, model_validator
from pydantic_core import PydanticCustomError

from lubedyn.lubrication.errors import InputError, did_you_mean
from lubedyn.lubrication.laws.lubricant import DowsonHigginson

from lubedyn import maps, outputs, validity
from lubedyn.config import BoundsModel, LimitsModel, LubricantModel, CaseTable, resolved_toml
from lubedyn.units import DIMENSIONS, UnitError, parse_quantity, parse_units
from lubedyn import limits
from lubedyn.lubrication.vtu import write_vtu

log = logging.getLogger(__name__)

FIELD_FILES = (("<kind>.npz", "map"), ("map.png", "png"), ("fields.pvd", "pvd"))


def _rule(key, value, text):
    return PydanticCustomError("case_rule", "{text}", {"key": key, "value": value, "text": text, "root": True})


def _dimension(unit: str) -> str:
    """Name of the dimension of a unit expression (``"m/s"`` -> ``"velocity"``; ``"-"`` -> dimensionless)."""
    if unit in ("", "-"):
        return "dimensionless"
    _, dim = parse_units(unit)
    for name, vector in DIMENSIONS.items():
        if vector == dim:
            return name
    raise InputError(f"axis unit {unit!r} has no named dimension")


class AxisModel(CaseTable):
    """Override of one axis of the kind (any subset of the keys)."""

    lo: Any = None
    hi: Any = None
    n: Annotated[int, Field(strict=True, ge=2)] | None = None
    scale: Literal["log", "linear"] | None = None
    nodes: list[Any] | None = None  # explicit nodes (replace lo, hi, n), e.g. refined near a kink


class BuildModel(CaseTable):
    method: Literal["hermite", "pchip", "linear"] = "hermite"
    workers: Annotated[int, Field(strict=True, ge=0)] = 0
    scheduler: str = ""
    cache_dir: str = ""
    accuracy_points: Annotated[int, Field(strict=True, ge=0)] = 20
    # stored in the map, which warns again when it is loaded (lubedyn.maps.ACCURACY_TOLERANCE: why 3 %)
    accuracy_tolerance: Annotated[float, Field(gt=0)] = maps.ACCURACY_TOLERANCE  # largest error without a warning
    seed: Annotated[int, Field(strict=True, ge=0)] = 0
    on_failure: Literal["raise", "fill"] = "raise"


class MapOutputModel(CaseTable):
    write: list[Literal["map", "png", "pvd"]] = ["map", "png", "pvd"]
    map_file: str = ""
    field_frames: Annotated[int, Field(strict=True, ge=1)] = 6
    field_at: dict[str, Any] = {}


class CaseModel(CaseTable):
    """A map scene; after validation every axis bound and numeric parameter is SI and ``params`` holds
    every parameter of the kind (its defaults with the case's overrides)."""

    scene: Literal["map"]
    description: str = ""
    kind: str
    axes: dict[str, AxisModel] = {}
    params: dict[str, Any] = {}
    lubricant: LubricantModel | None = None  # the typed [lubricant] table of every scene, for kinds with an oil
    build: BuildModel = Field(default_factory=BuildModel)
    output: MapOutputModel = Field(default_factory=MapOutputModel)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    validity: BoundsModel = Field(default_factory=BoundsModel)  # strict: lubedyn.bounds
    smoke: dict[str, Any] | None = None

    @model_validator(mode="after")
    def _resolve(self):
        known = maps.kinds()
        if self.kind not in known:
            hint = did_you_mean(self.kind, known)
            raise _rule("kind", self.kind, f"is not a map kind; choose one of {', '.join(map(repr, known))}{hint}")
        kind = known[self.kind]
        by_key = {maps.axis_key(a.name): a for a in kind.axes}
        for key, over in self.axes.items():
            if key not in by_key:
                hint = did_you_mean(key, by_key)
                raise _rule(f"axes.{key}", None, f"is not an axis of kind {self.kind!r}{hint} "
                            f"(axes: {', '.join(by_key)})")
            dim = _dimension(maps.axis_unit(by_key[key].name))
            for bound in ("lo", "hi"):
                value = getattr(over, bound)
                if value is None:
                    continue
                try:
                    setattr(over, bound, parse_quantity(value, dim))
                except UnitError as exc:
                    raise _rule(f"axes.{key}.{bound}", value, str(exc)) from None
            if over.n is not None and over.n > self.limits.map_points:  # before any array of n nodes exists
                raise _rule(f"axes.{key}.n", over.n, f"is more than limits.map_points = {self.limits.map_points} "
                            "points on one axis; use fewer nodes (or raise limits.map_points)")
            if over.nodes is not None:
                if any(getattr(over, k) is not None for k in ("lo", "hi", "n")):
                    raise _rule(f"axes.{key}.nodes", over.nodes, "cannot be combined with lo, hi, n; give one or the other")
                try:
                    over.nodes = [parse_quantity(v, dim) for v in over.nodes]
                except UnitError as exc:
                    raise _rule(f"axes.{key}.nodes", over.nodes, str(exc)) from None
            try:
                maps.resolve_axes(kind, {key: over.model_dump(exclude_none=True)})
            except InputError as exc:
                raise _rule(f"axes.{key}", over.model_dump(exclude_none=True), f"is not a valid axis: {exc}") from None
        first = maps.axis_key(kind.axes[0].name)
        for key, value in list(self.output.field_at.items()):
            if key not in by_key or key == first:
                others = [k for k in by_key if k != first]
                raise _rule(f"output.field_at.{key}", value, f"must be one of the axes after the first "
                            f"({', '.join(others) or 'none'})")
            try:
                self.output.field_at[key] = parse_quantity(value, _dimension(maps.axis_unit(by_key[key].name)))
            except UnitError as exc:
                raise _rule(f"output.field_at.{key}", value, str(exc)) from None
        defaults = kind.default_params()
        if self.lubricant is not None:
            self.params = {**self.params, **_lubricant_params(self.lubricant, self.kind, defaults, self.params)}
            self.lubricant = None  # resolved into params: case.resolved.toml lists them there
        for key, value in list(self.params.items()):
            if key not in defaults:
                hint = did_you_mean(key, defaults)
                raise _rule(f"params.{key}", value, f"is not a parameter of kind {self.kind!r}{hint} "
                            f"(parameters: {', '.join(defaults)})")
            self.params[key] = _param_value(key, value, defaults[key])
        # every default filled in (case.resolved.toml lists the parameters the map was built with)
        self.params = {**{k: v for k, v in defaults.items() if v is not None}, **self.params}
        return self


#: the parameters of a map kind that the [lubricant] table sets
LUBRICANT_PARAMS = ("viscosity_law", "eta0", "alpha", "density_law", "rho0", "eyring_stress", "rheology", "hb_consistency",
                    "hb_yield_stress", "hb_exponent", "hb_creep")


def _lubricant_params(lub, kind_name, defaults, params) -> dict:
    """The kind parameters of a typed ``[lubricant]`` table (same schema and unit checks as the film and
    EHL scenes).  A kind takes Barus, Roelands (given by alpha) or constant viscosity, and
    Dowson-Higginson (with the published a, b) or incompressible density."""
    if "eta0" not in defaults:
        raise _rule("lubricant", None, f"kind {kind_name!r} takes no lubricant")
    both = [k for k in LUBRICANT_PARAMS if k in params]
    if both:
        raise _rule(f"params.{both[0]}", params[both[0]], "is set by the [lubricant] table as well; give the "
                    "lubricant in one place ([lubricant], the typed table of every scene)")
    visc, dens = lub.viscosity, lub.density
    if visc.z is not None:
        raise _rule("lubricant.viscosity.z", visc.z, "map kinds take Roelands' law by alpha; give alpha instead of z")
    if dens.law == "dowson_higginson" and (dens.a, dens.b) != (DowsonHigginson.a, DowsonHigginson.b):
        raise _rule("lubricant.density.a", dens.a, "map kinds use Dowson and Higginson's published a, b")
    out = {"viscosity_law": visc.law, "eta0": visc.eta0, "density_law": dens.law, "rho0": dens.rho0}
    if visc.alpha is not None:
        out["alpha"] = visc.alpha
    if lub.eyring_stress is not None:
        if "eyring_stress" not in defaults:
            raise _rule("lubricant.eyring_stress", lub.eyring_stress, f"is not used by kind {kind_name!r}")
        out["eyring_stress"] = lub.eyring_stress
    if lub.herschel_bulkley is not None:
        if "rheology" not in defaults:
            raise _rule("lubricant.herschel_bulkley", lub.herschel_bulkley.model_dump(),
                        f"is not used by kind {kind_name!r} (only the roller kinds take a grease; the others are "
                        "Newtonian or Eyring)")
        # a grease on a roller kind (lubedyn.film_points.base._lubricant): the viscosity law is the consistency
        # phi(p) = phi0 exp(alpha p), as in the EHL scenes' [lubricant.herschel_bulkley]
        hb = lub.herschel_bulkley
        out.update({"rheology": "herschel_bulkley", "hb_consistency": visc.eta0, "hb_yield_stress": hb.yield_stress,
                    "hb_exponent": hb.exponent, "hb_creep": hb.creep})
    return out


def _param_value(key, value, default):
    """A numeric parameter: number, or "<number> <unit>" converted to SI; a string parameter: a string."""
    if isinstance(default, bool) or not isinstance(default, (int, float)):
        if not isinstance(value, type(default)) and default is not None:
            raise _rule(f"params.{key}", value, f"must be a {type(default).__name__} like the default {default!r}")
        return value
    if isinstance(value, bool):
        raise _rule(f"params.{key}", value, "must be a number (SI) or a string with units")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            number, *unit = value.split(maxsplit=1)
            factor = parse_units(unit[0])[0] if unit else 1.0
            return float(f"{float(number) * factor:.15g}")
        except (ValueError, UnitError) as exc:
            raise _rule(f"params.{key}", value, f"is not '<number> <units>' ({exc})") from None
    raise _rule(f"params.{key}", value, "must be a number (SI) or a string with units")


@dataclass(frozen=True)
class MapSetup:
    """What a case builds: the kind, its full parameters and the axes."""

    kind: Any
    params: dict
    axes: tuple

    @property
    def points(self) -> int:
        return int(np.prod([a.n for a in self.axes]))


# Measured CPU seconds per point at each kind's default resolution (the shipped maps' provenance:
# build time x workers / points): ball_ball (fine) 844 s x 2 / 480, EHL ball inner race 960 s / 168,
# outer race 353 s / 168, roller race 39 s x 2 / 693, roller cone / cup per length (34 x 13 x 37, the SRR
# nodes cost no EHL solve) ~440 s x 2 / 16354, rib with lithium grease (65 x 57 nodes, Herschel-Bulkley
# homotopy) ~140 s a point.  Other kinds: 1 s.
SECONDS_PER_POINT = {"ball_ball": 3.5, "ehl_ball_inner_race": 5.7, "ehl_ball_outer_race": 2.1,
                     "ehl_roller_cone": 0.06, "ehl_roller_cup": 0.06, "ehl_rib": 140.0}
# Memory per map point while a map is built: the point's dict and its hash, the result's dict of
# outputs (about 1 kB in CPython), the value arrays; about four times that:
BYTES_PER_POINT = 4096
WARN_HOURS = 1.0  # a build estimated to take longer is announced with a warning


def check_size(case: CaseModel, axes) -> None:
    """Refuse a map with more points than ``limits.map_points`` or more memory than the limit; warn
    when the estimated build time exceeds WARN_HOURS (:mod:`lubedyn.limits`)."""
    points = int(np.prod([a.n for a in axes], dtype=float))
    largest = max(axes, key=lambda a: a.n)
    shape = " x ".join(str(a.n) for a in axes)
    subject = f"axes.{largest.key}.n = {largest.n}: {shape} = {points:.3g} map points"
    if points > case.limits.map_points:
        raise InputError(f"{subject}, more than limits.map_points = {case.limits.map_points}; use fewer nodes "
                         "(or raise limits.map_points)")
    limits.check_memory(case, subject, points * BYTES_PER_POINT, "use fewer nodes")
    workers = effective_workers(case, points, quiet=True) if not case.build.scheduler else 1
    hours = points * SECONDS_PER_POINT.get(case.kind, 1.0) / workers / 3600.0
    if hours > WARN_HOURS:
        log.warning("%s: the build will take about %.3g h on %d process(es) (%.3g s of one core per point, "
                    "measured at the default resolution)", subject, hours, workers,
                    SECONDS_PER_POINT.get(case.kind, 1.0))


def effective_workers(case: CaseModel, points: int, quiet: bool = False) -> int:
    """Local processes of a build: ``build.workers`` (0: the usable cores), capped at the most points
    one pass solves (the grid or the accuracy points); a warning when above the usable cores."""
    cores = maps.default_workers()
    asked = case.build.workers or cores
    most = max(points, case.build.accuracy_points, 1)
    workers = min(asked, most)
    if not quiet:
        if workers < asked:
            log.info("build.workers = %d capped at %d: no pass solves more points", asked, workers)
        if workers > cores:
            log.warning("build.workers = %d is more than the %d usable core(s): the extra processes only share "
                        "them and each holds its own memory", workers, cores)
    return workers


def build(case: CaseModel) -> MapSetup:
    """Kind, parameters and axes of a validated case (no solve)."""
    kind = maps.get_kind(case.kind)
    params = {**kind.default_params(), **case.params}
    axes = maps.resolve_axes(kind, {k: v.model_dump(exclude_none=True) for k, v in case.axes.items()})
    check_size(case, axes)
    by_key = {a.key: a for a in axes}
    for key in case.output.field_at:
        if key not in by_key or key == axes[0].key:
            raise InputError(f"output.field_at.{key}: not one of the axes after the first "
                             f"({', '.join(a.key for a in axes[1:]) or 'none'})")
    return MapSetup(kind, params, axes)


def describe(case: CaseModel, setup: MapSetup) -> str:
    axes = " x ".join(f"{a.name} {a.lo:.4g}..{a.hi:.4g} ({a.n}, {a.scale})" for a in setup.axes)
    where = f"Dask scheduler {case.build.scheduler}" if case.build.scheduler else \
        f"{effective_workers(case, setup.points, quiet=True)} local process(es)"
    return (f"map scene: kind {setup.kind.name}, {axes} = {setup.points} points + {case.build.accuracy_points} "
            f"accuracy points on {where}, {case.build.method} interpolation")


def map_file_name(case: CaseModel) -> str:
    return case.output.map_file or f"{case.kind}.npz"


# ---------------------------------------------------------------------------
# outputs


def field_points(case: CaseModel, setup: MapSetup) -> list[dict]:
    """The points of the .pvd series: ``field_frames`` nodes of the first axis, the others at their
    middle node or at ``output.field_at``."""
    first = setup.axes[0]
    picks = sorted(set(np.linspace(0, first.n - 1, min(case.output.field_frames, first.n)).round().astype(int)))
    rest = {}
    for a in setup.axes[1:]:
        rest[a.name] = float(case.output.field_at.get(a.key, a.nodes[a.n // 2]))
    return [{first.name: float(first.nodes[i]), **rest} for i in picks]


def write_pvd(path, frames) -> Path:
    """A ParaView collection: ``frames`` = [(time, file name relative to the .pvd)]."""
    lines = ['<?xml version="1.0"?>', '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    lines += [f'    <DataSet timestep="{t:.17g}" group="" part="0" file={quoteattr(name)}/>' for t, name in frames]
    lines += ["  </Collection>", "</VTKFile>"]
    return outputs.write_text(path, "\n".join(lines) + "\n")


def _build_stop_reason(provenance: dict) -> str:
    """Why the build ended: every point solved (or loaded), or how many failed and were filled, with
    each distinct error (their messages carry the solver's own stop reason)."""
    if "loaded from cache" in provenance:
        return "loaded from cache"
    filled = provenance.get("filled points", [])
    if not filled:
        return "every point solved"
    errors = {}
    for f in filled:
        errors[f["error"]] = errors.get(f["error"], 0) + 1
    shown = "; ".join(f"{n} x {msg}" for msg, n in sorted(errors.items(), key=lambda kv: -kv[1])[:3])
    return (f"{len(filled)} of {provenance.get('points', '?')} points failed and were filled from their nearest "
            f"solved neighbour: {shown}")


def summarise(case: CaseModel, setup: MapSetup, fmap: maps.FilmMap) -> dict:
    """Flat summary: the map's identity, build information, accuracy and fit errors per output."""
    p = fmap.provenance
    out = {
        "Kind": setup.kind.name,
        "Map file": map_file_name(case),
        "Axes": "; ".join(f"{a.name} {a.lo:.6g}..{a.hi:.6g} ({a.n} nodes, {a.scale})" for a in fmap.axes),
        "Outputs": "; ".join(fmap.outputs),
        "Interpolation": fmap.method,
        "Grid points [-]": p.get("points", int(np.prod(fmap.shape))),
        "Points solved [-]": p.get("points solved", 0),
        "Points from cache [-]": p.get("points from cache", 0),
        "Filled (failed) points [-]": len(p.get("filled points", [])),
        "Map build stop reason": _build_stop_reason(p),
        "Backend": p.get("backend", ""),
        "Map build time [s]": p.get("build time [s]", 0.0),
        "Map loaded from cache": "loaded from cache" in p,
        "Accuracy points [-]": fmap.accuracy.get("requested points", 0),
        "Failed accuracy points [-]": len(fmap.accuracy.get("failed points", [])),
        "Accuracy tolerance [-]": fmap.accuracy_tolerance,
        "Map input sha256": p.get("input sha256", {}).get("map", ""),
    }
    for name in fmap.outputs:
        # the quantity comes last: keys never start with an output name (the CLI prints numeric keys
        # that start with e.g. "Maximum pressure")
        rep = fmap.accuracy.get(name)
        if rep:
            out[f"Interpolation median relative error [-] of {name}"] = rep["median"]
            out[f"Interpolation max relative error [-] of {name}"] = rep["max"]
            out[f"Accuracy points above 3 % [-] of {name}"] = rep.get("above 3 %", 0)
            out[f"Worst accuracy point of {name}"] = ", ".join(
                f"{a.name} = {x:.4g}" for a, x in zip(fmap.axes, rep["worst point"]))
        fit = fmap.fits.get(name)
        if fit is not None:
            out[f"Fitted closed form of {name}"] = fit.formula()
            out[f"Fit median relative error [-] of {name}"] = fit.median_error
            out[f"Fit max relative error [-] of {name}"] = fit.max_error
        out[f"Smallest value of {name}"] = float(np.min(fmap.values[name]))
        out[f"Largest value of {name}"] = float(np.max(fmap.values[name]))
    derived = getattr(setup.kind, "derived", None)
    if derived is not None:  # closed forms of the axes (e.g. the speeds of a polar ball_ball map), at the nodes
        rows = [derived(setup.params, {a.name: float(x) for a, x in zip(fmap.axes, row)}) for row in fmap.grid_points()]
        for name in rows[0] if rows else ():
            if name not in fmap.values:
                vals = np.array([r[name] for r in rows], dtype=float)
                out[f"Smallest value of {name}"] = float(vals.min())
                out[f"Largest value of {name}"] = float(vals.max())
    return out


@dataclass
class MapRun:
    """What :func:`run` produced."""

    case: CaseModel
    setup: MapSetup
    map: maps.FilmMap | None = None
    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)


def run(case: CaseModel, out_dir=None, *, name: str = "map", source: str = "", smoke: bool = False) -> MapRun:
    """Build the map of a case and (if ``out_dir``) write its outputs.

    Raises :class:`~lubedyn.lubrication.errors.InputError` for a case that cannot be
    built, :class:`~lubedyn.lubrication.errors.ConvergenceError` when points fail (with
    ``on_failure = "raise"``); then nothing is written but the point cache.
    """
    t0 = time.perf_counter()
    setup = build(case)
    t_build = time.perf_counter() - t0
    log.info("%s", describe(case, setup))
    b = case.build
    cache = Path(b.cache_dir) if b.cache_dir else (Path(out_dir) / ".map-cache" if out_dir is not None else None)
    workers = None if b.scheduler else effective_workers(case, setup.points)
    fmap = maps.build_map(setup.kind, case.params, setup.axes, method=b.method, workers=workers,
                          scheduler=b.scheduler or None, cache_dir=cache, progress=True,
                          accuracy_points=b.accuracy_points, seed=b.seed, on_failure=b.on_failure,
                          accuracy_tolerance=b.accuracy_tolerance, warn=False)
    scene_summary = summarise(case, setup, fmap)
    where = (f"map file {str(Path(out_dir) / map_file_name(case))!r}" if out_dir is not None
             and "map" in case.output.write else "")
    validity.report(scene_summary, [text for text in (fmap.accuracy_warning(where),) if text])
    summary = outputs.run_summary(case, name, smoke, scene_summary, t0, t_build)
    result = MapRun(case=case, setup=setup, map=fmap, summary=summary)
    if out_dir is None:
        return result
    header = outputs.resolved_header(name, source, smoke)
    out = Path(out_dir)
    write = case.output.write
    with outputs.staged(out) as stage:
        outputs.write_text(stage / "case.resolved.toml", resolved_toml(case, header))
        if "map" in write:
            fmap.save(stage / map_file_name(case))
        if "png" in write:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt

            fig = fmap.plot()
            try:
                outputs.save_figure(stage / "map.png", fig)
            finally:
                plt.close(fig)
        if "pvd" in write:
            _write_fields(case, setup, stage, summary)
        outputs.write_json(stage / "summary.json", summary)
        names = sorted(p.name for p in stage.iterdir())
    result.files = [out / n for n in names]
    return result


def _write_fields(case, setup, stage, summary):
    field = getattr(setup.kind, "field", None)
    if field is None:
        log.warning("kind %s has no film field: no fields.pvd", setup.kind.name)
        summary["Field frames [-]"] = 0
        return

    frames = []
    for k, point in enumerate(field_points(case, setup)):
        grid = field(setup.params, point)
        if type(grid).__name__ != "UnstructuredGrid":  # .vtu holds unstructured grids only
            grid = grid.cast_to_unstructured_grid()
        for axis, value in point.items():
            grid.field_data[axis] = np.array([value])
        fname = f"field_{k:03d}.vtu"
        write_vtu(grid, stage / fname)
        frames.append((point[setup.axes[0].name], fname))
    write_pvd(stage / "fields.pvd", frames)
    summary["Field frames [-]"] = len(frames)
    summary["Field series axis"] = setup.axes[0].name


def headline(summary: dict) -> list[str]:
    """The lines ``lubedyn run`` prints (:func:`lubedyn.outputs.headline_lines`: loads, pressures, films,
    then the solve's iterations and time)."""
    return outputs.headline_lines(summary)
