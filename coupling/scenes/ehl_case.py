"""The EHL scene's case schema (``scene = "ehl"``): one isothermal EHL point or line contact.

Layout (x the entrainment direction; the contact comes from exactly one of
``[contact]`` + ``[operating]``, ``[bearing]`` or ``[dimensionless]``)::

    scene = "ehl"
    [contact]    radius_x, radius_y (reduced radii) | line = true, length |
                 body1_radius_x, body1_radius_y, body2_radius_x, body2_radius_y
    [materials]  modulus1, poisson1, modulus2, poisson2 (body 2 defaults to body 1)
    [lubricant]  as for films: viscosity law, eta0, alpha; density law; eyring_stress, or
                 [lubricant.herschel_bulkley] yield_stress, exponent, creep (grease flow; eta0 is then
                 the consistency phi0 in Pa s^n, written as Pa s)
    [operating]  mean_speed + slide_to_roll | velocity1 + velocity2;
                 load [N] | load_per_length [N/m] (lines) | approach (h00)
    [bearing]    type = ball | roller, race = inner | outer, element_diameter,
                 pitch_diameter, n_elements, inner/outer_groove_radius,
                 diametral_clearance (balls), effective_length (rollers),
                 contact_angle, inner_speed, outer_speed, radial_load,
                 axial_load, stribeck_constant, load_distribution =
                 stribeck | quasi_static (balls): see :mod:`lubedyn.lubrication.laws.bearing`
    [dimensionless]  M, L, eta0 (Moes' parameters; EHLContact.from_moes)
    [grid]       nx (2^k + 1), ny, x_min, x_max, y_max (in Hertz semi-axes)
    [traction]   model = newtonian | limiting_shear | eyring, limiting_shear_stress,
                 limiting_shear_slope, eyring_stress
    [solver]     rtol, max_iter, max_step
    [output]     write = ["vtu", "png"]
    [validity]   max_pressure, min_film, max_reynolds (as for films; max_pressure default 4 GPa)
    [limits]     memory, map_points
    [smoke]      a partial case merged over this one by ``--smoke``

Read through :func:`lubedyn.config.load_case` (``CaseModel`` below); built by :mod:`lubedyn.scenes.ehl`.
"""
from __future__ import annotations

import math
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, ValidationInfo, model_validator

from lubedyn.lubrication.laws import bearing as bearings
from lubedyn.lubrication.laws.bearing import STRIBECK

from lubedyn.config import (EHL_MAX_PRESSURE, THIN_FILM, Length, LimitsModel, LubricantModel, PositiveInt, PositiveLength,
                     Q, Scaled, ValidityModel, Velocity, CaseTable, root_rule, show_value, bare_hint, check_scale,
                     context_raw, raise_scale, rule, thin_film)
from lubedyn.lubrication.errors import InputError
from lubedyn.lubrication.laws.contact import line_contact, point_contact, reduced_modulus

SMALL_CONTACT = THIN_FILM
"""The largest Hertz contact semi-axis over the radius of curvature along it (b/R_x, and a/R_y of a
point contact), and a line contact's half-width over its length, that a case may give.  Hertz's theory
(and the EHL solver's parabolic gap on elastic half-spaces) is the leading order in b/R, as Reynolds'
equation is in h/L (:data:`lubedyn.config.THIN_FILM`, the same 0.1); a hardened steel contact reaches
b/R = 0.1 only near 6-7 GPa, above the 4 GPa of validity.max_pressure, so a larger ratio is a slipped
unit (a modulus of 207 Pa for 207 GPa) or a load far beyond any film."""
SMALL_CONTACT_WHY = ("Hertz's half-space contact and the EHL film's parabolic gap need a contact much smaller "
                     "than the radii of curvature")
