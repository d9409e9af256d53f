"""Kinds ``ehl_ball_inner_race``, ``ehl_ball_outer_race``, ``ehl_roller_cone``, ``ehl_roller_cup``: isothermal EHL contacts of
a rolling element with its race (load response, film stiffness and damping, traction).

Part of :mod:`lubedyn.film_points` (the package docstring gives the physics and sources)."""
from __future__ import annotations

import logging
import math

import numpy as np

from lubedyn.lubrication.errors import ConvergenceError, InputError, unknown_choice

from lubedyn.film_points.base import (AxisDef, BALL_DIAMETER, BALL_MODULUS, BALL_POISSON, GREASE_ALPHA, INNER_GROOVE_RADIUS, N_BALLS,
                   OIL_ALPHA, OIL_ETA0, OIL_RHO0, OUTER_GROOVE_RADIUS, PAPER_B_AXIAL_LOAD, PITCH_DIAMETER_6206,
                   RING_MODULUS, RING_POISSON, ROLLER_BASE_OIL_ETA0, ROLLER_BASE_OIL_RHO0, ROLLER_EFFECTIVE_LENGTH,
                   ROLLER_EYRING_STRESS, ROLLER_FILM_SHEAR_MODULUS, ROLLER_INNER_CONTACT_ANGLE, ROLLER_MEAN_DIAMETER, ROLLER_MODULUS,
                   ROLLER_PITCH_DIAMETER, ROLLER_POISSON, _get, _lubricant, _reduced_modulus)
from lubedyn.lubrication.laws import bearing
from lubedyn.lubrication.laws.contact import line_contact
from lubedyn.lubrication.laws.film import moes_line_central
from lubedyn.lubrication.laws.grease import grease_at
from lubedyn.lubrication.laws.lubricant import Barus
from lubedyn.papers.wu2018.parameters import GREASE_TABLE, tapered_geometry

log = logging.getLogger(__name__)

# ====================================================================== EHL contacts

EHL_RESOLUTIONS = {
    # point contacts: (nx, ny) on the reference domain x in [-6, 1.5] b_x, |y| <= 1.5 b_y; line contacts:
    # nx on x in [-20, 3] b.  They fix the node *spacing* in Hertz semi-axes (:func:`_ehl_grid`): a
    # case's longer domain gets proportionally more nodes, so that the contact keeps its nodes per
    # Hertz radius (point default: 6.4 cells per b_x, 8 per b_y; line default 11.1 per b).
    # Measured on paper B's inner contact (Q = 723 N, u_e = 11.54 m/s), Fischer-Burmeister Newton,
    # (h_c, h_min, K, C, s per point with the other core busy): 33 x 17: 1.1152 um, 0.842 um, 1.2735e8 N/m, 1631 N s/m, 4 s;
    # 49 x 25: 1.1217, 0.991, 1.2818e8, 1593, 13 s; 65 x 33: 1.1272, 1.024, 1.2888e8, 1589, 32 s.
    # Roller (20 kN, 6.46 m/s), 129 / 257 / 513 nodes: h_c 4.046 / 3.990 / 3.992 um,
    # K 8.60e8 / 8.02e8 / 7.98e8 N/m, C 3.01e4 / 4.15e4 / 4.43e4 N s/m (the damping converges
    # slowly on line contacts: 257 nodes is 6 % below 513 there).
    "point": {"smoke": (33, 17), "default": (49, 25), "fine": (65, 33)},
    "line": {"smoke": 129, "default": 257, "fine": 513, "finer": 1025, "finest": 2049},
}
# the reference domains of EHL_RESOLUTIONS (Hertz semi-axes): point (x_min, x_max, y_max), line (x_min, x_max)
EHL_REFERENCE_DOMAIN = {"point": (-6.0, 1.5, 1.5), "line": (-20.0, 3.0)}
TRACTION = {"model": "limiting_shear", "limiting_shear_stress": 5e6, "limiting_shear_slope": 0.08}
EHL_OUTPUTS = (
    "Central film thickness [m]", "Minimum film thickness [m]",
    "Film stiffness [N/m]", "Film damping [N s/m]", "Traction coefficient [-]", "Approach [m]",
)


def _ball_race_geometry(race: str, contact_angle: float) -> tuple:
    """(R_x, R_y) [m] of a 6206 ball on its ``race`` at ``contact_angle`` [rad] (lubedyn.lubrication.laws.bearing)."""
    groove = INNER_GROOVE_RADIUS if race == "inner" else OUTER_GROOVE_RADIUS
    return bearing.race_radii(BALL_DIAMETER, PITCH_DIAMETER_6206, groove, race, contact_angle)


def _paper_b_contact_angle() -> float:
    """Contact angle [rad] of the 6206 (zero clearance) under paper B's axial load 200 N (lubedyn.lubrication.laws.bearing)."""
    r_i, r_o = INNER_GROOVE_RADIUS, OUTER_GROOVE_RADIUS
    e_star = _reduced_modulus(BALL_MODULUS, BALL_POISSON, RING_MODULUS, RING_POISSON)
    K_n = bearing.deflection_constant(BALL_DIAMETER, PITCH_DIAMETER_6206, r_i, r_o, 0.0, e_star)
    return bearing.thrust_contact_angle(PAPER_B_AXIAL_LOAD, N_BALLS, BALL_DIAMETER, r_i, r_o, K_n, 0.0)


def _ehl_ball_params(race: str) -> dict:
    alpha_c = _paper_b_contact_angle()  # 9.03 deg
    rx, ry = _ball_race_geometry(race, alpha_c)
    return {
        "contact": "point",
        "radius_x": rx,
        "radius_y": ry,
        "e_star": _reduced_modulus(BALL_MODULUS, BALL_POISSON, RING_MODULUS, RING_POISSON),
        "eta0": OIL_ETA0,
        "alpha": OIL_ALPHA,
        "rho0": OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "dowson_higginson",
        "length": 0.0,
        # inlet at -18.5 b_x: h_c within 0.3 % of an unbounded inlet over the map's axes (module docstring,
        # "Inlet length"); -6 starved the film by up to 9 % at 50 N, 30 m/s
        "x_min": -18.5, "x_max": 1.5, "y_max": 1.5,
        "traction_model": TRACTION["model"],
        "limiting_shear_stress": TRACTION["limiting_shear_stress"],
        "limiting_shear_slope": TRACTION["limiting_shear_slope"],
        # +-10 %: on the 129 x 25 grid the +-5 % secants still jitter by +-2.3 % between neighbouring
        # light loads (outer race, 50-94 N at 27 m/s: deviations from a smooth fit in log Q), +-10 %
        # by +-1.1 %, +-20 % by +-0.7 %; the bias of the wider secant is 0.1 % (+-10 %) / 0.3 % (+-20 %)
        "coefficients": "secant", "secant_step": 0.1,
        "resolution": "default",
    }


def ehl_ball_inner_race_default_params() -> dict:
    """6206 ball / inner race of paper B (Tables 1, 2, 4), contact angle 9.03 deg (Fa = 200 N, zero clearance)."""
    return _ehl_ball_params("inner")


def ehl_ball_outer_race_default_params() -> dict:
    """6206 ball / outer race of paper B (Tables 1, 2, 4), contact angle 9.03 deg (Fa = 200 N, zero clearance)."""
    return _ehl_ball_params("outer")


