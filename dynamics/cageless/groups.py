"""The cage-less bearing's data as frozen groups, one per table of a dynamics case (SI units).

Part of :mod:`lubedyn.dynamics.cageless`.  :class:`~lubedyn.dynamics.cageless.CagelessBearing` holds one of each:

=============  ===========  ===============================================================
group          case table   what
=============  ===========  ===============================================================
``bearing``    [bearing]    geometry, materials, masses and inertias
``operating``  [operating]  loads, speed, scenario (drop / steady / free), rotor contact
``fidelity``   [model]      degrees of freedom, Hertz constants, damping, traction, yield
``films``      [films]      the oil: viscosity, pressure-viscosity; ball-ball and race films
``slots``      [slots]      the local functional slots
``initial``    [initial]    the starting arrangement and its seeded perturbation (ensembles)
=============  ===========  ===============================================================

Paper data are not defaults here: paper B's values come from its parameter set
(:mod:`lubedyn.papers.zhang2024.parameters`); the defaults are model options and numerical settings.
Each group checks its own values; checks that need two groups live in the model.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from lubedyn.lubrication.laws import contact as laws_contact
from lubedyn.lubrication.laws.collision import ENTRAPPED_DAMPING, FRICTION_LAWS

from ..contacts import FILM_KINDS
from ..groups import Group
from .layout import DOFS, MAP_SPEED_AXES, RACES, RACE_FILMS, SCENARIOS, TRACTIONS


@dataclass(frozen=True, kw_only=True)
class Bearing(Group):
    """Geometry: ``n_balls`` Z, ``ball_diameter`` D, ``pitch_diameter`` d_m, groove radii r_i, r_o
    (groove bottoms at d_m/2 -+ D/2 - P_d/4, P_d the ``diametral_clearance``; negative: preload).
    Materials: E, nu of the balls and the rings.  ``ball_mass`` None: from ``ball_density``.
    ``ring_mass``: the inner ring plus the rotor share it carries; ``ring_inertia``: the inner ring
    alone about its axis; ``rotor_inertia`` (inf: a driven rotor).  ``outer_diameter`` and ``bore``
    (optional): the rings' outer diameter and bore, which bound a slot's depth (the case checks it)."""

    TABLE: ClassVar[str] = "bearing"

    n_balls: int
    ball_diameter: float
    pitch_diameter: float
    inner_groove_radius: float
    outer_groove_radius: float
    diametral_clearance: float = 0.0
    ball_modulus: float
    ball_poisson: float
    ring_modulus: float
    ring_poisson: float
    ball_density: float = 7850.0
    ball_mass: float | None = None
    ring_mass: float
    ring_inertia: float
    rotor_inertia: float
    outer_diameter: float | None = None
    bore: float | None = None

    def __post_init__(self):
        Z = self.n_balls
        if isinstance(Z, bool) or int(Z) != Z or Z < 3:
            raise self.fail("n_balls", "must be an integer >= 3")
        self.positive("ball_diameter", "pitch_diameter", "ball_modulus", "ring_modulus", "ball_density", "ring_mass",
                      "ring_inertia", "rotor_inertia")
        if self.ball_mass is not None:
            self.positive("ball_mass")
        D, dm = self.ball_diameter, self.pitch_diameter
        if not D < dm:
            raise self.fail("ball_diameter", f"must be < bearing.pitch_diameter = {dm:g} m")
        if Z * D >= math.pi * dm:
            raise self.fail("n_balls", f"balls of D = {D:g} m do not fit the pitch circle: Z D = {Z * D:g} m >= "
                                       f"pi d_m = {math.pi * dm:g} m")
        for name in ("inner_groove_radius", "outer_groove_radius"):
            if not getattr(self, name) > 0.5 * D:
                raise self.fail(name, f"must be > bearing.ball_diameter/2 = {0.5 * D:g} m (the groove must be wider "
                                      "than the ball: conformity r/D > 0.5)")
        bd = self.total_clearance
        if not (math.isfinite(self.diametral_clearance) and -0.05 * bd < self.diametral_clearance < 4.0 * bd):
            raise self.fail("diametral_clearance", f"must be in ({-0.05 * bd:g}, {4 * bd:g}) m, i.e. (-0.05 B D, "
                            f"4 B D) with B D = inner_groove_radius + outer_groove_radius - ball_diameter = {bd:g} m "
                            "(negative: interference, i.e. preload)")
        for name in ("ball_poisson", "ring_poisson"):
            if not -1.0 < getattr(self, name) < 0.5:
                raise self.fail(name, "must be in (-1, 0.5)")

    @property
    def total_clearance(self) -> float:
        """B D = r_i + r_o - D [m]."""
        return self.inner_groove_radius + self.outer_groove_radius - self.ball_diameter

    @property
    def mass(self) -> float:
        """Ball mass [kg]."""
        if self.ball_mass is not None:
            return float(self.ball_mass)
        return self.ball_density * math.pi / 6.0 * self.ball_diameter**3


@dataclass(frozen=True, kw_only=True)
class Operating(Group):
    """``scenario``: "drop" (the rotor spinning at ``speed`` [rad/s] lands on the inner ring and drags it
    up to speed by friction at ``rotor_contact_radius`` with ``rotor_friction``, regularised over
    ``rotor_slip_regularisation`` rad/s), "steady" (inner ring driven at ``speed``) or "free" (no
    rotor).  Loads on the inner ring [N], ``gravity`` [m/s^2] along -y, ``drop_speed`` [m/s] the
    ring's downward speed at the start of a drop."""

    TABLE: ClassVar[str] = "operating"

    scenario: str = "steady"
    speed: float
    radial_load: float
    axial_load: float
    gravity: float = 9.81
    drop_speed: float = 0.0
    rotor_friction: float = 0.1
    rotor_contact_radius: float = 15e-3
    rotor_slip_regularisation: float = 1.0

    def __post_init__(self):
        self.choice("scenario", SCENARIOS)
        self.positive("rotor_contact_radius", "rotor_slip_regularisation")
        self.non_negative("speed", "radial_load", "axial_load", "gravity", "drop_speed", "rotor_friction")


