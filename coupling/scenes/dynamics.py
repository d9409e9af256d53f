"""Dynamics scene: the cage-less 6206 ball bearing of paper B in the time domain.

``scene = "dynamics"``.  A case describes the bearing (defaults: paper B,
Tables 1, 2 and 4), its functional slots, the operating scenario (rotor drop
or steady inner-ring speed), the fidelity of each interaction (degrees of
freedom of the balls, Hertz constants exact or Hamrock-Brewe, the ball-ball
film: none / closed form / tabulated map), the integrator and the analyses.
``run(case, out_dir)`` builds :class:`lubedyn.dynamics.cageless.CagelessBearing`,
integrates from its quasi-static initial state with
:func:`lubedyn.dynamics.integrators.integrate` (a progress bar of simulated time on
a terminal) and writes

- ``timeseries.nc`` (``output.timeseries_format = "npz"``: ``timeseries.npz``): every state entry and
  the contact diagnostics at every sample, names with units (:func:`lubedyn.outputs.read_timeseries`);
- ``collisions.csv``: one line per ball-ball collision (pair, time of the
  force peak, position, force components, duration);
- ``bearing.pvd`` + ``frames/*.vtp``: balls, rings, slots and the ball-ball
  film pressure (rigid squeeze-film profile p = 3 eta v R_eff / h^2 while
  the film carries the load, Hertz ellipse p0 sqrt(1 - r^2/a^2) once the
  solids touch) for ParaView;
- PNG plots: ball trajectories (x, y, z), collision-force needles by
  direction (paper B, figure 5), phase portraits (fixed frame, and the frame
  turning with the ball train, where the orbit is removed), inner-ring
  acceleration spectrum with the bearing frequencies marked (a record too
  short after ``analysis.transient`` says so on the figure); the figures use
  matplotlib's constrained layout, long titles wrapped
  (tests/test_figure_layout.py checks that no text leaves a figure);
- ``summary.json``: Lyapunov exponents: per direction of ball
  ``analysis.ball`` (inertial x, y, z and co-rotating radial, tangential,
  axial) from each coordinate's time series by Wolf et al.'s
  fixed-evolution-time algorithm in bits/s and 1/s, and for x, y, z by
  Rosenstein's in 1/s and per shaft revolution; the whole system's by
  Benettin's (Gram-Schmidt) in 1/s, and with ``analysis.tangent_directions`` the per-direction
  exponents of Benettin's first tangent vector projected on the balls' radial, tangential and axial
  directions (1/s and bits/s, lambda T, the vector's share per direction); each with its uncertainty and a verdict
  ("positive" beyond two uncertainties, "not positive", or for Wolf's "not
  resolved"), after the detected end of the start-up transient, and only on a record that resolves an
  exponent (:class:`lubedyn.scenes.dynamics_lyapunov.RecordNeed`; else "not computed: ... needs ...",
  unless ``analysis.force``); collision
  counts and largest forces by direction, ball and inner-ring slip,
  integrator statistics, timings.

Paper B's Table 3 ("maximum Lyapunov exponent" in X, Y, Z, no units) was
computed by "the orthogonalization method" citing Wolf et al. with a log2
formula; the paper does not say which coordinates or how a tangent-space
method gives one exponent per coordinate, so the summary gives the
time-series reading (Wolf's algorithm, bits/s, see
:func:`_lyapunov_per_direction`) beside the whole-system spectrum.

Everything is computed before anything is written; the files are staged and
moved into place together (:func:`lubedyn.outputs.staged`).
"""
from __future__ import annotations

import logging
import math
import os
import sys
import textwrap
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from lubedyn.dynamics.integrators import ATOL_MAX, ATOL_WHY, RTOL_MAX, RTOL_WHY
from lubedyn.lubrication.errors import ConvergenceError, InputError
from lubedyn.lubrication.laws import bearing as bearings
from lubedyn.lubrication.laws.collision import ENTRAPPED_DAMPING

from lubedyn import outputs
from lubedyn.scenes.dynamics_lyapunov import (_benettin, _lyapunov_per_direction, benettin_need, benettin_not_computed,
                                              forced, record_need)
from lubedyn.config import (CASES_DIR, BoundsModel, LimitsModel, LubricantModel, PositiveInt, PositiveLength, Q,
                            CaseTable, TimeSeriesOutput, refuse_renamed, rule)
from lubedyn import limits
from lubedyn.results import BearingResult
from lubedyn.dynamics.analysis import collision_events, collision_summary
from lubedyn.dynamics.analysis.frequency import spectrum_limit
from lubedyn.dynamics.analysis.motion import run_columns
from lubedyn.dynamics.cageless import CagelessBearing, DIAG_NAMES, D_BBN, D_BBX, D_BBY, D_BBZ, D_H, D_PSIDOT, D_QI, D_QO, D_SPIN, N_RING_DIAG, forces_many, rhs
from lubedyn.dynamics.cageless.kernels import forces_example, forces_many_example
from lubedyn.dynamics.errors import DynamicsInputError
from lubedyn.dynamics.integrators import kernel_example
from lubedyn.dynamics.lyapunov import spectrum_kernel_example
from lubedyn.dynamics.specialise import compile_in_background
from lubedyn.dynamics.spectra import amplitude_spectrum, bearing_frequencies as bf
from lubedyn.lubrication.laws.contact import point_contact
from lubedyn.maps import FilmMap
from lubedyn.papers.zhang2024 import figures as paper_b_figures
from lubedyn.scenes.bearing_run import Integration, drive

log = logging.getLogger(__name__)

FIELD_FILES = (("timeseries.nc", "timeseries"), ("collisions.csv", "timeseries"), ("bearing.pvd", "pvd"),
               ("trajectories.png", "png"), ("collision_needles.png", "png"), ("phase_portraits.png", "png"),
               ("spectrum.png", "png"), ("angular_displacement.png", "png"), ("collision_map.png", "png"),
               ("poincare.png", "png"))

Force = Q("force", ge=0)
PositiveTime = Q("time", gt=0)


