"""Per-direction exponents from the tangent space (lubedyn.dynamics.tangent_directions).

References independent of the code: Lorenz (sigma 10, rho 28, beta 8/3) lambda_1 = 0.9056 1/s (Sprott,
*Chaos and time-series analysis*, 2003; tests/test_lyapunov.py); a linear block dx/dt = A x with A a rotation
at 2 rad/s decaying at 0.5 1/s has both exponents -0.5 1/s (A's eigenvalues -0.5 +- 2i).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from numba import njit

from lubedyn.dynamics import integrators as I
from lubedyn.dynamics import tangent_directions as TD
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.lyapunov import BenettinRun, lyapunov_spectrum

from test_lyapunov import LORENZ, LORENZ_L1, lorenz, lorenz_jvp

DECAY, TURN = 0.5, 2.0
#: sigma(T) sqrt(T) of Lorenz' finite-time lambda_1 [1/sqrt(s)] (measured by test_run_length_rule_predicts_the_spread:
#: 0.47): a finite record's lambda_1 is compared with 0.9056 within 3 sigma(T)
LORENZ_C = 0.5


@njit(cache=True)
def lorenz_and_linear(t, y, args, dydt):
    """Lorenz in y[0:3], dx/dt = A x in y[3:5] (A = [[-d, w], [-w, -d]]): a direct product."""
    s, r, b, d, w = args
    dydt[0] = s * (y[1] - y[0])
    dydt[1] = y[0] * (r - y[2]) - y[1]
    dydt[2] = y[0] * y[1] - b * y[2]
    dydt[3] = -d * y[3] + w * y[4]
    dydt[4] = -w * y[3] - d * y[4]


@njit(cache=True)
def lorenz_and_linear_jvp(t, y, v, args, out):
    s, r, b, d, w = args
    out[0] = s * (v[1] - v[0])
    out[1] = (r - y[2]) * v[0] - v[1] - y[0] * v[2]
    out[2] = y[1] * v[0] + y[0] * v[1] - b * v[2]
    out[3] = -d * v[3] + w * v[4]
    out[4] = -w * v[3] - d * v[4]


@pytest.fixture(scope="module")
def on_attractor():
    return I.integrate(lorenz, [1.0, 1.0, 20.0], [0.0, 20.0], LORENZ, rtol=1e-10, atol=1e-10).y[-1]


def lorenz_directions(y0, t_total, *, seed=0, jvp=lorenz_jvp):
    run = BenettinRun(lorenz, y0, LORENZ, dt=0.01, t_orth=0.05, t_transient=10.0, n_exponents=1, jvp=jvp, seed=seed)
    return TD.TangentDirections(run, TD.CoordinateDirections({"x": 0, "y": 1, "z": 2})).advance(t_total)


def test_coupled_directions_all_give_lambda_1(on_attractor):
    """Lorenz' x, y and z are coupled: each direction's exponent is lambda_1 (relation (1)), measured at
    T = 400 s: 0.905-0.909 1/s against 0.9056; the first vector's shares x 0.16, y 0.37, z 0.47 sum to 1;
    the largest lies inside max_bound; lambda_1 is the one lyapunov_spectrum gives for the same run."""
    res = lorenz_directions(on_attractor, 400.0).result()
    assert res.largest == pytest.approx(LORENZ_L1, abs=3 * LORENZ_C / math.sqrt(400.0))
    assert res.exponents == pytest.approx(res.largest, abs=0.01)  # the boundary term of (1)
    assert res.share.sum() == pytest.approx(1.0, rel=1e-12)
    low, high = res.max_bound
    assert low <= res.exponents.max() <= high and high - low < 0.01
    spec = lyapunov_spectrum(lorenz, on_attractor, LORENZ, dt=0.01, t_orth=0.05, t_transient=10.0, t_total=400.0,
                             n_exponents=1, jvp=lorenz_jvp)
    assert res.largest == spec.exponents[0]
    assert res.lambda_T == pytest.approx(res.exponents * 400.0)


@pytest.mark.parametrize("use_jvp", [True, False])
def test_direct_product_gives_each_block_its_own_exponent(on_attractor, use_jvp):
    """Lorenz x linear decay: the Lorenz coordinates give 0.906 1/s, the linear block -0.5 1/s (its
    eigenvalues' real part), with a jvp and with forward differences.  The linear block's rotation keeps
    the norm, so its exponent is exact; the Lorenz block's is its finite-time lambda_1 (within 3 sigma(T) of
    0.9056).  Measured at T = 300 s: Lorenz 0.912-0.917, linear RK4's own rate (-0.5 + 2.9e-9) to 1e-12 (jvp) and 3e-6
    (forward differences)."""
    y0 = np.concatenate([on_attractor, [0.0, 0.0]])
    args = LORENZ + (DECAY, TURN)
    run = BenettinRun(lorenz_and_linear, y0, args, dt=0.01, t_orth=0.05, t_transient=10.0, n_exponents=1,
                      jvp=lorenz_and_linear_jvp if use_jvp else None)
    proj = TD.CoordinateDirections({"x": 0, "y": 1, "z": 2, "lorenz": [0, 1, 2], "linear": [3, 4]},
                                   complete=[3, 4])
    res = TD.TangentDirections(run, proj).advance(300.0).result()
    lam = dict(zip(res.names, res.exponents))
    for name in ("x", "y", "z", "lorenz"):
        assert lam[name] == pytest.approx(LORENZ_L1, abs=3 * LORENZ_C / math.sqrt(300.0))
        assert lam[name] == pytest.approx(res.largest, abs=0.02)
    z = complex(-DECAY, TURN) * 0.01  # RK4's growth factor per step of the linear block: its exact discrete rate
    rk4 = math.log(abs(1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24)) / 0.01
    assert rk4 == pytest.approx(-DECAY, abs=1e-8)
    assert lam["linear"] == pytest.approx(rk4, abs=1e-12 if use_jvp else 1e-5)
    assert res.share[3] == pytest.approx(1.0, abs=1e-12)  # the first Lyapunov vector lives in the Lorenz block


def test_chunks_and_save_load_give_the_bits_of_one_run(on_attractor, tmp_path):
    """Advancing in pieces and resuming from saved files (state, tangent basis, log sums, projections)
    gives the exponents, running estimates and shares of one run to the last bit."""
    one = lorenz_directions(on_attractor, 30.0).result()
    td = lorenz_directions(on_attractor, 10.0)
    td.save(tmp_path / "run.npz")
    td = TD.TangentDirections.load(tmp_path / "run.npz", lorenz, LORENZ,
                                   TD.CoordinateDirections({"x": 0, "y": 1, "z": 2}), jvp=lorenz_jvp)
    td.advance(7.0).advance(13.0)
    cut = td.result()
    for a, b in ((one.exponents, cut.exponents), (one.running, cut.running), (one.share, cut.share),
                 (one.running_largest, cut.running_largest)):
        assert np.array_equal(a, b)
    assert np.array_equal(td.run.y, lorenz_directions(on_attractor, 30.0).run.y)


def test_run_length_rule_bounds_the_spread_further_on(on_attractor):
    """The rule from 16 members started at different points of the attractor, fitted on T <= 300 s, against
    the members' spread at 2,000 s: sigma(T_end) sqrt(T_end / T) bounds it (the finite-time exponent's
    spread falls faster than 1/sqrt(T) there: slope -0.8 to -1, a boundary term), by a factor 1.4-1.8
    measured (16 and 32 members, T_end 400 s, later 3,000 s).  The standard deviation of 16 samples has a
    relative standard error of 18 %: the bound is asserted with 1.2 for that, and that it is not loose by
    more than 3."""
    starts = I.integrate(lorenz, on_attractor, np.arange(16) * 7.3, LORENZ, rtol=1e-10, atol=1e-10).y
    members = [lyapunov_spectrum(lorenz, y, LORENZ, dt=0.01, t_orth=0.05, t_transient=10.0, t_total=2000.0,
                                 n_exponents=1, jvp=lorenz_jvp) for y in starts]
    times = members[0].times
    early = times <= 300.0
    rule = TD.run_length(times[early], np.array([m.running[early, 0] for m in members]), rel=0.05)
    assert -1.1 <= rule.slope <= -0.5
    predicted = rule.spread * math.sqrt(times[early][-1] / 2000.0)
    measured = float(np.std([m.exponents[0] for m in members], ddof=1))
    assert predicted / 3.0 <= measured <= 1.2 * predicted
    assert rule.required == pytest.approx(rule.spread ** 2 * times[early][-1] / (0.05 * rule.mean) ** 2)
    assert rule.required_mean == pytest.approx(rule.required / 16)


def test_bad_input(on_attractor):
    with pytest.raises(DynamicsInputError, match="t_total"):
        lorenz_directions(on_attractor, 1.0).advance(-1.0)
    with pytest.raises(DynamicsInputError, match="members"):
        TD.run_length([1.0, 2.0], [[1.0, 2.0]])
    with pytest.raises(DynamicsInputError, match="no 'Ball j"):
        TD.BallDirections([("x", "m")])
