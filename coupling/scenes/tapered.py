"""Tapered-roller dynamics scene (``scene = "tapered"``): paper A's bearing in time.

A case (usually ``parameters = "Wu2018"``: Table 1 and the parameter module's assumed values; each table
maps one to one onto a group of :class:`lubedyn.dynamics.tapered.model.TaperedBearing`, field by field)::

    scene = "tapered"
    parameters = "Wu2018"
    [operating]                 # lubedyn.dynamics.tapered.groups.Operating
    speed = "2400 rpm"          # cone; cup fixed
    radial_load = "20 kN"       # along +y
    axial = "locked"            # "locked" (at axial_displacement: > 0 a preload) or "force" (free under axial_load)
    cone_tilt = "locked"        # or "free": the cone tilts (two small rotations) under the loads' moment
    load_offset = "0 mm"        # the radial load's axial position from the cone's reference point (tilt free)
    applied_moment = ["0 N m", "0 N m"]   # (M_y, M_z) about that point (tilt free)
    [model]                     # Fidelity: one key per modelling option (which law, or none)
    slices = 10
    traction = "limited"        # "paper" (eq. 12), "limited" (HB + limiting shear + elastic film), "map" (roller EHL maps), "none"
    flange_friction = "none"    # "paper" (eqs. 22-23), "load_share", "none"
    pocket = "film"             # "film" (eqs. 30-38), "contact" (contact only), "none" (no cage)
    guide_land = "film"         # "film", "contact", "none" (with pocket = "none")
    [lubricant]                 # Lubricant: grease = "polyurea" | "lithium" | "calcium" (Table 2 at temperature_c),
    grease = "polyurea"         #   "custom" (yield_stress, consistency, exponent) or "none"
    viscosity = { law = "barus", eta0 = "0.1 Pa s", alpha = "4.662e-8 m^2/N" }   # the base oil, as in every scene
    oil_temperature = "walther" #   eta0 at oil_reference_c, moved to temperature_c on ASTM D341's line
    oil_nu100 = "8.6 mm^2/s"    #   through the base oil's viscosity at 100 C ("none": eta0 at every temperature)
    raceway_film = "formula"    # or "grease_ehl": the raceway films from the grease's EHL solve (below)
    [integrator]
    method = "dopri5"           # or "rk4" with dt (refused above the contact modes' stability limit)
    duration = "180 ms"
    [analysis]
    window = ["100 ms", "180 ms"]   # paper A's averaging window

``run`` starts from the quasi-static equilibrium (:func:`lubedyn.dynamics.tapered.quasistatic.solve`) with the
cage and rollers at their ideal speeds, integrates :func:`lubedyn.dynamics.tapered.kernels.rhs` and writes
``summary.json`` (for the paper's window and for the record's last cage revolution: per zone -- loaded,
unloaded, all -- the mean, amplitude and largest magnitude of tilt, skew, slip and radial displacement;
cage speed and slip, whirl radius, a periodicity measure; the quasi-static loads beside the largest
dynamic ones; the assumed values), ``timeseries.nc`` (or ``.npz``: ``output.timeseries_format``; every
state; per roller tilt, skew, speeds, slips, displacements (from the start and from the ideal, unloaded position), the loaded-zone marker,
loads, friction and every slice load; the cage),
``bearing.pvd`` with ``frames/*.vtu`` (cup, cone, rollers and cage for ParaView, loads and attitude
as point data) and the PNGs ``roller_attitude.png`` (loaded zone shaded), ``roller_displacement.png``,
``slip.png``, ``cage_whirl.png``, ``cone_orbit.png``, ``slice_loads.png``.

Definitions (paper A, sec. 4 and eq. 52; ``docs/paper_a.md``, "What paper A leaves out";
:meth:`TaperedBearing.diagnostics`): at each sample the roller
axis e is split in the roller's own radial frame (x axial, r radial through its centre, t tangential):
tilt = atan2(e_r, e_x) and skew = asin(e_t), both minus their values at the start; slip (eq. 52) =
(omega_ideal - omega)/omega_ideal of a roller centre's orbital speed and of the cage's spin, with
omega_ideal the geometry's own ideal cage speed omega_i (1 - gamma)/2.  A roller is in the loaded zone
while its cone load exceeds ``analysis.loaded_zone_fraction`` of the start's largest.  Periodicity:
:func:`lubedyn.dynamics.analysis.windows.periodicity` (1 when every roller repeats its neighbour's signal one
roller pass later).

With ``operating.cone_tilt = "free"`` the summary adds the cone's tilt (theta_y, theta_z) [rad]: its
quasi-static start, and per window its mean and amplitude; the time series carries it (the state's
"Cone tilt y/z [rad]" and the contacts' moment on the cone).

Raceway films (``lubricant.raceway_film``).  The compiled dynamics give each raceway slice the
Dowson-Toyoda central film at its line load and the ideal entrainment speed; it sets the limited
traction's shear rate and the film's elastic slope 2 G b^2/(u_e h), so the rollers' and the cage's slip
scale with it.  "formula" (the default) takes the films' Newtonian viscosity (``reading``: with
"base_oil" the assumed base oil, so the films do not depend on the grease).  "grease_ehl" solves, per
raceway, the line EHL contact of the case's grease (Herschel-Bulkley Poiseuille flow, phi0 exp(alpha p):
Table 2 at ``temperature_c`` or "custom") at the most loaded roller's quasi-static load per unit effective
length and the ideal entrainment speed (:func:`grease_ehl_film`: the roller kinds' film-scaled domain on
257 nodes, 513 where the solver's own checks reject the 257-node solution; cached per process), and gives
that raceway the viscosity eta_eff = eta (h_EHL/h_DT(eta))^(1/0.69) with which Dowson-Toyoda (H ~ U^0.69)
reproduces the solved film at that load (:func:`raceway_films`; the summary's "Raceway films": both films
in um, the factor, the viscosities, the grid, the solve's wall time).  The factor is held for every
slice and load of the run.  Measured (docs/paper_a.md, benchmarks/trb_raceway_film.py) at Fa 15 kN,
2,800 rpm (all rollers equally loaded), polyurea at 30 C: factors 1.70 (cup) and 1.71 (cone) at the
108 / 104 kN/m of the rollers; at 0.6 times that load 1.58 / 1.58 (-7 %, -8 %); at 0.3 times the solver
gives no grid-independent film, so a radially loaded bearing's light rollers take the heavy roller's
factor unchecked.  The cup's solution is not unique (loads 1e-9 apart converge to 10.13 or 11.33 um
from different Newtonian starts, 10.13-11.48 um within +-1 % of the load; the cone's within 0.05 %).  A grease the solver does
not reach (Table 2's lithium, n = 0.31) is a one-line error; "grease_ehl" needs a grease and a traction
that reads the film ("paper" or "limited").  Eq. 12's viscosity, the pocket, land and rib films keep
the films' viscosity.


Rib film (``[flange] rib_film``): "hamrock_dowson" (default), "paper_eq24" (eq. 24 rebuilt) or "ehl", the
project's EHL solver at the rib (Herschel-Bulkley flow of the grease) read from the shipped map of the case's
grease and temperature (:data:`RIB_FILM_MAPS`: lithium at 30 C; the solver does not reach the thick films of the
base oil, polyurea and calcium, coupling/film_points/rib.py).  Each is evaluated once, at the quasi-static start's
largest flange load and the rib's ideal entrainment speed (the kernel's film ratio is constant in a run).
"""
from __future__ import annotations

import dataclasses
import logging
import math
import time
from dataclasses import dataclass, field
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BeforeValidator, Field, model_validator

from lubedyn.results import BearingResult
from lubedyn.dynamics.analysis.windows import window_summary
from lubedyn.dynamics.integrators import ATOL_MAX, ATOL_WHY, RTOL_MAX, RTOL_WHY
from lubedyn.lubrication.errors import ConvergenceError, InputError

from lubedyn import outputs
from lubedyn.config import (BoundsModel, LimitsModel, LubricantModel, PositiveInt, Q, CaseTable, TimeSeriesOutput, Viscosity,
                            refuse_renamed, root_rule, rule)
from lubedyn.papers.wu2018.parameters import GREASE_TABLE as GREASES
from lubedyn.scenes.static import BearingTable
from lubedyn.config import CASES_DIR
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.integrators import kernel_example
from lubedyn.dynamics.rotations import to_scipy
from lubedyn.dynamics.specialise import compile_in_background
from lubedyn.dynamics.tapered import groups as G, kernels as K, layout as L
from lubedyn.dynamics.tapered.model import TaperedBearing
from lubedyn.lubrication.laws.film import dowson_toyoda_central
from lubedyn.lubrication.laws.grease import grease_at
from lubedyn.lubrication.laws.thermal import walther_dynamic
from lubedyn.maps import FilmMap
from lubedyn.scenes.bearing_run import Integration, drive
from lubedyn.scenes.static import body_grid, build as build_geometry, raceway_surface

