"""Paper A's Figures 5-16 from the project's studies, and the claim checklist beside them.

Run the studies first (``lubedyn study studies/<name>.toml --out runs/studies/<name>`` for trb_speed,
trb_preload, trb_plastic_viscosity, trb_yield_stress, trb_grease_temperature and the sensitivity studies
trb_sensitivity_* and trb_plastic_viscosity_paper_reading), then::

    python benchmarks/paper_a_figures.py [runs/studies]

Writes ``benchmarks/results/paper_a/fig05.png`` ... ``fig16.png`` (one figure per paper figure, the panels
as the paper's: Fig. 5 the cone orbit from the unloaded position, the roller displacements from the ideal
position, the cage whirl and speeds at 2,400 rpm, each with the paper's plotted ranges;
Figs. 6-9 tilt, skew, roller slip and cage slip of roller 0 against time at 2, 3, 4 and 5 krpm with the
loaded zone shaded; Figs. 10-13 the same against the preload; Figs. 14-16 the means against the parameter
over the paper's window and the converged window with the window-to-window change as error bars),
``claims.md`` (:func:`lubedyn.papers.wu2018.claims.markdown`: the verdict counts, the checklist, the
steadiness of every point, the elasticities and routes) and ``studies.json`` (every point's headline
numbers, for the docs).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]

from lubedyn.papers.wu2018 import claims as C  # noqa: E402
from lubedyn.outputs import read_timeseries, timeseries_path  # noqa: E402

OUT = ROOT / "benchmarks" / "results" / "paper_a"
SPEEDS = ("2000 rpm", "3000 rpm", "4000 rpm", "5000 rpm")
PRELOADS = ("10 um", "20 um", "30 um", "40 um")
#: Figs. 6-9 and 10-13: (time-series column, scale, axis label, what)
TIME_PANELS = (("Roller 0 tilt [rad]", 1e4, "tilt [1e-4 rad]", "roller tilt"),
               ("Roller 0 skew [rad]", 1e3, "skew [1e-3 rad]", "roller skew"),
               ("Roller 0 roller slip [-]", 100.0, "roller slip [%]", "roller slip (eq. 52)"),
               ("Cage slip [-]", 100.0, "cage slip [%]", "cage slip (eq. 52)"))


def _series(folder: Path):
    cols, _ = read_timeseries(timeseries_path(folder))
    return cols


def _shade(ax, t, loaded):
    """Shade the samples where the roller is in the loaded zone."""
    edges = np.flatnonzero(np.diff(np.r_[0, loaded.astype(int), 0]))
    for a, b in zip(edges[::2], edges[1::2]):
        ax.axvspan(t[a], t[min(b, len(t) - 1)], color="0.9", lw=0)


def _time_figure(st: C.Study, key: str, labels, column: str, scale: float, ylabel: str, title: str, path: Path,
                 paper_window=(0.1, 0.18)):
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True)
    for ax, lab in zip(axes.ravel(), labels):
        idx = st.where(**{key: lab})
        if not idx:
            ax.set_title(f"{lab}: not run")
            continue
        cols = _series(st.folders[idx[0]])
        t = cols["Time [s]"]
        x = cols[column]
        if "Roller 0 loaded zone [-]" in cols and column.startswith("Roller 0"):
            _shade(ax, t, cols["Roller 0 loaded zone [-]"] > 0.5)
        ax.plot(t, scale * x, lw=0.7)
        ax.axvspan(*paper_window, ymin=0, ymax=0.04, color="C3", alpha=0.6)
        ax.set_title(lab, fontsize=9)
        ax.set_ylabel(ylabel, fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]  (red bar: paper A's averaging window; grey: roller 0 in the loaded zone)", fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fig05(st: C.Study, path: Path):
    idx = st.where(speed="2400 rpm")
    if not idx:
        return None
    folder = st.folders[idx[0]]
    cols = _series(folder)
    s = st.summaries[idx[0]]
    t = cols["Time [s]"]
    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    # (a) from the unloaded position: across the load (our z, the paper's y) against along it (our y, its z)
    run = t <= 0.18
    ax[0, 0].plot(1e6 * cols["Cone z [m]"][run], 1e6 * cols["Cone y [m]"][run], lw=0.5, label="lubedyn, 0-0.18 s")
    across, along = (1e6 * x for x in C.FIG5_CONE)
    ax[0, 0].plot([-across, across, across, -across, -across], [0, 0, along, along, 0], "C3--", lw=0.8,
                  label="paper A: about +-6 x 0-15 um")
    ax[0, 0].set(xlabel="cone centre across the load [um] (paper's y)",
                 ylabel="along the load [um] (paper's z)", title="(a) cone centre from the unloaded position")
    ax[0, 0].legend(fontsize=7)
    # (b) roller 0 from its ideal, unloaded position
    d = C.ideal_displacements(folder, cols)
    if d is not None:
        for k, (name, axis) in enumerate((("radial", C.FIG5_RADIAL), ("axial", C.FIG5_AXIAL))):
            ax[0, 1].plot(t, 1e6 * d[k][:, 0], lw=0.7, color=f"C{k}", label=name)
            for y in axis:
                ax[0, 1].axhline(1e6 * y, color=f"C{k}", ls=":", lw=0.8)
    ax[0, 1].set(xlabel="t [s]", ylabel="roller 0 from its ideal position [um]",
                 title="(b) roller displacement (dotted: paper A's axes)")
    ax[0, 1].legend(fontsize=8)
    ax[1, 0].plot(1e3 * cols["Cage centre from the cone's, y [m]"], 1e3 * cols["Cage centre from the cone's, z [m]"], lw=0.5)
    ax[1, 0].set(xlabel="cage centre y [mm]", ylabel="cage centre z [mm]", title="(c) cage centre whirl (from the cone's)")
    ax[1, 0].set_aspect("equal", adjustable="datalim")
    rpm = 30 / np.pi
    ax[1, 1].axhspan(*C.FIG5_CAGE, color="C3", alpha=0.12, label="paper A's axes 1.02-1.10 krpm")
    ax[1, 1].plot(t, rpm * cols["Cage speed [rad/s]"], lw=0.7, label="cage")
    ax[1, 1].plot(t, rpm * cols["Roller 0 orbital speed [rad/s]"], lw=0.5, label="roller 0 orbit")
    ax[1, 1].axhline(s["Ideal cage speed [rpm]"], color="k", ls="--", lw=0.8, label="ideal (model geometry)")
    ax[1, 1].axhline(C.FIG5_IDEAL, color="C3", ls=":", lw=0.8, label="paper A's ideal 1.058 krpm")
    ax[1, 1].set(xlabel="t [s]", ylabel="speed [rpm]", title="(d) cage and roller orbital speed", ylim=(1000, 1120))
    ax[1, 1].legend(fontsize=7)
    fig.suptitle("Paper A Fig. 5's point: Fr 20 kN, 2,400 rpm, axial locked (studies/trb_speed.toml)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _means_figure(st: C.Study, key: str, group: str | None, path: Path, title: str, paper: dict):
    quantities = (("Tilt [rad]", "loaded zone", "tilt, loaded zone [rad]", 1.0),
                  ("Skew [rad]", "loaded zone", "skew, loaded zone [rad]", 1.0),
                  ("Roller slip [-]", "loaded zone", "roller slip, loaded zone [%]", 100.0),
                  ("Cage slip [-]", None, "cage slip [%]", 100.0))
    fig, axes = plt.subplots(2, 2, figsize=(11, 7))
    groups = sorted({lab[st.axes.index(group)] for lab in st.labels}, key=str) if group else [None]
    kx = st.axes.index(next(a for a in st.axes if a.rpartition(".")[2] == key))
    for ax, (stat, zone, ylabel, scale) in zip(axes.ravel(), quantities):
        for gi, g in enumerate(groups):
            idx = [i for i, lab in enumerate(st.labels) if g is None or lab[st.axes.index(group)] == g]
            xs = [float(str(st.labels[i][kx]).split()[0]) for i in idx]
            order = np.argsort(xs)
            vals = [C.window_value(st.summaries[idx[o]], stat, zone) for o in order]
            x = np.asarray(xs)[order]
            p = [scale * v.paper if v.paper is not None else np.nan for v in vals]
            c = [scale * v.converged if v.converged is not None else np.nan for v in vals]
            u = [scale * abs(v.uncertainty) if v.uncertainty is not None else 0.0 for v in vals]
            lab = f"{g}: " if g else ""
            ax.plot(x, p, "o-", color=f"C{gi}", label=f"{lab}0.1-0.18 s (paper's window)")
            ax.errorbar(x, c, yerr=u, fmt="s--", color=f"C{gi}", mfc="none", capsize=3,
                        label=f"{lab}0.26-0.34 s (converged, +- window-to-window change)")
        if ylabel in paper:
            lo, hi = paper[ylabel]
            ax.axhspan(lo, hi, color="C3", alpha=0.15, label="paper A's range")
        ax.set_ylabel(ylabel, fontsize=8)
        ax.set_xlabel(st.axes[kx], fontsize=8)
    axes[0, 0].legend(fontsize=6)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main(argv=None) -> list[Path]:
    base = Path((argv or sys.argv[1:] or [ROOT / "runs" / "studies"])[0])
    OUT.mkdir(parents=True, exist_ok=True)
    written = []
    speed = C.Study.load(base / "trb_speed")
    if speed is not None and fig05(speed, OUT / "fig05.png"):
        written.append(OUT / "fig05.png")
    for st, key, labels, first, what_runs in (
            (speed, "speed", SPEEDS, 6, "Fr 20 kN, axial locked, 2-5 krpm"),
            (C.Study.load(base / "trb_preload"), "axial_displacement", PRELOADS, 10, "Fr 0, 2,500 rpm, preload 10-40 um")):
        if st is None:
            continue
        for n, (col, scale, ylabel, what) in enumerate(TIME_PANELS, start=first):
            path = OUT / f"fig{n:02d}.png"
            _time_figure(st, key, labels, col, scale, ylabel, f"Paper A Fig. {n}: {what}, {what_runs}", path)
            written.append(path)
    for n, name, key, group, title, paper in (
            (14, "trb_plastic_viscosity", "consistency", None,
             "Paper A Fig. 14: plastic viscosity phi, Fa 15 kN, Fr 0, 2,800 rpm", {"tilt, loaded zone [rad]": (-5.2e-5, -4.7e-5)}),
            (15, "trb_yield_stress", "yield_stress", None, "Paper A Fig. 15: yield stress, Fa 15 kN, Fr 0, 2,800 rpm",
             {"tilt, loaded zone [rad]": (-5.5e-5, -4.8e-5), "skew, loaded zone [rad]": (3.5e-3, 4.5e-3),
              "roller slip, loaded zone [%]": (0.009, 0.015), "cage slip [%]": (0.009, 0.015)}),
            (16, "trb_grease_temperature", "temperature_c", "lubricant.grease",
             "Paper A Fig. 16: three greases against temperature, Fa 15 kN, Fr 0, 2,800 rpm", {})):
        st = C.Study.load(base / name)
        if st is not None:
            written.append(_means_figure(st, key, group, OUT / f"fig{n:02d}.png", title, paper))
    (OUT / "claims.md").write_text(C.markdown(base) + "\n")
    written.append(OUT / "claims.md")
    table = {}
    for name in C.MAIN_STUDIES + C.SENSITIVITY_STUDIES:
        st = C.Study.load(base / name)
        if st is None:
            continue
        table[name] = [{"axes": dict(zip(st.axes, map(str, lab))),
                        **{k: s.get(k) for k in s if isinstance(s.get(k), (int, float, bool)) or s.get(k) is None}}
                       for lab, s in zip(st.labels, st.summaries)]
    (OUT / "studies.json").write_text(json.dumps(table, indent=1))
    written.append(OUT / "studies.json")
    return written


if __name__ == "__main__":
    for p in main():
        print(p)
