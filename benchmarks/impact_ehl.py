"""Paper B's ball-ball collision through the oil film, solved in time (lubedyn.lubrication.ehl.impact): the
reference for the quasi-steady ball-ball film of the dynamics.

Two free steel balls of paper B (radius 4.7625 mm, E = 207 GPa, nu = 0.29, density 7850 kg/m^3: R_eff = R/2,
m_eff = m/2, E* = E/(2 (1 - nu^2))) collide head-on through Table 1's oil (eta0 = 0.050 Pa s, Barus
alpha = 1.85e-8 m^2/N, rho0 = 992 kg/m^3 with Dowson-Higginson compressibility; Roelands with the same
low-pressure slope for comparison) at the approach speeds of the drops: the ball-ball approach speeds of a
5 ms smoke run of ``cases/cageless_6206_10krpm_short.toml`` (179 collisions; relative normal speed 4 us
before each collision's start) have quartiles 0.03 / 0.18 / 0.50 m/s and a 90th percentile of 1.13 m/s;
here 0.05, 0.2, 0.5 and 1.0 m/s.

Each impact starts at the rigid gap where Reynolds' isoviscous squeeze force is 0.5 % of the Hertz
force (h_start = 6 pi eta0 R^2 v/(0.005 F*), at least 2 um) and runs to separation.  Outputs per speed:
restitution, energy dissipated (kinetic, and the film's viscous integral), largest force against Hertz,
minimum film, central film at the largest force, largest pressure, cost per impact; the histories.

Measured (160 nodes, 300 steps per Hertz duration; Barus / Roelands):

    v [m/s]   e              F_max/F_Hertz   h_min [nm]   h(0) at F_max [nm]   p_max [GPa]   cost [s, wall, shared machine]
    0.05      0.661 / 0.654  0.61 / 0.60     179 / 167    387 / 360            5.2 / 4.4     29 / 28
    0.2       0.904 / 0.902  0.84 / 0.84     272 / 253    828 / 774            9.3 / 7.6     14 / 7
    0.5       0.957 / 0.956  0.91 / 0.91     339 / 313    1317 / 1234          7.8 / 9.0     15 / 5
    1.0       0.975 / 0.975  0.93 / 0.93     392 / 361    1866 / 1749          15.2 / 11.8   13 / 5

The kinetic energy lost and the film's integrated dissipation agree within 2.1 % (the compressible film
stores some energy).  At 0.2 m/s (Barus): 80 instead of 160 nodes move e by -0.0041 and F_max by -0.2 %;
150 instead of 300 steps by < 1e-4; doubling the start gap lowers e by 0.0126 (0.904 -> 0.892): the
squeeze film dissipates 6 pi eta0 R^2 v^2 ln 2 per doubling of the gap (rigid, isoviscous: 2 % of the
kinetic energy at 0.2 m/s), so the restitution of a lubricated impact depends on where the approach
starts, and a quasi-steady law must be compared with this reference from the same gap.  The largest
pressure (the spike) is not resolved at 160 nodes (it jumps between speeds); the other outputs are.

Against the dynamics' own quasi-steady ball-ball law (:func:`quasi_steady`: the bundled film map or the
closed-form squeeze film in series with Hertz, same bodies, same start gap), measured:

    v [m/s]   e: transient / map / closed form   E_diss: map, closed form / transient   F_max: map, closed / transient
    0.05      0.661 / 0.829 / 0.737               0.56, 0.81                            0.86, 1.14
    0.2       0.904 / 0.973 / 0.938               0.29, 0.66                            0.85, 1.10
    0.5       0.957 / 0.993 / 0.976               0.17, 0.57                            0.86, 1.07
    1.0       0.975 / 0.998 / 0.988               0.08, 0.47                            0.87, 1.06

The map law dissipates 2-12 times less than the transient film (its film locks at 16.5 nm, where the
solids carry the load without loss, while the transient film keeps 0.18-0.39 um under an entrapped
dimple) and its largest force is 13-15 % low; the closed form is closer in energy (0.47-0.81) and 6-14 %
high in force.  Cost per impact: 5-28 s transient (160 nodes), 0.05-0.3 s quasi-steady.

"map memory": the map law whose lock keeps h_L at the impact speed (``ball_ball_normal(..., h_keep)``): the
transient's entrapped central film is 0.64-0.69 h_L(v0), but keeping the film changes the restitution by at
most 0.007 (the locked solids carry the load without loss); the transient loses 68-77 % of its energy while
the balls are loaded, which no quasi-steady law here has.

``python benchmarks/impact_ehl.py [--nodes N] [--steps S]`` -> results/impact_ehl.{json,png}
(about 5 minutes on one core of a shared machine); ``--quasi-only`` reruns the quasi-steady laws against the
stored transient rows.
"""
from __future__ import annotations