GROOVE_MAX_CONFORMITY = 1.0
"""The largest groove radius over the ball diameter (conformity r/D) a case may give: bearing grooves
conform closely (0.505-0.58; ISO 281 rates radial ball bearings for r <= 0.52-0.53 D); above r = D the
race is nearly flat and a groove radius that large is a slipped unit."""
FILL = (0.25, 1.0)
"""The range of a bearing's fill Z D/(pi d_m), the share of the pitch circle its Z elements take: below
1 they fit side by side; at 0.25 neighbours are three element diameters apart, sparser than any caged
bearing (paper B's cage-less bearing: 0.92, paper A's tapered roller bearing: 0.65)."""
ROLLER_MAX_SLENDERNESS = 20.0
"""The largest roller effective length over its diameter a case may give: needle rollers, the most
slender, reach about 10 (ISO 3096); a longer one is a slipped unit."""

def _two_power_plus_one(n: int, smallest: int) -> bool:
    return n >= smallest and (n - 1) & (n - 2) == 0


class ContactModel(CaseTable):
    """Contact geometry; x is the entrainment (rolling) direction.  One of:
    the reduced radii (``radius_x`` and ``radius_y``, or ``line = true``);
    the principal radii of the two bodies (``body1_radius_x`` ...: convex > 0,
    concave < 0, omitted = flat; 1/R = 1/r1 + 1/r2); or nothing, with a
    ``[bearing]`` table.  ``length``: effective length of a line contact."""

    radius_x: PositiveLength | None = None
    radius_y: PositiveLength | None = None
    line: bool = False
    length: PositiveLength | None = None
    body1_radius_x: Length | None = None
    body1_radius_y: Length | None = None
    body2_radius_x: Length | None = None
    body2_radius_y: Length | None = None

    BODY: ClassVar[tuple[str, ...]] = ("body1_radius_x", "body1_radius_y", "body2_radius_x", "body2_radius_y")

    @property
    def by_bodies(self) -> bool:
        return any(getattr(self, key) is not None for key in self.BODY)

    @property
    def given(self) -> list[str]:
        """The geometry keys that were given (for mode checks)."""
        return [k for k in ("radius_x", "radius_y", "length") + self.BODY if getattr(self, k) is not None]

    def reduced_radii(self) -> tuple[float | None, float | None]:
        """(R_x, R_y) [m]; R_y is None for a line contact."""
        if not self.by_bodies:
            return self.radius_x, (None if self.line else self.radius_y)

        def combine(a, b):
            curvature = sum(1.0 / r for r in (a, b) if r is not None)
            return 1.0 / curvature if curvature > 0 else None

        rx = combine(self.body1_radius_x, self.body2_radius_x)
        ry = None if self.line else combine(self.body1_radius_y, self.body2_radius_y)
        return rx, ry

    @model_validator(mode="after")
    def _geometry(self):
        for key in self.BODY:
            value = getattr(self, key)
            if value is not None and value == 0.0:
                raise rule(key, value, "must not be 0 (convex > 0, concave < 0; omit it for a flat surface)")
        if self.by_bodies:
            for key in ("radius_x", "radius_y"):
                if getattr(self, key) is not None:
                    raise rule(key, getattr(self, key), "cannot be combined with body radii (body1_radius_x ...); "
                               "give the reduced radii or the body radii")
            for axis in ("x",) + (() if self.line else ("y",)):
                r1, r2 = getattr(self, f"body1_radius_{axis}"), getattr(self, f"body2_radius_{axis}")
                curvature = sum(1.0 / r for r in (r1, r2) if r is not None)
                if r1 is None and r2 is None:
                    hint = "" if axis == "x" else " (or set line = true)"
                    raise rule(f"body1_radius_{axis}", None, f"is required: give body1_radius_{axis} and/or "
                               f"body2_radius_{axis}{hint}")
                if not curvature > 0.0:
                    raise rule(f"body1_radius_{axis}", r1, f"and body2_radius_{axis} = {show_value(r2) if r2 is not None else 'flat'} "
                               f"give 1/R_{axis} = {curvature:.4g} 1/m; it must be > 0 (the surfaces conform or separate)")
        if self.line:
            for key in ("radius_y", "body1_radius_y", "body2_radius_y"):
                if getattr(self, key) is not None:
                    raise rule(key, getattr(self, key), "is not used by a line contact (line = true)")
        elif self.length is not None:
            raise rule("length", self.length, "is for line contacts only (line = true)")
        return self