log = logging.getLogger(__name__)

FIELD_FILES = (("timeseries.nc", "timeseries"), ("bearing.pvd", "pvd"), ("roller_attitude.png", "png"),
               ("roller_displacement.png", "png"), ("slip.png", "png"), ("cage_whirl.png", "png"),
               ("cone_orbit.png", "png"), ("slice_loads.png", "png"))


class OperatingTable(CaseTable):
    """:class:`lubedyn.dynamics.tapered.groups.Operating`."""

    speed: Q("angular velocity", ge=0) = 0.0
    radial_load: Q("force", ge=0) = 0.0
    axial: Literal["locked", "force"] = "locked"
    axial_load: Q("force", ge=0) = 0.0
    axial_displacement: Q("length") = 0.0
    gravity: Q("acceleration", ge=0) = 0.0
    cone_tilt: Literal["locked", "free"] = "locked"
    load_offset: Q("length") = 0.0
    applied_moment: Annotated[list[Q("energy")], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [0.0, 0.0])

    @model_validator(mode="after")
    def _axial(self):
        if self.axial == "force" and self.axial_load == 0.0:
            raise rule("axial_load", 0.0, "must be > 0 with axial = 'force': a single tapered bearing has no "
                       "axial equilibrium without an axial load (docs/paper_a.md); or set axial = 'locked'")
        return self


class ModelTable(CaseTable):
    """:class:`lubedyn.dynamics.tapered.groups.Fidelity` (which law each contact uses, or none)."""

    slices: PositiveInt = 20
    traction: Literal["none", "paper", "limited", "map"] = "limited"
    flange_friction: Literal["none", "paper", "load_share"] = "none"
    pocket: Literal["none", "contact", "film"] = "film"
    guide_land: Literal["none", "contact", "film"] = "film"
    damping_alpha: Q("inverse velocity", ge=0) = 0.16
    cone_mass: Q("mass", gt=0) = 5.0  # assumed (not in paper A)
    quaternion_stabilisation: Q("frequency", ge=0) = 10.0
    friction_speed: Q("velocity", gt=0) = 1e-3
    pocket_switch: Literal["continuous", "paper"] = "continuous"
    side_beams: bool = True
    traction_evaluation: Literal["quadrature", "table"] = "table"


class LubricantTable(LubricantModel):
    """:class:`lubedyn.dynamics.tapered.groups.Lubricant`: the one ``[lubricant]`` table of every scene
    (:class:`lubedyn.config.LubricantModel`) with the grease's keys beside the oil.  The oil:
    ``[lubricant.viscosity]`` ``eta0`` the base oil's viscosity (read with ``reading = "base_oil"``; may be
    left out with another reading) and Barus' ``alpha`` (law = "barus"; "constant": alpha = 0), the
    pressure-viscosity coefficient of the films, of eq. 12 and of the grease's consistency phi0 exp(alpha p).
    ``grease``: a grease of paper A's Table 2 at ``temperature_c`` [C] (15-70; interpolated by
    :func:`lubedyn.lubrication.laws.grease.grease_at`), "custom" (``yield_stress``, ``consistency``,
    ``exponent`` given) or "none" (a Newtonian oil only).

    The base oil at ``temperature_c``: ``oil_temperature = "none"`` takes eta0 at every temperature;
    ``"walther"`` reads eta0 as the base oil's viscosity at ``oil_reference_c`` [C] and moves it along the
    ASTM D341 (Walther) line through (``oil_reference_c``, eta0/rho0) and (100 C, ``oil_nu100``)
    (:func:`lubedyn.lubrication.laws.thermal.walther_dynamic`; rho0 of ``[lubricant.density]``, its own
    change with temperature left out), so the films, the film's elastic traction slope and the pocket and
    guide-land films follow the temperature as the grease's Table 2 constants do."""

    viscosity: Viscosity | None = None
    grease: Literal["none", "custom", "polyurea", "lithium", "calcium"] = "none"
    temperature_c: float = 30.0
    yield_stress: Q("pressure", ge=0) | None = None
    consistency: Q("dimensionless", gt=0) | None = None   # phi [Pa s^n]: units depend on n
    exponent: Q("dimensionless", gt=0, le=2) | None = None
    reading: Literal["base_oil", "apparent", "paper"] = "base_oil"
    shear_rate: Q("frequency", gt=0) | None = None
    limiting_stress: Q("pressure", gt=0) = math.inf
    limiting_slope: Q("dimensionless", ge=0) = 0.0
    yield_rate: Q("frequency", ge=0) = 0.0
    shear_modulus: Q("pressure", gt=0) = math.inf
    oil_temperature: Literal["none", "walther"] = "none"
    oil_reference_c: float = 30.0
    oil_nu100: Q("kinematic viscosity", gt=0) | None = None
    raceway_film: Literal["formula", "grease_ehl"] = "formula"

    @model_validator(mode="after")
    def _grease(self):
        given = [getattr(self, k) is not None for k in ("yield_stress", "consistency", "exponent")]
        if self.grease == "custom" and not all(given):
            missing = [k for k, g in zip(("yield_stress", "consistency", "exponent"), given) if not g]
            raise rule(missing[0], None, "must be given with grease = 'custom'")
        if self.grease != "custom" and any(given):
            key = ("yield_stress", "consistency", "exponent")[given.index(True)]
            raise rule(key, getattr(self, key), f"is only read with grease = 'custom' (grease = {self.grease!r})")
        if self.grease in GREASES and not 15.0 <= self.temperature_c <= 70.0:
            raise rule("temperature_c", self.temperature_c, "must lie in 15-70 C, the temperatures of paper A's "
                       "Table 2 (not extrapolated)")
        if self.oil_temperature == "walther":
            if self.oil_nu100 is None:
                raise rule("oil_nu100", None, "is required with oil_temperature = 'walther': the base oil's "
                           "kinematic viscosity at 100 C, e.g. '8.6 mm^2/s'")
            if not -20.0 <= self.oil_reference_c < 100.0:
                raise rule("oil_reference_c", self.oil_reference_c, "must lie in -20 C to below 100 C (the "
                           "temperature of oil_nu100)")
            if not -20.0 <= self.temperature_c <= 150.0:
                raise rule("temperature_c", self.temperature_c, "must lie in -20 to 150 C with oil_temperature = "
                           "'walther' (a bearing's range; ASTM D341's line is not used beyond it)")
        if self.raceway_film == "grease_ehl" and self.grease == "none":
            raise rule("raceway_film", self.raceway_film, "needs a grease (its EHL film): lubricant.grease = 'polyurea', "
                       "'calcium', 'lithium' (Table 2 at temperature_c) or 'custom'; or raceway_film = 'formula'")
        if self.reading == "base_oil" and self.viscosity is None:
            raise rule("viscosity", None, "is required with reading = 'base_oil': the base oil's eta0 (and Barus' "
                       "alpha), e.g. viscosity = { law = 'barus', eta0 = '0.1 Pa s', alpha = '4.662e-8 m^2/N' }")
        return self

    def oil(self) -> tuple[float | None, float]:
        """``(eta0, alpha)`` of the base oil (:meth:`LubricantModel.barus`; ``(None, 0.0)`` without one)."""
        return self.barus("tapered", grease="its grease is lubricant.grease")

    def group_values(self) -> dict:
        """The fields of :class:`lubedyn.dynamics.tapered.groups.Lubricant`."""
        eta0, alpha = self.oil()
        if self.oil_temperature == "walther" and eta0 is not None:
            eta0 = walther_dynamic(self.temperature_c, self.oil_reference_c, eta0, 100.0, self.oil_nu100,
                                   self.density.rho0)
        out = {"reading": self.reading, "base_oil_viscosity": eta0, "pressure_viscosity": alpha,
               **{k: getattr(self, k) for k in ("shear_rate", "limiting_stress", "limiting_slope", "yield_rate",
                                                "shear_modulus")}}
        if self.grease in GREASES:
            g = grease_at(GREASES[self.grease], self.temperature_c, alpha, self.grease)
            out.update(yield_stress=g.yield_stress, consistency=g.consistency, exponent=g.exponent)
        elif self.grease == "custom":
            out.update(yield_stress=self.yield_stress, consistency=self.consistency, exponent=self.exponent)
        return out


