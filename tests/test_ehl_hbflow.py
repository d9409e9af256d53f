"""Herschel-Bulkley (grease) flow in the EHL solver (``Lubricant(herschel_bulkley=HerschelBulkleyFlow(...))``).

Checked against:
- the Herschel-Bulkley law integrated across the film by nested quadrature of the velocity profile
  (scipy.integrate.quad), for n = 1 and n != 1, with and without a yield stress;
- the Buckingham-Reiner slit flow of a Bingham fluid (n = 1): Phi = 1 - 3 xi/2 + xi^3/2;
- finite differences of the flow factor (dPhi/dT_w, d ln Phi/d ln phi = 1 - 1/n) and of the discrete
  residual (the Jacobian, line and point contacts), and the scikit-fem reference assembly;
- the Newtonian solver (tau_y = 0, n = 1: the same state to round-off);
- paper A's cone contact (R = 9.395 mm, E' = 225 GPa) with Table 2's greases at 30 C: a measured
  comparison of the central film with the base-oil (0.1 Pa s) EHL film and with
  lubedyn.lubrication.laws.grease.grease_line_film, and where the iteration stops converging.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.integrate import quad

from lubedyn.lubrication import ConvergenceError, InputError
from lubedyn.lubrication.ehl import EHLContact, EHLGrid, EHLOptions, multigrid_grid, solve_ehl
from lubedyn.lubrication.laws import grease as G
from lubedyn.lubrication.laws.lubricant import (Barus, DowsonHigginson, HerschelBulkleyFlow, Incompressible, Lubricant,
                                                herschel_bulkley_flow_factor)

from test_ehl import _complementarity
from test_ehl_point import _check_jacobian, _smooth_state

# paper A: the cone's reduced radius, E' = 2 E* of steel 205 GPa, 0.3; alpha of Table 1; Table 2 at 30 C
R_CONE, E_PRIME, ALPHA = 9.395e-3, 225e9, 4.662e-8
GREASES_30C = {"polyurea": (351.8, 8.44, 0.7196), "lithium": (805.2, 46.23, 0.3125),
               "calcium": (649.5, 49.23, 0.5344)}  # tau_y [Pa], phi0 [Pa s^n], n (Table 2, written out)
PAPER_GRID = EHLGrid(nx=257, x_min=-20.0, x_max=3.0)


def _quadrature_flow_factor(h, G_, tau_y, phi, n):
    """Poiseuille flow of tau = sign(D)(tau_y + phi |D|^n) between walls at rest at z = +-h/2 under a
    pressure gradient G_, over G_ h^3/(12 phi): |tau| = G_ |z|, shear rate ((G_ z - tau_y)/phi)^(1/n)
    outside the plug |z| < tau_y/G_, velocity u(z) = int_z^{h/2} rate (quad), flow 2 int_0^{h/2} u (quad)."""
    zp = min(tau_y / G_, h / 2)

    def rate(z):
        t = G_ * z
        return ((t - tau_y) / phi) ** (1.0 / n) if t > tau_y else 0.0

    def u(z):
        return quad(rate, max(z, zp), h / 2, epsabs=0, epsrel=1e-13, limit=200)[0]

    pts = [zp] if 0 < zp < h / 2 else None
    q = 2 * quad(u, 0.0, h / 2, points=pts, epsabs=0, epsrel=1e-12, limit=200)[0]
    return q / (G_ * h**3 / (12 * phi))


CASES = [  # h [m], |grad p| [Pa/m], tau_y [Pa], phi [Pa s^n], n
    (1e-6, 1e12, 0.0, 0.1, 1.0), (1e-6, 1e12, 1e2, 0.1, 1.0), (1e-6, 1e12, 3e5, 0.1, 1.0),
    (2e-6, 1e12, 805.2, 46.23, 0.3125), (2e-6, 1e9, 805.2, 46.23, 0.3125), (1e-5, 5e8, 351.8, 8.44, 0.7196),
    (1e-5, 5e8, 0.0, 8.44, 0.7196), (1e-5, 5e8, 0.0, 8.44, 1.5), (4e-6, 1e9, 649.5, 49.23, 0.5344),
]


@pytest.mark.parametrize("h, grad, tau_y, phi, n", CASES)
def test_flow_factor_is_the_integrated_law(h, grad, tau_y, phi, n):
    """Closed form against the quadrature of the velocity profile (measured: 1e-15 ... 4e-15 relative)."""
    closed = float(herschel_bulkley_flow_factor(h * grad / 2, phi, tau_y, n)[0])
    assert closed == pytest.approx(_quadrature_flow_factor(h, grad, tau_y, phi, n), rel=1e-10)


@pytest.mark.parametrize("xi", [0.0, 0.1, 0.5, 0.9, 0.999])
def test_bingham_is_buckingham_reiner(xi):
    """n = 1: Phi = 1 - 3 xi/2 + xi^3/2, xi = 2 tau_y/(h |grad p|) (Buckingham-Reiner, slit)."""
    T = 1e5
    phi = float(herschel_bulkley_flow_factor(T, 0.1, xi * T, 1.0)[0])
    assert phi == pytest.approx(1 - 1.5 * xi + 0.5 * xi**3, rel=1e-13, abs=1e-16)


@pytest.mark.parametrize("n", [0.3125, 1.0, 1.5])
def test_no_flow_below_the_yield_stress(n):
    """|grad p| h/2 <= tau_y: a plug across the film, no Poiseuille flow (and no derivative)."""
    phi, dphi = herschel_bulkley_flow_factor(np.array([0.0, 50.0, 100.0]), 8.44, 100.0, n)
    assert np.all(phi == 0.0) and np.all(dphi == 0.0)


@pytest.mark.parametrize("h, grad, tau_y, phi, n", CASES)
def test_flow_factor_derivatives_are_finite_differences(h, grad, tau_y, phi, n):
    """dPhi/dT_w against central differences; d ln Phi/d ln phi = 1 - 1/n (used by the Jacobian)."""
    T = h * grad / 2
    f, d = herschel_bulkley_flow_factor(T, phi, tau_y, n)
    e = 1e-6 * T
    fd = (herschel_bulkley_flow_factor(T + e, phi, tau_y, n)[0] - herschel_bulkley_flow_factor(T - e, phi, tau_y, n)[0])
    assert float(d) == pytest.approx(float(fd) / (2 * e), rel=1e-6)
    ep = 1e-6
    lp = (np.log(herschel_bulkley_flow_factor(T, phi * (1 + ep), tau_y, n)[0])
          - np.log(herschel_bulkley_flow_factor(T, phi * (1 - ep), tau_y, n)[0])) / (np.log1p(ep) - np.log1p(-ep))
    assert float(lp) == pytest.approx(1 - 1 / n, abs=1e-6)


def _hb_state(c, nx, n):
    """``_smooth_state`` with a Herschel-Bulkley lubricant whose yield stress is half the median wall
    stress h |grad p|/2 (so plugs, flowing regions and the switch between them are all present)."""
    P, p, h00 = _smooth_state(c, nx)
    g = np.sqrt(sum(np.asarray(d) ** 2 for d in P.forms.interpolate(p)[1]))
    h = P.forms.interpolate(np.maximum(P.film(p, h00), P.o.h_floor * P.hscale))[0]
    tau_y = float(np.median(h * g)) / 4
    P.c = dataclasses.replace(c, lubricant=dataclasses.replace(
        c.lubricant, herschel_bulkley=HerschelBulkleyFlow(tau_y, n)))
    ey = P._coefficients(np.maximum(P.forms.interpolate(p)[0], 0.0), h, P.forms.interpolate(p)[1]).ey
    assert 0.1 < np.mean(ey["phi"] == 0.0) < 0.9  # plugs and flow
    return P, p, h00


@pytest.mark.parametrize("line", [True, False])
@pytest.mark.parametrize("n", [1.0, 0.6, 1.4])
def test_hb_jacobian_is_exact_and_assemblies_agree(line, n):
    """The Herschel-Bulkley terms of the Jacobian (grad p grad p^T diffusion, dPhi/dh, Phi's dependence
    on the consistency phi(p), SUPG through Pe ~ phi/Phi) against central differences of the residual;
    the vectorised assembly against scikit-fem's (measured: 4e-16 ... 2e-14)."""
    c = EHLContact.from_moes(100, 10, line=line, density=DowsonHigginson(850.0))
    P, p, h00 = _hb_state(c, 65 if line else 17, n)
    _check_jacobian(P, p, h00)
    fast, ref = P.assemble(p, h00), P.assemble_skfem(p, h00)
    assert np.max(np.abs(fast[0] - ref[0])) < 1e-12 * np.max(np.abs(ref[0]))
    for a, b in ((fast[2], ref[2]), (fast[3], ref[3])):
        assert abs(a - b).max() < 1e-12 * abs(b).max()


