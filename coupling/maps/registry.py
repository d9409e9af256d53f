"""The registry of map kinds, the file format constants and the map axes.

Part of :mod:`lubedyn.maps` (the package docstring gives the overview)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from lubedyn.lubrication.errors import InputError, did_you_mean, unknown_choice

FORMAT = "lubedyn film map"
FORMAT_VERSION = 1
METHODS = ("hermite", "pchip", "linear")
ZERO_FLOOR = 1e-3  # relative-error floor, as a fraction of an output's largest |value|
#: Default accuracy tolerance of a map: the largest relative interpolation error of any output at the
#: accuracy report's random off-grid points (``build_map(accuracy_tolerance=)``, a map case's
#: ``build.accuracy_tolerance``) above which the map warns when built and when loaded
#: (:meth:`FilmMap.accuracy_warning`).  No tolerance existed before: 3 % is the target the shipped maps
#: are held to (median < 1 %, max < 3 %; cases/maps/README.md, tests/test_maps.py), about the
#: spread of the films themselves (K, C of neighbouring EHL solves jitter by 1-4 %), so a map within it
#: adds no error a film model would not; every miss recorded there (4-877 %: interpolation across a
#: front, or a solver's jitter) is above it.  The shipped maps meet it (worst: ball_ball damping 2.98 %);
#: the median target is not checked (a warning names the worst points, which the max covers).
ACCURACY_TOLERANCE = 0.03

# ---------------------------------------------------------------------------
# kinds


_REGISTRY: dict[str, Any] = {}


def register_kind(kind) -> None:
    """Make a point kind known to :func:`get_kind` (tests, user kinds)."""
    _REGISTRY[kind.name] = kind


def kinds() -> dict:
    """Every known point kind: :data:`lubedyn.film_points.KINDS` plus the registered ones."""
    out = {}
    try:
        from lubedyn.film_points import KINDS  # deferred: the point kinds import scikit-fem

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
    """``"Approach speed [m/s]"`` -> ``"m/s"`` ("" without brackets): :func:`lubedyn.results.split_unit`'s unit."""
    from lubedyn.results import split_unit

    return split_unit(name)[1].strip()


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

def _unknown_key(path: str, what: str, key: str, allowed) -> InputError:
    hint = did_you_mean(key, allowed)
    return InputError(f"{path}: {what}{hint} (allowed: {', '.join(map(str, allowed))})")


def _show_point(point: dict) -> str:
    return "(" + ", ".join(f"{k} = {v:.6g}" for k, v in point.items()) + ")"
