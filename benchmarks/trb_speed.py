"""Speed of the tapered roller bearing's dynamics (issue 42, decisions 3, 4 and 8): the right-hand side
against its per-contact floor, and the stiff raceway traction treated linearly implicitly (ROSW:
ROS34PW2 with the traction's per-roller 6 x 6 Jacobian as W, ``integrator.method = "rosw"``) against
RK4 at its automatic step, on cases/trb_fig5_2400rpm.toml (the limited traction, 10 slices).

1. Right-hand side: CPU seconds per call at the start state (best of 7 x 1,000 calls) of ``rhs`` and of
   ``rhs_w`` (with W), per contact evaluation (17 rollers x 10 slices x 2 raceways, flanges, pockets,
   land) against a floor of 10 ns per contact; with ``--before-python`` the same measurement under
   another checkout's interpreter (the code before this change), interleaved with this one in
   subprocesses.
2. Which term sets RK4's step: the model's closed-form rates and the right-hand side's own spectrum
   with the traction (the default) and without it, and ROSW's step (the spectrum of J - W).
3. Work and precision on ``--short`` (10 ms, means over its second half): RK4 at its automatic step and
   ROSW at 20/3, 5, 4, 2.5 us against RK4 at half its step.
4. Paper A's 0.18 s of Fig. 5 (``--duration``): RK4 "auto" and ROSW "auto", interleaved (``--repeats``),
   steps, integration wall and CPU seconds, the means' difference, every time also as a ratio to a
   reference loop timed in the same process.

Writes ``results/trb_speed.json`` and ``results/trb_speed.png`` with the machine noted.  Other jobs share
the cores: CPU seconds and ratios are the figures to compare, never absolute wall time.  Speed is
measured here, never asserted in tests.

    python benchmarks/trb_speed.py [--quick] [--before-python /path/to/old/.venv/bin/python]
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]
_spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
_common = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_common)
_spec = importlib.util.spec_from_file_location("_trb", _HERE / "trb.py")
_trb = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_trb)
RESULTS, machine_info, write_json, save_figure = (_common.RESULTS, _common.machine_info, _common.write_json,
                                                  _common.save_figure)
FLOOR_PER_CONTACT = 10e-9  # [s], issue 42's floor
SAMPLE = 20e-6             # the case's sample interval [s]


def _reference_loop():
    """A fixed numba loop (2e6 square roots) whose CPU time is the unit of the ratios."""
    from numba import njit

    @njit(cache=False)
    def loop(n):
        s = 0.0
        for i in range(n):
            s += math.sqrt(i + 1.0)
        return s

    loop(10)

    def run():
        t0 = time.process_time()
        loop(2_000_000)
        return time.process_time() - t0
    return run


def rhs_cost(repeats: int = 7, calls: int = 1000) -> dict:
    """CPU seconds per call of rhs (and rhs_w, when this checkout has it) at the start state of Fig. 5's
    case, best of ``repeats``, with the reference loop's CPU seconds measured alongside."""
    from lubedyn.dynamics.tapered import kernels as K
    from lubedyn.scenes import tapered as S

    model = S.build(_trb._case(0.001))
    qs = model.quasi_static()
    args, y0 = model.args(qs), model.start_state(qs)
    d = np.empty_like(y0)
    K.rhs(0.0, y0, args, d)
    ref = _reference_loop()
    out = {"reference loop [s]": [], "rhs [s]": []}
    has_w = hasattr(K, "rhs_w")
    if has_w:
        Z = model.n_rollers
        Jb, idx = np.zeros((Z, 6, 6)), np.zeros((Z, 6), dtype=np.int64)
        K.rhs_w(0.0, y0, args, d, Jb, idx)
        out["rhs_w [s]"] = []
    for _ in range(repeats):
        out["reference loop [s]"].append(ref())
        t0 = time.process_time()
        for _ in range(calls):
            K.rhs(0.0, y0, args, d)
        out["rhs [s]"].append((time.process_time() - t0) / calls)
        if has_w:
            t0 = time.process_time()
            for _ in range(calls):
                K.rhs_w(0.0, y0, args, d, Jb, idx)
            out["rhs_w [s]"].append((time.process_time() - t0) / calls)
    loads, SL, FR, CG, FC = K.forces_many(y0[None, :], args)
    Z, ns = model.n_rollers, model.n_slices
    contacts = Z * ns * 2 + Z + 2 * Z + 1
    best = {k: min(v) for k, v in out.items()}
    res = {"best CPU [s]": best, "contact evaluations [-]": contacts,
           "loaded slices [-]": int((SL[0] > 0).sum()),
           "rhs per contact [s]": best["rhs [s]"] / contacts,
           "rhs / floor (10 ns per contact) [-]": best["rhs [s]"] / (contacts * FLOOR_PER_CONTACT),
           "rhs / reference loop [-]": best["rhs [s]"] / best["reference loop [s]"]}
    if has_w:
        res["rhs_w / rhs [-]"] = best["rhs_w [s]"] / best["rhs [s]"]
    return res


