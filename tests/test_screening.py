"""Morris screening (lubedyn.scenes.screening, ``[study] combine = "morris"``) on functions whose
elementary effects are known in closed form, and a screened study of the inclined slider against its
closed-form load (Hamrock, Schmid & Jacobson 2004, ch. 8: W = 6 eta U L^2/(h_out^2 (K-1)^2) [ln K -
2 (K-1)/(K+1)], linear in eta and in U)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from lubedyn.lubrication.errors import InputError
from lubedyn.scenes import screening as S
from lubedyn.scenes.study import StudyError, read_study, run_study


def test_trajectories_move_one_factor_by_delta_inside_the_unit_cube():
    k, r, p = 5, 6, 4
    X = S.trajectories(k, r, p, seed=3)
    step = p / (2 * (p - 1))
    assert X.shape == (r, k + 1, k) and X.min() >= 0.0 and X.max() <= 1.0
    for t in range(r):
        moved = []
        for j in range(k):
            d = X[t, j + 1] - X[t, j]
            nz = np.flatnonzero(np.abs(d) > 1e-12)
            assert nz.size == 1 and abs(abs(d[nz[0]]) - step) < 1e-12
            moved.append(int(nz[0]))
        assert sorted(moved) == list(range(k))  # each factor once per trajectory
    # the grid: every coordinate a multiple of 1/(p - 1)
    assert np.allclose(X * (p - 1), np.round(X * (p - 1)), atol=1e-9)
    assert np.array_equal(X, S.trajectories(k, r, p, seed=3))  # the seed fixes the design


def test_a_linear_function_has_its_coefficients_as_effects():
    """y = sum c_i x_i in scaled units: every elementary effect is c_i, so mu = c_i, mu* = |c_i| and
    sigma = 0 exactly (up to round-off)."""
    c = np.array([3.0, -2.0, 0.0, 0.5])
    X = S.trajectories(4, 5, 6, seed=0).reshape(-1, 4)
    res = S.effects(X, X @ c, 4)
    for ci, e in zip(c, res):
        assert e["mu"] == pytest.approx(ci, abs=1e-12) and e["mu*"] == pytest.approx(abs(ci), abs=1e-12)
        assert e["sigma"] == pytest.approx(0.0, abs=1e-12) and e["effects"] == 5


def test_an_interaction_shows_in_sigma_and_a_failed_run_drops_its_steps():
    """y = x0 x1 + x2: x0's and x1's effects depend on the other factor (sigma > 0), x2's do not; a failed
    run (None) removes the two steps that touch it."""
    X = S.trajectories(3, 8, 4, seed=5).reshape(-1, 3)
    y = [a * b + c for a, b, c in X]
    res = S.effects(X, y, 3)
    assert res[0]["sigma"] > 0.05 and res[1]["sigma"] > 0.05 and res[2]["sigma"] == pytest.approx(0, abs=1e-12)
    y_failed = list(y)
    y_failed[1] = None  # the first trajectory's second point
    counts = [e["effects"] for e in S.effects(X, y_failed, 3)]
    assert sum(counts) == 3 * 8 - 2


def test_values_keep_their_units_and_log_axes_are_geometric():
    pts, X = S.design({"a.b": ["0.3 GPa", "3 GPa"], "c.d": [1.0, 2.0]}, 3, 4, 7, log=("a.b",))
    for p, x in zip(pts, X):
        v, unit = S.split_value("a.b", p["a.b"])
        assert unit == "GPa" and v == pytest.approx(10 ** (math.log10(0.3) + x[0]), rel=1e-5)
        assert p["c.d"] == pytest.approx(1.0 + x[1], rel=1e-6)


@pytest.mark.parametrize("axes, word", [
    ({"a.b": ["1 m", "2 s"]}, "one unit"),
    ({"a.b": [2.0, 1.0]}, "low < high"),
    ({"a.b": [1.0, 2.0, 3.0]}, "range [low, high]"),
    ({"a.b": [True, False]}, "booleans"),
])
def test_bad_factor_ranges_are_one_line_errors(axes, word):
    with pytest.raises(InputError) as err:
        S.design(axes, 2, 4, 0)
    assert word in str(err.value) and "\n" not in str(err.value)


def _slider_load(eta, u, h_in=20e-6, h_out=10e-6, length=20e-3):
    K = h_in / h_out
    return 6 * eta * u * length**2 / (h_out**2 * (K - 1) ** 2) * (math.log(K) - 2 * (K - 1) / (K + 1))


def test_a_screened_slider_study_gives_the_closed_forms_effects(tmp_path):
    """Morris over the runner speed (2-8 m/s) and the viscosity (0.01-0.04 Pa s, log-scaled) of the
    inclined slider: each elementary effect equals the closed form's difference over the step (relative
    1e-3, the smoke mesh's accuracy on W), so mu* matches the closed-form screening of the same design."""
    study = tmp_path / "screen.toml"
    study.write_text(
        'base = "inclined_slider"\n[axes]\n"motion.velocity_lower" = ["2 m/s", "8 m/s"]\n'
        '"lubricant.viscosity" = ["0.01 Pa s", "0.04 Pa s"]\n'
        '[study]\ncombine = "morris"\nskip_outputs = true\noutputs = ["Load per unit width [N/m]"]\n'
        '[study.morris]\ntrajectories = 3\nlevels = 4\nseed = 2\nlog = ["lubricant.viscosity"]\n', encoding="utf-8")
    st = read_study(study)
    res = run_study(st, study, tmp_path / "out", smoke=True, workers=1)
    assert res.total == 3 * 3 and not res.failed
    doc = json.loads((tmp_path / "out" / "study.json").read_text())
    got = doc["Morris screening"]["outputs"]["Load per unit width [N/m]"]
    pts, X = S.design(st.axes, 3, 4, 2, log=("lubricant.viscosity",))
    exact = [_slider_load(S.split_value("e", p["lubricant.viscosity"])[0], S.split_value("u", p["motion.velocity_lower"])[0])
             for p in pts]
    want = dict(zip(st.axes, S.effects(X, exact, 2)))
    for key in st.axes:
        assert got[key]["mu*"] == pytest.approx(want[key]["mu*"], rel=1e-3)
        assert got[key]["effects"] == 3
    # the speed's effect depends on the viscosity (W ~ eta U): sigma > 0 for both
    assert got["motion.velocity_lower"]["sigma"] > 0.0


def test_morris_keys_are_checked_before_anything_runs(tmp_path):
    study = tmp_path / "bad.toml"
    study.write_text('base = "inclined_slider"\n[axes]\n"motion.velocity_lower" = ["2 m/s", "8 m/s"]\n'
                     '[study]\ncombine = "morris"\noutputs = ["Load per unit width [N/m]"]\n'
                     '[study.morris]\nlevels = 3\n', encoding="utf-8")
    with pytest.raises(StudyError) as err:
        read_study(study)
    assert "levels" in str(err.value) and "\n" not in str(err.value)
    study.write_text('base = "inclined_slider"\n[axes]\n"motion.velocity_lower" = ["2 m/s", "8 m/s"]\n'
                     '[study]\ncombine = "grid"\noutputs = ["Load per unit width [N/m]"]\n'
                     '[study.morris]\nlevels = 4\n', encoding="utf-8")
    with pytest.raises(StudyError) as err:
        read_study(study)
    assert "study.morris" in str(err.value)
