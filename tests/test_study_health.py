"""Study tables carry each run's health (coupling/scenes/study.py): ``ok``, ``ok-with-warnings`` or ``failed`` per
row of study.csv and study.json with the warnings' texts, a count per point, marks on study.png, and the
warnings logged again when a resumed study reuses the runs.

One zipped study of the cheap inclined slider (``--smoke``) with three members of health: a clean run, a
run whose minimum film (10 um) is below ``validity.min_film = 1 mm`` (the film scene's validity warning),
and a run refused at run time by its size check (``limits.memory = 1 KiB``).
"""
from __future__ import annotations

import csv
import io
import json
import logging

import pytest

from lubedyn import cli
from lubedyn.scenes.study import aggregates, figure, plan_study, read_study, status, warnings_cell

LOAD = "Load per unit width [N/m]"
AXES = """"motion.velocity_lower" = ["2 m/s", "5 m/s", "8 m/s"]
"validity.min_film" = ["0.1 um", "1 mm", "0.1 um"]
"limits.memory" = ["40 GiB", "40 GiB", "1 KiB"]"""
WARNING = "Minimum film thickness 1e-05 m is below validity.min_film = 0.001 m"


def study_file(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text(f'base = "inclined_slider"\n[axes]\n{AXES}\n[study]\ncombine = "zip"\nskip_outputs = true\n'
                    f'outputs = ["{LOAD}"]\n')
    return path


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def warned_records(caplog):
    return [r.getMessage() for r in caplog.records
            if r.name == "lubedyn.scenes.study" and r.levelno == logging.WARNING and "warning" in r.getMessage()]


def test_study_tables_carry_ok_warned_and_failed_and_a_resume_logs_the_warnings_again(tmp_path, capsys, caplog):
    path, out = study_file(tmp_path), tmp_path / "study"
    with caplog.at_level(logging.INFO):
        code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert code == 1, err  # the failed run: exit 1; the warned one alone would not change it
    assert "3 runs (0 reused, 3 run, 1 failed), 1 with warnings" in stdout
    folder = "runs/motion.velocity_lower=2m_s,validity.min_film=0.1um,limits.memory=40GiB/m0"
    warned = "runs/motion.velocity_lower=5m_s,validity.min_film=1mm,limits.memory=40GiB/m0"
    fresh = warned_records(caplog)
    assert len(fresh) == 1 and fresh[0].startswith("run 2/3 done with warnings (motion.velocity_lower=5 m/s")
    assert f"{warned}: 1 warning: {WARNING}" in fresh[0]

    clean, warn, failed = list(csv.DictReader(io.StringIO((out / "study.csv").read_text())))
    assert (clean["run folder"], clean["status"], clean["warnings"], clean["error"]) == (folder, "ok", "", "")
    assert warn["status"] == "ok-with-warnings" and warn["error"] == ""
    assert warn["warnings"].startswith(f"1: {WARNING}") and " | " not in warn["warnings"]
    assert float(warn[LOAD]) == pytest.approx(float(clean[LOAD]) * 2.5, rel=1e-12)  # its result is kept, flagged (the film is linear in U)
    assert failed["status"] == "failed" and failed["warnings"] == "" and failed[LOAD] == ""
    assert "(limits.memory)" in failed["error"]

    doc = json.loads((out / "study.json").read_text())
    assert [r["status"] for r in doc["run list"]] == ["ok", "ok-with-warnings", "failed"]
    assert doc["run list"][1]["warnings"][0].startswith(WARNING) and doc["run list"][0]["warnings"] == []
    assert [r["run folder"] for r in doc["warned runs"]] == [warned]
    assert doc["runs"]["ok with warnings"] == 1 and doc["runs"]["failed"] == 1
    assert [(p["ok with warnings"], p["failed"]) for p in doc["points"]] == [(0, 0), (1, 0), (0, 1)]
    assert doc["points"][1]["outputs"][LOAD]["median"] == float(warn[LOAD])
    first_csv = (out / "study.csv").read_text()

    caplog.clear()
    with caplog.at_level(logging.INFO):
        code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert code == 1, err
    assert "3 runs (2 reused, 1 run, 1 failed), 1 with warnings" in stdout
    again = warned_records(caplog)
    assert again == [f"reused run {warned}: 1 warning: " + fresh[0].split(": 1 warning: ", 1)[1]]
    assert (out / "study.csv").read_text() == first_csv


def test_status_cells_and_study_png_marks_warned_and_failed_points(tmp_path):
    """The per-run helpers, and the figure of a planned study (nothing runs: synthetic summaries): a
    warned point gets the orange ring and a point with a failed member the red cross, each with one
    legend entry, and a point with no finished member is absent."""
    import matplotlib.pyplot as plt

    assert status(("ok", {LOAD: 1.0})) == "ok"
    assert status(("ok", {LOAD: 1.0, "Warnings": ["a", "b"]})) == "ok-with-warnings"
    assert status(("failed", "boom")) == "failed"
    assert warnings_cell(["a", "b"]) == "2: a | b" and warnings_cell([]) == ""

    path = study_file(tmp_path)
    path.write_text(path.read_text().replace("skip_outputs = true", "members = 2\nmember_key = 'mesh.refinements'"))
    study = read_study(path)
    plan = plan_study(study, path, smoke=True)
    results = [("ok", {LOAD: 1.0}), ("ok", {LOAD: 1.0}),  # point 0: clean
               ("ok", {LOAD: 2.0, "Warnings": ["low"]}), ("failed", "boom"),  # point 1: warned and failed
               ("failed", "boom"), ("failed", "boom")]  # point 2: nothing finished
    stats = aggregates(study, plan, results)
    assert [(p["ok with warnings"], p["failed"]) for p in stats] == [(0, 0), (1, 1), (0, 2)]
    fig = figure(study, plan, stats)
    try:
        ax = fig.axes[0]
        marks = {line.get_label(): line.get_xydata().tolist() for line in ax.get_lines()}
        assert marks["with warnings (study.csv)"] == [[5.0, 2.0]]
        assert marks["a member failed (study.csv)"] == [[5.0, 2.0]]
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["with warnings (study.csv)",
                                                                      "a member failed (study.csv)"]
    finally:
        plt.close(fig)
