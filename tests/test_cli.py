"""The ``lubedyn`` command line: exit codes, one-line messages, files written.

Most tests call ``lubedyn.cli.main(argv)`` in-process (fast) and capture
stdout/stderr; one runs ``python -m lubedyn.cli`` as a real process.
"""
from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR
from lubedyn.units import UnitError, parse_quantity

SLIDER = CASES_DIR / "inclined_slider.toml"
JOURNAL = CASES_DIR / "journal_finite.toml"
POCKET = CASES_DIR / "fowell_pocket.toml"


def run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def assert_one_line_error(err: str, *fragments: str):
    assert err.startswith("lubedyn: error: "), err
    assert err.count("\n") == 1, f"not one line: {err!r}"
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, f"{fragment!r} not in {err!r}"


def write_case(tmp_path, text: str, name="case.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# ---------------------------------------------------------------------------
# quantities at the boundary (lubedyn.units)


@pytest.mark.parametrize("text, dimension, si", [
    ("50 um", "length", 50e-6), ("0.05 Pa s", "dynamic viscosity", 0.05), ("10 cP", "dynamic viscosity", 0.01),
    ("10000 rpm", "angular velocity", 10000 * 2 * math.pi / 60), ("1.85e-8 m^2/N", "inverse pressure", 1.85e-8),
    ("2e-8 1/Pa", "inverse pressure", 2e-8), ("30 deg", "angle", math.pi / 6), ("0.1 MPa", "pressure", 1e5),
    ("992 kg/m^3", "density", 992.0), ("5 N s/m", "damping", 5.0), ("-1 mm/s", "velocity", -1e-3), (0.3, "length", 0.3),
])
def test_quantity_to_si(text, dimension, si):
    assert parse_quantity(text, dimension) == pytest.approx(si, rel=1e-14)


@pytest.mark.parametrize("text, dimension, message", [
    ("5 Pa", "length", "has units of pressure, expected length (m)"),
    ("50 Hz", "angular velocity", "has units of frequency, expected angular velocity (rad/s)"),
    ("5 ums", "length", "unknown unit 'ums'; did you mean"),
    ("fast", "velocity", "is not '<number> <units>'"),
    (True, "length", "is not a quantity"),
])
def test_quantity_errors(text, dimension, message):
    with pytest.raises(UnitError, match=re.escape(message)):
        parse_quantity(text, dimension)


# ---------------------------------------------------------------------------
# input errors: exit 2, one line naming key, value and what is allowed


def test_unknown_key_gets_a_suggestion(tmp_path, capsys):
    text = JOURNAL.read_text().replace('clearance = "50 um"', 'clearence = "50 um"')
    code, out, err = run(capsys, "validate", write_case(tmp_path, text))
    assert code == 2
    assert_one_line_error(err, "gap.clearence", "unknown key", "did you mean 'clearance'?")


def test_unknown_value_gets_a_suggestion(capsys):
    code, _, err = run(capsys, "validate", JOURNAL, "--set", "cavitation.model=reynold")
    assert code == 2
    assert_one_line_error(err, "cavitation.model = 'reynold'", "did you mean 'reynolds'?")


def test_wrong_unit_names_key_value_and_dimension(capsys):
    code, _, err = run(capsys, "run", JOURNAL, "--set", "gap.clearance=5 Pa", "--dry-run")
    assert code == 2
    assert_one_line_error(err, "gap.clearance = '5 Pa' has units of pressure, expected length")


def test_negative_clearance(capsys):
    code, _, err = run(capsys, "validate", JOURNAL, "--set", "gap.clearance=-50 um")
    assert code == 2
    assert_one_line_error(err, "gap.clearance = '-50 um' must be > 0 m")


@pytest.mark.parametrize("setting, fragment", [
    ("gap.eccentricity_ratio=1.0", "gap.eccentricity_ratio = 1 must be in [0, 1)"),
    ("gap.eccentricity_ratio=1.2", "gap.eccentricity_ratio = 1.2 must be in [0, 1)"),
])
def test_eccentricity_ratio_at_or_above_one(capsys, setting, fragment):
    code, _, err = run(capsys, "validate", JOURNAL, "--set", setting)
    assert code == 2
    assert_one_line_error(err, fragment, "touch")


def test_eccentricity_vector_outside_clearance(tmp_path, capsys):
    text = JOURNAL.read_text().replace("eccentricity_ratio = 0.6\n", "").replace('attitude_angle = "0 deg"\n', "")
    case = write_case(tmp_path, text)
    code, _, err = run(capsys, "validate", case, "--set", "gap.eccentricity_x=40 um", "--set", "gap.eccentricity_y=30 um")
    assert code == 2
    assert_one_line_error(err, "gap.eccentricity_x", "eccentricity ratio 1;", "must be < 1")


def test_zero_gap_parameter(capsys):
    code, _, err = run(capsys, "validate", SLIDER, "--set", "gap.h_out=0")
    assert code == 2
    assert_one_line_error(err, "gap.h_out = 0 must be > 0 m")


def test_gap_closing_inside_the_domain(capsys):
    """A pocket 'depth' of -1.04 um (a bump) closes the 1.04 um gap at x = 2 mm."""
    code, _, err = run(capsys, "run", POCKET, "--smoke", "--set", "gap.depth=-1.04 um", "--dry-run")
    assert code == 2
    assert_one_line_error(err, "gap (pocketed_slider)", "must be > 0 everywhere")


def test_scene_misspelt(capsys):
    code, _, err = run(capsys, "validate", JOURNAL, "--set", "scene=dynamic")
    assert code == 2
    assert_one_line_error(err, "scene = 'dynamic' is not allowed", "did you mean 'dynamics'")


def test_missing_file(tmp_path, capsys):
    code, _, err = run(capsys, "run", tmp_path / "nope.toml")
    assert code == 2
    assert_one_line_error(err, "nope.toml", "not found")


def test_toml_syntax_error(tmp_path, capsys):
    code, _, err = run(capsys, "validate", write_case(tmp_path, 'scene = "film"\n[gap\n'))
    assert code == 2
    assert_one_line_error(err, "invalid TOML")


def test_bad_set_syntax(capsys):
    code, _, err = run(capsys, "validate", SLIDER, "--set", "mesh.nx")
    assert code == 2
    assert_one_line_error(err, "must be KEY=VALUE")


# ---------------------------------------------------------------------------
# solver failure: exit 1, nothing lost


def test_non_converging_solve_exits_1(tmp_path, capsys):
    code, _, err = run(capsys, "run", POCKET, "--smoke", "--set", "solver.max_iter=1", "--out", tmp_path / "out")
    assert code == 1
    assert_one_line_error(err, "did not converge")
    assert not (tmp_path / "out").exists()


def test_failing_run_keeps_existing_outputs(tmp_path, capsys):
    out = tmp_path / "out"
    assert run(capsys, "run", POCKET, "--smoke", "--out", out)[0] == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    assert set(before) == {"summary.json", "case.resolved.toml", "film.vtu", "pressure.png", "manifest.json"}
    code, _, err = run(capsys, "run", POCKET, "--smoke", "--set", "solver.max_iter=1", "--out", out)
    assert code == 1
    after = {p.name: p.read_bytes() for p in out.iterdir()}
    assert after == before  # same files, same bytes, no temporaries left behind
    assert json.loads(after["summary.json"])["Cavitation model"] == "jfo"


def test_failure_while_writing_keeps_existing_outputs(tmp_path, capsys, monkeypatch):
    """Outputs are staged and moved into place only when all are written; a failure to write exits 3
    with one line naming the folder and the cause."""
    import lubedyn.lubrication.reynolds.solution

    out = tmp_path / "out"
    assert run(capsys, "run", POCKET, "--smoke", "--out", out)[0] == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}

    def broken_plot(self, ax=None):
        raise OSError("disk full (simulated)")

    monkeypatch.setattr(lubedyn.lubrication.reynolds.solution.FilmSolution, "plot_pressure", broken_plot)
    code, _, err = run(capsys, "run", POCKET, "--smoke", "--set", "motion.velocity_lower=2 m/s", "--out", out)
    assert code == 3
    assert_one_line_error(err, f"cannot write {out}: disk full (simulated)")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before  # no staging folder left either