import argparse
import functools
import json
import math
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from _common import RESULTS, machine_info, save_figure, write_json  # noqa: E402

SPEEDS = (0.05, 0.2, 0.5, 1.0)
#: the dynamics' quasi-steady ball-ball laws compared with the transient reference
QUASI_STEADY = ("map", "map_damped", "map_memory", "closed_form")


def balls():
    r = 4.7625e-3
    e_star = 207e9 / (2 * (1 - 0.29**2))
    m = 7850.0 * 4.0 / 3.0 * math.pi * r**3
    return dict(radius=r / 2, e_star=e_star, mass=m / 2)


def run(speed, law="barus", nodes=160, steps=300, h_factor=1.0):
    from lubedyn.lubrication.ehl.impact import ImpactNumerics, ImpactProblem, hertz_impact, simulate_impact
    from lubedyn.lubrication.laws.lubricant import Barus, DowsonHigginson, Lubricant, Roelands

    b = balls()
    visc = Barus(0.05, 1.85e-8) if law == "barus" else Roelands(0.05, alpha=1.85e-8)
    hz = hertz_impact(b["radius"], b["e_star"], b["mass"], speed)
    h_start = h_factor * max(2e-6, 6 * math.pi * 0.05 * b["radius"] ** 2 * speed / (0.005 * hz.force))
    pb = ImpactProblem(**b, lubricant=Lubricant(visc, DowsonHigginson(992.0)), speed=speed, h_start=h_start)
    res = simulate_impact(pb, ImpactNumerics(nodes=nodes, steps_per_contact=steps))
    s = res.summary()
    s.update(speed=speed, law=law, nodes=nodes, steps_per_contact=steps, h_start=h_start,
             hertz=dict(force=hz.force, approach=hz.approach, duration=hz.duration, radius=hz.radius,
                        pressure=hz.pressure),
             force_over_hertz=s["force_max"] / hz.force)
    i = np.linspace(0, len(res.t) - 1, min(len(res.t), 400)).astype(int)
    history = dict(t=res.t[i], h0=res.h0[i], h_central=res.h_central[i], h_min=res.h_min[i], p_max=res.p_max[i],
                   force=res.force[i])
    return s, history


@functools.lru_cache(maxsize=1)
def _bundled_map():
    from lubedyn.dynamics.cageless import _map_arrays
    from lubedyn.maps import FilmMap

    return _map_arrays(FilmMap.load(HERE.parent / "cases" / "maps" / "ball_ball.npz").dynamics_film_map(), None)


def quasi_steady(speed, h_start, film="map", beta=None):
    """The dynamics' own ball-ball law (:func:`lubedyn.dynamics.contacts.ball_ball_normal`: the film, from
    the bundled map ``cases/maps/ball_ball.npz`` or the closed form, in series with Hertz; elastic solids,
    no contact damping, the bundled case's rupture thickness 0.1 um), integrated as a free impact of the
    same bodies from the same start gap (:func:`lubedyn.dynamics.contacts.head_on_impact`): restitution,
    largest force, energy dissipated, cost.  ``film``: "map" (the lock without damping), "map_damped" (the
    lock with the entrapped film's damping beta C0 v/h_L, ``beta`` None: the calibrated default
    ENTRAPPED_DAMPING), "map_memory" (the lock keeping h_L of the impact speed), "closed_form"."""
    from lubedyn.dynamics.contacts import FILM_CLOSED_FORM, FILM_MAP, _lock, head_on_impact, with_map_ends
    from lubedyn.lubrication.laws.collision import ENTRAPPED_DAMPING, ball_ball_parameters

    b = balls()
    beta = (ENTRAPPED_DAMPING if beta is None else beta) if film == "map_damped" else 0.0
    p = ball_ball_parameters(ball_radius=2 * b["radius"], e_star=b["e_star"], viscosity=0.05,
                             rupture_thickness=1e-7, pressure_viscosity=1.85e-8, entrapped_damping=beta)
    ma = None
    if film.startswith("map"):
        ma = _bundled_map()
        p = with_map_ends(p, ma.ax0, ma.ax1, ma.opts)
    # "map_memory": the lock keeps the largest h_L of the contact; in a single impact the approach speed
    # only falls from the impact speed, so that is h_L(v0), held throughout
    keep = _lock(speed, 0.0, p, FILM_MAP, ma.ax1, ma.values, ma.opts) if film == "map_memory" else 0.0
    out = head_on_impact(p, b["mass"], speed, h_start, FILM_MAP if ma is not None else FILM_CLOSED_FORM, ma,
                         h_keep=keep)
    return dict(film=film, entrapped_damping=beta, kept_film=keep, **out)