# ---------------------------------------------------------------------------- case model
class BearingTable(CaseTable):
    """Geometry, materials and masses.  No paper data as defaults: a case names its parameter set
    (``parameters = "Zhang2024"``, :mod:`lubedyn.papers`) or gives every value."""

    n_balls: PositiveInt
    ball_diameter: PositiveLength
    pitch_diameter: PositiveLength
    inner_groove_radius: PositiveLength
    outer_groove_radius: PositiveLength
    diametral_clearance: Q("length", ge=0) = 0.0
    ball_modulus: Q("pressure", gt=0)
    ball_poisson: Q("dimensionless", gt=-1, lt=0.5)
    ring_modulus: Q("pressure", gt=0)
    ring_poisson: Q("dimensionless", gt=-1, lt=0.5)
    ball_density: Q("density", gt=0) = 7850.0
    ball_mass: Q("mass", gt=0) | None = None
    ring_mass: Q("mass", gt=0)
    ring_inertia: Q("moment of inertia", gt=0)
    rotor_inertia: Q("moment of inertia", gt=0)
    # the rings' outer diameter and bore (6206 catalogue: 62 mm, 30 mm): they bound the slot depth
    outer_diameter: PositiveLength
    bore: PositiveLength

    @model_validator(mode="after")
    def _geometry(self):
        """In this order, so that each message names the key that is wrong: the ball inside the pitch
        circle, grooves wider than the ball, a clearance in the model's range (-0.05 B D, 4 B D),
        rings around the races."""
        D, dm = self.ball_diameter, self.pitch_diameter
        if not D < dm:
            raise rule("ball_diameter", D, f"must be < pitch_diameter = {dm:g} m")
        for key in ("inner_groove_radius", "outer_groove_radius"):
            if not getattr(self, key) > 0.5 * D:
                raise rule(key, getattr(self, key), f"must be > ball_diameter/2 = {0.5 * D:g} m (the groove must "
                           "be wider than the ball: conformity r/D > 0.5)")
        bd = self.inner_groove_radius + self.outer_groove_radius - D
        if not -0.05 * bd < self.diametral_clearance < 4.0 * bd:
            raise rule("diametral_clearance", self.diametral_clearance, f"must be in ({-0.05 * bd:g}, {4 * bd:g}) m, "
                       f"i.e. (-0.05 B D, 4 B D) with B D = inner_groove_radius + outer_groove_radius - "
                       f"ball_diameter = {bd:g} m (negative: interference, i.e. preload)")
        if not self.outer_diameter > dm + D:
            raise rule("outer_diameter", self.outer_diameter, f"must be > pitch_diameter + ball_diameter = "
                       f"{dm + D:g} m (the outer race)")
        if not self.bore < dm - D:
            raise rule("bore", self.bore, f"must be < pitch_diameter - ball_diameter = {dm - D:g} m (the inner race)")
        return self

    def ring_wall(self, race: str) -> float:
        """Thickness [m] of a ring under its groove bottom."""
        D, dm = self.ball_diameter, self.pitch_diameter
        return 0.5 * (self.outer_diameter - dm - D) if race == "outer" else 0.5 * (dm - D - self.bore)

    def race_radius(self, race: str) -> float:
        """Radius [m] of a race's groove bottom."""
        return 0.5 * (self.pitch_diameter + (self.ball_diameter if race == "outer" else -self.ball_diameter))


class SlotsTable(CaseTable):
    """Local functional slots (paper B: :mod:`lubedyn.papers.zhang2024.parameters`).  ``azimuths = []``: no slot."""

    race: Literal["outer", "inner"]
    azimuths: list[Q("angle")]
    width: PositiveLength
    length: PositiveLength
    depth: PositiveLength
    edge_radius: PositiveLength = 2e-4


class InitialTable(CaseTable):
    """Where a run starts, for ensembles (:class:`lubedyn.dynamics.cageless.groups.Initial`): ``azimuths`` (one angle
    per ball; empty: evenly spaced from ``first_ball_azimuth``), a seeded random ``jitter`` of each ball's
    azimuth (uniform in +-jitter) and a ``kick`` of the inner ring's velocity in a random x-y direction.
    The same ``seed`` gives the same run bit for bit."""

    first_ball_azimuth: Q("angle") = math.radians(270.0)
    azimuths: list[Q("angle")] = Field(default_factory=list)
    jitter: Q("angle", ge=0) = 0.0
    kick: Q("velocity", ge=0) = 0.0
    seed: Annotated[int, Field(strict=True, ge=0)] = 0


class OperatingTable(CaseTable):
    """``scenario``: "drop" (the rotor spinning at ``speed`` lands on the inner
    ring and drags it up to speed by friction), "steady" (inner ring driven at
    ``speed``) or "free" (no rotor)."""

    scenario: Literal["drop", "steady", "free"] = "drop"
    speed: Q("angular velocity", gt=0)
    radial_load: Force
    axial_load: Force
    gravity: Q("acceleration", ge=0) = 9.81
    drop_speed: Q("velocity", ge=0) = 0.0
    rotor_friction: Q("dimensionless", ge=0) = 0.1
    rotor_contact_radius: PositiveLength = 15e-3


class ModelTable(CaseTable):
    """Fidelity of the bearing model."""

    dof: Literal["6dof", "planar"] = "6dof"
    hertz: Literal["exact", "hamrock_brewe"] = "exact"
    ball_ball: bool = True
    race_damping: Q("dimensionless", ge=0) = 0.2
    yield_stress: Q("pressure", gt=0) | None = 1.7e9
    traction_limit: Q("dimensionless", ge=0) = 0.07
    traction_srr: Q("dimensionless", gt=0) = 0.02
    # "map": the traction coefficient of the race contacts from the EHL maps (inner, outer race),
    # paths relative to the case file or to cases/
    traction: Literal["closed_form", "map"] = "closed_form"
    traction_maps: list[str] = Field(default_factory=lambda: ["maps/ehl_ball_inner_race.npz",
                                                              "maps/ehl_ball_outer_race.npz"],
                                     min_length=2, max_length=2)


class FilmsTable(CaseTable):
    """The oil film between neighbouring balls: "none", "closed_form" (rigid
    isoviscous squeeze film in series with Hertz) or "map" (a FilmMap file of
    kind ball_ball, path relative to the case file or to cases/).  The oil itself is the case's
    ``[lubricant]`` table (:class:`lubedyn.config.LubricantModel`: ``lubricant.viscosity.eta0`` and
    Barus' ``alpha``), as in every scene."""

    ball_ball: Literal["none", "closed_form", "map"] = "closed_form"
    map: str | None = None
    race: Literal["none", "closed_form"] = "none"  # EHL films on the ball-race contacts (Hamrock-Dowson)
    rupture_thickness: PositiveLength = 1e-7
    friction_film: Q("dimensionless", ge=0) = 0.03
    friction_boundary: Q("dimensionless", ge=0) = 0.1
    # "paper": paper B eqs. 17-21 (Barus shear limited by friction_film, asperity share of eq. 19)
    friction_law: Literal["exponential_share", "paper"] = "exponential_share"
    asperity_slope: Q("dimensionless", gt=0) = 0.02  # sigma_theta of eq. 19 (assumed: not in paper B)
    # beta of the map film's locked-state damping beta C0 v/h_L (0: the undamped lock), calibrated on the
    # transient EHL impact (lubedyn.lubrication.laws.collision.ENTRAPPED_DAMPING)
    entrapped_damping: Q("dimensionless", ge=0, lt=100) = ENTRAPPED_DAMPING

    @model_validator(mode="after")
    def _map_given(self):
        if self.ball_ball == "map" and not self.map:
            raise rule("map", None, "is required when ball_ball = 'map' (a .npz written by a map case)")
        return self


class IntegratorTable(CaseTable):
    """``rtol`` and ``atol``: DOPRI5's tolerances, refused where its error control means nothing
    (:data:`lubedyn.dynamics.integrators.RTOL_MAX` = 1e-3, ``ATOL_MAX`` = 1e-8: the measurement is there)."""

    method: Literal["dopri5", "rk4"] = "dopri5"
    rtol: Q("dimensionless", gt=0, le=RTOL_MAX, why=RTOL_WHY) = 1e-6
    atol: Q("dimensionless", gt=0, le=ATOL_MAX, why=ATOL_WHY) = 1e-9
    dt: PositiveTime | None = None
    duration: PositiveTime = 0.02
    sample_interval: PositiveTime = 2e-6
    max_steps: PositiveInt = 50_000_000

    @model_validator(mode="after")
    def _rk4_step(self):
        if self.method == "rk4" and self.dt is None:
            raise rule("dt", None, "is required with method = 'rk4' (a fixed step, e.g. '0.2 us')")
        if self.sample_interval > self.duration:
            raise rule("sample_interval", self.sample_interval, f"must be <= duration = {self.duration:g} s")
        return self