class CageTable(CaseTable):
    """:class:`lubedyn.dynamics.tapered.groups.Cage` (read when ``model.pocket`` != "none")."""

    mass: Q("mass", gt=0) | None = None
    boundary_friction: Q("dimensionless", ge=0) = 0.1
    modulus: Q("pressure", gt=0) | None = None
    poisson: Q("dimensionless", ge=0, lt=0.5) | None = None
    pocket_critical_film: Q("length", ge=0) = 0.0
    pocket_stiffness: Q("stiffness", ge=0) = 0.0
    pocket_damping: Q("damping", ge=0) = 0.0
    land_critical_film: Q("length", ge=0) = 0.0
    side_beam_clearance: Q("length", ge=0) = 0.0
    side_beam_thickness: Q("length", ge=0) = 0.0


class FlangeTable(CaseTable):
    """:class:`lubedyn.dynamics.tapered.groups.Flange` (read when ``model.flange_friction`` != "none")."""

    asperity_friction: Q("dimensionless", ge=0) = 0.2
    asperity_b: Q("dimensionless", ge=0) | None = None
    asperity_c: Q("dimensionless", ge=0) | None = None
    roughness: Q("length", gt=0) | None = None
    rib_film: Literal["hamrock_dowson", "paper_eq24", "ehl"] = "hamrock_dowson"


class InitialTable(CaseTable):
    """:class:`lubedyn.dynamics.tapered.groups.Initial`: offsets (y, z) of the cone's and the cage's centres."""

    cone_offset: Annotated[list[Q("length")], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [0.0, 0.0])
    cage_offset: Annotated[list[Q("length")], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [0.0, 0.0])


def _step_or_auto(value):
    """An RK4 step: a positive time (units, e.g. '2 us') or "auto"."""
    if value is None or value == "auto":
        return value
    from pydantic import TypeAdapter, ValidationError
    from pydantic_core import PydanticCustomError

    try:
        return TypeAdapter(Q("time", gt=0)).validate_python(value)
    except ValidationError:
        raise PydanticCustomError("quantity", "{text}", {"text": "must be a positive time (e.g. '2 us') or 'auto' "
                                                                 "(0.8 x the model's stable-step estimate)"}) from None


StepOrAuto = Annotated[Any, BeforeValidator(_step_or_auto)]


class IntegratorTable(CaseTable):
    """``method``: "rk4" (fixed step ``dt``; "auto": 0.8 x :meth:`TaperedBearing.stable_step`, the
    default) or "dopri5" (adaptive, ``rtol``/``atol``).  benchmarks/trb.py (20 ms): RK4 at the stable-step
    estimate is 4.8 x faster than DOPRI5 at rtol 1e-6, its mean skew and tilt within 2.5e-5 and 9.8e-5 of
    DOPRI5 at rtol 1e-9; at half of it 2.6 x, within 1.5e-6 and 5.9e-6.  ``rtol`` <= 1e-3 and ``atol`` <=
    1e-8: beyond them DOPRI5's error control means nothing (measured: :data:`lubedyn.dynamics.integrators.RTOL_MAX`)."""

    method: Literal["dopri5", "rk4"] = "rk4"
    dt: StepOrAuto = "auto"
    rtol: Q("dimensionless", gt=0, le=RTOL_MAX, why=RTOL_WHY) = 1e-7
    atol: Q("dimensionless", gt=0, le=ATOL_MAX, why=ATOL_WHY) = 1e-12
    duration: Q("time", gt=0)
    sample_interval: Q("time", gt=0) = 20e-6
    max_steps: PositiveInt = 50_000_000

    @model_validator(mode="after")
    def _samples(self):
        if self.method == "rk4" and self.dt is None:
            raise rule("dt", None, "is required with method = 'rk4': a fixed step, or 'auto' (0.8 x the model's "
                       "stable-step estimate)")
        n = self.duration / self.sample_interval
        if n < 2:
            raise rule("sample_interval", self.sample_interval, f"must be below integrator.duration = "
                       f"{self.duration:g} s (at least 2 samples)")
        if n > 2_000_000:
            raise rule("sample_interval", self.sample_interval, f"gives {n:.3g} samples; at most 2,000,000")
        return self


class AnalysisTable(CaseTable):
    """``window`` [s]: the averaging window of the summary (paper A's 0.1-0.18 s), clipped to the record;
    beside it the summary always reports the record's last cage revolution, and, when the record is at
    least twice ``converged_window`` [s] long, the "Converged window": the record's last
    ``converged_window`` against the one before it (:func:`converged_summary`; its means are called
    converged when every headline mean moved by at most ``converged_tolerance`` of its size).  A roller is
    in the loaded
    zone when its cone load exceeds ``loaded_zone_fraction`` of the quasi-static start's largest.
    ``frames``: ParaView frames of the ``.pvd`` series."""

    window: Annotated[list[Q("time", ge=0)], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [0.1, 0.18])
    converged_window: Q("time", gt=0) = 0.08
    converged_tolerance: Q("dimensionless", gt=0) = 0.02
    loaded_zone_fraction: Q("dimensionless", gt=0, lt=1) = 0.01
    frames: PositiveInt = 50

    @model_validator(mode="after")
    def _window(self):
        if not self.window[1] > self.window[0]:
            raise rule("window", self.window, "must be [start, end] with end > start")
        return self


class OutputTable(TimeSeriesOutput):
    """``[output]``: ``write`` the files (time series, ParaView frames, figures); ``timeseries_format``:
    :class:`lubedyn.config.TimeSeriesOutput`."""

    write: list[Literal["timeseries", "png", "pvd"]] = Field(default_factory=lambda: ["timeseries", "png", "pvd"])


class TaperedCase(CaseTable):
    scene: Literal["tapered"]
    description: str = ""
    bearing: BearingTable
    operating: OperatingTable = Field(default_factory=OperatingTable)
    model: ModelTable = Field(default_factory=ModelTable)
    lubricant: LubricantTable
    cage: CageTable = Field(default_factory=CageTable)
    flange: FlangeTable = Field(default_factory=FlangeTable)
    initial: InitialTable = Field(default_factory=InitialTable)
    integrator: IntegratorTable
    analysis: AnalysisTable = Field(default_factory=AnalysisTable)
    output: OutputTable = Field(default_factory=OutputTable)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    validity: BoundsModel = Field(default_factory=BoundsModel)  # strict: lubedyn.bounds
    smoke: dict[str, Any] | None = None

    @model_validator(mode="before")
    @classmethod
    def _renamed(cls, data):
        return refuse_renamed(data, ("lubricant.base_oil_viscosity", "lubricant.pressure_viscosity"))

    @model_validator(mode="after")
    def _oil(self):
        self.lubricant.oil()  # refuses what the scene would not read (LubricantModel.barus)
        if self.lubricant.raceway_film == "grease_ehl" and self.model.traction not in ("paper", "limited"):
            raise root_rule("lubricant.raceway_film", "grease_ehl", f"sets the raceway films that traction 'paper' "
                            f"and 'limited' read; model.traction = {self.model.traction!r} reads none (the maps "
                            "hold their own films): use raceway_film = 'formula'")
        return self


CaseModel = TaperedCase


def build(case: TaperedCase):
    """The :class:`lubedyn.dynamics.tapered.model.TaperedBearing` of a case: each table one group, field by field
    (the lubricant's grease resolved from Table 2); a bad value is a one-line error naming the key."""
    g = build_geometry(case)
    m = case.model
    try:
        groups = {"operating": G.Operating(**{**dict(case.operating),
                                              "applied_moment": tuple(case.operating.applied_moment)}),
                  "fidelity": G.Fidelity(**dict(m)),
                  "lubricant": G.Lubricant(**case.lubricant.group_values()),
                  "initial": G.Initial(cone_offset=tuple(case.initial.cone_offset),
                                       cage_offset=tuple(case.initial.cage_offset))}
        if m.pocket != "none":
            c = dict(case.cage)
            if c["mass"] is None:
                raise DynamicsInputError(f"cage.mass = None: must be given with model.pocket = {m.pocket!r}",
                                         key="cage.mass")
            groups["cage"] = G.Cage(**c)
        if m.flange_friction != "none":
            f = dict(case.flange)
            for key in ("asperity_b", "asperity_c", "roughness"):
                if f[key] is None:
                    raise DynamicsInputError(f"flange.{key} = None: must be given with model.flange_friction = "
                                             f"{m.flange_friction!r}", key=f"flange.{key}")
            groups["flange"] = G.Flange(**f)
        if m.traction == "map":
            groups["traction_maps"] = roller_traction_maps()
        if m.flange_friction != "none" and case.flange.rib_film == "ehl":
            groups["rib_film_map"] = rib_film_map(case.lubricant)
        model = TaperedBearing(geometry=g, **groups)
        if case.lubricant.raceway_film == "grease_ehl":
            films = raceway_films(case, model, model.quasi_static())
            model = dataclasses.replace(model, lubricant=dataclasses.replace(
                model.lubricant, raceway_film_viscosities=tuple(films[race]["Effective viscosity [Pa s]"]
                                                                for race in RACES)))
        return model
    except DynamicsInputError as exc:
        raise InputError(str(exc)) from None


