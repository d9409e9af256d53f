"""Parameter sets: each paper's data in one cited module (values, units, sources, assumptions).

A case file names a set with a top-level key and overrides what it changes::

    parameters = "Zhang2024"      # paper B's 6206 bearing, oil and operating point
    [operating]
    speed = "15000 rpm"           # the case's own value

:func:`apply_parameter_set` fills every key of the case's scene that the set provides and the file
does not give (the file and ``--set`` overrides win).  A set is a module with

- ``NAME``, ``CITATION``;
- ``VALUES``: ``{name: Parameter}``, each value written as a case file writes it (a quantity with its
  unit, exactly as the paper prints it where it does), its dimension, the table/equation/section it
  comes from, and a note saying what was assumed or how a garbled value was read;
- ``SCENES``: ``{scene: {"table.key": name}}``, where each case schema takes each value.

Library defaults carry no paper data; the film-point kinds of :mod:`lubedyn.film_points` read
their paper values from here with :func:`si`.

=============  =====================================================================================
set            paper
=============  =====================================================================================
``Zhang2024``  cage-less 6206 ball bearing with a functional slot (paper B; :mod:`.zhang2024`)
``Wu2018``     grease-lubricated tapered roller bearing (paper A; :mod:`.wu2018`)
=============  =====================================================================================
"""
from __future__ import annotations

import copy
import importlib
from dataclasses import dataclass
from types import ModuleType

from lubedyn.lubrication.errors import InputError, unknown_choice
from lubedyn.units import parse_quantity

SETS = {"Zhang2024": ".zhang2024.parameters", "Wu2018": ".wu2018.parameters"}


@dataclass(frozen=True)
class Parameter:
    """One value of a paper.

    ``value``: as a case file writes it (``"9.525 mm"``, ``14``, ``["270 deg"]``); ``dimension``: the
    quantity's dimension (:data:`lubedyn.units.DIMENSIONS`, ``"dimensionless"`` for plain numbers,
    ``"text"`` for a word, ``"angles"`` for a list of angles); ``source``: where in the paper
    (``"Table 4"``), or ``"assumed"``; ``note``: what was assumed, or how a printed value was read."""

    value: object
    dimension: str
    source: str
    note: str = ""

    def si(self) -> float:
        """The value in SI units (numbers as they are)."""
        if self.dimension in ("dimensionless", "text", "angles", "count"):
            return self.value
        return parse_quantity(self.value, self.dimension)


def parameter_set(name: str) -> ModuleType:
    """The module of the set ``name`` (one-line InputError naming the known sets otherwise)."""
    if name not in SETS:
        raise unknown_choice("parameters", name, SETS)
    return importlib.import_module(SETS[name], __name__)


def si(set_name: str, name: str):
    """The SI value of parameter ``name`` of the set ``set_name``."""
    values = parameter_set(set_name).VALUES
    if name not in values:
        raise unknown_choice(f"parameter of {set_name}", name, values)
    return values[name].si()


def printed(set_name: str, name: str, unit: str) -> float:
    """The number of parameter ``name`` as printed, which must be in ``unit`` (e.g. ``"rpm"``, ``"deg"``):
    for callers that convert it themselves (``math.radians``, rpm to rad/s)."""
    value = parameter_set(set_name).VALUES[name].value
    number, _, given = str(value).partition(" ")
    if given != unit:
        raise InputError(f"parameter {name} of {set_name} is {value!r}, not in {unit}")
    return float(number)


def _get(raw: dict, path: list[str]):
    node = raw
    for part in path:
        if not isinstance(node, dict) or part not in node:
            return _MISSING
        node = node[part]
    return node


_MISSING = object()


def apply_parameter_set(raw: dict) -> dict:
    """``raw`` with the values of its ``parameters`` set filled in where it does not give them.

    The ``parameters`` key is consumed: the resolved case lists every value explicitly (and stays a
    valid case file without the set).  A scene the set does not describe is an error that names
    the scenes it does."""
    name = raw.get("parameters")
    if name is None:
        return raw
    if not isinstance(name, str):
        raise InputError(f"parameters = {name!r} must be the name of a parameter set: one of "
                         f"{', '.join(map(repr, SETS))}")
    module = parameter_set(name)
    scene = raw.get("scene")
    if scene not in module.SCENES:
        raise InputError(f"parameters = {name!r} does not describe scene = {scene!r}; it gives values for "
                         f"scene = {', '.join(map(repr, module.SCENES))}")
    out = copy.deepcopy(raw)
    del out["parameters"]
    for key, pname in module.SCENES[scene].items():
        path = key.split(".")
        if _get(out, path) is not _MISSING:
            continue  # the case file (or an override) gives it
        node = out
        for part in path[:-1]:
            node = node.setdefault(part, {})
            if not isinstance(node, dict):
                raise InputError(f"{'.'.join(path[:-1])} must be a table to take parameters = {name!r}")
        node[path[-1]] = copy.deepcopy(module.VALUES[pname].value)
    return out


def assumed_values(case) -> dict:
    """The values of a validated ``case`` that its paper does not give: ``{case key: "value: reason"}`` for
    every key of the case's scene that its parameter set (``case._parameter_set``) marks ``source =
    "assumed"`` and whose value in the case is the set's (a value the case file or ``--set`` changed is
    the user's, not an assumption of the set).  Empty without a set."""
    import math

    name = getattr(case, "_parameter_set", None)
    if not name:
        return {}
    module = parameter_set(name)
    out = {}
    for key, pname in module.SCENES.get(case.scene, {}).items():
        p = module.VALUES[pname]
        if p.source != "assumed":
            continue
        value = case
        for part in key.split("."):
            value = getattr(value, part, None)
            if value is None:
                break
        given = p.si()
        if isinstance(value, (int, float)) and isinstance(given, (int, float)) and not isinstance(value, bool):
            same = math.isclose(float(value), float(given), rel_tol=1e-12, abs_tol=0.0)
        else:
            same = value == given
        if same:
            out[key] = f"{p.value}: {p.note}"
    return out