class AnalysisTable(CaseTable):
    lyapunov: bool = True  # largest exponent per direction of ball `ball` (Wolf et al. in bits/s; Rosenstein)
    lyapunov_exponents: Annotated[int, Field(strict=True, ge=0, le=20)] = 3  # whole system, Benettin; 0: off
    # (the rule: lubedyn.scenes.dynamics_lyapunov.RecordNeed, docs/atlas/lyapunov.md)
    force: bool = False  # true: compute the Lyapunov estimators (per direction, whole system, tangent directions) also on a record too short to resolve an exponent (lambda T < 15: lambda = 54 1/s measured at 10,000 rpm, scaled with the speed; 0.28 s after the window start at 10,000 rpm); false: such a run writes "not computed: the record of ... resolves no exponent; needs ..." instead of numbers
    # per-direction exponents from Benettin's first tangent vector, projected on every ball's radial, tangential
    # and axial directions (lubedyn.dynamics.tangent_directions); runs with the whole-system spectrum
    tangent_directions: bool = False
    ball: Annotated[int, Field(strict=True, ge=0)] = 0
    spectrum: bool = True
    collision_threshold: Q("force", gt=0) = 1.0
    transient: Q("time", ge=0) = 0.0
    frames: PositiveInt = 100
    collision_frames: Annotated[int, Field(strict=True, ge=0)] = 50  # extra frames at the strongest collisions
    # band of the dominant inner-ring acceleration frequency in the summary (paper B, Fig. 11: 950-1,000 Hz)
    vibration_band: Annotated[list[Q("frequency", ge=0)], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [500.0, 1500.0])

    @model_validator(mode="after")
    def _band(self):
        if not self.vibration_band[0] < self.vibration_band[1]:
            raise rule("analysis.vibration_band", self.vibration_band, "must be [low, high] with low < high")
        return self


class OutputTable(TimeSeriesOutput):
    """``[output]``: ``write`` the files (time series, ParaView frames, figures); ``timeseries_format``:
    :class:`lubedyn.config.TimeSeriesOutput`."""

    write: list[Literal["timeseries", "pvd", "png"]] = Field(default_factory=lambda: ["timeseries", "pvd", "png"])


class DynamicsCase(CaseTable):
    """A dynamics scene; after validation every value is SI and every default filled in."""

    scene: Literal["dynamics"]
    description: str = ""
    bearing: BearingTable
    slots: SlotsTable
    initial: InitialTable = Field(default_factory=InitialTable)
    operating: OperatingTable
    model: ModelTable = Field(default_factory=ModelTable)
    films: FilmsTable
    lubricant: LubricantModel  # the oil: eta0 and Barus' alpha (LubricantModel.barus)
    integrator: IntegratorTable = Field(default_factory=IntegratorTable)
    analysis: AnalysisTable = Field(default_factory=AnalysisTable)
    output: OutputTable = Field(default_factory=OutputTable)
    limits: LimitsModel = Field(default_factory=LimitsModel)
    validity: BoundsModel = Field(default_factory=BoundsModel)  # strict: lubedyn.bounds
    smoke: dict[str, Any] | None = None

    @model_validator(mode="before")
    @classmethod
    def _renamed(cls, data):
        return refuse_renamed(data, ("films.viscosity", "films.pressure_viscosity"))

    @model_validator(mode="after")
    def _checks(self):
        self.lubricant.barus("dynamics")
        self._slot_geometry()
        if self.analysis.ball >= self.bearing.n_balls:
            raise rule("analysis.ball", self.analysis.ball, f"must be < bearing.n_balls = {self.bearing.n_balls}")
        if self.analysis.transient >= self.integrator.duration:
            raise rule("analysis.transient", self.analysis.transient,
                       f"must be < integrator.duration = {self.integrator.duration:g} s")
        return self


    def _slot_geometry(self):
        """Slots that fit their ring: shallower than the ring's wall under the groove, narrower than the
        groove, shorter than the arc to the next slot (or than the race), edges rounded within the slot."""
        s, b = self.slots, self.bearing
        if not s.azimuths:
            return
        wall = b.ring_wall(s.race)
        if not s.depth < wall:
            what = ("(bearing.outer_diameter - pitch_diameter - ball_diameter)/2" if s.race == "outer" else
                    "(pitch_diameter - ball_diameter - bearing.bore)/2")
            raise rule("slots.depth", s.depth, f"must be < {wall:g} m, the {s.race} ring's wall under the groove "
                       f"({what})")
        groove = 2.0 * min(b.inner_groove_radius, b.outer_groove_radius)
        if not s.width < groove:
            raise rule("slots.width", s.width, f"must be < {groove:g} m, the groove diameter (2 x the smaller "
                       "groove radius)")
        radius = b.race_radius(s.race)
        az = sorted(a % (2.0 * math.pi) for a in s.azimuths)
        gaps = [b2 - a2 for a2, b2 in zip(az, az[1:] + [az[0] + 2.0 * math.pi])]
        arc = min(gaps) * radius
        if not s.length < arc:
            where = "the race's circumference" if len(az) == 1 else "the arc between the closest two slots"
            raise rule("slots.length", s.length, f"must be < {arc:g} m, {where} on the {s.race} race "
                       f"(radius {radius:g} m)")
        if not s.edge_radius < min(0.5 * s.width, s.depth):
            raise rule("slots.edge_radius", s.edge_radius, f"must be < {min(0.5 * s.width, s.depth):g} m (half "
                       "the slot width and its depth)")


CaseModel = DynamicsCase


# ---------------------------------------------------------------------------- build
@dataclass
class DynamicsSetup:
    """What a case builds: the bearing model, its initial state and output times."""

    model: Any  # lubedyn.dynamics.cageless.CagelessBearing
    y0: np.ndarray
    t_out: np.ndarray
    map_path: Path | None = None
    map_info: dict = field(default_factory=dict)


def _map_path(case: DynamicsCase, source: str | None, name: str | None = None, key: str = "films.map") -> Path:
    name = name if name is not None else case.films.map
    given = Path(name)
    candidates = [given] if given.is_absolute() else (
        ([Path(source).resolve().parent / given] if source else []) + [Path.cwd() / given, CASES_DIR / given])
    for path in candidates:
        if path.is_file():
            return path
    raise InputError(f"{key} = {name!r} not found (looked in: "
                     f"{', '.join(str(p.parent) for p in candidates)}); build it with a map case, "
                     "e.g. lubedyn run cases/map_ball_ball.toml")


def _film_map(case: DynamicsCase, source: str | None):
    path = _map_path(case, source)
    fmap = FilmMap.load(path, key="films.map")
    if fmap.kind != "ball_ball":
        raise InputError(f"films.map = {case.films.map!r} is a map of kind {fmap.kind!r}; ball_ball is needed")
    return path, fmap


