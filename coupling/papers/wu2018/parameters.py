"""Paper A: Wu, Xu & Deng, "Analysis of Dynamic Characteristics of Grease-Lubricated Tapered Roller
Bearings", *Shock and Vibration* 2018, 7183042.

Table 1 (bearing, cage, materials, grease at 30 C), Table 2 (Herschel-Bulkley rheology of three
greases at 15-70 C) and the operating points of Figs. 5-16.  Where the paper's tables and equations
do not fit together, the reading taken here is the one listed in ``docs/paper_a.md`` ("What paper A
leaves out"): the two roller end diameters of Table 1 are printed swapped (the large end is 24.76 mm);
the pitch diameter is the sum of the two raceway radii; what the paper does not give is
``source="assumed"`` with a reason.
The bearing's geometry (reconciliation of Table 1's non-common-apex values, rib, crown, cage and
guide-land placement) is :class:`lubedyn.lubrication.laws.tapered.TaperedRollerGeometry`, built from these
values; its quasi-static equilibrium is :mod:`lubedyn.dynamics.tapered.quasistatic`.  Default
reconciliation ``"common_apex"``: pitch radius, mean roller diameter, l_e and the roller axis angle
(the mean of the printed contact angles) are kept and the taper comes from a common apex, so the
raceway angles become 11.19 / 8.81 deg; ``"literal"`` keeps 15 / 5 deg and the roller's own 4.70 deg
taper (0.30 deg misfit per raceway, ends sliding +13.6 / -14.2 % on the cone).  The roller EHL
cases use the raceway, roller and grease values.
"""
from lubedyn.lubrication.laws.tapered import TaperedRollerGeometry

from lubedyn.papers import Parameter as P

NAME = "Wu2018"
CITATION = ("Z.-H. Wu, Y.-Q. Xu, S.-E. Deng, Shock and Vibration 2018, 7183042 "
            "(grease-lubricated tapered roller bearing)")

#: Herschel-Bulkley tau = tau_y + phi |D|^n of Table 2: grease -> [(T [C], tau_y [Pa], phi [Pa s^n], n)]
GREASE_TABLE = {
    "polyurea": [(15, 501.7, 11.87, 0.7731), (30, 351.8, 8.44, 0.7196), (50, 305.5, 6.16, 0.6621),
                 (70, 188.5, 6.10, 0.7378)],
    "lithium": [(15, 904.5, 54.35, 0.3053), (30, 805.2, 46.23, 0.3125), (50, 710.4, 41.13, 0.3151),
                (70, 339.8, 52.96, 0.3203)],
    "calcium": [(15, 990.8, 64.82, 0.3349), (30, 649.5, 49.23, 0.5344), (50, 336.1, 30.59, 0.5256),
                (70, 296.0, 35.88, 0.4356)],
}

