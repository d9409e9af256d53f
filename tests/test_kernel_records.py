"""The bearings' parameter records (lubedyn.dynamics.tapered.layout, lubedyn.dynamics.cageless.layout): the
kernels read their parameters by name from numba structured records built by ``parameter_record``.

Independent references: the kernels' source (every ``P.<name>`` read there must be a field of the record,
and every field must be read by a kernel: no unnamed slot, no dead field), and the record builder's
refusal of a missing or a misspelt field, which names it."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from lubedyn.dynamics.cageless import layout as cage_less
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.tapered import layout as tapered

DYNAMICS = Path(tapered.__file__).resolve().parents[1]
LAYOUTS = {"tapered": (tapered, ("tapered/kernels.py",)),
           "cageless": (cage_less, ("cageless/kernels.py",))}


def _values(layout):
    return {name: 1.0 for name in layout.PARAMETER_DTYPE.names}


@pytest.mark.parametrize("bearing", sorted(LAYOUTS))
def test_a_missing_or_misspelt_field_is_refused_by_name(bearing):
    layout, _ = LAYOUTS[bearing]
    values = _values(layout)
    record = layout.parameter_record(values)
    assert record[0].alpha == 1.0 and record.shape == (1,)
    missing = dict(values)
    del missing["alpha"]
    with pytest.raises(DynamicsInputError, match=r"misses the field 'alpha'") as err:
        layout.parameter_record(missing)
    assert err.value.key == "alpha"
    with pytest.raises(DynamicsInputError, match=r"'alpah' is not a field") as err:
        layout.parameter_record(values | {"alpah": 0.3})
    assert err.value.key == "alpah"


@pytest.mark.parametrize("bearing", sorted(LAYOUTS))
def test_the_kernels_read_named_fields_only_and_every_field(bearing):
    """Every parameter the kernels read is a field of the record (by name: ``P.kw``), no parameter is read
    by position (``P[k]``; ``args.P[0]`` is the record array's one row), and every field of the record is read by a kernel."""
    layout, files = LAYOUTS[bearing]
    source = "".join((DYNAMICS / f).read_text() for f in files)
    read = set(re.findall(r"\bP\.([a-z_][a-z0-9_]*)", source))
    fields = set(layout.PARAMETER_DTYPE.names)
    assert read - fields == set()
    assert fields - read == set()
    assert not re.search(r"\bP\[(?!0\])", source)   # P[0]: the record array's one row
    assert len(fields) == len(layout.PARAMETER_DTYPE.names)    # no field twice
