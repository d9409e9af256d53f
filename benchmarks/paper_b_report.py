"""Paper B's claims against the project's ensemble studies: a markdown table of verdicts.

Reads the run folders of three studies (``lubedyn study`` output folders) and prints, for every claim
of paper B (Zhang et al., Symmetry 16 (2024) 741) that the studies can test, the paper's statement, the
project's numbers (median and min-max over the seeded members of each point) and a verdict:

* **reproduced** / **not reproduced**: the members' ranges of the two compared points do not overlap
  (the difference is resolved) and its sign agrees / disagrees with the paper;
* **not resolvable**: the ranges overlap, so the ensemble cannot tell the sign;
* for magnitudes, the ratio to the paper's number.

::

    python benchmarks/paper_b_report.py --drop runs/cageless_drop_speeds --slot runs/cageless_slot_effect \\
        --fidelity runs/cageless_film_fidelity --sensitivity runs/cageless_slot_sensitivity > report.md

Speed claims as regressions (``--fine``, the 11-speed study ``studies/cageless_fine_speeds.toml``): each
output against the speed over every member run, Theil-Sen's slope (the median of the pairwise slopes:
robust to the few members far off, as the medians above) with its 95 % confidence band
(``scipy.stats.theilslopes``); *reproduced* / *not reproduced* where the band excludes zero and its sign
agrees / disagrees with the claim, *not resolvable* where it holds zero.  A claim on a speed range
(Fig. 5's axial force) is fitted on that range only.  Table 3's exponents (``--fine-exponents``, the
same axis with the guarded per-direction exponents on) enter only from runs whose guarded verdict resolved them (positive or not positive); with fewer than half resolved the claim is "not
resolvable" whatever the slope.  ``--fine`` also writes ``fine_speeds.png`` beside the study's table, and
answers Figs. 6-8's "fractal" claims on the correlation dimension D2 of ball 0's phase portraits (a trend
with speed for z; z against x and y per run by a sign test; x and y near 15,000/20,000 rpm against the
axis' ends by a Mann-Whitney U test).

Every number is read from the studies' ``summary.json`` files; nothing is typed in except the paper's
own values (Table 3 and the statements quoted).
"""
from __future__ import annotations

import argparse
import json
import csv
import functools
import statistics
from pathlib import Path

SPEEDS = (10000, 15000, 20000, 25000)
#: paper B, Table 3 ("maximum Lyapunov exponent", orthogonalisation method with log2, no unit printed)
TABLE3 = {"x": (4.5933, 4.2011, 3.9126, 3.9158), "y": (4.6431, 4.2613, 3.9350, 3.9094),
          "z": (7.6814, 7.9442, 7.9971, 8.6271)}


def members(study: Path, speed: int, extra: str = "") -> list[dict]:
    """The summaries of the members of one point (folder ``operating.speed=<speed>rpm<extra>``)."""
    folder = study / "runs" / f"operating.speed={speed}rpm{extra}"
    return [json.loads((m / "summary.json").read_text()) for m in sorted(folder.glob("m*"))
            if (m / "summary.json").is_file()]


def values(runs: list[dict], key: str) -> list[float]:
    return [float(r[key]) for r in runs if isinstance(r.get(key), (int, float))]


def stat(v: list[float], fmt: str = ".3g") -> str:
    if not v:
        return "n/a"
    return f"{statistics.median(v):{fmt}} [{min(v):{fmt}}, {max(v):{fmt}}]"


def compare(a: list[float], b: list[float], expect: str) -> str:
    """Verdict for the claim 'b is <expect> than a' (expect 'higher' or 'lower')."""
    if not a or not b:
        return "not computed"
    if max(a) < min(b):
        sign = "higher"
    elif max(b) < min(a):
        sign = "lower"
    else:
        return "not resolvable (ranges overlap)"
    return "reproduced" if sign == expect else f"not reproduced ({sign})"


