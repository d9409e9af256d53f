"""Frozen groups of a bearing model's data, one per case-file table.

A bearing model (:class:`lubedyn.dynamics.cageless.CagelessBearing`, and the next bearings) holds its data
as a few frozen dataclasses, each the SI twin of one table of a dynamics case file
(``[bearing]``, ``[operating]``, ``[model]``, ``[films]``, ``[slots]``): the case's tables become
groups one to one (:meth:`Group.build`), and each group checks its own values.  A group's
error names the case key (``"operating.radial_load = -1 ..."``) and carries it as
:attr:`~lubedyn.dynamics.errors.DynamicsInputError.key`, so a message reads the same from Python and from a
case file and nothing has to translate it.
"""
from __future__ import annotations

import math

import numpy as np
from dataclasses import dataclass, fields, replace
from typing import Any, ClassVar, Mapping

from lubedyn.lubrication.errors import did_you_mean

from .errors import DynamicsInputError


def fail(key: str, value: Any, rule: str) -> DynamicsInputError:
    """The one-line error ``"<key> = <value> <rule>"`` carrying ``key``."""
    return DynamicsInputError(f"{key} = {value!r} {rule}", key=key)


@dataclass(frozen=True, kw_only=True)
class Group:
    """Base of the frozen groups: :attr:`TABLE` is the case table the group mirrors."""

    TABLE: ClassVar[str] = ""

    def key(self, name: str) -> str:
        """The case key of field ``name`` (``"films.viscosity"``)."""
        return f"{self.TABLE}.{name}"

    def fail(self, name: str, rule: str, value: Any = None) -> DynamicsInputError:
        return fail(self.key(name), getattr(self, name) if value is None else value, rule)

    # checks used by the groups' __post_init__ ------------------------------------------------------
    def positive(self, *names: str) -> None:
        for name in names:
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0.0):
                raise self.fail(name, "must be > 0")

    def non_negative(self, *names: str) -> None:
        for name in names:
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and not isinstance(v, bool) and v >= 0.0 and math.isfinite(v)):
                raise self.fail(name, "must be a finite number >= 0")

    def choice(self, name: str, allowed) -> None:
        v = getattr(self, name)
        if v not in allowed:
            raise self.fail(name, f"is not allowed; choose one of {', '.join(map(repr, allowed))}"
                                  f"{did_you_mean(v, allowed, n=2)}")

    # construction -------------------------------------------------------------------------------
    @classmethod
    def names(cls) -> tuple[str, ...]:
        return tuple(f.name for f in fields(cls))

    @classmethod
    def _known(cls, names) -> None:
        """An unknown field name is a one-line error naming the case key, with "did you mean"."""
        allowed = cls.names()
        for name in names:
            if name not in allowed:
                raise DynamicsInputError(f"{cls.TABLE}.{name} is not a key of [{cls.TABLE}]"
                                         f"{did_you_mean(name, allowed, n=2)}", key=f"{cls.TABLE}.{name}")

    @classmethod
    def build(cls, values: Mapping[str, Any]):
        """The group from a mapping of its fields (a case table's, by name)."""
        cls._known(values)
        return cls(**values)

    def updated(self, changes: Mapping[str, Any] | "Group"):
        """A copy with ``changes`` (a mapping of fields, or a whole group of this type), checked again."""
        if isinstance(changes, Group):
            if type(changes) is not type(self):
                raise DynamicsInputError(f"{self.TABLE}: a {type(self).__name__} is needed, not "
                                         f"{type(changes).__name__}", key=self.TABLE)
            return changes
        self._known(changes)
        return replace(self, **changes)


def record_row(dtype, values: Mapping[str, float], what: str, fields_doc: Mapping[str, str], where: str):
    """A one-row record array of ``dtype`` filled from ``values`` {field: number}, the form the bearings'
    kernels take their parameters in (read by name, ``P = args.P[0]``: numba takes an array from Python at
    the cost of any array, a record scalar costs ten times more).  Every field of ``dtype`` and no other,
    else a :class:`DynamicsInputError` naming the field (a misspelt or forgotten parameter is not left at
    0); ``what`` names the record ("the tapered bearing's parameter record"), ``where`` the module listing
    its fields, ``fields_doc`` {field: description}."""
    names = dtype.names
    for name in values:
        if name not in names:
            raise DynamicsInputError(f"{name!r} is not a field of {what}; the fields are {where}", key=name)
    for name in names:
        if name not in values:
            raise DynamicsInputError(f"{what} misses the field {name!r} ({fields_doc[name]})", key=name)
    record = np.zeros(1, dtype=dtype).view(np.recarray)
    for name in names:
        record[name] = values[name]
    return record
