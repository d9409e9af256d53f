"""Journal stiffness and damping against eccentricity
==================================================

Film stiffness and damping of a journal bearing against eccentricity, by the FEM film solver's
perturbation equations, beside Ocvirk's short-bearing closed forms.

L/D = 1/10 (short), half-Sommerfeld cavitation.  The 2 x 2 matrices come in the solver's x, y frame
and Ocvirk's in the load frame; their traces and determinants do not depend on the frame, so those are
compared (the short-bearing theory is exact as L/D -> 0; at 1/10 it is within a few per cent,
tests/test_film_coefficients.py measures how the difference falls like (L/D)^2).
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

R, C, ETA, OMEGA = 25e-3, 50e-6, 0.05, 300.0
L = 0.1 * 2 * R


def coefficients(eps):
    n = 64 if SMOKE else 256
    m = meshes.rectangle(np.linspace(0.0, 2 * np.pi * R, n + 1), np.linspace(0.0, L, 5), cell="quad", periodic_x=True)
    alpha = 2 * np.pi / n / 6  # the rupture lines a sixth of an element from a vertex (see the test)
    film = Film(m, JournalBearing.from_ratio(R, C, eps, alpha), Lubricant.newtonian(ETA),
                velocity_upper=(OMEGA * R, 0.0), dirichlet={"bottom": 0.0, "top": 0.0}, element="P2",
                cavitation=Cavitation("half_sommerfeld", 0.0))
    _, K, Cm = film.solve().coefficients()
    return K, Cm


def main():
    eps_values = [0.3, 0.6] if SMOKE else [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8]
    rows = []
    for eps in eps_values:
        K, Cm = coefficients(eps)
        Kr, Cr = cf.short_journal_coefficients(R, C, L, eps, ETA, OMEGA * R)
        rows.append((eps, np.trace(K), np.trace(Kr), np.trace(Cm), np.trace(Cr), np.linalg.det(K), np.linalg.det(Kr)))
    rows = np.array(rows)
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.semilogy(rows[:, 0], rows[:, 1], "o-", label="FEM")
    a.semilogy(rows[:, 0], rows[:, 2], "k--", label="Ocvirk")
    a.set_xlabel("eccentricity ratio [-]")
    a.set_ylabel("trace K [N/m]")
    a.legend()
    b.semilogy(rows[:, 0], rows[:, 3], "o-", label="FEM")
    b.semilogy(rows[:, 0], rows[:, 4], "k--", label="Ocvirk")
    b.set_xlabel("eccentricity ratio [-]")
    b.set_ylabel("trace C [N s/m]")
    b.legend()
    fig.suptitle(f"journal R {R * 1e3:g} mm, c {C * 1e6:g} um, L/D 0.1, {OMEGA:g} rad/s")
    fig.tight_layout()
    OUT.mkdir(parents=True, exist_ok=True)
    fig.savefig(OUT / "journal_coefficients.png", dpi=100)
    return rows


if __name__ == "__main__":
    print("eps   trace K FEM / Ocvirk      trace C FEM / Ocvirk")
    for r in main():
        print(f"{r[0]:.1f}   {r[1]:.4g} / {r[2]:.4g}     {r[3]:.4g} / {r[4]:.4g}")
