"""The shipped paper B study (studies/cageless_drop_speeds.toml) at smoke size: every one of its 32 runs
(4 speeds x 8 seeded members) runs the FEM film map with no query outside its axes, the members of a
point differ (the seeds act), a member is reproduced bit for bit by a separate `lubedyn run` with the
same seed, and the table holds the paper's Table 3 values for the overlay."""
from __future__ import annotations

import csv
import io
import json
from pathlib import Path

from lubedyn import cli
from lubedyn.config import CASES_DIR

STUDY = Path(__file__).resolve().parents[1] / "studies" / "cageless_drop_speeds.toml"


def test_paper_b_study_at_smoke_size(tmp_path, capsys):
    out = tmp_path / "study"
    code = cli.main(["study", str(STUDY), "--smoke", "--workers", "2", "--out", str(out)])
    _, err = capsys.readouterr()
    assert code == 0, err
    rows = list(csv.DictReader(io.StringIO((out / "study.csv").read_text())))
    assert len(rows) == 32 and {r["status"] for r in rows} == {"ok"}
    assert {r["Film map queries outside axes [-]"] for r in rows} == {"0"}
    for speed in ("10000 rpm", "25000 rpm"):
        forces = {r["Largest collision normal force [N]"] for r in rows if r["operating.speed"] == speed}
        assert len(forces) >= 4, forces  # 8 seeds, at least 4 different starts
    # member 3 of 15,000 rpm again, by hand: the same numbers
    row = next(r for r in rows if r["operating.speed"] == "15000 rpm" and r["member"] == "3")
    again = tmp_path / "again"
    code = cli.main(["run", str(CASES_DIR / "cageless_6206_10krpm.toml"), "--smoke",
                     "--set", "output.write=[]", "--set", "initial.jitter='0.5 deg'", "--set", "initial.kick='1 mm/s'",
                     "--set", "operating.speed='15000 rpm'", "--set", "initial.seed=3", "--out", str(again)])
    assert code == 0
    mine = json.loads((out / row["run folder"] / "summary.json").read_text())
    theirs = json.loads((again / "summary.json").read_text())
    for key in ("Largest collision normal force [N]", "Inner ring speed at end [rpm]", "Accepted steps [-]"):
        assert mine[key] == theirs[key], key
    table = json.loads((out / "study.json").read_text())
    assert table["study"]["paper"]["Wolf exponent, ball 0 z [bits/s]"]["values"][0] == 7.6814


def test_slot_sensitivity_study_plans_and_report_groups_its_pairs(tmp_path):
    """studies/cageless_slot_sensitivity.toml validates (every one of its 88 runs' cases, with the
    changed assumption of each pair), and the report pairs each variant's slotted point with the
    unslotted point of the same assumptions: a synthetic table where the slot halves the collisions
    under one assumption only gives exactly that verdict."""
    import importlib.util

    from lubedyn.scenes.study import plan_study, read_study

    path = STUDY.parent / "cageless_slot_sensitivity.toml"
    plan = plan_study(read_study(path), path, smoke=True)
    assert len(plan.runs) == 88
    assert sum('films.friction_law="paper"' in r.overrides for r in plan.runs) == 16
    spec = importlib.util.spec_from_file_location("paper_b_report", STUDY.parents[1] / "benchmarks" / "paper_b_report.py")
    report = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(report)
    cols = ["slots.azimuths", "films.friction_law"]
    lines = [",".join(c + s for c in cols for s in ("", " [SI]")) + ",member,Ball-ball collisions [-],status"]
    for law, with_slot, without in (("exponential_share", 100, 50), ("paper", 30, 60)):
        for m in range(3):
            lines.append(f'"[""270 deg""]","[4.71]",{law},{law},{m},{with_slot + m},ok')
            lines.append(f"[],[],{law},{law},{m},{without + m},ok")
    (tmp_path / "study.csv").write_text("\n".join(lines) + "\n")
    rows = {r[0]: r[3] for r in report.rows_sensitivity(tmp_path)}
    assert rows == {"Sensitivity at 10000 rpm, baseline: slot at 270 deg against none": "not reproduced (higher)",
                    "Sensitivity at 10000 rpm, friction law of eqs. 17-21: slot at 270 deg against none": "reproduced"}