def rows_drop(study: Path) -> list[tuple]:
    runs = {s: members(study, s) for s in SPEEDS}
    out = []
    w = {d: {s: values(runs[s], f"Wolf exponent, ball 0 {d} [bits/s]") for s in SPEEDS} for d in "xyz"}
    for s in SPEEDS:
        verdicts = [compare(w["x"][s] + w["y"][s], w["z"][s], "higher")]
        out.append((f"Table 3 at {s} rpm: z largest", f"z {TABLE3['z'][SPEEDS.index(s)]} > x, y "
                    f"{TABLE3['x'][SPEEDS.index(s)]}, {TABLE3['y'][SPEEDS.index(s)]}",
                    f"Wolf z {stat(w['z'][s])}; x {stat(w['x'][s])}; y {stat(w['y'][s])} bits/s", verdicts[0]))
    for s in SPEEDS:
        out.append((f"Table 3 at {s} rpm: y slightly above x", "y > x by 0.1-1.4 %",
                    f"y {stat(w['y'][s])}; x {stat(w['x'][s])}", compare(w["x"][s], w["y"][s], "higher")))
    for d in "xy":
        out.append((f"Table 3: {d} falls from 10,000 to 25,000 rpm", f"{TABLE3[d][0]} -> {TABLE3[d][3]}",
                    f"{stat(w[d][10000])} -> {stat(w[d][25000])}", compare(w[d][10000], w[d][25000], "lower")))
    out.append(("Table 3: x at 25,000 above x at 20,000 rpm", "3.9158 > 3.9126 (+0.08 %)",
                f"{stat(w['x'][25000])} vs {stat(w['x'][20000])}", compare(w["x"][20000], w["x"][25000], "higher")))
    out.append(("Table 3: z rises with speed", "7.68 -> 8.63",
                f"{stat(w['z'][10000])} -> {stat(w['z'][25000])}", compare(w["z"][10000], w["z"][25000], "higher")))
    ratios = [statistics.median(w[d][s]) / TABLE3[d][i] for d in "xyz" for i, s in enumerate(SPEEDS) if w[d][s]]
    resolved = sum(r.get(f"Wolf exponent, ball 0 {d} verdict") in ("positive", "not positive")
                   for s in SPEEDS for r in runs[s] for d in "xyz")
    total = sum(len(runs[s]) for s in SPEEDS) * 3
    out.append(("Table 3 magnitudes", "x, y 3.9-4.6; z 7.7-8.6 (log2, unit not printed)",
                f"median / paper {min(ratios):.2g}-{max(ratios):.2g} (bits/s); resolved exponents "
                f"{resolved} of {total} (their verdict positive or not positive: in runs since the guards, "
                "distinguishable from surrogates, insensitive to the settings and converged)",
                "not comparable (unit and coordinates not stated; most estimates not resolved)"))
    spin = {s: values(runs[s], "Inner ring spin-up time [s]") for s in SPEEDS}
    out.append(("Fig. 3: faster settling at higher speed (inner ring)", "time to the stable stage falls with speed",
                " -> ".join(f"{stat([x * 1e3 for x in spin[s]])} ms" for s in SPEEDS),
                compare(spin[10000], spin[25000], "lower")))
    for d in "xy":
        key = f"Settling time, ball 0 {d} [s]"
        st = {s: values(runs[s], key) for s in SPEEDS}
        short = sum(str(r.get(key[:-4] + ", note", "")).startswith("record too short")
                    for s in (10000, 25000) for r in runs[s])
        verdict = compare(st[10000], st[25000], "lower")
        if short:  # members whose settling time is the record's edge (lubedyn.dynamics.analysis.settling)
            verdict = f"record too short ({short} of {len(runs[10000]) + len(runs[25000])} members)"
        out.append((f"Fig. 3: faster settling of the ball in {d}", "falls with speed",
                    f"{stat(st[10000])} s -> {stat(st[25000])} s", verdict))
    col = {s: values(runs[s], "Ball-ball collisions [-]") for s in SPEEDS}
    out.append(("Conclusions: fewer collisions at higher speed", "fewer at higher speed",
                " -> ".join(stat(col[s], ".4g") for s in SPEEDS), compare(col[10000], col[25000], "lower")))
    for s in SPEEDS:
        spin_t = values(runs[s], "Inner ring spin-up time [s]")
        dur = values(runs[s], "Simulated time [s]")
        during = values(runs[s], "Collisions during ring spin-up [-]")
        after = values(runs[s], "Collisions after ring spin-up [-]")
        r1 = [c / t for c, t in zip(during, spin_t)]
        r2 = [c / (T - t) for c, t, T in zip(after, spin_t, dur)]
        out.append((f"Fig. 5 at {s} rpm: a burst of collisions at spin-up, then far fewer",
                    "many during spin-up, much fewer later",
                    f"rate during spin-up {stat(r1)} Hz, after {stat(r2)} Hz", compare(r1, r2, "lower")))
    fz = {s: values(runs[s], "Largest collision force z [N]") for s in SPEEDS}
    out.append(("Fig. 5: largest axial collision force rises from 10,000 to 20,000 rpm", "rises",
                f"{stat(fz[10000])} -> {stat(fz[20000])} N", compare(fz[10000], fz[20000], "higher")))
    out.append(("Fig. 5: at 25,000 rpm not stronger than at 20,000 rpm", "not stronger",
                f"{stat(fz[25000])} vs {stat(fz[20000])} N", compare(fz[20000], fz[25000], "lower")))
    q = {k: {s: values(runs[s], f"Collisions in quadrant {k} [-]") for s in SPEEDS}
         for k in ("I (x > 0, y > 0)", "II (x < 0, y > 0)", "III (x < 0, y < 0)", "IV (x > 0, y < 0)")}
    out.append(("Fig. 5: collisions by quadrant (load zone at the bottom, y < 0)", "(no numbers)",
                "; ".join(f"{s}: " + ", ".join(f"{k.split()[0]} {statistics.median(q[k][s]):.0f}" for k in q)
                          for s in SPEEDS), "see numbers"))
    oob = [x for s in SPEEDS for x in values(runs[s], "Film map queries outside axes [-]")]
    out.append(("(pipeline) film-map queries outside the axes", "-", f"{int(max(oob)) if oob else 'n/a'} in "
                f"{len(oob)} runs", "none" if oob and max(oob) == 0 else "some"))
    return out