@dataclass(frozen=True, kw_only=True)
class Initial(Group):
    """Where the run starts (case table ``[initial]``), for ensembles of runs: the balls at ``azimuths``
    [rad] (one per ball; empty: evenly spaced from ``first_ball_azimuth``), each moved by a random angle
    uniform in (-``jitter``, ``jitter``) [rad]; after the quasi-static start the inner ring gets a
    velocity of ``kick`` [m/s] in a random direction of the x-y plane.  The random numbers come from
    numpy's PCG64 generator seeded with ``seed`` (the same on every machine): one seed, one run,
    bit for bit; with ``jitter = kick = 0`` the seed changes nothing."""

    TABLE: ClassVar[str] = "initial"

    first_ball_azimuth: float = math.radians(270.0)
    azimuths: tuple = ()
    jitter: float = 0.0
    kick: float = 0.0
    seed: int = 0

    def __post_init__(self):
        object.__setattr__(self, "azimuths", tuple(float(a) for a in self.azimuths))
        if not math.isfinite(self.first_ball_azimuth):
            raise self.fail("first_ball_azimuth", "must be a finite angle [rad]")
        if not all(math.isfinite(a) for a in self.azimuths):
            raise self.fail("azimuths", "must be finite angles [rad]")
        self.non_negative("jitter", "kick")
        if isinstance(self.seed, bool) or int(self.seed) != self.seed or self.seed < 0:
            raise self.fail("seed", "must be an integer >= 0")

    def ball_azimuths(self, n_balls: int):
        """The balls' starting azimuths [rad] (array of n_balls) and the ring's kick velocity (vx, vy)."""
        import numpy as np

        if self.azimuths:
            if len(self.azimuths) != n_balls:
                raise self.fail("azimuths", f"gives {len(self.azimuths)} angles; bearing.n_balls = {n_balls} "
                                "balls need one each", value=f"[{len(self.azimuths)} angles]")
            psi = np.array(self.azimuths, dtype=float)
        else:
            psi = self.first_ball_azimuth + 2.0 * np.pi * np.arange(n_balls) / n_balls
        rng = np.random.default_rng(int(self.seed))
        if self.jitter > 0.0:
            psi = psi + rng.uniform(-self.jitter, self.jitter, n_balls)
        kick = (0.0, 0.0)
        if self.kick > 0.0:
            angle = rng.uniform(0.0, 2.0 * np.pi)
            kick = (self.kick * math.cos(angle), self.kick * math.sin(angle))
        return psi, kick


@dataclass(frozen=True, kw_only=True)
class Fidelity(Group):
    """Model options (case table ``[model]``): ``dof`` ("6dof", "planar"), ``hertz`` ("exact",
    "hamrock_brewe" constants), ``ball_ball`` (contacts between neighbours), ``race_damping`` (the
    Hunt-Crossley alpha [s/m] of the race contacts), ``ball_ball_damping`` (the same for ball-ball),
    ``yield_stress`` [Pa] of the ball-ball contact (None: elastic) with ``plastic_memory_time`` [s],
    ``traction`` ("closed_form"; "map" with ``traction_maps`` = (inner, outer) kernel arrays of the
    EHL race maps), the closed-form curve's ``traction_limit``, ``traction_srr`` and
    ``traction_slip_regularisation`` [m/s], ``quaternion_stabilisation`` [1/s].
    ``shoulder_contact_angle_deg``: the largest contact angle before the contact ellipse runs over the
    groove shoulder (paper B gives no shoulder diameters; 40 deg assumed): a load that needs more is
    refused."""

    TABLE: ClassVar[str] = "model"

    dof: str = "6dof"
    hertz: str = "exact"
    ball_ball: bool = True
    race_damping: float = 0.2
    ball_ball_damping: float = 0.0
    yield_stress: float | None = 1.7e9
    plastic_memory_time: float = 1e-4
    traction: str = "closed_form"
    traction_maps: tuple | None = None
    traction_limit: float = 0.07
    traction_srr: float = 0.02
    traction_slip_regularisation: float = 0.05
    quaternion_stabilisation: float = 10.0
    shoulder_contact_angle_deg: float = 40.0

    def __post_init__(self):
        self.choice("dof", DOFS)
        self.choice("hertz", laws_contact.METHODS)
        self.choice("traction", TRACTIONS)
        self.positive("plastic_memory_time", "traction_srr", "traction_slip_regularisation",
                      "shoulder_contact_angle_deg")
        self.non_negative("race_damping", "ball_ball_damping", "traction_limit", "quaternion_stabilisation")
        if self.yield_stress is not None and not self.yield_stress > 0.0:
            raise self.fail("yield_stress", "must be > 0 [Pa] (or None: elastic)")
        if self.traction == "map" and self.traction_maps is None:
            raise self.fail("traction_maps", "are needed with model.traction = 'map': (inner, outer) kernel "
                            "arrays of the EHL race maps (lubedyn.maps.FilmMap.kernel_arrays('Traction "
                            "coefficient [-]'))")