# ---------------------------------------------------------------- raceway films from the grease's EHL solve
RACES = ("cup", "cone")
#: the EHL resolutions (lubedyn.film_points.EHL_RESOLUTIONS, line: 257 and 513 nodes on the roller kinds'
#: film-scaled domain) tried in turn: the finer one where the coarser solution fails the solver's own
#: a-posteriori checks (measured at Fa 15 kN, 2,800 rpm, phi0 = 38.44 Pa s^n: the cup's 257-node solve
#: returned a 408 um film flagged by the resolution check; 513 nodes gave 40.20 um, 1025 nodes 40.16 um)
RACEWAY_FILM_RESOLUTIONS = ("default", "fine")
_RACEWAY_EHL: dict = {}   # solve inputs -> film record or the error: one solve per process


def _dt_film(eta, speed, load, radius, alpha, e_prime) -> float:
    """Dowson-Toyoda's central film [m] (lubedyn.lubrication.laws.film.dowson_toyoda_central) of a line
    contact: the kernel's formula (lubedyn.dynamics.tapered.kernels.raceway_film)."""
    return radius * dowson_toyoda_central(eta * speed / (e_prime * radius), alpha * e_prime, load / (e_prime * radius))


def _grease_name(case) -> str:
    lu = case.lubricant
    if lu.grease == "custom":
        return (f"the custom grease (tau_y {lu.yield_stress:g} Pa, phi0 {lu.consistency:g} Pa s^n, n {lu.exponent:g}) "
                f"at {lu.temperature_c:g} C")
    return f"{lu.grease} at {lu.temperature_c:g} C"


def grease_ehl_film(race: str, radius: float, e_prime: float, grease, density: float, load: float,
                    speed: float, resolutions: tuple = RACEWAY_FILM_RESOLUTIONS) -> dict:
    """The central and minimum film [m] of a raceway's line contact (reduced radius ``radius`` [m], E'
    ``e_prime`` [Pa]) with the Herschel-Bulkley ``grease`` (:class:`lubedyn.lubrication.laws.grease.Grease`:
    Poiseuille flow of tau_y + phi |D|^n, phi = phi0 exp(alpha p)) at the line load ``load`` [N/m] and
    entrainment speed ``speed`` [m/s]: the roller kind's solve (:func:`lubedyn.film_points.ehl_load_response`,
    its film-scaled domain, the solver's Newtonian starts), at the resolutions of
    ``resolutions`` (:data:`RACEWAY_FILM_RESOLUTIONS`) in turn until a solution passes the solver's
    a-posteriori checks.
    Cached per process (the same inputs are solved once; a failure is raised again)."""
    from lubedyn.film_points import (ehl_load_response, ehl_roller_cone_default_params,  # deferred: scikit-fem
                                     ehl_roller_cup_default_params)

    key = (race, float(radius), float(e_prime), float(grease.yield_stress), float(grease.consistency),
           float(grease.exponent), float(grease.pressure_viscosity), float(density), float(load), float(speed),
           tuple(resolutions))
    if key in _RACEWAY_EHL:
        out = _RACEWAY_EHL[key]
        if isinstance(out, Exception):
            raise out
        return dict(out, cached=True)
    base = (ehl_roller_cup_default_params if race == "cup" else ehl_roller_cone_default_params)()
    t0 = time.perf_counter()
    tried = []
    try:
        for resolution in resolutions:
            params = {**base, "radius_x": float(radius), "e_star": 0.5 * float(e_prime),
                      "alpha": float(grease.pressure_viscosity), "rho0": float(density), "coefficients": "linearised",
                      "resolution": resolution, "rheology": "herschel_bulkley",
                      "hb_consistency": float(grease.consistency), "hb_yield_stress": float(grease.yield_stress),
                      "hb_exponent": float(grease.exponent), "hb_creep": 0.0}
            res = ehl_load_response(params, float(load), float(speed))
            sol = res["solution"]
            warnings = list(sol.info.get("warnings", []))
            g = sol.problem.g
            tried.append(f"{g.nx} nodes: h_c {res['Central film thickness [m]'] * 1e6:.4g} um"
                         + (f" ({'; '.join(warnings)})" if warnings else ""))
            if not warnings:
                break
        else:
            raise ConvergenceError(f"no solution passed the solver's checks ({' / '.join(tried)})")
    except ConvergenceError as exc:
        _RACEWAY_EHL[key] = exc
        raise
    out = {"central": float(res["Central film thickness [m]"]), "minimum": float(res["Minimum film thickness [m]"]),
           "grid": (int(g.nx), float(g.x_min), float(g.x_max)), "tried": tried, "seconds": time.perf_counter() - t0,
           "cached": False}
    _RACEWAY_EHL[key] = out
    log.info("raceway film (%s, %.4g N/m, %.4g m/s): grease EHL %.4g um in %.1f s", race, load, speed,
             out["central"] * 1e6, out["seconds"])
    return out


def raceway_films(case, model, qs) -> dict:
    """``lubricant.raceway_film = "grease_ehl"``: per raceway (cup, cone) the grease's EHL central film at the
    most loaded roller's quasi-static load per unit effective length (``qs``: the model's quasi-static
    equilibrium) and the run's ideal entrainment speed (:func:`grease_ehl_film`), Dowson-Toyoda's film there
    with the films' viscosity eta_ref (:meth:`lubedyn.dynamics.tapered.groups.Lubricant.viscosity`) and the
    effective viscosity eta_eff = eta_ref (h_EHL/h_DT(eta_ref))^(1/k), k = 0.69 Dowson-Toyoda's speed exponent
    (H ~ U^0.69; taken from the law itself): the viscosity with which the kernel's formula
    (:func:`lubedyn.dynamics.tapered.kernels.raceway_film`) gives the EHL film at that load.  The summary's
    "Raceway films" (films in um).  A solve that fails is a one-line :class:`InputError` naming
    ``lubricant.raceway_film``, the grease and its temperature."""
    g, lu = model.geometry, model.lubricant
    grease = lu.grease()
    speed = model.entrainment_speed
    eta_ref, alpha, ep = lu.viscosity(), lu.pressure_viscosity, g.e_prime
    # Dowson-Toyoda's exponent of the speed (and so of the viscosity), from the law itself: 0.69
    k = math.log(_dt_film(2.0, 1.0, 1e5, 0.01, alpha, ep) / _dt_film(1.0, 1.0, 1e5, 0.01, alpha, ep)) / math.log(2.0)
    out = {}
    for race, loads in zip(RACES, (qs.cup_loads, qs.cone_loads)):
        w = float(np.max(loads)) / g.effective_length
        radius = float(g.reduced_radius(race))
        try:
            ehl = grease_ehl_film(race, radius, ep, grease, case.lubricant.density.rho0, w, speed)
        except ConvergenceError as exc:
            log.info("lubricant.raceway_film = 'grease_ehl' (%s): %s", race, exc)
            raise InputError(f"lubricant.raceway_film = 'grease_ehl': the EHL line contact of {_grease_name(case)} "
                             f"did not converge on the {race} ({w:.4g} N/m, {speed:.4g} m/s; measured: Table 2's "
                             "lithium, n = 0.31, never converges at paper A's loads); use lubricant.raceway_film = 'formula' (Dowson-Toyoda with the "
                             "films' viscosity) or a grease the solver reaches (polyurea or calcium)") from exc
        h_dt = _dt_film(eta_ref, speed, w, radius, alpha, ep)
        factor = ehl["central"] / h_dt
        eta = eta_ref * factor ** (1.0 / k)
        out[race] = {"Line load [N/m]": w, "Entrainment speed [m/s]": speed, "Reduced radius [m]": radius,
                     "EHL central film [um]": 1e6 * ehl["central"], "EHL minimum film [um]": 1e6 * ehl["minimum"],
                     "Formula film [um]": 1e6 * h_dt, "Factor h_EHL/h_formula [-]": factor,
                     "Reference viscosity [Pa s]": eta_ref, "Effective viscosity [Pa s]": eta,
                     "Formula film at the effective viscosity [um]": 1e6 * _dt_film(eta, speed, w, radius, alpha, ep),
                     "EHL grid (nodes, x_min, x_max) [-, b, b]": list(ehl["grid"]),
                     "EHL resolutions tried": ehl["tried"],
                     "EHL solve wall time [s]": ehl["seconds"]}   # of its first solve in this process
    out["Grease"] = _grease_name(case)
    out["Dowson-Toyoda speed exponent [-]"] = k
    out["Load"] = ("the most loaded roller's quasi-static load per unit effective length, per raceway; the "
                   "effective viscosity is held for every slice and load of the run")
    return out