VALUES = {
    # bearing (Table 1)
    "n_rollers": P(17, "count", "Table 1"),
    "effective_length": P("42.06 mm", "length", "Table 1"),
    "roller_large_end_diameter": P("24.76 mm", "length", "Table 1",
                                   "printed as the small end: the two end diameters are swapped in print "
                                   "(half-taper atan(3.455/42.06) = 4.70 deg ~ (15 - 5)/2 deg)"),
    "roller_small_end_diameter": P("17.85 mm", "length", "Table 1", "printed as the large end (see above)"),
    "roller_mean_diameter": P("21.305 mm", "length", "Table 1", "(24.76 + 17.85)/2"),
    "roller_end_sphere_radius": P("136.20 mm", "length", "Table 1"),
    "outer_contact_angle": P("15 deg", "angle", "Table 1", "cup raceway"),
    "inner_contact_angle": P("5 deg", "angle", "Table 1", "cone raceway"),
    "flange_contact_angle": P("83 deg", "angle", "Table 1"),
    "outer_raceway_radius": P("99.52 mm", "length", "Table 1"),
    "inner_raceway_radius": P("78.48 mm", "length", "Table 1"),
    "pitch_diameter": P("178.00 mm", "length", "Table 1", "2 x (78.48 + 99.52)/2: the raceway radii's mean"),
    "guide_land_clearance": P("0.5 mm", "length", "Table 1",
                              "read as diametral (0.25 mm radial), as eq. 43's (r_y - r_d)/2 suggests"),
    "guide_land_width": P("4.93 mm", "length", "Table 1"),
    "cage_outer_diameter": P("205.76 mm", "length", "Table 1"),
    "cage_inner_diameter": P("196.10 mm", "length", "Table 1"),
    "cage_thickness": P("5 mm", "length", "Table 1"),
    "pocket_clearance": P("0.27 mm", "length", "Table 1"),
    # --- geometry, slices, quasi-static (not all in Table 1: the readings of docs/paper_a.md) ---
    "geometry_reconciliation": P("common_apex", "text", "assumed",
                                 "Table 1 is not a common-apex design (docs/paper_a.md): keep R_p 89 mm, D_m, l_e and "
                                 "the 10 deg roller axis, taper from a common apex (phi 1.19 deg, raceways "
                                 "11.19/8.81 deg); 'literal' keeps 15/5 deg and is edge-loaded"),
    "rib_height": P("8 mm", "length", "assumed",
                    "not given; the 83 deg flange contact sits 3.96 mm (common apex) / 5.44 mm (literal) above "
                    "the cone raceway, so 8 mm (0.32 D_large) keeps it on the rib"),
    "guide_land_axial_gap": P("2 mm", "length", "assumed",
                              "Table 1's cage (196.1-205.8 mm) fits no raceway (docs/paper_a.md): cage ring and "
                              "inner-ring guide land placed beyond the large end, 2 mm clear of it"),
    "roller_profile": P("logarithmic", "text", "assumed",
                        "not given; Lundberg/Johns-Gohar logarithmic crown (usual for TRB rollers), "
                        "'straight' as the other choice"),
    "crown_design_load": P("5 kN", "force", "assumed",
                           "crown design load: the most loaded roller at Fr 20 kN (4.8-5.0 kN, docs/paper_a.md)"),
    "n_slices": P(20, "count", "assumed",
                  "not given; the preload reaction changes by 0.6 % from 20 to 160 slices (order ~1.1 with "
                  "the logarithmic crown, tests/test_trb_quasistatic.py)"),
    "slice_damping_alpha": P("0.16 s/m", "inverse velocity", "assumed",
                             "alpha_e of eq. 11: only a range 0.08-0.32 s/m is given; its geometric mid-point"),
    "steel_density": P("7850 kg/m^3", "density", "assumed",
                       "bearing steel; gives the roller 0.118 kg (common apex) / 0.119 kg (literal)"),
    # materials (Table 1)
    "steel_modulus": P("205 GPa", "pressure", "Table 1"),
    "steel_poisson": P(0.3, "dimensionless", "Table 1"),
    "cage_modulus": P("8.3 GPa", "pressure", "Table 1", "polyamide, inner-ring guided"),
    "cage_poisson": P(0.28, "dimensionless", "Table 1"),
    # --- cage pocket and guide land (eqs. 30-46; most constants not given) ---
    "guide_land_radius": P("97.8 mm", "length", "assumed",
                           "the cage's centering surface is its bore (196.10/2 = 98.05 mm); the land lies 0.25 mm "
                           "inside it (Table 1's 0.5 mm read as diametral)"),
    "cage_mass": P("0.35 kg", "mass", "assumed",
                   "not given: a polyamide (1,140 kg/m^3) ring of 196.1-205.8 mm, 5 mm thick and about 25 mm wide "
                   "(0.2 kg) plus 17 bars"),
    "pocket_critical_film": P("2 um", "length", "assumed",
                              "Delta h0 of eq. 36, not given: about ten composite roughnesses of a moulded polyamide "
                              "pocket against a ground roller"),
    "guide_land_critical_film": P("2 um", "length", "assumed", "Delta h0' of eq. 45, not given: as the pocket's"),
    "pocket_contact_stiffness": P("1e8 N/m", "stiffness", "assumed",
                                  "k_h of eq. 37 per slice, not given: a steel slice (2 mm) on polyamide (E* 9 GPa) "
                                  "flattened by about 1 um under 100 N, the linearised line contact"),
    "pocket_contact_damping": P("100 N s/m", "damping", "assumed",
                                "c_h of eq. 37, not given: a damping ratio of about 0.1 with a 0.12 kg roller "
                                "on k_h"),
    "boundary_friction": P(0.1, "dimensionless", "assumed",
                           "mu_bd of eqs. 37 and 45, not given: steel on polyamide in boundary lubrication"),
    "side_beam_axial_clearance": P("0.3 mm", "length", "assumed",
                                   "Delta delta' of eq. 39 (roller end to side beam), not given: of the order of "
                                   "the pocket clearance 0.27 mm"),
    "side_beam_thickness": P("5 mm", "length", "assumed",
                             "h_s of eq. 40 (the beam's width the end's squeeze film flows across), not given: "
                             "the cage thickness of Table 1"),
    "pocket_switch": P("continuous", "text", "assumed",
                       "the paper switches film/boundary state abruptly at Delta h0; the continuous switch has no "
                       "jump in force or friction (lubrication/laws/cage.py)"),
    "guide_land_film": P("short_bearing", "text", "assumed",
                         "Ocvirk's short bearing, within 1 % of the FEM finite bearing at the land's "
                         "b/2r = 0.025 (Reynolds-cavitated FEM: 2.6e-4 to 9.5e-3 at eps 0.1-0.95); 'paper': eq. 44's "
                         "cylinder-over-plane law, 200-1.3e4 x the FEM"),
    "guide_land_reaction": P("kept", "text", "assumed",
                             "eq. 46 neglects the cage's load on the guiding ring; kept so that linear and angular "
                             "momentum are conserved ('neglected' reproduces the paper)"),
    # grease and base oil (Tables 1 and 2)
    "grease_yield_stress": P("351.8 Pa", "pressure", "Table 1", "polyurea grease at 30 C"),
    "grease_plastic_viscosity": P(8.44, "dimensionless", "Table 1",
                                  "phi in Pa s^n (n = 0.7196), polyurea at 30 C; the paper's eqs. 12, 25, 34-35, "
                                  "40 and 44 use it as a Newtonian viscosity"),
    "grease_power_law_exponent": P(0.7196, "dimensionless", "Table 1"),
    "pressure_viscosity": P("4.662e-8 m^2/N", "inverse pressure", "Table 1", "polyurea grease at 30 C only"),
    "viscosity_law": P("barus", "text", "Eq. 26", "Table 1's pressure-viscosity coefficient is Barus' alpha: "
                       "phi = phi0 exp(alpha p) of eq. 26, taken for the base oil's eta0 exp(alpha p) too"),
    "base_oil_viscosity": P("0.1 Pa s", "dynamic viscosity", "assumed",
                            "not in the paper; a 0.1 Pa s base oil gives a 5.4 um raceway film at 2.4 krpm"),
    "base_oil_density": P("870 kg/m^3", "density", "assumed", "mineral base oil: not in the paper"),
    "base_oil_temperature_law": P("walther", "text", "assumed",
                                  "the paper gives no base oil: its viscosity follows the grease's temperature "
                                  "on ASTM D341's Walther line (0.1 Pa s at 30 C)"),
    "base_oil_reference_c": P(30.0, "dimensionless", "assumed",
                              "the temperature of base_oil_viscosity: Table 1's grease temperature"),
    "base_oil_nu100": P("8.6 mm^2/s", "kinematic viscosity", "assumed",
                        "an ISO VG 68 mineral oil (about 68 mm^2/s at 40 C, 8.6 at 100 C): with 0.1 Pa s at 30 C "
                        "it gives 0.26 / 0.037 / 0.017 Pa s at 15 / 50 / 70 C"),
    # --- grease, traction, flange (eqs. 12-29; limits and constants the paper does not give) ---
    "grease_pressure_viscosity_all": P("4.662e-8 m^2/N", "inverse pressure", "assumed",
                                       "Table 1 gives alpha for polyurea at 30 C only; used for every grease "
                                       "and temperature of Table 2"),
    "grease_viscosity_reading": P("base_oil", "text", "assumed",
                                  "phi (Pa s^n) is used as a Newtonian viscosity in eqs. 12, 25 (docs/paper_a.md); films "
                                  "use the base oil (lubrication/laws/grease.py says why)"),
    "grease_limiting_shear_stress": P("1 MPa", "pressure", "assumed",
                                      "not in the paper (eq. 26 unbounded, docs/paper_a.md): ambient part tau_L0 of "
                                      "tau_L = tau_L0 + gamma_L p, of the order Bair & Winer (1979) report"),
    "grease_limiting_shear_slope": P(0.07, "dimensionless", "assumed",
                                     "gamma_L = d tau_L/dp: 0.04-0.1 for mineral oils (Bair & Winer 1979); "
                                     "bounds the traction coefficient"),
    "grease_yield_regularisation_rate": P("1 Hz", "frequency", "assumed",
                                          "Papanastasiou rate D_r: removes the yield-stress jump at zero slip; "
                                          "far below the contacts' 1e3-1e7 1/s"),
    "film_shear_modulus": P("1 GPa", "pressure", "assumed",
                            "not in the paper: the EHL film's elastic shear modulus of the limited raceway traction "
                            "(Johnson & Tevaarwerk 1977 report 0.3-3 GPa at 0.5-1 GPa for mineral oils); sets its "
                            "initial slope 2 G b^2/(u_e h)"),
    "raceway_traction_law": P("limited", "text", "assumed",
                              "eq. 12 as printed ('paper': linear, unlimited, the base oil's 0.1 Pa s at ambient "
                              "pressure) cannot hold the rollers against the pocket films' drag: measured at Fig. 5's "
                              "point, the rollers' spin falls 11 % in 20 ms; 'limited' (Barus HB with a limiting "
                              "shear stress and the film's elastic shear) holds them"),
    "grease_name": P("polyurea", "text", "Table 1", "the grease of Figs. 5-13 (Table 2 row at temperature)"),
    "grease_temperature_c": P(30.0, "dimensionless", "Table 1", "Table 1's grease values are polyurea at 30 C"),
    "rib_contact_radius": P("85.6 mm", "length", "assumed",
                            "not in the paper: roller axis at the large end 89 + 21.03 sin 10 deg = 92.65 mm "
                            "from the bearing axis, normal 3 deg off it: 136.2 sin 3 deg = 7.13 mm lower"),
    "flange_asperity_friction": P(0.2, "dimensionless", "Eq. 23", "s0/p0 ~ 0.2 for most metals"),
    "flange_asperity_b": P(1.8, "dimensionless", "assumed",
                           "B of eq. 23, not given: share 0.17 at lambda = 1, 1e-3 at lambda = 3 (a usual "
                           "full-film limit); values recalled from roller-end/rib models, not verified"),
    "flange_asperity_c": P(1.2, "dimensionless", "assumed", "C of eq. 23, not given (see flange_asperity_b)"),
    "flange_roughness": P("0.2 um", "length", "assumed",
                          "composite rms sigma of ground roller end and rib face (about 0.14 um each): not given"),
    "flange_friction_mixing": P("paper", "text", "assumed",
                                "eq. 22 adds asperity and grease friction as printed; 'load_share' weights the "
                                "grease part by 1 - exp(-B lambda^C)"),
    "rib_film_model": P("hamrock_dowson", "text", "assumed",
                        "eq. 24 has no length scale (docs/paper_a.md); 'paper_eq24' reads it as h_c/r_s"),
    "cone_mass": P("5 kg", "mass", "assumed",
                   "paper A gives no ring masses: about a steel cone of the 78.5 mm raceway radius and 50 mm width"),
    "radial_load_offset": P("0 mm", "length", "assumed",
                            "paper A gives no load point: the radial load at the roller mid-points' plane"),
    # operating point of Fig. 5
    "radial_load": P("20 kN", "force", "Fig. 5"),
    "inner_speed": P("2400 rpm", "angular velocity", "Fig. 5"),
    "simulated_time": P("0.18 s", "time", "Sec. 4", "from a quasi-static start; means over 0.1-0.18 s"),
}

