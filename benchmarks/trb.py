"""Paper A's tapered roller bearing in time: what each fidelity option costs and what
it changes, and how accuracy trades against wall time for DOPRI5 and RK4.

On cases/trb_fig5_2400rpm.toml (Fr 20 kN, 2,400 rpm, axial locked, polyurea, 10 slices) over ``T``
(default 20 ms; the summary's window is its second half, loaded zone):

1. cost of one right-hand side per option (2,000 calls at the start state, warm), as a ratio to the
   default's in the same process;
2. work-precision: mean loaded-zone skew and tilt, and the cage speed, from DOPRI5 at rtol 1e-6..1e-8 and
   RK4 at 1, 1/2, 1/4 x the model's stable step estimate, against DOPRI5 at rtol 1e-9 (the reference);
3. fidelity: the same means for each option (traction paper / limited at G = 0.1, 0.3, 1 GPa; pocket and
   land contact-only / film; flange friction none / paper; 5, 10, 20 slices) and their wall times.

Writes ``results/trb.json`` and ``results/trb.png`` with the machine noted.  Speed is measured here, never
asserted in tests.  ``python benchmarks/trb.py [--duration 20ms] [--quick]`` (quick: 5 ms, fewer points).
"""
from __future__ import annotations

import argparse
import importlib.resources
import importlib.util
import math
import sys
import time
from pathlib import Path

import numpy as np

_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]
_spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
_common = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_common)
RESULTS, ROOT, machine_info, write_json = _common.RESULTS, _common.ROOT, _common.machine_info, _common.write_json

CASE = Path(importlib.resources.files("lubedyn.cases")) / "trb_fig5_2400rpm.toml"
OPTIONS = {
    "default (limited G 1 GPa, film cage, flange paper, 10 slices)": [],
    "traction paper (eq. 12)": ["model.traction=paper"],
    "traction limited, G 0.3 GPa": ["lubricant.shear_modulus=0.3 GPa"],
    "traction limited, G 0.1 GPa": ["lubricant.shear_modulus=0.1 GPa"],
    "pocket and land contact only": ["model.pocket=contact", "model.guide_land=contact"],
    "flange friction none": ["model.flange_friction=none"],
    "5 slices": ["model.slices=5"],
    "20 slices": ["model.slices=20"],
    "traction by quadrature (no table)": ["model.traction_evaluation=quadrature"],
    "cone tilt free, load 10 mm off": ["operating.cone_tilt=free", "operating.load_offset=10 mm"],
    "traction from the roller EHL maps": ["model.traction=map"],
}


def _case(duration, *overrides):
    from lubedyn.config import load_case

    half = 0.5 * duration
    return load_case(CASE, overrides=[f"integrator.duration={duration}", f"analysis.window=[{half}, {duration}]",
                                      "output.write=[]", *overrides])


def _means(summary):
    """The summary's headline means (its top-level keys, from the window _case asks for)."""
    keys = ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]", "Roller slip, loaded zone, mean [-]",
            "Skew periodicity [-]")
    return {**{k: summary[k] for k in keys},
            "Cage speed, mean [rpm]": summary["Paper window (analysis.window)"]["Cage speed, mean [rpm]"]}


def _run(duration, *overrides):
    from lubedyn.scenes import tapered as S

    t0 = time.perf_counter()
    s = S.run(_case(duration, *overrides)).summary
    return {"wall [s]": time.perf_counter() - t0, "integration [s]": s["Integration wall time [s]"],
            "steps": s.get("Accepted steps [-]"), **_means(s)}


def rhs_costs():
    from lubedyn.scenes import tapered as S
    from lubedyn.dynamics.tapered import kernels as K

    out = {}
    for name, over in OPTIONS.items():
        model = S.build(_case(0.02, *over))
        args, y0 = model.args(), model.start_state()
        d = np.empty_like(y0)
        K.rhs(0.0, y0, args, d)
        t0 = time.perf_counter()
        for _ in range(2000):
            K.rhs(0.0, y0, args, d)
        out[name] = (time.perf_counter() - t0) / 2000
    base = out[next(iter(OPTIONS))]
    return {k: {"rhs [s]": v, "ratio to default [-]": v / base} for k, v in out.items()}