@pytest.mark.parametrize("moes", [True, False])
def test_no_yield_stress_and_n_one_is_newtonian(moes):
    """tau_y = 0, n = 1: Phi_HB = 1, the same discrete problem; from the same (Newtonian) start the
    solver returns the Newtonian state (measured: equal to the last bit at Moes M = 20, L = 10; at
    paper A's 135 kN/m, 10 m/s with the 0.1 Pa s base oil, h_c 5.757991065969508 um both)."""
    if moes:
        c, g = EHLContact.from_moes(20, 10, line=True), EHLGrid(nx=257)
    else:
        c = EHLContact(R_CONE, None, E_PRIME / 2, Lubricant(Barus(0.1, ALPHA), Incompressible(870.0)), 10.0,
                       load=135e3)
        g = PAPER_GRID
    a = solve_ehl(c, g)
    b = solve_ehl(dataclasses.replace(c, lubricant=dataclasses.replace(
        c.lubricant, herschel_bulkley=HerschelBulkleyFlow(0.0, 1.0))), g)
    assert b.central_film_thickness == pytest.approx(a.central_film_thickness, rel=1e-12)
    assert b.minimum_film_thickness == pytest.approx(a.minimum_film_thickness, rel=1e-12)
    assert np.max(np.abs(b.pressure - a.pressure)) <= 1e-9 * np.max(a.pressure)