def ehl_roller_race_default_params() -> dict:
    """Paper A roller / inner race line contact (Table 1; cases/ehl_roller_slice.toml for every number).

    Grease treated as its base oil (as in cases/ehl_roller_slice.toml):
    eta0 = 0.1 Pa s (assumed: paper A gives no base-oil viscosity), Barus
    with the grease's alpha = 4.662e-8 m^2/N (Table 1), incompressible
    870 kg/m^3, and Eyring shear thinning of the Poiseuille flow with tau0 =
    5 MPa (``eyring_stress``; assumed, the traction's limiting-shear
    intercept; paper A gives none).  R = (D/2)(1 - gamma), gamma = D cos(5
    deg)/d_m.

    Why Eyring (measured on 257 and 1025 nodes): with a Newtonian
    base oil this contact (L = 44-66) has several exact discrete solutions at
    the same load and speed -- starts from 0.8, 0.944, 1.06 and 1.25 times the
    load converge to outlet spikes 0.09 b apart and h_min up to 13 % apart
    (10 kN, 4 m/s), on every grid from 257 to 2049 nodes, so h_min, the
    damping and the approach were not functions of (load, speed) that a map
    could hold.  Capping the viscosity (1e6 ... 1e12 Pa s) or a
    Dowson-Higginson density left that unchanged.  The outlet's pressure
    gradient puts the Newtonian Poiseuille shear stress h |dp/dx|/2 at ~1e8
    Pa, far above what an oil carries; with the Eyring flow factor the same
    five starts agree to 1e-13 at 5-20 kN, 3-15 m/s, h_c moves by -1.2 % (10
    kN, 8.84 m/s: 5.177 -> 5.114 um; the inlet is Newtonian) and h_min/h_c
    becomes 0.76 (Newtonian: 0.90-0.95, branch-dependent).
    """
    rx = bearing.race_radius_x(ROLLER_MEAN_DIAMETER, ROLLER_PITCH_DIAMETER, ROLLER_INNER_CONTACT_ANGLE, "inner")
    return {
        "contact": "line",
        "radius_x": rx,
        "radius_y": 0.0,
        "e_star": _reduced_modulus(ROLLER_MODULUS, ROLLER_POISSON, ROLLER_MODULUS, ROLLER_POISSON),
        "eta0": ROLLER_BASE_OIL_ETA0,
        "alpha": GREASE_ALPHA,
        "rho0": ROLLER_BASE_OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "incompressible",
        "eyring_stress": ROLLER_EYRING_STRESS,
        "length": ROLLER_EFFECTIVE_LENGTH,
        "x_min": -20.0, "x_max": 3.0, "y_max": 0.0,
        "traction_model": TRACTION["model"],
        "limiting_shear_stress": TRACTION["limiting_shear_stress"],
        "limiting_shear_slope": TRACTION["limiting_shear_slope"],
        "coefficients": "linearised",
        "resolution": "default",
    }


# Roller kinds of paper A on a line-load axis: film-scaled domain.  The Hertz
# domain [-20, 3] b of the earlier map starves light loads (tests/test_ehl_limits.py: -13 % at 20 kN/m,
# 25 m/s; 3-10 times too thin at 1 kN/m): there the film is hydrodynamic and its pressure spans
# sqrt(2 R h), 10-160 b.  The kinds' domain is x in [-hypot(20, k_in r), hypot(3, k_out r)] b with
# r = sqrt(2 R h_Moes)/b (Moes' central film of the point: smooth in load and speed, so the discrete
# problem -- nx fixed -- varies smoothly along the axes, no jump in node layout), k_in = 8, k_out = 1.5:
# measured at 10 kN/m, 8 m/s (r = 10.4): h_c +1.0 % when k_in = 16 (4.962 -> 5.012 um).
ROLLER_INLET_FILM_LENGTHS = 8.0
ROLLER_OUTLET_FILM_LENGTHS = 1.5
ROLLER_RACES = ("cone", "cup")


def roller_race_radius(race: str) -> float:
    """Reduced radius R_x [m] of paper A's mid-slice roller/``race`` line contact from the model's own
    geometry (:func:`lubedyn.papers.wu2018.parameters.tapered_geometry`, ``reduced_radius``: roller rho_m/cos(phi)
    against the race's cone r_c/cos(alpha), concave for the cup): cone 9.395 mm, cup 11.906 mm."""
    if race not in ROLLER_RACES:
        raise unknown_choice("race", race, ROLLER_RACES)
    return float(tapered_geometry().reduced_radius(race))


def _roller_params(race: str) -> dict:
    """Paper A roller / ``race`` line contact per unit length (kinds ``ehl_roller_cone``/``ehl_roller_cup``).

    As :func:`ehl_roller_race_default_params` (base oil eta0 = 0.1 Pa s assumed, Barus with the grease's
    alpha, incompressible, Reynolds-Eyring flow tau0 = 5 MPa, limiting-shear traction) except: the
    reduced radius is the model's own (:func:`roller_race_radius`; the earlier map used the
    cylindrical-roller approximation (D/2)(1 - gamma) = 9.382 mm for the cone, 0.13 % below), the
    load is a line load (``length`` = 1 m: stiffness and damping per metre of contact), and the domain
    is scaled with the film (``inlet_film_lengths``; 0 gives the fixed Hertz domain)."""
    params = ehl_roller_race_default_params()
    params.update({
        # central secants over +-10 % load and squeeze velocity (as the ball races): the linearised
        # tangent jitters by +-3 % (K) / +-4 % (C) between neighbouring loads above the knee (cone, 7 m/s,
        # 38-67 kN/m, 257 nodes: K 1.927, 1.843, 1.901, 1.819, 1.759, 1.876e10 N/m^2), the secants by +-1 %
        # (1.868, 1.845, 1.839, 1.829, 1.827, 1.791e10)
        "coefficients": "secant", "secant_step": 0.1,
        # ... from Moes' M = 0.25 up: below it the load-step solves of the secant fail from the steady
        # state with every Newton variant (cone, 7 m/s: every load with M = 0.055-0.14; 28 m/s: most with
        # M = 0.028-0.09; 12-25 s per point before the tangent fallback) and the tangent is smooth there
        # (hydrodynamic film, no outlet jitter); secant / tangent at M = 0.18-0.29: K 1.004-1.016,
        # C 0.995-1.001 (7 m/s), K 1.013-1.027, C 0.994-1.011 (28 m/s)
        "secant_min_moes_M": 0.25,
        # the film's elastic shear (Johnson & Tevaarwerk's Maxwell fluid) in the traction: see
        # evaluate_ehl_line, "Traction"; inf gives the rigid limiting-shear law of the ball kinds
        "film_shear_modulus": ROLLER_FILM_SHEAR_MODULUS,
        # Poiseuille flow: "eyring" (the base oil above) or "herschel_bulkley" (a grease: hb_consistency phi0
        # [Pa s^n] with the Barus alpha, hb_yield_stress [Pa], hb_exponent, hb_creep; eta0 and eyring_stress
        # are then unused; lubedyn.film_points.base._lubricant, roller_grease_params)
        "rheology": "eyring",
        "hb_consistency": 0.0, "hb_yield_stress": 0.0, "hb_exponent": 1.0, "hb_creep": 0.0,
        "race": race,
        "radius_x": roller_race_radius(race),
        "length": 1.0,
        "inlet_film_lengths": ROLLER_INLET_FILM_LENGTHS,
        "outlet_film_lengths": ROLLER_OUTLET_FILM_LENGTHS,
        # graded line grid (_graded_fields; 1: uniform) and the Newton's pseudo-transient continuation
        # (lubedyn.lubrication.ehl EHLOptions.pseudo_transient; 0: off)
        "grid_refine": 1.0,
        "pseudo_transient": 0.0,
    })
    return params


def roller_grease_params(name: str, temperature_c: float = 30.0) -> dict:
    """The parameters that make a roller kind's film a grease of paper A's Table 2 (``name`` polyurea, lithium
    or calcium at ``temperature_c`` [C], 15-70, lubedyn.lubrication.laws.grease.grease_at): rheology =
    "herschel_bulkley", hb_consistency phi0 [Pa s^n], hb_yield_stress tau_y [Pa], hb_exponent n (the Barus
    alpha stays the kind's, Table 1's 4.662e-8 m^2/N, which the paper gives for polyurea at 30 C only).
    Merge them into the params of a build (``build_map("ehl_roller_cone", {**roller_grease_params(...)})``)
    or write them in a map case's [params]; they are recorded in the map's provenance."""
    if name not in GREASE_TABLE:
        raise unknown_choice("grease", name, sorted(GREASE_TABLE))
    g = grease_at(GREASE_TABLE[name], float(temperature_c), GREASE_ALPHA, name)
    return {"rheology": "herschel_bulkley", "hb_consistency": float(g.consistency),
            "hb_yield_stress": float(g.yield_stress), "hb_exponent": float(g.exponent), "hb_creep": 0.0}


def ehl_roller_cone_default_params() -> dict:
    """Paper A roller on the cone (inner race), per unit length (:func:`_roller_params`)."""
    return _roller_params("cone")


def ehl_roller_cup_default_params() -> dict:
    """Paper A roller on the cup (outer race), per unit length (:func:`_roller_params`)."""
    return _roller_params("cup")


