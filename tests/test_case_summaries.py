"""benchmarks/case_summaries.py, the before/after tool of refactors: its comparison is
bit-exact by default, names the key that changed and honours an explicit tolerance; a recording of
one cheap case is identical across two runs (a few seconds; no time is asserted)."""
import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

# loaded from its file, not by putting benchmarks/ on sys.path: its modules (dynamics.py, maps.py ...) would
# be importable by their short names for every test run later in the same worker
_spec = importlib.util.spec_from_file_location(
    "case_summaries", Path(__file__).resolve().parents[1] / "benchmarks" / "case_summaries.py")
case_summaries = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(case_summaries)


def _recording(load=20626.73843510263, series=None):
    series = np.linspace(0.0, 1.0, 5) if series is None else series
    return {"format": case_summaries.FORMAT, "version": 1, "resolution": "smoke",
            "cases": {"rayleigh_step": {"exit code": 0, "summary": {"Load per unit width [N/m]": load,
                                                                     "Element": "P1"},
                                        "arrays": {"film.vtu:point data Pressure [Pa]":
                                                   case_summaries.array_record(series)},
                                        "metadata": {}, "files": {}}}}


def _compare(tmp_path, a, b, capsys, **kw):
    pa, pb = tmp_path / "a.json", tmp_path / "b.json"
    pa.write_text(json.dumps(a))
    pb.write_text(json.dumps(b))
    code = case_summaries.compare(pa, pb, **kw)
    return code, capsys.readouterr().out


def test_identical_recordings_compare_equal(tmp_path, capsys):
    code, out = _compare(tmp_path, _recording(), _recording(), capsys)
    assert code == 0 and "identical: 1 cases" in out


def test_a_changed_float_is_named_with_its_relative_difference(tmp_path, capsys):
    """One unit in the last place of the load (2^-52 relative to 1.26, about 1.7e-16 here) is a
    difference at the default rtol 0 and passes at rtol 1e-15."""
    load = 20626.73843510263
    bumped = float(np.nextafter(load, np.inf))
    code, out = _compare(tmp_path, _recording(), _recording(load=bumped), capsys)
    assert code == 1
    line = next(s for s in out.splitlines() if "Load per unit width [N/m]" in s)
    assert line.startswith("rayleigh_step / summary / Load per unit width [N/m]: ")
    rel = float(line.split("rel ")[1])
    assert rel == pytest.approx((bumped - load) / bumped, rel=1e-3)
    assert "1 differences over 1 cases" in out
    code, out = _compare(tmp_path, _recording(), _recording(load=bumped), capsys, rtol=1e-15)
    assert code == 0 and "equal within rtol 1e-15" in out
    code, out = _compare(tmp_path, _recording(), _recording(load=load * (1 + 1e-9)), capsys, rtol=1e-10)
    assert code == 1


def test_a_changed_array_element_is_found_by_its_digest(tmp_path, capsys):
    """An array whose last bit changed in one element keeps its statistics but not its sha256: a
    difference at rtol 0, a note ("bits differ") within rtol 1e-12; a change of 1e-6 in its
    maximum is a difference at rtol 1e-12 (the max is named)."""
    series = np.linspace(0.0, 1.0, 5)
    nudged = series.copy()
    nudged[2] = np.nextafter(nudged[2], 1.0)
    code, out = _compare(tmp_path, _recording(series=series), _recording(series=nudged), capsys)
    assert code == 1 and "arrays / film.vtu:point data Pressure [Pa]" in out
    code, out = _compare(tmp_path, _recording(series=series), _recording(series=nudged), capsys, rtol=1e-12)
    assert code == 0 and "bits differ, statistics within rtol 1e-12" in out
    grown = series.copy()
    grown[-1] += 1e-6
    code, out = _compare(tmp_path, _recording(series=series), _recording(series=grown), capsys, rtol=1e-12)
    assert code == 1 and "Pressure [Pa] / max: 1.0 -> 1.000001" in out


def test_missing_case_and_ignore(tmp_path, capsys):
    a, b = _recording(), _recording(load=1.0)
    b["cases"]["journal_finite"] = b["cases"]["rayleigh_step"]
    code, out = _compare(tmp_path, a, b, capsys)
    assert code == 1 and "journal_finite: '(missing)' -> '(recorded)'" in out
    del b["cases"]["journal_finite"]
    code, out = _compare(tmp_path, a, b, capsys, ignore=("Load per unit width",))
    assert code == 0 and "ignoring keys containing: 'Load per unit width'" in out


def test_recording_one_case_twice_is_identical(tmp_path, capsys):
    """rayleigh_step --smoke through the CLI, twice: every kept value is bit-identical, the timings
    are left out, and the recorded load is Rayleigh's closed form (P1 is exact on this film)."""
    a = case_summaries.record(tmp_path / "a.json", smoke=True, only=["rayleigh_step"])
    b = case_summaries.record(tmp_path / "b.json", smoke=True, only=["rayleigh_step"])
    capsys.readouterr()
    rec = a["cases"]["rayleigh_step"]
    assert rec["exit code"] == 0
    assert not {"Run time [s]", "Solve time [s]", "Build time [s]"} & set(rec["summary"])
    assert rec["summary"]["Degrees of freedom [-]"] == 13
    # flow continuity at the step (cases/rayleigh_step.toml): p_step = 6 eta U (h1 - h2) B1 B2 /
    # (h1^3 B2 + h2^3 B1), W = p_step L / 2 = 20626.738 N/m; P1 with the step on a node is exact
    eta, u, h1, h2, b1, length = 0.02, 5.0, 18.66e-6, 10e-6, 7.1822e-3, 10e-3
    b2 = length - b1
    p_step = 6 * eta * u * (h1 - h2) * b1 * b2 / (h1**3 * b2 + h2**3 * b1)
    assert rec["summary"]["Load per unit width [N/m]"] == pytest.approx(p_step * length / 2, rel=1e-12)
    pressure = rec["arrays"]["film.vtu:point data Pressure [Pa]"]
    assert pressure["shape"] == [13] and pressure["max"] == rec["summary"]["Maximum pressure [Pa]"]
    assert case_summaries.compare(tmp_path / "a.json", tmp_path / "b.json") == 0
    assert b["cases"] == a["cases"]


def test_the_temporary_run_folder_named_in_a_text_is_not_a_difference(tmp_path, capsys):
    """A warning naming the map file a case wrote into its temporary folder
    (``tempfile.TemporaryDirectory(prefix="case-summaries-<case>-")``: 8 random characters) compares
    equal across two runs; any other change of the text is still a difference."""
    def warned(folder, tail="interpolation error 0.3 %"):
        rec = _recording()
        rec["cases"]["rayleigh_step"]["summary"]["Warnings"] = [
            f"map file '/tmp/case-summaries-map_ball_ball-{folder}/out/ball_ball.npz': {tail}"]
        return rec
    code, out = _compare(tmp_path, warned("me286y5q"), warned("esd3ke_8"), capsys)
    assert code == 0, out
    code, out = _compare(tmp_path, warned("me286y5q"), warned("esd3ke_8", "interpolation error 0.4 %"), capsys)
    assert code == 1 and "Warnings[0]" in out
