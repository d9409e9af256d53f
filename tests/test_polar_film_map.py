"""The bearing kernel's reader of the polar ball-ball film map
(lubedyn.dynamics.contacts._film_map with MAP_AXIS_POLAR) against the map itself.

Independent references: lubedyn.maps.FilmMap evaluates the shipped map in
Python on its own axes (gap, pressure number rho, squeeze angle theta), with
rho and theta from lubedyn.film_points.polar_numbers; the kernel converts
(gap, approach speed, entrainment speed) itself and returns dF/dh by the chain
rule, which is checked against a central difference of its own force.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from lubedyn import film_points as fp
from lubedyn.config import CASES_DIR
from lubedyn.maps import FilmMap
from lubedyn.dynamics import contacts as C
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.papers.zhang2024.parameters import cageless_bearing as paper_b  # noqa: E402


@pytest.fixture(scope="module")
def polar():
    fmap = FilmMap.load(CASES_DIR / "maps" / "ball_ball.npz")
    assert fmap.is_polar()
    params = fmap.provenance.get("params") or fp.ball_ball_default_params()
    model = paper_b(bearing=dict(n_balls=6), model=dict(dof="planar"), operating=dict(axial_load=0.0),
                    films=dict(ball_ball="map", map=fmap.dynamics_film_map(), viscosity=float(params["eta0"]),
                               pressure_viscosity=float(params["alpha"])))
    args = model.args()
    return fmap, params, args.bbp[0], (*args.film_map, args.counter)


@pytest.mark.parametrize("kernel", ["compiled", "py_func"])
def test_polar_reader_matches_the_map_and_its_gap_derivative(polar, kernel):
    fmap, params, bbp, (ax0, ax1, ax2, vals, opts, counter) = polar
    f = C._film_map if kernel == "compiled" else C._film_map.py_func
    rng = np.random.default_rng(3)
    h_lo, h_hi = fmap.axes[0].lo, fmap.axes[0].hi
    checked = 0
    for _ in range(12):
        h = math.exp(rng.uniform(math.log(h_lo), math.log(h_hi)))
        rho = math.exp(rng.uniform(math.log(fmap.axes[1].lo * 2), math.log(fmap.axes[1].hi / 2)))
        theta = rng.uniform(math.radians(-60.0), math.radians(85.0))
        v, ue = fp.polar_speeds(h, rho, theta, params)
        r2, t2 = fp.polar_numbers(h, v, ue, params)
        assert r2 == pytest.approx(rho, rel=1e-10) and t2 == pytest.approx(theta, rel=1e-10, abs=1e-12)
        expected = float(fmap("Force [N]", h, rho, theta))
        F, dFdh = f(h, v, ue, bbp, ax0, ax1, ax2, vals, opts, counter)
        assert F == pytest.approx(expected, rel=1e-8)
        dh = 1e-6 * h
        Fp, _ = f(h + dh, v, ue, bbp, ax0, ax1, ax2, vals, opts, counter)
        Fm, _ = f(h - dh, v, ue, bbp, ax0, ax1, ax2, vals, opts, counter)
        if h - dh > h_lo and h + dh < h_hi:
            assert dFdh == pytest.approx((Fp - Fm) / (2 * dh), rel=1e-5)
            checked += 1
    assert checked >= 8


def test_map_ends_in_the_parameters_change_no_bit(polar):
    """The bearing's parameter record carries the map's axis ends (``with_map_ends``, read instead of four
    exponentials a film read); a record without them (as ``ball_ball_parameters`` returns it) makes the
    kernels compute them from the axes: the collision's force, film, approach, phase and share are the
    same to the bit, across the lock, the map's gap range, above it and in separation."""
    from lubedyn.lubrication.laws import collision as LC

    fmap, params, bbp, (ax0, ax1, ax2, vals, opts, counter) = polar
    ends = [bbp.map_h0, bbp.map_htop, bbp.map_x1lo, bbp.map_x1top]
    assert ends == pytest.approx([fmap.axes[0].lo, fmap.axes[0].hi, fmap.axes[1].lo, fmap.axes[1].hi], rel=1e-12)
    bare = LC.ball_ball_row(bbp)[0]
    bare.map_h0 = bare.map_htop = bare.map_x1lo = bare.map_x1top = np.nan
    assert bare.r == bbp.r and math.isnan(bare.map_h0) and not math.isnan(bbp.map_h0)
    rng = np.random.default_rng(7)
    phases = set()
    for _ in range(400):
        g = math.exp(rng.uniform(math.log(1e-8), math.log(2e-4))) * rng.choice([-0.01, 1.0])
        v, ue = rng.uniform(-1.0, 3.0), rng.uniform(0.0, 8.0)
        a = C.ball_ball_normal(g, v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts, counter)
        b = C.ball_ball_normal(g, v, ue, 0.0, bare, C.FILM_MAP, ax0, ax1, ax2, vals, opts, counter)
        assert a == b
        phases.add(a[3])
    assert len(phases) >= 2