def test_fine_speed_regressions_on_a_synthetic_study(tmp_path):
    """The regression verdicts of benchmarks/paper_b_report.py --fine on a synthetic 11-speed study whose
    answers are known: collisions fall 20 per 1,000 rpm under +-30 of member scatter ("reproduced", the
    band around -20), the spin-up time rises ("not reproduced (rises)"), the axial force is flat noise
    ("not resolvable"), and an exponent resolved in 2 runs of 44 is "not resolvable" whatever its values;
    the study file itself plans 11 speeds x 4 members (<= 1,500 rpm apart, 10,000-25,000 rpm)."""
    import importlib.util
    import math

    import numpy as np

    from lubedyn.scenes.study import plan_study, read_study

    path = STUDY.parent / "cageless_fine_speeds.toml"
    plan = plan_study(read_study(path), path, smoke=True)
    assert len(plan.runs) == 44
    spec = importlib.util.spec_from_file_location("paper_b_report", STUDY.parents[1] / "benchmarks" / "paper_b_report.py")
    report = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(report)
    rng = np.random.default_rng(7)
    lines = ["operating.speed [SI],member,run folder,status"]
    for i, krpm in enumerate(np.arange(10.0, 25.01, 1.5)):
        for m in range(4):
            folder = tmp_path / "runs" / f"s{i}" / f"m{m}"
            folder.mkdir(parents=True)
            resolved = i == 0 and m < 2
            summary = {"Ball-ball collisions [-]": 1500.0 - 20.0 * krpm + rng.uniform(-30, 30),
                       "Inner ring spin-up time [s]": 7e-4 * krpm,
                       "Largest collision force z [N]": 3.0 + rng.uniform(-1, 1),
                       "Wolf exponent, ball 0 z [bits/s]": 50.0 * krpm,
                       "Wolf exponent, ball 0 z verdict": "positive" if resolved else "not distinguishable from its surrogates",
                       # D2: x dips near 15 and 20 krpm, y does not, z rises 0.02 per 1,000 rpm and lies above both
                       "Correlation dimension, ball 0 x phase portrait [-]":
                           1.3 - (0.2 if min(abs(krpm - 15), abs(krpm - 20)) <= 1 else 0.0) + rng.uniform(-0.05, 0.05),
                       "Correlation dimension, ball 0 y phase portrait [-]": 1.3 + rng.uniform(-0.1, 0.1),
                       "Correlation dimension, ball 0 z phase portrait [-]": 1.5 + 0.02 * krpm + rng.uniform(-0.05, 0.05),
                       "Correlation dimension, ball 0 z phase portrait verdict": "non-integer (fractal)"}
            if i == 10 and m == 3:  # no scaling range: its (absurd) value must be left out of every claim
                summary["Correlation dimension, ball 0 z phase portrait [-]"] = 0.1
                summary["Correlation dimension, ball 0 z phase portrait verdict"] = "no scaling range"
            (folder / "summary.json").write_text(json.dumps(summary))
            lines.append(f"{krpm * 1e3 * 2 * math.pi / 60},{m},runs/s{i}/m{m},ok")
    (tmp_path / "study.csv").write_text("\n".join(lines) + "\n")
    rows = {r[0].split(" (regression")[0]: r for r in report.rows_fine(tmp_path, tmp_path / "fine.png")}
    col = rows["Conclusions: fewer collisions at higher speed"]
    assert col[3] == "reproduced"
    slope, lo, hi = (float(v) for v in col[2].replace("slope ", "").translate(str.maketrans("", "", "[],")).split()[:3])
    assert lo < -20.0 < hi and abs(slope + 20.0) < 3.0
    assert rows["Fig. 3: the inner ring settles faster at higher speed"][3] == "not reproduced (rises)"
    assert rows["Fig. 5: largest axial collision force rises, 10,000-20,000 rpm"][3] == "not resolvable (band holds 0)"
    table3 = {r[0].split(" (regression")[0]: r for r in report.rows_fine(tmp_path, claims=report.EXPONENT_CLAIMS)}
    assert table3["Table 3: z rises with speed (7.68 -> 8.63)"][3] == "not resolvable (2 of 44 runs resolved)"
    assert table3["Table 3: x falls with speed (4.59 -> 3.92)"][3] == "not computed (no run gives a value)"
    assert rows["Fig. 8: z is less fractal the slower the rotor turns (D2)"][3] == "reproduced"
    assert "43 of 44 runs" in rows["Fig. 8: z is less fractal the slower the rotor turns (D2)"][2]
    assert (tmp_path / "fine.png").stat().st_size > 10_000
    dims = {r[0]: r for r in report.rows_dimension(tmp_path)}
    z = dims["Fig. 8: z is more chaotic than x and y (D2 per run)"]
    assert z[3] == "reproduced" and "43 of 43 runs" in z[2]
    assert dims["Fig. 6: x is less fractal at 15,000 and 20,000 rpm than at 10,000 and 25,000 rpm (D2)"][3] == "reproduced"
    assert dims["Fig. 7: y is less fractal at 15,000 and 20,000 rpm than at 10,000 and 25,000 rpm (D2)"][3].startswith(
        "not resolvable")