#: the rib's EHL film maps that flange.rib_film = "ehl" reads, per (grease, temperature [C]) of Table 2: built
#: by the map cases named in them (coupling/film_points/rib.py says where the solver reaches the rib contact:
#: the thin lithium films; the base oil, polyurea and calcium films, 7-300 um thick, are out of its reach)
RIB_FILM_MAPS = {("lithium", 30.0): "maps/ehl_rib_lithium_30C.npz"}
#: the grease parameters a rib map's provenance must match (relative)
RIB_MAP_MATCH = 1e-9


def rib_film_map(lubricant: "LubricantTable"):
    """The shipped rib EHL film map (:data:`RIB_FILM_MAPS`) of the case's grease at its temperature, checked
    against the case's grease (its Table 2 consistency, yield stress and exponent at the temperature, and
    alpha); a grease or temperature without a map is a one-line error naming ``flange.rib_film``."""
    key = (lubricant.grease, float(lubricant.temperature_c))
    shipped = ", ".join(f"{g} at {t:g} C" for g, t in RIB_FILM_MAPS)
    if key not in RIB_FILM_MAPS:
        raise InputError(f"flange.rib_film = 'ehl' has no rib EHL film map for lubricant.grease = {lubricant.grease!r} "
                         f"at temperature_c = {lubricant.temperature_c:g}: shipped {shipped} (the EHL solver does not "
                         "reach the rib's thick base-oil, polyurea and calcium films: coupling/film_points/rib.py); "
                         "or use flange.rib_film = 'hamrock_dowson'")
    fmap = FilmMap.load(CASES_DIR / RIB_FILM_MAPS[key])
    params = fmap.provenance.get("params", {})
    want = lubricant.group_values()
    for name, mine in (("hb_consistency", want["consistency"]), ("hb_yield_stress", want["yield_stress"]),
                       ("hb_exponent", want["exponent"]), ("alpha", want["pressure_viscosity"])):
        theirs = params.get(name)
        if theirs is None or abs(float(theirs) - float(mine)) > RIB_MAP_MATCH * abs(float(mine)):
            raise InputError(f"flange.rib_film = 'ehl': the rib map {RIB_FILM_MAPS[key]} was built with {name} = "
                             f"{theirs!r}, the case's lubricant has {mine!r}")
    return fmap


#: the roller EHL maps that raceway traction "map" reads (cup, cone): built by cases/map_ehl_roller_cup.toml
#: and cases/map_ehl_roller_cone.toml (cases/maps/README.md: axes, lubricant, accuracy)
ROLLER_TRACTION_MAPS = ("maps/ehl_roller_cup.npz", "maps/ehl_roller_cone.npz")


def roller_traction_maps() -> tuple:
    """The shipped roller EHL maps (cup, cone) of :data:`ROLLER_TRACTION_MAPS`, loaded once per process."""
    global _ROLLER_MAPS
    if _ROLLER_MAPS is None:
        _ROLLER_MAPS = tuple(FilmMap.load(CASES_DIR / rel) for rel in ROLLER_TRACTION_MAPS)
    return _ROLLER_MAPS


_ROLLER_MAPS = None


def traction_map_summary(model) -> dict:
    """What the raceway traction "map" read: each map's file, its build's input hash (the ball-ball map's
    convention, ``FilmMap.input_hash``) and the lubricant its films were solved with (the maps' own, not the
    case's grease), and the entrainment speed it was read at."""
    out = {"Raceway traction maps": {}, "Raceway traction map entrainment speed [m/s]": model.entrainment_speed}
    for race, rel, fmap in zip(("cup", "cone"), ROLLER_TRACTION_MAPS, model.traction_maps):
        prm = fmap.provenance.get("params", {})
        out["Raceway traction maps"][race] = {
            "file": rel, "input hash": fmap.input_hash,
            "lubricant": {k: prm.get(k) for k in ("eta0", "alpha", "viscosity_law", "density_law", "eyring_stress",
                                                  "film_shear_modulus", "limiting_shear_stress", "limiting_shear_slope")}}
    return out


def describe(case: TaperedCase, model) -> str:
    op, m, ig = case.operating, case.model, case.integrator
    if ig.method == "rk4":
        step = "RK4 at 0.8 x the stable step" if ig.dt == "auto" else f"RK4 at {ig.dt * 1e6:g} us"
    else:
        step = f"DOPRI5 rtol {ig.rtol:g}"
    return (f"tapered roller bearing, {model.n_rollers} rollers x {model.n_slices} slices, traction {m.traction}, "
            f"pocket {m.pocket}, land {m.guide_land}, flange friction {m.flange_friction}"
            f"{', raceway films from the grease EHL' if case.lubricant.raceway_film == 'grease_ehl' else ''}; "
            f"{op.speed * 30 / math.pi:g} rpm, F_r {op.radial_load:g} N, axial {op.axial}"
            f"{f', cone tilt free (load at {op.load_offset * 1e3:g} mm)' if op.cone_tilt == 'free' else ''}; "
            f"{ig.duration * 1e3:g} ms, {step}")


def ideal_roller_centre(geometry) -> tuple[float, float]:
    """(axial x [m], radial r [m]) of a roller's centre in its meridional plane at the ideal, unloaded
    position: the roller's reference point on the pitch radius, its axis at ``roller_axis_angle``, the
    centre ``uc`` along it (the mass centre of ``roller_mass_properties``), the cone undisplaced --
    where :meth:`TaperedBearing.start_state` puts a roller whose quasi-static displacement and tilt are
    zero."""
    _, _, _, uc = geometry.roller_mass_properties()
    beta = geometry.roller_axis_angle
    return uc * math.cos(beta), geometry.pitch_radius + uc * math.sin(beta)


def displacement_from_ideal(geometry, c) -> tuple[np.ndarray, np.ndarray]:
    """(radial, axial) displacement [m] of roller centres ``c`` (..., 3) (x, y, z) from their ideal,
    unloaded position (:func:`ideal_roller_centre`) at their own azimuth: |c_yz| - r_ideal and
    c_x - x_ideal (paper A's Fig. 5b measures the roller "relative to the initial position", its runs
    starting from the unloaded bearing)."""
    c = np.asarray(c, dtype=float)
    x0, r0 = ideal_roller_centre(geometry)
    return np.hypot(c[..., 1], c[..., 2]) - r0, c[..., 0] - x0


def record(model, Y, y0, qs, fraction):
    """Everything the outputs read from the sampled states: :meth:`TaperedBearing.diagnostics` plus the
    rollers' "Radial displacement [m]" and "Axial displacement [m]" of their centres from the start,
    the same from their ideal, unloaded position ("Radial displacement from the ideal position [m]",
    "Axial ...", :func:`displacement_from_ideal`: what paper A's Fig. 5b plots) and "Loaded zone [-]"
    (True where a roller's cone load exceeds ``fraction`` of the quasi-static start's largest cone
    load)."""
    D = model.diagnostics(Y, y0)
    Z = model.n_rollers
    idx = L.N_CONE + L.NB * np.arange(Z)
    c = np.stack([Y[:, idx + k] for k in range(3)], axis=-1)          # (n, Z, 3)
    c0 = np.stack([y0[idx + k] for k in range(3)], axis=-1)
    D["Radial displacement [m]"] = np.hypot(c[..., 1], c[..., 2]) - np.hypot(c0[:, 1], c0[:, 2])
    D["Axial displacement [m]"] = c[..., 0] - c0[:, 0]
    radial, axial = displacement_from_ideal(model.geometry, c)
    D["Radial displacement from the ideal position [m]"] = radial
    D["Axial displacement from the ideal position [m]"] = axial
    D["Loaded zone [-]"] = D["Cone load [N]"] > fraction * float(np.max(qs.cone_loads))
    return D


#: the headline means: (summary name, window statistic, zone or None for a whole-bearing statistic)
HEADLINE = (("Skew, loaded zone", "Skew [rad]", "loaded zone"), ("Skew, unloaded zone", "Skew [rad]", "unloaded zone"),
            ("Tilt, loaded zone", "Tilt [rad]", "loaded zone"), ("Tilt, unloaded zone", "Tilt [rad]", "unloaded zone"),
            ("Roller slip, loaded zone", "Roller slip [-]", "loaded zone"),
            ("Roller slip, unloaded zone", "Roller slip [-]", "unloaded zone"), ("Cage slip", "Cage slip [-]", None))