def _paper_contact(name, load, speed, creep=0.0):
    tau_y, phi0, n = GREASES_30C[name]
    lub = Lubricant(Barus(phi0, ALPHA), Incompressible(870.0), herschel_bulkley=HerschelBulkleyFlow(tau_y, n, creep))
    return EHLContact(R_CONE, None, E_PRIME / 2, lub, speed, load=load)


def _grease(name):
    from lubedyn.papers.wu2018.parameters import GREASE_TABLE

    return G.grease_at(GREASE_TABLE[name], 30.0, ALPHA, name)


# measured central films [um] at 135 kN/m, 10 m/s, 257 nodes on [-20, 3] b (513 nodes: 8.7221, 4.0971)
PAPER_A_FILMS = {"polyurea": 8.7125, "calcium": 4.0897}
BASE_OIL_FILM = 5.7580  # the same contact with the 0.1 Pa s base oil (Newtonian, Barus alpha), um


@pytest.mark.parametrize("name", ["polyurea", "calcium"])
def test_paper_a_grease_film_converges(name):
    """Paper A's cone contact at 135 kN/m, 10 m/s with Table 2's grease at 30 C (alpha 4.662e-8 for all)
    converges (FB Newton from the Newtonian start with the apparent viscosity); the state satisfies the
    discrete complementarity in the reference assembly.  Measured comparison (not a tolerance), h_c [um]:

    ========  ==========  =============  ==========================================
    grease    EHL, HB     EHL, base oil  grease_line_film: base_oil / apparent (DT, Moes) / paper
    ========  ==========  =============  ==========================================
    polyurea  8.7125      5.7580         4.959 / 6.786, 7.298 / 105.8
    calcium   4.0897      5.7580         4.959 / 2.819, 3.111 / 357.3
    ========  ==========  =============  ==========================================

    The Herschel-Bulkley film is 1.51 (polyurea) and 0.71 (calcium) times the base-oil film, and 1.28 /
    1.45 times the apparent-viscosity formula (Dowson-Toyoda; 1.19 / 1.31 times Moes): the formula takes
    the viscosity at the rolling shear rate u_m/h_c, while the inlet's Poiseuille shear rates are lower,
    where a shear-thinning grease is more viscous.  The creep regularisation does not matter here
    (eps = 0, 1e-8, 1e-6, 1e-4: h_c equal to 5 digits)."""
    s = solve_ehl(_paper_contact(name, 135e3, 10.0), PAPER_GRID)
    assert s.central_film_thickness * 1e6 == pytest.approx(PAPER_A_FILMS[name], rel=2e-4)
    free_res, cav_min, pr, load = _complementarity(s)
    assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load < 1e-6
    formula = G.grease_line_film(_grease(name), "apparent", 10.0, 135e3, R_CONE, E_PRIME).central
    ratio = s.central_film_thickness / formula
    assert 1.0 < ratio < 2.0, ratio  # the measured 1.28 / 1.45: thicker than the formula's reading
    assert s.info["hb_start"]["apparent_viscosity"] == pytest.approx(
        G.grease_line_film(_grease(name), "apparent", 10.0, 135e3, R_CONE, E_PRIME).viscosity, rel=1e-5)
    s6 = solve_ehl(_paper_contact(name, 135e3, 10.0, creep=1e-6), PAPER_GRID)
    assert s6.central_film_thickness == pytest.approx(s.central_film_thickness, rel=1e-6)


