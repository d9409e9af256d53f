"""Reynolds-Eyring flow in the EHL solver (``Lubricant(eyring_stress=tau0)``).

Checked against:
- the sinh law integrated across the film by quadrature (the flow factor's derivation);
- the Newtonian solver (tau0 -> infinity);
- the scikit-fem reference assembly (discrete complementarity of a returned state) and, in
  tests/test_ehl_point.py, finite differences of the residual (exact Jacobian) and the
  vectorised-against-scikit-fem assembly;
- uniqueness: on paper A's roller contact the Newtonian problem has two exact discrete
  solutions (pinned here: where the Newtonian method stops being a function of the load),
  the Eyring problem one;
- a second method for K and C (load steps against the linearised equations).
"""
import dataclasses

import numpy as np
import pytest
from scipy.integrate import quad

from lubedyn.lubrication import Barus, Film, InputError, Lubricant
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, multigrid_grid, solve_ehl
from lubedyn.lubrication.laws.lubricant import Incompressible, eyring_flow_factor

from test_ehl import _complementarity


def _sinh_law_flow_factor(x):
    """Poiseuille flow of the sinh law over the Newtonian one, by quadrature of the velocity.

    Film -h/2..h/2, pressure gradient G, shear stress tau(z) = G z (pure rolling: tau = 0 at
    mid-film), shear rate (tau0/eta) sinh(tau/tau0); velocity u(z) = int_z^{h/2} rate (in closed
    form: a nested quadrature could not meet its tolerance where u -> 0), flow int u dz by
    quadrature.  Units: h = 2, tau0 = 1, eta = 1, so G = x (x = h G/(2 tau0))."""
    h, G = 2.0, x

    def u(z):  # int_z^1 sinh(G s) ds = (cosh G - cosh G z)/G, written without cancellation
        return 2.0 * np.sinh(0.5 * G * (1.0 + z)) * np.sinh(0.5 * G * (1.0 - z)) / G

    flow = quad(u, -1.0, 1.0, epsabs=0, epsrel=1e-12)[0]
    return flow / (h**3 * G / 12.0)


@pytest.mark.parametrize("x", [1e-3, 0.2, 0.49, 0.51, 1.0, 3.0, 8.0, 20.0])
def test_flow_factor_is_the_integrated_sinh_law(x):
    phi, dphi_over_x = eyring_flow_factor(x)
    assert float(phi) == pytest.approx(_sinh_law_flow_factor(x), rel=1e-9)
    e = max(1e-6 * x, 1e-5)
    fd = (eyring_flow_factor(x + e)[0] - eyring_flow_factor(x - e)[0]) / (2 * e)
    assert float(dphi_over_x) * x == pytest.approx(float(fd), rel=1e-6)


def test_flow_factor_series_and_closed_form_meet():
    """The power series (x < 0.5) and the closed form (x >= 0.5) agree at the switch to 1e-14."""
    lo, hi = eyring_flow_factor(np.nextafter(0.5, 0)), eyring_flow_factor(0.5)
    assert float(lo[0]) == pytest.approx(float(hi[0]), rel=1e-14)
    assert float(lo[1]) == pytest.approx(float(hi[1]), rel=1e-11)


def test_large_eyring_stress_is_newtonian():
    """tau0 = 1e15 Pa (x ~ 1e-8): the solution equals the Newtonian one to 1e-9."""
    c = EHLContact.from_moes(20, 10, line=True)
    g = EHLGrid(nx=257)
    a = solve_ehl(c, g)
    ce = dataclasses.replace(c, lubricant=dataclasses.replace(c.lubricant, eyring_stress=1e15))
    b = solve_ehl(ce, g)
    assert b.minimum_film_thickness == pytest.approx(a.minimum_film_thickness, rel=1e-9)
    assert b.central_film_thickness == pytest.approx(a.central_film_thickness, rel=1e-9)
    assert abs(b.h00 - a.h00) < 1e-9 * a.central_film_thickness


def _roller(eyring: bool):
    from lubedyn import film_points as fp

    params = fp.ehl_roller_race_default_params()
    params["resolution"] = "default"
    if not eyring:
        params["eyring_stress"] = None
    return params


def _roller_solves(params, load, speed, factors):
    """Solves of one roller point: the default start, then from the converged state at each of
    ``factors`` times the load."""
    from lubedyn import film_points as fp

    length = params["length"]
    c, g, o = fp._ehl_setup(params, load / length, speed)
    out = [solve_ehl(c, g, o)]
    for f in factors:
        other = solve_ehl(dataclasses.replace(c, load=f * c.load), g, o)
        out.append(solve_ehl(c, g, o, initial=other))
    return out