#: where each case schema takes each value (the roller EHL contact of the ``ehl`` scene, the quasi-static
#: bearing of the ``static`` scene)
SCENES = {
    "static": {
        **{f"bearing.{k}": k for k in (
            "n_rollers", "effective_length", "outer_contact_angle", "inner_contact_angle", "flange_contact_angle",
            "outer_raceway_radius", "inner_raceway_radius", "rib_height", "cage_outer_diameter",
            "cage_inner_diameter", "cage_thickness", "guide_land_clearance", "guide_land_width", "pocket_clearance")},
        "bearing.large_end_diameter": "roller_large_end_diameter",
        "bearing.small_end_diameter": "roller_small_end_diameter",
        "bearing.end_sphere_radius": "roller_end_sphere_radius", "bearing.land_axial_gap": "guide_land_axial_gap",
        "bearing.modulus": "steel_modulus", "bearing.poisson": "steel_poisson", "bearing.density": "steel_density",
        "bearing.reconciliation": "geometry_reconciliation", "bearing.profile": "roller_profile",
        "bearing.crown_load": "crown_design_load", "model.slices": "n_slices",
    },
    "tapered": {},  # filled below: the static scene's bearing plus the dynamics' values
    "ehl": {
        "bearing.element_diameter": "roller_mean_diameter", "bearing.pitch_diameter": "pitch_diameter",
        "bearing.n_elements": "n_rollers", "bearing.effective_length": "effective_length",
        "materials.modulus1": "steel_modulus", "materials.poisson1": "steel_poisson",
        "lubricant.viscosity.law": "viscosity_law", "lubricant.viscosity.eta0": "base_oil_viscosity",
        "lubricant.viscosity.alpha": "pressure_viscosity", "lubricant.density.rho0": "base_oil_density",
    },
}