class MaterialsModel(CaseTable):
    """Elastic bodies; 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.  Body 2 defaults to body 1."""

    modulus1: Q("pressure", gt=0)
    poisson1: Q("dimensionless", gt=-1, lt=0.5)
    modulus2: Q("pressure", gt=0) | None = None
    poisson2: Q("dimensionless", gt=-1, lt=0.5) | None = None

    @model_validator(mode="after")
    def _second_body(self):
        self.modulus2 = self.modulus1 if self.modulus2 is None else self.modulus2
        self.poisson2 = self.poisson1 if self.poisson2 is None else self.poisson2
        return self

    @property
    def e_star(self) -> float:
        return reduced_modulus(self.modulus1, self.poisson1, self.modulus2, self.poisson2)


class OperatingModel(CaseTable):
    """Speeds along +x: ``mean_speed`` u_m (with ``slide_to_roll`` = (u2 - u1)/u_m),
    or the surface speeds ``velocity1``, ``velocity2``.  Load: ``load`` [N]
    (a line contact with ``contact.length``: N on that length),
    ``load_per_length`` [N/m] (lines) or ``approach`` h00 [m] (prescribed)."""

    mean_speed: Q("velocity", gt=0) | None = None
    slide_to_roll: Q("dimensionless") | None = None
    velocity1: Velocity | None = None
    velocity2: Velocity | None = None
    load: Q("force", gt=0) | None = None
    load_per_length: Q("force per length", gt=0) | None = None
    approach: Length | None = None

    LOADS: ClassVar[tuple[str, ...]] = ("load", "load_per_length", "approach")

    @model_validator(mode="after")
    def _speeds_and_load(self):
        by_surfaces = self.velocity1 is not None or self.velocity2 is not None
        if by_surfaces:
            if self.mean_speed is not None:
                raise rule("mean_speed", self.mean_speed, "cannot be combined with velocity1/velocity2; give one or the other")
            if self.slide_to_roll is not None:
                raise rule("slide_to_roll", self.slide_to_roll, "follows from velocity1 and velocity2; give it only with mean_speed")
            if self.velocity1 is None or self.velocity2 is None:
                missing = "velocity1" if self.velocity1 is None else "velocity2"
                raise rule(missing, None, "is required with the other surface velocity (or give mean_speed)")
            if not self.velocity1 + self.velocity2 > 0.0:
                raise rule("velocity1", self.velocity1, f"and velocity2 = {show_value(self.velocity2)} give a mean "
                           "(entrainment) speed <= 0 m/s; it must be > 0 (entrainment along +x)")
        given = [k for k in self.LOADS if getattr(self, k) is not None]
        if len(given) > 1:
            raise rule(given[1], getattr(self, given[1]), f"cannot be combined with {given[0]}; give one of "
                       + ", ".join(self.LOADS))
        return self

    def speeds(self) -> tuple[float, float]:
        """(u_m [m/s], slide-to-roll ratio [-])."""
        if self.velocity1 is not None:
            um = 0.5 * (self.velocity1 + self.velocity2)
            return um, (self.velocity2 - self.velocity1) / um
        return self.mean_speed, self.slide_to_roll or 0.0


class GridModel(CaseTable):
    """Uniform grid: ``nx`` nodes on x in [x_min, x_max] Hertz semi-axes along x,
    ``ny`` (default: about square cells) on |y| <= y_max semi-axes across
    (points only).  nx and ny are 2^k + 1: finer grids are reached by nested
    iteration from the grid with half the cells."""

    nx: PositiveInt = 65
    ny: PositiveInt | None = None
    x_min: Q("dimensionless", lt=0) = -4.5
    x_max: Q("dimensionless", gt=0) = 1.5
    y_max: Q("dimensionless", gt=0) | None = None

    @model_validator(mode="after")
    def _sizes(self):
        if not _two_power_plus_one(self.nx, 9):
            raise rule("nx", self.nx, "must be 2^k + 1 (9, 17, 33, 65, 129, 257, 513, ...) for nested iteration")
        if self.ny is not None and not _two_power_plus_one(self.ny, 5):
            raise rule("ny", self.ny, "must be 2^k + 1 (5, 9, 17, 33, 65, ...) for nested iteration")
        return self