# ----------------------------------------------------------------------------- beyond the map's axes
def test_above_the_last_gap_node_the_reader_matches_a_reynolds_solve(polar):
    """Above the map's last gap node (50 um) the reader scales the film self-similarly (F = h Phi(rho,
    theta)); checked against a scikit-fem Reynolds solve of the film itself at 120 and 300 um (below the
    starvation cut-off h_cut = R/10 = 476 um), with no clamped query."""
    fmap, params, bbp, (ax0, ax1, ax2, vals, opts, _) = polar
    counter = np.zeros(1, dtype=np.int64)
    for h, v, ue in ((120e-6, 2.0, 3.0), (300e-6, 5.0, 0.5)):
        F, dFdh = C._film_map(h, v, ue, bbp, ax0, ax1, ax2, vals, opts, counter)
        ref = fp.evaluate_ball_ball(dict(params, resolution="default"),
                                    {"Central gap [m]": h, "Approach speed [m/s]": v, "Entrainment speed [m/s]": ue})
        assert F == pytest.approx(ref["Force [N]"], rel=0.03)
        # dF/dh by the chain rule against the film's own stiffness K = -dF/dh0
        assert -dFdh == pytest.approx(ref["Stiffness [N/m]"], rel=0.05)
    assert counter[0] == 0


@pytest.mark.parametrize("v, ue", [(1.0, 0.0), (0.0, 2.0), (0.3, 1.0), (-0.01, 4.0), (-2.0, 0.1)])
def test_locked_gap_is_where_the_pressure_number_reaches_the_lock(polar, v, ue):
    """h_L solves rho(h) = rho_lock: against the closed forms of the pure cases (pure squeeze h =
    sqrt(sqf |v|/rho), pure entrainment h = (2 (sqf u_e)^2/(R rho^2))^(1/3)) and, for mixed ones, against
    lubedyn.film_points.polar_numbers (the map builder's own definition of rho); the entrainment
    regularisation u_reg shifts h_L as u_e -> sqrt(u_e^2 + u_reg^2)."""
    fmap, params, bbp, _ = polar
    sqf, R = bbp.sqf, bbp.r
    h = C.locked_gap(v, ue, sqf, R, 0.9, 0.0)
    if ue == 0.0:
        assert h == pytest.approx(math.sqrt(sqf * abs(v) / 0.9), rel=1e-12)
    elif v == 0.0:
        assert h == pytest.approx((2.0 * (sqf * ue) ** 2 / (R * 0.81)) ** (1.0 / 3.0), rel=1e-12)
    rho, theta = fp.polar_numbers(h, v, ue, params)
    assert rho == pytest.approx(0.9, rel=1e-10)
    u_reg = 0.01
    h_reg = C.locked_gap(v, ue, sqf, R, 0.9, u_reg)
    assert fp.polar_numbers(h_reg, v, math.hypot(ue, u_reg), params)[0] == pytest.approx(0.9, rel=1e-10)
    assert C.locked_gap(0.0, 0.0, sqf, R, 0.9, 0.0) == 0.0


def test_a_locked_film_hands_the_load_to_the_solids(polar):
    """Below h_L the rigid piezoviscous film has left the map (towards Barus' pole): the pair carries the
    Hertz force of the approach h_L - g through a film of thickness h_L (Hertz written here from E* and
    R_eff, elastic approaches only) and the entrapped film's damping, continuous with the film branch at the lock, and never a clamped
    query."""
    from lubedyn.lubrication.laws.collision import PHASE_FILM
    from lubedyn.lubrication.laws.contact import reduced_modulus

    fmap, params, bbp, (ax0, ax1, ax2, vals, opts, _) = polar
    K = 4.0 / 3.0 * reduced_modulus(207e9, 0.29, 207e9, 0.29) * math.sqrt(bbp.r)  # paper B's balls
    counter = np.zeros(1, dtype=np.int64)
    v, ue = 1.0, 1.0
    hL = C.locked_gap(v, ue, bbp.sqf, bbp.r, 0.9 * (1 - 1e-9), bbp.vreg)
    f_lock, _ = C._film_map(hL, v, ue, bbp, ax0, ax1, ax2, vals, opts, counter)
    g_star = hL - (f_lock / K) ** (2.0 / 3.0)  # below it the film is locked
    for g in (g_star - 0.05e-6, g_star - 0.2e-6, g_star - 0.4e-6):
        F, h, x, phase, share = C.ball_ball_normal(g, v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts,
                                                   counter)
        assert phase == PHASE_FILM and share == 1.0
        assert h == pytest.approx(hL, rel=1e-12) and x == pytest.approx(hL - g, rel=1e-9)
        # plus the entrapped film's damping beta C0 v/h_L, weighted by the solids' share beyond the lock
        Fs = K * (hL - g) ** 1.5
        assert bbp.bent > 0.0
        assert F == pytest.approx(Fs + bbp.bent * bbp.c0 * v / hL * (1.0 - f_lock / Fs), rel=1e-9)
    # continuity at the lock: where the solids carry exactly the film's force at h_L, both branches meet
    above = C.ball_ball_normal(g_star * (1 + 1e-7), v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts,
                               counter)
    below = C.ball_ball_normal(g_star * (1 - 1e-7), v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts,
                               counter)
    assert above[1] > hL and below[1] == pytest.approx(hL, rel=1e-12)
    assert above[0] == pytest.approx(f_lock, rel=1e-4) and below[0] == pytest.approx(f_lock, rel=1e-4)
    assert counter[0] == 0