def rows_slot(drop: Path, slot: Path) -> list[tuple]:
    out = []
    for s in SPEEDS:
        a = values(members(slot, s), "Ball-ball collisions [-]")
        b = values(members(drop, s), "Ball-ball collisions [-]")
        out.append((f"Sec. 3.2 at {s} rpm: the slot controls the balls (fewer collisions with it)",
                    "fewer collisions, no cumulative effect", f"with slot {stat(b, '.4g')}, without {stat(a, '.4g')}",
                    compare(a, b, "lower")))
    return out


def rows_fidelity(fid: Path) -> list[tuple]:
    out = []
    for s in (10000, 25000):
        m = members(fid, s, ",films.ball_ball=map")
        c = members(fid, s, ",films.ball_ball=closed_form")
        for key, what in (("Ball-ball collisions [-]", "collisions"), ("Largest collision normal force [N]",
                                                                      "largest collision force [N]"),
                          ("Integration wall time [s]", "integration wall time [s]")):
            a, b = values(m, key), values(c, key)
            out.append((f"film map vs closed form at {s} rpm: {what}", "-", f"map {stat(a, '.4g')}, closed form "
                        f"{stat(b, '.4g')}", compare(b, a, "higher").replace("reproduced", "map higher")
                        .replace("not map higher (lower)", "map lower")))
    return out


def rows_entrapped(study: Path) -> list[tuple]:
    """studies/cageless_entrapped_film.toml: the locked film with its entrapped-film damping (beta = 1.11, the
    default) against the undamped lock (beta = 0) at each drop speed; "damped higher / lower" where the members'
    ranges do not overlap."""
    out = []
    for s in SPEEDS:
        a = members(study, s, ",films.entrapped_damping=0.0")
        b = members(study, s, ",films.entrapped_damping=1.11")
        for key, what in (("Ball-ball collisions [-]", "collisions"),
                          ("Largest collision normal force [N]", "largest collision force [N]"),
                          ("Largest collision force z [N]", "largest axial collision force [N]"),
                          ("Longest collision [s]", "longest collision [s]"),
                          ("Inner ring spin-up time [s]", "spin-up time [s]"),
                          ("Settling time, ball 0 orbital speed [s]", "settling of ball 0's orbital speed [s]"),
                          ("Integration wall time [s]", "integration wall time [s]")):
            va, vb = values(a, key), values(b, key)
            out.append((f"entrapped film's damping at {s} rpm: {what}", "-",
                        f"damped {stat(vb, '.4g')}, undamped {stat(va, '.4g')}",
                        compare(va, vb, "higher").replace("not reproduced (lower)", "damped lower")
                        .replace("reproduced", "damped higher")))
    return out


