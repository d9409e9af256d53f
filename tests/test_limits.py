"""Sizes that cannot run are refused before anything is allocated (lubedyn.limits).

Each estimate is checked against what a small run really has (DOFs of the
built film exactly; values per dynamics sample exactly; a film's peak
resident memory within a factor of a few), and each huge request goes
through the CLI: exit 2, one line naming the key, the estimate and the limit,
and the output folder untouched.  Also: the smallest periodic journal mesh
and the cap on map workers.
"""
from __future__ import annotations

import json
import logging
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import lubedyn.lubrication as lub
from lubedyn import cli, limits
from lubedyn.config import CASES_DIR, CaseError, load_case
from lubedyn.scenes import film as film_scene
from lubedyn.scenes import map as map_scene
from lubedyn.lubrication import mesh as meshes
from lubedyn.lubrication.errors import InputError


def run_cli(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


# --------------------------------------------------------------------------- estimates against real runs
@pytest.mark.parametrize("case, sets", [
    ("journal_finite", []),                                              # periodic quad, P2
    ("journal_finite", ["mesh.element='P1'", "mesh.cell='tri'"]),         # periodic tri, P1
    ("inclined_slider", []),
    ("inclined_slider", ["mesh.element='P2'", "mesh.nx=7"]),
    ("sphere_plane_squeeze", ["mesh.refinements=2"]),                     # disk
    ("ball_ball_squeeze", ["mesh.element='P1'"]),
])
def test_film_dofs_are_predicted_exactly(case, sets):
    """film_dofs (mesh keys only, nothing built) equals the DOFs of the solved film."""
    c = load_case(CASES_DIR / f"{case}.toml", smoke=True, overrides=sets)
    solution = lub.solve(film_scene.build_film(c))
    assert film_scene.film_dofs(c) == solution.info["dofs"]


def test_slider_breakpoints_count_at_most_one_node_each():
    for case in ("rayleigh_step", "fowell_pocket"):
        c = load_case(CASES_DIR / f"{case}.toml", smoke=True)
        actual = lub.solve(film_scene.build_film(c)).info["dofs"]
        assert actual <= film_scene.film_dofs(c) <= actual + 2


MEASURE = textwrap.dedent("""
    import json
    from lubedyn.config import load_case
    from lubedyn.scenes import film as film_scene

    def status(key):  # kB
        return int(next(line for line in open("/proc/self/status") if line.startswith(key)).split()[1])

    small = load_case("journal_finite.toml", overrides=["mesh.nx=8", "mesh.ny=4", "mesh.element='P1'"])
    film_scene.run(small)  # every module and kernel loaded
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")  # resets the peak resident size VmHWM to the current VmRSS
    base = status("VmRSS:")
    case = load_case("journal_finite.toml", overrides=["mesh.nx=256", "mesh.ny=64", "mesh.element='P1'"])
    film_scene.run(case)
    print(json.dumps({"grown": (status("VmHWM:") - base) * 1024, "dofs": film_scene.film_dofs(case)}))
""")


@pytest.mark.skipif(not os.path.exists("/proc/self/clear_refs"), reason="needs Linux's peak-RSS reset")
def test_film_memory_estimate_is_conservative_within_a_few_times():
    """Peak resident memory of a 256 x 64 P1 journal with K and C (measured 52-58 MB, 16,640 DOFs) against
    the estimate DOFs x 8 kB (136 MB): the estimate is above the measurement and within 4 times it."""
    proc = subprocess.run([sys.executable, "-c", MEASURE], capture_output=True, text=True, timeout=300,
                          cwd=CASES_DIR)
    assert proc.returncode == 0, proc.stderr
    got = json.loads(proc.stdout.strip().splitlines()[-1])
    estimate = got["dofs"] * film_scene.BYTES_PER_DOF[2]
    assert got["grown"] < estimate < 4 * got["grown"], (got, estimate)


def test_dynamics_values_per_sample_match_a_run():
    """values_per_sample counts exactly the state, diagnostics, ring diagnostics and the 6 analysis
    coordinates per ball that a (0.1 ms) run holds per sample."""
    from lubedyn.scenes import dynamics as dynamics_scene
    from lubedyn.dynamics.cageless import forces_many

    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml", smoke=True,
                     overrides=["integrator.duration='0.1 ms'", "analysis.lyapunov=false",
                                "analysis.lyapunov_exponents=0", "analysis.spectrum=false"])
    res = dynamics_scene.run(case)
    setup = dynamics_scene.build(case)
    diag, ring = forces_many(res.t, res.y, setup.model.args())
    held = res.y.shape[1] + diag.shape[1] * diag.shape[2] + ring.shape[1] + 6 * setup.model.n_balls
    assert dynamics_scene.values_per_sample(setup.model) == held == 574
    assert dynamics_scene.sample_count(case) == len(res.t) == 51