def model_groups(case: DynamicsCase, **built) -> dict:
    """The case's tables as the model's frozen groups (keyword arguments of
    :class:`lubedyn.dynamics.cageless.CagelessBearing`).  ``built``: values loaded from files, by case key
    (``{"films.map": arrays}``), in place of the file names the case gives."""
    out = {}
    for table, attr in CagelessBearing.GROUPS.items():  # one to one, same field names
        values = dict(getattr(case, table))
        values.update({k.partition(".")[2]: v for k, v in built.items() if k.partition(".")[0] == table})
        if table == "films":
            values["viscosity"], values["pressure_viscosity"] = case.lubricant.barus("dynamics")
            if "films.map" not in built:
                values["map"] = None
        if table == "model" and "model.traction_maps" not in built:
            values["traction_maps"] = None
        if table in ("slots", "initial"):
            values["azimuths"] = tuple(values["azimuths"])
        out[attr] = CagelessBearing.GROUP_CLASSES[attr].build(values)
    return out


def build(case: DynamicsCase, source: str | None = None, *, precompile: bool = False) -> DynamicsSetup:
    """Bearing model, quasi-static initial state and output times (raises InputError).  With
    ``precompile``, the kernels the run will call (integrator, forces, Benettin) start compiling in a
    second process if numba's cache lacks them (a first run), while this one compiles the model."""
    built = {}
    map_path, info = None, {}
    if case.films.ball_ball == "map":
        map_path, fmap = _film_map(case, source)
        built["films.map"] = fmap.dynamics_film_map() if hasattr(fmap, "dynamics_film_map") else fmap.kernel_arrays(
            "Force [N]")
        info = {"Ball-ball film map": str(map_path), "Ball-ball film map hash": fmap.input_hash}
    if case.model.traction == "map":
        arrays = []
        for race, name in zip(("inner", "outer"), case.model.traction_maps):
            path = _map_path(case, source, name, "model.traction_maps")
            fmap = FilmMap.load(path, key="model.traction_maps")
            if fmap.kind != f"ehl_ball_{race}_race":
                raise InputError(f"model.traction_maps = {name!r} is a map of kind {fmap.kind!r}; the {race} race "
                                 f"needs kind 'ehl_ball_{race}_race'")
            arrays.append(fmap.kernel_arrays("Traction coefficient [-]"))
            info[f"Traction map, {race} race"] = str(path)
        built["model.traction_maps"] = tuple(arrays)
    try:
        model = CagelessBearing(**model_groups(case, **built))
        if precompile:
            compile_in_background(kernel_jobs(case, model))
        y0 = model.initial_state()
    except DynamicsInputError as exc:  # its message names the case key already
        raise InputError(str(exc)) from None
    check_size(case, model)  # before the output times exist
    ig = case.integrator
    n = int(round(ig.duration / ig.sample_interval))
    t_out = np.linspace(0.0, n * ig.sample_interval, n + 1)
    return DynamicsSetup(model=model, y0=y0, t_out=t_out, map_path=map_path, map_info=info)


def kernel_jobs(case: DynamicsCase, model) -> list:
    """``[(kernel, example arguments)]`` of the bound kernels a run of ``case`` calls (integrator, forces
    at the samples, Benettin): :func:`build` has those numba's cache lacks compiled in a second process
    while it compiles the model, since they do not contain the model's code (:mod:`lubedyn.dynamics.specialise`)."""
    args = model.args()
    # forces first: the quasi-static start calls it right after the model has compiled
    jobs = [forces_example(args), kernel_example(case.integrator.method, rhs, args), forces_many_example(args)]
    if case.analysis.lyapunov_exponents or case.analysis.tangent_directions:
        # not where the longest window the case can have (after analysis.transient) resolves no exponent
        ig, a = case.integrator, case.analysis
        need = record_need("", 0.9 * (ig.duration - a.transient), a.transient, case.operating.speed)
        if need.resolves or a.force:
            jobs.append(spectrum_kernel_example(rhs, args))
    return jobs


def values_per_sample(model) -> int:
    """Numbers a run keeps per output sample: the state, every ball's contact diagnostics, the ring's,
    and the ball centres and contact mid-points of the analysis (3 each per ball)."""
    return len(model.state_layout()) + model.n_balls * (len(DIAG_NAMES) + 6) + N_RING_DIAG


# bytes per stored number: float64, times 2 for the copies made while analysing and writing
BYTES_PER_VALUE = 16
# The adaptive step is set by the stiff ball-race contacts: 13,519 accepted steps over the 20 ms of the
# 10,000 rpm drop (1.48 us mean).  A run whose duration would need more than max_steps steps of ten
# times that is refused before it integrates for hours and fails at the step limit.
DOPRI5_LONGEST_MEAN_STEP = 1.5e-5


def sample_count(case: DynamicsCase) -> int:
    ig = case.integrator
    return int(round(ig.duration / ig.sample_interval)) + 1


def check_size(case: DynamicsCase, model) -> None:
    """Refuse a run whose samples cannot fit the memory limit, or whose fixed RK4 steps exceed
    ``integrator.max_steps`` (:mod:`lubedyn.limits`)."""
    ig = case.integrator
    n = ig.duration / ig.sample_interval + 1
    # name the key that made the count: the one farthest from its default
    defaults = IntegratorTable()
    if ig.duration / defaults.duration >= defaults.sample_interval / ig.sample_interval:
        key = f"integrator.duration = {ig.duration:g} s (integrator.sample_interval = {ig.sample_interval:g} s)"
    else:
        key = f"integrator.sample_interval = {ig.sample_interval:g} s (integrator.duration = {ig.duration:g} s)"
    per = values_per_sample(model)
    limits.check_memory(case, f"{key}: {n:.3g} samples of {per} values", n * per * BYTES_PER_VALUE,
                        "sample less often or simulate less time")
    if ig.method == "rk4" and ig.dt is not None and ig.duration / ig.dt > ig.max_steps:
        raise InputError(f"integrator.dt = {ig.dt:g} s: {ig.duration / ig.dt:.3g} fixed RK4 steps over integrator."
                         f"duration = {ig.duration:g} s, more than integrator.max_steps = {ig.max_steps}; use a "
                         "larger step or a shorter duration, or raise integrator.max_steps")
    steps = ig.duration / DOPRI5_LONGEST_MEAN_STEP
    if ig.method == "dopri5" and steps > ig.max_steps:
        raise InputError(f"integrator.duration = {ig.duration:g} s needs at least {steps:.3g} DOPRI5 steps (the "
                         f"mean step is at most {DOPRI5_LONGEST_MEAN_STEP:g} s: 10 times the 1.48 us measured on "
                         f"the 10,000 rpm drop), more than integrator.max_steps = {ig.max_steps}; simulate less "
                         "time, or raise integrator.max_steps")


def describe(case: DynamicsCase, setup: DynamicsSetup) -> str:
    m, op, ig = setup.model, case.operating, case.integrator
    return (f"cage-less bearing, {m.n_balls} balls ({case.model.dof}, {len(setup.y0)} states), "
            f"{op.scenario} at {op.speed * 60 / (2 * math.pi):.0f} rpm, Fr = {op.radial_load:g} N, "
            f"Fa = {op.axial_load:g} N, ball-ball film {case.films.ball_ball}, {len(case.slots.azimuths)} slot(s); "
            f"{ig.method} over {ig.duration:g} s, {len(setup.t_out)} samples")