# ---------------------------------------------------------------------------
# run, --set, --dry-run, validate, cases, info


def test_set_overrides_a_value(tmp_path, capsys):
    """The load of an isoviscous slider is linear in the sliding speed."""
    base, fast = tmp_path / "base", tmp_path / "fast"
    assert run(capsys, "run", SLIDER, "--smoke", "--out", base)[0] == 0
    code, out, _ = run(capsys, "run", SLIDER, "--smoke", "--out", fast, "--set", "motion.velocity_lower=10 m/s")
    assert code == 0 and "wrote" in out
    w0 = json.loads((base / "summary.json").read_text())["Load per unit width [N/m]"]
    w1 = json.loads((fast / "summary.json").read_text())["Load per unit width [N/m]"]
    assert w1 / w0 == pytest.approx(2.0, rel=1e-12)
    resolved = tomllib.loads((fast / "case.resolved.toml").read_text())
    assert resolved["motion"]["velocity_lower"] == [10.0]
    assert resolved["mesh"]["nx"] == 10  # the smoke value, resolved


def test_dry_run_writes_nothing(tmp_path, capsys):
    out = tmp_path / "out"
    code, stdout, err = run(capsys, "run", JOURNAL, "--dry-run", "--out", out)
    assert code == 0 and err == ""
    assert not out.exists()
    assert "dry run: film scene: gap journal" in stdout
    resolved = tomllib.loads(stdout.split("\n", 2)[2])  # the resolved case follows the two plan lines
    assert resolved["gap"]["clearance"] == pytest.approx(50e-6)
    assert resolved["motion"]["speed"] == pytest.approx(3000 * 2 * 3.141592653589793 / 60)


