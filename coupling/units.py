"""Quantities with units at the input boundary: ``"50 um"`` -> 5e-05 (m).

The one parser, :mod:`lubedyn.lubrication.laws.units` (on the ground floor, so that the films' Python
constructors take the same strings as the case files), under its public name.  Case files give a
quantity as a plain number, read as SI, or as a string ``"<number> <unit expression>"``
(``"50 um"``, ``"0.05 Pa s"``, ``"10000 rpm"``); conversion happens once, at the boundary.

>>> parse_quantity("50 um", "length")
5e-05
"""
from __future__ import annotations

from lubedyn.lubrication.laws.units import (COMMON_UNITS, DIMENSIONS, UnitError, dimension_name, parse_quantity,
                                            parse_units, quantity, si_fields, si_unit, unit_hint, written)

__all__ = ["COMMON_UNITS", "DIMENSIONS", "UnitError", "dimension_name", "parse_quantity", "parse_units", "quantity",
           "si_fields", "si_unit", "unit_hint", "written"]
