"""Journal-bearing stiffness and damping over speed, handed to ROSS
================================================================

A rotordynamics model wants each fluid-film bearing as 2 x 2 stiffness and damping matrices over the
rotor speed.  ``lubedyn.bearing_coefficients`` computes them with the finite-element film (the bundled
``journal_finite`` bearing: R = 25 mm, L = 50 mm, c = 50 um, 0.02 Pa s, Reynolds cavitation) with the
journal moved, at each speed, to where the film carries a static load; ``lubedyn.to_ross`` makes a ROSS
bearing element of them (``pip install 'lubedyn[ross]'``).

Checked against Raimondi and Boyd (1958): under the load of their Sommerfeld number S = 0.121 at
3000 rpm, W = (R/c)^2 eta N / S * 2 R L = 5165 N, the journal sits at their eccentricity ratio 0.6.  With
ROSS, a shaft with a disk on two such bearings carrying its weight shows the half-speed forward whirl of
lightly loaded plain journals (oil whirl).
"""
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import lubedyn

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse mesh, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes

# %%
# Coefficients over speed under a load
# ------------------------------------
# Speeds in rad/s or as strings with units; the load in N (a scalar points along -y, a weight) or a
# pair (W_x, W_y).  ``smoke=True`` takes the case's coarse ``[smoke]`` mesh.

rpm = np.array([1500.0, 2000.0, 3000.0, 4500.0, 6000.0])
R, c, L, eta = 0.025, 50e-6, 0.05, 0.02                     # the bundled case's bearing
W = (R / c) ** 2 * eta * (3000.0 / 60.0) / 0.121 * 2 * R * L  # Raimondi and Boyd's S = 0.121 at 3000 rpm
coef = lubedyn.bearing_coefficients("journal_finite", [f"{n} rpm" for n in rpm], load=W, smoke=SMOKE)
eps = coef["Eccentricity ratio [-]"]
print(f"load {W:.0f} N;  speed [rpm], eccentricity ratio, K[x,x] [N/m], C[y,y] [N s/m]:")
for n, e, kxx, cyy in zip(rpm, eps, coef["Stiffness K[x,x] [N/m]"], coef["Damping C[y,y] [N s/m]"]):
    print(f"  {n:6.0f}  {e:.4f}  {kxx:.4g}  {cyy:.4g}")

# %%
# The eight coefficients and the eccentricity
# -------------------------------------------
# ``coef.K`` and ``coef.C`` are (speeds, 2, 2) arrays in the solver's fixed frame (the journal turns from
# +x towards +y; with the load along -y that is Friswell et al.'s load frame u = x, v = y).

fig, (a, b, e_ax, r_ax) = plt.subplots(1, 4, figsize=(17, 4), layout="constrained")
styles = dict(zip(["x,x", "x,y", "y,x", "y,y"], ["o-", "s--", "^:", "d-"]))  # C[x,y] = C[y,x]: both drawn
for name in coef.names:
    kind, entry = name.split()[0], name.split()[1][2:-1]
    if kind in ("Stiffness", "Damping"):
        (a if kind == "Stiffness" else b).plot(rpm, coef[name], styles[entry], label=name.split()[1])
a.set(xlabel="speed [rpm]", ylabel="stiffness [N/m]", title=f"K under {W:.0f} N")
b.set(xlabel="speed [rpm]", ylabel="damping [N s/m]", title=f"C under {W:.0f} N")
a.legend()
b.legend()
e_ax.plot(rpm, eps, "o-", label="lubedyn")
e_ax.plot([3000.0], [0.6], "ks", label="Raimondi & Boyd, S = 0.121")
e_ax.set(xlabel="speed [rpm]", ylabel="eccentricity ratio [-]", title="equilibrium")
e_ax.legend()

# %%
# A ROSS rotor on these bearings
# ------------------------------
# A 50 mm steel shaft, 0.8 m long, with a disk in the middle, on two such bearings, each carrying half
# its weight (coefficients again, at that load).  ROSS evaluates the element at the rotor speed and
# interpolates between the speeds given.  The two lowest modes whirl forward at about half the running
# speed: the oil whirl of a lightly loaded plain journal.

try:
    import warnings

    with warnings.catch_warnings():  # a ROSS dependency warns on import that REFPROP is not configured
        warnings.filterwarnings("ignore", message=r"[\s\S]*REFPROP", category=UserWarning)
        import ross
except (ImportError, ValueError):  # ROSS 2.3 under plotly >= 7 fails with ValueError
    ross = None
    print("ROSS is not installed (pip install 'lubedyn[ross]'): no rotor model")
    r_ax.text(0.5, 0.5, "ROSS not installed:\npip install 'lubedyn[ross]'", ha="center", va="center",
              transform=r_ax.transAxes)
    r_ax.set_axis_off()

results = {"load [N]": W, "eccentricity at 3000 rpm [-]": float(eps[list(rpm).index(3000.0)]), "ross": ross is not None}
if ross is not None:
    shaft = [ross.ShaftElement(0.2, 0.0, 0.05, material=ross.steel) for _ in range(4)]
    disk = ross.DiskElement.from_geometry(n=2, material=ross.steel, width=0.07, i_d=0.05, o_d=0.28)
    weight = 9.81 * (sum(s.m for s in shaft) + disk.m)
    light = lubedyn.bearing_coefficients("journal_finite", rpm * np.pi / 30, load=weight / 2, smoke=SMOKE)
    rotor = ross.Rotor(shaft, [disk], [lubedyn.to_ross(light, n=0), lubedyn.to_ross(light, n=4)])
    lowest, whirl = [], []
    for w in light.speed:
        modal = rotor.run_modal(w, num_modes=8)
        lowest.append(modal.wd[0])
        whirl.append(str(modal.whirl_direction()[0]))
    print("speed [rpm], lowest damped natural frequency [rad/s] / running speed [rad/s], whirl:")
    for n, w, f, d in zip(rpm, light.speed, lowest, whirl):
        print(f"  {n:6.0f}  {f / w:.3f}  {d}")
    ratio = np.array(lowest) / light.speed
    r_ax.plot(rpm, ratio, "o-", label="ROSS, lowest mode")
    r_ax.axhline(0.5, color="k", ls="--", label="half the running speed")
    r_ax.set(xlabel="speed [rpm]", ylabel="damped natural frequency / speed [-]",
             title=f"rotor {weight / 9.81:.1f} kg on two bearings")
    r_ax.set_ylim(0.3, 0.7)
    r_ax.legend()
    results.update({"rotor weight [N]": weight, "lowest frequency / speed [-]": ratio,
                    "lowest whirl": whirl})

OUT.mkdir(parents=True, exist_ok=True)
fig.savefig(OUT / "ross_bearing.png", dpi=100)


def main():
    """The numbers this example shows (tests/test_examples.py checks them)."""
    return results


if __name__ == "__main__":
    for key, value in main().items():
        print(key, value)
