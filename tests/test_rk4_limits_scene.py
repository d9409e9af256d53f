"""RK4's growth guard through the dynamics scene: RK4 is checked along the run, not only at t0.

The 10 krpm drop (smoke) starts with the balls at rest on the races, where the linearised race
traction is a real eigenvalue of about -1.5e6 1/s (``lubedyn.dynamics.integrators`` module docstring), five
times the contact rate ``model.omega_max(y0)`` = 2.74e5 rad/s that the t0 check sees.  At
``integrator.dt = 2 us`` the t0 check passes (dt omega_max = 0.55) but RK4 is beyond its real-axis
limit for the traction (h lambda ~ 3 > 2.785): before the guard the run completed with the ball slips
chattering over the first steps; now the growth guard stops it within 5 steps with the stable step.
At 1 us the same run completes and reports its largest estimate (2.54, 9 % below the limit: the
margin of this case)."""
from __future__ import annotations

import json

from lubedyn import cli
from lubedyn.config import CASES_DIR

SHORT = CASES_DIR / "cageless_6206_10krpm_short.toml"
COMMON = ["--smoke", "--set", "integrator.method=rk4", "--set", "integrator.duration='0.1 ms'",
          "--set", "analysis.lyapunov_exponents=0", "--set", "analysis.lyapunov=false", "--set", "output.write=[]"]


def test_rk4_beyond_the_traction_limit_stops_with_the_stable_step(capsys, tmp_path):
    code = cli.main(["run", str(SHORT), *COMMON, "--set", "integrator.dt='2 us'", "--out", str(tmp_path / "bad")])
    _, err = capsys.readouterr()
    assert code == 1
    assert err.startswith("lubedyn: error: rk4 stopped at t = 8e-06 s") and err.count("\n") == 1, err
    assert "estimated |h lambda| = 3.265 > 2.785 (real axis: a decay)" in err
    assert "a stable step is dt <= 1.706e-06 s" in err and "integrator.dt = 2e-06 s" in err
    assert not (tmp_path / "bad" / "summary.json").exists()


def test_rk4_inside_the_limit_reports_its_largest_estimate(capsys, tmp_path):
    code = cli.main(["run", str(SHORT), *COMMON, "--set", "integrator.dt='1 us'", "--out", str(tmp_path)])
    capsys.readouterr()
    assert code == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["Integrator stop reason"] == "reached the last output time"
    assert 2.0 < s["Largest estimated h*|lambda| (RK4) [-]"] < 2.785
    assert s["Accepted steps [-]"] == 100
