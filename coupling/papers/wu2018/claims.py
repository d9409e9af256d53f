"""Paper A's claims checked against the project's studies.

Paper A (Wu, Xu & Deng, *Shock and Vibration* 2018, 7183042) makes its claims figure by figure
(its Figs. 5-16, listed with what each claims in ``docs/paper_a.md``) and sums them up in four conclusions.  This
module reads the results of ``lubedyn study`` for the studies of ``studies/trb_*.toml`` (each point's
``summary.json``; the time series where a study keeps them) and returns every claim as a :class:`Claim`:
the paper's statement and number, the project's number with its uncertainty, a verdict and the reason.

Numbers and their uncertainty
-----------------------------
Each study runs 0.34 s.  A point's number is its mean over the paper's window (0.1-0.18 s, what the paper
averages); beside it the mean over the converged window (0.26-0.34 s).  The uncertainty of a mean is the
converged window's *window-to-window change* (its mean minus the mean over 0.18-0.26 s,
:func:`lubedyn.scenes.tapered.converged_summary`): how much the number still moves from one 80 ms window
to the next.

Verdict rules (stated once, applied by code)
--------------------------------------------
- **Trend** ("X rises with P"): the change of X from the first to the last value of P, in the paper's
  window and in the converged window.  *Reproduced* when both changes have the claimed sign and the
  converged one exceeds the two end points' uncertainties together; *not reproduced* when both have the
  opposite sign beyond that; otherwise *not resolved* (the change is inside the uncertainty, or the two
  windows disagree).  Trends in magnitude use |X| (the paper's slips and tilts have the other sign).
- **Little effect**: the change across the range is below :data:`LITTLE` (5 %) of the mean magnitude.
- **Level** (a number the paper prints): *reproduced* within a factor 1.3 (either way) and with the
  paper's sign; otherwise *not reproduced*, with the ratio.  The paper's numbers are reported
  comparisons, never tolerances the model was tuned to.
- **Periodic**: the roller-pass periodicity measure (:func:`lubedyn.dynamics.analysis.windows.periodicity`) at least
  :data:`PERIODIC` (0.95).
- **Zone comparison** ("larger in the unloaded zone"): the zones' values, each with its uncertainty where
  there is one; *reproduced* when the claimed order holds by more than a tenth of the larger.
- *Not comparable*: the paper's quantity is not defined the same way here (the reason is given), or the
  study has not been run (``not run``).

Which assumption moves a claim that is not reproduced: :func:`sensitivity` ranks the sensitivity studies
(``studies/trb_sensitivity_*.toml``, Fig. 5's point) by how far each assumed value moves the mean skew and
tilt.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from lubedyn.outputs import read_timeseries

#: "little effect": a change below this fraction of the mean magnitude
LITTLE = 0.05
#: "periodic": the roller-pass periodicity measure at least this
PERIODIC = 0.95
#: a printed level is reproduced within this factor (either way) and with the paper's sign
LEVEL_FACTOR = 1.3

PAPER_WINDOW = "Paper window (analysis.window)"
CONVERGED = "Converged window"

MAIN_STUDIES = ("trb_speed", "trb_preload", "trb_plastic_viscosity", "trb_yield_stress", "trb_grease_temperature")
SENSITIVITY_STUDIES = ("trb_sensitivity_shear_modulus", "trb_sensitivity_limiting_slope", "trb_sensitivity_rib_roughness",
                       "trb_sensitivity_rib_film", "trb_sensitivity_damping", "trb_sensitivity_flange_mixing",
                       "trb_plastic_viscosity_paper_reading", "trb_plastic_viscosity_apparent_reading")


@dataclass
class Claim:
    """One row of the checklist."""

    figure: str
    statement: str
    paper: str
    ours: str
    verdict: str
    note: str = ""


@dataclass
class Value:
    """A mean over the paper's window, over the converged window, and its uncertainty (the converged
    window's window-to-window change; 0 when the record is too short to have one, None when unknown)."""

    paper: float | None
    converged: float | None = None
    uncertainty: float | None = None

    def text(self, fmt=".3g") -> str:
        if self.paper is None:
            return "-"
        out = format(self.paper, fmt)
        if self.converged is not None:
            u = "" if self.uncertainty is None else f" +- {abs(self.uncertainty):.1g}"
            out += f" (converged {format(self.converged, fmt)}{u})"
        return out


