"""Paper A's tapered bearing with the raceway films from the grease's EHL solve
(``lubricant.raceway_film = "grease_ehl"``) against Dowson-Toyoda with the base oil ("formula").

1. ``runs``: the plastic-viscosity study's point (cases/trb_grease_fa15kN.toml: Fa 15 kN, Fr 0, 2,800 rpm;
   tau_y 351.8 Pa and n 0.7196 held, studies/trb_plastic_viscosity.toml) at phi0 = 2.44 and 38.44 Pa s^n,
   each under "formula" and "grease_ehl", over ``--duration`` (default 60 ms; the summary's window is
   the last cage revolution): the headline means (skew, tilt, roller slip per zone, cage slip), the
   raceway films and factors, the build time and the EHL solves' wall time;
2. ``factors``: how far one load's factor h_EHL/h_DT carries to the lighter rollers of an orbit: the
   grease's EHL film (the scene's solve, :func:`lubedyn.scenes.tapered.grease_ehl_film`) at 1, 0.6 and
   0.3 times the most loaded roller's line load, on 257 and 513 nodes ("default", "fine"), per raceway.

3. ``cost``: 0.18 s of Fig. 5's point (cases/trb_fig5_2400rpm.toml, polyurea) with the grease's raceway films
   ("grease_ehl") against the default ("formula"), interleaved in one process (default, grease, default,
   grease; the scene's per-process cache of the EHL solves cleared before each run, so each grease run pays
   them): build, integration and run wall times, RK4 steps, and the ratio grease/default of the fastest of
   each (the cost the grease films add: their EHL solves at the start, and any change of the stable step).

Writes ``results/trb_raceway_film.json``.  ``nice -n 10 python benchmarks/trb_raceway_film.py runs
[--duration 60ms] [--phi 2.44 38.44]`` / ``... factors [--phi 8.44]`` / ``... cost [--duration 180ms]``.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import sys
import time
from pathlib import Path

_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]
_spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
_common = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_common)
RESULTS, machine_info, write_json = _common.RESULTS, _common.machine_info, _common.write_json

KEYS = ("Skew, loaded zone, mean [rad]", "Skew, unloaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]",
        "Tilt, unloaded zone, mean [rad]", "Roller slip, loaded zone, mean [-]", "Roller slip, unloaded zone, mean [-]",
        "Cage slip, mean [-]", "Averaged over", "Build time [s]", "Integration wall time [s]", "RK4 step [s]")
FILMS = "Raceway films (lubricant.raceway_film = 'grease_ehl')"


def _grease(phi: float) -> list[str]:
    return ["lubricant.grease=custom", "lubricant.yield_stress='351.8 Pa'", f"lubricant.consistency={phi}",
            "lubricant.exponent=0.7196"]


def runs(duration: str, phis) -> dict:
    import lubedyn
    from lubedyn.scenes import tapered as S

    out = {}
    for phi in phis:
        for film in ("formula", "grease_ehl"):
            case = lubedyn.load_case("trb_grease_fa15kN", overrides=[*_grease(phi), f"integrator.duration='{duration}'",
                                                                   f"lubricant.raceway_film={film}"])
            t0 = time.perf_counter()
            s = S.run(case).summary
            row = {k: s.get(k) for k in KEYS}
            row["Run wall time [s]"] = time.perf_counter() - t0
            if FILMS in s:
                row["Raceway films"] = {r: s[FILMS][r] for r in ("cup", "cone")}
            out[f"phi0 {phi:g}, {film}"] = row
            print(f"phi0 {phi:g} {film}: " + json.dumps({k: row[k] for k in KEYS[:7]}), flush=True)
    return out


def factors(phis, fractions=(1.0, 0.6, 0.3), resolutions=("default", "fine")) -> dict:
    import lubedyn
    from lubedyn.lubrication.errors import ConvergenceError
    from lubedyn.lubrication.laws.film import dowson_toyoda_central
    from lubedyn.scenes import tapered as S

    out = {}
    for phi in phis:
        case = lubedyn.load_case("trb_grease_fa15kN", overrides=_grease(phi))
        model = S.build(case)
        qs = model.quasi_static()
        g, lu = model.geometry, model.lubricant
        ue = model.entrainment_speed
        for race, loads in zip(S.RACES, (qs.cup_loads, qs.cone_loads)):
            w1 = float(max(loads)) / g.effective_length
            radius = float(g.reduced_radius(race))
            for res in resolutions:
                for f in fractions:
                    ep, w = g.e_prime, f * w1
                    h_dt = radius * dowson_toyoda_central(lu.viscosity() * ue / (ep * radius), lu.pressure_viscosity * ep,
                                                          w / (ep * radius))
                    t0 = time.perf_counter()
                    try:
                        r = S.grease_ehl_film(race, radius, g.e_prime, lu.grease(), 870.0, f * w1, ue, (res,))
                        row = {"EHL central film [um]": 1e6 * r["central"], "Formula film [um]": 1e6 * h_dt,
                               "Factor [-]": r["central"] / h_dt, "Checks": r["tried"]}
                    except ConvergenceError as exc:
                        row = {"failed": str(exc)[:300]}
                    row["seconds"] = time.perf_counter() - t0
                    key = f"phi0 {phi:g}, {race}, {res}, {f:g} x {w1:.4g} N/m"
                    out[key] = row
                    print(key, {k: v for k, v in row.items() if k != "Checks"}, flush=True)
    return out


def cost(duration: str, repeats: int = 2) -> dict:
    import lubedyn
    from lubedyn.scenes import tapered as S

    rows = {"formula": [], "grease_ehl": []}
    for _ in range(repeats):
        for film in rows:
            S._RACEWAY_EHL.clear()  # every grease run pays its own EHL solves (the scene caches them per process)
            case = lubedyn.load_case("trb_fig5_2400rpm", overrides=[f"integrator.duration='{duration}'",
                                                                  f"lubricant.raceway_film={film}"])
            t0 = time.perf_counter()
            s = S.run(case).summary
            row = {k: s.get(k) for k in ("Build time [s]", "Integration wall time [s]", "RK4 step [s]",
                                         "Skew, loaded zone, mean [rad]", "Cage slip, mean [-]")}
            row["Run wall time [s]"] = time.perf_counter() - t0
            if FILMS in s:
                row["EHL solves wall time [s]"] = sum(s[FILMS][r]["EHL solve wall time [s]"] for r in ("cup", "cone"))
            rows[film].append(row)
            print(f"{film}: " + json.dumps(row), flush=True)
    best = {film: {k: min(r[k] for r in rs) for k in ("Build time [s]", "Integration wall time [s]",
                                                      "Run wall time [s]")} for film, rs in rows.items()}
    ratio = {k: best["grease_ehl"][k] / best["formula"][k] for k in best["formula"]}
    return {"duration": duration, "runs": rows, "fastest of each": best, "ratio grease_ehl / formula": ratio,
            "target": "the run with the grease's films within 2x of the default's"}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=("runs", "factors", "cost"))
    ap.add_argument("--duration", default=None)
    ap.add_argument("--phi", type=float, nargs="+", default=None)
    a = ap.parse_args(argv)
    path = RESULTS / "trb_raceway_film.json"
    data = json.loads(path.read_text()) if path.exists() else {}
    if a.what == "runs":
        duration = a.duration or "60 ms"
        data["runs"] = {"duration": duration, "results": runs(duration, a.phi or (2.44, 38.44))}
    elif a.what == "cost":
        data["cost"] = cost(a.duration or "180 ms")
    else:
        data["factors"] = factors(a.phi or (8.44,))
    data["machine"] = machine_info()
    write_json(path, data)


if __name__ == "__main__":
    main()
