"""Graded line grids of the EHL solver (needed by paper A's roller maps): what they resolve, what they cost, where Newton stops.

1. Moes line contacts M = 20 and 100, L = 10 on [-4.5, 1.5] b: h_c, h_min, the spike's p_max and the time
   on uniform 257 / 513 / 1025 / 2049 nodes and graded 257 / 513 nodes (refine 4 and 8 on [-1.2, 1.2] b).
2. Paper A's cone (``ehl_roller_cone``, 7 m/s), a load continuation through the hydrodynamic-to-EHL knee
   (15-45 kN/m in 3 % steps, each solve started from the previous converged one, Newton steps capped at
   2, then 0.5, then 0.25 p_Hertz) on graded 257 nodes (``grid_refine`` 6), against the uniform 257-node
   kind: the Maxwell low-slip traction slope a = mu/SRR (the quantity whose +-10 % jitter between loads the
   roller maps' traction misses carry, cases/maps/README.md) and which loads converge.

``python benchmarks/ehl_graded.py`` -> results/ehl_graded.{json,png} (about 2 minutes on one core).
"""
from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from _common import RESULTS, machine_info, save_figure, write_json  # noqa: E402


def moes_table():
    from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, solve_ehl

    grids = [("uniform", dict(nx=n)) for n in (257, 513, 1025, 2049)]
    grids += [("graded", dict(nx=n, refine=r, refine_width=0.5)) for n, r in ((257, 4.0), (257, 8.0), (513, 4.0))]
    rows = []
    for M in (20.0, 100.0):
        c = EHLContact.from_moes(M, 10, line=True)
        for kind, kw in grids:
            g = EHLGrid(**kw)
            d = np.diff(g.x_nodes())
            row = dict(M=M, L=10.0, grid=kind, nx=g.nx, refine=g.refine, dx_min_b=float(d.min()), dx_max_b=float(d.max()))
            t = time.perf_counter()
            try:
                s = solve_ehl(c, g, EHLOptions())
                row.update(central_film_m=s.central_film_thickness, minimum_film_m=s.minimum_film_thickness,
                           pmax_over_pHertz=float(np.max(s.pressure) / s.problem.ph), newton=s.info["iterations"],
                           converged=True)
            except Exception as exc:  # recorded: where the method stops is a result
                row.update(converged=False, error=str(exc)[:300])
            row["wall_s"] = time.perf_counter() - t
            rows.append(row)
            print(row, flush=True)
    return rows


def knee_sweep(race="cone", speed=7.0, refine=6.0, ratio=1.03, w0=15e3, w1=45e3):
    from lubedyn.film_points import ehl
    from lubedyn.lubrication.ehl import solve_ehl

    par = ehl._roller_params(race)
    par["coefficients"] = "linearised"
    graded = dict(par, grid_refine=refine)
    G = par["film_shear_modulus"]
    rows, prev = [], None
    w = w0
    while w <= w1 * 1.0001:
        row = dict(load_N_per_m=w)
        t = time.perf_counter()
        base = ehl.ehl_load_response(par, w, speed)["solution"]
        row["uniform_a"] = ehl.maxwell_traction(ehl.couette_profile(base), 1e-12, G) / 1e-12
        row["uniform_central_film_m"] = base.central_film_thickness
        contact, grid, opt = ehl._ehl_setup(graded, w, speed)
        sol, err = None, None
        for step in (2.0, 0.5, 0.25):
            try:
                sol = solve_ehl(contact, grid, dataclasses.replace(opt, max_step=step), initial=prev)
                row["max_step"] = step
                break
            except Exception as exc:
                err = str(exc)[:300]
        if sol is None:
            row.update(converged=False, error=err)
        else:
            P = sol.problem
            i = int(np.argmax(sol.pressure))
            row.update(converged=True, graded_a=ehl.maxwell_traction(ehl.couette_profile(sol), 1e-12, G) / 1e-12,
                       graded_central_film_m=sol.central_film_thickness, pmax_over_pHertz=float(sol.pressure[i] / P.ph),
                       pmax_x_over_b=float(P.xs[i] / P.bx), newton=sol.info["iterations"])
            prev = sol
        row["wall_s"] = time.perf_counter() - t
        rows.append(row)
        print(row, flush=True)
        w *= ratio
    return rows


def main():
    out = dict(machine=machine_info(), moes=moes_table(), knee=knee_sweep())
    knee = out["knee"]
    conv = [r for r in knee if r["converged"]]
    out["knee_summary"] = dict(loads=len(knee), converged=len(conv),
                               failed_loads=[r["load_N_per_m"] for r in knee if not r["converged"]])
    write_json(RESULTS / "ehl_graded.json", out)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    w = np.array([r["load_N_per_m"] for r in knee]) / 1e3
    ax[0].semilogy(w, [r["uniform_a"] for r in knee], "o-", ms=3, label="uniform 257 nodes (the shipped kind)")
    ax[0].semilogy([r["load_N_per_m"] / 1e3 for r in conv], [r["graded_a"] for r in conv], "s-", ms=4,
                   label="graded 257 nodes (refine 6), converged")
    for r in knee:
        if not r["converged"]:
            ax[0].axvline(r["load_N_per_m"] / 1e3, color="0.85", lw=0.8, zorder=0)
    ax[0].set_xlabel("Line load [kN/m]")
    ax[0].set_ylabel("Maxwell low-slip traction slope a = mu/SRR [-]")
    ax[0].set_title("Cone, 7 m/s (grey: graded Newton failed)")
    ax[0].legend(fontsize=8)
    for M in (20.0, 100.0):
        rows = [r for r in out["moes"] if r["M"] == M and r["converged"]]
        for kind, mk in (("uniform", "o"), ("graded", "s")):
            sel = [r for r in rows if r["grid"] == kind]
            ax[1].loglog([r["wall_s"] for r in sel], [r["pmax_over_pHertz"] for r in sel], mk,
                         label=f"M = {M:g}, {kind}")
    ax[1].set_xlabel("Wall time [s]")
    ax[1].set_ylabel("p_max / p_Hertz (the spike's discrete height)")
    ax[1].set_title("Moes L = 10: spike height against cost")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, RESULTS / "ehl_graded.png")


if __name__ == "__main__":
    main()
