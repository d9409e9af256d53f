"""EHL contacts: film-thickness accuracy against wall time.

Writes ``benchmarks/results/ehl.json`` and ``ehl.png`` (``--quick``:
``ehl_quick.*``)::

    python benchmarks/ehl.py           # full run
    python benchmarks/ehl.py --quick   # small grids, well under a minute
    python benchmarks/ehl.py --only points   # one scene; the other's stored results are kept

Scenes
------
1. Line contacts, L = 10, M = 20, 100, 1000, on grids refined by 2 (nested
   iteration, second-order SUPG): dimensionless central and minimum film
   thickness H = h/R_x (2U)^-1/2, wall time, error against the Richardson
   extrapolation of the three finest grids (with the observed order), and
   Moes' (1992) formula.
2. Circular point contacts, L = 10, M = 20, 50, 100, 200, 500, 1000 on
   33 x 33 ... 257 x 257 nodes (Fischer-Burmeister Newton; dense LU up to
   33 x 33, bordered GMRES with a sparse-LU preconditioner beyond; 513 x 513
   is refused by ``EHLOptions.max_point_grid`` and recorded so): H_c, H_min,
   Newton iterations, wall time (one run per point: they take up to minutes),
   error against Nijenbanning-Venner-Moes (1994) and against the Richardson
   extrapolation of the three finest converged grids.  Failures are recorded
   with the solver's message.
3. The same circular contacts with ``ehl.method = "multigrid"`` (FAS
   multigrid, lubrication/ehl/multigrid.py), M = 20, 50, 100, 200, 500, 1000
   on 65 x 65 ... 513 x 513 nodes: H_c, H_min, cycles, work units, wall and
   CPU time, error against NVM and against the Richardson extrapolation of
   the three finest multigrid grids (129, 257, 513; the reference of both
   methods in the PNG, since both converge to the same H_c: M = 100, 4.648).
   The numba kernels are compiled (or loaded from the cache) by a warm-up
   solve before the timed runs.  Each grid is solved with the default
   error-based stop and with the former residual stop (projected residual
   1e-5), twice each, interleaved in the same process (CPU-time medians and
   their ratio, ``cpu_ratio_error_to_residual_stop``); for M <= 200 on
   257 x 257 and 513 x 513 also a tight solve (``tight``: cycles until the
   estimated algebraic errors are below 1e-6, with its final residual),
   against which both stops' H_c, H_min and load are compared.

Timings are medians of ``--repeats`` runs on this machine (noted in the
JSON); compare ratios, not seconds, across machines.  Point rows also record
the process CPU time (``cpu_s``: the solver is single-threaded, so this is
the wall time of an unloaded core; the machine is shared) and the load
average at the start of the row.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import _common  # noqa: E402

from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, solve_ehl  # noqa: E402
from lubedyn.lubrication.ehl.multigrid import MultigridOptions  # noqa: E402
from lubedyn.lubrication.laws.film import moes_line_central, nijenbanning_central  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
# points: a failing solve stops after 40 Newton steps (default 80) to bound the run time
POINT_OPTIONS = EHLOptions(max_iter=40)


def H(c, h):
    return h / c.radius_x * (2 * c.U) ** -0.5


def line_series(M, L, grids, repeats):
    c = EHLContact.from_moes(M, L, line=True)
    rows = []
    for n in grids:
        try:
            t, _, s = _common.timed(lambda: solve_ehl(c, EHLGrid(nx=n)), repeats=repeats)
        except Exception as exc:  # the solver's own one-line error, recorded
            rows.append(dict(nx=n, error=str(exc)))
            continue
        rows.append(dict(nx=n, time_s=t, Hc=H(c, s.central_film_thickness), Hmin=H(c, s.minimum_film_thickness),
                         newton_iterations=s.info["iterations"],
                         first_order_iterations=s.info.get("first_order_iterations")))
    ok = [r for r in rows if "Hc" in r]
    ref = _common.richardson([r["Hc"] for r in ok]) if len(ok) >= 3 else None
    for r in ok:
        if ref is not None:
            r["Hc_error"] = abs(r["Hc"] / ref["value"] - 1.0)
    return dict(M=M, L=L, moes_Hc=float(moes_line_central(M, L)), reference=ref, grids=rows)


def point_series(M, L, grids, repeats):
    import os
    import time

    c = EHLContact.from_moes(M, L)
    rows = []
    for n in grids:
        load = os.getloadavg()[0]
        cpu0 = time.process_time()
        try:
            t, _, s = _common.timed(lambda: solve_ehl(c, EHLGrid(nx=n), POINT_OPTIONS), repeats=repeats)
        except Exception as exc:
            rows.append(dict(nx=n, error=str(exc), cpu_s=time.process_time() - cpu0, load_average=load))
            continue
        cpu = (time.process_time() - cpu0) / max(1, repeats)
        rows.append(dict(nx=n, time_s=t, cpu_s=cpu, load_average=load, Hc=H(c, s.central_film_thickness),
                         Hmin=H(c, s.minimum_film_thickness),
                         newton_iterations=s.info["iterations"], unknowns=s.info["unknowns"],
                         gmres_iterations=s.info.get("gmres_iterations"), linear=s.info.get("linear"),
                         fallback="fallback" in s.info))
    return point_reference(dict(M=M, L=L, nvm_Hc=float(nijenbanning_central(M, L)), grids=rows))


MG_OPTIONS = EHLOptions(method="multigrid")  # default: error-based stop (MultigridOptions.stop = "error")
# the former default, run interleaved with it in the same process: cycles until the projected residual is 1e-5
MG_RESIDUAL = EHLOptions(method="multigrid", multigrid=MultigridOptions(stop="residual"))
# accuracy reference of both: cycles until H_c, H_min and the load change by less than 1e-6 (the error test with
# its cap at 1e-6 and the residual test out of reach; at M = 20 on 257^2 H_min still moves by 1e-6 per cycle after
# 60 cycles, so 1e-7 is out of reach).  The projected residual stalls at 1e-7 (M = 20, 257^2) to 5e-6 (M = 20,
# 513^2) where free-boundary nodes flip, so a residual tolerance cannot serve as the reference; the reference's own
# final residual is recorded next to it.
MG_TIGHT = EHLOptions(method="multigrid", multigrid=MultigridOptions(stop="error", error_cap=1e-6, rtol=1e-14,
                                                                     load_rtol=1e-14, max_cycles=60,
                                                                     stall_cycles=100))


def _mg_run(c, n, options):
    import time

    cpu0, t0 = time.process_time(), time.perf_counter()
    s = solve_ehl(c, EHLGrid(nx=n), options)
    return s, time.process_time() - cpu0, time.perf_counter() - t0


def multigrid_series(M, L, grids, repeats=2, tight_grids=()):
    """Each grid: the error-based stop (default) and the residual stop, ``repeats``
    times each, interleaved (A B B A ...), CPU-time medians; on ``tight_grids``
    also a tight solve, against which both stops' H_c, H_min and load are compared."""
    import os

    c = EHLContact.from_moes(M, L)
    rows = []
    for n in grids:
        load = os.getloadavg()[0]
        runs = {"error": [], "residual": []}
        try:
            for i in range(repeats):
                order = ("error", "residual") if i % 2 == 0 else ("residual", "error")
                for name in order:
                    runs[name].append(_mg_run(c, n, MG_OPTIONS if name == "error" else MG_RESIDUAL))
        except Exception as exc:
            rows.append(dict(nx=n, error=str(exc), load_average=load))
            continue
        s = runs["error"][0][0]
        cpu = float(np.median([r[1] for r in runs["error"]]))
        row = dict(nx=n, time_s=float(np.median([r[2] for r in runs["error"]])), cpu_s=cpu,
                   solver_cpu_s=float(np.median([r[0].info["cpu_time"] for r in runs["error"]])),
                   setup_wall_s=s.info["setup_time"], load_average=load,
                   Hc=H(c, s.central_film_thickness), Hmin=H(c, s.minimum_film_thickness),
                   cycles=s.info["cycles"], work_units=s.info["work_units"], residual=s.info["residual"],
                   load_error=s.info["load_error"], unknowns=s.info["unknowns"],
                   stop=s.info["history"][-1]["stop"], stop_detail=s.info["history"][-1]["stop_detail"],
                   max_pressure_over_hertz=s.maximum_pressure / s.problem.ph)
        r = runs["residual"][0][0]
        rcpu = float(np.median([x[1] for x in runs["residual"]]))
        row["residual_stop"] = dict(cpu_s=rcpu, time_s=float(np.median([x[2] for x in runs["residual"]])),
                                    Hc=H(c, r.central_film_thickness), Hmin=H(c, r.minimum_film_thickness),
                                    cycles=r.info["cycles"], work_units=r.info["work_units"],
                                    residual=r.info["residual"])
        row["cpu_ratio_error_to_residual_stop"] = cpu / rcpu
        if n in tight_grids:
            try:
                t, tcpu, _ = _mg_run(c, n, MG_TIGHT)
            except Exception as exc:
                row["tight"] = dict(error=str(exc))
            else:
                row["tight"] = dict(cpu_s=tcpu, Hc=H(c, t.central_film_thickness), Hmin=H(c, t.minimum_film_thickness),
                                    cycles=t.info["cycles"], residual=t.info["residual"])
                for tag, sol in (("error_stop", s), ("residual_stop", r)):
                    row["tight"][f"{tag}_relative_difference"] = dict(
                        Hc=sol.central_film_thickness / t.central_film_thickness - 1,
                        Hmin=sol.minimum_film_thickness / t.minimum_film_thickness - 1,
                        load=sol.load / t.load - 1)
        rows.append(row)
    series = dict(M=M, L=L, nvm_Hc=float(nijenbanning_central(M, L)), grids=rows)
    return point_reference(series)


