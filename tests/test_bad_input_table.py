"""Bad input through the command line, as a table: every row gets its exit code, exactly one line
on stderr that names the key (and the value where there is one), no traceback, and an --out
folder that is left exactly as it was.

The rows are bad inputs (sizes that cannot run, impossible geometry, misleading
messages) and those of tests/test_bad_input.py and tests/test_cli.py, each through ``lubedyn run``
into an --out that already holds a previous run's file, so "nothing already written is lost" is
checked for each.  Exit codes (README): 2 input error, 3 an output that cannot be written.
"""
from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from lubedyn import cli
from lubedyn.config import CASES_DIR

J, S, P = "journal_finite", "inclined_slider", "fowell_pocket"
D, M = "cageless_6206_10krpm_short", "map_ball_ball"
EB, ER = "ehl_ball_inner_race", "ehl_roller_slice"
TS, TD = "trb_static_preload", "trb_fig5_2400rpm"

# (case, --set overrides, exit code, fragments that the one line must contain)
ROWS = [
    # film geometry, units, choices
    (J, ["gap.clearance=-50 um"], 2, ["gap.clearance = '-50 um'", "must be > 0 m"]),
    (J, ["gap.eccentricity_ratio=1.0"], 2, ["gap.eccentricity_ratio = 1", "[0, 1)"]),
    (J, ["gap.eccentricity_ratio=1.2"], 2, ["gap.eccentricity_ratio = 1.2", "[0, 1)"]),
    (J, ["gap.clearence=50 um"], 2, ["gap.clearence", "unknown key", "did you mean 'clearance'"]),
    (J, ["gap.clearance=5 Pa"], 2, ["gap.clearance = '5 Pa'", "pressure", "expected length"]),
    (J, ["cavitation.model=reynold"], 2, ["cavitation.model = 'reynold'", "did you mean 'reynolds'"]),
    (J, ["scene=dynamic"], 2, ["scene = 'dynamic'", "did you mean 'dynamics'"]),
    (J, ["mesh.nx"], 2, ["--set 'mesh.nx'", "KEY=VALUE"]),
    (J, ["mesh.element=P3"], 2, ["mesh.element = 'P3'", "'P1', 'P2'"]),
    (J, ["solver.rtol=2"], 2, ["solver.rtol = 2", "(0, 1)"]),
    (J, ["lubricant.viscosity=-0.02 Pa s"], 2, ["lubricant.viscosity.eta0 = '-0.02 Pa s'", "> 0"]),
    (J, ["motion.speed=3000 m"], 2, ["motion.speed = '3000 m'", "angular velocity"]),
    (J, ["foo.bar=1"], 2, ["foo", "unknown key"]),
    (S, ["gap.h_out=0"], 2, ["gap.h_out = 0", "> 0 m"]),
    (P, ["gap.depth=-1.04 um"], 2, ["gap (pocketed_slider)", "must be > 0 everywhere"]),
    # sizes that cannot run
    (J, ["mesh.nx=1"], 2, ["mesh.nx = 1", ">= 3"]),
    (J, ["mesh.nx=100000", "mesh.ny=10000"], 2, ["mesh.nx = 100000", "mesh.ny = 10000", "TiB", "limit"]),
    (S, ["mesh.nx=1000000000"], 2, ["mesh.nx = 1000000000", "TiB", "limit"]),
    (D, ["integrator.duration=1e9 s"], 2, ["integrator.duration = 1e+09 s", "samples", "limit"]),
    (D, ["integrator.sample_interval=1e-12 s"], 2, ["integrator.sample_interval = 1e-12 s", "TiB", "limit"]),
    (M, ["axes.central_gap.n=1000000"], 2, ["axes.central_gap.n = 1000000", "limits.map_points"]),
    (ER, ["grid.nx=1048577"], 2, ["grid.nx = 1048577", "too fine for a line contact"]),
    # bearing geometry
    (D, ["bearing.inner_groove_radius=4 mm"], 2, ["bearing.inner_groove_radius = 0.004", "ball_diameter/2"]),
    (D, ["slots.depth=20 mm"], 2, ["slots.depth = 0.02", "wall under the groove"]),
    (D, ["bearing.n_balls=1"], 2, ["bearing.n_balls = 1", ">= 3"]),
    (D, ["films.friction_law=coulomb"], 2, ["films.friction_law = 'coulomb'", "'paper'"]),
    (D, ["films.asperity_slope=0"], 2, ["films.asperity_slope = 0", "> 0"]),
    # the oil's old spellings (one [lubricant] table for every scene): the old key and the new one
    (D, ["films.viscosity=0.05 Pa s"], 2, ["films.viscosity was renamed", 'lubricant.viscosity.eta0 = "0.05 Pa s"']),
    (D, ["films.pressure_viscosity=1.85e-8"], 2, ["films.pressure_viscosity was renamed",
                                                  "lubricant.viscosity.alpha = 1.85e-08", 'law = "barus"']),
    (TD, ["lubricant.base_oil_viscosity=0.1 Pa s"], 2, ["lubricant.base_oil_viscosity was renamed",
                                                        'lubricant.viscosity.eta0 = "0.1 Pa s"']),
    (TD, ["lubricant.pressure_viscosity=4.662e-8 m^2/N"], 2, ["lubricant.pressure_viscosity was renamed",
                                                              'lubricant.viscosity.alpha = "4.662e-8 m^2/N"']),
    (D, ["lubricant.viscosity.law=roelands"], 2, ["lubricant.viscosity.law = 'roelands'", "scene = 'dynamics'",
                                                  "Barus"]),
    (TD, ["lubricant.eyring_stress=5 MPa"], 2, ["lubricant.eyring_stress", "scene = 'tapered'"]),
    # paper A's tapered roller bearing: static and dynamics scenes
    (TS, ["operating.axial_load=5 kN"], 2, ["axial_load", "exactly one of"]),
    (TS, ["bearing.small_end_diameter=30 mm"], 2, ["bearing.small_end_diameter", "large_end_diameter"]),
    (TS, ["bearing.reconciliation=apex"], 2, ["bearing.reconciliation = 'apex'", "common_apex"]),
    (TS, ["bearing.pocket_clearance=-0.1 mm"], 2, ["bearing.pocket_clearance", "> 0"]),
    (TS, ["model.slices=0"], 2, ["model.slices = 0", ">= 1"]),
    (TD, ["operating.axial=force", "operating.axial_load=0 N"], 2, ["operating.axial_load = 0", "no axial equilibrium"]),
    (TD, ["lubricant.temperature_c=90"], 2, ["lubricant.temperature_c = 90", "15-70 C"]),
    (TD, ["lubricant.grease=soap"], 2, ["lubricant.grease = 'soap'", "'polyurea'"]),
    (TD, ["lubricant.consistency=5"], 2, ["lubricant.consistency = 5", "grease = 'custom'"]),
    (TD, ["model.pocket=film", "model.guide_land=none"], 2, ["model.guide_land", "exactly when"]),
    (TD, ["integrator.method=rk4", "integrator.dt=fast"], 2, ["integrator.dt", "auto"]),
    (TD, ["integrator.method=rk4", "integrator.dt=100 us"], 2, ["integrator.dt", "stab"]),
    (TD, ["analysis.window=[0.2, 0.1]"], 2, ["analysis.window", "end > start"]),
    (TD, ["model.traction=coulomb"], 2, ["model.traction = 'coulomb'", "'paper'"]),
    (TD, ["integrator.sample_interval=1 s"], 2, ["integrator.sample_interval", "at least 2 samples"]),
    (TD, ["cage.mass=-1 kg"], 2, ["cage.mass", "> 0"]),
    (D, ["integrator.method=rk5"], 2, ["integrator.method = 'rk5'", "did you mean 'rk4'"]),
    (D, ["integrator.rtol=0"], 2, ["integrator.rtol = 0", "(0, 0.001]"]),
    (D, ["model.dof=7dof"], 2, ["model.dof = '7dof'", "did you mean '6dof'"]),
    (D, ["operating.scenario=fall"], 2, ["operating.scenario = 'fall'", "'drop', 'steady', 'free'"]),
    # maps
    (M, ["build.method=cubic"], 2, ["build.method = 'cubic'", "'hermite', 'pchip', 'linear'"]),
    (M, ["axes.centre_gap.n=5"], 2, ["axes.centre_gap", "did you mean 'central_gap'"]),
    (M, ["kind=ball_bal"], 2, ["kind = 'ball_bal'", "did you mean 'ball_ball'"]),
    # EHL
    (EB, ["grid.nx=40"], 2, ["grid.nx = 40", "2^k + 1"]),
    (EB, ["grid.nx=513"], 2, ["grid.nx = 513", "too fine for a point contact"]),
    (EB, ["bearing.radial_load=-2000 N"], 2, ["bearing.radial_load = '-2000 N'", ">= 0 N"]),
    (EB, ["bearing.inner_groove_radius=4 mm"], 2, ["bearing.inner_groove_radius = 0.004 m", "D/2"]),
    (EB, ["lubricant.eyring_stress=-5 MPa"], 2, ["lubricant.eyring_stress = '-5 MPa'", "> 0"]),
    (ER, ["lubricant.herschel_bulkley.exponent=3", "lubricant.herschel_bulkley.yield_stress=300 Pa"], 2,
     ["lubricant.herschel_bulkley.exponent = 3", "(0, 2]"]),
    (ER, ["lubricant.herschel_bulkley.exponent=0.7", "lubricant.herschel_bulkley.yield_stress=-3 Pa"], 2,
     ["lubricant.herschel_bulkley.yield_stress = '-3 Pa'", ">= 0 Pa"]),
    (ER, ["lubricant.herschel_bulkley.exponent=0.7", "lubricant.herschel_bulkley.yield_stress=300 Pa", "lubricant.herschel_bulkley.creep=1"], 2,
     ["lubricant.herschel_bulkley.creep = 1", "[0, 1)"]),
    (ER, ["lubricant.herschel_bulkley.exponent=0.7", "lubricant.herschel_bulkley.yield_stress=300 Pa", "lubricant.eyring_stress=5 MPa"], 2,
     ["lubricant.eyring_stress = 5e+06", "[lubricant.herschel_bulkley]", "give one of them"]),
    (S, ["lubricant.herschel_bulkley.exponent=0.7", "lubricant.herschel_bulkley.yield_stress=300 Pa"], 2,
     ["lubricant.herschel_bulkley", "is for EHL scenes"]),
    (ER, ["grid.ny=33"], 2, ["grid.ny = 33", "not used by a line contact"]),
    (ER, ["solver.method=multigrid"], 2, ["solver.method = 'multigrid'", "point contacts"]),
]


