"""build_map and its accuracy report.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

import logging
import time
from pathlib import Path

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, InputError, unknown_choice

from lubedyn.maps.filmmap import FilmMap
from lubedyn.maps.provenance import _canonical, code_fingerprint, sha256_text, versions
from lubedyn.maps.registry import ACCURACY_TOLERANCE, METHODS, _show_point, _unknown_key, get_kind, resolve_axes
from lubedyn.maps.sweep import _PointStore, solve_points

log = logging.getLogger(__name__)

# ---------------------------------------------------------------------------
# building a map


def _fill_nearest(values: np.ndarray, missing: np.ndarray) -> np.ndarray:
    out = values.copy()
    have = np.argwhere(~missing)
    for idx in np.argwhere(missing):
        nearest = have[np.argmin(np.sum((have - idx) ** 2, axis=1))]
        out[tuple(idx)] = values[tuple(nearest)]
    return out


def random_points(axes, n: int, seed: int = 0) -> np.ndarray:
    """``n`` points uniform in interpolation space (log on log axes), strictly inside the axes and
    away from the nodes (at least 10 % of a cell from any node along every axis)."""
    rng = np.random.default_rng(seed)
    cols = []
    for a in axes:
        t = np.log(a.nodes) if a.log else a.nodes
        cell = rng.integers(0, a.n - 1, size=n)
        frac = rng.uniform(0.1, 0.9, size=n)
        s = t[cell] + frac * (t[cell + 1] - t[cell])
        cols.append(np.exp(s) if a.log else s)
    return np.stack(cols, axis=1)


def build_map(kind, params: dict | None = None, axes=None, *, method: str = "hermite", workers=None, scheduler=None,
              cache_dir=None, progress: bool = True, accuracy_points: int = 0, seed: int = 0,
              on_failure: str = "raise", fit: bool = True, accuracy_tolerance: float = ACCURACY_TOLERANCE,
              warn: bool = True) -> FilmMap:
    """Solve ``kind`` on the grid of ``axes`` and return a :class:`FilmMap`.

    Parameters
    ----------
    kind : a point kind or its name (:func:`get_kind`)
    params : overrides of ``kind.default_params()`` (SI); unknown keys raise InputError
    axes : None (the kind's defaults), a dict of overrides (:func:`resolve_axes`) or a sequence of :class:`MapAxis`
    method : interpolation, "hermite", "pchip" or "linear" (:class:`FilmMap`)
    workers : local processes (default: the usable cores; 1 solves in this process)
    scheduler : Dask scheduler address (or Client / cluster): solve there instead
    cache_dir : folder for solved points (``points/<kind>/<hash>.json``) and built maps
        (``<kind>-<hash>.npz``); a build with the same inputs loads the map, a killed or failed
        build resumes from the points already solved.  None: no cache.
    progress : tqdm bar (off when not on a terminal)
    accuracy_points : number of random off-grid points solved directly for the accuracy report
    on_failure : "raise" or "fill" (see the module docstring)
    accuracy_tolerance : the largest relative error of the accuracy report without a warning
        (:data:`~lubedyn.maps.ACCURACY_TOLERANCE`, 3 %); stored in the report (``"tolerance"``), so that
        the map warns again when loaded (:meth:`FilmMap.load`).  Not an input of the map's hash: a cached
        map is judged against the tolerance of the build that loads it.
    warn : log :meth:`FilmMap.accuracy_warning` (WARNING) when the report is above the tolerance (the map
        scene passes False and reports the line itself, naming its output file)

    The map's input hash covers the kind's name, the parameters, the axis
    nodes, the method, the number and seed of accuracy points and the code
    (the kind's source file and ``lubrication/**/*.py``); each point's hash covers
    the kind, parameters, point and code, so points are shared between maps
    whose grids overlap.
    """
    t0 = time.perf_counter()
    kind = get_kind(kind)
    if on_failure not in ("raise", "fill"):
        raise unknown_choice("on_failure", on_failure, ("raise", "fill"))
    if method not in METHODS:
        raise unknown_choice("method", method, METHODS)
    defaults = dict(kind.default_params())
    params = dict(params or {})
    for key in params:
        if key not in defaults:
            raise _unknown_key(f"params.{key}", f"is not a parameter of kind {kind.name!r}", key, sorted(defaults))
    params = {**defaults, **params}
    if axes is None or isinstance(axes, dict):
        axes = resolve_axes(kind, axes)
    axes = tuple(axes)
    code = code_fingerprint(kind)
    axes_desc = [{"name": a.name, "scale": a.scale, "nodes": a.nodes} for a in axes]
    hashes = {"params": sha256_text(_canonical(params)), "axes": sha256_text(_canonical(axes_desc)),
              "code": sha256_text(_canonical(code))}
    hashes["map"] = sha256_text(_canonical({"kind": kind.name, "hashes": hashes, "method": method,
                                            "accuracy": [int(accuracy_points), int(seed)], "on_failure": on_failure}))
    cache = Path(cache_dir) if cache_dir is not None else None
    map_file = cache / f"{kind.name}-{hashes['map'][:16]}.npz" if cache is not None else None
    if not (isinstance(accuracy_tolerance, (int, float)) and accuracy_tolerance > 0):
        raise InputError(f"accuracy_tolerance = {accuracy_tolerance!r} must be a relative error > 0 "
                         f"(default {ACCURACY_TOLERANCE})")
    if map_file is not None and map_file.is_file():
        try:
            cached = FilmMap.load(map_file, check=False)
            if cached.provenance.get("input sha256", {}).get("map") == hashes["map"]:
                log.info("map %s: inputs unchanged, loaded %s", kind.name, map_file)
                cached.provenance["loaded from cache"] = str(map_file)
                if cached.accuracy:
                    cached.accuracy["tolerance"] = float(accuracy_tolerance)
                return _warned(cached, map_file, warn)
        except InputError as exc:
            log.warning("rebuilding: cached map unreadable (%s)", exc)
    store = _PointStore(cache / "points" / kind.name if cache is not None else None)
    shape = tuple(a.n for a in axes)
    grid = np.stack([g.ravel() for g in np.meshgrid(*[a.nodes for a in axes], indexing="ij")], axis=1)
    points = [{a.name: float(x) for a, x in zip(axes, row)} for row in grid]
    results, info = solve_points(kind, params, points, workers=workers, scheduler=scheduler, store=store,
                                 progress=progress, code=code, desc=f"{kind.name} map")
    failed = info["failed"]
    if failed and on_failure == "raise":
        shown = "; ".join(f"{_show_point(p)}: {msg}" for _, p, msg in failed[:3])
        more = f" (and {len(failed) - 3} more)" if len(failed) > 3 else ""
        raise ConvergenceError(f"map {kind.name}: {len(failed)} of {len(points)} points failed: {shown}{more}; "
                               f"the {info['solved'] + info['cached']} solved points are "
                               + (f"kept in {store.root} for a rebuild" if store.root else "lost (no cache_dir)")
                               + " (or build with on_failure='fill')")
    names = list(kind.outputs) if getattr(kind, "outputs", None) else sorted(next(r for r in results if r))
    missing = np.array([r is None for r in results]).reshape(shape)
    values = {}
    for name in names:
        arr = np.array([r[name] if r is not None else np.nan for r in results], dtype=float).reshape(shape)
        values[name] = _fill_nearest(arr, missing) if missing.any() else arr
    provenance = {
        "kind": kind.name,
        "kind description": getattr(kind, "description", ""),
        "params": params,
        "axes": [{"name": a.name, "scale": a.scale, "lo": a.lo, "hi": a.hi, "n": a.n} for a in axes],
        "method": method,
        "versions": versions(),
        "code": code,
        "input sha256": hashes,
        "built": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "backend": info["backend"],
        "points": len(points),
        "points solved": info["solved"],
        "points from cache": info["cached"],
        "filled points": [{"point": p, "error": msg} for _, p, msg in failed],
    }
    signed = set(getattr(kind, "signed", ()) or ())
    sheared = {name: spec for name, spec in (getattr(kind, "sheared", None) or {}).items() if name in names}
    fmap = FilmMap(axes, values, method=method, provenance=provenance,
                   log_values={name: False for name in names if name in signed}, sheared=sheared)
    if fit:
        for name in names:
            fmap.fit_power_law(name)
    if accuracy_points:
        fmap.accuracy = accuracy_report(fmap, kind, params, accuracy_points, seed=seed, workers=workers,
                                        scheduler=scheduler, store=store, progress=progress, code=code)
        fmap.accuracy["tolerance"] = float(accuracy_tolerance)
    fmap.provenance["build time [s]"] = time.perf_counter() - t0
    if map_file is not None:
        fmap.save(map_file)
    return _warned(fmap, map_file, warn)


def _warned(fmap: FilmMap, map_file, warn: bool) -> FilmMap:
    """Log the map's accuracy warning (if ``warn`` and its report is above its tolerance)."""
    text = fmap.accuracy_warning(f"map file {str(map_file)!r}" if map_file is not None else "") if warn else None
    if text:
        log.warning("%s", text)
    return fmap


def accuracy_report(fmap: FilmMap, kind, params: dict, n: int, *, seed: int = 0, workers=None, scheduler=None,
                    store=None, progress=True, code=None) -> dict:
    """Solve ``n`` random off-grid points (:func:`random_points`) directly and compare with the map.

    Returns {output: {"median", "max", "points", "worst point"}} plus "seed", "requested points" and
    "failed points" (points whose direct solve failed are left out); :func:`build_map` adds the
    "tolerance" the report is judged against (:meth:`FilmMap.accuracy_warning`)."""
    pts = random_points(fmap.axes, n, seed)
    plist = [{a.name: float(x) for a, x in zip(fmap.axes, row)} for row in pts]
    results, info = solve_points(get_kind(kind), params, plist, workers=workers, scheduler=scheduler, store=store,
                                 progress=progress, code=code, desc="accuracy points")
    ok = [i for i, r in enumerate(results) if r is not None]
    direct = {name: np.array([results[i][name] for i in ok]) for name in fmap.outputs}
    report = fmap.accuracy_against(pts[ok], direct) if ok else {}
    report["seed"] = seed
    report["requested points"] = n
    report["failed points"] = [{"point": p, "error": msg} for _, p, msg in info["failed"]]
    return report