def _film_scaled_domain(params, contact, lengths=None, base=None):
    """(x_min, x_max) [Hertz half-widths b] of a line contact's domain scaled with its film: x_min =
    -hypot(x_min0, k_in r), x_max = hypot(x_max0, k_out r), r = sqrt(2 R h_Moes)/b (see
    ROLLER_INLET_FILM_LENGTHS)."""
    import math

    if contact.lubricant.herschel_bulkley is not None:
        # a grease: Moes' M and L would read the consistency phi0 as Pa s (8-49 Pa s^n: films and domains ~10
        # times too long; calcium then failed on every point); take the Newtonian film of its apparent
        # viscosity at the rolling shear rate (lubedyn.lubrication.ehl's own start for the grease)
        import dataclasses

        from lubedyn.lubrication.ehl.newton import hb_apparent_start  # deferred: scikit-fem

        lub = contact.lubricant
        eta_app, _ = hb_apparent_start(contact)
        contact = dataclasses.replace(contact, lubricant=dataclasses.replace(
            lub, viscosity=Barus(eta_app, lub.viscosity.pressure_viscosity), herschel_bulkley=None))
    R = contact.radius_x
    h = moes_line_central(contact.moes_M, contact.moes_L) * R * math.sqrt(2 * contact.U)
    b = line_contact(contact.load, R, contact.e_star).b
    r = math.sqrt(2 * R * h) / b
    k_in, k_out = lengths or (float(params["inlet_film_lengths"]), float(_get(params, "outlet_film_lengths", 1.5)))
    x0, x1 = base or (float(params["x_min"]), float(params["x_max"]))
    return -math.hypot(x0, k_in * r), math.hypot(x1, k_out * r)


def _graded_fields(params, contact) -> dict:
    """EHLGrid grading fields of a film-scaled line contact (params ``grid_refine`` > 1; {} for the uniform
    grid, the kinds' default): cells ``grid_refine`` times shorter on the zone [-hypot(refine_x_min,
    refine_inlet_lengths r), hypot(refine_x_max, refine_outlet_lengths r)] b (defaults -1.5, 1.1, 1.2, 0.1;
    r = sqrt(2 R h_Moes)/b as for the domain), graded over ``refine_width`` [b] (default 1).  The zone covers
    the pressurised part of paper A's roller films in the hydrodynamic-to-EHL knee (measured on the cone at
    7 m/s, 15-120 kN/m: p > 0.05 p_Hertz from -(0.7-1.14) r b to 0.3 b, the peak at -(0.2-0.4) r b).  The shipped
    roller maps use it (refine 6, with a Dowson-Higginson film and pseudo_transient 0.1: their map cases'
    [params]); the kinds' default stays the uniform grid (cases/maps/README.md, "Measured 28 Nov 2026";
    benchmarks/ehl_graded.py, roller_traction_sweeps.py --refine)."""
    r = float(_get(params, "grid_refine", 1.0))
    if r == 1.0:
        return {}
    import math

    lo, hi = _film_scaled_domain(params, contact, lengths=(float(_get(params, "refine_inlet_lengths", 1.1)),
                                                             float(_get(params, "refine_outlet_lengths", 0.1))),
                                 base=(float(_get(params, "refine_x_min", -1.5)),
                                       float(_get(params, "refine_x_max", 1.2))))
    return dict(refine=r, refine_zone=(lo, hi), refine_width=float(_get(params, "refine_width", 1.0)))


def _ehl_setup(params, load, speed):
    from lubedyn.lubrication.ehl import EHLContact, EHLOptions, Traction  # deferred: scikit-fem

    line = _get(params, "contact") == "line"
    res = _get(params, "resolution", "default")
    table = EHL_RESOLUTIONS["line" if line else "point"]
    if res not in table:
        raise unknown_choice("resolution", res, list(table))
    traction = Traction(_get(params, "traction_model", "limiting_shear"),
                        float(_get(params, "limiting_shear_stress", 5e6)),
                        float(_get(params, "limiting_shear_slope", 0.08)))
    contact = EHLContact(
        float(params["radius_x"]), None if line else float(params["radius_y"]), float(params["e_star"]),
        _lubricant(params), float(speed), load=float(load), traction=traction)
    if line and float(params.get("inlet_film_lengths", 0.0)) > 0:
        from lubedyn.lubrication.ehl import EHLGrid  # deferred: scikit-fem

        # fixed node count on a domain that grows smoothly with the film (_film_scaled_domain)
        x_lo, x_hi = _film_scaled_domain(params, contact)
        grid = EHLGrid(nx=table[res], x_min=x_lo, x_max=x_hi, **_graded_fields(params, contact))
    else:
        grid = _ehl_grid(table[res], line, float(params["x_min"]), float(params["x_max"]), float(params["y_max"]))
    return contact, grid, EHLOptions(pseudo_transient=float(_get(params, "pseudo_transient", 0.0)))


def _ehl_grid(nodes, line: bool, x_min: float, x_max: float, y_max: float):
    """EHLGrid on [x_min, x_max] (x |y| <= y_max) with the node spacing of ``nodes`` on the reference domain.

    The spacing (in Hertz semi-axes) of :data:`EHL_RESOLUTIONS` is kept: nx - 1 = round((x_max - x_min)
    / dx_ref), ny - 1 = round(2 y_max / dy_ref), ny odd (a node row on the centre line).  The x range
    is then moved to start x_max - (nx - 1) dx_ref, so that the nodes sit at the same x/b as on the
    reference domain (the inlet is extended by whole cells: x_min = -18.5 instead of -20 would put
    every node elsewhere).  The reference domain itself gives the table's grid."""
    from lubedyn.lubrication.ehl import EHLGrid  # deferred: scikit-fem

    ref = EHL_REFERENCE_DOMAIN["line" if line else "point"]
    nx_ref = nodes if line else nodes[0]
    dx = (ref[1] - ref[0]) / (nx_ref - 1)
    cells = max(8, int(round((x_max - x_min) / dx)))
    x_lo = x_max - cells * dx
    if line:
        return EHLGrid(nx=cells + 1, x_min=x_lo, x_max=x_max)
    dy = 2 * ref[2] / (nodes[1] - 1)
    ycells = max(2, int(round(2 * y_max / dy)))
    ycells += ycells % 2
    return EHLGrid(nx=cells + 1, ny=ycells + 1, x_min=x_lo, x_max=x_max, y_max=0.5 * ycells * dy)


_EHL_CACHE: dict = {}
_EHL_CACHE_SIZE = 64


def _ehl_key(params, load, speed):
    return (tuple(sorted((k, v) for k, v in params.items())), float(load), float(speed))


def _ehl_secant_coefficients(contact, grid, options, sol, step):
    """K, C as central secants of steady solves: load (1 +- ``step``) Q, and squeeze velocity +-v_s.

    K = -2 step Q / (h00(Q(1 + step)) - h00(Q(1 - step))); at the load Q with a squeeze
    velocity dh00/dt = +-v_s, v_s = ``step`` u_e h_c / b, by implicit differentiation of
    Q(h00, dh00/dt) at fixed Q: C = -K (h00(+v_s) - h00(-v_s)) / (2 v_s).  Each solve
    (lubedyn.lubrication.ehl.solve_ehl, load balance) starts from the steady state ``sol``.
    Why a finite secant and not the tangent: the discrete load F(h00) is only piecewise
    smooth -- each time a node of the outlet (cavitation) boundary changes side, dF/dh00
    jumps.  Measured on paper B's inner contact at 54 N (49 x 25 nodes, x in [-9, 1.5]),
    u_e = 24..28 m/s: the tangent (linearised, or central differences in h00 with step
    1e-3 h_c: they agree to 0.1 %) K = 4.93, 4.87, 4.91, 5.08, 4.80e7 N/m (65 x 33 nodes:
    4.83, 5.28, 4.77, 5.06e7 -- refining does not smooth it); central differences over
    +-3 % h_c 4.91, 4.93, 4.94, 4.91, 4.87e7, C monotone in u_e.  Prescribed-approach solves
    at +-3 % h_c fail at some points (inner race, 288 N, 25 and 30 m/s), and a load step
    moves h00 by ~(2/3) step delta_Hertz >> step h_c, which smooths more.  Each solve tries
    the Newton variants of :func:`ehl_load_response` (same discrete problem), from the
    steady state and from scratch; if all fail, half the step; then the tangent (logged).
    """
    import dataclasses

    from lubedyn.lubrication.ehl import ehl_normal_coefficients, solve_ehl  # deferred: scikit-fem

    w = float(contact.load)
    fields = {f.name for f in dataclasses.fields(options)}
    variants = [{}] + [v for v in ({"first_order_start": "every_grid"}, {"method": "active_set"}) if set(v) <= fields]
    variants += [{"max_step": 1.0, "max_iter": 150}, {"max_step": 0.5, "max_iter": 150}]

    ref_x_min = _longer_inlet(grid, contact.is_line)
    tries = [({}, sol)]
    if ref_x_min is not None:
        # long inlet: the short-inlet solution of the changed contact, prolonged (see ehl_load_response;
        # measured: paper B's inner race at 1200 N, 30 m/s on x in [-18.5, 1.5] b, all four solves
        # stall from the steady state with every Newton variant and converge from this start)
        tries.append(({}, "short inlet"))
    tries += [(v, start) for v in variants for start in (sol, None) if (v, start) != ({}, sol)]

    def h00(**change):
        # the fallbacks of ehl_load_response (other Newton strategies, same discrete problem)
        errors = []
        changed = dataclasses.replace(contact, **change)
        for v, start in tries:
            opts = dataclasses.replace(options, **v)
            try:
                if isinstance(start, str):
                    start = _short_inlet_start(changed, grid, opts, ref_x_min)
                return solve_ehl(changed, grid, opts, initial=start).h00
            except (ConvergenceError, np.linalg.LinAlgError) as exc:
                errors.append(str(exc))
        raise ConvergenceError(" / ".join(errors[-2:]))

    for st in (step, 0.5 * step):
        try:
            K = -2 * st * w / (h00(load=w * (1 + st)) - h00(load=w * (1 - st)))
            vs = st * contact.mean_speed * sol.central_film_thickness / sol.problem.bx
            C = -K * (h00(squeeze_velocity=contact.squeeze_velocity + vs)
                      - h00(squeeze_velocity=contact.squeeze_velocity - vs)) / (2 * vs)
            return K, C
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            log.warning("EHL secant coefficients with step %g failed (%s)", st, exc)
    log.warning("EHL secant coefficients failed; using the linearised tangent")
    K, C, _ = ehl_normal_coefficients(contact, grid, options, steady=sol)
    return K, C


