"""Film maps: many film solves tabulated on axes, fitted, stored, handed to dynamics.

A map tabulates the outputs of a *point kind* (:mod:`coupling.film_points`:
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
    arrays for :mod:`dynamics.interp`).

Interpolation (:mod:`dynamics.interp`): cubic Hermite on PCHIP node slopes
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
(:mod:`coupling.film_points`).  :meth:`FilmMap.dynamics_film_map` hands a polar ball-ball map to the
bearing kernel (polar arrays when :mod:`dynamics.contacts` reads them, else resampled on the Cartesian
nodes it reads, :func:`cartesian_resample`).

Failed points: a point whose solve raises is recorded (its message kept) and
not cached, so a later build retries it.  With ``on_failure = "raise"`` (the
default) the build, after solving and persisting every other point, raises
:class:`~lubrication.errors.ConvergenceError` naming the failed points; with
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
"""
from __future__ import annotations

import concurrent.futures as cf
import contextlib
import dataclasses
import hashlib
import inspect
import io
import json
import logging
import math
import os
import platform
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from dynamics import interp
from lubrication.errors import ConvergenceError, InputError, did_you_mean, unknown_choice

from . import outputs

log = logging.getLogger(__name__)

FORMAT = "lubedyn film map"
FORMAT_VERSION = 1
METHODS = ("hermite", "pchip", "linear")
ZERO_FLOOR = 1e-3  # relative-error floor, as a fraction of an output's largest |value|

# ---------------------------------------------------------------------------
# kinds


_REGISTRY: dict[str, Any] = {}


def register_kind(kind) -> None:
    """Make a point kind known to :func:`get_kind` (tests, user kinds)."""
    _REGISTRY[kind.name] = kind


def kinds() -> dict:
    """Every known point kind: :data:`coupling.film_points.KINDS` plus the registered ones."""
    out = {}
    try:
        from .film_points import KINDS

        out.update(KINDS)
    except ImportError:  # pragma: no cover - the physics module is optional for the machinery
        pass
    out.update(_REGISTRY)
    return out


def get_kind(kind):
    """A point kind by name (or the kind itself)."""
    if not isinstance(kind, str):
        return kind
    known = kinds()
    if kind not in known:
        raise unknown_choice("kind", kind, sorted(known))
    return known[kind]


# ---------------------------------------------------------------------------
# axes


@dataclass(frozen=True)
class MapAxis:
    """One axis: ``name`` with unit (``"Central gap [m]"``), increasing ``nodes`` (SI), ``scale``."""

    name: str
    nodes: np.ndarray
    scale: str = "linear"

    def __post_init__(self):
        if self.scale not in ("log", "linear"):
            raise unknown_choice(f"axis {self.name!r} scale", self.scale, ("log", "linear"))
        nodes = np.asarray(self.nodes, dtype=float)
        if nodes.ndim != 1 or nodes.size < 2 or not np.all(np.diff(nodes) > 0) or not np.all(np.isfinite(nodes)):
            raise InputError(f"axis {self.name!r}: nodes must be >= 2 finite, strictly increasing values")
        if self.scale == "log" and not nodes[0] > 0:
            raise InputError(f"axis {self.name!r}: a log axis needs nodes > 0 (lowest {nodes[0]:g})")
        object.__setattr__(self, "nodes", nodes)

    @property
    def log(self) -> bool:
        return self.scale == "log"

    @property
    def lo(self) -> float:
        return float(self.nodes[0])

    @property
    def hi(self) -> float:
        return float(self.nodes[-1])

    @property
    def n(self) -> int:
        return int(self.nodes.size)

    @property
    def key(self) -> str:
        """Short name for case files: ``"Central gap [m]"`` -> ``"central_gap"``."""
        return axis_key(self.name)

    @classmethod
    def uniform(cls, name: str, lo: float, hi: float, n: int, scale: str) -> "MapAxis":
        """``n`` nodes from ``lo`` to ``hi``, evenly spaced in x (linear) or log x (log)."""
        if scale == "log" and not (lo > 0 and hi > lo):
            raise InputError(f"axis {name!r}: a log axis needs 0 < lo < hi (got {lo:g}, {hi:g})")
        if not hi > lo or int(n) < 2:
            raise InputError(f"axis {name!r}: needs lo < hi and n >= 2 (got {lo:g}, {hi:g}, {n})")
        nodes = np.geomspace(lo, hi, int(n)) if scale == "log" else np.linspace(lo, hi, int(n))
        return cls(name, nodes, scale)


def axis_key(name: str) -> str:
    """``"Central gap [m]"`` -> ``"central_gap"``; ``"Slide-to-roll ratio [-]"`` -> ``"slide_to_roll_ratio"``."""
    base = name.split("[")[0].strip().lower()
    return "_".join("".join(c if c.isalnum() else " " for c in base).split())


def axis_unit(name: str) -> str:
    """``"Approach speed [m/s]"`` -> ``"m/s"`` ("" without brackets)."""
    return name[name.index("[") + 1:name.rindex("]")].strip() if "[" in name and "]" in name else ""


