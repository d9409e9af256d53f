"""Reynolds film solver: speed against accuracy.

Writes ``benchmarks/results/reynolds.json`` and ``reynolds.png`` (``--quick``:
``reynolds_quick.json``/``.png``, so a smoke run never replaces the full numbers)::

    python benchmarks/reynolds.py            # full run (several minutes)
    python benchmarks/reynolds.py --quick    # small sizes, under a minute

Scenes
------
1. Work-precision (error against wall time) for P1 and P2 elements:

   a. sphere-plane squeeze film (parabolic gap, ``mesh.disk``, refined),
      error of the load against the closed form
      F = 6 pi eta R^2 (-v)/h0 (1 - h0/h_edge)^2, h_edge = h0 + a^2/(2R);
   b. finite journal bearing (L/D = 0.5, eps = 0.6, periodic quad mesh),
      Reynolds (Swift-Stieber) cavitation and the half-Sommerfeld
      approximation, error of the load magnitude against a reference from the
      three finest P2 solutions (Richardson when they converge monotonically).
      Reynolds cavitation twice: with the solver's default (automatic
      coarse-to-fine start from 1000 DOFs, ``SolverOptions.warm_start_levels``)
      and cold (``warm_start_levels=0``).

2. A ~1-million-DOF P1 solve (inclined slider, 1000 x 1000 quads, full film):
   mesh, setup, assembly, reduction and linear-solve times separately, the
   solver used, and a cProfile of the public ``solve``.
   2b. ``--big-paths``: the same solve on the structured path (tensor grid: grid
   assembly, geometric multigrid; what ``solve`` picks on this mesh) and on
   scikit-fem's general path (``SolverOptions(structured=False)``), interleaved,
   process CPU seconds, stages, cProfiles, and their agreement
   (``results/reynolds_big_paths.json``, ``.png``).

3. ROSS's finite-difference journal solver (``ross.bearings.fluid_flow``) on
   the same bearing (half-Sommerfeld, which is what it computes): load,
   attitude and wall time on refining grids, against our converged
   half-Sommerfeld reference.

Times are wall-clock medians of a few repeats, in seconds and as ratios to a
reference run in the same process (P1 full-film journal on a 64 x 16 mesh,
1088 DOFs), so that runs on a busy machine stay comparable.  Nothing here
asserts a time.
"""
from __future__ import annotations

import argparse
import cProfile
import json
import logging
import os
import pstats
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import _common  # noqa: E402
import _ross  # noqa: E402

from lubedyn.lubrication import InclinedSlider, JournalBearing, Lubricant, SpherePlane  # noqa: E402
from lubedyn.lubrication import mesh as lmesh  # noqa: E402
from lubedyn.lubrication.reynolds import Cavitation, Film, SolverOptions, solve  # noqa: E402

log = logging.getLogger("benchmarks.reynolds")

# ------------------------------------------------------------------ scenes
SPHERE = dict(radius=10e-3, h0=10e-6, disk_radius=1.0e-3, viscosity=0.01, squeeze=-1e-3)
JOURNAL = dict(radius=50e-3, clearance=50e-6, length=50e-3, viscosity=0.02, omega=200.0, eccentricity_ratio=0.6)
SLIDER = dict(length=20e-3, h_in=20e-6, h_out=10e-6, viscosity=0.01, speed=1.0)

SIZES = {
    "quick": dict(
        sphere={"P1": [2, 3, 4, 5], "P2": [2, 3, 4]},
        journal={"P1": [16, 32, 64], "P2": [16, 32, 64]},
        big_n=300,
        ross_grids=[(9, 33), (17, 65), (33, 129)],
        repeats=3,
    ),
    "full": dict(
        sphere={"P1": [2, 3, 4, 5, 6, 7, 8], "P2": [2, 3, 4, 5, 6, 7]},
        journal={"P1": [16, 32, 64, 128, 256, 512], "P2": [16, 32, 64, 128, 256]},
        big_n=1000,
        ross_grids=[(9, 33), (17, 65), (33, 129), (49, 193), (65, 257)],
        repeats=3,
    ),
}
JOURNAL_ASPECT = 4  # nx = 4 ny: cells 1.6 times longer circumferentially than axially


def sphere_exact() -> float:
    s = SPHERE
    h_edge = s["h0"] + s["disk_radius"] ** 2 / (2 * s["radius"])
    return 6 * np.pi * s["viscosity"] * s["radius"] ** 2 * (-s["squeeze"]) / s["h0"] * (1 - s["h0"] / h_edge) ** 2


