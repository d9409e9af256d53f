"""The tapered roller bearing in time
==================================

Paper A's tapered roller bearing in time from Python: Fig. 5's operating point (Fr 20 kN, 2,400 rpm,
axial locked) with and without the roller-end/rib friction, to see what skews the rollers.

``lubedyn.config.load_case`` reads a bundled case with overrides (the same keys as ``lubedyn run --set``);
``lubedyn.scenes.tapered.run`` integrates it and returns the summary and every diagnostic
(:meth:`lubedyn.dynamics.tapered.model.TaperedBearing.diagnostics`: per roller and sample tilt, skew, slip,
loads, the loaded-zone marker).  Full size: 10 ms; smoke: 1 ms at 5 slices.
"""
import os
from pathlib import Path
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn.scenes import tapered as S
from lubedyn.config import CASES_DIR, load_case

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes

CASE = CASES_DIR / "trb_fig5_2400rpm.toml"


def main():
    duration = "1 ms" if SMOKE else "10 ms"
    base = [f"integrator.duration={duration}", "model.slices=5" if SMOKE else "model.slices=10",
            "analysis.window=[0, 1]"]
    runs = {}
    for label, over in (("flange friction (eqs. 22-23)", []), ("no flange friction", ["model.flange_friction=none"])):
        runs[label] = S.run(load_case(CASE, overrides=base + over))
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    out = {}
    for label, r in runs.items():
        D = r.diagnostics
        ms = r.t * 1e3
        a.plot(ms, np.mean(np.where(D["Loaded zone [-]"], D["Skew [rad]"], np.nan), axis=1), label=label)
        b.plot(ms, 100 * D["Roller slip [-]"][:, 0], label=label)
        w = r.summary["Paper window (analysis.window)"]
        out[f"mean loaded-zone skew, {label} [rad]"] = w["Skew [rad]"]["loaded zone"]["mean"]
        out[f"cage speed, {label} [rpm]"] = w["Cage speed, mean [rpm]"]
    out["ideal cage speed [rpm]"] = runs["no flange friction"].summary["Ideal cage speed [rpm]"]
    a.set_xlabel("time [ms]")
    a.set_ylabel("skew of the loaded rollers, mean [rad]")
    a.legend(fontsize=8)
    b.set_xlabel("time [ms]")
    b.set_ylabel("roller 0 slip [%] (eq. 52)")
    b.legend(fontsize=8)
    fig.suptitle("paper A, Fig. 5's point: the rib's friction skews the rollers")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "tapered_roller_dynamics.png", dpi=100)
    return out


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<52} {v:.6g}")