def coarse_transients(rows, resolutions=((40, 100), (80, 150))):
    """The transient reference at coarser nodes / steps per contact, for the accuracy-cost chart: restitution
    and cost per impact at each speed (Barus)."""
    out = []
    for nodes, steps in resolutions:
        for r in rows:
            if r["law"] == "barus":
                s, _ = run(r["speed"], "barus", nodes, steps)
                out.append(dict(speed=r["speed"], nodes=nodes, steps_per_contact=steps, restitution=s["restitution"],
                                seconds=s["seconds"]))
                print(f"   transient {nodes} nodes, {steps} steps: v {r['speed']} e {s['restitution']:.4f} "
                      f"{s['seconds']:.2f} s", flush=True)
    return out


def calibrate(rows, speed=0.2):
    """beta of the entrapped film's damping that makes the damped lock restitute as the transient at
    ``speed`` (Brent on the restitution), then the other speeds predicted with it."""
    from scipy.optimize import brentq

    ref = next(r for r in rows if r["law"] == "barus" and r["speed"] == speed)
    beta = brentq(lambda b: quasi_steady(speed, ref["h_start"], "map_damped", b)["restitution"] - ref["restitution"],
                  0.5, 2.0, xtol=1e-3)
    out = dict(speed=speed, beta=beta, rows=[])
    for r in rows:
        if r["law"] == "barus":
            q = quasi_steady(r["speed"], r["h_start"], "map_damped", round(beta, 2))
            out["rows"].append(dict(speed=r["speed"], transient=r["restitution"], law=q["restitution"],
                                    energy_ratio=q["energy_dissipated"] / r["energy_dissipated"],
                                    force_ratio=q["force_max"] / r["force_max"]))
            print(f"   v {r['speed']:.2f} m/s: e {q['restitution']:.4f} (transient {r['restitution']:.4f})  "
                  f"E_diss x {out['rows'][-1]['energy_ratio']:.3f}  F_max x {out['rows'][-1]['force_ratio']:.3f}",
                  flush=True)
    print(f"beta = {beta:.4f} at {speed} m/s", flush=True)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, default=160)
    ap.add_argument("--steps", type=int, default=300, help="time steps per Hertz contact duration")
    ap.add_argument("--out", type=Path, default=RESULTS / "impact_ehl.json")
    ap.add_argument("--quasi-only", action="store_true",
                    help="rerun only the quasi-steady laws against the transient rows stored in --out")
    ap.add_argument("--calibrate", action="store_true",
                    help="refit the entrapped film's damping on the transient rows stored in --out")
    args = ap.parse_args(argv)
    if args.calibrate:
        data = json.loads(args.out.read_text())
        write_json(args.out, dict(data, calibration=calibrate(data["rows"]), machine_calibration=machine_info()))
        return
    if args.quasi_only:
        data = json.loads(args.out.read_text())
        for s in data["rows"]:
            if s["law"] == "barus":
                s["quasi_steady"] = [quasi_steady(s["speed"], s["h_start"], film) for film in QUASI_STEADY]
                print(s["speed"], [(q["film"], round(q["restitution"], 4)) for q in s["quasi_steady"]], flush=True)
        data["coarse"] = coarse_transients(data["rows"])
        write_json(args.out, dict(data, machine_quasi_steady=machine_info()))
        plot(data["rows"], data["histories"], args.out, data["coarse"])
        return
    rows, histories = [], {}
    for law in ("barus", "roelands"):
        for v in SPEEDS:
            s, h = run(v, law, args.nodes, args.steps)
            if law == "barus":
                s["quasi_steady"] = [quasi_steady(v, s["h_start"], film) for film in QUASI_STEADY]
                for q in s["quasi_steady"]:
                    print(f"   quasi-steady {q['film']:11s} e {q['restitution']:.4f}  F_max {q['force_max']:.2f} N "
                          f"(transient {s['force_max']:.2f})  E_diss {q['energy_dissipated']:.3e} J  "
                          f"{q['seconds']:.2f} s", flush=True)
            rows.append(s)
            histories[f"{law} {v}"] = h
            print(f"{law:8s} v {v:5.2f} m/s  e {s['restitution']:.4f}  E_diss {s['energy_dissipated']:.3e} J "
                  f"(film {s['energy_dissipated_film']:.3e})  F_max/F_Hertz {s['force_over_hertz']:.3f}  "
                  f"h_min {s['h_min'] * 1e9:.0f} nm  h_c(F_max) {s['h_central_at_force_max'] * 1e9:.0f} nm  "
                  f"p_max {s['p_max'] / 1e9:.2f} GPa  {s['seconds']:.1f} s", flush=True)
    # the start gap and the resolution at 0.2 m/s (Barus)
    checks = []
    for kw in (dict(h_factor=2.0), dict(nodes=args.nodes // 2), dict(steps=args.steps // 2)):
        s, _ = run(0.2, "barus", **{**dict(nodes=args.nodes, steps=args.steps), **kw})
        checks.append(dict(change=kw, restitution=s["restitution"], force_max=s["force_max"], h_min=s["h_min"],
                           h_central_at_force_max=s["h_central_at_force_max"], seconds=s["seconds"]))
        print("check", kw, f"e {s['restitution']:.4f}  F_max {s['force_max']:.3f} N  h_min {s['h_min'] * 1e9:.1f} nm",
              flush=True)
    write_json(args.out, dict(machine=machine_info(), balls=balls(), speeds=SPEEDS, rows=rows, checks=checks,
                              histories=histories))
    plot(rows, histories, args.out)


def _loglog(ax, xlabel, ylabel):
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7)


def plot(rows, histories, out, coarse=None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 5 if coarse else 4, figsize=(24 if coarse else 19, 4.5), layout="constrained")
    for s in rows:
        h = histories[f"{s['law']} {s['speed']}"]
        t = (np.asarray(h["t"]) - h["t"][int(np.argmax(h["force"]))]) / s["hertz"]["duration"]
        ls = "-" if s["law"] == "barus" else "--"
        ax[0].plot(t, np.asarray(h["force"]) / s["hertz"]["force"], ls, label=f"{s['law']} {s['speed']} m/s")
        ax[1].plot(t, np.asarray(h["h_central"]) * 1e6, ls)
        ax[2].plot(t, np.asarray(h["h_min"]) * 1e6, ls)
    ax[0].set_ylabel("F / F_Hertz")
    ax[1].set_ylabel("central film h(0) [um]")
    ax[2].set_ylabel("minimum film [um]")
    barus = [s for s in rows if s["law"] == "barus"]
    v = [s["speed"] for s in barus]
    ax[3].plot(v, [1 - s["restitution"] for s in barus], "o-", label="transient EHL (Barus)")
    ax[3].plot(v, [1 - s["restitution"] for s in rows if s["law"] == "roelands"], "s--", label="transient EHL (Roelands)")
    for k, film in enumerate(QUASI_STEADY):
        ax[3].plot(v, [1 - s["quasi_steady"][k]["restitution"] for s in barus], "^:",
                   label=f"quasi-steady {film.replace('_', ' ')}")
    _loglog(ax[3], "approach speed [m/s]", "1 - e")
    for a in ax[:3]:
        a.set_xlabel("(t - t(F_max)) / t_Hertz")
        a.set_xlim(-1.5, 1.5)
    ax[1].set_ylim(bottom=0)
    ax[2].set_ylim(bottom=0)
    ax[0].legend(fontsize=7)
    if coarse:  # accuracy against cost per impact: mean |e - e_transient(160 nodes)| over the four speeds
        ref = {s["speed"]: s["restitution"] for s in barus}
        def point(runs, marker, label):  # runs: (speed, restitution, seconds) -> mean cost, mean |e error|
            ax[4].plot(np.mean([r[2] for r in runs]), np.mean([abs(r[1] - ref[r[0]]) for r in runs]), marker, ms=9,
                       label=label)

        for k, film in enumerate(QUASI_STEADY):
            point([(s["speed"], s["quasi_steady"][k]["restitution"], s["quasi_steady"][k]["seconds"]) for s in barus],
                  "^", f"quasi-steady {film.replace('_', ' ')}")
        for nodes in sorted({c["nodes"] for c in coarse}):
            point([(c["speed"], c["restitution"], c["seconds"]) for c in coarse if c["nodes"] == nodes], "o",
                  f"transient, {nodes} nodes")
        _loglog(ax[4], "cost per impact [s]", "mean |e - e(transient, 160 nodes)|")
    fig.suptitle("Paper B ball-ball impact through Table 1's oil (transient EHL)")
    save_figure(fig, out.with_suffix(".png"))


if __name__ == "__main__":
    main()