def sphere_film(refinements: int, element: str, curved: bool = False) -> Film:
    s = SPHERE
    return Film(
        mesh=lmesh.disk(s["disk_radius"], refinements, order=2 if curved else 1),
        gap=SpherePlane(s["radius"], s["h0"]),
        lubricant=Lubricant.newtonian(s["viscosity"]),
        squeeze=s["squeeze"],
        element=element,
    )


def journal_film(nx: int, element: str, cavitation: str, warm_start_levels=None) -> Film:
    j = JOURNAL
    ny = max(nx // JOURNAL_ASPECT, 1)
    m = lmesh.rectangle(
        np.linspace(0.0, 2 * np.pi * j["radius"], nx + 1), np.linspace(0.0, j["length"], ny + 1), "quad", periodic_x=True
    )
    return Film(
        mesh=m,
        gap=JournalBearing.from_ratio(j["radius"], j["clearance"], j["eccentricity_ratio"]),
        lubricant=Lubricant.newtonian(j["viscosity"]),
        velocity_upper=(j["omega"] * j["radius"], 0.0),
        element=element,
        cavitation=Cavitation(cavitation),
        dirichlet={"bottom": 0.0, "top": 0.0},
        options=SolverOptions(warm_start_levels=warm_start_levels),
    )


def slider_film(n: int) -> Film:
    s = SLIDER
    xs = np.linspace(0.0, s["length"], n + 1)
    return Film(
        mesh=lmesh.rectangle(xs, xs, "quad"),
        gap=InclinedSlider(s["h_in"], s["h_out"], s["length"]),
        lubricant=Lubricant.newtonian(s["viscosity"]),
        velocity_lower=(s["speed"], 0.0),
        element="P1",
    )


def journal_load(sol) -> tuple[float, float]:
    """Load magnitude [N] and attitude angle [deg] (journal centre on +x)."""
    F = sol.load_vector
    return float(np.hypot(F[0], F[1])), float(np.degrees(np.arctan2(abs(F[1]), abs(F[0]))))


# ------------------------------------------------------------------ helpers
class Clock:
    """Reference time unit: P1 full-film journal, 64 x 16 quads."""

    def __init__(self):
        film = journal_film(64, "P1", "none")
        solve(film)  # warm-up: imports, caches
        self.seconds, self.times, sol = _common.timed(lambda: solve(journal_film(64, "P1", "none")), repeats=7)
        self.dofs = sol.info["dofs"]

    def ratio(self, seconds: float) -> float:
        return seconds / self.seconds

    def describe(self) -> dict:
        return {
            "what": "solve() of the P1 full-film journal bearing on a 64 x 16 quad mesh, mesh build included",
            "dofs": self.dofs,
            "median [s]": self.seconds,
            "times [s]": self.times,
        }


def point(clock, label, make_film, repeats, value_of):
    """Build and solve a film ``repeats`` times; time = mesh + solve + load."""

    def run():
        sol = solve(make_film())
        return sol, value_of(sol)

    t, times, (sol, value) = _common.timed(run, repeats)
    out = {
        "label": label,
        "dofs": int(sol.info["dofs"]),
        "iterations": int(sol.info["iterations"]),
        "linear_solver": sol.info.get("linear_solver"),
        "time [s]": t,
        "times [s]": times,
        "time ratio [-]": clock.ratio(t),
    }
    if "nested" in sol.info:  # automatic coarse-to-fine start: iterations per level, coarsest first
        out["nested levels (dofs, iterations)"] = [(int(d), int(i)) for d, i, _ in sol.info["nested"]]
    out.update(value)
    log.info("%-34s %8d dofs %4d it %8.3f s  %s", label, out["dofs"], out["iterations"], t,
             ", ".join(f"{k}={v:.6g}" for k, v in value.items()))
    return out


def add_errors(points, key, reference, err_key="error [-]", uncertainty=0.0):
    """Relative error of ``p[key]``; ``below reference uncertainty`` marks errors
    that the reference cannot resolve (they are left out of the chart)."""
    for p in points:
        p[err_key] = abs(p[key] - reference) / abs(reference)
        p["below reference uncertainty"] = bool(p[err_key] <= (1 + 1e-9) * uncertainty / abs(reference))


def summarise(points, err_key="error [-]"):
    points = [p for p in points if not p.get("below reference uncertainty")]
    return {
        "fitted order (error vs 1/sqrt(dofs))": _common.fitted_order([p["dofs"] for p in points], [p[err_key] for p in points]),
        "time to error [s]": _common.time_to_error([p["time [s]"] for p in points], [p[err_key] for p in points]),
    }


# ------------------------------------------------------------------ 1. work-precision
def bench_sphere(clock, sizes, repeats):
    exact = sphere_exact()
    out = {"exact load [N]": exact, "parameters": SPHERE, "series": {}}
    for element, levels in sizes.items():
        pts = [
            point(clock, f"sphere {element} refine {k}", lambda k=k, e=element: sphere_film(k, e), repeats,
                  lambda s: {"load [N]": float(s.mode_forces["h0"])})
            for k in levels
        ]
        for p, k in zip(pts, levels):
            p["refinements"] = k
        add_errors(pts, "load [N]", exact)
        out["series"][element] = {"points": pts, **summarise(pts)}
    # the same P2 films on the isoparametric disk, mesh.disk(order=2)
    levels = sizes["P2"]
    pts = [
        point(clock, f"sphere P2 curved refine {k}", lambda k=k: sphere_film(k, "P2", curved=True), repeats,
              lambda s: {"load [N]": float(s.mode_forces["h0"])})
        for k in levels
    ]
    for p, k in zip(pts, levels):
        p["refinements"] = k
    add_errors(pts, "load [N]", exact)
    out["series"]["P2 curved"] = {"points": pts, "mesh": "mesh.disk(order=2): skfem.MeshTri2 (quadratic geometry)", **summarise(pts)}
    return out


def bench_journal(clock, sizes, repeats, cavitation):
    out = {"parameters": {**JOURNAL, "cavitation": cavitation, "nx/ny": JOURNAL_ASPECT}, "series": {}}
    for element, levels in sizes.items():
        pts = []
        for nx in levels:
            p = point(clock, f"journal {cavitation} {element} {nx}x{nx // JOURNAL_ASPECT}",
                      lambda nx=nx, e=element: journal_film(nx, e, cavitation), repeats,
                      lambda s: dict(zip(("load [N]", "attitude [deg]"), journal_load(s))))
            p["nx"], p["ny"] = nx, nx // JOURNAL_ASPECT
            pts.append(p)
        out["series"][element] = {"points": pts}
    p2 = out["series"]["P2"]["points"]
    ref = _common.richardson([p["load [N]"] for p in p2])
    ref_att = _common.richardson([p["attitude [deg]"] for p in p2])
    out["reference load"] = ref
    out["reference attitude"] = ref_att
    for element, series in out["series"].items():
        add_errors(series["points"], "load [N]", ref["value"], uncertainty=ref["uncertainty"] or 0.0)
        for p in series["points"]:
            p["attitude error [deg]"] = abs(p["attitude [deg]"] - ref_att["value"])
        series.update(summarise(series["points"]))
    return out


def bench_journal_cold(clock, sizes, repeats, cavitation, reference, uncertainty, reference_attitude):
    """The same films without the automatic coarse-to-fine start
    (``warm_start_levels=0``): the active set starts from the full film and
    moves its boundary about a node column per iteration."""
    out = {}
    for element, levels in sizes.items():
        pts = []
        for nx in levels:
            p = point(clock, f"journal {cavitation} {element} {nx}x{nx // JOURNAL_ASPECT} cold",
                      lambda nx=nx, e=element: journal_film(nx, e, cavitation, warm_start_levels=0), repeats,
                      lambda s: dict(zip(("load [N]", "attitude [deg]"), journal_load(s))))
            p["nx"], p["ny"] = nx, nx // JOURNAL_ASPECT
            pts.append(p)
        add_errors(pts, "load [N]", reference, uncertainty=uncertainty)
        for p in pts:
            p["attitude error [deg]"] = abs(p["attitude [deg]"] - reference_attitude)
        out[f"{element} cold"] = {"points": pts, **summarise(pts)}
    return out


# ------------------------------------------------------------------ 2. big P1 solve
def _phases(film):
    """Time the stages of one solve through the solver's internals (if they exist)."""
    from lubedyn.lubrication.reynolds import problem as rey

    t = {}
    t0 = time.perf_counter()
    prob = rey._Problem(film)
    t["setup (basis, quadrature fields, Dirichlet dofs) [s]"] = time.perf_counter() - t0
    N = prob.N
    p = np.where(prob.fixed, prob.p_fixed, film.ambient_pressure)
    t0 = time.perf_counter()
    R, Jp, _ = prob.assemble(p, np.zeros(N), with_void=False)
    t["assembly (residual + matrix) [s]"] = time.perf_counter() - t0
    idx = np.flatnonzero(prob.free)
    t0 = time.perf_counter()
    A = Jp[idx][:, idx]
    b = -R[idx]
    t["reduction to free dofs [s]"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    prob.solve_linear(A, b, symmetric=True, index=idx)
    t["linear solve [s]"] = time.perf_counter() - t0
    return t, getattr(prob, "linear_solver_used", None), A.tocsr(), b


def _profile(fn, top=25, timer=None):
    prof = cProfile.Profile(timer) if timer is not None else cProfile.Profile()
    prof.enable()
    fn()
    prof.disable()
    stats = pstats.Stats(prof)
    rows = []
    for (fname, line, func), (cc, nc, tt, ct, _) in stats.stats.items():
        rows.append({"function": f"{Path(fname).name}:{line}({func})", "ncalls": nc, "tottime [s]": tt, "cumtime [s]": ct})
    rows.sort(key=lambda r: -r["cumtime [s]"])
    by_tottime = sorted(rows, key=lambda r: -r["tottime [s]"])[:top]
    return {"total [s]": stats.total_tt, "by cumulative time": rows[:top], "by own time": by_tottime}


def _amg_alternatives(A, b, tol):
    """Setup + solve time of pyamg variants on the same SPD matrix (evidence for a fix)."""
    import pyamg

    out = {}
    for name, make in (
        ("smoothed aggregation + CG (pyamg default)", pyamg.smoothed_aggregation_solver),
        ("Ruge-Stuben + CG", pyamg.ruge_stuben_solver),
    ):
        t0 = time.perf_counter()
        ml = make(A)
        t1 = time.perf_counter()
        res = []
        x = ml.solve(b, tol=tol, accel="cg", maxiter=200, residuals=res)
        t2 = time.perf_counter()
        out[name] = {
            "setup [s]": t1 - t0, "solve [s]": t2 - t1, "total [s]": t2 - t0, "cg iterations": len(res) - 1,
            "relative residual": float(np.linalg.norm(b - A @ x) / np.linalg.norm(b)), "levels": len(ml.levels),
        }
        log.info("  %-44s setup %.2f s, solve %.2f s, %d its", name, t1 - t0, t2 - t1, len(res) - 1)
    return out


def bench_big(clock, n, repeats):
    out = {"parameters": {**SLIDER, "cells": f"{n} x {n} quads", "element": "P1", "cavitation": "none"}}
    t0 = time.perf_counter()
    film = slider_film(n)
    out["mesh build [s]"] = time.perf_counter() - t0
    t, times, sol = _common.timed(lambda: solve(film), repeats)
    out.update({
        "dofs": int(sol.info["dofs"]),
        "linear_solver": sol.info.get("linear_solver"),
        "iterations": int(sol.info["iterations"]),
        "solve [s]": t, "solve times [s]": times, "solve time ratio [-]": clock.ratio(t),
        "load [N]": float(sol.load),
        "target [s]": 10.0,
    })
    log.info("big P1: %d dofs, solve %.2f s (%s)", out["dofs"], t, out["linear_solver"])
    del sol
    try:
        phases, used, A, b = _phases(film)
        out["phases"] = phases
        out["phases linear solver"] = used
        out["assembly [s]"] = sum(v for k, v in phases.items() if not k.startswith("linear"))
        out["linear solve [s]"] = phases["linear solve [s]"]
        log.info("  phases: %s", ", ".join(f"{k} {v:.2f}" for k, v in phases.items()))
        out["amg alternatives on the same matrix"] = _amg_alternatives(A, b, film.options.amg_tol)
        del A, b
    except Exception as exc:  # internals moved: keep the public timing
        out["phases"] = f"not measured: {type(exc).__name__}: {exc}"
    out["profile of solve()"] = _profile(lambda: solve(film))
    return out


# ------------------------------------------------------------------ 2b. structured against general path
def _cpu(fn):
    """(process CPU seconds, wall seconds, result) of ``fn()``."""
    c0, t0 = time.process_time(), time.perf_counter()
    out = fn()
    return time.process_time() - c0, time.perf_counter() - t0, out


def _stages(film):
    """CPU seconds of the stages of one solve (as :func:`_phases`), the multigrid or AMG setup and its CG
    apart."""
    from lubedyn.lubrication.reynolds import problem as rey

    t = {}
    t["setup [s]"], _, prob = _cpu(lambda: rey._Problem(film))
    p = np.where(prob.fixed, prob.p_fixed, film.ambient_pressure)
    t["assembly [s]"], _, (R, Jp, _) = _cpu(lambda: prob.assemble(p, np.zeros(prob.N), with_void=False))
    idx = np.flatnonzero(prob.free)
    t["reduction [s]"], _, A = _cpu(lambda: Jp[idx][:, idx])
    b = -R[idx]
    res = []
    if prob.grid is not None:
        from pyamg.krylov import cg

        t["solver setup [s]"], _, pre = _cpu(lambda: prob.grid.preconditioner(A, idx))
        t["CG [s]"], _, _ = _cpu(lambda: cg(A, b, M=pre, tol=film.options.amg_tol, maxiter=200, residuals=res))
    else:
        import pyamg

        t["solver setup [s]"], _, ml = _cpu(lambda: pyamg.ruge_stuben_solver(A.tocsr()))
        t["CG [s]"], _, _ = _cpu(lambda: ml.solve(b, tol=film.options.amg_tol, accel="cg", maxiter=200,
                                                   residuals=res))
    t["CG iterations"] = len(res) - 1
    return t


def bench_big_paths(clock, n, rounds):
    """The 1M-DOF scene on the structured path (P1 tensor grid: grid assembly, geometric multigrid; chosen
    automatically) and on scikit-fem's general path (``SolverOptions(structured=False)``: what every mesh
    took before), interleaved in this process ``rounds`` times, process CPU seconds (the machine is
    shared) and wall seconds, with the reference run's ratio; then the stages of each and a cProfile
    (CPU time) of each ``solve()``, and the pressures' agreement."""
    from lubedyn.lubrication.reynolds import SolverOptions

    film = slider_film(n)
    films = {"structured": film, "general": film.with_(options=SolverOptions(structured=False))}
    out = {"parameters": {**SLIDER, "cells": f"{n} x {n} quads", "element": "P1", "cavitation": "none"},
           "target [s]": 2.0, "rounds": []}
    sols = {}
    for r in range(rounds):
        row = {}
        for name in (("general", "structured") if r % 2 == 0 else ("structured", "general")):
            cpu, wall, sol = _cpu(lambda: solve(films[name]))
            row[f"{name} solve CPU [s]"], row[f"{name} solve wall [s]"] = cpu, wall
            row[f"{name} load CPU [s]"], _, load = _cpu(lambda: sol.load)
            row[f"{name} load [N]"] = float(load)
            row[f"{name} linear solver"] = sol.info["linear_solver"]
            sols[name] = sol
        ref_cpu, _, _ = _cpu(lambda: solve(journal_film(64, "P1", "none")))
        row["reference run CPU [s]"] = ref_cpu
        row["structured/general solve CPU"] = row["structured solve CPU [s]"] / row["general solve CPU [s]"]
        out["rounds"].append(row)
        log.info("big paths round %d: general %.2f s CPU, structured %.2f s CPU (ratio %.2f); load %.2f / %.2f s",
                 r, row["general solve CPU [s]"], row["structured solve CPU [s]"], row["structured/general solve CPU"],
                 row["general load CPU [s]"], row["structured load CPU [s]"])
    out["dofs"] = int(sols["structured"].info["dofs"])
    g, f = sols["general"], sols["structured"]
    out["max |p_structured - p_general| / p_max"] = float(np.max(np.abs(f.pressure_dofs - g.pressure_dofs)) / g.p_max)
    out["load relative difference"] = float(f.load / g.load - 1)
    del sols, g, f
    out["stages (CPU)"] = {name: _stages(films[name]) for name in ("general", "structured")}
    for name, st in out["stages (CPU)"].items():
        log.info("  %s stages: %s", name, ", ".join(f"{k} {v:.2f}" for k, v in st.items()))
    out["cProfile (CPU) of solve()"] = {name: _profile(lambda: solve(films[name]), timer=time.process_time)
                                        for name in ("general", "structured")}
    return out


def plot_big_paths(data, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    big = data["big paths"]
    fig, axs = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
    rounds = big["rounds"]
    x = np.arange(len(rounds))
    for name, marker in (("general", "o"), ("structured", "s")):
        axs[0].plot(x, [r[f"{name} solve CPU [s]"] for r in rounds], marker + "-", label=f"{name} path: solve()")
        axs[0].plot(x, [r[f"{name} solve CPU [s]"] + r[f"{name} load CPU [s]"] for r in rounds], marker + ":",
                    label=f"{name} path: solve() + load")
    axs[0].axhline(big["target [s]"], color="k", ls="--", lw=0.8, label="target 2 s (warm, idle machine)")
    axs[0].set_xlabel("round (interleaved)")
    axs[0].set_ylabel("process CPU [s]")
    ratios = [r["structured/general solve CPU"] for r in rounds]
    load = data["machine"].get("load_average_at_start") or [float("nan")]
    axs[0].set_title(f"{big['dofs']:,} DOF P1 slider: structured/general {min(ratios):.2f}-{max(ratios):.2f}\n"
                     f"(load average {load[0]:.1f} at the start: CPU seconds above idle ones)", fontsize=9)
    axs[0].legend(fontsize=7)
    names = ["setup [s]", "assembly [s]", "reduction [s]", "solver setup [s]", "CG [s]"]
    bottom = np.zeros(2)
    for k in names:
        vals = np.array([big["stages (CPU)"][p][k] for p in ("general", "structured")])
        axs[1].bar([0, 1], vals, bottom=bottom, label=k.replace(" [s]", ""))
        bottom += vals
    axs[1].set_xticks([0, 1], ["general (scikit-fem, RS AMG)", "structured (grid, GMG)"])
    axs[1].set_ylabel("process CPU [s]")
    axs[1].set_title("stages of one solve", fontsize=9)
    axs[1].legend(fontsize=7)
    _common.save_figure(fig, path)
    plt.close(fig)


# ------------------------------------------------------------------ 3. ROSS
def bench_ross(grids, repeats, reference, ross_python=None, memory_cap_gib=2.5):
    spec = {k: JOURNAL[k] for k in ("radius", "clearance", "length", "viscosity", "omega", "eccentricity_ratio")}
    if ross_python:
        args = json.dumps({"spec": spec, "grids": grids, "repeats": repeats, "memory_cap_gib": memory_cap_gib})
        proc = subprocess.run([ross_python, str(Path(_ross.__file__)), args], capture_output=True, text=True)
        try:
            out = json.loads(proc.stdout.strip().splitlines()[-1])
        except (IndexError, json.JSONDecodeError):
            out = {"available": False, "reason": f"{ross_python} failed: {proc.stderr.strip()[-500:]}"}
        out["ran in"] = ross_python
    else:
        out = _ross.run_grids(spec, grids, repeats, memory_cap_gib)
        out["ran in"] = sys.executable
    out["solver"] = "ross.bearings.fluid_flow.FluidFlow (finite differences, dense assembly, SuperLU, negative pressures clipped)"
    out["compared with"] = "lubedyn half_sommerfeld reference (same physics as ROSS's clipping)"
    out["memory cap for the dense matrix [GiB]"] = memory_cap_gib
    if out.get("available"):
        for p in out["points"]:
            p["error [-]"] = abs(p["load [N]"] - reference["load"]) / reference["load"]
            p["attitude error [deg]"] = abs(p["attitude [deg]"] - reference["attitude"])
            log.info("ROSS %3d x %3d: load %.6g N, attitude %.3f deg, error %.2e, %.2f s",
                     p["nz"], p["ntheta"], p["load [N]"], p["attitude [deg]"], p["error [-]"], p["time [s]"])
        pts = out["points"]
        if len(pts) >= 2:
            h = 1.0 / np.sqrt([p["nodes"] for p in pts])
            e = np.array([p["error [-]"] for p in pts])
            order = float(np.polyfit(np.log(h[-3:]), np.log(e[-3:]), 1)[0])
            out["fitted order (error vs 1/sqrt(nodes), last 3)"] = order
            # nodes ROSS would need for 1e-3 at that order, and its dense matrix
            if order > 0:
                nodes = pts[-1]["nodes"] * (e[-1] / 1e-3) ** (2.0 / order)
                out["extrapolated nodes for 1e-3"] = float(nodes)
                out["extrapolated dense matrix for 1e-3 [GiB]"] = 8.0 * nodes**2 / 2**30
            out["time to error [s]"] = _common.time_to_error([p["time [s]"] for p in pts], e)
    return out


def ross_matched(ross, half_sommerfeld):
    """lubedyn's time for the error of ROSS's finest grid, and the speed-up."""
    if not ross.get("available") or not ross.get("points"):
        return None
    best = min(ross["points"], key=lambda p: p["error [-]"])
    out = {"ROSS grid": f"{best['nz']} x {best['ntheta']}", "ROSS error [-]": best["error [-]"], "ROSS time [s]": best["time [s]"]}
    for element, series in half_sommerfeld["series"].items():
        pts = [p for p in series["points"] if not p.get("below reference uncertainty")]
        t = _common.time_to_error([p["time [s]"] for p in pts], [p["error [-]"] for p in pts], (best["error [-]"],))
        t = next(iter(t.values()))
        cheapest = min((p for p in pts if p["error [-]"] <= best["error [-]"]), key=lambda p: p["time [s]"], default=None)
        out[f"lubedyn {element}"] = {
            "time to that error [s] (interpolated)": t,
            "speed-up [-]": best["time [s]"] / t if t else None,
            "cheapest mesh at or below it": None if cheapest is None else
            {"mesh": f"{cheapest['nx']}x{cheapest['ny']}", "dofs": cheapest["dofs"], "error [-]": cheapest["error [-]"], "time [s]": cheapest["time [s]"]},
        }
    return out


# ------------------------------------------------------------------ chart
def plot(results, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker  # noqa: F401

    fig, axes = plt.subplots(2, 2, figsize=(12, 9.5), constrained_layout=True)
    colours = {"P1": "tab:blue", "P2": "tab:orange", "P2 curved": "tab:green", "P1 cold": "tab:blue", "P2 cold": "tab:orange"}

    def series(ax, pts, **kw):
        pts = [p for p in pts if not p.get("below reference uncertainty")]
        ax.loglog([p["time [s]"] for p in pts], [p["error [-]"] for p in pts], **kw)

    def band(ax, result, **kw):
        ref = result["reference load"]
        if ref.get("uncertainty"):
            ax.axhline(ref["uncertainty"] / abs(ref["value"]), lw=0.8, **kw)

    ax = axes[0, 0]
    for el, s in results["sphere"]["series"].items():
        name = "P2, mesh.disk(order=2) (curved)" if el == "P2 curved" else f"{el}, mesh.disk"
        series(ax, s["points"], marker="o", color=colours[el], label=f"{name} (order {s['fitted order (error vs 1/sqrt(dofs))']:.2f})")
    ax.set_title("(a) sphere-plane squeeze film vs closed form")

    ax = axes[0, 1]
    for el, s in results["journal_reynolds"]["series"].items():
        if el.endswith("cold"):
            series(ax, s["points"], marker="x", ls=":", color=colours[el], label=f"{el[:2]}, Reynolds, cold start (warm_start_levels=0)")
        else:
            series(ax, s["points"], marker="o", color=colours[el], label=f"{el}, Reynolds cavitation (default)")
    for el, s in results["journal_half_sommerfeld"]["series"].items():
        series(ax, s["points"], marker="s", ls="--", color=colours[el], mfc="none", label=f"{el}, half-Sommerfeld")
    band(ax, results["journal_reynolds"], color="k", ls=":", label="reference uncertainty (Reynolds)")
    band(ax, results["journal_half_sommerfeld"], color="grey", ls="-.", label="reference uncertainty (half-Sommerfeld)")
    ax.set_title("(b) journal L/D = 0.5, eps = 0.6, vs finest P2")

    ax = axes[1, 0]
    for el, s in results["journal_half_sommerfeld"]["series"].items():
        series(ax, s["points"], marker="s", color=colours[el], label=f"lubedyn {el}")
    ross = results.get("ross", {})
    if ross.get("available") and ross.get("points"):
        series(ax, ross["points"], marker="^", color="tab:red", label="ROSS FluidFlow (FD)")
        for p in ross["points"]:
            ax.annotate(f"{p['nz']}x{p['ntheta']}", (p["time [s]"], p["error [-]"]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
    else:
        ax.text(0.05, 0.05, "ROSS: " + str(ross.get("reason", "not run")), transform=ax.transAxes, fontsize=8, wrap=True)
    band(ax, results["journal_half_sommerfeld"], color="grey", ls="-.", label="reference uncertainty")
    ax.set_title("(c) journal, half-Sommerfeld: lubedyn vs ROSS")

    for ax in (axes[0, 0], axes[0, 1], axes[1, 0]):
        ax.set_xlabel("wall time [s] (mesh + solve + load)")
        ax.set_ylabel("relative load error [-]")
        ax.grid(True, which="both", alpha=0.3)
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.legend(fontsize=7, loc="upper right" if ax is axes[0, 1] else "best")

    ax = axes[1, 1]
    big = results["big"]
    phases = big.get("phases")
    if isinstance(phases, dict):
        names = [k.split(" (")[0].replace(" [s]", "") for k in phases]
        vals = list(phases.values())
        names.insert(0, "mesh build")
        vals.insert(0, big["mesh build [s]"])
        ax.barh(names, vals, color="tab:blue")
        for i, v in enumerate(vals):
            ax.text(v, i, f" {v:.2f} s", va="center", fontsize=8)
        ax.invert_yaxis()
    ax.axvline(big["target [s]"], color="k", ls=":", label="10 s target (assembly + solve)")
    ax.set_xlabel("wall time [s]")
    ax.set_title(f"(d) {big['dofs']:,} DOF P1 solve: solve() {big['solve [s]']:.1f} s\n{big['linear_solver']}", fontsize=9)
    ax.legend(fontsize=8, loc="lower right")

    m = results["machine"]
    fig.suptitle(
        f"lubedyn Reynolds benchmark ({results['mode']}) - {m['cpu'].get('model name')}, {m['cpus_available_to_process']} cpus, "
        f"numpy {m['packages']['numpy']}, scipy {m['packages']['scipy']}, scikit-fem {m['packages']['scikit-fem']}; "
        f"time unit {results['reference run']['median [s]'] * 1e3:.1f} ms",
        fontsize=9,
    )
    _common.save_figure(fig, path)
    plt.close(fig)


# ------------------------------------------------------------------ main
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (< 60 s)")
    ap.add_argument("--out", type=Path, default=_common.RESULTS, help="output directory")
    ap.add_argument("--repeats", type=int, default=None, help="timed repeats per point (median)")
    ap.add_argument("--skip-ross", action="store_true", help="do not run the ROSS comparison")
    ap.add_argument("--ross-python", default=os.environ.get("LUBEDYN_ROSS_PYTHON"),
                    help="run ROSS in a subprocess with this interpreter (another venv)")
    ap.add_argument("--ross-memory-cap", type=float, default=2.5, help="largest dense ROSS matrix [GiB]")
    ap.add_argument("--big-paths", action="store_true",
                    help="only scene 2b: the 1M-DOF solve on the structured and the general path, interleaved "
                         "(-> results/reynolds_big_paths.json, .png; with --quick at 300 x 300)")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(message)s")
    log.setLevel(logging.INFO)
    logging.getLogger("skfem").setLevel(logging.ERROR)  # "Transforming over 1000 vertices to C_CONTIGUOUS"
    if args.big_paths:
        cfg = SIZES["quick" if args.quick else "full"]
        results = {"benchmark": "reynolds big paths", "started": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
                   "machine": _common.machine_info()}
        clock = Clock()
        results["reference run"] = clock.describe()
        results["big paths"] = bench_big_paths(clock, cfg["big_n"], args.repeats or 3)
        results["machine"]["load_average_at_end"] = list(os.getloadavg())
        stem = "reynolds_big_paths_quick" if args.quick else "reynolds_big_paths"
        _common.write_json(args.out / f"{stem}.json", results)
        plot_big_paths(results, args.out / f"{stem}.png")
        log.info("wrote %s.json and .png", args.out / stem)
        return results
    mode = "quick" if args.quick else "full"
    cfg = SIZES[mode]
    repeats = args.repeats or cfg["repeats"]
    t_start = time.perf_counter()

    results = {"benchmark": "reynolds", "mode": mode, "repeats": repeats,
               "started": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
               "machine": _common.machine_info(extra_packages=("ross-rotordynamics", "plotly"))}
    clock = Clock()
    results["reference run"] = clock.describe()
    log.info("reference run: %.4f s (%d dofs)", clock.seconds, clock.dofs)

    results["sphere"] = bench_sphere(clock, cfg["sphere"], repeats)
    results["journal_reynolds"] = bench_journal(clock, cfg["journal"], repeats, "reynolds")
    jr = results["journal_reynolds"]
    jr["series"].update(bench_journal_cold(clock, cfg["journal"], repeats, "reynolds", jr["reference load"]["value"],
                                           jr["reference load"]["uncertainty"] or 0.0, jr["reference attitude"]["value"]))
    results["journal_half_sommerfeld"] = bench_journal(clock, cfg["journal"], repeats, "half_sommerfeld")
    hs = results["journal_half_sommerfeld"]
    ref = {"load": hs["reference load"]["value"], "attitude": hs["reference attitude"]["value"]}
    if args.skip_ross:
        results["ross"] = {"available": False, "reason": "skipped (--skip-ross)"}
    else:
        results["ross"] = bench_ross(cfg["ross_grids"], repeats, ref, args.ross_python, args.ross_memory_cap)
        results["ross"]["lubedyn at ROSS's best accuracy"] = ross_matched(results["ross"], hs)
    results["big"] = bench_big(clock, cfg["big_n"], repeats)

    results["machine"]["load_average_at_end"] = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    results["total wall time [s]"] = time.perf_counter() - t_start
    stem = "reynolds_quick" if args.quick else "reynolds"  # a quick run never overwrites the full results
    out_json = _common.write_json(args.out / f"{stem}.json", results)
    plot(results, args.out / f"{stem}.png")
    log.info("wrote %s and %s in %.0f s", out_json, args.out / f"{stem}.png", results["total wall time [s]"])
    return results


if __name__ == "__main__":
    main()