@dataclass
class Study:
    """A study's points: axis values (as labelled) and each point's run summary."""

    name: str
    axes: list
    labels: list
    summaries: list
    folders: list = field(default_factory=list)

    @classmethod
    def load(cls, folder: Path) -> "Study | None":
        path = Path(folder) / "study.json"
        if not path.is_file():
            return None
        r = json.loads(path.read_text())
        axes = list(r["points"][0]["axes"])
        labels, summaries, folders = [], [], []
        for p in r["points"]:
            run = Path(folder) / p["run folders"][0]
            f = run / "summary.json"
            if not f.is_file():
                continue
            labels.append(tuple(p["axes"][a] for a in axes))
            summaries.append(json.loads(f.read_text()))
            folders.append(run)
        return cls(Path(folder).name, axes, labels, summaries, folders)

    def where(self, **fixed) -> list[int]:
        """Indices of the points whose axes (by the last part of their dotted key) have the given values."""
        out = []
        for i, lab in enumerate(self.labels):
            ok = True
            for k, v in fixed.items():
                a = next(j for j, name in enumerate(self.axes) if name.rpartition(".")[2] == k)
                ok &= str(lab[a]) == str(v)
            if ok:
                out.append(i)
        return out


def window_value(s: dict, stat: str, zone: str | None, what: str = "mean") -> Value:
    """The statistic ``stat`` ("Skew [rad]" ...) of a run summary, zone "loaded zone", "unloaded zone", "all"
    or None (a whole-bearing statistic such as "Cage slip [-]"), over the paper's window and the
    converged window, with the window-to-window change of the headline means as the uncertainty."""
    def pick(w):
        if not isinstance(w, dict) or stat not in w:
            return None
        x = w[stat]
        x = x[zone] if zone else x
        return x.get(what) if isinstance(x, dict) else x

    paper, conv = pick(s.get(PAPER_WINDOW)), pick(s.get(CONVERGED))
    unc = None
    c = s.get(CONVERGED)
    if isinstance(c, dict) and what == "mean":
        from lubedyn.scenes.tapered import HEADLINE  # deferred: numba

        key = next((name for name, st, z in HEADLINE if st == stat and z == zone), None)
        ch = c.get("Window-to-window change", {}).get(key)
        unc = None if ch is None else ch["change"]
    return Value(paper, conv, unc)


def _sign_word(x):
    return "rises" if x > 0 else "falls" if x < 0 else "is flat"


def trend(first: Value, last: Value, claimed: int, magnitude: bool = False) -> tuple[str, str]:
    """(verdict, what we measured) for the claim "X rises (claimed = +1) / falls (-1) from first to last"
    under the module's trend rule."""
    f = abs if magnitude else (lambda x: x)
    if first.paper is None or last.paper is None:
        return "not comparable", "no value (an empty zone)"
    dp = f(last.paper) - f(first.paper)
    have_conv = first.converged is not None and last.converged is not None
    dc = f(last.converged) - f(first.converged) if have_conv else dp
    u = abs(first.uncertainty or 0.0) + abs(last.uncertainty or 0.0)
    scale = max(abs(f(first.paper)), abs(f(last.paper)), 1e-300)
    what = ("|X| " if magnitude else "") + f"{_sign_word(dp)} by {dp:+.3g} ({100 * dp / scale:+.2g} %, paper's window)"
    if have_conv:
        what += f", {dc:+.3g} converged (uncertainty {u:.2g})"
    if abs(dc) <= u:
        return "not resolved", what + ": inside the window-to-window change"
    if np.sign(dp) != np.sign(dc):
        return "not resolved", what + ": the two windows disagree"
    return ("reproduced" if np.sign(dc) == claimed else "not reproduced"), what


def little_effect(values: list[Value]) -> tuple[str, str]:
    xs = [v.paper for v in values if v.paper is not None]
    if not xs:
        return "not comparable", "no value"
    scale = max(abs(float(np.mean(xs))), 1e-300)
    rel = (max(xs) - min(xs)) / scale
    verdict = "reproduced" if rel < LITTLE else "not reproduced"
    return verdict, f"{min(xs):.3g} to {max(xs):.3g} ({100 * rel:.2g} % of the mean)"


def level(ours: float | None, paper: float) -> tuple[str, str]:
    if ours is None:
        return "not comparable", "no value"
    ratio = ours / paper
    if ratio > 0 and 1 / LEVEL_FACTOR <= ratio <= LEVEL_FACTOR:
        return "reproduced", f"x {ratio:.2f} of the paper's"
    if ratio < 0:
        return "not reproduced", f"opposite sign (x {ratio:.2f})"
    return "not reproduced", f"x {ratio:.2f} of the paper's"


