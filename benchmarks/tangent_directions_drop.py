"""Per-direction tangent-space Lyapunov exponents of the 10,000 rpm rotor drop (paper B, Table 3), members in
chunks that resume from their checkpoints.

    python benchmarks/tangent_directions_drop.py run OUT --seed 1 [--case cageless_6206_10krpm]
        [--transient 20ms] [--total 200ms] [--chunk 2ms]
    python benchmarks/tangent_directions_drop.py report OUT [--rel 0.1]

``run`` integrates one member (``initial.seed`` = SEED with the study's ensemble: ``initial.jitter`` 0.5 deg,
``initial.kick`` 1 mm/s) from the quasi-static start with Benettin's RK4 (the transient aligns the first
tangent vector and is discarded), then advances the averaging in chunks, saving the run's state, tangent
basis and projections after each (``OUT/member_SEED.npz``): run it again and it continues.  ``report``
reads every member and writes ``OUT/report.json``: per direction (all balls and ball 0) the members'
exponents [1/s] and [bits/s], their mean and standard deviation, lambda T, shares and the run-length rule
(:func:`lubedyn.dynamics.tangent_directions.run_length`), and each member's CPU time.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from lubedyn.config import load_case
from lubedyn.dynamics.cageless import rhs
from lubedyn.dynamics.tangent_directions import BITS, BallDirections, TangentDirections, run_length, window_exponents
from lubedyn.scenes.dynamics import build
from lubedyn.scenes.dynamics_lyapunov import bearing_tangent_directions
from lubedyn.units import parse_quantity

ENSEMBLE = ("initial.jitter='0.5 deg'", "initial.kick='1 mm/s'")


def _model(case_name, seed):
    case = load_case(case_name, overrides=list(ENSEMBLE) + [f"initial.seed={seed}"])
    return build(case, None)


def run(out: Path, seed: int, case_name: str, transient: float, total: float, chunk: float):
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"member_{seed}.npz"
    setup = _model(case_name, seed)
    model = setup.model
    cpu0 = time.process_time()
    if path.exists():
        td = TangentDirections.load(path, rhs, model.args(), BallDirections(model.state_layout(), model.state_scales()))
        meta = json.loads((out / f"member_{seed}.json").read_text())
    else:
        td = bearing_tangent_directions(model, setup.y0, 0.0, t_transient=transient)
        meta = {"seed": seed, "case": case_name, "cpu [s]": 0.0, "transient [s]": transient}
    while True:
        done = len(td._log_p) * td.run.interval
        if done >= total - 1e-12:
            break
        td.advance(min(chunk, total - done))
        res = td.result()
        meta["cpu [s]"] += time.process_time() - cpu0
        cpu0 = time.process_time()
        meta.update({"averaging time [s]": res.averaging_time, "lambda_1 [1/s]": res.largest,
                     "exponents [1/s]": dict(zip(res.names, map(float, res.exponents))),
                     "share [-]": dict(zip(res.names, map(float, res.share))), "max bound [1/s]": list(res.max_bound),
                     "dt [s]": td.run.dt, "interval [s]": td.run.interval})
        td.save(path)
        np.savez(out / f"member_{seed}_running.npz", times=res.times, running=res.running,
                 running_largest=res.running_largest, names=np.array(res.names))
        (out / f"member_{seed}.json").write_text(json.dumps(meta, indent=1))
        print(f"seed {seed}: T = {res.averaging_time * 1e3:.1f} ms, lambda_1 = {res.largest:.1f} 1/s, "
              f"cpu {meta['cpu [s]']:.0f} s", flush=True)


def report(out: Path, rel: float, window: float = 0.25):
    members = sorted(out.glob("member_*_running.npz"))
    runs = [np.load(p) for p in members]
    metas = [json.loads(p.with_name(p.name.replace("_running.npz", ".json")).read_text()) for p in members]
    q = min(r["times"].size for r in runs)
    times = runs[0]["times"][:q]
    names = [str(n) for n in runs[0]["names"]]
    T = float(times[-1])
    rows = {}
    for i, name in enumerate(names + ["lambda_1 (first vector)"]):
        if not (name.startswith("ball 0 ") or name.endswith("(all balls)") or name.startswith("lambda_1")):
            continue
        R = np.array([r["running_largest"][:q] if name.startswith("lambda_1") else r["running"][:q, i] for r in runs])
        lam = R[:, -1]
        row = {"members [1/s]": lam.tolist(), "mean [1/s]": float(lam.mean()), "mean [bits/s]": float(lam.mean() * BITS),
               "std over members [1/s]": float(lam.std(ddof=1)) if lam.size > 1 else None,
               "lambda T (mean) [-]": float(lam.mean() * T)}
        if not name.startswith("lambda_1"):
            row["share (mean) [-]"] = float(np.mean([m["share [-]"][name] for m in metas]))
        ends, local = window_exponents(times, R, window)
        row["window ends [s]"] = ends.tolist()
        row["window exponents, members [1/s]"] = local.tolist()
        if lam.size > 1:
            rule = run_length(times, R, rel=rel, window=window)
            row.update({"run length for rel [s]": rule.required, "run length for rel, member mean [s]": rule.required_mean,
                        "run length, a c fit [s]": rule.required_fit, "spread slope [-]": rule.slope,
                        "run length note": rule.note, "c from windows [1/sqrt(s)]": rule.c_windows,
                        "run length for rel, from windows [s]": rule.required_windows,
                        "run length for rel, from windows, member mean [s]": rule.required_windows / rule.members,
                        "a [-]": rule.a, "c [1/sqrt(s)]": rule.c})
        rows[name] = row
    summary = {"averaging time [s]": T, "members": [m["seed"] for m in metas], "rel": rel,
               "cpu per member [s]": [m["cpu [s]"] for m in metas],
               "cpu per simulated second [s/s]": [m["cpu [s]"] / (m["averaging time [s]"] + m["transient [s]"])
                                                  for m in metas],
               "max bound per member [1/s]": [m["max bound [1/s]"] for m in metas], "directions": rows}
    (out / "report.json").write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary, indent=1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("out", type=Path)
    r.add_argument("--seed", type=int, required=True)
    r.add_argument("--case", default="cageless_6206_10krpm")
    r.add_argument("--transient", default="20 ms")
    r.add_argument("--total", default="200 ms")
    r.add_argument("--chunk", default="2 ms")
    p = sub.add_parser("report")
    p.add_argument("out", type=Path)
    p.add_argument("--rel", type=float, default=0.1)
    p.add_argument("--window", default="0.25 s")
    a = ap.parse_args()
    if a.cmd == "run":
        run(a.out, a.seed, a.case, parse_quantity(a.transient, "time"), parse_quantity(a.total, "time"),
            parse_quantity(a.chunk, "time"))
    else:
        report(a.out, a.rel, parse_quantity(a.window, "time"))


if __name__ == "__main__":
    main()
