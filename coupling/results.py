"""Results of a time-domain run, by name: what :func:`lubedyn.run` returns for the bearing scenes.

A bearing run (scenes ``dynamics`` and ``tapered``) returns a :class:`BearingResult`: its ``summary`` (the
dict written to ``summary.json``), the ``files`` written, the raw ``t`` and state ``y``, and ``series``, the
time series by the names ``timeseries.npz`` uses (name with unit -> array over ``t``), computed when first
read.  So from Python::

    res = lubedyn.run(lubedyn.load_case("cageless_6206_10krpm_short", smoke=True))
    res["Rotor speed [rad/s]"]          # one named series (numpy array over res.t)
    res.names                           # every name
    res.units("Rotor speed [rad/s]")    # "rad/s"
    res.warnings                        # the run's warnings (summary "Warnings"), [] when none
    ds = res.to_xarray()                # an xarray.Dataset over "time" (optional extra: xarray)

A name that does not exist is a one-line :class:`KeyError` with the closest names.  ``to_xarray()`` gives
one variable per column, named as the column without its unit, with the unit and the column's full name
in the attributes and the summary's scalar identity (case, scene, lubedyn version) in the dataset's.
"""
from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from lubedyn.lubrication.errors import did_you_mean

_UNIT = re.compile(r"^(?P<name>.*?)\s*\[(?P<unit>[^\[\]]*)\]$")


def split_unit(column: str) -> tuple[str, str]:
    """(name, unit) of a column name "Name [unit]" ("" when it has none).

    >>> split_unit("Rotor speed [rad/s]")
    ('Rotor speed', 'rad/s')
    >>> split_unit("Phase")
    ('Phase', '')
    """
    m = _UNIT.match(column)
    return (m["name"], m["unit"]) if m else (column, "")


class TimeSeries(Mapping):
    """A run's time series by name: ``t`` [s] and the columns of ``columns()`` (name with unit -> array over
    ``t``), computed on first access and kept."""

    def __init__(self, t, columns: Callable[[], dict] | None):
        self.t = np.asarray(t) if t is not None else np.zeros(0)
        self._make = columns
        self._cols: dict | None = None

    def _columns(self) -> dict:
        if self._cols is None:
            self._cols = dict(self._make()) if self._make is not None else {}
        return self._cols

    def __getitem__(self, name: str) -> np.ndarray:
        cols = self._columns()
        if name == "Time [s]":
            return self.t
        if name not in cols:
            raise KeyError(f"no time series named {name!r} ({len(cols)} series; lubedyn results' .names lists "
                           f"them){did_you_mean(str(name), list(cols))}")
        return cols[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns())

    def __len__(self) -> int:
        return len(self._columns())

    def to_xarray(self, attrs: dict | None = None):
        """An ``xarray.Dataset`` over the dimension "time" (coordinate in s): one variable per series, named
        without its unit, with ``units`` and ``long_name`` (the full column name) attributes."""
        try:
            import xarray as xr
        except ImportError:  # one line for the user, not a traceback of the optional dependency
            raise ImportError("to_xarray() needs xarray: pip install 'lubedyn[xarray]' (or pip install xarray)") from None
        data = {}
        for column, values in self._columns().items():
            name, unit = split_unit(column)
            values = np.asarray(values)
            if values.shape[:1] != self.t.shape:
                continue  # not a series over time
            dims = ("time",) + tuple(f"{name} axis {k}" for k in range(1, values.ndim))
            data[name] = xr.Variable(dims, values, attrs={"units": unit, "long_name": column})
        return xr.Dataset(data, coords={"time": ("time", self.t, {"units": "s", "long_name": "Time [s]"})},
                          attrs=dict(attrs or {}))


@dataclass
class BearingResult:
    """What a bearing scene's run returns (see the module docstring): ``summary``, ``files``, ``t`` [s],
    ``y`` (the state over ``t``), ``series`` (:class:`TimeSeries`); ``res[name]`` reads a series."""

    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)
    t: Any = None
    y: Any = None
    series: TimeSeries | None = None

    def __getitem__(self, name: str) -> np.ndarray:
        if self.series is None:
            raise KeyError("this result has no time series (it was made without its run's columns)")
        return self.series[name]

    @property
    def names(self) -> list[str]:
        """Every time series' name (with its unit), as in ``timeseries.npz``."""
        return [] if self.series is None else list(self.series)

    @staticmethod
    def units(name: str) -> str:
        """The unit of series ``name`` ("" when it has none)."""
        return split_unit(name)[1]

    @property
    def warnings(self) -> list[str]:
        """The run's warnings (summary ``"Warnings"``: outputs outside their physical bound under
        ``[validity] strict = false``, validity warnings), [] when none."""
        return list(self.summary.get("Warnings", []))

    def to_xarray(self):
        """The time series as an ``xarray.Dataset`` (:meth:`TimeSeries.to_xarray`), the summary's case, scene
        and version in its attributes."""
        if self.series is None:
            raise KeyError("this result has no time series (it was made without its run's columns)")
        keep = {k: v for k, v in self.summary.items() if k in ("Case", "Scene", "Description", "lubedyn version")
                and isinstance(v, (str, int, float))}
        return self.series.to_xarray(keep)
