"""``lubedyn study``: points, run folders, resume, backends, tables and one-line errors (coupling/scenes/study.py).

Every study here runs the cheap inclined slider (``--smoke``: 10 P2 cells, a linear film solved in
milliseconds), so the whole file stays fast; the worker-process and Dask runs pay only their start-up.
"""
from __future__ import annotations

import csv
import io
import json
import time
import logging
from pathlib import Path

import pytest

from lubedyn import cli
from lubedyn.scenes.study import StudyError, plan_study, points, read_study, slug

ROOT = Path(__file__).resolve().parents[1]
LOAD = "Load per unit width [N/m]"
FRICTION = "Friction lower x per unit width [N/m]"
SPEEDS = '"motion.velocity_lower" = ["2 m/s", "5 m/s", "8 m/s"]'


def study_file(tmp_path, axes=SPEEDS, study="", top="", name="study.toml", outputs=(LOAD, FRICTION)) -> Path:
    path = tmp_path / name
    listed = ", ".join(json.dumps(o) for o in outputs)
    path.write_text(f'base = "inclined_slider"\n{top}\n[axes]\n{axes}\n[study]\noutputs = [{listed}]\n{study}\n')
    return path


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def rows(out_dir: Path) -> list[dict]:
    return list(csv.DictReader(io.StringIO((out_dir / "study.csv").read_text())))


def assert_one_line_error(err: str, *fragments: str):
    lines = [line for line in err.splitlines() if not line.startswith("lubedyn: INFO:")]
    assert len(lines) == 1 and lines[0].startswith("lubedyn: error: "), err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in lines[0], f"{fragment!r} not in {lines[0]!r}"


# ---------------------------------------------------------------------------
# points and plans (nothing runs)


def test_grid_and_zip_point_counts_and_folder_names(tmp_path):
    axes = SPEEDS + '\n"mesh.nx" = [6, 8]'
    grid = read_study(study_file(tmp_path, axes))
    assert len(points(grid)) == 6
    assert points(grid)[:2] == [{"motion.velocity_lower": "2 m/s", "mesh.nx": 6},
                                {"motion.velocity_lower": "2 m/s", "mesh.nx": 8}]  # last axis fastest
    zipped = read_study(study_file(tmp_path, SPEEDS + '\n"mesh.nx" = [6, 8, 12]', 'combine = "zip"'))
    assert [tuple(p.values()) for p in points(zipped)] == [("2 m/s", 6), ("5 m/s", 8), ("8 m/s", 12)]
    # zipped axes may repeat a value (one assumption changed per pair of points), not a whole point
    zipped = read_study(study_file(tmp_path, '"motion.velocity_lower" = ["2 m/s", "2 m/s"]\n"mesh.nx" = [6, 8]',
                                   'combine = "zip"'))
    assert [tuple(p.values()) for p in points(zipped)] == [("2 m/s", 6), ("2 m/s", 8)]
    plan = plan_study(read_study(study_file(tmp_path, axes, "members = 2\nmember_key = 'mesh.refinements'")),
                      tmp_path / "study.toml", smoke=True)
    assert len(plan.runs) == 12
    assert plan.runs[5].folder == "runs/motion.velocity_lower=5m_s,mesh.nx=6/m1"
    assert plan.runs[5].overrides[-2:] == ["mesh.nx=6", "mesh.refinements=1"]
    assert plan.si[2] == {"motion.velocity_lower": 5.0, "mesh.nx": 6}
    assert slug({"operating.speed": "15000 rpm"}) == "operating.speed=15000rpm"
    assert len(slug({"a": "x" * 500})) <= 120