def test_newtonian_roller_contact_has_two_solutions():
    """Where the Newtonian method stops: paper A's roller at 10 kN, 8.84 m/s (Barus, alpha p_H = 44,
    L = 56), 257 nodes.  The default start and a start from 0.944 times the load converge to two
    states whose h_min differ by 5.3 % (measured), both exact discrete solutions (reference
    assembly)."""
    a, b = _roller_solves(_roller(eyring=False), 10e3, 8.84, [0.944])
    assert abs(b.minimum_film_thickness / a.minimum_film_thickness - 1) > 0.03
    for s in (a, b):
        free_res, cav_min, pr, load = _complementarity(s)
        assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load < 1e-6


@pytest.mark.parametrize("load, speed", [(10e3, 8.84), (15e3, 8.84), (10e3, 4.0)])
def test_eyring_roller_contact_has_one_solution(load, speed):
    """The same contact with Eyring flow (tau0 = 5 MPa, the map kind's default): starts from 0.8,
    1.06 and 1.25 times the load converge to the default start's state (measured: agree to 1e-13;
    the Newtonian h_min spreads 5.3 / 6.1 / 13 % at these points), which satisfies the discrete
    complementarity in the reference assembly; h_min/h_c is 0.76 at 10 kN, 8.84 m/s (the classic
    exit constriction; Newtonian 0.90-0.95 depending on the branch).  Not every start converges
    with Eyring flow (measured: from 0.944 times the load at 10 kN, 8.84 m/s the Newton iteration
    stalls; from the Newtonian state at 15 kN it overflows); those raise ConvergenceError, and the
    map's points fall back to other starts (lubedyn.film_points.ehl_load_response)."""
    sols = _roller_solves(_roller(eyring=True), load, speed, [0.8, 1.06, 1.25])
    ref = sols[0]
    for s in sols[1:]:
        assert s.minimum_film_thickness == pytest.approx(ref.minimum_film_thickness, rel=1e-9)
        assert abs(s.h00 - ref.h00) < 1e-9 * ref.central_film_thickness
    free_res, cav_min, pr, load_err = _complementarity(ref)
    assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load_err < 1e-6
    if (load, speed) == (10e3, 8.84):
        assert ref.minimum_film_thickness / ref.central_film_thickness == pytest.approx(0.76, abs=0.01)


def test_eyring_normal_coefficients_by_two_methods():
    """Roller with Eyring flow, 10 kN, 8.84 m/s, 257 nodes: K and C from the linearised
    equations (exact Jacobian, cavitated set frozen) against load steps (two more steady solves,
    K = -dQ/dh00 and C by implicit differentiation)."""
    from lubedyn import film_points as fp

    params = _roller(eyring=True)
    lin = fp.ehl_load_response(params, 10e3, 8.84)
    steps = fp.ehl_load_response(dict(params, coefficients="load_steps"), 10e3, 8.84)
    assert steps["Film stiffness [N/m]"] == pytest.approx(lin["Film stiffness [N/m]"], rel=0.02)
    assert steps["Film damping [N s/m]"] == pytest.approx(lin["Film damping [N s/m]"], rel=0.02)


def test_eyring_is_refused_where_it_is_not_implemented():
    from lubedyn.lubrication import mesh
    from lubedyn.lubrication import InclinedSlider

    lub = Lubricant(Barus(0.05, 2e-8), Incompressible(870.0), eyring_stress=5e6)
    with pytest.raises(InputError, match="eyring_stress = 5000000.0: the Reynolds film solver is Newtonian"):
        Film(mesh.interval(0, 0.01, 20), InclinedSlider(2e-6, 1e-6, 0.01), lub, velocity_lower=(1.0,))
    c = EHLContact(0.01, 0.01, 1e11, lub, 1.0, load=10.0)
    with pytest.raises(InputError, match="multigrid' is Newtonian"):
        multigrid_grid(c, EHLGrid(nx=65))
    with pytest.raises(InputError, match=r"lubricant eyring_stress \[Pa\] = -1.0 must be > 0"):
        Lubricant(Barus(0.05, 2e-8), eyring_stress=-1.0)


def test_case_files_take_eyring_stress_for_ehl_scenes_only(capsys):
    """``[lubricant] eyring_stress`` in a case file: an EHL scene builds an Eyring lubricant; a film
    scene is refused in one line naming the key and the value (exit 2)."""
    from lubedyn import cli
    from lubedyn.config import CASES_DIR

    code = cli.main(["run", str(CASES_DIR / "inclined_slider.toml"), "--set", "lubricant.eyring_stress=5 MPa",
                     "--dry-run"])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "lubricant.eyring_stress" in err and "5e+06" in err, err

    from lubedyn.config import load_case
    from lubedyn.scenes.ehl import build_lubricant

    case = load_case(CASES_DIR / "ehl_roller_slice.toml", overrides=["lubricant.eyring_stress=5 MPa"])
    assert build_lubricant(case).eyring_stress == pytest.approx(5e6)