#: the assumptions of studies/cageless_slot_sensitivity.toml: (axis, value other than the baseline's) -> label
SENSITIVITY = {("bearing.ball_density", "22104 kg/m^3"): "ball mass 0.01 kg (paper's print)",
               ("films.friction_law", "paper"): "friction law of eqs. 17-21",
               ("operating.rotor_friction", "0.3"): "rotor-ring friction 0.3",
               ("bearing.rotor_inertia", "2e-4 kg m^2"): "rotor inertia 2e-4 kg m^2"}


def rows_sensitivity(study: Path) -> list[tuple]:
    """The slot claim under each changed assumption: the points of the zipped study grouped by their
    values on every axis but ``slots.azimuths`` (read from its study.csv)."""
    import csv

    with open(study / "study.csv", newline="") as f:
        # runs with warnings are results too (their warnings are in the "warnings" column); failed runs are not
        rows = [r for r in csv.DictReader(f) if r["status"] in ("ok", "ok-with-warnings")]
    key = "Ball-ball collisions [-]"
    axes = [c for c in rows[0] if c.endswith(" [SI]") is False and c + " [SI]" in rows[0]]
    others = [a for a in axes if a != "slots.azimuths"]
    groups: dict[tuple, dict[str, list[float]]] = {}
    for r in rows:
        groups.setdefault(tuple(r[a] for a in others), {}).setdefault(r["slots.azimuths"], []).append(float(r[key]))
    out = []
    for variant, by_slot in groups.items():
        changed = [SENSITIVITY.get((a, v), f"{a} = {v}") for a, v in zip(others, variant)
                   if (a, v) in SENSITIVITY]
        label = ", ".join(changed) or "baseline"
        without = by_slot.get("[]", [])
        for slot, counts in by_slot.items():
            if slot == "[]":
                continue
            out.append((f"Sensitivity at 10000 rpm, {label}: slot at {json.loads(slot)[0]} against none",
                        "fewer collisions with the slot", f"with slot {stat(counts, '.4g')}, without "
                        f"{stat(without, '.4g')}", compare(without, counts, "lower")))
    return out


#: paper B's speed claims for the regression (output, claimed sign of d output / d speed, speed range
#: [krpm] or None for the whole axis, the paper's statement)
FINE_CLAIMS = (
    ("Inner ring spin-up time [s]", -1, None, "Fig. 3: the inner ring settles faster at higher speed"),
    ("Settling time, ball 0 x [s]", -1, None, "Fig. 3: the ball settles faster in x at higher speed"),
    ("Settling time, ball 0 y [s]", -1, None, "Fig. 3: the ball settles faster in y at higher speed"),
    ("Ball-ball collisions [-]", -1, None, "Conclusions: fewer collisions at higher speed"),
    ("Ball-ball collisions [-]", +1, (20.0, 25.0), "Fig. 5: more collisions at 25,000 than at 20,000 rpm"),
    ("Zone unsteady until [s]", -1, None, "Fig. 4: the unsteady zone ends sooner at higher speed"),
    ("Zone surge from [s]", -1, None, "Fig. 4: the surge zone comes sooner at higher speed"),
    ("Largest collision force z [N]", +1, (10.0, 20.0), "Fig. 5: largest axial collision force rises, 10,000-20,000 rpm"),
    ("Largest collision force z [N]", -1, (20.0, 25.0), "Fig. 5: not stronger at 25,000 than at 20,000 rpm"),
    ("Correlation dimension, ball 0 z phase portrait [-]", +1, None,
     "Fig. 8: z is less fractal the slower the rotor turns (D2)"),
)

