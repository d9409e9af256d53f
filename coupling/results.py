"""Results of a time-domain run, by name: what :func:`lubedyn.run` returns for the bearing scenes.

A bearing run (scenes ``dynamics`` and ``tapered``) returns a :class:`BearingResult`: its ``summary`` (the
dict written to ``summary.json``), the ``files`` written, the raw ``t`` and state ``y``, and ``series``, the
time series by the names the run's time series file (``timeseries.nc``) uses (name with unit -> array over ``t``), computed when first
read.  So from Python::

    res = lubedyn.run(lubedyn.load_case("cageless_6206_10krpm_short", smoke=True))
    res["Rotor speed [rad/s]"]          # one named series (numpy array over res.t)
    res.names                           # every name
    res.units("Rotor speed [rad/s]")    # "rad/s"
    res.warnings                        # the run's warnings (summary "Warnings"), [] when none
    ds = res.to_xarray()                # an xarray.Dataset over "time" (what timeseries.nc holds)
    fig = res.plot("trajectories")      # a figure lubedyn run writes (res.kinds lists them)

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
        """An ``xarray.Dataset`` over the dimension "time" (coordinate in s) (:func:`dataset`)."""
        return dataset(self.t, self._columns(), attrs)


_BODY = re.compile(r"^(?P<body>[A-Z][a-z]+) (?P<index>\d+(?:-\d+)?) (?P<rest>\S.*)$")


def import_xarray():
    """The xarray module, or an ImportError of one line saying how to install it."""
    try:
        import xarray as xr
    except ImportError:  # one line for the user, not a traceback of the optional dependency
        raise ImportError("to_xarray() needs xarray: pip install 'lubedyn[xarray]' (or pip install xarray)") from None
    return xr


def dataset(t, columns: dict, attrs: dict | None = None):
    """The columns (name with unit -> array over ``t``) as an ``xarray.Dataset`` over the dimension "time".

    The columns of numbered bodies, "Ball 3 x [m]" or "Pair 0-1 plastic memory [m]", become one variable per
    quantity over ("time", body): "Ball x" over ("time", "ball"), the coordinate "ball" holding the numbers
    (labels such as "0-1" as strings), when every body of that kind has the quantity; every other column is
    a variable of its own, named without its unit.  Each variable has the attributes ``units``,
    ``long_name`` (the name without its unit) and ``column``: the column's full name, for a body's variable
    with ``{ball}`` (the dimension's name in braces) where the number goes, which :func:`columns_of` reads
    back.  On the README's main job (smoke) the 490 columns are 48 variables; as compressed netCDF 1.25 MB
    against 3.3 MB with one variable per column (HDF5's overhead per variable)."""
    xr = import_xarray()
    t = np.asarray(t)
    bodies: dict = {}  # body kind -> {quantity: {index: column}}
    for column in columns:
        m = _BODY.match(column)
        if m is not None:
            bodies.setdefault(m["body"], {}).setdefault(m["rest"], {})[m["index"]] = column
    grouped: dict = {}  # column -> (body kind, quantity) of the columns that go in a body variable
    labels: dict = {}  # body kind -> its indices in the order of the columns
    for body, quantities in bodies.items():
        order = list(dict.fromkeys(i for q in quantities.values() for i in q))
        if len(order) < 2:
            continue
        labels[body] = order
        for rest, members in quantities.items():
            if list(members) == order:  # every body of the kind has it, in one order: a body variable
                grouped.update({c: (body, rest) for c in members.values()})
    data, done = {}, set()
    for column, values in columns.items():
        values = np.asarray(values)
        if values.shape[:1] != t.shape:
            continue  # not a series over time
        if column in grouped:
            body, rest = grouped[column]
            if (body, rest) in done:
                continue
            done.add((body, rest))
            dim = body.lower()
            name, unit = split_unit(f"{body} {rest}")
            members = bodies[body][rest]
            stacked = np.stack([np.asarray(columns[members[i]]) for i in labels[body]], axis=1)
            data[name] = xr.Variable(("time", dim), stacked, attrs={
                "units": unit, "long_name": name, "column": f"{body} {{{dim}}} {rest}"})
            continue
        name, unit = split_unit(column)
        dims = ("time",) + tuple(f"{name} axis {k}" for k in range(1, values.ndim))
        data[name] = xr.Variable(dims, values, attrs={"units": unit, "long_name": name, "column": column})
    coords = {"time": ("time", t, {"units": "s", "long_name": "Time", "column": "Time [s]"})}
    for body, order in labels.items():
        numbers = all(i.isdigit() for i in order)
        coords[body.lower()] = (body.lower(), np.array([int(i) for i in order] if numbers else order),
                                {"long_name": f"{body} number"})
    return xr.Dataset(data, coords=coords, attrs=dict(attrs or {}))


def columns_of(ds) -> dict:
    """The columns of a Dataset made by :func:`dataset` (or read from a file it was written to), by their
    full names, "Time [s]" first: the inverse of :func:`dataset`."""
    out = {"Time [s]": np.asarray(ds["time"].values)}
    for name, var in ds.data_vars.items():
        column = var.attrs.get("column", name)
        if var.dims[1:] and var.dims[1] in ds.coords and "{" + var.dims[1] + "}" in column:
            dim = var.dims[1]
            for k, label in enumerate(ds[dim].values):
                out[column.replace("{" + dim + "}", str(label))] = np.asarray(var.values[:, k])
        else:
            out[column] = np.asarray(var.values)
    return out


@dataclass
class BearingResult:
    """What a bearing scene's run returns (see the module docstring): ``summary``, ``files``, ``t`` [s],
    ``y`` (the state over ``t``), ``series`` (:class:`TimeSeries`); ``res[name]`` reads a series."""

    summary: dict = field(default_factory=dict)
    files: list = field(default_factory=list)
    t: Any = None
    y: Any = None
    series: TimeSeries | None = None
    drawings: dict = field(default_factory=dict, repr=False)  # {figure file name: draw(into=None)}

    @property
    def kinds(self) -> list[str]:
        """The figures :meth:`plot` draws: the names of the PNG files ``lubedyn run`` writes, without ``.png``."""
        return [name.removesuffix(".png") for name in self.drawings]

    def plot(self, kind: str, ax=None, fig=None):
        """Draw the figure ``kind`` (one of :attr:`kinds`: ``"trajectories"`` for ``trajectories.png`` ...)
        as ``lubedyn run`` writes it, by the same code, and return its matplotlib figure: a new figure
        (pyplot's for the cage-less bearing, a bare ``matplotlib.figure.Figure`` for the tapered one),
        or drawn into ``fig`` (a Figure or SubFigure: its panels are added there) or ``ax`` (an Axes, for a
        figure of one panel).  An unknown kind, or ``ax`` for a figure of several panels, is a one-line
        ValueError naming what is allowed."""
        name = f"{kind}.png" if isinstance(kind, str) else kind
        if name not in self.drawings:
            allowed = ", ".join(repr(k) for k in self.kinds) or "none (this result was made without its figures)"
            raise ValueError(f"plot kind {kind!r} is not one of {allowed}{did_you_mean(str(kind), self.kinds)}")
        if ax is not None and fig is not None:
            raise ValueError("plot takes ax= or fig=, not both")
        return self.drawings[name](ax if ax is not None else fig)

    def __getitem__(self, name: str) -> np.ndarray:
        if self.series is None:
            raise KeyError("this result has no time series (it was made without its run's columns)")
        return self.series[name]

    @property
    def names(self) -> list[str]:
        """Every time series' name (with its unit), as in the run's time series file."""
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
