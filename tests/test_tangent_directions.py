"""Per-direction exponents from the tangent space (lubedyn.dynamics.tangent_directions).

References independent of the code: Lorenz (sigma 10, rho 28, beta 8/3) lambda_1 = 0.9056 1/s (Sprott,
*Chaos and time-series analysis*, 2003; tests/test_lyapunov.py); a linear block dx/dt = A x with A a rotation
at 2 rad/s decaying at 0.5 1/s has both exponents -0.5 1/s (A's eigenvalues -0.5 +- 2i).
"""
from __future__ import annotations

import json
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
    the members' spread at 2,000 s: sigma(T_end) sqrt(T_end / T) bounds it under the model (the finite-time
    exponent's spread falls faster than 1/sqrt(T) there: slope -0.75, a boundary term).  Measured: predicted
    0.00258, measured 0.00273 1/s (0.95); with 16 and 32 members from 400 s to 3,000 s 1.4-1.8.  The standard
    deviation of 16 samples has a relative standard error of 18 %: the bound is asserted with 1.2 for that,
    and that it is not loose by more than 3."""
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
    # windows of each member: c_w^2 = window var(window exponents) = c^2 + 2 a^2 / window, an upper bound that
    # falls with the window (measured c_w 0.39, 0.26, 0.21 at 20, 50, 100 s: sigma(2,000 s) predicted 0.0087,
    # 0.0059, 0.0048 against 0.0027)
    R = np.array([m.running[:, 0] for m in members])
    c_w = [TD.run_length(times, R, rel=0.05, window=w).c_windows for w in (20.0, 100.0)]
    assert c_w[0] > c_w[1] >= measured * math.sqrt(2000.0) / 1.2


def test_ball_directions_by_hand():
    """Ball 0 at (0, 1, 0): e_r = (0, 1, 0), e_t = e_z x e_r = (-1, 0, 0); ball 1 at (1, 0, 0): e_r = e_x,
    e_t = e_y.  A position perturbation (1, 2, 3) of each: radial 2 and 1, tangential |-1| and 2, axial 3;
    inertial x 1, y 2; all balls: norms over the balls."""
    layout = [("Inner ring x", "m")] + [(f"Ball {j} {c}", "m") for j in range(2) for c in ("x", "y", "z", "q0")]
    proj = TD.BallDirections(layout, inertial=True)
    y, v = np.zeros(9), np.zeros(9)
    y[1:4], y[5:8] = (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    v[1:4] = v[5:8] = (1.0, 2.0, 3.0)
    got = dict(zip(proj.names, proj(y, v)))
    want = {"ball 0 radial": 2.0, "ball 0 tangential": 1.0, "ball 0 axial": 3.0, "ball 1 radial": 1.0,
            "ball 1 tangential": 2.0, "ball 1 axial": 3.0, "radial (all balls)": math.sqrt(5.0),
            "tangential (all balls)": math.sqrt(5.0), "axial (all balls)": math.sqrt(18.0), "ball 0 x": 1.0,
            "ball 0 y": 2.0, "ball 1 x": 1.0, "ball 1 y": 2.0, "x (all balls)": math.sqrt(2.0),
            "y (all balls)": math.sqrt(8.0)}
    assert got == pytest.approx(want, rel=1e-15)
    assert list(proj.complete) == list(range(6))
    with pytest.raises(DynamicsInputError, match="share one scale"):
        TD.BallDirections(layout, scale=[1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0])


def test_bad_input(on_attractor):
    with pytest.raises(DynamicsInputError, match="t_total"):
        lorenz_directions(on_attractor, 1.0).advance(-1.0)
    with pytest.raises(DynamicsInputError, match="members"):
        TD.run_length([1.0, 2.0], [[1.0, 2.0]])
    with pytest.raises(DynamicsInputError, match="no 'Ball j"):
        TD.BallDirections([("x", "m")])


# --- the cage-less bearing ----------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def drop_model():
    from lubedyn.config import load_case
    from lubedyn.scenes.dynamics import build

    return build(load_case("cageless_6206_10krpm_short", smoke=True), None)


def approaching_pair(setup, speed, gap):
    """The drop's start with ball 0 turned about the axis to ``gap`` [m] from ball 1 and moving towards it
    at ``speed`` [m/s]: a ball-ball film contact starts and ends within 0.4 ms."""
    m, y0 = setup.model, setup.y0.copy()
    names = [n for n, _ in m.state_layout()]
    i0, i1, iv = names.index("Ball 0 x"), names.index("Ball 1 x"), names.index("Ball 0 vx")
    p0 = y0[i0:i0 + 3].copy()
    d = y0[i1:i1 + 3] - p0
    now = np.linalg.norm(d) - m.bearing.ball_diameter
    a = math.copysign((now - gap) / math.hypot(p0[0], p0[1]), p0[0] * d[1] - p0[1] * d[0])
    y0[i0], y0[i0 + 1] = math.cos(a) * p0[0] - math.sin(a) * p0[1], math.sin(a) * p0[0] + math.cos(a) * p0[1]
    d = y0[i1:i1 + 3] - y0[i0:i0 + 3]
    y0[iv:iv + 3] += speed * d / np.linalg.norm(d)
    return y0


@pytest.mark.slow
def test_tangent_follows_the_secant_across_contact_onsets(drop_model):
    """No saltation matrix is needed where the forces are continuous (module docstring): over 0.4 ms of the
    10,000 rpm drop in which a ball-ball film contact starts and ends (ball 0 sent at 0.3 m/s towards ball
    1, 20 um away) and inner-race contacts start, the kernel's tangent vector (forward differences) and the
    secant (y(y0 + eps v0) - y(y0)) / eps of two trajectories of the same RK4 agree to first order in eps:
    relative difference 0.102, 0.0137, 0.0022 at eps = 1e-2, 1e-3, 1e-4 (scaled units; 1e-4 is 0.1 nm of
    a ball position).  A jump of the state or of the vector field would leave an O(1) difference."""
    from lubedyn.dynamics.cageless import D_PHASE, D_QI, forces_many, rhs
    from lubedyn.scenes.dynamics_lyapunov import bearing_tangent_directions, memory_states

    m = drop_model.model
    y0 = approaching_pair(drop_model, 0.3, 20e-6)
    run = bearing_tangent_directions(m, y0).run
    v0 = run.V[0].copy()
    states, times = [run.y.copy()], [0.0]
    n = int(math.ceil(4e-4 / run.interval))
    run.advance(n, observe=lambda r: (states.append(r.y.copy()), times.append(r.t)))
    diag, _ = forces_many(np.array(times), np.array(states), m.args())
    phase, qi = diag[:, 0, D_PHASE], diag[:, :, D_QI]
    assert phase[0] == 1 and phase[-1] == 0  # the pair's film carries load, then the balls separate
    assert np.sum((qi[:-1] == 0.0) & (qi[1:] > 0.0)) >= 1  # an inner-race contact starts
    keep = run.keep == 1.0
    tangent = (run.V[0] * math.exp(run.log_sum[0]))[keep]

    def secant(eps):
        pair = [BenettinRun(rhs, y, m.args(), scale=run.scale, dt=run.dt, t_orth=run.interval, n_exponents=1,
                            frozen=memory_states(m)) for y in (y0, y0 + eps * v0 * run.scale)]
        for r in pair:
            r.advance(n)
        s = ((pair[1].z - pair[0].z) / eps)[keep]
        return np.linalg.norm(s - np.sign(s @ tangent) * tangent) / np.linalg.norm(tangent)

    d = [secant(eps) for eps in (1e-3, 1e-4)]
    assert d[1] < 5e-3 and d[0] / d[1] > 4.0


@pytest.mark.slow
def test_scene_writes_direction_exponents_bounded_by_the_whole_system_lambda_1(tmp_path):
    """``analysis.tangent_directions = true`` on the main job's smoke run (1 ms): every per-direction value
    is finite, in 1/s and bits/s; the three all-ball shares sum to 1; the largest all-ball direction exponent
    lies within the bound that relation (1) gives around the whole-system lambda_1 (here the first vector's
    is exponent 1); and the whole-system exponents are the bits of the run without the projections.
    Measured: lambda_1 3,018 1/s, directions 1,354 (radial), 2,528 (tangential), 2,025 (axial) 1/s in the
    bound [-454, 8,264] 1/s: at 1 ms the boundary term (1/T) log p is of the size of lambda_1; the bound
    narrows as 1/T (on Lorenz at 400 s to 0.01 1/s, test_coupled_directions_all_give_lambda_1)."""
    from lubedyn import cli
    from lubedyn.config import CASES_DIR

    short = CASES_DIR / "cageless_6206_10krpm_short.toml"
    summaries = {}
    for on in (True, False):
        out = tmp_path / str(on)
        code = cli.main(["run", str(short), "--smoke", "--set", f"analysis.tangent_directions={str(on).lower()}",
                         "--set", "output.write=[]", "--out", str(out)])
        assert code == 0
        summaries[on] = json.loads((out / "summary.json").read_text())
    s = summaries[True]
    lam1 = s["Lyapunov exponent 1, whole system (Benettin) [1/s]"]
    assert s["Tangent-space largest exponent, first vector [1/s]"] == lam1
    for i in (1, 2):
        key = f"Lyapunov exponent {i}, whole system (Benettin) [1/s]"
        assert s[key] == summaries[False][key]
    assert not any(k.startswith("Tangent-space") for k in summaries[False])
    directions = [f"ball 0 {d}" for d in TD.CO_ROTATING + ("x", "y")] + [
        f"{d} (all balls)" for d in TD.CO_ROTATING + ("x", "y")]
    for d in directions:
        lam = s[f"Tangent-space exponent, {d} [1/s]"]
        assert math.isfinite(lam) and s[f"Tangent-space exponent, {d} [bits/s]"] == pytest.approx(lam / math.log(2))
        assert s[f"Tangent-space exponent, {d} lambda T [-]"] == pytest.approx(lam * s["Tangent-space averaging time [s]"])
    shares = [s[f"Tangent-space exponent, {d} (all balls) share [-]"] for d in TD.CO_ROTATING]
    assert sum(shares) == pytest.approx(1.0, abs=1e-9)
    low, high = s["Tangent-space largest direction exponent, bound from the first vector [1/s]"]
    largest = max(s[f"Tangent-space exponent, {d} (all balls) [1/s]"] for d in TD.CO_ROTATING)
    assert low <= largest <= high