#: Table 3's claims, from a fine-speed study with the guarded per-direction exponents on
#: (studies/cageless_fine_speeds_exponents.toml, ``--fine-exponents``): inertial x, y, z as the paper's X, Y,
#: Z, and the co-rotating radial and tangential directions as the other reading of X and Y (the paper does
#: not say which coordinates; co-rotating axial is inertial z)
EXPONENT_CLAIMS = (
    ("Wolf exponent, ball 0 x [bits/s]", -1, None, "Table 3: x falls with speed (4.59 -> 3.92)"),
    ("Wolf exponent, ball 0 y [bits/s]", -1, None, "Table 3: y falls with speed (4.64 -> 3.91)"),
    ("Wolf exponent, ball 0 z [bits/s]", +1, None, "Table 3: z rises with speed (7.68 -> 8.63)"),
    ("Wolf exponent, ball 0 radial [bits/s]", -1, None, "Table 3 read co-rotating: radial (X) falls with speed"),
    ("Wolf exponent, ball 0 tangential [bits/s]", -1, None, "Table 3 read co-rotating: tangential (Y) falls with speed"),
)


def fine_points(study: Path, key: str, window=None) -> tuple[list[float], list[float], int, int]:
    """(speeds [krpm], values, runs used, runs with a value) of one output over a study's member runs
    (study.csv; notes and verdicts from each run's summary.json).  An exponent counts only where its
    guarded verdict resolved it; a settling time only where it is not the record's edge."""
    x, y, have, total = [], [], 0, 0
    for speed, row in ok_runs(study):
        if window and not (window[0] - 1e-9 <= speed <= window[1] + 1e-9):
            continue
        total += 1
        value = usable_value(study, row, key)
        if value is None:
            continue
        have += 1
        x.append(speed)
        y.append(value)
    return x, y, have, total


def ok_runs(study: Path) -> list[tuple[float, dict]]:
    """(speed [krpm], study.csv row) of each finished run of a speed study."""
    with open(study / "study.csv", newline="") as f:
        return [(float(row["operating.speed [SI]"]) / _krpm(), row) for row in csv.DictReader(f)
                if row.get("status") == "ok"]


def _krpm() -> float:
    """1,000 rpm in rad/s, by the project's unit parser."""
    from lubedyn.units import parse_quantity

    return parse_quantity("1000 rpm", "angular velocity")


@functools.lru_cache(maxsize=None)
def _summary(path: Path) -> dict:
    """A run's summary.json, read once per report (every claim reads every run)."""
    return json.loads(path.read_text())


def usable_value(study: Path, row: dict, key: str) -> float | None:
    """The output ``key`` of one study row's run (its summary.json), or None where it is missing or not
    usable: an exponent whose guarded verdict did not resolve it, a settling time at the record's edge."""
    summary = _summary(study / row["run folder"] / "summary.json")
    value = summary.get(key)
    if not isinstance(value, (int, float)):
        return None
    name = key.rsplit(" [", 1)[0]
    if key.startswith("Wolf exponent") and summary.get(name + " verdict") not in ("positive", "not positive"):
        return None
    if key.startswith("Settling time") and str(summary.get(name + ", note", "")).startswith("record too short"):
        return None
    if key.startswith("Zone") and str(summary.get("Zones, note", "")).startswith("record too short"):
        return None  # the unsteady zone ends at the record's end: its end was not seen
    if key.startswith("Correlation dimension") and (str(summary.get(name + " verdict", "")).startswith("no scaling")
                                                    or str(summary.get(name + ", note", "")).startswith("forced")):
        return None  # no scaling range, or a record of too few orbits computed anyway
    return None if value != value else float(value)  # NaN: not computed


def _d2_key(direction: str) -> str:
    return f"Correlation dimension, ball 0 {direction} phase portrait [-]"