def _longer_inlet(grid, line: bool):
    """The reference domain's inlet x_min [Hertz semi-axes] if ``grid`` starts upstream of it (a long
    inlet, whose heavy loads are started from the short-inlet solution), else None."""
    ref_x_min = EHL_REFERENCE_DOMAIN["line" if line else "point"][0]
    return ref_x_min if grid.x_min < ref_x_min - 1e-9 else None


def _short_inlet_start(contact, grid, options, x_min):
    """Start for ``grid``: the steady solution on the same nodes with the inlet cut at ``x_min`` (Hertz
    semi-axes), returned as it is: ``solve_ehl`` interpolates a start from another grid onto its own
    (multilinear, zero upstream of the short inlet)."""
    import dataclasses

    from lubedyn.lubrication import ehl  # deferred: scikit-fem

    if grid.graded:  # the same nodes count on the shorter domain (only a start)
        short = dataclasses.replace(grid, x_min=x_min)
    else:
        cells = int(round((grid.x_max - x_min) * (grid.nx - 1) / (grid.x_max - grid.x_min)))
        dx = (grid.x_max - grid.x_min) / (grid.nx - 1)
        short = dataclasses.replace(grid, nx=cells + 1, x_min=grid.x_max - cells * dx)
    sol = None
    for variant in ({}, {"method": "active_set"}):
        try:
            sol = ehl.solve_ehl(contact, short, dataclasses.replace(options, **variant))
            break
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            error = exc
    if sol is None:
        raise ConvergenceError(f"short-inlet start: {error}")
    return sol


# Continuation path of a film-scaled line contact that does not converge from the solver's own start
# (speed fraction, inlet fraction of the final domain) -- see _continuation_start
# Continuation paths of a film-scaled line contact: steps (load fraction, speed fraction, inlet fraction
# of the step's own domain), tried in order (_continuation_start).  Measured need (Eyring flow):
# - the inlet alone grown from 0.15: light loads, where the solver's own start fails on the long domain
#   (cup at 0.7 kN/m, 28 m/s, 129 nodes: converges on 0.1 and 0.2 of the inlet, fails on 0.35, 0.6, 1);
# - from a lighter load: the transition M ~ 0.5-1 (cone at 39.8 kN/m, 14 m/s, 257 nodes: fails from its
#   own start, from 0.7-1.15 times the speed and from 1.25 and 1.5 times the load; converges from 0.67
#   and 0.8 times the load, to the same film to 1e-15 from both; at 59.6 kN/m, 28 m/s only from 0.67);
# - speed and inlet together: heavy load at high speed (100 kN/m, 25 m/s).
CONTINUATION_PATHS = (((1.0, 1.0, 0.15), (1.0, 1.0, 0.3), (1.0, 1.0, 0.5), (1.0, 1.0, 0.75)),
                      ((0.67, 1.0, 1.0), (0.8, 1.0, 1.0), (0.9, 1.0, 1.0)),
                      ((0.67, 1.0, 1.0),), ((0.5, 1.0, 1.0), (0.75, 1.0, 1.0)),
                      ((1.0, 0.5, 0.35), (1.0, 0.7, 0.6), (1.0, 0.85, 0.8)))


def _continuation_start(params, contact, grid, options):
    """Start for a film-scaled line contact (``inlet_film_lengths`` > 0): converged solutions along
    :data:`CONTINUATION_PATHS` -- a shorter inlet, a lighter load, or a lower speed, each
    from the previous, ending on the final grid (the returned solution is the point itself)
    (``solve_ehl`` interpolates a start from another grid onto its own).  Why (measured, 257 nodes,
    Eyring flow): the solver's own start (Hertz pressure, nested grids) fails where the Hertz zone is
    narrower than a cell of the coarse levels (1 kN/m: the domain spans 850 b) and at high speed with
    heavy load (100 kN/m, 25 m/s, M = 0.97: iteration limit); from a lower-speed, shorter-inlet
    solution both converge.  Raises ConvergenceError naming the step that failed."""
    import dataclasses

    from lubedyn.lubrication.ehl import EHLGrid, solve_ehl  # deferred: scikit-fem

    errors = []
    for path in CONTINUATION_PATHS:
        sol = None
        try:
            for fw, fu, fd in path:
                c = dataclasses.replace(contact, load=contact.load * fw, mean_speed=contact.mean_speed * fu)
                lo, hi = _film_scaled_domain(params, c)
                g = dataclasses.replace(grid, x_min=min(fd * lo, -1.5), x_max=max(fd * hi, 1.5),
                                        **_graded_fields(params, c))
                sol = solve_ehl(c, g, options, initial=sol)
            # the last step's solution is only a start for the final grid: converge it there
            return solve_ehl(contact, grid, options, initial=sol)
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            errors.append(f"continuation step (load x {fw}, speed x {fu}, inlet x {fd}): {exc}")
    raise ConvergenceError(" / ".join(errors))


# Load continuation of a film-scaled line contact (ehl_load_response, attempt "lighter"): converge the
# point at LIGHTER_LOAD_STEP times the load -- with every fallback of ehl_load_response, recursively, at
# most LIGHTER_LOAD_DEPTH levels (0.9**8 = 0.43) -- and start from it.  Measured need (cone, 257 nodes,
# Eyring flow): 72.7 kN/m, 17.7 m/s (M = 0.84) and 80.3 kN/m, 19.8 m/s (M = 0.88) fail from the solver's
# own start and along every CONTINUATION_PATHS path, because each path's first step (0.5 or 0.67 of the
# load, speed 0.5) is itself solved from the solver's own start, which fails at M ~ 0.4-0.9 (singular
# Jacobian, or the film collapsing to the floor from the Hertz start); from the converged 66 kN/m state
# (0.91 of the load) the same solve converges in 14 Newton iterations with every Newton variant, to the
# same film to 1e-15.  At 80.3 kN/m, 19.8 m/s (M = 0.88) the default Newton step (max_step 2 p_Hertz) cycles
# from every converged neighbour (0.9, 0.95, 0.98, 1.02, 1.05, 1.1 times the load: steps of 2 p_Hertz, the
# cavitated set flipping), and max_step 0.5 converges from each of them in 16 iterations to the same film
# (7.0943 um, to 1e-15): the continuation's final solve takes the damped step.
LIGHTER_LOAD_STEP = 0.9
LIGHTER_LOAD_DEPTH = 8


