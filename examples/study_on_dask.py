"""A study on a Dask cluster, its table as an xarray Dataset
=========================================================

The bundled slider study's three runner speeds (the inclined slider pad, at smoke size) run on a local
Dask cluster of two worker threads, the recipe of docs/study_dask.md: ``run_study`` takes the cluster as
``scheduler``; on many machines, pass the scheduler's address instead (``lubedyn study ... --scheduler
tcp://host:8786`` from the shell).  The table comes back as an xarray Dataset (``result.to_xarray()``) with
the runner speed as a coordinate and units in the attributes, the same Dataset as ``study.nc``.

Independent check: the isoviscous slider's load per unit width is linear in the runner speed (Reynolds'
equation is linear in it), so load / speed is the same at every point.  Needs the ``dask`` extra.
"""
import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr
from distributed import LocalCluster

from lubedyn.config import CASES_DIR
from lubedyn.scenes.study import read_study, run_study

OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes

# %%
# The study file: one axis, three speeds, one output.


def main():
    folder = Path(tempfile.mkdtemp())
    path = folder / "slider_speeds.toml"
    path.write_text(f'''
description = "inclined slider pad against the runner speed"
base = "{(CASES_DIR / "inclined_slider.toml").as_posix()}"
[axes]
"motion.velocity_lower" = ["2 m/s", "5 m/s", "8 m/s"]
[study]
skip_outputs = true
outputs = ["Load per unit width [N/m]"]
''')
    # %%
    # Two worker threads in this process; the dashboard on any free port.
    with LocalCluster(n_workers=2, processes=False, threads_per_worker=1, dashboard_address=":0") as cluster:
        result = run_study(read_study(path), path, folder / "out", smoke=True, scheduler=cluster)
    # %%
    # The table as a Dataset, and the file on disk.
    table = result.to_xarray()
    load = table["Load per unit width"]
    speed = table["motion.velocity_lower"]
    with xr.open_dataset(folder / "out" / "study.nc") as on_disk:
        same = bool(np.array_equal(on_disk["Load per unit width"].values, load.values))
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(speed.values, load.values, "o-")
    ax.set_xlabel(f"runner speed [{speed.attrs['units']}]")
    ax.set_ylabel(f"load per unit width [{load.attrs['units']}]")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "study_on_dask.png", dpi=100)
    return {"backend": result.backend, "runs": result.total, "failed": len(result.failed),
            "load / speed [N s/m^2]": (load.values / speed.values).tolist(), "study.nc = to_xarray()": same}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<26} {v}")
