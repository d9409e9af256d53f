"""The tapered roller bearing's data as frozen groups, one per table of a dynamics case (SI units).

Part of :mod:`lubedyn.dynamics.tapered`.  :class:`~lubedyn.dynamics.tapered.model.TaperedBearing` holds the geometry
(:class:`lubedyn.lubrication.laws.tapered.TaperedRollerGeometry`, a law) and one of each:

=============  ============  ===============================================================
group          case table    what
=============  ============  ===============================================================
``operating``  [operating]   cone speed, radial load, axial mode (locked / force / displacement), gravity
``fidelity``   [model]       slices, contacts, traction, flange friction, pocket and land levels, damping
``lubricant``  [lubricant]   the grease (Herschel-Bulkley, Table 2) and which viscosity the films read
``cage``       [cage]        cage mass and material, pocket and land law constants
``flange``     [flange]      eq. 23's asperity friction, B, C, roughness, the rib film formula
``initial``    [initial]     a perturbation of the quasi-static start
=============  ============  ===============================================================

Paper data are not defaults here: paper A's values (and what it had to assume) come from
:mod:`lubedyn.papers.wu2018.parameters`; the defaults are model options and numerical settings.  Each group
checks its own values and raises :class:`lubedyn.dynamics.errors.DynamicsInputError` naming the case key;
checks that need two groups live in the model.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from lubedyn.lubrication.laws.cage import POCKET_SWITCHES
from lubedyn.lubrication.laws.flange import RIB_FILMS
from lubedyn.lubrication.laws.grease import READINGS, Grease

from ..groups import Group
from .layout import AXIAL_MODES, CONE_TILTS, FLANGE_FRICTIONS, LANDS, POCKETS, TRACTIONS


@dataclass(frozen=True, kw_only=True)
class Operating(Group):
    """The cone's ``speed`` [rad/s] (the cup is fixed), ``radial_load`` [N] on the cone along +y;
    ``axial``: "locked" (the cone's axial DOF held at ``axial_displacement`` [m], closing: 0 is zero
    clearance as paper A's Figs. 5-9 hold it, docs/paper_a.md; > 0 a preload) or "force" (free under
    ``axial_load`` [N], closing the bearing);
    ``gravity`` [m/s^2] along -y on every body (0: none);
    ``cone_tilt``: "locked" (the cone's tilts held at zero: the shaft's other support carries the
    moment the loads make) or "free" (the cone tilts about its reference point, the origin of the
    geometry's meridional coordinates, under the contacts' moments and the loads'); the radial load
    acts at the axial position ``load_offset`` [m] from that reference point (a moment x_F F_r about z),
    plus ``applied_moment`` (M_y, M_z) [N m] about it; both act only with the tilt free."""

    TABLE: ClassVar[str] = "operating"

    speed: float = 0.0
    radial_load: float = 0.0
    axial: str = "force"
    axial_load: float = 0.0
    axial_displacement: float = 0.0
    gravity: float = 0.0
    cone_tilt: str = "locked"
    load_offset: float = 0.0
    applied_moment: tuple = (0.0, 0.0)

    def __post_init__(self):
        self.choice("axial", tuple(AXIAL_MODES))
        self.choice("cone_tilt", tuple(CONE_TILTS))
        if not (isinstance(self.load_offset, (int, float)) and math.isfinite(self.load_offset)):
            raise self.fail("load_offset", "must be a finite length [m]")
        m = self.applied_moment
        if len(m) != 2 or not all(math.isfinite(float(x)) for x in m):
            raise self.fail("applied_moment", "must be two finite numbers (M_y, M_z) [N m]")
        self.non_negative("speed", "radial_load", "axial_load", "gravity")
        if not math.isfinite(self.axial_displacement):
            raise self.fail("axial_displacement", "must be finite")
        if self.axial == "force" and self.axial_load == 0.0:
            raise self.fail("axial_load", "N with operating.axial = 'force' leaves the cone without an axial "
                                          "equilibrium (docs/paper_a.md): give an axial load or operating.axial = 'locked'")


@dataclass(frozen=True, kw_only=True)
class Fidelity(Group):
    """Numerical and modelling choices: ``slices`` per roller and raceway; ``contacts`` False: free
    bodies (a test of the equations of motion); ``traction`` "none", "paper" (eq. 12), "limited" (the
    limited Herschel-Bulkley strip law, an extension) or "map" (the roller EHL maps' film traction at the
    run's entrainment speed: :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.map_traction_tables`); ``flange_friction`` "none", "paper" (eqs. 22-23 as
    printed) or "load_share" (the grease term weighted by the fluid share); ``pocket`` "none" (no cage),
    "contact" (contact only: the roller touches a crossbeam beyond the pocket clearance, line contact,
    friction mu_bd) or "film" (:func:`lubedyn.lubrication.laws.cage.pocket_force`); ``guide_land`` "none",
    "contact" (contact only beyond the land clearance) or "film"; ``damping_alpha`` alpha_e [s/m] of
    eq. 11 (slices, flange, contact-only pocket and land); ``cone_mass`` [kg] (paper A gives none);
    ``quaternion_stabilisation`` [1/s]; ``friction_speed`` v_reg [m/s] of the regularised Coulomb
    friction of the contact-only pocket and land (mu tanh(v/v_reg)); ``pocket_switch`` of the film pocket;
    ``side_beams``: the roller ends against the pocket's side beams (eqs. 39-40, the cage's axial DOF free;
    False: the cage's axial position held); ``traction_evaluation`` of the limited raceway traction:
    "quadrature" (the strip law's Gauss rule at every slice and evaluation) or "table" (the same law
    tabulated once per raceway over sliding speed and line load, read by cubic Hermite interpolation:
    :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.traction_tables`; the default: over 0.18 s of Fig. 5's
    point the loaded-zone mean skew agrees with "quadrature" to 1.1e-6 and the tilt to 7e-8, relative,
    and the run is 2.2 x faster: 23.5 s against 50.7 s on one idle core, benchmarks/results/trb_target.json)."""

    TABLE: ClassVar[str] = "model"

    slices: int = 20
    contacts: bool = True
    traction: str = "paper"
    flange_friction: str = "none"
    pocket: str = "none"
    guide_land: str = "none"
    damping_alpha: float = 0.16
    cone_mass: float = 5.0
    quaternion_stabilisation: float = 10.0
    friction_speed: float = 1e-3
    pocket_switch: str = "continuous"
    side_beams: bool = True
    traction_evaluation: str = "table"

    def __post_init__(self):
        if isinstance(self.slices, bool) or int(self.slices) != self.slices or self.slices < 1:
            raise self.fail("slices", "must be an integer >= 1")
        self.choice("traction", tuple(TRACTIONS))
        self.choice("flange_friction", tuple(FLANGE_FRICTIONS))
        self.choice("pocket", tuple(POCKETS))
        self.choice("guide_land", tuple(LANDS))
        self.choice("pocket_switch", tuple(POCKET_SWITCHES))
        self.choice("traction_evaluation", ("quadrature", "table"))
        self.non_negative("damping_alpha", "quaternion_stabilisation")
        self.positive("cone_mass", "friction_speed")
        if (self.pocket == "none") != (self.guide_land == "none"):
            raise self.fail("guide_land", "must be 'none' exactly when model.pocket = 'none' (the cage is one body: "
                                          "with pockets it rides on the land)")


@dataclass(frozen=True, kw_only=True)
class Lubricant(Group):
    """The grease of paper A's Table 2 (``yield_stress`` tau_y [Pa], ``consistency`` phi0 [Pa s^n],
    ``exponent`` n; None: no grease, only a Newtonian oil), its ``pressure_viscosity`` alpha [1/Pa], and
    the ``reading`` of phi that films and eq. 12 take as their Newtonian viscosity (docs/paper_a.md;
    :meth:`lubedyn.lubrication.laws.grease.Grease.viscosity`): "base_oil" (``base_oil_viscosity`` [Pa s]),
    "apparent" (tau_y/D + phi D^(n-1) at ``shear_rate`` [1/s]) or "paper" (phi0's number as Pa s).
    The limited laws (raceway "limited", flange grease traction) use the grease with the limiting shear
    stress ``limiting_stress`` tau_L0 [Pa] (inf: none), ``limiting_slope`` gamma_L and the yield
    regularisation ``yield_rate`` D_r [1/s]; the raceway's "limited" law adds the film's elastic shear
    of modulus ``shear_modulus`` G [Pa] in series (inf: none, the near-Coulomb law).
    ``raceway_film_viscosities`` (cup, cone) [Pa s]: the viscosities of the raceway slices' Dowson-Toyoda
    films (None: :meth:`viscosity` for both; the tapered scene's ``lubricant.raceway_film = "grease_ehl"``
    sets them so that the formula gives the grease's EHL film; :meth:`film_viscosities`)."""

    TABLE: ClassVar[str] = "lubricant"

    reading: str = "base_oil"
    base_oil_viscosity: float | None = None
    yield_stress: float | None = None
    consistency: float | None = None
    exponent: float | None = None
    pressure_viscosity: float = 0.0
    shear_rate: float | None = None
    limiting_stress: float = math.inf
    limiting_slope: float = 0.0
    yield_rate: float = 0.0
    shear_modulus: float = math.inf
    raceway_film_viscosities: tuple | None = None

    def __post_init__(self):
        self.choice("reading", READINGS)
        v = self.raceway_film_viscosities
        if v is not None and (len(v) != 2 or not all(isinstance(x, (int, float)) and math.isfinite(x) and x > 0.0
                                                     for x in v)):
            raise self.fail("raceway_film_viscosities", "must be two viscosities > 0 [Pa s] (cup, cone), or None")
        self.non_negative("pressure_viscosity", "limiting_slope", "yield_rate")
        if not self.shear_modulus > 0.0:
            raise self.fail("shear_modulus", "must be > 0 (inf: no elastic compliance)")
        if not self.limiting_stress > 0.0:
            raise self.fail("limiting_stress", "must be > 0 (inf: no limit)")
        given = [getattr(self, k) is not None for k in ("yield_stress", "consistency", "exponent")]
        if any(given) and not all(given):
            raise self.fail("consistency", "yield_stress, consistency and exponent go together (a Herschel-Bulkley "
                                           "grease) or are all left out")
        if self.reading == "base_oil":
            if self.base_oil_viscosity is None:
                raise self.fail("base_oil_viscosity", "must be given with lubricant.reading = 'base_oil'")
            self.positive("base_oil_viscosity")
        elif self.grease() is None:
            raise self.fail("reading", f"needs a grease (lubricant.yield_stress, consistency, exponent)")
        if self.reading == "apparent":
            if self.shear_rate is None:
                raise self.fail("shear_rate", "must be given with lubricant.reading = 'apparent'")
            self.positive("shear_rate")
        if self.grease() is not None:
            self.non_negative("yield_stress")
            self.positive("consistency")
            if not 0.0 < self.exponent <= 2.0:
                raise self.fail("exponent", "must lie in (0, 2]")

    def grease(self) -> Grease | None:
        """The :class:`lubedyn.lubrication.laws.grease.Grease` (None without one)."""
        if self.consistency is None:
            return None
        return Grease(self.yield_stress, self.consistency, self.exponent, self.pressure_viscosity)

    def viscosity(self) -> float:
        """The Newtonian viscosity [Pa s] of the films and eq. 12 under :attr:`reading`."""
        g = self.grease()
        if g is None:
            return float(self.base_oil_viscosity)
        return float(g.viscosity(self.reading, shear_rate=self.shear_rate, base_oil_viscosity=self.base_oil_viscosity))

    def film_viscosities(self) -> tuple[float, float]:
        """(cup, cone) viscosities [Pa s] of the raceway films' Dowson-Toyoda formula:
        ``raceway_film_viscosities`` when given, else :meth:`viscosity` for both."""
        if self.raceway_film_viscosities is None:
            eta = self.viscosity()
            return eta, eta
        return float(self.raceway_film_viscosities[0]), float(self.raceway_film_viscosities[1])


@dataclass(frozen=True, kw_only=True)
class Cage(Group):
    """The cage: ``mass`` [kg] (a ring: the bars' share of the inertia is not known), ``modulus`` [Pa]
    and ``poisson`` of its polyamide (needed by the contact-only pocket and land); the film pocket's
    ``pocket_critical_film`` [m], ``pocket_stiffness`` [N/m], ``pocket_damping`` [N s/m]; the land's
    ``land_critical_film`` [m] (film land); ``boundary_friction`` mu_bd (all levels); the side beams'
    axial ``side_beam_clearance`` Delta delta' [m] (roller end to beam, each side) and ``side_beam_thickness``
    h_s [m] (eq. 40's squeeze flows across it)."""

    TABLE: ClassVar[str] = "cage"

    mass: float
    boundary_friction: float
    modulus: float | None = None
    poisson: float | None = None
    pocket_critical_film: float = 0.0
    pocket_stiffness: float = 0.0
    pocket_damping: float = 0.0
    land_critical_film: float = 0.0
    side_beam_clearance: float = 0.0
    side_beam_thickness: float = 0.0

    def __post_init__(self):
        self.positive("mass")
        self.non_negative("boundary_friction", "pocket_critical_film", "pocket_stiffness", "pocket_damping",
                          "land_critical_film", "side_beam_clearance", "side_beam_thickness")
        if (self.modulus is None) != (self.poisson is None):
            raise self.fail("modulus", "and cage.poisson go together")
        if self.modulus is not None:
            self.positive("modulus")
            if not 0.0 <= self.poisson < 0.5:
                raise self.fail("poisson", "must lie in [0, 0.5)")


@dataclass(frozen=True, kw_only=True)
class Flange(Group):
    """Eq. 23 at the rib: ``asperity_friction`` s0/p0, ``asperity_b`` B, ``asperity_c`` C, composite
    ``roughness`` sigma [m]; ``rib_film`` the film model (:data:`lubedyn.lubrication.laws.flange.RIB_FILMS`: two
    closed forms, or "ehl", the rib's EHL film map of the case's grease) evaluated once at the start's flange
    load and the ideal rib entrainment speed."""

    TABLE: ClassVar[str] = "flange"

    asperity_friction: float = 0.2
    asperity_b: float
    asperity_c: float
    roughness: float
    rib_film: str = "hamrock_dowson"

    def __post_init__(self):
        self.non_negative("asperity_friction", "asperity_b", "asperity_c")
        self.positive("roughness")
        self.choice("rib_film", RIB_FILMS)


@dataclass(frozen=True, kw_only=True)
class Initial(Group):
    """A perturbation of the quasi-static start: the cone's centre moved by ``cone_offset`` (y, z) [m],
    the cage's by ``cage_offset`` (y, z) [m]."""

    TABLE: ClassVar[str] = "initial"

    cone_offset: tuple = (0.0, 0.0)
    cage_offset: tuple = (0.0, 0.0)

    def __post_init__(self):
        for name in ("cone_offset", "cage_offset"):
            v = getattr(self, name)
            if len(v) != 2 or not all(math.isfinite(float(x)) for x in v):
                raise self.fail(name, "must be two finite numbers (y, z) [m]")