# ---------------------------------------------------------------------------- run
@dataclass
class DynamicsRun(BearingResult):
    """A cage-less bearing run (:class:`lubedyn.results.BearingResult`: ``res["Rotor speed [rad/s]"]``,
    ``res.to_xarray()``) and its ball-ball collision events."""

    events: list = None


def _contact_positions(setup: DynamicsSetup, Y: np.ndarray) -> np.ndarray:
    """Mid-points of neighbouring ball centres, (m, Z, 3) [m]."""
    c = ball_centres(setup, Y)
    return 0.5 * (c + np.roll(c, -1, axis=1))


def ball_centres(setup: DynamicsSetup, Y: np.ndarray) -> np.ndarray:
    """Ball centres (m, Z, 3) [m] in the inertial frame, for either ball model."""
    m = setup.model
    Y = np.atleast_2d(Y)
    out = np.zeros((Y.shape[0], m.n_balls, 3))
    for j in range(m.n_balls):
        b = m.ball_offset(j)
        if m.fidelity.dof == "6dof":
            out[:, j, :] = Y[:, b:b + 3]
        else:
            out[:, j, 0] = Y[:, b + 1] * np.cos(Y[:, b])
            out[:, j, 1] = Y[:, b + 1] * np.sin(Y[:, b])
    return out


def run(case: DynamicsCase, out_dir=None, *, name: str = "dynamics", source: str = "",
        smoke: bool = False) -> DynamicsRun:
    """Build, integrate, analyse and (with ``out_dir``) write the case through the bearing run driver
    (:func:`lubedyn.scenes.bearing_run.drive`, :class:`CagelessRunModel`)."""
    return drive(CagelessRunModel(case, source), out_dir, name=name, source=source, smoke=smoke)


