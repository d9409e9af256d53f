"""Reading a run's outputs (numpy, pyvista, ParaView)
==================================================

Reading a run's outputs: summary.json, the time series (netCDF: timeseries.nc, with xarray and with
lubedyn.outputs.read_timeseries) and the VTK fields, with numpy and pyvista.  Runs the smoke-size main job (paper B's rotor drop) into a temporary folder first, through
the same entry point as ``lubedyn run``.

ParaView: open ``bearing.pvd`` (the time series of the balls and rings), press Apply, colour by
"Ball-ball normal force [N]" and play; ``File > Save State`` keeps the view.  The static scene's
``bearing.vtu`` (paper A, ``lubedyn run cases/trb_static_radial.toml``) opens the same way.
"""
import os
import json
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv
import xarray as xr

from lubedyn import cli
from lubedyn.config import CASES_DIR
from lubedyn.outputs import read_timeseries

OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes


def main():
    out = Path(tempfile.mkdtemp()) / "drop"
    code = cli.main(["run", str(CASES_DIR / "cageless_6206_10krpm_short.toml"), "--smoke", "--out", str(out)])
    if code != 0:
        raise SystemExit(code)
    summary = json.loads((out / "summary.json").read_text())          # every scalar, names with units
    columns, meta = read_timeseries(out / "timeseries.nc")             # "Time [s]" and one array per column
    t = columns["Time [s]"]
    with xr.open_dataset(out / "timeseries.nc") as ds:                # the same file in xarray: units in attrs
        rotor = ds["Rotor speed"]
        rotor_units, rotor_xr = rotor.attrs["units"], rotor.values.copy()
    frames = pv.get_reader(str(out / "bearing.pvd"))                   # the ParaView collection
    frames.set_active_time_value(frames.time_values[-1])
    last = frames.read()
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.plot(t * 1e3, columns["Inner ring speed [rad/s]"], label="inner ring")
    a.plot(t * 1e3, columns["Rotor speed [rad/s]"], label="rotor")
    a.set_xlabel("time [ms]")
    a.set_ylabel("speed [rad/s]")
    a.legend()
    b.plot(t * 1e3, columns["Ball 0 z [m]"] * 1e6)
    b.set_xlabel("time [ms]")
    b.set_ylabel("ball 0 axial position [um]")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "read_outputs.png", dpi=100)
    return {"Simulated time [s]": summary["Simulated time [s]"], "samples": t.size,
            "frames": len(frames.time_values), "blocks in the last frame": last.n_blocks if hasattr(last, "n_blocks") else 1,
            "last sample time [s]": float(t[-1]),
            "rotor speed, xarray = read_timeseries": bool(np.array_equal(rotor_xr, columns["Rotor speed [rad/s]"])),
            "rotor speed units (xarray)": rotor_units}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<26} {v}")