SCENES["tapered"] = {
    **SCENES["static"],
    "model.damping_alpha": "slice_damping_alpha", "model.pocket_switch": "pocket_switch",
    "lubricant.viscosity.law": "viscosity_law", "lubricant.viscosity.eta0": "base_oil_viscosity",
    "lubricant.viscosity.alpha": "pressure_viscosity",
    "cage.mass": "cage_mass", "cage.pocket_critical_film": "pocket_critical_film",
    "cage.pocket_stiffness": "pocket_contact_stiffness", "cage.pocket_damping": "pocket_contact_damping",
    "cage.boundary_friction": "boundary_friction", "cage.land_critical_film": "guide_land_critical_film",
    "operating.speed": "inner_speed", "operating.radial_load": "radial_load",
    "operating.load_offset": "radial_load_offset", "model.cone_mass": "cone_mass",
    "model.traction": "raceway_traction_law", "model.flange_friction": "flange_friction_mixing",
    "lubricant.grease": "grease_name", "lubricant.temperature_c": "grease_temperature_c",
    "lubricant.oil_temperature": "base_oil_temperature_law", "lubricant.oil_reference_c": "base_oil_reference_c",
    "lubricant.oil_nu100": "base_oil_nu100", "lubricant.density.rho0": "base_oil_density",
    "lubricant.reading": "grease_viscosity_reading",
    "lubricant.limiting_stress": "grease_limiting_shear_stress", "lubricant.limiting_slope": "grease_limiting_shear_slope",
    "lubricant.yield_rate": "grease_yield_regularisation_rate", "lubricant.shear_modulus": "film_shear_modulus",
    "cage.modulus": "cage_modulus", "cage.poisson": "cage_poisson",
    "cage.side_beam_clearance": "side_beam_axial_clearance", "cage.side_beam_thickness": "side_beam_thickness",
    "flange.asperity_friction": "flange_asperity_friction", "flange.asperity_b": "flange_asperity_b",
    "flange.asperity_c": "flange_asperity_c", "flange.roughness": "flange_roughness", "flange.rib_film": "rib_film_model",
}


def tapered_geometry(**overrides):
    """:class:`lubedyn.lubrication.laws.tapered.TaperedRollerGeometry` of Table 1 with this module's assumed
    rib, cage-land gap, density, profile and crown load (the ``static`` scene's ``[bearing]`` table of
    :data:`SCENES`, so a case and this Python twin build the same bearing); ``overrides`` replace any
    field."""
    fields = {key.split(".", 1)[1]: VALUES[name].si() for key, name in SCENES["static"].items()
              if key.startswith("bearing.")}
    fields.update(overrides)
    return TaperedRollerGeometry(**fields)