def ehl_load_response(params: dict, load: float, speed: float, *, _depth: int = 0) -> dict:
    """EHL solve at element load ``load`` = Q [N] and entrainment speed ``speed`` [m/s] (SRR-independent).

    A line contact carries Q/``length`` per unit length; its stiffness and
    damping are returned for the whole ``length``.  Normal coefficients
    (``params["coefficients"]``)::

        Film stiffness  K = -dF/dh00        (h00 the rigid-body separation, -h00 the approach)
        Film damping    C = -dF/d(dh00/dt)  (at fixed h00)

    - ``"linearised"`` (default): :func:`lubedyn.lubrication.ehl.ehl_normal_coefficients`
      of the EHL module (one extra linear solve about the steady state, the
      cavitated set frozen);
    - ``"load_steps"``: two more steady solves, load (1 + 1e-3) Q and the load
      with a squeeze velocity dh00/dt = v_s = 1e-3 u_e h_c/b; K = -dQ/dh00
      along the steady states and, by implicit differentiation of
      Q(h00, dh00/dt) at fixed Q, C = -K dh00/d(dh00/dt).  A second method:
      measured against the linearised one on paper B's inner contact (smoke
      grid) K +2.0 %, C -0.5 %; paper A's roller (10 kN, 10 m/s) K +0.3 %,
      C +0.2 %;
    - ``"secant"`` (ball races' default): central secants of four steady solves, load
      (1 +- ``secant_step``) Q and squeeze velocity +-``secant_step`` u_e h_c/b
      (:func:`_ehl_secant_coefficients`).

    Cached per process (the slide-to-roll ratio only changes the traction,
    post-processing of the same pressure).
    """
    import dataclasses

    from lubedyn.lubrication.ehl import solve_ehl  # deferred: scikit-fem

    key = _ehl_key(params, load, speed)
    if key in _EHL_CACHE:
        if isinstance(_EHL_CACHE[key], ConvergenceError):  # a failed point fails once per process, not per SRR node
            raise _EHL_CACHE[key]
        return _EHL_CACHE[key]
    line = params["contact"] == "line"
    length = float(params["length"]) if line else 1.0  # 1 m for the per-length roller kinds
    w = float(load) / length
    method = _get(params, "coefficients", "linearised")
    if method not in ("linearised", "load_steps", "secant"):
        raise unknown_choice("coefficients", method, ("linearised", "load_steps", "secant"))
    contact, grid, options = _ehl_setup(params, w, speed)
    text = f"Load [N] = {load:.6g}, Entrainment speed [m/s] = {speed:.6g}"
    # Fallbacks, in order: other Newton strategies on the same discrete problem (the
    # answer does not change), continuation from twice the load, and last a slightly
    # larger domain (changes the film by ~0.2 % at paper B's inner contact; on the roller's
    # 257 nodes h_min and the damping by ~4 % at 5 kN, 6.5 m/s: a point that needs it is
    # discretised differently from its neighbours.  Extending the domain by whole cells
    # instead, so that the contact's nodes stay put, made the two roller points that need this
    # fallback (14.1 kN, 3 m/s; 20 kN, 13.9 m/s) fail altogether, as measured).  Measured: paper B's inner contact at
    # Q = 178 N, u_e = 30 m/s on 49 x 25 nodes (M = 120, L = 32) stalls with the default
    # Fischer-Burmeister Newton and converges, to the same h_c to 1e-11, with a
    # first-order start on every grid or with the active-set method; the roller line
    # contact at Q = 14.1 kN, u_e = 30 m/s (M = 3, L = 77) failed with max_step 2, 0.5
    # and 0.25 and converged with 1; light strongly piezoviscous line contacts (M ~ 1-2)
    # converge only from a heavier-load solution.
    fields = {f.name for f in dataclasses.fields(options)}
    variants = [{}]
    if "first_order_start" in fields:
        variants.append({"first_order_start": "every_grid"})
    if "method" in fields:
        variants.append({"method": "active_set"})
    variants += [{"max_step": 1.0, "max_iter": 150}, {"max_step": 0.5, "max_iter": 150}]
    attempts = [(grid, dataclasses.replace(options, **v)) for v in variants]
    ref_x_min = _longer_inlet(grid, line)
    if ref_x_min is not None:
        # a long inlet (ball races: x_min = -18.5): start from the solution on the reference inlet,
        # prolonged (measured: paper B's races at 700-1200 N, M = 480-2700, fail on x in [-18.5, 1.5]
        # from the nested-iteration start with every Newton variant above and converge in 1-2 s from
        # the x_min = -6 solution; the pressure upstream of -6 b is negligible there)
        attempts.insert(1, (grid, options, "short inlet"))
    slow = dataclasses.replace(options, max_step=0.5, max_iter=150)
    if contact.lubricant.eyring_stress is not None:
        # Eyring flow: start from the Newtonian solution of the same point (same grid, so the
        # discretisation stays that of the neighbours; measured on the roller map, 257 nodes:
        # the larger-domain fallback below moved h_c by 2.7 % at 5 kN, 7.7 m/s)
        attempts.append((grid, slow, "newtonian"))
    film_scaled = line and float(params.get("inlet_film_lengths", 0.0)) > 0
    if film_scaled:
        # continuation in speed and inlet length (_continuation_start): same final grid and problem
        attempts.insert(1, (grid, options, "continuation"))
        if _depth < LIGHTER_LOAD_DEPTH:
            # load continuation from a lighter converged state, itself solved with these fallbacks, with a
            # damped Newton step (LIGHTER_LOAD_STEP)
            attempts.insert(2, (grid, slow, "lighter"))
            if options.pseudo_transient > 0:
                # ... and with the undamped step: with the pseudo-transient Newton the damped step is the slower
                # (measured: paper A's cup, Dowson-Higginson film, graded 257 nodes, 109.6 kN/m, 8.3 m/s (M = 1.64)
                # fails with every other fallback and with max_step 0.5 from the converged 0.9 of the load, and
                # converges from it in 50 iterations with the default step)
                attempts.insert(2, (grid, options, "lighter"))
    attempts.append((grid, slow, 2.0))
    if line and not film_scaled:
        attempts.append((dataclasses.replace(grid, x_max=grid.x_max + 1.0), slow))
    else:
        attempts.append((dataclasses.replace(grid, y_max=grid.y_max + 0.5), slow))
    hb = contact.lubricant.herschel_bulkley
    if hb is not None:
        # a grease (rheology = "herschel_bulkley"): the solver's own Newtonian starts (lubedyn.lubrication.ehl.solve,
        # _solve_hb: four apparent viscosities), then the same with a damped step.  The oil's continuations
        # are left out: each of their solves from scratch is itself those four starts, and a grease the
        # solver cannot reach (Table 2's lithium, n = 0.31) would take minutes per point before failing
        attempts = [(grid, options), (grid, slow)]
    errors = []
    for number, attempt in enumerate(attempts):
        grid, options = attempt[:2]
        try:
            start = None
            if len(attempt) > 2 and attempt[2] == "short inlet":
                start = _short_inlet_start(contact, grid, options, ref_x_min)
            elif len(attempt) > 2 and attempt[2] == "continuation":
                start = _continuation_start(params, contact, grid, options)
            elif len(attempt) > 2 and attempt[2] == "lighter":
                start = ehl_load_response(params, float(load) * LIGHTER_LOAD_STEP, speed, _depth=_depth + 1)["solution"]
            elif len(attempt) > 2 and attempt[2] == "newtonian":
                newtonian = dataclasses.replace(contact.lubricant, eyring_stress=None)
                start = solve_ehl(dataclasses.replace(contact, lubricant=newtonian), grid, options)
            elif len(attempt) > 2:
                start = solve_ehl(dataclasses.replace(contact, load=w * attempt[2]), grid, options)
            if len(attempt) > 2 and attempt[2] == "continuation":
                # already converged on this grid (a re-solve from it met an exactly singular Newton
                # matrix at the converged state: 59.6 kN/m, 28 m/s, 257 nodes)
                sol = start
            else:
                sol = solve_ehl(contact, grid, options, initial=start)
            if method == "secant" and contact.moes_M < float(_get(params, "secant_min_moes_M", 0.0)):
                # light, hydrodynamic loads: the tangent (see _roller_params, "secant_min_moes_M")
                from lubedyn.lubrication.ehl import ehl_normal_coefficients  # deferred: scikit-fem

                K, C, _ = ehl_normal_coefficients(contact, grid, options, steady=sol)
            elif method == "secant":
                K, C = _ehl_secant_coefficients(contact, grid, options, sol, float(_get(params, "secant_step", 0.05)))
            elif method == "linearised":
                from lubedyn.lubrication.ehl import ehl_normal_coefficients  # deferred: scikit-fem

                K, C, _ = ehl_normal_coefficients(contact, grid, options, steady=sol)
            else:
                eps = 1e-3
                sol2 = solve_ehl(dataclasses.replace(contact, load=w * (1 + eps)), grid, options, initial=sol)
                vs = 1e-3 * speed * sol.central_film_thickness / sol.problem.bx
                sq = solve_ehl(dataclasses.replace(contact, squeeze_velocity=vs), grid, options, initial=sol)
                K = -w * eps / (sol2.h00 - sol.h00)
                C = -K * (sq.h00 - sol.h00) / vs
            break
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            errors.append(str(exc))
            log.info("EHL point (%s): attempt %d failed: %s", text, number + 1, exc)
    else:
        if hb is not None:
            log.info("EHL point (%s), Herschel-Bulkley: %s", text, " / then: ".join(errors))
            err = ConvergenceError(
                f"params.rheology = 'herschel_bulkley' (hb_consistency = {contact.lubricant.viscosity.eta0:g} Pa s^n, "
                f"hb_yield_stress = {hb.yield_stress:g} Pa, hb_exponent = {hb.exponent:g}): the EHL line contact did "
                f"not converge at {text} from the solver's Newtonian starts, nor with a damped step (measured on "
                "the roller kinds: Table 2's polyurea and calcium converge at 50-135 kN/m, 10 m/s, lithium does not; "
                "change the grease's "
                "parameters or the axes)")
        else:
            err = ConvergenceError(f"EHL point ({text}): {' / then: '.join(errors)}")
        if _depth == 0:  # (a failure inside the load continuation had fewer fallbacks than a direct call has)
            if len(_EHL_CACHE) >= _EHL_CACHE_SIZE:
                _EHL_CACHE.pop(next(iter(_EHL_CACHE)))
            _EHL_CACHE[key] = err
        raise err
    if number:
        log.info("EHL point (%s) converged at attempt %d (%s)", text, number + 1, options)
    out = {
        "solution": sol,
        "Central film thickness [m]": _film_at_centre(sol) if film_scaled else sol.central_film_thickness,
        "Minimum film thickness [m]": sol.minimum_film_thickness,
        "Maximum pressure [Pa]": sol.maximum_pressure,
        "Film stiffness [N/m]": float(K) * length,
        "Film damping [N s/m]": float(C) * length,
        "Approach [m]": -float(sol.h00),
    }
    if len(_EHL_CACHE) >= _EHL_CACHE_SIZE:
        _EHL_CACHE.pop(next(iter(_EHL_CACHE)))
    _EHL_CACHE[key] = out
    return out


