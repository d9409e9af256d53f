"""Your own gap function
=====================

Your own gap function: a parallel slider with a Rayleigh step written as a Python function.

``FunctionGap(func)`` takes any ``h(x)`` (``x`` has shape (dim, ...)); here a step from h_in to h_out
at 0.7183 of the length (Rayleigh's optimum proportions for a step ratio 1.866) over a 2-D pad.  With
a wide pad the load per unit width tends to Rayleigh's closed form (lubedyn.lubrication.closed_form
.rayleigh_step_load); the 1-D run is compared with it exactly, the 2-D one shows the side leakage.
"""
import os
from pathlib import Path
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn.lubrication import Film, FunctionGap, Lubricant
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes

H_OUT, RATIO, LENGTH, ETA, U = 20e-6, 1.866, 0.02, 0.05, 5.0
L_IN = 0.7183 * LENGTH


def step(x):
    """The user's gap: h_in upstream of the step, h_out downstream (x[0] along the runner)."""
    return np.where(x[0] < L_IN, RATIO * H_OUT, H_OUT)


def main():
    n = 20 if SMOKE else 80
    # a node on the step: the mesh has L_IN as a vertex
    xs = np.unique(np.concatenate([np.linspace(0, L_IN, int(n * 0.72) + 1), np.linspace(L_IN, LENGTH, n // 4 + 1)]))
    one_d = Film(meshes.interval(0, 0, 0, points=xs), FunctionGap(step), Lubricant.newtonian(ETA),
                 velocity_lower=(U,), element="P1").solve()
    exact = cf.rayleigh_step_load(RATIO * H_OUT, H_OUT, L_IN, LENGTH - L_IN, ETA, U / 2)
    width = LENGTH
    m = meshes.rectangle(xs, np.linspace(0, width, 9 if SMOKE else 25), cell="quad")
    two_d = Film(m, FunctionGap(step), Lubricant.newtonian(ETA), velocity_lower=(U, 0.0), element="P1").solve()
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    one_d.plot_pressure(ax=a)
    a.set_title(f"1-D: {one_d.load:.5g} N/m (Rayleigh {exact:.5g})")
    two_d.plot_pressure(ax=b)
    b.set_title(f"square pad: {two_d.load / width:.4g} N/m mean (side leakage)")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "own_gap.png", dpi=100)
    return {"1-D load [N/m]": one_d.load, "Rayleigh [N/m]": exact, "square pad load per width [N/m]": two_d.load / width}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<32} {v:.6g}")
