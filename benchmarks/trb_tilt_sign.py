"""Paper A's Fig. 5 point with each raceway traction law: which law gives which sign of the mean roller tilt, and why.

Runs ``cases/trb_fig5_2400rpm.toml`` (2,400 rpm, F_r 20 kN, axial locked, 10 slices, RK4 "auto") for
``--duration`` (default 40 ms) with ``model.traction`` = "limited" (the default), "paper" (eq. 12 as printed)
and "map" (the roller EHL maps), one after the other, and reports over the record's second half, per law:

- loaded- and unloaded-zone means of tilt (the scene's, from each roller's start, and from the nominal
  axis angle, the quasi-static start's reference), skew, roller slip and spin slip, the cage slip;
- the zone means of the terms of the contacts' moment about each roller's tilt axis through its mass
  centre (the kernel's diagnostics, :data:`lubedyn.dynamics.tapered.layout.TILT_MOMENT_NAMES`: cup and cone
  normal loads, cup and cone traction, flange normal force and friction, cage) and their sum;
- two independent checks of those moments: (1) their sum against the gyroscopic moment steady orbiting
  needs, Omega sin(beta) [I_x (omega_s + Omega cos beta) - I_y Omega cos beta] from the sampled attitude and
  speeds (Euler's equations of a roller orbiting at Omega and spinning at omega_s, the tilt's own
  acceleration averaging out); (2) the raceway traction's moment against the closed form of a skewed
  roller's axial traction couple, rho_m [mu_cup(|psi|) Q_cup + mu_cone(|psi|) Q_cone] sign(psi) (rho_m the
  mean roller radius, psi the mean skew, Q the mean raceway loads, mu the law at slide-to-roll ratio
  |psi|: the axial sliding psi u_e over the entrainment speed u_e);
- the quasi-static start's roller tilt (the rib's normal moment against the raceways, no traction) and the
  raceway normal loads' tilt stiffness k = dM/d(tilt), closed form sum (10/9) (q_k/delta_k) (u_k - u_c)^2
  over the start's loaded slices (Palmgren q = k_w delta^(10/9)), against the runs' own ratio of the
  change of the normal loads' moment to the change of tilt between two laws.

``python benchmarks/trb_tilt_sign.py [--duration 40] [--laws limited,paper,map]`` ->
results/trb_tilt_sign.json and results/trb_tilt_sign.png.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

CASE = "cases/trb_fig5_2400rpm.toml"
TERMS = ("cup normal", "cone normal", "cup traction", "cone traction", "flange normal", "flange friction", "cage")


def tilt_stiffness(model, qs, j):
    """Closed-form tilt stiffness [N m/rad] of roller j's raceway line contacts about its mass centre at
    the quasi-static start: sum over both raceways' loaded slices of (10/9) q_k/delta_k (u_k - u_c)^2,
    delta_k = (q_k/k_w)^(9/10) (Palmgren's slice law, the kernel's k_w)."""
    args = model.args(qs)
    P = args.P[0]
    u = np.asarray(args.U) - P.uc
    k = 0.0
    for q in (qs.cup_slice_loads[j], qs.cone_slice_loads[j]):
        q = np.asarray(q, float)
        on = q > 0.0
        delta = (q[on] / P.kw) ** 0.9
        k += float(np.sum(10.0 / 9.0 * q[on] / delta * u[on] ** 2))
    return k


def gyroscopic_demand(model, Y):
    """The contacts' moment about each roller's tilt axis [N m] that steady orbiting needs, per sample and
    roller: Omega sin(beta) [I_x (omega_s + Omega cos beta) - I_y Omega cos beta] (module docstring)."""
    from lubedyn.dynamics.tapered.model import attitude

    beta, _, orbital, spin = attitude(Y, model.n_rollers)
    P = model.args().P[0]
    return orbital * np.sin(beta) * (P.ix * (spin + orbital * np.cos(beta)) - P.iy * orbital * np.cos(beta))


def run_law(law, duration_ms):
    from lubedyn.config import load_case
    from lubedyn.scenes import tapered as S

    case = load_case(str(HERE.parent / CASE), overrides=[f"model.traction={law}",
                                                          f"integrator.duration={duration_ms} ms"])
    t0, c0 = time.perf_counter(), time.process_time()
    run = S.run(case)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    model = S.build(case)
    qs = model.quasi_static()
    args = model.args(qs)
    t, Y, D = run.t, run.y, run.diagnostics
    lo = 0.5 * t[-1]
    w = t >= lo
    zone = D["Loaded zone [-]"][w]
    s = run.summary
    key = next(k for k in ("Last cage revolution", "Record's second half (shorter than a cage revolution)") if k in s)
    win = s[key]

    def zmean(name, sel):
        x = D[name][w][sel]
        return float(np.mean(x)) if x.size else None

    out = {"law": law, "window [s]": [float(lo), float(t[-1])], "window source": key,
           "wall time [s]": wall, "CPU time of the process [s]": cpu,
           "RK4 step [s]": s.get("RK4 step [s]"), "Integration wall time [s]": s.get("Integration wall time [s]")}
    from lubedyn.dynamics.tapered.model import attitude

    # the tilt from the nominal (unloaded) axis angle: the quasi-static start's tilt is in the same
    # reference; the scene's "Tilt [rad]" is each roller's from its own start, whose azimuth (and so
    # quasi-static tilt) differs from where the roller is later
    D["Tilt from the nominal axis [rad]"] = attitude(Y, model.n_rollers)[0] - model.geometry.roller_axis_angle
    for name in ("Tilt [rad]", "Tilt from the nominal axis [rad]", "Skew [rad]", "Roller slip [-]", "Spin slip [-]"):
        out[name] = {"loaded zone": zmean(name, zone), "unloaded zone": zmean(name, ~zone)}
    out["Cage slip [-]"] = float(np.mean(D["Cage slip [-]"][w]))
    out["Tilt moment means [N m]"] = win["Tilt moment means [N m]"]
    g = gyroscopic_demand(model, Y)[w]
    out["Gyroscopic demand [N m]"] = {"loaded zone": float(np.mean(g[zone])), "unloaded zone": float(np.mean(g[~zone]))}
    # the closed form of the skewed rollers' axial traction couple (loaded zone)
    psi = out["Skew [rad]"]["loaded zone"]
    q_cup, q_cone = zmean("Cup load [N]", zone), zmean("Cone load [N]", zone)
    le = model.geometry.effective_length
    mu = [model.raceway_traction_coefficient(r, q / le, abs(psi), args) for r, q in (("cup", q_cup), ("cone", q_cone))]
    rho = model.geometry.mean_roller_radius
    couple = math.copysign(rho * (mu[0] * q_cup + mu[1] * q_cone), psi)
    m = out["Tilt moment means [N m]"]["loaded zone"]
    out["Axial traction couple, closed form"] = {
        "mean roller radius [m]": rho, "mean skew [rad]": psi, "cup, cone load [N]": [q_cup, q_cone],
        "law's mu at |psi| (cup, cone) [-]": mu, "couple [N m]": couple,
        "measured cup + cone traction moment [N m]": m["cup traction"] + m["cone traction"],
        "measured / closed form [-]": (m["cup traction"] + m["cone traction"]) / couple if couple else None}
    j = int(np.argmax(qs.cone_loads))
    loaded0 = qs.cone_loads > 0.1 * qs.cone_loads.max()
    out["Quasi-static start"] = {"roller tilt, most loaded roller [rad]": float(qs.roller_tilts[j]),
                                 "roller tilt, loaded-zone mean [rad]": float(np.mean(qs.roller_tilts[loaded0])),
                                 "raceway tilt stiffness, most loaded roller, closed form [N m/rad]":
                                     tilt_stiffness(model, qs, j)}
    # a 1-ms running mean of the loaded zone's tilt and skew (the figure)
    tz = np.where(D["Loaded zone [-]"], D["Tilt from the nominal axis [rad]"], np.nan)
    kz = np.where(D["Loaded zone [-]"], D["Skew [rad]"], np.nan)
    n = max(1, int(round(1e-3 / (t[1] - t[0]))))
    out["_series"] = {"t": t[::n].tolist(), "tilt": [float(np.nanmean(tz[i:i + n])) for i in range(0, len(t), n)],
                      "skew": [float(np.nanmean(kz[i:i + n])) for i in range(0, len(t), n)]}
    return out


def main(argv=None):
    from _common import machine_info, save_figure, write_json

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=40.0, help="simulated time [ms]")
    ap.add_argument("--laws", default="limited,paper,map")
    a = ap.parse_args(argv)
    runs = {law: run_law(law, a.duration) for law in a.laws.split(",")}
    result = {"machine": machine_info(), "load average at the end": list(os.getloadavg()), "case": CASE,
              "duration [ms]": a.duration, "runs": {k: {kk: vv for kk, vv in v.items() if kk != "_series"}
                                                     for k, v in runs.items()}}
    # the normal loads' tilt stiffness the runs show: change of their moment against the change of tilt
    if "limited" in runs and "paper" in runs:
        A, B = runs["limited"], runs["paper"]

        def normal(r):
            m = r["Tilt moment means [N m]"]["loaded zone"]
            return m["cup normal"] + m["cone normal"]

        dt = A["Tilt from the nominal axis [rad]"]["loaded zone"] - B["Tilt from the nominal axis [rad]"]["loaded zone"]
        result["Normal loads' tilt stiffness, limited vs paper [N m/rad]"] = -(normal(A) - normal(B)) / dt
    write_json(HERE / "results" / "trb_tilt_sign.json", result)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6))
    x = np.arange(len(TERMS) + 1)
    width = 0.8 / len(runs)
    for i, (law, r) in enumerate(runs.items()):
        m = r["Tilt moment means [N m]"]["loaded zone"]
        ax.bar(x + (i - (len(runs) - 1) / 2) * width, [m[k] for k in TERMS] + [m["sum"]], width, label=law)
        sr = r["_series"]
        bx.plot(np.array(sr["t"]) * 1e3, np.array(sr["tilt"]) * 1e6, label=f"{law}")
    ax.set_xticks(x, list(TERMS) + ["sum"], rotation=30, ha="right")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylabel("loaded-zone mean moment about the tilt axis [N m]")
    ax.set_title(f"tilt moment terms, {a.duration / 2:g}-{a.duration:g} ms")
    ax.legend()
    bx.axhline(0.0, color="k", lw=0.5)
    bx.set_xlabel("t [ms]")
    bx.set_ylabel("loaded-zone tilt from nominal axis [1e-6 rad]")
    bx.set_title("1 ms means; paper A, Fig. 6: mean tilt -14e-6 rad at 2 krpm")
    bx.legend()
    fig.tight_layout()
    save_figure(fig, HERE / "results" / "trb_tilt_sign.png")
    for law, r in result["runs"].items():
        print(law, {k: r[k] for k in ("Tilt [rad]", "Tilt from the nominal axis [rad]", "Skew [rad]", "Roller slip [-]",
                                      "Cage slip [-]")})


if __name__ == "__main__":
    main()
