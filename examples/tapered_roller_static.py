"""The tapered roller bearing at quasi-static equilibrium
======================================================

Paper A's tapered roller bearing at quasi-static equilibrium from Python: the load distribution
under a radial load with the axial motion locked, against Stribeck's estimate of the most loaded roller.

``lubedyn.papers.wu2018.parameters.tapered_geometry()`` builds the geometry of Table 1 with the parameter
module's assumed values (common-apex reading, crowned rollers; pass overrides, e.g.
``reconciliation="literal"``); ``lubedyn.dynamics.tapered.quasistatic.solve`` finds the equilibrium.
"""
import os
from pathlib import Path
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn.papers.wu2018.parameters import tapered_geometry
from lubedyn.dynamics.tapered.quasistatic import solve

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes


def main():
    g = tapered_geometry()
    fr = 20e3
    res = solve(g, radial_load=fr, axial_displacement=0.0, inner_speed=2400 * math.pi / 30,
                n_slices=8 if SMOKE else 20)
    stribeck = 4.08 * fr / (g.n_rollers * math.cos(g.cup_angle))
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    deg = np.degrees(res.azimuths)
    a.plot(deg, res.cup_loads, "o-", label="cup")
    a.plot(deg, res.cone_loads, "s-", label="cone")
    a.plot(deg, res.flange_loads, "^-", label="flange")
    a.axhline(stribeck, color="k", ls=":", label="Stribeck 4.08 Fr/(Z cos a)")
    a.set_xlabel("roller azimuth [deg]")
    a.set_ylabel("load [N]")
    a.legend()
    j = int(np.argmax(res.cup_loads))
    b.plot(res.cup_slice_loads[j], "o-", label="cup")
    b.plot(res.cone_slice_loads[j], "s-", label="cone")
    b.set_xlabel("slice (0: small end)")
    b.set_ylabel("slice load [N]")
    b.set_title(f"roller {j} (crowned)")
    b.legend()
    fig.suptitle(f"Fr {fr / 1e3:g} kN, 2,400 rpm, axial locked: {res.stop_reason}")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "tapered_roller_static.png", dpi=100)
    return {"most loaded roller, cup [N]": float(res.cup_loads.max()), "Stribeck [N]": stribeck,
            "induced thrust [N]": res.axial_load, "ideal cage speed [rpm]": res.kinematics["cage speed [rad/s]"] * 30 / math.pi}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<28} {v:.6g}")