# --------------------------------------------------------------------------- huge requests through the CLI
HUGE = [
    ("journal_finite", ["mesh.nx=100000", "mesh.ny=10000"], "mesh.nx = 100000 with mesh.ny = 10000",
     "4e+09 degrees of freedom"),
    ("inclined_slider", ["mesh.nx=1000000000"], "mesh.nx = 1000000000", "2e+09 degrees of freedom"),
    ("cageless_6206_10krpm_short", ["integrator.duration=1e9"], "integrator.duration = 1e+09 s", "5e+14 samples"),
    ("cageless_6206_10krpm_short", ["integrator.sample_interval=1e-12"], "integrator.sample_interval = 1e-12 s",
     "2e+10 samples"),
    ("map_ball_ball", ["axes.central_gap.n=1000000"], "axes.central_gap.n = 1000000",
     "more than limits.map_points = 1000000"),
    ("ehl_roller_slice", ["grid.nx=1048577"], "grid.nx = 1048577", "use nx <= 4097"),
    ("ehl_ball_inner_race", ["solver.method='multigrid'", "grid.nx=8193", "grid.ny=4097"], "grid.nx = 8193",
     "grid nodes (multigrid)"),
]


@pytest.mark.parametrize("case, sets, key, estimate", HUGE, ids=[h[2].split(" ")[0] + "-" + h[0] for h in HUGE])
@pytest.mark.parametrize("command", ["run", "validate"])
def test_huge_sizes_are_refused_in_one_line(capsys, tmp_path, monkeypatch, case, sets, key, estimate, command):
    monkeypatch.setenv(limits.ENV_MEMORY, "16 GiB")  # the same answer on every machine
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("earlier run")
    argv = [command, case] + (["--out", out] if command == "run" else [])
    for s in sets:
        argv += ["--set", s]
    code, stdout, err = run_cli(capsys, *argv)
    assert code == 2, err
    assert err.startswith(f"lubedyn: error: {key}") and err.count("\n") == 1 and "Traceback" not in err, err
    assert estimate in err
    if "memory" in err:
        assert "more than the limit of 16 GiB (LUBEDYN_MEMORY_LIMIT)" in err and "[limits] memory" in err
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]
    assert stdout == ""


def test_rk4_steps_beyond_max_steps_are_refused():
    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml",
                     overrides=["integrator.method='rk4'", "integrator.dt=1e-12"])
    from lubedyn.scenes import dynamics as dynamics_scene

    with pytest.raises(InputError, match=r"integrator.dt = 1e-12 s: 2e\+10 fixed RK4 steps .* more than "
                                         r"integrator.max_steps = 50000000"):
        dynamics_scene.build(case)


# --------------------------------------------------------------------------- the limit and its overrides
def test_memory_limit_precedence(monkeypatch):
    """[limits] memory, then LUBEDYN_MEMORY_LIMIT, then 80 % of the available memory."""
    smoke = dict(smoke=True)
    journal = CASES_DIR / "journal_finite.toml"  # smoke: 1088 DOFs x 8 kB = 8.5 MiB
    monkeypatch.delenv(limits.ENV_MEMORY, raising=False)
    limit, source = limits.memory_limit(load_case(journal, **smoke))
    assert limit == pytest.approx(0.8 * limits.available_memory(), rel=0.05) and "available" in source
    film_scene.build_film(load_case(journal, **smoke))
    monkeypatch.setenv(limits.ENV_MEMORY, "8 MiB")
    with pytest.raises(InputError, match=r"1.09e\+03 degrees of freedom \(P2, 2-D\) need about 8.5 MiB of memory, "
                                         r"more than the limit of 8 MiB \(LUBEDYN_MEMORY_LIMIT\)"):
        film_scene.build_film(load_case(journal, **smoke))
    film_scene.build_film(load_case(journal, overrides=["limits.memory='9 MiB'"], **smoke))  # the case wins
    with pytest.raises(InputError, match=r"more than the limit of 1 MiB \(limits.memory\)"):
        film_scene.build_film(load_case(journal, overrides=["limits.memory=1048576"], **smoke))
    monkeypatch.setenv(limits.ENV_MEMORY, "lots")
    with pytest.raises(InputError, match="LUBEDYN_MEMORY_LIMIT = 'lots' must be a size such as '40 GiB'"):
        film_scene.build_film(load_case(journal, **smoke))


@pytest.mark.parametrize("value, fragment", [("'1 MX'", "has unit 'MX'"), ("-5", "must be > 0"),
                                             ("true", "must be a size")])
def test_bad_memory_limit_is_a_case_error(value, fragment):
    with pytest.raises(CaseError, match=f"limits.memory = .* {fragment}"):
        load_case(CASES_DIR / "journal_finite.toml", overrides=[f"limits.memory={value}"])