@pytest.mark.parametrize("axes, study, fragments", [
    (SPEEDS + '\n"mesh.nx" = [6, 8]', 'combine = "zip"', ("study.combine = 'zip' needs axes of one length",
                                                          "'motion.velocity_lower': 3", "'mesh.nx': 2")),
    (SPEEDS, "members = 0", ("study.members = 0 must be >= 1",)),
    (SPEEDS, "memebrs = 2", ("study.memebrs: unknown key in [study]; did you mean 'members'",)),
    ('"mesh.nx" = []', "", ("axes.'mesh.nx' = [] has no values",)),
    ('"mesh.nx" = [6, 6]', "", ("axes.'mesh.nx'", "lists '6' twice")),
    ('"mesh.nx" = [6, 8, 6]\n"mesh.ny" = [4, 4, 4]', 'combine = "zip"',
     ("axes point 3 repeats point 1 (mesh.nx = '6', mesh.ny = '4')", "must differ in at least one axis")),
    ('"mesh.nx" = 6', "", ("axes.mesh.nx = 6 must be a list",)),
    ("", "", ("axes needs at least one axis",)),
    (SPEEDS, 'set = ["mesh.nx"]', ("study.set[0] = 'mesh.nx' must be KEY=VALUE",)),
    (SPEEDS, 'combine = "zipp"', ("study.combine = 'zipp' is not allowed; choose one of 'grid', 'zip'",)),
    (SPEEDS, "members = 2\nmember_key = 'motion.velocity_lower'", ("study.member_key", "is also an axis")),
    (SPEEDS, '[paper]\n"Load per unit widht [N/m]" = { axis = "motion.velocity_lower", at = ["2 m/s"], values = [1] }',
     ("paper.'Load per unit widht [N/m]' is not one of study.outputs", "did you mean 'Load per unit width [N/m]'")),
    (SPEEDS, '[paper]\n"Load per unit width [N/m]" = { axis = "mesh.nx", at = [6], values = [1] }',
     ("paper.'Load per unit width [N/m]'.axis = 'mesh.nx' must be the first axis 'motion.velocity_lower'",)),
    (SPEEDS, '[paper]\n"Load per unit width [N/m]" = { axis = "motion.velocity_lower", at = ["2 m/s"], values = [1, 2] }',
     ("paper.Load per unit width [N/m].values = [1.0, 2.0] has 2 entries and at has 1",)),
])
def test_a_bad_study_file_is_one_line_exit_2(tmp_path, capsys, axes, study, fragments):
    code, out, err = run(capsys, "study", study_file(tmp_path, axes, study), "--out", tmp_path / "o")
    assert code == 2
    assert_one_line_error(err, *fragments)
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("axes, study, fragments", [
    # an unknown axis key: named with its value, and the case's did-you-mean of `lubedyn run --set`
    ('"gap.h_inn" = ["20 um", "30 um"]', "", ("axes.'gap.h_inn' = '20 um': gap.h_inn: unknown key in [gap]",
                                               "did you mean 'h_in'?")),
    ('"gap.h_in" = ["20 um", "30 Pa"]', "", ("axes.'gap.h_in' = '30 Pa'", "units of pressure, expected length")),
    (SPEEDS, "set = [\"mesh.nx=5\", \"mesh.elemnt='P1'\"]", ("study.set[1] = \"mesh.elemnt='P1'\"",
                                                           "did you mean 'element'?")),
    # the film case has no initial.seed (the dynamics scene's member key)
    (SPEEDS, "members = 2", ("study.member_key = 'initial.seed' (member 0): initial: unknown key at the top level",)),
    # a bad base case
    (SPEEDS, "", ("base = 'inclined_slidr'", "did you mean 'inclined_slider'?")),
    (SPEEDS, '[paper]\n"Load per unit width [N/m]" = { axis = "motion.velocity_lower", at = ["2 m"], values = [1] }',
     ("paper.'Load per unit width [N/m]'.at[0] = '2 m'", "has units of length, expected velocity")),
])
def test_every_run_is_validated_before_anything_runs(tmp_path, capsys, axes, study, fragments):
    path = study_file(tmp_path, axes, study)
    if "inclined_slidr" in fragments[0]:
        path.write_text(path.read_text().replace('"inclined_slider"', '"inclined_slidr"'))
    code, out, err = run(capsys, "study", path, "--smoke", "--out", tmp_path / "o")
    assert code == 2
    assert_one_line_error(err, *fragments)
    assert not (tmp_path / "o" / "runs").exists()


# ---------------------------------------------------------------------------
# runs and tables


