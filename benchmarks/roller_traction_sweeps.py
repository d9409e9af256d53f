"""Roller EHL maps of paper A's roller: would a compressible film plus denser nodes make the traction interpolable?

Dense line-load sweeps of the roller kinds (``ehl_roller_cone``, ``ehl_roller_cup``; their parameters with
``density_law`` overridden, default Dowson-Higginson) at a few entrainment speeds, then the interpolation
error a map would make, estimated on the sweeps themselves:

- along the load: every k-th sweep point a node (all k offsets), cubic Hermite on PCHIP slopes in log-log
  (what ``FilmMap`` method "hermite" does along one axis), compared at the points in between;
- along the speed: PCHIP in log-log across the node speeds, compared at a speed between two of them;
- the traction as the map returns it ("sheared"): the transition slip s_t and the traction on the map's 37
  normalised-slip nodes G(sigma) interpolated across the nodes, then G along sigma at s/s_t (PCHIP in
  log-log), against the traction of the point at SRR 1e-5 ... 0.1 (9 values; "mu_sheared" is the largest
  of the 9 errors per point).  "mu1e-4" etc. interpolate the traction at a fixed SRR directly.

``python benchmarks/roller_traction_sweeps.py sweep TAG --races cone,cup --speeds 7,7.857 --loads 5000,150000,73
[--density dowson_higginson] [--resolution default] [--coefficients secant] [--refine 6]`` -> results/roller_sweeps/TAG.pkl
(2 worker processes); ``python benchmarks/roller_traction_sweeps.py summary`` -> results/roller_traction_sweeps.json
from every TAG.pkl present (the sweeps, their layouts and the error tables).
"""
from __future__ import annotations

import argparse
import os
import pickle
import sys
import time
from multiprocessing import Pool
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

RAW = HERE / "results" / "roller_sweeps"
SIG = np.geomspace(1e-7, 1e7, 281)           # dense normalised slip (20 per decade) for the direct traction
SRRS = (1e-5, 1e-4, 1e-3, 1e-2, 1e-1)
TEST_SRR = np.array([1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1])
OUTS = {"hc": "Central film thickness [m]", "hmin": "Minimum film thickness [m]", "K": "Film stiffness per length [N/m^2]",
        "C": "Film damping per length [N s/m^2]", "u0": "Central deflection [m]"}


def _point(task):
    race, u, w, density, resolution, coefficients, refine = task
    from lubedyn.film_points import ehl

    p = ehl._roller_params(race)
    p.update(density_law=density, resolution=resolution)
    if refine != 1.0:  # a graded line grid (lubedyn.lubrication.ehl.EHLGrid.refine; the kinds' zone scaled with the film)
        p["grid_refine"] = refine
    if coefficients:
        p["coefficients"] = coefficients
    t = time.perf_counter()
    try:
        out = ehl.evaluate_ehl_line(p, {"Line load [N/m]": w, "Entrainment speed [m/s]": u, "Slide-to-roll ratio [-]": 1e-4})
        base = ehl.ehl_load_response(p, w, u)
        prof = base["couette"] if "couette" in base else ehl.couette_profile(base["solution"])
        G = p["film_shear_modulus"]
        s_t = ehl.saturated_transition(ehl.transition_slide_to_roll(prof, G))
        res = dict(out=out, s_t=s_t, mu=[ehl.maxwell_traction(prof, s, G) for s in SRRS],
                   G=[ehl.maxwell_traction(prof, sg * s_t, G) for sg in SIG],
                   a=ehl.maxwell_traction(prof, 1e-12, G) / 1e-12, ok=True)
    except Exception as exc:  # a failed point is recorded with its message
        res = dict(ok=False, err=repr(exc)[:500])
    res.update(race=race, u=u, w=w, t=time.perf_counter() - t)
    return res


def sweep(tag, races, speeds, loads, density, resolution, coefficients, workers=2, refine=1.0):
    tasks = [(r, u, float(w), density, resolution, coefficients, refine) for r in races for u in speeds for w in loads]
    t0 = time.perf_counter()
    with Pool(workers) as pool:
        results = list(pool.imap(_point, tasks, chunksize=4))
    RAW.mkdir(parents=True, exist_ok=True)
    data = dict(results=results, loads=np.asarray(loads), speeds=list(speeds), races=list(races), SIG=SIG, SRRS=SRRS,
                density=density, resolution=resolution, coefficients=coefficients, refine=refine, wall=time.perf_counter() - t0,
                load_average=list(os.getloadavg()))
    with open(RAW / f"{tag}.pkl", "wb") as fh:
        pickle.dump(data, fh)
    return data