def resolve_axes(kind, overrides: dict | None = None) -> tuple[MapAxis, ...]:
    """The kind's default axes with ``overrides`` applied.

    ``overrides`` maps an axis key (:func:`axis_key`) or full name to a dict of
    any of ``lo``, ``hi``, ``n``, ``scale`` (SI) or ``nodes`` (explicit list).
    """
    kind = get_kind(kind)
    overrides = dict(overrides or {})
    by_key = {axis_key(a.name): a for a in kind.axes}
    names = {a.name: axis_key(a.name) for a in kind.axes}
    resolved = {}
    for key, over in overrides.items():
        k = names.get(key, key)
        if k not in by_key:
            raise _unknown_key(f"axes.{key}", f"is not an axis of kind {kind.name!r}", key, list(by_key))
        resolved[k] = dict(over)
    out = []
    for a in kind.axes:
        over = resolved.get(axis_key(a.name), {})
        unknown = set(over) - {"lo", "hi", "n", "scale", "nodes"}
        if unknown:
            raise unknown_choice(f"axes.{axis_key(a.name)} key", sorted(unknown)[0], ("lo", "hi", "n", "scale", "nodes"))
        scale = over.get("scale", a.scale)
        if over.get("nodes") is not None:
            out.append(MapAxis(a.name, np.asarray(over["nodes"], dtype=float), scale))
        elif getattr(a, "explicit", ()) and not over:
            out.append(MapAxis(a.name, np.asarray(a.explicit, dtype=float), scale))
        else:
            out.append(MapAxis.uniform(a.name, float(over.get("lo", a.lo)), float(over.get("hi", a.hi)),
                                       int(over.get("n", a.n)), scale))
    return tuple(out)


# ---------------------------------------------------------------------------
# power-law fit


@dataclass(frozen=True)
class PowerLawFit:
    """Closed form fitted to an output: a power law along every axis of one sign,
    a log-quadratic along an axis through zero::

        log|F| = c + sum_{i in P} a_i log|x_i| + sum_{j in Q} (b_j x_j + d_j x_j^2)
                   [+ sum_{i<k in P} e_ik log|x_i| log|x_k|],       sign(F) fixed

    P: axes whose nodes all have one sign (``terms[i] == "power"``); Q: axes
    through zero (``"quadratic"``: squeeze number, slide-to-roll ratio), where a
    power law is undefined.  Fitted by least squares on the grid nodes where
    the output has its dominant sign and is significant (at least ``ZERO_FLOOR``
    x the largest |value| at the same first-axis node; ``domain``);
    ``max_error``/``median_error`` are the relative errors there.
    ``exponents[i]`` = a_i (NaN on Q axes), ``quadratic[j]`` = (b_j, d_j) ((0, 0)
    on P axes), ``cross`` the e_ik in the order of the pairs of P axes.
    """

    output: str
    constant: float
    exponents: tuple
    cross: tuple
    sign: float
    max_error: float
    median_error: float
    points: int
    domain: str
    terms: tuple = ()
    quadratic: tuple = ()

    def __call__(self, *coords):
        x = [np.asarray(c, dtype=float) for c in coords]
        terms = self.terms or ("power",) * len(x)
        z = self.constant
        logs = {}
        for i, (xi, kind) in enumerate(zip(x, terms)):
            if kind == "power":
                logs[i] = np.log(np.abs(xi))
                z = z + self.exponents[i] * logs[i]
            else:
                b, d = self.quadratic[i]
                z = z + b * xi + d * xi * xi
        if self.cross:
            pairs = [(i, k) for i in logs for k in logs if i < k]
            z = z + sum(e * logs[i] * logs[k] for e, (i, k) in zip(self.cross, pairs))
        return self.sign * np.exp(z)

    def formula(self) -> str:
        terms = self.terms or ("power",) * len(self.exponents)
        parts = []
        for i, kind in enumerate(terms):
            if kind == "power":
                parts.append(f"|x{i}|^{self.exponents[i]:.4g}")
            else:
                b, d = self.quadratic[i]
                parts.append(f"exp({b:.4g} x{i} + {d:.4g} x{i}^2)")
        s = f"{self.sign * math.exp(self.constant):.6g} " + " ".join(parts)
        return s + (" (with cross terms)" if self.cross else "")


def relative_error(approx, exact, floor):
    """|approx - exact| / max(|exact|, floor) (floor: scalar or per point)."""
    approx, exact = np.asarray(approx, float), np.asarray(exact, float)
    return np.abs(approx - exact) / np.maximum(np.abs(exact), floor)


