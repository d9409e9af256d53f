"""Quantities with units at the input boundary: ``"50 um"`` -> 5e-05 (m).

Case files give a quantity either as a plain number, read as SI, or as a
string ``"<number> <unit expression>"``.  The expression is a product of unit
symbols with optional integer powers, separated by spaces or ``*``; ``/``
divides by the factor that follows it::

    "50 um"  "0.05 Pa s"  "1.85e-8 m^2/N"  "992 kg/m^3"  "10000 rpm"  "30 deg"

Dimensions are vectors over (length, mass, time, angle, temperature).  The
angle is kept as its own dimension so that an angular speed (``rpm``,
``rad/s``) is never confused with a frequency (``Hz``); its SI unit is the
radian.  Conversion happens once, here; everything past the boundary is SI.

The same strings are taken from Python: the case files' fields (``lubedyn.config``'s quantities) and the
constructors of the films' frozen SI dataclasses (gaps, viscosity and density laws:
:func:`si_fields` in their ``__post_init__``) go through :func:`parse_quantity`, so that
``JournalBearing(radius="25 mm", clearance="50 um")`` equals ``JournalBearing(0.025, 5e-05)``.  This module
lives on the ground floor (``lubedyn.lubrication.laws``, which both layers import); ``lubedyn.units`` is
its public name in the coupling layer.

>>> parse_quantity("50 um", "length")
5e-05
>>> parse_quantity("3000 rpm", "angular velocity")  # doctest: +ELLIPSIS
314.159...
"""
from __future__ import annotations

import math
import re

from ..errors import InputError, did_you_mean

# dimension exponents: (length, mass, time, angle, temperature)
_DIMS = ("m", "kg", "s", "rad", "K")

DIMENSIONS: dict[str, tuple[int, ...]] = {
    "dimensionless": (0, 0, 0, 0, 0),
    "length": (1, 0, 0, 0, 0),
    "area": (2, 0, 0, 0, 0),
    "mass": (0, 1, 0, 0, 0),
    "time": (0, 0, 1, 0, 0),
    "angle": (0, 0, 0, 1, 0),
    "temperature": (0, 0, 0, 0, 1),
    "velocity": (1, 0, -1, 0, 0),
    "inverse velocity": (-1, 0, 1, 0, 0),
    "acceleration": (1, 0, -2, 0, 0),
    "angular velocity": (0, 0, -1, 1, 0),
    "frequency": (0, 0, -1, 0, 0),
    "force": (1, 1, -2, 0, 0),
    "force per length": (0, 1, -2, 0, 0),
    "pressure": (-1, 1, -2, 0, 0),
    "inverse pressure": (1, -1, 2, 0, 0),
    "dynamic viscosity": (-1, 1, -1, 0, 0),
    "kinematic viscosity": (2, 0, -1, 0, 0),
    "density": (-3, 1, 0, 0, 0),
    "energy": (2, 1, -2, 0, 0),
    "power": (2, 1, -3, 0, 0),
    "volume flow": (3, 0, -1, 0, 0),
    "stiffness": (0, 1, -2, 0, 0),
    "damping": (0, 1, -1, 0, 0),
    "moment of inertia": (2, 1, 0, 0, 0),
}
_NAMES = {v: k for k, v in reversed(list(DIMENSIONS.items()))}
_NAMES[(0, 1, -2, 0, 0)] = "stiffness (force per length)"

_PI = math.pi
# symbol -> (factor to SI, dimension)
_UNITS: dict[str, tuple[float, tuple[int, ...]]] = {
    "1": (1.0, DIMENSIONS["dimensionless"]),
    "%": (1e-2, DIMENSIONS["dimensionless"]),
    "m": (1.0, DIMENSIONS["length"]),
    "in": (0.0254, DIMENSIONS["length"]),
    "g": (1e-3, DIMENSIONS["mass"]),
    "t": (1e3, DIMENSIONS["mass"]),
    "s": (1.0, DIMENSIONS["time"]),
    "min": (60.0, DIMENSIONS["time"]),
    "h": (3600.0, DIMENSIONS["time"]),
    "rad": (1.0, DIMENSIONS["angle"]),
    "deg": (_PI / 180.0, DIMENSIONS["angle"]),
    "°": (_PI / 180.0, DIMENSIONS["angle"]),
    "rev": (2.0 * _PI, DIMENSIONS["angle"]),
    "rpm": (2.0 * _PI / 60.0, DIMENSIONS["angular velocity"]),
    "rps": (2.0 * _PI, DIMENSIONS["angular velocity"]),
    "Hz": (1.0, DIMENSIONS["frequency"]),
    "K": (1.0, DIMENSIONS["temperature"]),
    "N": (1.0, DIMENSIONS["force"]),
    "Pa": (1.0, DIMENSIONS["pressure"]),
    "bar": (1e5, DIMENSIONS["pressure"]),
    "psi": (6894.757293168361, DIMENSIONS["pressure"]),
    "P": (0.1, DIMENSIONS["dynamic viscosity"]),  # poise; cP via the prefix
    "St": (1e-4, DIMENSIONS["kinematic viscosity"]),  # stokes; cSt (= mm^2/s) via the prefix
    "J": (1.0, DIMENSIONS["energy"]),
    "W": (1.0, DIMENSIONS["power"]),
    "L": (1e-3, (3, 0, 0, 0, 0)),
}
_PREFIXES = {"p": 1e-12, "n": 1e-9, "u": 1e-6, "µ": 1e-6, "μ": 1e-6, "m": 1e-3, "c": 1e-2,
             "d": 1e-1, "k": 1e3, "M": 1e6, "G": 1e9}