def test_a_kept_film_locks_at_its_thickness_at_any_approach_speed(polar):
    """``h_keep`` (an entrapped film the lock keeps): near the turnaround of an impact (v -> 0, where h_L(v)
    -> 0) the pair carries the Hertz force of the approach h_keep - g through a film of thickness h_keep;
    with h_keep below h_L(v) nothing changes (bit for bit)."""
    from lubedyn.lubrication.laws.contact import reduced_modulus

    fmap, params, bbp, (ax0, ax1, ax2, vals, opts, _) = polar
    bbp = np.array([bbp]).view(np.recarray)[0]
    bbp.bent = 0.0  # the lock alone (its damping: test_a_locked_film_hands_the_load_to_the_solids)
    K = 4.0 / 3.0 * reduced_modulus(207e9, 0.29, 207e9, 0.29) * math.sqrt(bbp.r)
    counter = np.zeros(1, dtype=np.int64)
    ue, keep = 0.0, C.locked_gap(0.2, 0.0, bbp.sqf, bbp.r, 0.9 * (1 - 1e-9), bbp.vreg)
    for v in (1e-3, 1e-2):
        assert C.locked_gap(v, ue, bbp.sqf, bbp.r, 0.9 * (1 - 1e-9), bbp.vreg) < 0.3 * keep
        for g in (-0.3e-6, -1e-6):  # elastic: below the yield approach (3.4 um here)
            F, h, x, phase, share = C.ball_ball_normal(g, v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts,
                                                       counter, keep)
            assert h == pytest.approx(keep, rel=1e-12) and share == 1.0
            assert F == pytest.approx(K * (keep - g) ** 1.5, rel=1e-9)
    g, v = -1e-6, 1.0  # h_L(1 m/s) > keep: the kept film plays no part
    assert (C.ball_ball_normal(g, v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts, counter, 0.5 * keep)
            == C.ball_ball_normal(g, v, ue, 0.0, bbp, C.FILM_MAP, ax0, ax1, ax2, vals, opts, counter))
    assert counter[0] == 0


def test_a_speed_axis_that_differs_from_the_maps_own_is_refused():
    """A polar map names its own speed axis (lubedyn.dynamics.cageless.layout.BallBallMap): the bearing takes
    it when films.map_speed_axis is not given, and refuses a different one by the key, not overriding it."""
    from lubedyn.dynamics.cageless import BallBallMap

    fmap = FilmMap.load(CASES_DIR / "maps" / "ball_ball.npz")
    arrays = fmap.dynamics_film_map()
    assert isinstance(arrays, BallBallMap) and arrays.speed_axis == "polar"
    films = dict(ball_ball="map", map=arrays, viscosity=0.01, pressure_viscosity=2e-8)
    model = paper_b(films=films)
    assert model.args().film_map.opts[C.MO_AXIS1] == C.MAP_AXIS_POLAR
    with pytest.raises(DynamicsInputError, match="films.map_speed_axis") as err:
        paper_b(films=films | {"map_speed_axis": "squeeze_number"}).args()
    assert "'polar'" in str(err.value)


def test_fixed_map_options_change_no_bit(polar):
    """The model hands the map's options to the kernels as compile-time constants
    (lubedyn.dynamics.interp.Fixed, issue 42 decision 7): the film read gives the bits of the same options
    in a runtime int64 array, at 400 random states over gaps, approach and entrainment speeds (and the same
    clamp counts)."""
    from lubedyn.dynamics.interp import Fixed

    _, _, p, (ax0, ax1, ax2, vals, opts, _) = polar
    assert all(isinstance(o, Fixed) for o in opts)
    r = np.random.default_rng(7)
    h = np.exp(r.uniform(math.log(math.exp(ax0[0]) * 0.5), math.log(math.exp(ax0[-1]) * 2.0), 400))
    v, ue = r.uniform(-0.05, 1.0, 400), r.uniform(0.0, 5.0, 400)
    got = []
    for o in (opts, np.array(opts, dtype=np.int64)):
        counter = np.zeros(1, np.int64)
        got.append((np.array([C._film_map(*s, p, ax0, ax1, ax2, vals, o, counter) for s in zip(h, v, ue)]),
                    int(counter[0])))
    assert got[0][1] == got[1][1]
    assert np.array_equal(got[0][0], got[1][0], equal_nan=True)
    assert np.count_nonzero(got[0][0][:, 0]) > 100  # most states carry a film force