def fit_power_law(axes, values, output: str = "", cross="auto") -> PowerLawFit | None:
    """Least-squares closed form of ``values`` on the grid of ``axes`` (see :class:`PowerLawFit`).

    ``cross``: False (no cross terms), True, or "auto" (cross terms between power-law axes kept when
    they at least halve the maximum error).  None when fewer points than terms + 2.
    """
    grids = np.meshgrid(*[a.nodes for a in axes], indexing="ij")
    x = np.stack([g.ravel() for g in grids], axis=1)
    v = np.asarray(values, float).ravel()
    sign = 1.0 if np.sum(v > 0) >= np.sum(v < 0) else -1.0
    terms = tuple("power" if (a.nodes > 0).all() or (a.nodes < 0).all() else "quadratic" for a in axes)
    ok = (v * sign > 0) & np.isfinite(v) & _significant(values)
    total = v.size
    nd = x.shape[1]
    xs = x[ok]
    lv = np.log(sign * v[ok])
    power = [i for i in range(nd) if terms[i] == "power"]
    pairs = [(i, k) for i in power for k in power if i < k]

    def solve(with_cross):
        cols = [np.ones(xs.shape[0])]
        for i in range(nd):
            if terms[i] == "power":
                cols.append(np.log(np.abs(xs[:, i])))
            else:
                cols += [xs[:, i], xs[:, i] ** 2]
        if with_cross:
            cols += [np.log(np.abs(xs[:, i])) * np.log(np.abs(xs[:, k])) for i, k in pairs]
        A = np.stack(cols, axis=1)
        if A.shape[0] < A.shape[1] + 2:
            return None
        coef = np.linalg.lstsq(A, lv, rcond=None)[0]
        err = np.abs(np.exp(A @ coef - lv) - 1.0)
        return coef, err

    plain = solve(False)
    if plain is None:
        return None
    best, with_cross = plain, False
    if cross and pairs:
        crossed = solve(True)
        if crossed is not None and (cross is True or crossed[1].max() <= 0.5 * plain[1].max()):
            best, with_cross = crossed, True
    coef, err = best
    exponents, quadratic, j = [], [], 1
    for i in range(nd):
        if terms[i] == "power":
            exponents.append(float(coef[j]))
            quadratic.append((0.0, 0.0))
            j += 1
        else:
            exponents.append(float("nan"))
            quadratic.append((float(coef[j]), float(coef[j + 1])))
            j += 2
    domain = "whole grid" if ok.all() else f"{int(ok.sum())} of {total} nodes (significant, sign {sign:+g})"
    return PowerLawFit(output, float(coef[0]), tuple(exponents),
                       tuple(float(c) for c in coef[j:]) if with_cross else (), sign,
                       float(err.max()), float(np.median(err)), int(ok.sum()), domain, terms, tuple(quadratic))


def local_floor(fmap, output: str, points: np.ndarray) -> np.ndarray:
    """Denominator floor of the relative error at each point (see the module docstring).

    0 for an output that is nonzero and of one sign on the whole grid (plain
    relative error).  Otherwise ``ZERO_FLOOR`` x the largest |value| on the
    nodes of the point's slab of the first axis (every node whose first index
    is that of the cell's two ends): the first axis carries the scale (gap,
    load, over decades), and an output that vanishes or changes sign along the
    others (the zero force of a separating, cavitated film; a traction
    coefficient through SRR = 0) is judged against its scale at that gap or
    load instead of against zero."""
    v = fmap.values[output]
    if np.all(v > 0) or np.all(v < 0):
        return np.zeros(points.shape[0])
    a = fmap.axes[0]
    cell = np.clip(np.searchsorted(a.nodes, points[:, 0], side="right") - 1, 0, a.n - 2)
    slab = np.abs(v).reshape(a.n, -1).max(axis=1)
    return ZERO_FLOOR * np.maximum(slab[cell], slab[cell + 1])


def _significant(values) -> np.ndarray:
    """Nodes whose |value| is at least ``ZERO_FLOOR`` x the largest |value| of their first-axis slab."""
    v = np.abs(np.asarray(values, float))
    slab = v.reshape(v.shape[0], -1).max(axis=1)
    return (v >= ZERO_FLOOR * slab.reshape((-1,) + (1,) * (v.ndim - 1))).ravel()


# ---------------------------------------------------------------------------
# the map


class KernelArrays(NamedTuple):
    """What :mod:`dynamics.interp` needs for one output (see its docstring).

    ``method`` 0 (linear) or 1 (pchip): ``interp3(*axes, *logs, values, logv, method, x0, x1, x2, mode,
    counter)``; ``method`` 2 (hermite): ``values`` is the node-derivative array of
    :func:`dynamics.interp.hermite_data`, shape (2**ndim, n0, ...): ``hermite3(*axes, *logs, values, logv,
    x0, x1, x2, mode, counter)`` (likewise 1 and 2 axes)."""

    axes: tuple      # prepared node coordinates (log applied on log axes), float64
    logs: tuple      # 0/1 per axis
    values: np.ndarray  # prepared values (log applied when logv), C order; hermite: node derivatives
    logv: int
    method: int      # interp.LINEAR, interp.PCHIP or interp.HERMITE