# where it stops: measured on 257 nodes, [-20, 3] b, paper A's cone, 30 C (alpha 4.662e-8)
#   polyurea: converges at 135/10, 135/15, 100/10, 100/15, 50/10 (kN/m, m/s); fails at 135/20, 50/20 (the
#             Newtonian starts fail)
#   calcium:  converges at all of 135/10, 135/15, 135/20, 100/10, 100/15, 50/10, 50/20
#   lithium (n = 0.31, apparent viscosity ~7e-5 Pa s at the rolling shear rate; formula film 34 nm):
#             converges at all seven through the (n, tau_y) homotopy from the Newtonian start
#             (lubedyn.lubrication.ehl.solve._hb_homotopy; 6-11 steps, 11-26 s each): h_c 39.41, 47.93, 54.95, 41.13,
#             50.29, 54.68, 76.24 nm (the Newtonian start's 34.4-54.8 nm: 1.14-1.39 times); before it, the direct
#             Herschel-Bulkley step from the Newtonian start stalled at all seven
@pytest.mark.parametrize("name, load, speed", [("polyurea", 135e3, 20.0)])
def test_where_the_grease_solve_stops_converging(name, load, speed):
    """The failures raise ConvergenceError naming the Herschel-Bulkley lubricant and every start tried (measured:
    polyurea at 135 kN/m, 20 m/s fails from all four Newtonian starts, directly and by the homotopy)."""
    with pytest.raises(ConvergenceError, match=r"Herschel-Bulkley contact did not converge from any Newtonian "
                                               r"start .*HerschelBulkleyFlow\(yield_stress=") as info:
        solve_ehl(_paper_contact(name, load, speed), PAPER_GRID)
    import re

    # each of the four start viscosities named (with, where its Newtonian contact converged, the direct step's
    # and the homotopy's failures from it)
    assert len(set(re.findall(r"Newtonian start eta = ([0-9.e+-]+) Pa s", str(info.value)))) == 4


@pytest.mark.parametrize("load, speed, film", [(50e3, 20.0, 76.2380), (135e3, 10.0, 39.4139)])
def test_lithium_converges_by_the_homotopy(load, speed, film):
    """Lithium (n = 0.3125) on paper A's cone: the direct Herschel-Bulkley step from the Newtonian start (its
    apparent viscosity) stalls, the homotopy in (n, tau_y) that keeps the apparent viscosity at the start's shear
    rate reaches it (measured h_c 76.238 / 39.414 nm, 1.39 / 1.14 times the Newtonian start's).  The end state is
    an exact discrete solution in the reference assembly, whatever the path (the complementarity, as for
    polyurea and calcium: measured free residual 1.8e-10 / 1.5e-7 of p_Hertz)."""
    s = solve_ehl(_paper_contact("lithium", load, speed), PAPER_GRID)
    start = s.info["hb_start"]
    assert start["homotopy"]["steps"][-1][0] == 1.0 and any("stalled" in f for f in start["failed_starts"])
    assert s.central_film_thickness * 1e9 == pytest.approx(film, rel=2e-4)
    assert 1.1 < s.central_film_thickness / start["central_film"] < 1.45
    free_res, cav_min, pr, load_err = _complementarity(s)
    assert free_res < 2e-7 and pr < 1e-7 and cav_min > -1e-7 and load_err < 1e-6