def _headline_mean(w: dict, stat: str, zone):
    if stat not in w:
        return None
    return w[stat][zone]["mean"] if zone else w[stat]["mean"]


def converged_summary(model, t, D, width: float, tolerance: float) -> dict | None:
    """The record's last ``width`` [s] against the ``width`` before it: the window statistics of the last
    (:func:`lubedyn.dynamics.analysis.windows.window_summary`) and, per headline mean (:data:`HEADLINE`), its value in both windows, the
    change and the change relative to the last window's magnitude.  "Converged [-]" when every relative
    change is at most ``tolerance`` (a mean that is None in either window, an empty zone, is left out).
    The change is the uncertainty of a mean: how much it still moves from one window to the
    next.  None when the record is shorter than two windows."""
    end = float(t[-1])
    if end - float(t[0]) < 2.0 * width:
        return None
    last = window_summary(model, t, D, end - width, end)
    before = window_summary(model, t, D, end - 2.0 * width, end - width)
    changes, worst = {}, 0.0
    for name, stat, zone in HEADLINE:
        a, b = _headline_mean(last, stat, zone), _headline_mean(before, stat, zone)
        if a is None or b is None:
            continue
        rel = abs(a - b) / abs(a) if a != 0.0 else (0.0 if a == b else math.inf)
        worst = max(worst, rel)
        changes[name] = {"mean": a, "mean in the window before": b, "change": a - b, "relative change [-]": rel}
    last["Window-to-window change"] = changes
    last["Largest relative change [-]"] = worst
    last["Tolerance [-]"] = tolerance
    last["Converged [-]"] = bool(worst <= tolerance)
    return last


def summarise(case, model, t, Y, D, qs) -> dict:
    """The scene's summary (module docstring): the paper's window and the last cage revolution."""
    kin = model.ideal()
    ideal = float(kin["cage speed [rad/s]"])
    s = {"Rollers [-]": model.n_rollers, "Slices per roller [-]": model.n_slices,
         "Fidelity": {**{k: getattr(case.model, k) for k in ("traction", "flange_friction", "pocket", "guide_land",
                                                            "pocket_switch", "traction_evaluation")},
                      "raceway_film": case.lubricant.raceway_film},
         "Integrator": case.integrator.method, "Cone speed [rpm]": model.speed * 30 / math.pi,
         "Simulated time [s]": float(t[-1]), "Samples [-]": int(t.size),
         "Ideal cage speed [rad/s]": ideal, "Ideal cage speed [rpm]": ideal * 30 / math.pi,
         "Ideal roller spin relative to the cage [rad/s]": float(kin["roller spin relative to cage [rad/s]"]),
         "Ideal kinematics": "the model's own geometry: cage omega_i (1 - gamma)/2 (TaperedRollerGeometry.kinematics)",
         "Quasi-static largest cup load [N]": float(np.max(qs.cup_loads)),
         "Quasi-static largest cone load [N]": float(np.max(qs.cone_loads)),
         "Quasi-static largest flange load [N]": float(np.max(qs.flange_loads))}
    if case.model.traction == "map":
        s.update(traction_map_summary(model))
    if case.lubricant.raceway_film == "grease_ehl":   # the build's solves, from the cache
        s["Raceway films (lubricant.raceway_film = 'grease_ehl')"] = raceway_films(case, model, qs)
    lo, hi = case.analysis.window
    if t[-1] >= lo + (t[1] - t[0]):
        s["Paper window (analysis.window)"] = window_summary(model, t, D, lo, min(hi, t[-1]))
    else:
        s["Paper window (analysis.window)"] = (f"not reached: the record ends at {t[-1]:g} s, the window starts "
                                               f"at {lo:g} s")
    period = 2.0 * math.pi / ideal if ideal > 0.0 else math.inf
    if t[-1] >= period:
        s["Last cage revolution"] = window_summary(model, t, D, t[-1] - period, t[-1])
    else:
        s["Record's second half (shorter than a cage revolution)"] = window_summary(model, t, D, 0.5 * t[-1], t[-1])
    conv = converged_summary(model, t, D, case.analysis.converged_window, case.analysis.converged_tolerance)
    if conv is not None:
        s["Converged window"] = conv
    # the headline means as top-level keys (what `lubedyn study` tabulates), from main_window, and from
    # the converged window with their window-to-window change
    _, key, w = main_window(s)
    s["Averaged over"] = f"{key}: {w['Window [s]'][0]:.4g}-{w['Window [s]'][1]:.4g} s"
    for name, stat, zone in HEADLINE:
        unit = stat.rpartition(" ")[2]
        if stat in w:
            s[f"{name}, mean {unit}"] = _headline_mean(w, stat, zone)
        # None when the record is shorter than two converged windows or the zone is empty
        c = conv["Window-to-window change"].get(name, {}) if conv is not None else {}
        s[f"{name}, converged mean {unit}"] = c.get("mean")
        s[f"{name}, window-to-window change {unit}"] = c.get("change")
    s["Converged window, converged [-]"] = None if conv is None else conv["Converged [-]"]
    if model.tilt_free:
        i_x, i_t = model.cone_inertia()
        s["Cone tilt"] = "free"
        s["Load offset [m]"] = model.operating.load_offset
        s["Cone polar and transverse moments of inertia [kg m^2]"] = [i_x, i_t]
        s["Cone inertia"] = ("assumed: a steel annulus of model.cone_mass over the cone's width, outer radius the "
                             "cone raceway's (TaperedBearing.cone_inertia)")
        k = model.tilt_index
        for j, ax in enumerate("yz"):
            s[f"Quasi-static cone tilt {ax} [rad]"] = float(qs.cone_tilt[j])
            s[f"Start cone tilt {ax} [rad]"] = float(Y[0, k + j])
            s[f"Cone tilt {ax}, mean [rad]"] = w[f"Cone tilt {ax} [rad]"]["mean"]
            s[f"Cone tilt {ax}, amplitude [rad]"] = w[f"Cone tilt {ax} [rad]"]["amplitude"]
    s["Skew amplitude, loaded zone [rad]"] = w["Skew [rad]"]["loaded zone"]["amplitude"]
    s["Skew periodicity [-]"] = w.get("Skew periodicity [-]")
    end = {"Largest cup load [N]": "Cup load [N]", "Largest cone load [N]": "Cone load [N]",
           "Largest flange load [N]": "Flange load [N]", "Largest pocket load [N]": "Pocket load [N]"}
    for k, key in end.items():
        s[k] = float(np.max(D[key]))
    s["Largest cup load at the end [N]"] = float(np.max(D["Cup load [N]"][-1]))
    s["Cone centre excursion, largest [m]"] = float(np.max(np.hypot(Y[:, 1] - Y[0, 1], Y[:, 2] - Y[0, 2])))
    if "Guide land load [N]" in D:
        s["Largest guide land load [N]"] = float(np.max(D["Guide land load [N]"]))
        s["Largest side beam load [N]"] = float(np.max(D["Side beam load [N]"]))
        s["Cage axial excursion, largest [m]"] = float(np.max(np.abs(Y[:, L.N_CONE + L.NB * model.n_rollers]
                                                                     - Y[0, L.N_CONE + L.NB * model.n_rollers])))
    return s


@dataclass
class TaperedRun(BearingResult):
    """A tapered roller bearing run (:class:`lubedyn.results.BearingResult`: ``res["Cage speed [rad/s]"]``,
    ``res.to_xarray()``) and the kernel's per-roller diagnostics over the samples."""

    diagnostics: dict = field(default_factory=dict)


#: the summary's averaging windows, in order of preference: (short name, summary key)
WINDOWS = (("paper window", "Paper window (analysis.window)"), ("last cage revolution", "Last cage revolution"),
           ("second half", "Record's second half (shorter than a cage revolution)"))


def main_window(s: dict) -> tuple[str, str, dict]:
    """(short name, summary key, statistics) of the window a summary's headline numbers come from: the
    paper's window when the record reaches it, else the last cage revolution, else the record's second
    half."""
    for name, key in WINDOWS:
        if isinstance(s.get(key), dict):
            return name, key, s[key]
    raise KeyError("no averaging window in the summary")