# --------------------------------------------------------------------------- smallest journal mesh
@pytest.mark.parametrize("nx", [1, 2])
def test_journal_needs_three_cells_around(nx):
    """nx = 1 gave scikit-fem's 'duplicate index' traceback, nx = 2 a film without boundaries (measured);
    both are refused at validation with the smallest allowed value."""
    with pytest.raises(CaseError, match=f"mesh.nx = {nx} must be >= 3 for a journal"):
        load_case(CASES_DIR / "journal_finite.toml", smoke=True, overrides=[f"mesh.nx={nx}"])
    with pytest.raises(InputError, match="at least 3 cells along x"):
        meshes.rectangle(np.linspace(0, 1, nx + 1), np.linspace(0, 1, 3), periodic_x=True)


def test_journal_with_three_cells_solves():
    c = load_case(CASES_DIR / "journal_finite.toml", smoke=True, overrides=["mesh.nx=3"])
    s = lub.solve(film_scene.build_film(c))
    assert s.info["dofs"] == film_scene.film_dofs(c) == 2 * 3 * (2 * 8 + 1)
    assert s.p_max > 0


# --------------------------------------------------------------------------- map workers and build time
def _capture_build(monkeypatch):
    seen = {}

    class Stop(Exception):
        pass

    def fake_build_map(*args, **kwargs):
        seen.update(kwargs)
        raise Stop

    monkeypatch.setattr(map_scene.maps, "build_map", fake_build_map)
    return seen, Stop


def test_map_workers_are_capped_at_the_points(monkeypatch, caplog):
    """40 workers on the 24-point smoke map of the ball-ball film (3 accuracy points) start 24 processes,
    logged at INFO, with a warning that 24 is more than the usable cores."""
    monkeypatch.setattr(map_scene.maps, "default_workers", lambda: 2)
    seen, Stop = _capture_build(monkeypatch)
    case = load_case(CASES_DIR / "map_ball_ball.toml", smoke=True, overrides=["build.workers=40"])
    with caplog.at_level(logging.INFO, logger="lubedyn.scenes.map"), pytest.raises(Stop):
        map_scene.run(case)
    assert seen["workers"] == 24
    infos = [r.getMessage() for r in caplog.records if r.levelno == logging.INFO]
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert "build.workers = 40 capped at 24: no pass solves more points" in infos
    assert warnings == ["build.workers = 24 is more than the 2 usable core(s): the extra processes only share "
                        "them and each holds its own memory"]


def test_map_default_workers_stay_at_the_cores(monkeypatch, caplog):
    monkeypatch.setattr(map_scene.maps, "default_workers", lambda: 2)
    seen, Stop = _capture_build(monkeypatch)
    case = load_case(CASES_DIR / "map_ball_ball.toml", smoke=True)
    with caplog.at_level(logging.INFO, logger="lubedyn.scenes.map"), pytest.raises(Stop):
        map_scene.run(case)
    assert seen["workers"] == 2
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]


def test_long_map_builds_are_announced(monkeypatch, caplog):
    """1000 x 12 x 20 ball-ball points at 3.5 s each on 2 processes: about 117 h."""
    monkeypatch.setattr(map_scene.maps, "default_workers", lambda: 2)
    case = load_case(CASES_DIR / "map_ball_ball.toml", overrides=["axes.central_gap.n=1000"])
    with caplog.at_level(logging.WARNING, logger="lubedyn.scenes.map"):
        setup = map_scene.build(case)
    assert setup.points == 240_000
    assert [r.getMessage() for r in caplog.records] == [
        "axes.central_gap.n = 1000: 1000 x 12 x 20 = 2.4e+05 map points: the build will take about 117 h on 2 "
        "process(es) (3.5 s of one core per point, measured at the default resolution)"]


def test_dopri5_runs_beyond_max_steps_are_refused():
    """A 1e9 s drop sampled every 1e6 s fits in memory (1001 samples) but needs at least 6.7e13 adaptive
    steps (mean step at most 10 x the measured 1.48 us); the bundled 0.1 s runs need 6,700 at that bound."""
    from lubedyn.scenes import dynamics as dynamics_scene

    case = load_case(CASES_DIR / "cageless_6206_10krpm_short.toml",
                     overrides=["integrator.duration=1e9", "integrator.sample_interval=1e6"])
    with pytest.raises(InputError, match=r"integrator.duration = 1e\+09 s needs at least 6.67e\+13 DOPRI5 steps .* "
                                         r"more than integrator.max_steps = 50000000"):
        dynamics_scene.build(case)
    dynamics_scene.build(load_case(CASES_DIR / "cageless_6206_10krpm.toml"))