def _snapshot(folder: Path) -> dict:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture
def previous_run(tmp_path):
    """An --out folder that holds a previous run's summary (and nothing may touch it)."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.json").write_text('{"Load [N]": 1.0}\n')
    return out


def _run(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _check(code, err, expected_code, fragments):
    assert code == expected_code, err
    assert err.startswith("lubedyn: error: "), err
    assert err.count("\n") == 1, f"not one line: {err!r}"
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, f"{fragment!r} not in {err!r}"


def test_the_table_has_at_least_40_rows():
    assert len(ROWS) + len(EXTRA) >= 40


@pytest.mark.parametrize("case, settings, code, fragments", ROWS,
                         ids=[f"{c}:{' '.join(s)}" for c, s, _, _ in ROWS])
def test_bad_setting(capsys, previous_run, case, settings, code, fragments):
    before = _snapshot(previous_run)
    argv = ["run", case, "--out", previous_run]
    for s in settings:
        argv += ["--set", s]
    got, _, err = _run(capsys, *argv)
    _check(got, err, code, fragments)
    assert _snapshot(previous_run) == before


def _bad_smoke(tmp_path):
    text = (CASES_DIR / "journal_finite.toml").read_text() + 'mesh.element = "P7"\n'  # last table: [smoke]
    path = tmp_path / "smoke.toml"
    path.write_text(text)
    return [path, "--smoke"], 2, ["smoke.mesh.element = 'P7'"]


def _bad_smoke_set(tmp_path):
    """An override of the [smoke] table itself: applied to it before the merge (it used to be applied
    after, where it changed nothing and was never checked)."""
    return [CASES_DIR / "journal_finite.toml", "--smoke", "--set", "smoke.mesh.element=P7"], 2, [
        "[smoke]", "mesh.element = 'P7'"]


def _toml_syntax(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('scene = "film"\n[gap\n')
    return [path], 2, ["invalid TOML"]


def _directory(tmp_path):
    return [CASES_DIR], 2, ["is a directory", "expected a .toml"]


def _typo(tmp_path):
    return ["journal_finit"], 2, ["journal_finit", "did you mean 'journal_finite'"]


def _missing(tmp_path):
    return [tmp_path / "nope.toml"], 2, ["nope.toml", "not found"]


def _out_is_a_file(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a folder\n")
    return ["rayleigh_step", "--smoke", "--out", blocker / "run"], 3, [str(blocker)]


def _empty_out(tmp_path):
    return ["rayleigh_step", "--out", ""], 2, ["--out = ''"]


EXTRA = [_bad_smoke, _bad_smoke_set, _toml_syntax, _directory, _typo, _missing, _out_is_a_file, _empty_out]


@pytest.mark.parametrize("make", EXTRA, ids=[f.__name__.lstrip("_") for f in EXTRA])
def test_bad_case_or_out(capsys, tmp_path, previous_run, make):
    args, code, fragments = make(tmp_path)
    before = _snapshot(previous_run)
    argv = ["run", *args]
    if "--out" not in args:
        argv += ["--out", previous_run]
    got, _, err = _run(capsys, *argv)
    _check(got, err, code, fragments)
    assert _snapshot(previous_run) == before