def table(d, race, u):
    """Per-load arrays of one (race, speed) sweep (failed points left out)."""
    from lubedyn.film_points import ehl

    sig_nodes = np.asarray(ehl.normalised_slip(np.geomspace(1e-5, 0.1, 37)))
    rs = sorted((r for r in d["results"] if r["race"] == race and abs(r["u"] - u) < 1e-9 and r["ok"]), key=lambda r: r["w"])
    w = np.array([r["w"] for r in rs])
    T = {k: np.array([r["out"][v] for r in rs]) for k, v in OUTS.items()}
    T["s_t"] = np.array([r["s_t"] for r in rs])
    T["a"] = np.array([r["a"] for r in rs])
    for j, s in enumerate(d["SRRS"]):
        T[f"mu{s:g}"] = np.array([r["mu"][j] for r in rs])
    Gd = np.array([r["G"] for r in rs])
    lsig = np.log(d["SIG"])
    T["Gn"] = np.exp(np.array([np.interp(np.log(sig_nodes), lsig, np.log(np.maximum(g, 1e-300))) for g in Gd]))
    T["mud"] = np.exp(np.array([np.interp(np.log(TEST_SRR / st), lsig, np.log(np.maximum(g, 1e-300)))
                                for g, st in zip(Gd, T["s_t"])]))
    T["sig_nodes"] = sig_nodes
    return w, T


def _sheared(xn, Tn, xt, sig_nodes):
    from scipy.interpolate import PchipInterpolator as P

    X, Xt = np.log(xn), np.log(xt)
    st = np.exp(P(X, np.log(Tn["s_t"]))(Xt))
    lG = P(X, np.log(Tn["Gn"]), axis=0)(Xt)
    ls = np.log(sig_nodes)
    return np.array([np.exp(P(ls, lG[i])(np.clip(np.log(TEST_SRR / st[i]), ls[0], ls[-1]))) for i in range(len(xt))])


def load_errors(w, T, k, keys):
    """Relative errors at the sweep points between nodes, every k-th point a node (all offsets)."""
    from scipy.interpolate import PchipInterpolator as P

    err = {key: [] for key in keys + ["mu_sheared"]}
    where = {key: [] for key in err}
    for off in range(k):
        idx = np.arange(off, len(w), k)
        test = np.setdiff1d(np.arange(idx[0], idx[-1] + 1), idx)
        if len(test) == 0 or len(idx) < 2:
            continue
        for key in keys:
            est = np.exp(P(np.log(w[idx]), np.log(np.abs(T[key][idx])))(np.log(w[test])))
            err[key].append(np.abs(est / np.abs(T[key][test]) - 1))
            where[key].append(w[test])
        est = _sheared(w[idx], {"s_t": T["s_t"][idx], "Gn": T["Gn"][idx]}, w[test], T["sig_nodes"])
        err["mu_sheared"].append(np.abs(est / T["mud"][test] - 1).max(axis=1))
        where["mu_sheared"].append(w[test])
    return {key: (np.concatenate(err[key]), np.concatenate(where[key])) for key in err}


def speed_errors(d, race, node_speeds, mid, keys):
    from scipy.interpolate import PchipInterpolator as P

    tabs = {u: table(d, race, u) for u in node_speeds}
    wm, Tm = table(d, race, mid)
    common = set(np.round(wm, 6))
    for u in node_speeds:
        common &= set(np.round(tabs[u][0], 6))
    common = np.array(sorted(common))
    pick = {u: np.isin(np.round(tabs[u][0], 6), common) for u in node_speeds}
    pm = np.isin(np.round(wm, 6), common)
    us = np.log(np.array(node_speeds))
    out = {}
    for key in keys:
        V = np.array([tabs[u][1][key][pick[u]] for u in node_speeds])
        est = np.exp(P(us, np.log(np.abs(V)), axis=0)(np.log(mid)))
        out[key] = (np.abs(est / np.abs(Tm[key][pm]) - 1), common)
    st = np.array([tabs[u][1]["s_t"][pick[u]] for u in node_speeds])
    Gn = np.array([tabs[u][1]["Gn"][pick[u]] for u in node_speeds])
    e = [np.abs(_sheared(np.array(node_speeds), {"s_t": st[:, i], "Gn": Gn[:, i]}, np.array([mid]), Tm["sig_nodes"])[0]
                / Tm["mud"][pm][i] - 1).max() for i in range(len(common))]
    out["mu_sheared"] = (np.array(e), common)
    return out