def test_study_rows_scale_with_speed_and_equal_a_separate_run(tmp_path, capsys, caplog):
    """The slider's film is linear in U: load and friction per speed are constant (to round-off); the
    5 m/s row is the summary of `lubedyn run inclined_slider --set motion.velocity_lower=...` bit for bit."""
    out = tmp_path / "study"
    with caplog.at_level(logging.WARNING):
        code, stdout, err = run(capsys, "study", study_file(tmp_path), "--smoke", "--workers", 1, "--out", out)
    assert code == 0, err
    assert "3 runs (0 reused, 3 run, 0 failed)" in stdout
    assert "run 3/3 done (motion.velocity_lower=8 m/s)" in err
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]  # no "kept files: runs" warning
    table = rows(out)
    assert [r["motion.velocity_lower"] for r in table] == ["2 m/s", "5 m/s", "8 m/s"]
    assert [float(r["motion.velocity_lower [SI]"]) for r in table] == [2.0, 5.0, 8.0]
    assert {r["status"] for r in table} == {"ok"} and {r["member"] for r in table} == {"0"}
    per_speed = [float(r[LOAD]) / float(r["motion.velocity_lower [SI]"]) for r in table]
    assert max(per_speed) == pytest.approx(min(per_speed), rel=1e-12)
    assert per_speed[0] * 5.0 == pytest.approx(63.55e3, rel=1e-3)  # the closed form of cases/inclined_slider.toml
    friction = [float(r[FRICTION]) / float(r["motion.velocity_lower [SI]"]) for r in table]
    assert max(friction) == pytest.approx(min(friction), rel=1e-12)

    single = tmp_path / "single"
    assert run(capsys, "run", "inclined_slider", "--smoke", "--set", 'motion.velocity_lower="5 m/s"',
               "--out", single)[0] == 0
    summary = json.loads((single / "summary.json").read_text())
    assert table[1][LOAD] == repr(summary[LOAD])
    folder = out / table[1]["run folder"]
    assert sorted(p.name for p in folder.iterdir()) == [".study-run.json", "case.resolved.toml", "film.vtu",
                                                        "manifest.json", "pressure.png", "summary.json"]
    assert json.loads((folder / "summary.json").read_text())[LOAD] == summary[LOAD]
    doc = json.loads((out / "study.json").read_text())
    assert doc["runs"]["total"] == 3 and doc["points"][1]["outputs"][LOAD]["median"] == summary[LOAD]
    assert (out / "study.png").stat().st_size > 0
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "runs", "study.csv", "study.json", "study.nc",
                                                  "study.png"]


def test_resume_reruns_only_what_is_missing_or_half_written(tmp_path, capsys):
    path = study_file(tmp_path, study="skip_outputs = true")
    out = tmp_path / "study"
    cpu0 = time.process_time()
    assert run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)[0] == 0
    cpu_study = time.process_time() - cpu0
    first = (out / "study.csv").read_text()
    # the runs' CPU time (serial: this process) is positive and within the CPU this process spent on the study
    info = json.loads((out / "study.json").read_text())["runs"]
    assert 0.0 < info["CPU time of the runs [s]"] <= cpu_study
    assert info["CPU time of the runs, runs counted"] == "3 of 3 finished runs"
    folders = [out / r["run folder"] for r in rows(out)]
    assert sorted(p.name for p in folders[0].iterdir()) == [".study-run.json", "case.resolved.toml",
                                                            "manifest.json", "summary.json"]
    stamps = {f: (f / "summary.json").stat().st_mtime_ns for f in folders}
    for f in folders[1].iterdir():  # a killed study: one run folder gone
        f.unlink()
    folders[1].rmdir()
    (folders[2] / "summary.json").write_text('{"Load per unit')  # and one half written
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert code == 0, err
    assert "3 runs (1 reused, 2 run, 0 failed)" in stdout
    assert "1 reused" in err  # the log says so too
    assert (folders[0] / "summary.json").stat().st_mtime_ns == stamps[folders[0]]
    assert (out / "study.csv").read_text() == first
    assert json.loads((out / "study.json").read_text())["runs"]["CPU time of the runs, runs counted"] == \
        "3 of 3 finished runs"  # the reused run's from its marker
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert "3 runs (3 reused, 0 run, 0 failed)" in stdout
    # a changed case (the resolved case differs) reruns everything
    path.write_text(path.read_text().replace("skip_outputs = true", 'skip_outputs = true\nset = ["mesh.element=\'P1\'"]'))
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert "3 runs (0 reused, 3 run, 0 failed)" in stdout
    assert (out / "study.csv").read_text() != first
    # with --smoke, a study.set entry the case's [smoke] table also sets gives way to the smoke value
    path.write_text(path.read_text().replace("set = [\"mesh.element='P1'\"]", 'set = ["mesh.nx=400"]'))
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert "3 runs (0 reused, 3 run, 0 failed)" in stdout and "study.set entries left out: mesh.nx=400" in err
    assert (out / "study.csv").read_text() == first


def test_members_are_rows_with_the_member_index_on_the_member_key(tmp_path, capsys):
    """The film case has no seed; mesh.refinements (used by disk meshes only) takes the member index, so
    the members of a point agree and their spread is zero.  (The dynamics scene's members will use
    initial.seed, the default member_key.)"""
    path = study_file(tmp_path, '"motion.velocity_lower" = ["2 m/s", "5 m/s"]',
                      "members = 3\nmember_key = 'mesh.refinements'\nskip_outputs = true")
    out = tmp_path / "study"
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert code == 0, err
    table = rows(out)
    assert [(r["motion.velocity_lower"], r["member"]) for r in table] == [
        ("2 m/s", "0"), ("2 m/s", "1"), ("2 m/s", "2"), ("5 m/s", "0"), ("5 m/s", "1"), ("5 m/s", "2")]
    assert table[4]["run folder"] == "runs/motion.velocity_lower=5m_s/m1"
    assert "refinements = 1" in (out / table[4]["run folder"] / "case.resolved.toml").read_text()
    assert "run 5/6 done" in err and ", member " in err
    stats = json.loads((out / "study.json").read_text())["points"][1]["outputs"][LOAD]
    assert stats["spread"] == 0.0 and stats["std"] == 0.0 and len(stats["values"]) == 3
    assert stats["min"] == stats["median"] == stats["max"] == float(table[3][LOAD])


