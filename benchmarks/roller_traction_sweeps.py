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

``python benchmarks/roller_traction_sweeps.py laws [--direct]`` -> results/roller_traction_laws.json and .png: the
tapered model's three raceway traction laws ("limited", "paper", "map"; each as the kernel evaluates a slice,
:meth:`lubedyn.dynamics.tapered.model.TaperedBearing.raceway_traction_coefficient`) as traction coefficient against slide-to-roll ratio
at paper A's most loaded roller (F_r 20 kN, axial locked; the quasi-static solve's cup and cone line loads)
at 2, 2.4 and 5 krpm, each against an independent value:

- "limited": the closed forms of its two limits -- the film's elastic shear, mu = 2 G b^2 s/(h w) (Johnson &
  Tevaarwerk's elastic limit, s the slide-to-roll ratio, h the Dowson-Toyoda central film), at s = 1e-6,
  and the limiting shear stress over the whole Hertz strip, mu = gamma_L + 2 b tau_L0/w (int p dx = w), at
  s = 0.1;
- "paper": the Couette traction eta s u_e int_{-b}^{b} 2 (h - h_0)/h^2 dx / w of eq. 12's gap h = h_0 + 2 x^2/R'
  by adaptive quadrature (what eq. 13's epsilon integrates in closed form), at s = 1e-3;
- "map": the EHL line contact solved directly with the map's own parameters (``--direct``, 2.4 krpm,
  s = 1e-2 and 0.1; about 10-60 s per solve).