def test_calcium_converges_across_the_paper_a_range():
    """Calcium at the corners of 50-135 kN/m x 10-20 m/s (measured h_c 4.23, 5.31, 4.09, 5.93 um)."""
    films = [solve_ehl(_paper_contact("calcium", w, u), PAPER_GRID).central_film_thickness
             for w, u in ((50e3, 10.0), (50e3, 20.0), (135e3, 10.0), (135e3, 20.0))]
    assert np.allclose(np.array(films) * 1e6, [4.2311, 5.3086, 4.0897, 5.9279], rtol=2e-4)


def test_bad_input_is_one_line():
    with pytest.raises(InputError, match=r"^lubricant herschel_bulkley.exponent n = 3.0 must lie in \(0, 2\]$"):
        HerschelBulkleyFlow(100.0, 3.0)
    with pytest.raises(InputError, match=r"^lubricant herschel_bulkley.yield_stress \[Pa\] = -1.0 must be"):
        HerschelBulkleyFlow(-1.0, 0.5)
    with pytest.raises(InputError, match=r"^lubricant herschel_bulkley.creep = 1.0 must lie in \[0, 1\)"):
        HerschelBulkleyFlow(1.0, 0.5, 1.0)
    with pytest.raises(InputError, match=r"^lubricant eyring_stress = 5000000.0 with herschel_bulkley: choose one"):
        Lubricant(Barus(8.44, ALPHA), eyring_stress=5e6, herschel_bulkley=HerschelBulkleyFlow(100.0, 0.7))
    with pytest.raises(InputError, match=r"^lubricant herschel_bulkley = \(100.0, 0.7\) must be a HerschelBulkleyFlow"):
        Lubricant(Barus(8.44, ALPHA), herschel_bulkley=(100.0, 0.7))
    c = EHLContact.from_moes(20, 10)
    c = dataclasses.replace(c, lubricant=dataclasses.replace(c.lubricant, herschel_bulkley=HerschelBulkleyFlow(1.0, 1.0)))
    with pytest.raises(InputError, match=r"solver.method = 'multigrid' is Newtonian"):
        multigrid_grid(c, EHLGrid(nx=65))
    from lubedyn.lubrication import Film, InclinedSlider, mesh

    with pytest.raises(InputError, match=r"herschel_bulkley = .*the Reynolds film solver is Newtonian"):
        Film(mesh.interval(0, 0.01, 20), InclinedSlider(2e-6, 1e-6, 0.01), c.lubricant, velocity_lower=(1.0,))


def test_lubricant_from_grease():
    g = _grease("polyurea")
    lub = Lubricant.from_grease(g)
    assert (lub.viscosity.eta0, lub.viscosity.alpha) == (8.44, ALPHA)
    assert (lub.herschel_bulkley.yield_stress, lub.herschel_bulkley.exponent) == (351.8, 0.7196)
    assert not lub.is_newtonian and not lub.is_constant


def test_case_file_takes_herschel_bulkley(tmp_path):
    """``[lubricant.herschel_bulkley]`` in the EHL roller-slice case (smoke grid, 129 nodes, polyurea at
    30 C with eta0 = phi0): the run converges and reports the start (measured h_c 9.273 um; the base-oil
    case's own smoke run: 6.193 um)."""
    import json

    from lubedyn import cli
    from lubedyn.config import CASES_DIR, load_case
    from lubedyn.scenes.ehl import build_lubricant

    sets = ["lubricant.viscosity.eta0=8.44 Pa s", "lubricant.herschel_bulkley.yield_stress=351.8 Pa",
            "lubricant.herschel_bulkley.exponent=0.7196"]
    case = load_case(CASES_DIR / "ehl_roller_slice.toml", overrides=sets)
    assert build_lubricant(case).herschel_bulkley == HerschelBulkleyFlow(351.8, 0.7196, 0.0)
    args = ["run", str(CASES_DIR / "ehl_roller_slice.toml"), "--smoke", "--out", str(tmp_path)]
    for s in sets:
        args += ["--set", s]
    assert cli.main(args) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["Central film thickness [m]"] == pytest.approx(9.273e-6, rel=1e-3)
    assert summary["Herschel-Bulkley exponent [-]"] == 0.7196
    assert "Dowson-Toyoda central film thickness [m]" not in summary