def rows_dimension(study: Path) -> list[tuple]:
    """Figs. 6-8's claims that are not trends, on the correlation dimension D2 of ball 0's phase portraits
    (lubedyn.dynamics.analysis.dimension) over every member run of the fine-speed study:

    * Fig. 8, "z is more chaotic than x and y": per run, is D2 of z above both x's and y's?  A one-sided
      sign test (``scipy.stats.binomtest``, p = 0.5) over the runs that give all three;
    * Figs. 6 and 7, "the fractal is smaller at 15,000 and 20,000 rpm" (x and y): the runs within
      1,000 rpm of 15,000 or 20,000 rpm against those within 500 rpm of 10,000 or 25,000 rpm, one-sided
      Mann-Whitney U (``scipy.stats.mannwhitneyu``).
    Both at the 5 % level; otherwise "not resolvable"."""
    from scipy.stats import binomtest, mannwhitneyu

    runs = [(speed, {d: usable_value(study, row, _d2_key(d)) for d in "xyz"}) for speed, row in ok_runs(study)]
    out = []
    trios = [v for _, v in runs if None not in v.values()]
    above = sum(1 for v in trios if v["z"] > max(v["x"], v["y"]))
    if not trios:
        out.append(("Fig. 8: z is more chaotic than x and y (D2 per run)", "z above x and y",
                    f"0 of {len(runs)} runs give D2 in all three directions", "not computed (no run gives all three)"))
    else:
        up = binomtest(above, len(trios), 0.5, alternative="greater").pvalue
        down = binomtest(above, len(trios), 0.5, alternative="less").pvalue
        verdict = ("reproduced" if up < 0.05 else "not reproduced (z below x or y in most runs)" if down < 0.05
                   else "not resolvable (sign test p >= 0.05 both ways)")
        med = {d: statistics.median(v[d] for v in trios) for d in "xyz"}
        out.append(("Fig. 8: z is more chaotic than x and y (D2 per run)", "z above x and y",
                    f"z above both in {above} of {len(trios)} runs (sign test p = {up:.2g}); median D2 x "
                    f"{med['x']:.3g}, y {med['y']:.3g}, z {med['z']:.3g}", verdict))
    for d, fig in (("x", "Fig. 6"), ("y", "Fig. 7")):
        mid = [v[d] for s, v in runs if v[d] is not None and min(abs(s - 15.0), abs(s - 20.0)) <= 1.0 + 1e-9]
        ends = [v[d] for s, v in runs if v[d] is not None and min(abs(s - 10.0), abs(s - 25.0)) <= 0.5 + 1e-9]
        claim = f"{fig}: {d} is less fractal at 15,000 and 20,000 rpm than at 10,000 and 25,000 rpm (D2)"
        if len(mid) < 3 or len(ends) < 3:
            out.append((claim, "smaller", f"{len(mid)} runs near 15/20 krpm, {len(ends)} near 10/25 krpm",
                        "not resolvable (fewer than 3 runs on a side)"))
            continue
        less = mannwhitneyu(mid, ends, alternative="less").pvalue
        more = mannwhitneyu(mid, ends, alternative="greater").pvalue
        verdict = ("reproduced" if less < 0.05 else "not reproduced (larger)" if more < 0.05
                   else "not resolvable (U test p >= 0.05 both ways)")
        out.append((claim, "smaller", f"median D2 {statistics.median(mid):.3g} ({len(mid)} runs within 1 krpm of "
                    f"15/20) against {statistics.median(ends):.3g} ({len(ends)} runs at 10/25); U test p = {less:.2g}",
                    verdict))
    return out


def slope_verdict(x: list[float], y: list[float], sign: int, used: int, total: int) -> tuple[str, str, tuple]:
    """(numbers, verdict, fit) of the claim d y / d speed has ``sign``: Theil-Sen's slope and its 95 % band."""
    from scipy.stats import theilslopes

    if used == 0:
        return (f"0 of {total} runs give a value", "not computed (no run gives a value)", None)
    if used < max(3, total / 2) or len(set(x)) < 3:
        return (f"{used} of {total} runs give a value", f"not resolvable ({used} of {total} runs resolved)", None)
    if len(set(y)) == 1:
        return (f"every one of {used} runs gives {y[0]:.4g}", "not resolvable (no change with speed)", None)
    slope, intercept, lo, hi = theilslopes(y, x, alpha=0.95)
    text = f"slope {slope:.3g} [{lo:.3g}, {hi:.3g}] per 1,000 rpm (95 %), {used} of {total} runs"
    if lo <= 0.0 <= hi:
        return text, "not resolvable (band holds 0)", (slope, intercept, lo, hi)
    found = 1 if lo > 0.0 else -1
    word = "rises" if found > 0 else "falls"
    return text, "reproduced" if found == sign else f"not reproduced ({word})", (slope, intercept, lo, hi)


