"""Pure squeeze EHL contacts (entrainment u_m = 0) of lubedyn.lubrication.ehl, against independent values.

- rigid isoviscous sphere-plane squeeze film: on the square domain |x|, |y| <= L with p = 0 on its edge the
  force lies between the closed forms with p = 0 on the inscribed (radius L) and circumscribed (radius
  sqrt(2) L) disks (maximum principle: the pressure grows with the domain);
- heavily loaded isoviscous film: the film is nearly uniform over the Hertz zone, so the rigid-body
  approach plus the central film is the Hertz approach of the load.
"""
import math

import pytest

import lubedyn.lubrication as lub
from lubedyn.lubrication.closed_form import sphere_plane_squeeze_force
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, solve_ehl
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws import contact as hertz

R = 0.0047625 / 2  # two 6206 balls (paper B): R_eff = R/2
ETA = 0.05


def _oil():
    return lub.Lubricant(lub.ConstantViscosity(ETA), lub.Incompressible(992.0))


def test_rigid_isoviscous_squeeze_between_disk_bounds():
    """129 x 129 nodes, h0 = 1 um, v = 0.01 m/s, E* = 1e14 Pa (rigid: h_c = h0 to 4e-6), L^2/(2R) = 40 h0.
    Measured W = 5.0966e-2 N against bounds 5.0867e-2 / 5.2130e-2 (33 / 65 nodes: 4.709e-2 / 5.014e-2,
    second order from below, Richardson 5.124e-2)."""
    h0, v = 1e-6, 0.01
    L = math.sqrt(2 * R * 40 * h0)
    b = hertz.point_contact(1.0, R, R, 1e14).a
    c = EHLContact(R, R, 1e14, _oil(), 0.0, approach=h0, squeeze_velocity=-v, scale_load=1.0)
    s = solve_ehl(c, EHLGrid(nx=129, ny=129, x_min=-L / b, x_max=L / b, y_max=L / b), EHLOptions())
    lo = sphere_plane_squeeze_force(R, h0, ETA, -v, L)
    hi = sphere_plane_squeeze_force(R, h0, ETA, -v, math.sqrt(2) * L)
    assert lo < s.load < hi
    assert s.central_film_thickness == pytest.approx(h0, rel=1e-5)


def test_heavy_isoviscous_squeeze_approach_is_hertz():
    """Q = 100 N, v = 0.1 m/s, steel balls (E* = 113 GPa), 33 x 33 nodes on |x|, |y| <= 3 a: measured
    -h00 = 5.2885 um, h_c = 0.498 um, their sum 5.787 um against Hertz 5.698 um (+1.6 %: the film is not
    quite uniform over the Hertz zone, h_min 0.303 um at the rim)."""
    es = 113003603013.43
    Q, v = 100.0, 0.1
    hp = hertz.point_contact(Q, R, R, es)
    c = EHLContact(R, R, es, _oil(), 0.0, load=Q, squeeze_velocity=-v)
    s = solve_ehl(c, EHLGrid(nx=33, ny=33, x_min=-3, x_max=3, y_max=3), EHLOptions())
    assert s.load == pytest.approx(Q, rel=1e-6)
    assert -s.h00 + s.central_film_thickness == pytest.approx(hp.approach, rel=0.02)
    assert s.minimum_film_thickness < s.central_film_thickness
    # a squeeze film, not a trapped-oil state: the largest pressure is the Hertz pressure's (measured 1.04 x)
    assert s.info["checks"]["squeeze_pressure"]["ratio"] == pytest.approx(1.0, abs=0.1) and not s.info["warnings"]


def test_trapped_oil_state_of_a_piezoviscous_squeeze_is_flagged():
    """Roelands (paper B's oil), 0.1 N, 1e-3 m/s, 33 x 33 nodes from the squeeze start: Newton converges to a
    state peaking at 19.5 GPa, 55 x the Hertz pressure (17 / 25 nodes: 1.65 / 2.1 x: no grid-independent
    quasi-steady film), which the solver's a-posteriori check names (and raises under EHLOptions.strict)."""
    from lubedyn.lubrication.errors import ConvergenceError
    from lubedyn.lubrication.laws.lubricant import Roelands

    oil = lub.Lubricant(Roelands(ETA, alpha=1.85e-8), lub.Incompressible(992.0))
    c = EHLContact(R, R, 113003603013.43, oil, 0.0, load=0.1, squeeze_velocity=-1e-3)
    grid = EHLGrid(nx=33, ny=33, x_min=-3, x_max=3, y_max=3)
    s = solve_ehl(c, grid, EHLOptions())
    assert s.info["checks"]["squeeze_pressure"]["ratio"] > 3.0
    assert any("trapped-oil state" in w for w in s.info["warnings"])
    with pytest.raises(ConvergenceError, match="trapped-oil state"):
        solve_ehl(c, grid, EHLOptions(strict=True))


def test_pure_squeeze_needs_an_approach():
    with pytest.raises(InputError, match="squeeze_velocity"):
        EHLContact(R, R, 1e11, _oil(), 0.0, load=1.0, squeeze_velocity=0.0)
    with pytest.raises(InputError, match="mean"):
        EHLContact(R, R, 1e11, _oil(), -1.0, load=1.0)