def test_calcium_contact_has_two_discrete_solutions():
    """Where the method stops being a function of the data (as the Newtonian roller does,
    tests/test_ehl_eyring.py): calcium at 135 kN/m, 10 m/s from the default start (Newtonian, apparent
    viscosity 0.0441 Pa s) and from the 0.1 Pa s base-oil state converge to two states, both exact
    discrete solutions in the reference assembly (measured h_c 4.0897 / 4.0708 um, h_min 3.843 /
    3.625 um: 0.46 % and 5.7 % apart).  The Herschel-Bulkley flow does not remove them; Eyring flow did."""
    c = _paper_contact("calcium", 135e3, 10.0)
    a = solve_ehl(c, PAPER_GRID)
    base = EHLContact(R_CONE, None, E_PRIME / 2, Lubricant(Barus(0.1, ALPHA), Incompressible(870.0)), 10.0,
                      load=135e3)
    b = solve_ehl(c, PAPER_GRID, initial=solve_ehl(base, PAPER_GRID))
    assert abs(b.minimum_film_thickness / a.minimum_film_thickness - 1) > 0.03
    for s in (a, b):
        free_res, cav_min, pr, load = _complementarity(s)
        assert free_res < 1e-7 and pr < 1e-7 and cav_min > -1e-7 and load < 1e-6


def _rib_contact(tau_y, phi0, n, load, speed):
    """Paper A's rib (roller end r_s 136.2 mm on the cone's rib: R_x 168.96 mm along the entrainment, R_y 136.2 mm)."""
    from lubedyn.lubrication.laws.flange import rib_radii

    rx, ry = rib_radii(0.1362, 0.08559954394988122, np.radians(83.0))
    lub = Lubricant(Barus(phi0, ALPHA), Incompressible(870.0), herschel_bulkley=HerschelBulkleyFlow(tau_y, n))
    return EHLContact(rx, ry, E_PRIME / 2, lub, speed, load=load)


def test_apparent_start_is_the_thinnest_fixed_point_on_a_point_contact():
    """hb_apparent_start on paper A's rib (calcium, 500 N, 11.3 m/s): the film h = h_guess(eta_app(h)) (measured
    9.188 um, eta_app 0.07244 Pa s) to round-off, and no thinner one (h_guess/h > 1 on a log grid from 1e-3 of it).
    The damped iteration from eta = phi0 it replaces ran off to the guess's rigid-isoviscous branch (0.95 m, 1.9 m,
    ... 2e5 m in 8 steps, then ZeroDivisionError).  A grease whose film has no fixed point (polyurea's yield stress
    with phi0 = 38.44 at 216 N: eta_app grows with h faster than the rigid film allows) is one ConvergenceError."""
    import dataclasses

    from lubedyn.lubrication.ehl.newton import _film_guess, hb_apparent_start

    c = _rib_contact(649.5, 49.23, 0.5344, 500.0, 11.3)
    eta, h = hb_apparent_start(c)
    assert (eta, h * 1e6) == pytest.approx((0.07244, 9.188), rel=2e-4)

    def guess(hh):
        D = c.mean_speed / hh
        e = 649.5 / D + 49.23 * D ** (0.5344 - 1.0)
        return _film_guess(dataclasses.replace(c, lubricant=dataclasses.replace(
            c.lubricant, viscosity=Barus(e, ALPHA), herschel_bulkley=None)))

    assert guess(h) == pytest.approx(h, rel=1e-10)
    assert all(guess(x) > x for x in np.geomspace(1e-3 * h, 0.999 * h, 40))
    with pytest.raises(ConvergenceError, match=r"^EHL Herschel-Bulkley start: no apparent-viscosity film h = "
                                               r"h_guess\(eta_app\(h\)\) between .* phi0 = 38.44 Pa s\^n"):
        hb_apparent_start(_rib_contact(351.8, 38.44, 0.7196, 215.9, 11.32))