class TractionModel(CaseTable):
    """Shear law for friction: limiting_shear (|tau| <= tau_L0 + gamma p, the default) | eyring |
    newtonian.  The default follows measured EHL traction (Bair & Winer 1979: a limiting shear stress
    proportional to pressure, gamma 0.04-0.1 for mineral oils; :class:`lubedyn.lubrication.ehl.Traction`); a
    Newtonian shear at the Hertz zone's piezoviscous viscosity gives coefficients far above 1, which the
    run refuses (:mod:`lubedyn.bounds`)."""

    model: Literal["newtonian", "limiting_shear", "eyring"] = "limiting_shear"
    limiting_shear_stress: Q("pressure", gt=0) = 5e6
    limiting_shear_slope: Q("dimensionless", ge=0) = 0.08
    eyring_stress: Q("pressure", gt=0) = 5e6


class EHLSolverModel(CaseTable):
    """EHL solver (:mod:`lubedyn.lubrication.ehl`).  ``method``: ``auto`` (FEM with
    Fischer-Burmeister Newton for points, active-set Newton for lines),
    ``fischer_burmeister``, ``active_set``, or ``multigrid`` (FAS multigrid of
    :mod:`lubedyn.lubrication.ehl.multigrid`: steady point contacts, grids nx = 16 2^k + 1,
    finite differences; 257 x 257 in 2-3 s).  Newton: relative tolerance,
    iteration limit, step limit (in Hertz pressures); the multigrid method has
    its own tolerances (:class:`lubedyn.lubrication.ehl.multigrid.MultigridOptions`)."""

    method: Literal["auto", "fischer_burmeister", "active_set", "multigrid"] = "auto"
    rtol: Q("dimensionless", gt=0, lt=1) = 1e-7
    max_iter: PositiveInt = 80
    max_step: Q("dimensionless", gt=0) = 2.0


class EHLOutputModel(CaseTable):
    write: list[Literal["vtu", "png"]] = ["vtu", "png"]