def _join(verdicts: list[str]) -> str:
    if all(v == "reproduced" for v in verdicts):
        return "reproduced"
    if all(v == "not reproduced" for v in verdicts):
        return "not reproduced"
    if any(v == "reproduced" for v in verdicts):
        return "partly reproduced"
    return "not reproduced" if "not reproduced" in verdicts else verdicts[0]


def _roller_series(folder: Path, name: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(t, x[:, rollers]) of a per-roller time-series column ("Tilt [rad]" -> "Roller j tilt [rad]")."""
    f = Path(folder) / "timeseries.npz"
    if not f.is_file():
        return None
    cols, _ = read_timeseries(f)
    base, _, unit = name.rpartition(" [")
    j, out = 0, []
    while f"Roller {j} {base[0].lower()}{base[1:]} [{unit}" in cols:
        out.append(cols[f"Roller {j} {base[0].lower()}{base[1:]} [{unit}"])
        j += 1
    return cols["Time [s]"], np.stack(out, axis=1)


def _oscillation(t, x, lo, hi) -> float:
    """Amplitude of the oscillation of the signals x[:, j] about their own straight-line trend over
    lo < t <= hi: sqrt(2) x the rms of the residuals (a sinusoid's amplitude), over every column."""
    w = (t > lo) & (t <= hi)
    tt = t[w] - t[w].mean()
    res = []
    for j in range(x.shape[1]):
        y = x[w, j]
        slope = float(tt @ (y - y.mean()) / (tt @ tt))
        res.append(y - y.mean() - slope * tt)
    return float(math.sqrt(2.0) * np.sqrt(np.mean(np.square(res))))


def _whirl(folder: Path, lo=0.1, hi=0.18) -> dict | None:
    """The cage centre's whirl over the window from the time series: radius mean, its coefficient of
    variation, and the turns the centre makes about the cone's centre."""
    f = Path(folder) / "timeseries.npz"
    if not f.is_file():
        return None
    cols, _ = read_timeseries(f)
    t = cols["Time [s]"]
    w = (t >= lo) & (t <= hi)
    y, z = cols["Cage centre from the cone's, y [m]"][w], cols["Cage centre from the cone's, z [m]"][w]
    r = np.hypot(y, z)
    angle = np.unwrap(np.arctan2(z, y))
    turns = abs(angle[-1] - angle[0]) / (2 * math.pi)
    return {"radius [m]": float(r.mean()), "cv": float(r.std() / r.mean()), "turns": float(turns)}


# --------------------------------------------------------------------------- the claims, figure by figure

def _fig5(st: Study | None) -> list[Claim]:
    if st is None or not st.where(speed="2400 rpm"):
        return [Claim("5", "Fig. 5's point (2.4 krpm, Fr 20 kN)", "-", "-", "not run", "studies/trb_speed.toml")]
    s = st.summaries[st.where(speed="2400 rpm")[0]]
    w = s[PAPER_WINDOW]
    out = []
    exc = s.get("Cone centre excursion, largest [m]")
    out.append(Claim("5a", "cone centre orbit: slight vibration", "about +-6 um (y) x 0-15 um (z)",
                     f"largest excursion from the start {1e6 * exc:.3g} um" if exc is not None else "-",
                     "not comparable", "the paper's orbit includes the static deflection from the unloaded "
                     "position; ours is measured from the quasi-static start (the cone sits on it)"))
    wh = _whirl(st.folders[st.where(speed="2400 rpm")[0]])
    if wh is None:
        out.append(Claim("5c", "cage centre: roughly circular whirl", "plotted on axes of +-0.6 mm", "-",
                         "not comparable", "the study kept no time series"))
    else:
        circular = wh["cv"] < 0.25 and wh["turns"] >= 1.0
        out.append(Claim("5c", "cage centre: roughly circular whirl", "plotted on axes of +-0.6 mm",
                         f"radius {1e3 * wh['radius [m]']:.3g} mm +- {100 * wh['cv']:.2g} %, {wh['turns']:.3g} turns "
                         "in 0.1-0.18 s", "reproduced" if circular else "not reproduced",
                         "rule: the radius varies by less than 25 % (coefficient of variation) and the centre goes "
                         "round at least once; the paper prints the plot's axes, not the radius"))
    ideal = s["Ideal cage speed [rpm]"]
    cs = w.get("Cage speed, mean [rpm]")
    out.append(Claim("5d", "cage speed near the ideal", "ideal 1.058 krpm; cage 1.02-1.10 krpm",
                     f"cage {cs:.4g} rpm, ideal (model geometry) {ideal:.4g} rpm" if cs else "-",
                     *level(ideal, 1058.0)))
    return out


def _speed(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("6-9", "speed series", "-", "-", "not run", "studies/trb_speed.toml")]
    order = [st.where(speed=f"{k} rpm")[0] for k in (2000, 3000, 4000, 5000) if st.where(speed=f"{k} rpm")]
    S = [st.summaries[i] for i in order]
    lo, hi = S[0], S[-1]
    out = []
    # Fig. 6: tilt
    tl = [window_value(s, "Tilt [rad]", "loaded zone") for s in S]
    tu = [window_value(s, "Tilt [rad]", "unloaded zone") for s in S]
    v, what = trend(tl[0], tl[-1], +1, magnitude=True)
    out.append(Claim("6", "mean tilt grows in magnitude with speed (2 -> 5 krpm)", "-0.14e-4 -> -0.40e-4 rad",
                     f"{tl[0].text()} -> {tl[-1].text()} rad", v, what))
    for i, (ours, paper) in enumerate(((tl[0].paper, -0.14e-4), (tl[-1].paper, -0.40e-4))):
        v, what = level(ours, paper)
        out.append(Claim("6", f"mean tilt at {('2', '5')[i]} krpm", f"{paper:.2g} rad", f"{ours:.3g} rad", v,
                         what + "; our quasi-static tilt from the rib's moment has the paper's sign (the run "
                         "adds the opposite tilt of the skewed rollers' axial traction couple)"))
    amp = [(window_value(s, "Tilt [rad]", "loaded zone", "amplitude").paper,
            window_value(s, "Tilt [rad]", "unloaded zone", "amplitude").paper) for s in S]
    ok = all(u is not None and l_ is not None and u > 1.1 * l_ for l_, u in amp)
    bad = all(u is not None and l_ is not None and l_ > 1.1 * u for l_, u in amp)
    out.append(Claim("6", "tilt larger in the unloaded zone", "visibly larger",
                     "amplitude loaded / unloaded: " + ", ".join(f"{a:.2g}/{b:.2g}" for a, b in amp) + " rad",
                     "reproduced" if ok else "not reproduced" if bad else "not resolved"))
    big = [window_value(s, "Tilt [rad]", "all", "largest magnitude").paper for s in S]
    spread = (max(big) - min(big)) / max(big)
    out.append(Claim("6", "largest tilt about the same at every speed", "about equal",
                     ", ".join(f"{b:.3g}" for b in big) + " rad",
                     "reproduced" if spread < 0.25 else "not reproduced", f"spread {100 * spread:.2g} % (rule: < 25 %)"))
    # Fig. 7: skew
    sk = [window_value(s, "Skew [rad]", "loaded zone") for s in S]
    v, what = trend(sk[0], sk[-1], +1)
    out.append(Claim("7", "mean skew grows with speed", "3.06e-3 -> 4.47e-3 rad (x 1.46)",
                     f"{sk[0].text()} -> {sk[-1].text()} rad (x {sk[-1].paper / sk[0].paper:.2f})", v, what))
    for i, (ours, paper) in enumerate(((sk[0].paper, 3.06e-3), (sk[-1].paper, 4.47e-3))):
        v, what = level(ours, paper)
        out.append(Claim("7", f"mean skew at {('2', '5')[i]} krpm", f"{paper:.3g} rad", f"{ours:.3g} rad", v,
                         what + "; literature 0.15-0.45 deg = 2.6e-3-7.9e-3 rad"))
    su = [window_value(s, "Skew [rad]", "unloaded zone").paper for s in S]
    sl = [x.paper for x in sk]
    ok = all(b is not None and a > 1.1 * b for a, b in zip(sl, su))
    out.append(Claim("7", "skew larger in the loaded zone", "larger",
                     "loaded / unloaded: " + ", ".join(f"{a:.3g}/{b:.3g}" for a, b in zip(sl, su)) + " rad",
                     "reproduced" if ok else "not reproduced",
                     "rule: larger by a tenth; our loaded and unloaded means are close: the skew does not relax "
                     "in the unloaded zone within a pass"))
    per = [s.get("Skew periodicity [-]") for s in S]
    claim_ok = per[0] is not None and per[0] < PERIODIC and all(p is not None and p >= PERIODIC for p in per[1:])
    out.append(Claim("7", "skew periodic from 3 krpm (not at 2)", "periodic at 3, 4, 5 krpm",
                     "periodicity " + ", ".join(f"{p:.3f}" for p in per), "reproduced" if claim_ok else "not reproduced",
                     f"rule: >= {PERIODIC} periodic"))
    # Fig. 8: roller slip
    rl = [window_value(s, "Roller slip [-]", "loaded zone") for s in S]
    ru = [window_value(s, "Roller slip [-]", "unloaded zone") for s in S]
    v, what = trend(ru[0], ru[-1], +1, magnitude=True)
    out.append(Claim("8", "roller slip rises with speed (unloaded zone, where it is largest)", "to about 10 % at 5 krpm",
                     f"{100 * ru[0].paper:.3g} % -> {100 * ru[-1].paper:.3g} %", v, what))
    ok = all(abs(u.paper) > 1.1 * abs(l_.paper) for l_, u in zip(rl, ru))
    out.append(Claim("8", "roller slip larger in the unloaded zone", "larger",
                     "loaded / unloaded: " + ", ".join(f"{100 * l_.paper:.2g}/{100 * u.paper:.2g} %" for l_, u in zip(rl, ru)),
                     "reproduced" if ok else "not reproduced"))
    v, what = level(abs(ru[-1].paper), 0.10)
    out.append(Claim("8", "roller slip at 5 krpm", "about 10 %", f"{100 * abs(ru[-1].paper):.2g} % (unloaded zone)", v,
                     what + "; the paper's slip is eq. 52 against its own ideal speeds; ours against the model "
                     "geometry's"))
    # Fig. 9: cage slip
    cg = [window_value(s, "Cage slip [-]", None) for s in S]
    v, what = trend(cg[0], cg[-1], +1, magnitude=True)
    out.append(Claim("9", "cage slip rises with speed", "rises; 2 krpm 0-0.03 %",
                     f"{100 * cg[0].paper:.3g} % -> {100 * cg[-1].paper:.3g} %", v, what))
    return out


def _preload(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("10-13", "preload series", "-", "-", "not run", "studies/trb_preload.toml")]
    order = [st.where(axial_displacement=f"{k} um")[0] for k in (10, 20, 30, 40)]
    S = [st.summaries[i] for i in order]
    out = []
    tl = [window_value(s, "Tilt [rad]", "loaded zone") for s in S]
    v, what = trend(tl[0], tl[-1], +1, magnitude=True)
    out.append(Claim("10", "mean tilt grows in magnitude with preload (10 -> 40 um)", "-0.27e-4 -> -0.96e-4 rad",
                     f"{tl[0].text()} -> {tl[-1].text()} rad", v, what))
    v, what = level(tl[-1].paper, -0.96e-4)
    out.append(Claim("10", "mean tilt at 40 um", "-0.96e-4 rad", f"{tl[-1].paper:.3g} rad", v, what))
    sk = [window_value(s, "Skew [rad]", "loaded zone") for s in S]
    v, what = trend(sk[0], sk[-1], +1)
    out.append(Claim("11", "mean skew grows with preload", "4.23e-3 -> 5.50e-3 rad",
                     f"{sk[0].text()} -> {sk[-1].text()} rad", v, what))
    v, what = level(sk[-1].paper, 5.50e-3)
    out.append(Claim("11", "mean skew at 40 um", "5.50e-3 rad", f"{sk[-1].paper:.3g} rad", v, what))
    # start amplitude that decays (except at 10 um): skew amplitude over 0-30 ms against the paper's window
    decays = []
    for i in order:
        ts = _roller_series(st.folders[i], "Skew [rad]")
        if ts is None:
            decays = None
            break
        t, x = ts
        early, late = _oscillation(t, x, 0.0, 0.03), _oscillation(t, x, 0.1, 0.18)
        decays.append(early / late if late > 0 else math.inf)
    if decays is None:
        out.append(Claim("11", "large start amplitude of skew that decays, except at 10 um", "-", "-", "not comparable",
                         "the study kept no time series"))
    else:
        out.append(Claim("11", "large start amplitude of skew that decays, except at 10 um", "decays at 20-40 um",
                         "early (0-30 ms) / late (0.1-0.18 s) amplitude: " + ", ".join(f"{d:.2g}" for d in decays),
                         "reproduced" if all(d > 2 for d in decays[1:]) and decays[0] < 2 else "not reproduced",
                         "oscillation amplitude about each roller's linear trend in the window (the skew's growth "
                         "from the start left out); rule: a ratio above 2 decays; our start is the quasi-static "
                         "equilibrium, not an impact"))
    rl = [window_value(s, "Roller slip [-]", "loaded zone") for s in S]
    v, what = trend(rl[0], rl[-1], -1, magnitude=True)
    out.append(Claim("12", "roller slip falls with preload", "0.0189 -> 0.0057 % (0.0073 % at 30 um)",
                     f"{100 * abs(rl[0].paper):.3g} -> {100 * abs(rl[-1].paper):.3g} % (magnitude)", v, what))
    v, what = level(abs(rl[0].paper), 0.0189e-2)
    out.append(Claim("12", "roller slip at 10 um", "0.0189 %", f"{100 * abs(rl[0].paper):.3g} % (magnitude)", v, what))
    cg = [window_value(s, "Cage slip [-]", None) for s in S]
    v, what = trend(cg[0], cg[-1], -1, magnitude=True)
    out.append(Claim("13", "cage slip falls with preload", "0.0189 -> 0.0055 %",
                     f"{100 * abs(cg[0].paper):.3g} -> {100 * abs(cg[-1].paper):.3g} % (magnitude)", v, what))
    a = [abs(c.paper) for c in cg]
    gain = (a[2] - a[3]) / (a[0] - a[3]) if a[0] != a[3] else math.nan
    out.append(Claim("13", "little gain from 30 to 40 um", "0.0076 -> 0.0055 % (16 % of the fall from 10 um)",
                     f"{100 * gain:.2g} % of the fall from 10 um", "reproduced" if gain < 0.25 else "not reproduced",
                     "rule: the 30 -> 40 um fall below a quarter of the 10 -> 40 um fall"))
    return out


def _axis_series(st: Study, key: str, values: list, stat: str, zone) -> list[Value]:
    return [window_value(st.summaries[st.where(**{key: v})[0]], stat, zone) for v in values]


def _grease_param(st: Study | None, fig: str, key: str, values: list, label: str, claims: dict,
                  levels: tuple = ()) -> list[Claim]:
    """Trend rows (each quantity's claimed direction, 0 for "little effect") and level rows (name, statistic,
    zone, the paper's number, a map applied to ours: abs for slips the paper prints as positive)."""
    if st is None:
        return [Claim(fig, f"{label} series", "-", "-", "not run", f"studies/{'trb_' + label.replace(' ', '_')}.toml")]
    out = []
    for name, (stat, zone, magnitude) in {"tilt": ("Tilt [rad]", "loaded zone", True),
                                          "skew": ("Skew [rad]", "loaded zone", False),
                                          "roller slip": ("Roller slip [-]", "loaded zone", True),
                                          "cage slip": ("Cage slip [-]", None, True)}.items():
        vals = _axis_series(st, key, values, stat, zone)
        claimed, paper = claims[name]
        if claimed == 0:
            v, what = little_effect(vals)
        else:
            v, what = trend(vals[0], vals[-1], claimed, magnitude=magnitude)
        direction = {1: "rises", -1: "falls", 0: "changes little"}[claimed]
        size = " (magnitude)" if magnitude and claimed else ""
        out.append(Claim(fig, f"{name}{size} {direction} with {label} ({values[0]} -> {values[-1]})", paper,
                         f"{vals[0].text()} -> {vals[-1].text()}", v, what))
    for name, stat, zone, paper, scale in levels:
        vals = [v.paper for v in _axis_series(st, key, values, stat, zone) if v.paper is not None]
        ours = float(np.mean(vals)) if vals else None
        v, what = level(None if ours is None else scale(ours), paper)
        out.append(Claim(fig, f"mean {name} over the {label} series", f"{paper:.3g}",
                         f"{scale(ours):.3g}" if vals else "-", v, what))
    return out


def _temperature(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("16", "grease x temperature series", "-", "-", "not run", "studies/trb_grease_temperature.toml")]
    claims = {"lithium": {"tilt": 1, "skew": -1, "roller slip": -1},
              "polyurea": {"tilt": -1, "skew": 1, "roller slip": 1},
              "calcium": {"tilt": -1, "skew": -1, "roller slip": -1}}
    out = []
    for grease, per in claims.items():
        for name, claimed in per.items():
            stat, zone, mag = {"tilt": ("Tilt [rad]", "loaded zone", True), "skew": ("Skew [rad]", "loaded zone", False),
                               "roller slip": ("Roller slip [-]", "loaded zone", True)}[name]
            lo = window_value(st.summaries[st.where(grease=grease, temperature_c=15)[0]], stat, zone)
            hi = window_value(st.summaries[st.where(grease=grease, temperature_c=70)[0]], stat, zone)
            v, what = trend(lo, hi, claimed, magnitude=mag)
            size = " (magnitude)" if mag else ""
            out.append(Claim("16", f"{grease}: {name}{size} {'rises' if claimed > 0 else 'falls'} from 15 to 70 C", "-",
                             f"{lo.text()} -> {hi.text()}", v, what))
    tilt = {g: np.mean([window_value(st.summaries[i], "Tilt [rad]", "loaded zone").paper
                        for i in st.where(grease=g)]) for g in claims}
    big = max(tilt, key=lambda g: abs(tilt[g]))
    out.append(Claim("16", "lithium has the largest tilt", "lithium",
                     ", ".join(f"{g} {t:.3g}" for g, t in tilt.items()) + " rad (mean over temperatures)",
                     "reproduced" if big == "lithium" else "not reproduced", f"largest magnitude: {big}"))
    return out


def claims(folder) -> list[Claim]:
    """Every claim of paper A (its figures and conclusions) checked against the studies under ``folder`` (each study in
    ``folder/<study name>``, as ``lubedyn study studies/<name>.toml --out folder/<name>`` writes)."""
    folder = Path(folder)
    st = {name: Study.load(folder / name) for name in MAIN_STUDIES}
    short = [name for name, x in st.items()
             if x is not None and not all(isinstance(s.get(PAPER_WINDOW), dict) for s in x.summaries)]
    for name in short:
        st[name] = None
    if short:
        return [Claim("-", f"studies {', '.join(short)}", "-", "-", "not comparable",
                      "their records do not reach the paper's window 0.1-0.18 s (smoke runs?)")] + claims_of(st)
    return claims_of(st)


def claims_of(st: dict) -> list[Claim]:
    """:func:`claims` for loaded studies (name -> :class:`Study` or None)."""
    out = _fig5(st["trb_speed"]) + _speed(st["trb_speed"]) + _preload(st["trb_preload"])
    phi = [2.44, 8.44, 18.44, 28.44, 38.44]
    out += _grease_param(st["trb_plastic_viscosity"], "14", "consistency", phi, "plastic viscosity",
                         {"tilt": (1, "about -4.7e-5 -> -5.2e-5 rad (increases: in magnitude)"),
                          "skew": (-1, "falls"), "roller slip": (-1, "falls"), "cage slip": (-1, "falls")})
    out += _grease_param(st["trb_yield_stress"], "15", "yield_stress", ["251.8 Pa", "501.8 Pa"], "yield stress",
                         {"tilt": (0, "-4.8e-5 to -5.5e-5 rad"), "skew": (0, "3.5e-3 to 4.5e-3 rad"),
                          "roller slip": (0, "0.009-0.015 %"), "cage slip": (0, "0.009-0.015 %")},
                         levels=(("tilt [rad]", "Tilt [rad]", "loaded zone", -5.15e-5, lambda x: x),
                                 ("skew [rad]", "Skew [rad]", "loaded zone", 4.0e-3, lambda x: x),
                                 ("roller slip [-] (magnitude)", "Roller slip [-]", "loaded zone", 1.2e-4, abs)))
    out += _temperature(st["trb_grease_temperature"])
    return out


def conclusions(rows: list[Claim]) -> list[Claim]:
    """Paper A's conclusions 1-4, each the combination of the rows that test it."""
    def pick(figs, words=()):
        return [r for r in rows if r.figure in figs and all(w in r.statement for w in words)]

    groups = (
        ("C1", "tilt larger in the unloaded zone, skew in the loaded zone; speed raises tilt, skew and slip",
         pick(("6",), ("unloaded",)) + pick(("7",), ("loaded zone",)) + pick(("6", "7", "8", "9"), ("with speed",))),
        ("C2", "preload reduces the bearing slip, raises tilt and skew",
         pick(("10", "11", "12", "13"), ("with preload",))),
        ("C3", "skew and slip fall and tilt rises with plastic viscosity; yield stress has little effect",
         pick(("14",), ("with plastic viscosity",)) + pick(("15",), ("with yield stress",))),
        ("C4", "the temperature's effect depends on the grease (lithium: tilt up, skew and slip down; polyurea "
               "the opposite; calcium all down)", pick(("16",), (":",))),
    )
    out = []
    for key, text, parts in groups:
        verdicts = [r.verdict for r in parts if r.verdict not in ("not run",)]
        if not verdicts:
            out.append(Claim(key, text, "-", "-", "not run"))
            continue
        count = {v: verdicts.count(v) for v in dict.fromkeys(verdicts)}
        out.append(Claim(key, text, "-", ", ".join(f"{n} {v}" for v, n in count.items()), _join(verdicts)))
    return out


def sensitivity(folder) -> list[dict]:
    """Per sensitivity study (Fig. 5's point unless the study says otherwise): the assumed key, its values,
    the loaded-zone mean skew and tilt at each, and the skew's relative range (largest / smallest)."""
    out = []
    for name in SENSITIVITY_STUDIES:
        st = Study.load(Path(folder) / name)
        if st is None:
            continue
        skew = [window_value(s, "Skew [rad]", "loaded zone").paper for s in st.summaries]
        tilt = [window_value(s, "Tilt [rad]", "loaded zone").paper for s in st.summaries]
        slip = [window_value(s, "Roller slip [-]", "loaded zone").paper for s in st.summaries]
        good = [x for x in skew if x]
        out.append({"study": name, "key": st.axes[0], "values": [lab[0] for lab in st.labels], "skew": skew,
                    "tilt": tilt, "slip": slip,
                    "skew range [-]": max(good) / min(good) if good and min(good) > 0 else None})
    return sorted(out, key=lambda r: -(r["skew range [-]"] or 0))


def _traction_evaluation(run: Path) -> str:
    """The run's model.traction_evaluation (its case.resolved.toml; "quadrature" before the key existed)."""
    import tomllib

    f = Path(run) / "case.resolved.toml"
    if not f.is_file():
        return "?"
    return str(tomllib.loads(f.read_text()).get("model", {}).get("traction_evaluation", "quadrature"))


def run_times(folder) -> list[dict]:
    """Per study found under ``folder``: runs, workers, wall time [s] and the traction evaluation its runs
    used (from ``study.json`` and the runs' summaries)."""
    out = []
    for name in MAIN_STUDIES + SENSITIVITY_STUDIES:
        path = Path(folder) / name / "study.json"
        if not path.is_file():
            continue
        r = json.loads(path.read_text())["runs"]
        st = Study.load(Path(folder) / name)
        how = sorted({_traction_evaluation(f) for f in st.folders})
        out.append({"study": name, "runs": r["total"], "workers": r["workers"], "wall time [s]": r["wall time [s]"],
                    "traction evaluation": ", ".join(how)})
    return out


def markdown(folder) -> str:
    """The checklist (claims, conclusions, sensitivity, run times) as markdown."""
    rows = claims(folder)
    lines = ["| fig | paper A's claim | paper | lubedyn | verdict | how measured |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r.figure} | {r.statement} | {r.paper} | {r.ours} | **{r.verdict}** | {r.note} |")
    lines += ["", "| conclusion | paper A | its rows | verdict |", "|---|---|---|---|"]
    for c in conclusions(rows):
        lines.append(f"| {c.figure} | {c.statement} | {c.ours} | **{c.verdict}** |")
    sens = sensitivity(folder)
    if sens:
        lines += ["", "| assumption (study) | values | loaded-zone skew [rad] | loaded-zone tilt [rad] | roller slip | "
                  "skew largest/smallest |", "|---|---|---|---|---|---|"]
        for r in sens:
            fmt = lambda xs, f: ", ".join("-" if x is None else format(x, f) for x in xs)  # noqa: E731
            rng = "-" if r["skew range [-]"] is None else f"{r['skew range [-]']:.2f}"
            lines.append(f"| `{r['key']}` ({r['study']}) | {', '.join(map(str, r['values']))} | {fmt(r['skew'], '.3g')} | "
                         f"{fmt(r['tilt'], '.2g')} | {fmt(r['slip'], '.2g')} | {rng} |")
    times = run_times(folder)
    if times:
        lines += ["", "| study | runs | workers | wall time | raceway traction evaluated by |", "|---|---|---|---|---|"]
        for t in times:
            lines.append(f"| `{t['study']}` | {t['runs']} | {t['workers']} | {t['wall time [s]'] / 60:.1f} min | "
                         f"{t['traction evaluation']} |")
    counts = {}
    for r in rows:
        counts[r.verdict] = counts.get(r.verdict, 0) + 1
    lines += ["", "Verdicts: " + ", ".join(f"{n} {v}" for v, n in counts.items()) + "."]
    return "\n".join(lines)