class CagelessRunModel:
    """The cage-less ball bearing's side of :func:`lubedyn.scenes.bearing_run.drive`: its model and
    quasi-static start (:func:`build`), the integrator options, the summary (collisions, slip, Lyapunov
    exponents, bearing frequencies, paper B's figures' quantities; the Benettin spectrum in a background
    thread) and the files (time series, ``collisions.csv``, ``.vtp`` frames, figures)."""

    def __init__(self, case: DynamicsCase, source: str = ""):
        self.case, self.source = case, source

    def build(self) -> None:
        self.setup = build(self.case, self.source or None, precompile=True)

    def describe(self) -> str:
        return describe(self.case, self.setup)

    def integration(self):
        ig, model = self.case.integrator, self.setup.model
        return Integration(rhs, self.setup.y0, self.setup.t_out, model.args(),
                           dict(method=ig.method, rtol=ig.rtol, atol=ig.atol, dt=ig.dt, max_steps=ig.max_steps,
                                # the highest contact rate at y0 and, with RK4, again at the state after every
                                # chunk (a contact that stiffens later in the run stops it, naming the stable step)
                                omega_max=model.omega_max),
                           # 200 kernel calls on a terminal or not: the result is bit-identical to one call
                           # (tests/test_chunking.py), and control comes back to Python between them, so a
                           # Ctrl-C in a pipe is taken within one chunk (the 0.1 s drop integrates in 1.4 s
                           # warm: 7 ms a chunk), not at the end of the integration
                           n_chunks=200, on_error=self._error)

    def modules(self, writing: bool = True) -> tuple[str, ...]:
        """The heavy modules the analysis and (``writing``) the outputs of this case import (imported during
        the integration: :func:`lubedyn.scenes.bearing_run.import_in_background`)."""
        case, names = self.case, ["scipy.signal"]  # the spectra (lubedyn.dynamics.spectra)
        write = case.output.write if writing else ()
        if case.analysis.lyapunov or case.analysis.lyapunov_exponents:
            names.append("scipy.spatial")  # neighbours of the time-series estimators
        if "timeseries" in write and case.output.timeseries_format == "netcdf":
            names += ["xarray", "netCDF4"]
        if "png" in write:
            names.append("matplotlib.pyplot" if os.environ.get("MPLBACKEND", "").lower() == "agg" else "matplotlib")
        if "pvd" in write:
            names += ["pyvista", "vtkmodules.vtkIOXML"]
        return tuple(names)

    def _error(self, exc):
        ig = self.case.integrator
        if isinstance(exc, DynamicsInputError):
            return InputError(str(exc))
        if ig.method == "rk4":  # the reason names the step that would be stable (or the step budget)
            return ConvergenceError(f"{exc} (integrator.method = 'rk4', integrator.dt = {ig.dt:g} s)")
        return ConvergenceError(f"{exc} (integrator.method = {ig.method!r}, rtol = {ig.rtol:g}; "
                                "tighten the tolerance or reduce integrator.dt)")

    def analyse(self, res, timing) -> dict:
        case, setup = self.case, self.setup
        model, ig = setup.model, case.integrator
        t0, t_int = timing.t0, timing.integration
        t, Y = res.t, res.y
        diag, ring = forces_many(t, Y, model.args())

        events = collision_events(t, diag[:, :, D_BBN], diag[:, :, [D_BBX, D_BBY, D_BBZ]],
                                  _contact_positions(setup, Y), case.analysis.collision_threshold)
        centres = ball_centres(setup, Y)
        omega_i = Y[:, 7]
        shaft = float(case.operating.speed)
        summary = {
            "Balls [-]": model.n_balls, "Ball degrees of freedom": case.model.dof, "States [-]": int(Y.shape[1]),
            "Scenario": case.operating.scenario, "Rotor speed at start [rpm]": shaft * 60 / (2 * math.pi),
            "Radial load [N]": case.operating.radial_load, "Axial load [N]": case.operating.axial_load,
            "Ball-ball film": case.films.ball_ball, "Simulated time [s]": float(t[-1]),
            "Sample interval [s]": float(t[1] - t[0]), "Integrator": ig.method,
        }
        summary.update(setup.map_info)
        summary.update(res.stats)
        summary["Integration wall time [s]"] = t_int
        summary["Simulated time per wall second [s/s]"] = float(t[-1]) / t_int if t_int > 0 else None
        summary["Inner ring speed at end [rpm]"] = float(omega_i[-1] * 60 / (2 * math.pi))
        if case.operating.scenario == "drop":
            Omega = Y[:, 8]
            summary["Rotor speed at end [rpm]"] = float(Omega[-1] * 60 / (2 * math.pi))
            summary["Inner ring slip against rotor at end [-]"] = float(1.0 - omega_i[-1] / Omega[-1])
        # ball slip: orbital speed against the no-slip epicyclic (ball-train) speed of the current ring speed
        ideal = bearings.cage_speed(model.bearing.ball_diameter, model.bearing.pitch_diameter, 0.0, omega_i[-1])
        orbital = diag[-1, :, D_PSIDOT]
        summary["Ball-train speed at end [rad/s]"] = float(np.mean(orbital))
        summary["Ball-train slip at end [-]"] = float(1.0 - np.mean(orbital) / ideal) if ideal else None
        if case.films.race == "closed_form":
            ue = bearings.entrainment_speed(model.bearing.ball_diameter, model.bearing.pitch_diameter, 0.0, omega_i[-1])
            h_i, h_o = model.race_film_thickness(ue)
            summary["Inner race film at end, epicyclic speed [m]"] = h_i
            summary["Outer race film at end, epicyclic speed [m]"] = h_o
        summary["Initial largest inner race load [N]"] = float(diag[0, :, D_QI].max())
        summary["Initial largest outer race load [N]"] = float(diag[0, :, D_QO].max())
        summary["Largest inner race load [N]"] = float(diag[:, :, D_QI].max())
        summary["Largest outer race load [N]"] = float(diag[:, :, D_QO].max())
        summary["Largest ball spin speed [rad/s]"] = float(np.abs(diag[:, :, D_SPIN]).max())
        summary.update(collision_summary(events, model.n_balls))
        counter = getattr(model, "map_counter", None)
        if counter is not None:
            summary["Film map queries outside axes [-]"] = int(counter[0])
            if (case.films.ball_ball == "map" or case.model.traction == "map") and counter[0] > 0:
                log.warning("the film maps were queried outside their axes %d times and clamped there; "
                            "widen the maps' axes for this scene", int(counter[0]))
        if case.analysis.lyapunov:
            drop = case.operating.scenario == "drop"
            summary.update(_lyapunov_per_direction(
                case, t, centres, shaft, ring_speed=omega_i, rotor_speed=Y[:, 8] if drop else None,
                collision_times=[e.t_peak for e in events],
                # a position is resolved to about rtol times its size (the error control of the integrator)
                scale_min=ig.rtol * float(np.max(np.abs(centres[:, case.analysis.ball, :])))))
        benettin = None
        if case.analysis.lyapunov_exponents or case.analysis.tangent_directions:
            start = summary.get("Lyapunov window start [s]")
            need = benettin_need(case, t, start, shaft)
            summary["Lyapunov record needed, whole system [s]"] = need.needed
            if need.resolves or forced(case):
                # the whole-system spectrum runs in a thread (its compiled kernel releases the GIL) while the
                # rest of the analysis, the frames and the figures are made; its entries join the summary
                # before the time series and summary.json are written (_BackgroundResult)
                benettin = _BackgroundResult(_benettin, case, model, t, Y, shaft, start=start,
                                             progress_label="Lyapunov spectrum (Benettin)")
                if not need.resolves:
                    summary["Lyapunov exponents, whole system, note"] = need.forced()
            else:  # a record that resolves no exponent: not computed, and why (decision 1 of issue 42)
                summary.update(benettin_not_computed(case, need))
        # characteristic frequencies at the inner ring's mean speed over the analysed window
        # (after a drop the ring is still spinning up: the lines move during the run)
        keep = t >= case.analysis.transient
        ring_hz = float(np.mean(omega_i[keep])) / (2 * math.pi)
        window = float(t[keep][-1] - t[keep][0]) if keep.sum() > 1 else 0.0
        n_in_window = sum(1 for e in events if e.t_peak >= case.analysis.transient)
        freqs = bearing_frequencies(ring_hz, model, {"Collision rate [Hz]": n_in_window / window if window else 0.0})
        summary["Mean inner ring speed in the analysed window [rpm]"] = ring_hz * 60.0
        summary.update(freqs)
        # paper B's figures 3-5 and 11: settling and spin-up times, zones, collisions by quadrant, vibration band

        summary.update(paper_b_figures.summary_entries(case, t, run_columns(model, Y, diag, ring), events, freqs))

        self.t, self.Y, self.diag, self.ring, self.events = t, Y, diag, ring, events
        self.centres, self.freqs, self.benettin = centres, freqs, benettin
        return summary

    def files(self, summary: dict, timing):
        t0, benettin = timing.t0, self.benettin

        def complete(summary):
            """The summary with the Benettin entries (waiting for their thread) and the run time updated."""
            if benettin is not None:
                run_time = summary.pop("Run time [s]")
                tail = {k: summary.pop(k) for k in ("Smoke resolution", "Build time [s]", "lubedyn version")
                        if k in summary}
                summary.update(benettin.result())
                summary.update(tail)
                summary["Run time [s]"] = max(run_time, time.perf_counter() - t0)
            return summary

        case, setup, t, Y, diag, ring, events = self.case, self.setup, self.t, self.Y, self.diag, self.ring, self.events
        return outputs.RunFiles(
            t=t, columns=lambda: run_columns(setup.model, Y, diag, ring),
            meta=lambda full: {"Case": full["Case"], "Scene": "dynamics", "Summary": full},
            texts=lambda: {"collisions.csv": _collisions_csv(events)},
            frames=self._frames, frame_ext="vtp",
            figures=lambda: ((name, draw()) for name, draw in self.drawings().items()),
            complete=complete, write_time=True)

    def _frames(self):
        """The ParaView frames: ``analysis.frames`` evenly spaced samples and the peaks of the
        ``analysis.collision_frames`` strongest collisions (so that the film pressure is seen)."""
        t, events = self.t, self.events
        n_frames = min(self.case.analysis.frames, len(t))
        picks = np.unique(np.linspace(0, len(t) - 1, n_frames).round().astype(int))
        strongest = sorted(events, key=lambda e: -e.peak_force)[:self.case.analysis.collision_frames]
        peaks = np.searchsorted(t, [e.t_peak for e in strongest])
        picks = np.unique(np.concatenate([picks, peaks]))
        scene3d = _Scene3D(self.case, self.setup)
        for i in picks:
            yield float(t[i]), scene3d.frame(self.Y[i], self.diag[i], D_BBN, D_H)

    def drawings(self) -> dict:
        return drawings(self.case, self.setup, self.t, self.Y, self.diag, self.ring, self.events, self.centres,
                        self.freqs)

    def result(self, summary: dict, files: list) -> DynamicsRun:
        return DynamicsRun(summary=summary, files=files, t=self.t, y=self.Y, events=self.events,
                           drawings=self.drawings())


class _BackgroundResult:
    """``func(*args, **kwargs)`` in a daemon thread; :meth:`result` waits and returns it (or raises its
    exception).  A daemon thread does not hold up the interpreter's exit after a Ctrl-C.  With
    ``progress_label``, ``func`` is also given ``progress=`` (a callable taking the fraction done) and, on a
    terminal, :meth:`result` shows a bar under that label while it waits."""

    def __init__(self, func, *args, progress_label: str | None = None, **kwargs):
        import threading

        self._out = None
        self._exc = None
        self._label = progress_label
        self.fraction = 0.0
        if progress_label is not None:
            kwargs["progress"] = self._advance

        def target():
            try:
                self._out = func(*args, **kwargs)
            except BaseException as exc:  # handed to the caller of result()
                self._exc = exc

        self._thread = threading.Thread(target=target, name="lubedyn-benettin", daemon=True)
        self._thread.start()

    def _advance(self, fraction: float):
        self.fraction = fraction  # one float store, read by result() in the main thread

    def result(self):
        bar = None
        if self._label is not None and self._thread.is_alive() and sys.stderr.isatty():
            from tqdm.auto import tqdm

            bar = tqdm(total=100, desc=self._label, unit="%", disable=None,
                       bar_format="{l_bar}{bar}| {n:.0f}/{total} % [{elapsed}<{remaining}]")
        try:
            while self._thread.is_alive():
                self._thread.join(0.1)  # short joins: a Ctrl-C in the main thread is taken at once
                if bar is not None:
                    bar.update(int(100 * self.fraction) - bar.n)
        finally:
            if bar is not None:
                bar.close()
        if self._exc is not None:
            raise self._exc
        return self._out