class FilmMap:
    """Outputs of a film kind tabulated on axes; see the module docstring.

    Parameters
    ----------
    axes : sequence of :class:`MapAxis` (1 to 3)
    values : {output name: array of shape (n0[, n1[, n2]])}
    method : "hermite" (cubic Hermite on PCHIP node slopes, default; the fastest cubic), "pchip"
        (sequential monotone cubic, as scipy's RegularGridInterpolator(method="pchip")) or "linear"
    log_values : {output: bool}; default: log where every value is > 0
    provenance, fits, accuracy : dicts (see :func:`build_map`)
    """

    def __init__(self, axes, values: dict, *, method: str = "hermite", log_values: dict | None = None,
                 provenance: dict | None = None, fits: dict | None = None, accuracy: dict | None = None):
        self.axes = tuple(axes)
        if not 1 <= len(self.axes) <= 3:
            raise InputError(f"a map has 1 to 3 axes, got {len(self.axes)}")
        if method not in METHODS:
            raise unknown_choice("method", method, METHODS)
        self.method = method
        shape = tuple(a.n for a in self.axes)
        self.values = {}
        for name, arr in values.items():
            arr = np.ascontiguousarray(arr, dtype=float)
            if arr.shape != shape:
                raise InputError(f"values of {name!r} have shape {arr.shape}; the axes need {shape}")
            self.values[name] = arr
        log_values = dict(log_values or {})
        self.log_values = {k: bool(log_values.get(k, bool(np.all(v > 0)))) for k, v in self.values.items()}
        self.provenance = dict(provenance or {})
        self.fits = dict(fits or {})
        self.accuracy = dict(accuracy or {})
        self._kernel: dict = {}

    # -- description
    @property
    def outputs(self) -> tuple:
        return tuple(self.values)

    @property
    def shape(self) -> tuple:
        return tuple(a.n for a in self.axes)

    @property
    def ndim(self) -> int:
        return len(self.axes)

    @property
    def kind(self) -> str:
        """Name of the point kind the map tabulates ("" when unknown)."""
        return str(self.provenance.get("kind", ""))

    @property
    def input_hash(self) -> str:
        """sha256 of every input of the build (kind, parameters, axes, method, code); "" when unknown."""
        return str(self.provenance.get("input sha256", {}).get("map", ""))

    def __repr__(self):
        axes = ", ".join(f"{a.name} {a.lo:.3g}..{a.hi:.3g} ({a.n}, {a.scale})" for a in self.axes)
        return f"FilmMap({self.provenance.get('kind', '?')}: {axes}; outputs {', '.join(self.outputs)})"

    def _output(self, output: str) -> str:
        if output not in self.values:
            raise unknown_choice("output", output, self.outputs)
        return output

    # -- kernel
    def kernel_arrays(self, output: str) -> KernelArrays:
        """Plain arrays of ``output`` for :mod:`dynamics.interp` (``interp2(*ka.axes, *ka.logs, ka.values,
        ka.logv, ka.method, x0, x1, mode, counter)``)."""
        output = self._output(output)
        if output not in self._kernel:
            logv = self.log_values[output]
            axes = tuple(interp.prepare_axis(a.nodes, a.log) for a in self.axes)
            u = interp.prepare_values(self.values[output], logv)
            if self.method == "hermite":
                u = interp.hermite_data(axes, u)
            self._kernel[output] = KernelArrays(axes, tuple(int(a.log) for a in self.axes), u, int(logv),
                                                interp.METHODS[self.method])
        return self._kernel[output]

    def __call__(self, output: str, *coords, mode: str = "raise", counter=None, grad: bool = False):
        """Interpolate ``output`` at broadcast ``coords`` (one array per axis, SI).

        ``mode``: "raise" (InputError for a point outside the axes or with a
        NaN coordinate), "clamp" (move it to the nearest end; ``counter[0]``
        counts such points, and points with a NaN coordinate, which give
        NaN), or "nan" (NaN for both).  ``grad=True`` also returns d output/d coordinate, shape (..., ndim).
        """
        if len(coords) != self.ndim:
            raise InputError(f"{output}: give {self.ndim} coordinates ({', '.join(a.name for a in self.axes)}), "
                             f"got {len(coords)}")
        if mode not in ("raise", "clamp", "nan"):
            raise unknown_choice("mode", mode, ("raise", "clamp", "nan"))
        ka = self.kernel_arrays(output)
        arrays = np.broadcast_arrays(*[np.asarray(c, dtype=float) for c in coords])
        shape = arrays[0].shape
        points = np.stack([a.ravel() for a in arrays], axis=1)
        counter = np.zeros(1, dtype=np.int64) if counter is None else counter
        kmode = interp.CLAMP if mode == "clamp" else interp.NAN
        v, g = interp.evaluate(ka.axes, ka.logs, ka.values, ka.logv, ka.method, points, kmode, counter, grad=True)
        if mode == "raise":
            nan_rows = np.isnan(points).any(axis=1)
            if nan_rows.any():
                first = int(np.flatnonzero(nan_rows)[0])
                names = [a.name for a, x in zip(self.axes, points[first]) if np.isnan(x)]
                raise InputError(f"map {self.provenance.get('kind', '')} {output}: {int(nan_rows.sum())} point(s) "
                                 f"with a NaN coordinate, first point {first} ({', '.join(names)} = nan); "
                                 f"every coordinate must be a number (mode='clamp' counts such points, "
                                 f"mode='nan' returns NaN)")
            bad = np.isnan(v)
            if bad.any():
                q = points[np.flatnonzero(bad)[0]]
                where = [f"{a.name} = {x:.6g} (axis {a.lo:.6g} .. {a.hi:.6g})" for a, x in zip(self.axes, q)
                         if not a.lo <= x <= a.hi]
                raise InputError(f"map {self.provenance.get('kind', '')} {output}: {int(bad.sum())} point(s) outside "
                                 f"the axes, first {', '.join(where)}; extend the axes or query with mode='clamp'")
        v = v.reshape(shape)
        return (v, g.reshape(shape + (self.ndim,))) if grad else v

    # -- dynamics
    def is_polar(self) -> bool:
        """True for a ball_ball map on the polar axes (gap, pressure number, squeeze angle)."""
        return [a.name for a in self.axes][1:] == [POLAR_AXES[0], POLAR_AXES[1]]

    def dynamics_film_map(self, output: str = "Force [N]"):
        """Kernel arrays of ``output`` for :class:`dynamics.cageless.CagelessBearing` (``film = "map"``).

        A map on (gap, squeeze number or approach speed, entrainment speed): its kernel arrays.  A polar
        ball_ball map (:mod:`coupling.film_points`, "Polar axes"): ``(*kernel_arrays, "polar")`` when the
        bearing kernel reads polar axes (``dynamics.contacts.MAP_AXIS_POLAR``); otherwise the map resampled
        on the (gap, squeeze number, entrainment speed) nodes that kernel reads (:func:`cartesian_resample`;
        transitional: that grid has the cone at zero approach speed that the polar axes remove)."""
        output = self._output(output)
        if not self.is_polar():
            return self.kernel_arrays(output)
        from dynamics import contacts

        if hasattr(contacts, "MAP_AXIS_POLAR"):
            return tuple(self.kernel_arrays(output)) + ("polar",)
        return cartesian_resample(self, output).kernel_arrays(output)

    def grid_points(self) -> np.ndarray:
        """All nodes as (N, ndim) in C order of the value arrays."""
        grids = np.meshgrid(*[a.nodes for a in self.axes], indexing="ij")
        return np.stack([g.ravel() for g in grids], axis=1)

    # -- fit
    def fit_power_law(self, output: str, cross="auto") -> PowerLawFit | None:
        """Fit (and keep in ``self.fits``) a power law of ``output``; see :func:`fit_power_law`."""
        output = self._output(output)
        fit = fit_power_law(self.axes, self.values[output], output, cross)
        self.fits[output] = fit
        return fit

    # -- accuracy
    def accuracy_against(self, points: np.ndarray, direct: dict) -> dict:
        """Interpolation error at ``points`` (m, ndim) against ``direct`` {output: (m,) values}:
        per output ``{"median": .., "max": .., "points": m, "above 3 %": .., "worst point": [...]}``."""
        report = {}
        for name, exact in direct.items():
            if name not in self.values:
                continue
            exact = np.asarray(exact, float)
            approx = self(name, *points.T, mode="nan")
            err = relative_error(approx, exact, local_floor(self, name, points))
            ok = np.isfinite(err)
            if not ok.any():
                continue
            worst = int(np.nanargmax(np.where(ok, err, -1)))
            report[name] = {"median": float(np.median(err[ok])), "max": float(err[ok].max()), "points": int(ok.sum()),
                            "above 3 %": int(np.sum(err[ok] > 0.03)),
                            "worst point": [float(x) for x in points[worst]]}
        return report

    # -- storage
    def _header(self) -> dict:
        return {
            "format": FORMAT, "format_version": FORMAT_VERSION, "method": self.method,
            "axes": [{"name": a.name, "scale": a.scale, "array": f"axis_{i}"} for i, a in enumerate(self.axes)],
            "outputs": [{"name": k, "log_values": self.log_values[k], "array": f"values_{i}"}
                        for i, k in enumerate(self.values)],
            "provenance": self.provenance,
            "fits": {k: (dataclasses.asdict(f) if f is not None else None) for k, f in self.fits.items()},
            "accuracy": self.accuracy,
        }

    def save(self, path) -> Path:
        """Write one self-describing ``.npz`` (arrays + JSON header) atomically."""
        arrays = {f"axis_{i}": a.nodes for i, a in enumerate(self.axes)}
        arrays.update({f"values_{i}": v for i, v in enumerate(self.values.values())})
        arrays["header"] = np.array(json.dumps(self._header(), default=_json_default))
        buffer = io.BytesIO()
        np.savez_compressed(buffer, **arrays)
        return outputs.write_bytes(path, buffer.getvalue())

    @classmethod
    def load(cls, path) -> "FilmMap":
        """Read a file written by :meth:`save`; checks the format name and version."""
        path = Path(path)
        if not path.is_file():
            raise InputError(f"map file {str(path)!r} not found")
        try:
            with np.load(path, allow_pickle=False) as data:
                header = json.loads(str(data["header"]))
                arrays = {k: np.array(data[k]) for k in data.files if k != "header"}
        except (KeyError, ValueError, OSError) as exc:
            raise InputError(f"map file {str(path)!r} is not a lubedyn film map ({' '.join(str(exc).split())})") from None
        if header.get("format") != FORMAT:
            raise InputError(f"map file {str(path)!r}: format {header.get('format')!r}, expected {FORMAT!r}")
        if header.get("format_version") != FORMAT_VERSION:
            raise InputError(f"map file {str(path)!r}: format_version = {header.get('format_version')!r}; this "
                             f"lubedyn reads version {FORMAT_VERSION} (rebuild the map)")
        axes = [MapAxis(a["name"], arrays[a["array"]], a["scale"]) for a in header["axes"]]
        values = {o["name"]: arrays[o["array"]] for o in header["outputs"]}
        fits = {k: (PowerLawFit(**{**f, "exponents": tuple(f["exponents"]), "cross": tuple(f["cross"]),
                                   "terms": tuple(f.get("terms", ())),
                                   "quadratic": tuple(tuple(q) for q in f.get("quadratic", ()))})
                    if f is not None else None) for k, f in header.get("fits", {}).items()}
        return cls(axes, values, method=header["method"],
                   log_values={o["name"]: o["log_values"] for o in header["outputs"]},
                   provenance=header.get("provenance", {}), fits=fits, accuracy=header.get("accuracy", {}))

    # -- plots
    def plot(self, outputs_=None, *, lines: int = 5):
        """One panel per output against axis 0, a line per node of axis 1 (up to ``lines``),
        the other axes at their middle node.  Returns the matplotlib figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        names = list(outputs_ or self.outputs)
        ncol = min(3, len(names))
        nrow = math.ceil(len(names) / ncol)
        fig, axs = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.6 * nrow), squeeze=False)
        a0 = self.axes[0]
        fine = np.geomspace(a0.lo, a0.hi, 200) if a0.log else np.linspace(a0.lo, a0.hi, 200)
        picks = [0] if self.ndim == 1 else sorted(set(np.linspace(0, self.axes[1].n - 1, min(lines, self.axes[1].n))
                                                      .round().astype(int)))
        mids = [a.nodes[a.n // 2] for a in self.axes[2:]]
        cmap = plt.get_cmap("viridis")
        for ax, name in zip(axs.ravel(), names):
            for c, j in enumerate(picks):
                coords = [fine] + ([np.full_like(fine, self.axes[1].nodes[j])] if self.ndim > 1 else []) + \
                         [np.full_like(fine, m) for m in mids]
                color = cmap(c / max(1, len(picks) - 1))
                label = f"{self.axes[1].name.split('[')[0].strip()} = {self.axes[1].nodes[j]:.3g}" if self.ndim > 1 else None
                ax.plot(fine, self(name, *coords, mode="clamp"), color=color, lw=1.2, label=label)
                index = (slice(None),) + ((j,) if self.ndim > 1 else ()) + tuple(a.n // 2 for a in self.axes[2:])
                ax.plot(a0.nodes, self.values[name][index], "o", color=color, ms=3)
            v = self.values[name]
            if a0.log:
                ax.set_xscale("log")
            pos = v[v > 0]
            if self.log_values[name] or (np.all(v >= 0) and pos.size and pos.max() > 1e3 * pos.min()):
                ax.set_yscale("log")  # zeros (a cavitated film's force) are left out of a log axis
            elif np.any(v < 0) and np.any(v > 0):
                ax.set_yscale("symlog", linthresh=ZERO_FLOOR * np.abs(v).max() * 10)
            ax.set_xlabel(a0.name)
            ax.set_ylabel(name)
            ax.grid(True, which="both", alpha=0.3)
        if self.ndim > 1:
            axs.ravel()[0].legend(fontsize=7)
        for ax in axs.ravel()[len(names):]:
            ax.set_visible(False)
        rest = ", ".join(f"{a.name} = {m:.3g}" for a, m in zip(self.axes[2:], mids))
        fig.suptitle(f"{self.provenance.get('kind', 'map')}: nodes (dots) and {self.method} interpolation (lines)"
                     + (f"; {rest}" if rest else ""), fontsize=9)
        fig.tight_layout()
        return fig


_json_default = outputs.json_default

POLAR_AXES = ("Pressure number [-]", "Squeeze angle [rad]")
CARTESIAN_SQUEEZE = (0.0, 0.01, 0.03, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9)
CARTESIAN_ENTRAINMENT = (0.0, 0.025, 0.05)


def cartesian_resample(fmap: "FilmMap", output: str = "Force [N]", squeeze=CARTESIAN_SQUEEZE,
                       entrainment=CARTESIAN_ENTRAINMENT, gaps: int = 19) -> "FilmMap":
    """A polar ball_ball map's ``output`` on (gap, squeeze number, entrainment speed) nodes (approach side).

    Each node (h0, Lambda, u_e) is turned into (rho, theta) (:func:`coupling.film_points.polar_numbers`)
    and read from the polar map: rho above the axis is clamped, rho below its first node scales the
    output by rho/rho_lo (isoviscous limit: F, K ~ rho), rho = 0 gives 0."""
    from . import film_points as fp

    params = fmap.provenance.get("params") or fp.ball_ball_default_params()
    g = fmap.axes[0]
    h_nodes = np.geomspace(g.lo, g.hi, gaps)
    rho_lo, rho_hi = fmap.axes[1].lo, fmap.axes[1].hi
    vals = np.zeros((gaps, len(squeeze), len(entrainment)))
    for i, h0 in enumerate(h_nodes):
        for j, lam in enumerate(squeeze):
            for k, ue in enumerate(entrainment):
                rho, theta = fp.polar_numbers(h0, fp.approach_speed(h0, lam, params), ue, params)
                if rho <= 0.0:
                    continue
                rq = min(max(rho, rho_lo), rho_hi)
                vals[i, j, k] = float(fmap(output, h0, rq, theta, mode="clamp")) * (rho / rho_lo if rho < rho_lo else 1.0)
    axes = [MapAxis(g.name, h_nodes, "log"), MapAxis("Squeeze number [-]", np.array(squeeze, float), "linear"),
            MapAxis("Entrainment speed [m/s]", np.array(entrainment, float), "linear")]
    prov = {**fmap.provenance, "resampled from": "polar axes (gap, pressure number, squeeze angle)"}
    return FilmMap(axes, {output: vals}, method=fmap.method, provenance=prov)


# ---------------------------------------------------------------------------
# hashing and versions


def _canonical(obj) -> str:
    """JSON with sorted keys and floats written exactly (hex), for hashing."""

    def plain(o):
        if isinstance(o, dict):
            return {str(k): plain(v) for k, v in sorted(o.items(), key=lambda kv: str(kv[0]))}
        if isinstance(o, (list, tuple)):
            return [plain(v) for v in o]
        if isinstance(o, np.ndarray):
            return [plain(v) for v in o.tolist()]
        if isinstance(o, (float, np.floating)):
            return float(o).hex()
        if isinstance(o, np.integer):
            return int(o)
        return o

    return json.dumps(plain(obj), sort_keys=True)


def sha256_text(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def code_fingerprint(kind) -> dict:
    """sha256 of the kind's source file and of ``lubrication/**/*.py`` (the solver and the laws), and the
    lubedyn version."""
    from . import __version__

    out = {"lubedyn": __version__}
    try:
        src = Path(inspect.getsourcefile(kind.evaluate))
        out[f"kind source {src.name}"] = hashlib.sha256(src.read_bytes()).hexdigest()
    except (TypeError, OSError):
        out["kind source"] = "unavailable"
    import lubrication

    digest = hashlib.sha256()
    root = Path(lubrication.__file__).parent
    for p in sorted(root.rglob("*.py")):
        digest.update(p.relative_to(root).as_posix().encode())
        digest.update(p.read_bytes())
    out["lubrication sources"] = digest.hexdigest()
    return out


def versions() -> dict:
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for dist in ("lubedyn", "numpy", "scipy", "scikit-fem", "numba", "dask", "distributed"):
        try:
            out[dist] = version(dist)
        except PackageNotFoundError:
            out[dist] = None
    return out


def point_hash(kind_name: str, params: dict, point: dict, code: dict) -> str:
    return sha256_text(_canonical({"kind": kind_name, "params": params, "point": point, "code": code}))


# ---------------------------------------------------------------------------
# solving points


def _solve_point(evaluate, params, point):
    """Worker: ("ok", outputs) or ("failed", message); never raises (one failure must not stop a pool)."""
    try:
        result = evaluate(params, point)
        return "ok", {k: float(v) for k, v in result.items()}
    except Exception as exc:  # noqa: BLE001 - recorded and reported by the caller
        return "failed", f"{type(exc).__name__}: {' '.join(str(exc).split())}"


def _solve_chunk(evaluate, params, points, store_root=None, keys=None):
    """Worker: :func:`_solve_point` for each point of a chunk, in order, in one process (a kind may
    cache work shared by the chunk, e.g. an EHL solve shared by every slide-to-roll ratio).  With
    ``store_root`` (a local folder), each solved point is stored at once (``keys``: the point hashes),
    so that an interrupted or killed build keeps every point finished before it stopped."""
    store = _PointStore(store_root) if store_root is not None else None
    out = []
    for i, p in enumerate(points):
        status, payload = _solve_point(evaluate, params, p)
        if store is not None and status == "ok":
            store.put(keys[i], p, payload)
        out.append((status, payload))
    return out


def _chunks(points, todo) -> list:
    """``todo`` indices grouped by every coordinate but the last (one line of the last axis per chunk)."""
    groups: dict = {}
    for i in todo:
        key = tuple(points[i].values())[:-1]
        groups.setdefault(key, []).append(i)
    return list(groups.values())


def _limit_threads():
    """One BLAS thread per worker process (the workers already fill the cores)."""
    try:
        from threadpoolctl import threadpool_limits

        threadpool_limits(1)
    except Exception:  # noqa: BLE001 - threadpoolctl is optional
        pass


def _die_with_parent(parent_pid: int) -> str:
    """Make this (worker) process end when ``parent_pid`` does; returns the means used.

    Linux: ``prctl(PR_SET_PDEATHSIG, SIGKILL)``, then a check that the parent did not die before it
    took effect.  Elsewhere: a daemon thread that polls ``os.getppid()`` twice a second."""
    import signal
    import sys

    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            if libc.prctl(1, int(signal.SIGKILL), 0, 0, 0) == 0:  # 1 = PR_SET_PDEATHSIG
                if os.getppid() != parent_pid:  # the parent died before prctl: nobody will signal us
                    os._exit(1)
                return "prctl"
        except (OSError, AttributeError):  # pragma: no cover - no libc prctl
            pass
    import threading

    def watch():
        while os.getppid() == parent_pid:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="lubedyn-parent-watch", daemon=True).start()
    return "watchdog thread"


def _init_worker(parent_pid: int):
    """Pool initializer: ignore SIGINT (the parent handles Ctrl-C and stops the workers), die with the
    parent, one BLAS thread."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})  # blocked by the parent while forking
    _die_with_parent(parent_pid)
    _limit_threads()