_PREFIXABLE = {"m", "g", "s", "N", "Pa", "bar", "P", "St", "J", "W", "Hz", "rad", "L"}
_SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻", "0123456789-")

_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_FACTOR = re.compile(r"^([^\s^*/()0-9.+-][^\s^*/()]*?)(?:(?:\^|\*\*)?([-+]?\d+))?$")


class UnitError(ValueError):
    """A string that is not ``<number> <units>`` or has the wrong dimension."""


def _unit(symbol: str) -> tuple[float, tuple[int, ...]]:
    if symbol in _UNITS:
        return _UNITS[symbol]
    if len(symbol) > 1 and symbol[0] in _PREFIXES and symbol[1:] in _PREFIXABLE:
        factor, dim = _UNITS[symbol[1:]]
        return _PREFIXES[symbol[0]] * factor, dim
    known = sorted(set(_UNITS) | {p + u for p in "numkMG" for u in _PREFIXABLE})
    hint = did_you_mean(symbol, known)
    raise UnitError(f"has an unknown unit {symbol!r}{hint}")


def parse_units(expression: str) -> tuple[float, tuple[int, ...]]:
    """Factor to SI and dimension vector of a unit expression, e.g. ``"N s/m"``."""
    expr = expression.translate(_SUPERSCRIPTS).replace("**", "^").replace("·", " ").replace("*", " ")
    expr = re.sub(r"\s*\^\s*", "^", expr.strip())
    expr = re.sub(r"\s*/\s*", " / ", expr)
    factor, dim = 1.0, [0] * len(_DIMS)
    divide = False
    tokens = expr.split()
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if tok == "/":
            if divide or i == len(tokens) - 1:
                raise UnitError(f"has a malformed unit expression {expression!r}")
            divide = True
            i += 1
            continue
        if tok == "1":  # "1/Pa"
            i += 1
            continue
        power = 1
        match = _FACTOR.match(tok)
        if not match:
            raise UnitError(f"has a malformed unit expression {expression!r}")
        symbol, exp = match.group(1), match.group(2)
        if exp is not None:
            power *= int(exp)
        f, d = _unit(symbol)
        sign = -1 if divide else 1
        factor *= f ** (sign * power)
        dim = [a + sign * power * b for a, b in zip(dim, d)]
        divide = False
        i += 1
    return factor, tuple(dim)


def dimension_name(dim: tuple[int, ...]) -> str:
    """``"pressure"`` for (-1, 1, -2, 0, 0); an SI unit string when unnamed."""
    if dim in _NAMES:
        return _NAMES[dim]
    parts = [f"{u}^{p}" if p != 1 else u for u, p in zip(_DIMS, dim) if p]
    return " ".join(parts) if parts else "dimensionless"


def si_unit(dimension: str) -> str:
    """The SI unit symbol of a named dimension (``"pressure"`` -> ``"Pa"``)."""
    special = {"dimensionless": "-", "pressure": "Pa", "force": "N", "dynamic viscosity": "Pa s",
               "kinematic viscosity": "m^2/s",
               "inverse pressure": "1/Pa", "velocity": "m/s", "angular velocity": "rad/s",
               "frequency": "Hz", "density": "kg/m^3", "energy": "J", "power": "W",
               "volume flow": "m^3/s", "stiffness": "N/m", "damping": "N s/m",
               "force per length": "N/m", "area": "m^2", "acceleration": "m/s^2",
               "moment of inertia": "kg m^2"}
    if dimension in special:
        return special[dimension]
    dim = DIMENSIONS[dimension]
    return " ".join(f"{u}^{p}" if p != 1 else u for u, p in zip(_DIMS, dim) if p)