def rows_fine(study: Path, figure: Path | None = None, claims=FINE_CLAIMS) -> list[tuple]:
    """Paper B's speed claims (``claims``: FINE_CLAIMS, or EXPONENT_CLAIMS for Table 3) as Theil-Sen
    regressions over a fine speed axis (see the module's docstring)."""
    out, panels = [], []
    for key, sign, window, claim in claims:
        x, y, used, total = fine_points(study, key, window)
        text, verdict, fit = slope_verdict(x, y, sign, used, total)
        span = f"{window[0]:g}-{window[1]:g} krpm" if window else "whole axis"
        weaker = window == (20.0, 25.0) and sign < 0  # "not stronger at 25,000 rpm": a flat force agrees
        said = "not stronger (a falling or flat force)" if weaker else ("falls" if sign < 0 else "rises")
        if weaker and verdict.startswith("not resolvable (band"):
            verdict = "consistent (band holds 0: not stronger, not resolved weaker)"
        out.append((claim + f" (regression, {span})", said, text, verdict))
        panels.append((key, claim, x, y, fit, window))
    if figure is not None:
        _fine_figure(panels, figure)
    return out


def _fine_figure(panels, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    n = len(panels)
    cols = 3
    fig, axes = plt.subplots((n + cols - 1) // cols, cols, figsize=(4.2 * cols, 3.2 * ((n + cols - 1) // cols)),
                             squeeze=False, layout="constrained")
    for ax, (key, claim, x, y, fit, window) in zip(axes.flat, panels):
        ax.plot(x, y, "o", ms=3, alpha=0.6, label="members")
        if fit is not None:
            slope, intercept, lo, hi = fit
            xs = np.linspace(min(x), max(x), 50)
            xm, ym = float(np.median(x)), float(np.median(y))
            ax.plot(xs, intercept + slope * xs, "k-", lw=1.2, label="Theil-Sen")
            ax.fill_between(xs, ym + lo * (xs - xm), ym + hi * (xs - xm), color="0.6", alpha=0.3, label="95 % slope band")
        ax.set_xlabel("Rotor speed [1,000 rpm]")
        ax.set_ylabel(key, fontsize=7)
        ax.set_title(claim, fontsize=7)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=6)
    fig.savefig(path, dpi=110)
    plt.close(fig)


#: the screen's outputs behind paper B's speed claims, with the claimed sign of d output / d speed
SCREEN_CLAIMS = (
    ("Ball-ball collisions [-]", -1, "Conclusions: fewer collisions at higher speed"),
    ("Inner ring spin-up time [s]", -1, "Fig. 3: the inner ring settles faster at higher speed"),
    ("Settling time, ball 0 x [s]", -1, "Fig. 3: the ball settles faster in x"),
    ("Settling time, ball 0 y [s]", -1, "Fig. 3: the ball settles faster in y"),
    ("Largest collision force z [N]", +1, "Fig. 5: larger axial collision force at higher speed"),
    ("Wolf exponent, ball 0 z [bits/s]", +1, "Table 3: z rises with speed"),
)