def _stats(e, w, bands=((0, 15e3), (15e3, 35e3), (35e3, 60e3), (60e3, 1e9))):
    out = {"median": float(np.median(e)), "max": float(e.max()), "at [N/m]": float(w[e.argmax()])}
    for lo, hi in bands:
        sel = (w > lo) & (w < hi)
        if sel.any():
            out[f"{lo / 1e3:g}-{hi / 1e3:g} kN/m"] = {"median": float(np.median(e[sel])), "max": float(e[sel].max())}
    return out


SPEED_SETS = {(7.0, 7.857, 8.819): 7.408, (22.22, 24.944, 28.0): 26.43}


def summary():
    from _common import machine_info, write_json

    keys = list(OUTS) + ["s_t", "mu0.0001", "mu0.001", "mu0.01"]
    # the raw sweeps are not versioned: sweeps summarised before (and whose .pkl is gone) are kept from the JSON
    out = HERE / "results" / "roller_traction_sweeps.json"
    import json

    kept = json.loads(out.read_text())["sweeps"] if out.exists() else {}
    result = {"machine": machine_info(), "sweeps": kept}
    for path in sorted(RAW.glob("*.pkl")):
        with open(path, "rb") as fh:
            d = pickle.load(fh)
        entry = {k: d.get(k) for k in ("density", "resolution", "coefficients", "refine", "wall", "load_average")}
        entry.update(races=d["races"], speeds=d["speeds"], loads=[float(d["loads"][0]), float(d["loads"][-1]), len(d["loads"])],
                     failed=[(r["race"], r["u"], r["w"], r.get("err", "")[:200]) for r in d["results"] if not r["ok"]],
                     points=len(d["results"]), load=[], speed=[], slope={})
        for race in d["races"]:
            for u in d["speeds"]:
                w, T = table(d, race, u)
                if len(w) < 9:
                    continue
                entry["slope"][f"{race} {u:g}"] = {"w": w.tolist(), "a": T["a"].tolist(), "s_t": T["s_t"].tolist()}
                ratio = (w[-1] / w[0]) ** (1 / (len(w) - 1))
                for k in (2, 3, 4, 6, 8):
                    if len(w) // k < 4:
                        continue
                    E = load_errors(w, T, k, keys)
                    entry["load"].append({"race": race, "speed": u, "node ratio": ratio ** k, "k": k,
                                          "errors": {key: _stats(e, ww) for key, (e, ww) in E.items()}})
            for nodes, mid in SPEED_SETS.items():
                if all(any(abs(u - s) < 1e-9 for u in d["speeds"]) for s in nodes + (mid,)):
                    E = speed_errors(d, race, list(nodes), mid, keys)
                    entry["speed"].append({"race": race, "nodes": nodes, "at": mid,
                                           "errors": {key: _stats(e, ww) for key, (e, ww) in E.items()}})
        result["sweeps"][path.stem] = entry
    return write_json(out, result)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("sweep", "summary"))
    ap.add_argument("tag", nargs="?")
    ap.add_argument("--races", default="cone,cup")
    ap.add_argument("--speeds", default="7,7.408,7.857,8.819")
    ap.add_argument("--loads", default="5000,150000,73", help="first, last, count (log)")
    ap.add_argument("--density", default="dowson_higginson")
    ap.add_argument("--resolution", default="default")
    ap.add_argument("--coefficients", default="", help="override the kinds' 'secant' (e.g. 'linearised')")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--refine", type=float, default=1.0, help="graded line grid: the kinds' grid_refine (1: uniform)")
    a = ap.parse_args(argv)
    if a.mode == "sweep":
        lo, hi, n = a.loads.split(",")
        sweep(a.tag, a.races.split(","), [float(s) for s in a.speeds.split(",")], np.geomspace(float(lo), float(hi), int(n)),
              a.density, a.resolution, a.coefficients, a.workers, a.refine)
    else:
        print(summary())


if __name__ == "__main__":
    main()
