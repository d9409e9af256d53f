"""A slider and a journal bearing
==============================

An inclined slider and a short journal bearing from Python, each against its closed form.

Slider: plane pad, h_in = 2 h_out (K = 1), runner at 5 m/s, 50 mm long, oil 0.05 Pa s: load per unit
width against W = 12 eta u_m l^2/(K^2 h_out^2) [ln(1 + K) - 2K/(2 + K)].  Journal: L/D = 1/10 at
eccentricity 0.6, half-Sommerfeld cavitation: load against Ocvirk's short bearing (within (L/D)^2).
"""
import os
from pathlib import Path
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from lubedyn.lubrication import Cavitation, Film, InclinedSlider, JournalBearing, Lubricant
from lubedyn.lubrication import closed_form as cf
from lubedyn.lubrication import mesh as meshes

SMOKE = os.environ.get("LUBEDYN_SMOKE", "") not in ("", "0")  # LUBEDYN_SMOKE=1: coarse, seconds
OUT = Path(os.environ.get("LUBEDYN_EXAMPLE_OUT", "."))  # where the figure goes


def slider():
    h_out, length, eta, u = 20e-6, 0.05, 0.05, 5.0
    film = Film(meshes.interval(0.0, length, 8 if SMOKE else 32), InclinedSlider(2 * h_out, h_out, length),
                Lubricant.newtonian(eta), velocity_lower=(u,), element="P2")
    sol = film.solve()
    exact = cf.inclined_slider_load(2 * h_out, h_out, length, eta, u / 2)
    return sol, exact


def journal():
    R, c, eps, eta, omega = 25e-3, 50e-6, 0.6, 0.05, 300.0
    L = 0.1 * 2 * R
    n = 64 if SMOKE else 256
    m = meshes.rectangle(np.linspace(0.0, 2 * np.pi * R, n + 1), np.linspace(0.0, L, 5), cell="quad", periodic_x=True)
    film = Film(m, JournalBearing.from_ratio(R, c, eps), Lubricant.newtonian(eta), velocity_upper=(omega * R, 0.0),
                dirichlet={"bottom": 0.0, "top": 0.0}, element="P2", cavitation=Cavitation("half_sommerfeld", 0.0))
    sol = film.solve()
    W = cf.short_journal_load(R, c, L, eps, eta, omega * R)[0]
    return sol, W


def main():
    s, ws = slider()
    j, wj = journal()
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    s.plot_pressure(ax=a)
    a.set_title(f"slider: {s.load:.5g} N/m (exact {ws:.5g})")
    j.plot_pressure(ax=b)
    b.set_title(f"journal: |F| {j.load:.4g} N (Ocvirk {wj:.4g})")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "slider_and_journal.png", dpi=100)
    return {"slider load [N/m]": s.load, "slider exact [N/m]": ws, "journal load [N]": j.load, "Ocvirk [N]": wj}


if __name__ == "__main__":
    for k, v in main().items():
        print(f"{k:<22} {v:.6g}")