@contextlib.contextmanager
def _sigint_blocked():
    """Block SIGINT in this thread while workers are forked (they inherit the mask and set SIG_IGN
    before unblocking), so that a Ctrl-C at that moment reaches the parent only."""
    import signal
    import threading

    can = hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()
    if can:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        if can:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _stop_pool(pool, timeout: float = 3.0):
    """Cancel every pending chunk and end the workers now (an interrupt or an error): the points
    they finished are already stored."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.terminate()
    deadline = time.monotonic() + timeout
    for proc in processes:
        with contextlib.suppress(Exception):
            proc.join(max(0.0, deadline - time.monotonic()))
            if proc.is_alive():
                proc.kill()
                proc.join(1.0)


def default_workers() -> int:
    """Cores this process may use (``os.sched_getaffinity``)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover
        return max(1, os.cpu_count() or 1)


class _PointStore:
    """One small JSON file per solved point, keyed by the point hash, written atomically."""

    def __init__(self, root):
        self.root = Path(root) if root is not None else None
        self.memory: dict = {}

    def get(self, key):
        if key in self.memory:
            return self.memory[key]
        if self.root is None:
            return None
        path = self.root / f"{key}.json"
        if path.is_file():
            try:
                return json.loads(path.read_text())["outputs"]
            except (ValueError, KeyError, OSError):
                log.warning("ignoring unreadable cached point %s", path)
        return None

    def put(self, key, point, result, *, write=True):
        self.memory[key] = result
        if self.root is not None and write:
            outputs.write_text(self.root / f"{key}.json",
                               json.dumps({"point": point, "outputs": result}, default=_json_default))


