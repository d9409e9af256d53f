"""Cavitation models on one bearing
================================

Cavitation models compared on one bearing.

An infinitely long journal bearing (R = 50 mm, c = 50 um, eccentricity 0.6, oil 0.02 Pa s, journal surface
speed 10 m/s) solved with each of the four cavitation models of :class:`lubedyn.lubrication.Cavitation`, each against
its own closed form (:mod:`lubedyn.lubrication.closed_form`):

- ``"none"`` (full Sommerfeld): negative pressures, the load perpendicular to the line of centres;
- ``"half_sommerfeld"`` (Guembel): the same pressures clipped at zero, not mass conserving;
- ``"reynolds"`` (Swift-Stieber): p = dp/dphi = 0 where the film ends, a complementarity problem;
- ``"jfo"`` (Jakobsson-Floberg-Olsson, mass conserving): fed at the largest gap (p = 0 there), its film
  ruptures where Swift-Stieber's does, so it carries the same load here; it differs where the film reforms
  inside the bearing (a pocket, a squeeze: the ``fowell_pocket`` case).

The long bearing is a periodic strip one element wide with no axial leakage and the gauge p(phi = 0) = 0
(as ``tests/conftest.py``'s ``long_journal_film``).  JFO runs on P1 elements (P2 is inaccurate for JFO and
warns); the others on P2.
"""
import os
from pathlib import Path
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn.lubrication import Cavitation, Film, JournalBearing, Lubricant
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes

R, C, EPS, ETA, U = 0.05, 50e-6, 0.6, 0.02, 10.0
WIDTH = 1e-3  # axial width of the strip [m]; forces are divided by it


def long_journal(model, n, element):
    """The long journal with cavitation ``model`` on ``n`` elements round the circumference."""
    mesh = meshes.rectangle(np.linspace(0.0, 2 * np.pi * R, n + 1), [0.0, WIDTH], cell="quad", periodic_x=True)
    column = [0.0, WIDTH] if element == "P1" else [0.0, 0.5 * WIDTH, WIDTH]
    film = Film(mesh, JournalBearing(R, C, -EPS * C, 0.0), Lubricant.newtonian(ETA), velocity_upper=(U, 0.0),
                dirichlet={}, pressure_points=tuple(((0.0, y), 0.0) for y in column), element=element,
                cavitation=Cavitation(model, 0.0))
    return film.solve()


def main():
    n = 32 if SMOKE else 128
    # closed forms: (W_r, W_t) per unit length [N/m]; W_r along the displacement, W_t perpendicular
    swift = cf.long_journal_reynolds(R, C, EPS, ETA, U)
    exact = {"none": (0.0, cf.long_journal_sommerfeld_load(R, C, EPS, ETA, U)),
             "half_sommerfeld": cf.long_journal_half_sommerfeld_load(R, C, EPS, ETA, U),
             "reynolds": (swift.W_r, swift.W_t),
             "jfo": (swift.W_r, swift.W_t)}
    phi = np.linspace(0.0, 2 * np.pi, 721)
    curves = {"none": cf.long_journal_sommerfeld_pressure(phi, R, C, EPS, ETA, U),
              "half_sommerfeld": np.maximum(cf.long_journal_sommerfeld_pressure(phi, R, C, EPS, ETA, U), 0.0),
              "reynolds": swift.pressure(phi)}
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    out = {}
    for model in ("none", "half_sommerfeld", "reynolds", "jfo"):
        sol = long_journal(model, 4 * n if model == "jfo" else n, "P1" if model == "jfo" else "P2")
        W_r, W_t = sol.mode_forces["x"] / WIDTH, -sol.mode_forces["y"] / WIDTH  # the strip's frame (tests/conftest.py)
        load, ref = np.hypot(W_r, W_t), np.hypot(*exact[model])
        out[f"{model} load [N/m]"], out[f"{model} closed form [N/m]"] = load, ref
        out[f"{model} attitude [deg]"] = np.degrees(np.arctan2(W_t, W_r))
        theta = sol.basis.doflocs[0] / R
        order = np.argsort(theta)
        line, = a.plot(np.degrees(theta[order]), sol.pressure[order] / 1e6, ".", ms=3, label=f"{model} (FEM)")
        if model in curves:
            a.plot(np.degrees(phi), curves[model] / 1e6, "-", color=line.get_color(), lw=0.8)
        b.bar(model, load / 1e3, color=line.get_color())
        b.plot([model], [ref / 1e3], "k_", ms=30, mew=2)
    a.set_xlabel("phi from the largest gap [deg]")
    a.set_ylabel("pressure [MPa]")
    a.set_title("dots: FEM, lines: closed forms")
    a.legend(fontsize=8)
    b.set_ylabel("load per unit length [kN/m] (black: closed form)")
    b.tick_params(axis="x", labelsize=8)
    fig.suptitle(f"long journal, eccentricity {EPS}: four cavitation models")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "cavitation_models.png", dpi=100)
    return out


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<32} {v:.6g}")