def headline(s: dict) -> list[str]:
    lines = []
    for k in ("Simulated time [s]", "Ideal cage speed [rpm]", "Largest cup load [N]", "RK4 step [s]",
              "Accepted steps [-]", "Integration wall time [s]"):
        if k in s:
            lines.append(f"{k:<44} {s[k]:.6g}" if isinstance(s[k], float) else f"{k:<44} {s[k]}")
    name, _, w = main_window(s)
    lines.append(f"Averaged over the {name}: {w['Window [s]'][0]:.4g}-{w['Window [s]'][1]:.4g} s")
    for k, unit in (("Tilt [rad]", "rad"), ("Skew [rad]", "rad"), ("Roller slip [-]", "-")):
        v = w[k]["loaded zone"]["mean"]
        if v is not None:
            label = f"  {k.rpartition(' [')[0]}, loaded zone, mean [{unit}]"
            lines.append(f"{label:<44} {v:.6g}")
    if "Cage speed, mean [rpm]" in w:
        lines.append(f"{'  Cage speed, mean [rpm]':<44} {w['Cage speed, mean [rpm]']:.6g}")
    c = s.get("Converged window")
    if isinstance(c, dict):
        verdict = "converged" if c["Converged [-]"] else "NOT converged"
        lines.append(f"Converged window {c['Window [s]'][0]:.4g}-{c['Window [s]'][1]:.4g} s: {verdict} (headline means "
                     f"moved by up to {100 * c['Largest relative change [-]']:.3g} % from the window before; "
                     f"tolerance {100 * c['Tolerance [-]']:.3g} %)")
    return lines


def kernel_jobs(case: TaperedCase) -> list:
    """``[(kernel, example arguments)]`` of the bound kernels a run of ``case`` calls (the integrator, the
    forces at the samples): they do not contain the model's code, so a first run compiles them in a second
    process while it compiles the model (:func:`lubedyn.dynamics.specialise.compile_in_background`)."""
    # only the argument types count here: they are the same for every case (TaperedBearing.args;
    # tests/test_specialise.py checks the jobs' signatures against a run's), and the real arguments cost
    # 35-95 ms (traction tables), which the run builds anyway on its quasi-static state
    args = L.example_args()
    return [kernel_example(case.integrator.method, K.rhs, args), K.forces_many_example(args)]


def run(case: TaperedCase, out_dir=None, *, name: str = "tapered", source: str = "", smoke: bool = False) -> TaperedRun:
    """Build, integrate, analyse and (with ``out_dir``) write the case through the bearing run driver
    (:func:`lubedyn.scenes.bearing_run.drive`, :class:`TaperedRunModel`)."""
    return drive(TaperedRunModel(case), out_dir, name=name, source=source, smoke=smoke)


class TaperedRunModel:
    """The tapered roller bearing's side of :func:`lubedyn.scenes.bearing_run.drive`: its model, quasi-static
    start and integrator options, summary (:func:`summarise`) and files (time series, ``.vtu`` frames,
    figures)."""

    def __init__(self, case: TaperedCase):
        self.case = case

    def build(self) -> None:
        self.model = build(self.case)
        # a first run compiles the integrator kernel in a second process meanwhile (lubedyn.dynamics.specialise)

        compile_in_background(kernel_jobs(self.case))
        self.qs = self.model.quasi_static()
        # the kernel arguments on the same equilibrium (the rib film reads it): solved once
        self.args = self.model.args(self.qs)
        self.y0 = self.model.start_state(self.qs)

    def describe(self) -> str:
        return describe(self.case, self.model)

    def integration(self):
        ig = self.case.integrator
        t_out = np.arange(0.0, ig.duration * (1 + 1e-12), ig.sample_interval)
        kw = dict(method="dopri5", rtol=ig.rtol, atol=ig.atol)
        self.dt = self.stable = None
        if ig.method == "rk4":
            self.stable = self.model.stable_step(self.qs, self.y0, self.args)
            self.dt = 0.8 * self.stable if ig.dt == "auto" else ig.dt
            if ig.duration / self.dt > ig.max_steps:  # fixed steps: the budget is known before the first one
                raise InputError(f"integrator.dt = {self.dt:g} s: {ig.duration / self.dt:.3g} fixed RK4 steps over "
                                 f"integrator.duration = {ig.duration:g} s, more than integrator.max_steps = "
                                 f"{ig.max_steps}; use a larger step or a shorter duration, or raise "
                                 "integrator.max_steps")
            # the integrator refuses a step beyond the limit on the imaginary axis; the estimate folds the
            # traction's real-axis decay into an equivalent omega
            kw = dict(method="rk4", dt=self.dt, omega_max=2.0 * math.sqrt(2.0) / self.stable)
        return Integration(K.rhs, self.y0, t_out, self.args, dict(max_steps=ig.max_steps, **kw), n_chunks=100,
                           on_error=self._error)

    def _error(self, exc):
        if isinstance(exc, DynamicsInputError):
            return InputError(f"integrator.dt = {self.dt:g} s: {exc}")
        ig = self.case.integrator
        what = f"integrator.dt = {self.dt:g} s" if ig.method == "rk4" else f"integrator.rtol = {ig.rtol:g}"
        return ConvergenceError(f"{exc} ({what})")

    def analyse(self, res, timing) -> dict:
        self.t, self.y = res.t, res.y
        self.D = record(self.model, res.y, self.y0, self.qs, self.case.analysis.loaded_zone_fraction)
        scene = summarise(self.case, self.model, res.t, res.y, self.D, self.qs)
        scene.update(res.stats)
        scene["Integration wall time [s]"] = timing.integration
        if self.case.integrator.method == "rk4":
            scene["RK4 stable step estimate [s]"] = self.stable
            scene["RK4 step bound [s]"] = self.dt
            # the integrator cuts each sample interval into ceil(interval/bound) equal steps
            # (lubedyn.dynamics.integrators): the step it takes is interval/n, up to the bound
            interval = self.case.integrator.sample_interval
            scene["RK4 step [s]"] = interval / max(1, math.ceil(interval / self.dt * (1.0 - 1e-12)))
        return scene

    def _frames(self):
        t, D = self.t, self.D
        picks = np.unique(np.linspace(0, len(t) - 1, min(self.case.analysis.frames, len(t))).round().astype(int))
        for i in picks:
            yield float(t[i]), frame_mesh(self.model, self.y[i], {key: D[key][i] for key in FRAME_FIELDS})

    def files(self, summary: dict, timing):
        return outputs.RunFiles(
            t=self.t, columns=lambda: _columns(self.model, self.y, self.D),
            meta=lambda full: {"Case": summary["Case"], "Scene": "tapered"},
            frames=self._frames, frame_ext="vtu",
            figures=lambda: ((name, draw()) for name, draw in self.drawings().items()))

    def drawings(self) -> dict:
        return drawings(self.model, self.t, self.y, self.D, self.qs)

    def result(self, summary: dict, files: list) -> TaperedRun:
        return TaperedRun(summary=summary, files=files, t=self.t, y=self.y, diagnostics=self.D,
                          drawings=self.drawings())


PER_ROLLER = ("Tilt [rad]", "Skew [rad]", "Orbital speed [rad/s]", "Spin speed [rad/s]", "Roller slip [-]",
              "Spin slip [-]", "Radial displacement [m]", "Axial displacement [m]",
              "Radial displacement from the ideal position [m]", "Axial displacement from the ideal position [m]",
              "Loaded zone [-]",
              "Cup load [N]", "Cone load [N]", "Flange load [N]", "Pocket load [N]", "Cup traction [N]",
              "Cone traction [N]", "Flange friction [N]", "Pocket friction [N]")
FRAME_FIELDS = ("Cup load [N]", "Cone load [N]", "Flange load [N]", "Pocket load [N]", "Tilt [rad]", "Skew [rad]",
                "Roller slip [-]", "Loaded zone [-]")


def _columns(model, Y, D) -> dict:
    """The time series' columns: every state, then per roller the :data:`PER_ROLLER` diagnostics and its
    slice loads, then the cage's."""
    cols = {n: Y[:, i] for i, n in enumerate(model.state_names())}
    for j in range(model.n_rollers):
        for key in PER_ROLLER:
            name, _, unit = key.rpartition(" [")
            cols[f"Roller {j} {name[0].lower()}{name[1:]} [{unit}"] = D[key][:, j].astype(float)
        for r, race in enumerate(("cup", "cone")):
            for k in range(model.n_slices):
                cols[f"Roller {j} {race} slice {k} load [N]"] = D["Slice loads [N]"][:, j, r, k]
    if "Cage speed [rad/s]" in D:
        cols["Cage speed [rad/s]"] = D["Cage speed [rad/s]"]
        cols["Cage slip [-]"] = D["Cage slip [-]"]
        cols["Cage centre from the cone's, y [m]"] = D["Cage centre [m]"][:, 0]
        cols["Cage centre from the cone's, z [m]"] = D["Cage centre [m]"][:, 1]
        cols["Guide land load [N]"] = D["Guide land load [N]"]
    for k, ax in enumerate("xyz"):
        cols[f"Force of rollers and cage on the cone, {ax} [N]"] = D["Cone force [N]"][:, k]
    if "Cone moment [N m]" in D:
        for k, ax in enumerate("yz"):
            cols[f"Moment of rollers and cage on the cone, {ax} [N m]"] = D["Cone moment [N m]"][:, k + 1]
    return cols