def point_reference(series):
    """NVM errors, and a Richardson reference from the three finest converged
    grids only where the observed order is at least 1 (an under-resolved
    sequence, e.g. M = 200 on 33 ... 129 with order 0.04, gives none)."""
    ok = [r for r in series["grids"] if "Hc" in r]
    ref = _common.richardson([r["Hc"] for r in ok]) if len(ok) >= 3 else None
    if ref is not None and not (ref.get("observed_order") or 0.0) >= 1.0:
        ref = dict(ref, method="none: observed order below 1 (grids not in the asymptotic range)", value=None)
    for r in ok:
        r["Hc_nvm_error"] = r["Hc"] / series["nvm_Hc"] - 1.0
        r.pop("Hc_error", None)
        if ref is not None and ref["value"] is not None:
            r["Hc_error"] = abs(r["Hc"] / ref["value"] - 1.0)
    series["reference"] = ref
    return series


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--repeats", type=int, default=None)
    ap.add_argument("--replot", action="store_true",
                    help="redo the derived references and the PNG from the stored JSON (no solves)")
    ap.add_argument("--only", choices=("points", "lines", "multigrid"), default=None,
                    help="run one scene and keep the other's stored results")
    args = ap.parse_args(argv)
    repeats = args.repeats or (1 if args.quick else 3)
    stem = "ehl_quick" if args.quick else "ehl"
    if args.replot:
        import json

        data = json.loads((RESULTS / f"{stem}.json").read_text())
        data["point"] = [point_reference(s) for s in data["point"]]
        data["multigrid"] = [point_reference(s) for s in data.get("multigrid", [])]
        _common.write_json(RESULTS / f"{stem}.json", data)
        return plot(data, stem)
    if args.quick:
        line_cases = {20: [129, 257, 513], 1000: [257, 513, 1025]}
        point_cases = {20: [33, 65], 100: [33, 65]}
        mg_cases = {100: [65, 129, 257]}
    else:
        line_cases = {20: [129, 257, 513, 1025], 100: [129, 257, 513, 1025], 1000: [257, 513, 1025, 2049]}
        # M = 100 first: the 257 x 257 target row
        # (513 x 513 is refused by EHLOptions.max_point_grid: its row records the message)
        point_cases = {100: [33, 65, 129, 257, 513], 200: [33, 65, 129, 257], 20: [33, 65, 129], 50: [33, 65, 129],
                       500: [65, 129], 1000: [65, 129]}
        mg_cases = {M: [65, 129, 257, 513] for M in (100, 200, 20, 50, 500, 1000)}
    if args.only == "points":
        line_cases, mg_cases = {}, {}
    elif args.only == "lines":
        point_cases, mg_cases = {}, {}
    elif args.only == "multigrid":
        line_cases, point_cases = {}, {}
    RESULTS.mkdir(exist_ok=True)
    data = dict(machine=_common.machine_info(), quick=args.quick, repeats=repeats, line=[], point=[], multigrid=[])
    if args.only:
        # keep the other scenes' stored results (and the machine information they were measured with)
        import json

        old = RESULTS / f"{stem}.json"
        if old.exists():
            prev = json.loads(old.read_text())
            ran = {"points": "point", "lines": "line", "multigrid": "multigrid"}[args.only]
            for other in ("line", "point", "multigrid"):
                if other != ran:
                    data[other] = prev.get(other, [])
            data["machine_previous_scenes"] = prev.get("machine")
    # written after every series, so that a long run leaves usable partial results
    for M, g in line_cases.items():
        data["line"] = [s for s in data["line"] if s["M"] != M] + [line_series(M, 10.0, g, repeats)]
        _common.write_json(RESULTS / f"{stem}.json", data)
    for M, g in point_cases.items():
        data["point"] = [s for s in data["point"] if s["M"] != M] + [point_series(M, 10.0, g, 1)]
        _common.write_json(RESULTS / f"{stem}.json", data)
    if mg_cases:
        import time

        t0, c0 = time.perf_counter(), time.process_time()
        solve_ehl(EHLContact.from_moes(100, 10), EHLGrid(nx=33), MG_OPTIONS)  # numba compile / cache load
        data["multigrid_warmup"] = dict(wall_s=time.perf_counter() - t0, cpu_s=time.process_time() - c0)
    for M, g in mg_cases.items():
        tight = [n for n in g if n >= 257 and M <= 200] if not args.quick else g
        data["multigrid"] = [s for s in data["multigrid"] if s["M"] != M] + [
            multigrid_series(M, 10.0, g, repeats=1 if args.quick else 2, tight_grids=tight)]
        _common.write_json(RESULTS / f"{stem}.json", data)
    plot(data, stem)


