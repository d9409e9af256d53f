"""The methods atlas (benchmarks/method_limits.py) classifies the known limit cases as the
library reports them: the sweep functions run against the current library, so an API change that
would break the benchmark, or a check that stops firing, fails here.  Smoke sizes (a few seconds;
no time is asserted)."""
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
method_limits = pytest.importorskip("method_limits")


def test_atlas_marks_the_ehl_line_limit():
    """Line M = 1000, L = 10: 257 nodes converge +86 % off Moes' formula and warn (measured +0.857);
    513 nodes are right (+1.3 %, margin 7x against the 10 % tolerance)."""
    pts = {p["nx"]: p for p in method_limits.ehl_line((1000,), (257, 513))["points"]}
    assert pts[257]["outcome"] == "warned" and pts[257]["error"] == pytest.approx(0.857, abs=0.02)
    assert "use grid.nx >= 513" in pts[257]["warnings"][0]
    assert pts[513]["outcome"] == "right" and abs(pts[513]["error"]) < 0.03


def test_atlas_marks_the_rk4_stability_limit():
    """RK4 on the undamped oscillator: h omega = 2.8 (1 % inside the 2.828 limit) runs and equals
    RK4's amplification |R|^N to 1e-8; 3.0 (6 % beyond) is stopped by the growth guard (bare call)
    and refused at t0 when omega_max is given."""
    pts = {(p["h_omega"], p["mode"]): p for p in method_limits.rk4_oscillator((2.8, 3.0))["points"]}
    inside = pts[(2.8, "bare call (growth guard)")]
    assert inside["outcome"] == "right" and inside["discrete_amplitude_error"] == pytest.approx(0.0, abs=1e-8)
    beyond = pts[(3.0, "bare call (growth guard)")]
    assert beyond["outcome"] == "refused" and beyond["exception"] == "IntegrationError"
    assert "a stable step is dt <= 2.828e-05 s" in beyond["message"]
    assert pts[(3.0, "omega_max given")]["stop_reason"] == "refused at input"
