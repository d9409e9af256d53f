"""A study's table from Python (StudyResult.to_xarray, lubedyn.scenes.study.study_dataset) and as netCDF
(study.nc): the outputs over the study's axes and members, units in the attributes, the same numbers as
study.csv; checked on the inclined slider at smoke size (a film linear in the runner speed, whose load at
5 m/s is the closed form of cases/inclined_slider.toml)."""
from __future__ import annotations

import csv
import io
import math

import numpy as np
import pytest

from lubedyn.scenes.study import read_study, run_study

xr = pytest.importorskip("xarray")
LOAD = "Load per unit width [N/m]"


def _study(tmp_path, axes: str, study: str = ""):
    path = tmp_path / "study.toml"
    path.write_text(f'base = "inclined_slider"\n[axes]\n{axes}\n[study]\nskip_outputs = true\n'
                    f'outputs = ["{LOAD}", "Scene"]\n{study}\n')
    return run_study(read_study(path), path, tmp_path / "out", smoke=True, workers=1)


def test_a_grid_study_with_members_is_axes_by_member(tmp_path):
    res = _study(tmp_path, '"motion.velocity_lower" = ["2 m/s", "5 m/s"]\n"limits.memory" = ["40 GiB", "1 KiB"]',
                 "members = 2\nmember_key = 'mesh.refinements'")
    ds = res.to_xarray()
    assert ds["Load per unit width"].dims == ("motion.velocity_lower", "limits.memory", "member")
    speed = ds["motion.velocity_lower"]
    assert list(speed.values) == [2.0, 5.0] and speed.attrs["units"] == "m/s"
    assert ds["limits.memory"].attrs["given"] == '["40 GiB", "1 KiB"]'
    load = ds["Load per unit width"]
    assert load.attrs["units"] == "N/m" and load.attrs["column"] == LOAD
    ok = load.sel({"limits.memory": ds["limits.memory"].values[0]})
    # linear in the speed, the closed form at 5 m/s, the members (mesh.refinements: unused here) equal
    assert float(ok.sel({"motion.velocity_lower": 5.0, "member": 0})) == pytest.approx(63.55e3, rel=1e-3)
    assert np.allclose(ok.values / speed.values[:, None], float(ok[1, 0]) / 5.0, rtol=1e-12)
    assert np.array_equal(ok.values[:, 0], ok.values[:, 1])
    # a run refused by its memory limit: NaN, status "failed"; a string output stays a string
    failed = load.sel({"limits.memory": ds["limits.memory"].values[1]})
    assert np.isnan(failed.values).all() and set(ds["status"].values[:, 1].ravel()) == {"failed"}
    assert set(ds["status"].values[:, 0].ravel()) == {"ok"} and ds["Scene"].values[0, 0, 0] == "film"
    # study.csv holds the same numbers, row by row (points in order, members within a point)
    rows = list(csv.DictReader(io.StringIO((res.out / "study.csv").read_text())))
    flat = load.values.reshape(-1)
    for row, value in zip(rows, flat):
        assert (row[LOAD] == "" and math.isnan(value)) or float(row[LOAD]) == value
    # study.nc: the same Dataset, read by xarray alone
    with xr.open_dataset(res.out / "study.nc") as disk:
        disk = disk.load()
    assert np.array_equal(disk["Load per unit width"].values, load.values, equal_nan=True)
    assert disk["Load per unit width"].attrs["units"] == "N/m" and disk.attrs["format"] == "lubedyn study"
    assert list(disk["status"].values.ravel()) == list(ds["status"].values.ravel())
    assert disk["Load per unit width"].encoding["zlib"]


def test_a_zipped_study_is_points_with_the_axes_as_coordinates(tmp_path):
    res = _study(tmp_path, '"motion.velocity_lower" = ["2 m/s", "8 m/s"]\n"mesh.nx" = [10, 12]',
                 'combine = "zip"\ntables = []')
    ds = res.to_xarray()
    assert ds["Load per unit width"].dims == ("point",)
    assert list(ds["motion.velocity_lower"].values) == [2.0, 8.0] and list(ds["mesh.nx"].values) == [10.0, 12.0]
    assert ds["motion.velocity_lower"].dims == ("point",) and "units" not in ds["mesh.nx"].attrs
    load = ds["Load per unit width"].values
    assert load[1] / load[0] == pytest.approx(4.0, rel=2e-3)  # linear in the speed (meshes 10 and 12 cells)
    assert not (res.out / "study.nc").exists()  # tables = []: study.csv and study.json only


def test_an_unknown_table_format_is_one_line(tmp_path):
    from lubedyn.scenes.study import StudyError

    path = tmp_path / "study.toml"
    path.write_text(f'base = "inclined_slider"\n[axes]\n"mesh.nx" = [10]\n[study]\noutputs = ["{LOAD}"]\n'
                    'tables = ["hdf5"]\n')
    with pytest.raises(StudyError) as err:
        read_study(path)
    assert "\n" not in str(err.value) and "study.tables" in str(err.value) and "'netcdf'" in str(err.value)