def plot(data, stem):
    """The work-precision PNG and a printed summary of ``data``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(16, 4.4), constrained_layout=True)
    for s in data["line"]:
        ok = [r for r in s["grids"] if "Hc_error" in r and r["Hc_error"] > 0]
        if ok:
            a1.loglog([r["time_s"] for r in ok], [r["Hc_error"] for r in ok], "o-",
                      label=f"line M={s['M']:g} (order {s['reference']['observed_order'] or float('nan'):.2f})")
    a1.set_xlabel("wall time [s]")
    a1.set_ylabel("|H_c / H_c,ref - 1| (Richardson reference)")
    a1.set_title("L = 10: work-precision (line: solid, circle: dashed)")
    a1.legend(fontsize=8)
    for s in data["line"]:
        ok = [r for r in s["grids"] if "Hc" in r]
        a2.semilogx([r["nx"] for r in ok], [r["Hc"] / s["moes_Hc"] for r in ok], "o-", label=f"line M={s['M']:g} / Moes")
    for s in data["point"]:
        ok = [r for r in s["grids"] if "Hc" in r]
        a2.semilogx([r["nx"] for r in ok], [r["Hc"] / s["nvm_Hc"] for r in ok], "s--", label=f"point M={s['M']:g} / NVM")
    for s in data["point"]:
        ok = [r for r in s["grids"] if r.get("Hc_error", 0) > 0]
        if ok:
            a1.loglog([r["time_s"] for r in ok], [r["Hc_error"] for r in ok], "s--", label=f"point M={s['M']:g}")
    a2.axhline(1.0, color="k", lw=0.8)
    a2.set_xlabel("nodes along x")
    a2.set_ylabel("H_c / formula")
    a2.set_title("Central film against Moes (line) and NVM (point)")
    for s in data.get("multigrid", []):
        ok = [r for r in s["grids"] if "Hc" in r]
        a2.semilogx([r["nx"] for r in ok], [r["Hc"] / s["nvm_Hc"] for r in ok], "^:",
                    label=f"multigrid M={s['M']:g} / NVM")
    a2.legend(fontsize=7)
    # circular contacts, both methods: error against the multigrid Richardson reference vs CPU time
    refs = {s["M"]: (s.get("reference") or {}).get("value") for s in data.get("multigrid", [])}
    for i, s in enumerate(sorted(data.get("multigrid", []), key=lambda s: s["M"])):
        ref = refs.get(s["M"])
        ok = [r for r in s["grids"] if "Hc" in r]
        if ref and ok:
            a3.loglog([r["cpu_s"] for r in ok], [max(abs(r["Hc"] / ref - 1), 1e-6) for r in ok], "o-", color=f"C{i}",
                      label=f"multigrid M={s['M']:g}")
            rs = [r for r in ok if "residual_stop" in r]
            if rs:  # the same grids with the former residual stop (hollow): same error, more CPU
                a3.loglog([r["residual_stop"]["cpu_s"] for r in rs],
                          [max(abs(r["residual_stop"]["Hc"] / ref - 1), 1e-6) for r in rs], "o:", mfc="none",
                          color=f"C{i}", alpha=0.7, label=f"residual stop M={s['M']:g}")
        fem = next((p for p in data["point"] if p["M"] == s["M"]), None)
        fok = [r for r in (fem or {}).get("grids", []) if "Hc" in r and r.get("cpu_s")]
        if ref and fok:
            a3.loglog([r["cpu_s"] for r in fok], [max(abs(r["Hc"] / ref - 1), 1e-6) for r in fok], "s--",
                      color=f"C{i}", alpha=0.7, label=f"FEM Newton M={s['M']:g}")
    a3.axvline(10.0, color="k", lw=0.8, ls=":")
    a3.set_xlabel("CPU time of one core [s] (dotted: 10 s)")
    a3.set_ylabel("|H_c / H_c,ref - 1| (multigrid Richardson reference)")
    a3.set_title("Circles, L = 10: multigrid (solid; hollow: residual stop), FEM Newton (dashed)",
                 fontsize=9)
    a3.legend(fontsize=6, ncol=2)
    _common.save_figure(fig, RESULTS / f"{stem}.png")
    for s in data["line"]:
        print(f"line M={s['M']:g}: " + ", ".join(
            f"{r['nx']}: Hc={r.get('Hc', float('nan')):.4f} ({r.get('time_s', float('nan')):.2f} s)" for r in s["grids"])
              + f"; ref {s['reference']['value'] if s['reference'] else None}, Moes {s['moes_Hc']:.4f}")
    for s in data["point"]:
        print(f"point M={s['M']:g}: " + ", ".join(
            f"{r['nx']}: Hc={r.get('Hc', float('nan')):.4f} ({r.get('time_s', float('nan')):.2f} s, "
            f"{r.get('newton_iterations')} it)" if "Hc" in r else f"{r['nx']}: FAILED ({r['error'][:60]})"
            for r in s["grids"]) + f"; NVM {s['nvm_Hc']:.4f}")
    for s in data.get("multigrid", []):
        print(f"multigrid M={s['M']:g}: " + ", ".join(
            f"{r['nx']}: Hc={r['Hc']:.4f} ({r['cpu_s']:.2f} s CPU, {r['time_s']:.2f} s wall, {r['cycles']} cycles)"
            if "Hc" in r else f"{r['nx']}: FAILED ({r['error'][:60]})" for r in s["grids"])
              + f"; NVM {s['nvm_Hc']:.4f}, ref {(s.get('reference') or {}).get('value')}")
    for s in data.get("multigrid", []):
        for r in s["grids"]:
            if "residual_stop" not in r:
                continue
            rs = r["residual_stop"]
            td = (r.get("tight") or {}).get("error_stop_relative_difference")
            print(f"  M={s['M']:g} {r['nx']}^2: error stop {r['cycles']} cyc {r['work_units']:.0f} WU {r['cpu_s']:.2f} s"
                  f" | residual stop {rs['cycles']} cyc {rs['work_units']:.0f} WU {rs['cpu_s']:.2f} s"
                  f" | ratio {r['cpu_ratio_error_to_residual_stop']:.2f}"
                  + (f" | vs tight: Hc {td['Hc']:+.1e} Hmin {td['Hmin']:+.1e} load {td['load']:+.1e}" if td else ""))


if __name__ == "__main__":
    main()