def _film_at_centre(sol) -> float:
    """Film thickness [m] at x = 0 of a line contact: the P1 film interpolated linearly between the two
    nodes around x = 0 (the film-scaled kinds' central film).  Why not the nearest node
    (``EHLSolution.central_film_thickness``): on a film-scaled domain the nodes move relative to the
    contact from one load to the next, the nearest node jumps from one side of x = 0 to the other, and the
    film's slope across the Hertz zone turns that into a sawtooth -- measured on the cone at 17.75 m/s,
    150-300 kN/m (257 nodes): h_c 6.742, 6.799, 6.880, 6.703, 6.777, 6.871 um at 150, 160, 170, 181, 193,
    206 kN/m (-2.6 % between 170 and 181 kN/m), which the map missed by 3.2 % at 254 kN/m."""
    x, h = sol._centre_line(sol.film_thickness)
    return float(np.interp(0.0, x, h))


def evaluate_ehl(params: dict, point: dict) -> dict:
    """One EHL contact point: "Load [N]", "Entrainment speed [m/s]", "Slide-to-roll ratio [-]".

    Outputs :data:`EHL_OUTPUTS`; "Traction coefficient [-]" = Couette friction
    over load from the limiting-shear law (tau = min(eta du/h, tau_L0 +
    gamma p), tau_L0 = 5 MPa, gamma = 0.08 by default: mineral-oil values; the
    papers give none for the race contacts), positive for SRR > 0 (u2 > u1),
    exactly odd in SRR (isothermal: the pressure does not depend on sliding).
    """
    import dataclasses

    load = float(point["Load [N]"])
    speed = float(point["Entrainment speed [m/s]"])
    srr = float(point.get("Slide-to-roll ratio [-]", 0.0))
    base = ehl_load_response(params, load, speed)
    sol = base["solution"]
    c = dataclasses.replace(sol.contact, slide_to_roll=srr)
    traction = dataclasses.replace(sol, contact=c).traction_coefficient()
    out = {k: float(v) for k, v in base.items() if k not in ("solution", "couette", "transition")}
    out["Traction coefficient [-]"] = float(traction)
    return out


LINE_RENAMES = {"Film stiffness [N/m]": "Film stiffness per length [N/m^2]",
                "Film damping [N s/m]": "Film damping per length [N s/m^2]",
                "Approach [m]": "Central deflection [m]"}
# "Central deflection [m]" u(0) = h_c - h00 (> 0 at every point): the approach -h00 of the per-length
# kinds changes sign at 50-100 kN/m (-180 um at 0.7 kN/m, 28 m/s; +12 um at 300 kN/m, 8 m/s), where a
# relative interpolation error means nothing; a consumer takes approach = u(0) - h_c.  (u is the strip
# kernel's deflection, lubedyn.lubrication.elastic, referenced as there: a line contact's approach is defined
# only up to a constant.)
EHL_LINE_OUTPUTS = tuple(LINE_RENAMES.get(name, name) for name in EHL_OUTPUTS)

# Traction of the per-length kinds on a sheared slide-to-roll coordinate (see evaluate_ehl_line, "Traction").
ROLLER_TRANSITION = "Transition slide-to-roll ratio [-]"
ROLLER_TRACTION_NORMALISED = "Traction coefficient at normalised slip [-]"
ROLLER_TRACTION_SHEAR = {
    "values": ROLLER_TRACTION_NORMALISED,  # tabulated: mu(Q, u, sigma s_t), sigma = T(axis coordinate)
    "shift": ROLLER_TRANSITION,            # tabulated: s_t(Q, u), constant along the slide-to-roll axis
    "axis": 2,                             # the slide-to-roll axis
    # T: ln sigma = a sinh(b ln(s/centre)), 1e-5..0.1 onto 1e-6..1e6, 1.5 times the axis' node density at
    # sigma = 1 (the front: 6 nodes per decade of sigma on 37 axis nodes), 6.7 times thinner at the ends
    # (1.3 per decade, where the traction is a power law of the slip)
    "centre": 1e-3, "b": 0.352,
    "a": math.log(1e6) / math.sinh(0.352 * math.log(100.0)),
    "transition": (1e-7, 10.0),            # s_t saturates smoothly (tanh in log) into this range
}
EHL_LINE_OUTPUTS = EHL_LINE_OUTPUTS + (ROLLER_TRANSITION, ROLLER_TRACTION_NORMALISED)


def evaluate_ehl_line(params: dict, point: dict) -> dict:
    """One point of a per-length line-contact kind (``ehl_roller_cone``, ``ehl_roller_cup``): "Line load
    [N/m]", "Entrainment speed [m/s]", "Slide-to-roll ratio [-]".  Outputs :data:`EHL_LINE_OUTPUTS`:
    as :func:`evaluate_ehl` with the film stiffness and damping per metre of contact length (a slice
    of length l: K l, C l), the central film interpolated at x = 0 (:func:`_film_at_centre`), and two
    outputs that carry the traction through a map:

    - "Transition slide-to-roll ratio [-]" c = S(s_t): s_t the slip at which the traction is half its
      Newtonian value (:func:`transition_slide_to_roll`, the Newtonian-to-limited front of this (load,
      speed)), S a smooth saturation into 1e-7..10 (:func:`saturated_transition`; S(s_t) = s_t on
      1e-6..1);
    - "Traction coefficient at normalised slip [-]" G = mu(T(s) c), T the fixed map of the slide-to-roll
      axis coordinate s onto the normalised slip sigma (:func:`normalised_slip`: 1e-5..0.1 onto 1e-6..1e6,
      denser at sigma = 1), odd in s.

    Traction: limiting shear makes mu(s) Newtonian (mu = a s) up to s_t and nearly
    flat above, and s_t falls by ~35 e-folds per e-fold of load in the hydrodynamic-to-EHL transition (cone,
    17.7 m/s: 4.6e-2 at 30 kN/m, 1.7e-6 at 40 kN/m) -- on the (load, speed, slide-to-roll) grid a front
    that crosses 1e-4..1e-3 between load nodes (the map missed by 665-877 %).  In sigma = s/c the front
    stays at sigma ~ 1 at every node.  A map of these kinds (``PointKind.sheared``, lubedyn.maps.FilmMap
    "sheared") therefore returns "Traction coefficient [-]" at (w, u, s) as G interpolated at
    (w, u, T^-1(s / c(w, u))), c interpolated; its own table of "Traction coefficient [-]" is kept for
    plots only.  A caller with a kernel of its own takes the kernel arrays of G and c and does the same.

    The traction itself (since 25 Nov 2026) is the film's as a Maxwell fluid of shear modulus
    ``film_shear_modulus`` G (paper A's assumed 1 GPa, the one the bearing's limited raceway law uses;
    :func:`maxwell_traction`, Johnson & Tevaarwerk 1977) capped by the limiting shear stress; G = inf is the
    rigid limiting-shear law of the ball kinds.  Why: with the rigid law the low-slip traction in the
    hydrodynamic-to-EHL transition (28-46 kN/m) was the viscosity at the one-cell pressure spike, which is
    neither grid-converged (cone, 31.66 kN/m, 17.7 m/s, mu(1e-4): 2.98e-4 / 5.79e-4 / 7.12e-4 on 257 / 513 /
    1025 nodes) nor smooth in load (s_t plateaued, then fell 50-fold within a 7 % load step; the map missed
    the traction by 14 % and s_t by 112 %).  An element crosses that spike in a small part of its relaxation
    time eta/G and shears elastically there: the Maxwell traction of the same states is 1.581e-4 / 1.595e-4 /
    1.596e-4, smooth in load on 257 nodes (interpolated along load sweeps at the map's node ratio 1.072: worst
    2-8 % against 50-140 % for the rigid law).  It also gives the heavy loads the finite initial slope of
    measured traction curves (2 G b^2/(u h) per metre when the whole strip shears elastically:
    lubedyn.lubrication.laws.traction.elastic_strip_slope), where the rigid Barus law was limited from SRR 1e-7 on."""
    import math

    if float(params.get("length", 1.0)) != 1.0:
        raise InputError(f"params.length = {params['length']!r}: a line-load kind works per metre (length = 1.0)")
    point = dict(point)
    point["Load [N]"] = float(point.pop("Line load [N/m]"))
    out = evaluate_ehl(params, point)
    out["Approach [m]"] = out["Central film thickness [m]"] + out["Approach [m]"]  # u(0) = h_c - h00
    out = {LINE_RENAMES.get(k, k): v for k, v in out.items()}
    base = ehl_load_response(params, point["Load [N]"], float(point["Entrainment speed [m/s]"]))
    shear_modulus = float(params.get("film_shear_modulus", math.inf))
    if "couette" not in base:
        base["couette"] = couette_profile(base["solution"])
    if "transition" not in base:
        base["transition"] = transition_slide_to_roll(base["couette"], shear_modulus)
    s_t = saturated_transition(base["transition"])
    srr = float(point.get("Slide-to-roll ratio [-]", 0.0))
    # the traction of the kind: the film's Maxwell shear (maxwell_traction; = the ball kinds' rigid law at G = inf)
    out["Traction coefficient [-]"] = math.copysign(maxwell_traction(base["couette"], abs(srr), shear_modulus), srr)
    out[ROLLER_TRANSITION] = s_t
    # odd in the slide-to-roll ratio, as the traction (the axis itself is > 0)
    out[ROLLER_TRACTION_NORMALISED] = (math.copysign(maxwell_traction(base["couette"], normalised_slip(abs(srr)) * s_t,
                                                                      shear_modulus), srr) if srr != 0.0 else 0.0)
    return out


