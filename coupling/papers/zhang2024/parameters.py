"""Paper B: Zhang, Wang, Guan, Zhang & Yang, "Study of Non-Smooth Symmetry Collision of Rolling
Bodies of Localized Functional-Slot Cage-Less Ball Bearings Considering Lubrication Flow",
*Symmetry* 16 (2024) 741.

A cage-less 6206-size deep-groove ball bearing with one local functional slot, the backup bearing
of an active magnetic bearing: the rotor drops onto the inner ring and drags it up to speed.
Tables 1 (lubricant, materials), 2 (bearing) and 4 (groove geometry, slot).  What the paper does
not give is marked ``source="assumed"`` with the reason.
"""
from lubedyn.papers import Parameter as P
from lubedyn.units import parse_quantity

NAME = "Zhang2024"
CITATION = ("J. Zhang, Y. Wang, L. Guan, Y. Zhang, S. Yang, Symmetry 16 (2024) 741 "
            "(cage-less 6206 ball bearing with a functional slot)")

VALUES = {
    # bearing (Tables 2 and 4)
    "n_balls": P(14, "count", "Table 2"),
    "ball_radius": P("4.7625 mm", "length", "Table 2"),
    "ball_diameter": P("9.525 mm", "length", "Table 4"),
    "pitch_diameter": P("46.005 mm", "length", "Table 4"),
    "inner_groove_radius": P("4.905 mm", "length", "Table 4"),
    "outer_groove_radius": P("4.953 mm", "length", "Table 4"),
    "diametral_clearance": P("0 mm", "length", "Table 2",
                             "groove bottoms 55.53 - 36.48 mm minus two balls of 9.525 mm: zero clearance"),
    "outer_diameter": P("62 mm", "length", "Table 2"),
    "bore": P("30 mm", "length", "Table 2"),
    "ball_modulus": P("207 GPa", "pressure", "Tables 1 and 2"),
    "ball_poisson": P(0.29, "dimensionless", "Tables 1 and 2"),
    "ring_modulus": P("208 GPa", "pressure", "Table 2", "printed as 208,000 MPa"),
    "ring_poisson": P(0.3, "dimensionless", "Table 2"),
    "ball_density": P("7850 kg/m^3", "density", "assumed",
                      "bearing steel; the paper prints a ball mass of 0.01 kg, but a 9.525 mm steel ball weighs "
                      "3.55 g, so the mass is taken from the density"),
    "ring_mass": P("3 kg", "mass", "assumed", "inner ring plus the rotor share it carries: not in the paper"),
    "ring_inertia": P("1.45e-5 kg m^2", "moment of inertia", "assumed",
                      "a 6206 inner ring about its axis: not in the paper"),
    "rotor_inertia": P("2e-3 kg m^2", "moment of inertia", "assumed",
                       "the dropped rotor about its axis: not in the paper"),
    # functional slot (Table 4)
    "slot_race": P("outer", "text", "Table 4", "slots machined by EDM in the outer ring"),
    "slot_azimuths": P(["270 deg"], "angles", "Sec. 2 and Fig. 1",
                       "one slot at the bottom of the load zone (under the radial load)"),
    "slot_width": P("3.5 mm", "length", "Table 4"),
    "slot_length": P("11.5 mm", "length", "Table 4"),
    "slot_depth": P("1 mm", "length", "Table 4"),
    # operating point (Sec. 3)
    "radial_load": P("2000 N", "force", "Sec. 3, Table 2"),
    "axial_load": P("200 N", "force", "Sec. 3, Table 2"),
    "speed": P("10000 rpm", "angular velocity", "Sec. 3",
               "the drop speed and the speed of the ball-ball film solution; 15,000-25,000 rpm are also studied"),
    # lubricant (Table 1)
    "viscosity": P("0.050 Pa s", "dynamic viscosity", "Table 1"),
    "pressure_viscosity": P("1.85e-8 m^2/N", "inverse pressure", "Table 1"),
    "viscosity_law": P("barus", "text", "Eq. 17", "Table 1's pressure-viscosity coefficient is Barus' alpha: "
                       "eta = eta0 exp(alpha p), the law of the film shear of eq. 17"),
    "density": P("992 kg/m^3", "density", "Table 1"),
}

#: where each case schema takes each value
SCENES = {
    "dynamics": {
        **{f"bearing.{k}": k for k in (
            "n_balls", "ball_diameter", "pitch_diameter", "inner_groove_radius", "outer_groove_radius",
            "diametral_clearance", "ball_modulus", "ball_poisson", "ring_modulus", "ring_poisson", "ball_density",
            "ring_mass", "ring_inertia", "rotor_inertia", "outer_diameter", "bore")},
        "slots.race": "slot_race", "slots.azimuths": "slot_azimuths", "slots.width": "slot_width",
        "slots.length": "slot_length", "slots.depth": "slot_depth",
        "operating.radial_load": "radial_load", "operating.axial_load": "axial_load", "operating.speed": "speed",
        "lubricant.viscosity.law": "viscosity_law", "lubricant.viscosity.eta0": "viscosity",
        "lubricant.viscosity.alpha": "pressure_viscosity",
    },
    "ehl": {
        "bearing.element_diameter": "ball_diameter", "bearing.pitch_diameter": "pitch_diameter",
        "bearing.n_elements": "n_balls", "bearing.inner_groove_radius": "inner_groove_radius",
        "bearing.outer_groove_radius": "outer_groove_radius", "bearing.diametral_clearance": "diametral_clearance",
        "bearing.inner_speed": "speed", "bearing.radial_load": "radial_load", "bearing.axial_load": "axial_load",
        "materials.modulus1": "ball_modulus", "materials.poisson1": "ball_poisson",
        "materials.modulus2": "ring_modulus", "materials.poisson2": "ring_poisson",
        "lubricant.viscosity.law": "viscosity_law", "lubricant.viscosity.eta0": "viscosity",
        "lubricant.viscosity.alpha": "pressure_viscosity", "lubricant.density.rho0": "density",
    },
    "film": {
        "lubricant.viscosity.law": "viscosity_law", "lubricant.viscosity.eta0": "viscosity",
        "lubricant.viscosity.alpha": "pressure_viscosity", "lubricant.density.rho0": "density",
    },
}


def cageless_bearing(**overrides):
    """Paper B's bearing as a :class:`lubedyn.dynamics.cageless.CagelessBearing`: the SI values of :data:`VALUES`
    placed in the model's groups by the case keys of :data:`SCENES` (``"bearing.n_balls"`` -> the
    ``bearing`` group), the Python-side twin of a dynamics case that says ``parameters = "Zhang2024"``.
    ``overrides`` as :meth:`~lubedyn.dynamics.cageless.CagelessBearing.replace` takes them: by group
    (``operating={"speed": 1e3}``) or by case key (``**{"model.dof": "planar"}``)."""
    from lubedyn.dynamics.cageless import CagelessBearing  # deferred: numba

    groups = {"bearing": {}, "operating": {}, "films": {}, "slots": {}}
    oil = {"lubricant.viscosity.eta0": "films.viscosity", "lubricant.viscosity.alpha": "films.pressure_viscosity"}
    for key, name in SCENES["dynamics"].items():
        if key == "lubricant.viscosity.law":
            continue  # Barus: the model's only law
        table, field = oil.get(key, key).split(".")  # the case's [lubricant] is the model's films group
        p = VALUES[name]
        groups[table][field] = (tuple(parse_quantity(a, "angle") for a in p.value) if p.dimension == "angles"
                                else p.si())
    model = CagelessBearing(**groups)
    return model.replace(**overrides) if overrides else model