def solve_points(kind, params: dict, points: list, *, workers=None, scheduler=None, store=None, progress=True,
                 code=None, desc="points") -> tuple[list, dict]:
    """Solve ``points`` (list of {axis name: value}); returns (results, info).

    ``results[i]`` is the output dict or None (failed: ``info["failed"]``
    lists (index, point, message)).  Cached points come from ``store``; new
    ones are stored as soon as they arrive.
    """
    store = store if store is not None else _PointStore(None)
    code = code if code is not None else code_fingerprint(kind)
    keys = [point_hash(kind.name, params, p, code) for p in points]
    results: list = [store.get(k) for k in keys]
    todo = [i for i, r in enumerate(results) if r is None]
    info = {"cached": len(points) - len(todo), "solved": 0, "failed": [], "backend": "none needed"}
    if not todo:
        return results, info
    from tqdm.auto import tqdm

    bar = tqdm(total=len(todo), desc=desc, unit="pt", disable=None if progress else True, leave=False)

    def accept(i, status, payload, stored=False):
        if status == "ok":
            results[i] = payload
            store.put(keys[i], points[i], payload, write=not stored)
            info["solved"] += 1
        else:
            info["failed"].append((i, points[i], payload))
            log.warning("map point %s failed: %s", points[i], payload)
        bar.update(1)

    workers = workers or min(default_workers(), len(todo))
    try:
        if scheduler is not None:
            info["backend"] = _solve_dask(kind, params, points, todo, scheduler, accept)
        elif workers <= 1 or len(todo) == 1:
            info["backend"] = "serial (this process)"
            for i in todo:
                accept(i, *_solve_point(kind.evaluate, params, points[i]))
        else:
            import multiprocessing

            info["backend"] = f"local processes ({workers})"
            ctx = multiprocessing.get_context("fork") if hasattr(os, "fork") else None
            pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init_worker,
                                          initargs=(os.getpid(),))
            root = str(store.root) if store.root is not None else None
            try:
                with _sigint_blocked():
                    futures = {pool.submit(_solve_chunk, kind.evaluate, params, [points[i] for i in chunk],
                                           root, [keys[i] for i in chunk]): chunk
                               for chunk in _chunks(points, todo)}
                for fut in cf.as_completed(futures):
                    for i, r in zip(futures[fut], fut.result()):
                        accept(i, *r, stored=root is not None)
            except BaseException:  # Ctrl-C or an error: do not wait for the queued points
                _stop_pool(pool)
                raise
            pool.shutdown(wait=True)
    finally:
        bar.close()
    return results, info