def _traction_at(sol, srr: float) -> float:
    """Traction coefficient of the converged ``sol`` at slide-to-roll ratio ``srr`` (post-processing)."""
    import dataclasses

    c = dataclasses.replace(sol.contact, slide_to_roll=float(srr))
    return float(dataclasses.replace(sol, contact=c).traction_coefficient())


def couette_profile(sol) -> dict:
    """The Couette-shear data of a converged line contact at its quadrature points, in the order of x (the
    flow's direction): x [m] (node spacing gaps ``gap``, the first from the domain's inlet), the quadrature
    weights ``dx`` [m], gauge pressure ``p`` (>= 0), film ``h`` (>= the solver's floor), viscosity or
    consistency ``eta`` (the lubricant's law at p), the entrainment speed ``u``, the load per length ``load``,
    the traction law and the Herschel-Bulkley flow (None for an oil) -- the quadrature of
    ``EHLSolution._shear_integrals``."""
    P, c = sol.problem, sol.contact
    if not c.is_line:
        raise InputError("couette_profile: a line contact's solution is needed (point contacts: traction_coefficient)")
    b = P.basis
    x = np.asarray(b.global_coordinates(), float)[0].ravel()
    order = np.argsort(x, kind="stable")
    pq = np.maximum(np.asarray(b.interpolate(sol.pressure)), 0.0).ravel()[order]
    hq = np.asarray(b.interpolate(np.maximum(sol.film_thickness, P.o.h_floor * P.hscale))).ravel()[order]
    dx = np.broadcast_to(np.asarray(b.dx), b.interpolate(sol.pressure).shape).ravel()[order]
    xs = x[order]
    x0 = float(P.mesh.p[0].min())
    return {"x": xs, "gap": np.diff(xs, prepend=x0), "dx": np.array(dx), "p": pq, "h": hq,
            "eta": np.asarray(c.lubricant.viscosity(pq), float), "u": float(c.mean_speed), "load": float(sol.load),
            "traction": c.traction, "hb": c.lubricant.herschel_bulkley}


def maxwell_traction(profile: dict, srr: float, shear_modulus: float = math.inf) -> float:
    """Traction coefficient [-] (>= 0) of a line contact's Couette shear at slide-to-roll ratio ``srr`` >= 0,
    the film a Maxwell fluid of shear modulus G = ``shear_modulus`` [Pa] whose stress is capped by the
    traction law's limit (Johnson & Tevaarwerk 1977, Proc. R. Soc. A 356, 215: elastic, viscous and
    plastic in series), ``profile`` from :func:`couette_profile`.

    An element convected at the entrainment speed u through the contact is sheared at D = s u/h; its
    stress obeys (u/G) dtau/dx + tau/eta_e = D (eta_e = tau_v/D, tau_v the viscous stress at D: eta D for
    an oil, tau_y + phi D^n for a Herschel-Bulkley grease), integrated exactly between quadrature points
    with the coefficients of the later point, tau <- tau_v + (tau - tau_v) exp(-G gap D/(u tau_v)), and
    capped, tau <- min(tau, tau_L), tau_L = tau_L0 + gamma p (``limiting_shear``; no cap for
    ``newtonian``), from tau = 0 at the inlet; mu = sum tau dx / load.  G = inf is the rigid law of
    ``EHLSolution.traction_coefficient`` (tau = min(tau_v, tau_L)) to round-off.

    Why: with the rigid law the low-slip traction of a contact in the
    hydrodynamic-to-EHL transition is eta(p_max)-weighted -- half of int eta/h dx sits at the one or two
    quadrature points of the pressure spike (cone, 17.7 m/s, 31-33 kN/m, 257 nodes), so it jumps with the
    spike's discrete height (mu(1e-4) 2.98e-4 on 257, 5.79e-4 on 513, 7.12e-4 on 1025 nodes at 31.6 kN/m;
    not smooth in load on 257 or 513 nodes).  An element crosses that spike (0.1-0.3 b, 1e-7-1e-6 s at
    17.7 m/s) in a small part of its relaxation time eta/G (2e-5 s at eta = 2e4 Pa s, G = 1 GPa): there it
    shears elastically, and its stress no longer depends on eta."""
    s = float(srr)
    if s <= 0.0:
        return 0.0
    tr = profile["traction"]
    if tr.model not in ("limiting_shear", "newtonian"):
        raise InputError(f"params.traction_model = {tr.model!r}: the Maxwell traction of the line kinds takes "
                         "'limiting_shear' or 'newtonian'")
    p, h, eta, u = profile["p"], profile["h"], profile["eta"], profile["u"]
    D = s * u / h
    hb = profile["hb"]
    tau_v = eta * D if hb is None else hb.yield_stress + eta * D ** hb.exponent
    cap = (tr.limiting_shear_stress + tr.limiting_shear_slope * p) if tr.model == "limiting_shear" else np.full_like(p, np.inf)
    if not math.isfinite(shear_modulus):
        return float(np.sum(np.minimum(tau_v, cap) * profile["dx"])) / profile["load"]
    # z = gap/(u lambda), lambda = eta_e/G the relaxation time; tau_v (1 - e^-z) -> G D gap/u where eta_e is
    # large (the elastic limit), written with expm1 so that it does not round to 0
    z = shear_modulus * profile["gap"] * D / (u * tau_v)
    tau = _maxwell_march(tau_v * -np.expm1(-z), np.exp(-z), cap)
    return float(np.sum(tau * profile["dx"])) / profile["load"]


def _maxwell_march(gain, keep, cap):
    """tau_i = min(tau_{i-1} keep_i + gain_i, cap_i), tau_{-1} = 0 (see maxwell_traction)."""
    out = np.empty_like(gain)
    t = 0.0
    for i, (g, k, c) in enumerate(zip(gain.tolist(), keep.tolist(), cap.tolist())):
        t = t * k + g
        if t > c:
            t = c
        out[i] = t
    return out