def slice_convergence(counts=(5, 10, 20, 40, 80), duration=0.005) -> dict:
    """Slice convergence: the loaded-zone mean skew and tilt over the second half of 5 ms
    of Fig. 5's point (RK4 auto, traction table) against the slice count, the differences between
    successive counts and the observed order log2(d_n / d_2n)."""
    from lubedyn.scenes import tapered as S
    from lubedyn.config import load_case

    rows = {}
    for n in counts:
        s = S.run(load_case(CASE, overrides=[f"model.slices={n}", f"integrator.duration={duration}",
                                             f"analysis.window=[{duration / 2}, {duration}]", "output.write=[]",
                                             "model.traction_evaluation=table"])).summary
        rows[n] = {"Skew, loaded zone, mean [rad]": s["Skew, loaded zone, mean [rad]"],
                   "Tilt, loaded zone, mean [rad]": s["Tilt, loaded zone, mean [rad]"],
                   "integration [s]": s["Integration wall time [s]"]}
    orders = {}
    for key in ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]"):
        v = [rows[n][key] for n in counts]
        d = [b - a for a, b in zip(v, v[1:])]
        orders[key] = {"differences": d, "observed orders": [math.log2(abs(a / b)) if b else None for a, b in zip(d, d[1:])],
                       "relative change from the finest": [abs(x / v[-1] - 1) for x in v]}
    out = {"machine": machine_info(), "case": f"cases/{CASE.name}", "simulated time [s]": duration,
           "slices": rows, "convergence": orders}
    write_json(RESULTS / "trb_slices.json", out)
    return out


#: the runs of :func:`target`: the limited traction by quadrature and by table, the EHL maps' traction
#: ("map"), and the map run at half its automatic step (its step error)
TARGET_RUNS = {"quadrature": ["model.traction_evaluation=quadrature"],
               "table": ["model.traction_evaluation=table"],
               "map": ["model.traction=map"]}