Published traction curves with stated inputs were searched for (Johnson & Tevaarwerk 1977 and Evans &
Johnson 1986: not found; Jacod, Venner & Lugt 2001, Bair & Winer 1979, Hoeglund & Jacobson 1986, Wikstroem &
Hoeglund 1994 and others: abstracts or first pages only, no formula, no number with its conditions), so the
JSON records "published": none usable, with what each stored text states (docs/paper_a.md, "Traction laws
against published curves").
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


# ---------------------------------------------------------------- the tapered model's raceway laws

LAW_CASE = "cases/trb_fig5_2400rpm.toml"
LAW_SPEEDS_RPM = (2000.0, 2400.0, 5000.0)
LAWS = ("limited", "paper", "map")
LAW_SRR = np.geomspace(1e-6, 0.1, 61)
#: what the searched sources' stored texts state (abstracts only); no number with its conditions
PUBLISHED_SEARCH = [
    {"source": "Jacod, Venner & Lugt 2001, A generalized traction curve for EHL contacts, J. Tribol. 123(2) 248, "
               "doi 10.1115/1.1308021",
     "stated": "a single generalized curve of a reduced friction coefficient against a characteristic "
               "nondimensional shear stress, from isothermal Eyring simulations of elliptic contacts, "
               "validated on measured data from the literature",
     "usable": "no: the stored text ends before the curve's formula and its fitted constants"},
    {"source": "Regimes of traction in concentrated contact lubrication (an abstract whose authors and year the "
               "stored text does not show; Evans & Johnson 1986 itself was not found)",
     "stated": "three regimes at a fixed slide-to-roll ratio: limiting-shear governed, mixed (Lambda < 1, "
               "higher traction), and thick films (pressure spread beyond the Hertz zone, lower traction)",
     "usable": "no: abstract only, no traction values"},
    {"source": "Vengudusamy, Enekes & Spallek 2019, EHD friction properties of ISO VG 320 gear oils with smooth "
               "and rough surfaces, Friction, doi 10.1007/s40544-019-0267-5",
     "stated": "ball-on-disc traction curves of PAOs, polyglycols and a mineral oil at six temperatures; with "
               "smooth surfaces only the polyglycols reach limiting friction, mineral oil and PAOs do not",
     "usable": "no: abstract only, no values with conditions"},
    {"source": "Bair & Winer 1979, Shear strength measurements of lubricants at high pressure, J. Lubr. "
               "Technol. 101(3) 251",
     "stated": "elastic, plastic and viscous behaviour of three lubricants; the limiting shear stress depends on "
               "temperature and pressure and sets the maximum EHL traction",
     "usable": "no: abstract only, no limiting-shear values"},
    {"source": "Hoeglund & Jacobson 1986, Experimental investigation of the shear strength of lubricants "
               "subjected to high pressure and temperature, J. Tribol. 108(4) 571",
     "stated": "pressures to 2.2 GPa, temperatures to 200 C; mineral oils behave alike; grease does not differ "
               "from liquid lubricants",
     "usable": "no: abstract only (supports reading the grease's limiting shear as its base oil's, no value)"},
    {"source": "Wikstroem & Hoeglund 1994, Investigation of parameters affecting the limiting shear "
               "stress-pressure coefficient, J. Tribol. 116(3) 612",
     "stated": "tau_L = tau_0 + gamma p (Johnson & Tevaarwerk); gamma depends on oil type, viscosity, "
               "pressure and temperature; an empirical model for a PAO/diester and a naphthenic oil, shear "
               "rate about 1e6 1/s",
     "usable": "no: abstract only, no gamma values"},
    {"source": "Johnson & Tevaarwerk 1977, Shear behaviour of elastohydrodynamic oil films, Proc. R. Soc. A "
               "356, 215",
     "stated": "(not found in the stored texts)", "usable": "no"},
]


def _law_models(speed_rpm):
    """{law: (model, kernel arguments)} at ``speed_rpm`` and the quasi-static start (one solve)."""
    from lubedyn.config import load_case
    from lubedyn.scenes import tapered as S

    out, qs = {}, None
    for law in LAWS:
        case = load_case(str(HERE.parent / LAW_CASE), overrides=[f"model.traction={law}",
                                                                  f"operating.speed={speed_rpm} rpm"])
        model = S.build(case)
        qs = model.quasi_static() if qs is None else qs
        out[law] = (model, model.args(qs))
    return out, qs


def law_mu(model, args, race, w, srr):
    """Traction coefficient [-] of ``race`` (0 cup, 1 cone) at line load ``w`` [N/m] and slide-to-roll ratio
    ``srr`` as the kernel evaluates a slice of that line load."""
    return model.raceway_traction_coefficient(("cup", "cone")[race], w, srr, args)


def strip(model, args, race, w):
    """(R' [m], Hertz half-width b [m], peak pressure p0 [Pa], Dowson-Toyoda central film h [m]) of ``race``'s
    strip at line load ``w`` [N/m], as the kernel's slices take them."""
    d = model.raceway_strip(("cup", "cone")[race], w, args)
    return d["reduced radius [m]"], d["half-width [m]"], d["peak pressure [Pa]"], d["film [m]"]


def limited_elastic_mu(model, args, race, w, srr):
    """Closed form of the limited law's small-slip limit: mu = 2 G b^2 s/(h w)."""
    _, b, _, h = strip(model, args, race, w)
    return 2.0 * args.P[0].gshear * b * b * srr / (h * w)


def limited_saturated_mu(model, args, race, w):
    """Closed form of the limited law's large-slip limit: mu = gamma_L + 2 b tau_L0/w."""
    _, b, _, _ = strip(model, args, race, w)
    P = args.P[0]
    return P.gammal + 2.0 * b * P.taul0 / w


def paper_couette_mu(model, args, race, w, srr):
    """Eq. 12's traction by quadrature of the Couette shear of its gap: eta v_s int_{-b}^{b} 2 (h - h0)/h^2 dx / w,
    h = h0 + 2 x^2/R' (lubrication/laws/traction.py), v_s = s u_e."""
    from scipy.integrate import quad

    radius, b, _, h0 = strip(model, args, race, w)
    P = args.P[0]
    val, _ = quad(lambda x: 2.0 * (2.0 * x * x / radius) / (h0 + 2.0 * x * x / radius) ** 2, -b, b, limit=200,
                  epsabs=0.0, epsrel=1e-12)
    return P.eta * srr * P.ue * val / w


def laws(direct=False):
    from _common import machine_info, save_figure, write_json

    t0 = time.perf_counter()
    result = {"machine": machine_info(), "case": LAW_CASE, "SRR": LAW_SRR.tolist(), "points": {},
              "published": {"usable": "none",
                            "searched": PUBLISHED_SEARCH,
                            "note": "no published traction value with its stated inputs was found in the "
                                    "searchable texts, so no law-to-published ratio is given"}}
    curves = {}
    for rpm in LAW_SPEEDS_RPM:
        models, qs = _law_models(rpm)
        lm, lim = models["limited"]
        j = int(np.argmax(qs.cone_loads))
        le = lm.geometry.effective_length
        entry = {"most loaded roller": j, "entrainment speed [m/s]": float(lim.P[0].ue), "races": {}}
        for race, name, loads in ((0, "cup", qs.cup_loads), (1, "cone", qs.cone_loads)):
            w = float(loads[j] / le)
            radius, b, p0, h = strip(lm, lim, race, w)
            r = {"line load [N/m]": w, "reduced radius [m]": radius, "Hertz half-width [m]": b,
                 "Hertz peak pressure [Pa]": p0, "Dowson-Toyoda central film [m]": h, "laws": {}}
            for law in LAWS:
                model, args = models[law]
                mu = np.array([law_mu(model, args, race, w, s) for s in LAW_SRR])
                curves[(rpm, name, law)] = mu
                r["laws"][law] = {"mu": mu.tolist(), "mu at 1e-4, 1e-3, 1e-2, 0.1": [
                    law_mu(model, args, race, w, s) for s in (1e-4, 1e-3, 1e-2, 0.1)]}
            ref_el, ref_sat = limited_elastic_mu(lm, lim, race, w, 1e-6), limited_saturated_mu(lm, lim, race, w)
            r["laws"]["limited"]["checks"] = {
                "elastic limit at s = 1e-6: law / closed form": law_mu(lm, lim, race, w, 1e-6) / ref_el,
                "saturated at s = 0.1: law / closed form": law_mu(lm, lim, race, w, 0.1) / ref_sat,
                "closed form gamma_L + 2 b tau_L0/w": ref_sat}
            pm, pa = models["paper"]
            r["laws"]["paper"]["checks"] = {
                "s = 1e-3: law / Couette quadrature": law_mu(pm, pa, race, w, 1e-3) / paper_couette_mu(pm, pa, race, w,
                                                                                                      1e-3)}
            mp = models["map"]
            r["laws"]["map"]["checks"] = {"map's limiting shear (tau_L0, gamma)": [
                float(mp[0].traction_maps[race].provenance["params"]["limiting_shear_stress"]),
                float(mp[0].traction_maps[race].provenance["params"]["limiting_shear_slope"])]}
            if direct and rpm == 2400.0:
                from lubedyn.film_points import evaluate_ehl_line

                fmap = mp[0].traction_maps[race]
                for s in (1e-2, 0.1):
                    d = evaluate_ehl_line(fmap.provenance["params"], {
                        "Line load [N/m]": w, "Entrainment speed [m/s]": float(mp[1].P[0].ue),
                        "Slide-to-roll ratio [-]": s})["Traction coefficient [-]"]
                    r["laws"]["map"]["checks"][f"s = {s:g}: map / direct EHL solve"] = law_mu(*mp, race, w, s) / d
            r["limited / map at 1e-4, 1e-3, 1e-2, 0.1"] = [
                a / b_ for a, b_ in zip(r["laws"]["limited"]["mu at 1e-4, 1e-3, 1e-2, 0.1"],
                                        r["laws"]["map"]["mu at 1e-4, 1e-3, 1e-2, 0.1"])]
            r["limited / paper at 1e-2"] = r["laws"]["limited"]["mu at 1e-4, 1e-3, 1e-2, 0.1"][2] / \
                r["laws"]["paper"]["mu at 1e-4, 1e-3, 1e-2, 0.1"][2]
            entry["races"][name] = r
        result["points"][f"{rpm:g} rpm"] = entry
    result["wall time [s]"] = time.perf_counter() - t0
    result["load average at the end"] = list(os.getloadavg())
    write_json(HERE / "results" / "roller_traction_laws.json", result)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(LAW_SPEEDS_RPM), figsize=(15, 4.6), sharey=True)
    colours = {"limited": "C0", "paper": "C3", "map": "C2"}
    for ax, rpm in zip(axes, LAW_SPEEDS_RPM):
        e = result["points"][f"{rpm:g} rpm"]
        for name, ls in (("cup", "-"), ("cone", "--")):
            for law in LAWS:
                ax.loglog(LAW_SRR, curves[(rpm, name, law)], ls, color=colours[law], label=f"{law}, {name}")
        w = e["races"]["cone"]["line load [N/m]"]
        ax.axhline(e["races"]["cone"]["laws"]["limited"]["checks"]["closed form gamma_L + 2 b tau_L0/w"], color="0.6",
                   lw=0.8, ls=":")
        ax.set_title(f"{rpm:g} rpm: u_e {e['entrainment speed [m/s]']:.2f} m/s, cone {w / 1e3:.0f} kN/m, "
                     f"p_H {e['races']['cone']['Hertz peak pressure [Pa]'] / 1e9:.2f} GPa", fontsize=9)
        ax.set_xlabel("slide-to-roll ratio [-]")
        ax.set_ylim(1e-9, 0.2)
    axes[0].set_ylabel("traction coefficient [-]")
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("paper A's most loaded roller (F_r 20 kN): the tapered model's raceway laws; dotted: limited law's "
                 "closed-form plateau; no published curve with stated inputs found")
    fig.tight_layout()
    save_figure(fig, HERE / "results" / "roller_traction_laws.png")
    return result


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("sweep", "summary", "laws"))
    ap.add_argument("tag", nargs="?")
    ap.add_argument("--races", default="cone,cup")
    ap.add_argument("--speeds", default="7,7.408,7.857,8.819")
    ap.add_argument("--loads", default="5000,150000,73", help="first, last, count (log)")
    ap.add_argument("--density", default="dowson_higginson")
    ap.add_argument("--resolution", default="default")
    ap.add_argument("--coefficients", default="", help="override the kinds' 'secant' (e.g. 'linearised')")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--refine", type=float, default=1.0, help="graded line grid: the kinds' grid_refine (1: uniform)")
    ap.add_argument("--direct", action="store_true", help="laws: the map's traction against direct EHL solves")
    a = ap.parse_args(argv)
    if a.mode == "laws":
        r = laws(a.direct)
        for rpm, e in r["points"].items():
            for name, rr in e["races"].items():
                print(rpm, name, {k: v.get("checks") for k, v in rr["laws"].items()})
    elif a.mode == "sweep":
        lo, hi, n = a.loads.split(",")
        sweep(a.tag, a.races.split(","), [float(s) for s in a.speeds.split(",")], np.geomspace(float(lo), float(hi), int(n)),
              a.density, a.resolution, a.coefficients, a.workers, a.refine)
    else:
        print(summary())


if __name__ == "__main__":
    main()