def _solve_dask(kind, params, points, todo, scheduler, accept) -> str:
    """Solve on a Dask distributed cluster: ``scheduler`` is an address, a Client or a cluster."""
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise InputError("build.scheduler needs dask.distributed (pip install lubedyn[dask])") from None
    own = False
    if isinstance(scheduler, Client):
        client = scheduler
    else:
        address = getattr(scheduler, "scheduler_address", scheduler)
        try:
            client = Client(address, timeout="10s")
        except (OSError, TimeoutError) as exc:
            raise InputError(f"build.scheduler = {address!r}: cannot connect ({' '.join(str(exc).split())})") from None
        own = True
    try:
        chunks = _chunks(points, todo)
        futures = client.map(_solve_chunk, [kind.evaluate] * len(chunks), [params] * len(chunks),
                             [[points[i] for i in chunk] for chunk in chunks], pure=False)
        index = {f.key: chunk for f, chunk in zip(futures, chunks)}
        try:
            for fut in as_completed(futures):
                for i, r in zip(index[fut.key], fut.result()):
                    accept(i, *r)
        except BaseException:  # Ctrl-C or an error: cancel what the cluster has not done yet
            with contextlib.suppress(Exception):
                client.cancel(futures)
            raise
        return f"dask ({client.scheduler.address})"
    finally:
        if own:
            client.close()


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
              on_failure: str = "raise", fit: bool = True) -> FilmMap:
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
    if map_file is not None and map_file.is_file():
        try:
            cached = FilmMap.load(map_file)
            if cached.provenance.get("input sha256", {}).get("map") == hashes["map"]:
                log.info("map %s: inputs unchanged, loaded %s", kind.name, map_file)
                cached.provenance["loaded from cache"] = str(map_file)
                return cached
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
    fmap = FilmMap(axes, values, method=method, provenance=provenance,
                   log_values={name: False for name in names if name in signed})
    if fit:
        for name in names:
            fmap.fit_power_law(name)
    if accuracy_points:
        fmap.accuracy = accuracy_report(fmap, kind, params, accuracy_points, seed=seed, workers=workers,
                                        scheduler=scheduler, store=store, progress=progress, code=code)
    fmap.provenance["build time [s]"] = time.perf_counter() - t0
    if map_file is not None:
        fmap.save(map_file)
    return fmap


def accuracy_report(fmap: FilmMap, kind, params: dict, n: int, *, seed: int = 0, workers=None, scheduler=None,
                    store=None, progress=True, code=None) -> dict:
    """Solve ``n`` random off-grid points (:func:`random_points`) directly and compare with the map.

    Returns {output: {"median", "max", "points", "worst point"}} plus "seed", "requested points" and
    "failed points" (points whose direct solve failed are left out)."""
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


def _unknown_key(path: str, what: str, key: str, allowed) -> InputError:
    hint = did_you_mean(key, allowed)
    return InputError(f"{path}: {what}{hint} (allowed: {', '.join(map(str, allowed))})")


def _show_point(point: dict) -> str:
    return "(" + ", ".join(f"{k} = {v:.6g}" for k, v in point.items()) + ")"