def parse_quantity(value, dimension: str) -> float:
    """``value`` (number in SI, or ``"<number> <units>"``) as a float in SI.

    Raises :class:`UnitError` with a message that completes the sentence
    ``"<key> = <value> ..."``, e.g. ``has units of pressure, expected length``.
    """
    expected = DIMENSIONS[dimension]
    if isinstance(value, bool) or value is None:
        raise UnitError(f"is not a quantity; expected {dimension} as a number in {si_unit(dimension)} or a string with units")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise UnitError(f"is not a quantity; expected {dimension} as a number in {si_unit(dimension)} or a string with units")
    match = _NUMBER.match(value)
    if not match:
        raise UnitError(f"is not '<number> <units>'; expected {dimension}, e.g. a number in {si_unit(dimension)}")
    number, units = float(match.group(1)), match.group(2)
    if not units:
        return number
    factor, dim = parse_units(units)
    if dim != expected:
        raise UnitError(f"has units of {dimension_name(dim)}, expected {dimension} ({si_unit(dimension)})")
    # 15 significant digits: "50 um" -> 5e-05, not 4.9999999999999996e-05
    return float(f"{number * factor:.15g}")


# ---------------------------------------------------------------------------
# unit hints: the value a user probably meant when a number is out of scale

# the units a quantity is commonly written in, by dimension: the candidates of a unit hint
COMMON_UNITS: dict[str, tuple[str, ...]] = {
    "length": ("m", "mm", "um", "nm"),
    "pressure": ("Pa", "kPa", "MPa", "GPa"),
    "force": ("N", "kN"),
    "force per length": ("N/m", "kN/m"),
    "velocity": ("m/s", "mm/s"),
}


def written(value, dimension: str) -> tuple[float, float] | None:
    """(number, factor to SI of its units) of a quantity as the user wrote it, or None when it is no
    quantity of ``dimension``: a bare number is SI (factor 1).

    >>> written(50, "length"), written("50 um", "length"), written("50 Pa", "length")
    ((50.0, 1.0), (50.0, 1e-06), None)
    """
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return float(value), 1.0
    if not isinstance(value, str):
        return None
    match = _NUMBER.match(value)
    if not match:
        return None
    if not match.group(2):
        return float(match.group(1)), 1.0
    try:
        factor, dim = parse_units(match.group(2))
    except UnitError:
        return None
    return (float(match.group(1)), factor) if dim == DIMENSIONS[dimension] else None


def unit_hint(value, dimension: str, passes) -> str | None:
    """``value``'s number (as written) in the common unit nearest to the one written (in powers of ten)
    whose SI value satisfies ``passes(si)``: the value the user probably meant; None when no common
    unit does.  A bare 50 for a clearance that must be below 2.5 mm:

    >>> unit_hint(50, "length", lambda si: si <= 2.5e-3)
    '50 um'
    >>> unit_hint("50 um", "length", lambda si: si >= 1e-2)
    '50 mm'
    """
    form = written(value, dimension)
    if form is None:
        return None
    number, factor = form
    candidates = []
    for unit in COMMON_UNITS.get(dimension, ()):
        f = parse_units(unit)[0]
        if not math.isclose(f, factor, rel_tol=1e-9):
            candidates.append((abs(math.log10(f / factor)), unit, f))
    for _, unit, f in sorted(candidates):
        if passes(float(f"{number * f:.15g}")):
            return f"{number:g} {unit}"
    return None


def quantity(value, dimension: str, key: str) -> float:
    """``value`` (a number in SI, or ``"<number> <units>"`` of ``dimension``) as an SI float; anything else
    an :class:`~lubedyn.lubrication.errors.InputError` of one line naming ``key``, the value and what is
    allowed.

    >>> quantity("50 um", "length", "JournalBearing.clearance")
    5e-05
    >>> quantity("50 Pa", "length", "JournalBearing.clearance")
    Traceback (most recent call last):
    ...
    lubedyn.lubrication.errors.InputError: JournalBearing.clearance = '50 Pa' has units of pressure, expected length (m)
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value  # numbers pass as they are (a numpy float stays one)
    try:
        return parse_quantity(value, dimension)
    except UnitError as exc:
        raise InputError(f"{key} = {value!r} {exc}") from None


def si_fields(obj, **dimensions: str) -> None:
    """In a frozen dataclass's ``__post_init__``: each field named in ``dimensions`` (field -> dimension)
    given as a string with units replaced by its SI float (:func:`quantity`, errors named
    ``ClassName.field``); numbers and None are left as they are."""
    for name, dimension in dimensions.items():
        value = getattr(obj, name)
        if value is not None:
            object.__setattr__(obj, name, quantity(value, dimension, f"{type(obj).__name__}.{name}"))