def transition_slide_to_roll(profile, shear_modulus: float = math.inf) -> float:
    """Slide-to-roll ratio s_t [-] at which the traction (:func:`maxwell_traction` of the
    :func:`couette_profile` ``profile``, or of a solution) is half its linear value: mu(s_t) = s_t a / 2,
    a = lim mu(s)/s (taken at s = 1e-12, below every cap on the kinds' axes: the Newtonian slope int eta
    u_e/h dx / w for G = inf, the Maxwell one otherwise).  mu(s)/(a s) falls monotonically from 1 (no
    point capped) to 0 (every point at its limiting stress tau_L0 + gamma p); its half point is the
    linear-to-limited front of the contact.  Bisection in log s over [1e-16, 1e6]; inf if the traction is
    above half its linear value at 1e6, 0 if below at 1e-16 (a grease without elasticity: the yield stress
    makes a infinite)."""
    if not isinstance(profile, dict):
        profile = couette_profile(profile)
    s0 = 1e-12
    slope = maxwell_traction(profile, s0, shear_modulus) / s0
    if not (slope > 0.0 and math.isfinite(slope)):
        return 0.0

    def ratio(ln_s):
        return maxwell_traction(profile, float(np.exp(ln_s)), shear_modulus) / (np.exp(ln_s) * slope)

    lo, hi = np.log(1e-16), np.log(1e6)
    if ratio(hi) > 0.5:
        return float("inf")
    if ratio(lo) < 0.5:
        return 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ratio(mid) > 0.5 else (lo, mid)
    return float(np.exp(0.5 * (lo + hi)))


def saturated_transition(s_t: float) -> float:
    """The tabulated transition slide-to-roll ratio: ``s_t`` itself within 1e-6..1 (the slide-to-roll
    axis 1e-5..0.1 and a decade either side), saturating beyond it into ROLLER_TRACTION_SHEAR["transition"]
    = (1e-7, 10): ln c = ln s_t inside, ln c = ln 1 + r tanh((ln s_t - ln 1)/r) above (r = ln 10; below
    likewise), twice continuously differentiable (tanh'(0) = 1, tanh''(0) = 0).  A hard clip would put a
    kink into the tabulated s_t; a tanh over the whole range moved the front off sigma = 1 by up to 0.16
    in ln sigma inside the axis (measured on tests/test_maps.py's front: 1.6 % against 0.x %)."""
    lo, hi = (math.log(v) for v in ROLLER_TRACTION_SHEAR["transition"])
    r = math.log(10.0)
    lo_in, hi_in = lo + r, hi - r
    if s_t <= 0.0:
        return math.exp(lo)
    if math.isinf(s_t):
        return math.exp(hi)
    x = math.log(s_t)
    if x > hi_in:
        x = hi_in + r * math.tanh((x - hi_in) / r)
    elif x < lo_in:
        x = lo_in - r * math.tanh((lo_in - x) / r)
    return math.exp(x)


def normalised_slip(srr):
    """Normalised slip sigma = T(srr) of the slide-to-roll axis coordinate ``srr`` (> 0):
    ln sigma = a sinh(b ln(srr/centre)) (ROLLER_TRACTION_SHEAR; 1e-5..0.1 onto 1e-6..1e6)."""
    spec = ROLLER_TRACTION_SHEAR
    return np.exp(spec["a"] * np.sinh(spec["b"] * np.log(np.asarray(srr, dtype=float) / spec["centre"])))


def field_ehl_line(params: dict, point: dict):
    """The EHL pressure/film field of a per-length line-contact point as a pyvista grid."""
    response = ehl_load_response(params, float(point["Line load [N/m]"]), float(point["Entrainment speed [m/s]"]))
    return response["solution"].to_pyvista()


def field_ehl(params: dict, point: dict):
    """The EHL pressure/film field at ``point`` as a pyvista grid."""
    response = ehl_load_response(params, float(point["Load [N]"]), float(point["Entrainment speed [m/s]"]))
    return response["solution"].to_pyvista()

# Slide-to-roll ratio: log, 3 nodes per decade from SRR_MIN (traction is odd in the SRR: mu(-s) = -mu(s);
# below SRR_MIN a caller takes mu(SRR_MIN) s/SRR_MIN, see the module docstring, "Traction axis").
SRR_MIN = 1e-3
EHL_SRR_AXIS = AxisDef("Slide-to-roll ratio [-]", SRR_MIN, 0.1, 7, "log")
EHL_BALL_AXES = (
    AxisDef("Load [N]", 50.0, 1200.0, 6, "log"),
    AxisDef("Entrainment speed [m/s]", 6.0, 30.0, 4, "log"),
    EHL_SRR_AXIS,
)
# paper A runs at 2000-5000 rpm: u_e = 4.4-11 m/s on the inner race
EHL_ROLLER_AXES = (
    # 9 x 11 nodes (Eyring flow, 257 nodes): on 5 x 6 the map missed h_c by 3.1 % and the approach by
    # 6.5 % in the light-load, high-speed corner, where inlet shear thinning sets in (h_c at 5 kN grows
    # 4-5 % per speed step between 3.9 and 5.1 m/s against 9-10 % elsewhere); 9 x 11: max 1.8 % / 0.6 %
    AxisDef("Load [N]", 5000.0, 20000.0, 9, "log"),
    AxisDef("Entrainment speed [m/s]", 3.0, 15.0, 11, "log"),
    EHL_SRR_AXIS,
)

# Paper A's roller kinds (its Table 1 bearing at its operating ranges): line load 1-200 kN/m (centrifugal-only rollers
# 2.1 kN/m at 2 krpm up to 135 kN/m at 40 um preload, plus slice peaks), entrainment 8-25 m/s, SRR 1e-5..0.1.
# Axes with margin: 0.7-300 kN/m, 7-28 m/s.  Slide-to-roll: log from ROLLER_SRR_MIN = 1e-5 (the steady
# slips of 0.005-0.02 % lie on the axis, not on an extrapolation); odd in the SRR; below 1e-5 the
# consumer takes mu(s) = mu(1e-5) s/1e-5 (the "linear" convention of the ball maps,
# dynamics/cageless/layout.py TRACTION_MAP_BELOW_AXIS, with a lower first node).  The SRR nodes cost no
# EHL solve (the isothermal pressure does not depend on sliding).
ROLLER_SRR_MIN = 1e-5


def _roller_line_loads() -> tuple:
    """Line-load nodes [N/m] of the roller kinds: log-uniform in three bands, 0.7-14 kN/m (8 cells, ratio
    1.45), 14-56 kN/m (36 cells, ratio 1.039; 20 cells of 1.072 before 28 Nov 2026) and 56-300 kN/m (5 cells,
    ratio 1.40): 50 nodes.  The middle
    band holds the hydrodynamic-to-EHL knee (measured on 257 nodes, linearised K: d ln K/d ln w falls
    from 2.3-3.0 to ~0 within one 11 % load step at 20-22 kN/m (cone, 7 m/s), 34-38 (cone, 28 m/s),
    25-27 (cup, 7 m/s), 38-42 kN/m (cup, 28 m/s)) and the traction's Newtonian-to-limited front, whose
    transition slip s_t falls by 35 e-folds per e-fold of load there (cone, 17.7 m/s: s_t = 4.6e-2 at
    30 kN/m, 1.7e-6 at 40 kN/m).  On 16 log nodes (ratio 1.50) the knee fell inside one cell (K and C
    missed by 7-8 %).  With the smooth films of the rebuilt maps (Dowson-Higginson, graded grid) a map at
    node ratio 1.076 missed the traction by 3.0 % in the knee (cone, 7 m/s; benchmarks/roller_traction_sweeps.py,
    sweep dh_graded6_cone7) and one at 1.05 the damping by 3.18 % (24.5 kN/m, 7.5 m/s): hence 1.039."""
    bands = (np.geomspace(700.0, 1.4e4, 9), np.geomspace(1.4e4, 5.6e4, 37), np.geomspace(5.6e4, 3.0e5, 6))
    nodes = np.concatenate([bands[0], bands[1][1:], bands[2][1:]])
    return tuple(float(x) for x in nodes)


ROLLER_LINE_LOADS = _roller_line_loads()
EHL_ROLLER_LINE_AXES = (
    AxisDef("Line load [N/m]", 700.0, 3.0e5, len(ROLLER_LINE_LOADS), "log", explicit=ROLLER_LINE_LOADS),
    # 17 nodes (ratio 1.09; 13 of 1.12 before 28 Nov 2026): the knee moves with Moes' M ~ w/sqrt(u), so a
    # speed step moves it like a load step of its square root (with 13 speeds the rebuilt cone map missed
    # the damping by 4.7 % at 35 kN/m, 24.5 m/s)
    AxisDef("Entrainment speed [m/s]", 7.0, 28.0, 17, "log"),
    # 37 nodes (9 per decade): the traction is tabulated on the normalised slip, whose axis spans 12
    # decades on these nodes (3 per decade; ROLLER_TRACTION_SHEAR); the nodes cost no EHL solve
    AxisDef("Slide-to-roll ratio [-]", ROLLER_SRR_MIN, 0.1, 37, "log"),
)