def frame_mesh(model, y, fields: dict, n_around: int = 16, n_along: int = 7):
    """One ParaView frame (pyvista UnstructuredGrid): the cup's and the cone's raceway surfaces (the cone
    moved by its displacement; both surfaces of revolution, so the cone's spin does not show), each roller
    as its crowned frustum placed by its centre and quaternion, and the cage as a ring at its centre.  Cell
    data "Body [-]" (0 cup, 1 cone, 2.. rollers, last the cage); point data per roller from ``fields``
    (arrays over rollers: loads, tilt, skew, slip, loaded zone; 0 on rings and cage)."""
    import pyvista as pv
    from scipy.spatial.transform import Rotation

    g = model.geometry
    l = g.effective_length
    u = np.linspace(-0.5 * l, 0.5 * l, n_along)
    t = np.linspace(0.0, 2.0 * np.pi, n_around + 1)
    _, _, _, uc = g.roller_mass_properties()
    blocks = []

    def grid(pts, body, values):
        return body_grid(pts, body, {k: float(v) for k, v in values.items()})

    zero = {k: 0.0 for k in fields}
    psi = np.linspace(0.0, 2.0 * np.pi, 4 * n_around + 1)
    for body, which, shift in ((0, "cup", (0.0, 0.0, 0.0)), (1, "cone", y[0:3])):
        pts = raceway_surface(g, which, u, psi.size)
        if which == "cone" and model.tilt_free:      # tilted about the cone's reference point
            k = model.tilt_index
            pts = Rotation.from_rotvec([0.0, y[k], y[k + 1]]).apply(pts.reshape(-1, 3)).reshape(pts.shape)
        blocks.append(grid(pts + np.asarray(shift, dtype=float), body, zero))
    rho = np.asarray(g.roller_radius(u), dtype=float)
    U, T = np.meshgrid(u - uc, t, indexing="ij")
    RHO, _ = np.meshgrid(rho, t, indexing="ij")
    body_pts = np.stack([U, RHO * np.cos(T), RHO * np.sin(T)], axis=-1).reshape(-1, 3)
    for j in range(model.n_rollers):
        b = L.N_CONE + j * L.NB
        pts = Rotation.from_quat(to_scipy(y[b + 3:b + 7])).apply(body_pts) + y[b:b + 3]
        blocks.append(grid(pts.reshape(U.shape + (3,)), 2 + j, {k: v[j] for k, v in fields.items()}))
    if model.has_cage:
        b = L.N_CONE + L.NB * model.n_rollers
        ro, ri, h = 0.5 * g.cage_outer_diameter, 0.5 * g.cage_inner_diameter, g.cage_thickness
        Rr, P = np.meshgrid([ri, ro], psi, indexing="ij")
        pts = np.stack([np.full_like(Rr, 0.0), Rr * np.cos(P), Rr * np.sin(P)], axis=-1).reshape(-1, 3)
        pts = Rotation.from_quat(to_scipy(y[b + 3:b + 7])).apply(pts) + y[b:b + 3]
        blocks.append(grid(pts.reshape(Rr.shape + (3,)), 2 + model.n_rollers, zero))
    return pv.merge(blocks, merge_points=False)


def drawings(model, t, Y, D, qs) -> dict:
    """The run's figures, ``{file name: draw}``, ``draw(into=None)`` making the figure (a new bare matplotlib
    Figure, laid out tight, or in ``into``: a Figure, SubFigure or, for one panel, an Axes;
    :func:`lubedyn.outputs.panels`) and returning it: what ``lubedyn run`` writes and ``res.plot(kind)``
    draws."""
    from matplotlib.patches import Circle

    ms = t * 1e3

    def new(into, nrows, ncols, figsize):
        return outputs.panels(into, nrows, ncols, figsize=figsize, pyplot=False)

    def done(fig, into):
        if into is None:  # the caller's figure keeps its own layout
            fig.tight_layout()
        return fig

    def shade(ax, j=0):
        z = D["Loaded zone [-]"][:, j]
        edges = np.flatnonzero(np.diff(np.concatenate([[0], z.astype(int), [0]])))
        for a, b in zip(edges[::2], edges[1::2]):
            ax.axvspan(ms[a], ms[min(b, len(ms) - 1)], color="0.9", lw=0)

    def roller_attitude(into=None):
        fig, axes = new(into, 1, 2, (10, 4))
        for ax, key in zip(axes, ("Tilt [rad]", "Skew [rad]")):
            shade(ax)
            ax.plot(ms, D[key][:, 0], label="roller 0 (grey: in the loaded zone)")
            ax.plot(ms, np.mean(D[key], axis=1), "k", lw=0.8, label="mean of all rollers")
            ax.set_xlabel("time [ms]")
            ax.set_ylabel(key.lower().replace("[", "from the start ["))
            ax.legend(fontsize=8)
        return done(fig, into)

    def roller_displacement(into=None):
        fig, axes = new(into, 1, 2, (10, 4))
        for ax, key in zip(axes, ("Radial displacement [m]", "Axial displacement [m]")):
            shade(ax)
            ax.plot(ms, D[key][:, 0] * 1e6, label="roller 0")
            ax.set_xlabel("time [ms]")
            ax.set_ylabel(key.replace("[m]", "[um]").lower())
            ax.legend(fontsize=8)
        return done(fig, into)

    def slip(into=None):
        fig, ax = new(into, 1, 1, (6.4, 4.2))
        shade(ax)
        ax.plot(ms, 100 * D["Roller slip [-]"][:, 0], label="roller 0")
        ax.plot(ms, 100 * np.mean(D["Roller slip [-]"], axis=1), "k", lw=0.8, label="mean of all rollers")
        if "Cage slip [-]" in D:
            ax.plot(ms, 100 * D["Cage slip [-]"], label="cage")
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("slip [%] (eq. 52, against the ideal cage speed)")
        ax.legend(fontsize=8)
        return done(fig, into)

    def cage_whirl(into=None):
        fig, ax = new(into, 1, 1, (5, 5))
        if "Cage centre [m]" in D:
            ax.plot(D["Cage centre [m]"][:, 0] * 1e6, D["Cage centre [m]"][:, 1] * 1e6, lw=0.8)
            c = 0.5 * model.geometry.guide_land_clearance * 1e6
            ax.add_patch(Circle((0, 0), c, fill=False, ls="--", label="land clearance"))
            ax.legend(fontsize=8)
        ax.set_xlabel("cage centre from the cone's, y [um]")
        ax.set_ylabel("z [um]")
        ax.set_aspect("equal", "datalim")
        ax.locator_params(nbins=4)  # a square of 5 inches: more labels of -0.025 overlap
        return done(fig, into)

    def cone_orbit(into=None):
        fig, ax = new(into, 1, 1, (5, 5))
        ax.plot((Y[:, 1] - Y[0, 1]) * 1e6, (Y[:, 2] - Y[0, 2]) * 1e6, lw=0.8)
        ax.set_xlabel("cone centre from its start, y [um]")
        ax.set_ylabel("z [um]")
        ax.set_aspect("equal", "datalim")
        ax.locator_params(nbins=4)  # a square of 5 inches: more labels of -0.025 overlap
        return done(fig, into)

    def slice_loads(into=None):
        fig, axes = new(into, 1, 2, (10, 4))
        j = int(np.argmax(qs.cup_loads))
        u = np.asarray(model.geometry.slices(model.n_slices)[0]) * 1e3
        for r, (ax, race) in enumerate(zip(axes, ("cup", "cone"))):
            ax.plot(u, D["Slice loads [N]"][-1, j, r], "o-", label=f"roller {j}, end of run")
            ax.plot(u, np.max(D["Slice loads [N]"][:, j, r], axis=0), ":", label="largest over the run")
            ax.set_xlabel("slice position along the roller [mm]")
            ax.set_ylabel(f"{race} slice load [N]")
            ax.legend(fontsize=8)
        return done(fig, into)

    return {"roller_attitude.png": roller_attitude, "roller_displacement.png": roller_displacement,
            "slip.png": slip, "cage_whirl.png": cage_whirl, "cone_orbit.png": cone_orbit,
            "slice_loads.png": slice_loads}
