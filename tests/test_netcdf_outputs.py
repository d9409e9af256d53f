"""Self-describing outputs: a time series written as compressed netCDF (lubedyn.outputs.write_timeseries_netcdf)
reads back, with xarray alone and with lubedyn.outputs.read_timeseries, to the very arrays it was given (the
same as the .npz of the same columns), with units and provenance in its attributes; the case option that
chooses the format refuses an unknown value in one line."""
from __future__ import annotations

import json

import numpy as np
import pytest

from lubedyn import outputs
from lubedyn.config import CaseError, load_case

xr = pytest.importorskip("xarray")
pytest.importorskip("netCDF4")


def _columns(n=7):
    """Columns shaped as a cage-less run's: states of one ring, three balls, pairs labelled "0-1", a quantity
    only some balls have (stays a column of its own), integers and booleans."""
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 1e-3, n)
    cols = {"Inner ring x [m]": rng.normal(size=n) * 1e-6, "Rotor speed [rad/s]": 1047.2 - t * 10}
    for j in range(3):
        cols[f"Ball {j} x [m]"] = rng.normal(size=n)
        cols[f"Ball {j} Inner race load [N]"] = rng.normal(size=n) * 100
    for a, b in ((0, 1), (1, 2), (2, 0)):
        cols[f"Pair {a}-{b} plastic memory [m]"] = rng.normal(size=n) * 1e-9
    cols["Ball 0 probe [-]"] = rng.normal(size=n)  # only ball 0: not a body variable
    cols["Collisions [-]"] = np.arange(n)
    cols["Loaded zone [-]"] = np.arange(n) % 2 == 0
    return t, cols


def test_round_trip_through_xarray_and_read_timeseries(tmp_path):
    t, cols = _columns()
    meta = {"Case": "drop", "Scene": "dynamics", "Summary": {"Load [N]": 1.5, "Warnings": []}}
    path = outputs.write_timeseries_netcdf(tmp_path / "timeseries.nc", t, cols, meta, resolved="scene = 'x'\n")
    outputs.write_timeseries(tmp_path / "timeseries.npz", t, cols, meta)
    with xr.open_dataset(path) as ds:  # xarray alone, no lubedyn reader
        ds = ds.load()
    assert ds["Ball x"].dims == ("time", "ball") and list(ds["ball"].values) == [0, 1, 2]
    for j in range(3):
        assert np.array_equal(ds["Ball x"].values[:, j], cols[f"Ball {j} x [m]"])
    assert list(ds["pair"].values) == ["0-1", "1-2", "2-0"]
    assert np.array_equal(ds["Pair plastic memory"].sel(pair="1-2").values, cols["Pair 1-2 plastic memory [m]"])
    assert np.array_equal(ds["Ball 0 probe"].values, cols["Ball 0 probe [-]"])
    assert ds["Ball Inner race load"].attrs["units"] == "N" and ds["Rotor speed"].attrs["units"] == "rad/s"
    assert ds["time"].attrs["units"] == "s" and np.array_equal(ds["time"].values, t)
    assert all("units" in var.attrs for var in ds.data_vars.values())
    # compressed (zlib with the byte shuffle), provenance in the global attributes
    assert ds["Ball x"].encoding["zlib"] and ds["Ball x"].encoding["shuffle"]
    from lubedyn import __version__

    assert ds.attrs["Case"] == "drop" and ds.attrs["lubedyn version"] == __version__
    assert ds.attrs["case parameters (resolved TOML)"] == "scene = 'x'\n"
    assert ds.attrs["date_created"].endswith("Z") and json.loads(ds.attrs["Summary"])["Load [N]"] == 1.5
    # lubedyn's reader: the same columns, in the order written, as the .npz of the same data holds them
    back, meta_back = outputs.read_timeseries(path)
    npz, _ = outputs.read_timeseries(tmp_path / "timeseries.npz")
    assert list(back) == list(npz) == ["Time [s]", *cols]
    for name in npz:
        assert np.array_equal(back[name], npz[name]) and back[name].dtype == npz[name].dtype, name
    assert meta_back["Summary"] == meta["Summary"] and meta_back["Scene"] == "dynamics"


def test_timeseries_path_finds_either_file_and_says_when_there_is_none(tmp_path):
    t, cols = _columns()
    with pytest.raises(FileNotFoundError, match=r"no timeseries.nc or timeseries.npz"):
        outputs.timeseries_path(tmp_path)
    outputs.write_timeseries(tmp_path / "timeseries.npz", t, cols)
    assert outputs.timeseries_path(tmp_path).name == "timeseries.npz"
    outputs.write_timeseries_netcdf(tmp_path / "timeseries.nc", t, cols)
    assert outputs.timeseries_path(tmp_path).name == "timeseries.nc"


def test_a_file_that_is_not_a_lubedyn_time_series_is_refused(tmp_path):
    xr.Dataset({"a": ("x", np.arange(3.0))}).to_netcdf(tmp_path / "other.nc", engine=outputs.NETCDF_ENGINE)
    with pytest.raises(ValueError, match="not a lubedyn time series file"):
        outputs.read_timeseries(tmp_path / "other.nc")


@pytest.mark.parametrize("case", ["cageless_6206_10krpm_short", "trb_fig5_2400rpm"])
def test_the_format_option_defaults_to_netcdf_and_refuses_others_in_one_line(case):
    assert load_case(case, smoke=True).output.timeseries_format == "netcdf"
    assert load_case(case, smoke=True, overrides=["output.timeseries_format=npz"]).output.timeseries_format == "npz"
    with pytest.raises(CaseError) as err:
        load_case(case, smoke=True, overrides=["output.timeseries_format=hdf5"])
    text = str(err.value)
    assert "\n" not in text and "output.timeseries_format" in text and "'hdf5'" in text
    assert "netcdf" in text and "npz" in text