class BearingModel(CaseTable):
    """The bearing the contact is taken from (:mod:`lubedyn.lubrication.laws.bearing`): the
    most loaded element on ``race``.  Balls: groove radii, optional diametral
    clearance; the contact angle follows from the axial load unless given.
    Rollers: line contact of ``effective_length`` at ``contact_angle``."""

    type: Literal["ball", "roller"]
    race: Literal["inner", "outer"] = "inner"
    element_diameter: PositiveLength
    pitch_diameter: PositiveLength
    n_elements: Annotated[int, Field(strict=True, ge=3)]
    inner_groove_radius: PositiveLength | None = None
    outer_groove_radius: PositiveLength | None = None
    diametral_clearance: Q("length", ge=0) | None = None
    effective_length: PositiveLength | None = None
    contact_angle: Q("angle", ge=0, lt=0.5 * math.pi) | None = None
    inner_speed: Q("angular velocity") = 0.0
    outer_speed: Q("angular velocity") = 0.0
    radial_load: Q("force", ge=0) = 0.0
    axial_load: Q("force", ge=0) = 0.0
    stribeck_constant: Q("dimensionless", gt=0) | None = None
    load_distribution: Literal["stribeck", "quasi_static"] = "stribeck"

    @model_validator(mode="after")
    def _kind(self, info: ValidationInfo):
        raw = context_raw(info)
        if self.type == "ball":
            for key in ("inner_groove_radius", "outer_groove_radius"):
                if getattr(self, key) is None:
                    raise rule(key, None, "is required for type = 'ball' (length, e.g. '4.905 mm')")
            if self.effective_length is not None:
                raise rule("effective_length", self.effective_length, "is for type = 'roller' only")
            self.diametral_clearance = self.diametral_clearance or 0.0
            self._ball_geometry(raw)
            if self.stribeck_constant is None:
                self.stribeck_constant = STRIBECK["point"]
        else:
            for key in ("inner_groove_radius", "outer_groove_radius", "diametral_clearance"):
                if getattr(self, key) is not None:
                    raise rule(key, getattr(self, key), "is for type = 'ball' only")
            for key in ("effective_length", "contact_angle"):
                if getattr(self, key) is None:
                    raise rule(key, None, "is required for type = 'roller'")
            self._element_scales(raw)
            if self.load_distribution != "stribeck":
                raise rule("load_distribution", self.load_distribution, "'quasi_static' is implemented for "
                           "type = 'ball' only; use 'stribeck'")
            if self.stribeck_constant is None:
                self.stribeck_constant = STRIBECK["line"]
        if self.inner_speed == self.outer_speed:
            raise rule("inner_speed", self.inner_speed, f"equals outer_speed = {show_value(self.outer_speed)} rad/s: the "
                       "rings do not turn relative to each other and nothing entrains the lubricant")
        if self.radial_load == 0.0 and self.axial_load == 0.0:
            raise rule("radial_load", 0.0, "and axial_load are both 0: no element is loaded")
        if self.type == "roller" and self.axial_load > 0.0 and self.contact_angle == 0.0:
            raise rule("axial_load", self.axial_load, "needs contact_angle > 0")
        return self


    def _element_scales(self, raw):
        """The element inside the pitch circle, the Z elements around it (:data:`FILL`), a roller's
        slenderness (:data:`ROLLER_MAX_SLENDERNESS`): its lengths against each other."""
        if not self.element_diameter < self.pitch_diameter:
            raise rule("element_diameter", self.element_diameter, f"must be < pitch_diameter = "
                       f"{self.pitch_diameter:g} m" + bare_hint(raw, "bearing.element_diameter", "length",
                                                               lambda si: si < self.pitch_diameter))
        D, dm = Scaled("bearing.element_diameter", self.element_diameter), Scaled("bearing.pitch_diameter",
                                                                                self.pitch_diameter)
        fill = lambda v: self.n_elements * v[D.key] / (math.pi * v[dm.key])  # noqa: E731
        name = f"fill Z D/(pi d_m) (Z = {self.n_elements})"
        raise_scale(check_scale(raw, name, fill, [D, dm], limit=FILL[1], strict=True,
                                why="the elements fit side by side around the pitch circle"))
        raise_scale(check_scale(raw, name, fill, [dm, D], limit=FILL[0], lower=True,
                                why="no bearing spaces its elements three diameters apart"))
        if self.type == "roller":
            length = Scaled("bearing.effective_length", self.effective_length)
            raise_scale(check_scale(raw, "effective_length/element_diameter", lambda v: v[length.key] / v[D.key],
                                    [length, D], limit=ROLLER_MAX_SLENDERNESS,
                                    why="needle rollers, the most slender, reach about 10"))

    def _ball_geometry(self, raw=None):
        """The ball inside the pitch circle, grooves that conform (:data:`GROOVE_MAX_CONFORMITY`) and a
        clearance that leaves the free contact angle below 90 deg (cos beta0 = 1 - P_d / (2 B D) > 0),
        checked only once the grooves are wider than the ball (else :mod:`lubedyn.lubrication.laws.bearing`
        names the groove radius), so that each message names the key that is wrong."""
        D = self.element_diameter
        self._element_scales(raw)
        for key in ("inner_groove_radius", "outer_groove_radius"):
            r = Scaled(f"bearing.{key}", getattr(self, key))
            raise_scale(check_scale(raw, f"{key}/element_diameter", lambda v, k=r.key: v[k] / D,
                                    [r, Scaled("bearing.element_diameter", D)], limit=GROOVE_MAX_CONFORMITY,
                                    blame=[r.key], why="bearing grooves conform closely to the ball, "
                                    "r/D = 0.505-0.58"))
        if not min(self.inner_groove_radius, self.outer_groove_radius) > 0.5 * D:
            return  # the groove radius is what is wrong: lubedyn.lubrication.laws.bearing names it ("must be > D/2")
        bd = self.inner_groove_radius + self.outer_groove_radius - D
        if not self.diametral_clearance < 2.0 * bd:
            raise rule("diametral_clearance", self.diametral_clearance, f"must be < 2 B D = {2 * bd:g} m, where "
                       f"the free contact angle reaches 90 deg (B D = inner_groove_radius + outer_groove_radius - "
                       f"element_diameter = {bd:g} m)" + bare_hint(raw, "bearing.diametral_clearance", "length",
                                                                    lambda si: si < 2.0 * bd))


