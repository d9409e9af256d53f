"""The bearings' parameter records (lubedyn.dynamics.tapered.layout, lubedyn.dynamics.cageless.layout): the
kernels read their parameters by name from numba structured records built by ``parameter_record``; the
ball-ball collision law's parameters likewise (lubedyn.lubrication.laws.collision.BALL_BALL_DTYPE, built by
``ball_ball_parameters``, read as ``p.hcut`` by the laws, the contact kernels and the cage-less rhs).

Independent references: the kernels' source (every ``P.<name>`` read there must be a field of the record,
and every field must be read by a kernel: no unnamed slot, no dead field), and the record builder's
refusal of a missing or a misspelt field, which names it."""
from __future__ import annotations

import inspect
import math
import re
from pathlib import Path

import numpy as np
import pytest

from lubedyn.dynamics.cageless import layout as cage_less
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics import contacts
from lubedyn.dynamics.tapered import layout as tapered
from lubedyn.lubrication.laws import collision

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


def _kernel_sources(module):
    """The source of every numba kernel (a dispatcher with ``py_func``) defined in ``module``."""
    return [inspect.getsource(obj.py_func) for obj in vars(module).values()
            if hasattr(obj, "py_func") and obj.py_func.__module__ == module.__name__]


def test_the_collision_laws_read_named_fields_only_and_every_field():
    """Every ball-ball parameter a kernel reads (the laws' ``p.hr``, the contact kernels' ``p.sqf``, the
    cage-less rhs's ``bbp.hcut``) is a field of the collision record, every field is read by a kernel, no
    kernel indexes the parameters (``p[k]``; ``args.bbp[0]`` is the record array's one row) and no index
    constant is left (``BB_*``)."""
    laws = _kernel_sources(collision) + _kernel_sources(contacts)
    assert len(laws) >= 10
    rhs = (DYNAMICS / "cageless" / "kernels.py").read_text()
    read = set()
    for source in laws:
        read |= set(re.findall(r"\bp\.([a-z_][a-z0-9_]*)", source))
        assert not re.search(r"\bp\[", source)
    read |= set(re.findall(r"\bbbp\.([a-z_][a-z0-9_]*)", rhs))
    assert not re.search(r"\bbbp\[(?!0\])", rhs)   # args.bbp[0]: the record array's one row
    assert "args.bbp[0]" in rhs
    fields = set(collision.BALL_BALL_DTYPE.names)
    assert read - fields == set()
    assert fields - read == set()
    for path in (Path(collision.__file__), Path(contacts.__file__), DYNAMICS / "cageless" / "kernels.py",
                 DYNAMICS / "cageless" / "invariants.py", DYNAMICS / "cageless" / "model.py"):
        assert not re.search(r"\bBB_[A-Z]", path.read_text()), path


def test_the_collision_record_holds_the_keywords_and_the_map_ends_by_name():
    """``ball_ball_parameters`` fills the named fields from its keywords (R_eff = R/2, C0 = 6 pi eta R_eff^2,
    the friction law's code) with the map's ends NaN; ``with_map_ends`` fills them (exp of log axes) in a
    copy; ``ball_ball_row`` is a one-row copy, the kernels' form."""
    p = collision.ball_ball_parameters(ball_radius=2e-3, e_star=1.1e11, viscosity=0.04, cutoff_gap=3e-4,
                                       mu_film=0.05, mu_boundary=0.11, memory_time=2e-4, friction_law="paper")
    assert p.r == 1e-3 and p.estar == 1.1e11 and p.eta == 0.04 and p.hcut == 3e-4 and p.tau == 2e-4
    assert p.c0 == pytest.approx(6 * math.pi * 0.04 * 1e-6, rel=1e-15) and (p.muf, p.mub) == (0.05, 0.11)
    assert p.flaw == 1 and p.py == math.inf
    assert all(math.isnan(p[name]) for name in ("map_h0", "map_htop", "map_x1lo", "map_x1top"))
    opts = np.zeros(contacts.MO_SIZE, dtype=np.int64)
    opts[contacts.MO_LOG0] = 1
    q = contacts.with_map_ends(p, np.log([1e-9, 5e-5]), np.array([0.1, 2.0]), opts)
    assert (q.map_h0, q.map_htop, q.map_x1lo, q.map_x1top) == pytest.approx((1e-9, 5e-5, 0.1, 2.0), rel=1e-14)
    assert math.isnan(p.map_h0) and q.r == p.r
    row = collision.ball_ball_row(q)
    assert row.shape == (1,) and row.dtype == collision.BALL_BALL_DTYPE and row[0].map_htop == q.map_htop
    row[0].hcut = 1.0
    assert q.hcut == 3e-4
