"""Results by name (lubedyn.results): a bearing run's time series read as ``res[name]`` with the names of
``timeseries.npz``, their units, the run's warnings, and ``to_xarray()``; each read is checked against a
value the case states or the physics fixes, not against the reader itself."""
import math

import numpy as np
import pytest

import lubedyn
from lubedyn.results import split_unit


@pytest.fixture(scope="module")
def tapered():
    case = lubedyn.load_case("trb_fig5_2400rpm", smoke=True)
    return case, lubedyn.run(case)


def test_a_tapered_run_reads_its_series_by_name(tapered):
    case, res = tapered
    t = res["Time [s]"]
    assert np.allclose(np.diff(t), case.integrator.sample_interval, rtol=1e-9)
    assert t[-1] == pytest.approx(case.integrator.duration, rel=1e-9)
    # the cage turns at its ideal (epicyclic) speed within the rollers' slip, 2,400 rpm on the cone
    ideal = res.summary["Ideal cage speed [rpm]"] * math.pi / 30.0
    cage = res["Cage speed [rad/s]"]
    assert cage.shape == t.shape and np.all(np.abs(cage / ideal - 1.0) < 0.03)
    assert res.units("Cage speed [rad/s]") == "rad/s" and "Cage speed [rad/s]" in res.names
    assert res.warnings == []
    with pytest.raises(KeyError, match=r"did you mean 'Cage speed \[rad/s\]'"):
        res["Cage sped [rad/s]"]


def test_to_xarray_names_units_and_identity(tapered):
    pytest.importorskip("xarray")
    _, res = tapered
    ds = res.to_xarray()
    assert ds.sizes["time"] == len(res.t)
    var = ds["Cage speed"]
    assert var.attrs == {"units": "rad/s", "long_name": "Cage speed", "column": "Cage speed [rad/s]"}
    assert np.array_equal(var.values, res["Cage speed [rad/s]"])
    # the rollers' columns along a dimension of their own: one variable per quantity, the case's 17 rollers
    tilt = ds["Roller tilt"]
    assert tilt.dims == ("time", "roller") and tilt.attrs["units"] == "rad"
    assert list(ds["roller"].values) == list(range(17))
    for j in (0, 5, 16):
        assert np.array_equal(tilt.values[:, j], res[f"Roller {j} tilt [rad]"])
    assert ds["time"].attrs["units"] == "s" and ds.attrs["Scene"] == "tapered"
    assert ds.attrs["lubedyn version"] == lubedyn.__version__


def test_a_cageless_run_starts_at_the_cases_rotor_speed():
    case = lubedyn.load_case("cageless_6206_10krpm_short", smoke=True)
    res = lubedyn.run(case)
    # 10,000 rpm before the drop, as the case states
    assert res["Rotor speed [rad/s]"][0] == pytest.approx(10000 * math.pi / 30.0, rel=1e-9)
    assert res["Inner ring speed [rad/s]"].shape == res.t.shape


def test_split_unit():
    assert split_unit("Ball 0 Inner sliding speed [m/s]") == ("Ball 0 Inner sliding speed", "m/s")
    assert split_unit("Loaded zone [-]") == ("Loaded zone", "-")
    assert split_unit("Phase") == ("Phase", "")