def screen_rows(study: Path, speed_key: str = "operating.speed") -> tuple[list[tuple], list[str]]:
    """Paper B's speed claims under the Morris screen of the unstated values (studies/
    cageless_screen_unstated.toml): each trajectory's step in speed is the speed trend at one parameter
    set; a claim is reproduced by the sets whose step has its sign.  Returns (claim rows, markdown lines
    of the factors' mu* and sigma per output, from study.json's "Morris screening")."""
    table = json.loads((study / "study.json").read_text())
    screen = table["Morris screening"]
    factors = list(next(iter(screen["outputs"].values())))
    k = len(factors)
    with open(study / "study.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if len(rows) % (k + 1):
        raise ValueError(f"{study / 'study.csv'}: {len(rows)} rows is not a whole number of Morris trajectories of {k + 1}")
    out = []
    for key, sign, claim in SCREEN_CLAIMS:
        steps = []
        for t in range(len(rows) // (k + 1)):
            traj = rows[t * (k + 1):(t + 1) * (k + 1)]
            for a, b in zip(traj, traj[1:]):
                if a[speed_key + " [SI]"] == b[speed_key + " [SI]"]:
                    continue
                ya, yb = (usable_value(study, r, key) if r.get("status") == "ok" else None for r in (a, b))
                if ya is None or yb is None:
                    continue  # a failed run, a value not computed or not usable
                steps.append((yb - ya) / (float(b[speed_key + " [SI]"]) - float(a[speed_key + " [SI]"])))
        agree = sum(1 for e in steps if e * sign > 0)
        n = len(rows) // (k + 1)
        if not steps:
            verdict = f"not computed (no trajectory gives both values; {n} trajectories)"
        elif agree == len(steps):
            verdict = f"reproduced under every set ({agree} of {len(steps)})"
        elif agree:
            verdict = f"reproduced under some sets ({agree} of {len(steps)})"
        else:
            verdict = f"reproduced under none ({len(steps)} sets)"
        stats = screen["outputs"].get(key, {})
        ranked = sorted(((v["mu*"], name) for name, v in stats.items() if v.get("mu*") is not None), reverse=True)
        top = ", ".join(f"{name} {m:.3g}" for m, name in ranked[:3])
        out.append((f"{claim} (Morris screen)", "falls" if sign < 0 else "rises",
                    f"speed steps with the claim's sign {agree} of {len(steps)}; largest mu*: {top}", verdict))
    lines = ["| output | " + " | ".join(factors) + " |", "|---|" + "---|" * k]
    for key, stats in screen["outputs"].items():
        if all(v.get("mu*") is None for v in stats.values()):
            continue  # a text output (a verdict) or one no run computed
        cells = [(f"{v['mu*']:.3g} ({v['sigma']:.2g})" if v.get("mu*") is not None and v.get("sigma") is not None
                  else "n/a") for v in (stats[f] for f in factors)]
        lines.append(f"| {key} | " + " | ".join(cells) + " |")
    return out, lines


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--drop", type=Path, help="output folder of studies/cageless_drop_speeds.toml")
    p.add_argument("--slot", type=Path, help="output folder of studies/cageless_slot_effect.toml")
    p.add_argument("--fidelity", type=Path, help="output folder of studies/cageless_film_fidelity.toml")
    p.add_argument("--sensitivity", type=Path, help="output folder of studies/cageless_slot_sensitivity.toml")
    p.add_argument("--entrapped", type=Path, help="output folder of studies/cageless_entrapped_film.toml")
    p.add_argument("--screen", type=Path, help="output folder of studies/cageless_screen_unstated.toml (Morris)")
    p.add_argument("--fine", type=Path, help="output folder of studies/cageless_fine_speeds.toml (regressions)")
    p.add_argument("--fine-exponents", type=Path,
                   help="output folder of studies/cageless_fine_speeds_exponents.toml (Table 3 as regressions)")
    args = p.parse_args(argv)
    if args.slot and not args.drop:
        p.error("--slot needs --drop (the slot claim compares the two studies)")
    rows = rows_drop(args.drop) if args.drop else []
    if args.entrapped:
        rows += rows_entrapped(args.entrapped)
    if args.fine:
        rows += rows_fine(args.fine, args.fine / "fine_speeds.png")
        rows += rows_dimension(args.fine)
    if args.fine_exponents:
        rows += rows_fine(args.fine_exponents, args.fine_exponents / "fine_speeds_exponents.png", EXPONENT_CLAIMS)
    if args.slot:
        rows += rows_slot(args.drop, args.slot)
    if args.fidelity:
        rows += rows_fidelity(args.fidelity)
    if args.sensitivity:
        rows += rows_sensitivity(args.sensitivity)
    mu_table = []
    if args.screen:
        screen, mu_table = screen_rows(args.screen)
        rows += screen
    print("| claim | paper | lubedyn: median [min, max] over the members | verdict |")
    print("|---|---|---|---|")
    for r in rows:
        print("| " + " | ".join(str(x) for x in r) + " |")
    if mu_table:
        print("\nMorris screen: mu* (sigma) per output and factor, output units per full range of the factor\n")
        print("\n".join(mu_table))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