HEADLINE = ("Simulated time [s]", "Inner ring speed at end [rpm]", "Rotor speed at end [rpm]",
            "Ball-train slip at end [-]", "Ball-ball collisions [-]", "Largest collision normal force [N]",
            "Largest inner race load [N]", "Accepted steps [-]", "Integration wall time [s]")


def headline(summary: dict) -> list[str]:
    """What ``lubedyn run`` prints for a dynamics run: the computed values of :data:`HEADLINE` and the
    chaos estimators, then one line counting those not computed (each keeps its value and its reason,
    a ``", note"`` entry, in summary.json)."""
    lines = []
    exponents = tuple(k for k in summary if ("Lyapunov exponent" in k and k.endswith("[1/s]"))
                      or (k.startswith("Wolf exponent") and (k.endswith("[bits/s]") or k.endswith(" verdict"))))
    for key in HEADLINE + exponents:
        value = summary.get(key)
        if outputs.computed(value):
            lines.append(f"{key:<52} {value:.6g}" if isinstance(value, float) else f"{key:<52} {value}")
    # the record rule's verdicts in full: an estimator not computed (or forced) on a record too short for it
    lines += [f"{key.removesuffix(', note')}: {summary[key]}" for key in RECORD_NOTES if summary.get(key)]
    return lines + outputs.not_computed_line(summary, HEADLINE + exponents)


#: the summary's notes of :class:`lubedyn.scenes.dynamics_lyapunov.RecordNeed` that the terminal shows
RECORD_NOTES = ("Lyapunov exponents per direction, note", "Lyapunov exponents, whole system, note")


def bearing_frequencies(ring_hz: float, model, extra=None) -> dict:
    """Kinematic bearing frequencies [Hz] at an inner-ring speed (outer ring fixed, zero contact angle)."""
    return bf(ring_hz, model.bearing.ball_diameter, model.bearing.pitch_diameter, model.n_balls, 0.0, extra=extra)


# ---------------------------------------------------------------------------- outputs
def _collisions_csv(events) -> str:
    lines = ["pair,t_start [s],t_peak [s],t_end [s],normal force [N],Fx [N],Fy [N],Fz [N],x [m],y [m],z [m]"]
    for e in events:
        lines.append(",".join(f"{v:.9g}" for v in (e.pair, e.t_start, e.t_peak, e.t_end, e.peak_force, *e.force,
                                                     *e.position)))
    return "\n".join(lines) + "\n"


class _Scene3D:
    """Geometry of the ParaView frames, built once: template surfaces (balls,
    rings, slots, a unit film disc) whose points are moved with numpy for each
    frame and written as one PolyData per frame with point fields
    "Body [-]" (0 outer ring, 1 inner ring, 2 slot, 3 ball, 4 film) and
    "Film pressure [Pa]".

    Film pressure on the disc between two balls: while the oil film carries
    the force F at a central film thickness h0 > 0, the rigid squeeze-film
    profile p = 3 eta v R_eff / h^2 with h = h0 + r^2/(2 R_eff) and v from
    F = 6 pi eta R_eff^2 v / h0; once the solids touch (h0 = 0), Hertz's
    p0 sqrt(1 - r^2/a^2) with a = (3 F R_eff / (4 E*))^(1/3)."""

    def __init__(self, case, setup):
        import pyvista as pv

        m = setup.model
        self.case, self.setup = case, setup
        self.R = 0.5 * m.bearing.ball_diameter
        self.r_eff = 0.5 * self.R
        self.eta = case.lubricant.viscosity.eta0
        self.e_star = m.e_star_ball
        r_po = 0.5 * m.bearing.pitch_diameter + self.R
        r_pi = 0.5 * m.bearing.pitch_diameter - self.R
        self.outer = pv.Disc(inner=r_po, outer=r_po + 3e-3, r_res=1, c_res=90).triangulate()
        self.inner = pv.Disc(inner=r_pi - 6e-3, outer=r_pi, r_res=1, c_res=90).triangulate()
        self.slots = []
        for az in case.slots.azimuths:
            sl = pv.Box(bounds=(-0.5 * case.slots.length, 0.5 * case.slots.length, 0, case.slots.depth,
                                -0.5 * case.slots.width, 0.5 * case.slots.width)).triangulate()
            radius = r_po if case.slots.race == "outer" else r_pi - case.slots.depth
            sl.translate((0, radius, 0), inplace=True)
            sl.rotate_z(math.degrees(az) - 90.0, inplace=True)
            self.slots.append(sl)
        self.sphere = pv.Sphere(radius=self.R, theta_resolution=16, phi_resolution=12).triangulate()
        self.disc = pv.Disc(inner=0.0, outer=1.0, r_res=12, c_res=24, normal=(0, 0, 1)).triangulate()

    @staticmethod
    def _faces(mesh):
        return mesh.faces.reshape(-1, 4)[:, 1:]

    def frame(self, y, diag_row, D_BBN, D_H):
        import pyvista as pv

        m = self.setup.model
        pts, tris, body, pres = [], [], [], []
        count = 0

        def add(points, faces, b, p=None):
            nonlocal count
            pts.append(points)
            tris.append(faces + count)
            body.append(np.full(len(points), b, dtype=np.int32))
            pres.append(np.zeros(len(points)) if p is None else p)
            count += len(points)

        add(self.outer.points, self._faces(self.outer), 0)
        c, s = math.cos(y[3]), math.sin(y[3])
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        add(self.inner.points @ rot.T + y[:3], self._faces(self.inner), 1)
        for sl in self.slots:
            p = sl.points @ rot.T + y[:3] if self.case.slots.race == "inner" else sl.points
            add(p, self._faces(sl), 2)
        centres = ball_centres(self.setup, y[None, :])[0]
        f_sphere = self._faces(self.sphere)
        for cen in centres:
            add(self.sphere.points + cen, f_sphere, 3)
        disc, f_disc = self.disc.points, self._faces(self.disc)
        r_unit = np.hypot(disc[:, 0], disc[:, 1])
        for j in range(m.n_balls):
            F = diag_row[j, D_BBN]
            if F <= 0.0:
                continue
            a, b = centres[j], centres[(j + 1) % m.n_balls]
            n = (b - a) / np.linalg.norm(b - a)
            e1 = np.cross(n, (0.0, 0.0, 1.0) if abs(n[2]) < 0.9 else (1.0, 0.0, 0.0))
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(n, e1)
            h0 = float(diag_row[j, D_H])
            hp = point_contact(F, self.r_eff, self.r_eff, self.e_star)
            # np.float64 (the dtype of the load read from the diagnostics): when 3 a_h sets the disc
            # size, r and the pressure are float64, not the float32 of the pyvista template points
            a_h, p0 = np.float64(hp.a), hp.p0
            size = max(3 * a_h, 3 * math.sqrt(2 * self.r_eff * max(h0, 1e-9)))
            r = r_unit * size
            if h0 > 0:
                v = F * h0 / (6 * math.pi * self.eta * self.r_eff**2)
                p = 3 * self.eta * v * self.r_eff / (h0 + r**2 / (2 * self.r_eff)) ** 2
            else:
                p = p0 * np.sqrt(np.clip(1 - (r / a_h) ** 2, 0.0, None))
            pos = 0.5 * (a + b) + size * (disc[:, :1] * e1 + disc[:, 1:2] * e2)
            add(pos, f_disc, 4, p)
        tri = np.concatenate(tris)
        mesh = pv.PolyData(np.concatenate(pts), np.hstack([np.full((len(tri), 1), 3), tri]).ravel())
        mesh.point_data["Body [-]"] = np.concatenate(body)
        mesh.point_data["Film pressure [Pa]"] = np.concatenate(pres)
        return mesh


