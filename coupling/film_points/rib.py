"""Kind ``ehl_rib``: the isothermal EHL point contact of paper A's roller end (a sphere, r_s = 136.2 mm) on
the cone's rib, per flange load and entrainment speed, with the base oil or a grease of Table 2.

Part of :mod:`lubedyn.film_points` (the package docstring gives the physics and sources).

Geometry (:func:`lubedyn.lubrication.laws.flange.rib_radii`, from the model's own contact point,
:func:`lubedyn.papers.wu2018.parameters.tapered_geometry`): R_x = R_circ = 168.96 mm along the
circumference, the entrainment and sliding direction (the rib is concave there), R_y = r_s = 136.2 mm along
the cone's generator; so the Hertz ellipse's major axis lies along the entrainment (k = b/a = 0.866).  E* of
steel on steel (112.6 GPa), Barus alpha = 4.662e-8 m^2/N (Table 1; for every grease), incompressible 870
kg/m^3.  The grease (``rheology = "herschel_bulkley"``, :func:`lubedyn.film_points.roller_grease_params`)
enters the Poiseuille flow (:mod:`lubedyn.lubrication.ehl`, Herschel-Bulkley flow: pure-rolling superposition,
so the film depends on the entrainment speed u_m and not on the sliding, as for a Newtonian film; the
isothermal solver has no shear heating, which the rib's large sliding, 0.48 u_m, would add).

Domain and grid: x in [-4.5, 1.5] b_x, |y| <= 3 b_y (the solver's defaults), square cells, nx by
``resolution`` (:data:`RIB_RESOLUTIONS`).  Solver: :func:`lubedyn.lubrication.ehl.solve_ehl` (Fischer-Burmeister
Newton; a grease from the Newtonian contact of its apparent viscosity, then the Herschel-Bulkley iteration or,
where that stalls, the homotopy of :func:`lubedyn.lubrication.ehl.solve._hb_homotopy`).

Where it converges (measured, 65 x 57 nodes, 30 C, 500 N and 11.3 m/s unless said): the thin films, i.e.
lithium grease (n = 0.31, apparent viscosity 2e-4 Pa s: Moes M = 150-570, L = 6-7 over 200-1000 N x
8-20 m/s): h_c 0.240 um, h_min 0.071 um (the homotopy; the direct Herschel-Bulkley step stalls), 60-300 s a
point on a shared core; up to about 500 N (its Newtonian start at 1500 N, 6 m/s, M = 1500-2500, fails on this
grid).  Not the thick films of the base oil, polyurea and calcium (Moes M = 1-10, L = 25-40: the light-load,
strongly piezoviscous corner): the Fischer-Burmeister Newton stalls, the active set cycles through the
cavitated set (a pseudo-transient continuation converged at one of five domains tried), the multigrid
stagnates below M ~ 2 and its film moves by 25 % with the domain's extent (y_max 3 -> 6 b_y: 10.17 -> 8.02 um
at 500 N).  There a point raises :class:`~lubedyn.lubrication.errors.ConvergenceError` (the solver's own,
naming every start).

Accuracy (lithium at 30 C, Fig. 14's point 215.9 N, 11.32 m/s unless said).  Grid: the Newtonian film of
lithium's apparent viscosity at 500 N, 11.3 m/s moves from 65 x 57 to 129 x 111 nodes by +3.0 % (h_c) and
+15 % (h_min): the default grid's films are about 4 % (h_c) low by Richardson's estimate.  Side extent y_max
3 -> 4.5 b_y: +0.01 %.  Inlet (the same spacing, 97 x 57 nodes): -7.5 b_x against the default -4.5, h_c +1.6 %,
h_min +0.8 % (so with the grid the map's films are about 5 % thin: lambda 1.52 -> ~1.60, share 0.051 -> ~0.042
at Fig. 14's point).  A shorter inlet starves the film: -3 b_x: -5.0 %, -1.5 b_x: -33 % (asperity share
0.051 -> 0.060 -> 0.159).  Against the closed forms: Hamrock-Dowson with the Newtonian film's
viscosity, +0.7 ... +4.5 % (h_c; h_min 0.42-0.64 times); the Herschel-Bulkley film is 1.23-1.56 times
Hamrock-Dowson's with the grease's apparent viscosity over the map's nodes (1.49 at Fig. 14's point; 1.34 /
1.29 / 1.44 at 15 / 50 / 70 C, 474 N, 12.2 m/s), so one correction factor would be off by up to 12 % where
the 3 x 3 map is within 0.6 % (its accuracy report).  The film's exponents over the map: load -0.20 ... -0.28,
speed 0.41-0.49 (Hamrock-Dowson at a fixed viscosity: -0.067, 0.67).
"""
from __future__ import annotations

from lubedyn.lubrication.errors import unknown_choice

from lubedyn.film_points.base import (AxisDef, GREASE_ALPHA, ROLLER_BASE_OIL_ETA0, ROLLER_BASE_OIL_RHO0, _get,
                                      _lubricant)
from lubedyn.lubrication.laws import flange as laws_flange
from lubedyn.papers.wu2018.parameters import tapered_geometry