def rhs_before_after(before_python: str, rounds: int = 3) -> dict:
    """The RHS measurement under ``before_python`` (another checkout's interpreter: the code before) and
    this interpreter, in subprocesses, interleaved ``rounds`` times."""
    rows = {"before": [], "after": []}
    for _ in range(rounds):
        for name, py in (("before", before_python), ("after", sys.executable)):
            text = subprocess.run([py, str(Path(__file__).resolve()), "--rhs-only"], capture_output=True, text=True,
                                  check=True, cwd="/tmp").stdout
            rows[name].append(json.loads(text.strip().splitlines()[-1]))
    out = {}
    for name, runs in rows.items():
        out[name] = {"rhs [s]": min(r["best CPU [s]"]["rhs [s]"] for r in runs),
                     "rhs / reference loop [-]": min(r["rhs / reference loop [-]"] for r in runs),
                     "runs": runs}
    out["after / before (reference-loop ratios) [-]"] = (out["after"]["rhs / reference loop [-]"]
                                                         / out["before"]["rhs / reference loop [-]"])
    return out


def step_limits() -> dict:
    """Which term sets RK4's step: the closed-form bounds, the spectral step with and without the traction,
    and ROSW's (J - W)."""
    from lubedyn.dynamics.integrators import stability_limit
    from lubedyn.scenes import tapered as S

    out = {}
    for name, over in (("limited traction (default)", []), ("no raceway traction", ["model.traction=none"])):
        model = S.build(_trb._case(0.001, *over))
        qs = model.quasi_static()
        args, y0 = model.args(qs), model.start_state(qs)
        rate = model.traction_rate(qs, args)
        row = {"contact modes 2 sqrt(2)/omega_max [s]": stability_limit("rk4") / model.omega_max(),
               "traction decay rate [1/s]": rate,
               "traction 2.785/rate [s]": stability_limit("rk4", "real") / rate if rate > 0 else None,
               "RK4 spectral step [s]": model.spectral_step(y0, args),
               "RK4 stable-step estimate [s]": model.stable_step(qs, y0, args)}
        if name.startswith("limited"):
            row["ROSW stable-step estimate (J - W) [s]"] = model.stable_step(qs, y0, args, "rosw")
        out[name] = row
    return out


def _run(duration, *over):
    """One scene run: the summary's means, steps and integration wall time, and the run's CPU seconds."""
    from lubedyn.scenes import tapered as S

    c0 = time.process_time()
    s = S.run(_trb._case(duration, *over)).summary
    cpu = time.process_time() - c0
    step = s.get("RK4 step [s]", s.get("ROSW step [s]"))
    return {"step [s]": step, "steps": s.get("Accepted steps [-]"), "integration wall [s]": s["Integration wall time [s]"],
            "run CPU [s]": cpu, **_trb._means(s)}


KEYS = ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]", "Roller slip, loaded zone, mean [-]",
        "Cage speed, mean [rpm]")


def _rel(a, b):
    return {k: abs(a[k] / b[k] - 1.0) for k in KEYS}


def work_precision(duration: float, ref_loop) -> dict:
    """RK4 auto and ROSW at fixed steps against RK4 at half its automatic step over ``duration``."""
    runs = {"RK4 auto": _run(duration, "integrator.method=rk4")}
    half = SAMPLE / (2 * round(SAMPLE / runs["RK4 auto"]["step [s]"]))
    runs["RK4 half step (reference)"] = _run(duration, "integrator.method=rk4", f"integrator.dt={half!r}")
    for n in (3, 4, 5, 8):
        runs[f"ROSW {SAMPLE / n * 1e6:.3g} us"] = _run(duration, "integrator.method=rosw", f"integrator.dt={SAMPLE / n!r}")
    ref = runs["RK4 half step (reference)"]
    unit = ref_loop()
    for name, r in runs.items():
        r["relative error of the means"] = _rel(r, ref)
        r["run CPU / reference loop [-]"] = r["run CPU [s]"] / unit
    return {"simulated time [s]": duration, "reference loop [s]": unit, "runs": runs}


