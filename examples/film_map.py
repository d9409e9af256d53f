"""A film map: build, save, query, check
=====================================

A film map built, saved, loaded, queried and checked: paper B's ball-ball oil film (Reynolds FEM,
Barus viscosity, Dowson-Higginson density) on polar axes (central gap, pressure number rho, squeeze
angle theta), a small grid solved in this process.

Checks shown: the map's own accuracy report (random off-grid points solved directly), a query at an
off-grid point against a direct solve of the kind there, and the pure-squeeze line (theta = 90 deg)
against the rigid Barus squeeze closed form of lubedyn.lubrication.laws.collision (Dowson-Higginson density
adds about 1 %).  The shipped map is cases/maps/ball_ball.npz (cases/map_ball_ball.toml).
Measured: 8 x 8 nodes (13 s), map 0.4195 N against the direct 0.4199 N (-0.09 %), accuracy median
0.15 %, pure squeeze within 0.53 % of the closed form; 4 x 4 (smoke) -1.2 %, 0.11 %, 0.70 %.
"""
import os
import math
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn import maps
from lubedyn.film_points.ball_ball import polar_speeds
from lubedyn.lubrication.laws.collision import barus_squeeze_film

import os

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes


def main():
    kind = maps.get_kind("ball_ball")
    params = dict(kind.default_params(), resolution="smoke")
    axes = {"central_gap": {"n": 2, "lo": 1e-6, "hi": 1e-5},
            "pressure_number": {"n": 4 if SMOKE else 8, "lo": 0.01, "hi": 0.5},
            "squeeze_angle": {"n": 4 if SMOKE else 8, "lo": math.radians(-60.0), "hi": math.radians(90.0)}}
    fmap = maps.build_map(kind, params, axes, workers=1, progress=False, accuracy_points=3)
    path = fmap.save(Path(tempfile.mkdtemp()) / "ball_ball_small.npz")
    fmap = maps.FilmMap.load(path)                      # what a dynamics case reads
    h0, rho, theta = 3e-6, 0.2, math.radians(50.0)      # off the grid
    from_map = float(fmap("Force [N]", h0, rho, theta))
    direct = kind.evaluate(params, {"Central gap [m]": h0, "Pressure number [-]": rho, "Squeeze angle [rad]": theta})
    # the pure-squeeze line against the closed form
    rhos = np.linspace(0.01, 0.5, 25)
    squeeze = [float(fmap("Force [N]", h0, r, 0.5 * math.pi)) for r in rhos]
    closed = []
    for r in rhos:
        v, _ = polar_speeds(h0, r, 0.5 * math.pi, params)
        closed.append(barus_squeeze_film(h0, v, params["eta0"], params["alpha"], 0.5 * params["ball_radius"])[0])
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(rhos, squeeze, "o-", label="map (Reynolds FEM, Dowson-Higginson)")
    ax.plot(rhos, closed, "k--", label="rigid Barus closed form (incompressible)")
    ax.set_xlabel("pressure number rho [-] (pure squeeze)")
    ax.set_ylabel(f"force at h0 = {h0 * 1e6:g} um [N]")
    ax.legend()
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "film_map.png", dpi=100)
    return {"map force [N]": from_map, "direct force [N]": direct["Force [N]"],
            "accuracy, force median [-]": fmap.accuracy["Force [N]"]["median"],
            "squeeze map/closed form, max deviation [-]": float(np.max(np.abs(np.array(squeeze) / closed - 1)))}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<44} {v:.5g}")