@dataclass(frozen=True, kw_only=True)
class Films(Group):
    """The oil and its films: ``viscosity`` eta0 [Pa s], ``pressure_viscosity`` alpha [1/Pa];
    ``ball_ball`` ("none", "closed_form": the rigid isoviscous squeeze film in series with Hertz,
    "map": ``map`` = the kernel arrays of a ball_ball force map (:class:`lubedyn.maps.KernelArrays`) whose
    speed axis is ``map_speed_axis`` (None: "squeeze_number"), or a
    :class:`lubedyn.dynamics.cageless.layout.BallBallMap` that names its own speed axis (then
    ``map_speed_axis``, if given, must agree)); the film ruptures below ``rupture_thickness`` [m] (``cutoff_gap`` [m]: where
    the squeeze film is cut off; None: the law's default), friction ``friction_film`` while the film
    carries the load and ``friction_boundary`` once it ruptures, regularised over
    ``slip_regularisation`` [m/s], mixed by ``friction_law`` ("exponential_share": the asperities'
    share exp(-h/rupture_thickness); "paper": paper B eqs. 17-21, Barus shear limited by
    ``friction_film``, asperity share of eq. 19 with ``asperity_slope`` [-]); ``entrapped_damping`` beta [-]:
    the map film's locked state damps with beta C0 v/h_L (:func:`lubedyn.dynamics.contacts.ball_ball_normal`;
    default :data:`lubedyn.lubrication.laws.collision.ENTRAPPED_DAMPING`, calibrated on the transient EHL
    impact; 0: the lock without damping); ``race`` ("none", "closed_form": Hamrock-Dowson films on the race
    contacts)."""

    TABLE: ClassVar[str] = "films"

    ball_ball: str = "closed_form"
    map: tuple | None = None
    map_speed_axis: str | None = None
    race: str = "none"
    viscosity: float
    pressure_viscosity: float
    rupture_thickness: float = 1e-7
    cutoff_gap: float | None = None
    friction_film: float = 0.03
    friction_boundary: float = 0.1
    slip_regularisation: float = 0.01
    friction_law: str = "exponential_share"
    asperity_slope: float = 0.02
    entrapped_damping: float = ENTRAPPED_DAMPING

    def __post_init__(self):
        self.choice("ball_ball", FILM_KINDS)
        self.choice("friction_law", FRICTION_LAWS)
        self.positive("asperity_slope")
        self.choice("race", RACE_FILMS)
        if self.map_speed_axis is not None:
            self.choice("map_speed_axis", MAP_SPEED_AXES)
        self.positive("rupture_thickness", "slip_regularisation")
        self.non_negative("viscosity", "pressure_viscosity", "friction_film", "friction_boundary",
                          "entrapped_damping")
        if self.ball_ball == "map" and self.map is None:
            raise self.fail("map", "is needed with films.ball_ball = 'map': (axes, logs, values, logv, method) of a "
                            "ball_ball force map (lubedyn.maps.FilmMap.kernel_arrays('Force [N]'))")


@dataclass(frozen=True, kw_only=True)
class Slots(Group):
    """Local functional slots on one race: ``azimuths`` [rad] (empty: no slot), each ``width`` across
    the groove x ``length`` along it x ``depth`` [m], edges rounded with ``edge_radius`` [m];
    ``blend`` [m]: the width of the smooth step where the groove surface ends."""

    TABLE: ClassVar[str] = "slots"

    race: str = "outer"
    azimuths: tuple = ()
    width: float
    length: float
    depth: float
    edge_radius: float = 2e-4
    blend: float = 2e-4

    def __post_init__(self):
        self.choice("race", RACES)
        object.__setattr__(self, "azimuths", tuple(float(a) for a in self.azimuths))
        self.positive("width", "length", "depth", "edge_radius", "blend")