class DimensionlessModel(CaseTable):
    """Moes' load and material parameters; the pressure-viscosity coefficient
    and the load follow at the scales R_x (contact.radius_x, default 10 mm),
    E* ([materials], default 100 GPa), eta0 and u_m (operating.mean_speed,
    default 1 m/s): :meth:`lubedyn.lubrication.ehl.EHLContact.from_moes`."""

    M: Q("dimensionless", gt=0)
    L: Q("dimensionless", ge=0)
    eta0: Q("dynamic viscosity", gt=0) = 0.04


class EHLCase(CaseTable):
    """An EHL scene; after validation every value is SI and every default filled in."""

    scene: Literal["ehl"]
    description: str = ""
    contact: ContactModel = Field(default_factory=ContactModel)
    materials: MaterialsModel | None = None
    lubricant: LubricantModel | None = None
    operating: OperatingModel = Field(default_factory=OperatingModel)
    bearing: BearingModel | None = None
    dimensionless: DimensionlessModel | None = None
    grid: GridModel = Field(default_factory=GridModel)
    traction: TractionModel = Field(default_factory=TractionModel)
    solver: EHLSolverModel = Field(default_factory=EHLSolverModel)
    output: EHLOutputModel = Field(default_factory=EHLOutputModel)
    validity: ValidityModel = Field(default_factory=ValidityModel)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    smoke: dict[str, Any] | None = None

    @property
    def is_line(self) -> bool:
        return self.contact.line

    @property
    def mode(self) -> str:
        """'bearing', 'dimensionless' or 'direct': where the contact data come from."""
        return "bearing" if self.bearing is not None else ("dimensionless" if self.dimensionless is not None else "direct")

    @model_validator(mode="after")
    def _resolve(self, info: ValidationInfo):
        c, op = self.contact, self.operating
        if self.bearing is not None and self.dimensionless is not None:
            raise root_rule("dimensionless", {}, "cannot be combined with [bearing]; give one")
        if self.mode == "dimensionless":
            self._resolve_dimensionless()
        elif self.mode == "bearing":
            for key in c.given:
                raise root_rule(f"contact.{key}", getattr(c, key), "is not used with [bearing] (the contact follows "
                                 "from the bearing; remove it or the [bearing] table)")
            if c.line != (self.bearing.type == "roller"):
                if c.line:
                    raise root_rule("contact.line", True, "does not match bearing.type = 'ball' (a point contact)")
                c.line = True
            for key in ("mean_speed", "velocity1", "velocity2") + OperatingModel.LOADS:
                if getattr(op, key) is not None:
                    raise root_rule(f"operating.{key}", getattr(op, key), "is not used with [bearing] (speed and "
                                     "load follow from the bearing's speeds and loads)")
            self._require_physics()
        else:
            if c.radius_x is None and not c.by_bodies:
                raise root_rule("contact.radius_x", None, "is required (length), or give body radii "
                                 "(body1_radius_x ...), a [bearing] or a [dimensionless] table")
            if not c.line and not c.by_bodies and c.radius_y is None:
                raise root_rule("contact.radius_y", None, "is required for a point contact (length), or set "
                                 "contact.line = true")
            if op.mean_speed is None and op.velocity1 is None:
                raise root_rule("operating.mean_speed", None, "is required (velocity, e.g. '2 m/s'), or give "
                                 "operating.velocity1 and operating.velocity2")
            if all(getattr(op, key) is None for key in OperatingModel.LOADS):
                raise root_rule("operating.load", None, "is required (force), or give "
                                 + ("load_per_length or approach" if c.line else "approach"))
            if not c.line and op.load_per_length is not None:
                raise root_rule("operating.load_per_length", op.load_per_length, "is for line contacts "
                                 "(contact.line = true); give operating.load [N]")
            if c.line and op.load is not None and c.length is None:
                raise root_rule("operating.load", op.load, "of a line contact needs contact.length (or give "
                                 "operating.load_per_length [N/m])")
            self._require_physics()
        if op.mean_speed is not None and op.slide_to_roll is None:
            op.slide_to_roll = 0.0
        g = self.grid
        if c.line:
            for key in ("ny", "y_max"):
                if getattr(g, key) is not None:
                    raise root_rule(f"grid.{key}", getattr(g, key), "is not used by a line contact")
        elif g.y_max is None:
            g.y_max = 3.0
        if self.validity.max_pressure is None:
            self.validity.max_pressure = EHL_MAX_PRESSURE
        if self.mode != "dimensionless":  # Moes' M and L fix the contact's proportions themselves
            self._check_scales(context_raw(info))
        return self

    def _contact_load(self, e_star: float):
        """(R_x, R_y or None, load [N, or N/m for lines], line length or None, the load's key) of the
        case's contact with reduced modulus ``e_star``; None when it has no load (an approach) or its
        bearing cannot be solved (the scene's build names why)."""
        c, op = self.contact, self.operating
        if self.mode == "bearing":
            try:
                race = race_contact(self, e_star)
            except (InputError, ValueError, ArithmeticError):
                return None
            line = race.radius_y is None
            key = "bearing.radial_load" if self.bearing.radial_load > 0.0 else "bearing.axial_load"
            return race.radius_x, race.radius_y, race.load_per_length if line else race.load, race.length, key
        rx, ry = c.reduced_radii()
        if op.load_per_length is not None:
            return rx, None, op.load_per_length, c.length, "operating.load_per_length"
        if op.load is None:
            return None
        return rx, ry, op.load / c.length if c.line else op.load, c.length, "operating.load"

    def _check_scales(self, raw):
        """A film possible: an approach thin against R_x (THIN_FILM), a Hertz contact small against the
        radii of curvature and a line contact's half-width small against its length (SMALL_CONTACT).
        Blamed: a bare modulus that a unit puts right (a bare 207 is 207 Pa: "207 GPa"), else a short
        line's length, else the load."""
        c, op, mat = self.contact, self.operating, self.materials
        rx, _ = c.reduced_radii()
        radius_x = Scaled("contact.radius_x", rx, given=c.radius_x is not None and not c.by_bodies)
        if op.approach is not None and self.mode == "direct":
            raise_scale(thin_film(raw, Scaled("operating.approach", op.approach), radius_x, "|approach|/R_x"))
        m1 = Scaled("materials.modulus1", mat.modulus1, "pressure")
        moduli = [m1] + ([Scaled("materials.modulus2", mat.modulus2, "pressure")]
                         if mat.modulus2 != mat.modulus1 or (raw or {}).get("materials", {}).get("modulus2") else [])

        def e_star_of(v):  # modulus2 follows modulus1 unless it was given
            return reduced_modulus(v[m1.key], mat.poisson1, v.get("materials.modulus2", v[m1.key]), mat.poisson2)

        got = self._contact_load(e_star_of({q.key: q.value for q in moduli}))
        if got is None:
            return
        rx, ry, load, length, load_key = got
        line = ry is None
        per_length = line and load_key == "operating.load"  # N on contact.length
        if self.mode == "bearing":
            load_q = Scaled(load_key, getattr(self.bearing, load_key.split(".")[1]), "force")
        else:
            load_q = Scaled(load_key, op.load if per_length else load,
                            "force per length" if line and not per_length else "force")

        def size(v):  # the largest Hertz semi-axis over its radius of curvature
            if self.mode == "bearing":
                again = self._contact_load(e_star_of(v))
                if again is None:
                    return 0.0
                Rx, Ry, w = again[:3]
            else:
                w = v.get(load_key, load_q.value)
                Rx, Ry, w = rx, ry, w / v.get("contact.length", length) if per_length else w
            e_star = e_star_of(v)
            if Ry is None:
                return line_contact(w, Rx, e_star).b / Rx
            h = point_contact(w, Rx, Ry, e_star)
            along_x, across = (h.b, h.a) if Ry >= Rx else (h.a, h.b)
            return max(along_x / Rx, across / Ry)

        small = lambda v: size(v) <= SMALL_CONTACT  # noqa: E731
        if line and length is not None:  # first: a short line is what a wide one means then
            b = line_contact(load, rx, e_star_of({q.key: q.value for q in moduli})).b
            key = "bearing.effective_length" if self.mode == "bearing" else "contact.length"

            def per_metre(v):
                if self.mode == "bearing":
                    return load
                return v[load_key] / v[key] if per_length else v[load_key]

            raise_scale(check_scale(raw, "b/length (Hertz half-width over the line's length)",
                                    lambda v: line_contact(per_metre(v), rx, e_star_of(v)).b / v[key],
                                    [Scaled(key, length), load_q] + moduli + [Scaled("b", b, given=False)],
                                    limit=SMALL_CONTACT, why="a line contact is long against its width",
                                    also=[small]))
        shown = [Scaled("R_x", rx, given=False)] + ([] if line else [Scaled("R_y", ry, given=False)])
        raise_scale(check_scale(raw, "Hertz semi-axis/radius of curvature", size, [load_q] + moduli + shown,
                                limit=SMALL_CONTACT, why=SMALL_CONTACT_WHY))

    def _require_physics(self):
        if self.materials is None:
            raise root_rule("materials", None, "is required: [materials] modulus1, poisson1 (and modulus2, "
                             "poisson2 when the second body differs)")
        if self.lubricant is None:
            raise root_rule("lubricant", None, "is required: [lubricant.viscosity] law, eta0, alpha ... "
                             "(or [lubricant] viscosity = '0.05 Pa s')")

    def _resolve_dimensionless(self):
        c, op = self.contact, self.operating
        if self.lubricant is not None:
            raise root_rule("lubricant", {}, "is not used with [dimensionless] (alpha follows from L; "
                             "give dimensionless.eta0; the density is incompressible)")
        for key in ("length",) + ContactModel.BODY:
            if getattr(c, key) is not None:
                raise root_rule(f"contact.{key}", getattr(c, key), "is not used with [dimensionless] (give "
                                 "contact.radius_x, and radius_y for an elliptical contact)")
        for key in ("velocity1", "velocity2") + OperatingModel.LOADS:
            if getattr(op, key) is not None:
                raise root_rule(f"operating.{key}", getattr(op, key), "is not used with [dimensionless] (the load "
                                 "follows from M; give operating.mean_speed)")
        if c.radius_x is None:
            c.radius_x = 0.01
        if not c.line and c.radius_y is None:
            c.radius_y = c.radius_x
        if op.mean_speed is None:
            op.mean_speed = 1.0


CaseModel = EHLCase


def race_contact(case: EHLCase, e_star: float) -> bearings.RaceContact:
    """The most loaded element's contact of the case's ``[bearing]``."""
    b = case.bearing
    common = dict(race=b.race, pitch_diameter=b.pitch_diameter, radial_load=b.radial_load, axial_load=b.axial_load,
                  inner_speed=b.inner_speed, outer_speed=b.outer_speed, stribeck_constant=b.stribeck_constant)
    if b.type == "ball":
        return bearings.ball_race_contact(
            ball_diameter=b.element_diameter, inner_groove_radius=b.inner_groove_radius,
            outer_groove_radius=b.outer_groove_radius, n_balls=b.n_elements, e_star=e_star,
            contact_angle=b.contact_angle, clearance=b.diametral_clearance, load_distribution=b.load_distribution,
            **common)
    return bearings.roller_race_contact(roller_diameter=b.element_diameter, effective_length=b.effective_length,
                                        n_rollers=b.n_elements, contact_angle=b.contact_angle, **common)