#: nx on x in [-4.5, 1.5] b_x (ny: square cells on |y| <= 3 b_y, odd): 33 x 29, 65 x 57, 129 x 111
RIB_RESOLUTIONS = {"smoke": 33, "default": 65, "fine": 129}
RIB_AXES = (
    # the flange loads of paper A's Fa = 15 kN series (216 N at the quasi-static start) and the rib's entrainment
    # speed in the cage frame (8.1-20.2 m/s over 2-5 krpm, TaperedBearing.rib_speeds), with a margin.  Not the
    # heavier rib loads (to ~1000 N): lithium's Newtonian start there (Moes M = 850-1500 at 1000-1500 N, 6-8 m/s)
    # is beyond the 65-node grid's reach (measured: 1500 N, 6 m/s fails from every start)
    AxisDef("Flange load [N]", 150.0, 500.0, 3, "log"),
    AxisDef("Entrainment speed [m/s]", 7.0, 22.0, 3, "log"),
)
RIB_OUTPUTS = ("Central film thickness [m]", "Minimum film thickness [m]")


def rib_geometry() -> dict:
    """The rib contact from the model's geometry: ``sphere_radius`` r_s, ``rib_contact_radius`` r_P (the
    contact point's distance from the bearing axis) [m], ``flange_angle`` beta_f [rad], ``e_star`` [Pa]
    (radii: :func:`lubedyn.lubrication.laws.flange.rib_radii`)."""
    g = tapered_geometry()
    return {"sphere_radius": float(g.end_sphere_radius), "rib_contact_radius": float(g.flange_point[1]),
            "flange_angle": float(g.flange_contact_angle), "e_star": float(g.e_star)}


def ehl_rib_default_params() -> dict:
    """Paper A's rib contact with the base oil (eta0 = 0.1 Pa s assumed, as the tapered cases' [lubricant]);
    merge :func:`lubedyn.film_points.roller_grease_params` for a grease of Table 2."""
    return {
        **rib_geometry(),
        "eta0": ROLLER_BASE_OIL_ETA0, "alpha": GREASE_ALPHA, "rho0": ROLLER_BASE_OIL_RHO0,
        "viscosity_law": "barus", "density_law": "incompressible",
        "rheology": "eyring", "eyring_stress": None,  # no eyring_stress: Newtonian
        "hb_consistency": 0.0, "hb_yield_stress": 0.0, "hb_exponent": 1.0, "hb_creep": 0.0,
        "x_min": -4.5, "x_max": 1.5, "y_max": 3.0,
        "resolution": "default",
    }


def rib_contact(params: dict, load: float, speed: float):
    """``(EHLContact, EHLGrid)`` of one rib point."""
    from lubedyn.lubrication.ehl import EHLContact, EHLGrid  # deferred: scikit-fem

    res = _get(params, "resolution", "default")
    if res not in RIB_RESOLUTIONS:
        raise unknown_choice("resolution", res, list(RIB_RESOLUTIONS))
    rx, ry = laws_flange.rib_radii(float(params["sphere_radius"]), float(params["rib_contact_radius"]),
                                   float(params["flange_angle"]))
    contact = EHLContact(rx, ry, float(params["e_star"]), _lubricant(params), float(speed), load=float(load))
    grid = EHLGrid(nx=RIB_RESOLUTIONS[res], x_min=float(params["x_min"]), x_max=float(params["x_max"]),
                   y_max=float(params["y_max"]))
    return contact, grid


def evaluate_ehl_rib(params: dict, point: dict) -> dict:
    """One rib point: "Flange load [N]", "Entrainment speed [m/s]" -> :data:`RIB_OUTPUTS` (h_c at the node
    nearest the centre, h_min the smallest nodal film), plus (not tabulated) "Apparent viscosity [Pa s]"
    of a grease's start (0 for an oil) and "Hamrock-Dowson central film [m]" at the start's viscosity
    (:func:`lubedyn.lubrication.laws.flange.rib_film`, the closed form this kind replaces)."""
    from lubedyn.lubrication.ehl import EHLOptions, solve_ehl  # deferred: scikit-fem

    load, speed = float(point["Flange load [N]"]), float(point["Entrainment speed [m/s]"])
    contact, grid = rib_contact(params, load, speed)
    sol = solve_ehl(contact, grid, EHLOptions(check_resolution=False))
    start = sol.info.get("hb_start") or {}
    eta = float(start.get("apparent_viscosity", contact.lubricant.viscosity.eta0))
    hd = laws_flange.rib_film("hamrock_dowson", load, speed, eta, contact.lubricant.viscosity.pressure_viscosity,
                              contact.e_prime, float(params["sphere_radius"]), float(params["rib_contact_radius"]),
                              float(params["flange_angle"]))
    return {"Central film thickness [m]": sol.central_film_thickness,
            "Minimum film thickness [m]": sol.minimum_film_thickness,
            "Apparent viscosity [Pa s]": eta if start else 0.0,
            "Hamrock-Dowson central film [m]": hd}