def test_default_out_dir_is_runs_case_stem(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert run(capsys, "run", "rayleigh_step", "--smoke")[0] == 0  # a bundled case by name
    assert (tmp_path / "runs" / "rayleigh_step" / "summary.json").is_file()


def test_summary_is_flat_with_units_and_solver_info(tmp_path, capsys):
    assert run(capsys, "run", JOURNAL, "--smoke", "--out", tmp_path)[0] == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert all(isinstance(v, (int, float, str, bool)) for v in summary.values())
    numeric = [k for k, v in summary.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    assert all(k.endswith("]") for k in numeric), [k for k in numeric if not k.endswith("]")]
    for key in ("Load [N]", "Newton iterations [-]", "Degrees of freedom [-]", "Solve time [s]", "Run time [s]",
                "Stiffness K[x,y] [N/m]", "Damping C[y,y] [N s/m]", "Flow top [m^3/s]"):
        assert key in summary
    assert summary["Linear solver"] and summary["Smoke resolution"] is True


def test_validate_ok_is_one_line(capsys):
    code, out, err = run(capsys, "validate", JOURNAL)
    assert code == 0 and err == ""
    assert out.startswith("OK ") and out.count("\n") == 1


def test_cases_lists_every_bundled_case(capsys):
    code, out, _ = run(capsys, "cases")
    assert code == 0
    lines = out.splitlines()
    paths = sorted(CASES_DIR.glob("*.toml"))
    assert len(lines) == len(paths)
    for path, line in zip(paths, lines):
        description = tomllib.loads(path.read_text())["description"]
        assert line.split()[0] == path.stem and line.endswith(description)


def test_info(capsys):
    code, out, _ = run(capsys, "info")
    assert code == 0
    for name in ("lubedyn", "python", "numpy", "scipy", "scikit-fem", "numba", "pyvista", "meshio", "cores"):
        assert any(line.split()[0] == name for line in out.splitlines()), name


def test_verbose_logs_to_stderr(tmp_path, capsys):
    code, _, err = run(capsys, "-v", "run", SLIDER, "--smoke", "--out", tmp_path)
    assert code == 0
    assert "lubedyn: INFO:" in err and "wrote" in err


def test_console_entry_point_as_a_process(tmp_path):
    """A real process: exit code 2 and a single stderr line, no traceback."""
    case = write_case(tmp_path, SLIDER.read_text().replace('h_out = "10 um"', 'h_out = "10 Pa"'))
    proc = subprocess.run([sys.executable, "-m", "lubedyn.cli", "run", str(case)], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2
    assert_one_line_error(proc.stderr, "gap.h_out = '10 Pa' has units of pressure, expected length")


# ---------------------------------------------------------------------------
# EHL scene

BALL_RACE = CASES_DIR / "ehl_ball_inner_race.toml"
ROLLER = CASES_DIR / "ehl_roller_slice.toml"
EHL_DIRECT = """scene = "ehl"
description = "steel ball on a steel flat, Barus oil"
[contact]
radius_x = "10 mm"
radius_y = "10 mm"
[materials]
modulus1 = "210 GPa"
poisson1 = 0.3
[lubricant.viscosity]
law = "barus"
eta0 = "0.04 Pa s"
alpha = "2e-8 m^2/N"
[operating]
mean_speed = "1 m/s"
load = "20 N"
[grid]
nx = 33
ny = 17
"""
EHL_MOES = """scene = "ehl"
description = "circular contact at Moes M = 20, L = 10"
[dimensionless]
M = 20
L = 10
[grid]
nx = 33
ny = 17
"""


def test_ehl_unknown_key_in_contact(tmp_path, capsys):
    case = write_case(tmp_path, EHL_DIRECT.replace('radius_x = "10 mm"', 'radious_x = "10 mm"'))
    code, _, err = run(capsys, "validate", case)
    assert code == 2
    assert_one_line_error(err, "contact.radious_x: unknown key in [contact]", "did you mean 'radius_x'")


@pytest.mark.parametrize("case, setting, fragment", [
    ("direct", "operating.load=-5 N", "operating.load = '-5 N' must be > 0 N"),
    ("ball", "bearing.radial_load=-2000 N", "bearing.radial_load = '-2000 N' must be >= 0 N"),
    ("direct", "grid.nx=40", "grid.nx = 40 must be 2^k + 1"),
    ("direct", "operating.load_per_length=5 N/m", "operating.load_per_length = 5 cannot be combined with load"),
    ("ball", "contact.radius_x=4 mm", "contact.radius_x = 0.004 is not used with [bearing]"),
    ("ball", "bearing.inner_groove_radius=4 mm", "bearing.inner_groove_radius = 0.004 m must be > D/2"),
    ("roller", "grid.ny=33", "grid.ny = 33 is not used by a line contact"),
    ("direct", "operating.load=5 m", "operating.load = '5 m' has units of length, expected force"),
    ("ball", "grid.nx=513", "grid.nx = 513 is too fine for a point contact"),
])
def test_ehl_input_errors(tmp_path, capsys, case, setting, fragment):
    path = {"direct": write_case(tmp_path, EHL_DIRECT), "ball": BALL_RACE, "roller": ROLLER}[case]
    code, _, err = run(capsys, "validate", path, "--set", setting)
    assert code == 2
    assert_one_line_error(err, fragment)


def test_ehl_run_writes_a_vtu_that_pyvista_and_meshio_read(tmp_path, capsys):
    """A circular contact given by Moes' M and L: the summary carries them back
    exactly, and ehl.vtu holds the solution's pressure and film on 3-D points."""
    import meshio
    import numpy as np
    import pyvista as pv

    out = tmp_path / "out"
    code, stdout, err = run(capsys, "run", write_case(tmp_path, EHL_MOES), "--out", out)
    assert code == 0 and err == ""
    assert "Central film thickness [m]" in stdout
    assert {p.name for p in out.iterdir()} == {"summary.json", "case.resolved.toml", "ehl.vtu", "profiles.png",
                                               "manifest.json"}
    s = json.loads((out / "summary.json").read_text())
    assert s["Scene"] == "ehl" and s["Contact"] == "point"
    assert s["Moes M [-]"] == pytest.approx(20, rel=1e-12) and s["Moes L [-]"] == pytest.approx(10, rel=1e-12)
    # Nijenbanning, Venner & Moes (1994), quoted within ~5 %; measured +0.4 % on 33 x 17 nodes
    assert s["Central film thickness [m]"] == pytest.approx(s["Nijenbanning central film thickness [m]"], rel=0.05)
    grid = pv.read(out / "ehl.vtu")
    mesh = meshio.read(out / "ehl.vtu")
    assert grid.n_points == len(mesh.points) == s["Degrees of freedom [-]"] == 33 * 17
    assert grid.points.shape[1] == 3 and np.all(grid.points[:, 2] == 0.0)
    for data in (grid.point_data, mesh.point_data):
        p, h = np.asarray(data["Pressure [Pa]"]), np.asarray(data["Film thickness [m]"])
        assert p.max() == pytest.approx(s["Maximum pressure [Pa]"], rel=1e-12)
        assert h.min() == pytest.approx(s["Minimum film thickness [m]"], rel=1e-12)
        assert p.min() >= 0.0


def test_ehl_failed_solve_exits_1_and_keeps_outputs(tmp_path, capsys):
    out = tmp_path / "out"
    assert run(capsys, "run", ROLLER, "--smoke", "--out", out)[0] == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    code, _, err = run(capsys, "run", ROLLER, "--smoke", "--set", "solver.max_iter=2", "--out", out)
    assert code == 1
    assert_one_line_error(err, "EHL solve did not converge in 2 Newton iterations")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before


def test_ehl_dry_run_and_validate(tmp_path, capsys):
    code, stdout, err = run(capsys, "run", BALL_RACE, "--dry-run", "--out", tmp_path / "out")
    assert code == 0 and err == "" and not (tmp_path / "out").exists()
    assert "dry run: ehl scene: point contact from a ball bearing (inner race)" in stdout
    assert "ehl.vtu, profiles.png" in stdout
    code, stdout, _ = run(capsys, "validate", ROLLER)
    assert code == 0 and stdout.startswith("OK ") and "line contact from a roller bearing" in stdout


def test_ehl_prescribed_approach_gives_back_the_load(tmp_path, capsys):
    """Load balance inverted: the approach h00 found for a 1 N load, prescribed,
    carries 1 N (same grid: with a prescribed approach the solver scales its
    grid on a nominal 1 N Hertz contact)."""
    direct = write_case(tmp_path, EHL_DIRECT.replace('load = "20 N"', 'load = "1 N"'))
    assert run(capsys, "run", direct, "--out", tmp_path / "load")[0] == 0
    h00 = json.loads((tmp_path / "load" / "summary.json").read_text())["Approach h00 [m]"]
    prescribed = write_case(tmp_path, EHL_DIRECT.replace('load = "20 N"', f"approach = {h00!r}"), "approach.toml")
    code, _, err = run(capsys, "run", prescribed, "--out", tmp_path / "approach")
    assert code == 0, err
    s = json.loads((tmp_path / "approach" / "summary.json").read_text())
    assert s["Load [N]"] == pytest.approx(1.0, rel=1e-6)


def test_multigrid_method_refuses_line_contacts_at_validate(capsys):
    """The EHL multigrid solves point contacts only: a line-contact case asking for it is refused before any
    solve, in one line naming the key, the value and what is allowed."""
    code, _, err = run(capsys, "validate", CASES_DIR / "ehl_roller_slice.toml", "--set", "solver.method=multigrid")
    assert code == 2
    assert_one_line_error(err, "solver.method = 'multigrid' solves point contacts", "line contacts use 'auto'")


def test_multigrid_stops_clearly_on_paper_b_elongated_contact(tmp_path, capsys):
    """Where the EHL multigrid stops, pinned: paper B's most loaded ball / inner race contact (k = 11,
    M = 1001, L = 25.4) on the case's anisotropic grid converges on 65 x 33 nodes and stagnates on
    129 x 33 (measured: relative residual 7.6e-2 at cycle 8); the run exits 1 with one line naming
    M, L, the grid and the residual, and writes nothing.  (The FEM Newton solves both grids.)"""
    out = tmp_path / "out"
    code, _, err = run(capsys, "run", CASES_DIR / "ehl_ball_inner_race.toml", "--set", "solver.method=multigrid",
                       "--set", "grid.nx=129", "--out", str(out))
    assert code == 1
    assert_one_line_error(err, "EHL multigrid stagnated at M = 1001, L = 25.44 on 129 x 33 nodes",
                          "relative residual")
    assert not out.exists() or not any(out.iterdir())


def test_set_of_the_smoke_table_takes_part_in_the_smoke_variant(capsys):
    """``--smoke --set smoke.mesh.nx=7``: the override edits [smoke] before it is merged, so the smoke
    run has 7 cells (it used to be applied after the merge and change nothing)."""
    code, out, _ = run(capsys, "run", "rayleigh_step", "--smoke", "--set", "smoke.mesh.nx=7", "--dry-run")
    assert code == 0
    assert "mesh with 7 cells" in out
