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

Signs
-----
Every comparison is of signed quantities, never of magnitudes.  Paper A's tilts are negative (Figs. 6
and 10 print negative means; the tilt axes of Figs. 14 and 16 are negative) and its words for them
describe the magnitude: "the average tilt angle rises from -0.14e-4 rad to -0.40e-4 rad" (Fig. 6).  So
"tilt increases" is read as a signed *fall* and "tilt decreases" as a signed *rise*, the same reading for
Figs. 6, 10, 14 and 16.  Its slips (eq. 52) and skews are positive.  Our tilts and slips can have the
other sign; a trend or level of the opposite sign is then not reproduced, whatever its size.

Verdict rules (stated once, applied by code)
--------------------------------------------
- **Trend** ("X rises from P1 to P2"): the signed change of X from the first to the last value of P, in
  the paper's window (dp) and in the converged window (dc), against u, the two end points' uncertainties
  added.  *Not resolved* when |dc| <= u (inside the window-to-window change) or dp and dc have opposite
  signs (the windows disagree); *not reproduced* when the change has the opposite sign to the paper's;
  otherwise its size decides.  Where the paper prints both ends (p1, p2), the size is the ratio of the
  relative changes, each over its own first value and signed: (dp/X(P1)) / ((p2 - p1)/p1) (the ratio
  of the absolute changes where the paper's quantity changes sign).  *Reproduced* when the ratio lies
  within :data:`SIZE_FACTOR` (2) either way; *direction only* (with the ratio) outside it -- including a
  negative ratio: our X has the other sign than the paper's, so a change of the paper's sign makes our
  |X| move the other way.  Where the paper prints no number, the change must exceed :data:`LITTLE` (5 %)
  of the two ends' mean magnitude -- below that this checklist itself calls a change "little effect" --
  and our X must have the paper's sign (:data:`PAPER_SIGN`), else *direction only*.  Why a factor 2: the
  assumed values the paper does not give move our skew by up to x 1.8 at Fig. 5's point (the limiting
  shear stress's slope 0.04-0.1, the sensitivity table), so a size within x 2 is as close as the model's
  unknowns let one expect; a factor 1.3 (the levels') would call sizes different that those unknowns
  alone can move that far.
- **Little effect**: the change across the range is below :data:`LITTLE` (5 %) of the mean magnitude.
- **Level** (a number the paper prints): *reproduced* within a factor :data:`LEVEL_FACTOR` (1.3, either
  way) and with the paper's sign; otherwise *not reproduced*, with the ratio.  The paper's numbers are
  reported comparisons, never tolerances the model was tuned to.
- **Periodic**: the roller-pass periodicity measure (:func:`lubedyn.dynamics.analysis.windows.periodicity`) at least
  :data:`PERIODIC` (0.95).
- **Zone comparison** ("larger in the unloaded zone"): the zones' values; *reproduced* when the claimed
  order holds by more than a tenth of the larger and, for signed quantities (slip), with the paper's sign.
- **Ranges on a plot** (Fig. 5a, 5b, 5d: the paper prints a plot's axes, not the curve's numbers): Fig. 5d's
  cage speed is reproduced when its range over the paper's window lies inside the plotted band; Fig. 5b's
  displacements when each range lies inside the paper's axis and spans at least 1/:data:`SIZE_FACTOR` of
  it (an axis frames its curve); Fig. 5a's orbit compares its largest distances from the unloaded
  position with the paper's as levels.
- **Steadiness**: a point is steady when its converged window is converged ("Converged window,
  converged [-]": every headline mean moved by at most ``analysis.converged_tolerance``, 2 %, from the
  window before; :func:`lubedyn.scenes.tapered.converged_summary`).  A comparison that uses a point that
  is not steady (or has no converged window) says so in its note, point by point, and a verdict that
  would be *reproduced* becomes *reproduced, not steady* (:data:`UNSTEADY`), counted apart as "not
  steady"; the other verdicts keep their name.
- *Not comparable*: the paper's quantity is not defined the same way here or the run lacks what it needs
  (the reason is given), or the study has not been run (``not run``).

Which assumption moves a claim that is not reproduced: :func:`sensitivity` ranks the sensitivity studies
(``studies/trb_sensitivity_*.toml``, Fig. 5's point) by how far each assumed value moves the mean skew and
tilt.  :func:`elasticities` gives, per main study, how strongly each headline output answers its
parameter (d ln|y| / d ln x) beside the paper's and the route by which the parameter enters the model.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from lubedyn.outputs import read_timeseries, timeseries_path

#: "little effect": a change below this fraction of the mean magnitude
LITTLE = 0.05
#: "periodic": the roller-pass periodicity measure at least this
PERIODIC = 0.95
#: a printed level is reproduced within this factor (either way) and with the paper's sign
LEVEL_FACTOR = 1.3
#: a trend's size (our relative change over the paper's) is reproduced within this factor, either way
SIZE_FACTOR = 2.0

#: the sign of paper A's quantities: its tilts negative, its skews and slips positive (module docstring)
PAPER_SIGN = {"tilt": -1, "skew": 1, "roller slip": 1, "cage slip": 1}

PAPER_WINDOW = "Paper window (analysis.window)"
CONVERGED = "Converged window"
STEADY = "Converged window, converged [-]"

#: the verdict that "reproduced" becomes when a point of the comparison is not steady
UNSTEADY = "reproduced, not steady"
#: the summary's categories, in order (UNSTEADY counts as "not steady")
CATEGORIES = ("reproduced", "direction only", "not reproduced", "not resolved", "not steady", "not comparable",
              "not run")

MAIN_STUDIES = ("trb_speed", "trb_preload", "trb_plastic_viscosity", "trb_yield_stress", "trb_grease_temperature")
SENSITIVITY_STUDIES = ("trb_sensitivity_shear_modulus", "trb_sensitivity_limiting_slope", "trb_sensitivity_rib_roughness",
                       "trb_sensitivity_rib_film", "trb_sensitivity_damping", "trb_sensitivity_flange_mixing",
                       "trb_plastic_viscosity_paper_reading", "trb_plastic_viscosity_apparent_reading")


def category(verdict: str) -> str:
    """The summary's category of a verdict (:data:`UNSTEADY` is "not steady")."""
    return "not steady" if verdict == UNSTEADY else verdict


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

    def label(self, i: int) -> str:
        return ", ".join(str(x) for x in self.labels[i])

    def unsteady(self, indices) -> list[str]:
        """The points among ``indices`` that are not steady (module docstring), each as "label (why)"."""
        out = []
        for i in dict.fromkeys(indices):
            s = self.summaries[i]
            flag = s.get(STEADY)
            if flag is True:
                continue
            c = s.get(CONVERGED)
            if flag is None:
                out.append(f"{self.label(i)} (no converged window)")
            elif isinstance(c, dict) and c.get("Largest relative change [-]") is not None:
                out.append(f"{self.label(i)} (a headline mean moved {100 * c['Largest relative change [-]']:.2g} % "
                           f"> {100 * c.get('Tolerance [-]', 0.02):.2g} % between the last two windows)")
            else:
                out.append(f"{self.label(i)} (not converged)")
        return out


def steady(claim: Claim, unsteady: list[str]) -> Claim:
    """``claim`` with the steadiness rule applied: its note names the points that are not steady and a
    "reproduced" becomes :data:`UNSTEADY`."""
    if unsteady:
        claim.note = (claim.note + "; " if claim.note else "") + "not steady: " + ", ".join(unsteady)
        if claim.verdict == "reproduced":
            claim.verdict = UNSTEADY
    return claim


def window_value(s: dict, stat: str, zone: str | None, what: str = "mean") -> Value:
    """The statistic ``stat`` ("Skew [rad]" ...) of a run summary, zone "loaded zone", "unloaded zone", "all"
    or None (a whole-bearing statistic such as "Cage slip [-]"), over the paper's window and the
    converged window, with the window-to-window change of the headline means as the uncertainty."""
    def pick(w):
        if not isinstance(w, dict) or stat not in w:
            return None
        x = w[stat]
        x = x.get(zone) if zone and isinstance(x, dict) else x
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


def size_ratio(first: float, last: float, paper: tuple[float, float]) -> tuple[float, str]:
    """(ratio, basis) of our change first -> last to the paper's p1 -> p2: the relative changes
    ((last - first)/first) / ((p2 - p1)/p1) -- each change over its own first value, signed, so the ratio
    is negative when our quantity and the paper's have opposite signs -- or the absolute changes
    (last - first)/(p2 - p1) where the paper's quantity changes sign (or ours starts at 0)."""
    p1, p2 = paper
    if p1 * p2 <= 0.0 or first == 0.0:
        return (last - first) / (p2 - p1), "absolute change"
    return ((last - first) / first) / ((p2 - p1) / p1), "relative change"


def trend(first: Value, last: Value, claimed: int | None = None, paper: tuple[float, float] | None = None,
          paper_sign: int | None = None) -> tuple[str, str]:
    """(verdict, what we measured) for the claim "X rises (claimed = +1) / falls (-1) from first to last",
    signed, under the module's trend rule.  ``paper`` = (p1, p2), the paper's printed ends, sets the sign
    (when ``claimed`` is None), the size the change is compared with and the sign of the paper's X;
    without ends, ``paper_sign`` (+1, -1 or None: not known) is the sign of the paper's X: where ours has
    the other sign, a change of the claimed sign goes the other way in magnitude (*direction only*)."""
    if paper is not None:
        sign = int(np.sign(paper[1] - paper[0]))
        if claimed is not None and claimed != sign:
            raise ValueError(f"claimed = {claimed!r} contradicts the paper's ends {paper!r}: allowed {sign}")
        claimed = sign
        if paper[0] * paper[1] > 0:
            paper_sign = int(np.sign(paper[0]))
    if claimed not in (1, -1):
        raise ValueError(f"claimed = {claimed!r}: allowed +1 (rises) or -1 (falls)")
    if first.paper is None or last.paper is None:
        return "not comparable", "no value (an empty zone)"
    dp = last.paper - first.paper
    have_conv = first.converged is not None and last.converged is not None
    dc = last.converged - first.converged if have_conv else dp
    u = abs(first.uncertainty or 0.0) + abs(last.uncertainty or 0.0)
    rel = f" (last/first x {last.paper / first.paper:.4g}, paper's window)" if first.paper else " (paper's window)"
    what = f"{_sign_word(dp)} by {dp:+.3g}{rel}"
    if have_conv:
        what += f", {dc:+.3g} converged (uncertainty {u:.2g})"
    if abs(dc) <= u:
        return "not resolved", what + ": inside the window-to-window change"
    if np.sign(dp) != np.sign(dc):
        return "not resolved", what + ": the two windows disagree"
    other = paper_sign is not None and first.paper * paper_sign < 0 and last.paper * paper_sign < 0
    if np.sign(dc) != claimed:
        return "not reproduced", what + ": the opposite sign to the paper's" + (
            " (our quantity has the other sign, so its magnitude moves the paper's way)" if other else "")
    if paper is not None:
        ratio, basis = size_ratio(first.paper, last.paper, paper)
        p1, p2 = paper
        theirs = f"x {p2 / p1:.3g}" if p1 * p2 > 0 else f"{p2 - p1:+.3g}"
        what += f"; size x {ratio:.2g} of the paper's {basis} ({theirs})"
        if 1.0 / SIZE_FACTOR <= ratio <= SIZE_FACTOR:
            return "reproduced", what
        if ratio < 0:
            return "direction only", what + ": our quantity has the other sign, so in magnitude it changes the other way"
        return "direction only", what + f": outside a factor {SIZE_FACTOR:g}"
    scale = 0.5 * (abs(first.paper) + abs(last.paper))
    size = abs(dp) / scale if scale > 0 else math.inf
    what += f"; {100 * size:.2g} % of the mean magnitude (the paper prints no size)"
    if other:
        return "direction only", what + ": our quantity has the other sign, so in magnitude it changes the other way"
    if size >= LITTLE:
        return "reproduced", what
    return "direction only", what + f": below the {100 * LITTLE:g} % of a 'little effect'"


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
    if any(v == "reproduced" for v in verdicts):
        return "partly reproduced"
    if "not reproduced" in verdicts:
        return "not reproduced"
    if "direction only" in verdicts:
        return "direction only"
    return verdicts[0]


def _timeseries(folder: Path | None) -> dict | None:
    try:
        f = None if folder is None else timeseries_path(folder)
    except FileNotFoundError:
        f = None
    if f is None:
        return None
    cols, _ = read_timeseries(f)
    return cols


def _roller_series(folder: Path, name: str) -> tuple[np.ndarray, np.ndarray] | None:
    """(t, x[:, rollers]) of a per-roller time-series column ("Tilt [rad]" -> "Roller j tilt [rad]")."""
    cols = _timeseries(folder)
    if cols is None:
        return None
    return cols["Time [s]"], _per_roller(cols, name)


def _per_roller(cols: dict, name: str) -> np.ndarray | None:
    base, _, unit = name.rpartition(" [")
    j, out = 0, []
    while f"Roller {j} {base[0].lower()}{base[1:]} [{unit}" in cols:
        out.append(cols[f"Roller {j} {base[0].lower()}{base[1:]} [{unit}"])
        j += 1
    return np.stack(out, axis=1) if out else None


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


def _window_columns(folder: Path, needs: tuple[str, ...], absent: str, lo: float,
                    hi: float) -> tuple[dict, np.ndarray] | str:
    """(the time series' columns, the mask of lo <= t <= hi) of a run, or the sentence that says why the
    run cannot give a window quantity: no time series kept, a column of ``needs`` missing (``absent``
    says what that means), or a record that does not reach the window."""
    cols = _timeseries(folder)
    if cols is None:
        return "the study kept no time series"
    if any(name not in cols for name in needs):
        return absent
    t = cols["Time [s]"]
    w = (t >= lo) & (t <= hi)
    if w.sum() < 2:
        return f"the record ({t[0]:g}-{t[-1]:g} s) does not reach the window {lo:g}-{hi:g} s"
    return cols, w


def _whirl(folder: Path, lo=0.1, hi=0.18) -> dict | str:
    """The cage centre's whirl over the window from the time series: radius mean, its coefficient of
    variation, and the turns the centre makes about the cone's centre (a sentence when the run cannot
    give it)."""
    got = _window_columns(folder, ("Cage centre from the cone's, y [m]", "Cage centre from the cone's, z [m]"),
                          "the run has no cage", lo, hi)
    if isinstance(got, str):
        return got
    cols, w = got
    y, z = cols["Cage centre from the cone's, y [m]"][w], cols["Cage centre from the cone's, z [m]"][w]
    r = np.hypot(y, z)
    angle = np.unwrap(np.arctan2(z, y))
    turns = abs(angle[-1] - angle[0]) / (2 * math.pi)
    return {"radius [m]": float(r.mean()), "cv": float(r.std() / r.mean()), "turns": float(turns)}


def cone_orbit(folder: Path, hi: float = 0.18) -> dict | str:
    """The cone centre over 0 <= t <= ``hi`` (paper A's run) measured from its unloaded, concentric
    position (the cone's state is that displacement: the run starts at the static deflection under the
    loads, :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.start_state`): along the radial load
    (+y here, the paper's z) its smallest and largest, across it (z here, the paper's y) its largest
    magnitude, and the start.  A sentence instead when the run cannot give it."""
    cols = _timeseries(folder)
    if cols is None:
        return "the study kept no time series"
    if "Cone y [m]" not in cols or "Cone z [m]" not in cols:
        return "the time series has no cone centre (Cone y/z [m])"
    t = cols["Time [s]"]
    w = t <= hi
    y, z = cols["Cone y [m]"][w], cols["Cone z [m]"][w]
    return {"along, smallest [m]": float(y.min()), "along, largest [m]": float(y.max()),
            "across, largest [m]": float(np.max(np.abs(z))), "start along [m]": float(y[0]),
            "window [s]": [float(t[w][0]), float(t[w][-1])]}


def ideal_displacements(folder: Path, cols: dict) -> tuple[np.ndarray, np.ndarray] | None:
    """(radial, axial) [m] (samples x rollers) of the rollers from their ideal, unloaded position: the
    time series' columns when the run wrote them, else from the rollers' state columns and the
    geometry of the run's ``case.resolved.toml`` (:func:`lubedyn.scenes.tapered.displacement_from_ideal`)."""
    radial = _per_roller(cols, "Radial displacement from the ideal position [m]")
    axial = _per_roller(cols, "Axial displacement from the ideal position [m]")
    if radial is not None and axial is not None:
        return radial, axial
    case_file = Path(folder) / "case.resolved.toml"
    if "Roller 0 x [m]" not in cols or not case_file.is_file():
        return None
    from lubedyn.config import load_case  # deferred: the scene's imports (numba)
    from lubedyn.scenes.static import build as build_geometry
    from lubedyn.scenes.tapered import displacement_from_ideal

    geometry = build_geometry(load_case(case_file))
    j, c = 0, []
    while f"Roller {j} x [m]" in cols:
        c.append(np.stack([cols[f"Roller {j} {k} [m]"] for k in "xyz"], axis=-1))
        j += 1
    return displacement_from_ideal(geometry, np.stack(c, axis=1))


def roller_displacements(folder: Path, lag: float | None, lo: float = 0.1, hi: float = 0.18) -> dict | str:
    """Roller 0's radial and axial displacement from its ideal, unloaded position over lo <= t <= hi:
    the range [m] of each, and each one's roller-pass periodicity over all rollers
    (:func:`lubedyn.dynamics.analysis.windows.periodicity` at ``lag`` [s]).  A sentence when the run cannot
    give them."""
    from lubedyn.dynamics.analysis.windows import periodicity

    got = _window_columns(folder, (), "", lo, hi)
    if isinstance(got, str):
        return got
    cols, w = got
    d = ideal_displacements(folder, cols)
    if d is None:
        return "the time series has neither the displacement from the ideal position nor the rollers' states"
    t = cols["Time [s]"]
    out = {}
    for name, x in zip(("radial", "axial"), d):
        out[f"{name} range [m]"] = (float(x[w, 0].min()), float(x[w, 0].max()))
        out[f"{name} periodicity [-]"] = None if lag is None else periodicity(t[w], x[w], lag)
    return out


def cage_speed(folder: Path, lo: float = 0.1, hi: float = 0.18) -> dict | str:
    """The cage's speed about the axis ("Cage speed [rad/s]" of the time series) over lo <= t <= hi:
    mean, smallest and largest [rpm]."""
    got = _window_columns(folder, ("Cage speed [rad/s]",), "the run has no cage", lo, hi)
    if isinstance(got, str):
        return got
    cols, w = got
    x = cols["Cage speed [rad/s]"][w] * 30.0 / math.pi
    return {"mean [rpm]": float(x.mean()), "smallest [rpm]": float(x.min()), "largest [rpm]": float(x.max())}


# --------------------------------------------------------------------------- the claims, figure by figure

#: Fig. 5's plotted ranges: the cone centre (across the load, along it) [m], roller 0's radial and axial
#: displacement axes [m], the cage speed band and the paper's ideal cage speed [rpm]
FIG5_CONE = (6e-6, 15e-6)
FIG5_RADIAL = (-20e-6, 10e-6)
FIG5_AXIAL = (-20e-6, 70e-6)
FIG5_CAGE = (1020.0, 1100.0)
FIG5_IDEAL = 1058.0


def _inside(rng, axis) -> tuple[bool, float]:
    """(the range lies inside the axis, the range's share of the axis span)."""
    return axis[0] <= rng[0] and rng[1] <= axis[1], (rng[1] - rng[0]) / (axis[1] - axis[0])


def _fig5(st: Study | None) -> list[Claim]:
    if st is None or not st.where(speed="2400 rpm"):
        return [Claim("5", "Fig. 5's point (2.4 krpm, Fr 20 kN)", "-", "-", "not run", "studies/trb_speed.toml")]
    i = st.where(speed="2400 rpm")[0]
    s, folder = st.summaries[i], st.folders[i] if st.folders else None
    unsteady = st.unsteady([i])
    out = []
    # (a) the cone centre from its unloaded position
    orbit = cone_orbit(folder) if folder is not None else "the study kept no time series"
    paper_a = "about +-6 um across the load (its y) x 0-15 um along it (its z), from the unloaded position"
    if isinstance(orbit, str):
        out.append(Claim("5a", "cone centre orbit: slight vibration", paper_a, "-", "not comparable", orbit))
    else:
        along, across = orbit["along, largest [m]"], orbit["across, largest [m]"]
        va, wa = level(along, FIG5_CONE[1])
        vc, wc = level(across, FIG5_CONE[0])
        out.append(Claim(
            "5a", "cone centre orbit: slight vibration", paper_a,
            f"along the load {1e6 * orbit['along, smallest [m]']:.3g} to {1e6 * along:.3g} um (static deflection "
            f"{1e6 * orbit['start along [m]']:.3g} um at the start), across it at most {1e6 * across:.2g} um",
            "reproduced" if va == vc == "reproduced" else "not reproduced",
            f"largest along the load {wa}, largest across it {wc}; over 0-0.18 s (the paper's run) from the "
            "unloaded, concentric position (the cone's radial displacements are free, its axial one locked); our "
            "run starts at the static deflection, the paper's from the unloaded bearing, so the paper's 0 along "
            "the load has no counterpart"))
    # (b) roller 0's displacements from its ideal position
    lag = s.get(PAPER_WINDOW, {}).get("Roller pass period [s]") if isinstance(s.get(PAPER_WINDOW), dict) else None
    disp = roller_displacements(folder, lag) if folder is not None else "the study kept no time series"
    paper_b = "radial -20..10 um, axial -20..70 um (axes); periodic with the load zone"
    if isinstance(disp, str):
        out.append(Claim("5b", "roller displacement periodic with the load zone", paper_b, "-", "not comparable", disp))
    else:
        parts, ok = [], True
        for name, axis in (("radial", FIG5_RADIAL), ("axial", FIG5_AXIAL)):
            rng, per = disp[f"{name} range [m]"], disp[f"{name} periodicity [-]"]
            inside, share = _inside(rng, axis)
            ok &= inside and share >= 1.0 / SIZE_FACTOR and per is not None and per >= PERIODIC
            parts.append(f"{name} {1e6 * rng[0]:.3g} to {1e6 * rng[1]:.3g} um ({100 * share:.2g} % of the paper's "
                         f"axis{'' if inside else ', outside it'}), periodicity "
                         + ("-" if per is None else f"{per:.3f}"))
        out.append(Claim("5b", "roller displacement periodic with the load zone", paper_b, "; ".join(parts),
                         "reproduced" if ok else "not reproduced",
                         "roller 0 from its ideal, unloaded position over 0.1-0.18 s; rule: each range inside the "
                         f"paper's axis and spanning at least 1/{SIZE_FACTOR:g} of it, periodicity >= {PERIODIC}"))
    # (c) the cage's whirl
    wh = _whirl(folder) if folder is not None else "the study kept no time series"
    if isinstance(wh, str):
        out.append(Claim("5c", "cage centre: roughly circular whirl", "plotted on axes of +-0.6 mm", "-",
                         "not comparable", wh))
    else:
        circular = wh["cv"] < 0.25 and wh["turns"] >= 1.0
        out.append(Claim("5c", "cage centre: roughly circular whirl", "plotted on axes of +-0.6 mm",
                         f"radius {1e3 * wh['radius [m]']:.3g} mm +- {100 * wh['cv']:.2g} %, {wh['turns']:.3g} turns "
                         "in 0.1-0.18 s", "reproduced" if circular else "not reproduced",
                         "rule: the radius varies by less than 25 % (coefficient of variation) and the centre goes "
                         "round at least once; the paper prints the plot's axes, not the radius"))
    # (d) the simulated cage speed against the paper's band
    cs = cage_speed(folder) if folder is not None else "the study kept no time series"
    paper_d = f"cage within {FIG5_CAGE[0] / 1e3:.2f}-{FIG5_CAGE[1] / 1e3:.2f} krpm (axes); ideal {FIG5_IDEAL / 1e3:.3f} krpm"
    if isinstance(cs, str):
        out.append(Claim("5d", "cage speed near the ideal", paper_d, "-", "not comparable", cs))
    else:
        inside, _ = _inside((cs["smallest [rpm]"], cs["largest [rpm]"]), FIG5_CAGE)
        out.append(Claim("5d", "cage speed near the ideal", paper_d,
                         f"cage {cs['mean [rpm]']:.4g} rpm (x {cs['mean [rpm]'] / FIG5_IDEAL:.3f} of the paper's ideal), "
                         f"{cs['smallest [rpm]']:.4g}-{cs['largest [rpm]']:.4g} rpm over 0.1-0.18 s; ideal (model "
                         f"geometry) {s.get('Ideal cage speed [rpm]', float('nan')):.4g} rpm",
                         "reproduced" if inside else "not reproduced",
                         "the simulated cage speed (the time series); rule: its range over the paper's window inside "
                         "the paper's band"))
    return [steady(c, unsteady) for c in out]


def _missing(st: Study, key: str, values) -> list[str]:
    """The axis values of ``values`` the study has no (finished) point for."""
    return [str(v) for v in values if not st.where(**{key: v})]


def _speed(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("6-9", "speed series", "-", "-", "not run", "studies/trb_speed.toml")]
    speeds = [f"{k} rpm" for k in (2000, 3000, 4000, 5000)]
    if _missing(st, "speed", speeds):
        return [Claim("6-9", "speed series", "-", "-", "not run", f"no finished run at {', '.join(_missing(st, 'speed', speeds))}")]
    order = [st.where(speed=k)[0] for k in speeds]
    S = [st.summaries[i] for i in order]
    ends, every = st.unsteady([order[0], order[-1]]), st.unsteady(order)
    out = []

    def add(claim, unsteady):
        out.append(steady(claim, unsteady))

    # Fig. 6: tilt
    tl = [window_value(s, "Tilt [rad]", "loaded zone") for s in S]
    v, what = trend(tl[0], tl[-1], paper=(-0.14e-4, -0.40e-4))
    add(Claim("6", "mean tilt falls (signed) with speed, 2 -> 5 krpm (grows in magnitude: the paper's is negative)",
              "-0.14e-4 -> -0.40e-4 rad", f"{tl[0].text()} -> {tl[-1].text()} rad", v, what), ends)
    for k, (i, paper) in enumerate(((order[0], -0.14e-4), (order[-1], -0.40e-4))):
        ours = tl[0 if k == 0 else -1].paper
        v, what = level(ours, paper)
        add(Claim("6", f"mean tilt at {('2', '5')[k]} krpm", f"{paper:.2g} rad",
                  "-" if ours is None else f"{ours:.3g} rad", v,
                  what + "; our quasi-static tilt from the rib's moment has the paper's sign (the run "
                  "adds the opposite tilt of the skewed rollers' axial traction couple)"), st.unsteady([i]))
    amp = [(window_value(s, "Tilt [rad]", "loaded zone", "amplitude").paper,
            window_value(s, "Tilt [rad]", "unloaded zone", "amplitude").paper) for s in S]
    known = all(u is not None and l_ is not None for l_, u in amp)
    ok = known and all(u > 1.1 * l_ for l_, u in amp)
    bad = known and all(l_ > 1.1 * u for l_, u in amp)
    add(Claim("6", "tilt larger in the unloaded zone", "visibly larger",
              "amplitude loaded / unloaded: " + ", ".join(f"{a:.2g}/{b:.2g}" if known else "-" for a, b in amp)
              + " rad", "not comparable" if not known else
              "reproduced" if ok else "not reproduced" if bad else "not resolved",
              "rule: larger by a tenth at every speed"), every)
    big = [window_value(s, "Tilt [rad]", "all", "largest magnitude").paper for s in S]
    if all(b is not None for b in big):
        spread = (max(big) - min(big)) / max(big)
        add(Claim("6", "largest tilt about the same at every speed", "about equal", ", ".join(f"{b:.3g}" for b in big)
                  + " rad", "reproduced" if spread < 0.25 else "not reproduced", f"spread {100 * spread:.2g} % (rule: < 25 %)"),
            every)
    # Fig. 7: skew
    sk = [window_value(s, "Skew [rad]", "loaded zone") for s in S]
    v, what = trend(sk[0], sk[-1], paper=(3.06e-3, 4.47e-3))
    x = f" (x {sk[-1].paper / sk[0].paper:.2f})" if sk[0].paper and sk[-1].paper is not None else ""
    add(Claim("7", "mean skew grows with speed", "3.06e-3 -> 4.47e-3 rad (x 1.46)",
              f"{sk[0].text()} -> {sk[-1].text()} rad{x}", v, what), ends)
    for k, (i, paper) in enumerate(((order[0], 3.06e-3), (order[-1], 4.47e-3))):
        ours = sk[0 if k == 0 else -1].paper
        v, what = level(ours, paper)
        add(Claim("7", f"mean skew at {('2', '5')[k]} krpm", f"{paper:.3g} rad", "-" if ours is None else f"{ours:.3g} rad",
                  v, what + "; literature 0.15-0.45 deg = 2.6e-3-7.9e-3 rad"), st.unsteady([i]))
    su = [window_value(s, "Skew [rad]", "unloaded zone").paper for s in S]
    sl = [x.paper for x in sk]
    known = all(a is not None and b is not None for a, b in zip(sl, su))
    ok = known and all(a > 1.1 * b and a > 0 for a, b in zip(sl, su))
    add(Claim("7", "skew larger in the loaded zone", "larger",
              "loaded / unloaded: " + ", ".join(f"{a:.3g}/{b:.3g}" if known else "-" for a, b in zip(sl, su)) + " rad",
              "not comparable" if not known else "reproduced" if ok else "not reproduced",
              "rule: larger by a tenth (and positive, the paper's sign); our loaded and unloaded means are close: the "
              "skew does not relax in the unloaded zone within a pass"), every)
    per = [s.get("Skew periodicity [-]") for s in S]
    claim_ok = per[0] is not None and per[0] < PERIODIC and all(p is not None and p >= PERIODIC for p in per[1:])
    add(Claim("7", "skew periodic from 3 krpm (not at 2)", "periodic at 3, 4, 5 krpm",
              "periodicity " + ", ".join("-" if p is None else f"{p:.3f}" for p in per),
              "reproduced" if claim_ok else "not reproduced", f"rule: >= {PERIODIC} periodic"), every)
    # Fig. 8: roller slip
    rl = [window_value(s, "Roller slip [-]", "loaded zone") for s in S]
    ru = [window_value(s, "Roller slip [-]", "unloaded zone") for s in S]
    v, what = trend(ru[0], ru[-1], +1, paper_sign=PAPER_SIGN["roller slip"])
    pct = lambda x: "-" if x is None else f"{100 * x:.3g} %"  # noqa: E731
    add(Claim("8", "roller slip rises with speed (unloaded zone, where it is largest)",
              "to about 10 % at 5 krpm (2 krpm: -0.01 to 0.07 %)", f"{pct(ru[0].paper)} -> {pct(ru[-1].paper)}", v,
              what + "; the paper's slip (eq. 52) is > 0, the roller slower than the ideal"), ends)
    known = all(a.paper is not None and b.paper is not None for a, b in zip(rl, ru))
    order_ok = known and all(abs(u.paper) > 1.1 * abs(l_.paper) for l_, u in zip(rl, ru))
    sign_ok = known and all(u.paper > 0 for u in ru)
    add(Claim("8", "roller slip larger in the unloaded zone", "larger (slip > 0)",
              "loaded / unloaded: " + ", ".join(f"{100 * l_.paper:.2g}/{100 * u.paper:.2g} %" if known else "-"
                                                for l_, u in zip(rl, ru)),
              "not comparable" if not known else "reproduced" if order_ok and sign_ok else "not reproduced",
              "rule: larger in magnitude by a tenth at every speed, with the paper's sign"
              + ("; larger in magnitude, but of the opposite sign (the rollers run faster than the ideal)"
                 if order_ok and not sign_ok else "")), every)
    v, what = level(ru[-1].paper, 0.10)
    add(Claim("8", "roller slip at 5 krpm", "about 10 %", f"{pct(ru[-1].paper)} (unloaded zone)", v,
              what + "; the paper's slip is eq. 52 against its own ideal speeds; ours against the model geometry's"),
        st.unsteady([order[-1]]))
    # Fig. 9: cage slip
    cg = [window_value(s, "Cage slip [-]", None) for s in S]
    v, what = trend(cg[0], cg[-1], +1, paper_sign=PAPER_SIGN["cage slip"])
    add(Claim("9", "cage slip rises with speed", "rises; 2 krpm 0-0.03 %", f"{pct(cg[0].paper)} -> {pct(cg[-1].paper)}",
              v, what), ends)
    return out


def _preload(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("10-13", "preload series", "-", "-", "not run", "studies/trb_preload.toml")]
    preloads = [f"{k} um" for k in (10, 20, 30, 40)]
    if _missing(st, "axial_displacement", preloads):
        return [Claim("10-13", "preload series", "-", "-", "not run",
                      f"no finished run at {', '.join(_missing(st, 'axial_displacement', preloads))}")]
    order = [st.where(axial_displacement=k)[0] for k in preloads]
    S = [st.summaries[i] for i in order]
    ends, every = st.unsteady([order[0], order[-1]]), st.unsteady(order)
    out = []

    def add(claim, unsteady):
        out.append(steady(claim, unsteady))

    pct = lambda x: "-" if x is None else f"{100 * x:.3g} %"  # noqa: E731
    tl = [window_value(s, "Tilt [rad]", "loaded zone") for s in S]
    v, what = trend(tl[0], tl[-1], paper=(-0.27e-4, -0.96e-4))
    add(Claim("10", "mean tilt falls (signed) with preload, 10 -> 40 um (grows in magnitude: the paper's is negative)",
              "-0.27e-4 -> -0.96e-4 rad", f"{tl[0].text()} -> {tl[-1].text()} rad", v, what), ends)
    v, what = level(tl[-1].paper, -0.96e-4)
    add(Claim("10", "mean tilt at 40 um", "-0.96e-4 rad", "-" if tl[-1].paper is None else f"{tl[-1].paper:.3g} rad",
              v, what), st.unsteady([order[-1]]))
    sk = [window_value(s, "Skew [rad]", "loaded zone") for s in S]
    v, what = trend(sk[0], sk[-1], paper=(4.23e-3, 5.50e-3))
    add(Claim("11", "mean skew grows with preload", "4.23e-3 -> 5.50e-3 rad",
              f"{sk[0].text()} -> {sk[-1].text()} rad", v, what), ends)
    v, what = level(sk[-1].paper, 5.50e-3)
    add(Claim("11", "mean skew at 40 um", "5.50e-3 rad", "-" if sk[-1].paper is None else f"{sk[-1].paper:.3g} rad",
              v, what), st.unsteady([order[-1]]))
    # start amplitude that decays (except at 10 um): skew amplitude over 0-30 ms against the paper's window
    decays = []
    for i in order:
        ts = _roller_series(st.folders[i], "Skew [rad]") if st.folders else None
        if ts is None or ts[1] is None:
            decays = None
            break
        t, x = ts
        early, late = _oscillation(t, x, 0.0, 0.03), _oscillation(t, x, 0.1, 0.18)
        decays.append(early / late if late > 0 else math.inf)
    if decays is None:
        out.append(Claim("11", "large start amplitude of skew that decays, except at 10 um", "-", "-", "not comparable",
                         "the study kept no time series"))
    else:
        add(Claim("11", "large start amplitude of skew that decays, except at 10 um", "decays at 20-40 um",
                  "early (0-30 ms) / late (0.1-0.18 s) amplitude: " + ", ".join(f"{d:.2g}" for d in decays),
                  "reproduced" if all(d > 2 for d in decays[1:]) and decays[0] < 2 else "not reproduced",
                  "oscillation amplitude about each roller's linear trend in the window (the skew's growth "
                  "from the start left out); rule: a ratio above 2 decays; our start is the quasi-static "
                  "equilibrium, not an impact"), every)
    rl = [window_value(s, "Roller slip [-]", "loaded zone") for s in S]
    v, what = trend(rl[0], rl[-1], paper=(0.0189e-2, 0.0057e-2))
    add(Claim("12", "roller slip falls with preload", "0.0189 -> 0.0057 % (0.0073 % at 30 um)",
              f"{pct(rl[0].paper)} -> {pct(rl[-1].paper)}", v, what), ends)
    v, what = level(rl[0].paper, 0.0189e-2)
    add(Claim("12", "roller slip at 10 um", "0.0189 %", pct(rl[0].paper), v,
              what + ("; slip < 0: our rollers run faster than the geometry's ideal speed"
                      if rl[0].paper is not None and rl[0].paper < 0 else "")), st.unsteady([order[0]]))
    cg = [window_value(s, "Cage slip [-]", None) for s in S]
    v, what = trend(cg[0], cg[-1], paper=(0.0189e-2, 0.0055e-2))
    add(Claim("13", "cage slip falls with preload", "0.0189 -> 0.0055 %", f"{pct(cg[0].paper)} -> {pct(cg[-1].paper)}",
              v, what), ends)
    a = [c.paper for c in cg]
    if any(x is None for x in a):
        out.append(Claim("13", "little gain from 30 to 40 um", "0.0076 -> 0.0055 % (16 % of the fall from 10 um)", "-",
                         "not comparable", "no value"))
    else:
        gain = (a[2] - a[3]) / (a[0] - a[3]) if a[0] != a[3] else math.nan
        falls = a[3] < a[0]
        add(Claim("13", "little gain from 30 to 40 um", "0.0076 -> 0.0055 % (16 % of the fall from 10 um)",
                  f"the 30 -> 40 um step is {100 * gain:.2g} % of the 10 -> 40 um change",
                  "reproduced" if falls and gain < 0.25 else "not reproduced",
                  "rule: the slip falls (signed) and the 30 -> 40 um fall is below a quarter of the 10 -> 40 um fall"
                  + ("" if falls else "; our cage slip rises (signed) with preload: there is no fall to gain")), every)
    return out


def _axis_series(st: Study, key: str, values: list, stat: str, zone) -> list[Value]:
    return [window_value(st.summaries[st.where(**{key: v})[0]], stat, zone) for v in values]


#: the headline outputs of the grease studies: name -> (statistic, zone)
HEADLINE_OUTPUTS = {"tilt": ("Tilt [rad]", "loaded zone"), "skew": ("Skew [rad]", "loaded zone"),
                    "roller slip": ("Roller slip [-]", "loaded zone"), "cage slip": ("Cage slip [-]", None)}


def _grease_param(st: Study | None, fig: str, key: str, values: list, label: str, claims: dict,
                  levels: tuple = ()) -> list[Claim]:
    """Trend rows (per quantity: (claimed sign, 0 for "little effect"; the paper's words; its printed ends
    or None)) and level rows (name, statistic, zone, the paper's number)."""
    if st is None:
        return [Claim(fig, f"{label} series", "-", "-", "not run", f"studies/{'trb_' + label.replace(' ', '_')}.toml")]
    if _missing(st, key, values):
        return [Claim(fig, f"{label} series", "-", "-", "not run", f"no finished run at {', '.join(_missing(st, key, values))}")]
    out = []
    idx = [st.where(**{key: v})[0] for v in values]
    for name, (stat, zone) in HEADLINE_OUTPUTS.items():
        vals = _axis_series(st, key, values, stat, zone)
        claimed, paper, ends = claims[name]
        if claimed == 0:
            v, what = little_effect(vals)
            used = idx
        else:
            v, what = trend(vals[0], vals[-1], claimed, paper=ends, paper_sign=PAPER_SIGN[name])
            used = [idx[0], idx[-1]]
        direction = {1: "rises", -1: "falls", 0: "changes little"}[claimed]
        signed = " (signed; grows in magnitude: the paper's is negative)" if name == "tilt" and claimed == -1 else ""
        out.append(steady(Claim(fig, f"{name} {direction}{signed} with {label} ({values[0]} -> {values[-1]})", paper,
                                f"{vals[0].text()} -> {vals[-1].text()}", v, what), st.unsteady(used)))
    for name, stat, zone, paper in levels:
        vals = [v.paper for v in _axis_series(st, key, values, stat, zone) if v.paper is not None]
        ours = float(np.mean(vals)) if vals else None
        v, what = level(ours, paper)
        out.append(steady(Claim(fig, f"mean {name} over the {label} series", f"{paper:.3g}",
                                f"{ours:.3g}" if vals else "-", v, what), st.unsteady(idx)))
    return out


#: Fig. 16's claims, signed (the paper's words on the tilt are of its magnitude; its tilts are negative)
FIG16 = {"lithium": {"tilt": -1, "skew": -1, "roller slip": -1},
         "polyurea": {"tilt": 1, "skew": 1, "roller slip": 1},
         "calcium": {"tilt": 1, "skew": -1, "roller slip": -1}}


def _temperature(st: Study | None) -> list[Claim]:
    if st is None:
        return [Claim("16", "grease x temperature series", "-", "-", "not run", "studies/trb_grease_temperature.toml")]
    gone = [f"{g} {t} C" for g in FIG16 for t in (15, 70) if not st.where(grease=g, temperature_c=t)]
    if gone:
        return [Claim("16", "grease x temperature series", "-", "-", "not run", f"no finished run at {', '.join(gone)}")]
    out = []
    for grease, per in FIG16.items():
        i_lo, i_hi = st.where(grease=grease, temperature_c=15)[0], st.where(grease=grease, temperature_c=70)[0]
        for name, claimed in per.items():
            stat, zone = HEADLINE_OUTPUTS[name]
            lo = window_value(st.summaries[i_lo], stat, zone)
            hi = window_value(st.summaries[i_hi], stat, zone)
            v, what = trend(lo, hi, claimed, paper_sign=PAPER_SIGN[name])
            words = {("tilt", 1): "falls in magnitude (signed: rises)", ("tilt", -1): "grows in magnitude (signed: falls)"}
            out.append(steady(Claim("16", f"{grease}: {name} "
                                    f"{words.get((name, claimed), 'rises' if claimed > 0 else 'falls')} from 15 to 70 C",
                                    "-", f"{lo.text()} -> {hi.text()}", v, what), st.unsteady([i_lo, i_hi])))
    tilt = {g: [window_value(st.summaries[i], "Tilt [rad]", "loaded zone").paper for i in st.where(grease=g)] for g in FIG16}
    if any(x is None for xs in tilt.values() for x in xs):
        out.append(Claim("16", "lithium has the largest tilt", "lithium (its tilts negative)", "-", "not comparable", "no value"))
        return out
    tilt = {g: float(np.mean(xs)) for g, xs in tilt.items()}
    big = max(tilt, key=lambda g: abs(tilt[g]))
    ok = big == "lithium" and tilt["lithium"] < 0
    out.append(steady(Claim("16", "lithium has the largest tilt", "lithium (its tilts negative)",
                            ", ".join(f"{g} {t:.3g}" for g, t in tilt.items()) + " rad (mean over temperatures)",
                            "reproduced" if ok else "not reproduced",
                            f"rule: lithium's mean tilt the largest in magnitude and negative; largest magnitude: {big}"
                            + ("" if tilt["lithium"] < 0 else "; our tilts are positive")),
                      st.unsteady(range(len(st.summaries)))))
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
                         {"tilt": (-1, "about -4.7e-5 -> -5.2e-5 rad (read off the figure's axis; 'increases': in "
                                       "magnitude)", (-4.7e-5, -5.2e-5)),
                          "skew": (-1, "falls", None), "roller slip": (-1, "falls", None),
                          "cage slip": (-1, "falls", None)})
    out += _grease_param(st["trb_yield_stress"], "15", "yield_stress", ["251.8 Pa", "501.8 Pa"], "yield stress",
                         {"tilt": (0, "-4.8e-5 to -5.5e-5 rad", None), "skew": (0, "3.5e-3 to 4.5e-3 rad", None),
                          "roller slip": (0, "0.009-0.015 %", None), "cage slip": (0, "0.009-0.015 %", None)},
                         levels=(("tilt [rad]", "Tilt [rad]", "loaded zone", -5.15e-5),
                                 ("skew [rad]", "Skew [rad]", "loaded zone", 4.0e-3),
                                 ("roller slip [-]", "Roller slip [-]", "loaded zone", 1.2e-4)))
    out += _temperature(st["trb_grease_temperature"])
    return out


def counts(rows: list[Claim]) -> dict:
    """Rows per summary category (:data:`CATEGORIES`; "not run" only when some study has not run)."""
    out = {c: 0 for c in CATEGORIES}
    for r in rows:
        c = category(r.verdict)
        out[c] = out.get(c, 0) + 1
    if not out["not run"]:
        del out["not run"]
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


# --------------------------------------------------------------------------- elasticities

#: per main study: the axis key (last part) and the route by which the parameter enters the model (read
#: from the code: lubedyn.dynamics.tapered.model.TaperedBearing.args, lubedyn.dynamics.tapered.kernels,
#: lubedyn.lubrication.laws); "{films}" is filled from the runs' cases (:func:`route`)
ROUTES = {
    "trb_speed": (
        "speed", "operating.speed, the cone's: the ideal kinematics (cage speed, entrainment speed u_e) and with "
        "them every raceway film (Dowson-Toyoda h0 at u_e, kernels._strip_film), the limited traction's shear rate "
        "v_s/h0 and its elastic-film slope 2 G b^2/(u_e h0); the rib's sliding and entrainment speeds and film "
        "(flange.rib_film); the pocket and guide-land films' surface speeds; the bodies' inertial (centrifugal, "
        "gyroscopic) terms; eq. 52's ideal speeds"),
    "trb_preload": (
        "axial_displacement", "operating.axial_displacement (the cone held there, axial locked): the contact "
        "approaches, so every slice load (Palmgren slice law), the Hertz strips (half-width b, peak p0) the "
        "traction integrates over, the films' load term and the flange load; no lubricant value changes"),
    "trb_plastic_viscosity": (
        "consistency", "lubricant.consistency phi0 (a custom grease): the Herschel-Bulkley stress "
        "tau_y r(D) + phi0 exp(alpha p) |D|^n of the limited laws, capped by tau_L = tau_L0 + gamma_L p "
        "(lubrication/laws/traction.py) -- the raceway traction (limited_strip_traction, tabulated or by "
        "quadrature) and the rib's grease friction (limited_ellipse_traction, added in flange.flange_friction); "
        "{films}; the paper's route for Fig. 14 (the rib film thickening with phi, the asperity share falling) "
        "needs a film that follows phi"),
    "trb_yield_stress": (
        "yield_stress", "lubricant.yield_stress tau_y: the same two limited laws, as the additive "
        "tau_y (1 - exp(-D/D_r)) (D_r = lubricant.yield_rate) in a stress capped by tau_L = tau_L0 + gamma_L p "
        "({limit}); {films}"),
    "trb_grease_temperature": (
        "temperature_c", "lubricant.grease and temperature_c: Table 2's tau_y, phi0 and n at the temperature "
        "(lubrication.laws.grease.grease_at, log-linear between its rows) into the same two limited laws; {films}; "
        "the elasticity is against the absolute temperature (K)"),
}


def _case_values(st: Study) -> dict:
    """The lubricant table of the study's first run (its case.resolved.toml), {} when not kept."""
    import tomllib

    f = Path(st.folders[0]) / "case.resolved.toml" if st.folders else None
    if f is None or not f.is_file():
        return {}
    return tomllib.loads(f.read_text()).get("lubricant", {})


def route(name: str, st: Study | None = None) -> str:
    """:data:`ROUTES`' text of a main study, its films part read from the runs' lubricant: under
    ``lubricant.reading = "base_oil"`` every film (raceway, rib, pocket, guide land) takes the base oil's
    viscosity, which follows ``temperature_c`` only with ``lubricant.oil_temperature = "walther"``."""
    text = ROUTES[name][1]
    if "{films}" not in text:
        return text
    lub = _case_values(st) if st is not None else {}
    tau_l0 = lub.get("limiting_stress")
    text = text.replace("{limit}", "tau_L0 not recorded" if tau_l0 is None else
                        f"tau_L0 = {tau_l0 / 1e6:g} MPa: tau_y/tau_L0 <= {501.8 / tau_l0:.2g} at 501.8 Pa")
    reading, law = lub.get("reading"), lub.get("oil_temperature", "none")
    if reading is None:
        films = "the films: as the runs' lubricant.reading says (their cases were not kept)"
    elif reading != "base_oil":
        films = (f"and, with lubricant.reading = '{reading}', the films' Newtonian viscosity "
                 "(lubrication.laws.grease.Grease.viscosity), so every film too")
    elif name == "trb_grease_temperature" and law == "walther":
        films = ("and every film (raceway h0, the rib film and its asperity share, the elastic-film slope, the pocket and "
                 "guide-land films) through the base oil's viscosity, which follows the temperature on ASTM D341's "
                 "line (lubricant.oil_temperature = 'walther', lubrication.laws.thermal)")
    elif name == "trb_grease_temperature":
        films = "no film: the base oil's viscosity stays at every temperature (lubricant.oil_temperature = 'none')"
    else:
        eta0 = lub.get("viscosity", {}).get("eta0") if isinstance(lub.get("viscosity"), dict) else None
        films = ("no film: every film (raceway, rib, pocket, guide land) takes the base oil's viscosity"
                 + ("" if eta0 is None else f" ({eta0:g} Pa s)") + " (lubricant.reading = 'base_oil')")
    return text.replace("{films}", films)


#: the paper's end points where it prints them: study -> output -> (y at the first value, y at the last)
PAPER_ENDS = {"trb_speed": {"tilt": (-0.14e-4, -0.40e-4), "skew": (3.06e-3, 4.47e-3)},
              "trb_preload": {"tilt": (-0.27e-4, -0.96e-4), "skew": (4.23e-3, 5.50e-3),
                              "roller slip": (0.0189e-2, 0.0057e-2), "cage slip": (0.0189e-2, 0.0055e-2)}}
#: what the paper gives instead where it prints no end points
PAPER_BOUNDS = {("trb_plastic_viscosity", "tilt"): (
    "not printed (its axis spans -4.7 to -5.2e-5 rad: |e| <= "
    f"{math.log(5.2 / 4.7) / math.log(38.44 / 2.44):.3f})"),
    ("trb_yield_stress", "tilt"): "not printed ('little effect')", ("trb_yield_stress", "skew"): "not printed ('little effect')",
    ("trb_yield_stress", "roller slip"): "not printed ('little effect')",
    ("trb_yield_stress", "cage slip"): "not printed ('little effect')"}


def _number(label) -> float:
    return float(str(label).split()[0])


def elasticity(x1: float, x2: float, y1: float | None, y2: float | None) -> float | None:
    """The end-point secant of d ln|y| / d ln x: ln(|y2|/|y1|) / ln(x2/x1) (None when a y is missing or 0)."""
    if y1 is None or y2 is None or y1 == 0.0 or y2 == 0.0 or x1 <= 0.0 or x2 <= 0.0 or x1 == x2:
        return None
    return math.log(abs(y2) / abs(y1)) / math.log(x2 / x1)


def elasticities(folder) -> list[dict]:
    """Per main study found under ``folder`` (per grease for the temperature study): each headline output's
    elasticity d ln|y| / d ln x between the axis' first and last value (paper's window means), the
    paper's from its printed numbers where it prints them, whether y changes sign, and the parameter's
    route into the model (:data:`ROUTES`)."""
    out = []
    for name in MAIN_STUDIES:
        st = Study.load(Path(folder) / name)
        if st is None or not st.summaries:
            continue
        key = ROUTES[name][0]
        how = route(name, st)
        kx = next(j for j, a in enumerate(st.axes) if a.rpartition(".")[2] == key)
        groups = [None]
        if name == "trb_grease_temperature":
            kg = next(j for j, a in enumerate(st.axes) if a.rpartition(".")[2] == "grease")
            groups = list(dict.fromkeys(lab[kg] for lab in st.labels))
        for g in groups:
            idx = [i for i, lab in enumerate(st.labels) if g is None or lab[kg] == g]
            idx.sort(key=lambda i: _number(st.labels[i][kx]))
            if len(idx) < 2:
                continue
            i1, i2 = idx[0], idx[-1]
            x1, x2 = _number(st.labels[i1][kx]), _number(st.labels[i2][kx])
            if name == "trb_grease_temperature":
                x1, x2 = x1 + 273.15, x2 + 273.15
            for out_name, (stat, zone) in HEADLINE_OUTPUTS.items():
                y1 = window_value(st.summaries[i1], stat, zone).paper
                y2 = window_value(st.summaries[i2], stat, zone).paper
                ends = PAPER_ENDS.get(name, {}).get(out_name)
                paper = (elasticity(x1, x2, *ends) if ends else None)
                out.append({"study": name + ("" if g is None else f" ({g})"), "axis": st.axes[kx],
                            "from": str(st.labels[i1][kx]), "to": str(st.labels[i2][kx]), "output": out_name,
                            "ours": elasticity(x1, x2, y1, y2),
                            "sign change": y1 is not None and y2 is not None and y1 * y2 < 0,
                            "paper": paper, "paper text": (f"{paper:.3g}" if paper is not None else
                                                           PAPER_BOUNDS.get((name, out_name), "not printed")),
                            "route": how})
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


#: the Morris screen of the unstated values (studies/trb_screen_unstated.toml) and paper A's numbers at its
#: point (2,000 rpm, Fr 20 kN: Figs. 6-9's first speed): output -> (paper's value or range, what it is)
SCREEN_STUDY = "trb_screen_unstated"
SCREEN_PAPER = {"Skew, loaded zone, mean [rad]": ((3.06e-3, 3.06e-3), "Fig. 7 mean"),
                "Tilt, loaded zone, mean [rad]": ((-0.14e-4, -0.14e-4), "Fig. 6 mean"),
                "Roller slip, loaded zone, mean [-]": ((-1e-4, 7e-4), "Fig. 8 inset, -0.01..0.07 %"),
                "Cage slip, mean [-]": ((0.0, 3e-4), "Fig. 9 inset, 0..0.03 %")}


def screen(folder) -> dict | None:
    """The Morris screen's answer per output (None when the study has not run): the range over every
    plausible set it ran, the paper's number, whether any set reproduces it (a level within
    :data:`LEVEL_FACTOR` with the paper's sign; a range: a value inside it) and the factors by mu*."""
    path = Path(folder) / SCREEN_STUDY / "study.json"
    if not path.is_file():
        return None
    doc = json.loads(path.read_text(encoding="utf-8"))
    morris = doc.get("Morris screening", {}).get("outputs", {})
    out = {"runs": doc["runs"]["total"], "failed": doc["runs"]["failed"], "outputs": {}}
    for name, ((lo, hi), what) in SCREEN_PAPER.items():
        values = [p["outputs"][name]["median"] for p in doc["points"] if p["outputs"][name]["median"] is not None]
        if lo == hi:  # a printed level
            hits = [v for v in values if v * lo > 0 and 1 / LEVEL_FACTOR <= v / lo <= LEVEL_FACTOR]
        else:
            hits = [v for v in values if lo <= v <= hi]
        ranked = sorted(morris.get(name, {}).items(), key=lambda kv: -(kv[1]["mu*"] or 0.0))
        out["outputs"][name] = {"min": min(values), "max": max(values), "paper": (lo, hi), "paper is": what,
                                "reproducing sets": len(hits), "sets": len(values),
                                "ranked": [(k, v["mu*"], v["mu"], v["sigma"]) for k, v in ranked]}
    return out


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
        r = json.loads(path.read_text()).get("runs")
        if r is None:   # a study.json without its run record (written by hand)
            continue
        st = Study.load(Path(folder) / name)
        how = sorted({_traction_evaluation(f) for f in st.folders})
        out.append({"study": name, "runs": r["total"], "workers": r["workers"], "wall time [s]": r["wall time [s]"],
                    "traction evaluation": ", ".join(how)})
    return out


def steadiness(folder) -> list[dict]:
    """Per point of the main studies found under ``folder``: whether it is steady (module docstring) and
    its converged window's largest relative change of a headline mean."""
    out = []
    for name in MAIN_STUDIES:
        st = Study.load(Path(folder) / name)
        if st is None:
            continue
        for i, s in enumerate(st.summaries):
            c = s.get(CONVERGED)
            out.append({"study": name, "point": st.label(i), "steady": s.get(STEADY) is True,
                        "largest relative change [-]": c.get("Largest relative change [-]") if isinstance(c, dict) else None})
    return out


def _cell(x) -> str:
    """A markdown table cell: its pipes escaped."""
    return str(x).replace("|", "\\|")


def markdown(folder) -> str:
    """The checklist (counts, claims, conclusions, steadiness per point, elasticities, sensitivity, run times)
    as markdown."""
    rows = claims(folder)
    n = counts(rows)
    lines = [f"Verdicts ({len(rows)} rows): " + ", ".join(f"{k} {v}" for k, v in n.items())
             + f".  Rules: `lubedyn.papers.wu2018.claims` (trend sizes within x {SIZE_FACTOR:g}, levels within "
             f"x {LEVEL_FACTOR:g}, signed; \"{UNSTEADY}\" counts as not steady).", "",
             "| fig | paper A's claim | paper | lubedyn | verdict | how measured |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join(_cell(x) for x in (r.figure, r.statement, r.paper, r.ours)) + f" | **{r.verdict}** | "
                     f"{_cell(r.note)} |")
    lines += ["", "| conclusion | paper A | its rows | verdict |", "|---|---|---|---|"]
    for c in conclusions(rows):
        lines.append(f"| {c.figure} | {_cell(c.statement)} | {_cell(c.ours)} | **{c.verdict}** |")
    steady_rows = steadiness(folder)
    if steady_rows:
        lines += ["", "| study | point | steady (converged window) | largest window-to-window change |", "|---|---|---|---|"]
        for r in steady_rows:
            ch = r["largest relative change [-]"]
            lines.append(f"| `{r['study']}` | {r['point']} | {'yes' if r['steady'] else '**no**'} | "
                         f"{'-' if ch is None else f'{100 * ch:.2g} %'} |")
    el = elasticities(folder)
    if el:
        lines += ["", "| study | axis | output | elasticity d ln\\|y\\| / d ln x, lubedyn | paper A |",
                  "|---|---|---|---|---|"]
        for r in el:
            ours = "-" if r["ours"] is None else f"{r['ours']:.3g}" + (" (y changes sign)" if r["sign change"] else "")
            lines.append(f"| `{r['study']}` | `{r['axis']}` {r['from']} -> {r['to']} | {r['output']} | {ours} | "
                         f"{_cell(r['paper text'])} |")
        lines += ["", "| study | how the parameter enters the model |", "|---|---|"]
        for name in MAIN_STUDIES:
            if any(r["study"].startswith(name) for r in el):
                lines.append(f"| `{name}` | {_cell(route(name, Study.load(Path(folder) / name)))} |")
    sens = sensitivity(folder)
    if sens:
        lines += ["", "| assumption (study) | values | loaded-zone skew [rad] | loaded-zone tilt [rad] | roller slip | "
                  "skew largest/smallest |", "|---|---|---|---|---|---|"]
        for r in sens:
            fmt = lambda xs, f: ", ".join("-" if x is None else format(x, f) for x in xs)  # noqa: E731
            rng = "-" if r["skew range [-]"] is None else f"{r['skew range [-]']:.2f}"
            lines.append(f"| `{r['key']}` ({r['study']}) | {', '.join(map(str, r['values']))} | {fmt(r['skew'], '.3g')} | "
                         f"{fmt(r['tilt'], '.2g')} | {fmt(r['slip'], '.2g')} | {rng} |")
    scr = screen(folder)
    if scr is not None:
        lines += ["", f"Morris screen of the unstated values (`{SCREEN_STUDY}`, {scr['runs']} runs, {scr['failed']} "
                  "failed; mu* in output units per full range of the factor):", "",
                  "| output | over the plausible sets | paper A | sets reproducing it | factors by mu* (mu) |",
                  "|---|---|---|---|---|"]
        for name, r in scr["outputs"].items():
            lo, hi = r["paper"]
            paper = f"{lo:.3g}" if lo == hi else f"{lo:.3g} .. {hi:.3g}"
            ranked = "; ".join(f"`{k}` {m:.2g} ({mu:+.2g})" for k, m, mu, _ in r["ranked"][:3])
            lines.append(f"| {name} | {r['min']:.3g} .. {r['max']:.3g} | {paper} ({r['paper is']}) | "
                         f"**{r['reproducing sets']} of {r['sets']}** | {ranked} |")
    times = run_times(folder)
    if times:
        lines += ["", "| study | runs | workers | wall time | raceway traction evaluated by |", "|---|---|---|---|---|"]
        for t in times:
            lines.append(f"| `{t['study']}` | {t['runs']} | {t['workers']} | {t['wall time [s]'] / 60:.1f} min | "
                         f"{t['traction evaluation']} |")
    return "\n".join(lines)
