"""Paper A's speed series in time (issue 23 sec. 3, last item): the bundled cases
cases/trb_speed_{2,3,4,5}krpm.toml and trb_fig5_2400rpm.toml run for the paper's 0.18 s with RK4 at a step
below the model's stable-step estimate, averaged over the paper's window 0.1-0.18 s (loaded zone),
beside the numbers paper A reports (Figs. 6-7; notes sec. 4): mean skew 3.06e-3 rad at 2 krpm rising to
4.47e-3 rad at 5 krpm, mean tilt -0.14e-4 to -0.40e-4 rad, skew measured in the literature 0.15-0.45 deg.
Reported comparisons, not tolerances.  Writes ``results/trb_paper_series.json`` and ``.png``.

``python benchmarks/trb_paper_series.py [--duration 0.18] [--slices 10]``"""
from __future__ import annotations

import argparse
import importlib.util
import sys
import time
from pathlib import Path

_HERE = Path(__file__).resolve().parent
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != _HERE]
_spec = importlib.util.spec_from_file_location("_common", _HERE / "_common.py")
_common = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_common)
RESULTS, ROOT, machine_info, write_json = _common.RESULTS, _common.ROOT, _common.machine_info, _common.write_json

CASES = {2000: "trb_speed_2krpm", 2400: "trb_fig5_2400rpm", 3000: "trb_speed_3krpm", 4000: "trb_speed_4krpm",
         5000: "trb_speed_5krpm"}
PAPER = {"Skew, loaded zone, mean [rad]": {2000: 3.06e-3, 5000: 4.47e-3},
         "Tilt, loaded zone, mean [rad]": {2000: -0.14e-4, 5000: -0.40e-4}}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=0.18)
    ap.add_argument("--slices", type=int, default=10)
    a = ap.parse_args(argv)
    from coupling import tapered_scene as S
    from coupling.config import load_case

    rows = {}
    for rpm, name in CASES.items():
        over = [f"integrator.duration={a.duration}", f"model.slices={a.slices}", "output.write=[]"]
        est = S.build(load_case(ROOT / "cases" / f"{name}.toml", overrides=over)).stable_step()
        dt = 0.8 * est
        case = load_case(ROOT / "cases" / f"{name}.toml", overrides=over + ["integrator.method=rk4", f"integrator.dt={dt}"])
        t0 = time.perf_counter()
        s = S.run(case).summary
        w = S.main_window(s)[2]
        rows[rpm] = {"case": name, "RK4 step [s]": dt, "wall [s]": time.perf_counter() - t0, "window [s]": w["Window [s]"],
                     "Skew, loaded zone, mean [rad]": w["Skew [rad]"]["loaded zone"]["mean"],
                     "Skew, unloaded zone, mean [rad]": w["Skew [rad]"]["unloaded zone"]["mean"],
                     "Tilt, loaded zone, mean [rad]": w["Tilt [rad]"]["loaded zone"]["mean"],
                     "Roller slip, loaded zone, mean [-]": w["Roller slip [-]"]["loaded zone"]["mean"],
                     "Roller slip, unloaded zone, mean [-]": w["Roller slip [-]"]["unloaded zone"]["mean"],
                     "Cage slip, mean [-]": w["Cage slip [-]"]["mean"],
                     "Skew periodicity [-]": w.get("Skew periodicity [-]"),
                     "Tilt periodicity [-]": w.get("Tilt periodicity [-]")}
    out = {"machine": machine_info(), "simulated time [s]": a.duration, "slices": a.slices, "runs": rows,
           "paper A": {k: {str(r): v for r, v in d.items()} for k, d in PAPER.items()}}
    write_json(RESULTS / "trb_paper_series.json", out)
    _chart(out)
    return out


def _chart(out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rpm = sorted(out["runs"])
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for ax, key in zip(axes[:2], ("Skew, loaded zone, mean [rad]", "Tilt, loaded zone, mean [rad]")):
        ax.plot(rpm, [out["runs"][r][key] for r in rpm], "o-", label="lubedyn (0.1-0.18 s, loaded zone)")
        p = PAPER[key]
        ax.plot(sorted(p), [p[r] for r in sorted(p)], "s--", label="paper A (Figs. 6-7)")
        ax.set_xlabel("cone speed [rpm]")
        ax.set_ylabel(key.replace(", loaded zone", ""))
        ax.legend(fontsize=8)
    ax = axes[2]
    for key in ("Roller slip, loaded zone, mean [-]", "Roller slip, unloaded zone, mean [-]", "Cage slip, mean [-]"):
        ax.plot(rpm, [out["runs"][r][key] for r in rpm], "o-", label=key.replace(", mean [-]", ""))
    ax.set_xlabel("cone speed [rpm]")
    ax.set_ylabel("slip (eq. 52) [-]")
    ax.legend(fontsize=8)
    fig.suptitle(f"paper A's speed series, Fr 20 kN, {out['slices']} slices; {out['machine'].get('cpu', '')}",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(RESULTS / "trb_paper_series.png", dpi=110)


if __name__ == "__main__":
    import json

    print(json.dumps(main()["runs"], indent=1))
