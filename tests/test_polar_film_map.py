"""The bearing kernel's reader of the polar ball-ball film map
(dynamics.contacts._film_map with MAP_AXIS_POLAR) against the map itself.

Independent references: coupling.maps.FilmMap evaluates the shipped map in
Python on its own axes (gap, pressure number rho, squeeze angle theta), with
rho and theta from coupling.film_points.polar_numbers; the kernel converts
(gap, approach speed, entrainment speed) itself and returns dF/dh by the chain
rule, which is checked against a central difference of its own force.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from coupling import film_points as fp
from coupling.config import CASES_DIR
from coupling.maps import FilmMap
from dynamics import contacts as C
from coupling.parameters.zhang2024 import cageless_bearing as paper_b  # noqa: E402


@pytest.fixture(scope="module")
def polar():
    fmap = FilmMap.load(CASES_DIR / "maps" / "ball_ball.npz")
    assert fmap.is_polar()
    params = fmap.provenance.get("params") or fp.ball_ball_default_params()
    model = paper_b(bearing=dict(n_balls=6), model=dict(dof="planar"), operating=dict(axial_load=0.0),
                    films=dict(ball_ball="map", map=fmap.dynamics_film_map(), viscosity=float(params["eta0"]),
                               pressure_viscosity=float(params["alpha"])))
    args = model.args()
    return fmap, params, args[2], args[4:10]


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