def test_an_unknown_output_is_one_line_after_the_first_run(tmp_path, capsys):
    path = study_file(tmp_path, outputs=("Load per unit widht [N/m]",), study="skip_outputs = true")
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", tmp_path / "o")
    assert code == 2
    assert_one_line_error(err, "study.outputs: 'Load per unit widht [N/m]' is not a key of the runs' summary.json",
                          "did you mean 'Load per unit width [N/m]'")
    assert not (tmp_path / "o" / "study.csv").exists()


def test_a_failed_run_is_recorded_and_the_study_goes_on(tmp_path, capsys):
    """A run refused by its size check (limits.memory = 1 KiB) fails; the other runs, the table and
    the figure are still written, and the exit code is 1."""
    path = study_file(tmp_path, '"limits.memory" = ["40 GiB", "1 KiB"]', "skip_outputs = true")
    out = tmp_path / "study"
    code, stdout, err = run(capsys, "study", path, "--smoke", "--workers", 1, "--out", out)
    assert code == 1
    assert "2 runs (0 reused, 2 run, 1 failed)" in stdout
    assert "lubedyn: error: 1 of 2 runs failed" in err and "Traceback" not in err
    ok, failed = rows(out)
    assert ok["status"] == "ok" and float(ok[LOAD]) > 0 and ok["error"] == ""
    assert failed["status"] == "failed" and failed[LOAD] == ""
    assert "more than the limit of 1 KiB (limits.memory)" in failed["error"]
    assert json.loads((out / "study.json").read_text())["runs"]["failed"] == 1
    assert (out / "study.png").is_file()


def test_the_example_study_runs_and_writes_only_below_out(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, stdout, err = run(capsys, "study", ROOT / "studies" / "slider_speeds.toml", "--smoke", "--workers", 1)
    assert code == 0, err
    assert [p.name for p in tmp_path.iterdir()] == ["runs"]
    out = tmp_path / "runs" / "slider_speeds"  # the default --out
    table = rows(out)
    paper = read_study(ROOT / "studies" / "slider_speeds.toml").paper[LOAD]
    assert [float(r[LOAD]) for r in table] == pytest.approx(paper.values, rel=1e-3)


# ---------------------------------------------------------------------------
# backends (last: the Dask cluster's threads stay behind in this process)


def test_one_worker_two_workers_and_dask_give_identical_tables(tmp_path, capsys):
    from distributed import LocalCluster

    path = study_file(tmp_path, SPEEDS + '\n"gap.h_out" = ["8 um", "10 um"]', "skip_outputs = true")
    tables = {}
    for name, extra in (("serial", ["--workers", 1]), ("local", ["--workers", 2])):
        code, stdout, err = run(capsys, "study", path, "--smoke", "--out", tmp_path / name, *extra)
        assert code == 0, err
        tables[name] = (tmp_path / name / "study.csv").read_bytes()
        assert ("serial (this process)" if name == "serial" else "local processes (2)") in stdout
    with LocalCluster(n_workers=1, processes=False, threads_per_worker=1, dashboard_address=None) as cluster:
        code, stdout, err = run(capsys, "study", path, "--smoke", "--out", tmp_path / "dask",
                                "--scheduler", cluster.scheduler_address)
    assert code == 0, err
    assert "dask (" in stdout
    tables["dask"] = (tmp_path / "dask" / "study.csv").read_bytes()
    assert len(rows(tmp_path / "dask")) == 6
    assert tables["serial"] == tables["local"] == tables["dask"]


def test_a_bad_scheduler_address_is_one_line(tmp_path, capsys):
    """(An address without a port fails at once; one that nobody answers fails the same way after
    the 10 s connect timeout.)"""
    code, stdout, err = run(capsys, "study", study_file(tmp_path), "--smoke", "--out", tmp_path / "o",
                            "--scheduler", "tcp://127.0.0.1")
    assert code == 2
    assert_one_line_error(err, "--scheduler = 'tcp://127.0.0.1': cannot connect (missing port number")


def test_read_study_names_a_missing_file_with_did_you_mean(tmp_path):
    study_file(tmp_path, name="speeds.toml")
    with pytest.raises(StudyError, match=r"study file .*speeds\.tml' not found; did you mean .*speeds\.toml"):
        read_study(tmp_path / "speeds.tml")