def target() -> dict:
    """The speed target of the tapered bearing, 0.18 s (paper A's run) of the full 17-roller model at
    converged accuracy in under 10 s warm on one core: RK4 at the 'auto' step (0.8 x the stable-step estimate; RK4 converges at order 3.6-3.9 there,
    tests/test_trb_scene.py) with the limited traction by quadrature and by table, and with the roller EHL
    maps' traction ("map"); the order quadrature, table, map, quadrature, table, map after a warm-up run;
    the map once more at half its step (its step error); the means over the paper's window."""
    from lubedyn.scenes import tapered as S
    from lubedyn.config import load_case

    def once(over):
        case = load_case(CASE, overrides=["integrator.duration=0.18", "output.write=[]", *over])
        t0 = time.perf_counter()
        s = S.run(case).summary
        return {"wall [s]": time.perf_counter() - t0, "integration [s]": s["Integration wall time [s]"],
                "steps": s.get("Accepted steps [-]"), "RK4 step [s]": s.get("RK4 step [s]"), **_means(s)}

    for over in TARGET_RUNS.values():                                                           # compile
        S.run(load_case(CASE, smoke=True, overrides=list(over)))
    runs = {f"{how} #{i}": once(over) for i in (1, 2) for how, over in TARGET_RUNS.items()}
    half = 0.5 * float(runs["map #1"]["RK4 step [s]"])
    runs["map, half step"] = once([*TARGET_RUNS["map"], f"integrator.dt={half!r}"])
    best = {how: min(r["integration [s]"] for k, r in runs.items() if k.split(" #")[0] == how) for how in TARGET_RUNS}
    q, t = runs["quadrature #1"], runs["table #1"]
    keys = ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]", "Roller slip, loaded zone, mean [-]",
            "Cage speed, mean [rpm]")
    m, mh = runs["map #1"], runs["map, half step"]
    out = {"machine": machine_info(), "case": f"cases/{CASE.name}", "simulated time [s]": 0.18,
           "runs": runs, "best integration time [s]": best, "speed-up of the table [-]": best["quadrature"] / best["table"],
           "speed-up of the map over the table [-]": best["table"] / best["map"],
           "relative difference of the means (table vs quadrature)": {
               k: abs(t[k] - q[k]) / max(abs(q[k]), 1e-30) for k in keys},
           "relative step error of the map's means (auto vs half step)": {
               k: abs(m[k] - mh[k]) / max(abs(mh[k]), 1e-30) for k in keys},
           "target [s]": 10.0}
    write_json(RESULTS / "trb_target.json", out)
    return out


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=0.02, help="simulated time [s]")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--target", action="store_true",
                    help="only the paper's window: 0.18 s of Fig. 5's point with RK4 at the 'auto' step, the limited "
                         "traction by quadrature and by table, the maps' traction (results/trb_target.json)")
    ap.add_argument("--slices", action="store_true",
                    help="only the slice convergence of the mean skew and tilt (5-80 slices, 5 ms; results/trb_slices.json)")
    a = ap.parse_args(argv)
    if a.target:
        return target()
    if a.slices:
        return slice_convergence()
    T = 0.005 if a.quick else a.duration
    from lubedyn.scenes import tapered as S

    est = S.build(_case(T)).stable_step()
    out = {"machine": machine_info(), "case": f"cases/{CASE.name}", "simulated time [s]": T,
           "RK4 stable step estimate [s]": est, "rhs cost": rhs_costs()}
    ref = _run(T, "integrator.method=dopri5", "integrator.rtol=1e-9", "integrator.atol=1e-14")
    out["reference (DOPRI5 rtol 1e-9)"] = ref
    wp = {}
    for rtol in ((1e-6, 1e-7) if a.quick else (1e-6, 1e-7, 1e-8)):
        wp[f"DOPRI5 rtol {rtol:g}"] = _run(T, "integrator.method=dopri5", f"integrator.rtol={rtol}")
    for f in ((1.0, 0.5) if a.quick else (1.0, 0.5, 0.25)):
        wp[f"RK4 dt {f:g} x estimate"] = _run(T, "integrator.method=rk4", f"integrator.dt={f * est}")
    keys = ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]", "Cage speed, mean [rpm]")
    for r in wp.values():
        for k in keys:
            r[k.replace(", mean", ", error of the mean")] = abs(r[k] - ref[k]) / max(abs(ref[k]), 1e-30)
    out["work-precision"] = wp
    fid = {}
    for name, over in OPTIONS.items():
        fid[name] = _run(T, "integrator.method=dopri5", *over)
    out["fidelity (DOPRI5 rtol 1e-7)"] = fid
    write_json(RESULTS / "trb.json", out)
    _chart(out)
    return out


def _chart(out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.6))
    for name, r in out["work-precision"].items():
        a.loglog(r["integration [s]"], max(r["Skew, loaded zone, error of the mean [rad]"], 1e-12), "o" if "DOPRI5"
                 in name else "s", label=name)
    a.set_xlabel("integration wall time [s]")
    a.set_ylabel("relative error of the mean loaded-zone skew")
    a.set_title(f"work-precision, {out['simulated time [s]'] * 1e3:g} ms of Fig. 5's point")
    a.legend(fontsize=7)
    names = list(out["fidelity (DOPRI5 rtol 1e-7)"])
    fid = out["fidelity (DOPRI5 rtol 1e-7)"]
    x = [fid[n]["integration [s]"] for n in names]
    y = [fid[n]["Skew, loaded zone, mean [rad]"] for n in names]
    b.semilogx(x, y, "o")
    for xi, yi, n in zip(x, y, names):
        b.annotate(n.split(" (")[0], (xi, yi), fontsize=7, xytext=(3, 3), textcoords="offset points")
    b.set_xlabel("integration wall time [s] (DOPRI5 rtol 1e-7)")
    b.set_ylabel("mean loaded-zone skew [rad]")
    b.set_title("fidelity options: cost against effect")
    m = out["machine"]
    fig.suptitle(f"{m.get('cpu', '')} ({m.get('logical_cpus', '')} logical CPUs)", fontsize=8)
    fig.tight_layout()
    fig.savefig(RESULTS / "trb.png", dpi=110)


if __name__ == "__main__":
    import json

    r = main()
    print(json.dumps({k: v for k, v in r.items() if k != "machine"}, indent=1, default=str))