def _phase_portraits(t, centres, j: int, into=None):
    """Ball ``j``'s phase portraits in two frames: the fixed (inertial) frame, x, y, z against their
    rates, where the orbit (a circle of the pitch radius) dominates x and y; and the frame turning with
    the ball train, where the orbit is removed: the radial position r (distance from the bearing axis),
    the position along the orbit relative to the ball train's mean azimuth (r times the ball's lead
    over the mean of every ball's unwrapped azimuth, its time mean removed) and z, against their rates."""
    vel = np.gradient(centres[:, j, :], t, axis=0)
    fig, axes = outputs.panels(into, 2, 3, figsize=(11, 6.8), layout="constrained")
    for i, axis in enumerate("xyz"):
        axes[0, i].plot(centres[:, j, i] * 1e3, vel[:, i], lw=0.5)
        axes[0, i].set_xlabel(f"{axis} [mm]")
        axes[0, i].set_ylabel(f"d{axis}/dt [m/s]")
    r = np.hypot(centres[:, :, 0], centres[:, :, 1])
    psi = np.unwrap(np.arctan2(centres[:, :, 1], centres[:, :, 0]), axis=0)
    lead = psi[:, j] - psi.mean(axis=1)
    arc = r[:, j] * (lead - lead.mean())
    r_mean = float(r[:, j].mean())
    for i, (x, scale, label) in enumerate(((r[:, j] - r_mean, 1e6, "r"), (arc, 1e3, "s"), (centres[:, j, 2], 1e6, "z"))):
        axes[1, i].plot(x * scale, np.gradient(x, t), lw=0.5, color="C1")
        axes[1, i].set_ylabel(f"d{label}/dt [m/s]")
    axes[1, 0].set_xlabel(f"r - {r_mean * 1e3:.4g} mm, radial [um]")
    axes[1, 1].set_xlabel("s, along the orbit vs ball train [mm]")
    axes[1, 2].set_xlabel("z [um]")
    for ax in axes.ravel():
        ax.locator_params(axis="x", nbins=4)  # long tick labels (an orbit at -23.02 mm) never overlap
    axes[0, 1].set_title("fixed (inertial) frame: the orbit dominates x and y", fontsize=10)
    axes[1, 1].set_title("frame turning with the ball train: orbit removed", fontsize=10)
    fig.suptitle(f"phase portraits, ball {j}")
    return fig


def drawings(case, setup, t, Y, diag, ring, events, centres, freqs) -> dict:
    """The run's figures, ``{file name: draw}``, ``draw(into=None)`` making the figure (a new pyplot figure,
    or in ``into``: a Figure, SubFigure or, for one panel, an Axes; :func:`lubedyn.outputs.panels`) and
    returning it: what ``lubedyn run`` writes and ``res.plot(kind)`` draws."""
    j = case.analysis.ball
    ms = t * 1e3

    def trajectories(into=None):
        fig, axes = outputs.panels(into, 3, 1, figsize=(8, 7), sharex=True, layout="constrained")
        for i, axis in enumerate("xyz"):
            axes[i].plot(ms, centres[:, j, i] * 1e3, lw=0.8)
            axes[i].set_ylabel(f"ball {j} {axis} [mm]")
        axes[-1].set_xlabel("time [ms]")
        # a case's description can be longer than the figure is wide: wrapped, never cut
        axes[0].set_title(textwrap.fill(f"{case.description or 'cage-less bearing'}: ball {j} centre", 80),
                          fontsize=10)
        return fig

    def collision_needles(into=None):
        fig, axes = outputs.panels(into, 3, 1, figsize=(8, 7), sharex=True, layout="constrained")
        for i, axis in enumerate("xyz"):
            if events:
                te = np.array([e.t_peak for e in events]) * 1e3
                fe = np.array([e.force[i] for e in events])
                axes[i].vlines(te, 0, fe, lw=0.8)
                axes[i].plot(te, fe, "o", ms=2)
            axes[i].axhline(0, color="k", lw=0.5)
            axes[i].set_ylabel(f"F{axis} [N]")
        axes[0].set_title(f"ball-ball collision forces ({len(events)} collisions)")
        axes[-1].set_xlabel("time [ms]")
        axes[-1].set_xlim(ms[0], ms[-1])
        return fig

    def spectrum(into=None):
        fig, ax = outputs.panels(into, figsize=(8, 4), layout="constrained")
        keep = t >= case.analysis.transient
        acc = np.gradient(Y[keep, 5], t[keep])  # inner ring vertical acceleration
        if keep.sum() >= 16:  # the summary's dominant frequency needs as many (lubedyn.dynamics.analysis.frequency)
            f, amp = amplitude_spectrum(acc, 1.0 / float(t[1] - t[0]))
            # up to 1.5 x the highest first harmonic of the bearing lines (not the collision rate, tens of kHz),
            # and the vibration band of the summary (shaded)
            band = case.analysis.vibration_band
            f_max = min(f[-1], max(spectrum_limit(freqs) or f[-1], band[1]))
            ax.axvspan(band[0] / 1e3, min(band[1], f_max) / 1e3, color="0.9", lw=0, label="analysis.vibration_band")
            shown = f <= f_max
            ax.semilogy(f[shown] / 1e3, np.maximum(amp[shown], 1e-12), lw=0.7)
            for k, (name, value) in enumerate(freqs.items()):
                if 0 < value < f_max:
                    ax.axvline(value / 1e3, color=f"C{k + 1}", lw=0.8, ls="--",
                               label=f"{name.replace(' [Hz]', '')} {value:.0f} Hz")
            ax.set_xlim(0.0, f_max / 1e3)
            ax.legend(fontsize=7)
        else:  # too short a record after the transient for a spectrum: the figure says so instead of staying blank
            ax.text(0.5, 0.5, f"no spectrum: {int(keep.sum())} samples after analysis.transient = "
                    f"{case.analysis.transient:.3g} s (at least 16 needed)", transform=ax.transAxes, ha="center",
                    va="center", fontsize=9, color="C3")
        ax.set_xlabel("frequency [kHz]")
        ax.set_ylabel("inner ring y acceleration [m/s^2]")
        ax.set_title("inner-ring acceleration spectrum")
        return fig

    draw = {"trajectories.png": trajectories, "collision_needles.png": collision_needles,
            "phase_portraits.png": lambda into=None: _phase_portraits(t, centres, j, into),
            "spectrum.png": spectrum}
    draw.update(paper_b_figures.drawings(case, t, run_columns(setup.model, Y, diag, ring), events))
    return draw