def paper_window(duration: float, repeats: int, ref_loop) -> dict:
    """0.18 s of Fig. 5: RK4 auto and ROSW auto, interleaved ``repeats`` times."""
    rows = {"RK4 auto": [], "ROSW auto": []}
    units = []
    for _ in range(repeats):
        for name, method in (("RK4 auto", "rk4"), ("ROSW auto", "rosw")):
            units.append(ref_loop())
            rows[name].append(_run(duration, f"integrator.method={method}"))
    units.append(ref_loop())
    unit = min(units)
    out = {"simulated time [s]": duration, "reference loop [s]": unit, "runs": rows}
    best = {name: min(r, key=lambda x: x["run CPU [s]"]) for name, r in rows.items()}
    out["best"] = {name: {"steps": b["steps"], "step [s]": b["step [s]"], "integration wall [s]": b["integration wall [s]"],
                          "run CPU [s]": b["run CPU [s]"], "run CPU / reference loop [-]": b["run CPU [s]"] / unit}
                   for name, b in best.items()}
    out["ROSW / RK4 run CPU [-]"] = best["ROSW auto"]["run CPU [s]"] / best["RK4 auto"]["run CPU [s]"]
    out["relative difference of the means (ROSW auto vs RK4 auto)"] = _rel(best["ROSW auto"], best["RK4 auto"])
    return out


def _chart(data):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.6))
    wp = data["work and precision"]
    for name, r in wp["runs"].items():
        if "reference" in name:
            continue
        e = max(r["relative error of the means"]["Tilt, loaded zone, mean [rad]"], 1e-9)
        a.loglog(r["run CPU / reference loop [-]"], e, "s" if name.startswith("RK4") else "o", label=name)
    a.set_xlabel("run CPU / reference loop [-]")
    a.set_ylabel("relative error of the mean loaded-zone tilt")
    a.set_title(f"{wp['simulated time [s]'] * 1e3:g} ms of Fig. 5 against RK4 at half its step", fontsize=9)
    a.legend(fontsize=7)
    rhs = data["right-hand side"]
    labels, values = ["rhs", "10 ns x contacts"], [rhs["best CPU [s]"]["rhs [s]"] * 1e6,
                                                    rhs["contact evaluations [-]"] * FLOOR_PER_CONTACT * 1e6]
    if "rhs_w [s]" in rhs["best CPU [s]"]:
        labels.insert(1, "rhs_w")
        values.insert(1, rhs["best CPU [s]"]["rhs_w [s]"] * 1e6)
    if "before/after" in data:
        labels.insert(0, "rhs before")
        values.insert(0, data["before/after"]["before"]["rhs [s]"] * 1e6)
    b.bar(labels, values)
    b.set_ylabel("CPU per call [us] (shared cores: see the ratios in the JSON)")
    b.set_title("right-hand side at Fig. 5's start state (10 slices)", fontsize=9)
    m = data["machine"]
    fig.suptitle(f"{m.get('cpu', {}).get('model name', '')} ({m.get('logical_cpus', '')} logical CPUs)", fontsize=8)
    fig.tight_layout()
    save_figure(fig, RESULTS / "trb_speed.png")
    plt.close(fig)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=0.18, help="simulated time of the paper window [s]")
    ap.add_argument("--short", type=float, default=0.01, help="simulated time of the work-precision runs [s]")
    ap.add_argument("--repeats", type=int, default=2, help="interleaved repeats of the paper-window runs")
    ap.add_argument("--before-python", default=None, help="interpreter of a checkout with the code before")
    ap.add_argument("--quick", action="store_true", help="20 ms windows, one repeat")
    ap.add_argument("--rhs-only", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.rhs_only:
        return rhs_cost()
    if a.quick:
        a.duration, a.short, a.repeats = 0.02, 0.005, 1
    ref_loop = _reference_loop()
    for method in ("rk4", "rosw"):  # compile (or load) both integrators' kernels before anything is timed
        _run(0.001, f"integrator.method={method}")
    data = {"machine": machine_info(), "case": "cases/trb_fig5_2400rpm.toml", "reference loop at start [s]": ref_loop()}
    data["right-hand side"] = rhs_cost()
    if a.before_python:
        data["before/after"] = rhs_before_after(a.before_python)
    data["step limits"] = step_limits()
    data["work and precision"] = work_precision(a.short, ref_loop)
    data["paper window"] = paper_window(a.duration, a.repeats, ref_loop)
    data["reference loop at end [s]"] = ref_loop()
    write_json(RESULTS / "trb_speed.json", data)
    _chart(data)
    return data


if __name__ == "__main__":
    out = main()
    print(json.dumps({k: v for k, v in out.items() if k != "machine"}, default=str))
